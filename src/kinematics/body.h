/* vtdyn — One body's kernels, written once and called by every pass: the kinematics in
 * kinematics/kinematics.c, the fused passes and the articulated and general routes in recursive/,
 * the dense reactions in dense/reactions.c. Always inlined: the fused passes compile them for one
 * joint kind at a time (jt and nv constants), with no call and no loop over rates left.
 *
 * One body i from its reference body j (the paper's (15)-(18); kinematics.c's banner), global
 * axes, every position from the reference point o (d->xrel), ε_k = 1 for a translational rate:
 *   orientation   p^i = p^j ⊗ p_J(q) ⊗ p0,  A^i = A(p^i);  a turn by q about u:
 *                 p_J = (cos ½q, sin ½q u)                                    (vt_body_turn)
 *   positions     P_i − o = (r^j − o) + s^{ij} + t,   r^i − o = (P_i − o) − s^{ji},
 *                 d^i = t − s^{ji},  t = Σ ε_k q_k e_k                          (17)
 *   velocities    ω^i = ω^j + Σ (1 − ε_k) q̇_k e_k                               (16)
 *                 v^i = v^j + ω^j × s^{ij} + Σ ε_k q̇_k e_k + ω^i × d^i           (15)
 *                 ṗ^i = ½ E^{iT} ω^i
 *   accelerations (e fixed on j: ė = ω^j × e; a universal joint's second axis rides on i:
 *                 ė = ω^i × e)
 *                 α^i = α^j + Σ (1 − ε_k)(q̈_k e_k + q̇_k ė_k)
 *                 a^i = a^j + α^j × s^{ij} + ω^j × (ω^j × s^{ij})
 *                       + Σ ε_k (q̈_k e_k + 2 q̇_k ė_k + q_k ë_k) − α^i × s^{ji} − ω^i × (ω^i × s^{ji})
 *                 p̈^i = ½ E^{iT} α^i − ¼ |ω^i|² p^i
 * A free joint's translation t turns with j and s^{ji} with i: v^i = v^j + ω^j × s^{ij} + Σ ṫ'_k e_k
 * + ω^j × d^i + (ω^i − ω^j) × (r^i − P_i). A base body (q = x) has no reference body: kinematics.c.
 *
 * The needed wrench of body i (Newton–Euler, the paper's (4) and (26) term by term), about a point
 * P from which its centre of mass lies at c = r^i − P, in global axes:
 *   f = m (a − g) − f_e
 *   n = A (J' α' + ω' × J' ω') − n_e + c × f,     ω' = A^T ω,  α' = A^T α  (body axes, J' constant)
 * a the centre of mass's acceleration, (f_e, n_e) the applied wrench at the centre of mass (xfrc,
 * or everything applied to the body in the dense reactions). With P = O (c = r^i − O) it is the
 * term of Q (4); with P = P_i (c = −s^{ji}) the term each inward pass sums about the joint points.
 *
 * The spatial inertia of body i about the same point, in 13 numbers (m, h = m c, J_P):
 *   J = A J' A^T,   J_P = J + m (|c|² 1 − c c^T),   I s = (J_P w + h × v, m v + w × h)
 *
 * The kinematics' and the wrench's kernels take and return their vectors as values (base/v4.h:
 * a 3-vector in four lanes) and read nothing of vt_data: the caller loads the reference body's
 * values, and stores the body's own once they are known (its outputs might alias the inputs as
 * far as the compiler knows); vt_body_wrench_global and the inertias read theirs from d.
 */
#ifndef VT_KINEMATICS_BODY_H
#define VT_KINEMATICS_BODY_H

#include "vtdyn.h"
#include "base/euler.h"
#include "base/v4.h"
#include "base/vec3.h"
#include "model/model.h"

#if defined(__GNUC__)
#define VT_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define VT_ALWAYS_INLINE inline
#endif

/* p^j ⊗ (cs, sn u), the reference body's orientation turned by an angle whose half has cosine
 * cs and sine sn about the unit axis u, written out: (cs p0 − sn p·u, cs p + sn p0 u + sn p × u) */
