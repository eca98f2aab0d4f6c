/* The augmented system of the paper's (5):
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 *
 * so that M* q̈ = Q + Φ_q^T λ (2) and Φ_q q̈ = γ.
 *
 * Why this factorization: the matrix is symmetric and indefinite (a saddle point: M* is
 * positive definite on the motions the constraints allow, the zero block makes it
 * indefinite), so Cholesky does not apply and LU would ignore the symmetry. LAPACK's
 * LDL^T with bounded Bunch–Kaufman (rook) pivoting (dsytrf_rk / dsytrs_3 / dsycon_3) uses the
 * symmetry (half LU's work and storage), its 1x1/2x2 pivots are stable for indefinite matrices,
 * and the rook variant bounds the entries of L (and its BLAS-3 solves are cheaper than
 * dsytrs/dsycon's BLAS-2 loops at these sizes).
 * Before factorizing, the matrix is scaled symmetrically (its rows and columns mix units:
 * kg·m², kg, m, rad); how, is said where it is done. Every route reports a condition estimate
 * of the pose (docs/method.md, "The condition estimate"): independent of units, of the scene's
 * frame and of inertia spread alone, the same number on the recursive path's routes. Round-off
 * of an exact zero is neither a row nor an inertia (roundoff_check). A system whose
 * estimate falls below rcond_min is refused: rows of Φ_q that are dependent to round-off (the
 * SVD of a frame- and unit-independent scaling of Φ_q, rows_decide) are named
 * (VT_ERR_DEPENDENT_CONSTRAINTS); otherwise the matrix is singular (a rate or body without
 * inertia that nothing fixes, named; an exactly zero pivot) or only ill-conditioned, and
 * VT_ERR_SINGULAR's message says which. Two other paths, each said where it is done: as many
 * rows as rates (LU of Φ_q alone, square_solve) and, for models that allow redundant rows,
 * (5) on the independent directions of the rows by SVD (redundant_solve).
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <stdio.h>
#include <string.h>

#include "dense/solve.h"
#include "base/arena.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "numeric/maximal.h"

static const char *owner_name(const vt_model *m, int row, char *buf, size_t n)
{
    const int kind = vt_row_owner_kind(m, row);
    if (kind == VT_OWNER_DRIVE) snprintf(buf, n, "drive %d", m->con_owner[row]);
    else if (kind == VT_OWNER_CUT) snprintf(buf, n, "cut joint %d", m->con_owner[row]);
    else if (kind == VT_OWNER_COUPLING) snprintf(buf, n, "coupling %d", m->con_owner[row]);
    else snprintf(buf, n, "p^T p = 1 of body %d", m->con_owner[row]);
    return buf;
}

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

int vt_rate_bounds(const vt_model *m, vt_data *d, int dense, double *beta)
{
    const size_t mark = vt_scratch_mark(d);
    double *T = VT_SCRATCH(d, double, 2 * (size_t)m->nv, "terms of M*'s diagonal");
    double *w = VT_SCRATCH(d, double, 4 * ((size_t)m->nbody + 1), "subtree sums");
    if (!w) return vt_scratch_fail(d, mark);
    if (dense) dense_rate_bounds(m, d, T, beta);
    else {
        vt_rate_terms(m, d, w, T);
        for (int a = 0; a < m->nv; a++) beta[a] = vt_rate_roundoff(T, a);
    }
    vt_scratch_release(d, mark);
    return 0;
}

/* rows that Φ_x S builds (points, lines, dot products, orientations) */
static int judged_row(const vt_model *m, int r)
{
    const int kind = m->con_kind[r];
    return kind != VT_ROW_JOINT && kind != VT_ROW_COUPLING && kind != VT_ROW_NORM;
}

/* B_r (as above) into B (nv) for row r; returns ‖B_r‖ */
static double row_terms(const vt_model *m, const vt_data *d, int r, double *B, const double *Lo)
{
    for (int a = 0; a < m->nv; a++) B[a] = 0.0;
    for (int side = 0; side < 2; side++) {
        const int b = m->con_body[2 * r + side];
        if (b <= 0) continue;
        const double *fx = d->Phix + 14 * (size_t)r + 7 * side;
        const double fr = fabs(fx[0]) + fabs(fx[1]) + fabs(fx[2]);
        double fp = fabs(fx[3]) + fabs(fx[4]) + fabs(fx[5]) + fabs(fx[6]);
        if (m->con_kind[r] == VT_ROW_DOT) fp = fmax(fp, 2.0); /* 2 (u × v)^T E is itself a sum: |u| |v| = 1 */
        const double rc = Lo[b]; /* |r_b − o|, as the twists, with its round-off's size (vt_lengths_from_o) */
        const int *path = m->path_dof + m->body_pathadr[b];
        for (int k = 0; k < m->body_pathnum[b]; k++) {
            const int a = path[k];
            const double *tw = d->twist + 6 * a, wn = sqrt(vt_dot3(tw, tw)), vn = sqrt(vt_dot3(tw + 3, tw + 3));
            int ax = 0;
            const int own_p = m->dof_body[a] == b && vt_dof_kind(m->body_joint[b], a - m->body_vadr[b], &ax) == VT_DOF_BASE_P;
            B[a] += fr * (vn + wn * rc) + fp * (own_p ? 1.0 : 0.5 * wn);
        }
    }
    double n2 = 0.0;
    for (int a = 0; a < m->nv; a++) n2 += B[a] * B[a];
    return sqrt(n2);
}

static double row_norm(const vt_model *m, const vt_data *d, int r)
{
    double n2 = 0.0;
    for (int a = 0; a < m->nv; a++) n2 += d->Phiq[r + (size_t)a * (size_t)m->nc] * d->Phiq[r + (size_t)a * (size_t)m->nc];
    return sqrt(n2);
}

/* Rows that are round-off of a zero row, flagged 1 in flag (nc; NULL: not kept): the caller
 * takes them as zero rows, dependent (rows_decide; vt_solve then names them). Then the rates whose M*_aa is round-off and that no
 * row (other than a flagged one) touches beyond round-off: VT_ERR_SINGULAR, named (nothing
 * fixes a motion that has no inertia). withM: M* is formed (else only the rows are judged).
 * Returns the number of rows flagged or a negative vt_status. */
