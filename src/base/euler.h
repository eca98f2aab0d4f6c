/* vtdyn — Euler parameters inline (the public ones are in vtdyn/euler.h, defined in base/euler.c): the
 * products with E and G, the rate of p, and the sine and cosine of half angles. */
#ifndef VT_BASE_EULER_H
#define VT_BASE_EULER_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "vtdyn/euler.h"

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
 * No library call, no table: inline in the fused passes' loop, where a call to libm's sincos
 * would spill every live value around it. vt_sincos_small needs
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
 * numbers): four integer loads instead of four double compares, once a body */
static inline int vt_quat_is_identity(const double *p)
{
    uint64_t u[4];
    memcpy(u, p, sizeof u);
    return ((u[0] ^ 0x3ff0000000000000u) | u[1] | u[2] | u[3]) == 0;
}

#endif
