/* src/model/urdf.c: URDF robots into a builder. The paper's two examples written as URDF files
 * (tests/urdf/, in URDF's conventions, independently of examples/scenes.c) against the C scenes,
 * every output of an instant to 1e-12; a fixed joint merged and rotated inertial frames against
 * a model whose inertias are combined and rotated by hand here (rotation matrices, the parallel
 * axes); every link frame against the joint origins composed by hand; and every kind of bad
 * input: its status, the element named, the line. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, setenv */
#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h> /* rmdir */

#include "vt_test.h"

#ifndef VT_TEST_URDF_DIR
#error "VT_TEST_URDF_DIR: the directory of the test's URDF files (tests/meson.build)"
#endif


static double worst = 0.0; /* the largest relative difference against the C scenes (printed) */

#define EXPECT_SAME(a, b, n, what)                                                                 \
    do {                                                                                           \
        const double r_ = vt_test_rel_diff((a), (b), (n));                                         \
        worst = fmax(worst, r_);                                                                   \
        if (!(r_ <= 1e-12)) fail_msg("%s: relative difference %.3g > 1e-12", (what), r_);          \
    } while (0)

static vt_model *load(const char *file, const vt_urdf_options *opt)
{
    char path[512], msg[256];
    snprintf(path, sizeof path, "%s/%s", VT_TEST_URDF_DIR, file);
    vt_builder *b = NULL;
    const vt_status st = vt_urdf_builder(&b, path, opt, msg);
    if (st != VT_OK) fail_msg("%s: %s (%s)", path, vt_status_string(st), msg);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* every output of vt_inverse_dynamics_motion() (or, with drives, vt_inverse_dynamics()) */
static void compare_instant(const vt_model *mu, vt_data *du, const vt_model *mc, vt_data *dc, int drives)
{
    const int n3 = 3 * (mc->nbody + 1);
    EXPECT_SAME(du->x, dc->x, mc->nx, "x");
    EXPECT_SAME(du->xdd, dc->xdd, mc->nx, "xdd");
    EXPECT_SAME(du->qfrc_drive, dc->qfrc_drive, mc->nv, "qfrc_drive");
    EXPECT_SAME(du->jnt_force, dc->jnt_force, n3, "jnt_force");
    EXPECT_SAME(du->jnt_moment, dc->jnt_moment, n3, "jnt_moment");
    EXPECT_SAME(du->jnt_force_body, dc->jnt_force_body, n3, "jnt_force_body");
    EXPECT_SAME(du->jnt_moment_body, dc->jnt_moment_body, n3, "jnt_moment_body");
    if (drives) {
        EXPECT_SAME(du->qdd, dc->qdd, mc->nv, "qdd");
        EXPECT_SAME(du->lambda, dc->lambda, mc->nc, "lambda");
        EXPECT_SAME(du->drive_effort, dc->drive_effort, mc->ndrive, "drive_effort");
        EXPECT_SAME(du->drive_force, dc->drive_force, 3 * mc->ndrive, "drive_force");
        EXPECT_SAME(du->drive_moment, dc->drive_moment, 3 * mc->ndrive, "drive_moment");
    }
    (void)mu;
}

/* The same layout: bodies, joints and rates in the same order, named after the URDF. */
static void same_layout(const vt_model *mu, const vt_model *mc, int n)
{
    assert_int_equal(mu->nbody, n);
    assert_int_equal(mc->nbody, n);
    assert_int_equal(mu->nq, mc->nq);
    assert_int_equal(mu->nv, mc->nv);
    for (int i = 1; i <= n; i++) {
        char name[16];
        snprintf(name, sizeof name, "link%d", i);
        assert_int_equal(vt_find_body(mu, name), i);
        snprintf(name, sizeof name, "joint%d", i);
        assert_int_equal(vt_find_joint(mu, name), i);
        assert_int_equal(mu->body_parent[i], mc->body_parent[i]);
        assert_int_equal(mu->body_joint[i], mc->body_joint[i]);
    }
}

/* The double link from tests/urdf/double_link.urdf (gravity y down, as the paper's) against
 * vt_scene_double_link: the motion given at several states, and with the lock drive. */
static void test_double_link(void **state)
{
    (void)state;
    vt_urdf_options opt = vt_default_urdf_options();
    opt.model.gravity[1] = -9.81;
    opt.model.gravity[2] = 0.0;
    vt_model *mu = load("double_link.urdf", &opt), *mc;
    assert_ok(vt_scene_double_link(&mc, 0));
    same_layout(mu, mc, 2);
    vt_data *du, *dc;
    assert_ok(vt_data_create(&du, mu));
    assert_ok(vt_data_create(&dc, mc));
    static const double st[4][6] = {{0, 0, 0, 0, 0, 0}, {-0.5, 0.3, -1.2, 0.7, 2.0, -3.0},
                                    {2.1, -1.4, 0.4, -2.2, -0.6, 1.1}, {-3.0, 2.9, 3.3, 0.1, 0.0, 5.0}};
    for (int s = 0; s < 4; s++) { /* q1 q2 q̇1 q̇2 q̈1 q̈2: the coordinates map 1:1 */
        for (int k = 0; k < 2; k++) {
            du->q[k] = dc->q[k] = st[s][k];
            du->qd[k] = dc->qd[k] = st[s][2 + k];
            du->qdd[k] = dc->qdd[k] = st[s][4 + k];
        }
        assert_ok(vt_inverse_dynamics_motion(mu, du));
        assert_ok(vt_inverse_dynamics_motion(mc, dc));
        compare_instant(mu, du, mc, dc, 0);
    }
    vt_data_free(du);
    vt_data_free(dc);
    vt_model_free(mc);
    vt_model_free(mu);

    /* locked: the C scene's drive added to the URDF builder */
    vt_builder *b;
    char msg[256];
    assert_ok(vt_scene_double_link(&mc, 1));
    char path[512];
    snprintf(path, sizeof path, "%s/double_link.urdf", VT_TEST_URDF_DIR);
    assert_ok(vt_urdf_builder(&b, path, &opt, msg));
    assert_int_equal(vt_builder_add_drive(b, &mc->drive[0]), 0);
    assert_ok(vt_builder_build(&mu, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(&du, mu));
    assert_ok(vt_data_create(&dc, mc));
    for (int s = 0; s < 3; s++) { /* fallen θ from rest: θ̇² = 7.3575 sin θ; q2 = 0 */
        const double th = 0.3 + 0.6 * s;
        du->q[0] = dc->q[0] = -th;
        du->qd[0] = dc->qd[0] = -sqrt(7.3575 * sin(th));
        assert_ok(vt_inverse_dynamics(mu, du));
        assert_ok(vt_inverse_dynamics(mc, dc));
        compare_instant(mu, du, mc, dc, 1);
        assert_near(du->drive_effort[0], -245.25 * cos(th), 1e-9); /* (29) */
    }
    vt_data_free(du);
    vt_data_free(dc);
    vt_model_free(mc);
    vt_model_free(mu);
}

/* The five-link arm from tests/urdf/five_link.urdf against vt_scene_five_link: the motion
 * given, and the five point drives (30)-(34) at consistent states along the circle. */
static void test_five_link(void **state)
{
    (void)state;
    vt_model *mu = load("five_link.urdf", NULL), *mc;
    assert_ok(vt_scene_five_link(&mc));
    same_layout(mu, mc, 5);
    assert_near(mu->gravity[2], -9.81, 0.0);
    /* the URDF's limits on the first rate of each joint */
    assert_near(mu->dof_limit[4 * 1 + 1], 3.14159, 0.0);
    assert_near(mu->dof_limit[4 * 1 + 3], 100.0, 0.0);
    assert_near(mu->dof_limit[4 * 4 + 2], 4.0, 0.0);
    vt_data *du, *dc;
    vt_model *mfree;
    assert_ok(vt_model_without_drives(&mfree, mc));
    assert_ok(vt_data_create(&du, mu));
    assert_ok(vt_data_create(&dc, mfree));
    uint64_t seed = 7;
    for (int s = 0; s < 5; s++) {
        for (int k = 0; k < 5; k++) {
            du->q[k] = dc->q[k] = vt_rand_uniform(&seed, -3.0, 3.0);
            du->qd[k] = dc->qd[k] = vt_rand_uniform(&seed, -2.0, 2.0);
            du->qdd[k] = dc->qdd[k] = vt_rand_uniform(&seed, -5.0, 5.0);
        }
        assert_ok(vt_inverse_dynamics_motion(mu, du));
        assert_ok(vt_inverse_dynamics_motion(mfree, dc));
        compare_instant(mu, du, mfree, dc, 0);
    }
    vt_data_free(du);
    vt_data_free(dc);
    vt_model_free(mfree);
    vt_model_free(mu);

    /* the scene's drives added to the URDF builder */
    char path[512], msg[256];
    snprintf(path, sizeof path, "%s/five_link.urdf", VT_TEST_URDF_DIR);
    vt_builder *b;
    assert_ok(vt_urdf_builder(&b, path, NULL, msg));
    for (int k = 0; k < mc->ndrive; k++) assert_int_equal(vt_builder_add_drive(b, &mc->drive[k]), k);
    assert_ok(vt_builder_build(&mu, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(&du, mu));
    assert_ok(vt_data_create(&dc, mc));
    for (int s = 0; s < 4; s++) {
        dc->time = 0.13 + 0.21 * s;
        vt_scene_five_link_guess(mc, dc, dc->time);
        assert_ok(vt_kinematic_solve(mc, dc, 1e-13, 30));
        du->time = dc->time;
        memcpy(du->q, dc->q, 5 * sizeof(double));
        memcpy(du->qd, dc->qd, 5 * sizeof(double));
        assert_ok(vt_inverse_dynamics(mu, du));
        compare_instant(mu, du, mc, dc, 1);
    }
    vt_data_free(du);
    vt_data_free(dc);
    vt_model_free(mc);
    vt_model_free(mu);
}

/* ---- by hand: rotation matrices and poses, independent of the library's Euler parameters ---- */

/* R = Rz(y) Ry(p) Rx(r), column-major */
static void rpy_matrix(double R[9], double r, double p, double y)
{
    const double cr = cos(r), sr = sin(r), cp = cos(p), sp = sin(p), cy = cos(y), sy = sin(y);
    const double M[9] = {cy * cp, sy * cp, -sp,
                         cy * sp * sr - sy * cr, sy * sp * sr + cy * cr, cp * sr,
                         cy * sp * cr + sy * sr, sy * sp * cr - cy * sr, cp * cr};
    memcpy(R, M, sizeof M);
}

/* Euler parameters of Rz(y) Ry(p) Rx(r) (the half-angle product) */
static void rpy_quat(double q[4], double r, double p, double y)
{
    const double cr = cos(r / 2), sr = sin(r / 2), cp = cos(p / 2), sp = sin(p / 2), cy = cos(y / 2), sy = sin(y / 2);
    q[0] = cr * cp * cy + sr * sp * sy;
    q[1] = sr * cp * cy - cr * sp * sy;
    q[2] = cr * sp * cy + sr * cp * sy;
    q[3] = cr * cp * sy - sr * sp * cy;
}

/* rotation by angle about the unit axis u (Rodrigues) */
static void axis_matrix(double R[9], const double u[3], double a)
{
    const double c = cos(a), s = sin(a), t = 1 - c;
    const double M[9] = {t * u[0] * u[0] + c, t * u[0] * u[1] + s * u[2], t * u[0] * u[2] - s * u[1],
                         t * u[0] * u[1] - s * u[2], t * u[1] * u[1] + c, t * u[1] * u[2] + s * u[0],
                         t * u[0] * u[2] + s * u[1], t * u[1] * u[2] - s * u[0], t * u[2] * u[2] + c};
    memcpy(R, M, sizeof M);
}

static void matmul(double C[9], const double A[9], const double B[9])
{
    double T[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) T[r + 3 * c] = A[r] * B[3 * c] + A[r + 3] * B[3 * c + 1] + A[r + 6] * B[3 * c + 2];
    memcpy(C, T, sizeof T);
}

static void matvec(double y[3], const double A[9], const double x[3])
{
    double t[3];
    for (int r = 0; r < 3; r++) t[r] = A[r] * x[0] + A[r + 3] * x[1] + A[r + 6] * x[2];
    memcpy(y, t, sizeof t);
}

/* pose (R, t) ← (R, t)(Rb, tb) */
static void compose(double R[9], double t[3], const double Rb[9], const double tb[3])
{
    double v[3];
    matvec(v, R, tb);
    for (int k = 0; k < 3; k++) t[k] += v[k];
    matmul(R, R, Rb);
}

/* J += R I R^T + m (|d|² 1 − d d^T) */
static void add_inertia(double J[9], const double R[9], const double I[9], double m, const double d[3])
{
    double RI[9], Rt[9];
    matmul(RI, R, I);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) Rt[r + 3 * c] = R[c + 3 * r];
    matmul(RI, RI, Rt);
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) J[r + 3 * c] += RI[r + 3 * c] + m * ((r == c ? dd : 0.0) - d[r] * d[c]);
}

/* A two-link arm with a tool: world → arm (revolute about y through origin o1, rpy g1) →
 * forearm (revolute about axis a2 at o2, rpy g2) → tool (fixed at o3, rpy g3). Each link's
 * inertial frame is rotated (rpy h_k) and offset (c_k), with a full inertia I_k. */
static const double o1[3] = {0.0, 0.0, 0.2}, g1[3] = {0.0, 0.0, 0.3};
static const double o2[3] = {0.6, 0.05, 0.0}, g2[3] = {0.2, -0.4, 0.1}, a2[3] = {0.0, 0.6, 0.8};
static const double o3[3] = {0.4, 0.0, 0.1}, g3[3] = {0.3, 0.2, -0.5};
static const double h[3][3] = {{0.4, -0.3, 0.7}, {-0.2, 0.5, 0.1}, {0.6, 0.1, -0.9}};
static const double c[3][3] = {{0.3, 0.02, -0.01}, {0.2, -0.03, 0.04}, {0.05, 0.02, 0.0}};
static const double mass[3] = {2.0, 1.2, 0.7};
static const double Iu[3][9] = {{0.02, 0.001, -0.002, 0.001, 0.06, 0.003, -0.002, 0.003, 0.07},
                                {0.01, -0.002, 0.0, -0.002, 0.03, 0.001, 0.0, 0.001, 0.035},
                                {0.004, 0.0, 0.0005, 0.0, 0.005, 0.0, 0.0005, 0.0, 0.006}};

static void tool_urdf(char *xml, size_t size)
{
    const char *name[3] = {"arm", "forearm", "tool"};
    int n = snprintf(xml, size, "<robot name=\"tooled\">\n  <link name=\"world\"/>\n");
    for (int k = 0; k < 3; k++)
        n += snprintf(xml + n, size - (size_t)n,
                      "  <link name=\"%s\"><inertial><origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/>"
                      "<mass value=\"%.17g\"/><inertia ixx=\"%.17g\" ixy=\"%.17g\" ixz=\"%.17g\" iyy=\"%.17g\" "
                      "iyz=\"%.17g\" izz=\"%.17g\"/></inertial></link>\n",
                      name[k], c[k][0], c[k][1], c[k][2], h[k][0], h[k][1], h[k][2], mass[k], Iu[k][0], Iu[k][3],
                      Iu[k][6], Iu[k][4], Iu[k][7], Iu[k][8]);
    snprintf(xml + n, size - (size_t)n,
             "  <joint name=\"shoulder\" type=\"revolute\"><parent link=\"world\"/><child link=\"arm\"/>"
             "<origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/><axis xyz=\"0 1 0\"/>"
             "<limit lower=\"-1\" upper=\"2\" effort=\"50\" velocity=\"3\"/></joint>\n"
             "  <joint name=\"elbow\" type=\"continuous\"><parent link=\"arm\"/><child link=\"forearm\"/>"
             "<origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/><axis xyz=\"%.17g %.17g %.17g\"/></joint>\n"
             "  <joint name=\"flange\" type=\"fixed\"><parent link=\"forearm\"/><child link=\"tool\"/>"
             "<origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/></joint>\n</robot>\n",
             o1[0], o1[1], o1[2], g1[0], g1[1], g1[2], o2[0], o2[1], o2[2], g2[0], g2[1], g2[2], a2[0], a2[1], a2[2],
             o3[0], o3[1], o3[2], g3[0], g3[1], g3[2]);
}

/* The same robot built by hand with body axes = the link frames: the arm's inertia rotated
 * into its link axes, the forearm and the tool combined (centre of mass, parallel axes). */
static vt_model *tool_by_hand(void)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[1] = 0.0;
    md.gravity[2] = -9.81;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    double R[9], R3[9], t3[3];
    vt_body_def arm = vt_default_body_def();
    arm.mass = mass[0];
    rpy_matrix(R, h[0][0], h[0][1], h[0][2]);
    add_inertia(arm.inertia, R, Iu[0], 0.0, c[0]);
    memcpy(arm.joint_parent, o1, sizeof o1);
    for (int k = 0; k < 3; k++) arm.joint_child[k] = -c[0][k];
    double Rg1[9];
    rpy_matrix(Rg1, g1[0], g1[1], g1[2]);
    const double y[3] = {0.0, 1.0, 0.0};
    matvec(arm.axis1, Rg1, y); /* the ground's axes */
    rpy_quat(arm.orientation, g1[0], g1[1], g1[2]);
    assert_int_equal(vt_builder_add_body(b, &arm), 1);

    /* forearm + tool in the forearm's link frame */
    vt_body_def fa = vt_default_body_def();
    rpy_matrix(R3, g3[0], g3[1], g3[2]);
    double ctool[3], Rt[9];
    matvec(ctool, R3, c[2]);
    for (int k = 0; k < 3; k++) ctool[k] += o3[k];
    fa.mass = mass[1] + mass[2];
    double com[3];
    for (int k = 0; k < 3; k++) com[k] = (mass[1] * c[1][k] + mass[2] * ctool[k]) / fa.mass;
    double d1[3], d2[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = c[1][k] - com[k];
        d2[k] = ctool[k] - com[k];
    }
    rpy_matrix(R, h[1][0], h[1][1], h[1][2]);
    add_inertia(fa.inertia, R, Iu[1], mass[1], d1);
    rpy_matrix(Rt, h[2][0], h[2][1], h[2][2]);
    matmul(Rt, R3, Rt);
    add_inertia(fa.inertia, Rt, Iu[2], mass[2], d2);
    fa.parent = 1;
    fa.joint = VT_JOINT_REVOLUTE;
    for (int k = 0; k < 3; k++) fa.joint_parent[k] = o2[k] - c[0][k];
    for (int k = 0; k < 3; k++) fa.joint_child[k] = -com[k];
    double Rg2[9];
    rpy_matrix(Rg2, g2[0], g2[1], g2[2]);
    matvec(fa.axis1, Rg2, a2);
    rpy_quat(fa.orientation, g2[0], g2[1], g2[2]);
    assert_int_equal(vt_builder_add_body(b, &fa), 2);
    (void)t3;
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* A fixed joint merged and rotated inertial frames: the efforts and the global reactions equal
 * those of the hand-built model (whose body axes differ, so the body-axes reactions do not). */
static void test_merged_and_rotated(void **state)
{
    (void)state;
    char xml[8192], msg[256];
    tool_urdf(xml, sizeof xml);
    vt_builder *b;
    if (vt_urdf_builder_string(&b, xml, NULL, msg) != VT_OK) fail_msg("%s", msg);
    vt_model *mu, *mh = tool_by_hand();
    assert_ok(vt_builder_build(&mu, b));
    vt_builder_free(b);
    assert_int_equal(mu->nbody, 2); /* the tool merged */
    assert_int_equal(vt_find_body(mu, "tool"), VT_ERR_NOT_FOUND);
    assert_int_equal(vt_find_joint(mu, "elbow"), 2);
    assert_near(mu->body_mass[2], mass[1] + mass[2], 1e-15);
    assert_near(mu->dof_limit[0], -1.0, 0.0);        /* revolute: lower, upper, velocity, effort */
    assert_near(mu->dof_limit[3], 50.0, 0.0);
    assert_true(isinf(mu->dof_limit[4 + 1]));        /* continuous, no <limit> */
    vt_data *du, *dh;
    assert_ok(vt_data_create(&du, mu));
    assert_ok(vt_data_create(&dh, mh));
    uint64_t seed = 3;
    for (int s = 0; s < 5; s++) {
        for (int k = 0; k < 2; k++) {
            du->q[k] = dh->q[k] = s ? vt_rand_uniform(&seed, -3.0, 3.0) : 0.0;
            du->qd[k] = dh->qd[k] = vt_rand_uniform(&seed, -2.0, 2.0);
            du->qdd[k] = dh->qdd[k] = vt_rand_uniform(&seed, -5.0, 5.0);
        }
        assert_ok(vt_inverse_dynamics_motion(mu, du));
        assert_ok(vt_inverse_dynamics_motion(mh, dh));
        const double e = vt_test_rel_diff(du->qfrc_drive, dh->qfrc_drive, 2);
        const double f = vt_test_rel_diff(du->jnt_force, dh->jnt_force, 9);
        const double n = vt_test_rel_diff(du->jnt_moment, dh->jnt_moment, 9);
        if (!(e <= 1e-12 && f <= 1e-12 && n <= 1e-12))
            fail_msg("state %d: efforts %.3g, forces %.3g, moments %.3g relative", s, e, f, n);
        for (int k = 0; k < 2; k++) { /* the centres of mass coincide */
            assert_near(du->x[7 * k], dh->x[7 * k], 1e-13);
            assert_near(du->x[7 * k + 1], dh->x[7 * k + 1], 1e-13);
            assert_near(du->x[7 * k + 2], dh->x[7 * k + 2], 1e-13);
        }
    }
    vt_data_free(du);
    vt_data_free(dh);
    vt_model_free(mh);

    /* every link frame where the URDF puts it: the joint origins composed by hand */
    assert_ok(vt_data_create(&du, mu));
    for (int s = 0; s < 2; s++) {
        const double q1 = s ? 0.7 : 0.0, q2 = s ? -1.1 : 0.0;
        du->q[0] = q1;
        du->q[1] = q2;
        assert_ok(vt_kinematics(mu, du));
        double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, t[3] = {0, 0, 0}, Rj[9], Rq[9];
        const double zero[3] = {0, 0, 0}, y[3] = {0, 1, 0};
        double u2[3];
        const double n2 = sqrt(a2[0] * a2[0] + a2[1] * a2[1] + a2[2] * a2[2]);
        for (int k = 0; k < 3; k++) u2[k] = a2[k] / n2;
        const char *names[4] = {"world", "arm", "forearm", "tool"};
        for (int l = 0; l < 4; l++) {
            if (l == 1) {
                rpy_matrix(Rj, g1[0], g1[1], g1[2]);
                compose(R, t, Rj, o1);
                axis_matrix(Rq, y, q1);
                compose(R, t, Rq, zero);
            } else if (l == 2) {
                rpy_matrix(Rj, g2[0], g2[1], g2[2]);
                compose(R, t, Rj, o2);
                axis_matrix(Rq, u2, q2);
                compose(R, t, Rq, zero);
            } else if (l == 3) {
                rpy_matrix(Rj, g3[0], g3[1], g3[2]);
                compose(R, t, Rj, o3);
            }
            const int f = vt_find_frame(mu, names[l]);
            assert_true(f >= 0);
            double pos[3], rot[9];
            assert_ok(vt_frame_pose(mu, du, f, pos, rot));
            for (int k = 0; k < 3; k++) assert_near(pos[k], t[k], 1e-14);
            for (int k = 0; k < 9; k++) assert_near(rot[k], R[k], 1e-14);
        }
    }
    vt_data_free(du);
    vt_model_free(mu);
}

/* a floating root (options.floating) becomes a base body; welded by default */
static void test_floating_root(void **state)
{
    (void)state;
    const char *xml = "<robot name=\"r\"><link name=\"base\"><inertial><mass value=\"3\"/>"
                      "<inertia ixx=\"0.1\" iyy=\"0.2\" izz=\"0.25\"/></inertial></link>"
                      "<link name=\"wheel\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" iyy=\"0.01\" izz=\"0.01\"/>"
                      "</inertial></link><joint name=\"axle\" type=\"continuous\"><parent link=\"base\"/>"
                      "<child link=\"wheel\"/><origin xyz=\"0 0.3 0\"/><axis xyz=\"0 1 0\"/></joint></robot>";
    vt_urdf_options opt = vt_default_urdf_options();
    vt_builder *b;
    vt_model *m;
    assert_ok(vt_urdf_builder_string(&b, xml, &opt, NULL));
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nbody, 1); /* the base welded: the ground */
    assert_int_equal(m->frame_body[vt_find_frame(m, "base")], 0);
    vt_model_free(m);
    opt.floating = 1;
    assert_ok(vt_urdf_builder_string(&b, xml, &opt, NULL));
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nbody, 2);
    assert_int_equal(m->body_joint[1], VT_JOINT_FREE);
    assert_int_equal(vt_find_body(m, "base"), 1);
    assert_int_equal(m->body_parent[2], 1);
    assert_near(m->body_jpar[3 * 2 + 1], 0.3, 0.0);
    vt_model_free(m);
}

