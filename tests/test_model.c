/* src/model/model.c: the sizes and paths follow the tree, the model's bytes grow as its bodies
 * (a chain of 100,000 links built and run on the recursive layout), the constraint rows (a planar
 * pin), names found in the builder and the model, limits kept per rate and by the model without
 * drives, and a massless link. */
#include <stdio.h>

#include "vt_test.h"
#include "model/model.h"

static void test_sizes_and_paths(void **state)
{
    (void)state;
    static const int nq[6] = {7, 1, 2, 4, 1, 2}, nv[6] = {7, 1, 2, 3, 1, 2};
    for (uint64_t seed = 1; seed <= 5; seed++) {
        vt_model *m = NULL;
        assert_ok(vt_scene_random_tree(&m, seed, 12, VT_SCENE_ALL_JOINTS));
        int sq = 0, sv = 0, maxpath = 0;
        int *path = malloc((size_t)m->maxpath * sizeof(int));
        assert_non_null(path);
        for (int i = 1; i <= m->nbody; i++) {
            const int jt = m->body_joint[i];
            assert_int_equal(m->body_qadr[i], sq);
            assert_int_equal(m->body_vadr[i], sv);
            sq += nq[jt];
            sv += nv[jt];
            /* the path of i: every rate of every joint between the ground and i, ascending */
            int count = 0;
            for (int b = i; b; b = m->body_parent[b]) count += m->body_nv[b];
            assert_int_equal(m->body_pathnum[i], count);
            maxpath = count > maxpath ? count : maxpath;
            for (int c = 0; c < m->maxpath; c++) path[c] = -1;
            assert_int_equal(vt_body_path(m, i, path), count);
            for (int c = 0; c < count; c++) {
                assert_true(path[c] >= 0 && path[c] < m->nv);
                if (c) assert_true(path[c] > path[c - 1]);
                int owner = m->dof_body[path[c]], on_path = 0;
                for (int b = i; b; b = m->body_parent[b]) on_path |= b == owner;
                assert_true(on_path);
            }
        }
        assert_int_equal(m->nq, sq);
        assert_int_equal(m->nv, sv);
        assert_int_equal(m->nx, 7 * m->nbody);
        assert_int_equal(m->maxpath, maxpath);
        free(path);
        vt_model_free(m);
    }
}

/* The model holds O(n) bytes: a chain of 1,000 links takes at most 2.2 times the bytes of one of
 * 500 (each body's list of the rates on its path, n(n+1)/2 of them, made it 3.4 times), and at most
 * 1 KB a link. vt_model_bytes counts the block: every array lies within it. */
static void test_model_bytes_linear(void **state)
{
    (void)state;
    size_t bytes[2];
    for (int k = 0; k < 2; k++) {
        const int n = 500 * (k + 1);
        vt_model *m = NULL;
        assert_ok(vt_scene_chain_layout(&m, n, VT_CHAIN_TIP_DRIVE, VT_LAYOUT_RECURSIVE));
        bytes[k] = vt_model_bytes(m);
        const char *end = (const char *)(m->frame_quat + 4 * (m->nframe ? m->nframe : 1));
        assert_true((size_t)(end - (const char *)m) <= bytes[k]);
        assert_true(bytes[k] <= 1024 * (size_t)n);
        vt_model_free(m);
    }
    if (!(bytes[1] < 2.2 * bytes[0])) fail_msg("model bytes: %zu for 500 links, %zu for 1,000", bytes[0], bytes[1]);
}

/* A chain of 100,000 links, every joint driven, built and laid out VT_LAYOUT_RECURSIVE: the model
 * takes the bytes a link of a chain of 1,000 does, within 1 % (its paths' lists would be 5e9
 * rates, past an int), and the recursive evaluation runs: the efforts are finite and the last
 * link's equals its own Newton–Euler balance about its joint, computed here from the kinematics.
 * About 300 MB in all (the model 110, the data 180): left out under valgrind. */
