/* src/model.c: every validation error of the builder returns its own status and message,
 * a refused body changes nothing, and the sizes and paths follow the tree. */
#include <stdio.h>

#include "vt_test.h"

static vt_builder *make_builder(void)
{
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    return b;
}

/* adds `bad` as body 2 and expects `want`; then a good body must still get id 2 */
static void expect_refused(vt_body_def bad, vt_status want)
{
    vt_builder *b = make_builder();
    const int got = vt_builder_add_body(b, &bad);
    if (got != (int)want)
        fail_msg("expected status %d (%s), got %d; message: %s", (int)want, vt_status_string(want), got,
                 vt_builder_message(b));
    assert_true(strlen(vt_builder_message(b)) > 0);
    assert_non_null(strstr(vt_builder_message(b), "body 2"));
    vt_body_def good = vt_default_body_def();
    assert_int_equal(vt_builder_add_body(b, &good), 2);
    assert_string_equal(vt_builder_message(b), "");
    vt_builder_free(b);
}

static void test_validation_errors(void **state)
{
    (void)state;
    vt_body_def d;

    d = vt_default_body_def(); d.mass = 0.0;
    expect_refused(d, VT_ERR_MASS);
    d = vt_default_body_def(); d.mass = -2.0;
    expect_refused(d, VT_ERR_MASS);
    d = vt_default_body_def(); d.mass = NAN;
    expect_refused(d, VT_ERR_NONFINITE);
    d = vt_default_body_def(); d.inertia[4] = INFINITY;
    expect_refused(d, VT_ERR_NONFINITE);
    d = vt_default_body_def(); d.joint_child[1] = NAN;
    expect_refused(d, VT_ERR_NONFINITE);
    d = vt_default_body_def(); d.axis1[0] = INFINITY;
    expect_refused(d, VT_ERR_NONFINITE);

    d = vt_default_body_def();
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 1.0; d.inertia[3] = 0.1; /* J12 ≠ J21 */
    expect_refused(d, VT_ERR_INERTIA_ASYMMETRIC);
    d = vt_default_body_def();
    d.inertia[0] = -0.1; d.inertia[4] = d.inertia[8] = 1.0;
    expect_refused(d, VT_ERR_INERTIA_NOT_PSD);
    d = vt_default_body_def();
    d.inertia[0] = d.inertia[4] = 1.0; d.inertia[8] = 3.0;  /* 1 + 1 < 3 */
    expect_refused(d, VT_ERR_INERTIA_TRIANGLE);
    d = vt_default_body_def();  /* the same, rotated off the axes: seen through dsyev */
    d.inertia[0] = 2.0; d.inertia[4] = 2.0; d.inertia[8] = 1.0; d.inertia[1] = d.inertia[3] = 1.0 + 1e-3;
    /* principal moments 3.001, 0.999, 1: 0.999 + 1 < 3.001 */
    expect_refused(d, VT_ERR_INERTIA_TRIANGLE);

    d = vt_default_body_def(); d.axis1[0] = d.axis1[1] = d.axis1[2] = 0.0;
    expect_refused(d, VT_ERR_AXIS_ZERO);
    d = vt_default_body_def(); d.joint = VT_JOINT_UNIVERSAL; d.axis2[0] = d.axis2[1] = d.axis2[2] = 0.0;
    expect_refused(d, VT_ERR_AXIS_ZERO);
    d = vt_default_body_def(); d.joint = VT_JOINT_UNIVERSAL; d.axis2[0] = 1.0; d.axis2[2] = 0.1;
    expect_refused(d, VT_ERR_AXES_NOT_PERPENDICULAR);

    d = vt_default_body_def(); d.parent = 2; /* itself */
    expect_refused(d, VT_ERR_PARENT);
    d = vt_default_body_def(); d.parent = 5;
    expect_refused(d, VT_ERR_PARENT);
    d = vt_default_body_def(); d.parent = -1;
    expect_refused(d, VT_ERR_PARENT);
    d = vt_default_body_def(); d.joint = VT_JOINT_BASE; d.parent = 1;
    expect_refused(d, VT_ERR_PARENT);
    d = vt_default_body_def(); d.joint = (vt_joint_type)42;
    expect_refused(d, VT_ERR_JOINT_TYPE);
    d = vt_default_body_def(); d.orientation[0] = 0.0;
    expect_refused(d, VT_ERR_QUATERNION);
}

