/* Scene builders shared by tests, examples and benchmarks (see scenes.h). */
#include <math.h>
#include <stdio.h>
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

static vt_status double_link(vt_model **model, int lock, vt_function f)
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
        drive.body = 2; /* q2 = f(t) */
        drive.f = f;
        id = vt_builder_add_drive(b, &drive);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_double_link(vt_model **model, int lock)
{
    return double_link(model, lock, vt_function_constant(0.0));
}

vt_status vt_scene_double_link_driven(vt_model **model, vt_function f)
{
    return double_link(model, 1, f);
}

vt_status vt_scene_free_joint_driven(vt_model **model)
{
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    vt_body_def body = vt_default_body_def();
    body.joint_child[0] = -0.5;
    body.inertia[0] = body.inertia[4] = body.inertia[8] = 0.1;
    int id = vt_builder_add_body(b, &body);
    body.parent = 1;
    body.joint = VT_JOINT_FREE;
    body.joint_parent[0] = 0.5;
    body.joint_child[0] = 0.2, body.joint_child[1] = -0.1, body.joint_child[2] = 0.3;
    if (id > 0) id = vt_builder_add_body(b, &body);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    dr.f = vt_function_sine(0.2, 0.7, 1.1, 0.3);
    if (id > 0) id = vt_builder_add_drive(b, &dr);
    for (int k = 0; k < 3 && id >= 0; k++) {
        dr.body = 2;
        dr.index = k;
        dr.f = vt_function_sine(0.1 * k, 0.3 + 0.1 * k, 0.9 + 0.4 * k, 0.2 * k);
        id = vt_builder_add_drive(b, &dr);
    }
    dr = vt_default_drive_def();
    dr.type = VT_DRIVE_ORIENTATION;
    dr.body = 2;
    dr.axis[0] = 0.0, dr.axis[1] = 0.6, dr.axis[2] = 0.8;
    dr.f = vt_function_sine(0.1, 0.5, 1.3, 0.0);
    if (id >= 0) id = vt_builder_add_drive(b, &dr);
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

void vt_scene_chain_state(int k, double *q, double *qd, double *qdd)
{
    *q = 0.3 * sin(1.3 * k + 0.2);
    *qd = 0.5 * cos(0.7 * k);
    *qdd = 0.4 * sin(0.9 * k + 1.0);
}

vt_status vt_scene_chain(vt_model **model, int n, int drives)
{
    return vt_scene_chain_layout(model, n, drives, VT_LAYOUT_FULL);
}

vt_status vt_scene_chain_layout(vt_model **model, int n, int drives, vt_layout layout)
{
    vt_builder *b;
    vt_model_def def = vt_default_model_def();
    def.layout = layout;
    vt_status st = vt_builder_create(&b, &def);
    if (st) return st;
    const double len = 0.5;
    for (int i = 1; i <= n && st == VT_OK; i++) {
        vt_body_def link = vt_default_body_def();
        link.parent = i - 1;
        rod_inertia(link.inertia, link.mass, len);
        link.inertia[0] = 2e-4;
        link.joint_parent[0] = i > 1 ? 0.5 * len : 0.0;
        link.joint_child[0] = -0.5 * len;
        memset(link.axis1, 0, sizeof link.axis1);
        link.axis1[(i - 1) % 3] = 1.0;
        const int id = vt_builder_add_body(b, &link);
        if (id < 0) st = (vt_status)id;
    }
    if (st == VT_OK && drives == VT_CHAIN_JOINT_DRIVEN) {
        for (int i = 1; i <= n && st == VT_OK; i++) {
            double c[3];
            vt_scene_chain_state(i - 1, &c[0], &c[1], &c[2]);
            c[2] *= 0.5;
            vt_drive_def dr = vt_default_drive_def();
            dr.body = i;
            dr.f = vt_function_polynomial(3, c);
            const int id = vt_builder_add_drive(b, &dr);
            if (id < 0) st = (vt_status)id;
        }
    }
    if (st == VT_OK && drives == VT_CHAIN_TIP_DRIVE) {
        /* the tip's y at the reference state, from the joint-driven chain's instant there (its
         * O(n) data: the positions without the dense S, at any n) */
        vt_model *free_chain = NULL;
        vt_data *d;
        st = vt_scene_chain_layout(&free_chain, n, VT_CHAIN_JOINT_DRIVEN, VT_LAYOUT_RECURSIVE);
        if (st == VT_OK && (st = vt_data_create(&d, free_chain)) == VT_OK) {
            double dummy;
            for (int k = 0; k < n; k++) vt_scene_chain_state(k, &d->q[k], &dummy, &dummy);
            st = vt_inverse_dynamics_recursive(free_chain, d);
            const double y0 = d->x[7 * (n - 1) + 1] + 0.5 * len * d->A[9 * n + 1];
            vt_data_free(d);
            vt_drive_def dr = vt_default_drive_def();
            dr.type = VT_DRIVE_POINT;
            dr.body = n;
            dr.index = 1;
            dr.point[0] = 0.5 * len;
            dr.f = vt_function_sine(y0, 0.05, 2.0 * VT_PI, 0.0);
            if (st == VT_OK) {
                const int id = vt_builder_add_drive(b, &dr);
                if (id < 0) st = (vt_status)id;
            }
        }
        if (free_chain) vt_model_free(free_chain);
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
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    return finish(model, b, vt_scene_random_bodies(b, seed, n, kinds));
}

vt_status vt_scene_random_bodies(vt_builder *b, uint64_t seed, int n, unsigned kinds)
{
    vt_joint_type allowed[VT_JOINT_TYPE_COUNT];
    int nallowed = 0;
    for (int k = 0; k < VT_JOINT_TYPE_COUNT; k++)
        if (kinds & (1u << k)) allowed[nallowed++] = (vt_joint_type)k;
    if (nallowed == 0) return VT_ERR_JOINT_TYPE;
    vt_status st = VT_OK;
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
    return st;
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
        case VT_JOINT_FREE:
            for (int k = 0; k < 3; k++) q[k] = vt_rand_uniform(s, -1.0, 1.0);
            vt_rand_unit(q + 3, 4, s);
            for (int k = 0; k < 6; k++) v[k] = vt_rand_uniform(s, -2.0, 2.0);
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

/* The spatial four-bar, exactly constrained: crank, coupler and rocker rods; the coupler on a
 * spherical joint and the loop closed by a universal one (RSUR), or the other way round (RUSR).
 * The universal's second axis is the coupler's y in both. */
static vt_status fourbar(vt_model **model, vt_function crank, int rusr)
{
    static const double len[3] = {VT_FB_A, VT_FB_B, VT_FB_C}, mass[3] = {1.0, 3.0, 2.0};
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    int id = 0;
    for (int k = 0; k < 3 && id >= 0; k++) {
        vt_body_def link = vt_default_body_def();
        link.mass = mass[k];
        rod_inertia(link.inertia, mass[k], len[k]);
        link.joint_child[0] = -0.5 * len[k];
        if (k == 1) { /* coupler at the crank's tip: spherical, or universal (z on the crank, then its y) */
            link.parent = 1;
            link.joint = rusr ? VT_JOINT_UNIVERSAL : VT_JOINT_SPHERICAL;
            link.joint_parent[0] = 0.5 * VT_FB_A;
            link.axis2[0] = 0.0;
            link.axis2[1] = 1.0;
        }
        if (k == 2) link.joint_parent[0] = VT_FB_D; /* rocker pivot on the ground */
        id = vt_builder_add_body(b, &link);
    }
    if (id > 0) { /* the rocker's tip and the coupler's tip */
        vt_cut_joint_def cut = vt_default_cut_joint_def();
        cut.joint = rusr ? VT_JOINT_SPHERICAL : VT_JOINT_UNIVERSAL;
        cut.body_a = 3;
        cut.body_b = 2;
        cut.point_a[0] = 0.5 * VT_FB_C;
        cut.point_b[0] = 0.5 * VT_FB_B;
        cut.axis2[0] = 0.0; /* universal: with b's axes taken as a's, the coupler's y */
        cut.axis2[1] = 1.0;
        id = vt_builder_add_cut_joint(b, &cut);
    }
    if (id >= 0) {
        vt_drive_def drive = vt_default_drive_def();
        drive.body = 1;
        drive.f = crank;
        id = vt_builder_add_drive(b, &drive);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_fourbar(vt_model **model, vt_function crank)
{
    return fourbar(model, crank, 0);
}

vt_status vt_scene_fourbar_rusr(vt_model **model, vt_function crank)
{
    return fourbar(model, crank, 1);
}

/* planar four-bar: coupler and rocker angles and rates from the crank's (open branch) */
static int fourbar_angles(double th2, double w2, double th[2], double w[2])
{
    /* crank tip B, rocker pivot O4; C on both circles |C − B| = b, |C − O4| = c */
    const double Bx = VT_FB_A * cos(th2), By = VT_FB_A * sin(th2);
    const double ex = VT_FB_D - Bx, ey = -By, L = sqrt(ex * ex + ey * ey);
    const double x = (L * L + VT_FB_B * VT_FB_B - VT_FB_C * VT_FB_C) / (2.0 * L);
    const double h2 = VT_FB_B * VT_FB_B - x * x;
    if (h2 < 0.0 || L == 0.0) return -1;
    const double h = sqrt(h2), ux = ex / L, uy = ey / L;
    double Cx = Bx + x * ux - h * uy, Cy = By + x * uy + h * ux;
    if (Cy < 0.0) { Cx = Bx + x * ux + h * uy; Cy = By + x * uy - h * ux; }
    th[0] = atan2(Cy - By, Cx - Bx);
    th[1] = atan2(Cy, Cx - VT_FB_D);
    /* rates: a ω2 k×e2 + b ω3 k×e3 = c ω4 k×e4 (two equations) */
    const double a11 = -VT_FB_B * sin(th[0]), a12 = VT_FB_C * sin(th[1]);
    const double a21 = VT_FB_B * cos(th[0]), a22 = -VT_FB_C * cos(th[1]);
    const double r1 = VT_FB_A * w2 * sin(th2), r2 = -VT_FB_A * w2 * cos(th2);
    const double det = a11 * a22 - a12 * a21;
    if (det == 0.0) return -1;
    w[0] = (r1 * a22 - a12 * r2) / det;
    w[1] = (a11 * r2 - a21 * r1) / det;
    return 0;
}

int vt_scene_fourbar_assemble(const vt_model *m, vt_data *d, double th2, double w2, double th[2], double w[2])
{
    double a[2], r[2];
    if (fourbar_angles(th2, w2, a, r)) return -1;
    const double z[3] = {0, 0, 1};
    d->q[m->body_qadr[1]] = th2;
    vt_quat_axis_angle(d->q + m->body_qadr[2], z, a[0] - th2);
    d->q[m->body_qadr[3]] = a[1];
    d->qd[m->body_vadr[1]] = w2;
    d->qd[m->body_vadr[2]] = 0.0;
    d->qd[m->body_vadr[2] + 1] = 0.0;
    d->qd[m->body_vadr[2] + 2] = r[0] - w2;
    d->qd[m->body_vadr[3]] = r[1];
    if (th) { th[0] = a[0]; th[1] = a[1]; }
    if (w) { w[0] = r[0]; w[1] = r[1]; }
    return 0;
}

int vt_scene_fourbar_rusr_assemble(const vt_model *m, vt_data *d, double th2, double w2, double th[2], double w[2])
{
    double a[2], r[2];
    if (fourbar_angles(th2, w2, a, r)) return -1;
    /* the universal's angles: the coupler's turn about z relative to the crank, then no tilt */
    d->q[m->body_qadr[1]] = th2;
    d->q[m->body_qadr[2]] = a[0] - th2;
    d->q[m->body_qadr[2] + 1] = 0.0;
    d->q[m->body_qadr[3]] = a[1];
    d->qd[m->body_vadr[1]] = w2;
    d->qd[m->body_vadr[2]] = r[0] - w2;
    d->qd[m->body_vadr[2] + 1] = 0.0;
    d->qd[m->body_vadr[3]] = r[1];
    if (th) { th[0] = a[0]; th[1] = a[1]; }
    if (w) { w[0] = r[0]; w[1] = r[1]; }
    return 0;
}

vt_status vt_scene_five_link(vt_model **model)
{
    return vt_scene_five_link_payload(model, 0.0, 1.0);
}

vt_status vt_scene_five_link_payload(vt_model **model, double payload, double period)
{
    static const double len[5] = {0.4, 0.5, 0.5, 0.2, 0.2}, mass[5] = {2.0, 1.5, 1.5, 0.5, 0.5};
    if (!(payload >= 0.0 && isfinite(payload) && period > 0.0 && isfinite(period))) return VT_ERR_BAD_OPTION;
    /* link 5 with the point mass at its tip: the centre moves c toward the tip (parallel axes) */
    const double c5 = payload * 0.5 * len[4] / (mass[4] + payload);
    vt_model_def md = vt_default_model_def();
    md.gravity[1] = 0.0;
    md.gravity[2] = -9.81;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    int id = 0;
    for (int k = 0; k < 5 && id >= 0; k++) {
        vt_body_def link = vt_default_body_def();
        link.parent = k;
        link.mass = mass[k];
        double I = mass[k] * len[k] * len[k] / 12.0;
        if (k == 4) {
            link.mass += payload;
            I += mass[k] * c5 * c5 + payload * (0.5 * len[k] - c5) * (0.5 * len[k] - c5);
        }
        memset(link.axis1, 0, sizeof link.axis1);
        if (k == 0) { /* column along z */
            link.inertia[0] = link.inertia[4] = I;
            link.joint_child[2] = -0.5 * len[0];
            link.axis1[2] = 1.0;
        } else {
            link.inertia[4] = link.inertia[8] = I;
            link.joint_child[0] = -0.5 * len[k] - (k == 4 ? c5 : 0.0);
            if (k == 1) link.joint_parent[2] = 0.5 * len[0];
            else link.joint_parent[0] = 0.5 * len[k - 1];
            link.axis1[k == 4 ? 2 : 1] = 1.0;
        }
        id = vt_builder_add_body(b, &link);
    }
    /* (30)-(34): tip x, tip y, joint-5 point y, tip z, joint-5 point z */
    static const int body[5] = {5, 5, 4, 5, 4}, comp[5] = {0, 1, 1, 2, 2};
    const double w = 2.0 * VT_PI / period;
    for (int k = 0; k < 5 && id >= 0; k++) {
        vt_drive_def dr = vt_default_drive_def();
        dr.type = VT_DRIVE_POINT;
        dr.body = body[k];
        dr.index = comp[k];
        dr.point[0] = body[k] == 5 ? 0.1 - c5 : 0.1; /* the far end of link 4 or link 5 */
        if (comp[k] == 0) dr.f = vt_function_sine(VT_FL_C1, 0.3, w, 0.5 * VT_PI);
        else if (comp[k] == 1) dr.f = vt_function_sine(0.0, 0.3, w, 0.0);
        else dr.f = vt_function_constant(VT_FL_CE);
        id = vt_builder_add_drive(b, &dr);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

void vt_scene_five_link_guess(const vt_model *m, vt_data *d, double t)
{
    const double w = 2.0 * VT_PI, a = 0.5, bl = 0.5;
    const double px = VT_FL_C1 - 0.2 + 0.3 * cos(w * t), py = 0.3 * sin(w * t);
    const double psi = atan2(py, px), rho = sqrt(px * px + py * py);
    const double X = rho - 0.2, Y = 0.4 - VT_FL_CE; /* to the end of link 3: out and down from joint 2 */
    const double D2 = X * X + Y * Y;
    double c3 = (D2 - a * a - bl * bl) / (2 * a * bl);
    c3 = c3 > 1 ? 1 : (c3 < -1 ? -1 : c3);
    const double q3 = -acos(c3);
    const double q2 = atan2(Y, X) - atan2(bl * sin(q3), a + bl * cos(q3));
    double *q = d->q;
    q[m->body_qadr[1]] = psi;
    q[m->body_qadr[2]] = q2;
    q[m->body_qadr[3]] = q3;
    q[m->body_qadr[4]] = -(q2 + q3);
    q[m->body_qadr[5]] = -psi;
}

/* drive i of VT_DELTA_IK: θ_i, θ̇_i, θ̈_i at the path's p(t), ṗ(t), p̈(t) */
static int delta_motor_path(double t, double out[3], void *user)
{
    const vt_delta_arm *arm = user;
    double p[3], pd[3], pdd[3];
    vt_scene_delta_path(t, arm->ik->period, p, pd, pdd);
    return vt_scene_delta_motor(arm->arm, p, pd, pdd, out) ? 1 : 0;
}

/* the Delta with the drives `drives`; ik the callbacks' data of VT_DELTA_IK */
static vt_status delta_build(vt_model **model, double period, int drives, vt_delta_ik *ik)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[1] = 0.0;
    md.gravity[2] = -9.81;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    int id = 0;
    for (int i = 0; i < 3 && id >= 0; i++) { /* the upper arms, bodies 1..3 */
        const double phi = 2.0 * VT_PI * i / 3.0, c = cos(phi), s = sin(phi);
        vt_body_def arm = vt_default_body_def();
        arm.mass = VT_DELTA_MA;
        rod_inertia(arm.inertia, VT_DELTA_MA, VT_DELTA_LA);
        arm.inertia[0] = 1e-4; /* about its own axis: a tube of 13 mm radius */
        arm.joint_parent[0] = VT_DELTA_RB * c;
        arm.joint_parent[1] = VT_DELTA_RB * s;
        arm.joint_child[0] = -0.5 * VT_DELTA_LA;
        arm.axis1[0] = -s;
        arm.axis1[1] = c;
        arm.axis1[2] = 0.0;
        arm.orientation[0] = cos(0.5 * phi);
        arm.orientation[3] = sin(0.5 * phi);
        id = vt_builder_add_body(b, &arm);
    }
    for (int i = 0; i < 3 && id >= 0; i++) /* the forearms' rods, bodies 4..9 */
        for (int k = 0; k < 2 && id >= 0; k++) {
            vt_body_def rod = vt_default_body_def();
            rod.parent = 1 + i;
            rod.joint = VT_JOINT_UNIVERSAL;
            rod.mass = VT_DELTA_MR;
            rod.inertia[0] = rod.inertia[4] = VT_DELTA_MR * VT_DELTA_LF * VT_DELTA_LF / 12.0;
            rod.inertia[8] = 0.5 * VT_DELTA_MR * 0.008 * 0.008; /* a tube of 8 mm radius */
            rod.joint_parent[0] = 0.5 * VT_DELTA_LA;
            rod.joint_parent[1] = k ? VT_DELTA_H : -VT_DELTA_H;
            rod.joint_child[2] = 0.5 * VT_DELTA_LF;
            rod.axis1[0] = 0.0; /* the arm's y, then the rod's x */
            rod.axis1[1] = 1.0;
            rod.axis1[2] = 0.0;
            rod.axis2[0] = 1.0;
            id = vt_builder_add_body(b, &rod);
        }
    if (id >= 0) { /* the platform, body 10 */
        vt_body_def pf = vt_default_body_def();
        pf.joint = VT_JOINT_FREE;
        pf.mass = VT_DELTA_MP;
        pf.inertia[0] = pf.inertia[4] = 1.0e-3;
        pf.inertia[8] = 0.5 * VT_DELTA_MP * VT_DELTA_RP * VT_DELTA_RP;
        id = vt_builder_add_body(b, &pf);
    }
    if (id >= 0) { /* the gripper's tip */
        vt_frame_def tool = vt_default_frame_def();
        tool.name = "tool";
        tool.body = 10;
        tool.point[2] = -VT_DELTA_TOOL;
        const int fr = vt_builder_add_frame(b, &tool);
        if (fr < 0) id = fr;
    }
    for (int i = 0; i < 3 && id >= 0; i++)
        for (int k = 0; k < 2 && id >= 0; k++) {
            const double phi = 2.0 * VT_PI * i / 3.0, c = cos(phi), s = sin(phi), h = k ? VT_DELTA_H : -VT_DELTA_H;
            vt_cut_joint_def cut = vt_default_cut_joint_def();
            cut.joint = VT_JOINT_SPHERICAL;
            cut.body_a = 10;
            cut.body_b = 4 + 2 * i + k;
            cut.point_a[0] = VT_DELTA_RP * c - h * s;
            cut.point_a[1] = VT_DELTA_RP * s + h * c;
            cut.point_b[2] = -0.5 * VT_DELTA_LF;
            id = vt_builder_add_cut_joint(b, &cut);
        }
    const double w = 2.0 * VT_PI / period;
    for (int k = 0; k < 3 && id >= 0; k++) {
        vt_drive_def dr = vt_default_drive_def();
        if (drives == VT_DELTA_PATH) {
            dr.type = VT_DRIVE_POINT;
            dr.body = 10;
            dr.index = k;
            if (k == 0) dr.f = vt_function_sine(0.0, VT_DELTA_RHO, w, 0.5 * VT_PI);
            else if (k == 1) dr.f = vt_function_sine(0.0, VT_DELTA_RHO, w, 0.0);
            else dr.f = vt_function_sine(VT_DELTA_Z0, VT_DELTA_DZ, 2.0 * w, 0.0);
        } else {
            dr.body = 1 + k; /* joint drive of the motor angle */
            if (drives == VT_DELTA_IK) dr.f = vt_function_user(delta_motor_path, &ik->arm[k]);
        }
        id = vt_builder_add_drive(b, &dr);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_delta(vt_model **model, double period, int drives)
{
    if (!(period > 0.0 && isfinite(period)) || (drives != VT_DELTA_PATH && drives != VT_DELTA_MOTORS))
        return VT_ERR_BAD_OPTION;
    return delta_build(model, period, drives, NULL);
}

vt_status vt_scene_delta_ik(vt_model **model, vt_delta_ik *ik, double period)
{
    if (!ik) return VT_ERR_NULL;
    if (!(period > 0.0 && isfinite(period))) return VT_ERR_BAD_OPTION;
    ik->period = period;
    for (int i = 0; i < 3; i++) {
        ik->arm[i].ik = ik;
        ik->arm[i].arm = i;
    }
    return delta_build(model, period, VT_DELTA_IK, ik);
}

/* Arm i (u = (cos φ_i, sin φ_i, 0), t = (−sin φ_i, cos φ_i, 0)): the elbow
 * E = (RB + LA cos θ) u − LA sin θ z and the rods' platform end p + RP u are LF apart. With
 * c = p + (RP − RB) u and its components a = c·u, b = c·t, z = c_z:
 *   |c − LA cos θ u + LA sin θ z|² = LF²  ⇔  F(θ, p) = A cos θ + B sin θ − K = 0,
 *   A = −2 LA a,  B = 2 LA z,  K = LF² − LA² − a² − b² − z²,
 * solved by θ = atan2(B, A) ± acos(K / √(A² + B²)), the elbow out the root of larger cos θ.
 * Along a motion ȧ = ṗ·u, ḃ = ṗ·t, ż = ṗ_z (and likewise for the second derivatives), so
 *   Ȧ = −2 LA ȧ,  Ḃ = 2 LA ż,  K̇ = −2 (a ȧ + b ḃ + z ż),  K̈ = −2 (ȧ² + ḃ² + ż² + a ä + b b̈ + z z̈),
 * and with F_θ = −A sin θ + B cos θ, differentiating F = 0 once and twice:
 *   F_θ θ̇ + Ȧ cos θ + Ḃ sin θ − K̇ = 0,
 *   F_θ θ̈ + Ä cos θ + B̈ sin θ − K̈ + 2 θ̇ (−Ȧ sin θ + Ḃ cos θ) − θ̇² (A cos θ + B sin θ) = 0. */
int vt_scene_delta_motor(int arm, const double p[3], const double pd[3], const double pdd[3], double th[3])
{
    const double phi = 2.0 * VT_PI * arm / 3.0;
    const double u[2] = {cos(phi), sin(phi)}, t[2] = {-u[1], u[0]};
    const double cx = p[0] + (VT_DELTA_RP - VT_DELTA_RB) * u[0], cy = p[1] + (VT_DELTA_RP - VT_DELTA_RB) * u[1];
    const double a = cx * u[0] + cy * u[1], bt = cx * t[0] + cy * t[1], z = p[2];
    const double A = -2.0 * a * VT_DELTA_LA, B = 2.0 * z * VT_DELTA_LA;
    const double K = VT_DELTA_LF * VT_DELTA_LF - VT_DELTA_LA * VT_DELTA_LA - a * a - bt * bt - z * z;
    const double rAB = sqrt(A * A + B * B);
    if (!(rAB > 0.0) || !(fabs(K) <= rAB)) return -1;
    const double th1 = atan2(B, A) + acos(K / rAB), th2 = atan2(B, A) - acos(K / rAB);
    const double q = cos(th1) >= cos(th2) ? th1 : th2, c = cos(q), s = sin(q);
    th[0] = q;
    if (!pd || !pdd) return 0;
    const double Fth = -A * s + B * c;
    if (!(Fth != 0.0)) return -1;
    const double ad = pd[0] * u[0] + pd[1] * u[1], bd = pd[0] * t[0] + pd[1] * t[1], zd = pd[2];
    const double add = pdd[0] * u[0] + pdd[1] * u[1], bdd = pdd[0] * t[0] + pdd[1] * t[1], zdd = pdd[2];
    const double Ad = -2.0 * VT_DELTA_LA * ad, Bd = 2.0 * VT_DELTA_LA * zd, Kd = -2.0 * (a * ad + bt * bd + z * zd);
    const double Add = -2.0 * VT_DELTA_LA * add, Bdd = 2.0 * VT_DELTA_LA * zdd;
    const double Kdd = -2.0 * (ad * ad + bd * bd + zd * zd + a * add + bt * bdd + z * zdd);
    const double qd = -(Ad * c + Bd * s - Kd) / Fth;
    th[1] = qd;
    th[2] = -(Add * c + Bdd * s - Kdd + 2.0 * qd * (-Ad * s + Bd * c) - qd * qd * (A * c + B * s)) / Fth;
    return 0;
}

void vt_scene_delta_path(double t, double period, double p[3], double pd[3], double pdd[3])
{
    const double w = 2.0 * VT_PI / period, c = cos(w * t), s = sin(w * t), c2 = cos(2 * w * t), s2 = sin(2 * w * t);
    if (p) {
        p[0] = VT_DELTA_RHO * c;
        p[1] = VT_DELTA_RHO * s;
        p[2] = VT_DELTA_Z0 + VT_DELTA_DZ * s2;
    }
    if (pd) {
        pd[0] = -VT_DELTA_RHO * w * s;
        pd[1] = VT_DELTA_RHO * w * c;
        pd[2] = 2.0 * w * VT_DELTA_DZ * c2;
    }
    if (pdd) {
        pdd[0] = -VT_DELTA_RHO * w * w * c;
        pdd[1] = -VT_DELTA_RHO * w * w * s;
        pdd[2] = -4.0 * w * w * VT_DELTA_DZ * s2;
    }
}

int vt_scene_delta_assemble(const vt_model *m, vt_data *d, const double p[3])
{
    for (int i = 0; i < 3; i++) {
        const double phi = 2.0 * VT_PI * i / 3.0;
        const double u[3] = {cos(phi), sin(phi), 0.0}, t[3] = {-u[1], u[0], 0.0};
        /* the rod runs from the elbow E = (RB + LA cos θ) u − LA sin θ z to the platform's point
         * p + RP u (either rod: the parallelogram), c − LA cos θ u + LA sin θ z with
         * c = p + (RP − RB) u; θ from vt_scene_delta_motor (elbow out) */
        const double cv[3] = {p[0] + (VT_DELTA_RP - VT_DELTA_RB) * u[0], p[1] + (VT_DELTA_RP - VT_DELTA_RB) * u[1], p[2]};
        const double a = cv[0] * u[0] + cv[1] * u[1], bt = cv[0] * t[0] + cv[1] * t[1], z = cv[2];
        double ths[3];
        if (vt_scene_delta_motor(i, p, NULL, NULL, ths)) return -1;
        const double th = ths[0];
        d->q[m->body_qadr[1 + i]] = th;
        /* the rod's direction in the arm's axes x_a = cos θ u − sin θ z, y_a = t,
         * z_a = sin θ u + cos θ z; the universal turns it from −z_a to
         * R_y(α) R_x(β) (0, 0, −1) = (−sin α cos β, sin β, −cos α cos β) */
        const double e[3] = {a - (VT_DELTA_LA * cos(th)), bt, z + VT_DELTA_LA * sin(th)}; /* in u, t, z */
        const double dx = (e[0] * cos(th) - e[2] * sin(th)) / VT_DELTA_LF, dy = e[1] / VT_DELTA_LF,
                     dz = (e[0] * sin(th) + e[2] * cos(th)) / VT_DELTA_LF;
        const double beta = asin(dy < -1.0 ? -1.0 : (dy > 1.0 ? 1.0 : dy)), alpha = atan2(-dx, -dz);
        for (int k = 0; k < 2; k++) {
            const int body = 4 + 2 * i + k;
            d->q[m->body_qadr[body]] = alpha;
            d->q[m->body_qadr[body] + 1] = beta;
        }
    }
    double *qp = d->q + m->body_qadr[10];
    qp[0] = p[0];
    qp[1] = p[1];
    qp[2] = p[2];
    qp[3] = 1.0;
    qp[4] = qp[5] = qp[6] = 0.0;
    for (int k = 0; k < m->nv; k++) d->qd[k] = 0.0;
    return 0;
}

/* a builder whose model has gravity −9.81 z (z up, as URDF robots) */
static vt_status z_up_builder(vt_builder **b, int allow_redundant)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = 0.0, md.gravity[2] = -9.81;
    md.allow_redundant = allow_redundant;
    return vt_builder_create(b, &md);
}

/* the quadruped's bodies and frames into b: VT_OK or the failing status */
static vt_status quadruped_bodies(vt_builder *b)
{
    vt_body_def torso = vt_default_body_def();
    torso.joint = VT_JOINT_FREE;
    torso.parent = 0;
    torso.mass = 10.0;
    const double lx = 0.6, ly = 0.3, lz = 0.1; /* a uniform box */
    torso.inertia[0] = torso.mass * (ly * ly + lz * lz) / 12.0;
    torso.inertia[4] = torso.mass * (lx * lx + lz * lz) / 12.0;
    torso.inertia[8] = torso.mass * (lx * lx + ly * ly) / 12.0;
    torso.name = "torso";
    torso.joint_name = "root";
    int id = vt_builder_add_body(b, &torso);
    static const char *const leg[4] = {"FL", "FR", "HL", "HR"};
    for (int k = 0; k < 4 && id > 0; k++) {
        char name[3][16], joint[3][16], foot[16];
        snprintf(name[0], 16, "%s_hip", leg[k]), snprintf(joint[0], 16, "%s_HAA", leg[k]);
        snprintf(name[1], 16, "%s_thigh", leg[k]), snprintf(joint[1], 16, "%s_HFE", leg[k]);
        snprintf(name[2], 16, "%s_shank", leg[k]), snprintf(joint[2], 16, "%s_KFE", leg[k]);
        snprintf(foot, 16, "%s_foot", leg[k]);
        vt_body_def hip = vt_default_body_def();
        hip.parent = 1;
        hip.mass = 0.3;
        hip.inertia[0] = hip.inertia[4] = hip.inertia[8] = 2e-4;
        hip.joint_parent[0] = k < 2 ? 0.3 : -0.3;
        hip.joint_parent[1] = k % 2 == 0 ? 0.15 : -0.15;
        hip.axis1[0] = 1.0, hip.axis1[1] = 0.0, hip.axis1[2] = 0.0;
        hip.name = name[0];
        hip.joint_name = joint[0];
        const int h = id = vt_builder_add_body(b, &hip);
        vt_body_def rod = vt_default_body_def();
        rod.axis1[0] = 0.0, rod.axis1[1] = 1.0, rod.axis1[2] = 0.0;
        rod.joint_child[2] = 0.1; /* the joint point 0.1 m above the centre of mass */
        for (int s = 1; s < 3 && id > 0; s++) {
            rod.parent = s == 1 ? h : id;
            rod.mass = s == 1 ? 1.0 : 0.5;
            memset(rod.inertia, 0, sizeof rod.inertia);
            rod.inertia[0] = rod.inertia[4] = rod.mass * 0.04 / 12.0;
            rod.inertia[8] = 1e-5;
            rod.joint_parent[2] = s == 1 ? 0.0 : -0.1;
            rod.name = name[s];
            rod.joint_name = joint[s];
            id = vt_builder_add_body(b, &rod);
        }
        if (id > 0) {
            vt_frame_def f = vt_default_frame_def();
            f.name = foot;
            f.body = id;
            f.point[2] = -0.1;
            const int fr = vt_builder_add_frame(b, &f);
            if (fr < 0) id = fr;
        }
    }
    return id < 0 ? (vt_status)id : VT_OK;
}

vt_status vt_scene_quadruped(vt_model **model)
{
    vt_builder *b;
    vt_status st = z_up_builder(&b, 0);
    if (st) return st;
    return finish(model, b, quadruped_bodies(b));
}

vt_status vt_scene_quadruped_feet(vt_model **model, unsigned feet)
{
    vt_builder *b;
    vt_status st = z_up_builder(&b, 1);
    if (st) return st;
    st = quadruped_bodies(b);
    for (int i = 2; i <= 13 && !st; i++) { /* every leg joint driven */
        vt_drive_def dr = vt_default_drive_def();
        dr.body = i;
        const int id = vt_builder_add_drive(b, &dr);
        if (id < 0) st = (vt_status)id;
    }
    static const char *const foot[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};
    for (int k = 0; k < 4 && !st; k++) {
        if (!(feet >> k & 1u)) continue;
        vt_cut_joint_def cj = vt_default_cut_joint_def();
        cj.joint = VT_JOINT_SPHERICAL;
        cj.body_a = 0;
        cj.point_a[0] = k < 2 ? 0.3 : -0.3; /* under the hip */
        cj.point_a[1] = k % 2 == 0 ? 0.15 : -0.15;
        cj.frame_b = foot[k];
        cj.name = foot[k];
        const int id = vt_builder_add_cut_joint(b, &cj);
        if (id < 0) st = (vt_status)id;
    }
    return finish(model, b, st);
}

vt_status vt_scene_quadruped_sway(vt_model **model, double period)
{
    vt_builder *b;
    vt_status st = z_up_builder(&b, 0);
    if (st) return st;
    st = quadruped_bodies(b);
    const double a = VT_SWAY_AMPLITUDE, w = 2.0 * 3.14159265358979323846 / period;
    const double h = 0.4 * cos(VT_SWAY_THETA);
    for (int k = 0; k < 4 && !st; k++) { /* the root's x, y, z, then its roll */
        vt_drive_def dr = vt_default_drive_def();
        dr.body = 1;
        dr.index = k;
        dr.f = k == 0 ? vt_function_sine(0.0, a, w, 0.0) : k == 1 ? vt_function_constant(0.0)
               : k == 2 ? vt_function_sine(h, a, 2.0 * w, 0.0) : vt_function_sine(0.0, a, w, 0.0);
        if (k == 3) {
            dr.type = VT_DRIVE_ORIENTATION;
            dr.index = 0;
            dr.axis[0] = 1.0, dr.axis[1] = dr.axis[2] = 0.0;
        }
        const int id = vt_builder_add_drive(b, &dr);
        if (id < 0) st = (vt_status)id;
    }
    static const char *const foot[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};
    for (int k = 0; k < 12 && !st; k++) { /* each foot's x, y, z under its hip */
        const int leg = k / 3, e = k % 3;
        vt_drive_def dr = vt_default_drive_def();
        dr.type = VT_DRIVE_POINT;
        dr.frame = foot[leg];
        dr.index = e;
        dr.f = vt_function_constant(e == 0 ? (leg < 2 ? 0.3 : -0.3) : e == 1 ? (leg % 2 == 0 ? 0.15 : -0.15) : 0.0);
        const int id = vt_builder_add_drive(b, &dr);
        if (id < 0) st = (vt_status)id;
    }
    return finish(model, b, st);
}

void vt_scene_quadruped_stand(const vt_model *m, vt_data *d, double theta)
{
    memset(d->qd, 0, (size_t)m->nv * sizeof(double));
    memset(d->qdd, 0, (size_t)m->nv * sizeof(double));
    double *q = d->q;
    q[0] = q[1] = 0.0, q[2] = 0.4 * cos(theta); /* the root: position, then Euler parameters */
    q[3] = 1.0, q[4] = q[5] = q[6] = 0.0;
    for (int i = 2; i <= m->nbody; i++) {
        const int k = (i - 2) % 3;                      /* hip, thigh, shank */
        const double th = (i - 2) / 6 == 0 ? theta : -theta; /* the hind legs mirror the front ones */
        q[m->body_qadr[i]] = k == 0 ? 0.0 : k == 1 ? th : -2.0 * th;
    }
}

void vt_scene_quintic(double u, double *s, double *sd, double *sdd)
{
    *s = u * u * u * (10 - 15 * u + 6 * u * u);
    *sd = 30 * u * u * (1 - u) * (1 - u);
    *sdd = 60 * u * (1 - u) * (1 - 2 * u);
}

void vt_scene_foot_step(double base, double n, double tau, double swing, double stride, double lift, int air,
                        double p[3], double v[3], double a[3])
{
    double s = 1.0, sd = 0.0, sdd = 0.0;
    if (air) vt_scene_quintic(tau / swing, &s, &sd, &sdd);
    p[0] = base + stride * (n + s);
    v[0] = stride * sd / swing;
    a[0] = stride * sdd / (swing * swing);
    v[1] = a[1] = 0.0;
    p[2] = v[2] = a[2] = 0.0;
    if (air) { /* lift sin²(π u) */
        const double w = 3.14159265358979323846 / swing, x = w * tau;
        p[2] = lift * sin(x) * sin(x);
        v[2] = lift * w * sin(2 * x);
        a[2] = 2 * lift * w * w * cos(2 * x);
    }
}

void vt_scene_leg_ik(double L, const double d[3], const double dd[3], const double ddd[3], double knee, double q[3],
                     double qd[3], double qdd[3])
{
    /* the abduction φ = atan2(a, b), a = d_y, b = −d_z, and the distance ρ in the leg's plane */
    const double a = d[1], b = -d[2], ad = dd[1], bd = -dd[2], add = ddd[1], bdd = -ddd[2];
    const double r2 = a * a + b * b, rho = sqrt(r2), g = a * ad + b * bd, cr = ad * b - a * bd;
    q[0] = atan2(a, b);
    qd[0] = cr / r2;
    qdd[0] = ((add * b - a * bdd) * r2 - cr * 2.0 * g) / (r2 * r2);
    const double rd = g / rho, rdd = (ad * ad + a * add + bd * bd + b * bdd) / rho - g * g / (rho * r2);
    /* the planar two-link leg, a link at angle α along (−sin α, −cos α), reaching p = (d_x, −ρ) */
    const double p[2] = {d[0], -rho}, pv[2] = {dd[0], -rd}, pa[2] = {ddd[0], -rdd};
    double c = (p[0] * p[0] + p[1] * p[1] - 2.0 * L * L) / (2.0 * L * L);
    c = c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c;
    q[2] = knee * acos(c);
    q[1] = atan2(-p[0], -p[1]) - 0.5 * q[2];
    const double a1 = q[1], a2 = q[1] + q[2];
    const double u1[2] = {-sin(a1), -cos(a1)}, u2[2] = {-sin(a2), -cos(a2)};
    const double J[4] = {L * (-cos(a1) - cos(a2)), L * (sin(a1) + sin(a2)), -L * cos(a2), L * sin(a2)}; /* columns */
    const double det = J[0] * J[3] - J[2] * J[1];
    qd[1] = (J[3] * pv[0] - J[2] * pv[1]) / det;
    qd[2] = (-J[1] * pv[0] + J[0] * pv[1]) / det;
    const double w1 = qd[1], w2 = qd[1] + qd[2];
    double r[2]; /* p̈ − J̇ q̇, J̇ q̇ = −L (u1 w1² + u2 w2²) */
    for (int e = 0; e < 2; e++) r[e] = pa[e] + L * (u1[e] * w1 * w1 + u2[e] * w2 * w2);
    qdd[1] = (J[3] * r[0] - J[2] * r[1]) / det;
    qdd[2] = (-J[1] * r[0] + J[0] * r[1]) / det;
}

vt_status vt_scene_humanoid(vt_model **model)
{
    vt_builder *b;
    vt_status st = z_up_builder(&b, 0);
    if (st) return st;
    vt_body_def trunk = vt_default_body_def();
    trunk.joint = VT_JOINT_FREE;
    trunk.parent = 0;
    trunk.mass = 20.0;
    trunk.inertia[0] = trunk.inertia[4] = trunk.mass * (0.09 + 0.25) / 12.0;
    trunk.inertia[8] = trunk.mass * (0.09 + 0.09) / 12.0;
    trunk.name = "trunk";
    trunk.joint_name = "root";
    int id = vt_builder_add_body(b, &trunk);
    static const char *const side[2] = {"L", "R"};
    for (int k = 0; k < 2 && id > 0; k++) {
        const double y = k == 0 ? 0.1 : -0.1, out = k == 0 ? 0.05 : -0.05;
        char name[5][24], joint[5][24];
        static const char *const part[5] = {"hip", "thigh", "shank", "ankle", "foot"};
        static const char *const kind[5] = {"hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll"};
        for (int j = 0; j < 5; j++) {
            snprintf(name[j], 24, "%s_%s", side[k], part[j]);
            snprintf(joint[j], 24, "%s_%s", side[k], kind[j]);
        }
        static const double mass[5] = {0.5, 3.0, 2.0, 0.2, 1.0};
        int parent = 1;
        for (int j = 0; j < 5 && id > 0; j++) {
            vt_body_def d = vt_default_body_def();
            d.parent = parent;
            d.mass = mass[j];
            d.name = name[j];
            d.joint_name = joint[j];
            const int roll = j == 0 || j == 4;
            d.axis1[0] = roll ? 1.0 : 0.0, d.axis1[1] = roll ? 0.0 : 1.0, d.axis1[2] = 0.0;
            if (j == 0) d.joint_parent[1] = y, d.joint_parent[2] = -0.2;
            if (j == 1 || j == 2) { /* rods: the joint point 0.2 m above the centre of mass */
                d.joint_child[2] = 0.2;
                d.inertia[0] = d.inertia[4] = d.mass * 0.16 / 12.0;
                d.inertia[8] = 1e-4;
            } else if (j == 4) { /* the foot: its centre 0.025 m below the ankle */
                d.joint_child[2] = 0.025;
                d.inertia[0] = d.mass * (0.01 + 0.0025) / 12.0;
                d.inertia[4] = d.mass * (0.04 + 0.0025) / 12.0;
                d.inertia[8] = d.mass * (0.04 + 0.01) / 12.0;
            } else {
                d.inertia[0] = d.inertia[4] = d.inertia[8] = 2e-4;
            }
            if (j == 2) d.joint_parent[2] = -0.2; /* the knee at the thigh's end */
            if (j == 3) d.joint_parent[2] = -0.2; /* the ankle at the shank's end */
            parent = id = vt_builder_add_body(b, &d);
        }
        static const char *const corner[4] = {"toe_in", "toe_out", "heel_in", "heel_out"};
        for (int c = 0; c < 4 && id > 0; c++) {
            char fname[24];
            snprintf(fname, sizeof fname, "%s_%s", side[k], corner[c]);
            vt_frame_def f = vt_default_frame_def();
            f.name = fname;
            f.body = id;
            f.point[0] = c < 2 ? 0.1 : -0.1;
            f.point[1] = c % 2 ? out : -out;
            f.point[2] = -0.025; /* the sole */
            const int fr = vt_builder_add_frame(b, &f);
            if (fr < 0) id = fr;
        }
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_pendulum(vt_model **model)
{
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    vt_body_def mass = vt_default_body_def(); /* 1 kg point mass */
    mass.joint_child[0] = -1.0;
    const int id = vt_builder_add_body(b, &mass);
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

static vt_status fourbar_rrrr(vt_model **model, vt_function crank, int allow_redundant, int planar)
{
    static const double len[3] = {VT_FB_A, VT_FB_B, VT_FB_C}, mass[3] = {1.0, 3.0, 2.0};
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = allow_redundant;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    int id = 0;
    for (int k = 0; k < 3 && id >= 0; k++) {
        vt_body_def link = vt_default_body_def();
        link.parent = k;
        link.mass = mass[k];
        rod_inertia(link.inertia, mass[k], len[k]);
        /* crank and coupler from their first end; the rocker hangs from its far end C */
        link.joint_child[0] = k == 2 ? 0.5 * len[k] : -0.5 * len[k];
        if (k > 0) link.joint_parent[0] = 0.5 * len[k - 1];
        id = vt_builder_add_body(b, &link);
    }
    if (id > 0) {
        vt_cut_joint_def cut = vt_default_cut_joint_def(); /* revolute about z */
        cut.body_a = 0;
        cut.body_b = 3;
        cut.point_a[0] = VT_FB_D;
        cut.point_b[0] = -0.5 * VT_FB_C;
        cut.planar = planar;
        id = vt_builder_add_cut_joint(b, &cut);
    }
    if (id >= 0) {
        vt_drive_def drive = vt_default_drive_def();
        drive.body = 1;
        drive.f = crank;
        id = vt_builder_add_drive(b, &drive);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_fourbar_planar(vt_model **model, vt_function crank, int allow_redundant)
{
    return fourbar_rrrr(model, crank, allow_redundant, 0);
}

vt_status vt_scene_fourbar_pin(vt_model **model, vt_function crank)
{
    return fourbar_rrrr(model, crank, 0, 1);
}

vt_status vt_scene_slider_crank(vt_model **model, vt_function crank, int planar)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = !planar;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    vt_body_def link = vt_default_body_def(); /* the crank, about z at the origin */
    link.mass = 1.0;
    rod_inertia(link.inertia, 1.0, VT_SC_R);
    link.joint_child[0] = -0.5 * VT_SC_R;
    int id = vt_builder_add_body(b, &link);
    link = vt_default_body_def(); /* the rod, at the crank's tip */
    link.parent = 1;
    link.mass = 2.0;
    rod_inertia(link.inertia, 2.0, VT_SC_L);
    link.joint_parent[0] = 0.5 * VT_SC_R;
    link.joint_child[0] = -0.5 * VT_SC_L;
    if (id > 0) id = vt_builder_add_body(b, &link);
    link = vt_default_body_def(); /* the slider, along x on the ground */
    link.joint = VT_JOINT_TRANSLATIONAL;
    link.mass = 1.5;
    link.inertia[0] = link.inertia[4] = link.inertia[8] = 0.01;
    link.axis1[0] = 1.0;
    link.axis1[2] = 0.0;
    link.joint_parent[1] = VT_SC_H;
    link.joint_child[0] = VT_SC_JX;
    link.joint_child[1] = VT_SC_JY;
    if (id > 0) id = vt_builder_add_body(b, &link);
    if (id > 0) { /* the rod's far end on the slider's pin */
        vt_cut_joint_def cut = vt_default_cut_joint_def();
        cut.body_a = 3;
        cut.body_b = 2;
        cut.point_a[0] = VT_SC_PX;
        cut.point_a[1] = VT_SC_PY;
        cut.point_b[0] = 0.5 * VT_SC_L;
        cut.planar = planar;
        id = vt_builder_add_cut_joint(b, &cut);
    }
    if (id >= 0) {
        vt_drive_def drive = vt_default_drive_def();
        drive.body = 1;
        drive.f = crank;
        id = vt_builder_add_drive(b, &drive);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

int vt_scene_slider_crank_assemble(const vt_model *m, vt_data *d, double th, double w)
{
    /* the pin B at height h = VT_SC_H − VT_SC_JY + VT_SC_PY: r sin θ + L sin φ = h, rod toward +x */
    const double h = VT_SC_H - VT_SC_JY + VT_SC_PY, s = (h - VT_SC_R * sin(th)) / VT_SC_L;
    if (!(fabs(s) < 1.0)) return -1;
    const double phi = asin(s), wphi = -VT_SC_R * w * cos(th) / (VT_SC_L * cos(phi));
    const double Bx = VT_SC_R * cos(th) + VT_SC_L * cos(phi), vBx = -VT_SC_R * w * sin(th) - VT_SC_L * wphi * sin(phi);
    d->q[m->body_qadr[1]] = th;
    d->q[m->body_qadr[2]] = phi - th;
    d->q[m->body_qadr[3]] = Bx - (VT_SC_PX - VT_SC_JX); /* the slider's joint point from (0, VT_SC_H) */
    d->qd[m->body_vadr[1]] = w;
    d->qd[m->body_vadr[2]] = wphi - w;
    d->qd[m->body_vadr[3]] = vBx;
    return 0;
}

int vt_scene_fourbar_planar_assemble(const vt_model *m, vt_data *d, double th2, double w2)
{
    double th[2], w[2];
    if (fourbar_angles(th2, w2, th, w)) return -1;
    /* the rocker's body x runs from its pivot at O4 to C: relative to the coupler th4 − th3 */
    d->q[m->body_qadr[1]] = th2;
    d->q[m->body_qadr[2]] = th[0] - th2;
    d->q[m->body_qadr[3]] = th[1] - th[0];
    d->qd[m->body_vadr[1]] = w2;
    d->qd[m->body_vadr[2]] = w[0] - w2;
    d->qd[m->body_vadr[3]] = w[1] - w[0];
    return 0;
}

vt_status vt_scene_nfourbar(vt_model **model, int N)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = 1;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    vt_body_def rod = vt_default_body_def();
    rod_inertia(rod.inertia, 1.0, 1.0);
    rod.joint_child[0] = -0.5;
    int id = vt_builder_add_body(b, &rod); /* crank 0 */
    for (int k = 1; k <= N && id > 0; k++) { /* couplers, each from the previous link's far end */
        rod.parent = k;
        rod.joint_parent[0] = 0.5;
        id = vt_builder_add_body(b, &rod);
    }
    for (int k = 1; k <= N && id > 0; k++) { /* cranks 1..N from the ground */
        rod.parent = 0;
        rod.joint_parent[0] = (double)k;
        id = vt_builder_add_body(b, &rod);
    }
    for (int k = 1; k <= N && id >= 0; k++) {
        vt_cut_joint_def cut = vt_default_cut_joint_def(); /* revolute about z */
        cut.body_a = N + 1 + k;  /* crank k */
        cut.body_b = 1 + k;      /* coupler k */
        cut.point_a[0] = 0.5;
        cut.point_b[0] = 0.5;
        id = vt_builder_add_cut_joint(b, &cut);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

void vt_scene_nfourbar_start(const vt_model *m, vt_data *d, int N, double w)
{
    const double up = 0.5 * VT_PI;
    d->q[m->body_qadr[1]] = up;
    d->qd[m->body_vadr[1]] = w;
    d->q[m->body_qadr[2]] = -up; /* coupler 1 horizontal: it translates */
    d->qd[m->body_vadr[2]] = -w;
    for (int k = 2; k <= N; k++) {
        d->q[m->body_qadr[1 + k]] = 0.0;
        d->qd[m->body_vadr[1 + k]] = 0.0;
    }
    for (int k = 1; k <= N; k++) {
        d->q[m->body_qadr[N + 1 + k]] = up;
        d->qd[m->body_vadr[N + 1 + k]] = w;
    }
}

vt_status vt_scene_bricard(vt_model **model, vt_joint_type cut_kind, int drive, vt_function f)
{
    /* the corners, each rod's direction and each joint's axis (global = body axes at q = 0) */
    static const double corner[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, {0, 0, 1}};
    static const int axis[6] = {1, 2, 0, 1, 2, 0}; /* y, z, x, y, z, x */
    if (cut_kind != VT_JOINT_REVOLUTE && cut_kind != VT_JOINT_UNIVERSAL) return VT_ERR_BAD_CUT_JOINT;
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = cut_kind == VT_JOINT_REVOLUTE;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    const double It = (1.0 + 0.01) / 12.0, Il = 2.0 * 0.01 / 12.0; /* m (L² + a²) / 12, m 2a² / 12 */
    double com[6][3];
    int id = 0;
    for (int k = 0; k < 5 && id >= 0; k++) {
        vt_body_def rod = vt_default_body_def();
        int dir = 0;
        for (int c = 0; c < 3; c++) {
            com[k][c] = 0.5 * (corner[k][c] + corner[k + 1][c]);
            if (corner[k + 1][c] != corner[k][c]) dir = c;
        }
        for (int c = 0; c < 3; c++) rod.inertia[4 * c] = c == dir ? Il : It;
        rod.parent = k;
        for (int c = 0; c < 3; c++) {
            rod.joint_parent[c] = corner[k][c] - (k > 0 ? com[k - 1][c] : 0.0);
            rod.joint_child[c] = corner[k][c] - com[k][c];
            rod.axis1[c] = c == axis[k];
        }
        id = vt_builder_add_body(b, &rod);
    }
    if (id > 0) {
        vt_cut_joint_def cut = vt_default_cut_joint_def();
        cut.joint = cut_kind;
        cut.body_a = 0;
        cut.body_b = 5;
        for (int c = 0; c < 3; c++) {
            cut.point_a[c] = corner[5][c];
            cut.point_b[c] = corner[5][c] - com[4][c];
            cut.axis1[c] = c == axis[5];
            cut.axis2[c] = c == 2;
        }
        id = vt_builder_add_cut_joint(b, &cut);
    }
    if (id >= 0 && drive) {
        vt_drive_def dr = vt_default_drive_def();
        dr.f = f;
        id = vt_builder_add_drive(b, &dr);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_spherical_chain(vt_model **model, int relative)
{
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    int id = 0;
    vt_body_def body = vt_default_body_def();
    body.mass = 2.0;
    const double J[9] = {0.12, 0.01, -0.02, 0.01, 0.2, 0.015, -0.02, 0.015, 0.15};
    memcpy(body.inertia, J, sizeof J);
    body.axis1[0] = 0.3; body.axis1[1] = 0.2; body.axis1[2] = 0.93;
    body.joint_child[1] = -0.4; body.joint_child[2] = 0.1;
    if (id >= 0) id = vt_builder_add_body(b, &body);
    body.parent = 1;
    body.joint = VT_JOINT_SPHERICAL;
    body.mass = 1.5;
    body.joint_parent[0] = 0.1; body.joint_parent[1] = -0.5; body.joint_parent[2] = 0.2;
    body.joint_child[0] = 0.2; body.joint_child[1] = 0.3; body.joint_child[2] = -0.1;
    const double q0[4] = {0.9, 0.1, -0.3, 0.2}; /* normalized by the builder */
    memcpy(body.orientation, q0, sizeof q0);
    if (id >= 0) id = vt_builder_add_body(b, &body);
    body.parent = 2;
    body.joint = VT_JOINT_REVOLUTE;
    body.mass = 0.8;
    body.orientation[0] = 1.0; body.orientation[1] = body.orientation[2] = body.orientation[3] = 0.0;
    body.axis1[0] = 1.0; body.axis1[1] = 0.0; body.axis1[2] = 0.0;
    body.joint_parent[0] = -0.2; body.joint_parent[1] = 0.4; body.joint_parent[2] = 0.0;
    body.joint_child[0] = 0.0; body.joint_child[1] = -0.3; body.joint_child[2] = 0.05;
    if (id >= 0) id = vt_builder_add_body(b, &body);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    dr.f = vt_function_sine(0.2, 0.6, 1.9, 0.1);
    if (id >= 0) id = vt_builder_add_drive(b, &dr);
    dr.type = relative ? VT_DRIVE_RELATIVE_ORIENTATION : VT_DRIVE_ORIENTATION;
    dr.body = 2;
    dr.sequence = "ZYX";
    dr.f = vt_function_sine(0.4, 0.5, 2.2, -0.3);
    dr.f2 = vt_function_sine(-0.3, 0.4, 1.4, 0.6);
    dr.f3 = vt_function_sine(0.1, -0.7, 2.7, 0.2);
    if (id >= 0) id = vt_builder_add_drive(b, &dr);
    dr = vt_default_drive_def();
    dr.body = 3;
    dr.f = vt_function_sine(-0.5, 0.3, 3.1, 0.0);
    if (id >= 0) id = vt_builder_add_drive(b, &dr);
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

/* ---- Stewart–Gough platform (6-UPS) ---- */

static const double sg_axis[3] = {0.40824829046386302, 0.40824829046386302, 0.81649658092772603}; /* (1,1,2)/√6 */

void vt_scene_stewart_points(int leg, double a[3], double b[3])
{
    const int k = leg / 2, j = leg % 2;
    const double deg = VT_PI / 180.0;
    const double ab = (120.0 * k + (j ? 15.0 : -15.0)) * deg, pb = (120.0 * k + (j ? 45.0 : -45.0)) * deg;
    a[0] = VT_SG_BASE_R * cos(ab);
    a[1] = VT_SG_BASE_R * sin(ab);
    a[2] = 0.0;
    b[0] = VT_SG_PLAT_R * cos(pb);
    b[1] = VT_SG_PLAT_R * sin(pb);
    b[2] = 0.0;
}

void vt_scene_stewart_pose(const vt_stewart *sg, double t, double r[9], double p[4], double w[6])
{
    const double om = sg->omega, ph = sg->phase + om * t, s1 = sin(ph), c1 = cos(ph), s2 = sin(2.0 * ph),
                 c2 = cos(2.0 * ph);
    r[0] = 0.08 * s1;
    r[1] = 0.06 * s2;
    r[2] = VT_SG_HEIGHT + 0.05 * s1;
    r[3] = om * 0.08 * c1;
    r[4] = om * 0.12 * c2;
    r[5] = om * 0.05 * c1;
    r[6] = -om * om * 0.08 * s1;
    r[7] = -om * om * 0.24 * s2;
    r[8] = -om * om * 0.05 * s1;
    /* a turn θ = 0.15 sin φ about the fixed axis n: ω = θ' n, ω̇ = θ'' n */
    const double th = 0.15 * s1, thd = 0.15 * om * c1, thdd = -0.15 * om * om * s1;
    vt_quat_axis_angle(p, sg_axis, th);
    for (int k = 0; k < 3; k++) {
        w[k] = thd * sg_axis[k];
        w[3 + k] = thdd * sg_axis[k];
    }
}

/* leg i's vector l = r + ρ − a from the universal's centre to the spherical's (ρ = A b), its
 * first and second derivatives: l' = ṙ + ω × ρ, l'' = r̈ + ω̇ × ρ + ω × (ω × ρ) */
static void sg_leg(const vt_stewart *sg, int leg, double t, double l[9])
{
    double r[9], p[4], w[6], A[9], a[3], b[3], rho[3], wr[3];
    vt_scene_stewart_pose(sg, t, r, p, w);
    vt_scene_stewart_points(leg, a, b);
    vt_euler_A(A, p);
    for (int k = 0; k < 3; k++) rho[k] = A[k] * b[0] + A[k + 3] * b[1] + A[k + 6] * b[2];
    wr[0] = w[1] * rho[2] - w[2] * rho[1];
    wr[1] = w[2] * rho[0] - w[0] * rho[2];
    wr[2] = w[0] * rho[1] - w[1] * rho[0];
    for (int k = 0; k < 3; k++) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        l[k] = r[k] + rho[k] - a[k];
        l[3 + k] = r[3 + k] + wr[k];
        l[6 + k] = r[6 + k] + (w[3 + k1] * rho[k2] - w[3 + k2] * rho[k1]) + (w[k1] * wr[k2] - w[k2] * wr[k1]);
    }
}

/* L = |l|, L' = l·l'/L, L'' = (l'·l' + l·l'' − L'²)/L */
static int sg_length(double t, double out[3], void *user)
{
    const vt_stewart_leg *lg = user;
    double l[9];
    sg_leg(lg->sg, lg->leg, t, l);
    const double L = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const double Ld = (l[0] * l[3] + l[1] * l[4] + l[2] * l[5]) / L;
    out[0] = L;
    out[1] = Ld;
    out[2] = (l[3] * l[3] + l[4] * l[4] + l[5] * l[5] + l[0] * l[6] + l[1] * l[7] + l[2] * l[8] - Ld * Ld) / L;
    return 0;
}

/* a solid cylinder along body z: transverse m (3 ρ² + ℓ²)/12, axial m ρ²/2 */
static void cylinder_inertia(double J[9], double mass, double length, double radius)
{
    memset(J, 0, 9 * sizeof(double));
    J[0] = J[4] = mass * (3.0 * radius * radius + length * length) / 12.0;
    J[8] = 0.5 * mass * radius * radius;
}

vt_status vt_scene_stewart(vt_model **model, vt_stewart *sg)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[1] = 0.0;
    md.gravity[2] = -9.81;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    vt_body_def plat = vt_default_body_def();
    plat.joint = VT_JOINT_FREE;
    plat.mass = VT_SG_M_PLAT;
    cylinder_inertia(plat.inertia, VT_SG_M_PLAT, 0.03, VT_SG_PLAT_R);
    plat.name = "platform";
    int id = vt_builder_add_body(b, &plat);
    for (int i = 0; i < 6 && id >= 0; i++) {
        double a[3], bp[3];
        vt_scene_stewart_points(i, a, bp);
        vt_body_def cyl = vt_default_body_def();
        cyl.joint = VT_JOINT_UNIVERSAL;
        cyl.mass = VT_SG_M_CYL;
        cylinder_inertia(cyl.inertia, VT_SG_M_CYL, 0.5, 0.04);
        memcpy(cyl.joint_parent, a, sizeof a);
        cyl.joint_child[2] = -VT_SG_HALF;
        cyl.axis1[0] = 1.0; /* the global x, then the cylinder's y */
        cyl.axis1[2] = 0.0;
        cyl.axis2[0] = 0.0;
        cyl.axis2[1] = 1.0;
        id = vt_builder_add_body(b, &cyl);
        if (id < 0) break;
        vt_body_def pis = vt_default_body_def();
        pis.parent = id;
        pis.joint = VT_JOINT_TRANSLATIONAL;
        pis.mass = VT_SG_M_PIST;
        cylinder_inertia(pis.inertia, VT_SG_M_PIST, 0.5, 0.02);
        pis.joint_parent[2] = -VT_SG_HALF; /* the universal's centre on the cylinder */
        pis.joint_child[2] = VT_SG_HALF;   /* the piston's top: its coordinate is the leg length */
        id = vt_builder_add_body(b, &pis);
        if (id < 0) break;
        vt_cut_joint_def cut = vt_default_cut_joint_def();
        cut.joint = VT_JOINT_SPHERICAL;
        cut.body_a = 1;
        cut.body_b = id;
        memcpy(cut.point_a, bp, sizeof bp);
        cut.point_b[2] = VT_SG_HALF;
        id = vt_builder_add_cut_joint(b, &cut);
        if (id < 0) break;
        sg->leg[i].sg = sg;
        sg->leg[i].leg = i;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = 3 + 2 * i;
        dr.f = vt_function_user(sg_length, &sg->leg[i]);
        id = vt_builder_add_drive(b, &dr);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

void vt_scene_stewart_assemble(const vt_model *m, vt_data *d, const vt_stewart *sg, double t)
{
    double r[9], p[4], w[6];
    vt_scene_stewart_pose(sg, t, r, p, w);
    for (int k = 0; k < 3; k++) {
        d->q[m->body_qadr[1] + k] = r[k];
        d->qd[m->body_vadr[1] + k] = r[3 + k];
        d->qd[m->body_vadr[1] + 3 + k] = w[k];
    }
    for (int k = 0; k < 4; k++) d->q[m->body_qadr[1] + 3 + k] = p[k];
    for (int i = 0; i < 6; i++) {
        double l[9];
        sg_leg(sg, i, t, l);
        const double L = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        const double u[3] = {l[0] / L, l[1] / L, l[2] / L}, ul = u[0] * l[3] + u[1] * l[4] + u[2] * l[5];
        double ud[3];
        for (int k = 0; k < 3; k++) ud[k] = (l[3 + k] - u[k] * ul) / L;
        /* u = Rx(q1) Ry(q2) z = (sin q2, −sin q1 cos q2, cos q1 cos q2) */
        const int c = 2 + 2 * i, s = 3 + 2 * i;
        d->q[m->body_qadr[c]] = atan2(-u[1], u[2]);
        d->q[m->body_qadr[c] + 1] = asin(u[0]);
        d->qd[m->body_vadr[c]] = (u[1] * ud[2] - u[2] * ud[1]) / (u[1] * u[1] + u[2] * u[2]);
        d->qd[m->body_vadr[c] + 1] = ud[0] / sqrt(u[1] * u[1] + u[2] * u[2]);
        d->q[m->body_qadr[s]] = L;
        d->qd[m->body_vadr[s]] = ul;
    }
    d->time = t;
}

/* ---- knee four-bar ---- */

/* a solid rod along body x: axial m ρ²/2, transverse m (3 ρ² + ℓ²)/12 */
static void rod_x_inertia(double J[9], double mass, double length, double radius)
{
    memset(J, 0, 9 * sizeof(double));
    J[0] = 0.5 * mass * radius * radius;
    J[4] = J[8] = mass * (3.0 * radius * radius + length * length) / 12.0;
}

vt_status vt_scene_knee_with(vt_model **model, vt_function hip, vt_function motor, int planar, const double mass[4],
                             int drives, const double effects[][3])
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = !planar;
    vt_builder *b;
    vt_status st = vt_builder_create(&b, &md);
    if (st) return st;
    const double ls = VT_KN_C + VT_KN_L, cs = 0.5 * ls - VT_KN_C; /* shank rod; its centre from the knee */
    vt_body_def thigh = vt_default_body_def();
    thigh.mass = mass[0];
    rod_x_inertia(thigh.inertia, mass[0], VT_KN_D, 0.01);
    thigh.joint_child[0] = -0.5 * VT_KN_D;
    thigh.name = "thigh";
    if (effects) thigh.armature[0] = effects[0][0], thigh.damping[0] = effects[0][1], thigh.friction[0] = effects[0][2];
    int id = vt_builder_add_body(b, &thigh);
    vt_body_def crank = vt_default_body_def();
    crank.parent = 1;
    crank.mass = mass[1];
    rod_x_inertia(crank.inertia, mass[1], VT_KN_A, 0.01);
    crank.joint_parent[0] = -0.5 * VT_KN_D; /* the hip, on the thigh */
    crank.joint_child[0] = -0.5 * VT_KN_A;
    crank.name = "crank";
    if (effects) crank.armature[0] = effects[1][0], crank.damping[0] = effects[1][1], crank.friction[0] = effects[1][2];
    if (id > 0) id = vt_builder_add_body(b, &crank);
    vt_body_def coupler = vt_default_body_def(); /* revolute about z at the crank's tip */
    coupler.parent = 2;
    coupler.mass = mass[2];
    rod_x_inertia(coupler.inertia, mass[2], VT_KN_B, 0.01);
    coupler.joint_parent[0] = 0.5 * VT_KN_A;
    coupler.joint_child[0] = -0.5 * VT_KN_B;
    coupler.name = "coupler";
    if (effects) coupler.armature[0] = effects[2][0], coupler.damping[0] = effects[2][1], coupler.friction[0] = effects[2][2];
    if (id > 0) id = vt_builder_add_body(b, &coupler);
    vt_body_def shank = vt_default_body_def();
    shank.parent = 1;
    shank.mass = mass[3];
    rod_x_inertia(shank.inertia, mass[3], ls, 0.01);
    shank.joint_parent[0] = 0.5 * VT_KN_D; /* the knee, on the thigh */
    shank.joint_child[0] = -cs;
    shank.name = "shank";
    if (effects) shank.armature[0] = effects[3][0], shank.damping[0] = effects[3][1], shank.friction[0] = effects[3][2];
    if (id > 0) id = vt_builder_add_body(b, &shank);
    if (id > 0) {
        /* a revolute about z (the shank's z): planar, its 2 in-plane rows, which with the 2
         * drives make 4 independent rows on the 4 rates; else all 5 rows, 3 of them dependent */
        vt_cut_joint_def cut = vt_default_cut_joint_def();
        cut.planar = planar;
        cut.body_a = 4;
        cut.body_b = 3;
        cut.point_a[0] = -cs - VT_KN_C; /* the lever point */
        cut.point_b[0] = 0.5 * VT_KN_B;
        cut.name = "lever";
        id = vt_builder_add_cut_joint(b, &cut);
    }
    for (int k = 0; k < 2 && id >= 0; k++) {
        if (!(drives & (1 << k))) continue;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = 1 + k;
        dr.f = k ? motor : hip;
        dr.name = k ? "motor" : "hip";
        id = vt_builder_add_drive(b, &dr);
    }
    return finish(model, b, id < 0 ? (vt_status)id : VT_OK);
}

vt_status vt_scene_knee(vt_model **model, vt_function hip, vt_function motor, int planar)
{
    static const double mass[4] = {1.5, 0.1, 0.08, 0.5};
    return vt_scene_knee_with(model, hip, motor, planar, mass, 3, NULL);
}

int vt_scene_knee_assemble(const vt_model *m, vt_data *d, double th1, double w1, double thm, double wm, double knee[2])
{
    /* in the thigh's frame: hip O = 0, knee K = (D, 0), crank tip B = A (cos θm, sin θm), lever
     * point C = K + C (cos ψ, sin ψ) with |C − B| = B_len: C on both circles */
    const double Bx = VT_KN_A * cos(thm), By = VT_KN_A * sin(thm);
    const double ex = VT_KN_D - Bx, ey = -By, L = sqrt(ex * ex + ey * ey);
    if (L == 0.0) return -1;
    const double x = (L * L + VT_KN_B * VT_KN_B - VT_KN_C * VT_KN_C) / (2.0 * L), h2 = VT_KN_B * VT_KN_B - x * x;
    if (h2 < 0.0) return -1;
    const double h = sqrt(h2), ux = ex / L, uy = ey / L;
    double psi = 0.0, best = HUGE_VAL;
    for (int s = -1; s <= 1; s += 2) { /* the branch with ψ nearest θm */
        const double Cx = Bx + x * ux - s * h * uy, Cy = By + x * uy + s * h * ux;
        const double p = atan2(Cy, Cx - VT_KN_D), dd = fabs(remainder(p - thm, 2.0 * VT_PI));
        if (dd < best) { best = dd; psi = p; }
    }
    const double Cx = VT_KN_D + VT_KN_C * cos(psi), Cy = VT_KN_C * sin(psi);
    const double phi = atan2(Cy - By, Cx - Bx); /* the coupler's angle from the thigh */
    /* rates: A θm' k×e(θm) + B φ' k×e(φ) = C ψ' k×e(ψ) */
    const double a11 = -VT_KN_B * sin(phi), a12 = VT_KN_C * sin(psi);
    const double a21 = VT_KN_B * cos(phi), a22 = -VT_KN_C * cos(psi);
    const double r1 = VT_KN_A * wm * sin(thm), r2 = -VT_KN_A * wm * cos(thm);
    const double det = a11 * a22 - a12 * a21;
    if (det == 0.0) return -1;
    const double phid = (r1 * a22 - a12 * r2) / det, psid = (a11 * r2 - a21 * r1) / det;
    d->q[m->body_qadr[1]] = th1;
    d->q[m->body_qadr[2]] = thm;
    d->q[m->body_qadr[3]] = phi - thm;
    d->q[m->body_qadr[4]] = remainder(psi - VT_PI, 2.0 * VT_PI); /* the shank points away from the lever */
    d->qd[m->body_vadr[1]] = w1;
    d->qd[m->body_vadr[2]] = wm;
    d->qd[m->body_vadr[3]] = phid - wm;
    d->qd[m->body_vadr[4]] = psid;
    if (knee) {
        knee[0] = d->q[m->body_qadr[4]];
        knee[1] = psid;
    }
    return 0;
}

double vt_scene_energy_rate(const vt_model *m, const vt_data *d)
{
    double P = 0.0;
    for (int b = 1; b <= m->nbody; b++) {
        const double *v = d->xd + 7 * (b - 1), *a = d->xdd + 7 * (b - 1), *A = d->A + 9 * b;
        const double *w = d->omega + 3 * b, *wd = d->alpha + 3 * b, *J = m->body_inertia + 9 * b;
        const double mass = m->body_mass[b];
        double wb[3], Jb[3];
        for (int k = 0; k < 3; k++) wb[k] = A[3 * k] * wd[0] + A[3 * k + 1] * wd[1] + A[3 * k + 2] * wd[2];
        for (int k = 0; k < 3; k++) Jb[k] = J[k] * wb[0] + J[k + 3] * wb[1] + J[k + 6] * wb[2];
        for (int k = 0; k < 3; k++) {
            const double Jg = A[k] * Jb[0] + A[k + 3] * Jb[1] + A[k + 6] * Jb[2];
            P += mass * v[k] * a[k] + w[k] * Jg - mass * m->gravity[k] * v[k];
        }
    }
    return P;
}
