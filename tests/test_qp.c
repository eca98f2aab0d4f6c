/* src/numeric/qp.c: the Goldfarb–Idnani QP against answers the test derives for itself.
 *   hand            projections of a point onto a box, a halfspace and the probability simplex
 *                   (closed forms: the clamp, the halfspace's formula, the sort-and-threshold
 *                   rule); an equality-only QP against its KKT system solved here by Gaussian
 *                   elimination; an inactive inequality (the unconstrained minimum −G⁻¹c by that
 *                   elimination, its multiplier 0); G's strict upper triangle never read.
 *   random          fixed-seed problems G = BᵀB + δI, feasible by construction (x0 chosen, b
 *                   made so that x0 is feasible): the KKT conditions checked here (stationarity,
 *                   λ_in ≥ 0, feasibility, complementarity, to 1e-12 relative) and, for small
 *                   sizes, x against brute force (every active set's equality QP by its own KKT
 *                   system, the feasible one with λ_in ≥ 0 kept).
 *   scaled          rows scaled by 10^±6, G and c by 1e5, x by 10^3: the same answer (the
 *                   tolerances are relative to the problem's scale).
 *   contact         friction pyramids (4 and 8 faces) under a six-row wrench balance, forces
 *                   chosen inside the cones: the KKT conditions as above.
 *   collinear       contact points nearly on a line (the balance's rows nearly dependent,
 *                   multipliers of 1e3 and more): the KKT conditions.
 *   ill-conditioned G = BᵀB + 1e-4 I, the unconstrained minimum far beyond the answer: the
 *                   KKT conditions to 1e-12 of the answer's own size.
 *   degenerate      every constraint through one point (b = 0: a cone, never infeasible); the
 *                   pyramids' apex (f = 0 the projection of a force pointing into the
 *                   ground: the polar cone), duplicated constraints (the same x, the duplicates'
 *                   multipliers summing to the single one's), dependent equalities (the answer of
 *                   the independent ones).
 *   infeasible      contradictory inequalities, a pyramid that cannot carry a required
 *                   tangential force, inconsistent dependent equalities: VT_QP_INFEASIBLE with
 *                   the culprit, x and lambda untouched; the contacts' problem of
 *                   tests/qp_rotated_infeasible.txt (ill-conditioned, a row dependent on the
 *                   active ones beyond J's round-off), with its Farkas certificate checked.
 *   errors          NaN/Inf inputs, finite data whose minimum overflows, an indefinite and a
 *                   singular G, invalid sizes: their results, x untouched.
 *   scratch         work of exactly vt_qp_scratch_bytes (at an odd address too) works; a byte
 *                   less, or none, is VT_QP_NO_SCRATCH. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "numeric/qp.h" /* internal */
#include "vt_test.h"
#include "qp_problem.h"

/* ---- the test's own linear algebra ---- */

/* solves the k x k system M y = v (column-major, ld k; M and v overwritten) by Gaussian
 * elimination with partial pivoting; 0 when a pivot falls below 1e-11 of the largest entry */
static int gauss(double *M, double *v, int k)
{
    double big = 0.0;
    for (int i = 0; i < k * k; i++) big = fmax(big, fabs(M[i]));
    for (int col = 0; col < k; col++) {
        int piv = col;
        for (int i = col + 1; i < k; i++)
            if (fabs(M[i + col * k]) > fabs(M[piv + col * k])) piv = i;
        if (!(fabs(M[piv + col * k]) > 1e-11 * big)) return 0;
        for (int j = 0; j < k; j++) {
            const double t = M[col + j * k];
            M[col + j * k] = M[piv + j * k];
            M[piv + j * k] = t;
        }
        const double t = v[col];
        v[col] = v[piv];
        v[piv] = t;
        for (int i = col + 1; i < k; i++) {
            const double f = M[i + col * k] / M[col + col * k];
            for (int j = col; j < k; j++) M[i + j * k] -= f * M[col + j * k];
            v[i] -= f * v[col];
        }
    }
    for (int i = k - 1; i >= 0; i--) {
        double s = v[i];
        for (int j = i + 1; j < k; j++) s -= M[i + j * k] * v[j];
        v[i] = s / M[i + i * k];
    }
    return 1;
}

/* the equality QP min ½xᵀGx + cᵀx, a_iᵀx = b_i for the m rows listed in rows[] of the stacked
 * constraint matrix A (mtot x n, ld mtot), by its KKT system [G −Aᵀ; A 0][x; λ] = [−c; b];
 * 0 when the system is singular (dependent rows) */
static int eq_qp(int n, const double *G, const double *c, const double *A, int mtot, const double *b,
                 const int *rows, int m, double *x, double *lam)
{
    const int k = n + m;
    double *M = calloc((size_t)(k * k), sizeof(double)), *v = calloc((size_t)k, sizeof(double));
    assert_non_null(M);
    assert_non_null(v);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) M[i + j * k] = G[i + j * n];
    for (int r = 0; r < m; r++)
        for (int j = 0; j < n; j++) {
            M[n + r + j * k] = A[rows[r] + j * mtot];
            M[j + (n + r) * k] = -A[rows[r] + j * mtot];
        }
    for (int i = 0; i < n; i++) v[i] = -c[i];
    for (int r = 0; r < m; r++) v[n + r] = b[rows[r]];
    const int ok = gauss(M, v, k);
    if (ok) {
        memcpy(x, v, (size_t)n * sizeof(double));
        if (lam) memcpy(lam, v + n, (size_t)m * sizeof(double));
    }
    free(M);
    free(v);
    return ok;
}

/* ---- a problem, its solve, its checks ---- */

/* problem, prob_new, prob_free, arow: tests/qp_problem.h; prob: prob_new, its memory checked */
static problem prob(int n, int meq, int min)
{
    problem p = prob_new(n, meq, min);
    assert_true(prob_ok(&p));
    return p;
}

/* vt_qp_solve on p with work of exactly the scratch bound; the equalities and inequalities are
 * passed as the stack's two blocks (ld meq + min for both) */