static void test_allowed_and_normalized(void **state)
{
    (void)state;
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def(); /* point mass: zero inertia is allowed */
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d.parent = 1;                          /* slender rod: principal moments 0, I, I */
    d.inertia[4] = d.inertia[8] = 0.5;
    d.axis1[0] = 3.0; d.axis1[1] = 4.0; d.axis1[2] = 0.0; /* normalized, not refused */
    d.orientation[0] = 2.0;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_near(m->body_axis[6 * 2 + 0], 0.6, 1e-15);
    assert_near(m->body_axis[6 * 2 + 1], 0.8, 1e-15);
    assert_near(m->body_quat0[4 * 2], 1.0, 1e-15);
    vt_model_free(m);
}

static void test_limits_and_null(void **state)
{
    (void)state;
    vt_builder *b = NULL;
    vt_model *m = NULL;
    assert_int_equal(vt_builder_create(NULL, NULL), VT_ERR_NULL);
    vt_model_def md = vt_default_model_def();
    md.gravity[2] = NAN;
    assert_int_equal(vt_builder_create(&b, &md), VT_ERR_NONFINITE);
    assert_null(b);
    md = vt_default_model_def();
    md.rcond_min = 0.0; /* would accept singular systems: refused (found by the fuzzer) */
    assert_int_equal(vt_builder_create(&b, &md), VT_ERR_BAD_OPTION);
    md.rcond_min = 1e-6;
    md.rcond_warn = 1e-8; /* a warning threshold below the refusal one */
    assert_int_equal(vt_builder_create(&b, &md), VT_ERR_BAD_OPTION);
    assert_null(b);
    assert_ok(vt_builder_create(&b, NULL));
    assert_int_equal(vt_builder_build(&m, b), VT_ERR_EMPTY_MODEL);
    assert_null(m);
    assert_int_equal(vt_builder_add_body(b, NULL), VT_ERR_NULL);
    assert_int_equal(vt_builder_add_body(NULL, NULL), VT_ERR_NULL);
    vt_body_def d = vt_default_body_def();
    for (int i = 1; i <= VT_MAX_BODIES; i++) {
        d.parent = i - 1;
        assert_int_equal(vt_builder_add_body(b, &d), i);
    }
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_TOO_MANY_BODIES);
    vt_builder_free(b);
}


static void test_sizes_and_paths(void **state)
{
    (void)state;
    static const int nq[6] = {7, 1, 2, 4, 1, 2}, nv[6] = {7, 1, 2, 3, 1, 2};
    for (uint64_t seed = 1; seed <= 5; seed++) {
        vt_model *m = NULL;
        assert_ok(vt_scene_random_tree(&m, seed, 12, VT_SCENE_ALL_JOINTS));
        int sq = 0, sv = 0;
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
            const int *path = m->path_dof + m->body_pathadr[i];
            for (int c = 0; c < count; c++) {
                if (c) assert_true(path[c] > path[c - 1]);
                int owner = m->dof_body[path[c]], on_path = 0;
                for (int b = i; b; b = m->body_parent[b]) on_path |= b == owner;
                assert_true(on_path);
            }
        }
        assert_int_equal(m->nq, sq);
        assert_int_equal(m->nv, sv);
        assert_int_equal(m->nx, 7 * m->nbody);
        vt_model_free(m);
    }
}


int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_validation_errors),
        cmocka_unit_test(test_allowed_and_normalized),
        cmocka_unit_test(test_limits_and_null),
        cmocka_unit_test(test_sizes_and_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
