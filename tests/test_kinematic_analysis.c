/* src/analysis/kinematic_analysis.c: the kinematic analysis of the five-link arm (tip on the prescribed circle,
 * the forward check; the free joint's forward check under the drives' loads), its rows
 * (recursive instants from predicted starts) against the dense vt_kinematic_solve from
 * independent starts, one Newton step per row, the stretched arm that warns then fails, and
 * the failure statuses (not fully driven, Newton that does not converge, abort, bad options); a
 * fully driven model with dependent rows, decided by rank; a spherical joint's relative
 * orientation drive through the forward check both ways; each row's instant, which takes
 * Newton's last positions and Φ_q, against a fresh recursive instant at the row's state; the
 * caller's loads (xfrc, qfrc) kept through the forward check; wrenches at frames over a run
 * (the Delta's gripper pressed) against the batch's on each row's state, and through the
 * forward check. */
#include <float.h>

#include "vt_test.h"

static void tip_of(double out[3], const vt_model *m, vt_data *d, const double *q)
{
    memcpy(d->q, q, (size_t)m->nq * sizeof(double));
    assert_ok(vt_kinematics(m, d));
    for (int k = 0; k < 3; k++) out[k] = d->x[7 * 4 + k] + 0.1 * d->A[9 * 5 + k];
}

#if VT_HAVE_SUNDIALS
static void test_five_link_circle_and_forward_check(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d, *dt;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dt, m));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 100;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    vt_scene_five_link_guess(m, d, 0.0);
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, 101);
    double dev = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double t = tr->t[k], w = 2.0 * 3.14159265358979323846;
        double p[3], pf[3];
        tip_of(p, m, dt, tr->q + 5 * k);
        assert_near(p[0], VT_FL_C1 + 0.3 * cos(w * t), 1e-10);
        assert_near(p[1], 0.3 * sin(w * t), 1e-10);
        assert_near(p[2], VT_FL_CE, 1e-10);
        tip_of(pf, m, dt, tr->q_fwd + 5 * k);
        dev = fmax(dev, sqrt((pf[0] - p[0]) * (pf[0] - p[0]) + (pf[1] - p[1]) * (pf[1] - p[1]) + (pf[2] - p[2]) * (pf[2] - p[2])));
        /* the torques are the joint-space form of the drives' forces: M* q̈ − Q */
        assert_near(tr->phi_norm[k], 0.0, 1e-12);
        assert_near(tr->phid_norm[k], 0.0, 1e-10);
    }
    assert_true(dev <= 1e-10); /* the exact efforts keep the undriven arm on the circle to round-off */
    assert_true(dev > 0.0);    /* a separate integration: not the driven run copied */
    assert_true(tr->steps_fwd > 0);
    vt_trajectory_free(tr);
    vt_data_free(dt);
    vt_data_free(d);
    vt_model_free(m);
}
/* The caller's loads (a force on the arm, a torque on a rate) are in every row's efforts and in
 * the forward check's, at the rows and between them: the arm stays on its circle, and with the
 * drives' own loads applied its reactions compare too */
static void test_forward_check_with_loads(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 20;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    vt_scene_five_link_guess(m, d, 0.0);
    d->xfrc[6 * 3 + 1] = 30.0; /* 30 N along y on body 3 */
    d->qfrc[1] = 4.0;          /* 4 N m on the second rate */
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_true(tr->fwd_err_q < 1e-10);
    assert_true(tr->fwd_err_qd < 1e-9);
    /* the tip's point drives as joint torques: the rows' reactions count the drives' forces at
     * the tip, the forward run's do not (vt_run_options.forward_as_loads); as the drives' own
     * loads, the reactions compare too */
    assert_true(tr->fwd_err_force > 1.0);
    opt.forward_as_loads = 1;
    vt_scene_five_link_guess(m, d, 0.0);
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_true(tr->fwd_err_q < 1e-10);
    assert_true(tr->fwd_err_force < 1e-8);
    assert_true(tr->fwd_err_moment < 1e-8);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}
/* The forward check integrates the deviation from the exact motion, which the exact efforts keep
 * at round-off: IDA crosses the period in a few dozen steps at any tolerance, also with an atol
 * far below the round-off of q (its weights are those of the state, rtol |q| + atol, so it does
 * not chase the deviation's round-off), and the deviation stays round-off */
static void test_forward_check_few_steps_any_tolerance(void **state)
{
    (void)state;
    static const double tol[4][2] = {{1e-4, 1e-6}, {1e-8, 1e-10}, {1e-12, 1e-14}, {1e-10, 1e-18}};
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 101));
    for (int k = 0; k < 4; k++) {
        vt_run_options opt = vt_default_run_options();
        opt.rtol = tol[k][0];
        opt.atol = tol[k][1];
        vt_scene_five_link_guess(m, d, 0.0);
        memset(d->qd, 0, 5 * sizeof(double));
        assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
        print_message("five-link forward check, rtol %g atol %g: %ld IDA steps, |q_fwd - q| %.2g rad\n", opt.rtol, opt.atol,
                      tr->steps_fwd, tr->fwd_err_q);
        assert_true(tr->steps_fwd > 0 && tr->steps_fwd <= 60);
        assert_true(tr->fwd_err_q <= 1e-10 && tr->fwd_err_qd <= 1e-9);
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* A spherical joint driven by a relative orientation drive (vt_scene_spherical_chain): the
 * kinematic analysis's Newton from the assembled pose, and the forward check both ways — the
 * generalized forces Φ_q^T λ, and each drive's own load (the relative drive's moment on body 2
 * and its opposite on body 1), which also compares the reactions — reproduce the motion. */
