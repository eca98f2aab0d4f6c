/* The augmented system of the paper's (5):
 *
 *   [ M*   Φ_q^T ] [  q̈ ]   [ Q ]
 *   [ Φ_q  0     ] [ −λ ] = [ γ ]                                        (5)
 *
 * so that M* q̈ = Q + Φ_q^T λ (2) and Φ_q q̈ = γ.
 *
 * Why this factorization: the matrix is symmetric and indefinite (a saddle point: M* is
 * positive definite on the motions the constraints allow, the zero block makes it
 * indefinite), so Cholesky does not apply and LU would ignore the symmetry. LAPACK's
 * LDL^T with bounded Bunch–Kaufman (rook) pivoting (dsytrf_rk / dsytrs_3 / dsycon_3) uses the
 * symmetry (half LU's work and storage), its 1x1/2x2 pivots are stable for indefinite matrices,
 * and the rook variant bounds the entries of L (and its BLAS-3 solves are cheaper than
 * dsytrs/dsycon's BLAS-2 loops at these sizes).
 * Before factorizing, the matrix is scaled symmetrically (its rows and columns mix units:
 * kg·m², kg, m, rad); how, is said where it is done. Every route reports a condition estimate
 * of the pose (docs/method.md, "The condition estimate"): independent of units, of the scene's
 * frame and of inertia spread alone, the same number on the recursive path's routes. Round-off
 * of an exact zero is neither a row nor an inertia (vt_roundoff_check). A system whose
 * estimate falls below rcond_min is refused: rows of Φ_q that are dependent to round-off (the
 * SVD of a frame- and unit-independent scaling of Φ_q, vt_rows_decide) are named
 * (VT_ERR_DEPENDENT_CONSTRAINTS); otherwise the matrix is singular (a rate or body without
 * inertia that nothing fixes, named; an exactly zero pivot) or only ill-conditioned, and
 * VT_ERR_SINGULAR's message says which. Two other paths, each said where it is done: as many
 * rows as rates (LU of Φ_q alone, vt_square_solve) and, for models that allow redundant rows,
 * (5) on the independent directions of the rows by SVD (vt_redundant_solve).
 * Here: which route solves (vt_solve_band, the dispatcher), what a refusal is diagnosed as, the
 * maximal route's turn, and the public vt_solve. The routes are dense/routes.c; the round-off
 * judgements numeric/roundoff.c, the scalings and the rank decision numeric/rank.c, the small
 * dense kernels and the square route's LU numeric/kkt.c, the diagnostics every route ends with
 * numeric/route.c: the recursive path calls those without this file.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "dense/solve.h"
#include "base/arena.h"
#include "base/scan.h"
#include "base/status.h"
#include "model/model.h"
#include "numeric/maximal.h"
#include "numeric/skeel.h"
#include "numeric/rank.h"
#include "numeric/roundoff.h"
#include "numeric/route.h"
#include "dense/routes.h"

static const char *owner_name(const vt_model *m, int row, char *buf, size_t n)
{
    const int kind = vt_row_owner_kind(m, row);
    if (kind == VT_OWNER_DRIVE) snprintf(buf, n, "drive %d", m->con_owner[row]);
    else if (kind == VT_OWNER_CUT) snprintf(buf, n, "cut joint %d", m->con_owner[row]);
    else if (kind == VT_OWNER_COUPLING) snprintf(buf, n, "coupling %d", m->con_owner[row]);
    else snprintf(buf, n, "p^T p = 1 of body %d", m->con_owner[row]);
    return buf;
}

/* A rate that no constraint row touches (its column of Φ_q zero: no drive, cut joint or coupling) */
static int untouched(const vt_model *m, const vt_data *d, int a)
{
    for (int r = 0; r < m->nc; r++)
        if (d->Phiq[r + (size_t)a * (size_t)m->nc] != 0.0) return 0;
    return 1;
}

/* What makes a solve singular by having nothing to move, written into buf (n bytes) as
 * " rate 2 (body 1) has no inertia; body 3, body 5: no mass or inertia beyond a joint that no
 * row touches",
 * empty if none: a rate that no row touches and whose M*_aa is exactly 0 (moving it alone costs
 * no kinetic energy), and a body with such a rate whose subtree carries neither mass nor
 * inertia. */
