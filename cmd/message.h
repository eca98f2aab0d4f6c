/* The command's error messages (cmd/message.c). */
#ifndef VTDYN_CMD_MESSAGE_H
#define VTDYN_CMD_MESSAGE_H

#include <stddef.h>

/* prints "vtdyn: " and the formatted message on standard error, a line; returns 1 (the exit
 * status). On a thread given a sink (cmd_message_sink) the first message goes there instead */
int cmd_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* this thread's messages kept in buf (size bytes; the first one, without "vtdyn: "), to be
 * printed later by another, in order; NULL: printed again */
void cmd_message_sink(char *buf, size_t size);

#endif
