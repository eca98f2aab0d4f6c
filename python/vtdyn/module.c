/* vtdyn._vtdyn — the Python extension module's entry point: the module and its functions,
 * vtdyn.Error (a status and the library's message), the Result type, and the helpers the other
 * files share to read arguments (numbers, names, arrays of rows) into what the C calls take.
 * Written with the CPython and NumPy C APIs only (docs/python.md says why); the library is
 * linked statically into the module. */
#define VTDYN_PY_MODULE_C
#include "vtdyn_py.h"

PyObject *vtpy_error;
PyTypeObject vtpy_result_type;
static int result_type_ready = 0;

/* the enum's name of a status ("VT_ERR_NONFINITE"), as in vtdyn/types.h */
const char *vtpy_status_name(int s)
{
    switch (s) {
    case VT_OK: return "VT_OK";
    case VT_ERR_NULL: return "VT_ERR_NULL";
    case VT_ERR_NO_MEMORY: return "VT_ERR_NO_MEMORY";
    case VT_ERR_NONFINITE: return "VT_ERR_NONFINITE";
    case VT_ERR_MASS: return "VT_ERR_MASS";
    case VT_ERR_INERTIA_ASYMMETRIC: return "VT_ERR_INERTIA_ASYMMETRIC";
    case VT_ERR_INERTIA_NOT_PSD: return "VT_ERR_INERTIA_NOT_PSD";
    case VT_ERR_INERTIA_TRIANGLE: return "VT_ERR_INERTIA_TRIANGLE";
    case VT_ERR_AXIS_ZERO: return "VT_ERR_AXIS_ZERO";
    case VT_ERR_AXES_NOT_PERPENDICULAR: return "VT_ERR_AXES_NOT_PERPENDICULAR";
    case VT_ERR_PARENT: return "VT_ERR_PARENT";
    case VT_ERR_JOINT_TYPE: return "VT_ERR_JOINT_TYPE";
    case VT_ERR_TOO_MANY_BODIES: return "VT_ERR_TOO_MANY_BODIES";
    case VT_ERR_QUATERNION: return "VT_ERR_QUATERNION";
    case VT_ERR_EMPTY_MODEL: return "VT_ERR_EMPTY_MODEL";
    case VT_ERR_BAD_INDEX: return "VT_ERR_BAD_INDEX";
    case VT_ERR_MODEL_MISMATCH: return "VT_ERR_MODEL_MISMATCH";
    case VT_ERR_LAPACK: return "VT_ERR_LAPACK";
    case VT_ERR_BAD_DRIVE: return "VT_ERR_BAD_DRIVE";
    case VT_ERR_BAD_CUT_JOINT: return "VT_ERR_BAD_CUT_JOINT";
    case VT_ERR_CALLBACK: return "VT_ERR_CALLBACK";
    case VT_ERR_SINGULAR: return "VT_ERR_SINGULAR";
    case VT_ERR_DEPENDENT_CONSTRAINTS: return "VT_ERR_DEPENDENT_CONSTRAINTS";
    case VT_ERR_NEWTON: return "VT_ERR_NEWTON";
    case VT_ERR_NOT_FULLY_DRIVEN: return "VT_ERR_NOT_FULLY_DRIVEN";
    case VT_ERR_IDA: return "VT_ERR_IDA";
    case VT_ERR_ABORTED: return "VT_ERR_ABORTED";
    case VT_ERR_BAD_OPTION: return "VT_ERR_BAD_OPTION";
    case VT_ERR_BAD_SIZE: return "VT_ERR_BAD_SIZE";
    case VT_ERR_BAD_NAME: return "VT_ERR_BAD_NAME";
    case VT_ERR_NOT_FOUND: return "VT_ERR_NOT_FOUND";
    case VT_ERR_FILE: return "VT_ERR_FILE";
    case VT_ERR_XML: return "VT_ERR_XML";
    case VT_ERR_LAYOUT: return "VT_ERR_LAYOUT";
    case VT_ERR_SKIPPED: return "VT_ERR_SKIPPED";
    case VT_ERR_CONTACT: return "VT_ERR_CONTACT";
    default: return "VT_ERR_UNKNOWN";
    }
}

/* raises vtdyn.Error(message) with .status (the name), .code and .row (None when < 0); NULL */
PyObject *vtpy_raise(int status, const char *message, long row)
{
    PyObject *exc = PyObject_CallFunction(vtpy_error, "s", message && message[0] ? message : vt_status_string(status));
    if (!exc) return NULL;
    PyObject *code = PyLong_FromLong(status), *name = PyUnicode_FromString(vtpy_status_name(status));
    PyObject *r = row >= 0 ? PyLong_FromLong(row) : (Py_INCREF(Py_None), Py_None);
    if (code && name && r && !PyObject_SetAttrString(exc, "code", code) && !PyObject_SetAttrString(exc, "status", name) &&
        !PyObject_SetAttrString(exc, "row", r))
        PyErr_SetObject(vtpy_error, exc);
    Py_XDECREF(code);
    Py_XDECREF(name);
    Py_XDECREF(r);
    Py_DECREF(exc);
    return NULL;
}

