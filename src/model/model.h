/* vtdyn — The model's internal layout as the stages read it (model/model.c): row kinds and owners, rate
 * kinds, drive rows, subtree sums. A drive's and a cut joint's rows and the joints' sizes are the
 * definitions' (model/builder.h, included). */
#ifndef VT_MODEL_MODEL_H
#define VT_MODEL_MODEL_H

#include "vtdyn.h"
#include "model/builder.h"

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

/* The last rate of body i's joint: where its path, walked down by dof_parent, starts (−1 for
 * the ground: an empty path) */
static inline int vt_last_rate(const vt_model *m, int i)
{
    return m->body_vadr[i] + m->body_nv[i] - 1;
}

/* The path of body i, the rates of the joints between the ground and i (the columns of S that are
 * non-zero in its rows), ascending, into path (body_pathnum[i] ≤ maxpath ints); returns their
 * number. The model holds no path lists (n(n+1)/2 entries for a chain of n): dof_parent gives
 * them leaf first, so they are laid from the end. A loop that sums along a path takes it in this
 * order (the sum's bits); one in which every rate gets a term of its own walks dof_parent itself. */
static inline int vt_body_path(const vt_model *m, int i, int *path)
{
    int k = m->body_pathnum[i];
    for (int a = vt_last_rate(m, i); a >= 0; a = m->dof_parent[a]) path[--k] = a;
    return m->body_pathnum[i];
}

/* The bytes of the model's one block (vt_builder_build's sizing pass, from the model's counts) */
size_t vt_model_bytes(const vt_model *m);

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
/* Number of rows that belong to drives (they come first). */
int vt_drive_rows(const vt_model *m);

#endif
