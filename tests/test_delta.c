/* The Delta robot of examples/delta.c (vt_scene_delta in examples/scenes.c), verified four ways:
 *  1. the forward check: the drives removed, their generalized forces applied, IDA from the same
 *     start; the platform centre stays on the driven run's to 1e-6 m (and the driven run on the
 *     prescribed path to 1e-10 m);
 *  2. statics in closed form, written here without vtdyn: the motor torques from the static
 *     Jacobian equation (below, "closed form") against vtdyn's, to 1e-9 relative, at rest
 *     (q̇ = q̈ = 0) and along the path run a million times slower;
 *  3. the power balance: the motors' power Σ τ_i θ̇_i, and the point drives' Σ f_k ṗ_k, against
 *     d/dt (T + V) = Σ_bodies m (a − g)·v + ω·J α from the bodies' own motion, to 1e-9 of the
 *     largest power term on the path;
 *  4. the one model driven at its motors by the path's inverse kinematics (vt_scene_delta_ik):
 *     its θ_i(t) against the path model's Newton solution (1e-12 rad), θ̇ and θ̈ against central
 *     differences of θ (1e-7, 1e-5) and the path model's q̇, q̈; its run on the path (1e-10 m),
 *     its forward check, and its torques and reactions against the two-model route (1e-9).
 * The model is exactly constrained (21 rates, 18 cut rows and 3 drives, no redundant rows). */
#include "vt_test.h"

#define PI 3.14159265358979323846

/* ---- closed form -------------------------------------------------------------------------
 * Arm i at φ_i = 2πi/3, u_i = (cos φ_i, sin φ_i, 0), z up, θ_i > 0 turning the arm down:
 *   elbow      E_i = (RB + LA cos θ_i) u_i − LA sin θ_i z,  E'_i = dE_i/dθ_i = −LA (sin θ_i u_i + cos θ_i z)
 *   rod vector w_i = P + RP u_i − E_i (both rods of the parallelogram), |w_i| = LF.
 * Differentiating |w_i|² = LF²: w_i·Ṗ = (w_i·E'_i) θ̇_i. Virtual power of the motors and of
 * gravity g over every motion of the platform Ṗ (the platform does not turn):
 *   Σ τ_i θ̇_i + g·[MP Ṗ + Σ_i MA Ė_i/2 + Σ_i 2 MR (Ė_i + Ṗ)/2] = 0
 * (arm's centre of mass at LA/2; each rod's centre at the middle of its ends, which move at Ė_i
 * and Ṗ: the rods' weight taken exactly). With θ̇_i = w_i·Ṗ / (w_i·E'_i) and
 * c_i = (MA/2 + MR) g·E'_i, for every Ṗ: Σ_i (τ_i + c_i) w_i / (w_i·E'_i) = −(MP + 3 MR) g.
 * So μ solves the 3 × 3 system Σ_i μ_i w_i = −(MP + 3 MR) g (μ_i w_i: the force the pair of rods
 * i carries along itself), and τ_i = μ_i (w_i·E'_i) − c_i. τ = J^T F with J = ∂P/∂θ. */
static void closed_form_ik(double th[3], const double P[3])
{
    for (int i = 0; i < 3; i++) {
        const double phi = 2.0 * PI * i / 3.0, u[2] = {cos(phi), sin(phi)};
        /* |P + (RP − RB) u − LA cos θ u + LA sin θ z| = LF: A cos θ + B sin θ = K */
        const double cx = P[0] + (VT_DELTA_RP - VT_DELTA_RB) * u[0], cy = P[1] + (VT_DELTA_RP - VT_DELTA_RB) * u[1];
        const double a = cx * u[0] + cy * u[1], z = P[2], c2 = cx * cx + cy * cy + z * z;
        const double A = -2.0 * a * VT_DELTA_LA, B = 2.0 * z * VT_DELTA_LA;
        const double K = VT_DELTA_LF * VT_DELTA_LF - VT_DELTA_LA * VT_DELTA_LA - c2;
        const double r = sqrt(A * A + B * B), t1 = atan2(B, A) + acos(K / r), t2 = atan2(B, A) - acos(K / r);
        th[i] = cos(t1) >= cos(t2) ? t1 : t2; /* elbow out */
    }
}

