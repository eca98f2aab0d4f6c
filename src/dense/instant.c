/* One instant by the dense reference path, stage after stage: the paper's method as written.
 *
 *   vt_kinematics          x, ẋ, S, Ṡq̇                    (15)-(18)
 *   vt_mass_matrix         M* = S^T M S                     (3)
 *   vt_forces              Q = S^T [F − M Ṡq̇ + h]          (4)
 *   vt_constraints         Φ, Φ_q = Φ_x S, Φ_t, γ           (22), (23)
 *   vt_solve               q̈, λ from the augmented system   (5)
 *   vt_reactions           efforts and joint reactions       (24)-(28)
 * R (vt_inverse_transform) is left out: only (14) needs it. The recursive evaluation of the same
 * instant is src/recursive/.
 *
 * A motion given through the data for a mechanism with loops or couplings (vt_motion_rows, for
 * vt_inverse_dynamics_motion): the same stages, with each joint drive's row Φ̈ = q̈_k − f'' = 0
 * taking its acceleration from the data instead of its time function, γ = q̈_k(given); the cut
 * joints and couplings give the other rates' q̈, and the drives' multipliers are the efforts.
 * Wrenches at frames (a batch row's loads) join xfrc once the poses are known, for the stages
 * that read it (vt_forces' F, vt_reactions), and xfrc is put back after.
 *
 * Both scan ẍ when the stages are done (accelerations_scanned): vt_reactions forms it from q̈ and
 * checks α and the loads, but the Euler parameters' p̈ enters no load, and q̈ near DBL_MAX (given,
 * or solved for a body of DBL_MIN inertia) overflows it alone (fuzz/corpus/motion-euler-rates-overflow).
 */
#include <stddef.h>
#include <string.h>

#include "dense/instant.h"
#include "kinematics/joint_effects.h"
#include "kinematics/state.h"
#include "base/status.h"
#include "base/arena.h"
#include "base/scan.h"
#include "model/model.h"

/* ẍ after the stages: one scan, then the first body whose ẍ overflows named; the route cleared
 * (no route claims outputs that are not finite) */
static vt_status accelerations_scanned(const vt_model *m, vt_data *d, const char *who)
{
    if (vt_all_finite(d->xdd, m->nx)) return vt_joint_effects_store(m, d), VT_OK;
    d->route = VT_ROUTE_NONE;
    int i = 1;
    while (i < m->nbody && vt_all_finite(d->xdd + vt_xoff(i), 7)) i++;
    return vt_fail(d->message, VT_ERR_NONFINITE, "%s: body %d's acceleration ẍ (a, or the Euler parameters' p̈) overflows",
                   who, i);
}

vt_status vt_inverse_dynamics(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_inverse_dynamics");
    if (st) return st;
    vt_diagnostics_reset(d); /* a stage refusing before vt_solve leaves no earlier call's */
    if ((st = vt_kinematics(m, d)) || (st = vt_mass_matrix(m, d)) || (st = vt_forces(m, d)) ||
        (st = vt_constraints(m, d)) || (st = vt_solve(m, d)) || (st = vt_reactions(m, d)))
        return st;
    return accelerations_scanned(m, d, "vt_inverse_dynamics");
}

vt_status vt_motion_rows(const vt_model *m, vt_data *d, const vt_frame_loads *loads)
{
    if (!d->Mstar)
        return vt_fail(d->message, VT_ERR_LAYOUT,
                       "vt_inverse_dynamics_motion: a loop's or coupling's given motion takes the dense stages, and the "
                       "data holds no S or M*: its model was built with layout VT_LAYOUT_RECURSIVE (VT_LAYOUT_FULL lays "
                       "them out)");
    /* the given q̈ is an input: kept here and put back when a stage fails, since vt_solve
     * writes every rate's q̈ into d->qdd; so is xfrc, which holds the loads while the stages run */
    const int loaded = loads && loads->n > 0;
    const size_t mark = vt_scratch_mark(d), nx = 6 * ((size_t)m->nbody + 1);
    double *given = VT_SCRATCH(d, double, m->nv, "the given q̈");
    double *xfrc = loaded ? VT_SCRATCH(d, double, nx, "xfrc without the loads at frames") : NULL;
    if (!given || (loaded && !xfrc)) return vt_scratch_fail(d, mark);
    memcpy(given, d->qdd, (size_t)m->nv * sizeof(double));
    if (loaded) memcpy(xfrc, d->xfrc, nx * sizeof(double));
    vt_status st;
    if (!(st = vt_kinematics(m, d)) && !(st = loaded ? vt_add_frame_loads(m, d, loads) : VT_OK) &&
        !(st = vt_mass_matrix(m, d)) && !(st = vt_forces(m, d)) && !(st = vt_constraints(m, d))) {
        for (int r = 0; r < m->nc; r++)
            if (m->con_kind[r] == VT_ROW_JOINT) d->gamma[r] = given[m->con_dof[r]];
        if (!(st = vt_solve(m, d)) && !(st = vt_reactions(m, d)))
            st = accelerations_scanned(m, d, "vt_inverse_dynamics_motion");
    }
    if (st) memcpy(d->qdd, given, (size_t)m->nv * sizeof(double));
    if (loaded) memcpy(d->xfrc, xfrc, nx * sizeof(double));
    vt_scratch_release(d, mark);
    return st;
}
