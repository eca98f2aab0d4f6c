/* src/model/inertia.c: the inertia checks against matrices whose principal moments are known
 * (a rotated diagonal: symmetric, on and off the triangle inequality, a negative moment, at and
 * beyond the tolerance), and the parallel axes against a rod's inertia about its end written from
 * the definition (m L² / 3) and against the two-step merge of three point masses (the sum of
 * m_k (|r_k|² 1 − r_k r_kᵀ) about the common centre of mass). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "model/inertia.h" /* internal */
#include "vt_test.h"

/* R diag(d) Rᵀ with R the rotation by angle a about the unit axis u */
static void turned(double J[9], const double d[3], const double u[3], double a)
{
    const double c = cos(a), s = sin(a), C = 1.0 - c;
    const double R[9] = {c + u[0] * u[0] * C,        u[1] * u[0] * C + u[2] * s, u[2] * u[0] * C - u[1] * s,
                         u[0] * u[1] * C - u[2] * s, c + u[1] * u[1] * C,        u[2] * u[1] * C + u[0] * s,
                         u[0] * u[2] * C + u[1] * s, u[1] * u[2] * C - u[0] * s, c + u[2] * u[2] * C};
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++) {
            double v = 0.0;
            for (int k = 0; k < 3; k++) v += R[r + 3 * k] * d[k] * R[q + 3 * k];
            J[r + 3 * q] = v;
        }
}

static void test_checks(void **state)
{
    (void)state;
    const double u[3] = {0.48, 0.6, 0.64}; /* unit */
    char msg[VT_MESSAGE_SIZE];
    double J[9];
    const struct {
        double d[3], tol;
        vt_status want;
    } cases[] = {
        {{1.0, 2.0, 2.5}, 1e-6, VT_OK},
        {{1.0, 2.0, 3.0}, 1e-6, VT_OK},                      /* on the triangle inequality's edge */
        {{1.0, 2.0, 3.018}, 1e-6, VT_ERR_INERTIA_TRIANGLE}, /* 0.6 % of the largest beyond it */
        {{1.0, 2.0, 3.018}, 1e-2, VT_OK},                   /* within a looser tolerance */
        {{-0.05, 2.0, 2.0}, 1e-6, VT_ERR_INERTIA_NOT_PSD},
        {{0.0, 0.0, 0.0}, 1e-6, VT_OK},                     /* a point mass */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        turned(J, cases[k].d, u, 0.7);
        msg[0] = '\0';
        const vt_status st = vt_check_inertia(msg, "body 4", J, cases[k].tol);
        if (st != cases[k].want) fail_msg("case %d: status %d, expected %d (%s)", (int)k, st, cases[k].want, msg);
        if (st) assert_non_null(strstr(msg, "body 4")), assert_non_null(strstr(msg, "inertia_tol"));
    }
    turned(J, cases[0].d, u, 0.7);
    J[3] += 1e-3; /* J12 ≠ J21 */
    assert_int_equal(vt_check_inertia(msg, "body 4", J, 1e-6), VT_ERR_INERTIA_ASYMMETRIC);
    vt_inertia_symmetric(J);
    assert_true(J[3] == J[1] && J[6] == J[2] && J[7] == J[5]);
}

static void test_parallel_axes(void **state)
{
    (void)state;
    /* a slender rod of mass m, length L along x, about its centre m L²/12 on y and z; about its
     * end (d = L/2 along x) m L²/3 */
    const double m = 3.0, L = 0.8, Jc[9] = {0, 0, 0, 0, m * L * L / 12, 0, 0, 0, m * L * L / 12}, d[3] = {L / 2, 0, 0};
    double J[9] = {0};
    vt_inertia_add(J, m, Jc, NULL, d);
    assert_true(fabs(J[4] - m * L * L / 3) <= 1e-15 * m * L * L && fabs(J[8] - m * L * L / 3) <= 1e-15 * m * L * L);
    assert_true(J[0] == 0.0 && J[1] == 0.0 && J[3] == 0.0);
    /* a point mass 1 km out along x, 1 and 2 cm off it: about x, m (0.01² + 0.02²) to the last
     * digits, not |d|² − d_x², whose 1e6 m² cancel to 5e-4 (1.2e-7 relative lost) */
    const double dfar[3] = {1e3, 0.01, 0.02}, zero9[9] = {0};
    double Jf[9] = {0};
    vt_inertia_add(Jf, m, zero9, NULL, dfar);
    assert_true(fabs(Jf[0] - m * 5e-4) <= 4.0 * DBL_EPSILON * m * 5e-4);
    assert_true(fabs(Jf[3] + m * 10.0) <= 4.0 * DBL_EPSILON * m * 10.0);
    /* three point masses merged one by one about their common centre equal Σ m (|r|² 1 − r rᵀ),
     * and a part in turned axes Q: Q Jp Qᵀ */
    const double pm[3] = {1.0, 2.0, 0.5}, pr[3][3] = {{0.3, -0.2, 0.1}, {-0.1, 0.4, 0.2}, {0.2, 0.1, -0.6}};
    double c[3] = {0, 0, 0}, M = 0.0, A[9] = {0}, Bm[9] = {0};
    for (int k = 0; k < 3; k++) {
        M += pm[k];
        for (int e = 0; e < 3; e++) c[e] += pm[k] * pr[k][e];
    }
    for (int e = 0; e < 3; e++) c[e] /= M;
    const double zero[9] = {0};
    for (int k = 0; k < 3; k++) {
        double r[3];
        for (int e = 0; e < 3; e++) r[e] = pr[k][e] - c[e];
        vt_inertia_add(A, pm[k], zero, NULL, r);
        const double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) Bm[i + 3 * j] += pm[k] * ((i == j ? rr : 0.0) - r[i] * r[j]);
    }
    for (int k = 0; k < 9; k++) assert_true(fabs(A[k] - Bm[k]) <= 1e-15);
    const double Q[9] = {0, 1, 0, -1, 0, 0, 0, 0, 1}, Jp[9] = {1, 0, 0, 0, 2, 0, 0, 0, 3}, z[3] = {0, 0, 0};
    double T[9] = {0};
    vt_inertia_add(T, 1.0, Jp, Q, z); /* a quarter turn about z swaps the x and y moments */
    assert_true(T[0] == 2.0 && T[4] == 1.0 && T[8] == 3.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_checks),
        cmocka_unit_test(test_parallel_axes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