/* A free joint's q is its link frame's pose: a floating root (its inertial frame off and turned)
 * and a floating joint between two links (from a turned joint origin): the link frames' poses
 * from vt_frame_pose against the poses composed by hand from q */
static void test_floating_pose(void **state)
{
    (void)state;
    const char *xml =
        "<robot name=\"r\"><link name=\"base\"><inertial><origin xyz=\"0.1 -0.2 0.05\" rpy=\"0.3 -0.2 0.7\"/>"
        "<mass value=\"3\"/><inertia ixx=\"0.1\" iyy=\"0.2\" izz=\"0.25\"/></inertial></link>"
        "<link name=\"drone\"><inertial><origin xyz=\"0.02 0 -0.03\" rpy=\"0.1 0.2 0.3\"/><mass value=\"1\"/>"
        "<inertia ixx=\"0.01\" iyy=\"0.02\" izz=\"0.02\"/></inertial></link>"
        "<joint name=\"tether\" type=\"floating\"><parent link=\"base\"/><child link=\"drone\"/>"
        "<origin xyz=\"0.4 0.1 -0.2\" rpy=\"0.5 0 -0.4\"/></joint></robot>";
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = 1;
    vt_builder *b;
    vt_model *m;
    assert_ok(vt_urdf_builder_string(&b, xml, &opt, NULL));
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nbody, 2);
    assert_int_equal(m->body_joint[1], VT_JOINT_FREE);
    assert_int_equal(m->body_joint[2], VT_JOINT_FREE);
    assert_int_equal(m->body_parent[2], 1);
    assert_int_equal(vt_find_joint(m, "tether"), 2);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    uint64_t s = 5;
    vt_scene_random_state(m, d, &s);
    assert_ok(vt_kinematics(m, d));
    double pb[3], Rb[9], pd[3], Rd[9], Rq[9], Ro[9];
    assert_ok(vt_frame_pose(m, d, vt_find_frame(m, "base"), pb, Rb));
    assert_ok(vt_frame_pose(m, d, vt_find_frame(m, "drone"), pd, Rd));
    /* the root: its link frame's origin at q[0..2], its axes A(q[3..6]) */
    vt_euler_A(Rq, d->q + 3);
    for (int k = 0; k < 3; k++) assert_near(pb[k], d->q[k], 1e-14);
    for (int k = 0; k < 9; k++) assert_near(Rb[k], Rq[k], 1e-14);
    /* the tether: origin O = p_b + R_b o; the drone's origin O + A^1 t (t in the base body's
     * axes, A^1 = R_b R_I) and axes A^1 A(p) R_I^T R_o, R_I the base's inertial rotation */
    const double o[3] = {0.4, 0.1, -0.2};
    double RI[9], RIt[9];
    rpy_matrix(RI, 0.3, -0.2, 0.7);
    rpy_matrix(Ro, 0.5, 0.0, -0.4);
    for (int r = 0; r < 3; r++)
        for (int c2 = 0; c2 < 3; c2++) RIt[r + 3 * c2] = RI[c2 + 3 * r];
    const double *A1 = d->A + 9;
    const double *t = d->q + 7;
    vt_euler_A(Rq, d->q + 10);
    for (int r = 0; r < 3; r++) {
        double x = pb[r];
        for (int k = 0; k < 3; k++) x += Rb[r + 3 * k] * o[k] + A1[r + 3 * k] * t[k];
        assert_near(pd[r], x, 1e-14);
    }
    double T1[9], T2[9], T3[9];
    matmul(T1, A1, Rq);  /* A^1 A(p) */
    matmul(T2, RIt, Ro); /* R_I^T R_o */
    matmul(T3, T1, T2);
    for (int k = 0; k < 9; k++) assert_near(Rd[k], T3[k], 1e-14);
    vt_data_free(d);
    vt_model_free(m);
}

