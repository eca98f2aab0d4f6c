/* The recursive (O(n) and O(n·depth)) evaluation of the same method, without the dense S.
 *
 * Every rate a has a twist s_a = (w_a, v_a) about the reference point O = d->origin (body 1's
 * joint point, near the mechanism; every r below is r − O, d->xrel, kinematics.c): the column of
 * S of every body below it is ṙ = v_a + w_a × r, ṗ = ½ E^T w_a (15)-(16). A wrench (n_O, f) about
 * O pairs with it as power s_a · W = w_a · n_O + v_a · f, so S^T F, summed over a subtree, is the
 * projection of the subtree's wrench (10).
 *
 *   body wrench needed   W_k = (J α + ω × J ω − n_e + r × f,  f = m a − f_e)   about O
 *                        (f_e: gravity and xfrc; n_e: xfrc's moment about the centre of mass)
 *   subtree              W̄_i = W_i + Σ_children W̄_c                       (inward pass)
 *   body inertia         I_k = [J − m c̃ c̃, m c̃; −m c̃, m I]  about O, (m, h = m c, J_O)
 *                        (I s = (J_O w + h × v, m v + w × h)); composite Ī_i = Σ_subtree I_k
 *   M* (3)               M*_ab = s_b · (Ī_i s_a),  i the body of rate a, b on i's path
 *   M*_aa alone          Σ_k m_k |v_a + w_a × c_k|² + u^T J'_k u,  u = A_k^T w_a, k below rate a
 *                        (twice the kinetic energy of s_a: the square path's scaling)
 *   Q  (4)               Q_a = qfrc_a − s_a · W̄⁰_i   with W̄⁰ from the accelerations at q̈ = 0 (Ṡq̇);
 *                        a base body's own ṗ rates add h's normal part 2 (ω^T J ω) p
 *   W linear in q̈        W_k = W⁰_k + I_k T_k,  T_k = Σ_{a on k's path} s_a q̈_a
 * The inward passes of every route but the general one take each body's W_k about its own joint
 * point P_k and sum the subtree about P_i, W̄_i = W_i + Σ_c (n_c + (P_c − P_i) × f_c, f_c)
 * (vt_sum_at_joints, shift_to_parent: P_c − P_i from the joints' own vectors), where s_a is
 * (e, 0) or (0, e): no term carries |P − O|, and a mechanism far from O keeps every digit (about
 * O the moments hold |P − O| |f| terms that cancel at the joints). The general route's composite
 * inertias and Q stay about O (an instant they cannot vouch for goes to the dense stages).
 * The routes (vt_data.route), by the rows the drives and cut joints give:
 * - JOINT_DRIVEN, every rate driven by one joint drive (joint_driven): q̈ = f''(t) is known and
 *   nothing is factorized (rcond 1); the efforts are τ_a = s_a · W̄_i − qfrc_a (the paper's
 *   Φ_q^T λ with unit rows, λ = τ), and the reaction at joint i is W̄_i moved to the joint point
 *   P_i less the joint's actuation (τ + qfrc) along its axes, W̄_i at P_i itself being the joint's
 *   total wrench (inward; without base bodies the kinematics fused into the same two passes,
 *   fused_pass, which also store α = ω̇ where they form it);
 * (a free joint's six rates are twists like any other: (0, e_k) and (e_k, P × e_k); no row, no
 * normal part, so the routes below take free bodies, base bodies only the general one)
 * - ARTICULATED, fewer rows than rates, no base body: (2) and Φ_q q̈ = γ by articulated bodies
 *   (articulated_solve: O(n) per right side, M* is not formed; each body's articulated inertia,
 *   bias wrenches and twists about its own joint point P_i, passed to the parent by the short
 *   P_i − P_j, so that round-off grows with the subtrees' extent, not with the distance from O),
 *   then the reactions from W̄ = Σ (W⁰ + I T), which the inward pass's I^A and p give without
 *   the sum and without the rows' loads (articulated_instant). A joint-driven rate's q̈ is known
 *   (f'' = γ): only the free rates are solved and only the other rows enter S; each joint drive's
 *   multiplier follows as s_a · W̄_i − qfrc_a (= (M* q̈ − Q − Φ_q,o^T λ_o)_a), and when every row
 *   is a joint drive (joint_rows_only) the inward pass as above gives them.
 *   rcond is the other rows' S's exact condition at unit diagonal (1 for one row, none without)
 *   times min/max of M*_FF's pivots (the free rates') taken leaf first, each over its diagonal
 *   entry, times the point drives' grip²: the number vt_solve's Schur route reports on the
 *   same system (it takes the driven rates as known too); a
 *   pivot below 1e-8 or round-off of 0 (VT_FALLBACK_ARTICULATED_PIVOT) or rcond below rcond_min
 *   (VT_FALLBACK_ARTICULATED_CONDITION) hands the instant to the general route;
 * - SQUARE, as many rows as rates, no base body: q̈ = Φ_q^-1 γ, then Φ_q^T λ = M* q̈ − Q =
 *   S^T W̄ − qfrc from one inward pass (square_instant: neither M* nor Q is formed); rcond as
 *   vt_solve's square route, and below rcond_min the general route takes over
 *   (VT_FALLBACK_SQUARE_CONDITION);
 * - otherwise (base bodies, couplings, redundant rows allowed, or a shortcut that gave way): M* and Q as
 *   above, Φ_q = Φ_x S from the twists, the augmented system (5) by vt_solve's routes (FREE_RATES,
 *   SCHUR, AUGMENTED, REDUNDANT: src/solve.c), which also diagnose, and the reactions (25)-(28)
 *   as in the dense path.
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "recursive/recursive.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/functions.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "numeric/maximal.h"
#include "dense/constraints.h"
#include "dense/instant.h"
#include "dense/reactions.h"
#include "dense/solve.h"

/* W = body i's needed wrench about the point from which its centre of mass lies at c (O:
 * c = xrel), (n − n_e + c × f, f = m (a − g) − f_e), from n = J α + ω × J ω and the centre of
 * mass's acceleration a; built in locals and written once (W might alias the inputs as far as
 * the compiler knows) */
static inline void needed_wrench_at(double W[6], const vt_model *m, const vt_data *d, int i, double n[3], const double *a,
                                    const double *c)
{
    const double *xf = d->xfrc + 6 * i, mass = m->body_mass[i];
    double f[3];
    for (int k = 0; k < 3; k++) {
        f[k] = mass * (a[k] - m->gravity[k]) - xf[k];
        n[k] -= xf[3 + k];
    }
    vt_addcross3(n, c, f);
    vt_copy3(W, n);
    vt_copy3(W + 3, f);
}

/* W = needed wrench of body i about the point from which its centre of mass lies at c (O: c =
 * xrel), given its accelerations a (3) and α (3) */
static void body_wrench_at(double W[6], const vt_model *m, const vt_data *d, int i, const double *a, const double *al,
                           const double *c)
{
    const double *Ai = d->A + 9 * i, *Jb = m->body_inertia + 9 * i, *w = d->omega + 3 * i;
    double wb[3], ab[3], Jw[3], Ja[3], n[3];
    vt_mulmat3t(wb, Ai, w);
    vt_mulmat3t(ab, Ai, al);
    vt_mulmat3(Jw, Jb, wb);
    vt_mulmat3(Ja, Jb, ab);
    vt_addcross3(Ja, wb, Jw);
    vt_mulmat3(n, Ai, Ja); /* J α + ω × J ω, body axes and back */
    needed_wrench_at(W, m, d, i, n, a, c);
}

/* W = needed wrench of body i about O, given its accelerations a (3) and α (3) */
static void body_wrench(double W[6], const vt_model *m, const vt_data *d, int i, const double *a, const double *al)
{
    body_wrench_at(W, m, d, i, a, al, d->xrel + 6 * i);
}

/* W̄: every subtree's needed wrench about its joint point P_i at the accelerations d->xdd and
 * alpha (3 x (nbody+1)): each body's about its own P_i (c = −s^{ji}), summed leaf first with the
 * short shifts P_i − P_j = s^{ij}_i + t_i − s^{ji}_j, so that no term carries |P − O| (a
 * mechanism far from O keeps its digits; about O the moments hold |P − O| |f| terms that cancel) */
static void subtree_wrenches_at_joints(const vt_model *m, const vt_data *d, const double *alpha, double *W)
{
    for (int i = 1; i <= m->nbody; i++) {
        double c[3];
        vt_joint_child(c, m, d, i);
        for (int k = 0; k < 3; k++) c[k] = -c[k];
        body_wrench_at(W + 6 * i, m, d, i, d->xdd + vt_xoff(i), alpha + 3 * i, c);
    }
    vt_sum_at_joints(m, d, W, 0, 3);
}


static double pair(const double w[3], const double v[3], const double W[6])
{
    return vt_dot3(w, W) + vt_dot3(v, W + 3);
}

/* body i's spatial inertia about the point from which its centre of mass lies at c, in 13 numbers:
 * (m, h = m c, J_O = J − m c̃ c̃), and J = A J' A^T (global axes, about the centre of mass) into J */
static void inertia_at(double I[13], double J[9], const vt_model *m, const vt_data *d, int i, const double c[3])
{
    double t[9];
    const double mass = m->body_mass[i], *A = d->A + 9 * i, *Jb = m->body_inertia + 9 * i;
    for (int col = 0; col < 3; col++) vt_mulmat3(t + 3 * col, Jb, (double[3]){A[col], A[col + 3], A[col + 6]});
    double u[6]; /* A t, symmetric: its upper triangle */
    for (int col = 0, k = 0; col < 3; col++)
        for (int r = 0; r <= col; r++, k++) u[k] = A[r] * t[3 * col] + A[r + 3] * t[1 + 3 * col] + A[r + 6] * t[2 + 3 * col];
    J[0] = u[0], J[1] = J[3] = u[1], J[4] = u[2], J[2] = J[6] = u[3], J[5] = J[7] = u[4], J[8] = u[5];
    const double h0 = mass * c[0], h1 = mass * c[1], h2 = mass * c[2];
    const double o0 = h1 * c[1] + h2 * c[2], o1 = h0 * c[0] + h2 * c[2], o2 = h0 * c[0] + h1 * c[1];
    I[0] = mass, I[1] = h0, I[2] = h1, I[3] = h2; /* J_O = J + m (|c|² 1 − c c^T) */
    I[4] = u[0] + o0, I[5] = I[7] = u[1] - h0 * c[1], I[8] = u[2] + o1;
    I[6] = I[10] = u[3] - h0 * c[2], I[9] = I[11] = u[4] - h1 * c[2], I[12] = u[5] + o2;
}

/* body i's spatial inertia about O (c = r − O) */
static void inertia_O(double I[13], double J[9], const vt_model *m, const vt_data *d, int i)
{
    inertia_at(I, J, m, d, i, d->xrel + 6 * i);
}

/* inertia_at, and body i's needed wrench at q̈ = 0 from the same global J (bias_wrench's, without
 * its turns to body axes): W⁰ = (J α + ω × J ω − n_e + c × f, f = m (a − g) − f_e) about the
 * point from which the centre of mass lies at c, at the accelerations Ṡq̇ (α = 2 E p̈) */
static void inertia_bias(double I[13], double W[6], const vt_model *m, const vt_data *d, int i, const double c[3])
{
    const int o = vt_xoff(i);
    const double *w = d->omega + 3 * i, *a = d->Sdqd + o;
    double J[9], al[3], Jw[3], n[3];
    inertia_at(I, J, m, d, i, c);
    vt_mulEp(al, d->x + o + 3, a + 3);
    for (int k = 0; k < 3; k++) al[k] *= 2.0;
    vt_mulmat3(n, J, al);
    vt_mulmat3(Jw, J, w);
    vt_addcross3(n, w, Jw);
    needed_wrench_at(W, m, d, i, n, a, c);
}

/* F = I s for an inertia I in inertia_O's form: (J_O w + h × v, m v + w × h) */
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
        const int *path = m->path_dof + m->body_pathadr[i];
        for (int k = 0; k < m->body_pathnum[i]; k++) {
            const int b = path[k];
            if (b > a) break; /* ascending: the rest are later rates of i's own joint */
            const double *wb = d->twist + 6 * b;
            const double v2 = pair(wb, wb + 3, F);
            d->Mstar[a + (size_t)b * (size_t)nv] = v2;
            d->Mstar[b + (size_t)a * (size_t)nv] = v2;
        }
    }
}

/* body i's needed wrench at q̈ = 0 (the accelerations Ṡq̇, α = 2 E p̈) */
static void bias_wrench(double W[6], const vt_model *m, const vt_data *d, int i)
{
    const int o = vt_xoff(i);
    double al[3];
    vt_mulEp(al, d->x + o + 3, d->Sdqd + o + 3);
    for (int k = 0; k < 3; k++) al[k] *= 2.0;
    body_wrench(W, m, d, i, d->Sdqd + o, al);
}

