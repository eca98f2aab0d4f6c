/* The Stewart–Gough platform of examples/scenes.c (vt_scene_stewart, docs/stewart.md) against
 * what does not come from vtdyn's solve:
 * - the scene's inverse kinematics: the assembled state closes every loop (Φ = 0, Φ̇ = 0) and
 *   the drives' leg lengths have the rates and accelerations of their central differences;
 * - the statics in closed form: at rest, each leg (cylinder and piston) is held by its
 *   universal joint, which carries no moment (its one moment component, along e1 × e2, is
 *   not perpendicular to the leg, and the moments about the leg axis balance), so the moment
 *   about the universal's centre fixes the transverse part of the spherical joint's force:
 *   F_i = s_i u_i + t_i, t_i = −(m_c d_c + m_p d_p)/L_i (g − (g·u_i) u_i) (d_c, d_p the centres
 *   of mass from the universal's centre along the leg); the platform's balance
 *   Σ F_i = m_P g, Σ ρ_i × F_i = 0 (ρ_i = A b_i) is the static Jacobian equation J^T s = W,
 *   6 x 6, solved by LAPACK; the piston's balance along u_i gives the actuator force
 *   f_i = −s_i − m_p g·u_i, the universal's reaction −F_i − (m_c + m_p) g and the prismatic
 *   joint's −F_i − m_p g − f_i u_i. Legs with their mass and inertia, exact;
 * - over a period of the moving pose: the platform on its prescribed pose, the forward check,
 *   and the power balance Σ f_i L̇_i = d(T + V)/dt with T and V from the bodies' velocities
 *   and accelerations. */
#include "vt_test.h"

