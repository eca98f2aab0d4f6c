/* Contacts: the given motion of a robot standing on points of its bodies (docs/contact.md).
 *
 * The instant's efforts without contact forces are τ⁰ = M*(q) q̈ − Q(q, q̇) (vt_inverse_dynamics_motion:
 * the given motion, eq (5) with q̈ known). A force f_c of the ground at a point p_c of body b adds
 * the generalized force J_cᵀ f_c, J_c's column a the velocity of p_c under rate a alone,
 *   J_c e_a = v_a + ω_a × (p_c − o)          (rate a's twist s_a = (ω_a, v_a) about o, eq (15)),
 * for the rates on b's path and 0 for the others; a point touching another moving body k (a
 * platform) rather than the ground takes J_c e_a less the same term on k's path (the velocity
 * relative to k: rates common to both paths cancel), −f_c acts on k at the same point, and the
 * normal and pyramid, given in k's axes, turn with it: n = A_k n', the rows A_k g'. So the
 * efforts with the contacts are
 *   τ = τ⁰ − Σ_c J_cᵀ f_c,
 * and a free joint's six rates (a floating root) are not actuated: τ_u = 0 on them, six linear
 * equations in the forces. Where more forces than equations remain (a quadruped on four feet),
 * the rule decides: the forces minimize
 *   ½ Σ_a∈A w_a τ_a² + ½ Σ_c w_c |f_c|²      (A: the actuated rates)
 *   = ½ fᵀ (J_Aᵀ W J_A + W_f) f − (J_Aᵀ W τ⁰_A)ᵀ f + const,
 * a strictly convex quadratic (W_f > 0), subject to
 *   J_uᵀ f = τ⁰_u                              (the unactuated rates),
 *   n_c · f_c ≥ 0,  μ_c cos(π/k) n_c · f_c − d_j · f_c ≥ 0, j = 0 … k−1   (a unilateral contact:
 *   it pushes, and its force stays in the pyramid of k faces inscribed in the friction cone, d_j
 *   = cos(2πj/k) t₁ + sin(2πj/k) t₂ the faces' outward directions in the tangent plane),
 * solved exactly: where no face binds, directly as the minimum under the equalities alone
 * (equality_minimum), else by the dual active-set method (numeric/qp.h). The forces are then applied as
 * loads (f_c at the centre of mass, (p_c − r_b) × f_c about it) by the instant's inward pass alone
 * (vt_motion_add_loads: a tree's; a model with cut joints or couplings is refused, its given
 * motion fixing the drives' rates only), so that
 * the efforts and every joint reaction of the data hold them (the unactuated rates' efforts
 * zero to round-off). No feasible forces: VT_ERR_CONTACT, the message naming the constraint the
 * solver could not meet — a contact that would have to pull, or slip, or unactuated rates the
 * active contacts cannot move.
 */
#include "analysis/contact.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/block.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "dense/reactions.h"
#include "numeric/qp.h"
#include "recursive/fused.h"

/* π, which ISO C's math.h does not name */
#define VT_CONTACT_PI 3.14159265358979323846

/* the most contacts of one set: the distribution is a dense problem of 3 per contact */
#define VT_CONTACTS_MAX 4096

struct vt_contacts {
    const vt_model *model;
    int n;
    int *body;            /* n */
    int *other;           /* n: 0 the ground, else the body touched (its normal and rows in its axes) */
    double *point;        /* body axes from the centre of mass (3n) */
    double *normal;       /* global (the other body's axes where it touches one), unit (3n) */
    double *tangent;      /* t₁, t₂: the same axes, unit, normal to it and to each other (6n) */
    vt_contact_kind *kind;
    double *mu, *weight;  /* n */
    int *faces;           /* n */
    double *cone;         /* each unilateral contact's rows, a 3-vector each: n, then μ cos(π/k) n − d_j
                           * for its k faces (3 (1 + k) from cone_at[c]) */
    int *cone_at;         /* n */
    char *name;           /* VT_NAME_MAX each (n) */
    double *effort_weight; /* nv */
    int nu, *unact;       /* the unactuated rates (a free joint's) */
    int nact, *act;       /* the others */
    /* the instant's workspace, sized for every contact active */
    int *on;              /* the active contacts' indices */
    int *active;          /* a run's schedule at one time (n) */
    int *row_of;          /* each rate's row: ≥ 0 in B (actuated), −1 − its row in Aeq (not) (nv) */
    double *sw;           /* √w_a of the actuated rates (nact) */
    double *B;            /* (√W J_A)ᵀ: 3 na x nact, row 3k + e the velocity of contact on[k]'s point
                           * along e under each actuated rate (a column), weighted */
    double *G, *c, *Aeq, *beq, *Ain, *bin, *f, *tau0, *wtau, *xfrc;
    double *lambda, *res, *slack;     /* the QP's multipliers (nu + rows), residuals (3n), slacks (nu + rows) */
    double *rownorm;                  /* the equalities' and inequalities' rows' 1-norms (nu + rows) */
    double *U, *sig, *Ar, *svd_work; /* the root's equations by their SVD: U (nu x nu), σ, the
                                      * independent rows Uᵣᵀ A_eq (nu x 3n), LAPACK's workspace */
    int svd_lwork;
    double *L;            /* the equality minimum's G = L Lᵀ (3n x 3n); vt_contacts_unique's U */
    double *saved;        /* vt_contacts_unique: the data's outputs while it probes (saved_len) */
    size_t saved_len;
    int *eu, *ju;         /* vt_contacts_unique's flags as they are found (nv, 6 (nbody + 1)) */
    int *row_contact;     /* the contact of each inequality row */
    int *row_face;        /* −1 for its normal row, else its face */
    void *qp;
    size_t qp_bytes;
};

vt_contact_def vt_default_contact_def(void)
{
    vt_contact_def d;
    memset(&d, 0, sizeof d);
    d.body = 1;
    d.kind = VT_CONTACT_UNILATERAL;
    d.mu = 1.0;
    d.faces = 4;
    d.weight = VT_CONTACT_WEIGHT;
    return d;
}

void vt_contacts_free(vt_contacts *c)
{
    free(c); /* one block */
}

int vt_contacts_count(const vt_contacts *c)
{
    return c ? c->n : 0;
}

