/* src/model/functions.c: f' and f'' of every built-in time function against central differences
 * of f and f', exact values, and the error paths of user callbacks. The spline: exact on the
 * polynomials its end conditions reproduce, its order of convergence on sin (error ratios
 * when the spacing halves), continuity at the knots, the model's own copy of the samples, and
 * a model's drive evaluated by bisection (bitwise the cubic of the interval a linear search
 * finds, reading only its own interval's samples). */
#include <float.h>

#include "vt_test.h"

static void check_derivatives(const vt_function *f, double t)
{
    const double h = 1e-5;
    double a[3], b[3], c[3];
    assert_ok(vt_function_eval(a, f, t + h));
    assert_ok(vt_function_eval(b, f, t - h));
    assert_ok(vt_function_eval(c, f, t));
    assert_near(c[1], (a[0] - b[0]) / (2 * h), 1e-7 * (1 + fabs(c[1])));
    assert_near(c[2], (a[1] - b[1]) / (2 * h), 1e-7 * (1 + fabs(c[2])));
}

static void test_builtins(void **state)
{
    (void)state;
    const double c[5] = {0.3, -1.0, 2.0, 0.5, -0.25};
    vt_function fs[4] = {vt_function_constant(2.5), vt_function_polynomial(5, c),
                         vt_function_sine(0.1, 0.3, 6.283185307179586, 0.4), vt_function_polynomial(1, c)};
    for (int k = 0; k < 4; k++)
        for (double t = -1.0; t <= 2.0; t += 0.37) check_derivatives(&fs[k], t);
    double v[3];
    assert_ok(vt_function_eval(v, &fs[1], 2.0)); /* 0.3 − 2 + 8 + 4 − 4 */
    assert_near(v[0], 6.3, 1e-14);
    assert_near(v[1], -1.0 + 2 * 2.0 * 2.0 + 3 * 0.5 * 4.0 - 4 * 0.25 * 8.0, 1e-14);
    assert_near(v[2], 2 * 2.0 + 6 * 0.5 * 2.0 - 12 * 0.25 * 4.0, 1e-14);
    assert_ok(vt_function_eval(v, &fs[2], 0.0));
    assert_near(v[0], 0.1 + 0.3 * sin(0.4), 1e-15);
    assert_ok(vt_function_eval(v, &fs[0], 7.0));
    assert_near(v[0], 2.5, 0.0);
    assert_near(v[1], 0.0, 0.0);
    assert_near(v[2], 0.0, 0.0);
}

static int cubic(double t, double out[3], void *user)
{
    const double s = *(const double *)user;
    out[0] = s * t * t * t;
    out[1] = 3 * s * t * t;
    out[2] = 6 * s * t;
    return 0;
}
static int failing(double t, double out[3], void *user)
{
    (void)t; (void)out; (void)user;
    return 7;
}
static int nan_out(double t, double out[3], void *user)
{
    (void)t; (void)user;
    out[0] = NAN; out[1] = 0; out[2] = 0;
    return 0;
}

/* *user = 3 k + w: slot k of the result is w = 0 NaN, 1 +Inf, 2 −Inf, the others finite */
static int bad_slot(double t, double out[3], void *user)
{
    const int code = *(const int *)user, k = code / 3, w = code % 3;
    out[0] = 1.0 + t, out[1] = -2.0, out[2] = 1e308;
    out[k] = w == 0 ? (double)NAN : w == 1 ? (double)INFINITY : -(double)INFINITY;
    return 0;
}

