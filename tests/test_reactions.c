/* src/dense/reactions.c: efforts (24) and reactions (25)-(28) against the paper's exact double-link
 * solution (29), a planar Newton–Euler solution of a four-bar, the power balance of every
 * effort, Newton–Euler balance of every body, and the reaction's orthogonality to a joint's
 * free directions; relative orientation drives against the same motion given to
 * vt_inverse_dynamics_motion and against a revolute's joint drive. */
#include <float.h>

#include "vt_test.h"

/* ---- the paper's double link, joint 2 locked --------------------------------------- */

static void test_double_link_exact(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    for (double th = 0.0; th <= 1.5; th += 0.125) {
        const double s = sin(th), c = cos(th);
        d->q[0] = -th;
        d->q[1] = 0.0;
        d->qd[0] = -sqrt(7.3575 * s); /* θ̇² = 7.3575 sin θ */
        d->qd[1] = 0.0;
        assert_ok(vt_inverse_dynamics(m, d));
        /* θ̈ = 3.67875 cos θ, θ = −q1 */
        assert_near(-d->qdd[0], 3.67875 * c, 1e-10 * 3.67875);
        assert_near(d->qdd[1], 0.0, 1e-10 * 3.67875);
        /* (29): the ground on link 1 at joint 1 */
        assert_near(d->jnt_force[3 + 0], -2207.25 * sin(2 * th), 1e-10 * 4905.0);
        assert_near(d->jnt_force[3 + 1], 4905.0 * s * s + 490.5 * c * c, 1e-10 * 4905.0);
        assert_near(d->jnt_force[3 + 2], 0.0, 1e-10 * 4905.0);
        /* link 1 on link 2 at joint 2 */
        assert_near(d->jnt_force[6 + 0], -1655.4375 * sin(2 * th), 1e-10 * 3188.25);
        assert_near(d->jnt_force[6 + 1], 3188.25 * s * s - 122.625 * c * c, 1e-10 * 3188.25);
        /* the locking torque, 245.25 |cos θ| (about −z here) */
        assert_near(fabs(d->drive_effort[0]), 245.25 * c, 1e-10 * 245.25);
        assert_near(d->drive_moment[2], d->drive_effort[0], 1e-12 * 245.25);
        /* revolute reactions carry no moment about their axis; in the plane none at all */
        for (int i = 1; i <= 2; i++)
            for (int k = 0; k < 3; k++) assert_near(d->jnt_moment[3 * i + k], 0.0, 1e-10 * 245.25);
        /* body-axes components (27): link 1 lies along −θ */
        assert_near(d->jnt_force_body[3 + 0], c * d->jnt_force[3] - s * d->jnt_force[4], 1e-9);
        assert_near(d->jnt_force_body[3 + 1], s * d->jnt_force[3] + c * d->jnt_force[4], 1e-9);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* ---- a model with every joint kind, drives of every kind and cut joints --------------- */

/* Random tree, some joints driven, a point and an orientation drive on base body 1; with cuts, a spherical
 * and a cylindrical cut joint on body 7 (a free base body, so no row depends on the others),
 * placed so that they hold at the random state the data is left in. */
static vt_model *build_mixed(uint64_t seed, int n, int with_cuts, vt_data **data)
{
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, seed, n, VT_SCENE_ALL_JOINTS));
    vt_data *pd_;
    assert_ok(vt_data_create(&pd_, probe));
    uint64_t st = seed * 3;
    vt_scene_random_state(probe, pd_, &st);
    assert_ok(vt_kinematics(probe, pd_));
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, seed, n, VT_SCENE_ALL_JOINTS));
    uint64_t s = seed + 7;
    for (int i = 2; i <= n; i += 2) { /* drive some joints, leave others free */
        const int jt = probe->body_joint[i];
        if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_BASE) continue;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = i;
        dr.f = vt_function_sine(0.1, 0.4, 2.0 + i, 0.0);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    vt_drive_def pd = vt_default_drive_def();
    pd.type = VT_DRIVE_POINT;
    pd.body = 1; /* the base body, whose orientation alone is driven */
    pd.index = 1;
    pd.point[0] = 0.3;
    pd.f = vt_function_sine(0.0, 0.2, 3.0, 0.0);
    assert_true(vt_builder_add_drive(b, &pd) >= 0);
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    od.body = 1; /* the base body */
    od.f = vt_function_sine(0.0, 0.5, 1.0, 0.0);
    assert_true(vt_builder_add_drive(b, &od) >= 0);
    if (with_cuts) {
        assert_int_equal(probe->body_joint[7], VT_JOINT_BASE);
        const int a = n - 1;
        const double *r7 = pd_->x + 7 * 6, *A7 = pd_->A + 9 * 7, *ra = pd_->x + 7 * (a - 1), *Aa = pd_->A + 9 * a;
        vt_cut_joint_def cj = vt_default_cut_joint_def();
        cj.joint = VT_JOINT_SPHERICAL;
        cj.body_a = a;
        cj.body_b = 7;
        double P[3], rel[3];
        for (int k = 0; k < 3; k++) cj.point_b[k] = vt_rand_uniform(&s, -0.3, 0.3);
        for (int k = 0; k < 3; k++) P[k] = r7[k] + A7[k] * cj.point_b[0] + A7[k + 3] * cj.point_b[1] + A7[k + 6] * cj.point_b[2];
        for (int k = 0; k < 3; k++) rel[k] = P[k] - ra[k];
        for (int k = 0; k < 3; k++) cj.point_a[k] = Aa[3 * k] * rel[0] + Aa[3 * k + 1] * rel[1] + Aa[3 * k + 2] * rel[2];
        assert_true(vt_builder_add_cut_joint(b, &cj) >= 0);
        /* cylindrical to the ground: along a random line through another point of body 7 */
        cj.joint = VT_JOINT_CYLINDRICAL;
        cj.body_a = 0;
        for (int k = 0; k < 3; k++) cj.point_b[k] = vt_rand_uniform(&s, -0.3, 0.3);
        for (int k = 0; k < 3; k++) cj.point_a[k] = r7[k] + A7[k] * cj.point_b[0] + A7[k + 3] * cj.point_b[1] + A7[k + 6] * cj.point_b[2];
        vt_rand_unit(cj.axis1, 3, &s);
        memcpy(cj.orientation, r7 + 3, 4 * sizeof(double)); /* b's axes relative to the ground's */
        assert_true(vt_builder_add_cut_joint(b, &cj) >= 0);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(data, m));
    memcpy((*data)->q, pd_->q, (size_t)m->nq * sizeof(double));
    memcpy((*data)->qd, pd_->qd, (size_t)m->nv * sizeof(double));
    (*data)->time = 0.3;
    vt_data_free(pd_);
    vt_model_free(probe);
    if (with_cuts) { /* the cut joints hold at this state */
        assert_ok(vt_kinematics(m, *data));
        assert_ok(vt_constraints(m, *data));
        for (int r = m->cut_row[0]; r < m->nc - 2; r++) assert_near((*data)->Phi[r], 0.0, 1e-12);
    }
    return m;
}

