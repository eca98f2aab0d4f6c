/* Scale: bytes and time per body of a spatial revolute chain from n = 10 to 100,000 links.
 *
 * The chain of vt_scene_chain (0.5 m links, 1 kg, axes cycling x, y, z, its reference state)
 * written as a URDF string, loaded (vt_urdf_builder_string), built and given its motion
 * (vt_inverse_dynamics_motion) on data laid out VT_LAYOUT_RECURSIVE; beside it the same chain
 * joint-driven from the builder (vt_scene_chain_layout), its instant by the fused passes
 * (vt_inverse_dynamics_recursive). For each n it prints the URDF's bytes, the load and build
 * times, vt_data_size() per body, and the median time per body of each instant over 41 rounds
 * (each round a batch of calls of about 2 ms; the range of the rounds beside the median). Then
 * the exponent of vt_data_size() in n from the first row to the last (1 for memory linear in n)
 * and each instant's time per body at the last n relative to n = 1000.
 *
 *     build-bench/bench/bench_scale [largest n]      (default 100000)
 *
 * Prints the date, the CPU and the command first; writes nothing else.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <vtdyn.h>

#include "cpuinfo.h"
#include "timing.h"
#include "scenes.h"

#define ROUNDS 41

/* The chain as URDF: link k's frame at its joint, its centre 0.25 m along its x, joint k + 1
 * 0.5 m along it; joint k about x, y, z in turn (vt_scene_chain's geometry and inertias). */
static char *chain_urdf(int n, size_t *len)
{
    const size_t cap = 512 + (size_t)n * 640;
    char *s = malloc(cap);
    if (!s) return NULL;
    size_t k = (size_t)snprintf(s, cap, "<robot name=\"chain\">\n<link name=\"base\"/>\n");
    static const char *const axes[3] = {"1 0 0", "0 1 0", "0 0 1"};
    for (int i = 1; i <= n; i++) {
        char parent[24] = "base";
        if (i > 1) snprintf(parent, sizeof parent, "l%d", i - 1);
        k += (size_t)snprintf(s + k, cap - k,
                              "<link name=\"l%d\"><inertial><origin xyz=\"0.25 0 0\"/><mass value=\"1\"/>"
                              "<inertia ixx=\"2e-4\" ixy=\"0\" ixz=\"0\" iyy=\"0.020833333333333332\" iyz=\"0\" "
                              "izz=\"0.020833333333333332\"/></inertial></link>\n"
                              "<joint name=\"j%d\" type=\"continuous\"><parent link=\"%s\"/><child link=\"l%d\"/>"
                              "<origin xyz=\"%s 0 0\"/><axis xyz=\"%s\"/></joint>\n",
                              i, i, parent, i, i > 1 ? "0.5" : "0", axes[(i - 1) % 3]);
    }
    k += (size_t)snprintf(s + k, cap - k, "</robot>\n");
    *len = k;
    return s;
}

typedef vt_status (*instant_fn)(const vt_model *, vt_data *);

/* median and range of ROUNDS rounds of the instant, in ns per body */
static void time_instant(instant_fn f, const vt_model *m, vt_data *d, double out[3])
{
    double t0 = now();
    long calls = 0;
    while (now() - t0 < 2e-3 || calls < 1) {
        if (f(m, d)) {
            fprintf(stderr, "bench_scale: %s\n", d->message);
            exit(1);
        }
        calls++;
    }
    double r[ROUNDS];
    for (int k = 0; k < ROUNDS; k++) {
        t0 = now();
        for (long c = 0; c < calls; c++) f(m, d);
        r[k] = (now() - t0) / (double)calls / m->nbody * 1e9;
    }
    qsort(r, ROUNDS, sizeof r[0], by_value);
    out[0] = r[ROUNDS / 2];
    out[1] = r[0];
    out[2] = r[ROUNDS - 1];
}

