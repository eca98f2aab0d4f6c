/* The maximal-coordinate form of (2)-(5): every body's accelerations and every joint's wrench
 * as unknowns beside q̈ and λ, so that no equation sums the wrenches of a whole subtree. Used
 * where a route with free motion leaves its answer in doubt (solve.c: its estimate below
 * rcond_warn, or a joint drive's effort cancelling below √rcond_warn): a well-posed motion over
 * a spread of inertia (docs/accuracy.md, "Mass ratios"; docs/method.md, "The maximal-coordinate
 * route").
 *
 * Why: (5) is the Newton–Euler equations of the bodies with the joints' wrenches eliminated,
 * M* = Σ_i J_i^T M_i J_i and Q = Σ_i J_i^T (...). Where a tiny driven link carries a huge free
 * one, each entry of M* and Q carries the huge body, and the small link's effort is the
 * difference of terms 1e13 times its size: no factorization of M* recovers digits that M* and
 * Q no longer hold. Kept apart, the equations hold each body's terms at its own size, and LU
 * with partial pivoting on the equilibrated matrix solves them to a few ε.
 *
 * Unknowns, per body i (1..n) its angular and linear acceleration α_i, a_i (centre of mass,
 * global axes) and the wrench its joint transmits from the reference body, n_i (about the
 * centre of mass) and f_i; then q̈ (nv) and λ (nc). Equations, in this order (N = 12 n + nv + nc):
 *
 *   kinematics     α_i − J_ω,i q̈ = 2 E_i (Ṡq̇)_p,i,   a_i − J_v,i q̈ = (Ṡq̇)_r,i         (15)-(18)
 *                  J_v,i = S_r,i, J_ω,i = 2 E_i S_p,i: body i's rows of S (ω = 2 E ṗ, (16))
 *   Newton–Euler   J_i α_i − n_i + Σ_c [n_c + (r_c − r_i) × f_c] − Σ_r λ_r jw_r,i = −ω_i × J_i ω_i + n_e,i
 *                  m_i a_i − f_i + Σ_c f_c − Σ_r λ_r jv_r,i = m_i g + f_e,i
 *                  (c the bodies whose reference body is i; J_i = A_i J'_i A_i^T; r over the
 *                  Cartesian rows on body i, whose force is Φ_x^T λ (7): jv = Φ_r, jw = ½ E Φ_p)
 *   joints         J_k,a^T [n_k; f_k] + a_a q̈_a − Σ_r Φ_q,ra λ_r = qfrc_a − b_a q̇_a − f_a s(q̇_a)  for each rate a of body k's
 *                  joint (r over the joint drives and couplings: rows on rates, generalized)
 *   rows           Φ_q q̈ = γ                                                          (5)
 *
 * Eliminating a_i, α_i and the wrenches (J_k,a^T [n_k; f_k] telescopes to the sum over k's
 * subtree of J^T times its Newton–Euler residuals) gives (2) and Φ_q q̈ = γ exactly: the same
 * q̈ and λ. A row's force acts where the row acts (a tip drive on the tip): taken as a
 * generalized force on the rates instead, it brings back the sums over subtrees, and the
 * chain falling from 1e12 kg driven at its tip loses 1e4 ε again. Base bodies (their Euler
 * parameters are rates, with a p^T p − 1 row) are not taken; nor are mechanisms with more than
 * VT_MAXIMAL_MAX unknowns (the matrix is dense: N² doubles in the arena).
 *
 * Solve: LAPACK's dgeequb (row and column scaling by powers of two, so that each equation and
 * unknown is of one size whatever the units and masses), dgetrf, dgetrs, and one step of
 * iterative refinement (the residual b − A x from the assembly itself, not from a copy of A).
 *
 * Estimate: the reciprocal of the answer's componentwise (Skeel) condition, normwise over q̈
 * and over λ, each in the equilibrated unknowns,
 *
 *   κ_P = ‖(|Â^{-1}| (|Â| |x̂| + |b̂|))_P‖_∞ / ‖x̂_P‖_∞  (P: q̈, then λ),   1 / max(1, κ_q̈, κ_λ)
 *
 * (Â = R A C, x̂ = C^{-1} x, b̂ = R b): the relative change of q̈ and λ that relative changes of ε
 * in every entry of the matrix and the right side can cause, measured by LAPACK's dlacn2
 * (Higham's estimator, as dgerfs measures its error bound; numeric/skeel.c). It does
 * not see inertia spread that leaves the answer well determined. Relative to the answer itself
 * it does not see rows that lose their independence either (their multipliers grow with it):
 * solve.c bounds it by the rows' own condition and the grip, and takes this route only after a
 * route that solved (d->rcond on this route: docs/method.md, "The condition estimate").
 */
