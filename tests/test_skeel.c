/* src/numeric/skeel.c: the componentwise condition against its definition computed here.
 *   vt_skeel_norm         ‖P C |Â^{-1}| w‖_∞ by dlacn2 against the explicit inverse (dgesv on the
 *                         identity) on badly scaled random matrices: never above the exact value
 *                         (dlacn2 estimates from below) and within a factor 3 of it.
 *   vt_answer_size        where the estimate is taken: loops with masses spread by 1e6 or more,
 *                         not the knee with its own masses, not a tree however spread.
 *   vt_answer_condition   on the knee four-bar with a 3e5 kg crank on a 1e-6 kg thigh, free at
 *                         the hip (vt_scene_knee_with): against 1 / max(1, κ_q̈, κ_λ) from the
 *                         explicit inverse of (5) formed here from the data's M*, Φ_q, Q and γ,
 *                         and the solve's d->rcond the smaller of it and the route's. Its answers
 *                         against the exact ones are tests/spread_oracle.py's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/lapack.h"
#include "numeric/skeel.h" /* internal */
#include "scenes.h"
#include "vt_test.h"

void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b, const int *ldb, int *info);

/* the inverse of the n x n A (A kept) by dgesv on the identity */
static void inverse(const double *A, int n, double *X)
{
    double *LU = malloc((size_t)n * (size_t)n * sizeof(double));
    int *ipiv = malloc((size_t)n * sizeof(int)), info = 0;
    assert_non_null(LU);
    assert_non_null(ipiv);
    memcpy(LU, A, (size_t)n * (size_t)n * sizeof(double));
    memset(X, 0, (size_t)n * (size_t)n * sizeof(double));
    for (int k = 0; k < n; k++) X[k + (size_t)k * (size_t)n] = 1.0;
    dgesv_(&n, &n, LU, &n, ipiv, X, &n, &info);
    assert_int_equal(info, 0);
    free(LU);
    free(ipiv);
}

/* max over i in lo..hi−1 of C_i Σ_j |X_ij| w_j */
static double exact_norm(const double *X, int n, const double *w, const double *C, int lo, int hi)
{
    double best = 0.0;
    for (int i = lo; i < hi; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++) s += fabs(X[i + (size_t)j * (size_t)n]) * w[j];
        best = fmax(best, (C ? C[i] : 1.0) * s);
    }
    return best;
}

static void test_skeel_norm(void **state)
{
    (void)state;
    enum { N = 9 };
    double A[N * N], LU[N * N], X[N * N], w[N], C[N], v[N], z[N];
    int ipiv[N], isgn[N];
    double worst = 1.0;
    for (uint64_t seed = 1; seed <= 40; seed++) {
        uint64_t s = seed;
        for (int c = 0; c < N; c++)
            for (int r = 0; r < N; r++)
                A[r + c * N] = vt_rand_uniform(&s, -1, 1) * pow(10.0, vt_rand_uniform(&s, -4, 4)) + (r == c ? 0.5 : 0.0);
        for (int k = 0; k < N; k++) w[k] = pow(10.0, vt_rand_uniform(&s, -3, 3)), C[k] = pow(2.0, vt_rand_uniform(&s, -8, 8));
        memcpy(LU, A, sizeof A);
        int n = N, info = 0;
        dgetrf_(&n, &n, LU, &n, ipiv, &info);
        assert_int_equal(info, 0);
        inverse(A, N, X);
        const int lo = (int)(seed % 4), hi = N - (int)(seed % 3);
        const double *cs = seed % 2 ? C : NULL;
        const double est = vt_skeel_norm(LU, ipiv, N, w, cs, lo, hi, v, z, isgn);
        const double ex = exact_norm(X, N, w, cs, lo, hi);
        if (!(est <= ex * (1.0 + 1e-10) && est >= ex / 3.0))
            fail_msg("seed %d: estimate %.17g, exact %.17g", (int)seed, est, ex);
        worst = fmin(worst, est / ex);
    }
    print_message("dlacn2's estimate over the exact norm: at least %.3g\n", worst);
}

static vt_status spread_knee(vt_model **m, int drives)
{
    static const double mass[4] = {1e-6, 3e5, 1.0, 1e-3}; /* thigh, crank, coupler, shank */
    return vt_scene_knee_with(m, vt_function_sine(-0.785, 0.35, 2.0, 0.0), vt_function_sine(1.57, 0.4, 2.0, 0.8), 1,
                              mass, drives, NULL);
}

