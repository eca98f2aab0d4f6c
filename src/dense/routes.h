/* vtdyn — The solve stage's five routes through (5) (dense/routes.c): each writes its answer
 * and returns VT_OK with its outcome (vt_outcome), or a negative vt_status. */
#ifndef VT_DENSE_ROUTES_H
#define VT_DENSE_ROUTES_H

#include <stddef.h>

#include "vtdyn.h"
#include "numeric/rank.h"
#include "numeric/route.h"

size_t vt_routes_scratch(const vt_model *m);

/* the whole augmented matrix of (5), scaled, LDL^T: [q̈; −λ] into b (nv + nc) */
vt_status vt_augmented_solve(const vt_model *m, vt_data *d, double *b, double *rcond_out, vt_outcome *out);
/* (5) on the kept directions of the rows (o: vt_rows_decide's, o->kept < nc): q̈, λ, their
 * null directions, rank, residual and warning into d (always solved, or an error) */
vt_status vt_redundant_solve(const vt_model *m, vt_data *d, const vt_rows_svd *o);
/* every row a joint drive on a rate of its own: q̈ and λ into d */
vt_status vt_free_rates_solve(const vt_model *m, vt_data *d, double *rcond_out, vt_outcome *out);
/* as many rows as rates: [q̈; λ] into b */
vt_status vt_square_solve(const vt_model *m, vt_data *d, double *b, double *rcond_out, vt_outcome *out);
/* fewer rows than rates: [q̈; λ] into sol; known: the joint-driven rates' q̈ taken as known */
vt_status vt_schur_solve(const vt_model *m, vt_data *d, int known, double *sol, double *rcond_out, vt_outcome *out);
/* whether the Schur route may take the joint-driven rates as known */
int vt_rates_known(const vt_model *m);

#endif
