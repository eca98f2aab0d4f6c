/* libFuzzer harness of the command's file formats (cmd/csv.c, cmd/npy.c and the numbers of
 * cmd/number_text.cc): the first byte picks a CSV or a .npy file, the rest is the file.
 * Whatever the bytes:
 *
 * - CSV: its first line is the header. csv_read_header either names every column, none twice,
 *   none empty, or fails with a message. Each later line is a row: csv_parse_row either gives
 *   the header's number of finite numbers, each of which, printed in its shortest form
 *   (number_print) and read again as a row, gives back the same bits, or fails with a message
 *   that names the file and the line;
 * - .npy: npy_read_header either refuses with a message or gives one or more named fields, a
 *   row count ≥ 0 and the data's offset within the bytes; the header written again for those
 *   names and rows (npy_header, as the command writes its outputs) reads back as the same names
 *   and rows.
 *
 * A broken promise prints which and aborts (libFuzzer keeps the input). Built and run by
 * fuzz/run.sh beside the other harnesses. */
#define _GNU_SOURCE /* fmemopen */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv.h"
#include "message.h"
#include "npy.h"
#include "number_text.h"

static void broken(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz_cmd: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    abort();
}

/* one CSV file: the header, then each row, as the command reads them (in place, cut at the line) */
static void csv_case(char *text)
{
    char msg[ROW_MESSAGE];
    table t = {0};
    char *line = text, *next = strchr(line, '\n');
    if (next) *next++ = '\0';
    char sink[512] = "";
    cmd_message_sink(sink, sizeof sink);
    const int bad = csv_read_header(&t, line, "fuzz.csv", 1);
    cmd_message_sink(NULL, 0);
    if (bad) {
        if (!sink[0]) broken("a CSV header refused without a message", NULL);
        table_free(&t);
        return;
    }
    if (t.ncol < 1) broken("a CSV header accepted with no column", NULL);
    for (int c = 0; c < t.ncol; c++) {
        if (!t.name[c] || !t.name[c][0]) broken("a CSV header accepted with an empty name", NULL);
        if (table_column(&t, t.name[c]) != c) broken("a CSV column not found by its name", t.name[c]);
    }
    double *v = malloc(2 * (size_t)t.ncol * sizeof(double));
    char *again = malloc((size_t)t.ncol * (NUMBER_TEXT_MAX + 1) + 1);
    if (!v || !again) broken("out of memory", NULL);
    for (long long ln = 2; next; ln++) {
        line = next;
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        msg[0] = '\0';
        if (csv_parse_row(&t, line, v, "fuzz.csv", ln, msg)) {
            char where[64];
            snprintf(where, sizeof where, "fuzz.csv:%lld:", ln);
            if (strncmp(msg, where, strlen(where)) != 0) broken("a CSV row refused without its place", msg);
            continue;
        }
        /* the numbers read, printed shortest and read again: the same bits */
        char *p = again;
        for (int c = 0; c < t.ncol; c++) {
            if (!isfinite(v[c])) broken("a CSV row accepted with a number not finite", NULL);
            if (c) *p++ = ',';
            p += number_print(p, v[c], 0);
        }
        *p = '\0';
        if (csv_parse_row(&t, again, v + t.ncol, "fuzz.csv", ln, msg)) broken("a printed row refused", msg);
        if (memcmp(v, v + t.ncol, (size_t)t.ncol * sizeof(double)) != 0)
            broken("a number printed and read again differs", NULL);
    }
    free(again);
    free(v);
    table_free(&t);
}

/* a .npy header read into t as the command reads it (cmd/input.c: npy_read_header, then
 * table_index, which refuses a field named twice); 0, or 1 with the message in sink */
static int npy_table(table *t, const void *bytes, size_t size, const char *path, char *sink, size_t cap,
                     long long *nrow, long long *offset)
{
    FILE *f = fmemopen((void *)(uintptr_t)bytes, size, "rb");
    if (!f) broken("fmemopen", NULL);
    sink[0] = '\0';
    cmd_message_sink(sink, cap);
    const int bad = npy_read_header(f, path, &t->name, &t->ncol, nrow, offset) || table_index(t, path, 0);
    cmd_message_sink(NULL, 0);
    fclose(f);
    return bad;
}

/* one .npy header read, and when read, written again and read back */
static void npy_case(const uint8_t *data, size_t size)
{
    if (size == 0) return;
    char sink[512];
    table t = {0}, t2 = {0};
    long long nrow = -1, offset = -1, nrow2 = -1, offset2 = -1;
    if (npy_table(&t, data, size, "fuzz.npy", sink, sizeof sink, &nrow, &offset)) {
        if (!sink[0]) broken("a .npy header refused without a message", NULL);
        table_free(&t);
        return;
    }
    if (t.ncol < 1 || nrow < 0 || offset < 10 || (unsigned long long)offset > size)
        broken("a .npy header accepted with no field, a negative shape or an offset outside the file", NULL);
    char *hdr = NULL;
    size_t len = 0;
    if (npy_header(&hdr, &len, (const char *const *)t.name, t.ncol, nrow, 0)) broken("out of memory", NULL);
    if (npy_table(&t2, hdr, len, "again.npy", sink, sizeof sink, &nrow2, &offset2))
        broken("a .npy header written again is refused", sink);
    if (t2.ncol != t.ncol || nrow2 != nrow || offset2 != (long long)len)
        broken("a .npy header written again reads as other fields, rows or offset", NULL);
    for (int k = 0; k < t.ncol; k++)
        if (strcmp(t.name[k], t2.name[k]) != 0) broken("a .npy field's name written again reads otherwise", t.name[k]);
    free(hdr);
    table_free(&t2);
    table_free(&t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    if (data[0] & 1) {
        npy_case(data + 1, size - 1);
        return 0;
    }
    char *text = malloc(size); /* the bytes after the first, and a NUL */
    if (!text) return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    csv_case(text);
    free(text);
    return 0;
}
