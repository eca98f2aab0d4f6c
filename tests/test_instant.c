/* src/instant.c: vt_inverse_dynamics is the stages called one after another, so on every scene
 * its results equal those of the stages run by hand, bitwise; the first stage that fails stops
 * it, with that stage's status and name in the message. */
#include "vt_test.h"

static void stages(const vt_model *m, vt_data *d)
{
    assert_ok(vt_kinematics(m, d));
    assert_ok(vt_mass_matrix(m, d));
    assert_ok(vt_forces(m, d));
    assert_ok(vt_constraints(m, d));
    assert_ok(vt_solve(m, d));
    assert_ok(vt_reactions(m, d));
}

static void same(const double *a, const double *b, int n, const char *what)
{
    if (n > 0 && memcmp(a, b, (size_t)n * sizeof(double)) != 0) fail_msg("%s differs", what);
}

static void test_pipeline_is_the_stages(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 8; seed++) {
        vt_model *m;
        vt_data *a, *b;
        assert_ok(vt_scene_random_tree(&m, seed, 8, VT_SCENE_ALL_JOINTS));
        assert_ok(vt_data_create(&a, m));
        assert_ok(vt_data_create(&b, m));
        uint64_t s = seed;
        vt_scene_random_state(m, a, &s);
        memcpy(b->q, a->q, (size_t)m->nq * sizeof(double));
        memcpy(b->qd, a->qd, (size_t)m->nv * sizeof(double));
        for (int c = 0; c < m->nv; c++) a->qfrc[c] = b->qfrc[c] = 0.1 * c;
        assert_ok(vt_inverse_dynamics(m, a));
        stages(m, b);
        const int nb3 = 3 * (m->nbody + 1);
        same(a->qdd, b->qdd, m->nv, "qdd");
        same(a->lambda, b->lambda, m->nc, "lambda");
        same(a->xdd, b->xdd, m->nx, "xdd");
        same(a->jnt_force, b->jnt_force, nb3, "jnt_force");
        same(a->jnt_moment, b->jnt_moment, nb3, "jnt_moment");
        same(a->drive_effort, b->drive_effort, m->ndrive, "drive_effort");
        assert_int_equal(a->route, b->route);
        assert_int_equal(a->fallback, b->fallback);
        vt_data_free(a);
        vt_data_free(b);
        vt_model_free(m);
    }
}

static void test_first_failure_stops(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    d->qd[1] = INFINITY; /* the kinematics refuse it */
    assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_NONFINITE);
    assert_non_null(strstr(d->message, "vt_kinematics"));
    d->qd[1] = 0.0;
    d->xfrc[6 + 2] = NAN; /* the forces refuse it */
    assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_NONFINITE);
    assert_non_null(strstr(d->message, "vt_forces"));
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pipeline_is_the_stages),
        cmocka_unit_test(test_first_failure_stops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