/* contact.h's, for the analyses over time */
const vt_model *vt_contacts_model(const vt_contacts *c) { return c->model; }
int *vt_contacts_active(vt_contacts *c) { return c->active; }
const double *vt_contacts_loads(const vt_contacts *c) { return c->xfrc; }
static void outputs(const vt_model *m, vt_data *d, vt_contacts *c, int save);
void vt_contacts_outputs(const vt_model *m, vt_data *d, vt_contacts *c, int save) { outputs(m, d, c, save); }

int vt_find_contact(const vt_contacts *c, const char *name)
{
    if (!c || !name || !name[0]) return VT_ERR_NOT_FOUND;
    for (int k = 0; k < c->n; k++)
        if (strcmp(c->name + (size_t)VT_NAME_MAX * (size_t)k, name) == 0) return k;
    return VT_ERR_NOT_FOUND;
}

/* the inequality rows of the n definitions: a unilateral contact's normal and faces */
static int inequality_rows(const vt_contact_def *defs, int n)
{
    int r = 0;
    for (int k = 0; k < n; k++)
        if (defs[k].kind == VT_CONTACT_UNILATERAL) r += 1 + defs[k].faces;
    return r;
}

/* the set's arrays in one block (b->base NULL: the sizing pass) */
static void layout(vt_block *b, vt_contacts *c, const vt_model *m, int n, int nin)
{
    const size_t N = (size_t)n, nv = (size_t)m->nv, nx = 3 * N, nr = (size_t)(nin ? nin : 1);
    c->body = vt_block_take(b, N, sizeof(int));
    c->other = vt_block_take(b, N, sizeof(int));
    c->point = vt_block_take(b, 3 * N, sizeof(double));
    c->normal = vt_block_take(b, 3 * N, sizeof(double));
    c->tangent = vt_block_take(b, 6 * N, sizeof(double));
    c->kind = vt_block_take(b, N, sizeof(vt_contact_kind));
    c->mu = vt_block_take(b, N, sizeof(double));
    c->weight = vt_block_take(b, N, sizeof(double));
    c->faces = vt_block_take(b, N, sizeof(int));
    c->cone = vt_block_take(b, 3 * nr, sizeof(double));
    c->cone_at = vt_block_take(b, N, sizeof(int));
    c->name = vt_block_take(b, N, VT_NAME_MAX);
    c->effort_weight = vt_block_take(b, nv ? nv : 1, sizeof(double));
    c->unact = vt_block_take(b, nv ? nv : 1, sizeof(int));
    c->act = vt_block_take(b, nv ? nv : 1, sizeof(int));
    c->on = vt_block_take(b, N, sizeof(int));
    c->active = vt_block_take(b, N, sizeof(int));
    c->row_of = vt_block_take(b, nv ? nv : 1, sizeof(int));
    c->sw = vt_block_take(b, nv ? nv : 1, sizeof(double));
    c->B = vt_block_take(b, (nv ? nv : 1) * nx, sizeof(double));
    c->wtau = vt_block_take(b, nv ? nv : 1, sizeof(double));
    c->G = vt_block_take(b, nx * nx, sizeof(double));
    c->c = vt_block_take(b, nx, sizeof(double));
    c->Aeq = vt_block_take(b, (nv ? nv : 1) * nx, sizeof(double));
    c->beq = vt_block_take(b, nv ? nv : 1, sizeof(double));
    c->Ain = vt_block_take(b, nr * nx, sizeof(double));
    c->bin = vt_block_take(b, nr, sizeof(double));
    c->f = vt_block_take(b, nx, sizeof(double));
    c->tau0 = vt_block_take(b, nv ? nv : 1, sizeof(double));
    c->lambda = vt_block_take(b, (nv ? nv : 1) + nr, sizeof(double));
    c->res = vt_block_take(b, nx, sizeof(double));
    c->slack = vt_block_take(b, (nv ? nv : 1) + nr, sizeof(double));
    c->rownorm = vt_block_take(b, (nv ? nv : 1) + nr, sizeof(double));
    c->U = vt_block_take(b, (nv ? nv : 1) * (nv ? nv : 1), sizeof(double));
    c->sig = vt_block_take(b, nv ? nv : 1, sizeof(double));
    c->Ar = vt_block_take(b, (nv ? nv : 1) * nx, sizeof(double));
    c->svd_work = vt_block_take(b, (size_t)c->svd_lwork, sizeof(double));
    c->xfrc = vt_block_take(b, 6 * ((size_t)m->nbody + 1), sizeof(double));
    c->L = vt_block_take(b, nx * nx, sizeof(double));
    c->saved_len = 4 * nv + 24 * ((size_t)m->nbody + 1);
    c->saved = vt_block_take(b, c->saved_len, sizeof(double));
    c->eu = vt_block_take(b, nv ? nv : 1, sizeof(int));
    c->ju = vt_block_take(b, 6 * ((size_t)m->nbody + 1), sizeof(int));
    c->row_contact = vt_block_take(b, nr, sizeof(int));
    c->row_face = vt_block_take(b, nr, sizeof(int));
    c->qp = vt_block_take(b, c->qp_bytes, 1);
}

/* definition k checked and normalized into the set: its body and point (a frame's resolved), its
 * unit normal and tangents; 0 or a status with the message */
