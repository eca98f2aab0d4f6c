/* vtdyn — The answer's componentwise condition (numeric/skeel.c). */
#ifndef VT_NUMERIC_SKEEL_H
#define VT_NUMERIC_SKEEL_H

#include <stddef.h>

#include "vtdyn.h"

/* Â^{-1} v (trans "N") or Â^{-T} v ("T") by dgetrf's LU (N x N, ld N); LAPACK's info */
int vt_lu_solve(const char *trans, const double *LU, const int *ipiv, int N, double *v);

/* ‖P C |Â^{-1}| w‖_∞ by dlacn2 on the LU of Â: P the unknowns lo..hi−1, C a diagonal column
 * scaling (NULL: none); v, z (N) and isgn (N) its work; −1 where a solve fails */
double vt_skeel_norm(const double *LU, const int *ipiv, int N, const double *w, const double *C, int lo, int hi,
                     double *v, double *z, int *isgn);

/* The componentwise estimate of (5) at its answer, where the model's masses are spread (at least
 * VT_SPREAD_ESTIMATE between its heaviest and lightest body) and (5) has at most VT_SPREAD_MAX
 * unknowns: vt_answer_size is that number (nv + nc), 0 where it is not taken. vt_answer_condition
 * puts into *rcond the reciprocal of the larger of q̈'s and λ's condition (skeel.c) at sol
 * ([q̈; λ], or [q̈; −λ] with neg); 0 where it cannot tell (a zero row or pivot). It reads M*, Q,
 * Φ_q and γ. Returns 0 or a negative vt_status (the arena). */
#define VT_SPREAD_ESTIMATE 1e6
enum { VT_SPREAD_MAX = 256 };
int vt_answer_size(const vt_model *m);
int vt_answer_condition(const vt_model *m, vt_data *d, const double *sol, int neg, double *rcond);
size_t vt_answer_scratch(const vt_model *m);

#endif
