/* The builder: the model's definitions as the caller adds them (vt_builder_add_body, _drive,
 * _cut_joint, _frame, _coupling), each validated and normalized when added (a refusal leaves the
 * builder as it was, with a message naming the element), with the vt_default_*_def values, the
 * builder's names and finds. The inertia check is model/inertia.c, payloads model/payload.c.
 * vt_builder_build (model/model.c) lays the
 * definitions out as a model; nothing here calls model.c.
 *
 * A drive's spline time functions (model/functions.c: f, and f2, f3 of an orientation drive's
 * sequence) own their samples and second derivatives: one block per drive in the builder (each
 * spline's t, y, f'' in turn), copied into the model's one block when it is built.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/builder.h"
#include "model/inertia.h"
#include "base/checked.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/functions.h"

vt_model_def vt_default_model_def(void)
{
    vt_model_def d;
    memset(&d, 0, sizeof d); /* every field has a default, also those added later */
    d.gravity[0] = 0.0;
    d.gravity[1] = -9.81;
    d.gravity[2] = 0.0;
    d.rcond_min = 1e-12;
    d.rcond_warn = 1e-6;
    d.allow_redundant = 0;
    d.layout = VT_LAYOUT_FULL;
    d.inertia_tol = VT_INERTIA_TOL;
    return d;
}

vt_drive_def vt_default_drive_def(void)
{
    vt_drive_def d;
    memset(&d, 0, sizeof d);
    d.type = VT_DRIVE_JOINT;
    d.body = 1;
    d.f = vt_function_constant(0.0);
    d.f2 = vt_function_constant(0.0);
    d.f3 = vt_function_constant(0.0);
    d.axis[2] = 1.0;
    d.orientation[0] = 1.0;
    d.reference = -1;
    return d;
}

vt_cut_joint_def vt_default_cut_joint_def(void)
{
    vt_cut_joint_def d;
    memset(&d, 0, sizeof d);
    d.joint = VT_JOINT_REVOLUTE;
    d.body_a = 0;
    d.body_b = 1;
    d.axis1[2] = 1.0;
    d.axis2[0] = 1.0;
    d.orientation[0] = 1.0;
    return d;
}

vt_coupling_def vt_default_coupling_def(void)
{
    vt_coupling_def d;
    memset(&d, 0, sizeof d);
    d.body_a = 2;
    d.body_b = 1;
    d.ratio = 1.0;
    return d;
}

vt_frame_def vt_default_frame_def(void)
{
    vt_frame_def d;
    memset(&d, 0, sizeof d);
    d.body = 1;
    d.orientation[0] = 1.0;
    return d;
}

vt_body_def vt_default_body_def(void)
{
    vt_body_def d;
    memset(&d, 0, sizeof d);
    for (int k = 0; k < 2; k++) {
        d.limit_lower[k] = -HUGE_VAL;
        d.limit_upper[k] = d.limit_velocity[k] = d.limit_effort[k] = HUGE_VAL;
        d.gear_ratio[k] = 1.0;
    }
    d.parent = 0;
    d.joint = VT_JOINT_REVOLUTE;
    d.mass = 1.0;
    d.axis1[2] = 1.0;
    d.axis2[0] = 1.0;
    d.orientation[0] = 1.0;
    return d;
}

vt_status vt_builder_create(vt_builder **builder, const vt_model_def *def)
{
    if (!builder) return VT_ERR_NULL;
    *builder = NULL;
    vt_model_def md = def ? *def : vt_default_model_def();
    if (!vt_all_finite(md.gravity, 3) || !isfinite(md.rcond_min) || !isfinite(md.rcond_warn)) return VT_ERR_NONFINITE;
    if (!(md.rcond_min > 0.0) || md.rcond_min > 1.0 || md.rcond_warn < md.rcond_min) return VT_ERR_BAD_OPTION;
    if (md.layout != VT_LAYOUT_FULL && md.layout != VT_LAYOUT_RECURSIVE) return VT_ERR_BAD_OPTION;
    if (!(md.inertia_tol >= 0.0 && md.inertia_tol < 1.0)) return VT_ERR_BAD_OPTION; /* NaN too */
    vt_builder *b = calloc(1, sizeof *b);
    if (!b) return VT_ERR_NO_MEMORY;
    b->def = md;
    *builder = b;
    return VT_OK;
}

const char *vt_builder_message(const vt_builder *builder)
{
    return builder ? builder->message : "builder is NULL";
}

void vt_builder_free(vt_builder *builder)
{
    if (!builder) return;
    free(builder->bodies);
    free(builder->body_names);
    free(builder->joint_names);
    for (int k = 0; k < builder->ndrive; k++) free(builder->samples[k]);
    free(builder->samples);
    free(builder->drives);
    free(builder->drive_names);
    free(builder->cuts);
    free(builder->cut_names);
    free(builder->frames);
    free(builder->couplings);
    free(builder->coupling_names);
    free(builder->frame_names);
    vt_names_free(&builder->body_index);
    vt_names_free(&builder->joint_index);
    vt_names_free(&builder->drive_index);
    vt_names_free(&builder->cut_index);
    vt_names_free(&builder->frame_index);
    vt_names_free(&builder->coupling_index);
    free(builder);
}

