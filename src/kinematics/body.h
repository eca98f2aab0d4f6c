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
 */
#ifndef VT_KINEMATICS_BODY_H
#define VT_KINEMATICS_BODY_H

#include "vtdyn.h"
#include "base/vec3.h"

#if defined(__GNUC__)
#define VT_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define VT_ALWAYS_INLINE inline
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

#endif
