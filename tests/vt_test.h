/* Shared by the CMocka test files: includes, a double compare, and quantities computed
 * independently of the library (energies from body velocities, dense products). */
#ifndef VT_TEST_H
#define VT_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "scenes.h"

/* CMocka 1.1.5 has no floating-point compare: this one prints both values. */
#define assert_near(a, b, tol)                                                                 \
    do {                                                                                       \
        const double a_ = (a), b_ = (b), t_ = (tol);                                           \
        if (!(fabs(a_ - b_) <= t_))                                                            \
            fail_msg("%s = %.17g, %s = %.17g: |diff| %.3g > %.3g", #a, a_, #b, b_,             \
                     fabs(a_ - b_), t_);                                                       \
    } while (0)

#define assert_ok(call)                                                                        \
    do {                                                                                       \
        const vt_status s_ = (call);                                                           \
        if (s_ != VT_OK) fail_msg("%s -> %d (%s)", #call, (int)s_, vt_status_string(s_));      \
    } while (0)

/* LAPACK, for independent checks */
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info, size_t l);
void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b, const int *ldb,
            int *info);

/* The Schur complement S = P M^-1 P^T of the n x n M and the nc x n P (column-major, leading
 * dimensions n and nc), by LAPACK's dgesv on copies, scaled to unit diagonal, and its exact
 * 1-norm reciprocal condition 1 / (‖S‖₁ ‖S^-1‖₁), which it returns */
static inline double vt_test_schur_rcond(const double *M, const double *P, int n, int nc)
{
    double *A = malloc(sizeof(double) * (size_t)(n * n + 2 * n * nc + 2 * nc * nc));
    int *ipiv = malloc(sizeof(int) * (size_t)(n + nc)), info = 0;
    assert_non_null(A);
    assert_non_null(ipiv);
    double *W = A + n * n, *S = W + n * nc, *X = S + nc * nc;
    memcpy(A, M, sizeof(double) * (size_t)(n * n));
    for (int r = 0; r < nc; r++)
        for (int a = 0; a < n; a++) W[a + r * n] = P[r + a * nc];
    dgesv_(&n, &nc, A, &n, ipiv, W, &n, &info);
    assert_int_equal(info, 0);
    for (int i = 0; i < nc; i++)
        for (int j = 0; j < nc; j++) {
            double v = 0.0;
            for (int a = 0; a < n; a++) v += P[i + a * nc] * W[a + j * n];
            S[i + j * nc] = v;
            X[i + j * nc] = i == j;
        }
    for (int j = 0; j < nc; j++) /* to unit diagonal: the rows' independence, not their sizes */
        for (int i = 0; i < nc; i++)
            if (i != j) S[i + j * nc] /= sqrt(S[i + i * nc] * S[j + j * nc]);
    for (int i = 0; i < nc; i++) S[i + i * nc] = 1.0;
    double sn = 0.0, xn = 0.0;
    for (int c = 0; c < nc; c++) {
        double cs = 0.0;
        for (int r = 0; r < nc; r++) cs += fabs(S[r + c * nc]);
        sn = fmax(sn, cs);
    }
    dgesv_(&nc, &nc, S, &nc, ipiv, X, &nc, &info);
    assert_int_equal(info, 0);
    for (int c = 0; c < nc; c++) {
        double cs = 0.0;
        for (int r = 0; r < nc; r++) cs += fabs(X[r + c * nc]);
        xn = fmax(xn, cs);
    }
    free(A);
    free(ipiv);
    return 1.0 / (sn * xn);
}

/* ρ, the radius of gyration of all bodies about their common centre of mass, from the model's
 * masses and inertias and the bodies' positions: ρ² Σ m = Σ (tr J'/2 + m |c − c_G|²) */
static inline double vt_test_gyration_radius(const vt_model *m, const vt_data *d)
{
    double mt = 0.0, cg[3] = {0, 0, 0}, i2 = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        mt += m->body_mass[i];
        for (int k = 0; k < 3; k++) cg[k] += m->body_mass[i] * d->x[7 * (i - 1) + k];
    }
    for (int k = 0; k < 3; k++) cg[k] /= mt;
    for (int i = 1; i <= m->nbody; i++) {
        const double *J = m->body_inertia + 9 * i;
        double r2 = 0.0;
        for (int k = 0; k < 3; k++) r2 += (d->x[7 * (i - 1) + k] - cg[k]) * (d->x[7 * (i - 1) + k] - cg[k]);
        i2 += 0.5 * (J[0] + J[4] + J[8]) + m->body_mass[i] * r2;
    }
    return sqrt(i2 / mt);
}

#ifdef VT_MODEL_MODEL_H /* the rows' kinds (con_kind): tests that include src/model/model.h first */
/* 1 when rate a turns (a rotation, an Euler parameter), 0 when it translates */
static inline int vt_test_rate_turns(const vt_model *m, int a)
{
    const int i = m->dof_body[a];
    return !(m->body_joint[i] == VT_JOINT_TRANSLATIONAL || (m->body_joint[i] == VT_JOINT_CYLINDRICAL && a > m->body_vadr[i]) ||
             (m->body_joint[i] == VT_JOINT_FREE && a < m->body_vadr[i] + 3) ||
             (m->body_joint[i] == VT_JOINT_BASE && a < m->body_vadr[i] + 3));
}

/* The velocity a unit rate a gives the point u' of body b (0: the ground), from the dense S
 * (vt_kinematics): V = ṙ_a + ω_a × (A u'), ω_a = 2 E(p) ṗ_a */
static inline void vt_test_point_rate(const vt_model *m, const vt_data *d, int b, const double *u, int a, double V[3])
{
    V[0] = V[1] = V[2] = 0.0;
    if (b == 0) return;
    const int o = 7 * (b - 1);
    const double *A = d->A + 9 * b, *p = d->x + o + 3, *Sa = d->S + (size_t)a * (size_t)m->nx + o;
    const double E[12] = {-p[1], -p[2], -p[3], p[0], p[3], -p[2], -p[3], p[0], p[1], p[2], -p[1], p[0]};
    double w[3] = {0, 0, 0}, Au[3];
    for (int i = 0; i < 3; i++) {
        Au[i] = A[i] * u[0] + A[i + 3] * u[1] + A[i + 6] * u[2];
        for (int j = 0; j < 4; j++) w[i] += 2.0 * E[i + 3 * j] * Sa[3 + j];
    }
    V[0] = Sa[0] + w[1] * Au[2] - w[2] * Au[1];
    V[1] = Sa[1] + w[2] * Au[0] - w[0] * Au[2];
    V[2] = Sa[2] + w[0] * Au[1] - w[1] * Au[0];
}

