// cmd/number_text.cc: the command's numbers as text. Against independent references: every
// printed double reads back as itself (std::from_chars), --precision P prints printf's %.Pg (on
// the same doubles, and on the midpoints of its rounding and their neighbours), and
// the shortest form, laid out here from Dragonbox's digits, is std::to_chars's byte for byte (the
// layout's reference, libstdc++'s Ryu); cells read as strtod reads them; number_print_room writes
// the same within its room. Built without Dragonbox the shortest form is std::to_chars itself:
// that comparison is not run (and says so).
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <csetjmp>
#include <random>

extern "C" {
#include <cmocka.h>
}

#include "number_text.h"

// the doubles every check runs on: random bit patterns (every exponent, subnormals), m 10^e for
// m < 1000 over the whole range and their neighbours, the integers about 2^53 (where %f's exact
// digits part from the shortest), values of a robot's outputs' sizes, and the edges
template <class F> static void each_double(F f)
{
    std::mt19937_64 g(20261207);
    for (int i = 0; i < 300000; i++) {
        const std::uint64_t u = g();
        double x;
        std::memcpy(&x, &u, sizeof x);
        if (std::isfinite(x)) f(x);
    }
    for (int e = -325; e <= 308; e++)
        for (int m = 1; m < 1000; m += 7) {
            const double x = m * std::pow(10.0, e);
            if (!std::isfinite(x)) continue;
            f(x), f(-x), f(std::nextafter(x, 0.0)), f(std::nextafter(x, INFINITY));
        }
    for (double k = -40; k <= 40; k++) f(9007199254740992.0 + 2 * k), f(-(18014398509481984.0 + 4 * k));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 100000; i++) f(u(g) * std::pow(10.0, static_cast<int>(g() % 9) - 4));
    const double edges[] = {0.0, -0.0, DBL_MAX, -DBL_MAX, DBL_MIN, DBL_TRUE_MIN, -DBL_TRUE_MIN, 1.0, 0.1, 1e15, 1e16,
                            1e17, 1e21, 1e22, 1e23, 123456789012345680000.0, 0.0001, 1e-5, 9.5, 0.5, 100.0};
    for (double x : edges) f(x);
}

// 10^k, 0 <= k <= 17
static std::uint64_t p10_of(int k)
{
    std::uint64_t r = 1;
    while (k-- > 0) r *= 10;
    return r;
}

static void test_shortest_as_to_chars(void **state)
{
    (void)state;
    long differ = 0;
    each_double([&](double x) {
        char a[NUMBER_TEXT_MAX], b[64];
        const int la = number_print(a, x, 0);
        const std::to_chars_result r = std::to_chars(b, b + sizeof b, x);
        const int lb = static_cast<int>(r.ptr - b);
        if (la != lb || std::memcmp(a, b, static_cast<size_t>(la)) != 0) {
            if (differ++ < 5) print_error("%.17g: '%.*s', std::to_chars '%.*s'\n", x, la, a, lb, b);
        }
    });
    assert_int_equal(differ, 0);
}

static void test_shortest_reads_back(void **state)
{
    (void)state;
    long bad = 0;
    each_double([&](double x) {
        char a[NUMBER_TEXT_MAX + 1];
        const int n = number_print(a, x, 0);
        double y = NAN;
        const std::from_chars_result r = std::from_chars(a, a + n, y);
        const bool ok = n > 0 && n <= NUMBER_TEXT_MAX && r.ec == std::errc() && r.ptr == a + n &&
                        std::memcmp(&x, &y, sizeof x) == 0; // the same bits: -0 too
        if (!ok && bad++ < 5) print_error("%.17g printed '%.*s'\n", x, n, a);
    });
    assert_int_equal(bad, 0);
}

// number_print at precision p against printf's "%.*g": *bad counts the differences (the first
// five printed)
static void as_printf(double x, int p, long *bad)
{
    char a[NUMBER_TEXT_MAX + 1], b[64];
    const int n = number_print(a, x, p);
    const int m = std::snprintf(b, sizeof b, "%.*g", p, x);
    if ((n != m || std::memcmp(a, b, static_cast<size_t>(n)) != 0) && (*bad)++ < 5)
        print_error("%.17g at %d: '%.*s', printf '%s'\n", x, p, n, a, b);
}

