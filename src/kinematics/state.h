/* vtdyn — State utilities (kinematics/state.c): the public ones (vtdyn.h) and the loads at
 * frames that a batch row carries. */
#ifndef VT_KINEMATICS_STATE_H
#define VT_KINEMATICS_STATE_H

#include "vtdyn.h"

/* wrenches the environment applies at frames: n of them, at frame[k] (on moving bodies), w 6 each
 * (the force, then the moment about the frame's origin, global axes) */
typedef struct vt_frame_loads {
    int n;
    const int *frame;
    const double *w;
} vt_frame_loads;

/* the loads added into xfrc at the poses of vt_kinematics(), each as vt_add_frame_load() adds it;
 * VT_OK, or the first failing one's status (a NaN or Inf load, or a sum that overflows) with the
 * loads before it added: the caller puts xfrc back */
vt_status vt_add_frame_loads(const vt_model *m, vt_data *d, const vt_frame_loads *loads);

#endif
