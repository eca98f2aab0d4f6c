/* A design sweep of the paper's five-link arm (Figs. 9-10): how large must its motors and joint
 * bearings be, for the payload it carries at the tip and the time it takes to draw its circle?
 *
 * For every point of a grid payload mass × cycle time (vt_scene_five_link_payload(): a point
 * mass at the tip, the drives' period), one cycle sampled at t_k = k T / nsample,
 * k = 0 .. nsample − 1: at each instant vt_kinematic_solve() (Newton on the five point drives,
 * then (5)) gives the joint torques Φ_q^T λ that produce the motion. The joint reactions are
 * those of the arm driven by those torques — the model without drives, the torques applied as
 * generalized forces (vt_inverse_dynamics() on vt_model_without_drives(), the same q̈) — and
 * not those with the point drives' forces applied at the tip by the ground, which no real arm
 * has. Per grid point: the peak |τ_j| and the peak reaction force |f_j| of each joint over the
 * cycle, and the status (0, or the vt_status of the first failing instant: its row is NaN).
 *
 * Writes CSV, one row per grid point, payloads outer, periods inner:
 *   payload_kg, period_s, tau1_max_Nm .. tau5_max_Nm, f1_max_N .. f5_max_N, status
 *
 * With MPI (built with VT_HAVE_MPI, run under mpirun) the grid is cut into one contiguous
 * block per rank and the rows are gathered to rank 0, which writes the file; every grid point
 * starts afresh from the same guess, so the file is byte-identical for any number of ranks and
 * to the program built without MPI (tests/sweep_mpi.sh checks it). When stderr is a terminal,
 * and the sweep lasts over half a second, rank 0 shows its progress there on one line (\r);
 * -v shows it anyway (mpirun hands the ranks pipes, not the terminal).
 *
 * Usage: sweep [-m NPAYLOAD] [-M MAX_KG] [-p NPERIOD] [-t MIN_S,MAX_S] [-s NSAMPLE] [-o OUT.csv] [-v]
 *   defaults: 21 payloads in [0, 2] kg, 16 cycle times in [0.5, 2] s, 360 samples a cycle,
 *   sweep.csv (336 grid points, 121 000 instants: about 2 s on one core)
 * Exit status 0, 1 when a grid point failed (its row says which status), 2 on bad arguments.
 */
#define _POSIX_C_SOURCE 200809L /* isatty */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "scenes.h"

#ifdef VT_HAVE_MPI
#include <mpi.h>
#endif

#define NJ 5                  /* joints of the arm */
#define NCOL (2 + 2 * NJ + 1) /* payload, period, peaks of τ and f, status */

typedef struct grid {
    int npay, nper, nsample;
    double pay_max, per_min, per_max;
} grid;

static double grid_payload(const grid *g, int k)
{
    const int i = k / g->nper;
    return g->npay > 1 ? g->pay_max * i / (g->npay - 1) : 0.0;
}

static double grid_period(const grid *g, int k)
{
    const int j = k % g->nper;
    return g->nper > 1 ? g->per_min + (g->per_max - g->per_min) * j / (g->nper - 1) : g->per_min;
}

