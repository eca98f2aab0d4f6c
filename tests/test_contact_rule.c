/* The distribution rule (analysis/contact_rule.c) against closed forms, a second method and
 * identities:
 * - a box on four corner contacts, no actuated rate: the rule's answer is the minimum-norm
 *   solution of the six balance equations (Σ f = m (a − g), Σ r × f = 0), solved here by the
 *   test with LAPACK's dgesv, wherever that solution lies inside the friction pyramids; at rest
 *   and symmetric each corner carries m g / 4; accelerated sideways beyond μ cos(π/4) g it must
 *   slip, and downward faster than g it must pull: both refused, the contact named, the forces
 *   and xfrc untouched;
 * - the quadruped (examples/scenes.c) standing: each foot carries M g / 4 by symmetry, the free
 *   root's efforts vanish, and every joint's effort is τ⁰ − Σ J_cᵀ f with τ⁰ the instant without
 *   contacts and J_c the feet's Jacobians by central differences of vt_frame_pose; the same forces
 *   applied as frame loads (vt_add_frame_load) give the same efforts; with a front foot lifted
 *   the diagonal pair under the centre of mass carries it all, half each; two points of one body
 *   cannot hold the torso (no moment about their line): refused;
 * - the rule itself on the quadruped moving, every foot inside its pyramid: the forces minimize
 *   ½ Σ w_a τ_a² + ½ Σ w_c |f_c|² subject to the free root's six equations, so with the feet's
 *   Jacobians (the root's columns e_k and e_k × (p − o), the joints' by central differences of
 *   vt_frame_pose) the test forms G, c and the equalities itself and solves the KKT system by
 *   LAPACK's dgesv; efforts weighted unevenly, one foot's weight apart;
 * - the quadruped on a diagonal pair (a trot's instant, examples/trot.c): the motion given whole is
 *   refused; the root's moment about the pair's line is affine in the torso's angular acceleration
 *   along it (checked at a third value), and with that component solved here from two instants of
 *   vt_inverse_dynamics_motion the instant is carried: the root's efforts zero, the swing feet's
 *   forces exactly zero, τ⁰ − Σ J_cᵀ f by central differences as above;
 * - a box on a tilting plate carried by a lift (contacts touching another body): the forces sum
 *   to the box's m (a − g) and make no moment about its centre; the lift's force is the three
 *   bodies' weight and acceleration, (m_l + m_p + m_b)(a + g), the plate's torque the box's load
 *   about its axis, ((r_b − P) × m_b (a + g) z)_x, both closed forms; the pyramids turn with the
 *   plate: tilted by tan β = 0.2 the box stands within μ cos(π/4) = 0.35 of the plate's normal,
 *   by 0.45 it must slip (it would stand on a pyramid that stayed level).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vt_test.h"
#include "scenes.h"

#define G0 9.81
#define PI 3.14159265358979323846

/* |a − b| within rel times the problem's scale */
#define assert_near_rel(a, b, rel, scale) assert_near(a, b, (rel) * (scale))

/* the box's state: at height 0.1, orientation identity, at rest, its centre accelerated by acc */
static void box_state(const vt_model *m, vt_data *d, const double acc[3])
{
    memcpy(d->q, m->q0, (size_t)m->nq * sizeof(double));
    d->q[2] = 0.1;
    memset(d->qd, 0, (size_t)m->nv * sizeof(double));
    memset(d->qdd, 0, (size_t)m->nv * sizeof(double));
    /* the free joint's rates are twists about o (its point, here the centre of mass), the three
     * translations first: at rest their accelerations are the centre's */
    for (int e = 0; e < 3; e++) d->qdd[e] = acc[e];
}

