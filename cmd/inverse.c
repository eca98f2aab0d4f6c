/* The command's `inverse`: a URDF robot's efforts and joint reactions, one output row per row of
 * a CSV or .npy file of states (positions, velocities, accelerations: the library's batch on
 * threads) or of samples of a trajectory (positions and t: a spline drive on each joint,
 * vt_kinematic_solve row by row; with a floating root, splines through its position and its
 * quaternion's components give each row's state, solved by the batch as the states are).
 *
 * The jobs in order: the input's header read and its columns mapped to the joints, the model
 * built (with the spline drives for samples, which read every row first), the output opened
 * beside its name, then chunk after chunk of rows: the numbers parsed and the states laid out in
 * row-major arrays (on the threads, in contiguous blocks), the chunk solved by one
 * vt_batch_inverse_dynamics_motion (bitwise the single call's whatever the threads), and its
 * output rows gathered and formatted (on the threads, each block into its own buffer) and written
 * in order. So the output's bytes do not depend on the number of threads, and the resident memory
 * is that of a chunk, whatever the rows. The first failing row of a chunk — a cell, a quaternion,
 * or the solve (the batch's status a row) — stops the run, named. */
#define _POSIX_C_SOURCE 200809L
#include "inverse.h"

#include <locale.h>
#include <pthread.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "csv.h"
#include "input.h"
#include "message.h"
#include "npy.h"
#include "number_text.h"
#include "parallel.h"
#include "robot.h"
#include "vtdyn.h"
#include "vtdyn/euler.h"

/* a floating root's input columns, after its name and '_' */
#define NFREE 19
static const char *const free_suffix[NFREE] = {"x",  "y",  "z",  "qw", "qx", "qy", "qz", "vx",  "vy",  "vz",
                                               "wx", "wy", "wz", "ax", "ay", "az", "alx", "aly", "alz"};

/* the rows of a chunk, at most, and the bytes its arrays may take (fewer rows for a large robot) */
#define CHUNK_ROWS 4096
#define CHUNK_BYTES ((size_t)64 << 20)

/* one moving joint's input columns and output */
typedef struct {
    int body, rate, qadr; /* the joint's body, its (first) rate and coordinate */
    int col, col_vel, col_acc;
    int free;             /* a floating root: its columns in fcol (samples: the first 7, the rest -1) */
    int fcol[NFREE];
    int spl;              /* samples with a floating root: its first spline, a drive of run.splines
                           * (a joint 1, a floating root 7: x, y, z, qw, qx, qy, qz) */
    const char *name;
} joint_cols;

/* what the rows give */
typedef enum {
    FORM_UNKNOWN, /* not yet known: no one-rate joint seen */
    FORM_STATES,  /* J, J_vel and J_acc for every joint: states */
    FORM_SAMPLES  /* t and the positions J alone: samples of a trajectory */
} form;

/* one block's state in a chunk's parallel work */
typedef struct {
    int failed;             /* the block's first failing row, or -1 */
    char msg[ROW_MESSAGE];  /* its message */
    char *text[2];          /* CSV output: the block's rows formatted, in either output set */
    size_t len[2], cap[2];
    double *v;              /* one row's output values */
} block_state;

/* one run of `inverse`: its files, model, columns and chunk, freed by run_free */
typedef struct {
    const char *urdf, *states; /* the files' names, for the messages */
    const inverse_options *o;
    input in;                  /* the input: its columns, and its cells for samples */
    vt_builder *b;
    vt_model *probe;           /* the robot as loaded; the joints' names point into it */
    vt_model *m;               /* the robot solved: with a spline drive per joint for samples
                                * without a floating root */
    vt_model *splines;         /* samples with a floating root: the splines, as drives (below) */
    int nfree;                 /* the floating roots */
    vt_data *d;                /* one row's data: samples, and a failing state's message */
    vt_batch *batch;           /* the states' solver */
    joint_cols *jc;            /* the moving joints, in the model's order, floating roots last */
    int nj;
    int ct;                    /* the column t, or -1 */
    form form;
    double *ts;                /* the samples' times (column t), for the splines */
    vt_run_options opt;        /* Newton's tolerance and iteration limit for the samples */
    /* the output */
    file_format ofmt;
    output out;
    int nout;                  /* values a row */
    char **names;              /* their names (nout) */
    size_t npy_len;            /* a .npy header written before the row count was known: its length */
    long long written;         /* rows written */
    int header_done;           /* the output's header written */
    /* a chunk: K rows at most, row-major arrays */
    int K, T;                  /* rows, threads */
    chunk ch[2];               /* rows read, before they are parsed: the chunk solved and the next */
    chunk *chp;                /* the chunk being solved */
    int oset;                  /* the output set being formatted (the other may be being written) */
    double *cells;             /* the inputs' numbers (K x ncol) */
    const double *incells;     /* the chunk's input rows for the output's t: cells, or the table's */
    double *q, *qd, *qdd;      /* the states (K x nq, K x nv, K x nv) */
    double *effort;            /* every rate's effort (K x nv) */
    double *reac, *reac_link;  /* the joints' reactions, world axes and the joint's frame, the child
                                * link's URDF axes (vt_model.jnt_frame) (K x 6 nbody), or NULL */
    double *bearing;           /* their bearing split (K x 4 nbody), or NULL */
    double *excess;            /* the rates' limit excess (K x 3 nv), or NULL */
    double *parts;             /* the efforts' armature, damping and friction parts (K x 3 nv), or NULL */
    int *status;               /* the rows' statuses (K) */
    double *vals[2];           /* .npy output: the rows' values, little-endian (K x nout), two sets */
    block_state *blk;          /* T */
    table_key *frames;         /* the probe's frames sorted by name (nframe): a link's frame in log n */
    /* the time spent, s */
    double t_read, t_solve, t_write;
} run;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* frees what the run holds (any part not yet made is NULL) */
static void run_free(run *x)
{
    free(x->frames);
    free(x->ts);
    free(x->jc);
    if (x->names)
        for (int k = 0; k < x->nout; k++) free(x->names[k]);
    free(x->names);
    free(x->cells);
    free(x->q);
    free(x->qd);
    free(x->qdd);
    free(x->effort);
    free(x->reac);
    free(x->reac_link);
    free(x->bearing);
    free(x->excess);
    free(x->parts);
    free(x->status);
    free(x->vals[0]);
    free(x->vals[1]);
    if (x->blk)
        for (int k = 0; k < x->T; k++) {
            free(x->blk[k].text[0]);
            free(x->blk[k].text[1]);
            free(x->blk[k].v);
        }
    free(x->blk);
    chunk_free(&x->ch[0]);
    chunk_free(&x->ch[1]);
    vt_batch_free(x->batch);
    vt_data_free(x->d);
    vt_model_free(x->m);
    vt_model_free(x->splines);
    vt_model_free(x->probe);
    vt_builder_free(x->b);
    input_close(&x->in);
}

