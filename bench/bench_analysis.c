/* Speed of the time layer: a kinematic analysis of the paper's five-link arm per output
 * instant, against one inverse-dynamics instant of the same arm.
 *
 * Methods, all in this one process, timed in alternating batches:
 *   recursive   vt_inverse_dynamics_recursive at the arm's consistent state at t = 0.1 (the instant)
 *   dense       vt_inverse_dynamics at the same state (the reference path's instant)
 *   analysis    vt_kinematic_analysis, t in [0, 1], 100 output intervals, forward check off,
 *               from the same start every call; its time divided by the 101 rows
 *   checked     the same with the forward check (the default options: IDA rtol 1e-8, atol 1e-10)
 * Every method of a round runs a batch sized to take about 3 ms, the order reversed every
 * other round, so that the machine's slow stretches hit them alike; a method's figure is the
 * median over the rounds of µs per call (per output row for the analyses), and the ratios
 * analysis / recursive, checked / recursive and (checked − analysis) / recursive (the forward
 * check's own cost per output instant) are the medians of the rounds' ratios, with their range.
 * Prints the CPU (from /proc/cpuinfo), the forward check's IDA counts, and writes
 * <outdir>/analysis_speed.csv (quantity, median, min, max).
 * Usage: bench_analysis [outdir] [rounds]       (41 rounds by default, at most 201)
 *        bench_analysis --once analysis|checked|recursive [calls]   one kind only, for callgrind
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes.h"

#define MAX_ROUNDS 201
#define NOUT 100

enum { M_RECURSIVE, M_DENSE, M_ANALYSIS, M_CHECKED, NMETHOD };
static const char *names[NMETHOD] = {"recursive", "dense", "analysis", "checked"};

typedef struct {
    vt_model *m;
    vt_data *d, *di;     /* the analyses' data, the instants' data */
    vt_trajectory *tr;
    double q0[5];        /* the analyses' start: the arm's guess at t = 0 */
} bench;

static void die(const char *what, const vt_data *d, vt_status st)
{
    fprintf(stderr, "bench_analysis: %s: %s: %s\n", what, vt_status_string(st), d ? d->message : "");
    exit(1);
}

static void run(bench *b, int method)
{
    vt_status st;
    if (method == M_RECURSIVE || method == M_DENSE) {
        st = method == M_RECURSIVE ? vt_inverse_dynamics_recursive(b->m, b->di) : vt_inverse_dynamics(b->m, b->di);
        if (st) die(names[method], b->di, st);
        return;
    }
    vt_run_options opt = vt_default_run_options();
    opt.nout = NOUT;
    opt.forward_check = method == M_CHECKED;
    memcpy(b->d->q, b->q0, sizeof b->q0);
    memset(b->d->qd, 0, sizeof b->q0);
    if ((st = vt_kinematic_analysis(b->m, b->d, &opt, b->tr))) die(names[method], b->d, st);
}

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec * 1e-3;
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median_of(double *a, int n)
{
    qsort(a, (size_t)n, sizeof(double), cmp);
    return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

/* median, smallest and largest of n values (a is sorted) */
static void summary(double *a, int n, double out[3])
{
    out[0] = median_of(a, n);
    out[1] = a[0];
    out[2] = a[n - 1];
}

static void cpu_name(char *buf, size_t size)
{
    snprintf(buf, size, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof line, f))
        if (strncmp(line, "model name", 10) == 0) {
            const char *c = strchr(line, ':');
            if (c) {
                c++;
                while (*c == ' ') c++;
                snprintf(buf, size, "%s", c);
                buf[strcspn(buf, "\n")] = '\0';
            }
            break;
        }
    fclose(f);
}

static void setup(bench *b)
{
    vt_status st;
    if ((st = vt_scene_five_link(&b->m))) die("five-link arm", NULL, st);
    if ((st = vt_data_create(&b->d, b->m)) || (st = vt_data_create(&b->di, b->m)) ||
        (st = vt_trajectory_create(&b->tr, b->m, NOUT + 1)))
        die("allocation", NULL, st);
    vt_scene_five_link_guess(b->m, b->d, 0.0);
    memcpy(b->q0, b->d->q, sizeof b->q0);
    vt_scene_five_link_guess(b->m, b->di, 0.1);
    b->di->time = 0.1;
    if ((st = vt_kinematic_solve(b->m, b->di, 1e-13, 30))) die("the instant's state", b->di, st);
}

