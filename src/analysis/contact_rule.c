/* Contacts: the distribution rule at one instant, the ground's forces on a contact set carrying
 * the given motion of a robot standing on points of its bodies (docs/contact.md; the set:
 * analysis/contact.c).
 *
 * The instant's efforts without contact forces are τ⁰ = M*(q) q̈ − Q(q, q̇) (vt_inverse_dynamics_motion:
 * the given motion, eq (5) with q̈ known). A force f_c of the ground at a point p_c of body b adds
 * the generalized force J_cᵀ f_c, J_c's column a the velocity of p_c under rate a alone,
 *   J_c e_a = v_a + ω_a × (p_c − o)          (rate a's twist s_a = (ω_a, v_a) about o, eq (15)),
 * for the rates on b's path and 0 for the others; a point touching another moving body k (a
 * platform) rather than the ground takes J_c e_a less the same term on k's path (the velocity
 * relative to k: rates common to both paths cancel), −f_c acts on k at the same point, and the
 * normal and pyramid, given in k's axes, turn with it: n = A_k n', the rows A_k g'. So the
 * efforts with the contacts are
 *   τ = τ⁰ − Σ_c J_cᵀ f_c,
 * and a free joint's six rates (a floating root) are not actuated: τ_u = 0 on them, six linear
 * equations in the forces. Where more forces than equations remain (a quadruped on four feet),
 * the rule decides: the forces minimize
 *   ½ Σ_a∈A w_a τ_a² + ½ Σ_c w_c |f_c|²      (A: the actuated rates)
 *   = ½ fᵀ (J_Aᵀ W J_A + W_f) f − (J_Aᵀ W τ⁰_A)ᵀ f + const,
 * a strictly convex quadratic (W_f > 0), subject to
 *   J_uᵀ f = τ⁰_u                              (the unactuated rates),
 *   n_c · f_c ≥ 0,  μ_c cos(π/k) n_c · f_c − d_j · f_c ≥ 0, j = 0 … k−1   (a unilateral contact:
 *   it pushes, and its force stays in the pyramid of k faces inscribed in the friction cone, d_j
 *   = cos(2πj/k) t₁ + sin(2πj/k) t₂ the faces' outward directions in the tangent plane; the set
 *   forms these rows once, in the touched body's axes where the point touches one),
 * solved exactly: where no face binds, directly as the minimum under the equalities alone
 * (equality_minimum), else by the dual active-set method (numeric/qp.h). The forces are then applied as
 * loads (f_c at the centre of mass, (p_c − r_b) × f_c about it) by the instant's inward pass alone
 * (vt_motion_add_loads: a tree's; a model with cut joints or couplings is refused, its given
 * motion fixing the drives' rates only), so that
 * the efforts and every joint reaction of the data hold them (the unactuated rates' efforts
 * zero to round-off). No feasible forces: VT_ERR_CONTACT, the message naming the constraint the
 * solver could not meet — a contact that would have to pull, or slip, or unactuated rates the
 * active contacts cannot move.
 */
#include "analysis/contact_rule.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "base/lapack.h"
#include "base/status.h"
#include "base/vec3.h"
#include "numeric/qp.h"
#include "recursive/fused.h"

/* The active contacts' J_c, split by rows: the actuated rates' weighted, √W J_A into B (nact x
 * 3 na), the others' into Aeq (nu x 3 na): column 3k + e is component e of the velocity of
 * contact on[k]'s point under each rate of its body's path (0 off it) */
