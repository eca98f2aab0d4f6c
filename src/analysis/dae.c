/* The DAE that a dynamic analysis and the forward check hand to SUNDIALS IDA: the index-1 form
 * of (5), its residual, iteration matrix and error weights.
 *
 * Unknowns y = [q; v; λ] (nq + nv + nc), v = q̇ the rates; residual F(t, y, y') = 0 with
 *   q' − T(q) v                  T = I, except a spherical joint: p' = ½ E(p)^T v
 *   M*(q) v' − Q(q, v, t) − Φ_q^T λ          (2)
 *   Φ_q v' − γ                               (5), second row
 * q and v are differential, λ algebraic (excluded from IDA's error test); the other
 * formulations (Baumgarte, GGL, ODE) at block_residual. The residual follows SUNDIALS's rules:
 * 0 ok, > 0 recoverable, < 0 fatal. A stage that refuses a trial state (a singular or
 * non-finite solve) is recoverable: IDA retries with a smaller step, at most VT_REFUSALS_MAX
 * times between two outputs (IDA's own limits, 10 failures a step and max_steps, bound it as
 * well). A failure of the user's functions at t (a drive's time function or orientation
 * callback: they depend on t alone, so no smaller step cures it) is fatal: the run ends at once
 * with its status and message. Either way the stage's status and message are kept and
 * reported, not IDA's generic one.
 *
 * The iteration matrix J = ∂F/∂y + c_j ∂F/∂y' (c_j from IDA's step): by forward differences,
 * column j from F(t, y + δ_j e_j, y' + c_j δ_j e_j) with IDA's own increments
 * δ_j = max(√ε max(|y_j|, |h y'_j|), 1/w_j), signed as h y'_j (w: IDA's error weights, h its
 * step) — the Jacobian IDA's dense difference quotient forms, written straight into IDA's matrix
 * with IDA's work vectors, so that a run allocates nothing after its start (IDA's own routine
 * clones a vector at every Jacobian). An analytic J needs ∂(M*)/∂q, ∂Q/∂q and ∂(Φ_q^T λ)/∂q:
 * not cheap.
 *
 * The forward check's block (analysis/dynamic_analysis.c) is the model without drives under the
 * drives' efforts: from the driven block's λ at the same t, from the driven run's steps
 * interpolated (vt_dae_hermite), or exact (fully driven: exact_efforts). With exact efforts
 * IDA's unknowns are the deviation from that exact motion y_ref(t) = [q; v; 0],
 * y_ref' = [T(q) v; q̈; 0]:
 *   e = y − y_ref(t),   G(t, e, e') = F(t, y_ref(t) + e, y_ref'(t) + e') = 0,
 * the same equations in shifted unknowns (y_ref and y_ref' exact, not integrated), so that IDA's
 * error test and steps follow what the efforts' error drives and not the motion itself: with
 * exact efforts e stays at round-off and IDA takes a few long steps (the five-link arm: 18 for
 * 100 rows, where y itself took about 500 at rtol 1e-8, its 1.4e-6 rad error IDA's own), and a
 * wrong effort shows as the deviation it causes (test_forward_check_measures_wrong_efforts). IDA's
 * error weights stay those of y, 1 / (rtol |y_ref + e| + atol) (vt_dae_deviation_weights). The
 * reference must sit on the forward model's constraints to round-off (GGL's Φ(q) = 0 rows):
 * Newton's error left within newton_tol would jitter from one t to the next, and IDA would chase
 * it. A forward model without constraint rows (a tree) has its residual M* v' − Q by one
 * recursive pass (vt_inverse_dynamics_motion with q̈ = v'): the same equations, O(n), M* and Q
 * not formed.
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <stdio.h>
#include <string.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "analysis/dae.h"
#include "analysis/contact_run.h"
#include "base/lapack.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "model/functions.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "dense/reactions.h"
#include "dense/solve.h"
#include "analysis/kinematic_solve.h"
#include "model/builder.h"

/* the driven run's y at t: the cubic Hermite interpolant of the recorded steps around t */
void vt_dae_hermite(const vt_dae_history *h, double t, double *out)
{
    int lo = 0, hi = h->n - 1;
    if (t <= h->t[0]) hi = 1;
    else if (t >= h->t[h->n - 1]) lo = h->n - 2;
    else
        while (hi - lo > 1) { /* bisection: t[lo] <= t < t[hi] */
            const int mid = (lo + hi) / 2;
            if (h->t[mid] <= t) lo = mid;
            else hi = mid;
        }
    const double t0 = h->t[lo], dt = h->t[lo + 1] - t0, sv = (t - t0) / dt;
    const double h00 = (2 * sv - 3) * sv * sv + 1, h10 = ((sv - 2) * sv + 1) * sv, h01 = (3 - 2 * sv) * sv * sv,
                 h11 = (sv - 1) * sv * sv;
    const double *y0 = h->y + (size_t)lo * (size_t)h->dim, *y1 = y0 + h->dim;
    const double *d0 = h->yp + (size_t)lo * (size_t)h->dim, *d1 = d0 + h->dim;
    for (int c = 0; c < h->dim; c++) out[c] = h00 * y0[c] + h10 * dt * d0[c] + h01 * y1[c] + h11 * dt * d1[c];
}

