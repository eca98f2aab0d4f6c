/* Euler-parameter kinematics: the paper's eq (8) and docs/method.md "Coordinates".
 *
 *   p = [p0; e],  e = [p1 p2 p3]
 *   E(p) = [-e, ẽ + p0 I]:  rows [-p1  p0 -p3  p2], [-p2  p3  p0 -p1], [-p3 -p2  p1  p0]
 *   G(p) = [-e, -ẽ + p0 I]: rows [-p1  p0  p3 -p2], [-p2 -p3  p0  p1], [-p3  p2 -p1  p0]
 *   A(p) = E(p) G(p)^T     (body → global)
 * (The printed (8) carries a stray transpose: E is 3x4.)
 */
#include "base/euler.h"

void vt_euler_E(double E[12], const double p[4])
{
    /* column-major 3x4: E[row + 3*col] */
    E[0] = -p[1]; E[1] = -p[2]; E[2] = -p[3];
    E[3] = p[0];  E[4] = p[3];  E[5] = -p[2];
    E[6] = -p[3]; E[7] = p[0];  E[8] = p[1];
    E[9] = p[2];  E[10] = -p[1]; E[11] = p[0];
}

void vt_euler_G(double G[12], const double p[4])
{
    G[0] = -p[1]; G[1] = -p[2]; G[2] = -p[3];
    G[3] = p[0];  G[4] = -p[3]; G[5] = p[2];
    G[6] = p[3];  G[7] = p[0];  G[8] = -p[1];
    G[9] = -p[2]; G[10] = p[1]; G[11] = p[0];
}

void vt_euler_A(double A[9], const double p[4])
{
    vt_euler_A_inline(A, p);
}

void vt_quat_mul(double r[4], const double a[4], const double b[4])
{
    vt_quat_mul_inline(r, a, b);
}

void vt_quat_axis_angle(double p[4], const double u[3], double angle)
{
    double s;
    vt_sincos(0.5 * angle, &s, p);
    p[1] = s * u[0]; p[2] = s * u[1]; p[3] = s * u[2];
}