static vt_qp_result solve(const problem *p, double *x, double *lam, int *active, int *culprit, int *iters)
{
    const size_t bytes = vt_qp_scratch_bytes(p->n, p->meq, p->min);
    void *work = malloc(bytes);
    assert_non_null(work);
    const int m = p->meq + p->min, ld = m > 0 ? m : 1;
    const vt_qp_result r = vt_qp_solve(p->n, p->G, p->n, p->c, p->meq, p->A, ld, p->b, p->min, p->A + p->meq, ld,
                                       p->b + p->meq, x, lam, active, culprit, work, bytes, iters);
    free(work);
    return r;
}

/* The KKT conditions at (x, λ), here: |G x + c − Aᵀλ| against the sum of the magnitudes of its
 * terms, λ_in ≥ 0, every constraint's slack and λ_i s_i against |a_i| X + |b_i|, X the size of
 * x the problem speaks of, ‖x‖_∞ + ‖c‖_∞ / max G_jj (x ≈ 0 at a pyramid's apex holds to the
 * round-off of the forces around it, not to that of 0) */
static void check_kkt(const problem *p, const double *x, const double *lam, double tol)
{
    const int n = p->n, m = p->meq + p->min;
    for (int i = 0; i < n; i++) {
        double res = p->c[i], mag = fabs(p->c[i]);
        for (int j = 0; j < n; j++) {
            res += p->G[i + j * n] * x[j];
            mag += fabs(p->G[i + j * n] * x[j]);
        }
        for (int k = 0; k < m; k++) {
            res -= p->A[k + i * m] * lam[k];
            mag += fabs(p->A[k + i * m] * lam[k]);
        }
        if (!(fabs(res) <= tol * fmax(mag, 1e-300)))
            fail_msg("stationarity row %d: residual %.3g, terms %.3g", i, res, mag);
    }
    double lmax = 0.0, xmax = 0.0, cmax = 0.0, gmax = 0.0;
    for (int k = 0; k < m; k++) lmax = fmax(lmax, fabs(lam[k]));
    for (int j = 0; j < n; j++) {
        xmax = fmax(xmax, fabs(x[j]));
        cmax = fmax(cmax, fabs(p->c[j]));
        gmax = fmax(gmax, p->G[j + j * n]);
    }
    const double X = xmax + cmax / gmax;
    for (int k = 0; k < m; k++) {
        double s = -p->b[k], mag = fabs(p->b[k]);
        for (int j = 0; j < n; j++) {
            s += p->A[k + j * m] * x[j];
            mag += fabs(p->A[k + j * m]) * X;
        }
        if (k < p->meq) {
            if (!(fabs(s) <= tol * mag)) fail_msg("equality %d: residual %.3g, scale %.3g", k, s, mag);
        } else {
            if (!(s >= -tol * mag)) fail_msg("inequality %d: slack %.3g, scale %.3g", k, s, mag);
            if (!(lam[k] >= -tol * lmax)) fail_msg("inequality %d: multiplier %.3g < 0", k, lam[k]);
            if (!(fabs(lam[k] * s) <= tol * fabs(lam[k]) * mag))
                fail_msg("inequality %d: complementarity %.3g (λ %.3g, s %.3g)", k, lam[k] * s, lam[k], s);
        }
    }
}

/* Brute force: every subset S of the inequalities with all equalities, its equality QP by its
 * own KKT system; the one whose x is feasible and whose λ_S ≥ 0 is the KKT point (unique x: G is
 * positive definite). Returns 1 with it in x, 0 when none (infeasible for small problems). */
static int brute_force(const problem *p, double *x)
{
    const int n = p->n, m = p->meq + p->min;
    int *rows = malloc(sizeof(int) * (size_t)(m + 1));
    double *y = malloc(sizeof(double) * (size_t)n), *lam = malloc(sizeof(double) * (size_t)(m + 1));
    assert_true(rows && y && lam);
    int found = 0;
    for (unsigned mask = 0; mask < (1u << p->min) && !found; mask++) {
        int k = 0;
        for (int i = 0; i < p->meq; i++) rows[k++] = i;
        for (int i = 0; i < p->min; i++)
            if (mask & (1u << i)) rows[k++] = p->meq + i;
        if (k > n || !eq_qp(n, p->G, p->c, p->A, m, p->b, rows, k, y, lam)) continue;
        int ok = 1;
        double xn = 0.0;
        for (int j = 0; j < n; j++) xn += fabs(y[j]);
        for (int r = p->meq; r < k && ok; r++) ok = lam[r] >= -1e-9 * (1.0 + fabs(lam[r]));
        for (int i = p->meq; i < m && ok; i++) {
            double s = -p->b[i], an = 0.0;
            for (int j = 0; j < n; j++) {
                s += p->A[i + j * m] * y[j];
                an += fabs(p->A[i + j * m]);
            }
            ok = s >= -1e-9 * (an * xn + fabs(p->b[i]) + 1.0);
        }
        if (ok) {
            memcpy(x, y, (size_t)n * sizeof(double));
            found = 1;
        }
    }
    free(rows);
    free(y);
    free(lam);
    return found;
}

/* the generator, random_spd and random_problem: tests/qp_problem.h */

/* ---- hand-derived problems ---- */

