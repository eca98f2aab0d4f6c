/* The command's threads: contiguous blocks of rows on threads made for the call (as the
 * library's batches share their rows), each in the C locale. */
#define _POSIX_C_SOURCE 200809L /* newlocale, uselocale */
#include "parallel.h"

#include <locale.h>
#include <pthread.h>
#include <stdlib.h>

typedef struct {
    block_fn fn;
    void *ctx;
    int first, end, k;
} block;

/* one block under the C locale (made once a block; newlocale is cheap next to a block's rows) */
static void *run_block(void *arg)
{
    const block *b = arg;
    locale_t c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    const locale_t old = c ? uselocale(c) : (locale_t)0;
    b->fn(b->ctx, b->first, b->end, b->k);
    if (c) {
        uselocale(old);
        freelocale(c);
    }
    return NULL;
}

void parallel_blocks(int T, int n, block_fn fn, void *ctx)
{
    if (n <= 0) return;
    if (T < 1) T = 1;
    if (T > n) T = n;
    block *b = malloc((size_t)T * sizeof *b);
    pthread_t *tid = malloc((size_t)T * sizeof *tid);
    int *started = calloc((size_t)T, sizeof *started);
    if (!b || !tid || !started) { /* no room for the threads' records: every block here, in turn */
        free(b);
        free(tid);
        free(started);
        for (int k = 0; k < T; k++) {
            const block one = {fn, ctx, (int)((long long)k * n / T), (int)((long long)(k + 1) * n / T), k};
            run_block((void *)&one);
        }
        return;
    }
    for (int k = 0; k < T; k++)
        b[k] = (block){fn, ctx, (int)((long long)k * n / T), (int)((long long)(k + 1) * n / T), k};
    for (int k = 1; k < T; k++) started[k] = pthread_create(&tid[k], NULL, run_block, &b[k]) == 0;
    run_block(&b[0]);
    for (int k = 1; k < T; k++) {
        if (started[k]) pthread_join(tid[k], NULL);
        else run_block(&b[k]);
    }
    free(b);
    free(tid);
    free(started);
}
