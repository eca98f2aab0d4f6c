/* The library's own time per row on the states `vtdyn inverse` reads (bench/bench_command.sh):
 * the URDF loaded as the command loads it (recursive layout, mimic joints independent, the root
 * fixed, or floating with --floating: a free joint whose 19 columns R_x ... R_alz are read as the
 * command reads them, the quaternion divided by its norm), the rows of a .npy file of states written by bench/command_states.py laid out as q, q̇,
 * q̈ arrays, and vt_batch_inverse_dynamics_motion on all of them with the outputs the command
 * writes by default (every rate's effort, the reactions in world axes and in the joints' frames),
 * on THREADS threads. Prints the median over ROUNDS calls of the time per row, µs. With --all,
 * every output Python's Model.inverse writes by default instead (efforts; reactions and totals in
 * world and body axes; the joint frames' reactions, the bearing split, the limits' excess, the
 * effort's parts, q̈ and the drives' efforts: bench/bench_python.py's C row for the same work). The output arrays are the
 * same every call (the first call's page faults are not in the median).
 *
 *   command_lib URDF STATES.npy THREADS [ROUNDS] [--floating] [--all]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vtdyn.h"

#include "timing.h"

static int fail(const char *what)
{
    fprintf(stderr, "command_lib: %s\n", what);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: command_lib URDF STATES.npy THREADS [ROUNDS] [--floating] [--all]\n");
        return 2;
    }
    const int threads = atoi(argv[3]), rounds = argc > 4 && atoi(argv[4]) > 0 ? atoi(argv[4]) : 5;
    /* the .npy file of command_states.py: format 1.0, the fields' names and the shape in its header */
    FILE *f = fopen(argv[2], "rb");
    unsigned char pre[10];
    if (!f || fread(pre, 1, 10, f) != 10 || memcmp(pre, "\x93NUMPY\x01", 7) != 0) return fail("not a .npy file of format 1.0");
    const size_t hlen = (size_t)pre[8] | (size_t)pre[9] << 8;
    char *h = malloc(hlen + 1);
    if (!h || fread(h, 1, hlen, f) != hlen) return fail("a short header");
    h[hlen] = '\0';
    char *names[4096];
    int ncol = 0;
    const char *shape = strstr(h, "'shape': (");
    if (!shape) return fail("no shape");
    const long nrow = strtol(shape + 10, NULL, 10);
    for (char *p = h; (p = strstr(p, "('")) && ncol < 4096;) {
        char *e = strchr(p + 2, '\'');
        if (!e) break;
        *e = '\0';
        names[ncol++] = p + 2;
        p = e + 1;
    }
    double *cells = malloc((size_t)nrow * (size_t)ncol * sizeof *cells);
    if (!cells || fread(cells, sizeof *cells, (size_t)nrow * (size_t)ncol, f) != (size_t)nrow * (size_t)ncol)
        return fail("short data");
    fclose(f);
    /* the robot as the command loads it */
    vt_builder *b;
    vt_model *m;
    char msg[VT_MESSAGE_SIZE];
    vt_urdf_options opt = vt_default_urdf_options();
    opt.mimic = 0;
    int all = 0;
    for (int k = 5; k < argc; k++) {
        if (strcmp(argv[k], "--floating") == 0) opt.floating = 1;
        else if (strcmp(argv[k], "--all") == 0) all = 1;
        else return fail("an unknown option (--floating, --all)");
    }
    opt.model.layout = VT_LAYOUT_RECURSIVE;
    if (vt_urdf_builder(&b, argv[1], &opt, msg) || vt_builder_build(&m, b)) return fail("the URDF");
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody;
    double *q = calloc((size_t)nrow * nq, sizeof *q), *qd = calloc((size_t)nrow * nv, sizeof *qd),
           *qdd = calloc((size_t)nrow * nv, sizeof *qdd), *effort = malloc((size_t)nrow * nv * sizeof *effort),
           *reac = malloc((size_t)nrow * nb6 * sizeof *reac), *reacb = malloc((size_t)nrow * nb6 * sizeof *reacb);
    int *status = malloc((size_t)nrow * sizeof *status);
    if (!q || !qd || !qdd || !effort || !reac || !reacb || !status) return fail("out of memory");
    static const char *const free_suffix[19] = {"x",  "y",  "z",  "qw", "qx", "qy", "qz", "vx",  "vy",  "vz",
                                                "wx", "wy", "wz", "ax", "ay", "az", "alx", "aly", "alz"};
    for (int i = 1; i <= m->nbody; i++) {
        const char *jn = m->joint_name + VT_NAME_MAX * i;
        if (!jn[0]) jn = m->body_name + VT_NAME_MAX * i; /* an implicit root joint: the link's name */
        const size_t qa = (size_t)m->body_qadr[i], va = (size_t)m->body_vadr[i];
        if (m->body_joint[i] == VT_JOINT_FREE) { /* R_x ... R_qz, R_vx ... R_wz, R_ax ... R_alz */
            int c[19];
            for (int k = 0; k < 19; k++) {
                char key[VT_NAME_MAX + 8];
                snprintf(key, sizeof key, "%s_%s", jn, free_suffix[k]);
                c[k] = -1;
                for (int h = 0; h < ncol; h++)
                    if (strcmp(names[h], key) == 0) c[k] = h;
                if (c[k] < 0) return fail("a floating root's columns (run with --floating)");
            }
            for (long r = 0; r < nrow; r++) {
                const double *cell = cells + (size_t)r * (size_t)ncol;
                double *qr = q + (size_t)r * nq + qa, nrm = 0.0;
                for (int k = 3; k < 7; k++) nrm += cell[c[k]] * cell[c[k]];
                nrm = sqrt(nrm);
                for (int k = 0; k < 7; k++) qr[k] = k < 3 ? cell[c[k]] : cell[c[k]] / nrm;
                for (int k = 0; k < 6; k++) {
                    qd[(size_t)r * nv + va + (size_t)k] = cell[c[7 + k]];
                    qdd[(size_t)r * nv + va + (size_t)k] = cell[c[13 + k]];
                }
            }
            continue;
        }
        /* one-rate joints: J, J_vel, J_acc */
        char vel[VT_NAME_MAX + 8], acc[VT_NAME_MAX + 8];
        snprintf(vel, sizeof vel, "%s_vel", jn);
        snprintf(acc, sizeof acc, "%s_acc", jn);
        int c[3] = {-1, -1, -1};
        for (int k = 0; k < ncol; k++) {
            if (strcmp(names[k], jn) == 0) c[0] = k;
            if (strcmp(names[k], vel) == 0) c[1] = k;
            if (strcmp(names[k], acc) == 0) c[2] = k;
        }
        if (m->body_nv[i] != 1 || c[0] < 0 || c[1] < 0 || c[2] < 0) return fail("a joint's columns");
        for (long r = 0; r < nrow; r++) {
            q[(size_t)r * nq + qa] = cells[(size_t)r * (size_t)ncol + (size_t)c[0]];
            qd[(size_t)r * nv + va] = cells[(size_t)r * (size_t)ncol + (size_t)c[1]];
            qdd[(size_t)r * nv + va] = cells[(size_t)r * (size_t)ncol + (size_t)c[2]];
        }
    }
    vt_batch *batch;
    vt_batch_def def = vt_default_batch_def();
    def.threads = threads;
    if (vt_batch_create(&batch, m, &def)) return fail("the batch");
    vt_batch_io io = {0};
    io.nrow = (int)nrow;
    io.q = q;
    io.qd = qd;
    io.qdd = qdd;
    io.effort = effort;
    io.reaction = reac;
    io.reaction_joint = reacb;
    io.status = status;
    if (all) { /* Model.inverse's default: every output */
        const size_t rows = (size_t)nrow;
        double *more[8];
        const size_t len[8] = {nb6, nb6, nb6, 4 * (size_t)m->nbody, 3 * nv, 3 * nv, nv, (size_t)m->ndrive + 1};
        for (int k = 0; k < 8; k++)
            if (!(more[k] = malloc(rows * len[k] * sizeof(double)))) return fail("out of memory");
        io.reaction_body = more[0];
        io.total = more[1];
        io.total_body = more[2];
        io.bearing = more[3];
        io.limit_excess = more[4];
        io.effort_parts = more[5];
        io.qdd_out = more[6];
        io.drive_effort = more[7];
    }
    double t[201];
    const int n = rounds < 201 ? rounds : 201;
    for (int k = 0; k < n; k++) {
        const double t0 = now();
        if (vt_batch_inverse_dynamics_motion(batch, &io)) return fail(vt_batch_message(batch));
        t[k] = now() - t0;
    }
    qsort(t, (size_t)n, sizeof *t, by_value);
    printf("%.4f\n", 1e6 * t[n / 2] / (double)nrow);
    vt_batch_free(batch);
    vt_model_free(m);
    vt_builder_free(b);
    return 0;
}
