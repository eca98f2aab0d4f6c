/* A small dense strictly convex QP by the dual active-set method of Goldfarb and Idnani,
 *
 *   D. Goldfarb, A. Idnani, "A numerically stable dual method for solving strictly convex
 *   quadratic programs", Mathematical Programming 27 (1983) 1-33
 *
 * (the method of quadprog, against which tests/peers/check_qp.py holds this one):
 *
 *   minimize ½ xᵀGx + cᵀx   subject to   a_iᵀx = b_i (i < meq),   a_iᵀx ≥ b_i (the others),
 *
 * G symmetric positive definite. No QP solver is packaged in Debian; the contact forces'
 * distribution rule needs the exact minimizer, not a tolerance-stopped iterate.
 *
 * The method. It keeps a pair (x, A): x the minimizer subject to the active set A held as
 * equalities, with multipliers u_A (≥ 0 for A's inequalities), so that G x + c = N u_A (N: A's
 * normals as columns). It starts at the unconstrained minimum x = −G⁻¹c, A = ∅ (no feasible
 * point needed), and adds one violated constraint p (normal a, slack s_p(x) = aᵀx − b_p) at a
 * time. With G = L Lᵀ (dpotrf) and the QR factors of the active normals in G's metric,
 *
 *   L⁻¹ N = Q [R; 0],   J = L⁻ᵀ Q = [J₁ J₂]   (J₁: the first q = |A| columns),
 *
 * the step towards p is
 *
 *   d = Jᵀ a,   z = J₂ d₂   (primal: z = H a, H = G⁻¹ − G⁻¹N (NᵀG⁻¹N)⁻¹ NᵀG⁻¹),
 *               r = R⁻¹ d₁  (dual:   r = (NᵀG⁻¹N)⁻¹ NᵀG⁻¹ a),
 *
 * and its length the smaller of
 *
 *   t₁ = min { u_j / r_j : j ∈ A an inequality, r_j > 0 }   (partial: a multiplier reaches 0),
 *   t₂ = −s_p(x) / zᵀa,   zᵀa = ‖d₂‖²                       (full: p holds with equality);
 *
 *   x ← x + t z,   u_A ← u_A − t r,   u_p ← u_p + t.
 *
 * The drop rule: at t = t₂ p joins A; at t = t₁ < t₂ the inequality k attaining t₁ (its
 * multiplier now 0) leaves A and the step is taken again for the same p. Each full step raises
 * the dual objective by t₂ (½ t₂ zᵀa + u_p) > 0, so no pair repeats and the method ends, after
 * finitely many steps, at a pair with no violated constraint: the KKT point, exact but for
 * round-off. Nothing is iterated to a tolerance; the tolerances below only tell round-off from
 * zero.
 *
 * Equalities are added first, in order, each by a full step of either sign (t₂ = −s_p/‖d₂‖²;
 * their multipliers have no sign), and never enter t₁ nor leave A. An equality whose normal
 * depends on the earlier ones (‖d₂‖ ≈ 0) is left out when it is consistent with them (δ below
 * is round-off; its multiplier 0, the earlier ones carry the force) and is the culprit of
 * VT_QP_INFEASIBLE otherwise.
 *
 * Degeneracy. A violated inequality whose normal depends on the active ones (z = 0: a friction
 * pyramid's fourth face through the apex f = 0 when three constraints are active there, with
 * one contact) has t₂ = ∞: the step is purely dual (x stays, u_p grows, the others shift) until
 * an active inequality's multiplier reaches 0 and it leaves A; then p is tried again. Zero-length
 * partial steps (t₁ = 0) drop without moving, and the active set only shrinks until p joins, as
 * in Goldfarb–Idnani's finiteness argument. Active constraints are never selected again (they
 * hold to round-off), and a constraint satisfied to within tolerance is not violated, so
 * duplicated constraints and the faces that pass through the apex unselected cause no step.
 *
 * Infeasibility. When p depends on the active constraints, a = N r, and no active inequality has
 * r_j > 0 (t₁ = ∞ as t₂), u_p could grow without bound along a ray of the dual. On the active
 * set p's slack is then δ = rᵀb_A − b_p, and since r_j n_jᵀx ≤ r_j b_j for every feasible x,
 * a_pᵀx ≤ rᵀb_A there: δ < 0 beyond round-off is the dual unbounded, the primal infeasible
 * (Goldfarb–Idnani, step 2(c)(i)), p the culprit. δ is read from the data (b_A, b_p, r), not from
 * the iterate: near-parallel active normals amplify x's round-off, and a slack of −2e-14 at a
 * vertex where everything meets at 0 is not a contradiction. A δ that is round-off means p holds
 * wherever A does: p is set aside (not violated, multiplier 0) until a constraint leaves A.
 * Every pass of the loop adds, drops, sets aside or returns, and the steps are bounded by
 * vt_qp_iteration_limit (round-off cycling, not seen), so it never loops.
 *
 * The answer afresh. The iterate x is a sum of steps and carries round-off of the largest of
 * them (the unconstrained minimum of a near-singular G can lie 1e3 times beyond the answer). At
 * the end x and u are formed again from the final factors alone (qp_polish), the tolerance
 * restarts from that x, and the method runs once more from there: what is still violated joins.
 *
 * Tolerances (ε = DBL_EPSILON, τ = 32 n ε, with room over the n ε of a dot product):
 *   violated:   s_i < −τ (‖a_i‖₂ X + |b_i|), X the largest ‖x‖₂ of the iterates since the start
 *               or since x was formed afresh: x's round-off is relative to them, not to x (x → 0
 *               at a pyramid's apex, from iterates of the forces' size). After VT_QP_OPTIMAL
 *               every inequality holds to it (X then the answer's own ‖x‖ but for the last
 *               pass's few steps), every equality is active (to round-off: the steps after it
 *               move x along J₂, orthogonal to it) or left out;
 *   dependent:  ‖d₂‖₂ ≤ τ ‖J‖_F ‖a‖₂, the round-off of d = Jᵀa (‖J‖₂ = ‖L⁻¹‖₂, unchanged by the
 *               rotations), so a dependence is decided relative to the problem's scale and G's;
 *               or ‖a − N r‖₂ ≤ τ (‖a‖ + Σ |r_i| ‖n_i‖), a = N r to its round-off in the data
 *               (qp_in_span: d₂ also carries what J's rotations have added up);
 *   r_j > 0:    r_j ‖n_j‖ > τ (‖a‖ + Σ |r_i| ‖n_i‖), the round-off of a = N r: a round-off r_j of
 *               1e-16 would make t₁ = u_j / r_j enormous and the step a blow-up (nearly
 *               collinear contact points make r of 1e3);
 *   consistent: |δ| (or −δ) ≤ τ (|b_p| + ‖a‖ X + Σ |r_j| (|b_j| + ‖n_j‖ X)).
 *
 * Why Givens updates (quadprog's way) rather than dgeqrf/dorgqr on the active normals at every
 * step: an add or a drop is then O(n²) (n − q − 1 rotations of J's columns, dlartg and drot)
 * instead of O(n³), which matters at a few hundred variables with as many steps, and J stays
 * L⁻ᵀ times an orthogonal matrix formed by rotations only, Goldfarb–Idnani's stable form.
 *
 * Nothing is allocated: all arrays lie in the caller's work (vt_qp_scratch_bytes). The caller's
 * x, lambda and active are written only on VT_QP_OPTIMAL.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "numeric/qp.h"
#include "base/lapack.h"

/* n² must fit an int (the BLAS's counts) */
enum { QP_MAX_N = 46340 };

