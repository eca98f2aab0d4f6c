// Numbers as text, see number_text.h: std::to_chars and std::from_chars of <charconv>.
#include "number_text.h"

#include <charconv>
#include <system_error>

int number_print(char *buf, double v, int precision)
{
    const std::to_chars_result r = precision > 0
        ? std::to_chars(buf, buf + NUMBER_TEXT_MAX, v, std::chars_format::general, precision)
        : std::to_chars(buf, buf + NUMBER_TEXT_MAX, v);
    return r.ec == std::errc() ? static_cast<int>(r.ptr - buf) : 0;
}

int number_parse(const char *s, size_t len, double *v)
{
    double x;
    const std::from_chars_result r = std::from_chars(s, s + len, x);
    if (r.ec != std::errc() || r.ptr != s + len) return 0;
    *v = x;
    return 1;
}
