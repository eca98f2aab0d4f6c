/* The joints' own efforts on their rates (vt_body_def.armature, damping, friction), which every
 * effort vtdyn returns includes:
 *
 *   τ_c = τ_c^rigid + a_c q̈_c + b_c q̇_c + f_c s(q̇_c),   s = sign (0 at rest) or tanh(q̇ / v)
 *
 * a_c the rotor's inertia seen through its gear (N² J_rotor), b_c viscous damping, f_c Coulomb
 * friction (each N², N², |N| times the motor's values where a gear ratio N is stated). They are
 * the generalized force −(a_c q̈_c + b_c q̇_c + f_c s(q̇_c)) on the rate, applied between the
 * joint's two bodies as qfrc is, with one difference: a_c q̈_c depends on the answer, so that a_c
 * is inertia where q̈ is solved for, added to M*_cc in (2) and to the rate's articulated pivot
 * (D_c = s · I^A s + a_c), while b_c q̇_c + f_c s(q̇_c) is known with the state and joins Q (4).
 * Where a drive fixes the rate the drive's effort takes all three; where none does they are
 * passive: a damped, rubbing, heavy-rotored joint. The reactions do not change: what reaches the
 * joint's bodies along the rate is τ − (a q̈ + b q̇ + f s) = τ^rigid (vt_rate_load). As MuJoCo's
 * armature, damping and frictionloss and Pinocchio's armature, the rotor's gyroscopic coupling
 * with the links is left out.
 */
#include <string.h>

#include "kinematics/joint_effects.h"
#include "model/model.h"

void vt_joint_effects_store(const vt_model *m, vt_data *d)
{
    if (!m->has_effects) return;
    for (int c = 0; c < m->nv; c++) {
        const double *e = m->dof_effects + 4 * c, qd = d->qd[c];
        d->effort_armature[c] = e[0] * d->qdd[c];
        d->effort_damping[c] = e[1] * qd;
        d->effort_friction[c] = e[2] * vt_friction_law(qd, e[3]);
    }
}