static void test_chain_of_100000(void **state)
{
    (void)state;
    const int n = 100000;
    if (under_valgrind()) skip();
    vt_model *m = NULL;
    assert_ok(vt_scene_chain_layout(&m, 1000, VT_CHAIN_JOINT_DRIVEN, VT_LAYOUT_RECURSIVE));
    const double per_link = (double)vt_model_bytes(m) / 1000.0;
    vt_model_free(m);
    m = NULL;
    assert_ok(vt_scene_chain_layout(&m, n, VT_CHAIN_JOINT_DRIVEN, VT_LAYOUT_RECURSIVE));
    assert_int_equal(m->maxpath, n);
    if (!((double)vt_model_bytes(m) / n <= 1.01 * per_link))
        fail_msg("model bytes a link: %g for 100,000 links, %g for 1,000", (double)vt_model_bytes(m) / n, per_link);
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    for (int k = 0; k < n; k++) {
        double qdd;
        vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
    }
    assert_ok(vt_inverse_dynamics_recursive(m, d));
    assert_true(d->route == VT_ROUTE_JOINT_DRIVEN);
    for (int k = 0; k < n; k++) assert_true(isfinite(d->qfrc_drive[k]));
    /* the last link: e · (J α + ω × J ω + (r − P) × m (a − g)) about its joint point P, J = A J' A^T,
     * r − P = −A s' from the joint point in the body's axes (the link is 28 km from the origin) */
    const double *A = d->A + 9 * n, *Jb = m->body_inertia + 9 * n, *w = d->omega + 3 * n, *al = d->alpha + 3 * n;
    const double *a = d->xdd + 7 * (n - 1), *s = m->body_jchild + 3 * n, *e = d->jaxis + 9 * n;
    double J[9], Jw[3], Ja[3], f[3], u[3], mo[3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            J[i + 3 * j] = 0.0;
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++) J[i + 3 * j] += A[i + 3 * k] * Jb[k + 3 * l] * A[j + 3 * l];
        }
    for (int i = 0; i < 3; i++) {
        Jw[i] = J[i] * w[0] + J[i + 3] * w[1] + J[i + 6] * w[2];
        Ja[i] = J[i] * al[0] + J[i + 3] * al[1] + J[i + 6] * al[2];
        f[i] = m->body_mass[n] * (a[i] - m->gravity[i]);
        u[i] = -(A[i] * s[0] + A[i + 3] * s[1] + A[i + 6] * s[2]);
    }
    double tau = 0.0, size = 0.0;
    for (int i = 0; i < 3; i++) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        mo[i] = Ja[i] + (w[i1] * Jw[i2] - w[i2] * Jw[i1]) + (u[i1] * f[i2] - u[i2] * f[i1]);
        tau += e[i] * mo[i];
        size += fabs(Ja[i]) + fabs(w[i1] * Jw[i2]) + fabs(w[i2] * Jw[i1]) + fabs(u[i1] * f[i2]) + fabs(u[i2] * f[i1]);
    }
    assert_near(d->qfrc_drive[n - 1], tau, 1e-14 * size);
    vt_data_free(d);
    vt_model_free(m);
}

/* A massless link between two hinges with crossing perpendicular axes is a universal joint: the
 * same free motion and the same reaction at the second body as a model built with one; a
 * massless link that moves nothing and that nothing drives makes the solve singular, and the
 * message names it */