static void test_relative_orientation_forward_check(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_spherical_chain(&m, 1));
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 50;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    for (int as_loads = 0; as_loads < 2; as_loads++) {
        opt.forward_as_loads = as_loads;
        assert_ok(vt_data_reset(m, d));
        assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
        assert_int_equal(tr->nfilled, opt.nout + 1);
        for (int k = 0; k < tr->nfilled; k++) assert_near(tr->phi_norm[k], 0.0, 1e-12);
        print_message("relative orientation drive, forward check (as_loads %d): |q| %.2g, |q̇| %.2g, "
                      "reaction force %.2g N, moment %.2g N·m\n", as_loads, tr->fwd_err_q, tr->fwd_err_qd,
                      tr->fwd_err_force, tr->fwd_err_moment);
        assert_true(tr->fwd_err_q < 1e-10 && tr->fwd_err_q > 0.0);
        assert_true(tr->fwd_err_qd < 1e-9);
        if (as_loads) assert_true(tr->fwd_err_force < 1e-9 && tr->fwd_err_moment < 1e-9);
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}
#else
/* a build without IDA (-Dsundials=disabled): the forward check is off by default and refused
 * when asked for; the analysis itself still puts the tip on its circle */
static void test_no_forward_check_without_sundials(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d, *dt;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dt, m));
    vt_run_options opt = vt_default_run_options();
    assert_int_equal(opt.forward_check, 0);
    opt.nout = 20;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    vt_scene_five_link_guess(m, d, 0.0);
    opt.forward_check = 1;
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(d->message, "SUNDIALS"));
    opt.forward_check = 0;
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, opt.nout + 1);
    for (int k = 0; k < tr->nfilled; k++) {
        const double t = tr->t[k], w = 2.0 * 3.14159265358979323846;
        double p[3];
        tip_of(p, m, dt, tr->q + 5 * k);
        assert_near(p[0], VT_FL_C1 + 0.3 * cos(w * t), 1e-10);
        assert_near(p[1], 0.3 * sin(w * t), 1e-10);
        assert_near(p[2], VT_FL_CE, 1e-10);
    }
    vt_trajectory_free(tr);
    vt_data_free(dt);
    vt_data_free(d);
    vt_model_free(m);
}
#endif

/* largest |a − b| / (1 + |b|) over n entries */
static double rel_diff(const double *a, const double *b, int n)
{
    double e = 0.0;
    for (int k = 0; k < n; k++) e = fmax(e, fabs(a[k] - b[k]) / (1.0 + fabs(b[k])));
    return e;
}

/* every stored output of row k against the data of an instant; the condition estimate, whose
 * round-off is the inverse's, to a hundredth of the tolerance */
static double row_diff(const vt_model *m, const vt_trajectory *tr, int k, const vt_data *d)
{
    const size_t r = (size_t)k;
    const int nb3 = 3 * (m->nbody + 1);
    double e = rel_diff(tr->q + r * (size_t)m->nq, d->q, m->nq);
    e = fmax(e, rel_diff(tr->qd + r * (size_t)m->nv, d->qd, m->nv));
    e = fmax(e, rel_diff(tr->qdd + r * (size_t)m->nv, d->qdd, m->nv));
    e = fmax(e, rel_diff(tr->lambda + r * (size_t)m->nc, d->lambda, m->nc));
    e = fmax(e, rel_diff(tr->qfrc_drive + r * (size_t)m->nv, d->qfrc_drive, m->nv));
    e = fmax(e, rel_diff(tr->drive_effort + r * (size_t)m->ndrive, d->drive_effort, m->ndrive));
    e = fmax(e, rel_diff(tr->drive_force + 3 * r * (size_t)m->ndrive, d->drive_force, 3 * m->ndrive));
    e = fmax(e, rel_diff(tr->drive_moment + 3 * r * (size_t)m->ndrive, d->drive_moment, 3 * m->ndrive));
    e = fmax(e, rel_diff(tr->jnt_force + r * (size_t)nb3, d->jnt_force, nb3));
    e = fmax(e, rel_diff(tr->jnt_moment + r * (size_t)nb3, d->jnt_moment, nb3));
    e = fmax(e, rel_diff(tr->cut_force + 3 * r * (size_t)m->ncut, d->cut_force, 3 * m->ncut));
    e = fmax(e, rel_diff(tr->cut_moment + 3 * r * (size_t)m->ncut, d->cut_moment, 3 * m->ncut));
    return fmax(e, 1e-2 * fabs(tr->rcond[k] - d->rcond) / d->rcond);
}

/* The analysis's rows (Newton from starts extrapolated from the rows before, the recursive
 * instant) against vt_kinematic_solve (the dense instant) from the scene's own start at each
 * time: the five-link arm (revolute joints, point drives) and the RSUR four-bar (a spherical
 * joint's Euler parameters, a cut joint), uniform rows and uneven given times */
