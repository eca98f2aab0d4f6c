/* Kinematics and the velocity transformation S: the paper's (15)-(18), docs/method.md
 * "Velocity transformation S".
 *
 * Body i, reference body j, joint axes e_k (global), ε_k = 1 for a translational rate,
 * 0 for a rotational one (18):
 *   positions    A^i = A^j A_J(q^i) A0^i,   r^i = r^j + s^{ij} + Σ ε_k q_k e_k − s^{ji}
 *                s^{ij} = A^j s'^{ij},  s^{ji} = A^i s'^{ji},  d^i = −s^{ji} + Σ ε_k q_k e_k   (17)
 *   velocities   ω^i = ω^j + Σ (1 − ε_k) q̇_k e_k                                           (16)
 *                v^i = v^j + ω̃^j s^{ij} + Σ ε_k q̇_k e_k + ω̃^i d^i                          (15)
 *                ṗ^i = ½ E^{iT} ω^i
 *   S, column of rate k of joint b, in the rows of every body i whose path holds b, from the
 *   rate's twist (w, v) about the reference point o (d->twist): ṙ^i += v + w × (r^i − o),
 *   ṗ^i += ½ E^{iT} w; that is
 *                rotational axis e through the joint point P_b:  ṙ^i += e × (r^i − P_b),
 *                                                                ṗ^i += ½ E^{iT} e
 *                translational axis e:                           ṙ^i += e
 *                base body b (q = x^b): its own block is I7; below it ω^b = 2 E^b ṗ^b
 *   Ṡq̇ = ẍ at q̈ = 0, from the time derivative of the position relations
 *   (e fixed on j: ė = ω̃^j e; e2 of a universal joint is fixed on i: ė2 = ω̃^i e2):
 *                α^i = α^j + Σ (1 − ε_k)(q̈_k e_k + q̇_k ė_k)
 *                a^i = a^j + α̃^j s^{ij} + ω̃^j ω̃^j s^{ij} + Σ ε_k (q̈_k e_k + 2 q̇_k ė_k + q_k ë_k)
 *                      − α̃^i s^{ji} − ω̃^i ω̃^i s^{ji}
 *                p̈^i = ½ E^{iT} α^i − ¼ (ω^i·ω^i) p^i
 * Free joint (6 rates, q = [t'; p_J], q̇ = [ṫ'; ω_rel] in the reference body's axes): the triad
 * e_k = A^j's columns for both the translation (ε = 1, t = A^j t' = Σ q_k e_k) and the rotation
 * (ε = 0, as spherical); the joint point P = r^j + s^{ij} + t. Since t turns with j and s^{ji}
 * with i, (15) reads  v^i = v^j + ω̃^j (s^{ij} + t) + Σ ṫ'_k e_k − ω̃^i s^{ji}; its twists are
 * (0, e_k) and (e_k, (P − o) × e_k), and Ṡq̇ is the a^i above with q_k the translation's components.
 * Lever arms from o, not from the global origin: o = body 1's joint point P_1 at this instant
 * (d->origin), and the positions recur relative to it,
 *   P_i − o = (r^j − o) + s^{ij} + t,   r^i − o = (P_i − o) − s^{ji}   (ground: r^0 − o = −o)
 * (d->xrel; = (r^j − o) + s^{ij} + d^i, summed so that a free root's t, its position, cancels
 * against o exactly), the absolute r^i and P_i = o + those after. Twists and wrenches about the global
 * origin would carry |r|·ω and |r|·f terms that cancel in the results, losing digits with the
 * distance (squared through the inertias about O); from o each lever arm is exact to its own
 * size, and a ground point (a root's joint point, a cut joint's or point drive's point on the
 * ground) enters once as (point − o), rounded as the point itself is.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "kinematics/kinematics.h"
#include "kinematics/body.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/v4.h"
#include "base/vec3.h"
#include "model/model.h"

static const double zero3[3] = {0, 0, 0};
static const double unit_quat[4] = {1, 0, 0, 0};

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status check_q(const vt_model *m, vt_data *d)
{
    if (!vt_all_finite(d->q, m->nq)) /* which one, for the message */
        for (int k = 0; k < m->nq; k++)
            if (!isfinite(d->q[k]))
                return vt_fail(d->message, VT_ERR_NONFINITE, "vt_kinematics: q[%d] = %g", k, d->q[k]);
    return VT_OK;
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status check_qd(const vt_model *m, vt_data *d)
{
    if (!vt_all_finite(d->qd, m->nv))
        for (int k = 0; k < m->nv; k++)
            if (!isfinite(d->qd[k]))
                return vt_fail(d->message, VT_ERR_NONFINITE, "vt_kinematics: qd[%d] = %g", k, d->qd[k]);
    return VT_OK;
}

