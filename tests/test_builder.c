/* src/model/builder.c: every validation error of the builder returns its own status and message,
 * a refused body changes nothing; what it accepts and normalizes (inertias of real files, axes
 * and Euler parameters of any length, universal axes), couplings, the free joint's refusals and
 * the splines it owns. */
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

    d = vt_default_body_def(); d.mass = -1e-300; /* negative; zero is allowed (test_real_files) */
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

/* Inertias near overflow are checked as well as ordinary ones: the check scales by the largest
 * entry first (a tolerance or difference formed from raw entries near 1e308 overflows to Inf
 * and lets anything through); entries so large that the rotational mass 4 GᵀJ'G (up to 12
 * times the largest entry) would overflow cannot be used and are refused as VT_ERR_NONFINITE. */
static void test_inertia_near_overflow(void **state)
{
    (void)state;
    const double big = 1e308;
    vt_body_def d;
    d = vt_default_body_def(); /* negative definite */
    d.inertia[0] = d.inertia[4] = d.inertia[8] = -big;
    expect_refused(d, VT_ERR_NONFINITE); /* too large to use, whatever its sign */
    d = vt_default_body_def(); /* negative definite, usable size */
    d.inertia[0] = d.inertia[4] = d.inertia[8] = -1e300;
    expect_refused(d, VT_ERR_INERTIA_NOT_PSD);
    d = vt_default_body_def(); /* asymmetric: J12 = −J21 */
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 1e300; d.inertia[3] = 1e300; d.inertia[1] = -1e300;
    expect_refused(d, VT_ERR_INERTIA_ASYMMETRIC);
    d = vt_default_body_def(); /* indefinite: eigenvalues 1 ± 1.5 (×1e300) */
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 1e300; d.inertia[1] = d.inertia[3] = 1.5e300;
    expect_refused(d, VT_ERR_INERTIA_NOT_PSD);
    d = vt_default_body_def(); /* 1 + 1 < 3, ×1e300 */
    d.inertia[0] = d.inertia[4] = 1e300; d.inertia[8] = 3e300;
    expect_refused(d, VT_ERR_INERTIA_TRIANGLE);
    d = vt_default_body_def(); /* positive definite but beyond use: 12 × 1.7e308 overflows */
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 1.7e308;
    expect_refused(d, VT_ERR_NONFINITE);
    d = vt_default_body_def(); /* the same, tiny: 1 + 1 < 3 ×1e-300, below VT_INERTIA_ABS_TOL: accepted */
    vt_builder *b = make_builder();
    d.inertia[0] = d.inertia[4] = 1e-300; d.inertia[8] = 3e-300;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 1e300; /* large and valid: accepted */
    assert_int_equal(vt_builder_add_body(b, &d), 3);
    vt_builder_free(b);
}

/* Axes and Euler parameters are directions: normalized by their largest component first, so
 * that lengths near overflow (whose sum of squares is Inf) and tiny ones (whose sum of squares
 * underflows to 0) keep their direction; only the zero vector is refused. Bodies, cut joints,
 * drives and frames; the expected directions are the same vectors at length ~1. */
