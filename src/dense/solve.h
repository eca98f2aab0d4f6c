/* vtdyn — The solve stage: the dispatcher among the routes through (5), its diagnosis of a
 * refusal, and vt_solve (dense/solve.c). */
#ifndef VT_DENSE_SOLVE_H
#define VT_DENSE_SOLVE_H

#include <stddef.h>

#include "vtdyn.h"
#include "kinematics/kinematics.h" /* vt_form */

size_t vt_solve_scratch(const vt_model *m);

/* vt_solve without the argument check and without clearing d->fallback: the
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
 * and the form of M* (vt_form: S^T M S, or the composite inertias about o, as vt_rate_bounds),
 * and vt_solve with it on the dense M*: the ODE formulation's residual */
vt_status vt_solve_band(const vt_model *m, vt_data *d, double band, vt_form form);
vt_status vt_solve_run(const vt_model *m, vt_data *d, double band);

#endif
