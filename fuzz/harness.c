/* fuzz_model's reading of its bytes and its reports (fuzz_model.c holds what the bytes become
 * and the comparisons' order): the bytes as small integers and numbers (num: mostly ordinary
 * ones, sometimes the awkward ones), a broken promise reported with the model and the two results
 * being compared (fail: the reason, then abort, which libFuzzer keeps as crash-*; FUZZ_EXCLUDE
 * skips known reasons), and the checks every call's outputs and failures must pass (finite
 * outputs after VT_OK; a failed call's message and untouched inputs; the model the builder
 * accepted). */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"

unsigned byte(bytes *b)
{
    if (b->n == 0) return 0;
    b->n--;
    return *b->p++;
}

fuzz_context context;

static void print_vec(const char *what, const double *a, int n)
{
    fprintf(stderr, "  %s:", what);
    for (int k = 0; k < n && k < 42; k++) fprintf(stderr, " %.6g", a[k]);
    fputc('\n', stderr);
}

void describe(void)
{
    const vt_model *m = context.m;
    if (!m) return;
    fprintf(stderr, "  model: %d bodies, nq %d, nv %d, nc %d, %d drives, %d cut joints, allow_redundant %d, rcond_min %g\n",
            m->nbody, m->nq, m->nv, m->nc, m->ndrive, m->ncut, m->allow_redundant, m->rcond_min);
    for (int k = 0; k < m->ncoupling; k++)
        fprintf(stderr, "  coupling %d: q of body %d = %g q of body %d + %g\n", k, m->coupling[k].body_a,
                m->coupling[k].ratio, m->coupling[k].body_b, m->coupling[k].offset);
    for (int i = 1; i <= m->nbody; i++)
    {
        const double *J = m->body_inertia + 9 * i;
        fprintf(stderr, "  body %d: parent %d, joint %d, mass %g, inertia %g %g %g / %g %g %g / %g %g %g, axis1 %g %g %g\n",
                i, m->body_parent[i], m->body_joint[i], m->body_mass[i], J[0], J[3], J[6], J[1], J[4], J[7], J[2], J[5],
                J[8], m->body_axis[6 * i], m->body_axis[6 * i + 1], m->body_axis[6 * i + 2]);
    }
    for (int i = 1; i <= m->nbody; i++)
        fprintf(stderr, "  body %d: joint_parent %.17g %.17g %.17g, joint_child %.17g %.17g %.17g\n", i,
                m->body_jpar[3 * i], m->body_jpar[3 * i + 1], m->body_jpar[3 * i + 2], m->body_jchild[3 * i],
                m->body_jchild[3 * i + 1], m->body_jchild[3 * i + 2]);
    fprintf(stderr, "  gravity %g %g %g\n", m->gravity[0], m->gravity[1], m->gravity[2]);
    for (int k = 0; k < m->ndrive; k++)
        fprintf(stderr, "  drive %d: type %d, body %d, index %d, function %d, point %g %g %g, axis %g %g %g, reference %d, sequence %s\n", k,
                m->drive[k].type, m->drive[k].body, m->drive[k].index, m->drive[k].f.type, m->drive[k].point[0],
                m->drive[k].point[1], m->drive[k].point[2], m->drive[k].axis[0], m->drive[k].axis[1], m->drive[k].axis[2],
                m->drive[k].reference, m->drive[k].sequence ? m->drive[k].sequence : "none");
    for (int k = 0; k < m->ncut; k++)
        fprintf(stderr, "  cut joint %d: joint %d, bodies %d %d, planar %d\n", k, m->cut[k].joint, m->cut[k].body_a,
                m->cut[k].body_b, m->cut[k].planar);
    const vt_data *both[2] = {context.a, context.b};
    for (int k = 0; k < 2; k++) {
        const vt_data *d = both[k];
        if (!d) continue;
        fprintf(stderr, " result %c: route %d, fallback %d, rcond %.6g, rank %d, residual %.6g, warning %d, time %g\n",
                'a' + k, d->route, d->fallback, d->rcond, d->rank, d->residual, d->warning, d->time);
        print_vec("q", d->q, m->nq);
        print_vec("qd", d->qd, m->nv);
        print_vec("qdd", d->qdd, m->nv);
        print_vec("x", d->x, m->nx);
        print_vec("qfrc_drive", d->qfrc_drive, m->nv);
        print_vec("origin", d->origin, 3);
        print_vec("xfrc", d->xfrc, 6 * (m->nbody + 1));
        print_vec("qfrc", d->qfrc, m->nv);
        print_vec("jnt_force", d->jnt_force, 3 * (m->nbody + 1));
        print_vec("jnt_moment", d->jnt_moment, 3 * (m->nbody + 1));
        print_vec("Phiq", d->Phiq, m->nc * m->nv);
        print_vec("gamma", d->gamma, m->nc);
        print_vec("Q", d->Q, m->nv);
        print_vec("lambda", d->lambda, m->nc);
        fprintf(stderr, "  Mstar diagonal:");
        for (int c = 0; c < m->nv; c++) fprintf(stderr, " %.6g", d->Mstar[c + c * m->nv]);
        fputc('\n', stderr);
    }
}

