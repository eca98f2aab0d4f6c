/* Actuating efforts and joint reactions: the paper's (24)-(28) and docs/method.md "Joint
 * reactions".
 *
 * The Cartesian force of constraint row r on body k is Φ_{x^k}^T λ_r; written as a force f and
 * a moment n about the centre of mass, [f; 2 E^T n] (24), so f = Φ_r^T λ and n = ½ E Φ_p^T λ
 * (E E^T = I). A drive's effort is the sum over its rows, moved to the drive's point.
 *
 * Body i obeys M^i ẍ^i = F_d^i + F_r^i + F_e^i + h^i (25) with ẍ = S q̈ + Ṡ q̇. Premultiplied by
 * diag(I, ½E) that is Newton–Euler about the centre of mass:
 *   m a = f_e + f_d + f_i − Σ_c f_c
 *   J α + ω̃ J ω = n_e + n_d + n_i + (P_i − r_i) × f_i − Σ_c [n_c + (P_c − r_i) × f_c]
 * where (f_i, n_i) is the reaction of the reference body on body i at its joint point P_i and
 * c runs over i's children (26). Inward from the tree's ends (bodies counted down) each
 * reaction is what remains once inertia, applied forces, efforts and the children's
 * reactions are balanced; it is then added into the parent. Reported in global axes and in
 * the body's axes, f' = A^T f, n' = A^T n (27)-(28). The drives' efforts are among the
 * applied forces, never inside the reactions: a revolute reaction moment has no axial part.
 * Summed over the subtree below joint i instead of counted down body by body, the same balance
 * reads: reaction = W̄_i − G_i, with W̄_i the subtree's needed wrench about o = d->origin (inertia
 * less gravity and applied loads) and G_i its rows' and generalized forces' wrenches, the
 * moment then moved to P_i; the recursive paths have W̄ already (vt_reactions_subtree).
 *
 * In each joint's frame (vt_model.jnt_frame, rotation C from the frame to the body's axes) and
 * split along its unit bearing axis a (in that frame; 0 for a joint without one), for every
 * path once its body-axes reactions are formed (vt_joint_frames):
 *   f_J = C^T f',  n_J = C^T n',  [a · f_J, |f_J − (a · f_J) a|, a · n_J, |n_J − (a · n_J) a|].
 * Limits (vt_model.dof_limit) against each rate's q, q̇ and effort Φ_q^T λ (vt_limits_flag,
 * vt_rate_limits in reactions.h):
 *   excess = x − hi where x > hi, x − lo where x < lo, else 0.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dense/reactions.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/v4.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/inverse_transform.h"
#include "kinematics/joint_effects.h"
#include "kinematics/body.h"
#include "kinematics/kinematics.h"
#include "numeric/roundoff.h"
#include "numeric/route.h"
#include "model/builder.h"

/* Every row's wrench on its two bodies for the multipliers lam (each 1 when lam is NULL), about
 * each body's centre of mass, [f_a n_a f_b n_b] into rw (12 x nc); the ground's side and the
 * normalization rows of base bodies (their moment ½ E (2 p λ) is zero) are zero. */
void vt_row_wrenches(double *rw, const vt_model *m, const vt_data *d, const double *lam)
{
    for (int r = 0; r < m->nc; r++)
        for (int side = 0; side < 2; side++) {
            const int k = m->con_body[2 * r + side];
            double *f = rw + 12 * r + 6 * side, *n = f + 3, t[4];
            if (k == 0 || m->con_kind[r] == VT_ROW_NORM) {
                memset(f, 0, 6 * sizeof(double));
                continue;
            }
            const double *px = d->Phix + 14 * r + 7 * side, l = lam ? lam[r] : 1.0;
            for (int c = 0; c < 3; c++) f[c] = px[c] * l;
            for (int c = 0; c < 4; c++) t[c] = 0.5 * px[3 + c] * l;
            vt_mulEp(n, d->x + vt_xoff(k) + 3, t);
        }
}

/* sum of the wrenches rw of rows [r0, r1) on side `side`, moved to the point P of their body,
 * s = P − r (from the body's own vectors: exact far from o) */
static void rows_wrench_at(const double *rw, int r0, int r1, int side, const double s[3], double f[3], double n[3])
{
    double t[3];
    memset(f, 0, 3 * sizeof(double));
    memset(n, 0, 3 * sizeof(double));
    if (r0 >= r1) return;
    for (int r = r0; r < r1; r++) {
        vt_axpy3(f, 1.0, rw + 12 * r + 6 * side);
        vt_axpy3(n, 1.0, rw + 12 * r + 6 * side + 3);
    }
    vt_cross3(t, s, f);
    for (int c = 0; c < 3; c++) n[c] -= t[c];
}

/* every drive and cut-joint row's wrench rw on its bodies, added into fe (6 x (nbody+1)) */
static void add_row_wrenches(const vt_model *m, const double *rw, double *fe)
{
    for (int r = 0; r < m->nc; r++)
        for (int side = 0; side < 2; side++) {
            const int k = m->con_body[2 * r + side];
            if (k == 0) continue;
            vt_axpy3(fe + 6 * k, 1.0, rw + 12 * r + 6 * side);
            vt_axpy3(fe + 6 * k + 3, 1.0, rw + 12 * r + 6 * side + 3);
        }
}

/* The drives' efforts (24) from d->lambda: each drive's force and moment on its body at the
 * drive's point, its effort along its coordinate or component, and Φ_q^T λ over the drives.
 * rw: the rows' wrenches at λ (vt_row_wrenches). */