/* Q = qfrc − S^T (needed wrenches at q̈ = 0) */
static void bias(const vt_model *m, vt_data *d, double *W /* 6 x (nbody+1) */)
{
    for (int i = 1; i <= m->nbody; i++) bias_wrench(W + 6 * i, m, d, i);
    vt_subtree_sum(m, W, 6);
    for (int a = 0; a < m->nv; a++) {
        const double *w = d->twist + 6 * a;
        d->Q[a] = d->qfrc[a] - pair(w, w + 3, W + 6 * m->dof_body[a]);
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

/* Every rate driven by a joint drive: q̈ = f'', efforts and reactions in one inward pass. */
/* the driven rates' prescribed q̈ = f'' (and their rows' Φ, Φ_t, γ) */
static vt_status drive_accelerations(const vt_model *m, vt_data *d)
{
    /* the arrays in locals: the time function's call would have them all read again per rate */
    const int nv = m->nv, *dof_drive = m->dof_drive, *drive_row = m->drive_row, *dof_body = m->dof_body;
    const int *qadr = m->body_qadr, *vadr = m->body_vadr;
    const vt_drive_def *drive = m->drive;
    const double t = d->time, *q = d->q;
    double *Phi = d->Phi, *Phit = d->Phit, *gamma = d->gamma, *qdd = d->qdd;
    for (int c = 0; c < nv; c++) {
        const int k = dof_drive[c];
        if (k < 0) continue;
        const int row = drive_row[k];
        double f[3];
        vt_status st = vt_function_eval_valid(f, &drive[k].f, t);
        if (st)
            return vt_fail(d->message, st, "vt_inverse_dynamics_recursive: drive %d: time function failed at t = %g", k,
                           d->time);
        const int i = dof_body[c];
        Phi[row] = q[qadr[i] + c - vadr[i]] - f[0];
        Phit[row] = -f[1];
        gamma[row] = f[2];
        qdd[c] = f[2];
    }
    return VT_OK;
}

/* joint i's efforts and reaction from its subtree's wrench Wi (about o): inward_pass's step for one
 * body; 1 if the reaction overflowed. With totals, also the joint's total wrench (reaction plus
 * actuation): W̄_i itself, its moment about P_i, before the actuation is taken off; d->jnt_force_total
 * is then the reaction's force but for a free joint, whose reaction is zeroed. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline int joint_reaction(const vt_model *m, vt_data *d, const double *Wi, int i, const int given,
                                 const int totals)
{
    const double *e = d->jaxis + 9 * i;
    double f[3], mo[3]; /* locals, stored once: the outputs might alias the inputs; W̄_i about P_i */
    vt_copy3(f, Wi + 3);
    vt_copy3(mo, Wi);
    if (totals) {
        double tb[3];
        vt_mulmat3t(tb, d->A + 9 * i, f);
        vt_copy3(d->jnt_force_total + 3 * i, f);
        vt_copy3(d->jnt_force_total_body + 3 * i, tb);
        vt_mulmat3t(tb, d->A + 9 * i, mo);
        vt_copy3(d->jnt_moment_total + 3 * i, mo);
        vt_copy3(d->jnt_moment_total_body + 3 * i, tb);
    }
    for (int k = 0; k < m->body_nv[i]; k++) {
        const int c = m->body_vadr[i] + k, dr = m->dof_drive[c];
        int ax;
        const int rot = vt_dof_kind(m->body_joint[i], k, &ax) == VT_DOF_ROT;
        double tau = 0.0;
        if (given || dr >= 0) { /* the rate's twist paired with W̄_i about P_i, where a turning
                                 * rate's twist is (w, 0) and a sliding one's (0, v) */
            const double *w = d->twist + 6 * c;
            tau = (rot || vt_dof_turns(m, c) ? vt_dot3(w, Wi) : vt_dot3(w + 3, Wi + 3)) - d->qfrc[c];
        }
        if (!given && dr >= 0) {
            d->lambda[m->drive_row[dr]] = tau;
            d->drive_effort[dr] = tau;
            double *df = d->drive_force + 3 * dr, *dm = d->drive_moment + 3 * dr;
            for (int r = 0; r < 3; r++) {
                df[r] = rot ? 0.0 : tau * e[3 * ax + r];
                dm[r] = rot ? tau * e[3 * ax + r] : 0.0;
            }
        }
        d->qfrc_drive[c] = tau;
        vt_axpy3(rot ? mo : f, -(tau + d->qfrc[c]), e + 3 * ax); /* actuation is not reaction */
    }
    if (m->body_joint[i] == VT_JOINT_FREE) /* transmits nothing: what is left is round-off */
        f[0] = f[1] = f[2] = mo[0] = mo[1] = mo[2] = 0.0;
    double fb[3], mb[3];
    vt_mulmat3t(fb, d->A + 9 * i, f);
    vt_mulmat3t(mb, d->A + 9 * i, mo);
    vt_copy3(d->jnt_force + 3 * i, f);
    vt_copy3(d->jnt_moment + 3 * i, mo);
    vt_copy3(d->jnt_force_body + 3 * i, fb);
    vt_copy3(d->jnt_moment_body + 3 * i, mb);
    return !vt_all_finite(f, 3) || !vt_all_finite(mo, 3);
}

/* with q̈ known for every rate: one inward pass for the joint drives' efforts τ = s · W̄ − qfrc
 * and every reaction (actuation — a drive's τ and an applied qfrc — is not reaction) */
/* given: the motion is given for every rate: every rate's effort, the drives left alone; else
 * the joint drives' efforts. Inlined, so that each use is compiled for its constant (the branch
 * in the loop cost 2.5 % on the chain). The trees without base bodies take the fused passes
 * below (fused_pass); this one follows the articulated solve of the free rates. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status inward_pass(const vt_model *m, vt_data *d, const int given, const int totals)
{
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1, mark = vt_scratch_mark(d);
    double *W = VT_SCRATCH(d, double, 6 * nb, "subtree wrenches");
    if (!W) return vt_scratch_fail(d, mark);
    vt_accelerations(m, d, d->qdd, d->xdd, d->alpha);
    subtree_wrenches_at_joints(m, d, d->alpha, W);
    for (int i = 1; i <= n; i++)
        if (totals ? joint_reaction(m, d, W + 6 * i, i, given, 1) : joint_reaction(m, d, W + 6 * i, i, given, 0))
            return vt_scratch_release(d, mark),
                   vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: joint %d's reaction overflowed", i);
    vt_scratch_release(d, mark);
    if (totals) { /* the ground's rows */
        memset(d->jnt_force_total, 0, 3 * sizeof(double));
        memset(d->jnt_moment_total, 0, 3 * sizeof(double));
        memset(d->jnt_force_total_body, 0, 3 * sizeof(double));
        memset(d->jnt_moment_total_body, 0, 3 * sizeof(double));
    }
    return vt_reactions_unique(m, d);
}

/* The fused passes: a tree without base bodies, every q̈ known (every rate joint-driven, or the
 * motion given): the kinematics, the accelerations and each body's needed wrench in one outward
 * loop over the bodies, the subtree wrenches, efforts and reactions in one inward loop; the same
 * equations as vt_kinematics_tree, vt_accelerations, body_wrench and inward_pass. A revolute body
 * has its own code, written for one rotational rate (e = A^j u, its twist (e, (P − o) × e),
 * t = 0, ė = ω^j × e, τ = e · the moment about P), a translational one its own code both ways
 * (fused_slide, fused_slide_inward); any other joint takes the general code's stages for the
 * body. */
static const double zero3[3] = {0, 0, 0}, unit_quat[4] = {1, 0, 0, 0};

/* fused_outward's body on a translational joint (vt_kinematics_body, vt_acceleration_body and
 * body_wrench_at for one sliding rate, written out): the body keeps its reference body's
 * orientation (p = p^j ⊗ p0), e = A^j u, t = q e, its twist (0, e); ω = ω^j,
 * v = v^j + ω^j × s^{ij} + q̇ e + ω × d^i (d^i = t − s^{ji}); α = α^j,
 * a = a^j + α^j × s^{ij} + ω^j × (ω^j × s^{ij}) + q̈ e + 2 q̇ ω^j × e + q (α^j × e + ω^j × (ω^j × e))
 *     − α × s^{ji} − ω × (ω × s^{ji});
 * its needed wrench about P_i. A gripper's fingers, a linear axis: the robot stays on the
 * fused passes' own code instead of the general stages' loops over kinds and rates. Not inlined:
 * in the revolute loop's body it cost the chain 5–11 % (bench/ab/run.sh), its code laid out anew. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_slide(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, int i)
{
    double *o = d->origin;
    const int j = m->body_parent[i], c = m->body_vadr[i];
    const double q = d->q[m->body_qadr[i]], qd = d->qd[c], qdd = d->qdd[c];
    const double *u = m->body_axis + 6 * i, *Aj = d->A + 9 * j, *p0 = m->body_quat0 + 4 * i;
    double p[4], A[9], e[3], sij[3], sji[3], t[3];
    memcpy(p, j ? d->x + vt_xoff(j) + 3 : unit_quat, sizeof p);
    if (!vt_quat_is_identity(p0)) vt_quat_mul_inline(p, p, p0);
    vt_euler_A_inline(A, p);
    vt_mulmat3(e, Aj, u);
    for (int k = 0; k < 3; k++) t[k] = q * e[k];
    vt_mulmat3(sij, Aj, m->body_jpar + 3 * i);
    vt_mulmat3(sji, A, m->body_jchild + 3 * i);
    if (i == 1) { /* o = P_1 */
        for (int k = 0; k < 3; k++) o[k] = sij[k] + t[k];
        for (int k = 0; k < 6; k++) d->xrel[k] = -o[k % 3];
    }
    const double *rjp = d->xrel + 6 * j, *wjp = d->omega + 3 * j, *aljp = alpha + 3 * j;
    const double *vjp = j ? d->xd + vt_xoff(j) : zero3, *ajp = j ? d->xdd + vt_xoff(j) : zero3;
    double rj[3], wj[3], alj[3], vj[3], aj[3];
    for (int k = 0; k < 3; k++) rj[k] = rjp[k], wj[k] = wjp[k], alj[k] = aljp[k], vj[k] = vjp[k], aj[k] = ajp[k];
    double di[3], v[3], a[3], ed[3], edd[3], tt[3], pd[4], pdd[4];
    double *x = d->x + vt_xoff(i), *ej = d->jaxis + 9 * i, *twc = d->twist + 6 * c;
    for (int k = 0; k < 3; k++) { /* positions from o (r^i − o from P_i − o, as position()) */
        const double b = rj[k] + sij[k], Pr = b + t[k], rr = Pr - sji[k];
        di[k] = t[k] - sji[k];
        x[k] = o[k] + rr;
        d->jpoint[3 * i + k] = o[k] + Pr;
        d->xrel[6 * i + k] = rr;
        d->xrel[6 * i + 3 + k] = Pr;
        d->jsij[3 * i + k] = sij[k];
        d->jd[3 * i + k] = di[k];
        ej[k] = e[k]; /* ej's rows 3–8 hold the zeros data_init set: one axis, on every path */
        twc[k] = 0.0;
        twc[3 + k] = e[k];
    }
    memcpy(x + 3, p, sizeof p);
    memcpy(d->A + 9 * i, A, sizeof A);
    /* velocities: ω = ω^j */
    vt_copy3(v, vj);
    vt_addcross3(v, wj, sij);
    vt_axpy3(v, qd, e);
    vt_addcross3(v, wj, di);
    vt_quat_rate(pd, p, wj);
    double *xd = d->xd + vt_xoff(i);
    vt_copy3(d->omega + 3 * i, wj);
    vt_copy3(xd, v);
    memcpy(xd + 3, pd, sizeof pd);
    /* accelerations: α = α^j */
    vt_copy3(a, aj);
    vt_addcross3(a, alj, sij);
    vt_cross3(tt, wj, sij);
    vt_addcross3(a, wj, tt);
    vt_cross3(ed, wj, e);
    vt_cross3(edd, alj, e);
    vt_addcross3(edd, wj, ed);
    vt_axpy3(a, qdd, e);
    vt_axpy3(a, 2.0 * qd, ed);
    vt_axpy3(a, q, edd);
    vt_cross3(tt, alj, sji);
    for (int k = 0; k < 3; k++) a[k] -= tt[k];
    vt_cross3(tt, wj, sji);
    vt_cross3(ed, wj, tt);
    for (int k = 0; k < 3; k++) a[k] -= ed[k];
    vt_quat_rate(pdd, p, alj);
    const double w2 = vt_dot3(wj, wj);
    for (int k = 0; k < 4; k++) pdd[k] -= 0.25 * w2 * p[k];
    double *xdd = d->xdd + vt_xoff(i);
    vt_copy3(alpha + 3 * i, alj);
    vt_copy3(xdd, a);
    memcpy(xdd + 3, pdd, sizeof pdd);
    for (int k = 0; k < 3; k++) sji[k] = -sji[k]; /* about P_i: r^i − P_i = −s^{ji} */
    body_wrench_at(W + 6 * i, m, d, i, a, alj, sji);
}

