/* vtdyn — Euler-parameter kinematics (method.md "Coordinates"; the paper's eq (8)).
 *
 * p = [p0 p1 p2 p3] (scalar first), e = [p1 p2 p3]:
 *   E(p) = [-e, ẽ + p0 I]  (3x4),   G(p) = [-e, -ẽ + p0 I]  (3x4),   A(p) = E G^T (3x3),
 *   ω = 2 E ṗ (global),  ω' = 2 G ṗ (body),  ṗ = ½ E^T ω,  p̈ = ½ E^T ω̇ − ¼ (ω·ω) p.
 * All matrices column-major. These are plain algebra without a status: every argument is an
 * array of the size shown, never NULL (as with memcpy()).
 */
#ifndef VTDYN_EULER_H
#define VTDYN_EULER_H

#include "vtdyn/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/// E(p), 3x4 column-major (12 entries).
VT_API void vt_euler_E(double E[12], const double p[4]);
/// G(p), 3x4 column-major (12 entries).
VT_API void vt_euler_G(double G[12], const double p[4]);
/// A(p) = E G^T, 3x3 column-major: rotation from body to global axes.
VT_API void vt_euler_A(double A[9], const double p[4]);
/// Hamilton product r = a ⊗ b, so that A(r) = A(a) A(b). r may alias a or b.
VT_API void vt_quat_mul(double r[4], const double a[4], const double b[4]);
/// Euler parameters of a rotation by angle (rad) about the unit axis u.
VT_API void vt_quat_axis_angle(double p[4], const double u[3], double angle);

#ifdef __cplusplus
}
#endif

#endif
