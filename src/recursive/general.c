/* The general (factorized) route of the recursive evaluation, and what the other recursive routes
 * take from it: M* by composite bodies, Q by a Newton–Euler pass, (5) solved by vt_solve's routes.
 *
 * Every rate a has a twist s_a = (w_a, v_a) about the reference point O = d->origin (body 1's
 * joint point, near the mechanism; every r below is r − O, d->xrel, kinematics.c): the column of
 * S of every body below it is ṙ = v_a + w_a × r, ṗ = ½ E^T w_a (15)-(16). A wrench (n_O, f) about
 * O pairs with it as power s_a · W = w_a · n_O + v_a · f, so S^T F, summed over a subtree, is the
 * projection of the subtree's wrench (10).
 *
 *   body wrench needed   W_k = (J α + ω × J ω − n_e + r × f,  f = m a − f_e)   about O
 *                        (f_e: gravity and xfrc; n_e: xfrc's moment about the centre of mass;
 *                        kinematics/body.h)
 *   subtree              W̄_i = W_i + Σ_children W̄_c
 *   body inertia         I_k = [J − m c̃ c̃, m c̃; −m c̃, m I]  about O, (m, h = m c, J_O)
 *                        (I s = (J_O w + h × v, m v + w × h)); composite Ī_i = Σ_subtree I_k
 *   M* (3)               M*_ab = s_b · (Ī_i s_a),  i the body of rate a, b on i's path
 *   Q  (4)               Q_a = qfrc_a − s_a · W̄⁰_i   with W̄⁰ from the accelerations at q̈ = 0 (Ṡq̇);
 *                        a base body's own ṗ rates add h's normal part 2 (ω^T J ω) p
 *   W linear in q̈        W_k = W⁰_k + I_k T_k,  T_k = Σ_{a on k's path} s_a q̈_a
 * then Φ_q = Φ_x S from the twists, the augmented system (5) by vt_solve's routes (FREE_RATES,
 * SCHUR, AUGMENTED, REDUNDANT: dense/solve.c), which also diagnose, and the reactions (25)-(28) as
 * in the dense path. This route takes every model (base bodies, couplings, redundant rows) and
 * every instant the shortcuts give up. Its composite inertias and Q stay about O: an instant they
 * cannot vouch for goes to the dense stages (composite_precision, VT_HANDOFF_DENSE).
 * vt_subtree_wrenches_at_joints sums the same W_k about the joint points instead, for the routes
 * above this file (the joint-driven inward pass, the square route).
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "recursive/general.h"
#include "kinematics/joint_effects.h"
#include "base/status.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/body.h"
#include "kinematics/kinematics.h"
#include "numeric/maximal.h"
#include "numeric/skeel.h"
#include "dense/reactions.h"
#include "dense/solve.h"
#include "numeric/roundoff.h"

/* W̄: every subtree's needed wrench about its joint point P_i at the accelerations d->xdd and
 * alpha (3 x (nbody+1)): each body's about its own P_i (c = −s^{ji}), summed leaf first with the
 * short shifts P_i − P_j = s^{ij}_i + t_i − s^{ji}_j, so that no term carries |P − O| (a
 * mechanism far from O keeps its digits; about O the moments hold |P − O| |f| terms that cancel) */
void vt_subtree_wrenches_at_joints(const vt_model *m, const vt_data *d, const double *alpha, double *W)
{
    for (int i = 1; i <= m->nbody; i++) {
        double c[3];
        vt_joint_child(c, m, d, i);
        for (int k = 0; k < 3; k++) c[k] = -c[k];
        vt_body_wrench_global(W + 6 * i, m, d, i, d->xdd + vt_xoff(i), alpha + 3 * i, c);
    }
    vt_sum_at_joints(m, d, W, 0, 3);
}


static double pair(const double w[3], const double v[3], const double W[6])
{
    return vt_dot3(w, W) + vt_dot3(v, W + 3);
}

/* body i's spatial inertia about O (c = r − O) */
static void inertia_O(double I[13], double J[9], const vt_model *m, const vt_data *d, int i)
{
    vt_body_inertia(I, J, m, d, i, d->xrel + 6 * i);
}

/* F = I s for an inertia I in vt_body_inertia's form: (J_O w + h × v, m v + w × h) */
static void inertia_mul(double F[6], const double I[13], const double w[3], const double v[3])
{
    const double *h = I + 1;
    vt_mulmat3(F, I + 4, w);
    vt_addcross3(F, h, v);
    for (int k = 0; k < 3; k++) F[3 + k] = I[0] * v[k];
    vt_addcross3(F + 3, w, h);
}

