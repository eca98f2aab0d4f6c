/* The Model type: a vt_model and the batches of its inverse dynamics. load_urdf makes one from
 * a URDF file (vt_urdf_builder), Builder.build from a builder (vtpy_model_new); Model.inverse
 * solves the given motion on one state or N states (vt_batch_inverse_dynamics_motion).
 *
 * A Model owns its vt_model and, per thread count asked for, one vt_batch made at the first call
 * and reused (the batch holds one vt_data per thread: no allocation per row). A lock per Model
 * serialises calls on it, since a batch's data are reused by every call; the GIL is released
 * while the lock is waited for and while the rows are solved, so other Python threads run (and
 * other Models' calls proceed in parallel). */
#include "vtdyn_py.h"

static void model_dealloc(ModelObject *self)
{
    for (int k = 0; k < self->nbatch; k++) vt_batch_free(self->batch[k]);
    vt_model_free(self->m);
    PyMem_RawFree(self->status);
    if (self->lock) PyThread_free_lock(self->lock);
    Py_XDECREF(self->body_names);
    Py_XDECREF(self->joint_names);
    Py_XDECREF(self->frame_names);
    Py_XDECREF(self->body_joint_names);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* a tuple of n names at base + VT_NAME_MAX * (first + k) */
static PyObject *names_tuple(const char *base, int first, int n)
{
    PyObject *t = PyTuple_New(n);
    for (int k = 0; t && k < n; k++) {
        PyObject *s = PyUnicode_DecodeUTF8(base + (size_t)VT_NAME_MAX * (size_t)(first + k),
                                           (Py_ssize_t)strlen(base + (size_t)VT_NAME_MAX * (size_t)(first + k)),
                                           "replace");
        if (!s) {
            Py_DECREF(t);
            return NULL;
        }
        PyTuple_SET_ITEM(t, k, s);
    }
    return t;
}

/* body i's joint's name as the command names it: an implicit floating root (no URDF joint) is
 * named after its link */
static const char *joint_label(const vt_model *m, int i)
{
    const char *name = m->joint_name + (size_t)VT_NAME_MAX * (size_t)i;
    return name[0] ? name : m->body_name + (size_t)VT_NAME_MAX * (size_t)i;
}

static int model_names(ModelObject *self)
{
    const vt_model *m = self->m;
    self->body_names = names_tuple(m->body_name, 1, m->nbody);
    self->frame_names = names_tuple(m->frame_name, 0, m->nframe);
    self->body_joint_names = PyTuple_New(m->nbody);
    if (!self->body_names || !self->frame_names || !self->body_joint_names) return -1;
    int nmoving = 0;
    for (int i = 1; i <= m->nbody; i++) {
        PyObject *s = PyUnicode_DecodeUTF8(joint_label(m, i), (Py_ssize_t)strlen(joint_label(m, i)), "replace");
        if (!s) return -1;
        PyTuple_SET_ITEM(self->body_joint_names, i - 1, s);
        nmoving += m->body_nv[i] > 0;
    }
    /* the moving joints in rate order (bodies are numbered in it; sorted here all the same) */
    self->joint_names = PyTuple_New(nmoving);
    if (!self->joint_names) return -1;
    int k = 0, last = -1;
    while (k < nmoving) {
        int best = 0;
        for (int i = 1; i <= m->nbody; i++)
            if (m->body_nv[i] > 0 && m->body_vadr[i] > last && (!best || m->body_vadr[i] < m->body_vadr[best])) best = i;
        last = m->body_vadr[best];
        PyObject *s = PyUnicode_DecodeUTF8(joint_label(m, best), (Py_ssize_t)strlen(joint_label(m, best)), "replace");
        if (!s) return -1;
        PyTuple_SET_ITEM(self->joint_names, k++, s);
    }
    return 0;
}

/* a new Model owning m (freed here on failure) */
PyObject *vtpy_model_new(vt_model *m)
{
    ModelObject *self = PyObject_New(ModelObject, &vtpy_model_type);
    if (!self) {
        vt_model_free(m);
        return NULL;
    }
    self->m = m;
    self->lock = NULL;
    self->nbatch = self->next = 0;
    self->contact_serial = 0;
    self->status = NULL;
    self->status_cap = 0;
    self->body_names = self->joint_names = self->frame_names = self->body_joint_names = NULL;
    self->lock = PyThread_allocate_lock();
    if (!self->lock) {
        Py_DECREF(self);
        return PyErr_NoMemory();
    }
    if (model_names(self)) {
        Py_DECREF(self);
        return NULL;
    }
    return (PyObject *)self;
}

/* load_urdf's joint_params and payloads, read from their Python objects (with the GIL) before the
 * loader runs (without it) */
typedef struct {
    char name[VT_NAME_MAX];
    double v[3]; /* armature, damping, friction */
} joint_param;

typedef struct {
    char link[VT_NAME_MAX];
    double mass, com[3], inertia[9];
} payload_spec;

/* joint_params {name: (armature, damping, friction)} into *jp (PyMem, *n entries); -1 on error */
static int read_joint_params(PyObject *o, joint_param **jp, Py_ssize_t *n)
{
    *jp = NULL, *n = 0;
    if (!o || o == Py_None) return 0;
    if (!PyDict_Check(o)) return PyErr_SetString(PyExc_ValueError, "joint_params: a dict {joint: (armature, damping, friction)}"), -1;
    *jp = PyMem_Calloc((size_t)PyDict_Size(o) + 1, sizeof **jp);
    if (!*jp) return PyErr_NoMemory(), -1;
    PyObject *key, *val;
    Py_ssize_t pos = 0;
    while (PyDict_Next(o, &pos, &key, &val)) {
        joint_param *e = &(*jp)[*n];
        if (vtpy_name(key, e->name, "joint_params: a joint's name") || vtpy_doubles(val, 3, e->v, "joint_params: a joint's (armature, damping, friction)"))
            return -1;
        (*n)++;
    }
    return 0;
}

/* payloads [(link, mass, com, inertia=None)] into *ps (PyMem, *n entries); -1 on error */
static int read_payloads(PyObject *o, payload_spec **ps, Py_ssize_t *n)
{
    *ps = NULL, *n = 0;
    if (!o || o == Py_None) return 0;
    PyObject *f = PySequence_Fast(o, "payloads: a sequence of (link, mass, com, inertia)");
    if (!f) return -1;
    const Py_ssize_t len = PySequence_Fast_GET_SIZE(f);
    *ps = PyMem_Calloc((size_t)len + 1, sizeof **ps);
    if (!*ps) return Py_DECREF(f), PyErr_NoMemory(), -1;
    for (Py_ssize_t k = 0; k < len; k++) {
        PyObject *t = PySequence_Fast(PySequence_Fast_GET_ITEM(f, k), "payloads: each (link, mass, com, inertia)");
        if (!t) return Py_DECREF(f), -1;
        const Py_ssize_t m = PySequence_Fast_GET_SIZE(t);
        payload_spec *p = &(*ps)[k];
        int bad = m < 3 || m > 4;
        if (bad) PyErr_Format(PyExc_ValueError, "payloads[%zd]: (link, mass, com[, inertia]), not %zd items", k, m);
        if (!bad) bad = vtpy_name(PySequence_Fast_GET_ITEM(t, 0), p->link, "payloads: a link's name");
        if (!bad) {
            p->mass = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(t, 1));
            bad = p->mass == -1.0 && PyErr_Occurred();
        }
        if (!bad) bad = vtpy_doubles(PySequence_Fast_GET_ITEM(t, 2), 3, p->com, "payloads: com (x, y, z)");
        if (!bad && m == 4 && PySequence_Fast_GET_ITEM(t, 3) != Py_None) {
            PyObject *row = PySequence_Fast(PySequence_Fast_GET_ITEM(t, 3), "payloads: inertia (3 x 3)");
            bad = !row;
            for (int r = 0; !bad && r < 3; r++) {
                if (PySequence_Fast_GET_SIZE(row) != 3) {
                    PyErr_SetString(PyExc_ValueError, "payloads: inertia: 3 rows of 3");
                    bad = 1;
                    break;
                }
                double v[3];
                bad = vtpy_doubles(PySequence_Fast_GET_ITEM(row, r), 3, v, "payloads: an inertia row");
                for (int c = 0; !bad && c < 3; c++) p->inertia[r + 3 * c] = v[c];
            }
            Py_XDECREF(row);
        }
        Py_DECREF(t);
        if (bad) return Py_DECREF(f), -1;
        (*n)++;
    }
    Py_DECREF(f);
    return 0;
}

