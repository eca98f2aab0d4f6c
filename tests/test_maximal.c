/* The maximal-coordinate route (src/numeric/maximal.c): its system against (5) solved by the dense
 * stages, its estimate against an explicit computation of its definition, rows losing their
 * independence shown whatever route solves, where it is and is not offered. Its answers on the
 * chains of spread masses against the exact ones are tests/ratio_oracle.py's; its translation
 * invariance is test_accuracy's. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "base/lapack.h" /* dgeequb */
#include "numeric/maximal.h" /* vt_maximal_*: internal */
#include "scenes.h"
#include "vt_test.h"

/* random trees of every joint kind but the base body (free roots too) with joint, point and
 * orientation drives, spherical cut joints and couplings (vt_test_partly_driven_tree) */
static vt_model *tree_scene(uint64_t seed)
{
    return vt_test_partly_driven_tree(seed, VT_SCENE_WITH_FREE, 1);
}

static void scene_state(const vt_model *m, vt_data *d, uint64_t seed)
{
    uint64_t s = seed * 7;
    vt_scene_random_state(m, d, &s);
    for (int i = 1; i <= m->nbody; i++)
        for (int k = 0; k < 6; k++) d->xfrc[6 * i + k] = vt_rand_uniform(&s, -3, 3);
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = vt_rand_uniform(&s, -1, 1);
    d->time = 0.3;
}

/* The system's elimination gives (5): on trees of every joint kind with every kind of row and
 * load, the route's q̈ and λ (called after the dense stages, whatever route they took) agree
 * with the dense path's to 1e-14 of each over the smaller estimate (at least 1e-11). */
static void test_maximal_equals_dense(void **state)
{
    (void)state;
    int ran = 0;
    for (uint64_t seed = 1; seed <= 16; seed++) {
        vt_model *m = tree_scene(seed);
        if (m->nc >= m->nv) {
            vt_model_free(m);
            continue;
        }
        if (!vt_maximal_size(m)) { /* beyond VT_MAXIMAL_MAX unknowns */
            vt_model_free(m);
            continue;
        }
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        scene_state(m, d, seed);
        if (vt_inverse_dynamics(m, d) == VT_ERR_DEPENDENT_CONSTRAINTS) { /* rows on too few rates */
            vt_data_free(d);
            vt_model_free(m);
            continue;
        }
        double *sol = malloc(((size_t)m->nv + (size_t)m->nc) * sizeof(double)), rc = 0.0;
        assert_non_null(sol);
        assert_int_equal(vt_maximal_solve(m, d, sol, &rc), 0);
        assert_true(rc > 0.0 && rc <= 1.0);
        const double tol = fmax(1e-11, 1e-14 / fmin(rc, d->rcond));
        const double qs = vt_test_maxabs(d->qdd, m->nv), ls = vt_test_maxabs(d->lambda, m->nc);
        double eq = 0.0, el = 0.0;
        for (int a = 0; a < m->nv; a++) eq = fmax(eq, fabs(sol[a] - d->qdd[a]) / qs);
        for (int r = 0; r < m->nc; r++) el = fmax(el, fabs(sol[m->nv + r] - d->lambda[r]) / ls);
        print_message("seed %d: %d bodies, %d rows (%d cut, %d coupling), route %d rcond %.3g, maximal %.3g: "
                      "q̈ %.2g, λ %.2g\n", (int)seed, m->nbody, m->nc, m->ncut, m->ncoupling, d->route, d->rcond, rc, eq, el);
        if (!(eq <= tol && el <= tol)) fail_msg("seed %d: q̈ off by %.3g, λ by %.3g (> %.3g)", (int)seed, eq, el, tol);
        ran++;
        free(sol);
        vt_data_free(d);
        vt_model_free(m);
    }
    assert_true(ran >= 8);
}

/* the definition, explicitly: Â = R A C (dgeequb's R and C), its inverse by dgesv, x̂ = Â^{-1} b̂,
 * Z = |Â^{-1}| (|Â| |x̂| + |b̂|), κ_P = max_P Z / max_P |x̂| for P = q̈, then λ;
 * 1 / max(1, κ_q̈, κ_λ) (no grip: vt_maximal_solve leaves it to solve.c) */