static void test_extreme_lengths(void **state)
{
    (void)state;
    const double scales[] = {1e200, 1e-200, 1.7e308, 5e-324 /* the smallest subnormal */};
    for (int s = 0; s < 4; s++) {
        const double c = scales[s];
        vt_builder *b = NULL;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def d = vt_default_body_def();
        d.axis1[0] = 0.0; d.axis1[1] = 0.0; d.axis1[2] = c;
        d.orientation[0] = c; d.orientation[3] = c; /* 90° about z */
        assert_int_equal(vt_builder_add_body(b, &d), 1);
        d = vt_default_body_def();
        d.parent = 1; d.joint = VT_JOINT_UNIVERSAL;
        d.axis1[0] = c; d.axis1[1] = 0.0; d.axis1[2] = 0.0;
        d.axis2[0] = 0.0; d.axis2[1] = c; d.axis2[2] = 0.0;
        assert_int_equal(vt_builder_add_body(b, &d), 2);
        vt_cut_joint_def cj = vt_default_cut_joint_def();
        cj.body_a = 1; cj.body_b = 2; cj.axis1[0] = 0.0; cj.axis1[1] = c; cj.axis1[2] = 0.0;
        cj.orientation[0] = c; cj.orientation[1] = c;
        assert_int_equal(vt_builder_add_cut_joint(b, &cj), 0);
        vt_drive_def dr = vt_default_drive_def();
        dr.type = VT_DRIVE_ORIENTATION; dr.body = 2;
        dr.axis[0] = c; dr.axis[1] = c; dr.axis[2] = 0.0;
        dr.orientation[0] = 0.0; dr.orientation[2] = c;
        assert_int_equal(vt_builder_add_drive(b, &dr), 0);
        vt_frame_def fr = vt_default_frame_def();
        fr.name = "f"; fr.orientation[0] = c; fr.orientation[2] = -c;
        assert_int_equal(vt_builder_add_frame(b, &fr), 0);
        vt_model *m = NULL;
        assert_ok(vt_builder_build(&m, b));
        vt_builder_free(b);
        const double h = sqrt(0.5);
        const double *a1 = m->body_axis + 6, *q1 = m->body_quat0 + 4, *a2 = m->body_axis + 12;
        assert_near(a1[2], 1.0, 1e-15); assert_near(a1[0], 0.0, 0.0);
        assert_near(q1[0], h, 1e-15); assert_near(q1[3], h, 1e-15);
        assert_near(a2[0], 1.0, 1e-15); assert_near(a2[4], 1.0, 1e-15);
        assert_near(m->cut[0].axis1[1], 1.0, 1e-15);
        assert_near(m->cut[0].orientation[0], h, 1e-15); assert_near(m->cut[0].orientation[1], h, 1e-15);
        assert_near(m->drive[0].axis[0], h, 1e-15); assert_near(m->drive[0].axis[1], h, 1e-15);
        assert_near(m->drive[0].orientation[2], 1.0, 1e-15);
        assert_near(m->frame_quat[0], h, 1e-15); assert_near(m->frame_quat[2], -h, 1e-15);
        vt_model_free(m);
    }
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
    vt_builder_free(b);
}

/* No fixed limit on bodies: a planar chain of 5,000 revolute links (five times the former bound
 * of 1,000), named, built, laid out VT_LAYOUT_RECURSIVE, held still and straight along x with
 * gravity along −y. Its total mass, and the torque each joint k (0-based) needs, against the
 * closed form: joint k carries links k..n−1, whose centres lie (i − k + ½) L beyond it, so
 * τ_k = m g L Σ_{i=k}^{n−1} (i − k + ½) = m g L (n − k)² / 2. Names are unique and found (the
 * builder's index); a duplicate among 5,000 is refused naming the first. */