static void test_massless_link(void **state)
{
    (void)state;
    vt_builder *b;
    vt_model *hinges, *cross;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def g = vt_default_body_def();
    g.mass = 0.0; /* the gimbal: a massless link, about z */
    assert_int_equal(vt_builder_add_body(b, &g), 1);
    vt_body_def rod = vt_default_body_def();
    rod.parent = 1;
    rod.axis1[0] = 1.0; rod.axis1[2] = 0.0; /* then about x */
    rod.mass = 3.0;
    rod.inertia[0] = 0.1; rod.inertia[4] = rod.inertia[8] = 0.4;
    rod.joint_child[0] = -0.5; rod.joint_child[1] = 0.2;
    assert_int_equal(vt_builder_add_body(b, &rod), 2);
    assert_ok(vt_builder_build(&hinges, b));
    vt_builder_free(b);
    assert_ok(vt_builder_create(&b, NULL));
    rod.parent = 0;
    rod.joint = VT_JOINT_UNIVERSAL;
    rod.axis1[0] = 0.0; rod.axis1[2] = 1.0;
    rod.axis2[0] = 1.0; rod.axis2[1] = rod.axis2[2] = 0.0;
    assert_int_equal(vt_builder_add_body(b, &rod), 1);
    assert_ok(vt_builder_build(&cross, b));
    vt_builder_free(b);
    vt_data *dh, *dc;
    assert_ok(vt_data_create(&dh, hinges));
    assert_ok(vt_data_create(&dc, cross));
    dh->q[0] = dc->q[0] = 0.4;
    dh->q[1] = dc->q[1] = -0.9;
    dh->qd[0] = dc->qd[0] = 1.1;
    dh->qd[1] = dc->qd[1] = 0.3;
    assert_ok(vt_inverse_dynamics(hinges, dh));
    assert_ok(vt_inverse_dynamics(cross, dc));
    for (int k = 0; k < 2; k++) assert_near(dh->qdd[k], dc->qdd[k], 1e-12 * (1 + fabs(dc->qdd[k])));
    for (int k = 0; k < 3; k++) {
        assert_near(dh->jnt_force[6 + k], dc->jnt_force[3 + k], 1e-11);
        assert_near(dh->jnt_force[3 + k], dc->jnt_force[3 + k], 1e-11); /* the gimbal passes it on */
    }
    assert_ok(vt_inverse_dynamics_recursive(hinges, dh));
    for (int k = 0; k < 2; k++) assert_near(dh->qdd[k], dc->qdd[k], 1e-12 * (1 + fabs(dc->qdd[k])));
    vt_data_free(dh);
    vt_data_free(dc);
    vt_model_free(hinges);
    vt_model_free(cross);
    /* a massless link at the end of a chain, on a free hinge: nothing fixes its motion */
    assert_ok(vt_builder_create(&b, NULL));
    vt_test_add_rods(b, 2, 1.0, (const double[2]){1.0, 1.0});
    vt_body_def tip = vt_default_body_def();
    tip.parent = 2;
    tip.mass = 0.0;
    tip.joint_parent[0] = 0.5;
    assert_int_equal(vt_builder_add_body(b, &tip), 3);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_SINGULAR);
    assert_non_null(strstr(d->message, "body 3"));
    assert_null(strstr(d->message, "body 2"));
    vt_data_free(d);
    vt_model_free(m);
}

/* Names: copied, unique among their kind, found again in the builder and in the model (and in
 * the model without drives); a name refused leaves the builder as it was */