/* composite inertias about O, summed over subtrees: (m, h = m c, J_O) per body */
static void composite(const vt_model *m, const vt_data *d, double *Ic /* 13 x (nbody+1) */)
{
    double J[9];
    for (int i = 1; i <= m->nbody; i++) inertia_O(Ic + 13 * i, J, m, d, i);
    vt_subtree_sum(m, Ic, 13);
}

/* M* by composite bodies */
static void crba(const vt_model *m, vt_data *d, double *Ic /* 13 x (nbody+1) */)
{
    const int nv = m->nv;
    composite(m, d, Ic);
    memset(d->Mstar, 0, (size_t)nv * (size_t)nv * sizeof(double));
    for (int a = 0; a < nv; a++) {
        const int i = m->dof_body[a];
        const double *w = d->twist + 6 * a;
        double F[6];
        inertia_mul(F, Ic + 13 * i, w, w + 3); /* Ī s_a */
        for (int b = a; b >= 0; b = m->dof_parent[b]) { /* b ≤ a on i's path, down from a (each entry set once) */
            const double *wb = d->twist + 6 * b;
            const double v2 = pair(wb, wb + 3, F);
            d->Mstar[a + (size_t)b * (size_t)nv] = v2;
            d->Mstar[b + (size_t)a * (size_t)nv] = v2;
        }
    }
    if (m->has_effects) /* the joints' armature (kinematics/joint_effects.c) */
        for (int a = 0; a < nv; a++) d->Mstar[a + (size_t)a * (size_t)nv] += m->dof_effects[4 * a];
}

/* body i's needed wrench at q̈ = 0 (the accelerations Ṡq̇, α = 2 E p̈) */
static void bias_wrench(double W[6], const vt_model *m, const vt_data *d, int i)
{
    const int o = vt_xoff(i);
    double al[3];
    vt_mulEp(al, d->x + o + 3, d->Sdqd + o + 3);
    for (int k = 0; k < 3; k++) al[k] *= 2.0;
    vt_body_wrench_global(W, m, d, i, d->Sdqd + o, al, d->xrel + 6 * i);
}

/* Q = qfrc (less the joints' damping and friction) − S^T (needed wrenches at q̈ = 0) */
static void bias(const vt_model *m, vt_data *d, double *W /* 6 x (nbody+1) */)
{
    for (int i = 1; i <= m->nbody; i++) bias_wrench(W + 6 * i, m, d, i);
    vt_subtree_sum(m, W, 6);
    for (int a = 0; a < m->nv; a++) {
        const double *w = d->twist + 6 * a;
        d->Q[a] = vt_rate_force(m, d, a) - pair(w, w + 3, W + 6 * m->dof_body[a]);
    }
    /* a base body's own ṗ rates: (4) in p also has h's normal part, p^T h_p = 2 ω^T J ω (the
     * Newton–Euler form above is its tangential part); p^T p = 1's multiplier takes it up, but
     * Q and λ then equal the dense path's */
    for (int i = 1; i <= m->nbody; i++) {
        if (m->body_joint[i] != VT_JOINT_BASE) continue;
        const double *w = d->omega + 3 * i, *p = d->x + vt_xoff(i) + 3, *A = d->A + 9 * i;
        double wb[3], Jw[3];
        vt_mulmat3t(wb, A, w);
        vt_mulmat3(Jw, m->body_inertia + 9 * i, wb);
        const double c = 2.0 * vt_dot3(wb, Jw);
        for (int k = 0; k < 4; k++) d->Q[m->body_vadr[i] + 3 + k] += c * p[k];
    }
}

/* Why an instant needs M* (the general route), for the refusal on data without it */
static const char *general_reason(const vt_model *m, const vt_data *d)
{
    if (m->joint_mix < 0) return "a base body";
    if (m->ncoupling > 0) return "couplings";
    if (m->allow_redundant) return "redundant rows allowed";
    if (d->fallback & VT_FALLBACK_SQUARE_CONDITION) return "the square route's Φ_q ill-conditioned";
    if (d->fallback & (VT_FALLBACK_ARTICULATED_CONDITION | VT_FALLBACK_ARTICULATED_PIVOT))
        return "the articulated route gave way: an ill-conditioned instant, or a pivot near zero";
    return "a row that is round-off of zero";
}