/* name into dst ("" for NULL), refused when too long or when one of the names taken (index,
 * over the list taken_names) has it */
static vt_status take_name(char *msg, vt_name dst, const char *name, const vt_names *index, const vt_name *taken_names,
                           const char *what, int id)
{
    if (!name || !name[0]) {
        dst[0] = '\0';
        return VT_OK;
    }
    const char *end = memchr(name, '\0', VT_NAME_MAX);
    const size_t len = end ? (size_t)(end - name) : VT_NAME_MAX;
    if (len >= VT_NAME_MAX)
        return vt_fail(msg, VT_ERR_BAD_NAME, "%s %d: name \"%.20s...\" longer than %d bytes", what, id, name, VT_NAME_MAX - 1);
    const int k = vt_names_find(index, taken_names, vt_name_in_array, name);
    if (k >= 0)
        return vt_fail(msg, VT_ERR_BAD_NAME, "%s %d: name \"%s\" already taken by %s %d", what, id, name, what,
                       k + (strcmp(what, "body") == 0 || strcmp(what, "joint") == 0));
    memcpy(dst, name, len + 1);
    return VT_OK;
}

/* entry k's name (copied to the list already) into its kind's index, unless unnamed */
static void index_name(vt_names *index, const vt_name *names, int k)
{
    if (names[k][0]) vt_names_insert(index, names, vt_name_in_array, k);
}

/* a count that would pass VT_COUNT_MAX with one more: the message names it */
static vt_status count_full(char *msg, int count, const char *what)
{
    return vt_fail(msg, VT_ERR_TOO_MANY_BODIES, "%s %d: more than VT_COUNT_MAX (%d) %s", what, count, VT_COUNT_MAX,
                   strcmp(what, "body") == 0 ? "bodies" : strcmp(what, "coupling") == 0 ? "couplings"
                   : strcmp(what, "frame") == 0 ? "frames" : strcmp(what, "drive") == 0 ? "drives" : "cut joints");
}

int vt_find_name(const char *names, int n, const char *name)
{
    if (!name || !name[0]) return VT_ERR_NOT_FOUND;
    for (int k = 0; k < n; k++)
        if (strcmp(names + (size_t)VT_NAME_MAX * (size_t)k, name) == 0) return k;
    return VT_ERR_NOT_FOUND;
}

/* Normalizes a in place (vt_normalize: scaled, so lengths near overflow or underflow keep their
 * direction); refuses only the zero vector: an axis or orientation is a direction, its length
 * a unit of the caller's, so no other length is "too short" in itself. */
static int normalize(double *a, int n)
{
    return vt_normalize(a, n) > 0.0;
}

/* Grows a builder array to hold entry n (its capacity doubled, at most VT_COUNT_MAX entries; the
 * bytes checked); 0 on failure, the array as it was. */
static int grow(void **arr, int *cap, int n, size_t size)
{
    if (n < *cap) return 1;
    const int nc = *cap == 0 ? 8 : *cap > VT_COUNT_MAX / 2 ? VT_COUNT_MAX : 2 * *cap;
    size_t bytes;
    if (n >= nc || !vt_size_mul(&bytes, (size_t)nc, size)) return 0;
    void *p = realloc(*arr, bytes);
    if (!p) return 0;
    *arr = p;
    *cap = nc;
    return 1;
}

/* a joint's own effects on its two rates: finite and not negative (a negative damping or friction
 * feeds energy in, a negative armature takes inertia away), a gear ratio finite and not 0, and the
 * products taken on the joint's side finite */
static vt_status validate_effects(char *msg, int id, const double *arm, const double *damp, const double *fric,
                                  const double *vel, const double *gear)
{
    for (int k = 0; k < 2; k++) {
        const double e[4] = {arm[k], damp[k], fric[k], vel[k]}, g = gear[k];
        for (int a = 0; a < 4; a++)
            if (!(isfinite(e[a]) && e[a] >= 0.0))
                return vt_fail(msg, VT_ERR_BAD_OPTION,
                               "body %d: rate %d's armature %g, damping %g, friction %g and friction_velocity %g must "
                               "be finite and not negative", id, k, e[0], e[1], e[2], e[3]);
        if (!(isfinite(g) && g != 0.0 && isfinite(g * g * fmax(e[0], e[1])) && isfinite(fabs(g) * e[2])))
            return vt_fail(msg, VT_ERR_BAD_OPTION,
                           "body %d: rate %d's gear_ratio %g must be finite and not 0 (and the armature, damping and "
                           "friction it carries to the joint's side finite)", id, k, g);
    }
    return VT_OK;
}

