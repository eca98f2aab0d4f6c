/* src/dense/forces.c: Q's gravity part against −∂V/∂q (finite differences of the potential),
 * Q's velocity part against the Lagrangian d/dt(∂T/∂q̇) − ∂T/∂q (finite differences along a
 * motion), against Newton–Euler, and against the power balance; (7) and (10) against the
 * virtual power of a load. */
#include "vt_test.h"

typedef struct {
    vt_model *m;
    vt_data *d;
    double *q, *v, *w;  /* state (nq, nv), scratch (nv) */
} fixture;

static void setup(fixture *f, uint64_t seed, int n, unsigned kinds)
{
    assert_ok(vt_scene_random_tree(&f->m, seed, n, kinds));
    assert_ok(vt_data_create(&f->d, f->m));
    uint64_t s = seed * 17 + 3;
    vt_scene_random_state(f->m, f->d, &s);
    f->q = malloc((size_t)f->m->nq * sizeof(double));
    f->v = malloc((size_t)f->m->nv * sizeof(double));
    f->w = malloc((size_t)f->m->nv * sizeof(double));
    memcpy(f->q, f->d->q, (size_t)f->m->nq * sizeof(double));
    memcpy(f->v, f->d->qd, (size_t)f->m->nv * sizeof(double));
}

static void teardown(fixture *f)
{
    free(f->q); free(f->v); free(f->w);
    vt_data_free(f->d);
    vt_model_free(f->m);
}

static void at(fixture *f, const double *q, const double *v)
{
    memcpy(f->d->q, q, (size_t)f->m->nq * sizeof(double));
    memcpy(f->d->qd, v, (size_t)f->m->nv * sizeof(double));
    assert_ok(vt_kinematics(f->m, f->d));
}

/* Q_v = Q − S^T F: the velocity part */
static void velocity_part(fixture *f, double *Qv)
{
    assert_ok(vt_mass_matrix(f->m, f->d));
    assert_ok(vt_forces(f->m, f->d));
    assert_ok(vt_generalized_force(Qv, f->m, f->d, f->d->F));
    for (int c = 0; c < f->m->nv; c++) Qv[c] = f->d->Q[c] - Qv[c];
}

static void test_gravity_is_minus_dV_dq(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        fixture f;
        setup(&f, seed, 12, VT_SCENE_ALL_JOINTS);
        const vt_model *m = f.m;
        const int nv = m->nv;
        double *zero = calloc((size_t)nv, sizeof(double)), *Q = malloc((size_t)nv * sizeof(double));
        double *qa = malloc((size_t)m->nq * sizeof(double)), *qb = malloc((size_t)m->nq * sizeof(double));
        at(&f, f.q, zero); /* at rest Q is gravity alone */
        assert_ok(vt_mass_matrix(m, f.d));
        assert_ok(vt_forces(m, f.d));
        memcpy(Q, f.d->Q, (size_t)nv * sizeof(double));
        const double h = 1e-5;
        /* along each rate (a base body's ṗ only along the tangent: the random rates) */
        for (int c = 0; c <= nv; c++) {
            double *dir = zero;
            if (c < nv) {
                const int b = m->dof_body[c];
                if (m->body_joint[b] == VT_JOINT_BASE && c - m->body_vadr[b] >= 3) continue;
                zero[c] = 1.0;
            } else {
                dir = f.v;
            }
            assert_ok(vt_integrate_q(qa, m, f.q, dir, h));
            assert_ok(vt_integrate_q(qb, m, f.q, dir, -h));
            memset(f.w, 0, (size_t)nv * sizeof(double));
            at(&f, qa, f.w);
            const double Va = vt_test_potential_energy(m, f.d);
            at(&f, qb, f.w);
            const double Vb = vt_test_potential_energy(m, f.d);
            double Qdir = 0.0;
            for (int k = 0; k < nv; k++) Qdir += Q[k] * dir[k];
            assert_near(Qdir, -(Va - Vb) / (2 * h), 1e-6 * (1 + fabs(Qdir)));
            if (c < nv) zero[c] = 0.0;
        }
        free(zero); free(Q); free(qa); free(qb);
        teardown(&f);
    }
}

