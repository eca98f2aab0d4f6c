/* src/model/payload.c: a payload on a body of a random tree equals the body defined with the
 * merged mass properties computed here by the parallel axes (written from the definitions, not
 * the library's); vt_builder_set_mass equals the body defined with those values; bad payloads
 * refused, each with its status and message, the builder unchanged. (A payload on a URDF link
 * against the file with the payload written in: test_urdf.) */
#include <stdio.h>

#include "vt_test.h"

/* J += R I Rᵀ + m (|d|² 1 − d dᵀ), written here from the definitions (not the library's) */
static void parallel_axes(double J[9], const double R[9], const double I[9], double m, const double d[3])
{
    double RI[9] = {0};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++) RI[r + 3 * c] += R[r + 3 * k] * I[k + 3 * c];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            double v = 0.0;
            for (int k = 0; k < 3; k++) v += RI[r + 3 * k] * R[c + 3 * k];
            J[r + 3 * c] += v + m * ((r == c ? d[0] * d[0] + d[1] * d[1] + d[2] * d[2] : 0.0) - d[r] * d[c]);
        }
}


/* A payload on a body of a random tree (examples/scenes.c), placed through a frame turned and
 * offset on the body, equals the same tree whose body is defined with the merged mass
 * properties computed here (the masses summed, the centre of mass their mean, the inertias by
 * the parallel axes) and its points written from the new centre of mass: the efforts and every
 * reaction of vt_inverse_dynamics_motion to 1e-15 at random states. The frames added before the
 * payload stay where they were on the body (their poses those of the tree without it), and the
 * point drive's and cut joint's points on the body move with the centre of mass. */