/* ℓ, the rows' lever arm (docs/method.md, "The condition estimate"), from the dense S: the
 * largest, over the point and line rows and the rates that turn, of |V_b − V_a|, the velocity a
 * unit rate gives the row's point on body b less that of its point on body a (a line row: less
 * that of body a's point at P_b, the body that carries the line) (differences below 1e-13 of
 * their terms taken as round-off); without any, the reciprocal of the largest column norm of the
 * couplings whose first rate turns on rates that translate; without either, 1 */
static inline double vt_test_rows_length(const vt_model *m, const vt_data *d)
{
    double arm = 0.0, inv = 0.0;
    for (int r = 0; r < m->nc; r++) {
        if (m->con_kind[r] != VT_ROW_POINT && m->con_kind[r] != VT_ROW_LINE) continue;
        for (int a = 0; a < m->nv; a++) {
            if (!vt_test_rate_turns(m, a)) continue;
            double Va[3], Vb[3], W = 0.0, T = 0.0, ua[3];
            const int ba = m->con_body[2 * r];
            memcpy(ua, m->con_point + 6 * r, sizeof ua);
            if (m->con_kind[r] == VT_ROW_LINE && ba > 0) { /* P_b in body a's axes, from its centre */
                const int bb = m->con_body[2 * r + 1];
                const double *ub = m->con_point + 6 * r + 3, *Aa = d->A + 9 * ba, *ra = d->x + 7 * (ba - 1);
                double Pb[3] = {0, 0, 0};
                if (bb > 0) {
                    const double *Ab = d->A + 9 * bb, *rb = d->x + 7 * (bb - 1);
                    for (int i = 0; i < 3; i++) Pb[i] = rb[i] + Ab[i] * ub[0] + Ab[i + 3] * ub[1] + Ab[i + 6] * ub[2];
                } else {
                    for (int i = 0; i < 3; i++) Pb[i] = ub[i];
                }
                for (int i = 0; i < 3; i++)
                    ua[i] = Aa[3 * i] * (Pb[0] - ra[0]) + Aa[3 * i + 1] * (Pb[1] - ra[1]) + Aa[3 * i + 2] * (Pb[2] - ra[2]);
            }
            vt_test_point_rate(m, d, ba, ua, a, Va);
            vt_test_point_rate(m, d, m->con_body[2 * r + 1], m->con_point + 6 * r + 3, a, Vb);
            for (int k = 0; k < 3; k++) {
                W += (Vb[k] - Va[k]) * (Vb[k] - Va[k]);
                T += Va[k] * Va[k] + Vb[k] * Vb[k];
            }
            if (sqrt(W) > 1e-13 * sqrt(T)) arm = fmax(arm, sqrt(W));
        }
    }
    if (arm == 0.0)
        for (int a = 0; a < m->nv; a++) {
            if (vt_test_rate_turns(m, a)) continue;
            double n2 = 0.0;
            for (int r = 0; r < m->nc; r++) {
                int first = 0;
                while (first < m->nv - 1 && d->Phiq[r + first * m->nc] == 0.0) first++;
                const double v = d->Phiq[r + a * m->nc];
                if (m->con_kind[r] == VT_ROW_COUPLING && vt_test_rate_turns(m, first)) n2 += v * v;
            }
            inv = fmax(inv, sqrt(n2));
        }
    return arm > 0.0 ? arm : inv > 0.0 ? 1.0 / inv : 1.0;
}
#endif

/* The smallest grip² of the point drives' rows (1 without any), from the dense S (vt_kinematics):
 * rate a moves the driven point P = r + A u' of body b by V_a = ṙ_a + ω_a × (A u'), ω_a = 2 E(p) ṗ_a
 * (ṙ_a, ṗ_a: S's rows of b, column a); the row's grip is ‖(e·V_a C_a)‖ / ‖(|V_a| C_a)‖ with e the
 * driven direction and C_a = 1/ρ for a rate that turns (ρ: rho), 1 for one that translates */
static inline double vt_test_grip2(const vt_model *m, const vt_data *d, double rho)
{
    double worst = 1.0;
    for (int k = 0; k < m->ndrive; k++) {
        const vt_drive_def *dr = m->drive + k;
        if (dr->type != VT_DRIVE_POINT) continue;
        const int b = dr->body, o = 7 * (b - 1);
        const double *A = d->A + 9 * b, *p = d->x + o + 3;
        double u[3], num = 0.0, den = 0.0;
        for (int i = 0; i < 3; i++) u[i] = A[i] * dr->point[0] + A[i + 3] * dr->point[1] + A[i + 6] * dr->point[2];
        const double E[12] = {-p[1], -p[2], -p[3], p[0], p[3], -p[2], -p[3], p[0], p[1], p[2], -p[1], p[0]};
        for (int a = 0; a < m->nv; a++) {
            const double *Sa = d->S + (size_t)a * (size_t)m->nx + o;
            double w[3] = {0, 0, 0}, V[3];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 4; j++) w[i] += 2.0 * E[i + 3 * j] * Sa[3 + j];
            V[0] = Sa[0] + w[1] * u[2] - w[2] * u[1];
            V[1] = Sa[1] + w[2] * u[0] - w[0] * u[2];
            V[2] = Sa[2] + w[0] * u[1] - w[1] * u[0];
            const int i = m->dof_body[a], turn = !(m->body_joint[i] == VT_JOINT_TRANSLATIONAL ||
                                                   (m->body_joint[i] == VT_JOINT_CYLINDRICAL && a > m->body_vadr[i]) ||
                                                   (m->body_joint[i] == VT_JOINT_FREE && a < m->body_vadr[i] + 3) ||
                                                   (m->body_joint[i] == VT_JOINT_BASE && a < m->body_vadr[i] + 3));
            const double ca = turn ? 1.0 / rho : 1.0, e = V[dr->index] * ca;
            num += e * e;
            den += (V[0] * V[0] + V[1] * V[1] + V[2] * V[2]) * ca * ca;
        }
        worst = fmin(worst, den > 0.0 ? num / den : 0.0);
    }
    return worst;
}

#ifdef VT_MODEL_MODEL_H
/* The Schur and articulated routes' condition (docs/method.md, "The condition estimate"), from
 * the dense path's M* and Φ_q by LAPACK, on the system left once the joint-driven rates (D) are
 * known: the exact 1-norm condition of the other rows' S = Φ_oF M*_FF^-1 Φ_oF^T (F the free
 * rates, o the rows but the joint drives; vt_test_schur_rcond) times min/max of M*_FF's pivots
 * taken in descending rate order (the Cholesky factor of M*_FF scaled to unit diagonal, rows and
 * columns reversed: L_kk²) times the point drives' grip² (vt_test_grip2). */