/* the outward pass: d's kinematic outputs, d->xdd, α and every body's needed wrench W (about o) */
/* small: every |q| ≤ 2^15, so every half angle is vt_sincos_small's (no call in the loop); compiled
 * once for each (fused_outward, fused_outward_any) */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void fused_outward_impl(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W,
                                      const int mixed, const int small)
{
    double *o = d->origin;
    o[0] = o[1] = o[2] = 0.0;
    memset(d->xrel, 0, 6 * sizeof(double));
    alpha[0] = alpha[1] = alpha[2] = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        if (mixed && m->body_joint[i] == VT_JOINT_TRANSLATIONAL) {
            fused_slide(m, d, alpha, W, i);
            continue;
        }
        if (mixed && m->body_joint[i] != VT_JOINT_REVOLUTE) { /* the general code's stages for this body */
            double c[3]; /* about the joint point: c = r^i − P_i = −s^{ji} */
            vt_kinematics_body(m, d, i);
            vt_acceleration_body(m, d, d->qdd, d->xdd, alpha, i);
            vt_joint_child(c, m, d, i);
            for (int k = 0; k < 3; k++) c[k] = -c[k];
            body_wrench_at(W + 6 * i, m, d, i, d->xdd + vt_xoff(i), alpha + 3 * i, c);
            continue;
        }
        const int j = m->body_parent[i], c = m->body_vadr[i];
        const double q = d->q[m->body_qadr[i]], qd = d->qd[c], qdd = d->qdd[c];
        const double *u = m->body_axis + 6 * i, *Aj = d->A + 9 * j;
        const double *pj = j ? d->x + vt_xoff(j) + 3 : unit_quat;
        double p[4], A[9], e[3], sij[3], sji[3];
        { /* p = p^j ⊗ (cos ½q, sin ½q u) written out, (c p0 − s p·u, c p + s p0 u + s p × u): no
           * calls with the vectors live */
            double cs, sn;
            if (small) vt_sincos_small(0.5 * q, &sn, &cs);
            else vt_sincos(0.5 * q, &sn, &cs);
            const double a0 = pj[0], a1 = pj[1], a2 = pj[2], a3 = pj[3];
            p[0] = cs * a0 - sn * (a1 * u[0] + a2 * u[1] + a3 * u[2]);
            p[1] = cs * a1 + sn * (a0 * u[0] + a2 * u[2] - a3 * u[1]);
            p[2] = cs * a2 + sn * (a0 * u[1] + a3 * u[0] - a1 * u[2]);
            p[3] = cs * a3 + sn * (a0 * u[2] + a1 * u[1] - a2 * u[0]);
        }
        const double *p0 = m->body_quat0 + 4 * i;
        if (!vt_quat_is_identity(p0)) vt_quat_mul_inline(p, p, p0);
        vt_euler_A_inline(A, p);
        vt_mulmat3(e, Aj, u);
        vt_mulmat3(sij, Aj, m->body_jpar + 3 * i);
        vt_mulmat3(sji, A, m->body_jchild + 3 * i);
        if (i == 1) { /* o = P_1 */
            vt_copy3(o, sij);
            for (int k = 0; k < 6; k++) d->xrel[k] = -o[k % 3];
        }
        /* the reference body's values in locals before the first store (the outputs might alias
         * them as far as the compiler knows); each output stored as soon as it is known, so that
         * fewer values stay live (spilled) to the end */
        const double *rjp = d->xrel + 6 * j, *wjp = d->omega + 3 * j, *aljp = alpha + 3 * j;
        const double *vjp = j ? d->xd + vt_xoff(j) : zero3, *ajp = j ? d->xdd + vt_xoff(j) : zero3;
        double rj[3], wj[3], alj[3], vj[3], aj[3];
        for (int k = 0; k < 3; k++) {
            rj[k] = rjp[k];
            wj[k] = wjp[k];
            alj[k] = aljp[k];
            vj[k] = vjp[k];
            aj[k] = ajp[k];
        }
        double rr[3], di[3], w[3], al[3], a[3], t[3], ed[3], wb[3], ab[3];
        { /* positions from o, the rate's twist */
            double Pr[3], tw[3];
            for (int k = 0; k < 3; k++) {
                Pr[k] = rj[k] + sij[k];
                rr[k] = Pr[k] - sji[k];
                di[k] = 0.0 - sji[k];
            }
            vt_cross3(tw, Pr, e);
            double *x = d->x + vt_xoff(i), *ej = d->jaxis + 9 * i, *twc = d->twist + 6 * c;
            for (int k = 0; k < 3; k++) {
                x[k] = o[k] + rr[k];
                d->jpoint[3 * i + k] = o[k] + Pr[k];
                d->xrel[6 * i + k] = rr[k];
                d->xrel[6 * i + 3 + k] = Pr[k];
                d->jsij[3 * i + k] = sij[k];
                d->jd[3 * i + k] = di[k];
                ej[k] = e[k]; /* ej's rows 3–8 hold the zeros data_init set: one axis, on every path */
                twc[k] = e[k];
                twc[3 + k] = tw[k];
            }
            memcpy(x + 3, p, sizeof p);
            memcpy(d->A + 9 * i, A, sizeof A);
        }
        { /* velocities */
            double v[3], pd[4];
            for (int k = 0; k < 3; k++) {
                w[k] = wj[k] + qd * e[k];
                v[k] = vj[k];
            }
            vt_addcross3(v, wj, sij);
            vt_addcross3(v, w, di);
            vt_quat_rate(pd, p, w);
            vt_mulmat3t(wb, A, w); /* ω in body axes for the wrench */
            double *xd = d->xd + vt_xoff(i);
            vt_copy3(d->omega + 3 * i, w);
            vt_copy3(xd, v);
            memcpy(xd + 3, pd, sizeof pd);
        }
        { /* accelerations */
            double pdd[4];
            vt_copy3(al, alj);
            vt_copy3(a, aj);
            vt_addcross3(a, alj, sij);
            vt_cross3(t, wj, sij);
            vt_addcross3(a, wj, t);
            vt_cross3(ed, wj, e);
            vt_axpy3(al, qdd, e);
            vt_axpy3(al, qd, ed);
            vt_cross3(ed, al, sji);
            for (int k = 0; k < 3; k++) a[k] -= ed[k];
            vt_cross3(t, w, sji);
            vt_cross3(ed, w, t);
            for (int k = 0; k < 3; k++) a[k] -= ed[k];
            vt_quat_rate(pdd, p, al);
            vt_mulmat3t(ab, A, al); /* α in body axes for the wrench */
            const double w2 = vt_dot3(w, w);
            for (int k = 0; k < 4; k++) pdd[k] -= 0.25 * w2 * p[k];
            double *xdd = d->xdd + vt_xoff(i);
            vt_copy3(alpha + 3 * i, al);
            vt_copy3(xdd, a);
            memcpy(xdd + 3, pdd, sizeof pdd);
        }
        { /* the needed wrench (body_wrench) */
            const double *Jb = m->body_inertia + 9 * i, *xf = d->xfrc + 6 * i, mass = m->body_mass[i];
            double Jw[3], Ja[3], nn[3], f[3];
            vt_mulmat3(Jw, Jb, wb);
            vt_mulmat3(Ja, Jb, ab);
            vt_addcross3(Ja, wb, Jw);
            vt_mulmat3(nn, A, Ja);
            for (int k = 0; k < 3; k++) {
                f[k] = mass * (a[k] - m->gravity[k]) - xf[k];
                nn[k] -= xf[3 + k];
            }
            vt_addcross3(nn, f, sji); /* about P_i: (r^i − P_i) × f = f × s^{ji} */
            double *Wi = W + 6 * i;
            vt_copy3(Wi, nn);
            vt_copy3(Wi + 3, f);
        }
    }
}

#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_outward(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, const int mixed)
{
    fused_outward_impl(m, d, alpha, W, mixed, 1);
}
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_outward_any(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, const int mixed)
{
    fused_outward_impl(m, d, alpha, W, mixed, 0);
}

/* The fused passes' results checked at once after both loops (a scan of whole arrays costs less
 * than checks joint by joint in the inward loop): ẍ, α, the efforts, the reactions and the total
 * wrenches. Copies are not scanned twice: λ and drive_effort hold qfrc_drive's τ, a revolute
 * joint's drive force is zero and its total force is its reaction's (f, stored twice); q̈ is the
 * drives' f'' (checked by vt_function_eval_valid) or the given one (checked on entry). The given
 * motion (vt_inverse_dynamics_motion) scans what it always did, the reactions and the totals, in
 * which an overflow of ẍ or τ shows (W̄ sums every body's wrench below the joint). A failure names
 * the first joint from the tree's ends, as a check in the inward loop would. */
