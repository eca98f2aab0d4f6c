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

#include "message.h"

void table_free(table *t)
{
    for (int c = 0; c < t->ncol; c++) free(t->name[c]);
    free(t->name);
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

/* the header row s (line `line` of path) as the table's names: each named, none twice; 0 or 1 */
static int read_header(table *t, char *s, const char *path, int line)
{
    for (char *p = s;;) {
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        char **nn = realloc(t->name, (size_t)(t->ncol + 1) * sizeof *nn);
        if (!nn) return cmd_fail("out of memory");
        t->name = nn;
        t->name[t->ncol] = strdup(trim(p));
        if (!t->name[t->ncol]) return cmd_fail("out of memory");
        t->ncol++;
        const char *nm = t->name[t->ncol - 1];
        if (!nm[0]) return cmd_fail("%s:%d: column %d has no name", path, line, t->ncol);
        for (int c = 0; c + 1 < t->ncol; c++)
            if (strcmp(t->name[c], nm) == 0) return cmd_fail("%s:%d: column '%s' twice", path, line, nm);
        if (!comma) return 0;
        p = comma + 1;
    }
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
    for (int c = 0; c < t->ncol; c++)
        if (strcmp(t->name[c], name) == 0) return c;
    return -1;
}

int output_open(output *o, const char *path)
{
    o->f = stdout;
    o->path = path;
    o->tmp = NULL;
    if (!path) return 0;
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
