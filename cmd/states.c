/* The command's `inverse`, the states form: chunk after chunk of rows, its numbers parsed and
 * laid out as states in row-major arrays (on the threads, in contiguous blocks), solved by one
 * vt_batch_inverse_dynamics_motion (bitwise the single call's whatever the threads), formatted and
 * written in order; with more than one thread the file's reading and writing run beside. */
#define _POSIX_C_SOURCE 200809L
#include "states.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "message.h"
#include "output.h"
#include "parallel.h"

/* the file's work between two chunks: the previous chunk's rows written (set wset, wn rows; wn
 * 0: none), then the next chunk read (into ch[rbuf]; rbuf -1: none), its message kept (a row
 * before it may fail first) */
typedef struct {
    run *x;
    int wset, wn, rbuf;
    int status;              /* the read's: 0 or 1 */
    char msg[ROW_MESSAGE];   /* its message */
    double t_read, t_write;  /* the time spent */
} file_job;

int chunk_arrays(run *x)
{
    const vt_model *m = x->m;
    const size_t ncol = (size_t)x->in.t.ncol, nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody,
                 nout = (size_t)x->nout, text = 26 * nout + 2;
    const unsigned g = x->o->groups;
    const int world = (g & COLS_WORLD) != 0, link = (g & COLS_LINK) != 0, bear = (g & COLS_BEARING) != 0,
              lim = (g & COLS_LIMITS) != 0, parts = (g & COLS_PARTS) != 0;
    const size_t nb4 = 4 * (size_t)m->nbody;
    const size_t nk = (size_t)x->ncontact;
    const size_t nl = 6 * (size_t)x->nload;
    const size_t row = 8 * (ncol + nq + 3 * nv + (size_t)(world + link) * nb6 + bear * nb4 + (lim + parts) * 3 * nv +
                            nout + 3 * nk + nl) + 4 * nk + 4 + 16 + text + 24 * ncol;
    size_t K = CHUNK_BYTES / row;
    const size_t most = x->T > 1 ? 8 * CHUNK_ROWS : CHUNK_ROWS;
    if (K > most) K = most;
    if (K < 1) K = 1;
    x->K = (int)K;
    x->cells = malloc(K * ncol * sizeof *x->cells);
    x->q = malloc(K * nq * sizeof *x->q);
    x->qd = calloc(K * nv, sizeof *x->qd);
    x->qdd = calloc(K * nv, sizeof *x->qdd);
    x->effort = calloc(K * nv, sizeof *x->effort);
    if (world) x->reac = calloc(K * nb6, sizeof *x->reac);
    if (link) x->reac_link = calloc(K * nb6, sizeof *x->reac_link);
    if (bear) x->bearing = calloc(K * nb4, sizeof *x->bearing);
    if (lim) x->excess = calloc(K * 3 * nv, sizeof *x->excess);
    if (parts) x->parts = calloc(K * 3 * nv, sizeof *x->parts);
    x->status = calloc(K, sizeof *x->status);
    if (nk) {
        x->active = calloc(K * nk, sizeof *x->active);
        x->cforce = calloc(K * 3 * nk, sizeof *x->cforce);
        if (!x->active || !x->cforce) return cmd_fail("out of memory");
    }
    if (nl && !(x->load = malloc(K * nl * sizeof *x->load))) return cmd_fail("out of memory");
    for (int k = 0; k < 2 && x->ofmt == FMT_NPY; k++) x->vals[k] = malloc(K * nout * sizeof *x->vals[k]);
    x->blk = calloc((size_t)x->tm.nblock, sizeof *x->blk);
    if (!x->cells || !x->q || !x->qd || !x->qdd || !x->effort || (world && !x->reac) || (link && !x->reac_link) ||
        (bear && !x->bearing) || (lim && !x->excess) || (parts && !x->parts) ||
        !x->status || (x->ofmt == FMT_NPY && (!x->vals[0] || !x->vals[1])) || !x->blk)
        return cmd_fail("out of memory");
    for (int k = 0; k < x->tm.nblock; k++)
        if (!(x->blk[k].v = malloc(nout * sizeof *x->blk[k].v))) return cmd_fail("out of memory");
    for (size_t r = 0; r < K; r++) memcpy(x->q + r * nq, x->d->q, nq * sizeof *x->q); /* every coordinate set */
    return 0;
}

