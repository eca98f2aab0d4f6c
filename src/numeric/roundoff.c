/* Round-off of exact zeros, the judgement every route makes before it solves (5)
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 *
 * and the recursive routes make on their own pivots: round-off of an exact zero is neither a
 * row nor an inertia. A row of Φ_q that is round-off of a zero row is a zero row (dependent:
 * the rank decision, numeric/rank.c, takes it so, and vt_solve names it); a rate whose M*_aa is
 * round-off and that no row fixes has no inertia (VT_ERR_SINGULAR, named). How each is judged:
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "numeric/roundoff.h"
#include "base/arena.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"

/* Round-off of exact zeros. M*_aa and Φ_q's entries are sums whose terms cancel exactly at some
 * poses (a point mass on a rate's axis: v + ω × c = 0; a point drive at a spherical joint's
 * centre), and what is computed there is round-off of the terms' size, not a small inertia or a
 * small row. Each is judged against the magnitude of what it was summed from, never by itself:
 *   rate a   M*_aa = Σ_k m_k |v_a + ω_a × c_k|² + u^T J'_k u over the bodies k it moves, whose
 *            terms are T_a = Σ_k m_k (|v_a| + |ω_a| L_k)² (L_k ≥ |c_k − o|, the lengths c_k − o
 *            is summed from, vt_lengths_from_o: its round-off's size) and R_a = |ω_a|² Σ_k tr J'_k:
 *            round-off when M*_aa ≤ τ ε (T_a + R_a) (first order: the composite-inertia form
 *            s · Ī s about O subtracts terms of that size); the dense S^T M S by the second order
 *            (vt_rate_bounds)
 *   row r    Φ_q,ra = Σ_j Φ_x,rj S_ja over the row's two bodies, terms bounded by B_ra = Σ_j
 *            |Φ_x,rj| |S_ja|max (|S_ja| ≤ |v_a| + |ω_a| L_r for a position, ½ |ω_a| for an Euler
 *            parameter, 1 for a base body's own ṗ): round-off when ‖Φ_q,r‖ ≤ τ ε ‖B_r‖. A dot
 *            product's Φ_x is itself a sum, 2 (u × v)^T E: its Euler-parameter entries are taken
 *            as at least their terms' size, 2 |u| |v| = 2 (u ∥ v makes them round-off)
 * with τ = VT_ROUND_TAU (64) and ε = DBL_EPSILON. (v_a, ω_a) is rate a's twist (d->twist), the one
 * both paths build S and M* from. Joint drives' and couplings' rows are exact (unit entries), and
 * p^T p − 1's row is 2 p^T: not judged. */
void vt_rate_terms(const vt_model *m, const vt_data *d, double *w, double *T)
{
    for (int k = 0; k < 4; k++) w[k] = 0.0;
    vt_lengths_from_o(m, d, w + 1, 4); /* |c − o|, as the twists, with its round-off's size */
    for (int i = 1; i <= m->nbody; i++) {
        const double *J = m->body_inertia + 9 * i, mi = m->body_mass[i], rc = w[4 * i + 1];
        w[4 * i] = mi, w[4 * i + 1] = mi * rc, w[4 * i + 2] = mi * rc * rc;
        w[4 * i + 3] = fabs(J[0]) + fabs(J[4]) + fabs(J[8]);
    }
    vt_subtree_sum(m, w, 4);
    for (int a = 0; a < m->nv; a++) {
        const double *tw = d->twist + 6 * a, *s = w + 4 * m->dof_body[a];
        const double wn = sqrt(vt_dot3(tw, tw)), vn = sqrt(vt_dot3(tw + 3, tw + 3));
        T[2 * a] = vn * vn * s[0] + 2.0 * vn * wn * s[1] + wn * wn * s[2];
        T[2 * a + 1] = wn * wn * s[3];
    }
}