#define ROUNDOFF_COMPOSITE (-1000) /* below every vt_status */
static int roundoff_check(const vt_model *m, vt_data *d, int *flag, int withM, int dense)
{
    const int nv = m->nv, nc = m->nc;
    const size_t mark = vt_scratch_mark(d);
    double *B = VT_SCRATCH(d, double, (size_t)nv * ((size_t)nc + 1), "terms of Φ_q's rows");
    double *beta = VT_SCRATCH(d, double, (size_t)nv, "round-off of M*'s diagonal");
    double *Lo = VT_SCRATCH(d, double, (size_t)m->nbody + 1, "lengths from o");
    int *fl = VT_SCRATCH(d, int, nc + 1, "round-off rows");
    if (!fl) return vt_scratch_fail(d, mark);
    const double te = VT_ROUND_TAU * DBL_EPSILON;
    int zero_rows = 0;
    vt_lengths_from_o(m, d, Lo, 1);
    for (int r = 0; r < nc; r++) {
        double *Br = B + (size_t)r * (size_t)nv;
        fl[r] = 0;
        if (!judged_row(m, r)) {
            for (int a = 0; a < nv; a++) Br[a] = 0.0; /* exact entries: any non-zero one counts */
            continue;
        }
        const double bn = row_terms(m, d, r, Br, Lo), rn = row_norm(m, d, r);
        if (!(rn > te * bn)) fl[r] = 1, zero_rows++;
    }
    if (flag) memcpy(flag, fl, (size_t)nc * sizeof(int));
    if (withM) {
        const int st = vt_rate_bounds(m, d, dense, beta);
        if (st < 0) return vt_scratch_release(d, mark), st;
        for (int a = 0; a < nv; a++) {
            const double maa = d->Mstar[a + (size_t)a * (size_t)nv];
            /* subnormal: its bound underflows, and it has lost its digits; near it, the dense stages decide */
            if (maa > beta[a] && maa >= (dense ? DBL_MIN : VT_PIVOT_NORMAL)) continue;
            int held = 0;
            for (int r = 0; r < nc && !held; r++)
                held = !fl[r] && fabs(d->Phiq[r + (size_t)a * (size_t)nc]) > te * B[(size_t)r * (size_t)nv + (size_t)a];
            if (held) {
                /* the composite inertias about o cannot tell a non-zero M*_aa below their bound
                 * from none (a point mass 1e-6 m off a spherical joint's line: 5e-11 kg m² against
                 * a bound of 1e-10); the dense S^T M S, about each joint, can: it decides */
                if (!dense && maa != 0.0) return vt_scratch_release(d, mark), ROUNDOFF_COMPOSITE;
                /* M* is semi-definite, so its row a is round-off too: exactly zero, as the dense
                 * path forms it, not a unit pivot once scaled */
                for (int b = 0; b < nv; b++) d->Mstar[a + (size_t)b * (size_t)nv] = d->Mstar[b + (size_t)a * (size_t)nv] = 0.0;
                continue;
            }
            const double bound = beta[a]; /* read before the scratch is released */
            vt_scratch_release(d, mark);
            /* the composite inertias about o cannot tell this inertia from round-off; S^T M S's
             * lever arms along the tree may (a body 1e9 m from its joint): the dense stages decide */
            if (!dense) return ROUNDOFF_COMPOSITE;
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
    return m->nc > 0 ? roundoff_check(m, d, NULL, 0, 0) : 0;
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
    if (!Lo) return vt_scratch_fail(d, mark);
    const double te = VT_ROUND_TAU * DBL_EPSILON;
    int zero = 0;
    vt_lengths_from_o(m, d, Lo, 1);
    for (int r = 0; r < nc; r++) {
        if (!judged_row(m, r)) continue;
        row_terms(m, d, r, B, Lo);
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

/* Small systems (n ≤ EXACT_RCOND_N): the exact 1-norm reciprocal condition from the inverse
 * itself, the factors applied to the identity in one multi-right-hand-side solve (as much work
 * as the factorization), costs fewer instructions than LAPACK's estimators (dgecon, dsycon_3:
 * iterations of overflow-guarded triangular solves, dlatrs) and is exact, not a bound.
 * small_inverse takes the identity X (n x n) with `extra` columns after it from the arena, or
 * returns NULL for a larger n (the caller then estimates) or when the arena failed (the
 * caller's next allocation says so). */
#define EXACT_RCOND_N 16
#define EXACT_EXTRA 2 /* most extra columns asked for */
static double *small_inverse(vt_data *d, int n, int extra)
{
    if (n > EXACT_RCOND_N) return NULL;
    double *X = VT_SCRATCH(d, double, (size_t)n * (size_t)(n + extra), "exact inverse");
    if (!X) return NULL;
    memset(X, 0, (size_t)n * (size_t)n * sizeof(double));
    for (int k = 0; k < n; k++) X[k + (size_t)k * (size_t)n] = 1.0;
    return X;
}

static double rcond_from_inverse(const double *X, int n, double anorm)
{
    double xn = 0.0;
    for (int c = 0; c < n; c++) {
        double cs = 0.0;
        for (int r = 0; r < n; r++) cs += fabs(X[r + (size_t)c * (size_t)n]);
        xn = cs > xn ? cs : xn; /* fmax without the call (a NaN is skipped by both) */
    }
    return anorm > 0.0 && xn > 0.0 ? 1.0 / (anorm * xn) : 0.0;
}

/* Cholesky of the symmetric n x n K (its lower triangle; 1-norm anorm) and its reciprocal
 * condition into *rcond (0 when K is not positive definite): exact from the inverse for n ≤ 16,
 * which then also solves, dpocon's estimate above; once factorized, b (n) is solved in place.
 * Returns 0 or a negative vt_status. */
static int chol_solve(vt_data *d, double *K, int n, double anorm, double *b, double *rcond)
{
    int info = 0;
    *rcond = 0.0;
    dpotf2_("L", &n, K, &n, &info, 1);
    if (info < 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotf2 info %d", info);
    if (info > 0) return 0;
    const size_t mark = vt_scratch_mark(d);
    double *X = small_inverse(d, n, 1);
    if (X) { /* K^-1 and the solution in one solve: [I, b] */
        const int ncol = n + 1;
        double *xb = X + (size_t)n * (size_t)n;
        memcpy(xb, b, (size_t)n * sizeof(double));
        dpotrs_("L", &n, &ncol, K, &n, X, &n, &info, 1);
        if (info == 0) {
            *rcond = rcond_from_inverse(X, n, anorm);
            memcpy(b, xb, (size_t)n * sizeof(double));
        }
        vt_scratch_release(d, mark);
        return info ? vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotrs info %d", info) : 0;
    }
    double *work = VT_SCRATCH(d, double, 3 * (size_t)n, "dpocon workspace");
    int *iwork = VT_SCRATCH(d, int, n, "dpocon integer workspace");
    if (!iwork) return vt_scratch_fail(d, mark);
    dpocon_("L", &n, K, &n, &anorm, rcond, work, iwork, &info, 1);
    vt_scratch_release(d, mark);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpocon info %d", info);
    const int one = 1;
    dpotrs_("L", &n, &one, K, &n, b, &n, &info, 1);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotrs info %d", info);
    return 0;
}

/* *out = the 1-norm of the symmetric n x n K from its lower triangle (LAPACK's dlansy) */
static int norm1_sym(vt_data *d, const double *K, int n, double *out)
{
    const size_t mark = vt_scratch_mark(d);
    double *work = VT_SCRATCH(d, double, n, "dlansy workspace");
    if (!work) return vt_scratch_fail(d, mark);
    *out = dlansy_("1", "L", &n, K, &n, work, 1, 1);
    vt_scratch_release(d, mark);
    return 0;
}

int vt_solve_spd(vt_data *d, double *S, int n, double *b, double *rcond)
{
    /* S to unit diagonal first (E S E, E = diag(S_rr^(-1/2)); b by E, the solution by E after):
     * its condition then measures how independent the rows are, not their sizes */
    for (int r = 0; r < n; r++) {
        const double srr = S[r + (size_t)r * (size_t)n];
        if (!(srr > 0.0)) return *rcond = 0.0, 0; /* not positive definite: nothing solved */
    }
    for (int c = 0; c < n; c++) {
        const double ec = 1.0 / sqrt(S[c + (size_t)c * (size_t)n]);
        for (int r = c + 1; r < n; r++) S[r + (size_t)c * (size_t)n] *= ec / sqrt(S[r + (size_t)r * (size_t)n]);
    }
    double *e = NULL;
    const size_t mark = vt_scratch_mark(d);
    if (n > 0 && !(e = VT_SCRATCH(d, double, n, "unit diagonal"))) return vt_scratch_fail(d, mark);
    for (int r = 0; r < n; r++) {
        const double er = 1.0 / sqrt(S[r + (size_t)r * (size_t)n]);
        if (e) e[r] = er;
        b[r] *= er;
        S[r + (size_t)r * (size_t)n] = 1.0;
    }
    int st = 0;
    if (n <= 1) *rcond = 1.0; /* one row: S is 1, its condition exactly 1, b solved */
    else {
        double snorm = 0.0;
        st = norm1_sym(d, S, n, &snorm);
        if (!st) st = chol_solve(d, S, n, snorm, b, rcond);
    }
    for (int r = 0; r < n && e; r++) b[r] *= e[r];
    vt_scratch_release(d, mark);
    return st;
}

/* The symmetric scaling D of (5): the rates by the mass metric, d_a = M*_aa^(-1/2), into
 * s[0..nv); with rows, each constraint row by its own norm in that metric, 1 / ‖(Φ_q D)_r‖, into
 * s[nv..nv+nc) (a row without entries: 1). Row by row, so that rows on bodies of very different
 * masses (a joint drive on a 1e-9 kg link beside p^T p − 1 on a 30 kg base) are not taken for
 * rows losing their grip; a row that does lose its grip (a point drive at an arm's full
 * stretch) is measured apart, vt_rows_grip. scaling_diag: the rates' part from M*'s diagonal
 * mdiag[a stride] (s may be mdiag itself with stride 1). */
static void scaling_diag(const vt_model *m, const double *mdiag, int stride, double *s)
{
    for (int a = 0; a < m->nv; a++) {
        const double mii = mdiag[(size_t)a * (size_t)stride];
        s[a] = mii > 0.0 ? 1.0 / sqrt(mii) : 1.0;
    }
}

static void scaling(const vt_model *m, const vt_data *d, double *s, int rows)
{
    const int nv = m->nv, nc = m->nc;
    scaling_diag(m, d->Mstar, nv + 1, s);
    if (!rows) return;
    for (int r = 0; r < nc; r++) {
        double rn = 0.0;
        for (int c = 0; c < nv; c++) {
            const double v = d->Phiq[r + (size_t)c * (size_t)nc] * s[c];
            rn += v * v;
        }
        s[nv + r] = rn > 0.0 ? 1.0 / sqrt(rn) : 1.0;
    }
}

/* A point drive's grip: the row is e · V_a, V_a = v_a + ω_a × P the velocity rate a's twist
 * gives the driven point P; the whole of V_a is what the rates can move the point by, the row
 * what of it lies along the driven direction e. Its grip is the ratio of the two, in the
 * rates' kinematic scaling (the square route's C: rates that turn by 1/ℓ, ℓ the rows' lever arm,
 * rows_length):
 *   grip_r = ‖(e · V_a C_a)_a‖ / ‖(|V_a| C_a)_a‖   in [0, 1]
 * 1 while the rates move P along e as well as across it, 0 where no rate moves P along e (an
 * arm stretched along e: a row that has lost its grip, with nothing else to show it when it is
 * the only row). Independent of the units, of the scene's frame and position, and of the
 * inertias. vt_rows_grip returns the smallest grip² over the point drives' rows (1 without). */
static double rows_length(const vt_model *m, const vt_data *d, const int *flag);
double vt_rows_grip(const vt_model *m, const vt_data *d)
{
    double worst = 1.0, rho = 0.0; /* ℓ */
    for (int r = 0; r < m->nc; r++) {
        if (m->con_kind[r] != VT_ROW_POINT || vt_row_owner_kind(m, r) != VT_OWNER_DRIVE) continue;
        if (rho == 0.0) rho = rows_length(m, d, NULL);
        const vt_drive_def *dr = m->drive + m->con_owner[r];
        const int b = dr->body;
        const double *A = d->A + 9 * b, *c = d->xrel + 6 * b; /* from o, as the twists */
        double P[3];
        vt_mulmat3(P, A, dr->point);
        for (int k = 0; k < 3; k++) P[k] += c[k];
        double num = 0.0, den = 0.0;
        const int *path = m->path_dof + m->body_pathadr[b];
        for (int k = 0; k < m->body_pathnum[b]; k++) {
            const int a = path[k], i = m->dof_body[a];
            const double *tw = d->twist + 6 * a;
            int ax = 0;
            const int kind = vt_dof_kind(m->body_joint[i], a - m->body_vadr[i], &ax);
            const double ca = kind == VT_DOF_ROT || kind == VT_DOF_BASE_P ? 1.0 / rho : 1.0;
            double V[3];
            vt_copy3(V, tw + 3);
            vt_addcross3(V, tw, P);
            const double e = d->Phiq[r + (size_t)a * (size_t)m->nc] * ca;
            num += e * e;
            den += vt_dot3(V, V) * ca * ca;
        }
        const double g2 = den > 0.0 ? num / den : 0.0;
        worst = g2 < worst ? g2 : worst;
    }
    return worst;
}

/* Factor and solve the augmented system of (5) into b = [q̈; −λ] (nv + nc); the condition
 * estimate into *rcond_out. Returns 0, 1 (below rcond_min: nothing solved) or a negative
 * vt_status. */
static int factor_solve(const vt_model *m, vt_data *d, double *b, double *rcond_out)
{
    const int nv = m->nv, nc = m->nc, nr = nc, N = nv + nr, one = 1;
    const size_t ld = (size_t)N, mark = vt_scratch_mark(d);
    double *K = VT_SCRATCH(d, double, ld * ld, "augmented matrix");
    double *s = VT_SCRATCH(d, double, N, "scaling"), *E = VT_SCRATCH(d, double, N, "D's off-diagonal");
    double *res = VT_SCRATCH(d, double, 2 * ld, "refinement residual");
    int *ipiv = VT_SCRATCH(d, int, N, "pivots");
    if (!ipiv) return vt_scratch_fail(d, mark);
#define PHI(r, c) d->Phiq[(size_t)(r) + (size_t)(c) * (size_t)nc]
    /* lower triangle: M* then the rows of Φ_q below it, zero block */
    for (int c = 0; c < nv; c++) {
        for (int r = c; r < nv; r++) K[r + c * ld] = d->Mstar[r + (size_t)c * (size_t)nv];
        for (int r = 0; r < nr; r++) K[nv + r + c * ld] = PHI(r, c);
    }
    for (int c = nv; c < N; c++)
        for (int r = c; r < N; r++) K[r + c * ld] = 0.0;
    memcpy(b, d->Q, (size_t)nv * sizeof(double));
    for (int r = 0; r < nr; r++) b[nv + r] = d->gamma[r];

    /* symmetric scaling D K D (scaling()) */
    scaling(m, d, s, 1);
    for (int c = 0; c < N; c++) {
        for (int r = c; r < N; r++) K[r + c * ld] *= s[r] * s[c];
        b[c] *= s[c];
    }

    int info = 0, lwork = 0, st = 0;
    double anorm = 0.0;
    if ((st = norm1_sym(d, K, N, &anorm))) return vt_scratch_release(d, mark), st;
    const size_t mark_work = vt_scratch_mark(d);
    double *work = vt_scratch_rest(d, 2 * ld, sizeof(double), &lwork, "dsytrf_rk workspace");
    if (!work) return vt_scratch_fail(d, mark);
    dsytrf_rk_("L", &N, K, &N, E, ipiv, work, &lwork, &info, 1);
    vt_scratch_release(d, mark_work);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrf_rk info %d", info);
    double rcond = 0.0;
    double *X = info == 0 ? small_inverse(d, N, 0) : NULL;
    const int inverse = X != NULL;
    if (inverse) {
        dsytrs_3_("L", &N, &N, K, &N, E, ipiv, X, &N, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs_3 info %d", info);
        rcond = rcond_from_inverse(X, N, anorm);
    } else if (info == 0) {
        work = VT_SCRATCH(d, double, 2 * ld, "dsycon_3 workspace");
        int *iwork = VT_SCRATCH(d, int, N, "dsycon_3 integer workspace");
        if (!iwork) return vt_scratch_fail(d, mark);
        dsycon_3_("L", &N, K, &N, E, ipiv, &anorm, &rcond, work, iwork, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsycon_3 info %d", info);
    }
    if (nc > 0) rcond *= vt_rows_grip(m, d);
    *rcond_out = rcond;
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), 1;
    double *t = res + N;
    /* with the inverse at hand (small systems) each solve is a product, else a solve with the
     * factors */
    if (inverse) {
        memcpy(t, b, (size_t)N * sizeof(double));
        cblas_dgemv(CblasColMajor, CblasNoTrans, N, N, 1.0, X, N, t, 1, 0.0, b, 1);
    } else {
        dsytrs_3_("L", &N, &one, K, &N, E, ipiv, b, &N, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs_3 info %d", info);
    }
    for (int k = 0; k < N; k++) b[k] *= s[k];
    /* one step of iterative refinement on the unscaled system (the residual from M* and Φ_q
     * themselves, the correction from the same factors): the symmetric scaling balances the
     * matrix only as far as its diagonal and its rows' norms show */
    memcpy(res, d->Q, (size_t)nv * sizeof(double));
    cblas_dgemv(CblasColMajor, CblasNoTrans, nv, nv, -1.0, d->Mstar, nv, b, 1, 1.0, res, 1);
    for (int r = 0; r < nr; r++) {
        double v = d->gamma[r];
        for (int c = 0; c < nv; c++) {
            res[c] -= PHI(r, c) * b[nv + r];
            v -= PHI(r, c) * b[c];
        }
        res[nv + r] = v;
    }
#undef PHI
    for (int k = 0; k < N; k++) res[k] *= s[k];
    if (inverse) {
        cblas_dgemv(CblasColMajor, CblasNoTrans, N, N, 1.0, X, N, res, 1, 0.0, t, 1);
        memcpy(res, t, (size_t)N * sizeof(double));
    } else {
        dsytrs_3_("L", &N, &one, K, &N, E, ipiv, res, &N, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs_3 info %d", info);
    }
    for (int k = 0; k < N; k++) b[k] += res[k] * s[k];
    vt_scratch_release(d, mark);
    if (!vt_all_finite(b, N)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    return 0;
}

/* Dependent rows: what is truly dependent, decided on Φ_q alone (kinematics: the masses do not
 * take part) in a scaling that neither the directions of the global axes nor the units change.
 * Φ̂ = G Φ_q C: C = 1 for rates that translate and 1/ℓ for rates that turn (rotations, Euler
 * parameters), ℓ the rows' own lever arm (rows_length: a length of the rows' geometry, not of the
 * mass distribution), so that every rate is dimensionless; G = diag(1 / t_r), t_r the size of
 * row r's terms in that scaling (row_size: what its entries are formed from, the speeds the rates
 * can give its points), so that each row's round-off is ε of 1 whatever its size: a row whose
 * lever arms are 1e17 times another's (a point drive 1e17 m out beside one at 1 m) keeps its
 * directions, where one factor for all rows put the short row below the rank's round-off. A row
 * losing its grip (its entries cancel at a singular pose while its terms do not) stays small. A
 * rotation of the scene turns a point's rows among themselves, which have one size, and a change
 * of units scales every entry and size alike, so the singular values of Φ̂ are unchanged by both,
 * and by inertia spread, which does not enter.
 * Its SVD Φ̂ = U Σ V^T (LAPACK dgesvd, U of nc columns) gives
 *   rank    the number of σ above max(nc, nv) ε σ_max (ε = DBL_EPSILON): dependence to round-off
 *           (rows that are round-off of zero, roundoff_check, are zero rows here)
 *   kept    the directions kept in the solve: those above max(that, band σ_max), band being a time
 *           analysis's vt_run_options.redundant_band (0 at every other instant)
 * and the null directions of Φ_q^T, z = G w for the last nc − rank columns w of U. */
typedef struct {
    double *U, *VT, *sig, *g, *s, *c; /* nc x nc, k x nv, k, nc, nv, nv (k = min(nc, nv)); s: the
                                       * mass metric D (redundant_solve's), c: C */
    int *flag;                        /* nc: 1 for a row that is round-off of zero (roundoff_check) */
    int k, rank, kept;
} rows_svd;

/* 1 when row r measures a length (a translation), 0 when an angle */
static int length_row(const vt_model *m, const vt_data *d, int r)
{
    const int kind = m->con_kind[r];
    if (kind == VT_ROW_POINT || kind == VT_ROW_LINE) return 1;
    if (kind != VT_ROW_JOINT && kind != VT_ROW_COUPLING) return 0;
    int c = kind == VT_ROW_JOINT ? m->con_dof[r] : 0, axis = 0;
    if (kind == VT_ROW_COUPLING) /* q_a − ratio q_b: rate a's unit, its entry the first non-zero */
        while (c < m->nv - 1 && d->Phiq[r + (size_t)c * (size_t)m->nc] == 0.0) c++;
    const int i = m->dof_body[c];
    return vt_dof_kind(m->body_joint[i], c - m->body_vadr[i], &axis) == VT_DOF_TRANS;
}

/* 1 when rate a turns (a rotation, an Euler parameter), 0 when it translates */
static int turning_rate(const vt_model *m, int a)
{
    const int i = m->dof_body[a];
    int ax = 0;
    const int kind = vt_dof_kind(m->body_joint[i], a - m->body_vadr[i], &ax);
    return kind == VT_DOF_ROT || kind == VT_DOF_BASE_P;
}

/* ℓ, the rows' lever arm: the largest, over the point and line rows and the rates that turn, of
 * the speed a unit rate gives the row's point on body b relative to what it is measured from
 * (a point row: the partner point P_a; a line row: body a, which carries the line), |W_ra| (a
 * length per radian: how far the rate moves the rows' points), with
 *   W_ra = v_a + ω_a × P_b            rate a moves body b (side b of row r) and not body a
 *        = −(v_a + ω_a × P_a)         rate a moves body a and not body b (a point row)
 *        = −(v_a + ω_a × P_b)         the same for a line row: its entry is −u · that, the line's
 *                                     turning acting over P_b − P_a (a cut joint whose points
 *                                     lie 3e43 m apart: ℓ 6 m without it, Φ̂'s line rows then
 *                                     1e42 of its angle rows, and its rank 2 of 4)
 *        = ω_a × (P_b − P_a)          rate a moves both (a point row; a line row's is 0)
 * ((ω_a, v_a) its twist about o, P the row's points from o) — all three components, not the one
 * the row measures: a row that measures y beside a rate turning about y would otherwise make ℓ
 * collapse with the direction it measures, and scale a nearly dependent column to unit size. A W
 * that is round-off of the terms it is formed from (|v_a| + |ω_a| (|P_a| + |P_b|), τ ε of them: a
 * point on the rate's axis) counts as zero.
 * Without point and line rows (or when every W is zero), the reciprocal of the largest column
 * norm of the couplings that measure angles on the rates that translate (rad/m); without
 * either, 1 (then Φ̂'s blocks do not mix the two kinds and its singular values do not depend on
 * ℓ). A rotation of the scene turns every W alike and leaves its length. flag (nc or NULL): rows
 * left out (round-off of zero). */
static double rows_length(const vt_model *m, const vt_data *d, const int *flag)
{
    const int nv = m->nv, nc = m->nc;
    double arm = 0.0, inv = 0.0;
    for (int r = 0; r < nc; r++) {
        const int kind = m->con_kind[r];
        if ((flag && flag[r]) || (kind != VT_ROW_POINT && kind != VT_ROW_LINE)) continue;
        const int ba = m->con_body[2 * r], bb = m->con_body[2 * r + 1];
        double P[2][3], dP[3];
        for (int s = 0; s < 2; s++) {
            const int b = s ? bb : ba;
            vt_mulmat3(P[s], d->A + 9 * b, m->con_point + 6 * r + 3 * s);
            for (int k = 0; k < 3; k++) P[s][k] += d->xrel[6 * b + k];
        }
        for (int k = 0; k < 3; k++) dP[k] = P[1][k] - P[0][k];
        /* the rates that move both bodies: their paths' common prefix (root first) */
        int shared = 0;
        if (ba > 0 && bb > 0) {
            const int *pa = m->path_dof + m->body_pathadr[ba], *pb = m->path_dof + m->body_pathadr[bb];
            const int na = m->body_pathnum[ba], nb = m->body_pathnum[bb];
            while (shared < na && shared < nb && pa[shared] == pb[shared]) shared++;
        }
        for (int s = 0; s < 2; s++) {
            const int b = s ? bb : ba;
            const int *path = m->path_dof + m->body_pathadr[b];
            for (int k = 0; k < m->body_pathnum[b]; k++) {
                const int a = path[k];
                if (!turning_rate(m, a)) continue;
                const int both = k < shared;
                if (both && (s == 0 || kind == VT_ROW_LINE)) continue; /* once, from side b; a line's: 0 */
                const double *w = d->twist + 6 * a;
                double W[3];
                if (both) vt_cross3(W, w, dP);
                else { /* a line's: at P_b also where the rate moves body a */
                    vt_copy3(W, w + 3);
                    vt_addcross3(W, w, P[kind == VT_ROW_LINE ? 1 : s]);
                }
                /* round-off of the terms W is formed from is no lever arm (a point on the rate's
                 * axis: W 1e-15, whose 1/ℓ would scale that rate's round-off entries to O(1)) */
                const double terms = sqrt(vt_dot3(w + 3, w + 3)) +
                                     sqrt(vt_dot3(w, w)) * (sqrt(vt_dot3(P[0], P[0])) + sqrt(vt_dot3(P[1], P[1])));
                const double wn = sqrt(vt_dot3(W, W));
                if (wn > VT_ROUND_TAU * DBL_EPSILON * terms) arm = fmax(arm, wn);
            }
        }
    }
    if (arm == 0.0)
        for (int a = 0; a < nv; a++) {
            if (turning_rate(m, a)) continue;
            double n2 = 0.0;
            for (int r = 0; r < nc; r++)
                if (!(flag && flag[r]) && m->con_kind[r] == VT_ROW_COUPLING && !length_row(m, d, r)) {
                    const double v = d->Phiq[r + (size_t)a * (size_t)nc];
                    n2 += v * v;
                }
            inv = fmax(inv, sqrt(n2));
        }
    const double len = arm > 0.0 ? arm : inv > 0.0 ? 1.0 / inv : 1.0;
    return isfinite(len) && len > 0.0 ? len : 1.0;
}

/* The size of row r's terms in the rates' scaling c (nv), ‖(t_a c_a)_a‖, B (nv) scratch: what
 * the row's entries are formed from, each rate's
 *   t_a = Σ_sides |v_a| + |ω_a| |P|   a point or line row (P its point on that side, from o: the
 *                                     speed the rate can give it)
 *       = Σ_sides |ω_a|               a row that measures an angle (dot products, orientations)
 *       = |Φ_q,ra|                     joint drives and couplings (exact)
 * over the rates that move either side ((ω_a, v_a) the rate's twist about o). Isotropic: a
 * point's rows measuring x, y or z (or any axis) get the same size, so a rotation of the scene,
 * which mixes them, leaves the scaled rows' singular values as they are; a change of units
 * scales entries and sizes alike. */
static double row_size(const vt_model *m, const vt_data *d, int r, const double *c, double *B)
{
    const int nv = m->nv, nc = m->nc, kind = m->con_kind[r];
    for (int a = 0; a < nv; a++) B[a] = 0.0;
    if (!judged_row(m, r)) {
        for (int a = 0; a < nv; a++) B[a] = fabs(d->Phiq[r + (size_t)a * (size_t)nc]);
    } else {
        const int pt = kind == VT_ROW_POINT || kind == VT_ROW_LINE;
        for (int side = 0; side < 2; side++) {
            const int b = m->con_body[2 * r + side];
            if (b <= 0) continue;
            double P[3];
            vt_mulmat3(P, d->A + 9 * b, m->con_point + 6 * r + 3 * side);
            for (int k = 0; k < 3; k++) P[k] += d->xrel[6 * b + k];
            const double pn = sqrt(vt_dot3(P, P));
            const int *path = m->path_dof + m->body_pathadr[b];
            for (int k = 0; k < m->body_pathnum[b]; k++) {
                const int a = path[k];
                const double *w = d->twist + 6 * a, wn = sqrt(vt_dot3(w, w));
                B[a] += pt ? sqrt(vt_dot3(w + 3, w + 3)) + wn * pn : wn;
            }
        }
    }
    double tmax = 0.0, t2 = 0.0;
    for (int a = 0; a < nv; a++) tmax = fmax(tmax, B[a] * c[a]);
    if (!(tmax > 0.0) || !isfinite(tmax)) return tmax;
    for (int a = 0; a < nv; a++) {
        const double v = B[a] * c[a] / tmax;
        t2 += v * v;
    }
    return tmax * sqrt(t2);
}

/* Φ̂ and its SVD into o (arrays on the arena: the caller releases them); band as above.
 * Returns 0 or a negative vt_status. */
static int rows_decide(const vt_model *m, vt_data *d, double band, rows_svd *o)
{
    const int nv = m->nv, nc = m->nc, k = nc < nv ? nc : nv;
    o->k = k;
    o->U = VT_SCRATCH(d, double, (size_t)nc * (size_t)nc, "U");
    o->VT = VT_SCRATCH(d, double, (size_t)k * (size_t)nv, "V^T");
    o->sig = VT_SCRATCH(d, double, k, "σ");
    o->g = VT_SCRATCH(d, double, nc, "row scaling");
    o->s = VT_SCRATCH(d, double, nv, "mass metric");
    o->c = VT_SCRATCH(d, double, nv, "rate scaling");
    int *flag = o->flag = VT_SCRATCH(d, int, nc, "round-off rows");
    if (!flag) return vt_scratch_fail(d, vt_scratch_mark(d)); /* the caller releases o's arrays */
    const int ro = roundoff_check(m, d, flag, 0, 0); /* a row that is round-off of zero counts as zero */
    if (ro < 0) return ro;
    const size_t mark = vt_scratch_mark(d);
    double *g = o->g, *s = o->c;
    scaling_diag(m, d->Mstar, nv + 1, o->s);
    const double len = rows_length(m, d, flag);
    for (int a = 0; a < nv; a++) s[a] = turning_rate(m, a) ? 1.0 / len : 1.0;
    {
        double *B = VT_SCRATCH(d, double, nv, "terms of a row");
        if (!B) return vt_scratch_fail(d, mark);
        for (int r = 0; r < nc; r++) {
            const double t = row_size(m, d, r, s, B);
            g[r] = t > 0.0 && isfinite(t) ? 1.0 / t : 1.0;
        }
        vt_scratch_release(d, mark);
    }
    double *P = VT_SCRATCH(d, double, (size_t)nc * (size_t)nv, "scaled Φ_q");
    int lw = 0;
    double *work = vt_scratch_rest(d, 5 * (size_t)(nc + nv), sizeof(double), &lw, "dgesvd workspace");
    if (!work) return vt_scratch_fail(d, mark);
    for (int r = 0; r < nc; r++) {
        for (int c = 0; c < nv; c++)
            P[r + (size_t)c * (size_t)nc] = flag[r] ? 0.0 : g[r] * d->Phiq[r + (size_t)c * (size_t)nc] * s[c];
    }
    /* LAPACK stops the program (xerbla) on some NaN inputs: refuse non-finite input first */
    if (!vt_all_finite(P, nc * nv) || !vt_all_finite(o->s, nv) || !vt_all_finite(d->Mstar, nv * nv))
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in the scaled M* or Φ_q (overflow)");
    int info = 0;
    dgesvd_("A", "S", &nc, &nv, P, &nc, o->sig, o->U, &nc, o->VT, &k, work, &lw, &info, 1, 1);
    vt_scratch_release(d, mark);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgesvd info %d", info);
    const double smax = k > 0 ? o->sig[0] : 0.0, tol = (double)(nc > nv ? nc : nv) * DBL_EPSILON * smax;
    const double keep = fmax(tol, band * smax);
    o->rank = o->kept = 0;
    while (o->rank < k && o->sig[o->rank] > tol) o->rank++;
    while (o->kept < k && o->sig[o->kept] > keep) o->kept++;
    return 0;
}

/* The part of row r in the null space of Φ̂^T (the last nc − rank columns of U, orthonormal):
 * 0 for a row independent of the others, up to 1 */
static double null_part(const vt_model *m, const rows_svd *o, int r)
{
    const int nc = m->nc;
    double p = 0.0;
    for (int j = o->rank; j < nc; j++) p += o->U[r + (size_t)j * (size_t)nc] * o->U[r + (size_t)j * (size_t)nc];
    return sqrt(p);
}
#define NULL_PART_TOL 1e-8 /* above it, a row takes part in a dependence (its multiplier is not unique) */

/* Redundant rows (models that allow them): (5) with the rows' dropped directions taken out
 * (rows_decide: those dependent to round-off, and a time analysis's band). With U_d the dropped
 * columns of U and P = I − U_d U_d^T, the rows Y = P G Φ_q (the original rows, each less its
 * parts along the dropped directions: round-off where those are dependent to round-off, so a row
 * stays itself and the rows of two unrelated bodies are not mixed), then factor_solve's scaling:
 * rates by the mass metric D = diag(M*_aa^(-1/2)), M̃ = D M* D, and each row to unit norm in it,
 * N = diag(1 / ‖(Y D)_r‖):
 *   [M̃ (N Y D)^T; N Y D 0] [ỹ; −μ] = [D Q; N P G γ],   q̈ = D ỹ
 * solved by dgelsd (least squares, minimum norm: the matrix has rank nv + kept, the dropped
 * directions being exactly dependent rows of N Y D, and M* may be singular on directions the
 * rows fix). Exactly dependent rows with consistent γ: this is (5) itself, q̈ and the efforts
 * unique, λ the one whose G^(-1) λ lies in the kept directions (the minimum norm one: G P N μ,
 * formed from Φ_q^T λ = M* q̈ − Q in the kept row directions, below). Directions
 * dropped by a time analysis's band (not dependent to round-off) hold in the least-squares sense:
 * d->residual = max |Φ_q q̈ − γ| says how well. Which multipliers are not unique: those in the
 * null directions z = G w of Φ_q^T, left in d->lambda_null for the reactions stage to tell which
 * reactions are not unique. */
#define ROWS_TAU 64.0 /* a row's part outside the dropped directions below τ max(nc, nv) ε σ_max: zero */
static vt_status redundant_solve(const vt_model *m, vt_data *d, const rows_svd *o)
{
    const int nv = m->nv, nc = m->nc, nr = o->kept, nd = nc - nr, N = nv + nc, want = nv + nr, one = 1;
    const size_t mark = vt_scratch_mark(d), ld = (size_t)N, snc = (size_t)nc;
    const double *s = o->s, *g = o->g, *U = o->U;
    double *h = VT_SCRATCH(d, double, nc, "rows' scaling");
    double *P = VT_SCRATCH(d, double, snc * (size_t)(nv + 1), "G [Φ_q, γ], round-off rows zero");
    double *W = VT_SCRATCH(d, double, (size_t)(nd > 0 ? nd : 1) * (size_t)(nv + 1), "U_d^T G [Φ_q, γ]");
    double *K = VT_SCRATCH(d, double, ld * ld, "augmented matrix of the kept rows");
    double *K0 = VT_SCRATCH(d, double, ld * ld, "its copy, for the refinement");
    double *b0 = VT_SCRATCH(d, double, ld, "right side's copy");
    double *b = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "right side");
    double *sv = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "singular values");
    int *iwork = VT_SCRATCH(d, int, vt_dgelsd_iwork(N, N), "dgelsd integer workspace");
    int lwd = 0;
    double *lsq_work = vt_scratch_rest(d, 1, sizeof(double), &lwd, "dgelsd workspace");
    if (!lsq_work) return vt_scratch_fail(d, mark);
    /* P = G [Φ_q, γ] (nc x (nv + 1)), the round-off rows zero; W = U_d^T P (nd x (nv + 1)): the
     * rows' parts along the dropped directions */
    for (int a = 0; a <= nv; a++)
        for (int r = 0; r < nc; r++)
            P[r + (size_t)a * snc] = o->flag[r] ? 0.0 : g[r] * (a < nv ? d->Phiq[r + (size_t)a * snc] : d->gamma[r]);
    if (nd > 0)
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, nd, nv + 1, nc, 1.0, U + (size_t)nr * snc, nc, P, nc, 0.0,
                    W, nd);
    /* Y D = (G Φ_q − U_d W) D into K's lower left block, each row to unit norm (N); the right side
     * N (G γ − U_d W_γ) */
    const double zero = o->k > 0 ? ROWS_TAU * (double)(nc > nv ? nc : nv) * DBL_EPSILON * o->sig[0] : 0.0;
    for (int r = 0; r < nc; r++) {
        double n2 = 0.0, c2 = 0.0;
        for (int a = 0; a <= nv; a++) {
            double v = P[r + (size_t)a * snc];
            for (int j = 0; j < nd; j++) v -= U[r + (size_t)(nr + j) * snc] * W[j + (size_t)a * (size_t)nd];
            if (a < nv) {
                c2 += v * o->c[a] * v * o->c[a];
                v *= s[a];
                K[nv + r + (size_t)a * ld] = v;
                n2 += v * v;
            } else b[nv + r] = v;
        }
        /* a row whose part outside the dropped directions is round-off in Φ̂'s scaling (a row
         * dependent on the others, or along a dropped direction) is a zero row */
        h[r] = n2 > 0.0 && sqrt(c2) > zero ? 1.0 / sqrt(n2) : 0.0;
        b[nv + r] *= h[r];
        for (int a = 0; a < nv; a++) K[nv + r + (size_t)a * ld] *= h[r];
    }
    /* M̃ and both triangles */
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nv; i++) K[i + (size_t)j * ld] = d->Mstar[i + (size_t)j * (size_t)nv] * s[i] * s[j];
    for (int j = nv; j < N; j++) {
        for (int i = 0; i < nv; i++) K[i + (size_t)j * ld] = K[j + (size_t)i * ld];
        for (int i = nv; i < N; i++) K[i + (size_t)j * ld] = 0.0;
    }
    for (int a = 0; a < nv; a++) b[a] = d->Q[a] * s[a];
    memcpy(K0, K, ld * ld * sizeof(double));
    memcpy(b0, b, ld * sizeof(double));
    /* M̃ alone may be singular on directions the rows fix; the dropped directions are round-off */
    const double rc = fmax(m->rcond_min, 64.0 * (double)N * DBL_EPSILON);
    int rk = 0, rk2 = 0, info = 0;
    dgelsd_(&N, &N, &one, K, &N, b, &N, sv, &rc, &rk, lsq_work, &lwd, iwork, &info);
    if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgelsd info %d", info);
    /* one step of iterative refinement (residual and correction in the same scaling): the SVD's
     * error is relative to the whole solution, whose multipliers may be far larger than ỹ (a row
     * on a rate of tiny inertia is large in the mass metric, and unit once scaled) */
    cblas_dgemv(CblasColMajor, CblasNoTrans, N, N, -1.0, K0, N, b, 1, 1.0, b0, 1);
    if (vt_all_finite(b, N) && vt_all_finite(b0, N)) {
        dgelsd_(&N, &N, &one, K0, &N, b0, &N, K, &rc, &rk2, lsq_work, &lwd, iwork, &info);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgelsd info %d", info);
        for (int i = 0; i < N; i++) b[i] += b0[i];
    }
    /* the estimate: the kept part's smallest singular value over the largest, or, if smaller,
     * (σ_kept / σ_max)² of Φ̂: its rows unit, the matrix cannot show a row losing its grip (a cut
     * joint's point row at a four-bar's singular pose), which Φ̂, each row over its own terms, does; squared,
     * the scale of the rows' Schur complement on the other routes */
    const double kin = nr > 0 && o->sig[0] > 0.0 ? o->sig[nr - 1] / o->sig[0] : 1.0;
    d->rcond = rk > 0 ? fmin(sv[(rk < want ? rk : want) - 1] / sv[0], kin * kin) : 0.0;
    d->rank = o->rank;
    if (rk != want)
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_SINGULAR,
                       "vt_solve: singular: Φ_q has rank %d of %d rows (%d directions kept), and the augmented matrix "
                       "of the kept rows has rank %d of %d (reciprocal condition %.3g, rcond_min %.3g): %s",
                       o->rank, nc, nr, rk, want, d->rcond, m->rcond_min,
                       rk < want ? "a motion without inertia that nothing fixes, or a pose near a singular one"
                                 : "dropped directions not dependent to round-off");
    if (!(d->rcond >= m->rcond_min))
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_SINGULAR,
                       "vt_solve: ill-conditioned: Φ_q has rank %d of %d rows (%d directions kept, the smallest kept "
                       "one %.3g of the largest), reciprocal condition %.3g below rcond_min %.3g: a pose near a "
                       "singular one", o->rank, nc, nr, kin, d->rcond, m->rcond_min);
    /* q̈ = D ỹ. The multipliers in the kept row directions of Φ̂ = U Σ V^T, not as G P N μ: N
     * makes a row far smaller than the others (a row 8e-10 of its partners, all three along one
     * direction) a unit row, the minimum-norm μ shares the load among them, and w = N μ carries
     * 1e9 times its share on that row, which P takes back through U's entries (each known to ε):
     * round-off of 1e9 ε on every λ. Instead λ = G U_k t with t from the first block row,
     * Φ_q^T λ = M* q̈ − Q = F, in the mass metric:
     *   (D Φ_q^T G U_k) t = D F   (least squares, LAPACK dgels; consistent: F lies in the range
     *                              of the kept rows, Y^T = Φ_q^T G U_k U_k^T)
     * the same minimum-norm λ (G^-1 λ in the kept directions) in exact arithmetic. Not from
     * Σ_k^-1 V_k^T C F: C scales a turning rate by 1/ℓ, and where ℓ is round-off (a point row
     * whose point lies on the rate's axis: ℓ 1e-15) C F carries F's round-off on that rate 1e15-fold. */
    for (int a = 0; a < nv; a++) b[a] *= s[a];
    double *F = W; /* nv (W holds at least nv + 1): D (M* q̈ − Q) */
    for (int a = 0; a < nv; a++) F[a] = -d->Q[a];
    if (nv > 0) cblas_dgemv(CblasColMajor, CblasNoTrans, nv, nv, 1.0, d->Mstar, nv, b, 1, 1.0, F, 1);
    for (int a = 0; a < nv; a++) F[a] *= s[a];
    double *B = K; /* nv x nr, leading dimension nv: D Φ_q^T G U_k = D P^T U_k */
    if (nr > 0 && nv > 0) {
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, nv, nr, nc, 1.0, P, nc, U, nc, 0.0, B, nv);
        for (int j = 0; j < nr; j++)
            for (int a = 0; a < nv; a++) B[a + (size_t)j * (size_t)nv] *= s[a];
    }
    if (nr > 0) {
        const int ldf = nv > 1 ? nv : 1;
        dgels_("N", &nv, &nr, &one, B, &ldf, F, &ldf, lsq_work, &lwd, &info, 1);
        if (info != 0)
            return vt_scratch_release(d, mark),
                   vt_fail(d->message, info < 0 ? VT_ERR_LAPACK : VT_ERR_SINGULAR,
                           "vt_solve: the kept rows' multipliers (dgels info %d)", info);
    }
    /* λ = G U_k t, t in F[0..nr); the round-off rows' zero */
    for (int r = 0; r < nc; r++) sv[r] = 0.0;
    if (nr > 0) cblas_dgemv(CblasColMajor, CblasNoTrans, nc, nr, 1.0, U, nc, F, 1, 0.0, sv, 1);
    for (int r = 0; r < nc; r++) sv[r] = o->flag[r] ? 0.0 : g[r] * sv[r];
    if (!vt_all_finite(b, nv) || !vt_all_finite(sv, nc))
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    double resid = 0.0; /* how well the kept rows hold: max |Φ_q q̈ − γ| (it may overflow: refused) */
    double *res = P; /* nc: P is no longer read */
    for (int r = 0; r < nc; r++) res[r] = -d->gamma[r];
    if (nv > 0) cblas_dgemv(CblasColMajor, CblasNoTrans, nc, nv, 1.0, d->Phiq, nc, b, 1, 1.0, res, 1);
    for (int r = 0; r < nc; r++) resid = fmax(resid, fabs(res[r]));
    if (!isfinite(resid))
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: the rows' residual |Φ_q q̈ − γ| overflows (not finite)");
    memcpy(d->qdd, b, (size_t)nv * sizeof(double));
    memcpy(d->lambda, sv, (size_t)nc * sizeof(double));
    vt_scratch_release(d, mark);
    d->residual = resid;
    /* the null directions z = G w of Φ_q^T (each scaled to a largest entry of 1), and which
     * multipliers they change */
    vt_mark_unique(m, d);
    for (int j = 0; j < nc - o->rank; j++) {
        double *z = d->lambda_null + (size_t)j * (size_t)nc, zmax = 0.0;
        for (int r = 0; r < nc; r++) {
            z[r] = g[r] * U[r + (size_t)(o->rank + j) * (size_t)nc];
            zmax = fmax(zmax, fabs(z[r]));
        }
        for (int r = 0; r < nc; r++) z[r] = zmax > 0.0 ? z[r] / zmax : 0.0;
    }
    for (int r = 0; r < nc; r++)
        if (null_part(m, o, r) > NULL_PART_TOL) d->lambda_unique[r] = 0;
    d->warning = (d->rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0) | (o->rank < nc ? VT_WARN_REDUNDANT : 0) |
                 (nr < o->rank ? VT_WARN_BAND : 0);
    return VT_OK;
}

/* Every row a joint drive q_k = f_k(t) on a rate of its own: those rates' q̈ are γ, and (5)
 * reduces to the free rates F, M*_FF q̈_F = Q_F − M*_FD q̈_D, with M*_FF symmetric positive
 * definite: LAPACK's Cholesky (dpotf2/dpotrs) on the mass-metric scaled matrix, its free rates in
 * descending order (leaf first), its condition estimate min/max of the pivots L_kk² (each
 * relative to its unit diagonal: the recursive articulated route's number); then λ_D = (M* q̈ − Q)_D. The same solution as (5), a fraction of
 * the work. Returns 0, 1 (below rcond_min) or a negative vt_status. */
static int joint_rows_solve(const vt_model *m, vt_data *d, double *rcond_out)
{
    const int nv = m->nv, nc = m->nc, nf = nv - nc;
    const size_t mark = vt_scratch_mark(d);
    int *freev = VT_SCRATCH(d, int, nf, "free rates");
    double *K = VT_SCRATCH(d, double, (size_t)nf * (size_t)nf, "free rates' M*");
    double *b = VT_SCRATCH(d, double, nf, "right side"), *s = VT_SCRATCH(d, double, nf, "scaling");
    double *qdd = VT_SCRATCH(d, double, nv, "q̈");
    if (!qdd) return vt_scratch_fail(d, mark);
    for (int c = 0; c < nv; c++) qdd[c] = 0.0;
    int k = 0;
    for (int c = nv - 1; c >= 0; c--) /* descending: leaf first, as the articulated pivots */
        if (m->dof_drive[c] < 0) freev[k++] = c;
    for (int r = 0; r < nc; r++) qdd[m->con_dof[r]] = d->gamma[r];
    for (int a = 0; a < nf; a++) {
        const double mii = d->Mstar[freev[a] + (size_t)freev[a] * (size_t)nv];
        s[a] = mii > 0.0 ? 1.0 / sqrt(mii) : 1.0;
    }
    for (int j = 0; j < nf; j++)
        for (int i = j; i < nf; i++)
            K[i + (size_t)j * (size_t)nf] = d->Mstar[freev[i] + (size_t)freev[j] * (size_t)nv] * s[i] * s[j];
    for (int i = 0; i < nf; i++) {
        double v = d->Q[freev[i]];
        for (int r = 0; r < nc; r++) v -= d->Mstar[freev[i] + (size_t)m->con_dof[r] * (size_t)nv] * d->gamma[r];
        b[i] = v * s[i];
    }
    /* the condition: min/max of the pivots (L_kk², each relative to its unit diagonal), as the
     * articulated route's over the same free rates in the same order */
    double rcond = 0.0;
    int info = 0;
    if (nf > 0) dpotf2_("L", &nf, K, &nf, &info, 1);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotf2 info %d", info);
    if (info == 0) {
        double pmin = 1.0, pmax = 0.0;
        for (int a = 0; a < nf; a++) {
            const double p = K[a + (size_t)a * (size_t)nf] * K[a + (size_t)a * (size_t)nf];
            pmin = p < pmin ? p : pmin;
            pmax = p > pmax ? p : pmax;
        }
        rcond = nf > 0 ? pmin / pmax : 1.0;
    }
    *rcond_out = rcond;
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), 1;
    const int one = 1;
    if (nf > 0) dpotrs_("L", &nf, &one, K, &nf, b, &nf, &info, 1);
    if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotrs info %d", info);
    for (int i = 0; i < nf; i++) qdd[freev[i]] = b[i] * s[i];
    if (!vt_all_finite(qdd, nv))
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    memcpy(d->qdd, qdd, (size_t)nv * sizeof(double));
    for (int r = 0; r < nc; r++) {
        const int c = m->con_dof[r];
        double v = -d->Q[c];
        for (int j = 0; j < nv; j++) v += d->Mstar[c + (size_t)j * (size_t)nv] * qdd[j];
        d->lambda[r] = v;
    }
    vt_scratch_release(d, mark);
    return 0;
}

/* As many independent constraint rows as rates (a kinematically determined mechanism: the
 * drives fix the whole motion, as the crank of a four-bar does): Φ_q is square and (5) splits
 * into its two block rows,
 *
 *   Φ_q q̈ = γ,        Φ_q^T λ = M* q̈ − Q,                                   (5), (2)
 *
 one LU factorization of R Φ_q D (LAPACK dgetf2, partial pivoting, unblocked: at these sizes
 * the blocked dgetrf's recursion costs more than it saves; D = diag(M*_aa^(-1/2)), R each row to
 * unit norm in that metric) serving both solves (dgetrs, then its transpose): M* is not
 * factorized at all. The motion is the rows' alone, and so is the question of its
 * conditioning, which is kinematic (the pose), whatever the inertias: the reported estimate is
 * the condition of Φ̂ = G Φ_q C (exact up to 16 rates, from the inverse of the solves' R Φ_q D
 * below, rescaled: one LU for both; dgecon on Φ̂'s own LU above), a scaling that makes Φ̂
 * dimensionless and its condition independent of units and of the scene's frame, and in which
 * no mass takes part: rows that measure angles by ℓ and
 * those that measure lengths by 1 (G; rows_decide scales each row by its own terms instead), rates that turn (rotations, Euler
 * parameters) by 1/ℓ and those that translate by 1 (C), ℓ the rows' own lever arm (rows_length,
 * a length of the rows' geometry). The two solves in sequence amplify errors by
 * cond(Φ̂) each, so the reported reciprocal condition is squared, the scale of the augmented
 * matrix's (whose inverse holds Φ_q^(-T) M* Φ_q^(-1)); the recursive square route computes the
 * same number. Returns 0, 1 (below rcond_min: nothing solved) or a negative vt_status. */
static int square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond_out)
{
    const int n = m->nv;
    sq->A = VT_SCRATCH(d, double, (size_t)n * (size_t)n, "LU of R Φ_q D");
    sq->s = VT_SCRATCH(d, double, 2 * (size_t)n, "scalings D and R");
    sq->x = VT_SCRATCH(d, double, 2 * (size_t)n, "q̈ and M* q̈ − Q");
    sq->ipiv = VT_SCRATCH(d, int, n, "pivots");
    if (!sq->ipiv) return VT_ERR_NO_MEMORY;
    sq->h = sq->x + n;
    sq->g = sq->s + n;
    double *A = sq->A, *s = sq->s, *g = sq->g;
    const size_t mark = vt_scratch_mark(d);
    double *gk = VT_SCRATCH(d, double, 2 * (size_t)n, "G and C");
    if (!gk) return vt_scratch_fail(d, mark);
    double *ck = gk + n;
    /* Φ̂ = G Φ_q C's scalings and its 1-norm, the largest column sum */
    const double rho = rows_length(m, d, NULL);
    for (int a = 0; a < n; a++) {
        const int i = m->dof_body[a];
        int ax = 0;
        const int kind = vt_dof_kind(m->body_joint[i], a - m->body_vadr[i], &ax);
        ck[a] = kind == VT_DOF_ROT || kind == VT_DOF_BASE_P ? 1.0 / rho : 1.0;
    }
    for (int r = 0; r < n; r++) gk[r] = length_row(m, d, r) ? 1.0 : rho;
    double anorm = 0.0;
    for (int c = 0; c < n; c++) {
        double cs = 0.0;
        for (int r = 0; r < n; r++) cs += fabs(gk[r] * d->Phiq[r + (size_t)c * (size_t)n] * ck[c]);
        anorm = cs > anorm ? cs : anorm;
    }
    /* the solves' matrix R Φ_q D, D the mass metric and R each row to unit norm in it. Its LU's
     * pivots then take the rows that act on heavy rates for those rates, and the substitutions
     * keep apart what the structure keeps apart: a light link's drive force is not made of a
     * heavy one's round-off (the inverse, a dense product, would mix them) */
    scaling_diag(m, mdiag, stride, s);
    for (int r = 0; r < n; r++) {
        double rn = 0.0;
        for (int c = 0; c < n; c++) rn += d->Phiq[r + (size_t)c * (size_t)n] * s[c] * d->Phiq[r + (size_t)c * (size_t)n] * s[c];
        g[r] = rn > 0.0 ? 1.0 / sqrt(rn) : 1.0;
    }
    for (int c = 0; c < n; c++)
        for (int r = 0; r < n; r++) A[r + (size_t)c * (size_t)n] = g[r] * d->Phiq[r + (size_t)c * (size_t)n] * s[c];
    int info = 0;
    dgetf2_(&n, &n, A, &n, sq->ipiv, &info);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetf2 info %d", info);
    if (info > 0) return vt_scratch_release(d, mark), *rcond_out = 0.0, 1; /* an exactly zero pivot */
    /* the condition of Φ̂ = G R^-1 (R Φ_q D) D^-1 C: up to 16 rates exactly, from the inverse of
     * R Φ_q D (one solve with the identity on the factors at hand), Φ̂^-1 = C^-1 D (R Φ_q D)^-1 R G^-1
     * entry by entry; above, LAPACK's dgecon on Φ̂'s own LU */
    double rcond = 0.0;
    double *X = small_inverse(d, n, 0);
    if (X) {
        dgetrs_("N", &n, &n, A, &n, sq->ipiv, X, &n, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetrs info %d", info);
        for (int c = 0; c < n; c++) {
            const double fc = g[c] / gk[c];
            for (int r = 0; r < n; r++) X[r + (size_t)c * (size_t)n] *= s[r] / ck[r] * fc;
        }
        rcond = rcond_from_inverse(X, n, anorm);
    } else {
        double *K = VT_SCRATCH(d, double, (size_t)n * (size_t)n, "G Φ_q C");
        double *work = VT_SCRATCH(d, double, 4 * (size_t)n, "dgecon workspace");
        int *ip = VT_SCRATCH(d, int, n, "pivots of G Φ_q C"), *iwork = VT_SCRATCH(d, int, n, "dgecon integer workspace");
        if (!iwork) return vt_scratch_fail(d, mark);
        for (int c = 0; c < n; c++)
            for (int r = 0; r < n; r++) K[r + (size_t)c * (size_t)n] = gk[r] * d->Phiq[r + (size_t)c * (size_t)n] * ck[c];
        dgetf2_(&n, &n, K, &n, ip, &info);
        if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetf2 info %d", info);
        if (info == 0) dgecon_("1", &n, K, &n, &anorm, &rcond, work, iwork, &info, 1);
        if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgecon info %d", info);
    }
    vt_scratch_release(d, mark);
    *rcond_out = rcond * rcond;
    return *rcond_out >= m->rcond_min ? 0 : 1;
}

int vt_square_apply(const vt_model *m, vt_data *d, const vt_square *sq, const double *b, double sign, double *x)
{
    const int n = m->nv, one = 1;
    int info = 0;
    for (int r = 0; r < n; r++) x[r] = sq->g[r] * b[r]; /* y = (R Φ_q D)^-1 R b, x = ± D y */
    dgetrs_("N", &n, &one, sq->A, &n, sq->ipiv, x, &n, &info, 1);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetrs info %d", info);
    for (int a = 0; a < n; a++) x[a] *= sign * sq->s[a];
    return 0;
}

int vt_square_first(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond_out)
{
    const int r = square_factor(m, d, sq, mdiag, stride, rcond_out);
    return r ? r : vt_square_apply(m, d, sq, d->gamma, 1.0, sq->x); /* q̈ = Φ_q^-1 γ */
}

int vt_square_second(const vt_model *m, vt_data *d, vt_square *sq)
{
    const int n = m->nv, one = 1;
    double *g = sq->h;
    int info = 0;
    for (int a = 0; a < n; a++) g[a] *= sq->s[a];
    dgetrs_("T", &n, &one, sq->A, &n, sq->ipiv, g, &n, &info, 1);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetrs info %d", info);
    for (int a = 0; a < n; a++) g[a] *= sq->g[a];
    if (!vt_all_finite(sq->x, 2 * n)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    return 0;
}

/* the square route of vt_solve: [q̈; λ] into b */
static int square_solve(const vt_model *m, vt_data *d, double *b, double *rcond_out)
{
    const int n = m->nv;
    const size_t mark = vt_scratch_mark(d);
    vt_square sq;
    int r = vt_square_first(m, d, &sq, d->Mstar, n + 1, rcond_out);
    if (r == 0) {
        memcpy(sq.h, d->Q, (size_t)n * sizeof(double)); /* h = M* q̈ − Q */
        cblas_dgemv(CblasColMajor, CblasNoTrans, n, n, 1.0, d->Mstar, n, sq.x, 1, -1.0, sq.h, 1);
        r = vt_square_second(m, d, &sq);
        if (r == 0) memcpy(b, sq.x, 2 * (size_t)n * sizeof(double));
    }
    vt_scratch_release(d, mark);
    return r;
}

/* Fewer rows than rates, M* well conditioned (the usual case: a chain whose tip follows a
 * path, an arm partly driven): (5) by its Schur complement on the constraint rows, in the
 * scaled variables (M̃ = D M* D with unit diagonal, Φ̃ = R Φ_q D, R each row to unit norm in
 * that metric):
 *
 *   M̃ = L L^T,   Y = L^-1 Φ̃^T,   z = L^-1 D Q,   S = Y^T Y = Φ̃ M̃^-1 Φ̃^T,
 *   S λ̃ = R γ − Y^T z,   ỹ = L^-T (z + Y λ̃),   q̈ = D ỹ,   λ = R λ̃,
 *
 * two Cholesky factorizations (LAPACK dpotf2, unblocked like dgetf2 above, of nv and of nc
 * unknowns) instead of the symmetric indefinite one of nv + nc: about a third of the work, and
 * no pivoting. With known rates (known: a joint drive on a rate of its own, its q̈_D = γ_D
 * exact, as the recursive articulated route takes it) the same on the free rates F and the
 * other rows o alone, the known ones moved to the right sides:
 *
 *   M*_FF q̈_F = Q_F − M*_FD q̈_D + Φ_oF^T λ_o,   Φ_oF q̈_F = γ_o − Φ_oD q̈_D,
 *   λ_D = (M* q̈ − Q − Φ_o^T λ_o)_D
 *
 * so that a point row beside a joint drive is judged by what it fixes on the rates that are
 * not known (a row [692208, −4.85, 0] beside the drive [1, 0, 0] fixes rate 1; in the mass
 * metric of all rates the two rows look parallel, 3e-6 apart, and the estimate squares that).
 * It applies when every pivot of L is at least 1e-4 (M̃'s unit diagonal bounds them by 1 from
 * above): below that M* is (nearly) singular on some rates, which only the constraints may fix,
 * and factor_solve takes over (return 2). M̃ is factorized with its rates in descending order
 * (leaf first), so that L_kk² are the articulated-body pivots each over its diagonal entry.
 * The reported reciprocal condition is S's at unit diagonal (vt_solve_spd: exact, 1 for one row,
 * for nc ≤ 16 from its inverse; dpocon's estimate above) times (min L_kk / max L_kk)² times the
 * point drives' grip² (vt_rows_grip): the recursive articulated route's number. It falls where
 * the rows lose independence in the mass metric, where a motion loses its inertia, and where a
 * point drive loses its grip (a lone one too). Returns 0, 2, 3 (below rcond_min: not solved), 4
 * (solved, below rcond_warn: vt_solve_band tries the augmented route too) or a negative vt_status. */
#define SCHUR_FEW 3 /* rows up to which S and its right side are formed by loops */
static int schur_solve(const vt_model *m, vt_data *d, int known, double *sol, double *rcond_out)
{
    const int nv = m->nv, nc = m->nc;
    const size_t mark = vt_scratch_mark(d);
    int *fr = VT_SCRATCH(d, int, (size_t)nv + (size_t)nc, "free rates, known rates, other rows"), *ro = fr + nv;
    if (!fr) return vt_scratch_fail(d, mark);
    int nf = 0, no = 0;
    for (int a = nv - 1; a >= 0; a--) /* descending: leaf first, as the articulated pivots */
        if (!known || m->dof_drive[a] < 0) fr[nf++] = a;
    const int *kr = fr + nf; /* the known rates after them, ascending: fr[nf..nv) */
    for (int a = 0, k = nf; a < nv; a++)
        if (known && m->dof_drive[a] >= 0) fr[k++] = a;
    for (int r = 0; r < nc; r++)
        if (!known || !vt_known_row(m, r)) ro[no++] = r;
    const int nrhs = no + 1;
    double *L = VT_SCRATCH(d, double, (size_t)nf * (size_t)nf, "Cholesky factor of M̃");
    double *B = VT_SCRATCH(d, double, (size_t)nf * (size_t)nrhs, "L^-1 [Φ̃^T, D Q]");
    double *S = VT_SCRATCH(d, double, (size_t)no * (size_t)no, "Schur complement");
    double *s = VT_SCRATCH(d, double, (size_t)nv + (size_t)no, "scaling");
    double *x = VT_SCRATCH(d, double, (size_t)nv + (size_t)no, "q̈ and λ̃");
    if (!x) return vt_scratch_fail(d, mark);
    double *lam = x + nv, *g = s + nv;
#define PHI(r, c) d->Phiq[(size_t)(r) + (size_t)(c) * (size_t)nc]
#define MS(r, c) d->Mstar[(size_t)(r) + (size_t)(c) * (size_t)nv]
    /* q̈_D = γ of the known rates' drives (0 elsewhere), D = M*_aa^(-1/2) on the free ones */
    for (int a = 0; a < nv; a++) x[a] = known && m->dof_drive[a] >= 0 ? d->gamma[m->drive_row[m->dof_drive[a]]] : 0.0;
    scaling_diag(m, d->Mstar, nv + 1, s);
    for (int k = 0; k < no; k++) {
        double rn = 0.0;
        for (int a = 0; a < nf; a++) {
            const double v = PHI(ro[k], fr[a]) * s[fr[a]];
            rn += v * v;
        }
        g[k] = rn > 0.0 ? 1.0 / sqrt(rn) : 1.0;
    }
    for (int j = 0; j < nf; j++)
        for (int i = j; i < nf; i++) L[i + (size_t)j * (size_t)nf] = MS(fr[i], fr[j]) * s[fr[i]] * s[fr[j]];
    int info = 0;
    if (nf > 0) dpotf2_("L", &nf, L, &nf, &info, 1);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotf2 info %d", info);
    if (info > 0) return vt_scratch_release(d, mark), 2;
    double lmin = 1.0, lmax = 0.0;
    for (int k = 0; k < nf; k++) {
        const double lk = L[k + (size_t)k * (size_t)nf];
        if (!(lk >= 1e-4)) return vt_scratch_release(d, mark), 2;
        lmin = lk < lmin ? lk : lmin; /* not fmin/fmax: lk is a number here, and they are calls */
        lmax = lk > lmax ? lk : lmax;
    }
    /* B = [Φ̃_oF^T, D (Q − M* q̈_D)_F], then L^-1 B */
    for (int k = 0; k < no; k++)
        for (int a = 0; a < nf; a++) B[a + (size_t)k * (size_t)nf] = g[k] * PHI(ro[k], fr[a]) * s[fr[a]];
    double *z = B + (size_t)no * (size_t)nf;
    for (int a = 0; a < nf; a++) {
        const int c = fr[a];
        double v = d->Q[c];
        for (int j = 0; j < nv - nf; j++) v -= MS(c, kr[j]) * x[kr[j]]; /* M*_FD q̈_D */
        z[a] = v * s[c];
    }
    if (nf > 0) cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, nf, nrhs, 1.0, L, nf, B, nf);
    const double *Y = B;
    /* S = Y^T Y and its right-hand side R (γ − Φ q̈_D) − Y^T z. With a few rows (a point drive: 1
     * to 3) these are a few dot products of nf terms, cheaper as loops than as BLAS calls (whose
     * argument checks cost more than the products); one row makes S a positive number, its
     * Cholesky factor a square root, and S's condition exactly 1. */
    for (int k = 0; k < no; k++) {
        double t = d->gamma[ro[k]];
        for (int j = 0; j < nv - nf; j++) t -= PHI(ro[k], kr[j]) * x[kr[j]]; /* Φ_oD q̈_D */
        lam[k] = g[k] * t;
    }
    const int few = no <= SCHUR_FEW;
    if (few) {
        for (int r = 0; r < no; r++) {
            const double *yr = Y + (size_t)r * (size_t)nf;
            double t = lam[r];
            for (int a = 0; a < nf; a++) t -= yr[a] * z[a];
            lam[r] = t;
            for (int k = r; k < no; k++) {
                const double *yk = Y + (size_t)k * (size_t)nf;
                double v = 0.0;
                for (int a = 0; a < nf; a++) v += yk[a] * yr[a];
                S[k + (size_t)r * (size_t)no] = v;
            }
        }
    } else {
        cblas_dsyrk(CblasColMajor, CblasLower, CblasTrans, no, nf, 1.0, Y, nf, 0.0, S, no);
        cblas_dgemv(CblasColMajor, CblasTrans, nf, no, -1.0, Y, nf, z, 1, 1.0, lam, 1);
    }
    double rcond = 0.0;
    const int st = vt_solve_spd(d, S, no, lam, &rcond);
    if (st) return vt_scratch_release(d, mark), st;
    rcond *= (lmin / lmax) * (lmin / lmax) * vt_rows_grip(m, d);
    *rcond_out = rcond;
    /* below rcond_min: not solved, 3 (vt_solve_band tries the augmented route before refusing) */
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), 3;
    /* ỹ = L^-T (z + Y λ̃), in place of z */
    if (few) {
        for (int r = 0; r < no; r++) {
            const double *yr = Y + (size_t)r * (size_t)nf, l = lam[r];
            for (int a = 0; a < nf; a++) z[a] += yr[a] * l;
        }
    } else {
        cblas_dgemv(CblasColMajor, CblasNoTrans, nf, no, 1.0, Y, nf, lam, 1, 1.0, z, 1);
    }
    if (nf > 0) cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, nf, L, nf, z, 1);
    for (int a = 0; a < nf; a++) x[fr[a]] = z[a] * s[fr[a]];
    for (int k = 0; k < no; k++) lam[k] *= g[k];
    memcpy(sol, x, (size_t)nv * sizeof(double));
    for (int k = 0; k < no; k++) sol[nv + ro[k]] = lam[k];
    for (int j = 0; j < nv - nf; j++) { /* λ_D = (M* q̈ − Q − Φ_o^T λ_o)_D on each known rate */
        const int a = kr[j];
        double v = -d->Q[a];
        for (int b = 0; b < nv; b++) v += MS(a, b) * x[b];
        for (int k = 0; k < no; k++) v -= PHI(ro[k], a) * lam[k];
        sol[nv + m->drive_row[m->dof_drive[a]]] = v;
    }
