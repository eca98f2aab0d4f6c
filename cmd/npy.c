/* The command's NumPy files: the .npy header (NEP 1 and numpy.lib.format) of a structured array
 * whose fields are the table's columns.
 *
 * A .npy file: the magic "\x93NUMPY", the format's major and minor version (1.0, 2.0 or 3.0), the
 * header's length (little-endian: 2 bytes for 1.0, 4 for 2.0 and 3.0), the header — a Python dict
 * literal, latin-1 (1.0, 2.0) or UTF-8 (3.0), padded with spaces and ended by '\n' so that the
 * data starts at a multiple of 64 bytes — then the data. This command reads and writes one kind:
 *
 *   {'descr': [('t', '<f8'), ('joint1_effort', '<f8'), ...], 'fortran_order': False, 'shape': (N,), }
 *
 * N records of the fields' float64 values, little-endian, in the fields' order (C order). The
 * reader parses the dict's literal syntax (strings with their escapes, integers, True/False,
 * tuples, lists) without evaluating anything, and refuses every other layout naming what it
 * found. */
#define _POSIX_C_SOURCE 200809L
#include "npy.h"

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "message.h"

static const char magic[6] = {'\x93', 'N', 'U', 'M', 'P', 'Y'};

/* ---- reading ---------------------------------------------------------------------------- */

/* the header's dict as parsed: what the checks after it need */
typedef struct {
    const char *p, *start, *end; /* the text, being read */
    int latin1;                  /* formats 1.0 and 2.0: a byte is a latin-1 character */
    char **names;                /* the fields' names, UTF-8 (nnames) */
    int nnames, cap;
    char *plain;                 /* 'descr' a string: a plain array's dtype */
    char *bad_name, *bad_type;   /* the first field that is not '<f8' (bad_type NULL: nested) */
    const char *bad_what;        /* what is wrong with it, when not its type */
    int has_descr, has_fortran, has_shape, fortran;
    long long shape[8];
    int ndim;
} hdr;

static void hdr_free(hdr *h)
{
    for (int k = 0; k < h->nnames; k++) free(h->names[k]);
    free(h->names);
    free(h->plain);
    free(h->bad_name);
    free(h->bad_type);
}

static void skip_space(hdr *h)
{
    while (h->p < h->end && (*h->p == ' ' || *h->p == '\t' || *h->p == '\n' || *h->p == '\r')) h->p++;
}

/* the next character (after spaces) is c: consumed, 1; else 0 */
static int take(hdr *h, char c)
{
    skip_space(h);
    if (h->p < h->end && *h->p == c) {
        h->p++;
        return 1;
    }
    return 0;
}

