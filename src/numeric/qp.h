/* vtdyn — A small dense strictly convex quadratic program by the Goldfarb–Idnani dual method
 * (numeric/qp.c): the contact forces' distribution rule.
 *
 *   minimize ½ xᵀ G x + cᵀ x   subject to   A_eq x = b_eq   (meq rows)
 *                                            A_in x ≥ b_in   (min rows)
 *
 * G symmetric positive definite (n x n, only its lower triangle is read). Matrices are
 * column-major, LAPACK's convention, and each constraint is a ROW of its matrix: A_eq is
 * meq x n with leading dimension ldaeq ≥ max(1, meq), A_in is min x n with ldain ≥ max(1, min),
 * so that row i, A[i + j·ld] for j = 0..n−1, is the normal of constraint i.
 *
 * The multipliers are those of the Lagrangian ½ xᵀGx + cᵀx − λ_eqᵀ(A_eq x − b_eq) − λ_inᵀ(A_in x
 * − b_in): at the optimum
 *     G x + c − A_eqᵀ λ_eq − A_inᵀ λ_in = 0,   λ_in ≥ 0,   λ_in,i (A_in x − b_in)_i = 0.
 * Constraints are numbered equalities first (0..meq−1), then inequalities (meq..meq+min−1), in
 * lambda, active and culprit alike. */
#ifndef VT_NUMERIC_QP_H
#define VT_NUMERIC_QP_H

#include <stddef.h>

typedef enum vt_qp_result {
    VT_QP_OPTIMAL = 0,         /* x, lambda (and active) hold the optimum */
    VT_QP_INFEASIBLE,          /* no x satisfies the constraints: *culprit names the one that could
                                * not be added (it depends on the active ones, none of which can go) */
    VT_QP_NOT_CONVEX,          /* G is not positive definite (its Cholesky factorization failed) */
    VT_QP_ITERATION_LIMIT,     /* more than vt_qp_iteration_limit() steps (round-off cycling; not
                                * seen in the tests) */
    VT_QP_NONFINITE,           /* NaN or Inf in G's lower triangle, c, A_eq, b_eq, A_in or b_in
                                * (or steps that overflowed on data near DBL_MAX) */
    VT_QP_NO_SCRATCH,          /* work_bytes < vt_qp_scratch_bytes(n, meq, min), or work NULL */
    VT_QP_INVALID              /* n < 1, meq or min < 0, a leading dimension too small, a required
                                * pointer NULL */
} vt_qp_result;

/* The bytes of work vt_qp_solve needs (any alignment: it aligns inside); 0 for invalid sizes.
 * 3n² + 5n + meq + min doubles and n + meq + min ints. */
size_t vt_qp_scratch_bytes(int n, int meq, int min);

/* The bound on the steps (each adds or drops one constraint): 10 (n + meq + min) + 100. */
int vt_qp_iteration_limit(int n, int meq, int min);

/* Solves the QP above. On VT_QP_OPTIMAL: x (n) the minimizer; lambda (meq + min, or NULL) the
 * multipliers (0 for a constraint not active, and for an equality dependent on earlier ones and
 * consistent with them); active (meq + min, or NULL) 1 for a constraint in the final active set,
 * 0 otherwise. On any other result x, lambda and active are left as the caller passed them.
 * culprit (or NULL): on VT_QP_INFEASIBLE the constraint's index, −1 otherwise. iterations (or
 * NULL): the steps taken, whatever the result. The problem's arrays are only read; nothing is
 * allocated and there is no global state (threads may call it at once on their own work). */
vt_qp_result vt_qp_solve(int n, const double *G, int ldg, const double *c,
                         int meq, const double *Aeq, int ldaeq, const double *beq,
                         int min, const double *Ain, int ldain, const double *bin,
                         double *x, double *lambda, int *active, int *culprit,
                         void *work, size_t work_bytes, int *iterations);

/* A short English name of a result ("optimal", "infeasible", ...) */
const char *vt_qp_result_string(vt_qp_result r);

#endif