#undef PHI
#undef MS
    vt_scratch_release(d, mark);
    if (!vt_all_finite(sol, nv + nc)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    /* below rcond_warn: solved, 4 (vt_solve_band also tries the augmented route) */
    return rcond >= m->rcond_warn ? 0 : 4;
}

/* Whether the Schur route may take the joint-driven rates as known: some rate has a joint
 * drive, and no row depends on the known rates by its kind alone, a second joint drive on a
 * driven rate or a coupling of two driven rates: their parts on the free rates are exactly zero,
 * where the dense S leaves round-off (R S = I to ε) that the rows' scaling would make a unit row.
 * Those the whole system decides, and names (rows that are round-off on the free rates:
 * vt_zero_rows_free, at the call). */
static int rates_known(const vt_model *m)
{
    int any = 0;
    for (int a = 0; a < m->nv; a++) any |= m->dof_drive[a] >= 0;
    for (int r = 0; r < m->nc && any; r++) {
        if (m->con_kind[r] == VT_ROW_JOINT && !vt_known_row(m, r)) return 0;
        if (m->con_kind[r] == VT_ROW_COUPLING) {
            const vt_coupling_def *c = m->coupling + m->con_owner[r];
            if (m->dof_drive[m->body_vadr[c->body_a] + c->index_a] >= 0 && m->dof_drive[m->body_vadr[c->body_b] + c->index_b] >= 0)
                return 0;
        }
    }
    return any;
}