static void closed_form_torques(double tau[3], const double P[3], const double th[3], const double g[3])
{
    double W[9], wE[3], c[3];
    for (int i = 0; i < 3; i++) {
        const double phi = 2.0 * PI * i / 3.0, u[3] = {cos(phi), sin(phi), 0.0};
        double E[3], Ed[3];
        for (int k = 0; k < 3; k++) {
            const double zk = k == 2;
            E[k] = (VT_DELTA_RB + VT_DELTA_LA * cos(th[i])) * u[k] - VT_DELTA_LA * sin(th[i]) * zk;
            Ed[k] = -VT_DELTA_LA * (sin(th[i]) * u[k] + cos(th[i]) * zk);
            W[k + 3 * i] = P[k] + VT_DELTA_RP * u[k] - E[k];
        }
        wE[i] = W[3 * i] * Ed[0] + W[3 * i + 1] * Ed[1] + W[3 * i + 2] * Ed[2];
        c[i] = (0.5 * VT_DELTA_MA + VT_DELTA_MR) * (g[0] * Ed[0] + g[1] * Ed[1] + g[2] * Ed[2]);
    }
    /* Σ μ_i w_i = −(MP + 3 MR) g by Cramer's rule */
    const double det = W[0] * (W[4] * W[8] - W[7] * W[5]) - W[3] * (W[1] * W[8] - W[7] * W[2]) +
                       W[6] * (W[1] * W[5] - W[4] * W[2]);
    double rhs[3];
    for (int k = 0; k < 3; k++) rhs[k] = -(VT_DELTA_MP + 3.0 * VT_DELTA_MR) * g[k];
    for (int i = 0; i < 3; i++) {
        double Wi[9];
        memcpy(Wi, W, sizeof Wi);
        for (int k = 0; k < 3; k++) Wi[k + 3 * i] = rhs[k];
        const double mu = (Wi[0] * (Wi[4] * Wi[8] - Wi[7] * Wi[5]) - Wi[3] * (Wi[1] * Wi[8] - Wi[7] * Wi[2]) +
                           Wi[6] * (Wi[1] * Wi[5] - Wi[4] * Wi[2])) / det;
        tau[i] = mu * wE[i] - c[i];
    }
}

/* ---- the runs ------------------------------------------------------------------------------ */

/* the path model's kinematic analysis over one period (nout rows), from the assembled start */
static void run_path(vt_model **m, vt_data **d, vt_trajectory **tr, double period, int nout, int forward)
{
    assert_ok(vt_scene_delta(m, period, VT_DELTA_PATH));
    assert_int_equal((*m)->nv, 21);
    assert_int_equal((*m)->nc, 21);
    assert_int_equal((*m)->allow_redundant, 0);
    assert_ok(vt_data_create(d, *m));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = period;
    opt.nout = nout;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.forward_check = forward;
    assert_ok(vt_trajectory_create(tr, *m, nout + 1));
    double p0[3];
    vt_scene_delta_path(0.0, period, p0, NULL, NULL);
    assert_int_equal(vt_scene_delta_assemble(*m, *d, p0), 0);
    assert_ok(vt_kinematic_analysis(*m, *d, &opt, *tr));
    assert_int_equal((*tr)->nfilled, nout + 1);
}

