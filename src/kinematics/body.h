/* vtdyn — One body's kernels, written once and called by every pass (kinematics/kinematics.c, the
 * recursive passes in recursive/, the dense reactions in dense/reactions.c).
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
