/* The command's `inverse`, the samples form: t and the joints' positions alone, samples of a
 * trajectory. Cubic splines through each joint's positions, and with a floating root through its
 * position and its quaternion's components (made sign-continuous, then normalised: ω = 2 E(p) ṗ,
 * α = 2 E(p) p̈), give each row's state at its t (on the batch's threads, a chunk's rows in
 * blocks), solved by the batch as the states are. */
#define _POSIX_C_SOURCE 200809L
#include "samples.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "message.h"
#include "number_text.h"
#include "output.h"
#include "parallel.h"
#include "states.h"

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

int spline_model(run *x)
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

/* spline k of x->splines at time t: out = [f, f', f'']; 0, or 1 with the message in msg
 * (ROW_MESSAGE bytes; safe on threads) */
static int spline_at(const run *x, int k, double t, double out[3], char *msg)
{
    const vt_status st = vt_function_eval(out, &x->splines->drive[k].f, t);
    if (st) snprintf(msg, ROW_MESSAGE, "%s: spline %d at t = %.17g: %s", x->states, k, t, vt_status_string(st));
    return st != VT_OK;
}

/* chunk row r's state from the splines at time t: each joint's position, velocity and
 * acceleration; a floating root's x, y, z and their derivatives (its origin's velocity and
 * acceleration, world axes), and from the quaternion components' splines s(t): n = |s|, the
 * orientation p = s/n, its rates ṗ = (ṡ − p (p·ṡ))/n and p̈ = (s̈ − 2 ṗ (p·ṡ) − p (ṗ·ṡ + p·s̈))/n
 * (the derivatives of s/|s|, with ṅ = p·ṡ and n̈ = ṗ·ṡ + p·s̈), the angular velocity ω = 2 E(p) ṗ
 * and acceleration α = 2 E(p) p̈ in world axes (α = d/dt 2 E(p) ṗ, whose other term 2 E(ṗ) ṗ is 0:
 * E(a) a = 0 for any a). At a sample's time s is the unit sample itself, so n = 1 to round-off.
 * 0, or 1 with the message in msg */
static int fill_sample(const run *x, int r, double t, char *msg)
{
    const vt_model *m = x->m;
    double *q = x->q + (size_t)r * (size_t)m->nq, *qd = x->qd + (size_t)r * (size_t)m->nv,
           *qdd = x->qdd + (size_t)r * (size_t)m->nv;
    for (int k = 0; k < x->nj; k++) {
        const joint_cols *j = &x->jc[k];
        double v[3];
        if (!j->free) {
            if (spline_at(x, j->spl, t, v, msg)) return 1;
            q[j->qadr] = v[0], qd[j->rate] = v[1], qdd[j->rate] = v[2];
            continue;
        }
        for (int c = 0; c < 3; c++) {
            if (spline_at(x, j->spl + c, t, v, msg)) return 1;
            q[j->qadr + c] = v[0], qd[j->rate + c] = v[1], qdd[j->rate + c] = v[2];
        }
        double s[4], sd[4], sdd[4], nn = 0.0;
        for (int c = 0; c < 4; c++) {
            if (spline_at(x, j->spl + 3 + c, t, v, msg)) return 1;
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

/* the chunk whose first row is x->r0's block of rows [first, end): each row's state from the
 * splines and its extras (contacts' flags, loads), on the team's threads; the block's first
 * failing row and its message in x->blk[k] */
static void sample_block(void *ctx, int first, int end, int k)
{
    run *x = ctx;
    block_state *b = &x->blk[k];
    const table *t = &x->in.t;
    for (int r = first; r < end; r++) {
        const int g = x->r0 + r;
        if (fill_sample(x, r, x->ts[g], b->msg) || row_extras(x, r, table_row(t, g), t->loc[g], b->msg)) {
            b->failed = r;
            return;
        }
    }
}

int run_samples(run *x)
{
    double start = 0.0, last = 0.0;
    const table *t = &x->in.t;
    if (write_header(x, t->nrow)) return 1;
    for (int r0 = 0; r0 < t->nrow; r0 += x->K) {
        const int n = t->nrow - r0 < x->K ? t->nrow - r0 : x->K;
        const double t0 = run_clock();
        x->r0 = r0;
        for (int k = 0; k < x->tm.nblock; k++) x->blk[k].failed = -1;
        parallel_blocks(&x->tm, n, sample_block, x);
        for (int k = 0; k < x->tm.nblock; k++) /* the blocks in order: the first failing row's message */
            if (x->blk[k].failed >= 0) return cmd_fail("%s", x->blk[k].msg);
        vt_batch_io io = chunk_io(x, n);
        const vt_status st = vt_batch_inverse_dynamics_motion(x->batch, &io);
        x->t_solve += run_clock() - t0;
        if (st) {
            for (int r = 0; r < n; r++)
                if (x->status[r] != VT_OK) return state_failure(x, r, t->loc[r0 + r]);
            return cmd_fail("%s: %s (%s)", x->states, vt_batch_message(x->batch), vt_status_string(st));
        }
        x->incells = table_row(t, r0);
        if (write_chunk(x, n, &start, &last)) return 1;
    }
    progress(x, 1, &start, &last);
    return 0;
}
