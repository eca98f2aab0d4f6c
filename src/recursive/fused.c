/* The fused passes: the joint-driven and the given-motion instants of a tree without base bodies,
 * every q̈ known, in one outward and one inward loop; and the inward pass after q̈ is known.
 *
 * The needed wrench of body k about its joint point P_k (kinematics/body.h), and the subtree's
 *   W̄_i = W_i + Σ_c (n_c + (P_c − P_i) × f_c, f_c)                          (the inward pass)
 * give the efforts and the reactions:
 *   τ_a = s_a · W̄_i − qfrc_a   (the paper's Φ_q^T λ with unit rows, λ = τ; (M* q̈ − Q)_a),
 *   reaction at joint i = W̄_i at P_i less the actuation (τ + qfrc) along the joint's axes (26),
 * W̄_i at P_i itself being the joint's total wrench. About P_i a rate's twist s_a is (e, 0) or
 * (0, e): no term carries |P − O|, and a mechanism far from O keeps every digit.
 * - JOINT_DRIVEN (vt_fused_driven), every rate driven by one joint drive: q̈ = f''(t) is known
 *   and nothing is factorized (rcond 1); the kinematics (15)-(18) of kinematics/body.h, the
 *   accelerations and each body's needed wrench in one outward loop (fused_outward), the subtree
 *   wrenches, efforts and reactions in one inward loop (fused_pass), which also store α = ω̇;
 * - MOTION (vt_inverse_dynamics_motion, declared in vtdyn.h, defined here): q̈ given for every
 *   rate, the same two loops, every rate's effort;
 * - vt_inward: the inward pass alone, after the kinematics and q̈ (a base body's tree, or the
 *   free rates solved by articulated bodies).
 * A free joint's six rates are twists like any other: (0, e_k) and (e_k, P × e_k); no row, no
 * normal part.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "recursive/fused.h"
#include "kinematics/joint_effects.h"
#include "recursive/general.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/v4.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/body.h"
#include "kinematics/kinematics.h"
#include "dense/constraints.h"
#include "dense/instant.h"
#include "dense/reactions.h"
#include "dense/solve.h"
#include "numeric/route.h"

/* The fused passes' choices, each compiled apart where it is a constant (no branch in the loops):
 * whose efforts (the joint drives', or every rate's when the motion is given); which joints (all
 * revolute, or revolute, translational and others mixed); whether the outputs need a scan
 * (fused_bounded); whether every half angle is within vt_sincos_small's range (angles_small);
 * whether the joints' total wrenches are formed */
typedef enum { MOTION_DRIVEN, MOTION_GIVEN } fused_motion;
typedef enum { TREE_REVOLUTE, TREE_MIXED } fused_tree;
typedef enum { OUTPUTS_SCANNED, OUTPUTS_BOUNDED } fused_outputs;
typedef enum { ANGLES_ANY, ANGLES_SMALL } fused_angles;
typedef enum { TOTALS_LEFT, TOTALS_FORMED } fused_totals;
typedef enum { STORE_SET, STORE_ADD } fused_store;

/* Joint i's efforts and reaction from its subtree's wrench W̄_i (Wi, about P_i): a turning rate's
 * twist (e, 0) and a sliding one's (0, e) about P_i paired with W̄_i give τ = s · W̄_i − qfrc (a
 * base body's rates: their twists); the reaction is W̄_i less the actuation (τ + qfrc) along each
 * axis (actuation — a drive's τ and an applied qfrc — is not reaction), a free joint's zeroed (it
 * transmits nothing: what is left is round-off). With TOTALS_FORMED also the joint's total wrench
 * (reaction plus actuation), W̄_i itself. jt and nv: the joint's kind and rates, constants where
 * the caller knows them (one rate of a revolute or translational joint), else m's. W̄_i is copied
 * into Wo (locals for the caller's shift to the parent: the outputs might alias W as far as the
 * compiler knows); 1 if the reaction overflowed. STORE_ADD (vt_motion_add_loads): W̄_i is a
 * change of loads alone, and its efforts (no qfrc in them), reaction and total are added to the
 * data's. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline int joint_reaction(const vt_model *m, vt_data *d, const double *Wi, double Wo[6], int i, const int jt,
                                 const int nv, const fused_motion motion, const fused_totals totals,
                                 const fused_store store)
{
    const double *e = d->jaxis + 9 * i, *A = d->A + 9 * i;
    /* rates that all turn leave the force, rates that all slide the moment: its axes once */
    const int turns = jt == VT_JOINT_REVOLUTE || jt == VT_JOINT_UNIVERSAL || jt == VT_JOINT_SPHERICAL;
    const int slides = jt == VT_JOINT_TRANSLATIONAL;
    double f[3], mo[3], fb[3], mb[3];
    for (int k = 0; k < 6; k++) Wo[k] = Wi[k];
    vt_copy3(f, Wo + 3);
    vt_copy3(mo, Wo);
    if (totals == TOTALS_FORMED) { /* fb and mb serve the reaction below too */
        vt_mulmat3t(fb, A, f);
        vt_mulmat3t(mb, A, mo);
        if (store == STORE_SET) vt_total_store(d, i, f, mo, fb, mb);
        else vt_total_add(d, i, f, mo, fb, mb);
    }
    for (int k = 0; k < nv; k++) {
        const int c = m->body_vadr[i] + k, dr = m->dof_drive[c];
        int ax;
        const int kind = vt_dof_kind(jt, k, &ax), rot = kind == VT_DOF_ROT;
        /* qfrc less the joint's own effects (τ takes them) */
        const double qf = store == STORE_ADD ? 0.0 : vt_rate_load_store(m, d, c);
        double tau = 0.0;
        if (motion == MOTION_GIVEN || dr >= 0) {
            const double *w = d->twist + 6 * c;
            const double *s = rot || kind == VT_DOF_TRANS ? e + 3 * ax : kind == VT_DOF_BASE_P ? w : w + 3;
            tau = (rot || kind == VT_DOF_BASE_P ? vt_dot3(s, Wo) : vt_dot3(s, Wo + 3)) - qf;
        }
        if (motion == MOTION_DRIVEN && dr >= 0) {
            d->lambda[m->drive_row[dr]] = tau;
            d->drive_effort[dr] = tau;
            double *df = d->drive_force + 3 * dr, *dm = d->drive_moment + 3 * dr;
            for (int r = 0; r < 3; r++) {
                df[r] = rot ? 0.0 : tau * e[3 * ax + r];
                dm[r] = rot ? tau * e[3 * ax + r] : 0.0;
            }
        }
        if (store == STORE_SET) d->qfrc_drive[c] = tau;
        else d->qfrc_drive[c] += tau;
        vt_axpy3(rot ? mo : f, -(tau + qf), e + 3 * ax);
    }
    if (jt == VT_JOINT_FREE) f[0] = f[1] = f[2] = mo[0] = mo[1] = mo[2] = 0.0;
    if (!(turns && totals == TOTALS_FORMED)) vt_mulmat3t(fb, A, f);
    if (!(slides && totals == TOTALS_FORMED)) vt_mulmat3t(mb, A, mo);
    if (store == STORE_ADD) { /* the data's reaction plus the loads' */
        for (int k = 0; k < 3; k++) {
            f[k] += d->jnt_force[3 * i + k];
            mo[k] += d->jnt_moment[3 * i + k];
            fb[k] += d->jnt_force_body[3 * i + k];
            mb[k] += d->jnt_moment_body[3 * i + k];
        }
    }
    vt_copy3(d->jnt_force + 3 * i, f);
    vt_copy3(d->jnt_moment + 3 * i, mo);
    vt_copy3(d->jnt_force_body + 3 * i, fb);
    vt_copy3(d->jnt_moment_body + 3 * i, mb);
    return !vt_all_finite(f, 3) || !vt_all_finite(mo, 3);
}

