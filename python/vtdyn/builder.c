/* vtdyn.Builder: a model built by hand (vt_builder), its definitions given as keyword arguments
 * that mirror the C definition structs field by field, with the C defaults
 * (vt_default_model_def, vt_default_body_def, vt_default_frame_def, vt_default_drive_def,
 * vt_default_cut_joint_def, vt_default_payload_def, vt_default_coupling_def). Kinds are named by
 * strings ("revolute", "joint", ...) mapped to the C enums here; a drive's time function is a
 * number (a constant) or a vtdyn.Function (kind, params): constant, polynomial, sine or spline.
 * build() makes a Model (model.c) of the same type as load_urdf's. The builder's calls are
 * short (O(1) a definition, build O(n)) and run with the GIL held, which also serialises the
 * calls on one builder from several threads. */
#include "vtdyn_py.h"

typedef struct {
    PyObject_HEAD
    vt_builder *b;
} BuilderObject;

static const char *joint_kinds[] = {"base", "revolute", "universal", "spherical", "translational", "cylindrical", "free"};
static const char *drive_kinds[] = {"joint", "point", "orientation", "relative_orientation"};

/* the index of a kind's name in names (n), aliases accepted; -1 with ValueError naming what */
static int kind_of(PyObject *o, const char *const *names, int n, const char *what)
{
    const char *s = PyUnicode_Check(o) ? PyUnicode_AsUTF8(o) : NULL;
    if (s && names == joint_kinds && !strcmp(s, "prismatic")) return VT_JOINT_TRANSLATIONAL;
    for (int k = 0; s && k < n; k++)
        if (!strcmp(s, names[k])) return k;
    char list[160] = "";
    for (int k = 0; k < n; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s'%s'", k ? ", " : "", names[k]);
    PyErr_Format(PyExc_ValueError, "%s: unknown kind %R (expected %s%s)", what, o, list,
                 names == joint_kinds ? ", or 'prismatic' for 'translational'" : "");
    return -1;
}

/* n doubles into out unless o is NULL or None (out keeps its default) */
static int opt_doubles(PyObject *o, int n, double *out, const char *what)
{
    return o && o != Py_None ? vtpy_doubles(o, n, out, what) : 0;
}

/* a joint's two-rate field: a number (the first rate) or two numbers */
static int pair(PyObject *o, double out[2], const char *what)
{
    if (!o || o == Py_None) return 0;
    if (PyNumber_Check(o) && !PySequence_Check(o)) {
        out[0] = PyFloat_AsDouble(o);
        return out[0] == -1.0 && PyErr_Occurred() ? -1 : 0;
    }
    return vtpy_doubles(o, 2, out, what);
}

/* an inertia: 3 principal moments (the diagonal) or a 3 x 3 matrix, into column-major out */
static int inertia(PyObject *o, double out[9], const char *what)
{
    if (!o || o == Py_None) return 0;
    PyArrayObject *a = (PyArrayObject *)PyArray_FromAny(o, PyArray_DescrFromType(NPY_DOUBLE), 1, 2,
                                                        NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED, NULL);
    const npy_intp *d = a ? PyArray_DIMS(a) : NULL;
    if (!a || (PyArray_NDIM(a) == 1 ? d[0] != 3 : d[0] != 3 || d[1] != 3)) {
        PyErr_Clear();
        PyErr_Format(PyExc_ValueError, "%s: 3 principal moments or a 3 x 3 matrix, kg m^2", what);
        Py_XDECREF(a);
        return -1;
    }
    const double *p = PyArray_DATA(a);
    memset(out, 0, 9 * sizeof(double));
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            out[r + 3 * c] = PyArray_NDIM(a) == 1 ? (r == c ? p[r] : 0.0) : p[3 * r + c];
    Py_DECREF(a);
    return 0;
}

/* an optional name into buf (VT_NAME_MAX): buf, or NULL for None */
static int opt_name(PyObject *o, char *buf, const char **out, const char *what)
{
    *out = NULL;
    if (!o || o == Py_None) return 0;
    if (vtpy_name(o, buf, what)) return -1;
    *out = buf;
    return 0;
}

/* a refused definition: vtdyn.Error with the builder's message; NULL */
static PyObject *refused(BuilderObject *self, int r)
{
    return vtpy_raise(r, vt_builder_message(self->b), -1);
}

static PyObject *index_or_error(BuilderObject *self, int r)
{
    return r < 0 ? refused(self, r) : PyLong_FromLong(r);
}

static void builder_dealloc(BuilderObject *self)
{
    vt_builder_free(self->b);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static int builder_init(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"gravity", "rcond_min", "rcond_warn", "allow_redundant", "layout", "inertia_tol", NULL};
    PyObject *og = NULL, *olayout = NULL;
    vt_model_def def = vt_default_model_def();
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|$OddpOd:Builder", kwlist, &og, &def.rcond_min, &def.rcond_warn,
                                     &def.allow_redundant, &olayout, &def.inertia_tol))
        return -1;
    if (opt_doubles(og, 3, def.gravity, "gravity")) return -1;
    if (olayout && olayout != Py_None) {
        static const char *layouts[] = {"full", "recursive"};
        const int l = kind_of(olayout, layouts, 2, "layout");
        if (l < 0) return -1;
        def.layout = (vt_layout)l;
    }
    vt_builder *b = NULL;
    const vt_status st = vt_builder_create(&b, &def);
    if (st) {
        char msg[128];
        snprintf(msg, sizeof msg, "Builder: %s (gravity finite; 0 < rcond_min <= rcond_warn <= 1; 0 <= inertia_tol < 1)",
                 vt_status_string(st));
        vtpy_raise(st, msg, -1);
        return -1;
    }
    vt_builder_free(self->b);
    self->b = b;
    return 0;
}

