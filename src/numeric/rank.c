/* The rows' scalings and the rank decision: how the solve stage measures Φ_q before it solves
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 *
 * with M* q̈ = Q + Φ_q^T λ (2): the symmetric scaling D of (5) (the rates by the mass metric,
 * each row by its norm in it), ℓ the rows' own lever arm, a point drive's grip (how much of what
 * the rates can move its point by lies along the driven direction), and the SVD of a frame-,
 * unit- and inertia-independent scaling of Φ_q, Φ̂ = G Φ_q C, that tells rows dependent to
 * round-off (the rank, the directions a time analysis's band keeps, the null directions of
 * Φ_q^T) from a matrix that is only ill-conditioned. Each is said where it is done.
 */
#include <math.h>
#include <stddef.h>
#include <float.h>
#include <string.h>

#include "numeric/rank.h"
#include "base/arena.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"
#include "numeric/roundoff.h"

/* The symmetric scaling D of (5): the rates by the mass metric, d_a = M*_aa^(-1/2), into
 * s[0..nv); with rows, each constraint row by its own norm in that metric, 1 / ‖(Φ_q D)_r‖, into
 * s[nv..nv+nc) (a row without entries: 1). Row by row, so that rows on bodies of very different
 * masses (a joint drive on a 1e-9 kg link beside p^T p − 1 on a 30 kg base) are not taken for
 * rows losing their grip; a row that does lose its grip (a point drive at an arm's full
 * stretch) is measured apart, vt_rows_grip. vt_scaling_diag (rank.h): the rates' part. */
void vt_scaling(const vt_model *m, const vt_data *d, double *s, int rows)
{
    const int nv = m->nv, nc = m->nc;
    vt_scaling_diag(m, d->Mstar, nv + 1, s);
    if (!rows) return;
    for (int r = 0; r < nc; r++) {
        double rn = 0.0;
        for (int c = 0; c < nv; c++) {
            const double v = d->Phiq[r + (size_t)c * (size_t)nc] * s[c];
            rn += v * v;
        }
        s[nv + r] = rn > 0.0 ? 1.0 / sqrt(rn) : 1.0;
    }
}

/* A point drive's grip: the row is e · V_a, V_a = v_a + ω_a × P the velocity rate a's twist
 * gives the driven point P; the whole of V_a is what the rates can move the point by, the row
 * what of it lies along the driven direction e. Its grip is the ratio of the two, in the
 * rates' kinematic scaling (the square route's C: rates that turn by 1/ℓ, ℓ the rows' lever arm,
 * vt_rows_length):
 *   grip_r = ‖(e · V_a C_a)_a‖ / ‖(|V_a| C_a)_a‖   in [0, 1]
 * 1 while the rates move P along e as well as across it, 0 where no rate moves P along e (an
 * arm stretched along e: a row that has lost its grip, with nothing else to show it when it is
 * the only row). Independent of the units, of the scene's frame and position, and of the
 * inertias. vt_rows_grip gives the smallest grip² over the point drives' rows (1 without); the
 * sums run along the driven body's path, root first (vt_body_path). */
int vt_rows_grip(const vt_model *m, vt_data *d, double *grip)
{
    double worst = 1.0, rho = 0.0; /* ℓ */
    const size_t mark = vt_scratch_mark(d);
    int *path = NULL;
    for (int r = 0; r < m->nc; r++) {
        if (m->con_kind[r] != VT_ROW_POINT || vt_row_owner_kind(m, r) != VT_OWNER_DRIVE) continue;
        if (rho == 0.0) rho = vt_rows_length(m, d, NULL);
        if (!path && !(path = VT_SCRATCH(d, int, m->maxpath, "a body's path"))) return vt_scratch_fail(d, mark);
        const vt_drive_def *dr = m->drive + m->con_owner[r];
        const int b = dr->body;
        const double *A = d->A + 9 * b, *c = d->xrel + 6 * b; /* from o, as the twists */
        double P[3];
        vt_mulmat3(P, A, dr->point);
        for (int k = 0; k < 3; k++) P[k] += c[k];
        double num = 0.0, den = 0.0;
        const int np = vt_body_path(m, b, path);
        for (int k = 0; k < np; k++) {
            const int a = path[k];
            const double *tw = d->twist + 6 * a;
            const double ca = vt_dof_turns(m, a) ? 1.0 / rho : 1.0;
            double V[3];
            vt_copy3(V, tw + 3);
            vt_addcross3(V, tw, P);
            const double e = d->Phiq[r + (size_t)a * (size_t)m->nc] * ca;
            num += e * e;
            den += vt_dot3(V, V) * ca * ca;
        }
        const double g2 = den > 0.0 ? num / den : 0.0;
        worst = g2 < worst ? g2 : worst;
    }
    vt_scratch_release(d, mark);
    *grip = worst;
    return 0;
}

