/* vtdyn — The general (factorized) recursive route (recursive/general.c): composite inertias, M*, Q
 * and (5) by vt_solve's routes; the lowest of the recursive files. */
#ifndef VT_RECURSIVE_GENERAL_H
#define VT_RECURSIVE_GENERAL_H

#include "vtdyn.h"
#include "numeric/route.h" /* vt_handoff */

/* W̄: every subtree's needed wrench about its joint point P_i at the accelerations d->xdd and
 * alpha (3 x (nbody+1)), into W (6 x (nbody+1)) */
void vt_subtree_wrenches_at_joints(const vt_model *m, const vt_data *d, const double *alpha, double *W);
/* M* by composite bodies and Q by a Newton–Euler pass, into d->Mstar and d->Q */
vt_status vt_mass_and_bias(const vt_model *m, vt_data *d);
/* (5) by vt_solve on the composite M*, its answer judged: VT_OK with *to VT_HANDOFF_DENSE or
 * VT_HANDOFF_MAXIMAL where the dense stages are to decide (nothing else then holds) */
vt_status vt_composite_solve(const vt_model *m, vt_data *d, vt_handoff *to);
/* 1 when a free-rate route's estimate rcond asks for the maximal-coordinate route (vt_maximal_wanted),
 * or its answer for the componentwise estimate of the dense stages (vt_answer_size) */
int vt_maximal_instead(const vt_model *m, const vt_data *d, vt_route route, double rcond);
/* M* and Q formed, (5) solved, the reactions inward: the constraints already evaluated */
vt_status vt_factorized_instant(const vt_model *m, vt_data *d, vt_handoff *to);

#endif
