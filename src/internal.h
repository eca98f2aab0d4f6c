/* vtdyn — internal helpers shared by the stage files: 3-vector algebra, the BLAS/LAPACK
 * entry points we use, and checks common to every stage. Never installed. */
#ifndef VTDYN_INTERNAL_H
#define VTDYN_INTERNAL_H

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cblas.h>

#include "vtdyn.h"

/* LAPACK (Fortran interface; the trailing size_t are the hidden lengths of the character
 * arguments, as gfortran passes them). */
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t ljobz, size_t luplo);

/* tridiagonal solve with partial pivoting (the spline's second derivatives, functions.c) */
void dgtsv_(const int *n, const int *nrhs, double *dl, double *d, double *du, double *b, const int *ldb, int *info);

/* Cartesian block of body i (1..n) in the paper's stacked 7n vectors. */
static inline int vt_xoff(int body) { return 7 * (body - 1); }

static inline void vt_copy3(double r[3], const double a[3])
{
    r[0] = a[0]; r[1] = a[1]; r[2] = a[2];
}
static inline double vt_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/* r = a × b; r must not alias a or b */
static inline void vt_cross3(double r[3], const double a[3], const double b[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}
/* r += s a */
static inline void vt_axpy3(double r[3], double s, const double a[3])
{
    r[0] += s * a[0]; r[1] += s * a[1]; r[2] += s * a[2];
}
/* r += a × b */
static inline void vt_addcross3(double r[3], const double a[3], const double b[3])
{
    double t[3];
    vt_cross3(t, a, b);
    r[0] += t[0]; r[1] += t[1]; r[2] += t[2];
}
/* r = M a for a 3x3 column-major M; r must not alias a */
static inline void vt_mulmat3(double r[3], const double M[9], const double a[3])
{
    r[0] = M[0] * a[0] + M[3] * a[1] + M[6] * a[2];
    r[1] = M[1] * a[0] + M[4] * a[1] + M[7] * a[2];
    r[2] = M[2] * a[0] + M[5] * a[1] + M[8] * a[2];
}
/* r = M^T a for a 3x3 column-major M; r must not alias a */
static inline void vt_mulmat3t(double r[3], const double M[9], const double a[3])
{
    r[0] = M[0] * a[0] + M[1] * a[1] + M[2] * a[2];
    r[1] = M[3] * a[0] + M[4] * a[1] + M[5] * a[2];
    r[2] = M[6] * a[0] + M[7] * a[1] + M[8] * a[2];
}
/* r = E^T a (4) for a 3x4 column-major E */
static inline void vt_mulE_t(double r[4], const double E[12], const double a[3])
{
    for (int k = 0; k < 4; k++) r[k] = E[3 * k] * a[0] + E[3 * k + 1] * a[1] + E[3 * k + 2] * a[2];
}
/* r = E a (3) for a 3x4 column-major E and a 4-vector a */
static inline void vt_mulE(double r[3], const double E[12], const double a[4])
{
    for (int k = 0; k < 3; k++) r[k] = E[k] * a[0] + E[3 + k] * a[1] + E[6 + k] * a[2] + E[9 + k] * a[3];
}

/* A(p) = E G^T written out, (p0² − e·e) I + 2 e e^T + 2 p0 ẽ: vt_euler_A, inline for the fused
 * passes (no call with their vectors live) */
static inline void vt_euler_A_inline(double A[9], const double p[4])
{
    const double p0 = p[0], p1 = p[1], p2 = p[2], p3 = p[3], s = p0 * p0 - p1 * p1 - p2 * p2 - p3 * p3;
    A[0] = s + 2 * p1 * p1, A[3] = 2 * (p1 * p2 - p0 * p3), A[6] = 2 * (p1 * p3 + p0 * p2);
    A[1] = 2 * (p1 * p2 + p0 * p3), A[4] = s + 2 * p2 * p2, A[7] = 2 * (p2 * p3 - p0 * p1);
    A[2] = 2 * (p1 * p3 - p0 * p2), A[5] = 2 * (p2 * p3 + p0 * p1), A[8] = s + 2 * p3 * p3;
}
/* r = a ⊗ b (r may be a or b): vt_quat_mul, inline */
static inline void vt_quat_mul_inline(double r[4], const double a[4], const double b[4])
{
    const double a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3], b0 = b[0], b1 = b[1], b2 = b[2], b3 = b[3];
    r[0] = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3;
    r[1] = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2;
    r[2] = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1;
    r[3] = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0;
}

/* r = ½ E(p)^T w = ½ [0; w] ⊗ p: the rate of Euler parameters p turning at w (global) */
static inline void vt_quat_rate(double r[4], const double p[4], const double w[3])
{
    r[0] = -0.5 * (w[0] * p[1] + w[1] * p[2] + w[2] * p[3]);
    r[1] = 0.5 * (w[0] * p[0] + w[1] * p[3] - w[2] * p[2]);
    r[2] = 0.5 * (w[1] * p[0] + w[2] * p[1] - w[0] * p[3]);
    r[3] = 0.5 * (w[2] * p[0] + w[0] * p[2] - w[1] * p[1]);
}

/* r = E(p) a (3) for Euler parameters p and a 4-vector a, without forming E (euler.c) */
static inline void vt_mulEp(double r[3], const double p[4], const double a[4])
{
    r[0] = -p[1] * a[0] + p[0] * a[1] - p[3] * a[2] + p[2] * a[3];
    r[1] = -p[2] * a[0] + p[3] * a[1] + p[0] * a[2] - p[1] * a[3];
    r[2] = -p[3] * a[0] - p[2] * a[1] + p[1] * a[2] + p[0] * a[3];
}

/* subtree sums, inward: W_parent += W_i, stride doubles per body ((nbody+1) x stride) */
static inline void vt_subtree_sum(const vt_model *m, double *W, int stride)
{
    for (int i = m->nbody; i >= 1; i--) {
        const int j = m->body_parent[i];
        if (j <= 0) continue;
        double *restrict dst = W + stride * j; /* a parent precedes its children: no overlap */
        const double *restrict src = W + stride * i;
        for (int c = 0; c < stride; c++) dst[c] += src[c];
    }
}

