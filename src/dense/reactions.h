/* vtdyn — The reactions stage (dense/reactions.c). */
#ifndef VT_DENSE_REACTIONS_H
#define VT_DENSE_REACTIONS_H

#include <stddef.h>

#include "vtdyn.h"
#include "base/scan.h"
#include "base/vec3.h"
#include "kinematics/kinematics.h" /* vt_form */

size_t vt_reactions_scratch(const vt_model *m);

/* vt_reactions without the argument checks (ẍ and α from d->qdd); form: M* and S are the dense
 * stages' (VT_FORM_DENSE) or the recursive general route's composite M* about o */
vt_status vt_reactions_impl(const vt_model *m, vt_data *d, vt_form form);
/* after vt_solve: VT_ERR_SINGULAR when rates whose M* row it zeroed (round-off held by rows)
 * leave the efforts without a certain digit (reactions.c); who names the caller; form as
 * vt_rate_bounds */
vt_status vt_zeroed_rates_check(const vt_model *m, vt_data *d, const char *who, vt_form form);
/* subtree sums about each joint point of wrenches about it: moment at noff, force at foff (reactions.c) */
void vt_sum_at_joints(const vt_model *m, const vt_data *d, double *X, int noff, int foff);
/* the same from the subtrees' needed wrenches about each joint point P_i at the full
 * accelerations, Wbar ([n; f], 6 x (nbody+1), recursive/), the rows' wrenches already taken off
 * it with rows_in_wbar; G: scratch of 6 x (nbody+1), apart from Wbar */
vt_status vt_reactions_subtree(const vt_model *m, vt_data *d, const double *Wbar, double *G, int rows_in_wbar);
/* Every row's wrench on its two bodies, for the multipliers lam (1 each when NULL), about each
 * body's centre of mass: [f_a n_a f_b n_b] into rw (12 x nc) (reactions.c). */
void vt_row_wrenches(double *rw, const vt_model *m, const vt_data *d, const double *lam);
/* jnt_unique and cut_unique, every one set, then those that a null direction of Φ_q^T (rank < nc:
 * the redundant solve's, in d->lambda_null) changes cleared (reactions.c) */
vt_status vt_reactions_nonunique(const vt_model *m, vt_data *d);
/* How far x lies beyond [lo, hi]: x − x clamped (x finite: the instant's inputs and outputs are
 * checked or bounded by then) */
static inline double vt_excess(double x, double lo, double hi)
{
    const double up = x < lo ? lo : x;
    return x - (up > hi ? hi : up);
}
/* Rate c's excesses over its limits lim (vt_model.dof_limit: its coordinate's lower and upper
 * bound, |q̇|'s and |effort|'s) into e (3): of its coordinate q (has_q 0 for a rate that is not
 * one: a spherical, free or base joint's, which has no limits), of q̇ and of its effort tau;
 * returns how many are not 0 */
static inline int vt_rate_limits(double e[3], const double lim[4], int has_q, double q, double qd, double tau)
{
    if ((!has_q || (q >= lim[0] && q <= lim[1])) && fabs(qd) <= lim[2] && fabs(tau) <= lim[3]) { /* within */
        e[0] = e[1] = e[2] = 0.0;
        return 0;
    }
    e[0] = has_q ? vt_excess(q, lim[0], lim[1]) : 0.0;
    e[1] = vt_excess(qd, -lim[2], lim[2]);
    e[2] = vt_excess(tau, -lim[3], lim[3]);
    return (e[0] != 0.0) + (e[1] != 0.0) + (e[2] != 0.0);
}
/* n rates' excesses found (vt_data.nlimit, VT_WARN_LIMIT) */
static inline void vt_limits_found(vt_data *d, int n)
{
    d->nlimit = n;
    d->warning = (d->warning & ~VT_WARN_LIMIT) | (n ? VT_WARN_LIMIT : 0);
}
/* The rates beyond their limits (vt_data.limit_excess, nlimit, VT_WARN_LIMIT) from q, q̇ and the
 * efforts qfrc_drive (reactions.c) */
void vt_limits_flag(const vt_model *m, vt_data *d);
/* Which reactions are unique: every one when the rows are independent (rank nc), otherwise
 * vt_reactions_nonunique's */
