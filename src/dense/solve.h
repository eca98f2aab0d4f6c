/* vtdyn — The solve stage and its numeric kernels (dense/solve.c). */
#ifndef VT_DENSE_SOLVE_H
#define VT_DENSE_SOLVE_H

#include <float.h>
#include <stddef.h>

#include "vtdyn.h"

size_t vt_solve_scratch(const vt_model *m);

/* every multiplier unique (vt_solve's exact routes) */
static inline void vt_mark_unique(const vt_model *m, vt_data *d)
{
    int *lu = d->lambda_unique;
    for (int r = 0; r < m->nc; r++) lu[r] = 1;
}
/* what a successful solve with independent rows records: the route, rcond and its warning,
 * rank nc, no residual, every multiplier unique (solve.c) */
void vt_solved(const vt_model *m, vt_data *d, vt_route route, double rcond);
/* vt_solve without the argument check and without clearing d->fallback (solve.c): the
 * recursive evaluation's general route, after its own shortcuts have flagged their fallbacks.
 * On its composite M* about o, a rate whose M*_aa is round-off of those terms and that no row
 * fixes is not refused: VT_NEEDS_DENSE (positive), the dense stages decide (recursive.c) */
#define VT_NEEDS_DENSE ((vt_status)1)
/* a free-rate route's estimate low enough that the maximal-coordinate route (maximal.c) may be
 * wanted (vt_maximal_wanted): the dense stages, which form what it needs, solve the instant
 * again and decide (recursive.c) */
#define VT_NEEDS_MAXIMAL ((vt_status)2)
/* vt_inverse_dynamics_recursive_positioned asked for q̇ as well, where its route has no LU of
 * Φ_q to solve them (recursive.c): the caller solves them, and asks again without */
#define VT_NEEDS_RATES ((vt_status)3)
vt_status vt_solve_impl(const vt_model *m, vt_data *d);
/* vt_solve_impl with a time analysis's band (vt_run_options.redundant_band; 0 is vt_solve_impl)
 * and the form of M* (dense: S^T M S, else the composite inertias about o, as vt_rate_bounds),
 * and vt_solve with it on the dense M* (solve.c): the ODE formulation's residual */
vt_status vt_solve_band(const vt_model *m, vt_data *d, double band, int dense);
vt_status vt_solve_run(const vt_model *m, vt_data *d, double band);
/* the diagnostics every solve starts from: route none, rcond 0, no warning, rank 0, residual 0 */
void vt_solve_reset(vt_data *d);
/* the rank of Φ_q to round-off, in the scaling of the redundant decision (from the current M*
 * and Φ_q), or a negative vt_status (solve.c) */
int vt_rows_rank(const vt_model *m, vt_data *d);
/* vt_solve's square route in two halves (solve.c), its state on the arena: the LU of R Φ_q D;
 * D (s) and R (g); q̈ (x) and then M* q̈ − Q, overwritten by λ (h) */
typedef struct {
    double *A, *s, *g, *x, *h;
    int *ipiv;
} vt_square;
int vt_square_first(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, int stride, double *rcond);
int vt_square_second(const vt_model *m, vt_data *d, vt_square *sq);
/* x = sign Φ_q^-1 b (nv) by the factors of sq: D (R Φ_q D)^-1 R b */
int vt_square_apply(const vt_model *m, vt_data *d, const vt_square *sq, const double *b, double sign, double *x);
/* the same for the recursive evaluation: the factors from M*'s diagonal mdiag (nv) and the
 * positions, q̈, and the outcome */
int vt_solve_square_factor(const vt_model *m, vt_data *d, vt_square *sq, const double *mdiag, double *rcond);
int vt_solve_square_accelerations(const vt_model *m, vt_data *d, vt_square *sq);
vt_status vt_solve_square_end(const vt_model *m, vt_data *d, vt_square *sq, double rcond);
/* Round-off of exact zeros (solve.c): T (2 nv) the magnitudes of the terms of each rate's M*_aa,
 * T_a = Σ_k m_k (|v_a| + |ω_a| L_k)² (L_k ≥ |c_k − o|: vt_lengths_from_o) and R_a = |ω_a|² Σ_k tr J'_k over the bodies k it moves,
 * from the twists (w: 4 (nbody + 1) scratch); vt_rate_roundoff, the size below which M*_aa is
 * round-off, τ ε (T_a + R_a). */
#define VT_ROUND_TAU 64.0
/* Below DBL_MIN a number has lost digits (the dense path refuses an M*_aa there, naming the
 * rate); the recursive routes, whose pivots round differently, hand every pivot below DBL_MIN / ε
 * to the dense stages, so that both paths decide the edge by the same numbers */
#define VT_PIVOT_NORMAL (DBL_MIN / DBL_EPSILON)
void vt_rate_terms(const vt_model *m, const vt_data *d, double *w, double *T);
double vt_rate_roundoff(const double *T, int a);
/* The bound below which M*_aa is round-off, for every rate, into beta (nv): of the M* the
 * dense stages form as S^T M S (dense != 0: S's columns squared, (τ ε)² T_a + τ ε R_a, T_a with
 * the dense S's lever arms, vt_lever) or of the recursive general route's composite inertias
 * about o (dense == 0: vt_rate_roundoff). Scratch: 2 nv + 4 (nbody + 1) doubles (solve.c) */
int vt_rate_bounds(const vt_model *m, vt_data *d, int dense, double *beta);
/* the number of rows of Φ_q that are round-off of a zero row (judged against the terms they are
 * summed from), or a negative vt_status (solve.c) */
int vt_zero_rows(const vt_model *m, vt_data *d);
/* the same on the free rates alone (known[a] < 0): rows dependent on the known rates' (solve.c) */
int vt_zero_rows_free(const vt_model *m, vt_data *d, const int *known);
/* dgelsd's integer workspace for an m x n problem (solve.c) */
int vt_dgelsd_iwork(int m, int n);
/* S b' = b for the symmetric positive definite n x n S (its lower triangle, overwritten: scaled
 * to unit diagonal, then factorized), b solved in place, the reciprocal condition of S at unit
 * diagonal into *rcond: 1 for n ≤ 1, exact from the inverse for n ≤ 16, dpocon's estimate above,
 * 0 when S is not positive definite (nothing solved). Returns 0 or a negative vt_status (solve.c). */
int vt_solve_spd(vt_data *d, double *S, int n, double *b, double *rcond);
/* the smallest grip² of the point drives' rows (1 without any): how much of what the rates can
 * move the driven point by lies along the driven direction (solve.c) */
double vt_rows_grip(const vt_model *m, const vt_data *d);

#endif
