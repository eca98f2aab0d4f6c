/* The scratch arena of a data struct (base/arena.h): a stack of named allocations, each on a cache
 * line, released in order; in AddressSanitizer builds what lies above the top is poisoned. The
 * arena itself is laid out by data.c. */
#include <stddef.h>
#include "base/arena.h"
#include "base/status.h"

void *vt_scratch_refuse(vt_data *d, size_t n, size_t size, const char *name)
{
    vt_arena *a = d->arena;
    if (!a->failed)
        vt_fail(d->message, VT_ERR_NO_MEMORY,
                "scratch arena: '%s' (%zu x %zu bytes) does not fit (%zu of %zu bytes in use): a sizing bug in vtdyn", name,
                n, size, a->top, a->size);
    a->failed = 1;
    return NULL;
}

void *vt_scratch_rest(vt_data *d, size_t need, size_t size, int *count, const char *name)
{
    const vt_arena *a = d->arena;
    size_t n = (a->size - a->top) / size;
    if (n > (size_t)1 << 30) n = (size_t)1 << 30; /* LAPACK counts in int */
    if (n < need) n = need;                        /* does not fit: vt_scratch_take says so */
    const size_t peak = a->peak, need_top = a->top + VT_SCRATCH_BYTES(need, size);
    void *p = vt_scratch_take(d, n, size, name);
    *count = p ? (int)n : 0;
    /* the peak counts what was needed, not the rest handed over (the bounds reserve `need`) */
    d->arena->peak = peak > need_top ? peak : need_top;
    return p;
}

vt_status vt_scratch_fail(vt_data *d, size_t mark)
{
    vt_scratch_release(d, mark);
    return VT_ERR_NO_MEMORY;
}