static void test_callbacks_and_errors(void **state)
{
    (void)state;
    double s = 2.0, v[3] = {1, 2, 3};
    vt_function f = vt_function_user(cubic, &s);
    assert_ok(vt_function_eval(v, &f, 1.5));
    assert_near(v[0], 6.75, 1e-15);
    const double keep[3] = {v[0], v[1], v[2]};
    f = vt_function_user(failing, NULL);
    assert_int_equal(vt_function_eval(v, &f, 0.0), VT_ERR_CALLBACK);
    f = vt_function_user(nan_out, NULL);
    assert_int_equal(vt_function_eval(v, &f, 0.0), VT_ERR_NONFINITE);
    f = vt_function_user(NULL, NULL);
    assert_int_equal(vt_function_eval(v, &f, 0.0), VT_ERR_BAD_DRIVE);
    f = vt_function_polynomial(0, NULL);
    assert_int_equal(vt_function_eval(v, &f, 0.0), VT_ERR_BAD_DRIVE);
    f = vt_function_sine(0, INFINITY, 1, 0);
    assert_int_equal(vt_function_eval(v, &f, 0.0), VT_ERR_NONFINITE);
    assert_memory_equal(v, keep, sizeof keep);
    for (int code = 0; code < 9; code++) { /* any slot, NaN or either infinity */
        f = vt_function_user(bad_slot, &code);
        assert_int_equal(vt_function_eval(v, &f, 0.0), VT_ERR_NONFINITE);
    }
    const double big[2] = {1e300, 1e300}; /* finite coefficients: f overflows at t = 1e10, f′ and f″ do not */
    f = vt_function_polynomial(2, big);
    assert_int_equal(vt_function_eval(v, &f, 1e10), VT_ERR_NONFINITE);
    assert_memory_equal(v, keep, sizeof keep);
    assert_int_equal(vt_function_eval(NULL, &f, 0.0), VT_ERR_NULL);
}

/* a one-body model whose joint drive follows f: the builder's copy of a spline (the model's) */
static vt_model *model_with(const vt_function *f)
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def link = vt_default_body_def();
    link.inertia[4] = link.inertia[8] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &link), 1);
    vt_drive_def dr = vt_default_drive_def();
    dr.f = *f;
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* p(t) = 0.5 − t + 2 t² − 0.7 t³ and its derivatives, truncated to degree `deg` */
static void poly(double v[3], double t, int deg)
{
    const double c[4] = {0.5, -1.0, 2.0, -0.7};
    v[0] = v[1] = v[2] = 0.0;
    for (int k = deg; k >= 0; k--) {
        v[2] = v[2] * t + 2.0 * v[1];
        v[1] = v[1] * t + v[0];
        v[0] = v[0] * t + c[k];
    }
}

/* not-a-knot reproduces cubics (n ≥ 4), the parabola of n = 3 a quadratic, the line of n = 2 a
 * line: f, f', f'' to round-off, inside the samples and on the continued end pieces outside */
static void test_spline_exact(void **state)
{
    (void)state;
    const double tk[9] = {-0.3, 0.1, 0.25, 0.9, 1.0, 1.6, 1.75, 2.4, 3.1};
    for (int n = 2; n <= 9; n++) {
        const int deg = n >= 4 ? 3 : n - 1;
        double yk[9], v[3], e[3];
        for (int k = 0; k < n; k++) {
            poly(v, tk[k], deg);
            yk[k] = v[0];
        }
        const vt_function f = vt_function_spline(n, tk, yk);
        vt_model *m = model_with(&f);
        for (double t = -1.0; t <= 4.0; t += 0.0625) {
            poly(e, t, deg);
            for (int route = 0; route < 2; route++) { /* standalone, then the model's copy */
                assert_ok(vt_function_eval(v, route ? &m->drive[0].f : &f, t));
                assert_near(v[0], e[0], 1e-12 * (1 + fabs(e[0])));
                assert_near(v[1], e[1], 1e-11 * (1 + fabs(e[1])));
                assert_near(v[2], e[2], 1e-10 * (1 + fabs(e[2])));
            }
        }
        vt_model_free(m);
    }
}

/* the largest errors of f, f', f'' of the spline through sin on [0, 3] at n samples, at 16
 * points in every interval, the same fractions of it on every grid (the model's copy: no limit
 * on n) */