static void massless(const vt_model *m, vt_data *d, char *buf, size_t n)
{
    buf[0] = '\0';
    size_t len = 0;
    int count = 0;
    for (int a = 0; a < m->nv && len + 48 < n; a++)
        if (d->Mstar[a + (size_t)a * (size_t)m->nv] == 0.0 && untouched(m, d, a))
            len += (size_t)snprintf(buf + len, n - len, "%s rate %d (body %d)", count++ ? "," : "", a, m->dof_body[a]);
    if (count) len += (size_t)snprintf(buf + len, n - len, " %s no inertia", count > 1 ? "have" : "has");
    const int rates = count;
    const size_t nb = (size_t)m->nbody + 1, mark = vt_scratch_mark(d);
    double *w = VT_SCRATCH(d, double, nb, "subtree inertia");
    if (!w) {
        vt_scratch_release(d, mark);
        return;
    }
    w[0] = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        const double *J = m->body_inertia + 9 * i;
        w[i] = m->body_mass[i] + fabs(J[0]) + fabs(J[4]) + fabs(J[8]);
    }
    vt_subtree_sum(m, w, 1);
    count = 0;
    for (int i = 1; i <= m->nbody && len + 48 < n; i++) {
        int free_rate = 0;
        for (int k = 0; k < m->body_nv[i]; k++) free_rate |= untouched(m, d, m->body_vadr[i] + k);
        if (w[i] != 0.0 || !free_rate) continue;
        len += (size_t)snprintf(buf + len, n - len, "%s body %d", count++ ? "," : rates ? ";" : "", i);
    }
    if (count) snprintf(buf + len, n - len, ": no mass or inertia beyond a joint that no row touches");
    vt_scratch_release(d, mark);
}

/* VT_ERR_SINGULAR with what was found: rates or bodies without inertia (named), an exactly zero
 * pivot (rcond 0), or neither: a matrix that is only ill-conditioned, its reciprocal condition
 * below rcond_min (with Φ_q's rank and smallest scaled singular value when rows were checked:
 * vt_rows_decide's, o NULL without rows). what: the matrix the route factorized. */
static vt_status singular(const vt_model *m, vt_data *d, const char *what, double rcond, const vt_rows_svd *o)
{
    char who[160], rows[96] = "";
    massless(m, d, who, sizeof who);
    if (o && o->k > 0)
        snprintf(rows, sizeof rows, "; Φ_q has full rank %d, its smallest scaled singular value %.3g of the largest",
                 o->rank, o->sig[0] > 0.0 ? o->sig[o->k - 1] / o->sig[0] : 0.0);
    if (who[0])
        return vt_fail(d->message, VT_ERR_SINGULAR, "vt_solve: singular:%s (reciprocal condition %.3g of the %s)", who,
                       rcond, what);
    if (rcond == 0.0)
        return vt_fail(d->message, VT_ERR_SINGULAR,
                       "vt_solve: singular: an exactly zero pivot of the %s: the drives and cut joints leave a motion "
                       "free that has no inertia%s", what, rows);
    return vt_fail(d->message, VT_ERR_SINGULAR,
                   "vt_solve: ill-conditioned: the %s has reciprocal condition %.3g, below rcond_min %.3g (no zero "
                   "pivot, no rate without inertia%s): a pose near a singular one, or a model beyond the precision "
                   "rcond_min asks for", what, rcond, m->rcond_min, rows);
}

/* A free-rate route's answer whose estimate is below rcond_warn, or below √rcond_warn with a
 * joint drive's multiplier that is the difference of terms 1/rcond_warn times its size: over a
 * spread of inertia M* and Q can have lost what the problem keeps (a tiny driven link carrying a
 * huge free body; docs/accuracy.md, "Mass ratios"). q̈ loses up to ε / rcond, which the
 * warning covers; a joint drive's effort λ_r = (M* q̈ − Q − Φ_q,oᵀ λ_o)_c (rate c) also loses ε
 * times its cancellation, g_r / |λ_r| with g_r = |Q_c| + Σ_j |M*_cj q̈_j| + Σ_o |Φ_q,oc λ_o|,
 * which grows as 1 / rcond² there and stays near 1 / rcond otherwise. The maximal-coordinate route
 * (maximal.c) keeps each body's equations at its own size; where the dense stages have formed
 * S and Φ_x it solves too, and its answer is kept where its estimate is the higher. Only after a
 * route that solved (r = VT_SOLVED): a refusal (dependent rows, a motion without inertia) stands. sol:
 * [q̈; λ], or [q̈; −λ] (neg). */
