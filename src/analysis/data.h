/* vtdyn — The data: its layout and the arena that holds every stage's scratch (analysis/data.c).
 * Offers only public functions (vtdyn.h). */
#ifndef VT_ANALYSIS_DATA_H
#define VT_ANALYSIS_DATA_H

#include "vtdyn.h"

#endif