static int ready(BuilderObject *self)
{
    if (self->b) return 1;
    PyErr_SetString(PyExc_RuntimeError, "Builder: not initialised");
    return 0;
}

static PyObject *add_body(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"parent", "joint", "mass", "inertia", "joint_parent", "joint_child", "axis1", "axis2",
                             "orientation", "name", "joint_name", "limit_lower", "limit_upper", "limit_velocity",
                             "limit_effort", "armature", "damping", "friction", "friction_velocity", "gear_ratio",
                             "joint_frame", NULL};
    vt_body_def d = vt_default_body_def();
    PyObject *o[19] = {NULL};
    if (!ready(self) ||
        !PyArg_ParseTupleAndKeywords(args, kw, "|$iOdOOOOOOOOOOOOOOOOOO:add_body", kwlist, &d.parent, &o[0], &d.mass, &o[1],
                                     &o[2], &o[3], &o[4], &o[5], &o[6], &o[7], &o[8], &o[9], &o[10], &o[11], &o[12],
                                     &o[13], &o[14], &o[15], &o[16], &o[17], &o[18]))
        return NULL;
    char name[VT_NAME_MAX], jname[VT_NAME_MAX];
    if (o[0] && o[0] != Py_None) {
        const int j = kind_of(o[0], joint_kinds, VT_JOINT_TYPE_COUNT, "joint");
        if (j < 0) return NULL;
        d.joint = (vt_joint_type)j;
    }
    double *pairs[] = {d.limit_lower, d.limit_upper, d.limit_velocity, d.limit_effort, d.armature,
                       d.damping,     d.friction,    d.friction_velocity, d.gear_ratio};
    if (inertia(o[1], d.inertia, "inertia") || opt_doubles(o[2], 3, d.joint_parent, "joint_parent") ||
        opt_doubles(o[3], 3, d.joint_child, "joint_child") || opt_doubles(o[4], 3, d.axis1, "axis1") ||
        opt_doubles(o[5], 3, d.axis2, "axis2") || opt_doubles(o[6], 4, d.orientation, "orientation") ||
        opt_name(o[7], name, &d.name, "name") || opt_name(o[8], jname, &d.joint_name, "joint_name") ||
        opt_doubles(o[18], 4, d.joint_frame, "joint_frame"))
        return NULL;
    for (int k = 0; k < 9; k++)
        if (pair(o[9 + k], pairs[k], kwlist[11 + k])) return NULL;
    return index_or_error(self, vt_builder_add_body(self->b, &d));
}