static void test_precision_as_printf(void **state)
{
    (void)state;
    long bad = 0, k = 0;
    each_double([&](double x) {
        if (k++ % 16) return; // a sixteenth of them, each at every precision
        for (int p = 1; p <= 17; p++) as_printf(x, p, &bad);
    });
    assert_int_equal(bad, 0);
}

// --precision P's own edges, each at its P (1 to 17) and beside it: the doubles nearest to P + 1
// digits ending in 5 (the midpoints of the P-digit grid, whose side the shortest digits do not
// tell), those of P nines then a 5 (rounded up, a digit more: 9.95 → 10), over exponents from
// the subnormals to DBL_MAX
static void test_precision_midpoints(void **state)
{
    (void)state;
    std::mt19937_64 g(20261208);
    long bad = 0;
    for (int p = 1; p <= 17; p++)
        for (int i = 0; i < 4000; i++) {
            std::uint64_t m = p10_of(p - 1) + g() % (9 * p10_of(p - 1)); // p digits
            if (i % 8 == 0) m = 10 * p10_of(p - 1) - 1;                  // p nines
            const int e = static_cast<int>(g() % 640) - 330;
            char text[64];
            std::snprintf(text, sizeof text, "%llu5e%d", static_cast<unsigned long long>(m), e);
            const double x0 = std::strtod(text, nullptr);
            for (double x : {x0, std::nextafter(x0, 0.0), std::nextafter(x0, INFINITY), -x0})
                if (std::isfinite(x) && x != 0.0) as_printf(x, p, &bad);
        }
    assert_int_equal(bad, 0);
}

// number_print_room (a row's numbers written one after the other): number_print's characters,
// and nothing written past NUMBER_TEXT_ROOM (the bytes after it left as they were)
static void test_room(void **state)
{
    (void)state;
    long bad = 0;
    each_double([&](double x) {
        for (int p : {0, 6}) {
            char a[NUMBER_TEXT_MAX], r[NUMBER_TEXT_ROOM + 16];
            std::memset(r, 0x5a, sizeof r);
            const int n = number_print(a, x, p), m = number_print_room(r, x, p);
            bool ok = n == m && std::memcmp(a, r, static_cast<size_t>(n)) == 0;
            for (int k = NUMBER_TEXT_ROOM; k < NUMBER_TEXT_ROOM + 16; k++) ok = ok && r[k] == 0x5a;
            if (!ok && bad++ < 5) print_error("%.17g (precision %d): '%.*s', room '%.*s'\n", x, p, n, a, m, r);
        }
    });
    assert_int_equal(bad, 0);
}

static void test_parse_as_strtod(void **state)
{
    (void)state;
    long bad = 0;
    each_double([&](double x) {
        char b[64];
        const int m = std::snprintf(b, sizeof b, "%.17g", x);
        double y = NAN;
        if ((!number_parse(b, static_cast<size_t>(m), &y) || y != std::strtod(b, nullptr)) && bad++ < 5)
            print_error("'%s' read as %.17g\n", b, y);
    });
    assert_int_equal(bad, 0);
    double v = 7.0;
    assert_int_equal(number_parse("1e400", 5, &v), 0); // beyond double: refused, v untouched
    assert_int_equal(number_parse("1.5x", 4, &v), 0);
    assert_true(v == 7.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shortest_reads_back),
        cmocka_unit_test(test_precision_as_printf),
        cmocka_unit_test(test_precision_midpoints),
        cmocka_unit_test(test_parse_as_strtod),
        cmocka_unit_test(test_room),
    };
    const struct CMUnitTest layout[] = {
        cmocka_unit_test(test_shortest_as_to_chars),
    };
    int failed = cmocka_run_group_tests(tests, nullptr, nullptr);
#ifdef VT_HAVE_DRAGONBOX
    failed += cmocka_run_group_tests(layout, nullptr, nullptr);
    return failed;
#else
    (void)layout;
    std::printf("test_shortest_as_to_chars: not run, built without Dragonbox (the shortest form is "
                "std::to_chars itself)\n");
    return failed;
#endif
}
