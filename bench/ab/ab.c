/* A/B speed of two builds of vtdyn in one process: vt_inverse_dynamics_recursive, one instant.
 *
 * What: for each scene, the time per call of build A and of build B (two shared objects made
 * by bench/ab/build.sh from two trees, each with its own copy of vtdyn bound inside it), and
 * the ratio B/A (> 1: B is slower).
 * How: both objects are dlopen'ed RTLD_NOW|RTLD_LOCAL into this process and set up on the
 * same scene and state (bench_inverse.c's); their outputs (drive efforts, drive forces, joint
 * and cut reactions) must agree to 1e-12 relative to their largest magnitude, else the scene is
 * not timed. A batch of calls is sized to about 5 ms (the same count for both); then in each of
 * the rounds (default 41) one batch of A and one of B are timed back to back, the order turned
 * every round (AB, BA, AB, ...), so drifts of the machine hit both alike and the per-round ratio
 * cancels them. Printed per scene: the median µs per call of A and of B over the rounds, and
 * of the per-round ratios B/A their median, range (min–max) and inter-quartile range.
 * usage: ab <A.so> <B.so> [rounds] [labelA labelB]   (bench/ab/run.sh builds and pins it)
 */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../cpuinfo.h"

#define MAXROUNDS 1001
#define MAXOUT 4096

typedef struct {
    const char *label;
    int (*setup)(const char *scene, int n);
    double (*batch)(long calls);
    int (*check)(double *out, int cap, double *sum);
} build;

static void load(build *b, const char *path, const char *label)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        fprintf(stderr, "ab: %s\n", dlerror());
        exit(1);
    }
    b->label = label;
    *(void **)&b->setup = dlsym(h, "ab_setup");
    *(void **)&b->batch = dlsym(h, "ab_batch");
    *(void **)&b->check = dlsym(h, "ab_check");
    if (!b->setup || !b->batch || !b->check) {
        fprintf(stderr, "ab: %s lacks ab_setup/ab_batch/ab_check\n", path);
        exit(1);
    }
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* quantile p of sorted v[0..n-1], linear between order statistics */
static double quant(const double *v, int n, double p)
{
    const double x = p * (n - 1);
    const int i = (int)x;
    return i + 1 < n ? v[i] + (x - i) * (v[i + 1] - v[i]) : v[n - 1];
}

static double timed(const build *b, long calls)
{
    const double s = b->batch(calls);
    if (s < 0.0) {
        fprintf(stderr, "ab: an instant of %s failed\n", b->label);
        exit(1);
    }
    return s;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: ab <A.so> <B.so> [rounds] [labelA labelB]\n");
        return 2;
    }
    const int rounds = argc > 3 ? atoi(argv[3]) : 41;
    if (rounds < 41 || rounds > MAXROUNDS) {
        fprintf(stderr, "ab: rounds must be 41..%d\n", MAXROUNDS);
        return 2;
    }
    build A, B;
    load(&A, argv[1], argc > 5 ? argv[4] : "A");
    load(&B, argv[2], argc > 5 ? argv[5] : "B");

    char date[64];
    const time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S %Z", localtime(&now));
    printf("vtdyn A/B, vt_inverse_dynamics_recursive, one instant: %d rounds, order turned each round\n", rounds);
    printf("date: %s\n", date);
    vt_bench_cpu_line();
    printf("compiler: %s\n", __VERSION__);
    printf("command:");
    for (int i = 0; i < argc; i++) printf(" %s", argv[i]);
    printf("\nA = %s (%s)\nB = %s (%s)\n\n", A.label, argv[1], B.label, argv[2]);
    printf("%-13s %4s %8s %10s %10s %7s %15s %15s %10s\n", "scene", "n", "calls", "A us/call", "B us/call",
           "B/A", "B/A min-max", "B/A IQR", "max rel");

    static const struct { const char *scene; int n; } scenes[] = {
        {"chain", 2}, {"chain", 10}, {"chain", 50}, {"chain", 200}, {"double_link", 2}, {"fourbar", 3},
        {"fourbar_rusr", 4}, {"chain_tip", 10}, {"chain_tip", 20}, {"five_link", 5}, {"delta", 21},
        {"stewart", 24}, {"knee", 4},
    };
    static double ta[MAXROUNDS], tb[MAXROUNDS], ratio[MAXROUNDS], oa[MAXOUT], ob[MAXOUT];
    for (size_t s = 0; s < sizeof scenes / sizeof scenes[0]; s++) {
        const char *name = scenes[s].scene;
        const int n = scenes[s].n;
        const int ra = A.setup(name, n), rb = B.setup(name, n);
        if (ra || rb) {
            static const char *why[] = {"", "scene missing in the tree", "build failed", "instant failed"};
            printf("%-13s %4d  skipped: A %s, B %s\n", name, n, ra ? why[ra] : "ok", rb ? why[rb] : "ok");
            continue;
        }
        double sa, sb;
        const int na = A.check(oa, MAXOUT, &sa), nb = B.check(ob, MAXOUT, &sb);
        double scale = 0.0, diff = 0.0;
        for (int k = 0; k < na && k < MAXOUT; k++) {
            scale = fmax(scale, fabs(oa[k]));
            diff = fmax(diff, fabs(oa[k] - ob[k]));
        }
        const double rel = diff / fmax(scale, 1e-300);
        if (na < 0 || na != nb || na > MAXOUT || !(rel <= 1e-12)) {
            printf("%-13s %4d  skipped: outputs disagree (counts %d, %d; checksums %.17g, %.17g; max rel %.3g)\n",
                   name, n, na, nb, sa, sb, rel);
            continue;
        }
        /* warm up both, then size the batch to about 5 ms */
        long calls = 1;
        for (;;) {
            const double t = 0.5 * (timed(&A, calls) + timed(&B, calls));
            if (t > 5e-3 || calls > (1L << 26)) {
                calls = (long)fmax(1.0, (double)calls * 5e-3 / t);
                break;
            }
            calls *= t < 5e-4 ? 8 : 2;
        }
        timed(&A, calls);
        timed(&B, calls);
        for (int r = 0; r < rounds; r++) {
            if (r % 2 == 0) {
                ta[r] = timed(&A, calls);
                tb[r] = timed(&B, calls);
            } else {
                tb[r] = timed(&B, calls);
                ta[r] = timed(&A, calls);
            }
            ratio[r] = tb[r] / ta[r];
        }
        qsort(ta, (size_t)rounds, sizeof(double), cmp);
        qsort(tb, (size_t)rounds, sizeof(double), cmp);
        qsort(ratio, (size_t)rounds, sizeof(double), cmp);
        const double us = 1e6 / (double)calls;
        printf("%-13s %4d %8ld %10.4f %10.4f %7.4f %7.4f-%-7.4f %7.4f-%-7.4f %10.1e\n", name, n, calls,
               quant(ta, rounds, 0.5) * us, quant(tb, rounds, 0.5) * us, quant(ratio, rounds, 0.5), ratio[0],
               ratio[rounds - 1], quant(ratio, rounds, 0.25), quant(ratio, rounds, 0.75), rel);
        fflush(stdout);
    }
    return 0;
}
