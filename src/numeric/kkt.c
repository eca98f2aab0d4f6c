/* The small dense kernels of the solve stage, called by its dense routes (dense/routes.c) and
 * by the recursive evaluation's routes alike, without the dense stage in between:
 *   - the exact reciprocal condition of small systems from their inverse (vt_small_inverse,
 *     vt_rcond_from_inverse) and the 1-norm of a symmetric matrix (vt_norm1_sym);
 *   - S b' = b for a symmetric positive definite S at unit diagonal, with its reciprocal
 *     condition (vt_solve_spd: the rows' Schur complement S = Φ̃ M̃^-1 Φ̃^T of (5));
 *   - the square route's LU: with as many independent rows as rates, (5) splits into its two
 *     block rows, Φ_q q̈ = γ and Φ_q^T λ = M* q̈ − Q ((5), (2)), both solved by one LU of the
 *     scaled Φ_q (vt_square_first/second/apply, and for the recursive evaluation
 *     vt_solve_square_factor/accelerations/end).
 * The augmented system they serve:
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "numeric/kkt.h"
#include "base/arena.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "numeric/rank.h"
#include "numeric/roundoff.h"
#include "numeric/route.h"

/* Small systems (n ≤ VT_EXACT_RCOND_N): the exact 1-norm reciprocal condition from the inverse
 * itself, the factors applied to the identity in one multi-right-hand-side solve (as much work
 * as the factorization), costs fewer instructions than LAPACK's estimators (dgecon, dsycon_3:
 * iterations of overflow-guarded triangular solves, dlatrs) and is exact, not a bound.
 * vt_small_inverse takes the identity X (n x n) with `extra` columns after it from the arena, or
 * returns NULL for a larger n (the caller then estimates) or when the arena failed (the
 * caller's next allocation says so). */
double *vt_small_inverse(vt_data *d, int n, int extra)
{
    if (n > VT_EXACT_RCOND_N) return NULL;
    double *X = VT_SCRATCH(d, double, (size_t)n * (size_t)(n + extra), "exact inverse");
    if (!X) return NULL;
    memset(X, 0, (size_t)n * (size_t)n * sizeof(double));
    for (int k = 0; k < n; k++) X[k + (size_t)k * (size_t)n] = 1.0;
    return X;
}

double vt_rcond_from_inverse(const double *X, int n, double anorm)
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
    double *X = vt_small_inverse(d, n, 1);
    if (X) { /* K^-1 and the solution in one solve: [I, b] */
        const int ncol = n + 1;
        double *xb = X + (size_t)n * (size_t)n;
        memcpy(xb, b, (size_t)n * sizeof(double));
        dpotrs_("L", &n, &ncol, K, &n, X, &n, &info, 1);
        if (info == 0) {
            *rcond = vt_rcond_from_inverse(X, n, anorm);
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
int vt_norm1_sym(vt_data *d, const double *K, int n, double *out)
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
        st = vt_norm1_sym(d, S, n, &snorm);
        if (!st) st = chol_solve(d, S, n, snorm, b, rcond);
    }
    for (int r = 0; r < n && e; r++) b[r] *= e[r];
    vt_scratch_release(d, mark);
    return st;
}

/* The order of R Φ_q D's columns in its LU (perm: column k of the LU's matrix is rate perm[k]),
 * fill-reducing: the rates a joint drive fixes first (the drive's row, a single entry, is then
 * a pivot that updates nothing), then the others by how many rows touch them, fewest first (a
 * leg's own rates before a platform's, whose columns every leg's rows share), ties in rate
 * order. Reference BLAS skips a zero of the pivot row in dger and a zero of the solution in
 * dtrsm: what the order keeps sparse is work not done. Partial pivoting's bound on growth holds
 * for any column order. The rows touching a rate are counted from the tree, not from Φ_q's
 * entries (no scan of nv² entries, and the order stays the same from one pose to the next): a
 * row between bodies a and b touches the rates of both paths, so rate k of body i counts the
 * rows with a body in i's subtree, the subtree sums of +1 at a and at b and −1 at their nearest
 * common ancestor (a row with both bodies below i counted once); a joint drive's row touches
 * its rate, a coupling's its non-zero entries. key: 2 nv + nbody + 3 ints of scratch. Returns 1
 * when the order is not the identity. Only from VT_ORDER_N rates: below, the order costs more
 * than the work it saves (the four-bars, the knee). */
