/* src/functions.c: f' and f'' of every built-in time function against central differences
 * of f and f', exact values, and the error paths of user callbacks. */
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
    assert_int_equal(vt_function_eval(NULL, &f, 0.0), VT_ERR_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builtins),
        cmocka_unit_test(test_callbacks_and_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