static void test_box(void **state)
{
    (void)state;
    const double mass = 8.0;
    vt_model *m = vt_test_contact_box(mass);
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    struct {
        double xf, xh, acc[3], mu;
    } cases[] = {{0.3, -0.3, {0, 0, 0}, 1.0},      /* symmetric: m g / 4 each */
                 {0.35, -0.15, {0, 0, 0}, 1.0},    /* the centre of mass off the middle */
                 {0.3, -0.3, {0.3 * G0, 0, 0}, 0.5}, /* sideways within the pyramid (0.3 < 0.5 cos 45°) */
                 {0.3, -0.25, {0.1, -0.4, 1.0}, 0.8}};
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        vt_contact_def def[4];
        vt_test_box_corners(def, cases[t].xf, cases[t].xh, cases[t].mu);
        vt_contacts *c = NULL;
        char msg[VT_MESSAGE_SIZE];
        assert_ok(vt_contacts_create(&c, m, def, 4, NULL, msg));
        assert_int_equal(vt_contacts_count(c), 4);
        box_state(m, d, cases[t].acc);
        double f[12], want[12];
        vt_test_min_norm_forces(def, mass, cases[t].acc, want);
        for (int k = 0; k < 4; k++) { /* the closed form inside the pyramids: it is the rule's answer */
            const double *w = want + 3 * k;
            assert_true(w[2] > 0.0);
            assert_true(fabs(w[0]) <= cases[t].mu * cos(PI / 4) * w[2] && fabs(w[1]) <= cases[t].mu * cos(PI / 4) * w[2]);
        }
        assert_ok(vt_inverse_dynamics_contacts(m, d, c, NULL, f));
        for (int k = 0; k < 12; k++) assert_near_rel(f[k], want[k], 1e-10, mass * G0);
        if (t == 0)
            for (int k = 0; k < 4; k++) assert_near_rel(f[3 * k + 2], mass * G0 / 4.0, 1e-12, mass * G0);
        for (int a = 0; a < 6; a++) assert_near_rel(d->qfrc_drive[a], 0.0, 1e-12, mass * G0); /* nothing actuated */
        for (int k = 0; k < 6 * (m->nbody + 1); k++) assert_true(d->xfrc[k] == 0.0); /* xfrc as it was */
        vt_contacts_free(c);
    }
    /* slip: 0.5 g sideways on mu 0.5 (at most 0.354 g); pull: down at 1.5 g */
    const double slip[3] = {0.5 * G0, 0, 0}, pull[3] = {0, 0, -1.5 * G0};
    for (int t = 0; t < 2; t++) {
        vt_contact_def def[4];
        vt_test_box_corners(def, 0.3, -0.3, 0.5);
        vt_contacts *c = NULL;
        assert_ok(vt_contacts_create(&c, m, def, 4, NULL, NULL));
        box_state(m, d, t == 0 ? slip : pull);
        double f[12];
        for (int k = 0; k < 12; k++) f[k] = 42.0;
        assert_int_equal(vt_inverse_dynamics_contacts(m, d, c, NULL, f), VT_ERR_CONTACT);
        assert_non_null(strstr(d->message, t == 0 ? "slip" : "pull"));
        assert_non_null(strstr(d->message, "contact "));
        for (int k = 0; k < 12; k++) assert_true(f[k] == 42.0);
        for (int k = 0; k < 6 * (m->nbody + 1); k++) assert_true(d->xfrc[k] == 0.0);
        vt_contacts_free(c);
    }
    /* bilateral corners hold the pull: the minimum-norm forces, negative */
    {
        vt_contact_def def[4];
        vt_test_box_corners(def, 0.3, -0.3, 0.5);
        for (int k = 0; k < 4; k++) def[k].kind = VT_CONTACT_BILATERAL;
        vt_contacts *c = NULL;
        assert_ok(vt_contacts_create(&c, m, def, 4, NULL, NULL));
        box_state(m, d, pull);
        double f[12], want[12];
        vt_test_min_norm_forces(def, mass, pull, want);
        assert_ok(vt_inverse_dynamics_contacts(m, d, c, NULL, f));
        for (int k = 0; k < 12; k++) assert_near_rel(f[k], want[k], 1e-10, mass * G0);
        assert_true(f[2] < 0.0);
        vt_contacts_free(c);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* ∂p/∂q_a of frame fr's origin by central differences of vt_frame_pose (z's q restored, its
 * kinematics left at a perturbed q: the caller runs vt_kinematics again where it needs them) */
