/* Batches: vt_inverse_dynamics_motion() on many states, the rows shared among threads.
 *
 * Each thread owns one data, made once with the batch; a call creates its threads, gives each a
 * contiguous block of rows (thread k: rows ⌊k n/T⌋ … ⌊(k+1) n/T⌋ − 1, the caller's thread the
 * first block) and joins them. A row is solved from its own inputs alone — q, q̇, q̈ and qfrc
 * copied into the thread's data, xfrc zero — so its results do not depend on the rows solved
 * before it on that data, nor on the number of threads: bitwise those of the single call. Each
 * thread keeps its first failure; the call reports the lowest row among them.
 */
#define _GNU_SOURCE /* sched_getaffinity: the CPUs the process may run on */
#include "analysis/batch.h"
#include "dense/reactions.h"

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/status.h"

struct vt_batch {
    const vt_model *model;
    int threads;
    int stop_on_error;
    vt_data **data;      /* one per thread */
    int failed_row;      /* the last call's failing row of lowest index, or −1 */
    char message[VT_MESSAGE_SIZE];
};

/* one thread's share of a call */
typedef struct {
    vt_batch *batch;
    const vt_batch_io *io;
    vt_data *d;
    int first, end;      /* rows [first, end) */
    atomic_int *stop;    /* set by a failing row when the batch stops on errors */
    int failed;          /* the block's first failing row, or −1 */
    vt_status status;    /* its status */
} share;

vt_batch_def vt_default_batch_def(void)
{
    return (vt_batch_def){.threads = 0, .stop_on_error = 0};
}

/* the CPUs this process may run on (its affinity), at least 1 */
static int cpus(void)
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0) {
        const int n = CPU_COUNT(&set);
        if (n > 0) return n;
    }
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 && n < 4096 ? (int)n : 1;
}

void vt_batch_free(vt_batch *batch)
{
    if (!batch) return;
    if (batch->data)
        for (int k = 0; k < batch->threads; k++) vt_data_free(batch->data[k]);
    free(batch->data);
    free(batch);
}

vt_status vt_batch_create(vt_batch **batch, const vt_model *model, const vt_batch_def *def)
{
    if (batch) *batch = NULL;
    if (!batch || !model) return VT_ERR_NULL;
    const vt_batch_def dd = def ? *def : vt_default_batch_def();
    if (dd.threads < 0 || (dd.stop_on_error != 0 && dd.stop_on_error != 1)) return VT_ERR_BAD_OPTION;
    vt_batch *b = calloc(1, sizeof *b);
    if (!b) return VT_ERR_NO_MEMORY;
    b->model = model;
    b->threads = dd.threads ? dd.threads : cpus();
    b->stop_on_error = dd.stop_on_error;
    b->failed_row = -1;
    b->data = calloc((size_t)b->threads, sizeof *b->data);
    if (!b->data) {
        free(b);
        return VT_ERR_NO_MEMORY;
    }
    for (int k = 0; k < b->threads; k++) {
        const vt_status st = vt_data_create(&b->data[k], model);
        if (st) {
            vt_batch_free(b);
            return st;
        }
    }
    *batch = b;
    return VT_OK;
}

int vt_batch_threads(const vt_batch *batch)
{
    return batch ? batch->threads : 0;
}

int vt_batch_failed_row(const vt_batch *batch)
{
    return batch ? batch->failed_row : -1;
}

const char *vt_batch_message(const vt_batch *batch)
{
    return batch ? batch->message : "";
}

/* row r of X (stride s, 0: packed rows of len) */
static inline const double *in_row(const double *x, size_t s, size_t len, int r)
{
    return x + (size_t)r * (s ? s : len);
}
static inline double *out_row(double *x, size_t s, size_t len, int r)
{
    return x + (size_t)r * (s ? s : len);
}

/* a body's two 3-vectors of each joint (arrays 3 (nbody+1)) as its 6 values (f, n) of the row */
static void wrenches(double *out, const double *f, const double *n, int nbody)
{
    for (int i = 1; i <= nbody; i++) {
        memcpy(out + 6 * (i - 1), f + 3 * i, 3 * sizeof(double));
        memcpy(out + 6 * (i - 1) + 3, n + 3 * i, 3 * sizeof(double));
    }
}

