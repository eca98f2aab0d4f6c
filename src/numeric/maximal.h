/* vtdyn — The maximal-coordinate route (numeric/maximal.c). */
#ifndef VT_NUMERIC_MAXIMAL_H
#define VT_NUMERIC_MAXIMAL_H

#include <stddef.h>

#include "vtdyn.h"

/* The maximal-coordinate route (maximal.c): vt_maximal_size is its number of unknowns, 0 where
 * it is not taken (base bodies, every rate joint-driven, more than VT_MAXIMAL_MAX unknowns);
 * vt_maximal_solve puts [q̈; λ] into sol (nv + nc) and the reciprocal of the answer's condition
 * into *rcond (without the grip g²). It needs the dense stages' S, Ṡq̇, Φ_x, Φ_q and γ. Returns
 * 0, 1 (singular: nothing solved) or a negative vt_status. */
enum { VT_MAXIMAL_MAX = 256 };
int vt_maximal_size(const vt_model *m);
int vt_maximal_wanted(const vt_model *m, double rcond);
int vt_maximal_solve(const vt_model *m, vt_data *d, double *sol, double *rcond);
size_t vt_maximal_scratch(const vt_model *m);
/* its matrix A (N x N, ld N, N = vt_maximal_size) and right side b, unscaled: for the tests */
void vt_maximal_system(const vt_model *m, const vt_data *d, double *A, double *b);

#endif
