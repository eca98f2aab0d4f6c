/* The command's tables (cmd/csv.c): the columns' names indexed, a CSV header and rows parsed,
 * and the output written beside its name and renamed when complete. */
#ifndef VTDYN_CMD_CSV_H
#define VTDYN_CMD_CSV_H

#include <stddef.h>
#include <stdio.h>

/* a column's name and index, in the table's index by name */
typedef struct {
    const char *name;
    int col;
} table_key;

/* sorts n keys by name (strcmp); the entry of name in sorted keys, or -1 (log n) */
void keys_sort(table_key *keys, int n);
int keys_find(const table_key *keys, int n, const char *name);

/* a table of numbers under named columns: the names always, the cells when read whole */
typedef struct {
    int ncol, nrow;
    int header_line;     /* a CSV header's line in the file (1 unless blank lines precede it); 0: a .npy file */
    char **name;         /* the columns' names (ncol) */
    table_key *order;    /* the columns sorted by name (ncol), for table_column */
    unsigned char *used; /* 1 where table_column has found the column (ncol) */
    double *cell;        /* nrow x ncol, row-major, when read whole (samples) */
    long long *loc;      /* each row's place for the messages: its line (CSV) or index (.npy) (nrow) */
} table;

/* longest line of a CSV file, in bytes, its line end not counted (docs/command.md): a robot of
 * 1,000 bodies has about 3000 columns, 75 kB of numbers at full precision and about 200 kB of
 * header names, so a line holds the states of some 3,500 bodies; a longer line (a file that is
 * not a table, /dev/zero) is refused, naming it, once the bound is passed (the file is read no
 * further) */
#define CSV_MAX_LINE (1024 * 1024)

/* the longest message about one row (csv_parse_row, the rows' other checks), and the longest
 * row's place in it (input_where: the file's name cut at 300 bytes, and the row) */
#define ROW_MESSAGE 1024
#define ROW_WHERE 400

/* frees the table's names, index and cells; *t is then empty */
void table_free(table *t);
/* the index of the table's t->ncol names (t->name): sorted, each name once, or the first name
 * given twice named with both its places (columns of the CSV header at line `line` of path, or
 * fields of a .npy file when line is 0); 0, or 1 with the message printed */
int table_index(table *t, const char *path, int line);
/* the index of the column named name (marked used), or -1; log ncol */
int table_column(const table *t, const char *name);
/* data row r (0-based) of a table read whole: its ncol cells */
static inline const double *table_row(const table *t, int r)
{
    return t->cell + (size_t)r * (size_t)t->ncol;
}

/* the CSV header row s (line `line` of path, cut in place) as the table's names: a name in double
 * quotes may hold commas, "" a quote (RFC 4180); each named, none twice; 0, or 1 with the message
 * printed */
int csv_read_header(table *t, char *s, const char *path, int line);
/* the CSV data row s (line `line` of path, cut in place; its spaces around cells skipped, a number
 * in double quotes allowed) as t->ncol finite numbers into out, with a '.' decimal point (the
 * calling thread's locale: the C one). 0, or 1 with the message (the file, the line, the column
 * and the cell) in msg (ROW_MESSAGE bytes). Safe on threads */
int csv_parse_row(const table *t, char *s, double *out, const char *path, long long line, char *msg);

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
/* reserves the output file's final size in bytes where the file system can (Linux's fallocate),
 * so that the writes do not allocate block by block and a full disk is found before the rows are
 * written: 0, or 1 with a message when the file system has no room for it; nothing for standard
 * output or where reserving is not supported */
int output_reserve(output *o, unsigned long long bytes);
/* ends the output: when complete is nonzero, checks that every write succeeded and renames
 * PATH.part to PATH (or flushes standard output); otherwise, or when that fails, removes
 * PATH.part. 0 when the output is complete under its name, else 1 (a message printed when the
 * failure is the output's own) */
int output_close(output *o, int complete);

#endif