static void point_velocity(double v[3], const vt_data *d, int body, const double P[3])
{
    if (body == 0) {
        v[0] = v[1] = v[2] = 0.0;
        return;
    }
    const double *r = d->x + 7 * (body - 1), *w = d->omega + 3 * body, *rd = d->xd + 7 * (body - 1);
    const double s[3] = {P[0] - r[0], P[1] - r[1], P[2] - r[2]};
    v[0] = rd[0] + w[1] * s[2] - w[2] * s[1];
    v[1] = rd[1] + w[2] * s[0] - w[0] * s[2];
    v[2] = rd[2] + w[0] * s[1] - w[1] * s[0];
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* power of a wrench (f, n at P) on body b, reacted by body a at the same point */
static double wrench_power(const vt_data *d, int a, int b, const double P[3], const double f[3], const double n[3])
{
    double va[3], vb[3];
    const double zero[3] = {0, 0, 0};
    point_velocity(va, d, a, P);
    point_velocity(vb, d, b, P);
    const double *wa = a ? d->omega + 3 * a : zero, *wb = d->omega + 3 * b;
    return f[0] * (vb[0] - va[0]) + f[1] * (vb[1] - va[1]) + f[2] * (vb[2] - va[2]) +
           n[0] * (wb[0] - wa[0]) + n[1] * (wb[1] - wa[1]) + n[2] * (wb[2] - wa[2]);
}

static double energy(const vt_model *m, vt_data *d)
{
    assert_ok(vt_kinematics(m, d));
    return vt_test_kinetic_energy(m, d) + vt_test_potential_energy(m, d);
}

/* Σ (power of every effort and cut-joint force) = d(T + V)/dt along (q̇, q̈) */
static void test_power_balance(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) {
        vt_data *d;
        vt_model *m = build_mixed(seed, 12, seed % 2, &d);
        assert_ok(vt_inverse_dynamics(m, d));
        double P = 0.0;
        for (int k = 0; k < m->ndrive; k++) {
            const vt_drive_def *dr = &m->drive[k];
            const int b = dr->body, a = dr->type == VT_DRIVE_JOINT ? m->body_parent[b] : 0;
            double Pt[3];
            if (dr->type == VT_DRIVE_JOINT) {
                memcpy(Pt, d->jpoint + 3 * b, sizeof Pt);
                /* the effort along its coordinate does the same power: τ q̇ */
                const double pw = wrench_power(d, a, b, Pt, d->drive_force + 3 * k, d->drive_moment + 3 * k);
                assert_near(pw, d->drive_effort[k] * d->qd[m->body_vadr[b] + dr->index], 1e-9 * (1 + fabs(pw)));
            } else if (dr->type == VT_DRIVE_POINT) {
                const double *A = d->A + 9 * b, *r = d->x + 7 * (b - 1);
                for (int c = 0; c < 3; c++) Pt[c] = r[c] + A[c] * dr->point[0] + A[c + 3] * dr->point[1] + A[c + 6] * dr->point[2];
            } else {
                memcpy(Pt, d->x + 7 * (b - 1), sizeof Pt);
            }
            P += wrench_power(d, a, b, Pt, d->drive_force + 3 * k, d->drive_moment + 3 * k);
        }
        for (int k = 0; k < m->ncut; k++) {
            const vt_cut_joint_def *c = &m->cut[k];
            const double *A = d->A + 9 * c->body_b, *r = d->x + 7 * (c->body_b - 1);
            double Pt[3];
            for (int e = 0; e < 3; e++) Pt[e] = r[e] + A[e] * c->point_b[0] + A[e + 3] * c->point_b[1] + A[e + 6] * c->point_b[2];
            P += wrench_power(d, c->body_a, c->body_b, Pt, d->cut_force + 3 * k, d->cut_moment + 3 * k);
        }
        const int nq = m->nq, nv = m->nv;
        double *q = malloc((size_t)nq * sizeof(double)), *v = malloc((size_t)nv * sizeof(double));
        double *a = malloc((size_t)nv * sizeof(double));
        memcpy(q, d->q, (size_t)nq * sizeof(double));
        memcpy(v, d->qd, (size_t)nv * sizeof(double));
        memcpy(a, d->qdd, (size_t)nv * sizeof(double));
        const double h = 1e-5;
        double Eh[2];
        for (int sgn = 0; sgn < 2; sgn++) {
            const double t = sgn ? h : -h;
            assert_ok(vt_integrate_q(d->q, m, q, v, t));
            for (int c = 0; c < nv; c++) d->qd[c] = v[c] + t * a[c];
            Eh[sgn] = energy(m, d);
        }
        assert_near(P, (Eh[1] - Eh[0]) / (2 * h), 1e-6 * (1 + fabs(P)));
        free(q); free(v); free(a);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* every body: m a = Σ f, J α + ω̃ J ω = Σ n about its centre of mass, with gravity, the
 * drives' efforts, the cut joints' forces, its own joint's reaction and its children's */
static void test_newton_euler_every_body(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) {
        vt_data *d;
        vt_model *m = build_mixed(seed + 10, 12, 1, &d);
        assert_ok(vt_inverse_dynamics(m, d));
        const int n = m->nbody;
        double *F = calloc(6 * ((size_t)n + 1), sizeof(double));
        double fmax = 0.0;
        /* add a wrench (f, n at P) to body b about its centre of mass */
#define ADD(b, P, f, nn, sgn)                                                                           \
    do {                                                                                                \
        if ((b) > 0) {                                                                                  \
            const double *r_ = d->x + 7 * ((b) - 1);                                                    \
            const double s_[3] = {(P)[0] - r_[0], (P)[1] - r_[1], (P)[2] - r_[2]};                      \
            double *w_ = F + 6 * (b);                                                                   \
            for (int c_ = 0; c_ < 3; c_++) w_[c_] += (sgn) * (f)[c_];                                   \
            w_[3] += (sgn) * ((nn)[0] + s_[1] * (f)[2] - s_[2] * (f)[1]);                               \
            w_[4] += (sgn) * ((nn)[1] + s_[2] * (f)[0] - s_[0] * (f)[2]);                               \
            w_[5] += (sgn) * ((nn)[2] + s_[0] * (f)[1] - s_[1] * (f)[0]);                               \
            fmax = fmax > fabs((f)[0]) + fabs((f)[1]) + fabs((f)[2]) ? fmax : fabs((f)[0]) + fabs((f)[1]) + fabs((f)[2]); \
        }                                                                                               \
    } while (0)
        for (int i = 1; i <= n; i++) {
            const double g[3] = {m->body_mass[i] * m->gravity[0], m->body_mass[i] * m->gravity[1], m->body_mass[i] * m->gravity[2]};
            const double zero[3] = {0, 0, 0};
            ADD(i, d->x + 7 * (i - 1), g, zero, 1.0);
            ADD(i, d->jpoint + 3 * i, d->jnt_force + 3 * i, d->jnt_moment + 3 * i, 1.0);
            ADD(m->body_parent[i], d->jpoint + 3 * i, d->jnt_force + 3 * i, d->jnt_moment + 3 * i, -1.0);
        }
        for (int k = 0; k < m->ndrive; k++) {
            const vt_drive_def *dr = &m->drive[k];
            double Pt[3];
            const int b = dr->body;
            if (dr->type == VT_DRIVE_JOINT) memcpy(Pt, d->jpoint + 3 * b, sizeof Pt);
            else if (dr->type == VT_DRIVE_POINT) {
                const double *A = d->A + 9 * b, *r = d->x + 7 * (b - 1);
                for (int c = 0; c < 3; c++) Pt[c] = r[c] + A[c] * dr->point[0] + A[c + 3] * dr->point[1] + A[c + 6] * dr->point[2];
            } else memcpy(Pt, d->x + 7 * (b - 1), sizeof Pt);
            ADD(b, Pt, d->drive_force + 3 * k, d->drive_moment + 3 * k, 1.0);
            if (dr->type == VT_DRIVE_JOINT) ADD(m->body_parent[b], Pt, d->drive_force + 3 * k, d->drive_moment + 3 * k, -1.0);
        }
        for (int k = 0; k < m->ncut; k++) {
            const vt_cut_joint_def *c = &m->cut[k];
            const double *A = d->A + 9 * c->body_b, *r = d->x + 7 * (c->body_b - 1);
            double Pt[3];
            for (int e = 0; e < 3; e++) Pt[e] = r[e] + A[e] * c->point_b[0] + A[e + 3] * c->point_b[1] + A[e + 6] * c->point_b[2];
            ADD(c->body_b, Pt, d->cut_force + 3 * k, d->cut_moment + 3 * k, 1.0);
            ADD(c->body_a, Pt, d->cut_force + 3 * k, d->cut_moment + 3 * k, -1.0);
        }
#undef ADD
        /* inertia side, from ẍ = S q̈ + Ṡ q̇ (dense) and α = 2 E p̈ */
        for (int i = 1; i <= n; i++) {
            const int o = 7 * (i - 1);
            double xdd[7] = {0}, E[12], al[3] = {0}, J[9], Jw[3], Ja[3];
            for (int r = 0; r < 7; r++) {
                xdd[r] = d->Sdqd[o + r];
                for (int c = 0; c < m->nv; c++) xdd[r] += d->S[o + r + (size_t)c * (size_t)m->nx] * d->qdd[c];
                /* the reported ẍ (from the rates' twists) is this dense product */
                assert_near(d->xdd[o + r], xdd[r], 1e-12 * (1.0 + fabs(xdd[r]) + vt_test_maxabs(d->qdd, m->nv)));
            }
            vt_euler_E(E, d->x + o + 3);
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 4; k++) al[r] += 2 * E[r + 3 * k] * xdd[3 + k];
            const double *w = d->omega + 3 * i;
            vt_test_global_inertia(J, m, d, i);
            for (int r = 0; r < 3; r++) {
                Jw[r] = J[r] * w[0] + J[r + 3] * w[1] + J[r + 6] * w[2];
                Ja[r] = J[r] * al[0] + J[r + 3] * al[1] + J[r + 6] * al[2];
            }
            const double need[6] = {m->body_mass[i] * xdd[0], m->body_mass[i] * xdd[1], m->body_mass[i] * xdd[2],
                                    Ja[0] + w[1] * Jw[2] - w[2] * Jw[1], Ja[1] + w[2] * Jw[0] - w[0] * Jw[2],
                                    Ja[2] + w[0] * Jw[1] - w[1] * Jw[0]};
            for (int r = 0; r < 6; r++) assert_near(F[6 * i + r], need[r], 1e-10 * fmax);
        }
        free(F);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* reactions have no component along a joint's free directions (efforts are reported apart) */
static void test_reaction_orthogonality(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        vt_data *d;
        vt_model *m = build_mixed(seed + 20, 14, seed % 2, &d);
        const vt_status st = vt_inverse_dynamics(m, d);
        if (st) fail_msg("seed %d: %s", (int)seed, d->message);
        double scale = 0.0;
        for (int i = 1; i <= m->nbody; i++)
            for (int k = 0; k < 3; k++) scale = fmax(scale, fabs(d->jnt_force[3 * i + k]) + fabs(d->jnt_moment[3 * i + k]));
        const double tol = 1e-10 * scale;
        for (int i = 1; i <= m->nbody; i++) {
            const double *f = d->jnt_force + 3 * i, *n = d->jnt_moment + 3 * i, *e = d->jaxis + 9 * i;
            switch (m->body_joint[i]) {
            case VT_JOINT_REVOLUTE: assert_near(dot3(n, e), 0.0, tol); break;
            case VT_JOINT_UNIVERSAL:
                assert_near(dot3(n, e), 0.0, tol);
                assert_near(dot3(n, e + 3), 0.0, tol);
                break;
            case VT_JOINT_SPHERICAL:
                for (int k = 0; k < 3; k++) assert_near(n[k], 0.0, tol);
                break;
            case VT_JOINT_TRANSLATIONAL: assert_near(dot3(f, e), 0.0, tol); break;
            case VT_JOINT_CYLINDRICAL:
                assert_near(dot3(f, e), 0.0, tol);
                assert_near(dot3(n, e), 0.0, tol);
                break;
            default: /* base: no joint, nothing transmitted */
                for (int k = 0; k < 3; k++) {
                    assert_near(f[k], 0.0, tol);
                    assert_near(n[k], 0.0, tol);
                }
            }
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* Φ_x^T λ of a joint drive is R^T Φ_q^T λ (14); of a point drive [f; 2 E^T s̃ f] (24) */
static void test_drive_cartesian_force(void **state)
{
    (void)state;
    vt_data *d;
    vt_model *m = build_mixed(3, 10, 0, &d);
    assert_ok(vt_inverse_dynamics(m, d));
    assert_ok(vt_inverse_transform(m, d));
    double *F = malloc((size_t)m->nx * sizeof(double)), *G = malloc((size_t)m->nx * sizeof(double));
    double *Q = calloc((size_t)m->nv, sizeof(double));
    for (int k = 0; k < m->ndrive; k++) {
        const vt_drive_def *dr = &m->drive[k];
        assert_ok(vt_drive_cartesian_force(F, m, d, k));
        if (dr->type == VT_DRIVE_JOINT) {
            const int c = m->body_vadr[dr->body] + dr->index;
            Q[c] = d->drive_effort[k];
            assert_ok(vt_equivalent_force(G, m, d, Q));
            Q[c] = 0.0;
        } else if (dr->type == VT_DRIVE_POINT) {
            memset(G, 0, (size_t)m->nx * sizeof(double));
            const int b = dr->body;
            double sg[3];
            const double *A = d->A + 9 * b, zero[3] = {0, 0, 0};
            for (int c = 0; c < 3; c++) sg[c] = A[c] * dr->point[0] + A[c + 3] * dr->point[1] + A[c + 6] * dr->point[2];
            double f[3] = {0, 0, 0};
            f[dr->index] = d->drive_effort[k];
            vt_cartesian_force(G + 7 * (b - 1), d->x + 7 * (b - 1) + 3, sg, f, zero);
        } else {
            continue;
        }
        for (int r = 0; r < m->nx; r++) assert_near(F[r], G[r], 1e-10 * (1 + fabs(G[r])));
    }
    assert_int_equal(vt_drive_cartesian_force(F, m, d, m->ndrive), VT_ERR_BAD_INDEX);
    /* a multiplier near overflow and an entry of Φ_x above 1 (set in the data): Φ_x^T λ overflows
     * and the call refuses, F untouched (it returned VT_OK with Inf: the fuzzer's crash-7bc3419220…) */
    for (int k = 0; k < m->ndrive; k++) {
        if (m->drive[k].type != VT_DRIVE_POINT) continue;
        const int r0 = m->drive_row[k];
        d->lambda[r0] = DBL_MAX; /* and an Euler-parameter entry of Φ_x above 1 on either side */
        d->Phix[14 * r0 + 3] = d->Phix[14 * r0 + 7 + 3] = 4.0;
        for (int r = 0; r < m->nx; r++) F[r] = 7.0;
        assert_int_equal(vt_drive_cartesian_force(F, m, d, k), VT_ERR_NONFINITE);
        assert_non_null(strstr(d->message, "overflows"));
        for (int r = 0; r < m->nx; r++) assert_true(F[r] == 7.0);
        break;
    }
    free(F); free(G); free(Q);
    vt_data_free(d);
    vt_model_free(m);
}

/* ---- the four-bar against a planar Newton–Euler solution --------------------------------- */

typedef struct { double th[3], w[3], al[3]; } planar_motion; /* crank, coupler, rocker */

static void cross_z(double out[2], double w, const double r[2]) { out[0] = -w * r[1]; out[1] = w * r[0]; }

/* planar kinematics and 9x9 Newton–Euler: F1 ground→crank at O2, F2 crank→coupler at B,
 * F3 rocker→coupler at C, F4 ground→rocker at O4, T ground→crank */
static void planar_solution(const planar_motion *pm, double x[9], double g)
{
    const double a = VT_FB_A, b = VT_FB_B, c = VT_FB_C, dd = VT_FB_D, L[3] = {a, b, c}, mass[3] = {1, 3, 2};
    double e[3][2], B[2], C[2], G[3][2], acc[3][2];
    for (int k = 0; k < 3; k++) { e[k][0] = cos(pm->th[k]); e[k][1] = sin(pm->th[k]); }
    B[0] = a * e[0][0]; B[1] = a * e[0][1];
    C[0] = dd + c * e[2][0]; C[1] = c * e[2][1];
    for (int k = 0; k < 2; k++) {
        G[0][k] = 0.5 * a * e[0][k];
        G[1][k] = B[k] + 0.5 * b * e[1][k];
        G[2][k] = (k == 0 ? dd : 0.0) + 0.5 * c * e[2][k];
    }
    /* a point at distance l along e_k of a link turning with (w, α) about a point of acceleration a0 */
    double t[2], aB[2];
    cross_z(t, pm->al[0], e[0]);
    for (int k = 0; k < 2; k++) aB[k] = a * (t[k] - pm->w[0] * pm->w[0] * e[0][k]);
    for (int k = 0; k < 2; k++) acc[0][k] = 0.5 * aB[k];
    cross_z(t, pm->al[1], e[1]);
    for (int k = 0; k < 2; k++) acc[1][k] = aB[k] + 0.5 * b * (t[k] - pm->w[1] * pm->w[1] * e[1][k]);
    cross_z(t, pm->al[2], e[2]);
    for (int k = 0; k < 2; k++) acc[2][k] = 0.5 * c * (t[k] - pm->w[2] * pm->w[2] * e[2][k]);
    double A[81] = {0}, rhs[9];
    /* unknown order: F1x F1y F2x F2y F3x F3y F4x F4y T; equations per body: fx, fy, moment */
#define EQ(row, col, v) A[(row) + 9 * (col)] += (v)
#define MOM(row, col, r) do { EQ(row, col, -(r)[1]); EQ(row, (col) + 1, (r)[0]); } while (0)
    double r[2];
    const double O2[2] = {0, 0}, O4[2] = {dd, 0};
    /* crank: F1 − F2 + m g = m a; T + (O2−G1)×F1 − (B−G1)×F2 = I α */
    EQ(0, 0, 1); EQ(0, 2, -1); EQ(1, 1, 1); EQ(1, 3, -1);
    r[0] = O2[0] - G[0][0]; r[1] = O2[1] - G[0][1]; MOM(2, 0, r);
    r[0] = -(B[0] - G[0][0]); r[1] = -(B[1] - G[0][1]); MOM(2, 2, r);
    EQ(2, 8, 1);
    /* coupler: F2 + F3 + m g = m a; (B−G2)×F2 + (C−G2)×F3 = I α */
    EQ(3, 2, 1); EQ(3, 4, 1); EQ(4, 3, 1); EQ(4, 5, 1);
    r[0] = B[0] - G[1][0]; r[1] = B[1] - G[1][1]; MOM(5, 2, r);
    r[0] = C[0] - G[1][0]; r[1] = C[1] - G[1][1]; MOM(5, 4, r);
    /* rocker: F4 − F3 + m g = m a; (O4−G3)×F4 − (C−G3)×F3 = I α */
    EQ(6, 6, 1); EQ(6, 4, -1); EQ(7, 7, 1); EQ(7, 5, -1);
    r[0] = O4[0] - G[2][0]; r[1] = O4[1] - G[2][1]; MOM(8, 6, r);
    r[0] = -(C[0] - G[2][0]); r[1] = -(C[1] - G[2][1]); MOM(8, 4, r);
#undef MOM
#undef EQ
    for (int k = 0; k < 3; k++) {
        rhs[3 * k] = mass[k] * acc[k][0];
        rhs[3 * k + 1] = mass[k] * (acc[k][1] + g); /* F − m (0, −g) = m a */
        rhs[3 * k + 2] = mass[k] * L[k] * L[k] / 12.0 * pm->al[k];
    }
    int n = 9, one = 1, ipiv[9], info = 0;
    dgesv_(&n, &one, A, &n, ipiv, rhs, &n, &info);
    assert_int_equal(info, 0);
    memcpy(x, rhs, sizeof rhs);
}

/* planar accelerations of coupler and rocker from the crank's */
static void planar_motion_at(planar_motion *pm, double th2, double w2, double al2, const double th[2], const double w[2])
{
    const double a = VT_FB_A, b = VT_FB_B, c = VT_FB_C;
    pm->th[0] = th2; pm->th[1] = th[0]; pm->th[2] = th[1];
    pm->w[0] = w2; pm->w[1] = w[0]; pm->w[2] = w[1];
    const double s2 = sin(th2), c2 = cos(th2), s3 = sin(th[0]), c3 = cos(th[0]), s4 = sin(th[1]), c4 = cos(th[1]);
    const double A11 = -b * s3, A12 = c * s4, A21 = b * c3, A22 = -c * c4;
    const double r1 = a * al2 * s2 + a * w2 * w2 * c2 + b * w[0] * w[0] * c3 - c * w[1] * w[1] * c4;
    const double r2 = -a * al2 * c2 + a * w2 * w2 * s2 + b * w[0] * w[0] * s3 - c * w[1] * w[1] * s4;
    const double det = A11 * A22 - A12 * A21;
    pm->al[0] = al2;
    pm->al[1] = (r1 * A22 - A12 * r2) / det;
    pm->al[2] = (A11 * r2 - A21 * r1) / det;
}

static double planar_energy(const planar_motion *pm, double g)
{
    const double a = VT_FB_A, b = VT_FB_B, c = VT_FB_C, L[3] = {a, b, c}, mass[3] = {1, 3, 2};
    double v[3][2], y[3];
    const double e0[2] = {cos(pm->th[0]), sin(pm->th[0])}, e1[2] = {cos(pm->th[1]), sin(pm->th[1])},
                 e2[2] = {cos(pm->th[2]), sin(pm->th[2])};
    for (int k = 0; k < 2; k++) {
        const double vB = a * pm->w[0] * (k ? e0[0] : -e0[1]);
        v[0][k] = 0.5 * vB;
        v[1][k] = vB + 0.5 * b * pm->w[1] * (k ? e1[0] : -e1[1]);
        v[2][k] = 0.5 * c * pm->w[2] * (k ? e2[0] : -e2[1]);
    }
    y[0] = 0.5 * a * e0[1]; y[1] = a * e0[1] + 0.5 * b * e1[1]; y[2] = 0.5 * c * e2[1];
    double E = 0.0;
    for (int k = 0; k < 3; k++)
        E += 0.5 * mass[k] * (v[k][0] * v[k][0] + v[k][1] * v[k][1]) +
             0.5 * mass[k] * L[k] * L[k] / 12.0 * pm->w[k] * pm->w[k] + mass[k] * g * y[k];
    return E;
}

static void test_fourbar(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5}; /* θ2 = 0.3 + 2 t + 1.5 t² */
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_fourbar(&m, vt_function_polynomial(3, coef)));
    assert_int_equal(m->nc, 5);
    assert_ok(vt_data_create(&d, m));
    const double g = 9.81;
    for (double t = 0.0; t < 2.0; t += 0.17) {
        const double th2 = coef[0] + coef[1] * t + coef[2] * t * t, w2 = coef[1] + 2 * coef[2] * t, al2 = 2 * coef[2];
        double th[2], w[2];
        assert_int_equal(vt_scene_fourbar_assemble(m, d, th2, w2, th, w), 0);
        d->time = t;
        assert_ok(vt_inverse_dynamics(m, d));
        /* the assembly closes the loop in position and velocity */
        for (int r = 0; r < m->nc; r++) {
            double vel = d->Phit[r];
            for (int c = 0; c < m->nv; c++) vel += d->Phiq[r + (size_t)c * (size_t)m->nc] * d->qd[c];
            assert_near(d->Phi[r], 0.0, 1e-12);
            assert_near(vel, 0.0, 1e-12);
        }
        planar_motion pm;
        planar_motion_at(&pm, th2, w2, al2, th, w);
        double x[9];
        planar_solution(&pm, x, g);
        const double tol = 1e-9 * (1 + vt_test_maxabs(x, 9));
        assert_near(d->drive_effort[0], x[8], tol);             /* crank torque */
        assert_near(d->jnt_force[3 * 1 + 0], x[0], tol);        /* ground on crank */
        assert_near(d->jnt_force[3 * 1 + 1], x[1], tol);
        assert_near(d->jnt_force[3 * 2 + 0], x[2], tol);        /* crank on coupler (spherical) */
        assert_near(d->jnt_force[3 * 2 + 1], x[3], tol);
        assert_near(d->cut_force[0], x[4], tol);                /* rocker on coupler (universal cut) */
        assert_near(d->cut_force[1], x[5], tol);
        assert_near(d->jnt_force[3 * 3 + 0], x[6], tol);        /* ground on rocker */
        assert_near(d->jnt_force[3 * 3 + 1], x[7], tol);
        /* nothing out of the plane, and no reaction moments in a planar mechanism */
        for (int i = 1; i <= 3; i++) {
            assert_near(d->jnt_force[3 * i + 2], 0.0, tol);
            for (int k = 0; k < 3; k++) assert_near(d->jnt_moment[3 * i + k], 0.0, tol);
        }
        assert_near(d->cut_force[2], 0.0, tol);
        for (int k = 0; k < 3; k++) assert_near(d->cut_moment[k], 0.0, tol);
        /* the crank torque against the energy balance of the planar motion: T ω2 = d(T+V)/dt */
        const double h = 1e-5;
        double E[2];
        for (int sgn = 0; sgn < 2; sgn++) {
            const double tt = t + (sgn ? h : -h);
            const double a2 = coef[0] + coef[1] * tt + coef[2] * tt * tt, b2 = coef[1] + 2 * coef[2] * tt;
            double th_[2], w_[2];
            assert_int_equal(vt_scene_fourbar_assemble(m, d, a2, b2, th_, w_), 0);
            planar_motion p2;
            planar_motion_at(&p2, a2, b2, al2, th_, w_);
            E[sgn] = planar_energy(&p2, g);
        }
        assert_near(x[8] * w2, (E[1] - E[0]) / (2 * h), 1e-6 * (1 + fabs(x[8] * w2)));
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* The four-bar built RUSR (universal joint at the crank's tip, spherical cut joint at the rocker's
 * tip) against the RSUR build: both are exactly constrained in space and move in the plane, so the
 * crank torque, the accelerations and the in-plane reactions at the ground pivots (statically
 * determinate in the plane) must agree, on both paths; the planar kinematics give the angular
 * accelerations of coupler and rocker independently of either model. */
static void test_fourbar_rusr(void **state)
{
    (void)state;
    const vt_function crank = vt_function_sine(0.3, 2.5, 1.7, 0.4); /* θ2 = 0.3 + 2.5 sin(1.7 t + 0.4) */
    vt_model *ms, *mu;
    assert_ok(vt_scene_fourbar(&ms, crank));
    assert_ok(vt_scene_fourbar_rusr(&mu, crank));
    assert_int_equal(mu->nv, 4);
    assert_int_equal(mu->nc, 4);
    assert_int_equal(mu->ncut, 1);
    assert_int_equal(mu->body_joint[2], VT_JOINT_UNIVERSAL);
    vt_data *ds, *du;
    assert_ok(vt_data_create(&ds, ms));
    assert_ok(vt_data_create(&du, mu));
    const int vs2 = ms->body_vadr[2], vs3 = ms->body_vadr[3], vu2 = mu->body_vadr[2], vu3 = mu->body_vadr[3];
    for (double t = 0.0; t < 4.0; t += 0.23) {
        double f[3];
        assert_ok(vt_function_eval(f, &crank, t));
        double th[2], w[2], thu[2], wu[2];
        assert_int_equal(vt_scene_fourbar_assemble(ms, ds, f[0], f[1], th, w), 0);
        assert_int_equal(vt_scene_fourbar_rusr_assemble(mu, du, f[0], f[1], thu, wu), 0);
        for (int k = 0; k < 2; k++) {
            assert_true(thu[k] == th[k]);
            assert_true(wu[k] == w[k]);
        }
        planar_motion pm;
        planar_motion_at(&pm, f[0], f[1], f[2], th, w);
        ds->time = du->time = t;
        for (int recursive = 0; recursive < 2; recursive++) {
            if (recursive) {
                assert_ok(vt_inverse_dynamics_recursive(ms, ds));
                assert_ok(vt_inverse_dynamics_recursive(mu, du));
            } else {
                assert_ok(vt_inverse_dynamics(ms, ds));
                assert_ok(vt_inverse_dynamics(mu, du));
            }
            /* square and of full rank, no warning; the assembly closes the loop in position and velocity */
            assert_int_equal(du->rank, 4);
            assert_int_equal(du->warning, 0);
            for (int r = 0; r < mu->nc; r++) {
                double vel = du->Phit[r];
                for (int c = 0; c < mu->nv; c++) vel += du->Phiq[r + (size_t)c * (size_t)mu->nc] * du->qd[c];
                assert_near(du->Phi[r], 0.0, 1e-12);
                assert_near(vel, 0.0, 1e-12);
            }
            /* crank torque to 1e-10 relative */
            const double T = ds->drive_effort[0];
            assert_near(du->drive_effort[0], T, 1e-10 * (1.0 + fabs(T)));
            /* q̈: the crank's α; coupler α_z = α2 + the relative rate's derivative (spherical: the
             * z component in the crank's axes, whose z is the global z; universal: its first angle);
             * rocker α_z; no tilt */
            const double al[3] = {ds->qdd[0], ds->qdd[0] + ds->qdd[vs2 + 2], ds->qdd[vs3]};
            const double alu[3] = {du->qdd[0], du->qdd[0] + du->qdd[vu2], du->qdd[vu3]};
            const double as = 1.0 + vt_test_maxabs(pm.al, 3);
            for (int k = 0; k < 3; k++) {
                assert_near(alu[k], al[k], 1e-10 * as);
                assert_near(alu[k], pm.al[k], 1e-9 * as);
            }
            assert_near(du->qdd[vu2 + 1], 0.0, 1e-10 * as);
            /* in-plane reactions of the ground on crank and rocker */
            const double fs = 1.0 + fmax(vt_test_maxabs(ds->jnt_force + 3, 3), vt_test_maxabs(ds->jnt_force + 9, 3));
            for (int i = 1; i <= 3; i += 2)
                for (int k = 0; k < 2; k++) assert_near(du->jnt_force[3 * i + k], ds->jnt_force[3 * i + k], 1e-10 * fs);
        }
    }
    vt_data_free(du);
    vt_data_free(ds);
    vt_model_free(mu);
    vt_model_free(ms);
}

/* ---- planar loops closed by a planar pin (vt_cut_joint_def.planar) ------------------------- */

/* One instant by path 0 the dense stages, 1 the recursive evaluation, 2 the motion given (the
 * crank's q̈, rate 0; the loop gives the rest) */
static void planar_instant(const vt_model *m, vt_data *d, int path, double crank_qdd)
{
    if (path == 0) {
        assert_ok(vt_inverse_dynamics(m, d));
    } else if (path == 1) {
        assert_ok(vt_inverse_dynamics_recursive(m, d));
    } else {
        memset(d->qdd, 0, (size_t)m->nv * sizeof(double));
        d->qdd[0] = crank_qdd;
        assert_ok(vt_inverse_dynamics_motion(m, d));
    }
}

/* |got − (x, y, z)| componentwise within tol; the largest relative difference to scale kept */
static void expect3(const double *got, double x, double y, double z, double tol, double scale, double *worst)
{
    const double want[3] = {x, y, z};
    for (int k = 0; k < 3; k++) {
        assert_near(got[k], want[k], tol);
        *worst = fmax(*worst, fabs(got[k] - want[k]) / scale);
    }
}

/* The four-bar closed by a planar pin at the rocker's ground pivot: 3 rows on 3 rates, no
 * allow_redundant. Against the planar Newton–Euler solution above (its own kinematics, dgesv)
 * on all three paths to 1e-12 of the largest force: the crank torque, q̈, every pin's in-plane
 * force (tree joints and the cut), nothing out of the plane, no pin moment, α of every link and
 * the total joint wrenches (the crank's carries the torque). Then the same mechanism with the
 * full 5-row revolute and allow_redundant: the same torque and in-plane forces. */
static void test_fourbar_planar_pin(void **state)
{
    (void)state;
    const vt_function crank = vt_function_sine(0.3, 2.5, 1.7, 0.4); /* θ2 = 0.3 + 2.5 sin(1.7 t + 0.4) */
    vt_model *m, *mr;
    assert_ok(vt_scene_fourbar_pin(&m, crank));
    assert_ok(vt_scene_fourbar_planar(&mr, crank, 1));
    assert_int_equal(m->nv, 3);
    assert_int_equal(m->nc, 3);
    assert_int_equal(m->allow_redundant, 0);
    assert_int_equal(mr->nc, 6);
    vt_data *d, *dr;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dr, mr));
    const double g = 9.81;
    double worst = 0.0;
    for (double t = 0.0; t < 4.0; t += 0.23) {
        double f[3];
        assert_ok(vt_function_eval(f, &crank, t));
        for (int path = 0; path < 3; path++) {
            assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, f[0], f[1]), 0);
            d->time = t;
            planar_instant(m, d, path, f[2]);
            assert_int_equal(d->rank, 3);
            assert_int_equal(d->warning, 0);
            /* the coupler's and rocker's global angles and rates: the joint angles summed */
            const double th[2] = {d->q[0] + d->q[1], d->q[0] + d->q[1] + d->q[2]};
            const double w[2] = {d->qd[0] + d->qd[1], d->qd[0] + d->qd[1] + d->qd[2]};
            planar_motion pm;
            planar_motion_at(&pm, f[0], f[1], f[2], th, w);
            double x[9];
            planar_solution(&pm, x, g);
            const double fs = vt_test_maxabs(x, 9), tol = 1e-12 * fs;
            const double as = vt_test_maxabs(pm.al, 3);
            /* q̈ and α */
            expect3(d->qdd, pm.al[0], pm.al[1] - pm.al[0], pm.al[2] - pm.al[1], 1e-12 * as, as, &worst);
            for (int i = 1; i <= 3; i++) expect3(d->alpha + 3 * i, 0.0, 0.0, pm.al[i - 1], 1e-12 * as, as, &worst);
            /* the crank torque, the pins' forces: ground on crank at O2, crank on coupler at B,
             * coupler on rocker at C (= −F3), ground on rocker at O4 (the planar pin) */
            assert_near(d->drive_effort[0], x[8], tol);
            worst = fmax(worst, fabs(d->drive_effort[0] - x[8]) / fs);
            expect3(d->jnt_force + 3, x[0], x[1], 0.0, tol, fs, &worst);
            expect3(d->jnt_force + 6, x[2], x[3], 0.0, tol, fs, &worst);
            expect3(d->jnt_force + 9, -x[4], -x[5], 0.0, tol, fs, &worst);
            expect3(d->cut_force, x[6], x[7], 0.0, tol, fs, &worst);
            expect3(d->cut_moment, 0.0, 0.0, 0.0, tol, fs, &worst);
            for (int i = 1; i <= 3; i++) expect3(d->jnt_moment + 3 * i, 0.0, 0.0, 0.0, tol, fs, &worst);
            /* the total wrenches: the reactions, and the crank's torque at O2 */
            expect3(d->jnt_force_total + 3, x[0], x[1], 0.0, tol, fs, &worst);
            expect3(d->jnt_moment_total + 3, 0.0, 0.0, x[8], tol, fs, &worst);
            for (int i = 2; i <= 3; i++) {
                expect3(d->jnt_force_total + 3 * i, d->jnt_force[3 * i], d->jnt_force[3 * i + 1], 0.0, tol, fs, &worst);
                expect3(d->jnt_moment_total + 3 * i, 0.0, 0.0, 0.0, tol, fs, &worst);
            }
        }
        /* the full revolute, 5 rows (2 of them and the axis rows' out-of-plane loads not unique) */
        assert_int_equal(vt_scene_fourbar_planar_assemble(mr, dr, f[0], f[1]), 0);
        dr->time = t;
        assert_ok(vt_inverse_dynamics(mr, dr));
        assert_int_equal(dr->rank, 3);
        const double fs = 1.0 + vt_test_maxabs(d->jnt_force + 3, 9);
        assert_near(dr->drive_effort[0], d->drive_effort[0], 1e-10 * fs);
        for (int i = 1; i <= 3; i++)
            for (int k = 0; k < 2; k++) {
                assert_int_equal(dr->jnt_unique[6 * i + k], 1);
                assert_near(dr->jnt_force[3 * i + k], d->jnt_force[3 * i + k], 1e-10 * fs);
            }
        for (int k = 0; k < 2; k++) assert_near(dr->cut_force[k], d->cut_force[k], 1e-10 * fs);
    }
    print_message("four-bar, planar pin: largest difference from the planar Newton-Euler solution %.2e of the largest force\n", worst);
    vt_data_free(dr);
    vt_data_free(d);
    vt_model_free(mr);
    vt_model_free(m);
}

