/* The command's `inverse`: a URDF robot's efforts and joint reactions, one output row per row of
 * a CSV file of states (positions, velocities, accelerations: vt_inverse_dynamics_motion) or of
 * samples of a trajectory (positions and t: a spline drive on each joint, vt_kinematic_solve).
 * The jobs in order: the columns mapped to the joints, the model built (with the spline drives
 * for samples), the output opened beside its name, each row solved and written. */
#define _POSIX_C_SOURCE 200809L
#include "inverse.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "csv.h"
#include "message.h"
#include "robot.h"
#include "vtdyn.h"

/* a floating root's input columns, after its name and '_' */
#define NFREE 19
static const char *const free_suffix[NFREE] = {"x",  "y",  "z",  "qw", "qx", "qy", "qz", "vx",  "vy",  "vz",
                                               "wx", "wy", "wz", "ax", "ay", "az", "alx", "aly", "alz"};

/* one moving joint's input columns and output */
typedef struct {
    int body, rate;       /* the joint's body and its (first) rate */
    int col, col_vel, col_acc;
    int free;             /* a floating root: its columns in fcol */
    int fcol[NFREE];
    int frame;            /* the child link's frame (its URDF axes), or -1 */
    const char *name;
} joint_cols;

/* what the rows give */
typedef enum {
    FORM_UNKNOWN, /* not yet known: no one-rate joint seen */
    FORM_STATES,  /* J, J_vel and J_acc for every joint: states */
    FORM_SAMPLES  /* t and the positions J alone: samples of a trajectory */
} form;

/* one run of `inverse`: its files, model and columns, freed by run_free */
typedef struct {
    const char *urdf, *states; /* the files' names, for the messages */
    table t;                   /* the input */
    vt_builder *b;
    vt_model *probe;           /* the robot as loaded; the joints' names point into it */
    vt_model *m;               /* the robot solved: with a spline drive per joint for samples */
    vt_data *d;
    joint_cols *jc;            /* the moving joints, in the model's order, floating roots last */
    int nj;
    int ct;                    /* the column t, or -1 */
    form form;
    double *ts;                /* the samples' times (column t), for the splines */
    double *effort;            /* one row's efforts: 6 a joint (the first alone for a one-rate joint) */
    vt_run_options opt;        /* Newton's tolerance and iteration limit for the samples */
} run;

/* frees what the run holds (any part not yet made is NULL) */
static void run_free(run *x)
{
    free(x->ts);
    free(x->jc);
    free(x->effort);
    vt_data_free(x->d);
    vt_model_free(x->m);
    vt_model_free(x->probe);
    vt_builder_free(x->b);
    table_free(&x->t);
}

/* loads the URDF and builds it once as it is (the probe, whose joints name the columns); 0 or 1 */
static int load_robot(run *x, int floating)
{
    if (cmd_load_urdf(&x->b, x->urdf, floating)) return 1;
    const vt_status st = vt_builder_build(&x->probe, x->b);
    if (st) return cmd_fail("%s: %s%s", x->urdf, vt_builder_message(x->b), cmd_empty_hint(st, floating));
    x->jc = calloc((size_t)x->probe->nbody, sizeof *x->jc);
    x->effort = calloc(6 * ((size_t)x->probe->nbody + 1), sizeof *x->effort);
    if (!x->jc || !x->effort) return cmd_fail("out of memory");
    return 0;
}

/* the one-rate joints' columns J, J_vel, J_acc, and from them the form (states or samples):
 * every joint needs its position, and its rates' columns all or none alike; 0 or 1 */