/* 1 when no a[k] is Inf or NaN. Branch-free, so that it vectorizes: an IEEE 754 double's
 * exponent field is all ones exactly then, and adding one to it carries into the sign bit. */
static inline int vt_all_finite(const double *a, int n)
{
    uint64_t any = 0;
    for (int k = 0; k < n; k++) {
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

/* sin x and cos x together, for the half angles of revolute joints (vt_quat_axis_angle and the
 * fused passes), within 0.81 ulp of the exact values where the C library's took 0.52
 * (tests/test_euler.c measures both against long double; docs/method.md "Sines and cosines"):
 *   x = n π/2 + r + rr,   |r| ≤ π/4 (a hair more), rr below half an ulp of r,
 *   sin(r + rr) = r − r³/3! + r⁵/5! − … − r¹⁵/15! + r¹⁷/17! + rr (1 − r²/2),
 *   cos(r + rr) = 1 − r²/2 + r⁴/4! − … + r¹⁶/16! − r rr,
 * then rotated by the quadrant n mod 4. The truncated Taylor terms stay below 1.2e-19 relative
 * for |r| ≤ π/4 (an ulp is 1.1e-16); 1 − r²/2 is summed with that subtraction's rounding error
 * carried (w + ((1 − w) − r²/2)), so that only r²'s own rounding is left of it. π/2 is held
 * in four pieces of 33, 33, 33 and 53 bits: for |n| < 2^20 each n P_k is exact (no FMA needed), and
 * the two sums that follow carry their rounding errors exactly (two-sum), so r + rr has 150 bits of
 * π/2 behind it, enough for the closest double to a multiple of π/2 below 2^14 (2^-60.5 away).
 * No library call, no table: inline in the fused passes' loop, where libm's sincos cost a body
 * 101 instructions and a spill of every live value around the call. vt_sincos_small needs
 * |x| ≤ 2^14 (its callers know it from a scan of the state); vt_sincos takes any x, the C library's sin
 * and cos beyond (and for NaN and ±Inf). sin(±0) = ±0. */
static inline void vt_sincos_kernel(double r, double rr, double *s, double *c, const int tail)
{
    const double z = r * r, v = z * r, hz = 0.5 * z, w = 1.0 - hz;
    const double qs = 0x1.1111111111111p-7 + z * (-0x1.a01a01a01a01ap-13 + z * (0x1.71de3a556c734p-19 +
                      z * (-0x1.ae64567f544e4p-26 + z * (0x1.6124613a86d09p-33 +
                      z * (-0x1.ae7f3e733b81fp-41 + z * 0x1.952c77030ad4ap-49))))); /* 1/5!, −1/7!, … 1/17! */
    const double qc = 0x1.5555555555555p-5 + z * (-0x1.6c16c16c16c17p-10 + z * (0x1.a01a01a01a01ap-16 +
                      z * (-0x1.27e4fb7789f5cp-22 + z * (0x1.1eed8eff8d898p-29 +
                      z * (-0x1.93974a8c07c9dp-37 + z * 0x1.ae7f3e733b81fp-45))))); /* 1/4!, −1/6!, … 1/16! */
    if (tail) { /* the reduced argument's low part, rr */
        *s = copysign(r + (v * (-0x1.5555555555555p-3 + z * qs) + rr * w), r);
        *c = w + (((1.0 - w) - hz) + (z * z * qc - r * rr));
    } else { /* |x| ≤ π/4 itself: r = x, rr = 0 (0 · rr is not folded away in IEEE arithmetic) */
        *s = copysign(r + v * (-0x1.5555555555555p-3 + z * qs), r);
        *c = w + (((1.0 - w) - hz) + z * z * qc);
    }
}
static inline void vt_sincos_small(double x, double *s, double *c)
{
    if (fabs(x) <= 0x1.921fb54442d18p-1) { /* π/4: no reduction (a revolute joint within ±π/2) */
        vt_sincos_kernel(x, 0.0, s, c, 0);
        return;
    }
    const long n = (long)(x * 0x1.45f306dc9c883p-1 + copysign(0.5, x)); /* x 2/π to the nearest */
    const double k = (double)n;
    const double a = x - k * 0x1.921fb54400000p+0; /* exact: n P1 exact, a near x (Sterbenz) */
    const double b = k * 0x1.0b4611a600000p-34, s1 = a - b, v1 = s1 - a;
    const double e1 = (a - (s1 - v1)) + (-b - v1); /* s1 + e1 = a − n P2 exactly */
    const double c3 = k * 0x1.3198a2e000000p-69, s2 = s1 - c3, v2 = s2 - s1;
    const double e2 = (s1 - (s2 - v2)) + (-c3 - v2); /* s2 + e2 = s1 − n P3 exactly */
    const double t = (e1 + e2) - k * 0x1.b839a252049c1p-104;
    const double r = s2 + t, rr = (s2 - r) + t;
    double sr, cr;
    vt_sincos_kernel(r, rr, &sr, &cr, 1);
    double so = (n & 1) ? cr : sr, co = (n & 1) ? -sr : cr; /* sin(r + π/2) = cos r, cos(r + π/2) = −sin r */
    if (n & 2) so = -so, co = -co;
    *s = so;
    *c = co;
}
static inline void vt_sincos(double x, double *s, double *c)
{
    if (fabs(x) <= 0x1p14) {
        vt_sincos_small(x, s, c);
    } else {
        *s = sin(x);
        *c = cos(x);
    }
}

/* 1 when p holds (1, 0, 0, 0) bit for bit (a −0 counts as not: p ⊗ it is then formed, the same
 * numbers): four integer loads, where four double compares cost 25 instructions a body */
static inline int vt_quat_is_identity(const double *p)
{
    uint64_t u[4];
    memcpy(u, p, sizeof u);
    return ((u[0] ^ 0x3ff0000000000000u) | u[1] | u[2] | u[3]) == 0;
}

/* a ← a/|a| for a vector of n entries, with |a| = s·sqrt(Σ (a_k/s)²) and s = max |a_k|: no
 * overflow of the sum of squares for lengths near DBL_MAX (1e160 and more), no underflow to zero
 * for tiny non-zero ones, so any finite non-zero vector keeps its direction. Returns |a| (Inf
 * when the length itself overflows; a is still normalized), or 0 for the zero vector (and a
 * NaN), which is left as it was. Axes and Euler parameters of definitions are directions: only
 * the zero vector has none (model.c). */
static inline double vt_normalize(double *a, int n)
{
    double s = 0.0;
    for (int k = 0; k < n; k++) s = fabs(a[k]) > s ? fabs(a[k]) : s;
    if (!(s > 0.0) || !isfinite(s)) return 0.0;
    double ss = 0.0;
    for (int k = 0; k < n; k++) ss += (a[k] / s) * (a[k] / s);
    const double r = sqrt(ss); /* in [1, sqrt(n)] */
    for (int k = 0; k < n; k++) a[k] = (a[k] / s) / r;
    return s * r;
}

/* ---- the scratch arena (data.c lays it out) ---------------------------------------------
 * A stack inside the data: a function that needs scratch marks the top, takes named
 * allocations (each on a cache line) and releases back to its mark before it returns, so no
 * file knows another's layout and no output array doubles as scratch. In AddressSanitizer
 * builds everything above the top is poisoned (in data from vt_data_create(); a caller's buffer
 * from vt_data_init() is left unpoisoned, the caller may reuse it at any time): a read or write
 * past an allocation, or into a released one, is reported where it happens. Sizes are fixed by the model: each source file
 * that takes scratch bounds what it takes at once with a vt_<file>_scratch(model) function
 * (bytes, VT_SCRATCH_BYTES per allocation), and the arena holds their sum, enough for any call
 * chain in which a file appears once. The analyses over time take none (they allocate what
 * they need at their start). An allocation that does not fit (a sizing bug) returns
 * NULL, names itself in d->message and fails every later one until the release. */
struct vt_arena {
    char *base;   /* on a VT_DATA_ALIGN boundary */
    size_t size;  /* bytes */
    size_t top;   /* bytes in use */
    int failed;   /* an allocation did not fit since the last release below it */
    int poison;   /* AddressSanitizer builds: poison what is not taken (vt_data_create()'s data) */
};

#if defined(__SANITIZE_ADDRESS__)
#define VT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VT_ASAN 1
#endif
#endif
#ifdef VT_ASAN
void __asan_poison_memory_region(void const volatile *addr, size_t size);
void __asan_unpoison_memory_region(void const volatile *addr, size_t size);
#define VT_POISON(p, n) __asan_poison_memory_region((p), (n))
#define VT_UNPOISON(p, n) __asan_unpoison_memory_region((p), (n))
#else
#define VT_POISON(p, n) ((void)(p), (void)(n))
#define VT_UNPOISON(p, n) ((void)(p), (void)(n))
#endif

/* bytes an allocation of n items of `size` bytes takes in the arena (its cache lines) */
#define VT_SCRATCH_BYTES(n, size) ((((size_t)(n) * (size_t)(size)) + (VT_DATA_ALIGN - 1)) & ~(size_t)(VT_DATA_ALIGN - 1))

static inline size_t vt_scratch_mark(const vt_data *d)
{
    return d->arena->top;
}

/* the allocation that does not fit: NULL, the arena failed, the message names it (arena.c) */
void *vt_scratch_refuse(vt_data *d, size_t n, size_t size, const char *name);

/* n items of `size` bytes, named for the message when they do not fit; inline, since an instant
 * takes a dozen of them */
static inline void *vt_scratch_take(vt_data *d, size_t n, size_t size, const char *name)
{
    vt_arena *a = d->arena;
    if (a->failed || (size && n > ((size_t)-1 >> 1) / size) || VT_SCRATCH_BYTES(n, size) > a->size - a->top)
        return vt_scratch_refuse(d, n, size, name);
    char *p = a->base + a->top;
    a->top += VT_SCRATCH_BYTES(n, size);
    if (a->poison) VT_UNPOISON(p, n * size); /* the padding up to the next cache line stays poisoned */
    return p;
}
#define VT_SCRATCH(d, type, n, name) ((type *)vt_scratch_take((d), (size_t)(n), sizeof(type), (name)))

/* the rest of the arena, at least `need` items of `size` bytes, as one allocation (LAPACK's
 * workspace: its count into *count) */
void *vt_scratch_rest(vt_data *d, size_t need, size_t size, int *count, const char *name);

static inline void vt_scratch_release(vt_data *d, size_t mark)
{
    vt_arena *a = d->arena;
    if (mark < a->top && a->poison) VT_POISON(a->base + mark, a->top - mark);
    a->top = mark;
    a->failed = 0;
}

/* 1 when every allocation since the mark fitted */
static inline int vt_scratch_ok(const vt_data *d)
{
    return !d->arena->failed;
}

/* releases to mark and returns the failure (the message names the allocation) */
vt_status vt_scratch_fail(vt_data *d, size_t mark);

/* each file's bound on the scratch it takes at once (bytes) */
size_t vt_kinematics_scratch(const vt_model *m);
size_t vt_mass_scratch(const vt_model *m);
size_t vt_forces_scratch(const vt_model *m);
size_t vt_constraints_scratch(const vt_model *m);
size_t vt_solve_scratch(const vt_model *m);
size_t vt_reactions_scratch(const vt_model *m);
size_t vt_recursive_scratch(const vt_model *m);
size_t vt_kinematic_solve_scratch(const vt_model *m);
size_t vt_inverse_transform_scratch(const vt_model *m);
/* vt_kinematic_solve without the argument check, the instant after the solve by the recursive
 * evaluation (recursive = VT_SOLVE_RECURSIVE, or VT_SOLVE_RECURSIVE_NO_TOTALS:
 * vt_kinematic_analysis) or the dense one (VT_SOLVE_DENSE); with qprev (q and q̇ of a
 * solution at t − h: qprev nq, qdprev nv) d->q is a start predicted from it, abandoned for qprev
 * itself when its max |Φ| exceeds ½ h max |Φ_t| (roughly qprev's own residual at t) */
/* vt_inverse_dynamics_recursive with d's positions, twists, Φ, Φ_t and Φ_q current at d->q and
 * d->time (Newton's last evaluation), q̇ new, or with rates, q̇ solved from Φ_q q̇ = −Φ_t by the
 * square route's LU (else VT_NEEDS_RATES, d->qd as it was); fd: the drives' functions at d->time
 * (vt_drive_values) or NULL; α and the joints' total wrenches only with totals (recursive.c) */
vt_status vt_inverse_dynamics_recursive_positioned(const vt_model *m, vt_data *d, const double *fd, int totals, int rates);
/* vt_kinematic_solve_impl's instants: the dense one, the recursive one, the recursive one
 * without α and the joints' total wrenches (vt_reactions_total; the analyses' rows and the
 * exact efforts do not keep them); or'ed with VT_SOLVE_POLISH, one Newton step more once
 * max |Φ| ≤ tol (from within tol the error is then round-off: the forward check's reference) */
enum { VT_SOLVE_DENSE = 0, VT_SOLVE_RECURSIVE = 1, VT_SOLVE_RECURSIVE_NO_TOTALS = 2, VT_SOLVE_POLISH = 4 };
vt_status vt_kinematic_solve_impl(const vt_model *m, vt_data *d, double tol, int maxit, int recursive,
                                  const double *qprev, const double *qdprev, double h);
/* Newton's start at d->time into d->q, d->qd: the Hermite polynomial through q, q̇, q̈ of rows k1
 * and k2 of tr (k2 before k1: extrapolated; after: interpolated; −1: Taylor from k1 alone) */
vt_status vt_kinematic_start(const vt_model *m, vt_data *d, const vt_trajectory *tr, int k1, int k2, int k3);

/* Writes a formatted message into buf (size 256) and returns status. */
vt_status vt_fail(char *buf, vt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Common argument check of every stage: non-NULL, data made for this model. */
vt_status vt_check_pair(const vt_model *m, vt_data *d, const char *who);

/* A body's inertia J (3x3 column-major) as the builder accepts it: symmetric, positive
 * semi-definite and within the triangle inequality to VT_INERTIA_TOL (model.c); the message
 * starts with who ("body 3", a URDF link). */
vt_status vt_check_inertia(char *msg, const char *who, const double J[9]);

/* Rotational (0) or translational (1) kind of each joint rate, and which of the joint's
 * axes it uses; base rates are reported separately. */
enum { VT_DOF_ROT, VT_DOF_TRANS, VT_DOF_BASE_R, VT_DOF_BASE_P };
static inline int vt_dof_kind(int joint_type, int k, int *axis)
{
    *axis = 0;
    switch (joint_type) {
    case VT_JOINT_BASE: *axis = k < 3 ? k : k - 3; return k < 3 ? VT_DOF_BASE_R : VT_DOF_BASE_P;
    case VT_JOINT_REVOLUTE: return VT_DOF_ROT;
    case VT_JOINT_UNIVERSAL: *axis = k; return VT_DOF_ROT;
    case VT_JOINT_SPHERICAL: *axis = k; return VT_DOF_ROT;
    case VT_JOINT_TRANSLATIONAL: return VT_DOF_TRANS;
    case VT_JOINT_FREE: *axis = k < 3 ? k : k - 3; return k < 3 ? VT_DOF_TRANS : VT_DOF_ROT;
    default: /* cylindrical: θ then s, both along axis 0 */
        return k == 0 ? VT_DOF_ROT : VT_DOF_TRANS;
    }
}

/* Mp = 4 G^T J' G (4x4 column-major), the rotational block of M^i (mass.c) */
void vt_rot_mass(double Mp[16], const double J[9], const double p[4]);
/* Body i's rows of S on its path columns, into Si (7 x body_pathnum[i], ld 7) (kinematics.c) */
void vt_gather_S(double *Si, const vt_model *m, const vt_data *d, int i);

/* vt_kinematics_tree's and vt_accelerations' rows of one body i, its reference body's done
 * (kinematics.c): for a pass that fuses them with other work body by body (recursive.c) */
void vt_kinematics_body(const vt_model *m, vt_data *d, int i);
void vt_acceleration_body(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, int i);
/* vt_kinematics_tree's checks of the state and of its outputs (without Ṡq̇) (kinematics.c) */
vt_status vt_kinematics_check_state(const vt_model *m, vt_data *d);
vt_status vt_kinematics_check_outputs(const vt_model *m, vt_data *d);
/* Kinematics (kinematics.c): ẍ = S q̈ + Ṡ q̇ into out (7n) (q̈ = 0 if qdd is NULL), with the
 * angular accelerations into alpha (3 x (nbody+1)). */
void vt_accelerations(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha);
/* The same from d->Sdqd and d->twist (both current), with T (6 x (nbody+1)) the twists q̈ adds
 * to the bodies' spatial accelerations; alpha may be NULL. */
void vt_accelerations_add(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, double *T);
/* The same from the dense S (vt_kinematics' lever arms along the tree), alpha not NULL */
void vt_accelerations_dense(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha);

/* Positions, velocities and (with Sdqd != 0) Ṡq̇, without the dense S (kinematics.c); the
 * state is checked. */
vt_status vt_kinematics_tree(const vt_model *m, vt_data *d, int Sdqd);
/* vt_kinematics_tree in two halves (kinematics.c): the positions and the rates' twists (q
 * checked), then the velocities and (Sdqd != 0) Ṡq̇ at those positions (q̇ checked) */
vt_status vt_kinematics_positions(const vt_model *m, vt_data *d);
vt_status vt_kinematics_velocities(const vt_model *m, vt_data *d, int Sdqd);
/* Column dof of S in body i's rows (kinematics.c), from the rate's twist d->twist's axis and the
 * lever arm u = r^i − P of the rate's joint point (vt_lever); Ei = E(p^i) */
void vt_S_column(double c[7], const vt_model *m, const vt_data *d, int i, const double Ei[12], int dof, const double u[3]);
/* whether rate dof turns (a rotational axis or a base body's ṗ: its twist's w), else slides */
static inline int vt_dof_turns(const vt_model *m, int dof)
{
    int ax;
    const int b = m->dof_body[dof], kind = vt_dof_kind(m->body_joint[b], dof - m->body_vadr[b], &ax);
    return kind == VT_DOF_ROT || kind == VT_DOF_BASE_P;
}
/* s^{ji} = A^i s'^{ji}, body i's centre of mass to its joint point (a base body's: 0). A joint
 * without translation has d^i = −s^{ji} exactly (kinematics.c forms d^i = t − s^{ji}, t = 0) */
static inline void vt_joint_child(double s[3], const vt_model *m, const vt_data *d, int i)
{
    const int jt = m->body_joint[i];
    if (jt == VT_JOINT_BASE) s[0] = s[1] = s[2] = 0.0;
    else if (jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL || jt == VT_JOINT_SPHERICAL)
        s[0] = -d->jd[3 * i], s[1] = -d->jd[3 * i + 1], s[2] = -d->jd[3 * i + 2];
    else vt_mulmat3(s, d->A + 9 * i, m->body_jchild + 3 * i);
}

/* P_i − P_j, body i's joint point from its reference body j's, from the joints' own vectors:
 * s^{ij}_i + t_i − s^{ji}_j with t_i = d^i + s^{ji}_i the joint's translation (17) */
static inline void vt_joint_shift(double r[3], const vt_model *m, const vt_data *d, int i, int j)
{
    double si[3], sj[3];
    vt_joint_child(si, m, d, i);
    vt_joint_child(sj, m, d, j);
    for (int k = 0; k < 3; k++) r[k] = d->jsij[3 * i + k] + (d->jd[3 * i + k] + si[k]) - sj[k];
}

/* The lever arms of the dense S (and of the recursive path's Φ_q), walked from body i up its
 * path: at joint k, u = r^i − P_k (P_k the point the joint's rates turn about; a base body's,
 * its centre of mass), summed from the joints' own short vectors,
 *   r^i − P_i = −s^{ji}_i,   r^i − P_j = (r^i − P_k) + (s^{ij}_k + t_k) − s^{ji}_j   (j = k's reference)
 * with t_k = d^k + s^{ji}_k the joint's translation (17); with with_len, len = the sum of those
 * vectors' lengths, the size of u's round-off; s = s^{ji} of joint k. The difference
 * (r^i − o) − (P_k − o) of positions from o would carry ε |r − o| of round-off: a mechanism 1e9 m
 * from o would have no digit of a 1 m lever arm. vt_lever_up moves to k's reference body and
 * returns 0 at the ground. */
typedef struct {
    int k, with_len;
    double u[3], s[3], len;
} vt_lever;
static inline void vt_lever_start(vt_lever *L, const vt_model *m, const vt_data *d, int i, int with_len)
{
    L->k = i;
    L->with_len = with_len;
    vt_joint_child(L->s, m, d, i);
    for (int c = 0; c < 3; c++) L->u[c] = -L->s[c];
    L->len = with_len ? sqrt(vt_dot3(L->s, L->s)) : 0.0;
}
static inline int vt_lever_up(vt_lever *L, const vt_model *m, const vt_data *d)
{
    const int k = L->k, j = m->body_parent[k];
    if (j == 0) return 0;
    double a[3], sj[3];
    const double *sij = d->jsij + 3 * k, *dk = d->jd + 3 * k;
    for (int c = 0; c < 3; c++) a[c] = sij[c] + (dk[c] + L->s[c]); /* P_k − r^j */
    vt_joint_child(sj, m, d, j);
    for (int c = 0; c < 3; c++) L->u[c] += a[c] - sj[c];
    if (L->with_len) L->len += sqrt(vt_dot3(a, a)) + sqrt(vt_dot3(sj, sj));
    vt_copy3(L->s, sj);
    L->k = j;
    return 1;
}
/* |r^i − o| bounded by the lengths it is summed from, the size of its round-off, for every body
 * into L[stride i] (kinematics.c) */
void vt_lengths_from_o(const vt_model *m, const vt_data *d, double *L, int stride);

/* every multiplier unique (vt_solve's exact routes) */
static inline void vt_mark_unique(const vt_model *m, vt_data *d)
{
    int *lu = d->lambda_unique;
    for (int r = 0; r < m->nc; r++) lu[r] = 1;
}
/* what a successful solve with independent rows records: the route, rcond and its warning,
 * rank nc, no residual, every multiplier unique (solve.c) */
void vt_solved(const vt_model *m, vt_data *d, vt_route route, double rcond);
/* vt_solve without the argument check and without clearing d->fallback (solve.c): the
 * recursive evaluation's general route, after its own shortcuts have flagged their fallbacks.
 * On its composite M* about o, a rate whose M*_aa is round-off of those terms and that no row
 * fixes is not refused: VT_NEEDS_DENSE (positive), the dense stages decide (recursive.c) */
#define VT_NEEDS_DENSE ((vt_status)1)
/* a free-rate route's estimate low enough that the maximal-coordinate route (maximal.c) may be
 * wanted (vt_maximal_wanted): the dense stages, which form what it needs, solve the instant
 * again and decide (recursive.c) */
#define VT_NEEDS_MAXIMAL ((vt_status)2)
/* vt_inverse_dynamics_recursive_positioned asked for q̇ as well, where its route has no LU of
 * Φ_q to solve them (recursive.c): the caller solves them, and asks again without */
#define VT_NEEDS_RATES ((vt_status)3)
vt_status vt_solve_impl(const vt_model *m, vt_data *d);
/* vt_solve_impl with a time analysis's band (vt_run_options.redundant_band; 0 is vt_solve_impl)
 * and the form of M* (dense: S^T M S, else the composite inertias about o, as vt_rate_bounds),
 * and vt_solve with it on the dense M* (solve.c): the ODE formulation's residual */
vt_status vt_solve_band(const vt_model *m, vt_data *d, double band, int dense);
vt_status vt_solve_run(const vt_model *m, vt_data *d, double band);
/* the diagnostics every solve starts from: route none, rcond 0, no warning, rank 0, residual 0 */
void vt_solve_reset(vt_data *d);
/* the rank of Φ_q to round-off, in the scaling of the redundant decision (from the current M*
 * and Φ_q), or a negative vt_status (solve.c) */
int vt_rows_rank(const vt_model *m, vt_data *d);
/* vt_solve's square route in two halves (solve.c), its state on the arena: the LU of R Φ_q D;
 * D (s) and R (g); q̈ (x) and then M* q̈ − Q, overwritten by λ (h) */
typedef struct {
    double *A, *s, *g, *x, *h;
    int *ipiv;
} vt_square;
int vt_square_first(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond);
int vt_square_second(const vt_model *m, vt_data *d, vt_square *sq);
/* x = sign Φ_q^-1 b (nv) by the factors of sq: D (R Φ_q D)^-1 R b */
int vt_square_apply(const vt_model *m, vt_data *d, const vt_square *sq, const double *b, double sign, double *x);
/* the same for the recursive evaluation: the factors from M*'s diagonal mdiag (nv) and the
 * positions, q̈, and the outcome */
int vt_solve_square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, double *rcond);
int vt_solve_square_accelerations(const vt_model *m, vt_data *d, vt_square *sq);
vt_status vt_solve_square_end(const vt_model *m, vt_data *d, vt_square *sq, double rcond);
/* Round-off of exact zeros (solve.c): T (2 nv) the magnitudes of the terms of each rate's M*_aa,
 * T_a = Σ_k m_k (|v_a| + |ω_a| L_k)² (L_k ≥ |c_k − o|: vt_lengths_from_o) and R_a = |ω_a|² Σ_k tr J'_k over the bodies k it moves,
 * from the twists (w: 4 (nbody + 1) scratch); vt_rate_roundoff, the size below which M*_aa is
 * round-off, τ ε (T_a + R_a). */
#define VT_ROUND_TAU 64.0
/* Below DBL_MIN a number has lost digits (the dense path refuses an M*_aa there, naming the
 * rate); the recursive routes, whose pivots round differently, hand every pivot below DBL_MIN / ε
 * to the dense stages, so that both paths decide the edge by the same numbers */
#define VT_PIVOT_NORMAL (DBL_MIN / DBL_EPSILON)
void vt_rate_terms(const vt_model *m, const vt_data *d, double *w, double *T);
double vt_rate_roundoff(const double *T, int a);
/* The bound below which M*_aa is round-off, for every rate, into beta (nv): of the M* the
 * dense stages form as S^T M S (dense != 0: S's columns squared, (τ ε)² T_a + τ ε R_a, T_a with
 * the dense S's lever arms, vt_lever) or of the recursive general route's composite inertias
 * about o (dense == 0: vt_rate_roundoff). Scratch: 2 nv + 4 (nbody + 1) doubles (solve.c) */
int vt_rate_bounds(const vt_model *m, vt_data *d, int dense, double *beta);
/* the number of rows of Φ_q that are round-off of a zero row (judged against the terms they are
 * summed from), or a negative vt_status (solve.c) */
int vt_zero_rows(const vt_model *m, vt_data *d);
/* the same on the free rates alone (known[a] < 0): rows dependent on the known rates' (solve.c) */
int vt_zero_rows_free(const vt_model *m, vt_data *d, const int *known);
/* dgelsd's integer workspace for an m x n problem (solve.c) */
int vt_dgelsd_iwork(int m, int n);
/* S b' = b for the symmetric positive definite n x n S (its lower triangle, overwritten: scaled
 * to unit diagonal, then factorized), b solved in place, the reciprocal condition of S at unit
 * diagonal into *rcond: 1 for n ≤ 1, exact from the inverse for n ≤ 16, dpocon's estimate above,
 * 0 when S is not positive definite (nothing solved). Returns 0 or a negative vt_status (solve.c). */
int vt_solve_spd(vt_data *d, double *S, int n, double *b, double *rcond);
/* the smallest grip² of the point drives' rows (1 without any): how much of what the rates can
 * move the driven point by lies along the driven direction (solve.c) */
double vt_rows_grip(const vt_model *m, const vt_data *d);
/* vt_reactions without the argument checks (ẍ and α from d->qdd); dense: M* and S are the
 * dense stages' (else the recursive general route's composite M* about o) */
vt_status vt_reactions_impl(const vt_model *m, vt_data *d, int dense);
/* after vt_solve: VT_ERR_SINGULAR when rates whose M* row it zeroed (round-off held by rows)
 * leave the efforts without a certain digit (reactions.c); who names the caller; dense as
 * vt_rate_bounds */
vt_status vt_zeroed_rates_check(const vt_model *m, vt_data *d, const char *who, int dense);
/* subtree sums about each joint point of wrenches about it: moment at noff, force at foff (reactions.c) */
void vt_sum_at_joints(const vt_model *m, const vt_data *d, double *X, int noff, int foff);
/* the same from the subtrees' needed wrenches about each joint point P_i at the full
 * accelerations, Wbar ([n; f], 6 x (nbody+1), recursive.c), the rows' wrenches already taken off
 * it with rows_in_wbar; G: scratch of 6 x (nbody+1), apart from Wbar */
vt_status vt_reactions_subtree(const vt_model *m, vt_data *d, const double *Wbar, double *G, int rows_in_wbar);
/* Every row's wrench on its two bodies, for the multipliers lam (1 each when NULL), about each
 * body's centre of mass: [f_a n_a f_b n_b] into rw (12 x nc) (reactions.c). */
void vt_row_wrenches(double *rw, const vt_model *m, const vt_data *d, const double *lam);
/* jnt_unique and cut_unique, every one set, then those that a null direction of Φ_q^T (rank < nc:
 * the redundant solve's, in d->lambda_null) changes cleared (reactions.c) */
vt_status vt_reactions_nonunique(const vt_model *m, vt_data *d);
/* Which reactions are unique: every one when the rows are independent (rank nc), otherwise
 * vt_reactions_nonunique's; inline, as vt_mark_unique: every instant ends with it */
static inline vt_status vt_reactions_unique(const vt_model *m, vt_data *d)
{
    const int nj = 6 * (m->nbody + 1), ncut = 6 * m->ncut;
    int *ju = d->jnt_unique, *cu = d->cut_unique;
    for (int i = 0; i < nj; i++) ju[i] = 1;
    for (int k = 0; k < ncut; k++) cu[k] = 1;
    return m->nc - d->rank > 0 ? vt_reactions_nonunique(m, d) : VT_OK;
}
/* what every instant path ends with: α of every body (from ẍ) and each joint's total wrench,
 * reaction plus actuation (given: the motion given, every rate's qfrc_drive its effort) */
vt_status vt_reactions_total(const vt_model *m, vt_data *d, int given);

/* the given motion of a mechanism with loops or couplings: the joint drives' rows take q̈ from
 * d->qdd (instant.c) */
vt_status vt_motion_rows(const vt_model *m, vt_data *d);

/* vt_constraints with Φ_q from the dense S (dense = 1) or from the twists (dense = 0) */
vt_status vt_constraints_impl(const vt_model *m, vt_data *d, int dense);
/* the same, its parts chosen: Φ and Φ_t always, Φ_x (VT_CON_PHIX) and Φ_q (VT_CON_PHIQ) from the
 * positions and twists, γ from the velocities and Ṡq̇ as well (VT_CON_GAMMA); a part left out may
 * be left as it was. fd: the joint and point drives' f, f', f'' at d->time (3 a drive, from
 * vt_drive_values), or NULL to evaluate them */
enum { VT_CON_PHIX = 1, VT_CON_PHIQ = 2, VT_CON_GAMMA = 4, VT_CON_ALL = 7 };
vt_status vt_constraints_parts(const vt_model *m, vt_data *d, int dense, int parts, const double *fd);
vt_status vt_drive_values(const vt_model *m, vt_data *d, double *fd);

/* Row of R (Table 1) for rate `dof`: its entries on x^j (rj, 7) and on x^i (ri, 7). */
void vt_R_row(const vt_model *m, const vt_data *d, int dof, double rj[7], double ri[7]);

/* Validates a time function (functions.c); msg may be NULL. */
vt_status vt_function_check(char *msg, const vt_function *f);
/* f, f′, f″ of a sine, a spline or a user's function (functions.c), into v; not checked for Inf */
vt_status vt_function_eval_other(double v[3], const vt_function *f, double t);
/* vt_function_eval for a function already validated (a model's drives: a spline's sample_d2 set);
 * inline, a polynomial or constant computed here: the drives' functions are evaluated rate by rate
 * in every instant, and a call cost a joint-driven chain more than the polynomial itself */
static inline vt_status vt_function_eval_valid(double out[3], const vt_function *f, double t)
{
    if (!isfinite(t)) return VT_ERR_NONFINITE;
    double v[3] = {0, 0, 0};
    if (f->type == VT_FUNCTION_POLYNOMIAL) {
        v[0] = f->c[f->ncoef - 1]; /* the first step from zeros: f′ and f″ stay 0 */
        for (int k = f->ncoef - 2; k >= 0; k--) { /* Horner for f, f′, f″ together */
            v[2] = v[2] * t + 2.0 * v[1];
            v[1] = v[1] * t + v[0];
            v[0] = v[0] * t + f->c[k];
        }
    } else if (f->type == VT_FUNCTION_CONSTANT) {
        v[0] = f->c[0];
    } else {
        const vt_status st = vt_function_eval_other(v, f, t);
        if (st) return st;
    }
    if (!(isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]))) return VT_ERR_NONFINITE; /* in registers */
    out[0] = v[0];
    out[1] = v[1];
    out[2] = v[2];
    return VT_OK;
}
/* A spline's second derivatives d2 (n) at its samples (functions.c), by LAPACK's dgtsv; work
 * holds 3n doubles; the samples already validated (vt_function_check); msg may be NULL.
 * Statuses: VT_ERR_LAPACK, VT_ERR_NONFINITE (spacings so uneven that d2 overflows). */
