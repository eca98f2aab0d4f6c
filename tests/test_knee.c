/* The knee four-bar of examples/scenes.c (vt_scene_knee, docs/knee.md), a planar loop of
 * revolute joints closed by a planar revolute cut joint, against what does not come from
 * vtdyn's solve:
 * - the scene's loop closure: the assembled state closes the loop (Φ = 0, Φ̇ = 0);
 * - the statics in closed form, planar, at rest: the lever point C from a Newton solve of
 *   |C(ψ) − B| = b written here; the force F of the shank on the coupler from the moments of
 *   the coupler about the crank's tip B and of the shank about the knee K,
 *     (C − B) × F + (G_cp − B) × m_cp g = 0,   (C − K) × (−F) + (G_s − K) × m_s g = 0;
 *   then the crank's moment about the hip gives the motor torque
 *     τ_m = −[B × (F + m_cp g) + G_c × m_c g]_z,
 *   the whole leg's the hip torque τ_hip = −Σ [G_i × m_i g]_z, and the bearings' forces
 *   follow from each body's force balance (the knee's F − m_s g, the crank–coupler revolute's
 *   −F − m_cp g, the motor bearing's −F − (m_cp + m_c) g);
 * - over two strides: the knee angle on the loop's closure, the forward check, and the power
 *   balance τ_hip q̇1 + τ_m q̇2 = d(T + V)/dt from the bodies' velocities and accelerations;
 * - over the strides, the same loop closed by the full 5-row revolute with allow_redundant (a
 *   second constraint set, solved by least squares): the same torques and in-plane forces. */
#include "vt_test.h"

#define PI 3.14159265358979323846

static double cross2(const double *a, const double *b) { return a[0] * b[1] - a[1] * b[0]; }

