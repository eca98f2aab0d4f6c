/* The command's tables: the columns' names indexed, a CSV header and rows parsed, and the output
 * written beside its name and renamed when complete, so a failed run leaves no partial file
 * under that name. */
#define _GNU_SOURCE /* fallocate */
#include "csv.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "message.h"
#include "number_text.h"

void table_free(table *t)
{
    for (int c = 0; c < t->ncol; c++) free(t->name[c]);
    free(t->name);
    free(t->order);
    free(t->used);
    free(t->cell);
    free(t->loc);
    memset(t, 0, sizeof *t);
}

/* s without the spaces, tabs and line ends around it (cut in place) */
static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) *--e = '\0';
    return s;
}

/* the next cell of a header row at *p, cut in place and unquoted: a cell in double quotes may
 * hold commas, and "" stands for one quote (RFC 4180); *p moves past the cell's comma, or to NULL
 * after the last cell. NULL, with *p untouched, for a quote that is not closed */
static char *next_name(char **p)
{
    char *s = *p;
    while (*s == ' ' || *s == '\t') s++;
    if (*s != '"') {
        char *comma = strchr(s, ',');
        if (comma) *comma = '\0';
        *p = comma ? comma + 1 : NULL;
        return trim(s);
    }
    char *w = s, *r = s + 1; /* unquoted in place: w writes, r reads */
    for (;; r++) {
        if (!*r) return NULL;
        if (*r == '"') {
            if (r[1] != '"') break;
            r++;
        }
        *w++ = *r;
    }
    *w = '\0';
    r++; /* past the closing quote: spaces, then a comma or the end */
    while (*r == ' ' || *r == '\t' || *r == '\r' || *r == '\n') r++;
    if (*r && *r != ',') return NULL;
    *p = *r == ',' ? r + 1 : NULL;
    return s;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(((const table_key *)a)->name, ((const table_key *)b)->name);
}

void keys_sort(table_key *keys, int n)
{
    qsort(keys, (size_t)n, sizeof *keys, by_name);
}

int keys_find(const table_key *keys, int n, const char *name)
{
    int lo = 0, hi = n - 1;
    while (lo <= hi) {
        const int mid = lo + (hi - lo) / 2, cmp = strcmp(name, keys[mid].name);
        if (cmp == 0) return mid;
        if (cmp < 0) hi = mid - 1;
        else lo = mid + 1;
    }
    return -1;
}

/* sorted by name: a lookup in log ncol, the whole header in ncol log ncol */
int table_index(table *t, const char *path, int line)
{
    t->order = malloc((size_t)t->ncol * sizeof *t->order);
    t->used = calloc((size_t)t->ncol, 1);
    if (!t->order || !t->used) return cmd_fail("out of memory");
    for (int c = 0; c < t->ncol; c++) t->order[c] = (table_key){t->name[c], c};
    keys_sort(t->order, t->ncol);
    for (int k = 1; k < t->ncol; k++) {
        const table_key *a = &t->order[k - 1], *b = &t->order[k];
        if (strcmp(a->name, b->name) != 0) continue;
        const int lo = (a->col < b->col ? a->col : b->col) + 1, hi = (a->col < b->col ? b->col : a->col) + 1;
        if (!line) return cmd_fail("%s: field '%s' twice (fields %d and %d)", path, b->name, lo, hi);
        return cmd_fail("%s:%d: column '%s' twice (columns %d and %d)", path, line, b->name, lo, hi);
    }
    return 0;
}

int csv_read_header(table *t, char *s, const char *path, int line)
{
    int cap = 0;
    t->header_line = line;
    for (char *p = s; p;) {
        char *nm = next_name(&p);
        if (!nm) return cmd_fail("%s:%d: column %d: a quote not closed", path, line, t->ncol + 1);
        if (!nm[0]) return cmd_fail("%s:%d: column %d has no name", path, line, t->ncol + 1);
        if (t->ncol == cap) {
            cap = cap ? 2 * cap : 64;
            char **nn = realloc(t->name, (size_t)cap * sizeof *nn);
            if (!nn) return cmd_fail("out of memory");
            t->name = nn;
        }
        if (!(t->name[t->ncol] = strdup(nm))) return cmd_fail("out of memory");
        t->ncol++;
    }
    return table_index(t, path, line);
}

