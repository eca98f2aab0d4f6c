/* vtdyn's answers for the knee four-bar of vt_scene_knee (examples/scenes.c: thigh, crank,
 * coupler, shank; the loop closed by a planar pin) with its masses spread over up to 11.5
 * orders (1e-6 … 3e5 kg, each link's inertia its rod's at that mass), for the high-precision
 * oracle tests/spread_oracle.py: fully driven (hip and knee motor), or partly (one drive
 * removed, its rate's q̈ from the dynamics), at two regular poses, one JSON line per path (dense
 * vt_inverse_dynamics, recursive) with the data the oracle needs (the masses, q, q̇, t, exact as
 * printed with 17 digits) and what vtdyn returns (status, route, warning, rcond, q̈, λ). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "vtdyn.h"
#include "scenes.h"

#define PI 3.14159265358979323846

static void rod(double J[9], double mass, double length, double radius)
{
    memset(J, 0, 9 * sizeof(double));
    J[0] = 0.5 * mass * radius * radius;
    J[4] = J[8] = mass * (3.0 * radius * radius + length * length) / 12.0;
}

/* vt_scene_knee (planar pin) with the links' masses mass[4] and drives a mask: 1 the hip, 2 the
 * knee motor */
static vt_status knee(vt_model **model, const double mass[4], int drives, vt_function hip, vt_function motor)
{
    vt_builder *b;
    vt_status st = vt_builder_create(&b, NULL);
    if (st) return st;
    const double ls = VT_KN_C + VT_KN_L, cs = 0.5 * ls - VT_KN_C;
    vt_body_def t = vt_default_body_def();
    t.mass = mass[0]; rod(t.inertia, mass[0], VT_KN_D, 0.01); t.joint_child[0] = -0.5 * VT_KN_D;
    int id = vt_builder_add_body(b, &t);
    vt_body_def c = vt_default_body_def();
    c.parent = 1; c.mass = mass[1]; rod(c.inertia, mass[1], VT_KN_A, 0.01);
    c.joint_parent[0] = -0.5 * VT_KN_D; c.joint_child[0] = -0.5 * VT_KN_A;
    if (id > 0) id = vt_builder_add_body(b, &c);
    vt_body_def u = vt_default_body_def();
    u.parent = 2; u.mass = mass[2]; rod(u.inertia, mass[2], VT_KN_B, 0.01);
    u.joint_parent[0] = 0.5 * VT_KN_A; u.joint_child[0] = -0.5 * VT_KN_B;
    if (id > 0) id = vt_builder_add_body(b, &u);
    vt_body_def s = vt_default_body_def();
    s.parent = 1; s.mass = mass[3]; rod(s.inertia, mass[3], ls, 0.01);
    s.joint_parent[0] = 0.5 * VT_KN_D; s.joint_child[0] = -cs;
    if (id > 0) id = vt_builder_add_body(b, &s);
    if (id > 0) {
        vt_cut_joint_def cut = vt_default_cut_joint_def();
        cut.planar = 1; cut.body_a = 4; cut.body_b = 3;
        cut.point_a[0] = -cs - VT_KN_C; cut.point_b[0] = 0.5 * VT_KN_B;
        id = vt_builder_add_cut_joint(b, &cut);
    }
    for (int k = 0; k < 2 && id >= 0; k++) {
        if (!(drives & (1 << k))) continue;
        vt_drive_def dr = vt_default_drive_def();
        dr.body = 1 + k; dr.f = k ? motor : hip;
        id = vt_builder_add_drive(b, &dr);
    }
    if (id < 0) st = (vt_status)id;
    if (st == VT_OK) st = vt_builder_build(model, b);
    vt_builder_free(b);
    return st;
}

static void list(const char *name, const double *v, int n)
{
    printf(", \"%s\": [", name);
    for (int i = 0; i < n; i++) printf("%s%.17g", i ? ", " : "", v[i]);
    printf("]");
}

int main(void)
{
    /* thigh, crank, coupler, shank (kg); the 7th the scene's own */
    static const double dist[][4] = {
        {3e5, 1e-6, 1e-3, 1.0}, {1e-6, 3e5, 1.0, 1e-3}, {1.0, 1e-6, 3e5, 1e-3}, {1e-6, 1e-3, 1.0, 3e5},
        {3e5, 1.0, 1e-3, 1e-6}, {1e-6, 1.0, 1e-3, 3e5}, {1.5, 0.1, 0.08, 0.5}, {3e5, 1e-6, 1e-6, 1e-6},
        {1e-6, 3e5, 3e5, 3e5}, {3e5, 1e-3, 1e-6, 1.0}, {1e-3, 1e-6, 3e5, 1.0}, {1.0, 3e5, 1e-6, 1e-3},
    };
    const double om = 2.0, tt = 0.3;
    for (int di = 0; di < (int)(sizeof dist / sizeof dist[0]); di++)
        for (int drives = 1; drives <= 3; drives++)
            for (int pose = 0; pose < 2; pose++) {
                const double ph = 0.9 * pose;
                vt_function hip = vt_function_sine(-0.25 * PI, 0.35, om, ph), motor = vt_function_sine(0.5 * PI, 0.4, om, 0.8 + ph);
                vt_model *m;
                if (knee(&m, dist[di], drives, hip, motor)) return 1;
                for (int path = 0; path < 2; path++) {
                    vt_data *d;
                    if (vt_data_create(&d, m)) return 1;
                    const double th1 = -0.25 * PI + 0.35 * sin(om * tt + ph), w1 = 0.35 * om * cos(om * tt + ph);
                    const double thm = 0.5 * PI + 0.4 * sin(om * tt + 0.8 + ph), wm = 0.4 * om * cos(om * tt + 0.8 + ph);
                    if (vt_scene_knee_assemble(m, d, th1, w1, thm, wm, NULL)) return 2;
                    d->time = tt;
                    const vt_status st = path ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
                    printf("{\"dist\": %d, \"drives\": %d, \"pose\": %d, \"path\": %d, \"status\": %d, \"route\": %d, \"fallback\": %d, \"warning\": %d, \"rcond\": %.17g, \"time\": %.17g, \"nc\": %d",
                           di, drives, pose, path, (int)st, (int)d->route, (int)d->fallback, d->warning, d->rcond, d->time, m->nc);
                    list("mass", dist[di], 4);
                    list("q", d->q, 4);
                    list("qd", d->qd, 4);
                    list("qdd", d->qdd, 4);
                    list("lambda", d->lambda, m->nc);
                    printf("}\n");
                    vt_data_free(d);
                }
                vt_model_free(m);
            }
    return 0;
}
