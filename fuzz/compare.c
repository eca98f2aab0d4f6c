/* fuzz_model's differential comparison (fuzz_model.c runs the routes): the tolerances of two
 * routes of one instant from both results' scales, the comparisons of q̈, efforts, reactions and
 * totals within them, and which pairs of statuses are consistent. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "compare.h"
#include "harness.h"

/* ---- the differential comparison ---------------------------------------------------------
 * Two routes of the same instant differ by round-off: each forms M*, Q, Φ_q and γ as sums of
 * terms (masses times accelerations, forces times lever arms about the global origin), so each
 * carries errors of about ε × the largest term, and the solve multiplies them by the condition
 * of the mass-scaled system, κ = 1/rcond (the reported one; the smaller of the two routes').
 * So every tolerance is e = C × (nv + nc + 1) × ε × κ times a scale of the largest terms, from
 * both results:
 * - forces Fs: the largest body term m (|a| + |g|), |xfrc|, |qfrc| and the joints' own effects,
 *   reaction or drive force;
 * - moments Ns: |qfrc| and the joints' own effects, Fs × L (L the largest position or joint
 *   offset: the routes take moments about
 *   different points), the largest inertia term |J| (|ω|² + |α|), moment, and m |c|² (|q̈| +
 *   |q̇|²) (the recursive route's spatial inertias about the origin hold m |c|²: far from the
 *   origin its round-off grows with the distance squared);
 * - generalized forces and efforts Gs = Fs + Ns;
 * - q̈ in the mass metric (rate a scaled by sqrt(M*_aa), the scaling whose condition rcond is):
 *   |Δq̈_a| sqrt(M*_aa) ≤ dq = e (max_b |q̈_b| sqrt(M*_bb) + max_b Gs/sqrt(M*_bb));
 * - what q̈'s error does to the loads, through ‖Δq̈‖_M* ≤ nv dq (M* positive semi-definite:
 *   |M*_ab| ≤ sqrt(M*_aa M*_bb)): a body's m |Δa| ≤ sqrt(m) ‖Δq̈‖_M*, so forces get
 *   nbody sqrt(m_max) nv dq more, moments nbody (2 L sqrt(m_max) + sqrt(|J|_max)) nv dq, the
 *   generalized forces sqrt(max M*_aa) nv dq.
 * C = 1e3: on the seed corpus (known bugs' inputs aside) the largest difference was a small
 * fraction of these tolerances (FUZZ_STATS=1 prints the ratio; docs/testing.md gives it); a
 * route that is wrong is off by O(1) of the scale, orders of magnitude above. Rates without
 * inertia (M*_aa = 0) compare q̈ in plain units, e × max |q̈|. */
#define C_TOL 1e3

