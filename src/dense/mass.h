/* vtdyn — The mass matrix stage (dense/mass.c). */
#ifndef VT_DENSE_MASS_H
#define VT_DENSE_MASS_H

#include <stddef.h>

#include "vtdyn.h"

size_t vt_mass_scratch(const vt_model *m);

/* Mp = 4 G^T J' G (4x4 column-major), the rotational block of M^i (mass.c) */
void vt_rot_mass(double Mp[16], const double J[9], const double p[4]);

#endif