void vt_contacts_jacobian(const vt_model *m, const vt_data *d, vt_contacts *c, int na)
{
    const size_t n = 3 * (size_t)na, nact = (size_t)c->nact, nu = (size_t)c->nu;
    memset(c->B, 0, (nact ? nact : 1) * n * sizeof(double));
    memset(c->Aeq, 0, (nu ? nu : 1) * n * sizeof(double));
    for (int k = 0; k < na; k++) {
        const int h = c->on[k], b = c->body[h];
        double r[3], po[3];
        vt_mulmat3(r, d->A + 9 * b, c->point + 3 * h);
        for (int e = 0; e < 3; e++) po[e] = d->xrel[6 * b + e] + r[e]; /* p − o */
        /* +1 on b's path; −1 on the touched body's (the velocity relative to it) */
        for (int side = 0, bb = b; side < 2 && bb > 0; side++, bb = c->other[h]) {
            const double sg = side ? -1.0 : 1.0;
            for (int a = m->body_vadr[bb] + m->body_nv[bb] - 1; a >= 0; a = m->dof_parent[a]) {
                const double *tw = d->twist + 6 * a;
                double v[3];
                vt_cross3(v, tw, po);
                const int row = c->row_of[a];
                for (int e = 0; e < 3; e++) {
                    const size_t col = 3 * (size_t)k + (size_t)e;
                    if (row >= 0) c->B[col + (size_t)row * n] += sg * c->sw[row] * (tw[3 + e] + v[e]);
                    else c->Aeq[(size_t)(-1 - row) + col * nu] += sg * (tw[3 + e] + v[e]);
                }
            }
        }
    }
}

/* the QP of the header: G (its lower triangle), c, the equalities and the inequalities of the na
 * active contacts; returns the inequality rows */
static int distribution(const vt_data *d, vt_contacts *c, int na)
{
    const int n = 3 * na, nact = c->nact;
    /* G = (√W J_A)ᵀ (√W J_A) + W_f, c = −(√W J_A)ᵀ √W τ⁰_A */
    for (int h = 0; h < nact; h++) c->wtau[h] = c->sw[h] * c->tau0[c->act[h]];
    if (nact > 0) {
        vt_dsyrk('L', 'N', n, nact, 1.0, c->B, n, 0.0, c->G, n);
        vt_dgemv('N', n, nact, -1.0, c->B, n, c->wtau, 1, 0.0, c->c, 1);
    } else {
        for (int j = 0; j < n; j++)
            for (int i = j; i < n; i++) c->G[(size_t)i + (size_t)j * (size_t)n] = 0.0;
        memset(c->c, 0, (size_t)n * sizeof(double));
    }
    for (int i = 0; i < n; i++) c->G[(size_t)i * (size_t)(n + 1)] += c->weight[c->on[i / 3]];
    /* J_uᵀ f = τ⁰_u (Aeq filled with B) */
    for (int h = 0; h < c->nu; h++) c->beq[h] = c->tau0[c->unact[h]];
    /* the unilateral contacts' rows: n·f ≥ 0, then μ cos(π/k) n·f − d_j·f ≥ 0 */
    int rows = 0;
    for (int k = 0; k < na; k++) {
        const int h = c->on[k];
        if (c->kind[h] == VT_CONTACT_UNILATERAL) rows += 1 + c->faces[h];
    }
    memset(c->Ain, 0, (size_t)(rows ? rows : 1) * (size_t)n * sizeof(double));
    int r = 0;
    for (int k = 0; k < na; k++) {
        const int h = c->on[k];
        if (c->kind[h] != VT_CONTACT_UNILATERAL) continue;
        const double *cone = c->cone + 3 * c->cone_at[h], *Ak = c->other[h] ? d->A + 9 * c->other[h] : NULL;
        for (int j = -1; j < c->faces[h]; j++, r++, cone += 3) {
            double g[3]; /* the row in global axes: turned with the touched body */
            if (Ak) vt_mulmat3(g, Ak, cone);
            else vt_copy3(g, cone);
            for (int e = 0; e < 3; e++) c->Ain[(size_t)r + (size_t)(3 * k + e) * (size_t)rows] = g[e];
            c->rownorm[c->nu + r] = fabs(g[0]) + fabs(g[1]) + fabs(g[2]);
            c->bin[r] = 0.0;
            c->row_contact[r] = h;
            c->row_face[r] = j;
        }
    }
    return rows;
}
/* G f + c − A_eqᵀ λ_eq − A_inᵀ λ_in = 0 (G's lower triangle; rows 0: λ_in zero) to 1e-8 of its
 * terms, amax the constraints' largest entry */
