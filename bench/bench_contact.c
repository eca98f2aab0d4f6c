/* Contacts: the quadruped's instant on its four feet (vt_inverse_dynamics_contacts) against the
 * same instant without contacts (vt_inverse_dynamics_motion), in one process: batches of calls of
 * about 2 ms each, the two alternating and their order turned every round (forwards, then
 * backwards), ROUNDS rounds (default 41). Prints the date, the CPU, the median µs a call of each
 * with the rounds' range, and the median of the rounds' ratios with its range.
 *
 *     build/bench/bench_contact [rounds]
 *
 * The state: vt_scene_quadruped standing (θ = 0.6) with its joints moving (the rates and
 * accelerations of tests/test_contact_rule.c), μ 0.8 on 4-face pyramids. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <vtdyn.h>

#include "cpuinfo.h"
#include "timing.h"
#include "scenes.h"

static const vt_model *m;
static vt_data *d;
static vt_contacts *c;
static double force[12];

/* one batch of n calls of method k (0: without contacts, 1: with); µs a call */
static double batch(int k, int n)
{
    const double t0 = now();
    for (int i = 0; i < n; i++) {
        const vt_status st = k ? vt_inverse_dynamics_contacts(m, d, c, NULL, force) : vt_inverse_dynamics_motion(m, d);
        if (st) {
            fprintf(stderr, "bench_contact: %s\n", d->message);
            exit(1);
        }
    }
    return 1e6 * (now() - t0) / n;
}

int main(int argc, char **argv)
{
    const int rounds = argc > 1 && atoi(argv[1]) > 0 ? atoi(argv[1]) : 41;
    vt_model *mm = NULL;
    if (vt_scene_quadruped(&mm) || vt_data_create(&d, mm)) return 1;
    m = mm;
    vt_scene_quadruped_stand(m, d, 0.6);
    for (int a = 6; a < m->nv; a++) {
        d->qd[a] = 0.3 * sin(1.7 * a);
        d->qdd[a] = 0.5 * cos(0.9 * a);
    }
    static const char *const feet[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};
    vt_contact_def def[4];
    for (int k = 0; k < 4; k++) {
        def[k] = vt_default_contact_def();
        def[k].frame = feet[k];
        def[k].mu = 0.8;
    }
    char msg[VT_MESSAGE_SIZE];
    if (vt_contacts_create(&c, m, def, 4, NULL, msg)) {
        fprintf(stderr, "bench_contact: %s\n", msg);
        return 1;
    }
    time_t t = time(NULL);
    char day[32];
    strftime(day, sizeof day, "%Y-%m-%d", gmtime(&t));
    printf("date: %s\n", day);
    vt_bench_cpu_line();
    printf("command: bench_contact %d (the quadruped, 18 rates, 4 feet)\n", rounds);
    int n[2];
    for (int k = 0; k < 2; k++) { /* calls a batch: about 2 ms */
        const double us = batch(k, 200);
        n[k] = us > 0 ? (int)(2000.0 / us) + 1 : 1000;
    }
    double *tm[2], *ratio = malloc((size_t)rounds * sizeof *ratio);
    for (int k = 0; k < 2; k++) tm[k] = malloc((size_t)rounds * sizeof *tm[k]);
    if (!ratio || !tm[0] || !tm[1]) return 1;
    for (int r = 0; r < rounds; r++) {
        for (int h = 0; h < 2; h++) {
            const int k = r % 2 ? 1 - h : h;
            tm[k][r] = batch(k, n[k]);
        }
        ratio[r] = tm[1][r] / tm[0][r];
    }
    for (int k = 0; k < 2; k++) qsort(tm[k], (size_t)rounds, sizeof *tm[k], by_value);
    qsort(ratio, (size_t)rounds, sizeof *ratio, by_value);
    printf("without contacts: %.3f us (%.3f-%.3f)\n", tm[0][rounds / 2], tm[0][0], tm[0][rounds - 1]);
    printf("with 4 contacts:  %.3f us (%.3f-%.3f)\n", tm[1][rounds / 2], tm[1][0], tm[1][rounds - 1]);
    printf("ratio: %.2f (%.2f-%.2f)\n", ratio[rounds / 2], ratio[0], ratio[rounds - 1]);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(mm);
    return 0;
}