void vt_solved(const vt_model *m, vt_data *d, vt_route route, double rcond)
{
    d->route = route;
    d->rcond = rcond;
    d->warning = rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0;
    d->rank = m->nc;
    d->residual = 0.0;
    vt_mark_unique(m, d);
}

void vt_solve_reset(vt_data *d)
{
    d->route = VT_ROUTE_NONE;
    d->rcond = 0.0;
    d->warning = 0;
    d->rank = 0;
    d->residual = 0.0;
}

/* A rate that no constraint row touches (its column of Φ_q zero: no drive, cut joint or coupling) */
static int untouched(const vt_model *m, const vt_data *d, int a)
{
    for (int r = 0; r < m->nc; r++)
        if (d->Phiq[r + (size_t)a * (size_t)m->nc] != 0.0) return 0;
    return 1;
}

/* What makes a solve singular by having nothing to move, written into buf (n bytes) as
 * " rate 2 (body 1) has no inertia; body 3, body 5: no mass or inertia beyond a joint that no
 * row touches",
 * empty if none: a rate that no row touches and whose M*_aa is exactly 0 (moving it alone costs
 * no kinetic energy), and a body with such a rate whose subtree carries neither mass nor
 * inertia. */
static void massless(const vt_model *m, vt_data *d, char *buf, size_t n)
{
    buf[0] = '\0';
    size_t len = 0;
    int count = 0;
    for (int a = 0; a < m->nv && len + 48 < n; a++)
        if (d->Mstar[a + (size_t)a * (size_t)m->nv] == 0.0 && untouched(m, d, a))
            len += (size_t)snprintf(buf + len, n - len, "%s rate %d (body %d)", count++ ? "," : "", a, m->dof_body[a]);
    if (count) len += (size_t)snprintf(buf + len, n - len, " %s no inertia", count > 1 ? "have" : "has");
    const int rates = count;
    const size_t nb = (size_t)m->nbody + 1, mark = vt_scratch_mark(d);
    double *w = VT_SCRATCH(d, double, nb, "subtree inertia");
    if (!w) {
        vt_scratch_release(d, mark);
        return;
    }
    w[0] = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        const double *J = m->body_inertia + 9 * i;
        w[i] = m->body_mass[i] + fabs(J[0]) + fabs(J[4]) + fabs(J[8]);
    }
    vt_subtree_sum(m, w, 1);
    count = 0;
    for (int i = 1; i <= m->nbody && len + 48 < n; i++) {
        int free_rate = 0;
        for (int k = 0; k < m->body_nv[i]; k++) free_rate |= untouched(m, d, m->body_vadr[i] + k);
        if (w[i] != 0.0 || !free_rate) continue;
        len += (size_t)snprintf(buf + len, n - len, "%s body %d", count++ ? "," : rates ? ";" : "", i);
    }
    if (count) snprintf(buf + len, n - len, ": no mass or inertia beyond a joint that no row touches");
    vt_scratch_release(d, mark);
}