/* The numbers are read in the C locale whatever the caller's LC_NUMERIC: under a comma-decimal
 * locale (de_DE.UTF-8, compiled here by localedef into a temporary LOCPATH when it is not
 * installed; skipped with a message when that fails) the five-link arm loads, and its model
 * equals the one loaded under the C locale entry for entry. */
static void test_comma_locale(void **state)
{
    (void)state;
    vt_model *ref = load("five_link.urdf", NULL);
    char dir[] = "/tmp/vtdyn-locale-XXXXXX", cmd[256];
    int have = setlocale(LC_NUMERIC, "de_DE.UTF-8") != NULL;
    int made = 0;
    if (!have && mkdtemp(dir)) {
        made = 1;
        snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
        if (system(cmd) == 0 && setenv("LOCPATH", dir, 1) == 0) have = setlocale(LC_NUMERIC, "de_DE.UTF-8") != NULL;
    }
    if (have && strtod("0,5", NULL) != 0.5) have = 0; /* not comma-decimal after all */
    if (!have) {
        setlocale(LC_NUMERIC, "C");
        print_message("    skipped: no comma-decimal locale (de_DE.UTF-8 not installed, localedef failed)\n");
    } else {
        vt_model *m = load("five_link.urdf", NULL);
        setlocale(LC_NUMERIC, "C");
        assert_int_equal(m->nbody, ref->nbody);
        assert_memory_equal(m->body_mass, ref->body_mass, ((size_t)m->nbody + 1) * sizeof(double));
        assert_memory_equal(m->body_inertia, ref->body_inertia, 9 * ((size_t)m->nbody + 1) * sizeof(double));
        assert_memory_equal(m->body_jpar, ref->body_jpar, 3 * ((size_t)m->nbody + 1) * sizeof(double));
        assert_memory_equal(m->body_jchild, ref->body_jchild, 3 * ((size_t)m->nbody + 1) * sizeof(double));
        assert_memory_equal(m->body_axis, ref->body_axis, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        assert_memory_equal(m->body_quat0, ref->body_quat0, 4 * ((size_t)m->nbody + 1) * sizeof(double));
        vt_model_free(m);
    }
    if (made) {
        snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
        assert_int_equal(system(cmd), 0);
        unsetenv("LOCPATH");
    }
    vt_model_free(ref);
}

typedef struct {
    const char *xml;
    vt_status status;
    const char *says; /* in the message */
} bad_case;

#define LINK(n) "<link name=\"" n "\"/>"
#define JOINT(n, t, p, c) "<joint name=\"" n "\" type=\"" t "\"><parent link=\"" p "\"/><child link=\"" c "\"/></joint>"

static void test_bad_input(void **state)
{
    (void)state;
    static const bad_case cases[] = {
        {"<robot name=\"r\">\n<link name=\"a\">\n</robot>", VT_ERR_XML, "line 3"},
        {"", VT_ERR_XML, "malformed XML"},
        {"<?xml version=\"1.0\"?>\n<model/>", VT_ERR_XML, "<model> (line 2)"},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("j1", "revolute", "world", "b")
         JOINT("j2", "revolute", "a", "b") "</robot>", VT_ERR_PARENT, "link \"b\" has two parents"},
        {"<robot>" LINK("a") JOINT("j", "revolute", "a", "nowhere") "</robot>", VT_ERR_NOT_FOUND,
         "child link \"nowhere\""},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("j0", "fixed", "world", "world2") "</robot>",
         VT_ERR_NOT_FOUND, "joint \"j0\""},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("ja", "revolute", "a", "b")
         JOINT("jb", "revolute", "b", "a") "</robot>", VT_ERR_PARENT, "loop"},
        {"<robot>" LINK("world") LINK("a") JOINT("j", "planar", "world", "a") "</robot>", VT_ERR_JOINT_TYPE,
         "joint \"j\" (line 1): joint type \"planar\""},
        {"<robot>" LINK("world") LINK("a") JOINT("j", "hinge", "world", "a") "</robot>", VT_ERR_JOINT_TYPE,
         "\"hinge\" unknown"},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("j", "revolute", "world", "a")
         "<joint name=\"m\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><mimic joint=\"zz\"/></joint>"
         "</robot>", VT_ERR_NOT_FOUND, "mimics \"zz\""},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("j", "fixed", "world", "a")
         "<joint name=\"m\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><mimic joint=\"j\"/></joint>"
         "</robot>", VT_ERR_JOINT_TYPE, "no scalar coordinate"},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("j", "revolute", "world", "a")
         "<joint name=\"m\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>"
         "<mimic joint=\"j\" multiplier=\"x\"/></joint></robot>", VT_ERR_NONFINITE, "multiplier"},
        {"<robot>\n<link name=\"a\">\n<inertial>\n<mass value=\"-2\"/></inertial></link></robot>", VT_ERR_MASS,
         "link \"a\", <mass> (line 4)"},
        {"<robot><link name=\"a\"><inertial><mass value=\"1.0abc\"/></inertial></link></robot>", VT_ERR_NONFINITE,
         "value=\"1.0abc\""},
        {"<robot><link name=\"a\"><inertial><mass value=\"nan\"/></inertial></link></robot>", VT_ERR_NONFINITE,
         "not finite"},
        {"<robot>" LINK("world") LINK("a") "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/>"
         "<child link=\"a\"/><origin xyz=\"1 2\"/></joint></robot>", VT_ERR_NONFINITE, "<origin>"},
        {"<robot>" LINK("world") LINK("a") "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/>"
         "<child link=\"a\"/><axis xyz=\"0 0 1e999\"/></joint></robot>", VT_ERR_NONFINITE, "<axis>"},
        {"<robot>" LINK("world") LINK("a") "<joint name=\"j\" type=\"prismatic\"><parent link=\"world\"/>"
         "<child link=\"a\"/><limit lower=\"0\" upper=\"1,5\"/></joint></robot>", VT_ERR_NONFINITE, "<limit>"},
        /* an inertia is checked on the body its link is (part of): here a body of its own */
        {"<robot>" LINK("world") "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"3\"/>"
         "</inertial></link>" JOINT("j", "revolute", "world", "a") "</robot>", VT_ERR_INERTIA_TRIANGLE, "joint \"j\""},
        {"<robot>" LINK("world") "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"-1\" iyy=\"1\" izz=\"1\"/>"
         "</inertial></link>" JOINT("j", "revolute", "world", "a") "</robot>", VT_ERR_INERTIA_NOT_PSD, "principal moment"},
        {"<robot>" LINK("a") LINK("a") "</robot>", VT_ERR_BAD_NAME, "link \"a\" (line 1): name already taken"},
        {"<robot>" LINK("world") LINK("a") LINK("b") JOINT("j", "revolute", "world", "a")
         JOINT("j", "revolute", "a", "b") "</robot>", VT_ERR_BAD_NAME, "joint \"j\""},
        {"<robot><link/></robot>", VT_ERR_BAD_NAME, "needs a name"},
        {"<robot>" LINK("world") LINK("a") "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/>"
         "<child link=\"a\"/><axis xyz=\"0 0 0\"/></joint></robot>", VT_ERR_AXIS_ZERO, "joint \"j\""},
        {"<robot>" LINK("world") LINK("a") "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/>"
         "<child link=\"a\"/><limit lower=\"1\" upper=\"-1\"/></joint></robot>", VT_ERR_BAD_OPTION, "joint \"j\""},
        {"<robot/>", VT_ERR_EMPTY_MODEL, "no <link>"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char msg[256] = "";
        vt_builder *b = (vt_builder *)&msg; /* not NULL: must be set to NULL */
        const vt_status st = vt_urdf_builder_string(&b, cases[k].xml, NULL, msg);
        if (st != cases[k].status || b != NULL || !strstr(msg, cases[k].says))
            fail_msg("case %zu: status %d (expected %d), message \"%s\" (expected to hold \"%s\")", k, (int)st,
                     (int)cases[k].status, msg, cases[k].says);
        assert_int_equal(vt_urdf_builder_string(&b, cases[k].xml, NULL, NULL), cases[k].status); /* no message */
    }
    /* files: missing, a directory; NULLs */
    char msg[256];
    vt_builder *b;
    assert_int_equal(vt_urdf_builder(&b, VT_TEST_URDF_DIR "/no_such.urdf", NULL, msg), VT_ERR_FILE);
    assert_null(b);
    assert_non_null(strstr(msg, "no_such.urdf"));
    assert_int_equal(vt_urdf_builder(&b, VT_TEST_URDF_DIR, NULL, msg), VT_ERR_FILE);
    assert_int_equal(vt_urdf_builder(&b, NULL, NULL, msg), VT_ERR_NULL);
    assert_int_equal(vt_urdf_builder(NULL, "x", NULL, msg), VT_ERR_NULL);
    assert_int_equal(vt_urdf_builder_string(&b, NULL, NULL, msg), VT_ERR_NULL);
    vt_urdf_options opt = vt_default_urdf_options();
    opt.model.rcond_min = 0.0;
    assert_int_equal(vt_urdf_builder_string(&b, "<robot><link name=\"a\"/></robot>", &opt, msg), VT_ERR_BAD_OPTION);
    assert_null(b);
}