/* FUZZ_EXCLUDE="text;text;...": a broken promise whose reason contains one of the texts skips
 * the rest of the input instead of aborting (known bugs set aside while looking for others;
 * run with -detect_leaks=0: the skipped input's memory is not freed) */
jmp_buf skip_input;
int excluded(const char *reason)
{
    const char *list = getenv("FUZZ_EXCLUDE");
    if (!list || !*list) return 0;
    char item[256];
    while (*list) {
        size_t n = strcspn(list, ";");
        if (n > 0 && n < sizeof item) {
            memcpy(item, list, n);
            item[n] = '\0';
            if (strstr(reason, item)) return 1;
        }
        list += n + (list[n] == ';');
    }
    return 0;
}

void fail(const char *fmt, ...)
{
    char reason[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    if (excluded(reason)) longjmp(skip_input, 1);
    fprintf(stderr, "\nfuzz_model: %s\n", reason);
    describe();
    abort();
}

/* Numbers: mostly ordinary ones ((v − 120)/16, −7.5..7.44), sometimes the awkward ones. Three
 * escapes read more bytes: 245 a huge magnitude ±1e150..1e308 (sqrt(DBL_MAX) = 1.34e154: from
 * there a square overflows, from 1e154 a sum of two squares does) or DBL_MAX; 246 a tiny one
 * ±1e-150..1e-324 or a subnormal; 247 eight raw bytes, an IEEE double (little-endian: the
 * dictionary fuzz/model.dict holds the edges of overflow and underflow in this form). */
double num(bytes *b)
{
    static const double special[16] = {0.0, 1.0, -1.0, 1e-9, 1e9, 0.0, 0.0, 0.0,
                                       (double)NAN, (double)INFINITY, -(double)INFINITY, 0.5, 2.0, 1e-6, 1e6, -0.0};
    const unsigned v = byte(b);
    if (v < 240) return ((double)v - 120.0) / 16.0;
    if (v == 245 || v == 246) {
        const unsigned k = byte(b);
        const double sign = k & 128 ? -1.0 : 1.0;
        const unsigned e = k & 63;
        if (v == 245) return k & 64 ? sign * (e < 32 ? DBL_MAX : 1.0e154 + (double)(e - 32) * 1e152)
                                    : sign * pow(10.0, 150.0 + 158.0 * (double)e / 63.0);
        return k & 64 ? sign * ldexp(1.0 + (double)(e & 7) / 8.0, -1074 + 8 * (int)(e >> 3))
                      : sign * pow(10.0, -150.0 - 174.0 * (double)e / 63.0);
    }
    if (v == 247) {
        uint8_t raw[8];
        for (int k = 0; k < 8; k++) raw[k] = (uint8_t)byte(b);
        uint64_t u = 0;
        for (int k = 7; k >= 0; k--) u = u << 8 | raw[k];
        double x;
        memcpy(&x, &u, sizeof x);
        return x;
    }
    return special[v - 240];
}

/* ---- checks ---------------------------------------------------------------------------- */

double maxabs(const double *a, int n)
{
    double s = 0.0;
    for (int k = 0; k < n; k++) s = fmax(s, fabs(a[k]));
    return s;
}

void finite(const double *a, int n, const char *call, const char *field)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i])) fail("%s returned VT_OK with %s[%d] = %g (not finite)", call, field, i, a[i]);
}

size_t input_count(const vt_model *m)
{
    return (size_t)m->nq + (size_t)m->nv + 6 * (size_t)(m->nbody + 1) + (size_t)m->nv;
}

void save_inputs(const vt_model *m, const vt_data *d, double *buf)
{
    size_t o = 0;
    memcpy(buf + o, d->q, (size_t)m->nq * sizeof(double)), o += (size_t)m->nq;
    memcpy(buf + o, d->qd, (size_t)m->nv * sizeof(double)), o += (size_t)m->nv;
    memcpy(buf + o, d->xfrc, 6 * (size_t)(m->nbody + 1) * sizeof(double)), o += 6 * (size_t)(m->nbody + 1);
    memcpy(buf + o, d->qfrc, (size_t)m->nv * sizeof(double));
    buf[input_count(m)] = d->time;
}

