/* Trajectories: the rows of an analysis over time (one allocation), the default run options,
 * the output times (row 0 at t0, then t_k = t0 + k (t1 − t0)/nout, k = 1..nout, or the caller's
 * list t_k = tout[k − 1], k = 1..ntout), and the comparison of the forward check with the driven run (the built-in self-check:
 * max |q_fwd − q|, max |q̇_fwd − q̇| and the reactions' largest differences, over the run and per
 * window of the forward check, vt_run_options.check_window). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/trajectory.h"
#include "analysis/contact.h"
#include "base/block.h"
#include "base/status.h"

vt_run_options vt_default_run_options(void)
{
    vt_run_options o;
    memset(&o, 0, sizeof o);
    o.t0 = 0.0;
    o.t1 = 1.0;
    o.nout = 100;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.max_step = 0.0;
    o.max_steps = 100000;
    o.newton_tol = 1e-12;
    o.newton_maxit = 30;
    o.forward_check = VT_HAVE_SUNDIALS; /* the forward check integrates with IDA */
    o.forward_independent = 1;
    o.history_steps = 100000;
    o.formulation = VT_FORMULATION_GGL;
    o.baumgarte_alpha = 10.0;
    o.baumgarte_beta = 10.0;
    o.tout = NULL; /* the uniform rows */
    o.ntout = 0;
    o.redundant_band = VT_REDUNDANT_TOL;
    o.check_window = VT_CHECK_WINDOW;
    return o;
}

static size_t layout(const vt_model *m, vt_trajectory *tr, char *base, int nrow, int ncontact)
{
    const size_t nct = (size_t)ncontact;
    const size_t r = (size_t)nrow, nq = (size_t)m->nq, nv = (size_t)m->nv, nc = (size_t)m->nc;
    const size_t nd = (size_t)m->ndrive, nb = (size_t)m->nbody + 1, nk = (size_t)m->ncut;
    /* every array of doubles on 16 bytes (calloc's alignment) */
    vt_block blk = {.base = base, .used = sizeof(vt_trajectory), .align = 16};
    tr->t = vt_block_take(&blk, r, sizeof(double));
    tr->q = vt_block_take(&blk, nq * r, sizeof(double));
    tr->qd = vt_block_take(&blk, nv * r, sizeof(double));
    tr->qdd = vt_block_take(&blk, nv * r, sizeof(double));
    tr->lambda = vt_block_take(&blk, nc * r, sizeof(double));
    tr->qfrc_drive = vt_block_take(&blk, nv * r, sizeof(double));
    tr->drive_effort = vt_block_take(&blk, nd * r, sizeof(double));
    tr->drive_force = vt_block_take(&blk, 3 * nd * r, sizeof(double));
    tr->drive_moment = vt_block_take(&blk, 3 * nd * r, sizeof(double));
    tr->jnt_force = vt_block_take(&blk, 3 * nb * r, sizeof(double));
    tr->jnt_moment = vt_block_take(&blk, 3 * nb * r, sizeof(double));
    tr->cut_force = vt_block_take(&blk, 3 * nk * r, sizeof(double));
    tr->cut_moment = vt_block_take(&blk, 3 * nk * r, sizeof(double));
    tr->phi_norm = vt_block_take(&blk, r, sizeof(double));
    tr->phid_norm = vt_block_take(&blk, r, sizeof(double));
    tr->rcond = vt_block_take(&blk, r, sizeof(double));
    tr->q_fwd = vt_block_take(&blk, nq * r, sizeof(double));
    tr->qd_fwd = vt_block_take(&blk, nv * r, sizeof(double));
    tr->jnt_force_fwd = vt_block_take(&blk, 3 * nb * r, sizeof(double));
    tr->jnt_moment_fwd = vt_block_take(&blk, 3 * nb * r, sizeof(double));
    tr->cut_force_fwd = vt_block_take(&blk, 3 * nk * r, sizeof(double));
    tr->cut_moment_fwd = vt_block_take(&blk, 3 * nk * r, sizeof(double));
    /* the forward check's windows: each ends at an output row, so at most nrow */
    tr->fwd_window_err_q = vt_block_take(&blk, r, sizeof(double));
    tr->fwd_window_err_qd = vt_block_take(&blk, r, sizeof(double));
    tr->fwd_window_err_force = vt_block_take(&blk, r, sizeof(double));
    tr->fwd_window_err_moment = vt_block_take(&blk, r, sizeof(double));
    tr->fwd_window_row = vt_block_take(&blk, r, sizeof(int));
    tr->contact_force = nct ? vt_block_take(&blk, 3 * nct * r, sizeof(double)) : NULL;
    tr->contact_active = nct ? vt_block_take(&blk, nct * r, sizeof(int)) : NULL;
    return blk.used;
}