/* one grid point: row = [payload, period, τ peaks, f peaks, status]; message for a failure */
static vt_status run_point(double *row, double payload, double period, int nsample, char *msg, size_t nmsg)
{
    vt_model *m = NULL, *mf = NULL;
    vt_data *d = NULL, *df = NULL;
    row[0] = payload;
    row[1] = period;
    for (int c = 2; c < NCOL; c++) row[c] = 0.0;
    msg[0] = '\0';
    vt_status st = vt_scene_five_link_payload(&m, payload, period);
    if (!st) st = vt_model_without_drives(&mf, m);
    if (!st) st = vt_data_create(&d, m);
    if (!st) st = vt_data_create(&df, mf);
    if (!st) vt_scene_five_link_guess(m, d, 0.0); /* a start for Newton; then each instant from the last */
    for (int k = 0; k < nsample && !st; k++) {
        const double t = period * k / nsample;
        d->time = t;
        st = vt_kinematic_solve(m, d, 1e-12, 30);
        if (st) {
            snprintf(msg, nmsg, "t = %g s: %s: %s", t, vt_status_string(st), d->message);
            break;
        }
        /* the arm driven by its joint torques: the same q, q̇, and Φ_q^T λ as applied torques */
        memcpy(df->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(df->qd, d->qd, (size_t)m->nv * sizeof(double));
        memcpy(df->qfrc, d->qfrc_drive, (size_t)m->nv * sizeof(double));
        df->time = t;
        st = vt_inverse_dynamics(mf, df);
        if (st) {
            snprintf(msg, nmsg, "t = %g s, torque-driven arm: %s: %s", t, vt_status_string(st), df->message);
            break;
        }
        for (int j = 0; j < NJ; j++) {
            const double *f = df->jnt_force + 3 * (j + 1);
            row[2 + j] = fmax(row[2 + j], fabs(d->qfrc_drive[j]));
            row[2 + NJ + j] = fmax(row[2 + NJ + j], sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
        }
    }
    if (st) {
        if (!msg[0]) snprintf(msg, nmsg, "%s", vt_status_string(st)); /* building the models */
        for (int c = 2; c < NCOL - 1; c++) row[c] = NAN;
    }
    row[NCOL - 1] = (double)st;
    vt_data_free(df);
    vt_data_free(d);
    vt_model_free(mf);
    vt_model_free(m);
    return st;
}

static int usage(int rank)
{
    if (rank == 0)
        fprintf(stderr, "usage: sweep [-m NPAYLOAD] [-M MAX_KG] [-p NPERIOD] [-t MIN_S,MAX_S] [-s NSAMPLE] [-o OUT.csv] [-v]\n"
                        "  defaults: -m 21 -M 2 -p 16 -t 0.5,2 -s 360 -o sweep.csv\n");
    return 2;
}

/* parses the command line into g, *path and *verbose; 0, or 2 after printing the usage */
static int parse(int argc, char **argv, grid *g, const char **path, int *verbose, int rank)
{
    for (int a = 1; a < argc; a++) {
        const char *o = argv[a];
        if (strcmp(o, "-v") == 0) {
            *verbose = 1;
            continue;
        }
        if (strlen(o) != 2 || o[0] != '-' || a + 1 >= argc) return usage(rank);
        const char *v = argv[++a];
        char *end;
        if (o[1] == 'o') {
            *path = v;
            continue;
        }
        switch (o[1]) {
        case 'm': g->npay = (int)strtol(v, &end, 10); break;
        case 'p': g->nper = (int)strtol(v, &end, 10); break;
        case 's': g->nsample = (int)strtol(v, &end, 10); break;
        case 'M': g->pay_max = strtod(v, &end); break;
        case 't':
            g->per_min = strtod(v, &end);
            if (*end != ',') return usage(rank);
            g->per_max = strtod(end + 1, &end);
            break;
        default: return usage(rank);
        }
        if (*end != '\0') return usage(rank);
    }
    if (g->npay < 1 || g->nper < 1 || g->nsample < 1 || !(g->pay_max >= 0.0) || !(g->per_min > 0.0) ||
        !(g->per_max >= g->per_min) || !isfinite(g->pay_max) || !isfinite(g->per_max) ||
        (double)g->npay * g->nper > 1e8)
        return usage(rank);
    return 0;
}

int main(int argc, char **argv)
{
    int rank = 0, size = 1;
#ifdef VT_HAVE_MPI
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
#endif
    grid g = {21, 16, 360, 2.0, 0.5, 2.0};
    const char *path = "sweep.csv";
    int verbose = 0;
    int rc = parse(argc, argv, &g, &path, &verbose, rank);
    const int npoint = g.npay * g.nper;
    /* rank r: grid points [npoint r / size, npoint (r + 1) / size) */
    const int lo = (int)((long long)npoint * rank / size), hi = (int)((long long)npoint * (rank + 1) / size);
    double *res = rc ? NULL : calloc((size_t)npoint * NCOL, sizeof(double));
    if (!rc && !res) {
        fprintf(stderr, "sweep: out of memory\n");
        rc = 1;
    }
#ifdef VT_HAVE_MPI
    MPI_Allreduce(MPI_IN_PLACE, &rc, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD); /* all go on, or none */
#endif
    int nfail = 0;
    if (!rc) {
        const int progress = rank == 0 && (verbose || isatty(STDERR_FILENO));
        const clock_t start = clock();
        double shown = 0.0;
        for (int k = lo; k < hi; k++) {
            char msg[320];
            if (run_point(res + (size_t)k * NCOL, grid_payload(&g, k), grid_period(&g, k), g.nsample, msg, sizeof msg)) {
                fprintf(stderr, "%ssweep: payload %g kg, period %g s: %s\n", progress ? "\n" : "", grid_payload(&g, k),
                        grid_period(&g, k), msg);
                nfail++;
            }
            const double el = (double)(clock() - start) / CLOCKS_PER_SEC;
            /* long sweeps only (after half a second), at most five updates a second */
            if (progress && el > 0.5 && (el - shown > 0.2 || k + 1 == hi)) {
                fprintf(stderr, "\rsweep: %d/%d grid points%s, %.1f s", k + 1 - lo, hi - lo,
                        size > 1 ? " (rank 0's share)" : "", el);
                shown = el;
            }
        }
        if (progress && shown > 0.0) fputc('\n', stderr);
    }
#ifdef VT_HAVE_MPI
    if (!rc && size > 1) {
        int *count = malloc(2 * (size_t)size * sizeof(int)), *displ = count ? count + size : NULL;
        if (count) {
            for (int r = 0; r < size; r++) {
                const int a = (int)((long long)npoint * r / size), b = (int)((long long)npoint * (r + 1) / size);
                count[r] = (b - a) * NCOL;
                displ[r] = a * NCOL;
            }
        }
        double *mine = res + (size_t)lo * NCOL;
        MPI_Gatherv(rank == 0 ? MPI_IN_PLACE : mine, (hi - lo) * NCOL, MPI_DOUBLE, res, count, displ, MPI_DOUBLE, 0,
                    MPI_COMM_WORLD);
        free(count);
        int total = 0;
        MPI_Reduce(&nfail, &total, 1, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
        nfail = total;
    }
#endif
    if (!rc && rank == 0) {
        FILE *f = fopen(path, "w");
        if (!f) {
            perror(path);
            rc = 1;
        } else {
            fprintf(f, "payload_kg,period_s");
            for (int j = 1; j <= NJ; j++) fprintf(f, ",tau%d_max_Nm", j);
            for (int j = 1; j <= NJ; j++) fprintf(f, ",f%d_max_N", j);
            fprintf(f, ",status\n");
            for (int k = 0; k < npoint; k++) {
                const double *row = res + (size_t)k * NCOL;
                fprintf(f, "%.6g,%.6g", row[0], row[1]);
                for (int c = 2; c < NCOL - 1; c++) fprintf(f, ",%.15g", row[c]);
                fprintf(f, ",%d\n", (int)row[NCOL - 1]);
            }
            if (fclose(f) != 0) {
                perror(path);
                rc = 1;
            }
        }
        if (!rc) {
            printf("sweep: %d grid points (%d payloads in [0, %g] kg x %d cycle times in [%g, %g] s), %d samples a cycle, "
                   "%d rank%s -> %s\n",
                   npoint, g.npay, g.pay_max, g.nper, g.per_min, g.per_max, g.nsample, size, size > 1 ? "s" : "", path);
            if (nfail) printf("sweep: %d grid points failed (status column)\n", nfail);
        }
        if (!rc && nfail) rc = 1;
    }
    free(res);
#ifdef VT_HAVE_MPI
    MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Finalize();
#endif
    return rc;
}