/* row r solved on d and its results written; its status */
static vt_status solve_row(const vt_model *m, vt_data *d, const vt_batch_io *io, int r)
{
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb = (size_t)m->nbody;
    memcpy(d->q, in_row(io->q, io->q_stride, nq, r), nq * sizeof(double));
    memcpy(d->qd, in_row(io->qd, io->qd_stride, nv, r), nv * sizeof(double));
    memcpy(d->qdd, in_row(io->qdd, io->qdd_stride, nv, r), nv * sizeof(double));
    if (io->qfrc) memcpy(d->qfrc, in_row(io->qfrc, io->qfrc_stride, nv, r), nv * sizeof(double));
    else memset(d->qfrc, 0, nv * sizeof(double));
    const vt_status st = vt_inverse_dynamics_motion(m, d);
    if (st) return st;
    if (io->effort) memcpy(out_row(io->effort, io->effort_stride, nv, r), d->qfrc_drive, nv * sizeof(double));
    if (io->drive_effort && m->ndrive > 0)
        memcpy(out_row(io->drive_effort, io->drive_effort_stride, (size_t)m->ndrive, r), d->drive_effort,
               (size_t)m->ndrive * sizeof(double));
    if (io->qdd_out) memcpy(out_row(io->qdd_out, io->qdd_out_stride, nv, r), d->qdd, nv * sizeof(double));
    if (io->reaction)
        wrenches(out_row(io->reaction, io->reaction_stride, 6 * nb, r), d->jnt_force, d->jnt_moment, m->nbody);
    if (io->reaction_body)
        wrenches(out_row(io->reaction_body, io->reaction_body_stride, 6 * nb, r), d->jnt_force_body,
                 d->jnt_moment_body, m->nbody);
    if (io->total)
        wrenches(out_row(io->total, io->total_stride, 6 * nb, r), d->jnt_force_total, d->jnt_moment_total, m->nbody);
    if (io->total_body)
        wrenches(out_row(io->total_body, io->total_body_stride, 6 * nb, r), d->jnt_force_total_body,
                 d->jnt_moment_total_body, m->nbody);
    if (io->effort_parts) {
        double *p = out_row(io->effort_parts, io->effort_parts_stride, 3 * nv, r);
        memcpy(p, d->effort_armature, nv * sizeof(double));
        memcpy(p + nv, d->effort_damping, nv * sizeof(double));
        memcpy(p + 2 * nv, d->effort_friction, nv * sizeof(double));
    }
    if (io->reaction_joint || io->bearing) vt_joint_frames(m, d); /* on demand: the instants leave them */
    if (io->reaction_joint)
        wrenches(out_row(io->reaction_joint, io->reaction_joint_stride, 6 * nb, r), d->jnt_force_joint,
                 d->jnt_moment_joint, m->nbody);
    if (io->bearing)
        memcpy(out_row(io->bearing, io->bearing_stride, 4 * nb, r), d->jnt_bearing + 4, 4 * nb * sizeof(double));
    if (io->limit_excess)
        memcpy(out_row(io->limit_excess, io->limit_excess_stride, 3 * nv, r), d->limit_excess, 3 * nv * sizeof(double));
    return VT_OK;
}

/* a thread's block of rows */
static void *run_share(void *arg)
{
    share *s = arg;
    const vt_batch *b = s->batch;
    for (int r = s->first; r < s->end; r++) {
        vt_status st = VT_ERR_SKIPPED;
        if (!b->stop_on_error || !atomic_load_explicit(s->stop, memory_order_relaxed))
            st = solve_row(b->model, s->d, s->io, r);
        if (st && st != VT_ERR_SKIPPED && s->failed < 0) {
            s->failed = r;
            s->status = st;
            if (b->stop_on_error) atomic_store_explicit(s->stop, 1, memory_order_relaxed);
        }
        if (s->io->status) s->io->status[r] = st;
    }
    return NULL;
}

