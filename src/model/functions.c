/* Prescribed functions of time for the drives: f(t), f'(t), f''(t), exact for the built-in
 * kinds (no finite differences):
 *   constant     f = c0                                   f' = 0, f'' = 0
 *   polynomial   f = Σ c_k t^k                            f' = Σ k c_k t^(k−1), f'' = Σ k(k−1) c_k t^(k−2)
 *   sine         f = c0 + c1 sin(c2 t + c3)               f' = c1 c2 cos(·), f'' = −c1 c2² sin(·)
 *   user         whatever the callback returns (checked for errors and non-finite values)
 *   spline       the C2 cubic through samples (t_k, y_k), k = 0..n−1; on [t_i, t_{i+1}], with
 *                h = t_{i+1} − t_i, s = t − t_i, δ_i = (y_{i+1} − y_i)/h and M_k = f''(t_k):
 *                  f   = y_i + b s + M_i s²/2 + (M_{i+1} − M_i) s³/(6h),  b = δ_i − h (2M_i + M_{i+1})/6
 *                  f'  = b + M_i s + (M_{i+1} − M_i) s²/(2h),   f'' = M_i + (M_{i+1} − M_i) s/h
 *                the interior knots' continuity of f' (i = 1..n−2):
 *                  h_{i−1} M_{i−1} + 2 (h_{i−1} + h_i) M_i + h_i M_{i+1} = 6 (δ_i − δ_{i−1})
 *                closed by "not-a-knot" ends for n ≥ 4 (f''' continuous at t_1 and t_{n−2}:
 *                  M_0 = ((h_0 + h_1) M_1 − h_0 M_2)/h_1, and the mirror image at the other end),
 *                which eliminated from the first and last rows leave a tridiagonal system in
 *                M_1..M_{n−2}, solved by LAPACK's dgtsv; n = 3: the parabola through the three
 *                samples, M = 2 (δ_1 − δ_0)/(h_0 + h_1); n = 2: the line, M = 0. Not-a-knot
 *                because a trajectory's ends are not at rest in general (natural ends would force
 *                f'' = 0 there) and it reproduces every cubic exactly. Outside [t_0, t_{n−1}]
 *                the first and last pieces' cubics are continued (a smooth extrapolation, never
 *                a jump in f, f' or f''). The interval by bisection: O(log n), nothing allocated.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "model/functions.h"
#include "base/lapack.h"
#include "base/scan.h"
#include "base/status.h"

vt_function vt_function_constant(double c)
{
    vt_function f;
    memset(&f, 0, sizeof f);
    f.type = VT_FUNCTION_CONSTANT;
    f.ncoef = 1;
    f.c[0] = c;
    return f;
}

vt_function vt_function_polynomial(int ncoef, const double *c)
{
    vt_function f;
    memset(&f, 0, sizeof f);
    f.type = VT_FUNCTION_POLYNOMIAL;
    f.ncoef = ncoef;
    if (c)
        for (int k = 0; k < ncoef && k < VT_POLY_MAX; k++) f.c[k] = c[k];
    return f;
}

vt_function vt_function_sine(double a, double b, double omega, double phase)
{
    vt_function f;
    memset(&f, 0, sizeof f);
    f.type = VT_FUNCTION_SINE;
    f.ncoef = 4;
    f.c[0] = a;
    f.c[1] = b;
    f.c[2] = omega;
    f.c[3] = phase;
    return f;
}

vt_function vt_function_user(vt_function_callback callback, void *user)
{
    vt_function f;
    memset(&f, 0, sizeof f);
    f.type = VT_FUNCTION_CALLBACK;
    f.callback = callback;
    f.user = user;
    return f;
}

vt_function vt_function_spline(int n, const double *t, const double *y)
{
    vt_function f;
    memset(&f, 0, sizeof f);
    f.type = VT_FUNCTION_SPLINE;
    f.nsample = n;
    f.sample_t = t;
    f.sample_y = y;
    f.sample_d2 = NULL; /* computed where the function is used: the builder, or vt_function_eval */
    return f;
}