/* Scalar coordinates: Q_v = −[d/dt (M* q̇) − ∂T/∂q] along q(t) = q + t q̇ (q̈ = 0) */
static void test_lagrangian(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        fixture f;
        setup(&f, seed, 10, VT_SCENE_SCALAR_JOINTS);
        const vt_model *m = f.m;
        const int nv = m->nv;
        assert_int_equal(m->nq, nv);
        double *Qv = malloc((size_t)nv * sizeof(double)), *qa = malloc((size_t)nv * sizeof(double));
        double *pa = malloc((size_t)nv * sizeof(double)), *pb = malloc((size_t)nv * sizeof(double));
        at(&f, f.q, f.v);
        velocity_part(&f, Qv);
        const double h = 1e-5;
        /* d/dt (M*(q(t)) q̇) */
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            for (int k = 0; k < nv; k++) qa[k] = f.q[k] + sgn * h * f.v[k];
            at(&f, qa, f.v);
            assert_ok(vt_mass_matrix(m, f.d));
            double *p = sgn > 0 ? pa : pb;
            for (int a = 0; a < nv; a++) {
                p[a] = 0.0;
                for (int b = 0; b < nv; b++) p[a] += f.d->Mstar[a + (size_t)b * (size_t)nv] * f.v[b];
            }
        }
        double scale = 1.0 + vt_test_maxabs(Qv, nv);
        for (int k = 0; k < nv; k++) {
            /* ∂T/∂q_k, T from the bodies' velocities */
            memcpy(qa, f.q, (size_t)nv * sizeof(double));
            qa[k] += h;
            at(&f, qa, f.v);
            const double Ta = vt_test_kinetic_energy(m, f.d);
            qa[k] -= 2 * h;
            at(&f, qa, f.v);
            const double Tb = vt_test_kinetic_energy(m, f.d);
            const double lagrange = (pa[k] - pb[k]) / (2 * h) - (Ta - Tb) / (2 * h);
            assert_near(Qv[k], -lagrange, 1e-6 * scale);
        }
        free(Qv); free(qa); free(pa); free(pb);
        teardown(&f);
    }
}

/* Every joint kind: Q_v = −Σ_i [Jv_i^T m a0_i + Jω_i^T (J α0_i + ω̃ J ω)], the Newton–Euler
 * form, with Jv, Jω the bodies' velocity Jacobians (ω = 2 E ṗ) and a0, α0 the accelerations
 * at q̈ = 0 (from Ṡq̇, α = 2 E p̈) */
