/* The distribution QP's peer (tests/peers/check_qp.py): writes a fixed set of QPs and vtdyn's
 * answers (src/numeric/qp.c) as JSON, for quadprog to solve the same problems.
 *   qp_problems OUT.json
 * The families (fixed seeds):
 *   random       G = BᵀB + δI (δ = 1 or 1e-2), n 2..60, up to 8 equalities and 3n inequalities,
 *                feasible by construction (x0 chosen, b made so that x0 is feasible, a third of
 *                the inequalities through x0);
 *   contact      3..8 contact points with friction pyramids of 4 or 8 faces under a six-row
 *                wrench balance, forces chosen inside the cones, a diagonal weight;
 *   apex         the same with one contact pulled into the ground (its force at or near the apex);
 *   collinear    the same with the points within 1e-3 or 1e-5 of a line (the balance's rows
 *                nearly dependent);
 *   ill-conditioned  G = BᵀB + 1e-4 I and c large (the unconstrained minimum far beyond the
 *                answer);
 *   duplicated   random problems with every inequality given twice;
 *   either       random problems with b_in at random (not made feasible): some feasible, some not;
 *   infeasible   contact problems whose balance asks more tangential force than μ Σ f_z allows.
 * Matrices are written row by row (G[i][j], A[i][j] with A = [A_eq; A_in]). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "numeric/qp.h" /* internal */
#include "../qp_problem.h"

/* problem, its generator and families: tests/qp_problem.h (test_qp's too); out of memory here
 * ends the program */
static problem checked(problem p)
{
    if (!prob_ok(&p)) {
        fprintf(stderr, "qp_problems: out of memory\n");
        exit(2);
    }
    return p;
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p) {
        fprintf(stderr, "qp_problems: out of memory\n");
        exit(2);
    }
    return p;
}

/* the contact family, contact 0 pulled into the ground with apex (its force at or near the apex) */
static problem contact_problem(uint64_t *s, int nc, int K, double mu, int apex, double yspread)
{
    problem p = checked(contact_problem_spread(s, nc, K, mu, apex, yspread));
    if (apex) p.c[2] = 5.0 * p.G[2 + 2 * p.n];
    return p;
}

static void write_vec(FILE *f, const char *key, const double *v, int n, int stride)
{
    fprintf(f, "\"%s\": [", key);
    for (int i = 0; i < n; i++) fprintf(f, "%s%.17g", i ? ", " : "", v[(size_t)i * (size_t)stride]);
    fprintf(f, "]");
}