static vt_status validate_body(char *msg, int id, vt_body_def *d, double inertia_tol)
{
    if ((int)d->joint < 0 || d->joint >= VT_JOINT_TYPE_COUNT)
        return vt_fail(msg, VT_ERR_JOINT_TYPE, "body %d: joint type %d unknown", id, (int)d->joint);
    if (d->parent < 0 || d->parent >= id)
        return vt_fail(msg, VT_ERR_PARENT, "body %d: reference body %d is not an earlier body",
                       id, d->parent);
    if (d->joint == VT_JOINT_BASE && d->parent != 0)
        return vt_fail(msg, VT_ERR_PARENT, "body %d: a base body must have the ground (0) as reference, not %d",
                       id, d->parent);
    if (!isfinite(d->mass) || !vt_all_finite(d->inertia, 9) || !vt_all_finite(d->joint_parent, 3) ||
        !vt_all_finite(d->joint_child, 3) || !vt_all_finite(d->axis1, 3) ||
        !vt_all_finite(d->axis2, 3) || !vt_all_finite(d->orientation, 4) || !vt_all_finite(d->joint_frame, 4))
        return vt_fail(msg, VT_ERR_NONFINITE, "body %d: NaN or Inf in its definition", id);
    if (!(d->mass >= 0.0)) /* zero: a massless link (a frame, a gimbal), refused only by a solve it leaves singular */
        return vt_fail(msg, VT_ERR_MASS, "body %d: mass %g kg is negative", id, d->mass);
    char who[32];
    snprintf(who, sizeof who, "body %d", id);
    vt_status st = vt_check_inertia(msg, who, d->inertia, inertia_tol);
    if (st) return st;
    vt_inertia_symmetric(d->inertia);
    const int uses_axis1 = d->joint != VT_JOINT_BASE && d->joint != VT_JOINT_SPHERICAL && d->joint != VT_JOINT_FREE;
    if (uses_axis1 && !normalize(d->axis1, 3))
        return vt_fail(msg, VT_ERR_AXIS_ZERO, "body %d: axis1 has zero length", id);
    if (d->joint == VT_JOINT_UNIVERSAL) {
        if (!normalize(d->axis2, 3))
            return vt_fail(msg, VT_ERR_AXIS_ZERO, "body %d: axis2 has zero length", id);
        const double c = vt_dot3(d->axis1, d->axis2);
        if (fabs(c) > 1e-9)
            return vt_fail(msg, VT_ERR_AXES_NOT_PERPENDICULAR,
                           "body %d: universal axes not perpendicular (cosine %g)", id, c);
        /* within the tolerance, made perpendicular to round-off (axis2 less its part along
         * axis1): the joint's R rows are S's left inverse only for perpendicular axes, and a
         * cosine of 1e-10 left R S = I off by 1e-10 on the dense path (a joint drive's
         * Φ_q = R S, its effort leaking to the other rate) */
        for (int k = 0; k < 3; k++) d->axis2[k] -= c * d->axis1[k];
        normalize(d->axis2, 3);
    }
    if (d->joint == VT_JOINT_BASE) {
        d->orientation[0] = 1.0;
        d->orientation[1] = d->orientation[2] = d->orientation[3] = 0.0;
    } else if (!normalize(d->orientation, 4)) {
        return vt_fail(msg, VT_ERR_QUATERNION, "body %d: orientation has zero norm", id);
    }
    /* all zero: the kind's documented frame (model.c, joint_frame); else any non-zero length is a direction */
    if (!(vt_normalize(d->joint_frame, 4) > 0.0)) memset(d->joint_frame, 0, sizeof d->joint_frame);
    for (int k = 0; k < 2; k++) { /* limits: ±∞ allowed, NaN not */
        if (isnan(d->limit_lower[k]) || isnan(d->limit_upper[k]) || isnan(d->limit_velocity[k]) ||
            isnan(d->limit_effort[k]))
            return vt_fail(msg, VT_ERR_NONFINITE, "body %d: NaN in the limits of rate %d", id, k);
        if (d->limit_lower[k] > d->limit_upper[k] || d->limit_velocity[k] < 0.0 || d->limit_effort[k] < 0.0)
            return vt_fail(msg, VT_ERR_BAD_OPTION,
                           "body %d: limits of rate %d: lower %g > upper %g, or a negative velocity %g or effort %g", id,
                           k, d->limit_lower[k], d->limit_upper[k], d->limit_velocity[k], d->limit_effort[k]);
    }
    return validate_effects(msg, id, d->armature, d->damping, d->friction, d->friction_velocity, d->gear_ratio);
}

int vt_builder_add_body(vt_builder *b, const vt_body_def *def)
{
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "body definition is NULL");
    const int id = b->n + 1;
    if (b->n >= VT_COUNT_MAX) return count_full(b->message, id, "body");
    vt_body_def d = *def;
    vt_status st = validate_body(b->message, id, &d, b->def.inertia_tol);
    if (st) return st;
    int nq = 0, nv = 0;
    if (!vt_count_add(&nq, b->nq, vt_joint_nq(d.joint), VT_COUNT_MAX) ||
        !vt_count_add(&nv, b->nv, vt_joint_nv(d.joint), VT_COUNT_MAX))
        return vt_fail(b->message, VT_ERR_TOO_MANY_BODIES, "body %d: more than VT_COUNT_MAX (%d) coordinates or rates", id,
                       VT_COUNT_MAX);
    vt_name name, joint;
    if ((st = take_name(b->message, name, d.name, &b->body_index, (const vt_name *)b->body_names, "body", id)) ||
        (st = take_name(b->message, joint, d.joint_name, &b->joint_index, (const vt_name *)b->joint_names, "joint", id)))
        return st;
    int capn = b->capnames; /* grown together: a failure leaves the builder as it was */
    if (!grow((void **)&b->bodies, &b->cap, b->n, sizeof d) ||
        !grow((void **)&b->body_names, &capn, b->n, sizeof(vt_name)) ||
        !grow((void **)&b->joint_names, &b->capnames, b->n, sizeof(vt_name)) ||
        vt_names_reserve(&b->body_index, id) || vt_names_reserve(&b->joint_index, id))
        return vt_fail(b->message, VT_ERR_NO_MEMORY, "body %d: out of memory", id);
    d.name = d.joint_name = NULL; /* the caller's memory: the builder keeps its own copies */
    memcpy(b->body_names[b->n], name, sizeof name);
    memcpy(b->joint_names[b->n], joint, sizeof joint);
    index_name(&b->body_index, (const vt_name *)b->body_names, b->n);
    index_name(&b->joint_index, (const vt_name *)b->joint_names, b->n);
    b->bodies[b->n++] = d;
    b->nq = nq;
    b->nv = nv;
    b->message[0] = '\0';
    return id;
}

