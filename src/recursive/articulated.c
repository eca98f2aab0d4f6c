/* The articulated route of the recursive evaluation: fewer rows than rates, no base body.
 *
 * (2) and Φ_q q̈ = γ by articulated bodies (Featherstone's recursion: articulated_solve_nr, whose
 * comment holds its equations; O(n) per right side, M* is not formed). Each body's articulated
 * inertia, bias wrenches and twists are taken about its own joint point P_i and passed to the
 * parent by the short P_i − P_j, so that round-off grows with the subtrees' extent, not with the
 * distance from O. The reactions then come from W̄ = Σ (W⁰ + I T) (W⁰ the needed wrench at
 * q̈ = 0, kinematics/body.h), which the inward pass's I^A and p give without the sum and without
 * the rows' loads (vt_articulated_instant). A joint-driven rate's q̈ is known (f'' = γ): only the
 * free rates are solved and only the other rows enter S; each joint drive's multiplier follows
 * as s_a · W̄_i − qfrc_a (= (M* q̈ − Q − Φ_q,o^T λ_o)_a), and when every row is a joint drive
 * (joint_rows_only) the inward pass of recursive/fused.c gives them (vt_articulated_free_rates).
 * rcond is the other rows' S's exact condition at unit diagonal (1 for one row, none without)
 * times min/max of M*_FF's pivots (the free rates') taken leaf first, each over its diagonal
 * entry, times the point drives' grip²: the number vt_solve's Schur route reports on the same
 * system (it takes the driven rates as known too). A pivot below 1e-8 or round-off of 0
 * (VT_FALLBACK_ARTICULATED_PIVOT) or rcond below rcond_min (VT_FALLBACK_ARTICULATED_CONDITION)
 * hands the instant to the general route (recursive/general.c, below this file).
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "recursive/articulated.h"
#include "kinematics/joint_effects.h"
#include "recursive/general.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/body.h"
#include "kinematics/kinematics.h"
#include "dense/constraints.h"
#include "dense/reactions.h"
#include "dense/solve.h"
#include "numeric/kkt.h"
#include "numeric/rank.h"
#include "numeric/roundoff.h"
#include "numeric/route.h"

/* G = body inertia I (vt_body_inertia's form) as a full 6x6, columns of 8 (the last two zero, so that
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

/* a composite inertia (m, h, J) about P_i (13 numbers, vt_body_inertia's form) added about P_j:
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
        vt_body_inertia_bias(Ic + 13 * i, p, m, d, i, L + 6 * i);
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
            /* the joint's armature is inertia of the rate's own, exact (kinematics/joint_effects.c) */
            const double arm = m->has_effects ? m->dof_effects[4 * a] : 0.0;
            const double Da = vt_dot3(e, Ua + off) + arm, ee = vt_dot3(e, e);
            double maa, tw2;
            if (off == 0) {
                double Je[3];
                vt_mulmat3(Je, Ii + 4, e);
                maa = vt_dot3(e, Je) + arm;
                tw2 = ee * (Ii[4] + Ii[8] + Ii[12]);
            } else {
                maa = Ii[0] * ee + arm;
                tw2 = Ii[0] * ee;
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
            ua[0] = vt_rate_force(m, d, a) - vt_dot3(e, p + off); /* qfrc less the joint's damping, friction */
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
    double grip = 1.0;
    const int sg = nc > 0 ? vt_rows_grip(m, d, &grip) : 0;
    if (sg) return sg;
    rcond *= pmin / pmax * grip;
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
vt_status vt_articulated_instant(const vt_model *m, vt_data *d, vt_handoff *to)
{
    *to = VT_HANDOFF_NONE;
    double rcond = 0.0;
    const int nr = aba_sides(m);
    /* a row that is round-off of zero would pass for a row once S is at unit diagonal: the
     * general route names it */
    int zero_rows = vt_zero_rows(m, d);
    /* with joint-driven rates known (articulated_solve), a row that only they move beyond
     * round-off is round-off on the free rates: dependent on their drives */
    if (zero_rows == 0 && nr <= m->nc) zero_rows = vt_zero_rows_free(m, d, m->dof_drive);
    if (zero_rows < 0) return (vt_status)zero_rows;
    if (zero_rows > 0) return vt_factorized_instant(m, d, to);
    const size_t mark = vt_scratch_mark(d), sr = 6 * (size_t)nr;
    aba_work w;
    if (aba_take(m, d, nr, &w)) return vt_scratch_fail(d, mark);
    const int r = articulated_solve(m, d, &w, &rcond);
    if (r || vt_maximal_instead(m, d, VT_ROUTE_ARTICULATED, rcond)) {
        vt_scratch_release(d, mark);
        if (r < 0) return (vt_status)r;
        if (r) return vt_factorized_instant(m, d, to);
        d->fallback |= VT_FALLBACK_ARTICULATED_CONDITION;
        *to = VT_HANDOFF_MAXIMAL; /* solved, but the maximal route may be wanted: the dense stages decide */
        return VT_OK;
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
            /* a known joint drive's multiplier: (M* q̈ − Q − Φ_q,o^T λ_o)_a = s_a · W̄_i − qfrc_a
             * (qfrc less the joint's own effects: vt_rate_load),
             * W̄_i about P_i here, without the other rows' loads; s_a about P_i (e at off) */
            const int k = m->dof_drive[a];
            if (k < 0) continue;
            double e[3];
            int off;
            twist_at_joint(e, &off, m, d, i, a);
            d->lambda[m->drive_row[k]] = vt_dot3(e, Wi + off) - vt_rate_load(m, d, a);
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

/* the free rates of a model whose rows are all joint drives (joint_rows_only), by articulated
 * bodies: q̈ with rcond; 0, 1 (the general route decides) or a negative vt_status */
int vt_articulated_free_rates(const vt_model *m, vt_data *d, double *rcond)
{
    const size_t mark = vt_scratch_mark(d);
    aba_work w;
    const int r = aba_take(m, d, 1, &w) ? VT_ERR_NO_MEMORY : articulated_solve(m, d, &w, rcond);
    vt_scratch_release(d, mark);
    return r;
}

/* the scratch this file takes at once: the work for every row as a right side, or for Q alone */
size_t vt_articulated_scratch(const vt_model *m)
{
    const size_t n = aba_bytes(m, m->nc + 1), one = aba_bytes(m, 1);
    return one > n ? one : n;
}
