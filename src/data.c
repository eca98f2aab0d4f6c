/* The data of a model: one block laid out once, never resized (sizes are fixed when the
 * model is built), allocated by vt_data_create() or the caller's own (vt_data_init()). Also
 * the state helpers that are not a stage of the method: applied point loads, (7), and
 * advancing q along q̇ on the Euler-parameter sphere,
 *   ṗ = ½ E^T ω  ⇒  p(t + h) = [cos(h|ω|/2); sin(h|ω|/2) ω/|ω|] ⊗ p(t)   for constant ω.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* the next array, on a cache line (VT_DATA_ALIGN: the vectorized kernels' 8-double columns) */
static void *take(char *base, size_t *used, size_t bytes)
{
    *used = (*used + (VT_DATA_ALIGN - 1)) & ~(size_t)(VT_DATA_ALIGN - 1);
    void *p = base ? base + *used : NULL;
    *used += bytes;
    return p;
}

/* Scratch used by the stages, the largest of: gathered S block and M S block
 * (2 x 7 x maxpath) with the path block of M* (maxpath²); accelerations α with two wrenches
 * per body (15 (n+1)); the reaction sensitivity's (18 (n+1) + 6 ncut);
 * S^T products (8 maxpath + 8) with a Cartesian vector (7n); and on top of that, every
 * constraint row's wrench on its two bodies (12 nc). */
static size_t work_size(const vt_model *m)
{
    const size_t k = (size_t)m->maxpath, nb = (size_t)m->nbody + 1, nx = (size_t)m->nx;
    size_t w = 14 * k + k * k;
    if (15 * nb > w) w = 15 * nb; /* reactions: α, applied and children's wrenches */
    if (18 * nb + 6 * (size_t)m->ncut > w) w = 18 * nb + 6 * (size_t)m->ncut; /* reaction sensitivity */
    if (8 * k + 8 + nx > w) w = 8 * k + 8 + nx;
    /* the articulated-body solve and its reactions (recursive.c): per body Ī, I^A, p and A for
     * nc + 1 right sides, T, W̄, G; U, D, u and x per rate; S and λ */
    const size_t nv = (size_t)m->nv, nr = (size_t)m->nc + 1;
    const size_t aba = (79 + 12 * nr) * nb + (9 + 2 * nr) * nv + nr * nr + 13 * 8; /* aba_layout, its 13 arrays on 8 */
    if (aba > w) w = aba;
    return w + 12 * (size_t)m->nc; /* on top: the rows' wrenches (reactions.c) */
}

/* LAPACK workspace of the solve, from LAPACK's own workspace queries: dsytrf on the
 * augmented matrix, dgeqp3 on Φ_q^T (nv x nc) plus its copy and τ, and 3 N for dsyequb,
 * dsycon and dlansy, dgels on Φ_q. */
static int lapack_work_size(const vt_model *m, size_t *niwork)
{
    const int N = m->nv + m->nc, nv = m->nv, nc = m->nc;
    int info = 0, lw = -1, need = 3 * N;
    double q = 0.0, dummy = 0.0;
    int idummy = 0;
    dsytrf_rk_("L", &N, &dummy, &N, &dummy, &idummy, &q, &lw, &info, 1);
    if (info == 0 && (int)q > need) need = (int)q;
    if (nc > 0) {
        dgeqp3_(&nv, &nc, &dummy, &nv, &idummy, &dummy, &q, &lw, &info);
        const int qr = (info == 0 ? (int)q : 3 * nc + 1) + nv * nc + nc;
        if (qr > need) need = qr;
        /* dgelsd on the augmented matrix (N x N): the minimum-norm solve of redundant rows */
        int iq = 0;
        const int ldb2 = nc > nv ? nc : nv, one2 = 1;
        double rc = -1.0;
        int rank = 0;
        dgelsd_(&N, &N, &one2, &dummy, &N, &dummy, &N, &dummy, &rc, &rank, &q, &lw, &iq, &info);
        if (info == 0 && (int)q > need) need = (int)q;
        if (info == 0 && (size_t)iq > *niwork) *niwork = (size_t)iq;
        dgelsd_(&nc, &nv, &one2, &dummy, &nc, &dummy, &ldb2, &dummy, &rc, &rank, &q, &lw, &iq, &info);
        if (info == 0 && (int)q > need) need = (int)q; /* and on Φ_q itself (projections) */
        /* dgesvd on the scaled Φ_q (nc x nv) with its copy, U, V^T and σ: redundant rows */
        const int k = nc < nv ? nc : nv;
        dgesvd_("S", "S", &nc, &nv, &dummy, &nc, &dummy, &dummy, &nc, &dummy, &k, &q, &lw, &info, 1, 1);
        const int svd = (info == 0 ? (int)q : 5 * (nc + nv)) + nc * nv + nc * k + k * nv + k;
        if (svd > need) need = svd;
        /* dgels on Φ_q (nc x nv) for the Newton and velocity corrections */
        const int one = 1, ldb = nc > nv ? nc : nv;
        dgels_("N", &nc, &nv, &one, &dummy, &nc, &dummy, &ldb, &q, &lw, &info, 1);
        if (info == 0 && (int)q > need) need = (int)q;
    }
    return need + 1;
}

