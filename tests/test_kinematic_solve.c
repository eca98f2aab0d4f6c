/* src/kinematic_solve.c: the consistent q̇ and q̈ of an instant against differences of the Newton
 * solutions in time. */
#include "vt_test.h"

/* q̇ and q̈ of the Newton solutions against central differences of q(t) and q̇(t) */
static void test_rates_against_differences(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    const double h = 1e-5;
    for (double t = 0.05; t < 1.0; t += 0.21) {
        double q[3][5], v[3][5], a[5];
        for (int s = 0; s < 3; s++) {
            vt_scene_five_link_guess(m, d, t + (s - 1) * h);
            d->time = t + (s - 1) * h;
            assert_ok(vt_kinematic_solve(m, d, 1e-13, 30));
            memcpy(q[s], d->q, sizeof q[s]);
            memcpy(v[s], d->qd, sizeof v[s]);
            if (s == 1) memcpy(a, d->qdd, sizeof a);
        }
        for (int k = 0; k < 5; k++) {
            assert_near(v[1][k], (q[2][k] - q[0][k]) / (2 * h), 1e-6 * (1 + fabs(v[1][k])));
            assert_near(a[k], (v[2][k] - v[0][k]) / (2 * h), 1e-5 * (1 + fabs(a[k])));
        }
    }
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rates_against_differences),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
