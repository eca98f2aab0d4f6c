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
 * The kernels compute into the caller's locals and read their inputs once: the caller's outputs
 * in vt_data might alias the inputs as far as the compiler knows.
 */
#ifndef VT_KINEMATICS_BODY_H
#define VT_KINEMATICS_BODY_H

#include "vtdyn.h"
#include "base/euler.h"
#include "base/vec3.h"
#include "model/model.h"

#if defined(__GNUC__)
#define VT_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define VT_ALWAYS_INLINE inline
#endif

/* p = p^j ⊗ (cs, sn u), the reference body's orientation turned by an angle whose half has
 * cosine cs and sine sn about the unit axis u, written out: (cs p0 − sn p·u, cs p + sn p0 u +
 * sn p × u) */
static VT_ALWAYS_INLINE void vt_body_turn(double p[4], const double pj[4], double cs, double sn, const double u[3])
{
    const double a0 = pj[0], a1 = pj[1], a2 = pj[2], a3 = pj[3];
    p[0] = cs * a0 - sn * (a1 * u[0] + a2 * u[1] + a3 * u[2]);
    p[1] = cs * a1 + sn * (a0 * u[0] + a2 * u[2] - a3 * u[1]);
    p[2] = cs * a2 + sn * (a0 * u[1] + a3 * u[0] - a1 * u[2]);
    p[3] = cs * a3 + sn * (a0 * u[2] + a1 * u[1] - a2 * u[0]);
}

/* p (holding p^j ⊗ p_J) ⊗= p0, the body's fixed offset (skipped when it is the identity bit for
 * bit), and A = A(p) */
static VT_ALWAYS_INLINE void vt_body_orientation(double p[4], double A[9], const double p0[4])
{
    if (!vt_quat_is_identity(p0)) vt_quat_mul_inline(p, p, p0);
    vt_euler_A_inline(A, p);
}

/* (17): Pr = P_i − o, rr = r^i − o and d^i from rj = r^j − o, s^{ij}, the joint's translation t
 * (NULL for none: P_i − o = (r^j − o) + s^{ij}, d^i = 0 − s^{ji}) and s^{ji}; r^i − o from
 * P_i − o, not via d^i (a free root's t, its position, then cancels against o exactly) */
static VT_ALWAYS_INLINE void vt_body_position(double Pr[3], double rr[3], double di[3], const double rj[3],
                                              const double sij[3], const double *t, const double sji[3])
{
    for (int k = 0; k < 3; k++) {
        const double b = rj[k] + sij[k]; /* for a root: (point on the ground − o), rounded once */
        if (t) {
            di[k] = t[k] - sji[k];
            Pr[k] = b + t[k];
        } else {
            di[k] = 0.0 - sji[k];
            Pr[k] = b;
        }
        rr[k] = Pr[k] - sji[k];
    }
}

/* (15)-(16): ω^i into w, v^i into v and ṗ^i into pd, for a joint of kind jt with nv rates along
 * the axes e (3 each; vt_dof_kind picks each rate's) at rates qd, from the reference body's ω^j
 * (wj) and v^j (vj), s^{ij}, d^i and p^i; sji (s^{ji}) is read for a free joint only */
static VT_ALWAYS_INLINE void vt_body_velocity(double w[3], double v[3], double pd[4], const double wj[3],
                                              const double vj[3], const double sij[3], const double di[3],
                                              const double *sji, const double p[4], int jt, int nv,
                                              const double *e, const double *qd)
{
    vt_copy3(w, wj);
    vt_copy3(v, vj);
    vt_addcross3(v, wj, sij);
    for (int k = 0; k < nv; k++) {
        int ax;
        if (vt_dof_kind(jt, k, &ax) == VT_DOF_ROT) vt_axpy3(w, qd[k], e + 3 * ax);
        else vt_axpy3(v, qd[k], e + 3 * ax);
    }
    if (jt == VT_JOINT_FREE) { /* ω^j × t − ω^i × s^{ji} = ω^j × d^i + (ω^i − ω^j) × (r^i − P) */
        double dw[3], u[3];
        for (int k = 0; k < 3; k++) {
            dw[k] = w[k] - wj[k];
            u[k] = -sji[k]; /* r^i − P = −s^{ji}, not (r^i − o) − (P − o) */
        }
        vt_addcross3(v, wj, di);
        vt_addcross3(v, dw, u);
    } else {
        vt_addcross3(v, w, di);
    }
    vt_quat_rate(pd, p, w);
}

/* the accelerations: α^i into al, a^i into a and p̈^i into pdd, for a joint of kind jt with nv
 * rates along the axes e at q (the joint's coordinates), qd and qdd (NULL: q̈ = 0, Ṡq̇), from the
 * reference body's α^j (alj), a^j (aj) and ω^j (wj), ω^i (wi), s^{ij}, s^{ji} and p^i */