static void data_scales(const vt_model *m, const vt_data *d, scales *s)
{
    const int n1 = m->nbody + 1;
    const double g = sqrt(m->gravity[0] * m->gravity[0] + m->gravity[1] * m->gravity[1] + m->gravity[2] * m->gravity[2]);
    const double qdd = maxabs(d->qdd, m->nv), qd = maxabs(d->qd, m->nv);
    for (int i = 1; i <= m->nbody; i++) {
        const double *x = d->x + 7 * (i - 1), *xdd = d->xdd + 7 * (i - 1), *xd = d->xd + 7 * (i - 1);
        s->L = fmax(s->L, fmax(maxabs(x, 3), maxabs(d->jpoint + 3 * i, 3)));
        s->L = fmax(s->L, fmax(maxabs(m->body_jpar + 3 * i, 3), maxabs(m->body_jchild + 3 * i, 3)));
        s->mmax = fmax(s->mmax, m->body_mass[i]);
        s->Jmax = fmax(s->Jmax, maxabs(m->body_inertia + 9 * i, 9));
        s->Fs = fmax(s->Fs, m->body_mass[i] * (maxabs(xdd, 3) + g));
        const double w = maxabs(d->omega + 3 * i, 3), pd = maxabs(xd + 3, 4), pdd = maxabs(xdd + 3, 4);
        s->Ns = fmax(s->Ns, maxabs(m->body_inertia + 9 * i, 9) * (w * w + 4.0 * (pdd + pd * pd) + 4.0 * w * pd));
        const double c = maxabs(x, 3);
        s->Ns = fmax(s->Ns, m->body_mass[i] * c * c * (qdd + qd * qd));
        /* ẍ is summed from terms α × s and ω × (ω × s) along the lever arms: m (|α| + |ω|²), times
         * the lengths in pair_scales (centres on a common axis turning at α = 5.8e14 rad/s²: a of
         * 1e-15 m/s² exactly, each route's round-off 1.3 m/s²) */
        s->mA = fmax(s->mA, m->body_mass[i] * (maxabs(d->alpha + 3 * i, 3) + w * w));
    }
    for (int k = 0; k < m->ndrive; k++) s->L = fmax(s->L, maxabs(m->drive[k].point, 3));
    for (int k = 0; k < m->ncut; k++) s->L = fmax(s->L, fmax(maxabs(m->cut[k].point_a, 3), maxabs(m->cut[k].point_b, 3)));
    s->Fs = fmax(s->Fs, fmax(maxabs(d->jnt_force, 3 * n1), maxabs(d->drive_force, 3 * m->ndrive)));
    s->Fs = fmax(s->Fs, fmax(maxabs(d->cut_force, 3 * m->ncut), maxabs(d->qfrc, m->nv)));
    for (int i = 0; i < n1; i++) {
        s->Fs = fmax(s->Fs, maxabs(d->xfrc + 6 * i, 3));
        s->Ns = fmax(s->Ns, maxabs(d->xfrc + 6 * i + 3, 3));
    }
    s->Ns = fmax(s->Ns, fmax(maxabs(d->jnt_moment, 3 * n1), maxabs(d->drive_moment, 3 * m->ndrive)));
    s->Ns = fmax(s->Ns, maxabs(d->cut_moment, 3 * m->ncut));
    /* a rate's generalized forces, the applied qfrc and its joint's own effects (armature q̈,
     * damping q̇, friction), are a force or a moment along it: both scales (armature 0.05 kg·m²
     * at q̈ = −2e201 against qfrc −1e200 leaves a moment's round-off of the 1e200's, not of the
     * 5 N·m the loads alone would say) */
    for (int c = 0; c < m->nv; c++) {
        const double *e = m->dof_effects + 4 * c;
        const double gq = fabs(d->qfrc[c]) + e[0] * fabs(d->qdd[c]) + e[1] * fabs(d->qd[c]) + e[2];
        s->Fs = fmax(s->Fs, gq);
        s->Ns = fmax(s->Ns, gq);
    }
    s->Gs = fmax(s->Gs, fmax(maxabs(d->qfrc_drive, m->nv), maxabs(d->drive_effort, m->ndrive)));
    s->Gs = fmax(s->Gs, maxabs(d->coupling_effort, m->ncoupling));
}