/* M* by composite bodies and Q by a Newton–Euler pass; refused on data without M* (laid out
 * VT_LAYOUT_RECURSIVE), which the O(n) routes serve */
vt_status vt_mass_and_bias(const vt_model *m, vt_data *d)
{
    if (!d->Mstar)
        return vt_fail(d->message, VT_ERR_LAYOUT,
                       "vt_inverse_dynamics_recursive: this instant needs M* (%s), and the data holds none: its model "
                       "was built with layout VT_LAYOUT_RECURSIVE (VT_LAYOUT_FULL lays it out)",
                       general_reason(m, d));
    const size_t nb = (size_t)m->nbody + 1, mark = vt_scratch_mark(d);
    double *Ic = VT_SCRATCH(d, double, 13 * nb, "composite inertias");
    if (!Ic) return vt_scratch_fail(d, mark);
    crba(m, d, Ic);
    bias(m, d, Ic); /* its 6 (n + 1) wrenches in the same scratch */
    vt_scratch_release(d, mark);
    return VT_OK;
}

/* The composite inertias about o hold m |c|² terms (c from o): M*_aa = s_a · (Ī s_a) carries
 * round-off up to τ ε (T_a + R_a) of the terms it subtracts (vt_rate_terms), so the scaled M*
 * that vt_solve's estimate measures (unit diagonal, the mass metric) is known to δ_a = τ ε (T_a +
 * R_a) / M*_aa in row and column a (an off-diagonal entry to τ ε sqrt(T_a T_b) / sqrt(M*_aa M*_bb)
 * ≤ max δ), and ‖ΔÃ‖_1 ≤ nv max_a δ_a ≤ nv max δ ‖Ã‖_1. The solution's relative error is up to
 * that over rcond: where nv max δ ≥ rcond not one digit is certain (M* may be singular within
 * its own round-off: a mechanism long against its bodies' radii of gyration), this route cannot
 * vouch for its answer, and the instant is computed again by the dense stages, whose S^T M S sums
 * positive terms (kinetic energies, no cancellation: round-off relative to each entry itself) and
 * is judged by vt_solve's own estimate (VT_FALLBACK_COMPOSITE_ROUNDOFF; handed on as
 * VT_HANDOFF_DENSE, as vt_solve_impl does for a rate whose M*_aa is round-off of these terms and
 * that no row fixes). Rates whose M* row vt_solve zeroed (round-off held by a row) are not measured:
 * they are exactly zero. The bound is a worst case: a 100-link chain driven at its tip, 72 m
 * long, meets it (nv max δ = 3.7e-5 against rcond 6.7e-7) while its two paths agree to 3e-9;
 * the articulated route, about each body's joint point, keeps such a chain and does not come
 * here. */
static vt_status composite_precision(const vt_model *m, vt_data *d, vt_handoff *to)
{
    const int nv = m->nv, nc = m->nc;
    const size_t mark = vt_scratch_mark(d);
    double *T = VT_SCRATCH(d, double, 2 * (size_t)nv, "terms of M*'s diagonal");
    double *w = VT_SCRATCH(d, double, 4 * ((size_t)m->nbody + 1), "subtree sums");
    if (!w) return vt_scratch_fail(d, mark);
    vt_rate_terms(m, d, w, T);
    double delta = 0.0;
    for (int a = 0; a < nv; a++) {
        const double maa = d->Mstar[a + (size_t)a * (size_t)nv];
        if (maa > 0.0 && vt_rate_roundoff(T, a) / maa > delta) delta = vt_rate_roundoff(T, a) / maa;
    }
    /* Q's own round-off: Q_a = qfrc_a − s_a · W̄ (bias) sums, body by body, ω_a · (n + c × f) and
     * v_a · f about o, terms that cancel where a load acts near the rate's axis (a force of 7e54 N
     * on a point mass at its spherical joint, 7 m from o: Q's 2.3 N·m lost whole). With the
     * subtree sums of t_f = m (|a| + |g|) + |f_e| and t_n = |n + c × f| + 2 |c| t_f (a the centre's
     * acceleration at q̈ = 0, c = xrel), Q_a is known to u_a = τ ε (|ω_a| t_n + |v_a| t_f +
     * |qfrc_a|), and rate a's equation balances terms of g_a = |Q_a| + Σ_b |M*_ab q̈_b| +
     * Σ_r |Φ_q,ra λ_r|: where nv u_a / g_a reaches rcond this route cannot vouch for its answer
     * either, and the dense stages, which sum S^T F along the tree, decide */
    double *tq = w; /* 2 x (nbody + 1): t_n, t_f */
    tq[0] = tq[1] = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        double W[6];
        bias_wrench(W, m, d, i);
        const double *a = d->Sdqd + vt_xoff(i), *fe = d->xfrc + 6 * i, *c = d->xrel + 6 * i;
        const double tf = m->body_mass[i] * (sqrt(vt_dot3(a, a)) + sqrt(vt_dot3(m->gravity, m->gravity))) +
                          sqrt(vt_dot3(fe, fe));
        tq[2 * i] = sqrt(vt_dot3(W, W)) + 2.0 * sqrt(vt_dot3(c, c)) * tf;
        tq[2 * i + 1] = tf;
    }
    vt_subtree_sum(m, tq, 2);
    const double te = VT_ROUND_TAU * DBL_EPSILON;
    int lost = 0;
    for (int a = 0; a < nv && !lost; a++) {
        const double *tw = d->twist + 6 * a, *t = tq + 2 * m->dof_body[a];
        const double u = te * (sqrt(vt_dot3(tw, tw)) * t[0] + sqrt(vt_dot3(tw + 3, tw + 3)) * t[1] + fabs(vt_rate_force(m, d, a)));
        double g = fabs(d->Q[a]);
        for (int b = 0; b < nv; b++) g += fabs(d->Mstar[a + (size_t)b * (size_t)nv] * d->qdd[b]);
        for (int r = 0; r < nc; r++) g += fabs(d->Phiq[r + (size_t)a * (size_t)nc] * d->lambda[r]);
        lost = u > 0.0 && !(nv * u < d->rcond * g);
    }
    vt_scratch_release(d, mark);
    if (lost || nv * delta >= d->rcond) *to = VT_HANDOFF_DENSE;
    return VT_OK;
}

