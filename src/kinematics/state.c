/* State helpers that are not a stage of the method: applied point loads, (7), and advancing q
 * along q̇ on the Euler-parameter sphere,
 *   ṗ = ½ E^T ω  ⇒  p(t + h) = [cos(h|ω|/2); sin(h|ω|/2) ω/|ω|] ⊗ p(t)   for constant ω.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "kinematics/state.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"

vt_status vt_add_point_load(const vt_model *m, vt_data *d, int body, const double point[3],
                            const double f[3], const double n[3])
{
    vt_status st = vt_check_pair(m, d, "vt_add_point_load");
    if (st) return st;
    if (body < 1 || body > m->nbody)
        return vt_fail(d->message, VT_ERR_BAD_INDEX, "vt_add_point_load: body %d not in 1..%d",
                       body, m->nbody);
    if (!point && f)
        return vt_fail(d->message, VT_ERR_NULL, "vt_add_point_load: point is NULL");
    if ((f && (!vt_all_finite(f, 3) || !vt_all_finite(point, 3))) || (n && !vt_all_finite(n, 3)))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_add_point_load: NaN or Inf in the load on body %d", body);
    double w[6]; /* the new wrench, stored only when finite: a sum past DBL_MAX changes nothing */
    memcpy(w, d->xfrc + 6 * body, sizeof w);
    if (f) {
        /* moment about the centre of mass: s × f with s = A s' (the s̃ f of (7)) */
        double s[3];
        vt_mulmat3(s, d->A + 9 * body, point);
        vt_axpy3(w, 1.0, f);
        vt_addcross3(w + 3, s, f);
    }
    if (n) vt_axpy3(w + 3, 1.0, n);
    if (!vt_all_finite(w, 6))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_add_point_load: the load on body %d overflows (xfrc not finite)", body);
    memcpy(d->xfrc + 6 * body, w, sizeof w);
    return VT_OK;
}

vt_status vt_add_frame_load(const vt_model *m, vt_data *d, int frame, const double f[3], const double n[3])
{
    vt_status st = vt_check_pair(m, d, "vt_add_frame_load");
    if (st) return st;
    if (frame < 0 || frame >= m->nframe || m->frame_body[frame] == 0)
        return vt_fail(d->message, VT_ERR_BAD_INDEX, "vt_add_frame_load: frame %d not in 0..%d, or on the ground", frame,
                       m->nframe - 1);
    return vt_add_point_load(m, d, m->frame_body[frame], m->frame_point + 3 * frame, f, n);
}

vt_status vt_add_frame_loads(const vt_model *m, vt_data *d, const vt_frame_loads *loads)
{
    for (int k = 0; k < loads->n; k++) {
        const int f = loads->frame[k];
        const vt_status st = vt_add_frame_load(m, d, f, loads->w + 6 * k, loads->w + 6 * k + 3);
        if (st) /* named as the caller gave it: its index and frame, not xfrc, which it did not set */
            return vt_fail(d->message, st, "vt_inverse_dynamics_motion: load %d at frame '%.40s': %s on body %d", k,
                           f >= 0 && f < m->nframe ? m->frame_name + (size_t)VT_NAME_MAX * f : "?",
                           st == VT_ERR_NONFINITE ? "NaN, Inf or an overflowing sum of the loads" : vt_status_string(st),
                           f >= 0 && f < m->nframe ? m->frame_body[f] : -1);
    }
    return VT_OK;
}

vt_status vt_frame_pose(const vt_model *m, vt_data *d, int frame, double position[3], double rotation[9])
{
    vt_status st = vt_check_pair(m, d, "vt_frame_pose");
    if (st) return st;
    if (frame < 0 || frame >= m->nframe)
        return vt_fail(d->message, VT_ERR_BAD_INDEX, "vt_frame_pose: frame %d not in 0..%d", frame, m->nframe - 1);
    const int b = m->frame_body[frame];
    static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double *A = b ? d->A + 9 * b : I3, *sp = m->frame_point + 3 * frame;
    if (position) {
        double s[3], o[3];
        vt_mulmat3(s, A, sp);
        for (int k = 0; k < 3; k++) o[k] = (b ? d->x[vt_xoff(b) + k] : 0.0) + s[k];
        if (!vt_all_finite(o, 3)) /* a far point on a far body: the sum overflows */
            return vt_fail(d->message, VT_ERR_NONFINITE, "vt_frame_pose: frame %d's position overflows", frame);
        vt_copy3(position, o);
    }
    if (rotation) {
        double Af[9];
        vt_euler_A(Af, m->frame_quat + 4 * frame);
        for (int c = 0; c < 3; c++) vt_mulmat3(rotation + 3 * c, A, Af + 3 * c); /* A_body A_frame */
    }
    return VT_OK;
}

