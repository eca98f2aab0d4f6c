/* vtdyn — State utilities (kinematics/state.c). Offers only public functions (vtdyn.h). */
#ifndef VT_KINEMATICS_STATE_H
#define VT_KINEMATICS_STATE_H

#include "vtdyn.h"

#endif
