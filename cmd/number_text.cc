// Numbers as text, see number_text.h: std::to_chars and std::from_chars of <charconv>; with
// Dragonbox (VT_HAVE_DRAGONBOX) the shortest digits come from its to_decimal and are laid out
// here as std::to_chars lays them out, and --precision up to 15 rounds them (rounded, below)
// as printf's %.Pg rounds the double (tests/test_number_text.cc holds them equal byte for byte).
#include "number_text.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <system_error>

#ifdef VT_HAVE_DRAGONBOX
#include <dragonbox/dragonbox.h>

// "00" ... "99"
static const char pairs[201] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                               "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                               "8081828384858687888990919293949596979899";

// u < 10^8 as its eight decimal digits (leading zeros kept) at d
static inline void eight_digits(char *d, std::uint32_t u)
{
    const std::uint32_t hi = u / 10000, lo = u % 10000; // two chains of two pairs each
    std::memcpy(d, pairs + 2 * (hi / 100), 2);
    std::memcpy(d + 2, pairs + 2 * (hi % 100), 2);
    std::memcpy(d + 4, pairs + 2 * (lo / 100), 2);
    std::memcpy(d + 6, pairs + 2 * (lo % 100), 2);
}

static const std::uint64_t p10[18] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000,
                                      1000000000, 10000000000, 100000000000, 1000000000000,
                                      10000000000000, 100000000000000, 1000000000000000,
                                      10000000000000000, 100000000000000000};

// how many decimal digits u has (1 <= u < 10^17): ⌊log10 2^b⌋ for its b bits (1233 / 4096 below
// log10 2), then one comparison
static inline int digit_count(std::uint64_t u)
{
    const int b = ((64 - __builtin_clzll(u)) * 1233) >> 12;
    return b + (u >= p10[b]);
}

// the decimal digits of u (1 <= u < 10^17: Dragonbox's significand of a double), most
// significant first: all seventeen written into t (leading zeros kept: no loop whose length
// depends on u), *n set to how many u has; returns its first
static const char *decimal_digits(char t[17], std::uint64_t u, int *n)
{
    *n = digit_count(u);
    const std::uint64_t hi = u / 100000000; // < 10^9
    t[0] = static_cast<char>('0' + hi / 100000000);
    eight_digits(t + 1, static_cast<std::uint32_t>(hi % 100000000));
    eight_digits(t + 9, static_cast<std::uint32_t>(u % 100000000));
    return t + 17 - *n;
}

// Copies and fills of a constant length (a move or two each, where a length known only at run
// time costs a call of memcpy or memset): DIGITS bytes from a source that has them, ZEROS '0's.
// They write past what the number keeps, into the room number_print_room's caller gives; the
// layout below writes each part after the one before, over what that one wrote beyond its end.
enum { DIGITS = 17, ZEROS = 24 };

// ±d.ddd 10^X, the k digits at dig (DIGITS of them readable), at buf: as printf's %e (d.ddde±XX,
// at least two exponent digits) when sci, else as its %f (the point placed among the digits, or
// zeros filled in before or after them, fewer than ZEROS); the characters kept. Writes up to
// NUMBER_TEXT_ROOM bytes at buf. Inlined into each caller: called, it cost 2 to 7 % of a CSV
// output's writing (the layout's branches then no longer follow from the caller's).
__attribute__((always_inline)) static inline int lay_out(char *buf, bool negative, const char *dig, int k, int X, bool sci)
{
    char *p = buf;
    *p = '-';
    p += negative;
    if (sci) {
        const int ax = X < 0 ? -X : X;
        p[0] = dig[0];
        p[1] = '.';
        std::memcpy(p + 2, dig + 1, DIGITS);
        p += k > 1 ? k + 1 : 1;
        *p++ = 'e';
        *p++ = X < 0 ? '-' : '+';
        *p = static_cast<char>('0' + ax / 100);
        p += ax >= 100;
        *p++ = static_cast<char>('0' + ax / 10 % 10);
        *p++ = static_cast<char>('0' + ax % 10);
    } else if (X < 0) { // 0.00ddd: −X − 1 zeros after the point
        *p++ = '0', *p++ = '.';
        std::memset(p, '0', ZEROS);
        p += -X - 1;
        std::memcpy(p, dig, DIGITS);
        p += k;
    } else if (k <= X + 1) { // the digits, then zeros up to X + 1 digits
        std::memcpy(p, dig, DIGITS);
        std::memset(p + k, '0', ZEROS);
        p += X + 1;
    } else { // the point among the digits, after X + 1 of them
        std::memcpy(p, dig, DIGITS);
        p[X + 1] = '.';
        std::memcpy(p + X + 2, dig + X + 1, DIGITS);
        p += k + 1;
    }
    return static_cast<int>(p - buf);
}