int vt_builder_find_body(const vt_builder *b, const char *name)
{
    if (!b || !name) return VT_ERR_NULL;
    const int k = name[0] ? vt_names_find(&b->body_index, b->body_names, vt_name_in_array, name) : -1;
    return k < 0 ? VT_ERR_NOT_FOUND : k + 1;
}

int vt_builder_find_joint(const vt_builder *b, const char *name)
{
    if (!b || !name) return VT_ERR_NULL;
    const int k = name[0] ? vt_names_find(&b->joint_index, b->joint_names, vt_name_in_array, name) : -1;
    return k < 0 ? VT_ERR_NOT_FOUND : k + 1;
}

vt_joint_effects_def vt_default_joint_effects_def(void)
{
    vt_joint_effects_def e;
    memset(&e, 0, sizeof e);
    e.gear_ratio[0] = e.gear_ratio[1] = 1.0;
    return e;
}

vt_status vt_builder_joint_effects(const vt_builder *b, int body, vt_joint_effects_def *out)
{
    if (!b || !out) return VT_ERR_NULL;
    if (body < 1 || body > b->n) return VT_ERR_BAD_INDEX;
    const vt_body_def *d = &b->bodies[body - 1];
    memcpy(out->armature, d->armature, sizeof out->armature);
    memcpy(out->damping, d->damping, sizeof out->damping);
    memcpy(out->friction, d->friction, sizeof out->friction);
    memcpy(out->friction_velocity, d->friction_velocity, sizeof out->friction_velocity);
    memcpy(out->gear_ratio, d->gear_ratio, sizeof out->gear_ratio);
    return VT_OK;
}

vt_status vt_builder_set_joint_effects(vt_builder *b, int body, const vt_joint_effects_def *def)
{
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "vt_builder_set_joint_effects: definition is NULL");
    if (body < 1 || body > b->n)
        return vt_fail(b->message, VT_ERR_BAD_INDEX, "vt_builder_set_joint_effects: no body %d (%d added)", body, b->n);
    vt_status st = validate_effects(b->message, body, def->armature, def->damping, def->friction,
                                    def->friction_velocity, def->gear_ratio);
    if (st) return st;
    vt_body_def *d = &b->bodies[body - 1];
    memcpy(d->armature, def->armature, sizeof d->armature);
    memcpy(d->damping, def->damping, sizeof d->damping);
    memcpy(d->friction, def->friction, sizeof d->friction);
    memcpy(d->friction_velocity, def->friction_velocity, sizeof d->friction_velocity);
    memcpy(d->gear_ratio, def->gear_ratio, sizeof d->gear_ratio);
    b->message[0] = '\0';
    return VT_OK;
}

int vt_builder_find_frame(const vt_builder *b, const char *name)
{
    if (!b || !name) return VT_ERR_NULL;
    const int k = name[0] ? vt_names_find(&b->frame_index, b->frame_names, vt_name_in_array, name) : -1;
    return k < 0 ? VT_ERR_NOT_FOUND : k;
}

/* the frame of that name added so far into *body and point, or a status with the message */
static vt_status resolve_frame(const vt_builder *b, char *msg, const char *frame, const char *what, int k, int *body,
                               double point[3])
{
    const int f = vt_names_find(&b->frame_index, b->frame_names, vt_name_in_array, frame);
    if (f < 0) return vt_fail(msg, VT_ERR_NOT_FOUND, "%s %d: no frame \"%.64s\" added so far", what, k, frame);
    *body = b->frames[f].body;
    memcpy(point, b->frames[f].point, 3 * sizeof(double));
    return VT_OK;
}

