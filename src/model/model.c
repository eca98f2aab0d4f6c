/* The model: vt_builder_build lays a builder's definitions (model/builder.c) out as one block
 * (base/block.h) and builds the constraint rows; the model without drives, the finds by name,
 * the rows' kinds and owners, vt_model_free.
 *
 * Body i (1..n) has Cartesian coordinates x^i = [r^i; p^i] (1) and relative coordinates q^i
 * of its joint to its reference body j < i (Table 1). The coordinates per joint kind:
 *   base          q = [r; p] (7), q̇ = [ṙ; ṗ] (7)     (reference must be the ground)
 *   revolute      θ about e1                          (1, 1)
 *   universal     θ1 about e1 (on j), θ2 about e2 (on i) (2, 2), e1 ⟂ e2
 *   spherical     relative Euler parameters (4), relative angular velocity in j's axes (3)
 *   translational s along e1                          (1, 1)
 *   cylindrical   θ about e1, then s along e1          (2, 2)
 * The path of body i is the list of rates of the joints between the ground and i: the
 * columns of S that are non-zero in body i's rows (S is block lower triangular in tree order,
 * the paper's "reference matrix"). The model keeps each path's length (body_pathnum) and each
 * rate's link to the one before it on its path (dof_parent), not the lists themselves
 * (n(n+1)/2 rates for a chain of n): a path is walked down from its body's last rate, so the
 * model is O(n).
 * The drives' spline samples (t, y, f'' of each spline, copied from the builder's blocks) are a
 * part of the model's one block.
 */
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "model/model.h"
#include "base/block.h"
#include "base/checked.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/builder.h"

int vt_drive_rows(const vt_model *m)
{
    if (m->ndrive == 0) return 0;
    const int last = m->ndrive - 1;
    return m->drive_row[last] + vt_drive_nrows(&m->drive[last]);
}

/* the given motion (vt_inverse_dynamics_motion) reads the time where a loop or coupling keeps a
 * point or orientation drive's rows */
int vt_motion_time_drive(const vt_model *m)
{
    if (!m) return VT_ERR_NULL;
    if (m->ncut == 0 && m->ncoupling == 0) return -1; /* a tree's given motion reads no drive */
    for (int k = 0; k < m->ndrive; k++) /* a joint drive's row takes the given q̈ */
        if (m->drive[k].type != VT_DRIVE_JOINT) return k;
    return -1;
}

int vt_row_owner_kind(const vt_model *m, int row)
{
    if (row < vt_drive_rows(m)) return VT_OWNER_DRIVE;
    if (m->ncoupling && row >= m->coupling_row[0] && row <= m->coupling_row[m->ncoupling - 1]) return VT_OWNER_COUPLING;
    if (m->ncut && row < m->cut_row[m->ncut - 1] + vt_cut_nrows(&m->cut[m->ncut - 1])) return VT_OWNER_CUT;
    return VT_OWNER_BASE;
}

/* two unit vectors h1, h2 with (u, h1, h2) orthonormal */
static void perpendiculars(double h1[3], double h2[3], const double u[3])
{
    const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    vt_cross3(h1, u, fabs(u[0]) < 0.6 ? ex : ey);
    vt_normalize(h1, 3);
    vt_cross3(h2, u, h1);
}

/* v_b = A0^T v_a: a vector of a's axes carried onto b's axes in the assembled pose */
static void onto_b(double vb[3], const double q0[4], const double va[3])
{
    double A0[9];
    vt_euler_A(A0, q0);
    vt_mulmat3t(vb, A0, va);
}

static int add_row(vt_model *m, int r, int kind, int a, int b, int owner)
{
    m->con_kind[r] = kind;
    m->con_body[2 * r] = a;
    m->con_body[2 * r + 1] = b;
    m->con_owner[r] = owner;
    return r + 1;
}

