/* vtdyn — The recursive evaluation of one instant (recursive/recursive.c): the dispatcher
 * vt_inverse_dynamics_recursive (declared in vtdyn.h), the square route, the positioned entry.
 *
 * The recursive files, lowest first; each .c calls only the files before it in this list (and the
 * lower folders):
 *   general.c      composite inertias, M*, Q, the factorized route (5)
 *   fused.c        the inward pass, the fused joint-driven and given-motion passes,
 *                  vt_inverse_dynamics_motion
 *   articulated.c  the articulated-body route (falls back to general.c's factorized instant)
 *   recursive.c    the dispatcher, the square route, the positioned entry, the scratch bound
 * (fused.c and articulated.c do not call each other.) */
#ifndef VT_RECURSIVE_RECURSIVE_H
#define VT_RECURSIVE_RECURSIVE_H

#include <stddef.h>

#include "vtdyn.h"
#include "numeric/route.h" /* vt_handoff */

/* the scratch the recursive files take at once */
size_t vt_recursive_scratch(const vt_model *m);

/* vt_inverse_dynamics_recursive with d's positions, twists, Φ, Φ_t and Φ_q current at d->q and
 * d->time (Newton's last evaluation), q̇ new, or with rates, q̇ solved from Φ_q q̇ = −Φ_t by the
 * square route's LU (else VT_OK with *to = VT_HANDOFF_RATES, d->qd as it was); fd: the drives' functions at d->time
 * (vt_drive_values) or NULL; α and the joints' total wrenches only with totals (recursive.c) */
vt_status vt_inverse_dynamics_recursive_positioned(const vt_model *m, vt_data *d, const double *fd, int totals, int rates,
                                                   vt_handoff *to);

#endif