static void frame_column(const vt_model *m, vt_data *z, int fr, int a, double col[3])
{
    const int qa = m->body_qadr[m->dof_body[a]];
    double pp[3], pm[3], R[9];
    const double h = 1e-6, q0 = z->q[qa];
    z->q[qa] = q0 + h;
    assert_ok(vt_kinematics(m, z));
    assert_ok(vt_frame_pose(m, z, fr, pp, R));
    z->q[qa] = q0 - h;
    assert_ok(vt_kinematics(m, z));
    assert_ok(vt_frame_pose(m, z, fr, pm, R));
    z->q[qa] = q0;
    for (int e = 0; e < 3; e++) col[e] = (pp[e] - pm[e]) / (2 * h);
}

static void test_quadruped(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_quadruped(&m));
    vt_data *d = NULL, *d0 = NULL;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&d0, m));
    const char *const *foot = VT_TEST_FOOT;
    vt_contact_def def[4];
    vt_test_feet(def, 0.8, VT_CONTACT_UNILATERAL);
    vt_contacts *c = NULL;
    assert_ok(vt_contacts_create(&c, m, def, 4, NULL, NULL));
    assert_int_equal(vt_find_contact(c, "HL_foot"), 2);
    assert_int_equal(vt_find_contact(c, "knee"), VT_ERR_NOT_FOUND);
    const double W = VT_QUADRUPED_MASS * G0, theta = 0.6;
    vt_scene_quadruped_stand(m, d, theta);
    /* a motion too: the joints moving, the torso swaying */
    for (int a = 6; a < m->nv; a++) {
        d->qd[a] = 0.3 * sin(1.7 * a);
        d->qdd[a] = 0.5 * cos(0.9 * a);
    }
    for (int pass = 0; pass < 2; pass++) { /* at rest (symmetric), then moving */
        vt_data *s = pass == 0 ? d0 : d;
        if (pass == 0) vt_scene_quadruped_stand(m, s, theta);
        double f[12];
        assert_ok(vt_inverse_dynamics_contacts(m, s, c, NULL, f));
        double sum[3] = {0, 0, 0};
        for (int k = 0; k < 4; k++) {
            for (int e = 0; e < 3; e++) sum[e] += f[3 * k + e];
            assert_true(f[3 * k + 2] >= 0.0); /* pushes, within the pyramid */
            assert_true(fabs(f[3 * k]) <= 0.8 * cos(PI / 4) * f[3 * k + 2] + 1e-12 * W);
            assert_true(fabs(f[3 * k + 1]) <= 0.8 * cos(PI / 4) * f[3 * k + 2] + 1e-12 * W);
            if (pass == 0) assert_near_rel(f[3 * k + 2], W / 4.0, 1e-10, W);
        }
        if (pass == 0) {
            assert_near_rel(sum[0], 0.0, 1e-12, W);
            assert_near_rel(sum[1], 0.0, 1e-12, W);
        }
        for (int a = 0; a < 6; a++) assert_near_rel(s->qfrc_drive[a], 0.0, 1e-10, W); /* the free root */
        /* τ = τ⁰ − Σ J_cᵀ f: τ⁰ the instant alone, J_c by central differences on each joint */
        vt_data *z = NULL;
        assert_ok(vt_data_create(&z, m));
        memcpy(z->q, s->q, (size_t)m->nq * sizeof(double));
        memcpy(z->qd, s->qd, (size_t)m->nv * sizeof(double));
        memcpy(z->qdd, s->qdd, (size_t)m->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(m, z));
        for (int a = 6; a < m->nv; a++) {
            double tau = z->qfrc_drive[a];
            for (int k = 0; k < 4; k++) {
                double col[3];
                frame_column(m, z, vt_find_frame(m, foot[k]), a, col);
                for (int e = 0; e < 3; e++) tau -= col[e] * f[3 * k + e];
            }
            assert_near_rel(s->qfrc_drive[a], tau, 1e-8, W);
        }
        /* the same forces as frame loads: the same efforts */
        memcpy(z->q, s->q, (size_t)m->nq * sizeof(double));
        assert_ok(vt_kinematics(m, z));
        for (int k = 0; k < 4; k++) assert_ok(vt_add_frame_load(m, z, vt_find_frame(m, foot[k]), f + 3 * k, NULL));
        assert_ok(vt_inverse_dynamics_motion(m, z));
        for (int a = 0; a < m->nv; a++) assert_near_rel(s->qfrc_drive[a], z->qfrc_drive[a], 1e-12, W);
        vt_data_free(z);
    }
    /* symmetric legs carry mirrored torques at rest: FL and FR, HL and HR alike in flexion */
    assert_near_rel(d0->qfrc_drive[m->body_vadr[vt_find_body(m, "FL_thigh")]],
                    d0->qfrc_drive[m->body_vadr[vt_find_body(m, "FR_thigh")]], 1e-10, W);
    /* the front left foot lifted: the centre of mass (over the middle) lies on the line from FR
     * to HL, so those two feet carry half the weight each and HR nothing (its moment about that
     * line has nothing to balance); FL's force is zero */
    vt_scene_quadruped_stand(m, d, theta);
    const int active[4] = {0, 1, 1, 1};
    double f[12];
    for (int k = 0; k < 12; k++) f[k] = 42.0;
    assert_ok(vt_inverse_dynamics_contacts(m, d, c, active, f));
    assert_true(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0);
    assert_near_rel(f[5], W / 2.0, 1e-9, W);
    assert_near_rel(f[8], W / 2.0, 1e-9, W);
    assert_near_rel(f[11], 0.0, 1e-9, W);
    for (int a = 0; a < 6; a++) assert_near_rel(d->qfrc_drive[a], 0.0, 1e-10, W);
    /* two points of one body (a bilateral one on the FL shank, the FL foot): their forces make no
     * moment about the line through them, which the torso needs; the root's equations are
     * dependent there and their rest unreachable: refused, not answered with huge forces that
     * cancel each other */
    {
        vt_contact_def two[2] = {vt_default_contact_def(), vt_default_contact_def()};
        two[0].kind = VT_CONTACT_BILATERAL;
        two[0].body = vt_find_body(m, "FL_shank");
        two[0].point[0] = 0.05;
        two[1].frame = "FL_foot";
        vt_contacts *c2 = NULL;
        assert_ok(vt_contacts_create(&c2, m, two, 2, NULL, NULL));
        vt_scene_quadruped_stand(m, d, theta);
        double f2[6] = {42, 42, 42, 42, 42, 42};
        assert_int_equal(vt_inverse_dynamics_contacts(m, d, c2, NULL, f2), VT_ERR_CONTACT);
        assert_non_null(strstr(d->message, "cannot give"));
        for (int k = 0; k < 6; k++) assert_true(f2[k] == 42.0);
        vt_contacts_free(c2);
    }
    vt_contacts_free(c);
    vt_data_free(d);
    vt_data_free(d0);
    vt_model_free(m);
}