static void test_payload_on_scene_tree(void **state)
{
    (void)state;
    const int n = 8, k = 3; /* the payload's body */
    vt_model *c0;
    assert_ok(vt_scene_random_tree(&c0, 7, n, VT_SCENE_WITH_FREE));
    const double pm = 2.5, pt[3] = {0.3, -0.1, 0.25}; /* in the frame's axes from its origin */
    const double pI[9] = {0.02, 0.003, -0.001, 0.003, 0.03, 0.002, -0.001, 0.002, 0.025};
    const double fo[4] = {0.8, 0.2, -0.4, 0.4}, fp[3] = {0.1, 0.2, -0.15}; /* the frame on body k (unit below) */
    double q[4], R[9], nq = 0.0;
    for (int e = 0; e < 4; e++) nq += fo[e] * fo[e];
    for (int e = 0; e < 4; e++) q[e] = fo[e] / sqrt(nq);
    /* R from the Euler parameters, written out (A = (2e0² − 1) 1 + 2 (e eᵀ + e0 ẽ)) */
    const double e0 = q[0], e1 = q[1], e2 = q[2], e3 = q[3];
    const double Rm[9] = {2 * (e0 * e0 + e1 * e1) - 1, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2),
                          2 * (e1 * e2 - e0 * e3), 2 * (e0 * e0 + e2 * e2) - 1, 2 * (e2 * e3 + e0 * e1),
                          2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), 2 * (e0 * e0 + e3 * e3) - 1};
    memcpy(R, Rm, sizeof R);
    double p[3]; /* the payload's centre of mass in body k's axes from its centre of mass */
    for (int r = 0; r < 3; r++) p[r] = fp[r] + R[r] * pt[0] + R[r + 3] * pt[1] + R[r + 6] * pt[2];
    const double M = c0->body_mass[k] + pm;
    double cm[3], J[9] = {0}, d[3];
    for (int e = 0; e < 3; e++) cm[e] = pm * p[e] / M;
    const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int e = 0; e < 3; e++) d[e] = -cm[e];
    parallel_axes(J, I3, c0->body_inertia + 9 * k, c0->body_mass[k], d);
    for (int e = 0; e < 3; e++) d[e] = p[e] - cm[e];
    parallel_axes(J, R, pI, pm, d);

    vt_builder *ba, *bb;
    assert_ok(vt_builder_create(&ba, NULL));
    assert_ok(vt_builder_create(&bb, NULL));
    for (int i = 1; i <= n; i++) {
        vt_body_def a = vt_test_body_of(c0, i), b = a;
        if (i == k) {
            b.mass = M;
            memcpy(b.inertia, J, sizeof J);
            for (int e = 0; e < 3; e++) b.joint_child[e] -= cm[e];
        }
        if (b.parent == k)
            for (int e = 0; e < 3; e++) b.joint_parent[e] -= cm[e];
        assert_int_equal(vt_builder_add_body(ba, &a), i);
        assert_int_equal(vt_builder_add_body(bb, &b), i);
    }
    vt_frame_def f = vt_default_frame_def();
    f.name = "grip";
    f.body = k;
    memcpy(f.point, fp, sizeof fp);
    memcpy(f.orientation, fo, sizeof fo); /* not unit: normalized */
    assert_int_equal(vt_builder_add_frame(ba, &f), 0);
    assert_int_equal(vt_builder_find_frame(ba, "grip"), 0);
    assert_int_equal(vt_builder_find_frame(ba, "grasp"), VT_ERR_NOT_FOUND);
    assert_int_equal(vt_builder_find_frame(NULL, "grip"), VT_ERR_NULL);
    vt_payload_def pl = vt_default_payload_def();
    pl.frame = "grip";
    pl.mass = pm;
    memcpy(pl.point, pt, sizeof pt);
    memcpy(pl.inertia, pI, sizeof pI);
    assert_int_equal(vt_builder_add_payload(ba, &pl), k);
    assert_string_equal(vt_builder_message(ba), "");
    vt_model *ma = vt_test_build(ba), *mb = vt_test_build(bb);
    vt_data *da, *db, *dc;
    assert_ok(vt_data_create(&da, ma));
    assert_ok(vt_data_create(&db, mb));
    assert_ok(vt_data_create(&dc, c0));
    uint64_t seed = 11;
    double worst = 0.0;
    for (int s = 0; s < 5; s++) {
        vt_scene_random_state(ma, da, &seed);
        for (int c = 0; c < ma->nv; c++) da->qdd[c] = vt_rand_uniform(&seed, -3.0, 3.0);
        memcpy(db->q, da->q, (size_t)ma->nq * sizeof(double));
        memcpy(db->qd, da->qd, (size_t)ma->nv * sizeof(double));
        memcpy(db->qdd, da->qdd, (size_t)ma->nv * sizeof(double));
        memcpy(dc->q, da->q, (size_t)ma->nq * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(ma, da));
        assert_ok(vt_inverse_dynamics_motion(mb, db));
        worst = fmax(worst, vt_test_motion_diff(ma, da, db));
        /* the frame where it was on the body: its pose in the tree without the payload */
        assert_ok(vt_kinematics(c0, dc));
        double pa[3], Ra[9], pc[3], Rc[9];
        assert_ok(vt_frame_pose(ma, da, 0, pa, Ra));
        double A[9], x[3];
        const double *xk = dc->x + 7 * (k - 1);
        vt_euler_A(A, xk + 3);
        for (int r2 = 0; r2 < 3; r2++) { /* the tree's body k: its centre of mass + A fp, A R */
            x[r2] = xk[r2];
            for (int e = 0; e < 3; e++) x[r2] += A[r2 + 3 * e] * fp[e];
            pc[r2] = x[r2];
            for (int c = 0; c < 3; c++) {
                Rc[r2 + 3 * c] = 0.0;
                for (int e = 0; e < 3; e++) Rc[r2 + 3 * c] += A[r2 + 3 * e] * R[e + 3 * c];
            }
        }
        for (int e = 0; e < 3; e++) assert_near(pa[e], pc[e], 1e-14);
        for (int e = 0; e < 9; e++) assert_near(Ra[e], Rc[e], 1e-14);
    }
    print_message("payload on the scene's tree: largest relative difference %.3g\n", worst);
    if (!(worst <= 1e-15)) fail_msg("relative difference %.3g > 1e-15", worst);
    vt_data_free(da);
    vt_data_free(db);
    vt_data_free(dc);
    vt_model_free(ma);
    vt_model_free(mb);

    /* a point drive's and a cut joint's points on body k, added before the payload, move with
     * its centre of mass (points from the centre of mass: p − c), the others stay */
    assert_ok(vt_builder_create(&ba, NULL));
    for (int i = 1; i <= n; i++) {
        vt_body_def a = vt_test_body_of(c0, i);
        assert_int_equal(vt_builder_add_body(ba, &a), i);
    }
    const int other = k == 1 ? 2 : 1;
    vt_drive_def dr = vt_default_drive_def();
    dr.type = VT_DRIVE_POINT;
    dr.body = k;
    dr.point[0] = 0.4; dr.point[1] = -0.2; dr.point[2] = 0.1;
    assert_int_equal(vt_builder_add_drive(ba, &dr), 0);
    vt_cut_joint_def cut = vt_default_cut_joint_def();
    cut.joint = VT_JOINT_SPHERICAL;
    cut.body_a = k;
    cut.body_b = other;
    cut.point_a[0] = -0.3; cut.point_b[1] = 0.2;
    assert_int_equal(vt_builder_add_cut_joint(ba, &cut), 0);
    assert_int_equal(vt_builder_add_frame(ba, &f), 0);
    assert_int_equal(vt_builder_add_payload(ba, &pl), k);
    vt_model *m2 = vt_test_build(ba);
    for (int e = 0; e < 3; e++) {
        assert_near(m2->drive[0].point[e], dr.point[e] - cm[e], 1e-15);
        assert_near(m2->cut[0].point_a[e], cut.point_a[e] - cm[e], 1e-15);
        assert_near(m2->cut[0].point_b[e], cut.point_b[e], 0.0);
        assert_near(m2->frame_point[e], fp[e] - cm[e], 1e-15);
    }
    vt_model_free(m2);
    vt_model_free(c0);
}