static vt_status check_spline(char *msg, const vt_function *f)
{
    const int n = f->nsample;
    if (n < 2) return vt_fail(msg, VT_ERR_BAD_DRIVE, "time function: spline with %d samples (at least 2)", n);
    if (!f->sample_t || !f->sample_y)
        return vt_fail(msg, VT_ERR_BAD_DRIVE, "time function: spline's sample times or values are NULL");
    for (int k = 0; k < n; k++)
        if (!isfinite(f->sample_t[k]) || !isfinite(f->sample_y[k]))
            return vt_fail(msg, VT_ERR_NONFINITE, "time function: spline sample %d not finite (t %g, y %g)", k,
                           f->sample_t[k], f->sample_y[k]);
    for (int k = 1; k < n; k++)
        if (!(f->sample_t[k] > f->sample_t[k - 1]))
            return vt_fail(msg, VT_ERR_BAD_DRIVE,
                           "time function: spline times not strictly increasing at sample %d (t[%d] %g, t[%d] %g)", k,
                           k - 1, f->sample_t[k - 1], k, f->sample_t[k]);
    if (f->sample_d2 && !vt_all_finite(f->sample_d2, n))
        return vt_fail(msg, VT_ERR_NONFINITE, "time function: spline's second derivatives not finite");
    return VT_OK;
}

vt_status vt_spline_d2(char *msg, int n, const double *t, const double *y, double *d2, double *work)
{
    if (n == 2) {
        d2[0] = d2[1] = 0.0;
        return VT_OK;
    }
    if (n == 3) { /* not-a-knot at both ends of two pieces: one parabola */
        const double c = 2.0 * ((y[2] - y[1]) / (t[2] - t[1]) - (y[1] - y[0]) / (t[1] - t[0])) / (t[2] - t[0]);
        d2[0] = d2[1] = d2[2] = c;
        return isfinite(c) ? VT_OK : vt_fail(msg, VT_ERR_NONFINITE, "time function: spline curvature overflows");
    }
    /* rows i = 1..n−2 of the knots' equations, unknowns M_1..M_{n−2} (N of them) in d2 + 1 */
    const int N = n - 2, one = 1;
    double *dl = work, *dg = work + n, *du = work + 2 * n, *b = d2 + 1;
    for (int i = 1; i <= n - 2; i++) {
        const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
        const int j = i - 1;
        dg[j] = 2.0 * (h0 + h1);
        if (j > 0) dl[j - 1] = h0;
        if (j < N - 1) du[j] = h1;
        b[j] = 6.0 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
    }
    /* not-a-knot: M_0 and M_{n−1} eliminated from the first and the last row */
    const double h0 = t[1] - t[0], h1 = t[2] - t[1];
    const double ha = t[n - 2] - t[n - 3], hb = t[n - 1] - t[n - 2]; /* h_{n−3}, h_{n−2} */
    dg[0] = (h0 + h1) * (h0 + 2.0 * h1) / h1;
    du[0] = (h1 - h0) * (h1 + h0) / h1;
    dl[N - 2] = (ha - hb) * (ha + hb) / ha;
    dg[N - 1] = (ha + hb) * (2.0 * ha + hb) / ha;
    int info = 0;
    dgtsv_(&N, &one, dl, dg, du, b, &N, &info);
    if (info != 0) return vt_fail(msg, VT_ERR_LAPACK, "time function: spline: dgtsv info %d", info);
    d2[0] = ((h0 + h1) * d2[1] - h0 * d2[2]) / h1;
    d2[n - 1] = ((ha + hb) * d2[n - 2] - hb * d2[n - 3]) / ha;
    if (!vt_all_finite(d2, n)) return vt_fail(msg, VT_ERR_NONFINITE, "time function: spline curvature overflows");
    return VT_OK;
}

/* the piece of [t_i, t_{i+1}] holding x (the end pieces continued outside) and its cubic */
static void spline_eval(double v[3], const vt_function *f, double x)
{
    const double *t = f->sample_t, *y = f->sample_y, *M = f->sample_d2;
    int lo = 0, hi = f->nsample - 1;
    while (hi - lo > 1) { /* bisection: t[lo] <= x < t[hi], or an end piece */
        const int mid = lo + (hi - lo) / 2;
        if (t[mid] <= x) lo = mid;
        else hi = mid;
    }
    const double h = t[lo + 1] - t[lo], s = x - t[lo], dM = M[lo + 1] - M[lo];
    const double b = (y[lo + 1] - y[lo]) / h - h * (2.0 * M[lo] + M[lo + 1]) / 6.0;
    v[0] = y[lo] + s * (b + s * (0.5 * M[lo] + s * dM / (6.0 * h)));
    v[1] = b + s * (M[lo] + s * dM / (2.0 * h));
    v[2] = M[lo] + s * dM / h;
}

