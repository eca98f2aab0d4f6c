/* src/constraints.c: Φ_q = Φ_x S (22) against central differences of Φ(x(q), t) along every
 * rate, Φ_t against differences in t, and γ (23) against the second difference of Φ along a
 * motion with q̈ = 0 — for every kind of row: joint, point and orientation drives (built-in
 * and callback), cut joints of every kind and a planar pin, the base bodies' p^T p = 1, and a
 * coupling of two joint coordinates. */
#include "vt_test.h"

/* prescribed orientation with a turning axis: p = [a t about u1] ⊗ [b t about u2] */
static int turning(double t, double p[4], double w[3], double wd[3], void *user)
{
    (void)user;
    const double u1[3] = {0.0, 0.6, 0.8}, u2[3] = {1.0, 0.0, 0.0}, a = 0.7, b = -1.3;
    double p1[4], p2[4], A1[9], v[3];
    vt_quat_axis_angle(p1, u1, a * t);
    vt_quat_axis_angle(p2, u2, b * t);
    vt_quat_mul(p, p1, p2);
    vt_euler_A(A1, p1);
    for (int k = 0; k < 3; k++) v[k] = A1[k] * u2[0] + A1[k + 3] * u2[1] + A1[k + 6] * u2[2];
    for (int k = 0; k < 3; k++) w[k] = a * u1[k] + b * v[k];
    /* ω̇ = b (a u1 × v) */
    wd[0] = a * b * (u1[1] * v[2] - u1[2] * v[1]);
    wd[1] = a * b * (u1[2] * v[0] - u1[0] * v[2]);
    wd[2] = a * b * (u1[0] * v[1] - u1[1] * v[0]);
    return 0;
}