/* the constraint rows of every drive, cut joint and base body (order: drives, cuts, bases) */
static void build_rows(vt_model *m)
{
    int r = 0;
    for (int k = 0; k < m->ndrive; k++) {
        const vt_drive_def *d = &m->drive[k];
        m->drive_row[k] = r;
        switch (d->type) {
        case VT_DRIVE_JOINT:
            m->con_dof[r] = m->body_vadr[d->body] + d->index;
            r = add_row(m, r, VT_ROW_JOINT, m->body_parent[d->body], d->body, k);
            break;
        case VT_DRIVE_POINT:
            m->con_vec[6 * r + d->index] = 1.0;
            memcpy(m->con_point + 6 * r + 3, d->point, 3 * sizeof(double));
            r = add_row(m, r, VT_ROW_POINT, 0, d->body, k);
            break;
        default: /* orientation: absolute (a = ground) or relative to body a = reference */
            for (int c = 0; c < 3; c++) {
                m->con_dof[r] = c;
                r = add_row(m, r, VT_ROW_ORIENT, d->type == VT_DRIVE_RELATIVE_ORIENTATION ? d->reference : 0, d->body, k);
            }
        }
    }
    for (int k = 0; k < m->ncut; k++) {
        const vt_cut_joint_def *c = &m->cut[k];
        const int a = c->body_a, b = c->body_b, jt = c->joint;
        double h1[3], h2[3], u1b[3], u2b[3], h2b[3];
        m->cut_row[k] = r;
        if (jt != VT_JOINT_SPHERICAL) perpendiculars(h1, h2, c->axis1);
        onto_b(u1b, c->orientation, c->axis1);
        onto_b(u2b, c->orientation, c->axis2);
        const int first = r;
        if (c->planar) { /* a planar pin: b's point in a's plane ⟂ axis1 through a's point, as the
                          * line rows below with d along h1 and h2 (the point may leave the plane) */
            for (int e = 0; e < 2; e++) {
                memcpy(m->con_vec + 6 * r, e ? h2 : h1, 3 * sizeof(double));
                r = add_row(m, r, VT_ROW_LINE, a, b, k);
            }
        } else if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL) {
            for (int e = 0; e < 3; e++) { /* the two joint points coincide */
                m->con_vec[6 * r + e] = 1.0;
                r = add_row(m, r, VT_ROW_POINT, a, b, k);
            }
        }
        if ((jt == VT_JOINT_REVOLUTE && !c->planar) || jt == VT_JOINT_CYLINDRICAL || jt == VT_JOINT_TRANSLATIONAL) {
            for (int e = 0; e < 2; e++) { /* b's axis stays parallel to a's */
                memcpy(m->con_vec + 6 * r, e ? h2 : h1, 3 * sizeof(double));
                memcpy(m->con_vec + 6 * r + 3, u1b, 3 * sizeof(double));
                r = add_row(m, r, VT_ROW_DOT, a, b, k);
            }
        }
        if (jt == VT_JOINT_UNIVERSAL) { /* the cross: axis1 on a ⟂ axis2 on b */
            memcpy(m->con_vec + 6 * r, c->axis1, 3 * sizeof(double));
            memcpy(m->con_vec + 6 * r + 3, u2b, 3 * sizeof(double));
            r = add_row(m, r, VT_ROW_DOT, a, b, k);
        }
        if (jt == VT_JOINT_CYLINDRICAL || jt == VT_JOINT_TRANSLATIONAL) {
            for (int e = 0; e < 2; e++) { /* b's point stays on a's axis line */
                memcpy(m->con_vec + 6 * r, e ? h2 : h1, 3 * sizeof(double));
                r = add_row(m, r, VT_ROW_LINE, a, b, k);
            }
        }
        if (jt == VT_JOINT_TRANSLATIONAL) { /* no turn about the axis */
            onto_b(h2b, c->orientation, h2);
            memcpy(m->con_vec + 6 * r, h1, 3 * sizeof(double));
            memcpy(m->con_vec + 6 * r + 3, h2b, 3 * sizeof(double));
            r = add_row(m, r, VT_ROW_DOT, a, b, k);
        }
        for (int q = first; q < r; q++) {
            memcpy(m->con_point + 6 * q, c->point_a, 3 * sizeof(double));
            memcpy(m->con_point + 6 * q + 3, c->point_b, 3 * sizeof(double));
        }
    }
    for (int k = 0; k < m->ncoupling; k++) { /* on no body's Cartesian coordinates directly: Φ_q from the rates */
        const vt_coupling_def *c = &m->coupling[k];
        m->coupling_row[k] = r;
        m->con_dof[r] = m->body_vadr[c->body_a] + c->index_a;
        r = add_row(m, r, VT_ROW_COUPLING, 0, 0, k);
    }
    for (int i = 1; i <= m->nbody; i++)
        if (m->body_joint[i] == VT_JOINT_BASE) r = add_row(m, r, VT_ROW_NORM, 0, i, i);

    /* joint drives by rate; fully joint-driven when each rate has exactly one and no other row */
    for (int c = 0; c < m->nv; c++) m->dof_drive[c] = -1;
    int once = m->nc == m->nv;
    for (int row = 0; row < m->nc; row++) {
        if (m->con_kind[row] != VT_ROW_JOINT) {
            once = 0;
            continue;
        }
        const int c = m->con_dof[row];
        if (m->dof_drive[c] >= 0) once = 0;
        m->dof_drive[c] = m->con_owner[row];
    }
    m->joint_driven = once;
    /* every row a joint drive on its own rate (some rates free): (5) reduces to the free rates */
    int rows_ok = m->nc > 0 && m->nc < m->nv;
    for (int row = 0; row < m->nc && rows_ok; row++)
        if (m->con_kind[row] != VT_ROW_JOINT || m->drive_row[m->dof_drive[m->con_dof[row]]] != row) rows_ok = 0;
    m->joint_rows_only = rows_ok;
    /* the recursive routes' selectors: the joints' kinds (recursive.c) */
    m->joint_mix = 1;
    m->has_quaternions = 0;
    for (int i = 1; i <= m->nbody; i++) {
        const int jt = m->body_joint[i];
        if (jt != VT_JOINT_REVOLUTE && m->joint_mix > 0) m->joint_mix = 0;
        if (jt == VT_JOINT_BASE) m->joint_mix = -1;
        if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_FREE || jt == VT_JOINT_BASE) m->has_quaternions = 1;
    }
    /* the sizes behind the fused passes' overflow bound (recursive.c, fused_bounded): every lever
     * arm of the tree at any pose is shorter than the sum of its offsets (Inf if that overflows:
     * no bound, the outputs are scanned) */
    double len = 0.0, mass = 0.0, mmin = HUGE_VAL, mmax = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        if (m->body_mass[i] > 0.0) mmin = fmin(mmin, m->body_mass[i]), mmax = fmax(mmax, m->body_mass[i]);
        double a[3], b[3];
        vt_copy3(a, m->body_jpar + 3 * i);
        vt_copy3(b, m->body_jchild + 3 * i);
        len += vt_normalize(a, 3) + vt_normalize(b, 3);
        double jmax = 0.0;
        for (int k = 0; k < 9; k++) jmax = fmax(jmax, fabs(m->body_inertia[9 * i + k]));
        mass = fmax(mass, m->body_mass[i] + 3.0 * jmax);
    }
    m->bound_length = len;
    /* the joints' own efforts, |armature q̈ + damping q̇ + friction s(q̇)| ≤ the largest of each
     * times max |q̈|, max |q̇| and 1 (|s| ≤ 1): loads of the same bound */
    m->bound_effect[0] = m->bound_effect[1] = m->bound_effect[2] = 0.0;
    for (int c = 0; c < m->nv; c++)
        for (int k = 0; k < 3; k++) m->bound_effect[k] = fmax(m->bound_effect[k], fabs(m->dof_effects[4 * c + k]));
    m->mass_spread = mmax > 0.0 ? mmax / mmin : 1.0;
    m->bound_mass = mass;
}

