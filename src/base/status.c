/* Statuses and messages: the text of every vt_status, the library's version, vt_fail, which
 * writes a call's message into the VT_MESSAGE_SIZE-byte buffer of a builder or a data struct, and the
 * argument check every stage makes first. */
#include <stdarg.h>
#include <stdio.h>

#include "base/status.h"

const char *vt_status_string(vt_status status)
{
    switch (status) {
    case VT_OK: return "ok";
    case VT_ERR_NULL: return "a required pointer is NULL";
    case VT_ERR_NO_MEMORY: return "out of memory";
    case VT_ERR_NONFINITE: return "NaN or Inf in the input, or a result past the largest double";
    case VT_ERR_MASS: return "mass must not be negative";
    case VT_ERR_INERTIA_ASYMMETRIC: return "inertia matrix not symmetric";
    case VT_ERR_INERTIA_NOT_PSD: return "inertia matrix not positive semi-definite";
    case VT_ERR_INERTIA_TRIANGLE: return "principal moments of inertia violate the triangle inequality";
    case VT_ERR_AXIS_ZERO: return "joint axis of zero length";
    case VT_ERR_AXES_NOT_PERPENDICULAR: return "universal joint axes not perpendicular";
    case VT_ERR_PARENT: return "reference body must be an earlier body (the ground for a base body)";
    case VT_ERR_JOINT_TYPE: return "unknown joint type";
    case VT_ERR_TOO_MANY_BODIES: return "a count or size beyond what the library can index or address";
    case VT_ERR_QUATERNION: return "Euler parameters of zero norm";
    case VT_ERR_EMPTY_MODEL: return "the model has no moving body";
    case VT_ERR_BAD_INDEX: return "index out of range";
    case VT_ERR_MODEL_MISMATCH: return "data struct belongs to another model";
    case VT_ERR_LAPACK: return "LAPACK reported an error";
    case VT_ERR_BAD_DRIVE: return "drive definition cannot be used";
    case VT_ERR_BAD_CUT_JOINT: return "cut joint definition cannot be used";
    case VT_ERR_CALLBACK: return "a user callback returned an error";
    case VT_ERR_SINGULAR: return "augmented system singular or ill-conditioned";
    case VT_ERR_DEPENDENT_CONSTRAINTS: return "constraint rows linearly dependent";
    case VT_ERR_NEWTON: return "Newton-Raphson on the constraints did not converge";
    case VT_ERR_NOT_FULLY_DRIVEN: return "the drives do not fix every degree of freedom";
    case VT_ERR_IDA: return "SUNDIALS IDA failed";
    case VT_ERR_ABORTED: return "stopped by the progress callback";
    case VT_ERR_BAD_OPTION: return "run option out of range";
    case VT_ERR_BAD_SIZE: return "caller-provided buffer too small";
    case VT_ERR_BAD_NAME: return "name too long or already taken";
    case VT_ERR_NOT_FOUND: return "no object of that name";
    case VT_ERR_FILE: return "file cannot be opened or read";
    case VT_ERR_XML: return "malformed XML or not the expected document";
    case VT_ERR_LAYOUT: return "the data does not hold what the call needs (layout)";
    case VT_ERR_SKIPPED: return "not solved: the batch stopped at a failing row";
    case VT_ERR_CONTACT: return "the contacts cannot carry the motion";
    }
    return "unknown status";
}

const char *vt_version(void)
{
    return VT_VERSION_STRING;
}

vt_status vt_fail(char *buf, vt_status status, const char *fmt, ...)
{
    if (buf) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(buf, VT_MESSAGE_SIZE, fmt, ap);
        va_end(ap);
    }
    return status;
}

vt_status vt_check_pair(const vt_model *m, vt_data *d, const char *who)
{
    if (!m || !d) return VT_ERR_NULL;
    if (d->model != m)
        return vt_fail(d->message, VT_ERR_MODEL_MISMATCH, "%s: data made for another model", who);
    return VT_OK;
}

vt_status vt_check_dense(const vt_model *m, vt_data *d, const char *who)
{
    const vt_status st = vt_check_pair(m, d, who);
    if (st) return st;
    if (!d->Mstar)
        return vt_fail(d->message, VT_ERR_LAYOUT,
                       "%s: a dense stage, and the data holds no S, R or M*: its model was built with layout "
                       "VT_LAYOUT_RECURSIVE (vt_model_def.layout = VT_LAYOUT_FULL lays them out)", who);
    return VT_OK;
}
