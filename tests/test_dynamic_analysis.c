/* src/analysis/dynamic_analysis.c: the dynamic analysis and its forward check against the paper's exact
 * double link (29) and its first integral; a free four-bar (cut joint, spherical joint)
 * against energy conservation; IDA's failures reaching the caller with IDA's own code; a
 * spherical joint's relative orientation drive against Newton's solution at each output. */
#include <ida/ida.h>

#include "vt_test.h"
#include "analysis/dynamic_analysis.h" /* vt_forward_exact */

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

/* A spherical joint's relative orientation drive (vt_scene_spherical_chain, fully driven):
 * IDA's integration of the driven motion against Newton's solution at each output time — the
 * state, the drive's moment and every reaction. */
static void test_relative_orientation_drive(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d, *dk;
    vt_trajectory *tr;
    assert_ok(vt_scene_spherical_chain(&m, 1));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dk, m));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 20;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.forward_check = 0;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    d->time = opt.t0;
    assert_ok(vt_kinematic_solve(m, d, 1e-14, 50)); /* a consistent start */
    assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, opt.nout + 1);
    double dq = 0.0, dn = 0.0, df = 0.0;
    const int nb3 = 3 * (m->nbody + 1);
    for (int k = 0; k < tr->nfilled; k++) {
        memcpy(dk->q, tr->q + (size_t)m->nq * (size_t)k, (size_t)m->nq * sizeof(double));
        dk->time = tr->t[k];
        assert_ok(vt_kinematic_solve(m, dk, 1e-14, 50));
        for (int c = 0; c < m->nq; c++) dq = fmax(dq, fabs(tr->q[(size_t)m->nq * (size_t)k + c] - dk->q[c]));
        for (int e = 0; e < 9; e++)
            dn = fmax(dn, fabs(tr->drive_moment[9 * k + e] - dk->drive_moment[e]) / (1 + vt_test_maxabs(dk->drive_moment, 9)));
        for (int e = 3; e < nb3; e++)
            df = fmax(df, fabs(tr->jnt_force[(size_t)nb3 * (size_t)k + e] - dk->jnt_force[e]) / vt_test_maxabs(dk->jnt_force, nb3));
    }
    print_message("relative orientation drive, IDA against Newton: q %.2g, drive moments %.2g, reactions %.2g\n", dq, dn, df);
    assert_true(dq < 1e-7 && dn < 1e-6 && df < 1e-6);
    vt_trajectory_free(tr);
    vt_data_free(dk);
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

/* A free-floating chain in space (no gravity): a body on a free joint off its centre of mass,
 * and under it a revolute, a spherical and a universal joint. Energy and the angular momentum
 * about the origin, Σ m r × v + J ω, stay at their initial values; the free joint's Euler
 * parameters stay on the sphere (the kinematics would accept them off it). */
static void test_free_floating_chain(void **state)
{
    (void)state;
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = md.gravity[2] = 0.0;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    static const vt_joint_type kinds[4] = {VT_JOINT_FREE, VT_JOINT_REVOLUTE, VT_JOINT_SPHERICAL, VT_JOINT_UNIVERSAL};
    for (int i = 0; i < 4; i++) {
        vt_body_def d = vt_default_body_def();
        d.joint = kinds[i];
        d.parent = i;
        d.mass = 1.0 + 0.5 * i;
        d.inertia[0] = 0.1 + 0.01 * i, d.inertia[4] = 0.12, d.inertia[8] = 0.15;
        d.joint_child[0] = -0.3, d.joint_child[1] = 0.05 * i;
        if (i) d.joint_parent[0] = 0.3;
        d.axis1[0] = 0.0, d.axis1[1] = 0.6, d.axis1[2] = 0.8;
        d.axis2[0] = 1.0, d.axis2[1] = d.axis2[2] = 0.0;
        assert_int_equal(vt_builder_add_body(b, &d), i + 1);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nc, 0);
    vt_data *d, *dk;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dk, m));
    uint64_t s = 3;
    vt_scene_random_state(m, d, &s);
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 40;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    vt_trajectory *tr;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
    if (st) print_error("%s\n", d->message);
    assert_ok(st);
    assert_int_equal(tr->nfilled, opt.nout + 1);
    double E0 = 0.0, L0[3] = {0, 0, 0}, Lscale = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        memcpy(dk->q, tr->q + (size_t)k * (size_t)m->nq, (size_t)m->nq * sizeof(double));
        memcpy(dk->qd, tr->qd + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
        assert_ok(vt_kinematics(m, dk));
        const double *p = dk->q + 3;
        assert_near(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3], 1.0, 1e-9);
        double L[3] = {0, 0, 0};
        for (int i = 1; i <= m->nbody; i++) {
            const double *r = dk->x + 7 * (i - 1), *v = dk->xd + 7 * (i - 1), *w = dk->omega + 3 * i, mi = m->body_mass[i];
            double J[9];
            vt_test_global_inertia(J, m, dk, i);
            L[0] += mi * (r[1] * v[2] - r[2] * v[1]);
            L[1] += mi * (r[2] * v[0] - r[0] * v[2]);
            L[2] += mi * (r[0] * v[1] - r[1] * v[0]);
            for (int c = 0; c < 3; c++) L[c] += J[c] * w[0] + J[c + 3] * w[1] + J[c + 6] * w[2];
        }
        const double E = vt_test_kinetic_energy(m, dk);
        if (k == 0) {
            E0 = E;
            memcpy(L0, L, sizeof L);
            Lscale = 1.0 + fabs(L[0]) + fabs(L[1]) + fabs(L[2]);
        }
        assert_near(E, E0, 1e-7 * (1 + E0));
        for (int c = 0; c < 3; c++) assert_near(L[c], L0[c], 1e-7 * Lscale);
    }
    assert_true(E0 > 1.0); /* it moves */
    assert_true(fabs(tr->q[(size_t)opt.nout * (size_t)m->nq + 7] - tr->q[7]) > 0.1); /* the revolute joint turned */
    vt_trajectory_free(tr);
    vt_data_free(dk);
    vt_data_free(d);
    vt_model_free(m);
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
}