/* n doubles of a Python sequence into out; -1 with ValueError naming what */
int vtpy_doubles(PyObject *o, int n, double *out, const char *what)
{
    PyObject *f = PySequence_Fast(o, what);
    if (!f) return -1;
    if (PySequence_Fast_GET_SIZE(f) != n) {
        PyErr_Format(PyExc_ValueError, "%s: %zd numbers, expected %d", what, PySequence_Fast_GET_SIZE(f), n);
        Py_DECREF(f);
        return -1;
    }
    for (int k = 0; k < n; k++) {
        out[k] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(f, k));
        if (out[k] == -1.0 && PyErr_Occurred()) {
            Py_DECREF(f);
            return -1;
        }
    }
    Py_DECREF(f);
    return 0;
}

/* a str into a name of at most VT_NAME_MAX − 1 bytes; -1 with ValueError */
int vtpy_name(PyObject *o, char *out, const char *what)
{
    const char *u = PyUnicode_Check(o) ? PyUnicode_AsUTF8(o) : NULL;
    if (!u) {
        if (!PyErr_Occurred()) PyErr_Format(PyExc_ValueError, "%s: a str, not %s", what, Py_TYPE(o)->tp_name);
        return -1;
    }
    if (strlen(u) >= VT_NAME_MAX) {
        PyErr_Format(PyExc_ValueError, "%s '%.40s...': longer than %d bytes", what, u, VT_NAME_MAX - 1);
        return -1;
    }
    snprintf(out, VT_NAME_MAX, "%s", u);
    return 0;
}

/* a new float64 array of the given shape */
PyObject *vtpy_new_array(int nd, npy_intp *dims)
{
    return PyArray_SimpleNew(nd, dims, NPY_DOUBLE);
}

/* one input as a float64 array whose rows the C call can take: ndim 1 (n) or 2 (N x n), entries
 * of a row contiguous, the row stride a non-negative multiple of 8 bytes at least the row's
 * length (else a C-contiguous copy); a new reference, or NULL with ValueError naming it */
PyArrayObject *vtpy_as_rows(PyObject *obj, const char *name, int n)
{
    PyArray_Descr *dt = PyArray_DescrFromType(NPY_DOUBLE);
    PyArrayObject *a = (PyArrayObject *)PyArray_FromAny(obj, dt, 0, 0, NPY_ARRAY_ALIGNED | NPY_ARRAY_NOTSWAPPED, NULL);
    if (!a) {
        PyObject *type, *value, *tb;
        PyErr_Fetch(&type, &value, &tb);
        PyObject *text = value ? PyObject_Str(value) : NULL;
        PyErr_Format(PyExc_ValueError, "%s: not convertible to a float64 array (%S)", name,
                     text ? text : Py_None);
        Py_XDECREF(text);
        Py_XDECREF(type);
        Py_XDECREF(value);
        Py_XDECREF(tb);
        return NULL;
    }
    const int nd = PyArray_NDIM(a);
    if (nd != 1 && nd != 2) {
        PyErr_Format(PyExc_ValueError, "%s: %d dimensions, expected 1 (one state of %d) or 2 (N states x %d)", name,
                     nd, n, n);
        Py_DECREF(a);
        return NULL;
    }
    const npy_intp *dims = PyArray_DIMS(a), *st = PyArray_STRIDES(a);
    if (dims[nd - 1] != n) {
        PyErr_Format(PyExc_ValueError, "%s: %zd entries a state, expected %d", name, (Py_ssize_t)dims[nd - 1], n);
        Py_DECREF(a);
        return NULL;
    }
    int ok = n <= 1 || st[nd - 1] == (npy_intp)sizeof(double);
    if (nd == 2 && dims[0] > 1)
        ok = ok && st[0] > 0 && st[0] % (npy_intp)sizeof(double) == 0 && st[0] >= (npy_intp)n * (npy_intp)sizeof(double);
    if (!ok) {
        PyArrayObject *c = (PyArrayObject *)PyArray_NewCopy(a, NPY_CORDER);
        Py_DECREF(a);
        a = c;
    }
    return a;
}

/* the row stride, in doubles, to pass for a: 0 (packed) for one row */
size_t vtpy_row_stride(PyArrayObject *a)
{
    if (PyArray_NDIM(a) != 2 || PyArray_DIMS(a)[0] <= 1) return 0;
    return (size_t)(PyArray_STRIDES(a)[0] / (npy_intp)sizeof(double));
}

/* ---- Result ------------------------------------------------------------------------------------ */