/* VT_ERR_SINGULAR with what was found: rates or bodies without inertia (named), an exactly zero
 * pivot (rcond 0), or neither: a matrix that is only ill-conditioned, its reciprocal condition
 * below rcond_min (with Φ_q's rank and smallest scaled singular value when rows were checked:
 * rows_decide's, o NULL without rows). what: the matrix the route factorized. */
static vt_status singular(const vt_model *m, vt_data *d, const char *what, double rcond, const rows_svd *o)
{
    char who[160], rows[96] = "";
    massless(m, d, who, sizeof who);
    if (o && o->k > 0)
        snprintf(rows, sizeof rows, "; Φ_q has full rank %d, its smallest scaled singular value %.3g of the largest",
                 o->rank, o->sig[0] > 0.0 ? o->sig[o->k - 1] / o->sig[0] : 0.0);
    if (who[0])
        return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: singular:%s (reciprocal condition %.3g of the %s)", who,
                       rcond, what);
    if (rcond == 0.0)
        return vt_fail(d->message, VT_ERR_SINGULAR,
                       "vt_solve: singular: an exactly zero pivot of the %s: the drives and cut joints leave a motion "
                       "free that has no inertia%s", what, rows);
    return vt_fail(d->message, VT_ERR_SINGULAR,
                   "vt_solve: ill-conditioned: the %s has reciprocal condition %.3g, below rcond_min %.3g (no zero "
                   "pivot, no rate without inertia%s): a pose near a singular one, or a model beyond the precision "
                   "rcond_min asks for", what, rcond, m->rcond_min, rows);
}