/* loads the URDF and builds it once as it is (the probe, whose joints name the columns); 0 or 1 */
static int load_robot(run *x, const inverse_options *o)
{
    const int floating = o->floating;
    if (cmd_load_urdf(&x->b, x->urdf, floating, !o->ideal, o->inertia_tol)) return 1;
    for (int k = 0; k < o->npayload; k++)
        if (cmd_add_payload(x->b, o->payload[k], x->urdf)) return 1;
    if (o->joint_params && cmd_joint_params(x->b, o->joint_params, x->urdf)) return 1;
    const vt_status st = vt_builder_build(&x->probe, x->b);
    if (st) return cmd_fail("%s: %s%s", x->urdf, vt_builder_message(x->b), cmd_empty_hint(st, floating));
    const vt_model *p = x->probe;
    x->jc = calloc((size_t)p->nbody, sizeof *x->jc);
    x->frames = malloc((size_t)(p->nframe > 0 ? p->nframe : 1) * sizeof *x->frames);
    if (!x->jc || !x->frames) return cmd_fail("out of memory");
    for (int k = 0; k < p->nframe; k++) x->frames[k] = (table_key){p->frame_name + (size_t)VT_NAME_MAX * k, k};
    keys_sort(x->frames, p->nframe);
    return 0;
}

/* the frame of that name (a link's), or -1: vt_find_frame in log nframe */
static int find_frame(const run *x, const char *name)
{
    const int k = keys_find(x->frames, x->probe->nframe, name);
    return k < 0 ? -1 : x->frames[k].col;
}

/* the input has no rows: refused, as a table without rows */
static int no_rows(const run *x)
{
    if (x->in.fmt == FMT_NPY) return cmd_fail("%s: no data rows (shape (0,))", x->states);
    return cmd_fail("%s: no data rows under the header", x->states);
}

/* the one-rate joints' columns J, J_vel, J_acc, and from them the form (states or samples):
 * every joint needs its position, and its rates' columns all or none alike; 0 or 1 */
static int map_joints(run *x)
{
    const vt_model *p = x->probe;
    x->ct = table_column(&x->in.t, "t");
    for (int i = 1; i <= p->nbody; i++) {
        const int jt = p->body_joint[i];
        const char *name = p->joint_name + VT_NAME_MAX * i;
        if (jt == VT_JOINT_FREE) continue; /* map_floating_roots, once the form is known */
        if (jt == VT_JOINT_BASE || jt == VT_JOINT_SPHERICAL || p->body_nv[i] != 1)
            return cmd_fail("%s: joint '%s' (%s): only revolute, continuous and prismatic joints are supported here",
                            x->urdf, name, cmd_joint_kind(jt));
        char key[VT_NAME_MAX + 8];
        joint_cols *j = &x->jc[x->nj++];
        j->body = i;
        j->rate = p->body_vadr[i];
        j->name = name;
        j->col = table_column(&x->in.t, name);
        snprintf(key, sizeof key, "%s_vel", name);
        j->col_vel = table_column(&x->in.t, key);
        snprintf(key, sizeof key, "%s_acc", name);
        j->col_acc = table_column(&x->in.t, key);
        if (j->col < 0) return cmd_fail("%s: no column '%s' (the position of joint %s)", x->states, name, name);
        const int full = j->col_vel >= 0 && j->col_acc >= 0, none = j->col_vel < 0 && j->col_acc < 0;
        const form f = full ? FORM_STATES : none ? FORM_SAMPLES : FORM_UNKNOWN;
        if (f == FORM_UNKNOWN || (x->form != FORM_UNKNOWN && f != x->form))
            return cmd_fail("%s: joint '%s': give '%s_vel' and '%s_acc' for every joint, or for none (then with 't', "
                            "samples)",
                            x->states, name, name, name);
        x->form = f;
    }
    return 0;
}

/* the floating roots' columns, after the one-rate joints: R_x ... R_alz for states, R_x ... R_qz
 * for samples (the form the joints gave, or with no joint the root's own: any rate column makes
 * it states); then a column t for samples; 0 or 1 */
static int map_floating_roots(run *x)
{
    const vt_model *p = x->probe;
    for (int i = 1; i <= p->nbody; i++) {
        if (p->body_joint[i] != VT_JOINT_FREE) continue;
        const char *name = p->joint_name + VT_NAME_MAX * i;
        if (!name[0]) name = p->body_name + VT_NAME_MAX * i; /* an implicit root joint: the link's name */
        if (p->body_parent[i] != 0)
            return cmd_fail("%s: floating joint '%s' from link '%s': only a floating root (from the world) is "
                            "supported here",
                            x->urdf, name, p->body_name + VT_NAME_MAX * p->body_parent[i]);
        joint_cols *j = &x->jc[x->nj++];
        j->body = i;
        j->rate = p->body_vadr[i];
        j->name = name;
        j->free = 1;
        x->nfree++;
        int rate = -1; /* its first rate column given */
        for (int k = 0; k < NFREE; k++) {
            char key[VT_NAME_MAX + 8];
            snprintf(key, sizeof key, "%s_%s", name, free_suffix[k]);
            j->fcol[k] = table_column(&x->in.t, key);
            if (k >= 7 && j->fcol[k] >= 0 && rate < 0) rate = k;
        }
        /* without R_x: the joints' form (states when there is none), the missing R_x named below */
        form f = rate >= 0 ? FORM_STATES : FORM_SAMPLES;
        if (rate < 0 && j->fcol[0] < 0) f = x->form == FORM_SAMPLES ? FORM_SAMPLES : FORM_STATES;
        if (x->form == FORM_SAMPLES && f == FORM_STATES)
            return cmd_fail("%s: column '%s_%s': a floating root's rate, but the joints have their positions alone "
                            "(samples): give every joint's _vel and _acc and %s_x ... %s_alz (states), or t, the "
                            "positions and %s_x ... %s_qz alone (samples)",
                            x->states, name, free_suffix[rate], name, name, name, name);
        if (x->form == FORM_STATES && f == FORM_SAMPLES)
            return cmd_fail("%s: no column '%s_vx' (floating root %s): the joints have their rates (states), so "
                            "give %s_x ... %s_alz; or t, the positions and %s_x ... %s_qz alone (samples)",
                            x->states, name, name, name, name, name, name);
        x->form = f;
        const int need = f == FORM_STATES ? NFREE : 7;
        for (int k = 0; k < need; k++) {
            if (j->fcol[k] >= 0) continue;
            const int implicit = p->joint_name[VT_NAME_MAX * i] == '\0';
            return cmd_fail("%s: no column '%s_%s' (floating root %s: %s_x ... %s_%s, see --help%s)", x->states,
                            name, free_suffix[k], name, name, name, f == FORM_STATES ? "alz" : "qz as samples",
                            implicit ? "; without --floating the root link is fixed to the world" : "");
        }
    }
    if (x->form == FORM_SAMPLES && x->ct < 0)
        return cmd_fail("%s: positions without velocities and accelerations are samples of a trajectory: a column "
                        "'t' is needed",
                        x->states);
    return 0;
}