static int stationary(vt_contacts *c, const double *Aeq, int n, int meq, int rows, double amax)
{
    const int ldeq = c->nu ? c->nu : 1, ldin = rows ? rows : 1;
    const double tol = 1e-8, xmax = vt_contacts_max_abs(c->f, n, 1);
    vt_dsymv('L', n, 1.0, c->G, n, c->f, 1, 0.0, c->res, 1);
    for (int i = 0; i < n; i++) c->res[i] += c->c[i];
    if (meq > 0) vt_dgemv('T', meq, n, -1.0, Aeq, ldeq, c->lambda, 1, 1.0, c->res, 1);
    if (rows > 0) vt_dgemv('T', rows, n, -1.0, c->Ain, ldin, c->lambda + meq, 1, 1.0, c->res, 1);
    double gmax = 0.0;
    for (int j = 0; j < n; j++) {
        const double g = vt_contacts_max_abs(c->G + (size_t)j * (size_t)(n + 1), n - j, 1);
        gmax = g > gmax ? g : gmax;
    }
    const double lmax = vt_contacts_max_abs(c->lambda, meq + rows, 1), cmax = vt_contacts_max_abs(c->c, n, 1);
    const double scale = (double)n * gmax * xmax + cmax + (double)(meq + rows) * amax * lmax;
    for (int i = 0; i < n; i++)
        if (!(fabs(c->res[i]) <= tol * scale + DBL_MIN)) return 0;
    return 1;
}

/* The QP's answer checked against its own optimality conditions (a certificate, whatever the
 * solver did): the equalities and inequalities hold, the inequalities' multipliers are ≥ 0, and
 * G f + c − A_eqᵀ λ_eq − A_inᵀ λ_in = 0, each to 1e-8 of the terms it is made of. A round-off
 * failure of the QP is then refused, never returned as forces. */
static int optimal(vt_contacts *c, const double *Aeq, int n, int meq, int rows)
{
    const int ldeq = c->nu ? c->nu : 1, ldin = rows ? rows : 1;
    const double tol = 1e-8, xmax = vt_contacts_max_abs(c->f, n, 1);
    double *s = c->slack; /* A f − b: the equalities' rows, then the inequalities' */
    memcpy(s, c->beq, (size_t)meq * sizeof(double));
    memcpy(s + meq, c->bin, (size_t)rows * sizeof(double));
    if (meq > 0) vt_dgemv('N', meq, n, 1.0, Aeq, ldeq, c->f, 1, -1.0, s, 1);
    if (rows > 0) vt_dgemv('N', rows, n, 1.0, c->Ain, ldin, c->f, 1, -1.0, s + meq, 1);
    double amax = 0.0;
    for (int r = 0; r < meq + rows; r++) { /* each constraint: its slack against its row's size */
        const double arow = r < meq ? vt_contacts_max_abs(Aeq + r, n, ldeq) : vt_contacts_max_abs(c->Ain + (r - meq), n, ldin);
        const double bv = r < meq ? c->beq[r] : c->bin[r - meq];
        const double size = tol * ((double)n * arow * xmax + fabs(bv)) + DBL_MIN;
        amax = arow > amax ? arow : amax;
        if (r < meq ? !(fabs(s[r]) <= size) : !(s[r] >= -size)) return 0;
        if (r >= meq && !(c->lambda[r] >= -tol * fabs(c->lambda[r]) - DBL_MIN)) return 0;
    }
    return stationary(c, Aeq, n, meq, rows, amax);
}

/* The common case, no face of a pyramid binding (feet well inside their cones, or bilateral
 * contacts): the minimum subject to the equalities alone, by the range-space solution of its KKT
 * system G f + c = A_eqᵀ λ, A_eq f = b with G = L Lᵀ (dpotf2),
 *   Z = A_eq L⁻ᵀ,   (Z Zᵀ) λ = b + Z L⁻¹ c   (Z Zᵀ = A_eq G⁻¹ A_eqᵀ = K Kᵀ, dpotf2),
 *   f = L⁻ᵀ (Zᵀ λ − L⁻¹ c),
 * is the QP's answer when it meets every inequality: with λ_in = 0 it meets the KKT conditions
 * of the whole problem, and a strictly convex problem has one minimizer. Returns 1 with c->f and
 * c->lambda set; 0 where the QP must decide: dependent equalities (two feet: Z Zᵀ singular, which
 * shows as a pivot of K below 1e-4 of the largest, an unpivoted Cholesky factor's pivots bounding
 * its eigenvalues), an inequality violated beyond its round-off (32 n ε of its terms, as the QP
 * judges), an equality missed by more than 1e-10 of its terms, or stationarity failing the
 * certificate's 1e-8. Nothing is iterated: the solution is exact but for round-off, as the QP's. */