/* q2 = 0.2 sin 3t up to t = 0.5; then (mode 0) the callback fails, or (mode 1) returns NaN */
typedef struct {
    int mode;
    long calls, late; /* all calls, and those after t = 0.5 */
} late_drive;

static int late_drive_fn(double t, double out[3], void *user)
{
    late_drive *c = user;
    c->calls++;
    out[0] = 0.2 * sin(3.0 * t);
    out[1] = 0.6 * cos(3.0 * t);
    out[2] = -1.8 * sin(3.0 * t);
    if (t <= 0.5) return 0;
    c->late++;
    if (c->mode == 0) return 1;
    out[0] = NAN;
    return 0;
}

/* A drive's time function that fails or returns NaN from t = 0.5 on (the partly driven double
 * link): the run ends at the first failing call with VT_ERR_CALLBACK or VT_ERR_NONFINITE and a
 * message naming the drive and a time just past 0.5, in every formulation, without the forward
 * check and with it (one IDA system, or independent); the rows before it hold q2 = f(t). */
static void test_drive_fails_midway(void **state)
{
    (void)state;
    for (int mode = 0; mode < 2; mode++)
        for (int form = 0; form < VT_FORMULATION_COUNT; form++)
            for (int forward = 0; forward < 3; forward++) {
                late_drive c = {mode, 0, 0};
                vt_model *m;
                vt_data *d;
                vt_trajectory *tr;
                assert_ok(vt_scene_double_link_driven(&m, vt_function_user(late_drive_fn, &c)));
                assert_ok(vt_data_create(&d, m));
                vt_run_options opt = vt_default_run_options();
                opt.formulation = form;
                opt.forward_check = forward > 0;
                opt.forward_independent = forward == 2;
                opt.t1 = 1.0;
                opt.nout = 10;
                opt.max_steps = 5000; /* (for the code before the fix: IDA crept toward t = 0.5) */
                assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
                const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
                const char *at = strstr(d->message, "at t = ");
                const double t_fail = at ? strtod(at + 7, NULL) : -1.0;
                if (st != (mode ? VT_ERR_NONFINITE : VT_ERR_CALLBACK) || !strstr(d->message, "drive 0") ||
                    !(t_fail > 0.5 && t_fail < 0.6) || c.late > 2 || c.calls > 2000)
                    fail_msg("mode %d, formulation %d, forward %d: status %d (%s), %ld calls (%ld after t = 0.5): %s",
                             mode, form, forward, st, vt_status_string(st), c.calls, c.late, d->message);
                assert_true(tr->nfilled >= 5 && tr->nfilled <= 6); /* the rows up to t = 0.4 or 0.5 */
                for (int k = 0; k < tr->nfilled; k++)
                    assert_near(tr->q[2 * k + 1], 0.2 * sin(3.0 * tr->t[k]), 1e-6);
                vt_trajectory_free(tr);
                vt_data_free(d);
                vt_model_free(m);
            }
}