static vt_status fused_check(const vt_model *m, vt_data *d, const int given, const int mixed)
{
    const int n = m->nbody, nb3 = 3 * (n + 1), nd = 3 * m->ndrive;
    vt_finite_scan s = {0};
    vt_finite_add(&s, d->alpha, nb3);
    vt_finite_add(&s, d->jnt_force, nb3);
    vt_finite_add(&s, d->jnt_moment, nb3);
    vt_finite_add(&s, d->jnt_force_body, nb3);
    vt_finite_add(&s, d->jnt_moment_total, nb3);
    vt_finite_add(&s, d->jnt_moment_total_body, nb3);
    if (mixed) {
        vt_finite_add(&s, d->jnt_force_total, nb3);
        vt_finite_add(&s, d->jnt_force_total_body, nb3);
    }
    if (!given) { /* the driver's scan */
        vt_finite_add(&s, d->xdd, m->nx);
        vt_finite_add(&s, d->qfrc_drive, m->nv);
        vt_finite_add(&s, d->jnt_moment_body, nb3);
        vt_finite_add(&s, d->drive_moment, nd);
        if (mixed) vt_finite_add(&s, d->drive_force, nd);
    }
    if (vt_finite_ok(&s)) return VT_OK;
    d->route = VT_ROUTE_NONE;
    for (int i = n; i >= 1; i--) {
        if (!vt_all_finite(d->jnt_force + 3 * i, 3) || !vt_all_finite(d->jnt_moment + 3 * i, 3) ||
            !vt_all_finite(d->jnt_force_body + 3 * i, 3) || !vt_all_finite(d->jnt_moment_body + 3 * i, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: joint %d's reaction overflowed", i);
        if (!vt_all_finite(d->jnt_force_total + 3 * i, 3) || !vt_all_finite(d->jnt_moment_total + 3 * i, 3) ||
            !vt_all_finite(d->jnt_force_total_body + 3 * i, 3) || !vt_all_finite(d->jnt_moment_total_body + 3 * i, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "joint %d's total wrench (reaction and actuation) overflows", i);
    }
    for (int i = 1; i <= n; i++)
        if (!vt_all_finite(d->alpha + 3 * i, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "body %d's angular acceleration overflows", i);
    return vt_fail(d->message, VT_ERR_NONFINITE,
                   "vt_inverse_dynamics_recursive: the accelerations, efforts or reactions overflow (not finite)");
}

/* W̄_j += W̄_i moved from P_i to P_j by the short P_i − P_j = s^{ij}_i + t_i − s^{ji}_j */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void shift_to_parent(const vt_model *m, const vt_data *d, double *W, int i, int j)
{
    double r[3];
    vt_joint_shift(r, m, d, i, j);
    const double *Wi = W + 6 * i;
    double *Wj = W + 6 * j;
    vt_addcross3(Wj, r, Wi + 3);
    for (int k = 0; k < 6; k++) Wj[k] += Wi[k];
}

/* fused_pass's inward step on a translational joint (joint_reaction and shift_to_parent for one
 * sliding rate, written out): its twist (0, e) paired with W̄_i gives τ = e · f − qfrc, the
 * reaction is W̄_i less the actuation (τ + qfrc) e along the axis, its whole moment kept. Not
 * inlined, as fused_slide. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_slide_inward(const vt_model *m, vt_data *d, double *W, int i, const int given)
{
    const int c = m->body_vadr[i], dr = m->dof_drive[c], j = m->body_parent[i];
    const double *Wi = W + 6 * i, *e = d->jaxis + 9 * i, *A = d->A + 9 * i, qf = d->qfrc[c];
    double f[3], mo[3], fb[3], mb[3]; /* locals, stored once: the outputs might alias the inputs */
    vt_copy3(f, Wi + 3);
    vt_copy3(mo, Wi);
    vt_mulmat3t(fb, A, f);
    vt_mulmat3t(mb, A, mo);
    vt_copy3(d->jnt_force_total + 3 * i, f); /* the total: W̄_i about P_i, actuation included */
    vt_copy3(d->jnt_moment_total + 3 * i, mo);
    vt_copy3(d->jnt_force_total_body + 3 * i, fb);
    vt_copy3(d->jnt_moment_total_body + 3 * i, mb);
    double tau = 0.0;
    if (given || dr >= 0) tau = vt_dot3(e, f) - qf;
    if (!given && dr >= 0) {
        d->lambda[m->drive_row[dr]] = tau;
        d->drive_effort[dr] = tau;
        double *df = d->drive_force + 3 * dr, *dm = d->drive_moment + 3 * dr;
        for (int k = 0; k < 3; k++) {
            df[k] = tau * e[k];
            dm[k] = 0.0;
        }
    }
    d->qfrc_drive[c] = tau;
    vt_axpy3(f, -(tau + qf), e); /* actuation is not reaction */
    vt_mulmat3t(fb, A, f);
    vt_copy3(d->jnt_force + 3 * i, f);
    vt_copy3(d->jnt_moment + 3 * i, mo);
    vt_copy3(d->jnt_force_body + 3 * i, fb);
    vt_copy3(d->jnt_moment_body + 3 * i, mb);
    if (j > 0) shift_to_parent(m, d, W, i, j);
}

/* the joint-driven (given = 0) or given (1) instant of a tree without base bodies: inward_pass's
 * outputs, and vt_kinematics_tree's (without Ṡq̇); bounded: fused_bounded holds, the outputs need
 * no scan */
static inline vt_status fused_pass(const vt_model *m, vt_data *d, const int given, const int mixed, const int bounded,
                                   const int small)
{
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1, mark = vt_scratch_mark(d);
    double *W = VT_SCRATCH(d, double, 6 * nb, "subtree wrenches");
    if (!W) return vt_scratch_fail(d, mark);
    if (small) fused_outward(m, d, d->alpha, W, mixed);
    else fused_outward_any(m, d, d->alpha, W, mixed);
    vt_status st = bounded ? VT_OK : vt_kinematics_check_outputs(m, d);
    if (st) { /* as vt_kinematics_tree's failure before any route */
        d->route = VT_ROUTE_NONE;
        return vt_scratch_release(d, mark), st;
    }
    for (int i = n; i >= 1; i--) { /* leaf first: W_i is its subtree's when its turn comes */
        const int c = m->body_vadr[i], dr = m->dof_drive[c], j = m->body_parent[i];
        if (mixed && m->body_joint[i] == VT_JOINT_TRANSLATIONAL) {
            fused_slide_inward(m, d, W, i, given);
            continue;
        }
        if (mixed && m->body_joint[i] != VT_JOINT_REVOLUTE) {
            (void)joint_reaction(m, d, W + 6 * i, i, given, 1); /* checked with the rest: fused_check */
            if (j > 0) shift_to_parent(m, d, W, i, j);
            continue;
        }
        const double *Wi = W + 6 * i, *e = d->jaxis + 9 * i;
        double f[3], Wn[3], mo[3]; /* locals, stored once: the outputs might alias the inputs */
        vt_copy3(f, Wi + 3);
        vt_copy3(Wn, Wi);
        vt_copy3(mo, Wn); /* W̄_i is about P_i */
        const double qf = d->qfrc[c];
        double tau = 0.0;
        if (given || dr >= 0) tau = vt_dot3(e, mo) - qf; /* s · W̄ = e · (the moment about P_i) */
        if (!given && dr >= 0) {
            d->lambda[m->drive_row[dr]] = tau;
            d->drive_effort[dr] = tau;
            double *df = d->drive_force + 3 * dr, *dm = d->drive_moment + 3 * dr;
            for (int k = 0; k < 3; k++) {
                df[k] = 0.0;
                dm[k] = tau * e[k];
            }
        }
        d->qfrc_drive[c] = tau;
        double fb[3], mb[3];
        vt_mulmat3t(fb, d->A + 9 * i, f);
        vt_mulmat3t(mb, d->A + 9 * i, mo);
        vt_copy3(d->jnt_force_total + 3 * i, f); /* the total: W̄_i about P_i, actuation included */
        vt_copy3(d->jnt_moment_total + 3 * i, mo);
        vt_copy3(d->jnt_force_total_body + 3 * i, fb);
        vt_copy3(d->jnt_moment_total_body + 3 * i, mb);
        vt_axpy3(mo, -(tau + qf), e); /* actuation is not reaction */
        vt_mulmat3t(mb, d->A + 9 * i, mo);
        vt_copy3(d->jnt_force + 3 * i, f);
        vt_copy3(d->jnt_moment + 3 * i, mo);
        vt_copy3(d->jnt_force_body + 3 * i, fb);
        vt_copy3(d->jnt_moment_body + 3 * i, mb);
        if (j > 0) { /* W̄_j += W̄_i moved to P_j: P_i − P_j = s^{ij}_i − s^{ji}_j (no translation at i) */
            double r[3];
            if (mixed) {
                double sj[3];
                vt_joint_child(sj, m, d, j);
                for (int k = 0; k < 3; k++) r[k] = d->jsij[3 * i + k] - sj[k];
            } else { /* j revolute: −s^{ji}_j = d^j */
                for (int k = 0; k < 3; k++) r[k] = d->jsij[3 * i + k] + d->jd[3 * j + k];
            }
            double *Wj = W + 6 * j;
            vt_addcross3(Wj, r, f);
            for (int k = 0; k < 3; k++) {
                Wj[k] += Wn[k];
                Wj[3 + k] += f[k];
            }
        }
    }
    vt_scratch_release(d, mark);
    memset(d->jnt_force_total, 0, 3 * sizeof(double)); /* the ground's rows (α's: fused_outward) */
    memset(d->jnt_moment_total, 0, 3 * sizeof(double));
    memset(d->jnt_force_total_body, 0, 3 * sizeof(double));
    memset(d->jnt_moment_total_body, 0, 3 * sizeof(double));
    if (!bounded && (st = fused_check(m, d, given, mixed))) return st;
    return vt_reactions_unique(m, d);
}

/* the inward pass after q̈ is known; without base bodies it also forms the total wrenches, W̄_i
 * about P_i (a base body's rates act at its centre of mass and through p: vt_reactions_total) */
static vt_status inward(const vt_model *m, vt_data *d, int totals)
{
    return inward_pass(m, d, 0, totals);
}

/* M* by composite bodies and Q by a Newton–Euler pass */
static vt_status mass_and_bias(const vt_model *m, vt_data *d)
{
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
 * is judged by vt_solve's own estimate (VT_FALLBACK_COMPOSITE_ROUNDOFF; returned as
 * VT_NEEDS_DENSE, as vt_solve_impl does for a rate whose M*_aa is round-off of these terms and
 * that no row fixes). Rates whose M* row vt_solve zeroed (round-off held by a row) are not measured:
 * they are exactly zero. The bound is a worst case: a 100-link chain driven at its tip, 72 m
 * long, meets it (nv max δ = 3.7e-5 against rcond 6.7e-7) while its two paths agree to 3e-9;
 * the articulated route, about each body's joint point, keeps such a chain and does not come
 * here. */
static vt_status composite_precision(const vt_model *m, vt_data *d)
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
        const double u = te * (sqrt(vt_dot3(tw, tw)) * t[0] + sqrt(vt_dot3(tw + 3, tw + 3)) * t[1] + fabs(d->qfrc[a]));
        double g = fabs(d->Q[a]);
        for (int b = 0; b < nv; b++) g += fabs(d->Mstar[a + (size_t)b * (size_t)nv] * d->qdd[b]);
        for (int r = 0; r < nc; r++) g += fabs(d->Phiq[r + (size_t)a * (size_t)nc] * d->lambda[r]);
        lost = u > 0.0 && !(nv * u < d->rcond * g);
    }
    vt_scratch_release(d, mark);
    return lost || nv * delta >= d->rcond ? VT_NEEDS_DENSE : VT_OK;
}

/* a free-rate route's estimate below √rcond_warn where the maximal-coordinate route is offered
 * (vt_maximal_wanted): the dense stages solve the instant again and decide for both paths (their
 * estimate on M*, the drives' cancellation; maximal.c, solve.c). The two paths' estimates
 * measure the same system but not always alike: a point mass 1e6 m from its joint gave 7.6e-6
 * here and below rcond_warn on M*, where the articulated answer had lost 1.45e-6 and the
 * maximal route's kept 5e-12 (fuzz/findings.md) */
static int maximal_instead(const vt_model *m, vt_route route, double rcond)
{
    return route != VT_ROUTE_SQUARE && route != VT_ROUTE_REDUNDANT && vt_maximal_wanted(m, rcond);
}

/* (5) solved by vt_solve on the composite M*: its answer judged by composite_precision against
 * its estimate; its refusal (singular or dependent) is the dense stages' to give. A verdict on the
 * composite M* may be its round-off's: a point mass 1e6 m from o whose exact zero inertia the
 * composite inertias blur into an indefinite pivot, a base body 1e34 m from o whose real inertia
 * they cannot tell from none (its rates zeroed, which composite_precision does not measure).
 * Refusals are rare; the dense stages, about each joint, decide them. */
static vt_status composite_solve(const vt_model *m, vt_data *d)
{
    const vt_status st = vt_solve_impl(m, d);
    if (st == VT_ERR_SINGULAR || st == VT_ERR_DEPENDENT_CONSTRAINTS) return VT_NEEDS_DENSE;
    const vt_status sp = st ? st : composite_precision(m, d);
    return !sp && maximal_instead(m, d->route, d->rcond) ? VT_NEEDS_MAXIMAL : sp;
}

/* M* and Q formed, (5) solved by vt_solve (which also diagnoses), the reactions inward:
 * constraints already evaluated */
static vt_status factorized_instant(const vt_model *m, vt_data *d)
{
    vt_status st = mass_and_bias(m, d);
    if (!st) st = composite_solve(m, d);
    return st ? st : vt_reactions_impl(m, d, 0);
}

/* M*'s diagonal without the composite inertias: M*_aa = s_a · (Ī_i s_a) is twice the kinetic
 * energy of the bodies k below rate a moving with its twist s_a = (w, v) alone,
 *   M*_aa = Σ_k  m_k |v + w × c_k|² + u^T J'_k u,   u = A_k^T w,
 * summed body by body over each body's path (no base bodies: their ṗ rates are not twists). */
static void mass_diagonal(const vt_model *m, const vt_data *d, double *diag)
{
    memset(diag, 0, (size_t)m->nv * sizeof(double));
    for (int k = 1; k <= m->nbody; k++) {
        const double *c = d->xrel + 6 * k, *A = d->A + 9 * k, *J = m->body_inertia + 9 * k, mass = m->body_mass[k];
        const int *path = m->path_dof + m->body_pathadr[k];
        for (int p = 0; p < m->body_pathnum[k]; p++) {
            const double *w = d->twist + 6 * path[p], *v = w + 3;
            double t[3], u[3], Ju[3];
            vt_copy3(t, v);
            vt_addcross3(t, w, c);
            vt_mulmat3t(u, A, w);
            vt_mulmat3(Ju, J, u);
            diag[path[p]] += mass * vt_dot3(t, t) + vt_dot3(u, Ju);
        }
    }
}

/* Square Φ_q (as many rows as rates, e.g. the crank-driven four-bar): q̈ = Φ_q^-1 γ needs only
 * M*'s diagonal, for the solves' scaling (its condition is kinematic: vt_solve's square route),
 * and the right side of Φ_q^T λ = M* q̈ − Q is S^T W̄ − qfrc with
 * the needed wrenches W at the full accelerations, one inward pass as for joint drives: neither
 * M* nor Q is formed. Where Φ_q is ill-conditioned, the general path diagnoses it.
 * square_factor: the LU of the scaled Φ_q and its condition, from the positions alone (0, 1
 * ill-conditioned, or a negative vt_status), on the arena from its mark; square_solved: the rest,
 * from γ. */
static int square_factor(const vt_model *m, vt_data *d, vt_square *sq, double *rcond)
{
    const size_t mark = vt_scratch_mark(d);
    double *mdiag = VT_SCRATCH(d, double, m->nv, "M*'s diagonal");
    if (!mdiag) return vt_scratch_fail(d, mark);
    mass_diagonal(m, d, mdiag);
    return vt_solve_square_factor(m, d, sq, mdiag, rcond);
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
    subtree_wrenches_at_joints(m, d, alpha, W);
    for (int a = 0; a < nv; a++) { /* M* q̈ − Q = s_a · W̄_i − qfrc_a, s_a about P_i: (e, 0) or (0, e) */
        const double *s = d->twist + 6 * a, *Wi = W + 6 * m->dof_body[a];
        sq->h[a] = (vt_dof_turns(m, a) ? vt_dot3(s, Wi) : vt_dot3(s + 3, Wi + 3)) - d->qfrc[a];
    }
    st = vt_solve_square_end(m, d, sq, rcond);
    if (!st) st = vt_reactions_subtree(m, d, W, G, 0);
    vt_scratch_release(d, mark);
    return st;
}

static vt_status square_instant(const vt_model *m, vt_data *d)
{
    const size_t mark = vt_scratch_mark(d);
    double rcond = 0.0;
    vt_square sq;
    const int r = square_factor(m, d, &sq, &rcond);
    if (r < 0) return vt_scratch_release(d, mark), (vt_status)r;
    if (r == 1) {
        vt_scratch_release(d, mark);
        d->fallback |= VT_FALLBACK_SQUARE_CONDITION;
        return factorized_instant(m, d);
    }
    const vt_status st = square_solved(m, d, &sq, rcond);
    vt_scratch_release(d, mark);
    return st;
}

/* G = body inertia I (inertia_O's form) as a full 6x6, columns of 8 (the last two zero, so that
 * a column is two 4-wide vectors), acting on (w, v): [J_O  h̃; h̃^T  m 1] with h̃ v = h × v */
static inline void column8(double *restrict g, double a, double b, double c, double d, double e, double f)
{
    g[0] = a, g[1] = b, g[2] = c, g[3] = d, g[4] = e, g[5] = f, g[6] = 0.0, g[7] = 0.0;
}

static void inertia_full(double *restrict G, const double *restrict I)
{
    const double *h = I + 1, *J = I + 4, m = I[0];
    column8(G, J[0], J[1], J[2], 0.0, -h[2], h[1]); /* written whole: no zeroing pass */
    column8(G + 8, J[3], J[4], J[5], h[2], 0.0, -h[0]);
    column8(G + 16, J[6], J[7], J[8], -h[1], h[0], 0.0);
    column8(G + 24, 0.0, h[2], -h[1], m, 0.0, 0.0);
    column8(G + 32, -h[2], 0.0, h[0], 0.0, m, 0.0);
    column8(G + 40, h[1], -h[0], 0.0, 0.0, 0.0, m);
}

/* Kernels of the articulated-body passes: I^A in columns of 8 (two 4-wide vectors, which the
 * compiler uses), sums as balanced pairs (shorter dependency chains; C keeps the order written). */

/* G −= U U^T / D (inv = 1 / D), G 6x6 in columns of 8. Rows outer, so that the row loop is
 * vectorized a column at a time (columns outer invites vectorizing across columns, with
 * shuffles) */
static inline void rank1_cols8(double *restrict G, const double *restrict U, double inv)
{
    for (int r = 0; r < 8; r++) {
        const double v = U[r] * inv;
        for (int c = 0; c < 6; c++) G[r + 8 * c] -= v * U[c];
    }
}

/* U = G s, G 6x6 in columns of 8 */
static inline void mul_cols8(double *restrict U, const double *restrict G, const double *restrict s)
{
    for (int r = 0; r < 8; r++)
        U[r] = (G[r] * s[0] + G[r + 8] * s[1]) + (G[r + 16] * s[2] + G[r + 24] * s[3]) +
               (G[r + 32] * s[4] + G[r + 40] * s[5]);
}

static double dot6(const double *a, const double *b)
{
    return (a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3]) + (a[4] * b[4] + a[5] * b[5]);
}