static int equality_minimum(vt_contacts *c, int n, int rows)
{
    const int nu = c->nu;
    double *L = c->L, *Z = c->Ar, *K = c->U, *y = c->res, *lam = c->lambda;
    int info = 0;
    for (int j = 0; j < n; j++)
        memcpy(L + (size_t)j * (size_t)(n + 1), c->G + (size_t)j * (size_t)(n + 1), (size_t)(n - j) * sizeof(double));
    dpotf2_("L", &n, L, &n, &info, 1);
    if (info) return 0;
    memcpy(y, c->c, (size_t)n * sizeof(double));
    vt_dtrsv('L', 'N', 'N', n, L, n, y, 1); /* L⁻¹ c */
    memset(lam, 0, ((size_t)nu + (size_t)rows) * sizeof(double));
    if (nu > 0) {
        memcpy(Z, c->Aeq, (size_t)nu * (size_t)n * sizeof(double));
        vt_dtrsm('R', 'L', 'T', 'N', nu, n, 1.0, L, n, Z, nu);
        vt_dsyrk('L', 'N', nu, n, 1.0, Z, nu, 0.0, K, nu);
        dpotf2_("L", &nu, K, &nu, &info, 1);
        if (info) return 0;
        double kmin = HUGE_VAL, kmax = 0.0;
        for (int h = 0; h < nu; h++) {
            const double k = K[(size_t)h * (size_t)(nu + 1)];
            kmin = k < kmin ? k : kmin;
            kmax = k > kmax ? k : kmax;
        }
        if (!(kmin > 1e-4 * kmax)) return 0;
        memcpy(lam, c->beq, (size_t)nu * sizeof(double));
        vt_dgemv('N', nu, n, 1.0, Z, nu, y, 1, 1.0, lam, 1);
        vt_dtrsv('L', 'N', 'N', nu, K, nu, lam, 1);
        vt_dtrsv('L', 'T', 'N', nu, K, nu, lam, 1);
        memcpy(c->f, y, (size_t)n * sizeof(double));
        vt_dgemv('T', nu, n, 1.0, Z, nu, lam, 1, -1.0, c->f, 1); /* Zᵀ λ − L⁻¹ c */
    } else {
        for (int i = 0; i < n; i++) c->f[i] = -y[i];
    }
    vt_dtrsv('L', 'T', 'N', n, L, n, c->f, 1);
    /* as strict as the QP's own answer: every inequality to its round-off (32 n ε of its terms, a
     * face the minimum leaves by more is the QP's to bind) and every equality to 1e-10 of its
     * terms (a poorly conditioned Z Zᵀ costs digits the QP's factors keep); then the certificate */
    const double tau = 32.0 * (double)n * DBL_EPSILON, fm = vt_contacts_max_abs(c->f, n, 1);
    double *sl = c->slack;
    memcpy(sl, c->beq, (size_t)nu * sizeof(double));
    memcpy(sl + nu, c->bin, (size_t)rows * sizeof(double));
    if (nu > 0) vt_dgemv('N', nu, n, 1.0, c->Aeq, nu, c->f, 1, -1.0, sl, 1);
    if (rows > 0) vt_dgemv('N', rows, n, 1.0, c->Ain, rows, c->f, 1, -1.0, sl + nu, 1);
    double *a1 = c->rownorm; /* the equalities' rows' 1-norms, column by column (distribution: the faces') */
    memset(a1, 0, (size_t)nu * sizeof(double));
    for (int i = 0; i < n; i++)
        for (int h = 0; h < nu; h++) a1[h] += fabs(c->Aeq[(size_t)h + (size_t)i * (size_t)nu]);
    for (int r = 0; r < nu + rows; r++) {
        const double terms = a1[r] * fm + fabs(r < nu ? c->beq[r] : c->bin[r - nu]);
        if (r < nu ? !(fabs(sl[r]) <= 1e-10 * terms) : !(sl[r] >= -tau * terms - DBL_MIN)) return 0;
    }
    /* the equalities and inequalities hold, the inequalities' multipliers are zero: what is left
     * of the certificate (optimal) is stationarity */
    return stationary(c, c->Aeq, n, nu, 0, vt_contacts_max_abs(c->Aeq, nu * n, 1));
}