/* A free-rate route's answer whose estimate is below rcond_warn, or below √rcond_warn with a
 * joint drive's multiplier that is the difference of terms 1/rcond_warn times its size: over a
 * spread of inertia M* and Q can have lost what the problem keeps (a tiny driven link carrying a
 * huge free body; docs/accuracy.md, "Mass ratios"). q̈ loses up to ε / rcond, which the
 * warning covers; a joint drive's effort λ_r = (M* q̈ − Q − Φ_q,oᵀ λ_o)_c (rate c) also loses ε
 * times its cancellation, g_r / |λ_r| with g_r = |Q_c| + Σ_j |M*_cj q̈_j| + Σ_o |Φ_q,oc λ_o|,
 * which grows as 1 / rcond² there and stays near 1 / rcond otherwise. The maximal-coordinate route
 * (maximal.c) keeps each body's equations at its own size; where the dense stages have formed
 * S and Φ_x it solves too, and its answer is kept where its estimate is the higher. Only after a
 * route that solved (r = 0): a refusal (dependent rows, a motion without inertia) stands. sol:
 * [q̈; λ], or [q̈; −λ] (neg). */
static int maximal_wanted(const vt_model *m, const vt_data *d, int r, double rcond, const double *sol, int neg)
{
    if (r != 0 || !vt_maximal_wanted(m, rcond)) return 0;
    if (rcond < m->rcond_warn) return 1;
    const int nv = m->nv, nc = m->nc;
    const double *lam = sol + nv, sg = neg ? -1.0 : 1.0;
    for (int q = 0; q < nc; q++) {
        if (!vt_known_row(m, q)) continue;
        const int c = m->con_dof[q];
        double g = fabs(d->Q[c]);
        for (int j = 0; j < nv; j++) g += fabs(d->Mstar[c + (size_t)j * (size_t)nv] * sol[j]);
        for (int o = 0; o < nc; o++)
            if (o != q) g += fabs(d->Phiq[o + (size_t)c * (size_t)nc] * lam[o]);
        if (!(g * m->rcond_warn < fabs(sg * lam[q]))) return 1; /* g / |λ| ≥ 1 / rcond_warn */
    }
    return 0;
}

