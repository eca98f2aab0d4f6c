/* The inverse velocity transformation R, q̇ = R ẋ: the paper's (19)-(21) and Table 1, with
 * the equivalent Cartesian force of a generalized force, F_eq = R^T Q (14).
 *
 * Row of each rate of body i's joint to its reference j (19)-(20), q̇^i = R_ij ẋ^j + R_ii ẋ^i,
 * ω = 2 E ṗ:
 *   base body       q̇ = ẋ^i:                  R_ii = [I3 0; 0 I4]
 *   rotational e    q̇ = e^T(ω^i − ω^j):       R_ij = [0, −2 e^T E^j],     R_ii = [0, 2 e^T E^i]
 *   translational e q̇ = e^T(v^i − v^j − ω̃^i d^i − ω̃^j s^{ij}):
 *                                              R_ij = [−e^T, 2 e^T s̃^{ij} E^j],
 *                                              R_ii = [ e^T, 2 e^T d̃^i E^i]
 * (universal: e1, e2; spherical: e1, e2, e3; cylindrical: the rotational row, then the
 * translational one; free: three translational rows on the reference body's axes, with d^i →
 * r^i − P and s^{ij} → P − r^j since its translation turns with j, then the spherical rows). With e^T s̃ = (e × s)^T the p-parts are 2 E^T (e × s). R S = I.
 */
#include <stddef.h>
#include <string.h>

#include "kinematics/inverse_transform.h"
#include "base/lapack.h"
#include "base/arena.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"

void vt_R_row(const vt_model *m, const vt_data *d, int dof, double rj[7], double ri[7])
{
    const int i = m->dof_body[dof], j = m->body_parent[i], jt = m->body_joint[i];
    const double *e = d->jaxis + 9 * i;
    double Ei[12], Ej[12], u[3];
    int ax;
    memset(ri, 0, 7 * sizeof(double));
    memset(rj, 0, 7 * sizeof(double));
    vt_euler_E(Ei, d->x + vt_xoff(i) + 3);
    if (j) vt_euler_E(Ej, d->x + vt_xoff(j) + 3);
    switch (vt_dof_kind(jt, dof - m->body_vadr[i], &ax)) {
    case VT_DOF_ROT:
        vt_mulE_t(ri + 3, Ei, e + 3 * ax);
        if (j) vt_mulE_t(rj + 3, Ej, e + 3 * ax);
        for (int c = 3; c < 7; c++) { ri[c] *= 2.0; rj[c] *= -2.0; }
        break;
    case VT_DOF_TRANS: {
        /* free: d^i → r^i − P and s^{ij} → P − r^j (t turns with j, s^{ji} with i) */
        double dI[3], sJ[3], s[3]; /* from the joint's own vectors, not positions from o */
        vt_joint_child(s, m, d, i);
        for (int c = 0; c < 3; c++) {
            dI[c] = jt == VT_JOINT_FREE ? -s[c] : d->jd[3 * i + c];
            sJ[c] = jt == VT_JOINT_FREE ? d->jsij[3 * i + c] + (d->jd[3 * i + c] + s[c]) : d->jsij[3 * i + c];
        }
        vt_copy3(ri, e + 3 * ax);
        vt_cross3(u, e + 3 * ax, dI);
        vt_mulE_t(ri + 3, Ei, u);
        if (j) {
            for (int c = 0; c < 3; c++) rj[c] = -e[3 * ax + c];
            vt_cross3(u, e + 3 * ax, sJ);
            vt_mulE_t(rj + 3, Ej, u);
        }
        for (int c = 3; c < 7; c++) { ri[c] *= 2.0; rj[c] *= 2.0; }
        break;
    }
    case VT_DOF_BASE_R: ri[ax] = 1.0; break;
    default: ri[3 + ax] = 1.0; break;
    }
}

vt_status vt_inverse_transform(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_inverse_transform");
    if (st) return st;
    const size_t ld = (size_t)m->nv;
    for (int dof = 0; dof < m->nv; dof++) {
        const int i = m->dof_body[dof], j = m->body_parent[i];
        double ri[7], rj[7];
        vt_R_row(m, d, dof, rj, ri);
        if (!vt_all_finite(ri, 7) || (j && !vt_all_finite(rj, 7)))
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_inverse_transform: row %d of R (body %d) is not finite", dof, i);
        for (int c = 0; c < 7; c++) d->R[(size_t)dof + (size_t)(vt_xoff(i) + c) * ld] = ri[c];
        if (j)
            for (int c = 0; c < 7; c++) d->R[(size_t)dof + (size_t)(vt_xoff(j) + c) * ld] = rj[c];
    }
    return VT_OK;
}

vt_status vt_equivalent_force(double *Feq, const vt_model *m, vt_data *d, const double *Q)
{
    vt_status st = vt_check_dense(m, d, "vt_equivalent_force");
    if (st) return st;
    if (!Feq || !Q) return vt_fail(d->message, VT_ERR_NULL, "vt_equivalent_force: NULL argument");
    if (!vt_all_finite(Q, m->nv))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_equivalent_force: NaN or Inf in Q");
    const int ld = m->nv;
    /* into scratch, the caller's Feq written only when finite (R^T Q can overflow) */
    const size_t mark = vt_scratch_mark(d);
    double *out = Feq;
    Feq = VT_SCRATCH(d, double, m->nx, "R^T Q");
    if (!Feq) return vt_scratch_fail(d, mark);
    memset(Feq, 0, (size_t)m->nx * sizeof(double));
    /* only the blocks R_ii and R_ij of each joint are non-zero */
    for (int i = 1; i <= m->nbody; i++) {
        const int j = m->body_parent[i], row = m->body_vadr[i], nvi = m->body_nv[i];
        vt_dgemv('T', nvi, 7, 1.0, d->R + row + (size_t)vt_xoff(i) * (size_t)ld, ld,
                    Q + row, 1, 1.0, Feq + vt_xoff(i), 1);
        if (j)
            vt_dgemv('T', nvi, 7, 1.0, d->R + row + (size_t)vt_xoff(j) * (size_t)ld, ld,
                        Q + row, 1, 1.0, Feq + vt_xoff(j), 1);
    }
    if (!vt_all_finite(Feq, m->nx))
        return vt_scratch_release(d, mark), vt_fail(d->message, VT_ERR_NONFINITE, "vt_equivalent_force: R^T Q overflows (Q too large)");
    memcpy(out, Feq, (size_t)m->nx * sizeof(double));
    vt_scratch_release(d, mark);
    return VT_OK;
}

/* vt_equivalent_force's R^T Q */
size_t vt_inverse_transform_scratch(const vt_model *m)
{
    return VT_SCRATCH_BYTES(m->nx, sizeof(double));
}
