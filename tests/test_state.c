/* src/kinematics/state.c: applied point loads, and q advanced along q̇ against the rotation it should
 * produce. */
#include "vt_test.h"

static void test_point_load_bad_input_changes_nothing(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_double_link(&m, 0));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    const double s[3] = {1, 0, 0}, f[3] = {0, -10, 0}, bad[3] = {0, NAN, 0};
    assert_ok(vt_add_point_load(m, d, 2, s, f, NULL));
    double before[18];
    memcpy(before, d->xfrc, sizeof before);
    assert_int_equal(vt_add_point_load(m, d, 3, s, f, NULL), VT_ERR_BAD_INDEX);
    assert_int_equal(vt_add_point_load(m, d, 0, s, f, NULL), VT_ERR_BAD_INDEX);
    assert_int_equal(vt_add_point_load(m, d, 1, s, bad, NULL), VT_ERR_NONFINITE);
    assert_int_equal(vt_add_point_load(m, d, 1, NULL, f, NULL), VT_ERR_NULL);
    assert_memory_equal(before, d->xfrc, sizeof before);
    /* at q = 0 link 2 lies along +x: 10 N down at 1 m from its centre is −10 N·m about z */
    assert_near(d->xfrc[6 * 2 + 1], -10.0, 1e-15);
    assert_near(d->xfrc[6 * 2 + 5], -10.0, 1e-15);
    vt_data_free(d);
    vt_model_free(m);
}

/* A of a body from q, via the kinematics */
static void body_rotation(double A[9], const vt_model *m, vt_data *d, const double *q, int body)
{
    memcpy(d->q, q, (size_t)m->nq * sizeof(double));
    assert_ok(vt_kinematics(m, d));
    memcpy(A, d->A + 9 * body, 9 * sizeof(double));
}

