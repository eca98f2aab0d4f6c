/* The kinematic analysis over time: a fully driven model (its constraint rows fix every rate) at
 * every output time, each instant by vt_kinematic_solve's Newton–Raphson from the previous rows
 * extrapolated (vt_kinematic_start in analysis/kinematic_solve.c: Hermite through q, q̇, q̈ of the last
 * two, O(h⁶)), or from the previous row itself when that start's residual is not below ½ h max |Φ_t| or Newton fails
 * from it; the instant after the solve by the recursive evaluation. Then the forward check
 * (analysis/dynamic_analysis.c, its residual in analysis/dae.c): the model without drives integrated under the drives' efforts,
 * which must reproduce the motion. Rows at t0 and the output times (the uniform ones, or the
 * caller's list vt_run_options.tout): each exact at its time. A model is fully driven when its
 * rows fix every rate: as many independent rows as rates, or more rows of that rank (dependent
 * rows, which the model must allow: vt_model_def.allow_redundant).
 */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/kinematic_analysis.h"
#include "analysis/contact_run.h"
#include "analysis/data.h"
#include "base/status.h"
#include "dense/reactions.h"
#include "numeric/rank.h"
#include "analysis/dynamic_analysis.h"
#include "analysis/kinematic_solve.h"
#include "analysis/trajectory.h"

/* Fully driven when Φ_q's rank (to round-off, vt_solve's decision) equals the rates, any other
 * rows dependent; those a model solves only when it allows them. A model that does not, with
 * more rows than rates, is refused before the run, its rank taken at t0 and the given q (the
 * stages' outputs change, nothing of the caller's state); one that does is checked at the first
 * row, solved, so that a start guess at a singular pose (a stretched arm at q = 0) is no reason. */
static vt_status fully_driven(const vt_model *m, vt_data *d, double t0, int solved)
{
    vt_status st = VT_OK;
    int rank = 0;
    if (!solved) {
        const double t = d->time;
        d->time = t0;
        if (!(st = vt_kinematics(m, d)) && !(st = vt_mass_matrix(m, d)) && !(st = vt_constraints(m, d)) &&
            (rank = vt_rows_rank(m, d)) < 0)
            st = (vt_status)rank;
        d->time = t;
    } else if ((rank = vt_rows_rank(m, d)) < 0) {
        st = (vt_status)rank;
    }
    if (st) return st;
    if (rank < m->nv)
        return vt_fail(d->message, VT_ERR_NOT_FULLY_DRIVEN,
                       "vt_kinematic_analysis: %d constraint rows of rank %d for %d rates at t = %g: they fix %d of "
                       "the rates (or t0 is a singular pose); drive the others, or run a dynamic analysis", m->nc, rank,
                       m->nv, t0, rank);
    if (!m->allow_redundant)
        return vt_fail(d->message, VT_ERR_DEPENDENT_CONSTRAINTS,
                       "vt_kinematic_analysis: %d constraint rows of rank %d for %d rates: fully driven, with %d "
                       "dependent rows; a model built with allow_redundant = 1 (vt_model_def) solves them",
                       m->nc, rank, m->nv, m->nc - rank);
    return VT_OK;
}

/* rows 0..nrow into tr (base: the caller's loads of a run with loads at frames or on contacts,
 * else NULL) */
