/* The five routes of the solve stage, each a way to solve the augmented system of the paper's (5):
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 *
 * so that M* q̈ = Q + Φ_q^T λ (2) and Φ_q q̈ = γ, cheapest first:
 *   free rates  every row a joint drive on a rate of its own: Cholesky of the free rates' M*
 *               (vt_free_rates_solve)
 *   redundant   rows dependent to round-off (or within a time analysis's band) taken out by the
 *               SVD of the rank decision (vt_redundant_solve)
 *   square      as many rows as rates: one LU of the scaled Φ_q (vt_square_solve, its factors in
 *               numeric/kkt.c)
 *   Schur       fewer rows than rates, M* well conditioned: two Cholesky factorizations
 *               (vt_schur_solve)
 *   augmented   the whole matrix, LDL^T with rook pivoting (vt_augmented_solve)
 * Each returns VT_OK and its outcome (vt_outcome, numeric/route.h: solved, below rcond_min, or
 * why it gives way), or a negative vt_status; which route is taken, and what follows an
 * outcome, is the dispatcher's (vt_solve_band, dense/solve.c).
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "dense/routes.h"
#include "base/arena.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"
#include "model/model.h"
#include "numeric/kkt.h"
#include "numeric/rank.h"
#include "numeric/route.h"

/* Factor and solve the augmented system of (5) into b = [q̈; −λ] (nv + nc); the condition
 * estimate into *rcond_out, the outcome into *out: VT_SOLVED, or VT_BELOW_MIN (the estimate below
 * rcond_min: nothing solved, the dispatcher diagnoses). Returns VT_OK or a negative vt_status. */