/* the slider-crank's planar motion: crank θ, ω, α; rod φ, φ̇, φ̈; the pin B's x and its rates */
typedef struct { double th, w, al, phi, wphi, alphi, Bx, aBx; } slider_motion;

static void slider_motion_at(slider_motion *s, double th, double w, double al)
{
    const double R = VT_SC_R, L = VT_SC_L, h = VT_SC_H - VT_SC_JY + VT_SC_PY; /* B's height */
    s->th = th; s->w = w; s->al = al;
    /* R sin θ + L sin φ = h, differentiated twice */
    s->phi = asin((h - R * sin(th)) / L);
    const double cp = cos(s->phi), sp = sin(s->phi);
    s->wphi = -R * w * cos(th) / (L * cp);
    s->alphi = (-R * (al * cos(th) - w * w * sin(th)) + L * s->wphi * s->wphi * sp) / (L * cp);
    s->Bx = R * cos(th) + L * cp;
    s->aBx = -R * (al * sin(th) + w * w * cos(th)) - L * (s->alphi * sp + s->wphi * s->wphi * cp);
}

/* 9x9 Newton–Euler of the slider-crank: unknowns F_O (ground on crank at O) x y, F_A (crank on
 * rod at A) x y, F_B (slider on rod at the pin B) x y, N (the guide on the slider along y at its
 * joint point P), M (the guide's moment on the slider about P), T (the crank torque) */
