/* The recursive (O(n) and O(n·depth)) evaluation of the same method, without the dense S: the
 * dispatcher vt_inverse_dynamics_recursive, the square route, the positioned entry for Newton's
 * last evaluation, and the scratch bound of the recursive files.
 *
 * The routes (vt_data.route), by the rows the drives and cut joints give:
 * - JOINT_DRIVEN, every rate driven by one joint drive: q̈ = f'' known, nothing factorized,
 *   τ_a = s_a · W̄_i − qfrc_a and the reactions (26) from one inward pass (recursive/fused.c;
 *   without base bodies fused with the kinematics into one outward and one inward loop);
 * - ARTICULATED, fewer rows than rates, no base body: (2) and Φ_q q̈ = γ by articulated bodies
 *   (recursive/articulated.c);
 * - SQUARE, as many rows as rates, no base body (square_instant, here):
 *     q̈ = Φ_q^-1 γ,   Φ_q^T λ = M* q̈ − Q = S^T W̄ − qfrc   (3)-(5)
 *   from one inward pass of the needed wrenches at the full accelerations (kinematics/body.h),
 *   neither M* nor Q formed; only M*'s diagonal, for the solves' scaling:
 *     M*_aa = Σ_k m_k |v_a + w_a × c_k|² + u^T J'_k u,  u = A_k^T w_a,  k below rate a
 *   (twice the kinetic energy of s_a). rcond as vt_solve's square route; below rcond_min the
 *   general route takes over (VT_FALLBACK_SQUARE_CONDITION);
 * - otherwise (base bodies, couplings, redundant rows allowed, or a shortcut that gave way): M*
 *   (3) and Q (4) by composite bodies and (5) by vt_solve's routes (recursive/general.c).
 * The inward passes of every route but the general one take each body's W_k about its own joint
 * point P_k and sum the subtree about P_i, W̄_i = W_i + Σ_c (n_c + (P_c − P_i) × f_c, f_c)
 * (vt_sum_at_joints: P_c − P_i from the joints' own vectors), where s_a is (e, 0) or (0, e): no
 * term carries |P − O|, and a mechanism far from O keeps every digit (about O the moments hold
 * |P − O| |f| terms that cancel at the joints).
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "recursive/recursive.h"
#include "kinematics/joint_effects.h"
#include "recursive/articulated.h"
#include "recursive/fused.h"
#include "recursive/general.h"
#include "base/arena.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "numeric/kkt.h"
#include "numeric/maximal.h"
#include "numeric/rank.h"
#include "numeric/roundoff.h"
#include "numeric/route.h"
#include "dense/constraints.h"
#include "dense/instant.h"
#include "dense/reactions.h"
#include "dense/solve.h"
#include "base/scan.h"

/* who formed α and the joints' total wrenches: nobody (vt_reactions_total forms them after the
 * outputs' scan) or the inward pass (its outputs scanned here); the fused passes
 * (vt_fused_driven) check their own */
typedef enum { FORMED_NONE, FORMED_INWARD } formed_by;

/* M*'s diagonal without the composite inertias: M*_aa = s_a · (Ī_i s_a) is twice the kinetic
 * energy of the bodies k below rate a moving with its twist s_a = (w, v) alone,
 *   M*_aa = Σ_k  m_k |v + w × c_k|² + u^T J'_k u,   u = A_k^T w,
 * summed body by body over each body's path, walked down by dof_parent (each rate takes one term
 * a body, in the order of k whatever the walk's) (no base bodies: their ṗ rates are not twists). */
static void mass_diagonal(const vt_model *m, const vt_data *d, double *diag)
{
    memset(diag, 0, (size_t)m->nv * sizeof(double));
    for (int k = 1; k <= m->nbody; k++) {
        const double *c = d->xrel + 6 * k, *A = d->A + 9 * k, *J = m->body_inertia + 9 * k, mass = m->body_mass[k];
        for (int a = vt_last_rate(m, k); a >= 0; a = m->dof_parent[a]) {
            const double *w = d->twist + 6 * a, *v = w + 3;
            double t[3], u[3], Ju[3];
            vt_copy3(t, v);
            vt_addcross3(t, w, c);
            vt_mulmat3t(u, A, w);
            vt_mulmat3(Ju, J, u);
            diag[a] += mass * vt_dot3(t, t) + vt_dot3(u, Ju);
        }
    }
}

