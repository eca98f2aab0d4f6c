/* The command's `inverse`, the output's columns, rows and file (cmd/output.c). */
#ifndef VTDYN_CMD_OUTPUT_H
#define VTDYN_CMD_OUTPUT_H

#include "run.h"

/* the input has no rows: refused, as a table without rows */
int no_rows(const run *x);

/* the output's columns: t when given, then per joint the selected groups in their order (effort,
 * world, link, bearing, limits; a floating root's efforts in world then link axes in `effort`,
 * nothing else); 0 or 1 */
int output_columns(run *x);

/* the output's header: the CSV row of names, or the .npy header (with its row count when known,
 * else with room for any: rewritten by finish_output); 0 or 1 */
int write_header(run *x, long long nrow);

/* the chunk's n rows formatted on the threads into the output set x->oset; 0 or 1 */
int format_rows(run *x, int n);

/* output set `set`, n rows formatted, written in order (its blocks' buffers, or its values) */
void put_rows(run *x, int set, int n);

/* the samples forms' chunk of n rows, solved in output set 0: formatted, written in order and
 * the progress shown (*start, *last as progress takes them); 0 or 1 */
int write_chunk(run *x, int n, double *start, double *last);

/* a .npy header written before the row count was known: rewritten with it, in place; 0 or 1 */
int finish_output(run *x);

/* "row R of N" (or "row R, P% of the file"), rows per second and the time left on standard error
 * when it is a terminal and the file long, refreshed at most twice a second (and at the end);
 * *start is the time of the first row, *last that of the previous line (0 before the first) */
void progress(const run *x, int done, double *start, double *last);

/* the output's format: --format, else -o's name (.npy), else CSV; npy on standard output only
 * with the row count known ahead; 0 or 1 */
int output_format(run *x, const char *outpath);

#endif
