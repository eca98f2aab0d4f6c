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
 * kg·m², kg, m, rad) so that dsycon's reciprocal condition estimate measures the mechanism
 * rather than its units; how, is said where it is done. A system whose
 * estimate falls below rcond_min is refused: Φ_q of full row rank with M* singular on its null
 * space means a motion without inertia that nothing fixes (VT_ERR_SINGULAR); rows of Φ_q that
 * a rank-revealing QR with column pivoting (dgeqp3 on the row-normalized Φ_q^T) finds dependent
 * are named (VT_ERR_DEPENDENT_CONSTRAINTS). Two other paths, each said where it is done: as
 * many rows as rates (LU of Φ_q alone, square_solve) and, for models that allow redundant
 * rows, the minimum-norm least-squares solution by SVD (redundant_solve).
 */
#include <stdio.h>
#include <string.h>

#include "internal.h"

static const char *owner_name(const vt_model *m, int row, char *buf, size_t n)
{
    const int kind = vt_row_owner_kind(m, row);
    if (kind == VT_OWNER_DRIVE) snprintf(buf, n, "drive %d", m->con_owner[row]);
    else if (kind == VT_OWNER_CUT) snprintf(buf, n, "cut joint %d", m->con_owner[row]);
    else if (kind == VT_OWNER_COUPLING) snprintf(buf, n, "coupling %d", m->con_owner[row]);
    else snprintf(buf, n, "p^T p = 1 of body %d", m->con_owner[row]);
    return buf;
}

/* Rank of Φ_q by QR with column pivoting of its row-normalized transpose; the pivots past the
 * rank are the dependent rows. The QR goes to A (nv x nc) and its pivots to jpvt (nc), which
 * the redundant route reads. Returns the rank (the message lists the dependent rows) or a
 * negative vt_status. */
static int dependent_rows(const vt_model *m, vt_data *d, double rcond, double tau, double *A, int *jpvt)
{
    const int nv = m->nv, nc = m->nc;
    const size_t mark = vt_scratch_mark(d);
    int lwork = 0;
    double *tau_qr = VT_SCRATCH(d, double, nc, "QR τ");
    double *work = vt_scratch_rest(d, 3 * (size_t)nc + 1, sizeof(double), &lwork, "dgeqp3 workspace");
    if (!work) return vt_scratch_fail(d, mark);
    for (int r = 0; r < nc; r++) {
        double s = 0.0;
        for (int c = 0; c < nv; c++) s += d->Phiq[r + (size_t)c * (size_t)nc] * d->Phiq[r + (size_t)c * (size_t)nc];
        s = s > 0.0 ? 1.0 / sqrt(s) : 0.0;
        for (int c = 0; c < nv; c++) A[c + (size_t)r * (size_t)nv] = s * d->Phiq[r + (size_t)c * (size_t)nc];
        jpvt[r] = 0;
    }
    int info = 0;
    dgeqp3_(&nv, &nc, A, &nv, jpvt, tau_qr, work, &lwork, &info);
    vt_scratch_release(d, mark);
    if (info != 0) return nc;
    const int kmax = nv < nc ? nv : nc;
    const double r11 = kmax > 0 ? fabs(A[0]) : 0.0;
    int rank = 0;
    while (rank < kmax && fabs(A[rank + (size_t)rank * (size_t)nv]) > tau * r11) rank++;
    if (rank == nc) return rank;
    /* rcond is NaN when the rank is checked first (models that allow redundant rows) */
    int len = isnan(rcond) ? snprintf(d->message, sizeof d->message,
                                      "vt_solve: Φ_q has rank %d of %d rows; dependent:", rank, nc)
                           : snprintf(d->message, sizeof d->message,
                                      "vt_solve: rcond %.3g; Φ_q has rank %d of %d rows; dependent:", rcond, rank, nc);
    for (int k = rank; k < nc && len < (int)sizeof d->message - 40; k++) {
        char name[64];
        const int row = jpvt[k] - 1;
        len += snprintf(d->message + len, sizeof d->message - (size_t)len, " row %d (%s)", row,
                        owner_name(m, row, name, sizeof name));
    }
    return rank;
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
    if (n <= 1) { /* one row: S is a number, its condition exactly 1 */
        *rcond = n == 0 || S[0] > 0.0 ? 1.0 : 0.0;
        if (n == 1 && *rcond > 0.0) b[0] /= S[0];
        return 0;
    }
    double snorm = 0.0;
    const int st = norm1_sym(d, S, n, &snorm);
    return st ? st : chol_solve(d, S, n, snorm, b, rcond);
}