#define VT_ORDER_N 17
static int column_order(const vt_model *m, const double *Phiq, int n, int *restrict perm, int *restrict key)
{
    const int nb = m->nbody;
    int *restrict sub = key + n, *restrict start = sub; /* sub: nbody + 1, then start: n + 2 */
    for (int i = 0; i <= nb; i++) sub[i] = 0;
    for (int c = 0; c < n; c++) key[c] = 0;
    int pa = -1, pb = -1, common = 0;
    for (int r = 0; r < n; r++) {
        const int kind = m->con_kind[r];
        if (kind == VT_ROW_JOINT) { /* its rate first, whatever else touches it */
            key[m->con_dof[r]] = -(n + 1) * n;
            continue;
        }
        if (kind == VT_ROW_COUPLING) {
            for (int c = 0; c < n; c++) key[c] += Phiq[r + (size_t)c * (size_t)n] != 0.0;
            continue;
        }
        const int ba = m->con_body[2 * r], bb = m->con_body[2 * r + 1];
        if (ba != pa || bb != pb) { /* a cut joint's rows share their bodies: walked once */
            pa = ba, pb = bb, common = ba; /* the nearest common ancestor: lower the larger id (a parent's is the smaller) */
            for (int y = bb; common != y;)
                if (common > y) common = m->body_parent[common];
                else y = m->body_parent[y];
        }
        sub[ba]++, sub[bb]++, sub[common]--;
    }
    for (int i = nb; i >= 1; i--)
        if (m->body_parent[i] > 0) sub[m->body_parent[i]] += sub[i];
    int sorted = 1;
    for (int c = 0; c < n; c++) {
        key[c] = key[c] < 0 ? 0 : key[c] + sub[m->dof_body[c]];
        if (key[c] > n) key[c] = n;
        sorted &= c == 0 || key[c] >= key[c - 1];
    }
    if (sorted) return 0; /* the rates' own order already */
    for (int v = 0; v < n + 2; v++) start[v] = 0;
    for (int c = 0; c < n; c++) start[key[c] + 1]++;
    for (int v = 1; v < n + 2; v++) start[v] += start[v - 1];
    for (int c = 0; c < n; c++) perm[start[key[c]]++] = c; /* stable: ties in rate order */
    return 1;
}

/* One right side w (n) of the LU's factors L U (dgetf2's, in A), in its row order: L U y = w
 * (lu_solve) or U^T L^T y = w (lu_solve_t), y over w. The callers take w from, and return y to,
 * the rows' own order by vt_square.rows (the interchanges), so that dgetrs's row swaps of the
 * vector are not made; dtrsv is dgetrs's dtrsm on one column */
static void lu_solve(const double *A, int n, double *w)
{
    vt_dtrsv('L', 'N', 'U', n, A, n, w, 1);
    vt_dtrsv('U', 'N', 'N', n, A, n, w, 1);
}

static void lu_solve_t(const double *A, int n, double *w)
{
    vt_dtrsv('U', 'T', 'N', n, A, n, w, 1);
    vt_dtrsv('L', 'T', 'U', n, A, n, w, 1);
}

/* the rate of the LU's column k: perm[k], or k without an order */
static inline int rate_at(const int *perm, int k)
{
    return perm ? perm[k] : k;
}

