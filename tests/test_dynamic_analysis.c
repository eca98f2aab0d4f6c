/* src/dynamic_analysis.c: the dynamic analysis and its forward check against the paper's exact
 * double link (29) and its first integral; a free four-bar (cut joint, spherical joint)
 * against energy conservation; IDA's failures reaching the caller with IDA's own code. */
#include <ida/ida.h>

#include "vt_test.h"

static void tip(double out[2], const vt_model *m, vt_data *d, const double *q)
{
    memcpy(d->q, q, (size_t)m->nq * sizeof(double));
    assert_ok(vt_kinematics(m, d));
    out[0] = d->x[7] + d->A[18];
    out[1] = d->x[8] + d->A[19];
}

static void test_double_link(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d, *dt;
    vt_trajectory *tr;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dt, m));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.9;
    opt.nout = 190;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.max_step = 0.005;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, 191);
    double dev = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double th = -tr->q[2 * k], thd = -tr->qd[2 * k], s = sin(th), c = cos(th);
        const double *f1 = tr->jnt_force + 9 * k + 3;
        assert_near(f1[0], -2207.25 * sin(2 * th), 1e-8 * 1962.0);
        assert_near(f1[1], 4905.0 * s * s + 490.5 * c * c, 1e-8 * 1962.0);
        assert_near(thd * thd, 7.3575 * s, 1e-8);               /* the first integral */
        assert_near(-tr->qdd[2 * k], 3.67875 * c, 1e-8);
        assert_near(fabs(tr->drive_effort[k]), 245.25 * fabs(c), 1e-8 * 245.25);
        double p[2], pf[2];
        tip(p, m, dt, tr->q + 2 * k);
        tip(pf, m, dt, tr->q_fwd + 2 * k);
        dev = fmax(dev, hypot(pf[0] - p[0], pf[1] - p[1]));
        /* the forward run's reactions: joint 2's torque applied, the same reactions */
        for (int e = 0; e < 9; e++) assert_near(tr->jnt_force_fwd[9 * k + e], tr->jnt_force[9 * k + e], 1e-8 * 1962.0);
    }
    assert_true(dev <= 1e-7);
    assert_true(dev > 0.0); /* an independent integration, not a copy of the driven run */
    assert_true(tr->fwd_interp_err < 1e-8); /* the stated error of the interpolated state */
    assert_near(-tr->q[2 * 190], 3.1395, 1e-3); /* it swings through the bottom, nearly to the far side */
    assert_true(tr->steps > 0 && tr->res_evals >= tr->steps);
    vt_trajectory_free(tr);
    vt_data_free(dt);
    vt_data_free(d);
    vt_model_free(m);
}

/* a four-bar swinging freely under gravity: T + V is conserved, the loop stays closed */
static void test_free_fourbar(void **state)
{
    (void)state;
    vt_model *driven, *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_fourbar(&driven, vt_function_constant(0.0)));
    assert_ok(vt_model_without_drives(&m, driven));
    assert_int_equal(m->ndrive, 0);
    assert_int_equal(m->nc, 4);
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_scene_fourbar_assemble(m, d, 0.6, 1.0, NULL, NULL), 0);
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 40;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
    double E0 = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double E = vt_test_row_energy(m, d, tr, k);
        if (k == 0) E0 = E;
        assert_near(E, E0, 1e-6 * (1 + fabs(E0)));
        assert_true(tr->phi_norm[k] < 1e-7);
        assert_true(tr->phid_norm[k] < 1e-7);
    }
    /* it moved: the crank turned */
    assert_true(fabs(tr->q[(size_t)40 * (size_t)m->nq] - tr->q[0]) > 0.1);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
    vt_model_free(driven);
}

/* the free four-bar for 20 s at rtol 1e-6: the stabilized formulations hold the constraints,
 * the plain index-1 form drifts; the default (GGL) keeps ‖Φ‖ ≤ 1e-5 and ‖Φ̇‖ ≤ 1e-4 */