static void test_assembly_closes(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_knee(&m, vt_function_constant(0.0), vt_function_constant(0.0), 1));
    assert_int_equal(m->nv, 4); /* four revolutes */
    assert_int_equal(m->nc, 4); /* two drives, the pin's two in-plane rows */
    assert_int_equal(m->allow_redundant, 0);
    assert_ok(vt_data_create(&d, m));
    uint64_t s = 7;
    for (int k = 0; k < 20; k++) {
        const double th1 = vt_rand_uniform(&s, -PI, PI), thm = vt_rand_uniform(&s, 0.5 * PI - 0.6, 0.5 * PI + 0.6);
        assert_int_equal(vt_scene_knee_assemble(m, d, th1, vt_rand_uniform(&s, -3, 3), thm, vt_rand_uniform(&s, -3, 3), NULL), 0);
        assert_ok(vt_kinematics(m, d));
        assert_ok(vt_constraints(m, d));
        for (int r = 2; r < m->nc; r++) { /* the cut's rows (the drives' are not at these angles) */
            double phid = d->Phit[r];
            for (int c = 0; c < m->nv; c++) phid += d->Phiq[r + m->nc * c] * d->qd[c];
            assert_near(d->Phi[r], 0.0, 1e-15);
            assert_near(phid, 0.0, 1e-14);
        }
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* the closed-form statics: efforts tau[2], the shank's force on the coupler F[2], the knee's,
 * the crank–coupler revolute's and the motor bearing's forces R[6] (global, planar) */
static void closed_form(double th1, double thm, double tau[2], double F[2], double R[6])
{
    const double g[2] = {0.0, -9.81}, mt = 1.5, mc = 0.1, mcp = 0.08, ms = 0.5;
    const double cs = 0.5 * (VT_KN_C + VT_KN_L) - VT_KN_C;
    /* thigh frame: B on the crank circle; ψ from Newton on |K + c e(ψ) − B|² = b², from ψ = θm */
    const double Bt[2] = {VT_KN_A * cos(thm), VT_KN_A * sin(thm)};
    double psi = thm;
    for (int it = 0; it < 50; it++) {
        const double dx = VT_KN_D + VT_KN_C * cos(psi) - Bt[0], dy = VT_KN_C * sin(psi) - Bt[1];
        const double r = dx * dx + dy * dy - VT_KN_B * VT_KN_B;
        const double dr = 2.0 * (-dx * VT_KN_C * sin(psi) + dy * VT_KN_C * cos(psi));
        psi -= r / dr;
    }
    const double Ct[2] = {VT_KN_D + VT_KN_C * cos(psi), VT_KN_C * sin(psi)};
    /* to global: turn by th1 about the hip (the origin) */
    const double c1 = cos(th1), s1 = sin(th1);
#define G(out, p) do { (out)[0] = c1 * (p)[0] - s1 * (p)[1]; (out)[1] = s1 * (p)[0] + c1 * (p)[1]; } while (0)
    double B[2], C[2], K[2], Gt[2], Gc[2], Gcp[2], Gs[2];
    const double Kt[2] = {VT_KN_D, 0.0}, Gtt[2] = {0.5 * VT_KN_D, 0.0}, Gct[2] = {0.5 * Bt[0], 0.5 * Bt[1]};
    const double Gcpt[2] = {0.5 * (Bt[0] + Ct[0]), 0.5 * (Bt[1] + Ct[1])};
    const double Gst[2] = {VT_KN_D - cs * cos(psi), -cs * sin(psi)}; /* the shank points away from its lever */
    G(B, Bt); G(C, Ct); G(K, Kt); G(Gt, Gtt); G(Gc, Gct); G(Gcp, Gcpt); G(Gs, Gst);
#undef G
    /* the two moment equations, linear in F: rows [−(C−B)_y, (C−B)_x] F = −(G_cp − B) × m_cp g,
     * [(C−K)_y, −(C−K)_x] F = −(G_s − K) × m_s g */
    const double CB[2] = {C[0] - B[0], C[1] - B[1]}, CK[2] = {C[0] - K[0], C[1] - K[1]};
    const double gcp[2] = {mcp * g[0], mcp * g[1]}, gs[2] = {ms * g[0], ms * g[1]};
    const double GB[2] = {Gcp[0] - B[0], Gcp[1] - B[1]}, GK[2] = {Gs[0] - K[0], Gs[1] - K[1]};
    const double a11 = -CB[1], a12 = CB[0], b1 = -cross2(GB, gcp);
    const double a21 = CK[1], a22 = -CK[0], b2 = -cross2(GK, gs);
    const double det = a11 * a22 - a12 * a21;
    F[0] = (b1 * a22 - a12 * b2) / det;
    F[1] = (a11 * b2 - a21 * b1) / det;
    const double Fc[2] = {F[0] + gcp[0], F[1] + gcp[1]}, gc[2] = {mc * g[0], mc * g[1]}, gt[2] = {mt * g[0], mt * g[1]};
    tau[1] = -(cross2(B, Fc) + cross2(Gc, gc));
    tau[0] = -(cross2(Gt, gt) + cross2(Gc, gc) + cross2(Gcp, gcp) + cross2(Gs, gs));
    for (int k = 0; k < 2; k++) {
        R[k] = F[k] - ms * g[k];                  /* thigh on shank at the knee */
        R[2 + k] = -F[k] - mcp * g[k];            /* crank on coupler at their revolute */
        R[4 + k] = -F[k] - (mcp + mc) * g[k];     /* thigh on crank at the hip */
    }
}

static void test_static_closed_form(void **state)
{
    (void)state;
    double worst = 0.0;
    uint64_t s = 3;
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < 10; k++) {
            const double th1 = vt_rand_uniform(&s, -PI, PI), thm = vt_rand_uniform(&s, 0.5 * PI - 0.5, 0.5 * PI + 0.5);
            vt_model *m;
            vt_data *d;
            assert_ok(vt_scene_knee(&m, vt_function_constant(th1), vt_function_constant(thm), 1));
            assert_ok(vt_data_create(&d, m));
            assert_int_equal(vt_scene_knee_assemble(m, d, th1, 0.0, thm, 0.0, NULL), 0);
            assert_ok(pass ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d));
            double tau[2], F[2], R[6];
            closed_form(th1, thm, tau, F, R);
            const double scale = fmax(fabs(tau[0]), 1.0); /* N·m over a 0.3 m leg, N */
            for (int j = 0; j < 2; j++) {
                assert_near(d->drive_effort[j], tau[j], 1e-9 * scale);
                worst = fmax(worst, fabs(d->drive_effort[j] - tau[j]) / scale);
            }
            const double Fs = fmax(hypot(F[0], F[1]), 1.0);
            for (int c = 0; c < 2; c++) {
                const double got[4] = {d->cut_force[c], d->jnt_force[3 * 4 + c], d->jnt_force[3 * 3 + c], d->jnt_force[3 * 2 + c]};
                const double want[4] = {F[c], R[c], R[2 + c], R[4 + c]};
                for (int j = 0; j < 4; j++) {
                    assert_near(got[j], want[j], 1e-9 * Fs);
                    worst = fmax(worst, fabs(got[j] - want[j]) / Fs);
                }
            }
            assert_near(d->cut_force[2], 0.0, 1e-9 * Fs); /* the pin's force is in the plane */
            for (int c = 0; c < 3; c++) assert_near(d->cut_moment[c], 0.0, 1e-9 * Fs);
            vt_data_free(d);
            vt_model_free(m);
        }
    print_message("static closed form: largest relative difference %.3g\n", worst);
}