static void test_large_chain(void **state)
{
    (void)state;
    const int n = 5000;
    const double L = 0.5, mass = 2.0, g = 9.81;
    vt_model_def md = vt_default_model_def(); /* gravity (0, −9.81, 0) */
    md.layout = VT_LAYOUT_RECURSIVE;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def d = vt_default_body_def();
    d.mass = mass;
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 0.01;
    for (int i = 1; i <= n; i++) {
        char name[32], joint[32];
        snprintf(name, sizeof name, "link%d", i);
        snprintf(joint, sizeof joint, "joint%d", i);
        d.name = name;
        d.joint_name = joint;
        d.parent = i - 1;
        d.joint_parent[0] = i > 1 ? 0.5 * L : 0.0; /* the parent's end, from its centre */
        d.joint_child[0] = -0.5 * L;               /* this link's start, from its centre */
        const int id = vt_builder_add_body(b, &d);
        if (id != i) fail_msg("body %d: %d (%s)", i, id, vt_builder_message(b));
    }
    d.name = "link1234"; /* taken */
    d.joint_name = NULL;
    d.parent = n;
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_BAD_NAME);
    assert_non_null(strstr(vt_builder_message(b), "already taken by body 1234"));
    assert_int_equal(vt_builder_find_body(b, "link4321"), 4321);
    assert_int_equal(vt_builder_find_body(b, "link5001"), VT_ERR_NOT_FOUND);
    vt_model *m;
    if (vt_builder_build(&m, b) != VT_OK) fail_msg("build: %s", vt_builder_message(b));
    vt_builder_free(b);
    assert_int_equal(m->nbody, n);
    assert_int_equal(m->nv, n);
    double total = 0.0;
    for (int i = 0; i <= n; i++) total += m->body_mass[i];
    assert_near(total, n * mass, 1e-9 * n * mass);
    assert_int_equal(vt_find_joint(m, "joint5000"), 5000);
    vt_data *data;
    assert_ok(vt_data_create(&data, m));
    assert_true(vt_data_size(m) < 4000 * (size_t)n); /* O(n): the recursive layout */
    if (vt_inverse_dynamics_motion(m, data) != VT_OK) fail_msg("%s", data->message);
    double worst = 0.0;
    for (int k = 0; k < n; k++) {
        const double exact = mass * g * L * (double)(n - k) * (double)(n - k) / 2.0;
        worst = fmax(worst, fabs(data->qfrc_drive[k] - exact) / exact);
    }
    if (!(worst < 1e-9)) fail_msg("joint torques off the closed form by %g relative", worst);
    vt_data_free(data);
    vt_model_free(m);
}

/* What real model files contain is accepted: a massless link, and inertias off symmetric,
 * positive semi-definite or the triangle inequality by round-off (VT_INERTIA_TOL, relative to
 * the largest entry), the symmetric part kept; off by more than the tolerance is refused */
static void test_real_files(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    d.mass = 0.0; /* a massless link */
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d = vt_default_body_def();
    d.parent = 1;
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 2.0;
    d.inertia[3] = 0.5; d.inertia[1] = 0.5 * (1.0 + 1e-9);  /* J12, J21 off by 5e-10 */
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    d = vt_default_body_def();
    d.parent = 2;
    d.inertia[0] = -5e-20; d.inertia[4] = d.inertia[8] = 1e-3; /* a moment of −5e-20 kg m² */
    assert_int_equal(vt_builder_add_body(b, &d), 3);
    d = vt_default_body_def();
    d.parent = 3;
    d.inertia[0] = 1.0; d.inertia[4] = 2.0; d.inertia[8] = 3.0 * (1.0 + 1e-7); /* 1 + 2 < 3 by 3e-7 */
    assert_int_equal(vt_builder_add_body(b, &d), 4);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    const double *J2 = m->body_inertia + 9 * 2;
    assert_near(J2[1], J2[3], 0.0); /* stored symmetric: the mean */
    assert_near(J2[1], 0.5 * (1.0 + 0.5e-9), 1e-16);
    vt_model_free(m);
    /* beyond the tolerance: refused, and the builder keeps its four bodies */
    d = vt_default_body_def();
    d.parent = 4;
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 2.0;
    d.inertia[3] = 0.5; d.inertia[1] = 0.5 * (1.0 + 1e-4);
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_INERTIA_ASYMMETRIC);
    d.inertia[1] = 0.5;
    d.inertia[0] = -1e-4;
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_INERTIA_NOT_PSD);
    d.inertia[0] = 1.0; d.inertia[3] = d.inertia[1] = 0.0; d.inertia[4] = 2.0; d.inertia[8] = 3.0 * (1.0 + 1e-4);
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_INERTIA_TRIANGLE);
    d.inertia[8] = 3.0;
    assert_int_equal(vt_builder_add_body(b, &d), 5);
    vt_body_def pm = vt_default_body_def(); /* a point mass written as a URDF file does (iCub's r_hip_2) */
    pm.parent = 5;
    pm.mass = 0.526;
    pm.inertia[0] = pm.inertia[4] = -5.42101e-20; /* within VT_INERTIA_ABS_TOL */
    assert_int_equal(vt_builder_add_body(b, &pm), 6);
    pm.inertia[0] = pm.inertia[4] = -1e-12; /* beyond it */
    assert_int_equal(vt_builder_add_body(b, &pm), VT_ERR_INERTIA_NOT_PSD);
    vt_builder_free(b);
}