static VT_ALWAYS_INLINE vt_v4 vt_body_turn(vt_v4 pj, double cs, double sn, vt_v4 u)
{
    const vt_v4 a = vt_v4_left(pj);
    const vt_v4 in = vt_v4_add(vt_v4_mul(vt_v4_x(pj), u), vt_v4_cross(a, u));
    return vt_v4_add(vt_v4_scale(cs, pj), vt_v4_scale(sn, vt_v4_with0(vt_v4_right(in), -vt_v4_dot3(a, u))));
}

/* p (holding p^j ⊗ p_J) ⊗ p0, the body's fixed offset (skipped when it is the identity bit for
 * bit), and A = A(p) and R = A^T */
static VT_ALWAYS_INLINE vt_v4 vt_body_orientation(vt_v4 p, const double p0[4], vt_m3 *A, vt_m3 *R)
{
    if (!vt_quat_is_identity(p0)) p = vt_v4_quat_mul(p, vt_v4_load(p0));
    vt_v4_rotation(p, A, R);
    return p;
}

/* (17): Pr = P_i − o, rr = r^i − o and d^i from rj = r^j − o, s^{ij}, the joint's translation t
 * (NULL for none: P_i − o = (r^j − o) + s^{ij}, d^i = 0 − s^{ji}) and s^{ji}; r^i − o from
 * P_i − o, not via d^i (a free root's t, its position, then cancels against o exactly) */
static VT_ALWAYS_INLINE void vt_body_position(vt_v4 *Pr, vt_v4 *rr, vt_v4 *di, vt_v4 rj, vt_v4 sij, const vt_v4 *t,
                                              vt_v4 sji)
{
    const vt_v4 b = vt_v4_add(rj, sij); /* for a root: (point on the ground − o), rounded once */
    *Pr = t ? vt_v4_add(b, *t) : b;
    *di = vt_v4_sub(t ? *t : vt_v4_splat(0.0), sji);
    *rr = vt_v4_sub(*Pr, sji);
}

/* (15)-(16): ω^i into w, v^i into v and ṗ^i into pd, for a joint of kind jt with nv rates along
 * the axes e (vt_dof_kind picks each rate's) at rates qd, from the reference body's ω^j (wj) and
 * v^j (vj), s^{ij}, d^i and p^i; sji (s^{ji}) is used by a free joint only */
static VT_ALWAYS_INLINE void vt_body_velocity(vt_v4 *w, vt_v4 *v, vt_v4 *pd, vt_v4 wj, vt_v4 vj, vt_v4 sij, vt_v4 di,
                                              vt_v4 sji, vt_v4 p, int jt, int nv, vt_m3 e, const double *qd)
{
    vt_v4 wi = wj, vi = vt_v4_add(vj, vt_v4_cross(wj, sij));
    for (int k = 0; k < nv; k++) {
        int ax;
        if (vt_dof_kind(jt, k, &ax) == VT_DOF_ROT) wi = vt_v4_madd(wi, qd[k], e.c[ax]);
        else vi = vt_v4_madd(vi, qd[k], e.c[ax]);
    }
    if (jt == VT_JOINT_FREE) { /* ω^j × t − ω^i × s^{ji} = ω^j × d^i + (ω^i − ω^j) × (r^i − P) */
        vi = vt_v4_add(vi, vt_v4_cross(wj, di));
        vi = vt_v4_add(vi, vt_v4_cross(vt_v4_sub(wi, wj), vt_v4_sub(vt_v4_splat(0.0), sji)));
    } else {
        vi = vt_v4_add(vi, vt_v4_cross(wi, di));
    }
    *w = wi;
    *v = vi;
    *pd = vt_v4_quat_rate(p, wi);
}

