/* The kinematic analysis over time: a fully driven model (as many constraint rows as rates) at
 * every output time, each instant by vt_kinematic_solve from the previous one, then the forward
 * check (src/dynamic_analysis.c): the model without drives integrated under the drives' efforts,
 * which must reproduce the motion. Rows at t0 and the output times (the uniform ones, or the
 * caller's list vt_run_options.tout): each exact at its time.
 */
#include <string.h>

#include "internal.h"

vt_status vt_kinematic_analysis(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr)
{
    vt_status st = vt_check_run(m, d, opt, tr, "vt_kinematic_analysis");
    if (st) return st;
#if !VT_HAVE_SUNDIALS
    if (opt->forward_check)
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "vt_kinematic_analysis: the forward check needs SUNDIALS IDA, and this build has none");
#endif
    if (m->nc != m->nv)
        return vt_fail(d->message, VT_ERR_NOT_FULLY_DRIVEN,
                       "vt_kinematic_analysis: %d constraint rows for %d rates; a dynamic analysis handles the rest",
                       m->nc, m->nv);
    vt_trajectory_reset(tr);
    const int nrow = vt_run_rows(opt);
    const double tend = vt_run_time(opt, nrow);
    for (int k = 0; k <= nrow; k++) { /* t0, then the uniform rows or the caller's times */
        d->time = vt_run_time(opt, k);
        if ((st = vt_kinematic_solve(m, d, opt->newton_tol, opt->newton_maxit))) return st;
        vt_trajectory_store(tr, m, d, k);
        if (opt->progress && opt->progress(d->time, tend, opt->user))
            return vt_fail(d->message, VT_ERR_ABORTED, "vt_kinematic_analysis: stopped at t = %g", d->time);
    }
#if VT_HAVE_SUNDIALS
    if (!opt->forward_check) return VT_OK;
    /* the forward check starts from the first row's state */
    vt_data *dk;
    if ((st = vt_data_create(&dk, m))) return vt_fail(d->message, st, "vt_kinematic_analysis: %s", vt_status_string(st));
    memcpy(dk->q, tr->q, (size_t)m->nq * sizeof(double));
    memcpy(dk->qd, tr->qd, (size_t)m->nv * sizeof(double));
    dk->time = opt->t0;
    st = vt_forward_exact(m, d, dk, opt, tr);
    vt_data_free(dk);
    return st;
#else
    return VT_OK;
#endif
}