static void drive_efforts(const vt_model *m, vt_data *d, const double *rw)
{
    for (int k = 0; k < m->ndrive; k++) {
        const vt_drive_def *dr = &m->drive[k];
        const int r0 = m->drive_row[k], b = dr->body;
        double s[3] = {0, 0, 0}; /* the drive's point from the body's centre of mass */
        if (dr->type == VT_DRIVE_JOINT) vt_joint_child(s, m, d, b);
        else if (dr->type == VT_DRIVE_POINT) vt_mulmat3(s, d->A + 9 * b, dr->point);
        rows_wrench_at(rw, r0, r0 + vt_drive_nrows(dr), 1, s, d->drive_force + 3 * k, d->drive_moment + 3 * k);
        d->drive_effort[k] = vt_drive_turns(dr->type) ? 0.0 : d->lambda[r0];
    }

    /* the drives' generalized force Φ_q^T λ over their rows */
    memset(d->qfrc_drive, 0, (size_t)m->nv * sizeof(double));
    for (int r = 0; r < vt_drive_rows(m); r++)
        for (int c = 0; c < m->nv; c++) d->qfrc_drive[c] += d->Phiq[r + (size_t)c * (size_t)m->nc] * d->lambda[r];
}

vt_status vt_drive_efforts(const vt_model *m, vt_data *d)
{
    const size_t mark = vt_scratch_mark(d);
    double *rw = VT_SCRATCH(d, double, 12 * (size_t)m->nc, "rows' wrenches");
    if (!rw) return vt_scratch_fail(d, mark);
    vt_row_wrenches(rw, m, d, d->lambda);
    drive_efforts(m, d, rw);
    vt_scratch_release(d, mark);
    return VT_OK;
}

/* The forward check's loads on the model without drives, on top of the applied loads xfrc0 and
 * d's applied generalized forces qfrc:
 * as_loads = 0: the drives' generalized force Φ_q^T λ (joint torques and forces, the paper's
 * Figs. 6-8 and 10); as_loads = 1: each drive's own load — a joint drive's effort on its
 * coordinate, a body drive's force and moment at the same body point. */
void vt_apply_drive_loads(const vt_model *mf, vt_data *df, const vt_model *m, const vt_data *d, const double *xfrc0,
                          int as_loads)
{
    memcpy(df->xfrc, xfrc0, 6 * ((size_t)mf->nbody + 1) * sizeof(double));
    /* the applied generalized forces stay applied (d's: the caller's) */
    if (!as_loads) {
        for (int c = 0; c < mf->nv; c++) df->qfrc[c] = d->qfrc[c] + d->qfrc_drive[c];
        return;
    }
    memcpy(df->qfrc, d->qfrc, (size_t)mf->nv * sizeof(double));
    for (int k = 0; k < m->ndrive; k++) {
        const vt_drive_def *dr = &m->drive[k];
        const int b = dr->body;
        const double *f = d->drive_force + 3 * k, *n = d->drive_moment + 3 * k;
        if (dr->type == VT_DRIVE_JOINT) {
            df->qfrc[mf->body_vadr[b] + dr->index] += d->drive_effort[k];
            continue;
        }
        double s[3] = {0, 0, 0};
        if (dr->type == VT_DRIVE_POINT) vt_mulmat3(s, df->A + 9 * b, dr->point);
        double *w = df->xfrc + 6 * b;
        vt_axpy3(w, 1.0, f);
        vt_axpy3(w + 3, 1.0, n);
        vt_addcross3(w + 3, s, f);
        if (dr->type == VT_DRIVE_RELATIVE_ORIENTATION && dr->reference > 0) /* a pure moment: its opposite on a */
            vt_axpy3(df->xfrc + 6 * dr->reference + 3, -1.0, n);
    }
}

vt_status vt_reactions(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_reactions");
    if (st) return st;
    if ((st = vt_reactions_impl(m, d, VT_FORM_DENSE))) return st;
    return vt_reactions_total(m, d, 0);
}

/* Into fe (6 x (nbody+1), added, about each body's centre of mass) the applied generalized
 * forces' wrenches. An applied generalized force acts between a joint's two bodies: its
 * Cartesian form is R^T qfrc (14), on the body [f; 2 E^T n] and on its reference body the rest
 * of the row. */
static void rate_load(const vt_model *m, const vt_data *d, int c, double g, double *fe)
{
    const int i = m->dof_body[c], j = m->body_parent[i];
    double rj[7], ri[7];
    vt_R_row(m, d, c, rj, ri);
    for (int side = 0; side < 2; side++) {
        const int k = side ? i : j;
        const double *row = side ? ri : rj;
        if (k == 0) continue;
        double E[12], t4[4], nn[3];
        vt_euler_E(E, d->x + vt_xoff(k) + 3);
        for (int e = 0; e < 4; e++) t4[e] = 0.5 * row[3 + e] * g;
        vt_mulE(nn, E, t4);
        vt_axpy3(fe + 6 * k, g, row);
        vt_axpy3(fe + 6 * k + 3, 1.0, nn);
    }
}

static void qfrc_loads(const vt_model *m, vt_data *d, double *fe)
{
    for (int c = 0; c < m->nv; c++) {
        const double g = vt_rate_load(m, d, c); /* qfrc less the joint's own effects */
        if (g != 0.0) rate_load(m, d, c, g, fe);
    }
}

