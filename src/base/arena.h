/* vtdyn — The scratch arena inside the data (base/arena.c). */
#ifndef VT_BASE_ARENA_H
#define VT_BASE_ARENA_H

#include <stddef.h>

#include "vtdyn.h"

/* ---- the scratch arena (data.c lays it out) ---------------------------------------------
 * A stack inside the data: a function that needs scratch marks the top, takes named
 * allocations (each on a cache line) and releases back to its mark before it returns, so no
 * file knows another's layout and no output array doubles as scratch. In AddressSanitizer
 * builds everything above the top is poisoned (in data from vt_data_create(); a caller's buffer
 * from vt_data_init() is left unpoisoned, the caller may reuse it at any time): a read or write
 * past an allocation, or into a released one, is reported where it happens. Sizes are fixed by the model: each source file
 * that takes scratch bounds what it takes at once with a vt_<file>_scratch(model) function
 * (bytes, VT_SCRATCH_BYTES per allocation), and the arena holds their sum, enough for any call
 * chain in which a file appears once. The analyses over time take none (they allocate what
 * they need at their start). An allocation that does not fit (a sizing bug) returns
 * NULL, names itself in d->message and fails every later one until the release. */
struct vt_arena {
    char *base;   /* on a VT_DATA_ALIGN boundary */
    size_t size;  /* bytes */
    size_t top;   /* bytes in use */
    size_t peak;  /* the highest top since the data was laid out or vt_scratch_peak_reset: the
                   * measured use that each file's bound is tested against (MuJoCo's maxuse_arena) */
    int failed;   /* an allocation did not fit since the last release below it */
    int poison;   /* AddressSanitizer builds: poison what is not taken (vt_data_create()'s data) */
};

#if defined(__SANITIZE_ADDRESS__)
#define VT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VT_ASAN 1
#endif
#endif
#ifdef VT_ASAN
void __asan_poison_memory_region(void const volatile *addr, size_t size);
void __asan_unpoison_memory_region(void const volatile *addr, size_t size);
#define VT_POISON(p, n) __asan_poison_memory_region((p), (n))
#define VT_UNPOISON(p, n) __asan_unpoison_memory_region((p), (n))
#else
#define VT_POISON(p, n) ((void)(p), (void)(n))
#define VT_UNPOISON(p, n) ((void)(p), (void)(n))
#endif

/* bytes an allocation of n items of `size` bytes takes in the arena (its cache lines) */
#define VT_SCRATCH_BYTES(n, size) ((((size_t)(n) * (size_t)(size)) + (VT_DATA_ALIGN - 1)) & ~(size_t)(VT_DATA_ALIGN - 1))

static inline size_t vt_scratch_mark(const vt_data *d)
{
    return d->arena->top;
}

/* the allocation that does not fit: NULL, the arena failed, the message names it (arena.c) */
void *vt_scratch_refuse(vt_data *d, size_t n, size_t size, const char *name);

/* n items of `size` bytes, named for the message when they do not fit; inline, since an instant
 * takes a dozen of them */
static inline void *vt_scratch_take(vt_data *d, size_t n, size_t size, const char *name)
{
    vt_arena *a = d->arena;
    if (a->failed || (size && n > ((size_t)-1 >> 1) / size) || VT_SCRATCH_BYTES(n, size) > a->size - a->top)
        return vt_scratch_refuse(d, n, size, name);
    char *p = a->base + a->top;
    a->top += VT_SCRATCH_BYTES(n, size);
    a->peak = a->top > a->peak ? a->top : a->peak;
    if (a->poison) VT_UNPOISON(p, n * size); /* the padding up to the next cache line stays poisoned */
    return p;
}
#define VT_SCRATCH(d, type, n, name) ((type *)vt_scratch_take((d), (size_t)(n), sizeof(type), (name)))

/* the rest of the arena, at least `need` items of `size` bytes, as one allocation (LAPACK's
 * workspace: its count into *count) */
void *vt_scratch_rest(vt_data *d, size_t need, size_t size, int *count, const char *name);

static inline void vt_scratch_release(vt_data *d, size_t mark)
{
    vt_arena *a = d->arena;
    if (mark < a->top && a->poison) VT_POISON(a->base + mark, a->top - mark);
    a->top = mark;
    a->failed = 0;
}

/* 1 when every allocation since the mark fitted */
static inline int vt_scratch_ok(const vt_data *d)
{
    return !d->arena->failed;
}

/* the arena's peak use in bytes, and its reset (tests/test_scratch_bounds.c measures each file's
 * bound against it) */
static inline size_t vt_scratch_peak(const vt_data *d)
{
    return d->arena->peak;
}
static inline void vt_scratch_peak_reset(vt_data *d)
{
    d->arena->peak = d->arena->top;
}

/* releases to mark and returns the failure (the message names the allocation) */
vt_status vt_scratch_fail(vt_data *d, size_t mark);

#endif