/* The shifts of Featherstone's articulated-body algorithm between joint points, global axes
 * (only the reference point moves), r = P_i − P_j from the parent's joint point to the child's:
 * a motion (α, a) about P_j is (α, a + α × r) about P_i; a wrench (n, f) about P_i is
 * (n + r × f, f) about P_j; an inertia G about P_i is X^T G X about P_j, X = [1 0; −r̃ 1] the
 * motion shift (r̃ x = r × x). With G = [A B; C D] (rows n, f; columns w, v; B = C^T, D = D^T):
 *   E = D r̃,  C' = C − E,  B' = C'^T,  D' = D,
 *   A' = A − B r̃ + r̃ C' = A + r̃ C + (r̃ C)^T − r̃ E = A + T + T^T,  T = r̃ (C − ½ E)
 * (r̃ E = r̃ D r̃ is symmetric; a point mass m at P_i: A' = −m r̃ r̃, B' = m r̃, its inertia about
 * P_j). Row k of E is D_k × r (D_k row k of D), column k of T is r × (C − ½ E)^k. */
static inline void shift_inertia_add(double *restrict Gj, const double *restrict G, const double r[3])
{
    double E[9], T[9]; /* column-major */
    for (int k = 0; k < 3; k++) {
        const double Dk[3] = {G[3 + k + 24], G[3 + k + 32], G[3 + k + 40]};
        double x[3];
        vt_cross3(x, Dk, r);
        E[k] = x[0], E[k + 3] = x[1], E[k + 6] = x[2];
    }
    for (int c = 0; c < 3; c++) {
        const double h[3] = {G[3 + 8 * c] - 0.5 * E[3 * c], G[4 + 8 * c] - 0.5 * E[1 + 3 * c], G[5 + 8 * c] - 0.5 * E[2 + 3 * c]};
        vt_cross3(T + 3 * c, r, h);
    }
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++) {
            const double cp = G[3 + k + 8 * c] - E[k + 3 * c];
            Gj[k + 8 * c] += G[k + 8 * c] + (T[k + 3 * c] + T[c + 3 * k]);
            Gj[3 + k + 8 * c] += cp;
            Gj[c + 8 * (3 + k)] += cp;
            Gj[3 + k + 8 * (3 + c)] += G[3 + k + 8 * (3 + c)];
        }
}

/* a composite inertia (m, h, J) about P_i (13 numbers, inertia_at's form) added about P_j:
 * h' = h + m r, J' = J + 2 (g · r) 1 − (g r^T + r g^T) with g = h + ½ m r
 * (= J + 2 (h · r) 1 − (h r^T + r h^T) + m (|r|² 1 − r r^T)) */
static inline void shift_composite_add(double *restrict Ij, const double *restrict I, const double r[3])
{
    const double mass = I[0], *h = I + 1, *J = I + 4;
    const double g0 = h[0] + 0.5 * mass * r[0], g1 = h[1] + 0.5 * mass * r[1], g2 = h[2] + 0.5 * mass * r[2];
    const double a0 = g0 * r[0], a1 = g1 * r[1], a2 = g2 * r[2];
    const double j01 = J[3] - (g0 * r[1] + r[0] * g1), j02 = J[6] - (g0 * r[2] + r[0] * g2),
                 j12 = J[7] - (g1 * r[2] + r[1] * g2);
    Ij[0] += mass;
    for (int k = 0; k < 3; k++) Ij[1 + k] += h[k] + mass * r[k];
    Ij[4] += J[0] + 2.0 * (a1 + a2);
    Ij[8] += J[4] + 2.0 * (a0 + a2);
    Ij[12] += J[8] + 2.0 * (a0 + a1);
    Ij[5] += j01, Ij[7] += j01;
    Ij[6] += j02, Ij[10] += j02;
    Ij[9] += j12, Ij[11] += j12;
}

/* the articulated route's lever arms, each short whatever the distance from o (6 x (nbody+1)):
 * body i's centre of mass from its joint point, c_i = r_i − P_i = −s^{ji} = −A_i s'^{ji}, and its
 * joint point from its reference body's: P_i = r_j + s^{ij} + t_i and P_j = r_j − c_j give
 * r_i = P_i − P_j = s^{ij} + t_i + c_j = s^{ij} + d^i − c_i + c_j (t_i the joint's translation,
 * d^i = t_i − s^{ji}, (17)); 0 for a root, whose reference is the ground */
static void lever_arms(const vt_model *m, const vt_data *d, double *L)
{
    for (int i = 1; i <= m->nbody; i++) {
        const int j = m->body_parent[i];
        double *c = L + 6 * i, *r = c + 3, s[3];
        vt_mulmat3(s, d->A + 9 * i, m->body_jchild + 3 * i);
        for (int k = 0; k < 3; k++) c[k] = -s[k];
        if (j > 0)
            for (int k = 0; k < 3; k++) r[k] = d->jsij[3 * i + k] + d->jd[3 * i + k] + s[k] + L[6 * j + k];
        else
            r[0] = r[1] = r[2] = 0.0;
    }
}

/* rate a's twist about its own body's joint point: (e, 0) for a rotation about an axis through
 * it, (0, e) for a translation (no base body here); *off the place of e in (w, v), 0 or 3 */
static inline void twist_at_joint(double e[3], int *off, const vt_model *m, const vt_data *d, int i, int a)
{
    int ax;
    const int rot = vt_dof_kind(m->body_joint[i], a - m->body_vadr[i], &ax) == VT_DOF_ROT;
    *off = rot ? 0 : 3;
    vt_copy3(e, d->twist + 6 * a + *off);
}

/* articulated_solve's work on the arena, nr right sides: per body I^A (48, columns of 8), Ī (13),
 * p and A (6 nr each); per rate U (8), 1 / D, u and x (nr each); S (nc x nc) and λ; the rows'
 * wrenches (12 nc); then the reactions' T (6), W̄ (6) and G (6, first the lever arms) per body.
 * Each array starts on
 * a cache line (the 8-wide columns' loads stay within one). */
typedef struct {
    double *IA, *Ic, *P, *A, *U, *Dinv, *u, *X, *S, *lam, *rw, *T, *W, *G;
    int *rows; /* the rows that are right sides, S's order (schur_rows) */
} aba_work;

/* takes the work for nr right sides; 0 or VT_ERR_NO_MEMORY (the caller releases) */
static int aba_take(const vt_model *m, vt_data *d, int nr, aba_work *w)
{
    const size_t nb = (size_t)m->nbody + 1, nv = (size_t)m->nv, nc = (size_t)nr - 1, sr = 6 * (size_t)nr;
    w->IA = VT_SCRATCH(d, double, 48 * nb, "articulated inertias");
    w->Ic = VT_SCRATCH(d, double, 13 * nb, "composite inertias");
    w->P = VT_SCRATCH(d, double, sr * nb, "articulated bias wrenches");
    w->A = VT_SCRATCH(d, double, sr * nb, "spatial accelerations");
    w->U = VT_SCRATCH(d, double, 8 * nv, "U");
    w->Dinv = VT_SCRATCH(d, double, nv, "1 / D");
    w->u = VT_SCRATCH(d, double, (size_t)nr * nv, "u");
    w->X = VT_SCRATCH(d, double, nv * (size_t)nr, "solutions");
    w->S = VT_SCRATCH(d, double, nc * nc, "Schur complement");
    w->lam = VT_SCRATCH(d, double, nc, "λ");
    w->rw = VT_SCRATCH(d, double, 12 * (size_t)m->nc, "rows' wrenches");
    w->T = VT_SCRATCH(d, double, 6 * nb, "twists of q̈");
    w->W = VT_SCRATCH(d, double, 6 * nb, "subtree wrenches");
    w->G = VT_SCRATCH(d, double, 6 * nb, "G");
    w->rows = VT_SCRATCH(d, int, (size_t)m->nc, "the rows of S");
    return vt_scratch_ok(d) ? 0 : VT_ERR_NO_MEMORY;
}

/* what aba_take takes for nr right sides */
static size_t aba_bytes(const vt_model *m, int nr)
{
    const size_t nb = (size_t)m->nbody + 1, nv = (size_t)m->nv, nc = (size_t)nr - 1, sr = 6 * (size_t)nr;
    const size_t D = sizeof(double);
    return VT_SCRATCH_BYTES(48 * nb, D) + VT_SCRATCH_BYTES(13 * nb, D) + 2 * VT_SCRATCH_BYTES(sr * nb, D) +
           VT_SCRATCH_BYTES(8 * nv, D) + VT_SCRATCH_BYTES(nv, D) + 2 * VT_SCRATCH_BYTES((size_t)nr * nv, D) +
           VT_SCRATCH_BYTES(nc * nc, D) + VT_SCRATCH_BYTES(nc, D) + VT_SCRATCH_BYTES(12 * (size_t)m->nc, D) +
           3 * VT_SCRATCH_BYTES(6 * nb, D) + VT_SCRATCH_BYTES((size_t)m->nc, sizeof(int));
}

/* the rows that stay in the Schur system (every row but the known joint drives) into rows (or
 * only counted with NULL); their count */
static int schur_rows(const vt_model *m, int *rows)
{
    int k = 0;
    for (int r = 0; r < m->nc; r++)
        if (!vt_known_row(m, r)) {
            if (rows) rows[k] = r;
            k++;
        }
    return k;
}

