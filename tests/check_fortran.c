/* The Fortran example (examples/double_link.f90) builds the paper's double link itself, through
 * the bindings in fortran/vtdyn.f90, and prints the inverse dynamics of one instant. This test
 * runs it at several angles and holds every printed number to
 *   - the C side: vt_scene_double_link(&m, 1) at the same state, within 1e-12 of the quantity's
 *     scale (a model built differently — a mass, a joint point, the lock — shows at once);
 *   - the closed forms (29): θ̈ = 3.67875 cos θ, |τ2| = 245.25 cos θ,
 *     f1 = [−2207.25 sin 2θ, 4905 sin²θ + 490.5 cos²θ], f2 = [−1655.4375 sin 2θ,
 *     3188.25 sin²θ − 122.625 cos²θ], within 1e-10 (as tests/test_reactions.c).
 * Usage: check_fortran <path of double_link_f>
 */
#define _POSIX_C_SOURCE 200809L /* popen */
#include <stdio.h>

#include "vt_test.h"

static const char *exe_path;

typedef struct printed {
    double q[2], qd[2], qdd[2], effort, drive_f[3], drive_n[3], f1[3], n1[3], f2[3], n2[3];
    int seen; /* lines read */
} printed;

/* runs the Fortran example at angle th and reads its name-value lines */
static void run_fortran(printed *out, double th)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' %.17g", exe_path, th);
    FILE *p = popen(cmd, "r");
    if (!p) fail_msg("cannot run %s", cmd);
    memset(out, 0, sizeof *out);
    char line[1024];
    while (fgets(line, sizeof line, p)) {
        char name[32];
        double v[3] = {0, 0, 0};
        const int n = sscanf(line, "%31s %lf %lf %lf", name, &v[0], &v[1], &v[2]);
        if (n < 2) continue;
        static const struct { const char *name; size_t off; int n; } key[] = {
            {"q", offsetof(printed, q), 2},           {"qd", offsetof(printed, qd), 2},
            {"qdd", offsetof(printed, qdd), 2},       {"effort", offsetof(printed, effort), 1},
            {"drive_f", offsetof(printed, drive_f), 3}, {"drive_n", offsetof(printed, drive_n), 3},
            {"f1", offsetof(printed, f1), 3},         {"n1", offsetof(printed, n1), 3},
            {"f2", offsetof(printed, f2), 3},         {"n2", offsetof(printed, n2), 3},
        };
        for (size_t k = 0; k < sizeof key / sizeof key[0]; k++) {
            if (strcmp(name, key[k].name) != 0) continue;
            if (n - 1 != key[k].n) fail_msg("line '%s': %d values, expected %d", name, n - 1, key[k].n);
            memcpy((char *)out + key[k].off, v, (size_t)key[k].n * sizeof(double));
            out->seen++;
        }
    }
    const int rc = pclose(p);
    if (rc != 0) fail_msg("%s exited with status %d", cmd, rc);
    if (out->seen != 10) fail_msg("%s printed %d of the 10 result lines", cmd, out->seen);
}

static void near3(const double *a, const double *b, double tol)
{
    for (int k = 0; k < 3; k++) assert_near(a[k], b[k], tol);
}

static void test_against_c(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    const double W = 1962.0 * 2.5, T = 245.25, A = 3.67875; /* scales: 2.5 weights, τ2(0), θ̈(0) */
    for (double th = 0.0; th <= 1.5; th += 0.3) {
        printed f;
        run_fortran(&f, th);
        d->q[0] = -th;
        d->q[1] = 0.0;
        d->qd[0] = -sqrt(7.3575 * sin(th));
        d->qd[1] = 0.0;
        assert_ok(vt_inverse_dynamics(m, d));
        for (int k = 0; k < 2; k++) {
            assert_near(f.q[k], d->q[k], 1e-15);
            assert_near(f.qd[k], d->qd[k], 1e-15 * 3.0);
            assert_near(f.qdd[k], d->qdd[k], 1e-12 * A);
        }
        assert_near(f.effort, d->drive_effort[0], 1e-12 * T);
        near3(f.drive_f, d->drive_force, 1e-12 * W);
        near3(f.drive_n, d->drive_moment, 1e-12 * T);
        near3(f.f1, d->jnt_force + 3, 1e-12 * W);
        near3(f.n1, d->jnt_moment + 3, 1e-12 * T);
        near3(f.f2, d->jnt_force + 6, 1e-12 * W);
        near3(f.n2, d->jnt_moment + 6, 1e-12 * T);
    }
    vt_data_free(d);
    vt_model_free(m);
}

static void test_closed_form(void **state)
{
    (void)state;
    for (double th = 0.0; th <= 1.5; th += 0.25) {
        printed f;
        run_fortran(&f, th);
        const double s = sin(th), c = cos(th);
        assert_near(-f.qdd[0], 3.67875 * c, 1e-10 * 3.67875);
        assert_near(f.qdd[1], 0.0, 1e-10 * 3.67875);
        assert_near(fabs(f.effort), 245.25 * c, 1e-10 * 245.25);
        assert_near(f.drive_n[2], f.effort, 1e-12 * 245.25);
        assert_near(f.f1[0], -2207.25 * sin(2 * th), 1e-10 * 4905.0);
        assert_near(f.f1[1], 4905.0 * s * s + 490.5 * c * c, 1e-10 * 4905.0);
        assert_near(f.f2[0], -1655.4375 * sin(2 * th), 1e-10 * 3188.25);
        assert_near(f.f2[1], 3188.25 * s * s - 122.625 * c * c, 1e-10 * 3188.25);
        for (int k = 0; k < 3; k++) {
            assert_near(f.n1[k], 0.0, 1e-10 * 245.25);
            assert_near(f.n2[k], 0.0, 1e-10 * 245.25);
        }
        assert_near(f.f1[2], 0.0, 1e-10 * 4905.0);
        assert_near(f.f2[2], 0.0, 1e-10 * 4905.0);
    }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: check_fortran <path of double_link_f>\n");
        return 2;
    }
    exe_path = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_c),
        cmocka_unit_test(test_closed_form),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