/* Entities: URDF needs none, so a document that declares one is refused, its expansion never
 * done: one internal entity of 16 kB used 300 times in an attribute (an 18 kB file that would
 * expand to 4.8 MB), and in content; the predefined entities and character references are
 * still read (a name "a&b<c" written "a&amp;b&#60;c"). */
static void test_entities(void **state)
{
    (void)state;
    const size_t big = 16000, uses = 300;
    char *xml = malloc(big + 6 * uses + 512);
    assert_non_null(xml);
    char *p = xml + sprintf(xml, "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n<!ENTITY e \"");
    memset(p, 'x', big);
    p += big;
    p += sprintf(p, "\">\n]>\n<robot name=\"r\"><link name=\"world\"/><link name=\"");
    for (size_t k = 0; k < uses; k++) p += sprintf(p, "&e;");
    sprintf(p, "\"/></robot>\n");
    assert_true(strlen(xml) < 18000);
    char msg[256] = "";
    vt_builder *b = (vt_builder *)&msg;
    vt_status st = vt_urdf_builder_string(&b, xml, NULL, msg);
    if (st != VT_ERR_XML || b || !strstr(msg, "entities") || !strstr(msg, "<!ENTITY e>") || !strstr(msg, "line 3"))
        fail_msg("the large entity: status %d, message \"%s\"", (int)st, msg);
    free(xml);
    static const char *const refused[] = {
        /* used in content, and a parameter entity */
        "<!DOCTYPE robot [<!ENTITY e \"xyz\">]><robot><link name=\"a\">&e;</link></robot>",
        "<!DOCTYPE robot [<!ENTITY % e \"<!ENTITY f 'b'>\"> %e;]><robot><link name=\"&f;\"/></robot>",
        /* declared, not used: refused too (nothing in URDF declares one) */
        "<!DOCTYPE robot [<!ENTITY e \"xyz\">]><robot><link name=\"a\"/></robot>",
        "<!DOCTYPE robot [<!NOTATION n SYSTEM \"n\"><!ENTITY e SYSTEM \"e.bin\" NDATA n>]><robot><link name=\"a\"/></robot>",
    };
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        st = vt_urdf_builder_string(&b, refused[k], NULL, msg);
        if (st != VT_ERR_XML || b || !strstr(msg, "entities are refused"))
            fail_msg("refused[%zu]: status %d, message \"%s\"", k, (int)st, msg);
    }
    /* a DOCTYPE without entities, the predefined entities and character references: read */
    const char *fine = "<?xml version=\"1.0\"?><!DOCTYPE robot [<!ELEMENT robot ANY>]>"
                       "<robot name=\"r\"><link name=\"world\"/><link name=\"a&amp;b&#60;c\"/>"
                       "<joint name=\"j&gt;\" type=\"revolute\"><parent link=\"world\"/><child link=\"a&amp;b&lt;c\"/>"
                       "</joint><!-- &amp; --></robot>";
    st = vt_urdf_builder_string(&b, fine, NULL, msg);
    if (st != VT_OK) fail_msg("predefined entities: status %d, message \"%s\"", (int)st, msg);
    assert_int_equal(vt_builder_find_body(b, "a&b<c"), 1);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(vt_find_joint(m, "j>"), 1);
    vt_model_free(m);
}

