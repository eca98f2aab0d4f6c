/* src/base/euler.c: the Euler-parameter identities of method.md, at random parameters. */
#include <float.h>

#include "base/euler.h" /* vt_sincos */
#include "vt_test.h"

static void mat34_mul_t(double *C, const double *X, const double *Y) /* C = X Y^T, X,Y 3x4 */
{
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += X[r + 3 * k] * Y[c + 3 * k];
            C[r + 3 * c] = s;
        }
}

static void test_E_G_A(void **state)
{
    (void)state;
    uint64_t s = 1;
    for (int trial = 0; trial < 100; trial++) {
        double p[4], E[12], G[12], A[9], EEt[9], GGt[9], AAt[9];
        vt_rand_unit(p, 4, &s);
        vt_euler_E(E, p);
        vt_euler_G(G, p);
        vt_euler_A(A, p);
        /* A = E G^T */
        double EGt[9];
        mat34_mul_t(EGt, E, G);
        for (int k = 0; k < 9; k++) assert_near(A[k], EGt[k], 1e-15);
        /* E E^T = G G^T = I, E p = G p = 0 */
        mat34_mul_t(EEt, E, E);
        mat34_mul_t(GGt, G, G);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                assert_near(EEt[r + 3 * c], r == c, 1e-15);
                assert_near(GGt[r + 3 * c], r == c, 1e-15);
            }
        for (int r = 0; r < 3; r++) {
            double ep = 0.0, gp = 0.0;
            for (int k = 0; k < 4; k++) { ep += E[r + 3 * k] * p[k]; gp += G[r + 3 * k] * p[k]; }
            assert_near(ep, 0.0, 1e-15);
            assert_near(gp, 0.0, 1e-15);
        }
        /* A orthonormal with det +1 */
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                double v = 0.0;
                for (int k = 0; k < 3; k++) v += A[r + 3 * k] * A[c + 3 * k];
                AAt[r + 3 * c] = v;
                assert_near(AAt[r + 3 * c], r == c, 1e-15);
            }
        const double det = A[0] * (A[4] * A[8] - A[7] * A[5]) - A[3] * (A[1] * A[8] - A[7] * A[2]) +
                           A[6] * (A[1] * A[5] - A[4] * A[2]);
        assert_near(det, 1.0, 1e-14);
        /* the printed rows of E (eq 8): [-p1 p0 -p3 p2], [-p2 p3 p0 -p1], [-p3 -p2 p1 p0] */
        const double rows[12] = {-p[1], p[0], -p[3], p[2], -p[2], p[3], p[0], -p[1], -p[3], -p[2], p[1], p[0]};
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 4; k++) assert_near(E[r + 3 * k], rows[4 * r + k], 0.0);
    }
}

/* a smooth unit path p(t), its derivatives by finite differences */
static void path(double p[4], double t, const double a[4], const double b[4], const double c[4])
{
    double n = 0.0;
    for (int k = 0; k < 4; k++) { p[k] = a[k] + t * b[k] + t * t * c[k]; n += p[k] * p[k]; }
    n = sqrt(n);
    for (int k = 0; k < 4; k++) p[k] /= n;
}