/* The unit Euler parameters p of the rotation C, p0 ≥ 0 (Shepperd: from the largest of the four
 * squares 4 p_k², so that no division is by a small number) */
static void quat_of_rotation(double p[4], const double C[9])
{
    const double t = C[0] + C[4] + C[8];
    const double sq[4] = {1.0 + t, 1.0 + 2.0 * C[0] - t, 1.0 + 2.0 * C[4] - t, 1.0 + 2.0 * C[8] - t};
    int k = 0;
    for (int j = 1; j < 4; j++) k = sq[j] > sq[k] ? j : k;
    const double r = 0.5 * sqrt(sq[k]), f = 0.25 / r;
    /* C[r + 3c] = C_rc: C_21 − C_12 = 4 p0 p1 (and cyclic), C_10 + C_01 = 4 p1 p2 (and the others);
     * each divided by 4 |p_k| */
    const double a = (C[5] - C[7]) * f, b = (C[6] - C[2]) * f, c = (C[1] - C[3]) * f; /* p0 p1, p0 p2, p0 p3 */
    const double x = (C[1] + C[3]) * f, y = (C[2] + C[6]) * f, z = (C[5] + C[7]) * f; /* p1 p2, p1 p3, p2 p3 */
    switch (k) {
    case 0: p[0] = r, p[1] = a, p[2] = b, p[3] = c; break;
    case 1: p[0] = a, p[1] = r, p[2] = x, p[3] = y; break;
    case 2: p[0] = b, p[1] = x, p[2] = r, p[3] = z; break;
    default: p[0] = c, p[1] = y, p[2] = z, p[3] = r; break;
    }
    if (p[0] < 0.0) for (int j = 0; j < 4; j++) p[j] = -p[j];
}