PyObject *vtpy_load_urdf(PyObject *mod, PyObject *args, PyObject *kw)
{
    (void)mod;
    static char *kwlist[] = {"path", "floating", "mimic", "dynamics", "joint_params", "payloads", "inertia_tol", NULL};
    PyObject *pathb = NULL, *ojp = NULL, *opl = NULL, *otol = NULL;
    int floating = 0, mimic = 0, dynamics = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O&|pppOOO:load_urdf", kwlist, PyUnicode_FSConverter, &pathb, &floating,
                                     &mimic, &dynamics, &ojp, &opl, &otol))
        return NULL;
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = floating;
    opt.mimic = mimic;
    opt.dynamics = dynamics;
    /* the given-motion instant needs O(n) data only; a coupling (mimic) needs the full layout */
    opt.model.layout = mimic ? VT_LAYOUT_FULL : VT_LAYOUT_RECURSIVE;
    joint_param *jp = NULL;
    payload_spec *ps = NULL;
    Py_ssize_t njp = 0, nps = 0;
    if (otol && otol != Py_None) {
        opt.model.inertia_tol = PyFloat_AsDouble(otol);
        if (opt.model.inertia_tol == -1.0 && PyErr_Occurred()) return Py_DECREF(pathb), NULL;
    }
    if (read_joint_params(ojp, &jp, &njp) || read_payloads(opl, &ps, &nps)) {
        PyMem_Free(jp);
        PyMem_Free(ps);
        Py_DECREF(pathb);
        return NULL;
    }
    char msg[VT_MESSAGE_SIZE] = "";
    vt_builder *b = NULL;
    vt_model *m = NULL;
    vt_status st;
    Py_BEGIN_ALLOW_THREADS
    st = vt_urdf_builder(&b, PyBytes_AS_STRING(pathb), &opt, msg);
    for (Py_ssize_t k = 0; !st && k < nps; k++) { /* each payload in its link's URDF frame */
        vt_payload_def pd = vt_default_payload_def();
        pd.frame = ps[k].link;
        pd.mass = ps[k].mass;
        memcpy(pd.point, ps[k].com, sizeof pd.point);
        memcpy(pd.inertia, ps[k].inertia, sizeof pd.inertia);
        const int r = vt_builder_add_payload(b, &pd);
        if (r < 0) st = (vt_status)r, snprintf(msg, sizeof msg, "payloads[%zd]: %s", k, vt_builder_message(b));
    }
    for (Py_ssize_t k = 0; !st && k < njp; k++) { /* each named joint takes all three */
        const int body = vt_builder_find_joint(b, jp[k].name);
        vt_joint_effects_def e = vt_default_joint_effects_def();
        e.armature[0] = jp[k].v[0], e.damping[0] = jp[k].v[1], e.friction[0] = jp[k].v[2];
        if (body < 0) st = (vt_status)body, snprintf(msg, sizeof msg, "joint_params: no moving joint '%s'", jp[k].name);
        else if ((st = vt_builder_set_joint_effects(b, body, &e)))
            snprintf(msg, sizeof msg, "joint_params['%s']: %s", jp[k].name, vt_builder_message(b));
    }
    if (!st) {
        st = vt_builder_build(&m, b);
        if (st) snprintf(msg, sizeof msg, "%s", vt_builder_message(b));
    }
    vt_builder_free(b);
    Py_END_ALLOW_THREADS
    PyMem_Free(jp);
    PyMem_Free(ps);
    Py_DECREF(pathb);
    if (st) return vtpy_raise(st, msg, -1);
    return vtpy_model_new(m);
}