/* Dependent rows: what is truly dependent, decided on Φ_q alone (kinematics: the masses do not
 * take part) in a scaling that neither the directions of the global axes nor the units change.
 * Φ̂ = G Φ_q C: C = 1 for rates that translate and 1/ℓ for rates that turn (rotations, Euler
 * parameters), ℓ the rows' own lever arm (vt_rows_length: a length of the rows' geometry, not of the
 * mass distribution), so that every rate is dimensionless; G = diag(1 / t_r), t_r the size of
 * row r's terms in that scaling (row_size: what its entries are formed from, the speeds the rates
 * can give its points), so that each row's round-off is ε of 1 whatever its size: a row whose
 * lever arms are 1e17 times another's (a point drive 1e17 m out beside one at 1 m) keeps its
 * directions, where one factor for all rows put the short row below the rank's round-off. A row
 * losing its grip (its entries cancel at a singular pose while its terms do not) stays small. A
 * rotation of the scene turns a point's rows among themselves, which have one size, and a change
 * of units scales every entry and size alike, so the singular values of Φ̂ are unchanged by both,
 * and by inertia spread, which does not enter.
 * Its SVD Φ̂ = U Σ V^T (LAPACK dgesvd, U of nc columns) gives
 *   rank    the number of σ above max(nc, nv) ε σ_max (ε = DBL_EPSILON): dependence to round-off
 *           (rows that are round-off of zero, vt_roundoff_check, are zero rows here)
 *   kept    the directions kept in the solve: those above max(that, band σ_max), band being a time
 *           analysis's vt_run_options.redundant_band (0 at every other instant)
 * and the null directions of Φ_q^T, z = G w for the last nc − rank columns w of U (vt_rows_svd,
 * rank.h). */

/* 1 when row r measures a length (a translation), 0 when an angle */
int vt_length_row(const vt_model *m, const vt_data *d, int r)
{
    const int kind = m->con_kind[r];
    if (kind == VT_ROW_POINT || kind == VT_ROW_LINE) return 1;
    if (kind != VT_ROW_JOINT && kind != VT_ROW_COUPLING) return 0;
    int c = kind == VT_ROW_JOINT ? m->con_dof[r] : 0, axis = 0;
    if (kind == VT_ROW_COUPLING) /* q_a − ratio q_b: rate a's unit, its entry the first non-zero */
        while (c < m->nv - 1 && d->Phiq[r + (size_t)c * (size_t)m->nc] == 0.0) c++;
    const int i = m->dof_body[c];
    return vt_dof_kind(m->body_joint[i], c - m->body_vadr[i], &axis) == VT_DOF_TRANS;
}

/* ℓ, the rows' lever arm: the largest, over the point and line rows and the rates that turn, of
 * the speed a unit rate gives the row's point on body b relative to what it is measured from
 * (a point row: the partner point P_a; a line row: body a, which carries the line), |W_ra| (a
 * length per radian: how far the rate moves the rows' points), with
 *   W_ra = v_a + ω_a × P_b            rate a moves body b (side b of row r) and not body a
 *        = −(v_a + ω_a × P_a)         rate a moves body a and not body b (a point row)
 *        = −(v_a + ω_a × P_b)         the same for a line row: its entry is −u · that, the line's
 *                                     turning acting over P_b − P_a (a cut joint whose points
 *                                     lie 3e43 m apart: ℓ 6 m without it, Φ̂'s line rows then
 *                                     1e42 of its angle rows, and its rank 2 of 4)
 *        = ω_a × (P_b − P_a)          rate a moves both (a point row; a line row's is 0)
 * ((ω_a, v_a) its twist about o, P the row's points from o) — all three components, not the one
 * the row measures: a row that measures y beside a rate turning about y would otherwise make ℓ
 * collapse with the direction it measures, and scale a nearly dependent column to unit size. A W
 * that is round-off of the terms it is formed from (|v_a| + |ω_a| (|P_a| + |P_b|), τ ε of them: a
 * point on the rate's axis) counts as zero.
 * Without point and line rows (or when every W is zero), the reciprocal of the largest column
 * norm of the couplings that measure angles on the rates that translate (rad/m); without
 * either, 1 (then Φ̂'s blocks do not mix the two kinds and its singular values do not depend on
 * ℓ). A rotation of the scene turns every W alike and leaves its length. flag (nc or NULL): rows
 * left out (round-off of zero). */
