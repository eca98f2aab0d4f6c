/* vtdyn — The kinematic analysis over time (analysis/kinematic_analysis.c). Offers only public
 * functions (vtdyn.h). */
#ifndef VT_ANALYSIS_KINEMATIC_ANALYSIS_H
#define VT_ANALYSIS_KINEMATIC_ANALYSIS_H

#include "vtdyn.h"

#endif