static void test_formulations_drift(void **state)
{
    (void)state;
    vt_model *driven, *m;
    assert_ok(vt_scene_fourbar(&driven, vt_function_constant(0.0)));
    assert_ok(vt_model_without_drives(&m, driven));
    const double bound_phi[VT_FORMULATION_COUNT] = {1.0, 1e-4, 1e-11, 1e-5, 1e-4};
    const double bound_phid[VT_FORMULATION_COUNT] = {1.0, 1e-3, 1e-12, 1e-4, 1e-3};
    double worst[VT_FORMULATION_COUNT];
    for (int form = 0; form < VT_FORMULATION_COUNT; form++) {
        vt_data *d;
        vt_trajectory *tr;
        assert_ok(vt_data_create(&d, m));
        assert_int_equal(vt_scene_fourbar_assemble(m, d, 0.3, 12.0, NULL, NULL), 0);
        vt_run_options opt = vt_default_run_options();
        if (form == VT_FORMULATION_GGL) assert_int_equal(opt.formulation, VT_FORMULATION_GGL); /* the default */
        opt.formulation = form;
        opt.t1 = 20.0;
        opt.nout = 40;
        opt.rtol = 1e-6;
        opt.atol = 1e-8;
        opt.forward_check = 0;
        assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
        assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
        double pm = 0.0, pdm = 0.0;
        for (int k = 0; k < tr->nfilled; k++) {
            pm = fmax(pm, tr->phi_norm[k]);
            pdm = fmax(pdm, tr->phid_norm[k]);
        }
        if (!(pm <= bound_phi[form] && pdm <= bound_phid[form]))
            fail_msg("formulation %d: max |Φ| %.3g, max |Φ̇| %.3g", form, pm, pdm);
        worst[form] = pm;
        vt_trajectory_free(tr);
        vt_data_free(d);
    }
    /* stabilization matters: index-1 drifts by orders of magnitude more */
    assert_true(worst[VT_FORMULATION_INDEX1] > 100.0 * worst[VT_FORMULATION_GGL]);
    assert_true(worst[VT_FORMULATION_INDEX1] > 100.0 * worst[VT_FORMULATION_BAUMGARTE]);
    vt_model_free(m);
    vt_model_free(driven);
}

/* IFToMM A02, the N-four-bar, with the ODE formulation and the rank-revealing solve: through
 * its first singular (horizontal) pose, energy conserved and the loops closed. (Past the
 * second one, at a full crank turn, IDA's corrector fails: see the README.) */