vt_status vt_spline_d2(char *msg, int n, const double *t, const double *y, double *d2, double *work);

/* Kinds of constraint row (model.c builds them, constraints.c evaluates them). */
enum {
    VT_ROW_JOINT,   /* q_k − f(t) = 0                                          joint drive */
    VT_ROW_POINT,   /* c·(P_b − P_a) − f(t) = 0, c global                      point drive, cut joints */
    VT_ROW_DOT,     /* (A_a u')·(A_b v') = 0                                   cut joints */
    VT_ROW_LINE,    /* (A_a u')·(P_b − P_a) = 0                                cut joints */
    VT_ROW_ORIENT,  /* 2 (G(p_d) p)_k = 0                                      orientation drive */
    VT_ROW_NORM,    /* p^T p − 1 = 0                                           base body */
    VT_ROW_COUPLING /* q_a − ratio q_b − offset = 0                            coupling */
};
/* Which kind of object owns a row: drive, cut joint or base body. */
enum { VT_OWNER_DRIVE, VT_OWNER_CUT, VT_OWNER_COUPLING, VT_OWNER_BASE };
int vt_row_owner_kind(const vt_model *m, int row);
/* row r a joint drive whose rate is known: the rate's only joint drive (dof_drive), its q̈ the
 * drive's f'' = γ_r exactly; the recursive articulated route and the dense Schur route solve the
 * other rows on the remaining rates */