static void test_names(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    char buf[VT_NAME_MAX + 8];
    strcpy(buf, "upper_arm");
    vt_body_def d = vt_default_body_def();
    d.name = buf;
    d.joint_name = "shoulder";
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    strcpy(buf, "forearm"); /* the builder kept its own copy */
    d.parent = 1;
    d.joint_name = "elbow";
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    d.parent = 2;
    d.joint_name = NULL;
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_BAD_NAME); /* "forearm" again */
    assert_non_null(strstr(vt_builder_message(b), "forearm"));
    d.name = NULL; /* unnamed */
    d.joint_name = "shoulder";
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_BAD_NAME); /* joint names are unique too */
    memset(buf, 'x', VT_NAME_MAX);
    buf[VT_NAME_MAX] = '\0';
    d.name = buf; /* VT_NAME_MAX bytes: one too many */
    d.joint_name = NULL;
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_BAD_NAME);
    buf[VT_NAME_MAX - 1] = '\0'; /* the longest allowed */
    assert_int_equal(vt_builder_add_body(b, &d), 3);
    d.name = NULL;
    assert_int_equal(vt_builder_add_body(b, &d), 4); /* unnamed bodies do not collide */
    d.parent = 3;
    assert_int_equal(vt_builder_add_body(b, &d), 5);
    assert_int_equal(vt_builder_find_body(b, "upper_arm"), 1);
    assert_int_equal(vt_builder_find_body(b, "forearm"), 2);
    assert_int_equal(vt_builder_find_body(b, "hand"), VT_ERR_NOT_FOUND);
    assert_int_equal(vt_builder_find_body(b, ""), VT_ERR_NOT_FOUND);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 2;
    dr.name = "elbow_motor";
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_NAME);
    vt_cut_joint_def cj = vt_default_cut_joint_def();
    cj.joint = VT_JOINT_SPHERICAL;
    cj.body_b = 5;
    cj.name = "closure";
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), 0);
    vt_frame_def f = vt_default_frame_def();
    f.name = "tool";
    f.body = 5;
    f.point[0] = 0.3;
    assert_int_equal(vt_builder_add_frame(b, &f), 0);
    vt_model *m, *mf;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_ok(vt_model_without_drives(&mf, m));
    const vt_model *both[2] = {m, mf};
    for (int k = 0; k < 2; k++) {
        const vt_model *x = both[k];
        assert_int_equal(vt_find_body(x, "upper_arm"), 1);
        assert_int_equal(vt_find_body(x, "forearm"), 2);
        assert_int_equal(vt_find_body(x, buf), 3);
        assert_int_equal(vt_find_joint(x, "shoulder"), 1);
        assert_int_equal(vt_find_joint(x, "elbow"), 2);
        assert_int_equal(vt_find_joint(x, "wrist"), VT_ERR_NOT_FOUND);
        assert_int_equal(vt_find_cut_joint(x, "closure"), 0);
        assert_int_equal(vt_find_frame(x, "tool"), 0);
        assert_string_equal(x->body_name + VT_NAME_MAX * 2, "forearm");
        assert_string_equal(x->body_name + VT_NAME_MAX * 4, "");
        assert_string_equal(x->cut[0].name, "closure"); /* the stored definition points at the model's copy */
    }
    assert_int_equal(vt_find_drive(m, "elbow_motor"), 0);
    assert_string_equal(m->drive[0].name, "elbow_motor");
    assert_int_equal(vt_find_drive(mf, "elbow_motor"), VT_ERR_NOT_FOUND); /* no drives there */
    assert_int_equal(vt_find_body(NULL, "x"), VT_ERR_NULL);
    assert_int_equal(vt_find_frame(m, NULL), VT_ERR_NULL);
    vt_model_free(mf);
    vt_model_free(m);
}

/* Joint limits: kept per rate (defaults ±∞), survive the model without drives; NaN and
 * inconsistent limits refused */