/* body b's load of the ground's force f at contact h's point: f at the centre of mass and
 * (p − r_b) × f about it, added into xfrc; where the point touches another body k, −f on k at
 * the same point, (p − r_k) × (−f) about k's centre, p − r_k = (p − o) − (r_k − o) */
void vt_contacts_add_load(const vt_data *d, const vt_contacts *c, int h, const double f[3], double *xfrc)
{
    const int b = c->body[h], k = c->other[h];
    double r[3], n[3];
    vt_mulmat3(r, d->A + 9 * b, c->point + 3 * h);
    vt_cross3(n, r, f);
    for (int e = 0; e < 3; e++) {
        xfrc[6 * b + e] += f[e];
        xfrc[6 * b + 3 + e] += n[e];
    }
    if (k == 0) return;
    for (int e = 0; e < 3; e++) r[e] += d->xrel[6 * b + e] - d->xrel[6 * k + e];
    vt_cross3(n, r, f);
    for (int e = 0; e < 3; e++) {
        xfrc[6 * k + e] -= f[e];
        xfrc[6 * k + 3 + e] -= n[e];
    }
}

/* The root's equations J_uᵀ f = τ⁰_u (A_eq f = b) hold for some f only if b lies in A_eq's range,
 * and their dependent combinations (two feet: the moment about the line through them) must not
 * reach the QP as equations, whose round-off it would take for a direction. By the SVD
 * A_eq = U Σ Vᵀ: the rows with σ_k > 64 (nu + n) ε σ₁ are independent, and Uᵣᵀ A_eq f = Uᵣᵀ b
 * (into c->Ar, c->beq: *meq rows) says what they say; the rest of b, U₀ᵀ b, is what no force gives:
 * beyond 1e-9 of |b| and of σ₁ |f| ~ |b| the motion cannot be carried (*culprit the rate most
 * in it, else −1). Returns a status only when LAPACK fails. */
static vt_status independent_rows(vt_data *d, vt_contacts *c, int n, int *meq, int *culprit)
{
    const int nu = c->nu;
    *meq = 0;
    *culprit = -1;
    if (nu == 0) return VT_OK;
    double *A = c->Ar; /* dgesvd overwrites its matrix: A_eq copied, then the reduced rows */
    memcpy(A, c->Aeq, (size_t)nu * (size_t)n * sizeof(double));
    const int k = nu < n ? nu : n;
    int info = 0, one = 1;
    double dummy = 0.0;
    dgesvd_("A", "N", &nu, &n, A, &nu, c->sig, c->U, &nu, &dummy, &one, c->svd_work, &c->svd_lwork, &info, 1, 1);
    if (info) return vt_fail(d->message, VT_ERR_LAPACK, "vt_inverse_dynamics_contacts: dgesvd info %d", info);
    const double tol = 64.0 * (double)(nu + n) * DBL_EPSILON * c->sig[0];
    int r = 0;
    while (r < k && c->sig[r] > tol) r++;
    double bb = 0.0, out = 0.0, worst = 0.0;
    for (int h = 0; h < nu; h++) bb += c->beq[h] * c->beq[h];
    for (int j = r; j < nu; j++) { /* b's part along the directions no force reaches */
        double u = 0.0;
        for (int h = 0; h < nu; h++) u += c->U[(size_t)h + (size_t)j * (size_t)nu] * c->beq[h];
        out += u * u;
        for (int h = 0; h < nu; h++)
            if (fabs(c->U[(size_t)h + (size_t)j * (size_t)nu] * u) > worst) {
                worst = fabs(c->U[(size_t)h + (size_t)j * (size_t)nu] * u);
                *culprit = h;
            }
    }
    if (!(sqrt(out) <= 1e-9 * sqrt(bb) + DBL_MIN)) return VT_OK; /* *culprit set: refused */
    *culprit = -1;
    /* the independent rows Uᵣᵀ A_eq (r x n, leading dimension nu) and right sides Uᵣᵀ b */
    double *ub = c->wtau; /* distribution's, done with */
    for (int j = 0; j < r; j++) {
        double u = 0.0;
        for (int h = 0; h < nu; h++) u += c->U[(size_t)h + (size_t)j * (size_t)nu] * c->beq[h];
        ub[j] = u;
    }
    vt_dgemm('T', 'N', r, n, nu, 1.0, c->U, nu, c->Aeq, nu, 0.0, A, nu);
    memcpy(c->beq, ub, (size_t)r * sizeof(double));
    *meq = r;
    return VT_OK;
}