int csv_parse_row(const table *t, char *s, double *out, const char *path, long long line, char *msg)
{
    int c = 0;
    for (char *p = s;; c++) {
        char *comma = strchr(p, ',');
        if (c >= t->ncol) {
            snprintf(msg, ROW_MESSAGE, "%s:%lld: more cells than the %d columns of the header", path, line, t->ncol);
            return 1;
        }
        char *cell = p, *e = comma ? comma : p + strlen(p); /* the cell without the blanks around it */
        while (*cell == ' ' || *cell == '\t') cell++;
        while (e > cell && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) e--;
        if (e - cell >= 2 && cell[0] == '"' && e[-1] == '"') { /* a quoted number */
            cell++;
            e--;
        }
        if (!number_parse(cell, (size_t)(e - cell), &out[c]) || !isfinite(out[c])) {
            /* what <charconv> does not read (a '+', a hexadecimal number) strtod may; its
             * verdict stands, and a cell neither reads, or that overflows, is refused */
            *e = '\0';
            char *end = NULL;
            errno = 0;
            out[c] = strtod(cell, &end);
            if (!*cell || *end || (errno == ERANGE && fabs(out[c]) == HUGE_VAL) || !isfinite(out[c])) {
                snprintf(msg, ROW_MESSAGE, "%s:%lld: column '%.100s': '%.60s%s' is not a finite number", path,
                         line, t->name[c], cell, strlen(cell) > 60 ? "..." : "");
                return 1;
            }
        }
        if (!comma) break;
        p = comma + 1;
    }
    if (c + 1 != t->ncol) {
        snprintf(msg, ROW_MESSAGE, "%s:%lld: %d cells for the %d columns of the header", path, line, c + 1, t->ncol);
        return 1;
    }
    return 0;
}

int table_column(const table *t, const char *name)
{
    const int k = keys_find(t->order, t->ncol, name);
    if (k < 0) return -1;
    t->used[t->order[k].col] = 1;
    return t->order[k].col;
}

int output_open(output *o, const char *path, const char *const *inputs, int ninputs)
{
    o->f = stdout;
    o->path = path;
    o->tmp = NULL;
    if (!path) return 0;
    /* a new path, or a regular file that is none of the inputs (under any of its names): a device,
     * a pipe or a directory would be replaced by a regular file, an input by the results */
    struct stat so, si;
    if (stat(path, &so) == 0) {
        if (!S_ISREG(so.st_mode))
            return cmd_fail("%s: not a regular file: -o writes a new file or replaces a regular one (without -o the "
                            "results go to standard output)",
                            path);
        for (int k = 0; k < ninputs; k++)
            if (stat(inputs[k], &si) == 0 && si.st_dev == so.st_dev && si.st_ino == so.st_ino)
                return cmd_fail("%s: is the input %s: -o would replace it with the results", path, inputs[k]);
    } else if (errno != ENOENT) {
        return cmd_fail("%s: %s", path, strerror(errno));
    }
    char *tmp = malloc(strlen(path) + 8);
    if (!tmp) return cmd_fail("out of memory");
    sprintf(tmp, "%s.part", path);
    o->f = fopen(tmp, "wx"); /* ours alone: an existing one is not overwritten, nor removed */
    if (!o->f) {
        const int e = errno;
        cmd_fail("%s: %s%s", tmp, strerror(e), e == EEXIST ? " (left by another run? remove it)" : "");
        free(tmp);
        return 1;
    }
    o->tmp = tmp;
    return 0;
}

int output_reserve(output *o, unsigned long long bytes)
{
#if defined(__linux__)
    /* Linux's fallocate, not posix_fallocate: where the file system cannot reserve, glibc's
     * posix_fallocate would write the zeros itself, as many bytes again as the results */
    const off_t len = (off_t)bytes;
    if (!o->tmp || bytes == 0 || len <= 0 || (unsigned long long)len != bytes || fflush(o->f)) return 0;
    if (fallocate(fileno(o->f), 0, 0, len) == 0) return 0;
    if (errno == ENOSPC || errno == EFBIG)
        return cmd_fail("%s: no room for the results' %llu bytes: %s", o->tmp, bytes, strerror(errno));
#else
    (void)o, (void)bytes;
#endif
    return 0;
}

int output_close(output *o, int complete)
{
    int status = !complete;
    if (!o->path) {
        if (complete && (fflush(stdout) || ferror(stdout))) status = cmd_fail("stdout: %s", strerror(errno));
        return status;
    }
    const int bad = ferror(o->f);
    const int closed = fclose(o->f);
    o->f = NULL;
    if (!status && (bad || closed)) status = cmd_fail("%s: writing failed", o->tmp);
    if (!status && rename(o->tmp, o->path)) status = cmd_fail("%s: %s", o->path, strerror(errno));
    if (status) remove(o->tmp);
    free(o->tmp);
    o->tmp = NULL;
    return status;
}