/* with q̈ known for every rate: one inward pass for the joint drives' efforts τ = s · W̄ − qfrc
 * and every reaction (actuation — a drive's τ and an applied qfrc — is not reaction) */
/* The joint-driven trees without base bodies take the fused passes below (fused_pass); this one
 * follows the articulated solve of the free rates, or a base body's tree. */
static vt_status inward_pass(const vt_model *m, vt_data *d, const fused_totals totals)
{
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1, mark = vt_scratch_mark(d);
    double *W = VT_SCRATCH(d, double, 6 * nb, "subtree wrenches");
    if (!W) return vt_scratch_fail(d, mark);
    vt_accelerations(m, d, d->qdd, d->xdd, d->alpha);
    vt_subtree_wrenches_at_joints(m, d, d->alpha, W);
    for (int i = 1; i <= n; i++) {
        double Wo[6];
        const int jt = m->body_joint[i], nv = m->body_nv[i];
        const int over = totals == TOTALS_FORMED
                             ? joint_reaction(m, d, W + 6 * i, Wo, i, jt, nv, MOTION_DRIVEN, TOTALS_FORMED, STORE_SET)
                             : joint_reaction(m, d, W + 6 * i, Wo, i, jt, nv, MOTION_DRIVEN, TOTALS_LEFT, STORE_SET);
        if (over)
            return vt_scratch_release(d, mark),
                   vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_recursive: joint %d's reaction overflowed", i);
    }
    vt_scratch_release(d, mark);
    if (totals == TOTALS_FORMED) { /* the ground's rows */
        memset(d->jnt_force_total, 0, 3 * sizeof(double));
        memset(d->jnt_moment_total, 0, 3 * sizeof(double));
        memset(d->jnt_force_total_body, 0, 3 * sizeof(double));
        memset(d->jnt_moment_total_body, 0, 3 * sizeof(double));
    }
    return vt_reactions_unique(m, d);
}

/* The fused passes: a tree without base bodies, every q̈ known (every rate joint-driven, or the
 * motion given): the kinematics, the accelerations and each body's needed wrench in one outward
 * loop over the bodies (the kernels of kinematics/body.h, as vt_kinematics_tree and
 * vt_accelerations call them), the subtree wrenches, efforts and reactions in one inward loop (as
 * inward_pass). A revolute and a translational body each have the kernels compiled for their one
 * rate (fused_body: e = A^j u; a revolute's twist (e, (P − o) × e), t = 0, τ = e · the moment
 * about P; a translational one's (0, e), t = q e, τ = e · f), a free joint its six (fused_free:
 * the triad of its reference body's axes); any other joint takes the general code's stages for
 * the body (fused_other). Their vectors are base/v4.h's, each output stored four lanes at a time
 * in the order of its array (outward: increasing; inward: decreasing, vt_v4_store3_down). */
static const double unit_quat[4] = {1, 0, 0, 0}, zero4[4] = {0, 0, 0, 0};

