/* Batches: vt_inverse_dynamics_motion() on many states (with contacts
 * vt_inverse_dynamics_contacts()), the rows shared among threads.
 *
 * Each thread owns one data (and one contact set, its workspace), made once with the batch, as
 * are its threads: the caller's and a pool's workers (base/pool.c), asleep between calls. The
 * threads take the rows in blocks of BATCH_BLOCK, the next block from a shared counter, so that a
 * thread slowed by the machine's other work takes fewer rows, and a worker that wakes after the
 * last block is taken none. A row is solved from its own inputs alone — q, q̇, q̈, qfrc and the
 * time copied into the thread's data, xfrc zero — so its results do not depend on the rows
 * solved before it on that data, nor on which thread solved it or how many there are: bitwise
 * those of the single call. A thread takes its blocks in increasing order, so its first failure
 * is its lowest; the call reports the lowest row among the threads'.
 *
 * Wrenches at frames (io->load) go into the row's instant as its passes carry xfrc, between the
 * outward pass (which has the frames' places) and the inward one (vt_motion_loaded); with loops
 * or couplings, into xfrc for the dense stages once the poses are known (vt_motion_rows); with
 * contacts, before the ground's forces are shared (vt_contacts_inverse), which then balance the
 * loads too.
 */
#define _GNU_SOURCE /* sched_getaffinity: the CPUs the process may run on */
#include "analysis/batch.h"
#include "analysis/contact.h"
#include "analysis/contact_rule.h"
#include "dense/reactions.h"

#include <sched.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/pool.h"
#include "base/status.h"
#include "recursive/fused.h"

/* the rows a thread takes at a time: enough that the shared counter is touched seldom (a row
 * takes 0.1 µs and more), few enough that the threads end together */
#define BATCH_BLOCK 16

/* one thread's share of a call */
typedef struct share {
    struct vt_batch *batch;
    const vt_batch_io *io;
    vt_data *d;
    vt_contacts *contacts; /* the thread's, or NULL */
    atomic_llong *next;  /* the next block's first row, shared (64 bits: it passes nrow) */
    atomic_int *stop;    /* set by a failing row when the batch stops on errors */
    int failed;          /* the thread's first failing row, or −1 */
    vt_status status;    /* its status */
    char message[VT_MESSAGE_SIZE]; /* its message (the data's is overwritten by the rows after) */
} share;

struct vt_batch {
    const vt_model *model;
    int threads;
    int stop_on_error;
    vt_data **data;      /* one per thread asked for (ndata; threads may be fewer) */
    int ndata;
    vt_contacts **contacts; /* with contacts: one set per thread (its workspace), else NULL */
    int ncontact;        /* 0 without */
    struct share *shares; /* the threads' shares of a call: the caller's 0, worker k's k */
    vt_pool *pool;       /* the workers (NULL on one thread) */
    atomic_int busy;     /* a call is running (a second one, from its work or another thread, is
                          * refused: the pool runs one call at a time) */
    int failed_row;      /* the last call's failing row of lowest index, or −1 */
    char message[VT_MESSAGE_SIZE];
};

vt_batch_def vt_default_batch_def(void)
{
    return (vt_batch_def){.threads = 0, .stop_on_error = 0, .contacts = NULL, .ncontact = 0, .effort_weight = NULL};
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
        for (int k = 0; k < batch->ndata; k++) vt_data_free(batch->data[k]);
    if (batch->contacts)
        for (int k = 0; k < batch->ndata; k++) vt_contacts_free(batch->contacts[k]);
    free(batch->data);
    free(batch->contacts);
    free(batch->shares);
    vt_pool_free(batch->pool);
    free(batch);
}