/* recoverable refusals of trial states allowed between two outputs (or in one step of a run
 * that keeps its history) before the run ends with the last one */
#define VT_REFUSALS_MAX 100

/* The drives' functions at t (they depend on t alone): VT_OK, or the first failure with a
 * message naming the drive. */
static vt_status drive_functions(const vt_model *m, double t, char *msg, size_t size)
{
    for (int k = 0; k < m->ndrive; k++) {
        const vt_drive_def *dr = &m->drive[k];
        const char *name = m->drive_name ? m->drive_name + (size_t)VT_NAME_MAX * (size_t)k : "";
        double v[3], p[4], w[3], wd[3];
        vt_status st = VT_OK;
        if (vt_drive_turns(dr->type) && dr->orientation_callback) {
            if (dr->orientation_callback(t, p, w, wd, dr->user) != 0) st = VT_ERR_CALLBACK;
            else if (!vt_all_finite(p, 4) || !vt_all_finite(w, 3) || !vt_all_finite(wd, 3)) st = VT_ERR_NONFINITE;
            if (st) {
                snprintf(msg, size, "drive %d%s%s: orientation callback %s at t = %.17g", k, name[0] ? " " : "", name,
                         st == VT_ERR_CALLBACK ? "failed" : "returned NaN or Inf", t);
                return st;
            }
        } else {
            const vt_function *fs[3];
            const int nf = vt_drive_functions(dr, fs);
            for (int e = 0; e < nf; e++)
                if ((st = vt_function_eval_valid(v, fs[e], t))) {
                    snprintf(msg, size, "drive %d%s%s: time function %s%s at t = %.17g", k, name[0] ? " " : "", name,
                             e == 0 ? "" : e == 1 ? "f2 " : "f3 ",
                             st == VT_ERR_CALLBACK ? "failed" : st == VT_ERR_NONFINITE ? "returned NaN or Inf" : "failed",
                             t);
                    return st;
                }
        }
    }
    return VT_OK;
}

/* A stage refused (t, y) with status st and the message in msg: kept for the report. Fatal
 * (< 0) if the user's functions fail at t, or after VT_REFUSALS_MAX refusals; else recoverable
 * (> 0): IDA retries with a smaller step. */
static int refused(vt_dae *p, vt_status st, const char *msg, double t)
{
    const vt_model *drv = p->dk ? p->dk->model : p->m; /* the driven model: the drives are its */
    const vt_status user = drv ? drive_functions(drv, t, p->s.msg, sizeof p->s.msg) : VT_OK;
    p->s.t = t;
    if (user) {
        p->s.why = user;
        p->s.fatal = 1;
        return -1;
    }
    p->s.why = st ? st : VT_ERR_IDA;
    snprintf(p->s.msg, sizeof p->s.msg, "%s", msg);
    if (++p->s.refusals > VT_REFUSALS_MAX) {
        p->s.fatal = 2;
        return -1;
    }
    return 1;
}

/* before each IDASolve call: no refusal yet */
void vt_dae_fresh(vt_dae *p)
{
    p->s.why = VT_OK;
    p->s.fatal = 0;
    p->s.refusals = 0;
}

/* [q; v], [q; v; λ] (index-1, Baumgarte, projection) or [q; v; λ; μ] (GGL) */
int vt_dae_block_size(const vt_model *m, int form)
{
    if (form == VT_FORMULATION_ODE) return m->nq + m->nv;
    return m->nq + m->nv + (form == VT_FORMULATION_GGL ? 2 : 1) * m->nc;
}