static inline int vt_known_row(const vt_model *m, int r)
{
    return m->con_kind[r] == VT_ROW_JOINT && m->drive_row[m->dof_drive[m->con_dof[r]]] == r;
}
/* Rows of a cut joint: its kind's, or 2 for a planar pin. */
int vt_cut_nrows(const vt_cut_joint_def *c);
/* Number of rows that belong to drives (they come first). */
int vt_drive_rows(const vt_model *m);
/* An orientation drive, absolute or relative (3 rows, p_d(t) from prescribed orientation) */
static inline int vt_drive_turns(vt_drive_type type)
{
    return type == VT_DRIVE_ORIENTATION || type == VT_DRIVE_RELATIVE_ORIENTATION;
}
/* Rows of one drive */
static inline int vt_drive_nrows(const vt_drive_def *d) { return vt_drive_turns(d->type) ? 3 : 1; }
/* A drive's time functions (f; with an orientation drive's sequence also f2, f3; none for an
 * orientation callback) into fs; returns how many */
static inline int vt_drive_functions(const vt_drive_def *d, const vt_function *fs[3])
{
    if (vt_drive_turns(d->type) && d->orientation_callback) return 0;
    fs[0] = &d->f;
    if (!vt_drive_turns(d->type) || !d->sequence) return 1;
    fs[1] = &d->f2;
    fs[2] = &d->f3;
    return 3;
}

