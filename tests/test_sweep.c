/* examples/sweep.c, the design sweep of the five-link arm, run as a program on small grids; its
 * CSV held to closed forms that use neither vtdyn nor the scene's model:
 *   - the arm's positions along the circle from its geometry (scenes.h: the tip and the
 *     joint-5 point on their circles, link 5 along X, link 4 level, the elbow below the line
 *     from joint 2 to the wrist, as vt_scene_five_link_guess), the accelerations of every
 *     centre of mass and rod direction by finite differences of them (4th order);
 *   - the reaction at joint j under joint-torque actuation: Newton for the bodies beyond it,
 *     f_j = Σ_{k ≥ j} m_k (a_k − g) (the joint torques act in pairs, the point payload counts
 *     with link 5); the torque of joint j: Euler about its point P_j along its axis,
 *     τ_j = axis · Σ_{k ≥ j} [(r_k − P_j) × m_k (a_k − g) + J_k e_k × ë_k], a slender rod's
 *     angular momentum being J e × ė;
 *   - at a very long cycle (1e5 s, quasi-static) the static identities alone: |f_j| is the
 *     weight beyond joint j, payload included; the pitch torques are g Σ m_k × the lever arm
 *     (r_k − P_j)·u (u radial); the yaw joints 1 and 5 carry nothing.
 * Then: the grid's order and values, and bad arguments refused.
 * Usage: test_sweep <path of the sweep program> <directory for its CSV files>
 */
#include <stdio.h>

#include "vt_test.h"

#define PI 3.14159265358979323846
#define NCOLS 13
#define G 9.81

static const char *sweep_path, *out_dir;

/* runs the sweep with `args` writing <out_dir>/<name>; returns its exit status */
static int run_sweep(const char *args, const char *name)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' %s -o '%s/%s' > /dev/null 2>&1", sweep_path, args, out_dir, name);
    const int rc = system(cmd);
    return rc == -1 ? -1 : (rc >> 8) & 0xff; /* POSIX wait status: the exit code */
}

/* reads the CSV rows into rows[n][NCOLS]; returns the number of rows */
static int read_csv(const char *name, double rows[][NCOLS], int max)
{
    char path[4096], line[2048];
    snprintf(path, sizeof path, "%s/%s", out_dir, name);
    FILE *f = fopen(path, "r");
    if (!f) fail_msg("cannot open %s", path);
    if (!fgets(line, sizeof line, f)) fail_msg("%s is empty", path);
    if (strncmp(line, "payload_kg,period_s,tau1_max_Nm,", 32) != 0) fail_msg("%s: header %s", path, line);
    int n = 0;
    while (n < max && fgets(line, sizeof line, f)) {
        double *r = rows[n];
        int status;
        const int got = sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%d", &r[0], &r[1], &r[2], &r[3], &r[4],
                               &r[5], &r[6], &r[7], &r[8], &r[9], &r[10], &r[11], &status);
        if (got != NCOLS) fail_msg("%s: row %d has %d fields: %s", path, n + 1, got, line);
        r[12] = status;
        n++;
    }
    fclose(f);
    return n;
}

/* ---- the arm from its geometry (scenes.h) -------------------------------------------- */

static const double link_len[5] = {0.4, 0.5, 0.5, 0.2, 0.2}, link_mass[5] = {2.0, 1.5, 1.5, 0.5, 0.5};

typedef struct pose {
    double r[6][3]; /* centres of mass of links 1..5, then the payload (the tip) */
    double e[6][3]; /* unit direction of each rod (link 1 along z); the payload's unused */
    double P[5][3]; /* joint points 1..5 */
    double u[3];    /* radial unit vector of the vertical plane of links 2-4 */
} pose;

