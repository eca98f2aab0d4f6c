/* Contacts over time: a fully driven robot's kinematic analysis on its contacts, and the forward
 * check that proves it (docs/contact.md, "Over time").
 *
 * At each time t the drives fix q, q̇ and q̈ (the kinematic solve). The ground's forces f_c are the
 * distribution rule's at that state (vt_inverse_dynamics_contacts, over the contacts the schedule
 * puts on the ground at t), and the drives' efforts are those of the driven instant with the
 * forces applied as loads, the paper's (5) with them in Q:
 *   Φ_q^T λ = M* q̈ − Q − Σ_c J_c^T f_c = τ,
 * τ the rule's efforts: zero on a free root's rates, whose equations the forces satisfy. The
 * drives' generalized force Φ_q^T λ is then what the motors give, whatever drives fix the motion
 * (joint drives on the legs, or point drives holding the feet and a free root's drives moving the
 * torso). The efforts and the joint reactions kept are the contacts' instant's, the motors' τ the
 * actuation: the driven instant's would count a body drive's force (a point drive holding a foot)
 * as a load on the body, where no such force acts. The forward check integrates the model without
 * drives under τ and the forces as applied loads (analysis/dae.c): the motion, and with
 * vt_run_options.forward_as_loads = 0 the reactions, must come back.
 */
#include <stddef.h>
#include <string.h>

#include "analysis/contact_run.h"
#include "analysis/contact.h"
#include "base/status.h"

vt_status vt_contacts_run_check(const vt_model *m, vt_data *d, const vt_run_options *opt, const vt_trajectory *tr,
                                const char *who)
{
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

vt_status vt_contacts_driven(const vt_model *m, vt_data *d, const vt_run_options *opt, const double *base,
                             double *force, int *active, int drives, const char *who)
{
    vt_contacts *c = opt->contacts;
    const int n = vt_contacts_count(c);
    const size_t nxf = 6 * ((size_t)m->nbody + 1);
    const double t = d->time;
    char msg[VT_MESSAGE_SIZE];
    if (!active) active = vt_contacts_active(c);
    for (int k = 0; k < n; k++) active[k] = 1;
    if (opt->contact_schedule && opt->contact_schedule(t, active, opt->contact_user))
        return vt_fail(d->message, VT_ERR_CALLBACK, "%s: the contact schedule failed at t = %.10g", who, t);
    for (int k = 0; k < n; k++) active[k] = active[k] != 0;
    memcpy(d->xfrc, base, nxf * sizeof(double));
    vt_status st = vt_inverse_dynamics_contacts(m, d, c, active, force);
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
    memcpy(d->xfrc, base, nxf * sizeof(double));
    memcpy(msg, d->message, sizeof msg);
    return vt_fail(d->message, st, "%s: contacts at t = %.10g: %s", who, t, msg);
}
