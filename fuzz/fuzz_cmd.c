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

static void free_names(char **names, int n)
{
    for (int k = 0; k < n; k++) free(names[k]);
    free(names);
}

/* one .npy header read, and when read, written again and read back */
static void npy_case(const uint8_t *data, size_t size)
{
    if (size == 0) return;
    FILE *f = fmemopen((void *)(uintptr_t)data, size, "rb");
    if (!f) return;
    char **names = NULL, sink[512] = "";
    int ncol = 0;
    long long nrow = -1, offset = -1;
    cmd_message_sink(sink, sizeof sink);
    const int bad = npy_read_header(f, "fuzz.npy", &names, &ncol, &nrow, &offset);
    cmd_message_sink(NULL, 0);
    fclose(f);
    if (bad) {
        if (!sink[0]) broken("a .npy header refused without a message", NULL);
        return;
    }
    if (ncol < 1 || !names || nrow < 0 || offset < 10 || (unsigned long long)offset > size)
        broken("a .npy header accepted with no field, a negative shape or an offset outside the file", NULL);
    char *hdr = NULL;
    size_t len = 0;
    if (npy_header(&hdr, &len, (const char *const *)names, ncol, nrow, 0)) broken("out of memory", NULL);
    f = fmemopen(hdr, len, "rb");
    if (!f) broken("fmemopen", NULL);
    char **names2 = NULL;
    int ncol2 = 0;
    long long nrow2 = -1, offset2 = -1;
    sink[0] = '\0';
    cmd_message_sink(sink, sizeof sink);
    const int bad2 = npy_read_header(f, "again.npy", &names2, &ncol2, &nrow2, &offset2);
    cmd_message_sink(NULL, 0);
    fclose(f);
    if (bad2) broken("a .npy header written again is refused", sink);
    if (ncol2 != ncol || nrow2 != nrow || offset2 != (long long)len)
        broken("a .npy header written again reads as other fields, rows or offset", NULL);
    for (int k = 0; k < ncol; k++)
        if (strcmp(names[k], names2[k]) != 0) broken("a .npy field's name written again reads otherwise", names[k]);
    free_names(names2, ncol2);
    free(hdr);
    free_names(names, ncol);
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
