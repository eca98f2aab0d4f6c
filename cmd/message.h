/* The command's error messages (cmd/message.c). */
#ifndef VTDYN_CMD_MESSAGE_H
#define VTDYN_CMD_MESSAGE_H

/* prints "vtdyn: " and the formatted message on standard error, a line; returns 1 (the exit status) */
int cmd_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