int vt_builder_add_frame(vt_builder *b, const vt_frame_def *def)
{
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "frame definition is NULL");
    const int k = b->nframe;
    vt_frame_def f = *def;
    if (k >= VT_COUNT_MAX) return count_full(b->message, k, "frame");
    if (!f.name || !f.name[0]) return vt_fail(b->message, VT_ERR_BAD_NAME, "frame %d: a frame needs a name", k);
    vt_name name;
    vt_status st = take_name(b->message, name, f.name, &b->frame_index, (const vt_name *)b->frame_names, "frame", k);
    if (st) return st;
    if (!f.reference && (f.body < 0 || f.body > b->n))
        return vt_fail(b->message, VT_ERR_BAD_INDEX, "frame %d (%s): body %d is not the ground or a body added so far (1..%d)",
                       k, name, f.body, b->n);
    if (!vt_all_finite(f.point, 3) || !vt_all_finite(f.orientation, 4))
        return vt_fail(b->message, VT_ERR_NONFINITE, "frame %d (%s): NaN or Inf in its definition", k, name);
    if (!normalize(f.orientation, 4))
        return vt_fail(b->message, VT_ERR_QUATERNION, "frame %d (%s): orientation of zero norm", k, name);
    if (f.reference) { /* the pose composed onto the reference frame's: its body's axes from its centre of mass */
        const int r = vt_names_find(&b->frame_index, b->frame_names, vt_name_in_array, f.reference);
        if (r < 0)
            return vt_fail(b->message, VT_ERR_NOT_FOUND, "frame %d (%s): no reference frame \"%.64s\" added so far",
                           k, name, f.reference);
        const vt_frame_def *ref = &b->frames[r];
        double A[9], p[3];
        vt_euler_A(A, ref->orientation);
        vt_mulmat3(p, A, f.point);
        for (int e = 0; e < 3; e++) p[e] += ref->point[e];
        if (!vt_all_finite(p, 3))
            return vt_fail(b->message, VT_ERR_NONFINITE, "frame %d (%s): its point overflows on frame \"%s\"", k, name,
                           f.reference);
        vt_copy3(f.point, p);
        vt_quat_mul(f.orientation, ref->orientation, f.orientation);
        f.body = ref->body;
    }
    int capn = b->capframenames;
    if (!grow((void **)&b->frames, &b->capframe, b->nframe, sizeof f) ||
        !grow((void **)&b->frame_names, &capn, b->nframe, sizeof(vt_name)) || vt_names_reserve(&b->frame_index, k + 1)) {
        b->capframenames = capn;
        return vt_fail(b->message, VT_ERR_NO_MEMORY, "frame %d: out of memory", k);
    }
    b->capframenames = capn;
    f.name = f.reference = NULL;
    memcpy(b->frame_names[k], name, sizeof name);
    index_name(&b->frame_index, (const vt_name *)b->frame_names, k);
    b->frames[b->nframe++] = f;
    b->message[0] = '\0';
    return k;
}


/* The library's copy of an orientation drive's sequence name, or NULL if it names none: three
 * axes of one case, no letter twice in a row (upper case body-fixed, lower case fixed axes) */
static const char *sequence_literal(const char *s)
{
    static const char *const known[] = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY",
                                        "ZXZ", "ZYZ", "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx",
                                        "yxy", "yzy", "zxz", "zyz"};
    for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
        if (strcmp(s, known[k]) == 0) return known[k];
    return NULL;
}