static int maximal_wanted(const vt_model *m, const vt_data *d, vt_outcome r, double rcond, const double *sol, int neg)
{
    if (r != VT_SOLVED || !vt_maximal_wanted(m, rcond)) return 0;
    if (rcond < m->rcond_warn) return 1;
    const int nv = m->nv, nc = m->nc;
    const double *lam = sol + nv, sg = neg ? -1.0 : 1.0;
    for (int q = 0; q < nc; q++) {
        if (!vt_known_row(m, q)) continue;
        const int c = m->con_dof[q];
        double g = fabs(d->Q[c]);
        for (int j = 0; j < nv; j++) g += fabs(d->Mstar[c + (size_t)j * (size_t)nv] * sol[j]);
        for (int o = 0; o < nc; o++)
            if (o != q) g += fabs(d->Phiq[o + (size_t)c * (size_t)nc] * lam[o]);
        if (!(g * m->rcond_warn < fabs(sg * lam[q]))) return 1; /* g / |λ| ≥ 1 / rcond_warn */
    }
    return 0;
}

/* The maximal route's [q̈; λ] into sol and its estimate into *rcond where it is the higher:
 * returns 1 then, 0 where the answer in sol stays, or a negative vt_status. Its estimate is the
 * answer's condition (maximal.c) bounded by the rows' own: (σ_min / σ_max)² of Φ̂ = G Φ_q C
 * (vt_rows_decide: no masses), times the grip g². The answer's condition alone, relative to the
 * answer, does not see rows that lose their independence (their multipliers grow with the
 * answer); the rows' condition does, whatever the inertias. */
static int maximal_alternative(const vt_model *m, vt_data *d, double *rcond, double *sol)
{
    const size_t n = (size_t)m->nv + (size_t)m->nc, mark = vt_scratch_mark(d);
    double rho = 1.0;
    if (m->nc > 0) {
        vt_rows_svd o;
        const int r = vt_rows_decide(m, d, 0.0, &o);
        if (r < 0) return vt_scratch_release(d, mark), r;
        const double ratio = o.sig[0] > 0.0 ? o.sig[o.k - 1] / o.sig[0] : 0.0;
        rho = o.rank < m->nc ? 0.0 : ratio * ratio;
        vt_scratch_release(d, mark);
    }
    if (!(rho > *rcond)) return 0; /* cannot be the higher */
    double *alt = VT_SCRATCH(d, double, n, "maximal route's solution");
    if (!alt) return vt_scratch_fail(d, mark);
    double rc = 0.0;
    const int r = vt_maximal_solve(m, d, alt, &rc);
    double grip = 1.0;
    const int rg = r == 0 ? vt_rows_grip(m, d, &grip) : 0;
    if (rg < 0) return vt_scratch_release(d, mark), rg;
    if (r == 0) rc = fmin(rc, rho) * grip;
    const int take = r == 0 && rc >= m->rcond_min && rc > *rcond;
    if (take) {
        memcpy(sol, alt, n * sizeof(double));
        *rcond = rc;
        d->fallback |= VT_FALLBACK_MAXIMAL_CONDITION;
    }
    vt_scratch_release(d, mark);
    return r < 0 ? r : take;
}

/* Over a spread of masses (vt_answer_size: VT_SPREAD_ESTIMATE between the heaviest and the
 * lightest body), an answer with free rates takes the smaller of its route's estimate and the
 * reciprocal of its componentwise condition on (5) (skeel.c): M* and Q hold their entries to ε
 * of their size, and what the answer loses by that the routes' estimates, in the mass metric,
 * do not see. Sets *spread where it is the smaller. sol: [q̈; λ], or [q̈; −λ] (neg). */
static int spread_estimate(const vt_model *m, vt_data *d, const double *sol, int neg, double *rcond, int *spread)
{
    if (!vt_answer_size(m)) return 0;
    double rc = 1.0;
    const int st = vt_answer_condition(m, d, sol, neg, &rc);
    if (st < 0) return st;
    if (rc < *rcond) *rcond = rc, *spread = 1;
    return 0;
}