/* a random tree with every joint kind and every kind of constraint row */
static vt_model *build_all_kinds(uint64_t seed)
{
    const int n = 14;
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, seed, n, VT_SCENE_ALL_JOINTS));
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, seed, n, VT_SCENE_ALL_JOINTS));
    uint64_t s = seed + 100;
    for (int i = 1; i <= n; i++) {
        const int jt = probe->body_joint[i];
        if (jt == VT_JOINT_SPHERICAL) continue;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = i;
        dr.index = jt == VT_JOINT_BASE ? 1 : probe->body_nv[i] - 1;
        dr.f = vt_function_sine(vt_rand_uniform(&s, -1, 1), vt_rand_uniform(&s, -1, 1), vt_rand_uniform(&s, 1, 5), 0.3);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    for (int c = 0; c < 3; c++) { /* point drives, each component */
        vt_drive_def dr = vt_default_drive_def();
        const double coef[3] = {0.2, -0.5, 0.7};
        dr.type = VT_DRIVE_POINT;
        dr.body = 2 + 4 * c;
        dr.index = c;
        for (int k = 0; k < 3; k++) dr.point[k] = vt_rand_uniform(&s, -0.5, 0.5);
        dr.f = vt_function_polynomial(3, coef);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    vt_drive_def od = vt_default_drive_def(); /* orientation, built-in */
    od.type = VT_DRIVE_ORIENTATION;
    od.body = 5;
    vt_rand_unit(od.axis, 3, &s);
    vt_rand_unit(od.orientation, 4, &s);
    od.f = vt_function_sine(0.2, 0.8, 3.0, 0.1);
    assert_true(vt_builder_add_drive(b, &od) >= 0);
    od.body = 9; /* orientation, callback */
    od.orientation_callback = turning;
    assert_true(vt_builder_add_drive(b, &od) >= 0);
    static const vt_joint_type kinds[6] = {VT_JOINT_REVOLUTE, VT_JOINT_UNIVERSAL, VT_JOINT_SPHERICAL,
                                           VT_JOINT_TRANSLATIONAL, VT_JOINT_CYLINDRICAL, VT_JOINT_REVOLUTE};
    for (int k = 0; k < 6; k++) { /* the last a planar pin */
        vt_cut_joint_def cj = vt_default_cut_joint_def();
        cj.joint = kinds[k];
        cj.planar = k == 5;
        cj.body_a = k == 0 ? 0 : 1 + k;
        cj.body_b = 8 + k;
        for (int c = 0; c < 3; c++) {
            cj.point_a[c] = vt_rand_uniform(&s, -0.5, 0.5);
            cj.point_b[c] = vt_rand_uniform(&s, -0.5, 0.5);
        }
        vt_rand_unit(cj.axis1, 3, &s);
        double t[3];
        vt_rand_unit(t, 3, &s);
        const double dt = t[0] * cj.axis1[0] + t[1] * cj.axis1[1] + t[2] * cj.axis1[2];
        for (int c = 0; c < 3; c++) cj.axis2[c] = t[c] - dt * cj.axis1[c];
        vt_rand_unit(cj.orientation, 4, &s);
        assert_true(vt_builder_add_cut_joint(b, &cj) >= 0);
    }
    int scalar[2] = {0, 0}; /* a coupling of two scalar coordinates, the last rate of each joint */
    for (int i = n, k = 0; i >= 1 && k < 2; i--)
        if (probe->body_joint[i] != VT_JOINT_SPHERICAL && probe->body_joint[i] != VT_JOINT_BASE) scalar[k++] = i;
    assert_true(scalar[1] > 0);
    vt_coupling_def cp = vt_default_coupling_def();
    cp.body_a = scalar[0];
    cp.index_a = probe->body_nv[scalar[0]] - 1;
    cp.body_b = scalar[1];
    cp.index_b = probe->body_nv[scalar[1]] - 1;
    cp.ratio = -0.7;
    cp.offset = 0.2;
    assert_int_equal(vt_builder_add_coupling(b, &cp), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_model_free(probe);
    return m;
}

static void eval_phi(const vt_model *m, vt_data *d, const double *q, const double *v, double t, double *phi)
{
    memcpy(d->q, q, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, v, (size_t)m->nv * sizeof(double));
    d->time = t;
    assert_ok(vt_kinematics(m, d));
    assert_ok(vt_constraints(m, d));
    if (phi) memcpy(phi, d->Phi, (size_t)m->nc * sizeof(double));
}

static void test_rows_against_finite_differences(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) {
        vt_model *m = build_all_kinds(seed);
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        const int nq = m->nq, nv = m->nv, nc = m->nc;
        int kinds_seen[7] = {0}; /* joint, point, dot, line, orientation, normalization, coupling */
        for (int r = 0; r < nc; r++) kinds_seen[m->con_kind[r]]++;
        for (int k = 0; k < 7; k++) assert_true(kinds_seen[k] > 0);
        uint64_t s = seed * 5;
        vt_scene_random_state(m, d, &s);
        const double t0 = 0.37;
        double *q = malloc((size_t)nq * sizeof(double)), *v = malloc((size_t)nv * sizeof(double));
        double *qa = malloc((size_t)nq * sizeof(double)), *qb = malloc((size_t)nq * sizeof(double));
        double *e = calloc((size_t)nv, sizeof(double)), *zero = calloc((size_t)nv, sizeof(double));
        double *pa = malloc((size_t)nc * sizeof(double)), *pb = malloc((size_t)nc * sizeof(double));
        double *p0 = malloc((size_t)nc * sizeof(double)), *Phiq = malloc((size_t)nc * (size_t)nv * sizeof(double));
        double *gam = malloc((size_t)nc * sizeof(double)), *Phit = malloc((size_t)nc * sizeof(double));
        memcpy(q, d->q, (size_t)nq * sizeof(double));
        memcpy(v, d->qd, (size_t)nv * sizeof(double));
        eval_phi(m, d, q, v, t0, p0);
        memcpy(Phiq, d->Phiq, (size_t)nc * (size_t)nv * sizeof(double));
        { /* the planar pin's two rows: the joint points' separation in the plane ⟂ a's axis1 */
            const int k = m->ncut - 1;
            const vt_cut_joint_def *c = &m->cut[k];
            assert_int_equal(c->planar, 1);
            assert_int_equal(m->cut_row[k] + 2, k + 1 < m->ncut ? m->cut_row[k + 1] : m->coupling_row[0]);
            double P[2][3], ax[3], sep[3];
            for (int side = 0; side < 2; side++) {
                const int bd = side ? c->body_b : c->body_a;
                const double *sp = side ? c->point_b : c->point_a, *A = d->A + 9 * bd;
                for (int e = 0; e < 3; e++)
                    P[side][e] = (bd ? d->x[7 * (bd - 1) + e] : 0.0) + A[e] * sp[0] + A[e + 3] * sp[1] + A[e + 6] * sp[2];
            }
            const double *Aa = d->A + 9 * c->body_a;
            for (int e = 0; e < 3; e++) {
                ax[e] = Aa[e] * c->axis1[0] + Aa[e + 3] * c->axis1[1] + Aa[e + 6] * c->axis1[2];
                sep[e] = P[1][e] - P[0][e];
            }
            const double along = sep[0] * ax[0] + sep[1] * ax[1] + sep[2] * ax[2];
            const double inplane2 = sep[0] * sep[0] + sep[1] * sep[1] + sep[2] * sep[2] - along * along;
            const double r0 = p0[m->cut_row[k]], r1 = p0[m->cut_row[k] + 1];
            assert_near(r0 * r0 + r1 * r1, inplane2, 1e-12 * (1 + inplane2));
            assert_true(inplane2 > 1e-4 && fabs(along) > 1e-3); /* a random pose: both parts present */
        }
        memcpy(gam, d->gamma, (size_t)nc * sizeof(double));
        memcpy(Phit, d->Phit, (size_t)nc * sizeof(double));

        /* Φ_q, column by column (a base body's ṗ only along the tangent, below) */
        const double h = 1e-6;
        for (int c = 0; c <= nv; c++) {
            const double *dir = v;
            if (c < nv) {
                const int bb = m->dof_body[c];
                if (m->body_joint[bb] == VT_JOINT_BASE && c - m->body_vadr[bb] >= 3) continue;
                e[c] = 1.0;
                dir = e;
            }
            assert_ok(vt_integrate_q(qa, m, q, dir, h));
            assert_ok(vt_integrate_q(qb, m, q, dir, -h));
            eval_phi(m, d, qa, zero, t0, pa);
            eval_phi(m, d, qb, zero, t0, pb);
            for (int r = 0; r < nc; r++) {
                double want = 0.0;
                for (int k = 0; k < nv; k++) want += Phiq[r + (size_t)k * (size_t)nc] * dir[k];
                assert_near((pa[r] - pb[r]) / (2 * h), want, 1e-7 * (1 + fabs(want)));
            }
            if (c < nv) e[c] = 0.0;
        }
        /* Φ_t */
        eval_phi(m, d, q, zero, t0 + h, pa);
        eval_phi(m, d, q, zero, t0 - h, pb);
        for (int r = 0; r < nc; r++) assert_near((pa[r] - pb[r]) / (2 * h), Phit[r], 1e-7 * (1 + fabs(Phit[r])));

        /* γ = Φ_q q̈_path − Φ̈ along q(τ) = q ⊕ τ q̇, t = t0 + τ. The path keeps the rates
         * constant except a base body's ṗ, which turns with p: q̈_p = −¼ |ω|² p. */
        const double hh = 1e-4;
        assert_ok(vt_integrate_q(qa, m, q, v, hh));
        assert_ok(vt_integrate_q(qb, m, q, v, -hh));
        double *va = malloc((size_t)nv * sizeof(double)), *vb = malloc((size_t)nv * sizeof(double));
        double *qpath = calloc((size_t)nv, sizeof(double));
        memcpy(va, v, (size_t)nv * sizeof(double));
        memcpy(vb, v, (size_t)nv * sizeof(double));
        for (int i = 1; i <= m->nbody; i++) {
            if (m->body_joint[i] != VT_JOINT_BASE) continue;
            const int o = m->body_vadr[i] + 3;
            double E[12], w[3] = {0};
            vt_euler_E(E, q + m->body_qadr[i] + 3);
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 4; k++) w[r] += 2 * E[r + 3 * k] * v[o + k];
            const double w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
            for (int k = 0; k < 4; k++) qpath[o + k] = -0.25 * w2 * q[m->body_qadr[i] + 3 + k];
        }
        eval_phi(m, d, qa, va, t0 + hh, pa);
        eval_phi(m, d, qb, vb, t0 - hh, pb);
        for (int r = 0; r < nc; r++) {
            double Pq = 0.0;
            for (int k = 0; k < nv; k++) Pq += Phiq[r + (size_t)k * (size_t)nc] * qpath[k];
            const double phidd = (pa[r] - 2 * p0[r] + pb[r]) / (hh * hh);
            assert_near(gam[r], Pq - phidd, 1e-5 * (1 + fabs(gam[r])));
        }
        free(va); free(vb); free(qpath);
        free(q); free(v); free(qa); free(qb); free(e); free(zero); free(pa); free(pb); free(p0);
        free(Phiq); free(gam); free(Phit);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* A joint drive's Φ_x is the row of R, so Φ_q = Φ_x S is a unit row (R S = I) */
static void test_joint_rows_are_unit(void **state)
{
    (void)state;
    vt_model *m = build_all_kinds(3);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    uint64_t s = 2;
    vt_scene_random_state(m, d, &s);
    assert_ok(vt_kinematics(m, d));
    assert_ok(vt_constraints(m, d));
    for (int r = 0; r < m->nc; r++) {
        if (m->con_kind[r] != 0 /* VT_ROW_JOINT */) continue;
        for (int c = 0; c < m->nv; c++)
            assert_near(d->Phiq[r + (size_t)c * (size_t)m->nc], c == m->con_dof[r] ? 1.0 : 0.0, 1e-13);
    }
    vt_data_free(d);
    vt_model_free(m);
}

static int broken(double t, double p[4], double w[3], double wd[3], void *user)
{
    (void)t; (void)p; (void)w; (void)wd; (void)user;
    return -1;
}

static void test_callback_failure(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_SPHERICAL;
    body.inertia[0] = body.inertia[4] = body.inertia[8] = 1.0;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    od.orientation_callback = broken;
    assert_int_equal(vt_builder_add_drive(b, &od), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    assert_int_equal(vt_constraints(m, d), VT_ERR_CALLBACK);
    assert_non_null(strstr(d->message, "drive 0"));
    vt_data_free(d);
    vt_model_free(m);
}

/* Finite inputs whose constraint values overflow: a joint drive to f = 1.7e308 rad from
 * q = −1.7e308 rad gives Φ = q − f = −Inf. vt_constraints refuses it (VT_ERR_NONFINITE) and
 * names the row and its drive, instead of returning VT_OK with Inf in Φ. */
static void test_overflowing_rows(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_drive_def jd = vt_default_drive_def();
    jd.f = vt_function_constant(1.7e308);
    assert_int_equal(vt_builder_add_drive(b, &jd), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    d->q[0] = -1.7e308;
    assert_ok(vt_kinematics(m, d));
    assert_int_equal(vt_constraints(m, d), VT_ERR_NONFINITE);
    assert_non_null(strstr(d->message, "row 0"));
    assert_non_null(strstr(d->message, "drive 0"));
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rows_against_finite_differences),
        cmocka_unit_test(test_joint_rows_are_unit),
        cmocka_unit_test(test_callback_failure),
        cmocka_unit_test(test_overflowing_rows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