/* code point cp as UTF-8 at o; the bytes written */
static int utf8(char *o, unsigned long cp)
{
    if (cp < 0x80) {
        o[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        o[0] = (char)(0xC0 | (cp >> 6));
        o[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        o[0] = (char)(0xE0 | (cp >> 12));
        o[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        o[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    o[0] = (char)(0xF0 | (cp >> 18));
    o[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    o[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
    o[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* n hex digits at s as a number into *v; 0, or -1 when one is not a hex digit */
static int hex(const char *s, int n, unsigned long *v)
{
    *v = 0;
    for (int k = 0; k < n; k++) {
        const char c = s[k];
        const int d = c >= '0' && c <= '9'   ? c - '0'
                      : c >= 'a' && c <= 'f' ? c - 'a' + 10
                      : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                             : -1;
        if (d < 0) return -1;
        *v = 16 * *v + (unsigned long)d;
    }
    return 0;
}

/* a Python string literal ('...' or "...", with the escapes repr writes) into a new UTF-8 string
 * *out; 0, or -1 (not a string, or malformed), -2 out of memory */
static int parse_string(hdr *h, char **out)
{
    skip_space(h);
    if (h->p >= h->end || (*h->p != '\'' && *h->p != '"')) return -1;
    const char q = *h->p++;
    char *o = malloc(4 * (size_t)(h->end - h->p) + 1), *w = o;
    if (!o) return -2;
    while (h->p < h->end && *h->p != q) {
        unsigned long cp = (unsigned char)*h->p++;
        if (cp == '\n') break; /* a literal does not span lines */
        if (cp == '\\') {
            if (h->p >= h->end) break;
            const char e = *h->p++;
            int n = 0;
            switch (e) {
            case '\\': case '\'': case '"': cp = (unsigned char)e; break;
            case 'n': cp = '\n'; break;
            case 't': cp = '\t'; break;
            case 'r': cp = '\r'; break;
            case '0': cp = 0; break;
            case 'x': n = 2; break;
            case 'u': n = 4; break;
            case 'U': n = 8; break;
            default: free(o); return -1;
            }
            if (n) {
                if (h->end - h->p < n || hex(h->p, n, &cp) || cp > 0x10FFFF) {
                    free(o);
                    return -1;
                }
                h->p += n;
            }
            if (cp == 0) { /* a NUL in a name: no C string holds it */
                free(o);
                return -1;
            }
            w += utf8(w, cp);
        } else if (cp >= 0x80 && h->latin1) {
            w += utf8(w, cp); /* a latin-1 character */
        } else {
            *w++ = (char)cp; /* ASCII, or a byte of UTF-8 (format 3.0) */
        }
    }
    if (h->p >= h->end || *h->p != q) {
        free(o);
        return -1;
    }
    h->p++;
    *w = '\0';
    *out = o;
    return 0;
}

/* a non-negative integer (Python 2's numpy wrote 10L) into *v; 0 or -1 */
static int parse_int(hdr *h, long long *v)
{
    skip_space(h);
    if (h->p >= h->end || *h->p < '0' || *h->p > '9') return -1;
    long long x = 0;
    while (h->p < h->end && *h->p >= '0' && *h->p <= '9') {
        const int d = *h->p++ - '0';
        if (x > (LLONG_MAX - d) / 10) return -1;
        x = 10 * x + d;
    }
    if (h->p < h->end && *h->p == 'L') h->p++;
    *v = x;
    return 0;
}

/* a tuple of integers (a shape) into h->shape; 0 or -1 */
static int parse_shape(hdr *h)
{
    if (!take(h, '(')) return -1;
    h->ndim = 0;
    while (!take(h, ')')) {
        long long v;
        if (h->ndim == 8 || parse_int(h, &v)) return -1;
        h->shape[h->ndim++] = v;
        if (!take(h, ',')) {
            if (!take(h, ')')) return -1;
            break;
        }
    }
    return 0;
}

/* skips one literal of any kind (a field's subarray shape, a nested dtype), depth-bounded; 0 or -1 */
static int skip_value(hdr *h, int depth)
{
    skip_space(h);
    if (h->p >= h->end || depth > 16) return -1;
    const char c = *h->p;
    if (c == '\'' || c == '"') {
        char *s;
        const int st = parse_string(h, &s);
        if (st) return -1;
        free(s);
        return 0;
    }
    if (c == '(' || c == '[') {
        const char close = c == '(' ? ')' : ']';
        h->p++;
        while (!take(h, close)) {
            if (skip_value(h, depth + 1)) return -1;
            if (!take(h, ',')) return take(h, close) ? 0 : -1;
        }
        return 0;
    }
    const char *s = h->p;
    while (h->p < h->end && ((*h->p >= '0' && *h->p <= '9') || (*h->p >= 'A' && *h->p <= 'Z') ||
                             (*h->p >= 'a' && *h->p <= 'z') || *h->p == '_' || *h->p == '-' || *h->p == '.'))
        h->p++;
    return h->p > s ? 0 : -1;
}

/* one field of 'descr': (name, typestr) or (name, typestr, shape); a field that is not a plain
 * '<f8' is kept as the first bad one; 0, -1 malformed, -2 out of memory */
static int parse_field(hdr *h)
{
    if (!take(h, '(')) return -1;
    char *name = NULL, *type = NULL;
    const char *what = NULL;
    skip_space(h);
    if (h->p < h->end && *h->p == '(') { /* (title, name): a field with a title */
        h->p++;
        char *title = NULL;
        if (parse_string(h, &title) || !take(h, ',') || parse_string(h, &name) || !take(h, ')')) {
            free(title);
            free(name);
            return -1;
        }
        free(title);
        what = "has a title";
    } else {
        const int st = parse_string(h, &name);
        if (st) return st;
    }
    if (!take(h, ',')) {
        free(name);
        return -1;
    }
    skip_space(h);
    if (h->p < h->end && *h->p == '[') { /* a nested structure */
        if (skip_value(h, 0)) {
            free(name);
            return -1;
        }
        if (!what) what = "is a nested structure";
    } else {
        const int st = parse_string(h, &type);
        if (st) {
            free(name);
            return st;
        }
    }
    if (take(h, ',')) { /* a subarray's shape */
        skip_space(h);
        if (!(h->p < h->end && *h->p == ')')) {
            if (skip_value(h, 0)) {
                free(name);
                free(type);
                return -1;
            }
            if (!what) what = "is a subarray";
        }
    }
    if (!take(h, ')')) {
        free(name);
        free(type);
        return -1;
    }
    if (!what && !name[0]) what = "has no name (padding?)";
    if (!what && type && strcmp(type, "<f8") != 0) what = "";
    if (what) {
        if (!h->bad_name) {
            h->bad_name = name;
            h->bad_type = type;
            h->bad_what = what;
            return 0;
        }
        free(name);
        free(type);
        return 0;
    }
    free(type);
    if (h->nnames == h->cap) {
        const int cap = h->cap ? 2 * h->cap : 64;
        char **nn = realloc(h->names, (size_t)cap * sizeof *nn);
        if (!nn) {
            free(name);
            return -2;
        }
        h->names = nn;
        h->cap = cap;
    }
    h->names[h->nnames++] = name;
    return 0;
}

/* the header's dict: its keys 'descr', 'fortran_order' and 'shape' (each once, no other);
 * 0, -1 malformed (h->p where), -2 out of memory, -3 an unknown or repeated key */
static int parse_dict(hdr *h, char **key_out)
{
    if (!take(h, '{')) return -1;
    while (!take(h, '}')) {
        char *key;
        int st = parse_string(h, &key);
        if (st) return st;
        if (!take(h, ':')) {
            free(key);
            return -1;
        }
        if (strcmp(key, "descr") == 0 && !h->has_descr) {
            h->has_descr = 1;
            skip_space(h);
            if (h->p < h->end && *h->p == '[') {
                h->p++;
                while (!take(h, ']')) {
                    if ((st = parse_field(h))) break;
                    if (!take(h, ',')) {
                        st = take(h, ']') ? 0 : -1;
                        break;
                    }
                }
            } else {
                st = parse_string(h, &h->plain);
            }
        } else if (strcmp(key, "fortran_order") == 0 && !h->has_fortran) {
            h->has_fortran = 1;
            skip_space(h);
            if (h->end - h->p >= 4 && memcmp(h->p, "True", 4) == 0) {
                h->fortran = 1;
                h->p += 4;
            } else if (h->end - h->p >= 5 && memcmp(h->p, "False", 5) == 0) {
                h->p += 5;
            } else {
                st = -1;
            }
        } else if (strcmp(key, "shape") == 0 && !h->has_shape) {
            h->has_shape = 1;
            st = parse_shape(h);
        } else {
            *key_out = key;
            return -3;
        }
        free(key);
        if (st) return st;
        if (!take(h, ',')) return take(h, '}') ? 0 : -1;
    }
    return 0;
}

/* the shape as Python writes it, "(3, 4)", into buf */
static const char *shape_text(char buf[256], const hdr *h)
{
    int n = snprintf(buf, 256, "(");
    for (int k = 0; k < h->ndim && n < 200; k++)
        n += snprintf(buf + n, 256 - (size_t)n, "%lld%s", h->shape[k],
                      h->ndim == 1 ? "," : k + 1 < h->ndim ? ", " : "");
    snprintf(buf + n, 256 - (size_t)n, ")");
    return buf;
}

/* the parsed header's checks: a list of '<f8' fields, C order, shape (N,); 0 or 1 */
static int check_header(const hdr *h, const char *path)
{
    char sh[256];
    if (!h->has_descr || !h->has_fortran || !h->has_shape)
        return cmd_fail("%s: the .npy header lacks '%s'", path,
                        !h->has_descr ? "descr" : !h->has_fortran ? "fortran_order" : "shape");
    if (h->plain)
        return cmd_fail("%s: a plain array of '%s' of shape %s: no column names. Save a structured array whose fields "
                        "are the columns, each '<f8' (e.g. numpy.lib.recfunctions.unstructured_to_structured(a, "
                        "names=[...]))",
                        path, h->plain, shape_text(sh, h));
    if (h->bad_name) {
        if (h->bad_what[0])
            return cmd_fail("%s: field '%s' %s: every field must be a plain '<f8' (little-endian float64) named as a "
                            "CSV column",
                            path, h->bad_name, h->bad_what);
        return cmd_fail("%s: field '%s' is '%s': every field must be '<f8' (little-endian float64; e.g. "
                        "arr.astype([(n, '<f8') for n in arr.dtype.names]))",
                        path, h->bad_name, h->bad_type);
    }
    if (h->nnames == 0) return cmd_fail("%s: a structured array with no fields", path);
    if (h->fortran)
        return cmd_fail("%s: fortran_order True: save the array in C order (numpy.ascontiguousarray)", path);
    if (h->ndim != 1)
        return cmd_fail("%s: shape %s: one record a row is needed, shape (N,) (arr.reshape(-1))", path,
                        shape_text(sh, h));
    return 0;
}

int npy_read_header(FILE *f, const char *path, char ***names, int *ncol, long long *nrow, long long *offset)
{
    *names = NULL;
    *ncol = 0;
    unsigned char pre[12];
    size_t got = fread(pre, 1, 10, f);
    if (got < 10 || memcmp(pre, magic, 6) != 0)
        return cmd_fail("%s: not a .npy file (it does not start with \\x93NUMPY)%s", path,
                        ferror(f) ? ": cannot be read" : "");
    const int major = pre[6], minor = pre[7];
    if (!((major == 1 || major == 2 || major == 3) && minor == 0))
        return cmd_fail("%s: .npy format version %d.%d: versions 1.0, 2.0 and 3.0 are read", path, major, minor);
    unsigned long hlen = (unsigned long)pre[8] | (unsigned long)pre[9] << 8;
    long long off = 10;
    if (major >= 2) {
        if (fread(pre + 10, 1, 2, f) != 2) return cmd_fail("%s: truncated in its .npy header", path);
        hlen |= (unsigned long)pre[10] << 16 | (unsigned long)pre[11] << 24;
        off = 12;
    }
    if (hlen > NPY_MAX_HEADER)
        return cmd_fail("%s: a .npy header of %lu bytes: longer than %d bytes (this command's bound)", path, hlen,
                        NPY_MAX_HEADER);
    char *text = malloc(hlen + 1);
    if (!text) return cmd_fail("out of memory");
    if (fread(text, 1, hlen, f) != hlen) {
        free(text);
        return cmd_fail("%s: truncated in its .npy header (%lu bytes announced)", path, hlen);
    }
    text[hlen] = '\0';
    off += (long long)hlen;
    hdr h = {.p = text, .start = text, .end = text + hlen, .latin1 = major < 3};
    char *key = NULL;
    int st = parse_dict(&h, &key);
    if (!st) {
        skip_space(&h);
        if (h.p != h.end) st = -1;
    }
    int status = 0;
    if (st == -2) status = cmd_fail("out of memory");
    else if (st == -3)
        status = cmd_fail("%s: the .npy header has a key '%s': only 'descr', 'fortran_order' and 'shape' (each once)",
                          path, key);
    else if (st)
        status = cmd_fail("%s: the .npy header is not a dict of 'descr', 'fortran_order' and 'shape' (unreadable at "
                          "its byte %ld)",
                          path, (long)(h.p - h.start));
    else status = check_header(&h, path);
    free(key);
    free(text);
    if (!status) { /* the size: the header and N rows of 8 bytes a field */
        const long long n = h.shape[0], row = 8LL * h.nnames;
        struct stat s;
        if (n > (LLONG_MAX - off) / row) {
            status = cmd_fail("%s: shape (%lld,): more rows than a file can hold", path, n);
        } else if (fstat(fileno(f), &s) == 0 && S_ISREG(s.st_mode) && (long long)s.st_size != off + n * row) {
            status = cmd_fail("%s: %lld bytes, but its header says %lld rows of %d float64 fields: %lld bytes (%s)",
                              path, (long long)s.st_size, n, h.nnames, off + n * row,
                              (long long)s.st_size < off + n * row ? "truncated" : "bytes after the data");
        }
    }
    if (status) {
        hdr_free(&h);
        return status;
    }
    *names = h.names;
    *ncol = h.nnames;
    *nrow = h.shape[0];
    *offset = off;
    h.names = NULL;
    h.nnames = 0;
    hdr_free(&h);
    return 0;
}

/* ---- writing ---------------------------------------------------------------------------- */

/* a growing text */
typedef struct {
    char *s;
    size_t n, cap;
    int oom;
} text;

static void put(text *t, const char *s, size_t n)
{
    if (t->oom) return;
    if (t->n + n + 1 > t->cap) {
        size_t cap = t->cap ? t->cap : 4096;
        while (cap < t->n + n + 1) cap *= 2;
        char *p = realloc(t->s, cap);
        if (!p) {
            t->oom = 1;
            return;
        }
        t->s = p;
        t->cap = cap;
    }
    memcpy(t->s + t->n, s, n);
    t->n += n;
    t->s[t->n] = '\0';
}

static void puts_(text *t, const char *s)
{
    put(t, s, strlen(s));
}

/* name as a Python string literal: quoted, its quote and backslash escaped, control characters as
 * \xNN, other bytes as they are (UTF-8: format 3.0 when one is not ASCII) */
static void put_name(text *t, const char *name)
{
    put(t, "'", 1);
    for (const unsigned char *c = (const unsigned char *)name; *c; c++) {
        char e[8];
        if (*c == '\'' || *c == '\\') {
            e[0] = '\\';
            e[1] = (char)*c;
            put(t, e, 2);
        } else if (*c < 0x20 || *c == 0x7F) {
            snprintf(e, sizeof e, "\\x%02x", *c);
            put(t, e, 4);
        } else {
            put(t, (const char *)c, 1);
        }
    }
    put(t, "'", 1);
}

/* the dict of ncol '<f8' fields named names and nrow rows, as numpy writes it */
static void put_dict(text *t, const char *const *names, int ncol, long long nrow)
{
    puts_(t, "{'descr': [");
    for (int k = 0; k < ncol; k++) {
        put(t, "(", 1);
        put_name(t, names[k]);
        puts_(t, k + 1 < ncol ? ", '<f8'), " : ", '<f8')");
    }
    char tail[64];
    snprintf(tail, sizeof tail, "], 'fortran_order': False, 'shape': (%lld,), }", nrow);
    puts_(t, tail);
}

int npy_header(char **out, size_t *len, const char *const *names, int ncol, long long nrow, size_t min_len)
{
    text d = {0};
    put_dict(&d, names, ncol, nrow);
    if (d.oom) {
        free(d.s);
        return 1;
    }
    int ascii = 1;
    for (size_t k = 0; k < d.n; k++) ascii &= (unsigned char)d.s[k] < 0x80;
    /* the total (magic, version, length field, dict, spaces, '\n') a multiple of 64, at least min_len */
    int major = ascii ? 1 : 3;
    size_t field = major == 1 ? 2 : 4;
    size_t total = (10 + (field - 2) + d.n + 1 + 63) / 64 * 64;
    if (total < min_len) total = min_len;
    if (major == 1 && total - 10 > 65535) {
        major = 2;
        field = 4;
        total = (12 + d.n + 1 + 63) / 64 * 64;
        if (total < min_len) total = min_len;
    }
    char *h = malloc(total);
    if (!h) {
        free(d.s);
        return 1;
    }
    const size_t hlen = total - 8 - field;
    memcpy(h, magic, 6);
    h[6] = (char)major;
    h[7] = 0;
    for (size_t k = 0; k < field; k++) h[8 + k] = (char)((hlen >> (8 * k)) & 0xFF);
    memcpy(h + 8 + field, d.s, d.n);
    memset(h + 8 + field + d.n, ' ', total - (8 + field + d.n) - 1);
    h[total - 1] = '\n';
    free(d.s);
    *out = h;
    *len = total;
    return 0;
}

size_t npy_max_header_len(const char *const *names, int ncol)
{
    char *h;
    size_t len;
    if (npy_header(&h, &len, names, ncol, 9223372036854775807LL, 0)) return 0;
    free(h);
    return len;
}
