/* The recursive (O(n) and O(n·depth)) evaluation of the same method, without the dense S.
 *
 * Every rate a has a twist s_a = (w_a, v_a) about the global origin O (d->twist, from the kinematics): the
 * column of S of every body below it is ṙ = v_a + w_a × r, ṗ = ½ E^T w_a (15)-(16). A wrench
 * (n_O, f) about O pairs with it as power s_a · W = w_a · n_O + v_a · f, so S^T F, summed over a
 * subtree, is the projection of the subtree's wrench (10).
 *
 *   body wrench needed   W_k = (J α + ω × J ω − n_e + r × f,  f = m a − f_e)   about O
 *                        (f_e: gravity and xfrc; n_e: xfrc's moment about the centre of mass)
 *   subtree              W̄_i = W_i + Σ_children W̄_c                       (inward pass)
 *   composite inertia    Ī_i = Σ_subtree [J − m c̃ c̃, m c̃; −m c̃, m I]  about O, (m, h = m c, J_O)
 *   M* (3)               M*_ab = s_b · (Ī_i s_a),  i the body of rate a, b on i's path
 *                        (Ī s = (J_O w + h × v, m v + w × h))
 *   M*_aa alone          Σ_k m_k |v_a + w_a × c_k|² + u^T J'_k u,  u = A_k^T w_a, k below rate a
 *                        (the square path's scaling: twice the kinetic energy of s_a)
 *   Q  (4)               Q_a = qfrc_a − s_a · W̄⁰_i   with W̄⁰ from the accelerations at q̈ = 0 (Ṡq̇);
 *                        a base body's own ṗ rates add h's normal part 2 (ω^T J ω) p
 * With every rate driven by one joint drive (the model's joint_driven), q̈ = f''(t) is known
 * and nothing is factorized (when only some rates are, joint_rows_only, the free rates' q̈ come
 * from M*_FF first, then the same inward pass): the efforts are τ_a = s_a · W̄_i − qfrc_a (the paper's Φ_q^T λ with
 * unit rows, λ = τ), and the reaction at joint i is W̄_i moved to the joint point P_i less the
 * joint's actuation (τ + qfrc) along its axes. Otherwise M* and Q as above, Φ_q = Φ_x S from
 * the twists, the augmented system (5) and the reactions (25)-(28) as in the dense path.
 */
#include <string.h>

#include "internal.h"

/* W = needed wrench of body i about O, given its accelerations a (3) and α (3) */
static void body_wrench(double W[6], const vt_model *m, const vt_data *d, int i, const double *a, const double *al)
{
    const double *Ai = d->A + 9 * i, *Jb = m->body_inertia + 9 * i, *w = d->omega + 3 * i;
    const double *r = d->x + vt_xoff(i), *xf = d->xfrc + 6 * i, mass = m->body_mass[i];
    double wb[3], ab[3], Jw[3], Ja[3];
    vt_mulmat3t(wb, Ai, w);
    vt_mulmat3t(ab, Ai, al);
    vt_mulmat3(Jw, Jb, wb);
    vt_mulmat3(Ja, Jb, ab);
    vt_addcross3(Ja, wb, Jw);
    vt_mulmat3(W, Ai, Ja); /* J α + ω × J ω, body axes and back */
    for (int c = 0; c < 3; c++) {
        W[3 + c] = mass * (a[c] - m->gravity[c]) - xf[c];
        W[c] -= xf[3 + c];
    }
    vt_addcross3(W, r, W + 3);
}

/* W̄: every subtree's needed wrench about O at the accelerations d->xdd and alpha (3 x (nbody+1)) */
static void subtree_wrenches(const vt_model *m, const vt_data *d, const double *alpha, double *W /* 6 x (nbody+1) */)
{
    for (int i = 1; i <= m->nbody; i++) body_wrench(W + 6 * i, m, d, i, d->xdd + vt_xoff(i), alpha + 3 * i);
    vt_subtree_sum(m, W, 6);
}

static double pair(const double w[3], const double v[3], const double W[6])
{
    return vt_dot3(w, W) + vt_dot3(v, W + 3);
}