/* Couplings: refused when a side is not a scalar coordinate of a body added so far, couples a
 * rate with itself, or is not finite; the builder unchanged; kept by the model without drives */
static void test_couplings(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d.parent = 1;
    d.joint = VT_JOINT_SPHERICAL;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    d.joint = VT_JOINT_CYLINDRICAL;
    assert_int_equal(vt_builder_add_body(b, &d), 3);
    vt_coupling_def c = vt_default_coupling_def();
    c.body_a = 4;
    assert_int_equal(vt_builder_add_coupling(b, &c), VT_ERR_BAD_INDEX);
    c.body_a = 2; /* spherical */
    assert_int_equal(vt_builder_add_coupling(b, &c), VT_ERR_BAD_DRIVE);
    assert_non_null(strstr(vt_builder_message(b), "scalar"));
    c.body_a = 3;
    c.index_a = 2; /* a cylindrical joint has rates 0 and 1 */
    assert_int_equal(vt_builder_add_coupling(b, &c), VT_ERR_BAD_INDEX);
    c.index_a = 1;
    c.body_b = 3;
    c.index_b = 1;
    assert_int_equal(vt_builder_add_coupling(b, &c), VT_ERR_BAD_DRIVE); /* itself */
    c.body_b = 1;
    c.index_b = 0;
    c.ratio = NAN;
    assert_int_equal(vt_builder_add_coupling(b, &c), VT_ERR_NONFINITE);
    c.ratio = 0.5; /* the slide follows the first hinge, 0.5 m/rad */
    c.name = "screw";
    assert_int_equal(vt_builder_add_coupling(b, &c), 0);
    assert_int_equal(vt_builder_add_coupling(b, &c), VT_ERR_BAD_NAME);
    vt_model *m, *mf;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->ncoupling, 1);
    assert_int_equal(m->nc, 1);
    assert_ok(vt_model_without_drives(&mf, m));
    assert_int_equal(mf->ncoupling, 1);
    assert_int_equal(vt_find_coupling(mf, "screw"), 0);
    assert_near(mf->coupling[0].ratio, 0.5, 0.0);
    vt_model_free(mf);
    vt_model_free(m);
}

/* The free joint: 7 coordinates and 6 rates, no row, q0 = (0, identity); joint drives on its
 * translation only, couplings likewise; no cut joint of that kind */
static void test_free_joint(void **state)
{
    (void)state;
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    d.joint = VT_JOINT_REVOLUTE;
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d.joint = VT_JOINT_FREE; /* on a moving reference body */
    d.parent = 1;
    d.axis1[0] = d.axis1[1] = d.axis1[2] = 0.0; /* no axis used: not refused */
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 2;
    for (int k = 3; k < 6; k++) {
        dr.index = k;
        assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
        assert_non_null(strstr(vt_builder_message(b), "orientation drive"));
    }
    dr.index = 6;
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    dr.index = 2;
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_coupling_def c = vt_default_coupling_def();
    c.body_a = 2;
    c.index_a = 4;
    c.body_b = 1;
    assert_true(vt_builder_add_coupling(b, &c) == VT_ERR_BAD_DRIVE);
    c.index_a = 1;
    assert_int_equal(vt_builder_add_coupling(b, &c), 0);
    vt_cut_joint_def cj = vt_default_cut_joint_def();
    cj.joint = VT_JOINT_FREE;
    cj.body_b = 2;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_BAD_CUT_JOINT);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nq, 1 + 7);
    assert_int_equal(m->nv, 1 + 6);
    assert_int_equal(m->nc, 2); /* the drive and the coupling: no norm row */
    assert_int_equal(m->body_nq[2], 7);
    assert_int_equal(m->body_nv[2], 6);
    const double q0[7] = {0, 0, 0, 1, 0, 0, 0};
    for (int k = 0; k < 7; k++) assert_true(m->q0[1 + k] == q0[k]);
    vt_model_free(m);
}