/* The maximal route's [q̈; λ] into sol and its estimate into *rcond where it is the higher:
 * returns 1 then, 0 where the answer in sol stays, or a negative vt_status. Its estimate is the
 * answer's condition (maximal.c) bounded by the rows' own: (σ_min / σ_max)² of Φ̂ = G Φ_q C
 * (rows_decide: no masses), times the grip g². The answer's condition alone, relative to the
 * answer, does not see rows that lose their independence (their multipliers grow with the
 * answer); the rows' condition does, whatever the inertias. */
static int maximal_alternative(const vt_model *m, vt_data *d, double *rcond, double *sol)
{
    const size_t n = (size_t)m->nv + (size_t)m->nc, mark = vt_scratch_mark(d);
    double rho = 1.0;
    if (m->nc > 0) {
        rows_svd o;
        const int r = rows_decide(m, d, 0.0, &o);
        if (r < 0) return vt_scratch_release(d, mark), r;
        const double ratio = o.sig[0] > 0.0 ? o.sig[o.k - 1] / o.sig[0] : 0.0;
        rho = o.rank < m->nc ? 0.0 : ratio * ratio;
        vt_scratch_release(d, mark);
    }
    if (!(rho > *rcond)) return 0; /* cannot be the higher */
    double *alt = VT_SCRATCH(d, double, n, "maximal route's solution");
    if (!alt) return vt_scratch_fail(d, mark);
    double rc = 0.0;
    const int r = vt_maximal_solve(m, d, alt, &rc);
    if (r == 0) rc = fmin(rc, rho) * vt_rows_grip(m, d);
    const int take = r == 0 && rc >= m->rcond_min && rc > *rcond;
    if (take) {
        memcpy(sol, alt, n * sizeof(double));
        *rcond = rc;
        d->fallback |= VT_FALLBACK_MAXIMAL_CONDITION;
    }
    vt_scratch_release(d, mark);
    return r < 0 ? r : take;
}

/* The routes, cheapest first (the model's rows decide; vt_data.route records the one taken):
 *   FREE_RATES  every row a joint drive on a rate of its own (joint_rows_solve)
 *   REDUNDANT   allow_redundant, and rows_decide drops a direction: dependent to round-off, or
 *               within a time analysis's band (redundant_solve)
 *   SQUARE      as many rows as rates (square_solve); ill-conditioned: diagnosed, no fallback
 *   SCHUR       fewer rows than rates (schur_solve); a small pivot of M̃ gives way to
 *   AUGMENTED   the whole augmented matrix (factor_solve, also every other case), flagged
 *               VT_FALLBACK_SCHUR_PIVOT; with an estimate below rcond_warn the augmented route
 *               solves too and the answer of the higher estimate is kept (the augmented one:
 *               VT_FALLBACK_SCHUR_CONDITION)
 *   MAXIMAL     after FREE_RATES, SCHUR or AUGMENTED solved with an answer in doubt
 *               (maximal_wanted): the bodies' equations unreduced (maximal.c), kept where its
 *               estimate is the higher (VT_FALLBACK_MAXIMAL_CONDITION)
 * d->rcond is the pose's condition estimate (docs/method.md, "The condition estimate"): the free
 * rates' leaf-first pivot ratio (FREE_RATES); G Φ_q C's, squared (SQUARE); the same pivot ratio
 * over the rates no joint drive fixes times the other rows' unit-diagonal Schur complement's and
 * the point drives' grip² (SCHUR); the
 * scaled augmented matrix's times the grip² (AUGMENTED); the kept rows' matrix's singular value
 * ratio or (σ_kept / σ_max)² of Φ̂, the smaller (REDUNDANT); the answer's componentwise condition
 * bounded by Φ̂'s squared, times the grip² (MAXIMAL, maximal_alternative). Round-off of an exact zero taken for a row or an inertia is caught first
 * (roundoff_check). Below rcond_min the rows' rank (rows_decide)
 * tells dependent rows (VT_ERR_DEPENDENT_CONSTRAINTS, named) from a singular or ill-conditioned
 * matrix (VT_ERR_SINGULAR, saying which). Every solve starts from cleared diagnostics
 * (vt_solve_reset): on failure q̈ and λ are left as they were, the route is VT_ROUTE_NONE, the
 * warning 0, rcond what the route measured (0 if nothing) and rank what was found (0 if nothing). */