/* the suffix of a floating root's input column that name ends with after its '_', or NULL */
static const char *free_column_suffix(const char *name)
{
    const char *us = strrchr(name, '_');
    if (!us) return NULL;
    for (int k = 0; k < NFREE; k++)
        if (strcmp(us + 1, free_suffix[k]) == 0) return us + 1;
    return NULL;
}

/* every input column is one of the robot's (nothing ignored): an unknown column stops the run,
 * named, with the way out where it is a floating root's on a robot loaded fixed; 0 or 1 */
static int check_columns(const run *x, int floating)
{
    const vt_model *p = x->probe;
    char head[ROW_MESSAGE]; /* the header's place: its line, or the .npy file */
    if (x->in.t.header_line) snprintf(head, sizeof head, "%s:%d", x->states, x->in.t.header_line);
    else snprintf(head, sizeof head, "%s", x->states);
    for (int c = 0; c < x->in.t.ncol; c++) {
        if (x->in.t.used[c]) continue;
        const char *name = x->in.t.name[c], *sfx = free_column_suffix(name);
        if (!floating && sfx) { /* P_x ... with P a link fixed to the world: the root, floating in the file */
            char root[VT_NAME_MAX];
            const size_t len = (size_t)(sfx - 1 - name);
            if (len < sizeof root) {
                memcpy(root, name, len);
                root[len] = '\0';
                const int f = find_frame(x, root);
                if (f >= 0 && p->frame_body[f] == 0)
                    return cmd_fail("%s: column %d '%s': a floating root's column, but %s is loaded with its root "
                                    "link '%s' fixed to the world: run with --floating",
                                    head, c + 1, name, x->urdf, root);
            }
        }
        return cmd_fail("%s: column %d '%s' is none of the robot's (%s): every column must be t, a moving joint J's "
                        "J, J_vel or J_acc, or a floating root R's R_x ... R_alz (vtdyn info lists the joints)",
                        head, c + 1, name, x->urdf);
    }
    return 0;
}

/* v in the fewest significant digits that read back as v, into buf */
static const char *shortest(char buf[32], double v)
{
    buf[number_print(buf, v, 0)] = '\0';
    return buf;
}

/* the samples' times, column t, into x->ts: strictly increasing, or the first row whose t is not
 * after the row before's named (its line, or its index in a .npy file); 0 or 1 */
static int sample_times(run *x)
{
    const table *t = &x->in.t;
    const int n = t->nrow;
    x->ts = malloc((size_t)n * sizeof *x->ts);
    if (!x->ts) return cmd_fail("out of memory");
    for (int r = 0; r < n; r++) x->ts[r] = table_row(t, r)[x->ct];
    for (int r = 1; r < n; r++) {
        if (x->ts[r] > x->ts[r - 1]) continue;
        char now[32], before[32], where[ROW_WHERE];
        input_where(&x->in, t->loc[r], where);
        if (x->ts[r] == x->ts[r - 1])
            return cmd_fail("%s: column 't': %s again (as on the row before): samples of a trajectory (positions "
                            "alone) need 't' increasing from row to row",
                            where, shortest(now, x->ts[r]));
        return cmd_fail("%s: column 't': %s after %s on the row before: samples of a trajectory (positions "
                        "alone) need 't' increasing from row to row",
                        where, shortest(now, x->ts[r]), shortest(before, x->ts[r - 1]));
    }
    return 0;
}

/* for samples, every row read and the times checked; 0 or 1 */
static int read_samples(run *x)
{
    if (input_read_all(&x->in)) return 1;
    if (x->in.t.nrow == 0) return no_rows(x);
    return sample_times(x);
}

/* for samples, a joint drive on every joint, following the cubic spline through its column's
 * samples over t (the drives in the joints' order, drive k on joint k): every row read first;
 * 0 or 1 */
static int add_spline_drives(run *x)
{
    if (read_samples(x)) return 1;
    double *ys = malloc((size_t)x->in.t.nrow * sizeof *ys);
    if (!ys) return cmd_fail("out of memory");
    for (int k = 0; k < x->nj; k++) { /* (no floating root here) */
        for (int r = 0; r < x->in.t.nrow; r++) ys[r] = table_row(&x->in.t, r)[x->jc[k].col];
        vt_drive_def dr = vt_default_drive_def();
        dr.body = x->jc[k].body;
        dr.f = vt_function_spline(x->in.t.nrow, x->ts, ys);
        if (vt_builder_add_drive(x->b, &dr) < 0) {
            cmd_fail("%s: column '%s' as samples: %s", x->states, x->jc[k].name, vt_builder_message(x->b));
            free(ys);
            return 1;
        }
    }
    free(ys);
    return 0;
}

/* one spline through ys over the samples' times, as the drive of a body of its own in hb (column
 * `col` named in a refusal); 0 or 1 */
static int add_spline(run *x, vt_builder *hb, const double *ys, const char *col)
{
    vt_body_def bd = vt_default_body_def();
    const int body = vt_builder_add_body(hb, &bd);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = body;
    dr.f = vt_function_spline(x->in.t.nrow, x->ts, ys);
    if (body < 0 || vt_builder_add_drive(hb, &dr) < 0)
        return cmd_fail("%s: column '%s' as samples: %s", x->states, col, vt_builder_message(hb));
    return 0;
}

/* for samples with a floating root, the splines through the samples: each joint's position,
 * each root's x, y, z and its quaternion's four components — every quaternion sample unit within
 * --normalize-quaternions (refused, its row named), normalised, and its sign turned where it
 * points away from the sample before (q and −q are one orientation; the spline must not pass
 * through 0 between them). The model solved has no drives (the given motion ignores them): the
 * splines are the drives of a model of their own, x->splines, one body each, because a model's
 * drive is the library's only spline evaluated in O(log n) at any n (vt_function_eval solves a
 * spline outside a model afresh at each call, and only up to VT_SPLINE_EVAL_MAX samples); that
 * model is never solved. 0 or 1 */