static size_t layout(const vt_model *m, vt_data *d, char *base)
{
    const size_t n = (size_t)m->nbody, nb = n + 1, nx = 7 * n, nv = (size_t)m->nv;
    size_t used = sizeof(vt_data);
    d->q = take(base, &used, (size_t)m->nq * sizeof(double));
    d->qd = take(base, &used, nv * sizeof(double));
    d->xfrc = take(base, &used, 6 * nb * sizeof(double));
    d->qfrc = take(base, &used, nv * sizeof(double));
    d->x = take(base, &used, nx * sizeof(double));
    d->xd = take(base, &used, nx * sizeof(double));
    d->A = take(base, &used, 9 * nb * sizeof(double));
    d->omega = take(base, &used, 3 * nb * sizeof(double));
    d->jaxis = take(base, &used, 9 * nb * sizeof(double));
    d->jsij = take(base, &used, 3 * nb * sizeof(double));
    d->jd = take(base, &used, 3 * nb * sizeof(double));
    d->jpoint = take(base, &used, 3 * nb * sizeof(double));
    d->twist = take(base, &used, 6 * nv * sizeof(double));
    d->S = take(base, &used, nx * nv * sizeof(double));
    d->Sdqd = take(base, &used, nx * sizeof(double));
    d->R = take(base, &used, nv * nx * sizeof(double));
    d->Mp = take(base, &used, 16 * nb * sizeof(double));
    d->Mstar = take(base, &used, nv * nv * sizeof(double));
    d->F = take(base, &used, nx * sizeof(double));
    d->h = take(base, &used, nx * sizeof(double));
    d->Q = take(base, &used, nv * sizeof(double));
    const size_t nc = (size_t)m->nc, nd = (size_t)m->ndrive, nk = (size_t)m->ncut, N = nv + nc;
    d->Phi = take(base, &used, nc * sizeof(double));
    d->Phix = take(base, &used, 14 * nc * sizeof(double));
    d->Phiq = take(base, &used, nc * nv * sizeof(double));
    d->Phit = take(base, &used, nc * sizeof(double));
    d->gamma = take(base, &used, nc * sizeof(double));
    d->qdd = take(base, &used, nv * sizeof(double));
    d->lambda = take(base, &used, nc * sizeof(double));
    d->xdd = take(base, &used, nx * sizeof(double));
    d->qfrc_drive = take(base, &used, nv * sizeof(double));
    d->drive_effort = take(base, &used, nd * sizeof(double));
    d->drive_force = take(base, &used, 3 * nd * sizeof(double));
    d->drive_moment = take(base, &used, 3 * nd * sizeof(double));
    d->jnt_force = take(base, &used, 3 * nb * sizeof(double));
    d->jnt_moment = take(base, &used, 3 * nb * sizeof(double));
    d->jnt_force_body = take(base, &used, 3 * nb * sizeof(double));
    d->jnt_moment_body = take(base, &used, 3 * nb * sizeof(double));
    d->cut_force = take(base, &used, 3 * nk * sizeof(double));
    d->cut_moment = take(base, &used, 3 * nk * sizeof(double));
    d->cut_force_body = take(base, &used, 3 * nk * sizeof(double));
    d->cut_moment_body = take(base, &used, 3 * nk * sizeof(double));
    d->nwork = work_size(m);
    d->work = take(base, &used, d->nwork * sizeof(double));
    d->kkt = take(base, &used, N * N * sizeof(double));
    d->kkt_rhs = take(base, &used, N * sizeof(double));
    d->kkt_scale = take(base, &used, 2 * N * sizeof(double)); /* scaling, then D's off-diagonal */
    size_t niwork = 33 * N + 64; /* pivots of dsycon, dgeqp3; dgelsd's iwork (raised by its query) */
    d->nlwork = lapack_work_size(m, &niwork);
    d->lwork = take(base, &used, (size_t)d->nlwork * sizeof(double));
    d->ipiv = take(base, &used, N * sizeof(int));
    d->liwork = take(base, &used, niwork * sizeof(int));
    d->qsave = take(base, &used, ((size_t)m->nq + nv) * sizeof(double));
    d->lambda_unique = take(base, &used, (nc ? nc : 1) * sizeof(int));
    d->jnt_unique = take(base, &used, 6 * nb * sizeof(int));
    d->cut_unique = take(base, &used, 6 * (nk ? nk : 1) * sizeof(int));
    d->nullvec = take(base, &used, (nc ? nc : 1) * sizeof(double));
    /* X = R11^-1 R12 (rank x (nc - rank) <= nc^2 / 4), row norms (nc), U_r (nc x nr <= nc^2) */
    d->red_work = take(base, &used, (2 * nc * nc + nc + 1) * sizeof(double));
    d->red_iwork = take(base, &used, (2 * nc + 1) * sizeof(int));
    return used;
}