static void test_nfourbar_through_singular_pose(void **state)
{
    (void)state;
    const int Ns[2] = {2, 5};
    for (int t = 0; t < 2; t++) {
        const int N = Ns[t];
        vt_model *m;
        vt_data *d;
        vt_trajectory *tr;
        assert_ok(vt_scene_nfourbar(&m, N));
        assert_int_equal(m->nc, 5 * N);
        assert_ok(vt_data_create(&d, m));
        vt_scene_nfourbar_start(m, d, N, 1.0);
        vt_run_options opt = vt_default_run_options();
        opt.formulation = VT_FORMULATION_ODE;
        opt.t1 = 2.5;
        opt.nout = 125;
        opt.rtol = 1e-8;
        opt.atol = 1e-10;
        opt.forward_check = 0;
        assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
        assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
        assert_int_equal(tr->nfilled, opt.nout + 1);
        double E0 = 0.0, phimax = 0.0, phidmax = 0.0, dEmax = 0.0;
        for (int k = 0; k < tr->nfilled; k++) {
            const double E = vt_test_row_energy(m, d, tr, k);
            if (k == 0) E0 = E;
            dEmax = fmax(dEmax, fabs(E - E0));
            phimax = fmax(phimax, tr->phi_norm[k]);
            phidmax = fmax(phidmax, tr->phid_norm[k]);
            /* the parallelogram branch: every crank keeps turning forward, all at one angle */
            const double *q = tr->q + (size_t)k * (size_t)m->nq;
            assert_true(tr->qd[(size_t)k * (size_t)m->nv] > 0.5);
            for (int c = 1; c <= N; c++) assert_near(q[m->body_qadr[N + 1 + c]], q[0], 1e-3);
        }
        /* through both horizontal poses (crank at π and 2π), energy kept and loops closed */
        assert_true(tr->q[(size_t)opt.nout * (size_t)m->nq] > 2.0 * 3.14159265358979323846 + 1.0);
        if (!(dEmax < 1e-4 * (1 + fabs(E0))) || !(phimax < 1e-4) || !(phidmax < 1e-3))
            fail_msg("N = %d: energy error %.3g of %.3g J, max |Φ| %.3g, max |Φ̇| %.3g", N, dEmax, E0, phimax, phidmax);
        vt_trajectory_free(tr);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* IFToMM A04, Bricard's mechanism falling from the cube pose at rest: closed by a revolute
 * cut joint (one dependent row: the rank-revealing solve of the ODE form) and by a universal
 * joint (no redundancy), the two motions agree, energy is conserved and the constraints hold.
 * Up to t = 0.8 s: near 0.88 s rods 1 and 2 fold into a line, a singular pose of the loop where
 * the universal joint's loop has a branch of its own; the redundant model goes on through it. */
static void test_bricard_free_motion(void **state)
{
    (void)state;
    vt_model *m[2];
    vt_data *d[2];
    vt_trajectory *tr[2];
    vt_run_options opt = vt_default_run_options();
    opt.formulation = VT_FORMULATION_ODE;
    opt.t1 = 0.8;
    opt.nout = 40;
    opt.rtol = 1e-9;
    opt.atol = 1e-11;
    opt.forward_check = 0;
    for (int k = 0; k < 2; k++) {
        assert_ok(vt_scene_bricard(&m[k], k ? VT_JOINT_UNIVERSAL : VT_JOINT_REVOLUTE, 0, vt_function_constant(0.0)));
        assert_ok(vt_data_create(&d[k], m[k]));
        assert_ok(vt_trajectory_create(&tr[k], m[k], opt.nout + 1));
        const vt_status st = vt_dynamic_analysis(m[k], d[k], &opt, tr[k]);
        if (st) print_error("%s\n", d[k]->message);
        assert_ok(st);
        assert_int_equal(tr[k]->nfilled, opt.nout + 1);
    }
    const double E0 = vt_test_row_energy(m[0], d[0], tr[0], 0);
    for (int r = 0; r < tr[0]->nfilled; r++) {
        for (int j = 0; j < 5; j++) assert_near(tr[0]->q[5 * r + j], tr[1]->q[5 * r + j], 1e-7);
        for (int k = 0; k < 2; k++) {
            assert_near(vt_test_row_energy(m[k], d[k], tr[k], r), E0, 1e-7 * (1 + fabs(E0)));
            assert_true(tr[k]->phi_norm[r] < 1e-8);
        }
    }
    assert_true(tr[0]->q[5 * opt.nout + 1] < -1.0); /* rod 2 has turned by more than a radian */
    for (int k = 0; k < 2; k++) vt_trajectory_free(tr[k]);
    /* the benchmark's 10 s, through the fold near 0.88 s (where the universal joint's loop has
     * a branch of its own and the two models part): the redundant model keeps its energy */
    opt.t1 = 10.0;
    opt.nout = 200;
    assert_ok(vt_trajectory_create(&tr[0], m[0], opt.nout + 1));
    assert_ok(vt_data_reset(m[0], d[0]));
    assert_ok(vt_dynamic_analysis(m[0], d[0], &opt, tr[0]));
    assert_int_equal(tr[0]->nfilled, opt.nout + 1);
    double q1max = -10.0;
    for (int r = 0; r < tr[0]->nfilled; r++) {
        assert_near(vt_test_row_energy(m[0], d[0], tr[0], r), E0, 1e-5 * (1 + fabs(E0)));
        assert_true(tr[0]->phi_norm[r] < 1e-6);
        q1max = fmax(q1max, tr[0]->q[5 * r]);
    }
    assert_true(q1max > 3.0); /* rod 1 swings on past the fold */
    vt_trajectory_free(tr[0]);
    for (int k = 0; k < 2; k++) {
        vt_data_free(d[k]);
        vt_model_free(m[k]);
    }
}

/* The forward check in one IDA system with each formulation (the ODE form has no λ among the
 * unknowns: found by the fuzzer reading past y there) and independently: the forward run follows */
/* rows at irregular given times (the last before t1): the double link's exact first integral
 * and joint-1 reaction (29) at exactly those times, in both forward-check modes */
static void test_given_output_times(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 1));
    const double tout[8] = {0.013, 0.2, 0.2001, 0.5, 0.77, 1.3, 1.31, 1.85};
    for (int indep = 0; indep < 2; indep++) {
        vt_data *d;
        vt_trajectory *tr;
        assert_ok(vt_data_create(&d, m));
        vt_run_options opt = vt_default_run_options();
        opt.t1 = 1.9;
        opt.tout = tout;
        opt.ntout = 8;
        opt.rtol = 1e-10;
        opt.atol = 1e-12;
        opt.max_step = 0.005;
        opt.forward_independent = indep;
        assert_ok(vt_trajectory_create(&tr, m, 9));
        assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
        assert_int_equal(tr->nfilled, 9);
        assert_true(tr->t[0] == 0.0);
        for (int k = 0; k < 9; k++) {
            if (k) assert_true(tr->t[k] == tout[k - 1]);
            const double th = -tr->q[2 * k], thd = -tr->qd[2 * k], s = sin(th);
            const double *f1 = tr->jnt_force + 9 * k + 3, c = cos(th);
            assert_near(thd * thd, 7.3575 * s, 1e-8);
            assert_near(f1[0], -2207.25 * sin(2 * th), 1e-8 * 1962.0);
            assert_near(f1[1], 4905.0 * s * s + 490.5 * c * c, 1e-8 * 1962.0);
        }
        assert_true(d->time == tout[7]); /* the run ends at the last given time */
        if (!(tr->fwd_err_q < 1e-6)) fail_msg("independent %d: forward q error %.3g", indep, tr->fwd_err_q);
        vt_trajectory_free(tr);
        vt_data_free(d);
    }
    vt_model_free(m);
}