/* the arguments: every required array with rows, every stride at least its row */
static vt_status check_io(vt_batch *b, const vt_batch_io *io)
{
    const vt_model *m = b->model;
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody;
    if (io->nrow < 0) return vt_fail(b->message, VT_ERR_BAD_SIZE, "vt_batch: nrow %d < 0", io->nrow);
    if (io->nrow > 0 && (!io->q || !io->qd || !io->qdd))
        return vt_fail(b->message, VT_ERR_NULL, "vt_batch: q, qd and qdd are required");
    const struct {
        const char *name;
        int given;
        size_t stride, len;
    } a[] = {{"q", 1, io->q_stride, nq},
             {"qd", 1, io->qd_stride, nv},
             {"qdd", 1, io->qdd_stride, nv},
             {"qfrc", io->qfrc != NULL, io->qfrc_stride, nv},
             {"effort", io->effort != NULL, io->effort_stride, nv},
             {"drive_effort", io->drive_effort != NULL, io->drive_effort_stride, (size_t)m->ndrive},
             {"qdd_out", io->qdd_out != NULL, io->qdd_out_stride, nv},
             {"reaction", io->reaction != NULL, io->reaction_stride, nb6},
             {"reaction_body", io->reaction_body != NULL, io->reaction_body_stride, nb6},
             {"total", io->total != NULL, io->total_stride, nb6},
             {"total_body", io->total_body != NULL, io->total_body_stride, nb6},
             {"effort_parts", io->effort_parts != NULL, io->effort_parts_stride, 3 * nv},
             {"reaction_joint", io->reaction_joint != NULL, io->reaction_joint_stride, nb6},
             {"bearing", io->bearing != NULL, io->bearing_stride, 4 * (size_t)m->nbody},
             {"limit_excess", io->limit_excess != NULL, io->limit_excess_stride, 3 * nv}};
    for (size_t k = 0; k < sizeof a / sizeof a[0]; k++)
        if (a[k].given && a[k].stride != 0 && a[k].stride < a[k].len)
            return vt_fail(b->message, VT_ERR_BAD_SIZE, "vt_batch: %s_stride %zu below its row's %zu values",
                           a[k].name, a[k].stride, a[k].len);
    return VT_OK;
}

vt_status vt_batch_inverse_dynamics_motion(vt_batch *batch, const vt_batch_io *io)
{
    if (!batch) return VT_ERR_NULL;
    batch->failed_row = -1;
    batch->message[0] = '\0';
    if (!io) return vt_fail(batch->message, VT_ERR_NULL, "vt_batch: io is NULL");
    vt_status st = check_io(batch, io);
    if (st) return st;
    const int n = io->nrow, T = batch->threads < n ? batch->threads : (n > 0 ? n : 1);
    share shares[T > 0 ? T : 1];
    pthread_t tid[T > 0 ? T : 1];
    int started[T > 0 ? T : 1];
    atomic_int stop;
    atomic_init(&stop, 0);
    for (int k = 0; k < T; k++) {
        shares[k] = (share){.batch = batch, .io = io, .d = batch->data[k], .stop = &stop, .failed = -1,
                            .first = (int)((long long)k * n / T), .end = (int)((long long)(k + 1) * n / T)};
        started[k] = 0;
    }
    /* the other blocks on threads of their own; a thread that cannot be created leaves its block
     * to the caller's thread */
    for (int k = 1; k < T; k++) started[k] = pthread_create(&tid[k], NULL, run_share, &shares[k]) == 0;
    run_share(&shares[0]);
    for (int k = 1; k < T; k++) {
        if (started[k]) pthread_join(tid[k], NULL);
        else run_share(&shares[k]);
    }
    for (int k = 0; k < T; k++) { /* the blocks are in row order: the first failure is the lowest */
        if (shares[k].failed < 0) continue;
        batch->failed_row = shares[k].failed;
        return vt_fail(batch->message, shares[k].status, "row %d: %s", shares[k].failed, shares[k].d->message);
    }
    return VT_OK;
}
