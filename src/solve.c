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
 * and the rook variant bounds the entries of L (and its BLAS-3 solves cost 18 % fewer
 * instructions per instant on the four-bar than dsytrs/dsycon's BLAS-2 loops, by callgrind).
 * Before factorizing, the matrix is scaled symmetrically (its rows and columns mix units:
 * kg·m², kg, m, rad) so that dsycon's reciprocal condition estimate measures the mechanism
 * rather than its units; how, is said where it is done. A system whose
 * estimate falls below rcond_min is refused: Φ_q of full row rank with M* singular on its null
 * space means a motion without inertia that nothing fixes (VT_ERR_SINGULAR); rows of Φ_q that
 * a rank-revealing QR with column pivoting (dgeqp3 on the row-normalized Φ_q^T) finds dependent
 * are named (VT_ERR_DEPENDENT_CONSTRAINTS).
 */
#include <stdio.h>
#include <string.h>

#include "internal.h"

static const char *owner_name(const vt_model *m, int row, char *buf, size_t n)
{
    const int kind = vt_row_owner_kind(m, row);
    if (kind == VT_OWNER_DRIVE) snprintf(buf, n, "drive %d", m->con_owner[row]);
    else if (kind == VT_OWNER_CUT) snprintf(buf, n, "cut joint %d", m->con_owner[row]);
    else snprintf(buf, n, "p^T p = 1 of body %d", m->con_owner[row]);
    return buf;
}

/* Rank of Φ_q by QR with column pivoting of its row-normalized transpose; the pivots past the
 * rank are the dependent rows. Returns the rank; the message lists those rows. */
static int dependent_rows(const vt_model *m, vt_data *d, double rcond)
{
    const int nv = m->nv, nc = m->nc;
    double *A = d->lwork, *tau = A + (size_t)nv * (size_t)nc, *work = tau + nc;
    int *jpvt = d->liwork;
    const int lwork = d->nlwork - nv * nc - nc;
    for (int r = 0; r < nc; r++) {
        double s = 0.0;
        for (int c = 0; c < nv; c++) s += d->Phiq[r + (size_t)c * (size_t)nc] * d->Phiq[r + (size_t)c * (size_t)nc];
        s = s > 0.0 ? 1.0 / sqrt(s) : 0.0;
        for (int c = 0; c < nv; c++) A[c + (size_t)r * (size_t)nv] = s * d->Phiq[r + (size_t)c * (size_t)nc];
        jpvt[r] = 0;
    }
    int info = 0;
    dgeqp3_(&nv, &nc, A, &nv, jpvt, tau, work, &lwork, &info);
    if (info != 0) return nc;
    const int kmax = nv < nc ? nv : nc;
    const double r11 = kmax > 0 ? fabs(A[0]) : 0.0;
    int rank = 0;
    while (rank < kmax && fabs(A[rank + (size_t)rank * (size_t)nv]) > 1e-9 * r11) rank++;
    if (rank == nc) return rank;
    int len = snprintf(d->message, sizeof d->message,
                       "vt_solve: rcond %.3g; Φ_q has rank %d of %d rows; dependent:", rcond, rank, nc);
    for (int k = rank; k < nc && len < (int)sizeof d->message - 40; k++) {
        char name[64];
        const int row = jpvt[k] - 1;
        len += snprintf(d->message + len, sizeof d->message - (size_t)len, " row %d (%s)", row,
                        owner_name(m, row, name, sizeof name));
    }
    return rank;
}

vt_status vt_solve(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_solve");
    if (st) return st;
    const int nv = m->nv, nc = m->nc, N = nv + nc, one = 1;
    const size_t ld = (size_t)N;
    double *K = d->kkt, *b = d->kkt_rhs, *s = d->kkt_scale;

    if (!vt_all_finite(d->Q, nv) || !vt_all_finite(d->gamma, nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");

    /* lower triangle: M* then Φ_q below it, zero block */
    for (int c = 0; c < nv; c++) {
        for (int r = c; r < nv; r++) K[r + c * ld] = d->Mstar[r + (size_t)c * (size_t)nv];
        for (int r = 0; r < nc; r++) K[nv + r + c * ld] = d->Phiq[r + (size_t)c * (size_t)nc];
    }
    for (int c = nv; c < N; c++)
        for (int r = c; r < N; r++) K[r + c * ld] = 0.0;
    memcpy(b, d->Q, (size_t)nv * sizeof(double));
    memcpy(b + nv, d->gamma, (size_t)nc * sizeof(double));

    int info = 0;
    /* symmetric scaling D K D: the rates by the mass metric, d_a = M*_aa^(-1/2), and every
     * constraint row by one common factor, 1 / (largest row norm of Φ_q D). One factor for all
     * rows keeps their relative sizes: a drive whose row shrinks toward a singular pose (an arm
     * reaching its full stretch) shows in the condition estimate instead of being scaled away,
     * as a row-by-row equilibration (LAPACK's dsyequb) would do. */
    for (int a = 0; a < nv; a++) {
        const double mii = d->Mstar[a + (size_t)a * (size_t)nv];
        s[a] = mii > 0.0 ? 1.0 / sqrt(mii) : 1.0;
    }
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
    for (int c = 0; c < N; c++) {
        for (int r = c; r < N; r++) K[r + c * ld] *= s[r] * s[c];
        b[c] *= s[c];
    }

    const double anorm = dlansy_("1", "L", &N, K, &N, d->lwork, 1, 1);
    double *E = d->kkt_scale + N; /* the off-diagonal of D (rk format) */
    dsytrf_rk_("L", &N, K, &N, E, d->ipiv, d->lwork, &d->nlwork, &info, 1);
    if (info < 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrf info %d", info);
    double rcond = 0.0;
    if (info == 0) {
        dsycon_3_("L", &N, K, &N, E, d->ipiv, &anorm, &rcond, d->lwork, d->liwork, &info, 1);
        if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsycon info %d", info);
    }
    d->rcond = rcond;
    d->warning = rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0;
    if (!(rcond >= m->rcond_min)) {
        if (nc > 0 && dependent_rows(m, d, rcond) < nc) return VT_ERR_DEPENDENT_CONSTRAINTS;
        return vt_fail(d->message, VT_ERR_SINGULAR,
                       "vt_solve: augmented matrix of (5) has rcond %.3g < %.3g: the drives and cut joints "
                       "leave a motion unfixed that has no inertia, or a singular pose",
                       rcond, m->rcond_min);
    }
    dsytrs_3_("L", &N, &one, K, &N, E, d->ipiv, b, &N, &info, 1);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs info %d", info);
    for (int k = 0; k < N; k++) b[k] *= s[k];
    /* one step of iterative refinement on the unscaled system (the residual from M* and Φ_q
     * themselves, the correction from the same factors): the common row factor above can
     * leave the scaled matrix less well balanced than a row-by-row equilibration would */
    double *res = d->lwork;
    memcpy(res, d->Q, (size_t)nv * sizeof(double));
    cblas_dgemv(CblasColMajor, CblasNoTrans, nv, nv, -1.0, d->Mstar, nv, b, 1, 1.0, res, 1);
    if (nc > 0) {
        cblas_dgemv(CblasColMajor, CblasTrans, nc, nv, -1.0, d->Phiq, nc, b + nv, 1, 1.0, res, 1);
        memcpy(res + nv, d->gamma, (size_t)nc * sizeof(double));
        cblas_dgemv(CblasColMajor, CblasNoTrans, nc, nv, -1.0, d->Phiq, nc, b, 1, 1.0, res + nv, 1);
    }
    for (int k = 0; k < N; k++) res[k] *= s[k];
    dsytrs_3_("L", &N, &one, K, &N, E, d->ipiv, res, &N, &info, 1);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs info %d", info);
    for (int k = 0; k < N; k++) b[k] += res[k] * s[k];
    if (!vt_all_finite(b, N)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    memcpy(d->qdd, b, (size_t)nv * sizeof(double));
    for (int r = 0; r < nc; r++) d->lambda[r] = -b[nv + r];
    return VT_OK;
}
