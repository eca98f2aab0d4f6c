/* Dynamic analysis and the forward check with SUNDIALS IDA: the set-up, the steps and the
 * outputs. The equations IDA solves (the index-1 form of (5), the other formulations, the
 * iteration matrix, the deviation from an exact motion) are in analysis/dae.c.
 *
 * Consistent initial values are computed, not guessed: q and v projected onto Φ = 0 and
 * Φ_q v = −Φ_t (vt_kinematic_solve), then q̈ and λ from (5).
 *
 * Forward check (the paper's Figs. 6-8, 10): the model without drives (cut joints and p^T p = 1
 * kept) under the drives' efforts: by default their generalized force Φ_q,d^T λ_d as qfrc (the
 * joint torques, as the paper applies them); with forward_as_loads each drive's own load (a
 * point drive's force at its body point, ...), the same physical loads, so that the reactions
 * must agree as well (with joint torques only a joint-driven model's do). For a partly
 * driven model the driven run keeps every step (t, y, y') and a separate forward run takes the
 * efforts at any t from the driven state's cubic Hermite interpolant between two steps, solved
 * again; the interpolant's error is measured against IDA's own at each step's middle. (Or, with
 * forward_independent = 0, both share one IDA run, y = [y_driven; y_forward], the efforts from
 * the driven block's λ at the same t.) For a fully driven model they are exact: the kinematic
 * solution at every t that IDA asks for, Newton started from the analysis's rows around t
 * interpolated and taken one step past newton_tol (VT_SOLVE_POLISH: its error is then
 * round-off), and at the output times the rows themselves; IDA's unknowns are then the
 * deviation from that exact motion (analysis/dae.c).
 *
 * Windows (vt_run_options.check_window, s): the forward motion of a chaotic or unstable mechanism
 * leaves the driven one exponentially whatever the efforts' accuracy, so one check over a long
 * run measures the chaos. At the first output row check_window or more past a window's start the
 * forward block restarts from the driven state of that row (restart_forward) and a new window
 * begins. In seconds, not rows: the growth is a matter of time, whatever the output rate; at
 * output rows, so that a restart sits on a stored driven state and a trajectory holds at most
 * nrow windows (no allocation at a run's start or per window). The default, 5 s, keeps every
 * run of a few seconds in one window, bit for bit as before. The independent check interleaves
 * its two runs window by window (run_independent), so that the history need hold one window's
 * steps; history_steps is a capacity, not a limit: a full history makes the forward run catch up
 * with the driven run's newest step (catch_up; not a restart), then keeps that step alone.
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "analysis/dynamic_analysis.h"
#include "analysis/contact_run.h"
#include "analysis/data.h"
#include "base/status.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "dense/reactions.h"
#include "analysis/dae.h"
#include "analysis/kinematic_solve.h"
#include "analysis/trajectory.h"

/* IDA's objects for one run (NULL until made; ida_free releases them), the call that failed and
 * the steps counted before a restart */
typedef struct {
    SUNContext ctx;
    N_Vector y, yp, id, atol;
    N_Vector yint;      /* IDA's own interpolant (a run that keeps its history) */
    SUNMatrix A;
    SUNLinearSolver LS;
    void *mem;          /* IDA's memory */
    int N;              /* the length of y */
    double tend;        /* the last output time */
    double tstop;       /* IDA's stop time: tend, or a forward run's bound (run_state.stop) */
    const char *call;   /* the last SUNDIALS call made, named in a failure's message */
    int flag;           /* its return value: < 0 it failed (ida_failure reports it) */
    long nst_done, nre_done; /* steps and residuals before IDAReInit restarts the counters */
} ida_run;

/* SUNDIALS' check_retval: the call named, and on failure (< 0) out with VT_ERR_IDA, r->flag the
 * failed call's value (the caller reports it with ida_failure) */
#define CHECK(expr, name)                                                                             \
    do {                                                                                              \
        r->call = name;                                                                               \
        if ((r->flag = (expr)) < 0) return VT_ERR_IDA;                                                \
    } while (0)

/* an allocation that failed: reported as a SUNDIALS call returning -1 */
static vt_status no_memory(ida_run *r, const char *call)
{
    r->call = call;
    r->flag = -1;
    return VT_ERR_IDA;
}

/* IDA set up on y0, y'0 and the ids (r->N each): its vectors, matrix and dense solver, the
 * residual, Jacobian and tolerances of dae.c, the limits of opt and the stop time r->tend (the
 * last output: IDA never steps past it, so an independent forward check's driven history covers
 * every time the forward run asks for, no extrapolation); with p->rec the interpolant's vector */