static void sin_errors(int n, double err[3])
{
    double *tk = malloc(2 * (size_t)n * sizeof(double)), *yk = tk + n;
    assert_non_null(tk);
    for (int k = 0; k < n; k++) {
        tk[k] = 3.0 * k / (n - 1);
        yk[k] = sin(tk[k]);
    }
    const vt_function f = vt_function_spline(n, tk, yk);
    vt_model *m = model_with(&f);
    free(tk); /* the model has its own copy */
    err[0] = err[1] = err[2] = 0.0;
    for (int j = 0; j < 16 * (n - 1); j++) {
        const double t = 3.0 * (j + 0.5) / (16.0 * (n - 1));
        double v[3];
        assert_ok(vt_function_eval(v, &m->drive[0].f, t));
        err[0] = fmax(err[0], fabs(v[0] - sin(t)));
        err[1] = fmax(err[1], fabs(v[1] - cos(t)));
        err[2] = fmax(err[2], fabs(v[2] + sin(t)));
    }
    vt_model_free(m);
}

static void test_spline_convergence(void **state)
{
    (void)state;
    double prev[3], cur[3];
    /* the not-a-knot ends' boundary layer keeps coarser grids' ratios above the asymptotic ones
     * (24, 12, 5.8 from 10 to 20 intervals; 17.9, 8.9, 4.4 from 80 to 160) */
    sin_errors(161, prev);
    for (int n = 321; n <= 1281; n = 2 * n - 1) { /* h halves */
        sin_errors(n, cur);
        const double r0 = prev[0] / cur[0], r1 = prev[1] / cur[1], r2 = prev[2] / cur[2];
        if (!(r0 > 15 && r0 < 17.5) || !(r1 > 7.5 && r1 < 8.75) || !(r2 > 3.75 && r2 < 4.4))
            fail_msg("n %d: error ratios %.3g %.3g %.3g (expected 16, 8, 4)", n, r0, r1, r2);
        memcpy(prev, cur, sizeof prev);
    }
    assert_true(cur[0] < 1e-11);
}

/* f' and f'' against central differences of f and f'; f, f', f'' continuous at the knots
 * (the values just left of a knot, from the left piece, against the value at it) */
static void test_spline_derivatives_and_continuity(void **state)
{
    (void)state;
    const double tk[7] = {0.0, 0.3, 0.45, 1.1, 1.2, 1.9, 2.5}, yk[7] = {0.2, -0.4, 0.1, 0.9, 0.7, -0.3, 0.5};
    const vt_function f = vt_function_spline(7, tk, yk);
    for (double t = -0.5; t <= 3.0; t += 0.0173) check_derivatives(&f, t);
    for (int k = 0; k < 7; k++) {
        double at[3], left[3];
        assert_ok(vt_function_eval(at, &f, tk[k]));
        assert_near(at[0], yk[k], 1e-15 * (1 + fabs(yk[k]))); /* it interpolates */
        assert_ok(vt_function_eval(left, &f, nextafter(tk[k], -INFINITY)));
        for (int c = 0; c < 3; c++) assert_near(left[c], at[c], 1e-12 * (1 + fabs(at[c])));
    }
    /* the jump of f''' at an interior knot that is not t_1 or t_{n−2}: a spline, not one cubic */
    double a[3], b[3], c[3], dd[3];
    const double h = 1e-4;
    assert_ok(vt_function_eval(a, &f, tk[3] - 2 * h));
    assert_ok(vt_function_eval(b, &f, tk[3] - h));
    assert_ok(vt_function_eval(c, &f, tk[3] + h));
    assert_ok(vt_function_eval(dd, &f, tk[3] + 2 * h));
    assert_true(fabs((b[2] - a[2]) - (dd[2] - c[2])) > 1e-6);
}

/* the caller's arrays freed or overwritten after the drive is added change nothing; bad
 * samples and too many samples for a standalone evaluation are refused, out untouched */