PyStructSequence_Field vtpy_result_fields[] = {
    {"effort", "every rate's generalized force (N x nv, or nv): N m or N; a floating root's six in world axes"},
    {"reaction", "each body's joint reaction (N x nbody x 6): force, then moment about the joint point, world axes"},
    {"reaction_body", "the same in the body's axes (the link's inertial axes)"},
    {"total", "each joint's total wrench, reaction plus actuation, world axes"},
    {"total_body", "the same in the body's axes"},
    {"reaction_joint", "each body's joint reaction in the joint's frame (the child link's URDF axes, N x nbody x 6)"},
    {"bearing", "each joint's bearing split (N x nbody x 4): axial and radial force, axial and tilting moment"},
    {"limit_excess", "each rate's excess beyond its position, velocity and effort limits (N x nv x 3), 0 within"},
    {"effort_parts", "the parts of each rate's effort its joint's armature, damping and friction take (N x 3 x nv)"},
    {"contact_force", "with contacts: the ground's force at each contact (N x ncontact x 3), world axes, 0 where inactive"},
    {"qdd", "every rate's acceleration (N x nv): a's back on a tree; with loops or couplings the driven rates' given "
            "and the others' solved"},
    {"drive_effort", "each joint drive's effort (N x ndrive): with loops or couplings, the given rates' actuators"},
    {NULL, NULL},
};

static PyStructSequence_Desc result_desc = {
    "vtdyn.Result", "The results of Model.inverse (NumPy float64 arrays; None for a field outputs= left out).",
    vtpy_result_fields, NRESULT,
};

/* ---- the module --------------------------------------------------------------------------------- */

static PyObject *version(PyObject *mod, PyObject *unused)
{
    (void)mod;
    (void)unused;
    return PyUnicode_FromString(vt_version());
}

static PyMethodDef module_methods[] = {
    {"load_urdf", (PyCFunction)(void (*)(void))vtpy_load_urdf, METH_VARARGS | METH_KEYWORDS,
     "load_urdf(path, floating=False, mimic=False, dynamics=True, joint_params=None, payloads=None,\n"
     "          inertia_tol=None) -> Model: a URDF robot (vt_urdf_builder); dynamics: the joints'\n"
     "<dynamics damping friction> in every effort (False: ideal joints); joint_params: {joint: (armature,\n"
     "damping, friction)}, all three taken; payloads: [(link, mass, com, inertia=None)], com and the 3 x 3\n"
     "inertia about it in the link's URDF frame; inertia_tol: the inertia checks' relative tolerance"},
    {"version", version, METH_NOARGS, "the C library's version (vt_version)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module_def = {
    PyModuleDef_HEAD_INIT, "vtdyn._vtdyn", "vtdyn's C extension (see the package vtdyn).", -1, module_methods,
    NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__vtdyn(void)
{
    import_array();
    if (PyType_Ready(&vtpy_model_type) < 0 || PyType_Ready(&vtpy_contacts_type) < 0 || PyType_Ready(&vtpy_builder_type) < 0)
        return NULL;
    if (!result_type_ready) {
        if (PyStructSequence_InitType2(&vtpy_result_type, &result_desc) < 0) return NULL;
        if (PyStructSequence_InitType2(&vtpy_trajectory_type, &vtpy_trajectory_desc) < 0) return NULL;
        result_type_ready = 1;
    }
    PyObject *mod = PyModule_Create(&module_def);
    if (!mod) return NULL;
    if (!vtpy_error) {
        vtpy_error = PyErr_NewExceptionWithDoc(
            "vtdyn.Error",
            "A status the library returned: .status its name (\"VT_ERR_NONFINITE\"), .code the int, "
            ".row the failing row of N states (None otherwise); the message is the library's.",
            PyExc_RuntimeError, NULL);
        if (!vtpy_error) goto fail;
    }
    Py_INCREF(vtpy_error);
    if (PyModule_AddObject(mod, "Error", vtpy_error) < 0) {
        Py_DECREF(vtpy_error);
        goto fail;
    }
    Py_INCREF(&vtpy_model_type);
    if (PyModule_AddObject(mod, "Model", (PyObject *)&vtpy_model_type) < 0) {
        Py_DECREF(&vtpy_model_type);
        goto fail;
    }
    if (PyModule_AddObjectRef(mod, "ContactSet", (PyObject *)&vtpy_contacts_type) < 0 ||
        PyModule_AddObjectRef(mod, "Builder", (PyObject *)&vtpy_builder_type) < 0 ||
        PyModule_AddObjectRef(mod, "Trajectory", (PyObject *)&vtpy_trajectory_type) < 0)
        goto fail;
    PyObject *w = PyFloat_FromDouble(VT_CONTACT_WEIGHT);
    const int bad = !w || PyModule_AddObjectRef(mod, "VT_CONTACT_WEIGHT", w) < 0;
    Py_XDECREF(w);
    if (bad) goto fail;
    Py_INCREF(&vtpy_result_type);
    if (PyModule_AddObject(mod, "Result", (PyObject *)&vtpy_result_type) < 0) {
        Py_DECREF(&vtpy_result_type);
        goto fail;
    }
    if (PyModule_AddIntConstant(mod, "VT_HAVE_SUNDIALS", VT_HAVE_SUNDIALS) < 0) goto fail;
    return mod;
fail:
    Py_DECREF(mod);
    return NULL;
}
