/* The command's threads: the blocks of a range taken in turn, from a shared counter, by the
 * batch's threads (vt_batch_run: a worker that wakes after the last block is taken takes none,
 * so every block is run by whoever is there). */
#define _POSIX_C_SOURCE 200809L /* newlocale, uselocale */
#include "parallel.h"

#include <stdatomic.h>

int team_make(team *t, vt_batch *batch)
{
    *t = (team){0};
    t->c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!t->c) return 1;
    t->batch = batch;
    const int T = vt_batch_threads(batch);
    t->nblock = T > 1 ? 4 * T : 1;
    return 0;
}

void team_free(team *t)
{
    if (t->c) freelocale(t->c);
    *t = (team){0};
}

int team_blocks(const team *t, int n)
{
    return n < t->nblock ? n : t->nblock;
}

/* one call's blocks and the counter its runners take them from */
typedef struct {
    block_fn fn;
    void *ctx;
    int n, B;
    locale_t c;
    atomic_int next;
} blocks;

/* a runner (the caller's thread, or a worker): block after block until none is left */
static void run_blocks(void *arg, int runner)
{
    (void)runner;
    blocks *b = arg;
    const locale_t old = uselocale(b->c);
    for (int k; (k = atomic_fetch_add_explicit(&b->next, 1, memory_order_relaxed)) < b->B;)
        b->fn(b->ctx, (int)((long long)k * b->n / b->B), (int)((long long)(k + 1) * b->n / b->B), k);
    uselocale(old);
}

void parallel_blocks(const team *t, int n, block_fn fn, void *ctx)
{
    const int B = team_blocks(t, n);
    if (B <= 0) return;
    blocks b = {fn, ctx, n, B, t->c, 0};
    atomic_init(&b.next, 0);
    if (B == 1) run_blocks(&b, 0); /* one block: no worker woken */
    else vt_batch_run(t->batch, run_blocks, &b);
}