static vt_status create(vt_trajectory **out, const vt_model *m, int nrow, int ncontact)
{
    *out = NULL;
    if (nrow < 1) return VT_ERR_BAD_OPTION;
    vt_trajectory probe;
    /* every array is one row's size times nrow (+ 1): countable in size_t where nrow + 1 rows'
     * bytes, counted in double, are */
    if ((double)layout(m, &probe, NULL, 1, ncontact) * ((double)nrow + 1.0) > (double)SIZE_MAX / 4.0)
        return VT_ERR_NO_MEMORY;
    const size_t bytes = layout(m, &probe, NULL, nrow, ncontact);
    char *block = calloc(1, bytes);
    if (!block) return VT_ERR_NO_MEMORY;
    vt_trajectory *tr = (vt_trajectory *)block;
    layout(m, tr, block, nrow, ncontact);
    tr->model = m;
    tr->nrow = nrow;
    tr->ncontact = ncontact;
    *out = tr;
    return VT_OK;
}

vt_status vt_trajectory_create(vt_trajectory **out, const vt_model *m, int nrow)
{
    if (!out || !m) return VT_ERR_NULL;
    return create(out, m, nrow, 0);
}

vt_status vt_trajectory_create_contacts(vt_trajectory **out, const vt_model *m, const vt_contacts *c, int nrow)
{
    if (!out || !m || !c) return VT_ERR_NULL;
    *out = NULL;
    if (vt_contacts_model(c) != m) return VT_ERR_MODEL_MISMATCH;
    return create(out, m, nrow, vt_contacts_count(c));
}

void vt_trajectory_free(vt_trajectory *tr)
{
    free(tr);
}

static void put(double *dst, const double *src, int n, int row)
{
    memcpy(dst + (size_t)row * (size_t)n, src, (size_t)n * sizeof(double));
}

void vt_trajectory_store(vt_trajectory *tr, const vt_model *m, const vt_data *d, int row)
{
    const int nb3 = 3 * (m->nbody + 1);
    tr->t[row] = d->time;
    put(tr->q, d->q, m->nq, row);
    put(tr->qd, d->qd, m->nv, row);
    put(tr->qdd, d->qdd, m->nv, row);
    put(tr->lambda, d->lambda, m->nc, row);
    put(tr->qfrc_drive, d->qfrc_drive, m->nv, row);
    put(tr->drive_effort, d->drive_effort, m->ndrive, row);
    put(tr->drive_force, d->drive_force, 3 * m->ndrive, row);
    put(tr->drive_moment, d->drive_moment, 3 * m->ndrive, row);
    put(tr->jnt_force, d->jnt_force, nb3, row);
    put(tr->jnt_moment, d->jnt_moment, nb3, row);
    put(tr->cut_force, d->cut_force, 3 * m->ncut, row);
    put(tr->cut_moment, d->cut_moment, 3 * m->ncut, row);
    double pn = 0.0, pdn = 0.0;
    for (int r = 0; r < m->nc; r++) {
        double v = d->Phit[r];
        if (!d->Phiq) v += d->qd[m->con_dof[r]]; /* a joint-driven model's data without Φ_q: its unit rows */
        else
            for (int c = 0; c < m->nv; c++) v += d->Phiq[r + (size_t)c * (size_t)m->nc] * d->qd[c];
        pn = fabs(d->Phi[r]) > pn ? fabs(d->Phi[r]) : pn; /* NaN passed over, as fmax does */
        pdn = fabs(v) > pdn ? fabs(v) : pdn;
    }
    tr->phi_norm[row] = pn;
    tr->phid_norm[row] = pdn;
    tr->rcond[row] = d->rcond;
    if (d->warning & VT_WARN_ILL_CONDITIONED) {
        if (tr->nwarn == 0) tr->t_warn = d->time;
        tr->nwarn++;
    }
    if (row + 1 > tr->nfilled) tr->nfilled = row + 1;
}

