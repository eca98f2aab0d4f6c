/* Scene builders shared by tests, examples and benchmarks (see scenes.h). */
#include <math.h>
#include <string.h>

#include "scenes.h"

#define VT_PI 3.14159265358979323846

static uint64_t splitmix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double vt_rand_uniform(uint64_t *state, double lo, double hi)
{
    return lo + (hi - lo) * (double)(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

void vt_rand_unit(double *v, int n, uint64_t *state)
{
    double s;
    do {
        s = 0.0;
        for (int k = 0; k < n; k++) {
            v[k] = vt_rand_uniform(state, -1.0, 1.0);
            s += v[k] * v[k];
        }
    } while (s > 1.0 || s < 1e-4);
    s = sqrt(s);
    for (int k = 0; k < n; k++) v[k] /= s;
}

static vt_status finish(vt_model **model, vt_builder *b, vt_status st)
{
    if (st == VT_OK) st = vt_builder_build(model, b);
    vt_builder_free(b);
    return st;
}

/* inertia of a uniform slender rod along body x about its centre */
static void rod_inertia(double J[9], double mass, double length)
{
    memset(J, 0, 9 * sizeof(double));
    J[4] = J[8] = mass * length * length / 12.0;
}

vt_status vt_scene_double_link(vt_model **model, int lock)
{
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    vt_body_def link = vt_default_body_def();
    link.mass = VT_DL_MASS;
    rod_inertia(link.inertia, VT_DL_MASS, VT_DL_LENGTH);
    link.joint_child[0] = -0.5 * VT_DL_LENGTH;
    int id = vt_builder_add_body(b, &link); /* link 1: pinned to the ground at the origin */
    if (id > 0) {
        link.parent = id;
        link.joint_parent[0] = 0.5 * VT_DL_LENGTH;
        id = vt_builder_add_body(b, &link);
    }
    if (id > 0 && lock) {
        vt_drive_def drive = vt_default_drive_def();
        drive.body = 2; /* q2 = 0 */
        id = vt_builder_add_drive(b, &drive);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_chain(vt_model **model, int n)
{
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    const double len = 0.5;
    for (int i = 1; i <= n && st == VT_OK; i++) {
        vt_body_def link = vt_default_body_def();
        link.parent = i - 1;
        rod_inertia(link.inertia, link.mass, len);
        link.joint_parent[0] = i > 1 ? 0.5 * len : 0.0;
        link.joint_child[0] = -0.5 * len;
        memset(link.axis1, 0, sizeof link.axis1);
        link.axis1[(i - 1) % 3] = 1.0;
        const int id = vt_builder_add_body(b, &link);
        if (id < 0) st = (vt_status)id;
    }
    return finish(model, b, st);
}

static void random_rotation(double A[9], uint64_t *s)
{
    double p[4];
    vt_rand_unit(p, 4, s);
    vt_euler_A(A, p);
}

vt_status vt_scene_random_tree(vt_model **model, uint64_t seed, int n, unsigned kinds)
{
    vt_joint_type allowed[VT_JOINT_TYPE_COUNT];
    int nallowed = 0;
    for (int k = 0; k < VT_JOINT_TYPE_COUNT; k++)
        if (kinds & (1u << k)) allowed[nallowed++] = (vt_joint_type)k;
    if (nallowed == 0) return VT_ERR_JOINT_TYPE;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    uint64_t s = seed;
    for (int i = 1; i <= n && st == VT_OK; i++) {
        vt_body_def d = vt_default_body_def();
        /* cycle through the kinds so every one appears; base bodies hang from the ground */
        d.joint = allowed[(i - 1) % nallowed];
        d.parent = d.joint == VT_JOINT_BASE ? 0 : (int)(vt_rand_uniform(&s, 0.0, 1.0) * i) % i;
        d.mass = vt_rand_uniform(&s, 0.5, 3.0);
        /* principal moments (b+c, a+c, a+b) satisfy the triangle inequality */
        double a[3], R[9], Dg[3];
        for (int k = 0; k < 3; k++) a[k] = vt_rand_uniform(&s, 0.1, 1.0) * 0.1 * d.mass;
        Dg[0] = a[1] + a[2]; Dg[1] = a[0] + a[2]; Dg[2] = a[0] + a[1];
        random_rotation(R, &s);
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++) {
                double v = 0.0;
                for (int k = 0; k < 3; k++) v += R[r + 3 * k] * Dg[k] * R[c + 3 * k];
                d.inertia[r + 3 * c] = v;
            }
        for (int c = 0; c < 3; c++) /* exact symmetry */
            for (int r = c + 1; r < 3; r++) d.inertia[c + 3 * r] = d.inertia[r + 3 * c];
        for (int k = 0; k < 3; k++) {
            d.joint_parent[k] = vt_rand_uniform(&s, -0.5, 0.5);
            d.joint_child[k] = vt_rand_uniform(&s, -0.5, 0.5);
        }
        vt_rand_unit(d.axis1, 3, &s);
        double t[3];
        vt_rand_unit(t, 3, &s);
        const double c = t[0] * d.axis1[0] + t[1] * d.axis1[1] + t[2] * d.axis1[2];
        for (int k = 0; k < 3; k++) d.axis2[k] = t[k] - c * d.axis1[k];
        vt_rand_unit(d.orientation, 4, &s);
        const int id = vt_builder_add_body(b, &d);
        if (id < 0) st = (vt_status)id;
    }
    return finish(model, b, st);
}

void vt_scene_random_state(const vt_model *m, vt_data *d, uint64_t *s)
{
    for (int i = 1; i <= m->nbody; i++) {
        double *q = d->q + m->body_qadr[i], *v = d->qd + m->body_vadr[i];
        switch (m->body_joint[i]) {
        case VT_JOINT_BASE: {
            double w[3], E[12];
            for (int k = 0; k < 3; k++) {
                q[k] = vt_rand_uniform(s, -1.0, 1.0);
                v[k] = vt_rand_uniform(s, -2.0, 2.0);
                w[k] = vt_rand_uniform(s, -2.0, 2.0);
            }
            vt_rand_unit(q + 3, 4, s);
            vt_euler_E(E, q + 3);
            for (int k = 0; k < 4; k++) v[3 + k] = 0.5 * (E[3 * k] * w[0] + E[3 * k + 1] * w[1] + E[3 * k + 2] * w[2]);
            break;
        }
        case VT_JOINT_SPHERICAL:
            vt_rand_unit(q, 4, s);
            for (int k = 0; k < 3; k++) v[k] = vt_rand_uniform(s, -2.0, 2.0);
            break;
        case VT_JOINT_TRANSLATIONAL:
            q[0] = vt_rand_uniform(s, -1.0, 1.0);
            v[0] = vt_rand_uniform(s, -2.0, 2.0);
            break;
        case VT_JOINT_CYLINDRICAL:
            q[0] = vt_rand_uniform(s, -VT_PI, VT_PI);
            q[1] = vt_rand_uniform(s, -1.0, 1.0);
            v[0] = vt_rand_uniform(s, -2.0, 2.0);
            v[1] = vt_rand_uniform(s, -2.0, 2.0);
            break;
        default: /* revolute, universal */
            for (int k = 0; k < m->body_nv[i]; k++) {
                q[k] = vt_rand_uniform(s, -VT_PI, VT_PI);
                v[k] = vt_rand_uniform(s, -2.0, 2.0);
            }
        }
    }
}