static int spline_model(run *x)
{
    if (read_samples(x)) return 1;
    const table *t = &x->in.t;
    const int n = t->nrow;
    vt_builder *hb = NULL;
    double *ys = malloc(4 * (size_t)n * sizeof *ys);
    int status = !ys || vt_builder_create(&hb, NULL) ? cmd_fail("out of memory") : 0;
    int nspl = 0;
    char col[VT_NAME_MAX + 8];
    for (int k = 0; k < x->nj && !status; k++) {
        joint_cols *j = &x->jc[k];
        j->spl = nspl;
        if (!j->free) {
            for (int r = 0; r < n; r++) ys[r] = table_row(t, r)[j->col];
            status = add_spline(x, hb, ys, j->name);
            nspl++;
            continue;
        }
        for (int c = 0; c < 3 && !status; c++) {
            for (int r = 0; r < n; r++) ys[r] = table_row(t, r)[j->fcol[c]];
            snprintf(col, sizeof col, "%s_%s", j->name, free_suffix[c]);
            status = add_spline(x, hb, ys, col);
            nspl++;
        }
        /* the quaternions, component c of row r at ys[c n + r] */
        for (int r = 0; r < n && !status; r++) {
            const double *row = table_row(t, r);
            double v[4], nq = 0.0, dot = 0.0;
            for (int c = 0; c < 4; c++) {
                v[c] = row[j->fcol[3 + c]];
                nq += v[c] * v[c];
            }
            nq = sqrt(nq);
            if (!(fabs(nq - 1.0) <= x->o->quat_tol)) {
                char where[ROW_WHERE];
                status = cmd_fail("%s: columns '%s_qw' ... '%s_qz': a quaternion of norm %.17g, not 1 (within %g: "
                                  "--normalize-quaternions TOL)",
                                  input_where(&x->in, t->loc[r], where), j->name, j->name, nq, x->o->quat_tol);
                break;
            }
            for (int c = 0; c < 4 && r > 0; c++) dot += v[c] * ys[(size_t)c * (size_t)n + (size_t)r - 1];
            const double sign = dot < 0.0 ? -1.0 : 1.0;
            for (int c = 0; c < 4; c++) ys[(size_t)c * (size_t)n + (size_t)r] = sign * v[c] / nq;
        }
        for (int c = 0; c < 4 && !status; c++) {
            snprintf(col, sizeof col, "%s_%s", j->name, free_suffix[3 + c]);
            status = add_spline(x, hb, ys + (size_t)c * (size_t)n, col);
            nspl++;
        }
    }
    if (!status && vt_builder_build(&x->splines, hb)) status = cmd_fail("%s", vt_builder_message(hb));
    vt_builder_free(hb);
    free(ys);
    return status;
}

/* the model solved (the robot, with the spline drives for samples) and its data; for states the
 * batch on the run's threads; 0 or 1 */
static int build_model(run *x)
{
    if (x->form == FORM_SAMPLES && (x->nfree ? spline_model(x) : add_spline_drives(x))) return 1;
    if (vt_builder_build(&x->m, x->b) || vt_data_create(&x->d, x->m))
        return cmd_fail("%s: %s", x->urdf, vt_builder_message(x->b));
    for (int k = 0; k < x->nj; k++) x->jc[k].qadr = x->m->body_qadr[x->jc[k].body];
    /* the batch (the states' solver) counts the CPUs for -j 0; the samples' threads are as many */
    vt_batch_def def = vt_default_batch_def();
    def.threads = x->o->threads;
    const vt_status st = vt_batch_create(&x->batch, x->m, &def);
    if (st) return cmd_fail("%s: %d threads: %s", x->urdf, x->o->threads, vt_status_string(st));
    x->T = vt_batch_threads(x->batch);
    return 0;
}

/* ---- the output's columns ---------------------------------------------------------------- */

/* name k of the output, "J_suffix", into x->names; 0 or 1 */
static int add_name(run *x, int *k, const char *joint, const char *suffix)
{
    const size_t n = strlen(joint) + strlen(suffix) + 1;
    if (!(x->names[*k] = malloc(n))) return 1;
    snprintf(x->names[*k], n, "%s%s", joint, suffix);
    (*k)++;
    return 0;
}

/* the output's columns: t when given, then per joint the selected groups in their order (effort,
 * world, link, bearing, limits; a floating root's efforts in world then link axes in `effort`,
 * nothing else); 0 or 1 */
static int output_columns(run *x)
{
    static const char *const effort6[12] = {"_effort_fx", "_effort_fy", "_effort_fz", "_effort_nx", "_effort_ny",
                                            "_effort_nz", "_effort_fx_link", "_effort_fy_link", "_effort_fz_link",
                                            "_effort_nx_link", "_effort_ny_link", "_effort_nz_link"};
    static const char *const world[6] = {"_fx", "_fy", "_fz", "_nx", "_ny", "_nz"};
    static const char *const link[6] = {"_fx_link", "_fy_link", "_fz_link", "_nx_link", "_ny_link", "_nz_link"};
    static const char *const parts[4] = {"_effort_rigid", "_effort_armature", "_effort_damping", "_effort_friction"};
    static const char *const bearing[4] = {"_axial_force", "_radial_force", "_axial_moment", "_tilt_moment"};
    static const char *const limits[3] = {"_position_excess", "_vel_excess", "_effort_excess"};
    const unsigned g = x->o->groups;
    int n = x->ct >= 0;
    for (int k = 0; k < x->nj; k++)
        n += x->jc[k].free ? (g & COLS_EFFORT ? 12 : 0)
                           : (g & COLS_EFFORT ? 1 : 0) + (g & COLS_PARTS ? 4 : 0) + (g & COLS_WORLD ? 6 : 0) +
                                 (g & COLS_LINK ? 6 : 0) + (g & COLS_BEARING ? 4 : 0) + (g & COLS_LIMITS ? 3 : 0);
    if (n == (x->ct >= 0)) /* t alone is no output */
        return cmd_fail("--columns: none of the selected groups has a column for %s (a floating root has efforts "
                        "alone)",
                        x->urdf);
    x->names = calloc((size_t)n, sizeof *x->names);
    if (!x->names) return cmd_fail("out of memory");
    x->nout = n;
    int k = 0, bad = 0;
    if (x->ct >= 0) bad |= add_name(x, &k, "t", "");
    for (int i = 0; i < x->nj; i++) {
        const joint_cols *j = &x->jc[i];
        if (j->free) {
            for (int c = 0; c < 12 && (g & COLS_EFFORT); c++) bad |= add_name(x, &k, j->name, effort6[c]);
            continue;
        }
        if (g & COLS_EFFORT) bad |= add_name(x, &k, j->name, "_effort");
        for (int c = 0; c < 4 && (g & COLS_PARTS); c++) bad |= add_name(x, &k, j->name, parts[c]);
        for (int c = 0; c < 6 && (g & COLS_WORLD); c++) bad |= add_name(x, &k, j->name, world[c]);
        for (int c = 0; c < 6 && (g & COLS_LINK); c++) bad |= add_name(x, &k, j->name, link[c]);
        for (int c = 0; c < 4 && (g & COLS_BEARING); c++) bad |= add_name(x, &k, j->name, bearing[c]);
        for (int c = 0; c < 3 && (g & COLS_LIMITS); c++) bad |= add_name(x, &k, j->name, limits[c]);
    }
    return bad ? cmd_fail("out of memory") : 0;
}

/* ---- a chunk's arrays ---------------------------------------------------------------------- */