/* two models of two bodies with the same masses, inertias, joint points and frame points, byte
 * for byte; frees both */
static void same_mass_and_points(vt_model *m1, vt_model *m2)
{
    assert_int_equal(m1->nbody, 2);
    assert_int_equal(m2->nbody, 2);
    assert_int_equal(m1->nframe, m2->nframe);
    assert_memory_equal(m1->body_mass, m2->body_mass, 3 * sizeof(double));
    assert_memory_equal(m1->body_inertia, m2->body_inertia, 27 * sizeof(double));
    assert_memory_equal(m1->body_jpar, m2->body_jpar, 9 * sizeof(double));
    assert_memory_equal(m1->body_jchild, m2->body_jchild, 9 * sizeof(double));
    if (m1->nframe) assert_memory_equal(m1->frame_point, m2->frame_point, 3 * (size_t)m1->nframe * sizeof(double));
    vt_model_free(m1);
    vt_model_free(m2);
}

/* vt_builder_set_mass: a body's mass properties replaced, at a new centre of mass, equals the
 * body defined with them and its points (its own joint point, its child's) written from the new
 * centre of mass: the same model, entry for entry. */
static void test_set_mass(void **state)
{
    (void)state;
    vt_body_def a = vt_default_body_def(), b = vt_default_body_def();
    a.joint_parent[2] = 0.5; a.joint_child[0] = -0.3; a.axis1[0] = 1.0; a.axis1[2] = 0.0;
    a.inertia[0] = a.inertia[4] = a.inertia[8] = 0.1;
    b.parent = 1; b.joint_parent[0] = 0.3; b.joint_child[0] = -0.2; b.mass = 0.5;
    vt_builder *b1, *b2;
    assert_ok(vt_builder_create(&b1, NULL));
    assert_ok(vt_builder_create(&b2, NULL));
    assert_int_equal(vt_builder_add_body(b1, &a), 1);
    assert_int_equal(vt_builder_add_body(b1, &b), 2);
    vt_payload_def pd = vt_default_payload_def();
    pd.body = vt_builder_find_body(b1, "");
    assert_int_equal(pd.body, VT_ERR_NOT_FOUND);
    pd.body = 1;
    pd.mass = 3.0;
    pd.point[0] = 0.05; pd.point[1] = -0.02; pd.point[2] = 0.01;
    const double J[9] = {0.2, 0.01, 0.0, 0.01, 0.3, 0.02, 0.0, 0.02, 0.25};
    memcpy(pd.inertia, J, sizeof J);
    assert_int_equal(vt_builder_set_mass(b1, &pd), 1);
    a.mass = 3.0;
    memcpy(a.inertia, J, sizeof J);
    for (int e = 0; e < 3; e++) {
        a.joint_child[e] -= pd.point[e];
        b.joint_parent[e] -= pd.point[e];
    }
    assert_int_equal(vt_builder_add_body(b2, &a), 1);
    assert_int_equal(vt_builder_add_body(b2, &b), 2);
    same_mass_and_points(vt_test_build(b1), vt_test_build(b2));
}

