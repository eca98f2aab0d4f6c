/* The command's error messages: one line on standard error, after the command's name; or kept,
 * on a thread whose work may fail after another's (the file read ahead of the rows solved). */
#include "message.h"

#include <stdarg.h>
#include <stdio.h>

static _Thread_local char *sink;
static _Thread_local size_t sink_size;

void cmd_message_sink(char *buf, size_t size)
{
    sink = buf;
    sink_size = size;
    if (buf && size) buf[0] = '\0';
}

int cmd_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (sink) {
        if (!sink[0]) vsnprintf(sink, sink_size, fmt, ap);
    } else {
        fputs("vtdyn: ", stderr);
        vfprintf(stderr, fmt, ap);
        fputc('\n', stderr);
    }
    va_end(ap);
    return 1;
}