static PyObject *get_nq(ModelObject *s, void *c) { (void)c; return PyLong_FromLong(s->m->nq); }
static PyObject *get_nv(ModelObject *s, void *c) { (void)c; return PyLong_FromLong(s->m->nv); }
static PyObject *get_nbody(ModelObject *s, void *c) { (void)c; return PyLong_FromLong(s->m->nbody); }
static PyObject *get_body_names(ModelObject *s, void *c) { (void)c; return Py_NewRef(s->body_names); }
static PyObject *get_joint_names(ModelObject *s, void *c) { (void)c; return Py_NewRef(s->joint_names); }
static PyObject *get_frame_names(ModelObject *s, void *c) { (void)c; return Py_NewRef(s->frame_names); }
static PyObject *get_body_joint_names(ModelObject *s, void *c) { (void)c; return Py_NewRef(s->body_joint_names); }

static PyObject *get_masses(ModelObject *s, void *c)
{
    (void)c;
    npy_intp n = s->m->nbody;
    PyObject *a = vtpy_new_array(1, &n);
    if (a) memcpy(PyArray_DATA((PyArrayObject *)a), s->m->body_mass + 1, (size_t)n * sizeof(double));
    return a;
}

static PyObject *get_gravity(ModelObject *s, void *c)
{
    (void)c;
    npy_intp n = 3;
    PyObject *a = vtpy_new_array(1, &n);
    if (a) memcpy(PyArray_DATA((PyArrayObject *)a), s->m->gravity, 3 * sizeof(double));
    return a;
}

static PyObject *get_q0(ModelObject *s, void *c)
{
    (void)c;
    npy_intp n = s->m->nq;
    PyObject *a = vtpy_new_array(1, &n);
    if (a) memcpy(PyArray_DATA((PyArrayObject *)a), s->m->q0, (size_t)n * sizeof(double));
    return a;
}

static PyObject *get_limits(ModelObject *s, void *c)
{
    (void)c;
    npy_intp d[2] = {s->m->nv, 4}; /* dof_limit is 4 x nv column-major: row-major nv x 4 */
    PyObject *a = vtpy_new_array(2, d);
    if (a) memcpy(PyArray_DATA((PyArrayObject *)a), s->m->dof_limit, (size_t)d[0] * 4 * sizeof(double));
    return a;
}

/* per body: its first index in q, its count, its first rate, its count (nbody x 4, int) */
static PyObject *get_body_index(ModelObject *s, void *c)
{
    (void)c;
    npy_intp d[2] = {s->m->nbody, 4};
    PyObject *a = PyArray_SimpleNew(2, d, NPY_INT64);
    if (!a) return NULL;
    int64_t *p = PyArray_DATA((PyArrayObject *)a);
    for (int i = 1; i <= s->m->nbody; i++) {
        p[4 * (i - 1)] = s->m->body_qadr[i];
        p[4 * (i - 1) + 1] = s->m->body_nq[i];
        p[4 * (i - 1) + 2] = s->m->body_vadr[i];
        p[4 * (i - 1) + 3] = s->m->body_nv[i];
    }
    return a;
}

static PyObject *get_floating(ModelObject *s, void *c)
{
    (void)c;
    for (int i = 1; i <= s->m->nbody; i++)
        if (s->m->body_joint[i] == VT_JOINT_FREE) Py_RETURN_TRUE;
    Py_RETURN_FALSE;
}

/* the cached batch of this thread count and contact set (NULL: none), made at its first use
 * (under the lock, GIL released); the message of a refusal in msg */