/* LAPACK routines of the solve (solve.c) */
void dsytrf_rk_(const char *uplo, const int *n, double *a, const int *lda, double *e, int *ipiv, double *work,
                const int *lwork, int *info, size_t luplo);
void dsytrs_3_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, const double *e,
               const int *ipiv, double *b, const int *ldb, int *info, size_t luplo);
void dsycon_3_(const char *uplo, const int *n, const double *a, const int *lda, const double *e, const int *ipiv,
               const double *anorm, double *rcond, double *work, int *iwork, int *info, size_t luplo);
double dlansy_(const char *norm, const char *uplo, const int *n, const double *a, const int *lda,
               double *work, size_t lnorm, size_t luplo);
void dgels_(const char *trans, const int *m, const int *n, const int *nrhs, double *a, const int *lda,
            double *b, const int *ldb, double *work, const int *lwork, int *info, size_t ltrans);
void dgelsd_(const int *m, const int *n, const int *nrhs, double *a, const int *lda, double *b, const int *ldb,
             double *s, const double *rcond, int *rank, double *work, const int *lwork, int *iwork, int *info);
void dtrtrs_(const char *uplo, const char *trans, const char *diag, const int *n, const int *nrhs, const double *a,
             const int *lda, double *b, const int *ldb, int *info, size_t l1, size_t l2, size_t l3);