/* p_d(t): a turn by a = 0.3 sin 2t about z, up to t = 0.5; then (mode 0) the callback fails, or
 * (mode 1) returns NaN */
static int late_orientation(double t, double p[4], double w[3], double wd[3], void *user)
{
    late_drive *c = user;
    c->calls++;
    const double a = 0.3 * sin(2.0 * t);
    p[0] = cos(0.5 * a);
    p[1] = p[2] = 0.0;
    p[3] = sin(0.5 * a);
    w[0] = w[1] = wd[0] = wd[1] = 0.0;
    w[2] = 0.6 * cos(2.0 * t);
    wd[2] = -1.2 * sin(2.0 * t);
    if (t <= 0.5) return 0;
    c->late++;
    if (c->mode == 0) return 1;
    wd[2] = INFINITY;
    return 0;
}

/* The same with an orientation drive's callback: body 1 on a spherical joint, its orientation
 * prescribed, and a link hinged to it swinging freely under gravity (partly driven: 3 of 4 rates) */
static void test_orientation_callback_fails_midway(void **state)
{
    (void)state;
    for (int mode = 0; mode < 2; mode++)
        for (int form = 0; form < VT_FORMULATION_COUNT; form++)
            for (int forward = 0; forward < 3; forward++) {
                late_drive c = {mode, 0, 0};
                vt_builder *b;
                assert_ok(vt_builder_create(&b, NULL));
                vt_body_def body = vt_default_body_def();
                body.joint = VT_JOINT_SPHERICAL;
                body.inertia[0] = 0.1;
                body.inertia[4] = 0.2;
                body.inertia[8] = 0.3;
                assert_int_equal(vt_builder_add_body(b, &body), 1);
                vt_body_def link = vt_default_body_def();
                link.parent = 1;
                link.joint_parent[0] = 0.5;
                link.joint_child[0] = -0.5;
                link.inertia[4] = link.inertia[8] = 0.1;
                assert_int_equal(vt_builder_add_body(b, &link), 2);
                vt_drive_def od = vt_default_drive_def();
                od.type = VT_DRIVE_ORIENTATION;
                od.body = 1;
                od.orientation_callback = late_orientation;
                od.user = &c;
                assert_int_equal(vt_builder_add_drive(b, &od), 0);
                vt_model *m;
                vt_data *d;
                vt_trajectory *tr;
                assert_ok(vt_builder_build(&m, b));
                vt_builder_free(b);
                assert_ok(vt_data_create(&d, m));
                vt_run_options opt = vt_default_run_options();
                opt.formulation = form;
                opt.forward_check = forward > 0;
                opt.forward_independent = forward == 2;
                opt.t1 = 1.0;
                opt.nout = 10;
                opt.max_steps = 5000;
                assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
                const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
                const char *at = strstr(d->message, "at t = ");
                const double t_fail = at ? strtod(at + 7, NULL) : -1.0;
                if (st != (mode ? VT_ERR_NONFINITE : VT_ERR_CALLBACK) || !strstr(d->message, "drive 0") ||
                    !strstr(d->message, "orientation callback") || !(t_fail > 0.5 && t_fail < 0.6) || c.late > 2 ||
                    c.calls > 5000) /* (the calls before t = 0.5 are the run's work: up to 2,400 with projection) */
                    fail_msg("mode %d, formulation %d, forward %d: status %d (%s), %ld calls (%ld after t = 0.5): %s",
                             mode, form, forward, st, vt_status_string(st), c.calls, c.late, d->message);
                assert_true(tr->nfilled >= 5 && tr->nfilled <= 6);
                for (int k = 0; k < tr->nfilled; k++) { /* the rows before: body 1 turned as prescribed */
                    const double *q = tr->q + (size_t)k * (size_t)m->nq, a = 0.3 * sin(2.0 * tr->t[k]);
                    assert_near(fabs(q[0]), cos(0.5 * a), 1e-6);
                    assert_near(fabs(q[1]) + fabs(q[2]), 0.0, 1e-6);
                    assert_near(q[3] * (q[0] < 0 ? -1 : 1), sin(0.5 * a), 1e-6);
                }
                vt_trajectory_free(tr);
                vt_data_free(d);
                vt_model_free(m);
            }
}