static PyObject *add_frame(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"name", "body", "point", "orientation", "reference", NULL};
    vt_frame_def d = vt_default_frame_def();
    PyObject *oname, *op = NULL, *oo = NULL, *oref = NULL;
    char name[VT_NAME_MAX], ref[VT_NAME_MAX];
    if (!ready(self) ||
        !PyArg_ParseTupleAndKeywords(args, kw, "O|$iOOO:add_frame", kwlist, &oname, &d.body, &op, &oo, &oref) ||
        opt_name(oname, name, &d.name, "name") || opt_doubles(op, 3, d.point, "point") ||
        opt_doubles(oo, 4, d.orientation, "orientation") || opt_name(oref, ref, &d.reference, "reference"))
        return NULL;
    return index_or_error(self, vt_builder_add_frame(self->b, &d));
}

/* a time function: a number (constant) or (kind, params); a spline's samples copied into *mem
 * (PyMem; the caller frees it after the drive is added, which copies them) */
static int read_function(PyObject *o, vt_function *f, double **mem, const char *what)
{
    *mem = NULL;
    if (!o || o == Py_None) return 0;
    if (PyNumber_Check(o) && !PySequence_Check(o)) {
        const double c = PyFloat_AsDouble(o);
        if (c == -1.0 && PyErr_Occurred()) return -1;
        *f = vt_function_constant(c);
        return 0;
    }
    PyObject *t = PySequence_Check(o) && !PyUnicode_Check(o) ? PySequence_Tuple(o) : NULL;
    if (!t || PyTuple_GET_SIZE(t) != 2 || !PyUnicode_Check(PyTuple_GET_ITEM(t, 0))) {
        Py_XDECREF(t);
        PyErr_Clear();
        PyErr_Format(PyExc_ValueError, "%s: a number or a vtdyn.Function (kind, params)", what);
        return -1;
    }
    const char *kind = PyUnicode_AsUTF8(PyTuple_GET_ITEM(t, 0));
    PyObject *p = PyTuple_GET_ITEM(t, 1);
    char sub[96];
    snprintf(sub, sizeof sub, "%s (%s)", what, kind ? kind : "?");
    int bad = 0;
    double c[VT_POLY_MAX];
    if (kind && !strcmp(kind, "constant")) {
        bad = vtpy_doubles(p, 1, c, sub);
        if (!bad) *f = vt_function_constant(c[0]);
    } else if (kind && !strcmp(kind, "sine")) {
        bad = vtpy_doubles(p, 4, c, sub);
        if (!bad) *f = vt_function_sine(c[0], c[1], c[2], c[3]);
    } else if (kind && !strcmp(kind, "polynomial")) {
        const Py_ssize_t n = PySequence_Check(p) ? PySequence_Size(p) : -1;
        bad = n < 1 || n > VT_POLY_MAX;
        if (bad) PyErr_Format(PyExc_ValueError, "%s: 1 to %d coefficients c0, c1, ...", sub, VT_POLY_MAX);
        if (!bad) bad = vtpy_doubles(p, (int)n, c, sub);
        if (!bad) *f = vt_function_polynomial((int)n, c);
    } else if (kind && !strcmp(kind, "spline")) {
        PyArrayObject *ts = NULL, *ys = NULL;
        bad = !PySequence_Check(p) || PySequence_Size(p) != 2;
        if (!bad) {
            PyObject *a = PySequence_GetItem(p, 0), *b = a ? PySequence_GetItem(p, 1) : NULL;
            ts = b ? vtpy_as_rows(a, "Function.spline t", (int)PyObject_Size(a)) : NULL;
            ys = ts ? vtpy_as_rows(b, "Function.spline y", (int)PyObject_Size(b)) : NULL;
            Py_XDECREF(a);
            Py_XDECREF(b);
            bad = !ys || PyArray_NDIM(ts) != 1 || PyArray_NDIM(ys) != 1 || PyArray_DIMS(ts)[0] != PyArray_DIMS(ys)[0];
        }
        if (bad) {
            PyErr_Clear();
            PyErr_Format(PyExc_ValueError, "%s: (t, y), two 1-D arrays of as many samples", sub);
        } else {
            const npy_intp n = PyArray_DIMS(ts)[0];
            *mem = PyMem_Malloc((size_t)(2 * n + 1) * sizeof(double));
            if (!*mem) {
                bad = 1;
                PyErr_NoMemory();
            } else {
                memcpy(*mem, PyArray_DATA(ts), (size_t)n * sizeof(double));
                memcpy(*mem + n, PyArray_DATA(ys), (size_t)n * sizeof(double));
                *f = vt_function_spline((int)n, *mem, *mem + n); /* checked when the drive is added */
            }
        }
        Py_XDECREF(ts);
        Py_XDECREF(ys);
    } else {
        bad = 1;
        PyErr_Format(PyExc_ValueError, "%s: unknown kind (expected 'constant', 'polynomial', 'sine' or 'spline')", sub);
    }
    Py_DECREF(t);
    return bad ? -1 : 0;
}