/* row k's motion given to the motor-driven model: its efforts are the motor torques */
static void motors_at_row(const vt_model *mm, vt_data *dm, const vt_trajectory *tr, int k)
{
    const vt_model *m = tr->model;
    memcpy(dm->q, tr->q + (size_t)k * (size_t)m->nq, (size_t)m->nq * sizeof(double));
    memcpy(dm->qd, tr->qd + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
    memcpy(dm->qdd, tr->qdd + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
    dm->time = tr->t[k];
    assert_ok(vt_inverse_dynamics_motion(mm, dm));
}

/* 1. the scene's assembly closes every loop; the forward check; the motors' model moves alike */
#if VT_HAVE_SUNDIALS /* the forward check needs IDA */
static void test_forward_check(void **state)
{
    (void)state;
    vt_model *m, *mm;
    vt_data *d, *dm;
    vt_trajectory *tr;
    run_path(&m, &d, &tr, 1.0, 100, 1);
    assert_ok(vt_scene_delta(&mm, 1.0, VT_DELTA_MOTORS));
    assert_ok(vt_data_create(&dm, mm));
    /* the assembly (inverse kinematics) against vtdyn's constraint rows, around the path */
    for (int k = 0; k < 8; k++) {
        double p[3];
        vt_scene_delta_path(k / 8.0, 1.0, p, NULL, NULL);
        assert_int_equal(vt_scene_delta_assemble(m, dm, p), 0);
        dm->time = 0.0;
        assert_ok(vt_kinematics(mm, dm));
        assert_ok(vt_constraints(mm, dm));
        for (int r = 3; r < mm->nc; r++) assert_near(dm->Phi[r], 0.0, 1e-14); /* the cut rows */
    }
    const int pq = m->body_qadr[10];
    double dev = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + (size_t)k * (size_t)m->nq, *qf = tr->q_fwd + (size_t)k * (size_t)m->nq;
        double p[3], e = 0.0;
        vt_scene_delta_path(tr->t[k], 1.0, p, NULL, NULL);
        for (int c = 0; c < 3; c++) {
            assert_near(q[pq + c], p[c], 1e-10);
            e += (qf[pq + c] - q[pq + c]) * (qf[pq + c] - q[pq + c]);
        }
        dev = fmax(dev, sqrt(e));
        /* the parallelograms keep the platform parallel to the base: no row drives its turn */
        assert_near(q[pq + 3], 1.0, 1e-12);
        for (int c = 4; c < 7; c++) assert_near(q[pq + c], 0.0, 1e-12);
        assert_true(tr->phi_norm[k] <= 1e-12);
        assert_true(tr->phid_norm[k] <= 1e-10);
        /* the motor angles' accelerations given, the cut joints give the rest: the path's q̈ */
        motors_at_row(mm, dm, tr, k);
        const double *qdd = tr->qdd + (size_t)k * (size_t)m->nv;
        for (int c = 0; c < m->nv; c++) assert_near(dm->qdd[c], qdd[c], 1e-9 * (1.0 + fabs(qdd[c])));
    }
    print_message("delta forward check: platform deviation %.3g m, %ld IDA steps\n", dev, tr->steps_fwd);
    assert_true(dev <= 1e-10);
    assert_true(dev > 0.0); /* a separate integration, not the driven run copied */
    vt_trajectory_free(tr);
    vt_data_free(dm);
    vt_data_free(d);
    vt_model_free(mm);
    vt_model_free(m);
}
#endif

/* 2. statics: at rest at poses of the path, then along the path a million times slower */
static void test_quasi_static(void **state)
{
    (void)state;
    vt_model *m, *mm;
    vt_data *d, *dm;
    vt_trajectory *tr;
    const double period = 1e6, g[3] = {0.0, 0.0, -9.81};
    run_path(&m, &d, &tr, period, 12, 0);
    assert_ok(vt_scene_delta(&mm, period, VT_DELTA_MOTORS));
    assert_ok(vt_data_create(&dm, mm));
    const int pq = m->body_qadr[10];
    double worst_rest = 0.0, worst_slow = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + (size_t)k * (size_t)m->nq;
        double th[3], tau[3];
        closed_form_ik(th, q + pq);
        /* the same pose to Newton's tolerance (|Φ| ≤ 1e-12 m) */
        for (int i = 0; i < 3; i++) assert_near(th[i], q[m->body_qadr[1 + i]], 1e-10);
        closed_form_torques(tau, q + pq, th, g);
        const double scale = fmax(fabs(tau[0]), fmax(fabs(tau[1]), fabs(tau[2])));
        assert_true(scale > 1.0); /* torques of newtons times metres: the check is not of zeros */
        /* slow: the run's own q, q̇, q̈ */
        motors_at_row(mm, dm, tr, k);
        for (int i = 0; i < 3; i++) worst_slow = fmax(worst_slow, fabs(dm->drive_effort[i] - tau[i]) / scale);
        /* at rest */
        memset(dm->qd, 0, (size_t)mm->nv * sizeof(double));
        memset(dm->qdd, 0, (size_t)mm->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(mm, dm));
        for (int i = 0; i < 3; i++) worst_rest = fmax(worst_rest, fabs(dm->drive_effort[i] - tau[i]) / scale);
    }
    print_message("delta statics: motor torques against the closed form, at rest %.3g, slow %.3g (relative)\n",
                  worst_rest, worst_slow);
    assert_true(worst_rest <= 1e-9);
    assert_true(worst_slow <= 1e-9);
    vt_trajectory_free(tr);
    vt_data_free(dm);
    vt_data_free(d);
    vt_model_free(mm);
    vt_model_free(m);
}