/* the chunk's rows (as many as CHUNK_BYTES holds, CHUNK_ROWS at most) and arrays; 0 or 1 */
static int chunk_arrays(run *x)
{
    const vt_model *m = x->m;
    const size_t ncol = (size_t)x->in.t.ncol, nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody,
                 nout = (size_t)x->nout, text = 26 * nout + 2;
    const unsigned g = x->o->groups;
    const int world = (g & COLS_WORLD) != 0, link = (g & COLS_LINK) != 0, bear = (g & COLS_BEARING) != 0,
              lim = (g & COLS_LIMITS) != 0, parts = (g & COLS_PARTS) != 0;
    const size_t nb4 = 4 * (size_t)m->nbody;
    const size_t row = 8 * (ncol + nq + 3 * nv + (size_t)(world + link) * nb6 + bear * nb4 + (lim + parts) * 3 * nv +
                            nout) + 4 + 16 + text + 24 * ncol;
    size_t K = CHUNK_BYTES / row;
    if (K > CHUNK_ROWS) K = CHUNK_ROWS;
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
    for (int k = 0; k < 2 && x->ofmt == FMT_NPY; k++) x->vals[k] = malloc(K * nout * sizeof *x->vals[k]);
    x->blk = calloc((size_t)x->T, sizeof *x->blk);
    if (!x->cells || !x->q || !x->qd || !x->qdd || !x->effort || (world && !x->reac) || (link && !x->reac_link) ||
        (bear && !x->bearing) || (lim && !x->excess) || (parts && !x->parts) ||
        !x->status || (x->ofmt == FMT_NPY && (!x->vals[0] || !x->vals[1])) || !x->blk)
        return cmd_fail("out of memory");
    for (int k = 0; k < x->T; k++)
        if (!(x->blk[k].v = malloc(nout * sizeof *x->blk[k].v))) return cmd_fail("out of memory");
    for (size_t r = 0; r < K; r++) memcpy(x->q + r * nq, x->d->q, nq * sizeof *x->q); /* every coordinate set */
    return 0;
}

/* ---- rows in: a state from its numbers ------------------------------------------------------- */

/* row r's state from its numbers: positions, a floating root's position, quaternion (normalised,
 * refused beyond the tolerance of the unit norm) and six rates, the velocities and accelerations,
 * into the chunk's arrays; 0, or 1 with the message in msg */
static int fill_state(const run *x, int r, const double *row, char *msg)
{
    const vt_model *m = x->m;
    double *q = x->q + (size_t)r * (size_t)m->nq, *qd = x->qd + (size_t)r * (size_t)m->nv,
           *qdd = x->qdd + (size_t)r * (size_t)m->nv;
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

/* ---- rows out: the values, CSV or .npy --------------------------------------------------- */

/* w (3 forces, 3 moments) turned by the transpose of the column-major rotation R into out */
static void turn_back(double out[6], const double R[9], const double w[6])
{
    for (int h = 0; h < 6; h += 3)
        for (int c = 0; c < 3; c++) out[h + c] = R[3 * c] * w[h] + R[3 * c + 1] * w[h + 1] + R[3 * c + 2] * w[h + 2];
}

/* chunk row r's output values into v: t when given, then per joint its selected groups */
static void gather(const run *x, int r, double *v)
{
    const vt_model *m = x->m;
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody;
    const unsigned g = x->o->groups;
    const double *q = x->q + r * nq, *e = x->effort + r * nv;
    const double *rw = x->reac ? x->reac + r * nb6 : NULL, *rl = x->reac_link ? x->reac_link + r * nb6 : NULL;
    const double *be = x->bearing ? x->bearing + r * 4 * (size_t)m->nbody : NULL;
    const double *ex = x->excess ? x->excess + r * 3 * nv : NULL;
    int o = 0;
    if (x->ct >= 0) v[o++] = x->incells[(size_t)r * (size_t)x->in.t.ncol + (size_t)x->ct];
    for (int k = 0; k < x->nj; k++) {
        const joint_cols *j = &x->jc[k];
        const size_t b6 = 6 * (size_t)(j->body - 1);
        if (j->free) { /* its six efforts, world axes, then its link's (the quaternion given) */
            if (!(g & COLS_EFFORT)) continue;
            double R[9];
            memcpy(v + o, e + j->rate, 6 * sizeof *v);
            vt_euler_A(R, q + j->qadr + 3);
            turn_back(v + o + 6, R, e + j->rate);
            o += 12;
            continue;
        }
        if (g & COLS_EFFORT) v[o++] = e[j->rate];
        if (g & COLS_PARTS) {
            const double *pr = x->parts + r * 3 * nv, a = pr[j->rate], b = pr[nv + j->rate], f = pr[2 * nv + j->rate];
            v[o++] = e[j->rate] - (a + b + f); /* the rigid-body part: the effort less the joint's own */
            v[o++] = a, v[o++] = b, v[o++] = f;
        }
        if (g & COLS_WORLD) {
            memcpy(v + o, rw + b6, 6 * sizeof *v);
            o += 6;
        }
        if (g & COLS_LINK) {
            memcpy(v + o, rl + b6, 6 * sizeof *v);
            o += 6;
        }
        if (g & COLS_BEARING) {
            memcpy(v + o, be + 4 * (size_t)(j->body - 1), 4 * sizeof *v);
            o += 4;
        }
        if (g & COLS_LIMITS) {
            memcpy(v + o, ex + 3 * (size_t)j->rate, 3 * sizeof *v);
            o += 3;
        }
    }
}

/* a block of rows formatted as CSV (the run's precision) into its buffer */
static void format_block(void *ctx, int first, int end, int k)
{
    run *x = ctx;
    block_state *b = &x->blk[k];
    const size_t need = (size_t)(end - first) * ((NUMBER_TEXT_MAX + 1) * (size_t)x->nout + 1);
    const int o = x->oset;
    b->len[o] = 0;
    if (need > b->cap[o]) {
        char *t = realloc(b->text[o], need);
        if (!t) {
            b->failed = first;
            snprintf(b->msg, ROW_MESSAGE, "out of memory");
            return;
        }
        b->text[o] = t;
        b->cap[o] = need;
    }
    char *p = b->text[o];
    const int prec = x->o->precision;
    for (int r = first; r < end; r++) {
        gather(x, r, b->v);
        for (int c = 0; c < x->nout; c++) {
            p += number_print(p, b->v[c], prec);
            *p++ = c + 1 < x->nout ? ',' : '\n';
        }
    }
    b->len[o] = (size_t)(p - b->text[o]);
}

/* a block of rows' values as little-endian float64 into the chunk's .npy rows */
static void encode_block(void *ctx, int first, int end, int k)
{
    (void)k;
    run *x = ctx;
    for (int r = first; r < end; r++) {
        double *v = x->vals[x->oset] + (size_t)r * (size_t)x->nout;
        gather(x, r, v);
#if !(defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)
        for (int c = 0; c < x->nout; c++) {
            uint64_t u, s = 0;
            memcpy(&u, v + c, 8);
            for (int b = 0; b < 8; b++) s |= ((u >> (8 * b)) & 0xFF) << (8 * (7 - b));
            memcpy(v + c, &s, 8);
        }
#endif
    }
}

/* the output's header: the CSV row of names, or the .npy header (with its row count when known,
 * else with room for any: rewritten by finish_output); 0 or 1 */
static int write_header(run *x, long long nrow)
{
    FILE *f = x->out.f;
    if (x->ofmt == FMT_CSV) {
        for (int k = 0; k < x->nout; k++) {
            fputs(x->names[k], f);
            fputc(k + 1 < x->nout ? ',' : '\n', f);
        }
        return 0;
    }
    char *h;
    size_t len, min = 0;
    const char *const *names = (const char *const *)x->names;
    if (nrow < 0) {
        if (!(min = x->npy_len = npy_max_header_len(names, x->nout))) return cmd_fail("out of memory");
        nrow = 0;
    }
    if (npy_header(&h, &len, names, x->nout, nrow, min)) return cmd_fail("out of memory");
    fwrite(h, 1, len, f);
    free(h);
    return 0;
}

/* the chunk's n rows formatted on the threads into the output set x->oset; 0 or 1 */
static int format_rows(run *x, int n)
{
    const double t0 = now();
    if (x->ofmt == FMT_NPY) {
        parallel_blocks(x->T, n, encode_block, x);
    } else {
        for (int k = 0; k < x->T; k++) x->blk[k].failed = -1;
        parallel_blocks(x->T, n, format_block, x);
        for (int k = 0; k < x->T; k++)
            if (x->blk[k].failed >= 0) return cmd_fail("%s", x->blk[k].msg);
    }
    x->t_write += now() - t0;
    return 0;
}

/* output set `set`, n rows formatted, written in order (its blocks' buffers, or its values) */
static void put_rows(run *x, int set, int n)
{
    if (x->ofmt == FMT_NPY) {
        fwrite(x->vals[set], 8 * (size_t)x->nout, (size_t)n, x->out.f);
    } else {
        for (int k = 0; k < x->T && k < n; k++) fwrite(x->blk[k].text[set], 1, x->blk[k].len[set], x->out.f);
    }
    x->written += n;
}

/* a .npy header written before the row count was known: rewritten with it, in place; 0 or 1 */
static int finish_output(run *x)
{
    if (x->ofmt != FMT_NPY || !x->npy_len) return 0;
    char *h;
    size_t len;
    if (npy_header(&h, &len, (const char *const *)x->names, x->nout, x->written, x->npy_len))
        return cmd_fail("out of memory");
    const int bad =
        len != x->npy_len || fflush(x->out.f) || fseek(x->out.f, 0, SEEK_SET) || fwrite(h, 1, len, x->out.f) != len;
    free(h);
    if (bad) return cmd_fail("%s: the .npy header could not be rewritten", x->out.tmp ? x->out.tmp : "stdout");
    return 0;
}

/* "row R of N" (or "row R, P% of the file"), rows per second and the time left on standard error
 * when it is a terminal and the file long, refreshed at most twice a second (and at the end);
 * *start is the time of the first row, *last that of the previous line (0 before the first) */
static void progress(const run *x, int done, double *start, double *last)
{
    const input *in = &x->in;
    const long long rows = in->fmt == FMT_NPY ? in->nrow : x->form == FORM_SAMPLES ? in->t.nrow : -1;
    const long long row = x->written;
    if (!isatty(2) || (rows >= 0 ? rows : row) < 2000) return;
    const double t = now();
    if (*last == 0.0) *start = *last = t;
    if (t - *last < 0.5 && !done) return;
    *last = t;
    const double rate = t > *start ? (double)row / (t - *start) : 0.0;
    double frac = rows > 0 ? (double)row / (double)rows : in->size > 0 ? (double)in->pos / (double)in->size : 0.0;
    if (rows >= 0) fprintf(stderr, "\rvtdyn: row %lld of %lld", row, rows);
    else fprintf(stderr, "\rvtdyn: row %lld, %.0f%% of the file", row, 100.0 * frac);
    if (rate > 0.0 && frac > 0.0)
        fprintf(stderr, ", %.0f rows/s, %.0f s left ", rate, (t - *start) * (1.0 - frac) / frac);
    if (done) fputc('\n', stderr);
}

/* ---- the two forms ----------------------------------------------------------------------- */

/* the batch's inputs and outputs for the chunk's first n rows: the run's arrays */
static vt_batch_io chunk_io(const run *x, int n)
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
    return io;
}