/* The input's bound, VT_URDF_MAX_BYTES (256 MiB): a robot padded with white space to exactly that
 * size is read from a string, one byte more is refused naming the bound, from a string
 * (VT_ERR_XML) and a file (VT_ERR_FILE, by its size: a sparse file); a sparse file of exactly
 * the bound is read whole (its hole NUL bytes after the robot, where libxml2's document ends);
 * /dev/zero, which never ends, is refused once the bound is passed instead of growing a buffer
 * until memory runs out. The reads at the bound (hundreds of MB, a parse of 256 MiB) are left
 * out under valgrind. */
static void test_size_bound(void **state)
{
    (void)state;
    const size_t max = (size_t)VT_URDF_MAX_BYTES;
    assert_true(max == 256u * 1024u * 1024u);
    const int full = !under_valgrind();
    const char *robot = "<robot name=\"r\"><link name=\"world\"/><link name=\"a\"/>"
                        "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/><child link=\"a\"/></joint></robot>\n";
    char *xml = malloc(max + 2);
    assert_non_null(xml);
    const size_t n = strlen(robot);
    memcpy(xml, robot, n);
    /* padded to exactly max bytes inside <robot> with white space, which makes no node, in runs
     * of 1 MiB (libxml2 refuses more than 10 MB read at once) each closed by an element the loader
     * ignores */
    size_t at = n - strlen("</robot>\n");
    const size_t body = max - strlen("</robot>\n");
    while (at < body) {
        const size_t run = body - at < ((size_t)1 << 20) ? body - at : (size_t)1 << 20;
        memset(xml + at, ' ', run);
        if (run > 4) memcpy(xml + at + run - 4, "<x/>", 4);
        at += run;
    }
    memcpy(xml + body, "</robot>\n", strlen("</robot>\n"));
    xml[max] = '\0';
    char msg[256];
    vt_builder *b;
    vt_status st;
    if (full) {
        st = vt_urdf_builder_string(&b, xml, NULL, msg);
        if (st != VT_OK) fail_msg("a string of VT_URDF_MAX_BYTES: status %d, message \"%s\"", (int)st, msg);
        assert_int_equal(vt_builder_find_body(b, "a"), 1);
        vt_builder_free(b);
    }
    xml[max] = ' ';
    xml[max + 1] = '\0'; /* one byte more */
    st = vt_urdf_builder_string(&b, xml, NULL, msg);
    if (st != VT_ERR_XML || b || !strstr(msg, "VT_URDF_MAX_BYTES") || !strstr(msg, "268435456"))
        fail_msg("a string of VT_URDF_MAX_BYTES + 1: status %d, message \"%s\"", (int)st, msg);
    free(xml);
    /* files (sparse): exactly the bound, read whole; one byte more, refused by its size */
    char dir[] = "/tmp/vtdyn_urdf_size_XXXXXX", path[64];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/big.urdf", dir);
    for (size_t size = max; size <= max + 1; size++) {
        if (size == max && !full) continue;
        FILE *f = fopen(path, "wb");
        assert_non_null(f);
        assert_int_equal(fwrite(robot, 1, n, f), n);
        assert_int_equal(fseek(f, (long)size - 1, SEEK_SET), 0); /* a hole up to the last byte */
        assert_int_equal(fputc(' ', f), ' ');
        assert_int_equal(fclose(f), 0);
        st = vt_urdf_builder(&b, path, NULL, msg);
        if (size == max) { /* read whole: libxml2 takes the first NUL byte after the robot as its end */
            if (st != VT_OK) fail_msg("a file of VT_URDF_MAX_BYTES: status %d, message \"%s\"", (int)st, msg);
            assert_int_equal(vt_builder_find_body(b, "a"), 1);
            vt_builder_free(b);
        }
        if (size > max && (st != VT_ERR_FILE || b || !strstr(msg, "big.urdf") || !strstr(msg, "VT_URDF_MAX_BYTES")))
            fail_msg("a file of VT_URDF_MAX_BYTES + 1: status %d, message \"%s\"", (int)st, msg);
    }
    remove(path);
    rmdir(dir);
    /* a device that never ends */
    if (full) {
        st = vt_urdf_builder(&b, "/dev/zero", NULL, msg);
        if (st != VT_ERR_FILE || b || !strstr(msg, "/dev/zero") || !strstr(msg, "VT_URDF_MAX_BYTES"))
            fail_msg("/dev/zero: status %d, message \"%s\"", (int)st, msg);
    }
}