static void slider_solution(const slider_motion *s, double x[9], double g)
{
    const double R = VT_SC_R, L = VT_SC_L, m1 = 1.0, m2 = 2.0, m3 = 1.5, I1 = m1 * R * R / 12, I2 = m2 * L * L / 12;
    const double e1[2] = {cos(s->th), sin(s->th)}, ep[2] = {cos(s->phi), sin(s->phi)};
    double A[2], G1[2], G2[2], B[2], G3[2], P[2], a1[2], a2[2], t[2], u[2];
    for (int k = 0; k < 2; k++) {
        A[k] = R * e1[k];
        G1[k] = 0.5 * R * e1[k];
        B[k] = A[k] + L * ep[k];
        G2[k] = A[k] + 0.5 * L * ep[k];
    }
    G3[0] = B[0] - VT_SC_PX; G3[1] = B[1] - VT_SC_PY;
    P[0] = G3[0] + VT_SC_JX; P[1] = G3[1] + VT_SC_JY;
    cross_z(t, s->al, e1);
    cross_z(u, s->alphi, ep);
    for (int k = 0; k < 2; k++) {
        const double aA = R * (t[k] - s->w * s->w * e1[k]);
        a1[k] = 0.5 * aA;
        a2[k] = aA + 0.5 * L * (u[k] - s->wphi * s->wphi * ep[k]);
    }
    double M[81] = {0}, rhs[9];
#define EQ(row, col, v) M[(row) + 9 * (col)] += (v)
#define MOM(row, col, r, sg) do { EQ(row, col, -(sg) * (r)[1]); EQ(row, (col) + 1, (sg) * (r)[0]); } while (0)
    double r[2];
    /* crank: F_O − F_A + m g = m a; T + (O − G1) × F_O − (A − G1) × F_A = I α */
    EQ(0, 0, 1); EQ(0, 2, -1); EQ(1, 1, 1); EQ(1, 3, -1);
    r[0] = -G1[0]; r[1] = -G1[1]; MOM(2, 0, r, 1.0);
    r[0] = A[0] - G1[0]; r[1] = A[1] - G1[1]; MOM(2, 2, r, -1.0);
    EQ(2, 8, 1);
    /* rod: F_A + F_B + m g = m a; (A − G2) × F_A + (B − G2) × F_B = I φ̈ */
    EQ(3, 2, 1); EQ(3, 4, 1); EQ(4, 3, 1); EQ(4, 5, 1);
    r[0] = A[0] - G2[0]; r[1] = A[1] - G2[1]; MOM(5, 2, r, 1.0);
    r[0] = B[0] - G2[0]; r[1] = B[1] - G2[1]; MOM(5, 4, r, 1.0);
    /* slider: (0, N) − F_B + m g = m a; M + (P − G3) × (0, N) − (B − G3) × F_B = 0 (it does not turn) */
    EQ(6, 4, -1); EQ(7, 5, -1); EQ(7, 6, 1);
    EQ(8, 7, 1); EQ(8, 6, P[0] - G3[0]);
    r[0] = B[0] - G3[0]; r[1] = B[1] - G3[1]; MOM(8, 4, r, -1.0);
#undef MOM
#undef EQ
    rhs[0] = m1 * a1[0]; rhs[1] = m1 * (a1[1] + g); rhs[2] = I1 * s->al;
    rhs[3] = m2 * a2[0]; rhs[4] = m2 * (a2[1] + g); rhs[5] = I2 * s->alphi;
    rhs[6] = m3 * s->aBx; rhs[7] = m3 * g; rhs[8] = 0.0;
    int n = 9, one = 1, ipiv[9], info = 0;
    dgesv_(&n, &one, M, &n, ipiv, rhs, &n, &info);
    assert_int_equal(info, 0);
    memcpy(x, rhs, sizeof rhs);
}

/* The offset slider-crank closed by a planar pin between the rod's end and the slider (3 rows on
 * 3 rates, no allow_redundant), on all three paths, against its planar Newton–Euler solution to
 * 1e-12 of the largest force: the crank torque, q̈, every pin's force, the guide's normal force
 * and moment, α, the total wrenches; nothing out of the plane. The full revolute with
 * allow_redundant gives the same torque. */
static void test_slider_crank_planar_pin(void **state)
{
    (void)state;
    const vt_function crank = vt_function_sine(0.2, 3.0, 2.1, -0.3);
    vt_model *m, *mr;
    assert_ok(vt_scene_slider_crank(&m, crank, 1));
    assert_ok(vt_scene_slider_crank(&mr, crank, 0));
    assert_int_equal(m->nv, 3);
    assert_int_equal(m->nc, 3);
    assert_int_equal(m->allow_redundant, 0);
    vt_data *d, *dr;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&dr, mr));
    double worst = 0.0;
    for (double t = 0.0; t < 3.0; t += 0.19) {
        double f[3];
        assert_ok(vt_function_eval(f, &crank, t));
        slider_motion s;
        slider_motion_at(&s, f[0], f[1], f[2]);
        double x[9];
        slider_solution(&s, x, 9.81);
        const double fs = vt_test_maxabs(x, 9), tol = 1e-12 * fs;
        const double as = fmax(fmax(fabs(s.al), fabs(s.alphi)), fabs(s.aBx));
        for (int path = 0; path < 3; path++) {
            assert_int_equal(vt_scene_slider_crank_assemble(m, d, f[0], f[1]), 0);
            d->time = t;
            planar_instant(m, d, path, f[2]);
            assert_int_equal(d->rank, 3);
            assert_int_equal(d->warning, 0);
            expect3(d->qdd, s.al, s.alphi - s.al, s.aBx, 1e-12 * as, as, &worst);
            expect3(d->alpha + 3, 0.0, 0.0, s.al, 1e-12 * as, as, &worst);
            expect3(d->alpha + 6, 0.0, 0.0, s.alphi, 1e-12 * as, as, &worst);
            expect3(d->alpha + 9, 0.0, 0.0, 0.0, 1e-12 * as, as, &worst);
            assert_near(d->drive_effort[0], x[8], tol);
            worst = fmax(worst, fabs(d->drive_effort[0] - x[8]) / fs);
            expect3(d->jnt_force + 3, x[0], x[1], 0.0, tol, fs, &worst);   /* ground on crank at O */
            expect3(d->jnt_force + 6, x[2], x[3], 0.0, tol, fs, &worst);   /* crank on rod at A */
            expect3(d->jnt_force + 9, 0.0, x[6], 0.0, tol, fs, &worst);    /* guide on slider at P */
            expect3(d->jnt_moment + 9, 0.0, 0.0, x[7], tol, fs, &worst);
            expect3(d->cut_force, x[4], x[5], 0.0, tol, fs, &worst);       /* slider on rod at B */
            expect3(d->cut_moment, 0.0, 0.0, 0.0, tol, fs, &worst);
            for (int i = 1; i <= 2; i++) expect3(d->jnt_moment + 3 * i, 0.0, 0.0, 0.0, tol, fs, &worst);
            expect3(d->jnt_moment_total + 3, 0.0, 0.0, x[8], tol, fs, &worst);
            expect3(d->jnt_force_total + 9, 0.0, x[6], 0.0, tol, fs, &worst);
            expect3(d->jnt_moment_total + 9, 0.0, 0.0, x[7], tol, fs, &worst);
        }
        assert_int_equal(vt_scene_slider_crank_assemble(mr, dr, f[0], f[1]), 0);
        dr->time = t;
        assert_ok(vt_inverse_dynamics(mr, dr));
        assert_int_equal(dr->rank, 3);
        assert_near(dr->drive_effort[0], x[8], 1e-10 * fs);
    }
    print_message("slider-crank, planar pin: largest difference from the planar Newton-Euler solution %.2e of the largest force\n", worst);
    vt_data_free(dr);
    vt_data_free(d);
    vt_model_free(mr);
    vt_model_free(m);
}

/* vt_scene_fourbar_pin's links by hand, with the rocker's hinge on the coupler tilted by `tilt`
 * about the coupler's x (tilt ≠ 0: a loop that is not planar) and the pin's axis1 given */