/* solves p by vt_qp_solve and writes it and the answer as one JSON object */
static void emit(FILE *f, int *first, const char *family, int id, const problem *p)
{
    const int n = p->n, m = p->meq + p->min, ld = m > 0 ? m : 1;
    const size_t bytes = vt_qp_scratch_bytes(n, p->meq, p->min);
    void *work = xcalloc(bytes, 1);
    double *x = xcalloc((size_t)n, sizeof(double)), *lam = xcalloc((size_t)m, sizeof(double));
    int culprit = -1, iters = 0;
    const vt_qp_result r = vt_qp_solve(n, p->G, n, p->c, p->meq, p->A, ld, p->b, p->min, p->A + p->meq, ld,
                                       p->b + p->meq, x, lam, NULL, &culprit, work, bytes, &iters);
    fprintf(f, "%s\n  {\"family\": \"%s\", \"id\": %d, \"n\": %d, \"meq\": %d, \"min\": %d,\n   \"G\": [", *first ? "" : ",",
            family, id, n, p->meq, p->min);
    for (int i = 0; i < n; i++) {
        fprintf(f, "%s[", i ? ", " : "");
        for (int j = 0; j < n; j++) fprintf(f, "%s%.17g", j ? ", " : "", p->G[i + j * n]);
        fprintf(f, "]");
    }
    fprintf(f, "],\n   ");
    write_vec(f, "c", p->c, n, 1);
    fprintf(f, ",\n   \"A\": [");
    for (int i = 0; i < m; i++) {
        fprintf(f, "%s[", i ? ", " : "");
        for (int j = 0; j < n; j++) fprintf(f, "%s%.17g", j ? ", " : "", p->A[i + j * m]);
        fprintf(f, "]");
    }
    fprintf(f, "],\n   ");
    write_vec(f, "b", p->b, m, 1);
    fprintf(f, ",\n   \"status\": \"%s\", \"culprit\": %d, \"iterations\": %d", vt_qp_result_string(r), culprit, iters);
    if (r == VT_QP_OPTIMAL) {
        fprintf(f, ",\n   ");
        write_vec(f, "x", x, n, 1);
        fprintf(f, ",\n   ");
        write_vec(f, "lambda", lam, m, 1);
    }
    fprintf(f, "}");
    *first = 0;
    free(work);
    free(x);
    free(lam);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: qp_problems OUT.json\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "w");
    if (!f) {
        perror(argv[1]);
        return 2;
    }
    int first = 1;
    fprintf(f, "{\"problems\": [");
    uint64_t s = 1983; /* Goldfarb and Idnani's year */
    for (int id = 0; id < 150; id++) {
        const int n = 2 + (int)(rng_next(&s) % 59);
        const int meq = (int)(rng_next(&s) % (uint64_t)(n < 9 ? n : 9));
        const int min = (int)(rng_next(&s) % (uint64_t)(3 * n + 1));
        problem p = checked(random_problem(&s, n, meq, min, id % 3 == 0 ? 1e-2 : 1.0));
        emit(f, &first, "random", id, &p);
        prob_free(&p);
    }
    for (int id = 0; id < 60; id++) {
        problem p = contact_problem(&s, 3 + id % 6, id % 2 ? 8 : 4, 0.3 + 0.25 * (urand(&s) + 1.0), 0, 1.0);
        emit(f, &first, "contact", id, &p);
        prob_free(&p);
    }
    for (int id = 0; id < 30; id++) {
        problem p = contact_problem(&s, 3 + id % 4, id % 2 ? 8 : 4, 0.5, 1, 1.0);
        emit(f, &first, "apex", id, &p);
        prob_free(&p);
    }
    for (int id = 0; id < 30; id++) {
        problem p = contact_problem(&s, 3 + id % 6, id % 2 ? 8 : 4, 0.4, id % 3 == 0, id % 2 ? 1e-3 : 1e-5);
        emit(f, &first, "collinear", id, &p);
        prob_free(&p);
    }
    for (int id = 0; id < 30; id++) {
        const int n = 8 + id % 30, meq = id % 4, min = 2 * n + id % 7;
        problem p = checked(random_problem(&s, n, meq, min, 1e-4));
        for (int j = 0; j < n; j++) p.c[j] *= 10.0;
        emit(f, &first, "ill-conditioned", id, &p);
        prob_free(&p);
    }
    for (int id = 0; id < 30; id++) {
        const int n = 2 + id % 10, min = 1 + id % 12;
        problem p = checked(random_problem(&s, n, id % 3, min, 0.5)), d = checked(prob_new(n, p.meq, 2 * min));
        memcpy(d.G, p.G, sizeof(double) * (size_t)(n * n));
        memcpy(d.c, p.c, sizeof(double) * (size_t)n);
        for (int i = 0; i < d.meq + d.min; i++) {
            const int from = i < p.meq ? i : p.meq + (i - p.meq) % min;
            for (int j = 0; j < n; j++) *arow(&d, i, j) = *arow(&p, from, j);
            d.b[i] = p.b[from];
        }
        emit(f, &first, "duplicated", id, &d);
        prob_free(&p);
        prob_free(&d);
    }
    for (int id = 0; id < 60; id++) { /* b at random, not made feasible: feasible or not */
        const int n = 2 + id % 9, meq = id % 3 < n ? id % 3 : 0, min = 2 * n + id % 5;
        problem p = checked(random_problem(&s, n, meq, min, 1.0));
        for (int i = meq; i < meq + min; i++) p.b[i] = 1.5 * urand(&s) + 0.6;
        emit(f, &first, "either", id, &p);
        prob_free(&p);
    }
    for (int id = 0; id < 20; id++) {
        problem p = contact_problem(&s, 3 + id % 4, id % 2 ? 8 : 4, 0.5, 0, 1.0);
        p.b[0] = 0.6 * p.b[2]; /* Σ f_x ≤ μ Σ f_z = 0.5 F_z: more is infeasible */
        p.b[1] = 0.0;
        emit(f, &first, "infeasible", id, &p);
        prob_free(&p);
    }
    fprintf(f, "\n]}\n");
    if (fclose(f) != 0) {
        perror(argv[1]);
        return 2;
    }
    return 0;
}