/* p ← exp(h ω) ⊗ p, normalized */
static void rotate_quat(double p[4], const double w[3], double h)
{
    double r[4], u[3] = {w[0], w[1], w[2]};
    const double a = vt_normalize(u, 3) * h; /* |ω| h, u = ω/|ω| (scaled: no overflow) */
    if (a != 0.0) {
        vt_quat_axis_angle(r, u, a);
        vt_quat_mul(p, r, p);
    }
    vt_normalize(p, 4);
}

/* 1 for a joint whose coordinates advance as q + h q̇ (all but those holding Euler parameters) */
static inline int advances_linearly(int jt)
{
    return jt != VT_JOINT_SPHERICAL && jt != VT_JOINT_FREE && jt != VT_JOINT_BASE;
}

/* body i's coordinates advanced, into qi (body_nq[i] entries, at most 7), for a joint with Euler
 * parameters */
static void advance_rotation(double *qi, const vt_model *m, int i, const double *v, double h)
{
    const double *vi = v + m->body_vadr[i];
    switch (m->body_joint[i]) {
    case VT_JOINT_SPHERICAL:
        rotate_quat(qi, vi, h);
        break;
    case VT_JOINT_FREE: /* translation in the reference axes, then as spherical */
        vt_axpy3(qi, h, vi);
        rotate_quat(qi + 3, vi + 3, h);
        break;
    default: { /* base: ṗ's rates */
        double E[12], w[3];
        vt_euler_E(E, qi + 3);
        vt_mulE(w, E, vi + 3);
        w[0] *= 2; w[1] *= 2; w[2] *= 2; /* ω = 2 E ṗ */
        vt_axpy3(qi, h, vi);
        rotate_quat(qi + 3, w, h);
        break;
    }
    }
}

vt_status vt_integrate_q(double *q_out, const vt_model *m, const double *q, const double *v, double h)
{
    if (!q_out || !m || !q || !v) return VT_ERR_NULL;
    if (!isfinite(h)) return VT_ERR_NONFINITE;
    if (!m->has_quaternions) { /* every q advances linearly (nq = nv): a NaN or Inf in q or v gives one in q + h v */
        int finite = 1;
        for (int k = 0; k < m->nq; k++) finite &= isfinite(q[k] + h * v[k]) != 0;
        if (!finite) return VT_ERR_NONFINITE;
        for (int k = 0; k < m->nq; k++) q_out[k] = q[k] + h * v[k];
        return VT_OK;
    }
    if (!vt_all_finite(q, m->nq) || !vt_all_finite(v, m->nv)) return VT_ERR_NONFINITE;
    /* finite inputs can still overflow (q + h q̇ past DBL_MAX): every body's result is checked
     * first (a rotating one advanced into a local), and q_out is written only when all are finite
     * (each body reads only its own entries, so q_out may alias q); q + h q̇ is written as checked */
    int finite = 1;
    for (int i = 1; i <= m->nbody; i++) {
        const int n = m->body_nq[i];
        const double *qi0 = q + m->body_qadr[i], *vi = v + m->body_vadr[i];
        if (advances_linearly(m->body_joint[i])) {
            for (int k = 0; k < n; k++) finite &= isfinite(qi0[k] + h * vi[k]) != 0;
            continue;
        }
        double qi[7];
        memcpy(qi, qi0, (size_t)n * sizeof(double));
        advance_rotation(qi, m, i, v, h);
        finite &= vt_all_finite(qi, n);
    }
    if (!finite) return VT_ERR_NONFINITE;
    if (q_out != q) memcpy(q_out, q, (size_t)m->nq * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) {
        double *qo = q_out + m->body_qadr[i];
        const double *vi = v + m->body_vadr[i];
        if (!advances_linearly(m->body_joint[i])) advance_rotation(qo, m, i, v, h);
        else
            for (int k = 0; k < m->body_nq[i]; k++) qo[k] = qo[k] + h * vi[k];
    }
    return VT_OK;
}
