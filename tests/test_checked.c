/* src/base/checked.h: sizes added and multiplied in size_t, a result that does not fit reported
 * (0, and SIZE_MAX in the result) instead of wrapped, against the exact result in 128-bit
 * arithmetic where the compiler has it (unsigned __int128) and against the bounds themselves;
 * counts added within a limit. */
#include "vt_test.h"

#include "base/checked.h"

/* the operands: small, around the square root of SIZE_MAX, around half of it, at the top */
static const size_t values[] = {0, 1, 2, 3, 7, 255, 65535, 65536, (size_t)1 << 31, (size_t)UINT32_MAX,
                                (size_t)UINT32_MAX + 1, (size_t)UINT32_MAX + 2, SIZE_MAX / 3, SIZE_MAX / 2,
                                SIZE_MAX / 2 + 1, SIZE_MAX - 1, SIZE_MAX};
enum { NVALUES = sizeof values / sizeof values[0] };

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 wide; /* GCC and Clang: exact for any two size_t */
#endif

static void test_add(void **state)
{
    (void)state;
    for (int i = 0; i < NVALUES; i++)
        for (int j = 0; j < NVALUES; j++) {
            const size_t a = values[i], b = values[j];
            size_t r = 12345;
            const int ok = vt_size_add(&r, a, b);
            const int fits = a <= SIZE_MAX - b; /* the bound itself */
            assert_int_equal(ok, fits);
            if (fits) {
                assert_true(r == a + b);
                assert_true(r >= a && r >= b); /* no wrap */
            } else {
                assert_true(r == SIZE_MAX);
            }
#if defined(__SIZEOF_INT128__)
            const wide exact = (wide)a + b;
            assert_int_equal(ok, exact <= SIZE_MAX);
#endif
        }
}

static void test_mul(void **state)
{
    (void)state;
    for (int i = 0; i < NVALUES; i++)
        for (int j = 0; j < NVALUES; j++) {
            const size_t a = values[i], b = values[j];
            size_t r = 12345;
            const int ok = vt_size_mul(&r, a, b);
            if (ok) {
                assert_true(r == a * b);
                assert_true(a == 0 || r / a == b); /* no wrap */
            } else {
                assert_true(r == SIZE_MAX);
                assert_true(a != 0 && b != 0);
            }
#if defined(__SIZEOF_INT128__)
            const wide exact = (wide)a * b;
            assert_int_equal(ok, exact <= SIZE_MAX);
#endif
        }
    /* what the model's and data's sizes look like: 2^32 rates squared, times 8 bytes */
    size_t r;
    const size_t nv = (size_t)UINT32_MAX + 1;
    assert_int_equal(vt_size_mul(&r, nv, nv), sizeof(size_t) > 8);
    assert_int_equal(vt_size_mul(&r, (size_t)1 << 30, 8), 1);
    assert_true(r == (size_t)1 << 33);
}

static void test_count_add(void **state)
{
    (void)state;
    int r = -1;
    assert_int_equal(vt_count_add(&r, 3, 4, 7), 1);
    assert_int_equal(r, 7);
    assert_int_equal(vt_count_add(&r, 4, 4, 7), 0);
    assert_int_equal(r, 7); /* unchanged */
    assert_int_equal(vt_count_add(&r, 0, 8, 7), 0);
    assert_int_equal(vt_count_add(&r, INT32_MAX - 1, 1, INT32_MAX), 1);
    assert_int_equal(r, INT32_MAX);
    assert_int_equal(vt_count_add(&r, INT32_MAX, 1, INT32_MAX), 0); /* never past INT_MAX */
    assert_int_equal(vt_count_add(&r, 1, INT32_MAX, INT32_MAX), 0);
    assert_int_equal(r, INT32_MAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_add),
        cmocka_unit_test(test_mul),
        cmocka_unit_test(test_count_add),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
