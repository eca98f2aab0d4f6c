/* One instant of a kinematic analysis: the state that the drives and cut joints fix at time t.
 *
 *   positions    Φ(q, t) = 0:  Φ_q Δ = −Φ,  q ← q ⊕ Δ  (Newton–Raphson; ⊕ as vt_integrate_q)
 *   velocities   Φ_q q̇ = −Φ_t                                   (time derivative of Φ = 0)
 *   accelerations and multipliers from (5), then efforts (24) and reactions (25)-(28)
 * Newton's Φ, Φ_t and Φ_q come from the positions and the rates' twists alone
 * (vt_kinematics_positions, vt_constraints_parts without the dense S, Φ_x or γ; the drives'
 * functions once per instant): Φ_q = Φ_x S column by column, as the recursive evaluation forms
 * it; the recursive instant then takes that last evaluation, at the converged q, and adds the
 * velocities, Ṡq̇, Φ_x and γ (vt_inverse_dynamics_recursive_positioned). Each linear step: with
 * as many independent rows as rates, Φ_q is square and the step is Φ_q^-1 b by LU with partial
 * pivoting (LAPACK's dgetf2/dgetrf, dgetrs), one factorization at each Newton iterate; the
 * velocities at the converged q, where the recursive instant takes the square route, by that
 * route's LU of the scaled Φ_q, which it forms there anyway (one solve, q̇ = −Φ_q^-1 Φ_t);
 * otherwise by the last iterate's LU, refined (q̇ += LU^-1 (−Φ_t − Φ_q q̇) with the converged Φ_q:
 * its error shrinks by the O(|Δq|) the two Φ_q differ by) until the residual is round-off, or by
 * a fresh LU after two corrections or without a step; with fewer rows
 * (consistent initial values of a dynamic analysis) LAPACK's dgels gives the least-norm
 * correction, a projection onto the constraint manifold; dependent rows of a model that allows
 * them, the least-norm least-squares step (dgelsd).
 * A joint-driven model (every rate driven on its own, no other row) needs none of it: q = f(t)
 * and q̇ = f'(t) exactly, Φ = 0.
 * Newton's starts for the analyses over time (vt_kinematic_start, below): the Hermite polynomial
 * through q, q̇, q̈ of two or three rows of a trajectory, extrapolated to the next row's time by
 * the kinematic analysis, interpolated to the times IDA asks for by its forward check.
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "analysis/kinematic_solve.h"
#include "base/arena.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"
#include "kinematics/kinematics.h"
#include "numeric/rank.h"
#include "dense/constraints.h"
#include "dense/solve.h"
#include "recursive/recursive.h"

static double max_abs(const double *a, int n)
{
    double s = 0.0;
    for (int k = 0; k < n; k++) s = fabs(a[k]) > s ? fabs(a[k]) : s; /* NaN passed over, as fmax does */
    return s;
}

/* b = −Φ (positions) or b = −Φ_t − Φ_q q̇ (velocities), into B (ldb ≥ nc) */
static void phiq_rhs(const vt_model *m, const vt_data *d, int velocities, double *B, int ldb)
{
    const int nc = m->nc, nv = m->nv;
    memset(B, 0, (size_t)ldb * sizeof(double));
    for (int r = 0; r < nc; r++) {
        double v = velocities ? -d->Phit[r] : -d->Phi[r];
        if (velocities)
            for (int c = 0; c < nv; c++) v -= d->Phiq[r + (size_t)c * (size_t)nc] * d->qd[c];
        B[r] = v;
    }
}

/* A square Φ_q's LU factors and pivots, held by the caller across Newton's steps: the last
 * step's (held = 1) serve the velocities at the converged q (held_velocities) */
typedef struct {
    double *A, *b;
    int *ipiv;
    int held;
} phiq_lu;

/* x = the exact solution of a square Φ_q x = b, or the least-norm one of fewer rows, with
 * b = −Φ (positions) or b = −Φ_t − Φ_q q̇ (velocities); x has nv entries. A square Φ_q's LU goes
 * to lu when given (else to the scratch) */
