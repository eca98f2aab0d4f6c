/* One allocation carved into aligned arrays (base/block.h): the sizing pass and the carving pass
 * are the same calls, with base NULL and then with the allocation. */
#include <stddef.h>

#include "base/block.h"

void *vt_block_take(vt_block *b, size_t n, size_t size)
{
    b->used = (b->used + (b->align - 1)) & ~(b->align - 1);
    void *p = b->base ? b->base + b->used : NULL;
    b->used += n * size;
    return p;
}
