/* vtdyn — The solve stage's small dense kernels: exact conditions of small systems, the SPD
 * solve, the square route's LU (numeric/kkt.c). */
#ifndef VT_NUMERIC_KKT_H
#define VT_NUMERIC_KKT_H

#include <stddef.h>

#include "vtdyn.h"
#include "numeric/route.h"

size_t vt_kkt_scratch(const vt_model *m);

/* Small systems (n ≤ VT_EXACT_RCOND_N): the exact 1-norm reciprocal condition from the inverse.
 * vt_small_inverse takes the identity X (n x n) with `extra` (≤ VT_EXACT_EXTRA) columns after it
 * from the arena, or returns NULL for a larger n (the caller then estimates) or when the arena
 * failed (the caller's next allocation says so); vt_rcond_from_inverse: 1 / (anorm ‖X‖_1), 0
 * when either is 0 */
#define VT_EXACT_RCOND_N 16
#define VT_EXACT_EXTRA 2 /* most extra columns asked for */
double *vt_small_inverse(vt_data *d, int n, int extra);
double vt_rcond_from_inverse(const double *X, int n, double anorm);
/* *out = the 1-norm of the symmetric n x n K from its lower triangle (LAPACK's dlansy); 0 or a
 * negative vt_status */
int vt_norm1_sym(vt_data *d, const double *K, int n, double *out);
/* S b' = b for the symmetric positive definite n x n S (its lower triangle, overwritten: scaled
 * to unit diagonal, then factorized), b solved in place, the reciprocal condition of S at unit
 * diagonal into *rcond: 1 for n ≤ 1, exact from the inverse for n ≤ 16, dpocon's estimate above,
 * 0 when S is not positive definite (nothing solved). Returns 0 or a negative vt_status. */
int vt_solve_spd(vt_data *d, double *S, int n, double *b, double *rcond);

/* vt_solve's square route in two halves, its state on the arena: the LU of R Φ_q D;
 * D (s) and R (g); q̈ (x) and then M* q̈ − Q, overwritten by λ (h). vt_square_first factorizes
 * (the rates' scaling from M*'s diagonal mdiag[a stride]) and solves q̈ = Φ_q^-1 γ; with
 * h = M* q̈ − Q in sq->h, vt_square_second solves λ. They return VT_SOLVED (0), VT_BELOW_MIN (1:
 * the estimate below rcond_min or an exactly zero pivot, nothing solved; vt_square_first only)
 * or a negative vt_status. */
typedef struct {
    double *A, *s, *g, *x, *h;
    double *w;  /* 2 nv: a solve's vectors in the LU's column order */
    int *ipiv;
    int *perm;  /* nv: the LU's column k is rate perm[k] (a fill-reducing order), or NULL: rate k */
    int *rows;  /* nv: the LU's row k is row rows[k] of R Φ_q D (ipiv's interchanges, composed) */
    int solved; /* x holds Φ_q^-1 b already (the factorization's b) */
} vt_square;
int vt_square_first(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond);
int vt_square_second(const vt_model *m, vt_data *d, vt_square *sq);
/* x = sign Φ_q^-1 b (nv) by the factors of sq: D (R Φ_q D)^-1 R b */
int vt_square_apply(const vt_model *m, vt_data *d, const vt_square *sq, const double *b, double sign, double *x);
/* the same for the recursive evaluation: the factors from M*'s diagonal mdiag (nv) and the
 * positions (VT_BELOW_MIN also for a zero row; _with: and Φ_q^-1 b, b (nv) γ when it is known or
 * NULL, solved with the condition's first solve), q̈, and the outcome */
int vt_solve_square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, double *rcond);
int vt_solve_square_factor_with(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, const double *b,
                                double *rcond);
int vt_solve_square_accelerations(const vt_model *m, vt_data *d, vt_square *sq);
vt_status vt_solve_square_end(const vt_model *m, vt_data *d, vt_square *sq, double rcond);

#endif
