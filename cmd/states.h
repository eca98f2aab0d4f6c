/* The command's `inverse`, the states form (cmd/states.c). */
#ifndef VTDYN_CMD_STATES_H
#define VTDYN_CMD_STATES_H

#include "run.h"

/* the chunk's rows (as many as CHUNK_BYTES holds, CHUNK_ROWS a thread at most) and arrays; 0 or 1 */
int chunk_arrays(run *x);

/* chunk row r's own inputs beside its state, from its numbers (row, at loc in the input): each
 * contact's C_active (0 or 1, else refused) and the loads at frames, as read (a sample's are not
 * splined); 0, or 1 with the message in msg (ROW_MESSAGE) */
int row_extras(const run *x, int r, const double *row, long long loc, char *msg);

/* the batch's inputs and outputs for the chunk's first n rows: the run's arrays */
vt_batch_io chunk_io(const run *x, int n);

/* chunk row r's failing state (by the batch), at loc in the input, solved alone on the run's
 * data for its message */
int state_failure(run *x, int r, long long loc);

/* states: chunk after chunk parsed and laid out (on the threads), solved by the batch, formatted
 * (on the threads) and written in order. With more than one thread the file's work — the chunk
 * before written, the chunk after read — runs on a thread of its own beside them (two chunks
 * read, two output sets); with one, in turn on the caller's thread. 0, or 1 at the chunk's first
 * failing row (the chunks before it written) */
int run_states(run *x);

#endif