int row_extras(const run *x, int r, const double *row, long long loc, char *msg)
{
    for (int k = 0; k < x->ncontact; k++) { /* C_active: 0 or 1, else the row refused */
        const int c = x->ccol[k];
        const double a = c >= 0 ? row[c] : 1.0;
        if (a != 0.0 && a != 1.0) {
            char where[ROW_WHERE];
            snprintf(msg, ROW_MESSAGE, "%s: column '%.100s_active': %g is neither 0 nor 1",
                     input_where(&x->in, loc, where), x->cname[k], a);
            return 1;
        }
        x->active[(size_t)r * (size_t)x->ncontact + (size_t)k] = a != 0.0;
    }
    for (int k = 0; k < 6 * x->nload; k++) x->load[(size_t)r * 6 * (size_t)x->nload + (size_t)k] = row[x->lcol[k]];
    return 0;
}

/* row r's state from its numbers: positions, a floating root's position, quaternion (normalised,
 * refused beyond the tolerance of the unit norm) and six rates, the velocities and accelerations,
 * into the chunk's arrays, and its row_extras; 0, or 1 with the message in msg */
static int fill_state(const run *x, int r, const double *row, char *msg)
{
    const vt_model *m = x->m;
    double *q = x->q + (size_t)r * (size_t)m->nq, *qd = x->qd + (size_t)r * (size_t)m->nv,
           *qdd = x->qdd + (size_t)r * (size_t)m->nv;
    if (row_extras(x, r, row, x->chp->loc[r], msg)) return 1;
    for (int k = 0; k < x->nj; k++) {
        const joint_cols *j = &x->jc[k];
        if (!j->free) {
            q[j->qadr] = row[j->col];
            qd[j->rate] = row[j->col_vel];
            qdd[j->rate] = row[j->col_acc];
            continue;
        }
        const int *fc = j->fcol;
        double nq = 0.0;
        for (int c = 0; c < 4; c++) nq += row[fc[3 + c]] * row[fc[3 + c]];
        nq = sqrt(nq);
        if (!(fabs(nq - 1.0) <= x->o->quat_tol)) {
            char where[ROW_WHERE];
            snprintf(msg, ROW_MESSAGE,
                     "%s: columns '%.100s_qw' ... '%.100s_qz': a quaternion of norm %.17g, not 1 (within %g: "
                     "--normalize-quaternions TOL)",
                     input_where(&x->in, x->chp->loc[r], where), j->name, j->name, nq, x->o->quat_tol);
            return 1;
        }
        for (int c = 0; c < 3; c++) q[j->qadr + c] = row[fc[c]];
        for (int c = 0; c < 4; c++) q[j->qadr + 3 + c] = row[fc[3 + c]] / nq;
        for (int c = 0; c < 6; c++) {
            qd[j->rate + c] = row[fc[7 + c]];
            qdd[j->rate + c] = row[fc[13 + c]];
        }
    }
    return 0;
}

/* a block of the chunk's rows parsed and laid out as states; its first failure kept */
static void fill_block(void *ctx, int first, int end, int k)
{
    run *x = ctx;
    block_state *b = &x->blk[k];
    const size_t ncol = (size_t)x->in.t.ncol;
    for (int r = first; r < end; r++) {
        double *row = x->cells + (size_t)r * ncol;
        if (input_parse(&x->in, x->chp, r, row, b->msg) || fill_state(x, r, row, b->msg)) {
            b->failed = r;
            return;
        }
    }
}

vt_batch_io chunk_io(const run *x, int n)
{
    vt_batch_io io = {0};
    io.nrow = n;
    io.q = x->q;
    io.qd = x->qd;
    io.qdd = x->qdd;
    io.effort = x->effort;
    io.reaction = x->reac;
    io.reaction_joint = x->reac_link;
    io.bearing = x->bearing;
    io.limit_excess = x->excess;
    io.effort_parts = x->parts;
    io.status = x->status;
    io.contact_active = x->active;
    io.contact_force = x->cforce;
    io.nload = x->nload;
    io.load_frame = x->lframe;
    io.load = x->load;
    return io;
}