double vt_rows_length(const vt_model *m, const vt_data *d, const int *flag)
{
    const int nv = m->nv, nc = m->nc;
    double arm2 = 0.0, inv = 0.0; /* the largest |W|², √ at the end (√ is monotonic: the same ℓ) */
    int prev = -1;                /* the last row measured: its bodies and points */
    for (int r = 0; r < nc; r++) {
        const int kind = m->con_kind[r];
        if ((flag && flag[r]) || (kind != VT_ROW_POINT && kind != VT_ROW_LINE)) continue;
        const int ba = m->con_body[2 * r], bb = m->con_body[2 * r + 1];
        /* a cut joint's rows on the same two points (a spherical joint's three) give the same W:
         * once */
        if (prev >= 0 && m->con_kind[prev] == kind && m->con_body[2 * prev] == ba && m->con_body[2 * prev + 1] == bb &&
            memcmp(m->con_point + 6 * prev, m->con_point + 6 * r, 6 * sizeof(double)) == 0)
            continue;
        prev = r;
        double P[2][3], dP[3];
        for (int s = 0; s < 2; s++) {
            const int b = s ? bb : ba;
            vt_mulmat3(P[s], d->A + 9 * b, m->con_point + 6 * r + 3 * s);
            for (int k = 0; k < 3; k++) P[s][k] += d->xrel[6 * b + k];
        }
        for (int k = 0; k < 3; k++) dP[k] = P[1][k] - P[0][k];
        const double pn = sqrt(vt_dot3(P[0], P[0])) + sqrt(vt_dot3(P[1], P[1]));
        /* the rates that move both bodies: those of the joints from their nearest common ancestor
         * (0: none) to the ground; an ancestor's id is below its descendants', so lowering the
         * larger of the two ids meets it */
        int common = 0;
        if (ba > 0 && bb > 0) {
            common = ba;
            for (int y = bb; common != y;)
                if (common > y) common = m->body_parent[common];
                else y = m->body_parent[y];
        }
        /* each side's path, walked down by dof_parent (the largest |W| in any order) */
        for (int s = 0; s < 2; s++) {
            for (int a = vt_last_rate(m, s ? bb : ba); a >= 0; a = m->dof_parent[a]) {
                if (!vt_dof_turns(m, a)) continue;
                const int both = m->dof_body[a] <= common;
                if (both && (s == 0 || kind == VT_ROW_LINE)) continue; /* once, from side b; a line's: 0 */
                const double *w = d->twist + 6 * a;
                double W[3];
                if (both) vt_cross3(W, w, dP);
                else { /* a line's: at P_b also where the rate moves body a */
                    vt_copy3(W, w + 3);
                    vt_addcross3(W, w, P[kind == VT_ROW_LINE ? 1 : s]);
                }
                /* round-off of the terms W is formed from is no lever arm (a point on the rate's
                 * axis: W 1e-15, whose 1/ℓ would scale that rate's round-off entries to O(1)) */
                const double w2 = vt_dot3(W, W);
                if (w2 <= arm2) continue; /* no larger than one already counted */
                const double terms = sqrt(vt_dot3(w + 3, w + 3)) + sqrt(vt_dot3(w, w)) * pn;
                if (sqrt(w2) > VT_ROUND_TAU * DBL_EPSILON * terms) arm2 = w2;
            }
        }
    }
    const double arm = sqrt(arm2);
    if (arm == 0.0)
        for (int a = 0; a < nv; a++) {
            if (vt_dof_turns(m, a)) continue;
            double n2 = 0.0;
            for (int r = 0; r < nc; r++)
                if (!(flag && flag[r]) && m->con_kind[r] == VT_ROW_COUPLING && !vt_length_row(m, d, r)) {
                    const double v = d->Phiq[r + (size_t)a * (size_t)nc];
                    n2 += v * v;
                }
            inv = fmax(inv, sqrt(n2));
        }
    const double len = arm > 0.0 ? arm : inv > 0.0 ? 1.0 / inv : 1.0;
    return isfinite(len) && len > 0.0 ? len : 1.0;
}

