/* src/kinematics/kinematics.c: S against central finite differences of x(q), Ṡq̇ against finite
 * differences of S along q̇, ẋ from the recursion (15)-(16) against S q̇, and the joints'
 * geometric closure — on random trees that use every joint kind. */
#include <stdio.h>

#include "vt_test.h"

typedef struct {
    vt_model *m;
    vt_data *d;
    double *q, *v, *qa, *qb, *xa, *xb, *Sa, *Sb, *y;
} fixture;

static void setup(fixture *f, uint64_t seed, int n, unsigned kinds)
{
    assert_ok(vt_scene_random_tree(&f->m, seed, n, kinds));
    assert_ok(vt_data_create(&f->d, f->m));
    const size_t nq = (size_t)f->m->nq, nv = (size_t)f->m->nv, nx = (size_t)f->m->nx;
    f->q = malloc(nq * sizeof(double));  f->v = malloc(nv * sizeof(double));
    f->qa = malloc(nq * sizeof(double)); f->qb = malloc(nq * sizeof(double));
    f->xa = malloc(nx * sizeof(double)); f->xb = malloc(nx * sizeof(double));
    f->Sa = malloc(nx * nv * sizeof(double)); f->Sb = malloc(nx * nv * sizeof(double));
    f->y = malloc(nx * sizeof(double));
    uint64_t s = seed * 77 + 1;
    vt_scene_random_state(f->m, f->d, &s);
    memcpy(f->q, f->d->q, nq * sizeof(double));
    memcpy(f->v, f->d->qd, nv * sizeof(double));
}

static void teardown(fixture *f)
{
    free(f->q); free(f->v); free(f->qa); free(f->qb); free(f->xa); free(f->xb);
    free(f->Sa); free(f->Sb); free(f->y);
    vt_data_free(f->d);
    vt_model_free(f->m);
}

/* x and S at q */
static void eval(fixture *f, const double *q, double *x, double *S)
{
    memcpy(f->d->q, q, (size_t)f->m->nq * sizeof(double));
    assert_ok(vt_kinematics(f->m, f->d));
    if (x) memcpy(x, f->d->x, (size_t)f->m->nx * sizeof(double));
    if (S) memcpy(S, f->d->S, (size_t)f->m->nx * (size_t)f->m->nv * sizeof(double));
}

static int is_base_p(const vt_model *m, int c)
{
    const int b = m->dof_body[c];
    return m->body_joint[b] == VT_JOINT_BASE && c - m->body_vadr[b] >= 3;
}

/* (x(q ⊕ h v) − x(q ⊕ −h v)) / 2h against S v */
static void check_S_along(fixture *f, const double *v, double tol)
{
    const vt_model *m = f->m;
    const double h = 1e-6;
    assert_ok(vt_integrate_q(f->qa, m, f->q, v, h));
    assert_ok(vt_integrate_q(f->qb, m, f->q, v, -h));
    eval(f, f->qa, f->xa, NULL);
    eval(f, f->qb, f->xb, NULL);
    eval(f, f->q, NULL, NULL);
    vt_test_S_times(f->y, m, f->d, v);
    for (int r = 0; r < m->nx; r++) assert_near((f->xa[r] - f->xb[r]) / (2 * h), f->y[r], tol);
}

static void run_S_fd(uint64_t seed, int n, unsigned kinds)
{
    fixture f;
    setup(&f, seed, n, kinds);
    const vt_model *m = f.m;
    double *e = calloc((size_t)m->nv, sizeof(double));
    /* column by column, except a base body's ṗ columns, whose normal part is not a motion */
    for (int c = 0; c < m->nv; c++) {
        if (is_base_p(m, c)) continue;
        e[c] = 1.0;
        check_S_along(&f, e, 1e-7);
        e[c] = 0.0;
    }
    /* along the random state's rates (base ṗ tangent to the unit sphere) */
    check_S_along(&f, f.v, 1e-7);
    free(e);
    teardown(&f);
}

static void test_S_finite_differences(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) run_S_fd(seed, 12, VT_SCENE_ALL_JOINTS);
    for (uint64_t seed = 5; seed <= 7; seed++) run_S_fd(seed, 10, VT_SCENE_NO_BASE);
    /* free joints on any reference body (every sixth body) */
    for (uint64_t seed = 8; seed <= 11; seed++) run_S_fd(seed, 14, VT_SCENE_WITH_FREE);
}