vt_status vt_function_check(char *msg, const vt_function *f)
{
    switch (f->type) {
    case VT_FUNCTION_CONSTANT:
        if (!isfinite(f->c[0])) return vt_fail(msg, VT_ERR_NONFINITE, "time function: constant is not finite");
        return VT_OK;
    case VT_FUNCTION_POLYNOMIAL:
        if (f->ncoef < 1 || f->ncoef > VT_POLY_MAX)
            return vt_fail(msg, VT_ERR_BAD_DRIVE, "time function: polynomial with %d coefficients (1..%d)",
                           f->ncoef, VT_POLY_MAX);
        if (!vt_all_finite(f->c, f->ncoef))
            return vt_fail(msg, VT_ERR_NONFINITE, "time function: coefficient not finite");
        return VT_OK;
    case VT_FUNCTION_SINE:
        if (!vt_all_finite(f->c, 4)) return vt_fail(msg, VT_ERR_NONFINITE, "time function: coefficient not finite");
        return VT_OK;
    case VT_FUNCTION_CALLBACK:
        if (!f->callback) return vt_fail(msg, VT_ERR_BAD_DRIVE, "time function: user callback is NULL");
        return VT_OK;
    case VT_FUNCTION_SPLINE:
        return check_spline(msg, f);
    }
    return vt_fail(msg, VT_ERR_BAD_DRIVE, "time function: unknown type %d", (int)f->type);
}

/* A spline whose samples and second derivatives lie in one block t | y | f'' of 3n doubles, as
 * the library lays out a drive's spline (own_splines into the builder, vt_builder_build into the
 * model, model.c): checked when the drive was added (vt_function_check, vt_spline_d2), and
 * constant since (the model's block is its own, read through const pointers). Its evaluation
 * needs no check of the n samples: the bisection and the interval's cubic, O(log n). A function
 * of the caller's arrays, even with a sample_d2 of its own, is not laid out so and is checked in
 * full. The pointers compared as integers: nothing is formed past the caller's arrays. */
static int spline_in_model(const vt_function *f)
{
    const uintptr_t t = (uintptr_t)f->sample_t, stride = (uintptr_t)f->nsample * sizeof(double);
    return f->nsample >= 2 && f->sample_t && f->sample_d2 && (uintptr_t)f->sample_y - t == stride &&
           (uintptr_t)f->sample_d2 - t == 2 * stride;
}

vt_status vt_function_eval(double out[3], const vt_function *f, double t)
{
    if (!out || !f) return VT_ERR_NULL;
    if (f->type == VT_FUNCTION_SPLINE && spline_in_model(f)) return vt_function_eval_valid(out, f, t);
    vt_status st = vt_function_check(NULL, f);
    if (st) return st;
    if (f->type == VT_FUNCTION_SPLINE && !f->sample_d2) {
        /* not yet in a model: the second derivatives solved here, in a fixed local buffer (no
         * allocation), hence the limit on n */
        if (f->nsample > VT_SPLINE_EVAL_MAX) return VT_ERR_BAD_SIZE;
        double d2[VT_SPLINE_EVAL_MAX], work[3 * VT_SPLINE_EVAL_MAX];
        if ((st = vt_spline_d2(NULL, f->nsample, f->sample_t, f->sample_y, d2, work))) return st;
        vt_function g = *f;
        g.sample_d2 = d2;
        return vt_function_eval_valid(out, &g, t);
    }
    return vt_function_eval_valid(out, f, t);
}

vt_status vt_function_eval_other(double v[3], const vt_function *f, double t)
{
    switch (f->type) {
    case VT_FUNCTION_SINE: {
        const double a = f->c[2] * t + f->c[3];
        v[0] = f->c[0] + f->c[1] * sin(a);
        v[1] = f->c[1] * f->c[2] * cos(a);
        v[2] = -f->c[1] * f->c[2] * f->c[2] * sin(a);
        break;
    }
    case VT_FUNCTION_SPLINE:
        spline_eval(v, f, t);
        break;
    default:
        if (f->callback(t, v, f->user) != 0) return VT_ERR_CALLBACK;
        break;
    }
    return VT_OK;
}
