/* src/dense/mass.c: ½ q̇^T M* q̇ against the bodies' kinetic energies, every entry of M* by
 * polarization of those energies, symmetry and positive definiteness (Cholesky), and
 * 4 G^T J' G = 4 E^T J E. */
#include "vt_test.h"

static void setup(vt_model **m, vt_data **d, uint64_t seed, int n, unsigned kinds)
{
    assert_ok(vt_scene_random_tree(m, seed, n, kinds));
    assert_ok(vt_data_create(d, *m));
    uint64_t s = seed * 13 + 5;
    vt_scene_random_state(*m, *d, &s);
    assert_ok(vt_kinematics(*m, *d));
    assert_ok(vt_mass_matrix(*m, *d));
}

static double quad(const vt_model *m, const vt_data *d, const double *v)
{
    double s = 0.0;
    for (int a = 0; a < m->nv; a++)
        for (int b = 0; b < m->nv; b++) s += v[a] * d->Mstar[a + (size_t)b * (size_t)m->nv] * v[b];
    return s;
}

/* T from the bodies' velocities at rates v (keeps d's M*, overwrites its kinematics) */
static double energy_at(const vt_model *m, vt_data *d, const double *v)
{
    memcpy(d->qd, v, (size_t)m->nv * sizeof(double));
    assert_ok(vt_kinematics(m, d));
    return vt_test_kinetic_energy(m, d);
}

static void test_kinetic_energy(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 10; seed++) {
        vt_model *m;
        vt_data *d;
        setup(&m, &d, seed, 6 + (int)seed, VT_SCENE_ALL_JOINTS);
        const double T = vt_test_kinetic_energy(m, d);
        assert_near(0.5 * quad(m, d, d->qd), T, 1e-12 * T);
        vt_data_free(d);
        vt_model_free(m);
    }
}

static void test_polarization(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    setup(&m, &d, 4, 12, VT_SCENE_ALL_JOINTS);
    const int nv = m->nv;
    double *v = calloc((size_t)nv, sizeof(double)), *Tk = malloc((size_t)nv * sizeof(double));
    double scale = vt_test_maxabs(d->Mstar, nv * nv);
    for (int a = 0; a < nv; a++) {
        v[a] = 1.0;
        Tk[a] = energy_at(m, d, v);
        v[a] = 0.0;
        assert_near(d->Mstar[a + (size_t)a * (size_t)nv], 2.0 * Tk[a], 1e-12 * scale);
    }
    for (int a = 0; a < nv; a++)
        for (int b = 0; b < a; b++) {
            v[a] = v[b] = 1.0;
            const double Tab = energy_at(m, d, v);
            v[a] = v[b] = 0.0;
            assert_near(d->Mstar[a + (size_t)b * (size_t)nv], Tab - Tk[a] - Tk[b], 1e-12 * scale);
            assert_near(d->Mstar[b + (size_t)a * (size_t)nv], Tab - Tk[a] - Tk[b], 1e-12 * scale);
        }
    free(v); free(Tk);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_symmetric_positive_definite(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 8; seed++) {
        vt_model *m;
        vt_data *d;
        setup(&m, &d, seed, 10, VT_SCENE_NO_BASE);
        const int nv = m->nv;
        const double scale = vt_test_maxabs(d->Mstar, nv * nv);
        for (int a = 0; a < nv; a++)
            for (int b = 0; b < a; b++)
                assert_near(d->Mstar[a + (size_t)b * nv], d->Mstar[b + (size_t)a * nv], 1e-14 * scale);
        double *L = malloc((size_t)nv * (size_t)nv * sizeof(double));
        memcpy(L, d->Mstar, (size_t)nv * (size_t)nv * sizeof(double));
        int info = 0;
        dpotrf_("L", &nv, L, &nv, &info, 1);
        assert_int_equal(info, 0);
        free(L);
        vt_data_free(d);
        vt_model_free(m);
    }
    /* with a base body M* is only semi-definite in q̇ = ẋ: 4 G^T J' G p = 0, the normal
     * direction of the Euler parameters, which p^T p = 1 removes; on tangent rates it is
     * positive */
    vt_model *m;
    vt_data *d;
    setup(&m, &d, 2, 6, VT_SCENE_ALL_JOINTS);
    assert_int_equal(m->body_joint[1], VT_JOINT_BASE);
    double *v = calloc((size_t)m->nv, sizeof(double));
    memcpy(v + 3, d->x + 3, 4 * sizeof(double)); /* ṗ = p */
    assert_near(quad(m, d, v), 0.0, 1e-12 * vt_test_maxabs(d->Mstar, m->nv * m->nv));
    assert_true(quad(m, d, d->qd) > 0.0);
    free(v);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_rotational_block(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    setup(&m, &d, 5, 9, VT_SCENE_ALL_JOINTS);
    for (int i = 1; i <= m->nbody; i++) {
        /* 4 E^T J E with J = A J' A^T */
        double J[9], E[12];
        vt_test_global_inertia(J, m, d, i);
        vt_euler_E(E, d->x + 7 * (i - 1) + 3);
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) {
                double s = 0.0;
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) s += E[a + 3 * r] * J[a + 3 * b] * E[b + 3 * c];
                assert_near(d->Mp[16 * i + r + 4 * c], 4.0 * s, 1e-13);
            }
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* A point mass of 1e300 kg on a hinge 1e10 m away: positions and velocities are finite, but its
 * M* entry m |e × r|² = 1e320 overflows: refused, naming the entry. */
static void test_overflowing_entry_refused(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.mass = 1e300;
    body.joint_child[0] = -1e10;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    d->message[0] = '\0';
    assert_int_equal(vt_mass_matrix(m, d), VT_ERR_NONFINITE);
    assert_non_null(strstr(d->message, "M*[0, 0]"));
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kinetic_energy),
        cmocka_unit_test(test_polarization),
        cmocka_unit_test(test_symmetric_positive_definite),
        cmocka_unit_test(test_rotational_block),
        cmocka_unit_test(test_overflowing_entry_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