/* An orientation drive's three angles may be splines: the builder owns each one's samples (the
 * caller's arrays overwritten after the drive is added change nothing), and the angles are the
 * parabola through three samples and the line through two: the body's q against the Z–Y–X
 * product of those angles, and q̇ = ω against its closed form. */
static void test_sequence_splines_owned(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_SPHERICAL;
    body.inertia[0] = body.inertia[4] = body.inertia[8] = 1.0;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    double t1[3] = {0.0, 1.0, 2.0}, y1[3] = {0.0, 0.5, 2.0}; /* the parabola y = t²/2 */
    double t3[2] = {0.0, 1.0}, y3[2] = {0.2, -0.4};           /* y = 0.2 − 0.6 t */
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    od.sequence = "ZYX";
    od.f = vt_function_spline(3, t1, y1);
    od.f2 = vt_function_constant(0.3);
    od.f3 = vt_function_spline(2, t3, y3);
    assert_int_equal(vt_builder_add_drive(b, &od), 0);
    for (int k = 0; k < 3; k++) t1[k] = y1[k] = -7.0;
    t3[0] = t3[1] = y3[0] = y3[1] = 9.0;
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    const double t = 0.7, a = 0.5 * t * t, ad = t, c = 0.2 - 0.6 * t, cd = -0.6;
    d->time = t;
    assert_ok(vt_kinematic_solve(m, d, 1e-14, 50));
    const double ez[3] = {0, 0, 1}, ey[3] = {0, 1, 0}, ex[3] = {1, 0, 0};
    double rz[4], ry[4], rx[4], want[4], Azy[9], rzy[4];
    vt_quat_axis_angle(rz, ez, a);
    vt_quat_axis_angle(ry, ey, 0.3);
    vt_quat_axis_angle(rx, ex, c);
    vt_quat_mul(rzy, rz, ry);
    vt_quat_mul(want, rzy, rx);
    const double sg = d->q[0] * want[0] < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 4; k++) assert_near(d->q[k], sg * want[k], 1e-12);
    vt_euler_A(Azy, rzy);
    for (int k = 0; k < 3; k++) assert_near(d->qd[k], ad * ez[k] + cd * Azy[k], 1e-12); /* ω = ȧ z + ċ (R_z R_y x) */
    vt_data_free(d);
    vt_model_free(m);
}

/* Universal axes within the 1e-9 tolerance of perpendicular are made perpendicular to round-off:
 * with axis1 at a cosine of 1.35e-10 to axis2 (a fuzz input, crash-d87f…), the joint's R rows
 * were not S's left inverse, and a joint drive on the second rate, whose row the dense path forms
 * as Φ_x S = R S, leaked 1.35e-10 of its effort (4e-4 N·m of 3e6) onto the first rate, where the
 * recursive path's unit row puts none. Now the stored axes are perpendicular to 1e-16, the dense
 * row is the unit row to round-off, and the two paths' qfrc_drive agree. */