static PyObject *add_drive(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"body", "kind", "index", "f", "point", "axis", "orientation", "name", "frame",
                             "reference", "sequence", "f2", "f3", NULL};
    vt_drive_def d = vt_default_drive_def();
    PyObject *okind = NULL, *of = NULL, *op = NULL, *oa = NULL, *oo = NULL, *oname = NULL, *oframe = NULL, *oseq = NULL;
    PyObject *of2 = NULL, *of3 = NULL;
    char name[VT_NAME_MAX], frame[VT_NAME_MAX], seq[VT_NAME_MAX];
    if (!ready(self) || !PyArg_ParseTupleAndKeywords(args, kw, "|$iOiOOOOOOiOOO:add_drive", kwlist, &d.body, &okind, &d.index,
                                                     &of, &op, &oa, &oo, &oname, &oframe, &d.reference, &oseq, &of2, &of3))
        return NULL;
    if (okind && okind != Py_None) {
        const int k = kind_of(okind, drive_kinds, VT_DRIVE_TYPE_COUNT, "kind");
        if (k < 0) return NULL;
        d.type = (vt_drive_type)k;
    }
    if (opt_doubles(op, 3, d.point, "point") || opt_doubles(oa, 3, d.axis, "axis") ||
        opt_doubles(oo, 4, d.orientation, "orientation") || opt_name(oname, name, &d.name, "name") ||
        opt_name(oframe, frame, &d.frame, "frame") || opt_name(oseq, seq, &d.sequence, "sequence"))
        return NULL;
    double *m1 = NULL, *m2 = NULL, *m3 = NULL;
    PyObject *res = NULL;
    if (!read_function(of, &d.f, &m1, "f") && !read_function(of2, &d.f2, &m2, "f2") && !read_function(of3, &d.f3, &m3, "f3"))
        res = index_or_error(self, vt_builder_add_drive(self->b, &d)); /* the samples copied by the builder */
    PyMem_Free(m1);
    PyMem_Free(m2);
    PyMem_Free(m3);
    return res;
}