static vt_status model_batch(ModelObject *self, int threads, const ContactSetObject *cs, vt_batch **out, char *msg,
                             size_t size)
{
    const long key = cs ? cs->serial : 0;
    for (int k = 0; k < self->nbatch; k++)
        if (self->batch_threads[k] == threads && self->batch_contacts[k] == key) {
            *out = self->batch[k];
            return VT_OK;
        }
    vt_batch_def def = vt_default_batch_def();
    def.threads = threads;
    if (cs) {
        def.contacts = cs->defs;
        def.ncontact = cs->n;
        def.effort_weight = cs->effort_weight;
    }
    vt_batch *b = NULL;
    const vt_status st = vt_batch_create(&b, self->m, &def);
    if (st) {
        snprintf(msg, size, "vt_batch_create (threads %d): %s", threads, vt_status_string(st));
        return st;
    }
    int slot;
    if (self->nbatch < NCACHE) {
        slot = self->nbatch++;
    } else { /* full: the oldest made goes */
        slot = self->next;
        vt_batch_free(self->batch[slot]);
        self->next = (slot + 1) % NCACHE;
    }
    self->batch[slot] = b;
    self->batch_threads[slot] = threads;
    self->batch_contacts[slot] = key;
    *out = b;
    return VT_OK;
}

/* active: None, or 0/1 per contact (one state: ncontact; N states: N x ncontact), as a
 * C-contiguous int array the batch reads (a new reference in *out; NULL for None) */
static int read_active(PyObject *o, int nd, npy_intp N, int nc, PyArrayObject **out)
{
    *out = NULL;
    if (!o || o == Py_None) return 0;
    /* integers or booleans only (a float would be truncated by the cast) */
    PyArrayObject *raw = (PyArrayObject *)PyArray_FROM_O(o), *a = NULL;
    const char kind = raw ? PyArray_DESCR(raw)->kind : 0;
    if (raw && (kind == 'b' || kind == 'i' || kind == 'u' || PyArray_SIZE(raw) == 0))
        a = (PyArrayObject *)PyArray_FromAny((PyObject *)raw, PyArray_DescrFromType(NPY_INT), 0, 0,
                                             NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | NPY_ARRAY_NOTSWAPPED | NPY_ARRAY_FORCECAST,
                                             NULL);
    Py_XDECREF(raw);
    if (!a) {
        PyObject *type = NULL, *value = NULL, *tb = NULL;
        if (PyErr_Occurred()) PyErr_Fetch(&type, &value, &tb);
        if (value) PyErr_Format(PyExc_ValueError, "active: not an array of 0 and 1 (%S)", value);
        else PyErr_SetString(PyExc_ValueError, "active: not an array of 0 and 1 (integers or booleans)");
        Py_XDECREF(type);
        Py_XDECREF(value);
        Py_XDECREF(tb);
        return -1;
    }
    const npy_intp *d = PyArray_DIMS(a);
    if (PyArray_NDIM(a) != nd)
        PyErr_Format(PyExc_ValueError, "active: %d dimensions, expected %d as q (one 0 or 1 a contact%s)", PyArray_NDIM(a), nd,
                     nd == 2 ? ", a row a state" : "");
    else if (d[nd - 1] != nc)
        PyErr_Format(PyExc_ValueError, "active: %zd entries a state, expected %d (one 0 or 1 a contact)", (Py_ssize_t)d[nd - 1], nc);
    else if (nd == 2 && d[0] != N)
        PyErr_Format(PyExc_ValueError, "active: %zd states, q has %zd", (Py_ssize_t)d[0], (Py_ssize_t)N);
    if (PyErr_Occurred()) {
        Py_DECREF(a);
        return -1;
    }
    const int *p = PyArray_DATA(a);
    for (npy_intp k = 0; k < PyArray_SIZE(a); k++)
        if (p[k] != 0 && p[k] != 1) {
            PyErr_Format(PyExc_ValueError, "active: entry %zd is %d, expected 0 or 1", (Py_ssize_t)k, p[k]);
            Py_DECREF(a);
            return -1;
        }
    *out = a;
    return 0;
}

/* outputs: None (every field of Result) or an iterable of Result's field names; want[k] 1 for
 * each field asked for (contact_force needs contacts); 0, or −1 with ValueError naming it */
static int read_outputs(PyObject *o, int want[NRESULT])
{
    for (int k = 0; k < NRESULT; k++) want[k] = o == NULL || o == Py_None;
    if (o == NULL || o == Py_None) return 0;
    if (PyUnicode_Check(o)) {
        PyErr_SetString(PyExc_ValueError, "outputs: a sequence of Result's field names, not one string");
        return -1;
    }
    PyObject *it = PyObject_GetIter(o);
    if (!it) {
        PyErr_Format(PyExc_ValueError, "outputs: a sequence of Result's field names, not %s", Py_TYPE(o)->tp_name);
        return -1;
    }
    PyObject *x;
    int bad = 0;
    while (!bad && (x = PyIter_Next(it))) {
        const char *name = PyUnicode_Check(x) ? PyUnicode_AsUTF8(x) : NULL;
        int k = 0;
        while (name && k < NRESULT && strcmp(name, vtpy_result_fields[k].name) != 0) k++;
        if (!name || k == NRESULT) {
            PyErr_Format(PyExc_ValueError, "outputs: %R is not a field of vtdyn.Result", x);
            bad = 1;
        } else {
            want[k] = 1;
        }
        Py_DECREF(x);
    }
    Py_DECREF(it);
    return bad || PyErr_Occurred() ? -1 : 0;
}

