/* vtdyn — Round-off of exact zeros: M*'s diagonal and Φ_q's rows judged against the terms
 * they are summed from (numeric/roundoff.c). */
#ifndef VT_NUMERIC_ROUNDOFF_H
#define VT_NUMERIC_ROUNDOFF_H

#include <float.h>
#include <stddef.h>

#include "vtdyn.h"
#include "kinematics/kinematics.h" /* vt_form */
#include "model/model.h"

size_t vt_roundoff_scratch(const vt_model *m);

/* Round-off of exact zeros: T (2 nv) the magnitudes of the terms of each rate's M*_aa,
 * T_a = Σ_k m_k (|v_a| + |ω_a| L_k)² (L_k ≥ |c_k − o|: vt_lengths_from_o) and R_a = |ω_a|² Σ_k tr J'_k over the bodies k it moves,
 * from the twists (w: 4 (nbody + 1) scratch); vt_rate_roundoff, the size below which M*_aa is
 * round-off, τ ε (T_a + R_a). */
#define VT_ROUND_TAU 64.0
/* Below DBL_MIN a number has lost digits (the dense path refuses an M*_aa there, naming the
 * rate); the recursive routes, whose pivots round differently, hand every pivot below DBL_MIN / ε
 * to the dense stages, so that both paths decide the edge by the same numbers */
#define VT_PIVOT_NORMAL (DBL_MIN / DBL_EPSILON)
void vt_rate_terms(const vt_model *m, const vt_data *d, double *w, double *T);
double vt_rate_roundoff(const double *T, int a);
/* The bound below which M*_aa is round-off, for every rate, into beta (nv): of the M* the
 * dense stages form as S^T M S (VT_FORM_DENSE: S's columns squared, (τ ε)² T_a + τ ε R_a, T_a with
 * the dense S's lever arms, vt_lever) or of the recursive general route's composite inertias
 * about o (VT_FORM_TWISTS: vt_rate_roundoff). Scratch: 2 nv + 4 (nbody + 1) doubles */
int vt_rate_bounds(const vt_model *m, vt_data *d, vt_form form, double *beta);

/* the rows that Φ_x S builds (points, lines, dot products, orientations), whose entries are
 * sums and can be round-off; joint drives', couplings' and p^T p − 1's entries are exact */
static inline int vt_judged_row(const vt_model *m, int r)
{
    const int kind = m->con_kind[r];
    return kind != VT_ROW_JOINT && kind != VT_ROW_COUPLING && kind != VT_ROW_NORM;
}

/* Rows that are round-off of a zero row, flagged 1 in flag (nc; NULL: not kept), and, with
 * withM (M* formed), the rates whose M*_aa is round-off and that no row fixes: VT_ERR_SINGULAR,
 * named. form: M* is the dense S^T M S (VT_FORM_DENSE), else the recursive general route's composite inertias
 * about o, which cannot decide every such rate: VT_ROUNDOFF_COMPOSITE then (the dense stages
 * decide). Returns the number of rows flagged, VT_ROUNDOFF_COMPOSITE or a negative vt_status. */
#define VT_ROUNDOFF_COMPOSITE (-1000) /* below every vt_status */
int vt_roundoff_check(const vt_model *m, vt_data *d, int *flag, int withM, vt_form form);
/* the number of rows of Φ_q that are round-off of a zero row (judged against the terms they are
 * summed from), or a negative vt_status */
int vt_zero_rows(const vt_model *m, vt_data *d);
/* the same on the free rates alone (known[a] < 0): rows dependent on the known rates' */
int vt_zero_rows_free(const vt_model *m, vt_data *d, const int *known);

#endif