vt_status vt_augmented_solve(const vt_model *m, vt_data *d, double *b, double *rcond_out, vt_outcome *out)
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

    /* symmetric scaling D K D (vt_scaling) */
    vt_scaling(m, d, s, 1);
    for (int c = 0; c < N; c++) {
        for (int r = c; r < N; r++) K[r + c * ld] *= s[r] * s[c];
        b[c] *= s[c];
    }

    int info = 0, lwork = 0, st = 0;
    double anorm = 0.0;
    if ((st = vt_norm1_sym(d, K, N, &anorm))) return vt_scratch_release(d, mark), (vt_status)st;
    const size_t mark_work = vt_scratch_mark(d);
    double *work = vt_scratch_rest(d, 2 * ld, sizeof(double), &lwork, "dsytrf_rk workspace");
    if (!work) return vt_scratch_fail(d, mark);
    dsytrf_rk_("L", &N, K, &N, E, ipiv, work, &lwork, &info, 1);
    vt_scratch_release(d, mark_work);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrf_rk info %d", info);
    double rcond = 0.0;
    double *X = info == 0 ? vt_small_inverse(d, N, 0) : NULL;
    const int inverse = X != NULL;
    if (inverse) {
        dsytrs_3_("L", &N, &N, K, &N, E, ipiv, X, &N, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs_3 info %d", info);
        rcond = vt_rcond_from_inverse(X, N, anorm);
    } else if (info == 0) {
        work = VT_SCRATCH(d, double, 2 * ld, "dsycon_3 workspace");
        int *iwork = VT_SCRATCH(d, int, N, "dsycon_3 integer workspace");
        if (!iwork) return vt_scratch_fail(d, mark);
        dsycon_3_("L", &N, K, &N, E, ipiv, &anorm, &rcond, work, iwork, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsycon_3 info %d", info);
    }
    if (nc > 0) {
        double grip = 1.0;
        if ((st = vt_rows_grip(m, d, &grip))) return vt_scratch_release(d, mark), (vt_status)st;
        rcond *= grip;
    }
    *rcond_out = rcond;
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), *out = VT_BELOW_MIN, VT_OK;
    double *t = res + N;
    /* with the inverse at hand (small systems) each solve is a product, else a solve with the
     * factors */
    if (inverse) {
        memcpy(t, b, (size_t)N * sizeof(double));
        vt_dgemv('N', N, N, 1.0, X, N, t, 1, 0.0, b, 1);
    } else {
        dsytrs_3_("L", &N, &one, K, &N, E, ipiv, b, &N, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs_3 info %d", info);
    }
    for (int k = 0; k < N; k++) b[k] *= s[k];
    /* one step of iterative refinement on the unscaled system (the residual from M* and Φ_q
     * themselves, the correction from the same factors): the symmetric scaling balances the
     * matrix only as far as its diagonal and its rows' norms show */
    memcpy(res, d->Q, (size_t)nv * sizeof(double));
    vt_dgemv('N', nv, nv, -1.0, d->Mstar, nv, b, 1, 1.0, res, 1);
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
        vt_dgemv('N', N, N, 1.0, X, N, res, 1, 0.0, t, 1);
        memcpy(res, t, (size_t)N * sizeof(double));
    } else {
        dsytrs_3_("L", &N, &one, K, &N, E, ipiv, res, &N, &info, 1);
        if (info != 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dsytrs_3 info %d", info);
    }
    for (int k = 0; k < N; k++) b[k] += res[k] * s[k];
    vt_scratch_release(d, mark);
    if (!vt_all_finite(b, N)) return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    *out = VT_SOLVED;
    return VT_OK;
}

/* Redundant rows (models that allow them): (5) with the rows' dropped directions taken out
 * (vt_rows_decide: those dependent to round-off, and a time analysis's band). With U_d the dropped
 * columns of U and P = I − U_d U_d^T, the rows Y = P G Φ_q (the original rows, each less its
 * parts along the dropped directions: round-off where those are dependent to round-off, so a row
 * stays itself and the rows of two unrelated bodies are not mixed), then vt_augmented_solve's scaling:
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
vt_status vt_redundant_solve(const vt_model *m, vt_data *d, const vt_rows_svd *o)
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
        vt_dgemm('T', 'N', nd, nv + 1, nc, 1.0, U + (size_t)nr * snc, nc, P, nc, 0.0,
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
    vt_dgemv('N', N, N, -1.0, K0, N, b, 1, 1.0, b0, 1);
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
    if (nv > 0) vt_dgemv('N', nv, nv, 1.0, d->Mstar, nv, b, 1, 1.0, F, 1);
    for (int a = 0; a < nv; a++) F[a] *= s[a];
    double *B = K; /* nv x nr, leading dimension nv: D Φ_q^T G U_k = D P^T U_k */
    if (nr > 0 && nv > 0) {
        vt_dgemm('T', 'N', nv, nr, nc, 1.0, P, nc, U, nc, 0.0, B, nv);
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
    if (nr > 0) vt_dgemv('N', nc, nr, 1.0, U, nc, F, 1, 0.0, sv, 1);
    for (int r = 0; r < nc; r++) sv[r] = o->flag[r] ? 0.0 : g[r] * sv[r];
    if (!vt_all_finite(b, nv) || !vt_all_finite(sv, nc))
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: solution not finite");
    double resid = 0.0; /* how well the kept rows hold: max |Φ_q q̈ − γ| (it may overflow: refused) */
    double *res = P; /* nc: P is no longer read */
    for (int r = 0; r < nc; r++) res[r] = -d->gamma[r];
    if (nv > 0) vt_dgemv('N', nc, nv, 1.0, d->Phiq, nc, b, 1, 1.0, res, 1);
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
        if (vt_null_part(m, o, r) > VT_NULL_PART_TOL) d->lambda_unique[r] = 0;
    d->warning = (d->rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0) | (o->rank < nc ? VT_WARN_REDUNDANT : 0) |
                 (nr < o->rank ? VT_WARN_BAND : 0);
    return VT_OK;
}

/* Every row a joint drive q_k = f_k(t) on a rate of its own: those rates' q̈ are γ, and (5)
 * reduces to the free rates F, M*_FF q̈_F = Q_F − M*_FD q̈_D, with M*_FF symmetric positive
 * definite: LAPACK's Cholesky (dpotf2/dpotrs) on the mass-metric scaled matrix, its free rates in
 * descending order (leaf first), its condition estimate min/max of the pivots L_kk² (each
 * relative to its unit diagonal: the recursive articulated route's number); then λ_D = (M* q̈ − Q)_D. The same solution as (5), a fraction of
 * the work. The outcome into *out: VT_SOLVED, or VT_BELOW_MIN (nothing solved). Returns VT_OK or a
 * negative vt_status. */
vt_status vt_free_rates_solve(const vt_model *m, vt_data *d, double *rcond_out, vt_outcome *out)
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
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), *out = VT_BELOW_MIN, VT_OK;
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
    *out = VT_SOLVED;
    return VT_OK;
}