/* the tolerances of comparing a and b; ref is a dense result (its M*), rcond the condition */
scales pair_scales(const vt_model *m, const vt_data *ref, const vt_data *a, const vt_data *b, double rcond)
{
    scales s;
    memset(&s, 0, sizeof s);
    data_scales(m, a, &s);
    data_scales(m, b, &s);
    /* below DBL_MIN a number is known only to DBL_TRUE_MIN (ε DBL_MIN / 2) absolute, not to ε of
     * itself: the scales of forces and of q̈ are floored there (a subnormal gravity's torque of
     * 7e-211 N·m over 1e100 m on M*_aa = 1e199: the true q̈ of 7e-410 rounds to 0, and the motion
     * given as 0 needs that torque back) */
    s.Fs = fmax(fmax(s.Fs, s.mA * s.L), DBL_MIN);
    s.Ns += s.Fs * s.L;
    s.Gs = fmax(s.Gs, s.Fs + s.Ns);
    s.kappa = 1.0 / fmin(rcond, 1.0);
    s.e = C_TOL * (m->nv + m->nc + 1) * DBL_EPSILON * s.kappa;
    double qs = 0.0, gs = 0.0, mdmax = 0.0;
    int massless = 0;
    for (int c = 0; c < m->nv; c++) {
        const double mc = ref->Mstar[(size_t)c + (size_t)c * (size_t)m->nv];
        mdmax = fmax(mdmax, mc);
        if (!(mc > 0.0)) massless = 1;
        else {
            qs = fmax(qs, fmax(fmax(fabs(a->qdd[c]), fabs(b->qdd[c])), DBL_MIN) * sqrt(mc));
            gs = fmax(gs, s.Gs / sqrt(mc));
        }
    }
    s.tq = s.e * fmax(fmax(maxabs(a->qdd, m->nv), maxabs(b->qdd, m->nv)), DBL_MIN);
    /* a rate without inertia: the dense routes scale it by 1 (solve.c, scaling_diag: a unit
     * inertia, 1 kg or 1 kg·m²), so their solution [ỹ; μ] holds its q̈ as it is, and the SVD's and
     * LDL^T's error, relative to that whole solution, reaches the multipliers as e |q̈_a| × that
     * unit: the loads' floor where every load is round-off of zero (a massless body held by two
     * identical drives: recursive 0 N·m, dense SVD 2e-31) */
    if (massless) {
        for (int c = 0; c < m->nv; c++)
            if (!(ref->Mstar[(size_t)c + (size_t)c * (size_t)m->nv] > 0.0))
                qs = fmax(qs, fmax(fabs(a->qdd[c]), fabs(b->qdd[c])));
        gs = fmax(gs, s.Gs);
        mdmax = fmax(mdmax, 1.0);
        s.mmax = fmax(s.mmax, 1.0);
        s.Jmax = fmax(s.Jmax, 1.0);
    }
    /* the rates with inertia in the mass metric whether or not others have none (a point mass's
     * turning rates, fixed by rows): their q̈ carries the loads' round-off, Gs / sqrt(M*_aa),
     * as anywhere (a rate turning at 1e9 rad/s: 1e18 N centripetal terms) */
    s.dq = s.e * (qs + gs);
    const double norm = m->nv * fmax(s.dq, massless ? s.tq * sqrt(mdmax) : 0.0), nb = m->nbody;
    s.tf = s.e * s.Fs + nb * sqrt(s.mmax) * norm;
    s.tn = s.e * s.Ns + nb * (2.0 * s.L * sqrt(s.mmax) + sqrt(s.Jmax)) * norm;
    s.tg = s.e * s.Gs + sqrt(mdmax) * norm;
    /* the multipliers: the dense routes solve for the scaled μ_r = λ_r g_r, g_r = ‖(Φ_q D)_r‖ (D
     * the mass metric, a rate without inertia by 1), with an error up to dq (the scaled solution's
     * size, as q̈'s); so λ_r is known to dq / g_r, which is far above e Fs where a row's lever arm
     * is short against the moments' terms (a point drive's line 0.0625 m from its axis, moments of
     * 1e14 N·m: λ 2.4e5 N to 0.125 N). Forces built from λ get it, moments it times the lengths */
    double gmin = HUGE_VAL;
    for (int r = 0; r < m->nc; r++) {
        double g2 = 0.0;
        for (int c = 0; c < m->nv; c++) {
            const double mc = ref->Mstar[(size_t)c + (size_t)c * (size_t)m->nv], v = ref->Phiq[r + (size_t)c * (size_t)m->nc];
            g2 += v * v / (mc > 0.0 ? mc : 1.0);
        }
        if (g2 > 0.0) gmin = fmin(gmin, sqrt(g2));
    }
    if (gmin < HUGE_VAL) {
        const double tl = s.dq / gmin;
        s.tf = fmax(s.tf, tl);
        s.tn = fmax(s.tn, 2.0 * s.L * tl);
    }
    /* and a row's own round-off: a point, orientation or cut row's entries are lever arms and
     * direction cosines formed from the tree's lengths, each known to ε × those lengths (Lm: the
     * tree's offsets and the rows' points; not the distance from the origin, which the rows no
     * longer carry), so a short row ‖Φ_q,r‖ ≪ Lm (a driven point 1e-9 m from its axis: 4.5e-10)
     * is known only to ε Lm / ‖Φ_q,r‖ relative, and its λ_r = (M* q̈ − Q)_a / Φ_q,ra with it
     * (5.4e11 N to 1.7e5 N, the efforts to 1e-13). Joint-drive and coupling rows are exact. */
    double Lm = 1.0 + m->bound_length, lrel = 0.0;
    for (int k = 0; k < m->ndrive; k++) Lm += maxabs(m->drive[k].point, 3);
    for (int k = 0; k < m->ncut; k++) Lm += maxabs(m->cut[k].point_a, 3) + maxabs(m->cut[k].point_b, 3);
    for (int r = 0; r < m->nc; r++) {
        int exact = 0;
        for (int k = 0; k < m->ndrive; k++) exact |= m->drive[k].type == VT_DRIVE_JOINT && m->drive_row[k] == r;
        for (int k = 0; k < m->ncoupling; k++) exact |= m->coupling_row[k] == r;
        if (exact) continue;
        double g2 = 0.0;
        for (int c = 0; c < m->nv; c++) g2 += ref->Phiq[r + (size_t)c * (size_t)m->nc] * ref->Phiq[r + (size_t)c * (size_t)m->nc];
        if (g2 > 0.0) lrel = fmax(lrel, Lm / sqrt(g2) * fmax(fabs(a->lambda[r]), fabs(b->lambda[r])));
    }
    if (isfinite(lrel) && lrel > 0.0) {
        const double tr = s.e * lrel;
        s.tf = fmax(s.tf, tr);
        s.tn = fmax(s.tn, 2.0 * s.L * tr);
        s.tg = fmax(s.tg, tr);
    }
    return s;
}