/* where a constraint stands */
typedef enum qp_state {
    QP_FREE = 0,
    QP_ACTIVE = 1,
    QP_LEFT_OUT = 2, /* an equality on earlier ones, consistent with them: for good */
    QP_IMPLIED = 3   /* an inequality the active set implies at equality: until one is dropped */
} qp_state;

typedef struct {
    int n, meq, min, ldaeq, ldain;
    const double *c, *Aeq, *beq, *Ain, *bin;
    double *L, *J, *R; /* n x n each, ld n: G's Cholesky factor, L⁻ᵀQ, the active normals' R */
    double *x, *z, *d, *r, *u; /* n each: the iterate, the primal step, Jᵀa, the dual step,
                                * the active multipliers (in act's order) */
    double *norm;      /* meq + min: ‖a_i‖₂ */
    int *act;          /* n: the active constraints' indices, equalities first */
    int *state;        /* meq + min: qp_state */
    int q;             /* |A| */
    double jnorm, tau; /* ‖J‖_F; 32 n ε */
    double xscale;     /* the largest ‖x‖₂ of the iterates so far: x's round-off is relative to it */
} qp_ws;

static size_t qp_doubles(int n, int meq, int min)
{
    const size_t nn = (size_t)n * (size_t)n;
    return 3 * nn + 5 * (size_t)n + (size_t)meq + (size_t)min;
}
static size_t qp_ints(int n, int meq, int min) { return (size_t)n + (size_t)meq + (size_t)min; }

