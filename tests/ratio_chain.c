/* vtdyn's answers for the chains of vt_test_ratio_chain (tests/vt_test.h), for the high-precision
 * oracle tests/ratio_oracle.py: for each mass distribution (1 kg rods; falling and rising by 1e6
 * a rod, 1e24 in all, and by 1e3, 1e12), each way of driving it and three states, one JSON line
 * per path (dense vt_inverse_dynamics, recursive) with the data the oracle needs (the masses and
 * inertias as the model holds them, q, q̇, t, exact as printed with 17 digits) and what vtdyn
 * returns (status, route, warning, rcond, q̈, λ). */
#include <stdio.h>

#include "vt_test.h"

static void list(const char *name, const double *v, int n)
{
    printf(", \"%s\": [", name);
    for (int i = 0; i < n; i++) printf("%s%.17g", i ? ", " : "", v[i]);
    printf("]");
}

int main(void)
{
    for (int chain = 0; chain < 5; chain++)
        for (int drive = 0; drive < 4; drive++) {
            /* 1 kg rods; falling and rising by 1e6 a rod (1e24 in all); by 1e3 (1e12) */
            const int rising = chain == 0 ? -1 : (chain - 1) % 2;
            const int step = chain < 3 ? 6 : 3;
            vt_model *m = vt_test_ratio_chain(rising, drive, step);
            for (int k = 0; k < 3; k++)
                for (int path = 0; path < 2; path++) {
                    vt_data *d;
                    if (vt_data_create(&d, m) != VT_OK) return 1;
                    double q[5], qd[5], izz[5];
                    for (int c = 0; c < 5; c++) {
                        d->q[c] = q[c] = 0.3 + 0.25 * c + 0.4 * k; /* test_mass_ratios' states */
                        d->qd[c] = qd[c] = 0.5 - 0.2 * c + 0.1 * k;
                        izz[c] = m->body_inertia[9 * (c + 1) + 8];
                    }
                    d->time = 0.2 * k;
                    const vt_status st = path ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
                    printf("{\"step\": %d, \"rising\": %d, \"drive\": %d, \"state\": %d, \"path\": %d, \"status\": %d, "
                           "\"route\": %d, \"warning\": %d, \"rcond\": %.17g, \"time\": %.17g",
                           step, rising, drive, k, path, (int)st, (int)d->route, d->warning, d->rcond, d->time);
                    list("mass", m->body_mass + 1, 5);
                    list("izz", izz, 5);
                    list("q", q, 5);
                    list("qd", qd, 5);
                    list("qdd", d->qdd, 5);
                    list("lambda", d->lambda, m->nc);
                    printf("}\n");
                    vt_data_free(d);
                }
            vt_model_free(m);
        }
    return 0;
}
