/* One allocation carved into aligned arrays (base/block.h): the sizing pass and the carving pass
 * are the same calls, with base NULL and then with the allocation; a size that would wrap marks
 * the block instead. */
#include <stddef.h>

#include "base/block.h"
#include "base/checked.h"

void *vt_block_take(vt_block *b, size_t n, size_t size)
{
    size_t at, bytes, end;
    if (b->overflow || !vt_size_add(&at, b->used, b->align - 1) || !vt_size_mul(&bytes, n, size) ||
        !vt_size_add(&end, at & ~(b->align - 1), bytes)) {
        b->overflow = 1;
        b->used = SIZE_MAX;
        return NULL;
    }
    at &= ~(b->align - 1);
    void *p = b->base ? b->base + at : NULL;
    b->used = end;
    return p;
}
