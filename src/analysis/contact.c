/* Contacts: the contact set of a robot standing on points of its bodies (docs/contact.md), what
 * the distribution rule (analysis/contact_rule.c) works on at each instant.
 *
 * Each contact is a point p_c of body b (given in a frame's axes from its origin, or in b's axes
 * from its centre of mass)
 * on the ground or on another moving body k (a platform), its unit normal n_c (given, else opposite
 * to gravity) in global axes or k's, the tangents t₁ (the axis least along n_c, less its part along
 * it) and t₂ = n_c × t₁, and a unilateral contact's friction pyramid of k faces inscribed in its
 * cone, the rows
 *   n_c,   μ_c cos(π/k) n_c − d_j,   d_j = cos(2πj/k) t₁ + sin(2πj/k) t₂, j = 0 … k−1,
 * formed once here (the rule's inequalities n_c · f_c ≥ 0 and (μ_c cos(π/k) n_c − d_j) · f_c ≥ 0,
 * turned with k where the point touches one). A free joint's six rates (a floating root) are not
 * actuated, the others weighted by w_a. The set holds the rule's workspace too, sized for every
 * contact active, in one block with the definitions: nothing is allocated per instant. The
 * analyses over time keep the data's outputs here while they probe (vt_contacts_outputs), and
 * vt_contacts_unique tells which results the motion fixes and which the rule chooses.
 */
#include "analysis/contact.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/contact_rule.h"
#include "base/block.h"
#include "base/euler.h"
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
        /* the point in the frame's axes from its origin (a sole's corner on its link's frame):
         * the origin's offset from the centre of mass plus A(frame) p, as a payload's */
        double A[9];
        vt_euler_A(A, m->frame_quat + 4 * f);
        vt_mulmat3(point, A, def->point);
        for (int e = 0; e < 3; e++) point[e] += m->frame_point[3 * f + e];
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
        vt_contacts_jacobian(m, d, c, na);
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
            vt_contacts_add_load(d, c, c->on[k], z + 3 * k, c->xfrc);
            for (int e = 0; force_unique && e < 3; e++)
                if (fabs(z[3 * k + e]) > 1e-9) force_unique[3 * c->on[k] + e] = 0;
        }
        outputs(m, d, c, -1);
        if ((st = vt_motion_add_loads(m, d, c->xfrc))) break;
        const double *f = d->jnt_force, *mo = d->jnt_moment;
        const int nb = m->nbody + 1;
        double big = vt_contacts_max_abs(d->qfrc_drive, m->nv, 1);
        big = fmax(big, fmax(vt_contacts_max_abs(f, 3 * nb, 1), vt_contacts_max_abs(mo, 3 * nb, 1)));
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