/* the bytes from an array's first element to past its last (non-negative strides, as the inputs
 * vtpy_as_rows gives and the C-contiguous outputs have) */
static void extent(PyArrayObject *x, const char **lo, const char **hi)
{
    *lo = *hi = PyArray_BYTES(x);
    if (PyArray_SIZE(x) == 0) return;
    npy_intp last = PyArray_ITEMSIZE(x);
    for (int d = 0; d < PyArray_NDIM(x); d++) last += (PyArray_DIMS(x)[d] - 1) * PyArray_STRIDES(x)[d];
    *hi = *lo + last;
}

/* 1 when the extents of a and b overlap */
static int overlap(PyArrayObject *a, PyArrayObject *b)
{
    const char *a0, *a1, *b0, *b1;
    extent(a, &a0, &a1);
    extent(b, &b0, &b1);
    return a0 < a1 && b0 < b1 && a0 < b1 && b0 < a1;
}

/* out= field k: the array of an earlier Result, to be written again: float64, C-contiguous,
 * writeable, of the shape this call gives, apart from the inputs (q, v, a, qfrc, loads, t or NULL); a
 * new reference, or NULL with ValueError naming it */
static PyObject *reused_array(PyObject *reuse, int k, int rank, const npy_intp *dims, PyObject *const in[6])
{
    const char *name = vtpy_result_fields[k].name;
    PyObject *o = PyStructSequence_GetItem(reuse, k);
    if (!o || !PyArray_Check(o))
        return PyErr_Format(PyExc_ValueError, "out.%s: an array is needed (the earlier call left it out)", name);
    PyArrayObject *x = (PyArrayObject *)o;
    int same = PyArray_NDIM(x) == rank && PyArray_TYPE(x) == NPY_DOUBLE && PyArray_IS_C_CONTIGUOUS(x) &&
               PyArray_ISWRITEABLE(x) && PyArray_ISNOTSWAPPED(x);
    for (int d = 0; same && d < rank; d++) same = PyArray_DIMS(x)[d] == dims[d];
    if (!same)
        return PyErr_Format(PyExc_ValueError, "out.%s: not a writeable C-contiguous float64 array of this call's shape",
                            name);
    static const char *const input[6] = {"q", "v", "a", "qfrc", "loads", "t"};
    for (int i = 0; i < 6; i++)
        if (in[i] && overlap((PyArrayObject *)in[i], x))
            return PyErr_Format(PyExc_ValueError, "out.%s: shares memory with %s", name, input[i]);
    Py_INCREF(o);
    return o;
}

/* t= of inverse: None, a number, or one per state (N) into *t (float64, N or 1 values; a new
 * reference) and *stride (0: packed, the array's N; a number broadcast over N states is an array
 * of N); None with a model that reads the time is refused, naming the drive. -1 on error */
static int read_time(const vt_model *m, PyObject *o, int nd, npy_intp N, PyArrayObject **t)
{
    *t = NULL;
    if (!o || o == Py_None) {
        const int k = vt_motion_time_drive(m);
        if (k < 0) return 0;
        PyErr_Format(PyExc_ValueError,
                     "t: needed: drive %d (\"%s\") is a %s drive on a model with %s, whose given motion keeps "
                     "its rows, and they read its function at the state's time (t=: a number, or one a state)",
                     k, m->drive[k].name, m->drive[k].type == VT_DRIVE_POINT ? "point" : "orientation",
                     m->ncut ? "cut joints" : "couplings");
        return -1;
    }
    PyArray_Descr *dt = PyArray_DescrFromType(NPY_DOUBLE);
    PyArrayObject *x = (PyArrayObject *)PyArray_FromAny(o, dt, 0, 1, NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED |
                                                                         NPY_ARRAY_NOTSWAPPED, NULL);
    if (!x) {
        PyErr_Clear();
        PyErr_Format(PyExc_ValueError, "t: a number%s (s), not convertible to float64", nd == 2 ? " or one a state" : "");
        return -1;
    }
    if (PyArray_NDIM(x) == 1 && (nd == 1 || PyArray_DIMS(x)[0] != N)) {
        PyErr_Format(PyExc_ValueError, "t: %zd values, expected %s", (Py_ssize_t)PyArray_DIMS(x)[0],
                     nd == 2 ? "a number or one a state (N)" : "a number (one state)");
        Py_DECREF(x);
        return -1;
    }
    if (PyArray_NDIM(x) == 0 && nd == 2) { /* one time for every state */
        const double v = *(const double *)PyArray_DATA(x);
        Py_DECREF(x);
        x = (PyArrayObject *)PyArray_SimpleNew(1, &N, NPY_DOUBLE);
        if (!x) return -1;
        double *p = PyArray_DATA(x);
        for (npy_intp i = 0; i < N; i++) p[i] = v;
    }
    *t = x;
    return 0;
}

