/* vtdyn — The generalized forces stage (dense/forces.c). */
#ifndef VT_DENSE_FORCES_H
#define VT_DENSE_FORCES_H

#include <stddef.h>

#include "vtdyn.h"

size_t vt_forces_scratch(const vt_model *m);

#endif
