/* Batches of few rows: the time of one vt_batch_inverse_dynamics_motion call on 1 and on 2
 * threads (one batch each, made once), 1 to 4,096 rows of the 6-link spatial chain (a UR5's
 * size: vt_scene_chain, random states), the efforts and the reactions in world axes written.
 * The two are run in turn, round after round in one process (the order turned every round), a
 * round timing a batch of calls of about 2 ms; printed: the median over 41 rounds of µs per
 * call for each, and the median of the rounds' ratios 2 threads / 1 thread with their range
 * (below 1: the second thread pays). Prints the date, the CPU and the command first.
 *
 *     build/bench/bench_batch
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <vtdyn.h>

#include "cpuinfo.h"
#include "timing.h"
#include "scenes.h"

#define ROUNDS 41
#define MAX_ROWS 4096

/* µs per call of `calls` calls */
static double time_calls(vt_batch *b, const vt_batch_io *io, int calls)
{
    const double t0 = now();
    for (int c = 0; c < calls; c++)
        if (vt_batch_inverse_dynamics_motion(b, io)) {
            fprintf(stderr, "bench_batch: %s\n", vt_batch_message(b));
            exit(1);
        }
    return (now() - t0) / calls * 1e6;
}

int main(int argc, char **argv)
{
    (void)argc;
    time_t t = time(NULL);
    char day[32];
    strftime(day, sizeof day, "%Y-%m-%d %H:%M UTC", gmtime(&t));
    printf("vtdyn batches of few rows: median of %d interleaved rounds, us per call\ndate: %s\n", ROUNDS, day);
    vt_bench_cpu_line();
    printf("command: %s\n", argv[0]);
    vt_model *m = NULL;
    vt_data *d = NULL;
    if (vt_scene_chain(&m, 6, 0) || vt_data_create(&d, m)) return 1;
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody;
    double *q = malloc(MAX_ROWS * nq * sizeof(double)), *qd = malloc(MAX_ROWS * nv * sizeof(double)),
           *qdd = malloc(MAX_ROWS * nv * sizeof(double)), *effort = malloc(MAX_ROWS * nv * sizeof(double)),
           *reaction = malloc(MAX_ROWS * nb6 * sizeof(double));
    if (!q || !qd || !qdd || !effort || !reaction) return 1;
    uint64_t seed = 11;
    for (int r = 0; r < MAX_ROWS; r++) {
        vt_scene_random_state(m, d, &seed);
        memcpy(q + r * nq, d->q, nq * sizeof(double));
        memcpy(qd + r * nv, d->qd, nv * sizeof(double));
        for (size_t k = 0; k < nv; k++) qdd[r * nv + k] = vt_rand_uniform(&seed, -3.0, 3.0);
    }
    vt_batch *b[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        vt_batch_def def = vt_default_batch_def();
        def.threads = k + 1;
        if (vt_batch_create(&b[k], m, &def)) return 1;
    }
    printf("%6s %12s %12s %24s\n", "rows", "1 thread", "2 threads", "2 / 1 (range)");
    const int sizes[] = {1, 16, 32, 64, 128, 256, 1024, 4096};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        vt_batch_io io = {0};
        io.nrow = sizes[s];
        io.q = q;
        io.qd = qd;
        io.qdd = qdd;
        io.effort = effort;
        io.reaction = reaction;
        const int calls = 1 + (int)(2000.0 / (0.8 * sizes[s])); /* about 2 ms on one thread */
        double us[2][ROUNDS], ratio[ROUNDS];
        for (int k = 0; k < 2; k++) time_calls(b[k], &io, calls); /* warm */
        for (int r = 0; r < ROUNDS; r++) {
            for (int i = 0; i < 2; i++) {
                const int k = r % 2 ? 1 - i : i;
                us[k][r] = time_calls(b[k], &io, calls);
            }
            ratio[r] = us[1][r] / us[0][r];
        }
        qsort(us[0], ROUNDS, sizeof(double), by_value);
        qsort(us[1], ROUNDS, sizeof(double), by_value);
        qsort(ratio, ROUNDS, sizeof(double), by_value);
        printf("%6d %12.2f %12.2f %10.2f (%.2f-%.2f)\n", sizes[s], us[0][ROUNDS / 2], us[1][ROUNDS / 2],
               ratio[ROUNDS / 2], ratio[0], ratio[ROUNDS - 1]);
    }
    for (int k = 0; k < 2; k++) vt_batch_free(b[k]);
    free(q);
    free(qd);
    free(qdd);
    free(effort);
    free(reaction);
    vt_data_free(d);
    vt_model_free(m);
    return 0;
}