/* 3. Σ efforts · rates = d/dt (T + V): dT/dt = Σ m v·a + ω·J α (the gyroscopic term ω·(ω × Jω)
 * is zero), dV/dt = −Σ m g·v; α = 2 E(p) p̈ (E(ṗ) ṗ = 0), with E checked by ω = 2 E(p) ṗ */
static void test_power_balance(void **state)
{
    (void)state;
    vt_model *m, *mm;
    vt_data *d, *dm;
    vt_trajectory *tr;
    run_path(&m, &d, &tr, 1.0, 100, 0);
    assert_ok(vt_scene_delta(&mm, 1.0, VT_DELTA_MOTORS));
    assert_ok(vt_data_create(&dm, mm));
    double worst_m = 0.0, worst_p = 0.0, scale = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        motors_at_row(mm, dm, tr, k);
        double dE = 0.0, terms = 0.0;
        for (int i = 1; i <= mm->nbody; i++) {
            const double *x = dm->x + 7 * (i - 1), *v = dm->xd + 7 * (i - 1), *a = dm->xdd + 7 * (i - 1);
            const double *p = x + 3, *pd = v + 3, *pdd = a + 3, *w = dm->omega + 3 * i;
            /* E(p) = [−e, ẽ + e0 I] applied to a 4-vector y: −e y0 + e × y_v + e0 y_v */
            double wE[3], al[3], J[9];
            for (int r = 0; r < 3; r++) {
                const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
                wE[r] = 2.0 * (-p[1 + r] * pd[0] + p[1 + r1] * pd[1 + r2] - p[1 + r2] * pd[1 + r1] + p[0] * pd[1 + r]);
                al[r] = 2.0 * (-p[1 + r] * pdd[0] + p[1 + r1] * pdd[1 + r2] - p[1 + r2] * pdd[1 + r1] + p[0] * pdd[1 + r]);
                assert_near(wE[r], w[r], 1e-12 * (1.0 + fabs(w[r])));
            }
            vt_test_global_inertia(J, mm, dm, i);
            const double mass = mm->body_mass[i];
            double lin = 0.0, rot = 0.0;
            for (int r = 0; r < 3; r++) {
                lin += mass * (a[r] - mm->gravity[r]) * v[r];
                rot += w[r] * (J[r] * al[0] + J[r + 3] * al[1] + J[r + 6] * al[2]);
            }
            dE += lin + rot;
            terms += fabs(lin) + fabs(rot);
        }
        double Pm = 0.0, Pp = 0.0;
        for (int i = 0; i < 3; i++) {
            Pm += dm->drive_effort[i] * dm->qd[mm->body_vadr[1 + i]];
            Pp += tr->drive_effort[(size_t)k * 3 + (size_t)i] * dm->qd[m->body_vadr[10] + i];
        }
        worst_m = fmax(worst_m, fabs(Pm - dE));
        worst_p = fmax(worst_p, fabs(Pp - dE));
        scale = fmax(scale, terms);
    }
    print_message("delta power balance: motors %.3g W, point drives %.3g W, largest power term %.4g W\n", worst_m,
                  worst_p, scale);
    assert_true(scale > 1.0);
    assert_true(worst_m <= 1e-9 * scale);
    assert_true(worst_p <= 1e-9 * scale);
    vt_trajectory_free(tr);
    vt_data_free(dm);
    vt_data_free(d);
    vt_model_free(mm);
    vt_model_free(m);
}

/* 4. the one model driven at its motors by the path's inverse kinematics (VT_DELTA_IK): its time
 * functions against the path model's solved motor angles (Newton on all 21 rows from another
 * pose) and against central differences of themselves */
