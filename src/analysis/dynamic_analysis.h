/* vtdyn — The dynamic analysis and the forward check with IDA (analysis/dynamic_analysis.c). */
#ifndef VT_ANALYSIS_DYNAMIC_ANALYSIS_H
#define VT_ANALYSIS_DYNAMIC_ANALYSIS_H

#include "vtdyn.h"

/* The forward check with IDA (dynamic_analysis.c): integrates m without drives from the driven
 * state at opt->t0, with the drives' generalized force at each time, evaluated exactly on dk (of
 * dk->model: m itself, or in a test a model of other inertia with the same joints and drives) by
 * vt_kinematic_solve_impl from the rows of tr around it, interpolated (vt_kinematic_start), and at
 * the output times taken from tr's rows (fully driven models). IDA's unknowns are the deviation
 * from that exact motion. */
vt_status vt_forward_exact(const vt_model *m, vt_data *d, vt_data *dk, const vt_run_options *opt, vt_trajectory *tr);

#endif