/* The symmetric scaling D of (5): the rates by the mass metric, d_a = M*_aa^(-1/2), into
 * s[0..nv); with rows, every constraint row by one common factor, 1 / (largest row norm of
 * Φ_q D), into s[nv..nv+nc). One factor for all rows keeps their relative sizes: a drive whose
 * row shrinks toward a singular pose (an arm reaching its full stretch) shows in the condition
 * estimate instead of being scaled away, as a row-by-row equilibration (LAPACK's dsyequb)
 * would do. scaling_diag: the rates' part from M*'s diagonal mdiag[a stride] (s may be mdiag
 * itself with stride 1). */
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
    double rmax = 0.0;
    for (int r = 0; r < nc; r++) {
        double rn = 0.0;
        for (int c = 0; c < nv; c++) {
            const double v = d->Phiq[r + (size_t)c * (size_t)nc] * s[c];
            rn += v * v;
        }
        rmax = fmax(rmax, sqrt(rn));
    }
    for (int r = 0; r < nc; r++) s[nv + r] = rmax > 0.0 ? 1.0 / rmax : 1.0;
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
     * themselves, the correction from the same factors): the common row factor above can
     * leave the scaled matrix less well balanced than a row-by-row equilibration would */
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

/* Redundant rows (models that allow them): the constraint rows reduced to their independent
 * directions, then (5) on those. With the scaling of factor_solve, Φ̃ = c Φ_q D = U Σ V^T
 * (LAPACK dgesvd); the directions with σ ≥ VT_REDUNDANT_TOL σ_max (1e-3) are kept as the rows
 * R = Σ_r V_r^T with right-hand side U_r^T c γ, the others dropped; the reduced system
 * [M̃ R^T; R 0] [ỹ; −μ] = [D Q; U_r^T c γ] is solved by dgelsd (minimum norm, for an M* singular
 * on directions R fixes), q̈ = D ỹ and λ = c U_r μ, of minimum norm. With exactly dependent rows
 * and consistent γ this is (5) itself. Where a row is about to become dependent (a singular
 * pose, as the IFToMM N-four-bar's horizontal one) or drift makes γ slightly inconsistent, the
 * nearly dependent direction is dropped instead of amplified by 1/σ², which is what carries a
 * time analysis through the pose; the price is a constraint held in the least-squares sense
 * within that band (Baumgarte's terms of the ODE form close it after). Then the residual
 * max |Φ_q q̈ − γ|, and which multipliers are not unique: those that change along the null
 * directions z of Φ_q^T, from the QR of dependent_rows (z = P [−R11^{-1} R12; I] in the
 * row-normalized space), which are left in d->lambda_null for the reactions stage to tell
 * which reactions are not unique. */
void vt_mark_unique(const vt_model *m, vt_data *d)
{
    const int nc = m->nc;
    int *lu = d->lambda_unique;
    for (int r = 0; r < nc; r++) lu[r] = 1;
}