static int map_joints(run *x)
{
    const vt_model *p = x->probe;
    x->ct = table_column(&x->t, "t");
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
        j->col = table_column(&x->t, name);
        snprintf(key, sizeof key, "%s_vel", name);
        j->col_vel = table_column(&x->t, key);
        snprintf(key, sizeof key, "%s_acc", name);
        j->col_acc = table_column(&x->t, key);
        j->frame = vt_find_frame(p, p->body_name + VT_NAME_MAX * i);
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

/* the floating roots' columns R_x ... R_alz (states only: no spline through orientations), after
 * the one-rate joints; then a column t for samples; 0 or 1 */
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
        char kx[VT_NAME_MAX + 8], kv[VT_NAME_MAX + 8], ka[VT_NAME_MAX + 8];
        snprintf(kx, sizeof kx, "%s_x", name);
        snprintf(kv, sizeof kv, "%s_vx", name);
        snprintf(ka, sizeof ka, "%s_ax", name);
        if (x->form == FORM_SAMPLES ||
            (table_column(&x->t, kx) >= 0 && table_column(&x->t, kv) < 0 && table_column(&x->t, ka) < 0))
            return cmd_fail("%s: positions alone (samples of a trajectory) with a floating root '%s': not supported "
                            "(no spline through orientations); give the states: %s_x ... %s_alz and every joint's "
                            "_vel and _acc",
                            x->states, name, name, name);
        joint_cols *j = &x->jc[x->nj++];
        j->body = i;
        j->rate = p->body_vadr[i];
        j->name = name;
        j->free = 1;
        j->frame = vt_find_frame(p, p->body_name + VT_NAME_MAX * i);
        for (int k = 0; k < NFREE; k++) {
            char key[VT_NAME_MAX + 8];
            snprintf(key, sizeof key, "%s_%s", name, free_suffix[k]);
            if ((j->fcol[k] = table_column(&x->t, key)) < 0)
                return cmd_fail("%s: no column '%s' (floating root %s: %s_x ... %s_alz, see --help%s)", x->states,
                                key, name, name, name,
                                p->body_joint[i] == VT_JOINT_FREE && p->joint_name[VT_NAME_MAX * i] == '\0'
                                    ? "; without --floating the root link is fixed to the world"
                                    : "");
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
    for (int c = 0; c < x->t.ncol; c++) {
        if (x->t.used[c]) continue;
        const char *name = x->t.name[c], *sfx = free_column_suffix(name);
        if (!floating && sfx) { /* P_x ... with P a link fixed to the world: the root, floating in the file */
            char root[VT_NAME_MAX];
            const size_t len = (size_t)(sfx - 1 - name);
            if (len < sizeof root) {
                memcpy(root, name, len);
                root[len] = '\0';
                const int f = vt_find_frame(p, root);
                if (f >= 0 && p->frame_body[f] == 0)
                    return cmd_fail("%s:%d: column %d '%s': a floating root's column, but %s is loaded with its root "
                                    "link '%s' fixed to the world: run with --floating",
                                    x->states, x->t.header_line, c + 1, name, x->urdf, root);
            }
        }
        return cmd_fail("%s:%d: column %d '%s' is none of the robot's (%s): every column must be t, a moving joint J's "
                        "J, J_vel or J_acc, or a floating root R's R_x ... R_alz (vtdyn info lists the joints)",
                        x->states, x->t.header_line, c + 1, name, x->urdf);
    }
    return 0;
}

/* v in the fewest significant digits that read back as v (at most 17), into buf */
static const char *shortest(char buf[32], double v)
{
    for (int digits = 1; digits <= 17; digits++) {
        snprintf(buf, 32, "%.*g", digits, v);
        if (strtod(buf, NULL) == v) break;
    }
    return buf;
}

/* the samples' times, column t, into x->ts: strictly increasing, or the first row whose t is not
 * after the row before's named (as the other row errors: its line in a file without blank lines,
 * the header line 1); 0 or 1 */
static int sample_times(run *x)
{
    const int n = x->t.nrow;
    x->ts = malloc((size_t)n * sizeof *x->ts);
    if (!x->ts) return cmd_fail("out of memory");
    for (int r = 0; r < n; r++) x->ts[r] = table_row(&x->t, r)[x->ct];
    for (int r = 1; r < n; r++) {
        if (x->ts[r] > x->ts[r - 1]) continue;
        char now[32], before[32];
        if (x->ts[r] == x->ts[r - 1])
            return cmd_fail("%s:%d: column 't': %s again (as on the row before): samples of a trajectory (positions "
                            "alone) need 't' increasing from row to row",
                            x->states, r + 2, shortest(now, x->ts[r]));
        return cmd_fail("%s:%d: column 't': %s after %s on the row before: samples of a trajectory (positions "
                        "alone) need 't' increasing from row to row",
                        x->states, r + 2, shortest(now, x->ts[r]), shortest(before, x->ts[r - 1]));
    }
    return 0;
}

/* for samples, a joint drive on every joint, following the cubic spline through its column's
 * samples over t (the drives in the joints' order, drive k on joint k); 0 or 1 */
static int add_spline_drives(run *x)
{
    if (sample_times(x)) return 1;
    double *ys = malloc((size_t)x->t.nrow * sizeof *ys);
    if (!ys) return cmd_fail("out of memory");
    for (int k = 0; k < x->nj; k++) { /* (no floating root here) */
        for (int r = 0; r < x->t.nrow; r++) ys[r] = table_row(&x->t, r)[x->jc[k].col];
        vt_drive_def dr = vt_default_drive_def();
        dr.body = x->jc[k].body;
        dr.f = vt_function_spline(x->t.nrow, x->ts, ys);
        if (vt_builder_add_drive(x->b, &dr) < 0) {
            cmd_fail("%s: column '%s' as samples: %s", x->states, x->jc[k].name, vt_builder_message(x->b));
            free(ys);
            return 1;
        }
    }
    free(ys);
    return 0;
}

/* the model solved (the robot, with the spline drives for samples) and its data; 0 or 1 */
static int build_model(run *x)
{
    if (x->form == FORM_SAMPLES && add_spline_drives(x)) return 1;
    if (vt_builder_build(&x->m, x->b) || vt_data_create(&x->d, x->m))
        return cmd_fail("%s: %s", x->urdf, vt_builder_message(x->b));
    return 0;
}

/* the output's header row: t when given, then each joint's columns */
static void write_header(FILE *out, const run *x)
{
    if (x->ct >= 0) fputs("t,", out);
    for (int k = 0; k < x->nj; k++) {
        const char *n = x->jc[k].name, *end = k + 1 < x->nj ? "," : "\n";
        if (x->jc[k].free) {
            fprintf(out, "%s_effort_fx,%s_effort_fy,%s_effort_fz,%s_effort_nx,%s_effort_ny,%s_effort_nz,"
                         "%s_effort_fx_link,%s_effort_fy_link,%s_effort_fz_link,%s_effort_nx_link,%s_effort_ny_link,"
                         "%s_effort_nz_link%s",
                    n, n, n, n, n, n, n, n, n, n, n, n, end);
            continue;
        }
        fprintf(out, "%s_effort,%s_fx,%s_fy,%s_fz,%s_nx,%s_ny,%s_nz,%s_fx_link,%s_fy_link,%s_fz_link,%s_nx_link,"
                     "%s_ny_link,%s_nz_link%s",
                n, n, n, n, n, n, n, n, n, n, n, n, n, end);
    }
}

/* one output row from the solved data: t when given, then per joint its effort and reaction in
 * world axes and in the child link's (a floating root: its six efforts, world then link axes) */
static void write_row(FILE *out, const run *x, const double *row)
{
    const vt_model *m = x->m;
    vt_data *d = x->d;
    if (x->ct >= 0) fprintf(out, "%.17g,", row[x->ct]);
    for (int k = 0; k < x->nj; k++) {
        const joint_cols *j = &x->jc[k];
        const int i = j->body;
        const char *end = k + 1 < x->nj ? "," : "\n";
        const double *f = j->free ? x->effort + 6 * k : d->jnt_force + 3 * i;
        const double *n = j->free ? f + 3 : d->jnt_moment + 3 * i;
        double R[9], fl[3], nl[3];
        const int framed = j->frame >= 0 && vt_frame_pose(m, d, j->frame, NULL, R) == VT_OK;
        if (framed || j->free) {
            if (!framed) memcpy(R, d->A + 9 * i, sizeof R); /* no link frame: the body's own axes */
            for (int c = 0; c < 3; c++) {
                fl[c] = R[3 * c] * f[0] + R[3 * c + 1] * f[1] + R[3 * c + 2] * f[2];
                nl[c] = R[3 * c] * n[0] + R[3 * c + 1] * n[1] + R[3 * c + 2] * n[2];
            }
        } else { /* no link frame: the body's own axes */
            memcpy(fl, d->jnt_force_body + 3 * i, sizeof fl);
            memcpy(nl, d->jnt_moment_body + 3 * i, sizeof nl);
        }
        if (!j->free) fprintf(out, "%.17g,", x->effort[6 * k]);
        fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g%s", f[0], f[1], f[2],
                n[0], n[1], n[2], fl[0], fl[1], fl[2], nl[0], nl[1], nl[2], end);
    }
}

