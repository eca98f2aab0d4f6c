/* src/analysis/trajectory.c: allocation, defaults, and the forward check's error norms measured
 * against a hand-made difference. */
#include "vt_test.h"

static void test_create_and_defaults(void **state)
{
    (void)state;
    vt_model *m;
    vt_trajectory *tr = NULL;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_int_equal(vt_trajectory_create(&tr, m, 0), VT_ERR_BAD_OPTION);
    assert_null(tr);
    assert_int_equal(vt_trajectory_create(NULL, m, 3), VT_ERR_NULL);
    assert_ok(vt_trajectory_create(&tr, m, 3));
    assert_int_equal(tr->nrow, 3);
    assert_int_equal(tr->nfilled, 0);
    assert_ptr_equal(tr->model, m);
    /* every array is writable over its full size */
    for (int k = 0; k < 3 * m->nq; k++) tr->q[k] = tr->q_fwd[k] = 1.0;
    for (int k = 0; k < 3 * 3 * (m->nbody + 1); k++) tr->jnt_force[k] = tr->jnt_moment_fwd[k] = 2.0;
    vt_trajectory_free(tr);
    vt_trajectory_free(NULL);
    const vt_run_options o = vt_default_run_options();
    assert_near(o.t0, 0.0, 0.0);
    assert_near(o.t1, 1.0, 0.0);
    assert_int_equal(o.nout, 100);
    assert_true(o.rtol > 0 && o.atol > 0 && o.newton_tol > 0 && o.forward_check == VT_HAVE_SUNDIALS);
    vt_model_free(m);
}

#if VT_HAVE_SUNDIALS /* the forward check integrates with IDA */
/* the self-check norms are the largest differences between the two runs */
static void test_forward_error_norms(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 20;
    opt.t1 = 0.5;
    assert_ok(vt_trajectory_create(&tr, m, 21));
    assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
    double eq = 0.0, ev = 0.0, ef = 0.0, em = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        for (int c = 0; c < m->nq; c++) eq = fmax(eq, fabs(tr->q_fwd[2 * k + c] - tr->q[2 * k + c]));
        for (int c = 0; c < m->nv; c++) ev = fmax(ev, fabs(tr->qd_fwd[2 * k + c] - tr->qd[2 * k + c]));
        for (int c = 0; c < 9; c++) {
            ef = fmax(ef, fabs(tr->jnt_force_fwd[9 * k + c] - tr->jnt_force[9 * k + c]));
            em = fmax(em, fabs(tr->jnt_moment_fwd[9 * k + c] - tr->jnt_moment[9 * k + c]));
        }
    }
    assert_near(tr->fwd_err_q, eq, 0.0);
    assert_near(tr->fwd_err_qd, ev, 0.0);
    assert_near(tr->fwd_err_force, ef, 0.0);
    assert_near(tr->fwd_err_moment, em, 0.0);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}
#endif

/* The run options' tolerances and step limits must be finite: +Inf passed the checks `!(tol > 0)`
 * (with newton_tol = Inf every instant "converged" at any residual, the rows off their drives).
 * Each refused with VT_ERR_BAD_OPTION and a message, by both analyses. */
static void test_infinite_options(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 11));
    for (int k = 0; k < 4; k++) {
        vt_run_options opt = vt_default_run_options();
        opt.nout = 10;
        opt.forward_check = 0;
        double *field[4] = {&opt.rtol, &opt.atol, &opt.newton_tol, &opt.max_step};
        *field[k] = INFINITY;
        d->message[0] = '\0';
        assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
        assert_true(strlen(d->message) > 0);
#if VT_HAVE_SUNDIALS
        assert_int_equal(vt_dynamic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
#endif
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* The forward check's window (vt_run_options.check_window): 0, negative and NaN refused with
 * VT_ERR_BAD_OPTION and a message naming it, by both analyses, before anything is written: the
 * data's state and the trajectory as they were (the contract's promise, tests/test_contract.c);
 * +Inf (the whole run one window) and the default accepted. */
static void test_check_window_option(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 11));
    const double bad[4] = {0.0, -1.0, NAN, -INFINITY};
    for (int k = 0; k < 4; k++) {
        vt_run_options opt = vt_default_run_options();
        opt.nout = 10;
        opt.check_window = bad[k];
        for (int a = 0; a < 1 + VT_HAVE_SUNDIALS; a++) {
            d->q[0] = 0.25;
            d->q[1] = -0.5;
            d->time = 7.0;
            d->message[0] = '\0';
            tr->nfilled = 5;
            tr->t[3] = 42.0;
            tr->nwindow = 3;
            tr->fwd_err_q = 9.0;
#if VT_HAVE_SUNDIALS
            const vt_status st = a ? vt_dynamic_analysis(m, d, &opt, tr) : vt_kinematic_analysis(m, d, &opt, tr);
#else
            const vt_status st = vt_kinematic_analysis(m, d, &opt, tr);
#endif
            assert_int_equal(st, VT_ERR_BAD_OPTION);
            if (!strstr(d->message, "check_window")) fail_msg("check_window %g: message \"%s\"", bad[k], d->message);
            assert_true(d->q[0] == 0.25 && d->q[1] == -0.5 && d->time == 7.0);
            assert_true(tr->nfilled == 5 && tr->t[3] == 42.0 && tr->nwindow == 3 && tr->fwd_err_q == 9.0);
        }
    }
    assert_near(vt_default_run_options().check_window, VT_CHECK_WINDOW, 0.0);
#if VT_HAVE_SUNDIALS
    vt_run_options opt = vt_default_run_options();
    opt.nout = 10;
    opt.t1 = 0.5;
    opt.check_window = INFINITY;
    d->q[0] = d->q[1] = 0.0;
    d->time = 0.0;
    assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nwindow, 1);
    assert_int_equal(tr->fwd_window_row[0], 0);
    assert_near(tr->fwd_window_err_q[0], tr->fwd_err_q, 0.0);
#endif
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_and_defaults),
        cmocka_unit_test(test_check_window_option),
#if VT_HAVE_SUNDIALS
        cmocka_unit_test(test_forward_error_norms),
#endif
        cmocka_unit_test(test_infinite_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
