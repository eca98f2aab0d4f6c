/* fuzz_model's differential comparison (compare.c): tolerances and comparisons of two routes */
#ifndef FUZZ_COMPARE_H
#define FUZZ_COMPARE_H

#include "vtdyn.h"

/* an instant's tolerances (compare.c's opening comment) */
typedef struct {
    double kappa; /* 1/rcond */
    double e;     /* C (nv + nc + 1) ε κ */
    double Fs, Ns, Gs, L, mmax, Jmax, mA;
    double dq;            /* q̈'s tolerance in the mass metric (0: plain units) */
    double tq, tf, tn, tg; /* q̈ in plain units (rates without inertia), forces, moments, generalized */
} scales;

/* inputs at least this large are at overflow's edge */
#define EDGE_INPUT 1e75

extern double perturb;     /* FUZZ_PERTURB=r: the recursive q̈ and the last joint's x force times 1 + r */
extern double worst_ratio; /* FUZZ_STATS: the largest |difference| / tolerance seen (tuning only) */

scales pair_scales(const vt_model *m, const vt_data *ref, const vt_data *a, const vt_data *b, double rcond);
void agree(const char *pair, const char *what, const double *a, const double *b, int n, double tol, const scales *s);
void agree_qdd(const char *pair, const vt_model *m, const vt_data *ref, const double *a, const double *b,
               const scales *s);
void agree_loads(const char *pair, const vt_model *m, const vt_data *a, const vt_data *b, const scales *s, int drives,
                 int reactions);
void agree_totals(const char *pair, const vt_model *m, const vt_data *ref, const vt_data *a, const vt_data *b,
                  const scales *s);
double input_magnitude(const vt_model *m, const vt_data *d);
/* a refusal of round-off of lever arms from o (compare.c) */
int beyond_lever_arms(const vt_data *d);
/* 1 when both statuses are VT_OK; fails on an inconsistent pair */
int consistent(const char *pair, const vt_model *m, vt_status sa, const vt_data *a, vt_status sb, const vt_data *b,
               double in_mag);
int rows_hold(const vt_model *m, const vt_data *d, double e);

#endif
