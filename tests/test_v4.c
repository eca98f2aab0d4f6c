/* src/base/v4.h: the four-lane algebra of the body kernels, against the scalar algebra it
 * replaces there (base/vec3.h, base/euler.h) on random vectors and Euler parameters. Built twice
 * (tests/meson.build): with the compiler's vector extensions, and with VT_V4_PORTABLE (the
 * struct of four doubles other compilers get), so that both forms are held to the same answers.
 *   products    cross, dot, M a and M^T a (vt_m3_mul, vt_m3_transpose), a + s b: within a few
 *               ulps of the scalar expressions (an FMA may round once where they round twice).
 *   quaternions a ⊗ b, ½ E(p)^T w and A(p) with A^T: within a few ulps of vt_quat_mul_inline,
 *               vt_quat_rate and vt_euler_A_inline; A^T's entries are A's bit for bit.
 *   lanes       set, splat, load3, with0, the turns and broadcasts: exact; vt_v4_store3 writes
 *               three doubles and leaves the fourth, vt_v4_store3_up and vt_v4_store3_down the
 *               three and at most the one after or before them.
 * The vector form is the one an AVX target compiles (-mavx, -march=x86-64-v3 or native); CI's
 * sanitizers' build is one (.ci/run). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "base/euler.h"
#include "base/v4.h"
#include "base/vec3.h"
#include "vt_test.h"

static double uniform(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return (double)(*s >> 11) * 0x1p-52 - 1.0; /* [-1, 1) */
}

static vt_v4 random_v4(uint64_t *s, double out[4])
{
    for (int k = 0; k < 4; k++) out[k] = uniform(s);
    return vt_v4_load(out);
}

/* |got − want| within 4 ulps of the terms' size (inputs in [-1, 1]: at most a few units) */
static void near(double got, double want, double size, const char *what)
{
    if (!(fabs(got - want) <= 4.0 * 0x1p-52 * size)) fail_msg("%s: %.17g, scalar %.17g", what, got, want);
}

static void test_products(void **state)
{
    (void)state;
    uint64_t s = 7;
    for (int trial = 0; trial < 2000; trial++) {
        double a[4], b[4], M[12], r[3];
        const vt_v4 va = random_v4(&s, a), vb = random_v4(&s, b);
        for (int k = 0; k < 12; k++) M[k] = uniform(&s); /* M[9..11]: the spare doubles after it */
        const double sc = uniform(&s);

        vt_cross3(r, a, b);
        const vt_v4 c = vt_v4_cross(va, vb);
        for (int k = 0; k < 3; k++) near(vt_v4_lane(c, k), r[k], 2.0, "cross");
        near(vt_v4_dot3(va, vb), vt_dot3(a, b), 3.0, "dot3");

        const vt_m3 Mv = vt_m3_load(M), T = vt_m3_transpose(Mv);
        vt_mulmat3(r, M, a);
        const vt_v4 Ma = vt_m3_mul(Mv, va);
        for (int k = 0; k < 3; k++) near(vt_v4_lane(Ma, k), r[k], 3.0, "M a");
        vt_mulmat3t(r, M, a);
        const vt_v4 Mta = vt_m3_mul(T, va);
        for (int k = 0; k < 3; k++) near(vt_v4_lane(Mta, k), r[k], 3.0, "M^T a");
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) assert_true(vt_v4_lane(T.c[i], j) == M[i + 3 * j]); /* rows, exactly */

        double ax[3] = {a[0], a[1], a[2]};
        vt_axpy3(ax, sc, b);
        const vt_v4 m = vt_v4_madd(va, sc, vb);
        for (int k = 0; k < 3; k++) near(vt_v4_lane(m, k), ax[k], 2.0, "a + s b");
        const vt_v4 sub = vt_v4_sub(va, vb), add = vt_v4_add(va, vb), mul = vt_v4_mul(va, vb), sca = vt_v4_scale(sc, va);
        for (int k = 0; k < 4; k++) { /* one rounding each: exact against the scalar operation */
            assert_true(vt_v4_lane(sub, k) == a[k] - b[k]);
            assert_true(vt_v4_lane(add, k) == a[k] + b[k]);
            assert_true(vt_v4_lane(mul, k) == a[k] * b[k]);
            assert_true(vt_v4_lane(sca, k) == sc * a[k]);
        }
    }
}