static vt_status solve_phiq(const vt_model *m, vt_data *d, int velocities, double *x, phiq_lu *lu)
{
    const int nc = m->nc, nv = m->nv, one = 1, ldb = nc > nv ? nc : nv;
    const int square = nc == nv && !m->allow_redundant;
    const size_t mark = vt_scratch_mark(d);
    double *A = square && lu ? lu->A : VT_SCRATCH(d, double, (size_t)nc * (size_t)nv, "Φ_q, factorized");
    double *B = VT_SCRATCH(d, double, ldb, "right side");
    if (!B || !A) return vt_scratch_fail(d, mark);
    memcpy(A, d->Phiq, (size_t)nc * (size_t)nv * sizeof(double));
    phiq_rhs(m, d, velocities, B, ldb);
    int info = 0;
    if (square) { /* square: Φ_q = P L U */
        int *ipiv = lu ? lu->ipiv : VT_SCRATCH(d, int, nv, "LU pivots");
        if (!ipiv) return vt_scratch_fail(d, mark);
        if (lu) lu->held = 0;
        if (nv <= 32) dgetf2_(&nv, &nv, A, &nv, ipiv, &info);
        else dgetrf_(&nv, &nv, A, &nv, ipiv, &info);
        if (info < 0)
            return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_kinematic_solve: LU (dgetf2/dgetrf) info %d", info);
        if (info > 0)
            return vt_scratch_release(d, mark),
                   vt_fail(d->message, VT_ERR_SINGULAR, "vt_kinematic_solve: Φ_q rank deficient at t = %g", d->time);
        dgetrs_("N", &nv, &one, A, &nv, ipiv, B, &ldb, &info, 1);
        if (info != 0)
            return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_kinematic_solve: dgetrs info %d", info);
        memcpy(x, B, (size_t)nv * sizeof(double));
        if (lu) lu->held = 1;
        vt_scratch_release(d, mark);
        return VT_OK;
    }
    double *sv = VT_SCRATCH(d, double, ldb, "singular values");
    int *iwork = VT_SCRATCH(d, int, vt_dgelsd_iwork(nc, nv), "dgelsd integer workspace");
    int lwork = 0;
    double *work = vt_scratch_rest(d, 1, sizeof(double), &lwork, "dgels workspace");
    if (!work) return vt_scratch_fail(d, mark);
    dgels_("N", &nc, &nv, &one, A, &nc, B, &ldb, work, &lwork, &info, 1);
    if (info < 0) return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_kinematic_solve: dgels info %d", info);
    if (info > 0 && m->allow_redundant) { /* dependent rows: the least-norm least-squares step (SVD) */
        memcpy(A, d->Phiq, (size_t)nc * (size_t)nv * sizeof(double));
        phiq_rhs(m, d, velocities, B, ldb);
        const double rc = 1e-10;
        int rank = 0;
        /* LAPACK's dgelsd stops the program (xerbla) on a NaN norm: refuse non-finite input */
        if (!vt_all_finite(A, (size_t)nc * (size_t)nv) || !vt_all_finite(B, (size_t)ldb))
            return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_NONFINITE, "vt_kinematic_solve: NaN or Inf in Φ_q or Φ");
        dgelsd_(&nc, &nv, &one, A, &nc, B, &ldb, sv, &rc, &rank, work, &lwork, iwork, &info);
        if (info != 0)
            return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_LAPACK, "vt_kinematic_solve: dgelsd info %d", info);
    } else if (info > 0) {
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_SINGULAR, "vt_kinematic_solve: Φ_q rank deficient at t = %g", d->time);
    }
    memcpy(x, B, (size_t)nv * sizeof(double));
    vt_scratch_release(d, mark);
    return VT_OK;
}