/* The outward step of body i from its reference body j (kinematics/body.h's kernels): given its
 * orientation p and A (columns A, rows R), its joint's axes e (nv of them, kind jt) and
 * translation t (jt's own: zero for a revolute joint), s^{ij}, s^{ji} and the reference body's
 * values, it stores every kinematic output of body i and of its rates' twists (four lanes at a
 * time, in the order of the arrays: base/v4.h), its velocities, accelerations and needed wrench
 * W_i about P_i (c = r^i − P_i = −s^{ji}). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void fused_step(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, int i,
                              const int jt, const int nv, vt_v4 p, vt_m3 A, vt_m3 R, vt_m3 e, vt_v4 t, vt_v4 sij,
                              vt_v4 sji, vt_v4 g)
{
    const int j = m->body_parent[i], c = m->body_vadr[i];
    const double *q = d->q + m->body_qadr[i], *qd = d->qd + c, *qdd = d->qdd + c;
    if (i == 1) { /* o = P_1 */
        const vt_v4 o1 = jt == VT_JOINT_REVOLUTE ? sij : vt_v4_add(sij, t);
        vt_v4_store3(d->origin, o1);
        vt_v4_store3_up(d->xrel, vt_v4_sub(vt_v4_splat(0.0), o1));
        vt_v4_store3_up(d->xrel + 3, vt_v4_sub(vt_v4_splat(0.0), o1));
    }
    const vt_v4 o = vt_v4_load3(d->origin);
    const vt_v4 rj = vt_v4_load(d->xrel + 6 * j), wj = vt_v4_load(d->omega + 3 * j), alj = vt_v4_load(alpha + 3 * j);
    const vt_v4 vj = vt_v4_load(j ? d->xd + vt_xoff(j) : zero4), aj = vt_v4_load(j ? d->xdd + vt_xoff(j) : zero4);
    vt_v4 Pr, rr, di;
    vt_body_position(&Pr, &rr, &di, rj, sij, jt == VT_JOINT_REVOLUTE ? NULL : &t, sji);
    {
        double *x = d->x + vt_xoff(i), *ej = d->jaxis + 9 * i, *tw = d->twist + 6 * c, *Ai = d->A + 9 * i;
        vt_v4_store3_up(x, vt_v4_add(o, rr));
        vt_v4_store(x + 3, p);
        vt_v4_store3_up(d->jpoint + 3 * i, vt_v4_add(o, Pr));
        vt_v4_store3_up(d->xrel + 6 * i, rr);
        vt_v4_store3_up(d->xrel + 6 * i + 3, Pr);
        vt_v4_store3_up(d->jsij + 3 * i, sij);
        vt_v4_store3_up(d->jd + 3 * i, di);
        for (int k = 0; k < (jt == VT_JOINT_FREE ? 3 : 1); k++) vt_v4_store3(ej + 3 * k, e.c[k]);
        for (int k = 0; k < nv; k++, tw += 6) { /* (e, (P − o) × e) or (0, e) */
            int ax;
            const int rot = vt_dof_kind(jt, k, &ax) == VT_DOF_ROT;
            vt_v4_store3_up(tw, rot ? e.c[ax] : vt_v4_splat(0.0));
            vt_v4_store3_up(tw + 3, rot ? vt_v4_cross(Pr, e.c[ax]) : e.c[ax]);
        }
        for (int k = 0; k < 3; k++) vt_v4_store3_up(Ai + 3 * k, A.c[k]);
    }
    vt_v4 w, v, pd, al, a, pdd;
    vt_body_velocity(&w, &v, &pd, wj, vj, sij, di, sji, p, jt, nv, e, qd);
    vt_body_acceleration(&al, &a, &pdd, alj, aj, wj, w, sij, sji, p, jt, nv, e, q, qd, qdd);
    {
        double *xd = d->xd + vt_xoff(i), *xdd = d->xdd + vt_xoff(i);
        vt_v4_store3_up(d->omega + 3 * i, w);
        vt_v4_store3_up(xd, v);
        vt_v4_store(xd + 3, pd);
        vt_v4_store3_up(alpha + 3 * i, al);
        vt_v4_store3_up(xdd, a);
        vt_v4_store(xdd + 3, pdd);
    }
    const double *fe = d->xfrc + 6 * i;
    vt_body_wrench(W + 6 * i, m, i, A, vt_m3_mul(R, w), vt_m3_mul(R, al), a, g, vt_v4_load(fe), vt_v4_load(fe + 3),
                   vt_v4_sub(vt_v4_splat(0.0), sji));
}

/* fused_outward's body i on a revolute or translational joint (jt, a constant): e = A^j u; a
 * revolute's turn p^j ⊗ (cos ½q, sin ½q u), a translational one's t = q e */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void fused_body(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, int i,
                              const int jt, const fused_angles angles, vt_v4 g)
{
    const int j = m->body_parent[i];
    const double q = d->q[m->body_qadr[i]];
    double cs = 1.0, sn = 0.0;
    if (jt == VT_JOINT_REVOLUTE) { /* no calls with the vectors live */
        if (angles == ANGLES_SMALL) vt_sincos_small(0.5 * q, &sn, &cs);
        else vt_sincos(0.5 * q, &sn, &cs);
    }
    const vt_m3 Aj = vt_m3_load(d->A + 9 * j);
    vt_m3 A, R;
    const vt_v4 u = vt_v4_load(m->body_axis + 6 * i), pj = vt_v4_load(j ? d->x + vt_xoff(j) + 3 : unit_quat);
    const vt_v4 p = vt_body_orientation(jt == VT_JOINT_REVOLUTE ? vt_body_turn(pj, cs, sn, u) : pj,
                                        m->body_quat0 + 4 * i, &A, &R);
    const vt_v4 e = vt_m3_mul(Aj, u);
    const vt_v4 t = jt == VT_JOINT_TRANSLATIONAL ? vt_v4_scale(q, e) : vt_v4_splat(0.0);
    const vt_v4 sij = vt_m3_mul(Aj, vt_v4_load(m->body_jpar + 3 * i));
    const vt_v4 sji = vt_m3_mul(A, vt_v4_load(m->body_jchild + 3 * i));
    fused_step(m, d, alpha, W, i, jt, 1, p, A, R, (vt_m3){{e, e, e}}, t, sij, sji, g);
}

/* A gripper's fingers, a linear axis: the robot stays on the fused passes' own code instead of
 * the general stages' loops over kinds and rates. Not inlined: its code in the revolute loop's
 * body would have that loop laid out anew, and slower. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_slide(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, int i, vt_v4 g)
{
    fused_body(m, d, alpha, W, i, VT_JOINT_TRANSLATIONAL, ANGLES_ANY, g);
}

/* A free joint's body (a floating robot's root): the triad e_k of its reference body's axes,
 * translation t = A^j q_{0..2} and turn p_J = q_{3..6} normalized (as vt_kinematics_body). Not
 * inlined, as fused_slide. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_free(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, int i, vt_v4 g)
{
    const int j = m->body_parent[i];
    const double *q = d->q + m->body_qadr[i];
    double pJ[4];
    memcpy(pJ, q + 3, sizeof pJ);
    vt_normalize(pJ, 4); /* scaled: no overflow for a norm ≥ 1e154 */
    const vt_m3 E = vt_m3_load(d->A + 9 * j);
    vt_m3 A, R;
    const vt_v4 pj = vt_v4_load(j ? d->x + vt_xoff(j) + 3 : unit_quat);
    const vt_v4 p = vt_body_orientation(vt_v4_quat_mul(pj, vt_v4_load(pJ)), m->body_quat0 + 4 * i, &A, &R);
    const vt_v4 sij = vt_m3_mul(E, vt_v4_load(m->body_jpar + 3 * i));
    const vt_v4 sji = vt_m3_mul(A, vt_v4_load(m->body_jchild + 3 * i));
    fused_step(m, d, alpha, W, i, VT_JOINT_FREE, 6, p, A, R, E, vt_m3_mul(E, vt_v4_load(q)), sij, sji, g);
}