size_t vt_qp_scratch_bytes(int n, int meq, int min)
{
    if (n < 1 || n > QP_MAX_N || meq < 0 || min < 0 || meq > INT_MAX - min) return 0;
    /* sizeof(double) − 1 more: work may come at any address, the doubles are aligned inside */
    return qp_doubles(n, meq, min) * sizeof(double) + qp_ints(n, meq, min) * sizeof(int) + sizeof(double) - 1;
}

int vt_qp_iteration_limit(int n, int meq, int min)
{
    const long long k = 10LL * ((long long)n + meq + min) + 100;
    return k > INT_MAX ? INT_MAX : (int)k;
}

const char *vt_qp_result_string(vt_qp_result r)
{
    switch (r) {
    case VT_QP_OPTIMAL: return "optimal";
    case VT_QP_INFEASIBLE: return "infeasible";
    case VT_QP_NOT_CONVEX: return "G not positive definite";
    case VT_QP_ITERATION_LIMIT: return "iteration limit";
    case VT_QP_NONFINITE: return "non-finite input";
    case VT_QP_NO_SCRATCH: return "work too small";
    case VT_QP_INVALID: return "invalid argument";
    }
    return "unknown result";
}

/* constraint i's row (its first entry and stride) and right-hand side */
static const double *qp_row(const qp_ws *w, int i, int *inc)
{
    if (i < w->meq) {
        *inc = w->ldaeq;
        return w->Aeq + i;
    }
    *inc = w->ldain;
    return w->Ain + (i - w->meq);
}
static double qp_rhs(const qp_ws *w, int i) { return i < w->meq ? w->beq[i] : w->bin[i - w->meq]; }

/* s_i(x) = a_iᵀx − b_i, and the round-off within which it counts as 0 */
static double qp_slack(const qp_ws *w, int i)
{
    int inc;
    const double *a = qp_row(w, i, &inc);
    const int one = 1;
    return ddot_(&w->n, a, &inc, w->x, &one) - qp_rhs(w, i);
}
static double qp_feas_tol(const qp_ws *w, int i)
{
    return w->tau * (w->norm[i] * w->xscale + fabs(qp_rhs(w, i)));
}

/* The most violated free inequality, by its distance s_i / ‖a_i‖ (−1: none violated). A zero row
 * with b_i > 0 comes first: nothing satisfies it. */
static int qp_most_violated(const qp_ws *w)
{
    int p = -1;
    double worst = 0.0;
    for (int i = w->meq; i < w->meq + w->min; i++) {
        if (w->state[i] != QP_FREE) continue;
        const double s = qp_slack(w, i);
        if (!(s < -qp_feas_tol(w, i))) continue;
        const double dist = w->norm[i] > 0.0 ? s / w->norm[i] : -HUGE_VAL;
        if (p < 0 || dist < worst) {
            p = i;
            worst = dist;
        }
    }
    return p;
}

/* p joins A with multiplier up: rotations zero d[q+1..n−1] into d[q] (J ← J Pᵀ keeps
 * Jᵀa = P d), and d[0..q] becomes R's new column */