/* Euler parameters of norm 1 ideally: below 1e-12 is zero */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status check_quaternions(const vt_model *m, vt_data *d)
{
    const int *nq = m->body_nq;
    for (int i = 1; i <= m->nbody; i++) {
        if (nq[i] < 4) continue; /* Euler parameters: a spherical joint's 4 coordinates, a free or base one's 7 */
        const double *p = d->q + m->body_qadr[i] + (nq[i] == 4 ? 0 : 3);
        const double a0 = fabs(p[0]), a1 = fabs(p[1]), a2 = fabs(p[2]), a3 = fabs(p[3]);
        const double b0 = a0 > a1 ? a0 : a1, b1 = a2 > a3 ? a2 : a3;
        if ((b0 > b1 ? b0 : b1) > 1e-12) continue; /* |p| ≥ max |p_k| */
        double u[4] = {p[0], p[1], p[2], p[3]}; /* scaled: no underflow */
        if (!(vt_normalize(u, 4) > 1e-12))
            return vt_fail(d->message, VT_ERR_QUATERNION,
                           "vt_kinematics: body %d: Euler parameters of zero norm", i);
    }
    return VT_OK;
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status check_state(const vt_model *m, vt_data *d)
{
    vt_status st = check_q(m, d);
    if (!st) st = check_qd(m, d);
    return st ? st : check_quaternions(m, d);
}

/* x, A, joint axes e_k, s^{ij}, d^i and the joint point on the body; o and the positions from
 * it (xrel) */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void position(const vt_model *m, vt_data *d, int i)
{
    double *o = d->origin;
    {
        const int j = m->body_parent[i], jt = m->body_joint[i];
        const double *qi = d->q + m->body_qadr[i];
        const double *rj = d->xrel + 6 * j; /* r^j − o */
        const double *pj = j ? d->x + vt_xoff(j) + 3 : unit_quat;
        double *rr = d->xrel + 6 * i, *Pr = rr + 3;
        const double *Aj = d->A + 9 * j;
        const double *ax1 = m->body_axis + 6 * i, *ax2 = ax1 + 3;
        double *ri = d->x + vt_xoff(i), *pi = ri + 3, *Ai = d->A + 9 * i;
        double *e = d->jaxis + 9 * i, *sij = d->jsij + 3 * i, *di = d->jd + 3 * i;
        double *P = d->jpoint + 3 * i;

        memset(e, 0, 9 * sizeof(double));
        if (jt == VT_JOINT_BASE) {
            memcpy(ri, qi, 7 * sizeof(double));
            vt_euler_A(Ai, pi);
            memset(sij, 0, 3 * sizeof(double));
            memset(di, 0, 3 * sizeof(double));
            vt_copy3(P, ri);
            if (i == 1) { /* o = r^1: the ground at −o */
                vt_copy3(o, qi);
                for (int k = 0; k < 6; k++) d->xrel[k] = -o[k % 3];
            }
            for (int k = 0; k < 3; k++) rr[k] = Pr[k] = qi[k] - o[k];
            return;
        }
        /* the joint's turn p_J (or p itself), its axes e (zero where it has none) and translation t */
        const vt_v4 t0 = vt_v4_splat(0.0);
        const vt_m3 Ajv = vt_m3_load(Aj);
        vt_m3 ev = {{t0, t0, t0}};
        vt_v4 p, t = t0;
        const vt_v4 pjv = vt_v4_load(pj);
        switch (jt) {
        case VT_JOINT_REVOLUTE:
        case VT_JOINT_CYLINDRICAL: { /* p^i = p^j ⊗ (cos ½q, sin ½q u): vt_body_turn */
            double cs, sn;
            vt_sincos(0.5 * qi[0], &sn, &cs);
            const vt_v4 u = vt_v4_load3(ax1);
            p = vt_body_turn(pjv, cs, sn, u);
            ev.c[0] = vt_m3_mul(Ajv, u);
            if (jt == VT_JOINT_CYLINDRICAL) t = vt_v4_scale(qi[1], ev.c[0]);
            break;
        }
        case VT_JOINT_UNIVERSAL: {
            double p1[4], p2[4], pJ[4], A1[9], a2[3];
            vt_quat_axis_angle(p1, ax1, qi[0]);
            vt_quat_axis_angle(p2, ax2, qi[1]);
            vt_quat_mul(pJ, p1, p2);
            vt_euler_A(A1, p1);
            vt_mulmat3(a2, A1, ax2); /* e2 rides on the body: turned by the first angle */
            ev.c[0] = vt_m3_mul(Ajv, vt_v4_load3(ax1));
            ev.c[1] = vt_m3_mul(Ajv, vt_v4_load3(a2));
            p = vt_v4_quat_mul(pjv, vt_v4_load(pJ));
            break;
        }
        case VT_JOINT_SPHERICAL:
        case VT_JOINT_FREE: { /* free: the translation (reference axes), then as spherical */
            double pJ[4];
            memcpy(pJ, jt == VT_JOINT_FREE ? qi + 3 : qi, sizeof pJ);
            vt_normalize(pJ, 4); /* scaled: no overflow for a norm ≥ 1e154 */
            ev = Ajv; /* triad: the reference body's axes */
            if (jt == VT_JOINT_FREE) t = vt_m3_mul(Ajv, vt_v4_load3(qi));
            p = vt_v4_quat_mul(pjv, vt_v4_load(pJ));
            break;
        }
        default: /* translational: p^i = p^j */
            p = pjv;
            ev.c[0] = vt_m3_mul(Ajv, vt_v4_load3(ax1));
            t = vt_v4_scale(qi[0], ev.c[0]);
            break;
        }
        vt_m3 A, R;
        p = vt_body_orientation(p, m->body_quat0 + 4 * i, &A, &R);
        const int ne = jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_FREE ? 3 : jt == VT_JOINT_UNIVERSAL ? 2 : 1;
        for (int k = 0; k < ne; k++) vt_v4_store3(e + 3 * k, ev.c[k]);
        vt_v4_store(pi, p);
        for (int k = 0; k < 3; k++) vt_v4_store3(Ai + 3 * k, A.c[k]);

        const vt_v4 sv = vt_m3_mul(Ajv, vt_v4_load3(m->body_jpar + 3 * i));
        const vt_v4 sji = vt_m3_mul(A, vt_v4_load3(m->body_jchild + 3 * i));
        vt_v4_store3(sij, sv);
        if (i == 1) { /* o = P_1 (the ground's A is I: s^{01} is the point on the ground) */
            vt_v4_store3(o, vt_v4_add(sv, t));
            for (int k = 0; k < 6; k++) d->xrel[k] = -o[k % 3];
        }
        vt_v4 Prv, rrv, dv;
        vt_body_position(&Prv, &rrv, &dv, vt_v4_load3(rj), sv, &t, sji);
        const vt_v4 ov = vt_v4_load3(o);
        vt_v4_store3(Pr, Prv);
        vt_v4_store3(rr, rrv);
        vt_v4_store3(di, dv);
        vt_v4_store3(ri, vt_v4_add(ov, rrv));
        vt_v4_store3(P, vt_v4_add(ov, Prv));
    }
}

/* ω (16), v (15), ṗ = ½ E^T ω */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void velocity(const vt_model *m, vt_data *d, int i)
{
    {
        const int j = m->body_parent[i], jt = m->body_joint[i];
        const double *qdi = d->qd + m->body_vadr[i];
        const double *wj = d->omega + 3 * j;
        const double *vj = j ? d->xd + vt_xoff(j) : zero3;
        const double *pi = d->x + vt_xoff(i) + 3;
        double *wi = d->omega + 3 * i, *vi = d->xd + vt_xoff(i), *pdi = vi + 3;
        if (jt == VT_JOINT_BASE) {
            double E[12];
            vt_euler_E(E, pi);
            memcpy(vi, qdi, 7 * sizeof(double));
            vt_mulE(wi, E, pdi);
            wi[0] *= 2; wi[1] *= 2; wi[2] *= 2;
            return;
        }
        double sji[3] = {0, 0, 0};
        if (jt == VT_JOINT_FREE) vt_joint_child(sji, m, d, i);
        const double *ej = d->jaxis + 9 * i;
        const vt_m3 e = {{vt_v4_load3(ej), vt_v4_load3(ej + 3), vt_v4_load3(ej + 6)}};
        vt_v4 w, v, pd; /* stored once known: the outputs might alias the inputs */
        vt_body_velocity(&w, &v, &pd, vt_v4_load3(wj), vt_v4_load3(vj), vt_v4_load3(d->jsij + 3 * i),
                         vt_v4_load3(d->jd + 3 * i), vt_v4_load3(sji), vt_v4_load(pi), jt, m->body_nv[i], e, qdi);
        vt_v4_store3(wi, w);
        vt_v4_store3(vi, v);
        vt_v4_store(pdi, pd);
    }
}

/* Twist of every rate about the reference point o, into d->twist: angular part w, velocity of
 * the point at o v. Rotational axis e through the joint point P: (e, (P − o) × e); translational
 * e: (0, e); a base body's r_k: (0, e_k); its ṗ_k: ω = 2 E^b e_k about r^b, (ω, (r^b − o) × ω). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void twist(const vt_model *m, vt_data *d, int dof)
{
    {
        const int b = m->dof_body[dof], jt = m->body_joint[b];
        const double *e = d->jaxis + 9 * b;
        double *w = d->twist + 6 * dof, *v = w + 3;
        int ax;
        switch (vt_dof_kind(jt, dof - m->body_vadr[b], &ax)) {
        case VT_DOF_ROT:
            vt_copy3(w, e + 3 * ax);
            vt_cross3(v, d->xrel + 6 * b + 3, w);
            break;
        case VT_DOF_TRANS:
            w[0] = w[1] = w[2] = 0.0;
            vt_copy3(v, e + 3 * ax);
            break;
        case VT_DOF_BASE_R:
            w[0] = w[1] = w[2] = 0.0;
            v[0] = v[1] = v[2] = 0.0;
            v[ax] = 1.0;
            break;
        default: { /* VT_DOF_BASE_P */
            double E[12];
            vt_euler_E(E, d->x + vt_xoff(b) + 3);
            for (int r = 0; r < 3; r++) w[r] = 2.0 * E[3 * ax + r];
            vt_cross3(v, d->xrel + 6 * b, w);
            break;
        }
        }
    }
}