static vt_status take_def(vt_contacts *c, const vt_model *m, const vt_contact_def *def, int k, char *msg)
{
    const char *name = def->name ? def->name : "";
    if (strlen(name) >= VT_NAME_MAX)
        return vt_fail(msg, VT_ERR_BAD_NAME, "contact %d: a name of %zu bytes (at most %d)", k, strlen(name),
                       VT_NAME_MAX - 1);
    for (int h = 0; name[0] && h < k; h++)
        if (strcmp(c->name + (size_t)VT_NAME_MAX * (size_t)h, name) == 0)
            return vt_fail(msg, VT_ERR_BAD_NAME, "contact %d: the name \"%s\" is contact %d's", k, name, h);
    memcpy(c->name + (size_t)VT_NAME_MAX * (size_t)k, name, strlen(name) + 1);
    int body = def->body;
    double point[3];
    vt_copy3(point, def->point);
    if (def->frame) {
        const int f = vt_find_frame(m, def->frame);
        if (f < 0) return vt_fail(msg, VT_ERR_NOT_FOUND, "contact %d (%s): no frame \"%.64s\"", k, name, def->frame);
        body = m->frame_body[f];
        vt_copy3(point, m->frame_point + 3 * f);
    }
    if (body < 1 || body > m->nbody)
        return vt_fail(msg, VT_ERR_BAD_INDEX, "contact %d (%s): body %d is not a moving body (1..%d)", k, name, body,
                       m->nbody);
    if (def->other < 0 || def->other > m->nbody || def->other == body)
        return vt_fail(msg, VT_ERR_BAD_INDEX, "contact %d (%s): other %d is neither the ground (0) nor another moving "
                       "body (1..%d, not the contact's own %d)", k, name, def->other, m->nbody, body);
    if (!vt_all_finite(point, 3) || !vt_all_finite(def->normal, 3) || !isfinite(def->mu) || !isfinite(def->weight))
        return vt_fail(msg, VT_ERR_NONFINITE, "contact %d (%s): NaN or Inf in its definition", k, name);
    if (def->kind != VT_CONTACT_UNILATERAL && def->kind != VT_CONTACT_BILATERAL)
        return vt_fail(msg, VT_ERR_BAD_OPTION, "contact %d (%s): kind %d is neither unilateral nor bilateral", k, name,
                       (int)def->kind);
    if (def->kind == VT_CONTACT_UNILATERAL && (!(def->mu >= 0.0) || def->faces < 3 || def->faces > 64))
        return vt_fail(msg, VT_ERR_BAD_OPTION, "contact %d (%s): mu %g (>= 0) and faces %d (3 to 64)", k, name,
                       def->mu, def->faces);
    if (!(def->weight > 0.0))
        return vt_fail(msg, VT_ERR_BAD_OPTION, "contact %d (%s): weight %g is not > 0", k, name, def->weight);
    double *nrm = c->normal + 3 * k;
    vt_copy3(nrm, def->normal);
    if (!(vt_normalize(nrm, 3) > 0.0)) { /* opposite to gravity */
        for (int e = 0; e < 3; e++) nrm[e] = -m->gravity[e];
        if (!(vt_normalize(nrm, 3) > 0.0))
            return vt_fail(msg, VT_ERR_BAD_OPTION, "contact %d (%s): no normal given and no gravity to take it from",
                           k, name);
    }
    /* t₁: the global axis least along the normal, less its part along it; t₂ = n × t₁ */
    double *t1 = c->tangent + 6 * k, *t2 = t1 + 3;
    int least = 0;
    for (int e = 1; e < 3; e++)
        if (fabs(nrm[e]) < fabs(nrm[least])) least = e;
    for (int e = 0; e < 3; e++) t1[e] = (e == least) - nrm[least] * nrm[e];
    vt_normalize(t1, 3);
    vt_cross3(t2, nrm, t1);
    c->body[k] = body;
    c->other[k] = def->other;
    vt_copy3(c->point + 3 * k, point);
    c->kind[k] = def->kind;
    c->mu[k] = def->kind == VT_CONTACT_UNILATERAL ? def->mu : 0.0;
    c->faces[k] = def->kind == VT_CONTACT_UNILATERAL ? def->faces : 0;
    c->weight[k] = def->weight;
    return VT_OK;
}

vt_status vt_contacts_create(vt_contacts **out, const vt_model *m, const vt_contact_def *defs, int n,
                             const double *effort_weight, char *message)
{
    char sink[VT_MESSAGE_SIZE];
    char *msg = message ? message : sink;
    msg[0] = '\0';
    if (out) *out = NULL;
    if (!out || !m || !defs) return vt_fail(msg, VT_ERR_NULL, "vt_contacts_create: contacts, model or defs is NULL");
    if (n < 1 || n > VT_CONTACTS_MAX)
        return vt_fail(msg, VT_ERR_BAD_INDEX, "vt_contacts_create: %d contacts (1 to %d)", n, VT_CONTACTS_MAX);
    for (int k = 0; k < n; k++)
        if (defs[k].kind == VT_CONTACT_UNILATERAL && (defs[k].faces < 3 || defs[k].faces > 64))
            return vt_fail(msg, VT_ERR_BAD_OPTION, "contact %d: faces %d (3 to 64)", k, defs[k].faces);
    for (int a = 0; effort_weight && a < m->nv; a++)
        if (!(effort_weight[a] > 0.0) || !isfinite(effort_weight[a]))
            return vt_fail(msg, VT_ERR_BAD_OPTION,
                           "vt_contacts_create: effort_weight[%d] = %g is not a finite number > 0", a, effort_weight[a]);
    if (m->ncut > 0 || m->ncoupling > 0) /* their given motion gives the drives' rates, not every rate's */
        return vt_fail(msg, VT_ERR_BAD_OPTION,
                       "vt_contacts_create: the model has %d cut joints and %d couplings: contacts take a tree's given "
                       "motion (every rate's q̈; a URDF robot loaded with mimic = 0)", m->ncut, m->ncoupling);
    const int nin = inequality_rows(defs, n);
    /* dgesvd's least workspace for the root's equations (nu ≤ nv rows, ≤ 3n columns): 5 (nv + 3n) */
    const int svd_lwork = 5 * (m->nv + 3 * n) + 64;
    vt_contacts probe = {.qp_bytes = vt_qp_scratch_bytes(3 * n, m->nv, nin), .svd_lwork = svd_lwork};
    vt_block blk = {.base = NULL, .used = sizeof(vt_contacts), .align = 16}; /* calloc's alignment */
    layout(&blk, &probe, m, n, nin);
    if (blk.overflow) return vt_fail(msg, VT_ERR_NO_MEMORY, "vt_contacts_create: its size does not fit in memory");
    char *mem = calloc(1, blk.used);
    if (!mem) return vt_fail(msg, VT_ERR_NO_MEMORY, "vt_contacts_create: out of memory (%zu bytes)", blk.used);
    vt_contacts *c = (vt_contacts *)mem;
    c->qp_bytes = probe.qp_bytes;
    c->svd_lwork = svd_lwork;
    blk = (vt_block){.base = mem, .used = sizeof(vt_contacts), .align = 16};
    layout(&blk, c, m, n, nin);
    c->model = m;
    c->n = n;
    for (int k = 0; k < n; k++) {
        const vt_status st = take_def(c, m, &defs[k], k, msg);
        if (st) {
            free(mem);
            return st;
        }
    }
    for (int k = 0, r = 0; k < n; k++) { /* the pyramids' rows, once */
        c->cone_at[k] = r;
        const double *nrm = c->normal + 3 * k, *t1 = c->tangent + 6 * k, *t2 = t1 + 3;
        const int K = c->faces[k];
        const double mc = c->mu[k] * cos(VT_CONTACT_PI / K);
        for (int j = -1; K && j < K; j++, r++) {
            const double th = 2.0 * VT_CONTACT_PI * j / K, cs = cos(th), sn = sin(th);
            for (int e = 0; e < 3; e++) c->cone[3 * r + e] = j < 0 ? nrm[e] : mc * nrm[e] - (cs * t1[e] + sn * t2[e]);
        }
    }
    for (int a = 0; a < m->nv; a++) {
        c->effort_weight[a] = effort_weight ? effort_weight[a] : 1.0;
        if (m->body_joint[m->dof_body[a]] == VT_JOINT_FREE) {
            c->row_of[a] = -1 - c->nu;
            c->unact[c->nu++] = a;
        } else {
            c->row_of[a] = c->nact;
            c->sw[c->nact] = sqrt(c->effort_weight[a]);
            c->act[c->nact++] = a;
        }
    }
    *out = c;
    return VT_OK;
}