/* the couplings' generalized forces for the multipliers lam (nc), λ on rate a and −ratio λ on
 * rate b, as wrenches on the joints' bodies into fe, as qfrc_loads (a coupling's row has no
 * Φ_x: it acts through the rates) */
static void coupling_loads(const vt_model *m, const vt_data *d, const double *lam, double *fe)
{
    for (int k = 0; k < m->ncoupling; k++) {
        const vt_coupling_def *c = &m->coupling[k];
        const double l = lam[m->coupling_row[k]];
        if (l == 0.0) continue;
        rate_load(m, d, m->body_vadr[c->body_a] + c->index_a, l, fe);
        rate_load(m, d, m->body_vadr[c->body_b] + c->index_b, -c->ratio * l, fe);
    }
}

/* The drives' efforts and the cut joints' reactions from the rows' wrenches rw (vt_row_wrenches
 * at λ), checked */
static vt_status row_efforts(const vt_model *m, vt_data *d, const double *rw)
{
    drive_efforts(m, d, rw);

    /* cut joints: the rows' wrench on body_b, at its joint point */
    for (int k = 0; k < m->ncut; k++) {
        const vt_cut_joint_def *c = &m->cut[k];
        const int r0 = m->cut_row[k];
        const int rend = r0 + vt_cut_nrows(c);
        double s[3];
        vt_mulmat3(s, d->A + 9 * c->body_b, c->point_b);
        double *f = d->cut_force + 3 * k, *mo = d->cut_moment + 3 * k;
        rows_wrench_at(rw, r0, rend, 1, s, f, mo);
        vt_mulmat3t(d->cut_force_body + 3 * k, d->A + 9 * c->body_b, f);
        vt_mulmat3t(d->cut_moment_body + 3 * k, d->A + 9 * c->body_b, mo);
    }

    for (int k = 0; k < m->ncoupling; k++) d->coupling_effort[k] = d->lambda[m->coupling_row[k]];
    vt_finite_scan fs = {0}; /* as one scan: one test at the end */
    vt_finite_add(&fs, d->coupling_effort, m->ncoupling);
    vt_finite_add(&fs, d->drive_force, 3 * m->ndrive);
    vt_finite_add(&fs, d->drive_moment, 3 * m->ndrive);
    vt_finite_add(&fs, d->qfrc_drive, m->nv);
    vt_finite_add(&fs, d->cut_force, 3 * m->ncut);
    vt_finite_add(&fs, d->cut_moment, 3 * m->ncut);
    if (!vt_finite_ok(&fs))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_reactions: an effort overflowed (an ill-posed instant?)");
    return VT_OK;
}

/* Into fe (6 x (nbody+1), added, about each body's centre of mass): every drive and cut-joint
 * row's wrench (normalization rows of base bodies exert nothing: their moment ½ E (2 p λ) is
 * zero) and the applied generalized forces'; on the way, the drives' efforts and the cut
 * joints' reactions. rw: scratch for the rows' wrenches (12 x nc). */
static vt_status row_loads(const vt_model *m, vt_data *d, double *fe, double *rw)
{
    qfrc_loads(m, d, fe);
    vt_row_wrenches(rw, m, d, d->lambda);
    add_row_wrenches(m, rw, fe);
    coupling_loads(m, d, d->lambda, fe);
    return row_efforts(m, d, rw);
}

/* Limits (vt_model.dof_limit: lower, upper, |q̇| max, |effort| max per rate), compared strictly:
 *   e_q = q − upper if q > upper, q − lower if q < lower, else 0 (scalar coordinates only),
 *   e_v = q̇ − v if q̇ > v, q̇ + v if q̇ < −v, else 0, the same for the effort with its limit;
 * the difference of two doubles that differ is never 0 (gradual underflow), so a value one ulp
 * beyond is flagged and one at the limit is not. Infinite limits are never passed by finite values. */

void vt_joint_frames(const vt_model *m, vt_data *d, int bearing)
{
    for (int i = 1; i <= m->nbody; i++) {
        const double *C = m->jnt_frame_A + 9 * i;
        double fj[3], mj[3];
        vt_mulmat3t(fj, C, d->jnt_force_body + 3 * i);
        vt_mulmat3t(mj, C, d->jnt_moment_body + 3 * i);
        vt_copy3(d->jnt_force_joint + 3 * i, fj);
        vt_copy3(d->jnt_moment_joint + 3 * i, mj);
    }
    if (!bearing) return;
    for (int i = 1; i <= m->nbody; i++) {
        const double *a = m->jnt_frame_axis + 3 * i, *fj = d->jnt_force_joint + 3 * i, *mj = d->jnt_moment_joint + 3 * i;
        const double fa = vt_dot3(a, fj), ma = vt_dot3(a, mj);
        double *b = d->jnt_bearing + 4 * i;
        b[0] = fa;
        b[1] = vt_perp_norm(fj, a, fa);
        b[2] = ma;
        b[3] = vt_perp_norm(mj, a, ma);
    }
}

/* vt_perp_norm's lengths out of the plain sum's range (and 0): out of line, seldom taken */
double vt_perp_norm_scaled(double u[3])
{
    return vt_normalize(u, 3);
}