/* the twists of body b's rates */
static inline void twists(const vt_model *m, vt_data *d, int b)
{
    for (int dof = m->body_vadr[b]; dof < m->body_vadr[b] + m->body_nv[b]; dof++) twist(m, d, dof);
}

/* Body i's positions, its rates' twists and its velocities, its reference body's known (body 1
 * first: it sets o; d->origin and the ground's xrel zeroed before) */
void vt_kinematics_body(const vt_model *m, vt_data *d, int i)
{
    position(m, d, i);
    twists(m, d, i);
    velocity(m, d, i);
}



/* An upper bound on |r^i − o| and on the size of its round-off, for every body, into L[stride i]:
 * the lengths of the vectors r^i − o is summed from (xrel: the root's joint point from o, then
 * s^{ij} + t and s^{ji} down the tree, as vt_lever sums them); two point masses at o at the ends
 * of 7.5 m links have |r − o| = 0 but round-off of 7.5 ε in it. O(n), parents first:
 *   L_i = |s^{ji}_i| + (|s^{ij}_i + t_i| + L_j, or |P_i − o| for a root) */
void vt_lengths_from_o(const vt_model *m, const vt_data *d, double *L, int stride)
{
    for (int i = 1; i <= m->nbody; i++) {
        const int j = m->body_parent[i];
        double s[3], a[3];
        vt_joint_child(s, m, d, i);
        if (j) {
            for (int c = 0; c < 3; c++) a[c] = d->jsij[3 * i + c] + (d->jd[3 * i + c] + s[c]);
            L[stride * i] = sqrt(vt_dot3(s, s)) + sqrt(vt_dot3(a, a)) + L[stride * j];
        } else {
            const double *P = d->xrel + 6 * i + 3;
            L[stride * i] = sqrt(vt_dot3(s, s)) + sqrt(vt_dot3(P, P));
        }
    }
}