/* chunk row r's failing state (by the batch), at loc in the input, solved alone on the run's
 * data for its message */
static int state_failure(run *x, int r, long long loc)
{
    const vt_model *m = x->m;
    vt_data *d = x->d;
    char where[ROW_WHERE];
    memcpy(d->q, x->q + (size_t)r * (size_t)m->nq, (size_t)m->nq * sizeof *d->q);
    memcpy(d->qd, x->qd + (size_t)r * (size_t)m->nv, (size_t)m->nv * sizeof *d->qd);
    memcpy(d->qdd, x->qdd + (size_t)r * (size_t)m->nv, (size_t)m->nv * sizeof *d->qdd);
    const vt_status st = vt_inverse_dynamics_motion(m, d);
    input_where(&x->in, loc, where);
    if (st) return cmd_fail("%s: %s (%s)", where, d->message, vt_status_string(st));
    return cmd_fail("%s: %s (%s)", where, vt_batch_message(x->batch), vt_status_string(x->status[r]));
}

/* chunk x->chp's n rows parsed and laid out as states (on the threads), solved by the batch
 * and formatted into output set `set`; 0, or 1 at its first failing row (a cell or a
 * quaternion, or the solve: the lowest) */
static int solve_chunk(run *x, int n, int set)
{
    const double t0 = now();
    for (int k = 0; k < x->T; k++) x->blk[k].failed = -1;
    parallel_blocks(x->T, n, fill_block, x);
    int f = n, fk = -1; /* the first row whose numbers or quaternion fail */
    for (int k = 0; k < x->T && fk < 0; k++)
        if (x->blk[k].failed >= 0) f = x->blk[fk = k].failed;
    const double t1 = now();
    x->t_read += t1 - t0;
    vt_batch_io io = chunk_io(x, f);
    const vt_status st = vt_batch_inverse_dynamics_motion(x->batch, &io);
    x->t_solve += now() - t1;
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

static void *file_work(void *arg)
{
    file_job *j = arg;
    run *x = j->x;
    cmd_message_sink(j->msg, sizeof j->msg);
    const double t0 = now();
    if (j->wn > 0) put_rows(x, j->wset, j->wn);
    const double t1 = now();
    j->status = j->rbuf >= 0 ? input_read(&x->in, &x->ch[j->rbuf], x->K, CHUNK_BYTES / 4) : 0;
    j->t_write = t1 - t0;
    j->t_read = now() - t1;
    cmd_message_sink(NULL, 0);
    return NULL;
}

/* states: chunk after chunk parsed and laid out (on the threads), solved by the batch, formatted
 * (on the threads) and written in order. With more than one thread the file's work — the chunk
 * before written, the chunk after read — runs on a thread of its own beside them (two chunks
 * read, two output sets); with one, in turn on the caller's thread. 0, or 1 at the chunk's first
 * failing row (the chunks before it written) */
static int run_states(run *x)
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

/* samples: each row solved in turn (Newton on the spline drives at its t), gathered a chunk at a
 * time and written; 0, or 1 at the first row that fails */
static int run_samples(run *x)
{
    double start = 0.0, last = 0.0;
    const vt_model *m = x->m;
    vt_data *d = x->d;
    const table *t = &x->in.t;
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb = (size_t)m->nbody;
    if (write_header(x, t->nrow)) return 1;
    for (int r0 = 0; r0 < t->nrow; r0 += x->K) {
        const int n = t->nrow - r0 < x->K ? t->nrow - r0 : x->K;
        const double t0 = now();
        for (int r = 0; r < n; r++) {
            const double *row = table_row(t, r0 + r);
            for (int k = 0; k < x->nj; k++) d->q[m->body_qadr[x->jc[k].body]] = row[x->jc[k].col];
            d->time = row[x->ct];
            const vt_status st = vt_kinematic_solve(m, d, x->opt.newton_tol, x->opt.newton_maxit);
            if (st) {
                char where[ROW_WHERE];
                return cmd_fail("%s: %s (%s)", input_where(&x->in, t->loc[r0 + r], where), d->message,
                                vt_status_string(st));
            }
            double *e = x->effort + r * nv;
            for (int k = 0; k < x->nj; k++) e[x->jc[k].rate] = d->drive_effort[k];
            if (x->parts) {
                double *pr = x->parts + r * 3 * nv;
                memcpy(pr, d->effort_armature, nv * sizeof(double));
                memcpy(pr + nv, d->effort_damping, nv * sizeof(double));
                memcpy(pr + 2 * nv, d->effort_friction, nv * sizeof(double));
            }
            memcpy(x->q + r * nq, d->q, nq * sizeof *d->q);
            if ((x->reac_link || x->bearing) && vt_reactions_joint_frame(m, d)) return cmd_fail("%s", d->message);
            for (size_t i = 1; i <= nb; i++) {
                if (x->reac) {
                    memcpy(x->reac + r * 6 * nb + 6 * (i - 1), d->jnt_force + 3 * i, 3 * sizeof(double));
                    memcpy(x->reac + r * 6 * nb + 6 * (i - 1) + 3, d->jnt_moment + 3 * i, 3 * sizeof(double));
                }
                if (x->reac_link) {
                    memcpy(x->reac_link + r * 6 * nb + 6 * (i - 1), d->jnt_force_joint + 3 * i, 3 * sizeof(double));
                    memcpy(x->reac_link + r * 6 * nb + 6 * (i - 1) + 3, d->jnt_moment_joint + 3 * i, 3 * sizeof(double));
                }
            }
            if (x->bearing) memcpy(x->bearing + r * 4 * nb, d->jnt_bearing + 4, 4 * nb * sizeof(double));
            if (x->excess) memcpy(x->excess + r * 3 * nv, d->limit_excess, 3 * nv * sizeof(double));
        }
        x->t_solve += now() - t0;
        x->incells = table_row(t, r0);
        x->oset = 0;
        if (format_rows(x, n)) return 1;
        const double t1 = now();
        put_rows(x, 0, n);
        x->t_write += now() - t1;
        progress(x, 0, &start, &last);
    }
    progress(x, 1, &start, &last);
    return 0;
}

/* spline k of x->splines at time t: out = [f, f', f'']; 0 or 1 */
static int spline_at(const run *x, int k, double t, double out[3])
{
    const vt_status st = vt_function_eval(out, &x->splines->drive[k].f, t);
    return st ? cmd_fail("%s: spline %d at t = %.17g: %s", x->states, k, t, vt_status_string(st)) : 0;
}

/* chunk row r's state from the splines at time t: each joint's position, velocity and
 * acceleration; a floating root's x, y, z and their derivatives (its origin's velocity and
 * acceleration, world axes), and from the quaternion components' splines s(t): n = |s|, the
 * orientation p = s/n, its rates ṗ = (ṡ − p (p·ṡ))/n and p̈ = (s̈ − 2 ṗ (p·ṡ) − p (ṗ·ṡ + p·s̈))/n
 * (the derivatives of s/|s|, with ṅ = p·ṡ and n̈ = ṗ·ṡ + p·s̈), the angular velocity ω = 2 E(p) ṗ
 * and acceleration α = 2 E(p) p̈ in world axes (α = d/dt 2 E(p) ṗ, whose other term 2 E(ṗ) ṗ is 0:
 * E(a) a = 0 for any a). At a sample's time s is the unit sample itself, so n = 1 to round-off.
 * 0 or 1 */
static int fill_sample(const run *x, int r, double t)
{
    const vt_model *m = x->m;
    double *q = x->q + (size_t)r * (size_t)m->nq, *qd = x->qd + (size_t)r * (size_t)m->nv,
           *qdd = x->qdd + (size_t)r * (size_t)m->nv;
    for (int k = 0; k < x->nj; k++) {
        const joint_cols *j = &x->jc[k];
        double v[3];
        if (!j->free) {
            if (spline_at(x, j->spl, t, v)) return 1;
            q[j->qadr] = v[0], qd[j->rate] = v[1], qdd[j->rate] = v[2];
            continue;
        }
        for (int c = 0; c < 3; c++) {
            if (spline_at(x, j->spl + c, t, v)) return 1;
            q[j->qadr + c] = v[0], qd[j->rate + c] = v[1], qdd[j->rate + c] = v[2];
        }
        double s[4], sd[4], sdd[4], nn = 0.0;
        for (int c = 0; c < 4; c++) {
            if (spline_at(x, j->spl + 3 + c, t, v)) return 1;
            s[c] = v[0], sd[c] = v[1], sdd[c] = v[2];
            nn += s[c] * s[c];
        }
        nn = sqrt(nn);
        double p[4], pd[4], pdd[4], psd = 0.0, pdsd = 0.0, psdd = 0.0;
        for (int c = 0; c < 4; c++) {
            p[c] = s[c] / nn;
            psd += p[c] * sd[c];
            psdd += p[c] * sdd[c];
        }
        for (int c = 0; c < 4; c++) {
            pd[c] = (sd[c] - p[c] * psd) / nn;
            pdsd += pd[c] * sd[c];
        }
        for (int c = 0; c < 4; c++) pdd[c] = (sdd[c] - 2.0 * pd[c] * psd - p[c] * (pdsd + psdd)) / nn;
        double E[12];
        vt_euler_E(E, p);
        for (int c = 0; c < 4; c++) q[j->qadr + 3 + c] = p[c];
        for (int a = 0; a < 3; a++) {
            double w = 0.0, al = 0.0;
            for (int c = 0; c < 4; c++) {
                w += E[a + 3 * c] * pd[c];
                al += E[a + 3 * c] * pdd[c];
            }
            qd[j->rate + 3 + a] = 2.0 * w;
            qdd[j->rate + 3 + a] = 2.0 * al;
        }
    }
    return 0;
}

/* samples with a floating root: a chunk of rows at a time, each row's state from the splines at
 * its t, solved by the batch as states are, formatted and written; 0, or 1 at the first row that
 * fails */
static int run_samples_motion(run *x)
{
    double start = 0.0, last = 0.0;
    const table *t = &x->in.t;
    if (write_header(x, t->nrow)) return 1;
    for (int r0 = 0; r0 < t->nrow; r0 += x->K) {
        const int n = t->nrow - r0 < x->K ? t->nrow - r0 : x->K;
        const double t0 = now();
        for (int r = 0; r < n; r++)
            if (fill_sample(x, r, x->ts[r0 + r])) return 1;
        vt_batch_io io = chunk_io(x, n);
        const vt_status st = vt_batch_inverse_dynamics_motion(x->batch, &io);
        x->t_solve += now() - t0;
        if (st) {
            for (int r = 0; r < n; r++)
                if (x->status[r] != VT_OK) return state_failure(x, r, t->loc[r0 + r]);
            return cmd_fail("%s: %s (%s)", x->states, vt_batch_message(x->batch), vt_status_string(st));
        }
        x->incells = table_row(t, r0);
        x->oset = 0;
        if (format_rows(x, n)) return 1;
        const double t1 = now();
        put_rows(x, 0, n);
        x->t_write += now() - t1;
        progress(x, 0, &start, &last);
    }
    progress(x, 1, &start, &last);
    return 0;
}

/* the output's format: --format, else -o's name (.npy), else CSV; npy on standard output only
 * with the row count known ahead; 0 or 1 */
static int output_format(run *x, const char *outpath)
{
    const int named = outpath ? (int)format_of(outpath) : -1;
    if (x->o->format >= 0 && outpath) {
        const size_t n = strlen(outpath);
        const int csvname = n >= 4 && strcmp(outpath + n - 4, ".csv") == 0;
        if ((x->o->format == FMT_CSV && named == FMT_NPY) || (x->o->format == FMT_NPY && csvname))
            return cmd_fail("-o %s and --format %s disagree", outpath, x->o->format == FMT_NPY ? "npy" : "csv");
    }
    x->ofmt = x->o->format >= 0 ? (file_format)x->o->format : named == FMT_NPY ? FMT_NPY : FMT_CSV;
    if (x->ofmt == FMT_NPY && !outpath && x->in.fmt != FMT_NPY && x->form != FORM_SAMPLES)
        return cmd_fail("--format npy on standard output needs the row count ahead, which a CSV file of states does "
                        "not give: write to a file, -o OUT.npy");
    if (x->ofmt == FMT_NPY && x->o->precision_given)
        return cmd_fail("--precision: a .npy output holds every value's float64 exactly (it is for CSV)");
    return 0;
}

int cmd_inverse(const char *urdf, const char *states, const char *outpath, const inverse_options *o)
{
    /* Newton's tolerance and iteration limit for the samples: the library's defaults (1e-12, 30) */
    run x = {.urdf = urdf, .states = states, .o = o, .form = FORM_UNKNOWN, .opt = vt_default_run_options()};
    /* numbers read and written with a '.' whatever LC_NUMERIC: this thread in the C locale (the
     * threads' blocks set their own) */
    locale_t cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!cloc) return cmd_fail("out of memory (the C locale)");
    const locale_t oldloc = uselocale(cloc);
    int status = input_open(&x.in, states) || load_robot(&x, o) || map_joints(&x) ||
                 map_floating_roots(&x) || check_columns(&x, o->floating) || build_model(&x) ||
                 output_columns(&x) || output_format(&x, outpath) || chunk_arrays(&x);
    if (!status) {
        const char *inputs[2] = {urdf, states};
        status = output_open(&x.out, outpath, inputs, 2);
        if (!status) {
            static char obuf[1 << 20];
            setvbuf(x.out.f, obuf, _IOFBF, sizeof obuf);
            const double t0 = now();
            const int ok = !(x.form == FORM_SAMPLES ? (x.nfree ? run_samples_motion(&x) : run_samples(&x))
                                                    : run_states(&x)) &&
                           !finish_output(&x);
            status = output_close(&x.out, ok);
            if (o->times && ok) {
                const double all = now() - t0;
                fprintf(stderr,
                        "vtdyn: %lld rows in %.3f s (%.0f rows/s, %d threads): read %.3f s, solve %.3f s, "
                        "write %.3f s\n",
                        x.written, all, all > 0 ? (double)x.written / all : 0.0, x.T, x.t_read, x.t_solve, x.t_write);
            }
        }
    }
    run_free(&x);
    uselocale(oldloc);
    freelocale(cloc);
    return status;
}