/* a failed call: a message, and the inputs bit for bit as before (NaN inputs included) */
void failed_call(const vt_model *m, const vt_data *d, const double *before, vt_status st, const char *call)
{
    if (d->message[0] == '\0') fail("%s failed (%s) with an empty message", call, vt_status_string(st));
    double *now = malloc((input_count(m) + 1) * sizeof(double));
    if (!now) return;
    save_inputs(m, d, now);
    if (memcmp(now, before, (input_count(m) + 1) * sizeof(double)) != 0) {
        size_t k = 0;
        while (k <= input_count(m) && memcmp(now + k, before + k, sizeof(double)) == 0) k++;
        fail("%s failed (%s: %s) and changed its inputs: entry %zu of (q, q̇, xfrc, qfrc, time) %.17g -> %.17g",
             call, vt_status_string(st), d->message, k, before[k], now[k]);
    }
    free(now);
}

/* every output array the stages and the instants fill (R only after vt_inverse_transform) */
void data_finite(const vt_model *m, const vt_data *d, const char *call)
{
    const int n1 = m->nbody + 1, nx = m->nx, nv = m->nv, nc = m->nc;
    finite(d->x, nx, call, "x");
    finite(d->xd, nx, call, "xd");
    finite(d->A, 9 * n1, call, "A");
    finite(d->omega, 3 * n1, call, "omega");
    finite(d->jaxis, 9 * n1, call, "jaxis");
    finite(d->jsij, 3 * n1, call, "jsij");
    finite(d->jd, 3 * n1, call, "jd");
    finite(d->jpoint, 3 * n1, call, "jpoint");
    finite(d->twist, 6 * nv, call, "twist");
    finite(d->S, nx * nv, call, "S");
    finite(d->Sdqd, nx, call, "Sdqd");
    finite(d->R, nv * nx, call, "R");
    finite(d->Mp, 16 * n1, call, "Mp");
    finite(d->Mstar, nv * nv, call, "Mstar");
    finite(d->F, nx, call, "F");
    finite(d->h, nx, call, "h");
    finite(d->Q, nv, call, "Q");
    finite(d->Phi, nc, call, "Phi");
    finite(d->Phix, 14 * nc, call, "Phix");
    finite(d->Phiq, nc * nv, call, "Phiq");
    finite(d->Phit, nc, call, "Phit");
    finite(d->gamma, nc, call, "gamma");
    finite(d->qdd, nv, call, "qdd");
    finite(d->lambda, nc, call, "lambda");
    finite(&d->rcond, 1, call, "rcond");
    finite(&d->residual, 1, call, "residual");
    finite(d->xdd, nx, call, "xdd");
    finite(d->qfrc_drive, nv, call, "qfrc_drive");
    finite(d->drive_effort, m->ndrive, call, "drive_effort");
    finite(d->drive_force, 3 * m->ndrive, call, "drive_force");
    finite(d->drive_moment, 3 * m->ndrive, call, "drive_moment");
    finite(d->jnt_force, 3 * n1, call, "jnt_force");
    finite(d->jnt_moment, 3 * n1, call, "jnt_moment");
    finite(d->jnt_force_body, 3 * n1, call, "jnt_force_body");
    finite(d->jnt_moment_body, 3 * n1, call, "jnt_moment_body");
    finite(d->cut_force, 3 * m->ncut, call, "cut_force");
    finite(d->cut_moment, 3 * m->ncut, call, "cut_moment");
    finite(d->cut_force_body, 3 * m->ncut, call, "cut_force_body");
    finite(d->cut_moment_body, 3 * m->ncut, call, "cut_moment_body");
    finite(d->coupling_effort, m->ncoupling, call, "coupling_effort");
    finite(d->alpha, 3 * n1, call, "alpha");
    finite(d->jnt_force_total, 3 * n1, call, "jnt_force_total");
    finite(d->jnt_moment_total, 3 * n1, call, "jnt_moment_total");
    finite(d->jnt_force_total_body, 3 * n1, call, "jnt_force_total_body");
    finite(d->jnt_moment_total_body, 3 * n1, call, "jnt_moment_total_body");
}

/* What the builder accepted must satisfy what it checks: items an overflowing check would let
 * through (a sum of squares of 1e160 is Inf, and a vector divided by it is zero). */