static void test_ik_angles(void **state)
{
    (void)state;
    vt_model *m, *mi;
    vt_data *d;
    vt_delta_ik ik;
    assert_ok(vt_scene_delta(&m, 1.0, VT_DELTA_PATH));
    assert_ok(vt_scene_delta_ik(&mi, &ik, 1.0));
    assert_int_equal(mi->ndrive, 3);
    assert_int_equal(mi->nc, 21);
    assert_ok(vt_data_create(&d, m));
    double e_q = 0.0, e_qd = 0.0, e_qdd = 0.0, e_fd1 = 0.0, e_fd2 = 0.0;
    for (int k = 0; k < 24; k++) {
        const double t = k / 24.0 + 0.01;
        /* the path model solved at t from the pose 0.03 s later: Newton has work to do */
        double p[3];
        vt_scene_delta_path(t + 0.03, 1.0, p, NULL, NULL);
        assert_int_equal(vt_scene_delta_assemble(m, d, p), 0);
        d->time = t;
        assert_ok(vt_kinematic_solve(m, d, 1e-14, 30));
        for (int i = 0; i < 3; i++) {
            double f[3], fp[3], fm[3], gp[3], gm[3];
            assert_ok(vt_function_eval(f, &mi->drive[i].f, t));
            assert_ok(vt_function_eval(fp, &mi->drive[i].f, t + 1e-5));
            assert_ok(vt_function_eval(fm, &mi->drive[i].f, t - 1e-5));
            assert_ok(vt_function_eval(gp, &mi->drive[i].f, t + 1e-4));
            assert_ok(vt_function_eval(gm, &mi->drive[i].f, t - 1e-4));
            const int v = m->body_vadr[1 + i];
            e_q = fmax(e_q, fabs(f[0] - d->q[m->body_qadr[1 + i]]));
            e_qd = fmax(e_qd, fabs(f[1] - d->qd[v]) / (1.0 + fabs(d->qd[v])));
            e_qdd = fmax(e_qdd, fabs(f[2] - d->qdd[v]) / (1.0 + fabs(d->qdd[v])));
            e_fd1 = fmax(e_fd1, fabs(f[1] - (fp[0] - fm[0]) / 2e-5) / (1.0 + fabs(f[1])));
            e_fd2 = fmax(e_fd2, fabs(f[2] - (gp[0] - 2.0 * f[0] + gm[0]) / 1e-8) / (1.0 + fabs(f[2])));
        }
    }
    print_message("delta IK: θ against the path model's Newton %.3g rad; θ̇, θ̈ against its q̇, q̈ %.3g, %.3g "
                  "(relative); against central differences %.3g, %.3g\n",
                  e_q, e_qd, e_qdd, e_fd1, e_fd2);
    assert_true(e_q <= 1e-12);
    assert_true(e_qd <= 1e-10);
    assert_true(e_qdd <= 1e-10);
    assert_true(e_fd1 <= 1e-7);
    assert_true(e_fd2 <= 1e-5);
    vt_data_free(d);
    vt_model_free(mi);
    vt_model_free(m);
}

/* 5. the IK model's kinematic analysis: its platform on the path, its forward check (the motor
 * torques applied, the motor drives removed), and its efforts and reactions against the two-model
 * route (the path model's motion given to the motor model, as the example used to print) */
