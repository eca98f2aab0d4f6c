/* src/numeric/kkt.c: the small dense kernels against independent solves.
 *   vt_solve_spd  on symmetric positive definite S with an integer solution (S = A^T A + n I,
 *                 b = S x), against that x and LAPACK's dposv; its reciprocal condition against
 *                 the exact one of S at unit diagonal, 1 / (‖Ŝ‖₁ ‖Ŝ^-1‖₁), Ŝ^-1 by dgesv (LU) on
 *                 the identity (n ≤ 16: the same number to round-off; above: dpocon's estimate,
 *                 never below the exact one and within a factor n); not positive definite: 0.
 *   the square route's LU (vt_square_first/second/apply, vt_solve_square_factor) on the
 *                 RSUR four-bar (as many rows as rates): q̈ = Φ_q^-1 γ, λ = Φ_q^-T h and
 *                 x = ± Φ_q^-1 b against dgesv on Φ_q itself (unscaled) and on Φ_q^T. */
#include "base/arena.h"
#include "numeric/kkt.h"

#include "vt_test.h"

void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b, const int *ldb, int *info);
void dposv_(const char *uplo, const int *n, const int *nrhs, double *a, const int *lda, double *b, const int *ldb,
            int *info, size_t luplo);

/* A deterministic integer in [-3, 3] */
static int small_int(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (int)((*s >> 33) % 7) - 3;
}

/* S = A^T A + n I (n x n, symmetric positive definite, integer entries), x integers, b = S x */
static void spd_problem(int n, uint64_t seed, double *S, double *x, double *b)
{
    double *A = malloc((size_t)n * (size_t)n * sizeof(double));
    assert_non_null(A);
    for (int k = 0; k < n * n; k++) A[k] = small_int(&seed);
    for (int c = 0; c < n; c++)
        for (int r = 0; r < n; r++) {
            double v = r == c ? (double)n : 0.0;
            for (int k = 0; k < n; k++) v += A[k + (size_t)r * (size_t)n] * A[k + (size_t)c * (size_t)n];
            S[r + (size_t)c * (size_t)n] = v;
        }
    for (int r = 0; r < n; r++) x[r] = small_int(&seed) + 0.5 * r;
    for (int r = 0; r < n; r++) {
        double v = 0.0;
        for (int c = 0; c < n; c++) v += S[r + (size_t)c * (size_t)n] * x[c];
        b[r] = v;
    }
    free(A);
}

/* the exact reciprocal 1-norm condition of S at unit diagonal, by an LU inverse */
static double unit_diagonal_rcond(int n, const double *S)
{
    const size_t nn = (size_t)n * (size_t)n;
    double *K = malloc(nn * sizeof(double)), *X = calloc(nn, sizeof(double));
    int *ipiv = malloc((size_t)n * sizeof(int));
    assert_non_null(K);
    assert_non_null(X);
    assert_non_null(ipiv);
    for (int c = 0; c < n; c++)
        for (int r = 0; r < n; r++)
            K[r + (size_t)c * (size_t)n] = S[r + (size_t)c * (size_t)n] / sqrt(S[r + (size_t)r * (size_t)n] * S[c + (size_t)c * (size_t)n]);
    double kn = 0.0, xn = 0.0;
    for (int c = 0; c < n; c++) {
        double cs = 0.0;
        for (int r = 0; r < n; r++) cs += fabs(K[r + (size_t)c * (size_t)n]);
        kn = fmax(kn, cs);
        X[c + (size_t)c * (size_t)n] = 1.0;
    }
    int info = 0;
    dgesv_(&n, &n, K, &n, ipiv, X, &n, &info);
    assert_int_equal(info, 0);
    for (int c = 0; c < n; c++) {
        double cs = 0.0;
        for (int r = 0; r < n; r++) cs += fabs(X[r + (size_t)c * (size_t)n]);
        xn = fmax(xn, cs);
    }
    free(K);
    free(X);
    free(ipiv);
    return 1.0 / (kn * xn);
}

