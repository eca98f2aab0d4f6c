/* Numbers as text for the command's CSV: C++17's <charconv> (the compiler's own library, GCC's
 * libstdc++), which prints the shortest decimal that reads back as the same double (Ryu) and
 * reads decimals correctly rounded (fast_float), several times faster than printf("%.17g") and
 * strtod; where the build has Dragonbox, the shortest digits (and the %.Pg ones up to P = 15) are
 * its, faster, in the same bytes.
 * Locale-independent, like the "C" locale the command runs in. */
#ifndef VTDYN_CMD_NUMBER_TEXT_H
#define VTDYN_CMD_NUMBER_TEXT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* the most characters number_print writes: "-2.2250738585072014e-308" */
#define NUMBER_TEXT_MAX 24

/* the bytes number_print_room may write at buf: its copies are of a constant length, past what
 * the number keeps */
#define NUMBER_TEXT_ROOM 64

/* v into buf (no terminating NUL; buf holds NUMBER_TEXT_MAX): with precision 0 the fewest
 * significant digits that read back as v, fixed or exponent, whichever is shorter; with precision
 * 1 to 17 the bytes of printf's "%.{precision}g". Returns the characters written.
 * number_print_room: the same characters, buf holding NUMBER_TEXT_ROOM (the bytes after the
 * number's are overwritten, with anything): for a row's numbers one after the other. */
int number_print(char *buf, double v, int precision);
int number_print_room(char *buf, double v, int precision);

/* the len characters at s read as one decimal number (an optional '-', digits with an optional
 * point, an optional exponent; or inf, nan), correctly rounded: 1 when the whole of them is one
 * such number within the range of double, else 0 (v untouched; the caller reads the text another
 * way or refuses it). */
int number_parse(const char *s, size_t len, double *v);

#ifdef __cplusplus
}
#endif

#endif
