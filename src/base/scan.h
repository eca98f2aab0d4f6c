/* vtdyn — Scans of arrays for Inf, NaN and the largest magnitude, branch-free so that they vectorize. */
#ifndef VT_BASE_SCAN_H
#define VT_BASE_SCAN_H

#include <stdint.h>
#include <string.h>
#include <math.h>


/* 1 when no a[k] is Inf or NaN. Branch-free, so that it vectorizes: an IEEE 754 double's
 * exponent field is all ones exactly then, and adding one to it carries into the sign bit. */
static inline int vt_all_finite(const double *a, size_t n)
{
    uint64_t any = 0;
    for (size_t k = 0; k < n; k++) {
        uint64_t u;
        memcpy(&u, a + k, sizeof u);
        any |= (u & 0x7ff0000000000000u) + 0x0010000000000000u;
    }
    return !(any >> 63);
}

/* Several arrays scanned as one: each array's entries ORed into four lanes (the last four
 * entries taken whole, overlapping the ones before: an OR does not mind), tested once at the
 * end. For the fused passes' many short arrays: a vt_all_finite per array paid its set-up,
 * remainder and reduction for a few entries each. The four lanes are one 256-bit vector where
 * the target has AVX2, else two of 128 bits: SSE2 (baseline x86-64) keeps a 256-bit generic
 * vector in memory and splits its compares into scalars. */
#if defined(__GNUC__)
#if defined(__AVX2__)
#define VT_SCAN_PARTS 1
typedef uint64_t vt_scan_u __attribute__((vector_size(32)));
typedef double vt_scan_f __attribute__((vector_size(32)));
#else
#define VT_SCAN_PARTS 2
typedef uint64_t vt_scan_u __attribute__((vector_size(16)));
typedef double vt_scan_f __attribute__((vector_size(16)));
#endif
#define VT_SCAN_LANES (4 / VT_SCAN_PARTS)
#endif
typedef struct {
#if defined(__GNUC__)
    vt_scan_u l[VT_SCAN_PARTS];
#else
    uint64_t l[4];
#endif
} vt_finite_scan;
static inline uint64_t vt_nonfinite_bit(const double *a)
{
    uint64_t u;
    memcpy(&u, a, sizeof u);
    return (u & 0x7ff0000000000000u) + 0x0010000000000000u;
}
/* four entries' bits */
static inline void vt_finite_add4(vt_finite_scan *s, const double *a)
{
#if defined(__GNUC__)
    for (int h = 0; h < VT_SCAN_PARTS; h++) {
        vt_scan_u u;
        memcpy(&u, a + VT_SCAN_LANES * h, sizeof u);
        s->l[h] |= (u & 0x7ff0000000000000u) + 0x0010000000000000u;
    }
#else
    for (int j = 0; j < 4; j++) s->l[j] |= vt_nonfinite_bit(a + j);
#endif
}
static inline void vt_finite_add(vt_finite_scan *s, const double *a, int n)
{
    if (n < 4) {
        double t[4] = {0, 0, 0, 0};
        for (int k = 0; k < n; k++) t[k] = a[k];
        vt_finite_add4(s, t);
        return;
    }
    for (int k = 0; k < n - 4; k += 4) vt_finite_add4(s, a + k);
    vt_finite_add4(s, a + n - 4);
}
/* the four lanes ORed */
static inline uint64_t vt_finite_bits(const vt_finite_scan *s)
{
#if defined(__GNUC__)
    vt_scan_u u = s->l[0];
    for (int h = 1; h < VT_SCAN_PARTS; h++) u |= s->l[h];
    uint64_t any = 0;
    for (int k = 0; k < VT_SCAN_LANES; k++) any |= u[k];
    return any;
#else
    return (s->l[0] | s->l[1]) | (s->l[2] | s->l[3]);
#endif
}
static inline int vt_finite_ok(const vt_finite_scan *s)
{
    return !(vt_finite_bits(s) >> 63);
}

