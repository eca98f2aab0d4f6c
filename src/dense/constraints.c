/* Constraints in Cartesian form Φ(x, t) = 0: the paper's (21) (the second one), (22), (23)
 * and docs/method.md "Constraints and drives".
 *
 *   Φ_q = Φ_x S                                                     (22)
 *   γ   = −Φ̇_x ẋ − Φ̇_t − Φ_x Ṡ q̇ = −Φ̈ evaluated at q̈ = 0           (23)
 * Φ_x is kept in the E-form: along admissible ṗ, ∂(A s')/∂p = −2 s̃ E, so a row whose rate is
 * Φ̇ = jv·v + jw·ω on a body has Φ_x = [jv^T, 2 jw^T E] there. Rows, with P = r + A s' a body
 * point, u = A u' a body vector, d = P_b − P_a, and (·)0 the accelerations at q̈ = 0:
 *   joint drive    q_k − f(t)                 Φ_x = the row of R (Table 1), since δq = R δx (12)
 *                                             Φ_t = −f', γ = f''
 *   point          c·(P_b − P_a) − f(t)       jv = ±c, jw = s × c;  γ = f'' − c·(P̈_b − P̈_a)0   (30)-(34)
 *   dot            u_a·v_b                    jw_a = u × v, jw_b = v × u;  γ = −(ü·v + 2 u̇·v̇ + u·v̈)0
 *   line           u_a·d                      jv = ±u, jw_b = s_b × u, jw_a = u × d − s_a × u
 *                                             γ = −(ü·d + 2 u̇·ḋ + u·d̈)0
 *                  (a planar pin, vt_cut_joint_def.planar: two line rows, u = h1, h2 ⟂ axis1)
 *   orientation    2 G(p_d) p  (3 rows)       Φ_p = 2 G(p_d), Φ_t = 2 G(ṗ_d) p,
 *                                             γ = −[2 G(p̈_d) p + 4 G(ṗ_d) ṗ + 2 G(p_d) p̈0]
 *                  (G(a) b is the vector part of a* ⊗ b: zero when p = p_d)
 *   relative       2 G(p_d) p_r  (3 rows)     as orientation with p_r = p_a* ⊗ p_b for p (γ from ṗ_r,
 *   orientation                               p̈_r0); Φ_x the exact gradients of the bilinear p_r on
 *                                             both bodies (relative_row); along the rates Φ̇ sees
 *                                             ω_b − ω_a only, so its moment on a is minus b's
 *   normalization  p^T p − 1 (base body)      Φ_p = 2 p^T, γ = −2 ṗ·ṗ
 *   coupling       q_a − k q_b − c            Φ_q = e_a − k e_b directly (the coordinates of two
 *                                             joints: up to four bodies, so no Φ_x), Φ_t = 0, γ = 0
 * The prescribed orientation of a built-in orientation drive: p_d = [f(t) about axis] ⊗ p0,
 * ω_d = f' axis, ω̇_d = f'' axis, or three angles in a sequence (sequence_turn), then
 * ṗ_d = ½ E^T ω_d, p̈_d = ½ E^T ω̇_d − ¼ |ω_d|² p_d (a relative drive: p_d, ω_d in a's axes).
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dense/constraints.h"
#include "base/lapack.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/functions.h"
#include "model/model.h"
#include "kinematics/inverse_transform.h"
#include "kinematics/kinematics.h"
#include "model/builder.h"

/* Motion of one body as a row sees it; the ground is at rest with identity axes. Positions are
 * taken from the reference point o (d->xrel, kinematics.c), the ground's at −o: a point P below
 * is P − o, and a point on the ground enters as (point − o), rounded once. */
typedef struct {
    int id;
    const double *r, *p, *A, *w, *v;
    double a0[3], al0[3], pd[4], pdd0[4];
} body_state;

