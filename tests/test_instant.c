/* src/dense/instant.c: vt_inverse_dynamics is the stages called one after another, so on every scene
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

/* a copy of the caller's inputs, to compare after a failed call */
typedef struct {
    double q[64], qd[64], xfrc[6 * 16], qfrc[64], time;
} inputs;
static void keep(inputs *k, const vt_model *m, const vt_data *d)
{
    assert_true(m->nq <= 64 && m->nv <= 64 && m->nbody < 16);
    memcpy(k->q, d->q, (size_t)m->nq * sizeof(double));
    memcpy(k->qd, d->qd, (size_t)m->nv * sizeof(double));
    memcpy(k->xfrc, d->xfrc, 6 * (size_t)(m->nbody + 1) * sizeof(double));
    memcpy(k->qfrc, d->qfrc, (size_t)m->nv * sizeof(double));
    k->time = d->time;
}
static void unchanged(const inputs *k, const vt_model *m, const vt_data *d)
{
    assert_memory_equal(k->q, d->q, (size_t)m->nq * sizeof(double));
    assert_memory_equal(k->qd, d->qd, (size_t)m->nv * sizeof(double));
    assert_memory_equal(k->xfrc, d->xfrc, 6 * (size_t)(m->nbody + 1) * sizeof(double));
    assert_memory_equal(k->qfrc, d->qfrc, (size_t)m->nv * sizeof(double));
    assert_memory_equal(&k->time, &d->time, sizeof k->time);
}

/* Finite inputs whose results overflow: both evaluations of the instant refuse them with
 * VT_ERR_NONFINITE and a message, and leave the inputs as they were (they returned VT_OK with
 * Inf, or a status with no message). A base body's Euler parameters ×1e200 (A(p) overflows),
 * every rate at 1e300 (ω² overflows), and on the double link 1.5e308 N across both links (Q
 * overflows). */
static void test_overflow_refused(void **state)
{
    (void)state;
    for (int c = 0; c < 3; c++) {
        vt_model *m;
        vt_data *d;
        if (c < 2) {
            uint64_t seed = 1;
            for (;; seed++) { /* a tree with a base body */
                assert_ok(vt_scene_random_tree(&m, seed, 8, VT_SCENE_ALL_JOINTS));
                int base = 0;
                for (int i = 1; i <= m->nbody; i++) base += m->body_joint[i] == VT_JOINT_BASE;
                if (base) break;
                vt_model_free(m);
            }
            assert_ok(vt_data_create(&d, m));
            uint64_t s = seed;
            vt_scene_random_state(m, d, &s);
            if (c == 0) {
                for (int i = 1; i <= m->nbody; i++)
                    if (m->body_joint[i] == VT_JOINT_BASE)
                        for (int k = 3; k < 7; k++) d->q[m->body_qadr[i] + k] *= 1e200;
            } else {
                for (int k = 0; k < m->nv; k++) d->qd[k] = 1e300;
            }
        } else {
            assert_ok(vt_scene_double_link(&m, 0));
            assert_ok(vt_data_create(&d, m));
            d->xfrc[6 * 1 + 1] = d->xfrc[6 * 2 + 1] = 1.5e308;
        }
        inputs k;
        keep(&k, m, d);
        for (int recursive = 0; recursive < 2; recursive++) {
            d->message[0] = '\0';
            const vt_status st = recursive ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
            if (st != VT_ERR_NONFINITE) fail_msg("case %d, recursive %d: status %d (%s)", c, recursive, (int)st, d->message);
            if (!d->message[0]) fail_msg("case %d, recursive %d: no message", c, recursive);
            unchanged(&k, m, d);
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pipeline_is_the_stages),
        cmocka_unit_test(test_first_failure_stops),
        cmocka_unit_test(test_overflow_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
