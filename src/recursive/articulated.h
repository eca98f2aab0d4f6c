/* vtdyn — The articulated route of the recursive evaluation (recursive/articulated.c): (5) by
 * articulated bodies, without M*; it falls back to the general route (recursive/general.c). */
#ifndef VT_RECURSIVE_ARTICULATED_H
#define VT_RECURSIVE_ARTICULATED_H

#include <stddef.h>

#include "vtdyn.h"
#include "numeric/route.h" /* vt_handoff */

/* fewer independent rows than rates, no base body: q̈, λ and the reactions, the constraints
 * evaluated; the general route where a pivot or the estimate gives way */
vt_status vt_articulated_instant(const vt_model *m, vt_data *d, vt_handoff *to);
/* every row a joint drive: the free rates' q̈ and the estimate rcond; 0, 1 (a pivot or the
 * estimate gave way: the general route decides) or a negative vt_status */
int vt_articulated_free_rates(const vt_model *m, vt_data *d, double *rcond);
/* the scratch vt_articulated_instant and vt_articulated_free_rates take at once */
size_t vt_articulated_scratch(const vt_model *m);

#endif
