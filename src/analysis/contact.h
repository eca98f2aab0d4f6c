/* vtdyn — Contacts: the given motion of a robot on the ground, the ground's forces by the
 * distribution rule (analysis/contact.c). The entry points are public (vtdyn.h: vt_contacts_*,
 * vt_default_contact_def, vt_find_contact, vt_inverse_dynamics_contacts); nothing internal is
 * shared. */
#ifndef VT_ANALYSIS_CONTACT_H
#define VT_ANALYSIS_CONTACT_H

#include "vtdyn.h"

#endif