static vt_status ida_setup(vt_dae *p, const vt_run_options *opt, const double *y0, const double *yp0,
                           const double *ids, ida_run *r)
{
    const int N = r->N;
    CHECK(SUNContext_Create(NULL, &r->ctx), "SUNContext_Create");
    r->y = N_VNew_Serial(N, r->ctx);
    r->yp = N_VNew_Serial(N, r->ctx);
    r->id = N_VNew_Serial(N, r->ctx);
    r->A = SUNDenseMatrix(N, N, r->ctx);
    r->mem = IDACreate(r->ctx);
    p->s.ida = r->mem;
    vt_dae_fresh(p);
    if (!r->y || !r->yp || !r->id || !r->A || !r->mem)
        return no_memory(r, "allocation of IDA's vectors, matrix and memory");
    r->LS = SUNLinSol_Dense(r->y, r->A, r->ctx);
    if (!r->LS) return no_memory(r, "SUNLinSol_Dense");
    memcpy(N_VGetArrayPointer(r->y), y0, (size_t)N * sizeof(double));
    memcpy(N_VGetArrayPointer(r->yp), yp0, (size_t)N * sizeof(double));
    memcpy(N_VGetArrayPointer(r->id), ids, (size_t)N * sizeof(double));
    void *mem = r->mem;
    CHECK(IDASetErrHandlerFn(mem, vt_dae_ida_error, p), "IDASetErrHandlerFn");
    CHECK(IDAInit(mem, vt_dae_residual, opt->t0, r->y, r->yp), "IDAInit");
    /* absolute tolerances: atol on q and q̇; the multipliers are out of the error test, and a
     * loose weight keeps them from stalling the corrector's convergence test (their index-2
     * errors are O(1/h) in GGL) */
    r->atol = N_VNew_Serial(N, r->ctx);
    if (!r->atol) return no_memory(r, "N_VNew_Serial");
    for (int k = 0; k < N; k++) N_VGetArrayPointer(r->atol)[k] = ids[k] > 0.5 ? opt->atol : 1.0;
    CHECK(IDASetUserData(mem, p), "IDASetUserData"); /* (before IDAWFtolerances: its function's data) */
    if (p->s.ref) {
        p->s.rtol = opt->rtol;
        p->s.atol = N_VGetArrayPointer(r->atol);
        CHECK(IDAWFtolerances(mem, vt_dae_deviation_weights), "IDAWFtolerances");
    } else {
        CHECK(IDASVtolerances(mem, opt->rtol, r->atol), "IDASVtolerances");
    }
    CHECK(IDASetLinearSolver(mem, r->LS, r->A), "IDASetLinearSolver");
    CHECK(IDASetJacFn(mem, vt_dae_jacobian), "IDASetJacFn");
    CHECK(IDASetId(mem, r->id), "IDASetId");
    CHECK(IDASetSuppressAlg(mem, SUNTRUE), "IDASetSuppressAlg");
    CHECK(IDASetMaxNumSteps(mem, opt->max_steps), "IDASetMaxNumSteps");
    if (opt->max_step > 0.0) CHECK(IDASetMaxStep(mem, opt->max_step), "IDASetMaxStep");
    CHECK(IDASetStopTime(mem, r->tend), "IDASetStopTime");
    r->tstop = r->tend;
    vt_dae_history *h = p->rec;
    if (h) {
        r->yint = N_VNew_Serial(N, r->ctx);
        if (!r->yint) return no_memory(r, "N_VNew_Serial");
        h->n = 0;
        h->err = 0.0;
    }
    return VT_OK;
}

/* One IDA run in progress: the driven run, the forward run, or both in one system. An
 * independent forward check has two, interleaved: the driven run keeps its steps in a history,
 * and the forward run that reads them follows it window by window (run_independent) */
typedef struct run_state {
    vt_dae *p;
    const vt_run_options *opt;
    vt_trajectory *tr;
    ida_run r;
    double *buf;            /* y0, y'0, ids (3 N), then p->w and p->s.ref */
    double tstep;           /* a run that keeps its history: its last step's time */
    int k;                  /* the last row stored */
    int nrow;               /* rows after row 0 */
    double stop;            /* a forward run reading a history: how far it may go (IDA's stop time):
                               the newest recorded step, or its window's end */
    struct run_state *fwd;  /* a run that keeps its history: the forward run reading it */
} run_state;

static vt_status catch_up(run_state *fw);

/* IDA's stop time moved to t (only when it changes: a run in one window keeps tend, set once) */
static vt_status stop_at(ida_run *r, double t)
{
    if (t == r->tstop) return VT_OK;
    CHECK(IDASetStopTime(r->mem, t), "IDASetStopTime");
    r->tstop = t;
    return VT_OK;
}

/* IDA from rs->tstep on to row k's time tout, *tret the time reached. A run that keeps its
 * history (p->rec) goes one step at a time, records every step and the interpolation's error,
 * and takes the output from IDA's interpolant; when the history is full the forward run reading
 * it first catches up (catch_up: it then needs only the newest step). Any other run lets IDA step
 * to tout */