static const double zero3[3] = {0, 0, 0};
static const double ident9[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

/* rates: the velocities and the accelerations at q̈ = 0 as well (γ's rows need them) */
static void load_body(body_state *b, const vt_model *m, const vt_data *d, int id, int rates)
{
    (void)m;
    b->id = id;
    if (id == 0) {
        static const double unit[4] = {1, 0, 0, 0};
        b->r = d->xrel; b->p = unit; b->A = ident9; b->w = zero3; b->v = zero3;
        memset(b->a0, 0, sizeof b->a0);
        memset(b->al0, 0, sizeof b->al0);
        memset(b->pd, 0, sizeof b->pd);
        memset(b->pdd0, 0, sizeof b->pdd0);
        return;
    }
    const int o = vt_xoff(id);
    b->r = d->xrel + 6 * id;
    b->p = d->x + o + 3;
    b->A = d->A + 9 * id;
    b->w = d->omega + 3 * id;
    b->v = d->xd + o;
    if (!rates) return;
    vt_copy3(b->a0, d->Sdqd + o);
    memcpy(b->pd, d->xd + o + 3, sizeof b->pd);
    memcpy(b->pdd0, d->Sdqd + o + 3, sizeof b->pdd0);
    vt_mulEp(b->al0, b->p, b->pdd0); /* α = 2 E p̈ (2 Ė ṗ = 0) */
    for (int k = 0; k < 3; k++) b->al0[k] *= 2.0;
}

/* a body point: position, velocity, acceleration at q̈ = 0 (with rates); s = A s' */
static void point_motion(const body_state *b, const double sp[3], double s[3], double P[3], double vP[3], double aP[3],
                         int rates)
{
    double t[3];
    vt_mulmat3(s, b->A, sp);
    for (int k = 0; k < 3; k++) P[k] = b->r[k] + s[k];
    if (!rates) return;
    vt_copy3(vP, b->v);
    vt_addcross3(vP, b->w, s);
    vt_copy3(aP, b->a0);
    vt_addcross3(aP, b->al0, s);
    vt_cross3(t, b->w, s);
    vt_addcross3(aP, b->w, t);
}

/* point_motion remembered across the rows of one cut joint or drive, which share their points */
typedef struct {
    int id;
    double sp[3], s[3], P[3], vP[3], aP[3];
} point_memo;

static const point_memo *point_motion_memo(point_memo *c, const body_state *b, const double sp[3], int rates)
{
    if (c->id != b->id || c->sp[0] != sp[0] || c->sp[1] != sp[1] || c->sp[2] != sp[2]) {
        c->id = b->id;
        vt_copy3(c->sp, sp);
        point_motion(b, sp, c->s, c->P, c->vP, c->aP, rates);
    }
    return c;
}

/* a body vector: u, u̇, ü at q̈ = 0 (with rates) */
static void vector_motion(const body_state *b, const double up[3], double u[3], double ud[3], double udd[3], int rates)
{
    vt_mulmat3(u, b->A, up);
    if (!rates) return;
    vt_cross3(ud, b->w, u);
    vt_cross3(udd, b->al0, u);
    vt_addcross3(udd, b->w, ud);
}

/* Φ_x of a row on one body from its rate coefficients: [jv; 2 E^T jw] */
static void phix_from(double *px, const body_state *b, const double jv[3], const double jw[3])
{
    if (b->id == 0) {
        memset(px, 0, 7 * sizeof(double));
        return;
    }
    vt_copy3(px, jv);
    vt_quat_rate(px + 3, b->p, jw); /* ½ E^T jw */
    for (int k = 3; k < 7; k++) px[k] *= 4.0;
}

/* The turn by three angles in a named sequence (vt_drive_def.sequence): q = R_1 ⊗ R_2 ⊗ R_3,
 * R_i a turn by φ_i about the unit axis e_i (body-fixed order; a lower-case sequence about
 * fixed axes is the upper-case one read backwards, angles too). The axis of each turn as seen
 * from outside, u_1 = e_1, u_2 = R_1 e_2, u_3 = R_1 R_2 e_3, gives
 *   ω = φ̇_1 u_1 + φ̇_2 u_2 + φ̇_3 u_3,
 *   ω̇ = Σ φ̈_i u_i + φ̇_2 (ω_1 × u_2) + φ̇_3 (ω_12 × u_3),  ω_1 = φ̇_1 u_1, ω_12 = ω_1 + φ̇_2 u_2
 * (u_2 turns with R_1, u_3 with R_1 R_2). f: the three functions' values and derivatives. */
static void sequence_turn(const char *seq, const double f[3][3], double q[4], double w[3], double wd[3])
{
    const int fixed = seq[0] >= 'a';
    double u[3][3], R[4] = {1, 0, 0, 0};
    const double *fi[3];
    memset(w, 0, 3 * sizeof(double));
    memset(wd, 0, 3 * sizeof(double));
    for (int i = 0; i < 3; i++) {
        const int s = fixed ? 2 - i : i; /* the turn applied i-th from the outside */
        double e[3] = {0, 0, 0}, A[9], r[4];
        e[(seq[s] - (fixed ? 'x' : 'X'))] = 1.0;
        fi[i] = f[s];
        vt_euler_A(A, R);
        vt_mulmat3(u[i], A, e);
        vt_quat_axis_angle(r, e, fi[i][0]);
        vt_quat_mul(R, R, r);
    }
    memcpy(q, R, 4 * sizeof(double));
    double w1[3], w12[3];
    for (int c = 0; c < 3; c++) {
        w1[c] = fi[0][1] * u[0][c];
        w12[c] = w1[c] + fi[1][1] * u[1][c];
        w[c] = w12[c] + fi[2][1] * u[2][c];
        wd[c] = fi[0][2] * u[0][c] + fi[1][2] * u[1][c] + fi[2][2] * u[2][c];
    }
    double t[3];
    vt_cross3(t, w1, u[1]);
    vt_axpy3(wd, fi[1][1], t);
    vt_cross3(t, w12, u[2]);
    vt_axpy3(wd, fi[2][1], t);
}

/* p_d, ṗ_d, p̈_d of an orientation drive at time t (a relative drive's: of b's axes relative to
 * a's, with ω_d, ω̇_d in a's axes) */
static vt_status prescribed_orientation(char *msg, int k, const vt_drive_def *dr, double t, double pdes[4],
                                        double pdes_d[4], double pdes_dd[4])
{
    double w[3], wd[3], E[12];
    if (dr->sequence) {
        double f[3][3], r[4];
        const vt_function *fs[3] = {&dr->f, &dr->f2, &dr->f3};
        for (int e = 0; e < 3; e++) {
            vt_status st = vt_function_eval_valid(f[e], fs[e], t);
            if (st)
                return vt_fail(msg, st, "vt_constraints: drive %d: time function %s failed at t = %g (%s)", k,
                               e == 0 ? "f" : e == 1 ? "f2" : "f3", t, vt_status_string(st));
        }
        sequence_turn(dr->sequence, (const double(*)[3])f, r, w, wd);
        vt_quat_mul(pdes, r, dr->orientation);
    } else if (dr->orientation_callback) {
        double p[4];
        if (dr->orientation_callback(t, p, w, wd, dr->user) != 0)
            return vt_fail(msg, VT_ERR_CALLBACK, "vt_constraints: drive %d: orientation callback failed at t = %g", k, t);
        if (!vt_all_finite(p, 4) || !vt_all_finite(w, 3) || !vt_all_finite(wd, 3))
            return vt_fail(msg, VT_ERR_NONFINITE, "vt_constraints: drive %d: orientation callback returned NaN or Inf", k);
        for (int c = 0; c < 4; c++) pdes[c] = p[c];
        if (!(vt_normalize(pdes, 4) > 1e-12)) /* of norm 1 ideally (scaled: no overflow or underflow) */
            return vt_fail(msg, VT_ERR_QUATERNION, "vt_constraints: drive %d: orientation of zero norm", k);
        /* a relative drive's callback gives the turn before `orientation` (a joint's p0: builder.c);
         * a constant right factor leaves ω_d and ω̇_d as they are */
        if (dr->type == VT_DRIVE_RELATIVE_ORIENTATION) vt_quat_mul(pdes, pdes, dr->orientation);
    } else {
        double f[3], r[4];
        vt_status st = vt_function_eval_valid(f, &dr->f, t);
        if (st) return vt_fail(msg, st, "vt_constraints: drive %d: time function failed at t = %g (%s)", k, t, vt_status_string(st));
        vt_quat_axis_angle(r, dr->axis, f[0]);
        vt_quat_mul(pdes, r, dr->orientation);
        for (int c = 0; c < 3; c++) { w[c] = f[1] * dr->axis[c]; wd[c] = f[2] * dr->axis[c]; }
    }
    vt_euler_E(E, pdes);
    vt_mulE_t(pdes_d, E, w);
    vt_mulE_t(pdes_dd, E, wd);
    const double w2 = vt_dot3(w, w);
    for (int c = 0; c < 4; c++) {
        pdes_d[c] *= 0.5;
        pdes_dd[c] = 0.5 * pdes_dd[c] - 0.25 * w2 * pdes[c];
    }
    return VT_OK;
}

static double dot4(const double a[4], const double b[4])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

/* row k (0..2) of G(a) b */
static double G_row(const double a[4], const double b[4], int k)
{
    double G[12];
    vt_euler_G(G, a);
    return G[k] * b[0] + G[3 + k] * b[1] + G[6 + k] * b[2] + G[9 + k] * b[3];
}

static void conj4(double c[4], const double p[4])
{
    c[0] = p[0]; c[1] = -p[1]; c[2] = -p[2]; c[3] = -p[3];
}

/* b's orientation relative to a's, p_r = p_a* ⊗ p_b, its rate and its second rate at q̈ = 0:
 * ṗ_r = ṗ_a* ⊗ p_b + p_a* ⊗ ṗ_b, p̈_r0 = p̈_a0* ⊗ p_b + 2 ṗ_a* ⊗ ṗ_b + p_a* ⊗ p̈_b0 */
static void relative_motion(const body_state *A, const body_state *B, double pr[4], double prd[4], double prdd[4],
                            int rates)
{
    double ca[4], cad[4], cadd[4], t[4];
    conj4(ca, A->p);
    vt_quat_mul(pr, ca, B->p);
    if (!rates) return;
    conj4(cad, A->pd);
    conj4(cadd, A->pdd0);
    vt_quat_mul(prd, cad, B->p);
    vt_quat_mul(t, ca, B->pd);
    for (int c = 0; c < 4; c++) prd[c] += t[c];
    vt_quat_mul(prdd, cadd, B->p);
    vt_quat_mul(t, cad, B->pd);
    for (int c = 0; c < 4; c++) prdd[c] += 2.0 * t[c];
    vt_quat_mul(t, ca, B->pdd0);
    for (int c = 0; c < 4; c++) prdd[c] += t[c];
}

/* Row k of a relative orientation drive, 2 G(p_d) p_r with p_r = p_a* ⊗ p_b: bilinear in p_a
 * and p_b, so its exact gradients are the row on p_r's columns e_c* ⊗ p_b (for p_a) and
 * p_a* ⊗ e_c (for p_b); Φ_t = 2 G(ṗ_d) p_r, γ = −[2 G(p̈_d) p_r + 4 G(ṗ_d) ṗ_r + 2 G(p_d) p̈_r0] */
static void relative_row(vt_data *d, int r, int k, const body_state *A, const body_state *B, const double pdes[4],
                         const double pdes_d[4], const double pdes_dd[4], const double pr[4], const double prd[4],
                         const double prdd[4], int rates)
{
    double *pxa = d->Phix + 14 * r, *pxb = pxa + 7, ca[4], G[12];
    conj4(ca, A->p);
    vt_euler_G(G, pdes);
    memset(pxa, 0, 14 * sizeof(double));
    for (int c = 0; c < 4; c++) {
        double e[4] = {0, 0, 0, 0}, col[4];
        e[c] = 1.0;
        if (A->id != 0) {
            double ec[4];
            conj4(ec, e);
            vt_quat_mul(col, ec, B->p);
            pxa[3 + c] = 2.0 * (G[k] * col[0] + G[3 + k] * col[1] + G[6 + k] * col[2] + G[9 + k] * col[3]);
        }
        vt_quat_mul(col, ca, e);
        pxb[3 + c] = 2.0 * (G[k] * col[0] + G[3 + k] * col[1] + G[6 + k] * col[2] + G[9 + k] * col[3]);
    }
    d->Phi[r] = 2.0 * G_row(pdes, pr, k);
    d->Phit[r] = 2.0 * G_row(pdes_d, pr, k);
    if (rates) d->gamma[r] = -(2.0 * G_row(pdes_dd, pr, k) + 4.0 * G_row(pdes_d, prd, k) + 2.0 * G_row(pdes, prdd, k));
}

/* The dense Φ_q's scratch: a body's S block (7 x maxpath), its product with a row (maxpath) and
 * the body's path (maxpath) */
typedef struct {
    double *S, *row;
    int *path;
} s_block;

/* Φ_q = Φ_x S (22) for row r, body by body on the body's path columns: from the dense S
 * (gathered into Si), or column by column as the dense S forms them (the recursive path, which
 * has no dense S): lever arms along the tree (vt_lever) */
static void phiq_row(const vt_model *m, vt_data *d, int r, vt_form form, const s_block *Si)
{
    const int nc = m->nc;
    for (int side = 0; side < 2; side++) {
        const int b = m->con_body[2 * r + side];
        if (b == 0) continue;
        const double *px = d->Phix + 14 * r + 7 * side;
        if (form == VT_FORM_DENSE) {
            const int k = vt_body_path(m, b, Si->path);
            vt_gather_S(Si->S, m, d, b, Si->path);
            vt_dgemv('T', 7, k, 1.0, Si->S, 7, px, 1, 0.0, Si->row, 1);
            for (int c = 0; c < k; c++) d->Phiq[r + (size_t)Si->path[c] * (size_t)nc] += Si->row[c];
        } else {
            double E[12], col[7];
            vt_euler_E(E, d->x + vt_xoff(b) + 3);
            vt_lever L;
            vt_lever_start(&L, m, d, b, 0);
            do {
                for (int a = m->body_vadr[L.k]; a < m->body_vadr[L.k] + m->body_nv[L.k]; a++) {
                    vt_S_column(col, m, d, b, E, a, L.u);
                    double v = 0.0;
                    for (int e = 0; e < 7; e++) v += px[e] * col[e];
                    d->Phiq[r + (size_t)a * (size_t)nc] += v;
                }
            } while (vt_lever_up(&L, m, d));
        }
    }
}

/* The recursive path's Φ_q for a row whose rate on body b is Φ̇ = jv·v_b + jw·ω_b (v_b the
 * centre of mass's velocity): a turning rate c of a joint at P moves the centre by ω_c × u,
 * u = r_b − P (vt_lever: along the tree, exact far from o), a sliding one by its axis v_c, so
 * Φ_q[r, c] = (jw + u × jv)·ω_c or jv·v_c — no E, no 7-vectors. It equals Φ_x S: along the
 * rates (2 E^T jw)·ṗ = jw·ω, ω = 2 E ṗ (16), for a base body's own ṗ too (ω = 2 E e_k about r_b,
 * u = 0). */
static void phiq_twist(const vt_model *m, vt_data *d, int r, int b, const double jv[3], const double jw[3])
{
    if (b == 0) return;
    vt_lever L;
    vt_lever_start(&L, m, d, b, 0);
    do {
        double jwu[3];
        vt_cross3(jwu, L.u, jv);
        for (int k = 0; k < 3; k++) jwu[k] += jw[k];
        const int jt = m->body_joint[L.k], turn = jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL || jt == VT_JOINT_SPHERICAL;
        for (int a = m->body_vadr[L.k]; a < m->body_vadr[L.k] + m->body_nv[L.k]; a++) {
            const double *w = d->twist + 6 * a;
            d->Phiq[r + (size_t)a * (size_t)m->nc] += turn || vt_dof_turns(m, a) ? vt_dot3(jwu, w) : vt_dot3(jv, w + 3);
        }
    } while (vt_lever_up(&L, m, d));
}

/* A point's velocity Jacobian along its body's path, for the recursive Φ_q of point drives: P =
 * r_b + s moves by w_a × (u + s) for a turning rate a of a joint on the path (u = r_b − P_k,
 * vt_lever: exact far from o; w_a the rate's twist's angular part), by v_a for a sliding one.
 * Its columns are kept for every drive on the same point (a tool point's x, y and z, in any
 * order: JAC_SLOTS points at once), and each row pairs its direction c with them,
 * Φ_q[r, a] = c · (J_b,a − J_a,a): one walk up the tree per point instead of one per row. */
enum { JAC_SLOTS = 4 };
typedef struct {
    int body, n;    /* the body (−1: empty slot), the rates on its path */
    double sp[3];   /* the point in the body's axes: with the body, the slot's key */
    int *rate;      /* the path's rates (maxpath) */
    double *J;      /* their columns (3 x maxpath) */
} point_jac;

static const point_jac *point_jac_get(point_jac *slots, int *next, const vt_model *m, const vt_data *d, int b,
                                      const double sp[3], const double s[3])
{
    for (int k = 0; k < JAC_SLOTS; k++)
        if (slots[k].body == b && slots[k].sp[0] == sp[0] && slots[k].sp[1] == sp[1] && slots[k].sp[2] == sp[2])
            return &slots[k];
    point_jac *p = &slots[*next];
    *next = (*next + 1) % JAC_SLOTS;
    p->body = b;
    vt_copy3(p->sp, sp);
    p->n = 0;
    vt_lever L;
    vt_lever_start(&L, m, d, b, 0);
    do {
        double us[3];
        for (int k = 0; k < 3; k++) us[k] = L.u[k] + s[k]; /* P − P_k */
        const int jt = m->body_joint[L.k], turn = jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL || jt == VT_JOINT_SPHERICAL;
        for (int a = m->body_vadr[L.k]; a < m->body_vadr[L.k] + m->body_nv[L.k]; a++) {
            const double *w = d->twist + 6 * a;
            double *J = p->J + 3 * p->n;
            if (turn || vt_dof_turns(m, a)) vt_cross3(J, w, us);
            else vt_copy3(J, w + 3);
            p->rate[p->n++] = a;
        }
    } while (vt_lever_up(&L, m, d));
    return p;
}

/* Φ_q[r, ·] += sign × c · the point's columns */
static void phiq_point(const vt_model *m, vt_data *d, int r, const point_jac *p, const double c[3], double sign)
{
    for (int k = 0; k < p->n; k++) d->Phiq[r + (size_t)p->rate[k] * (size_t)m->nc] += sign * vt_dot3(c, p->J + 3 * k);
}

/* Φ_q rows r..r+2 += sign × the velocity Jacobian of the point s (P − r_b) moving with body b:
 * a turning rate's column w × (u + s), a sliding one's its axis (phiq_twist with jv = e_k) */
static void point_jacobian_rows(const vt_model *m, vt_data *d, int r, int b, const double s[3], double sign)
{
    if (b == 0) return;
    vt_lever L;
    vt_lever_start(&L, m, d, b, 0);
    do {
        double u[3];
        for (int k = 0; k < 3; k++) u[k] = L.u[k] + s[k];
        const int jt = m->body_joint[L.k], turn = jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL || jt == VT_JOINT_SPHERICAL;
        for (int a = m->body_vadr[L.k]; a < m->body_vadr[L.k] + m->body_nv[L.k]; a++) {
            const double *w = d->twist + 6 * a;
            double J[3];
            if (turn || vt_dof_turns(m, a)) vt_cross3(J, w, u);
            else vt_copy3(J, w + 3);
            double *col = d->Phiq + r + (size_t)a * (size_t)m->nc;
            for (int k = 0; k < 3; k++) col[k] += sign * J[k];
        }
    } while (vt_lever_up(&L, m, d));
}

/* The three point rows of a cut joint, P_b − P_a = 0 along the global axes e_k, at once */
static void cut_point_rows(const vt_model *m, vt_data *d, int r, const body_state *A, const body_state *B,
                           const point_memo *pa, const point_memo *pb, vt_form form, const s_block *Si, int parts)
{
    for (int k = 0; k < 3; k++) {
        double *pxa = d->Phix + 14 * (r + k), *pxb = pxa + 7, e[3] = {0, 0, 0}, jv[3] = {0, 0, 0}, jw[3];
        e[k] = 1.0;
        jv[k] = -1.0;
        if (parts & VT_CON_PHIX) {
            vt_cross3(jw, e, pa->s); /* −s_a × e */
            phix_from(pxa, A, jv, jw);
            vt_cross3(jw, pb->s, e);
            phix_from(pxb, B, e, jw);
        }
        d->Phi[r + k] = pb->P[k] - pa->P[k];
        d->Phit[r + k] = 0.0;
        if (parts & VT_CON_GAMMA) d->gamma[r + k] = pa->aP[k] - pb->aP[k];
        if (form == VT_FORM_DENSE && (parts & VT_CON_PHIQ)) phiq_row(m, d, r + k, VT_FORM_DENSE, Si);
    }
    if (form != VT_FORM_DENSE && (parts & VT_CON_PHIQ)) {
        point_jacobian_rows(m, d, r, A->id, pa->s, -1.0);
        point_jacobian_rows(m, d, r, B->id, pb->s, 1.0);
    }
}

vt_status vt_constraints(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_constraints");
    if (st) return st;
    return vt_constraints_impl(m, d, VT_FORM_DENSE);
}

vt_status vt_constraints_impl(const vt_model *m, vt_data *d, vt_form form)
{
    return vt_constraints_parts(m, d, form, VT_CON_ALL, NULL);
}

/* The joint and point drives' f, f', f'' at d->time into fd (3 per drive; an orientation
 * drive's entries untouched) */
vt_status vt_drive_values(const vt_model *m, vt_data *d, double *fd)
{
    const double t = d->time;
    if (!isfinite(t)) return vt_fail(d->message, VT_ERR_NONFINITE, "vt_constraints: time is %g", t);
    for (int k = 0; k < m->ndrive; k++) {
        if (vt_drive_turns(m->drive[k].type)) continue;
        const vt_status st = vt_function_eval_valid(fd + 3 * k, &m->drive[k].f, t);
        if (st)
            return vt_fail(d->message, st, "vt_constraints: drive %d: time function failed at t = %g (%s)", k, t,
                           vt_status_string(st));
    }
    return VT_OK;
}

/* Φ and Φ_t, and the parts asked for (VT_CON_*): Φ_x (the positions and t alone), Φ_q (the
 * positions and twists), γ (d's kinematics complete: the velocities and Ṡq̇); a part not asked
 * for may be left as it was. fd: the joint and point drives' functions at d->time
 * (vt_drive_values), or NULL to evaluate them here. */
vt_status vt_constraints_parts(const vt_model *m, vt_data *d, vt_form form, int parts, const double *fd)
{
    vt_status st;
    const int rates = parts & VT_CON_GAMMA, phiq = parts & VT_CON_PHIQ, phix = parts & VT_CON_PHIX;
    const double t = d->time;
    if (!isfinite(t)) return vt_fail(d->message, VT_ERR_NONFINITE, "vt_constraints: time is %g", t);
    double pdes[4] = {1, 0, 0, 0}, pdes_d[4] = {0}, pdes_dd[4] = {0};
    double prel[4] = {1, 0, 0, 0}, prel_d[4] = {0}, prel_dd0[4] = {0}; /* p_a* ⊗ p_b and its rates */
    const int drive_rows = vt_drive_rows(m);
    const size_t mark = vt_scratch_mark(d);
    s_block blk = {NULL, NULL, NULL}, *Si = form == VT_FORM_DENSE && phiq ? &blk : NULL;
    if (Si) {
        blk.S = VT_SCRATCH(d, double, 8 * (size_t)m->maxpath, "S block");
        blk.path = VT_SCRATCH(d, int, m->maxpath, "a body's path");
        if (!blk.path) return vt_scratch_fail(d, mark); /* after a failed allocation every later one fails */
        blk.row = blk.S + 7 * (size_t)m->maxpath;
    }
    if (phiq) memset(d->Phiq, 0, (size_t)m->nc * (size_t)m->nv * sizeof(double));
    point_jac jac[JAC_SLOTS];
    int jac_next = -1; /* the slots taken from the scratch at the first point drive */

    body_state A = {.id = -1}, B = {.id = -1}; /* loaded when a row's bodies change */
    point_memo ma = {.id = -1}, mb = {.id = -1};
    for (int r = 0; r < m->nc; r++) {
        const int kind = m->con_kind[r], owner = m->con_owner[r];
        if (A.id != m->con_body[2 * r]) load_body(&A, m, d, m->con_body[2 * r], rates), ma.id = -1;
        if (B.id != m->con_body[2 * r + 1]) load_body(&B, m, d, m->con_body[2 * r + 1], rates), mb.id = -1;
        const double *va = m->con_vec + 6 * r, *vb = va + 3, *sa = m->con_point + 6 * r, *sb = sa + 3;
        double *pxa = d->Phix + 14 * r, *pxb = pxa + 7;
        double f[3] = {0, 0, 0}, jv[3], jw[3];
        if ((kind == VT_ROW_JOINT || kind == VT_ROW_POINT) && r < drive_rows && fd) {
            vt_copy3(f, fd + 3 * owner);
        } else if ((kind == VT_ROW_JOINT || kind == VT_ROW_POINT) && r < drive_rows) {
            st = vt_function_eval_valid(f, &m->drive[owner].f, t);
            if (st)
                return vt_scratch_release(d, mark), vt_fail(d->message, st, "vt_constraints: drive %d: time function failed at t = %g (%s)",
                               owner, t, vt_status_string(st));
        }
        switch (kind) {
        case VT_ROW_JOINT: {
            const int dof = m->con_dof[r], i = m->dof_body[dof];
            d->Phi[r] = d->q[m->body_qadr[i] + dof - m->body_vadr[i]] - f[0];
            d->Phit[r] = -f[1];
            if (rates) d->gamma[r] = f[2];
            if (phix) {
                vt_R_row(m, d, dof, pxa, pxb);
                if (A.id == 0) memset(pxa, 0, 7 * sizeof(double));
            }
            if (phiq && form == VT_FORM_DENSE) phiq_row(m, d, r, VT_FORM_DENSE, Si);
            else if (phiq) d->Phiq[r + (size_t)dof * (size_t)m->nc] = 1.0; /* R S = I */
            break;
        }
        case VT_ROW_POINT: {
            if (r >= drive_rows && r == m->cut_row[owner]) { /* a cut joint's three point rows */
                cut_point_rows(m, d, r, &A, &B, point_motion_memo(&ma, &A, sa, rates), point_motion_memo(&mb, &B, sb, rates),
                               form, Si, parts);
                r += 2;
                continue;
            }
            const point_memo *pa = point_motion_memo(&ma, &A, sa, rates), *pb = point_motion_memo(&mb, &B, sb, rates);
            if (phix) {
                vt_cross3(jw, pa->s, va);
                for (int k = 0; k < 3; k++) { jv[k] = -va[k]; jw[k] = -jw[k]; }
                phix_from(pxa, &A, jv, jw);
                vt_cross3(jw, pb->s, va);
                phix_from(pxb, &B, va, jw);
            }
            if (phiq && form != VT_FORM_DENSE) {
                if (jac_next < 0) {
                    const size_t mp = (size_t)m->maxpath;
                    double *J = VT_SCRATCH(d, double, JAC_SLOTS * 3 * mp, "points' Jacobian columns");
                    int *rate = VT_SCRATCH(d, int, JAC_SLOTS * mp, "their rates");
                    if (!rate) return vt_scratch_fail(d, mark);
                    for (int k = 0; k < JAC_SLOTS; k++) jac[k] = (point_jac){.body = -1, .rate = rate + k * mp, .J = J + 3 * k * mp};
                    jac_next = 0;
                }
                if (A.id > 0) phiq_point(m, d, r, point_jac_get(jac, &jac_next, m, d, A.id, sa, pa->s), va, -1.0);
                if (B.id > 0) phiq_point(m, d, r, point_jac_get(jac, &jac_next, m, d, B.id, sb, pb->s), va, 1.0);
            }
            double dP[3], daP[3];
            for (int k = 0; k < 3; k++) dP[k] = pb->P[k] - pa->P[k];
            d->Phi[r] = vt_dot3(va, dP) - f[0];
            d->Phit[r] = -f[1];
            if (rates) {
                for (int k = 0; k < 3; k++) daP[k] = pb->aP[k] - pa->aP[k];
                d->gamma[r] = f[2] - vt_dot3(va, daP);
            }
            break;
        }
        case VT_ROW_DOT: {
            double u[3], ud[3] = {0, 0, 0}, udd[3] = {0, 0, 0}, v[3], vd[3] = {0, 0, 0}, vdd[3] = {0, 0, 0};
            vector_motion(&A, va, u, ud, udd, rates);
            vector_motion(&B, vb, v, vd, vdd, rates);
            memset(jv, 0, sizeof jv);
            vt_cross3(jw, u, v);
            if (phix) phix_from(pxa, &A, jv, jw);
            if (phiq && form != VT_FORM_DENSE) phiq_twist(m, d, r, A.id, jv, jw);
            vt_cross3(jw, v, u);
            if (phix) phix_from(pxb, &B, jv, jw);
            if (phiq && form != VT_FORM_DENSE) phiq_twist(m, d, r, B.id, jv, jw);
            d->Phi[r] = vt_dot3(u, v);
            d->Phit[r] = 0.0;
            if (rates) d->gamma[r] = -(vt_dot3(udd, v) + 2.0 * vt_dot3(ud, vd) + vt_dot3(u, vdd));
            break;
        }
        case VT_ROW_LINE: {
            double u[3], ud[3] = {0, 0, 0}, udd[3] = {0, 0, 0};
            double dd[3], ddd[3], dddd[3];
            vector_motion(&A, va, u, ud, udd, rates);
            const point_memo *pa = point_motion_memo(&ma, &A, sa, rates), *pb = point_motion_memo(&mb, &B, sb, rates);
            const double *s_a = pa->s, *s_b = pb->s;
            for (int k = 0; k < 3; k++) dd[k] = pb->P[k] - pa->P[k];
            double t1[3], t2[3];
            vt_cross3(t1, u, dd);
            vt_cross3(t2, s_a, u);
            for (int k = 0; k < 3; k++) { jv[k] = -u[k]; jw[k] = t1[k] - t2[k]; }
            if (phix) phix_from(pxa, &A, jv, jw);
            if (phiq && form != VT_FORM_DENSE) phiq_twist(m, d, r, A.id, jv, jw);
            vt_cross3(jw, s_b, u);
            if (phix) phix_from(pxb, &B, u, jw);
            if (phiq && form != VT_FORM_DENSE) phiq_twist(m, d, r, B.id, u, jw);
            d->Phi[r] = vt_dot3(u, dd);
            d->Phit[r] = 0.0;
            if (rates) {
                for (int k = 0; k < 3; k++) {
                    ddd[k] = pb->vP[k] - pa->vP[k];
                    dddd[k] = pb->aP[k] - pa->aP[k];
                }
                d->gamma[r] = -(vt_dot3(udd, dd) + 2.0 * vt_dot3(ud, ddd) + vt_dot3(u, dddd));
            }
            break;
        }
        case VT_ROW_ORIENT: {
            const int k = m->con_dof[r];
            if (k == 0) {
                st = prescribed_orientation(d->message, owner, &m->drive[owner], t, pdes, pdes_d, pdes_dd);
                if (st) return vt_scratch_release(d, mark), st;
            }
            if (m->drive[owner].type == VT_DRIVE_RELATIVE_ORIENTATION) {
                if (k == 0) relative_motion(&A, &B, prel, prel_d, prel_dd0, rates);
                relative_row(d, r, k, &A, &B, pdes, pdes_d, pdes_dd, prel, prel_d, prel_dd0, rates);
                if (phiq) phiq_row(m, d, r, form, Si);
                break;
            }
            double G[12];
            vt_euler_G(G, pdes);
            memset(pxa, 0, 7 * sizeof(double));
            memset(pxb, 0, 3 * sizeof(double));
            for (int c = 0; c < 4; c++) pxb[3 + c] = 2.0 * G[3 * c + k];
            d->Phi[r] = 2.0 * G_row(pdes, B.p, k);
            d->Phit[r] = 2.0 * G_row(pdes_d, B.p, k);
            if (rates)
                d->gamma[r] = -(2.0 * G_row(pdes_dd, B.p, k) + 4.0 * G_row(pdes_d, B.pd, k) + 2.0 * G_row(pdes, B.pdd0, k));
            if (phiq) phiq_row(m, d, r, form, Si);
            break;
        }
        case VT_ROW_COUPLING: { /* on the coordinates themselves: Φ_q = e_a − ratio e_b, Φ̈ = Φ_q q̈ (no γ) */
            const vt_coupling_def *c = &m->coupling[owner];
            const int a = m->body_vadr[c->body_a] + c->index_a, b = m->body_vadr[c->body_b] + c->index_b;
            const double qa = d->q[m->body_qadr[c->body_a] + c->index_a], qb = d->q[m->body_qadr[c->body_b] + c->index_b];
            memset(pxa, 0, 14 * sizeof(double)); /* its force acts through the rates (reactions.c) */
            d->Phi[r] = qa - c->ratio * qb - c->offset;
            d->Phit[r] = 0.0;
            if (rates) d->gamma[r] = 0.0;
            if (phiq) {
                d->Phiq[r + (size_t)a * (size_t)m->nc] += 1.0;
                d->Phiq[r + (size_t)b * (size_t)m->nc] -= c->ratio;
            }
            break;
        }
        default: { /* VT_ROW_NORM */
            memset(pxa, 0, 7 * sizeof(double));
            memset(pxb, 0, 3 * sizeof(double));
            for (int c = 0; c < 4; c++) pxb[3 + c] = 2.0 * B.p[c];
            d->Phi[r] = dot4(B.p, B.p) - 1.0;
            d->Phit[r] = 0.0;
            if (rates) d->gamma[r] = -2.0 * dot4(B.pd, B.pd);
            if (phiq) phiq_row(m, d, r, form, Si);
            break;
        }
        }
        if (phiq && form == VT_FORM_DENSE && kind != VT_ROW_JOINT && kind != VT_ROW_ORIENT && kind != VT_ROW_NORM) phiq_row(m, d, r, VT_FORM_DENSE, Si);
    }
    vt_scratch_release(d, mark);
    /* finite inputs can still overflow (q − f(t) with both near DBL_MAX, far points): scanned */
    const int nc = m->nc;
    const size_t nphiq = (size_t)m->nc * (size_t)m->nv; /* nc x nv: may pass an int */
    vt_finite_scan fs = {0}; /* as one scan: one test at the end */
    vt_finite_add(&fs, d->Phi, nc);
    vt_finite_add(&fs, d->Phit, nc);
    if (rates) vt_finite_add(&fs, d->gamma, nc);
    if (phix) vt_finite_add(&fs, d->Phix, 14 * nc);
    if (vt_finite_ok(&fs) && (!phiq || vt_all_finite(d->Phiq, nphiq))) return VT_OK;
    static const char *const owner_kind[] = {"drive", "cut joint", "coupling", "base body"};
    for (int r = 0; r < nc; r++) {
        int bad = !isfinite(d->Phi[r]) || !isfinite(d->Phit[r]) || (rates && !isfinite(d->gamma[r])) ||
                  (phix && !vt_all_finite(d->Phix + 14 * r, 14));
        for (int c = 0; c < m->nv && phiq && !bad; c++) bad = !isfinite(d->Phiq[r + (size_t)c * (size_t)nc]);
        if (bad)
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_constraints: row %d (%s %d) overflows (Φ, Φ_x, Φ_q, Φ_t or γ at t = %g)",
                           r, owner_kind[vt_row_owner_kind(m, r)], m->con_owner[r], t);
    }
    return VT_OK;
}