/* b = −Φ_t − Φ_q q̇ into b (nc); 1 when each row's is round-off of its terms,
 * |b_r| ≤ 4 nv ε (|Φ_t,r| + Σ_c |Φ_q,rc q̇_c|), as small as a backward-stable solve leaves it */
static int velocity_residual(const vt_model *m, const vt_data *d, double *b)
{
    const int nc = m->nc, nv = m->nv;
    const double te = 4.0 * (double)nv * DBL_EPSILON;
    int small = 1;
    for (int r = 0; r < nc; r++) {
        double v = -d->Phit[r], terms = fabs(v);
        for (int c = 0; c < nv; c++) {
            const double p = d->Phiq[r + (size_t)c * (size_t)nc] * d->qd[c];
            v -= p;
            terms += fabs(p);
        }
        b[r] = v;
        small &= fabs(v) <= te * terms;
    }
    return small;
}

/* The velocities at the converged q from the LU of Newton's last iterate, whose Φ_q differs from
 * the converged one by O(|Δq|): each correction q̇ += (Φ_q^last)^-1 (−Φ_t − Φ_q q̇), the residual
 * with the converged Φ_q, shrinks the error by that factor (iterative refinement); at most two,
 * then 0 and the caller solves with a fresh LU. 1 when the residual is round-off. */
static int held_velocities(const vt_model *m, vt_data *d, const phiq_lu *lu)
{
    const int nv = m->nv, one = 1;
    for (int k = 0;; k++) {
        if (velocity_residual(m, d, lu->b)) return 1;
        int info = 0;
        if (k == 2) return 0;
        dgetrs_("N", &nv, &one, lu->A, &nv, lu->ipiv, lu->b, &nv, &info, 1);
        if (info != 0) return 0;
        for (int c = 0; c < nv; c++) d->qd[c] += lu->b[c];
    }
}

/* q and q̇ back to what the caller gave (qsave: nq + nv), the scratch released */
static vt_status restore(const vt_model *m, vt_data *d, const double *qsave, size_t mark, vt_status st)
{
    memcpy(d->q, qsave, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, qsave + m->nq, (size_t)m->nv * sizeof(double));
    vt_scratch_release(d, mark);
    return st;
}