/* As many independent constraint rows as rates (a kinematically determined mechanism: the
 * drives fix the whole motion, as the crank of a four-bar does): Φ_q is square and (5) splits
 * into its two block rows,
 *
 *   Φ_q q̈ = γ,        Φ_q^T λ = M* q̈ − Q,                                   (5), (2)
 *
 one LU factorization of R Φ_q D (LAPACK dgetf2, partial pivoting, unblocked: at these sizes
 * the blocked dgetrf's recursion costs more than it saves; D = diag(M*_aa^(-1/2)), R each row to
 * unit norm in that metric) serving both solves (its triangular factors, then their transposes): M* is not
 * factorized at all. The motion is the rows' alone, and so is the question of its
 * conditioning, which is kinematic (the pose), whatever the inertias: the reported estimate is
 * the condition of Φ̂ = G Φ_q C (exact up to 16 rates, from the inverse of the solves' R Φ_q D
 * below, rescaled: one LU for both; above, LAPACK's estimator dlacn2, as dgecon runs it, with
 * solves on that LU), a scaling that makes Φ̂
 * dimensionless and its condition independent of units and of the scene's frame, and in which
 * no mass takes part: rows that measure angles by ℓ and
 * those that measure lengths by 1 (G; vt_rows_decide scales each row by its own terms instead), rates that turn (rotations, Euler
 * parameters) by 1/ℓ and those that translate by 1 (C), ℓ the rows' own lever arm (vt_rows_length,
 * a length of the rows' geometry). The two solves in sequence amplify errors by
 * cond(Φ̂) each, so the reported reciprocal condition is squared, the scale of the augmented
 * matrix's (whose inverse holds Φ_q^(-T) M* Φ_q^(-1)); the recursive square route computes the
 * same number. Returns VT_SOLVED, VT_BELOW_MIN (nothing solved) or a negative vt_status. */