static inline double vt_test_known_rcond(const vt_model *m, const vt_data *dd)
{
    int *fr = calloc((size_t)m->nv, sizeof(int)), nf = 0, info = 0, *orow = calloc((size_t)m->nc + 1, sizeof(int)), no = 0;
    assert_non_null(fr);
    assert_non_null(orow);
    for (int a = 0; a < m->nv; a++)
        if (m->dof_drive[a] < 0) fr[nf++] = a;
    for (int r = 0; r < m->nc; r++)
        if (m->con_kind[r] != VT_ROW_JOINT) orow[no++] = r;
    double *Mff = calloc((size_t)nf * (size_t)nf + 1, sizeof(double)), *Pof = calloc((size_t)no * (size_t)nf + 1, sizeof(double));
    assert_non_null(Mff);
    assert_non_null(Pof);
    for (int c = 0; c < nf; c++) {
        for (int r = 0; r < nf; r++) Mff[r + c * nf] = dd->Mstar[fr[r] + fr[c] * m->nv];
        for (int r = 0; r < no; r++) Pof[r + c * no] = dd->Phiq[orow[r] + fr[c] * m->nc];
    }
    const double schur = no > 0 ? vt_test_schur_rcond(Mff, Pof, nf, no) * vt_test_grip2(m, dd, vt_test_rows_length(m, dd)) : 1.0;
    free(Mff);
    free(Pof);
    free(orow);
    double *K = calloc((size_t)nf * (size_t)nf, sizeof(double));
    assert_non_null(K);
    for (int c = 0; c < nf; c++)
        for (int r = 0; r < nf; r++) {
            const int rr = fr[nf - 1 - r], cc = fr[nf - 1 - c], ld = m->nv;
            const double *Ms = dd->Mstar;
            K[r + c * nf] = Ms[rr + cc * ld] / sqrt(Ms[rr + rr * ld] * Ms[cc + cc * ld]);
        }
    dpotrf_("L", &nf, K, &nf, &info, 1);
    assert_int_equal(info, 0);
    double pmin = 1e300, pmax = 0.0;
    for (int k = 0; k < nf; k++) {
        const double p = K[k + k * nf] * K[k + k * nf];
        pmin = fmin(pmin, p);
        pmax = fmax(pmax, p);
    }
    free(K);
    free(fr);
    return schur * pmin / pmax;
}
#endif

static inline double vt_test_maxabs(const double *a, int n)
{
    double s = 0.0;
    for (int k = 0; k < n; k++)
        if (fabs(a[k]) > s) s = fabs(a[k]);
    return s;
}

/* largest |a − b| over n entries relative to the largest |b| (1 when all are 0) */
static inline double vt_test_rel_diff(const double *a, const double *b, int n)
{
    double d = 0.0, s = 0.0;
    for (int k = 0; k < n; k++) {
        d = fmax(d, fabs(a[k] - b[k]));
        s = fmax(s, fabs(b[k]));
    }
    return d / (s > 0.0 ? s : 1.0);
}

/* the largest of vt_test_rel_diff over the efforts (qfrc_drive) and the joint reactions in both
 * frames of two data of models of the same layout */
static inline double vt_test_motion_diff(const vt_model *m, const vt_data *a, const vt_data *b)
{
    const int n3 = 3 * (m->nbody + 1);
    const double r[5] = {vt_test_rel_diff(a->qfrc_drive, b->qfrc_drive, m->nv),
                         vt_test_rel_diff(a->jnt_force, b->jnt_force, n3), vt_test_rel_diff(a->jnt_moment, b->jnt_moment, n3),
                         vt_test_rel_diff(a->jnt_force_body, b->jnt_force_body, n3),
                         vt_test_rel_diff(a->jnt_moment_body, b->jnt_moment_body, n3)};
    return fmax(fmax(fmax(r[0], r[1]), fmax(r[2], r[3])), r[4]);
}

/* Adds to an empty builder n uniform rods of length L along their body x, masses mass[k] (kg),
 * in a chain on revolute joints about z: body 1 at the origin, body k + 1 at body k's far end. */
static inline void vt_test_add_rods(vt_builder *b, int n, double L, const double *mass)
{
    for (int k = 0; k < n; k++) {
        vt_body_def link = vt_default_body_def();
        link.parent = k;
        link.mass = mass[k];
        link.inertia[4] = link.inertia[8] = mass[k] * L * L / 12.0;
        link.joint_child[0] = -0.5 * L;
        link.joint_parent[0] = k ? 0.5 * L : 0.0;
        assert_int_equal(vt_builder_add_body(b, &link), k + 1);
    }
}

/* Σ ½ m v·v + ½ ω·(A J' A^T) ω from the bodies' own velocities (d->xd, d->omega). */
static inline double vt_test_kinetic_energy(const vt_model *m, const vt_data *d)
{
    double T = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        const double *v = d->xd + 7 * (i - 1), *w = d->omega + 3 * i, *A = d->A + 9 * i;
        const double *J = m->body_inertia + 9 * i;
        double wb[3], Jwb[3];
        for (int r = 0; r < 3; r++) wb[r] = A[3 * r] * w[0] + A[3 * r + 1] * w[1] + A[3 * r + 2] * w[2];
        for (int r = 0; r < 3; r++) Jwb[r] = J[r] * wb[0] + J[r + 3] * wb[1] + J[r + 6] * wb[2];
        T += 0.5 * m->body_mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
             0.5 * (wb[0] * Jwb[0] + wb[1] * Jwb[1] + wb[2] * Jwb[2]);
    }
    return T;
}

/* J = A J' A^T: body i's inertia about its centre of mass in global axes */
static inline void vt_test_global_inertia(double J[9], const vt_model *m, const vt_data *d, int i)
{
    const double *A = d->A + 9 * i, *Jb = m->body_inertia + 9 * i;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            double s = 0.0;
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) s += A[r + 3 * a] * Jb[a + 3 * b] * A[c + 3 * b];
            J[r + 3 * c] = s;
        }
}

/* V = −Σ m g·r */
static inline double vt_test_potential_energy(const vt_model *m, const vt_data *d)
{
    double V = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        const double *r = d->x + 7 * (i - 1);
        V -= m->body_mass[i] * (m->gravity[0] * r[0] + m->gravity[1] * r[1] + m->gravity[2] * r[2]);
    }
    return V;
}