#define PI 3.14159265358979323846

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(double c[3], const double *a, const double *b)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void test_assembly_closes_and_lengths_differentiate(void **state)
{
    (void)state;
    vt_stewart sg = {2.0 * PI, 0.3, {{0}}};
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_stewart(&m, &sg));
    assert_int_equal(m->nv, 24);
    assert_int_equal(m->nc, 24);
    assert_ok(vt_data_create(&d, m));
    for (int k = 0; k < 7; k++) {
        const double t = 0.137 * k;
        vt_scene_stewart_assemble(m, d, &sg, t);
        assert_ok(vt_kinematics(m, d));
        assert_ok(vt_constraints(m, d));
        for (int r = 0; r < m->nc; r++) {
            double phid = d->Phit[r];
            for (int c = 0; c < m->nv; c++) phid += d->Phiq[r + m->nc * c] * d->qd[c];
            assert_near(d->Phi[r], 0.0, 1e-14);
            assert_near(phid, 0.0, 1e-13);
        }
        for (int i = 0; i < m->ndrive; i++) {
            double f[3], fp[3], fm[3], f2p[3], f2m[3];
            const double h = 1e-4;
            assert_ok(vt_function_eval(f, &m->drive[i].f, t));
            assert_ok(vt_function_eval(fp, &m->drive[i].f, t + h));
            assert_ok(vt_function_eval(fm, &m->drive[i].f, t - h));
            assert_ok(vt_function_eval(f2p, &m->drive[i].f, t + 2 * h));
            assert_ok(vt_function_eval(f2m, &m->drive[i].f, t - 2 * h));
            assert_true(f[0] > 0.8 && f[0] < 1.2); /* the legs' realistic range */
            /* fourth-order central differences: error ~ h⁴ f⁽⁵⁾ */
            assert_near(f[1], (8 * (fp[0] - fm[0]) - (f2p[0] - f2m[0])) / (12 * h), 1e-9);
            assert_near(f[2], (16 * (fp[0] + fm[0]) - (f2p[0] + f2m[0]) - 30 * f[0]) / (12 * h * h), 1e-6);
            assert_near(f[2], (8 * (fp[1] - fm[1]) - (f2p[1] - f2m[1])) / (12 * h), 1e-8);
        }
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* the closed-form statics above, at the prescribed pose of sg at rest */
static void closed_form(const vt_stewart *sg, const double g[3], double f[6], double F[18], double U[18],
                        double P[18])
{
    double r[9], p[4], w[6], A[9], u[18], t[18], K[36], s[6];
    vt_scene_stewart_pose(sg, 0.0, r, p, w);
    /* A(p) from the Euler parameters, written out here (not vtdyn's) */
    const double p0 = p[0], p1 = p[1], p2 = p[2], p3 = p[3];
    A[0] = 2 * (p0 * p0 + p1 * p1) - 1; A[3] = 2 * (p1 * p2 - p0 * p3);     A[6] = 2 * (p1 * p3 + p0 * p2);
    A[1] = 2 * (p1 * p2 + p0 * p3);     A[4] = 2 * (p0 * p0 + p2 * p2) - 1; A[7] = 2 * (p2 * p3 - p0 * p1);
    A[2] = 2 * (p1 * p3 - p0 * p2);     A[5] = 2 * (p2 * p3 + p0 * p1);     A[8] = 2 * (p0 * p0 + p3 * p3) - 1;
    double W[6] = {VT_SG_M_PLAT * g[0], VT_SG_M_PLAT * g[1], VT_SG_M_PLAT * g[2], 0, 0, 0};
    for (int i = 0; i < 6; i++) {
        double a[3], b[3], rho[3], l[3], c[3];
        vt_scene_stewart_points(i, a, b);
        for (int k = 0; k < 3; k++) rho[k] = A[k] * b[0] + A[k + 3] * b[1] + A[k + 6] * b[2];
        for (int k = 0; k < 3; k++) l[k] = r[k] + rho[k] - a[k];
        const double L = sqrt(dot3(l, l));
        double *ui = u + 3 * i, *ti = t + 3 * i;
        for (int k = 0; k < 3; k++) ui[k] = l[k] / L;
        const double Kl = (VT_SG_M_CYL * VT_SG_HALF + VT_SG_M_PIST * (L - VT_SG_HALF)) / L, gu = dot3(g, ui);
        for (int k = 0; k < 3; k++) ti[k] = -Kl * (g[k] - gu * ui[k]);
        /* column i of J^T: [u_i; ρ_i × u_i]; W − Σ [t_i; ρ_i × t_i] on the right */
        cross3(c, rho, ui);
        for (int k = 0; k < 3; k++) {
            K[k + 6 * i] = ui[k];
            K[3 + k + 6 * i] = c[k];
        }
        cross3(c, rho, ti);
        for (int k = 0; k < 3; k++) {
            W[k] -= ti[k];
            W[3 + k] -= c[k];
        }
    }
    int n = 6, one = 1, ipiv[6], info = 0;
    memcpy(s, W, sizeof s);
    dgesv_(&n, &one, K, &n, ipiv, s, &n, &info);
    assert_int_equal(info, 0);
    for (int i = 0; i < 6; i++) {
        const double *ui = u + 3 * i;
        f[i] = -s[i] - VT_SG_M_PIST * dot3(g, ui);
        for (int k = 0; k < 3; k++) {
            F[3 * i + k] = s[i] * ui[k] + t[3 * i + k];
            U[3 * i + k] = -F[3 * i + k] - (VT_SG_M_CYL + VT_SG_M_PIST) * g[k];
            P[3 * i + k] = -F[3 * i + k] - VT_SG_M_PIST * g[k] - f[i] * ui[k];
        }
    }
}

static void test_static_closed_form(void **state)
{
    (void)state;
    double worst = 0.0;
    for (int pass = 0; pass < 2; pass++) /* vt_inverse_dynamics, then the recursive path */
        for (int k = 0; k < 6; k++) {
            vt_stewart sg = {0.0, 1.047 * k + 0.2, {{0}}};
            vt_model *m;
            vt_data *d;
            assert_ok(vt_scene_stewart(&m, &sg));
            assert_ok(vt_data_create(&d, m));
            vt_scene_stewart_assemble(m, d, &sg, 0.0);
            for (int c = 0; c < m->nv; c++) assert_true(d->qd[c] == 0.0);
            assert_ok(pass ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d));
            double f[6], F[18], U[18], P[18];
            closed_form(&sg, m->gravity, f, F, U, P);
            double scale = 0.0;
            for (int i = 0; i < 6; i++) scale = fmax(scale, fabs(f[i]));
            const double tol = 1e-9 * scale;
            for (int i = 0; i < 6; i++) {
                worst = fmax(worst, fabs(d->drive_effort[i] - f[i]) / scale);
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fmax(fabs(d->cut_force[3 * i + c] - F[3 * i + c]),
                                             fabs(d->jnt_force[3 * (2 + 2 * i) + c] - U[3 * i + c])) / scale);
            }
            for (int i = 0; i < 6; i++) {
                const int cyl = 2 + 2 * i, pis = 3 + 2 * i;
                assert_int_equal(m->drive[i].body, pis);
                assert_near(d->drive_effort[i], f[i], tol);
                for (int c = 0; c < 3; c++) {
                    assert_near(d->cut_force[3 * i + c], F[3 * i + c], tol);
                    assert_near(d->jnt_force[3 * cyl + c], U[3 * i + c], tol);
                    assert_near(d->jnt_moment[3 * cyl + c], 0.0, tol * 1.0); /* N·m on a 1 m leg */
                    assert_near(d->jnt_force[3 * pis + c], P[3 * i + c], tol);
                }
            }
            /* the ground's six universal forces carry the whole weight */
            double Uz = 0.0;
            for (int i = 0; i < 6; i++) Uz += d->jnt_force[3 * (2 + 2 * i) + 2];
            assert_near(Uz, 9.81 * (VT_SG_M_PLAT + 6 * (VT_SG_M_CYL + VT_SG_M_PIST)), 1e-9 * Uz);
            vt_data_free(d);
            vt_model_free(m);
        }
    print_message("static closed form: largest difference %.3g of the largest leg force\n", worst);
}

