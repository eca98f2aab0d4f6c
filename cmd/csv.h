/* The command's files (cmd/csv.c): a CSV table of numbers read whole, and an output written
 * beside its name and renamed when complete. */
#ifndef VTDYN_CMD_CSV_H
#define VTDYN_CMD_CSV_H

#include <stdio.h>

/* a column's name and index, in the table's index by name */
typedef struct {
    const char *name;
    int col;
} table_key;

/* a CSV file of numbers under a header row */
typedef struct {
    int ncol, nrow;
    int header_line;  /* the header's line in the file (1 unless blank lines precede it) */
    char **name;      /* header cells (ncol) */
    table_key *order; /* the columns sorted by name (ncol), for table_column */
    unsigned char *used; /* 1 where table_column has found the column (ncol) */
    double *cell;     /* nrow x ncol, row-major */
} table;

/* longest line of a CSV file, in bytes, its line end not counted (docs/command.md): a robot of
 * 1,000 bodies has about 3000 columns, 75 kB of numbers at full precision and about 200 kB of
 * header names, so a line holds the states of some 3,500 bodies; a longer line (a file that is not a table, /dev/zero) is refused, naming it,
 * once the bound is passed (nothing after it is read) */
#define CSV_MAX_LINE (1024 * 1024)

/* reads the CSV file at path: a header row of distinct names (a name in double quotes may hold
 * commas, "" a quote), then rows of as many finite
 * numbers (a '.' decimal point whatever the locale; blank lines, a UTF-8 byte-order mark and
 * spaces around cells skipped; lines of at most CSV_MAX_LINE bytes); 0, or 1 with the message,
 * naming the file's line, printed and *t empty */
int table_read(table *t, const char *path);
/* frees the table's cells and names; *t is then empty */
void table_free(table *t);
/* the index of the column named name (marked used), or -1; log ncol */
int table_column(const table *t, const char *name);
/* data row r (0-based): its ncol cells */
static inline const double *table_row(const table *t, int r)
{
    return t->cell + (size_t)r * (size_t)t->ncol;
}

/* an output: standard output, or a file written as PATH.part and renamed PATH when complete */
typedef struct {
    FILE *f;          /* where to write */
    const char *path; /* the name asked for, or NULL for standard output */
    char *tmp;        /* PATH.part while writing, created by us (NULL for standard output) */
} output;

/* opens the output: standard output when path is NULL, else PATH.part, created new (an existing
 * one is left alone and refused); PATH must be new or a regular file that is none of the ninputs
 * files inputs (the same file under another name too); 0, or 1 with the message printed */
int output_open(output *o, const char *path, const char *const *inputs, int ninputs);
/* ends the output: when complete is nonzero, checks that every write succeeded and renames
 * PATH.part to PATH (or flushes standard output); otherwise, or when that fails, removes
 * PATH.part. 0 when the output is complete under its name, else 1 (a message printed when the
 * failure is the output's own) */
int output_close(output *o, int complete);

#endif