double perturb, worst_ratio;

void agree(const char *pair, const char *what, const double *a, const double *b, int n, double tol,
           const scales *s)
{
    for (int k = 0; k < n; k++) {
        const double diff = fabs(a[k] - b[k]);
        if (tol > 0.0 && diff / tol > worst_ratio) worst_ratio = diff / tol;
        if (!(diff <= tol))
            fail("%s disagree on %s[%d]: %.17g vs %.17g, |difference| %.3g > tolerance %.3g "
                 "(1/rcond %.3g, force scale %.3g N, moment scale %.3g N·m, length %.3g m)",
                 pair, what, k, a[k], b[k], diff, tol, s->kappa, s->Fs, s->Ns, s->L);
    }
}

/* q̈ in the mass metric (see above); rates without inertia in plain units */
void agree_qdd(const char *pair, const vt_model *m, const vt_data *ref, const double *a, const double *b,
               const scales *s)
{
    for (int c = 0; c < m->nv; c++) {
        const double mc = ref->Mstar[(size_t)c + (size_t)c * (size_t)m->nv];
        const double tol = mc > 0.0 && s->dq > 0.0 ? s->dq / sqrt(mc) : s->tq;
        if (isfinite(tol)) agree(pair, "qdd", a + c, b + c, 1, tol, s);
    }
}

