/* vtdyn — Contacts over time: the kinematic analysis's rows and the forward check's efforts on a
 * robot's contacts (analysis/contact_run.c). */
#ifndef VT_ANALYSIS_CONTACT_RUN_H
#define VT_ANALYSIS_CONTACT_RUN_H

#include "vtdyn.h"

/* a run on opt->contacts (none: VT_OK): made for m, and the trajectory with room for their forces */
vt_status vt_contacts_run_check(const vt_model *m, vt_data *d, const vt_run_options *opt, const vt_trajectory *tr,
                                const char *who);

/* At d's driven state (q, q̇, q̈ consistent at d->time): the schedule's flags at d->time into active
 * (one per contact; NULL: the contacts' own), the ground's forces into force (NULL: not kept), the
 * efforts and reactions of the contacts' instant, and with drives the drives' λ and efforts of
 * the driven instant again with base (the caller's loads) and the forces applied (without, d's
 * drive outputs are left as they were: the forward check's joint torques need none). On return
 * d->xfrc holds base plus the forces' loads; on failure base alone, the message naming the time. */
vt_status vt_contacts_driven(const vt_model *m, vt_data *d, const vt_run_options *opt, const double *base,
                             double *force, int *active, int drives, const char *who);

#endif
