/* The command's threads (cmd/parallel.c): a range of rows shared among threads in contiguous
 * blocks, for the work around the library's batch (parsing the input's numbers, formatting the
 * output's) so that the rows' bytes never depend on the number of threads. */
#ifndef VTDYN_CMD_PARALLEL_H
#define VTDYN_CMD_PARALLEL_H

/* one block's work: rows [first, end) of the call's range, block number k */
typedef void (*block_fn)(void *ctx, int first, int end, int k);

/* calls fn on the T blocks of [0, n) (block k: rows ⌊k n/T⌋ … ⌊(k+1) n/T⌋ − 1; empty blocks are
 * not called): block 0 on the caller's thread, the others on threads created for the call and
 * joined before it returns (a block whose thread cannot be created runs on the caller's). Every
 * block runs in the C locale (numbers with a '.' whatever LC_NUMERIC). */
void parallel_blocks(int T, int n, block_fn fn, void *ctx);

#endif