/* ---- info: the states file's header ---------------------------------------------------------- */

int cmd_states_header(const vt_model *p, FILE *out)
{
    for (int i = 1; i <= p->nbody; i++) {
        const int jt = p->body_joint[i];
        if ((jt == VT_JOINT_FREE && p->body_parent[i] != 0) ||
            (jt != VT_JOINT_FREE && (jt == VT_JOINT_BASE || jt == VT_JOINT_SPHERICAL || p->body_nv[i] != 1))) {
            fprintf(out, "states columns: none: `inverse` does not take joint '%s' (%s)\n",
                    p->joint_name + VT_NAME_MAX * i, cmd_joint_kind(jt));
            return 1;
        }
    }
    fputs("states columns (a header for `inverse`; t may come first):\n", out);
    const char *sep = "";
    for (int i = 1; i <= p->nbody; i++) {
        if (p->body_joint[i] == VT_JOINT_FREE) continue;
        const char *n = p->joint_name + VT_NAME_MAX * i;
        fprintf(out, "%s%s,%s_vel,%s_acc", sep, n, n, n);
        sep = ",";
    }
    for (int i = 1; i <= p->nbody; i++) { /* the floating roots last, as `inverse` lists them */
        if (p->body_joint[i] != VT_JOINT_FREE) continue;
        const char *n = p->joint_name + VT_NAME_MAX * i;
        if (!n[0]) n = p->body_name + VT_NAME_MAX * i;
        for (int k = 0; k < NFREE; k++) {
            fprintf(out, "%s%s_%s", sep, n, free_suffix[k]);
            sep = ",";
        }
    }
    fputc('\n', out);
    return 0;
}