/* composite inertias about O, summed over subtrees: (m, h = m c, J_O) per body */
static void composite(const vt_model *m, const vt_data *d, double *Ic /* 13 x (nbody+1) */)
{
    for (int i = 1; i <= m->nbody; i++) {
        double *I = Ic + 13 * i, J[9], t[9];
        const double mass = m->body_mass[i], *c = d->x + vt_xoff(i), *A = d->A + 9 * i, *Jb = m->body_inertia + 9 * i;
        /* J = A J' A^T, then J_O = J − m c̃ c̃ = J + m (|c|² I − c c^T) */
        for (int col = 0; col < 3; col++) vt_mulmat3(t + 3 * col, Jb, (double[3]){A[col], A[col + 3], A[col + 6]});
        for (int col = 0; col < 3; col++) vt_mulmat3(J + 3 * col, A, t + 3 * col);
        const double c2 = vt_dot3(c, c);
        I[0] = mass;
        for (int k = 0; k < 3; k++) I[1 + k] = mass * c[k];
        for (int col = 0; col < 3; col++)
            for (int r = 0; r < 3; r++) I[4 + r + 3 * col] = J[r + 3 * col] - mass * c[r] * c[col];
        for (int k = 0; k < 3; k++) I[4 + 4 * k] += mass * c2;
    }
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
        /* F = Ī s_a = (J_O w + h × v, m v + w × h) */
        const double *I = Ic + 13 * i, *h = I + 1, *w = d->twist + 6 * a, *v = w + 3;
        double F[6];
        vt_mulmat3(F, I + 4, w);
        vt_addcross3(F, h, v);
        for (int k = 0; k < 3; k++) F[3 + k] = I[0] * v[k];
        vt_addcross3(F + 3, w, h);
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

/* Q = qfrc − S^T (needed wrenches at q̈ = 0) */
static void bias(const vt_model *m, vt_data *d, double *W /* 6 x (nbody+1) */)
{
    for (int i = 1; i <= m->nbody; i++) {
        const int o = vt_xoff(i);
        double al[3];
        vt_mulEp(al, d->x + o + 3, d->Sdqd + o + 3); /* α = 2 E p̈ */
        for (int k = 0; k < 3; k++) al[k] *= 2.0;
        body_wrench(W + 6 * i, m, d, i, d->Sdqd + o, al);
    }
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
    for (int c = 0; c < m->nv; c++) {
        const int k = m->dof_drive[c];
        if (k < 0) continue;
        const int row = m->drive_row[k];
        double f[3];
        vt_status st = vt_function_eval_valid(f, &m->drive[k].f, d->time);
        if (st)
            return vt_fail(d->message, st, "vt_inverse_dynamics_recursive: drive %d: time function failed at t = %g", k,
                           d->time);
        const int i = m->dof_body[c];
        d->Phi[row] = d->q[m->body_qadr[i] + c - m->body_vadr[i]] - f[0];
        d->Phit[row] = -f[1];
        d->gamma[row] = f[2];
        d->qdd[c] = f[2];
    }
    return VT_OK;
}

/* with q̈ known for every rate: one inward pass for the joint drives' efforts τ = s · W̄ − qfrc
 * and every reaction (actuation — a drive's τ and an applied qfrc — is not reaction) */
static vt_status inward(const vt_model *m, vt_data *d)
{
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1;
    double *alpha = d->work, *W = alpha + 3 * nb;
    vt_accelerations(m, d, d->qdd, d->xdd, alpha);
    subtree_wrenches(m, d, alpha, W);
    for (int i = 1; i <= n; i++) {
        const double *Wi = W + 6 * i, *P = d->jpoint + 3 * i, *e = d->jaxis + 9 * i;
        double *f = d->jnt_force + 3 * i, *mo = d->jnt_moment + 3 * i;
        vt_copy3(f, Wi + 3);
        vt_copy3(mo, Wi);
        double t[3];
        vt_cross3(t, P, f);
        for (int c = 0; c < 3; c++) mo[c] -= t[c]; /* about P_i */
        for (int k = 0; k < m->body_nv[i]; k++) {
            const int c = m->body_vadr[i] + k, dr = m->dof_drive[c];
            int ax;
            const int rot = vt_dof_kind(m->body_joint[i], k, &ax) == VT_DOF_ROT;
            double tau = 0.0;
            if (dr >= 0) {
                const double *w = d->twist + 6 * c;
                tau = pair(w, w + 3, Wi) - d->qfrc[c];
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
        vt_mulmat3t(d->jnt_force_body + 3 * i, d->A + 9 * i, f);
        vt_mulmat3t(d->jnt_moment_body + 3 * i, d->A + 9 * i, mo);
        if (!vt_all_finite(f, 3) || !vt_all_finite(mo, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: joint %d's reaction overflowed", i);
    }
    return VT_OK;
}

/* M* and Q formed, (5) solved by vt_solve, the reactions inward: constraints already evaluated */
static vt_status factorized_instant(const vt_model *m, vt_data *d)
{
    crba(m, d, d->work);
    bias(m, d, d->work);
    vt_status st = vt_solve(m, d);
    return st ? st : vt_reactions_impl(m, d);
}

/* M*'s diagonal without the composite inertias: M*_aa = s_a · (Ī_i s_a) is twice the kinetic
 * energy of the bodies k below rate a moving with its twist s_a = (w, v) alone,
 *   M*_aa = Σ_k  m_k |v + w × c_k|² + u^T J'_k u,   u = A_k^T w,
 * summed body by body over each body's path (no base bodies: their ṗ rates are not twists). */
static void mass_diagonal(const vt_model *m, const vt_data *d, double *diag)
{
    memset(diag, 0, (size_t)m->nv * sizeof(double));
    for (int k = 1; k <= m->nbody; k++) {
        const double *c = d->x + vt_xoff(k), *A = d->A + 9 * k, *J = m->body_inertia + 9 * k, mass = m->body_mass[k];
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
 * M*'s diagonal, for the scaling, and the right side of Φ_q^T λ = M* q̈ − Q is S^T W̄ − qfrc with
 * the needed wrenches W at the full accelerations, one inward pass as for joint drives: neither
 * M* nor Q is formed. Where Φ_q is ill-conditioned, the general path diagnoses it. */
static vt_status square_instant(const vt_model *m, vt_data *d)
{
    const int nv = m->nv;
    const size_t nb = (size_t)m->nbody + 1;
    double rcond = 0.0;
    mass_diagonal(m, d, d->kkt_scale);
    const int r = vt_solve_square_begin(m, d, d->kkt_scale, &rcond);
    if (r < 0) return (vt_status)r;
    if (r == 1) return factorized_instant(m, d);
    /* α, then vt_accelerations_add's scratch of 6 (n+1) (free after it: G of the reactions), W̄ */
    double *alpha = d->work, *G = alpha + 3 * nb, *W = alpha + 9 * nb;
    vt_accelerations_add(m, d, d->kkt_rhs, d->xdd, alpha);
    subtree_wrenches(m, d, alpha, W);
    for (int a = 0; a < nv; a++) {
        const double *s = d->twist + 6 * a;
        d->kkt_rhs[nv + a] = pair(s, s + 3, W + 6 * m->dof_body[a]) - d->qfrc[a]; /* M* q̈ − Q */
    }
    const vt_status st = vt_solve_square_end(m, d, rcond);
    return st ? st : vt_reactions_subtree(m, d, W, G);
}

static int has_base(const vt_model *m)
{
    for (int i = 1; i <= m->nbody; i++)
        if (m->body_joint[i] == VT_JOINT_BASE) return 1;
    return 0;
}

vt_status vt_inverse_dynamics_recursive(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_recursive");
    if (st) return st;
    if (!vt_all_finite(d->xfrc, 6 * (m->nbody + 1)) || !vt_all_finite(d->qfrc, m->nv))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: NaN or Inf in xfrc or qfrc");
    if ((st = vt_kinematics_tree(m, d, !m->joint_driven))) return st; /* Ṡq̇ only when factorizing */
    if (m->joint_driven) { /* nothing to factorize: always well defined */
        d->rcond = 1.0;
        d->warning = 0;
        d->rank = m->nc; /* one unit row per rate: independent, every multiplier and reaction unique */
        d->residual = 0.0;
        vt_mark_unique(m, d);
        if ((st = drive_accelerations(m, d))) return st;
        return inward(m, d);
    }
    if (m->joint_rows_only) { /* q̈ of the free rates from M*_FF (vt_solve), then the inward pass */
        crba(m, d, d->work);
        bias(m, d, d->work);
        memset(d->Phiq, 0, (size_t)m->nc * (size_t)m->nv * sizeof(double)); /* unit rows (R S = I) */
        for (int r = 0; r < m->nc; r++) d->Phiq[r + (size_t)m->con_dof[r] * (size_t)m->nc] = 1.0;
        if ((st = drive_accelerations(m, d)) || (st = vt_solve(m, d))) return st;
        return inward(m, d);
    }
    if ((st = vt_constraints_impl(m, d, 0))) return st;
    /* square, exactly constrained, no base body (whose ṗ rates carry (4)'s normal part): */
    if (m->nc == m->nv && !m->allow_redundant && !has_base(m)) return square_instant(m, d);
    return factorized_instant(m, d);
}