/* The largest |a_k| of several arrays, scanned as one (as vt_finite_scan). A double's bits with
 * the sign cleared order as the magnitudes do, and Inf's and NaN's lie above every finite one:
 * with AVX2, one 64-bit integer maximum of the bits gives both. SSE2 has no 64-bit integer
 * compare (the baseline build spilled every lane to make one), so there the magnitudes are kept
 * by a floating-point maximum and vt_finite_scan's bits beside them (a NaN compares false and
 * would be passed over). vt_max_result: the largest magnitude, +Inf if any entry is Inf or NaN. */
#if defined(__GNUC__) && VT_SCAN_PARTS == 1
typedef int64_t vt_scan_i __attribute__((vector_size(32)));
typedef struct {
    vt_scan_i m[1];
} vt_max_scan;
#else
typedef struct {
#if defined(__GNUC__)
    vt_scan_f m[VT_SCAN_PARTS];
#else
    double m[4];
#endif
    vt_finite_scan bad;
} vt_max_scan;
#endif
static inline void vt_max_add4(vt_max_scan *s, const double *a)
{
#if defined(__GNUC__) && VT_SCAN_PARTS == 1
    vt_scan_i u;
    memcpy(&u, a, sizeof u);
    u &= 0x7fffffffffffffff;
    const vt_scan_i gt = u > s->m[0];
    s->m[0] = (u & gt) | (s->m[0] & ~gt);
#elif defined(__GNUC__)
    vt_finite_add4(&s->bad, a);
    for (int h = 0; h < VT_SCAN_PARTS; h++) {
        vt_scan_u v;
        memcpy(&v, a + VT_SCAN_LANES * h, sizeof v);
        v &= 0x7fffffffffffffffu;
        vt_scan_f x;
        memcpy(&x, &v, sizeof x);
        const vt_scan_u gt = (vt_scan_u)(x > s->m[h]); /* all ones where x is larger: a blend, no branch */
        s->m[h] = (vt_scan_f)((v & gt) | ((vt_scan_u)s->m[h] & ~gt));
    }
#else
    vt_finite_add4(&s->bad, a);
    for (int j = 0; j < 4; j++) {
        const double x = fabs(a[j]);
        if (x > s->m[j]) s->m[j] = x;
    }
#endif
}
static inline void vt_max_add(vt_max_scan *s, const double *a, int n)
{
    if (n < 4) { /* one by one into the first lane: a copy to pad four cost more */
        for (int k = 0; k < n; k++) {
#if defined(__GNUC__) && VT_SCAN_PARTS == 1
            int64_t u;
            memcpy(&u, a + k, sizeof u);
            u &= 0x7fffffffffffffff;
            if (u > s->m[0][0]) s->m[0][0] = u;
#else
            const double x = fabs(a[k]);
#if defined(__GNUC__)
            s->bad.l[0][0] |= vt_nonfinite_bit(a + k);
            if (x > s->m[0][0]) s->m[0][0] = x;
#else
            s->bad.l[0] |= vt_nonfinite_bit(a + k);
            if (x > s->m[0]) s->m[0] = x;
#endif
#endif
        }
        return;
    }
    for (int k = 0; k < n - 4; k += 4) vt_max_add4(s, a + k);
    vt_max_add4(s, a + n - 4);
}
static inline double vt_max_result(const vt_max_scan *s)
{
#if defined(__GNUC__) && VT_SCAN_PARTS == 1
    int64_t mx = 0;
    for (int k = 0; k < 4; k++) mx = s->m[0][k] > mx ? s->m[0][k] : mx;
    if (mx >= 0x7ff0000000000000) return HUGE_VAL;
    double r;
    memcpy(&r, &mx, sizeof r);
    return r;
#else
    if (vt_finite_bits(&s->bad) >> 63) return HUGE_VAL;
    double mx = 0.0;
#if defined(__GNUC__)
    for (int h = 0; h < VT_SCAN_PARTS; h++)
        for (int k = 0; k < VT_SCAN_LANES; k++) mx = s->m[h][k] > mx ? s->m[h][k] : mx;
#else
    for (int k = 0; k < 4; k++) mx = s->m[k] > mx ? s->m[k] : mx;
#endif
    return mx;
#endif
}

#endif