static void test_rows_against_dense_instants(void **state)
{
    (void)state;
    for (int scene = 0; scene < 4; scene++) {
        const int fourbar = scene >= 2, uneven = scene % 2;
        const vt_function crank = vt_function_sine(0.3, 1.0, 2.0, 0.0);
        vt_model *m;
        vt_data *d, *di;
        vt_trajectory *tr;
        if (fourbar) assert_ok(vt_scene_fourbar(&m, crank));
        else assert_ok(vt_scene_five_link(&m));
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&di, m));
        vt_run_options opt = vt_default_run_options();
        opt.forward_check = 0;
        opt.newton_tol = 1e-14;
        opt.nout = 40;
        double tout[40];
        for (int k = 0; k < 40; k++) tout[k] = 0.025 * (k + 1) - (k % 3 == 1 ? 0.011 : 0.0);
        if (uneven) {
            opt.tout = tout;
            opt.ntout = 40;
        }
        assert_ok(vt_trajectory_create(&tr, m, 41));
        if (fourbar) assert_int_equal(vt_scene_fourbar_assemble(m, d, 0.3, 2.0, NULL, NULL), 0);
        else vt_scene_five_link_guess(m, d, 0.0);
        assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
        assert_int_equal(tr->nfilled, 41);
        double worst = 0.0;
        for (int k = 0; k <= 40; k++) {
            const double t = tr->t[k];
            double f[3];
            assert_ok(vt_function_eval(f, &crank, t));
            if (fourbar) assert_int_equal(vt_scene_fourbar_assemble(m, di, f[0], f[1], NULL, NULL), 0);
            else vt_scene_five_link_guess(m, di, t);
            di->time = t;
            assert_ok(vt_kinematic_solve(m, di, 1e-14, 30));
            worst = fmax(worst, row_diff(m, tr, k, di));
            assert_true(tr->phi_norm[k] <= 1e-14);
            assert_true(tr->phid_norm[k] <= 1e-12);
        }
        if (!(worst <= 1e-12)) fail_msg("scene %d: rows differ from the dense instants by %.3g", scene, worst);
        vt_trajectory_free(tr);
        vt_data_free(di);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* the scene vt_scene_free_joint_driven: 7 rates, 7 rows */
static vt_model *free_joint_model(void)
{
    vt_model *m;
    assert_ok(vt_scene_free_joint_driven(&m));
    return m;
}

/* The recursive instant of a row takes what Newton's last evaluation left (positions, twists,
 * Φ, Φ_q at the converged q) and computes only the velocities, Ṡq̇, Φ_x and γ (α and the total
 * wrenches, which the rows do not keep, at the last row only): every row after the first (the
 * dense instant) against a fresh vt_inverse_dynamics_recursive at the row's own state, which
 * evaluates everything again, and d after the run against the last row's — the five-link arm (square route), the RSUR four-bar
 * (a cut joint, a spherical joint's Euler parameters), the free joint's 7 rows, and the planar
 * four-bar with dependent rows (the factorized route) */
static void test_rows_equal_fresh_recursive_instants(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5};
    const vt_function crank = vt_function_polynomial(3, coef);
    for (int scene = 0; scene < 4; scene++) {
        vt_model *m;
        vt_data *d, *di;
        vt_trajectory *tr;
        if (scene == 0) assert_ok(vt_scene_five_link(&m));
        else if (scene == 1) assert_ok(vt_scene_fourbar(&m, crank));
        else if (scene == 2) m = free_joint_model();
        else assert_ok(vt_scene_fourbar_planar(&m, crank, 1));
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&di, m));
        vt_run_options opt = vt_default_run_options();
        opt.forward_check = 0;
        opt.nout = 30;
        assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
        if (scene == 0) vt_scene_five_link_guess(m, d, 0.0);
        else if (scene == 1) assert_int_equal(vt_scene_fourbar_assemble(m, d, coef[0], coef[1], NULL, NULL), 0);
        else if (scene == 3) assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, coef[0], coef[1]), 0);
        const vt_status st = vt_kinematic_analysis(m, d, &opt, tr);
        if (st) fail_msg("scene %d: %s", scene, d->message);
        double worst = 0.0, worst_phi = 0.0;
        for (int k = 1; k <= opt.nout; k++) {
            memcpy(di->q, tr->q + (size_t)k * (size_t)m->nq, (size_t)m->nq * sizeof(double));
            memcpy(di->qd, tr->qd + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
            di->time = tr->t[k];
            assert_ok(vt_inverse_dynamics_recursive(m, di));
            worst = fmax(worst, row_diff(m, tr, k, di));
            double pn = 0.0;
            for (int r = 0; r < m->nc; r++) pn = fmax(pn, fabs(di->Phi[r]));
            worst_phi = fmax(worst_phi, fabs(tr->phi_norm[k] - pn));
        }
        /* d holds the last row's whole instant, α and the joints' total wrenches too */
        const int nb3 = 3 * (m->nbody + 1);
        worst = fmax(worst, rel_diff(d->alpha, di->alpha, nb3));
        worst = fmax(worst, rel_diff(d->jnt_force_total, di->jnt_force_total, nb3));
        worst = fmax(worst, rel_diff(d->jnt_moment_total, di->jnt_moment_total, nb3));
        worst = fmax(worst, rel_diff(d->jnt_moment_total_body, di->jnt_moment_total_body, nb3));
        if (!(worst <= 4.0 * DBL_EPSILON && worst_phi <= 4.0 * DBL_EPSILON))
            fail_msg("scene %d: rows differ from fresh recursive instants by %.3g (max |Φ| by %.3g)", scene, worst,
                     worst_phi);
        vt_trajectory_free(tr);
        vt_data_free(di);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* The free joint's rows (its rotation's rates extrapolated by their cubic q̇) against
 * vt_kinematic_solve's dense instant started from the row before, as the analysis used to */