/* Body i's joint frame (vt_model.jnt_frame): the definition's, or the kind's documented one from
 * the joint's axes in body axes, A0^T axis (A0 the orientation at q = 0: axis1 is fixed on the
 * body for the joints that turn or slide about it, axis2 for a universal's body); its bearing
 * axis in that frame, C^T A0^T axis */
static void joint_frame(vt_model *m, int i, const vt_body_def *d)
{
    const int jt = d->joint;
    double A0[9], a1[3], a2[3], bear[3] = {0, 0, 0};
    vt_euler_A(A0, d->orientation);
    vt_mulmat3t(a1, A0, d->axis1);
    vt_mulmat3t(a2, A0, d->axis2);
    const int axial = jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_TRANSLATIONAL || jt == VT_JOINT_CYLINDRICAL;
    if (axial) vt_copy3(bear, a1);
    if (jt == VT_JOINT_UNIVERSAL) vt_copy3(bear, a2);
    double *C = m->jnt_frame_A + 9 * i, *p = m->jnt_frame + 4 * i;
    if (d->joint_frame[0] != 0.0 || d->joint_frame[1] != 0.0 || d->joint_frame[2] != 0.0 || d->joint_frame[3] != 0.0) {
        memcpy(p, d->joint_frame, 4 * sizeof(double));
        vt_euler_A(C, p);
    } else {
        double x[3] = {1, 0, 0}, y[3], z[3] = {0, 0, 1};
        if (axial || jt == VT_JOINT_UNIVERSAL) vt_copy3(z, a1);
        if (jt == VT_JOINT_UNIVERSAL) vt_copy3(x, a2);
        else if (axial) { /* the body axis least aligned with z, less its part along z */
            int k = 0;
            for (int j = 1; j < 3; j++) k = fabs(z[j]) < fabs(z[k]) ? j : k;
            x[0] = x[1] = x[2] = 0.0;
            x[k] = 1.0;
            vt_axpy3(x, -z[k], z);
            vt_normalize(x, 3);
        }
        vt_cross3(y, z, x);
        vt_copy3(C, x);
        vt_copy3(C + 3, y);
        vt_copy3(C + 6, z);
        quat_of_rotation(p, C);
        vt_euler_A(C, p); /* the rotation of the stored parameters, to round-off */
    }
    vt_mulmat3t(m->jnt_frame_axis + 3 * i, C, bear);
    if (axial || jt == VT_JOINT_UNIVERSAL) vt_normalize(m->jnt_frame_axis + 3 * i, 3);
}

void vt_model_free(vt_model *m)
{
    free(m); /* one block */
}

