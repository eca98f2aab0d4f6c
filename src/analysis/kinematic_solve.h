/* vtdyn — The kinematic solve: Newton on Φ(q, t) = 0, then the instant (analysis/kinematic_solve.c). */
#ifndef VT_ANALYSIS_KINEMATIC_SOLVE_H
#define VT_ANALYSIS_KINEMATIC_SOLVE_H

#include <stddef.h>

#include "vtdyn.h"

size_t vt_kinematic_solve_scratch(const vt_model *m);

/* vt_kinematic_solve without the argument check, the instant after the solve by the recursive
 * evaluation (recursive = VT_SOLVE_RECURSIVE, or VT_SOLVE_RECURSIVE_NO_TOTALS:
 * vt_kinematic_analysis) or the dense one (VT_SOLVE_DENSE); with qprev (q and q̇ of a
 * solution at t − h: qprev nq, qdprev nv) d->q is a start predicted from it, abandoned for qprev
 * itself when its max |Φ| exceeds ½ h max |Φ_t| (roughly qprev's own residual at t) */

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

#endif