static void integrate_q(unsigned kinds)
{
    vt_model *m = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_random_tree(&m, 11, 12, kinds));
    assert_ok(vt_data_create(&d, m));
    uint64_t s = 9;
    vt_scene_random_state(m, d, &s);
    double *q = malloc((size_t)m->nq * sizeof(double)), *qp = malloc((size_t)m->nq * sizeof(double));
    double *qm = malloc((size_t)m->nq * sizeof(double)), *v = malloc((size_t)m->nv * sizeof(double));
    memcpy(q, d->q, (size_t)m->nq * sizeof(double));
    memcpy(v, d->qd, (size_t)m->nv * sizeof(double));
    const double h = 1e-5;
    assert_ok(vt_integrate_q(qp, m, q, v, h));
    assert_ok(vt_integrate_q(qm, m, q, v, -h));
    for (int i = 1; i <= m->nbody; i++) {
        const int jt = m->body_joint[i], qa = m->body_qadr[i], va = m->body_vadr[i];
        if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_BASE || jt == VT_JOINT_FREE) {
            const int o = jt == VT_JOINT_SPHERICAL ? 0 : 3;
            const double *p = qp + qa + o;
            assert_near(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3], 1.0, 1e-14);
            if (jt == VT_JOINT_FREE) /* the translation along its rates, exactly */
                for (int k = 0; k < 3; k++) assert_near(qp[qa + k], q[qa + k] + h * v[va + k], 1e-15);
            if (jt == VT_JOINT_BASE)
                for (int k = 0; k < 7; k++) assert_near((qp[qa + k] - qm[qa + k]) / (2 * h), v[va + k], 1e-8);
        } else {
            for (int k = 0; k < m->body_nq[i]; k++) assert_near(qp[qa + k], q[qa + k] + h * v[va + k], 1e-15);
        }
    }
    /* a spherical joint's rates are the relative angular velocity in the reference's axes:
     * d/dt (A^{jT} A^i) = ω̃' (A^{jT} A^i) with ω' = q̇ */
    for (int i = 1; i <= m->nbody; i++) {
        if (m->body_joint[i] != VT_JOINT_SPHERICAL && m->body_joint[i] != VT_JOINT_FREE) continue;
        const int j = m->body_parent[i];
        double Ai[9], Aj[9], Aip[9], Ajp[9], Aim[9], Ajm[9], rel[9], relp[9], relm[9];
        body_rotation(Ai, m, d, q, i);
        memcpy(Aj, d->A + 9 * j, sizeof Aj);
        body_rotation(Aip, m, d, qp, i);
        memcpy(Ajp, d->A + 9 * j, sizeof Ajp);
        body_rotation(Aim, m, d, qm, i);
        memcpy(Ajm, d->A + 9 * j, sizeof Ajm);
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++) {
                rel[r + 3 * c] = relp[r + 3 * c] = relm[r + 3 * c] = 0.0;
                for (int k = 0; k < 3; k++) {
                    rel[r + 3 * c] += Aj[k + 3 * r] * Ai[k + 3 * c];
                    relp[r + 3 * c] += Ajp[k + 3 * r] * Aip[k + 3 * c];
                    relm[r + 3 * c] += Ajm[k + 3 * r] * Aim[k + 3 * c];
                }
            }
        /* the relative rotation of the body's axes includes the fixed A0 on the right: the
         * derivative is still ω̃' rel */
        const double *w = v + m->body_vadr[i] + (m->body_joint[i] == VT_JOINT_FREE ? 3 : 0);
        for (int c = 0; c < 3; c++) {
            const double *u = rel + 3 * c;
            const double wu[3] = {w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]};
            for (int r = 0; r < 3; r++)
                assert_near((relp[r + 3 * c] - relm[r + 3 * c]) / (2 * h), wu[r], 1e-8);
        }
    }
    /* bad input: status, output untouched */
    double *keep = malloc((size_t)m->nq * sizeof(double));
    memcpy(keep, qp, (size_t)m->nq * sizeof(double));
    v[0] = NAN;
    assert_int_equal(vt_integrate_q(qp, m, q, v, h), VT_ERR_NONFINITE);
    assert_memory_equal(keep, qp, (size_t)m->nq * sizeof(double));
    free(keep);
    free(q); free(qp); free(qm); free(v);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_integrate_q(void **state)
{
    (void)state;
    integrate_q(VT_SCENE_ALL_JOINTS);
    integrate_q(VT_SCENE_WITH_FREE); /* free joints: the translation, then as spherical */
}

/* Frames: a frame's pose against the double link's geometry; a load and a point drive at a
 * frame equal the same given by body and point (bitwise); a cut joint at frames equals the
 * four-bar's; bad frames refused */