static void test_newton_euler(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        fixture f;
        setup(&f, seed, 14, VT_SCENE_ALL_JOINTS);
        const vt_model *m = f.m;
        vt_data *d = f.d;
        const int nv = m->nv, nx = m->nx;
        double *Qv = malloc((size_t)nv * sizeof(double)), *ne = calloc((size_t)nv, sizeof(double));
        at(&f, f.q, f.v);
        velocity_part(&f, Qv);
        for (int i = 1; i <= m->nbody; i++) {
            const int o = 7 * (i - 1);
            const double *w = d->omega + 3 * i;
            double E[12], J[9], al[3] = {0}, Jw[3], Ja[3], tq[3], fr[3];
            vt_euler_E(E, d->x + o + 3);
            vt_test_global_inertia(J, m, d, i);
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 4; k++) al[r] += 2 * E[r + 3 * k] * d->Sdqd[o + 3 + k];
            for (int r = 0; r < 3; r++) {
                Jw[r] = J[r] * w[0] + J[r + 3] * w[1] + J[r + 6] * w[2];
                Ja[r] = J[r] * al[0] + J[r + 3] * al[1] + J[r + 6] * al[2];
                fr[r] = m->body_mass[i] * d->Sdqd[o + r];
            }
            tq[0] = Ja[0] + w[1] * Jw[2] - w[2] * Jw[1];
            tq[1] = Ja[1] + w[2] * Jw[0] - w[0] * Jw[2];
            tq[2] = Ja[2] + w[0] * Jw[1] - w[1] * Jw[0];
            for (int c = 0; c < nv; c++) {
                const double *Sc = d->S + (size_t)c * (size_t)nx + o;
                double jw[3] = {0};
                for (int r = 0; r < 3; r++)
                    for (int k = 0; k < 4; k++) jw[r] += 2 * E[r + 3 * k] * Sc[3 + k];
                ne[c] -= Sc[0] * fr[0] + Sc[1] * fr[1] + Sc[2] * fr[2] + jw[0] * tq[0] + jw[1] * tq[1] + jw[2] * tq[2];
            }
        }
        /* A base body's own ṗ columns: the Lagrangian form (4) in p and the Newton–Euler
         * form differ by a multiple of p, the normal direction that the constraint
         * p^T p = 1 takes up (p^T h_p = 2 ω'^T J' ω'): compare the tangential parts. */
        for (int i = 1; i <= m->nbody; i++) {
            if (m->body_joint[i] != VT_JOINT_BASE) continue;
            const double *p = d->x + 7 * (i - 1) + 3;
            double *a = Qv + m->body_vadr[i] + 3, *b = ne + m->body_vadr[i] + 3;
            const double pa = p[0] * a[0] + p[1] * a[1] + p[2] * a[2] + p[3] * a[3];
            const double pb = p[0] * b[0] + p[1] * b[1] + p[2] * b[2] + p[3] * b[3];
            for (int k = 0; k < 4; k++) { a[k] -= pa * p[k]; b[k] -= pb * p[k]; }
        }
        const double scale = 1.0 + vt_test_maxabs(ne, nv);
        for (int c = 0; c < nv; c++) assert_near(Qv[c], ne[c], 1e-12 * scale);
        free(Qv); free(ne);
        teardown(&f);
    }
}

/* Every joint kind: dT/dt = q̇^T (M* q̈ − Q_v) along a motion with rates q̇ + t q̈ */
static void test_power_balance(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        fixture f;
        setup(&f, seed, 12, VT_SCENE_ALL_JOINTS);
        const vt_model *m = f.m;
        const int nv = m->nv;
        double *Qv = malloc((size_t)nv * sizeof(double)), *qdd = malloc((size_t)nv * sizeof(double));
        double *qa = malloc((size_t)m->nq * sizeof(double)), *va = malloc((size_t)nv * sizeof(double));
        uint64_t s = seed;
        /* q̈, tangent for a base body's Euler parameters like its ṗ */
        for (int c = 0; c < nv; c++) qdd[c] = f.v[c] * vt_rand_uniform(&s, -1, 1);
        for (int i = 1; i <= m->nbody; i++)
            if (m->body_joint[i] == VT_JOINT_BASE)
                for (int k = 0; k < 4; k++) qdd[m->body_vadr[i] + 3 + k] = 0.3 * f.v[m->body_vadr[i] + 3 + k];
        at(&f, f.q, f.v);
        velocity_part(&f, Qv);
        double power = 0.0;
        for (int a = 0; a < nv; a++) {
            double s2 = 0.0;
            for (int b = 0; b < nv; b++) s2 += f.d->Mstar[a + (size_t)b * (size_t)nv] * qdd[b];
            power += f.v[a] * (s2 - Qv[a]);
        }
        const double h = 1e-5;
        double T[2];
        for (int k = 0; k < 2; k++) {
            const double t = k ? h : -h;
            assert_ok(vt_integrate_q(qa, m, f.q, f.v, t));
            for (int c = 0; c < nv; c++) va[c] = f.v[c] + t * qdd[c];
            at(&f, qa, va);
            T[k] = vt_test_kinetic_energy(m, f.d);
        }
        assert_near(power, (T[1] - T[0]) / (2 * h), 1e-6 * (1 + fabs(power)));
        free(Qv); free(qdd); free(qa); free(va);
        teardown(&f);
    }
}

