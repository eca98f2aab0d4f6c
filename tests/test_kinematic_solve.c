/* src/kinematic_solve.c: the consistent q̇ and q̈ of an instant against differences of the Newton
 * solutions in time; a free joint driven by joint drives and an orientation drive; fewer rows than
 * rates: the least-norm corrections. */
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

/* A free joint driven whole: body 2 on a free joint from body 1 (a driven hinge), its
 * translation by three joint drives and its orientation by an orientation drive. The solved q
 * holds the drives (translation = f_k(t), orientation = p_d(t)); body 2's angular velocity is
 * f'(t) times the drive's axis; the bodies' velocities and accelerations against central
 * differences of the solved positions and velocities in time. */
static void test_free_joint_driven(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint_child[0] = -0.5;
    body.inertia[0] = body.inertia[4] = body.inertia[8] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    body.parent = 1;
    body.joint = VT_JOINT_FREE;
    body.joint_parent[0] = 0.5;
    body.joint_child[0] = 0.2, body.joint_child[1] = -0.1, body.joint_child[2] = 0.3;
    assert_int_equal(vt_builder_add_body(b, &body), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    dr.f = vt_function_sine(0.2, 0.7, 1.1, 0.3);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    for (int k = 0; k < 3; k++) {
        dr.body = 2;
        dr.index = k;
        dr.f = vt_function_sine(0.1 * k, 0.3 + 0.1 * k, 0.9 + 0.4 * k, 0.2 * k);
        assert_int_equal(vt_builder_add_drive(b, &dr), k + 1);
    }
    dr = vt_default_drive_def();
    dr.type = VT_DRIVE_ORIENTATION;
    dr.body = 2;
    dr.axis[0] = 0.0, dr.axis[1] = 0.6, dr.axis[2] = 0.8;
    dr.f = vt_function_sine(0.1, 0.5, 1.3, 0.0);
    assert_int_equal(vt_builder_add_drive(b, &dr), 4);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nc, m->nv); /* 1 + 3 + 3 rows, 1 + 6 rates */
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    const double h = 1e-5;
    for (double t = 0.1; t < 1.5; t += 0.33) {
        double x[3][14], xd[3][14], xdd[14], q[8], w[3];
        for (int s = 0; s < 3; s++) {
            d->time = t + (s - 1) * h;
            assert_ok(vt_kinematic_solve(m, d, 1e-13, 30));
            memcpy(x[s], d->x, sizeof x[s]);
            memcpy(xd[s], d->xd, sizeof xd[s]);
            if (s == 1) {
                memcpy(xdd, d->xdd, sizeof xdd);
                memcpy(q, d->q, sizeof q);
                memcpy(w, d->omega + 6, sizeof w);
            }
        }
        for (int k = 0; k < 3; k++) {
            double f[3];
            assert_ok(vt_function_eval(f, &m->drive[1 + k].f, t));
            assert_near(q[1 + k], f[0], 1e-12);
        }
        double f[3], pd[4], u[3] = {0.0, 0.6, 0.8};
        assert_ok(vt_function_eval(f, &m->drive[4].f, t));
        vt_quat_axis_angle(pd, u, f[0]);
        const double *p = x[1] + 7 + 3, dot = p[0] * pd[0] + p[1] * pd[1] + p[2] * pd[2] + p[3] * pd[3];
        assert_near(fabs(dot), 1.0, 1e-12);
        for (int k = 0; k < 3; k++) assert_near(w[k], f[1] * u[k], 1e-10);
        for (int r = 0; r < 14; r++) {
            assert_near(xd[1][r], (x[2][r] - x[0][r]) / (2 * h), 1e-6 * (1 + fabs(xd[1][r])));
            assert_near(xdd[r], (xd[2][r] - xd[0][r]) / (2 * h), 1e-5 * (1 + fabs(xdd[r])));
        }
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* One drive on the double link's second joint (one row, two rates): the least-norm corrections
 * move only the driven rate, so q1 and q̇1 stay exactly as given and q2, q̇2 take the drive's f, f' */
static void test_fewer_rows_least_norm(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    const vt_function f = vt_function_sine(0.2, 0.5, 3.0, 0.1);
    assert_ok(vt_scene_double_link_driven(&m, f));
    assert_int_equal(m->nc, 1);
    assert_int_equal(m->nv, 2);
    assert_ok(vt_data_create(&d, m));
    d->q[0] = 0.4, d->q[1] = -0.3, d->qd[0] = 0.7, d->qd[1] = 2.0;
    d->time = 0.37;
    assert_ok(vt_kinematic_solve(m, d, 1e-14, 30));
    double v[3];
    assert_ok(vt_function_eval(v, &f, 0.37));
    assert_true(d->q[0] == 0.4 && d->qd[0] == 0.7);
    assert_near(d->q[1], v[0], 1e-14);
    assert_near(d->qd[1], v[1], 1e-14);
    assert_near(d->qdd[1], v[2], 1e-12);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rates_against_differences),
        cmocka_unit_test(test_free_joint_driven),
        cmocka_unit_test(test_fewer_rows_least_norm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