/* The active contacts' J_c, split by rows: the actuated rates' weighted, √W J_A into B (nact x
 * 3 na), the others' into Aeq (nu x 3 na): column 3k + e is component e of the velocity of
 * contact on[k]'s point under each rate of its body's path (0 off it) */
static void contact_jacobian(const vt_model *m, const vt_data *d, vt_contacts *c, int na)
{
    const size_t n = 3 * (size_t)na, nact = (size_t)c->nact, nu = (size_t)c->nu;
    memset(c->B, 0, (nact ? nact : 1) * n * sizeof(double));
    memset(c->Aeq, 0, (nu ? nu : 1) * n * sizeof(double));
    for (int k = 0; k < na; k++) {
        const int h = c->on[k], b = c->body[h];
        double r[3], po[3];
        vt_mulmat3(r, d->A + 9 * b, c->point + 3 * h);
        for (int e = 0; e < 3; e++) po[e] = d->xrel[6 * b + e] + r[e]; /* p − o */
        /* +1 on b's path; −1 on the touched body's (the velocity relative to it) */
        for (int side = 0, bb = b; side < 2 && bb > 0; side++, bb = c->other[h]) {
            const double sg = side ? -1.0 : 1.0;
            for (int a = m->body_vadr[bb] + m->body_nv[bb] - 1; a >= 0; a = m->dof_parent[a]) {
                const double *tw = d->twist + 6 * a;
                double v[3];
                vt_cross3(v, tw, po);
                const int row = c->row_of[a];
                for (int e = 0; e < 3; e++) {
                    const size_t col = 3 * (size_t)k + (size_t)e;
                    if (row >= 0) c->B[col + (size_t)row * n] += sg * c->sw[row] * (tw[3 + e] + v[e]);
                    else c->Aeq[(size_t)(-1 - row) + col * nu] += sg * (tw[3 + e] + v[e]);
                }
            }
        }
    }
}

/* the QP of the header: G (its lower triangle), c, the equalities and the inequalities of the na
 * active contacts; returns the inequality rows */
static int distribution(const vt_data *d, vt_contacts *c, int na)
{
    const int n = 3 * na, nact = c->nact;
    /* G = (√W J_A)ᵀ (√W J_A) + W_f, c = −(√W J_A)ᵀ √W τ⁰_A */
    for (int h = 0; h < nact; h++) c->wtau[h] = c->sw[h] * c->tau0[c->act[h]];
    if (nact > 0) {
        vt_dsyrk('L', 'N', n, nact, 1.0, c->B, n, 0.0, c->G, n);
        vt_dgemv('N', n, nact, -1.0, c->B, n, c->wtau, 1, 0.0, c->c, 1);
    } else {
        for (int j = 0; j < n; j++)
            for (int i = j; i < n; i++) c->G[(size_t)i + (size_t)j * (size_t)n] = 0.0;
        memset(c->c, 0, (size_t)n * sizeof(double));
    }
    for (int i = 0; i < n; i++) c->G[(size_t)i * (size_t)(n + 1)] += c->weight[c->on[i / 3]];
    /* J_uᵀ f = τ⁰_u (Aeq filled with B) */
    for (int h = 0; h < c->nu; h++) c->beq[h] = c->tau0[c->unact[h]];
    /* the unilateral contacts' rows: n·f ≥ 0, then μ cos(π/k) n·f − d_j·f ≥ 0 */
    int rows = 0;
    for (int k = 0; k < na; k++) {
        const int h = c->on[k];
        if (c->kind[h] == VT_CONTACT_UNILATERAL) rows += 1 + c->faces[h];
    }
    memset(c->Ain, 0, (size_t)(rows ? rows : 1) * (size_t)n * sizeof(double));
    int r = 0;
    for (int k = 0; k < na; k++) {
        const int h = c->on[k];
        if (c->kind[h] != VT_CONTACT_UNILATERAL) continue;
        const double *cone = c->cone + 3 * c->cone_at[h], *Ak = c->other[h] ? d->A + 9 * c->other[h] : NULL;
        for (int j = -1; j < c->faces[h]; j++, r++, cone += 3) {
            double g[3]; /* the row in global axes: turned with the touched body */
            if (Ak) vt_mulmat3(g, Ak, cone);
            else vt_copy3(g, cone);
            for (int e = 0; e < 3; e++) c->Ain[(size_t)r + (size_t)(3 * k + e) * (size_t)rows] = g[e];
            c->rownorm[c->nu + r] = fabs(g[0]) + fabs(g[1]) + fabs(g[2]);
            c->bin[r] = 0.0;
            c->row_contact[r] = h;
            c->row_face[r] = j;
        }
    }
    return rows;
}

/* the largest |a_k| (a NaN passed over: the checks below fail on it themselves) */
static double max_abs(const double *a, int n, int inc)
{
    double m = 0.0;
    for (int k = 0; k < n; k++) {
        const double v = fabs(a[(size_t)k * (size_t)inc]);
        m = v > m ? v : m;
    }
    return m;
}

/* G f + c − A_eqᵀ λ_eq − A_inᵀ λ_in = 0 (G's lower triangle; rows 0: λ_in zero) to 1e-8 of its
 * terms, amax the constraints' largest entry */