/* (7) and (10): a force f and moment n at a body point s do the virtual power
 * f·(v + ω × s) + n·ω = F^T ẋ = Q^T q̇ */
static void test_load_virtual_power(void **state)
{
    (void)state;
    fixture f;
    setup(&f, 9, 12, VT_SCENE_ALL_JOINTS);
    const vt_model *m = f.m;
    vt_data *d = f.d;
    const int nv = m->nv, nx = m->nx;
    double *Q0 = malloc((size_t)nv * sizeof(double)), *Q = malloc((size_t)nv * sizeof(double));
    double *F = calloc((size_t)nx, sizeof(double)), *Qd = malloc((size_t)nv * sizeof(double));
    at(&f, f.q, f.v);
    assert_ok(vt_mass_matrix(m, d));
    assert_ok(vt_forces(m, d));
    memcpy(Q0, d->Q, (size_t)nv * sizeof(double));
    uint64_t s = 4;
    double expect = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        double sp[3], fo[3], n[3], sg[3], vp[3];
        const double *A = d->A + 9 * i, *v = d->xd + 7 * (i - 1), *w = d->omega + 3 * i;
        for (int k = 0; k < 3; k++) {
            sp[k] = vt_rand_uniform(&s, -1, 1);
            fo[k] = vt_rand_uniform(&s, -10, 10);
            n[k] = vt_rand_uniform(&s, -10, 10);
        }
        assert_ok(vt_add_point_load(m, d, i, sp, fo, n));
        for (int k = 0; k < 3; k++) sg[k] = A[k] * sp[0] + A[k + 3] * sp[1] + A[k + 6] * sp[2];
        vp[0] = v[0] + w[1] * sg[2] - w[2] * sg[1];
        vp[1] = v[1] + w[2] * sg[0] - w[0] * sg[2];
        vp[2] = v[2] + w[0] * sg[1] - w[1] * sg[0];
        expect += fo[0] * vp[0] + fo[1] * vp[1] + fo[2] * vp[2] + n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
        /* the same load through (7) directly */
        vt_cartesian_force(F + 7 * (i - 1), d->x + 7 * (i - 1) + 3, sg, fo, n);
    }
    assert_ok(vt_forces(m, d));
    double pw = 0.0, pw7 = 0.0, pwx = 0.0;
    assert_ok(vt_generalized_force(Qd, m, d, F));
    for (int c = 0; c < nv; c++) {
        Q[c] = d->Q[c] - Q0[c];
        pw += Q[c] * f.v[c];
        pw7 += Qd[c] * f.v[c];
        assert_near(Q[c], Qd[c], 1e-10 * (1 + fabs(Qd[c])));
    }
    for (int r = 0; r < nx; r++) pwx += F[r] * d->xd[r];
    assert_near(pw, expect, 1e-10 * (1 + fabs(expect)));
    assert_near(pw7, expect, 1e-10 * (1 + fabs(expect)));
    assert_near(pwx, expect, 1e-10 * (1 + fabs(expect)));
    /* (10) against the dense product S^T F */
    for (int c = 0; c < nv; c++) {
        double sum = 0.0;
        for (int r = 0; r < nx; r++) sum += d->S[r + (size_t)c * (size_t)nx] * F[r];
        assert_near(Qd[c], sum, 1e-12 * (1 + fabs(sum)));
    }
    free(Q0); free(Q); free(F); free(Qd);
    teardown(&f);
}

static void test_bad_input(void **state)
{
    (void)state;
    fixture f;
    setup(&f, 2, 6, VT_SCENE_ALL_JOINTS);
    at(&f, f.q, f.v);
    f.d->xfrc[6 * 2 + 1] = NAN;
    assert_int_equal(vt_forces(f.m, f.d), VT_ERR_NONFINITE);
    double *Q = malloc((size_t)f.m->nv * sizeof(double));
    assert_int_equal(vt_generalized_force(Q, f.m, f.d, NULL), VT_ERR_NULL);
    free(Q);
    teardown(&f);
}