static vt_status advance(run_state *rs, double tout, double *tret)
{
    vt_dae *p = rs->p;
    const vt_run_options *opt = rs->opt;
    ida_run *r = &rs->r;
    vt_data *md = p->msg;
    vt_dae_history *h = p->rec;
    if (!h) {
        vt_dae_fresh(p);
        CHECK(IDASolve(r->mem, tout, tret, r->y, r->yp, IDA_NORMAL), "IDASolve");
        return VT_OK;
    }
    if (h->n == 0) { /* the start */
        h->t[0] = opt->t0;
        memcpy(h->y, rs->buf, (size_t)h->dim * sizeof(double));
        memcpy(h->yp, rs->buf + r->N, (size_t)h->dim * sizeof(double));
        h->n = 1;
    }
    long taken = 0;
    double *tstep = &rs->tstep;
    while (*tstep < tout) {
        if (++taken > opt->max_steps) { /* IDA's own mxstep limit does not apply to one-step mode */
            md->ida_flag = IDA_TOO_MUCH_WORK;
            return vt_fail(md->message, VT_ERR_IDA,
                           "IDASolve: IDA_TOO_MUCH_WORK: %ld steps taken before t = %g (at t = %g)", opt->max_steps,
                           tout, *tstep);
        }
        vt_dae_fresh(p);
        CHECK(IDASolve(r->mem, r->tend, tstep, r->y, r->yp, IDA_ONE_STEP), "IDASolve");
        vt_status st;
        if (h->n == h->cap && (st = catch_up(rs->fwd))) return st;
        h->t[h->n] = *tstep;
        memcpy(h->y + (size_t)h->n * (size_t)h->dim, N_VGetArrayPointer(r->y), (size_t)h->dim * sizeof(double));
        memcpy(h->yp + (size_t)h->n * (size_t)h->dim, N_VGetArrayPointer(r->yp), (size_t)h->dim * sizeof(double));
        h->n++;
        /* the interpolation's error, against IDA's own interpolant at the step's middle */
        CHECK(IDAGetDky(r->mem, 0.5 * (h->t[h->n - 2] + *tstep), 0, r->yint), "IDAGetDky");
        vt_dae_hermite(h, 0.5 * (h->t[h->n - 2] + *tstep), h->tmp);
        for (int c = 0; c < h->dim; c++) h->err = fmax(h->err, fabs(h->tmp[c] - N_VGetArrayPointer(r->yint)[c]));
    }
    CHECK(IDAGetDky(r->mem, tout, 0, r->yint), "IDAGetDky");
    *tret = tout;
    memcpy(N_VGetArrayPointer(r->y), N_VGetArrayPointer(r->yint), (size_t)r->N * sizeof(double));
    return VT_OK;
}

/* The state at row k (time tret) into *yv: IDA's y, or with exact efforts the row's reference
 * plus IDA's deviation. The projection formulation puts it back onto the constraints and
 * restarts IDA there */
static vt_status row_state(vt_dae *p, ida_run *r, int k, double tret, const double **yv)
{
    vt_data *md = p->msg;
    const int N = r->N;
    *yv = N_VGetArrayPointer(r->y);
    double *yw = N_VGetArrayPointer(r->y), *ypw = N_VGetArrayPointer(r->yp);
    if (p->s.ref) { /* the state: the row (the reference at tout) + the deviation */
        const vt_status st = vt_dae_row_efforts(p, p->dk->model, k);
        if (st) return vt_fail(md->message, st, "%s", p->dk->message);
        p->s.dk_valid = 0; /* dk holds the row, not the residual's polished reference */
        vt_dae_block_reference(p->dk->model, p->dk, N, p->s.ref, p->s.ref + N);
        yw = p->s.ref + 2 * (size_t)N;
        ypw = yw + N;
        for (int c = 0; c < N; c++) {
            yw[c] = p->s.ref[c] + N_VGetArrayPointer(r->y)[c];
            ypw[c] = p->s.ref[N + c] + N_VGetArrayPointer(r->yp)[c];
        }
        *yv = yw;
    }
    if (p->form != VT_FORMULATION_PROJECTION) return VT_OK;
    /* back onto the constraints, then restart IDA */
    const vt_data *dp = p->m ? p->d : p->df;
    vt_status st = VT_OK;
    if ((p->m && (st = vt_dae_block_project(p, p->m, p->d, tret, yw, ypw))) ||
        (p->mf && (dp = p->df, st = vt_dae_block_project(p, p->mf, p->df, tret, yw + p->nd, ypw + p->nd)))) {
        char why[VT_MESSAGE_SIZE]; /* (dp's message may be md's) */
        snprintf(why, sizeof why, "%s", dp->message);
        vt_fail(md->message, st, "projection at t = %g failed: %.200s", tret, why);
        return st;
    }
    if (p->s.ref) /* back to the deviation */
        for (int c = 0; c < N; c++) {
            N_VGetArrayPointer(r->y)[c] = yw[c] - p->s.ref[c];
            N_VGetArrayPointer(r->yp)[c] = ypw[c] - p->s.ref[N + c];
        }
    long a = 0, b = 0;
    IDAGetNumSteps(r->mem, &a);
    IDAGetNumResEvals(r->mem, &b);
    r->nst_done += a;
    r->nre_done += b;
    CHECK(IDAReInit(r->mem, tret, r->y, r->yp), "IDAReInit");
    return VT_OK;
}