/* d(T + V)/dt = Σ m v·a + ω·(J ω̇) − m g·v, ω̇ = 2 E(p) p̈ with E written out */
static double energy_rate(const vt_model *m, const vt_data *d)
{
    double P = 0.0;
    for (int b = 1; b <= m->nbody; b++) {
        const double *v = d->xd + 7 * (b - 1), *a = d->xdd + 7 * (b - 1), *w = d->omega + 3 * b;
        const double *p = d->x + 7 * (b - 1) + 3, *pdd = a + 3;
        double wd[3], J[9];
        wd[0] = 2.0 * (-p[1] * pdd[0] + p[2] * pdd[3] - p[3] * pdd[2] + p[0] * pdd[1]);
        wd[1] = 2.0 * (-p[2] * pdd[0] + p[3] * pdd[1] - p[1] * pdd[3] + p[0] * pdd[2]);
        wd[2] = 2.0 * (-p[3] * pdd[0] + p[1] * pdd[2] - p[2] * pdd[1] + p[0] * pdd[3]);
        vt_test_global_inertia(J, m, d, b);
        for (int k = 0; k < 3; k++)
            P += m->body_mass[b] * (v[k] * a[k] - m->gravity[k] * v[k]) +
                 w[k] * (J[k] * wd[0] + J[k + 3] * wd[1] + J[k + 6] * wd[2]);
    }
    return P;
}

static void test_strides_forward_power(void **state)
{
    (void)state;
    const double om = 4.0 * PI;
    vt_model *m, *mr;
    vt_data *d, *di, *dr;
    vt_trajectory *tr;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.0;
    opt.nout = 50;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    assert_ok(vt_scene_knee(&m, vt_function_sine(-0.25 * PI, 0.35, om, 0.0), vt_function_sine(0.5 * PI, 0.4, om, 0.8), 1));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&di, m));
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    /* the full revolute: 2 drives and 5 cut rows of rank 4 on the 4 rates */
    assert_ok(vt_scene_knee(&mr, vt_function_sine(-0.25 * PI, 0.35, om, 0.0), vt_function_sine(0.5 * PI, 0.4, om, 0.8), 0));
    assert_int_equal(mr->nc, 7);
    assert_int_equal(mr->allow_redundant, 1);
    assert_ok(vt_data_create(&dr, mr));
    assert_int_equal(vt_scene_knee_assemble(m, d, -0.25 * PI, 0.35 * om, 0.5 * PI + 0.4 * sin(0.8), 0.4 * om * cos(0.8), NULL), 0);
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, opt.nout + 1);
    assert_true(tr->fwd_err_q <= 1e-10);
    double pmax = 0.0, perr = 0.0, rworst = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + m->nq * k, *qd = tr->qd + m->nv * k;
        double kn[2];
        assert_int_equal(vt_scene_knee_assemble(m, di, q[0], qd[0], q[1], qd[1], kn), 0);
        assert_near(remainder(q[m->body_qadr[4]] - kn[0], 2.0 * PI), 0.0, 1e-10);
        assert_near(qd[m->body_vadr[4]], kn[1], 1e-9);
        di->time = tr->t[k];
        memcpy(di->q, q, (size_t)m->nq * sizeof(double));
        memcpy(di->qd, qd, (size_t)m->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics(m, di));
        const double P = di->drive_effort[0] * qd[0] + di->drive_effort[1] * qd[1];
        pmax = fmax(pmax, fabs(P));
        perr = fmax(perr, fabs(P - energy_rate(m, di)));
        /* the full revolute at the same state: the torques, the cut's and every joint's
         * in-plane force (the out-of-plane loads of its dependent rows are not unique) */
        dr->time = tr->t[k];
        memcpy(dr->q, q, (size_t)m->nq * sizeof(double));
        memcpy(dr->qd, qd, (size_t)m->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics(mr, dr));
        assert_int_equal(dr->rank, 4);
        const double fs = 1.0 + vt_test_maxabs(di->jnt_force + 3, 12);
        for (int j = 0; j < 2; j++) {
            assert_near(dr->drive_effort[j], di->drive_effort[j], 1e-10 * fs);
            assert_int_equal(dr->cut_unique[j], 1);
            assert_near(dr->cut_force[j], di->cut_force[j], 1e-10 * fs);
            rworst = fmax(rworst, fabs(dr->drive_effort[j] - di->drive_effort[j]) / fs);
            rworst = fmax(rworst, fabs(dr->cut_force[j] - di->cut_force[j]) / fs);
            for (int i = 1; i <= 4; i++) {
                assert_int_equal(dr->jnt_unique[6 * i + j], 1);
                assert_near(dr->jnt_force[3 * i + j], di->jnt_force[3 * i + j], 1e-10 * fs);
                rworst = fmax(rworst, fabs(dr->jnt_force[3 * i + j] - di->jnt_force[3 * i + j]) / fs);
            }
        }
    }
    print_message("power balance: max error %.3g W of %.4g W\n", perr, pmax);
    print_message("full 5-row revolute against the planar pin: largest difference %.3g (relative)\n", rworst);
    assert_true(pmax > 1.0);
    assert_true(perr <= 1e-9 * pmax);
    vt_trajectory_free(tr);
    vt_data_free(dr);
    vt_data_free(di);
    vt_data_free(d);
    vt_model_free(mr);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_assembly_closes),
        cmocka_unit_test(test_static_closed_form),
        cmocka_unit_test(test_strides_forward_power),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