/* A chain of n revolute links as a generated file writes it, an element a line (16 lines a link),
 * its links and its joints each in a scrambled order (link k + 1 at position k · 7919 mod n), so
 * that neither the file's order nor sorted names give the tree's; mimic joints every 1000th
 * joint (mimicking the joint before). With dup, a second link "l<dup>" at the end. The line of
 * link l<k> into *line_of (when not NULL). */
static char *chain_urdf(int n, int dup, long *line_of, int want)
{
    const size_t cap = 1024 + (size_t)n * 720;
    char *s = malloc(cap);
    assert_non_null(s);
    size_t k = (size_t)snprintf(s, cap, "<?xml version=\"1.0\"?>\n<robot name=\"chain\">\n  <link name=\"base\"/>\n");
    long line = 4;
    for (int pass = 0; pass < 2; pass++)
        for (int e = 0; e < n; e++) {
            const int i = 1 + (int)((long)e * 7919 % n); /* 7919 is prime: a permutation unless n is its multiple */
            if (pass == 0) {
                if (i == want && line_of) *line_of = line;
                k += (size_t)snprintf(s + k, cap - k,
                                      "  <link name=\"l%d\">\n    <inertial>\n      <origin xyz=\"0.25 0 0\"/>\n"
                                      "      <mass value=\"1\"/>\n      <inertia ixx=\"2e-4\" ixy=\"0\" ixz=\"0\" "
                                      "iyy=\"0.0208\" iyz=\"0\" izz=\"0.0208\"/>\n    </inertial>\n  </link>\n",
                                      i);
                line += 7;
            } else {
                char parent[24] = "base", mimic[64] = "";
                if (i > 1) snprintf(parent, sizeof parent, "l%d", i - 1);
                if (i > 1 && i % 1000 == 0) snprintf(mimic, sizeof mimic, "    <mimic joint=\"j%d\" multiplier=\"2\"/>\n", i - 1);
                k += (size_t)snprintf(s + k, cap - k,
                                      "  <joint name=\"j%d\" type=\"revolute\">\n    <parent link=\"%s\"/>\n"
                                      "    <child link=\"l%d\"/>\n    <origin xyz=\"%s 0 0\"/>\n"
                                      "    <axis xyz=\"0 0 1\"/>\n%s  </joint>\n",
                                      i, parent, i, i > 1 ? "0.5" : "0", mimic);
                line += 6 + (mimic[0] != 0);
            }
        }
    if (dup) k += (size_t)snprintf(s + k, cap - k, "  <link name=\"l%d\"/>\n", dup);
    snprintf(s + k, cap - k, "</robot>\n");
    return s;
}

/* loads the chain of n links, checks its bodies in the tree's order and its couplings */
static void load_chain(int n)
{
    char *xml = chain_urdf(n, 0, NULL, 0);
    {
        char msg[256];
        vt_builder *b = NULL;
        const vt_status st = vt_urdf_builder_string(&b, xml, NULL, msg);
        if (st != VT_OK) fail_msg("a chain of %d links: status %d, message \"%s\"", n, (int)st, msg);
        /* body k is link l<k> (breadth-first from the root, whatever the file's order) */
        for (int k = 1; k <= n; k++) {
            char name[24];
            snprintf(name, sizeof name, "l%d", k);
            if (vt_builder_find_body(b, name) != k) fail_msg("%s: body %d", name, vt_builder_find_body(b, name));
        }
        assert_int_equal(vt_builder_find_body(b, "base"), VT_ERR_NOT_FOUND); /* the ground */
        vt_body_def d = vt_default_body_def(); /* one more body takes the next id */
        d.parent = n;
        assert_int_equal(vt_builder_add_body(b, &d), n + 1);
        vt_coupling_def c = vt_default_coupling_def(); /* the mimic joints' couplings came first */
        c.body_a = n + 1;
        c.body_b = 1;
        assert_int_equal(vt_builder_add_coupling(b, &c), n / 1000);
        vt_builder_free(b);
    }
    free(xml);
}

/* No bound on links beyond memory (and VT_COUNT_MAX): a generated chain of 20,000 links (2,000
 * under valgrind), written in a scrambled order, loads with its bodies in the tree's order. Its
 * time per link (O(n log n) names, a linear tree walk) is the benchmark bench_scale's */
static void test_long_chain(void **state)
{
    (void)state;
    load_chain(under_valgrind() ? 2000 : 20000);
}

/* Lines past 65535 (libxml2 2.9 keeps an element's line in 16 bits): a link named twice in a
 * file of 200,000 lines is refused naming both lines exactly, and so is a joint that gives a link
 * a second parent */
static void test_lines_past_65535(void **state)
{
    (void)state;
    if (under_valgrind()) skip();
    const int n = 13000, dup = 1 + (int)((long)(n - 1) * 7919 % n); /* the last link in the file */
    long first = 0;
    char *xml = chain_urdf(n, dup, &first, dup);
    assert_true(first > 65535);
    const long last = 4 + 13L * n + n / 1000; /* the duplicate's line: after every link and joint */
    char msg[256], want[160];
    vt_builder *b;
    vt_status st = vt_urdf_builder_string(&b, xml, NULL, msg);
    snprintf(want, sizeof want, "link \"l%d\" (line %ld): name already taken by the link on line %ld", dup, last, first);
    if (st != VT_ERR_BAD_NAME || !strstr(msg, want)) fail_msg("status %d, message \"%s\", expected \"%s\"", (int)st, msg, want);
    free(xml);
}

static int report(void **state)
{
    (void)state;
    printf("largest relative difference against the C scenes: %.3g\n", worst);
    return 0;
}

/* Mimic joints become couplings (q_m = multiplier q_j + offset), or are ignored with mimic = 0;
 * the coupled motion keeps the coupling at the acceleration level and equals a model whose
 * coupling is added by hand. A placeholder inertia (rank one, 1e-6 in all six entries) on a link
 * fixed to a heavier one is accepted: the merged body's is sound. */