static void test_box(void **state)
{
    (void)state;
    enum { N = 5 };
    const double pt[N] = {2.0, -3.0, 0.25, 1.0, -0.5}, lo[N] = {-1, -1, -1, -1, 0}, hi[N] = {1, 1, 1, 1, 1};
    problem p = prob(N, 0, 2 * N);
    for (int j = 0; j < N; j++) {
        p.G[j + j * N] = 1.0;
        p.c[j] = -pt[j];
        *arow(&p, j, j) = 1.0; /* x_j ≥ lo_j */
        p.b[j] = lo[j];
        *arow(&p, N + j, j) = -1.0; /* −x_j ≥ −hi_j */
        p.b[N + j] = -hi[j];
    }
    double x[N], lam[2 * N];
    int active[2 * N];
    assert_int_equal(solve(&p, x, lam, active, NULL, NULL), VT_QP_OPTIMAL);
    for (int j = 0; j < N; j++) {
        const double want = fmin(fmax(pt[j], lo[j]), hi[j]);
        assert_near(x[j], want, 1e-15);
        /* the clamp's multipliers: how far the point lies beyond the bound */
        assert_near(lam[j], fmax(lo[j] - pt[j], 0.0), 1e-15);
        assert_near(lam[N + j], fmax(pt[j] - hi[j], 0.0), 1e-15);
    }
    assert_int_equal(active[0] + active[1] + active[5] + active[6], 2); /* x0 at hi, x1 at lo */
    assert_int_equal(active[5], 1);
    assert_int_equal(active[1], 1);
    check_kkt(&p, x, lam, 1e-14);
    prob_free(&p);
}

static void test_halfspace(void **state)
{
    (void)state;
    enum { N = 4 };
    const double a[N] = {1.0, -2.0, 0.5, 3.0}, pt[N] = {0.3, 0.7, -1.2, -0.4}, b = 2.0;
    for (int flip = 0; flip < 2; flip++) { /* violated at pt, then satisfied at pt (inactive) */
        problem p = prob(N, 0, 1);
        double an2 = 0.0, ap = 0.0;
        for (int j = 0; j < N; j++) {
            p.G[j + j * N] = 1.0;
            p.c[j] = -pt[j];
            *arow(&p, 0, j) = flip ? -a[j] : a[j];
            an2 += a[j] * a[j];
            ap += a[j] * pt[j];
        }
        p.b[0] = flip ? -b : b; /* flip: aᵀx ≤ b, which pt satisfies (aᵀpt = −1.55) */
        double x[N], lam[1];
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        const double mu = flip ? 0.0 : (b - ap) / an2; /* x = pt + μ a, μ = max(0, b − aᵀpt) / ‖a‖² */
        for (int j = 0; j < N; j++) assert_near(x[j], pt[j] + mu * a[j], 1e-15);
        assert_near(lam[0], mu, 1e-15);
        prob_free(&p);
    }
}

/* the projection onto {x ≥ 0, Σx = 1}: x_i = max(p_i − θ, 0), θ from the sorted p */
static int cmp_desc(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}
static void test_simplex(void **state)
{
    (void)state;
    enum { N = 7 };
    uint64_t s = 11;
    for (int rep = 0; rep < 20; rep++) {
        double pt[N], sorted[N], x[N], lam[N + 1];
        for (int j = 0; j < N; j++) pt[j] = sorted[j] = 1.5 * urand(&s);
        qsort(sorted, N, sizeof(double), cmp_desc);
        double cum = 0.0, theta = 0.0;
        for (int k = 0; k < N; k++) {
            cum += sorted[k];
            const double t = (cum - 1.0) / (k + 1);
            if (sorted[k] - t > 0.0) theta = t;
        }
        problem p = prob(N, 1, N);
        for (int j = 0; j < N; j++) {
            p.G[j + j * N] = 1.0;
            p.c[j] = -pt[j];
            *arow(&p, 0, j) = 1.0;
            *arow(&p, 1 + j, j) = 1.0;
        }
        p.b[0] = 1.0;
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        for (int j = 0; j < N; j++) assert_near(x[j], fmax(pt[j] - theta, 0.0), 1e-14);
        assert_near(lam[0], -theta, 1e-14); /* x − pt = λ_eq 1 + λ_in on the support: λ_eq = −θ */
        check_kkt(&p, x, lam, 1e-13);
        prob_free(&p);
    }
}

static void test_equality_only(void **state)
{
    (void)state;
    uint64_t s = 5;
    for (int rep = 0; rep < 10; rep++) {
        const int n = 3 + rep, meq = 1 + rep / 2;
        problem p = random_problem(&s, n, meq, 0, 0.5);
        double x[16], lam[16], xr[16], lr[16];
        int rows[16];
        for (int i = 0; i < meq; i++) rows[i] = i;
        assert_true(eq_qp(n, p.G, p.c, p.A, meq, p.b, rows, meq, xr, lr));
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        for (int j = 0; j < n; j++) assert_near(x[j], xr[j], 1e-11 * (1.0 + fabs(xr[j])));
        for (int i = 0; i < meq; i++) assert_near(lam[i], lr[i], 1e-10 * (1.0 + fabs(lr[i])));
        prob_free(&p);
    }
}

/* an inequality the unconstrained minimum satisfies: x = −G⁻¹c, its multiplier 0, not active;
 * and G's strict upper triangle is not read (NaN there changes nothing) */
static void test_inactive(void **state)
{
    (void)state;
    enum { N = 4 };
    uint64_t s = 3;
    problem p = prob(N, 0, 1);
    random_spd(&s, N, 0.3, p.G);
    for (int j = 0; j < N; j++) p.c[j] = urand(&s);
    double xr[N], M[N * N];
    memcpy(M, p.G, sizeof M);
    for (int j = 0; j < N; j++) xr[j] = -p.c[j];
    assert_true(gauss(M, xr, N));
    *arow(&p, 0, 0) = 1.0;
    p.b[0] = xr[0] - 1.0; /* x_0 ≥ x_0* − 1 */
    for (int j = 1; j < N; j++)
        for (int i = 0; i < j; i++) p.G[i + j * N] = (double)NAN;
    double x[N], lam[1];
    int active[1] = {7}, iters = -1;
    assert_int_equal(solve(&p, x, lam, active, NULL, &iters), VT_QP_OPTIMAL);
    for (int j = 0; j < N; j++) assert_near(x[j], xr[j], 1e-13 * (1.0 + fabs(xr[j])));
    assert_true(lam[0] == 0.0);
    assert_int_equal(active[0], 0);
    assert_int_equal(iters, 0);
    prob_free(&p);
}

/* ---- random problems ---- */

