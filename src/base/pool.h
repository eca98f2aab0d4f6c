/* vtdyn — A team of threads started once, for work shared among threads (base/pool.c): a
 * batch's rows, and the caller's own work on the batch's threads (vt_batch_run). */
#ifndef VT_BASE_POOL_H
#define VT_BASE_POOL_H

/* the work of one call, run by the caller's thread (k = 0) and by each worker that joins the
 * call (k its number, 1 ... threads − 1). How many join is not known ahead (a worker that wakes
 * after the caller is done takes no part), so the work shares its items itself: each runner
 * takes the next item from a counter the work owns, until none is left. */
typedef void (*vt_pool_fn)(void *ctx, int k);

typedef struct vt_pool vt_pool;

/* a pool of threads − 1 workers, asleep until a call (the caller's thread is the first of the
 * threads); NULL when out of memory. A worker the system refuses leaves the pool fewer
 * (vt_pool_threads). */
vt_pool *vt_pool_create(int threads);

/* ends the workers and frees the pool (NULL is allowed); no call may be running */
void vt_pool_free(vt_pool *pool);

/* the caller's thread and the workers: 1 for a NULL pool */
int vt_pool_threads(const vt_pool *pool);

/* fn(ctx, 0) on the caller's thread and fn(ctx, k) on each worker k < threads that wakes while
 * the caller runs its part; returns once every worker that joined has returned. One call at a
 * time on a pool; with threads ≤ 1 (or a NULL pool) fn(ctx, 0) alone, no worker woken. */
void vt_pool_run(vt_pool *pool, int threads, vt_pool_fn fn, void *ctx);

#endif