/* the message of an infeasible distribution: what the culprit constraint asks */
static vt_status infeasible(const vt_model *m, vt_data *d, const vt_contacts *c, int culprit)
{
    if (culprit < c->nu) {
        const int a = c->unact[culprit < 0 ? 0 : culprit], b = m->dof_body[a];
        const char *joint = m->joint_name + (size_t)VT_NAME_MAX * (size_t)b;
        return vt_fail(d->message, VT_ERR_CONTACT,
                       "vt_inverse_dynamics_contacts: the active contacts cannot give the unactuated rate %d's "
                       "force %g (the free joint of body %d \"%.64s\"): no forces on the ground carry the motion",
                       a, c->tau0[a], b, joint[0] ? joint : m->body_name + (size_t)VT_NAME_MAX * (size_t)b);
    }
    const int r = culprit - c->nu, h = c->row_contact[r];
    const char *name = c->name + (size_t)VT_NAME_MAX * (size_t)h;
    if (c->row_face[r] < 0)
        return vt_fail(d->message, VT_ERR_CONTACT,
                       "vt_inverse_dynamics_contacts: contact %d \"%.64s\" (body %d) would have to pull on the ground",
                       h, name, c->body[h]);
    return vt_fail(d->message, VT_ERR_CONTACT,
                   "vt_inverse_dynamics_contacts: contact %d \"%.64s\" (body %d) would have to slip: its force "
                   "leaves the friction pyramid (mu %g, %d faces)",
                   h, name, c->body[h], c->mu[h], c->faces[h]);
}

/* The forces by the QP (where equality_minimum could not decide): the root's equations as they
 * are; where the QP finds them inconsistent or its answer fails the optimality conditions, again
 * by their independent rows (independent_rows). VT_OK with c->f, else the status and message. */
static vt_status by_qp(const vt_model *m, vt_data *d, vt_contacts *c, int n, int rows)
{
    vt_status st;
    int culprit = -1, meq = c->nu;
    const double *Aeq = c->Aeq;
    vt_qp_result qs = vt_qp_solve(n, c->G, n, c->c, meq, Aeq, c->nu ? c->nu : 1, c->beq, rows, c->Ain,
                                  rows ? rows : 1, c->bin, c->f, c->lambda, NULL, &culprit, c->qp, c->qp_bytes, NULL);
    if ((qs == VT_QP_INFEASIBLE && culprit < c->nu) || (qs == VT_QP_OPTIMAL && !optimal(c, Aeq, n, meq, rows))) {
        if ((st = independent_rows(d, c, n, &meq, &culprit))) return st;
        if (culprit >= 0) return infeasible(m, d, c, culprit);
        Aeq = c->Ar;
        qs = vt_qp_solve(n, c->G, n, c->c, meq, Aeq, c->nu ? c->nu : 1, c->beq, rows, c->Ain, rows ? rows : 1, c->bin,
                         c->f, c->lambda, NULL, &culprit, c->qp, c->qp_bytes, NULL);
        if (qs == VT_QP_OPTIMAL && !optimal(c, Aeq, n, meq, rows))
            return vt_fail(d->message, VT_ERR_SINGULAR,
                           "vt_inverse_dynamics_contacts: the distribution's answer does not meet its optimality "
                           "conditions to round-off (an ill-conditioned problem: contacts whose forces cancel, "
                           "weights far apart); no forces returned");
    }
    if (qs == VT_QP_INFEASIBLE && culprit < meq) culprit = 0; /* an equality: the root's wrench */
    else if (qs == VT_QP_INFEASIBLE) culprit += c->nu - meq;   /* an inequality, as infeasible() counts */
    if (qs == VT_QP_INFEASIBLE) return infeasible(m, d, c, culprit);
    if (qs != VT_QP_OPTIMAL)
        return vt_fail(d->message, qs == VT_QP_NONFINITE ? VT_ERR_NONFINITE : VT_ERR_SINGULAR,
                       "vt_inverse_dynamics_contacts: the distribution's problem could not be solved (%s)",
                       vt_qp_result_string(qs));
    return VT_OK;
}

