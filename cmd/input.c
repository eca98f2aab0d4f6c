/* The command's input: a CSV or .npy table read in chunks of rows. A CSV file is read through a
 * window of 2 CSV_MAX_LINE bytes in which the lines are found (memchr), so that a line is bounded
 * and the file is never held whole; a chunk keeps its rows' text until they are parsed, on
 * threads. A .npy file's rows are its records, 8 bytes a field. */
#define _POSIX_C_SOURCE 200809L
#include "input.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "message.h"
#include "npy.h"

file_format format_of(const char *path)
{
    const size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".npy") == 0 ? FMT_NPY : FMT_CSV;
}

void chunk_free(chunk *c)
{
    free(c->loc);
    free(c->off);
    free(c->text);
    free(c->raw);
    memset(c, 0, sizeof *c);
}

void input_close(input *in)
{
    if (in->f) fclose(in->f);
    free(in->buf);
    table_free(&in->t);
    memset(in, 0, sizeof *in);
}

/* the next line of the CSV file: *s its first byte, *n its bytes with its line end (not
 * NUL-ended; valid until the next call): 1, 0 at the end, -1 longer than CSV_MAX_LINE (the file
 * read no further than the window), -2 a read error */
static int next_line(input *in, char **s, size_t *n)
{
    for (;;) {
        char *b = in->buf + in->beg, *nl = memchr(b, '\n', in->end - in->beg);
        if (nl || (in->eof && in->end > in->beg)) {
            *s = b;
            *n = nl ? (size_t)(nl - b) + 1 : in->end - in->beg;
            in->beg += *n;
            in->pos += (long long)*n;
            in->line++;
            const size_t body = *n - (nl != NULL) - (nl && nl > b && nl[-1] == '\r');
            return body > (size_t)CSV_MAX_LINE ? -1 : 1;
        }
        if (in->eof) return 0;
        if (in->end - in->beg > (size_t)CSV_MAX_LINE + 1) { /* more than the bound and "\r", no '\n' */
            in->line++;
            return -1;
        }
        memmove(in->buf, b, in->end - in->beg);
        in->end -= in->beg;
        in->beg = 0;
        const size_t got = fread(in->buf + in->end, 1, in->cap - in->end, in->f);
        in->end += got;
        if (got == 0) {
            if (ferror(in->f)) return -2;
            in->eof = 1;
        }
    }
}

/* s[0, *n) without the spaces, tabs and line ends around it */
static char *trim_span(char *s, size_t *n)
{
    while (*n > 0 && (s[*n - 1] == ' ' || s[*n - 1] == '\t' || s[*n - 1] == '\r' || s[*n - 1] == '\n')) (*n)--;
    while (*n > 0 && (*s == ' ' || *s == '\t')) {
        s++;
        (*n)--;
    }
    return s;
}

/* the next line that is not blank, trimmed (a byte-order mark skipped on line 1): 1, 0 at the
 * end, or 1 with the message printed as -1 */
static int next_text(input *in, char **s, size_t *n)
{
    for (;;) {
        const int got = next_line(in, s, n);
        if (got == -1) {
            cmd_fail("%s:%d: a line longer than %d bytes (a CSV line's limit)", in->path, in->line, CSV_MAX_LINE);
            return -1;
        }
        if (got == -2) {
            cmd_fail("%s: %s", in->path, strerror(errno));
            return -1;
        }
        if (got == 0) return 0;
        *s = trim_span(*s, n);
        if (in->line == 1 && *n >= 3 && (unsigned char)(*s)[0] == 0xEF && (unsigned char)(*s)[1] == 0xBB &&
            (unsigned char)(*s)[2] == 0xBF) { /* a UTF-8 byte-order mark */
            *s += 3;
            *n -= 3;
            *s = trim_span(*s, n);
        }
        if (*n > 0) return 1;
    }
}

int input_open(input *in, const char *path)
{
    memset(in, 0, sizeof *in);
    in->path = path;
    in->fmt = format_of(path);
    in->size = -1;
    in->nrow = -1;
    in->f = fopen(path, "rb");
    if (!in->f) return cmd_fail("%s: %s", path, strerror(errno));
    struct stat s;
    if (fstat(fileno(in->f), &s) == 0 && S_ISREG(s.st_mode)) in->size = (long long)s.st_size;
    if (in->fmt == FMT_NPY) {
        long long off;
        if (npy_read_header(in->f, path, &in->t.name, &in->t.ncol, &in->nrow, &off)) return 1;
        in->pos = off;
        return table_index(&in->t, path, 0);
    }
    in->cap = 2 * (size_t)CSV_MAX_LINE;
    in->buf = malloc(in->cap);
    if (!in->buf) return cmd_fail("out of memory");
    char *line;
    size_t n;
    const int got = next_text(in, &line, &n);
    if (got < 0) return 1;
    if (got == 0) return cmd_fail("%s: no header row", path);
    char *h = malloc(n + 1);
    if (!h) return cmd_fail("out of memory");
    memcpy(h, line, n);
    h[n] = '\0';
    const int st = csv_read_header(&in->t, h, path, in->line);
    free(h);
    return st;
}