/* Row k of the trajectory from the state yv at tret: the driven block's instant and the forward
 * block's (its efforts from the interpolated driven run, the analysis's row or the driven block,
 * then its q̈ and reactions) */
static vt_status store_rows(vt_dae *p, vt_trajectory *tr, int k, double tret, const double *yv)
{
    vt_data *md = p->msg;
    vt_status st;
    if (p->m) {
        if ((st = vt_dae_block_output(p->m, p->d, tret, yv, p->band))) return st;
        vt_trajectory_store(tr, p->m, p->d, k);
    }
    if (!p->mf) return VT_OK;
    const vt_model *m = p->dk ? p->dk->model : p->m;
    vt_data *src = p->dk ? p->dk : p->d;
    if (p->src) { /* the driven run's interpolated state and its efforts */
        if ((st = vt_dae_driven_at(p, m, tret)))
            return vt_fail(md->message, st, "forward check at t = %g: %s", tret, p->dk->message);
    } else if (p->dk && !p->s.ref) { /* exact efforts: the kinematic row already stored at this time */
        if ((st = vt_dae_row_efforts(p, m, k))) return vt_fail(md->message, st, "%s", p->dk->message);
        p->s.dk_valid = 1;
    }
    memcpy(p->df->q, yv + p->nd, (size_t)p->mf->nq * sizeof(double));
    if (p->s.motion) { /* a tree: its q̈ and reactions by the recursive instant (articulated bodies) */
        memcpy(p->df->qd, yv + p->nd + p->mf->nq, (size_t)p->mf->nv * sizeof(double));
        p->df->time = tret;
        if (p->as_loads && (st = vt_kinematics_tree(p->mf, p->df, 0))) return st;
        vt_apply_drive_loads(p->mf, p->df, m, src, p->xfrc0, p->as_loads);
        st = vt_inverse_dynamics_recursive(p->mf, p->df);
    } else {
        if ((st = vt_kinematics(p->mf, p->df))) return st;
        vt_apply_drive_loads(p->mf, p->df, m, src, p->xfrc0, p->as_loads);
        st = vt_dae_block_output(p->mf, p->df, tret, yv + p->nd, p->band);
    }
    if (st) return vt_fail(md->message, st, "forward check at t = %g: %s", tret, p->df->message);
    vt_trajectory_store_forward(tr, p->mf, p->df, k);
    return VT_OK;
}

/* A failed SUNDIALS call (r->call returned r->flag < 0) into p->msg: the residual's own status and
 * message when a refusal caused it, else the call, IDA's flag name and IDA's message */
static vt_status ida_failure(vt_dae *p, const ida_run *r)
{
    vt_data *md = p->msg;
    const int flag = r->flag;
    md->ida_flag = flag;
    if (p->s.why && (p->s.fatal || flag == IDA_CONV_FAIL || flag == IDA_REP_RES_ERR || flag == IDA_RES_FAIL ||
                     flag == IDA_LSETUP_FAIL || flag == IDA_FIRST_RES_FAIL)) {
        /* the residual's own failure, not IDA's generic report of it */
        char detail[VT_MESSAGE_SIZE];
        snprintf(detail, sizeof detail, "%s", p->s.msg);
        if (p->s.fatal == 1)
            snprintf(md->message, sizeof md->message, "%.250s", detail);
        else
            snprintf(md->message, sizeof md->message,
                     "%.20s returned %d after %d refused trial states; the last, at t = %.10g: %.120s", r->call, flag,
                     p->s.refusals, p->s.t, detail);
        return p->s.why;
    }
    char *name = IDAGetReturnFlagName(flag);
    char detail[200];
    snprintf(detail, sizeof detail, "%.150s", md->message);
    snprintf(md->message, sizeof md->message, "%.40s returned %d (%.30s)%s%.150s", r->call, flag, name ? name : "?",
             detail[0] ? ": " : "", detail);
    free(name);
    return VT_ERR_IDA;
}