/* vt_solve_spd needs a vt_data only for its arena and message */
static vt_data *scratch_data(vt_model **m)
{
    vt_data *d;
    assert_ok(vt_scene_chain(m, 30, 0));
    assert_ok(vt_data_create(&d, *m));
    return d;
}

static void test_spd_against_exact_and_dposv(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d = scratch_data(&m);
    const int sizes[] = {1, 2, 3, 5, 8, 16, 17, 24};
    for (size_t t = 0; t < sizeof sizes / sizeof *sizes; t++) {
        const int n = sizes[t];
        const size_t nn = (size_t)n * (size_t)n;
        double *S = malloc(nn * sizeof(double)), *S0 = malloc(nn * sizeof(double)), *x = malloc((size_t)n * sizeof(double));
        double *b = malloc((size_t)n * sizeof(double)), *b0 = malloc((size_t)n * sizeof(double));
        assert_non_null(S);
        assert_non_null(S0);
        assert_non_null(x);
        assert_non_null(b);
        assert_non_null(b0);
        spd_problem(n, 1000u + (uint64_t)n, S, x, b);
        memcpy(S0, S, nn * sizeof(double));
        memcpy(b0, b, (size_t)n * sizeof(double));
        const double exact = unit_diagonal_rcond(n, S0);
        const size_t mark = vt_scratch_mark(d);
        double rcond = -1.0;
        assert_int_equal(vt_solve_spd(d, S, n, b, &rcond), 0);
        assert_int_equal(vt_scratch_mark(d), mark); /* its scratch released */
        /* the integer solution, and LAPACK's own Cholesky solve of the unscaled S */
        int info = 0, one = 1;
        dposv_("L", &n, &one, S0, &n, b0, &n, &info, 1);
        assert_int_equal(info, 0);
        const double xmax = vt_test_maxabs(x, n);
        for (int r = 0; r < n; r++) {
            assert_near(b[r], x[r], 1e-12 * xmax / exact);
            assert_near(b[r], b0[r], 1e-12 * xmax / exact);
        }
        if (n == 1) assert_true(rcond == 1.0);
        else if (n <= VT_EXACT_RCOND_N) assert_near(rcond, exact, 1e-10 * exact);
        else { /* dpocon: an estimate of ‖Ŝ^-1‖₁ from below */
            assert_true(rcond >= exact * (1.0 - 1e-10));
            assert_true(rcond <= exact * n);
        }
        free(S);
        free(S0);
        free(x);
        free(b);
        free(b0);
    }
    vt_data_free(d);
    vt_model_free(m);
}

static void test_spd_not_positive_definite(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d = scratch_data(&m);
    double rcond = -1.0;
    double S1[4] = {1.0, 2.0, 2.0, 1.0}, b1[2] = {1.0, 1.0}; /* eigenvalues 3 and −1 */
    assert_int_equal(vt_solve_spd(d, S1, 2, b1, &rcond), 0);
    assert_true(rcond == 0.0);
    double S2[4] = {-1.0, 0.0, 0.0, 1.0}, b2[2] = {1.0, 2.0}; /* a negative diagonal: nothing solved */
    rcond = -1.0;
    assert_int_equal(vt_solve_spd(d, S2, 2, b2, &rcond), 0);
    assert_true(rcond == 0.0);
    assert_true(b2[0] == 1.0 && b2[1] == 2.0);
    vt_data_free(d);
    vt_model_free(m);
}