static void test_Sdot_qdot_finite_differences(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 9; seed++) {
        fixture f;
        setup(&f, seed, 12, seed > 6 ? VT_SCENE_WITH_FREE : seed % 2 ? VT_SCENE_ALL_JOINTS : VT_SCENE_NO_BASE);
        const vt_model *m = f.m;
        const double h = 1e-6;
        assert_ok(vt_integrate_q(f.qa, m, f.q, f.v, h));
        assert_ok(vt_integrate_q(f.qb, m, f.q, f.v, -h));
        eval(&f, f.qa, NULL, f.Sa);
        eval(&f, f.qb, NULL, f.Sb);
        eval(&f, f.q, NULL, NULL);
        for (int r = 0; r < m->nx; r++) {
            double s = 0.0;
            for (int c = 0; c < m->nv; c++) {
                const size_t k = (size_t)r + (size_t)c * (size_t)m->nx;
                s += (f.Sa[k] - f.Sb[k]) / (2 * h) * f.v[c];
            }
            assert_near(f.d->Sdqd[r], s, 1e-6 * (1.0 + fabs(s)));
        }
        teardown(&f);
    }
}

static void test_velocities_equal_S_qdot(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 9; seed++) {
        fixture f;
        setup(&f, seed, 15, seed > 6 ? VT_SCENE_WITH_FREE : VT_SCENE_ALL_JOINTS);
        const vt_model *m = f.m;
        eval(&f, f.q, NULL, NULL);
        vt_test_S_times(f.y, m, f.d, f.v);
        for (int r = 0; r < m->nx; r++) assert_near(f.d->xd[r], f.y[r], 1e-12 * (1 + fabs(f.y[r])));
        for (int i = 1; i <= m->nbody; i++) {
            /* ω = 2 E ṗ */
            double E[12], w[3] = {0};
            vt_euler_E(E, f.d->x + 7 * (i - 1) + 3);
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 4; k++) w[r] += 2 * E[r + 3 * k] * f.d->xd[7 * (i - 1) + 3 + k];
            for (int r = 0; r < 3; r++) assert_near(f.d->omega[3 * i + r], w[r], 1e-12);
        }
        teardown(&f);
    }
}

/* every joint holds: the joint point on the body equals the joint point on the reference
 * plus the joint's translation along its axis; translations and the revolute axis are
 * the same line seen from either body */
static void joint_closure(unsigned kinds)
{
    fixture f;
    setup(&f, 3, 18, kinds);
    const vt_model *m = f.m;
    vt_data *d = f.d;
    eval(&f, f.q, NULL, NULL);
    for (int i = 1; i <= m->nbody; i++) {
        const int j = m->body_parent[i], jt = m->body_joint[i];
        if (jt == VT_JOINT_BASE) continue;
        const double *ri = d->x + 7 * (i - 1), *Ai = d->A + 9 * i, *Aj = d->A + 9 * j;
        const double *rj = j ? d->x + 7 * (j - 1) : NULL;
        const double *sc = m->body_jchild + 3 * i, *sp = m->body_jpar + 3 * i;
        const double *q = d->q + m->body_qadr[i];
        double Pi[3], Pj[3];
        for (int r = 0; r < 3; r++) {
            Pi[r] = ri[r] + Ai[r] * sc[0] + Ai[r + 3] * sc[1] + Ai[r + 6] * sc[2];
            Pj[r] = (rj ? rj[r] : 0.0) + Aj[r] * sp[0] + Aj[r + 3] * sp[1] + Aj[r + 6] * sp[2];
        }
        if (jt == VT_JOINT_FREE) { /* P_i = P_j + A^j t', and A^i = A^j A(p_J) A0 */
            double Aq[9], A0[9];
            vt_euler_A(Aq, q + 3);
            vt_euler_A(A0, m->body_quat0 + 4 * i);
            for (int r = 0; r < 3; r++) {
                assert_near(Pi[r], Pj[r] + Aj[r] * q[0] + Aj[r + 3] * q[1] + Aj[r + 6] * q[2], 1e-12);
                for (int c = 0; c < 3; c++) {
                    double a = 0.0;
                    for (int k = 0; k < 3; k++)
                        for (int l = 0; l < 3; l++) a += Aj[r + 3 * k] * Aq[k + 3 * l] * A0[l + 3 * c];
                    assert_near(Ai[r + 3 * c], a, 1e-12);
                }
            }
            continue;
        }
        double t = 0.0;
        if (jt == VT_JOINT_TRANSLATIONAL) t = q[0];
        if (jt == VT_JOINT_CYLINDRICAL) t = q[1];
        const double *ax = m->body_axis + 6 * i;
        for (int r = 0; r < 3; r++) {
            const double e = Aj[r] * ax[0] + Aj[r + 3] * ax[1] + Aj[r + 6] * ax[2];
            assert_near(Pi[r], Pj[r] + t * e, 1e-12);
        }
        if (jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_CYLINDRICAL || jt == VT_JOINT_TRANSLATIONAL) {
            /* axis fixed in both bodies: A^{iT} e is the same at every q: A0^T axis */
            double e[3], ei[3], p0[9];
            for (int r = 0; r < 3; r++) e[r] = Aj[r] * ax[0] + Aj[r + 3] * ax[1] + Aj[r + 6] * ax[2];
            for (int r = 0; r < 3; r++) ei[r] = Ai[3 * r] * e[0] + Ai[3 * r + 1] * e[1] + Ai[3 * r + 2] * e[2];
            vt_euler_A(p0, m->body_quat0 + 4 * i);
            for (int r = 0; r < 3; r++)
                assert_near(ei[r], p0[3 * r] * ax[0] + p0[3 * r + 1] * ax[1] + p0[3 * r + 2] * ax[2], 1e-12);
        }
    }
    teardown(&f);
}