static void test_random_kkt(void **state)
{
    (void)state;
    uint64_t s = 20240601;
    int count = 0;
    for (int rep = 0; rep < 300; rep++) {
        const int n = 2 + (int)(rng_next(&s) % 40);
        const int meq = (int)(rng_next(&s) % (uint64_t)(n < 7 ? n : 7));
        const int min = (int)(rng_next(&s) % (uint64_t)(3 * n + 1));
        const double delta = rep % 3 == 0 ? 1e-2 : 1.0;
        problem p = random_problem(&s, n, meq, min, delta);
        double *x = malloc(sizeof(double) * (size_t)n), *lam = malloc(sizeof(double) * (size_t)(meq + min + 1));
        assert_true(x && lam);
        int iters = 0;
        const vt_qp_result r = solve(&p, x, lam, NULL, NULL, &iters);
        if (r != VT_QP_OPTIMAL) fail_msg("rep %d (n %d, meq %d, min %d): %s", rep, n, meq, min, vt_qp_result_string(r));
        assert_true(iters <= vt_qp_iteration_limit(n, meq, min));
        check_kkt(&p, x, lam, 1e-12);
        count++;
        free(x);
        free(lam);
        prob_free(&p);
    }
    assert_int_equal(count, 300);
}

static void test_random_brute(void **state)
{
    (void)state;
    uint64_t s = 77;
    for (int rep = 0; rep < 400; rep++) {
        const int n = 1 + (int)(rng_next(&s) % 6);
        const int meq = (int)(rng_next(&s) % (uint64_t)(n < 3 ? n : 3));
        const int min = (int)(rng_next(&s) % 9);
        problem p = random_problem(&s, n, meq, min, rep % 2 ? 0.05 : 1.0);
        double x[8], xb[8], lam[16];
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        assert_true(brute_force(&p, xb));
        double xn = 0.0;
        for (int j = 0; j < n; j++) xn = fmax(xn, fabs(xb[j]));
        for (int j = 0; j < n; j++) assert_near(x[j], xb[j], 1e-10 * fmax(xn, 1.0));
        check_kkt(&p, x, lam, 1e-12);
        prob_free(&p);
    }
}

/* the tolerances are relative: rows of A and b scaled by 10^k (k in −6..6), G and c by 1e5, x by
 * a change of variables x = 10^3 y: the same y to round-off, the multipliers scaled back */
static void test_scaled(void **state)
{
    (void)state;
    uint64_t s = 606;
    for (int rep = 0; rep < 60; rep++) {
        const int n = 2 + rep % 12, meq = rep % 3 < n ? rep % 3 : 0, min = 1 + rep % 20, m = meq + min;
        problem p = random_problem(&s, n, meq, min, rep % 2 ? 1.0 : 0.05), q = prob(n, meq, min);
        const double gs = 1e5, xs = 1e3; /* q: G' = gs G / xs², c' = gs c / xs in x = xs y */
        double rs[64];
        for (int j = 0; j < n * n; j++) q.G[j] = gs * p.G[j] / (xs * xs);
        for (int j = 0; j < n; j++) q.c[j] = gs * p.c[j] / xs;
        for (int i = 0; i < m; i++) {
            rs[i] = pow(10.0, (double)((int)(rng_next(&s) % 13) - 6));
            for (int j = 0; j < n; j++) *arow(&q, i, j) = rs[i] * *arow(&p, i, j) / xs;
            q.b[i] = rs[i] * p.b[i];
        }
        double y[16], x[16], ly[64], lx[64];
        assert_int_equal(solve(&p, y, ly, NULL, NULL, NULL), VT_QP_OPTIMAL);
        assert_int_equal(solve(&q, x, lx, NULL, NULL, NULL), VT_QP_OPTIMAL);
        double yn = 0.0, ln = 0.0;
        for (int j = 0; j < n; j++) yn = fmax(yn, fabs(y[j]));
        for (int i = 0; i < m; i++) ln = fmax(ln, fabs(ly[i]));
        for (int j = 0; j < n; j++) assert_near(x[j] / xs, y[j], 1e-11 * fmax(yn, 1.0));
        for (int i = 0; i < m; i++) assert_near(lx[i] * rs[i] / gs, ly[i], 1e-9 * fmax(ln, 1e-300));
        check_kkt(&q, x, lx, 1e-12);
        prob_free(&p);
        prob_free(&q);
    }
}

/* ---- contact: pyramids under a wrench balance ---- */

/* nc contacts at points r_k on the ground (z = 0), each with the normal f_z ≥ 0 and K faces
 * μ f_z − (cos φ f_x + sin φ f_y) ≥ 0; the six equalities Σ f_k = F, Σ r_k × f_k = M with
 * (F, M) the wrench of forces chosen inside the cones; G a positive diagonal weight; c = −W f_des */
static problem contact_problem(uint64_t *s, int nc, int K, double mu, int apex_first)
{
    return contact_problem_spread(s, nc, K, mu, apex_first, 1.0);
}
static void test_contact(void **state)
{
    (void)state;
    uint64_t s = 4242;
    for (int rep = 0; rep < 120; rep++) {
        const int nc = 2 + rep % 7, K = rep % 2 ? 8 : 4;
        problem p = contact_problem(&s, nc, K, 0.3 + 0.5 * (urand(&s) + 1.0) / 2.0, rep % 3 == 0);
        double x[24], lam[6 + 8 * 9];
        const vt_qp_result r = solve(&p, x, lam, NULL, NULL, NULL);
        if (r != VT_QP_OPTIMAL) fail_msg("rep %d: %s", rep, vt_qp_result_string(r));
        check_kkt(&p, x, lam, 1e-12);
        prob_free(&p);
    }
}

/* contact points nearly on a line (y within 1e-3 .. 1e-7 of the x axis): a round-off r_j of
 * 1e-16 beside multipliers of 1e3 must not count as a multiplier that decreases (t₁ = u_j / r_j
 * would be 1e16); the KKT conditions as above */