static double maxdiff(const double *a, const double *b, size_t n)
{
    double e = 0.0;
    for (size_t k = 0; k < n; k++) e = fmax(e, fabs(a[k] - b[k]));
    return e;
}

/* the forward model has the same bodies, joints and cut joints: q, q̇ and the reactions are
 * laid out as in the driven model */
void vt_trajectory_store_forward(vt_trajectory *tr, const vt_model *mf, const vt_data *df, int row)
{
    const int nb3 = 3 * (mf->nbody + 1);
    put(tr->q_fwd, df->q, mf->nq, row);
    put(tr->qd_fwd, df->qd, mf->nv, row);
    put(tr->jnt_force_fwd, df->jnt_force, nb3, row);
    put(tr->jnt_moment_fwd, df->jnt_moment, nb3, row);
    put(tr->cut_force_fwd, df->cut_force, 3 * mf->ncut, row);
    put(tr->cut_moment_fwd, df->cut_moment, 3 * mf->ncut, row);
    const size_t r = (size_t)row, nk3 = 3 * (size_t)mf->ncut;
    const double eq = maxdiff(tr->q_fwd + r * (size_t)mf->nq, tr->q + r * (size_t)mf->nq, (size_t)mf->nq);
    const double eqd = maxdiff(tr->qd_fwd + r * (size_t)mf->nv, tr->qd + r * (size_t)mf->nv, (size_t)mf->nv);
    const double ef = fmax(maxdiff(tr->jnt_force_fwd + r * (size_t)nb3, tr->jnt_force + r * (size_t)nb3, (size_t)nb3),
                           maxdiff(tr->cut_force_fwd + r * nk3, tr->cut_force + r * nk3, nk3));
    const double em = fmax(maxdiff(tr->jnt_moment_fwd + r * (size_t)nb3, tr->jnt_moment + r * (size_t)nb3, (size_t)nb3),
                           maxdiff(tr->cut_moment_fwd + r * nk3, tr->cut_moment + r * nk3, nk3));
    tr->fwd_err_q = fmax(tr->fwd_err_q, eq);
    tr->fwd_err_qd = fmax(tr->fwd_err_qd, eqd);
    tr->fwd_err_force = fmax(tr->fwd_err_force, ef);
    tr->fwd_err_moment = fmax(tr->fwd_err_moment, em);
    if (row == 0) vt_trajectory_window(tr, 0); /* the forward check's start: its first window */
    const int w = tr->nwindow - 1;
    tr->fwd_window_err_q[w] = fmax(tr->fwd_window_err_q[w], eq);
    tr->fwd_window_err_qd[w] = fmax(tr->fwd_window_err_qd[w], eqd);
    tr->fwd_window_err_force[w] = fmax(tr->fwd_window_err_force[w], ef);
    tr->fwd_window_err_moment[w] = fmax(tr->fwd_window_err_moment[w], em);
}

/* a new window of the forward check, restarted from the driven state at row `row` (row 0: the
 * first, the list started again) */
void vt_trajectory_window(vt_trajectory *tr, int row)
{
    if (row == 0) tr->nwindow = 0;
    const int w = tr->nwindow++;
    tr->fwd_window_row[w] = row;
    tr->fwd_window_err_q[w] = tr->fwd_window_err_qd[w] = tr->fwd_window_err_force[w] = tr->fwd_window_err_moment[w] = 0.0;
}

int vt_run_rows(const vt_run_options *opt)
{
    return opt->tout ? opt->ntout : opt->nout;
}

double vt_run_time(const vt_run_options *opt, int k)
{
    if (k == 0) return opt->t0;
    if (opt->tout) return opt->tout[k - 1];
    /* the last row exactly at t1, whatever the rounding of the quotient */
    return k == opt->nout ? opt->t1 : opt->t0 + (opt->t1 - opt->t0) * k / opt->nout;
}

