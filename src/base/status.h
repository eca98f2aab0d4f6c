/* vtdyn — Status messages and the argument check every stage starts with (base/status.c). */
#ifndef VT_BASE_STATUS_H
#define VT_BASE_STATUS_H

#include "vtdyn.h"

/* Writes a formatted message into buf (VT_MESSAGE_SIZE bytes) and returns status. */
vt_status vt_fail(char *buf, vt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Common argument check of every stage: non-NULL, data made for this model. */
vt_status vt_check_pair(const vt_model *m, vt_data *d, const char *who);

#endif