static void test_collinear_contacts(void **state)
{
    (void)state;
    uint64_t s = 30261;
    const double spread[3] = {1e-3, 1e-5, 1e-7};
    for (int rep = 0; rep < 150; rep++) {
        problem p = contact_problem_spread(&s, 3 + rep % 6, rep % 2 ? 8 : 4, 0.4, rep % 5 == 0, spread[rep % 3]);
        double x[24], lam[6 + 8 * 9];
        const vt_qp_result r = solve(&p, x, lam, NULL, NULL, NULL);
        if (r != VT_QP_OPTIMAL) fail_msg("rep %d: %s", rep, vt_qp_result_string(r));
        check_kkt(&p, x, lam, 1e-12);
        prob_free(&p);
    }
}

/* one such problem found by a long random run (three contacts, nearly collinear by chance, the
 * first at its apex): with r_j > 0 taken literally, a round-off r_j of 2e-16 made a dual step of
 * 1e16 and the answer's stationarity failed outright */
static void test_round_off_r(void **state)
{
    (void)state;
    uint64_t s = 11716959347793686543ULL;
    problem p = contact_problem(&s, 3, 4, 0.70586079518517697, 1);
    p.c[2] = 0.0;
    double x[9], lam[6 + 15];
    assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
    check_kkt(&p, x, lam, 1e-12);
    prob_free(&p);
}

/* G = BᵀB + 1e-4 I (condition about 1e5 and more) with c large: the unconstrained minimum lies
 * 1e3 to 1e5 times farther out than the answer, so the iterates carry round-off of that size;
 * the answer is formed afresh from the final factors and still holds the KKT conditions to
 * 1e-12 of its own size */
static void test_ill_conditioned(void **state)
{
    (void)state;
    uint64_t s = 10000;
    for (int rep = 0; rep < 150; rep++) {
        const int n = 8 + rep % 30, meq = rep % 4, min = 2 * n + rep % 7;
        problem p = random_problem(&s, n, meq, min, 1e-4);
        for (int j = 0; j < n; j++) p.c[j] *= 10.0;
        double *x = malloc(sizeof(double) * (size_t)n), *lam = malloc(sizeof(double) * (size_t)(meq + min));
        assert_true(x && lam);
        const vt_qp_result r = solve(&p, x, lam, NULL, NULL, NULL);
        if (r != VT_QP_OPTIMAL) fail_msg("rep %d: %s", rep, vt_qp_result_string(r));
        check_kkt(&p, x, lam, 1e-12);
        free(x);
        free(lam);
        prob_free(&p);
    }
}

/* every constraint through one point (b = 0: x = 0 is feasible, 3n inequalities meet there, a
 * vertex as degenerate as it gets), half of them in pairs of nearly parallel rows: never
 * VT_QP_INFEASIBLE. A dependent violated constraint whose slack is round-off of the active
 * ones' (amplified by their small angle) is implied by them, not a contradiction. */
static void test_cone(void **state)
{
    (void)state;
    uint64_t s = 17138;
    for (int rep = 0; rep < 400; rep++) {
        const int n = 2 + rep % 12, meq = (rep / 12) % 3 < n ? (rep / 12) % 3 : 0, min = 3 * n;
        problem p = random_problem(&s, n, meq, min, 1.0);
        if (rep % 2) { /* in pairs of nearly parallel rows: round-off of x amplified by 1 / angle */
            const double eps = rep % 3 == 0 ? 1e-2 : rep % 3 == 1 ? 1e-3 : 1e-5;
            for (int i = 1; i < meq + min; i += 2)
                for (int j = 0; j < n; j++) *arow(&p, i, j) = *arow(&p, i - 1, j) + eps * urand(&s);
        }
        memset(p.b, 0, sizeof(double) * (size_t)(meq + min));
        double x[16], lam[64];
        const vt_qp_result r = solve(&p, x, lam, NULL, NULL, NULL);
        if (r != VT_QP_OPTIMAL) fail_msg("rep %d (n %d, meq %d): %s", rep, n, meq, vt_qp_result_string(r));
        check_kkt(&p, x, lam, 1e-12);
        prob_free(&p);
    }
}

/* ---- degenerate cases ---- */

/* one contact's pyramid, K faces and the normal all through f = 0; f_des points into the ground,
 * inside the polar cone: the projection is the apex, and the multipliers say f_des = −Σ λ a */
static void test_apex(void **state)
{
    (void)state;
    const int Ks[2] = {4, 8};
    for (int t = 0; t < 2; t++)
        for (int side = 0; side < 2; side++) {
            const int K = Ks[t], min = K + 1;
            const double mu = 0.6, fdes[3] = {0.3, side ? 0.45 : -0.2, -1.0};
            problem p = prob(3, 0, min);
            for (int j = 0; j < 3; j++) {
                p.G[j + j * 3] = 1.0;
                p.c[j] = -fdes[j];
            }
            *arow(&p, 0, 2) = 1.0;
            for (int j = 0; j < K; j++) {
                const double phi = 2.0 * QP_PI * j / K;
                *arow(&p, 1 + j, 0) = -cos(phi);
                *arow(&p, 1 + j, 1) = -sin(phi);
                *arow(&p, 1 + j, 2) = mu;
            }
            double x[3] = {9, 9, 9}, lam[9];
            int active[9];
            assert_int_equal(solve(&p, x, lam, active, NULL, NULL), VT_QP_OPTIMAL);
            for (int j = 0; j < 3; j++) assert_near(x[j], 0.0, 1e-15);
            int na = 0;
            for (int i = 0; i < min; i++) na += active[i];
            assert_true(na <= 3); /* independent normals only */
            check_kkt(&p, x, lam, 1e-13);
            prob_free(&p);
        }
    /* and several contacts under the wrench balance with one of them at its apex */
    uint64_t s = 99;
    for (int rep = 0; rep < 40; rep++) {
        problem p = contact_problem(&s, 3, rep % 2 ? 8 : 4, 0.5, 1);
        /* contact 0 wants to pull: c's z entry makes f_des point into the ground */
        p.c[2] = 5.0 * p.G[2 + 2 * p.n];
        double x[9], lam[6 + 27];
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        check_kkt(&p, x, lam, 1e-12);
        prob_free(&p);
    }
}