/* The model's arrays in the block (a sizing pass with b->base NULL, then the carving pass) */
static void layout_model(vt_block *b, vt_model *m, int n, int nv, int nq, int ndrive, int ncut, int nc, int nframe,
                         int ncoupling)
{
    const size_t nu = (size_t)(ncoupling ? ncoupling : 1);
    m->coupling = vt_block_take(b, nu, sizeof(vt_coupling_def));
    m->coupling_row = vt_block_take(b, nu, sizeof(int));
    m->coupling_name = vt_block_take(b, nu, VT_NAME_MAX);
    const size_t nd = (size_t)(ndrive ? ndrive : 1), nk = (size_t)(ncut ? ncut : 1), ncc = (size_t)(nc ? nc : 1);
    m->drive = vt_block_take(b, nd, sizeof(vt_drive_def));
    m->drive_row = vt_block_take(b, nd, sizeof(int));
    m->cut = vt_block_take(b, nk, sizeof(vt_cut_joint_def));
    m->cut_row = vt_block_take(b, nk, sizeof(int));
    m->con_kind = vt_block_take(b, ncc, sizeof(int));
    m->con_body = vt_block_take(b, 2 * ncc, sizeof(int));
    m->con_owner = vt_block_take(b, ncc, sizeof(int));
    m->con_dof = vt_block_take(b, ncc, sizeof(int));
    m->con_vec = vt_block_take(b, 6 * ncc, sizeof(double));
    m->con_point = vt_block_take(b, 6 * ncc, sizeof(double));
    m->dof_drive = vt_block_take(b, (size_t)(nv ? nv : 1), sizeof(int));
    const size_t nb = (size_t)n + 1;
    m->body_parent = vt_block_take(b, nb, sizeof(int));
    m->body_joint = vt_block_take(b, nb, sizeof(int));
    m->body_qadr = vt_block_take(b, nb, sizeof(int));
    m->body_nq = vt_block_take(b, nb, sizeof(int));
    m->body_vadr = vt_block_take(b, nb, sizeof(int));
    m->body_nv = vt_block_take(b, nb, sizeof(int));
    m->body_mass = vt_block_take(b, nb, sizeof(double));
    /* one double more where the body kernels read four lanes (base/v4.h): the last body's */
    m->body_inertia = vt_block_take(b, 9 * nb + 1, sizeof(double));
    m->body_jpar = vt_block_take(b, 3 * nb + 1, sizeof(double));
    m->body_jchild = vt_block_take(b, 3 * nb + 1, sizeof(double));
    m->body_axis = vt_block_take(b, 6 * nb, sizeof(double));
    m->body_quat0 = vt_block_take(b, 4 * nb, sizeof(double));
    m->jnt_frame = vt_block_take(b, 4 * nb, sizeof(double));
    m->jnt_frame_axis = vt_block_take(b, 3 * nb, sizeof(double));
    m->jnt_frame_A = vt_block_take(b, 9 * nb, sizeof(double));
    m->body_pathnum = vt_block_take(b, nb, sizeof(int));
    m->dof_body = vt_block_take(b, (size_t)nv, sizeof(int));
    m->dof_parent = vt_block_take(b, (size_t)nv, sizeof(int));
    m->q0 = vt_block_take(b, (size_t)nq, sizeof(double));
    m->dof_limit = vt_block_take(b, 4 * (size_t)nv, sizeof(double));
    m->dof_effects = vt_block_take(b, 4 * (size_t)nv, sizeof(double));
    const size_t nf = (size_t)(nframe ? nframe : 1);
    m->body_name = vt_block_take(b, nb, VT_NAME_MAX);
    m->joint_name = vt_block_take(b, nb, VT_NAME_MAX);
    m->drive_name = vt_block_take(b, nd, VT_NAME_MAX);
    m->cut_name = vt_block_take(b, nk, VT_NAME_MAX);
    m->frame_name = vt_block_take(b, nf, VT_NAME_MAX);
    m->frame_body = vt_block_take(b, nf, sizeof(int));
    m->frame_point = vt_block_take(b, 3 * nf, sizeof(double));
    m->frame_quat = vt_block_take(b, 4 * nf, sizeof(double));
}

/* the drives' spline samples: t, y and f'' of each */
static size_t spline_samples(const vt_drive_def *drives, int ndrive)
{
    size_t nsample = 0;
    for (int k = 0; k < ndrive; k++) {
        const vt_function *fs[3];
        const int nf = vt_drive_functions(&drives[k], fs);
        for (int e = 0; e < nf; e++)
            if (fs[e]->type == VT_FUNCTION_SPLINE) nsample += (size_t)fs[e]->nsample;
    }
    return nsample;
}

/* the sizing pass: every array on 16 bytes (calloc's alignment; none needs more) */
static size_t block_bytes(int n, int nv, int nq, int ndrive, int ncut, int nc, int nframe, int ncoupling,
                          size_t nsample)
{
    vt_block blk = {.base = NULL, .used = sizeof(vt_model), .align = 16};
    vt_model tmp;
    layout_model(&blk, &tmp, n, nv, nq, ndrive, ncut, nc, nframe, ncoupling);
    vt_block_take(&blk, 3 * nsample, sizeof(double));
    return blk.overflow ? SIZE_MAX : blk.used; /* SIZE_MAX: beyond size_t */
}

size_t vt_model_bytes(const vt_model *m)
{
    return block_bytes(m->nbody, m->nv, m->nq, m->ndrive, m->ncut, m->nc, m->nframe, m->ncoupling,
                       spline_samples(m->drive, m->ndrive));
}