void vt_trajectory_reset(vt_trajectory *tr)
{
    tr->nfilled = 0;
    tr->nwarn = 0;
    tr->t_warn = (double)NAN; /* NAN is a float */
    tr->fwd_err_q = tr->fwd_err_qd = tr->fwd_err_force = tr->fwd_err_moment = tr->fwd_interp_err = 0.0;
    tr->steps = tr->res_evals = tr->steps_fwd = tr->res_evals_fwd = 0;
    tr->nwindow = 0;
}

vt_status vt_check_run(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr, const char *who)
{
    vt_status st = vt_check_pair(m, d, who);
    if (st) return st;
    vt_diagnostics_reset(d); /* the analyses' diagnostics: those of their last instant, none before */
    if (!opt || !tr) return vt_fail(d->message, VT_ERR_NULL, "%s: NULL options or trajectory", who);
    if (tr->model != m) return vt_fail(d->message, VT_ERR_MODEL_MISMATCH, "%s: trajectory made for another model", who);
    if (!isfinite(opt->t0) || !isfinite(opt->t1) || !(opt->t1 > opt->t0))
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: need finite t0 < t1 (t0 %g, t1 %g)", who, opt->t0, opt->t1);
    if (opt->tout || opt->ntout) { /* the caller's output times */
        if (!opt->tout || opt->ntout < 1)
            return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: output times: tout %s with ntout %d (need both, ntout >= 1)",
                           who, opt->tout ? "given" : "NULL", opt->ntout);
        if (opt->ntout + 1 > tr->nrow)
            return vt_fail(d->message, VT_ERR_BAD_OPTION,
                           "%s: ntout %d needs %d trajectory rows (row 0 is t0), the trajectory has %d", who, opt->ntout,
                           opt->ntout + 1, tr->nrow);
        for (int k = 0; k < opt->ntout; k++) {
            const double v = opt->tout[k], before = k ? opt->tout[k - 1] : opt->t0;
            if (!isfinite(v)) return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: tout[%d] is not finite", who, k);
            if (!(v > before))
                return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: tout[%d] = %g is not after %s = %g", who, k, v,
                               k ? "the previous entry" : "t0", before);
            if (v > opt->t1)
                return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: tout[%d] = %g is after t1 = %g", who, k, v, opt->t1);
        }
    } else if (opt->nout < 1 || opt->nout + 1 > tr->nrow) {
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: nout %d needs 1..%d (the trajectory's rows − 1)", who,
                       opt->nout, tr->nrow - 1);
    }
    if (!(opt->rtol > 0.0) || !(opt->atol > 0.0) || !(opt->max_step >= 0.0) || opt->max_steps < 1 ||
        !(opt->newton_tol > 0.0) || opt->newton_maxit < 1 || opt->history_steps < 2 || /* +Inf passes `> 0` */
        !isfinite(opt->rtol) || !isfinite(opt->atol) || !isfinite(opt->max_step) || !isfinite(opt->newton_tol))
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "%s: tolerances and step limits must be finite and positive (rtol %g, atol %g, newton_tol %g, max_step %g "
                       "≥ 0), step and iteration counts positive", who, opt->rtol, opt->atol, opt->newton_tol, opt->max_step);
    if (opt->formulation < 0 || opt->formulation >= VT_FORMULATION_COUNT || !(opt->baumgarte_alpha >= 0.0) ||
        !(opt->baumgarte_beta >= 0.0) || !isfinite(opt->baumgarte_alpha) || !isfinite(opt->baumgarte_beta))
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: formulation %d or Baumgarte parameters out of range", who,
                       opt->formulation);
    if (!(opt->redundant_band >= 0.0 && opt->redundant_band < 1.0))
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: redundant_band %g outside [0, 1)", who, opt->redundant_band);
    if (!(opt->check_window > 0.0)) /* (NaN fails; +Inf is one window) */
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "%s: check_window %g s must be > 0 (+Inf: the whole run one window)",
                       who, opt->check_window);
    return VT_OK;
}