void vt_limits_flag(const vt_model *m, vt_data *d)
{
    if (!m->any_limit) return; /* limit_excess and nlimit stay the zeros they were laid out with */
    /* the arrays in locals: the stores below might alias them as far as the compiler knows */
    const int nv = m->nv, *dof_body = m->dof_body, *qadr = m->body_qadr, *vadr = m->body_vadr;
    const int *nq = m->body_nq, *nvb = m->body_nv;
    const double *q = d->q, *qd = d->qd, *tau = d->qfrc_drive;
    int n = 0;
    for (int c = 0; c < nv; c++) {
        const int i = dof_body[c], has_q = nq[i] == nvb[i];
        n += vt_rate_limits(d->limit_excess + 3 * c, m->dof_limit + 4 * c, has_q, has_q ? q[qadr[i] + c - vadr[i]] : 0.0,
                            qd[c], tau[c]);
    }
    vt_limits_found(d, n);
}

/* every joint's reaction (f, moment mo about P_i, global) also in body axes, and checked from
 * the tree's ends inward (an overflow shows first where it arises) */
static vt_status joint_reactions_done(const vt_model *m, vt_data *d)
{
    vt_status st = vt_reactions_unique(m, d);
    if (st) return st;
    for (int i = m->nbody; i >= 1; i--) {
        if (m->body_joint[i] == VT_JOINT_FREE) { /* transmits nothing: what the balance leaves is round-off */
            memset(d->jnt_force + 3 * i, 0, 3 * sizeof(double));
            memset(d->jnt_moment + 3 * i, 0, 3 * sizeof(double));
        }
        const double *f = d->jnt_force + 3 * i, *mo = d->jnt_moment + 3 * i, *Ai = d->A + 9 * i;
        double fb[3], mb[3]; /* locals, stored once: the outputs might alias the inputs */
        vt_mulmat3t(fb, Ai, f);
        vt_mulmat3t(mb, Ai, mo);
        vt_copy3(d->jnt_force_body + 3 * i, fb);
        vt_copy3(d->jnt_moment_body + 3 * i, mb);
        if (!vt_all_finite(f, 3) || !vt_all_finite(mo, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE,
                           "vt_reactions: joint %d's reaction overflowed (accelerations of order %.3g: an ill-posed instant?)",
                           i, fabs(d->xdd[vt_xoff(i)]));
    }
    return VT_OK;
}

/* Efforts that round-off leaves undetermined. vt_solve zeroes M*'s row a where M*_aa is
 * round-off of the terms it is summed from, β_a = τ ε (T_a + R_a) (vt_rate_terms: lever arms from
 * o), and a row holds the rate. The true M*_aa is then anywhere in [0, β_a], and M* being
 * semi-definite, the true M*_ba of another rate b anywhere up to sqrt(β_a M*_bb) (0 when neither
 * rate's body is on the other's path): rate b's
 * equation M* q̈ − Q = Φ_q^T λ is known only to
 *   u_b = Σ_{a zeroed} sqrt(β_a M*_bb) |q̈_a|   against its terms g_b = |Q_b| + Σ_c |M*_bc q̈_c|,
 * and the solve turns that into a relative error of the efforts and the free rates' q̈ of up to
 * u_b / (rcond g_b). Where that reaches 1 no digit is certain: refused (VT_ERR_SINGULAR). A rate
 * truly without inertia near o (a point mass on its axis) has a tiny β_a and passes; a rate whose
 * inertia about its own axis is real but below the round-off of lever arms from o (a 1e9 m link
 * carrying a body of a few metres) does not. Both paths call this after vt_solve (the recursive
 * one's joint-rows route too), so they refuse alike. (A zeroed rate's own equation has lost its
 * terms: it is judged through the others.) */
/* rates a and b can couple in M* (one's body on the other's path); apart, M*_ab is zero by
 * structure (separate trees or branches), whatever the round-off of their diagonals */
static int on_path(const vt_model *m, int body, int rate)
{
    for (int a = vt_last_rate(m, body); a >= rate; a = m->dof_parent[a]) /* descending */
        if (a == rate) return 1;
    return 0;
}

static int coupled(const vt_model *m, int a, int b)
{
    return on_path(m, m->dof_body[b], a) || on_path(m, m->dof_body[a], b);
}

vt_status vt_zeroed_rates_check(const vt_model *m, vt_data *d, const char *who, vt_form form)
{
    const int nv = m->nv;
    const size_t mark = vt_scratch_mark(d);
    double *beta = VT_SCRATCH(d, double, (size_t)nv, "round-off of M*'s diagonal");
    if (!beta) return vt_scratch_fail(d, mark);
    int zeroed = 0;
    for (int a = 0; a < nv; a++) zeroed += d->Mstar[a + (size_t)a * (size_t)nv] == 0.0;
    if (!zeroed) return vt_scratch_release(d, mark), VT_OK;
    const int r = vt_rate_bounds(m, d, form, beta);
    if (r < 0) return vt_scratch_release(d, mark), (vt_status)r;
    double worst = 0.0, ub = 0.0, gb = 0.0;
    int wb = 0;
    for (int b = 0; b < nv; b++) {
        const double mbb = d->Mstar[b + (size_t)b * (size_t)nv];
        if (!(mbb > 0.0)) continue; /* a zeroed rate's own row: its terms are gone, judged through the others */
        double u = 0.0, g = fabs(d->Q[b]);
        for (int c = 0; c < nv; c++) {
            g += fabs(d->Mstar[b + (size_t)c * (size_t)nv] * d->qdd[c]);
            if (d->Mstar[c + (size_t)c * (size_t)nv] == 0.0 && coupled(m, b, c))
                u += sqrt(beta[c] * mbb) * fabs(d->qdd[c]);
        }
        if (u > 0.0 && !(u <= worst * g)) worst = g > 0.0 ? u / g : (double)INFINITY, wb = b, ub = u, gb = g;
    }
    vt_scratch_release(d, mark);
    if (!(worst >= d->rcond)) return VT_OK;
    const double rcond = d->rcond;
    vt_solve_reset(d);
    return vt_fail(d->message, VT_ERR_SINGULAR,
                   "%s: no certain digit: rate %d's M* q̈ − Q known to %.3g against terms of %.3g (rcond %.3g): "
                   "moving rates whose M*_aa is round-off of their lever arms from the reference point",
                   who, wb, ub, gb, rcond);
}

vt_status vt_reactions_impl(const vt_model *m, vt_data *d, vt_form form)
{
    vt_status st0 = vt_zeroed_rates_check(m, d, "vt_reactions", form);
    if (st0) return st0;
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1, mark = vt_scratch_mark(d);
    /* α, the applied wrenches and the children's reactions one after the other, in one block */
    double *alpha = VT_SCRATCH(d, double, 15 * nb, "α, applied wrenches, children's reactions");
    double *rw = VT_SCRATCH(d, double, 12 * (size_t)m->nc, "rows' wrenches");
    int *path = form == VT_FORM_DENSE ? VT_SCRATCH(d, int, m->maxpath, "a body's path") : NULL;
    if (!rw || (form == VT_FORM_DENSE && !path)) return vt_scratch_fail(d, mark);
    double *fe = alpha + 3 * nb, *cf = fe + 6 * nb;
    if (form == VT_FORM_DENSE) vt_accelerations_dense(m, d, d->qdd, d->xdd, alpha, path);
    else vt_accelerations_add(m, d, d->qdd, d->xdd, alpha, fe); /* T: scratch, in fe before fe is set */

    /* applied: xfrc, and every row and generalized force (gravity: vt_body_wrench) */
    memset(cf, 0, 6 * nb * sizeof(double));
    for (int i = 1; i <= n; i++) {
        double *w = fe + 6 * i;
        for (int c = 0; c < 6; c++) w[c] = d->xfrc[6 * i + c];
    }
    vt_status st = row_loads(m, d, fe, rw);
    if (st) return vt_scratch_release(d, mark), st;

    /* tree joints, inward (26) */
    for (int i = n; i >= 1; i--) {
        const int j = m->body_parent[i];
        const double *a = d->xdd + vt_xoff(i), *al = alpha + 3 * i;
        const double *w = d->omega + 3 * i, *Ai = d->A + 9 * i;
        double *f = d->jnt_force + 3 * i, *mo = d->jnt_moment + 3 * i;
        double t[3], s[3], ci[3], app[6], Wi[6];
        double sji[3]; /* P_i − r^i and P_i − r^j from the joint's own vectors, not as differences
                        * of positions from o (exact far from o) */
        vt_joint_child(sji, m, d, i);
        for (int c = 0; c < 3; c++) ci[c] = -sji[c];
        /* the reaction at P_i is the needed wrench about P_i with the loads less the children's
         * reactions as the applied wrench */
        for (int c = 0; c < 6; c++) app[c] = fe[6 * i + c] - cf[6 * i + c];
        const vt_m3 A = vt_m3_load(Ai), R = vt_m3_transpose(A);
        vt_body_wrench(Wi, m, i, A, vt_m3_mul(R, vt_v4_load3(w)), vt_m3_mul(R, vt_v4_load3(al)), vt_v4_load3(a),
                       vt_v4_load3(m->gravity), vt_v4_load3(app), vt_v4_load3(app + 3), vt_v4_load3(ci));
        vt_copy3(mo, Wi);
        vt_copy3(f, Wi + 3);
        if (j) { /* into the parent: f and its moment about the parent's centre of mass */
            const double *sij = d->jsij + 3 * i, *di = d->jd + 3 * i;
            for (int c = 0; c < 3; c++) s[c] = sij[c] + (di[c] + sji[c]); /* s^{ij} + t */
            vt_cross3(t, s, f);
            for (int c = 0; c < 3; c++) {
                cf[6 * j + c] += f[c];
                cf[6 * j + 3 + c] += mo[c] + t[c];
            }
        }
    }
    vt_scratch_release(d, mark);
    return joint_reactions_done(m, d);
}

/* Subtree sums about each body's joint point P_i of wrenches X_i about P_i (moment at noff,
 * force at foff of each 6), leaf first, moved by the short P_i − P_j = s^{ij}_i + t_i − s^{ji}_j:
 * no term carries |P − o| */
void vt_sum_at_joints(const vt_model *m, const vt_data *d, double *X, int noff, int foff)
{
    for (int i = m->nbody; i >= 1; i--) {
        const int j = m->body_parent[i];
        if (j == 0) continue;
        double r[3];
        vt_joint_shift(r, m, d, i, j);
        const double *Xi = X + 6 * i;
        double *Xj = X + 6 * j;
        vt_addcross3(Xj + noff, r, Xi + foff);
        for (int k = 0; k < 3; k++) Xj[noff + k] += Xi[noff + k], Xj[foff + k] += Xi[foff + k];
    }
}

/* The same reactions from the subtrees' needed wrenches W̄ about each joint point P_i (recursive/,
 * which has them from its inward passes): the reaction at joint i is W̄_i less the rows' and the
 * generalized forces' wrenches G over i's subtree, about P_i (vt_sum_at_joints). With rows_in_wbar
 * W̄ already has the rows' wrenches taken off (the articulated path starts its row right sides
 * from them) and G holds the generalized forces' alone, when there are any.
 * G: scratch of 6 x (nbody+1). */
vt_status vt_reactions_subtree(const vt_model *m, vt_data *d, const double *Wbar, double *G, int rows_in_wbar)
{
    static const double zero6[6] = {0, 0, 0, 0, 0, 0};
    const int n = m->nbody;
    const size_t mark = vt_scratch_mark(d);
    double *rw = VT_SCRATCH(d, double, 12 * (size_t)m->nc, "rows' wrenches");
    if (!rw) return vt_scratch_fail(d, mark);
    vt_row_wrenches(rw, m, d, d->lambda);
    vt_status st = row_efforts(m, d, rw);
    if (st) return vt_scratch_release(d, mark), st;
    int loads = !rows_in_wbar && m->nc > 0; /* any load for G */
    for (int c = 0; c < m->nv && !loads; c++) loads = vt_rate_load(m, d, c) != 0.0;
    if (loads) {
        memset(G, 0, 6 * ((size_t)n + 1) * sizeof(double));
        qfrc_loads(m, d, G);
        if (!rows_in_wbar) add_row_wrenches(m, rw, G);
        for (int i = 1; i <= n; i++) { /* about the centre of mass → about P_i: (r_i − P_i) × f */
            double c[3];
            vt_joint_child(c, m, d, i);
            for (int k = 0; k < 3; k++) c[k] = -c[k];
            vt_addcross3(G + 6 * i + 3, c, G + 6 * i);
        }
        vt_sum_at_joints(m, d, G, 3, 0);
    }
    for (int i = 1; i <= n; i++) {
        const double *W = Wbar + 6 * i, *g = loads ? G + 6 * i : zero6;
        double f[3], mo[3]; /* locals, stored once: the outputs might alias the inputs */
        for (int c = 0; c < 3; c++) {
            f[c] = W[3 + c] - g[c];
            mo[c] = W[c] - g[3 + c]; /* about P_i */
        }
        vt_copy3(d->jnt_force + 3 * i, f);
        vt_copy3(d->jnt_moment + 3 * i, mo);
    }
    vt_scratch_release(d, mark);
    return joint_reactions_done(m, d);
}

/* The outputs every instant path ends with, from what each leaves alike (the reactions, ẍ, λ,
 * qfrc_drive), so that the dense, recursive and motion paths share them:
 * - each body's angular acceleration α = 2 E p̈ (ω = 2 E ṗ, and 2 Ė ṗ = 0), from ẍ;
 * - each tree joint's total wrench, reaction plus actuation: the generalized force g_c along each
 *   of its rates c — the joint drives' multipliers on c (given: every rate's qfrc_drive, the
 *   motion given), the applied qfrc_c and the couplings' λ (−ratio λ on rate b) — as the force
 *   g e along a translational axis e or the moment g e about a rotational one, at the joint point
 *   P (a free joint's rates are such axes). A base body's rates act at its centre of mass r: force
 *   g e_k on r_k, moment ½ g E e_k on p_k (the Cartesian form R^T g, as rate_load), the force's
 *   moment then moved to P. Summed this way the total is the wrench the reference body passes to
 *   the subtree: its Newton–Euler wrench less the loads from outside it (25)-(26). */
vt_status vt_reactions_total(const vt_model *m, vt_data *d, int given)
{
    const int n = m->nbody, nv = m->nv;
    const size_t mark = vt_scratch_mark(d);
    double *g = VT_SCRATCH(d, double, nv > 0 ? (size_t)nv : 1, "actuation per rate");
    if (!g) return vt_scratch_fail(d, mark);
    for (int c = 0; c < nv; c++) g[c] = vt_rate_load(m, d, c);
    if (given) {
        for (int c = 0; c < nv; c++) g[c] += d->qfrc_drive[c];
    } else {
        for (int r = 0; r < vt_drive_rows(m); r++)
            if (m->con_kind[r] == VT_ROW_JOINT) g[m->con_dof[r]] += d->lambda[r];
        for (int k = 0; k < m->ncoupling; k++) {
            const vt_coupling_def *c = &m->coupling[k];
            const double l = d->lambda[m->coupling_row[k]];
            g[m->body_vadr[c->body_a] + c->index_a] += l;
            g[m->body_vadr[c->body_b] + c->index_b] -= c->ratio * l;
        }
    }
    memset(d->alpha, 0, 3 * sizeof(double));
    memset(d->jnt_force_total, 0, 3 * sizeof(double));
    memset(d->jnt_moment_total, 0, 3 * sizeof(double));
    memset(d->jnt_force_total_body, 0, 3 * sizeof(double));
    memset(d->jnt_moment_total_body, 0, 3 * sizeof(double));
    for (int i = 1; i <= n; i++) {
        const double *p = d->x + vt_xoff(i) + 3, *e = d->jaxis + 9 * i, *Ai = d->A + 9 * i;
        const int jt = m->body_joint[i];
        double al[3], f[3], mo[3], fb[3], mb[3];
        vt_mulEp(al, p, d->xdd + vt_xoff(i) + 3);
        for (int c = 0; c < 3; c++) al[c] *= 2.0;
        vt_copy3(f, d->jnt_force + 3 * i);
        vt_copy3(mo, d->jnt_moment + 3 * i);
        for (int k = 0; k < m->body_nv[i]; k++) {
            const double gc = g[m->body_vadr[i] + k];
            if (gc == 0.0) continue;
            int ax;
            switch (vt_dof_kind(jt, k, &ax)) {
            case VT_DOF_ROT: vt_axpy3(mo, gc, e + 3 * ax); break;
            case VT_DOF_TRANS: vt_axpy3(f, gc, e + 3 * ax); break;
            case VT_DOF_BASE_R: { /* at r: force g e_k, its moment about P (r − P) × g e_k */
                double u[3] = {0, 0, 0}, s[3];
                u[ax] = gc;
                vt_axpy3(f, 1.0, u);
                for (int c = 0; c < 3; c++) s[c] = d->xrel[6 * i + c] - d->xrel[6 * i + 3 + c];
                vt_addcross3(mo, s, u);
                break;
            }
            default: { /* VT_DOF_BASE_P: ½ g E e_k */
                double u[4] = {0, 0, 0, 0}, t[3];
                u[ax] = 0.5 * gc;
                vt_mulEp(t, p, u);
                vt_axpy3(mo, 1.0, t);
                break;
            }
            }
        }
        vt_mulmat3t(fb, Ai, f);
        vt_mulmat3t(mb, Ai, mo);
        vt_copy3(d->alpha + 3 * i, al);
        vt_total_store(d, i, f, mo, fb, mb);
    }
    vt_scratch_release(d, mark);
    const int nb3 = 3 * (n + 1);
    vt_finite_scan fs = {0}; /* as one scan: one test at the end */
    vt_finite_add(&fs, d->alpha, nb3);
    vt_finite_add(&fs, d->jnt_force_total, nb3);
    vt_finite_add(&fs, d->jnt_moment_total, nb3);
    vt_finite_add(&fs, d->jnt_force_total_body, nb3);
    vt_finite_add(&fs, d->jnt_moment_total_body, nb3);
    if (vt_finite_ok(&fs)) return VT_OK;
    for (int i = 1; i <= n; i++)
        if (!vt_all_finite(d->alpha + 3 * i, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "body %d's angular acceleration overflows", i);
    for (int i = 1; i <= n; i++)
        if (!vt_total_finite(d, i))
            return vt_fail(d->message, VT_ERR_NONFINITE, "joint %d's total wrench (reaction and actuation) overflows", i);
    return vt_fail(d->message, VT_ERR_NONFINITE, "a total wrench or angular acceleration overflows");
}

/* Marks in d->jnt_unique and d->cut_unique the reactions that the multiplier direction z
 * (Φ_q^T z = 0) changes by more than tol of its largest change: the reactions that the
 * multipliers z alone produce (no inertia, no applied load). Scratch: fe, cf (6 x (nbody+1)
 * each), mag (6 x (nbody+1) + 6 ncut), rw (12 nc). */
static void reaction_sensitivity(const vt_model *m, vt_data *d, const double *z, double tol, double *fe, double *cf,
                                 double *mag, double *rw)
{
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1;
    memset(fe, 0, 6 * nb * sizeof(double));
    memset(cf, 0, 6 * nb * sizeof(double));
    vt_row_wrenches(rw, m, d, z);
    add_row_wrenches(m, rw, fe);
    coupling_loads(m, d, z, fe);
    /* the size of the direction's loads, before they cancel on the bodies */
    double big = 0.0, *cmag = mag + 6 * nb, loads = 0.0;
    for (size_t k = 0; k < 12 * (size_t)m->nc; k++) loads = fabs(rw[k]) > loads ? fabs(rw[k]) : loads;
    for (int k = 0; k < m->ncoupling; k++) {
        const double g = fabs(z[m->coupling_row[k]]) * (fabs(m->coupling[k].ratio) > 1.0 ? fabs(m->coupling[k].ratio) : 1.0);
        loads = g > loads ? g : loads;
    }
    for (int k = 0; k < m->ncut; k++) {
        const vt_cut_joint_def *c = &m->cut[k];
        const int r0 = m->cut_row[k];
        double s[3], f[3], mo[3];
        vt_mulmat3(s, d->A + 9 * c->body_b, c->point_b);
        rows_wrench_at(rw, r0, r0 + vt_cut_nrows(c), 1, s, f, mo);
        for (int e = 0; e < 3; e++) {
            cmag[6 * k + e] = fabs(f[e]);
            cmag[6 * k + 3 + e] = fabs(mo[e]);
            big = fmax(big, fmax(fabs(f[e]), fabs(mo[e])));
        }
    }
    for (int i = n; i >= 1; i--) {
        const int j = m->body_parent[i];
        const double *ri = d->xrel + 6 * i;
        double f[3], N[3], s[3], t[3], mo[3];
        for (int c = 0; c < 3; c++) {
            f[c] = -fe[6 * i + c] + cf[6 * i + c];
            N[c] = -fe[6 * i + 3 + c] + cf[6 * i + 3 + c];
            s[c] = ri[3 + c] - ri[c];
        }
        vt_cross3(t, s, f);
        for (int c = 0; c < 3; c++) mo[c] = N[c] - t[c];
        for (int e = 0; e < 3; e++) {
            mag[6 * i + e] = fabs(f[e]);
            mag[6 * i + 3 + e] = fabs(mo[e]);
            big = fmax(big, fmax(fabs(f[e]), fabs(mo[e])));
        }
        if (j) {
            const double *rj = d->xrel + 6 * j;
            for (int c = 0; c < 3; c++) s[c] = d->xrel[6 * i + 3 + c] - rj[c];
            vt_cross3(t, s, f);
            for (int c = 0; c < 3; c++) {
                cf[6 * j + c] += f[c];
                cf[6 * j + 3 + c] += mo[c] + t[c];
            }
        }
    }
    /* a direction whose loads cancel in every joint (its largest change is round-off of them)
     * changes no reaction: nothing is marked */
    if (!(big > tol * loads)) return;
    for (int i = 1; i <= n; i++)
        for (int e = 0; e < 6; e++)
            if (mag[6 * i + e] > tol * big) d->jnt_unique[6 * i + e] = 0;
    for (int k = 0; k < m->ncut; k++)
        for (int e = 0; e < 6; e++)
            if (cmag[6 * k + e] > tol * big) d->cut_unique[6 * k + e] = 0;
}

vt_status vt_reactions_nonunique(const vt_model *m, vt_data *d)
{
    const int nnull = m->nc - d->rank;
    const size_t nb = (size_t)m->nbody + 1, mark = vt_scratch_mark(d);
    double *fe = VT_SCRATCH(d, double, 6 * nb, "applied wrenches"), *cf = VT_SCRATCH(d, double, 6 * nb, "children's reactions");
    double *mag = VT_SCRATCH(d, double, 6 * nb + 6 * (size_t)m->ncut, "reaction changes");
    double *rw = VT_SCRATCH(d, double, 12 * (size_t)m->nc, "rows' wrenches");
    if (!rw) return vt_scratch_fail(d, mark);
    for (int j = 0; j < nnull; j++)
        reaction_sensitivity(m, d, d->lambda_null + (size_t)j * (size_t)m->nc, 1e-9, fe, cf, mag, rw);
    vt_scratch_release(d, mark);
    return VT_OK;
}

/* The scratch reactions.c takes at once: the inward pass (α, two wrenches a body, the rows'
 * wrenches, the dense accelerations' path) or the uniqueness (three wrenches a body, the cuts',
 * the rows'), or the total wrenches' actuation per rate (alone). */
size_t vt_reactions_scratch(const vt_model *m)
{
    const size_t nb = (size_t)m->nbody + 1, rw = VT_SCRATCH_BYTES(12 * (size_t)m->nc, sizeof(double));
    const size_t inward = VT_SCRATCH_BYTES(15 * nb, sizeof(double)) + VT_SCRATCH_BYTES(m->maxpath, sizeof(int));
    const size_t unique = 2 * VT_SCRATCH_BYTES(6 * nb, sizeof(double)) +
                          VT_SCRATCH_BYTES(6 * nb + 6 * (size_t)m->ncut, sizeof(double));
    const size_t total = VT_SCRATCH_BYTES(m->nv > 0 ? (size_t)m->nv : 1, sizeof(double));
    const size_t zeroed = VT_SCRATCH_BYTES((size_t)m->nv, sizeof(double)) + VT_SCRATCH_BYTES(2 * (size_t)m->nv, sizeof(double)) +
                          VT_SCRATCH_BYTES(4 * nb, sizeof(double)); /* β, vt_rate_bounds' T and w */
    size_t most = inward > unique ? inward : unique;
    most = (most > zeroed ? most : zeroed) + rw;
    return most > total ? most : total;
}

vt_status vt_drive_cartesian_force(double *F, const vt_model *m, vt_data *d, int k)
{
    vt_status st = vt_check_dense(m, d, "vt_drive_cartesian_force");
    if (st) return st;
    if (!F) return vt_fail(d->message, VT_ERR_NULL, "vt_drive_cartesian_force: F is NULL");
    if (k < 0 || k >= m->ndrive)
        return vt_fail(d->message, VT_ERR_BAD_INDEX, "vt_drive_cartesian_force: drive %d not in 0..%d", k, m->ndrive - 1);
    /* the drive's rows (at most 3) touch at most 6 bodies: their 7 entries formed aside, written
     * only when finite (a product or sum may overflow), so that a failure leaves F as it was */
    enum { MAXB = 6 };
    int body[MAXB], nb = 0;
    double f[MAXB][7] = {{0.0}};
    const int r0 = m->drive_row[k];
    for (int r = r0; r < r0 + vt_drive_nrows(&m->drive[k]); r++)
        for (int side = 0; side < 2; side++) {
            const int b = m->con_body[2 * r + side];
            if (b == 0) continue;
            int j = 0;
            while (j < nb && body[j] != b) j++;
            if (j == nb) body[nb++] = b;
            for (int c = 0; c < 7; c++) f[j][c] += d->Phix[14 * r + 7 * side + c] * d->lambda[r];
        }
    for (int j = 0; j < nb; j++)
        if (!vt_all_finite(f[j], 7))
            return vt_fail(d->message, VT_ERR_NONFINITE,
                           "vt_drive_cartesian_force: drive %d's force on body %d overflows (Φ_x^T λ not finite)", k,
                           body[j]);
    memset(F, 0, (size_t)m->nx * sizeof(double));
    for (int j = 0; j < nb; j++) memcpy(F + vt_xoff(body[j]), f[j], sizeof f[j]);
    return VT_OK;
}

vt_status vt_reactions_joint_frame(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_reactions_joint_frame");
    if (st) return st;
    vt_joint_frames(m, d, 1);
    return VT_OK;
}