/* The routes, cheapest first (the model's rows decide; vt_data.route records the one taken):
 *   FREE_RATES  every row a joint drive on a rate of its own (vt_free_rates_solve)
 *   REDUNDANT   allow_redundant, and vt_rows_decide drops a direction: dependent to round-off, or
 *               within a time analysis's band (vt_redundant_solve)
 *   SQUARE      as many rows as rates (vt_square_solve); ill-conditioned: diagnosed, no fallback
 *   SCHUR       fewer rows than rates (vt_schur_solve); a small pivot of M̃ gives way to
 *   AUGMENTED   the whole augmented matrix (vt_augmented_solve, also every other case), flagged
 *               VT_FALLBACK_SCHUR_PIVOT; with an estimate below rcond_warn the augmented route
 *               solves too and the answer of the higher estimate is kept (the augmented one:
 *               VT_FALLBACK_SCHUR_CONDITION)
 *   MAXIMAL     after FREE_RATES, SCHUR or AUGMENTED solved with an answer in doubt
 *               (maximal_wanted): the bodies' equations unreduced (maximal.c), kept where its
 *               estimate is the higher (VT_FALLBACK_MAXIMAL_CONDITION)
 * d->rcond is the pose's condition estimate (docs/method.md, "The condition estimate"): the free
 * rates' leaf-first pivot ratio (FREE_RATES); G Φ_q C's, squared (SQUARE); the same pivot ratio
 * over the rates no joint drive fixes times the other rows' unit-diagonal Schur complement's and
 * the point drives' grip² (SCHUR); the
 * scaled augmented matrix's times the grip² (AUGMENTED); the kept rows' matrix's singular value
 * ratio or (σ_kept / σ_max)² of Φ̂, the smaller (REDUNDANT); the answer's componentwise condition
 * bounded by Φ̂'s squared, times the grip² (MAXIMAL, maximal_alternative). Round-off of an exact zero taken for a row or an inertia is caught first
 * (vt_roundoff_check). Below rcond_min the rows' rank (vt_rows_decide)
 * tells dependent rows (VT_ERR_DEPENDENT_CONSTRAINTS, named) from a singular or ill-conditioned
 * matrix (VT_ERR_SINGULAR, saying which). Every solve starts from cleared diagnostics
 * (vt_solve_reset): on failure q̈ and λ are left as they were, the route is VT_ROUTE_NONE, the
 * warning 0, rcond what the route measured (0 if nothing) and rank what was found (0 if nothing). */