static int stationary(vt_contacts *c, const double *Aeq, int n, int meq, int rows, double amax)
{
    const int ldeq = c->nu ? c->nu : 1, ldin = rows ? rows : 1;
    const double tol = 1e-8, xmax = max_abs(c->f, n, 1);
    vt_dsymv('L', n, 1.0, c->G, n, c->f, 1, 0.0, c->res, 1);
    for (int i = 0; i < n; i++) c->res[i] += c->c[i];
    if (meq > 0) vt_dgemv('T', meq, n, -1.0, Aeq, ldeq, c->lambda, 1, 1.0, c->res, 1);
    if (rows > 0) vt_dgemv('T', rows, n, -1.0, c->Ain, ldin, c->lambda + meq, 1, 1.0, c->res, 1);
    double gmax = 0.0;
    for (int j = 0; j < n; j++) {
        const double g = max_abs(c->G + (size_t)j * (size_t)(n + 1), n - j, 1);
        gmax = g > gmax ? g : gmax;
    }
    const double lmax = max_abs(c->lambda, meq + rows, 1), cmax = max_abs(c->c, n, 1);
    const double scale = (double)n * gmax * xmax + cmax + (double)(meq + rows) * amax * lmax;
    for (int i = 0; i < n; i++)
        if (!(fabs(c->res[i]) <= tol * scale + DBL_MIN)) return 0;
    return 1;
}

/* The QP's answer checked against its own optimality conditions (a certificate, whatever the
 * solver did): the equalities and inequalities hold, the inequalities' multipliers are ≥ 0, and
 * G f + c − A_eqᵀ λ_eq − A_inᵀ λ_in = 0, each to 1e-8 of the terms it is made of. A round-off
 * failure of the QP is then refused, never returned as forces. */
static int optimal(vt_contacts *c, const double *Aeq, int n, int meq, int rows)
{
    const int ldeq = c->nu ? c->nu : 1, ldin = rows ? rows : 1;
    const double tol = 1e-8, xmax = max_abs(c->f, n, 1);
    double *s = c->slack; /* A f − b: the equalities' rows, then the inequalities' */
    memcpy(s, c->beq, (size_t)meq * sizeof(double));
    memcpy(s + meq, c->bin, (size_t)rows * sizeof(double));
    if (meq > 0) vt_dgemv('N', meq, n, 1.0, Aeq, ldeq, c->f, 1, -1.0, s, 1);
    if (rows > 0) vt_dgemv('N', rows, n, 1.0, c->Ain, ldin, c->f, 1, -1.0, s + meq, 1);
    double amax = 0.0;
    for (int r = 0; r < meq + rows; r++) { /* each constraint: its slack against its row's size */
        const double arow = r < meq ? max_abs(Aeq + r, n, ldeq) : max_abs(c->Ain + (r - meq), n, ldin);
        const double bv = r < meq ? c->beq[r] : c->bin[r - meq];
        const double size = tol * ((double)n * arow * xmax + fabs(bv)) + DBL_MIN;
        amax = arow > amax ? arow : amax;
        if (r < meq ? !(fabs(s[r]) <= size) : !(s[r] >= -size)) return 0;
        if (r >= meq && !(c->lambda[r] >= -tol * fabs(c->lambda[r]) - DBL_MIN)) return 0;
    }
    return stationary(c, Aeq, n, meq, rows, amax);
}

/* The common case, no face of a pyramid binding (feet well inside their cones, or bilateral
 * contacts): the minimum subject to the equalities alone, by the range-space solution of its KKT
 * system G f + c = A_eqᵀ λ, A_eq f = b with G = L Lᵀ (dpotf2),
 *   Z = A_eq L⁻ᵀ,   (Z Zᵀ) λ = b + Z L⁻¹ c   (Z Zᵀ = A_eq G⁻¹ A_eqᵀ = K Kᵀ, dpotf2),
 *   f = L⁻ᵀ (Zᵀ λ − L⁻¹ c),
 * is the QP's answer when it meets every inequality: with λ_in = 0 it meets the KKT conditions
 * of the whole problem, and a strictly convex problem has one minimizer. Returns 1 with c->f and
 * c->lambda set; 0 where the QP must decide: dependent equalities (two feet: Z Zᵀ singular, which
 * shows as a pivot of K below 1e-4 of the largest, an unpivoted Cholesky factor's pivots bounding
 * its eigenvalues), an inequality violated beyond its round-off (32 n ε of its terms, as the QP
 * judges), an equality missed by more than 1e-10 of its terms, or stationarity failing the
 * certificate's 1e-8. Nothing is iterated: the solution is exact but for round-off, as the QP's. */
