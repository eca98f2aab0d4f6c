/* vtdyn — The velocity transformation's rows of R (Table 1) (kinematics/inverse_transform.c). */
#ifndef VT_KINEMATICS_INVERSE_TRANSFORM_H
#define VT_KINEMATICS_INVERSE_TRANSFORM_H

#include "vtdyn.h"

size_t vt_inverse_transform_scratch(const vt_model *m);

/* Row of R (Table 1) for rate `dof`: its entries on x^j (rj, 7) and on x^i (ri, 7). */
void vt_R_row(const vt_model *m, const vt_data *d, int dof, double rj[7], double ri[7]);

#endif