void dpotf2_(const char *uplo, const int *n, double *a, const int *lda, int *info, size_t l);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
             const int *ldb, int *info, size_t l);
void dpocon_(const char *uplo, const int *n, const double *a, const int *lda, const double *anorm, double *rcond,
             double *work, int *iwork, int *info, size_t l);
void dgeqp3_(const int *m, const int *n, double *a, const int *lda, int *jpvt, double *tau,
             double *work, const int *lwork, int *info);
void dgesvd_(const char *jobu, const char *jobvt, const int *m, const int *n, double *a, const int *lda, double *s,
             double *u, const int *ldu, double *vt, const int *ldvt, double *work, const int *lwork, int *info,
             size_t lu, size_t lvt);
void dgetf2_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info, size_t ltrans);
void dgecon_(const char *norm, const int *n, const double *a, const int *lda, const double *anorm, double *rcond,
             double *work, int *iwork, int *info, size_t lnorm);
/* and of the maximal-coordinate route (maximal.c) */
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgeequb_(const int *m, const int *n, const double *a, const int *lda, double *r, double *c, double *rowcnd,
              double *colcnd, double *amax, int *info);
void dlacn2_(const int *n, double *v, double *x, int *isgn, double *est, int *kase, int *isave);

/* The maximal-coordinate route (maximal.c): vt_maximal_size is its number of unknowns, 0 where
 * it is not taken (base bodies, every rate joint-driven, more than VT_MAXIMAL_MAX unknowns);
 * vt_maximal_solve puts [q̈; λ] into sol (nv + nc) and the reciprocal of the answer's condition
 * into *rcond (without the grip g²). It needs the dense stages' S, Ṡq̇, Φ_x, Φ_q and γ. Returns
 * 0, 1 (singular: nothing solved) or a negative vt_status. */