static void test_universal_axes_made_perpendicular(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    d.mass = 2.7;
    d.joint_child[1] = 3.9;
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d = vt_default_body_def();
    d.parent = 1;
    d.joint = VT_JOINT_UNIVERSAL;
    d.mass = 0.6;
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 0.01;
    d.axis1[0] = 1.35472e-10, d.axis1[1] = -0.719693, d.axis1[2] = -0.694292; /* cosine 1.35e-10 to x */
    d.joint_parent[0] = -7.0, d.joint_parent[1] = 6.75;
    d.joint_child[0] = -6.9, d.joint_child[1] = -4.4, d.joint_child[2] = -1.0;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 2;
    dr.index = 1;
    dr.f = vt_function_polynomial(3, (const double[3]){0.3, 0.0, 0.0});
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    const double *a1 = m->body_axis + 6 * 2, *a2 = a1 + 3;
    assert_true(fabs(a1[0] * a2[0] + a1[1] * a2[1] + a1[2] * a2[2]) <= 4e-16);
    vt_data *dd, *dr_;
    assert_ok(vt_data_create(&dd, m));
    assert_ok(vt_data_create(&dr_, m));
    const double q[3] = {1.1625, 1.89375, -1.78125}, qd[3] = {-1.0, -1.25, 4.375};
    memcpy(dd->q, q, sizeof q), memcpy(dr_->q, q, sizeof q);
    memcpy(dd->qd, qd, sizeof qd), memcpy(dr_->qd, qd, sizeof qd);
    dd->time = dr_->time = 6.0625;
    assert_ok(vt_inverse_dynamics(m, dd));
    assert_ok(vt_inverse_dynamics_recursive(m, dr_));
    const double big = fabs(dd->qfrc_drive[2]);
    print_message("dense Φ_q on rate 1: %.3g; qfrc_drive[1] dense %.3g, recursive %.3g (effort %.3g)\n", dd->Phiq[1],
                  dd->qfrc_drive[1], dr_->qfrc_drive[1], big);
    assert_true(fabs(dd->Phiq[1]) <= 1e-15); /* the row on the first rate */
    assert_true(fabs(dd->qfrc_drive[1] - dr_->qfrc_drive[1]) <= 64 * 2.220446049250313e-16 * big);
    vt_data_free(dd);
    vt_data_free(dr_);
    vt_model_free(m);
}

/* The inertia checks' tolerance is an option (vt_model_def.inertia_tol): an inertia off the
 * triangle inequality by 0.18 % of its largest moment (romeo_small's) is refused by default, the
 * message naming the option, and accepted with inertia_tol 2e-3, stored as given; a tolerance
 * outside [0, 1) is refused. */
static void test_inertia_tolerance_option(void **state)
{
    (void)state;
    vt_body_def d = vt_default_body_def();
    d.inertia[0] = 1.0;
    d.inertia[4] = 1.0;
    d.inertia[8] = 2.0036; /* 1 + 1 < 2.0036 by 0.0036, 0.18 % of 2.0036 */
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_INERTIA_TRIANGLE);
    assert_non_null(strstr(vt_builder_message(b), "vt_model_def.inertia_tol"));
    vt_builder_free(b);
    vt_model_def md = vt_default_model_def();
    assert_near(md.inertia_tol, VT_INERTIA_TOL, 0.0);
    md.inertia_tol = 2e-3;
    assert_ok(vt_builder_create(&b, &md));
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    vt_model *m = vt_test_build(b);
    assert_memory_equal(m->body_inertia + 9, d.inertia, sizeof d.inertia);
    vt_model_free(m);
    md.inertia_tol = 1e-3; /* below 0.18 %: refused */
    assert_ok(vt_builder_create(&b, &md));
    assert_int_equal(vt_builder_add_body(b, &d), VT_ERR_INERTIA_TRIANGLE);
    vt_builder_free(b);
    const double bad[3] = {-1e-9, 1.0, NAN};
    for (int k = 0; k < 3; k++) {
        md.inertia_tol = bad[k];
        b = (vt_builder *)&md; /* set to NULL by the refusal */
        assert_int_equal(vt_builder_create(&b, &md), VT_ERR_BAD_OPTION);
        assert_null(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_validation_errors),
        cmocka_unit_test(test_allowed_and_normalized),
        cmocka_unit_test(test_inertia_near_overflow),
        cmocka_unit_test(test_extreme_lengths),
        cmocka_unit_test(test_limits_and_null),
        cmocka_unit_test(test_real_files),
        cmocka_unit_test(test_couplings),
        cmocka_unit_test(test_free_joint),
        cmocka_unit_test(test_sequence_splines_owned),
        cmocka_unit_test(test_universal_axes_made_perpendicular),
        cmocka_unit_test(test_large_chain),
        cmocka_unit_test(test_inertia_tolerance_option),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
