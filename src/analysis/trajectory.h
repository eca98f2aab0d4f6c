/* vtdyn — Trajectories and run options (analysis/trajectory.c). */
#ifndef VT_ANALYSIS_TRAJECTORY_H
#define VT_ANALYSIS_TRAJECTORY_H

#include "vtdyn.h"

/* Trajectory rows (trajectory.c) */
void vt_trajectory_store(vt_trajectory *tr, const vt_model *m, const vt_data *d, int row);
void vt_trajectory_store_forward(vt_trajectory *tr, const vt_model *mf, const vt_data *df, int row);
void vt_trajectory_reset(vt_trajectory *tr);
/* a new window of the forward check from row `row` (row 0 starts the list again; store_forward
 * of row 0 does it) */
void vt_trajectory_window(vt_trajectory *tr, int row);
vt_status vt_check_run(const vt_model *m, vt_data *d, const vt_run_options *opt, vt_trajectory *tr, const char *who);
/* Output rows of a run after row 0 (nout or ntout), and the time of row k (0 = t0) */
int vt_run_rows(const vt_run_options *opt);
double vt_run_time(const vt_run_options *opt, int k);

#endif
