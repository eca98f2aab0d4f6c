/* The command's `inverse` (cmd/inverse.c): efforts and joint reactions from a CSV file of states
 * or of samples of a trajectory. */
#ifndef VTDYN_CMD_INVERSE_H
#define VTDYN_CMD_INVERSE_H

/* `vtdyn inverse [--floating] URDF STATES [-o OUTPATH]`: one output row per input row, to
 * OUTPATH (written beside it and renamed when complete) or standard output when NULL; 0, or 1
 * with the message printed */
int cmd_inverse(const char *urdf, const char *states, const char *outpath, int floating);

#endif