static void test_free_joint_rows_against_dense_instants(void **state)
{
    (void)state;
    vt_model *m = free_joint_model();
    vt_data *d, *di;
    vt_trajectory *tr;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&di, m));
    vt_run_options opt = vt_default_run_options();
    opt.forward_check = 0;
    opt.newton_tol = 1e-14;
    opt.t1 = 2.0;
    opt.nout = 50;
    assert_ok(vt_trajectory_create(&tr, m, 51));
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    double worst = 0.0;
    for (int k = 1; k <= 50; k++) {
        memcpy(di->q, tr->q + (size_t)(k - 1) * (size_t)m->nq, (size_t)m->nq * sizeof(double));
        memcpy(di->qd, tr->qd + (size_t)(k - 1) * (size_t)m->nv, (size_t)m->nv * sizeof(double));
        di->time = tr->t[k];
        assert_ok(vt_kinematic_solve(m, di, 1e-14, 30));
        worst = fmax(worst, row_diff(m, tr, k, di));
    }
    if (!(worst <= 1e-12)) fail_msg("rows differ from the dense instants by %.3g", worst);
    vt_trajectory_free(tr);
    vt_data_free(di);
    vt_data_free(d);
    vt_model_free(m);
}

#if VT_HAVE_SUNDIALS
/* The forward check of the free joint (Euler parameters integrated on the sphere, the exact
 * efforts' Newton started from the rows interpolated by the rotation's cubic q̇): the undriven
 * run under the drives' own loads reproduces the rows' motion and their reactions */
static void test_free_joint_forward_check(void **state)
{
    (void)state;
    vt_model *m = free_joint_model();
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 50;
    opt.forward_as_loads = 1;
    assert_ok(vt_trajectory_create(&tr, m, 51));
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_true(tr->steps_fwd > 0);
    if (!(tr->fwd_err_q <= 1e-10 && tr->fwd_err_q > 0.0 && tr->fwd_err_qd <= 1e-9 && tr->fwd_err_force <= 1e-9 &&
          tr->fwd_err_moment <= 1e-9))
        fail_msg("forward check off: |q| %.3g, |q'| %.3g, reactions %.3g N, %.3g N m", tr->fwd_err_q, tr->fwd_err_qd,
                 tr->fwd_err_force, tr->fwd_err_moment);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}
#endif

/* From the predicted starts one Newton step reaches 1e-10 at every row of the five-link arm
 * (from the previous row itself it takes two or three) */
static void test_one_newton_step_a_row(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d, *dt;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dt, m));
    vt_run_options opt = vt_default_run_options();
    opt.forward_check = 0;
    opt.newton_tol = 1e-10;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    vt_scene_five_link_guess(m, d, 0.0);
    assert_ok(vt_kinematic_solve(m, d, 1e-14, 30)); /* row 0 exact: the count is about the rows after */
    opt.newton_maxit = 1;
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, opt.nout + 1);
    for (int k = 0; k < tr->nfilled; k++) {
        const double t = tr->t[k], w = 2.0 * 3.14159265358979323846;
        double p[3];
        tip_of(p, m, dt, tr->q + 5 * k);
        assert_near(p[0], VT_FL_C1 + 0.3 * cos(w * t), 1e-10);
        assert_near(p[1], 0.3 * sin(w * t), 1e-10);
        assert_near(p[2], VT_FL_CE, 1e-10);
    }
    vt_trajectory_free(tr);
    vt_data_free(dt);
    vt_data_free(d);
    vt_model_free(m);
}

static int stop_now(double t, double t_end, void *user)
{
    (void)t_end;
    *(double *)user = t;
    return t > 0.25;
}

static void test_failures(void **state)
{
    (void)state;
    vt_model *m, *dl;
    vt_data *d, *dd;
    vt_trajectory *tr, *trd;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 11));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 10;
    opt.forward_check = 0;

    /* Newton from a poor start with one iteration: the residual is reported, q restored */
    vt_scene_five_link_guess(m, d, 0.0);
    for (int k = 0; k < m->nq; k++) d->q[k] += 0.2;
    double q0[5];
    memcpy(q0, d->q, sizeof q0);
    assert_int_equal(vt_kinematic_solve(m, d, 1e-12, 1), VT_ERR_NEWTON);
    assert_non_null(strstr(d->message, "max |Φ|"));
    assert_memory_equal(q0, d->q, sizeof q0);

    /* the progress callback stops the run */
    double when = 0.0;
    opt.progress = stop_now;
    opt.user = &when;
    vt_scene_five_link_guess(m, d, 0.0);
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_ABORTED);
    assert_near(when, 0.3, 1e-12);
    opt.progress = NULL;

    /* bad options */
    opt.nout = 11; /* needs 12 rows */
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    opt.nout = 10;
    opt.t1 = opt.t0;
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    opt.t1 = 1.0;
    opt.newton_tol = 0.0;
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    opt.newton_tol = 1e-12;

    /* a partly driven model is refused */
    assert_ok(vt_scene_double_link(&dl, 1));
    assert_ok(vt_data_create(&dd, dl));
    assert_ok(vt_trajectory_create(&trd, dl, 11));
    assert_int_equal(vt_kinematic_analysis(dl, dd, &opt, trd), VT_ERR_NOT_FULLY_DRIVEN);
    /* a trajectory of another model is refused */
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, trd), VT_ERR_MODEL_MISMATCH);
    vt_trajectory_free(trd);
    vt_data_free(dd);
    vt_model_free(dl);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* Two 1 m links, the tip driven along x toward and past the reach (2 m, at t = 1): the drives
 * stop fixing the motion. The condition estimate falls, the solve warns before the stretched
 * pose, and the analysis stops with a clear status there instead of returning huge efforts. */