// v (finite, nonzero) = D 10^E, D the fewest digits that read back as v (Dragonbox): printf's %e
// with those digits (d.ddde±XX, at least two exponent digits) or its %f (the digits with the point
// placed, zeros filled in), whichever is shorter, %f on a tie, as C++17 asks of std::to_chars;
// the characters kept, or 0 where %f would print more digits than D's (std::to_chars then).
// Writes up to NUMBER_TEXT_ROOM bytes at buf.
static int shortest(char *buf, double v)
{
    const auto dec = jkj::dragonbox::to_decimal(v);
    char all[17 + DIGITS] = {}; // the digits, then room for a constant-length copy from any of them
    int k;
    const char *dig = decimal_digits(all, dec.significand, &k);
    const int E = dec.exponent, X = E + k - 1;
    const int ax = X < 0 ? -X : X, xdigits = ax >= 100 ? 3 : 2;
    const int sci = k + (k > 1) + 2 + xdigits;
    const int fixed = E >= 0 ? k + E : k + E > 0 ? k + 1 : 2 - E;
    // %f of an integer from 2^53 on prints its exact digits, not the shortest with zeros after
    if (fixed <= sci && E > 0 && std::fabs(v) >= 9007199254740992.0) return 0;
    return lay_out(buf, dec.is_negative, dig, k, X, !(fixed <= sci));
}

// The precisions whose %.Pg digits come from Dragonbox's shortest ones: P <= 15. A normal double's
// shortest digits D 10^E are within half its ulp, 2^-53 |v| < 1.2e-16 · 10^(X+1) (X its decimal
// exponent), of v, and v's P-digit rounding grid has half a step 0.5 · 10^(X-P+1), larger for
// every P up to 15. So
//  - D of at most P digits is a point of that grid within half a step of v: the rounding itself;
//  - D of more digits rounds as v does: a midpoint of the grid (P + 1 digits) strictly between
//    v and D would read back as v with no more digits than D and nearer to v, and Dragonbox's D
//    is the shortest, the nearest to v among those. The one case left is D's own digits ending
//    on that midpoint (P + 1 digits, the last a 5): v's side of it decides, which these digits
//    do not tell; std::to_chars prints it (and every P of 16 or 17, and the subnormals, whose
//    ulp is no longer small beside v).
enum { ROUNDED_MAX = 15 };

// v (normal, finite, nonzero) as printf's "%.Pg" (1 <= P <= ROUNDED_MAX): the P-digit rounding
// of v, its trailing zeros dropped, as %e (d.ddde±XX, at least two exponent digits) where its
// decimal exponent X is below -4 or at least P, else as %f; the characters kept, or 0 for the
// case above (std::to_chars then). Writes up to NUMBER_TEXT_ROOM bytes at buf.
static int rounded(char *buf, double v, int P)
{
    const auto dec = jkj::dragonbox::to_decimal(v);
    std::uint64_t u = dec.significand;
    int k = digit_count(u);
    int X = dec.exponent + k - 1;
    if (k > P) {
        const std::uint64_t step = p10[k - P], r = u % step, half = step / 2;
        if (r == half) return 0; // D ends on a midpoint (then k = P + 1: D has no trailing zero)
        u = u / step + (r > half);
        k = P;
        if (u == p10[P]) u = p10[P - 1], X++; // 9.99… rounded up to 10.0…
        while (u % 10 == 0) u /= 10, k--;     // %g drops the trailing zeros
    }
    char all[17 + DIGITS] = {};
    const char *dig = decimal_digits(all, u, &k);
    return lay_out(buf, dec.is_negative, dig, k, X, X < -4 || X >= P);
}
#endif

int number_print_room(char *buf, double v, int precision)
{
#ifdef VT_HAVE_DRAGONBOX
    if (precision == 0 && v != 0.0 && std::isfinite(v)) {
        const int n = shortest(buf, v);
        if (n > 0) return n;
    } else if (precision <= ROUNDED_MAX && std::fabs(v) >= DBL_MIN && std::isfinite(v)) {
        const int n = rounded(buf, v, precision);
        if (n > 0) return n;
    }
#endif
    const std::to_chars_result r = precision > 0
        ? std::to_chars(buf, buf + NUMBER_TEXT_MAX, v, std::chars_format::general, precision)
        : std::to_chars(buf, buf + NUMBER_TEXT_MAX, v);
    return r.ec == std::errc() ? static_cast<int>(r.ptr - buf) : 0;
}

int number_print(char *buf, double v, int precision)
{
    char room[NUMBER_TEXT_ROOM];
    const int n = number_print_room(room, v, precision);
    std::memcpy(buf, room, static_cast<size_t>(n));
    return n;
}

int number_parse(const char *s, size_t len, double *v)
{
    double x;
    const std::from_chars_result r = std::from_chars(s, s + len, x);
    if (r.ec != std::errc() || r.ptr != s + len) return 0;
    *v = x;
    return 1;
}
