/* The command's threads (cmd/parallel.c): a range of rows cut into blocks that the batch's
 * threads (vt_batch_run: started once with the batch) take in turn, for the
 * work around the batch's rows (parsing the input's numbers, formatting the output's). Each
 * block has its own buffers, written in order, so the rows' bytes never depend on the threads. */
#ifndef VTDYN_CMD_PARALLEL_H
#define VTDYN_CMD_PARALLEL_H

#include <locale.h>

#include "vtdyn.h"

/* the run's threads: the batch's */
typedef struct {
    vt_batch *batch;
    int nblock;    /* the blocks a range is cut into: 4 a thread (one on one thread), so that a
                    * thread the machine slows takes fewer */
    locale_t c;    /* the C locale every block runs in (numbers with a '.' whatever LC_NUMERIC) */
} team;

/* the team of the batch's threads; 0, or 1 out of memory (t then holds nothing to free) */
int team_make(team *t, vt_batch *batch);

/* frees what the team made (a zeroed team is allowed; the batch is the caller's) */
void team_free(team *t);

/* the blocks a range of n rows is cut into: at most t->nblock, none empty */
int team_blocks(const team *t, int n);

/* one block's work: rows [first, end), block number k */
typedef void (*block_fn)(void *ctx, int first, int end, int k);

/* calls fn on the team_blocks(t, n) blocks of [0, n) (block k: rows ⌊k n/B⌋ … ⌊(k+1) n/B⌋ − 1),
 * each once, on the team's threads, each block under the C locale; returns when all are done */
void parallel_blocks(const team *t, int n, block_fn fn, void *ctx);

#endif