/* IDA's objects released, in the reverse order of their making */
static void ida_free(ida_run *r)
{
    if (r->mem) IDAFree(&r->mem);
    if (r->LS) SUNLinSolFree(r->LS);
    if (r->A) SUNMatDestroy(r->A);
    if (r->id) N_VDestroy(r->id);
    if (r->atol) N_VDestroy(r->atol);
    if (r->yint) N_VDestroy(r->yint);
    if (r->yp) N_VDestroy(r->yp);
    if (r->y) N_VDestroy(r->y);
    if (r->ctx) SUNContext_Free(&r->ctx);
}

/* Row k of a run: IDA to its time (a forward run reading a history no further than rs->stop),
 * the state there, the driven and forward rows stored, the progress reported; a failed SUNDIALS
 * call reported (ida_failure) */
static vt_status row(run_state *rs, int k)
{
    vt_dae *p = rs->p;
    const vt_run_options *opt = rs->opt;
    ida_run *r = &rs->r;
    double tret = 0.0;
    const double *yv = NULL;
    vt_status st = p->src ? stop_at(r, rs->stop) : VT_OK;
    if (!st && !(st = advance(rs, vt_run_time(opt, k), &tret)) && !(st = row_state(p, r, k, tret, &yv)) &&
        !(st = store_rows(p, rs->tr, k, tret, yv))) {
        rs->k = k;
        if (opt->progress && opt->progress(tret, r->tend, opt->user))
            st = vt_fail(p->msg->message, VT_ERR_ABORTED, "stopped at t = %g", tret);
    }
    if (st && r->flag < 0) {
        st = ida_failure(p, r);
        r->flag = 0; /* (reported) */
    }
    return st;
}

/* the history from the step at or before t on: all that a forward run at t still reads */
static void history_from(vt_dae_history *h, double t)
{
    int j = 0;
    while (j + 1 < h->n && h->t[j + 1] <= t) j++;
    if (j == 0) return;
    const size_t n = (size_t)(h->n - j), dim = (size_t)h->dim;
    memmove(h->t, h->t + j, n * sizeof(double));
    memmove(h->y, h->y + (size_t)j * dim, n * dim * sizeof(double));
    memmove(h->yp, h->yp + (size_t)j * dim, n * dim * sizeof(double));
    h->n = (int)n;
}

/* The history is full: the forward run catches up with its newest step T (its rows up to T, then
 * IDA to T, its stop time), and the history keeps that step alone. The forward check is not
 * restarted: history_steps bounds the memory, not the run (the forward run's steps are only cut
 * at T) */
static vt_status catch_up(run_state *fw)
{
    vt_dae_history *h = fw->p->src;
    ida_run *r = &fw->r;
    const double T = h->t[h->n - 1];
    vt_status st = VT_OK;
    fw->stop = T;
    for (int k = fw->k + 1; k <= fw->nrow && vt_run_time(fw->opt, k) <= T; k++)
        if ((st = row(fw, k))) return st;
    double tn = 0.0, hh = 0.0, tret = 0.0;
    IDAGetCurrentTime(r->mem, &tn);
    IDAGetCurrentStep(r->mem, &hh);
    if (T - tn > 100.0 * DBL_EPSILON * (fabs(tn) + fabs(hh))) { /* (IDA's own round-off of a time) */
        vt_dae_fresh(fw->p);
        r->call = "IDASolve";
        if ((st = stop_at(r, T)) || (r->flag = IDASolve(r->mem, T, &tret, r->y, r->yp, IDA_NORMAL)) < 0) {
            st = ida_failure(fw->p, r);
            r->flag = 0;
            return st;
        }
    }
    history_from(h, T);
    return VT_OK;
}

/* A window of the forward check ends at row k (time t): the forward block restarts from the
 * driven state there (the row's q and q̇, the drives' efforts as its residual takes them at t:
 * the interpolated driven run's, the row's exact ones, or the driven block's), consistent
 * accelerations and multipliers by the forward instant, IDA restarted; a new window in the
 * trajectory */