static void test_quaternions(void **state)
{
    (void)state;
    uint64_t s = 11;
    for (int trial = 0; trial < 2000; trial++) {
        double a[4], b[4], w[4], r[4], A[9];
        vt_v4 va = random_v4(&s, a), vb = random_v4(&s, b);
        const vt_v4 vw = random_v4(&s, w);
        vt_normalize(a, 4);
        vt_normalize(b, 4);
        va = vt_v4_load(a);
        vb = vt_v4_load(b);

        vt_quat_mul_inline(r, a, b);
        const vt_v4 ab = vt_v4_quat_mul(va, vb);
        for (int k = 0; k < 4; k++) near(vt_v4_lane(ab, k), r[k], 4.0, "a ⊗ b");

        vt_quat_rate(r, a, w);
        const vt_v4 pd = vt_v4_quat_rate(va, vw);
        for (int k = 0; k < 4; k++) near(vt_v4_lane(pd, k), r[k], 2.0, "½ E^T w");

        vt_euler_A_inline(A, a);
        vt_m3 Av, Rv;
        vt_v4_rotation(va, &Av, &Rv);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                near(vt_v4_lane(Av.c[j], i), A[i + 3 * j], 4.0, "A(p)");
                /* A^T's rows are A's columns: the same products, the ẽ term's sign turned */
                assert_true(vt_v4_lane(Rv.c[i], j) == vt_v4_lane(Av.c[j], i));
            }
    }
}

static void test_lanes(void **state)
{
    (void)state;
#if defined(VT_V4_PORTABLE)
    assert_int_equal(VT_V4_VECTOR, 0); /* this build holds the struct form to the answers */
#elif defined(__GNUC__) && defined(__AVX__)
    assert_int_equal(VT_V4_VECTOR, 1); /* the vector extensions where AVX is the target's */
#endif
    const vt_v4 a = vt_v4_set(1.0, 2.0, 3.0, 4.0);
    const double want[][4] = {{2, 3, 1, 4}, {2, 3, 4, 1}, {4, 1, 2, 3}, {1, 1, 1, 1}, {2, 2, 2, 2}, {3, 3, 3, 3},
                              {9, 2, 3, 4}, {5, 5, 5, 5}};
    const vt_v4 got[] = {vt_v4_yzx(a),   vt_v4_left(a), vt_v4_right(a),      vt_v4_x(a),
                         vt_v4_y(a),     vt_v4_z(a),    vt_v4_with0(a, 9.0), vt_v4_splat(5.0)};
    for (int t = 0; t < 8; t++)
        for (int k = 0; k < 4; k++) assert_true(vt_v4_lane(got[t], k) == want[t][k]);
    const double three[3] = {7.0, 8.0, 9.0};
    const vt_v4 l = vt_v4_load3(three);
    for (int k = 0; k < 3; k++) assert_true(vt_v4_lane(l, k) == three[k]);

    double p[6] = {-1, -1, -1, -1, -1, -1};
    vt_v4_store3(p + 1, a);
    assert_true(p[0] == -1.0 && p[1] == 1.0 && p[2] == 2.0 && p[3] == 3.0 && p[4] == -1.0);
    double u[6] = {-1, -1, -1, -1, -1, -1};
    vt_v4_store3_up(u + 1, a); /* u[4] is the one after: written or not, its value any */
    assert_true(u[0] == -1.0 && u[1] == 1.0 && u[2] == 2.0 && u[3] == 3.0 && u[5] == -1.0);
    double q[6] = {-1, -1, -1, -1, -1, -1};
    vt_v4_store3_down(q + 2, a); /* q[1] is the one before: written, its value any */
    assert_true(q[0] == -1.0 && q[2] == 1.0 && q[3] == 2.0 && q[4] == 3.0 && q[5] == -1.0);
    double r4[5] = {0, 0, 0, 0, -1};
    vt_v4_store(r4, a);
    for (int k = 0; k < 4; k++) assert_true(r4[k] == vt_v4_lane(a, k));
    assert_true(r4[4] == -1.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_products),
        cmocka_unit_test(test_quaternions),
        cmocka_unit_test(test_lanes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
