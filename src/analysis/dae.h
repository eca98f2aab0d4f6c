/* vtdyn — The DAE handed to IDA: residual, Jacobian, blocks of y, the exact reference
 * (analysis/dae.c). */
#ifndef VT_ANALYSIS_DAE_H
#define VT_ANALYSIS_DAE_H

#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include "vtdyn.h"

/* The driven run's steps, kept for an independent forward run: t, y = [q; v] and y' at every
 * step IDA takes from the forward run's time on (analysis/dynamic_analysis.c drops the older ones
 * at each window's end, or when full); between steps y is the cubic Hermite interpolant of the
 * two ends. */
typedef struct vt_dae_history {
    int cap;            /* steps the arrays hold */
    int n;              /* steps recorded */
    int dim;            /* length of y: nq + nv of the driven model */
    double *t, *y, *yp; /* (cap), (dim x cap), (dim x cap) */
    double *tmp;        /* an interpolated y (dim) */
    double err;         /* largest |Hermite − IDA's own interpolant| at step midpoints */
} vt_dae_history;

/* y at t from the recorded steps into out (dim): the cubic Hermite interpolant of the two steps
 * around t (extrapolated from the first or last two outside them) */
void vt_dae_hermite(const vt_dae_history *h, double t, double *out);

/* One IDA system: the blocks present in y (driven first, then forward) and what their residual
 * needs. Zero what is absent (designated initializers): a run has a driven block (m), a forward
 * block (mf), or both. */
typedef struct vt_dae {
    const vt_model *m;          /* driven block (NULL when Q_d is exact) */
    vt_data *d;                 /* its data */
    const vt_model *mf;         /* forward block (NULL without the forward check) */
    vt_data *df;                /* its data */
    vt_data *dk;                /* exact Q_d (fully driven), or the interpolated driven state (src) */
    vt_data *msg;               /* where IDA's messages go */
    const double *xfrc0;        /* applied loads of the driven run, kept in the forward one (with
                                   loads at frames or on contacts dk's: the caller's, the frames'
                                   and the ground's forces) */
    const vt_run_options *run;  /* a run with loads at frames or on contacts (exact efforts): dk's
                                   efforts with them and the ground's forces
                                   (analysis/contact_run.c); NULL: none */
    const double *base;         /* with run: the caller's loads */
    int as_loads;               /* vt_run_options.forward_as_loads */
    double newton_tol;          /* vt_run_options.newton_tol: projections and exact efforts */
    int newton_maxit;           /* vt_run_options.newton_maxit */
    int nd;                     /* size of the driven block in y (set by the start) */
    int form;                   /* vt_formulation */
    double alpha, beta;         /* 1/s, Baumgarte's terms (vt_run_options.baumgarte_alpha, _beta) */
    vt_dae_history *rec;        /* driven run: record its steps here */
    vt_dae_history *src;        /* forward run: the driven steps, efforts from their interpolant */
    double *w;                  /* the GGL residual's v + Φ_q^T μ (nv; set by the start) */
    double band;                /* vt_run_options.redundant_band (ODE form; set by the start) */
    struct {                    /* set by the run */
        void *ida;              /* IDA's memory: the Jacobian's increments use its step and weights */
        vt_status why;          /* the last refusal's status since the current IDASolve call began */
        int fatal;              /* 1: the user's functions failed, 2: too many refusals; the run ends with it */
        int refusals;           /* recoverable refusals since the current IDASolve call began */
        double t;               /* the last refusal's time */
        char msg[256];          /* and its message */
        int dk_valid;           /* dk holds the exact efforts at dk->time (they depend on t alone) */
        int motion;             /* the forward block's residual by motion_residual (set by the start) */
        const vt_trajectory *rows; /* exact efforts: the kinematic analysis's rows, Newton's starts */
        double *ref;            /* exact efforts: y_ref, y'_ref of the reference motion at dk->time, then
                                   y = y_ref + e and y' (4 x N); NULL: IDA's unknowns are y itself */
        double rtol;            /* with ref: IDA's weights are those of y, 1 / (rtol |y_ref + e| + atol) */
        const double *atol;     /* with ref: the absolute tolerances (N) */
    } s;
} vt_dae;

/* before each IDASolve call: no refusal yet */
void vt_dae_fresh(vt_dae *p);
/* the length of one model's block of y in formulation form: [q; v], [q; v; λ] or [q; v; λ; μ] */
int vt_dae_block_size(const vt_model *m, int form);

/* IDA's callbacks, user data a vt_dae: the residual F(t, y, y') (0 ok, > 0 recoverable, < 0
 * fatal), the iteration matrix by IDA's difference quotient, the deviation's error weights
 * (s.ref) and the error handler (into msg->message) */
int vt_dae_residual(sunrealtype t, N_Vector yy, N_Vector yyp, N_Vector rr, void *user);
int vt_dae_jacobian(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yyp, N_Vector rr, SUNMatrix J, void *user,
                    N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
int vt_dae_deviation_weights(N_Vector yy, N_Vector ewt, void *user);
void vt_dae_ida_error(int code, const char *module, const char *function, char *msg, void *user);

/* The driven run's state at t (p->src's Hermite interpolant) into p->dk (model m), and its
 * instant: the drives' efforts there (a failure: its status, p->dk->message says why) */
vt_status vt_dae_driven_at(const vt_dae *p, const vt_model *m, double t);
/* At an output time the drives' efforts are row k of p->s.rows, copied into p->dk; on contacts
 * (p->run) the row's state's efforts and loads formed again in dk (a failure: its status) */
vt_status vt_dae_row_efforts(const vt_dae *p, const vt_model *m, int k);
/* y_ref, y'_ref of one block (length n) at a state in d: [q; v; 0], [T(q) v; q̈; 0] */
void vt_dae_block_reference(const vt_model *m, const vt_data *d, int n, double *yr, double *ypr);
/* y and y' of one block at a consistent state in d: [q; v; λ (; μ = 0)], [T(q) v; q̈; 0] */
void vt_dae_block_initial(const vt_model *m, const vt_data *d, int form, double *y, double *yp);
/* IDA's ids of one block: 1 for q and v (differential), 0 for λ and μ (algebraic) */
void vt_dae_block_ids(const vt_model *m, int form, double *id);
/* a block of y projected onto Φ = 0 and Φ_q v = −Φ_t, y' and λ consistent again */
vt_status vt_dae_block_project(const vt_dae *p, const vt_model *m, vt_data *d, double t, double *y, double *yp);
/* a block of y into d, then the whole instant (efforts, reactions) with the residual's band */
vt_status vt_dae_block_output(const vt_model *m, vt_data *d, double t, const double *y, double band);

#endif