/* Bytes from the buffer's start to its first VT_DATA_ALIGN boundary: the struct and every
 * array (take) start on a cache line. */
static size_t align_pad(const void *buffer)
{
    const uintptr_t a = (uintptr_t)buffer % VT_DATA_ALIGN;
    return a ? (size_t)(VT_DATA_ALIGN - a) : 0;
}

size_t vt_data_size(const vt_model *m)
{
    if (!m) return 0;
    vt_data probe;
    return layout(m, &probe, NULL) + (VT_DATA_ALIGN - 1); /* any start can be aligned */
}

/* The one path that lays out a data struct: vt_data_create() allocates the buffer and calls it. */
vt_status vt_data_init(vt_data **data, const vt_model *m, void *buffer, size_t size)
{
    if (!data) return VT_ERR_NULL;
    *data = NULL;
    if (!m || !buffer) return VT_ERR_NULL;
    vt_data probe;
    const size_t bytes = layout(m, &probe, NULL), pad = align_pad(buffer);
    if (size < pad || size - pad < bytes) return VT_ERR_BAD_SIZE; /* the buffer is left untouched */
    char *base = (char *)buffer + pad;
    memset(base, 0, bytes); /* zero: the structural zeros of S and R stay zero */
    vt_data *d = (vt_data *)base;
    layout(m, d, base);
    d->model = m;
    d->block = NULL; /* the caller's memory: vt_data_free() leaves it alone */
    /* the ground: identity rotation, at rest */
    d->A[0] = d->A[4] = d->A[8] = 1.0;
    vt_data_reset(m, d);
    *data = d;
    return VT_OK;
}

vt_status vt_data_create(vt_data **data, const vt_model *m)
{
    if (!data || !m) return VT_ERR_NULL;
    *data = NULL;
    const size_t bytes = vt_data_size(m);
    void *block = malloc(bytes); /* vt_data_init zeroes what it uses */
    if (!block) return VT_ERR_NO_MEMORY;
    const vt_status st = vt_data_init(data, m, block, bytes);
    if (st) {
        free(block);
        return st;
    }
    (*data)->block = block;
    return VT_OK;
}