static int equality_minimum(vt_contacts *c, int n, int rows)
{
    const int nu = c->nu;
    double *L = c->L, *Z = c->Ar, *K = c->U, *y = c->res, *lam = c->lambda;
    int info = 0;
    for (int j = 0; j < n; j++)
        memcpy(L + (size_t)j * (size_t)(n + 1), c->G + (size_t)j * (size_t)(n + 1), (size_t)(n - j) * sizeof(double));
    dpotf2_("L", &n, L, &n, &info, 1);
    if (info) return 0;
    memcpy(y, c->c, (size_t)n * sizeof(double));
    vt_dtrsv('L', 'N', 'N', n, L, n, y, 1); /* L⁻¹ c */
    memset(lam, 0, ((size_t)nu + (size_t)rows) * sizeof(double));
    if (nu > 0) {
        memcpy(Z, c->Aeq, (size_t)nu * (size_t)n * sizeof(double));
        vt_dtrsm('R', 'L', 'T', 'N', nu, n, 1.0, L, n, Z, nu);
        vt_dsyrk('L', 'N', nu, n, 1.0, Z, nu, 0.0, K, nu);
        dpotf2_("L", &nu, K, &nu, &info, 1);
        if (info) return 0;
        double kmin = HUGE_VAL, kmax = 0.0;
        for (int h = 0; h < nu; h++) {
            const double k = K[(size_t)h * (size_t)(nu + 1)];
            kmin = k < kmin ? k : kmin;
            kmax = k > kmax ? k : kmax;
        }
        if (!(kmin > 1e-4 * kmax)) return 0;
        memcpy(lam, c->beq, (size_t)nu * sizeof(double));
        vt_dgemv('N', nu, n, 1.0, Z, nu, y, 1, 1.0, lam, 1);
        vt_dtrsv('L', 'N', 'N', nu, K, nu, lam, 1);
        vt_dtrsv('L', 'T', 'N', nu, K, nu, lam, 1);
        memcpy(c->f, y, (size_t)n * sizeof(double));
        vt_dgemv('T', nu, n, 1.0, Z, nu, lam, 1, -1.0, c->f, 1); /* Zᵀ λ − L⁻¹ c */
    } else {
        for (int i = 0; i < n; i++) c->f[i] = -y[i];
    }
    vt_dtrsv('L', 'T', 'N', n, L, n, c->f, 1);
    /* as strict as the QP's own answer: every inequality to its round-off (32 n ε of its terms, a
     * face the minimum leaves by more is the QP's to bind) and every equality to 1e-10 of its
     * terms (a poorly conditioned Z Zᵀ costs digits the QP's factors keep); then the certificate */
    const double tau = 32.0 * (double)n * DBL_EPSILON, fm = max_abs(c->f, n, 1);
    double *sl = c->slack;
    memcpy(sl, c->beq, (size_t)nu * sizeof(double));
    memcpy(sl + nu, c->bin, (size_t)rows * sizeof(double));
    if (nu > 0) vt_dgemv('N', nu, n, 1.0, c->Aeq, nu, c->f, 1, -1.0, sl, 1);
    if (rows > 0) vt_dgemv('N', rows, n, 1.0, c->Ain, rows, c->f, 1, -1.0, sl + nu, 1);
    double *a1 = c->rownorm; /* the equalities' rows' 1-norms, column by column (distribution: the faces') */
    memset(a1, 0, (size_t)nu * sizeof(double));
    for (int i = 0; i < n; i++)
        for (int h = 0; h < nu; h++) a1[h] += fabs(c->Aeq[(size_t)h + (size_t)i * (size_t)nu]);
    for (int r = 0; r < nu + rows; r++) {
        const double terms = a1[r] * fm + fabs(r < nu ? c->beq[r] : c->bin[r - nu]);
        if (r < nu ? !(fabs(sl[r]) <= 1e-10 * terms) : !(sl[r] >= -tau * terms - DBL_MIN)) return 0;
    }
    /* the equalities and inequalities hold, the inequalities' multipliers are zero: what is left
     * of the certificate (optimal) is stationarity */
    return stationary(c, c->Aeq, n, nu, 0, max_abs(c->Aeq, nu * n, 1));
}

/* body b's load of the ground's force f at contact h's point: f at the centre of mass and
 * (p − r_b) × f about it, added into xfrc; where the point touches another body k, −f on k at
 * the same point, (p − r_k) × (−f) about k's centre, p − r_k = (p − o) − (r_k − o) */
static void add_load(const vt_data *d, const vt_contacts *c, int h, const double f[3], double *xfrc)
{
    const int b = c->body[h], k = c->other[h];
    double r[3], n[3];
    vt_mulmat3(r, d->A + 9 * b, c->point + 3 * h);
    vt_cross3(n, r, f);
    for (int e = 0; e < 3; e++) {
        xfrc[6 * b + e] += f[e];
        xfrc[6 * b + 3 + e] += n[e];
    }
    if (k == 0) return;
    for (int e = 0; e < 3; e++) r[e] += d->xrel[6 * b + e] - d->xrel[6 * k + e];
    vt_cross3(n, r, f);
    for (int e = 0; e < 3; e++) {
        xfrc[6 * k + e] -= f[e];
        xfrc[6 * k + 3 + e] -= n[e];
    }
}

/* The root's equations J_uᵀ f = τ⁰_u (A_eq f = b) hold for some f only if b lies in A_eq's range,
 * and their dependent combinations (two feet: the moment about the line through them) must not
 * reach the QP as equations, whose round-off it would take for a direction. By the SVD
 * A_eq = U Σ Vᵀ: the rows with σ_k > 64 (nu + n) ε σ₁ are independent, and Uᵣᵀ A_eq f = Uᵣᵀ b
 * (into c->Ar, c->beq: *meq rows) says what they say; the rest of b, U₀ᵀ b, is what no force gives:
 * beyond 1e-9 of |b| and of σ₁ |f| ~ |b| the motion cannot be carried (*culprit the rate most
 * in it, else −1). Returns a status only when LAPACK fails. */
static vt_status independent_rows(vt_data *d, vt_contacts *c, int n, int *meq, int *culprit)
{
    const int nu = c->nu;
    *meq = 0;
    *culprit = -1;
    if (nu == 0) return VT_OK;
    double *A = c->Ar; /* dgesvd overwrites its matrix: A_eq copied, then the reduced rows */
    memcpy(A, c->Aeq, (size_t)nu * (size_t)n * sizeof(double));
    const int k = nu < n ? nu : n;
    int info = 0, one = 1;
    double dummy = 0.0;
    dgesvd_("A", "N", &nu, &n, A, &nu, c->sig, c->U, &nu, &dummy, &one, c->svd_work, &c->svd_lwork, &info, 1, 1);
    if (info) return vt_fail(d->message, VT_ERR_LAPACK, "vt_inverse_dynamics_contacts: dgesvd info %d", info);
    const double tol = 64.0 * (double)(nu + n) * DBL_EPSILON * c->sig[0];
    int r = 0;
    while (r < k && c->sig[r] > tol) r++;
    double bb = 0.0, out = 0.0, worst = 0.0;
    for (int h = 0; h < nu; h++) bb += c->beq[h] * c->beq[h];
    for (int j = r; j < nu; j++) { /* b's part along the directions no force reaches */
        double u = 0.0;
        for (int h = 0; h < nu; h++) u += c->U[(size_t)h + (size_t)j * (size_t)nu] * c->beq[h];
        out += u * u;
        for (int h = 0; h < nu; h++)
            if (fabs(c->U[(size_t)h + (size_t)j * (size_t)nu] * u) > worst) {
                worst = fabs(c->U[(size_t)h + (size_t)j * (size_t)nu] * u);
                *culprit = h;
            }
    }
    if (!(sqrt(out) <= 1e-9 * sqrt(bb) + DBL_MIN)) return VT_OK; /* *culprit set: refused */
    *culprit = -1;
    /* the independent rows Uᵣᵀ A_eq (r x n, leading dimension nu) and right sides Uᵣᵀ b */
    double *ub = c->wtau; /* distribution's, done with */
    for (int j = 0; j < r; j++) {
        double u = 0.0;
        for (int h = 0; h < nu; h++) u += c->U[(size_t)h + (size_t)j * (size_t)nu] * c->beq[h];
        ub[j] = u;
    }
    vt_dgemm('T', 'N', r, n, nu, 1.0, c->U, nu, c->Aeq, nu, 0.0, A, nu);
    memcpy(c->beq, ub, (size_t)r * sizeof(double));
    *meq = r;
    return VT_OK;
}