/* Finite loads whose generalized force overflows: 1.5e308 N across each link of the double
 * link (2 m links about z, along x at q = 0) is a moment of 1.5e308 × (1 + 3) N·m about joint 1. vt_forces refuses it (VT_ERR_NONFINITE, with a message) instead of
 * returning VT_OK with Inf in Q. */
static void test_overflowing_loads(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 0));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    for (int i = 1; i <= m->nbody; i++) d->xfrc[6 * i + 1] = 1.5e308;
    assert_int_equal(vt_forces(m, d), VT_ERR_NONFINITE);
    assert_true(strlen(d->message) > 0);
    vt_data_free(d);
    vt_model_free(m);
}

/* vt_generalized_force with a finite F whose S^T F overflows (1.5e308 N across both links of the
 * double link: 1.5e308 × (1 + 3) N·m about joint 1): VT_ERR_NONFINITE, Q left as it was. */
static void test_generalized_force_overflow(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 0));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_kinematics(m, d));
    double F[14] = {0}, Q[2] = {42.0, 43.0};
    F[1] = F[7 + 1] = 1.5e308;
    assert_int_equal(vt_generalized_force(Q, m, d, F), VT_ERR_NONFINITE);
    assert_true(strlen(d->message) > 0);
    assert_true(Q[0] == 42.0 && Q[1] == 43.0);
    vt_data_free(d);
    vt_model_free(m);
}

/* vt_cartesian_force: a NULL argument (the moment n = NULL was dereferenced) is VT_ERR_NULL, a
 * NaN or a result that overflows VT_ERR_NONFINITE, and F is untouched; a good call gives (7)
 * written out by hand: a force f = (0, 3, 0) at s = (2, 0, 0) on a body turned 90° about z
 * (p = (c, 0, 0, c), c = √½) has the moment s × f = (0, 0, 6), and 2 E^T (0, 0, 6) = 12 (−p3,
 * −p2, p1, p0) = 12 c (−1, 0, 0, 1). */
static void test_cartesian_force_contract(void **state)
{
    (void)state;
    const double c = sqrt(0.5), p[4] = {c, 0, 0, c}, s[3] = {2, 0, 0}, f[3] = {0, 3, 0}, n[3] = {0, 0, 0};
    const double nan3[3] = {0, NAN, 0}, big[3] = {0, 1e300, 0}, far[3] = {1e300, 0, 0};
    double F[7], before[7];
    for (int k = 0; k < 7; k++) F[k] = before[k] = 42.0 + k;
    assert_int_equal(vt_cartesian_force(NULL, p, s, f, n), VT_ERR_NULL);
    assert_int_equal(vt_cartesian_force(F, NULL, s, f, n), VT_ERR_NULL);
    assert_int_equal(vt_cartesian_force(F, p, NULL, f, n), VT_ERR_NULL);
    assert_int_equal(vt_cartesian_force(F, p, s, NULL, n), VT_ERR_NULL);
    assert_int_equal(vt_cartesian_force(F, p, s, f, NULL), VT_ERR_NULL);
    assert_int_equal(vt_cartesian_force(F, p, s, nan3, n), VT_ERR_NONFINITE);
    assert_int_equal(vt_cartesian_force(F, p, far, big, n), VT_ERR_NONFINITE); /* moment 1e600 */
    assert_memory_equal(F, before, sizeof F);
    assert_ok(vt_cartesian_force(F, p, s, f, n));
    const double want[7] = {0, 3, 0, -12 * c, 0, 0, 12 * c};
    for (int k = 0; k < 7; k++) assert_near(F[k], want[k], 1e-14);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gravity_is_minus_dV_dq),
        cmocka_unit_test(test_lagrangian),
        cmocka_unit_test(test_newton_euler),
        cmocka_unit_test(test_power_balance),
        cmocka_unit_test(test_load_virtual_power),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_overflowing_loads),
        cmocka_unit_test(test_generalized_force_overflow),
        cmocka_unit_test(test_cartesian_force_contract),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