static void test_forward_modes(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 1));
    for (int indep = 0; indep < 2; indep++)
        for (int form = 0; form < VT_FORMULATION_COUNT; form++) {
            vt_data *d;
            vt_trajectory *tr;
            assert_ok(vt_data_create(&d, m));
            vt_run_options opt = vt_default_run_options();
            opt.t1 = 0.5;
            opt.nout = 10;
            opt.formulation = form;
            opt.forward_independent = indep;
            assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
            assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
            if (!(tr->fwd_err_q < 1e-6)) fail_msg("independent %d, formulation %d: forward q error %.3g", indep, form, tr->fwd_err_q);
            vt_trajectory_free(tr);
            vt_data_free(d);
        }
    vt_model_free(m);
}

static int fails_late(double t, double out[3], void *user)
{
    (void)user;
    out[0] = out[1] = out[2] = 0.0;
    return t > 0.5 ? 1 : 0;
}

static void test_ida_failures(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 10;
    assert_ok(vt_trajectory_create(&tr, m, 11));
    /* too few steps allowed: IDA's IDA_TOO_MUCH_WORK reaches the caller with IDA's message */
    opt.max_steps = 2;
    assert_int_equal(vt_dynamic_analysis(m, d, &opt, tr), VT_ERR_IDA);
    assert_int_equal(d->ida_flag, IDA_TOO_MUCH_WORK);
    assert_non_null(strstr(d->message, "IDA_TOO_MUCH_WORK"));
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);

    /* a drive whose time function fails after t = 0.5: the residual keeps failing */
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def link = vt_default_body_def();
    link.inertia[4] = link.inertia[8] = 0.1;
    link.joint_child[0] = -0.5;
    assert_int_equal(vt_builder_add_body(b, &link), 1);
    link.parent = 1;
    link.joint_parent[0] = 0.5;
    assert_int_equal(vt_builder_add_body(b, &link), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 2;
    dr.f = vt_function_user(fails_late, NULL);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 11));
    opt = vt_default_run_options();
    opt.nout = 10;
    opt.max_steps = 5000; /* IDA creeps toward t = 0.5 with ever smaller steps: its step budget stops it */
    const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
    assert_int_equal(st, VT_ERR_IDA);
    assert_true(d->ida_flag < 0);
    assert_true(strlen(d->message) > 0);
    assert_true(tr->nfilled >= 5 && tr->nfilled <= 7); /* the rows up to t = 0.5 were written */
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* The band that carries the ODE form through the N-four-bar's singular poses is the run's
 * explicit choice (vt_run_options.redundant_band): with none (0, rows dropped only when
 * dependent to round-off) the solve is refused at the first horizontal pose and the run stops
 * there, with it the run goes on; a band outside [0, 1) is refused. */
static void test_redundant_band_option(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_scene_nfourbar(&m, 2));
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    assert_true(opt.redundant_band == VT_REDUNDANT_TOL);
    opt.formulation = VT_FORMULATION_ODE;
    opt.t1 = 1.6; /* past the first horizontal pose, near t = 1.23 */
    opt.nout = 80;
    opt.rtol = 1e-8;
    opt.atol = 1e-10;
    opt.forward_check = 0;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    const double bad[3] = {-0.1, 1.0, NAN};
    for (int k = 0; k < 3; k++) {
        opt.redundant_band = bad[k];
        assert_int_equal(vt_dynamic_analysis(m, d, &opt, tr), VT_ERR_BAD_OPTION);
    }
    for (int k = 0; k < 2; k++) {
        opt.redundant_band = k ? VT_REDUNDANT_TOL : 0.0;
        vt_scene_nfourbar_start(m, d, 2, 1.0);
        const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
        if (k) {
            assert_ok(st);
            assert_int_equal(tr->nfilled, opt.nout + 1);
            assert_true(tr->phi_norm[opt.nout] < 1e-6);
        } else {
            assert_int_not_equal(st, VT_OK);
            assert_true(tr->nfilled < opt.nout + 1);
            assert_true(tr->t[tr->nfilled - 1] > 1.0); /* it stopped at the pose, not before */
        }
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_link),
        cmocka_unit_test(test_free_fourbar),
        cmocka_unit_test(test_formulations_drift),
        cmocka_unit_test(test_nfourbar_through_singular_pose),
        cmocka_unit_test(test_redundant_band_option),
        cmocka_unit_test(test_bricard_free_motion),
        cmocka_unit_test(test_forward_modes),
        cmocka_unit_test(test_given_output_times),
        cmocka_unit_test(test_ida_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