/* The size of row r's terms in the rates' scaling c (nv), ‖(t_a c_a)_a‖, B (nv) scratch: what
 * the row's entries are formed from, each rate's
 *   t_a = Σ_sides |v_a| + |ω_a| |P|   a point or line row (P its point on that side, from o: the
 *                                     speed the rate can give it)
 *       = Σ_sides |ω_a|               a row that measures an angle (dot products, orientations)
 *       = |Φ_q,ra|                     joint drives and couplings (exact)
 * over the rates that move either side ((ω_a, v_a) the rate's twist about o). Isotropic: a
 * point's rows measuring x, y or z (or any axis) get the same size, so a rotation of the scene,
 * which mixes them, leaves the scaled rows' singular values as they are; a change of units
 * scales entries and sizes alike. */
static double row_size(const vt_model *m, const vt_data *d, int r, const double *c, double *B)
{
    const int nv = m->nv, nc = m->nc, kind = m->con_kind[r];
    for (int a = 0; a < nv; a++) B[a] = 0.0;
    if (!vt_judged_row(m, r)) {
        for (int a = 0; a < nv; a++) B[a] = fabs(d->Phiq[r + (size_t)a * (size_t)nc]);
    } else {
        const int pt = kind == VT_ROW_POINT || kind == VT_ROW_LINE;
        for (int side = 0; side < 2; side++) {
            const int b = m->con_body[2 * r + side];
            if (b <= 0) continue;
            double P[3];
            vt_mulmat3(P, d->A + 9 * b, m->con_point + 6 * r + 3 * side);
            for (int k = 0; k < 3; k++) P[k] += d->xrel[6 * b + k];
            const double pn = sqrt(vt_dot3(P, P));
            for (int a = vt_last_rate(m, b); a >= 0; a = m->dof_parent[a]) { /* the path: one term a rate */
                const double *w = d->twist + 6 * a, wn = sqrt(vt_dot3(w, w));
                B[a] += pt ? sqrt(vt_dot3(w + 3, w + 3)) + wn * pn : wn;
            }
        }
    }
    double tmax = 0.0, t2 = 0.0;
    for (int a = 0; a < nv; a++) tmax = fmax(tmax, B[a] * c[a]);
    if (!(tmax > 0.0) || !isfinite(tmax)) return tmax;
    for (int a = 0; a < nv; a++) {
        const double v = B[a] * c[a] / tmax;
        t2 += v * v;
    }
    return tmax * sqrt(t2);
}

/* Φ̂ and its SVD into o (arrays on the arena: the caller releases them); band as above.
 * Returns 0 or a negative vt_status. */
int vt_rows_decide(const vt_model *m, vt_data *d, double band, vt_rows_svd *o)
{
    const int nv = m->nv, nc = m->nc, k = nc < nv ? nc : nv;
    o->k = k;
    o->U = VT_SCRATCH(d, double, (size_t)nc * (size_t)nc, "U");
    o->VT = VT_SCRATCH(d, double, (size_t)k * (size_t)nv, "V^T");
    o->sig = VT_SCRATCH(d, double, k, "σ");
    o->g = VT_SCRATCH(d, double, nc, "row scaling");
    o->s = VT_SCRATCH(d, double, nv, "mass metric");
    o->c = VT_SCRATCH(d, double, nv, "rate scaling");
    int *flag = o->flag = VT_SCRATCH(d, int, nc, "round-off rows");
    if (!flag) return vt_scratch_fail(d, vt_scratch_mark(d)); /* the caller releases o's arrays */
    const int ro = vt_roundoff_check(m, d, flag, 0, VT_FORM_TWISTS); /* a row that is round-off of zero counts as zero */
    if (ro < 0) return ro;
    const size_t mark = vt_scratch_mark(d);
    double *g = o->g, *s = o->c;
    vt_scaling_diag(m, d->Mstar, nv + 1, o->s);
    const double len = vt_rows_length(m, d, flag);
    for (int a = 0; a < nv; a++) s[a] = vt_dof_turns(m, a) ? 1.0 / len : 1.0;
    {
        double *B = VT_SCRATCH(d, double, nv, "terms of a row");
        if (!B) return vt_scratch_fail(d, mark);
        for (int r = 0; r < nc; r++) {
            const double t = row_size(m, d, r, s, B);
            g[r] = t > 0.0 && isfinite(t) ? 1.0 / t : 1.0;
        }
        vt_scratch_release(d, mark);
    }
    double *P = VT_SCRATCH(d, double, (size_t)nc * (size_t)nv, "scaled Φ_q");
    int lw = 0;
    double *work = vt_scratch_rest(d, 5 * (size_t)(nc + nv), sizeof(double), &lw, "dgesvd workspace");
    if (!work) return vt_scratch_fail(d, mark);
    for (int r = 0; r < nc; r++) {
        for (int c = 0; c < nv; c++)
            P[r + (size_t)c * (size_t)nc] = flag[r] ? 0.0 : g[r] * d->Phiq[r + (size_t)c * (size_t)nc] * s[c];
    }
    /* LAPACK stops the program (xerbla) on some NaN inputs: refuse non-finite input first */
    if (!vt_all_finite(P, (size_t)nc * (size_t)nv) || !vt_all_finite(o->s, (size_t)nv) ||
        !vt_all_finite(d->Mstar, (size_t)nv * (size_t)nv))
        return vt_scratch_release(d, mark),
               vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in the scaled M* or Φ_q (overflow)");
    int info = 0;
    dgesvd_("A", "S", &nc, &nv, P, &nc, o->sig, o->U, &nc, o->VT, &k, work, &lw, &info, 1, 1);
    vt_scratch_release(d, mark);
    if (info != 0) return vt_fail(d->message, VT_ERR_LAPACK, "vt_solve: dgesvd info %d", info);
    const double smax = k > 0 ? o->sig[0] : 0.0, tol = (double)(nc > nv ? nc : nv) * DBL_EPSILON * smax;
    const double keep = fmax(tol, band * smax);
    o->rank = o->kept = 0;
    while (o->rank < k && o->sig[o->rank] > tol) o->rank++;
    while (o->kept < k && o->sig[o->kept] > keep) o->kept++;
    return 0;
}