static int square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, const double *b,
                         double *rcond_out)
{
    const int n = m->nv;
    sq->A = VT_SCRATCH(d, double, (size_t)n * (size_t)n, "LU of R Φ_q D");
    sq->s = VT_SCRATCH(d, double, 4 * (size_t)n, "scalings D and R, a solve's two vectors");
    sq->x = VT_SCRATCH(d, double, 2 * (size_t)n, "q̈ and M* q̈ − Q");
    sq->ipiv = VT_SCRATCH(d, int, 3 * (size_t)n, "pivots, the columns' and the rows' order");
    if (!sq->ipiv) return VT_ERR_NO_MEMORY;
    sq->h = sq->x + n;
    sq->g = sq->s + n;
    sq->w = sq->s + 2 * n;
    sq->perm = sq->ipiv + n;
    sq->rows = sq->ipiv + 2 * n;
    sq->solved = 0;
    double *restrict A = sq->A, *restrict s = sq->s, *restrict g = sq->g, *restrict w = sq->w;
    const double *restrict Phiq = d->Phiq;
    const size_t mark = vt_scratch_mark(d);
    double *gk = VT_SCRATCH(d, double, 4 * (size_t)n, "G and C, and their ratios to R and D");
    int *key = VT_SCRATCH(d, int, 2 * (size_t)n + (size_t)m->nbody + 3, "the columns' keys");
    if (!key) return vt_scratch_fail(d, mark);
    /* rg = R G^-1 and dc = D C^-1, the factors between the solves' matrix and Φ̂ (below; dc in
     * the LU's column order) */
    double *restrict ck = gk + n, *restrict rg = gk + 2 * n, *restrict dc = gk + 3 * n;
    /* Φ̂ = G Φ_q C's scalings and its 1-norm, the largest column sum */
    const double rho = vt_rows_length(m, d, NULL);
    for (int a = 0; a < n; a++) ck[a] = vt_dof_turns(m, a) ? 1.0 / rho : 1.0;
    for (int r = 0; r < n; r++) gk[r] = vt_length_row(m, d, r) ? 1.0 : rho;
    double anorm = 0.0;
    for (int c = 0; c < n; c++) {
        double cs = 0.0;
        for (int r = 0; r < n; r++) cs += fabs(gk[r] * Phiq[r + (size_t)c * (size_t)n] * ck[c]);
        anorm = cs > anorm ? cs : anorm;
    }
    /* the solves' matrix R Φ_q D, D the mass metric and R each row to unit norm in it. Its LU's
     * pivots then take the rows that act on heavy rates for those rates, and the substitutions
     * keep apart what the structure keeps apart: a light link's drive force is not made of a
     * heavy one's round-off (the inverse, a dense product, would mix them). The rows' norms
     * column by column: each row's sum in the same order, all rows at once. Its columns in the
     * order column_order gives: Φ_q x = b is (R Φ_q D P) (P^T D^-1 x) = R b, and Φ_q^T λ = h is
     * (R Φ_q D P)^T (R^-1 λ) = P^T D h */
    vt_scaling_diag(m, mdiag, stride, s);
    for (int r = 0; r < n; r++) g[r] = 0.0;
    for (int c = 0; c < n; c++) {
        const double *restrict col = Phiq + (size_t)c * (size_t)n;
        const double sc = s[c];
        for (int r = 0; r < n; r++) g[r] += col[r] * sc * col[r] * sc;
    }
    for (int r = 0; r < n; r++) g[r] = g[r] > 0.0 ? 1.0 / sqrt(g[r]) : 1.0;
    if (n < VT_ORDER_N || !column_order(m, Phiq, n, sq->perm, key)) sq->perm = NULL;
    const int *restrict perm = sq->perm;
    for (int k = 0; k < n; k++) {
        const int c = rate_at(perm, k);
        const double *restrict col = Phiq + (size_t)c * (size_t)n;
        const double sc = s[c];
        for (int r = 0; r < n; r++) A[r + (size_t)k * (size_t)n] = g[r] * col[r] * sc;
    }
    for (int a = 0; a < n; a++) rg[a] = g[a] / gk[a], dc[a] = s[rate_at(perm, a)] / ck[rate_at(perm, a)];
    int info = 0;
    dgetf2_(&n, &n, A, &n, sq->ipiv, &info);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetf2 info %d", info);
    if (info > 0) return vt_scratch_release(d, mark), *rcond_out = 0.0, VT_BELOW_MIN; /* an exactly zero pivot */
    /* the row interchanges composed once: the solves below read and write their vectors in the
     * LU's row order directly, the triangular factors' BLAS solves on them (what dgetrs does,
     * without its copy of the interchanges, dlaswp, over every right side) */
    int *restrict rows = sq->rows;
    for (int k = 0; k < n; k++) rows[k] = k;
    for (int k = 0; k < n; k++) {
        const int p = sq->ipiv[k] - 1, t = rows[k];
        rows[k] = rows[p], rows[p] = t;
    }
    /* the condition of Φ̂ = G R^-1 (R Φ_q D) D^-1 C: up to 16 rates exactly, from the inverse of
     * R Φ_q D (one solve with the identity on the factors at hand; its rows in the columns'
     * order, which the norm does not see), Φ̂^-1 = C^-1 D (R Φ_q D)^-1 R G^-1 entry by entry;
     * above, LAPACK's estimator of ‖Φ̂^-1‖_1 on the same factors. A right side b at hand takes a
     * column of the solve the condition makes first (the same substitutions as a solve of its
     * own, without a call of its own) */
    double rcond = 0.0;
    double *X = vt_small_inverse(d, n, b ? 1 : 0);
    if (X) {
        /* the identity's rows and b's in the LU's row order: X = (R Φ_q D P)^-1 = U^-1 L^-1 Π,
         * Π the interchanges (rows) */
        const int ncol = b ? n + 1 : n;
        double *xb = X + (size_t)n * (size_t)n;
        for (int k = 0; k < n; k++) X[k + (size_t)k * (size_t)n] = 0.0, X[k + (size_t)rows[k] * (size_t)n] = 1.0;
        if (b)
            for (int k = 0; k < n; k++) xb[k] = g[rows[k]] * b[rows[k]];
        vt_dtrsm('L', 'L', 'N', 'U', n, ncol, 1.0, A, n, X, n);
        vt_dtrsm('L', 'U', 'N', 'N', n, ncol, 1.0, A, n, X, n);
        double xn = 0.0; /* ‖Φ̂^-1‖_1 */
        for (int c = 0; c < n; c++) {
            const double fc = rg[c];
            double cs = 0.0;
            for (int k = 0; k < n; k++) cs += fabs(X[k + (size_t)c * (size_t)n] * (dc[k] * fc));
            xn = cs > xn ? cs : xn; /* fmax without the call (a NaN is skipped by both) */
        }
        rcond = anorm > 0.0 && xn > 0.0 ? 1.0 / (anorm * xn) : 0.0;
        if (b) {
            for (int k = 0; k < n; k++) sq->x[rate_at(perm, k)] = xb[k] * s[rate_at(perm, k)];
            sq->solved = 1;
        }
    } else {
        /* ‖Φ̂^-1‖_1 by Hager and Higham's estimator (LAPACK's dlacn2, as dgecon uses it) on the
         * factors at hand: Φ̂^-1 x = C^-1 D (R Φ_q D)^-1 R G^-1 x and its transpose, each product
         * one solve with the LU above (a second LU of Φ̂ itself would cost as much again), the
         * rates taken back to their own order (the estimator sees Φ̂ itself) */
        double *v = VT_SCRATCH(d, double, 2 * (size_t)n, "dlacn2's vectors");
        int *isgn = VT_SCRATCH(d, int, n, "dlacn2's signs");
        if (!isgn) return vt_scratch_fail(d, mark);
        double *x = v + n, est = 0.0;
        int kase = 0, isave[3] = {0, 0, 0};
        do {
            dlacn2_(&n, v, x, isgn, &est, &kase, isave);
            if (kase == 0) break;
            /* each solve on w (its columns' order), x in the rates' own */
            if (kase == 1) {
                for (int k = 0; k < n; k++) w[k] = x[rows[k]] * rg[rows[k]];
                /* its first product is a solve with Φ_q: b beside it, in w's next column */
                const int both = b && !sq->solved;
                if (both) {
                    for (int k = 0; k < n; k++) w[n + k] = g[rows[k]] * b[rows[k]];
                    lu_solve(A, n, w + n);
                }
                lu_solve(A, n, w);
                for (int k = 0; k < n; k++) x[rate_at(perm, k)] = w[k] * dc[k];
                if (both) {
                    for (int k = 0; k < n; k++) sq->x[rate_at(perm, k)] = w[n + k] * s[rate_at(perm, k)];
                    sq->solved = 1;
                }
            } else {
                for (int k = 0; k < n; k++) w[k] = x[rate_at(perm, k)] * dc[k];
                lu_solve_t(A, n, w);
                for (int k = 0; k < n; k++) x[rows[k]] = w[k] * rg[rows[k]];
            }
        } while (1);
        rcond = anorm > 0.0 && est > 0.0 && isfinite(est) ? 1.0 / (anorm * est) : 0.0;
    }
    vt_scratch_release(d, mark);
    *rcond_out = rcond * rcond;
    return *rcond_out >= m->rcond_min ? VT_SOLVED : VT_BELOW_MIN;
}