/* d(T + V)/dt = Σ m v·a + ω·(J ω̇) − m g·v, ω̇ = 2 E(p) p̈ with E written out */
static double energy_rate(const vt_model *m, const vt_data *d)
{
    double P = 0.0;
    for (int b = 1; b <= m->nbody; b++) {
        const double *v = d->xd + 7 * (b - 1), *a = d->xdd + 7 * (b - 1), *w = d->omega + 3 * b;
        const double *p = d->x + 7 * (b - 1) + 3, *pdd = a + 3;
        /* E(p) = [−e, ẽ + p0 I]: ω̇ = 2 (−e p̈0 + e × p̈_e + p0 p̈_e) */
        const double e[3] = {p[1], p[2], p[3]}, ed[3] = {pdd[1], pdd[2], pdd[3]};
        double wd[3], J[9];
        cross3(wd, e, ed);
        for (int k = 0; k < 3; k++) wd[k] = 2.0 * (-e[k] * pdd[0] + wd[k] + p[0] * ed[k]);
        vt_test_global_inertia(J, m, d, b);
        for (int k = 0; k < 3; k++)
            P += m->body_mass[b] * (v[k] * a[k] - m->gravity[k] * v[k]) +
                 w[k] * (J[k] * wd[0] + J[k + 3] * wd[1] + J[k + 6] * wd[2]);
    }
    return P;
}

static void test_period_pose_forward_power(void **state)
{
    (void)state;
    vt_stewart sg = {2.0 * PI, 0.0, {{0}}};
    vt_model *m;
    vt_data *d, *di;
    vt_trajectory *tr;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.0;
    opt.nout = 50;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    assert_ok(vt_scene_stewart(&m, &sg));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&di, m));
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    vt_scene_stewart_assemble(m, d, &sg, 0.0);
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nfilled, opt.nout + 1);
    assert_true(tr->fwd_err_q <= 1e-9);
    double pmax = 0.0, perr = 0.0, dyn = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + m->nq * k;
        double r[9], p[4], w[6];
        vt_scene_stewart_pose(&sg, tr->t[k], r, p, w);
        for (int c = 0; c < 3; c++) assert_near(q[c], r[c], 1e-10);
        for (int c = 0; c < 4; c++) assert_near(q[3 + c], p[c], 1e-10);
        for (int c = 0; c < 3; c++) assert_near(tr->q_fwd[m->nq * k + c], r[c], 1e-6);
        /* the row's state again, with its velocities and accelerations */
        vt_scene_stewart_assemble(m, di, &sg, tr->t[k]);
        for (int c = 0; c < m->nv; c++) assert_near(tr->qd[m->nv * k + c], di->qd[c], 1e-9);
        assert_ok(vt_inverse_dynamics(m, di));
        double P = 0.0;
        for (int i = 0; i < 6; i++) {
            assert_near(di->drive_effort[i], tr->drive_effort[6 * k + i], 1e-6);
            P += di->drive_effort[i] * di->qd[m->body_vadr[3 + 2 * i]];
        }
        pmax = fmax(pmax, fabs(P));
        perr = fmax(perr, fabs(P - energy_rate(m, di)));
        /* the motion is fast: its leg forces are not the static ones */
        vt_stewart still = {0.0, sg.phase + sg.omega * tr->t[k], {{0}}};
        double f[6], F[18], U[18], Pp[18];
        closed_form(&still, m->gravity, f, F, U, Pp);
        for (int i = 0; i < 6; i++) dyn = fmax(dyn, fabs(di->drive_effort[i] - f[i]));
    }
    print_message("power balance: max error %.3g W of %.4g W; largest dynamic part of a leg force %.4g N\n", perr,
                  pmax, dyn);
    assert_true(pmax > 10.0);
    assert_true(perr <= 1e-9 * pmax);
    assert_true(dyn > 1.0);
    vt_trajectory_free(tr);
    vt_data_free(di);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_assembly_closes_and_lengths_differentiate),
        cmocka_unit_test(test_static_closed_form),
        cmocka_unit_test(test_period_pose_forward_power),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