static PyObject *model_inverse(ModelObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"q", "v", "a", "threads", "contacts", "active", "outputs", "out", "qfrc", "loads",
                             "load_frames", "t", NULL};
    PyObject *oq, *ov, *oa, *ocs = NULL, *oact = NULL, *oout = NULL, *reuse = NULL, *oqf = NULL, *old = NULL, *olf = NULL,
             *ot = NULL;
    int threads = 0, want[NRESULT];
    if (!PyArg_ParseTupleAndKeywords(args, kw, "OOO|iOOOOOOOO:inverse", kwlist, &oq, &ov, &oa, &threads, &ocs, &oact,
                                     &oout, &reuse, &oqf, &old, &olf, &ot))
        return NULL;
    if (oqf == Py_None) oqf = NULL;
    if (old == Py_None) old = NULL;
    if (olf == Py_None) olf = NULL;
    if (!old != !olf)
        return PyErr_Format(PyExc_ValueError, "%s given without %s: loads (F x 6 a state: force, then moment about "
                            "the frame's origin, world axes) and load_frames (F frame names) go together",
                            old ? "loads" : "load_frames", old ? "load_frames" : "loads");
    if (reuse == Py_None) reuse = NULL;
    if (reuse && !PyObject_TypeCheck(reuse, &vtpy_result_type))
        return PyErr_Format(PyExc_ValueError, "out: a vtdyn.Result of an earlier call, not %s", Py_TYPE(reuse)->tp_name);
    if (read_outputs(oout, want)) return NULL;
    if (threads < 0) return PyErr_Format(PyExc_ValueError, "threads: %d, expected 0 (every CPU) or more", threads);
    const ContactSetObject *cs = NULL;
    if (ocs && ocs != Py_None) {
        if (!PyObject_TypeCheck(ocs, &vtpy_contacts_type))
            return PyErr_Format(PyExc_ValueError, "contacts: a vtdyn.ContactSet (Model.contacts), not %s", Py_TYPE(ocs)->tp_name);
        cs = (const ContactSetObject *)ocs;
        if (cs->model != self) return PyErr_Format(PyExc_ValueError, "contacts: made for another Model");
    } else if (oact && oact != Py_None) {
        return PyErr_Format(PyExc_ValueError, "active: given without contacts");
    }
    const int ncontact = cs ? cs->n : 0;
    const vt_model *m = self->m;
    PyArrayObject *q = vtpy_as_rows(oq, "q", m->nq), *v = q ? vtpy_as_rows(ov, "v", m->nv) : NULL;
    PyArrayObject *a = v ? vtpy_as_rows(oa, "a", m->nv) : NULL, *act = NULL;
    PyArrayObject *qf = a && oqf ? vtpy_as_rows(oqf, "qfrc", m->nv) : NULL;
    PyObject *res = NULL, *out[NRESULT] = {NULL};
    PyArrayObject *ld = NULL, *tm = NULL;
    int *lframe = NULL, nload = 0;
    if (!a || (oqf && !qf)) goto done;
    const int nd = PyArray_NDIM(q);
    if (qf && (PyArray_NDIM(qf) != nd || (nd == 2 && PyArray_DIMS(qf)[0] != PyArray_DIMS(q)[0]))) {
        PyErr_Format(PyExc_ValueError, "qfrc: %d dimensions%s, expected q's shape of states (N x nv, or nv)",
                     PyArray_NDIM(qf), PyArray_NDIM(qf) == nd ? " and another row count" : "");
        goto done;
    }
    if (PyArray_NDIM(v) != nd || PyArray_NDIM(a) != nd) {
        PyErr_Format(PyExc_ValueError, "%s: %d dimensions, q has %d (one state: all 1-D; N states: all N x n)",
                     PyArray_NDIM(v) != nd ? "v" : "a", PyArray_NDIM(v) != nd ? PyArray_NDIM(v) : PyArray_NDIM(a), nd);
        goto done;
    }
    const npy_intp N = nd == 2 ? PyArray_DIMS(q)[0] : 1;
    if (nd == 2 && (PyArray_DIMS(v)[0] != N || PyArray_DIMS(a)[0] != N)) {
        const int bad_v = PyArray_DIMS(v)[0] != N;
        PyErr_Format(PyExc_ValueError, "%s: %zd states, q has %zd", bad_v ? "v" : "a",
                     (Py_ssize_t)PyArray_DIMS(bad_v ? v : a)[0], (Py_ssize_t)N);
        goto done;
    }
    if (N > INT_MAX) {
        PyErr_Format(PyExc_ValueError, "q: %zd states, at most %d a call", (Py_ssize_t)N, INT_MAX);
        goto done;
    }
    if (cs && read_active(oact, nd, N, ncontact, &act)) goto done;
    if (read_time(m, ot, nd, N, &tm)) goto done;
    if (old) { /* F frames, and their wrenches as packed rows of 6 F */
        if (!(lframe = vtpy_frame_indices(m, olf, &nload, "load_frames"))) goto done;
        PyArray_Descr *dt = PyArray_DescrFromType(NPY_DOUBLE);
        ld = (PyArrayObject *)PyArray_FromAny(old, dt, 0, 0, NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | NPY_ARRAY_NOTSWAPPED,
                                              NULL);
        if (!ld) {
            PyErr_Clear();
            PyErr_Format(PyExc_ValueError, "loads: not convertible to a float64 array");
            goto done;
        }
        const npy_intp *ldim = PyArray_DIMS(ld);
        if (PyArray_NDIM(ld) != nd + 1 || ldim[nd] != 6 || ldim[nd - 1] != nload || (nd == 2 && ldim[0] != N)) {
            PyErr_Format(PyExc_ValueError, "loads: expected %s%d x 6 (a wrench for each of the %d load_frames)",
                         nd == 2 ? "N x " : "", nload, nload);
            goto done;
        }
    }
    /* effort, then the 6-a-body arrays, the bearing split (4 a body), the limit excess (3 a rate),
     * the effort's parts (3 x nv), the contact forces (3 a contact), q̈ (a rate), the drives' efforts */
    npy_intp de[2] = {N, m->nv}, dr[3] = {N, m->nbody, 6}, db[3] = {N, m->nbody, 4}, dl[3] = {N, m->nv, 3};
    npy_intp dp[3] = {N, 3, m->nv}, dc[3] = {N, ncontact, 3}, dd[2] = {N, m->ndrive};
    for (int k = 0; k < NRESULT; k++) { /* a field not asked for: None, and nothing computed for it */
        npy_intp *dims = k == 0 || k == 10 ? de : k == 6 ? db : k == 7 ? dl : k == 8 ? dp : k == 9 ? dc : k == 11 ? dd : dr;
        const int rank = k == 0 || k >= 10 ? 2 : 3;
        if (!want[k]) {
            Py_INCREF(Py_None);
            out[k] = Py_None;
            continue;
        }
        out[k] = reuse ? reused_array(reuse, k, nd == 2 ? rank : rank - 1, nd == 2 ? dims : dims + 1, (PyObject *[]){
                                              (PyObject *)q, (PyObject *)v, (PyObject *)a, (PyObject *)qf,
                                              (PyObject *)ld, (PyObject *)tm})
                       : nd == 2 ? vtpy_new_array(rank, dims) : vtpy_new_array(rank - 1, dims + 1);
        if (!out[k]) goto done;
    }
    vt_batch_io io;
    memset(&io, 0, sizeof io);
    io.nrow = (int)N;
    io.q = PyArray_DATA(q), io.q_stride = vtpy_row_stride(q);
    io.qd = PyArray_DATA(v), io.qd_stride = vtpy_row_stride(v);
    io.qdd = PyArray_DATA(a), io.qdd_stride = vtpy_row_stride(a);
    if (qf) io.qfrc = PyArray_DATA(qf), io.qfrc_stride = vtpy_row_stride(qf);
    if (ld) io.nload = nload, io.load_frame = lframe, io.load = PyArray_DATA(ld); /* packed rows */
    if (tm) io.time = PyArray_DATA(tm);                                            /* packed: one a row */