void vt_data_free(vt_data *d)
{
    if (d && d->block) free(d->block); /* NULL for data in the caller's buffer: not ours to free */
}

vt_status vt_check_pair(const vt_model *m, vt_data *d, const char *who)
{
    if (!m || !d) return VT_ERR_NULL;
    if (d->model != m)
        return vt_fail(d->message, VT_ERR_MODEL_MISMATCH, "%s: data made for another model", who);
    return VT_OK;
}

vt_status vt_data_reset(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_data_reset");
    if (st) return st;
    memcpy(d->q, m->q0, (size_t)m->nq * sizeof(double));
    memset(d->qd, 0, (size_t)m->nv * sizeof(double));
    memset(d->xfrc, 0, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    memset(d->qfrc, 0, (size_t)m->nv * sizeof(double));
    d->ida_flag = 0;
    d->warning = 0;
    d->time = 0.0;
    d->message[0] = '\0';
    return VT_OK;
}

vt_status vt_add_point_load(const vt_model *m, vt_data *d, int body, const double point[3],
                            const double f[3], const double n[3])
{
    vt_status st = vt_check_pair(m, d, "vt_add_point_load");
    if (st) return st;
    if (body < 1 || body > m->nbody)
        return vt_fail(d->message, VT_ERR_BAD_INDEX, "vt_add_point_load: body %d not in 1..%d",
                       body, m->nbody);
    if (!point && f)
        return vt_fail(d->message, VT_ERR_NULL, "vt_add_point_load: point is NULL");
    if ((f && (!vt_all_finite(f, 3) || !vt_all_finite(point, 3))) || (n && !vt_all_finite(n, 3)))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_add_point_load: NaN or Inf in the load on body %d", body);
    double *w = d->xfrc + 6 * body;
    if (f) {
        /* moment about the centre of mass: s × f with s = A s' (the s̃ f of (7)) */
        double s[3];
        vt_mulmat3(s, d->A + 9 * body, point);
        vt_axpy3(w, 1.0, f);
        vt_addcross3(w + 3, s, f);
    }
    if (n) vt_axpy3(w + 3, 1.0, n);
    return VT_OK;
}

/* p ← exp(h ω) ⊗ p, normalized */
static void rotate_quat(double p[4], const double w[3], double h)
{
    const double a = sqrt(vt_dot3(w, w)) * h;
    if (a != 0.0) {
        double r[4], u[3] = {w[0], w[1], w[2]};
        const double inv = 1.0 / sqrt(vt_dot3(w, w));
        u[0] *= inv; u[1] *= inv; u[2] *= inv;
        vt_quat_axis_angle(r, u, a);
        vt_quat_mul(p, r, p);
    }
    const double s = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
    if (s > 0.0)
        for (int k = 0; k < 4; k++) p[k] /= s;
}

vt_status vt_integrate_q(double *q_out, const vt_model *m, const double *q, const double *v, double h)
{
    if (!q_out || !m || !q || !v) return VT_ERR_NULL;
    if (!isfinite(h) || !vt_all_finite(q, m->nq) || !vt_all_finite(v, m->nv)) return VT_ERR_NONFINITE;
    if (q_out != q) memcpy(q_out, q, (size_t)m->nq * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) {
        double *qi = q_out + m->body_qadr[i];
        const double *vi = v + m->body_vadr[i];
        switch (m->body_joint[i]) {
        case VT_JOINT_SPHERICAL:
            rotate_quat(qi, vi, h);
            break;
        case VT_JOINT_BASE: {
            double E[12], w[3];
            vt_euler_E(E, qi + 3);
            vt_mulE(w, E, vi + 3);
            w[0] *= 2; w[1] *= 2; w[2] *= 2; /* ω = 2 E ṗ */
            vt_axpy3(qi, h, vi);
            rotate_quat(qi + 3, w, h);
            break;
        }
        default:
            for (int k = 0; k < m->body_nq[i]; k++) qi[k] += h * vi[k];
        }
    }
    return VT_OK;
}
