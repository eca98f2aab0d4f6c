/* src/kinematics/joint_effects.c: the joints' armature, damping and friction in every effort.
 *   closed form   a planar double link (two 2 m, 100 kg rods on revolute joints about z) whose
 *                 equations of motion are written here (Lagrange, absolute angles):
 *                   τ = M(q) q̈ + c(q, q̇) + g(q) + a q̈ + b q̇ + f s(q̇)
 *                 both joints driven, on the dense, recursive and given-motion paths; joint 2
 *                 left free (its q̈ from the second row, the passive effects in it), on the dense
 *                 and recursive paths; the parts (armature q̈, damping q̇, friction s(q̇)) and a
 *                 gear ratio stated on the motor's side.
 *   friction law  s = sign with 0 at rest, or tanh(q̇ / v).
 *   loops         the knee four-bar with only the hip driven (the crank and shank joints free):
 *                 damping and friction equal the same generalized forces applied as qfrc on the
 *                 model without them; armature on the hip (whose reference is the ground) equals
 *                 a massless rotor body of that inertia on the hip's axis coupled to the hip
 *                 rate (a coupling of ratio 1), on both paths.
 *   forward check a dynamic analysis of the double link with every effect: the efforts applied
 *                 to the forward run reproduce the motion.
 *   validation    negative, NaN or infinite values and a zero gear ratio refused, named. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"
#include "vt_test.h"

#define L 2.0
#define MASS 100.0
#define G 9.81

static const double arm[2] = {0.7, 0.3}, damp[2] = {2.0, 1.5}, fric[2] = {3.0, 1.2};

/* the double link; drives: 1 joint 1 by f1, 2 joint 2 by f2 (a mask); effects: 1 with arm, damp
 * and fric (joint 2's stated on the motor's side of a 10:1 gear), 0 without; smooth: the friction
 * velocity (0: the sign) */