static void test_spline_ownership_and_errors(void **state)
{
    (void)state;
    const int n = 200; /* beyond VT_SPLINE_EVAL_MAX */
    double *tk = malloc(2 * (size_t)n * sizeof(double)), *yk = tk + n;
    assert_non_null(tk);
    for (int k = 0; k < n; k++) {
        tk[k] = 0.01 * k + 0.001 * sin(k);
        yk[k] = cos(3.0 * tk[k]);
    }
    vt_function f = vt_function_spline(n, tk, yk);
    double v[3] = {1, 2, 3};
    assert_int_equal(vt_function_eval(v, &f, 0.5), VT_ERR_BAD_SIZE);
    assert_true(v[0] == 1 && v[1] == 2 && v[2] == 3);

    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def link = vt_default_body_def();
    link.inertia[4] = link.inertia[8] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &link), 1);
    vt_drive_def dr = vt_default_drive_def();
    dr.f = f;
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m1;
    assert_ok(vt_builder_build(&m1, b)); /* before the arrays change */
    double keep[3 * 11];
    for (int j = 0; j <= 10; j++) assert_ok(vt_function_eval(keep + 3 * j, &m1->drive[0].f, 0.2 * j - 0.1));
    for (int k = 0; k < n; k++) tk[k] = yk[k] = NAN; /* overwritten, then freed */
    free(tk);
    vt_model *m2;
    assert_ok(vt_builder_build(&m2, b)); /* the builder's copy, after */
    vt_builder_free(b);
    vt_model *m3;
    assert_ok(vt_model_without_drives(&m3, m2));
    assert_int_equal(m3->ndrive, 0);
    vt_model_free(m3);
    for (int j = 0; j <= 10; j++) {
        assert_ok(vt_function_eval(v, &m2->drive[0].f, 0.2 * j - 0.1));
        assert_memory_equal(v, keep + 3 * j, sizeof v);
    }
    vt_model_free(m1);
    vt_model_free(m2);

    /* malformed samples */
    v[0] = 1;
    v[1] = 2;
    v[2] = 3;
    const double t3[3] = {0.0, 1.0, 1.0}, y3[3] = {0, 1, 2}, tn[3] = {0.0, NAN, 2.0};
    const vt_function bad[4] = {vt_function_spline(1, t3, y3), vt_function_spline(3, t3, y3),
                                vt_function_spline(3, tn, y3), vt_function_spline(3, NULL, y3)};
    const vt_status want[4] = {VT_ERR_BAD_DRIVE, VT_ERR_BAD_DRIVE, VT_ERR_NONFINITE, VT_ERR_BAD_DRIVE};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(vt_function_eval(v, &bad[k], 0.5), want[k]);
        assert_true(v[0] == 1 && v[1] == 2 && v[2] == 3);
    }
}

/* the cubic of interval lo of a spline (samples t, y, curvatures M), written out as
 * functions.c's header states it, evaluated at x */
static void spline_reference(double v[3], const double *t, const double *y, const double *M, int lo, double x)
{
    const double h = t[lo + 1] - t[lo], s = x - t[lo], dM = M[lo + 1] - M[lo];
    const double b = (y[lo + 1] - y[lo]) / h - h * (2.0 * M[lo] + M[lo + 1]) / 6.0;
    v[0] = y[lo] + s * (b + s * (0.5 * M[lo] + s * dM / (6.0 * h)));
    v[1] = b + s * (M[lo] + s * dM / (2.0 * h));
    v[2] = M[lo] + s * dM / h;
}

/* the interval of x by a linear search: the last k ≤ n − 2 with t[k] ≤ x (0 before t[0]) */
static int linear_interval(const double *t, int n, double x)
{
    int lo = 0;
    for (int k = 1; k <= n - 2; k++)
        if (t[k] <= x) lo = k;
    return lo;
}

/* f, f', f'' equal to the reference: bitwise, except where the build may fuse a * b + c
 * differently in the test and in the library (FMA targets: -ffp-contract=fast) */
static void assert_spline_equal(const double v[3], const double e[3], double x)
{
    for (int c = 0; c < 3; c++) {
#if defined(__FP_FAST_FMA)
        const double tol = 8 * DBL_EPSILON * (fabs(e[0]) + fabs(e[1]) + fabs(e[2]) + 1.0);
#else
        const double tol = 0.0;
#endif
        if (!(fabs(v[c] - e[c]) <= tol))
            fail_msg("x %.17g: component %d %.17g, reference %.17g", x, c, v[c], e[c]);
    }
}