static PyObject *add_cut_joint(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"body_a", "body_b", "joint", "point_a", "point_b", "axis1", "axis2", "orientation",
                             "name", "frame_a", "frame_b", "planar", NULL};
    vt_cut_joint_def d = vt_default_cut_joint_def();
    PyObject *o[10] = {NULL};
    char name[VT_NAME_MAX], fa[VT_NAME_MAX], fb[VT_NAME_MAX];
    if (!ready(self) || !PyArg_ParseTupleAndKeywords(args, kw, "|$iiOOOOOOOOOp:add_cut_joint", kwlist, &d.body_a, &d.body_b,
                                                     &o[0], &o[1], &o[2], &o[3], &o[4], &o[5], &o[6], &o[7], &o[8],
                                                     &d.planar))
        return NULL;
    if (o[0] && o[0] != Py_None) {
        const int j = kind_of(o[0], joint_kinds, VT_JOINT_TYPE_COUNT, "joint");
        if (j < 0) return NULL;
        d.joint = (vt_joint_type)j;
    }
    if (opt_doubles(o[1], 3, d.point_a, "point_a") || opt_doubles(o[2], 3, d.point_b, "point_b") ||
        opt_doubles(o[3], 3, d.axis1, "axis1") || opt_doubles(o[4], 3, d.axis2, "axis2") ||
        opt_doubles(o[5], 4, d.orientation, "orientation") || opt_name(o[6], name, &d.name, "name") ||
        opt_name(o[7], fa, &d.frame_a, "frame_a") || opt_name(o[8], fb, &d.frame_b, "frame_b"))
        return NULL;
    return index_or_error(self, vt_builder_add_cut_joint(self->b, &d));
}

static PyObject *add_payload(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"body", "mass", "point", "inertia", "frame", NULL};
    vt_payload_def d = vt_default_payload_def();
    PyObject *op = NULL, *oi = NULL, *of = NULL;
    char frame[VT_NAME_MAX];
    if (!ready(self) ||
        !PyArg_ParseTupleAndKeywords(args, kw, "|$idOOO:add_payload", kwlist, &d.body, &d.mass, &op, &oi, &of) ||
        opt_doubles(op, 3, d.point, "point") || inertia(oi, d.inertia, "inertia") || opt_name(of, frame, &d.frame, "frame"))
        return NULL;
    return index_or_error(self, vt_builder_add_payload(self->b, &d));
}

static PyObject *add_coupling(BuilderObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"body_a", "index_a", "body_b", "index_b", "ratio", "offset", "name", NULL};
    vt_coupling_def d = vt_default_coupling_def();
    PyObject *oname = NULL;
    char name[VT_NAME_MAX];
    if (!ready(self) ||
        !PyArg_ParseTupleAndKeywords(args, kw, "|$iiiiddO:add_coupling", kwlist, &d.body_a, &d.index_a, &d.body_b,
                                     &d.index_b, &d.ratio, &d.offset, &oname) ||
        opt_name(oname, name, &d.name, "name"))
        return NULL;
    return index_or_error(self, vt_builder_add_coupling(self->b, &d));
}

/* find_body, find_joint, find_frame: the id or index of that name, or vtdyn.Error VT_ERR_NOT_FOUND */
static PyObject *find(BuilderObject *self, PyObject *arg, int (*fn)(const vt_builder *, const char *), const char *kind)
{
    char name[VT_NAME_MAX];
    if (!ready(self) || vtpy_name(arg, name, "name")) return NULL;
    const int r = fn(self->b, name);
    if (r >= 0) return PyLong_FromLong(r);
    char msg[VT_NAME_MAX + 32];
    snprintf(msg, sizeof msg, "no %s \"%s\"", kind, name);
    return vtpy_raise(r, msg, -1);
}

static PyObject *find_body(BuilderObject *s, PyObject *a) { return find(s, a, vt_builder_find_body, "body"); }
static PyObject *find_joint(BuilderObject *s, PyObject *a) { return find(s, a, vt_builder_find_joint, "joint"); }
static PyObject *find_frame(BuilderObject *s, PyObject *a) { return find(s, a, vt_builder_find_frame, "frame"); }