/* any other joint: the general code's stages for body i, its wrench about P_i (c = r^i − P_i =
 * −s^{ji}). Not inlined, as fused_slide. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_other(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, int i)
{
    double c[3];
    vt_kinematics_body(m, d, i);
    vt_acceleration_body(m, d, d->qdd, d->xdd, alpha, i);
    vt_joint_child(c, m, d, i);
    for (int k = 0; k < 3; k++) c[k] = -c[k];
    vt_body_wrench_global(W + 6 * i, m, d, i, d->xdd + vt_xoff(i), alpha + 3 * i, c);
}

/* the outward pass: d's kinematic outputs, d->xdd, α and every body's needed wrench W (about P_i) */
/* ANGLES_SMALL: every |q| ≤ 2^15, so every half angle is vt_sincos_small's (no call in the loop);
 * compiled once for each (fused_outward, fused_outward_any) */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void fused_outward_impl(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W,
                                      const fused_tree tree, const fused_angles angles)
{
    double *o = d->origin;
    o[0] = o[1] = o[2] = 0.0;
    memset(d->xrel, 0, 6 * sizeof(double));
    alpha[0] = alpha[1] = alpha[2] = 0.0;
    const vt_v4 g = vt_v4_load3(m->gravity);
    for (int i = 1; i <= m->nbody; i++) {
        if (tree == TREE_MIXED && m->body_joint[i] == VT_JOINT_TRANSLATIONAL) fused_slide(m, d, alpha, W, i, g);
        else if (tree == TREE_MIXED && m->body_joint[i] == VT_JOINT_FREE) fused_free(m, d, alpha, W, i, g);
        else if (tree == TREE_MIXED && m->body_joint[i] != VT_JOINT_REVOLUTE) fused_other(m, d, alpha, W, i);
        else fused_body(m, d, alpha, W, i, VT_JOINT_REVOLUTE, angles, g);
    }
}

#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_outward(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W, const fused_tree tree)
{
    fused_outward_impl(m, d, alpha, W, tree, ANGLES_SMALL);
}
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void fused_outward_any(const vt_model *m, vt_data *d, double *restrict alpha, double *restrict W,
                              const fused_tree tree)
{
    fused_outward_impl(m, d, alpha, W, tree, ANGLES_ANY);
}

/* The fused passes' results checked at once after both loops (a scan of whole arrays costs less
 * than checks joint by joint in the inward loop): ẍ (the Euler parameters' p̈ among them), α, the
 * efforts, the reactions and the total wrenches, the same for the driven and the given motion.
 * An overflow of p̈ shows nowhere else: ½ E^T α sums p_k α_k, which overflows where |α| is near
 * DBL_MAX while α, and a light body's wrench, stay finite (fuzz/corpus/motion-euler-rates-overflow). Copies are not
 * scanned twice: λ and drive_effort hold qfrc_drive's τ, a revolute joint's drive force is zero
 * and its total force is its reaction's (f, stored twice); q̈ is the drives' f'' (checked by
 * vt_function_eval_valid) or the given one (checked on entry). A failure names the first joint
 * from the tree's ends, as a check in the inward loop would, then the first body whose α or ẍ
 * overflows. */