/* T + V of row k of a trajectory (its state loaded into d) */
static inline double vt_test_row_energy(const vt_model *m, vt_data *d, const vt_trajectory *tr, int k)
{
    memcpy(d->q, tr->q + (size_t)k * (size_t)m->nq, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, tr->qd + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
    if (vt_kinematics(m, d) != VT_OK) return NAN;
    return vt_test_kinetic_energy(m, d) + vt_test_potential_energy(m, d);
}

/* y = S v (dense, every entry) */
static inline void vt_test_S_times(double *y, const vt_model *m, const vt_data *d, const double *v)
{
    for (int r = 0; r < m->nx; r++) {
        double s = 0.0;
        for (int c = 0; c < m->nv; c++) s += d->S[r + (size_t)c * (size_t)m->nx] * v[c];
        y[r] = s;
    }
}

/* Mass ratios along a chain: five planar rods (vt_test_add_rods, 0.4 m) whose masses fall by
 * 10^step a rod about the middle one's 1 kg (rising 0: 1e12 … 1e-12 kg for step 6), rise (1), or
 * are all 1 kg (rising −1), driven as
 *   0  every joint (nothing factorized)
 *   1  joints 1-3 and the tip's x, y (square: the rows fix the motion)
 *   2  joints 1-2 and the tip's x, y (one rate free)
 *   3  joint 1 alone (four free rates)
 *   4  no joint; the far end of rod 2 and the tip, x and y (one rate free: test_solve)
 * joint k by f = 0.3 + 0.2 k + 0.4 sin(1.5 t + 0.2 k) (k from 0), the tip's x and y by
 * 0.05 sin(t + 0.3 c) (c = 0, 1), rod 2's by 0.05 sin(t + 0.3 (c + 2)). test_accuracy and the
 * high-precision oracle (ratio_oracle.py, which writes the same chain's equations itself) use
 * it. */
static inline vt_model *vt_test_ratio_chain(int rising, int drive, double step)
{
    double mass[5];
    for (int k = 0; k < 5; k++) mass[k] = rising < 0 ? 1.0 : pow(10.0, (rising ? step : -step) * (k - 2));
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_test_add_rods(b, 5, 0.4, mass);
    const int joints = drive == 0 ? 5 : drive == 1 ? 3 : drive == 2 ? 2 : drive == 3 ? 1 : 0;
    for (int k = 0; k < joints; k++) {
        vt_drive_def dr = vt_default_drive_def();
        dr.body = k + 1;
        dr.f = vt_function_sine(0.3 + 0.2 * k, 0.4, 1.5, 0.2 * k);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    for (int c = drive == 4 ? -2 : 0; c < 2 && (drive == 1 || drive == 2 || drive == 4); c++) {
        vt_drive_def tip = vt_default_drive_def(); /* c < 0: rod 2's far end */
        tip.type = VT_DRIVE_POINT;
        tip.body = c < 0 ? 2 : 5;
        tip.index = c < 0 ? c + 2 : c;
        tip.point[0] = 0.2;
        tip.f = vt_function_sine(0.0, 0.05, 1.0, 0.3 * (c < 0 ? c + 4 : c)); /* only its derivatives matter here */
        assert_true(vt_builder_add_drive(b, &tip) >= 0);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* A random tree of n = 8 + seed bodies (vt_scene_random_bodies with `kinds`) with fewer rows
 * than rates: joint drives on bodies 2, 5, 8, ... (not on spherical or free joints), a point drive
 * on body n, an orientation drive (on body 3 when seed % 3 == 0, else a relative one on the last
 * spherical joint's body: three angles to its grandparent, or the joint's own drive), a spherical
 * cut joint from the ground to body n − 1 on odd seeds and, with `coupling` and seed % 4 == 0, a
 * coupling of two revolute joints (test_recursive's articulated route, test_maximal) */
static inline vt_model *vt_test_partly_driven_tree(uint64_t seed, unsigned kinds, int coupling)
{
    const int n = 8 + (int)seed;
    vt_builder *b;
    vt_model *probe, *m;
    assert_ok(vt_scene_random_tree(&probe, seed, n, kinds));
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, seed, n, kinds));
    for (int i = 2; i <= n; i += 3) {
        if (probe->body_joint[i] == VT_JOINT_SPHERICAL || probe->body_joint[i] == VT_JOINT_FREE) continue;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = i;
        dr.f = vt_function_sine(0.1, 0.3, 2.0, 0.5);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    vt_drive_def pd = vt_default_drive_def();
    pd.type = VT_DRIVE_POINT;
    pd.body = n;
    pd.index = (int)(seed % 3);
    pd.point[0] = 0.2;
    pd.f = vt_function_sine(0.05, 0.2, 1.5, 0.0);
    assert_true(vt_builder_add_drive(b, &pd) >= 0);
    int sph = n;
    while (sph > 1 && probe->body_joint[sph] != VT_JOINT_SPHERICAL) sph--;
    if (seed % 3 == 0) {
        vt_drive_def od = vt_default_drive_def();
        od.type = VT_DRIVE_ORIENTATION;
        od.body = 3;
        od.f = vt_function_sine(0.1, 0.4, 1.0, 0.0);
        assert_true(vt_builder_add_drive(b, &od) >= 0);
    } else if (probe->body_joint[sph] == VT_JOINT_SPHERICAL) {
        vt_drive_def od = vt_default_drive_def();
        od.type = VT_DRIVE_RELATIVE_ORIENTATION;
        od.body = sph;
        od.reference = seed % 3 == 1 ? probe->body_parent[probe->body_parent[sph]] : -1;
        od.sequence = seed % 3 == 1 ? "XYZ" : NULL;
        od.f = vt_function_sine(0.1, 0.4, 1.0, 0.0);
        od.f2 = vt_function_sine(-0.2, 0.3, 2.0, 0.5);
        od.f3 = vt_function_sine(0.3, -0.2, 1.5, 0.1);
        assert_true(vt_builder_add_drive(b, &od) >= 0);
    }
    if (seed % 2) {
        vt_cut_joint_def cj = vt_default_cut_joint_def();
        cj.joint = VT_JOINT_SPHERICAL;
        cj.body_a = 0;
        cj.body_b = n - 1;
        assert_true(vt_builder_add_cut_joint(b, &cj) >= 0);
    }
    int first = 0, second = 0; /* two revolute joints, for the coupling */
    for (int i = 2; i <= n; i++)
        if (probe->body_joint[i] == VT_JOINT_REVOLUTE) {
            if (!first) first = i;
            else if (!second && i % 3 != 2) second = i;
        }
    if (coupling && seed % 4 == 0 && first && second) {
        vt_coupling_def cp = vt_default_coupling_def();
        cp.body_a = second;
        cp.body_b = first;
        cp.ratio = 0.5;
        assert_true(vt_builder_add_coupling(b, &cp) >= 0);
    }
    vt_model_free(probe);
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* the model of builder b, which it frees */
static inline vt_model *vt_test_build(vt_builder *b)
{
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* a joint drive of rate `index` of body `body`'s joint, q = f(t) */
static inline void vt_test_add_joint_drive(vt_builder *b, int body, int index, vt_function f)
{
    vt_drive_def dr = vt_default_drive_def();
    dr.body = body;
    dr.index = index;
    dr.f = f;
    assert_true(vt_builder_add_drive(b, &dr) >= 0);
}

/* Contact scenes (test_contact, test_contact_rule) */

/* a free box (mass m, 0.6 x 0.4 x 0.2 m; gravity −9.81 z) with corners at (x_k, ±0.2, −0.1) from its centre of
 * mass, x_k = xf front and xh hind */
static inline vt_model *vt_test_contact_box(double mass)
{
    vt_builder *b = NULL;
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = 0.0, md.gravity[2] = -9.81; /* z up */
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_FREE;
    body.parent = 0;
    body.mass = mass;
    body.inertia[0] = mass * (0.16 + 0.04) / 12.0;
    body.inertia[4] = mass * (0.36 + 0.04) / 12.0;
    body.inertia[8] = mass * (0.36 + 0.16) / 12.0;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* the minimum-norm corner forces f (12) of the box at rest in orientation identity with its
 * centre of mass accelerated by acc: E f = w, E's rows Σ f and Σ r × f, f = Eᵀ (E Eᵀ)⁻¹ w */
static inline void vt_test_min_norm_forces(const vt_contact_def def[4], double mass, const double acc[3], double f[12])
{
    double E[6 * 12] = {0}, w[6] = {mass * acc[0], mass * acc[1], mass * (acc[2] + 9.81), 0, 0, 0};
    for (int k = 0; k < 4; k++) {
        const double *r = def[k].point;
        for (int e = 0; e < 3; e++) E[e + 6 * (3 * k + e)] = 1.0;
        /* (r × f)_x = r_y f_z − r_z f_y, ... */
        E[3 + 6 * (3 * k + 2)] = r[1], E[3 + 6 * (3 * k + 1)] = -r[2];
        E[4 + 6 * (3 * k + 0)] = r[2], E[4 + 6 * (3 * k + 2)] = -r[0];
        E[5 + 6 * (3 * k + 1)] = r[0], E[5 + 6 * (3 * k + 0)] = -r[1];
    }
    double EEt[36];
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double s = 0.0;
            for (int k = 0; k < 12; k++) s += E[i + 6 * k] * E[j + 6 * k];
            EEt[i + 6 * j] = s;
        }
    int n6 = 6, one = 1, ipiv[6], info = 0;
    dgesv_(&n6, &one, EEt, &n6, ipiv, w, &n6, &info); /* LAPACK, not the library's QP */
    assert_int_equal(info, 0);
    for (int k = 0; k < 12; k++) {
        double s = 0.0;
        for (int i = 0; i < 6; i++) s += E[i + 6 * k] * w[i];
        f[k] = s;
    }
}

static inline void vt_test_box_corners(vt_contact_def def[4], double xf, double xh, double mu)
{
    static const char *const names[4] = {"FL", "FR", "HL", "HR"};
    for (int k = 0; k < 4; k++) {
        def[k] = vt_default_contact_def();
        def[k].name = names[k];
        def[k].body = 1;
        def[k].point[0] = k < 2 ? xf : xh;
        def[k].point[1] = k % 2 == 0 ? 0.2 : -0.2;
        def[k].point[2] = -0.1;
        def[k].mu = mu;
    }
}

/* the four feet of the quadruped as contacts of friction mu and the given kind, named by their
 * frames */
static const char *const VT_TEST_FOOT[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};
static inline void vt_test_feet(vt_contact_def def[4], double mu, vt_contact_kind kind)
{
    for (int k = 0; k < 4; k++) {
        def[k] = vt_default_contact_def();
        def[k].frame = def[k].name = VT_TEST_FOOT[k];
        def[k].mu = mu;
        def[k].kind = kind;
    }
}

/* The recursive evaluation against the dense path (test_recursive, test_accuracy) */

/* every |a_k − b_k| within rel × scale, each failure naming the entry and both values */
static inline void vt_test_compare_at(const double *a, const double *b, int n, double rel, double scale, const char *what)
{
    for (int k = 0; k < n; k++)
        if (!(fabs(a[k] - b[k]) <= rel * scale))
            fail_msg("%s[%d]: recursive %.17g, dense %.17g (scale %.3g)", what, k, a[k], b[k], scale);
}

/* the same against 1 + the larger of the two arrays' largest entries */
static inline void vt_test_compare(const double *a, const double *b, int n, double rel, const char *what)
{
    vt_test_compare_at(a, b, n, rel, 1.0 + fmax(vt_test_maxabs(a, n), vt_test_maxabs(b, n)), what);
}

/* an instant's inputs from src to dst (data of the same model): q, q̇, the loads and the time */
static inline void vt_test_copy_inputs(const vt_model *m, vt_data *dst, const vt_data *src)
{
    memcpy(dst->q, src->q, (size_t)m->nq * sizeof(double));
    memcpy(dst->qd, src->qd, (size_t)m->nv * sizeof(double));
    memcpy(dst->qfrc, src->qfrc, (size_t)m->nv * sizeof(double));
    memcpy(dst->xfrc, src->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    dst->time = src->time;
}

/* vt_scene_chain's reference state for every rate (vt_scene_chain_state), its q̈ into d->qdd
 * when with_qdd (the motion given) */
static inline void vt_test_chain_state(const vt_model *m, vt_data *d, int with_qdd)
{
    for (int k = 0; k < m->nv; k++) {
        double qdd;
        vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
        if (with_qdd) d->qdd[k] = qdd;
    }
}

/* body i of m as a definition (its parent, joint, mass, inertia, joint points, axes and
 * orientation; names and limits left at their defaults), to build another model from */
static inline vt_body_def vt_test_body_of(const vt_model *m, int i)
{
    vt_body_def d = vt_default_body_def();
    d.parent = m->body_parent[i];
    d.joint = (vt_joint_type)m->body_joint[i];
    d.mass = m->body_mass[i];
    memcpy(d.inertia, m->body_inertia + 9 * i, 9 * sizeof(double));
    memcpy(d.joint_parent, m->body_jpar + 3 * i, 3 * sizeof(double));
    memcpy(d.joint_child, m->body_jchild + 3 * i, 3 * sizeof(double));
    memcpy(d.axis1, m->body_axis + 6 * i, 3 * sizeof(double));
    memcpy(d.axis2, m->body_axis + 6 * i + 3, 3 * sizeof(double));
    memcpy(d.orientation, m->body_quat0 + 4 * i, 4 * sizeof(double));
    return d;
}

/* A floating tree: root body 1 on a free joint (root_free) or the paper's base joint, and under
 * it the bodies of a random tree (its ground-hung bodies hung from the root instead); the free
 * joint's point is c' from the root's centre of mass (joint_child). */
static inline vt_model *vt_test_floating_tree(uint64_t seed, int n, int root_free, const double c[3])
{
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, seed, n, VT_SCENE_NO_BASE));
    vt_builder *b;
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = 1.0, md.gravity[1] = -9.81, md.gravity[2] = 2.0;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def root = vt_default_body_def();
    root.joint = root_free ? VT_JOINT_FREE : VT_JOINT_BASE;
    root.mass = 4.0;
    const double J[9] = {0.5, 0.05, -0.02, 0.05, 0.7, 0.03, -0.02, 0.03, 0.9};
    memcpy(root.inertia, J, sizeof J);
    if (root_free) memcpy(root.joint_child, c, 3 * sizeof(double));
    assert_int_equal(vt_builder_add_body(b, &root), 1);
    for (int i = 1; i <= probe->nbody; i++) {
        vt_body_def d = vt_test_body_of(probe, i);
        d.parent += 1;
        assert_int_equal(vt_builder_add_body(b, &d), i + 1);
    }
    vt_model_free(probe);
    return vt_test_build(b);
}

#ifdef VT_MODEL_MODEL_H /* vt_test_known_rcond */
/* which intermediates the recursive evaluation forms on the route it recorded: INWARD none
 * (every rate joint-driven), SQUARE Ṡq̇ and Φ_q (square Φ_q: M* and Q are never formed),
 * ARTICULATED the same (articulated bodies, no M*), FACTORIZED those and M*, Q (vt_solve's
 * routes, which the dense path takes too) */
enum { VT_TEST_INWARD, VT_TEST_SQUARE, VT_TEST_ARTICULATED, VT_TEST_FACTORIZED };
static inline int vt_test_path_of(const vt_data *dr)
{
    switch (dr->route) {
    case VT_ROUTE_JOINT_DRIVEN: return VT_TEST_INWARD;
    case VT_ROUTE_ARTICULATED: return VT_TEST_ARTICULATED;
    case VT_ROUTE_SQUARE: return dr->fallback ? VT_TEST_FACTORIZED : VT_TEST_SQUARE;
    default: return VT_TEST_FACTORIZED;
    }
}

/* vt_inverse_dynamics on dd and vt_inverse_dynamics_recursive on dr (the same inputs), every
 * output compared to 1e-12, and the intermediates that the recursive path forms (vt_test_path_of) */
static inline void vt_test_both(const vt_model *m, vt_data *dr, vt_data *dd)
{
    assert_ok(vt_inverse_dynamics(m, dd));
    assert_ok(vt_inverse_dynamics_recursive(m, dr));
    const int path = vt_test_path_of(dr);
    assert_true(dr->route > VT_ROUTE_NONE && dr->route < VT_ROUTE_COUNT);
    /* when the recursive evaluation factorizes, vt_solve takes the dense path's route */
    if (path == VT_TEST_FACTORIZED) assert_int_equal(dr->route, dd->route);
    assert_int_equal(dd->fallback & ~(VT_FALLBACK_SCHUR_PIVOT | VT_FALLBACK_SCHUR_CONDITION | VT_FALLBACK_MAXIMAL_CONDITION),
                     0); /* the dense path's only fallbacks */
    const int nb3 = 3 * (m->nbody + 1);
    /* a reaction moment that is zero in exact arithmetic (a planar scene's) is the round-off of
     * the moments through the joint: measure it against them */
    const double mscale = 1.0 + fmax(fmax(vt_test_maxabs(dd->jnt_moment, nb3), vt_test_maxabs(dd->drive_effort, m->ndrive)),
                                     fmax(vt_test_maxabs(dd->drive_moment, 3 * m->ndrive), vt_test_maxabs(dd->qfrc_drive, m->nv)));
    const struct { const char *what; const double *r, *d; int n, moment; } out[] = {
        {"x", dr->x, dd->x, m->nx, 0}, {"xd", dr->xd, dd->xd, m->nx, 0}, {"qdd", dr->qdd, dd->qdd, m->nv, 0},
        {"lambda", dr->lambda, dd->lambda, m->nc, 0}, {"xdd", dr->xdd, dd->xdd, m->nx, 0},
        {"qfrc_drive", dr->qfrc_drive, dd->qfrc_drive, m->nv, 0},
        {"drive_effort", dr->drive_effort, dd->drive_effort, m->ndrive, 0},
        {"drive_force", dr->drive_force, dd->drive_force, 3 * m->ndrive, 0},
        {"drive_moment", dr->drive_moment, dd->drive_moment, 3 * m->ndrive, 0},
        {"jnt_force", dr->jnt_force, dd->jnt_force, nb3, 0}, {"jnt_moment", dr->jnt_moment, dd->jnt_moment, nb3, 1},
        {"jnt_force_body", dr->jnt_force_body, dd->jnt_force_body, nb3, 0},
        {"jnt_moment_body", dr->jnt_moment_body, dd->jnt_moment_body, nb3, 1},
        {"jnt_force_joint", dr->jnt_force_joint, dd->jnt_force_joint, nb3, 0},
        {"jnt_moment_joint", dr->jnt_moment_joint, dd->jnt_moment_joint, nb3, 1},
        {"cut_force", dr->cut_force, dd->cut_force, 3 * m->ncut, 0},
        {"cut_moment", dr->cut_moment, dd->cut_moment, 3 * m->ncut, 0}, {"alpha", dr->alpha, dd->alpha, nb3, 0},
        {"jnt_force_total", dr->jnt_force_total, dd->jnt_force_total, nb3, 0},
        {"jnt_moment_total", dr->jnt_moment_total, dd->jnt_moment_total, nb3, 1},
        {"jnt_force_total_body", dr->jnt_force_total_body, dd->jnt_force_total_body, nb3, 0},
        {"jnt_moment_total_body", dr->jnt_moment_total_body, dd->jnt_moment_total_body, nb3, 1},
        {"Phi", dr->Phi, dd->Phi, m->nc, 0}};
    for (size_t k = 0; k < sizeof out / sizeof out[0]; k++) {
        if (out[k].moment) vt_test_compare_at(out[k].r, out[k].d, out[k].n, 1e-12, mscale, out[k].what);
        else vt_test_compare(out[k].r, out[k].d, out[k].n, 1e-12, out[k].what);
    }
    if (path == VT_TEST_SQUARE) { /* the square path computes the condition of the same Φ_q D itself */
        assert_near(dr->rcond, dd->rcond, 1e-9 * dd->rcond);
        assert_int_equal(dr->warning, dd->warning);
    }
    if (path == VT_TEST_ARTICULATED) {
        const double expect = vt_test_known_rcond(m, dd);
        assert_near(dr->rcond, expect, 1e-9 * expect);
        if (dd->route == VT_ROUTE_SCHUR) assert_near(dd->rcond, expect, 1e-9 * expect); /* the same system */
    }
    vt_test_compare(dr->gamma, dd->gamma, m->nc, 1e-12, "gamma");
    assert_int_equal(dr->rank, dd->rank); /* and the same uniqueness flags (vt_solve's) */
    for (int r = 0; r < m->nc; r++) assert_int_equal(dr->lambda_unique[r], dd->lambda_unique[r]);
    for (int k = 6; k < 6 * (m->nbody + 1); k++) assert_int_equal(dr->jnt_unique[k], dd->jnt_unique[k]);
    if (path != VT_TEST_INWARD) {
        vt_test_compare(dr->Sdqd, dd->Sdqd, m->nx, 1e-12, "Sdqd");
        vt_test_compare(dr->Phiq, dd->Phiq, m->nc * m->nv, 1e-12, "Phiq");
    }
    if (path == VT_TEST_FACTORIZED) {
        vt_test_compare(dr->Mstar, dd->Mstar, m->nv * m->nv, 1e-12, "Mstar");
        vt_test_compare(dr->Q, dd->Q, m->nv, 1e-12, "Q");
    }
}
#endif

/* ---- Newton–Euler of a chain, written apart from the library (test_reactions, test_urdf) ----
 * Each body k (1..n, parent p < k, 0 the ground at rest) has a frame (origin o_k, axes R_k); its
 * joint: the point s_par on the parent (parent frame), a fixed rotation pre (parent frame → the
 * joint's frame at q = 0), the joint's motion in that frame (a turn about u1; a universal's turn
 * about u1 then about u2 as carried by it; a slide along u1), a fixed rotation post, and the point
 * s_child on the body (body frame): R_k = R_p pre M(q) post, P_k = o_p + R_p s_par (+ q R_p pre u1),
 * o_k = P_k − R_k s_child. Mass m, centre of mass c and inertia J about it, both in the body's frame.
 * Out: every joint's total wrench (force, moment about P_k) of the parent on the subtree, its
 * reaction (the total less τ u along each rate's axis u, τ = u · the total), global, and R_k. */
typedef struct {
    int parent, kind; /* kind: 0 revolute, 1 universal, 2 translational */
    double s_par[3], pre[9], u1[3], u2[3], post[9], s_child[3];
    double mass, c[3], J[9];
} vt_ne_body;

static inline void vt_ne_rot(double R[9], const double u[3], double q) /* Rodrigues, u unit */
{
    const double c = cos(q), s = sin(q), v = 1.0 - c;
    const double x = u[0], y = u[1], z = u[2];
    const double r[9] = {c + x * x * v, y * x * v + z * s, z * x * v - y * s, x * y * v - z * s, c + y * y * v,
                         z * y * v + x * s, x * z * v + y * s, y * z * v - x * s, c + z * z * v};
    memcpy(R, r, sizeof r);
}
static inline void vt_ne_mul(double C[9], const double A[9], const double B[9])
{
    double T[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) T[r + 3 * c] = A[r] * B[3 * c] + A[r + 3] * B[3 * c + 1] + A[r + 6] * B[3 * c + 2];
    memcpy(C, T, sizeof T);
}
static inline void vt_ne_mv(double y[3], const double A[9], const double x[3])
{
    double t[3];
    for (int r = 0; r < 3; r++) t[r] = A[r] * x[0] + A[r + 3] * x[1] + A[r + 6] * x[2];
    memcpy(y, t, sizeof t);
}
static inline void vt_ne_mtv(double y[3], const double A[9], const double x[3])
{
    double t[3];
    for (int r = 0; r < 3; r++) t[r] = A[3 * r] * x[0] + A[3 * r + 1] * x[1] + A[3 * r + 2] * x[2];
    memcpy(y, t, sizeof t);
}
static inline void vt_ne_cross(double r[3], const double a[3], const double b[3])
{
    const double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(r, t, sizeof t);
}
/* the rotation of unit Euler parameters (scalar first) */
static inline void vt_ne_quat(double R[9], const double p[4])
{
    const double w = p[0], x = p[1], y = p[2], z = p[3];
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),
                         2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),
                         2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    memcpy(R, r, sizeof r);
}
/* URDF's rpy: R = Rz(y) Ry(p) Rx(r) */
static inline void vt_ne_rpy(double R[9], double r, double p, double y)
{
    static const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    double X[9], Y[9], Z[9];
    vt_ne_rot(X, ex, r);
    vt_ne_rot(Y, ey, p);
    vt_ne_rot(Z, ez, y);
    vt_ne_mul(R, Z, Y);
    vt_ne_mul(R, R, X);
}

/* q, qd, qdd: one entry per rate, bodies in order (a universal two); g gravity; out per body k
 * (arrays of 3 (n+1), entry k): total force F, moment M (about P_k), reaction Fr, Mr; R (9 (n+1)) */
static inline void vt_ne_chain(const vt_ne_body *b, int n, const double *q, const double *qd, const double *qdd,
                               const double g[3], double *F, double *M, double *Fr, double *Mr, double *R)
{
    double o[3 * 33] = {0}, w[3 * 33] = {0}, al[3 * 33] = {0}, ao[3 * 33] = {0}, P[3 * 33], f[3 * 33], nn[3 * 33],
           ax[6 * 33] = {0};
    int nrate[33];
    assert_true(n < 33);
    static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(R, I3, sizeof I3);
    for (int k = 1, c = 0; k <= n; k++) {
        const vt_ne_body *B = &b[k];
        const int p = B->parent;
        double Rp0[9], M1[9], u1[3], u2[3], r[3], t[3];
        nrate[k] = B->kind == 1 ? 2 : 1;
        vt_ne_mul(Rp0, R + 9 * p, B->pre); /* the joint's frame at q = 0, global */
        vt_ne_mv(u1, Rp0, B->u1);
        vt_ne_mv(r, R + 9 * p, B->s_par); /* P0 − o_p */
        double aP[3];
        vt_ne_cross(t, w + 3 * p, r);
        vt_ne_cross(t, w + 3 * p, t);
        vt_ne_cross(aP, al + 3 * p, r);
        for (int i = 0; i < 3; i++) aP[i] += ao[3 * p + i] + t[i], P[3 * k + i] = o[3 * p + i] + r[i];
        double wk[3], ak[3];
        memcpy(wk, w + 3 * p, sizeof wk);
        memcpy(ak, al + 3 * p, sizeof ak);
        memcpy(M1, I3, sizeof I3);
        if (B->kind == 2) { /* slide q u1, u1 fixed on the parent */
            double qu[3], a1[3], a2[3];
            for (int i = 0; i < 3; i++) qu[i] = q[c] * u1[i];
            vt_ne_cross(a1, al + 3 * p, qu);
            vt_ne_cross(t, w + 3 * p, qu);
            vt_ne_cross(t, w + 3 * p, t);
            vt_ne_cross(a2, w + 3 * p, u1);
            for (int i = 0; i < 3; i++) {
                P[3 * k + i] += qu[i];
                aP[i] += a1[i] + t[i] + 2.0 * qd[c] * a2[i] + qdd[c] * u1[i];
            }
        } else {
            vt_ne_rot(M1, B->u1, q[c]);
            vt_ne_cross(t, wk, u1);
            for (int i = 0; i < 3; i++) ak[i] += qdd[c] * u1[i] + qd[c] * t[i], wk[i] += qd[c] * u1[i];
            if (B->kind == 1) {
                double M2[9], Rk1[9];
                vt_ne_mul(Rk1, Rp0, M1);
                vt_ne_mv(u2, Rk1, B->u2); /* u2 as carried by the first turn */
                vt_ne_rot(M2, B->u2, q[c + 1]);
                vt_ne_mul(M1, M1, M2);
                vt_ne_cross(t, wk, u2);
                for (int i = 0; i < 3; i++) ak[i] += qdd[c + 1] * u2[i] + qd[c + 1] * t[i], wk[i] += qd[c + 1] * u2[i];
            }
        }
        memcpy(ax + 6 * k, u1, sizeof u1);
        if (B->kind == 1) memcpy(ax + 6 * k + 3, u2, sizeof u2);
        vt_ne_mul(R + 9 * k, Rp0, M1);
        vt_ne_mul(R + 9 * k, R + 9 * k, B->post);
        memcpy(w + 3 * k, wk, sizeof wk);
        memcpy(al + 3 * k, ak, sizeof ak);
        double sc[3];
        vt_ne_mv(sc, R + 9 * k, B->s_child);
        for (int i = 0; i < 3; i++) r[i] = -sc[i]; /* o_k − P_k */
        vt_ne_cross(t, wk, r);
        vt_ne_cross(t, wk, t);
        double a1[3];
        vt_ne_cross(a1, ak, r);
        for (int i = 0; i < 3; i++) o[3 * k + i] = P[3 * k + i] + r[i], ao[3 * k + i] = aP[i] + a1[i] + t[i];
        c += nrate[k];
    }
    for (int k = 1; k <= n; k++) { /* each body's needed wrench, about its centre of mass */
        const vt_ne_body *B = &b[k];
        double rc[3], t[3], a1[3], Jw[9], Iw[3], Ia[3];
        vt_ne_mv(rc, R + 9 * k, B->c);
        vt_ne_cross(t, w + 3 * k, rc);
        vt_ne_cross(t, w + 3 * k, t);
        vt_ne_cross(a1, al + 3 * k, rc);
        for (int i = 0; i < 3; i++) f[3 * k + i] = B->mass * (ao[3 * k + i] + a1[i] + t[i] - g[i]);
        double RT[9];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) RT[r + 3 * c] = R[9 * k + c + 3 * r];
        vt_ne_mul(Jw, R + 9 * k, B->J);
        vt_ne_mul(Jw, Jw, RT);
        vt_ne_mv(Iw, Jw, w + 3 * k);
        vt_ne_mv(Ia, Jw, al + 3 * k);
        vt_ne_cross(t, w + 3 * k, Iw);
        for (int i = 0; i < 3; i++) nn[3 * k + i] = Ia[i] + t[i];
        /* about P_k: + (c − P_k) × f */
        double cp[3];
        for (int i = 0; i < 3; i++) cp[i] = o[3 * k + i] + rc[i] - P[3 * k + i];
        vt_ne_cross(t, cp, f + 3 * k);
        for (int i = 0; i < 3; i++) F[3 * k + i] = f[3 * k + i], M[3 * k + i] = nn[3 * k + i] + t[i];
    }
    for (int k = n; k >= 1; k--) { /* subtree sums, leaf first */
        const int p = b[k].parent;
        if (p > 0) {
            double d[3], t[3];
            for (int i = 0; i < 3; i++) d[i] = P[3 * k + i] - P[3 * p + i];
            vt_ne_cross(t, d, F + 3 * k);
            for (int i = 0; i < 3; i++) F[3 * p + i] += F[3 * k + i], M[3 * p + i] += M[3 * k + i] + t[i];
        }
    }
    for (int k = 1; k <= n; k++) {
        memcpy(Fr + 3 * k, F + 3 * k, 3 * sizeof(double));
        memcpy(Mr + 3 * k, M + 3 * k, 3 * sizeof(double));
        for (int a = 0; a < nrate[k]; a++) {
            const double *u = ax + 6 * k + 3 * a;
            double *x = b[k].kind == 2 ? Fr + 3 * k : Mr + 3 * k;
            const double *X = b[k].kind == 2 ? F + 3 * k : M + 3 * k;
            const double tau = u[0] * X[0] + u[1] * X[1] + u[2] * X[2];
            for (int i = 0; i < 3; i++) x[i] -= tau * u[i];
        }
    }
}

/* valgrind's memcheck runs the tests in CI (its LD_PRELOAD names its vgpreload): what takes
 * hundreds of megabytes is left to the other runs there */
static inline int under_valgrind(void)
{
    const char *preload = getenv("LD_PRELOAD");
    return preload && strstr(preload, "vgpreload");
}

#endif