static void test_stretched_arm(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_test_add_rods(b, 2, 1.0, (const double[2]){1.0, 1.0});
    vt_drive_def tip = vt_default_drive_def();
    tip.type = VT_DRIVE_POINT;
    tip.body = 2;
    tip.point[0] = 0.5;
    const double cx[2] = {1.2, 0.8};
    tip.f = vt_function_polynomial(2, cx); /* x = 1.2 + 0.8 t */
    assert_int_equal(vt_builder_add_drive(b, &tip), 0);
    tip.index = 1;
    tip.f = vt_function_constant(0.0);
    assert_int_equal(vt_builder_add_drive(b, &tip), 1);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.2;
    opt.nout = 120;
    opt.forward_check = 0;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    d->q[0] = -0.9; /* elbow bent: q1 = −acos(0.6), q2 = 2 acos(0.6) */
    d->q[1] = 1.8;
    const vt_status st = vt_kinematic_analysis(m, d, &opt, tr);
    /* a clear failure at the stretched pose (t = 1), not huge efforts */
    assert_int_equal(st, VT_ERR_SINGULAR);
    assert_non_null(strstr(d->message, "rcond"));
    assert_int_equal(tr->nfilled, 100); /* rows up to t = 0.99 */
    for (int k = 1; k < tr->nfilled; k++) assert_true(tr->rcond[k] < tr->rcond[k - 1]); /* falling */
    /* toward it, t = 1 − 10^-k: the estimate falls like the distance, the efforts grow like its
     * inverse square root, and the solve warns once the estimate passes rcond_warn */
    double q0[2] = {tr->q[2 * 99], tr->q[2 * 99 + 1]}, last = 1.0;
    int warned_at = 0;
    for (int k = 2; k <= 9; k++) {
        d->q[0] = q0[0];
        d->q[1] = q0[1];
        d->time = 1.0 - pow(10.0, -k);
        assert_ok(vt_kinematic_solve(m, d, 1e-14, 50));
        assert_true(d->rcond < last);
        last = d->rcond;
        if ((d->warning & VT_WARN_ILL_CONDITIONED) && !warned_at) warned_at = k;
        assert_int_equal((d->warning & VT_WARN_ILL_CONDITIONED) != 0, d->rcond < 1e-6);
        assert_true(isfinite(d->drive_effort[0]));
    }
    assert_true(warned_at >= 3 && warned_at <= 8);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

#if VT_HAVE_SUNDIALS
/* rows at irregular given times: each the kinematic solution at its time, solved independently
 * from the scene's guess at that time; and the forward check over them */
static void test_given_output_times(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d, *di;
    vt_trajectory *tr;
    assert_ok(vt_scene_five_link(&m));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&di, m));
    const double tout[7] = {0.0137, 0.05, 0.051, 0.3, 0.62, 0.9, 0.97};
    vt_run_options opt = vt_default_run_options();
    opt.tout = tout;
    opt.ntout = 7;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    assert_ok(vt_trajectory_create(&tr, m, 8));
    vt_scene_five_link_guess(m, d, 0.0);
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, 8);
    assert_true(tr->t[0] == 0.0);
    for (int k = 1; k <= 7; k++) {
        assert_true(tr->t[k] == tout[k - 1]);
        vt_scene_five_link_guess(m, di, tout[k - 1]);
        di->time = tout[k - 1];
        assert_ok(vt_kinematic_solve(m, di, 1e-12, 30));
        for (int c = 0; c < m->nq; c++) assert_near(tr->q[m->nq * k + c], di->q[c], 1e-10);
        for (int c = 0; c < m->nv; c++) assert_near(tr->qd[m->nv * k + c], di->qd[c], 1e-9);
        for (int c = 0; c < m->ndrive; c++)
            assert_near(tr->drive_effort[m->ndrive * k + c], di->drive_effort[c], 1e-8 * (1 + fabs(di->drive_effort[c])));
    }
    assert_true(tr->fwd_err_q < 1e-10 && tr->fwd_err_q > 0.0); /* the forward check ran to the last time */
    vt_trajectory_free(tr);
    vt_data_free(di);
    vt_data_free(d);
    vt_model_free(m);
}
#endif

/* a 2 kg, 1 m rod pinned at one end, its joint driven by f */
static vt_model *pendulum(const vt_function *f)
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def rod = vt_default_body_def();
    rod.mass = 2.0;
    rod.inertia[4] = rod.inertia[8] = 2.0 / 12.0;
    rod.joint_child[0] = -0.5;
    assert_int_equal(vt_builder_add_body(b, &rod), 1);
    vt_drive_def dr = vt_default_drive_def();
    dr.f = *f;
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* the largest differences of effort and joint force between the analysis driven by the spline
 * through n samples of θ = 0.3 sin 2t on [0, 2] and the one driven by the sine itself */
static double spline_effort_error(int n, const vt_trajectory *exact)
{
    double *tk = malloc(2 * (size_t)n * sizeof(double)), *yk = tk + n;
    assert_non_null(tk);
    for (int k = 0; k < n; k++) {
        tk[k] = 2.0 * k / (n - 1);
        yk[k] = 0.3 * sin(2.0 * tk[k]);
    }
    const vt_function f = vt_function_spline(n, tk, yk);
    vt_model *m = pendulum(&f);
    free(tk);
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 41));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 40;
    opt.forward_check = 0;
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    double e = 0.0;
    for (int r = 0; r <= 40; r++) {
        e = fmax(e, fabs(tr->drive_effort[r] - exact->drive_effort[r]));
        for (int c = 0; c < 3; c++) e = fmax(e, fabs(tr->jnt_force[6 * r + 3 + c] - exact->jnt_force[6 * r + 3 + c]));
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
    return e;
}