int vt_square_apply(const vt_model *m, vt_data *d, const vt_square *sq, const double *b, double sign, double *x)
{
    (void)d;
    const int n = m->nv;
    double *w = sq->w;
    /* y = (R Φ_q D P)^-1 R b, x = ± D P y */
    for (int k = 0; k < n; k++) w[k] = sq->g[sq->rows[k]] * b[sq->rows[k]];
    lu_solve(sq->A, n, w);
    for (int k = 0; k < n; k++) x[rate_at(sq->perm, k)] = w[k] * (sign * sq->s[rate_at(sq->perm, k)]);
    return 0;
}

int vt_square_first(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond_out)
{
    return square_factor(m, d, sq, mdiag, stride, d->gamma, rcond_out); /* with q̈ = Φ_q^-1 γ */
}

int vt_square_second(const vt_model *m, vt_data *d, vt_square *sq)
{
    const int n = m->nv;
    double *g = sq->h, *w = sq->w;
    for (int k = 0; k < n; k++) w[k] = g[rate_at(sq->perm, k)] * sq->s[rate_at(sq->perm, k)]; /* P^T D h */
    lu_solve_t(sq->A, n, w);
    for (int k = 0; k < n; k++) g[sq->rows[k]] = w[k] * sq->g[sq->rows[k]];
    if (!vt_all_finite(sq->x, 2 * n)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    return 0;
}

/* The recursive evaluation's square route (recursive.c): vt_solve's square route in three steps
 * with M* q̈ − Q computed between the last two by a Newton–Euler pass instead of from M* and Q
 * (neither is formed). vt_solve_square_factor, from the positions alone: mdiag (nv) holds M*'s
 * diagonal, which scales the solves; the route's state (the LU of R Φ_q D) goes to *sq on the
 * arena (the caller releases it), the condition to *rcond; vt_solve_square_factor_with also solves
 * b (nv, or NULL), γ when it is known already, with the condition's first solve. Returns VT_SOLVED, VT_BELOW_MIN (a zero row or
 * ill-conditioned: the caller falls back to vt_solve, which diagnoses it) or a negative
 * vt_status. Its LU also solves other right sides (vt_square_apply: the kinematic analysis's
 * velocities). vt_solve_square_accelerations: q̈ = Φ_q^-1 γ to sq->x (solved already when γ was
 * b). vt_solve_square_end: with
 * h = M* q̈ − Q in sq->h, λ, and everything vt_solve sets on success. */
int vt_solve_square_factor_with(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, const double *b,
                                double *rcond)
{
    const int zero_rows = vt_roundoff_check(m, d, NULL, 0, VT_FORM_TWISTS); /* a zero row: the general route diagnoses it */
    if (zero_rows) return zero_rows < 0 ? zero_rows : VT_BELOW_MIN;
    return square_factor(m, d, sq, mdiag, 1, b, rcond);
}

int vt_solve_square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, double *rcond)
{
    return vt_solve_square_factor_with(m, d, sq, mdiag, NULL, rcond);
}