static vt_status validate_drive(const vt_builder *b, char *msg, int k, vt_drive_def *d)
{
    if ((int)d->type < 0 || d->type >= VT_DRIVE_TYPE_COUNT)
        return vt_fail(msg, VT_ERR_BAD_DRIVE, "drive %d: unknown type %d", k, (int)d->type);
    if (d->body < 1 || d->body > b->n)
        return vt_fail(msg, VT_ERR_BAD_INDEX, "drive %d: body %d is not a body added so far (1..%d)", k,
                       d->body, b->n);
    const vt_body_def *body = &b->bodies[d->body - 1];
    if (d->sequence && !vt_drive_turns(d->type))
        return vt_fail(msg, VT_ERR_BAD_DRIVE, "drive %d: a sequence of angles belongs to orientation drives", k);
    switch (d->type) {
    case VT_DRIVE_JOINT:
        if (d->index < 0 || d->index >= vt_joint_nv(body->joint))
            return vt_fail(msg, VT_ERR_BAD_DRIVE, "drive %d: body %d's joint has no rate %d", k, d->body, d->index);
        if (body->joint == VT_JOINT_SPHERICAL)
            return vt_fail(msg, VT_ERR_BAD_DRIVE,
                           "drive %d: a spherical joint has no scalar coordinate; use an orientation drive", k);
        if (body->joint == VT_JOINT_FREE && d->index >= 3)
            return vt_fail(msg, VT_ERR_BAD_DRIVE,
                           "drive %d: a free joint's rotation rates (3..5) have no scalar coordinate; drive 0..2 "
                           "(translation) and use an orientation drive for the rotation", k);
        if (body->joint == VT_JOINT_BASE && d->index >= 3)
            return vt_fail(msg, VT_ERR_BAD_DRIVE,
                           "drive %d: a base body's Euler parameters are not driven one by one; use an orientation drive", k);
        break;
    case VT_DRIVE_POINT:
        if (d->index < 0 || d->index > 2)
            return vt_fail(msg, VT_ERR_BAD_DRIVE, "drive %d: component %d is not 0 (x), 1 (y) or 2 (z)", k, d->index);
        if (!vt_all_finite(d->point, 3))
            return vt_fail(msg, VT_ERR_NONFINITE, "drive %d: point not finite", k);
        break;
    default: /* orientation, absolute or relative */
        if (!vt_all_finite(d->axis, 3) || !vt_all_finite(d->orientation, 4))
            return vt_fail(msg, VT_ERR_NONFINITE, "drive %d: axis or orientation not finite", k);
        if (d->sequence && d->orientation_callback)
            return vt_fail(msg, VT_ERR_BAD_DRIVE, "drive %d: a sequence and an orientation callback both given; use one", k);
        if (d->sequence && !(d->sequence = sequence_literal(d->sequence)))
            return vt_fail(msg, VT_ERR_BAD_DRIVE,
                           "drive %d: unknown sequence (three of X, Y, Z body-fixed or of x, y, z about fixed axes, "
                           "no letter twice in a row, e.g. \"ZYX\", \"ZXZ\", \"xyz\")", k);
        if (!d->orientation_callback && !d->sequence && !normalize(d->axis, 3))
            return vt_fail(msg, VT_ERR_AXIS_ZERO, "drive %d: axis of zero length", k);
        if ((!d->orientation_callback || d->type == VT_DRIVE_RELATIVE_ORIENTATION) && !normalize(d->orientation, 4))
            return vt_fail(msg, VT_ERR_QUATERNION, "drive %d: orientation of zero norm", k);
        if (d->type == VT_DRIVE_RELATIVE_ORIENTATION) {
            if (d->reference < -1 || d->reference > b->n)
                return vt_fail(msg, VT_ERR_BAD_INDEX,
                               "drive %d: reference %d is not the ground (0), a body added so far (1..%d) or the body's "
                               "joint (-1)", k, d->reference, b->n);
            if (d->reference == d->body)
                return vt_fail(msg, VT_ERR_BAD_DRIVE, "drive %d: body %d's orientation relative to itself", k, d->body);
            if (d->reference == -1) { /* the joint's drive: p_a* ⊗ p_b = p_J ⊗ p0 (kinematics.c) */
                d->reference = body->parent;
                vt_quat_mul(d->orientation, d->orientation, body->orientation);
            }
        }
        break;
    }
    const vt_function *fs[3];
    const int nf = vt_drive_functions(d, fs);
    for (int e = 0; e < nf; e++) {
        char fmsg[VT_MESSAGE_SIZE];
        vt_status st = vt_function_check(fmsg, fs[e]);
        if (st) return vt_fail(msg, st, "drive %d: %s%s", k, e == 0 ? "" : e == 1 ? "f2: " : "f3: ", fmsg);
    }
    return VT_OK;
}

/* the samples of a drive's spline functions (f, f2, f3) copied, with their second derivatives,
 * into one block of the builder's (each spline's t, y, f'': 3n doubles), so that the caller's
 * arrays are free after the drive is added; *block NULL if the drive has no spline */
static vt_status own_splines(char *msg, int k, vt_drive_def *d, double **block)
{
    vt_function *fs[3] = {&d->f, &d->f2, &d->f3};
    const vt_function *used[3];
    const int nf = vt_drive_functions(d, used);
    size_t total = 0, most = 0;
    for (int e = 0; e < nf; e++)
        if (fs[e]->type == VT_FUNCTION_SPLINE) {
            total += (size_t)fs[e]->nsample;
            most = (size_t)fs[e]->nsample > most ? (size_t)fs[e]->nsample : most;
        }
    *block = NULL;
    if (total == 0) return VT_OK;
    size_t bytes; /* 3 total doubles (most <= total) */
    if (!vt_size_mul(&bytes, total, 3 * sizeof(double)))
        return vt_fail(msg, VT_ERR_TOO_MANY_BODIES, "drive %d: %zu spline samples do not fit in memory", k, total);
    double *own = malloc(bytes), *work = malloc(3 * most * sizeof(double));
    if (!own || !work) {
        free(own);
        free(work);
        return vt_fail(msg, VT_ERR_NO_MEMORY, "drive %d: out of memory for %zu spline samples", k, total);
    }
    double *at = own;
    for (int e = 0; e < nf; e++) {
        vt_function *f = fs[e];
        if (f->type != VT_FUNCTION_SPLINE) continue;
        const size_t n = (size_t)f->nsample;
        memcpy(at, f->sample_t, n * sizeof(double));
        memcpy(at + n, f->sample_y, n * sizeof(double));
        char fmsg[VT_MESSAGE_SIZE];
        const vt_status st = vt_spline_d2(fmsg, f->nsample, at, at + n, at + 2 * n, work);
        if (st) {
            free(work);
            free(own);
            return vt_fail(msg, st, "drive %d: %s%s", k, e == 0 ? "" : e == 1 ? "f2: " : "f3: ", fmsg);
        }
        at += 3 * n;
    }
    free(work);
    at = own;
    for (int e = 0; e < nf; e++) { /* every spline checked: the definition now points at the block */
        vt_function *f = fs[e];
        if (f->type != VT_FUNCTION_SPLINE) continue;
        const size_t n = (size_t)f->nsample;
        f->sample_t = at;
        f->sample_y = at + n;
        f->sample_d2 = at + 2 * n;
        at += 3 * n;
    }
    *block = own;
    return VT_OK;
}