/* efforts converge to the exact ones as the samples get denser: as f'', O(h²) */
static void test_spline_drive_converges(void **state)
{
    (void)state;
    const vt_function sine = vt_function_sine(0.0, 0.3, 2.0, 0.0);
    vt_model *m = pendulum(&sine);
    vt_data *d;
    vt_trajectory *exact;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&exact, m, 41));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 40;
    opt.forward_check = 0;
    assert_ok(vt_kinematic_analysis(m, d, &opt, exact));
    /* errors 0.063, 0.021, 0.0057, 0.0015, 0.00038 N for 10 .. 160 intervals: ratios 3.0, 3.6,
     * 3.8, 3.9 toward 4 */
    double prev = spline_effort_error(21, exact);
    assert_true(prev < 0.05 && prev > 1e-6); /* N·m and N, beside efforts of order 10 */
    for (int n = 41; n <= 161; n = 2 * n - 1) {
        const double e = spline_effort_error(n, exact);
        if (!(prev / e > 3.4 && prev / e < 4.6)) fail_msg("n %d: error %.3g, ratio %.3g (expected 4)", n, e, prev / e);
        prev = e;
    }
    assert_true(prev < 5e-4);
    vt_trajectory_free(exact);
    vt_data_free(d);
    vt_model_free(m);
}

/* The same four-bar closed by a planar pin (3 independent rows for 3 rates, no allow_redundant):
 * a kinematic analysis's every row equals the closed-form assembly, its crank torque the RSUR
 * model's at the same state; the forward check runs in the default (GGL) formulation, whose IDA
 * Jacobian the redundant model's dependent rows make singular, and reproduces the motion and
 * the reactions. */
static void test_planar_pin_over_time(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5};
    const vt_function crank = vt_function_polynomial(3, coef);
    vt_model *m, *rsur;
    assert_ok(vt_scene_fourbar_pin(&m, crank));
    assert_ok(vt_scene_fourbar(&rsur, crank));
    vt_data *d, *dx, *du;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dx, m));
    assert_ok(vt_data_create(&du, rsur));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.0;
    opt.nout = 10;
#if !VT_HAVE_SUNDIALS
    opt.forward_check = 0;
#endif
    vt_trajectory *tr;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, coef[0], coef[1]), 0);
    const vt_status st = vt_kinematic_analysis(m, d, &opt, tr);
    if (st) fail_msg("%s", d->message);
    assert_int_equal(tr->nfilled, opt.nout + 1);
    for (int k = 0; k <= opt.nout; k++) {
        const double t = tr->t[k], th2 = coef[0] + coef[1] * t + coef[2] * t * t, w2 = coef[1] + 2 * coef[2] * t;
        assert_int_equal(vt_scene_fourbar_planar_assemble(m, dx, th2, w2), 0);
        for (int c = 0; c < 3; c++) {
            assert_near(tr->q[3 * k + c], dx->q[c], 1e-10);
            assert_near(tr->qd[3 * k + c], dx->qd[c], 1e-9);
        }
        assert_int_equal(vt_scene_fourbar_assemble(rsur, du, th2, w2, NULL, NULL), 0);
        du->time = t;
        assert_ok(vt_inverse_dynamics(rsur, du));
        assert_near(tr->drive_effort[k], du->drive_effort[0], 1e-8 * (1 + fabs(du->drive_effort[0])));
    }
#if VT_HAVE_SUNDIALS
    assert_true(tr->fwd_err_q < 1e-10); /* the exact efforts: a deviation of round-off */
    assert_true(tr->fwd_err_force < 1e-9 * (1 + vt_test_maxabs(tr->jnt_force, 3 * 4 * (opt.nout + 1))));
    print_message("planar pin four-bar, forward check: |q| %.2e rad, reactions %.2e N\n", tr->fwd_err_q, tr->fwd_err_force);
#endif
    vt_trajectory_free(tr);
    vt_data_free(du);
    vt_data_free(dx);
    vt_data_free(d);
    vt_model_free(rsur);
    vt_model_free(m);
}

/* A fully driven model with dependent rows: the planar four-bar closed by a spatial revolute
 * cut joint, its crank driven (6 rows of rank 3 for 3 rates). Built without allow_redundant it
 * is refused as having dependent rows, with the advice to allow them (not as "not fully
 * driven"); built with it, every row is the closed-form assembly of the four-bar at the crank's
 * angle (positions and rates, vt_scene_fourbar_planar_assemble) and its crank torque that of the
 * exactly constrained RSUR model of the same mechanism at the same state. Without the crank's
 * drive (the N-four-bar: 10 rows of rank 4 for 5 rates) the rank says not fully driven. */