/* The part of row r in the null space of Φ̂^T (the last nc − rank columns of U, orthonormal):
 * 0 for a row independent of the others, up to 1 */
double vt_null_part(const vt_model *m, const vt_rows_svd *o, int r)
{
    const int nc = m->nc;
    double p = 0.0;
    for (int j = o->rank; j < nc; j++) p += o->U[r + (size_t)j * (size_t)nc] * o->U[r + (size_t)j * (size_t)nc];
    return sqrt(p);
}

int vt_rows_rank(const vt_model *m, vt_data *d)
{
    if (m->nc == 0) return 0;
    const size_t mark = vt_scratch_mark(d);
    vt_rows_svd o;
    const int r = vt_rows_decide(m, d, 0.0, &o);
    vt_scratch_release(d, mark);
    return r < 0 ? r : o.rank;
}

/* dgelsd's integer workspace for an m x n problem, from its workspace query */
int vt_dgelsd_iwork(int m, int n)
{
    if (m < 1 || n < 1) return 1; /* nothing to solve (and LAPACK's xerbla would stop the program) */
    const int one = 1, ld = m > n ? m : n, lw = -1;
    int info = 0, iq = 0, rank = 0;
    double q = 0.0, dummy = 0.0, rc = -1.0;
    dgelsd_(&m, &n, &one, &dummy, &m, &dummy, &ld, &dummy, &rc, &rank, &q, &lw, &iq, &info);
    return info == 0 && iq > 0 ? iq : 1;
}

/* The scratch rank.c takes at once: vt_rows_decide's SVD, held by its caller (U, V^T, σ, the
 * row scaling, the mass metric, the rate scaling, the round-off rows), and while it runs a row's
 * terms, or the scaled Φ_q and dgesvd's workspace (by its own query); or vt_rows_grip's path
 * (maxpath ≤ nv ints: within a row's terms) */
size_t vt_rank_scratch(const vt_model *m)
{
    int nv = m->nv, nc = m->nc, k = nc < nv ? nc : nv;
    const size_t snv = (size_t)nv, snc = (size_t)nc, D = sizeof(double), I = sizeof(int);
    size_t lapack = 5 * (snc + snv);
    if (nc > 0) {
        int info = 0, lw = -1;
        double q = 0.0, dummy = 0.0;
        dgesvd_("A", "S", &nc, &nv, &dummy, &nc, &dummy, &dummy, &nc, &dummy, &k, &q, &lw, &info, 1, 1);
        if (info == 0 && q > (double)lapack) lapack = (size_t)q;
    }
    const size_t held = VT_SCRATCH_BYTES(snc * snc, D) + VT_SCRATCH_BYTES((size_t)k * snv, D) +
                        VT_SCRATCH_BYTES((size_t)k, D) + VT_SCRATCH_BYTES(snc, D) + 2 * VT_SCRATCH_BYTES(snv, D) +
                        VT_SCRATCH_BYTES(snc, I);
    const size_t svd = VT_SCRATCH_BYTES(snc * snv, D) + VT_SCRATCH_BYTES(lapack, D);
    const size_t terms = VT_SCRATCH_BYTES(snv, D);
    return held + (svd > terms ? svd : terms);
}