static vt_status restart_forward(run_state *rs, int k)
{
    vt_dae *p = rs->p;
    ida_run *r = &rs->r;
    vt_trajectory *tr = rs->tr;
    vt_data *md = p->msg, *df = p->df;
    const vt_model *m = p->dk ? p->dk->model : p->m, *mf = p->mf;
    vt_data *src = p->dk ? p->dk : p->d;
    const double t = tr->t[k];
    const int nf = vt_dae_block_size(mf, p->form);
    double *y = N_VGetArrayPointer(r->y) + p->nd, *yp = N_VGetArrayPointer(r->yp) + p->nd;
    vt_status st = VT_OK;
    if (p->src) { /* the efforts of the driven state interpolated at t, as the residual's */
        if ((st = vt_dae_driven_at(p, m, t)))
            return vt_fail(md->message, st, "forward check: restart at t = %g: %s", t, p->dk->message);
    } else if (p->dk) { /* exact efforts: the row's */
        if ((st = vt_dae_row_efforts(p, m, k))) return vt_fail(md->message, st, "%s", p->dk->message);
        p->s.dk_valid = 0;
    } /* (else the driven block's: d holds row k's instant) */
    memcpy(df->q, tr->q + (size_t)k * (size_t)m->nq, (size_t)mf->nq * sizeof(double));
    memcpy(df->qd, tr->qd + (size_t)k * (size_t)m->nv, (size_t)mf->nv * sizeof(double));
    df->time = t;
    if ((st = vt_kinematics(mf, df)) == VT_OK) {
        vt_apply_drive_loads(mf, df, m, src, p->xfrc0, p->as_loads);
        st = vt_inverse_dynamics(mf, df);
    }
    if (st) return vt_fail(md->message, st, "forward check: restart at t = %g: %s", t, df->message);
    vt_dae_block_initial(mf, df, p->form, y, yp);
    if (p->s.ref) { /* the deviation from the reference motion at t: 0 in q and v */
        vt_dae_block_reference(m, p->dk, nf, p->s.ref, p->s.ref + nf);
        for (int c = 0; c < nf; c++) {
            y[c] -= p->s.ref[c];
            yp[c] -= p->s.ref[nf + c];
        }
    }
    long a = 0, b = 0;
    IDAGetNumSteps(r->mem, &a);
    IDAGetNumResEvals(r->mem, &b);
    r->nst_done += a;
    r->nre_done += b;
    r->call = "IDAReInit";
    if ((r->flag = IDAReInit(r->mem, t, r->y, r->yp)) < 0) {
        st = ida_failure(p, r);
        r->flag = 0;
        return st;
    }
    vt_trajectory_window(tr, k);
    return VT_OK;
}

/* row k ends the forward check's window that began at row s: the first row check_window or more
 * after s */
static int window_ends(const vt_run_options *opt, int s, int k)
{
    return vt_run_time(opt, k) - vt_run_time(opt, s) >= opt->check_window;
}

/* The end of a run: its steps and residual evaluations counted into tr (on success), IDA's
 * objects and the initial values freed; st passed on */
static vt_status close_run(run_state *rs, vt_status st)
{
    if (!st && rs->r.mem) {
        long nst = 0, nre = 0;
        IDAGetNumSteps(rs->r.mem, &nst);
        IDAGetNumResEvals(rs->r.mem, &nre);
        nst += rs->r.nst_done;
        nre += rs->r.nre_done;
        if (rs->p->m) { rs->tr->steps = nst; rs->tr->res_evals = nre; }
        if (rs->p->mf) { rs->tr->steps_fwd = nst; rs->tr->res_evals_fwd = nre; }
    }
    ida_free(&rs->r);
    free(rs->buf);
    rs->buf = NULL;
    return st;
}
#undef CHECK

/* the forward model and its data, started from the state in d (efforts already computed) */
static vt_status forward_setup(const vt_model *m, const vt_data *d, const double *xfrc0, int as_loads, vt_model **mf,
                               vt_data **df)
{
    vt_status st = vt_model_without_drives(mf, m);
    if (st) return st;
    if ((st = vt_data_create(df, *mf))) return st;
    memcpy((*df)->q, d->q, (size_t)m->nq * sizeof(double));
    memcpy((*df)->qd, d->qd, (size_t)m->nv * sizeof(double));
    (*df)->time = d->time;
    if ((st = vt_kinematics(*mf, *df))) return st;
    vt_apply_drive_loads(*mf, *df, m, d, xfrc0, as_loads);
    return vt_inverse_dynamics(*mf, *df);
}

/* a run's dae with the options filled; the caller names its blocks (m and d, mf and df, dk) and
 * histories, everything else starts zero */
static vt_dae dae_options(vt_data *d, const vt_run_options *opt)
{
    return (vt_dae){.msg = d,
                    .xfrc0 = d->xfrc,
                    .as_loads = opt->forward_as_loads,
                    .newton_tol = opt->newton_tol,
                    .newton_maxit = opt->newton_maxit,
                    .form = opt->formulation,
                    .alpha = opt->baumgarte_alpha,
                    .beta = opt->baumgarte_beta};
}

/* A run opened: y0, y'0 and the ids of the blocks present in p (driven first), IDA set up on
 * them (a failure reported: ida_failure); close_run ends it, whatever the outcome */