/* the accelerations: α^i into al, a^i into a and p̈^i into pdd, for a joint of kind jt with nv
 * rates along the axes e at q (the joint's coordinates), qd and qdd (NULL: q̈ = 0, Ṡq̇), from the
 * reference body's α^j (alj), a^j (aj) and ω^j (wj), ω^i (wi), s^{ij}, s^{ji} and p^i */
static VT_ALWAYS_INLINE void vt_body_acceleration(vt_v4 *al, vt_v4 *a, vt_v4 *pdd, vt_v4 alj, vt_v4 aj, vt_v4 wj,
                                                  vt_v4 wi, vt_v4 sij, vt_v4 sji, vt_v4 p, int jt, int nv,
                                                  vt_m3 e, const double *q, const double *qd,
                                                  const double *qdd)
{
    vt_v4 ali = alj, ai = vt_v4_add(vt_v4_add(aj, vt_v4_cross(alj, sij)), vt_v4_cross(wj, vt_v4_cross(wj, sij)));
    for (int k = 0; k < nv; k++) {
        int ax;
        const int kind = vt_dof_kind(jt, k, &ax);
        const vt_v4 ek = e.c[ax];
        const double qddk = qdd ? qdd[k] : 0.0;
        if (kind == VT_DOF_ROT) {
            const vt_v4 ed = vt_v4_cross((jt == VT_JOINT_UNIVERSAL && k == 1) ? wi : wj, ek);
            ali = vt_v4_madd(vt_v4_madd(ali, qddk, ek), qd[k], ed);
        } else {
            const double qk = q[jt == VT_JOINT_CYLINDRICAL ? 1 : (jt == VT_JOINT_FREE ? k : 0)];
            const vt_v4 ed = vt_v4_cross(wj, ek), edd = vt_v4_add(vt_v4_cross(alj, ek), vt_v4_cross(wj, ed));
            ai = vt_v4_madd(vt_v4_madd(vt_v4_madd(ai, qddk, ek), 2.0 * qd[k], ed), qk, edd);
        }
    }
    ai = vt_v4_sub(ai, vt_v4_cross(ali, sji));
    ai = vt_v4_sub(ai, vt_v4_cross(wi, vt_v4_cross(wi, sji)));
    *al = ali;
    *a = ai;
    *pdd = vt_v4_sub(vt_v4_quat_rate(p, ali), vt_v4_scale(0.25 * vt_v4_dot3(wi, wi), p));
}

/* W = (n − n_e + c × f, f = m (a − g) − f_e) for body i, from n = J α + ω × J ω (global axes,
 * however formed) and the applied wrench (f_e, n_e) at the centre of mass; W[0..3] and W[3..5]
 * written (W[3] twice) */
static VT_ALWAYS_INLINE void vt_body_wrench_n(double W[6], const vt_model *m, int i, vt_v4 n, vt_v4 a, vt_v4 g,
                                              vt_v4 fe, vt_v4 ne, vt_v4 c)
{
    const vt_v4 f = vt_v4_sub(vt_v4_scale(m->body_mass[i], vt_v4_sub(a, g)), fe);
    vt_v4_store3_up(W, vt_v4_add(vt_v4_sub(n, ne), vt_v4_cross(c, f)));
    vt_v4_store3(W + 3, f);
}

/* The needed wrench W of body i with orientation A (columns), from ω and α in body axes (wb,
 * ab): J' in body axes, n = A (J' α' + ω' × J' ω'), then vt_body_wrench_n */
static VT_ALWAYS_INLINE void vt_body_wrench(double W[6], const vt_model *m, int i, vt_m3 A, vt_v4 wb,
                                            vt_v4 ab, vt_v4 a, vt_v4 g, vt_v4 fe, vt_v4 ne, vt_v4 c)
{
    const vt_m3 J = vt_m3_load(m->body_inertia + 9 * i);
    const vt_v4 Ja = vt_v4_add(vt_m3_mul(J, ab), vt_v4_cross(wb, vt_m3_mul(J, wb)));
    vt_body_wrench_n(W, m, i, vt_m3_mul(A, Ja), a, g, fe, ne, c);
}