/* efforts and reactions; reactions only where both say they are unique */
void agree_loads(const char *pair, const vt_model *m, const vt_data *a, const vt_data *b, const scales *s,
                 int drives, int reactions)
{
    const int n1 = m->nbody + 1;
    const double tg = s->tg, tf = s->tf, tn = s->tn;
    if (!isfinite(tg) || !isfinite(tn) || !isfinite(tf)) return; /* scales at overflow's edge: nothing to compare to */
    agree(pair, "qfrc_drive", a->qfrc_drive, b->qfrc_drive, m->nv, tg, s);
    if (drives) {
        /* a point drive's effort is its force λ, an orientation drive's a moment: their
         * tolerances as drive_force's and drive_moment's below (a driven point 1e-9 m off its
         * axis: λ = τ / 5.8e-10 m, the moments' round-off over that lever arm, 1e-6 N where the
         * exact effort is 0) */
        for (int k = 0; k < m->ndrive; k++) {
            const vt_drive_type ty = m->drive[k].type;
            const double te = ty == VT_DRIVE_JOINT ? tg : fmax(ty == VT_DRIVE_POINT ? tf : tn, tg);
            agree(pair, "drive_effort", a->drive_effort + k, b->drive_effort + k, 1, te, s);
        }
        /* a drive's force and moment are its effort times its unit axis: the effort's tolerance
         * (a point drive's λ = τ_a / Φ_q,ra carries the moments' round-off over the row's lever
         * arm: 0.0625 m under moments of 1e14 N·m, 0.125 N of 2.4e5 N) */
        agree(pair, "drive_force", a->drive_force, b->drive_force, 3 * m->ndrive, fmax(tf, tg), s);
        agree(pair, "drive_moment", a->drive_moment, b->drive_moment, 3 * m->ndrive, fmax(tn, tg), s);
        agree(pair, "coupling_effort", a->coupling_effort, b->coupling_effort, m->ncoupling, tg, s);
    }
    if (!reactions) return;
    for (int i = 1; i < n1; i++)
        for (int c = 0; c < 3; c++) {
            const int k = 3 * i + c;
            if (a->jnt_unique[6 * i + c] && b->jnt_unique[6 * i + c]) {
                agree(pair, "jnt_force", a->jnt_force + k, b->jnt_force + k, 1, tf, s);
                agree(pair, "jnt_force_body", a->jnt_force_body + k, b->jnt_force_body + k, 1, tf, s);
            }
            if (a->jnt_unique[6 * i + 3 + c] && b->jnt_unique[6 * i + 3 + c]) {
                agree(pair, "jnt_moment", a->jnt_moment + k, b->jnt_moment + k, 1, tn, s);
                agree(pair, "jnt_moment_body", a->jnt_moment_body + k, b->jnt_moment_body + k, 1, tn, s);
            }
        }
    for (int j = 0; j < m->ncut; j++)
        for (int c = 0; c < 3; c++) {
            const int k = 3 * j + c;
            if (a->cut_unique[6 * j + c] && b->cut_unique[6 * j + c]) {
                agree(pair, "cut_force", a->cut_force + k, b->cut_force + k, 1, tf, s);
                agree(pair, "cut_force_body", a->cut_force_body + k, b->cut_force_body + k, 1, tf, s);
            }
            if (a->cut_unique[6 * j + 3 + c] && b->cut_unique[6 * j + 3 + c]) {
                agree(pair, "cut_moment", a->cut_moment + k, b->cut_moment + k, 1, tn, s);
                agree(pair, "cut_moment_body", a->cut_moment_body + k, b->cut_moment_body + k, 1, tn, s);
            }
        }
}

/* α and the joints' totals, derived from q̈ and the same loads as the reactions. α = Σ (rate's
 * angular twist, |·| ≤ 2: unit axes, or 2 E with |p| = 1) q̈ + velocity products: q̈'s error
 * (each rate's tolerance, agree_qdd's) times 2 nv, plus round-off e (|α| + (|ω| + |q̇|)²). The
 * totals with the reactions' tolerances, where every reaction is unique (with redundant rows the
 * cut joints' share, and so the subtree's outside loads, is not). */
