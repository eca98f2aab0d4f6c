/* vtdyn — Batches: the given-motion instant on many states, on threads (analysis/batch.c). The
 * entry points are public (vtdyn.h: vt_batch_*); nothing internal is shared. */
#ifndef VT_ANALYSIS_BATCH_H
#define VT_ANALYSIS_BATCH_H

#include "vtdyn.h"

#endif
