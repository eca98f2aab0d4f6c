/* vtdyn — The rows' scalings, lever arm and grip, and the SVD rank decision on Φ_q
 * (numeric/rank.c). */
#ifndef VT_NUMERIC_RANK_H
#define VT_NUMERIC_RANK_H

#include <math.h>
#include <stddef.h>

#include "vtdyn.h"

size_t vt_rank_scratch(const vt_model *m);

/* The rates' part of the symmetric scaling D of (5), d_a = M*_aa^(-1/2) (1 for a rate without
 * inertia), into s (nv) from M*'s diagonal mdiag[a stride] (s may be mdiag itself with stride 1) */
static inline void vt_scaling_diag(const vt_model *m, const double *mdiag, int stride, double *s)
{
    for (int a = 0; a < m->nv; a++) {
        const double mii = mdiag[(size_t)a * (size_t)stride];
        s[a] = mii > 0.0 ? 1.0 / sqrt(mii) : 1.0;
    }
}
/* D into s[0..nv) and, with rows, each constraint row by its own norm in that metric into
 * s[nv..nv+nc) (the augmented route's scaling of (5)) */
void vt_scaling(const vt_model *m, const vt_data *d, double *s, int rows);
/* the smallest grip² of the point drives' rows (1 without any), into *grip: how much of what the
 * rates can move the driven point by lies along the driven direction. Returns 0, or a negative
 * vt_status (its scratch, a body's path). */
int vt_rows_grip(const vt_model *m, vt_data *d, double *grip);
/* ℓ, the rows' own lever arm (a length of their geometry; flag (nc or NULL): rows left out) */
double vt_rows_length(const vt_model *m, const vt_data *d, const int *flag);
/* 1 when row r measures a length (a translation), 0 when an angle */
int vt_length_row(const vt_model *m, const vt_data *d, int r);

/* The SVD of Φ̂ = G Φ_q C (rank.c) and what it decides: arrays on the arena (the caller of
 * vt_rows_decide releases them) */
typedef struct {
    double *U, *VT, *sig, *g, *s, *c; /* nc x nc, k x nv, k, nc, nv, nv (k = min(nc, nv)); s: the
                                       * mass metric D (the redundant route's), c: C */
    int *flag;                        /* nc: 1 for a row that is round-off of zero (vt_roundoff_check) */
    int k, rank, kept;                /* rank: dependence to round-off; kept: the directions kept
                                       * (those above a time analysis's band too) */
} vt_rows_svd;
/* Φ̂ and its SVD into o; band a time analysis's vt_run_options.redundant_band (0 at every other
 * instant). Returns 0 or a negative vt_status. */
int vt_rows_decide(const vt_model *m, vt_data *d, double band, vt_rows_svd *o);
/* The part of row r in the null space of Φ̂^T: 0 for a row independent of the others, up to 1 */
double vt_null_part(const vt_model *m, const vt_rows_svd *o, int r);
#define VT_NULL_PART_TOL 1e-8 /* above it, a row takes part in a dependence (its multiplier is not unique) */
/* the rank of Φ_q to round-off, in the scaling of the redundant decision (from the current M*
 * and Φ_q), or a negative vt_status */
int vt_rows_rank(const vt_model *m, vt_data *d);
/* dgelsd's integer workspace for an m x n problem */
int vt_dgelsd_iwork(int m, int n);

#endif