static vt_model *fourbar_pin_variant(double tilt, const double axis[3], int allow_redundant)
{
    static const double len[3] = {VT_FB_A, VT_FB_B, VT_FB_C}, mass[3] = {1.0, 3.0, 2.0};
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = allow_redundant;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    for (int k = 0; k < 3; k++) {
        vt_body_def link = vt_default_body_def();
        link.parent = k;
        link.mass = mass[k];
        link.inertia[4] = link.inertia[8] = mass[k] * len[k] * len[k] / 12.0;
        link.joint_child[0] = k == 2 ? 0.5 * len[k] : -0.5 * len[k];
        if (k > 0) link.joint_parent[0] = 0.5 * len[k - 1];
        if (k == 2) {
            link.axis1[1] = sin(tilt);
            link.axis1[2] = cos(tilt);
        }
        assert_int_equal(vt_builder_add_body(b, &link), k + 1);
    }
    vt_cut_joint_def cut = vt_default_cut_joint_def();
    cut.body_b = 3;
    cut.point_a[0] = VT_FB_D;
    cut.point_b[0] = -0.5 * VT_FB_C;
    memcpy(cut.axis1, axis, sizeof cut.axis1);
    cut.planar = 1;
    assert_int_equal(vt_builder_add_cut_joint(b, &cut), 0);
    vt_drive_def drive = vt_default_drive_def();
    drive.f = vt_function_sine(0.3, 2.5, 1.7, 0.4);
    assert_int_equal(vt_builder_add_drive(b, &drive), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* A planar pin where the loop is not planar, as documented: it holds only the joint point in the
 * plane ⟂ axis1. (1) The rocker's hinge tilted 0.2 rad: the loop closes (kinematic solve) with
 * the rocker's end off the plane along axis1; 3 independent rows; the pin's force lies in the
 * plane and it carries no moment; dense and recursive paths agree; and the crank torque does the
 * work the motion needs, τ ω = d(T + V)/dt (energies from the bodies' velocities, central
 * differences). (2) A pin whose axis1 lies in the plane of a planar loop: its out-of-plane row
 * has Φ_q = 0, refused as dependent (the message names the cut joint), or with allow_redundant
 * solved at rank 2. */
static void test_planar_pin_off_plane(void **state)
{
    (void)state;
    const double z[3] = {0, 0, 1}, xaxis[3] = {1, 0, 0};
    vt_model *m = fourbar_pin_variant(0.2, z, 0);
    vt_data *d, *d2;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&d2, m));
    for (double t = 0.1; t < 1.0; t += 0.3) {
        double f[3];
        assert_ok(vt_function_eval(f, &m->drive[0].f, t));
        assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, f[0], f[1]), 0); /* a start near */
        d->time = t;
        assert_ok(vt_kinematic_solve(m, d, 1e-13, 50));
        assert_int_equal(d->rank, 3);
        /* the rocker's end O4 in the plane z = 0 at (VT_FB_D, 0), off it along z */
        const double *A3 = d->A + 9 * 3, *r3 = d->x + 14;
        double O4[3];
        for (int k = 0; k < 3; k++) O4[k] = r3[k] - 0.5 * VT_FB_C * A3[k];
        assert_near(O4[0], VT_FB_D, 1e-12);
        assert_near(O4[1], 0.0, 1e-12);
        assert_true(fabs(O4[2]) > 1e-3);
        const double fs = 1.0 + vt_test_maxabs(d->jnt_force + 3, 9);
        assert_near(d->cut_force[2], 0.0, 1e-12 * fs);
        for (int k = 0; k < 3; k++) assert_near(d->cut_moment[k], 0.0, 1e-12 * fs);
        assert_true(fabs(d->jnt_moment[9]) + fabs(d->jnt_moment[10]) > 1e-3 * fs); /* the tree takes the tilt */
        memcpy(d2->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(d2->qd, d->qd, (size_t)m->nv * sizeof(double));
        d2->time = t;
        assert_ok(vt_inverse_dynamics_recursive(m, d2));
        assert_near(d2->drive_effort[0], d->drive_effort[0], 1e-12 * fs);
        for (int k = 0; k < 3; k++) {
            assert_near(d2->cut_force[k], d->cut_force[k], 1e-12 * fs);
            for (int i = 1; i <= 3; i++) assert_near(d2->jnt_force[3 * i + k], d->jnt_force[3 * i + k], 1e-12 * fs);
        }
        /* power balance */
        const double P = d->drive_effort[0] * d->qd[0], h = 1e-5;
        double q[3], v[3], a[3], E[2];
        memcpy(q, d->q, sizeof q);
        memcpy(v, d->qd, sizeof v);
        memcpy(a, d->qdd, sizeof a);
        for (int sgn = 0; sgn < 2; sgn++) {
            const double s = sgn ? h : -h;
            for (int c = 0; c < 3; c++) {
                d2->q[c] = q[c] + s * v[c];
                d2->qd[c] = v[c] + s * a[c];
            }
            assert_ok(vt_kinematics(m, d2));
            E[sgn] = vt_test_kinetic_energy(m, d2) + vt_test_potential_energy(m, d2);
        }
        assert_near(P, (E[1] - E[0]) / (2 * h), 1e-7 * (1 + fabs(P)));
    }
    vt_data_free(d2);
    vt_data_free(d);
    vt_model_free(m);

    for (int redundant = 0; redundant < 2; redundant++) {
        m = fourbar_pin_variant(0.0, xaxis, redundant);
        assert_ok(vt_data_create(&d, m));
        assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, 0.7, 1.1), 0);
        d->time = 0.0;
        if (!redundant) {
            assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_DEPENDENT_CONSTRAINTS);
            assert_non_null(strstr(d->message, "cut joint 0"));
            assert_int_equal(vt_inverse_dynamics_recursive(m, d), VT_ERR_DEPENDENT_CONSTRAINTS);
        } else {
            assert_ok(vt_inverse_dynamics(m, d));
            assert_int_equal(d->rank, 2);
            assert_true(d->warning & VT_WARN_REDUNDANT);
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* ---- the total joint wrench and every body's α ------------------------------------------- */

/* Each body's centre-of-mass acceleration and angular acceleration by central differences of its
 * velocity and ω (vt_kinematics) along (q ⊕ τ q̇, q̇ + τ q̈), whose rates at τ = 0 are the
 * instant's own; dk: a data of the model for the differences */
static void fd_accelerations(const vt_model *m, vt_data *dk, const vt_data *d, double *acc, double *al)
{
    const double h = 1e-5;
    const int nb3 = 3 * (m->nbody + 1);
    double *vel[2], *om[2];
    for (int sgn = 0; sgn < 2; sgn++) {
        const double s = sgn ? h : -h;
        assert_ok(vt_integrate_q(dk->q, m, d->q, d->qd, s));
        for (int c = 0; c < m->nv; c++) dk->qd[c] = d->qd[c] + s * d->qdd[c];
        assert_ok(vt_kinematics(m, dk));
        vel[sgn] = calloc((size_t)nb3, sizeof(double));
        om[sgn] = malloc((size_t)nb3 * sizeof(double));
        for (int i = 1; i <= m->nbody; i++) memcpy(vel[sgn] + 3 * i, dk->xd + 7 * (i - 1), 3 * sizeof(double));
        memcpy(om[sgn], dk->omega, (size_t)nb3 * sizeof(double));
    }
    for (int k = 0; k < nb3; k++) {
        acc[k] = (vel[1][k] - vel[0][k]) / (2 * h);
        al[k] = (om[1][k] - om[0][k]) / (2 * h);
    }
    for (int sgn = 0; sgn < 2; sgn++) {
        free(vel[sgn]);
        free(om[sgn]);
    }
}

/* The wrench that must reach body i's subtree through joint i, force f and moment n about the
 * joint point P_i: over the subtree, Σ m (a − g) − f_x and Σ J α + ω × J ω − n_x + (r − P_i) ×
 * (m (a − g) − f_x), J = A J' A^T, from the centres' accelerations acc and α al (3 x (nbody+1)) */
static void subtree_wrench(const vt_model *m, const vt_data *d, const double *acc, const double *al, int i, double f[3],
                           double n[3])
{
    const double *P = d->jpoint + 3 * i;
    memset(f, 0, 3 * sizeof(double));
    memset(n, 0, 3 * sizeof(double));
    for (int k = i; k <= m->nbody; k++) {
        int up = k;
        while (up > i) up = m->body_parent[up];
        if (up != i) continue;
        const double *r = d->x + 7 * (k - 1), *w = d->omega + 3 * k, *a = acc + 3 * k, *xf = d->xfrc + 6 * k;
        double J[9], Jw[3], Ja[3], fk[3], s[3];
        vt_test_global_inertia(J, m, d, k);
        for (int c = 0; c < 3; c++) {
            Jw[c] = J[c] * w[0] + J[c + 3] * w[1] + J[c + 6] * w[2];
            Ja[c] = J[c] * al[3 * k] + J[c + 3] * al[3 * k + 1] + J[c + 6] * al[3 * k + 2];
            fk[c] = m->body_mass[k] * (a[c] - m->gravity[c]) - xf[c];
            s[c] = r[c] - P[c];
        }
        for (int c = 0; c < 3; c++) {
            const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            f[c] += fk[c];
            n[c] += Ja[c] + (w[c1] * Jw[c2] - w[c2] * Jw[c1]) - xf[3 + c] + (s[c1] * fk[c2] - s[c2] * fk[c1]);
        }
    }
}

/* Checks d's α against differences of ω, the centres' accelerations too, and each joint's total
 * wrench against its subtree's Newton–Euler wrench: from the instant's own accelerations (ẍ, α)
 * to round-off, from the differences to their error; the body-axes totals as A^T of the global
 * ones. Keeps the largest relative differences. */
static void check_totals(const vt_model *m, vt_data *d, vt_data *dk, double worst[2])
{
    const int n = m->nbody, nb3 = 3 * (n + 1);
    double *acc = malloc((size_t)nb3 * sizeof(double)), *al = malloc((size_t)nb3 * sizeof(double));
    double *own = calloc((size_t)nb3, sizeof(double));
    fd_accelerations(m, dk, d, acc, al);
    for (int i = 1; i <= n; i++) memcpy(own + 3 * i, d->xdd + 7 * (i - 1), 3 * sizeof(double));
    const double as = 1.0 + fmax(vt_test_maxabs(al, nb3), vt_test_maxabs(acc, nb3));
    for (int k = 0; k < 3; k++) assert_true(d->alpha[k] == 0.0);
    for (int k = 3; k < nb3; k++) {
        assert_near(d->alpha[k], al[k], 1e-7 * as);
        assert_near(own[k], acc[k], 1e-7 * as);
        worst[1] = fmax(worst[1], fabs(d->alpha[k] - al[k]) / as);
    }
    double *W = malloc(6 * (size_t)(n + 1) * sizeof(double)), *Wd = malloc(6 * (size_t)(n + 1) * sizeof(double));
    double ws = 1.0;
    for (int i = 1; i <= n; i++) {
        subtree_wrench(m, d, own, d->alpha, i, W + 6 * i, W + 6 * i + 3);
        subtree_wrench(m, d, acc, al, i, Wd + 6 * i, Wd + 6 * i + 3);
        ws = fmax(ws, vt_test_maxabs(W + 6 * i, 6));
    }
    for (int i = 1; i <= n; i++) {
        const double *A = d->A + 9 * i, *ft = d->jnt_force_total + 3 * i, *nt = d->jnt_moment_total + 3 * i;
        for (int c = 0; c < 3; c++) {
            assert_near(ft[c], W[6 * i + c], 1e-11 * ws);
            assert_near(nt[c], W[6 * i + 3 + c], 1e-11 * ws);
            assert_near(ft[c], Wd[6 * i + c], 1e-7 * ws);
            assert_near(nt[c], Wd[6 * i + 3 + c], 1e-7 * ws);
            worst[0] = fmax(worst[0], fmax(fabs(ft[c] - W[6 * i + c]), fabs(nt[c] - W[6 * i + 3 + c])) / ws);
            assert_near(d->jnt_force_total_body[3 * i + c], A[3 * c] * ft[0] + A[3 * c + 1] * ft[1] + A[3 * c + 2] * ft[2], 1e-12 * ws);
            assert_near(d->jnt_moment_total_body[3 * i + c], A[3 * c] * nt[0] + A[3 * c + 1] * nt[1] + A[3 * c + 2] * nt[2], 1e-12 * ws);
        }
    }
    free(W); free(Wd); free(acc); free(al); free(own);
}

static void random_loads(const vt_model *m, vt_data *d, uint64_t *s)
{
    for (int k = 6; k < 6 * (m->nbody + 1); k++) d->xfrc[k] = vt_rand_uniform(s, -3.0, 3.0);
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = vt_rand_uniform(s, -2.0, 2.0);
}

/* The total wrench a joint transmits (reaction plus actuation) is what the subtree outboard of
 * it needs: its Newton–Euler wrench less gravity and the applied loads xfrc on it (the applied
 * qfrc of the joints inside it cancel in pairs), computed here from masses, inertias and the
 * bodies' accelerations, which differences of the velocities check; α against differences of ω.
 *  (1) trees of scalar joints, every rate joint-driven, xfrc and qfrc applied: the dense, the
 *      recursive (joint-driven route) and the motion paths;
 *  (2) trees with spherical and free joints, the motion given for every rate;
 *  (3) trees with every joint kind, base bodies among them, some rates driven (a base body's
 *      r_y too), a coupling, the rest free: the dense and recursive paths. */
static void test_total_wrench_subtree(void **state)
{
    (void)state;
    double worst[2] = {0.0, 0.0};
    for (uint64_t seed = 1; seed <= 3; seed++) {
        /* (1) */
        vt_model *probe;
        assert_ok(vt_scene_random_tree(&probe, seed, 10, VT_SCENE_SCALAR_JOINTS));
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        assert_ok(vt_scene_random_bodies(b, seed, 10, VT_SCENE_SCALAR_JOINTS));
        uint64_t s = seed * 7;
        for (int i = 1; i <= probe->nbody; i++)
            for (int k = 0; k < probe->body_nv[i]; k++) {
                vt_drive_def dr = vt_default_drive_def();
                dr.body = i;
                dr.index = k;
                const double c[3] = {vt_rand_uniform(&s, -1, 1), vt_rand_uniform(&s, -2, 2), vt_rand_uniform(&s, -2, 2)};
                dr.f = vt_function_polynomial(3, c);
                assert_true(vt_builder_add_drive(b, &dr) >= 0);
            }
        vt_model *m;
        assert_ok(vt_builder_build(&m, b));
        vt_builder_free(b);
        vt_model_free(probe);
        vt_data *d, *dk;
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&dk, m));
        const double t = 0.4;
        for (int path = 0; path < 3; path++) {
            for (int k = 0; k < m->ndrive; k++) {
                double f[3];
                assert_ok(vt_function_eval(f, &m->drive[k].f, t));
                const int c = m->body_vadr[m->drive[k].body] + m->drive[k].index;
                d->q[m->body_qadr[m->drive[k].body] + m->drive[k].index] = f[0];
                d->qd[c] = f[1];
                d->qdd[c] = f[2];
            }
            uint64_t ls = seed;
            random_loads(m, d, &ls);
            d->time = t;
            if (path == 0) assert_ok(vt_inverse_dynamics(m, d));
            if (path == 1) {
                assert_ok(vt_inverse_dynamics_recursive(m, d));
                assert_int_equal(d->route, VT_ROUTE_JOINT_DRIVEN);
            }
            if (path == 2) {
                assert_ok(vt_inverse_dynamics_motion(m, d));
                assert_int_equal(d->route, VT_ROUTE_MOTION);
            }
            check_totals(m, d, dk, worst);
        }
        vt_data_free(dk);
        vt_data_free(d);
        vt_model_free(m);

        /* (2) */
        assert_ok(vt_scene_random_tree(&m, seed + 20, 10, VT_SCENE_WITH_FREE));
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&dk, m));
        s = seed * 11;
        vt_scene_random_state(m, d, &s);
        for (int c = 0; c < m->nv; c++) d->qdd[c] = vt_rand_uniform(&s, -3.0, 3.0);
        random_loads(m, d, &s);
        assert_ok(vt_inverse_dynamics_motion(m, d));
        check_totals(m, d, dk, worst);
        vt_data_free(dk);
        vt_data_free(d);
        vt_model_free(m);

        /* (3) */
        assert_ok(vt_scene_random_tree(&probe, seed + 40, 10, VT_SCENE_ALL_JOINTS));
        assert_ok(vt_builder_create(&b, NULL));
        assert_ok(vt_scene_random_bodies(b, seed + 40, 10, VT_SCENE_ALL_JOINTS));
        int scalar[2] = {0, 0}, ns = 0;
        for (int i = 1; i <= probe->nbody; i += 2) {
            const int jt = probe->body_joint[i];
            if (jt == VT_JOINT_SPHERICAL) continue;
            vt_drive_def dr = vt_default_drive_def();
            dr.body = i;
            dr.index = jt == VT_JOINT_BASE ? 1 : 0;
            dr.f = vt_function_sine(0.1, 0.5, 1.3, 0.2 * (double)i);
            assert_true(vt_builder_add_drive(b, &dr) >= 0);
        }
        for (int i = 2; i <= probe->nbody && ns < 2; i += 2)
            if (probe->body_joint[i] != VT_JOINT_SPHERICAL && probe->body_joint[i] != VT_JOINT_BASE) scalar[ns++] = i;
        assert_int_equal(ns, 2);
        vt_coupling_def cp = vt_default_coupling_def();
        cp.body_a = scalar[0];
        cp.body_b = scalar[1];
        cp.ratio = -0.6;
        assert_int_equal(vt_builder_add_coupling(b, &cp), 0);
        assert_ok(vt_builder_build(&m, b));
        vt_builder_free(b);
        vt_model_free(probe);
        int bases = 0;
        for (int i = 1; i <= m->nbody; i++) bases += m->body_joint[i] == VT_JOINT_BASE;
        assert_true(bases > 0);
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&dk, m));
        for (int path = 0; path < 2; path++) {
            s = seed * 13;
            vt_scene_random_state(m, d, &s);
            random_loads(m, d, &s);
            d->time = 0.3;
            if (path == 0) assert_ok(vt_inverse_dynamics(m, d));
            else assert_ok(vt_inverse_dynamics_recursive(m, d));
            check_totals(m, d, dk, worst);
        }
        vt_data_free(dk);
        vt_data_free(d);
        vt_model_free(m);
    }
    print_message("total wrench against the subtree's Newton-Euler wrench: %.2e of the largest; alpha against differences of omega: %.2e\n",
                  worst[0], worst[1]);
}

/* A double link of arbitrary link length L and masses m1, m2 (uniform rods), joint 2 locked:
 * the pair pivots as one rigid body with mass M = m1 + m2, centre of mass at x_c from the pivot
 * and inertia I_p about it, so θ̇² = 2 M g x_c sin θ / I_p, θ̈ = M g x_c cos θ / I_p and the
 * ground's force on link 1 is f = M a_c − M g. Accuracy must hold relative to the scene's scale
 * for masses from 1e-6 to 1e6 (and ratios between the links that large) and lengths from 1e-3
 * to 1e3 m. */
static void test_extreme_scales(void **state)
{
    (void)state;
    const double lengths[3] = {1e-3, 1.0, 1e3};
    const double masses[4][2] = {{1e-6, 1e-6}, {1e6, 1e6}, {1.0, 1e-6}, {1e-6, 1e6}};
    for (int li = 0; li < 3; li++)
        for (int mi = 0; mi < 4; mi++) {
            const double L = lengths[li], m1 = masses[mi][0], m2 = masses[mi][1], g = 9.81;
            vt_builder *b;
            assert_ok(vt_builder_create(&b, NULL));
            vt_test_add_rods(b, 2, L, masses[mi]);
            vt_drive_def lock = vt_default_drive_def();
            lock.body = 2;
            assert_int_equal(vt_builder_add_drive(b, &lock), 0);
            vt_model *m;
            assert_ok(vt_builder_build(&m, b));
            vt_builder_free(b);
            vt_data *d;
            assert_ok(vt_data_create(&d, m));
            const double M = m1 + m2, xc = (m1 * 0.5 * L + m2 * 1.5 * L) / M;
            const double Ip = m1 * L * L / 3.0 + m2 * (L * L / 12.0 + 2.25 * L * L);
            for (double th = 0.1; th < 1.5; th += 0.35) {
                const double s = sin(th), c = cos(th), thd2 = 2 * M * g * xc * s / Ip, thdd = M * g * xc * c / Ip;
                d->q[0] = -th;
                d->q[1] = 0.0;
                d->qd[0] = -sqrt(thd2);
                d->qd[1] = 0.0;
                assert_ok(vt_inverse_dynamics(m, d));
                assert_near(-d->qdd[0], thdd, 1e-9 * (g / L));
                /* centre of mass at xc (cos θ, −sin θ): a_c = xc [−θ̈ sin − θ̇² cos, −θ̈ cos + θ̇² sin] */
                const double fx = M * xc * (-thdd * s - thd2 * c), fy = M * xc * (-thdd * c + thd2 * s) + M * g;
                assert_near(d->jnt_force[3], fx, 1e-9 * M * g);
                assert_near(d->jnt_force[4], fy, 1e-9 * M * g);
                assert_true(d->rcond > 1e-12);
            }
            vt_data_free(d);
            vt_model_free(m);
        }
}