/* A (nv x nc) and jpvt (nc): the QR of the row-normalized Φ_q^T and its pivots (dependent_rows) */
static vt_status redundant_solve(const vt_model *m, vt_data *d, int rank, const double *A, const int *jpvt)
{
    const int nv = m->nv, nc = m->nc, nfree = nc - rank, N = nv + nc, one = 1;
    const size_t mark = vt_scratch_mark(d);
    double *X = VT_SCRATCH(d, double, (size_t)rank * (size_t)nfree, "R11^-1 R12");
    double *rownorm = VT_SCRATCH(d, double, nc, "row norms"), *Ur = VT_SCRATCH(d, double, (size_t)nc * (size_t)nc, "U_r");
    double *K = VT_SCRATCH(d, double, (size_t)N * (size_t)N, "reduced augmented matrix");
    double *b = VT_SCRATCH(d, double, N, "right side"), *s = VT_SCRATCH(d, double, N, "scaling");
    double *sv = VT_SCRATCH(d, double, N, "singular values");
    int *perm = VT_SCRATCH(d, int, nc, "row permutation");
    if (!perm) return vt_scratch_fail(d, mark);
    for (int k = 0; k < nc; k++) perm[k] = jpvt[k] - 1;
    for (int r = 0; r < nc; r++) {
        double sn = 0.0;
        for (int c = 0; c < nv; c++) sn += d->Phiq[r + (size_t)c * (size_t)nc] * d->Phiq[r + (size_t)c * (size_t)nc];
        rownorm[r] = sqrt(sn);
    }
    /* X = R11^{-1} R12 (before dgelsd reuses the workspace) */
    for (int j = 0; j < nfree; j++)
        for (int i = 0; i < rank; i++) X[i + (size_t)j * (size_t)rank] = A[i + (size_t)(rank + j) * (size_t)nv];
    int info = 0;
    if (rank > 0 && nfree > 0) {
        dtrtrs_("U", "N", "N", &rank, &nfree, A, &nv, X, &rank, &info, 1, 1, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dtrtrs info %d", info);
    }
    /* the scaled rows Φ̃ = c Φ_q D and their SVD U Σ V^T (dgesvd); the directions with
     * σ < VT_REDUNDANT_TOL σ_max are dropped, the others kept as the rows Σ_r V_r^T with the
     * right-hand side U_r^T c γ: the least-squares constraint on the rows' independent
     * directions, bounded where a row is about to become dependent (a singular pose) and whatever
     * drift makes γ inconsistent */
    scaling(m, d, s, 1);
    const double c = s[nv];
    const int k = nc < nv ? nc : nv;
    const size_t mark_svd = vt_scratch_mark(d);
    double *P = VT_SCRATCH(d, double, (size_t)nc * (size_t)nv, "scaled Φ_q");
    double *U = VT_SCRATCH(d, double, (size_t)nc * (size_t)k, "U"), *VT = VT_SCRATCH(d, double, (size_t)k * (size_t)nv, "V^T");
    double *sig = VT_SCRATCH(d, double, k, "σ");
    int lw = 0;
    double *svd_work = vt_scratch_rest(d, 5 * (size_t)(nc + nv), sizeof(double), &lw, "dgesvd workspace");
    if (!svd_work) return vt_scratch_fail(d, mark);
    for (int a = 0; a < nv; a++)
        for (int r = 0; r < nc; r++) P[r + (size_t)a * (size_t)nc] = c * d->Phiq[r + (size_t)a * (size_t)nc] * s[a];
    /* LAPACK stops the program (xerbla) on some NaN inputs: refuse non-finite input first */
    if (!vt_all_finite(P, nc * nv) || !vt_all_finite(s, nv) || !vt_all_finite(d->Mstar, nv * nv))
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in the scaled M* or Φ_q (overflow)");
    dgesvd_("S", "S", &nc, &nv, P, &nc, sig, U, &nc, VT, &k, svd_work, &lw, &info, 1, 1);
    if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgesvd info %d", info);
    int nr = 0;
    while (nr < k && sig[nr] > VT_REDUNDANT_TOL * sig[0]) nr++;
    memcpy(Ur, U, (size_t)nc * (size_t)nr * sizeof(double));
    /* the reduced augmented matrix [M̃ R^T; R 0], R = Σ_r V_r^T, both triangles */
    const int Nr = nv + nr;
    const size_t ld = (size_t)Nr;
    for (int j = 0; j < Nr; j++)
        for (int i = 0; i < Nr; i++) {
            double v = 0.0;
            if (i < nv && j < nv) v = d->Mstar[i + (size_t)j * (size_t)nv] * s[i] * s[j];
            else if (i >= nv && j < nv) v = sig[i - nv] * VT[(i - nv) + (size_t)j * (size_t)k];
            else if (i < nv && j >= nv) v = sig[j - nv] * VT[(j - nv) + (size_t)i * (size_t)k];
            K[i + j * ld] = v;
        }
    for (int a = 0; a < nv; a++) b[a] = d->Q[a] * s[a];
    for (int i = 0; i < nr; i++) {
        double v = 0.0;
        for (int r = 0; r < nc; r++) v += Ur[r + (size_t)i * (size_t)nc] * c * d->gamma[r];
        b[nv + i] = v;
    }
    vt_scratch_release(d, mark_svd); /* the SVD's arrays: U_r is kept */
    const double rc = m->rcond_min; /* M̃ alone may still be singular on directions R fixes */
    int rk = 0, lwd = 0;
    int *iwork = VT_SCRATCH(d, int, vt_dgelsd_iwork(Nr, Nr), "dgelsd integer workspace");
    double *lsq_work = vt_scratch_rest(d, 1, sizeof(double), &lwd, "dgelsd workspace");
    if (!lsq_work) return vt_scratch_fail(d, mark);
    dgelsd_(&Nr, &Nr, &one, K, &Nr, b, &Nr, sv, &rc, &rk, lsq_work, &lwd, iwork, &info);
    if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgelsd info %d", info);
    d->rcond = rk > 0 ? sv[rk - 1] / sv[0] : 0.0;
    if (rk < Nr)
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_SINGULAR,
                       "vt_solve: Φ_q has rank %d of %d rows, and the reduced augmented matrix keeps rank %d of %d "
                       "(rcond %.3g): a motion without inertia that nothing fixes", nr, nc, rk, Nr, d->rcond);
    /* q̈ = D ỹ; λ = c U_r μ (minimum norm: in the range of U_r), with b = [ỹ; −μ] */
    for (int a = 0; a < nv; a++) b[a] *= s[a];
    for (int r = 0; r < nc; r++) {
        double v = 0.0;
        for (int i = 0; i < nr; i++) v += Ur[r + (size_t)i * (size_t)nc] * b[nv + i];
        sv[r] = -c * v;
    }
    if (!vt_all_finite(b, nv) || !vt_all_finite(sv, nc))
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    memcpy(d->qdd, b, (size_t)nv * sizeof(double));
    memcpy(d->lambda, sv, (size_t)nc * sizeof(double));
    double resid = 0.0;
    for (int r = 0; r < nc; r++) {
        double v = -d->gamma[r];
        for (int a = 0; a < nv; a++) v += d->Phiq[r + (size_t)a * (size_t)nc] * d->qdd[a];
        resid = fmax(resid, fabs(v));
    }
    d->residual = resid;
    /* the null directions z of Φ_q^T: which multipliers they change (and, in the reactions
     * stage, which reactions) */
    vt_mark_unique(m, d);
    for (int j = 0; j < nfree; j++) {
        double *z = d->lambda_null + (size_t)j * (size_t)nc, zmax = 0.0;
        memset(z, 0, (size_t)nc * sizeof(double));
        for (int i = 0; i < rank; i++) z[perm[i]] = -X[i + (size_t)j * (size_t)rank];
        z[perm[rank + j]] = 1.0;
        for (int r = 0; r < nc; r++) { /* back from the row-normalized space */
            if (rownorm[r] > 0.0) z[r] /= rownorm[r];
            zmax = fmax(zmax, fabs(z[r]));
        }
        for (int r = 0; r < nc; r++)
            if (fabs(z[r]) > 1e-9 * zmax) d->lambda_unique[r] = 0;
    }
    vt_scratch_release(d, mark);
    d->rank = rank;
    d->warning = (d->rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0) | VT_WARN_REDUNDANT;
    return VT_OK;
}

