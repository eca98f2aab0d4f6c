/* A rigid body's inertia, the checks the builder makes of it and the parallel axes that merge
 * parts of a body (the URDF loader's fixed links, a payload):
 *
 *   J accepted:   J = Jᵀ, principal moments λ1 ≤ λ2 ≤ λ3 with λ1 ≥ 0 and λ1 + λ2 ≥ λ3, each to
 *                 reltol of its largest entry (vt_check_inertia)
 *   J merged:     J += Q Jp Qᵀ + m (|d|² 1 − d dᵀ)   (vt_inertia_add)
 */
#include <math.h>
#include <stddef.h>

#include "model/inertia.h"
#include "base/lapack.h"
#include "base/status.h"

/* Inertia: symmetric, principal moments ≥ 0 and each ≤ the sum of the other two, to the relative
 * tolerance reltol (vt_model_def.inertia_tol, by default VT_INERTIA_TOL) of its largest entry
 * (files such as URDF print inertias to a few digits: moments off the triangle inequality, or an
 * entry of −5e-20, by round-off; a genuinely bad inertia is off by far more, and a file off by
 * more than round-off is the caller's to accept with a larger reltol, which the messages name).
 * Zero is a point mass and allowed. Principal moments from LAPACK's dsyev, on J divided by its
 * largest entry: no overflow near DBL_MAX. */
/* the tail of a refusal: the tolerance, and the option that relaxes it */
#define TOL_HINT "the tolerance %g (vt_model_def.inertia_tol relaxes it)"

vt_status vt_check_inertia(char *msg, const char *who, const double J[9], double reltol)
{
    double scale = 0.0;
    for (int k = 0; k < 9; k++) scale = fabs(J[k]) > scale ? fabs(J[k]) : scale;
    /* the rotational mass 4 GᵀJ'G has entries up to 12 times the largest (G's rows orthonormal
     * for unit p): VT_INERTIA_MAX = 1e307 < DBL_MAX/16 keeps it finite; beyond, it cannot be used */
    if (scale > VT_INERTIA_MAX)
        return vt_fail(msg, VT_ERR_NONFINITE, "%s: inertia entry of magnitude %g beyond %g: its mass matrix would overflow",
                       who, scale, VT_INERTIA_MAX);
    if (scale == 0.0) return VT_OK;
    /* checked on J/scale (entries in [−1, 1]): no difference, tolerance or moment overflows */
    double a[9], w[3], work[16];
    for (int k = 0; k < 9; k++) a[k] = J[k] / scale;
    const double tol = reltol + VT_INERTIA_ABS_TOL / scale; /* the floor: a point mass written −5e-20 */
    if (!(fabs(a[1] - a[3]) <= tol) || !(fabs(a[2] - a[6]) <= tol) || !(fabs(a[5] - a[7]) <= tol))
        return vt_fail(msg, VT_ERR_INERTIA_ASYMMETRIC,
                       "%s: inertia not symmetric (J12 %g J21 %g, J13 %g J31 %g, J23 %g J32 %g) beyond " TOL_HINT,
                       who, J[3], J[1], J[6], J[2], J[7], J[5], reltol);
    const int n = 3, lwork = 16;
    int info = 0;
    dsyev_("N", "L", &n, a, &n, w, work, &lwork, &info, 1, 1);
    if (info != 0)
        return vt_fail(msg, VT_ERR_LAPACK, "%s: dsyev info %d on the inertia matrix", who, info);
    if (w[0] < -tol)
        return vt_fail(msg, VT_ERR_INERTIA_NOT_PSD, "%s: principal moment %g < 0 by %.2g of the largest entry, beyond "
                       TOL_HINT, who, w[0] * scale, -w[0], reltol);
    if (w[0] + w[1] < w[2] - tol)
        return vt_fail(msg, VT_ERR_INERTIA_TRIANGLE, "%s: principal moments %g + %g < %g by %.2g of the largest entry, "
                       "beyond " TOL_HINT, who, w[0] * scale, w[1] * scale, w[2] * scale, w[2] - w[0] - w[1], reltol);
    return VT_OK;
}

/* an inertia the check accepted made symmetric: off-symmetric by its tolerance at most */
void vt_inertia_symmetric(double J[9])
{
    for (int r = 0; r < 3; r++)
        for (int c = r + 1; c < 3; c++) J[r + 3 * c] = J[c + 3 * r] = 0.5 * (J[r + 3 * c] + J[c + 3 * r]);
}

void vt_inertia_add(double J[9], double m, const double Jp[9], const double Q[9], const double d[3])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            double s = 0.0;
            if (!Q)
                s = Jp[r + 3 * c];
            else
                for (int a = 0; a < 3; a++)
                    for (int e = 0; e < 3; e++) s += Q[r + 3 * a] * Jp[a + 3 * e] * Q[c + 3 * e];
            /* m (|d|² δ_rc − d_r d_c): on the diagonal the other two squares, not |d|² − d_r²,
             * which cancels (and, contracted into one FMA, leaves d_r²'s rounding where the
             * exact value is 0: a rod's own axis) */
            const double pa = r == c ? d[(r + 1) % 3] * d[(r + 1) % 3] + d[(r + 2) % 3] * d[(r + 2) % 3] : -(d[r] * d[c]);
            J[r + 3 * c] += s + m * pa;
        }
}

