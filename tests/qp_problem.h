/* The distribution QP's test problems, shared by tests/test_qp.c and the quadprog peer
 * (tests/peers/qp_problems.c), so that both draw the same families from the same seeds:
 *   minimize ½ xᵀGx + cᵀx  subject to  A_eq x = b_eq,  A_in x ≥ b_in,
 * A the (meq + min) x n stack [A_eq; A_in], column-major with ld meq + min, b likewise. */
#ifndef VT_TESTS_QP_PROBLEM_H
#define VT_TESTS_QP_PROBLEM_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#define QP_PI 3.14159265358979323846

typedef struct {
    int n, meq, min;
    double *G, *c, *A, *b;
} problem;

/* the arrays zeroed (one more entry each, never a zero-size allocation); prob_ok is 0 where one
 * allocation failed */
static inline problem prob_new(int n, int meq, int min)
{
    problem p = {n, meq, min, calloc((size_t)(n * n) + 1, sizeof(double)), calloc((size_t)n + 1, sizeof(double)),
                 calloc((size_t)((meq + min) * n) + 1, sizeof(double)), calloc((size_t)(meq + min) + 1, sizeof(double))};
    return p;
}
static inline int prob_ok(const problem *p) { return p->G && p->c && p->A && p->b; }
static inline void prob_free(problem *p)
{
    free(p->G);
    free(p->c);
    free(p->A);
    free(p->b);
}
static inline double *arow(problem *p, int i, int j) { return &p->A[i + j * (p->meq + p->min)]; }

/* a fixed-seed generator (splitmix64) and a uniform number in [−1, 1) */
static inline uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}
static inline double urand(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1.0p-53 * 2.0 - 1.0; }

/* G = BᵀB + δI with B n x n of uniform entries; 0, or −1 out of memory */
static inline int random_spd(uint64_t *s, int n, double delta, double *G)
{
    double *B = malloc(sizeof(double) * (size_t)(n * n) + 1);
    if (!B) return -1;
    for (int i = 0; i < n * n; i++) B[i] = urand(s);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double v = i == j ? delta : 0.0;
            for (int k = 0; k < n; k++) v += B[k + i * n] * B[k + j * n];
            G[i + j * n] = v;
        }
    free(B);
    return 0;
}

/* a random feasible problem: x0 random, b_eq = A_eq x0, b_in = A_in x0 − slack with a third of
 * the slacks 0 (constraints through x0) and the rest in [0, 1); c pulls x away from x0. Check
 * prob_ok. */
static inline problem random_problem(uint64_t *s, int n, int meq, int min, double delta)
{
    problem p = prob_new(n, meq, min);
    double *x0 = malloc(sizeof(double) * (size_t)n + 1);
    if (!prob_ok(&p) || !x0 || random_spd(s, n, delta, p.G)) {
        free(x0);
        free(p.G);
        p.G = NULL;
        return p;
    }
    for (int j = 0; j < n; j++) x0[j] = urand(s);
    for (int j = 0; j < n; j++) p.c[j] = 3.0 * urand(s);
    for (int i = 0; i < meq + min; i++) {
        double v = 0.0;
        for (int j = 0; j < n; j++) {
            *arow(&p, i, j) = urand(s);
            v += *arow(&p, i, j) * x0[j];
        }
        p.b[i] = v - (i < meq || rng_next(s) % 3 == 0 ? 0.0 : 0.5 * (urand(s) + 1.0));
    }
    free(x0);
    return p;
}

/* nc ground contacts (z = 0), each f_z ≥ 0 and K faces μ f_z − (cos φ f_x + sin φ f_y) ≥ 0; the
 * six equalities Σ f_k = F, Σ r_k × f_k = M with (F, M) the wrench of forces chosen inside the
 * cones (contact 0's at the apex with apex_first); the points' y scaled by yspread (≪ 1: nearly
 * collinear points, the moment rows nearly dependent); G a positive diagonal weight, c = −W f_des
 * with a desired force anywhere (many faces active). nc ≤ 8. Check prob_ok. */
static inline problem contact_problem_spread(uint64_t *s, int nc, int K, double mu, int apex_first, double yspread)
{
    const int n = 3 * nc, meq = 6;
    problem p = prob_new(n, meq, nc * (K + 1));
    if (!prob_ok(&p)) return p;
    double f0[3 * 8], r[3 * 8];
    for (int k = 0; k < nc; k++) {
        r[3 * k] = urand(s);
        r[3 * k + 1] = yspread * urand(s);
        r[3 * k + 2] = 0.0;
        const double fz = apex_first && k == 0 ? 0.0 : 1.0 + urand(s);
        const double ang = QP_PI * urand(s), rad = 0.5 * mu * cos(QP_PI / K) * fz * (1.0 + urand(s)) / 2.0;
        f0[3 * k] = rad * cos(ang);
        f0[3 * k + 1] = rad * sin(ang);
        f0[3 * k + 2] = fz;
    }
    double wrench[6] = {0};
    for (int k = 0; k < nc; k++) {
        const double *f = f0 + 3 * k, *rk = r + 3 * k;
        for (int a = 0; a < 3; a++) {
            /* Σ f: row a, Σ r × f: row 3 + a, (r × f)_a = r_b f_c − r_c f_b */
            *arow(&p, a, 3 * k + a) = 1.0;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            *arow(&p, 3 + a, 3 * k + c) += rk[b];
            *arow(&p, 3 + a, 3 * k + b) -= rk[c];
            wrench[a] += f[a];
            wrench[3 + a] += rk[b] * f[c] - rk[c] * f[b];
        }
        const int base = meq + k * (K + 1);
        *arow(&p, base, 3 * k + 2) = 1.0;
        for (int j = 0; j < K; j++) {
            const double phi = 2.0 * QP_PI * j / K;
            *arow(&p, base + 1 + j, 3 * k) = -cos(phi);
            *arow(&p, base + 1 + j, 3 * k + 1) = -sin(phi);
            *arow(&p, base + 1 + j, 3 * k + 2) = mu;
        }
    }
    for (int a = 0; a < 6; a++) p.b[a] = wrench[a];
    for (int j = 0; j < n; j++) {
        const double wgt = 1.0 + 0.5 * (urand(s) + 1.0);
        p.G[j + j * n] = wgt;
        p.c[j] = -wgt * 2.0 * urand(s);
    }
    return p;
}

#endif