/* Every row a joint drive q_k = f_k(t) on a rate of its own: those rates' q̈ are γ, and (5)
 * reduces to the free rates F, M*_FF q̈_F = Q_F − M*_FD q̈_D, with M*_FF symmetric positive
 * definite: LAPACK's Cholesky (dpotf2/dpotrs) and its condition (small_inverse, or dpocon) on the
 * mass-metric scaled matrix; then λ_D = (M* q̈ − Q)_D. The same solution as (5), a fraction of
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
    for (int c = 0; c < nv; c++)
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
    double anorm = 0.0, rcond = 0.0;
    int st = norm1_sym(d, K, nf, &anorm);
    if (!st) st = chol_solve(d, K, nf, anorm, b, &rcond);
    if (st) return vt_scratch_release(d, mark), st;
    *rcond_out = rcond;
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), 1;
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
 * one LU factorization of Φ_q D (LAPACK dgetf2, partial pivoting, unblocked: at these sizes the
 * blocked dgetrf's recursion costs more than it saves; D = diag(M*_aa^(-1/2)), the
 * mass metric of factor_solve) serving both solves (dgetrs, then its transpose; or products
 * with the inverse that small systems compute for their condition anyway). M* is not
 * factorized at all: a quarter of the augmented matrix's size, an eighth of its work. The two
 * solves in sequence amplify errors by cond(Φ_q D) each, so the reported reciprocal condition is
 * squared, the scale of the augmented matrix's (whose inverse holds Φ_q^(-T) M* Φ_q^(-1)).
 * Returns 0, 1 (below rcond_min: nothing solved) or a negative vt_status. */