static void test_rates(void **state)
{
    (void)state;
    uint64_t s = 2;
    const double h = 1e-4;
    for (int trial = 0; trial < 50; trial++) {
        double a[4], b[4], c[4];
        vt_rand_unit(a, 4, &s);
        for (int k = 0; k < 4; k++) { b[k] = vt_rand_uniform(&s, -1, 1); c[k] = vt_rand_uniform(&s, -1, 1); }
        double p[4], pp[4], pm[4], pd[4], pdd[4], E[12], G[12];
        path(p, 0, a, b, c);
        path(pp, h, a, b, c);
        path(pm, -h, a, b, c);
        for (int k = 0; k < 4; k++) {
            pd[k] = (pp[k] - pm[k]) / (2 * h);
            pdd[k] = (pp[k] - 2 * p[k] + pm[k]) / (h * h);
        }
        vt_euler_E(E, p);
        vt_euler_G(G, p);
        /* p^T ṗ = 0 */
        assert_near(p[0] * pd[0] + p[1] * pd[1] + p[2] * pd[2] + p[3] * pd[3], 0.0, 1e-7);
        /* ω = 2 E ṗ is the global angular velocity: Ȧ = ω̃ A; ω' = 2 G ṗ = A^T ω */
        double w[3] = {0}, wb[3] = {0}, A[9], Ap[9], Am[9];
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 4; k++) { w[r] += 2 * E[r + 3 * k] * pd[k]; wb[r] += 2 * G[r + 3 * k] * pd[k]; }
        vt_euler_A(A, p);
        vt_euler_A(Ap, pp);
        vt_euler_A(Am, pm);
        for (int col = 0; col < 3; col++) {
            const double *u = A + 3 * col;
            const double wu[3] = {w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]};
            for (int r = 0; r < 3; r++) assert_near((Ap[r + 3 * col] - Am[r + 3 * col]) / (2 * h), wu[r], 1e-7);
        }
        for (int r = 0; r < 3; r++)
            assert_near(wb[r], A[3 * r] * w[0] + A[3 * r + 1] * w[1] + A[3 * r + 2] * w[2], 1e-12);
        /* ṗ = ½ E^T ω */
        for (int k = 0; k < 4; k++)
            assert_near(pd[k], 0.5 * (E[3 * k] * w[0] + E[3 * k + 1] * w[1] + E[3 * k + 2] * w[2]), 1e-7);
        /* p̈ = ½ E^T ω̇ − ¼ (ω·ω) p, ω̇ by finite differences of ω(t) */
        double wd[3];
        {
            double p2p[4], p2m[4], Ep[12], Em[12], wp[3] = {0}, wm[3] = {0}, pdp[4], pdm[4];
            path(p2p, 2 * h, a, b, c); /* ṗ(±h) by central differences */
            path(p2m, -2 * h, a, b, c);
            for (int k = 0; k < 4; k++) { pdp[k] = (p2p[k] - p[k]) / (2 * h); pdm[k] = (p[k] - p2m[k]) / (2 * h); }
            vt_euler_E(Ep, pp);
            vt_euler_E(Em, pm);
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 4; k++) { wp[r] += 2 * Ep[r + 3 * k] * pdp[k]; wm[r] += 2 * Em[r + 3 * k] * pdm[k]; }
            for (int r = 0; r < 3; r++) wd[r] = (wp[r] - wm[r]) / (2 * h);
        }
        const double w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        for (int k = 0; k < 4; k++)
            assert_near(pdd[k], 0.5 * (E[3 * k] * wd[0] + E[3 * k + 1] * wd[1] + E[3 * k + 2] * wd[2]) - 0.25 * w2 * p[k], 1e-5);
    }
}

static void test_quaternion_product(void **state)
{
    (void)state;
    uint64_t s = 3;
    for (int trial = 0; trial < 50; trial++) {
        double a[4], b[4], ab[4], Aa[9], Ab[9], Aab[9];
        vt_rand_unit(a, 4, &s);
        vt_rand_unit(b, 4, &s);
        vt_quat_mul(ab, a, b);
        vt_euler_A(Aa, a);
        vt_euler_A(Ab, b);
        vt_euler_A(Aab, ab);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                double v = 0.0;
                for (int k = 0; k < 3; k++) v += Aa[r + 3 * k] * Ab[k + 3 * c];
                assert_near(Aab[r + 3 * c], v, 1e-14);
            }
    }
    /* a quarter turn about z takes x to y */
    const double z[3] = {0, 0, 1};
    double p[4], A[9];
    vt_quat_axis_angle(p, z, 0.5 * 3.14159265358979323846);
    vt_euler_A(A, p);
    assert_near(A[0], 0.0, 1e-15);
    assert_near(A[1], 1.0, 1e-15);
    assert_near(A[2], 0.0, 1e-15);
}

/* The error of y against the exact value ref, in units in the last place of a double at ref
 * (the spacing of the binade ref lies in; below DBL_MIN the subnormals' spacing) */
static double ulps(double y, long double ref)
{
    if (ref == 0.0L) return y == 0.0 ? 0.0 : HUGE_VAL;
    int e;
    (void)frexpl(ref, &e);
    const int p = e - DBL_MANT_DIG < DBL_MIN_EXP - DBL_MANT_DIG ? DBL_MIN_EXP - DBL_MANT_DIG : e - DBL_MANT_DIG;
    return (double)(fabsl((long double)y - ref) / ldexpl(1.0L, p));
}

/* long double carries 11 more bits than double here (x87), unless the arithmetic is emulated in
 * doubles (valgrind) or long double is double (other platforms) */
static int long_double_is_wider(void)
{
    volatile long double one = 1.0L, tiny = LDBL_EPSILON;
    return LDBL_MANT_DIG > DBL_MANT_DIG + 8 && one + tiny != one && one + tiny - one == tiny;
}