static void test_redundant_fully_driven(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5};
    const vt_function crank = vt_function_polynomial(3, coef);
    vt_model *strict, *red, *rsur, *nfb;
    assert_ok(vt_scene_fourbar_planar(&strict, crank, 0));
    assert_ok(vt_scene_fourbar_planar(&red, crank, 1));
    assert_ok(vt_scene_fourbar(&rsur, crank));
    assert_int_equal(red->nc, 6);
    assert_int_equal(red->nv, 3);
    vt_data *ds, *dr, *du;
    assert_ok(vt_data_create(&ds, strict));
    assert_ok(vt_data_create(&dr, red));
    assert_ok(vt_data_create(&du, rsur));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.0;
    opt.nout = 10;
    opt.forward_check = 0;
    vt_trajectory *trs, *tr;
    assert_ok(vt_trajectory_create(&trs, strict, opt.nout + 1));
    assert_ok(vt_trajectory_create(&tr, red, opt.nout + 1));
    assert_int_equal(vt_scene_fourbar_planar_assemble(strict, ds, coef[0], coef[1]), 0);
    const double t_before = ds->time;
    assert_int_equal(vt_kinematic_analysis(strict, ds, &opt, trs), VT_ERR_DEPENDENT_CONSTRAINTS);
    assert_non_null(strstr(ds->message, "rank 3"));
    assert_non_null(strstr(ds->message, "allow_redundant"));
    assert_true(ds->time == t_before);

    assert_int_equal(vt_scene_fourbar_planar_assemble(red, dr, coef[0], coef[1]), 0);
    const vt_status st = vt_kinematic_analysis(red, dr, &opt, tr);
    if (st) fail_msg("%s", dr->message);
    assert_int_equal(tr->nfilled, opt.nout + 1);
    vt_data *dx; /* the closed form */
    assert_ok(vt_data_create(&dx, red));
    for (int k = 0; k <= opt.nout; k++) {
        const double t = tr->t[k], th2 = coef[0] + coef[1] * t + coef[2] * t * t, w2 = coef[1] + 2 * coef[2] * t;
        assert_int_equal(vt_scene_fourbar_planar_assemble(red, dx, th2, w2), 0);
        for (int c = 0; c < 3; c++) {
            assert_near(tr->q[3 * k + c], dx->q[c], 1e-10);
            assert_near(tr->qd[3 * k + c], dx->qd[c], 1e-9);
        }
        assert_int_equal(vt_scene_fourbar_assemble(rsur, du, th2, w2, NULL, NULL), 0);
        du->time = t;
        assert_ok(vt_inverse_dynamics(rsur, du));
        assert_near(tr->drive_effort[k], du->drive_effort[0], 1e-8 * (1 + fabs(du->drive_effort[0])));
    }
    vt_data_free(dx);
#if VT_HAVE_SUNDIALS
    /* the forward check: the model without its drive keeps the dependent cut rows, which the
     * ODE formulation's solve takes (the DAE forms' IDA Jacobian is singular with them) */
    opt.forward_check = 1;
    opt.formulation = VT_FORMULATION_ODE;
    assert_int_equal(vt_scene_fourbar_planar_assemble(red, dr, coef[0], coef[1]), 0);
    assert_ok(vt_kinematic_analysis(red, dr, &opt, tr));
    assert_true(tr->fwd_err_q < 1e-10);
    opt.forward_check = 0;
#endif

    assert_ok(vt_scene_nfourbar(&nfb, 2));
    assert_true(nfb->nc > nfb->nv);
    vt_data *dn;
    vt_trajectory *trn;
    assert_ok(vt_data_create(&dn, nfb));
    assert_ok(vt_trajectory_create(&trn, nfb, opt.nout + 1));
    vt_scene_nfourbar_start(nfb, dn, 2, 1.0);
    assert_int_equal(vt_kinematic_analysis(nfb, dn, &opt, trn), VT_ERR_NOT_FULLY_DRIVEN);
    assert_non_null(strstr(dn->message, "rank 4"));
    vt_trajectory_free(trn);
    vt_data_free(dn);
    vt_model_free(nfb);
    vt_trajectory_free(trs);
    vt_trajectory_free(tr);
    vt_data_free(ds);
    vt_data_free(dr);
    vt_data_free(du);
    vt_model_free(strict);
    vt_model_free(red);
    vt_model_free(rsur);
}

/* Wrenches at frames over a run (vt_run_options.loads): the Delta driven at its motors by the
 * path's inverse kinematics (vt_scene_delta_ik), its gripper's tip (frame "tool") pressed by a
 * force and a moment that change with time. Each row's motor torques equal the batch's on the
 * row's state with the same wrench (vt_batch_io.load: the dense stages of the motion given,
 * another route than the rows' recursive one) to 1e-9 of the largest; they differ from the
 * unloaded run's; the forward check (the drives removed, the loaded torques and the wrenches
 * applied) follows the path to 1e-10 m. A callback that fails at t = 0.5 ends the run there
 * with VT_ERR_CALLBACK (the rows before it kept), one that returns NaN with VT_ERR_NONFINITE;
 * bad frames and counts are refused, and so is a dynamic analysis with loads; xfrc is the
 * caller's after every run. */
typedef struct {
    double t_fail;
    int nan;
} tool_press;

static int tool_wrench(double t, double *w, void *user)
{
    const tool_press *p = user;
    if (t >= p->t_fail && !p->nan) return 1;
    const double s = sin(2.0 * 3.14159265358979323846 * t), c = cos(2.0 * 3.14159265358979323846 * t);
    w[0] = 5.0 * s, w[1] = -3.0, w[2] = t >= p->t_fail ? NAN : -40.0 - 20.0 * c;
    w[3] = 0.5 * s, w[4] = -0.2 * s, w[5] = 1.0 * s;
    return 0;
}