static void test_limits(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    d.limit_lower[0] = -1.5;
    d.limit_upper[0] = 2.0;
    d.limit_velocity[0] = 3.0;
    d.limit_effort[0] = 40.0;
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    vt_body_def c = vt_default_body_def();
    c.parent = 1;
    c.joint = VT_JOINT_CYLINDRICAL;
    c.limit_lower[1] = -0.1;
    c.limit_upper[1] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &c), 2);
    vt_body_def s = vt_default_body_def();
    s.parent = 2;
    s.joint = VT_JOINT_SPHERICAL;
    assert_int_equal(vt_builder_add_body(b, &s), 3);
    vt_body_def bad = vt_default_body_def();
    bad.limit_lower[0] = NAN;
    assert_int_equal(vt_builder_add_body(b, &bad), VT_ERR_NONFINITE);
    bad = vt_default_body_def();
    bad.limit_lower[0] = 1.0;
    bad.limit_upper[0] = 0.5;
    assert_int_equal(vt_builder_add_body(b, &bad), VT_ERR_BAD_OPTION);
    bad = vt_default_body_def();
    bad.limit_effort[1] = -1.0;
    assert_int_equal(vt_builder_add_body(b, &bad), VT_ERR_BAD_OPTION);
    vt_model *m, *mf;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nbody, 3);
    assert_ok(vt_model_without_drives(&mf, m));
    const double want[6][4] = {{-1.5, 2.0, 3.0, 40.0}, {-HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL},
                               {-0.1, 0.1, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL},
                               {-HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL}};
    assert_int_equal(m->nv, 6);
    for (int a = 0; a < 6; a++)
        for (int k = 0; k < 4; k++) {
            assert_true(m->dof_limit[4 * a + k] == want[a][k]);
            assert_true(mf->dof_limit[4 * a + k] == want[a][k]);
        }
    vt_model_free(mf);
    vt_model_free(m);
}

/* The planar pin: only a revolute may be one (the builder refuses any other kind, naming it,
 * and any value but 0 or 1); it has 2 rows, along two unit vectors ⟂ axis1 in a's axes, each
 * on both joint points; a full revolute beside it keeps its 5; a builder's refusal adds nothing */
static void test_planar_cut_joint(void **state)
{
    (void)state;
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d.parent = 1;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    vt_cut_joint_def cj = vt_default_cut_joint_def();
    assert_int_equal(cj.planar, 0);
    cj.body_b = 2;
    cj.planar = 1;
    static const vt_joint_type others[4] = {VT_JOINT_UNIVERSAL, VT_JOINT_SPHERICAL, VT_JOINT_TRANSLATIONAL,
                                            VT_JOINT_CYLINDRICAL};
    for (int k = 0; k < 4; k++) {
        cj.joint = others[k];
        assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_BAD_CUT_JOINT);
        assert_non_null(strstr(vt_builder_message(b), "planar"));
    }
    cj.joint = VT_JOINT_REVOLUTE;
    cj.planar = 2;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_BAD_CUT_JOINT);
    assert_non_null(strstr(vt_builder_message(b), "planar is 2"));
    cj.planar = 1;
    cj.axis1[0] = 3.0; /* normalized: (0.6, 0, 0.8) */
    cj.axis1[1] = 0.0;
    cj.axis1[2] = 4.0;
    cj.point_a[0] = 0.3;
    cj.point_b[1] = -0.2;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), 0);
    cj.planar = 0;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), 1);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->ncut, 2);
    assert_int_equal(m->nc, 2 + 5);
    assert_int_equal(m->cut_row[0], 0);
    assert_int_equal(m->cut_row[1], 2);
    assert_int_equal(m->cut[0].planar, 1);
    const double a[3] = {0.6, 0.0, 0.8};
    double u[2][3];
    for (int r = 0; r < 2; r++) {
        const double *v = m->con_vec + 6 * r, *p = m->con_point + 6 * r;
        memcpy(u[r], v, sizeof u[r]);
        assert_int_equal(m->con_owner[r], 0);
        assert_int_equal(m->con_body[2 * r], 0);
        assert_int_equal(m->con_body[2 * r + 1], 2);
        assert_near(v[0] * a[0] + v[1] * a[1] + v[2] * a[2], 0.0, 1e-15);
        assert_near(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], 1.0, 1e-15);
        assert_near(p[0], 0.3, 0.0);
        assert_near(p[4], -0.2, 0.0);
    }
    assert_near(u[0][0] * u[1][0] + u[0][1] * u[1][1] + u[0][2] * u[1][2], 0.0, 1e-15);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sizes_and_paths),
        cmocka_unit_test(test_model_bytes_linear),
        cmocka_unit_test(test_chain_of_100000),
        cmocka_unit_test(test_massless_link),
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_planar_cut_joint),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
