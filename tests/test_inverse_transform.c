/* src/kinematics/inverse_transform.c: R S = I on random trees with every joint kind, and F_eq = R^T Q (14)
 * against the forces a joint effort puts on its two bodies, written with (7). */
#include "vt_test.h"

static void state_for(vt_model **m, vt_data **d, uint64_t seed, int n, unsigned kinds)
{
    assert_ok(vt_scene_random_tree(m, seed, n, kinds));
    assert_ok(vt_data_create(d, *m));
    uint64_t s = seed * 31 + 7;
    vt_scene_random_state(*m, *d, &s);
    assert_ok(vt_kinematics(*m, *d));
    assert_ok(vt_inverse_transform(*m, *d));
}

static void test_RS_identity(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 20; seed++) {
        vt_model *m;
        vt_data *d;
        state_for(&m, &d, seed, 4 + (int)seed, seed % 4 == 0 ? VT_SCENE_WITH_FREE : seed % 3 ? VT_SCENE_ALL_JOINTS : VT_SCENE_NO_BASE);
        const int nv = m->nv, nx = m->nx;
        for (int a = 0; a < nv; a++)
            for (int b = 0; b < nv; b++) {
                double s = 0.0;
                for (int k = 0; k < nx; k++) s += d->R[a + (size_t)k * (size_t)nv] * d->S[k + (size_t)b * (size_t)nx];
                assert_near(s, a == b ? 1.0 : 0.0, 1e-12);
            }
        /* hence q̇ = R ẋ */
        for (int a = 0; a < nv; a++) {
            double s = 0.0;
            for (int k = 0; k < nx; k++) s += d->R[a + (size_t)k * (size_t)nv] * d->xd[k];
            assert_near(s, d->qd[a], 1e-12 * (1 + fabs(d->qd[a])));
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* A unit effort at one rate of a joint: on body i and on its reference j it is
 * a moment ±e (rotational rate), or a force ±e at the reference's joint point P_j
 * (translational rate). F_eq = R^T Q must be those forces, written with (7). */
static void test_equivalent_force(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    state_for(&m, &d, 3, 18, VT_SCENE_NO_BASE);
    const int nv = m->nv, nx = m->nx;
    double *Q = calloc((size_t)nv, sizeof(double)), *Feq = malloc((size_t)nx * sizeof(double));
    double *want = malloc((size_t)nx * sizeof(double));
    for (int c = 0; c < nv; c++) {
        const int i = m->dof_body[c], j = m->body_parent[i], jt = m->body_joint[i];
        const int k = c - m->body_vadr[i];
        const int rot = !(jt == VT_JOINT_TRANSLATIONAL || (jt == VT_JOINT_CYLINDRICAL && k == 1));
        const double *e = d->jaxis + 9 * i + 3 * (jt == VT_JOINT_CYLINDRICAL ? 0 : k);
        Q[c] = 1.0;
        assert_ok(vt_equivalent_force(Feq, m, d, Q));
        Q[c] = 0.0;
        memset(want, 0, (size_t)nx * sizeof(double));
        const double zero[3] = {0, 0, 0};
        double minus[3] = {-e[0], -e[1], -e[2]};
        /* P_j = r^j + s^{ij}; from body i's origin: P_j − r^i */
        double Pj[3], si[3], sj[3];
        for (int r = 0; r < 3; r++) {
            Pj[r] = (j ? d->x[7 * (j - 1) + r] : 0.0) + d->jsij[3 * i + r];
            si[r] = Pj[r] - d->x[7 * (i - 1) + r];
            sj[r] = d->jsij[3 * i + r];
        }
        if (rot) {
            vt_cartesian_force(want + 7 * (i - 1), d->x + 7 * (i - 1) + 3, zero, zero, e);
            if (j) vt_cartesian_force(want + 7 * (j - 1), d->x + 7 * (j - 1) + 3, zero, zero, minus);
        } else {
            vt_cartesian_force(want + 7 * (i - 1), d->x + 7 * (i - 1) + 3, si, e, zero);
            if (j) vt_cartesian_force(want + 7 * (j - 1), d->x + 7 * (j - 1) + 3, sj, minus, zero);
        }
        for (int r = 0; r < nx; r++) assert_near(Feq[r], want[r], 1e-12);
    }
    /* bad input: status, output untouched */
    memcpy(want, Feq, (size_t)nx * sizeof(double));
    Q[0] = NAN;
    assert_int_equal(vt_equivalent_force(Feq, m, d, Q), VT_ERR_NONFINITE);
    assert_memory_equal(want, Feq, (size_t)nx * sizeof(double));
    assert_int_equal(vt_equivalent_force(NULL, m, d, Q), VT_ERR_NULL);
    free(Q); free(Feq); free(want);
    vt_data_free(d);
    vt_model_free(m);
}

/* vt_equivalent_force with a finite Q whose R^T Q overflows: on the double link (both joints
 * about z) link 1's block is 2 E^T e (Q1 − Q2), with Q = (1.7e308, −1.7e308) beyond DBL_MAX:
 * VT_ERR_NONFINITE, Feq left as it was. */
static void test_equivalent_force_overflow(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 0));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    assert_ok(vt_inverse_transform(m, d));
    double Feq[14], before[14], Q[2] = {1.7e308, -1.7e308};
    for (int k = 0; k < 14; k++) Feq[k] = before[k] = k + 0.5;
    assert_int_equal(vt_equivalent_force(Feq, m, d, Q), VT_ERR_NONFINITE);
    assert_true(strlen(d->message) > 0);
    assert_memory_equal(Feq, before, sizeof Feq);
    vt_data_free(d);
    vt_model_free(m);
}

/* A translational joint whose body's joint point lies 1e308 m from its centre of mass: every
 * position is finite, but R's row (2 E^T (e × d)) overflows: refused, naming the row. */
static void test_overflowing_row_refused(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_TRANSLATIONAL;
    body.axis1[0] = 1.0, body.axis1[2] = 0.0;
    body.joint_child[1] = -1e308;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    d->message[0] = '\0';
    assert_int_equal(vt_inverse_transform(m, d), VT_ERR_NONFINITE);
    assert_non_null(strstr(d->message, "row 0"));
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_RS_identity),
        cmocka_unit_test(test_equivalent_force),
        cmocka_unit_test(test_equivalent_force_overflow),
        cmocka_unit_test(test_overflowing_row_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