static void pose_at(pose *p, double t, double period)
{
    const double w = 2.0 * PI / period, c = cos(w * t), s = sin(w * t);
    const double tip[3] = {VT_FL_C1 + 0.3 * c, 0.3 * s, VT_FL_CE};
    const double P5[3] = {tip[0] - 0.2, tip[1], VT_FL_CE}; /* link 5 along X */
    const double rho = hypot(P5[0], P5[1]);
    const double u[3] = {P5[0] / rho, P5[1] / rho, 0.0};
    /* in the plane (ρ, z): joint 2 at (0, 0.4), wrist W at (ρ − 0.2, C_e) (link 4 level); the
     * elbow E is 0.5 m from both, below the line from joint 2 to W */
    const double Jx = 0.0, Jz = 0.4, Wx = rho - 0.2, Wz = VT_FL_CE;
    const double dx = Wx - Jx, dz = Wz - Jz, d = hypot(dx, dz);
    const double h = sqrt(0.25 - 0.25 * d * d);
    const double Ex = 0.5 * (Jx + Wx) + h * dz / d, Ez = 0.5 * (Jz + Wz) - h * dx / d;
    const double origin[3] = {0, 0, 0}, J2[3] = {0.0, 0.0, 0.4};
    const double E[3] = {Ex * u[0], Ex * u[1], Ez}, W[3] = {Wx * u[0], Wx * u[1], Wz};
    const double *ends[5][2] = {{origin, J2}, {J2, E}, {E, W}, {W, P5}, {P5, tip}};
    for (int k = 0; k < 5; k++) {
        for (int i = 0; i < 3; i++) {
            p->r[k][i] = 0.5 * (ends[k][0][i] + ends[k][1][i]);
            p->e[k][i] = (ends[k][1][i] - ends[k][0][i]) / link_len[k];
            p->P[k][i] = ends[k][0][i];
        }
    }
    for (int i = 0; i < 3; i++) {
        p->r[5][i] = tip[i];
        p->e[5][i] = 0.0;
        p->u[i] = u[i];
    }
}

/* accelerations of the centres and second derivatives of the directions, 4th-order differences */
static void accel_at(double a[6][3], double edd[6][3], double t, double period)
{
    const double h = 3e-4 * period; /* truncation and round-off both near 1e-10 of the loads */
    static const double wgt[5] = {-1.0, 16.0, -30.0, 16.0, -1.0};
    memset(a, 0, 18 * sizeof(double));
    memset(edd, 0, 18 * sizeof(double));
    for (int s = 0; s < 5; s++) {
        pose p;
        pose_at(&p, t + (s - 2) * h, period);
        for (int k = 0; k < 6; k++)
            for (int i = 0; i < 3; i++) {
                a[k][i] += wgt[s] * p.r[k][i] / (12.0 * h * h);
                edd[k][i] += wgt[s] * p.e[k][i] / (12.0 * h * h);
            }
    }
}

static void cross(double c[3], const double a[3], const double b[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* peaks over the sweep's samples t_k = k T / n of |τ_j| and |f_j| by Newton–Euler (dynamic) or
 * the static lever arms alone (dynamic = 0) */
static void closed_form_peaks(double tau[5], double f[5], double payload, double period, int nsample, int dynamic)
{
    double mass[6], J[6];
    for (int k = 0; k < 5; k++) {
        mass[k] = link_mass[k];
        J[k] = k == 0 ? 0.0 : link_mass[k] * link_len[k] * link_len[k] / 12.0; /* link 1 turns about its own axis */
    }
    mass[5] = payload;
    J[5] = 0.0;
    for (int j = 0; j < 5; j++) tau[j] = f[j] = 0.0;
    for (int s = 0; s < nsample; s++) {
        const double t = period * s / nsample;
        pose p;
        double a[6][3], edd[6][3];
        pose_at(&p, t, period);
        accel_at(a, edd, t, period);
        if (!dynamic) {
            memset(a, 0, sizeof a);
            memset(edd, 0, sizeof edd);
        }
        const double pitch[3] = {-p.u[1], p.u[0], 0.0}, z[3] = {0, 0, 1};
        for (int j = 0; j < 5; j++) {
            const double *axis = (j == 0 || j == 4) ? z : pitch;
            double F[3] = {0, 0, 0}, M[3] = {0, 0, 0};
            for (int k = j; k < 6; k++) { /* the bodies beyond joint j; the payload beyond every joint */
                const double ma[3] = {mass[k] * a[k][0], mass[k] * a[k][1], mass[k] * (a[k][2] + G)};
                double arm[3], m1[3], m2[3];
                for (int i = 0; i < 3; i++) arm[i] = p.r[k][i] - p.P[j][i];
                cross(m1, arm, ma);
                cross(m2, p.e[k], edd[k]);
                for (int i = 0; i < 3; i++) {
                    F[i] += ma[i];
                    M[i] += m1[i] + J[k] * m2[i];
                }
            }
            tau[j] = fmax(tau[j], fabs(axis[0] * M[0] + axis[1] * M[1] + axis[2] * M[2]));
            f[j] = fmax(f[j], sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]));
        }
    }
}