/* a body's S block, its product with a row and its path (the dense Φ_q), or the points' Jacobian
 * columns (the recursive Φ_q) */
size_t vt_constraints_scratch(const vt_model *m)
{
    const size_t mp = (size_t)m->maxpath;
    const size_t dense = VT_SCRATCH_BYTES(8 * mp, sizeof(double)) + VT_SCRATCH_BYTES(mp, sizeof(int));
    const size_t points = VT_SCRATCH_BYTES(JAC_SLOTS * 3 * mp, sizeof(double)) + VT_SCRATCH_BYTES(JAC_SLOTS * mp, sizeof(int));
    return dense > points ? dense : points;
}

/* the driven rates' prescribed q̈ = f'' (and their rows' Φ, Φ_t, γ) */
vt_status vt_drive_accelerations(const vt_model *m, vt_data *d)
{
    /* the arrays in locals: the time function's call would have them all read again per rate */
    const int nv = m->nv, *dof_drive = m->dof_drive, *drive_row = m->drive_row, *dof_body = m->dof_body;
    const int *qadr = m->body_qadr, *vadr = m->body_vadr;
    const vt_drive_def *drive = m->drive;
    const double t = d->time, *q = d->q;
    double *Phi = d->Phi, *Phit = d->Phit, *gamma = d->gamma, *qdd = d->qdd;
    for (int c = 0; c < nv; c++) {
        const int k = dof_drive[c];
        if (k < 0) continue;
        const int row = drive_row[k];
        double f[3];
        vt_status st = vt_function_eval_valid(f, &drive[k].f, t);
        if (st)
            return vt_fail(d->message, st, "vt_inverse_dynamics_recursive: drive %d: time function failed at t = %g", k,
                           d->time);
        const int i = dof_body[c];
        Phi[row] = q[qadr[i] + c - vadr[i]] - f[0];
        Phit[row] = -f[1];
        gamma[row] = f[2];
        qdd[c] = f[2];
    }
    return VT_OK;
}
