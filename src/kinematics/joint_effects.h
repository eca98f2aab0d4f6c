/* vtdyn — The joints' own efforts: armature, damping, friction (kinematics/joint_effects.c). */
#ifndef VT_KINEMATICS_JOINT_EFFECTS_H
#define VT_KINEMATICS_JOINT_EFFECTS_H

#include <math.h>

#include "vtdyn.h"

/* s(q̇): the sign (0 at rest), or tanh(q̇ / v) where the rate's friction velocity v is > 0 */
static inline double vt_friction_law(double qd, double v)
{
    if (v > 0.0) return tanh(qd / v);
    return qd > 0.0 ? 1.0 : qd < 0.0 ? -1.0 : 0.0;
}

/* damping q̇ + friction s(q̇) on rate c: the part of its effort its joint takes at this velocity */
static inline double vt_effect_velocity(const vt_model *m, const vt_data *d, int c)
{
    const double *e = m->dof_effects + 4 * c, qd = d->qd[c];
    return e[1] * qd + e[2] * vt_friction_law(qd, e[3]);
}

/* The generalized force acting along rate c before its q̈ is known: the applied qfrc less the
 * joint's damping and friction (its armature is inertia: M*_cc, an articulated pivot) */
static inline double vt_rate_force(const vt_model *m, const vt_data *d, int c)
{
    return m->has_effects ? d->qfrc[c] - vt_effect_velocity(m, d, c) : d->qfrc[c];
}

/* The same with q̈ known (d->qdd): less armature q̈ too. What reaches the joint's bodies along
 * the rate besides a drive's effort: the effort τ = s · W̄ − this, the reaction W̄ less (τ + this) */
static inline double vt_rate_load(const vt_model *m, const vt_data *d, int c)
{
    return m->has_effects ? d->qfrc[c] - m->dof_effects[4 * c] * d->qdd[c] - vt_effect_velocity(m, d, c)
                          : d->qfrc[c];
}

/* vt_rate_load, its parts armature q̈, damping q̇ and friction s(q̇) stored into the data's
 * effort_armature, effort_damping and effort_friction as they are formed (the same numbers as
 * vt_joint_effects_store's): for a pass that has the rate at hand */
static inline double vt_rate_load_store(const vt_model *m, vt_data *d, int c)
{
    if (!m->has_effects) return d->qfrc[c];
    const double *e = m->dof_effects + 4 * c, qd = d->qd[c];
    const double arm = e[0] * d->qdd[c], damp = e[1] * qd, fric = e[2] * vt_friction_law(qd, e[3]);
    d->effort_armature[c] = arm;
    d->effort_damping[c] = damp;
    d->effort_friction[c] = fric;
    return d->qfrc[c] - arm - (damp + fric);
}

/* each rate's parts of its effort, armature q̈, damping q̇ and friction s(q̇), into the data's
 * effort_armature, effort_damping and effort_friction (left at 0 without effects) */
void vt_joint_effects_store(const vt_model *m, vt_data *d);

#endif
