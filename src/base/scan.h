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
 * remainder and reduction for a few entries each. */
#if defined(__GNUC__)
typedef uint64_t vt_u64x4 __attribute__((vector_size(32)));
#else
typedef struct {
    uint64_t l[4];
} vt_u64x4;
#endif
typedef struct {
    vt_u64x4 l;
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
    vt_u64x4 u;
    memcpy(&u, a, sizeof u);
    s->l |= (u & 0x7ff0000000000000u) + 0x0010000000000000u;
#else
    for (int j = 0; j < 4; j++) s->l.l[j] |= vt_nonfinite_bit(a + j);
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
static inline int vt_finite_ok(const vt_finite_scan *s)
{
#if defined(__GNUC__)
    const uint64_t any = (s->l[0] | s->l[1]) | (s->l[2] | s->l[3]);
#else
    const uint64_t any = (s->l.l[0] | s->l.l[1]) | (s->l.l[2] | s->l.l[3]);
#endif
    return !(any >> 63);
}

/* The largest |a_k| of several arrays, scanned as one (as vt_finite_scan): a double's bits with
 * the sign cleared order as the magnitudes do, and Inf's and NaN's lie above every finite one,
 * so one integer maximum gives both. vt_max_result: the largest magnitude, +Inf if any entry is
 * Inf or NaN. */
#if defined(__GNUC__)
typedef int64_t vt_i64x4 __attribute__((vector_size(32)));
#else
typedef struct {
    int64_t l[4];
} vt_i64x4;
#endif
typedef struct {
    vt_i64x4 l;
} vt_max_scan;
static inline void vt_max_add4(vt_max_scan *s, const double *a)
{
#if defined(__GNUC__)
    vt_i64x4 u;
    memcpy(&u, a, sizeof u);
    u &= 0x7fffffffffffffff;
    const vt_i64x4 gt = u > s->l;
    s->l = (u & gt) | (s->l & ~gt);
#else
    for (int j = 0; j < 4; j++) {
        int64_t u;
        memcpy(&u, a + j, sizeof u);
        u &= 0x7fffffffffffffff;
        if (u > s->l.l[j]) s->l.l[j] = u;
    }
#endif
}
static inline void vt_max_add(vt_max_scan *s, const double *a, int n)
{
    if (n < 4) { /* one by one into the first lane: a copy to pad four cost more */
        for (int k = 0; k < n; k++) {
            int64_t u;
            memcpy(&u, a + k, sizeof u);
            u &= 0x7fffffffffffffff;
#if defined(__GNUC__)
            if (u > s->l[0]) s->l[0] = u;
#else
            if (u > s->l.l[0]) s->l.l[0] = u;
#endif
        }
        return;
    }
    for (int k = 0; k < n - 4; k += 4) vt_max_add4(s, a + k);
    vt_max_add4(s, a + n - 4);
}
static inline double vt_max_result(const vt_max_scan *s)
{
#if defined(__GNUC__)
    const int64_t l0 = s->l[0], l1 = s->l[1], l2 = s->l[2], l3 = s->l[3];
#else
    const int64_t l0 = s->l.l[0], l1 = s->l.l[1], l2 = s->l.l[2], l3 = s->l.l[3];
#endif
    int64_t mx = l0 > l1 ? l0 : l1;
    mx = mx > l2 ? mx : l2;
    mx = mx > l3 ? mx : l3;
    if (mx >= 0x7ff0000000000000) return HUGE_VAL;
    double r;
    memcpy(&r, &mx, sizeof r);
    return r;
}

#endif
