/* Loads over time: a fully driven model's kinematic analysis with wrenches at frames (a Delta's
 * gripper pressing a part: vt_run_options.loads) and on a robot's contacts, and the forward
 * check that proves it (docs/contact.md, "Over time").
 *
 * At each time t the drives fix q, q̇ and q̈ (the kinematic solve). The wrenches at frames join the
 * caller's xfrc at that state's poses, each as vt_add_frame_load() adds it (force f at the
 * frame's point p, moment n about it: f, and n + (p − c) × f about the body's centre of mass c),
 * and the instant is taken again with them. On contacts, the ground's forces f_c are the
 * distribution rule's at that state (vt_inverse_dynamics_contacts, over the contacts the schedule
 * puts on the ground at t), and the drives' efforts are those of the driven instant with the
 * forces applied as loads, the paper's (5) with them in Q:
 *   Φ_q^T λ = M* q̈ − Q − Σ_c J_c^T f_c = τ,
 * τ the rule's efforts (the wrenches at frames in Q too): zero on a free root's rates, whose
 * equations the forces satisfy. The
 * drives' generalized force Φ_q^T λ is then what the motors give, whatever drives fix the motion
 * (joint drives on the legs, or point drives holding the feet and a free root's drives moving the
 * torso). The efforts and the joint reactions kept are the contacts' instant's, the motors' τ the
 * actuation: the driven instant's would count a body drive's force (a point drive holding a foot)
 * as a load on the body, where no such force acts. The forward check integrates the model without
 * drives under τ and the forces and wrenches as applied loads, formed at the driven state
 * (analysis/dae.c): the motion, and with
 * vt_run_options.forward_as_loads = 0 the reactions, must come back.
 */
#include <stddef.h>
#include <string.h>

#include "analysis/contact_run.h"
#include "analysis/contact.h"
#include "base/status.h"
#include "kinematics/state.h"

vt_status vt_run_loads_check(const vt_model *m, vt_data *d, const vt_run_options *opt, const vt_trajectory *tr,
                             const char *who)
{
    if (opt->nload < 0 || opt->nload > VT_RUN_LOADS_MAX)
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: nload %d outside 0..%d", who, opt->nload, VT_RUN_LOADS_MAX);
    if (opt->nload > 0 && (!opt->load_frame || !opt->loads))
        return vt_fail(d->message, VT_ERR_NULL, "%s: nload %d with load_frame or loads NULL", who, opt->nload);
    for (int k = 0; k < opt->nload; k++) {
        const int f = opt->load_frame[k];
        if (f < 0 || f >= m->nframe)
            return vt_fail(d->message, VT_ERR_BAD_INDEX, "%s: load %d at frame %d: the model has %d frames", who, k, f,
                           m->nframe);
        if (m->frame_body[f] == 0) /* the ground takes it: the mechanism feels nothing */
            return vt_fail(d->message, VT_ERR_BAD_INDEX, "%s: load %d at frame %d '%s': on the ground", who, k, f,
                           m->frame_name + (size_t)VT_NAME_MAX * f);
    }
    if (!opt->contacts) return VT_OK;
    if (vt_contacts_model(opt->contacts) != m)
        return vt_fail(d->message, VT_ERR_MODEL_MISMATCH, "%s: contacts made for another model", who);
    if (tr->ncontact != vt_contacts_count(opt->contacts))
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "%s: the trajectory has room for %d contacts' forces and the run has %d: make it with "
                       "vt_trajectory_create_contacts() on the same contacts", who, tr->ncontact,
                       vt_contacts_count(opt->contacts));
    return VT_OK;
}

/* the wrenches at frames at d->time added to d->xfrc, at the poses of d's instant */
static vt_status frame_loads(const vt_model *m, vt_data *d, const vt_run_options *opt, const char *who)
{
    if (opt->nload == 0) return VT_OK;
    double w[6 * VT_RUN_LOADS_MAX];
    vt_status st;
    if (opt->loads(d->time, w, opt->load_user))
        return vt_fail(d->message, VT_ERR_CALLBACK, "%s: the loads' callback failed at t = %.10g", who, d->time);
    const vt_frame_loads fl = {opt->nload, opt->load_frame, w};
    st = vt_add_frame_loads(m, d, &fl);
    if (st) {
        char msg[VT_MESSAGE_SIZE];
        memcpy(msg, d->message, sizeof msg);
        return vt_fail(d->message, st, "%s: the loads at t = %.10g: %s", who, d->time, msg);
    }
    return VT_OK;
}

vt_status vt_run_loads(const vt_model *m, vt_data *d, const vt_run_options *opt, const double *base, double *force,
                       int *active, int drives, const char *who)
{
    vt_contacts *c = opt->contacts;
    const size_t nxf = 6 * ((size_t)m->nbody + 1);
    const double t = d->time;
    char msg[VT_MESSAGE_SIZE];
    memcpy(d->xfrc, base, nxf * sizeof(double));
    vt_status st = frame_loads(m, d, opt, who);
    if (st) {
        memcpy(d->xfrc, base, nxf * sizeof(double));
        return st;
    }
    if (!c) { /* the driven instant again, the loads applied */
        if (!(st = vt_inverse_dynamics_recursive(m, d))) return VT_OK;
    } else {
        const int n = vt_contacts_count(c);
        if (!active) active = vt_contacts_active(c);
        for (int k = 0; k < n; k++) active[k] = 1;
        if (opt->contact_schedule && opt->contact_schedule(t, active, opt->contact_user)) {
            memcpy(d->xfrc, base, nxf * sizeof(double));
            return vt_fail(d->message, VT_ERR_CALLBACK, "%s: the contact schedule failed at t = %.10g", who, t);
        }
        for (int k = 0; k < n; k++) active[k] = active[k] != 0;
        st = vt_inverse_dynamics_contacts(m, d, c, active, force);
        if (!st) { /* the forces as loads (what the instant applied by its inward pass); with drives
                    * the drives' efforts with them, and the instant's own efforts and reactions back */
            const double *loads = vt_contacts_loads(c);
            for (size_t k = 0; k < nxf; k++) d->xfrc[k] += loads[k];
            if (drives) {
                vt_contacts_outputs(m, d, c, 1);
                st = vt_inverse_dynamics_recursive(m, d);
                if (!st) vt_contacts_outputs(m, d, c, 0);
            }
        }
        if (!st) return VT_OK;
    }
    memcpy(d->xfrc, base, nxf * sizeof(double));
    memcpy(msg, d->message, sizeof msg);
    return vt_fail(d->message, st, "%s: %s at t = %.10g: %s", who, c ? "contacts" : "the loads", t, msg);
}