static int toward_stretch(double t, double out[3], void *user)
{
    (void)user;
    out[0] = 3.0 + 2.0 * t; /* the tip's x reaches the links' reach, 4 m, at t = 0.5 */
    out[1] = 2.0;
    out[2] = 0.0;
    return 0;
}

/* A rotor about a vertical axis (no gravity moment): I q̈ = τ. The forward check of a kinematic
 * analysis must report what efforts of the wrong inertia do: efforts I (1 + ε) q̈ on the rotor
 * of inertia I turn it by q + ε (q − q0 − q̇0 t) exactly. vt_forward_exact takes the efforts of a
 * second model (ε) for the forward run of the first; with ε = 0 the deviation is round-off. */
static vt_model *rotor(double eps)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = md.gravity[2] = 0.0;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def body = vt_default_body_def();
    body.mass = 2.0;
    body.joint_child[0] = -0.5;                                  /* I = 0.1 + 2 · 0.5² = 0.6 about the axis */
    body.inertia[0] = body.inertia[4] = 0.2;
    body.inertia[8] = 0.1 + eps * 0.6;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    static const double c[4] = {0.2, 0.5, 1.5, -0.8};             /* q = 0.2 + 0.5 t + 1.5 t² − 0.8 t³ */
    vt_drive_def dr = vt_default_drive_def();
    dr.f = vt_function_polynomial(4, c);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

