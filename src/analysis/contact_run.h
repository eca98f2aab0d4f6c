/* vtdyn — Loads over time: the kinematic analysis's rows and the forward check's efforts with a
 * run's wrenches at frames and on a robot's contacts (analysis/contact_run.c). */
#ifndef VT_ANALYSIS_CONTACT_RUN_H
#define VT_ANALYSIS_CONTACT_RUN_H

#include "vtdyn.h"

/* a run's loads at frames (opt->nload, opt->load_frame, opt->loads) and contacts (opt->contacts):
 * VT_OK when none; the frames the model's on moving bodies, the contacts made for m and the
 * trajectory with room for their forces */
vt_status vt_run_loads_check(const vt_model *m, vt_data *d, const vt_run_options *opt, const vt_trajectory *tr,
                             const char *who);

/* 1 when a run has loads at frames or contacts (vt_run_loads has work) */
static inline int vt_run_has_loads(const vt_run_options *opt)
{
    return opt->nload > 0 || opt->contacts != NULL;
}

/* At d's driven state (q, q̇, q̈ consistent at d->time, the instant done there: its poses): base
 * (the caller's loads) plus the wrenches at frames opt->loads gives at d->time, then on contacts
 * the schedule's flags at d->time into active (one per contact; NULL: the contacts' own), the
 * ground's forces into force (NULL: not kept), the efforts and reactions of the contacts'
 * instant, and with drives the drives' λ and efforts of the driven instant again with the loads
 * and forces applied (without, d's drive outputs are left as they were: the forward check's joint
 * torques need none); without contacts the driven instant again with the loads. On return
 * d->xfrc holds base plus the loads; on failure base alone, the message naming the time. */
vt_status vt_run_loads(const vt_model *m, vt_data *d, const vt_run_options *opt, const double *base, double *force,
                       int *active, int drives, const char *who);

#endif