#define OUT(k) (want[k] ? PyArray_DATA((PyArrayObject *)out[k]) : NULL)
    io.effort = OUT(0);
    io.reaction = OUT(1);
    io.reaction_body = OUT(2);
    io.total = OUT(3);
    io.total_body = OUT(4);
    io.reaction_joint = OUT(5);
    io.bearing = OUT(6);
    io.limit_excess = OUT(7);
    io.effort_parts = OUT(8);
    io.qdd_out = OUT(10);
    io.drive_effort = OUT(11);
    if (cs) {
        io.contact_force = OUT(9);
        io.contact_active = act ? PyArray_DATA(act) : NULL; /* packed rows (stride 0) */
    }
#undef OUT
    vt_status st = VT_OK;
    int failed = -1, nomem = 0;
    char msg[VT_MESSAGE_SIZE + 32] = "";
    Py_BEGIN_ALLOW_THREADS
    PyThread_acquire_lock(self->lock, WAIT_LOCK);
    vt_batch *b = NULL;
    if ((size_t)N > self->status_cap) {
        int *p = PyMem_RawRealloc(self->status, (size_t)N * sizeof(int));
        if (p) {
            self->status = p;
            self->status_cap = (size_t)N;
        } else {
            nomem = 1;
        }
    }
    if (!nomem) st = model_batch(self, threads, cs, &b, msg, sizeof msg);
    if (!nomem && !st) {
        io.status = self->status;
        st = vt_batch_inverse_dynamics_motion(b, &io);
        if (st) {
            failed = vt_batch_failed_row(b);
            snprintf(msg, sizeof msg, "%s", vt_batch_message(b));
        }
    }
    PyThread_release_lock(self->lock);
    Py_END_ALLOW_THREADS
    if (nomem) {
        PyErr_NoMemory();
        goto done;
    }
    if (st) {
        const char *text = msg;
        if (nd == 1 && strncmp(text, "row 0: ", 7) == 0) text += 7; /* one state: no row to name */
        vtpy_raise(st, text, nd == 2 ? failed : -1);
        goto done;
    }
    res = PyStructSequence_New(&vtpy_result_type);
    if (!res) goto done;
    for (int k = 0; k < NRESULT; k++) {
        PyStructSequence_SET_ITEM(res, k, out[k]);
        out[k] = NULL;
    }
done:
    for (int k = 0; k < NRESULT; k++) Py_XDECREF(out[k]);
    Py_XDECREF(q);
    Py_XDECREF(v);
    Py_XDECREF(a);
    Py_XDECREF(qf);
    Py_XDECREF(ld);
    Py_XDECREF(tm);
    PyMem_Free(lframe);
    Py_XDECREF(act);
    return res;
}

static PyObject *model_repr(ModelObject *self)
{
    return PyUnicode_FromFormat("<vtdyn.Model: %d bodies, nq %d, nv %d>", self->m->nbody, self->m->nq, self->m->nv);
}