void agree_totals(const char *pair, const vt_model *m, const vt_data *ref, const vt_data *a, const vt_data *b,
                  const scales *s)
{
    const int n1 = m->nbody + 1;
    double tq = 0.0;
    for (int c = 0; c < m->nv; c++) {
        const double mc = ref->Mstar[(size_t)c + (size_t)c * (size_t)m->nv];
        tq = fmax(tq, mc > 0.0 && s->dq > 0.0 ? s->dq / sqrt(mc) : s->tq);
    }
    const double w = fmax(maxabs(a->omega, 3 * n1), maxabs(b->omega, 3 * n1));
    const double v = fmax(maxabs(a->qd, m->nv), maxabs(b->qd, m->nv)) + w;
    const double ta = 2.0 * m->nv * tq + s->e * (fmax(maxabs(a->alpha, 3 * n1), maxabs(b->alpha, 3 * n1)) + v * v);
    if (isfinite(ta)) agree(pair, "alpha", a->alpha, b->alpha, 3 * n1, ta, s);
    if (!isfinite(s->tf) || !isfinite(s->tn)) return;
    for (int k = 0; k < 6 * n1; k++)
        if (!a->jnt_unique[k] || !b->jnt_unique[k]) return;
    for (int k = 0; k < 6 * m->ncut; k++)
        if (!a->cut_unique[k] || !b->cut_unique[k]) return;
    agree(pair, "jnt_force_total", a->jnt_force_total, b->jnt_force_total, 3 * n1, s->tf, s);
    agree(pair, "jnt_force_total_body", a->jnt_force_total_body, b->jnt_force_total_body, 3 * n1, s->tf, s);
    agree(pair, "jnt_moment_total", a->jnt_moment_total, b->jnt_moment_total, 3 * n1, s->tn, s);
    agree(pair, "jnt_moment_total_body", a->jnt_moment_total_body, b->jnt_moment_total_body, 3 * n1, s->tn, s);
}

/* The largest magnitude among the inputs of an instant: the model's masses, inertias, offsets,
 * the state, the loads. From about 1e75 on, a product of four of them (m r² ω²) overflows: the
 * edge of overflow, where one route may overflow in an intermediate and the other not. */
double input_magnitude(const vt_model *m, const vt_data *d)
{
    double s = maxabs(m->body_mass, m->nbody + 1);
    s = fmax(s, maxabs(m->body_inertia, 9 * (m->nbody + 1)));
    s = fmax(s, fmax(maxabs(m->body_jpar, 3 * (m->nbody + 1)), maxabs(m->body_jchild, 3 * (m->nbody + 1))));
    s = fmax(s, fmax(maxabs(d->q, m->nq), maxabs(d->qd, m->nv)));
    s = fmax(s, fmax(maxabs(d->xfrc, 6 * (m->nbody + 1)), maxabs(d->qfrc, m->nv)));
    s = fmax(s, fmax(maxabs(m->gravity, 3), fabs(d->time)));
    for (int k = 0; k < m->ndrive; k++) {
        s = fmax(s, maxabs(m->drive[k].point, 3));
        double f[3];
        if (vt_function_eval(f, &m->drive[k].f, d->time) == VT_OK) s = fmax(s, maxabs(f, 3));
        if (m->drive[k].f.type != VT_FUNCTION_CALLBACK && m->drive[k].f.type != VT_FUNCTION_SPLINE)
            s = fmax(s, maxabs(m->drive[k].f.c, VT_POLY_MAX));
    }
    for (int k = 0; k < m->ncut; k++) s = fmax(s, fmax(maxabs(m->cut[k].point_a, 3), maxabs(m->cut[k].point_b, 3)));
    return s;
}
#define EDGE_OUTPUT 1e280

static int singularish(vt_status st)
{
    return st == VT_ERR_SINGULAR || st == VT_ERR_DEPENDENT_CONSTRAINTS;
}

/* Statuses of two routes of one instant. Both OK: compared by the caller. One refuses as
 * singular or dependent and the other succeeds: only near the threshold, the successful one's
 * rcond below NEAR × rcond_min (the routes measure the condition of different matrices: the
 * articulated route's estimate is a product of the pivots' ratio and the rows' condition, and
 * can sit orders of magnitude from the augmented matrix's). One NONFINITE and the other OK with
 * finite outputs: only at overflow's edge (inputs ≥ EDGE_INPUT, or the OK route's scales times
 * its 1/rcond ≥ EDGE_OUTPUT); at that edge a singular refusal too (an M* that overflowed). Both
 * fail: singular, dependent and NONFINITE may swap, and a failing user function (CALLBACK) may
 * stand beside any refusal (the routes meet the two in different orders); any other pair of
 * different statuses is a disagreement. Returns 1 when both are OK. */