static vt_status fused_check(const vt_model *m, vt_data *d, const fused_motion motion, const fused_tree tree)
{
    const int n = m->nbody, nb3 = 3 * (n + 1), nd = 3 * m->ndrive;
    vt_finite_scan s = {0};
    vt_finite_add(&s, d->xdd, m->nx);
    vt_finite_add(&s, d->alpha, nb3);
    vt_finite_add(&s, d->qfrc_drive, m->nv);
    vt_finite_add(&s, d->jnt_force, nb3);
    vt_finite_add(&s, d->jnt_moment, nb3);
    vt_finite_add(&s, d->jnt_force_body, nb3);
    vt_finite_add(&s, d->jnt_moment_body, nb3);
    vt_finite_add(&s, d->jnt_moment_total, nb3);
    vt_finite_add(&s, d->jnt_moment_total_body, nb3);
    if (tree == TREE_MIXED) {
        vt_finite_add(&s, d->jnt_force_total, nb3);
        vt_finite_add(&s, d->jnt_force_total_body, nb3);
    }
    if (motion == MOTION_DRIVEN) { /* the drives' own outputs */
        vt_finite_add(&s, d->drive_moment, nd);
        if (tree == TREE_MIXED) vt_finite_add(&s, d->drive_force, nd);
    }
    if (vt_finite_ok(&s)) return VT_OK;
    d->route = VT_ROUTE_NONE;
    const char *who = motion == MOTION_GIVEN ? "vt_inverse_dynamics_motion" : "vt_inverse_dynamics_recursive";
    for (int i = n; i >= 1; i--) {
        if (!vt_all_finite(d->jnt_force + 3 * i, 3) || !vt_all_finite(d->jnt_moment + 3 * i, 3) ||
            !vt_all_finite(d->jnt_force_body + 3 * i, 3) || !vt_all_finite(d->jnt_moment_body + 3 * i, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "%s: joint %d's reaction overflowed", who, i);
        if (!vt_total_finite(d, i))
            return vt_fail(d->message, VT_ERR_NONFINITE, "%s: joint %d's total wrench (reaction and actuation) overflows",
                           who, i);
    }
    for (int i = 1; i <= n; i++) {
        if (!vt_all_finite(d->alpha + 3 * i, 3))
            return vt_fail(d->message, VT_ERR_NONFINITE, "%s: body %d's angular acceleration overflows", who, i);
        if (!vt_all_finite(d->xdd + vt_xoff(i), 7))
            return vt_fail(d->message, VT_ERR_NONFINITE,
                           "%s: body %d's acceleration ẍ (a, or the Euler parameters' p̈) overflows", who, i);
    }
    return vt_fail(d->message, VT_ERR_NONFINITE, "%s: the accelerations, efforts or reactions overflow (not finite)", who);
}

/* W̄_j += W̄_i moved from P_i to P_j by the short P_i − P_j = s^{ij}_i + t_i − s^{ji}_j */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void shift_to_parent(const vt_model *m, const vt_data *d, double *W, int i, int j)
{
    double r[3];
    vt_joint_shift(r, m, d, i, j);
    const double *Wi = W + 6 * i;
    double *Wj = W + 6 * j;
    vt_addcross3(Wj, r, Wi + 3);
    for (int k = 0; k < 6; k++) Wj[k] += Wi[k];
}

/* fused_pass's inward step on joint i (jt revolute or translational, a constant): its effort
 * τ = e · W̄_i − qfrc (the moment for a revolute joint, the force for a translational one), its
 * reaction W̄_i less the actuation (τ + qfrc) e, both and the total W̄_i in both frames, W̄_i added
 * to its parent's about P_j, and its rate's limits (the number beyond returned) */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline int fused_inward(const vt_model *m, vt_data *d, double *W, int i, int j, const int jt,
                               const fused_motion motion, const fused_tree tree)
{
    const int c = m->body_vadr[i], dr = m->dof_drive[c], rev = jt == VT_JOINT_REVOLUTE;
    const double *Ap = d->A + 9 * i;
    const vt_m3 A = vt_m3_load(Ap), R = vt_m3_transpose(A);
    const vt_v4 mo = vt_v4_load(W + 6 * i), f = vt_v4_load(W + 6 * i + 3), e = vt_v4_load(d->jaxis + 9 * i);
    const vt_v4 fb = vt_m3_mul(R, f), mb = vt_m3_mul(R, mo);
    vt_v4_store3_down(d->jnt_force_total + 3 * i, f);
    vt_v4_store3_down(d->jnt_moment_total + 3 * i, mo);
    vt_v4_store3_down(d->jnt_force_total_body + 3 * i, fb);
    vt_v4_store3_down(d->jnt_moment_total_body + 3 * i, mb);
    const double qf = vt_rate_load_store(m, d, c);
    double tau = 0.0;
    if (motion == MOTION_GIVEN || dr >= 0) tau = vt_v4_dot3(e, rev ? mo : f) - qf;
    if (motion == MOTION_DRIVEN && dr >= 0) {
        d->lambda[m->drive_row[dr]] = tau;
        d->drive_effort[dr] = tau;
        vt_v4_store3(d->drive_force + 3 * dr, rev ? vt_v4_splat(0.0) : vt_v4_scale(tau, e));
        vt_v4_store3(d->drive_moment + 3 * dr, rev ? vt_v4_scale(tau, e) : vt_v4_splat(0.0));
    }
    d->qfrc_drive[c] = tau;
    const vt_v4 k = vt_v4_scale(tau + qf, e);
    const vt_v4 fr = rev ? f : vt_v4_sub(f, k), mr = rev ? vt_v4_sub(mo, k) : mo;
    vt_v4_store3_down(d->jnt_force + 3 * i, fr);
    vt_v4_store3_down(d->jnt_moment + 3 * i, mr);
    vt_v4_store3_down(d->jnt_force_body + 3 * i, rev ? fb : vt_m3_mul(R, fr));
    vt_v4_store3_down(d->jnt_moment_body + 3 * i, rev ? vt_m3_mul(R, mr) : mb);
    if (j > 0) { /* W̄_j += W̄_i moved to P_j: P_i − P_j = s^{ij}_i + t_i − s^{ji}_j */
        vt_v4 r = vt_v4_load(d->jsij + 3 * i);
        if (!rev) /* t_i */
            r = vt_v4_add(r, vt_v4_add(vt_v4_load(d->jd + 3 * i), vt_m3_mul(A, vt_v4_load(m->body_jchild + 3 * i))));
        if (tree == TREE_MIXED) {
            double sj[3];
            vt_joint_child(sj, m, d, j);
            r = vt_v4_sub(r, vt_v4_load3(sj));
        } else { /* j revolute: −s^{ji}_j = d^j */
            r = vt_v4_add(r, vt_v4_load(d->jd + 3 * j));
        }
        double *Wj = W + 6 * j;
        vt_v4_store3(Wj, vt_v4_add(vt_v4_add(vt_v4_load(Wj), vt_v4_cross(r, f)), mo));
        vt_v4_store3(Wj + 3, vt_v4_add(vt_v4_load(Wj + 3), f));
    }
    if (!m->any_limit) return 0;
    return vt_rate_limits(d->limit_excess + 3 * c, m->dof_limit + 4 * c, 1, d->q[m->body_qadr[i]], d->qd[c], tau);
}

/* the rates of joint i beyond their limits, their efforts known (vt_rate_limits) */
static int joint_limits(const vt_model *m, vt_data *d, int i)
{
    const int c0 = m->body_vadr[i], nv = m->body_nv[i], has_q = m->body_nq[i] == nv;
    const double *q = d->q + m->body_qadr[i];
    int n = 0;
    for (int k = 0; k < nv; k++)
        n += vt_rate_limits(d->limit_excess + 3 * (c0 + k), m->dof_limit + 4 * (c0 + k), has_q, has_q ? q[k] : 0.0,
                            d->qd[c0 + k], d->qfrc_drive[c0 + k]);
    return n;
}

/* fused_pass's inward step on a free joint (a floating robot's root): its rates' twists (0, e_k)
 * and (e_k, 0) about P_i give τ = E^T f − qfrc and E^T n − qfrc, E the triad (its reference
 * body's axes); it transmits nothing, so its reaction is zero and its total wrench W̄_i itself
 * (joint_reaction's, without the loop over rates). Not inlined, as fused_slide. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static int fused_free_inward(const vt_model *m, vt_data *d, double *W, int i, const fused_motion motion)
{
    const int j = m->body_parent[i], c = m->body_vadr[i];
    const vt_m3 A = vt_m3_load(d->A + 9 * i), R = vt_m3_transpose(A);
    const vt_m3 ET = vt_m3_transpose(vt_m3_load(d->A + 9 * j));
    const vt_v4 mo = vt_v4_load(W + 6 * i), f = vt_v4_load(W + 6 * i + 3);
    vt_v4_store3(d->jnt_force_total + 3 * i, f);
    vt_v4_store3(d->jnt_moment_total + 3 * i, mo);
    vt_v4_store3(d->jnt_force_total_body + 3 * i, vt_m3_mul(R, f));
    vt_v4_store3(d->jnt_moment_total_body + 3 * i, vt_m3_mul(R, mo));
    const vt_v4 ft = vt_m3_mul(ET, f), nt = vt_m3_mul(ET, mo);
    for (int k = 0; k < 6; k++) {
        const int dr = m->dof_drive[c + k];
        const double s = k < 3 ? vt_v4_lane(ft, k) : vt_v4_lane(nt, k - 3);
        const double qf = vt_rate_load_store(m, d, c + k);
        const double tau = motion == MOTION_GIVEN || dr >= 0 ? s - qf : 0.0;
        if (motion == MOTION_DRIVEN && dr >= 0) { /* a drive on a free joint's rate */
            d->lambda[m->drive_row[dr]] = tau;
            d->drive_effort[dr] = tau;
            const double *ek = d->jaxis + 9 * i + 3 * (k % 3);
            for (int r = 0; r < 3; r++) {
                d->drive_force[3 * dr + r] = k < 3 ? tau * ek[r] : 0.0;
                d->drive_moment[3 * dr + r] = k < 3 ? 0.0 : tau * ek[r];
            }
        }
        d->qfrc_drive[c + k] = tau;
    }
    double *zero[4] = {d->jnt_force, d->jnt_moment, d->jnt_force_body, d->jnt_moment_body};
    for (int k = 0; k < 4; k++) memset(zero[k] + 3 * i, 0, 3 * sizeof(double));
    if (j > 0) shift_to_parent(m, d, W, i, j);
    return m->any_limit ? joint_limits(m, d, i) : 0;
}