static double rcond_explicit(const vt_model *m, const vt_data *d)
{
    const int N = vt_maximal_size(m), iq = 12 * m->nbody, il = iq + m->nv;
    const size_t sN = (size_t)N;
    double *A = malloc(sN * sN * sizeof(double)), *X = calloc(sN * sN, sizeof(double));
    double *b = malloc(sN * sizeof(double)), *R = malloc(sN * sizeof(double)), *C = malloc(sN * sizeof(double));
    double *x = malloc(sN * sizeof(double)), *w = malloc(sN * sizeof(double)), *Z = malloc(sN * sizeof(double));
    int *ipiv = malloc(sN * sizeof(int)), info = 0;
    assert_non_null(ipiv);
    vt_maximal_system(m, d, A, b);
    double rowcnd, colcnd, amax;
    dgeequb_(&N, &N, A, &N, R, C, &rowcnd, &colcnd, &amax, &info);
    assert_int_equal(info, 0);
    for (int c = 0; c < N; c++) {
        for (int r = 0; r < N; r++) A[r + c * sN] *= R[r] * C[c];
        X[c + c * sN] = 1.0;
        b[c] *= R[c];
    }
    for (int r = 0; r < N; r++) {
        w[r] = fabs(b[r]);
        x[r] = 0.0;
    }
    double *LU = malloc(sN * sN * sizeof(double));
    memcpy(LU, A, sN * sN * sizeof(double));
    dgesv_(&N, &N, LU, &N, ipiv, X, &N, &info);
    assert_int_equal(info, 0);
    for (int r = 0; r < N; r++)
        for (int c = 0; c < N; c++) x[r] += X[r + c * sN] * b[c];
    for (int r = 0; r < N; r++)
        for (int c = 0; c < N; c++) w[r] += fabs(A[r + c * sN]) * fabs(x[c]);
    for (int r = 0; r < N; r++) {
        Z[r] = 0.0;
        for (int c = 0; c < N; c++) Z[r] += fabs(X[r + c * sN]) * w[c];
    }
    double kappa = 1.0;
    for (int part = 0; part < 2; part++) {
        const int lo = part ? il : iq, hi = part ? N : il;
        double zmax = 0.0, xmax = 0.0;
        for (int r = lo; r < hi; r++) zmax = fmax(zmax, Z[r]), xmax = fmax(xmax, fabs(x[r]));
        if (lo < hi) kappa = fmax(kappa, zmax / xmax);
    }
    free(A), free(X), free(b), free(R), free(C), free(x), free(w), free(Z), free(ipiv), free(LU);
    return 1.0 / kappa;
}

/* The estimate against its definition computed explicitly: LAPACK's dlacn2 estimates the norm
 * from below, so the route's estimate is at least the explicit one, and within 3 of it; on the
 * chains rising by 1e6 a rod (joint 1 driven) and falling (joints 1-2 and the tip), and on the
 * random trees. */
static void test_maximal_estimate(void **state)
{
    (void)state;
    int ran = 0;
    for (int c = 0; c < 18; c++) {
        vt_model *m = c < 2 ? vt_test_ratio_chain(c == 0, c == 0 ? 3 : 2, 6.0) : tree_scene((uint64_t)c - 1);
        if (!vt_maximal_size(m)) {
            vt_model_free(m);
            continue;
        }
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        for (int k = 0; k < 3; k++) {
            if (c < 2)
                for (int a = 0; a < m->nv; a++) d->q[a] = 0.3 + 0.25 * a + 0.4 * k, d->qd[a] = 0.5 - 0.2 * a + 0.1 * k;
            else
                scene_state(m, d, (uint64_t)(c + 20 * k));
            if (vt_inverse_dynamics(m, d) == VT_ERR_DEPENDENT_CONSTRAINTS) continue; /* rows on too few rates */
            double *sol = malloc(((size_t)m->nv + (size_t)m->nc) * sizeof(double)), rc = 0.0;
            assert_int_equal(vt_maximal_solve(m, d, sol, &rc), 0);
            const double ex = rcond_explicit(m, d);
            print_message("case %d state %d: estimate %.4g, explicit %.4g\n", c, k, rc, ex);
            if (!(rc >= ex * (1.0 - 1e-6) && rc <= 3.0 * ex)) fail_msg("case %d state %d: estimate %.4g, explicit %.4g", c, k, rc, ex);
            if (c < 2) assert_true(rc > 1e-3); /* spread masses alone: well determined */
            free(sol);
            ran++;
        }
        vt_data_free(d);
        vt_model_free(m);
    }
    assert_true(ran >= 20);
}

