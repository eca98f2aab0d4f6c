/* vtdyn — One allocation carved into arrays (base/block.c): the model's block (model/model.c), the
 * data's (analysis/data.c) and a trajectory's (analysis/trajectory.c). */
#ifndef VT_BASE_BLOCK_H
#define VT_BASE_BLOCK_H

#include <stddef.h>

/* A block being carved: base (NULL in the sizing pass), the bytes used so far from base, the
 * alignment of every array's offset (a power of two), and whether a size wrapped. The same calls
 * made twice, first with base NULL to count the bytes, then with the allocation, give the same
 * offsets: the first pass's used is the allocation's size. Each array starts on an offset that is
 * a multiple of align; its address is aligned as well when base is (calloc: 16 bytes; data.c
 * moves base to VT_DATA_ALIGN). */
typedef struct {
    char *base;
    size_t used;
    size_t align;
    int overflow; /* set (and kept) when a take's n x size, or used past it, does not fit in size_t */
} vt_block;

/* The next n x size bytes: used rounded up to a multiple of align, then advanced by n x size;
 * returns base + that offset, or NULL in the sizing pass (base NULL). n = 0 is allowed (an empty
 * array at an aligned offset). A size that does not fit in size_t sets overflow, leaves used at
 * SIZE_MAX and returns NULL: the sizing pass's caller checks overflow before it allocates. */
void *vt_block_take(vt_block *b, size_t n, size_t size);

#endif