static vt_status open_run(run_state *rs, vt_dae *p, const vt_run_options *opt, vt_trajectory *tr)
{
    *rs = (run_state){.p = p, .opt = opt, .tr = tr, .tstep = opt->t0, .nrow = vt_run_rows(opt)};
    const int nd = p->m ? vt_dae_block_size(p->m, p->form) : 0, N = nd + (p->mf ? vt_dae_block_size(p->mf, p->form) : 0);
    const int nv = p->m ? p->m->nv : p->mf->nv;
    const int dev = p->dk && !p->src && !p->m; /* exact efforts: the deviation from the rows */
    double *buf = malloc(((3 + (dev ? 4 : 0)) * (size_t)N + (size_t)nv) * sizeof(double));
    if (!buf) return vt_fail(p->msg->message, VT_ERR_NO_MEMORY, "IDA set-up: out of memory");
    rs->buf = buf;
    p->w = buf + 3 * (size_t)N;
    p->s.ref = dev ? p->w + nv : NULL;
    p->band = p->form == VT_FORMULATION_ODE ? opt->redundant_band : 0.0; /* the ODE form's solves */
    /* a forward model without rows (no loop, no base body): its residual by one recursive pass */
    p->s.motion = p->mf && p->mf->nc == 0 && p->form != VT_FORMULATION_ODE;
    if (p->m) {
        vt_dae_block_initial(p->m, p->d, p->form, buf, buf + N);
        vt_dae_block_ids(p->m, p->form, buf + 2 * N);
    }
    if (p->mf) {
        vt_dae_block_initial(p->mf, p->df, p->form, buf + nd, buf + N + nd);
        vt_dae_block_ids(p->mf, p->form, buf + 2 * N + nd);
    }
    p->nd = nd;
    if (dev) { /* e = y − y_ref at t0, the first row */
        const vt_status st = vt_dae_row_efforts(p, p->dk->model, 0);
        if (st) return vt_fail(p->msg->message, st, "%s", p->dk->message);
        p->s.dk_valid = 0; /* (as at the output rows) */
        vt_dae_block_reference(p->dk->model, p->dk, N, p->s.ref, p->s.ref + N);
        for (int k = 0; k < N; k++) {
            buf[k] -= p->s.ref[k];
            buf[N + k] -= p->s.ref[N + k];
        }
    }
    rs->r = (ida_run){.N = N, .tend = vt_run_time(opt, rs->nrow)};
    rs->stop = rs->r.tend;
    vt_status st = ida_setup(p, opt, buf, buf + N, buf + 2 * N, &rs->r);
    if (st && rs->r.flag < 0) st = ida_failure(p, &rs->r);
    return st;
}

/* One run of every block in p (the driven run alone, both in one system, or the forward run with
 * exact efforts): rows 1..nrow; with a forward block, a new window of the check wherever one ends */
static vt_status start(vt_dae *p, const vt_run_options *opt, vt_trajectory *tr)
{
    run_state rs;
    vt_status st = open_run(&rs, p, opt, tr);
    for (int k = 1, s = 0; !st && k <= rs.nrow; k++)
        if (!(st = row(&rs, k)) && p->mf && k < rs.nrow && window_ends(opt, s, k)) {
            st = restart_forward(&rs, k);
            s = k;
        }
    return close_run(&rs, st);
}

/* The independent forward check: the driven run (its steps recorded in h) and the forward run
 * (its efforts from them) interleaved window by window: the driven run to the window's last row,
 * then the forward run to the same row, where it restarts from the driven state; the history
 * then keeps the steps from that row on. A run in one window is the driven run, then the forward
 * run, as before windows */
static vt_status run_independent(vt_dae *pd, vt_dae *pf, const vt_run_options *opt, vt_trajectory *tr)
{
    run_state dr, fr;
    vt_status st = open_run(&dr, pd, opt, tr);
    fr.buf = NULL;
    fr.r = (ida_run){.N = 0};
    if (!st) st = open_run(&fr, pf, opt, tr);
    dr.fwd = &fr;
    for (int k = 1, s = 0; !st && k <= dr.nrow; k++) {
        if ((st = row(&dr, k))) break;
        if (k < dr.nrow && !window_ends(opt, s, k)) continue;
        fr.stop = tr->t[k];
        for (int j = fr.k + 1; !st && j <= k; j++) st = row(&fr, j);
        if (!st && k < dr.nrow && !(st = restart_forward(&fr, k))) {
            history_from(pd->rec, tr->t[k]);
            s = k;
        }
    }
    st = close_run(&dr, st);
    return close_run(&fr, st);
}