static void test_frames(void **state)
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
    vt_frame_def f = vt_default_frame_def();
    f.name = "tip";
    f.body = 2;
    f.point[0] = 1.0; /* the far end of link 2 */
    vt_quat_axis_angle(f.orientation, (const double[3]){0, 0, 1}, 0.25); /* turned 0.25 rad about z */
    assert_int_equal(vt_builder_add_frame(b, &f), 0);
    vt_frame_def bad = f;
    assert_int_equal(vt_builder_add_frame(b, &bad), VT_ERR_BAD_NAME); /* "tip" taken */
    bad.name = NULL;
    assert_int_equal(vt_builder_add_frame(b, &bad), VT_ERR_BAD_NAME); /* a frame needs a name */
    bad.name = "elsewhere";
    bad.body = 3;
    assert_int_equal(vt_builder_add_frame(b, &bad), VT_ERR_BAD_INDEX);
    bad.body = 1;
    bad.orientation[0] = bad.orientation[1] = bad.orientation[2] = bad.orientation[3] = 0.0;
    assert_int_equal(vt_builder_add_frame(b, &bad), VT_ERR_QUATERNION);
    vt_drive_def pd = vt_default_drive_def();
    pd.type = VT_DRIVE_POINT;
    pd.index = 1;
    pd.frame = "tip"; /* the tip's y */
    pd.f = vt_function_sine(-1.0, 0.5, 2.0, 0.0);
    assert_int_equal(vt_builder_add_drive(b, &pd), 0);
    pd.frame = "nowhere";
    assert_int_equal(vt_builder_add_drive(b, &pd), VT_ERR_NOT_FOUND);
    pd.type = VT_DRIVE_JOINT;
    pd.frame = "tip";
    assert_int_equal(vt_builder_add_drive(b, &pd), VT_ERR_BAD_DRIVE); /* frames place point drives */
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->drive[0].body, 2);
    assert_near(m->drive[0].point[0], 1.0, 0.0);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    const double q1 = -0.4, q2 = 0.9;
    d->q[0] = q1;
    d->q[1] = q2;
    assert_ok(vt_kinematics(m, d));
    double P[3], R[9];
    assert_ok(vt_frame_pose(m, d, 0, P, R));
    assert_near(P[0], 2 * cos(q1) + 2 * cos(q1 + q2), 1e-14);
    assert_near(P[1], 2 * sin(q1) + 2 * sin(q1 + q2), 1e-14);
    assert_near(P[2], 0.0, 1e-14);
    const double a = q1 + q2 + 0.25; /* the frame's axes: turned q1 + q2 + 0.25 about z */
    assert_near(R[0], cos(a), 1e-14);
    assert_near(R[1], sin(a), 1e-14);
    assert_near(R[3], -sin(a), 1e-14);
    assert_near(R[8], 1.0, 1e-14);
    assert_int_equal(vt_frame_pose(m, d, 1, P, NULL), VT_ERR_BAD_INDEX);
    /* a load at the frame equals the same load at link 2's point (1, 0, 0) */
    const double fl[3] = {3.0, -4.0, 1.0}, nl[3] = {0.5, 0.0, -0.2};
    assert_ok(vt_add_frame_load(m, d, 0, fl, nl));
    double x1[12];
    memcpy(x1, d->xfrc + 6, sizeof x1);
    memset(d->xfrc, 0, 18 * sizeof(double));
    assert_ok(vt_add_point_load(m, d, 2, (const double[3]){1.0, 0.0, 0.0}, fl, nl));
    assert_memory_equal(x1, d->xfrc + 6, sizeof x1);
    assert_int_equal(vt_add_frame_load(m, d, 5, fl, nl), VT_ERR_BAD_INDEX);
    vt_data_free(d);
    vt_model_free(m);
}

/* Finite inputs whose results overflow are refused and change nothing: two loads of 1.5e308 N
 * on one body sum past DBL_MAX in xfrc; q + h q̇ with q̇ = 1e300 and h = 1e10 is Inf (every kind
 * of joint), also in place (q_out = q). Before, both returned VT_OK with Inf in the outputs. */
