/* vtdyn — 3-vectors and 3x3 column-major matrices: the algebra every pass is written in. */
#ifndef VT_BASE_VEC3_H
#define VT_BASE_VEC3_H

#include <math.h>


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

/* a ← a/|a| for a vector of n entries, with |a| = s·sqrt(Σ (a_k/s)²) and s = max |a_k|: no
 * overflow of the sum of squares for lengths near DBL_MAX (1e160 and more), no underflow to zero
 * for tiny non-zero ones, so any finite non-zero vector keeps its direction. Returns |a| (Inf
 * when the length itself overflows; a is still normalized), or 0 for the zero vector (and a
 * NaN), which is left as it was. Axes and Euler parameters of definitions are directions: only
 * the zero vector has none (model/builder.c). */
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

#endif