/* q' = T(q) v */
static void qdot_from_v(const vt_model *m, const double *q, const double *v, double *qd)
{
    for (int i = 1; i <= m->nbody; i++) {
        const int qa = m->body_qadr[i], va = m->body_vadr[i];
        const int jt = m->body_joint[i];
        if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_FREE) { /* free: ṫ' = its rates, then as spherical */
            const int o = jt == VT_JOINT_FREE ? 3 : 0;
            double E[12];
            for (int k = 0; k < o; k++) qd[qa + k] = v[va + k];
            vt_euler_E(E, q + qa + o);
            vt_mulE_t(qd + qa + o, E, v + va + o);
            for (int k = 0; k < 4; k++) qd[qa + o + k] *= 0.5;
        } else {
            for (int k = 0; k < m->body_nq[i]; k++) qd[qa + k] = v[va + k];
        }
    }
}

/* The residual of one model's block; p gives the formulation:
 *   index-1 (and projection)  q' − T v,          M* v' − Q − Φ_q^T λ,   Φ_q v' − γ
 *   Baumgarte                 q' − T v,          M* v' − Q − Φ_q^T λ,   Φ_q v' − γ + 2α Φ̇ + β² Φ
 *   GGL (index 2)             q' − T (v + Φ_q^T μ), M* v' − Q − Φ_q^T λ,   Φ,   Φ_q v + Φ_t
 *   ODE                       q' − T v,          v' − q̈   with q̈ from vt_solve, γ − 2α Φ̇ − β² Φ
 * with Φ̇ = Φ_q v + Φ_t; λ (and μ) algebraic. */
static vt_status block_residual(const vt_dae *p, const vt_model *m, vt_data *d, double t, const double *y,
                                const double *yp, double *r)
{
    const int nq = m->nq, nv = m->nv, nc = m->nc, ggl = p->form == VT_FORMULATION_GGL;
    memcpy(d->q, y, (size_t)nq * sizeof(double));
    memcpy(d->qd, y + nq, (size_t)nv * sizeof(double));
    d->time = t;
    vt_status st;
    if ((st = vt_kinematics(m, d)) || (st = vt_mass_matrix(m, d)) || (st = vt_forces(m, d)) ||
        (st = vt_constraints(m, d)))
        return st;
    if (p->form == VT_FORMULATION_ODE) { /* q' − T q̇, q̇' − q̈(q, q̇, t) with γ − 2α Φ̇ − β² Φ */
        const double a2 = 2.0 * p->alpha, b2 = p->beta * p->beta;
        for (int k = 0; k < nc; k++) {
            double phid = d->Phit[k];
            for (int c = 0; c < nv; c++) phid += d->Phiq[k + (size_t)c * (size_t)nc] * y[nq + c];
            d->gamma[k] -= a2 * phid + b2 * d->Phi[k];
        }
        if ((st = vt_solve_run(m, d, p->band))) return st;
        qdot_from_v(m, y, y + nq, r);
        for (int k = 0; k < nq; k++) r[k] = yp[k] - r[k];
        for (int k = 0; k < nv; k++) r[nq + k] = yp[nq + k] - d->qdd[k];
        return vt_all_finite(r, nq + nv) ? VT_OK
                                         : vt_fail(d->message, VT_ERR_NONFINITE, "the residual at t = %.10g is not finite", t);
    }
    const double *qp = yp, *vp = yp + nq, *lam = y + nq + nv;
    double *rq = r, *rv = r + nq, *rl = r + nq + nv;
    if (ggl && nc > 0) { /* T (v + Φ_q^T μ) */
        double *w = p->w;
        memcpy(w, y + nq, (size_t)nv * sizeof(double));
        vt_dgemv('T', nc, nv, 1.0, d->Phiq, nc, lam + nc, 1, 1.0, w, 1);
        qdot_from_v(m, y, w, rq);
    } else {
        qdot_from_v(m, y, y + nq, rq);
    }
    for (int k = 0; k < nq; k++) rq[k] = qp[k] - rq[k];
    vt_dgemv('N', nv, nv, 1.0, d->Mstar, nv, vp, 1, 0.0, rv, 1);
    for (int k = 0; k < nv; k++) rv[k] -= d->Q[k];
    if (nc > 0) {
        vt_dgemv('T', nc, nv, -1.0, d->Phiq, nc, lam, 1, 1.0, rv, 1);
        if (ggl) {
            double *rm = rl + nc;
            memcpy(rl, d->Phi, (size_t)nc * sizeof(double));
            memcpy(rm, d->Phit, (size_t)nc * sizeof(double));
            vt_dgemv('N', nc, nv, 1.0, d->Phiq, nc, y + nq, 1, 1.0, rm, 1);
        } else {
            vt_dgemv('N', nc, nv, 1.0, d->Phiq, nc, vp, 1, 0.0, rl, 1);
            for (int k = 0; k < nc; k++) rl[k] -= d->gamma[k];
            if (p->form == VT_FORMULATION_BAUMGARTE) {
                const double a2 = 2.0 * p->alpha, b2 = p->beta * p->beta;
                for (int k = 0; k < nc; k++) rl[k] += a2 * d->Phit[k] + b2 * d->Phi[k];
                vt_dgemv('N', nc, nv, a2, d->Phiq, nc, y + nq, 1, 1.0, rl, 1);
            }
        }
    }
    return vt_all_finite(r, vt_dae_block_size(m, p->form))
               ? VT_OK
               : vt_fail(d->message, VT_ERR_NONFINITE, "the residual at t = %.10g is not finite", t);
}