#define NEAR 1e6

/* The refusals of round-off of lever arms from the reference point o, which the routes meet
 * differently: vt_solve zeroes an M* row whose diagonal is round-off of its terms about o and
 * refuses when the rates it zeroed leave no certain digit ("no certain digit", reactions.c),
 * which the recursive articulated, square and joint-driven routes never do (they zero nothing).
 * Such a refusal against VT_OK is a refusal of what a route cannot trust, not a disagreement
 * (test_long_link_roundoff_inertia). (Where the recursive general route's composite inertias
 * about o leave M* less precise than its condition needs, it hands the instant to the dense
 * stages: test_roundoff_hides_singular; the articulated route, about each body's joint point,
 * keeps long chains: test_long_chain.) */
int beyond_lever_arms(const vt_data *d)
{
    return strstr(d->message, "no certain digit") != NULL;
}

int consistent(const char *pair, const vt_model *m, vt_status sa, const vt_data *a, vt_status sb,
               const vt_data *b, double in_mag)
{
    if (sa == VT_OK && sb == VT_OK) return 1;
    if (sa != VT_OK && sb != VT_OK) {
        /* a failing user function may be reached before or after another refusal, by route */
        const int ok = sa == sb || ((singularish(sa) || sa == VT_ERR_NONFINITE) && (singularish(sb) || sb == VT_ERR_NONFINITE)) ||
                       sa == VT_ERR_CALLBACK || sb == VT_ERR_CALLBACK;
        if (!ok)
            fail("%s: statuses %s (%s) and %s (%s)", pair, vt_status_string(sa), a->message, vt_status_string(sb),
                 b->message);
        return 0;
    }
    const vt_status se = sa ? sa : sb;
    const vt_data *ok = sa ? b : a, *bad = sa ? a : b;
    if (singularish(se) && ok->rcond <= NEAR * m->rcond_min) return 0;
    if (se == VT_ERR_SINGULAR && beyond_lever_arms(bad)) return 0;
    if (in_mag >= EDGE_INPUT && singularish(se)) return 0; /* an overflowed M* may look singular */
    if (se == VT_ERR_NONFINITE) {
        const scales s = pair_scales(m, ok, ok, ok, ok->rcond);
        if (in_mag >= EDGE_INPUT || !(s.Gs * s.kappa < EDGE_OUTPUT) || !(s.Ns * s.kappa < EDGE_OUTPUT)) return 0;
    }
    if (m->allow_redundant && singularish(se)) return 0; /* rank decisions of the redundant route: near by definition */
    fail("%s: one route %s (%s), the other VT_OK (rcond %.3g, rcond_min %.3g, input magnitude %.3g)", pair,
         vt_status_string(se), bad->message, ok->rcond, m->rcond_min, in_mag);
    return 0;
}

/* Whether q̈ is a motion the rows allow: a redundant solve whose dependent rows' γ disagree holds
 * them only in the least-squares sense, to d->residual = max |Φ_q q̈ − γ|; beyond the round-off e
 * of the rows' terms (|γ_r| + Σ_a |Φ_q,ra q̈_a|), that q̈, given to vt_inverse_dynamics_motion, poses
 * another problem (its joint-driven rates held at values their drives do not ask for), whose
 * answer has nothing to agree with (a 1.3e154 kg body weighs its rows to nothing in the mass
 * metric: the corpus input fuzz/corpus/crash-c4b3cebe…) */
int rows_hold(const vt_model *m, const vt_data *d, double e)
{
    if (!(d->residual > 0.0)) return 1;
    double scale = 0.0;
    for (int r = 0; r < m->nc; r++) {
        double t = fabs(d->gamma[r]);
        for (int a = 0; a < m->nv; a++) t += fabs(d->Phiq[r + (size_t)a * (size_t)m->nc] * d->qdd[a]);
        scale = fmax(scale, t);
    }
    return d->residual <= e * scale;
}