/* fused_pass's inward step on a translational joint. Not inlined, as fused_slide. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static int fused_slide_inward(const vt_model *m, vt_data *d, double *W, int i, const fused_motion motion)
{
    return fused_inward(m, d, W, i, m->body_parent[i], VT_JOINT_TRANSLATIONAL, motion, TREE_MIXED);
}

/* Wrenches at frames (the given motion's loads, vt_motion_loaded) into the bodies' needed wrenches
 * W about their joint points P_b, between the passes, where the outward one has the poses: frame F
 * on body b, its origin r^b + A_b p_F, its force f and moment n about that origin (global axes),
 *   W_b −= (n + (A_b p_F − (P_b − r^b)) × f,  f)
 * as an xfrc entry [f; n + (A_b p_F) × f] about r^b would take off (vt_body_wrench); the inward
 * pass then carries them as any load. */
static void frame_loads_into(const vt_model *m, const vt_data *d, const vt_frame_loads *loads, double *W)
{
    for (int k = 0; k < loads->n; k++) {
        const int f = loads->frame[k], b = m->frame_body[f];
        const double *w = loads->w + 6 * k;
        double lever[3], c[3];
        vt_mulmat3(lever, d->A + 9 * b, m->frame_point + 3 * f);
        vt_joint_child(c, m, d, b); /* P_b − r^b */
        for (int h = 0; h < 3; h++) lever[h] -= c[h];
        double *Wb = W + 6 * b, mo[3];
        vt_cross3(mo, lever, w);
        for (int h = 0; h < 3; h++) Wb[h] -= w[3 + h] + mo[h], Wb[3 + h] -= w[h];
    }
}

/* the joint-driven (MOTION_DRIVEN) or given (MOTION_GIVEN) instant of a tree without base bodies:
 * inward_pass's outputs, and vt_kinematics_tree's (without Ṡq̇); OUTPUTS_BOUNDED: fused_bounded
 * holds, the outputs need no scan. Inlined: each caller's constants compiled apart */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status fused_pass(const vt_model *m, vt_data *d, const fused_motion motion, const fused_tree tree,
                                   const fused_outputs outputs, const fused_angles angles, const vt_frame_loads *loads)
{
    const int n = m->nbody;
    const size_t nb = (size_t)n + 1, mark = vt_scratch_mark(d);
    double *W = VT_SCRATCH(d, double, 6 * nb + 1, "subtree wrenches");
    if (!W) return vt_scratch_fail(d, mark);
    if (angles == ANGLES_SMALL) fused_outward(m, d, d->alpha, W, tree);
    else fused_outward_any(m, d, d->alpha, W, tree);
    vt_status st = outputs == OUTPUTS_BOUNDED ? VT_OK : vt_kinematics_check_outputs(m, d);
    if (st) { /* as vt_kinematics_tree's failure before any route */
        d->route = VT_ROUTE_NONE;
        return vt_scratch_release(d, mark), st;
    }
    if (loads) frame_loads_into(m, d, loads, W);
    int nlimit = 0; /* the rates beyond their limits, flagged as each joint's efforts are known */
    for (int i = n; i >= 1; i--) { /* leaf first: W_i is its subtree's when its turn comes */
        const int j = m->body_parent[i];
        if (tree == TREE_MIXED && m->body_joint[i] == VT_JOINT_TRANSLATIONAL) {
            nlimit += fused_slide_inward(m, d, W, i, motion);
            continue;
        }
        if (tree == TREE_MIXED && m->body_joint[i] == VT_JOINT_FREE) {
            nlimit += fused_free_inward(m, d, W, i, motion);
            continue;
        }
        if (tree == TREE_MIXED && m->body_joint[i] != VT_JOINT_REVOLUTE) {
            double Wo[6];
            /* checked with the rest: fused_check */
            (void)joint_reaction(m, d, W + 6 * i, Wo, i, m->body_joint[i], m->body_nv[i], motion, TOTALS_FORMED, STORE_SET);
            if (j > 0) shift_to_parent(m, d, W, i, j);
            if (m->any_limit) nlimit += joint_limits(m, d, i);
            continue;
        }
        nlimit += fused_inward(m, d, W, i, j, VT_JOINT_REVOLUTE, motion, tree);
    }
    vt_scratch_release(d, mark);
    /* the ground's rows (α's: fused_outward), the last entries of which body 1's stores overwrote */
    double *ground[8] = {d->jnt_force_total, d->jnt_moment_total, d->jnt_force_total_body, d->jnt_moment_total_body,
                         d->jnt_force, d->jnt_moment, d->jnt_force_body, d->jnt_moment_body};
    for (int k = 0; k < 8; k++) memset(ground[k], 0, 3 * sizeof(double));
    if (outputs == OUTPUTS_SCANNED && (st = fused_check(m, d, motion, tree))) return st;
    if (m->any_limit) vt_limits_found(d, nlimit);
    return vt_reactions_unique_rows(m, d);
}

/* the inward pass after q̈ is known; without base bodies it also forms the total wrenches, W̄_i
 * about P_i (a base body's rates act at its centre of mass and through p: vt_reactions_total) */
vt_status vt_inward(const vt_model *m, vt_data *d, int totals)
{
    return inward_pass(m, d, totals ? TOTALS_FORMED : TOTALS_LEFT);
}