/* ---- tests ------------------------------------------------------------------------- */

static void test_quasi_static(void **state)
{
    (void)state;
    double rows[3][NCOLS];
    assert_int_equal(run_sweep("-m 3 -M 2 -p 1 -t 1e5,1e5 -s 24", "sweep_static.csv"), 0);
    assert_int_equal(read_csv("sweep_static.csv", rows, 3), 3);
    for (int n = 0; n < 3; n++) {
        const double *r = rows[n], pay = r[0];
        assert_near(pay, 1.0 * n, 0.0);
        assert_near(r[1], 1e5, 0.0);
        assert_near(r[12], 0.0, 0.0);
        /* reactions: the weight beyond each joint, payload included */
        double beyond = pay;
        for (int j = 4; j >= 0; j--) {
            beyond += link_mass[j];
            assert_near(r[7 + j], G * beyond, 1e-8 * G * beyond);
        }
        /* torques: the yaw joints carry nothing, the pitch joints g Σ m × lever arm */
        double tau[5], f[5];
        closed_form_peaks(tau, f, pay, 1e5, 24, 0);
        assert_near(r[2], 0.0, 1e-6);
        assert_near(r[6], 0.0, 1e-6);
        for (int j = 1; j <= 3; j++) assert_near(r[2 + j], tau[j], 1e-8 * tau[j]);
        /* the payload's share of joint 2's peak (at t = 0, at full reach): m g × the tip's lever arm,
         * 0.8 + 0.3 m from the yaw axis */
        assert_near(r[3] - rows[0][3], pay * G * 1.1, 1e-8 * rows[0][3]);
    }
}

static void test_dynamic(void **state)
{
    (void)state;
    double rows[4][NCOLS];
    assert_int_equal(run_sweep("-m 2 -M 1.5 -p 2 -t 0.6,1.2 -s 40", "sweep_dynamic.csv"), 0);
    assert_int_equal(read_csv("sweep_dynamic.csv", rows, 4), 4);
    for (int n = 0; n < 4; n++) {
        const double *r = rows[n];
        assert_near(r[12], 0.0, 0.0);
        double tau[5], f[5], tstat[5], fstat[5];
        closed_form_peaks(tau, f, r[0], r[1], 40, 1);
        closed_form_peaks(tstat, fstat, r[0], r[1], 40, 0);
        for (int j = 0; j < 5; j++) {
            const double tscale = fmax(tau[1], 1.0), fscale = f[0];
            assert_near(r[2 + j], tau[j], 1e-8 * tscale);
            assert_near(r[7 + j], f[j], 1e-8 * fscale);
        }
        /* and the motion matters here: the yaw torque is far from its static 0 */
        assert_true(r[2] > 0.1);
    }
}

static void test_grid_and_arguments(void **state)
{
    (void)state;
    double rows[6][NCOLS];
    assert_int_equal(run_sweep("-m 3 -M 1 -p 2 -t 1,2 -s 4", "sweep_grid.csv"), 0);
    assert_int_equal(read_csv("sweep_grid.csv", rows, 6), 6);
    for (int n = 0; n < 6; n++) { /* payloads outer, periods inner */
        assert_near(rows[n][0], 0.5 * (n / 2), 0.0);
        assert_near(rows[n][1], 1.0 + (n % 2), 0.0);
    }
    /* heavier payloads need more torque at joint 2 */
    assert_true(rows[2][3] > rows[0][3] && rows[4][3] > rows[2][3]);
    assert_int_equal(run_sweep("-m 0", "bad.csv"), 2);
    assert_int_equal(run_sweep("-t 2,1", "bad.csv"), 2);
    assert_int_equal(run_sweep("-t 1", "bad.csv"), 2);
    assert_int_equal(run_sweep("-x 1", "bad.csv"), 2);
    assert_int_equal(run_sweep("-s", "bad.csv"), 2);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_sweep <sweep program> <output directory>\n");
        return 2;
    }
    sweep_path = argv[1];
    out_dir = argv[2];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quasi_static),
        cmocka_unit_test(test_dynamic),
        cmocka_unit_test(test_grid_and_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
