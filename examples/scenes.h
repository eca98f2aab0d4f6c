/* Scenes written once and shared by the tests, the examples and the benchmarks. */
#ifndef VT_SCENES_H
#define VT_SCENES_H

#include <stdint.h>

#include "vtdyn.h"

/* The paper's double link (Fig. 4): two uniform slender links, 2 m and 100 kg each, joined
 * to the ground and to each other by revolute joints about z; body frames at the links'
 * centres with x along the link; at q = 0 both lie along +x from the origin; y up,
 * gravity (0, −9.81, 0). The angle fallen below x is θ = −q1. With lock != 0, drive 0 keeps
 * joint 2 at q2 = 0 (the paper's "q² = const.") and the pair falls as one 4 m rod. */
#define VT_DL_LENGTH 2.0
#define VT_DL_MASS 100.0
vt_status vt_scene_double_link(vt_model **model, int lock);

/* A spatial serial chain of n uniform rods (1 kg, 0.5 m along x) joined by revolute joints
 * whose axes cycle x, y, z. */
vt_status vt_scene_chain(vt_model **model, int n);

/* A random tree of n bodies whose joints cycle through the kinds in `kinds` (a mask of
 * 1 << vt_joint_type; base bodies hang from the ground): random parents, masses, principal
 * inertias, joint points, axes and orientations at q = 0. Deterministic in seed. */
#define VT_SCENE_ALL_JOINTS 0x3Fu
#define VT_SCENE_NO_BASE (VT_SCENE_ALL_JOINTS & ~(1u << VT_JOINT_BASE))
/* joints whose coordinates are all scalar (q̇ is the time derivative of q) */
#define VT_SCENE_SCALAR_JOINTS ((1u << VT_JOINT_REVOLUTE) | (1u << VT_JOINT_UNIVERSAL) | \
                                (1u << VT_JOINT_TRANSLATIONAL) | (1u << VT_JOINT_CYLINDRICAL))
vt_status vt_scene_random_tree(vt_model **model, uint64_t seed, int n, unsigned kinds);

/* A random state: angles in [−π, π], translations in [−1, 1], random unit Euler parameters,
 * rates in [−2, 2] (base bodies: ṗ = ½ E^T ω, tangent to the unit sphere). */
void vt_scene_random_state(const vt_model *model, vt_data *data, uint64_t *seed);

/* Random numbers for scenes and tests: splitmix64 on a caller-held state. */
double vt_rand_uniform(uint64_t *state, double lo, double hi);
void vt_rand_unit(double *v, int n, uint64_t *state); /* uniform direction in R^n */

#endif
