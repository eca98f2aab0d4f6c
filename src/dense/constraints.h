/* vtdyn — The constraint rows stage (dense/constraints.c). */
#ifndef VT_DENSE_CONSTRAINTS_H
#define VT_DENSE_CONSTRAINTS_H

#include <stddef.h>

#include "vtdyn.h"
#include "kinematics/kinematics.h" /* vt_form */

size_t vt_constraints_scratch(const vt_model *m);

/* vt_constraints with Φ_q in the form asked (vt_form: from the dense S or from the twists) */
vt_status vt_constraints_impl(const vt_model *m, vt_data *d, vt_form form);
/* the same, its parts chosen: Φ and Φ_t always, Φ_x (VT_CON_PHIX) and Φ_q (VT_CON_PHIQ) from the
 * positions and twists, γ from the velocities and Ṡq̇ as well (VT_CON_GAMMA); a part left out may
 * be left as it was. fd: the joint and point drives' f, f', f'' at d->time (3 a drive, from
 * vt_drive_values), or NULL to evaluate them */
enum { VT_CON_PHIX = 1, VT_CON_PHIQ = 2, VT_CON_GAMMA = 4, VT_CON_ALL = 7 };
vt_status vt_constraints_parts(const vt_model *m, vt_data *d, vt_form form, int parts, const double *fd);
vt_status vt_drive_values(const vt_model *m, vt_data *d, double *fd);
/* the driven rates' prescribed q̈ = f'' and their rows' Φ, Φ_t, γ (the recursive evaluation's joint
 * drives, without the rows' Jacobian) */
vt_status vt_drive_accelerations(const vt_model *m, vt_data *d);

#endif