static void test_forward_check_measures_wrong_efforts(void **state)
{
    (void)state;
    static const double eps[2] = {0.0, 1e-6};
    vt_model *m = rotor(0.0);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    for (int e = 0; e < 2; e++) {
        vt_model *m2 = rotor(eps[e]); /* the efforts' model */
        vt_data *d2, *dk;
        vt_trajectory *tr;
        assert_ok(vt_data_create(&d2, m2));
        assert_ok(vt_data_create(&dk, m2));
        vt_run_options opt = vt_default_run_options();
        opt.nout = 50;
        opt.forward_check = 0;
        opt.rtol = 1e-10; /* IDA's error in the deviation, about rtol |q|, well below 1e-3 of it */
        opt.atol = 1e-12;
        assert_ok(vt_trajectory_create(&tr, m2, opt.nout + 1));
        assert_ok(vt_kinematic_analysis(m2, d2, &opt, tr));
        dk->q[0] = tr->q[0];
        dk->qd[0] = tr->qd[0];
        dk->time = opt.t0;
        assert_ok(vt_forward_exact(m, d, dk, &opt, tr));
        const double q0 = tr->q[0], v0 = tr->qd[0];
        assert_near(q0, 0.2, 1e-12);
        assert_near(v0, 0.5, 1e-12);
        double worst = 0.0, dev = 0.0;
        for (int k = 0; k < tr->nfilled; k++) {
            const double t = tr->t[k], q = tr->q[k], v = tr->qd[k];
            const double eq = eps[e] * (q - q0 - v0 * t), ev = eps[e] * (v - v0); /* exact deviations */
            worst = fmax(worst, fmax(fabs(tr->q_fwd[k] - q - eq), fabs(tr->qd_fwd[k] - v - ev)));
            dev = fmax(dev, fabs(eq));
        }
        print_message("rotor, efforts of inertia (1 + %g) I: deviation %.3g rad, its error %.3g\n", eps[e], dev, worst);
        if (e == 0) assert_true(worst <= 1e-13 && tr->fwd_err_q <= 1e-13);
        else assert_true(dev > 5e-7 && worst <= 1e-3 * dev && fabs(tr->fwd_err_q - dev) <= 1e-3 * dev);
        vt_trajectory_free(tr);
        vt_data_free(dk);
        vt_data_free(d2);
        vt_model_free(m2);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* Trial states a stage refuses stay recoverable (IDA retries with smaller steps), and when IDA
 * gives up the refusing stage's status and message are returned, not IDA's generic failure:
 * two 2 m links whose tip's x is driven to 3 + 2t, their full reach at t = 0.5 (the rates grow
 * without bound toward it, the residual overflows in the trial states near it). */
static void test_refused_states_reported(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def link = vt_default_body_def();
    link.mass = 100.0;
    link.inertia[4] = link.inertia[8] = 100.0 * 4.0 / 12.0;
    link.joint_child[0] = -1.0;
    assert_int_equal(vt_builder_add_body(b, &link), 1);
    link.parent = 1;
    link.joint_parent[0] = 1.0;
    assert_int_equal(vt_builder_add_body(b, &link), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.type = VT_DRIVE_POINT;
    dr.body = 2;
    dr.index = 0;
    dr.point[0] = 1.0;
    dr.f = vt_function_user(toward_stretch, NULL);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m;
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(&d, m));
    d->q[0] = -0.5; /* a guess on the elbow-up branch: made consistent (tip x = 3) first */
    d->q[1] = 1.0;
    vt_run_options opt = vt_default_run_options();
    opt.formulation = VT_FORMULATION_INDEX1;
    opt.forward_check = 0;
    opt.nout = 10;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
    if (st != VT_ERR_NONFINITE || !strstr(d->message, "refused") || !strstr(d->message, "not finite"))
        fail_msg("status %d (%s): %s", st, vt_status_string(st), d->message);
    assert_true(d->ida_flag < 0); /* IDA's own code is kept */
    /* the rows up to t = 0.4, and the one at the reach itself, t = 0.5, where IDA reaches it before
     * giving up a step later (which, round-off decides: the rates there are ~5e3 rad/s) */
    assert_in_range(tr->nfilled, 5, 6);
    for (int k = 0; k < tr->nfilled; k++) { /* and they hold the drive: 2 cos q1 + 2 cos(q1 + q2) = 3 + 2t */
        const double q1 = tr->q[2 * k], q2 = tr->q[2 * k + 1];
        assert_near(2.0 * cos(q1) + 2.0 * cos(q1 + q2), 3.0 + 2.0 * tr->t[k], 1e-6);
    }
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

/* max over row k's n coordinates of |fwd − drv| */
static double row_deviation(int n, int k, const double *fwd, const double *drv)
{
    double e = 0.0;
    for (int c = 0; c < n; c++) e = fmax(e, fabs(fwd[(size_t)k * (size_t)n + (size_t)c] - drv[(size_t)k * (size_t)n + (size_t)c]));
    return e;
}

/* A long run of the free double pendulum (no drive, chaotic: a single forward check over it means
 * nothing, its deviation grows exponentially whatever the efforts' accuracy), 40 s with room for
 * 2000 driven steps (it takes over 12000): it used to stop with VT_ERR_BAD_OPTION "the driven run
 * took more than history_steps" (the same refusal as 1000 s at the default 100000). Now it
 * succeeds in 2 s windows: one per 20 rows, each starting at its row, each window's deviation
 * the largest of its rows', the run's the largest of the windows'; each small beside a 2 s run
 * of its own (an independent check of the same length) and far below the single 40 s window's. */
static void test_long_run_in_windows(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 0));
    vt_data *d;
    vt_trajectory *tr, *one;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, 401));
    assert_ok(vt_trajectory_create(&one, m, 401));
    vt_run_options opt = vt_default_run_options();
    double short_q = 0.0, short_qd = 0.0;
    for (int indep = 1; indep >= 0; indep--) {
        memset(d->q, 0, (size_t)m->nq * sizeof(double));
        memset(d->qd, 0, (size_t)m->nv * sizeof(double));
        opt.t1 = 40.0;
        opt.nout = 400;
        opt.history_steps = 2000;
        opt.check_window = 2.0;
        opt.forward_independent = indep;
        const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
        if (st) fail_msg("independent %d: %s: %s", indep, vt_status_string(st), d->message);
        assert_int_equal(tr->nfilled, 401);
        if (indep) { /* the short run: 2 s, one window (its own independent check) */
            vt_run_options o2 = vt_default_run_options();
            o2.t1 = 2.0;
            o2.nout = 20;
            vt_data *d2;
            assert_ok(vt_data_create(&d2, m));
            assert_ok(vt_dynamic_analysis(m, d2, &o2, one));
            assert_int_equal(one->nwindow, 1);
            short_q = one->fwd_err_q;
            short_qd = one->fwd_err_qd;
            vt_data_free(d2);
        }
        if (indep) assert_true(tr->steps > 5 * opt.history_steps); /* it outgrew the history, and went on */
        assert_int_equal(tr->nwindow, 20);
        double worst_q = 0.0, worst_qd = 0.0;
        for (int w = 0; w < tr->nwindow; w++) {
            assert_int_equal(tr->fwd_window_row[w], 20 * w);
            double eq = 0.0, eqd = 0.0; /* the window's rows */
            for (int k = 20 * w + (w > 0); k <= 20 * w + 20; k++) {
                eq = fmax(eq, row_deviation(m->nq, k, tr->q_fwd, tr->q));
                eqd = fmax(eqd, row_deviation(m->nv, k, tr->qd_fwd, tr->qd));
            }
            assert_near(tr->fwd_window_err_q[w], eq, 0.0);
            assert_near(tr->fwd_window_err_qd[w], eqd, 0.0);
            if (!(eq <= 1e3 * short_q && eqd <= 1e3 * short_qd && eq < 1e-3))
                fail_msg("independent %d, window %d: deviation %.3g (q̇ %.3g), a 2 s run's %.3g (%.3g)", indep, w, eq, eqd,
                         short_q, short_qd);
            worst_q = fmax(worst_q, eq);
            worst_qd = fmax(worst_qd, eqd);
        }
        assert_near(tr->fwd_err_q, worst_q, 0.0); /* the worst window's */
        assert_near(tr->fwd_err_qd, worst_qd, 0.0);
        /* the same run in one window: its deviation is the chaos's, not the efforts' */
        memset(d->q, 0, (size_t)m->nq * sizeof(double));
        memset(d->qd, 0, (size_t)m->nv * sizeof(double));
        opt.check_window = INFINITY;
        assert_ok(vt_dynamic_analysis(m, d, &opt, one));
        assert_int_equal(one->nwindow, 1);
        assert_true(one->fwd_err_q > 1e3 * worst_q);
    }
    vt_trajectory_free(one);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* A window's boundary restarts the forward run from the driven state: rows at 1, 2, 3 and 4 s,
 * then 1 µs later and at 5 s, windows of 4 s. The free double pendulum's forward deviation has
 * grown by row 4 (the first window's end); at the row 1 µs after it, the first of the second
 * window, it is at round-off (a forward run carried on from row 4 keeps its deviation there) —
 * with the forward check in its own run and in one system with the driven run. */
static void test_window_restarts_from_driven_state(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 0));
    const double tout[6] = {1.0, 2.0, 3.0, 4.0, 4.000001, 5.0};
    for (int indep = 0; indep < 2; indep++) {
        vt_data *d;
        vt_trajectory *tr;
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_trajectory_create(&tr, m, 7));
        vt_run_options opt = vt_default_run_options();
        opt.t1 = 5.0;
        opt.tout = tout;
        opt.ntout = 6;
        opt.check_window = 4.0;
        opt.forward_independent = indep;
        assert_ok(vt_dynamic_analysis(m, d, &opt, tr));
        assert_int_equal(tr->nfilled, 7);
        const double end_q = row_deviation(m->nq, 4, tr->q_fwd, tr->q), end_qd = row_deviation(m->nv, 4, tr->qd_fwd, tr->qd);
        const double next_q = row_deviation(m->nq, 5, tr->q_fwd, tr->q), next_qd = row_deviation(m->nv, 5, tr->qd_fwd, tr->qd);
        if (!(end_q > 1e-9 && next_q < 1e-12 && next_qd < 1e-11))
            fail_msg("independent %d: deviation %.3g (q̇ %.3g) at the window's end, %.3g (%.3g) 1 µs after", indep, end_q,
                     end_qd, next_q, next_qd);
        assert_int_equal(tr->nwindow, 2);
        assert_int_equal(tr->fwd_window_row[0], 0);
        assert_int_equal(tr->fwd_window_row[1], 4);
        assert_near(tr->fwd_window_err_q[0], fmax(end_q, fmax(row_deviation(m->nq, 1, tr->q_fwd, tr->q),
                                                              fmax(row_deviation(m->nq, 2, tr->q_fwd, tr->q),
                                                                   row_deviation(m->nq, 3, tr->q_fwd, tr->q)))), 0.0);
        vt_trajectory_free(tr);
        vt_data_free(d);
    }
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_link),
        cmocka_unit_test(test_relative_orientation_drive),
        cmocka_unit_test(test_free_fourbar),
        cmocka_unit_test(test_free_floating_chain),
        cmocka_unit_test(test_formulations_drift),
        cmocka_unit_test(test_nfourbar_through_singular_pose),
        cmocka_unit_test(test_redundant_band_option),
        cmocka_unit_test(test_bricard_free_motion),
        cmocka_unit_test(test_forward_modes),
        cmocka_unit_test(test_given_output_times),
        cmocka_unit_test(test_ida_failures),
        cmocka_unit_test(test_drive_fails_midway),
        cmocka_unit_test(test_orientation_callback_fails_midway),
        cmocka_unit_test(test_refused_states_reported),
        cmocka_unit_test(test_forward_check_measures_wrong_efforts),
        cmocka_unit_test(test_long_run_in_windows),
        cmocka_unit_test(test_window_restarts_from_driven_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