/* a spherical joint driven through the pose where Z–Y–X angles lock (Y at 90°): the Euler
 * parameters have no such pose, so the efforts stay smooth, and they equal the rigid body's
 * Euler equation about the pivot, n = I_p α + ω × I_p ω − c × m g */
static int zyx_turn(double t, double p[4], double w[3], double wd[3], void *user)
{
    (void)user;
    const double rz = 0.5, ry = 0.5 * 3.14159265358979323846, rx = 0.3; /* Y passes 90° at t = 1 */
    const double ez[3] = {0, 0, 1}, ey[3] = {0, 1, 0}, ex[3] = {1, 0, 0};
    double pz[4], py[4], px[4], pzy[4], Az[9], Azy[9], y1[3], x2[3];
    vt_quat_axis_angle(pz, ez, rz * t);
    vt_quat_axis_angle(py, ey, ry * t);
    vt_quat_axis_angle(px, ex, rx * t);
    vt_quat_mul(pzy, pz, py);
    vt_quat_mul(p, pzy, px);
    vt_euler_A(Az, pz);
    vt_euler_A(Azy, pzy);
    for (int k = 0; k < 3; k++) {
        y1[k] = Az[3 + k];   /* Az e_y */
        x2[k] = Azy[k];      /* Azy e_x */
        w[k] = rz * ez[k] + ry * y1[k] + rx * x2[k];
    }
    /* ω̇ = ry (rz z × y1) + rx ((rz z + ry y1) × x2) */
    const double a[3] = {rz * ez[0] + ry * y1[0], rz * ez[1] + ry * y1[1], rz * ez[2] + ry * y1[2]};
    wd[0] = ry * rz * (ez[1] * y1[2] - ez[2] * y1[1]) + rx * (a[1] * x2[2] - a[2] * x2[1]);
    wd[1] = ry * rz * (ez[2] * y1[0] - ez[0] * y1[2]) + rx * (a[2] * x2[0] - a[0] * x2[2]);
    wd[2] = ry * rz * (ez[0] * y1[1] - ez[1] * y1[0]) + rx * (a[0] * x2[1] - a[1] * x2[0]);
    return 0;
}

static void test_spherical_through_gimbal_lock(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_SPHERICAL;
    body.mass = 2.0;
    body.inertia[0] = 0.1; body.inertia[4] = 0.2; body.inertia[8] = 0.25;
    body.joint_child[0] = -0.3; body.joint_child[1] = 0.1; /* pivot off the centre of mass */
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    od.orientation_callback = zyx_turn;
    assert_int_equal(vt_builder_add_drive(b, &od), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    vt_trajectory *tr;
    assert_ok(vt_data_create(&d, m));
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 200;
    opt.forward_check = 0;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    assert_ok(vt_kinematic_analysis(m, d, &opt, tr));
    assert_int_equal(tr->nwarn, 0);
    double prev[3] = {0, 0, 0}, pprev[3] = {0, 0, 0}, big = 0.0, jump = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        /* the state of the row, and the Euler equation about the pivot */
        memcpy(d->q, tr->q + 4 * k, 4 * sizeof(double));
        memcpy(d->qd, tr->qd + 3 * k, 3 * sizeof(double));
        d->time = tr->t[k];
        assert_ok(vt_inverse_dynamics(m, d));
        double J[9], c[3], Ip[9], w[3], al[3], Iw[3], Ia[3], n[3];
        vt_test_global_inertia(J, m, d, 1);
        for (int e = 0; e < 3; e++) c[e] = d->x[e] - d->jpoint[3 + e]; /* pivot → centre of mass */
        const double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        for (int col = 0; col < 3; col++)
            for (int r = 0; r < 3; r++) Ip[r + 3 * col] = J[r + 3 * col] + 2.0 * ((r == col) * c2 - c[r] * c[col]);
        double pw[4];
        zyx_turn(d->time, pw, w, al, NULL);
        for (int r = 0; r < 3; r++) {
            Iw[r] = Ip[r] * w[0] + Ip[r + 3] * w[1] + Ip[r + 6] * w[2];
            Ia[r] = Ip[r] * al[0] + Ip[r + 3] * al[1] + Ip[r + 6] * al[2];
        }
        const double mg[3] = {0, -9.81 * 2.0, 0};
        n[0] = Ia[0] + w[1] * Iw[2] - w[2] * Iw[1] - (c[1] * mg[2] - c[2] * mg[1]);
        n[1] = Ia[1] + w[2] * Iw[0] - w[0] * Iw[2] - (c[2] * mg[0] - c[0] * mg[2]);
        n[2] = Ia[2] + w[0] * Iw[1] - w[1] * Iw[0] - (c[0] * mg[1] - c[1] * mg[0]);
        for (int e = 0; e < 3; e++) {
            assert_near(d->drive_moment[e], n[e], 1e-9 * (1 + fabs(n[e])));
            assert_near(d->jnt_moment[3 + e], 0.0, 1e-9); /* a spherical joint carries no moment */
            big = fmax(big, fabs(n[e]));
            if (k >= 2) jump = fmax(jump, fabs(n[e] - 2 * prev[e] + pprev[e]));
            pprev[e] = prev[e];
            prev[e] = n[e];
        }
    }
    /* smooth: second differences of the effort over 0.01 s stay small */
    assert_true(jump < 1e-2 * big);
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* Two rods on hinges at separate ground points, their angles coupled (a gear pair,
 * q1 = k q2 + c): the free motion, the coupling's effort and the pins' reactions against the
 * closed forms of the one-degree-of-freedom Lagrangian, with T = ½ I_O (k² + 1) q̇2² and
 * V = m g (L/2)(sin q1 + sin q2); then the same with q2 driven (a kinematic solve) */
static vt_model *coupled_rods(double m, double L, double k, double c, int drive)
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def rod = vt_default_body_def();
    rod.mass = m;
    rod.inertia[4] = rod.inertia[8] = m * L * L / 12.0;
    rod.joint_child[0] = -L / 2;
    assert_int_equal(vt_builder_add_body(b, &rod), 1);
    rod.joint_parent[0] = 3.0; /* the second pin at (3, 0, 0) */
    assert_int_equal(vt_builder_add_body(b, &rod), 2);
    vt_coupling_def cp = vt_default_coupling_def();
    cp.body_a = 1;
    cp.body_b = 2;
    cp.ratio = k;
    cp.offset = c;
    cp.name = "gears";
    if (drive) {
        vt_drive_def dr = vt_default_drive_def();
        dr.body = 2;
        dr.f = vt_function_sine(0.4, 0.5, 1.7, 0.0);
        assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    }
    assert_int_equal(vt_builder_add_coupling(b, &cp), 0);
    vt_model *model;
    assert_ok(vt_builder_build(&model, b));
    vt_builder_free(b);
    return model;
}

static void test_coupling(void **state)
{
    (void)state;
    const double m = 2.0, L = 1.5, k = -0.6, c = 0.3, g = 9.81, IO = m * L * L / 3.0;
    vt_model *model = coupled_rods(m, L, k, c, 0);
    assert_int_equal(vt_find_coupling(model, "gears"), 0);
    vt_data *d;
    assert_ok(vt_data_create(&d, model));
    for (int rec = 0; rec < 2; rec++)
        for (double q2 = -1.0; q2 <= 1.0; q2 += 0.5) {
            const double w2 = 0.7 - 0.2 * q2, q1 = k * q2 + c, w1 = k * w2;
            d->q[0] = q1;
            d->q[1] = q2;
            d->qd[0] = w1;
            d->qd[1] = w2;
            assert_ok(rec ? vt_inverse_dynamics_recursive(model, d) : vt_inverse_dynamics(model, d));
            const double a2 = -m * g * (L / 2) * (k * cos(q1) + cos(q2)) / (IO * (k * k + 1.0)), a1 = k * a2;
            assert_near(d->qdd[1], a2, 1e-12);
            assert_near(d->qdd[0], a1, 1e-12);
            assert_near(d->coupling_effort[0], IO * a1 + m * g * (L / 2) * cos(q1), 1e-11);
            const double qs[2] = {q1, q2}, ws[2] = {w1, w2}, as[2] = {a1, a2};
            for (int i = 0; i < 2; i++) { /* a pin's force: m (a_c − g), a_c the centre's acceleration */
                const double ax = (L / 2) * (-sin(qs[i]) * as[i] - cos(qs[i]) * ws[i] * ws[i]);
                const double ay = (L / 2) * (cos(qs[i]) * as[i] - sin(qs[i]) * ws[i] * ws[i]);
                assert_near(d->jnt_force[3 * (i + 1)], m * ax, 1e-11);
                assert_near(d->jnt_force[3 * (i + 1) + 1], m * (ay + g), 1e-11);
                assert_near(d->jnt_moment[3 * (i + 1) + 2], 0.0, 1e-11); /* the gears' torque is not reaction */
            }
        }
    vt_data_free(d);
    vt_model_free(model);
    /* q2 driven: a fully driven mechanism, solved at the drive's time; its effort by the Lagrangian */
    model = coupled_rods(m, L, k, c, 1);
    assert_ok(vt_data_create(&d, model));
    d->q[1] = 0.4;
    d->q[0] = k * 0.4 + c;
    for (double t = 0.0; t < 2.0; t += 0.4) {
        d->time = t;
        assert_ok(vt_kinematic_solve(model, d, 1e-13, 30));
        double f[3];
        assert_ok(vt_function_eval(f, &model->drive[0].f, t));
        assert_near(d->q[1], f[0], 1e-12);
        assert_near(d->q[0], k * f[0] + c, 1e-12);
        assert_near(d->qd[0], k * f[1], 1e-12);
        const double tau = IO * (k * k + 1.0) * f[2] + m * g * (L / 2) * (k * cos(d->q[0]) + cos(d->q[1]));
        assert_near(d->drive_effort[0], tau, 1e-10);
    }
    vt_data_free(d);
    vt_model_free(model);
}

/* A redundant row that moves no reaction: a two-link arm whose second hinge is both driven and
 * coupled to the first (allow_redundant). The null direction of Φ_q^T changes only the split
 * between the drives' and the coupling's efforts; every reaction stays unique, as adding the
 * direction to λ and recomputing the reactions shows */