/* room in c for one more row, and for `bytes` more bytes of text; 0 or 1 (out of memory) */
static int chunk_room(chunk *c, size_t bytes)
{
    if (c->n == c->cap) {
        const int cap = c->cap ? 2 * c->cap : 256;
        long long *loc = realloc(c->loc, (size_t)cap * sizeof *loc);
        if (loc) c->loc = loc;
        size_t *off = realloc(c->off, (size_t)cap * sizeof *off);
        if (off) c->off = off;
        if (!loc || !off) return 1;
        c->cap = cap;
    }
    if (c->len + bytes > c->tcap) {
        size_t cap = c->tcap ? c->tcap : 1 << 16;
        while (cap < c->len + bytes) cap *= 2;
        char *t = realloc(c->text, cap);
        if (!t) return 1;
        c->text = t;
        c->tcap = cap;
    }
    return 0;
}

int input_read(input *in, chunk *c, int maxrows, size_t maxbytes)
{
    c->n = 0;
    c->len = 0;
    if (in->fmt == FMT_NPY) {
        const size_t rowbytes = 8 * (size_t)in->t.ncol;
        long long n = in->nrow - in->next, fit = (long long)(maxbytes / rowbytes);
        if (n > maxrows) n = maxrows;
        if (n > fit) n = fit > 0 ? fit : 1;
        if (n <= 0) return 0;
        if ((size_t)n * rowbytes > c->rcap) {
            unsigned char *r = realloc(c->raw, (size_t)n * rowbytes);
            if (!r) return cmd_fail("out of memory");
            c->raw = r;
            c->rcap = (size_t)n * rowbytes;
        }
        if (c->cap < n) {
            long long *loc = realloc(c->loc, (size_t)n * sizeof *loc);
            if (!loc) return cmd_fail("out of memory");
            c->loc = loc;
            c->cap = (int)n;
        }
        const size_t got = fread(c->raw, rowbytes, (size_t)n, in->f);
        if (got != (size_t)n)
            return cmd_fail("%s: %s at row %lld of the %lld its header announces", in->path,
                            ferror(in->f) ? strerror(errno) : "truncated", in->next + (long long)got, in->nrow);
        for (int r = 0; r < (int)n; r++) c->loc[r] = in->next + r;
        c->n = (int)n;
        in->next += n;
        in->pos += n * (long long)rowbytes;
        return 0;
    }
    while (c->n < maxrows && (c->n == 0 || c->len < maxbytes)) {
        char *s;
        size_t n;
        const int got = next_text(in, &s, &n);
        if (got < 0) return 1;
        if (got == 0) break;
        if (chunk_room(c, n + 1)) return cmd_fail("out of memory");
        c->off[c->n] = c->len;
        memcpy(c->text + c->len, s, n);
        c->text[c->len + n] = '\0';
        c->len += n + 1;
        c->loc[c->n++] = in->line;
    }
    in->next += c->n;
    return 0;
}

const char *input_where(const input *in, long long loc, char *buf)
{
    if (in->fmt == FMT_NPY) snprintf(buf, ROW_WHERE, "%.300s[%lld]", in->path, loc);
    else snprintf(buf, ROW_WHERE, "%.300s:%lld", in->path, loc);
    return buf;
}

/* a little-endian float64 at p */
static inline double le_double(const unsigned char *p)
{
    double v;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    memcpy(&v, p, 8);
#else
    uint64_t u = 0;
    for (int k = 7; k >= 0; k--) u = u << 8 | p[k];
    memcpy(&v, &u, 8);
#endif
    return v;
}

int input_parse(const input *in, chunk *c, int r, double *out, char *msg)
{
    if (in->fmt == FMT_CSV) return csv_parse_row(&in->t, c->text + c->off[r], out, in->path, c->loc[r], msg);
    const unsigned char *p = c->raw + (size_t)r * 8 * (size_t)in->t.ncol;
    for (int k = 0; k < in->t.ncol; k++) {
        out[k] = le_double(p + 8 * (size_t)k);
        if (!isfinite(out[k])) {
            char where[ROW_WHERE];
            snprintf(msg, ROW_MESSAGE, "%s: column '%.100s': %g is not a finite number",
                     input_where(in, c->loc[r], where), in->t.name[k], out[k]);
            return 1;
        }
    }
    return 0;
}

int input_read_all(input *in)
{
    table *t = &in->t;
    chunk c = {0};
    int cap = 0, status = 0;
    char msg[ROW_MESSAGE];
    while (!status && !(status = input_read(in, &c, 4096, 16u << 20)) && c.n > 0) {
        if (t->nrow + c.n > cap) {
            while (cap < t->nrow + c.n) cap = cap ? 2 * cap : 4096;
            double *cell = realloc(t->cell, (size_t)cap * (size_t)t->ncol * sizeof *cell);
            if (cell) t->cell = cell;
            long long *loc = realloc(t->loc, (size_t)cap * sizeof *loc);
            if (loc) t->loc = loc;
            if (!cell || !loc) {
                status = cmd_fail("out of memory");
                break;
            }
        }
        for (int r = 0; r < c.n && !status; r++) {
            if (input_parse(in, &c, r, t->cell + (size_t)(t->nrow + r) * (size_t)t->ncol, msg))
                status = cmd_fail("%s", msg);
            t->loc[t->nrow + r] = c.loc[r];
        }
        if (!status) t->nrow += c.n;
    }
    chunk_free(&c);
    return status;
}