double vt_rate_roundoff(const double *T, int a)
{
    return VT_ROUND_TAU * DBL_EPSILON * (T[2 * a] + T[2 * a + 1]);
}

/* The dense M* = S^T M S: T_a = Σ_k m_k (|v_a| + |ω_a| len_ka)², len_ka the length of body k's
 * lever arm from rate a's joint as the dense S sums it (vt_lever: its round-off is ε len_ka, not
 * ε |c_k − o|), and R_a = |ω_a|² Σ_k tr J'_k (a base body's own ṗ too: 4 G^T J' G's diagonal). Its
 * translational part sums m |V_k|² over S's columns V_k: an exact zero (each V_k zero) comes out
 * as the square of their round-off, at most (τ ε)² T_a, and a real inertia keeps its digits; its
 * rotational part is a quadratic form in 4 G^T J' G, first order: τ ε R_a. */
static void dense_rate_bounds(const vt_model *m, const vt_data *d, double *T, double *beta)
{
    const int nv = m->nv;
    const double te = VT_ROUND_TAU * DBL_EPSILON;
    for (int a = 0; a < 2 * nv; a++) T[a] = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        const double *J = m->body_inertia + 9 * i, mi = m->body_mass[i];
        const double trJ = fabs(J[0]) + fabs(J[4]) + fabs(J[8]);
        vt_lever L;
        vt_lever_start(&L, m, d, i, 1);
        do {
            const int b = L.k;
            for (int a = m->body_vadr[b]; a < m->body_vadr[b] + m->body_nv[b]; a++) {
                int ax;
                const int kind = vt_dof_kind(m->body_joint[b], a - m->body_vadr[b], &ax);
                const double *tw = d->twist + 6 * a, wn = sqrt(vt_dot3(tw, tw));
                if (kind == VT_DOF_BASE_P && b == i) T[2 * a + 1] += wn * wn * trJ; /* 4 |G_a|² tr J' */
                else if (kind == VT_DOF_ROT || kind == VT_DOF_BASE_P) {
                    const double v = wn * L.len;
                    T[2 * a] += mi * v * v;
                    T[2 * a + 1] += wn * wn * trJ;
                } else T[2 * a] += mi;
            }
        } while (vt_lever_up(&L, m, d));
    }
    for (int a = 0; a < nv; a++) beta[a] = te * te * T[2 * a] + te * T[2 * a + 1];
}

int vt_rate_bounds(const vt_model *m, vt_data *d, vt_form form, double *beta)
{
    const size_t mark = vt_scratch_mark(d);
    double *T = VT_SCRATCH(d, double, 2 * (size_t)m->nv, "terms of M*'s diagonal");
    double *w = VT_SCRATCH(d, double, 4 * ((size_t)m->nbody + 1), "subtree sums");
    if (!w) return vt_scratch_fail(d, mark);
    if (form == VT_FORM_DENSE) dense_rate_bounds(m, d, T, beta);
    else {
        vt_rate_terms(m, d, w, T);
        for (int a = 0; a < m->nv; a++) beta[a] = vt_rate_roundoff(T, a);
    }
    vt_scratch_release(d, mark);
    return 0;
}

/* B_r (as above) into B (nv) for row r; returns ‖B_r‖ */
/* each rate's |ω_a|, |v_a| and whether it is a base body's ṗ rate (1, else 0), into T (3 nv):
 * what row_terms reads of every rate, once an instant */
static void rate_terms(const vt_model *m, const vt_data *d, double *T)
{
    for (int a = 0; a < m->nv; a++) {
        const double *tw = d->twist + 6 * a;
        const int b = m->dof_body[a];
        int ax = 0;
        T[3 * a] = sqrt(vt_dot3(tw, tw));
        T[3 * a + 1] = sqrt(vt_dot3(tw + 3, tw + 3));
        T[3 * a + 2] = vt_dof_kind(m->body_joint[b], a - m->body_vadr[b], &ax) == VT_DOF_BASE_P;
    }
}