static void test_ik_model(void **state)
{
    (void)state;
    vt_model *m, *mm, *mi;
    vt_data *d, *dm, *di;
    vt_trajectory *tr, *ti;
    vt_delta_ik ik;
    run_path(&m, &d, &tr, 1.0, 100, 0);
    assert_ok(vt_scene_delta(&mm, 1.0, VT_DELTA_MOTORS));
    assert_ok(vt_data_create(&dm, mm));
    assert_ok(vt_scene_delta_ik(&mi, &ik, 1.0));
    assert_ok(vt_data_create(&di, mi));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.0;
    opt.nout = 100;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.forward_check = VT_HAVE_SUNDIALS;
    assert_ok(vt_trajectory_create(&ti, mi, 101));
    double p0[3];
    vt_scene_delta_path(0.0, 1.0, p0, NULL, NULL);
    assert_int_equal(vt_scene_delta_assemble(mi, di, p0), 0);
    assert_ok(vt_kinematic_analysis(mi, di, &opt, ti));
    assert_int_equal(ti->nfilled, 101);
    const int pq = mi->body_qadr[10];
    double path = 0.0, dev = 0.0, tau_max = 0.0, e_tau = 0.0, f_max = 0.0, e_f = 0.0;
    for (int k = 0; k < ti->nfilled; k++) {
        const double *q = ti->q + (size_t)k * (size_t)mi->nq, *qf = ti->q_fwd + (size_t)k * (size_t)mi->nq;
        double p[3], e = 0.0;
        assert_near(ti->t[k], tr->t[k], 1e-15);
        vt_scene_delta_path(ti->t[k], 1.0, p, NULL, NULL);
        for (int c = 0; c < 3; c++) {
            path = fmax(path, fabs(q[pq + c] - p[c]));
            e += (qf[pq + c] - q[pq + c]) * (qf[pq + c] - q[pq + c]);
        }
        dev = fmax(dev, sqrt(e));
        assert_near(q[pq + 3], 1.0, 1e-12);
        for (int c = 4; c < 7; c++) assert_near(q[pq + c], 0.0, 1e-12);
        motors_at_row(mm, dm, tr, k);
        for (int i = 0; i < 3; i++) {
            tau_max = fmax(tau_max, fabs(dm->drive_effort[i]));
            e_tau = fmax(e_tau, fabs(ti->drive_effort[(size_t)k * 3 + (size_t)i] - dm->drive_effort[i]));
        }
        /* every bearing: the motors' and elbows' (bodies 1..9) and the ball joints */
        const double *jf = ti->jnt_force + (size_t)k * 3 * (size_t)(mi->nbody + 1);
        const double *jm = ti->jnt_moment + (size_t)k * 3 * (size_t)(mi->nbody + 1);
        const double *cf = ti->cut_force + (size_t)k * 3 * (size_t)mi->ncut;
        for (int c = 3; c < 30; c++) {
            f_max = fmax(f_max, fabs(dm->jnt_force[c]));
            e_f = fmax(e_f, fmax(fabs(jf[c] - dm->jnt_force[c]), fabs(jm[c] - dm->jnt_moment[c])));
        }
        for (int c = 0; c < 18; c++) e_f = fmax(e_f, fabs(cf[c] - dm->cut_force[c]));
    }
    print_message("delta IK model: platform on the path %.3g m, forward check %.3g m (%ld IDA steps); against the "
                  "two-model route: torques %.3g of %.4g N m, reactions %.3g of %.4g N\n",
                  path, dev, ti->steps_fwd, e_tau, tau_max, e_f, f_max);
    assert_true(path <= 1e-10);
#if VT_HAVE_SUNDIALS
    assert_true(dev <= 1e-10);
    assert_true(dev > 0.0); /* a separate integration, not the driven run copied */
#endif
    assert_true(tau_max > 1.0);
    assert_true(e_tau <= 1e-9 * tau_max);
    assert_true(e_f <= 1e-9 * f_max);
    vt_trajectory_free(ti);
    vt_trajectory_free(tr);
    vt_data_free(di);
    vt_data_free(dm);
    vt_data_free(d);
    vt_model_free(mi);
    vt_model_free(mm);
    vt_model_free(m);
}

/* the scene's refusals */
static void test_bad_options(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_int_equal(vt_scene_delta(&m, 0.0, VT_DELTA_PATH), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_scene_delta(&m, INFINITY, VT_DELTA_PATH), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_scene_delta(&m, 1.0, 7), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_scene_delta(&m, 1.0, VT_DELTA_IK), VT_ERR_BAD_OPTION); /* needs vt_scene_delta_ik */
    vt_delta_ik ik;
    assert_int_equal(vt_scene_delta_ik(&m, NULL, 1.0), VT_ERR_NULL);
    assert_int_equal(vt_scene_delta_ik(&m, &ik, 0.0), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_scene_delta_ik(&m, &ik, NAN), VT_ERR_BAD_OPTION);
    assert_null(m);
    double th[3] = {0.0, 0.0, 0.0};
    const double far2[3] = {0.0, 0.0, -2.0}, zero[3] = {0.0, 0.0, 0.0};
    assert_int_equal(vt_scene_delta_motor(0, far2, zero, zero, th), -1);
    assert_ok(vt_scene_delta(&m, 1.0, VT_DELTA_PATH));
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    const double far[3] = {0.0, 0.0, -2.0}; /* beyond the arms' reach */
    assert_int_equal(vt_scene_delta_assemble(m, d, far), -1);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
#if VT_HAVE_SUNDIALS
        cmocka_unit_test(test_forward_check),
#endif
        cmocka_unit_test(test_quasi_static),
        cmocka_unit_test(test_power_balance),
        cmocka_unit_test(test_ik_angles),
        cmocka_unit_test(test_ik_model),
        cmocka_unit_test(test_bad_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