/* A model's spline drive (uneven spacing, 4097 samples) evaluated by vt_function_eval (the
 * bisection) equals the cubic formula on the interval a linear search finds, bitwise: at the
 * first and the last sample, at every sample and the doubles either side of it, at every
 * interval's midpoint, at 2000 pseudo-random points and outside [t_0, t_{n−1}] (the end pieces
 * continued) */
static void test_spline_interval_search(void **state)
{
    (void)state;
    const int n = 4097;
    double *tk = malloc(2 * (size_t)n * sizeof(double)), *yk = tk + n;
    assert_non_null(tk);
    for (int k = 0; k < n; k++) {
        tk[k] = 0.01 * k + 0.003 * sin(1.7 * k);
        yk[k] = cos(0.37 * tk[k]) + 0.01 * sin(5.0 * k);
    }
    const vt_function g = vt_function_spline(n, tk, yk);
    vt_model *m = model_with(&g);
    free(tk);
    const vt_function *f = &m->drive[0].f;
    const double *t = f->sample_t, *y = f->sample_y, *M = f->sample_d2;
    double v[3], e[3];
#define CHECK_AT(xx)                                                    \
    do {                                                                \
        const double x_ = (xx);                                         \
        assert_ok(vt_function_eval(v, f, x_));                          \
        spline_reference(e, t, y, M, linear_interval(t, n, x_), x_);    \
        assert_spline_equal(v, e, x_);                                  \
    } while (0)
    for (int k = 0; k < n; k++) {
        CHECK_AT(t[k]);
        CHECK_AT(nextafter(t[k], -INFINITY));
        CHECK_AT(nextafter(t[k], INFINITY));
        if (k < n - 1) CHECK_AT(0.5 * (t[k] + t[k + 1]));
    }
    uint64_t r = 0x9e3779b97f4a7c15u;
    const double span = t[n - 1] - t[0];
    for (int j = 0; j < 2000; j++) {
        r = r * 6364136223846793005u + 1442695040888963407u;
        CHECK_AT(t[0] - 0.05 * span + 1.1 * span * (double)(r >> 11) / 9007199254740992.0);
    }
    const double outside[4] = {t[0] - 1.0, t[0] - 1e-300, t[n - 1] + 1e-9, t[n - 1] + 3.0};
    for (int j = 0; j < 4; j++) CHECK_AT(outside[j]);
#undef CHECK_AT
    vt_model_free(m);
}

/* a straight line is every spline's exact answer (its curvatures solve to exact zeros when the
 * samples' slopes are exact): y = 3 + t/2 at dyadic, uneven times, every value exact at dyadic
 * points inside and outside, standalone (n ≤ VT_SPLINE_EVAL_MAX) and as a model's drive */
static void test_spline_line_exact(void **state)
{
    (void)state;
    double tk[40], yk[40];
    for (int k = 0; k < 40; k++) {
        tk[k] = 0.25 * k + 0.0625 * (k % 3);
        yk[k] = 3.0 + 0.5 * tk[k];
    }
    for (int n = 2; n <= 40; n += n < 6 ? 1 : 17) {
        const vt_function f = vt_function_spline(n, tk, yk);
        vt_model *m = model_with(&f);
        for (int j = -32; j <= 16 * n + 32; j++) {
            const double x = j / 64.0;
            for (int route = 0; route < 2; route++) {
                double v[3];
                assert_ok(vt_function_eval(v, route ? &m->drive[0].f : &f, x));
                if (!(v[0] == 3.0 + 0.5 * x && v[1] == 0.5 && v[2] == 0.0))
                    fail_msg("n %d, x %g, %s: %.17g %.17g %.17g", n, x, route ? "model" : "standalone", v[0], v[1], v[2]);
            }
        }
        vt_model_free(m);
    }
}