/* Fewer independent rows than rates, no base body: (5) by articulated bodies, without M*.
 * Featherstone's articulated-body recursion, each rate of a multi-rate joint a massless link of
 * its own, solves M* x = b for several right sides b at once. Every body's quantities are taken
 * about its own joint point P_i (global axes), so that each holds the terms of its own subtree's
 * extent, not of the distance from O: a rate's twist about P_i is (e, 0) or (0, e) (its axis
 * passes through P_i), the body's inertia I_i about P_i (c_i = r_i − P_i), and the articulated
 * inertia, bias wrenches and accelerations pass between a body and its parent by the short
 * r_i = P_i − P_j (shift_inertia_add; lever_arms):
 *   inward, body i's rates last first, I^A starting as i's inertia about P_i plus what its
 *   children pass, p as i's b-wrench plus theirs:
 *     U_a = I^A s_a,  D_a = s_a · U_a,  u_a = b_a − s_a · p,
 *     I^A ← I^A − U_a U_a^T / D_a,  p ← p + U_a u_a / D_a
 *   then to the parent:  I^A_j += X^T I^A X,  p_j += (n + r_i × f, f)
 *   outward, A the spatial acceleration about P_i, from the parent's (α, a + α × r_i):
 *     x_a = (u_a − U_a · A) / D_a,  A ← A + s_a x_a
 * For b = Q (4) p starts as the bodies' needed wrenches W⁰ at q̈ = 0 and b_a = qfrc_a, since
 * Q_a = qfrc_a − s_a · W̄⁰ (the pairing of a twist and a wrench is the same about any point);
 * for b = Φ_q^T e_r = S^T Φ_x^T e_r, the row's own wrench w_r on its bodies (vt_row_wrenches at
 * λ_r = 1) is an applied load: p starts at −w_r there and b_a = 0, since Σ_{k below a} s_a · w_r,k
 * = (Φ_q^T e_r)_a (10); so the I^A T + p that give the reactions come without the rows' loads.
 * With q̈ = x⁰ + X λ (2), the rows Φ_q q̈ = γ give S λ = γ − Φ_q x⁰, S = Φ_q X = Φ_q M*^-1 Φ_q^T,
 * the Schur complement of vt_solve's Schur path, whose S̃ = R S R has the same unit-diagonal
 * form. The D_a are M*'s pivots taken leaf first (rates in descending order); the reported
 * condition is S's at unit diagonal times min/max of D_a / M*_aa (those pivots of M* scaled to
 * unit diagonal, each in (0, 1]; M*_aa = s_a · Ī s_a by composite inertias about P_i) times the
 * point drives' grip², the number the Schur path computes from its leaf-first Cholesky pivots:
 * both fall where a motion loses its inertia. A D_a that is round-off of 0 (below VT_ROUND_TAU ε
 * of the subtree's terms about P_i it is a difference of) is no pivot: the general route decides.
 * A rate with a joint drive (drv, its only one: vt_known_row) has its q̈ known, f'' = γ of the
 * drive's row, and that row is no right side: such a rate articulates nothing,
 *   inward  p ← p + U_a q̈_a for Q (0 for a row's side; I^A unchanged),   outward  A ← A + s_a q̈_a,
 * the others are the free rates, M*_FF's pivots and the other rows' S = Φ_oF M*_FF^-1 Φ_oF^T
 * give the condition (π over the free rates alone: a light link driven beside a heavy one
 * weighs nothing in it), and the drives' λ come after from the subtrees' wrenches
 * (articulated_instant; with only joint-drive rows the inward pass).
 * articulated_solve_nr: nr right sides (1 + the rows in w->rows), drv the rates' joint drives or NULL.
 * Fills q̈ (and the other rows' λ), and leaves the lever arms in w->G; returns 0, 1 (a scaled pivot
 * below 1e-8, or rcond below rcond_min: the factorized instant decides and diagnoses) or a
 * negative vt_status. */
#define PIVOT_MIN 1e-8
static inline int articulated_solve_nr(const vt_model *m, vt_data *d, const aba_work *w, double *rcond_out,
                                       const int *drv, const int nr)
{
    const int n = m->nbody, nv = m->nv, nc = nr - 1, ncall = m->nc, *rows = w->rows;
    const size_t sr = 6 * (size_t)nr;
    double *Ic = w->Ic, *IA = w->IA, *P = w->P, *Aw = w->A, *U = w->U, *Dinv = w->Dinv, *u = w->u, *X = w->X,
           *S = w->S, *lam = w->lam, *L = w->G;
    lever_arms(m, d, L);
    for (int i = 1; i <= n; i++) { /* p⁰ = W⁰, I^A = Ī = I_i, about P_i (the children's added below) */
        double *p = P + sr * (size_t)i;
        for (int k = 6; k < 6 * nr; k++) p[k] = 0.0; /* the rows' sides */
        inertia_bias(Ic + 13 * i, p, m, d, i, L + 6 * i);
        inertia_full(IA + 48 * i, Ic + 13 * i);
    }
    if (nc > 0) { /* p^r: the row's wrench for λ_r = 1 on its bodies, about P_b, as an applied load */
        double *rw = w->rw;
        vt_row_wrenches(rw, m, d, NULL);
        for (int k = 0; k < nc; k++)
            for (int side = 0; side < 2; side++) {
                const int r = rows[k], b = m->con_body[2 * r + side];
                if (b == 0) continue;
                const double *f = rw + 12 * r + 6 * side, *n0 = f + 3;
                double *p = P + sr * (size_t)b + 6 * (size_t)(k + 1), t[3];
                vt_cross3(t, L + 6 * b, f); /* about the centre of mass → about P_b */
                for (int c = 0; c < 3; c++) {
                    p[c] -= n0[c] + t[c];
                    p[3 + c] -= f[c];
                }
            }
    }
    double pmin = 1.0, pmax = 0.0, dmax = 0.0; /* dmax: the largest τ ε tw² / M*_aa (below) */
    for (int i = n; i >= 1; i--) {
        double *restrict G = IA + 48 * i, *restrict p = P + sr * (size_t)i;
        const double *Ii = Ic + 13 * i; /* Ī about P_i: its subtree's all added */
        for (int a = m->body_vadr[i] + m->body_nv[i] - 1; a >= m->body_vadr[i]; a--) {
            double e[3], Ua[8]; /* local: no aliasing with G, stored to U after */
            int off; /* s_a = e at off, zero elsewhere: U_a = G's three columns there times e */
            twist_at_joint(e, &off, m, d, i, a);
            const double *Gc = G + 8 * off;
            for (int r = 0; r < 8; r++) Ua[r] = Gc[r] * e[0] + Gc[r + 8] * e[1] + Gc[r + 16] * e[2];
            if (drv && drv[a] >= 0) { /* q̈_a = f'' = γ known: I^A passes unchanged, p += U_a q̈_a (0 for a row's side) */
                const double qa = d->gamma[m->drive_row[drv[a]]];
                for (int r = 0; r < 6; r++) p[r] += Ua[r] * qa;
                continue;
            }
            /* M*_aa = s · Ī s = e · J̄ e or m̄ e · e; D_a is a difference of terms as large as
             * |e|² tr J̄ or |e|² m̄ (tw²): below VT_ROUND_TAU ε of them it is round-off of an exact
             * zero, not inertia */
            const double Da = vt_dot3(e, Ua + off), ee = vt_dot3(e, e);
            double maa, tw2;
            if (off == 0) {
                double Je[3];
                vt_mulmat3(Je, Ii + 4, e);
                maa = vt_dot3(e, Je);
                tw2 = ee * (Ii[4] + Ii[8] + Ii[12]);
            } else {
                maa = Ii[0] * ee;
                tw2 = maa;
            }
            const double piv = Da / maa, tol = VT_ROUND_TAU * DBL_EPSILON * tw2;
            /* M* is semi-definite: a pivot below PIVOT_MIN of its diagonal or within its round-off,
             * or negative (M* lost to round-off: the elimination of a light rate far out, a
             * 1.85 kg point mass 1e6 m along its axis, cancels terms far beyond the composite
             * inertia's bound), is no pivot this route can trust; nor is one near the subnormal
             * range (VT_PIVOT_NORMAL): the general route decides */
            if (!(piv >= PIVOT_MIN) || !(Da > tol) || !(Da >= VT_PIVOT_NORMAL)) return d->fallback |= VT_FALLBACK_ARTICULATED_PIVOT, 1;
            pmin = piv < pmin ? piv : pmin;
            pmax = piv > pmax ? piv : pmax;
            dmax = fmax(dmax, tol / maa);
            const double inv = 1.0 / Da;
            Dinv[a] = inv;
            double *restrict ua = u + (size_t)nr * (size_t)a;
            ua[0] = d->qfrc[a] - vt_dot3(e, p + off);
            for (int k = 1; k < nr; k++) ua[k] = -vt_dot3(e, p + 6 * k + off); /* b_a = 0: the row's wrench is in p */
            rank1_cols8(G, Ua, inv);
            memcpy(U + 8 * a, Ua, sizeof Ua);
            for (int k = 0; k < nr; k++) {
                const double t = ua[k] * inv;
                for (int r = 0; r < 6; r++) p[6 * k + r] += Ua[r] * t;
            }
        }
        const int j = m->body_parent[i];
        if (j <= 0) continue;
        const double *ri = L + 6 * i + 3;
        double *restrict pj = P + sr * (size_t)j;
        shift_inertia_add(IA + 48 * j, G, ri);
        shift_composite_add(Ic + 13 * j, Ii, ri);
        for (int k = 0; k < nr; k++) {
            const double *pk = p + 6 * k;
            double t[3];
            vt_cross3(t, ri, pk + 3);
            for (int r = 0; r < 3; r++) {
                pj[6 * k + r] += pk[r] + t[r];
                pj[6 * k + 3 + r] += pk[3 + r];
            }
        }
    }
    /* outward: A of every body about its P_i for every right side (a root's starts at 0) */
    for (int i = 1; i <= n; i++) {
        double *Ai = Aw + sr * (size_t)i;
        const int j = m->body_parent[i];
        if (j > 0) {
            const double *Aj = Aw + sr * (size_t)j, *ri = L + 6 * i + 3;
            for (int k = 0; k < nr; k++) {
                const double *ak = Aj + 6 * k;
                double t[3];
                vt_cross3(t, ak, ri);
                for (int r = 0; r < 3; r++) {
                    Ai[6 * k + r] = ak[r];
                    Ai[6 * k + 3 + r] = ak[3 + r] + t[r];
                }
            }
        } else {
            memset(Ai, 0, sr * sizeof(double));
        }
        for (int a = m->body_vadr[i]; a < m->body_vadr[i] + m->body_nv[i]; a++) {
            const double *Ua = U + 8 * a, *ua = u + (size_t)nr * (size_t)a;
            double e[3];
            int off;
            twist_at_joint(e, &off, m, d, i, a);
            if (drv && drv[a] >= 0) {
                X[a] = d->gamma[m->drive_row[drv[a]]];
                for (int k = 1; k < nr; k++) X[a + (size_t)k * (size_t)nv] = 0.0;
                vt_axpy3(Ai + off, X[a], e);
            } else {
                const double inv = Dinv[a];
                for (int k = 0; k < nr; k++) { /* a multi-rate joint's next rate: from this one's A */
                    const double x = (ua[k] - dot6(Ua, Ai + 6 * k)) * inv;
                    X[a + (size_t)k * (size_t)nv] = x;
                    vt_axpy3(Ai + 6 * k + off, x, e);
                }
            }
        }
    }
    /* S λ = γ − Φ_q x⁰, S = Φ_q X (lower triangle), over the Schur system's rows */
    for (int c = 0; c < nc; c++) {
        const int r = rows[c];
        const double *phi = d->Phiq + r;
        double t = d->gamma[r];
        for (int a = 0; a < nv; a++) t -= phi[(size_t)a * (size_t)ncall] * X[a];
        lam[c] = t;
        for (int k = 0; k <= c; k++) {
            const double *xk = X + (size_t)(k + 1) * (size_t)nv;
            double v = 0.0;
            for (int a = 0; a < nv; a++) v += phi[(size_t)a * (size_t)ncall] * xk[a];
            S[c + (size_t)k * (size_t)nc] = v;
        }
    }
    double rcond = 0.0;
    const int st = vt_solve_spd(d, S, nc, lam, &rcond);
    if (st) return st;
    rcond *= pmin / pmax * (nc > 0 ? vt_rows_grip(m, d) : 1.0);
    *rcond_out = rcond;
    if (!(rcond >= m->rcond_min)) return d->fallback |= VT_FALLBACK_ARTICULATED_CONDITION, 1;
    /* M*_aa = s · Ī s about P_i is known to τ ε tw² only: the pivots, which subtract such terms,
     * carry no digit where nv times that over M*_aa reaches rcond (composite_precision's bound):
     * the general route decides (a point mass 1e6 m from its spherical joint: M* exactly
     * singular, its last pivot round-off amplified by the small one before it) */
    if (!(nv * dmax < rcond)) return d->fallback |= VT_FALLBACK_ARTICULATED_CONDITION, 1;
    for (int a = 0; a < nv; a++) {
        double x = X[a];
        for (int r = 0; r < nc; r++) x += X[a + (size_t)(r + 1) * (size_t)nv] * lam[r];
        d->qdd[a] = x;
    }
    for (int c = 0; c < nc; c++) d->lambda[rows[c]] = lam[c]; /* the known joint drives': articulated_instant */
    if (!vt_all_finite(d->qdd, nv) || !vt_all_finite(lam, nc)) /* conditioned (rcond checked): an overflow */
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: q̈ or λ overflows (loads or rates too large)");
    return 0;
}

/* right sides of the articulated solve: Q, and one per row but the known joint drives */
static int aba_sides(const vt_model *m)
{
    return schur_rows(m, NULL) + 1;
}

