/* What every route of the solve stage ends with, dense and recursive alike: the diagnostics a
 * solve starts from (vt_solve_reset: nothing found yet) and those a route with independent rows
 * records once it has solved (5) (vt_solved: the route, the condition estimate and its warning,
 * rank nc, no residual, every multiplier unique). The outcomes a route can reach are
 * vt_outcome (numeric/route.h). */
#include "numeric/route.h"

void vt_solved(const vt_model *m, vt_data *d, vt_route route, double rcond)
{
    d->route = route;
    d->rcond = rcond;
    d->warning = rcond < m->rcond_warn ? VT_WARN_ILL_CONDITIONED : 0;
    d->rank = m->nc;
    d->residual = 0.0;
    vt_mark_unique(m, d);
}

void vt_solve_reset(vt_data *d)
{
    d->route = VT_ROUTE_NONE;
    d->rcond = 0.0;
    d->warning = 0;
    d->rank = 0;
    d->residual = 0.0;
}