/* Evaluating a model's spline drive reads the samples of its own interval, not all n (the
 * samples were checked when the drive was added): with every other sample's value and curvature
 * in the model's copy overwritten by NaN (white box: the test writes into the model it owns),
 * f, f', f'' at points of the kept interval are bitwise what they were, and a point of an
 * interval whose samples are NaN is refused (VT_ERR_NONFINITE). A check of the n samples at
 * each call refused every one. A raw function (the caller's arrays, its sample_d2 set by the
 * caller) is still checked in full. */
static void test_spline_drive_reads_its_interval(void **state)
{
    (void)state;
    const int n = 3001;
    double *tk = malloc(2 * (size_t)n * sizeof(double)), *yk = tk + n;
    assert_non_null(tk);
    for (int k = 0; k < n; k++) {
        tk[k] = 0.5 * k + 0.1 * sin((double)k);
        yk[k] = sin(0.05 * tk[k]);
    }
    const vt_function g = vt_function_spline(n, tk, yk);
    vt_model *m = model_with(&g);
    const vt_function *f = &m->drive[0].f;
    double *y = (double *)f->sample_y, *M = (double *)f->sample_d2; /* the model's own block */
    double *ykeep = malloc(2 * (size_t)n * sizeof(double)), *Mkeep = ykeep + n;
    assert_non_null(ykeep);
    memcpy(ykeep, y, (size_t)n * sizeof(double));
    memcpy(Mkeep, M, (size_t)n * sizeof(double));
    const int intervals[5] = {0, 1, 1234, n / 2, n - 2};
    for (int j = 0; j < 5; j++) {
        const int i = intervals[j];
        const double x[3] = {f->sample_t[i], 0.3 * f->sample_t[i] + 0.7 * f->sample_t[i + 1],
                             nextafter(f->sample_t[i + 1], -INFINITY)};
        double before[9], v[3] = {1, 2, 3};
        for (int p = 0; p < 3; p++) assert_ok(vt_function_eval(before + 3 * p, f, x[p]));
        for (int k = 0; k < n; k++)
            if (k != i && k != i + 1) y[k] = M[k] = NAN;
        for (int p = 0; p < 3; p++) {
            const vt_status st = vt_function_eval(v, f, x[p]);
            if (st != VT_OK) fail_msg("interval %d, x %.17g: status %d with the other samples NaN", i, x[p], (int)st);
            assert_memory_equal(v, before + 3 * p, sizeof v);
        }
        const int other = i < n / 2 ? n - 2 : 0; /* an interval of NaN samples */
        assert_int_equal(vt_function_eval(v, f, 0.5 * (f->sample_t[other] + f->sample_t[other + 1])), VT_ERR_NONFINITE);
        assert_memory_equal(v, before + 6, sizeof v); /* untouched */
        memcpy(y, ykeep, (size_t)n * sizeof(double));
        memcpy(M, Mkeep, (size_t)n * sizeof(double));
    }
    /* the caller's own arrays with its own sample_d2: checked in full (here a far value NaN) */
    double *d2 = malloc((size_t)n * sizeof(double));
    assert_non_null(d2);
    memcpy(d2, Mkeep, (size_t)n * sizeof(double));
    yk[n - 7] = NAN;
    vt_function raw = g;
    raw.sample_d2 = d2;
    double v[3];
    assert_int_equal(vt_function_eval(v, &raw, tk[3]), VT_ERR_NONFINITE);
    yk[n - 7] = sin(0.05 * tk[n - 7]);
    assert_ok(vt_function_eval(v, &raw, tk[3]));
    free(d2);
    free(ykeep);
    free(tk);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builtins),
        cmocka_unit_test(test_callbacks_and_errors),
        cmocka_unit_test(test_spline_exact),
        cmocka_unit_test(test_spline_convergence),
        cmocka_unit_test(test_spline_derivatives_and_continuity),
        cmocka_unit_test(test_spline_ownership_and_errors),
        cmocka_unit_test(test_spline_interval_search),
        cmocka_unit_test(test_spline_line_exact),
        cmocka_unit_test(test_spline_drive_reads_its_interval),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
