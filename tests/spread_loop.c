/* vtdyn's answers for the knee four-bar of vt_scene_knee_with (examples/scenes.c: thigh, crank,
 * coupler, shank; the loop closed by a planar pin) with its masses spread over up to 11.5
 * orders (1e-6 … 3e5 kg, each link's inertia its rod's at that mass), for the high-precision
 * oracle tests/spread_oracle.py: fully driven (hip and knee motor), or partly (one drive
 * removed, its rate's q̈ from the dynamics), at two regular poses, one JSON line per path (dense
 * vt_inverse_dynamics, recursive) with the data the oracle needs (the masses, q, q̇, t, exact as
 * printed with 17 digits) and what vtdyn returns (status, route, warning, rcond, q̈, λ). */
#include <math.h>
#include <stdio.h>
#include "vtdyn.h"
#include "scenes.h"

#define PI 3.14159265358979323846

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
                if (vt_scene_knee_with(&m, hip, motor, 1, dist[di], drives, NULL)) return 1;
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