/* every constraint of a random problem three times: the same x, the copies' multipliers summing
 * to the single one's */
static void test_duplicated(void **state)
{
    (void)state;
    uint64_t s = 1234;
    for (int rep = 0; rep < 40; rep++) {
        const int n = 2 + rep % 6, min = 1 + rep % 7;
        problem p = random_problem(&s, n, 0, min, 0.5), d = prob(n, 0, 3 * min);
        memcpy(d.G, p.G, sizeof(double) * (size_t)(n * n));
        memcpy(d.c, p.c, sizeof(double) * (size_t)n);
        for (int i = 0; i < 3 * min; i++) {
            for (int j = 0; j < n; j++) *arow(&d, i, j) = *arow(&p, i % min, j);
            d.b[i] = p.b[i % min];
        }
        double x[8], xd[8], lam[8], lamd[24];
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        assert_int_equal(solve(&d, xd, lamd, NULL, NULL, NULL), VT_QP_OPTIMAL);
        for (int j = 0; j < n; j++) assert_near(xd[j], x[j], 1e-12 * (1.0 + fabs(x[j])));
        for (int i = 0; i < min; i++)
            assert_near(lamd[i] + lamd[min + i] + lamd[2 * min + i], lam[i], 1e-11 * (1.0 + fabs(lam[i])));
        check_kkt(&d, xd, lamd, 1e-12);
        prob_free(&p);
        prob_free(&d);
    }
}

/* equalities with dependent rows (a sum and a multiple of two independent ones, consistent):
 * the answer of the two independent ones */
static void test_dependent_equalities(void **state)
{
    (void)state;
    uint64_t s = 8;
    for (int rep = 0; rep < 30; rep++) {
        const int n = 4 + rep % 4, min = rep % 5;
        problem p = random_problem(&s, n, 4, min, 0.5);
        for (int j = 0; j < n; j++) {
            *arow(&p, 2, j) = *arow(&p, 0, j) + *arow(&p, 1, j);
            *arow(&p, 3, j) = -2.5 * *arow(&p, 1, j);
        }
        p.b[2] = p.b[0] + p.b[1];
        p.b[3] = -2.5 * p.b[1];
        /* the reference: the same problem with rows 2 and 3 made trivial (0 = 0) */
        problem r = prob(n, 4, min);
        memcpy(r.G, p.G, sizeof(double) * (size_t)(n * n));
        memcpy(r.c, p.c, sizeof(double) * (size_t)n);
        memcpy(r.A, p.A, sizeof(double) * (size_t)((4 + min) * n));
        memcpy(r.b, p.b, sizeof(double) * (size_t)(4 + min));
        for (int j = 0; j < n; j++) *arow(&r, 2, j) = *arow(&r, 3, j) = 0.0;
        r.b[2] = r.b[3] = 0.0;
        double x[8], xr[8], lam[16], lr[16];
        assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_OPTIMAL);
        assert_int_equal(solve(&r, xr, lr, NULL, NULL, NULL), VT_QP_OPTIMAL);
        for (int j = 0; j < n; j++) assert_near(x[j], xr[j], 1e-12 * (1.0 + fabs(xr[j])));
        check_kkt(&p, x, lam, 1e-12);
        prob_free(&p);
        prob_free(&r);
    }
}

/* ---- infeasible ---- */

static void expect_infeasible(const problem *p, int want_culprit)
{
    double x[24], lam[80];
    int active[80], culprit = -5, iters = 0;
    for (int j = 0; j < 24; j++) x[j] = 100.0 + j;
    for (int j = 0; j < 80; j++) {
        lam[j] = -7.0;
        active[j] = 3;
    }
    assert_int_equal(solve(p, x, lam, active, &culprit, &iters), VT_QP_INFEASIBLE);
    if (want_culprit >= 0) assert_int_equal(culprit, want_culprit);
    assert_true(culprit >= 0 && culprit < p->meq + p->min);
    for (int j = 0; j < 24; j++) assert_true(x[j] == 100.0 + j);
    for (int j = 0; j < 80; j++) assert_true(lam[j] == -7.0 && active[j] == 3);
    assert_true(iters > 0 && iters <= vt_qp_iteration_limit(p->n, p->meq, p->min));
}

static void test_infeasible(void **state)
{
    (void)state;
    /* x_0 ≥ 1 and −x_0 ≥ 0 in 3-D with a coupled G: the second one added is the culprit */
    problem p = prob(3, 0, 3);
    uint64_t s = 17;
    random_spd(&s, 3, 0.5, p.G);
    *arow(&p, 0, 1) = 1.0; /* x_1 ≥ −10: satisfied throughout */
    p.b[0] = -10.0;
    *arow(&p, 1, 0) = 1.0;
    p.b[1] = 1.0;
    *arow(&p, 2, 0) = -1.0;
    p.b[2] = 0.0;
    expect_infeasible(&p, 2);
    prob_free(&p);

    /* a pyramid that cannot carry a required tangential force: f_x = 1, f_z = 1, μ = 0.5 */
    p = prob(3, 2, 5);
    for (int j = 0; j < 3; j++) p.G[j + j * 3] = 1.0;
    *arow(&p, 0, 0) = 1.0;
    p.b[0] = 1.0;
    *arow(&p, 1, 2) = 1.0;
    p.b[1] = 1.0;
    *arow(&p, 2, 2) = 1.0;
    for (int j = 0; j < 4; j++) {
        const double phi = 2.0 * QP_PI * j / 4;
        *arow(&p, 3 + j, 0) = -cos(phi);
        *arow(&p, 3 + j, 1) = -sin(phi);
        *arow(&p, 3 + j, 2) = 0.5;
    }
    expect_infeasible(&p, 3); /* the face φ = 0: μ f_z − f_x ≥ 0 */
    prob_free(&p);

    /* the same over several contacts: the balance asks more tangential force than μ Σ f_z */
    s = 5;
    for (int rep = 0; rep < 20; rep++) {
        const int nc = 2 + rep % 4, K = rep % 2 ? 8 : 4;
        problem q = contact_problem(&s, nc, K, 0.5, 0);
        double fz = q.b[2];
        q.b[0] = 0.6 * fz; /* |Σ f_x| ≤ Σ |f_x| ≤ μ Σ f_z = 0.5 F_z */
        q.b[1] = 0.0;
        double x[24], lam[80];
        int culprit = -1;
        assert_int_equal(solve(&q, x, lam, NULL, &culprit, NULL), VT_QP_INFEASIBLE);
        assert_true(culprit >= 6); /* a face or a normal: the six equalities are consistent */
        expect_infeasible(&q, culprit);
        prob_free(&q);
    }

    /* dependent, inconsistent equalities: the third is the culprit */
    p = prob(3, 3, 0);
    for (int j = 0; j < 3; j++) p.G[j + j * 3] = 2.0;
    *arow(&p, 0, 0) = 1.0;
    *arow(&p, 0, 1) = 1.0;
    p.b[0] = 1.0;
    *arow(&p, 1, 2) = 1.0;
    p.b[1] = 2.0;
    *arow(&p, 2, 0) = 2.0;
    *arow(&p, 2, 1) = 2.0;
    p.b[2] = 2.5;
    expect_infeasible(&p, 2);
    prob_free(&p);

    /* a zero row asking 0 ≥ 1 */
    p = prob(2, 0, 2);
    p.G[0] = p.G[3] = 1.0;
    *arow(&p, 0, 0) = 1.0;
    p.b[1] = 1.0;
    expect_infeasible(&p, 1);
    prob_free(&p);
}