/* Square Φ_q (as many rows as rates, e.g. the crank-driven four-bar): q̈ = Φ_q^-1 γ needs only
 * M*'s diagonal, for the solves' scaling (its condition is kinematic: vt_solve's square route),
 * and the right side of Φ_q^T λ = M* q̈ − Q is S^T W̄ − qfrc with
 * the needed wrenches W at the full accelerations, one inward pass as for joint drives: neither
 * M* nor Q is formed. Where Φ_q is ill-conditioned, the general path diagnoses it.
 * square_factor: the LU of the scaled Φ_q and its condition, from the positions alone (0, 1
 * ill-conditioned, or a negative vt_status), on the arena from its mark, with q̈ where γ is
 * known (b); square_solved: the rest, from γ. */
static int square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *b, double *rcond)
{
    const size_t mark = vt_scratch_mark(d);
    double *mdiag = VT_SCRATCH(d, double, m->nv, "M*'s diagonal");
    if (!mdiag) return vt_scratch_fail(d, mark);
    mass_diagonal(m, d, mdiag);
    return vt_solve_square_factor_with(m, d, sq, mdiag, b, rcond);
}

static vt_status square_solved(const vt_model *m, vt_data *d, vt_square *sq, double rcond)
{
    const int nv = m->nv;
    const size_t nb = (size_t)m->nbody + 1, mark = vt_scratch_mark(d);
    vt_status st = (vt_status)vt_solve_square_accelerations(m, d, sq);
    if (st) return st;
    /* α, then vt_accelerations_add's scratch of 6 (n+1) (free after it: G of the reactions), W̄ */
    double *alpha = VT_SCRATCH(d, double, 15 * nb, "α, twists of q̈ then G, subtree wrenches");
    if (!alpha) return vt_scratch_fail(d, mark);
    double *G = alpha + 3 * nb, *W = alpha + 9 * nb; /* one after the other, as in inward */
    vt_accelerations_add(m, d, sq->x, d->xdd, alpha, G);
    vt_subtree_wrenches_at_joints(m, d, alpha, W);
    for (int a = 0; a < nv; a++) { /* M* q̈ − Q = s_a · W̄_i − qfrc_a, s_a about P_i: (e, 0) or (0, e) */
        const double *s = d->twist + 6 * a, *Wi = W + 6 * m->dof_body[a];
        sq->h[a] = (vt_dof_turns(m, a) ? vt_dot3(s, Wi) : vt_dot3(s + 3, Wi + 3)) - vt_rate_force(m, d, a);
        if (m->has_effects) sq->h[a] += m->dof_effects[4 * a] * sq->x[a]; /* the joint's armature q̈ */
    }
    st = vt_solve_square_end(m, d, sq, rcond);
    if (!st) st = vt_reactions_subtree(m, d, W, G, 0);
    vt_scratch_release(d, mark);
    return st;
}

