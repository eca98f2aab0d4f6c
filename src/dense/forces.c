/* Forces: the paper's (4), (7), (9), (10) and docs/method.md "Equations of motion".
 *
 *   F^i = [f; 2 E^T s̃ f + 2 E^T n]          force f, moment n at body point s (7)
 *         gravity adds [m^i g; 0]; d->xfrc holds f and the moment about the centre of mass
 *   h^i = −Ṁ^i ẋ^i + (∂T^i/∂x^i)^T = [0; −8 Ġ^T J' G ṗ]
 *   Q   = S^T [F − M Ṡq̇ + h] (+ qfrc, a generalized force the caller applies)   (4)
 *   Q   = S^T F for a Cartesian force alone  (10)
 * As in mass.c, S^T acts body by body on the columns of the body's path only.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dense/forces.h"
#include "base/lapack.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "dense/mass.h"
#include "kinematics/joint_effects.h"

vt_status vt_cartesian_force(double F[7], const double p[4], const double s[3], const double f[3],
                             const double n[3])
{
    if (!F || !p || !s || !f || !n) return VT_ERR_NULL;
    if (!vt_all_finite(p, 4) || !vt_all_finite(s, 3) || !vt_all_finite(f, 3) || !vt_all_finite(n, 3))
        return VT_ERR_NONFINITE;
    double E[12], t[3], G[7]; /* into G: F written only when finite */
    vt_cross3(t, s, f);
    vt_axpy3(t, 1.0, n);
    vt_copy3(G, f);
    vt_euler_E(E, p);
    vt_mulE_t(G + 3, E, t);
    for (int k = 3; k < 7; k++) G[k] *= 2.0;
    if (!vt_all_finite(G, 7)) return VT_ERR_NONFINITE;
    memcpy(F, G, sizeof G);
    return VT_OK;
}

/* Q = S^T G for a Cartesian vector G (7n) */
static vt_status apply_St(double *Q, const vt_model *m, vt_data *d, const double *G)
{
    const size_t mark = vt_scratch_mark(d);
    double *Si = VT_SCRATCH(d, double, 7 * (size_t)m->maxpath, "S block");
    double *Qk = VT_SCRATCH(d, double, m->maxpath, "S block^T G");
    int *path = VT_SCRATCH(d, int, m->maxpath, "a body's path");
    if (!path) return vt_scratch_fail(d, mark);
    memset(Q, 0, (size_t)m->nv * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) {
        const int k = vt_body_path(m, i, path);
        vt_gather_S(Si, m, d, i, path);
        vt_dgemv('T', 7, k, 1.0, Si, 7, G + vt_xoff(i), 1, 0.0, Qk, 1);
        for (int c = 0; c < k; c++) Q[path[c]] += Qk[c];
    }
    vt_scratch_release(d, mark);
    return VT_OK;
}

vt_status vt_generalized_force(double *Q, const vt_model *m, vt_data *d, const double *F)
{
    vt_status st = vt_check_dense(m, d, "vt_generalized_force");
    if (st) return st;
    if (!Q || !F) return vt_fail(d->message, VT_ERR_NULL, "vt_generalized_force: NULL argument");
    if (!vt_all_finite(F, m->nx))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_generalized_force: NaN or Inf in F");
    /* into scratch (nv ≤ nx: within vt_forces_scratch), the caller's Q written only when finite */
    const size_t mark = vt_scratch_mark(d);
    double *Qs = VT_SCRATCH(d, double, m->nv, "S^T F");
    if (!Qs) return vt_scratch_fail(d, mark);
    if ((st = apply_St(Qs, m, d, F))) return vt_scratch_release(d, mark), st;
    if (!vt_all_finite(Qs, m->nv))
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_NONFINITE, "vt_generalized_force: S^T F overflows (F too large)");
    memcpy(Q, Qs, (size_t)m->nv * sizeof(double));
    vt_scratch_release(d, mark);
    return VT_OK;
}

vt_status vt_forces(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_forces");
    if (st) return st;
    if (!vt_all_finite(d->xfrc, 6 * (m->nbody + 1)) || !vt_all_finite(d->qfrc, m->nv))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_forces: NaN or Inf in xfrc or qfrc");
    const size_t mark = vt_scratch_mark(d);
    double *g = VT_SCRATCH(d, double, m->nx, "F − M Ṡq̇ + h");
    if (!g) return vt_scratch_fail(d, mark);
    for (int i = 1; i <= m->nbody; i++) {
        const int o = vt_xoff(i);
        const double *p = d->x + o + 3, *pd = d->xd + o + 3, *w = d->xfrc + 6 * i;
        const double mass = m->body_mass[i];
        double E[12], G[12], Gd[12], u[3], v[3];
        double *F = d->F + o, *h = d->h + o;

        vt_euler_E(E, p);
        for (int r = 0; r < 3; r++) F[r] = mass * m->gravity[r] + w[r];
        vt_mulE_t(F + 3, E, w + 3);
        for (int r = 3; r < 7; r++) F[r] *= 2.0;

        /* h_p = −8 Ġ^T J' G ṗ, Ġ = G(ṗ) */
        vt_euler_G(G, p);
        vt_euler_G(Gd, pd);
        vt_mulE(u, G, pd);
        vt_mulmat3(v, m->body_inertia + 9 * i, u);
        memset(h, 0, 3 * sizeof(double));
        vt_mulE_t(h + 3, Gd, v);
        for (int r = 3; r < 7; r++) h[r] *= -8.0;

        /* g = F − M Ṡq̇ + h */
        const double *a = d->Sdqd + o;
        for (int r = 0; r < 3; r++) g[o + r] = F[r] - mass * a[r];
        double Mp[16];
        vt_rot_mass(Mp, m->body_inertia + 9 * i, p);
        for (int r = 0; r < 4; r++) {
            double s = 0.0;
            for (int c = 0; c < 4; c++) s += Mp[r + 4 * c] * a[3 + c];
            g[o + 3 + r] = F[3 + r] - s + h[3 + r];
        }
    }
    st = apply_St(d->Q, m, d, g);
    vt_scratch_release(d, mark);
    if (st) return st;
    for (int c = 0; c < m->nv; c++) d->Q[c] += vt_rate_force(m, d, c); /* qfrc less the joints' damping, friction */
    /* finite loads can still overflow (their sum in Q, a large ṗ squared in h): scanned, O(n) */
    if (vt_all_finite(d->F, m->nx) && vt_all_finite(d->h, m->nx) && vt_all_finite(d->Q, m->nv)) return VT_OK;
    for (int i = 1; i <= m->nbody; i++)
        if (!vt_all_finite(d->F + vt_xoff(i), 7) || !vt_all_finite(d->h + vt_xoff(i), 7))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_forces: body %d: applied force F or h overflows (xfrc, mass or ṗ too large)", i);
    for (int c = 0; c < m->nv; c++)
        if (!isfinite(d->Q[c]))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_forces: Q[%d] (body %d's rate) overflows (loads too large)", c,
                           m->dof_body[c]);
    return VT_OK;
}

/* F − M Ṡq̇ + h, with S^T's blocks on top */
size_t vt_forces_scratch(const vt_model *m)
{
    const size_t D = sizeof(double);
    return VT_SCRATCH_BYTES(m->nx, D) + VT_SCRATCH_BYTES(7 * (size_t)m->maxpath, D) + VT_SCRATCH_BYTES(m->maxpath, D) +
           VT_SCRATCH_BYTES(m->maxpath, sizeof(int));
}