/* a free-rate route's estimate below √rcond_warn where the maximal-coordinate route is offered
 * (vt_maximal_wanted): the dense stages solve the instant again and decide for both paths (their
 * estimate on M*, the drives' cancellation; maximal.c, solve.c). The two paths' estimates
 * measure the same system but not always alike: a point mass 1e6 m from its joint gave 7.6e-6
 * here and below rcond_warn on M*, where the articulated answer had lost 1.45e-6 and the
 * maximal route's kept 5e-12 (fuzz/findings.md). Over a spread of masses (vt_answer_size), the
 * articulated route, which forms no M*, gives way to the dense stages for their componentwise
 * estimate on (5) (skeel.c), where the data holds M* (VT_LAYOUT_FULL) */
int vt_maximal_instead(const vt_model *m, const vt_data *d, vt_route route, double rcond)
{
    if (route == VT_ROUTE_SQUARE || route == VT_ROUTE_REDUNDANT) return 0;
    return vt_maximal_wanted(m, rcond) || (route == VT_ROUTE_ARTICULATED && d->Mstar && vt_answer_size(m));
}

/* (5) solved by vt_solve on the composite M*: its answer judged by composite_precision against
 * its estimate; its refusal (singular or dependent) is the dense stages' to give. A verdict on the
 * composite M* may be its round-off's: a point mass 1e6 m from o whose exact zero inertia the
 * composite inertias blur into an indefinite pivot, a base body 1e34 m from o whose real inertia
 * they cannot tell from none (its rates zeroed, which composite_precision does not measure).
 * Refusals are rare; the dense stages, about each joint, decide them. */
vt_status vt_composite_solve(const vt_model *m, vt_data *d, vt_handoff *to)
{
    const vt_status st = vt_solve_impl(m, d, to);
    if (st == VT_ERR_SINGULAR || st == VT_ERR_DEPENDENT_CONSTRAINTS) {
        *to = VT_HANDOFF_DENSE;
        return VT_OK;
    }
    if (st || *to) return st;
    const vt_status sp = composite_precision(m, d, to);
    if (!sp && !*to && vt_maximal_instead(m, d, d->route, d->rcond)) *to = VT_HANDOFF_MAXIMAL;
    return sp;
}

/* M* and Q formed, (5) solved by vt_solve (which also diagnoses), the reactions inward:
 * constraints already evaluated */
vt_status vt_factorized_instant(const vt_model *m, vt_data *d, vt_handoff *to)
{
    *to = VT_HANDOFF_NONE;
    vt_status st = vt_mass_and_bias(m, d);
    if (!st) st = vt_composite_solve(m, d, to);
    return st || *to ? st : vt_reactions_impl(m, d, VT_FORM_TWISTS);
}