int main(int argc, char **argv)
{
    const int nmax = argc > 1 ? atoi(argv[1]) : 100000;
    time_t t = time(NULL);
    char date[64];
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&t));
    printf("bench_scale, %s, vtdyn %s\n", date, vt_version());
    vt_bench_cpu_line();
    printf("command: %s", argv[0]);
    for (int k = 1; k < argc; k++) printf(" %s", argv[k]);
    printf("\n\n%8s %11s %9s %9s %12s %22s %22s\n", "n", "URDF bytes", "load s", "build s", "data B/body",
           "motion ns/body (range)", "driven ns/body (range)");
    double n0 = 0.0, b0 = 0.0, n1 = 0.0, b1 = 0.0, at1000[2] = {0.0, 0.0}, last[2] = {0.0, 0.0};
    for (int n = 10; n <= nmax; n *= 10) {
        size_t len = 0;
        char *xml = chain_urdf(n, &len);
        if (!xml) break;
        char msg[VT_MESSAGE_SIZE] = "";
        vt_urdf_options o = vt_default_urdf_options();
        o.model.layout = VT_LAYOUT_RECURSIVE;
        o.model.gravity[1] = -9.81; /* vt_scene_chain's gravity: y down */
        o.model.gravity[2] = 0.0;
        vt_builder *b = NULL;
        vt_model *m = NULL;
        vt_data *d = NULL;
        double ta = now();
        vt_status st = vt_urdf_builder_string(&b, xml, &o, msg);
        const double tload = now() - ta;
        free(xml);
        if (st) {
            printf("%8d %11zu refused: %s (%s)\n", n, len, msg, vt_status_string(st));
            break;
        }
        ta = now();
        st = vt_builder_build(&m, b);
        const double tbuild = now() - ta;
        if (st || (st = vt_data_create(&d, m))) {
            printf("%8d %11zu refused: %s (%s)\n", n, len, vt_builder_message(b), vt_status_string(st));
            vt_builder_free(b);
            break;
        }
        vt_builder_free(b);
        for (int k = 0; k < m->nv; k++) vt_scene_chain_state(k, &d->q[k], &d->qd[k], &d->qdd[k]);
        double tm[3], tj[3];
        time_instant(vt_inverse_dynamics_motion, m, d, tm);
        const double bytes = (double)vt_data_size(m);
        vt_data_free(d);
        vt_model_free(m);
        /* the joint-driven chain from the builder */
        if ((st = vt_scene_chain_layout(&m, n, VT_CHAIN_JOINT_DRIVEN, VT_LAYOUT_RECURSIVE)) || (st = vt_data_create(&d, m))) {
            printf("%8d joint-driven chain refused (%s)\n", n, vt_status_string(st));
            break;
        }
        for (int k = 0; k < m->nv; k++) {
            double qdd;
            vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
        }
        time_instant(vt_inverse_dynamics_recursive, m, d, tj);
        vt_data_free(d);
        vt_model_free(m);
        printf("%8d %11zu %9.3f %9.3f %12.0f %8.1f (%5.1f-%5.1f) %8.1f (%5.1f-%5.1f)\n", n, len, tload, tbuild,
               bytes / n, tm[0], tm[1], tm[2], tj[0], tj[1], tj[2]);
        fflush(stdout);
        if (n0 == 0.0) n0 = n, b0 = bytes;
        n1 = n, b1 = bytes;
        if (n == 1000) at1000[0] = tm[0], at1000[1] = tj[0];
        last[0] = tm[0], last[1] = tj[0];
    }
    if (n1 > n0)
        printf("\ndata bytes ~ n^%.3f from n = %.0f to %.0f\n", log(b1 / b0) / log(n1 / n0), n0, n1);
    if (n1 > 1000 && at1000[0] > 0.0)
        printf("time per body at n = %.0f over n = 1000: motion %.2f, joint-driven %.2f\n", n1, last[0] / at1000[0],
               last[1] / at1000[1]);
    return 0;
}
