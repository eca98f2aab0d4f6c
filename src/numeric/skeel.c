/* The answer's componentwise condition (Skeel), the kernel of two estimates: the maximal route's
 * on its own system (maximal.c) and the one below on (5) itself,
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 *
 * For A x = b and the unknowns P (q̈, or λ),
 *
 *   κ_P = ‖(|A^{-1}| (|A| |x| + |b|))_P‖_∞ / ‖x_P‖_∞
 *
 * is the relative change of x_P that relative changes of ε in every entry of A and b can cause
 * (first order): ε κ_P bounds the error of an answer whose data carry errors of ε relative to
 * each entry, as LAPACK's dgerfs bounds its forward error. It is measured by dlacn2 (Higham's
 * estimator) on the LU of the equilibrated Â = R A C (dgeequb), two solves a step:
 * |A^{-1}| g = C |Â^{-1}| R g.
 *
 * Why (5) needs it where the masses are spread: M* and Q are sums over the bodies, and each of
 * their entries is formed to ε of its own size, not better. The routes' estimates measure the
 * pose and the rows in the mass metric (docs/method.md, "The condition estimate"), which does
 * not see how far the answer moves when M* and Q move by ε of their entries: the knee four-bar
 * with a 3e5 kg crank on a 1e-6 kg thigh, left free at the hip, had λ off by 1.1e-12 (5e3 ε) at
 * a route estimate of 0.84 (docs/accuracy.md, "Mass ratios"). Over a spread of at least
 * VT_SPREAD_ESTIMATE, the routes that leave rates free take the smaller of their estimate and
 * 1 / max(κ_q̈, κ_λ) (solve.c), so that ε / rcond covers what M* and Q lost. Below that spread
 * the entries carry the masses at one size and the routes' estimates stand alone (the ratio
 * chains of docs/accuracy.md: errors within ε / rcond at 1e3 a rod and more).
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "numeric/skeel.h"
#include "base/arena.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "model/model.h"

int vt_lu_solve(const char *trans, const double *LU, const int *ipiv, int N, double *v)
{
    const int one = 1;
    int info = 0;
    dgetrs_(trans, &N, &one, LU, &N, ipiv, v, &N, &info, 1);
    return info;
}

/* ‖P C |Â^{-1}| w‖_∞ = ‖W Â^{-T} C P‖_1, the 1-norm of an operator dlacn2 applies and transposes */
double vt_skeel_norm(const double *LU, const int *ipiv, int N, const double *w, const double *C, int lo, int hi,
                     double *v, double *z, int *isgn)
{
    double est = 0.0;
    int kase = 0, isave[3] = {0, 0, 0};
    for (;;) {
        dlacn2_(&N, v, z, isgn, &est, &kase, isave);
        if (kase == 0) return est;
        if (kase == 1) { /* z ← W Â^{-T} C P z */
            for (int r = 0; r < N; r++) z[r] = r >= lo && r < hi ? (C ? C[r] : 1.0) * z[r] : 0.0;
            if (vt_lu_solve("T", LU, ipiv, N, z)) return -1.0;
            for (int r = 0; r < N; r++) z[r] *= w[r];
        } else { /* z ← P C Â^{-1} W z */
            for (int r = 0; r < N; r++) z[r] *= w[r];
            if (vt_lu_solve("N", LU, ipiv, N, z)) return -1.0;
            for (int r = 0; r < N; r++) z[r] = r >= lo && r < hi ? (C ? C[r] : 1.0) * z[r] : 0.0;
        }
    }
}

int vt_answer_size(const vt_model *m)
{
    const long N = (long)m->nv + m->nc;
    return m->ncut > 0 && m->mass_spread >= VT_SPREAD_ESTIMATE && !m->joint_driven && N <= VT_SPREAD_MAX ? (int)N : 0;
}

size_t vt_answer_scratch(const vt_model *m)
{
    const size_t n = (size_t)vt_answer_size(m), D = sizeof(double);
    return n ? VT_SCRATCH_BYTES(n * n, D) + 6 * VT_SCRATCH_BYTES(n, D) + 2 * VT_SCRATCH_BYTES(n, sizeof(int)) : 0;
}

int vt_answer_condition(const vt_model *m, vt_data *d, const double *sol, int neg, double *rcond)
{
    *rcond = 0.0;
    const int N = vt_answer_size(m), nv = m->nv, nc = m->nc;
    if (!N) return *rcond = 1.0, 0;
    const size_t mark = vt_scratch_mark(d), sN = (size_t)N;
    double *A = VT_SCRATCH(d, double, sN * sN, "(5) for its estimate");
    double *x = VT_SCRATCH(d, double, sN, "(5)'s answer"), *w = VT_SCRATCH(d, double, sN, "|A| |x| + |b|");
    double *R = VT_SCRATCH(d, double, sN, "row scaling"), *C = VT_SCRATCH(d, double, sN, "column scaling");
    double *v = VT_SCRATCH(d, double, sN, "dlacn2's v"), *z = VT_SCRATCH(d, double, sN, "dlacn2's x");
    int *ipiv = VT_SCRATCH(d, int, sN, "pivots"), *isgn = VT_SCRATCH(d, int, sN, "dlacn2's signs");
    if (!isgn) return vt_scratch_fail(d, mark);
    memset(A, 0, sN * sN * sizeof(double));
    for (int c = 0; c < nv; c++) {
        memcpy(A + (size_t)c * sN, d->Mstar + (size_t)c * (size_t)nv, (size_t)nv * sizeof(double));
        for (int o = 0; o < nc; o++)
            A[nv + o + (size_t)c * sN] = A[c + (size_t)(nv + o) * sN] = d->Phiq[o + (size_t)c * (size_t)nc];
    }
    for (int k = 0; k < N; k++) x[k] = k < nv || neg ? sol[k] : -sol[k];
    /* w = |A| |x| + |b|, then R w */
    for (int r = 0; r < N; r++) {
        double s = fabs(r < nv ? d->Q[r] : d->gamma[r - nv]);
        for (int c = 0; c < N; c++) s += fabs(A[r + (size_t)c * sN] * x[c]);
        w[r] = s;
    }
    double rowcnd = 0.0, colcnd = 0.0, amax = 0.0;
    int info = 0;
    dgeequb_(&N, &N, A, &N, R, C, &rowcnd, &colcnd, &amax, &info);
    if (info != 0) return vt_scratch_release(d, mark), 0; /* a zero row or column */
    for (int c = 0; c < N; c++)
        for (int r = 0; r < N; r++) A[r + (size_t)c * sN] *= R[r] * C[c];
    dgetrf_(&N, &N, A, &N, ipiv, &info);
    if (info != 0) return vt_scratch_release(d, mark), 0; /* an exactly zero pivot */
    for (int r = 0; r < N; r++) w[r] *= R[r];
    double kappa = 1.0;
    for (int part = 0; part < 2; part++) { /* q̈, then λ: each over its own entries */
        const int lo = part ? nv : 0, hi = part ? N : nv;
        if (lo == hi) continue;
        double xmax = 0.0;
        for (int r = lo; r < hi; r++) xmax = fmax(xmax, fabs(x[r]));
        const double est = vt_skeel_norm(A, ipiv, N, w, C, lo, hi, v, z, isgn);
        if (!(est >= 0.0)) return vt_scratch_release(d, mark), 0;
        kappa = fmax(kappa, xmax > 0.0 ? est / xmax : est > 0.0 ? HUGE_VAL : 1.0);
    }
    *rcond = 1.0 / kappa;
    vt_scratch_release(d, mark);
    return 0;
}