static void test_mimic_and_placeholders(void **state)
{
    (void)state;
    const char *xml =
        "<robot name=\"r\"><link name=\"world\"/>"
        "<link name=\"a\"><inertial><origin xyz=\"0.5 0 0\"/><mass value=\"2\"/>"
        "<inertia ixx=\"0.01\" iyy=\"0.2\" izz=\"0.2\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>"
        "<link name=\"b\"><inertial><origin xyz=\"0.3 0 0\"/><mass value=\"1\"/>"
        "<inertia ixx=\"0.01\" iyy=\"0.05\" izz=\"0.05\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>"
        "<link name=\"cam\"><inertial><mass value=\"1e-6\"/>"
        "<inertia ixx=\"1e-6\" iyy=\"1e-6\" izz=\"1e-6\" ixy=\"1e-6\" ixz=\"1e-6\" iyz=\"1e-6\"/></inertial></link>"
        "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/><child link=\"a\"/><axis xyz=\"0 0 1\"/></joint>"
        "<joint name=\"m\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"1 0 0\"/>"
        "<axis xyz=\"0 1 0\"/><mimic joint=\"j\" multiplier=\"-0.5\" offset=\"0.1\"/></joint>"
        "<joint name=\"c\" type=\"fixed\"><parent link=\"a\"/><child link=\"cam\"/><origin xyz=\"0.2 0 0\"/></joint>"
        "</robot>";
    vt_urdf_options opt = vt_default_urdf_options();
    char msg[256];
    vt_builder *b;
    assert_int_equal(vt_urdf_builder_string(&b, xml, &opt, msg), VT_OK);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nbody, 2);
    assert_int_equal(m->ncoupling, 1);
    assert_int_equal(vt_find_coupling(m, "m"), 0);
    assert_int_equal(m->coupling[0].body_a, vt_find_joint(m, "m"));
    assert_int_equal(m->coupling[0].body_b, vt_find_joint(m, "j"));
    assert_near(m->coupling[0].ratio, -0.5, 0.0);
    assert_near(m->coupling[0].offset, 0.1, 0.0);
    /* without the mimic: two free joints; the coupling added by hand gives the same instant */
    opt.mimic = 0;
    assert_int_equal(vt_urdf_builder_string(&b, xml, &opt, msg), VT_OK);
    vt_model *free2;
    assert_ok(vt_builder_build(&free2, b));
    assert_int_equal(free2->ncoupling, 0);
    vt_coupling_def c = vt_default_coupling_def();
    c.body_a = vt_builder_find_body(b, "b");
    c.body_b = vt_builder_find_body(b, "a");
    c.ratio = -0.5;
    c.offset = 0.1;
    assert_int_equal(vt_builder_add_coupling(b, &c), 0);
    vt_model *hand;
    assert_ok(vt_builder_build(&hand, b));
    vt_builder_free(b);
    vt_data *d, *dh;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dh, hand));
    d->q[0] = dh->q[0] = 0.3;
    d->q[1] = dh->q[1] = -0.5 * 0.3 + 0.1;
    d->qd[0] = dh->qd[0] = 0.8;
    d->qd[1] = dh->qd[1] = -0.5 * 0.8;
    assert_ok(vt_inverse_dynamics(m, d));
    assert_ok(vt_inverse_dynamics(hand, dh));
    assert_near(d->qdd[1], -0.5 * d->qdd[0], 1e-12); /* the coupling held */
    assert_near(d->qdd[0], dh->qdd[0], 1e-12 * (1 + fabs(dh->qdd[0])));
    assert_near(d->coupling_effort[0], dh->coupling_effort[0], 1e-12 * (1 + fabs(dh->coupling_effort[0])));
    vt_data_free(d);
    vt_data_free(dh);
    vt_model_free(m);
    vt_model_free(free2);
    vt_model_free(hand);
}

/* A payload fixed to a link through the API (vt_builder_add_payload on the link's frame, after a
 * tool frame placed on the tool's frame) equals the same payload and tool frame written into the
 * file as links fixed to it (the loader's own merge): the efforts and every reaction of
 * vt_inverse_dynamics_motion to 1e-15 at random states, and every link frame's pose, on each of
 * the robot's links: a moving one (arm, forearm) and one merged by a fixed joint (tool). With
 * inertia_tol (the URDF options' model), an inertia 0.18 % off the triangle inequality loads. */
static void test_payload_as_edited_file(void **state)
{
    (void)state;
    static const char *const links[3] = {"arm", "forearm", "tool"};
    const double pm = 5.0, pc[3] = {0.12, -0.07, 0.21};
    const double pI[9] = {0.03, 0.004, -0.002, 0.004, 0.05, 0.001, -0.002, 0.001, 0.04};
    const double tcp_xyz[3] = {0.01, 0.02, 0.15}, tcp_rpy[3] = {0.3, -0.2, 1.1};
    char xml[8192], edited[12288], msg[256];
    tool_urdf(xml, sizeof xml);
    double worst_payload = 0.0;
    for (int l = 0; l < 3; l++) {
        const size_t n = strlen(xml) - strlen("</robot>\n");
        memcpy(edited, xml, n);
        snprintf(edited + n, sizeof edited - n,
                 "  <link name=\"payload\"><inertial><origin xyz=\"%.17g %.17g %.17g\"/><mass value=\"%.17g\"/>"
                 "<inertia ixx=\"%.17g\" ixy=\"%.17g\" ixz=\"%.17g\" iyy=\"%.17g\" iyz=\"%.17g\" izz=\"%.17g\"/>"
                 "</inertial></link>\n"
                 "  <joint name=\"grip\" type=\"fixed\"><parent link=\"%s\"/><child link=\"payload\"/></joint>\n"
                 "  <link name=\"tcp\"/>\n"
                 "  <joint name=\"tcp_joint\" type=\"fixed\"><parent link=\"tool\"/><child link=\"tcp\"/>"
                 "<origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/></joint>\n</robot>\n",
                 pc[0], pc[1], pc[2], pm, pI[0], pI[3], pI[6], pI[4], pI[7], pI[8], links[l], tcp_xyz[0], tcp_xyz[1],
                 tcp_xyz[2], tcp_rpy[0], tcp_rpy[1], tcp_rpy[2]);
        vt_builder *be, *ba;
        if (vt_urdf_builder_string(&be, edited, NULL, msg) != VT_OK) fail_msg("%s", msg);
        if (vt_urdf_builder_string(&ba, xml, NULL, msg) != VT_OK) fail_msg("%s", msg);
        vt_frame_def f = vt_default_frame_def();
        f.name = "tcp";
        f.reference = "tool";
        memcpy(f.point, tcp_xyz, sizeof tcp_xyz);
        rpy_quat(f.orientation, tcp_rpy[0], tcp_rpy[1], tcp_rpy[2]);
        assert_true(vt_builder_add_frame(ba, &f) >= 0);
        vt_payload_def p = vt_default_payload_def();
        p.frame = links[l];
        p.mass = pm;
        memcpy(p.point, pc, sizeof pc);
        memcpy(p.inertia, pI, sizeof pI);
        assert_int_equal(vt_builder_add_payload(ba, &p), l == 0 ? 1 : 2);
        vt_model *me, *ma;
        assert_ok(vt_builder_build(&me, be));
        assert_ok(vt_builder_build(&ma, ba));
        vt_builder_free(be);
        vt_builder_free(ba);
        assert_int_equal(ma->nbody, me->nbody);
        vt_data *de, *da;
        assert_ok(vt_data_create(&de, me));
        assert_ok(vt_data_create(&da, ma));
        uint64_t seed = 5 + (uint64_t)l;
        for (int s = 0; s < 5; s++) {
            for (int k = 0; k < 2; k++) {
                da->q[k] = de->q[k] = vt_rand_uniform(&seed, -3.0, 3.0);
                da->qd[k] = de->qd[k] = vt_rand_uniform(&seed, -2.0, 2.0);
                da->qdd[k] = de->qdd[k] = vt_rand_uniform(&seed, -5.0, 5.0);
            }
            assert_ok(vt_inverse_dynamics_motion(ma, da));
            assert_ok(vt_inverse_dynamics_motion(me, de));
            worst_payload = fmax(worst_payload, vt_test_motion_diff(ma, da, de));
            static const char *const frames[5] = {"world", "arm", "forearm", "tool", "tcp"};
            for (int k = 0; k < 5; k++) {
                double pa[3], Ra[9], pe[3], Re[9];
                assert_ok(vt_frame_pose(ma, da, vt_find_frame(ma, frames[k]), pa, Ra));
                assert_ok(vt_frame_pose(me, de, vt_find_frame(me, frames[k]), pe, Re));
                for (int e = 0; e < 3; e++) assert_near(pa[e], pe[e], 1e-15);
                for (int e = 0; e < 9; e++) assert_near(Ra[e], Re[e], 1e-15);
            }
        }
        vt_data_free(de);
        vt_data_free(da);
        vt_model_free(me);
        vt_model_free(ma);
    }
    print_message("payload through the API against the edited file: largest relative difference %.3g\n", worst_payload);
    /* two orders of the same sums (the URDF's merge, the payload's): 1e-15 measured without FMA
     * contraction, 2e-15 with (-march=native) */
    if (!(worst_payload <= 1e-14)) fail_msg("relative difference %.3g > 1e-14", worst_payload);

    /* inertia_tol in the URDF options: romeo_small's 0.18 % off the triangle inequality */
    const char *romeo = "<robot name=\"r\"><link name=\"world\"/><link name=\"a\"><inertial><mass value=\"1\"/>"
                        "<inertia ixx=\"1\" iyy=\"1\" izz=\"2.0036\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>"
                        "<joint name=\"j\" type=\"continuous\"><parent link=\"world\"/><child link=\"a\"/></joint></robot>";
    vt_urdf_options opt = vt_default_urdf_options();
    vt_builder *b;
    assert_int_equal(vt_urdf_builder_string(&b, romeo, &opt, msg), VT_ERR_INERTIA_TRIANGLE);
    assert_non_null(strstr(msg, "inertia_tol"));
    opt.model.inertia_tol = 2e-3;
    assert_int_equal(vt_urdf_builder_string(&b, romeo, &opt, msg), VT_OK);
    vt_builder_free(b);
}