static VT_ALWAYS_INLINE void vt_body_acceleration(double al[3], double a[3], double pdd[4], const double alj[3],
                                                  const double aj[3], const double wj[3], const double wi[3],
                                                  const double sij[3], const double sji[3], const double p[4],
                                                  int jt, int nv, const double *e, const double *q,
                                                  const double *qd, const double *qdd)
{
    double t[3], u[3];
    vt_copy3(al, alj);
    vt_copy3(a, aj);
    vt_addcross3(a, alj, sij);
    vt_cross3(t, wj, sij);
    vt_addcross3(a, wj, t);
    for (int k = 0; k < nv; k++) {
        int ax;
        const int kind = vt_dof_kind(jt, k, &ax);
        const double *ek = e + 3 * ax, qddk = qdd ? qdd[k] : 0.0;
        double ed[3];
        if (kind == VT_DOF_ROT) {
            vt_cross3(ed, (jt == VT_JOINT_UNIVERSAL && k == 1) ? wi : wj, ek);
            vt_axpy3(al, qddk, ek);
            vt_axpy3(al, qd[k], ed);
        } else {
            double edd[3];
            const double qk = q[jt == VT_JOINT_CYLINDRICAL ? 1 : (jt == VT_JOINT_FREE ? k : 0)];
            vt_cross3(ed, wj, ek);
            vt_cross3(edd, alj, ek);
            vt_addcross3(edd, wj, ed);
            vt_axpy3(a, qddk, ek);
            vt_axpy3(a, 2.0 * qd[k], ed);
            vt_axpy3(a, qk, edd);
        }
    }
    vt_cross3(u, al, sji);
    for (int r = 0; r < 3; r++) a[r] -= u[r];
    vt_cross3(t, wi, sji);
    vt_cross3(u, wi, t);
    for (int r = 0; r < 3; r++) a[r] -= u[r];
    vt_quat_rate(pdd, p, al);
    const double w2 = vt_dot3(wi, wi);
    for (int r = 0; r < 4; r++) pdd[r] -= 0.25 * w2 * p[r];
}

/* W = (n − n_e + c × f, f = m (a − g) − f_e) for body i, from n = J α + ω × J ω (global axes,
 * however formed) and fe = (f_e, n_e); built in locals and written once (W might alias the inputs
 * as far as the compiler knows) */
static VT_ALWAYS_INLINE void vt_body_wrench_n(double W[6], const vt_model *m, int i, const double n_in[3],
                                              const double a[3], const double fe[6], const double c[3])
{
    const double mass = m->body_mass[i];
    double f[3], n[3];
    for (int k = 0; k < 3; k++) {
        f[k] = mass * (a[k] - m->gravity[k]) - fe[k];
        n[k] = n_in[k] - fe[3 + k];
    }
    vt_addcross3(n, c, f);
    vt_copy3(W, n);
    vt_copy3(W + 3, f);
}

/* The needed wrench W of body i with orientation A, from ω and α in body axes (wb, ab): J' in
 * body axes, n = A (J' α' + ω' × J' ω'), then vt_body_wrench_n */
static VT_ALWAYS_INLINE void vt_body_wrench(double W[6], const vt_model *m, int i, const double A[9], const double wb[3],
                                            const double ab[3], const double a[3], const double fe[6], const double c[3])
{
    const double *Jb = m->body_inertia + 9 * i;
    double Jw[3], Ja[3], n[3];
    vt_mulmat3(Jw, Jb, wb);
    vt_mulmat3(Ja, Jb, ab);
    vt_addcross3(Ja, wb, Jw);
    vt_mulmat3(n, A, Ja);
    vt_body_wrench_n(W, m, i, n, a, fe, c);
}

/* vt_body_wrench from d's orientation, ω and xfrc of body i and global α (al) */
static inline void vt_body_wrench_global(double W[6], const vt_model *m, const vt_data *d, int i, const double a[3],
                                         const double al[3], const double c[3])
{
    const double *Ai = d->A + 9 * i;
    double wb[3], ab[3];
    vt_mulmat3t(wb, Ai, d->omega + 3 * i);
    vt_mulmat3t(ab, Ai, al);
    vt_body_wrench(W, m, i, Ai, wb, ab, a, d->xfrc + 6 * i, c);
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
    const double *w = d->omega + 3 * i, *a = d->Sdqd + o;
    double J[9], al[3], Jw[3], n[3];
    vt_body_inertia(I, J, m, d, i, c);
    vt_mulEp(al, d->x + o + 3, a + 3);
    for (int k = 0; k < 3; k++) al[k] *= 2.0;
    vt_mulmat3(n, J, al);
    vt_mulmat3(Jw, J, w);
    vt_addcross3(n, w, Jw);
    vt_body_wrench_n(W, m, i, n, a, d->xfrc + 6 * i, c);
}

#endif