static void test_joint_closure(void **state)
{
    (void)state;
    joint_closure(VT_SCENE_ALL_JOINTS);
    joint_closure(VT_SCENE_WITH_FREE);
}

static void test_sparsity_follows_paths(void **state)
{
    (void)state;
    fixture f;
    setup(&f, 4, 14, VT_SCENE_ALL_JOINTS);
    const vt_model *m = f.m;
    eval(&f, f.q, NULL, NULL);
    for (int i = 1; i <= m->nbody; i++)
        for (int c = 0; c < m->nv; c++) {
            int on_path = 0;
            for (int b = i; b; b = m->body_parent[b]) on_path |= b == m->dof_body[c];
            if (on_path) continue;
            for (int r = 0; r < 7; r++) assert_near(f.d->S[7 * (i - 1) + r + (size_t)c * (size_t)m->nx], 0.0, 0.0);
        }
    teardown(&f);
}

static void test_bad_state(void **state)
{
    (void)state;
    fixture f;
    setup(&f, 2, 8, VT_SCENE_ALL_JOINTS);
    const vt_model *m = f.m;
    f.d->q[m->nq - 1] = NAN;
    assert_int_equal(vt_kinematics(m, f.d), VT_ERR_NONFINITE);
    assert_non_null(strstr(f.d->message, "q["));
    memcpy(f.d->q, f.q, (size_t)m->nq * sizeof(double));
    f.d->qd[0] = INFINITY;
    assert_int_equal(vt_kinematics(m, f.d), VT_ERR_NONFINITE);
    memcpy(f.d->qd, f.v, (size_t)m->nv * sizeof(double));
    for (int i = 1; i <= m->nbody; i++)
        if (m->body_joint[i] == VT_JOINT_SPHERICAL) memset(f.d->q + m->body_qadr[i], 0, 4 * sizeof(double));
    assert_int_equal(vt_kinematics(m, f.d), VT_ERR_QUATERNION);
    teardown(&f);
}

/* Euler parameters of spherical joints are normalized by scaling (their length ×1e200 or ×1e-11
 * gives the pose of the unit ones: the sum of squares would overflow to Inf); a state's Euler
 * parameters should be unit, so below 1e-12 they count as zero (VT_ERR_QUATERNION);
 * a state whose outputs overflow (a base body's Euler parameters ×1e200, which enter A(p)
 * squared; rates of 1e300 rad/s, whose ω² overflows in Ṡq̇) is refused with VT_ERR_NONFINITE
 * naming the body, by vt_kinematics and by the recursive evaluation's own kinematics. */