/* w->rows filled by the caller (schur_rows) */
static int articulated_solve(const vt_model *m, vt_data *d, const aba_work *w, double *rcond_out)
{
    /* joint drives among the rows: the driven rates' q̈ are known (d->qdd, drive_accelerations),
     * their rows are no right side */
    const int nr = schur_rows(m, w->rows) + 1, *drv = nr <= m->nc ? m->dof_drive : NULL;
    /* one and two right sides (no row, one row) compiled apart: their loops over right sides unroll */
    if (nr == 1) return articulated_solve_nr(m, d, w, rcond_out, drv, 1);
    if (nr == 2) return articulated_solve_nr(m, d, w, rcond_out, drv, 2);
    return articulated_solve_nr(m, d, w, rcond_out, drv, nr);
}

/* (5) by articulated bodies, then the reactions from the subtrees' needed wrenches: the inward
 * pass leaves, for body i, the I^A and p its subtree passes to the parent (after its own rates,
 * about P_i), and for any right side the subtree then needs W̄_i = I^A T_j + p at the parent's
 * acceleration T_j moved to P_i (the outward pass: A_i = T_j + s_a x_a and u_a − U_a·T_j = D_a x_a
 * give I^A_i T_j + p_i = I^A T_i + p before the rate's update). At the solution, p = p⁰ +
 * Σ_r λ_r p^r, and the part q̈ adds to body i's spatial acceleration about P_i is T_i = A⁰_i +
 * Σ_r λ_r A^r_i (the outward pass's, linear in the right sides), so
 *   W̄_i = I^A_i (T_j moved to P_i) + p⁰_i + Σ_r λ_r p^r_i   (= Σ over i's subtree of W⁰ + I T − Σ_r λ_r w_r)
 * about P_i, as vt_reactions_subtree takes it (no term carries |P_i − O|), the rows' loads
 * already off (the p^r start from them); and
 * ẍ from the same T_i (T about O, as vt_accelerations_add sums it, carries |P − O| |q̈| terms:
 * the forces of a mechanism 1 km from o changed by 2e-11 with it, 5e-13 with T_i). A known joint
 * drive's λ_r on rate a of body i is s_a · W̄_i − qfrc_a with W̄_i about P_i (s_a = (e, 0) or
 * (0, e) there), W̄_i being then M* q̈ − Q less the other rows' loads over the subtree; its own
 * load (on its two bodies) is then taken off W̄ over each subtree too, as the reactions want. */