enum { VT_MAXIMAL_MAX = 256 };
int vt_maximal_size(const vt_model *m);
int vt_maximal_wanted(const vt_model *m, double rcond);
int vt_maximal_solve(const vt_model *m, vt_data *d, double *sol, double *rcond);
size_t vt_maximal_scratch(const vt_model *m);
/* its matrix A (N x N, ld N, N = vt_maximal_size) and right side b, unscaled: for the tests */
void vt_maximal_system(const vt_model *m, const vt_data *d, double *A, double *b);

/* Efforts of the drives from d->lambda (reactions.c), and the forward check's loads */
vt_status vt_drive_efforts(const vt_model *m, vt_data *d);
void vt_apply_drive_loads(const vt_model *mf, vt_data *df, const vt_model *m, const vt_data *d, const double *xfrc0,
                          int as_loads);

/* Trajectory rows (trajectory.c) */
void vt_trajectory_store(vt_trajectory *tr, const vt_model *m, const vt_data *d, int row);
void vt_trajectory_store_forward(vt_trajectory *tr, const vt_model *mf, const vt_data *df, int row);
void vt_trajectory_reset(vt_trajectory *tr);
vt_status vt_check_run(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr, const char *who);
/* Output rows of a run after row 0 (nout or ntout), and the time of row k (0 = t0) */
int vt_run_rows(const vt_run_options *opt);
double vt_run_time(const vt_run_options *opt, int k);

/* The forward check with IDA (dynamic_analysis.c): integrates m without drives from the driven
 * state at opt->t0, with the drives' generalized force at each time, evaluated exactly on dk (of
 * dk->model: m itself, or in a test a model of other inertia with the same joints and drives) by
 * vt_kinematic_solve_impl from the rows of tr around it, interpolated (vt_kinematic_start), and at
 * the output times taken from tr's rows (fully driven models). IDA's unknowns are the deviation
 * from that exact motion. */
vt_status vt_forward_exact(const vt_model *m, vt_data *d, vt_data *dk, const vt_run_options *opt, vt_trajectory *tr);

#endif
