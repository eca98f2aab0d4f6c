/* The command's `inverse`, the samples form (cmd/samples.c). */
#ifndef VTDYN_CMD_SAMPLES_H
#define VTDYN_CMD_SAMPLES_H

#include "run.h"

/* for samples, the splines through them (every row read first): each joint's position,
 * each root's x, y, z and its quaternion's four components — every quaternion sample unit within
 * --normalize-quaternions (refused, its row named), normalised, and its sign turned where it
 * points away from the sample before (q and −q are one orientation; the spline must not pass
 * through 0 between them). The model solved has no drives (the given motion ignores them): the
 * splines are the drives of a model of their own, x->splines, one body each, because a model's
 * drive is the library's only spline evaluated in O(log n) at any n (vt_function_eval solves a
 * spline outside a model afresh at each call, and only up to VT_SPLINE_EVAL_MAX samples); that
 * model is never solved. 0 or 1 */
int spline_model(run *x);

/* samples: a chunk of rows at a time, each row's state from the splines at its t (its loads at
 * frames and contacts' C_active its own), solved by the batch as states are, formatted and
 * written; 0, or 1 at the first row that fails */
int run_samples(run *x);

#endif
