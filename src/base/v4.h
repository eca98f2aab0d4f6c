/* prototype */
#ifndef VT_BASE_V4_H
#define VT_BASE_V4_H
#include <string.h>
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double vt_v4 __attribute__((vector_size(32)));
#define VT_PERM(a, i, j, k, l) __builtin_shufflevector((a), (a), i, j, k, l)
#define VT_BC(a, k) VT_PERM(a, k, k, k, k)
static inline vt_v4 v4_ld(const double *p) { vt_v4 r; memcpy(&r, p, sizeof r); return r; }
static inline void v4_st(double *p, vt_v4 a) { memcpy(p, &a, sizeof a); }
typedef double vt_v2 __attribute__((vector_size(16)));
static inline void v4_st3(double *p, vt_v4 a)
{
    const vt_v2 lo = __builtin_shufflevector(a, a, 0, 1);
    memcpy(p, &lo, sizeof lo);
    p[2] = a[2];
}
static inline vt_v4 v4_s(double s) { return (vt_v4){s, s, s, s}; }
/* a × b in lanes 0-2: c = a (b1 b2 b0) − (a1 a2 a0) b = (r2 r0 r1) */
static inline vt_v4 v4_cross(vt_v4 a, vt_v4 b)
{
    const vt_v4 c = a * VT_PERM(b, 1, 2, 0, 3) - VT_PERM(a, 1, 2, 0, 3) * b;
    return VT_PERM(c, 1, 2, 0, 3);
}
static inline vt_v4 v4_mat(vt_v4 c0, vt_v4 c1, vt_v4 c2, vt_v4 a)
{
    return c0 * VT_BC(a, 0) + c1 * VT_BC(a, 1) + c2 * VT_BC(a, 2);
}
static inline double v4_dot3(vt_v4 a, vt_v4 b)
{
    const vt_v4 t = a * b;
    return t[0] + t[1] + t[2];
}
/* rows r0, r1, r2 of the matrix of columns c0, c1, c2 */
static inline void v4_transpose(vt_v4 c0, vt_v4 c1, vt_v4 c2, vt_v4 *r0, vt_v4 *r1, vt_v4 *r2)
{
    const vt_v4 t0 = __builtin_shufflevector(c0, c1, 0, 4, 2, 6), t1 = __builtin_shufflevector(c0, c1, 1, 5, 3, 7);
    *r0 = __builtin_shufflevector(t0, c2, 0, 1, 4, 7);
    *r1 = __builtin_shufflevector(t1, c2, 0, 1, 5, 7);
    *r2 = __builtin_shufflevector(t0, c2, 2, 3, 6, 7);
}
#endif