/* the message of an infeasible distribution: what the culprit constraint asks */
static vt_status infeasible(const vt_model *m, vt_data *d, const vt_contacts *c, int culprit)
{
    if (culprit < c->nu) {
        const int a = c->unact[culprit < 0 ? 0 : culprit], b = m->dof_body[a];
        const char *joint = m->joint_name + (size_t)VT_NAME_MAX * (size_t)b;
        return vt_fail(d->message, VT_ERR_CONTACT,
                       "vt_inverse_dynamics_contacts: the active contacts cannot give the unactuated rate %d's "
                       "force %g (the free joint of body %d \"%.64s\"): no forces on the ground carry the motion",
                       a, c->tau0[a], b, joint[0] ? joint : m->body_name + (size_t)VT_NAME_MAX * (size_t)b);
    }
    const int r = culprit - c->nu, h = c->row_contact[r];
    const char *name = c->name + (size_t)VT_NAME_MAX * (size_t)h;
    if (c->row_face[r] < 0)
        return vt_fail(d->message, VT_ERR_CONTACT,
                       "vt_inverse_dynamics_contacts: contact %d \"%.64s\" (body %d) would have to pull on the ground",
                       h, name, c->body[h]);
    return vt_fail(d->message, VT_ERR_CONTACT,
                   "vt_inverse_dynamics_contacts: contact %d \"%.64s\" (body %d) would have to slip: its force "
                   "leaves the friction pyramid (mu %g, %d faces)",
                   h, name, c->body[h], c->mu[h], c->faces[h]);
}

/* The forces by the QP (where equality_minimum could not decide): the root's equations as they
 * are; where the QP finds them inconsistent or its answer fails the optimality conditions, again
 * by their independent rows (independent_rows). VT_OK with c->f, else the status and message. */
static vt_status by_qp(const vt_model *m, vt_data *d, vt_contacts *c, int n, int rows)
{
    vt_status st;
    int culprit = -1, meq = c->nu;
    const double *Aeq = c->Aeq;
    vt_qp_result qs = vt_qp_solve(n, c->G, n, c->c, meq, Aeq, c->nu ? c->nu : 1, c->beq, rows, c->Ain,
                                  rows ? rows : 1, c->bin, c->f, c->lambda, NULL, &culprit, c->qp, c->qp_bytes, NULL);
    if ((qs == VT_QP_INFEASIBLE && culprit < c->nu) || (qs == VT_QP_OPTIMAL && !optimal(c, Aeq, n, meq, rows))) {
        if ((st = independent_rows(d, c, n, &meq, &culprit))) return st;
        if (culprit >= 0) return infeasible(m, d, c, culprit);
        Aeq = c->Ar;
        qs = vt_qp_solve(n, c->G, n, c->c, meq, Aeq, c->nu ? c->nu : 1, c->beq, rows, c->Ain, rows ? rows : 1, c->bin,
                         c->f, c->lambda, NULL, &culprit, c->qp, c->qp_bytes, NULL);
        if (qs == VT_QP_OPTIMAL && !optimal(c, Aeq, n, meq, rows))
            return vt_fail(d->message, VT_ERR_SINGULAR,
                           "vt_inverse_dynamics_contacts: the distribution's answer does not meet its optimality "
                           "conditions to round-off (an ill-conditioned problem: contacts whose forces cancel, "
                           "weights far apart); no forces returned");
    }
    if (qs == VT_QP_INFEASIBLE && culprit < meq) culprit = 0; /* an equality: the root's wrench */
    else if (qs == VT_QP_INFEASIBLE) culprit += c->nu - meq;   /* an inequality, as infeasible() counts */
    if (qs == VT_QP_INFEASIBLE) return infeasible(m, d, c, culprit);
    if (qs != VT_QP_OPTIMAL)
        return vt_fail(d->message, qs == VT_QP_NONFINITE ? VT_ERR_NONFINITE : VT_ERR_SINGULAR,
                       "vt_inverse_dynamics_contacts: the distribution's problem could not be solved (%s)",
                       vt_qp_result_string(qs));
    return VT_OK;
}

vt_status vt_inverse_dynamics_contacts(const vt_model *m, vt_data *d, vt_contacts *c, const int *active, double *force)
{
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_contacts");
    if (st) return st;
    if (!c) return vt_fail(d->message, VT_ERR_NULL, "vt_inverse_dynamics_contacts: contacts is NULL");
    if (c->model != m)
        return vt_fail(d->message, VT_ERR_MODEL_MISMATCH,
                       "vt_inverse_dynamics_contacts: contacts made for another model");
    if ((st = vt_inverse_dynamics_motion(m, d))) return st;
    const size_t nv = (size_t)m->nv, nxf = 6 * ((size_t)m->nbody + 1);
    memcpy(c->tau0, d->qfrc_drive, nv * sizeof(double));
    int na = 0;
    for (int k = 0; k < c->n; k++)
        if (!active || active[k]) c->on[na++] = k;
    memset(c->xfrc, 0, nxf * sizeof(double)); /* the loads (none in the air), vt_contacts_loads's */
    if (na == 0) { /* no contact on the ground: in free flight the unactuated rates need nothing */
        double big = 0.0, scale = 0.0;
        int worst = 0;
        for (int h = 0; h < c->nu; h++)
            if (fabs(c->tau0[c->unact[h]]) > big) {
                big = fabs(c->tau0[c->unact[h]]);
                worst = h;
            }
        for (int a = 0; a < m->nv; a++) scale = fmax(scale, fabs(c->tau0[a]));
        if (big > 64.0 * DBL_EPSILON * (1.0 + scale)) return infeasible(m, d, c, worst);
        if (force) memset(force, 0, 3 * (size_t)c->n * sizeof(double));
        return VT_OK;
    }
    const int n = 3 * na;
    contact_jacobian(m, d, c, na);
    const int rows = distribution(d, c, na);
    /* the equality-constrained minimum where no face binds, else the QP */
    if (!equality_minimum(c, n, rows) && (st = by_qp(m, d, c, n, rows))) return st;
    /* the forces applied as loads by the instant's inward pass alone (it is linear in the loads) */
    for (int k = 0; k < na; k++) add_load(d, c, c->on[k], c->f + 3 * k, c->xfrc);
    if ((st = vt_motion_add_loads(m, d, c->xfrc))) return st;
    if (force) {
        memset(force, 0, 3 * (size_t)c->n * sizeof(double));
        for (int k = 0; k < na; k++) vt_copy3(force + 3 * c->on[k], c->f + 3 * k);
    }
    return VT_OK;
}