vt_status vt_inverse_dynamics_contacts(const vt_model *m, vt_data *d, vt_contacts *c, const int *active, double *force)
{
    return vt_contacts_inverse(m, d, c, active, force, NULL);
}

vt_status vt_contacts_inverse(const vt_model *m, vt_data *d, vt_contacts *c, const int *active, double *force,
                              const vt_frame_loads *loads)
{
    vt_status st = vt_check_pair(m, d, "vt_inverse_dynamics_contacts");
    if (st) return st;
    if (!c) return vt_fail(d->message, VT_ERR_NULL, "vt_inverse_dynamics_contacts: contacts is NULL");
    if (c->model != m)
        return vt_fail(d->message, VT_ERR_MODEL_MISMATCH,
                       "vt_inverse_dynamics_contacts: contacts made for another model");
    /* loads at frames in the instant: part of what the ground's forces balance */
    if ((st = vt_motion_loaded(m, d, loads))) return st;
    const size_t nv = (size_t)m->nv, nxf = 6 * ((size_t)m->nbody + 1);
    memcpy(c->tau0, d->qfrc_drive, nv * sizeof(double));
    int na = 0;
    for (int k = 0; k < c->n; k++)
        if (!active || active[k]) c->on[na++] = k;
    memset(c->xfrc, 0, nxf * sizeof(double)); /* the loads (none in the air), vt_contacts_loads's */
    if (na == 0) { /* no contact on the ground: in free flight the unactuated rates need nothing */
        double big = 0.0, scale = 0.0;
        int worst = 0;
        for (int h = 0; h < c->nu; h++)
            if (fabs(c->tau0[c->unact[h]]) > big) {
                big = fabs(c->tau0[c->unact[h]]);
                worst = h;
            }
        for (int a = 0; a < m->nv; a++) scale = fmax(scale, fabs(c->tau0[a]));
        if (big > 64.0 * DBL_EPSILON * (1.0 + scale)) return infeasible(m, d, c, worst);
        if (force) memset(force, 0, 3 * (size_t)c->n * sizeof(double));
        return VT_OK;
    }
    const int n = 3 * na;
    vt_contacts_jacobian(m, d, c, na);
    const int rows = distribution(d, c, na);
    /* the equality-constrained minimum where no face binds, else the QP */
    if (!equality_minimum(c, n, rows) && (st = by_qp(m, d, c, n, rows))) return st;
    /* the forces applied as loads by the instant's inward pass alone (it is linear in the loads) */
    for (int k = 0; k < na; k++) vt_contacts_add_load(d, c, c->on[k], c->f + 3 * k, c->xfrc);
    if ((st = vt_motion_add_loads(m, d, c->xfrc))) return st;
    if (force) {
        memset(force, 0, 3 * (size_t)c->n * sizeof(double));
        for (int k = 0; k < na; k++) vt_copy3(force + 3 * c->on[k], c->f + 3 * k);
    }
    return VT_OK;
}
