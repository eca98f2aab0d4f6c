/* vtdyn — The model's internal layout as the stages read it (model/model.c): row kinds and owners, rate
 * kinds, drive rows, subtree sums. */
#ifndef VT_MODEL_MODEL_H
#define VT_MODEL_MODEL_H

#include "vtdyn.h"

/* Cartesian block of body i (1..n) in the paper's stacked 7n vectors. */
static inline int vt_xoff(int body) { return 7 * (body - 1); }

/* subtree sums, inward: W_parent += W_i, stride doubles per body ((nbody+1) x stride) */
static inline void vt_subtree_sum(const vt_model *m, double *W, int stride)
{
    for (int i = m->nbody; i >= 1; i--) {
        const int j = m->body_parent[i];
        if (j <= 0) continue;
        double *restrict dst = W + stride * j; /* a parent precedes its children: no overlap */
        const double *restrict src = W + stride * i;
        for (int c = 0; c < stride; c++) dst[c] += src[c];
    }
}

/* A body's inertia J (3x3 column-major) as the builder accepts it: symmetric, positive
 * semi-definite and within the triangle inequality to VT_INERTIA_TOL (model.c); the message
 * starts with who ("body 3", a URDF link). */
vt_status vt_check_inertia(char *msg, const char *who, const double J[9]);

/* Rotational (0) or translational (1) kind of each joint rate, and which of the joint's
 * axes it uses; base rates are reported separately. */
enum { VT_DOF_ROT, VT_DOF_TRANS, VT_DOF_BASE_R, VT_DOF_BASE_P };
static inline int vt_dof_kind(int joint_type, int k, int *axis)
{
    *axis = 0;
    switch (joint_type) {
    case VT_JOINT_BASE: *axis = k < 3 ? k : k - 3; return k < 3 ? VT_DOF_BASE_R : VT_DOF_BASE_P;
    case VT_JOINT_REVOLUTE: return VT_DOF_ROT;
    case VT_JOINT_UNIVERSAL: *axis = k; return VT_DOF_ROT;
    case VT_JOINT_SPHERICAL: *axis = k; return VT_DOF_ROT;
    case VT_JOINT_TRANSLATIONAL: return VT_DOF_TRANS;
    case VT_JOINT_FREE: *axis = k < 3 ? k : k - 3; return k < 3 ? VT_DOF_TRANS : VT_DOF_ROT;
    default: /* cylindrical: θ then s, both along axis 0 */
        return k == 0 ? VT_DOF_ROT : VT_DOF_TRANS;
    }
}

/* Kinds of constraint row (model.c builds them, constraints.c evaluates them). */
enum {
    VT_ROW_JOINT,   /* q_k − f(t) = 0                                          joint drive */
    VT_ROW_POINT,   /* c·(P_b − P_a) − f(t) = 0, c global                      point drive, cut joints */
    VT_ROW_DOT,     /* (A_a u')·(A_b v') = 0                                   cut joints */
    VT_ROW_LINE,    /* (A_a u')·(P_b − P_a) = 0                                cut joints */
    VT_ROW_ORIENT,  /* 2 (G(p_d) p)_k = 0                                      orientation drive */
    VT_ROW_NORM,    /* p^T p − 1 = 0                                           base body */
    VT_ROW_COUPLING /* q_a − ratio q_b − offset = 0                            coupling */
};
/* Which kind of object owns a row: drive, cut joint or base body. */
enum { VT_OWNER_DRIVE, VT_OWNER_CUT, VT_OWNER_COUPLING, VT_OWNER_BASE };
int vt_row_owner_kind(const vt_model *m, int row);
/* row r a joint drive whose rate is known: the rate's only joint drive (dof_drive), its q̈ the
 * drive's f'' = γ_r exactly; the recursive articulated route and the dense Schur route solve the
 * other rows on the remaining rates */
static inline int vt_known_row(const vt_model *m, int r)
{
    return m->con_kind[r] == VT_ROW_JOINT && m->drive_row[m->dof_drive[m->con_dof[r]]] == r;
}
/* Rows of a cut joint: its kind's, or 2 for a planar pin. */
int vt_cut_nrows(const vt_cut_joint_def *c);
/* Number of rows that belong to drives (they come first). */
int vt_drive_rows(const vt_model *m);
/* An orientation drive, absolute or relative (3 rows, p_d(t) from prescribed orientation) */
static inline int vt_drive_turns(vt_drive_type type)
{
    return type == VT_DRIVE_ORIENTATION || type == VT_DRIVE_RELATIVE_ORIENTATION;
}
/* Rows of one drive */
static inline int vt_drive_nrows(const vt_drive_def *d) { return vt_drive_turns(d->type) ? 3 : 1; }
/* A drive's time functions (f; with an orientation drive's sequence also f2, f3; none for an
 * orientation callback) into fs; returns how many */
static inline int vt_drive_functions(const vt_drive_def *d, const vt_function *fs[3])
{
    if (vt_drive_turns(d->type) && d->orientation_callback) return 0;
    fs[0] = &d->f;
    if (!vt_drive_turns(d->type) || !d->sequence) return 1;
    fs[1] = &d->f2;
    fs[2] = &d->f3;
    return 3;
}

#endif