static void qp_append(qp_ws *w, int p, double up)
{
    const int n = w->n, q = w->q, one = 1;
    for (int i = n - 1; i > q; i--) {
        double cs, sn, rr;
        dlartg_(&w->d[i - 1], &w->d[i], &cs, &sn, &rr);
        w->d[i - 1] = rr;
        w->d[i] = 0.0;
        drot_(&n, w->J + (size_t)(i - 1) * (size_t)n, &one, w->J + (size_t)i * (size_t)n, &one, &cs, &sn);
    }
    memcpy(w->R + (size_t)q * (size_t)n, w->d, (size_t)(q + 1) * sizeof(double));
    w->act[q] = p;
    w->u[q] = up;
    w->state[p] = QP_ACTIVE;
    w->q = q + 1;
}

/* The k-th active constraint leaves A: its column goes out of R, and the Hessenberg that leaves
 * is made triangular again by rotations of R's rows j, j+1 and J's columns j, j+1 */
static void qp_drop(qp_ws *w, int k)
{
    const int n = w->n, q = w->q, one = 1;
    w->state[w->act[k]] = QP_FREE;
    for (int i = w->meq; i < w->meq + w->min; i++) /* what A implied, A without k may not */
        if (w->state[i] == QP_IMPLIED) w->state[i] = QP_FREE;
    for (int j = k; j < q - 1; j++) {
        w->act[j] = w->act[j + 1];
        w->u[j] = w->u[j + 1];
        memcpy(w->R + (size_t)j * (size_t)n, w->R + (size_t)(j + 1) * (size_t)n, (size_t)(j + 2) * sizeof(double));
    }
    memset(w->R + (size_t)(q - 1) * (size_t)n, 0, (size_t)n * sizeof(double));
    for (int j = k; j < q - 1; j++) {
        double *Rj = w->R + j + (size_t)j * (size_t)n, cs, sn, rr;
        dlartg_(&Rj[0], &Rj[1], &cs, &sn, &rr);
        Rj[0] = rr;
        Rj[1] = 0.0;
        const int rest = q - 2 - j; /* the columns j+1 .. q−2 */
        if (rest > 0) drot_(&rest, Rj + n, &n, Rj + n + 1, &n, &cs, &sn);
        drot_(&n, w->J + (size_t)j * (size_t)n, &one, w->J + (size_t)(j + 1) * (size_t)n, &one, &cs, &sn);
    }
    w->q = q - 1;
}

/* p depends on the active constraints, a = N r, and no active inequality can leave (r_j ≤ 0 for
 * each): on the active set a_pᵀx = rᵀb_A, so p's slack there is δ = rᵀb_A − b_p, whatever x's
 * round-off (which near-parallel active normals amplify). For an inequality, δ < 0 beyond the
 * round-off of its terms means a_pᵀx ≤ rᵀb_A < b_p on the whole feasible set (each r_j n_jᵀx ≤
 * r_j b_j): infeasible, p the culprit; otherwise p holds wherever A does, and is set aside
 * until a constraint leaves A. An equality (A then holds equalities only) is left out for good
 * when |δ| is round-off, and is the culprit otherwise. */
static vt_qp_result qp_dependent(qp_ws *w, int p, int *culprit)
{
    double delta = -qp_rhs(w, p), mag = fabs(qp_rhs(w, p)) + w->norm[p] * w->xscale;
    for (int j = 0; j < w->q; j++) {
        const double bj = qp_rhs(w, w->act[j]);
        delta += w->r[j] * bj;
        mag += fabs(w->r[j]) * (fabs(bj) + w->norm[w->act[j]] * w->xscale);
    }
    const int eq = p < w->meq;
    if (eq ? fabs(delta) <= w->tau * mag : delta >= -w->tau * mag) {
        w->state[p] = eq ? QP_LEFT_OUT : QP_IMPLIED;
        return VT_QP_OPTIMAL;
    }
    *culprit = p;
    return VT_QP_INFEASIBLE;
}

/* 1 when a = N r holds to the round-off of its terms, τ (‖a‖ + Σ |r_j| ‖n_j‖) = τ rmag, read from
 * the data (the active rows themselves, r from the factors). d₂ = J₂ᵀa, whose size decides
 * dependence first, carries the round-off of every rotation J has had: after a score of adds
 * and drops on a G of condition 1e5 a dependent row's ‖d₂‖ can stand at twice its bound, and
 * its full step (1e25 in tests/qp_rotated_infeasible.txt) throw x beyond any answer. a − N r =
 * L Q₂ d₂ is the same part of a, measured in the data's units, where the round-off bound holds. */