/* Loads added after the given motion's instant. The instant is linear in the loads and its
 * kinematics do not depend on them, so loads δ (as xfrc: a force at each centre of mass, a
 * moment about it) change each body's needed wrench about P_i by
 *   δW_i = −(δn_i + (r^i − P_i) × δf_i, δf_i)          (r^i − P_i = −s^{ji}_i)
 * and the rest follows by the inward pass alone on δW: δτ_a = s_a · δW̄_i, the reactions and the
 * totals changed by δW̄_i less the actuation δτ along the joint's axes, all added to what the
 * instant left. A tree's given motion only (the fused passes' route): loops and couplings carry
 * multipliers that the loads change too. */
vt_status vt_motion_add_loads(const vt_model *m, vt_data *d, const double *xf)
{
    if (m->ncut > 0 || m->ncoupling > 0 || d->route != VT_ROUTE_MOTION)
        return vt_fail(d->message, VT_ERR_BAD_OPTION,
                       "vt_motion_add_loads: needs vt_inverse_dynamics_motion's instant of a tree just before");
    const int n = m->nbody;
    const size_t mark = vt_scratch_mark(d);
    double *W = VT_SCRATCH(d, double, 6 * ((size_t)n + 1), "the loads' subtree wrenches");
    if (!W) return vt_scratch_fail(d, mark);
    for (int i = 1; i <= n; i++) {
        double c[3];
        const double *fe = xf + 6 * i;
        vt_joint_child(c, m, d, i); /* P_i − r^i */
        double *w = W + 6 * i;
        for (int k = 0; k < 3; k++) {
            w[k] = -fe[3 + k];
            w[3 + k] = -fe[k];
        }
        vt_addcross3(w, w + 3, c); /* (r^i − P_i) × (−δf) = (−δf) × (P_i − r^i) */
    }
    int over = 0;
    for (int i = n; i >= 1; i--) {
        double Wo[6];
        const int j = m->body_parent[i];
        over |= joint_reaction(m, d, W + 6 * i, Wo, i, m->body_joint[i], m->body_nv[i], MOTION_GIVEN, TOTALS_FORMED,
                               STORE_ADD);
        if (j > 0) shift_to_parent(m, d, W, i, j);
    }
    vt_scratch_release(d, mark);
    if (over || !vt_all_finite(d->qfrc_drive, m->nv))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_motion_add_loads: the efforts or reactions with the loads overflowed");
    return vt_reactions_unique(m, d); /* the limits flagged again: the efforts changed */
}

/* 1 when every half angle is within vt_sincos_small's 2^14 (fused_outward, not _any): from the
 * state's maximum smax (vt_state_max), q scanned again alone only where that is above 2^15 */
static inline fused_angles angles_small(const vt_model *m, const vt_data *d, double smax)
{
    return smax <= 0x1p15 || vt_array_max(d->q, m->nq) <= 0x1p15 ? ANGLES_SMALL : ANGLES_ANY;
}

/* 1 when no output of the fused passes can overflow, from the inputs' sizes alone: then their
 * scans (vt_kinematics_check_outputs, fused_check) are skipped. With U = 1 + Σ_i (|s^{ij}| +
 * |s^{ji}|) + nq max|q| (every position, lever arm and o itself: a path's offsets and
 * translations; every orientation is unit, the Euler parameters normalized), R = 1 + nv max|q̇|,
 * A = 1 + nv max|q̈| + 4 R² + |g|, M = 1 + max (m + 3 max|J_kl|), F = 1 + max(|xfrc|, |qfrc|):
 *   |ω| ≤ R, |v| ≤ 2 R U, |α| ≤ Σ|q̈| + Σ|q̇| |ω| ≤ A, |a| ≤ 2 A U + 2 R² U + 2 R² + Σ|q̈| ≤ 4 A U,
 *   |p̈| ≤ ½ |α| + ¼ |ω|² ≤ A, a body's force ≤ 5 M A U + 2 F, its moment about its joint point
 *   ≤ 6 M A + 2 F + 2 U × the force ≤ 16 U² (M A + F), a subtree's (n bodies, moved by lever arms
 *   < 2U) ≤ 26 n U² (M A + F), efforts and reactions at most twice that (the actuation taken off),
 *   in either frame (a rotation keeps lengths);
 * so every output is below B = 64 (n + 1) U² (M A + F), and B < 1e300 leaves round-off (relative
 * ε per operation) 8 orders of magnitude from DBL_MAX. Where B is not below it (a rate of 1e150
 * rad/s, loads near DBL_MAX, B itself Inf), the scans decide, as before. B only grows with each
 * maximum, so the instants pass one maximum of |xfrc|, |qfrc|, |q| and |q̇| (vt_state_max: one scan)
 * for all four. */
static inline fused_outputs fused_bounded(const vt_model *m, double qmax, double vmax, double amax,
                                double fmax_)
{
    const double g = fabs(m->gravity[0]) + fabs(m->gravity[1]) + fabs(m->gravity[2]);
    const double U = 1.0 + m->bound_length + m->nq * qmax, R = 1.0 + m->nv * vmax;
    const double A = 1.0 + m->nv * amax + 4.0 * R * R + g;
    /* the joints' own effects (armature q̈, damping q̇, friction) are loads along the rates, as qfrc */
    const double F = 1.0 + fmax_ + m->bound_effect[0] * amax + m->bound_effect[1] * vmax + m->bound_effect[2];
    const double B = 64.0 * (m->nbody + 1) * U * U * ((1.0 + m->bound_mass) * A + F);
    return B < 1e300 ? OUTPUTS_BOUNDED : OUTPUTS_SCANNED;
}

/* The joint-driven instant of a tree without base bodies (joint_mix ≥ 0), every rate driven by a
 * joint drive: q̈ = f'' known, the fused passes; the whole of vt_inverse_dynamics_recursive for
 * such a model, its inputs checked here and its outputs in fused_pass */
vt_status vt_fused_driven(const vt_model *m, vt_data *d)
{
    double smax;
    vt_status st = vt_recursive_start(m, d, &smax);
    if (st) return st;
    const int mix = m->joint_mix;
    /* Euler parameters' norms to check (a revolute or translational joint's q is any finite
     * number), or q or q̇ not finite */
    if (!(smax < HUGE_VAL)) st = vt_kinematics_check_state(m, d);
    else if (mix == 0 && m->has_quaternions) st = vt_kinematics_check_quaternions(m, d); /* q and q̇ finite */
    if (st) return st;
    if ((st = vt_drive_accelerations(m, d))) { /* the status the separate passes would give */
        const vt_status sk = vt_kinematics_tree(m, d, 0);
        return sk ? sk : st;
    }
    vt_solved(m, d, VT_ROUTE_JOINT_DRIVEN, 1.0); /* nothing factorized: one unit row per rate */
    const fused_outputs outputs = fused_bounded(m, smax, smax, vt_array_max(d->qdd, m->nv), smax);
    const fused_angles angles = angles_small(m, d, smax);
    /* the joints' effort parts (vt_joint_effects_store's) stored by the inward pass */
    return mix ? fused_pass(m, d, MOTION_DRIVEN, TREE_REVOLUTE, outputs, angles, NULL)
               : fused_pass(m, d, MOTION_DRIVEN, TREE_MIXED, outputs, angles, NULL);
}