/* ---- errors and scratch ---- */

/* tests/qp_rotated_infeasible.txt (its opening lines say what it holds): the numbers after its
 * comment lines into v, at most cap of them; the count */
static int read_numbers(const char *path, double *v, int cap)
{
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[256];
    int k = 0;
    while (fgets(line, sizeof line, f))
        for (char *t = line, *end; *t && *t != '#' && k < cap; t = end) {
            const double x = strtod(t, &end);
            if (end == t) break;
            v[k++] = x;
        }
    fclose(f);
    return k;
}

/* A distribution problem of the contacts the fuzzer found (fuzz/corpus_contact/
 * qp-optimal-violated-refused-by-certificate), its six equalities rotated by an SVD as the
 * contacts' independent rows are; G of condition 2.8e5. After a score of steps a row dependent on
 * the active ones kept ‖J₂ᵀa‖ at twice its round-off bound (J's rotations add to it), its full step
 * of 1e25 threw x to 3e18, and the method answered VT_QP_OPTIMAL with constraints violated by as
 * much. It is infeasible: the file's Farkas certificate, y and z ≥ 0 with r = A_eqᵀy + A_inᵀz and
 * γ = b_eqᵀy + b_inᵀz, gives for a feasible x 0 ≤ zᵀ(A_in x − b_in) = rᵀx − γ, so ‖x‖₁ ≥ γ/‖r‖_∞,
 * checked here to exceed 1e12 (quadprog and HiGHS call it infeasible too) */
static void test_infeasible_rotated_contacts(void **state)
{
    (void)state;
    enum { CAP = 1024 };
    double *v = calloc(CAP, sizeof(double));
    assert_non_null(v);
    const int k = read_numbers(VT_TEST_QP_CASE, v, CAP);
    assert_true(k >= 3);
    const int n = (int)v[0], meq = (int)v[1], min = (int)v[2], m = meq + min;
    assert_int_equal(k, 3 + n * n + n + m * n + m + m);
    problem p = prob(n, meq, min);
    const double *G = v + 3, *c = G + n * n, *Aeq = c + n, *beq = Aeq + meq * n, *Ain = beq + meq,
                 *bin = Ain + min * n, *y = bin + min, *z = y + meq;
    memcpy(p.G, G, (size_t)(n * n) * sizeof(double));
    memcpy(p.c, c, (size_t)n * sizeof(double));
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < meq; i++) *arow(&p, i, j) = Aeq[i + j * meq];
        for (int i = 0; i < min; i++) *arow(&p, meq + i, j) = Ain[i + j * min];
    }
    memcpy(p.b, beq, (size_t)meq * sizeof(double));
    memcpy(p.b + meq, bin, (size_t)min * sizeof(double));
    double gamma = 0.0, rmax = 0.0;
    for (int i = 0; i < meq; i++) gamma += beq[i] * y[i];
    for (int i = 0; i < min; i++) {
        assert_true(z[i] >= 0.0);
        gamma += bin[i] * z[i];
    }
    for (int j = 0; j < n; j++) {
        double r = 0.0;
        for (int i = 0; i < meq; i++) r += Aeq[i + j * meq] * y[i];
        for (int i = 0; i < min; i++) r += Ain[i + j * min] * z[i];
        rmax = fmax(rmax, fabs(r));
    }
    assert_true(gamma > 0.5 && gamma > 1e12 * rmax);
    expect_infeasible(&p, -1);
    prob_free(&p);
    free(v);
}

