/* vtdyn — A rigid body's inertia: the builder's checks and the parallel axes (model/inertia.c). */
#ifndef VT_MODEL_INERTIA_H
#define VT_MODEL_INERTIA_H

#include "vtdyn.h"

/* A body's inertia J (3x3 column-major) as the builder accepts it: symmetric, positive
 * semi-definite and within the triangle inequality to reltol (vt_model_def.inertia_tol) of its
 * largest entry; the message starts with who ("body 3", a URDF link) and names the
 * option. */
vt_status vt_check_inertia(char *msg, const char *who, const double J[9], double reltol);

/* J += Q Jp Qᵀ + m (|d|² 1 − d dᵀ): a rigid part of mass m and inertia Jp (about its centre of
 * mass, in axes that Q maps to J's; Q NULL: J's axes) whose centre of mass is at d from the point
 * J is about, in J's axes (the parallel axes): how a body's parts are merged, the URDF loader's
 * fixed links (model/urdf.c) and a payload (vt_builder_add_payload). */
void vt_inertia_add(double J[9], double m, const double Jp[9], const double Q[9], const double d[3]);

/* an inertia the check accepted made symmetric (off-symmetric by its tolerance at most) */
void vt_inertia_symmetric(double J[9]);

#endif
