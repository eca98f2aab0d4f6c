/* One instant by the dense reference path, stage after stage: the paper's method as written.
 *
 *   vt_kinematics          x, ẋ, S, Ṡq̇                    (15)-(18)
 *   vt_mass_matrix         M* = S^T M S                     (3)
 *   vt_forces              Q = S^T [F − M Ṡq̇ + h]          (4)
 *   vt_constraints         Φ, Φ_q = Φ_x S, Φ_t, γ           (22), (23)
 *   vt_solve               q̈, λ from the augmented system   (5)
 *   vt_reactions           efforts and joint reactions       (24)-(28)
 * R (vt_inverse_transform) is left out: only (14) needs it. The recursive evaluation of the same
 * instant is src/recursive.c.
 */
#include "internal.h"

vt_status vt_inverse_dynamics(const vt_model *m, vt_data *d)
{
    vt_status st;
    if ((st = vt_kinematics(m, d)) || (st = vt_mass_matrix(m, d)) || (st = vt_forces(m, d)) ||
        (st = vt_constraints(m, d)) || (st = vt_solve(m, d)))
        return st;
    return vt_reactions(m, d);
}