/* The data's outputs that vt_motion_add_loads changes: qfrc_drive, limit_excess, and each joint's
 * reaction and total in both axes; into (save 1) or back from (0) c->saved, or zeroed (−1) */
static void outputs(const vt_model *m, vt_data *d, vt_contacts *c, int save)
{
    const size_t nv = (size_t)m->nv, nb = 3 * ((size_t)m->nbody + 1);
    double *const a[10] = {d->qfrc_drive, d->limit_excess, d->jnt_force, d->jnt_moment, d->jnt_force_body,
                           d->jnt_moment_body, d->jnt_force_total, d->jnt_moment_total, d->jnt_force_total_body,
                           d->jnt_moment_total_body};
    double *s = c->saved;
    for (int k = 0; k < 10; k++) {
        const size_t len = k == 0 ? nv : k == 1 ? 3 * nv : nb;
        if (save > 0) memcpy(s, a[k], len * sizeof(double));
        else if (save == 0) memcpy(a[k], s, len * sizeof(double));
        else memset(a[k], 0, len * sizeof(double));
        s += len;
    }
}

/* The forces the root's equations allow are f + N z, N a basis of A_eq's null space (the
 * columns of U past the rank r of A_eqᵀ = U Σ Vᵀ, dgesvd; every direction when nothing is
 * unactuated). A result is fixed by the motion and the contacts when no direction changes it:
 * a force component when N's row is 0, the efforts and reactions when the loads of N's column
 * leave them, each by the inward pass of the loads alone (vt_motion_add_loads on zeroed outputs:
 * the change itself), beyond 1e-9 of the largest change a unit direction makes. */
vt_status vt_contacts_unique(const vt_model *m, vt_data *d, vt_contacts *c, const int *active, int *effort_unique,
                             int *force_unique)
{
    vt_status st = vt_check_pair(m, d, "vt_contacts_unique");
    if (st) return st;
    if (!c) return vt_fail(d->message, VT_ERR_NULL, "vt_contacts_unique: contacts is NULL");
    if (c->model != m)
        return vt_fail(d->message, VT_ERR_MODEL_MISMATCH, "vt_contacts_unique: contacts made for another model");
    if (d->route != VT_ROUTE_MOTION) /* the set's model is a tree: vt_contacts_create refuses the rest */
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "vt_contacts_unique: needs vt_inverse_dynamics_contacts's instant on this data just before");
    int na = 0;
    for (int k = 0; k < c->n; k++)
        if (!active || active[k]) c->on[na++] = k;
    const int n = 3 * na, nu = c->nu, nj = 6 * (m->nbody + 1);
    for (int a = 0; a < m->nv; a++) c->eu[a] = 1;
    for (int k = 0; k < nj; k++) c->ju[k] = 1;
    if (force_unique)
        for (int k = 0; k < 3 * c->n; k++) force_unique[k] = 1;
    int r = 0;
    double *U = c->L;
    if (n > 0) {
        contact_jacobian(m, d, c, na);
        if (nu > 0) { /* A_eqᵀ (n x nu) into Ar, its left singular vectors into U */
            for (int h = 0; h < nu; h++)
                for (int i = 0; i < n; i++) c->Ar[(size_t)i + (size_t)h * (size_t)n] = c->Aeq[(size_t)h + (size_t)i * (size_t)nu];
            int info = 0, one = 1, nn = n, mu = nu;
            double dummy = 0.0;
            dgesvd_("A", "N", &nn, &mu, c->Ar, &nn, c->sig, U, &nn, &dummy, &one, c->svd_work, &c->svd_lwork, &info, 1, 1);
            if (info) return vt_fail(d->message, VT_ERR_LAPACK, "vt_contacts_unique: dgesvd info %d", info);
            const int k = nu < n ? nu : n;
            const double tol = 64.0 * (double)(nu + n) * DBL_EPSILON * c->sig[0];
            while (r < k && c->sig[r] > tol) r++;
        } else {
            memset(U, 0, (size_t)n * (size_t)n * sizeof(double));
            for (int i = 0; i < n; i++) U[(size_t)i * (size_t)(n + 1)] = 1.0;
        }
    }
    const size_t nxf = 6 * ((size_t)m->nbody + 1);
    if (r < n) outputs(m, d, c, 1);
    for (int j = r; j < n; j++) { /* each direction the rule chooses along */
        const double *z = U + (size_t)j * (size_t)n;
        memset(c->xfrc, 0, nxf * sizeof(double));
        for (int k = 0; k < na; k++) {
            add_load(d, c, c->on[k], z + 3 * k, c->xfrc);
            for (int e = 0; force_unique && e < 3; e++)
                if (fabs(z[3 * k + e]) > 1e-9) force_unique[3 * c->on[k] + e] = 0;
        }
        outputs(m, d, c, -1);
        if ((st = vt_motion_add_loads(m, d, c->xfrc))) break;
        const double *f = d->jnt_force, *mo = d->jnt_moment;
        const int nb = m->nbody + 1;
        double big = max_abs(d->qfrc_drive, m->nv, 1);
        big = fmax(big, fmax(max_abs(f, 3 * nb, 1), max_abs(mo, 3 * nb, 1)));
        const double tol = 1e-9 * big + DBL_MIN;
        for (int a = 0; a < m->nv; a++)
            if (fabs(d->qfrc_drive[a]) > tol) c->eu[a] = 0;
        for (int i = 0; i < nb; i++)
            for (int e = 0; e < 3; e++) {
                if (fabs(f[3 * i + e]) > tol) c->ju[6 * i + e] = 0;
                if (fabs(mo[3 * i + e]) > tol) c->ju[6 * i + 3 + e] = 0;
            }
    }
    if (r < n) {
        outputs(m, d, c, 0);
        (void)vt_reactions_unique(m, d); /* the limits and warning as the instant left them (a tree: no rows) */
    }
    if (st) return st;
    memcpy(d->jnt_unique, c->ju, (size_t)nj * sizeof(int));
    if (effort_unique) memcpy(effort_unique, c->eu, (size_t)m->nv * sizeof(int));
    return VT_OK;
}