vt_status vt_batch_create(vt_batch **batch, const vt_model *model, const vt_batch_def *def)
{
    if (batch) *batch = NULL;
    if (!batch || !model) return VT_ERR_NULL;
    const vt_batch_def dd = def ? *def : vt_default_batch_def();
    if (dd.threads < 0 || (dd.stop_on_error != 0 && dd.stop_on_error != 1) || dd.ncontact < 0 ||
        (dd.ncontact > 0 && !dd.contacts))
        return VT_ERR_BAD_OPTION;
    vt_batch *b = calloc(1, sizeof *b);
    if (!b) return VT_ERR_NO_MEMORY;
    b->model = model;
    b->threads = b->ndata = dd.threads ? dd.threads : cpus();
    b->stop_on_error = dd.stop_on_error;
    b->failed_row = -1;
    atomic_init(&b->busy, 0);
    b->data = calloc((size_t)b->threads, sizeof *b->data);
    b->shares = malloc((size_t)b->threads * sizeof *b->shares);
    if (!b->data || !b->shares) {
        vt_batch_free(b);
        return VT_ERR_NO_MEMORY;
    }
    if (dd.ncontact > 0 && !(b->contacts = calloc((size_t)b->threads, sizeof *b->contacts))) {
        vt_batch_free(b);
        return VT_ERR_NO_MEMORY;
    }
    b->ncontact = dd.ncontact;
    for (int k = 0; k < b->threads; k++) {
        vt_status st = vt_data_create(&b->data[k], model);
        if (!st && dd.ncontact > 0)
            st = vt_contacts_create(&b->contacts[k], model, dd.contacts, dd.ncontact, dd.effort_weight, NULL);
        if (st) {
            vt_batch_free(b);
            return st;
        }
    }
    if (b->threads > 1) { /* a worker the system refuses leaves the batch fewer threads */
        if (!(b->pool = vt_pool_create(b->threads))) {
            vt_batch_free(b);
            return VT_ERR_NO_MEMORY;
        }
        b->threads = vt_pool_threads(b->pool);
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

/* row r solved on d (with the contacts c, or NULL) and its results written; its status */
static vt_status solve_row(const vt_model *m, vt_data *d, vt_contacts *c, const vt_batch_io *io, int r)
{
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb = (size_t)m->nbody;
    memcpy(d->q, in_row(io->q, io->q_stride, nq, r), nq * sizeof(double));
    memcpy(d->qd, in_row(io->qd, io->qd_stride, nv, r), nv * sizeof(double));
    memcpy(d->qdd, in_row(io->qdd, io->qdd_stride, nv, r), nv * sizeof(double));
    if (io->qfrc) memcpy(d->qfrc, in_row(io->qfrc, io->qfrc_stride, nv, r), nv * sizeof(double));
    else memset(d->qfrc, 0, nv * sizeof(double));
    d->time = io->time ? *in_row(io->time, io->time_stride, 1, r) : 0.0;
    vt_status st;
    const vt_frame_loads loads = {io->nload, io->load_frame,
                                  io->nload > 0 ? in_row(io->load, io->load_stride, 6 * (size_t)io->nload, r) : NULL};
    if (c) {
        const size_t nc = (size_t)vt_contacts_count(c);
        const size_t as = io->contact_active_stride ? io->contact_active_stride : nc;
        const int *active = io->contact_active ? io->contact_active + (size_t)r * as : NULL;
        double *force = io->contact_force ? out_row(io->contact_force, io->contact_force_stride, 3 * nc, r) : NULL;
        st = vt_contacts_inverse(m, d, c, active, force, io->nload > 0 ? &loads : NULL);
    } else {
        st = vt_motion_loaded(m, d, io->nload > 0 ? &loads : NULL);
    }
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
    if (io->reaction_joint || io->bearing) /* on demand: the instants leave them */
        vt_joint_frames(m, d, io->bearing != NULL);
    if (io->reaction_joint)
        wrenches(out_row(io->reaction_joint, io->reaction_joint_stride, 6 * nb, r), d->jnt_force_joint,
                 d->jnt_moment_joint, m->nbody);
    if (io->bearing)
        memcpy(out_row(io->bearing, io->bearing_stride, 4 * nb, r), d->jnt_bearing + 4, 4 * nb * sizeof(double));
    if (io->limit_excess)
        memcpy(out_row(io->limit_excess, io->limit_excess_stride, 3 * nv, r), d->limit_excess, 3 * nv * sizeof(double));
    return VT_OK;
}

/* runner k's rows (its share of the call): block after block from the shared counter until none
 * is left */
static void run_share(void *arg, int k)
{
    share *s = (share *)arg + k;
    const vt_batch *b = s->batch;
    const long long n = s->io->nrow;
    for (;;) {
        const long long first = atomic_fetch_add_explicit(s->next, BATCH_BLOCK, memory_order_relaxed);
        if (first >= n) break;
        const int end = (int)(n - first < BATCH_BLOCK ? n : first + BATCH_BLOCK);
        for (int r = (int)first; r < end; r++) {
            vt_status st = VT_ERR_SKIPPED;
            if (!b->stop_on_error || !atomic_load_explicit(s->stop, memory_order_relaxed))
                st = solve_row(b->model, s->d, s->contacts, s->io, r);
            if (st && st != VT_ERR_SKIPPED && s->failed < 0) {
                s->failed = r;
                s->status = st;
                snprintf(s->message, sizeof s->message, "%s", s->d->message);
                if (b->stop_on_error) atomic_store_explicit(s->stop, 1, memory_order_relaxed);
            }
            if (s->io->status) s->io->status[r] = st;
        }
    }
}

/* the batch taken for a call (1), or 0 when one is running already */
static int claim(vt_batch *batch)
{
    int idle = 0;
    return atomic_compare_exchange_strong_explicit(&batch->busy, &idle, 1, memory_order_acquire, memory_order_relaxed);
}

static void release(vt_batch *batch)
{
    atomic_store_explicit(&batch->busy, 0, memory_order_release);
}

vt_status vt_batch_run(vt_batch *batch, vt_batch_work work, void *ctx)
{
    if (!batch || !work) return VT_ERR_NULL;
    if (!claim(batch)) return VT_ERR_BAD_OPTION;
    vt_pool_run(batch->pool, batch->threads, work, ctx);
    release(batch);
    return VT_OK;
}

/* the arguments: every required array with rows, every stride at least its row */
static vt_status check_io(vt_batch *b, const vt_batch_io *io)
{
    const vt_model *m = b->model;
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody;
    if (io->nrow < 0) return vt_fail(b->message, VT_ERR_BAD_SIZE, "vt_batch: nrow %d < 0", io->nrow);
    if (io->nrow > 0 && (!io->q || !io->qd || !io->qdd))
        return vt_fail(b->message, VT_ERR_NULL, "vt_batch: q, qd and qdd are required");
    if (io->nload < 0) return vt_fail(b->message, VT_ERR_BAD_SIZE, "vt_batch: nload %d < 0", io->nload);
    if (io->nload > 0) {
        if (!io->load_frame || (io->nrow > 0 && !io->load))
            return vt_fail(b->message, VT_ERR_NULL, "vt_batch: nload %d with load_frame or load NULL", io->nload);
        for (int k = 0; k < io->nload; k++) {
            const int f = io->load_frame[k];
            if (f < 0 || f >= m->nframe)
                return vt_fail(b->message, VT_ERR_BAD_INDEX, "vt_batch: load %d at frame %d: the model has %d frames", k, f,
                               m->nframe);
            if (m->frame_body[f] == 0) /* as vt_add_frame_load: the ground takes it, the robot feels nothing */
                return vt_fail(b->message, VT_ERR_BAD_INDEX, "vt_batch: load %d at frame %d '%s': on the ground", k, f,
                               m->frame_name + (size_t)VT_NAME_MAX * f);
        }
    }
    const int td = io->nrow > 0 && !io->time ? vt_motion_time_drive(m) : -1;
    if (td >= 0)
        return vt_fail(b->message, VT_ERR_BAD_OPTION,
                       "vt_batch: time NULL, and drive %d \"%s\" (a %s drive on a model with %s) is evaluated at "
                       "each row's time: give io.time", td, m->drive[td].name,
                       m->drive[td].type == VT_DRIVE_POINT ? "point" : "orientation", m->ncut ? "cut joints" : "couplings");
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
             {"limit_excess", io->limit_excess != NULL, io->limit_excess_stride, 3 * nv},
             {"contact_active", io->contact_active != NULL, io->contact_active_stride, (size_t)b->ncontact},
             {"contact_force", io->contact_force != NULL, io->contact_force_stride, 3 * (size_t)b->ncontact},
             {"load", io->nload > 0, io->load_stride, 6 * (size_t)(io->nload > 0 ? io->nload : 0)},
             {"time", io->time != NULL, io->time_stride, 1}};
    for (size_t k = 0; k < sizeof a / sizeof a[0]; k++)
        if (a[k].given && a[k].stride != 0 && a[k].stride < a[k].len)
            return vt_fail(b->message, VT_ERR_BAD_SIZE, "vt_batch: %s_stride %zu below its row's %zu values",
                           a[k].name, a[k].stride, a[k].len);
    return VT_OK;
}

static vt_status batch_call(vt_batch *batch, const vt_batch_io *io);

vt_status vt_batch_inverse_dynamics_motion(vt_batch *batch, const vt_batch_io *io)
{
    if (!batch) return VT_ERR_NULL;
    if (!claim(batch)) return VT_ERR_BAD_OPTION; /* the running call's message and row stay */
    const vt_status st = batch_call(batch, io);
    release(batch);
    return st;
}

/* the call, the batch taken */
static vt_status batch_call(vt_batch *batch, const vt_batch_io *io)
{
    batch->failed_row = -1;
    batch->message[0] = '\0';
    if (!io) return vt_fail(batch->message, VT_ERR_NULL, "vt_batch: io is NULL");
    vt_status st = check_io(batch, io);
    if (st) return st;
    /* the threads that can have a block (a call of one block stays on the caller's) */
    const int n = io->nrow;
    const int blocks = n / BATCH_BLOCK + (n % BATCH_BLOCK != 0);
    const int T = blocks < batch->threads ? (blocks > 0 ? blocks : 1) : batch->threads;
    share *shares = batch->shares;
    atomic_int stop;
    atomic_llong next;
    atomic_init(&stop, 0);
    atomic_init(&next, 0);
    for (int k = 0; k < T; k++)
        shares[k] = (share){.batch = batch, .io = io, .d = batch->data[k], .next = &next, .stop = &stop,
                            .failed = -1, .contacts = batch->contacts ? batch->contacts[k] : NULL};
    vt_pool_run(batch->pool, T, run_share, shares);
    int low = -1; /* the thread whose first failure is the lowest row */
    for (int k = 0; k < T; k++)
        if (shares[k].failed >= 0 && (low < 0 || shares[k].failed < shares[low].failed)) low = k;
    if (low < 0) return VT_OK;
    batch->failed_row = shares[low].failed;
    return vt_fail(batch->message, shares[low].status, "row %d: %s", shares[low].failed, shares[low].message);
}