static void test_loads_at_frames(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_delta_ik ik;
    assert_ok(vt_scene_delta_ik(&m, &ik, 1.0));
    assert_ok(vt_data_create(&d, m));
    const int tool[1] = {vt_find_frame(m, "tool")};
    assert_true(tool[0] >= 0);
    vt_run_options opt = vt_default_run_options();
    opt.nout = 50;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    vt_trajectory *bare, *tr;
    assert_ok(vt_trajectory_create(&bare, m, 51));
    assert_ok(vt_trajectory_create(&tr, m, 51));
    double p0[3];
    vt_scene_delta_path(0.0, 1.0, p0, NULL, NULL);
    assert_int_equal(vt_scene_delta_assemble(m, d, p0), 0);
    opt.forward_check = 0;
    assert_ok(vt_kinematic_analysis(m, d, &opt, bare));
    tool_press press = {HUGE_VAL, 0};
    opt.nload = 1, opt.load_frame = tool, opt.loads = tool_wrench, opt.load_user = &press;
    opt.forward_check = VT_HAVE_SUNDIALS;
    assert_int_equal(vt_scene_delta_assemble(m, d, p0), 0);
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, 51);
    for (int k = 0; k < 6 * (m->nbody + 1); k++) assert_true(d->xfrc[k] == 0.0);
    /* the batch on every row's state, each with the row's wrench */
    const int n = tr->nfilled;
    double *w = malloc(6 * (size_t)n * sizeof(double)), *de = malloc(3 * (size_t)n * sizeof(double));
    int *st = malloc((size_t)n * sizeof(int));
    assert_non_null(w);
    assert_non_null(de);
    assert_non_null(st);
    for (int k = 0; k < n; k++) assert_int_equal(tool_wrench(tr->t[k], w + 6 * k, &press), 0);
    vt_batch *b = NULL;
    vt_batch_def bd = vt_default_batch_def();
    bd.threads = 1;
    assert_ok(vt_batch_create(&b, m, &bd));
    vt_batch_io io = {0};
    io.nrow = n, io.q = tr->q, io.qd = tr->qd, io.qdd = tr->qdd, io.time = tr->t;
    io.nload = 1, io.load_frame = tool, io.load = w, io.drive_effort = de, io.status = st;
    assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
    vt_batch_free(b);
    double tau_max = 0.0, diff = 0.0, moved = 0.0;
    for (int k = 0; k < n * 3; k++) tau_max = fmax(tau_max, fabs(de[k]));
    for (int k = 0; k < n * 3; k++) {
        diff = fmax(diff, fabs(tr->drive_effort[k] - de[k]));
        moved = fmax(moved, fabs(tr->drive_effort[k] - bare->drive_effort[k]));
    }
    print_message("delta with a tool force over the run: motor torques against the batch's %.3g of %.4g N m; "
                  "the force moves them by up to %.3g N m\n", diff, tau_max, moved);
    assert_true(diff <= 1e-9 * tau_max && moved > 1.0);
#if VT_HAVE_SUNDIALS
    const int pq = m->body_qadr[10];
    double dev = 0.0;
    for (int k = 0; k < n; k++) {
        const double *q = tr->q + (size_t)k * (size_t)m->nq, *qf = tr->q_fwd + (size_t)k * (size_t)m->nq;
        double e = 0.0;
        for (int c = 0; c < 3; c++) e += (qf[pq + c] - q[pq + c]) * (qf[pq + c] - q[pq + c]);
        dev = fmax(dev, sqrt(e));
    }
    print_message("  forward check under the loaded torques and the tool's wrench: platform %.3g m\n", dev);
    assert_true(dev <= 1e-10 && dev > 0.0);
#endif
    /* a callback that fails, or returns NaN, at t = 0.5: the run ends there */
    opt.forward_check = 0;
    for (int nan = 0; nan < 2; nan++) {
        press.t_fail = 0.5, press.nan = nan;
        assert_int_equal(vt_scene_delta_assemble(m, d, p0), 0);
        assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), nan ? VT_ERR_NONFINITE : VT_ERR_CALLBACK);
        assert_non_null(strstr(d->message, "t = 0.5"));
        assert_int_equal(tr->nfilled, 25);
        for (int k = 0; k < 6 * (m->nbody + 1); k++) assert_true(d->xfrc[k] == 0.0);
    }
    press.t_fail = HUGE_VAL;
    const int bad_frame[1] = {m->nframe}, many = VT_RUN_LOADS_MAX + 1;
    opt.load_frame = bad_frame;
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_INDEX);
    opt.load_frame = NULL;
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_NULL);
    opt.load_frame = tool, opt.nload = many;
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    opt.nload = 1;
#if VT_HAVE_SUNDIALS
    assert_int_equal(vt_dynamic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(d->message, "loads at frames"));
#endif
    free(w);
    free(de);
    free(st);
    vt_trajectory_free(tr);
    vt_trajectory_free(bare);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
#if VT_HAVE_SUNDIALS
        cmocka_unit_test(test_five_link_circle_and_forward_check),
        cmocka_unit_test(test_forward_check_few_steps_any_tolerance),
        cmocka_unit_test(test_forward_check_with_loads),
        cmocka_unit_test(test_relative_orientation_forward_check),
        cmocka_unit_test(test_free_joint_forward_check),
#else
        cmocka_unit_test(test_no_forward_check_without_sundials),
#endif
        cmocka_unit_test(test_rows_against_dense_instants),
        cmocka_unit_test(test_free_joint_rows_against_dense_instants),
        cmocka_unit_test(test_rows_equal_fresh_recursive_instants),
        cmocka_unit_test(test_one_newton_step_a_row),
        cmocka_unit_test(test_failures),
        cmocka_unit_test(test_stretched_arm),
        cmocka_unit_test(test_spline_drive_converges),
        cmocka_unit_test(test_redundant_fully_driven),
        cmocka_unit_test(test_planar_pin_over_time),
        cmocka_unit_test(test_loads_at_frames),
#if VT_HAVE_SUNDIALS
        cmocka_unit_test(test_given_output_times),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