/* row r's Φ_x on one side's body: the sizes of its position part (fr) and of its Euler-parameter
 * part (fp) */
static void side_sizes(const vt_model *m, const vt_data *d, int r, int side, double *fr, double *fp)
{
    const double *fx = d->Phix + 14 * (size_t)r + 7 * side;
    *fr = fabs(fx[0]) + fabs(fx[1]) + fabs(fx[2]);
    *fp = fabs(fx[3]) + fabs(fx[4]) + fabs(fx[5]) + fabs(fx[6]);
    if (m->con_kind[r] == VT_ROW_DOT) *fp = fmax(*fp, 2.0); /* 2 (u × v)^T E is itself a sum: |u| |v| = 1 */
}

static double row_terms(const vt_model *m, const vt_data *d, int r, double *B, const double *Lo, const double *T)
{
    for (int a = 0; a < m->nv; a++) B[a] = 0.0;
    for (int side = 0; side < 2; side++) {
        const int b = m->con_body[2 * r + side];
        if (b <= 0) continue;
        double fr, fp;
        side_sizes(m, d, r, side, &fr, &fp);
        const double rc = Lo[b]; /* |r_b − o|, as the twists, with its round-off's size (vt_lengths_from_o) */
        /* the path: one term a rate; b's own rates first (the walk meets them first), the only
         * ones whose Euler-parameter term can be their own ṗ's */
        int a = vt_last_rate(m, b);
        for (int k = 0; k < m->body_nv[b] && a >= 0; k++, a = m->dof_parent[a]) {
            const double wn = T[3 * a], vn = T[3 * a + 1];
            B[a] += fr * (vn + wn * rc) + fp * (T[3 * a + 2] != 0.0 ? 1.0 : 0.5 * wn);
        }
        for (; a >= 0; a = m->dof_parent[a]) {
            const double wn = T[3 * a], vn = T[3 * a + 1];
            B[a] += fr * (vn + wn * rc) + fp * (0.5 * wn);
        }
    }
    double n2 = 0.0;
    for (int a = 0; a < m->nv; a++) n2 += B[a] * B[a];
    return sqrt(n2);
}

/* row_terms's ‖B_r‖₁ bounded over every rate at once (sv, sw, sp: the sums of |v_a|, |ω_a| and
 * of the Euler-parameter terms' largest factor) */
static double row_bound(const vt_model *m, const vt_data *d, int r, const double *Lo, double sv, double sw, double sp)
{
    double u = 0.0;
    for (int side = 0; side < 2; side++) {
        const int b = m->con_body[2 * r + side];
        if (b <= 0) continue;
        double fr, fp;
        side_sizes(m, d, r, side, &fr, &fp);
        u += fr * (sv + sw * Lo[b]) + fp * sp;
    }
    return u;
}

static double row_norm(const vt_model *m, const vt_data *d, int r)
{
    double n2 = 0.0;
    for (int a = 0; a < m->nv; a++) n2 += d->Phiq[r + (size_t)a * (size_t)m->nc] * d->Phiq[r + (size_t)a * (size_t)m->nc];
    return sqrt(n2);
}

/* Rows that are round-off of a zero row, flagged 1 in flag (nc; NULL: not kept): the caller
 * takes them as zero rows, dependent (vt_rows_decide; vt_solve then names them). Then the rates whose M*_aa is round-off and that no
 * row (other than a flagged one) touches beyond round-off: VT_ERR_SINGULAR, named (nothing
 * fixes a motion that has no inertia). withM: M* is formed (else only the rows are judged).
 * Returns the number of rows flagged or a negative vt_status. */