/* y = Φ_q^-1 rhs (trans 0) or Φ_q^-T rhs (trans 1) by dgesv on the unscaled Φ_q */
static void direct_solve(const vt_data *d, int n, int trans, const double *rhs, double *y)
{
    const size_t nn = (size_t)n * (size_t)n;
    double *A = malloc(nn * sizeof(double));
    int *ipiv = malloc((size_t)n * sizeof(int));
    assert_non_null(A);
    assert_non_null(ipiv);
    for (int c = 0; c < n; c++)
        for (int r = 0; r < n; r++)
            A[r + (size_t)c * (size_t)n] = trans ? d->Phiq[c + (size_t)r * (size_t)n] : d->Phiq[r + (size_t)c * (size_t)n];
    memcpy(y, rhs, (size_t)n * sizeof(double));
    int info = 0, one = 1;
    dgesv_(&n, &one, A, &n, ipiv, y, &n, &info);
    assert_int_equal(info, 0);
    free(A);
    free(ipiv);
}

static void test_square_lu_against_dgesv(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_fourbar(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0)));
    assert_ok(vt_data_create(&d, m));
    const int n = m->nv;
    assert_int_equal(m->nc, n); /* the square route's case */
    double *mdiag = malloc((size_t)n * sizeof(double)), *y = malloc((size_t)n * sizeof(double));
    double *x = malloc((size_t)n * sizeof(double)), *b = malloc((size_t)n * sizeof(double));
    double *h = malloc((size_t)n * sizeof(double));
    assert_non_null(mdiag);
    assert_non_null(y);
    assert_non_null(x);
    assert_non_null(b);
    assert_non_null(h);
    for (double th = 0.2; th < 6.2; th += 0.7) {
        assert_int_equal(vt_scene_fourbar_assemble(m, d, th, 1.3, NULL, NULL), 0);
        assert_ok(vt_inverse_dynamics(m, d)); /* Φ_q, γ, M* and Q formed */
        for (int a = 0; a < n; a++) mdiag[a] = d->Mstar[a + (size_t)a * (size_t)n];
        for (int form = 0; form < 2; form++) { /* vt_square_first, vt_solve_square_factor */
            const size_t mark = vt_scratch_mark(d);
            vt_square sq;
            double rcond = 0.0;
            if (form == 0) assert_int_equal(vt_square_first(m, d, &sq, d->Mstar, n + 1, &rcond), VT_SOLVED);
            else {
                assert_int_equal(vt_solve_square_factor(m, d, &sq, mdiag, &rcond), VT_SOLVED);
                assert_int_equal(vt_solve_square_accelerations(m, d, &sq), 0);
            }
            assert_true(rcond > 0.0 && rcond <= 1.0);
            /* q̈ = Φ_q^-1 γ */
            direct_solve(d, n, 0, d->gamma, y);
            const double ys = 1.0 + vt_test_maxabs(y, n);
            for (int a = 0; a < n; a++) assert_near(sq.x[a], y[a], 1e-10 * ys);
            /* x = −Φ_q^-1 b for another right side */
            for (int r = 0; r < n; r++) b[r] = 1.0 + 0.25 * r - (r % 2 ? 2.0 : 0.0);
            assert_int_equal(vt_square_apply(m, d, &sq, b, -1.0, x), 0);
            direct_solve(d, n, 0, b, y);
            const double bs = 1.0 + vt_test_maxabs(y, n);
            for (int a = 0; a < n; a++) assert_near(x[a], -y[a], 1e-10 * bs);
            /* λ = Φ_q^-T h, h = M* q̈ − Q */
            for (int a = 0; a < n; a++) {
                double v = -d->Q[a];
                for (int c = 0; c < n; c++) v += d->Mstar[a + (size_t)c * (size_t)n] * sq.x[c];
                h[a] = sq.h[a] = v;
            }
            assert_int_equal(vt_square_second(m, d, &sq), 0);
            direct_solve(d, n, 1, h, y);
            const double ls = 1.0 + vt_test_maxabs(y, n);
            for (int r = 0; r < n; r++) assert_near(sq.h[r], y[r], 1e-10 * ls);
            vt_scratch_release(d, mark);
        }
    }
    free(mdiag);
    free(y);
    free(x);
    free(b);
    free(h);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spd_against_exact_and_dposv),
        cmocka_unit_test(test_spd_not_positive_definite),
        cmocka_unit_test(test_square_lu_against_dgesv),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