vt_status vt_forward_exact(const vt_model *m, vt_data *d, vt_data *dk, const vt_run_options *opt, vt_trajectory *tr)
{
    vt_model *mf = NULL;
    vt_data *df = NULL;
    vt_status st = vt_kinematic_solve(dk->model, dk, opt->newton_tol, opt->newton_maxit);
    /* with loads at frames or on contacts the efforts with them and the ground's forces, which
     * dk->xfrc then holds */
    const int loaded = vt_run_has_loads(opt);
    if (st == VT_OK && loaded) st = vt_run_loads(m, dk, opt, d->xfrc, NULL, NULL, opt->forward_as_loads, "forward check");
    if (st == VT_OK) st = forward_setup(m, dk, loaded ? dk->xfrc : d->xfrc, opt->forward_as_loads, &mf, &df);
    if (st) {
        vt_fail(d->message, st, "forward check: set-up failed: %s", df ? df->message : dk->message);
    } else {
        vt_trajectory_store_forward(tr, mf, df, 0);
        vt_dae p = dae_options(d, opt); /* the forward block, its efforts exact */
        p.mf = mf;
        p.df = df;
        p.dk = dk;
        p.s.rows = tr;
        if (loaded) {
            p.run = opt;
            p.base = d->xfrc;
            p.xfrc0 = dk->xfrc;
        }
        st = start(&p, opt, tr);
    }
    vt_data_free(df);
    vt_model_free(mf);
    return st;
}

vt_status vt_dynamic_analysis(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr)
{
    vt_status st = vt_check_run(m, d, opt, tr, "vt_dynamic_analysis");
    if (st) return st;
    if (opt->contacts) /* its free rates follow from the forces, which the rule needs the motion for */
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "vt_dynamic_analysis: contacts are for a kinematic analysis (every rate driven) or the given "
                       "motion; a dynamic analysis would need the ground's forces to find its free rates");
    if (opt->nload) /* its residual would need them at every trial pose */
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "vt_dynamic_analysis: loads at frames (nload %d) are for a kinematic analysis or the given "
                       "motion (a batch's loads); a dynamic analysis takes xfrc", opt->nload);
    if (!d->Mstar) /* IDA's residual and iteration matrix are M*'s */
        return vt_fail(d->message, VT_ERR_LAYOUT,
                       "vt_dynamic_analysis: integrates (5) with M*, and the data holds none: its model was built with "
                       "layout VT_LAYOUT_RECURSIVE (VT_LAYOUT_FULL lays it out)");
    vt_trajectory_reset(tr);
    d->ida_flag = 0;
    d->time = opt->t0;
    if ((st = vt_kinematic_solve(m, d, opt->newton_tol, opt->newton_maxit))) return st;
    vt_trajectory_store(tr, m, d, 0);
    vt_model *mf = NULL;
    vt_data *df = NULL, *dk = NULL;
    vt_dae_history h = {.cap = opt->history_steps, .dim = m->nq + m->nv}; /* (an independent forward check) */
    double *hbuf = NULL;
    if (opt->forward_check && (st = forward_setup(m, d, d->xfrc, opt->forward_as_loads, &mf, &df))) {
        vt_fail(d->message, st, "vt_dynamic_analysis: forward check set-up: %s", df ? df->message : vt_status_string(st));
        goto out;
    }
    if (mf) vt_trajectory_store_forward(tr, mf, df, 0);
    if (!mf || !opt->forward_independent) { /* the driven run, and the forward one in the same system */
        vt_dae p = dae_options(d, opt);
        p.m = m;
        p.d = d;
        p.mf = mf;
        p.df = df;
        st = start(&p, opt, tr);
        goto out;
    }
    /* independent forward check: the driven run, its steps kept, and the forward run, its efforts
     * from the driven state interpolated at each time it asks for (run_independent) */
    const size_t per = 1 + 2 * (size_t)h.dim;
    hbuf = malloc(((size_t)h.cap * per + (size_t)h.dim) * sizeof(double));
    if (!hbuf || (st = vt_data_create_full(&dk, m))) {
        st = vt_fail(d->message, VT_ERR_NO_MEMORY, "vt_dynamic_analysis: out of memory for %d steps", h.cap);
        goto out;
    }
    h.t = hbuf;
    h.y = h.t + h.cap;
    h.yp = h.y + (size_t)h.cap * (size_t)h.dim;
    h.tmp = h.yp + (size_t)h.cap * (size_t)h.dim;
    memcpy(dk->xfrc, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    memcpy(dk->qfrc, d->qfrc, (size_t)m->nv * sizeof(double));
    {
        vt_dae pd = dae_options(d, opt); /* the driven block, its steps recorded */
        pd.m = m;
        pd.d = d;
        pd.rec = &h;
        vt_dae pf = dae_options(d, opt); /* the forward block, its efforts from the recorded steps */
        pf.mf = mf;
        pf.df = df;
        pf.dk = dk;
        pf.src = &h;
        st = run_independent(&pd, &pf, opt, tr);
        tr->fwd_interp_err = h.err;
    }
out:
    free(hbuf);
    vt_data_free(dk);
    vt_data_free(df);
    vt_model_free(mf);
    return st;
}

