/* src/analysis/kinematic_solve.c: the consistent q̇ and q̈ of an instant against differences of the Newton
 * solutions in time; a free joint driven by joint drives and an orientation drive; fewer rows than
 * rates: the least-norm corrections; Newton's starts from a trajectory's rows (vt_kinematic_start)
 * exact for the polynomials of their degree. */
#include "vt_test.h"
#include "analysis/kinematic_solve.h" /* vt_kinematic_start */

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
    vt_model *m;
    assert_ok(vt_scene_free_joint_driven(&m));
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

/* A free body (base joint) held by an orientation drive about `axis` turning f(t) = 0.8 sin 2t
 * and three point drives keeping its centre at the origin: as many rows as rates. */
static vt_model *driven_base(const double axis[3])
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_BASE;
    body.inertia[0] = 1.0; body.inertia[4] = 2.0; body.inertia[8] = 2.5;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    memcpy(od.axis, axis, sizeof od.axis);
    od.f = vt_function_sine(0.0, 0.8, 2.0, 0.0);
    assert_int_equal(vt_builder_add_drive(b, &od), 0);
    for (int k = 0; k < 3; k++) {
        vt_drive_def pd = vt_default_drive_def();
        pd.type = VT_DRIVE_POINT;
        pd.index = k;
        assert_int_equal(vt_builder_add_drive(b, &pd), k + 1);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* The drive's axis (0, 0, 1e200) is the z axis (its sum of squares overflows: it was stored as
 * zero and the body held still): the body turns f(t) about z, p = [cos f/2, 0, 0, sin f/2] up to
 * sign, at ω = f'(t) about z. */
static void test_orientation_drive_long_axis(void **state)
{
    (void)state;
    const double axis[3] = {0.0, 0.0, 1e200};
    vt_model *m = driven_base(axis);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    for (double t = 0.3; t < 1.0; t += 0.4) {
        d->time = t;
        assert_ok(vt_kinematic_solve(m, d, 1e-13, 30));
        const double th = 0.8 * sin(2.0 * t), *p = d->q + 3, sg = p[0] < 0 ? -1.0 : 1.0;
        assert_near(sg * p[0], cos(0.5 * th), 1e-12);
        assert_near(sg * p[3], sin(0.5 * th), 1e-12);
        assert_near(p[1], 0.0, 1e-12);
        assert_near(p[2], 0.0, 1e-12);
        assert_near(d->omega[3 + 2], 1.6 * cos(2.0 * t), 1e-10);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* Every refusal of vt_kinematic_solve says why in d->message and gives q and q̇ back as they
 * were: Euler parameters ×1e200 (A(p) overflows; the status came with an empty message),
 * tol = +Inf (passed the check `!(tol > 0)`, and Newton then stopped at any residual), tol NaN,
 * maxit 0, a NaN in q. */
static void test_failures_have_messages(void **state)
{
    (void)state;
    const double axis[3] = {0.0, 0.0, 1.0};
    vt_model *m = driven_base(axis);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    d->time = 0.4;
    double q0[7], qd0[7];
    for (int c = 0; c < 5; c++) {
        assert_ok(vt_data_reset(m, d));
        d->time = 0.4;
        d->q[0] = 0.1; d->qd[1] = 0.2;
        double tol = 1e-12;
        int maxit = 30;
        switch (c) {
        case 0: for (int k = 3; k < 7; k++) d->q[k] *= 1e200; break;
        case 1: tol = INFINITY; break;
        case 2: tol = NAN; break;
        case 3: maxit = 0; break;
        default: d->q[2] = NAN;
        }
        memcpy(q0, d->q, sizeof q0);
        memcpy(qd0, d->qd, sizeof qd0);
        d->message[0] = '\0';
        const vt_status st = vt_kinematic_solve(m, d, tol, maxit);
        if (st == VT_OK) fail_msg("case %d: accepted", c);
        if (!d->message[0]) fail_msg("case %d: status %d with an empty message", c, (int)st);
        assert_memory_equal(d->q, q0, sizeof q0);
        assert_memory_equal(d->qd, qd0, sizeof qd0);
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

/* coordinate c of a polynomial motion of degree deg and its derivatives (der 0, 1, 2) at t */
static double poly(int deg, int c, int der, double t)
{
    double s = 0.0;
    for (int j = der; j <= deg; j++) {
        double f = 1.0;
        for (int k = 0; k < der; k++) f *= j - k;
        s += f * ((j % 2 ? -1.0 : 1.0) * (c + 1.0) / (j + 1.0)) * pow(t, j - der);
    }
    return s;
}

/* Newton's start from rows whose q, q̇, q̈ are those of a polynomial motion: the Hermite
 * polynomial through three rows (degree 8), two rows (degree 5) and one (Taylor, degree 2)
 * reproduces a motion of its degree exactly, interpolated between irregular rows and
 * extrapolated past them; one degree more and it does not */
static void test_start_exact_for_its_degree(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m)); /* five revolute joints: q̇ is the derivative of q */
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 4));
    static const double times[4] = {0.0, 0.1, 0.25, 0.3};
    static const struct { int k1, k2, k3, deg; double t; } cases[] = {
        {1, 2, 3, 8, 0.18}, {2, 1, 3, 8, 0.12}, {3, 2, 1, 8, 0.36}, {1, 2, -1, 5, 0.2}, {2, 1, -1, 5, 0.33},
        {1, -1, -1, 2, 0.14},
    };
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++)
        for (int extra = 0; extra < 2; extra++) { /* the motion of the start's degree, then one more */
            const int deg = cases[n].deg + extra;
            for (int k = 0; k < 4; k++) {
                tr->t[k] = times[k];
                for (int c = 0; c < 5; c++) {
                    tr->q[5 * k + c] = poly(deg, c, 0, times[k]);
                    tr->qd[5 * k + c] = poly(deg, c, 1, times[k]);
                    tr->qdd[5 * k + c] = poly(deg, c, 2, times[k]);
                }
            }
            tr->nfilled = 4;
            d->time = cases[n].t;
            assert_ok(vt_kinematic_start(m, d, tr, cases[n].k1, cases[n].k2, cases[n].k3));
            double err = 0.0;
            for (int c = 0; c < 5; c++) err = fmax(err, fabs(d->q[c] - poly(deg, c, 0, cases[n].t)));
            if (extra == 0 && !(err <= 1e-12)) fail_msg("case %zu: degree %d off by %g", n, deg, err);
            if (extra == 1 && !(err > 1e-11)) fail_msg("case %zu: degree %d reproduced (%g): the test cannot fail", n, deg, err);
        }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rates_against_differences),
        cmocka_unit_test(test_free_joint_driven),
        cmocka_unit_test(test_orientation_drive_long_axis),
        cmocka_unit_test(test_failures_have_messages),
        cmocka_unit_test(test_fewer_rows_least_norm),
        cmocka_unit_test(test_start_exact_for_its_degree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