/* Rows that lose their independence still show, whatever route solves: four planar rods whose
 * masses rise by 1e3 a rod (1e-4 … 10 kg, where the free-rate routes' estimate is low and the
 * maximal route solves too), the tip driven in x at two points of the last rod h apart along it:
 * as h falls the two rows become one, the rows' condition falls as h², and so must the reported
 * estimate (the answer's condition alone, relative to λ that grows as 1/h, would not show it) */
static void test_maximal_rows_losing_independence(void **state)
{
    (void)state;
    const double h[4] = {0.1, 1e-3, 1e-5, 1e-7};
    for (int k = 0; k < 4; k++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        const double mass[4] = {1e-4, 1e-1, 1e2, 1e5};
        vt_test_add_rods(b, 4, 0.5, mass);
        for (int p = 0; p < 2; p++) {
            vt_drive_def tip = vt_default_drive_def();
            tip.type = VT_DRIVE_POINT;
            tip.body = 4;
            tip.index = 0;
            tip.point[0] = 0.25 - p * h[k];
            tip.f = vt_function_sine(0.0, 0.05, 1.0, 0.3 * p);
            assert_true(vt_builder_add_drive(b, &tip) >= 0);
        }
        vt_model *m;
        assert_ok(vt_builder_build(&m, b));
        vt_builder_free(b);
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        for (int a = 0; a < 4; a++) d->q[a] = 0.3 + 0.2 * a, d->qd[a] = 0.4 - 0.1 * a;
        const vt_status st = vt_inverse_dynamics(m, d);
        print_message("h = %g: %s, route %d, rcond %.3g, fallback %d\n", h[k], vt_status_string(st), d->route, d->rcond,
                      d->fallback);
        if (st == VT_OK && !(d->rcond <= 100.0 * h[k] * h[k]))
            fail_msg("h = %g: rcond %.3g on route %d, the rows' condition is about h²", h[k], d->rcond, d->route);
        if (k == 3) assert_true(st != VT_OK || (d->warning & VT_WARN_ILL_CONDITIONED));
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* offered only where it can help and fits: not with base bodies (their ṗ rates), not where the
 * rows fix the motion (the square route's estimate is Φ_q's alone), not when every rate is
 * joint-driven, not beyond VT_MAXIMAL_MAX unknowns; and the data's arena holds it where it is */
static void test_maximal_offered(void **state)
{
    (void)state;
    vt_model *m;
    int based = 0;
    for (uint64_t seed = 1; seed <= 20; seed++) {
        assert_ok(vt_scene_random_tree(&m, seed, 6, VT_SCENE_ALL_JOINTS));
        if (m->joint_mix < 0) {
            assert_int_equal(vt_maximal_size(m), 0);
            based++;
        }
        vt_model_free(m);
    }
    assert_true(based > 0);
    assert_ok(vt_scene_fourbar(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0)));
    assert_int_equal(m->nc, m->nv);
    assert_int_equal(vt_maximal_size(m), 0);
    vt_model_free(m);
    m = vt_test_ratio_chain(1, 0, 6.0); /* every rate joint-driven */
    assert_int_equal(vt_maximal_size(m), 0);
    vt_model_free(m);
    m = vt_test_ratio_chain(1, 3, 6.0);
    assert_int_equal(vt_maximal_size(m), 12 * 5 + 5 + 1);
    assert_true(vt_data_size(m) > (size_t)(66 * 66) * sizeof(double));
    vt_model_free(m);
    assert_ok(vt_scene_chain(&m, 30, VT_CHAIN_TIP_DRIVE)); /* 12 * 30 + 30 + 2 > VT_MAXIMAL_MAX */
    assert_int_equal(vt_maximal_size(m), 0);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_maximal_equals_dense),
        cmocka_unit_test(test_maximal_estimate),
        cmocka_unit_test(test_maximal_rows_losing_independence),
        cmocka_unit_test(test_maximal_offered),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
