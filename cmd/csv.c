/* The command's files: a CSV table of numbers read whole under its header, and the output
 * written beside its name and renamed when complete, so a failed run leaves no partial file
 * under that name. */
#define _POSIX_C_SOURCE 200809L
#include "csv.h"

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "message.h"

void table_free(table *t)
{
    for (int c = 0; c < t->ncol; c++) free(t->name[c]);
    free(t->name);
    free(t->order);
    free(t->used);
    free(t->cell);
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

/* the header row s (line `line` of path) as the table's names: each named, none twice, indexed
 * by name (sorted: a lookup in log ncol, the whole header in ncol log ncol); 0 or 1 */
static int read_header(table *t, char *s, const char *path, int line)
{
    int cap = 0;
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
    t->order = malloc((size_t)t->ncol * sizeof *t->order);
    t->used = calloc((size_t)t->ncol, 1);
    if (!t->order || !t->used) return cmd_fail("out of memory");
    for (int c = 0; c < t->ncol; c++) t->order[c] = (table_key){t->name[c], c};
    qsort(t->order, (size_t)t->ncol, sizeof *t->order, by_name);
    for (int k = 1; k < t->ncol; k++) {
        const table_key *a = &t->order[k - 1], *b = &t->order[k];
        if (strcmp(a->name, b->name) == 0)
            return cmd_fail("%s:%d: column '%s' twice (columns %d and %d)", path, line, b->name,
                            (a->col < b->col ? a->col : b->col) + 1, (a->col < b->col ? b->col : a->col) + 1);
    }
    return 0;
}

/* the data row s (line `line` of path) appended to the table: one finite number per column,
 * the cells grown by doubling (*cap_rows rows allocated); 0 or 1 */
static int read_row(table *t, char *s, const char *path, int line, int *cap_rows)
{
    if (t->nrow == *cap_rows) {
        *cap_rows = *cap_rows ? 2 * *cap_rows : 256;
        double *nc = realloc(t->cell, (size_t)*cap_rows * (size_t)t->ncol * sizeof *nc);
        if (!nc) return cmd_fail("out of memory");
        t->cell = nc;
    }
    double *out = t->cell + (size_t)t->nrow * (size_t)t->ncol;
    int c = 0;
    for (char *p = s;; c++) {
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        if (c >= t->ncol) return cmd_fail("%s:%d: more cells than the %d columns of the header", path, line, t->ncol);
        char *cell = trim(p), *end = NULL;
        const size_t len = strlen(cell);
        if (len >= 2 && cell[0] == '"' && cell[len - 1] == '"') { /* a quoted number */
            cell[len - 1] = '\0';
            cell++;
        }
        errno = 0;
        out[c] = strtod(cell, &end);
        if (!*cell || *end || (errno == ERANGE && fabs(out[c]) == HUGE_VAL) || !isfinite(out[c]))
            return cmd_fail("%s:%d: column '%s': '%s' is not a finite number", path, line, t->name[c], cell);
        if (!comma) break;
        p = comma + 1;
    }
    if (c + 1 != t->ncol) return cmd_fail("%s:%d: %d cells for the %d columns of the header", path, line, c + 1, t->ncol);
    t->nrow++;
    return 0;
}

/* the next line of f into *text (grown as needed, *cap bytes), its line end kept: 1, 0 at the
 * end of the file, -1 when it is longer than CSV_MAX_LINE (read no further than
 * CSV_MAX_LINE + 2 bytes), -2 out of memory */
static int next_line(FILE *f, char **text, size_t *cap)
{
    size_t n = 0;
    for (int c = 0; c != '\n';) {
        if (n + 2 > *cap) {
            const size_t nc = *cap ? 2 * *cap : 4096;
            char *p = realloc(*text, nc);
            if (!p) return -2;
            *text = p;
            *cap = nc;
        }
        if ((c = getc(f)) == EOF) break;
        (*text)[n++] = (char)c;
        if (n > (size_t)CSV_MAX_LINE + 1 && c != '\n') return -1; /* more than the bound and "\r" */
    }
    (*text)[n] = '\0';
    const size_t body = n - (n > 0 && (*text)[n - 1] == '\n') - (n > 1 && (*text)[n - 1] == '\n' && (*text)[n - 2] == '\r');
    if (body > (size_t)CSV_MAX_LINE) return -1;
    return n > 0;
}

/* the lines of f: the first non-blank one the header, the others data rows; 0 or 1 */
static int read_lines(table *t, FILE *f, const char *path)
{
    char *text = NULL;
    size_t cap = 0;
    int line = 0, cap_rows = 0, status = 0, got;
    while (!status && (got = next_line(f, &text, &cap)) != 0) {
        line++;
        if (got == -2) {
            status = cmd_fail("out of memory");
            break;
        }
        if (got == -1) {
            status = cmd_fail("%s:%d: a line longer than %d bytes (a CSV line's limit)", path, line, CSV_MAX_LINE);
            break;
        }
        char *s = trim(text);
        if (line == 1 && (unsigned char)s[0] == 0xEF && (unsigned char)s[1] == 0xBB && (unsigned char)s[2] == 0xBF)
            s = trim(s + 3); /* a UTF-8 byte-order mark */
        if (!*s) continue;   /* blank lines */
        if (!t->ncol) t->header_line = line;
        status = t->ncol ? read_row(t, s, path, line, &cap_rows) : read_header(t, s, path, line);
    }
    free(text);
    if (status) return status;
    if (!t->ncol) return cmd_fail("%s: no header row", path);
    if (!t->nrow) return cmd_fail("%s: no data rows under the header", path);
    return 0;
}

int table_read(table *t, const char *path)
{
    memset(t, 0, sizeof *t);
    /* numbers with a '.' whatever LC_NUMERIC: this thread in the C locale while reading */
    locale_t cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!cloc) return cmd_fail("out of memory (the C locale)");
    const locale_t oldloc = uselocale(cloc);
    int status;
    FILE *f = fopen(path, "r");
    if (f) {
        status = read_lines(t, f, path);
        fclose(f);
    } else {
        status = cmd_fail("%s: %s", path, strerror(errno));
    }
    uselocale(oldloc);
    freelocale(cloc);
    if (status) table_free(t);
    return status;
}

int table_column(const table *t, const char *name)
{
    int lo = 0, hi = t->ncol - 1;
    while (lo <= hi) {
        const int mid = lo + (hi - lo) / 2, c = t->order[mid].col, cmp = strcmp(name, t->order[mid].name);
        if (cmp == 0) {
            t->used[c] = 1;
            return c;
        }
        if (cmp < 0) hi = mid - 1;
        else lo = mid + 1;
    }
    return -1;
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