/* a floating root's state from data row r: its position, quaternion (normalised, refused beyond
 * 1e-6 of the unit norm) and six rates and accelerations into d; 0 or 1 */
static int set_floating_root(run *x, const joint_cols *j, const double *row, int r)
{
    const int *fc = j->fcol;
    double *q = x->d->q + x->m->body_qadr[j->body], *qd = x->d->qd + j->rate, *qdd = x->d->qdd + j->rate;
    double nq = 0.0;
    for (int c = 0; c < 3; c++) q[c] = row[fc[c]];
    for (int c = 0; c < 4; c++) nq += row[fc[3 + c]] * row[fc[3 + c]];
    nq = sqrt(nq);
    if (!(fabs(nq - 1.0) <= 1e-6))
        return cmd_fail("%s:%d: columns '%s_qw' ... '%s_qz': a quaternion of norm %.17g, not 1 (within 1e-6)",
                        x->states, r + 2, j->name, j->name, nq);
    for (int c = 0; c < 4; c++) q[3 + c] = row[fc[3 + c]] / nq;
    for (int c = 0; c < 6; c++) {
        qd[c] = row[fc[7 + c]];
        qdd[c] = row[fc[13 + c]];
    }
    return 0;
}

/* solves data row r into x->effort and the data's reactions: the positions (and a floating
 * root's state) set, then for samples Newton on the drives at the row's t, for states the
 * motion's inverse dynamics; 0, or 1 with the message naming the row (its line in a file
 * without blank lines) */