/* The residual of a block without constraint rows (a tree: the forward model of most
 * mechanisms), q' − T v and M* v' − Q, by one recursive pass: M* v' − Q is the effort
 * s · W̄ − qfrc that the motion v' needs (vt_inverse_dynamics_motion, O(n)), neither M* nor Q
 * formed; the loads already in d */
static vt_status motion_residual(const vt_model *m, vt_data *d, double t, const double *y, const double *yp, double *r)
{
    const int nq = m->nq, nv = m->nv;
    memcpy(d->q, y, (size_t)nq * sizeof(double));
    memcpy(d->qd, y + nq, (size_t)nv * sizeof(double));
    memcpy(d->qdd, yp + nq, (size_t)nv * sizeof(double));
    d->time = t;
    const vt_status st = vt_inverse_dynamics_motion(m, d);
    if (st) return st;
    qdot_from_v(m, y, y + nq, r);
    for (int k = 0; k < nq; k++) r[k] = yp[k] - r[k];
    memcpy(r + nq, d->qfrc_drive, (size_t)nv * sizeof(double));
    return vt_all_finite(r, nq + nv) ? VT_OK : vt_fail(d->message, VT_ERR_NONFINITE, "the residual at t = %.10g is not finite", t);
}

/* The drives' exact efforts at t into dk: the kinematic solution at t by Newton from the analysis's
 * two rows around t interpolated (vt_kinematic_start: at mid-interval often within newton_tol
 * already, so that the solve is one evaluation of Φ and Φ_q, the velocities' solve and the
 * instant), or, should Newton fail from there, from the nearer row itself */
static vt_status exact_efforts(const vt_dae *p, const vt_model *m, double t)
{
    const vt_trajectory *tr = p->s.rows;
    vt_data *dk = p->dk;
    int lo = 0, hi = tr->nfilled - 1; /* t[lo] ≤ t < t[hi], or the last two rows */
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (tr->t[mid] <= t) lo = mid;
        else hi = mid;
    }
    const int near = t - tr->t[lo] <= tr->t[hi] - t ? lo : hi, far = near == lo ? hi : lo;
    int third = -1; /* the next row out on either side, the nearer one */
    if (lo > 0 && (hi + 1 >= tr->nfilled || t - tr->t[lo - 1] <= tr->t[hi + 1] - t)) third = lo - 1;
    else if (hi + 1 < tr->nfilled) third = hi + 1;
    if (far == near) third = -1;
    vt_status st = vt_kinematic_start(m, dk, tr, near, far == near ? -1 : far, third);
    if (!st) st = vt_kinematic_solve_impl(m, dk, p->newton_tol, p->newton_maxit, VT_SOLVE_RECURSIVE_NO_TOTALS | VT_SOLVE_POLISH, NULL, NULL, 0.0);
    if (st == VT_ERR_NEWTON) {
        memcpy(dk->q, tr->q + (size_t)near * (size_t)m->nq, (size_t)m->nq * sizeof(double));
        memcpy(dk->qd, tr->qd + (size_t)near * (size_t)m->nv, (size_t)m->nv * sizeof(double));
        st = vt_kinematic_solve_impl(m, dk, p->newton_tol, p->newton_maxit, VT_SOLVE_RECURSIVE_NO_TOTALS | VT_SOLVE_POLISH, NULL, NULL, 0.0);
    }
    if (!st && p->run) st = vt_run_loads(m, dk, p->run, p->base, NULL, NULL, p->as_loads, "forward check");
    return st;
}