#include <stddef.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "numeric/maximal.h"
#include "numeric/skeel.h"
#include "kinematics/joint_effects.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/vec3.h"
#include "model/model.h"

/* where the assembly's entries go: into the matrix A (ld N); or, with x, entry · x_col (abs = 0:
 * A x) or |entry| |x_col| (abs = 1: |A| |x|) into w */
typedef struct {
    double *A;
    const double *x;
    double *w;
    int N, abs;
} sink;

static inline void put(sink *s, int r, int c, double v)
{
    if (s->A) s->A[r + (size_t)c * (size_t)s->N] += v;
    else if (s->abs) s->w[r] += fabs(v * s->x[c]);
    else s->w[r] += v * s->x[c];
}

static int generalized_row(const vt_model *m, int r)
{
    return m->con_kind[r] == VT_ROW_JOINT || m->con_kind[r] == VT_ROW_COUPLING;
}

int vt_maximal_size(const vt_model *m)
{
    /* base bodies; every rate joint-driven; as many rows as rates (the square route, whose
     * estimate is Φ_q's alone) */
    if (m->joint_mix < 0 || m->joint_driven || m->nc >= m->nv) return 0;
    const long N = 12L * m->nbody + m->nv + m->nc;
    return N <= VT_MAXIMAL_MAX ? (int)N : 0;
}

/* Where the maximal route may be tried after a route with free motion solved at estimate rcond:
 * below √rcond_warn (solve.c then decides: below rcond_warn, or where a joint drive's effort
 * cancels, which loses about ε / rcond² over a spread of inertia) */
int vt_maximal_wanted(const vt_model *m, double rcond)
{
    return rcond < sqrt(m->rcond_warn) && vt_maximal_size(m) > 0;
}

size_t vt_maximal_scratch(const vt_model *m)
{
    const int N = vt_maximal_size(m);
    if (!N) return 0;
    const size_t n = (size_t)N, D = sizeof(double);
    return VT_SCRATCH_BYTES(n * n, D) + 8 * VT_SCRATCH_BYTES(n, D) + 2 * VT_SCRATCH_BYTES(n, sizeof(int)) +
           VT_SCRATCH_BYTES((size_t)m->nv + (size_t)m->nc, D);
}