/* ---- reactions in the URDF joint frame ------------------------------------------------ */

/* Two revolute joints and a prismatic one, every origin and inertial frame turned (rpy), axes off
 * the frames' axes */
static const char jf_urdf[] =
    "<robot name='jf'><link name='base'/>"
    "<link name='a'><inertial><origin xyz='0.1 -0.05 0.2' rpy='0.3 -0.2 0.5'/><mass value='2'/>"
    "<inertia ixx='0.3' iyy='0.25' izz='0.2' ixy='0.01' ixz='-0.02' iyz='0.015'/></inertial></link>"
    "<link name='b'><inertial><origin xyz='0.25 0.05 -0.1' rpy='-0.4 0.1 0.7'/><mass value='1.5'/>"
    "<inertia ixx='0.12' iyy='0.1' izz='0.08' ixy='0' ixz='0.01' iyz='0'/></inertial></link>"
    "<link name='c'><inertial><origin xyz='0.0 0.1 0.15' rpy='0.2 0.6 -0.3'/><mass value='0.8'/>"
    "<inertia ixx='0.05' iyy='0.04' izz='0.06' ixy='0.005' ixz='0' iyz='-0.004'/></inertial></link>"
    "<joint name='j1' type='revolute'><parent link='base'/><child link='a'/>"
    "<origin xyz='0.1 0.2 0.3' rpy='0.4 -0.3 0.9'/><axis xyz='0 0.6 0.8'/>"
    "<limit lower='-2' upper='2' effort='100' velocity='3'/></joint>"
    "<joint name='j2' type='continuous'><parent link='a'/><child link='b'/>"
    "<origin xyz='0.5 -0.1 0.05' rpy='-1.1 0.2 0.35'/><axis xyz='1 0 0'/></joint>"
    "<joint name='j3' type='prismatic'><parent link='b'/><child link='c'/>"
    "<origin xyz='0.3 0.1 -0.2' rpy='0.5 0.7 -0.6'/><axis xyz='0.6 0 0.8'/>"
    "<limit lower='-1' upper='1' effort='50' velocity='2'/></joint></robot>";

static void test_joint_frame_reactions(void **state)
{
    (void)state;
    static const double q[3] = {0.3, -0.7, 0.25}, qd[3] = {1.1, -0.6, -0.4}, qdd[3] = {0.5, 1.3, 0.7};
    /* the chain in URDF's terms: link frames, joint origins, inertial frames */
    static const double xyz[3][3] = {{0.1, 0.2, 0.3}, {0.5, -0.1, 0.05}, {0.3, 0.1, -0.2}};
    static const double rpy[3][3] = {{0.4, -0.3, 0.9}, {-1.1, 0.2, 0.35}, {0.5, 0.7, -0.6}};
    static const double axis[3][3] = {{0, 0.6, 0.8}, {1, 0, 0}, {0.6, 0, 0.8}};
    static const double cxyz[3][3] = {{0.1, -0.05, 0.2}, {0.25, 0.05, -0.1}, {0.0, 0.1, 0.15}};
    static const double crpy[3][3] = {{0.3, -0.2, 0.5}, {-0.4, 0.1, 0.7}, {0.2, 0.6, -0.3}};
    static const double mass[3] = {2.0, 1.5, 0.8};
    static const double in[3][6] = {{0.3, 0.25, 0.2, 0.01, -0.02, 0.015}, {0.12, 0.1, 0.08, 0, 0.01, 0},
                                    {0.05, 0.04, 0.06, 0.005, 0, -0.004}}; /* xx yy zz xy xz yz */
    vt_ne_body nb[4];
    memset(nb, 0, sizeof nb);
    for (int k = 1; k <= 3; k++) {
        vt_ne_body *B = &nb[k];
        B->parent = k - 1;
        B->kind = k == 3 ? 2 : 0;
        memcpy(B->s_par, xyz[k - 1], sizeof B->s_par);
        vt_ne_rpy(B->pre, rpy[k - 1][0], rpy[k - 1][1], rpy[k - 1][2]);
        memcpy(B->u1, axis[k - 1], sizeof B->u1);
        B->post[0] = B->post[4] = B->post[8] = 1.0;
        B->mass = mass[k - 1];
        memcpy(B->c, cxyz[k - 1], sizeof B->c);
        const double *I = in[k - 1];
        const double Ji[9] = {I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2]};
        double Ri[9], T[9], RiT[9];
        vt_ne_rpy(Ri, crpy[k - 1][0], crpy[k - 1][1], crpy[k - 1][2]);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) RiT[r + 3 * c] = Ri[c + 3 * r];
        vt_ne_mul(T, Ri, Ji);
        vt_ne_mul(B->J, T, RiT); /* in the link frame */
    }
    const double g[3] = {0, 0, -9.81};
    double F[12], M[12], Fr[12], Mr[12], R[36];
    vt_ne_chain(nb, 3, q, qd, qdd, g, F, M, Fr, Mr, R);
    double scale = 0.0;
    for (int k = 3; k < 12; k++) scale = fmax(scale, fmax(fabs(F[k]), fabs(M[k])));
    char msg[256];
    for (int drives = 0; drives < 2; drives++) {
        vt_builder *b;
        if (vt_urdf_builder_string(&b, jf_urdf, NULL, msg) != VT_OK) fail_msg("%s", msg);
        for (int k = 1; drives && k <= 3; k++) {
            const double coef[3] = {q[k - 1], qd[k - 1], 0.5 * qdd[k - 1]};
            vt_test_add_joint_drive(b, k, 0, vt_function_polynomial(3, coef));
        }
        vt_model *m = vt_test_build(b);
        assert_int_equal(vt_find_joint(m, "j3"), 3);
        for (int path = 0; path < (drives ? 2 : 1); path++) {
            vt_data *d;
            assert_ok(vt_data_create(&d, m));
            memcpy(d->q, q, sizeof q);
            memcpy(d->qd, qd, sizeof qd);
            memcpy(d->qdd, qdd, sizeof qdd);
            assert_ok(!drives ? vt_inverse_dynamics_motion(m, d)
                              : path ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d));
            assert_ok(vt_reactions_joint_frame(m, d));
            for (int k = 1; k <= 3; k++) {
                /* the URDF joint frame is the child's link frame R_k; the bearing axis the URDF axis */
                double fj[3], mj[3];
                vt_ne_mtv(fj, R + 9 * k, Fr + 3 * k);
                vt_ne_mtv(mj, R + 9 * k, Mr + 3 * k);
                for (int c = 0; c < 3; c++) {
                    assert_near(d->jnt_force_joint[3 * k + c], fj[c], 1e-12 * scale);
                    assert_near(d->jnt_moment_joint[3 * k + c], mj[c], 1e-12 * scale);
                    assert_near(m->jnt_frame_axis[3 * k + c], axis[k - 1][c], 1e-15);
                }
                const double *a = axis[k - 1], fa = a[0] * fj[0] + a[1] * fj[1] + a[2] * fj[2],
                             ma = a[0] * mj[0] + a[1] * mj[1] + a[2] * mj[2];
                double fr[3], mr[3];
                for (int c = 0; c < 3; c++) fr[c] = fj[c] - fa * a[c], mr[c] = mj[c] - ma * a[c];
                const double *bb = d->jnt_bearing + 4 * k;
                assert_near(bb[0], fa, 1e-12 * scale);
                assert_near(bb[1], sqrt(fr[0] * fr[0] + fr[1] * fr[1] + fr[2] * fr[2]), 1e-12 * scale);
                assert_near(bb[2], ma, 1e-12 * scale);
                assert_near(bb[3], sqrt(mr[0] * mr[0] + mr[1] * mr[1] + mr[2] * mr[2]), 1e-12 * scale);
                /* the joint's own effort is what is not reaction: a turning joint's axial moment and
                 * a sliding one's axial force are zero */
                assert_near(bb[k == 3 ? 0 : 2], 0.0, 1e-12 * scale);
            }
            vt_data_free(d);
        }
        vt_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_link),
        cmocka_unit_test(test_five_link),
        cmocka_unit_test(test_merged_and_rotated),
        cmocka_unit_test(test_floating_root),
        cmocka_unit_test(test_floating_pose),
        cmocka_unit_test(test_comma_locale),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_mimic_and_placeholders),
        cmocka_unit_test(test_entities),
        cmocka_unit_test(test_size_bound),
        cmocka_unit_test(test_long_chain),
        cmocka_unit_test(test_lines_past_65535),
        cmocka_unit_test(test_payload_as_edited_file),
        cmocka_unit_test(test_joint_frame_reactions),
    };
    return cmocka_run_group_tests(tests, NULL, report);
}