static int qp_in_span(const qp_ws *w, const double *a, int inc, double rmag)
{
    if (w->q == 0) return 0;
    const int one = 1;
    double *v = w->z; /* free here: the step's z is formed after */
    for (int i = 0; i < w->n; i++) v[i] = a[(size_t)i * (size_t)inc];
    for (int j = 0; j < w->q; j++) {
        int ij;
        const double *nj = qp_row(w, w->act[j], &ij), mr = -w->r[j];
        daxpy_(&w->n, &mr, nj, &ij, v, &one);
    }
    return dnrm2_(&w->n, v, &one) <= w->tau * rmag;
}

/* Adds constraint p: the steps of the method until p joins A (full step), is left out (a
 * consistent dependent equality) or is found infeasible */
static vt_qp_result qp_add(qp_ws *w, int p, int *it, int limit, int *culprit)
{
    const int n = w->n, one = 1, eq = p < w->meq;
    int inc;
    const double *a = qp_row(w, p, &inc);
    double up = 0.0; /* p's multiplier, grown by the partial steps */
    for (;;) {
        if (*it >= limit) return VT_QP_ITERATION_LIMIT;
        ++*it;
        const int q = w->q, nfree = n - q;
        vt_dgemv('T', n, n, 1.0, w->J, n, a, inc, 0.0, w->d, 1);
        const double dn = nfree > 0 ? dnrm2_(&nfree, w->d + q, &one) : 0.0;
        const double s = qp_slack(w, p);
        memcpy(w->r, w->d, (size_t)q * sizeof(double));
        if (q > 0) vt_dtrsv('U', 'N', 'N', q, w->R, n, w->r, 1);
        /* r_j counts as positive above the round-off of a = N r (the opening comment) */
        double rmag = w->norm[p];
        for (int j = 0; j < q; j++) rmag += fabs(w->r[j]) * w->norm[w->act[j]];
        const int dependent = !(dn > w->tau * w->jnorm * w->norm[p]) || qp_in_span(w, a, inc, rmag);
        double t1 = HUGE_VAL;
        int k = -1;
        for (int j = 0; j < q; j++)
            if (w->act[j] >= w->meq && w->r[j] * w->norm[w->act[j]] > w->tau * rmag) {
                const double t = w->u[j] / w->r[j];
                if (t < t1) {
                    t1 = t;
                    k = j;
                }
            }
        if (dependent && k < 0) /* a = N r, and nothing can leave: implied or infeasible */
            return qp_dependent(w, p, culprit);
        double t2 = HUGE_VAL;
        if (!dependent) {
            t2 = -(s / dn) / dn; /* not over dn², which could underflow */
            if (!eq && t2 < 0.0) t2 = 0.0; /* p came to hold by round-off: it joins as it is */
        }
        if (!(t2 <= t1) && k < 0) return VT_QP_NONFINITE; /* t2 NaN: the steps overflowed */
        const double t = t2 <= t1 ? t2 : t1;
        if (!dependent) {
            vt_dgemv('N', n, nfree, 1.0, w->J + (size_t)q * (size_t)n, n, w->d + q, 1, 0.0, w->z, 1);
            for (int i = 0; i < n; i++) w->x[i] += t * w->z[i];
            w->xscale = fmax(w->xscale, dnrm2_(&n, w->x, &one));
        }
        for (int j = 0; j < q; j++) {
            w->u[j] -= t * w->r[j];
            if (w->act[j] >= w->meq && w->u[j] < 0.0) w->u[j] = 0.0; /* round-off below 0 */
        }
        up += t;
        if (t2 <= t1) {
            qp_append(w, p, up);
            return VT_QP_OPTIMAL;
        }
        w->u[k] = 0.0;
        qp_drop(w, k);
    }
}