vt_status vt_builder_build(vt_model **model, vt_builder *b)
{
    if (!model) return VT_ERR_NULL;
    *model = NULL;
    if (!b) return VT_ERR_NULL;
    const int n = b->n;
    if (n == 0) return vt_fail(b->message, VT_ERR_EMPTY_MODEL, "the model has no moving body");

    /* sizes: coordinates and path lengths (nq and nv within VT_COUNT_MAX: the builder's counts;
     * the rows checked here) */
    int nq = 0, nv = 0, nc = 0, rows_ok = 1;
    int *depth_nv = calloc((size_t)n + 1, sizeof(int)); /* rates on the path to each body */
    if (!depth_nv) return vt_fail(b->message, VT_ERR_NO_MEMORY, "out of memory");
    for (int i = 1; i <= n; i++) {
        const vt_body_def *d = &b->bodies[i - 1];
        nq += vt_joint_nq(d->joint);
        nv += vt_joint_nv(d->joint);
        depth_nv[i] = depth_nv[d->parent] + vt_joint_nv(d->joint);
        nc += d->joint == VT_JOINT_BASE;
    }
    for (int k = 0; k < b->ndrive; k++) rows_ok = rows_ok && vt_count_add(&nc, nc, vt_drive_nrows(&b->drives[k]), VT_COUNT_MAX);
    for (int k = 0; k < b->ncut; k++) rows_ok = rows_ok && vt_count_add(&nc, nc, vt_cut_nrows(&b->cuts[k]), VT_COUNT_MAX);
    rows_ok = rows_ok && vt_count_add(&nc, nc, b->ncoupling, VT_COUNT_MAX);
    if (!rows_ok) {
        free(depth_nv);
        return vt_fail(b->message, VT_ERR_TOO_MANY_BODIES, "more than VT_COUNT_MAX (%d) constraint rows", VT_COUNT_MAX);
    }

    /* sizing pass, then the carving pass */
    const size_t nsample = spline_samples(b->drives, b->ndrive);
    const size_t bytes = block_bytes(n, nv, nq, b->ndrive, b->ncut, nc, b->nframe, b->ncoupling, nsample);
    if (bytes == SIZE_MAX) {
        free(depth_nv);
        return vt_fail(b->message, VT_ERR_TOO_MANY_BODIES, "the model's size does not fit in size_t");
    }
    char *block = calloc(1, bytes);
    if (!block) {
        free(depth_nv);
        return vt_fail(b->message, VT_ERR_NO_MEMORY, "out of memory (%zu bytes)", bytes);
    }
    vt_model *m = (vt_model *)block;
    vt_block blk = {.base = block, .used = sizeof(vt_model), .align = 16};
    layout_model(&blk, m, n, nv, nq, b->ndrive, b->ncut, nc, b->nframe, b->ncoupling);
    double *samples = vt_block_take(&blk, 3 * nsample, sizeof(double));

    m->nbody = n;
    m->nq = nq;
    m->nv = nv;
    m->nx = 7 * n;
    memcpy(m->gravity, b->def.gravity, sizeof m->gravity);
    m->rcond_min = b->def.rcond_min;
    m->rcond_warn = b->def.rcond_warn;
    m->allow_redundant = b->def.allow_redundant != 0;
    m->layout = b->def.layout;
    m->ndrive = b->ndrive;
    m->ncut = b->ncut;
    m->nc = nc;
    if (b->ndrive) memcpy(m->drive, b->drives, (size_t)b->ndrive * sizeof(vt_drive_def));
    for (int k = 0; k < b->ndrive; k++) { /* the model's own copy of each spline's samples */
        if (!b->samples[k]) continue;
        vt_drive_def *dr = &m->drive[k];
        vt_function *fs[3] = {&dr->f, &dr->f2, &dr->f3};
        const vt_function *used[3];
        const int nf = vt_drive_functions(dr, used);
        const double *from = b->samples[k];
        for (int e = 0; e < nf; e++) {
            vt_function *f = fs[e];
            if (f->type != VT_FUNCTION_SPLINE) continue;
            const size_t ns = (size_t)f->nsample;
            memcpy(samples, from, 3 * ns * sizeof(double));
            f->sample_t = samples;
            f->sample_y = samples + ns;
            f->sample_d2 = samples + 2 * ns;
            samples += 3 * ns;
            from += 3 * ns;
        }
    }
    if (b->ncut) memcpy(m->cut, b->cuts, (size_t)b->ncut * sizeof(vt_cut_joint_def));
    /* names (the model's own copies; a stored definition's name points at its copy) and frames */
    for (int k = 0; k < b->ndrive; k++) {
        memcpy(m->drive_name + (size_t)VT_NAME_MAX * (size_t)k, b->drive_names[k], VT_NAME_MAX);
        m->drive[k].name = m->drive_name + (size_t)VT_NAME_MAX * (size_t)k;
    }
    for (int k = 0; k < b->ncut; k++) {
        memcpy(m->cut_name + (size_t)VT_NAME_MAX * (size_t)k, b->cut_names[k], VT_NAME_MAX);
        m->cut[k].name = m->cut_name + (size_t)VT_NAME_MAX * (size_t)k;
    }
    for (int i = 1; i <= n; i++) {
        memcpy(m->body_name + (size_t)VT_NAME_MAX * (size_t)i, b->body_names[i - 1], VT_NAME_MAX);
        memcpy(m->joint_name + (size_t)VT_NAME_MAX * (size_t)i, b->joint_names[i - 1], VT_NAME_MAX);
    }
    m->ncoupling = b->ncoupling;
    for (int k = 0; k < b->ncoupling; k++) {
        m->coupling[k] = b->couplings[k];
        memcpy(m->coupling_name + (size_t)VT_NAME_MAX * (size_t)k, b->coupling_names[k], VT_NAME_MAX);
        m->coupling[k].name = m->coupling_name + (size_t)VT_NAME_MAX * (size_t)k;
    }
    m->nframe = b->nframe;
    for (int k = 0; k < b->nframe; k++) {
        memcpy(m->frame_name + (size_t)VT_NAME_MAX * (size_t)k, b->frame_names[k], VT_NAME_MAX);
        m->frame_body[k] = b->frames[k].body;
        memcpy(m->frame_point + 3 * k, b->frames[k].point, 3 * sizeof(double));
        memcpy(m->frame_quat + 4 * k, b->frames[k].orientation, 4 * sizeof(double));
    }

    m->body_parent[0] = -1;
    m->body_joint[0] = -1;
    m->body_quat0[0] = 1.0;
    m->jnt_frame[0] = m->jnt_frame_A[0] = m->jnt_frame_A[4] = m->jnt_frame_A[8] = 1.0;
    int qadr = 0, vadr = 0;
    m->maxpath = 0;
    for (int i = 1; i <= n; i++) {
        const vt_body_def *d = &b->bodies[i - 1];
        const int jt = d->joint;
        m->body_parent[i] = d->parent;
        m->body_joint[i] = jt;
        m->body_qadr[i] = qadr;
        m->body_nq[i] = vt_joint_nq(jt);
        m->body_vadr[i] = vadr;
        m->body_nv[i] = vt_joint_nv(jt);
        m->body_mass[i] = d->mass;
        memcpy(m->body_inertia + 9 * i, d->inertia, 9 * sizeof(double));
        memcpy(m->body_jpar + 3 * i, d->joint_parent, 3 * sizeof(double));
        memcpy(m->body_jchild + 3 * i, d->joint_child, 3 * sizeof(double));
        memcpy(m->body_axis + 6 * i, d->axis1, 3 * sizeof(double));
        memcpy(m->body_axis + 6 * i + 3, d->axis2, 3 * sizeof(double));
        memcpy(m->body_quat0 + 4 * i, d->orientation, 4 * sizeof(double));
        joint_frame(m, i, d);
        for (int k = 0; k < vt_joint_nv(jt); k++) {
            m->dof_body[vadr + k] = i;
            m->dof_parent[vadr + k] = k > 0 ? vadr + k - 1 : d->parent > 0 ? vt_last_rate(m, d->parent) : -1;
            double *lim = m->dof_limit + 4 * (vadr + k);
            const int own = k < 2 && jt != VT_JOINT_BASE && jt != VT_JOINT_SPHERICAL && jt != VT_JOINT_FREE;
            lim[0] = own ? d->limit_lower[k] : -HUGE_VAL;
            lim[1] = own ? d->limit_upper[k] : HUGE_VAL;
            lim[2] = own ? d->limit_velocity[k] : HUGE_VAL;
            lim[3] = own ? d->limit_effort[k] : HUGE_VAL;
            double *ef = m->dof_effects + 4 * (vadr + k);
            const double g = own ? d->gear_ratio[k] : 0.0;
            ef[0] = own ? g * g * d->armature[k] : 0.0;
            ef[1] = own ? g * g * d->damping[k] : 0.0;
            ef[2] = own ? fabs(g) * d->friction[k] : 0.0;
            ef[3] = own ? d->friction_velocity[k] : 0.0;
            if (ef[0] != 0.0 || ef[1] != 0.0 || ef[2] != 0.0) m->has_effects = 1;
            for (int l = 0; l < 4; l++) m->any_limit |= isfinite(lim[l]);
        }

        /* reference configuration: zero angles and translations, unit Euler parameters */
        if (jt == VT_JOINT_BASE) m->q0[qadr + 3] = 1.0;
        if (jt == VT_JOINT_SPHERICAL) m->q0[qadr] = 1.0;
        if (jt == VT_JOINT_FREE) m->q0[qadr + 3] = 1.0;

        /* the path's length: the reference body's, and this joint's own rates */
        m->body_pathnum[i] = depth_nv[i];
        if (depth_nv[i] > m->maxpath) m->maxpath = depth_nv[i];

        qadr += vt_joint_nq(jt);
        vadr += vt_joint_nv(jt);
    }
    free(depth_nv);
    build_rows(m);
    *model = m;
    return VT_OK;
}