int vt_roundoff_check(const vt_model *m, vt_data *d, int *flag, int withM, vt_form form)
{
    const int nv = m->nv, nc = m->nc;
    const size_t mark = vt_scratch_mark(d);
    double *B = VT_SCRATCH(d, double, (size_t)nv * ((size_t)nc + 1), "terms of Φ_q's rows");
    double *beta = VT_SCRATCH(d, double, (size_t)nv, "round-off of M*'s diagonal");
    double *Lo = VT_SCRATCH(d, double, (size_t)m->nbody + 1, "lengths from o");
    double *T = VT_SCRATCH(d, double, 3 * (size_t)nv, "the rates' terms");
    int *fl = VT_SCRATCH(d, int, nc + 1, "round-off rows");
    if (!fl) return vt_scratch_fail(d, mark);
    const double te = VT_ROUND_TAU * DBL_EPSILON;
    int zero_rows = 0;
    vt_lengths_from_o(m, d, Lo, 1);
    rate_terms(m, d, T);
    /* Without M* (the square and Schur routes) each row's B_r serves its judgement alone, and a row
     * well above the bound of every rate's terms at once, ‖B_r‖₂ ≤ ‖B_r‖₁ ≤ Σ_side f_r (Σ_a |v_a|
     * + Σ_a |ω_a| |r_b − o|) + f_p Σ_a max(1, ½ |ω_a|), is above its own: accepted at once, twice
     * that sum clear of its rounding, and B_r is formed only for the rest */
    double sv = 0.0, sw = 0.0, sp = 0.0;
    if (!withM)
        for (int a = 0; a < nv; a++) {
            sv += T[3 * a + 1], sw += T[3 * a];
            sp += T[3 * a + 2] != 0.0 ? fmax(1.0, 0.5 * T[3 * a]) : 0.5 * T[3 * a];
        }
    for (int r = 0; r < nc; r++) {
        double *Br = B + (size_t)r * (size_t)nv;
        fl[r] = 0;
        if (!vt_judged_row(m, r)) {
            for (int a = 0; a < nv; a++) Br[a] = 0.0; /* exact entries: any non-zero one counts */
            continue;
        }
        const double rn = row_norm(m, d, r);
        if (!withM && rn > 2.0 * te * row_bound(m, d, r, Lo, sv, sw, sp)) continue;
        const double bn = row_terms(m, d, r, Br, Lo, T);
        if (!(rn > te * bn)) fl[r] = 1, zero_rows++;
    }
    if (flag) memcpy(flag, fl, (size_t)nc * sizeof(int));
    if (withM) {
        const int st = vt_rate_bounds(m, d, form, beta);
        if (st < 0) return vt_scratch_release(d, mark), st;
        for (int a = 0; a < nv; a++) {
            const double maa = d->Mstar[a + (size_t)a * (size_t)nv];
            /* subnormal: its bound underflows, and it has lost its digits; near it, the dense stages decide */
            if (maa > beta[a] && maa >= (form == VT_FORM_DENSE ? DBL_MIN : VT_PIVOT_NORMAL)) continue;
            int held = 0;
            for (int r = 0; r < nc && !held; r++)
                held = !fl[r] && fabs(d->Phiq[r + (size_t)a * (size_t)nc]) > te * B[(size_t)r * (size_t)nv + (size_t)a];
            if (held) {
                /* the composite inertias about o cannot tell a non-zero M*_aa below their bound
                 * from none (a point mass 1e-6 m off a spherical joint's line: 5e-11 kg m² against
                 * a bound of 1e-10); the dense S^T M S, about each joint, can: it decides */
                if (form != VT_FORM_DENSE && maa != 0.0) return vt_scratch_release(d, mark), VT_ROUNDOFF_COMPOSITE;
                /* M* is semi-definite, so its row a is round-off too: exactly zero, as the dense
                 * path forms it, not a unit pivot once scaled */
                for (int b = 0; b < nv; b++) d->Mstar[a + (size_t)b * (size_t)nv] = d->Mstar[b + (size_t)a * (size_t)nv] = 0.0;
                continue;
            }
            const double bound = beta[a]; /* read before the scratch is released */
            vt_scratch_release(d, mark);
            /* the composite inertias about o cannot tell this inertia from round-off; S^T M S's
             * lever arms along the tree may (a body 1e9 m from its joint): the dense stages decide */
            if (form != VT_FORM_DENSE) return VT_ROUNDOFF_COMPOSITE;
            if (maa > bound) /* then below DBL_MIN */
                return vt_fail(d->message, VT_ERR_SINGULAR,
                               "vt_solve: singular: rate %d (body %d) has no inertia (M*_aa = %.3g is below the smallest "
                               "normal number, where it has lost its digits) and no row fixes it", a, m->dof_body[a], maa);
            return vt_fail(d->message, VT_ERR_SINGULAR,
                           "vt_solve: singular: rate %d (body %d) has no inertia (M*_aa = %.3g is below its round-off "
                           "%.3g) and no row fixes it", a, m->dof_body[a], maa, bound);
        }
    }
    vt_scratch_release(d, mark);
    return zero_rows;
}