static void test_extreme_states(void **state)
{
    (void)state;
    fixture f;
    uint64_t seed = 1;
    for (;; seed++) { /* a tree with a spherical joint and a base body */
        setup(&f, seed, 8, VT_SCENE_ALL_JOINTS);
        int sph = 0, base = 0;
        for (int i = 1; i <= f.m->nbody; i++) {
            sph += f.m->body_joint[i] == VT_JOINT_SPHERICAL;
            base += f.m->body_joint[i] == VT_JOINT_BASE;
        }
        if (sph && base) break;
        teardown(&f);
    }
    const vt_model *m = f.m;
    const size_t nx = (size_t)m->nx;
    double *x0 = malloc(nx * sizeof(double));
    eval(&f, f.q, x0, NULL);
    const double scale[3] = {1e200, 1e-11, 1e-200};
    for (int s = 0; s < 3; s++) {
        memcpy(f.d->q, f.q, (size_t)m->nq * sizeof(double));
        for (int i = 1; i <= m->nbody; i++)
            if (m->body_joint[i] == VT_JOINT_SPHERICAL)
                for (int k = 0; k < 4; k++) f.d->q[m->body_qadr[i] + k] *= scale[s];
        if (s == 2) {
            assert_int_equal(vt_kinematics(m, f.d), VT_ERR_QUATERNION);
            continue;
        }
        assert_ok(vt_kinematics(m, f.d));
        for (size_t r = 0; r < nx; r++) assert_near(f.d->x[r], x0[r], 1e-14 * (1 + fabs(x0[r])));
    }
    int base = 0;
    for (int i = 1; i <= m->nbody && !base; i++)
        if (m->body_joint[i] == VT_JOINT_BASE) base = i;
    char want[32];
    snprintf(want, sizeof want, "body %d", base);
    memcpy(f.d->q, f.q, (size_t)m->nq * sizeof(double));
    for (int k = 3; k < 7; k++) f.d->q[m->body_qadr[base] + k] *= 1e200;
    assert_int_equal(vt_kinematics(m, f.d), VT_ERR_NONFINITE);
    assert_non_null(strstr(f.d->message, want));
    assert_int_equal(vt_inverse_dynamics_recursive(m, f.d), VT_ERR_NONFINITE);
    assert_non_null(strstr(f.d->message, want));
    memcpy(f.d->q, f.q, (size_t)m->nq * sizeof(double));
    for (int k = 0; k < m->nv; k++) f.d->qd[k] = 1e300;
    assert_int_equal(vt_kinematics(m, f.d), VT_ERR_NONFINITE);
    assert_true(strlen(f.d->message) > 0);
    assert_int_equal(vt_inverse_dynamics_recursive(m, f.d), VT_ERR_NONFINITE);
    assert_true(strlen(f.d->message) > 0);
    free(x0);
    teardown(&f);
}

/* Far from the global origin (every root's joint point on the ground, and free and base roots'
 * positions, moved by 1e6 m): the twists are about d->origin, body 1's joint point; d->xrel is
 * x − origin and jpoint − origin to the rounding of the absolute positions (ulp(1e6) = 1.2e-10 m);
 * and ẋ from the recursion (15)-(16) still equals S q̇ from the twists to 1e-12, which about the
 * global origin lose ulp(1e6)·|ω| to cancellation. */
static void test_far_from_origin(void **state)
{
    (void)state;
    const double D[3] = {0.48e6, -0.6e6, 0.64e6};
    for (uint64_t seed = 1; seed <= 9; seed++) {
        fixture f;
        setup(&f, seed, 15, seed > 6 ? VT_SCENE_WITH_FREE : VT_SCENE_ALL_JOINTS);
        vt_model *m = f.m;
        for (int i = 1; i <= m->nbody; i++) {
            if (m->body_parent[i] != 0) continue;
            const int jt = m->body_joint[i];
            double *p = jt == VT_JOINT_FREE || jt == VT_JOINT_BASE ? f.q + m->body_qadr[i] : m->body_jpar + 3 * i;
            for (int k = 0; k < 3; k++) p[k] += D[k];
        }
        eval(&f, f.q, NULL, NULL);
        const vt_data *d = f.d;
        for (int k = 0; k < 3; k++) assert_near(d->origin[k], d->jpoint[3 + k], 0.0);
        for (int i = 1; i <= m->nbody; i++)
            for (int k = 0; k < 3; k++) {
                assert_near(d->xrel[6 * i + k], d->x[7 * (i - 1) + k] - d->origin[k], 3e-10);
                assert_near(d->xrel[6 * i + 3 + k], d->jpoint[3 * i + k] - d->origin[k], 3e-10);
            }
        vt_test_S_times(f.y, m, f.d, f.v);
        for (int r = 0; r < m->nx; r++) assert_near(d->xd[r], f.y[r], 1e-12 * (1 + fabs(f.y[r])));
        teardown(&f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_S_finite_differences),
        cmocka_unit_test(test_Sdot_qdot_finite_differences),
        cmocka_unit_test(test_velocities_equal_S_qdot),
        cmocka_unit_test(test_joint_closure),
        cmocka_unit_test(test_sparsity_follows_paths),
        cmocka_unit_test(test_bad_state),
        cmocka_unit_test(test_extreme_states),
        cmocka_unit_test(test_far_from_origin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