static inline vt_status vt_reactions_unique_rows(const vt_model *m, vt_data *d)
{
    const int nj = 6 * (m->nbody + 1), ncut = 6 * m->ncut;
    int *ju = d->jnt_unique, *cu = d->cut_unique;
    for (int i = 0; i < nj; i++) ju[i] = 1;
    for (int k = 0; k < ncut; k++) cu[k] = 1;
    return m->nc - d->rank > 0 ? vt_reactions_nonunique(m, d) : VT_OK;
}
/* vt_reactions_unique_rows, and the limits flagged (the efforts are known by then). Inline, as
 * vt_mark_unique: every instant ends with it */
static inline vt_status vt_reactions_unique(const vt_model *m, vt_data *d)
{
    vt_limits_flag(m, d);
    return vt_reactions_unique_rows(m, d);
}
/* what every instant path ends with: α of every body (from ẍ) and each joint's total wrench,
 * reaction plus actuation (given: the motion given, every rate's qfrc_drive its effort) */
vt_status vt_reactions_total(const vt_model *m, vt_data *d, int given);

/* Efforts of the drives from d->lambda (reactions.c), and the forward check's loads */
vt_status vt_drive_efforts(const vt_model *m, vt_data *d);
void vt_apply_drive_loads(const vt_model *mf, vt_data *df, const vt_model *m, const vt_data *d, const double *xfrc0,
                          int as_loads);

/* |r − (a · r) a| for a unit a (or 0: |r|), with no overflow of the squares of a length near
 * DBL_MAX nor underflow of a tiny one (the scaled sum of vt_normalize where the plain one is out
 * of range) */
double vt_perp_norm_scaled(double u[3]);
static inline double vt_perp_norm(const double r[3], const double a[3], double along)
{
    double u[3];
    for (int k = 0; k < 3; k++) u[k] = r[k] - along * a[k];
    const double ss = vt_dot3(u, u);
    if (ss < 0x1p1000 && ss > 0x1p-1000) return sqrt(ss);
    return vt_perp_norm_scaled(u);
}

/* Every joint's reaction, force f_b and moment n_b in its body's axes (jnt_force_body,
 * jnt_moment_body), into the joint's frame (vt_model.jnt_frame, C: frame → body axes):
 *   f_J = C^T f_b,  n_J = C^T n_b,
 * and its bearing split along the frame's unit axis a (0: none):
 *   a · f_J,  |f_J − (a · f_J) a|,  a · n_J,  |n_J − (a · n_J) a|.
 * (bearing 0: the frames' reactions alone, jnt_bearing left as it was); on demand, after an instant
 * (vt_reactions_joint_frame, the batch where its io asks for them): the instants' passes carry
 * none of its cost */
void vt_joint_frames(const vt_model *m, vt_data *d, int bearing);

/* joint i's total wrench (reaction plus actuation, about P_i) into the data: force f and moment mo
 * in global axes, fb and mb the same in body i's */
static inline void vt_total_store(vt_data *d, int i, const double f[3], const double mo[3], const double fb[3],
                                  const double mb[3])
{
    vt_copy3(d->jnt_force_total + 3 * i, f);
    vt_copy3(d->jnt_moment_total + 3 * i, mo);
    vt_copy3(d->jnt_force_total_body + 3 * i, fb);
    vt_copy3(d->jnt_moment_total_body + 3 * i, mb);
}
/* the same added to what the data holds (a change of loads alone: vt_motion_add_loads) */
static inline void vt_total_add(vt_data *d, int i, const double f[3], const double mo[3], const double fb[3],
                                const double mb[3])
{
    vt_axpy3(d->jnt_force_total + 3 * i, 1.0, f);
    vt_axpy3(d->jnt_moment_total + 3 * i, 1.0, mo);
    vt_axpy3(d->jnt_force_total_body + 3 * i, 1.0, fb);
    vt_axpy3(d->jnt_moment_total_body + 3 * i, 1.0, mb);
}
/* 1 when joint i's total wrench, as vt_total_store left it, is finite */
static inline int vt_total_finite(const vt_data *d, int i)
{
    return vt_all_finite(d->jnt_force_total + 3 * i, 3) && vt_all_finite(d->jnt_moment_total + 3 * i, 3) &&
           vt_all_finite(d->jnt_force_total_body + 3 * i, 3) && vt_all_finite(d->jnt_moment_total_body + 3 * i, 3);
}

#endif