static void test_answer_size(void **state)
{
    (void)state;
    vt_model *m;
    assert_int_equal(vt_scene_knee(&m, vt_function_constant(-0.7), vt_function_constant(1.5), 1), VT_OK);
    assert_int_equal(vt_answer_size(m), 0); /* 1.5 … 0.08 kg */
    vt_model_free(m);
    assert_int_equal(spread_knee(&m, 2), VT_OK);
    assert_int_equal(vt_answer_size(m), m->nv + m->nc); /* 3e11 */
    assert_int_equal(vt_answer_size(m), 7);
    vt_model_free(m);
    assert_int_equal(spread_knee(&m, 3), VT_OK);
    assert_int_equal(vt_answer_size(m), 8);
    vt_model_free(m);
    /* a chain of masses 1e-6 … 1e6 kg, partly driven, without a loop */
    vt_builder *b;
    assert_int_equal(vt_builder_create(&b, NULL), VT_OK);
    for (int i = 1; i <= 3; i++) {
        vt_body_def body = vt_default_body_def();
        body.parent = i - 1;
        body.mass = pow(1e6, i - 2);
        for (int k = 0; k < 3; k++) body.inertia[4 * k] = body.mass;
        body.joint_child[0] = -0.5;
        if (i > 1) body.joint_parent[0] = 0.5;
        assert_int_equal(vt_builder_add_body(b, &body), i);
    }
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    dr.f = vt_function_constant(0.3);
    assert_true(vt_builder_add_drive(b, &dr) >= 0);
    assert_int_equal(vt_builder_build(&m, b), VT_OK);
    vt_builder_free(b);
    assert_true(m->mass_spread >= 1e12 * (1 - 1e-12));
    assert_int_equal(vt_answer_size(m), 0);
    vt_model_free(m);
}

static void test_answer_condition(void **state)
{
    (void)state;
    for (int pose = 0; pose < 2; pose++) {
        vt_model *m;
        vt_data *d;
        assert_int_equal(spread_knee(&m, 2), VT_OK);
        assert_int_equal(vt_data_create(&d, m), VT_OK);
        const double tt = 0.3 + 0.45 * pose;
        const double thm = 1.57 + 0.4 * sin(2.0 * tt + 0.8), wm = 0.8 * cos(2.0 * tt + 0.8);
        assert_int_equal(vt_scene_knee_assemble(m, d, -0.7 + 0.2 * pose, 0.3, thm, wm, NULL), 0);
        d->time = tt;
        assert_int_equal(vt_inverse_dynamics(m, d), VT_OK);
        const int nv = m->nv, nc = m->nc, N = nv + nc;
        double sol[16], K[256], X[256], x[16], g[16];
        memcpy(sol, d->qdd, (size_t)nv * sizeof(double));
        memcpy(sol + nv, d->lambda, (size_t)nc * sizeof(double));
        double rc = 0.0;
        assert_int_equal(vt_answer_condition(m, d, sol, 0, &rc), 0);
        /* the definition, here: K, x = [q̈; −λ], b = [Q; γ] of (5), g = |K| |x| + |b| */
        memset(K, 0, sizeof K);
        for (int c = 0; c < nv; c++) {
            for (int r = 0; r < nv; r++) K[r + c * N] = d->Mstar[r + c * nv];
            for (int o = 0; o < nc; o++) K[nv + o + c * N] = K[c + (nv + o) * N] = d->Phiq[o + c * nc];
        }
        for (int k = 0; k < N; k++) x[k] = k < nv ? d->qdd[k] : -d->lambda[k - nv];
        for (int r = 0; r < N; r++) {
            g[r] = fabs(r < nv ? d->Q[r] : d->gamma[r - nv]);
            for (int c = 0; c < N; c++) g[r] += fabs(K[r + c * N] * x[c]);
        }
        inverse(K, N, X);
        double kappa = 1.0;
        for (int part = 0; part < 2; part++) {
            const int lo = part ? nv : 0, hi = part ? N : nv;
            double xmax = 0.0;
            for (int r = lo; r < hi; r++) xmax = fmax(xmax, fabs(x[r]));
            kappa = fmax(kappa, exact_norm(X, N, g, NULL, lo, hi) / xmax);
        }
        print_message("pose %d: estimate %.4g, definition %.4g, d->rcond %.4g (route %d)\n", pose, rc, 1.0 / kappa,
                      d->rcond, d->route);
        assert_true(rc >= (1.0 / kappa) * (1.0 - 1e-9) && rc <= 3.0 / kappa);
        assert_true(rc < 1e-3);                             /* the loss it sees: about 5e3 ε */
        assert_true(d->rcond <= rc * (1.0 + 1e-12));        /* the solve took it */
        vt_data_free(d);
        vt_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_skeel_norm),
        cmocka_unit_test(test_answer_size),
        cmocka_unit_test(test_answer_condition),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