/* A payload or mass refused (each bad input its status and a message) leaves the builder as it
 * was: the model built after the refusals equals the one built before them, byte for byte in
 * the mass properties and points. */
static void test_payload_refused(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    d.joint_child[0] = 0.2;
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d.parent = 1;
    d.joint_parent[0] = -0.2;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    vt_frame_def f = vt_default_frame_def();
    f.name = "flange";
    f.body = 2;
    f.point[1] = 0.1;
    assert_int_equal(vt_builder_add_frame(b, &f), 0);
    f.name = "fixed";
    f.body = 0;
    assert_int_equal(vt_builder_add_frame(b, &f), 1);
    vt_model *before;
    assert_ok(vt_builder_build(&before, b));
    const vt_payload_def good = vt_default_payload_def();
    vt_payload_def p;
    struct {
        int set; /* 0 payload, 1 set_mass */
        vt_status want;
        const char *words;
    } cases[] = {{0, VT_ERR_MASS, "negative"}, {0, VT_ERR_NONFINITE, "NaN"},     {1, VT_ERR_BAD_INDEX, "body 3"},
                 {0, VT_ERR_NOT_FOUND, "tcp"}, {0, VT_ERR_BAD_INDEX, "ground"}, {1, VT_ERR_INERTIA_TRIANGLE, "inertia_tol"},
                 {0, VT_ERR_NONFINITE, "overflows"}, {0, VT_ERR_NULL, "NULL"}};
    for (int c = 0; c < (int)(sizeof cases / sizeof cases[0]); c++) {
        p = good;
        p.body = 2;
        p.mass = 1.0;
        switch (c) {
        case 0: p.mass = -1.0; break;
        case 1: p.point[1] = NAN; break;
        case 2: p.body = 3; break;
        case 3: p.frame = "tcp"; break;
        case 4: p.frame = "fixed"; break;
        case 5: p.inertia[0] = 1.0; p.inertia[4] = 1.0; p.inertia[8] = 2.1; break;
        case 6: p.point[0] = 1.7e308; p.mass = 1e300; break; /* the points from the new centre of mass overflow */
        default: break;
        }
        const int got = cases[c].set ? vt_builder_set_mass(b, c == 7 ? NULL : &p)
                                     : vt_builder_add_payload(b, c == 7 ? NULL : &p);
        if (got != (int)cases[c].want || !strstr(vt_builder_message(b), cases[c].words))
            fail_msg("case %d: status %d (want %d), message \"%s\" (want \"%s\")", c, got, (int)cases[c].want,
                     vt_builder_message(b), cases[c].words);
    }
    vt_model *after;
    assert_ok(vt_builder_build(&after, b));
    same_mass_and_points(before, after);
    /* a tool frame on the flange frame: its body, and the pose composed */
    f = vt_default_frame_def();
    f.name = "tcp";
    f.reference = "flange";
    f.body = 7; /* unused with a reference */
    f.point[2] = 0.05;
    f.orientation[0] = f.orientation[3] = 1.0; /* a quarter turn about z (normalized) */
    assert_int_equal(vt_builder_add_frame(b, &f), 2);
    f.reference = "nowhere";
    f.name = "tcp2";
    assert_int_equal(vt_builder_add_frame(b, &f), VT_ERR_NOT_FOUND);
    assert_non_null(strstr(vt_builder_message(b), "nowhere"));
    vt_model *m = vt_test_build(b);
    assert_int_equal(m->frame_body[2], 2);
    assert_near(m->frame_point[6], 0.0, 0.0);
    assert_near(m->frame_point[7], 0.1, 0.0);
    assert_near(m->frame_point[8], 0.05, 0.0);
    assert_near(m->frame_quat[8], sqrt(0.5), 2e-16);
    assert_near(m->frame_quat[11], sqrt(0.5), 2e-16);
    vt_model_free(m);
}


int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_payload_on_scene_tree),
        cmocka_unit_test(test_set_mass),
        cmocka_unit_test(test_payload_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
