/* vtdyn — The solve stage: the dispatcher among the routes through (5), its diagnosis of a
 * refusal, and vt_solve (dense/solve.c). */
#ifndef VT_DENSE_SOLVE_H
#define VT_DENSE_SOLVE_H

#include <stddef.h>

#include "vtdyn.h"
#include "kinematics/kinematics.h" /* vt_form */
#include "numeric/route.h"           /* vt_handoff */

size_t vt_solve_scratch(const vt_model *m);

/* vt_solve without the argument check and without clearing d->fallback, on the recursive general
 * route's composite M* about o (VT_FORM_TWISTS), after its own shortcuts have flagged their
 * fallbacks. A rate whose M*_aa is round-off of the composite terms and that no row fixes is not
 * refused: VT_OK with *to = VT_HANDOFF_DENSE, nothing solved (the dense stages decide); else *to
 * = VT_HANDOFF_NONE. */
vt_status vt_solve_impl(const vt_model *m, vt_data *d, vt_handoff *to);
/* the same with a time analysis's band (vt_run_options.redundant_band; 0 is vt_solve_impl) and
 * the form of M* (vt_form: S^T M S, or the composite inertias about o, as vt_rate_bounds); to may
 * be NULL with VT_FORM_DENSE, which never hands off. vt_solve_run: vt_solve with the band on the
 * dense M*, the ODE formulation's residual */
vt_status vt_solve_band(const vt_model *m, vt_data *d, double band, vt_form form, vt_handoff *to);
vt_status vt_solve_run(const vt_model *m, vt_data *d, double band);

#endif