/* vt_sincos against long double sinl and cosl, the exact values within 1/2048 ulp of a double:
 * at most 0.9 ulp in every range (the C library's sin and cos, measured the same way, are
 * within 0.52; the two may differ in the last bit). Where long double is not wider (valgrind's
 * x87 emulation is in doubles) the C library's double sin and cos are the reference, to 1.5 ulp
 * (our 0.81 and its 0.52). Each range draws 200,000 arguments; then the doubles nearest the
 * multiples of π/2 below 2^14 and their 8 neighbours each way, where x − n π/2 cancels most;
 * the double nearest 29 π/2 (2^-60.5 from it, the closest below 2^14: cos is −0x1.6d61b58c99c43p-61,
 * from 300-bit arithmetic); ±0, ±Inf, NaN and beyond 2^14, where the C library answers. */
static void test_sincos(void **state)
{
    (void)state;
    const int wide = long_double_is_wider();
    const double bound = wide ? 0.9 : 1.5;
    if (!wide) print_message("test_sincos: long double is not wider than double here: libm's sin and cos are the reference\n");
    const double range[] = {0x1.921fb54442d18p-1, 4.0, 100.0, 0x1p14, 1e-5};
    uint64_t seed = 7;
    double worst = 0.0, worst_libm = 0.0;
    for (int g = 0; g < 5; g++)
        for (int i = 0; i < 200000; i++) {
            const double x = vt_rand_uniform(&seed, -range[g], range[g]);
            double s, c;
            vt_sincos(x, &s, &c);
            const long double rs = wide ? sinl(x) : sin(x), rc = wide ? cosl(x) : cos(x);
            const double e = fmax(ulps(s, rs), ulps(c, rc));
            if (e > bound) fail_msg("sincos(%a): sin %a, cos %a: %.3f ulp from %La, %La", x, s, c, e, rs, rc);
            worst = fmax(worst, e);
            if (wide) worst_libm = fmax(worst_libm, fmax(ulps(sin(x), rs), ulps(cos(x), rc)));
        }
    for (int k = 1; k * 1.5707963267948966 < 0x1p14; k++)
        for (int sg = -1; sg <= 1; sg += 2) {
            double x = sg * k * 1.5707963267948966;
            for (int j = 0; j < 8; j++) x = nextafter(x, 0.0);
            for (int j = 0; j < 17; j++, x = nextafter(x, sg * HUGE_VAL)) {
                double s, c;
                vt_sincos(x, &s, &c);
                const long double rs = wide ? sinl(x) : sin(x), rc = wide ? cosl(x) : cos(x);
                const double e = fmax(ulps(s, rs), ulps(c, rc));
                if (e > bound) fail_msg("sincos(%a) near %d π/2: %.3f ulp", x, sg * k, e);
                worst = fmax(worst, e);
            }
        }
    double s, c;
    vt_sincos(0x1.6c6cbc45dc8dep+5, &s, &c);
    assert_true(s == 1.0 && c == -0x1.6d61b58c99c43p-61);
    vt_sincos(-0.0, &s, &c);
    assert_true(s == 0.0 && signbit(s) && c == 1.0);
    vt_sincos(0.0, &s, &c);
    assert_true(s == 0.0 && !signbit(s) && c == 1.0);
    vt_sincos(0x1p-1074, &s, &c);
    assert_true(s == 0x1p-1074 && c == 1.0);
    const double beyond[] = {0x1.0000000000001p14, -1e5, 1e300, HUGE_VAL, -HUGE_VAL, NAN};
    for (int k = 0; k < 6; k++) {
        vt_sincos(beyond[k], &s, &c);
        const double ls = sin(beyond[k]), lc = cos(beyond[k]);
        assert_true((s == ls || (isnan(s) && isnan(ls))) && (c == lc || (isnan(c) && isnan(lc))));
    }
    /* the last argument the inline reduction takes, and vt_quat_axis_angle through it */
    vt_sincos(0x1p14, &s, &c);
    assert_true(ulps(s, wide ? sinl(0x1p14) : sin(0x1p14)) <= bound && ulps(c, wide ? cosl(0x1p14) : cos(0x1p14)) <= bound);
    const double u[3] = {0.0, 0.6, 0.8};
    double p[4];
    vt_quat_axis_angle(p, u, 3.0);
    vt_sincos(1.5, &s, &c);
    assert_true(p[0] == c && p[1] == 0.0 && p[2] == s * 0.6 && p[3] == s * 0.8);
    if (wide) print_message("test_sincos: largest error %.3f ulp (the C library's %.3f)\n", worst, worst_libm);
    else print_message("test_sincos: largest difference from the C library's %.3f ulp\n", worst);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_E_G_A),
        cmocka_unit_test(test_rates),
        cmocka_unit_test(test_quaternion_product),
        cmocka_unit_test(test_sincos),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
