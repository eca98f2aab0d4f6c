/* vtdyn — Status messages and the argument check every stage starts with (base/status.c). */
#ifndef VT_BASE_STATUS_H
#define VT_BASE_STATUS_H

#include "vtdyn.h"

/* Writes a formatted message into buf (VT_MESSAGE_SIZE bytes) and returns status. */
vt_status vt_fail(char *buf, vt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Common argument check of every stage: non-NULL, data made for this model. */
vt_status vt_check_pair(const vt_model *m, vt_data *d, const char *who);

/* The same for the dense stages and what calls them: the data must hold S, R and M* (laid out
 * VT_LAYOUT_FULL, or the analyses' own full data), else VT_ERR_LAYOUT naming who. */
vt_status vt_check_dense(const vt_model *m, vt_data *d, const char *who);

/* The diagnostics of the last instant or solve cleared (route none, no fallback, no warning,
 * rank 0, rcond 0, residual 0): what every entry point that owns them (the instants, vt_solve,
 * vt_kinematic_solve, the analyses, vt_data_reset) does first, after its argument check and
 * before anything that can fail, so that a call refused before its solve leaves nothing of
 * the previous call's. vt_solve_reset (dense/solve.h) is the same without the fallback, which
 * the recursive routes set before the solve they hand on to. */
static inline void vt_diagnostics_reset(vt_data *d)
{
    d->route = VT_ROUTE_NONE;
    d->fallback = 0;
    d->warning = 0;
    d->rank = 0;
    d->rcond = 0.0;
    d->residual = 0.0;
}

#endif
