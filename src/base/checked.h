/* vtdyn — Sizes counted in size_t with every sum and product checked: a size that would wrap is
 * reported, never used (the model's block, the builder's arrays, the data's layout). */
#ifndef VT_BASE_CHECKED_H
#define VT_BASE_CHECKED_H

#include <stddef.h>
#include <stdint.h>

/* *r = a + b; 1, or 0 (and *r = SIZE_MAX) when the sum does not fit in size_t */
static inline int vt_size_add(size_t *r, size_t a, size_t b)
{
    if (a > SIZE_MAX - b) {
        *r = SIZE_MAX;
        return 0;
    }
    *r = a + b;
    return 1;
}

/* *r = a b; 1, or 0 (and *r = SIZE_MAX) when the product does not fit in size_t */
static inline int vt_size_mul(size_t *r, size_t a, size_t b)
{
    if (b != 0 && a > SIZE_MAX / b) {
        *r = SIZE_MAX;
        return 0;
    }
    *r = a * b;
    return 1;
}

/* *r = a + b for counts that must stay within limit (a, b >= 0): 1, or 0 (*r unchanged) when
 * the sum passes limit */
static inline int vt_count_add(int *r, int a, int b, int limit)
{
    if (b > limit || a > limit - b) return 0;
    *r = a + b;
    return 1;
}

#endif