int vt_square_first(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond_out)
{
    const int n = m->nv;
    sq->A = VT_SCRATCH(d, double, (size_t)n * (size_t)n, "LU of Φ_q D");
    sq->s = VT_SCRATCH(d, double, n, "scaling");
    sq->x = VT_SCRATCH(d, double, 2 * (size_t)n, "q̈ and M* q̈ − Q");
    sq->ipiv = VT_SCRATCH(d, int, n, "pivots");
    if (!sq->ipiv) return VT_ERR_NO_MEMORY;
    sq->h = sq->x + n;
    double *A = sq->A, *s = sq->s, *x = sq->x;
    scaling_diag(m, mdiag, stride, s);
    double anorm = 0.0; /* ‖Φ_q D‖_1, the largest column sum, as the columns are scaled */
    for (int c = 0; c < n; c++) {
        double cs = 0.0;
        for (int r = 0; r < n; r++) {
            const double v = d->Phiq[r + (size_t)c * (size_t)n] * s[c];
            A[r + (size_t)c * (size_t)n] = v;
            cs += fabs(v);
        }
        anorm = cs > anorm ? cs : anorm;
    }
    int info = 0;
    dgetf2_(&n, &n, A, &n, sq->ipiv, &info);
    if (info < 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetf2 info %d", info);
    double rcond = 0.0;
    sq->X = info == 0 ? small_inverse(d, n, 1) : NULL; /* kept for the second half */
    if (sq->X) { /* the inverse X */
        dgetrs_("N", &n, &n, A, &n, sq->ipiv, sq->X, &n, &info, 1);
        if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetrs info %d", info);
        rcond = rcond_from_inverse(sq->X, n, anorm);
    } else if (info == 0) {
        const size_t mark = vt_scratch_mark(d);
        double *work = VT_SCRATCH(d, double, 4 * (size_t)n, "dgecon workspace");
        int *iwork = VT_SCRATCH(d, int, n, "dgecon integer workspace");
        if (!iwork) return vt_scratch_fail(d, mark);
        dgecon_("1", &n, A, &n, &anorm, &rcond, work, iwork, &info, 1);
        vt_scratch_release(d, mark);
        if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgecon info %d", info);
    }
    *rcond_out = rcond * rcond;
    if (!(*rcond_out >= m->rcond_min)) return 1;
    /* y = (Φ_q D)^-1 γ, q̈ = D y: with the inverse at hand (small systems) by loops, else with
     * the LU factors */
    if (sq->X) {
        const double *X = sq->X;
        for (int r = 0; r < n; r++) x[r] = 0.0;
        for (int c = 0; c < n; c++)
            for (int r = 0; r < n; r++) x[r] += X[r + (size_t)c * (size_t)n] * d->gamma[c];
    } else {
        const int one = 1;
        memcpy(x, d->gamma, (size_t)n * sizeof(double));
        dgetrs_("N", &n, &one, A, &n, sq->ipiv, x, &n, &info, 1);
        if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetrs info %d", info);
    }
    for (int a = 0; a < n; a++) x[a] *= s[a];
    return 0;
}

int vt_square_second(const vt_model *m, vt_data *d, vt_square *sq)
{
    const int n = m->nv, one = 1;
    double *g = sq->h;
    int info = 0;
    for (int a = 0; a < n; a++) g[a] *= sq->s[a];
    if (sq->X) { /* λ = X^T g, by loops at n ≤ 16; the inverse's extra column holds g */
        const double *X = sq->X;
        double *h = sq->X + (size_t)n * (size_t)n;
        memcpy(h, g, (size_t)n * sizeof(double));
        for (int a = 0; a < n; a++) {
            double v = 0.0;
            for (int r = 0; r < n; r++) v += X[r + (size_t)a * (size_t)n] * h[r];
            g[a] = v;
        }
    } else {
        dgetrs_("T", &n, &one, sq->A, &n, sq->ipiv, g, &n, &info, 1);
        if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgetrs info %d", info);
    }
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
 * scaled variables (M̃ = D M* D with unit diagonal, Φ̃ = c Φ_q D, as factor_solve):
 *
 *   M̃ = L L^T,   Y = L^-1 Φ̃^T,   z = L^-1 D Q,   S = Y^T Y = Φ̃ M̃^-1 Φ̃^T,
 *   S λ̃ = c γ − Y^T z,   ỹ = L^-T (z + Y λ̃),   q̈ = D ỹ,   λ = c λ̃,
 *
 * two Cholesky factorizations (LAPACK dpotf2, unblocked like dgetf2 above, of nv and of nc
 * unknowns) instead of the symmetric indefinite one of nv + nc: about a third of the work, and
 * no pivoting. It applies when every pivot of L is at least 1e-4 (M̃'s unit diagonal bounds them
 * by 1 from above): below that M* is (nearly) singular on some rates, which only the constraints
 * may fix, and factor_solve takes over (return 2). The reported reciprocal condition is S's
 * (exact: 1 for one row, for nc ≤ 16 from its inverse; dpocon's estimate above) times (min L_kk / max L_kk)²,
 * the pivots' estimate of M̃'s: it falls where the constraint rows lose independence in the
 * mass metric — a drive losing its grip. Returns 0, 1 (below rcond_min), 2 or a negative
 * vt_status. */
#define SCHUR_FEW 3 /* rows up to which S and its right side are formed by loops */
static int schur_solve(const vt_model *m, vt_data *d, double *sol, double *rcond_out)
{
    const int nv = m->nv, nc = m->nc, nrhs = nc + 1;
    const size_t mark = vt_scratch_mark(d);
    double *L = VT_SCRATCH(d, double, (size_t)nv * (size_t)nv, "Cholesky factor of M̃");
    double *B = VT_SCRATCH(d, double, (size_t)nv * (size_t)nrhs, "L^-1 [Φ̃^T, D Q]");
    double *S = VT_SCRATCH(d, double, (size_t)nc * (size_t)nc, "Schur complement");
    double *s = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "scaling");
    if (!s) return vt_scratch_fail(d, mark);
    double *x = sol, *lam = sol + nv;
    scaling(m, d, s, 1);
    const double c = s[nv];
    for (int j = 0; j < nv; j++) {
        const double *restrict Mc = d->Mstar + (size_t)j * (size_t)nv;
        double *restrict Lc = L + (size_t)j * (size_t)nv;
        const double sj = s[j];
        for (int i = j; i < nv; i++) Lc[i] = Mc[i] * s[i] * sj;
    }
    int info = 0;
    dpotf2_("L", &nv, L, &nv, &info, 1);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dpotf2 info %d", info);
    if (info > 0) return vt_scratch_release(d, mark), 2;
    double lmin = 1.0, lmax = 0.0;
    for (int k = 0; k < nv; k++) {
        const double lk = L[k + (size_t)k * (size_t)nv];
        if (!(lk >= 1e-4)) return vt_scratch_release(d, mark), 2;
        lmin = lk < lmin ? lk : lmin; /* not fmin/fmax: lk is a number here, and they are calls */
        lmax = lk > lmax ? lk : lmax;
    }
    /* B = [Φ̃^T, D Q], then L^-1 B */
    for (int r = 0; r < nc; r++)
        for (int a = 0; a < nv; a++) B[a + (size_t)r * (size_t)nv] = c * d->Phiq[r + (size_t)a * (size_t)nc] * s[a];
    for (int a = 0; a < nv; a++) B[a + (size_t)nc * (size_t)nv] = d->Q[a] * s[a];
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, nv, nrhs, 1.0, L, nv, B, nv);
    const double *Y = B, *z = B + (size_t)nc * (size_t)nv;
    /* S = Y^T Y and its right-hand side c γ − Y^T z. With a few rows (a point drive: 1 to 3)
     * these are a few dot products of nv terms, cheaper as loops than as BLAS calls (whose
     * argument checks cost more than the products); one row makes S a positive number, its
     * Cholesky factor a square root, and S's condition exactly 1. */
    const int few = nc <= SCHUR_FEW;
    if (few) {
        for (int r = 0; r < nc; r++) {
            const double *yr = Y + (size_t)r * (size_t)nv;
            double t = c * d->gamma[r];
            for (int a = 0; a < nv; a++) t -= yr[a] * z[a];
            lam[r] = t;
            for (int k = r; k < nc; k++) {
                const double *yk = Y + (size_t)k * (size_t)nv;
                double v = 0.0;
                for (int a = 0; a < nv; a++) v += yk[a] * yr[a];
                S[k + (size_t)r * (size_t)nc] = v;
            }
        }
    } else {
        cblas_dsyrk(CblasColMajor, CblasLower, CblasTrans, nc, nv, 1.0, Y, nv, 0.0, S, nc);
        for (int r = 0; r < nc; r++) lam[r] = c * d->gamma[r];
        cblas_dgemv(CblasColMajor, CblasTrans, nv, nc, -1.0, Y, nv, z, 1, 1.0, lam, 1);
    }
    double rcond = 0.0;
    const int st = vt_solve_spd(d, S, nc, lam, &rcond);
    if (st) return vt_scratch_release(d, mark), st;
    rcond *= (lmin / lmax) * (lmin / lmax);
    *rcond_out = rcond;
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), 1;
    /* ỹ = L^-T (z + Y λ̃) */
    memcpy(x, z, (size_t)nv * sizeof(double));
    if (few) {
        for (int r = 0; r < nc; r++) {
            const double *yr = Y + (size_t)r * (size_t)nv, l = lam[r];
            for (int a = 0; a < nv; a++) x[a] += yr[a] * l;
        }
    } else {
        cblas_dgemv(CblasColMajor, CblasNoTrans, nv, nc, 1.0, Y, nv, lam, 1, 1.0, x, 1);
    }
    cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, nv, L, nv, x, 1);
    for (int a = 0; a < nv; a++) x[a] *= s[a];
    for (int r = 0; r < nc; r++) lam[r] *= c;
    vt_scratch_release(d, mark);
    if (!vt_all_finite(x, nv + nc)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    return 0;
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

/* The bodies that make a solve singular by having nothing to move: a free rate (no joint drive)
 * whose body and everything beyond it carry neither mass nor inertia. Written into buf (n
 * bytes) as " (body 3, body 5 ...: no mass or inertia beyond a free joint)", empty if none. */
static void massless(const vt_model *m, vt_data *d, char *buf, size_t n)
{
    buf[0] = '\0';
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
    size_t len = 0;
    int count = 0;
    for (int i = 1; i <= m->nbody && len + 40 < n; i++) {
        int free_rate = 0;
        for (int k = 0; k < m->body_nv[i]; k++) free_rate |= m->dof_drive[m->body_vadr[i] + k] < 0;
        if (w[i] != 0.0 || !free_rate) continue;
        len += (size_t)snprintf(buf + len, n - len, "%s body %d", count++ ? "," : " (", i);
    }
    if (count) snprintf(buf + len, n - len, ": no mass or inertia beyond a free joint)");
    vt_scratch_release(d, mark);
}

/* The routes, cheapest first (the model's rows decide; vt_data.route records the one taken):
 *   FREE_RATES  every row a joint drive on a rate of its own (joint_rows_solve)
 *   REDUNDANT   allow_redundant and Φ_q found rank-deficient first (redundant_solve)
 *   SQUARE      as many rows as rates (square_solve); ill-conditioned: diagnosed, no fallback
 *   SCHUR       fewer rows than rates (schur_solve); a small pivot of M̃ gives way to
 *   AUGMENTED   the whole augmented matrix (factor_solve, also every other case), flagged
 *               VT_FALLBACK_SCHUR_PIVOT
 * d->rcond is the reciprocal condition of what the route factorized: the free rates' scaled M*
 * (FREE_RATES); Φ_q D's, squared (SQUARE); the Schur complement's times M̃'s pivot ratio squared
 * (SCHUR); the scaled augmented matrix's (AUGMENTED); the reduced system's singular value ratio
 * (REDUNDANT). A lone row's condition is 1 on the Schur route (the scaling normalizes it): a
 * lone drive losing its grip does not show there. On failure q̈ and λ are left as they were and
 * the route is VT_ROUTE_NONE. */
vt_status vt_solve_impl(const vt_model *m, vt_data *d)
{
    const int nv = m->nv, nc = m->nc;
    d->route = VT_ROUTE_NONE;
    if (!vt_all_finite(d->Q, nv) || !vt_all_finite(d->gamma, nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");
    double rcond = 0.0;
    if (m->joint_rows_only) {
        const int r = joint_rows_solve(m, d, &rcond);
        if (r < 0) return (vt_status)r;
        d->rcond = rcond;
        d->warning = rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0;
        if (r == 1) {
            char who[128];
            massless(m, d, who, sizeof who);
            return vt_fail(d->message, VT_ERR_SINGULAR,
                           "vt_solve: the free rates' mass matrix has rcond %.3g < %.3g: a motion without inertia "
                           "that no drive fixes%s", rcond, m->rcond_min, who);
        }
        vt_solved(m, d, VT_ROUTE_FREE_RATES, rcond);
        return VT_OK;
    }
    const size_t mark = vt_scratch_mark(d);
    double *qr = NULL, *sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution");
    int *jpvt = NULL;
    if (nc > 0) {
        qr = VT_SCRATCH(d, double, (size_t)nv * (size_t)nc, "QR of Φ_q^T");
        jpvt = VT_SCRATCH(d, int, nc, "QR pivots");
    }
    if (!vt_scratch_ok(d)) return vt_scratch_fail(d, mark);
    vt_status st = VT_OK;
    if (m->allow_redundant && nc > 0) {
        /* rank first: near a redundant model's constraint manifold Φ_q is only nearly
         * rank-deficient, and solving its near-dependent rows exactly would amplify the drift */
        const int rank = dependent_rows(m, d, NAN, VT_REDUNDANT_TOL, qr, jpvt);
        if (rank < 0 || rank < nc) {
            st = rank < 0 ? (vt_status)rank : redundant_solve(m, d, rank, qr, jpvt);
            if (!st) d->route = VT_ROUTE_REDUNDANT;
            vt_scratch_release(d, mark);
            return st;
        }
    }
    const int square = nc == nv && nc > 0;
    vt_route route = square ? VT_ROUTE_SQUARE : nc > 0 && nc < nv ? VT_ROUTE_SCHUR : VT_ROUTE_AUGMENTED;
    int r = 2; /* sol holds [q̈; λ], or [q̈; −λ] on the augmented route (factor_solve) */
    if (route == VT_ROUTE_SQUARE) r = square_solve(m, d, sol, &rcond);
    else if (route == VT_ROUTE_SCHUR) r = schur_solve(m, d, sol, &rcond);
    if (r == 2) {
        if (route == VT_ROUTE_SCHUR) d->fallback |= VT_FALLBACK_SCHUR_PIVOT;
        route = VT_ROUTE_AUGMENTED;
        r = factor_solve(m, d, sol, &rcond);
    }
    if (r < 0) return vt_scratch_release(d, mark), (vt_status)r;
    d->rcond = rcond;
    d->warning = rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0;
    if (r == 1) {
        /* the augmented matrix's condition goes as the square of Φ_q's: rows are dependent to the
         * precision rcond_min asks for when R's diagonal falls below sqrt(rcond_min) of its first */
        const int rank = nc > 0 ? dependent_rows(m, d, rcond, sqrt(m->rcond_min), qr, jpvt) : nc;
        if (rank < 0) st = (vt_status)rank;
        else if (rank < nc && m->allow_redundant) {
            st = redundant_solve(m, d, rank, qr, jpvt);
            if (!st) d->route = VT_ROUTE_REDUNDANT;
        } else if (rank < nc) st = VT_ERR_DEPENDENT_CONSTRAINTS;
        else {
            char who[128];
            massless(m, d, who, sizeof who);
            st = vt_fail(d->message, VT_ERR_SINGULAR,
                         "vt_solve: augmented matrix of (5) has rcond %.3g < %.3g: the drives and cut joints "
                         "leave a motion unfixed that has no inertia, or a singular pose%s",
                         rcond, m->rcond_min, who);
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

vt_status vt_solve(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_solve");
    if (st) return st;
    d->fallback = 0;
    return vt_solve_impl(m, d);
}

/* The recursive evaluation's square route (recursive.c): vt_solve's square route in two halves
 * with M* q̈ − Q computed between them by a Newton–Euler pass instead of from M* and Q (neither
 * is formed). vt_solve_square_begin: mdiag (nv) holds M*'s diagonal, which sets the scaling D;
 * the route's state goes to *sq on the arena (the caller releases it), q̈ to sq->x, the
 * condition to *rcond. Returns 0, 1 (ill-conditioned: the caller falls back to vt_solve, which
 * diagnoses it) or a negative vt_status. vt_solve_square_end: with h = M* q̈ − Q in sq->h, λ,
 * and everything vt_solve sets on success. */
int vt_solve_square_begin(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, double *rcond)
{
    if (!vt_all_finite(d->gamma, m->nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");
    return vt_square_first(m, d, sq, mdiag, 1, rcond);
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
        dgeqp3_(&nv, &nc, &dummy, &nv, &idummy, &dummy, &q, &lw, &info);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
        dgesvd_("S", "S", &nc, &nv, &dummy, &nc, &dummy, &dummy, &nc, &dummy, &k, &q, &lw, &info, 1, 1);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
        dgelsd_(&N, &N, &one, &dummy, &N, &dummy, &N, &dummy, &rc, &rank, &q, &lw, &idummy, &info);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
    }
    lapack = VT_SCRATCH_BYTES(lapack + 5 * (snc + snv), D);
    const size_t held = VT_SCRATCH_BYTES(sN, D) + VT_SCRATCH_BYTES(snv * snc, D) + VT_SCRATCH_BYTES(snc, I) +
                        VT_SCRATCH_BYTES(snc, D); /* solution, QR, pivots, τ */
    const size_t small = VT_SCRATCH_BYTES((size_t)EXACT_RCOND_N * (EXACT_RCOND_N + EXACT_EXTRA), D) +
                         VT_SCRATCH_BYTES(sN, D); /* an exact inverse, or dlansy's / dpocon's work */
    size_t route = VT_SCRATCH_BYTES(sN * sN, D) + 4 * VT_SCRATCH_BYTES(2 * sN, D) + VT_SCRATCH_BYTES(sN, I);
    const size_t redundant = VT_SCRATCH_BYTES(snc * snc, D) * 2 + VT_SCRATCH_BYTES(snc, D) + VT_SCRATCH_BYTES(sN * sN, D) +
                             3 * VT_SCRATCH_BYTES(sN, D) + VT_SCRATCH_BYTES(snc, I) +
                             VT_SCRATCH_BYTES((size_t)vt_dgelsd_iwork(N, N), I) + VT_SCRATCH_BYTES(snc * snv, D) +
                             VT_SCRATCH_BYTES(snc * (size_t)k, D) + VT_SCRATCH_BYTES((size_t)k * snv, D) +
                             VT_SCRATCH_BYTES((size_t)k, D);
    if (redundant > route) route = redundant;
    return held + route + small + lapack + 8 * VT_DATA_ALIGN;
}