/* the matrix (into s) and, with b, the right side; column and row blocks as the top comment */
static void assemble(const vt_model *m, const vt_data *d, sink *s, double *b)
{
    const int n = m->nbody, nv = m->nv, nc = m->nc, iw = 6 * n, iq = 12 * n, il = 12 * n + nv;
    int path[VT_MAXIMAL_MAX]; /* a body's (nv < N ≤ VT_MAXIMAL_MAX), root first: the residual's sums' order */
    for (int i = 1; i <= n; i++) {
        const int o = vt_xoff(i), ka = 6 * (i - 1), kw = iw + 6 * (i - 1);
        const double *p = d->x + o + 3, *Ai = d->A + 9 * i, *w = d->omega + 3 * i, *xf = d->xfrc + 6 * i;
        const int np = vt_body_path(m, i, path);
        /* kinematics: α_i − J_ω q̈ = α⁰, a_i − J_v q̈ = a⁰ */
        for (int k = 0; k < 6; k++) put(s, ka + k, ka + k, 1.0);
        for (int c = 0; c < np; c++) {
            const double *Sc = d->S + (size_t)path[c] * (size_t)m->nx + (size_t)o;
            double jw[3];
            vt_mulEp(jw, p, Sc + 3);
            for (int k = 0; k < 3; k++) {
                put(s, ka + k, iq + path[c], -2.0 * jw[k]);
                put(s, ka + 3 + k, iq + path[c], -Sc[k]);
            }
        }
        /* Newton–Euler about the centre of mass: J α − n_i, m a − f_i */
        double J[9], Jw[3], g[3]; /* J = A J' A^T */
        const double *Jb = m->body_inertia + 9 * i;
        for (int k = 0; k < 3; k++)
            for (int l = 0; l < 3; l++) {
                double v = 0.0;
                for (int e = 0; e < 3; e++)
                    for (int f = 0; f < 3; f++) v += Ai[k + 3 * e] * Jb[e + 3 * f] * Ai[l + 3 * f];
                J[k + 3 * l] = v;
            }
        for (int k = 0; k < 3; k++) {
            for (int l = 0; l < 3; l++) put(s, kw + k, ka + l, J[k + 3 * l]);
            put(s, kw + 3 + k, ka + 3 + k, m->body_mass[i]);
            put(s, kw + k, kw + k, -1.0);
            put(s, kw + 3 + k, kw + 3 + k, -1.0);
        }
        if (b) {
            double a0[3];
            vt_mulEp(a0, p, d->Sdqd + o + 3);
            vt_mulmat3(Jw, J, w);
            vt_cross3(g, w, Jw);
            for (int k = 0; k < 3; k++) {
                b[ka + k] = 2.0 * a0[k];
                b[ka + 3 + k] = d->Sdqd[o + k];
                b[kw + k] = xf[3 + k] - g[k];
                b[kw + 3 + k] = m->body_mass[i] * m->gravity[k] + xf[k];
            }
        }
        /* the reference body's equations: + n_i + (r_i − r_j) × f_i, + f_i */
        const int j = m->body_parent[i];
        if (j > 0) {
            const int jw0 = iw + 6 * (j - 1);
            const double *ri = d->xrel + 6 * i, *rj = d->xrel + 6 * j;
            const double e[3] = {ri[0] - rj[0], ri[1] - rj[1], ri[2] - rj[2]};
            for (int k = 0; k < 3; k++) {
                put(s, jw0 + k, kw + k, 1.0);
                put(s, jw0 + 3 + k, kw + 3 + k, 1.0);
            }
            /* e × f as a matrix on f */
            put(s, jw0 + 0, kw + 4, -e[2]);
            put(s, jw0 + 0, kw + 5, e[1]);
            put(s, jw0 + 1, kw + 3, e[2]);
            put(s, jw0 + 1, kw + 5, -e[0]);
            put(s, jw0 + 2, kw + 3, -e[1]);
            put(s, jw0 + 2, kw + 4, e[0]);
        }
        /* the joint's rates: J_k,a^T [n; f] */
        for (int a = m->body_vadr[i]; a < m->body_vadr[i] + m->body_nv[i]; a++) {
            const double *Sc = d->S + (size_t)a * (size_t)m->nx + (size_t)o;
            double jw[3];
            vt_mulEp(jw, p, Sc + 3);
            for (int k = 0; k < 3; k++) {
                put(s, iq + a, kw + k, 2.0 * jw[k]);
                put(s, iq + a, kw + 3 + k, Sc[k]);
            }
            /* the joint's armature on its own q̈ (kinematics/joint_effects.c), its damping and
             * friction with the applied qfrc */
            if (m->has_effects && m->dof_effects[4 * a] != 0.0) put(s, iq + a, iq + a, m->dof_effects[4 * a]);
            if (b) b[iq + a] = vt_rate_force(m, d, a);
        }
    }
    for (int r = 0; r < nc; r++) {
        for (int a = 0; a < nv; a++) {
            const double v = d->Phiq[r + (size_t)a * (size_t)nc];
            if (v == 0.0) continue;
            put(s, il + r, iq + a, v);
            if (generalized_row(m, r)) put(s, iq + a, il + r, -v);
        }
        if (b) b[il + r] = d->gamma[r];
        if (generalized_row(m, r)) continue;
        for (int side = 0; side < 2; side++) { /* Φ_x^T λ on the row's bodies */
            const int bd = m->con_body[2 * r + side];
            if (bd == 0) continue;
            const double *px = d->Phix + 14 * r + 7 * side, *p = d->x + vt_xoff(bd) + 3;
            const int kw = iw + 6 * (bd - 1);
            double jw[3];
            vt_mulEp(jw, p, px + 3);
            for (int k = 0; k < 3; k++) {
                put(s, kw + k, il + r, -0.5 * jw[k]);
                put(s, kw + 3 + k, il + r, -px[k]);
            }
        }
    }
}

void vt_maximal_system(const vt_model *m, const vt_data *d, double *A, double *b)
{
    const size_t N = (size_t)vt_maximal_size(m);
    memset(A, 0, N * N * sizeof(double));
    sink s = {A, NULL, NULL, (int)N, 0};
    assemble(m, d, &s, b);
}