static void test_errors(void **state)
{
    (void)state;
    uint64_t s = 31;
    problem p = random_problem(&s, 4, 1, 3, 0.5);
    double x[4] = {1, 2, 3, 4}, lam[4] = {5, 6, 7, 8};
    const double x0[4] = {1, 2, 3, 4}, l0[4] = {5, 6, 7, 8};
    double *slots[5] = {&p.G[1], &p.c[2], &p.A[5], &p.b[0], &p.b[3]}; /* G's lower triangle, c, A, b_eq, b_in */
    for (int k = 0; k < 5; k++)
        for (int v = 0; v < 2; v++) {
            const double keep = *slots[k];
            *slots[k] = v ? (double)INFINITY : (double)NAN;
            assert_int_equal(solve(&p, x, lam, NULL, NULL, NULL), VT_QP_NONFINITE);
            assert_memory_equal(x, x0, sizeof x);
            assert_memory_equal(lam, l0, sizeof lam);
            *slots[k] = keep;
        }
    /* finite data whose minimum overflows: G = 1e-300 I, c = 1e10 (x = −1e310) */
    {
        problem o = prob(2, 0, 1);
        o.G[0] = o.G[3] = 1e-300;
        o.c[0] = o.c[1] = 1e10;
        *arow(&o, 0, 0) = 1.0;
        o.b[0] = -1.0;
        assert_int_equal(solve(&o, x, lam, NULL, NULL, NULL), VT_QP_NONFINITE);
        assert_memory_equal(x, x0, sizeof x);
        prob_free(&o);
    }
    /* indefinite, then singular G */
    problem q = random_problem(&s, 4, 1, 3, 0.5);
    memset(q.G, 0, sizeof(double) * 16);
    for (int j = 0; j < 4; j++) q.G[j + j * 4] = j == 2 ? -1.0 : 1.0;
    assert_int_equal(solve(&q, x, lam, NULL, NULL, NULL), VT_QP_NOT_CONVEX);
    q.G[2 + 2 * 4] = 0.0;
    assert_int_equal(solve(&q, x, lam, NULL, NULL, NULL), VT_QP_NOT_CONVEX);
    assert_memory_equal(x, x0, sizeof x);
    assert_memory_equal(lam, l0, sizeof lam);
    /* invalid sizes and pointers */
    char work[4096];
    int culprit = 9;
    assert_int_equal(vt_qp_solve(0, p.G, 4, p.c, 0, NULL, 1, NULL, 0, NULL, 1, NULL, x, NULL, NULL, &culprit, work,
                                 sizeof work, NULL),
                     VT_QP_INVALID);
    assert_int_equal(culprit, -1);
    assert_int_equal(vt_qp_solve(4, p.G, 3, p.c, 0, NULL, 1, NULL, 0, NULL, 1, NULL, x, NULL, NULL, NULL, work,
                                 sizeof work, NULL),
                     VT_QP_INVALID);
    assert_int_equal(vt_qp_solve(4, p.G, 4, p.c, 2, p.A, 1, p.b, 0, NULL, 1, NULL, x, NULL, NULL, NULL, work,
                                 sizeof work, NULL),
                     VT_QP_INVALID);
    assert_int_equal(vt_qp_solve(4, p.G, 4, p.c, 0, NULL, 1, NULL, 0, NULL, 1, NULL, NULL, NULL, NULL, NULL, work,
                                 sizeof work, NULL),
                     VT_QP_INVALID);
    assert_memory_equal(x, x0, sizeof x);
    assert_int_equal(vt_qp_scratch_bytes(0, 0, 0), 0);
    assert_int_equal(vt_qp_scratch_bytes(3, -1, 0), 0);
    assert_string_equal(vt_qp_result_string(VT_QP_INFEASIBLE), "infeasible");
    prob_free(&p);
    prob_free(&q);
}

static void test_scratch(void **state)
{
    (void)state;
    uint64_t s = 64;
    for (int rep = 0; rep < 12; rep++) {
        const int n = 1 + rep * 3, meq = rep % 4 < n ? rep % 4 : 0, min = 2 * rep;
        problem p = random_problem(&s, n, meq, min, 0.5);
        const int m = meq + min, ld = m > 0 ? m : 1;
        const size_t bytes = vt_qp_scratch_bytes(n, meq, min);
        assert_true(bytes > 0);
        /* exactly the bound, at every offset from an aligned address; a guard byte after it */
        unsigned char *buf = malloc(bytes + 16);
        assert_non_null(buf);
        double *x = malloc(sizeof(double) * (size_t)n), *xr = malloc(sizeof(double) * (size_t)n);
        assert_true(x && xr);
        for (int off = 0; off < 8; off++) {
            memset(buf, 0xA5, bytes + 16);
            const vt_qp_result r = vt_qp_solve(n, p.G, n, p.c, meq, p.A, ld, p.b, min, p.A + meq, ld, p.b + meq, x,
                                               NULL, NULL, NULL, buf + off, bytes, NULL);
            assert_int_equal(r, VT_QP_OPTIMAL);
            for (int g = (int)bytes + off; g < (int)bytes + 16; g++) assert_int_equal(buf[g], 0xA5);
            if (off == 0) memcpy(xr, x, sizeof(double) * (size_t)n);
            for (int j = 0; j < n; j++) assert_true(x[j] == xr[j]);
            for (int j = 0; j < n; j++) x[j] = 42.0;
            assert_int_equal(vt_qp_solve(n, p.G, n, p.c, meq, p.A, ld, p.b, min, p.A + meq, ld, p.b + meq, x, NULL,
                                         NULL, NULL, buf + off, bytes - 1, NULL),
                             VT_QP_NO_SCRATCH);
            for (int j = 0; j < n; j++) assert_true(x[j] == 42.0);
        }
        assert_int_equal(vt_qp_solve(n, p.G, n, p.c, meq, p.A, ld, p.b, min, p.A + meq, ld, p.b + meq, x, NULL, NULL,
                                     NULL, NULL, bytes, NULL),
                         VT_QP_NO_SCRATCH);
        free(buf);
        free(x);
        free(xr);
        prob_free(&p);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box),          cmocka_unit_test(test_halfspace),
        cmocka_unit_test(test_simplex),      cmocka_unit_test(test_equality_only),
        cmocka_unit_test(test_inactive),     cmocka_unit_test(test_random_kkt),
        cmocka_unit_test(test_random_brute), cmocka_unit_test(test_scaled),
        cmocka_unit_test(test_contact),
        cmocka_unit_test(test_collinear_contacts), cmocka_unit_test(test_round_off_r),
        cmocka_unit_test(test_ill_conditioned),
        cmocka_unit_test(test_cone),
        cmocka_unit_test(test_apex),         cmocka_unit_test(test_duplicated),
        cmocka_unit_test(test_dependent_equalities), cmocka_unit_test(test_infeasible),
        cmocka_unit_test(test_infeasible_rotated_contacts),
        cmocka_unit_test(test_errors),       cmocka_unit_test(test_scratch),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