static int solve_row(run *x, int r)
{
    const vt_model *m = x->m;
    vt_data *d = x->d;
    const double *row = table_row(&x->t, r);
    vt_status st;
    for (int k = 0; k < x->nj; k++) {
        if (!x->jc[k].free) d->q[m->body_qadr[x->jc[k].body]] = row[x->jc[k].col];
        else if (set_floating_root(x, &x->jc[k], row, r)) return 1;
    }
    if (x->form == FORM_SAMPLES) {
        d->time = row[x->ct];
        st = vt_kinematic_solve(m, d, x->opt.newton_tol, x->opt.newton_maxit);
        for (int k = 0; k < x->nj && !st; k++) x->effort[6 * k] = d->drive_effort[k];
    } else {
        for (int k = 0; k < x->nj; k++) {
            if (x->jc[k].free) continue;
            d->qd[x->jc[k].rate] = row[x->jc[k].col_vel];
            d->qdd[x->jc[k].rate] = row[x->jc[k].col_acc];
        }
        st = vt_inverse_dynamics_motion(m, d);
        for (int k = 0; k < x->nj && !st; k++)
            for (int c = 0; c < (x->jc[k].free ? 6 : 1); c++) x->effort[6 * k + c] = d->qfrc_drive[x->jc[k].rate + c];
    }
    if (st) return cmd_fail("%s:%d: %s (%s)", x->states, r + 2, d->message, vt_status_string(st));
    return 0;
}

/* "row R of N, rows per second, time left" on standard error when it is a terminal and the file
 * long, refreshed at most twice a second (and at the last row); *start is the time of the first
 * row, *last that of the previous line (0 before the first) */
static void progress(int row, int nrow, double *start, double *last)
{
    if (!isatty(2) || nrow < 2000) return;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    const double now = (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
    if (*last == 0.0) *start = *last = now;
    if (now - *last < 0.5 && row + 1 < nrow) return;
    *last = now;
    const double rate = now > *start ? (double)(row + 1) / (now - *start) : 0.0;
    if (rate > 0.0)
        fprintf(stderr, "\rvtdyn: row %d of %d, %.0f rows/s, %.0f s left ", row + 1, nrow, rate,
                (double)(nrow - row - 1) / rate);
    else
        fprintf(stderr, "\rvtdyn: row %d of %d", row + 1, nrow);
    if (row + 1 == nrow) fputc('\n', stderr);
}

/* the header, then each row solved and written; 0, or 1 at the first row that fails */
static int write_rows(run *x, FILE *out)
{
    double start = 0.0, last = 0.0;
    write_header(out, x);
    for (int r = 0; r < x->t.nrow; r++) {
        if (solve_row(x, r)) return 1;
        write_row(out, x, table_row(&x->t, r));
        progress(r, x->t.nrow, &start, &last);
    }
    return 0;
}

int cmd_inverse(const char *urdf, const char *states, const char *outpath, int floating)
{
    /* Newton's tolerance and iteration limit for the samples: the library's defaults (1e-12, 30) */
    run x = {.urdf = urdf, .states = states, .form = FORM_UNKNOWN, .opt = vt_default_run_options()};
    int status = table_read(&x.t, states);
    if (!status)
        status = load_robot(&x, floating) || map_joints(&x) || map_floating_roots(&x) || check_columns(&x, floating) ||
                 build_model(&x);
    if (!status) {
        output out;
        const char *inputs[2] = {urdf, states};
        status = output_open(&out, outpath, inputs, 2);
        if (!status) status = output_close(&out, !write_rows(&x, out.f));
    }
    run_free(&x);
    return status;
}