static vt_status square_instant(const vt_model *m, vt_data *d, vt_handoff *to)
{
    *to = VT_HANDOFF_NONE;
    const size_t mark = vt_scratch_mark(d);
    double rcond = 0.0;
    vt_square sq;
    const int r = square_factor(m, d, &sq, d->gamma, &rcond);
    if (r < 0) return vt_scratch_release(d, mark), (vt_status)r;
    if (r == 1) {
        vt_scratch_release(d, mark);
        d->fallback |= VT_FALLBACK_SQUARE_CONDITION;
        return vt_factorized_instant(m, d, to);
    }
    const vt_status st = square_solved(m, d, &sq, rcond);
    vt_scratch_release(d, mark);
    return st;
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status recursive_instant(const vt_model *m, vt_data *d, formed_by *formed, vt_handoff *to);
static vt_status constrained_instant(const vt_model *m, vt_data *d, vt_handoff *to);
static vt_status outputs_scanned(const vt_model *m, vt_data *d, vt_status st, vt_handoff to, formed_by formed, int totals);

/* every other model's instant: not inlined, so that the fused passes' models reach
 * vt_fused_driven without this one's set-up */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static vt_status routed_instant(const vt_model *m, vt_data *d)
{
    formed_by formed = FORMED_NONE;
    vt_handoff to = VT_HANDOFF_NONE;
    const vt_status st = recursive_instant(m, d, &formed, &to);
    return outputs_scanned(m, d, st, to, formed, 1);
}

vt_status vt_inverse_dynamics_recursive(const vt_model *m, vt_data *d)
{
    /* every rate joint-driven, no base body: the fused passes, whole (the checks of m and d there) */
    if (m && m->joint_driven && m->joint_mix >= 0) return vt_fused_driven(m, d);
    return routed_instant(m, d);
}

/* The instant after it, its outputs scanned: finite inputs whose products overflow (an
 * acceleration of −Inf from loads near DBL_MAX) are refused, not returned with VT_OK. to: what the
 * routes handed on (the dense stages then solve the instant); formed: who formed α and the joints'
 * total wrenches (formed_by); with FORMED_NONE and totals, vt_reactions_total forms them */
static vt_status outputs_scanned(const vt_model *m, vt_data *d, vt_status st, vt_handoff to, formed_by formed, int totals)
{
    if (!st && (to == VT_HANDOFF_DENSE || to == VT_HANDOFF_MAXIMAL)) {
        /* the composite inertias about o cannot vouch for a digit, or the estimate is low enough
         * that the maximal route may be wanted (vt_maximal_instead): the dense stages */
        if (!d->Mstar) {
            d->route = VT_ROUTE_NONE;
            return vt_fail(d->message, VT_ERR_LAYOUT,
                           "vt_inverse_dynamics_recursive: this instant needs the dense stages (%s), and the data "
                           "holds no S or M*: its model was built with layout VT_LAYOUT_RECURSIVE (VT_LAYOUT_FULL "
                           "lays them out)",
                           to == VT_HANDOFF_DENSE ? "the composite inertias cannot vouch for a digit"
                                                  : "an estimate low enough that the maximal route may be wanted");
        }
        const int left = d->fallback | (to == VT_HANDOFF_DENSE ? VT_FALLBACK_COMPOSITE_ROUNDOFF : 0);
        d->message[0] = '\0'; /* a refusal the dense stages decide again is no diagnosis */
        st = vt_inverse_dynamics(m, d);
        d->fallback |= left;
        return st;
    }
    if (st) return st;
    const int nb = 3 * (m->nbody + 1), nd = 3 * m->ndrive, nk = 3 * m->ncut;
    /* the outputs as one scan (vt_finite_scan: one test at the end, not a set-up, remainder and
     * reduction an array; only a failed instant would have stopped earlier) */
    vt_finite_scan fs = {0};
    vt_finite_add(&fs, d->qdd, m->nv);
    vt_finite_add(&fs, d->xdd, m->nx);
    vt_finite_add(&fs, d->qfrc_drive, m->nv);
    vt_finite_add(&fs, d->drive_effort, m->ndrive);
    vt_finite_add(&fs, d->drive_force, nd);
    vt_finite_add(&fs, d->drive_moment, nd);
    vt_finite_add(&fs, d->jnt_force, nb);
    vt_finite_add(&fs, d->jnt_moment, nb);
    vt_finite_add(&fs, d->jnt_force_body, nb);
    vt_finite_add(&fs, d->jnt_moment_body, nb);
    vt_finite_add(&fs, d->cut_force, nk);
    vt_finite_add(&fs, d->cut_moment, nk);
    vt_finite_add(&fs, d->cut_force_body, nk);
    vt_finite_add(&fs, d->cut_moment_body, nk);
    if (formed == FORMED_INWARD) {
        vt_finite_add(&fs, d->alpha, nb);
        vt_finite_add(&fs, d->jnt_force_total, nb);
        vt_finite_add(&fs, d->jnt_moment_total, nb);
        vt_finite_add(&fs, d->jnt_force_total_body, nb);
        vt_finite_add(&fs, d->jnt_moment_total_body, nb);
    }
    if (!vt_finite_ok(&fs)) {
        d->route = VT_ROUTE_NONE;
        return vt_fail(d->message, VT_ERR_NONFINITE,
                       "vt_inverse_dynamics_recursive: the accelerations, efforts or reactions overflow (not finite)");
    }
    if (formed == FORMED_NONE && totals && (st = vt_reactions_total(m, d, 0))) d->route = VT_ROUTE_NONE; /* α and the total wrenches, as the dense path */
    if (!st) vt_joint_effects_store(m, d);
    return st;
}

static inline vt_status recursive_instant(const vt_model *m, vt_data *d, formed_by *formed, vt_handoff *to)
{
    double smax;
    vt_status st = vt_recursive_start(m, d, &smax);
    if (st) return st;
    if ((st = vt_kinematics_tree(m, d, !m->joint_driven))) return st; /* Ṡq̇ only when factorizing */
    if (m->joint_driven) { /* nothing to factorize: always well defined */
        if ((st = vt_drive_accelerations(m, d))) return st;
        /* one unit row per rate: independent, every multiplier and reaction unique */
        vt_solved(m, d, VT_ROUTE_JOINT_DRIVEN, 1.0);
        *formed = m->joint_mix >= 0 ? FORMED_INWARD : FORMED_NONE;
        return vt_inward(m, d, *formed == FORMED_INWARD);
    }
    if (m->joint_rows_only) { /* q̈ of the free rates, then the inward pass */
        memset(d->Phiq, 0, (size_t)m->nc * (size_t)m->nv * sizeof(double)); /* unit rows (R S = I) */
        for (int r = 0; r < m->nc; r++) d->Phiq[r + (size_t)m->con_dof[r] * (size_t)m->nc] = 1.0;
        if ((st = vt_drive_accelerations(m, d))) return st;
        double rcond = 0.0;
        int r = 1;
        if (m->joint_mix >= 0) r = vt_articulated_free_rates(m, d, &rcond); /* by articulated bodies */
        if (r < 0) return (vt_status)r;
        if (r == 0 && vt_maximal_instead(m, d, VT_ROUTE_ARTICULATED, rcond)) {
            d->fallback |= VT_FALLBACK_ARTICULATED_CONDITION;
            *to = VT_HANDOFF_MAXIMAL;
            return VT_OK;
        }
        if (r == 0) vt_solved(m, d, VT_ROUTE_ARTICULATED, rcond);
        else if ((st = vt_mass_and_bias(m, d)) || (st = vt_composite_solve(m, d, to)) || *to ||
                 (st = vt_zeroed_rates_check(m, d, "vt_inverse_dynamics_recursive", VT_FORM_TWISTS))) /* or from M*_FF, which also diagnoses */
            return st;
        *formed = m->joint_mix >= 0 ? FORMED_INWARD : FORMED_NONE;
        return vt_inward(m, d, *formed == FORMED_INWARD);
    }
    if ((st = vt_constraints_impl(m, d, VT_FORM_TWISTS))) return st;
    return constrained_instant(m, d, to);
}

/* no base body (whose ṗ rates carry (4)'s normal part), no redundant rows, no coupling (whose
 * force acts through two rates, not through the rows' wrenches): the square and articulated
 * shortcuts, each falling back to vt_factorized_instant when ill-conditioned */
static int shortcuts(const vt_model *m)
{
    return !m->allow_redundant && m->joint_mix >= 0 && m->ncoupling == 0;
}

/* The instant of a model with rows other than joint drives, its kinematics and constraints
 * evaluated */
static vt_status constrained_instant(const vt_model *m, vt_data *d, vt_handoff *to)
{
    if (shortcuts(m)) {
        if (m->nc == m->nv) return square_instant(m, d, to);
        if (m->nc < m->nv) return vt_articulated_instant(m, d, to);
    }
    return vt_factorized_instant(m, d, to);
}

/* vt_inverse_dynamics_recursive at a state whose positions d already holds, as Newton's last
 * evaluation leaves them (vt_kinematic_solve_impl): vt_kinematics_positions' outputs and the
 * constraints' Φ, Φ_t and Φ_q (vt_constraints_parts with VT_CON_PHIQ, from the twists) at d->q
 * and d->time, q̇ new; fd the drives' functions at d->time (vt_drive_values) or NULL. The
 * velocities, Ṡq̇, Φ_x and γ are computed, then the same routes: the same outputs as
 * vt_inverse_dynamics_recursive, bitwise (α and the joints' total wrenches only with totals).
 * A model whose rows are all joint drives (the fused passes, or the free rates' solve) takes
 * vt_inverse_dynamics_recursive. */
vt_status vt_inverse_dynamics_recursive_positioned(const vt_model *m, vt_data *d, const double *fd, int totals, int rates,
                                                   vt_handoff *to)
{
    const int joints = m->joint_driven || m->joint_rows_only;
    *to = VT_HANDOFF_NONE;
    if (rates && (joints || !shortcuts(m) || m->nc != m->nv)) {
        *to = VT_HANDOFF_RATES;
        return VT_OK;
    }
    if (joints) return vt_inverse_dynamics_recursive(m, d);
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_recursive");
    if (st) return st;
    vt_diagnostics_reset(d);
    if (!vt_all_finite(d->xfrc, 6 * (m->nbody + 1)) || !vt_all_finite(d->qfrc, m->nv))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: NaN or Inf in xfrc or qfrc");
    d->route = VT_ROUTE_NONE;
    d->fallback = 0;
    if (!rates) {
        if (!(st = vt_kinematics_velocities(m, d, 1)) && !(st = vt_constraints_parts(m, d, VT_FORM_TWISTS, VT_CON_PHIX | VT_CON_GAMMA, fd)))
            st = constrained_instant(m, d, to);
        return outputs_scanned(m, d, st, *to, FORMED_NONE, totals);
    }
    /* the square route's LU of Φ_q, from the positions, solves q̇ = −Φ_q^-1 Φ_t before it
     * solves q̈: the instant then runs as square_instant does */
    const size_t mark = vt_scratch_mark(d);
    double rcond = 0.0;
    vt_square sq;
    const int r = square_factor(m, d, &sq, NULL, &rcond);
    if (r) { /* an error, or Φ_q ill-conditioned: the caller solves q̇ and asks again */
        vt_scratch_release(d, mark);
        if (r < 0) return (vt_status)r;
        *to = VT_HANDOFF_RATES;
        return VT_OK;
    }
    if (!(st = (vt_status)vt_square_apply(m, d, &sq, d->Phit, -1.0, d->qd)) && !(st = vt_kinematics_velocities(m, d, 1)) &&
        !(st = vt_constraints_parts(m, d, VT_FORM_TWISTS, VT_CON_PHIX | VT_CON_GAMMA, fd)))
        st = square_solved(m, d, &sq, rcond);
    vt_scratch_release(d, mark);
    return outputs_scanned(m, d, st, VT_HANDOFF_NONE, FORMED_NONE, totals);
}

/* The scratch recursive.c takes at once: the articulated route's work (the largest, with the
 * reactions' arrays), or the square route's (M*'s diagonal and three arrays a body; vt_solve's
 * square state is solve.c's), or the composite inertias. */
size_t vt_recursive_scratch(const vt_model *m)
{
    const size_t nb = (size_t)m->nbody + 1, D = sizeof(double);
    size_t n = m->joint_driven ? 0 : vt_articulated_scratch(m); /* the fused passes need no rows' work */
    const size_t square = VT_SCRATCH_BYTES(m->nv, D) + VT_SCRATCH_BYTES(15 * nb, D);
    if (square > n) n = square;
    if (VT_SCRATCH_BYTES(13 * nb, D) > n) n = VT_SCRATCH_BYTES(13 * nb, D);
    /* composite_precision's terms of M*'s diagonal and subtree sums */
    const size_t terms = VT_SCRATCH_BYTES(2 * (size_t)m->nv, D) + VT_SCRATCH_BYTES(4 * nb, D);
    if (terms > n) n = terms;
    /* vt_motion_rows (instant.c, called from fused.c) holds the given q̈ and xfrc while the
     * stages run */
    const size_t rows = VT_SCRATCH_BYTES(m->nv, D) + VT_SCRATCH_BYTES(6 * nb, D);
    if (rows > n) n = rows;
    return n;
}
