/* Payloads and tools fixed to a body already in a builder (vt_builder_add_payload), or a body's
 * mass properties replaced (vt_builder_set_mass), merged as the URDF loader merges a fixed link:
 *
 *   m' = m + m_p,   c' = m_p p / m'   (from the body's centre of mass, its axes),
 *   J' = J about c' + Q J_p Qᵀ about c' (the parallel axes, model/inertia.c),
 *
 * and every point the builder holds on the body (written from its centre of mass) moved by −c',
 * so that nothing moves on the body itself.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model/payload.h"
#include "model/builder.h"
#include "model/inertia.h"
#include "base/euler.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"

vt_payload_def vt_default_payload_def(void)
{
    vt_payload_def d;
    memset(&d, 0, sizeof d);
    d.body = 1;
    return d;
}

/* p − c into p when write, else only whether it is finite; 0 when it is not */
static int shifted(double p[3], const double c[3], int write)
{
    double s[3];
    for (int e = 0; e < 3; e++) s[e] = p[e] - c[e];
    if (!vt_all_finite(s, 3)) return 0;
    if (write) vt_copy3(p, s);
    return 1;
}

/* Body i's centre of mass moved by c (its axes): a body's points are stored from its centre of
 * mass, so every point on it — its joint point, its children's, its frames', its point drives'
 * and its cut joints' — becomes p − c and stays where it is on the body. write 0: only whether
 * every shifted point is finite (nothing written), so that a refusal changes nothing. */
static int shift_points(vt_builder *b, int i, const double c[3], int write)
{
    int ok = shifted(b->bodies[i - 1].joint_child, c, write);
    for (int k = i; k < b->n; k++) /* children come after their parent */
        if (b->bodies[k].parent == i) ok = ok && shifted(b->bodies[k].joint_parent, c, write);
    for (int k = 0; k < b->nframe; k++)
        if (b->frames[k].body == i) ok = ok && shifted(b->frames[k].point, c, write);
    for (int k = 0; k < b->ndrive; k++)
        if (b->drives[k].type == VT_DRIVE_POINT && b->drives[k].body == i)
            ok = ok && shifted(b->drives[k].point, c, write);
    for (int k = 0; k < b->ncut; k++) {
        if (b->cuts[k].body_a == i) ok = ok && shifted(b->cuts[k].point_a, c, write);
        if (b->cuts[k].body_b == i) ok = ok && shifted(b->cuts[k].point_b, c, write);
    }
    return ok;
}

/* vt_builder_add_payload (merge 1: the body's and the payload's mass properties combined, as the
 * URDF loader merges a fixed link) and vt_builder_set_mass (merge 0: the def's replace the body's). */
static int mass_change(vt_builder *b, const vt_payload_def *def, int merge)
{
    const char *what = merge ? "payload" : "mass properties";
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "%s: definition is NULL", what);
    if (!isfinite(def->mass) || !vt_all_finite(def->point, 3) || !vt_all_finite(def->inertia, 9))
        return vt_fail(b->message, VT_ERR_NONFINITE, "%s: NaN or Inf in its definition", what);
    if (!(def->mass >= 0.0)) return vt_fail(b->message, VT_ERR_MASS, "%s: mass %g kg is negative", what, def->mass);
    int i = def->body;
    double p[3], Q[9];
    const double *axes = NULL; /* the def's axes onto the body's: NULL, the same */
    vt_copy3(p, def->point);
    if (def->frame) {
        const int f = vt_builder_find_frame(b, def->frame);
        if (f < 0) return vt_fail(b->message, VT_ERR_NOT_FOUND, "%s: no frame \"%.64s\" added so far", what, def->frame);
        const vt_frame_def *fr = &b->frames[f];
        if (fr->body == 0)
            return vt_fail(b->message, VT_ERR_BAD_INDEX,
                           "%s: frame \"%.64s\" is on the ground, which has no mass to change", what, def->frame);
        i = fr->body;
        vt_euler_A(Q, fr->orientation);
        vt_mulmat3(p, Q, def->point);
        for (int e = 0; e < 3; e++) p[e] += fr->point[e];
        axes = Q;
    } else if (i < 1 || i > b->n) {
        return vt_fail(b->message, VT_ERR_BAD_INDEX, "%s: body %d is not a body added so far (1..%d)", what, i, b->n);
    }
    char who[64];
    snprintf(who, sizeof who, "%s on body %d", what, i);
    vt_status st = vt_check_inertia(b->message, who, def->inertia, b->def.inertia_tol);
    if (st) return st;
    vt_body_def *body = &b->bodies[i - 1];
    const double mass = merge ? body->mass + def->mass : def->mass;
    double c[3], J[9] = {0.0}, d[3];
    if (merge) { /* the new centre of mass c from the old one (0), then both parts about it */
        for (int e = 0; e < 3; e++) c[e] = mass > 0.0 ? def->mass * p[e] / mass : 0.0;
        for (int e = 0; e < 3; e++) d[e] = -c[e];
        vt_inertia_add(J, body->mass, body->inertia, NULL, d);
        for (int e = 0; e < 3; e++) d[e] = p[e] - c[e];
        vt_inertia_add(J, def->mass, def->inertia, axes, d);
    } else {
        vt_copy3(c, p);
        d[0] = d[1] = d[2] = 0.0;
        vt_inertia_add(J, 0.0, def->inertia, axes, d);
    }
    if (!isfinite(mass) || !vt_all_finite(J, 9) || !vt_all_finite(c, 3))
        return vt_fail(b->message, VT_ERR_NONFINITE, "%s on body %d: the body's mass or inertia overflows", what, i);
    snprintf(who, sizeof who, "body %d with the %s", i, what);
    if ((st = vt_check_inertia(b->message, who, J, b->def.inertia_tol))) return st;
    if (!shift_points(b, i, c, 0))
        return vt_fail(b->message, VT_ERR_NONFINITE,
                       "%s on body %d: a point on the body overflows as its centre of mass moves", what, i);
    shift_points(b, i, c, 1);
    vt_inertia_symmetric(J);
    body->mass = mass;
    memcpy(body->inertia, J, sizeof J);
    b->message[0] = '\0';
    return i;
}

int vt_builder_add_payload(vt_builder *b, const vt_payload_def *def)
{
    return mass_change(b, def, 1);
}

int vt_builder_set_mass(vt_builder *b, const vt_payload_def *def)
{
    return mass_change(b, def, 0);
}