int vt_builder_add_drive(vt_builder *b, const vt_drive_def *def)
{
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "drive definition is NULL");
    if (b->ndrive >= VT_COUNT_MAX) return count_full(b->message, b->ndrive, "drive");
    vt_drive_def d = *def;
    if (d.f.type == VT_FUNCTION_SPLINE) d.f.sample_d2 = NULL; /* computed here, never trusted */
    if (d.f2.type == VT_FUNCTION_SPLINE) d.f2.sample_d2 = NULL;
    if (d.f3.type == VT_FUNCTION_SPLINE) d.f3.sample_d2 = NULL;
    vt_status st = VT_OK;
    if (d.frame) {
        if (d.type != VT_DRIVE_POINT)
            return vt_fail(b->message, VT_ERR_BAD_DRIVE, "drive %d: a frame places point drives only", b->ndrive);
        if ((st = resolve_frame(b, b->message, d.frame, "drive", b->ndrive, &d.body, d.point))) return st;
    }
    if ((st = validate_drive(b, b->message, b->ndrive, &d))) return st;
    vt_name name;
    if ((st = take_name(b->message, name, d.name, &b->drive_index, (const vt_name *)b->drive_names, "drive", b->ndrive)))
        return st;
    double *own = NULL;
    if ((st = own_splines(b->message, b->ndrive, &d, &own))) return st;
    int capn = b->capdrivenames;
    if (!grow((void **)&b->drives, &b->capdrive, b->ndrive, sizeof d) ||
        !grow((void **)&b->drive_names, &capn, b->ndrive, sizeof(vt_name)) ||
        !grow((void **)&b->samples, &b->capsamples, b->ndrive, sizeof own) ||
        vt_names_reserve(&b->drive_index, b->ndrive + 1)) {
        b->capdrivenames = capn; /* only capacities may have grown: the builder's content is as it was */
        free(own);
        return vt_fail(b->message, VT_ERR_NO_MEMORY, "drive %d: out of memory", b->ndrive);
    }
    b->capdrivenames = capn;
    d.name = d.frame = NULL;
    memcpy(b->drive_names[b->ndrive], name, sizeof name);
    index_name(&b->drive_index, (const vt_name *)b->drive_names, b->ndrive);
    b->drives[b->ndrive] = d;
    b->samples[b->ndrive] = own;
    b->message[0] = '\0';
    return b->ndrive++;
}

static vt_status validate_cut(const vt_builder *b, char *msg, int k, vt_cut_joint_def *d)
{
    if ((int)d->joint < 0 || d->joint >= VT_JOINT_TYPE_COUNT)
        return vt_fail(msg, VT_ERR_JOINT_TYPE, "cut joint %d: joint type %d unknown", k, (int)d->joint);
    if (d->joint == VT_JOINT_BASE || d->joint == VT_JOINT_FREE)
        return vt_fail(msg, VT_ERR_BAD_CUT_JOINT, "cut joint %d: a base or free (floating) joint constrains nothing", k);
    if (d->body_a < 0 || d->body_a > b->n || d->body_b < 1 || d->body_b > b->n)
        return vt_fail(msg, VT_ERR_BAD_INDEX, "cut joint %d: bodies %d and %d not both added so far (b: 1..%d, a: 0..%d)",
                       k, d->body_a, d->body_b, b->n, b->n);
    if (d->body_a == d->body_b)
        return vt_fail(msg, VT_ERR_BAD_CUT_JOINT, "cut joint %d: joins body %d to itself", k, d->body_a);
    if (d->planar != 0 && d->planar != 1)
        return vt_fail(msg, VT_ERR_BAD_CUT_JOINT, "cut joint %d: planar is %d (0 or 1)", k, d->planar);
    if (d->planar && d->joint != VT_JOINT_REVOLUTE)
        return vt_fail(msg, VT_ERR_BAD_CUT_JOINT,
                       "cut joint %d: planar is a revolute's pin in the plane ⟂ axis1 (joint VT_JOINT_REVOLUTE), not joint type %d",
                       k, (int)d->joint);
    if (!vt_all_finite(d->point_a, 3) || !vt_all_finite(d->point_b, 3) || !vt_all_finite(d->axis1, 3) ||
        !vt_all_finite(d->axis2, 3) || !vt_all_finite(d->orientation, 4))
        return vt_fail(msg, VT_ERR_NONFINITE, "cut joint %d: NaN or Inf in its definition", k);
    if (d->joint != VT_JOINT_SPHERICAL && !normalize(d->axis1, 3))
        return vt_fail(msg, VT_ERR_AXIS_ZERO, "cut joint %d: axis1 has zero length", k);
    if (d->joint == VT_JOINT_UNIVERSAL) {
        if (!normalize(d->axis2, 3)) return vt_fail(msg, VT_ERR_AXIS_ZERO, "cut joint %d: axis2 has zero length", k);
        const double c = vt_dot3(d->axis1, d->axis2);
        if (fabs(c) > 1e-9)
            return vt_fail(msg, VT_ERR_AXES_NOT_PERPENDICULAR, "cut joint %d: universal axes not perpendicular (cosine %g)", k, c);
    }
    if (!normalize(d->orientation, 4)) return vt_fail(msg, VT_ERR_QUATERNION, "cut joint %d: orientation of zero norm", k);
    return VT_OK;
}