/* Column `dof` (a rate of joint L->k) of S in body i's rows, with the lever arm u = r^i − P_k:
 * a turning rate (axis or base body's ω = 2 E e, its twist's w) ṙ^i = w × u, ṗ^i = ½ E^{iT} w;
 * a sliding one ṙ^i = e; a base body's own ṗ, S's block I. Ei = E(p^i). */
void vt_S_column(double c[7], const vt_model *m, const vt_data *d, int i, const double Ei[12], int dof, const double u[3])
{
    int ax;
    const int kind = vt_dof_kind(m->body_joint[m->dof_body[dof]], dof - m->body_vadr[m->dof_body[dof]], &ax);
    const double *w = d->twist + 6 * dof;
    memset(c, 0, 7 * sizeof(double));
    if (kind == VT_DOF_BASE_P && m->dof_body[dof] == i) c[3 + ax] = 1.0;
    else if (kind == VT_DOF_ROT || kind == VT_DOF_BASE_P) {
        vt_cross3(c, w, u);
        vt_mulE_t(c + 3, Ei, w);
        for (int r = 3; r < 7; r++) c[r] *= 0.5;
    } else vt_copy3(c, w + 3); /* the axis (a base body's unit vector): the twist's v */
}

/* The non-zero blocks of S: body i's rows, the columns of its path, with lever arms along the
 * tree (vt_lever_start) */