/* the rule against its KKT system solved here: [G −A_uᵀ; A_u 0] [f; λ] = [−c; τ⁰_u] with
 * G = J_Aᵀ W J_A + W_f, c = −J_Aᵀ W τ⁰_A, J the feet's 3 x nv Jacobians in world axes */
static void test_rule(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_quadruped(&m));
    const int nv = m->nv, nf = 12;
    assert_int_equal(nv, 18);
    vt_data *d = NULL, *z = NULL;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&z, m));
    const char *const *foot = VT_TEST_FOOT;
    vt_contact_def def[4];
    vt_test_feet(def, 0.9, VT_CONTACT_UNILATERAL);
    def[2].weight = 4e-4;
    double w[18];
    for (int a = 0; a < nv; a++) w[a] = 1.0 + 0.1 * a;
    vt_contacts *c = NULL;
    assert_ok(vt_contacts_create(&c, m, def, 4, w, NULL));
    for (int seed = 0; seed < 5; seed++) {
        vt_scene_quadruped_stand(m, d, 0.55 + 0.03 * seed);
        for (int a = 0; a < nv; a++) {
            d->qd[a] = 0.2 * sin(1.3 * a + seed);
            d->qdd[a] = (a < 6 ? 0.3 : 0.8) * cos(0.7 * a + 2.0 * seed);
        }
        double f[12];
        assert_ok(vt_inverse_dynamics_contacts(m, d, c, NULL, f));
        const double W = VT_QUADRUPED_MASS * G0;
        for (int k = 0; k < 4; k++) { /* inside the pyramid: no face binds, the equalities decide */
            assert_true(f[3 * k + 2] > 0.05 * W);
            assert_true(fabs(f[3 * k]) < 0.8 * 0.9 * cos(PI / 4) * f[3 * k + 2]);
            assert_true(fabs(f[3 * k + 1]) < 0.8 * 0.9 * cos(PI / 4) * f[3 * k + 2]);
        }
        /* τ⁰ and the Jacobians from the state alone */
        memcpy(z->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(z->qd, d->qd, (size_t)nv * sizeof(double));
        memcpy(z->qdd, d->qdd, (size_t)nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(m, z));
        double tau0[18], J[12 * 18] = {0}; /* J: row 3k + e, column a (column-major, ld 12) */
        memcpy(tau0, z->qfrc_drive, sizeof tau0);
        const double *o = z->jpoint + 3; /* the free joint's point, body 1 */
        for (int k = 0; k < 4; k++) {
            const int fr = vt_find_frame(m, foot[k]);
            double p[3], R[9];
            assert_ok(vt_frame_pose(m, z, fr, p, R));
            const double r[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
            for (int e = 0; e < 3; e++) J[3 * k + e + 12 * e] = 1.0;
            /* e_x × r = (0, −r_z, r_y), e_y × r = (r_z, 0, −r_x), e_z × r = (−r_y, r_x, 0) */
            J[3 * k + 1 + 12 * 3] = -r[2], J[3 * k + 2 + 12 * 3] = r[1];
            J[3 * k + 0 + 12 * 4] = r[2], J[3 * k + 2 + 12 * 4] = -r[0];
            J[3 * k + 0 + 12 * 5] = -r[1], J[3 * k + 1 + 12 * 5] = r[0];
            for (int a = 6; a < nv; a++) {
                double col[3];
                frame_column(m, z, fr, a, col);
                for (int e = 0; e < 3; e++) J[3 * k + e + 12 * a] = col[e];
            }
            assert_ok(vt_kinematics(m, z));
        }
        /* the KKT matrix (18 x 18: 12 forces, 6 multipliers) and its right side */
        double K[18 * 18] = {0}, b[18] = {0};
        for (int i = 0; i < nf; i++) {
            for (int j = 0; j < nf; j++) {
                double g = 0.0;
                for (int a = 6; a < nv; a++) g += J[i + 12 * a] * w[a] * J[j + 12 * a];
                K[i + 18 * j] = g + (i == j ? def[i / 3].weight : 0.0);
            }
            double cc = 0.0;
            for (int a = 6; a < nv; a++) cc -= J[i + 12 * a] * w[a] * tau0[a];
            b[i] = -cc;
            for (int h = 0; h < 6; h++) {
                K[i + 18 * (nf + h)] = -J[i + 12 * h];
                K[nf + h + 18 * i] = J[i + 12 * h];
            }
        }
        for (int h = 0; h < 6; h++) b[nf + h] = tau0[h];
        int n18 = 18, one = 1, ipiv[18], info = 0;
        dgesv_(&n18, &one, K, &n18, ipiv, b, &n18, &info); /* LAPACK, not the library's solve */
        assert_int_equal(info, 0);
        for (int i = 0; i < nf; i++) assert_near_rel(f[i], b[i], 1e-7, W);
    }
    vt_contacts_free(c);
    vt_data_free(d);
    vt_data_free(z);
    vt_model_free(m);
}

/* u · (M_o + (o − p1) × F) of the root's efforts (F, M_o): their moment about the line through p1
 * along u, o the root's point (the torso's centre of mass, q[0..2]) */
static double line_moment(const vt_data *d, const double u[3], const double p1[3])
{
    const double r[3] = {d->q[0] - p1[0], d->q[1] - p1[1], d->q[2] - p1[2]}, *F = d->qfrc_drive;
    const double c[3] = {r[1] * F[2] - r[2] * F[1], r[2] * F[0] - r[0] * F[2], r[0] * F[1] - r[1] * F[0]};
    return u[0] * (F[3] + c[0]) + u[1] * (F[4] + c[1]) + u[2] * (F[5] + c[2]);
}

static void test_diagonal_pair(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_quadruped(&m));
    vt_data *d = NULL, *z = NULL;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&z, m));
    const char *const *foot = VT_TEST_FOOT;
    vt_contact_def def[4];
    vt_test_feet(def, 0.8, VT_CONTACT_UNILATERAL);
    vt_contacts *c = NULL;
    assert_ok(vt_contacts_create(&c, m, def, 4, NULL, NULL));
    const double W = VT_QUADRUPED_MASS * G0;
    const int active[4] = {1, 0, 0, 1}; /* FL and HR: a trot's pair */
    vt_scene_quadruped_stand(m, d, 0.6);
    d->q[3] = cos(0.02), d->q[4] = sin(0.02) * 0.6, d->q[5] = sin(0.02) * 0.8; /* tilted a little */
    for (int a = 0; a < m->nv; a++) {
        d->qd[a] = 0.2 * sin(1.3 * a + 0.4);
        d->qdd[a] = 0.3 * cos(0.7 * a + 0.1);
    }
    assert_ok(vt_kinematics(m, d));
    double p1[3], p2[3], R[9], u[3];
    assert_ok(vt_frame_pose(m, d, vt_find_frame(m, foot[0]), p1, R));
    assert_ok(vt_frame_pose(m, d, vt_find_frame(m, foot[3]), p2, R));
    const double len = sqrt((p2[0] - p1[0]) * (p2[0] - p1[0]) + (p2[1] - p1[1]) * (p2[1] - p1[1]) +
                            (p2[2] - p1[2]) * (p2[2] - p1[2]));
    for (int e = 0; e < 3; e++) u[e] = (p2[e] - p1[e]) / len;
    double f[12];
    for (int k = 0; k < 12; k++) f[k] = 42.0;
    assert_int_equal(vt_inverse_dynamics_contacts(m, d, c, active, f), VT_ERR_CONTACT); /* given whole */
    assert_non_null(strstr(d->message, "cannot give"));
    for (int k = 0; k < 12; k++) assert_true(f[k] == 42.0);
    /* the moment about the line at three values of α·u: affine (the instant is linear in q̈) */
    const double along = d->qdd[3] * u[0] + d->qdd[4] * u[1] + d->qdd[5] * u[2];
    double r[3];
    for (int j = 0; j < 3; j++) {
        memcpy(z->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(z->qd, d->qd, (size_t)m->nv * sizeof(double));
        memcpy(z->qdd, d->qdd, (size_t)m->nv * sizeof(double));
        for (int e = 0; e < 3; e++) z->qdd[3 + e] += (j - along) * u[e];
        assert_ok(vt_inverse_dynamics_motion(m, z));
        r[j] = line_moment(z, u, p1);
    }
    assert_near_rel(r[2], 2.0 * r[1] - r[0], 1e-12, W);
    assert_true(fabs(r[0]) > 1e-3 * W); /* 2 N m here: the motion given whole is far from carried */
    const double s = -r[0] / (r[1] - r[0]);
    for (int e = 0; e < 3; e++) d->qdd[3 + e] += (s - along) * u[e];
    assert_ok(vt_inverse_dynamics_contacts(m, d, c, active, f));
    for (int k = 3; k < 9; k++) assert_true(f[k] == 0.0); /* FR and HL swing */
    for (int k = 0; k < 4; k += 3) {
        assert_true(f[3 * k + 2] > 0.0);
        assert_true(fabs(f[3 * k]) <= 0.8 * cos(PI / 4) * f[3 * k + 2] + 1e-12 * W);
        assert_true(fabs(f[3 * k + 1]) <= 0.8 * cos(PI / 4) * f[3 * k + 2] + 1e-12 * W);
    }
    for (int a = 0; a < 6; a++) assert_near_rel(d->qfrc_drive[a], 0.0, 1e-10, W);
    /* τ = τ⁰ − Σ J_cᵀ f on the joints, J_c by central differences */
    memcpy(z->q, d->q, (size_t)m->nq * sizeof(double));
    memcpy(z->qdd, d->qdd, (size_t)m->nv * sizeof(double));
    assert_ok(vt_inverse_dynamics_motion(m, z));
    for (int a = 6; a < m->nv; a++) {
        double tau = z->qfrc_drive[a];
        for (int k = 0; k < 4; k += 3) {
            double col[3];
            frame_column(m, z, vt_find_frame(m, foot[k]), a, col);
            for (int e = 0; e < 3; e++) tau -= col[e] * f[3 * k + e];
        }
        assert_near_rel(d->qfrc_drive[a], tau, 1e-8, W);
    }
    /* off the solved value the instant is refused again */
    for (int e = 0; e < 3; e++) d->qdd[3 + e] += 0.5 * u[e];
    assert_int_equal(vt_inverse_dynamics_contacts(m, d, c, active, f), VT_ERR_CONTACT);
    vt_contacts_free(c);
    vt_data_free(z);
    vt_data_free(d);
    vt_model_free(m);
}

