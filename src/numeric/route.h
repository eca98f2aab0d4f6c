/* vtdyn — What every solve route ends with (numeric/route.c): its outcome, the diagnostics it
 * starts from and those a successful solve records. */
#ifndef VT_NUMERIC_ROUTE_H
#define VT_NUMERIC_ROUTE_H

#include "vtdyn.h"

/* What a route of the solve stage concluded (dense/routes.c, the square route's factors in
 * numeric/kkt.c), and so what the dispatcher (vt_solve_band, dense/solve.c) does next. A route
 * function returns VT_OK with its outcome, or a negative vt_status (an error: nothing more is
 * tried). */
/* What a recursive route hands on when it does not answer the instant itself, returned beside a
 * status of VT_OK (never cast into a vt_status): the caller acts on it. */
typedef enum {
    VT_HANDOFF_NONE = 0, /* answered here */
    VT_HANDOFF_DENSE,    /* the composite inertias about o cannot vouch for a digit (a rate's M*_aa
                          * or the answer within their round-off): the dense stages decide */
    VT_HANDOFF_MAXIMAL,  /* a free-rate route's estimate low enough that the maximal-coordinate
                          * route may be wanted: the dense stages solve again and decide for both */
    VT_HANDOFF_RATES     /* q̇ was asked for where the route has no LU of Φ_q: the caller solves q̇
                          * and asks again without */
} vt_handoff;

typedef enum {
    /* solved: q̈ and λ written, the estimate at least rcond_min (on the Schur route, at least
     * rcond_warn too) */
    VT_SOLVED = 0,
    /* the estimate below rcond_min (or an exactly zero pivot, or a zero row): nothing solved.
     * The dispatcher does not look further: it diagnoses (dependent rows, named, or a singular or
     * ill-conditioned matrix) */
    VT_BELOW_MIN = 1,
    /* the Schur route gave way: a pivot of M̃'s Cholesky factor below 1e-4, M* (nearly) singular
     * on rates that only the constraints may fix, which M̃ alone cannot: the whole augmented
     * matrix (5) takes over, flagged VT_FALLBACK_SCHUR_PIVOT */
    VT_PIVOT_GAVE_WAY = 2,
    /* the Schur route's estimate below rcond_min: not solved. The rows' Schur complement in the
     * mass metric can lose digits that the whole matrix keeps (a chain whose masses rise by 1e3 a
     * rod), so the augmented route is tried before refusing */
    VT_SCHUR_BELOW_MIN = 3,
    /* the Schur route solved with an estimate below rcond_warn: the augmented route solves too,
     * for the same reason, and the answer of the higher estimate is kept */
    VT_SCHUR_BELOW_WARN = 4,
    /* no cheaper route applies (no rows, more rows than rates): the augmented route solves */
    VT_TO_AUGMENTED = 5
} vt_outcome;

/* every multiplier unique (vt_solve's exact routes) */
static inline void vt_mark_unique(const vt_model *m, vt_data *d)
{
    int *lu = d->lambda_unique;
    for (int r = 0; r < m->nc; r++) lu[r] = 1;
}
/* what a successful solve with independent rows records: the route, rcond and its warning,
 * rank nc, no residual, every multiplier unique */
void vt_solved(const vt_model *m, vt_data *d, vt_route route, double rcond);
/* the diagnostics every solve starts from: route none, rcond 0, no warning, rank 0, residual 0 */
void vt_solve_reset(vt_data *d);

#endif