static vt_builder *double_link_builder(int drives, int effects, double smooth)
{
    vt_builder *b;
    assert_int_equal(vt_builder_create(&b, NULL), VT_OK);
    for (int i = 1; i <= 2; i++) {
        vt_body_def body = vt_default_body_def();
        body.parent = i - 1;
        body.mass = MASS;
        body.inertia[0] = 1e-3;
        body.inertia[4] = body.inertia[8] = MASS * L * L / 12.0;
        body.joint_child[0] = -0.5 * L;
        if (i == 2) body.joint_parent[0] = 0.5 * L;
        if (effects) {
            const double N = i == 2 ? 10.0 : 1.0; /* motor-side values: J / N², b / N², f / N */
            body.gear_ratio[0] = i == 2 ? -N : 1.0; /* the sign of the ratio changes nothing */
            body.armature[0] = arm[i - 1] / (N * N);
            body.damping[0] = damp[i - 1] / (N * N);
            body.friction[0] = fric[i - 1] / N;
            body.friction_velocity[0] = smooth;
        }
        assert_int_equal(vt_builder_add_body(b, &body), i);
    }
    for (int k = 0; k < 2; k++) {
        if (!(drives & (1 << k))) continue;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = 1 + k;
        dr.f = k ? vt_function_sine(0.4, 0.8, 1.7, 0.3) : vt_function_sine(-0.5, 0.6, 1.1, 0.0);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    return b;
}

static vt_model *built(vt_builder *b)
{
    vt_model *m;
    assert_int_equal(vt_builder_build(&m, b), VT_OK);
    vt_builder_free(b);
    return m;
}

static vt_model *double_link(int drives, int effects, double smooth)
{
    return built(double_link_builder(drives, effects, smooth));
}

static double sgn(double v)
{
    return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0;
}

/* the rigid-body part: M (2 x 2, row-major) and h = c + g */
static void rigid(const double q[2], const double qd[2], double M[4], double h[2])
{
    const double lc = 0.5 * L, I = MASS * L * L / 12.0, c2 = cos(q[1]), s2 = sin(q[1]);
    M[0] = 2.0 * I + MASS * lc * lc + MASS * (L * L + lc * lc + 2.0 * L * lc * c2);
    M[1] = M[2] = I + MASS * (lc * lc + L * lc * c2);
    M[3] = I + MASS * lc * lc;
    const double k = MASS * L * lc * s2;
    h[0] = -k * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + (MASS * lc + MASS * L) * G * cos(q[0]) +
           MASS * lc * G * cos(q[0] + q[1]);
    h[1] = k * qd[0] * qd[0] + MASS * lc * G * cos(q[0] + q[1]);
}

static void state(vt_data *d, double t, int k)
{
    d->time = t;
    d->q[0] = -0.5 + 0.6 * sin(1.1 * t);
    d->qd[0] = 0.66 * cos(1.1 * t);
    d->q[1] = 0.4 + 0.8 * sin(1.7 * t + 0.3);
    d->qd[1] = 1.36 * cos(1.7 * t + 0.3);
    if (k == 1) d->qd[1] = 0.0; /* joint 2 at rest: friction's 0 */
    if (k == 2) d->qd[0] = -d->qd[0];
}

static void test_driven_closed_form(void **state_)
{
    (void)state_;
    vt_model *m = double_link(3, 1, 0.0);
    vt_data *d;
    assert_int_equal(vt_data_create(&d, m), VT_OK);
    double worst = 0.0;
    for (int k = 0; k < 3; k++)
        for (int path = 0; path < 3; path++) {
            const double t = 0.37 + 0.61 * k;
            state(d, t, k);
            const double qdd[2] = {-0.6 * 1.21 * sin(1.1 * t), -0.8 * 2.89 * sin(1.7 * t + 0.3)};
            if (path == 2) memcpy(d->qdd, qdd, sizeof qdd);
            const vt_status st = path == 0 ? vt_inverse_dynamics(m, d)
                               : path == 1 ? vt_inverse_dynamics_recursive(m, d)
                                           : vt_inverse_dynamics_motion(m, d);
            assert_int_equal(st, VT_OK);
            double M[4], h[2];
            rigid(d->q, d->qd, M, h);
            for (int c = 0; c < 2; c++) {
                const double rb = M[2 * c] * qdd[0] + M[2 * c + 1] * qdd[1] + h[c];
                const double parts[3] = {arm[c] * qdd[c], damp[c] * d->qd[c], fric[c] * sgn(d->qd[c])};
                const double tau = rb + parts[0] + parts[1] + parts[2];
                const double got = path == 2 ? d->qfrc_drive[c] : d->drive_effort[c];
                const double err = fabs(got - tau) / (fabs(tau) + fabs(rb));
                worst = fmax(worst, err);
                if (!(err < 1e-13)) fail_msg("state %d path %d rate %d: effort %.17g, closed form %.17g", k, path, c, got, tau);
                assert_true(fabs(d->effort_armature[c] - parts[0]) <= 1e-15 * fabs(parts[0]));
                assert_true(fabs(d->effort_damping[c] - parts[1]) <= 1e-15 * fabs(parts[1]));
                assert_true(d->effort_friction[c] == parts[2]);
            }
        }
    print_message("both joints driven, dense, recursive and given motion: largest relative error %.3g\n", worst);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_passive_closed_form(void **state_)
{
    (void)state_;
    vt_model *m = double_link(1, 1, 0.0);
    vt_data *d;
    assert_int_equal(vt_data_create(&d, m), VT_OK);
    for (int k = 0; k < 3; k++)
        for (int path = 0; path < 2; path++) {
            const double t = 0.21 + 0.5 * k;
            state(d, t, k);
            assert_int_equal(path ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d), VT_OK);
            double M[4], h[2];
            rigid(d->q, d->qd, M, h);
            const double qdd1 = -0.6 * 1.21 * sin(1.1 * t);
            /* row 2, no effort: M21 q̈1 + (M22 + a2) q̈2 + h2 + b2 q̇2 + f2 s(q̇2) = 0 */
            const double qdd2 = -(M[2] * qdd1 + h[1] + damp[1] * d->qd[1] + fric[1] * sgn(d->qd[1])) / (M[3] + arm[1]);
            const double tau = M[0] * qdd1 + M[1] * qdd2 + h[0] + arm[0] * qdd1 + damp[0] * d->qd[0] + fric[0] * sgn(d->qd[0]);
            if (!(fabs(d->qdd[1] - qdd2) <= 1e-13 * fabs(qdd2) + 1e-14))
                fail_msg("state %d path %d: q̈2 %.17g, closed form %.17g", k, path, d->qdd[1], qdd2);
            if (!(fabs(d->drive_effort[0] - tau) <= 1e-13 * fabs(tau)))
                fail_msg("state %d path %d: effort %.17g, closed form %.17g", k, path, d->drive_effort[0], tau);
            /* the free joint's passive parts are reported too */
            assert_true(fabs(d->effort_armature[1] - arm[1] * d->qdd[1]) <= 1e-15 * fabs(arm[1] * d->qdd[1]));
        }
    vt_data_free(d);
    vt_model_free(m);
}

static void test_friction_law(void **state_)
{
    (void)state_;
    vt_builder *b;
    assert_int_equal(vt_builder_create(&b, NULL), VT_OK);
    vt_body_def body = vt_default_body_def();
    body.joint_child[0] = -0.5;
    body.friction[0] = 2.0;
    body.friction_velocity[0] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_drive_def dr = vt_default_drive_def();
    dr.f = vt_function_constant(0.0);
    assert_true(vt_builder_add_drive(b, &dr) >= 0);
    vt_model *m;
    assert_int_equal(vt_builder_build(&m, b), VT_OK);
    vt_builder_free(b);
    vt_data *d;
    assert_int_equal(vt_data_create(&d, m), VT_OK);
    const double v[3] = {0.0, 0.05, -0.3};
    for (int k = 0; k < 3; k++) {
        d->qd[0] = v[k];
        d->qdd[0] = 0.0;
        assert_int_equal(vt_inverse_dynamics_motion(m, d), VT_OK);
        assert_true(fabs(d->effort_friction[0] - 2.0 * tanh(v[k] / 0.1)) <= 1e-15);
    }
    vt_data_free(d);
    vt_model_free(m);
}

static void test_validation(void **state_)
{
    (void)state_;
    vt_builder *b;
    assert_int_equal(vt_builder_create(&b, NULL), VT_OK);
    const double bad[4] = {-1.0, NAN, HUGE_VAL, 0.0};
    for (int k = 0; k < 4; k++) {
        vt_body_def body = vt_default_body_def();
        if (k < 3) body.damping[0] = bad[k];
        else body.gear_ratio[0] = 0.0;
        assert_int_equal(vt_builder_add_body(b, &body), VT_ERR_BAD_OPTION);
        assert_non_null(strstr(vt_builder_message(b), k < 3 ? "damping" : "gear_ratio"));
    }
    vt_builder_free(b);
}

/* the knee four-bar (vt_scene_knee_with), hip driven, crank and shank free */
static const double knee_mass[4] = {1.5, 0.1, 0.08, 0.5};

static void knee_state(const vt_model *m, vt_data *d, double t)
{
    d->time = t;
    assert_int_equal(vt_scene_knee_assemble(m, d, -0.785 + 0.35 * sin(2.0 * t), 0.7 * cos(2.0 * t), 1.4, -0.9, NULL), 0);
}

static void test_loop_damping_friction(void **state_)
{
    (void)state_;
    const double effects[4][3] = {{0, 0, 0}, {0, 0.8, 0.3}, {0, 0, 0}, {0, 0.5, 0.2}}; /* armature, damping, friction */
    vt_model *me, *m0;
    vt_function hip = vt_function_sine(-0.785, 0.35, 2.0, 0.0), motor = vt_function_constant(1.4);
    assert_int_equal(vt_scene_knee_with(&me, hip, motor, 1, knee_mass, 1, effects), VT_OK);
    assert_int_equal(vt_scene_knee_with(&m0, hip, motor, 1, knee_mass, 1, NULL), VT_OK);
    vt_data *de, *d0;
    assert_int_equal(vt_data_create(&de, me), VT_OK);
    assert_int_equal(vt_data_create(&d0, m0), VT_OK);
    for (int path = 0; path < 2; path++) {
        knee_state(me, de, 0.4);
        knee_state(m0, d0, 0.4);
        for (int c = 0; c < 4; c++) /* the same generalized forces, as qfrc */
            d0->qfrc[c] = -(effects[c][1] * d0->qd[c] + effects[c][2] * sgn(d0->qd[c]));
        assert_int_equal(path ? vt_inverse_dynamics_recursive(me, de) : vt_inverse_dynamics(me, de), VT_OK);
        assert_int_equal(path ? vt_inverse_dynamics_recursive(m0, d0) : vt_inverse_dynamics(m0, d0), VT_OK);
        print_message("path %d: route %d, hip effort %.6g\n", path, de->route, de->drive_effort[0]);
        for (int c = 0; c < 4; c++) assert_true(fabs(de->qdd[c] - d0->qdd[c]) <= 1e-13 * (1.0 + fabs(d0->qdd[c])));
        assert_true(fabs(de->drive_effort[0] - d0->drive_effort[0]) <= 1e-13 * fabs(d0->drive_effort[0]));
        for (int k = 0; k < 3 * 5; k++) {
            assert_true(fabs(de->jnt_force[k] - d0->jnt_force[k]) <= 1e-12 * (1.0 + fabs(d0->jnt_force[k])));
            assert_true(fabs(de->jnt_moment[k] - d0->jnt_moment[k]) <= 1e-12 * (1.0 + fabs(d0->jnt_moment[k])));
        }
    }
    vt_data_free(de);
    vt_data_free(d0);
    vt_model_free(me);
    vt_model_free(m0);
}

/* armature a on the hip (its reference is the ground, so the armature's ½ a q̇² is a rotor's
 * kinetic energy exactly): the knee with a rotor body, massless, inertia a about the hip's axis,
 * on its own revolute at the hip and coupled to the hip's rate */
static void test_loop_armature_rotor(void **state_)
{
    (void)state_;
    const double a = 0.25;
    const double effects[4][3] = {{a, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const vt_function motor = vt_function_constant(1.4);
    vt_model *me;
    assert_int_equal(vt_scene_knee_with(&me, motor, motor, 1, knee_mass, 2, effects), VT_OK); /* hip free, motor driven */
    /* the same knee with the rotor: bodies 1..4 as vt_scene_knee_with, body 5 the rotor */
    vt_builder *b;
    assert_int_equal(vt_builder_create(&b, NULL), VT_OK);
    {
        vt_model *k0;
        assert_int_equal(vt_scene_knee_with(&k0, motor, motor, 1, knee_mass, 2, NULL), VT_OK);
        for (int i = 1; i <= 4; i++) {
            vt_body_def body = vt_default_body_def();
            body.parent = k0->body_parent[i];
            body.mass = k0->body_mass[i];
            memcpy(body.inertia, k0->body_inertia + 9 * i, sizeof body.inertia);
            memcpy(body.joint_parent, k0->body_jpar + 3 * i, sizeof body.joint_parent);
            memcpy(body.joint_child, k0->body_jchild + 3 * i, sizeof body.joint_child);
            assert_int_equal(vt_builder_add_body(b, &body), i);
        }
        vt_body_def rotor = vt_default_body_def();
        rotor.mass = 0.0;
        rotor.inertia[0] = rotor.inertia[4] = 0.5 * a; /* a disc: its inertia on the triangle inequality's edge */
        rotor.inertia[8] = a;
        assert_int_equal(vt_builder_add_body(b, &rotor), 5);
        for (int c = 0; c < k0->ncut; c++) assert_true(vt_builder_add_cut_joint(b, &k0->cut[c]) >= 0);
        for (int k = 0; k < k0->ndrive; k++) assert_true(vt_builder_add_drive(b, &k0->drive[k]) >= 0);
        vt_model_free(k0);
    }
    vt_coupling_def cp = vt_default_coupling_def();
    cp.body_a = 5;
    cp.body_b = 1;
    cp.ratio = 1.0;
    assert_true(vt_builder_add_coupling(b, &cp) >= 0);
    vt_model *mr;
    assert_int_equal(vt_builder_build(&mr, b), VT_OK);
    vt_builder_free(b);
    vt_data *de, *dr;
    assert_int_equal(vt_data_create(&de, me), VT_OK);
    assert_int_equal(vt_data_create(&dr, mr), VT_OK);
    for (int path = 0; path < 2; path++) {
        knee_state(me, de, 0.4);
        knee_state(me, dr, 0.4); /* bodies 1..4 alike */
        dr->q[4] = de->q[0], dr->qd[4] = de->qd[0];
        dr->time = de->time;
        assert_int_equal(path ? vt_inverse_dynamics_recursive(me, de) : vt_inverse_dynamics(me, de), VT_OK);
        assert_int_equal(path ? vt_inverse_dynamics_recursive(mr, dr) : vt_inverse_dynamics(mr, dr), VT_OK);
        for (int c = 0; c < 4; c++) assert_true(fabs(de->qdd[c] - dr->qdd[c]) <= 1e-12 * (1.0 + fabs(dr->qdd[c])));
        assert_true(fabs(de->drive_effort[0] - dr->drive_effort[0]) <= 1e-12 * (1.0 + fabs(dr->drive_effort[0])));
        assert_true(fabs(de->effort_armature[0] - a * de->qdd[0]) <= 1e-15 * (1.0 + fabs(a * de->qdd[0])));
    }
    vt_data_free(de);
    vt_data_free(dr);
    vt_model_free(me);
    vt_model_free(mr);
}

#if VT_HAVE_SUNDIALS
/* the forward check of a kinematic analysis over 3 s: the efforts with every effect, applied to
 * the model without drives (which has the same joints), reproduce the motion, with the smooth
 * friction law and with the sign law alike (the forward run's q̇ stays within 1e-14 of the
 * driven one, so its friction jumps where the driven one's does: six zeros of q̇ in the run) */
static void test_forward_check(void **state_)
{
    (void)state_;
    for (int law = 0; law < 2; law++) {
        vt_model *m = double_link(3, 1, law ? 0.0 : 0.05);
        vt_data *d;
        vt_trajectory *tr;
        assert_int_equal(vt_data_create(&d, m), VT_OK);
        vt_run_options opt = vt_default_run_options();
        opt.t1 = 3.0;
        opt.nout = 60;
        opt.rtol = 1e-10;
        opt.atol = 1e-12;
        assert_int_equal(vt_trajectory_create(&tr, m, opt.nout + 1), VT_OK);
        state(d, 0.0, 0);
        assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), VT_OK);
        print_message("%s friction: forward check's deviation %.3g rad, %.3g rad/s\n", law ? "sign" : "smooth",
                      tr->fwd_err_q, tr->fwd_err_qd);
        assert_true(tr->fwd_err_q <= 1e-10 && tr->fwd_err_qd <= 1e-10);
        vt_trajectory_free(tr);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* a dynamic analysis of the double link left free (no drive), with armature, damping and smooth
 * friction: the energy T + V (T with the rotors' ½ a q̇², from the closed-form M) falls by what
 * damping and friction take, ∫ Σ (b q̇² + f s(q̇) q̇) dt (Simpson's rule over 2,000 rows) */
static void test_energy_balance(void **state_)
{
    (void)state_;
    vt_model *m = double_link(0, 1, 0.05);
    vt_data *d;
    vt_trajectory *tr;
    assert_int_equal(vt_data_create(&d, m), VT_OK);
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 2000;
    opt.rtol = 1e-11;
    opt.atol = 1e-13;
    opt.forward_check = 0;
    assert_int_equal(vt_trajectory_create(&tr, m, opt.nout + 1), VT_OK);
    d->q[0] = -0.5, d->q[1] = 0.4, d->qd[0] = 0.3, d->qd[1] = -0.2;
    assert_int_equal(vt_dynamic_analysis(m, d, &opt, tr), VT_OK);
    assert_int_equal(tr->nfilled, opt.nout + 1);
    double E[2], dissipated = 0.0;
    const double lc = 0.5 * L, h = tr->t[1] - tr->t[0];
    for (int k = 0; k <= opt.nout; k++) {
        const double *q = tr->q + 2 * k, *qd = tr->qd + 2 * k;
        double M[4], hh[2], p = 0.0;
        rigid(q, qd, M, hh);
        for (int c = 0; c < 2; c++) p += damp[c] * qd[c] * qd[c] + fric[c] * tanh(qd[c] / 0.05) * qd[c];
        dissipated += (k == 0 || k == opt.nout ? 1.0 : k % 2 ? 4.0 : 2.0) * p * h / 3.0;
        if (k == 0 || k == opt.nout) {
            const double T = 0.5 * (M[0] * qd[0] * qd[0] + 2.0 * M[1] * qd[0] * qd[1] + M[3] * qd[1] * qd[1]) +
                             0.5 * (arm[0] * qd[0] * qd[0] + arm[1] * qd[1] * qd[1]);
            const double V = MASS * G * (lc * sin(q[0]) + L * sin(q[0]) + lc * sin(q[0] + q[1]));
            E[k ? 1 : 0] = T + V;
        }
    }
    print_message("energy lost %.10g J, dissipated %.10g J\n", E[0] - E[1], dissipated);
    assert_true(dissipated > 10.0); /* the effects take a good part of the motion: not a test of nothing */
    assert_true(fabs(E[0] - E[1] - dissipated) <= 1e-6 * dissipated);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}
#endif

/* The joints' effects in the given motion's overflow bound (recursive/fused.c, fused_bounded):
 * armature q̈ and damping q̇ are loads along the rates, so a model with them skips the output
 * scans only where they cannot overflow. The double link, both joints with a given q̈ and q̇:
 * armature or damping near DBL_MAX times rates that push the effort past it is refused as
 * overflowing (VT_ERR_NONFINITE, the message says so), never returned as Inf with VT_OK; the
 * same coefficients with small rates give finite efforts whose parts are the products
 * themselves. */
static void test_effects_overflow(void **state_)
{
    (void)state_;
    for (int kind = 0; kind < 2; kind++) { /* 0 armature, 1 damping */
        vt_builder *b = double_link_builder(0, 0, 0.0);
        vt_joint_effects_def ef = vt_default_joint_effects_def();
        if (kind == 0) ef.armature[0] = 1e306;
        else ef.damping[0] = 1e306;
        for (int i = 1; i <= 2; i++) assert_int_equal(vt_builder_set_joint_effects(b, i, &ef), VT_OK);
        vt_model *m = built(b);
        vt_data *d;
        assert_int_equal(vt_data_create(&d, m), VT_OK);
        for (int big = 0; big < 2; big++) {
            const double rate = big ? 1e3 : 0.5; /* 1e306 × 1e3 overflows; × 0.5 does not */
            d->q[0] = 0.3, d->q[1] = -0.2;
            d->qd[0] = d->qd[1] = kind ? rate : 0.1;
            d->qdd[0] = d->qdd[1] = kind ? 0.2 : rate;
            d->message[0] = '\0';
            const vt_status st = vt_inverse_dynamics_motion(m, d);
            if (big) {
                assert_int_equal(st, VT_ERR_NONFINITE);
                assert_non_null(strstr(d->message, "overflow"));
            } else {
                assert_int_equal(st, VT_OK);
                for (int c = 0; c < 2; c++) {
                    const double part = kind ? d->effort_damping[c] : d->effort_armature[c];
                    assert_true(part == 1e306 * rate);
                    assert_true(isfinite(d->qfrc_drive[c]));
                    /* the effort is the part plus the rigid bodies' (a few kN·m at these rates) */
                    assert_true(fabs(d->qfrc_drive[c] - part) <= 1e-12 * part);
                }
            }
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_driven_closed_form), cmocka_unit_test(test_passive_closed_form),
        cmocka_unit_test(test_friction_law),       cmocka_unit_test(test_validation),
        cmocka_unit_test(test_loop_damping_friction), cmocka_unit_test(test_loop_armature_rotor),
#if VT_HAVE_SUNDIALS
        cmocka_unit_test(test_forward_check), cmocka_unit_test(test_energy_balance),
#endif
        cmocka_unit_test(test_effects_overflow),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