int vt_maximal_solve(const vt_model *m, vt_data *d, double *sol, double *rcond_out)
{
    *rcond_out = 0.0;
    const int N = vt_maximal_size(m), nv = m->nv, nc = m->nc, iq = 12 * m->nbody;
    if (!N) return 1;
    const size_t mark = vt_scratch_mark(d), sN = (size_t)N;
    double *A = VT_SCRATCH(d, double, sN * sN, "maximal-coordinate matrix");
    double *b = VT_SCRATCH(d, double, sN, "maximal-coordinate right side");
    double *x = VT_SCRATCH(d, double, sN, "maximal-coordinate solution");
    double *R = VT_SCRATCH(d, double, sN, "row scaling"), *C = VT_SCRATCH(d, double, sN, "column scaling");
    double *w = VT_SCRATCH(d, double, sN, "|A| |x| + |b|");
    double *v = VT_SCRATCH(d, double, sN, "dlacn2's v"), *z = VT_SCRATCH(d, double, sN, "dlacn2's x");
    int *ipiv = VT_SCRATCH(d, int, sN, "pivots"), *isgn = VT_SCRATCH(d, int, sN, "dlacn2's signs");
    if (!isgn) return vt_scratch_fail(d, mark);
    vt_maximal_system(m, d, A, b);
    if (!vt_all_finite(A, (int)(sN * sN)) || !vt_all_finite(b, N)) return vt_scratch_release(d, mark), 1;
    double rowcnd = 0.0, colcnd = 0.0, amax = 0.0;
    int info = 0;
    dgeequb_(&N, &N, A, &N, R, C, &rowcnd, &colcnd, &amax, &info);
    if (info != 0) return vt_scratch_release(d, mark), 1; /* a zero row or column: singular */
    for (int c = 0; c < N; c++)
        for (int r = 0; r < N; r++) A[r + (size_t)c * sN] *= R[r] * C[c];
    dgetrf_(&N, &N, A, &N, ipiv, &info);
    if (info != 0) return vt_scratch_release(d, mark), 1; /* an exactly zero pivot */
    for (int r = 0; r < N; r++) x[r] = R[r] * b[r];
    if (vt_lu_solve("N", A, ipiv, N, x)) return vt_scratch_release(d, mark), 1;
    for (int c = 0; c < N; c++) x[c] *= C[c]; /* x = C x̂ */
    if (!vt_all_finite(x, N)) return vt_scratch_release(d, mark), 1;
    /* one step of refinement with the residual in working precision: a componentwise small
     * backward error (Skeel), which the estimate below presumes */
    for (int r = 0; r < N; r++) w[r] = 0.0;
    sink t = {NULL, x, w, N, 0};
    assemble(m, d, &t, NULL);
    for (int r = 0; r < N; r++) z[r] = R[r] * (b[r] - w[r]);
    if (vt_lu_solve("N", A, ipiv, N, z)) return vt_scratch_release(d, mark), 1;
    for (int c = 0; c < N; c++) x[c] += C[c] * z[c];
    if (!vt_all_finite(x, N)) return vt_scratch_release(d, mark), 1;
    /* w = R (|A| |x| + |b|) = |Â| |x̂| + |b̂| */
    for (int r = 0; r < N; r++) w[r] = fabs(b[r]);
    t.abs = 1;
    assemble(m, d, &t, NULL);
    for (int r = 0; r < N; r++) w[r] *= R[r];
    /* κ of q̈ and of λ, each over its own entries: one normwise over both would let a large λ
     * hide q̈'s loss (and the reverse) */
    double kappa = 1.0;
    for (int part = 0; part < 2; part++) {
        const int lo = part ? iq + nv : iq, hi = part ? N : iq + nv;
        double xmax = 0.0;
        for (int r = lo; r < hi; r++) xmax = fmax(xmax, fabs(x[r] / C[r]));
        if (lo == hi) continue;
        const double est = vt_skeel_norm(A, ipiv, N, w, NULL, lo, hi, v, z, isgn);
        if (est < 0.0) return vt_scratch_release(d, mark), 1;
        const double k = xmax > 0.0 ? est / xmax : est > 0.0 ? HUGE_VAL : 1.0;
        kappa = fmax(kappa, k);
    }
    *rcond_out = 1.0 / kappa;
    memcpy(sol, x + iq, ((size_t)nv + (size_t)nc) * sizeof(double));
    vt_scratch_release(d, mark);
    return 0;
}