int vt_builder_add_cut_joint(vt_builder *b, const vt_cut_joint_def *def)
{
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "cut joint definition is NULL");
    if (b->ncut >= VT_COUNT_MAX) return count_full(b->message, b->ncut, "cut joint");
    vt_cut_joint_def d = *def;
    vt_status st = VT_OK;
    if (d.frame_a && (st = resolve_frame(b, b->message, d.frame_a, "cut joint", b->ncut, &d.body_a, d.point_a))) return st;
    if (d.frame_b && (st = resolve_frame(b, b->message, d.frame_b, "cut joint", b->ncut, &d.body_b, d.point_b))) return st;
    if ((st = validate_cut(b, b->message, b->ncut, &d))) return st;
    vt_name name;
    if ((st = take_name(b->message, name, d.name, &b->cut_index, (const vt_name *)b->cut_names, "cut joint", b->ncut)))
        return st;
    int capn = b->capcutnames;
    if (!grow((void **)&b->cuts, &b->capcut, b->ncut, sizeof d) ||
        !grow((void **)&b->cut_names, &capn, b->ncut, sizeof(vt_name)) || vt_names_reserve(&b->cut_index, b->ncut + 1)) {
        b->capcutnames = capn;
        return vt_fail(b->message, VT_ERR_NO_MEMORY, "cut joint %d: out of memory", b->ncut);
    }
    b->capcutnames = capn;
    d.name = d.frame_a = d.frame_b = NULL;
    memcpy(b->cut_names[b->ncut], name, sizeof name);
    index_name(&b->cut_index, (const vt_name *)b->cut_names, b->ncut);
    b->cuts[b->ncut] = d;
    b->message[0] = '\0';
    return b->ncut++;
}

/* a coupling's coordinate: body in 1..n, a scalar rate of its joint */
static vt_status coupling_side(const vt_builder *b, char *msg, int k, int body, int index, const char *side)
{
    if (body < 1 || body > b->n)
        return vt_fail(msg, VT_ERR_BAD_INDEX, "coupling %d: body_%s %d is not a body added so far (1..%d)", k, side, body,
                       b->n);
    const int jt = b->bodies[body - 1].joint;
    if (index < 0 || index >= vt_joint_nv(jt))
        return vt_fail(msg, VT_ERR_BAD_INDEX, "coupling %d: body %d's joint has no rate %d", k, body, index);
    if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_BASE || (jt == VT_JOINT_FREE && index >= 3))
        return vt_fail(msg, VT_ERR_BAD_DRIVE,
                       "coupling %d: body %d's joint has no scalar coordinate %d (spherical, base, or a free joint's rotation)",
                       k, body, index);
    return VT_OK;
}

int vt_builder_add_coupling(vt_builder *b, const vt_coupling_def *def)
{
    if (!b) return VT_ERR_NULL;
    if (!def) return vt_fail(b->message, VT_ERR_NULL, "coupling definition is NULL");
    const int k = b->ncoupling;
    if (k >= VT_COUNT_MAX) return count_full(b->message, k, "coupling");
    vt_coupling_def c = *def;
    vt_status st;
    if ((st = coupling_side(b, b->message, k, c.body_a, c.index_a, "a")) ||
        (st = coupling_side(b, b->message, k, c.body_b, c.index_b, "b")))
        return st;
    if (c.body_a == c.body_b && c.index_a == c.index_b)
        return vt_fail(b->message, VT_ERR_BAD_DRIVE, "coupling %d: couples body %d's rate %d with itself", k, c.body_a,
                       c.index_a);
    if (!isfinite(c.ratio) || !isfinite(c.offset))
        return vt_fail(b->message, VT_ERR_NONFINITE, "coupling %d: ratio %g or offset %g not finite", k, c.ratio, c.offset);
    vt_name name;
    if ((st = take_name(b->message, name, c.name, &b->coupling_index, (const vt_name *)b->coupling_names, "coupling", k)))
        return st;
    int capn = b->capcouplingnames;
    if (!grow((void **)&b->couplings, &b->capcoupling, k, sizeof c) ||
        !grow((void **)&b->coupling_names, &capn, k, sizeof(vt_name)) || vt_names_reserve(&b->coupling_index, k + 1)) {
        b->capcouplingnames = capn;
        return vt_fail(b->message, VT_ERR_NO_MEMORY, "coupling %d: out of memory", k);
    }
    b->capcouplingnames = capn;
    c.name = NULL;
    memcpy(b->coupling_names[k], name, sizeof name);
    index_name(&b->coupling_index, (const vt_name *)b->coupling_names, k);
    b->couplings[b->ncoupling++] = c;
    b->message[0] = '\0';
    return k;
}

/* rows of a cut joint by kind (base and free constrain nothing: refused) */
static const int cut_rows[VT_JOINT_TYPE_COUNT] = {0, 5, 4, 3, 5, 4, 0};

int vt_cut_nrows(const vt_cut_joint_def *c)
{
    return c->planar ? 2 : cut_rows[c->joint];
}
