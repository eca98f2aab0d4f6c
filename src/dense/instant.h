/* vtdyn — One instant by the dense stages (dense/instant.c). */
#ifndef VT_DENSE_INSTANT_H
#define VT_DENSE_INSTANT_H

#include "vtdyn.h"

/* the given motion of a mechanism with loops or couplings: the joint drives' rows take q̈ from
 * d->qdd (instant.c) */
vt_status vt_motion_rows(const vt_model *m, vt_data *d);

#endif