/* x and u from the final factors alone, the equality QP on A solved afresh:
 *   x = J₁ R⁻ᵀ b_A − J₂ J₂ᵀ c,   u = R⁻¹ (R⁻ᵀ b_A + J₁ᵀ c)
 * (Lᵀx's parts along Q₁ and Q₂; the two terms of x are G-orthogonal, so neither is larger than
 * x in G's norm). The iterate x is a sum of steps and carries ε times the largest of them: from
 * an unconstrained minimum −G⁻¹c 1e3 times the answer (G near singular), 1e-10 of violation
 * that the tolerance, relative to those iterates, let pass. Afresh, x's round-off is relative
 * to x, xscale restarts from it, and a second pass adds what is still violated. */
static void qp_polish(qp_ws *w)
{
    const int n = w->n, q = w->q, one = 1;
    for (int j = 0; j < q; j++) w->r[j] = qp_rhs(w, w->act[j]);
    vt_dgemv('T', n, n, 1.0, w->J, n, w->c, 1, 0.0, w->d, 1);
    if (q > 0) {
        vt_dtrsv('U', 'T', 'N', q, w->R, n, w->r, 1);
        vt_dgemv('N', n, q, 1.0, w->J, n, w->r, 1, 0.0, w->x, 1);
    } else {
        memset(w->x, 0, (size_t)n * sizeof(double));
    }
    if (q < n) vt_dgemv('N', n, n - q, -1.0, w->J + (size_t)q * (size_t)n, n, w->d + q, 1, 1.0, w->x, 1);
    for (int j = 0; j < q; j++) w->u[j] = w->r[j] + w->d[j];
    if (q > 0) vt_dtrsv('U', 'N', 'N', q, w->R, n, w->u, 1);
    for (int j = 0; j < q; j++)
        if (w->act[j] >= w->meq && w->u[j] < 0.0) w->u[j] = 0.0;
    w->xscale = dnrm2_(&n, w->x, &one);
}

static int qp_finite(const double *a, int rows, int cols, int ld)
{
    for (int j = 0; j < cols; j++)
        for (int i = 0; i < rows; i++)
            if (!isfinite(a[i + (size_t)j * (size_t)ld])) return 0;
    return 1;
}

/* the inputs' sizes, pointers and values, before anything is written */
static vt_qp_result qp_check(int n, const double *G, int ldg, const double *c, int meq, const double *Aeq,
                             int ldaeq, const double *beq, int min, const double *Ain, int ldain, const double *bin,
                             const double *x, const void *work, size_t work_bytes)
{
    if (n < 1 || n > QP_MAX_N || meq < 0 || min < 0 || meq > INT_MAX - min || !G || ldg < n || !c || !x)
        return VT_QP_INVALID;
    if (meq > 0 && (!Aeq || !beq || ldaeq < meq)) return VT_QP_INVALID;
    if (min > 0 && (!Ain || !bin || ldain < min)) return VT_QP_INVALID;
    if (!work || work_bytes < vt_qp_scratch_bytes(n, meq, min)) return VT_QP_NO_SCRATCH;
    for (int j = 0; j < n; j++) /* the lower triangle: what dpotrf reads */
        if (!qp_finite(G + j + (size_t)j * (size_t)ldg, n - j, 1, ldg)) return VT_QP_NONFINITE;
    if (!qp_finite(c, n, 1, n) || (meq > 0 && (!qp_finite(Aeq, meq, n, ldaeq) || !qp_finite(beq, meq, 1, meq))) ||
        (min > 0 && (!qp_finite(Ain, min, n, ldain) || !qp_finite(bin, min, 1, min))))
        return VT_QP_NONFINITE;
    return VT_QP_OPTIMAL;
}

