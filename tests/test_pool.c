/* src/base/pool.c: a team of threads started once. Every item of a call is run once and only
 * once, by runners numbered below the call's threads (the caller 0), over thousands of calls
 * back to back and after pauses long enough for the workers to sleep; no worker touches a call
 * that has returned (each call's context is marked closed after it returns and a runner that
 * meets a closed one counts it); a call of one thread stays on the caller's; a NULL pool runs
 * the work on the caller's; pools freed with their workers asleep, spinning, or never called; a
 * forked child's calls run on its one thread. */
#define _POSIX_C_SOURCE 200809L /* nanosleep */
#include <pthread.h>
#include <stdatomic.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "base/pool.h"
#include "vt_test.h"

#define MAX_ITEMS 512

/* one call: items taken from a counter, each item's runs counted */
typedef struct {
    atomic_int next;
    int nitem, threads;
    atomic_int runs[MAX_ITEMS];
    atomic_int bad_runner; /* runs by a runner numbered at or above the call's threads */
    atomic_int closed;     /* set after the call returned */
    atomic_int late;       /* runners that met the call closed */
    pthread_t caller;
    atomic_int off_caller; /* runner 0 not on the caller's thread */
} call_ctx;

static void work(void *arg, int k)
{
    call_ctx *c = arg;
    if (atomic_load(&c->closed)) atomic_fetch_add(&c->late, 1);
    if (k < 0 || k >= c->threads) atomic_fetch_add(&c->bad_runner, 1);
    if (k == 0 && !pthread_equal(pthread_self(), c->caller)) atomic_fetch_add(&c->off_caller, 1);
    for (int i; (i = atomic_fetch_add(&c->next, 1)) < c->nitem;) {
        atomic_fetch_add(&c->runs[i], 1);
        if (i % 7 == 0) /* some items take longer, so that workers have some left to take */
            for (volatile int spin = 0; spin < 2000; spin++) {
            }
    }
    if (atomic_load(&c->closed)) atomic_fetch_add(&c->late, 1);
}

/* calls of a pool of `threads`, each with its own context (kept, so that a late runner would be
 * counted, not crash) */
static void run_calls(vt_pool *p, int threads, int ncall)
{
    call_ctx *ctx = calloc((size_t)ncall, sizeof *ctx);
    assert_non_null(ctx);
    for (int n = 0; n < ncall; n++) {
        call_ctx *c = &ctx[n];
        c->nitem = (n * 37) % MAX_ITEMS;
        c->threads = 1 + n % threads;
        c->caller = pthread_self();
        vt_pool_run(p, c->threads, work, c);
        atomic_store(&c->closed, 1);
        for (int i = 0; i < c->nitem; i++) assert_int_equal(atomic_load(&c->runs[i]), 1);
        for (int i = c->nitem; i < MAX_ITEMS; i++) assert_int_equal(atomic_load(&c->runs[i]), 0);
        if (n % 500 == 499) { /* the workers fall asleep */
            const struct timespec pause = {0, 3000000};
            nanosleep(&pause, NULL);
        }
    }
    const struct timespec pause = {0, 20000000}; /* any late runner has run by now */
    nanosleep(&pause, NULL);
    for (int n = 0; n < ncall; n++) {
        assert_int_equal(atomic_load(&ctx[n].late), 0);
        assert_int_equal(atomic_load(&ctx[n].bad_runner), 0);
        assert_int_equal(atomic_load(&ctx[n].off_caller), 0);
    }
    free(ctx);
}

static void test_every_item_once(void **state)
{
    (void)state;
    const int threads[3] = {2, 3, 8};
    for (int t = 0; t < 3; t++) {
        vt_pool *p = vt_pool_create(threads[t]);
        assert_non_null(p);
        assert_int_equal(vt_pool_threads(p), threads[t]);
        run_calls(p, threads[t], 3000);
        vt_pool_free(p);
    }
}

/* one thread, a NULL pool, and a call of one thread on a pool: the caller's thread alone */
static void test_caller_alone(void **state)
{
    (void)state;
    assert_int_equal(vt_pool_threads(NULL), 1);
    call_ctx *c = calloc(1, sizeof *c);
    assert_non_null(c);
    c->nitem = 100;
    c->threads = 1;
    c->caller = pthread_self();
    vt_pool_run(NULL, 4, work, c); /* a NULL pool: 4 asked, the caller's alone (runner 0) */
    for (int i = 0; i < 100; i++) assert_int_equal(atomic_load(&c->runs[i]), 1);
    assert_int_equal(atomic_load(&c->bad_runner), 0);
    vt_pool *p = vt_pool_create(1);
    assert_non_null(p);
    assert_int_equal(vt_pool_threads(p), 1);
    run_calls(p, 1, 50);
    vt_pool_free(p);
    free(c);
}

/* pools freed with their workers never called, spinning just after a call, and asleep */
static void test_freed(void **state)
{
    (void)state;
    vt_pool_free(NULL);
    vt_pool_free(vt_pool_create(8));
    vt_pool *p = vt_pool_create(4);
    assert_non_null(p);
    run_calls(p, 4, 10);
    vt_pool_free(p);
    p = vt_pool_create(4);
    assert_non_null(p);
    run_calls(p, 4, 10);
    const struct timespec pause = {0, 5000000};
    nanosleep(&pause, NULL);
    vt_pool_free(p);
}

/* a pool used, then the process forked (Python's multiprocessing does so): the child has the
 * pool but not its workers, and its calls run every item on the caller's thread */
static void test_forked(void **state)
{
    (void)state;
    vt_pool *p = vt_pool_create(4);
    assert_non_null(p);
    run_calls(p, 4, 20);
    const pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        call_ctx *c = calloc(1, sizeof *c);
        int ok = c != NULL;
        for (int n = 0; n < 100 && ok; n++) {
            memset(c, 0, sizeof *c);
            c->nitem = 300;
            c->threads = 4;
            c->caller = pthread_self();
            vt_pool_run(p, 4, work, c);
            for (int i = 0; i < c->nitem; i++) ok &= atomic_load(&c->runs[i]) == 1;
        }
        _exit(ok ? 0 : 1);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    run_calls(p, 4, 20); /* the parent's workers are still there */
    vt_pool_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_item_once),
        cmocka_unit_test(test_caller_alone),
        cmocka_unit_test(test_freed),
        cmocka_unit_test(test_forked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
