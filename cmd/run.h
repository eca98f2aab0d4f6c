/* The command's `inverse`: what one run holds — its files, model, columns, chunk and output —
 * shared by its parts (cmd/inverse.c: the columns mapped and the model built; cmd/states.c and
 * cmd/samples.c: the two forms of input; cmd/output.c: the output). */
#ifndef VTDYN_CMD_RUN_H
#define VTDYN_CMD_RUN_H

#include <stddef.h>
#include <time.h>

#include "csv.h"
#include "input.h"
#include "inverse.h"
#include "parallel.h"
#include "vtdyn.h"

/* a floating root's input columns, after its name and '_' */
#define NFREE 19
extern const char *const free_suffix[NFREE];

/* the rows of a chunk, at most: on one thread few enough that they stay in the core's cache from
 * their parsing through the solve to their output; on more, eight times as many, since each chunk
 * costs the threads' wake-ups and waits (bench/bench_command.sh, docs/command.md). And the bytes
 * a chunk's arrays may take (fewer rows for a large robot). */
#define CHUNK_ROWS 512
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
    vt_model *m;               /* the robot solved */
    vt_model *splines;         /* samples: the splines, as drives (samples.h) */
    int nfree;                 /* the floating roots */
    vt_data *d;                /* one data: the rows' q before they are read, a failing row's message */
    vt_batch *batch;           /* the rows' solver */
    joint_cols *jc;            /* the moving joints, in the model's order, floating roots last */
    int nj;
    int ct;                    /* the column t, or -1 */
    form form;
    double *ts;                /* the samples' times (column t), for the splines */
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
    int r0;                    /* samples: the chunk's first row (its blocks' work, sample_block) */
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
    team tm;                   /* the threads of the parsing and formatting */
    block_state *blk;          /* tm.nblock */
    table_key *frames;         /* the probe's frames sorted by name (nframe): a link's frame in log n */
    /* --contacts: the feet on the ground */
    int ncontact;
    vt_contact_def *cdef;      /* their definitions (ncontact), names in cname */
    char (*cname)[VT_NAME_MAX];
    int *ccol;                 /* each contact's input column C_active, or -1: always on (ncontact) */
    int *active;               /* the rows' active contacts (K x ncontact) */
    double *cforce;            /* the rows' ground forces (K x 3 ncontact) */
    vt_contacts *contacts;     /* a failing row's message: solved alone on d with these */
    /* --loads: wrenches at frames */
    int nload;
    int *lframe;               /* their frames in the solved model (nload) */
    int *lcol;                 /* their input columns F_fx ... F_nz (6 nload) */
    double *load;              /* the rows' wrenches (K x 6 nload) */
    /* the time spent, s */
    double t_read, t_solve, t_write;
} run;

/* a monotonic clock, s */
static inline double run_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