vt_status vt_kinematic_solve_impl(const vt_model *m, vt_data *d, double tol, int maxit, int recursive,
                                  const double *qprev, const double *qdprev, double h)
{
    vt_diagnostics_reset(d); /* the instant's: an option or a Newton step refused leaves no earlier one's */
    if (!(tol > 0.0) || !isfinite(tol) || maxit < 1)
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "vt_kinematic_solve: tol %g must be finite and positive, maxit %d positive",
                       tol, maxit);
    const int polish = recursive & VT_SOLVE_POLISH;
    recursive &= ~VT_SOLVE_POLISH;
    const size_t mark = vt_scratch_mark(d);
    double *qsave = VT_SCRATCH(d, double, (size_t)m->nq + (size_t)m->nv, "q and q̇ as given");
    double *step = VT_SCRATCH(d, double, m->nv, "Newton step");
    double *fd = VT_SCRATCH(d, double, 3 * (size_t)m->ndrive + 1, "the drives' functions at t");
    phiq_lu lu = {.held = 0}, *plu = NULL;
    if (m->nc == m->nv && !m->allow_redundant && !m->joint_driven) {
        lu.A = VT_SCRATCH(d, double, (size_t)m->nv * (size_t)m->nv, "Φ_q's LU, held");
        lu.b = VT_SCRATCH(d, double, m->nv, "velocities' residual");
        lu.ipiv = VT_SCRATCH(d, int, m->nv, "Φ_q's LU pivots, held");
        plu = &lu;
    }
    if (!fd || (plu && !lu.ipiv)) return vt_scratch_fail(d, mark);
    memcpy(qsave, d->q, (size_t)m->nq * sizeof(double));
    memcpy(qsave + m->nq, d->qd, (size_t)m->nv * sizeof(double));
    double res = 0.0;
    int it = 0, polished = !polish;
    vt_status st;
    if (m->joint_driven) { /* every rate driven on its own: q = f(t), q̇ = f'(t), exact, no Newton */
        if ((st = vt_drive_values(m, d, fd))) return restore(m, d, qsave, mark, st);
        for (int r = 0; r < m->nc; r++) {
            const int dof = m->con_dof[r], i = m->dof_body[dof];
            const double *f = fd + 3 * m->con_owner[r];
            d->q[m->body_qadr[i] + dof - m->body_vadr[i]] = f[0];
            d->qd[dof] = f[1];
            d->Phi[r] = 0.0;
            d->Phit[r] = -f[1];
        }
        st = recursive ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
        if (st) return restore(m, d, qsave, mark, st);
        vt_scratch_release(d, mark);
        return VT_OK;
    }
    if (m->nc > 0) {
        if ((st = vt_drive_values(m, d, fd))) return restore(m, d, qsave, mark, st); /* once: t is fixed */
        for (;; it++) { /* Φ, Φ_t and Φ_q from the positions and twists alone */
            if ((st = vt_kinematics_positions(m, d)) || (st = vt_constraints_parts(m, d, VT_FORM_TWISTS, VT_CON_PHIQ, fd)))
                return restore(m, d, qsave, mark, st);
            if (!vt_all_finite(d->Phi, m->nc))
                return restore(m, d, qsave, mark, vt_fail(d->message, VT_ERR_NONFINITE,
                                                         "vt_kinematic_solve: Φ is not finite at t = %g", d->time));
            res = max_abs(d->Phi, m->nc);
            if (qprev && it == 0 && res > tol && res > 0.5 * h * max_abs(d->Phit, m->nc)) {
                /* a start predicted worse than the previous solution's h Φ_t: from that one */
                memcpy(d->q, qprev, (size_t)m->nq * sizeof(double));
                memcpy(d->qd, qdprev, (size_t)m->nv * sizeof(double));
                qprev = NULL;
                it--;
                continue;
            }
            if (res <= tol) {
                if (polished) break;
                polished = 1; /* one step more: its error is the square of this one's */
            } else if (it >= maxit)
                return restore(m, d, qsave, mark, vt_fail(d->message, VT_ERR_NEWTON,
                                             "vt_kinematic_solve: max |Φ| = %.3g after %d iterations at t = %g", res,
                                             maxit, d->time));
            if ((st = solve_phiq(m, d, 0, step, plu))) return restore(m, d, qsave, mark, st);
            if ((st = vt_integrate_q(d->q, m, d->q, step, 1.0))) /* a step so large that q overflows */
                return restore(m, d, qsave, mark, vt_fail(d->message, st, "vt_kinematic_solve: Newton step %d overflows q (max |Φ| = %.3g at t = %g)",
                                                          it + 1, res, d->time));
        }
    }
    /* the recursive instant takes the positions, twists, Φ and Φ_q of Newton's last evaluation,
     * and on its square route, whose LU of Φ_q at the converged q solves q̇ too, the velocities */
    const int totals = recursive != VT_SOLVE_RECURSIVE_NO_TOTALS;
    vt_handoff to = VT_HANDOFF_RATES;
    st = recursive && m->nc > 0 ? vt_inverse_dynamics_recursive_positioned(m, d, fd, totals, 1, &to) : VT_OK;
    if (!st && to == VT_HANDOFF_RATES) {
        /* velocities: the correction of q̇ that makes Φ_q q̇ = −Φ_t, Φ_q at the converged q; by
         * the last Newton step's LU when it gets the residual to round-off */
        if (m->nc > 0 && (!lu.held || !held_velocities(m, d, &lu))) {
            if ((st = solve_phiq(m, d, 1, step, NULL))) return restore(m, d, qsave, mark, st);
            for (int c = 0; c < m->nv; c++) d->qd[c] += step[c];
        }
        st = !recursive ? vt_inverse_dynamics(m, d)
             : m->nc > 0 ? vt_inverse_dynamics_recursive_positioned(m, d, fd, totals, 0, &to)
                         : vt_inverse_dynamics_recursive(m, d);
    }
    if (st) return restore(m, d, qsave, mark, st);
    vt_scratch_release(d, mark);
    return VT_OK;
}

