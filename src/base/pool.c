/* A team of threads started once (MuJoCo's mjThreadPool, OpenMP's team): threads − 1 workers
 * that sleep on a condition variable between calls, so that a call creates no thread and a
 * batch of a few rows costs a wake-up, not a thread's creation.
 *
 * A call is open to the workers while the caller runs its part: a worker that wakes joins it by
 * counting itself in `open`; the caller, done with its part (the work's items are then all taken),
 * closes it (sets CLOSED) and waits for those that joined, and a worker that wakes after the
 * close leaves it. So a worker the machine wakes late never delays the caller, and no worker
 * touches a call that has returned. Both wait by spinning for SPIN_NS first — the caller for
 * the workers' last items, a worker for the next call (a log's chunks and a control loop's
 * batches come back to back) — since a wake-up from sleep costs more than that on a virtual
 * machine; then they sleep. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "base/pool.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <time.h>

/* `open` once the caller has closed the call (the lower bits count the workers that joined) */
#define CLOSED 0x40000000

/* how long a thread spins before it sleeps, ns */
#define SPIN_NS 50000

struct vt_pool {
    pthread_mutex_t lock;
    pthread_cond_t go;     /* a new call, or quit */
    pthread_cond_t done;   /* a worker finished its part */
    pthread_t *tid;        /* the workers (nworker) */
    int nworker;
    int quit;              /* under lock: the workers end */
    atomic_ulong call;     /* the number of the last call opened (changed under lock) */
    atomic_int open;       /* the workers joined to the open call, | CLOSED once closed */
    atomic_int finished;   /* the workers of the open call done with it */
    /* the open call, written before it opens */
    vt_pool_fn fn;
    void *ctx;
    int threads;
};

/* a spinning thread's pause (the CPU's hint, where there is one) */
static inline void pause_a_little(void)
{
    for (int i = 0; i < 64; i++) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
    }
}

/* the monotonic clock, ns */
static long long now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (long long)t.tv_sec * 1000000000LL + t.tv_nsec;
}

typedef struct {
    vt_pool *pool;
    int k;
} worker_arg;

/* worker k: asleep until a call opens, then its part if the call is still open, again */
static void *worker(void *arg)
{
    vt_pool *p = ((worker_arg *)arg)->pool;
    const int k = ((worker_arg *)arg)->k;
    free(arg);
    unsigned long seen = 0; /* the last call this worker woke for */
    for (;;) {
        for (const long long t0 = now_ns();
             atomic_load_explicit(&p->call, memory_order_relaxed) == seen && now_ns() - t0 < SPIN_NS;)
            pause_a_little();
        pthread_mutex_lock(&p->lock);
        while (!p->quit && atomic_load_explicit(&p->call, memory_order_relaxed) == seen)
            pthread_cond_wait(&p->go, &p->lock);
        const int quit = p->quit;
        seen = atomic_load_explicit(&p->call, memory_order_relaxed);
        pthread_mutex_unlock(&p->lock);
        if (quit) return NULL;
        int x = atomic_load_explicit(&p->open, memory_order_acquire);
        while (!(x & CLOSED))
            if (atomic_compare_exchange_weak_explicit(&p->open, &x, x + 1, memory_order_acq_rel,
                                                      memory_order_acquire)) {
                /* joined the open call (perhaps one opened after the wake-up: its number is the
                 * current one, which stays until this worker is counted finished) */
                seen = atomic_load_explicit(&p->call, memory_order_relaxed);
                if (k < p->threads) p->fn(p->ctx, k);
                atomic_fetch_add_explicit(&p->finished, 1, memory_order_release);
                pthread_mutex_lock(&p->lock); /* the caller, when it sleeps, sleeps under it */
                pthread_cond_signal(&p->done);
                pthread_mutex_unlock(&p->lock);
                break;
            }
    }
}

vt_pool *vt_pool_create(int threads)
{
    vt_pool *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    if (threads > 1 && !(p->tid = malloc((size_t)(threads - 1) * sizeof *p->tid))) {
        free(p);
        return NULL;
    }
    if (pthread_mutex_init(&p->lock, NULL)) goto no_lock;
    if (pthread_cond_init(&p->go, NULL)) goto no_go;
    if (pthread_cond_init(&p->done, NULL)) goto no_done;
    atomic_init(&p->call, 0);
    atomic_init(&p->open, CLOSED);
    atomic_init(&p->finished, 0);
    for (int k = 1; k < threads; k++) {
        worker_arg *a = malloc(sizeof *a);
        if (!a) break;
        *a = (worker_arg){p, k};
        if (pthread_create(&p->tid[p->nworker], NULL, worker, a)) {
            free(a);
            break;
        }
        p->nworker++;
    }
    return p;
no_done:
    pthread_cond_destroy(&p->go);
no_go:
    pthread_mutex_destroy(&p->lock);
no_lock:
    free(p->tid);
    free(p);
    return NULL;
}

void vt_pool_free(vt_pool *pool)
{
    if (!pool) return;
    pthread_mutex_lock(&pool->lock);
    pool->quit = 1;
    pthread_cond_broadcast(&pool->go);
    pthread_mutex_unlock(&pool->lock);
    for (int k = 0; k < pool->nworker; k++) pthread_join(pool->tid[k], NULL);
    pthread_cond_destroy(&pool->done);
    pthread_cond_destroy(&pool->go);
    pthread_mutex_destroy(&pool->lock);
    free(pool->tid);
    free(pool);
}

int vt_pool_threads(const vt_pool *pool)
{
    return pool ? 1 + pool->nworker : 1;
}

void vt_pool_run(vt_pool *pool, int threads, vt_pool_fn fn, void *ctx)
{
    if (!pool || threads <= 1 || pool->nworker == 0) {
        fn(ctx, 0);
        return;
    }
    pthread_mutex_lock(&pool->lock); /* open the call */
    pool->fn = fn;
    pool->ctx = ctx;
    pool->threads = threads;
    atomic_store_explicit(&pool->finished, 0, memory_order_relaxed);
    atomic_store_explicit(&pool->call, atomic_load_explicit(&pool->call, memory_order_relaxed) + 1,
                          memory_order_relaxed);
    atomic_store_explicit(&pool->open, 0, memory_order_release);
    pthread_cond_broadcast(&pool->go);
    pthread_mutex_unlock(&pool->lock);
    fn(ctx, 0);
    /* closed: the workers that joined are waited for, the late ones leave it */
    const int joined = atomic_fetch_or_explicit(&pool->open, CLOSED, memory_order_acq_rel) & ~CLOSED;
    for (const long long t0 = now_ns();
         atomic_load_explicit(&pool->finished, memory_order_acquire) < joined && now_ns() - t0 < SPIN_NS;)
        pause_a_little();
    if (atomic_load_explicit(&pool->finished, memory_order_acquire) < joined) {
        pthread_mutex_lock(&pool->lock);
        while (atomic_load_explicit(&pool->finished, memory_order_acquire) < joined)
            pthread_cond_wait(&pool->done, &pool->lock);
        pthread_mutex_unlock(&pool->lock);
    }
}