vt_status vt_solve_band(const vt_model *m, vt_data *d, double band, vt_form form, vt_handoff *to)
{
    const int nv = m->nv, nc = m->nc;
    vt_solve_reset(d);
    if (to) *to = VT_HANDOFF_NONE;
    if (!vt_all_finite(d->Q, nv) || !vt_all_finite(d->gamma, nc))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_solve: NaN or Inf in Q or γ");
    /* round-off of an exact zero is neither a row nor an inertia: a rate without inertia that
     * nothing fixes is refused here, zero rows are dependent (vt_rows_decide below says so) */
    const int zero_rows = vt_roundoff_check(m, d, NULL, 1, form);
    if (zero_rows == VT_ROUNDOFF_COMPOSITE) { /* only VT_FORM_TWISTS, whose callers pass to */
        *to = VT_HANDOFF_DENSE;
        return VT_OK;
    }
    if (zero_rows < 0) return (vt_status)zero_rows;
    double rcond = 0.0;
    vt_outcome r = VT_BELOW_MIN;
    vt_status st = VT_OK;
    if (m->joint_rows_only) {
        if ((st = vt_free_rates_solve(m, d, &rcond, &r))) return st;
        d->rank = nc; /* one unit row on a rate of its own each: independent */
        vt_route route = VT_ROUTE_FREE_RATES;
        int spread = 0;
        if (r == VT_SOLVED && (vt_answer_size(m) || (form == VT_FORM_DENSE && vt_maximal_wanted(m, rcond)))) {
            const size_t mark = vt_scratch_mark(d);
            double *sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution");
            if (!sol) return vt_scratch_fail(d, mark);
            memcpy(sol, d->qdd, (size_t)nv * sizeof(double));
            memcpy(sol + nv, d->lambda, (size_t)nc * sizeof(double));
            int t = spread_estimate(m, d, sol, 0, &rcond, &spread);
            if (t == 0 && form == VT_FORM_DENSE && maximal_wanted(m, d, r, rcond, sol, 0))
                t = maximal_alternative(m, d, &rcond, sol);
            if (t < 0) return vt_scratch_release(d, mark), (vt_status)t;
            if (t == 1) {
                memcpy(d->qdd, sol, (size_t)nv * sizeof(double));
                memcpy(d->lambda, sol + nv, (size_t)nc * sizeof(double));
                route = VT_ROUTE_MAXIMAL;
            }
            vt_scratch_release(d, mark);
            if (route == VT_ROUTE_FREE_RATES && spread && rcond < m->rcond_min) r = VT_BELOW_MIN;
        }
        if (r == VT_BELOW_MIN)
            return d->rcond = rcond, singular(m, d, spread ? "system (5) at its answer, componentwise," : "free rates' scaled M*",
                                              rcond, NULL);
        vt_solved(m, d, route, rcond);
        return VT_OK;
    }
    const size_t mark = vt_scratch_mark(d);
    double *sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution");
    if (!sol) return vt_scratch_fail(d, mark);
    vt_rows_svd o;
    if (m->allow_redundant && nc > 0) {
        /* rows first: exactly dependent rows would make every other route fail */
        const int rd = vt_rows_decide(m, d, band, &o);
        if (rd < 0) return vt_scratch_release(d, mark), (vt_status)rd;
        if (o.kept < nc) {
            st = vt_redundant_solve(m, d, &o);
            if (!st) d->route = VT_ROUTE_REDUNDANT;
            vt_scratch_release(d, mark);
            return st;
        }
        vt_scratch_release(d, mark);
        sol = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "solution"); /* the same place again */
    }
    const int square = nc == nv && nc > 0;
    vt_route route = square ? VT_ROUTE_SQUARE : nc > 0 && nc < nv ? VT_ROUTE_SCHUR : VT_ROUTE_AUGMENTED;
    /* sol holds [q̈; λ], or [q̈; −λ] on the augmented route (vt_augmented_solve) */
    switch (zero_rows ? VT_ROUTE_NONE : route) {
    case VT_ROUTE_NONE: r = VT_BELOW_MIN; break; /* a zero row: nothing solved, diagnosed below */
    case VT_ROUTE_SQUARE: st = vt_square_solve(m, d, sol, &rcond, &r); break;
    case VT_ROUTE_SCHUR: {
        /* joint-driven rates known (as the recursive articulated route takes them), unless a
         * row is dependent on their drives by its kind (vt_rates_known) or is round-off of zero
         * on the other rates: the whole system's rank then names it */
        int known = vt_rates_known(m);
        if (known) {
            const int zf = vt_zero_rows_free(m, d, m->dof_drive);
            if (zf < 0) return vt_scratch_release(d, mark), (vt_status)zf;
            known = zf == 0;
        }
        st = vt_schur_solve(m, d, known, sol, &rcond, &r);
        break;
    }
    default: r = VT_TO_AUGMENTED; break; /* no cheaper route: the whole augmented matrix */
    }
    if (st) return vt_scratch_release(d, mark), st;
    switch (r) {
    case VT_SCHUR_BELOW_MIN:
    case VT_SCHUR_BELOW_WARN: {
        /* the Schur route's estimate below rcond_warn (solved) or rcond_min (not): the rows'
         * Schur complement in the mass metric can lose digits that the whole matrix keeps (a chain
         * whose masses rise by 1e3 a rod: 7e-13 against 2e-3; docs/accuracy.md, "Mass ratios").
         * The augmented route solves too, and the answer whose estimate is the higher is kept */
        double *alt = VT_SCRATCH(d, double, (size_t)nv + (size_t)nc, "augmented route's solution");
        if (!alt) return vt_scratch_fail(d, mark);
        double rc = 0.0;
        vt_outcome ra = VT_BELOW_MIN;
        if ((st = vt_augmented_solve(m, d, alt, &rc, &ra))) return vt_scratch_release(d, mark), st;
        if (ra == VT_SOLVED && rc > rcond) {
            memcpy(sol, alt, ((size_t)nv + (size_t)nc) * sizeof(double));
            d->fallback |= VT_FALLBACK_SCHUR_CONDITION;
            route = VT_ROUTE_AUGMENTED;
            rcond = rc;
            r = VT_SOLVED;
        } else if (r == VT_SCHUR_BELOW_WARN) r = VT_SOLVED; /* the Schur route's answer, and its estimate */
        else { /* neither above rcond_min: the higher one is diagnosed */
            if (rc > rcond) route = VT_ROUTE_AUGMENTED, rcond = rc, d->fallback |= VT_FALLBACK_SCHUR_CONDITION;
            r = VT_BELOW_MIN;
        }
        break;
    }
    case VT_PIVOT_GAVE_WAY: /* M* (nearly) singular on rates only the rows may fix: M̃ alone cannot */
        d->fallback |= VT_FALLBACK_SCHUR_PIVOT;
        /* fall through */
    case VT_TO_AUGMENTED:
        route = VT_ROUTE_AUGMENTED;
        if ((st = vt_augmented_solve(m, d, sol, &rcond, &r))) return vt_scratch_release(d, mark), st;
        break;
    case VT_SOLVED:
    case VT_BELOW_MIN: /* the square route's below rcond_min stands: the motion is the rows' alone */
        break;
    }
    /* r is VT_SOLVED or VT_BELOW_MIN here */
    int spread = 0;
    if (r == VT_SOLVED && route != VT_ROUTE_SQUARE) {
        const int t = spread_estimate(m, d, sol, route == VT_ROUTE_AUGMENTED, &rcond, &spread);
        if (t < 0) return vt_scratch_release(d, mark), (vt_status)t;
    }
    if (form == VT_FORM_DENSE && !zero_rows && route != VT_ROUTE_SQUARE && maximal_wanted(m, d, r, rcond, sol, route == VT_ROUTE_AUGMENTED)) {
        const int t = maximal_alternative(m, d, &rcond, sol);
        if (t < 0) return vt_scratch_release(d, mark), (vt_status)t;
        if (t == 1) route = VT_ROUTE_MAXIMAL, r = VT_SOLVED;
    }
    if (route != VT_ROUTE_MAXIMAL && spread && rcond < m->rcond_min) r = VT_BELOW_MIN;
    if (r == VT_BELOW_MIN) {
        /* below rcond_min: dependent rows, or a singular or ill-conditioned matrix */
        d->rcond = rcond;
        const char *what = route != VT_ROUTE_MAXIMAL && spread ? "system (5) at its answer, componentwise,"
                         : route == VT_ROUTE_SQUARE ? "scaled Φ_q (squared)"
                         : route == VT_ROUTE_SCHUR  ? "Schur complement of the scaled (5)"
                                                    : "scaled augmented matrix of (5)";
        if (nc == 0) st = singular(m, d, what, rcond, NULL);
        else if ((st = (vt_status)vt_rows_decide(m, d, 0.0, &o)) == VT_OK) {
            d->rank = o.rank;
            if (o.rank == nc) st = singular(m, d, what, rcond, &o);
            else { /* only without allow_redundant: with it, vt_rows_decide above took them */
                int len = snprintf(d->message, sizeof d->message,
                                   "vt_solve: Φ_q has rank %d of %d rows (reciprocal condition %.3g of the %s); "
                                   "dependent:", o.rank, nc, rcond, what);
                for (int k = 0; k < nc && len < (int)sizeof d->message - 40; k++) {
                    if (!(vt_null_part(m, &o, k) > VT_NULL_PART_TOL)) continue;
                    char name[64];
                    len += snprintf(d->message + len, sizeof d->message - (size_t)len, " row %d (%s)", k,
                                    owner_name(m, k, name, sizeof name));
                }
                st = VT_ERR_DEPENDENT_CONSTRAINTS;
            }
        }
        vt_scratch_release(d, mark);
        return st;
    }
    vt_solved(m, d, route, rcond);
    memcpy(d->qdd, sol, (size_t)nv * sizeof(double));
    for (int k = 0; k < nc; k++) d->lambda[k] = route == VT_ROUTE_AUGMENTED ? -sol[nv + k] : sol[nv + k];
    vt_scratch_release(d, mark);
    return VT_OK;
}