int main(int argc, char **argv)
{
    bench b;
    setup(&b);
    if (argc > 1 && strcmp(argv[1], "--once") == 0) { /* one kind, for callgrind */
        int method = -1;
        for (int k = 0; k < NMETHOD; k++)
            if (argc > 2 && strcmp(argv[2], names[k]) == 0) method = k;
        if (method < 0) {
            fprintf(stderr, "usage: bench_analysis --once recursive|dense|analysis|checked [calls]\n");
            return 1;
        }
        const int calls = argc > 3 ? atoi(argv[3]) : 1;
        for (int k = 0; k < calls; k++) run(&b, method);
        printf("%s: %d calls\n", names[method], calls);
        return 0;
    }
    const char *outdir = argc > 1 ? argv[1] : ".";
    const int rounds = argc > 2 ? atoi(argv[2]) : 41;
    if (rounds < 1 || rounds > MAX_ROUNDS) {
        fprintf(stderr, "bench_analysis: rounds must be 1..%d\n", MAX_ROUNDS);
        return 1;
    }
    char cpu[256];
    cpu_name(cpu, sizeof cpu);
    /* warm up and size each batch to about 3 ms */
    long reps[NMETHOD];
    for (int k = 0; k < NMETHOD; k++) {
        long r = 1;
        for (;;) {
            const double t0 = now_us();
            for (long i = 0; i < r; i++) run(&b, k);
            const double dt = now_us() - t0;
            if (dt > 3000.0 || r > (1L << 24)) break;
            r *= dt < 300.0 ? 8 : 2;
        }
        reps[k] = r;
    }
    static double us[NMETHOD][MAX_ROUNDS];
    for (int round = 0; round < rounds; round++)
        for (int j = 0; j < NMETHOD; j++) {
            const int k = round % 2 ? NMETHOD - 1 - j : j;
            const double t0 = now_us();
            for (long i = 0; i < reps[k]; i++) run(&b, k);
            const double per = k == M_ANALYSIS || k == M_CHECKED ? (double)(NOUT + 1) : 1.0;
            us[k][round] = (now_us() - t0) / (double)reps[k] / per;
        }
    /* per-round ratios to the recursive instant */
    static double ra[MAX_ROUNDS], rc[MAX_ROUNDS], rf[MAX_ROUNDS], rd[MAX_ROUNDS], rfa[MAX_ROUNDS];
    for (int round = 0; round < rounds; round++) {
        const double inst = us[M_RECURSIVE][round];
        ra[round] = us[M_ANALYSIS][round] / inst;
        rc[round] = us[M_CHECKED][round] / inst;
        rf[round] = (us[M_CHECKED][round] - us[M_ANALYSIS][round]) / inst;
        rfa[round] = (us[M_CHECKED][round] - us[M_ANALYSIS][round]) / us[M_ANALYSIS][round];
        rd[round] = us[M_DENSE][round] / inst;
    }
    double med[NMETHOD][3], s_a[3], s_c[3], s_f[3], s_d[3], s_fa[3];
    for (int k = 0; k < NMETHOD; k++) summary(us[k], rounds, med[k]);
    summary(ra, rounds, s_a);
    summary(rc, rounds, s_c);
    summary(rf, rounds, s_f);
    summary(rd, rounds, s_d);
    summary(rfa, rounds, s_fa);
    printf("vtdyn time layer, five-link arm: %d alternating rounds, batches of about 3 ms, on %s\n", rounds, cpu);
    printf("  batch sizes: recursive %ld, dense %ld, analysis %ld, checked %ld calls\n", reps[0], reps[1], reps[2],
           reps[3]);
    for (int k = 0; k < NMETHOD; k++)
        printf("  %-10s %8.3f us %s (%.3f-%.3f)\n", names[k], med[k][0],
               k >= M_ANALYSIS ? "per output instant" : "per instant       ", med[k][1], med[k][2]);
    printf("  dense / recursive                         %6.2f (%.2f-%.2f)\n", s_d[0], s_d[1], s_d[2]);
    printf("  analysis (check off) / recursive instant  %6.2f (%.2f-%.2f)\n", s_a[0], s_a[1], s_a[2]);
    printf("  analysis with check / recursive instant   %6.2f (%.2f-%.2f)\n", s_c[0], s_c[1], s_c[2]);
    printf("  forward check alone / recursive instant   %6.2f (%.2f-%.2f)\n", s_f[0], s_f[1], s_f[2]);
    printf("  forward check alone / analysis instant    %6.2f (%.2f-%.2f)\n", s_fa[0], s_fa[1], s_fa[2]);
    run(&b, M_CHECKED);
    printf("  forward check: %ld IDA steps, %ld residuals (without the Jacobian's) for %d output intervals;"
           " max |q_fwd - q| %.3g rad\n", b.tr->steps_fwd, b.tr->res_evals_fwd, NOUT, b.tr->fwd_err_q);
    char path[4096];
    snprintf(path, sizeof path, "%s/analysis_speed.csv", outdir);
    FILE *csv = fopen(path, "w");
    if (!csv) {
        perror(path);
        return 1;
    }
    fprintf(csv, "# %s, %d rounds\nquantity,median,min,max\n", cpu, rounds);
    for (int k = 0; k < NMETHOD; k++) fprintf(csv, "%s_us,%.6g,%.6g,%.6g\n", names[k], med[k][0], med[k][1], med[k][2]);
    fprintf(csv, "dense_over_recursive,%.4g,%.4g,%.4g\n", s_d[0], s_d[1], s_d[2]);
    fprintf(csv, "analysis_over_recursive,%.4g,%.4g,%.4g\n", s_a[0], s_a[1], s_a[2]);
    fprintf(csv, "checked_over_recursive,%.4g,%.4g,%.4g\n", s_c[0], s_c[1], s_c[2]);
    fprintf(csv, "check_over_recursive,%.4g,%.4g,%.4g\n", s_f[0], s_f[1], s_f[2]);
    fprintf(csv, "check_over_analysis,%.4g,%.4g,%.4g\n", s_fa[0], s_fa[1], s_fa[2]);
    fclose(csv);
    printf("wrote %s\n", path);
    vt_trajectory_free(b.tr);
    vt_data_free(b.di);
    vt_data_free(b.d);
    vt_model_free(b.m);
    return 0;
}