/* the given motion's fused passes: not inlined, and the tree a variable, so that one compact copy
 * serves both kinds of tree (a floating robot's tree is mixed: its free root takes fused_free),
 * where copies compiled for each kind lengthen the mixed trees' loops */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static vt_status fused_given(const vt_model *m, vt_data *d, const fused_tree tree, const fused_outputs outputs,
                             const fused_angles angles, const vt_frame_loads *loads)
{
    return fused_pass(m, d, MOTION_GIVEN, tree, outputs, angles, loads);
}

/* The motion given for every rate of a tree: q̈ is known, and one outward and one inward pass
 * give every rate's effort τ_a = s_a · W̄_i − qfrc_a (= (M* q̈ − Q)_a) and the reactions, the
 * actuation taken off (route VT_ROUTE_MOTION, nothing factorized). A loop's or a coupling's
 * rates are not independent: there the joint-driven rates are the given ones and the rest
 * follows from the rows (vt_motion_rows, instant.c). Base bodies of a tree are refused: a base
 * body's ṗ rates carry (4)'s normal part (its multiplier); a free joint (VT_JOINT_FREE), whose
 * six rates are twists, is what a floating robot uses here. */
vt_status vt_inverse_dynamics_motion(const vt_model *m, vt_data *d)
{
    return vt_motion_loaded(m, d, NULL);
}

vt_status vt_motion_loaded(const vt_model *m, vt_data *d, const vt_frame_loads *loads)
{
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_motion");
    if (st) return st;
    vt_diagnostics_reset(d);
    const double amax = vt_array_max(d->qdd, m->nv);
    if (!(amax < HUGE_VAL)) {
        for (int c = 0; c < m->nv; c++)
            if (!isfinite(d->qdd[c]))
                return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_motion: qdd[%d] = %g", c, d->qdd[c]);
    }
    if (loads && loads->n > 0 && !vt_all_finite(loads->w, 6 * (size_t)loads->n))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_motion: NaN or Inf in a load at a frame");
    if (m->ncut > 0 || m->ncoupling > 0) { /* loops or couplings: the joint-driven rates are the given ones */
        int given = 0;
        for (int r = 0; r < m->nc; r++) given += m->con_kind[r] == VT_ROW_JOINT;
        if (!given && m->ncoupling == 0)
            return vt_fail(d->message, VT_ERR_BAD_OPTION,
                           "vt_inverse_dynamics_motion: the model has %d cut joints and no joint drive: "
                           "drive the rates whose motion is given", m->ncut);
        if (!given) /* what a URDF robot with mimic joints meets first: the leader's drive, or no couplings */
            return vt_fail(d->message, VT_ERR_BAD_OPTION,
                           "vt_inverse_dynamics_motion: %d couplings, no joint drive: put a joint drive on each "
                           "coupling's leader (\"%.24s\" follows \"%.24s\") and free rate, or load the URDF with "
                           "vt_urdf_options.mimic = 0 (as Pinocchio does)", m->ncoupling,
                           m->joint_name + (size_t)VT_NAME_MAX * m->coupling[0].body_a,
                           m->joint_name + (size_t)VT_NAME_MAX * m->coupling[0].body_b);
        return vt_motion_rows(m, d, loads);
    }
    for (int i = 1; m->joint_mix < 0 && i <= m->nbody; i++)
        if (m->body_joint[i] == VT_JOINT_BASE)
            return vt_fail(d->message, VT_ERR_BAD_OPTION,
                           "vt_inverse_dynamics_motion: body %d has a base (floating) joint, not supported here; "
                           "use VT_JOINT_FREE", i);
    const double smax = vt_state_max(m, d); /* loads, q and q̇; the loads alone where one is not finite */
    if (!(smax < HUGE_VAL) && !(vt_loads_max(m, d) < HUGE_VAL))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_dynamics_motion: NaN or Inf in xfrc or qfrc");
    /* the outward passes fused (no base body here) */
    const int mix = m->joint_mix;
    /* Euler parameters' norms to check (a revolute or translational joint's q is any finite
     * number), or q or q̇ not finite */
    if (!(smax < HUGE_VAL)) st = vt_kinematics_check_state(m, d);
    else if (mix == 0 && m->has_quaternions) st = vt_kinematics_check_quaternions(m, d); /* q and q̇ finite */
    if (st) return st;
    /* loads at frames bounded as xfrc entries would be: |f|∞ (1 + 2 |p_F|₁) + |n|∞ each bounds every
     * entry of [f; n + (A p_F) × f] (|(A p) × f|∞ ≤ |p|₂ |f|₂ ≤ 2 |p|₁ |f|∞), summed over them */
    double lb = 0.0;
    for (int k = 0; loads && k < loads->n; k++) {
        const double *w = loads->w + 6 * k, *p = m->frame_point + 3 * loads->frame[k];
        const double fi = fmax(fabs(w[0]), fmax(fabs(w[1]), fabs(w[2]))), ni = fmax(fabs(w[3]), fmax(fabs(w[4]), fabs(w[5])));
        lb += fi * (1.0 + 2.0 * (fabs(p[0]) + fabs(p[1]) + fabs(p[2]))) + ni;
    }
    const fused_outputs outputs = fused_bounded(m, smax, smax, amax, smax + lb);
    vt_solved(m, d, VT_ROUTE_MOTION, 1.0); /* nothing factorized */
    const fused_angles angles = angles_small(m, d, smax);
    /* α, the totals and the joints' effort parts formed in it */
    st = fused_given(m, d, mix ? TREE_REVOLUTE : TREE_MIXED, outputs, angles, loads && loads->n > 0 ? loads : NULL);
    if (st) d->route = VT_ROUTE_NONE; /* as vt_solve_reset left it */
    return st;
}
