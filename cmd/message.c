/* The command's error messages: one line on standard error, after the command's name. */
#include "message.h"

#include <stdarg.h>
#include <stdio.h>

int cmd_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("vtdyn: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return 1;
}