vt_status vt_solve_impl(const vt_model *m, vt_data *d, vt_handoff *to)
{
    return vt_solve_band(m, d, 0.0, VT_FORM_TWISTS, to);
}

vt_status vt_solve(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_solve");
    if (st) return st;
    d->fallback = 0;
    return vt_solve_band(m, d, 0.0, VT_FORM_DENSE, NULL);
}

vt_status vt_solve_run(const vt_model *m, vt_data *d, double band)
{
    vt_status st = vt_check_dense(m, d, "vt_solve");
    if (st) return st;
    d->fallback = 0;
    return vt_solve_band(m, d, band, VT_FORM_DENSE, NULL);
}

/* The scratch solve.c takes at once, beside what its routes and kernels take (dense/routes.c,
 * numeric/: each file's own bound, summed by analysis/data.c): the solution, the augmented
 * route's beside the Schur route's, the maximal route's, and massless()'s subtree inertias */
size_t vt_solve_scratch(const vt_model *m)
{
    const size_t sN = (size_t)m->nv + (size_t)m->nc, D = sizeof(double);
    return 3 * VT_SCRATCH_BYTES(sN, D) + VT_SCRATCH_BYTES((size_t)m->nbody + 1, D) + vt_answer_scratch(m) +
           8 * VT_DATA_ALIGN;
}