static void test_overflow_changes_nothing(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_double_link(&m, 0));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    const double s[3] = {1, 0, 0}, f[3] = {1.5e308, 0, 0}, n[3] = {0, 0, 1.5e308};
    assert_ok(vt_add_point_load(m, d, 2, s, f, n));
    double before[18];
    memcpy(before, d->xfrc, sizeof before);
    assert_int_equal(vt_add_point_load(m, d, 2, s, f, NULL), VT_ERR_NONFINITE);
    assert_true(strlen(d->message) > 0);
    assert_int_equal(vt_add_point_load(m, d, 2, s, NULL, n), VT_ERR_NONFINITE);
    assert_memory_equal(before, d->xfrc, sizeof before);
    vt_data_free(d);
    vt_model_free(m);

    assert_ok(vt_scene_random_tree(&m, 3, 12, VT_SCENE_ALL_JOINTS));
    assert_ok(vt_data_create(&d, m));
    const size_t nq = (size_t)m->nq;
    double *q = malloc(nq * sizeof(double)), *q_out = malloc(nq * sizeof(double)), *v = malloc((size_t)m->nv * sizeof(double));
    memcpy(q, d->q, nq * sizeof(double));
    for (int k = 0; k < m->nv; k++) v[k] = 1e300;
    for (size_t k = 0; k < nq; k++) q_out[k] = 42.0;
    assert_int_equal(vt_integrate_q(q_out, m, q, v, 1e10), VT_ERR_NONFINITE);
    for (size_t k = 0; k < nq; k++) assert_true(q_out[k] == 42.0);
    memcpy(q_out, q, nq * sizeof(double));
    assert_int_equal(vt_integrate_q(q_out, m, q_out, v, 1e10), VT_ERR_NONFINITE);
    assert_memory_equal(q_out, q, nq * sizeof(double));
    free(q); free(q_out); free(v);
    vt_data_free(d);
    vt_model_free(m);

    /* without Euler parameters every q advances linearly: q + h v entry by entry; a NaN or Inf
     * in q, v or h, or a sum past DBL_MAX, refused with the output untouched */
    assert_ok(vt_scene_chain(&m, 4, VT_CHAIN_FREE));
    double ql[4] = {0.1, -0.2, 0.3, 1e308}, vl[4] = {1.0, 2.0, -3.0, 0.0}, ol[4], keep[4] = {42.0, 42.0, 42.0, 42.0};
    assert_ok(vt_integrate_q(ol, m, ql, vl, 0.5));
    for (int k = 0; k < 4; k++) assert_true(ol[k] == ql[k] + 0.5 * vl[k]);
    const struct { int k; double q, v, h; } bad[] = {
        {0, NAN, 1.0, 0.5}, {1, 0.0, NAN, 0.5}, {2, INFINITY, 0.0, 0.5}, {3, 1e308, 1e308, 1.0}, {0, 0.0, INFINITY, 0.0},
        {1, 0.0, 1.0, INFINITY}};
    for (size_t c = 0; c < sizeof bad / sizeof bad[0]; c++) {
        double qb[4], vb[4];
        memcpy(qb, ql, sizeof qb);
        memcpy(vb, vl, sizeof vb);
        qb[bad[c].k] = bad[c].q;
        vb[bad[c].k] = bad[c].v;
        memcpy(ol, keep, sizeof ol);
        assert_int_equal(vt_integrate_q(ol, m, qb, vb, bad[c].h), VT_ERR_NONFINITE);
        assert_memory_equal(ol, keep, sizeof ol);
    }
    vt_model_free(m);
}

/* A frame whose position overflows (a point 1.5e308 m out on a body 1.5e308 m out along the same
 * axis) is refused with VT_ERR_NONFINITE, the caller's array untouched (it returned VT_OK with
 * Inf); the same frame at q = 0 is where the sum puts it. */
static void test_frame_pose_overflow(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_TRANSLATIONAL;
    body.axis1[0] = 1.0; body.axis1[1] = 0.0; body.axis1[2] = 0.0;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_frame_def fr = vt_default_frame_def();
    fr.name = "far";
    fr.point[0] = 1.5e308;
    assert_int_equal(vt_builder_add_frame(b, &fr), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    double pos[3] = {1, 2, 3};
    assert_ok(vt_kinematics(m, d));
    assert_ok(vt_frame_pose(m, d, 0, pos, NULL));
    assert_true(pos[0] == 1.5e308 && pos[1] == 0.0 && pos[2] == 0.0);
    d->q[0] = 1.5e308;
    assert_ok(vt_kinematics(m, d));
    pos[0] = 1; pos[1] = 2; pos[2] = 3;
    assert_int_equal(vt_frame_pose(m, d, 0, pos, NULL), VT_ERR_NONFINITE);
    assert_true(strlen(d->message) > 0);
    assert_true(pos[0] == 1 && pos[1] == 2 && pos[2] == 3);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_load_bad_input_changes_nothing),
        cmocka_unit_test(test_integrate_q),
        cmocka_unit_test(test_frames),
        cmocka_unit_test(test_overflow_changes_nothing),
        cmocka_unit_test(test_frame_pose_overflow),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