static void test_unique_despite_redundant_row(void **state)
{
    (void)state;
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = 1;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    vt_test_add_rods(b, 2, 1.0, (const double[2]){2.0, 2.0});
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    dr.f = vt_function_sine(0.4, 0.1, 2.0, 0.0);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    dr.body = 2;
    dr.f = vt_function_sine(0.9, 0.2, 2.0, 0.0); /* q2 = 2 q1 + 0.1 exactly */
    assert_int_equal(vt_builder_add_drive(b, &dr), 1);
    vt_coupling_def c = vt_default_coupling_def();
    c.ratio = 2.0;
    c.offset = 0.1;
    assert_int_equal(vt_builder_add_coupling(b, &c), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    d->time = 0.3;
    assert_ok(vt_kinematic_solve(m, d, 1e-12, 50));
    assert_int_equal(d->rank, 2);
    assert_int_equal(d->route, VT_ROUTE_REDUNDANT);
    double f0[9], n0[9];
    memcpy(f0, d->jnt_force, sizeof f0);
    memcpy(n0, d->jnt_moment, sizeof n0);
    for (int k = 6; k < 18; k++) assert_int_equal(d->jnt_unique[k], 1);
    for (int r = 0; r < 3; r++) d->lambda[r] += 5.0 * d->lambda_null[r]; /* another solution */
    assert_ok(vt_reactions(m, d));
    for (int k = 3; k < 9; k++) {
        assert_near(d->jnt_force[k], f0[k], 1e-10 * (1 + fabs(f0[k])));
        assert_near(d->jnt_moment[k], n0[k], 1e-10 * (1 + fabs(n0[k])));
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* ---- relative orientation drives ----------------------------------------------------- */

/* every joint's reaction of two data of models with the same bodies, to tol of the largest */
static void same_reactions(const vt_model *m, const vt_data *a, const vt_data *b, int from, double tol)
{
    const int n = 3 * (m->nbody + 1);
    const double fs = vt_test_maxabs(a->jnt_force, n), ns = vt_test_maxabs(a->jnt_moment, n);
    for (int k = 3 * from; k < n; k++) {
        assert_near(a->jnt_force[k], b->jnt_force[k], tol * fs);
        assert_near(a->jnt_moment[k], b->jnt_moment[k], tol * ns);
    }
}

/* vt_scene_spherical_chain: a spherical joint driven by a relative orientation drive
 * (reference −1: its own rotation, three Z–Y–X angles) between two driven revolutes. The kinematic solve's
 * motion given to vt_inverse_dynamics_motion on the model without drives: the same generalized
 * forces (the drive's moment is the spherical joint's three efforts, turned from body 1's
 * axes), the same reactions of every joint (the spherical one's moment 0); the recursive path
 * the same again. (The drive's rows do not move with rate 0, so the first joint's torque is its
 * joint drive's multiplier alone: a drive reacting on the ground would change it.) */
static void test_spherical_joint_drive(void **state)
{
    (void)state;
    vt_model *m, *m0;
    assert_ok(vt_scene_spherical_chain(&m, 1));
    assert_ok(vt_model_without_drives(&m0, m));
    vt_data *d, *d0, *dr;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&d0, m0));
    assert_ok(vt_data_create(&dr, m));
    double worst_q = 0.0, worst_n = 0.0, worst_r = 0.0;
    for (double t = 0.0; t < 2.0; t += 0.37) {
        d->time = t;
        assert_ok(vt_kinematic_solve(m, d, 1e-14, 50));
        { /* the spherical joint's own q is the Z–Y–X turn: q = R_z(f) ⊗ R_y(f2) ⊗ R_x(f3) */
            const vt_drive_def *sd = &m->drive[1];
            const double ez[3] = {0, 0, 1}, ey[3] = {0, 1, 0}, ex[3] = {1, 0, 0};
            double f1[3], f2[3], f3[3], r1[4], r2[4], r3[4], want[4];
            assert_ok(vt_function_eval(f1, &sd->f, t));
            assert_ok(vt_function_eval(f2, &sd->f2, t));
            assert_ok(vt_function_eval(f3, &sd->f3, t));
            vt_quat_axis_angle(r1, ez, f1[0]);
            vt_quat_axis_angle(r2, ey, f2[0]);
            vt_quat_axis_angle(r3, ex, f3[0]);
            vt_quat_mul(want, r1, r2);
            vt_quat_mul(want, want, r3);
            const double *qs = d->q + m->body_qadr[2], sg = qs[0] * want[0] < 0 ? -1.0 : 1.0;
            for (int e = 0; e < 4; e++) assert_near(qs[e], sg * want[e], 1e-12);
        }
        memcpy(d0->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(d0->qd, d->qd, (size_t)m->nv * sizeof(double));
        memcpy(d0->qdd, d->qdd, (size_t)m->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(m0, d0));
        const double qs = vt_test_maxabs(d0->qfrc_drive, m->nv);
        for (int c = 0; c < m->nv; c++) {
            assert_near(d->qfrc_drive[c], d0->qfrc_drive[c], 1e-10 * qs);
            worst_q = fmax(worst_q, fabs(d->qfrc_drive[c] - d0->qfrc_drive[c]) / qs);
        }
        /* the drive's moment on body 2: the spherical joint's efforts (body 1's axes) turned */
        double n[3];
        for (int e = 0; e < 3; e++)
            n[e] = d->A[9 + e] * d0->qfrc_drive[1] + d->A[12 + e] * d0->qfrc_drive[2] + d->A[15 + e] * d0->qfrc_drive[3];
        for (int e = 0; e < 3; e++) {
            assert_near(d->drive_moment[3 + e], n[e], 1e-10 * qs);
            assert_near(d->drive_force[3 + e], 0.0, 0.0);
            worst_n = fmax(worst_n, fabs(d->drive_moment[3 + e] - n[e]) / qs);
        }
        assert_near(d->drive_effort[1], 0.0, 0.0);
        same_reactions(m, d, d0, 1, 1e-10);
        for (int e = 0; e < 3; e++) assert_near(d->jnt_moment[6 + e], 0.0, 1e-10 * qs);
        for (int k = 3; k < 12; k++)
            worst_r = fmax(worst_r, fmax(fabs(d->jnt_force[k] - d0->jnt_force[k]) / vt_test_maxabs(d0->jnt_force, 12),
                                         fabs(d->jnt_moment[k] - d0->jnt_moment[k]) / vt_test_maxabs(d0->jnt_moment, 12)));
        /* the recursive instant on the driven model */
        memcpy(dr->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(dr->qd, d->qd, (size_t)m->nv * sizeof(double));
        dr->time = t;
        assert_ok(vt_inverse_dynamics_recursive(m, dr));
        for (int c = 0; c < m->nv; c++) {
            assert_near(dr->qdd[c], d->qdd[c], 1e-10 * (1 + vt_test_maxabs(d->qdd, m->nv)));
            assert_near(dr->qfrc_drive[c], d->qfrc_drive[c], 1e-10 * qs);
        }
        for (int e = 0; e < 9; e++) assert_near(dr->drive_moment[e], d->drive_moment[e], 1e-10 * qs);
        same_reactions(m, dr, d, 1, 1e-10);
    }
    print_message("spherical joint's drive vs the motion given: generalized forces %.2g, drive moment %.2g, "
                  "reactions %.2g (largest relative differences)\n", worst_q, worst_n, worst_r);

    vt_data_free(d);
    vt_data_free(d0);
    vt_data_free(dr);
    vt_model_free(m);
    vt_model_free(m0);
}

/* Two links on revolute joints; the second's joint drive replaced by a relative orientation
 * drive of link 2 to link 1 about the joint's axis (in link 1's axes, link 2's assembled
 * orientation given as the drive's): the same motion from the kinematic solve, the same
 * generalized forces and reactions (the two rows that repeat the joint's own constraints are
 * dependent: allow_redundant, their multipliers 0 at minimum norm), and the drive's moment
 * the joint torque along the turned axis. */
static vt_model *two_links(int relative)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = relative;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def body = vt_default_body_def();
    body.mass = 3.0;
    const double J[9] = {0.2, 0.02, 0.0, 0.02, 0.05, 0.01, 0.0, 0.01, 0.22};
    memcpy(body.inertia, J, sizeof J);
    body.joint_child[0] = -0.5;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    body.parent = 1;
    body.mass = 1.2;
    body.joint_parent[0] = 0.5; body.joint_parent[2] = 0.1;
    body.joint_child[0] = -0.3; body.joint_child[1] = 0.05;
    body.axis1[0] = 0.0; body.axis1[1] = 0.6; body.axis1[2] = 0.8;
    const double q0[4] = {0.8, 0.2, 0.1, -0.3};
    memcpy(body.orientation, q0, sizeof q0);
    assert_int_equal(vt_builder_add_body(b, &body), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    dr.f = vt_function_sine(0.3, 0.8, 2.0, 0.0);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    dr.body = 2;
    dr.f = vt_function_sine(-0.2, 1.1, 3.0, 0.4);
    if (relative) {
        dr.type = VT_DRIVE_RELATIVE_ORIENTATION;
        dr.reference = 1;
        memcpy(dr.axis, body.axis1, sizeof dr.axis);
        memcpy(dr.orientation, q0, sizeof q0);
    }
    assert_int_equal(vt_builder_add_drive(b, &dr), 1);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

static void test_relative_drive_for_joint_drive(void **state)
{
    (void)state;
    vt_model *mj = two_links(0), *mr = two_links(1);
    vt_data *dj, *drel;
    assert_ok(vt_data_create(&dj, mj));
    assert_ok(vt_data_create(&drel, mr));
    double worst = 0.0;
    for (double t = 0.1; t < 2.0; t += 0.3) {
        dj->time = drel->time = t;
        assert_ok(vt_kinematic_solve(mj, dj, 1e-14, 50));
        assert_ok(vt_kinematic_solve(mr, drel, 1e-14, 50));
        assert_int_equal(drel->rank, 2);
        for (int c = 0; c < 2; c++) {
            assert_near(drel->q[c], dj->q[c], 1e-12);
            assert_near(drel->qd[c], dj->qd[c], 1e-10);
            assert_near(drel->qdd[c], dj->qdd[c], 1e-9);
        }
        const double qs = vt_test_maxabs(dj->qfrc_drive, 2);
        for (int c = 0; c < 2; c++) assert_near(drel->qfrc_drive[c], dj->qfrc_drive[c], 1e-9 * qs);
        assert_near(drel->drive_effort[0], dj->drive_effort[0], 1e-9 * qs);
        same_reactions(mj, drel, dj, 1, 1e-9);
        double u[3]; /* the joint axis, global: link 1's axes turned */
        for (int e = 0; e < 3; e++)
            u[e] = dj->A[9 + e] * mj->body_axis[12] + dj->A[12 + e] * mj->body_axis[13] + dj->A[15 + e] * mj->body_axis[14];
        for (int e = 0; e < 3; e++) {
            const double want = dj->drive_effort[1] * u[e];
            assert_near(drel->drive_moment[3 + e], want, 1e-9 * qs);
            worst = fmax(worst, fabs(drel->drive_moment[3 + e] - want) / qs);
        }
    }
    print_message("relative drive for a joint drive: drive moment vs torque × axis %.2g (relative)\n", worst);
    vt_data_free(dj);
    vt_data_free(drel);
    vt_model_free(mj);
    vt_model_free(mr);
}

/* ---- a driven rate whose inertia is round-off of its lever arm from the reference point -------
 * A slider along x (body 1, point mass m1, its joint point L from its centre of mass along y)
 * carries a point mass m2 on a revolute joint about z at body 1's centre, at ℓ from the axis.
 * At θ = π/2, θ̇ = ẋ = 0, with θ̈ driven and no gravity (Lagrange, exact):
 *   (m1 + m2) ẍ − m2 ℓ sin θ θ̈ = 0,   τ = m2 ℓ² θ̈ − m2 ℓ sin θ ẍ = m2 ℓ² θ̈ m1 / (m1 + m2).
 * The reference point o is the slider's joint point, L from the masses. Summed from lever arms
 * from o, M*_θθ = m2 ℓ² came from terms of m2 (2L)², round-off of them when L ≫ ℓ / sqrt(τ ε): at
 * L = 1e9 the dense answer was once τ = 0, ẍ = 0 with VT_OK, then a refusal ("no certain
 * digit"). The dense S now takes each lever arm along the tree (kinematics.c, vt_lever): the
 * revolute joint's is the link's own ℓ, exact at any L, so the dense path solves to 64 ε at every
 * L. The recursive articulated route (the driven rate's acceleration through the body's inertia
 * about its joint point, with positions from o: round-off ε m2 L ℓ against m2 ℓ²) solves to
 * 64 ε (1 + L/ℓ). */
static vt_model *long_link(double L, double m1, double m2, double ell, double thdd)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = md.gravity[2] = 0.0;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_TRANSLATIONAL;
    body.axis1[0] = 1.0, body.axis1[1] = 0.0, body.axis1[2] = 0.0;
    body.mass = m1;
    body.joint_child[1] = L;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    body = vt_default_body_def();
    body.parent = 1;
    body.joint = VT_JOINT_REVOLUTE;
    body.axis1[0] = 0.0, body.axis1[1] = 0.0, body.axis1[2] = 1.0;
    body.mass = m2;
    body.joint_child[0] = -ell; /* the centre of mass ℓ along the body's x from the axis */
    assert_int_equal(vt_builder_add_body(b, &body), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 2;
    const double c[3] = {1.5707963267948966, 0.0, thdd / 2};
    dr.f = vt_function_polynomial(3, c);
    assert_true(vt_builder_add_drive(b, &dr) >= 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

static void test_long_link_roundoff_inertia(void **state)
{
    (void)state;
    const double m1 = 3.0, m2 = 2.0, ell = 1.5, thdd = 4.0;
    const double tau = m2 * ell * ell * thdd * m1 / (m1 + m2), xdd = m2 * ell * thdd / (m1 + m2);
    const double Ls[3] = {10.0, 1e5, 1e9};
    for (int k = 0; k < 3; k++) {
        const double L = Ls[k];
        vt_model *m = long_link(L, m1, m2, ell, thdd);
        vt_data *dd, *dr;
        assert_ok(vt_data_create(&dd, m));
        assert_ok(vt_data_create(&dr, m));
        dd->q[1] = dr->q[1] = 1.5707963267948966;
        const vt_status sd = vt_inverse_dynamics(m, dd), sr = vt_inverse_dynamics_recursive(m, dr);
        print_message("L = %g: dense %s (%s) effort %.17g, recursive %s (%s) effort %.17g, exact %.17g\n", L,
                      vt_status_string(sd), dd->message, dd->drive_effort[0],
                      vt_status_string(sr), dr->message, dr->drive_effort[0], tau);
        const double eps = 2.220446049250313e-16, tol = 64.0 * eps * (1.0 + L / ell); /* positions from o */
        assert_ok(sd);
        assert_near(dd->drive_effort[0], tau, 64.0 * eps * tau);
        assert_near(dd->qdd[0], xdd, 64.0 * eps * xdd);
        assert_ok(sr);
        assert_near(dr->drive_effort[0], tau, tol * tau);
        assert_near(dr->qdd[0], xdd, tol * xdd);
        vt_data_free(dd);
        vt_data_free(dr);
        vt_model_free(m);
    }
}

/* ---- reactions in the joint's frame and the bearing split ------------------------------ */

/* A revolute, a universal and a translational joint, axes and orientations off the body axes */
static const double jf_q[4] = {0.3, -0.7, 0.4, 0.25}, jf_qd[4] = {1.1, -0.6, 0.9, -0.4},
                    jf_qdd[4] = {0.5, 1.3, -0.8, 0.7};

static void jf_defs(vt_body_def d[4])
{
    static const double J[3][9] = {{0.30, 0.02, -0.01, 0.02, 0.25, 0.03, -0.01, 0.03, 0.20},
                                   {0.12, -0.01, 0.02, -0.01, 0.10, 0.01, 0.02, 0.01, 0.08},
                                   {0.05, 0.01, 0.0, 0.01, 0.04, -0.005, 0.0, -0.005, 0.06}};
    static const double q0[3][4] = {{0.9, 0.1, -0.3, 0.2}, {0.8, -0.2, 0.3, 0.1}, {0.7, 0.3, 0.1, -0.4}};
    static const double jp[3][3] = {{0.1, -0.2, 0.3}, {0.4, 0.1, -0.1}, {0.2, 0.3, -0.1}};
    static const double jc[3][3] = {{-0.3, 0.1, 0.05}, {0.05, -0.25, 0.1}, {0.1, 0.0, -0.2}};
    static const double a1[3][3] = {{1.0 / 3, 2.0 / 3, 2.0 / 3}, {0.0, 0.6, 0.8}, {0.48, 0.6, 0.64}};
    static const vt_joint_type kind[3] = {VT_JOINT_REVOLUTE, VT_JOINT_UNIVERSAL, VT_JOINT_TRANSLATIONAL};
    static const double mass[3] = {2.0, 1.5, 0.8};
    for (int k = 1; k <= 3; k++) {
        d[k] = vt_default_body_def();
        d[k].parent = k - 1;
        d[k].joint = kind[k - 1];
        d[k].mass = mass[k - 1];
        memcpy(d[k].inertia, J[k - 1], sizeof d[k].inertia);
        memcpy(d[k].joint_parent, jp[k - 1], sizeof d[k].joint_parent);
        memcpy(d[k].joint_child, jc[k - 1], sizeof d[k].joint_child);
        memcpy(d[k].axis1, a1[k - 1], sizeof d[k].axis1);
        const double nq = sqrt(q0[k - 1][0] * q0[k - 1][0] + q0[k - 1][1] * q0[k - 1][1] + q0[k - 1][2] * q0[k - 1][2] +
                               q0[k - 1][3] * q0[k - 1][3]);
        for (int c = 0; c < 4; c++) d[k].orientation[c] = q0[k - 1][c] / nq;
    }
    d[2].axis2[0] = 1.0, d[2].axis2[1] = d[2].axis2[2] = 0.0; /* ⟂ (0, 0.6, 0.8) */
}

/* drives: 1 adds a joint drive on every rate with q, q̇, q̈ of jf_* at t = 0 */
static vt_model *jf_model(int drives, vt_layout layout)
{
    vt_body_def d[4];
    jf_defs(d);
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = 0.5, md.gravity[1] = -9.81, md.gravity[2] = 1.2;
    md.layout = layout;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    for (int k = 1; k <= 3; k++) assert_int_equal(vt_builder_add_body(b, &d[k]), k);
    for (int c = 0, k = 1; drives && k <= 3; k++)
        for (int a = 0; a < (k == 2 ? 2 : 1); a++, c++) {
            const double coef[3] = {jf_q[c], jf_qd[c], 0.5 * jf_qdd[c]};
            vt_test_add_joint_drive(b, k, a, vt_function_polynomial(3, coef));
        }
    return vt_test_build(b);
}

/* the documented frame of a hand-built joint, from the definition alone: z along the joint's axis
 * in body axes (A0^T axis1), x the body axis least aligned with it made ⟂, y = z × x; a universal's
 * x along A0^T axis2. Columns: the frame's axes in body axes; bear: the bearing axis in the frame */
static void jf_documented(const vt_body_def *d, double C[9], double bear[3])
{
    double A0[9], z[3], x[3] = {0, 0, 0}, y[3];
    vt_ne_quat(A0, d->orientation);
    vt_ne_mtv(z, A0, d->axis1);
    if (d->joint == VT_JOINT_UNIVERSAL) {
        vt_ne_mtv(x, A0, d->axis2);
    } else {
        int k = 0;
        for (int j = 1; j < 3; j++)
            if (fabs(z[j]) < fabs(z[k])) k = j;
        x[k] = 1.0;
        for (int c = 0; c < 3; c++) x[c] -= z[k] * z[c];
        const double nx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        for (int c = 0; c < 3; c++) x[c] /= nx;
    }
    vt_ne_cross(y, z, x);
    for (int c = 0; c < 3; c++) C[c] = x[c], C[3 + c] = y[c], C[6 + c] = z[c];
    bear[0] = d->joint == VT_JOINT_UNIVERSAL, bear[1] = 0.0, bear[2] = d->joint != VT_JOINT_UNIVERSAL;
}

/* every joint's reaction in its frame, and its bearing split, against the chain's Newton–Euler */
static void jf_check(const vt_model *m, const vt_data *d, const double *C, const double *bear, const double *Rbody,
                     const double *Fr, const double *Mr, double scale)
{
    for (int k = 1; k <= m->nbody; k++) {
        double Rj[9], fj[3], mj[3];
        vt_ne_mul(Rj, Rbody + 9 * k, C + 9 * k); /* the joint frame, global */
        vt_ne_mtv(fj, Rj, Fr + 3 * k);
        vt_ne_mtv(mj, Rj, Mr + 3 * k);
        for (int c = 0; c < 3; c++) {
            assert_near(d->jnt_force_joint[3 * k + c], fj[c], 1e-12 * scale);
            assert_near(d->jnt_moment_joint[3 * k + c], mj[c], 1e-12 * scale);
        }
        const double *a = bear + 3 * k, fa = a[0] * fj[0] + a[1] * fj[1] + a[2] * fj[2],
                     ma = a[0] * mj[0] + a[1] * mj[1] + a[2] * mj[2];
        double fr = 0.0, mr = 0.0;
        for (int c = 0; c < 3; c++) fr += (fj[c] - fa * a[c]) * (fj[c] - fa * a[c]), mr += (mj[c] - ma * a[c]) * (mj[c] - ma * a[c]);
        const double *b = d->jnt_bearing + 4 * k;
        assert_near(b[0], fa, 1e-12 * scale);
        assert_near(b[1], sqrt(fr), 1e-12 * scale);
        assert_near(b[2], ma, 1e-12 * scale);
        assert_near(b[3], sqrt(mr), 1e-12 * scale);
    }
}

static void test_joint_frame_hand_built(void **state)
{
    (void)state;
    vt_body_def def[4];
    jf_defs(def);
    vt_ne_body nb[4];
    memset(nb, 0, sizeof nb);
    double C[9 * 4] = {0}, bear[3 * 4] = {0};
    for (int k = 1; k <= 3; k++) {
        vt_ne_body *B = &nb[k];
        B->parent = k - 1;
        B->kind = def[k].joint == VT_JOINT_REVOLUTE ? 0 : def[k].joint == VT_JOINT_UNIVERSAL ? 1 : 2;
        memcpy(B->s_par, def[k].joint_parent, sizeof B->s_par);
        B->pre[0] = B->pre[4] = B->pre[8] = 1.0;
        memcpy(B->u1, def[k].axis1, sizeof B->u1);
        memcpy(B->u2, def[k].axis2, sizeof B->u2);
        vt_ne_quat(B->post, def[k].orientation);
        memcpy(B->s_child, def[k].joint_child, sizeof B->s_child);
        B->mass = def[k].mass;
        memcpy(B->J, def[k].inertia, sizeof B->J);
        jf_documented(&def[k], C + 9 * k, bear + 3 * k);
    }
    vt_model *m = jf_model(0, VT_LAYOUT_FULL);
    double F[12], M[12], Fr[12], Mr[12], R[36];
    vt_ne_chain(nb, 3, jf_q, jf_qd, jf_qdd, m->gravity, F, M, Fr, Mr, R);
    double scale = 0.0;
    for (int k = 3; k < 12; k++) scale = fmax(scale, fmax(fabs(F[k]), fabs(M[k])));
    /* the model's frames and axes are the documented ones */
    for (int k = 1; k <= 3; k++) {
        double A[9];
        vt_euler_A(A, m->jnt_frame + 4 * k);
        for (int c = 0; c < 9; c++) assert_near(A[c], C[9 * k + c], 1e-15);
        for (int c = 0; c < 3; c++) assert_near(m->jnt_frame_axis[3 * k + c], bear[3 * k + c], 1e-15);
    }
    /* the given motion (fused passes), on both layouts */
    for (int lay = 0; lay < 2; lay++) {
        vt_model *ml = lay ? jf_model(0, VT_LAYOUT_RECURSIVE) : m;
        vt_data *d;
        assert_ok(vt_data_create(&d, ml));
        memcpy(d->q, jf_q, sizeof jf_q);
        memcpy(d->qd, jf_qd, sizeof jf_qd);
        memcpy(d->qdd, jf_qdd, sizeof jf_qdd);
        assert_ok(vt_inverse_dynamics_motion(ml, d));
        for (int k = 1; k <= 3; k++) /* the library's global reaction is the same Newton–Euler */
            for (int c = 0; c < 3; c++) assert_near(d->jnt_force[3 * k + c], Fr[3 * k + c], 1e-12 * scale);
        assert_ok(vt_reactions_joint_frame(ml, d));
        jf_check(ml, d, C, bear, R, Fr, Mr, scale);
        vt_data_free(d);
        if (lay) vt_model_free(ml);
    }
    /* the same motion driven: the dense stages and the recursive joint-driven passes */
    vt_model *md = jf_model(1, VT_LAYOUT_FULL);
    for (int path = 0; path < 2; path++) {
        vt_data *d;
        assert_ok(vt_data_create(&d, md));
        memcpy(d->q, jf_q, sizeof jf_q);
        memcpy(d->qd, jf_qd, sizeof jf_qd);
        d->time = 0.0;
        assert_ok(path ? vt_inverse_dynamics_recursive(md, d) : vt_inverse_dynamics(md, d));
        assert_ok(vt_reactions_joint_frame(md, d));
        jf_check(md, d, C, bear, R, Fr, Mr, scale);
        vt_data_free(d);
    }
    vt_model_free(md);
    vt_model_free(m);
}

/* a joint frame given in the definition is the model's, and the bearing axis is the joint's axis
 * in it; a frame of zero norm is the documented one, NaN refused */
static void test_joint_frame_given(void **state)
{
    (void)state;
    vt_body_def d[4];
    jf_defs(d);
    const double p[4] = {0.5, 0.5, -0.5, 0.5}; /* a turn of 120° about (1, −1, 1) */
    for (int c = 0; c < 4; c++) d[1].joint_frame[c] = 2.0 * p[c]; /* normalized by the builder */
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_int_equal(vt_builder_add_body(b, &d[1]), 1);
    d[2].joint_frame[0] = NAN;
    assert_int_equal(vt_builder_add_body(b, &d[2]), VT_ERR_NONFINITE);
    vt_model *m = vt_test_build(b);
    for (int c = 0; c < 4; c++) assert_near(m->jnt_frame[4 + c], p[c], 1e-16);
    double A0[9], a[3], C[9], ab[3];
    vt_ne_quat(A0, d[1].orientation);
    vt_ne_mtv(a, A0, d[1].axis1); /* body axes */
    vt_ne_quat(C, p);
    vt_ne_mtv(ab, C, a);
    for (int c = 0; c < 3; c++) assert_near(m->jnt_frame_axis[3 + c], ab[c], 1e-15);
    vt_model_free(m);
}

/* the bearing split of reactions near 1e200 N, whose squares overflow: the magnitudes across the
 * axis against hypot of the joint-frame components (libm's, scaled) */
static void test_bearing_split_huge(void **state)
{
    (void)state;
    vt_model *m = jf_model(0, VT_LAYOUT_FULL);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    memcpy(d->q, jf_q, sizeof jf_q);
    d->xfrc[6 * 3 + 0] = 3e200, d->xfrc[6 * 3 + 1] = -4e200, d->xfrc[6 * 3 + 2] = 1e200; /* on body 3 */
    assert_ok(vt_inverse_dynamics_motion(m, d));
    assert_ok(vt_reactions_joint_frame(m, d));
    for (int k = 1; k <= 3; k++) {
        const double *fj = d->jnt_force_joint + 3 * k, *mj = d->jnt_moment_joint + 3 * k, *a = m->jnt_frame_axis + 3 * k;
        const double *b = d->jnt_bearing + 4 * k;
        const double fa = a[0] * fj[0] + a[1] * fj[1] + a[2] * fj[2], ma = a[0] * mj[0] + a[1] * mj[1] + a[2] * mj[2];
        const double fr = hypot(hypot(fj[0] - fa * a[0], fj[1] - fa * a[1]), fj[2] - fa * a[2]);
        const double mr = hypot(hypot(mj[0] - ma * a[0], mj[1] - ma * a[1]), mj[2] - ma * a[2]);
        assert_true(fr > 1e199 && isfinite(b[1]) && isfinite(b[3]));
        assert_near(b[1], fr, 1e-14 * fr);
        assert_near(b[3], mr, 1e-14 * mr);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* ---- limits flagged, strictly ------------------------------------------------------------ */

/* jf_model with limits on every rate from the values x (q, q̇ and the efforts e of the instant):
 * mode 1 exactly at them (upper = q on even rates, lower = q on odd ones, |q̇|, |e|), mode 2 one
 * ulp inside them, so that the instant's values are one ulp beyond */
static vt_model *limits_model(int drives, int mode, const double *q, const double *qd, const double *e)
{
    vt_body_def d[4];
    jf_defs(d);
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = 0.5, md.gravity[1] = -9.81, md.gravity[2] = 1.2;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    for (int c = 0, k = 1; k <= 3; k++) {
        for (int a = 0; a < (k == 2 ? 2 : 1); a++, c++) {
            const int in = mode == 2;
            if (c % 2 == 0) d[k].limit_upper[a] = in ? nextafter(q[c], -HUGE_VAL) : q[c];
            else d[k].limit_lower[a] = in ? nextafter(q[c], HUGE_VAL) : q[c];
            d[k].limit_velocity[a] = in ? nextafter(fabs(qd[c]), 0.0) : fabs(qd[c]);
            d[k].limit_effort[a] = in ? nextafter(fabs(e[c]), 0.0) : fabs(e[c]);
        }
        assert_int_equal(vt_builder_add_body(b, &d[k]), k);
    }
    for (int c = 0, k = 1; drives && k <= 3; k++)
        for (int a = 0; a < (k == 2 ? 2 : 1); a++, c++) {
            const double coef[3] = {jf_q[c], jf_qd[c], 0.5 * jf_qdd[c]};
            vt_test_add_joint_drive(b, k, a, vt_function_polynomial(3, coef));
        }
    return vt_test_build(b);
}

/* path 0: the given motion; 1: the dense stages, driven; 2: the recursive passes, driven */
static void limits_solve(const vt_model *m, vt_data *d, int path)
{
    memcpy(d->q, jf_q, sizeof jf_q);
    memcpy(d->qd, jf_qd, sizeof jf_qd);
    memcpy(d->qdd, jf_qdd, sizeof jf_qdd);
    d->time = 0.0;
    assert_ok(path == 0 ? vt_inverse_dynamics_motion(m, d)
                        : path == 1 ? vt_inverse_dynamics(m, d) : vt_inverse_dynamics_recursive(m, d));
}

static void test_limits_strict(void **state)
{
    (void)state;
    for (int path = 0; path < 3; path++) {
        const int drives = path > 0;
        double e[4];
        vt_model *m0 = jf_model(drives, VT_LAYOUT_FULL);
        vt_data *d;
        assert_ok(vt_data_create(&d, m0));
        limits_solve(m0, d, path);
        memcpy(e, d->qfrc_drive, sizeof e);
        assert_int_equal(d->nlimit, 0); /* no limits: nothing beyond */
        assert_int_equal(d->warning & VT_WARN_LIMIT, 0);
        for (int k = 0; k < 12; k++) assert_true(d->limit_excess[k] == 0.0);
        vt_data_free(d);
        vt_model_free(m0);
        for (int mode = 1; mode <= 2; mode++) {
            vt_model *m = limits_model(drives, mode, jf_q, jf_qd, e);
            assert_ok(vt_data_create(&d, m));
            limits_solve(m, d, path);
            for (int c = 0; c < 4; c++) assert_true(d->qfrc_drive[c] == e[c]); /* the limits change no effort */
            if (mode == 1) { /* exactly at every limit: none passed */
                assert_int_equal(d->nlimit, 0);
                assert_int_equal(d->warning & VT_WARN_LIMIT, 0);
                for (int k = 0; k < 12; k++) assert_true(d->limit_excess[k] == 0.0);
            } else { /* one ulp beyond every one: each flagged, by the value less the limit */
                assert_int_equal(d->nlimit, 12);
                assert_int_equal(d->warning & VT_WARN_LIMIT, VT_WARN_LIMIT);
                for (int c = 0; c < 4; c++) {
                    const double *lim = m->dof_limit + 4 * c, *x = d->limit_excess + 3 * c;
                    assert_true(x[0] == jf_q[c] - (c % 2 == 0 ? lim[1] : lim[0]));
                    assert_true(x[0] != 0.0 && (x[0] > 0.0) == (c % 2 == 0));
                    assert_true(x[1] == (jf_qd[c] > 0.0 ? jf_qd[c] - lim[2] : jf_qd[c] + lim[2]));
                    assert_true(x[2] == (e[c] > 0.0 ? e[c] - lim[3] : e[c] + lim[3]));
                    assert_true(x[1] != 0.0 && x[2] != 0.0);
                }
            }
            vt_data_free(d);
            vt_model_free(m);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_link_exact),
        cmocka_unit_test(test_power_balance),
        cmocka_unit_test(test_newton_euler_every_body),
        cmocka_unit_test(test_reaction_orthogonality),
        cmocka_unit_test(test_drive_cartesian_force),
        cmocka_unit_test(test_fourbar),
        cmocka_unit_test(test_fourbar_rusr),
        cmocka_unit_test(test_fourbar_planar_pin),
        cmocka_unit_test(test_slider_crank_planar_pin),
        cmocka_unit_test(test_planar_pin_off_plane),
        cmocka_unit_test(test_total_wrench_subtree),
        cmocka_unit_test(test_extreme_scales),
        cmocka_unit_test(test_spherical_through_gimbal_lock),
        cmocka_unit_test(test_coupling),
        cmocka_unit_test(test_unique_despite_redundant_row),
        cmocka_unit_test(test_spherical_joint_drive),
        cmocka_unit_test(test_relative_drive_for_joint_drive),
        cmocka_unit_test(test_long_link_roundoff_inertia),
        cmocka_unit_test(test_joint_frame_hand_built),
        cmocka_unit_test(test_joint_frame_given),
        cmocka_unit_test(test_bearing_split_huge),
        cmocka_unit_test(test_limits_strict),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