static void fill_S(const vt_model *m, vt_data *d)
{
    const size_t ld = (size_t)m->nx;
    for (int i = 1; i <= m->nbody; i++) {
        double Ei[12];
        vt_euler_E(Ei, d->x + vt_xoff(i) + 3);
        vt_lever L;
        vt_lever_start(&L, m, d, i, 0);
        do {
            for (int a = m->body_vadr[L.k]; a < m->body_vadr[L.k] + m->body_nv[L.k]; a++)
                vt_S_column(d->S + (size_t)a * ld + (size_t)vt_xoff(i), m, d, i, Ei, a, L.u);
        } while (vt_lever_up(&L, m, d));
    }
}

/* Copies body i's rows of S on its path columns into Si (7 x k, ld 7). */
void vt_gather_S(double *Si, const vt_model *m, const vt_data *d, int i, const int *path)
{
    for (int c = 0; c < m->body_pathnum[i]; c++)
        memcpy(Si + 7 * c, d->S + (size_t)path[c] * (size_t)m->nx + (size_t)vt_xoff(i), 7 * sizeof(double));
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void acceleration(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, int i)
{
    {
        const int j = m->body_parent[i], jt = m->body_joint[i];
        const double *qi = d->q + m->body_qadr[i], *qdi = d->qd + m->body_vadr[i];
        const double *qddi = qdd ? qdd + m->body_vadr[i] : NULL;
        const double *wj = d->omega + 3 * j, *wi = d->omega + 3 * i;
        const double *alj = alpha + 3 * j;
        const double *aj = j ? out + vt_xoff(j) : zero3;
        const double *ri = d->x + vt_xoff(i), *pi = ri + 3;
        double *ali = alpha + 3 * i, *ai = out + vt_xoff(i), *pddi = ai + 3;
        if (jt == VT_JOINT_BASE) {
            double E[12];
            vt_euler_E(E, pi);
            if (qddi) memcpy(ai, qddi, 7 * sizeof(double));
            else memset(ai, 0, 7 * sizeof(double));
            vt_mulE(ali, E, pddi); /* α = 2 E p̈ + 2 Ė ṗ, and Ė ṗ = E(ṗ) ṗ = 0 */
            ali[0] *= 2; ali[1] *= 2; ali[2] *= 2;
            return;
        }
        double sji[3];
        vt_joint_child(sji, m, d, i); /* not (P_i − o) − (r^i − o): exact far from o */
        const double *ej = d->jaxis + 9 * i;
        const vt_m3 e = {{vt_v4_load3(ej), vt_v4_load3(ej + 3), vt_v4_load3(ej + 6)}};
        vt_v4 al, a, pdd; /* stored once known: out may alias the inputs */
        vt_body_acceleration(&al, &a, &pdd, vt_v4_load3(alj), vt_v4_load3(aj), vt_v4_load3(wj), vt_v4_load3(wi),
                             vt_v4_load3(d->jsij + 3 * i), vt_v4_load3(sji), vt_v4_load(pi), jt, m->body_nv[i], e, qi,
                             qdi, qddi);
        vt_v4_store(pddi, pdd);
        vt_v4_store3(ali, al);
        vt_v4_store3(ai, a);
    }
}

/* Cartesian accelerations ẍ = S q̈ + Ṡ q̇ into out (7n); with qdd == NULL, Ṡ q̇.
 * alpha: angular accelerations (3 x (nbody+1)), filled as well. */
void vt_accelerations(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha)
{
    memset(alpha, 0, 3 * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) acceleration(m, d, qdd, out, alpha, i);
}

/* body i's row of vt_accelerations, its reference body's known (alpha's ground entry zeroed) */
void vt_acceleration_body(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, int i)
{
    acceleration(m, d, qdd, out, alpha, i);
}

/* ẍ = S q̈ + Ṡq̇ from the stored Ṡq̇ (d->Sdqd) and the rates' twists, outward: the twist of
 * accelerations T^i = T^j + Σ_own q̈_a s_a (a sum of twists about o) gives
 *   α^i = α0^i + T_w,   a^i = a0^i + T_v + T_w × (r^i − o),   p̈^i = p̈0^i + ½ E^{iT} T_w
 * with α0 = 2 E p̈0 (E p = 0, E E^T = I); a base body's own ṗ rates enter its p̈ as themselves
 * (S's block I), whose part along p the twist form leaves out: p̈ += p (p · q̈_p). */
void vt_accelerations_add(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, double *T)
{
    memset(T, 0, 6 * sizeof(double));
    if (alpha) memset(alpha, 0, 3 * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) {
        const int j = m->body_parent[i], o = vt_xoff(i);
        double *ai = out + o, t[6], a[3], pdd[4]; /* locals, stored once: out may alias the inputs */
        const double *pi = d->x + o + 3, *a0 = d->Sdqd + o;
        memcpy(t, T + 6 * j, sizeof t);
        for (int k = m->body_vadr[i]; k < m->body_vadr[i] + m->body_nv[i]; k++) {
            const double *s = d->twist + 6 * k;
            for (int c = 0; c < 6; c++) t[c] += qdd[k] * s[c];
        }
        memcpy(T + 6 * i, t, sizeof t);
        if (alpha) {
            double *ali = alpha + 3 * i;
            vt_mulEp(ali, pi, a0 + 3);
            for (int c = 0; c < 3; c++) ali[c] = 2.0 * ali[c] + t[c];
        }
        for (int c = 0; c < 3; c++) a[c] = a0[c] + t[3 + c];
        vt_addcross3(a, t, d->xrel + 6 * i);
        vt_quat_rate(pdd, pi, t); /* ½ E^T T_w */
        vt_copy3(ai, a);
        for (int c = 0; c < 4; c++) ai[3 + c] = a0[3 + c] + pdd[c];
        if (m->body_joint[i] == VT_JOINT_BASE) {
            const double *qp = qdd + m->body_vadr[i] + 3;
            const double pq = pi[0] * qp[0] + pi[1] * qp[1] + pi[2] * qp[2] + pi[3] * qp[3];
            for (int c = 0; c < 4; c++) ai[3 + c] += pq * pi[c];
        }
    }
}

/* The same from the dense S (its lever arms along the tree, fill_S): ẍ^i = Ṡq̇^i + Σ_c S_ic q̈_c over
 * i's path, α^i = α0^i + Σ_c w_c q̈_c; no term carries |r − o|, so the accelerations of a mechanism
 * far from o keep the digits of its own lengths. The sums run root first (vt_body_path). */
void vt_accelerations_dense(const vt_model *m, vt_data *d, const double *qdd, double *out, double *alpha, int *path)
{
    const size_t ld = (size_t)m->nx;
    memset(alpha, 0, 3 * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) {
        const int o = vt_xoff(i), np = vt_body_path(m, i, path);
        const double *a0 = d->Sdqd + o;
        double a[7], al[3];
        memcpy(a, a0, sizeof a);
        vt_mulEp(al, d->x + o + 3, a0 + 3);
        for (int c = 0; c < 3; c++) al[c] *= 2.0;
        for (int k = 0; k < np; k++) {
            const int c = path[k];
            const double *col = d->S + (size_t)c * ld + (size_t)o, *w = d->twist + 6 * c;
            for (int r = 0; r < 7; r++) a[r] += col[r] * qdd[c];
            for (int r = 0; r < 3; r++) al[r] += w[r] * qdd[c];
        }
        memcpy(out + o, a, sizeof a);
        vt_copy3(alpha + 3 * i, al);
    }
}

/* A finite state can still overflow (a base body's Euler parameters ×1e200 enter A squared, a
 * rate of 1e300 rad/s its square in Ṡq̇): the outputs are scanned (branch-free, O(n)) and the
 * first body with a non-finite one is named; parts: which outputs (OUT_POSITIONS: x, A, the joint
 * points, d^i and the twists; OUT_VELOCITIES: ω, ẋ; OUT_SDQD: Ṡq̇). */
enum { OUT_POSITIONS = 1, OUT_VELOCITIES = 2, OUT_SDQD = 4 };
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline vt_status check_outputs(const vt_model *m, vt_data *d, const int parts)
{
    const int n = m->nbody, nb = n + 1, pos = parts & OUT_POSITIONS, vel = parts & OUT_VELOCITIES,
              acc = parts & OUT_SDQD;
    vt_finite_scan s = {0}; /* the outputs as one scan */
    if (pos) {
        vt_finite_add(&s, d->x, 7 * n);
        vt_finite_add(&s, d->A, 9 * nb);
        vt_finite_add(&s, d->jpoint, 3 * nb);
        vt_finite_add(&s, d->jd, 3 * nb);
        vt_finite_add(&s, d->twist, 6 * m->nv);
    }
    if (vel) {
        vt_finite_add(&s, d->omega, 3 * nb);
        vt_finite_add(&s, d->xd, 7 * n);
    }
    if (acc) vt_finite_add(&s, d->Sdqd, 7 * n);
    if (vt_finite_ok(&s)) return VT_OK;
    for (int i = 1; i <= n; i++) {
        const char *what = NULL;
        if (pos && (!vt_all_finite(d->x + vt_xoff(i), 7) || !vt_all_finite(d->A + 9 * i, 9) ||
                    !vt_all_finite(d->jpoint + 3 * i, 3) || !vt_all_finite(d->jd + 3 * i, 3)))
            what = "position or orientation";
        else if ((vel && (!vt_all_finite(d->omega + 3 * i, 3) || !vt_all_finite(d->xd + vt_xoff(i), 7))) ||
                 (pos && !vt_all_finite(d->twist + 6 * m->body_vadr[i], 6 * m->body_nv[i])))
            what = "velocity";
        else if (acc && !vt_all_finite(d->Sdqd + vt_xoff(i), 7))
            what = "acceleration at q̈ = 0 (Ṡq̇)";
        if (what)
            return vt_fail(d->message, VT_ERR_NONFINITE,
                           "vt_kinematics: body %d: %s overflows (q or q̇ too large; Euler parameters should be unit)", i, what);
    }
    return vt_fail(d->message, VT_ERR_NONFINITE, "vt_kinematics: an output overflows (q or q̇ too large)");
}

/* vt_kinematics_tree's checks, for a pass that computes the same outputs (recursive/fused.c's
 * outward pass): the state before, the outputs (without Ṡq̇) after */
vt_status vt_kinematics_check_state(const vt_model *m, vt_data *d)
{
    return check_state(m, d);
}

vt_status vt_kinematics_check_quaternions(const vt_model *m, vt_data *d)
{
    return check_quaternions(m, d);
}

vt_status vt_kinematics_check_outputs(const vt_model *m, vt_data *d)
{
    return check_outputs(m, d, OUT_POSITIONS | OUT_VELOCITIES);
}

/* Ṡq̇ into d->Sdqd (its angular accelerations on the arena) */
static vt_status sdqd(const vt_model *m, vt_data *d)
{
    const size_t mark = vt_scratch_mark(d);
    double *alpha = VT_SCRATCH(d, double, 3 * ((size_t)m->nbody + 1), "α at q̈ = 0");
    if (!alpha) return vt_scratch_fail(d, mark);
    vt_accelerations(m, d, NULL, d->Sdqd, alpha);
    vt_scratch_release(d, mark);
    return VT_OK;
}

vt_status vt_kinematics_tree(const vt_model *m, vt_data *d, int Sdqd)
{
    vt_status st = check_state(m, d);
    if (st) return st;
    d->origin[0] = d->origin[1] = d->origin[2] = 0.0;
    memset(d->xrel, 0, 6 * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) position(m, d, i);
    for (int dof = 0; dof < m->nv; dof++) twist(m, d, dof);
    for (int i = 1; i <= m->nbody; i++) velocity(m, d, i);
    if (Sdqd && (st = sdqd(m, d))) return st;
    return check_outputs(m, d, OUT_POSITIONS | OUT_VELOCITIES | (Sdqd ? OUT_SDQD : 0));
}

/* vt_kinematics_tree in two halves: the positions and the rates' twists from q alone (Newton's
 * evaluations need no more), then the velocities and Ṡq̇ from q̇ with the positions known (the
 * instant at Newton's converged q) */
vt_status vt_kinematics_positions(const vt_model *m, vt_data *d)
{
    vt_status st = check_q(m, d);
    if (st || (st = check_quaternions(m, d))) return st;
    d->origin[0] = d->origin[1] = d->origin[2] = 0.0;
    memset(d->xrel, 0, 6 * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) position(m, d, i);
    for (int dof = 0; dof < m->nv; dof++) twist(m, d, dof);
    return check_outputs(m, d, OUT_POSITIONS);
}

vt_status vt_kinematics_velocities(const vt_model *m, vt_data *d, int Sdqd)
{
    vt_status st = check_qd(m, d);
    if (st) return st;
    for (int i = 1; i <= m->nbody; i++) velocity(m, d, i);
    if (Sdqd && (st = sdqd(m, d))) return st;
    return check_outputs(m, d, OUT_VELOCITIES | (Sdqd ? OUT_SDQD : 0));
}

/* the angular accelerations of Ṡq̇ */
size_t vt_kinematics_scratch(const vt_model *m)
{
    return VT_SCRATCH_BYTES(3 * ((size_t)m->nbody + 1), sizeof(double));
}

vt_status vt_kinematics(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_kinematics");
    if (st) return st;
    if ((st = vt_kinematics_tree(m, d, 1))) return st;
    fill_S(m, d);
    const size_t nS = (size_t)m->nx * (size_t)m->nv;
    if (vt_all_finite(d->S, nS)) return VT_OK;
    for (size_t k = 0; k < nS; k++)
        if (!isfinite(d->S[k]))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_kinematics: S of body %d, rate %d overflows (q too large)",
                           (int)(k % (size_t)m->nx) / 7 + 1, (int)(k / (size_t)m->nx));
    return VT_OK;
}
