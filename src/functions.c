/* Prescribed functions of time for the drives: f(t), f'(t), f''(t), exact for the built-in
 * kinds (no finite differences):
 *   constant     f = c0                                   f' = 0, f'' = 0
 *   polynomial   f = Σ c_k t^k                            f' = Σ k c_k t^(k−1), f'' = Σ k(k−1) c_k t^(k−2)
 *   sine         f = c0 + c1 sin(c2 t + c3)               f' = c1 c2 cos(·), f'' = −c1 c2² sin(·)
 *   user         whatever the callback returns (checked for errors and non-finite values)
 */
#include <string.h>

#include "internal.h"

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
    }
    return vt_fail(msg, VT_ERR_BAD_DRIVE, "time function: unknown type %d", (int)f->type);
}

vt_status vt_function_eval(double out[3], const vt_function *f, double t)
{
    if (!out || !f) return VT_ERR_NULL;
    vt_status st = vt_function_check(NULL, f);
    if (st) return st;
    return vt_function_eval_valid(out, f, t);
}

vt_status vt_function_eval_valid(double out[3], const vt_function *f, double t)
{
    if (!isfinite(t)) return VT_ERR_NONFINITE;
    double v[3] = {0, 0, 0};
    switch (f->type) {
    case VT_FUNCTION_CONSTANT:
        v[0] = f->c[0];
        break;
    case VT_FUNCTION_POLYNOMIAL:
        /* Horner for f, f', f'' together */
        for (int k = f->ncoef - 1; k >= 0; k--) {
            v[2] = v[2] * t + 2.0 * v[1];
            v[1] = v[1] * t + v[0];
            v[0] = v[0] * t + f->c[k];
        }
        break;
    case VT_FUNCTION_SINE: {
        const double a = f->c[2] * t + f->c[3];
        v[0] = f->c[0] + f->c[1] * sin(a);
        v[1] = f->c[1] * f->c[2] * cos(a);
        v[2] = -f->c[1] * f->c[2] * f->c[2] * sin(a);
        break;
    }
    default:
        if (f->callback(t, v, f->user) != 0) return VT_ERR_CALLBACK;
        break;
    }
    if (!vt_all_finite(v, 3)) return VT_ERR_NONFINITE;
    out[0] = v[0];
    out[1] = v[1];
    out[2] = v[2];
    return VT_OK;
}