vt_qp_result vt_qp_solve(int n, const double *G, int ldg, const double *c, int meq, const double *Aeq, int ldaeq,
                         const double *beq, int min, const double *Ain, int ldain, const double *bin, double *x,
                         double *lambda, int *active, int *culprit, void *work, size_t work_bytes, int *iterations)
{
    int it = 0, bad = -1;
    if (iterations) *iterations = 0;
    if (culprit) *culprit = -1;
    vt_qp_result res = qp_check(n, G, ldg, c, meq, Aeq, ldaeq, beq, min, Ain, ldain, bin, x, work, work_bytes);
    if (res != VT_QP_OPTIMAL) return res;

    /* the arrays, doubles first from the first aligned byte of work */
    const size_t nn = (size_t)n * (size_t)n, pad = (sizeof(double) - (uintptr_t)work % sizeof(double)) % sizeof(double);
    double *dw = (double *)(void *)((unsigned char *)work + pad);
    qp_ws w = {.n = n, .meq = meq, .min = min, .ldaeq = ldaeq, .ldain = ldain,
               .c = c, .Aeq = Aeq, .beq = beq, .Ain = Ain, .bin = bin, .q = 0,
               .tau = 32.0 * n * DBL_EPSILON};
    w.L = dw;
    w.J = w.L + nn;
    w.R = w.J + nn;
    w.x = w.R + nn;
    w.z = w.x + n;
    w.d = w.z + n;
    w.r = w.d + n;
    w.u = w.r + n;
    w.norm = w.u + n;
    w.act = (int *)(void *)(dw + qp_doubles(n, meq, min));
    w.state = w.act + n;

    /* G = L Lᵀ; J = L⁻ᵀ (Q = I, A = ∅); x = −G⁻¹c */
    memset(w.L, 0, 3 * nn * sizeof(double));
    for (int j = 0; j < n; j++)
        memcpy(w.L + j + (size_t)j * (size_t)n, G + j + (size_t)j * (size_t)ldg, (size_t)(n - j) * sizeof(double));
    int info = 0;
    dpotrf_("L", &n, w.L, &n, &info, 1);
    if (info != 0) return VT_QP_NOT_CONVEX;
    for (int j = 0; j < n; j++) w.J[j + (size_t)j * (size_t)n] = 1.0;
    vt_dtrsm('L', 'L', 'T', 'N', n, n, 1.0, w.L, n, w.J, n);
    const int nn_int = n * n, one = 1;
    w.jnorm = dnrm2_(&nn_int, w.J, &one);
    for (int i = 0; i < n; i++) w.x[i] = -c[i];
    vt_dtrsv('L', 'N', 'N', n, w.L, n, w.x, 1);
    vt_dtrsv('L', 'T', 'N', n, w.L, n, w.x, 1);
    w.xscale = dnrm2_(&n, w.x, &one);
    for (int i = 0; i < meq + min; i++) {
        int inc;
        const double *a = qp_row(&w, i, &inc);
        w.norm[i] = dnrm2_(&n, a, &inc);
        w.state[i] = QP_FREE;
    }

    const int limit = vt_qp_iteration_limit(n, meq, min);
    for (int p = 0; p < meq && res == VT_QP_OPTIMAL; p++) res = qp_add(&w, p, &it, limit, &bad);
    /* the method; then x and u afresh from the final factors, and once more the method from
     * there with the violation measured against the fresh x (what it still finds joins A) */
    for (int pass = 0; pass < 2 && res == VT_QP_OPTIMAL; pass++) {
        while (res == VT_QP_OPTIMAL) {
            const int p = qp_most_violated(&w);
            if (p < 0) break;
            res = qp_add(&w, p, &it, limit, &bad);
        }
        if (res == VT_QP_OPTIMAL) qp_polish(&w);
    }
    if (res == VT_QP_OPTIMAL && !(qp_finite(w.x, n, 1, n) && qp_finite(w.u, w.q, 1, w.q)))
        res = VT_QP_NONFINITE; /* finite data whose steps overflowed (entries near DBL_MAX) */
    if (iterations) *iterations = it;
    if (res != VT_QP_OPTIMAL) {
        if (res == VT_QP_INFEASIBLE && culprit) *culprit = bad;
        return res;
    }
    memcpy(x, w.x, (size_t)n * sizeof(double));
    if (lambda) {
        memset(lambda, 0, (size_t)(meq + min) * sizeof(double));
        for (int j = 0; j < w.q; j++) lambda[w.act[j]] = w.u[j];
    }
    if (active)
        for (int i = 0; i < meq + min; i++) active[i] = w.state[i] == QP_ACTIVE;
    return VT_QP_OPTIMAL;
}