static PyGetSetDef model_getset[] = {
    {"nq", (getter)get_nq, NULL, "length of q (a floating root: 7, position then Euler parameters w x y z)", NULL},
    {"nv", (getter)get_nv, NULL, "length of v and a (a floating root: 6, world linear then angular)", NULL},
    {"nbody", (getter)get_nbody, NULL, "moving bodies (URDF links merged through fixed joints)", NULL},
    {"body_names", (getter)get_body_names, NULL, "the moving bodies' link names (nbody), the rows of reaction", NULL},
    {"body_joint_names", (getter)get_body_joint_names, NULL, "each body's joint's name (nbody)", NULL},
    {"joint_names", (getter)get_joint_names, NULL, "the moving joints in rate order, as the command names them", NULL},
    {"frame_names", (getter)get_frame_names, NULL, "the model's frames (every URDF link)", NULL},
    {"masses", (getter)get_masses, NULL, "each body's mass, kg (nbody)", NULL},
    {"gravity", (getter)get_gravity, NULL, "gravity, m/s^2, world axes (3)", NULL},
    {"q0", (getter)get_q0, NULL, "the reference configuration (nq): zero angles, unit Euler parameters", NULL},
    {"limits", (getter)get_limits, NULL,
     "per rate (nv x 4): lowest and highest coordinate, largest |rate| and |effort| (inf where none)", NULL},
    {"body_index", (getter)get_body_index, NULL,
     "per body (nbody x 4, int64): first index in q, count in q, first rate in v, count in v", NULL},
    {"floating", (getter)get_floating, NULL, "True when a body has a free joint (a floating root)", NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyMethodDef model_methods[] = {
    {"inverse", (PyCFunction)(void (*)(void))model_inverse, METH_VARARGS | METH_KEYWORDS,
     "inverse(q, v, a, threads=0, contacts=None, active=None, outputs=None) -> Result: the given motion's\n"
     "efforts and joint reactions (vt_batch_inverse_dynamics_motion) on one state (1-D) or N states (N x n);\n"
     "with contacts (Model.contacts) the ground's forces at them carry the free root\n"
     "(vt_inverse_dynamics_contacts), active: None (all) or 0/1 per contact (ncontact, or N x ncontact);\n"
     "outputs: None (every field) or the Result fields wanted, e.g. ('effort', 'reaction'): the others are\n"
     "None and neither computed nor written; out: an earlier Result of the same shapes whose arrays are\n"
     "written again (no new memory: a log solved chunk by chunk); qfrc: applied generalized forces (as v's\n"
     "shape), which the efforts then need not give; loads (F x 6, or N x F x 6) and load_frames (F names):\n"
     "wrenches the environment applies at frames, force (N) then moment about the frame's origin (N m), world\n"
     "axes, as a tool's force sensor measures them turned into world axes (with contacts the ground's\n"
     "forces balance them too); t: the states' time (s; a number, or N), read by a loop's or coupling's\n"
     "point and orientation drives (needed there, and without effect elsewhere)"},
    {"kinematic_analysis", (PyCFunction)(void (*)(void))vtpy_kinematic_analysis, METH_VARARGS | METH_KEYWORDS,
     "kinematic_analysis(t1, nout=100, t0=0.0, *, tout=None, q=None, qd=None, newton_tol=1e-12, newton_maxit=30,\n"
     "forward_check=True (False without SUNDIALS), ...) -> Trajectory: a fully driven model's motion, efforts and\n"
     "reactions at each output time (vt_kinematic_analysis; the other keywords: vt_run_options's fields)"},
    {"dynamic_analysis", (PyCFunction)(void (*)(void))vtpy_dynamic_analysis, METH_VARARGS | METH_KEYWORDS,
     "dynamic_analysis(t1, nout=100, t0=0.0, *, tout=None, q=None, qd=None, rtol=1e-8, atol=1e-10, max_step=0.0,\n"
     "max_steps=100000, formulation='ggl', forward_check=True, forward_independent=True, ...) -> Trajectory: the\n"
     "motion the drives leave free, integrated by SUNDIALS IDA (vt_dynamic_analysis), from q, qd at t0\n"
     "(None: the reference configuration, at rest)"},
    {"frame_poses", (PyCFunction)(void (*)(void))vtpy_frame_poses, METH_VARARGS | METH_KEYWORDS,
     "frame_poses(q, frames=None) -> (position, rotation): the frames' origins (m, world axes) and axes\n"
     "(rotation R, frame to world: R @ v) at one configuration (nq) or N (N x nq), for every frame (None) or\n"
     "the named ones: position (N x F x 3), rotation (N x F x 3 x 3) (vt_kinematics, vt_frame_pose)"},
    {"contacts", (PyCFunction)(void (*)(void))vtpy_model_contacts, METH_VARARGS | METH_KEYWORDS,
     "contacts(contacts, effort_weight=None) -> ContactSet: the robot's contacts with the ground\n"
     "(vt_contacts_create), each a vtdyn.Contact; effort_weight: each rate's weight w_a in the rule (nv; None: 1)"},
    {NULL, NULL, 0, NULL},
};

PyTypeObject vtpy_model_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "vtdyn.Model",
    .tp_basicsize = sizeof(ModelObject),
    .tp_dealloc = (destructor)model_dealloc,
    .tp_repr = (reprfunc)model_repr,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A model: a robot loaded by vtdyn.load_urdf, or built by vtdyn.Builder.build (no public constructor).",
    .tp_methods = model_methods,
    .tp_getset = model_getset,
};