void unit(const double *a, int n, const char *what, int k)
{
    double s = 0.0, big = maxabs(a, n);
    for (int c = 0; c < n; c++) s += (a[c] / big) * (a[c] / big); /* scaled: cannot overflow */
    if (!(big > 0.0) || !(fabs(big * sqrt(s) - 1.0) <= 1e-9))
        fail("the model's %s %d is not a unit vector: (%g, %g, %g%s) after normalization", what, k, a[0], a[1],
             a[2], n == 4 ? ", ...)" : ")");
}

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda, double *w,
                   double *work, const int *lwork, int *info, size_t, size_t);

void model_check(const vt_model *m)
{
    for (int i = 1; i <= m->nbody; i++) {
        const int jt = m->body_joint[i];
        if (!(m->body_mass[i] >= 0.0) || !isfinite(m->body_mass[i])) fail("body %d: mass %g accepted", i, m->body_mass[i]);
        if (jt != VT_JOINT_BASE && jt != VT_JOINT_SPHERICAL && jt != VT_JOINT_FREE)
            unit(m->body_axis + 6 * i, 3, "body axis1", i);
        if (jt == VT_JOINT_UNIVERSAL) unit(m->body_axis + 6 * i + 3, 3, "body axis2", i);
        if (jt != VT_JOINT_BASE) unit(m->body_quat0 + 4 * i, 4, "body orientation", i);
        /* inertia: symmetric to the tolerance, its principal moments (LAPACK) ≥ −tol and within
         * the triangle inequality to tol, tol = VT_INERTIA_TOL × largest entry (twice, for the
         * eigenvalues' own round-off) */
        const double *J = m->body_inertia + 9 * i;
        finite(J, 9, "vt_builder_build", "body_inertia");
        const double big = maxabs(J, 9), tol = 2.0 * (VT_INERTIA_TOL * big + VT_INERTIA_ABS_TOL);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                if (!(fabs(J[r + 3 * c] - J[c + 3 * r]) <= tol))
                    fail("body %d: asymmetric inertia accepted: J[%d,%d] %g, J[%d,%d] %g", i, r, c, J[r + 3 * c], c, r,
                         J[c + 3 * r]);
        if (big > 0.0) {
            double a[9], w[3], work[16];
            const int n = 3, lwork = 16;
            int info = 0;
            for (int k = 0; k < 9; k++) a[k] = J[k] / big; /* scaled: LAPACK's own sums cannot overflow */
            dsyev_("N", "U", &n, a, &n, w, work, &lwork, &info, 1, 1);
            const double t = tol / big;
            if (info == 0 && (!(w[0] >= -t) || !(w[0] + w[1] >= w[2] - t)))
                fail("body %d: inertia with principal moments %g, %g, %g kg·m² accepted (tolerance %g)", i, w[0] * big,
                     w[1] * big, w[2] * big, tol);
        }
    }
    for (int k = 0; k < m->ndrive; k++)
        if ((m->drive[k].type == VT_DRIVE_ORIENTATION || m->drive[k].type == VT_DRIVE_RELATIVE_ORIENTATION) &&
            !m->drive[k].orientation_callback && !m->drive[k].sequence) {
            unit(m->drive[k].axis, 3, "drive axis", k);
            unit(m->drive[k].orientation, 4, "drive orientation", k);
        }
    for (int k = 0; k < m->ncut; k++) {
        if (m->cut[k].joint != VT_JOINT_SPHERICAL) unit(m->cut[k].axis1, 3, "cut joint axis1", k);
        if (m->cut[k].joint == VT_JOINT_UNIVERSAL) unit(m->cut[k].axis2, 3, "cut joint axis2", k);
        unit(m->cut[k].orientation, 4, "cut joint orientation", k);
    }
}

/* every array of an analysis's filled rows */
void trajectory_finite(const vt_model *m, const vt_trajectory *tr, const char *call)
{
    const int r = tr->nfilled;
    finite(tr->t, r, call, "t");
    finite(tr->q, m->nq * r, call, "trajectory q");
    finite(tr->qd, m->nv * r, call, "trajectory qd");
    finite(tr->qdd, m->nv * r, call, "trajectory qdd");
    finite(tr->lambda, m->nc * r, call, "trajectory lambda");
    finite(tr->qfrc_drive, m->nv * r, call, "trajectory qfrc_drive");
    finite(tr->drive_effort, m->ndrive * r, call, "trajectory drive_effort");
    finite(tr->jnt_force, 3 * (m->nbody + 1) * r, call, "trajectory jnt_force");
    finite(tr->jnt_moment, 3 * (m->nbody + 1) * r, call, "trajectory jnt_moment");
    finite(tr->cut_force, 3 * m->ncut * r, call, "trajectory cut_force");
    finite(tr->cut_moment, 3 * m->ncut * r, call, "trajectory cut_moment");
}
