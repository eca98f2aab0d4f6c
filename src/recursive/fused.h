/* vtdyn — The fused passes (recursive/fused.c): the joint-driven and the given-motion instants of a
 * tree without base bodies, and the inward pass after q̈ is known. vt_inverse_dynamics_motion
 * (declared in vtdyn.h) is defined in recursive/fused.c. */
#ifndef VT_RECURSIVE_FUSED_H
#define VT_RECURSIVE_FUSED_H

#include <math.h>

#include "vtdyn.h"
#include "base/scan.h"
#include "base/status.h"
#include "kinematics/state.h"

/* the largest |xfrc| and |qfrc| (one scan), the largest of those and |q|, |q̇| (one scan), of
 * |q̈|: +Inf where one is not finite */
static inline double vt_loads_max(const vt_model *m, const vt_data *d)
{
    vt_max_scan s = {0};
    vt_max_add(&s, d->xfrc, 6 * (m->nbody + 1));
    vt_max_add(&s, d->qfrc, m->nv);
    return vt_max_result(&s);
}
static inline double vt_state_max(const vt_model *m, const vt_data *d)
{
    vt_max_scan s = {0};
    vt_max_add(&s, d->xfrc, 6 * (m->nbody + 1));
    vt_max_add(&s, d->qfrc, m->nv);
    vt_max_add(&s, d->q, m->nq);
    vt_max_add(&s, d->qd, m->nv);
    return vt_max_result(&s);
}
static inline double vt_array_max(const double *a, int n)
{
    vt_max_scan s = {0};
    vt_max_add(&s, a, n);
    return vt_max_result(&s);
}

/* The start of every recursive instant: the pair checked, the diagnostics cleared, the loads
 * finite; *smax the largest |·| of the loads, q and q̇ (+Inf where q or q̇ is not finite) */
static inline vt_status vt_recursive_start(const vt_model *m, vt_data *d, double *smax)
{
    const vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_recursive");
    if (st) return st;
    vt_diagnostics_reset(d);
    *smax = vt_state_max(m, d); /* loads, q and q̇; the loads alone where one is not finite */
    if (!(*smax < HUGE_VAL) && !(vt_loads_max(m, d) < HUGE_VAL))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: NaN or Inf in xfrc or qfrc");
    return VT_OK;
}

/* the inward pass after the kinematics and q̈: the joint drives' efforts and every reaction; with
 * totals (no base body) also α and the joints' total wrenches */
vt_status vt_inward(const vt_model *m, vt_data *d, int totals);
/* vt_inverse_dynamics_recursive of a model whose every rate is joint-driven, without base bodies
 * (joint_driven, joint_mix ≥ 0): the fused passes, α and the total wrenches formed, the inputs and
 * outputs checked */
vt_status vt_fused_driven(const vt_model *m, vt_data *d);
/* after vt_inverse_dynamics_motion's instant of a tree (no cut joint, no coupling), its efforts,
 * reactions and totals with the loads xf (6 (nbody+1), as vt_data.xfrc) added, by the inward
 * pass alone (the instant is linear in the loads); the limits flagged again */
vt_status vt_motion_add_loads(const vt_model *m, vt_data *d, const double *xf);
/* vt_inverse_dynamics_motion() with loads at frames (NULL: none): a tree's passes carry them as
 * they carry xfrc; with loops or couplings they are added to xfrc for the dense stages and xfrc
 * is put back after (vt_motion_rows). VT_ERR_NONFINITE for a NaN or Inf load, before anything is
 * computed */
vt_status vt_motion_loaded(const vt_model *m, vt_data *d, const vt_frame_loads *loads);

#endif