/* vt_body_wrench from d's orientation, ω and xfrc of body i and global α (al), arrays of three */
static inline void vt_body_wrench_global(double W[6], const vt_model *m, const vt_data *d, int i, const double a[3],
                                         const double al[3], const double c[3])
{
    const vt_m3 A = vt_m3_load(d->A + 9 * i), R = vt_m3_transpose(A);
    const double *fe = d->xfrc + 6 * i;
    vt_body_wrench(W, m, i, A, vt_m3_mul(R, vt_v4_load3(d->omega + 3 * i)), vt_m3_mul(R, vt_v4_load3(al)),
                   vt_v4_load3(a), vt_v4_load3(m->gravity), vt_v4_load3(fe), vt_v4_load3(fe + 3), vt_v4_load3(c));
}

/* body i's spatial inertia about the point from which its centre of mass lies at c, in 13 numbers:
 * (m, h = m c, J_O = J − m c̃ c̃), and J = A J' A^T (global axes, about the centre of mass) into J */
static inline void vt_body_inertia(double I[13], double J[9], const vt_model *m, const vt_data *d, int i, const double c[3])
{
    double t[9];
    const double mass = m->body_mass[i], *A = d->A + 9 * i, *Jb = m->body_inertia + 9 * i;
    for (int col = 0; col < 3; col++) vt_mulmat3(t + 3 * col, Jb, (double[3]){A[col], A[col + 3], A[col + 6]});
    double u[6]; /* A t, symmetric: its upper triangle */
    for (int col = 0, k = 0; col < 3; col++)
        for (int r = 0; r <= col; r++, k++) u[k] = A[r] * t[3 * col] + A[r + 3] * t[1 + 3 * col] + A[r + 6] * t[2 + 3 * col];
    J[0] = u[0], J[1] = J[3] = u[1], J[4] = u[2], J[2] = J[6] = u[3], J[5] = J[7] = u[4], J[8] = u[5];
    const double h0 = mass * c[0], h1 = mass * c[1], h2 = mass * c[2];
    const double o0 = h1 * c[1] + h2 * c[2], o1 = h0 * c[0] + h2 * c[2], o2 = h0 * c[0] + h1 * c[1];
    I[0] = mass, I[1] = h0, I[2] = h1, I[3] = h2; /* J_O = J + m (|c|² 1 − c c^T) */
    I[4] = u[0] + o0, I[5] = I[7] = u[1] - h0 * c[1], I[8] = u[2] + o1;
    I[6] = I[10] = u[3] - h0 * c[2], I[9] = I[11] = u[4] - h1 * c[2], I[12] = u[5] + o2;
}

/* vt_body_inertia, and body i's needed wrench at q̈ = 0 from the same global J (the general
 * route's bias wrench, without its turns to body axes: vt_body_wrench_n): W⁰ = (J α + ω × J ω − n_e + c × f, f = m (a − g) − f_e) about the
 * point from which the centre of mass lies at c, at the accelerations Ṡq̇ (α = 2 E p̈) */
static inline void vt_body_inertia_bias(double I[13], double W[6], const vt_model *m, const vt_data *d, int i, const double c[3])
{
    const int o = vt_xoff(i);
    const double *w = d->omega + 3 * i, *a = d->Sdqd + o, *fe = d->xfrc + 6 * i;
    double J[9], al[3], Jw[3], n[3];
    vt_body_inertia(I, J, m, d, i, c);
    vt_mulEp(al, d->x + o + 3, a + 3);
    for (int k = 0; k < 3; k++) al[k] *= 2.0;
    vt_mulmat3(n, J, al);
    vt_mulmat3(Jw, J, w);
    vt_addcross3(n, w, Jw);
    vt_body_wrench_n(W, m, i, vt_v4_load3(n), vt_v4_load3(a), vt_v4_load3(m->gravity), vt_v4_load3(fe),
                     vt_v4_load3(fe + 3), vt_v4_load3(c));
}

#endif
