/* The command's input (cmd/input.c): a CSV or .npy file of numbers under named columns, its
 * header read first, then its rows in chunks (resident memory flat in the number of rows), or
 * every row at once (the samples form). */
#ifndef VTDYN_CMD_INPUT_H
#define VTDYN_CMD_INPUT_H

#include <stddef.h>
#include <stdio.h>

#include "csv.h"

/* a file's format, by its name */
typedef enum { FMT_CSV, FMT_NPY } file_format;
/* FMT_NPY for a name ending in ".npy" (any case), else FMT_CSV */
file_format format_of(const char *path);

/* an input file being read */
typedef struct {
    const char *path;
    file_format fmt;
    FILE *f;
    table t;          /* its columns (the cells only after input_read_all) */
    long long nrow;   /* .npy: the rows its header announces; CSV: -1 (known at the end) */
    long long next;   /* the rows read so far */
    long long size;   /* its bytes when a regular file, else -1 (for the progress line) */
    long long pos;    /* the bytes read so far */
    /* CSV: a window of the file (the lines are found in it) and the line count */
    char *buf;
    size_t cap, beg, end;
    int eof, line;
} input;

/* rows read and not yet parsed */
typedef struct {
    int n, cap;        /* rows held, rows allocated */
    long long *loc;    /* each row's place: its line (CSV) or index from 0 (.npy) */
    size_t *off;       /* CSV: each row's text (its line, trimmed, NUL-ended) at text + off[r] */
    char *text;
    size_t len, tcap;
    unsigned char *raw; /* .npy: the rows' bytes, 8 a field */
    size_t rcap;
} chunk;

/* opens the file and reads its header (a CSV header row, the first line that is not blank; a
 * .npy header, checked, and its size); 0, or 1 with the message printed */
int input_open(input *in, const char *path);
/* closes the file and frees what the input holds */
void input_close(input *in);
/* the next rows, at most maxrows and about maxbytes bytes of text (at least one row), into c
 * (c->n 0 at the end of the file); blank lines skipped; 0, or 1 with the message printed (a line
 * too long, a truncated file, a read error) */
int input_read(input *in, chunk *c, int maxrows, size_t maxbytes);
/* row r of c as the t.ncol numbers into out: 0, or 1 with the message (file, row, column) in msg
 * (ROW_MESSAGE bytes). A CSV row's text is cut in place: parsed once. Safe on threads when each
 * row is parsed by one */
int input_parse(const input *in, chunk *c, int r, double *out, char *msg);
/* a row's place as the messages name it, into buf (ROW_WHERE bytes): "states.csv:12" (its line)
 * or "states.npy[10]" (its index) */
const char *input_where(const input *in, long long loc, char *buf);
/* every row (left) of the file parsed into in->t's cells and places (the samples form); 0, or 1
 * with the message printed */
int input_read_all(input *in);
/* frees the chunk's arrays */
void chunk_free(chunk *c);

#endif