/* a lift (3 kg, translational along z from the ground), a plate on it (5 kg, its centre at the
 * lift's, tilting about x) and a free box (2 kg, 0.4 x 0.3 x 0.2 m) standing on the plate on four
 * bottom corners, μ 0.5; the box at rest on the plate tilted by beta, the lift accelerating up
 * by acc: the state into d */
static vt_model *lift_model(vt_contacts **c, const vt_model **out)
{
    vt_builder *b = NULL;
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = 0.0, md.gravity[2] = -G0;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def lift = vt_default_body_def(), plate = vt_default_body_def(), box = vt_default_body_def();
    lift.joint = VT_JOINT_TRANSLATIONAL;
    lift.mass = 3.0;
    lift.inertia[0] = lift.inertia[4] = lift.inertia[8] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &lift), 1);
    plate.parent = 1;
    plate.axis1[0] = 1.0, plate.axis1[1] = 0.0, plate.axis1[2] = 0.0;
    plate.mass = 5.0;
    plate.inertia[0] = plate.inertia[4] = plate.inertia[8] = 0.2;
    assert_int_equal(vt_builder_add_body(b, &plate), 2);
    box.joint = VT_JOINT_FREE;
    box.mass = 2.0;
    box.inertia[0] = 2.0 * (0.09 + 0.04) / 12.0;
    box.inertia[4] = 2.0 * (0.16 + 0.04) / 12.0;
    box.inertia[8] = 2.0 * (0.16 + 0.09) / 12.0;
    assert_int_equal(vt_builder_add_body(b, &box), 3);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_contact_def def[4];
    for (int k = 0; k < 4; k++) {
        def[k] = vt_default_contact_def();
        def[k].body = 3;
        def[k].other = 2;
        def[k].mu = 0.5;
        def[k].point[0] = k < 2 ? 0.2 : -0.2;
        def[k].point[1] = k % 2 ? -0.15 : 0.15;
        def[k].point[2] = -0.1;
    }
    assert_ok(vt_contacts_create(c, m, def, 4, NULL, NULL));
    *out = m;
    return m;
}