static vt_status rows(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr, const double *base)
{
    vt_status st = VT_OK;
    vt_trajectory_reset(tr);
    const int nrow = vt_run_rows(opt);
    const double tend = vt_run_time(opt, nrow);
    for (int k = 0; k <= nrow; k++) { /* t0, then the uniform rows or the caller's times */
        d->time = vt_run_time(opt, k);
        const double *qp = k ? tr->q + (size_t)(k - 1) * (size_t)m->nq : NULL;
        const double *qdp = k ? tr->qd + (size_t)(k - 1) * (size_t)m->nv : NULL;
        if (k > 0 && (st = vt_kinematic_start(m, d, tr, k - 1, k >= 2 ? k - 2 : -1, -1))) return st;
        /* row 0 by the dense instant: its M* and Φ_q decide the rank below; the rows after by the
         * recursive one without α and the joints' total wrenches, which the rows do not keep
         * (the last row's after the loop) */
        const int solve = k > 0 ? VT_SOLVE_RECURSIVE_NO_TOTALS : d->Mstar ? VT_SOLVE_DENSE : VT_SOLVE_RECURSIVE;
        if ((st = vt_kinematic_solve_impl(m, d, opt->newton_tol, opt->newton_maxit, solve, qp, qdp, k ? d->time - tr->t[k - 1] : 0.0))) {
            if (k == 0 || st != VT_ERR_NEWTON) return st;
            /* Newton from the prediction failed: once more from the previous row */
            memcpy(d->q, qp, (size_t)m->nq * sizeof(double));
            memcpy(d->qd, qdp, (size_t)m->nv * sizeof(double));
            if ((st = vt_kinematic_solve_impl(m, d, opt->newton_tol, opt->newton_maxit, solve, NULL, NULL, 0.0))) return st;
        }
        /* a model that solves dependent rows would also solve a rank-deficient one dynamically */
        if (k == 0 && m->allow_redundant && (st = fully_driven(m, d, opt->t0, 1))) return st;
        if (base) { /* the loads at frames and the ground's forces, and the drives' efforts with them */
            const size_t r = (size_t)k * (size_t)tr->ncontact;
            if ((st = vt_run_loads(m, d, opt, base, opt->contacts ? tr->contact_force + 3 * r : NULL,
                                   opt->contacts ? tr->contact_active + r : NULL, 1, "vt_kinematic_analysis")))
                return st;
        }
        vt_trajectory_store(tr, m, d, k);
        const int stop = opt->progress && opt->progress(d->time, tend, opt->user);
        /* d left with the last row's whole instant */
        if ((stop || k == nrow) && k > 0 && !base && (st = vt_reactions_total(m, d, 0))) return st;
        if (stop) return vt_fail(d->message, VT_ERR_ABORTED, "vt_kinematic_analysis: stopped at t = %g", d->time);
    }
    return VT_OK;
}

vt_status vt_kinematic_analysis(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr)
{
    vt_status st = vt_check_run(m, d, opt, tr, "vt_kinematic_analysis");
    if (st) return st;
#if !VT_HAVE_SUNDIALS
    if (opt->forward_check)
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "vt_kinematic_analysis: the forward check needs SUNDIALS IDA, and this build has none");
#endif
    if (m->nc < m->nv)
        return vt_fail(d->message, VT_ERR_NOT_FULLY_DRIVEN,
                       "vt_kinematic_analysis: %d constraint rows for %d rates: not fully driven; a dynamic analysis "
                       "handles partly driven models", m->nc, m->nv);
    if ((st = vt_run_loads_check(m, d, opt, tr, "vt_kinematic_analysis"))) return st;
    if (m->nc > m->nv && !m->allow_redundant && (st = fully_driven(m, d, opt->t0, 0))) return st;
    /* with loads at frames or on contacts: the caller's loads, which each row's instant takes
     * those onto */
    const size_t nxf = 6 * ((size_t)m->nbody + 1);
    const int loaded = vt_run_has_loads(opt);
    double *base = loaded ? malloc(nxf * sizeof(double)) : NULL;
    if (loaded && !base) return vt_fail(d->message, VT_ERR_NO_MEMORY, "vt_kinematic_analysis: out of memory");
    if (base) memcpy(base, d->xfrc, nxf * sizeof(double));
    st = rows(m, d, opt, tr, base);
    if (base) {
        memcpy(d->xfrc, base, nxf * sizeof(double));
        free(base);
    }
    if (st) return st;
#if VT_HAVE_SUNDIALS
    if (!opt->forward_check) return VT_OK;
    /* the forward check starts from the first row's state */
    vt_data *dk;
    /* the forward check's own data: the forward model's stages are the dense ones, whatever d holds */
    if ((st = vt_data_create_full(&dk, m))) return vt_fail(d->message, st, "vt_kinematic_analysis: %s", vt_status_string(st));
    memcpy(dk->q, tr->q, (size_t)m->nq * sizeof(double));
    memcpy(dk->qd, tr->qd, (size_t)m->nv * sizeof(double));
    /* its exact efforts between the rows with the caller's loads, as the rows' */
    memcpy(dk->xfrc, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    memcpy(dk->qfrc, d->qfrc, (size_t)m->nv * sizeof(double));
    dk->time = opt->t0;
    st = vt_forward_exact(m, d, dk, opt, tr);
    vt_data_free(dk);
    return st;
#else
    return VT_OK;
#endif
}