/* A start for Newton at d->time from rows k1 and k2 of tr (τ = t − t1, δ = t1 − t2, s = h / δ, h
 * the step to t from t1; k2 before k1 to extrapolate, after it to interpolate, or −1): the Hermite
 * polynomial that matches q, q̇, q̈ at both rows, exact for quintics (error O(h⁶)), for the rates
 * whose q̇ is the derivative of q,
 *   q(t1 + h) − q1 = h q̇1 + ½ h² q̈1 + u3 s³ + u4 s⁴ + u5 s⁵,
 *   u5 = −(R2 + 6 R1 + 12 R0) / 2,  u4 = 2 u5 − R1 − 3 R0,  u3 = u5 − R1 − 4 R0,
 *   R0 = q2 − q1 + δ q̇1 − ½ δ² q̈1,  R1 = δ (q̇2 − q̇1 + δ q̈1),  R2 = δ² (q̈2 − q̈1);
 * for a rotation's rates (spherical, free), whose q is not their integral, the cubic q̇ that
 * matches q̇, q̈ at both rows, integrated over [t1, t]:
 *   h q̇1 + ½ h² q̈1 + w2 h s² / 3 + w3 h s³ / 4,  w3 = S1 + 2 S0,  w2 = 3 S0 + S1,
 *   S0 = q̇2 − q̇1 + δ q̈1,  S1 = δ (q̈2 − q̈1);
 * from row k1 alone, Taylor's h q̇1 + ½ h² q̈1. Then q ← q1 ⊕ increment, and q̇ the same
 * polynomial's rate at t (Taylor's q̇1 + h q̈1 from one row): where the velocities are refined
 * from it, it is off by O(h⁵), which the LU of Newton's last iterate corrects to round-off in one
 * or two steps.
 * d->qd holds the increment while vt_integrate_q turns it into q (Euler parameters on the sphere).
 * The analysis extrapolates from its last two rows; the forward check interpolates between the
 * two rows around the time IDA asks for (at mid-interval 2⁶ × 2³ times closer than extrapolated). */
/* The Hermite polynomial through q, q̇, q̈ at three rows (degree 8) in Newton's form, from the
 * confluent divided differences of the nodes z = (t1, t1, t1, t2, t2, t2, t3, t3, t3) − t1, where
 * f[z_i..z_{i+j}] over one row's repeated node is q̇ (j = 1) or ½ q̈ (j = 2):
 *   q(t1 + h) − q1 = h (f1 + (h − z1) (f2 + (h − z2) (f3 + …)))
 * The nodes' reciprocal differences are the same for every coordinate: taken once */
typedef struct {
    int row[3];
    double z[9], inv[9][9]; /* inv[j][n] = 1 / (z[n] − z[n − j]), 0 over one row's node */
} hermite3;

static void hermite3_nodes(hermite3 *H, const vt_trajectory *tr, int k1, int k2, int k3)
{
    H->row[0] = k1, H->row[1] = k2, H->row[2] = k3;
    for (int n = 0; n < 9; n++) H->z[n] = tr->t[H->row[n / 3]] - tr->t[k1];
    for (int j = 1; j < 9; j++)
        for (int n = j; n < 9; n++) H->inv[j][n] = n / 3 == (n - j) / 3 ? 0.0 : 1.0 / (H->z[n] - H->z[n - j]);
}