/* The square route of vt_solve: as many rows as rates, (5) split into its two block rows and
 * both solved by one LU of the scaled Φ_q (vt_square_first/second, numeric/kkt.c, which says how
 * and what the estimate is). [q̈; λ] into b, the outcome into *out: VT_SOLVED, or VT_BELOW_MIN
 * (an exactly zero pivot or the estimate below rcond_min: nothing solved, and no other route is
 * tried, the motion being the rows' alone). Returns VT_OK or a negative vt_status. */
vt_status vt_square_solve(const vt_model *m, vt_data *d, double *b, double *rcond_out, vt_outcome *out)
{
    const int n = m->nv;
    const size_t mark = vt_scratch_mark(d);
    vt_square sq;
    int r = vt_square_first(m, d, &sq, d->Mstar, n + 1, rcond_out);
    if (r == 0) {
        memcpy(sq.h, d->Q, (size_t)n * sizeof(double)); /* h = M* q̈ − Q */
        vt_dgemv('N', n, n, 1.0, d->Mstar, n, sq.x, 1, -1.0, sq.h, 1);
        r = vt_square_second(m, d, &sq);
        if (r == 0) memcpy(b, sq.x, 2 * (size_t)n * sizeof(double));
    }
    vt_scratch_release(d, mark);
    if (r < 0) return (vt_status)r;
    *out = r == VT_SOLVED ? VT_SOLVED : VT_BELOW_MIN;
    return VT_OK;
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
 * and the augmented route takes over (VT_PIVOT_GAVE_WAY). M̃ is factorized with its rates in descending order
 * (leaf first), so that L_kk² are the articulated-body pivots each over its diagonal entry.
 * The reported reciprocal condition is S's at unit diagonal (vt_solve_spd: exact, 1 for one row,
 * for nc ≤ 16 from its inverse; dpocon's estimate above) times (min L_kk / max L_kk)² times the
 * point drives' grip² (vt_rows_grip): the recursive articulated route's number. It falls where
 * the rows lose independence in the mass metric, where a motion loses its inertia, and where a
 * point drive loses its grip (a lone one too). The outcome into *out: VT_SOLVED,
 * VT_PIVOT_GAVE_WAY (a pivot below 1e-4: not solved), VT_SCHUR_BELOW_MIN (not solved) or
 * VT_SCHUR_BELOW_WARN (solved): in the last two vt_solve_band tries the augmented route too.
 * Returns VT_OK or a negative vt_status. */
#define SCHUR_FEW 3 /* rows up to which S and its right side are formed by loops */

/* S = Y^T Y (its lower triangle, no x no) and rhs −= Y^T z, Y nf x no: with a few rows (a point
 * drive: 1 to 3) a few dot products of nf terms, cheaper as loops than as BLAS calls (whose
 * argument checks cost more than the products); one row makes S a positive number, its
 * Cholesky factor a square root, and S's condition exactly 1 */
static void schur_gram(const double *Y, int nf, int no, const double *z, double *rhs, double *S)
{
    if (no > SCHUR_FEW) {
        vt_dsyrk('L', 'T', no, nf, 1.0, Y, nf, 0.0, S, no);
        vt_dgemv('T', nf, no, -1.0, Y, nf, z, 1, 1.0, rhs, 1);
        return;
    }
    for (int r = 0; r < no; r++) {
        const double *yr = Y + (size_t)r * (size_t)nf;
        double t = rhs[r];
        for (int a = 0; a < nf; a++) t -= yr[a] * z[a];
        rhs[r] = t;
        for (int k = r; k < no; k++) {
            const double *yk = Y + (size_t)k * (size_t)nf;
            double v = 0.0;
            for (int a = 0; a < nf; a++) v += yk[a] * yr[a];
            S[k + (size_t)r * (size_t)no] = v;
        }
    }
}

/* z += Y l (Y nf x no), by loops for a few rows as schur_gram */
static void schur_add(const double *Y, int nf, int no, const double *l, double *z)
{
    if (no > SCHUR_FEW) {
        vt_dgemv('N', nf, no, 1.0, Y, nf, l, 1, 1.0, z, 1);
        return;
    }
    for (int r = 0; r < no; r++) {
        const double *yr = Y + (size_t)r * (size_t)nf, lr = l[r];
        for (int a = 0; a < nf; a++) z[a] += yr[a] * lr;
    }
}

vt_status vt_schur_solve(const vt_model *m, vt_data *d, int known, double *sol, double *rcond_out, vt_outcome *out)
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
    vt_scaling_diag(m, d->Mstar, nv + 1, s);
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
    if (info > 0) return vt_scratch_release(d, mark), *out = VT_PIVOT_GAVE_WAY, VT_OK;
    double lmin = 1.0, lmax = 0.0;
    for (int k = 0; k < nf; k++) {
        const double lk = L[k + (size_t)k * (size_t)nf];
        if (!(lk >= 1e-4)) return vt_scratch_release(d, mark), *out = VT_PIVOT_GAVE_WAY, VT_OK;
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
    if (nf > 0) vt_dtrsm('L', 'L', 'N', 'N', nf, nrhs, 1.0, L, nf, B, nf);
    const double *Y = B;
    /* S = Y^T Y and its right-hand side R (γ − Φ q̈_D) − Y^T z */
    for (int k = 0; k < no; k++) {
        double t = d->gamma[ro[k]];
        for (int j = 0; j < nv - nf; j++) t -= PHI(ro[k], kr[j]) * x[kr[j]]; /* Φ_oD q̈_D */
        lam[k] = g[k] * t;
    }
    schur_gram(Y, nf, no, z, lam, S);
    double rcond = 0.0;
    int st = vt_solve_spd(d, S, no, lam, &rcond);
    if (st) return vt_scratch_release(d, mark), (vt_status)st;
    double grip = 1.0;
    if ((st = vt_rows_grip(m, d, &grip))) return vt_scratch_release(d, mark), (vt_status)st;
    rcond *= (lmin / lmax) * (lmin / lmax) * grip;
    *rcond_out = rcond;
    /* below rcond_min: not solved (vt_solve_band tries the augmented route before refusing) */
    if (!(rcond >= m->rcond_min)) return vt_scratch_release(d, mark), *out = VT_SCHUR_BELOW_MIN, VT_OK;
    /* ỹ = L^-T (z + Y λ̃), in place of z */
    schur_add(Y, nf, no, lam, z);
    if (nf > 0) vt_dtrsv('L', 'T', 'N', nf, L, nf, z, 1);
    for (int a = 0; a < nf; a++) x[fr[a]] = z[a] * s[fr[a]];
    for (int k = 0; k < no; k++) lam[k] *= g[k];
    /* below √rcond_warn, where the answer may have lost more than 1e3 ε: one step of iterative
     * refinement against the unscaled reduced system, on the same factors (the residual
     * r = [Q_F − M*_FD q̈_D + Φ_oF^T λ_o − M*_FF q̈_F; γ_o − Φ_o q̈] solved as Q and γ above) */
    if (rcond < sqrt(m->rcond_warn) && no > 0) {
        double *t = VT_SCRATCH(d, double, no, "refinement's right side");
        if (!t) return vt_scratch_fail(d, mark);
        for (int a = 0; a < nf; a++) {
            const int c = fr[a];
            double v = d->Q[c];
            for (int b = 0; b < nv; b++) v -= MS(c, b) * x[b];
            for (int k = 0; k < no; k++) v += PHI(ro[k], c) * lam[k];
            z[a] = v * s[c];
        }
        for (int k = 0; k < no; k++) {
            double v = d->gamma[ro[k]];
            for (int b = 0; b < nv; b++) v -= PHI(ro[k], b) * x[b];
            t[k] = g[k] * v;
        }
        if (nf > 0) vt_dtrsv('L', 'N', 'N', nf, L, nf, z, 1);
        schur_gram(Y, nf, no, z, t, S); /* S again: vt_solve_spd factorized it in place */
        double rc = 0.0;
        const int st2 = vt_solve_spd(d, S, no, t, &rc);
        if (st2) return vt_scratch_release(d, mark), (vt_status)st2;
        schur_add(Y, nf, no, t, z);
        if (nf > 0) vt_dtrsv('L', 'T', 'N', nf, L, nf, z, 1);
        for (int a = 0; a < nf; a++) x[fr[a]] += z[a] * s[fr[a]];
        for (int k = 0; k < no; k++) lam[k] += g[k] * t[k];
    }
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
    /* below rcond_warn: solved (vt_solve_band also tries the augmented route) */
    *out = rcond >= m->rcond_warn ? VT_SOLVED : VT_SCHUR_BELOW_WARN;
    return VT_OK;
}

/* Whether the Schur route may take the joint-driven rates as known: some rate has a joint
 * drive, and no row depends on the known rates by its kind alone, a second joint drive on a
 * driven rate or a coupling of two driven rates: their parts on the free rates are exactly zero,
 * where the dense S leaves round-off (R S = I to ε) that the rows' scaling would make a unit row.
 * Those the whole system decides, and names (rows that are round-off on the free rates:
 * vt_zero_rows_free, at the call). */
int vt_rates_known(const vt_model *m)
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

/* The scratch routes.c takes at once: the largest route with LAPACK's workspace by its own
 * queries (the rank decision's SVD the redundant route reads: numeric/rank.c; the square
 * route's factors and vt_solve_spd's: numeric/kkt.c) */
size_t vt_routes_scratch(const vt_model *m)
{
    const int nv = m->nv, nc = m->nc, N = nv + nc, one = 1;
    const size_t sN = (size_t)N, snv = (size_t)nv, snc = (size_t)nc, D = sizeof(double), I = sizeof(int);
    int info = 0, lw = -1, idummy = 0, rank = 0;
    double q = 0.0, dummy = 0.0, rc = -1.0;
    /* vt_augmented_solve: K, the scaling, D's off-diagonal, the refinement's residual, the
     * pivots, then dsytrf_rk's workspace (at least 2 N, as much as its query asks), dlansy's, the
     * exact inverse or dsycon_3's workspaces */
    size_t sytrf = 2 * sN;
    dsytrf_rk_("L", &N, &dummy, &N, &dummy, &idummy, &q, &lw, &info, 1);
    if (info == 0 && q > (double)sytrf) sytrf = (size_t)q;
    size_t after = VT_SCRATCH_BYTES(sytrf, D);
    const size_t sycon = VT_SCRATCH_BYTES(2 * sN, D) + VT_SCRATCH_BYTES(sN, I);
    const size_t exact = N <= VT_EXACT_RCOND_N ? VT_SCRATCH_BYTES(sN * sN, D) : 0;
    if (sycon > after) after = sycon;
    if (exact > after) after = exact;
    size_t route = VT_SCRATCH_BYTES(sN * sN, D) + 2 * VT_SCRATCH_BYTES(sN, D) + VT_SCRATCH_BYTES(2 * sN, D) +
                   VT_SCRATCH_BYTES(sN, I) + after;
    /* vt_redundant_solve: the rows' scaling, G [Φ_q, γ], U_d^T of it, K and its copy, the right
     * side and its copy, the singular values, dgelsd's workspaces (by its query) */
    if (nc > 0) { /* without rows this route is never taken */
        size_t lsq = 1;
        dgelsd_(&N, &N, &one, &dummy, &N, &dummy, &N, &dummy, &rc, &rank, &q, &lw, &idummy, &info);
        if (info == 0 && q > (double)lsq) lsq = (size_t)q;
        const size_t redundant = VT_SCRATCH_BYTES(snc, D) + 2 * VT_SCRATCH_BYTES(snc * (snv + 1) + 1, D) +
                                 2 * VT_SCRATCH_BYTES(sN * sN, D) + 3 * VT_SCRATCH_BYTES(sN, D) +
                                 VT_SCRATCH_BYTES((size_t)vt_dgelsd_iwork(N, N), I) + VT_SCRATCH_BYTES(lsq, D);
        if (redundant > route) route = redundant;
    }
    /* vt_schur_solve: its index lists, L, B, S, the scaling, q̈ and λ̃ (vt_free_rates_solve's
     * arrays are fewer) */
    const size_t schur = VT_SCRATCH_BYTES(sN, I) + VT_SCRATCH_BYTES(snv * snv, D) + VT_SCRATCH_BYTES(snv * (snc + 1), D) +
                         VT_SCRATCH_BYTES(snc * snc, D) + 2 * VT_SCRATCH_BYTES(sN, D);
    if (schur > route) route = schur;
    return route;
}