int vt_solve_square_accelerations(const vt_model *m, vt_data *d, vt_square *sq)
{
    if (!vt_all_finite(d->gamma, m->nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");
    return sq->solved ? 0 : vt_square_apply(m, d, sq, d->gamma, 1.0, sq->x);
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

/* The scratch kkt.c takes at once: the square route's state (the LU of R Φ_q D, its scalings,
 * q̈ and M* q̈ − Q, a solve's vector, its pivots, column and row orders), held by its caller, with
 * the columns' keys, G, C and their ratios to R and D and
 * the condition's inverse with a right side (n ≤ 16) or dlacn2's vectors; or vt_solve_spd's unit diagonal and its Cholesky's
 * inverse or dlansy's and dpocon's workspaces (n ≤ nc: the rows' Schur complement): the larger,
 * since different routes take them and neither calls the other */
size_t vt_kkt_scratch(const vt_model *m)
{
    const size_t snv = (size_t)m->nv, snc = (size_t)m->nc, D = sizeof(double), I = sizeof(int);
    /* the square route's LU: only with as many rows as rates (nv² is then the rows' own size) */
    const size_t square = m->nc != m->nv ? 0
                          : VT_SCRATCH_BYTES(snv * snv, D) + VT_SCRATCH_BYTES(4 * snv, D) + VT_SCRATCH_BYTES(2 * snv, D) +
                                VT_SCRATCH_BYTES(3 * snv, I) + VT_SCRATCH_BYTES(4 * snv, D) + VT_SCRATCH_BYTES(2 * snv + (size_t)m->nbody + 3, I) +
                                VT_SCRATCH_BYTES(snv * (snv + 1), D) + VT_SCRATCH_BYTES(2 * snv, D) + VT_SCRATCH_BYTES(snv, I);
    const size_t exact = VT_SCRATCH_BYTES((size_t)VT_EXACT_RCOND_N * (VT_EXACT_RCOND_N + VT_EXACT_EXTRA), D);
    const size_t pocon = VT_SCRATCH_BYTES(3 * snc, D) + VT_SCRATCH_BYTES(snc, I);
    size_t spd = exact > pocon ? exact : pocon;
    if (VT_SCRATCH_BYTES(snc, D) > spd) spd = VT_SCRATCH_BYTES(snc, D); /* dlansy's */
    spd += VT_SCRATCH_BYTES(snc, D);
    return square > spd ? square : spd; /* the square route and the SPD solve never nest */
}