vt_status vt_dae_driven_at(const vt_dae *p, const vt_model *m, double t)
{
    vt_dae_hermite(p->src, t, p->src->tmp);
    memcpy(p->dk->q, p->src->tmp, (size_t)m->nq * sizeof(double));
    memcpy(p->dk->qd, p->src->tmp + m->nq, (size_t)m->nv * sizeof(double));
    p->dk->time = t;
    return vt_inverse_dynamics(m, p->dk);
}

/* At an output time the drives' efforts are row k of the analysis (stored at exactly that time):
 * what vt_apply_drive_loads reads, copied into dk */
vt_status vt_dae_row_efforts(const vt_dae *p, const vt_model *m, int k)
{
    const vt_trajectory *tr = p->s.rows;
    vt_data *dk = p->dk;
    const size_t r = (size_t)k, nv = (size_t)m->nv, nd = (size_t)m->ndrive, D = sizeof(double);
    memcpy(dk->q, tr->q + r * (size_t)m->nq, (size_t)m->nq * D);
    memcpy(dk->qd, tr->qd + r * nv, nv * D);
    memcpy(dk->qdd, tr->qdd + r * nv, nv * D);
    memcpy(dk->lambda, tr->lambda + r * (size_t)m->nc, (size_t)m->nc * D);
    memcpy(dk->qfrc_drive, tr->qfrc_drive + r * nv, nv * D);
    memcpy(dk->drive_effort, tr->drive_effort + r * nd, nd * D);
    memcpy(dk->drive_force, tr->drive_force + 3 * r * nd, 3 * nd * D);
    memcpy(dk->drive_moment, tr->drive_moment + 3 * r * nd, 3 * nd * D);
    dk->time = tr->t[k];
    /* with loads at frames or on contacts the loads too, which the row keeps as forces: both formed
     * at the row's state (the frames' at its poses, formed here: the row keeps none) */
    if (!p->run) return VT_OK;
    vt_status st = p->run->nload > 0 ? vt_kinematics_tree(m, dk, 0) : VT_OK;
    return st ? st : vt_run_loads(m, dk, p->run, p->base, NULL, NULL, p->as_loads, "forward check");
}

/* y_ref, y'_ref of one block at a state in d: [q; v; 0], [T(q) v; q̈; 0] */
void vt_dae_block_reference(const vt_model *m, const vt_data *d, int n, double *yr, double *ypr)
{
    const int nq = m->nq, nv = m->nv;
    memcpy(yr, d->q, (size_t)nq * sizeof(double));
    memcpy(yr + nq, d->qd, (size_t)nv * sizeof(double));
    memset(yr + nq + nv, 0, (size_t)(n - nq - nv) * sizeof(double));
    qdot_from_v(m, d->q, d->qd, ypr);
    memcpy(ypr + nq, d->qdd, (size_t)nv * sizeof(double));
    memset(ypr + nq + nv, 0, (size_t)(n - nq - nv) * sizeof(double));
}

/* the exact efforts at t in dk (IDA's iterations and Jacobian at one t reuse them), and the
 * reference motion there */
static vt_status reference(vt_dae *p, const vt_model *m, double t)
{
    if (p->s.dk_valid && p->dk->time == t) return VT_OK;
    p->dk->time = t;
    p->s.dk_valid = 0;
    const vt_status st = exact_efforts(p, m, t);
    if (st) return st;
    p->s.dk_valid = 1;
    if (p->s.ref) {
        const int n = vt_dae_block_size(p->mf, p->form);
        vt_dae_block_reference(m, p->dk, n, p->s.ref, p->s.ref + n);
    }
    return VT_OK;
}

/* F(t, y, y') of every block in p (IDA's residual function): the driven block, then the forward
 * block under the drives' efforts (from the driven λ, the interpolated driven run or exact); a
 * stage's refusal through refused() */