vt_status vt_solve_band(const vt_model *m, vt_data *d, double band, int dense)
{
    const int nv = m->nv, nc = m->nc;
    vt_solve_reset(d);
    if (!vt_all_finite(d->Q, nv) || !vt_all_finite(d->gamma, nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");
    /* round-off of an exact zero is neither a row nor an inertia: a rate without inertia that
     * nothing fixes is refused here, zero rows are dependent (rows_decide below says so) */
    const int zero_rows = roundoff_check(m, d, NULL, 1, dense);
    if (zero_rows == ROUNDOFF_COMPOSITE) return VT_NEEDS_DENSE;
    if (zero_rows < 0) return (vt_status)zero_rows;
    double rcond = 0.0;
    if (m->joint_rows_only) {
        int r = joint_rows_solve(m, d, &rcond);
        if (r < 0) return (vt_status)r;
        d->rank = nc; /* one unit row on a rate of its own each: independent */
        vt_route route = VT_ROUTE_FREE_RATES;
        if (dense && r == 0 && vt_maximal_wanted(m, rcond)) {
            const size_t mark = vt_scratch_mark(d);
            double *sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution");
            if (!sol) return vt_scratch_fail(d, mark);
            memcpy(sol, d->qdd, (size_t)nv * sizeof(double));
            memcpy(sol + nv, d->lambda, (size_t)nc * sizeof(double));
            const int t = maximal_wanted(m, d, r, rcond, sol, 0) ? maximal_alternative(m, d, &rcond, sol) : 0;
            if (t < 0) return vt_scratch_release(d, mark), (vt_status)t;
            if (t == 1) {
                memcpy(d->qdd, sol, (size_t)nv * sizeof(double));
                memcpy(d->lambda, sol + nv, (size_t)nc * sizeof(double));
                route = VT_ROUTE_MAXIMAL;
            }
            vt_scratch_release(d, mark);
        }
        if (r == 1) return d->rcond = rcond, singular(m, d, "free rates' scaled M*", rcond, NULL);
        vt_solved(m, d, route, rcond);
        return VT_OK;
    }
    const size_t mark = vt_scratch_mark(d);
    double *sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution");
    if (!sol) return vt_scratch_fail(d, mark);
    vt_status st = VT_OK;
    rows_svd o;
    if (m->allow_redundant && nc > 0) {
        /* rows first: exactly dependent rows would make every other route fail */
        const int r = rows_decide(m, d, band, &o);
        if (r < 0) return vt_scratch_release(d, mark), (vt_status)r;
        if (o.kept < nc) {
            st = redundant_solve(m, d, &o);
            if (!st) d->route = VT_ROUTE_REDUNDANT;
            vt_scratch_release(d, mark);
            return st;
        }
        vt_scratch_release(d, mark);
        sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution"); /* the same place again */
    }
    const int square = nc == nv && nc > 0;
    vt_route route = square ? VT_ROUTE_SQUARE : nc > 0 && nc < nv ? VT_ROUTE_SCHUR : VT_ROUTE_AUGMENTED;
    int r = zero_rows ? 1 : 2; /* sol holds [q̈; λ], or [q̈; −λ] on the augmented route (factor_solve) */
    if (r == 1) {} /* a zero row: nothing solved, diagnosed below */
    else if (route == VT_ROUTE_SQUARE) r = square_solve(m, d, sol, &rcond);
    else if (route == VT_ROUTE_SCHUR) {
        /* joint-driven rates known (as the recursive articulated route takes them), unless a
         * row is dependent on their drives by its kind (rates_known) or is round-off of zero on
         * the other rates: the whole system's rank then names it */
        int known = rates_known(m);
        if (known) {
            const int zf = vt_zero_rows_free(m, d, m->dof_drive);
            if (zf < 0) return vt_scratch_release(d, mark), (vt_status)zf;
            known = zf == 0;
        }
        r = schur_solve(m, d, known, sol, &rcond);
    }
    if (r == 3 || r == 4) {
        /* the Schur route's estimate below rcond_warn (4: solved) or rcond_min (3: not): the rows'
         * Schur complement in the mass metric can lose digits that the whole matrix keeps (a chain
         * whose masses rise by 1e3 a rod: 7e-13 against 2e-3; docs/accuracy.md, "Mass ratios").
         * The augmented route solves too, and the answer whose estimate is the higher is kept */
        double *alt = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "augmented route's solution");
        if (!alt) return vt_scratch_fail(d, mark);
        double rc = 0.0;
        const int ra = factor_solve(m, d, alt, &rc);
        if (ra < 0) return vt_scratch_release(d, mark), (vt_status)ra;
        if (ra == 0 && rc > rcond) {
            memcpy(sol, alt, ((size_t)nv + (size_t)nc) * sizeof(double));
            d->fallback |= VT_FALLBACK_SCHUR_CONDITION;
            route = VT_ROUTE_AUGMENTED;
            rcond = rc;
            r = 0;
        } else if (r == 4) r = 0; /* the Schur route's answer, and its estimate */
        else { /* neither above rcond_min: the higher one is diagnosed */
            if (rc > rcond) route = VT_ROUTE_AUGMENTED, rcond = rc, d->fallback |= VT_FALLBACK_SCHUR_CONDITION;
            r = 1;
        }
    }
    if (r == 2) {
        if (route == VT_ROUTE_SCHUR) d->fallback |= VT_FALLBACK_SCHUR_PIVOT;
        route = VT_ROUTE_AUGMENTED;
        r = factor_solve(m, d, sol, &rcond);
    }
    if (r < 0) return vt_scratch_release(d, mark), (vt_status)r;
    if (dense && !zero_rows && route != VT_ROUTE_SQUARE && maximal_wanted(m, d, r, rcond, sol, route == VT_ROUTE_AUGMENTED)) {
        const int t = maximal_alternative(m, d, &rcond, sol);
        if (t < 0) return vt_scratch_release(d, mark), (vt_status)t;
        if (t == 1) route = VT_ROUTE_MAXIMAL, r = 0;
    }
    if (r == 1) {
        /* below rcond_min: dependent rows, or a singular or ill-conditioned matrix */
        d->rcond = rcond;
        const char *what = route == VT_ROUTE_SQUARE ? "scaled Φ_q (squared)"
                         : route == VT_ROUTE_SCHUR  ? "Schur complement of the scaled (5)"
                                                    : "scaled augmented matrix of (5)";
        if (nc == 0) st = singular(m, d, what, rcond, NULL);
        else if ((st = (vt_status)rows_decide(m, d, 0.0, &o)) == VT_OK) {
            d->rank = o.rank;
            if (o.rank == nc) st = singular(m, d, what, rcond, &o);
            else { /* only without allow_redundant: with it, rows_decide above took them */
                int len = snprintf(d->message, sizeof d->message,
                                   "vt_solve: Φ_q has rank %d of %d rows (reciprocal condition %.3g of the %s); "
                                   "dependent:", o.rank, nc, rcond, what);
                for (int k = 0; k < nc && len < (int)sizeof d->message - 40; k++) {
                    if (!(null_part(m, &o, k) > NULL_PART_TOL)) continue;
                    char name[64];
                    len += snprintf(d->message + len, sizeof d->message - (size_t)len, " row %d (%s)", k,
                                    owner_name(m, k, name, sizeof name));
                }
                st = VT_ERR_DEPENDENT_CONSTRAINTS;
            }
        }
        vt_scratch_release(d, mark);
        return st;
    }
    vt_solved(m, d, route, rcond);
    memcpy(d->qdd, sol, (size_t)nv * sizeof(double));
    for (int k = 0; k < nc; k++) d->lambda[k] = route == VT_ROUTE_AUGMENTED ? -sol[nv + k] : sol[nv + k];
    vt_scratch_release(d, mark);
    return VT_OK;
}

vt_status vt_solve_impl(const vt_model *m, vt_data *d)
{
    return vt_solve_band(m, d, 0.0, 0);
}

vt_status vt_solve(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_solve");
    if (st) return st;
    d->fallback = 0;
    return vt_solve_band(m, d, 0.0, 1);
}

vt_status vt_solve_run(const vt_model *m, vt_data *d, double band)
{
    vt_status st = vt_check_pair(m, d, "vt_solve");
    if (st) return st;
    d->fallback = 0;
    return vt_solve_band(m, d, band, 1);
}

int vt_rows_rank(const vt_model *m, vt_data *d)
{
    if (m->nc == 0) return 0;
    const size_t mark = vt_scratch_mark(d);
    rows_svd o;
    const int r = rows_decide(m, d, 0.0, &o);
    vt_scratch_release(d, mark);
    return r < 0 ? r : o.rank;
}

/* The recursive evaluation's square route (recursive.c): vt_solve's square route in three steps
 * with M* q̈ − Q computed between the last two by a Newton–Euler pass instead of from M* and Q
 * (neither is formed). vt_solve_square_factor, from the positions alone: mdiag (nv) holds M*'s
 * diagonal, which scales the solves; the route's state (the LU of R Φ_q D) goes to *sq on the
 * arena (the caller releases it), the condition to *rcond. Returns 0, 1 (a zero row or
 * ill-conditioned: the caller falls back to vt_solve, which diagnoses it) or a negative
 * vt_status. Its LU also solves other right sides (vt_square_apply: the kinematic analysis's
 * velocities). vt_solve_square_accelerations: q̈ = Φ_q^-1 γ to sq->x. vt_solve_square_end: with
 * h = M* q̈ − Q in sq->h, λ, and everything vt_solve sets on success. */
int vt_solve_square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, double *rcond)
{
    const int zero_rows = roundoff_check(m, d, NULL, 0, 0); /* a zero row: the general route diagnoses it */
    if (zero_rows) return zero_rows < 0 ? zero_rows : 1;
    return square_factor(m, d, sq, mdiag, 1, rcond);
}

int vt_solve_square_accelerations(const vt_model *m, vt_data *d, vt_square *sq)
{
    if (!vt_all_finite(d->gamma, m->nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");
    return vt_square_apply(m, d, sq, d->gamma, 1.0, sq->x);
}

vt_status vt_solve_square_end(const vt_model *m, vt_data *d, vt_square *sq, double rcond)
{
    const int r = vt_square_second(m, d, sq);
    if (r) return (vt_status)r;
    vt_solved(m, d, VT_ROUTE_SQUARE, rcond);
    memcpy(d->qdd, sq->x, (size_t)m->nv * sizeof(double));
    memcpy(d->lambda, sq->h, (size_t)m->nc * sizeof(double));
    return VT_OK;
}

/* dgelsd's integer workspace for an m x n problem, from its workspace query */
int vt_dgelsd_iwork(int m, int n)
{
    if (m < 1 || n < 1) return 1; /* nothing to solve (and LAPACK's xerbla would stop the program) */
    const int one = 1, ld = m > n ? m : n, lw = -1;
    int info = 0, iq = 0, rank = 0;
    double q = 0.0, dummy = 0.0, rc = -1.0;
    dgelsd_(&m, &n, &one, &dummy, &m, &dummy, &ld, &dummy, &rc, &rank, &q, &lw, &iq, &info);
    return info == 0 && iq > 0 ? iq : 1;
}

/* The scratch solve.c takes at once: the largest route, with what vt_solve holds around it
 * (the solution, Φ_q^T's QR) and LAPACK's workspace by its own queries. */
size_t vt_solve_scratch(const vt_model *m)
{
    const int nv = m->nv, nc = m->nc, N = nv + nc, k = nc < nv ? nc : nv;
    const size_t sN = (size_t)N, snv = (size_t)nv, snc = (size_t)nc, D = sizeof(double), I = sizeof(int);
    int info = 0, lw = -1, idummy = 0, rank = 0;
    const int one = 1;
    double q = 0.0, dummy = 0.0, rc = -1.0;
    /* LAPACK's workspaces (the largest; a route takes it last, as the rest of the arena) */
    size_t lapack = 3 * sN + 1;
    dsytrf_rk_("L", &N, &dummy, &N, &dummy, &idummy, &q, &lw, &info, 1);
    if (info == 0 && q > (double)lapack) lapack = (size_t)q;
    if (nc > 0) {
        dgesvd_("A", "S", &nc, &nv, &dummy, &nc, &dummy, &dummy, &nc, &dummy, &k, &q, &lw, &info, 1, 1);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
        dgelsd_(&N, &N, &one, &dummy, &N, &dummy, &N, &dummy, &rc, &rank, &q, &lw, &idummy, &info);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
    }
    lapack = VT_SCRATCH_BYTES(lapack + 5 * (snc + snv), D);
    const size_t held = 2 * VT_SCRATCH_BYTES(sN, D); /* the solution; the augmented route's beside the Schur route's */
    const size_t small = VT_SCRATCH_BYTES((size_t)EXACT_RCOND_N * (EXACT_RCOND_N + EXACT_EXTRA), D) +
                         VT_SCRATCH_BYTES(sN, D) + /* an exact inverse, or dlansy's / dpocon's work */
                         VT_SCRATCH_BYTES((size_t)m->nbody + 1, D); /* massless()'s subtree inertias */
    size_t route = VT_SCRATCH_BYTES(sN * sN, D) + 4 * VT_SCRATCH_BYTES(2 * sN, D) + VT_SCRATCH_BYTES(sN, I);
    /* schur_solve: its index lists, L, B, S, the scaling, q̈ and λ̃ */
    const size_t schur = VT_SCRATCH_BYTES(sN, I) + VT_SCRATCH_BYTES(snv * snv, D) + VT_SCRATCH_BYTES(snv * (snc + 1), D) +
                         VT_SCRATCH_BYTES(snc * snc, D) + 2 * VT_SCRATCH_BYTES(sN, D);
    if (schur > route) route = schur;
    /* rows_decide's SVD (U, V^T, σ, both scalings; the scaled Φ_q while it runs), then
     * redundant_solve's reduced system */
    const size_t rows = VT_SCRATCH_BYTES(snc * snc, D) + VT_SCRATCH_BYTES((size_t)k * snv, D) +
                        VT_SCRATCH_BYTES((size_t)k, D) + VT_SCRATCH_BYTES(snc, D) + 2 * VT_SCRATCH_BYTES(snv, D);
    const size_t solve_kept = 2 * VT_SCRATCH_BYTES(sN * sN, D) + 3 * VT_SCRATCH_BYTES(sN, D) + VT_SCRATCH_BYTES(snc, D) +
                              VT_SCRATCH_BYTES(snc * (snv + 1), D) + VT_SCRATCH_BYTES(snc * (snv + 1) + 1, D) + VT_SCRATCH_BYTES((size_t)vt_dgelsd_iwork(N, N), I);
    const size_t after = VT_SCRATCH_BYTES(snc * snv, D) > solve_kept ? VT_SCRATCH_BYTES(snc * snv, D) : solve_kept;
    if (rows + after > route) route = rows + after;
    /* roundoff_check (before a route, and inside rows_decide with its flags), the square route's
     * condition (G Φ_q C, its pivots, its inverse) and vt_solve_spd's unit diagonal */
    const size_t nb1 = (size_t)m->nbody + 1;
    const size_t roundoff = VT_SCRATCH_BYTES(snv * (snc + 1), D) + VT_SCRATCH_BYTES(snv, D) +
                            VT_SCRATCH_BYTES(2 * snv, D) + VT_SCRATCH_BYTES(5 * nb1, D) +
                            2 * VT_SCRATCH_BYTES(snc + 1, I); /* B, β, vt_rate_bounds' T and w, L, flags */
    const size_t square = 2 * VT_SCRATCH_BYTES(snv * snv, D) + VT_SCRATCH_BYTES(4 * snv, D) + 2 * VT_SCRATCH_BYTES(snv, I);
    return held + route + small + lapack + roundoff + square + VT_SCRATCH_BYTES(snc, D) + 8 * VT_DATA_ALIGN;
}
