/* What the benchmarks share to time and to take medians: the monotonic clock in seconds and an
 * ordering of doubles for qsort. The includer defines _POSIX_C_SOURCE (clock_gettime). */
#ifndef VT_BENCH_TIMING_H
#define VT_BENCH_TIMING_H

#include <time.h>

static inline double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* for qsort: ascending */
static inline int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#endif