int vt_dae_residual(sunrealtype t, N_Vector yy, N_Vector yyp, N_Vector rr, void *user)
{
    vt_dae *p = user;
    const double *y = N_VGetArrayPointer(yy), *yp = N_VGetArrayPointer(yyp);
    double *r = N_VGetArrayPointer(rr);
    vt_status st;
    if (p->m && (st = block_residual(p, p->m, p->d, t, y, yp, r))) return refused(p, st, p->d->message, t);
    if (!p->mf) return 0;
    const vt_model *m = p->dk ? p->dk->model : p->m;
    vt_data *src = p->dk ? p->dk : p->d;
    if (p->src) { /* the driven run's state at t, interpolated, and its efforts */
        if ((st = vt_dae_driven_at(p, m, t))) return refused(p, st, p->dk->message, t);
    } else if (p->dk) {
        if ((st = reference(p, m, t))) return refused(p, st, p->dk->message, t);
        if (p->s.ref) { /* IDA's unknowns are the deviation e from the reference: y = y_ref + e */
            const int n = vt_dae_block_size(p->mf, p->form);
            double *yf = p->s.ref + 2 * (size_t)n, *ypf = yf + n;
            for (int k = 0; k < n; k++) {
                yf[k] = p->s.ref[k] + y[k];
                ypf[k] = p->s.ref[n + k] + yp[k];
            }
            y = yf;
            yp = ypf;
        }
    } else { /* the efforts of the driven block's current λ */
        /* (the ODE form has no λ in y: its residual's vt_solve left them in d already) */
        if (p->form != VT_FORMULATION_ODE) memcpy(p->d->lambda, y + m->nq + m->nv, (size_t)m->nc * sizeof(double));
        if ((st = vt_drive_efforts(m, p->d))) return refused(p, st, p->d->message, t);
    }
    /* the forward block's positions first: body drives' loads act at its body points (joint
     * torques, the default, need none) */
    memcpy(p->df->q, y + p->nd, (size_t)p->mf->nq * sizeof(double));
    memcpy(p->df->qd, y + p->nd + p->mf->nq, (size_t)p->mf->nv * sizeof(double));
    if (p->as_loads && (st = vt_kinematics_tree(p->mf, p->df, 0))) return refused(p, st, p->df->message, t);
    vt_apply_drive_loads(p->mf, p->df, m, src, p->xfrc0, p->as_loads);
    st = p->s.motion ? motion_residual(p->mf, p->df, t, y + p->nd, yp + p->nd, r + p->nd)
                   : block_residual(p, p->mf, p->df, t, y + p->nd, yp + p->nd, r + p->nd);
    return st ? refused(p, st, p->df->message, t) : 0;
}

/* J = ∂F/∂y + c_j ∂F/∂y' by IDA's dense difference quotient (see the top of the file), in IDA's
 * matrix, with tmp1 for the perturbed residual and tmp2 for the weights: nothing allocated */
int vt_dae_jacobian(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yyp, N_Vector rr, SUNMatrix J, void *user,
                    N_Vector tmp1, N_Vector tmp2, N_Vector tmp3)
{
    vt_dae *p = user;
    (void)tmp3;
    if (p->s.ref) { /* (the reference at t: the residual's at t, unless IDA evaluated another t since) */
        const vt_status st = reference(p, p->dk->model, t);
        if (st) return refused(p, st, p->dk->message, t);
    }
    double h = 0.0;
    if (IDAGetCurrentStep(p->s.ida, &h) < 0 || IDAGetErrWeights(p->s.ida, tmp2) < 0) return -1;
    double *y = N_VGetArrayPointer(yy), *yp = N_VGetArrayPointer(yyp);
    const double *r = N_VGetArrayPointer(rr), *rj = N_VGetArrayPointer(tmp1), *w = N_VGetArrayPointer(tmp2);
    const double srur = sqrt(DBL_EPSILON);
    const sunindextype n = SUNDenseMatrix_Columns(J);
    /* with the deviation as unknowns the increments are those of y = y_ref + e: round-off is
     * relative to y, not to e */
    const double *yr = p->s.ref, *ypr = p->s.ref ? p->s.ref + n : NULL;
    for (sunindextype j = 0; j < n; j++) {
        const double yj = y[j], ypj = yp[j];
        const double ya = yr ? yr[j] + yj : yj, ypa = ypr ? ypr[j] + ypj : ypj;
        double inc = fmax(srur * fmax(fabs(ya), fabs(h * ypa)), 1.0 / w[j]);
        if (h * ypa < 0.0) inc = -inc;
        inc = (yj + inc) - yj; /* the increment as represented */
        y[j] += inc;
        yp[j] += cj * inc;
        const int res = vt_dae_residual(t, yy, yyp, tmp1, p);
        y[j] = yj;
        yp[j] = ypj;
        if (res) return res;
        const double s = 1.0 / inc;
        double *col = SUNDenseMatrix_Column(J, j);
        for (sunindextype i = 0; i < n; i++) col[i] = s * (rj[i] - r[i]);
    }
    return 0;
}

