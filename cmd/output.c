/* The command's `inverse`, its output: the columns' names chosen by --columns, each row's values
 * gathered from the batch's arrays (a floating root's efforts also turned into its link's axes),
 * formatted as CSV or laid out as .npy rows on the threads, written in order; the .npy header and
 * its row count; the progress line. */
#define _POSIX_C_SOURCE 200809L
#include "output.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "message.h"
#include "npy.h"
#include "number_text.h"
#include "parallel.h"

int no_rows(const run *x)
{
    if (x->in.fmt == FMT_NPY) return cmd_fail("%s: no data rows (shape (0,))", x->states);
    return cmd_fail("%s: no data rows under the header", x->states);
}

/* name k of the output, "J_suffix", into x->names; 0 or 1 */
static int add_name(run *x, int *k, const char *joint, const char *suffix)
{
    const size_t n = strlen(joint) + strlen(suffix) + 1;
    if (!(x->names[*k] = malloc(n))) return 1;
    snprintf(x->names[*k], n, "%s%s", joint, suffix);
    (*k)++;
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* every output column's name once (a contact named as a joint would give two `J_fx`): sorted
 * copies compared in turn; 0, or 1 naming the column */
static int distinct_names(const run *x)
{
    char **s = malloc((size_t)x->nout * sizeof *s);
    if (!s) return cmd_fail("out of memory");
    memcpy(s, x->names, (size_t)x->nout * sizeof *s);
    qsort(s, (size_t)x->nout, sizeof *s, by_name);
    int bad = 0;
    for (int k = 1; k < x->nout && !bad; k++)
        if (strcmp(s[k - 1], s[k]) == 0)
            bad = cmd_fail("two output columns would be named '%s'%s", s[k],
                           x->ncontact ? " (a contact named as a joint or another contact's column: --contacts's "
                                         "column name gives it another)"
                                       : "");
    free(s);
    return bad;
}

int output_columns(run *x)
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
    n += 3 * x->ncontact;
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
    static const char *const force[3] = {"_fx", "_fy", "_fz"};
    for (int i = 0; i < x->ncontact; i++) /* the contacts' forces last */
        for (int c = 0; c < 3; c++) bad |= add_name(x, &k, x->cname[i], force[c]);
    return bad ? cmd_fail("out of memory") : distinct_names(x);
}

/* w (3 forces, 3 moments) turned by the transpose of the column-major rotation R into out */
static void turn_back(double out[6], const double R[9], const double w[6])
{
    for (int h = 0; h < 6; h += 3)
        for (int c = 0; c < 3; c++) out[h + c] = R[3 * c] * w[h] + R[3 * c + 1] * w[h + 1] + R[3 * c + 2] * w[h + 2];
}

/* chunk row r's output values into v: t when given, then per joint its selected groups, then
 * the contacts' forces */
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
    if (x->ncontact) memcpy(v + o, x->cforce + r * 3 * (size_t)x->ncontact, 3 * (size_t)x->ncontact * sizeof *v);
}

/* a block of rows formatted as CSV (the run's precision) into its buffer */
static void format_block(void *ctx, int first, int end, int k)
{
    run *x = ctx;
    block_state *b = &x->blk[k];
    /* the last number's room beyond (number_print_room) */
    const size_t need = (size_t)(end - first) * ((NUMBER_TEXT_MAX + 1) * (size_t)x->nout + 1) + NUMBER_TEXT_ROOM;
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
            p += number_print_room(p, b->v[c], prec);
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

int write_header(run *x, long long nrow)
{
    FILE *f = x->out.f;
    if (x->ofmt == FMT_CSV) {
        for (int k = 0; k < x->nout; k++) {
            fputs(x->names[k], f);
            fputc(k + 1 < x->nout ? ',' : '\n', f);
        }
        return 0;
    }
    /* the rows' values go to the file as they are, not through a buffer (its first write) */
    setvbuf(f, NULL, _IONBF, 0);
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
    /* the rows known (a .npy input): the file's final size reserved (a size past the largest
     * number is not asked for: the writes then fail and say so) */
    const unsigned long long row = 8u * (unsigned long long)x->nout;
    if (!min && (unsigned long long)nrow <= (ULLONG_MAX - len) / row &&
        output_reserve(&x->out, len + (unsigned long long)nrow * row))
        return 1;
    return 0;
}

int format_rows(run *x, int n)
{
    const double t0 = run_clock();
    if (x->ofmt == FMT_NPY) {
        parallel_blocks(&x->tm, n, encode_block, x);
    } else {
        for (int k = 0; k < x->tm.nblock; k++) x->blk[k].failed = -1;
        parallel_blocks(&x->tm, n, format_block, x);
        for (int k = 0; k < x->tm.nblock; k++)
            if (x->blk[k].failed >= 0) return cmd_fail("%s", x->blk[k].msg);
    }
    x->t_write += run_clock() - t0;
    return 0;
}

void put_rows(run *x, int set, int n)
{
    if (x->ofmt == FMT_NPY) {
        fwrite(x->vals[set], 8 * (size_t)x->nout, (size_t)n, x->out.f);
    } else {
        for (int k = 0, B = team_blocks(&x->tm, n); k < B; k++)
            fwrite(x->blk[k].text[set], 1, x->blk[k].len[set], x->out.f);
    }
    x->written += n;
}

int finish_output(run *x)
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

void progress(const run *x, int done, double *start, double *last)
{
    const input *in = &x->in;
    const long long rows = in->fmt == FMT_NPY ? in->nrow : x->form == FORM_SAMPLES ? in->t.nrow : -1;
    const long long row = x->written;
    if (!isatty(2) || (rows >= 0 ? rows : row) < 2000) return;
    const double t = run_clock();
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

int output_format(run *x, const char *outpath)
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

int write_chunk(run *x, int n, double *start, double *last)
{
    x->oset = 0;
    if (format_rows(x, n)) return 1;
    const double t1 = run_clock();
    put_rows(x, 0, n);
    x->t_write += run_clock() - t1;
    progress(x, 0, start, last);
    return 0;
}