int state_failure(run *x, int r, long long loc)
{
    const vt_model *m = x->m;
    vt_data *d = x->d;
    char where[ROW_WHERE];
    memcpy(d->q, x->q + (size_t)r * (size_t)m->nq, (size_t)m->nq * sizeof *d->q);
    memcpy(d->qd, x->qd + (size_t)r * (size_t)m->nv, (size_t)m->nv * sizeof *d->qd);
    memcpy(d->qdd, x->qdd + (size_t)r * (size_t)m->nv, (size_t)m->nv * sizeof *d->qdd);
    input_where(&x->in, loc, where);
    if (x->nload) { /* the batch's own message, its "row k: " (the chunk's index) left out */
        const char *msg = vt_batch_message(x->batch), *c = strncmp(msg, "row ", 4) == 0 ? strstr(msg, ": ") : NULL;
        return cmd_fail("%s: %s (%s)", where, c ? c + 2 : msg, vt_status_string(x->status[r]));
    }
    const int *active = x->contacts ? x->active + (size_t)r * (size_t)x->ncontact : NULL;
    const vt_status st =
        x->contacts ? vt_inverse_dynamics_contacts(m, d, x->contacts, active, NULL) : vt_inverse_dynamics_motion(m, d);
    if (st) return cmd_fail("%s: %s (%s)", where, d->message, vt_status_string(st));
    return cmd_fail("%s: %s (%s)", where, vt_batch_message(x->batch), vt_status_string(x->status[r]));
}

/* chunk x->chp's n rows parsed and laid out as states (on the threads), solved by the batch
 * and formatted into output set `set`; 0, or 1 at its first failing row (a cell or a
 * quaternion, or the solve: the lowest) */
static int solve_chunk(run *x, int n, int set)
{
    const double t0 = run_clock();
    for (int k = 0; k < x->tm.nblock; k++) x->blk[k].failed = -1;
    parallel_blocks(&x->tm, n, fill_block, x);
    int f = n, fk = -1; /* the first row whose numbers or quaternion fail */
    for (int k = 0; k < x->tm.nblock && fk < 0; k++)
        if (x->blk[k].failed >= 0) f = x->blk[fk = k].failed;
    const double t1 = run_clock();
    x->t_read += t1 - t0;
    vt_batch_io io = chunk_io(x, f);
    const vt_status st = vt_batch_inverse_dynamics_motion(x->batch, &io);
    x->t_solve += run_clock() - t1;
    if (st) { /* the first row whose status is a failure */
        int s = -1;
        for (int r = 0; r < f && s < 0; r++)
            if (x->status[r] != VT_OK) s = r;
        if (s < 0) return cmd_fail("%s: %s (%s)", x->states, vt_batch_message(x->batch), vt_status_string(st));
        return state_failure(x, s, x->chp->loc[s]);
    }
    if (fk >= 0) return cmd_fail("%s", x->blk[fk].msg);
    if (!x->header_done) {
        if (write_header(x, x->in.nrow)) return 1;
        x->header_done = 1;
    }
    x->oset = set;
    return format_rows(x, n);
}

static void *file_work(void *arg)
{
    file_job *j = arg;
    run *x = j->x;
    cmd_message_sink(j->msg, sizeof j->msg);
    const double t0 = run_clock();
    if (j->wn > 0) put_rows(x, j->wset, j->wn);
    const double t1 = run_clock();
    j->status = j->rbuf >= 0 ? input_read(&x->in, &x->ch[j->rbuf], x->K, CHUNK_BYTES / 4) : 0;
    j->t_write = t1 - t0;
    j->t_read = run_clock() - t1;
    cmd_message_sink(NULL, 0);
    return NULL;
}

int run_states(run *x)
{
    double start = 0.0, last = 0.0;
    x->incells = x->cells;
    int pending = 0; /* the rows of the output set before, to write */
    file_job job = {.x = x, .rbuf = 0, .wn = 0};
    file_work(&job); /* the first chunk */
    x->t_read += job.t_read;
    for (int cur = 0;; cur ^= 1) {
        if (job.status) return cmd_fail("%s", job.msg);
        x->chp = &x->ch[cur];
        const int n = x->chp->n;
        /* this round's file work: the set before written, the next chunk read */
        job = (file_job){.x = x, .wset = cur ^ 1, .wn = pending, .rbuf = n > 0 ? cur ^ 1 : -1};
        pthread_t tid;
        const int threaded = x->T > 1 && n > 0 && pthread_create(&tid, NULL, file_work, &job) == 0;
        if (!threaded) file_work(&job);
        const int status = n > 0 ? solve_chunk(x, n, cur) : 0;
        if (threaded) pthread_join(tid, NULL);
        x->t_read += job.t_read;
        x->t_write += job.t_write;
        if (status) return 1;
        if (n == 0) {
            if (x->written == 0) return no_rows(x);
            progress(x, 1, &start, &last);
            return 0;
        }
        pending = n;
        progress(x, 0, &start, &last);
    }
}