int vt_zero_rows(const vt_model *m, vt_data *d)
{
    return m->nc > 0 ? vt_roundoff_check(m, d, NULL, 0, VT_FORM_TWISTS) : 0;
}

/* The same on the free rates alone (known[a] < 0; the others' q̈ known, as the recursive
 * articulated route takes joint-driven rates): a row whose part on the free rates is round-off
 * of zero, ‖Φ_q,rF‖ ≤ τ ε ‖B_rF‖, is dependent on the known rates' rows, though it is not zero
 * as a whole (a point drive whose point the free rates move by round-off only). Returns the
 * number of such rows or a negative vt_status. */
int vt_zero_rows_free(const vt_model *m, vt_data *d, const int *known)
{
    const int nv = m->nv, nc = m->nc;
    const size_t mark = vt_scratch_mark(d);
    double *B = VT_SCRATCH(d, double, (size_t)nv, "terms of Φ_q's row");
    double *Lo = VT_SCRATCH(d, double, (size_t)m->nbody + 1, "lengths from o");
    double *T = VT_SCRATCH(d, double, 3 * (size_t)nv, "the rates' terms");
    if (!T) return vt_scratch_fail(d, mark);
    const double te = VT_ROUND_TAU * DBL_EPSILON;
    int zero = 0;
    vt_lengths_from_o(m, d, Lo, 1);
    rate_terms(m, d, T);
    for (int r = 0; r < nc; r++) {
        if (!vt_judged_row(m, r)) continue;
        row_terms(m, d, r, B, Lo, T);
        double rn = 0.0, bn = 0.0;
        for (int a = 0; a < nv; a++) {
            if (known[a] >= 0) continue;
            const double v = d->Phiq[r + (size_t)a * (size_t)nc];
            rn += v * v, bn += B[a] * B[a];
        }
        zero += !(sqrt(rn) > te * sqrt(bn));
    }
    vt_scratch_release(d, mark);
    return zero;
}

/* The scratch roundoff.c takes at once: vt_roundoff_check's terms of Φ_q's rows (and a row for
 * the free rates), M*'s bounds, the lengths from o, the rates' terms and its flags, and inside it vt_rate_bounds'
 * terms of M*'s diagonal and subtree sums */
size_t vt_roundoff_scratch(const vt_model *m)
{
    const size_t snv = (size_t)m->nv, snc = (size_t)m->nc, nb1 = (size_t)m->nbody + 1;
    const size_t D = sizeof(double), I = sizeof(int);
    return VT_SCRATCH_BYTES(snv * (snc + 1), D) + VT_SCRATCH_BYTES(snv, D) + VT_SCRATCH_BYTES(nb1, D) +
           VT_SCRATCH_BYTES(3 * snv, D) + VT_SCRATCH_BYTES(snc + 1, I) + VT_SCRATCH_BYTES(2 * snv, D) + VT_SCRATCH_BYTES(4 * nb1, D);
}
