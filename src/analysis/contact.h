/* vtdyn — Contacts: the contact set of a robot on the ground (analysis/contact.c), whose forces
 * the distribution rule gives (analysis/contact_rule.c). The entry points are public (vtdyn.h:
 * vt_contacts_*, vt_default_contact_def, vt_find_contact); the analyses over time
 * (analysis/contact_run.c) take the model they were made for, a flag per contact for the
 * schedule, the forces' loads and the instant's outputs kept. */
#ifndef VT_ANALYSIS_CONTACT_H
#define VT_ANALYSIS_CONTACT_H

#include "vtdyn.h"

const vt_model *vt_contacts_model(const vt_contacts *contacts);
/* one int per contact, the contacts' own (a run's schedule writes it at each time) */
int *vt_contacts_active(vt_contacts *contacts);
/* the last instant's forces as loads, 6 (nbody + 1) as vt_data.xfrc (what its inward pass applied) */
const double *vt_contacts_loads(const vt_contacts *contacts);
/* the data's efforts (qfrc_drive), limit excesses and joint reactions and totals in both axes: into
 * the contacts' keeping (save 1) or back (0) */
void vt_contacts_outputs(const vt_model *model, vt_data *data, vt_contacts *contacts, int save);

#endif