/* q(t1 + h) − q1 of coordinate e (rate c), and its rate q̇(t1 + h) into *rate */
static double hermite3_increment(const hermite3 *H, const vt_trajectory *tr, int e, int c, double h, double *rate)
{
    const size_t nq = (size_t)tr->model->nq, nv = (size_t)tr->model->nv;
    double q[3], v[3], a[3]; /* each row's q, q̇ and ½ q̈ */
    for (int k = 0; k < 3; k++) {
        const size_t r = (size_t)H->row[k];
        q[k] = tr->q[r * nq + (size_t)e];
        v[k] = tr->qd[r * nv + (size_t)c];
        a[k] = 0.5 * tr->qdd[r * nv + (size_t)c];
    }
    /* the table's columns bottom up, in place: in columns 1 and 2 a row's repeated node takes its
     * derivative / j! (inv 0 there), every other entry (and all of columns 3..8) the quotient */
    double f[9] = {q[0], v[0], a[0], (q[1] - q[0]) * H->inv[1][3], 0.0, a[1], (q[2] - q[1]) * H->inv[1][6], 0.0, a[2]};
    f[7] = (v[2] - f[6]) * H->inv[2][7]; /* column 2 from column 1 (v[1], v[1], v[2], v[2] at 4, 5, 7, 8) */
    f[6] = (f[6] - v[1]) * H->inv[2][6];
    f[4] = (v[1] - f[3]) * H->inv[2][4];
    f[3] = (f[3] - v[0]) * H->inv[2][3];
    for (int j = 3; j < 9; j++)
        for (int n = 8; n >= j; n--) f[n] = (f[n] - f[n - 1]) * H->inv[j][n];
    double p = f[8], dp = 0.0; /* P(h) and P'(h), the increment h P(h) */
    for (int n = 7; n >= 1; n--) {
        dp = p + (h - H->z[n]) * dp;
        p = f[n] + (h - H->z[n]) * p;
    }
    *rate = p + h * dp;
    return h * p;
}

vt_status vt_kinematic_start(const vt_model *m, vt_data *d, const vt_trajectory *tr, int k1, int k2, int k3)
{
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, mark = vt_scratch_mark(d);
    const double t1 = tr->t[k1], h = d->time - t1;
    const double *q1 = tr->q + (size_t)k1 * nq, *v1 = tr->qd + (size_t)k1 * nv, *a1 = tr->qdd + (size_t)k1 * nv;
    double *rate = VT_SCRATCH(d, double, nv, "q̇ predicted");
    if (!rate) return vt_scratch_fail(d, mark);
    for (size_t c = 0; c < nv; c++) {
        d->qd[c] = h * (v1[c] + 0.5 * h * a1[c]);
        rate[c] = v1[c] + h * a1[c];
    }
    if (k2 >= 0) {
        const double *q2 = tr->q + (size_t)k2 * nq, *v2 = tr->qd + (size_t)k2 * nv, *a2 = tr->qdd + (size_t)k2 * nv;
        const double dl = t1 - tr->t[k2], s = h / dl;
        hermite3 H;
        if (k3 >= 0) hermite3_nodes(&H, tr, k1, k2, k3);
        for (int i = 1; i <= m->nbody; i++) {
            const int jt = m->body_joint[i], va = m->body_vadr[i], qa = m->body_qadr[i];
            for (int o = 0; o < m->body_nv[i]; o++) {
                const size_t c = (size_t)(va + o);
                if (jt == VT_JOINT_SPHERICAL || (jt == VT_JOINT_FREE && o >= 3)) {
                    const double S0 = v2[c] - v1[c] + dl * a1[c], S1 = dl * (a2[c] - a1[c]);
                    const double w2 = 3.0 * S0 + S1, w3 = S1 + 2.0 * S0;
                    d->qd[c] += h * s * s * (w2 / 3.0 + s * w3 / 4.0);
                    rate[c] += s * s * (w2 + s * w3);
                } else if (k3 >= 0) { /* degree 8 through the three rows */
                    d->qd[c] = hermite3_increment(&H, tr, qa + o, (int)c, h, rate + c);
                } else {
                    const size_t e = (size_t)(qa + o);
                    const double R0 = q2[e] - q1[e] + dl * (v1[c] - 0.5 * dl * a1[c]), R1 = dl * (v2[c] - v1[c] + dl * a1[c]),
                                 R2 = dl * dl * (a2[c] - a1[c]);
                    const double u5 = -0.5 * (R2 + 6.0 * R1 + 12.0 * R0), u4 = 2.0 * u5 - R1 - 3.0 * R0,
                                 u3 = u5 - R1 - 4.0 * R0;
                    d->qd[c] += s * s * s * (u3 + s * (u4 + s * u5));
                    rate[c] += s * s * (3.0 * u3 + s * (4.0 * u4 + s * 5.0 * u5)) / dl;
                }
            }
        }
    }
    const vt_status st = vt_integrate_q(d->q, m, q1, d->qd, 1.0);
    if (st)
        return vt_scratch_release(d, mark),
               vt_fail(d->message, st, "vt_kinematic_analysis: the start predicted at t = %g is not finite", d->time);
    memcpy(d->qd, rate, nv * sizeof(double));
    vt_scratch_release(d, mark);
    return VT_OK;
}