vt_status vt_model_without_drives(vt_model **out, const vt_model *m)
{
    if (!out || !m) return VT_ERR_NULL;
    *out = NULL;
    vt_model_def md = vt_default_model_def();
    memcpy(md.gravity, m->gravity, sizeof md.gravity);
    md.rcond_min = m->rcond_min;
    md.rcond_warn = m->rcond_warn;
    md.allow_redundant = m->allow_redundant;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    for (int i = 1; i <= m->nbody && st == VT_OK; i++) {
        vt_body_def d = vt_default_body_def();
        d.parent = m->body_parent[i];
        d.joint = (vt_joint_type)m->body_joint[i];
        d.mass = m->body_mass[i];
        memcpy(d.inertia, m->body_inertia + 9 * i, sizeof d.inertia);
        memcpy(d.joint_parent, m->body_jpar + 3 * i, sizeof d.joint_parent);
        memcpy(d.joint_child, m->body_jchild + 3 * i, sizeof d.joint_child);
        memcpy(d.axis1, m->body_axis + 6 * i, sizeof d.axis1);
        memcpy(d.axis2, m->body_axis + 6 * i + 3, sizeof d.axis2);
        memcpy(d.orientation, m->body_quat0 + 4 * i, sizeof d.orientation);
        memcpy(d.joint_frame, m->jnt_frame + 4 * i, sizeof d.joint_frame);
        d.name = m->body_name + (size_t)VT_NAME_MAX * (size_t)i;
        d.joint_name = m->joint_name + (size_t)VT_NAME_MAX * (size_t)i;
        for (int k = 0; k < 2 && k < m->body_nv[i]; k++) {
            const double *lim = m->dof_limit + 4 * (m->body_vadr[i] + k);
            d.limit_lower[k] = lim[0];
            d.limit_upper[k] = lim[1];
            d.limit_velocity[k] = lim[2];
            d.limit_effort[k] = lim[3];
            const double *ef = m->dof_effects + 4 * (m->body_vadr[i] + k); /* the joint's side: ratio 1 */
            d.armature[k] = ef[0];
            d.damping[k] = ef[1];
            d.friction[k] = ef[2];
            d.friction_velocity[k] = ef[3];
        }
        const int id = vt_builder_add_body(b, &d);
        if (id < 0) st = (vt_status)id;
    }
    for (int k = 0; k < m->nframe && st == VT_OK; k++) {
        vt_frame_def f = vt_default_frame_def();
        f.name = m->frame_name + (size_t)VT_NAME_MAX * (size_t)k;
        f.body = m->frame_body[k];
        memcpy(f.point, m->frame_point + 3 * k, sizeof f.point);
        memcpy(f.orientation, m->frame_quat + 4 * k, sizeof f.orientation);
        const int id = vt_builder_add_frame(b, &f);
        if (id < 0) st = (vt_status)id;
    }
    for (int k = 0; k < m->ncut && st == VT_OK; k++) {
        const int id = vt_builder_add_cut_joint(b, &m->cut[k]);
        if (id < 0) st = (vt_status)id;
    }
    for (int k = 0; k < m->ncoupling && st == VT_OK; k++) { /* constraints of the mechanism, not drives */
        const int id = vt_builder_add_coupling(b, &m->coupling[k]);
        if (id < 0) st = (vt_status)id;
    }
    if (st == VT_OK) st = vt_builder_build(out, b);
    vt_builder_free(b);
    return st;
}

int vt_find_body(const vt_model *m, const char *name)
{
    if (!m || !name) return VT_ERR_NULL;
    const int k = vt_find_name(m->body_name + VT_NAME_MAX, m->nbody, name); /* past the ground's */
    return k < 0 ? k : k + 1;
}

int vt_find_joint(const vt_model *m, const char *name)
{
    if (!m || !name) return VT_ERR_NULL;
    const int k = vt_find_name(m->joint_name + VT_NAME_MAX, m->nbody, name);
    return k < 0 ? k : k + 1;
}

int vt_find_drive(const vt_model *m, const char *name)
{
    return !m || !name ? VT_ERR_NULL : vt_find_name(m->drive_name, m->ndrive, name);
}

int vt_find_cut_joint(const vt_model *m, const char *name)
{
    return !m || !name ? VT_ERR_NULL : vt_find_name(m->cut_name, m->ncut, name);
}

int vt_find_frame(const vt_model *m, const char *name)
{
    return !m || !name ? VT_ERR_NULL : vt_find_name(m->frame_name, m->nframe, name);
}

int vt_find_coupling(const vt_model *m, const char *name)
{
    return !m || !name ? VT_ERR_NULL : vt_find_name(m->coupling_name, m->ncoupling, name);
}
