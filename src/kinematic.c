/* Kinematic analysis: the motion fixed by the drives alone, solved instant by instant.
 *
 *   positions    Φ(q, t) = 0:  Φ_q Δ = −Φ,  q ← q ⊕ Δ  (Newton–Raphson; ⊕ as vt_integrate_q)
 *   velocities   Φ_q q̇ = −Φ_t                                   (time derivative of Φ = 0)
 *   accelerations and multipliers from (5), then efforts (24) and reactions (25)-(28)
 * Each linear step is LAPACK's dgels on Φ_q: with as many rows as rates it is the Newton step
 * itself; with fewer (consistent initial values of a dynamic analysis) the least-norm
 * correction, a projection onto the constraint manifold.
 */
#include <string.h>

#include "internal.h"

static double max_abs(const double *a, int n)
{
    double s = 0.0;
    for (int k = 0; k < n; k++) s = fmax(s, fabs(a[k]));
    return s;
}

/* x = least-norm (or exact) solution of Φ_q x = b with b = −Φ (positions) or
 * b = −Φ_t − Φ_q q̇ (velocities); x has nv entries */
static vt_status solve_phiq(const vt_model *m, vt_data *d, int velocities, double *x)
{
    const int nc = m->nc, nv = m->nv, one = 1, ldb = nc > nv ? nc : nv;
    double *A = d->kkt, *B = d->kkt_rhs;
    memcpy(A, d->Phiq, (size_t)nc * (size_t)nv * sizeof(double));
    memset(B, 0, (size_t)ldb * sizeof(double));
    for (int r = 0; r < nc; r++) {
        double v = velocities ? -d->Phit[r] : -d->Phi[r];
        if (velocities)
            for (int c = 0; c < nv; c++) v -= d->Phiq[r + (size_t)c * (size_t)nc] * d->qd[c];
        B[r] = v;
    }
    int info = 0;
    dgels_("N", &nc, &nv, &one, A, &nc, B, &ldb, d->lwork, &d->nlwork, &info, 1);
    if (info < 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_kinematic_solve: dgels info %d", info);
    if (info > 0 && m->allow_redundant) { /* dependent rows: the least-norm least-squares step (SVD) */
        memcpy(A, d->Phiq, (size_t)nc * (size_t)nv * sizeof(double));
        for (int r = 0; r < nc; r++) {
            double v = velocities ? -d->Phit[r] : -d->Phi[r];
            if (velocities)
                for (int c = 0; c < nv; c++) v -= d->Phiq[r + (size_t)c * (size_t)nc] * d->qd[c];
            B[r] = v;
        }
        for (int r = nc; r < ldb; r++) B[r] = 0.0;
        const double rc = 1e-10;
        int rank = 0;
        double *sv = d->kkt_scale;
        /* LAPACK's dgelsd stops the program (xerbla) on a NaN norm: refuse non-finite input */
        if (!vt_all_finite(A, nc * nv) || !vt_all_finite(B, ldb))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_kinematic_solve: NaN or Inf in Φ_q or Φ");
        dgelsd_(&nc, &nv, &one, A, &nc, B, &ldb, sv, &rc, &rank, d->lwork, &d->nlwork, d->liwork, &info);
        if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_kinematic_solve: dgelsd info %d", info);
    } else if (info > 0) {
        return vt_fail(d->message, VT_ERR_SINGULAR, "vt_kinematic_solve: Φ_q rank deficient at t = %g", d->time);
    }
    memcpy(x, B, (size_t)nv * sizeof(double));
    return VT_OK;
}

static vt_status restore(const vt_model *m, vt_data *d, vt_status st)
{
    memcpy(d->q, d->qsave, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, d->qsave + m->nq, (size_t)m->nv * sizeof(double));
    return st;
}

vt_status vt_kinematic_solve(const vt_model *m, vt_data *d, double tol, int maxit)
{
    vt_status st = vt_check_pair(m, d, "vt_kinematic_solve");
    if (st) return st;
    if (!(tol > 0.0) || maxit < 1)
        return vt_fail(d->message, VT_ERR_BAD_OPTION, "vt_kinematic_solve: tol %g and maxit %d must be positive", tol, maxit);
    memcpy(d->qsave, d->q, (size_t)m->nq * sizeof(double));
    memcpy(d->qsave + m->nq, d->qd, (size_t)m->nv * sizeof(double));
    double *step = d->xdd; /* free until vt_reactions: nx ≥ nv */
    double res = 0.0;
    int it = 0;
    if (m->nc > 0) {
        for (;; it++) {
            if ((st = vt_kinematics(m, d)) || (st = vt_constraints(m, d))) return restore(m, d, st);
            res = max_abs(d->Phi, m->nc);
            if (res <= tol) break;
            if (it == maxit)
                return restore(m, d, vt_fail(d->message, VT_ERR_NEWTON,
                                             "vt_kinematic_solve: max |Φ| = %.3g after %d iterations at t = %g", res,
                                             maxit, d->time));
            if ((st = solve_phiq(m, d, 0, step))) return restore(m, d, st);
            if ((st = vt_integrate_q(d->q, m, d->q, step, 1.0))) return restore(m, d, st);
        }
        /* velocities: the correction of q̇ that makes Φ_q q̇ = −Φ_t */
        if ((st = solve_phiq(m, d, 1, step))) return restore(m, d, st);
        for (int c = 0; c < m->nv; c++) d->qd[c] += step[c];
    }
    if ((st = vt_inverse_dynamics(m, d))) return restore(m, d, st);
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
    if (m->nc != m->nv)
        return vt_fail(d->message, VT_ERR_NOT_FULLY_DRIVEN,
                       "vt_kinematic_analysis: %d constraint rows for %d rates; a dynamic analysis handles the rest",
                       m->nc, m->nv);
    vt_trajectory_reset(tr);
    for (int k = 0; k <= opt->nout; k++) {
        d->time = opt->t0 + (opt->t1 - opt->t0) * k / opt->nout;
        if ((st = vt_kinematic_solve(m, d, opt->newton_tol, opt->newton_maxit))) return st;
        vt_trajectory_store(tr, m, d, k);
        if (opt->progress && opt->progress(d->time, opt->t1, opt->user))
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