/* The error weights of the deviation e are those IDA would give y = y_ref + e: the tolerances
 * keep their meaning (rtol relative to the state), and e's round-off, which is relative to y,
 * stays far below them whatever atol (weights of e alone, 1 / (rtol |e| + atol), would make IDA
 * chase that round-off once atol nears ε |y|). y_ref is the one last taken, within a step of
 * IDA's current time: weights are scales, and a fresh exact solution for them would cost as
 * much as a step's efforts */
int vt_dae_deviation_weights(N_Vector yy, N_Vector ewt, void *user)
{
    const vt_dae *p = user;
    const double *y = N_VGetArrayPointer(yy);
    double *w = N_VGetArrayPointer(ewt);
    const sunindextype n = N_VGetLength(yy);
    for (sunindextype k = 0; k < n; k++) w[k] = 1.0 / (p->s.rtol * fabs(p->s.ref[k] + y[k]) + p->s.atol[k]);
    return 0;
}

/* IDA's error handler: its message into p->msg->message (a failed call's report quotes it) */
void vt_dae_ida_error(int code, const char *module, const char *function, char *msg, void *user)
{
    vt_dae *p = user;
    (void)module;
    snprintf(p->msg->message, sizeof p->msg->message, "IDA %s (%d): %s", function, code, msg);
}

/* y and y' of one block at a consistent state in d: [q; v; λ (; μ = 0)], [T(q) v; q̈; 0] */
void vt_dae_block_initial(const vt_model *m, const vt_data *d, int form, double *y, double *yp)
{
    const int nq = m->nq, nv = m->nv, nc = m->nc, na = vt_dae_block_size(m, form) - nq - nv;
    memcpy(y, d->q, (size_t)nq * sizeof(double));
    memcpy(y + nq, d->qd, (size_t)nv * sizeof(double));
    memset(y + nq + nv, 0, (size_t)na * sizeof(double));
    if (na >= nc) memcpy(y + nq + nv, d->lambda, (size_t)nc * sizeof(double));
    qdot_from_v(m, d->q, d->qd, yp);
    memcpy(yp + nq, d->qdd, (size_t)nv * sizeof(double));
    memset(yp + nq + nv, 0, (size_t)na * sizeof(double));
}

/* 1: differential (q, v), 0: algebraic (λ, μ) */
void vt_dae_block_ids(const vt_model *m, int form, double *id)
{
    const int nd = m->nq + m->nv, n = vt_dae_block_size(m, form);
    for (int k = 0; k < n; k++) id[k] = k < nd ? 1.0 : 0.0;
}

/* coordinate projection of a block of y onto Φ = 0 and Φ_q v = −Φ_t (least-norm corrections,
 * vt_kinematic_solve), with y' and λ made consistent again; nonzero on failure */
vt_status vt_dae_block_project(const vt_dae *p, const vt_model *m, vt_data *d, double t, double *y, double *yp)
{
    memcpy(d->q, y, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, y + m->nq, (size_t)m->nv * sizeof(double));
    d->time = t;
    const vt_status st = vt_kinematic_solve(m, d, p->newton_tol, p->newton_maxit);
    if (st) return st;
    vt_dae_block_initial(m, d, p->form, y, yp);
    return VT_OK;
}

/* the state of a block of y into its data, then the whole instant (efforts, reactions), its
 * solve with the residual's band */
vt_status vt_dae_block_output(const vt_model *m, vt_data *d, double t, const double *y, double band)
{
    memcpy(d->q, y, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, y + m->nq, (size_t)m->nv * sizeof(double));
    d->time = t;
    vt_status st;
    if ((st = vt_kinematics(m, d)) || (st = vt_mass_matrix(m, d)) || (st = vt_forces(m, d)) ||
        (st = vt_constraints(m, d)) || (st = vt_solve_run(m, d, band)))
        return st;
    return vt_reactions(m, d);
}