static vt_status articulated_instant(const vt_model *m, vt_data *d)
{
    double rcond = 0.0;
    const int nr = aba_sides(m);
    /* a row that is round-off of zero would pass for a row once S is at unit diagonal: the
     * general route names it */
    int zero_rows = vt_zero_rows(m, d);
    /* with joint-driven rates known (articulated_solve), a row that only they move beyond
     * round-off is round-off on the free rates: dependent on their drives */
    if (zero_rows == 0 && nr <= m->nc) zero_rows = vt_zero_rows_free(m, d, m->dof_drive);
    if (zero_rows < 0) return (vt_status)zero_rows;
    if (zero_rows > 0) return factorized_instant(m, d);
    const size_t mark = vt_scratch_mark(d), sr = 6 * (size_t)nr;
    aba_work w;
    if (aba_take(m, d, nr, &w)) return vt_scratch_fail(d, mark);
    const int r = articulated_solve(m, d, &w, &rcond);
    if (r || maximal_instead(m, VT_ROUTE_ARTICULATED, rcond)) {
        vt_scratch_release(d, mark);
        if (r == 0) d->fallback |= VT_FALLBACK_ARTICULATED_CONDITION;
        return r < 0 ? (vt_status)r : r ? factorized_instant(m, d) : VT_NEEDS_MAXIMAL;
    }
    vt_solved(m, d, VT_ROUTE_ARTICULATED, rcond);
    const double *L = w.G; /* the lever arms (articulated_solve) */
    for (int i = 1; i <= m->nbody; i++) { /* parents first: T_j is known at i's turn */
        const int j = m->body_parent[i], o = vt_xoff(i);
        double *Wi = w.W + 6 * i, *Ti = w.T + 6 * i, IT[8], Tj[6] = {0, 0, 0, 0, 0, 0};
        if (j > 0) { /* the parent's T about P_i */
            const double *tj = w.T + 6 * j;
            double t[3];
            vt_cross3(t, tj, L + 6 * i + 3);
            for (int k = 0; k < 3; k++) Tj[k] = tj[k], Tj[3 + k] = tj[3 + k] + t[k];
        }
        const double *p = w.P + sr * (size_t)i, *Ai = w.A + sr * (size_t)i;
        mul_cols8(IT, w.IA + 48 * i, Tj);
        for (int k = 0; k < 6; k++) Wi[k] = IT[k] + p[k], Ti[k] = Ai[k];
        for (int c = 1; c < nr; c++) {
            const double l = d->lambda[w.rows[c - 1]];
            for (int k = 0; k < 6; k++) Wi[k] += l * p[6 * c + k], Ti[k] += l * Ai[6 * c + k];
        }
        for (int a = m->body_vadr[i]; a < m->body_vadr[i] + m->body_nv[i] && nr <= m->nc; a++) {
            /* a known joint drive's multiplier: (M* q̈ − Q − Φ_q,o^T λ_o)_a = s_a · W̄_i − qfrc_a,
             * W̄_i about P_i here, without the other rows' loads; s_a about P_i (e at off) */
            const int k = m->dof_drive[a];
            if (k < 0) continue;
            double e[3];
            int off;
            twist_at_joint(e, &off, m, d, i, a);
            d->lambda[m->drive_row[k]] = vt_dot3(e, Wi + off) - d->qfrc[a];
        }
        /* ẍ = S q̈ + Ṡq̇ (vt_accelerations_add's, from T about P_i): the centre of mass, c_i from
         * P_i, a = a⁰ + T_v + T_ω × c_i; p̈ = p̈⁰ + ½ E^T T_ω (no base body on this route) */
        const double *a0 = d->Sdqd + o, *ci = L + 6 * i;
        double *xi = d->xdd + o, a[3], pdd[4];
        for (int k = 0; k < 3; k++) a[k] = a0[k] + Ti[3 + k];
        vt_addcross3(a, Ti, ci);
        vt_quat_rate(pdd, d->x + o + 3, Ti);
        vt_copy3(xi, a);
        for (int k = 0; k < 4; k++) xi[3 + k] = a0[3 + k] + pdd[k];
    }
    if (nr <= m->nc) { /* the known joint drives' loads off W̄ too (about P_i, over each subtree) */
        double *J = w.T;
        if (nr == 1) vt_row_wrenches(w.rw, m, d, NULL); /* articulated_solve formed them with other rows */
        memset(J, 0, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        for (int q = 0; q < m->nc; q++) {
            if (!vt_known_row(m, q)) continue;
            for (int side = 0; side < 2; side++) {
                const int b = m->con_body[2 * q + side];
                if (b == 0) continue;
                const double *f = w.rw + 12 * q + 6 * side, l = d->lambda[q];
                double *Jb = J + 6 * b, t[3];
                vt_cross3(t, L + 6 * b, f); /* about the centre of mass → about P_b */
                for (int c = 0; c < 3; c++) {
                    Jb[c] += l * (f[3 + c] + t[c]);
                    Jb[3 + c] += l * f[c];
                }
            }
        }
        vt_sum_at_joints(m, d, J, 0, 3);
        for (int k = 6; k < 6 * (m->nbody + 1); k++) w.W[k] -= J[k];
    }
    const vt_status st = vt_reactions_subtree(m, d, w.W, w.G, 1);
    vt_scratch_release(d, mark);
    return st;
}

/* the largest |xfrc| and |qfrc| (one scan), the largest of those and |q|, |q̇| (one scan), of
 * |q̈|: +Inf where one is not finite */
static inline double loads_max(const vt_model *m, const vt_data *d)
{
    vt_max_scan s = {0};
    vt_max_add(&s, d->xfrc, 6 * (m->nbody + 1));
    vt_max_add(&s, d->qfrc, m->nv);
    return vt_max_result(&s);
}
static inline double state_max(const vt_model *m, const vt_data *d)
{
    vt_max_scan s = {0};
    vt_max_add(&s, d->xfrc, 6 * (m->nbody + 1));
    vt_max_add(&s, d->qfrc, m->nv);
    vt_max_add(&s, d->q, m->nq);
    vt_max_add(&s, d->qd, m->nv);
    return vt_max_result(&s);
}
static inline double array_max(const double *a, int n)
{
    vt_max_scan s = {0};
    vt_max_add(&s, a, n);
    return vt_max_result(&s);
}
/* 1 when every half angle is within vt_sincos_small's 2^14 (fused_outward, not _any): from the
 * state's maximum smax (state_max), q scanned again alone only where that is above 2^15 */
static inline int angles_small(const vt_model *m, const vt_data *d, double smax)
{
    return smax <= 0x1p15 || array_max(d->q, m->nq) <= 0x1p15;
}

/* 1 when no output of the fused passes can overflow, from the inputs' sizes alone: then their
 * scans (vt_kinematics_check_outputs, fused_check) are skipped. With U = 1 + Σ_i (|s^{ij}| +
 * |s^{ji}|) + nq max|q| (every position, lever arm and o itself: a path's offsets and
 * translations; every orientation is unit, the Euler parameters normalized), R = 1 + nv max|q̇|,
 * A = 1 + nv max|q̈| + 4 R² + |g|, M = 1 + max (m + 3 max|J_kl|), F = 1 + max(|xfrc|, |qfrc|):
 *   |ω| ≤ R, |v| ≤ 2 R U, |α| ≤ Σ|q̈| + Σ|q̇| |ω| ≤ A, |a| ≤ 2 A U + 2 R² U + 2 R² + Σ|q̈| ≤ 4 A U,
 *   |p̈| ≤ ½ |α| + ¼ |ω|² ≤ A, a body's force ≤ 5 M A U + 2 F, its moment about its joint point
 *   ≤ 6 M A + 2 F + 2 U × the force ≤ 16 U² (M A + F), a subtree's (n bodies, moved by lever arms
 *   < 2U) ≤ 26 n U² (M A + F), efforts and reactions at most twice that (the actuation taken off),
 *   in either frame (a rotation keeps lengths);
 * so every output is below B = 64 (n + 1) U² (M A + F), and B < 1e300 leaves round-off (relative
 * ε per operation) 8 orders of magnitude from DBL_MAX. Where B is not below it (a rate of 1e150
 * rad/s, loads near DBL_MAX, B itself Inf), the scans decide, as before. B only grows with each
 * maximum, so the instants pass one maximum of |xfrc|, |qfrc|, |q| and |q̇| (state_max: one scan)
 * for all four. */
static inline int fused_bounded(const vt_model *m, double qmax, double vmax, double amax,
                                double fmax_)
{
    const double g = fabs(m->gravity[0]) + fabs(m->gravity[1]) + fabs(m->gravity[2]);
    const double U = 1.0 + m->bound_length + m->nq * qmax, R = 1.0 + m->nv * vmax;
    const double A = 1.0 + m->nv * amax + 4.0 * R * R + g;
    const double B = 64.0 * (m->nbody + 1) * U * U * ((1.0 + m->bound_mass) * A + 1.0 + fmax_);
    return B < 1e300;
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status recursive_instant(const vt_model *m, vt_data *d, int *formed);
static vt_status constrained_instant(const vt_model *m, vt_data *d);
static vt_status outputs_scanned(const vt_model *m, vt_data *d, vt_status st, int formed, int totals);

vt_status vt_inverse_dynamics_recursive(const vt_model *m, vt_data *d)
{
    int formed = 0;
    const vt_status st = recursive_instant(m, d, &formed);
    return outputs_scanned(m, d, st, formed, 1);
}

/* The instant after it, its outputs scanned: finite inputs whose products overflow (an
 * acceleration of −Inf from loads near DBL_MAX) are refused, not returned with VT_OK. formed: 2
 * the fused passes formed α and the total wrenches and checked their outputs themselves; 1 the
 * inward pass formed α and the total wrenches (scanned here); 0 neither: with totals,
 * vt_reactions_total forms them */
static vt_status outputs_scanned(const vt_model *m, vt_data *d, vt_status st, int formed, int totals)
{
    if (st == VT_NEEDS_DENSE || st == VT_NEEDS_MAXIMAL) {
        /* the composite inertias about o cannot vouch for a digit, or the estimate is low enough
         * that the maximal route may be wanted (maximal_instead): the dense stages */
        const int left = d->fallback | (st == VT_NEEDS_DENSE ? VT_FALLBACK_COMPOSITE_ROUNDOFF : 0);
        d->message[0] = '\0'; /* a refusal the dense stages decide again is no diagnosis */
        st = vt_inverse_dynamics(m, d);
        d->fallback |= left;
        return st;
    }
    if (st) return st;
    if (formed == 2) return VT_OK; /* its outputs checked by fused_check */
    const int nb = 3 * (m->nbody + 1), nd = 3 * m->ndrive, nk = 3 * m->ncut;
    if (!vt_all_finite(d->qdd, m->nv) || !vt_all_finite(d->xdd, m->nx) || !vt_all_finite(d->qfrc_drive, m->nv) ||
        !vt_all_finite(d->drive_effort, m->ndrive) || !vt_all_finite(d->drive_force, nd) ||
        !vt_all_finite(d->drive_moment, nd) || !vt_all_finite(d->jnt_force, nb) || !vt_all_finite(d->jnt_moment, nb) ||
        !vt_all_finite(d->jnt_force_body, nb) || !vt_all_finite(d->jnt_moment_body, nb) ||
        !vt_all_finite(d->cut_force, nk) || !vt_all_finite(d->cut_moment, nk) ||
        !vt_all_finite(d->cut_force_body, nk) || !vt_all_finite(d->cut_moment_body, nk) ||
        (formed && (!vt_all_finite(d->alpha, nb) || !vt_all_finite(d->jnt_force_total, nb) ||
                    !vt_all_finite(d->jnt_moment_total, nb) || !vt_all_finite(d->jnt_force_total_body, nb) ||
                    !vt_all_finite(d->jnt_moment_total_body, nb)))) {
        d->route = VT_ROUTE_NONE;
        return vt_fail(d->message, VT_ERR_NONFINITE,
                       "vt_inverse_dynamics_recursive: the accelerations, efforts or reactions overflow (not finite)");
    }
    if (!formed && totals && (st = vt_reactions_total(m, d, 0))) d->route = VT_ROUTE_NONE; /* α and the total wrenches, as the dense path */
    return st;
}

static inline vt_status recursive_instant(const vt_model *m, vt_data *d, int *formed)
{
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_recursive");
    if (st) return st;
    vt_diagnostics_reset(d);
    const double smax = state_max(m, d); /* loads, q and q̇; the loads alone where one is not finite */
    if (!(smax < HUGE_VAL) && !(loads_max(m, d) < HUGE_VAL))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: NaN or Inf in xfrc or qfrc");
    d->route = VT_ROUTE_NONE;
    d->fallback = 0;
    const int mix = m->joint_mix;
    if (m->joint_driven && mix >= 0) { /* the outward passes fused */
        /* Euler parameters' norms to check (a revolute or translational joint's q is any finite
         * number), or q or q̇ not finite */
        if ((mix == 0 && m->has_quaternions) || !(smax < HUGE_VAL))
            if ((st = vt_kinematics_check_state(m, d))) return st;
        if ((st = drive_accelerations(m, d))) { /* the status the separate passes would give */
            const vt_status sk = vt_kinematics_tree(m, d, 0);
            return sk ? sk : st;
        }
        d->route = VT_ROUTE_JOINT_DRIVEN;
        d->rcond = 1.0;
        d->warning = 0;
        d->rank = m->nc;
        d->residual = 0.0;
        vt_mark_unique(m, d);
        *formed = 2;
        const int bounded = fused_bounded(m, smax, smax, array_max(d->qdd, m->nv), smax);
        const int small = angles_small(m, d, smax);
        return mix ? fused_pass(m, d, 0, 0, bounded, small) : fused_pass(m, d, 0, 1, bounded, small);
    }
    if ((st = vt_kinematics_tree(m, d, !m->joint_driven))) return st; /* Ṡq̇ only when factorizing */
    if (m->joint_driven) { /* nothing to factorize: always well defined */
        if ((st = drive_accelerations(m, d))) return st;
        d->route = VT_ROUTE_JOINT_DRIVEN;
        d->rcond = 1.0;
        d->warning = 0;
        d->rank = m->nc; /* one unit row per rate: independent, every multiplier and reaction unique */
        d->residual = 0.0;
        vt_mark_unique(m, d);
        *formed = m->joint_mix >= 0;
        return inward(m, d, *formed);
    }
    if (m->joint_rows_only) { /* q̈ of the free rates, then the inward pass */
        memset(d->Phiq, 0, (size_t)m->nc * (size_t)m->nv * sizeof(double)); /* unit rows (R S = I) */
        for (int r = 0; r < m->nc; r++) d->Phiq[r + (size_t)m->con_dof[r] * (size_t)m->nc] = 1.0;
        if ((st = drive_accelerations(m, d))) return st;
        double rcond = 0.0;
        int r = 1;
        if (m->joint_mix >= 0) { /* by articulated bodies */
            const size_t mark = vt_scratch_mark(d);
            aba_work w;
            r = aba_take(m, d, 1, &w) ? VT_ERR_NO_MEMORY : articulated_solve(m, d, &w, &rcond);
            vt_scratch_release(d, mark);
        }
        if (r < 0) return (vt_status)r;
        if (r == 0 && maximal_instead(m, VT_ROUTE_ARTICULATED, rcond))
            return d->fallback |= VT_FALLBACK_ARTICULATED_CONDITION, VT_NEEDS_MAXIMAL;
        if (r == 0) vt_solved(m, d, VT_ROUTE_ARTICULATED, rcond);
        else if ((st = mass_and_bias(m, d)) || (st = composite_solve(m, d)) ||
                 (st = vt_zeroed_rates_check(m, d, "vt_inverse_dynamics_recursive", 0))) /* or from M*_FF, which also diagnoses */
            return st;
        *formed = m->joint_mix >= 0;
        return inward(m, d, *formed);
    }
    if ((st = vt_constraints_impl(m, d, 0))) return st;
    return constrained_instant(m, d);
}

/* no base body (whose ṗ rates carry (4)'s normal part), no redundant rows, no coupling (whose
 * force acts through two rates, not through the rows' wrenches): the square and articulated
 * shortcuts, each falling back to factorized_instant when ill-conditioned */
static int shortcuts(const vt_model *m)
{
    return !m->allow_redundant && m->joint_mix >= 0 && m->ncoupling == 0;
}

/* The instant of a model with rows other than joint drives, its kinematics and constraints
 * evaluated */
static vt_status constrained_instant(const vt_model *m, vt_data *d)
{
    if (shortcuts(m)) {
        if (m->nc == m->nv) return square_instant(m, d);
        if (m->nc < m->nv) return articulated_instant(m, d);
    }
    return factorized_instant(m, d);
}

/* vt_inverse_dynamics_recursive at a state whose positions d already holds, as Newton's last
 * evaluation leaves them (vt_kinematic_solve_impl): vt_kinematics_positions' outputs and the
 * constraints' Φ, Φ_t and Φ_q (vt_constraints_parts with VT_CON_PHIQ, from the twists) at d->q
 * and d->time, q̇ new; fd the drives' functions at d->time (vt_drive_values) or NULL. The
 * velocities, Ṡq̇, Φ_x and γ are computed, then the same routes: the same outputs as
 * vt_inverse_dynamics_recursive, bitwise (α and the joints' total wrenches only with totals).
 * A model whose rows are all joint drives (the fused passes, or the free rates' solve) takes
 * vt_inverse_dynamics_recursive. */
vt_status vt_inverse_dynamics_recursive_positioned(const vt_model *m, vt_data *d, const double *fd, int totals, int rates)
{
    const int joints = m->joint_driven || m->joint_rows_only;
    if (rates && (joints || !shortcuts(m) || m->nc != m->nv)) return VT_NEEDS_RATES;
    if (joints) return vt_inverse_dynamics_recursive(m, d);
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_recursive");
    if (st) return st;
    vt_diagnostics_reset(d);
    if (!vt_all_finite(d->xfrc, 6 * (m->nbody + 1)) || !vt_all_finite(d->qfrc, m->nv))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: NaN or Inf in xfrc or qfrc");
    d->route = VT_ROUTE_NONE;
    d->fallback = 0;
    if (!rates) {
        if (!(st = vt_kinematics_velocities(m, d, 1)) && !(st = vt_constraints_parts(m, d, 0, VT_CON_PHIX | VT_CON_GAMMA, fd)))
            st = constrained_instant(m, d);
        return outputs_scanned(m, d, st, 0, totals);
    }
    /* the square route's LU of Φ_q, from the positions, solves q̇ = −Φ_q^-1 Φ_t before it
     * solves q̈: the instant then runs as square_instant does */
    const size_t mark = vt_scratch_mark(d);
    double rcond = 0.0;
    vt_square sq;
    const int r = square_factor(m, d, &sq, &rcond);
    if (r) return vt_scratch_release(d, mark), r == 1 ? VT_NEEDS_RATES : (vt_status)r;
    if (!(st = (vt_status)vt_square_apply(m, d, &sq, d->Phit, -1.0, d->qd)) && !(st = vt_kinematics_velocities(m, d, 1)) &&
        !(st = vt_constraints_parts(m, d, 0, VT_CON_PHIX | VT_CON_GAMMA, fd)))
        st = square_solved(m, d, &sq, rcond);
    vt_scratch_release(d, mark);
    return outputs_scanned(m, d, st, 0, totals);
}

/* The scratch recursive.c takes at once: the articulated route's work (the largest, with the
 * reactions' arrays), or the square route's (M*'s diagonal and three arrays a body; vt_solve's
 * square state is solve.c's), or the composite inertias. */
size_t vt_recursive_scratch(const vt_model *m)
{
    const size_t nb = (size_t)m->nbody + 1, D = sizeof(double);
    size_t n = aba_bytes(m, m->nc + 1), one = aba_bytes(m, 1);
    const size_t square = VT_SCRATCH_BYTES(m->nv, D) + VT_SCRATCH_BYTES(15 * nb, D);
    if (one > n) n = one;
    if (square > n) n = square;
    if (VT_SCRATCH_BYTES(13 * nb, D) > n) n = VT_SCRATCH_BYTES(13 * nb, D);
    /* composite_precision's terms of M*'s diagonal and subtree sums */
    const size_t terms = VT_SCRATCH_BYTES(2 * (size_t)m->nv, D) + VT_SCRATCH_BYTES(4 * nb, D);
    if (terms > n) n = terms;
    /* vt_motion_rows (instant.c, called from here) holds the given q̈ while the stages run */
    if (VT_SCRATCH_BYTES(m->nv, D) > n) n = VT_SCRATCH_BYTES(m->nv, D);
    return n;
}

/* The motion given for every rate of a tree: q̈ is known, and one outward and one inward pass
 * give every rate's effort τ_a = s_a · W̄_i − qfrc_a (= (M* q̈ − Q)_a) and the reactions, the
 * actuation taken off (route VT_ROUTE_MOTION, nothing factorized). A loop's or a coupling's
 * rates are not independent: there the joint-driven rates are the given ones and the rest
 * follows from the rows (vt_motion_rows, instant.c). Base bodies of a tree are refused: a base
 * body's ṗ rates carry (4)'s normal part (its multiplier); a free joint (VT_JOINT_FREE), whose
 * six rates are twists, is what a floating robot uses here. */
vt_status vt_inverse_dynamics_motion(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_motion");
    if (st) return st;
    vt_solve_reset(d);
    d->fallback = 0;
    const double amax = array_max(d->qdd, m->nv);
    if (!(amax < HUGE_VAL)) {
        for (int c = 0; c < m->nv; c++)
            if (!isfinite(d->qdd[c]))
                return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_motion: qdd[%d] = %g", c, d->qdd[c]);
    }
    if (m->ncut > 0 || m->ncoupling > 0) { /* loops or couplings: the joint-driven rates are the given ones */
        int given = 0;
        for (int r = 0; r < m->nc; r++) given += m->con_kind[r] == VT_ROW_JOINT;
        if (!given)
            return vt_fail(d->message, VT_ERR_BAD_OPTION,
                           "vt_inverse_dynamics_motion: the model has %d cut joints and %d couplings and no joint drive: "
                           "drive the rates whose motion is given", m->ncut, m->ncoupling);
        return vt_motion_rows(m, d);
    }
    for (int i = 1; m->joint_mix < 0 && i <= m->nbody; i++)
        if (m->body_joint[i] == VT_JOINT_BASE)
            return vt_fail(d->message, VT_ERR_BAD_OPTION,
                           "vt_inverse_dynamics_motion: body %d has a base (floating) joint, not supported here; "
                           "use VT_JOINT_FREE", i);
    const double smax = state_max(m, d); /* loads, q and q̇; the loads alone where one is not finite */
    if (!(smax < HUGE_VAL) && !(loads_max(m, d) < HUGE_VAL))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_motion: NaN or Inf in xfrc or qfrc");
    /* the outward passes fused (no base body here) */
    const int mix = m->joint_mix;
    /* Euler parameters' norms to check (a revolute or translational joint's q is any finite
     * number), or q or q̇ not finite */
    if ((mix == 0 && m->has_quaternions) || !(smax < HUGE_VAL))
        if ((st = vt_kinematics_check_state(m, d))) return st;
    const int bounded = fused_bounded(m, smax, smax, amax, smax);
    d->rcond = 1.0;
    d->warning = 0;
    d->rank = m->nc;
    d->residual = 0.0;
    vt_mark_unique(m, d);
    const int small = angles_small(m, d, smax);
    if ((st = mix ? fused_pass(m, d, 1, 0, bounded, small) : fused_pass(m, d, 1, 1, bounded, small))) return st; /* α and the totals formed in it */
    d->route = VT_ROUTE_MOTION;
    return VT_OK;
}