static PyObject *build(BuilderObject *self, PyObject *unused)
{
    (void)unused;
    if (!ready(self)) return NULL;
    vt_model *m = NULL;
    const vt_status st = vt_builder_build(&m, self->b);
    if (st) return refused(self, st);
    return vtpy_model_new(m);
}

#define KW METH_VARARGS | METH_KEYWORDS
#define FN(f) (PyCFunction)(void (*)(void))(f)
static PyMethodDef builder_methods[] = {
    {"add_body", FN(add_body), KW,
     "add_body(*, parent=0, joint='revolute', mass=1.0, inertia=None, joint_parent=None, joint_child=None,\n"
     "axis1=None, axis2=None, orientation=None, name=None, joint_name=None, limit_lower=None, limit_upper=None,\n"
     "limit_velocity=None, limit_effort=None, armature=None, damping=None, friction=None,\n"
     "friction_velocity=None, gear_ratio=None, joint_frame=None) -> int: a body and its joint\n"
     "(vt_body_def; None: the C default); its id 1, 2, ..."},
    {"add_frame", FN(add_frame), KW,
     "add_frame(name, *, body=1, point=None, orientation=None, reference=None) -> int: a named frame on a body\n"
     "(vt_frame_def); its index"},
    {"add_drive", FN(add_drive), KW,
     "add_drive(*, body=1, kind='joint', index=0, f=0.0, point=None, axis=None, orientation=None, name=None,\n"
     "frame=None, reference=-1, sequence=None, f2=0.0, f3=0.0) -> int: a drive (vt_drive_def), f a number or\n"
     "a vtdyn.Function; its index"},
    {"add_cut_joint", FN(add_cut_joint), KW,
     "add_cut_joint(*, body_a=0, body_b=1, joint='revolute', point_a=None, point_b=None, axis1=None, axis2=None,\n"
     "orientation=None, name=None, frame_a=None, frame_b=None, planar=False) -> int: a loop's cut joint\n"
     "(vt_cut_joint_def; planar: a planar loop's pin, two rows); its index"},
    {"add_payload", FN(add_payload), KW,
     "add_payload(*, body=1, mass=0.0, point=None, inertia=None, frame=None) -> int: a rigid body fixed to a\n"
     "body (vt_payload_def); the body's id"},
    {"add_coupling", FN(add_coupling), KW,
     "add_coupling(*, body_a=2, index_a=0, body_b=1, index_b=0, ratio=1.0, offset=0.0, name=None) -> int:\n"
     "q_a = ratio q_b + offset (vt_coupling_def); its index"},
    {"find_body", (PyCFunction)find_body, METH_O, "find_body(name) -> int: the id of the body of that name"},
    {"find_joint", (PyCFunction)find_joint, METH_O, "find_joint(name) -> int: the id of the body whose joint has that name"},
    {"find_frame", (PyCFunction)find_frame, METH_O, "find_frame(name) -> int: the index of the frame of that name"},
    {"build", (PyCFunction)build, METH_NOARGS,
     "build() -> Model: the model (vt_builder_build); the builder stays usable (it may add more and build again)"},
    {NULL, NULL, 0, NULL},
};

PyTypeObject vtpy_builder_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "vtdyn.Builder",
    .tp_basicsize = sizeof(BuilderObject),
    .tp_dealloc = (destructor)builder_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Builder(*, gravity=(0, -9.81, 0), rcond_min=1e-12, rcond_warn=1e-6, allow_redundant=False,\n"
              "layout='full', inertia_tol=1e-6): a model built by hand (vt_builder_create with vt_model_def's\n"
              "fields and C defaults); add bodies, frames, drives, cut joints, payloads, then build().",
    .tp_methods = builder_methods,
    .tp_init = (initproc)builder_init,
    .tp_new = PyType_GenericNew,
};