static void lift_state(const vt_model *m, vt_data *d, double beta, double acc)
{
    memset(d->qd, 0, (size_t)m->nv * sizeof(double));
    memset(d->qdd, 0, (size_t)m->nv * sizeof(double));
    d->q[0] = 0.3, d->qdd[0] = acc; /* the lift */
    d->q[1] = beta;                 /* the plate */
    double *p = d->q + m->body_qadr[3];
    p[0] = 0.0, p[1] = -0.1 * sin(beta), p[2] = 0.3 + 0.1 * cos(beta); /* the box's centre, 0.1 above the plate */
    p[3] = cos(beta / 2), p[4] = sin(beta / 2), p[5] = p[6] = 0.0;  /* turned with the plate */
    d->qdd[m->body_vadr[3] + 2] = acc;                              /* and lifted with it */
}

static void test_other_body(void **state)
{
    (void)state;
    vt_contacts *c = NULL;
    const vt_model *m = NULL;
    vt_model *mm = lift_model(&c, &m);
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    const double mb = 2.0, acc = 1.5, W = (3.0 + 5.0 + 2.0) * (G0 + acc);
    const double beta = atan(0.2);
    lift_state(m, d, beta, acc);
    double f[12];
    assert_ok(vt_inverse_dynamics_contacts(m, d, c, NULL, f));
    double sum[3] = {0, 0, 0}, mom[3] = {0, 0, 0};
    const double n[3] = {0.0, -sin(beta), cos(beta)}, t2[3] = {0.0, cos(beta), sin(beta)};
    for (int k = 0; k < 4; k++) {
        const double *fk = f + 3 * k;
        double rp[3], R[9], mk[3]; /* the corner from the box's centre, global */
        vt_ne_quat(R, d->q + m->body_qadr[3] + 3);
        const double pt[3] = {k < 2 ? 0.2 : -0.2, k % 2 ? -0.15 : 0.15, -0.1};
        for (int e = 0; e < 3; e++) rp[e] = R[e] * pt[0] + R[e + 3] * pt[1] + R[e + 6] * pt[2];
        mk[0] = rp[1] * fk[2] - rp[2] * fk[1], mk[1] = rp[2] * fk[0] - rp[0] * fk[2], mk[2] = rp[0] * fk[1] - rp[1] * fk[0];
        for (int e = 0; e < 3; e++) sum[e] += fk[e], mom[e] += mk[e];
        const double fn = n[0] * fk[0] + n[1] * fk[1] + n[2] * fk[2];
        const double ft1 = fk[0], ft2 = t2[0] * fk[0] + t2[1] * fk[1] + t2[2] * fk[2];
        assert_true(fn > 0.0);
        assert_true(fabs(ft1) <= 0.5 * cos(PI / 4) * fn + 1e-12 * W && fabs(ft2) <= 0.5 * cos(PI / 4) * fn + 1e-12 * W);
    }
    assert_near_rel(sum[0], 0.0, 1e-12, W);
    assert_near_rel(sum[1], 0.0, 1e-12, W);
    assert_near_rel(sum[2], mb * (G0 + acc), 1e-12, W);
    for (int e = 0; e < 3; e++) assert_near_rel(mom[e], 0.0, 1e-12, W);
    for (int a = 0; a < 6; a++) assert_near_rel(d->qfrc_drive[m->body_vadr[3] + a], 0.0, 1e-12, W); /* the box's root */
    assert_near_rel(d->qfrc_drive[0], W, 1e-12, W);                                          /* the lift */
    assert_near_rel(d->qfrc_drive[1], -0.1 * sin(beta) * mb * (G0 + acc), 1e-12, W);          /* the plate */
    /* tilted by tan 0.45: beyond the turned pyramid's 0.35, the box slips */
    lift_state(m, d, atan(0.45), acc);
    for (int k = 0; k < 12; k++) f[k] = 42.0;
    assert_int_equal(vt_inverse_dynamics_contacts(m, d, c, NULL, f), VT_ERR_CONTACT);
    assert_non_null(strstr(d->message, "slip"));
    assert_true(f[0] == 42.0);
    /* the touched body: not the contact's own, a moving body or the ground */
    vt_contact_def bad = vt_default_contact_def();
    bad.body = 3;
    vt_contacts *c2 = NULL;
    char msg[VT_MESSAGE_SIZE];
    for (int other = 3; other <= 4; other += 1) {
        bad.other = other;
        assert_int_equal(vt_contacts_create(&c2, m, &bad, 1, NULL, msg), VT_ERR_BAD_INDEX);
        assert_non_null(strstr(msg, "other"));
    }
    bad.other = -1;
    assert_int_equal(vt_contacts_create(&c2, m, &bad, 1, NULL, msg), VT_ERR_BAD_INDEX);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(mm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_quadruped),
        cmocka_unit_test(test_rule),
        cmocka_unit_test(test_diagonal_pair),
        cmocka_unit_test(test_other_body),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
