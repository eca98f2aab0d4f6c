/* vtdyn — URDF files into a builder (model/urdf.c, libxml2). Offers only public functions (vtdyn.h). */
#ifndef VT_MODEL_URDF_H
#define VT_MODEL_URDF_H

#include "vtdyn.h"

#endif