vt_status vt_kinematic_solve(const vt_model *m, vt_data *d, double tol, int maxit)
{
    const vt_status st = vt_check_pair(m, d, "vt_kinematic_solve");
    /* the dense instant where the data holds it, else the recursive one */
    return st ? st : vt_kinematic_solve_impl(m, d, tol, maxit, d->Mstar ? VT_SOLVE_DENSE : VT_SOLVE_RECURSIVE, NULL, NULL, 0.0);
}

/* q and q̇ as given, the Newton step and the drives' functions, held across the instant; solve_phiq's arrays (the LU's
 * pivots, or the least squares' arrays and LAPACK's workspaces (dgels, dgelsd) by their queries) */
size_t vt_kinematic_solve_scratch(const vt_model *m)
{
    const int nc = m->nc, nv = m->nv, one = 1, ldb = nc > nv ? nc : nv, lw = -1;
    const size_t D = sizeof(double);
    int info = 0, rank = 0, iq = 0;
    double q = 0.0, dummy = 0.0, rc = -1.0;
    size_t lapack = 1;
    /* a joint-driven model's state is its drives' values: no Φ_q, no Newton */
    if (m->joint_driven)
        return VT_SCRATCH_BYTES((size_t)m->nq + (size_t)nv, D) + 2 * VT_SCRATCH_BYTES(nv, D) +
               VT_SCRATCH_BYTES(3 * (size_t)m->ndrive + 1, D);
    if (nc > 0) {
        dgels_("N", &nc, &nv, &one, &dummy, &nc, &dummy, &ldb, &q, &lw, &info, 1);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
        dgelsd_(&nc, &nv, &one, &dummy, &nc, &dummy, &ldb, &dummy, &rc, &rank, &q, &lw, &iq, &info);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
    }
    /* Φ_q's LU held between Newton's last step and the velocities: square rows only */
    const size_t held = nc == nv && !m->allow_redundant ? VT_SCRATCH_BYTES((size_t)nv * (size_t)nv, D) +
                                                              VT_SCRATCH_BYTES(nv, D) + VT_SCRATCH_BYTES(nv, sizeof(int))
                                                        : 0;
    return VT_SCRATCH_BYTES((size_t)m->nq + (size_t)nv, D) + 2 * VT_SCRATCH_BYTES(nv, D) +
           VT_SCRATCH_BYTES(3 * (size_t)m->ndrive + 1, D) + held +
           VT_SCRATCH_BYTES((size_t)nc * (size_t)nv, D) + 2 * VT_SCRATCH_BYTES(ldb, D) +
           VT_SCRATCH_BYTES((size_t)vt_dgelsd_iwork(nc, nv), sizeof(int)) + VT_SCRATCH_BYTES(lapack, D) +
           VT_SCRATCH_BYTES(nv, sizeof(int));
}

