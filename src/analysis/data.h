/* vtdyn — The data: its layout and the arena that holds every stage's scratch (analysis/data.c). */
#ifndef VT_ANALYSIS_DATA_H
#define VT_ANALYSIS_DATA_H

#include "vtdyn.h"

/* vt_data_create's data with the dense arrays whatever the model's layout: the analyses' own
 * data for the stages they run (the forward check, the dynamic analysis's). */
vt_status vt_data_create_full(vt_data **data, const vt_model *m);

#endif
