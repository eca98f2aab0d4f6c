/* vtdyn — Kinematics of the tree (kinematics/kinematics.c): positions, velocities, S, Ṡq̇ and accelerations,
 * body by body or as passes, and the joint geometry the other passes share. */
#ifndef VT_KINEMATICS_KINEMATICS_H
#define VT_KINEMATICS_KINEMATICS_H

#include <math.h>

#include "vtdyn.h"
#include "base/vec3.h"
#include "model/model.h"

size_t vt_kinematics_scratch(const vt_model *m);

/* Body i's rows of S on its path columns (path: vt_body_path's of i), into Si (7 x body_pathnum[i],
 * ld 7) (kinematics.c) */
void vt_gather_S(double *Si, const vt_model *m, const vt_data *d, int i, const int *path);

/* How M* and Φ_q are formed: from the dense S of vt_kinematics (S^T M S, Φ_x S, lever arms along
 * the tree: the dense stages) or from the rates' twists about o (the recursive evaluation's
 * composite inertias and Φ_q). The stages that judge round-off or pick a route take it. */
typedef enum { VT_FORM_TWISTS = 0, VT_FORM_DENSE = 1 } vt_form;

/* vt_kinematics_tree's and vt_accelerations' rows of one body i, its reference body's done
 * (kinematics.c): for a pass that fuses them with other work body by body (recursive/fused.c) */
void vt_kinematics_body(const vt_model *m, vt_data *d, int i);
void vt_acceleration_body(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, int i);
/* vt_kinematics_tree's checks of the state and of its outputs (without Ṡq̇) (kinematics.c) */
vt_status vt_kinematics_check_state(const vt_model *m, vt_data *d);
/* the Euler parameters' norms alone, where q and q̇ are known finite */
vt_status vt_kinematics_check_quaternions(const vt_model *m, vt_data *d);
vt_status vt_kinematics_check_outputs(const vt_model *m, vt_data *d);
/* Kinematics (kinematics.c): ẍ = S q̈ + Ṡ q̇ into out (7n) (q̈ = 0 if qdd is NULL), with the
 * angular accelerations into alpha (3 x (nbody+1)). */
void vt_accelerations(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha);
/* The same from d->Sdqd and d->twist (both current), with T (6 x (nbody+1)) the twists q̈ adds
 * to the bodies' spatial accelerations; alpha may be NULL. */
void vt_accelerations_add(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, double *T);
/* The same from the dense S (vt_kinematics' lever arms along the tree), alpha not NULL; path:
 * scratch of maxpath ints */
void vt_accelerations_dense(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, int *path);

/* Positions, velocities and (with Sdqd != 0) Ṡq̇, without the dense S (kinematics.c); the
 * state is checked. */
vt_status vt_kinematics_tree(const vt_model *m, vt_data *d, int Sdqd);
/* vt_kinematics_tree in two halves (kinematics.c): the positions and the rates' twists (q
 * checked), then the velocities and (Sdqd != 0) Ṡq̇ at those positions (q̇ checked) */
vt_status vt_kinematics_positions(const vt_model *m, vt_data *d);
vt_status vt_kinematics_velocities(const vt_model *m, vt_data *d, int Sdqd);
/* Column dof of S in body i's rows (kinematics.c), from the rate's twist d->twist's axis and the
 * lever arm u = r^i − P of the rate's joint point (vt_lever); Ei = E(p^i) */
void vt_S_column(double c[7], const vt_model *m, const vt_data *d, int i, const double Ei[12], int dof, const double u[3]);
/* whether rate dof turns (a rotational axis or a base body's ṗ: its twist's w), else slides */
static inline int vt_dof_turns(const vt_model *m, int dof)
{
    int ax;
    const int b = m->dof_body[dof], kind = vt_dof_kind(m->body_joint[b], dof - m->body_vadr[b], &ax);
    return kind == VT_DOF_ROT || kind == VT_DOF_BASE_P;
}
/* s^{ji} = A^i s'^{ji}, body i's centre of mass to its joint point (a base body's: 0). A joint
 * without translation has d^i = −s^{ji} exactly (kinematics.c forms d^i = t − s^{ji}, t = 0) */
static inline void vt_joint_child(double s[3], const vt_model *m, const vt_data *d, int i)
{
    const int jt = m->body_joint[i];
    if (jt == VT_JOINT_BASE) s[0] = s[1] = s[2] = 0.0;
    else if (jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL || jt == VT_JOINT_SPHERICAL)
        s[0] = -d->jd[3 * i], s[1] = -d->jd[3 * i + 1], s[2] = -d->jd[3 * i + 2];
    else vt_mulmat3(s, d->A + 9 * i, m->body_jchild + 3 * i);
}

/* P_i − P_j, body i's joint point from its reference body j's, from the joints' own vectors:
 * s^{ij}_i + t_i − s^{ji}_j with t_i = d^i + s^{ji}_i the joint's translation (17) */
static inline void vt_joint_shift(double r[3], const vt_model *m, const vt_data *d, int i, int j)
{
    double si[3], sj[3];
    vt_joint_child(si, m, d, i);
    vt_joint_child(sj, m, d, j);
    for (int k = 0; k < 3; k++) r[k] = d->jsij[3 * i + k] + (d->jd[3 * i + k] + si[k]) - sj[k];
}

/* The lever arms of the dense S (and of the recursive path's Φ_q), walked from body i up its
 * path: at joint k, u = r^i − P_k (P_k the point the joint's rates turn about; a base body's,
 * its centre of mass), summed from the joints' own short vectors,
 *   r^i − P_i = −s^{ji}_i,   r^i − P_j = (r^i − P_k) + (s^{ij}_k + t_k) − s^{ji}_j   (j = k's reference)
 * with t_k = d^k + s^{ji}_k the joint's translation (17); with with_len, len = the sum of those
 * vectors' lengths, the size of u's round-off; s = s^{ji} of joint k. The difference
 * (r^i − o) − (P_k − o) of positions from o would carry ε |r − o| of round-off: a mechanism 1e9 m
 * from o would have no digit of a 1 m lever arm. vt_lever_up moves to k's reference body and
 * returns 0 at the ground. */
typedef struct {
    int k, with_len;
    double u[3], s[3], len;
} vt_lever;
static inline void vt_lever_start(vt_lever *L, const vt_model *m, const vt_data *d, int i, int with_len)
{
    L->k = i;
    L->with_len = with_len;
    vt_joint_child(L->s, m, d, i);
    for (int c = 0; c < 3; c++) L->u[c] = -L->s[c];
    L->len = with_len ? sqrt(vt_dot3(L->s, L->s)) : 0.0;
}
static inline int vt_lever_up(vt_lever *L, const vt_model *m, const vt_data *d)
{
    const int k = L->k, j = m->body_parent[k];
    if (j == 0) return 0;
    double a[3], sj[3];
    const double *sij = d->jsij + 3 * k, *dk = d->jd + 3 * k;
    for (int c = 0; c < 3; c++) a[c] = sij[c] + (dk[c] + L->s[c]); /* P_k − r^j */
    vt_joint_child(sj, m, d, j);
    for (int c = 0; c < 3; c++) L->u[c] += a[c] - sj[c];
    if (L->with_len) L->len += sqrt(vt_dot3(a, a)) + sqrt(vt_dot3(sj, sj));
    vt_copy3(L->s, sj);
    L->k = j;
    return 1;
}
/* |r^i − o| bounded by the lengths it is summed from, the size of its round-off, for every body
 * into L[stride i] (kinematics.c) */
void vt_lengths_from_o(const vt_model *m, const vt_data *d, double *L, int stride);

#endif
