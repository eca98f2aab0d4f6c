/* vtdyn — Time functions of the drives (model/functions.c): checks, evaluation, spline set-up. */
#ifndef VT_MODEL_FUNCTIONS_H
#define VT_MODEL_FUNCTIONS_H

#include <math.h>

#include "vtdyn.h"

/* Validates a time function (functions.c); msg may be NULL. */
vt_status vt_function_check(char *msg, const vt_function *f);
/* f, f′, f″ of a sine, a spline or a user's function (functions.c), into v; not checked for Inf */
vt_status vt_function_eval_other(double v[3], const vt_function *f, double t);
/* vt_function_eval for a function already validated (a model's drives: a spline's sample_d2 set);
 * inline, a polynomial or constant computed here: the drives' functions are evaluated rate by rate
 * in every instant, and a call cost a joint-driven chain more than the polynomial itself */
static inline vt_status vt_function_eval_valid(double out[3], const vt_function *f, double t)
{
    if (!isfinite(t)) return VT_ERR_NONFINITE;
    double v[3] = {0, 0, 0};
    if (f->type == VT_FUNCTION_POLYNOMIAL) {
        v[0] = f->c[f->ncoef - 1]; /* the first step from zeros: f′ and f″ stay 0 */
        for (int k = f->ncoef - 2; k >= 0; k--) { /* Horner for f, f′, f″ together */
            v[2] = v[2] * t + 2.0 * v[1];
            v[1] = v[1] * t + v[0];
            v[0] = v[0] * t + f->c[k];
        }
    } else if (f->type == VT_FUNCTION_CONSTANT) {
        v[0] = f->c[0];
    } else {
        const vt_status st = vt_function_eval_other(v, f, t);
        if (st) return st;
    }
    if (!(isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]))) return VT_ERR_NONFINITE; /* in registers */
    out[0] = v[0];
    out[1] = v[1];
    out[2] = v[2];
    return VT_OK;
}
/* A spline's second derivatives d2 (n) at its samples (functions.c), by LAPACK's dgtsv; work
 * holds 3n doubles; the samples already validated (vt_function_check); msg may be NULL.
 * Statuses: VT_ERR_LAPACK, VT_ERR_NONFINITE (spacings so uneven that d2 overflows). */
vt_status vt_spline_d2(char *msg, int n, const double *t, const double *y, double *d2, double *work);

#endif
