/* A Model's contact set (vtdyn.ContactSet, made by Model.contacts): the contacts of a floating
 * robot with the ground (docs/contact.md), each read from a vtdyn.Contact (or any object with
 * its attributes) into a vt_contact_def, validated once by vt_contacts_create and kept, with the
 * rule's effort weights, to make the Model's batches from (vt_batch_def.contacts): Model.inverse
 * given contacts=set solves every row by vt_inverse_dynamics_contacts. The set is immutable, so
 * a batch made from it stays valid; the Model's cache keys its batches on the set's serial. */
#include "vtdyn_py.h"

/* attribute `name` of o, or NULL (no error) where o has none or it is None */
static PyObject *attr(PyObject *o, const char *name)
{
    PyObject *v = PyObject_GetAttrString(o, name);
    if (!v) {
        if (PyErr_ExceptionMatches(PyExc_AttributeError)) PyErr_Clear();
        return NULL;
    }
    if (v == Py_None) {
        Py_DECREF(v);
        return NULL;
    }
    return v;
}

/* contact k's fields, C defaults where absent; name and frame copied into the set's buffers */
static int read_contact(ContactSetObject *cs, PyObject *o, int k)
{
    vt_contact_def *d = &cs->defs[k];
    *d = vt_default_contact_def();
    char what[96];
    PyObject *v;
    int bad = 0;
#define FIELD(NAME) (bad ? (v = NULL) : (snprintf(what, sizeof what, "contacts[%d].%s", k, NAME), v = attr(o, NAME)))
    if (FIELD("name")) {
        bad = vtpy_name(v, cs->names + (size_t)k * VT_NAME_MAX, what);
        d->name = cs->names + (size_t)k * VT_NAME_MAX;
        Py_DECREF(v);
    }
    if (FIELD("frame")) {
        bad = vtpy_name(v, cs->frames + (size_t)k * VT_NAME_MAX, what);
        d->frame = cs->frames + (size_t)k * VT_NAME_MAX;
        Py_DECREF(v);
    }
    if (FIELD("body")) {
        const long b = PyLong_AsLong(v);
        bad = b == -1 && PyErr_Occurred();
        if (!bad && (b < INT_MIN || b > INT_MAX)) bad = (PyErr_Format(PyExc_ValueError, "%s: %ld out of range", what, b), 1);
        d->body = (int)b;
        Py_DECREF(v);
    }
    if (FIELD("point")) {
        bad = vtpy_doubles(v, 3, d->point, what);
        Py_DECREF(v);
    }
    if (FIELD("other")) {
        const long b = PyLong_AsLong(v);
        bad = b == -1 && PyErr_Occurred();
        if (!bad && (b < INT_MIN || b > INT_MAX)) bad = (PyErr_Format(PyExc_ValueError, "%s: %ld out of range", what, b), 1);
        d->other = (int)b;
        Py_DECREF(v);
    }
    if (FIELD("normal")) {
        bad = vtpy_doubles(v, 3, d->normal, what);
        Py_DECREF(v);
    }
    if (FIELD("kind")) {
        const char *s = PyUnicode_Check(v) ? PyUnicode_AsUTF8(v) : NULL;
        if (s && !strcmp(s, "unilateral")) d->kind = VT_CONTACT_UNILATERAL;
        else if (s && !strcmp(s, "bilateral")) d->kind = VT_CONTACT_BILATERAL;
        else bad = 1, PyErr_Format(PyExc_ValueError, "%s: %R, expected 'unilateral' or 'bilateral'", what, v);
        Py_DECREF(v);
    }
    if (FIELD("mu")) {
        d->mu = PyFloat_AsDouble(v);
        bad = d->mu == -1.0 && PyErr_Occurred();
        Py_DECREF(v);
    }
    if (FIELD("faces")) {
        const long f = PyLong_AsLong(v);
        bad = f == -1 && PyErr_Occurred();
        d->faces = f < 0 ? -1 : f > 1000 ? 1000 : (int)f; /* out of 3..64: the library refuses it */
        Py_DECREF(v);
    }
    if (FIELD("weight")) {
        d->weight = PyFloat_AsDouble(v);
        bad = d->weight == -1.0 && PyErr_Occurred();
        Py_DECREF(v);
    }
#undef FIELD
    if (bad && PyErr_ExceptionMatches(PyExc_TypeError)) { /* a wrong type: ValueError naming it */
        PyObject *type, *value, *tb;
        PyErr_Fetch(&type, &value, &tb);
        PyErr_Format(PyExc_ValueError, "%s: %S", what, value ? value : Py_None);
        Py_XDECREF(type);
        Py_XDECREF(value);
        Py_XDECREF(tb);
    }
    return bad ? -1 : 0;
}

static void contacts_dealloc(ContactSetObject *self)
{
    PyMem_Free(self->defs);
    PyMem_Free(self->names);
    PyMem_Free(self->frames);
    PyMem_Free(self->effort_weight);
    Py_XDECREF(self->contact_names);
    Py_XDECREF(self->model);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

PyObject *vtpy_model_contacts(ModelObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"contacts", "effort_weight", NULL};
    PyObject *olist, *ow = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|O:contacts", kwlist, &olist, &ow)) return NULL;
    PyObject *f = PySequence_Fast(olist, "contacts: a sequence of vtdyn.Contact");
    if (!f) return NULL;
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(f);
    if (n < 1 || n > VT_COUNT_MAX) {
        Py_DECREF(f);
        return PyErr_Format(PyExc_ValueError, "contacts: %zd contacts, expected 1 or more", n);
    }
    ContactSetObject *cs = PyObject_New(ContactSetObject, &vtpy_contacts_type);
    if (!cs) return Py_DECREF(f), NULL;
    cs->model = (ModelObject *)Py_NewRef((PyObject *)self);
    cs->n = (int)n;
    cs->serial = ++self->contact_serial;
    cs->defs = PyMem_Calloc((size_t)n, sizeof *cs->defs);
    cs->names = PyMem_Calloc((size_t)n, VT_NAME_MAX);
    cs->frames = PyMem_Calloc((size_t)n, VT_NAME_MAX);
    cs->effort_weight = NULL;
    cs->contact_names = NULL;
    if (!cs->defs || !cs->names || !cs->frames) {
        Py_DECREF(f);
        Py_DECREF(cs);
        return PyErr_NoMemory();
    }
    for (Py_ssize_t k = 0; k < n; k++)
        if (read_contact(cs, PySequence_Fast_GET_ITEM(f, k), (int)k)) {
            Py_DECREF(f);
            Py_DECREF(cs);
            return NULL;
        }
    Py_DECREF(f);
    const int nv = self->m->nv;
    if (ow && ow != Py_None) {
        PyArrayObject *w = vtpy_as_rows(ow, "effort_weight", nv);
        if (w && PyArray_NDIM(w) != 1) {
            PyErr_Format(PyExc_ValueError, "effort_weight: %d dimensions, expected 1 (nv = %d)", PyArray_NDIM(w), nv);
            Py_CLEAR(w);
        }
        if (!w) return Py_DECREF(cs), NULL;
        cs->effort_weight = PyMem_Malloc((size_t)(nv > 0 ? nv : 1) * sizeof(double));
        if (cs->effort_weight) memcpy(cs->effort_weight, PyArray_DATA(w), (size_t)nv * sizeof(double));
        Py_DECREF(w);
        if (!cs->effort_weight) return Py_DECREF(cs), PyErr_NoMemory();
    }
    /* validated here, once (the batches made from the definitions later cannot fail on them) */
    char msg[VT_MESSAGE_SIZE] = "";
    vt_contacts *c = NULL;
    vt_status st;
    Py_BEGIN_ALLOW_THREADS
    st = vt_contacts_create(&c, self->m, cs->defs, cs->n, cs->effort_weight, msg);
    vt_contacts_free(c);
    Py_END_ALLOW_THREADS
    if (st) {
        Py_DECREF(cs);
        return vtpy_raise(st, msg, -1);
    }
    cs->contact_names = PyTuple_New(n);
    for (Py_ssize_t k = 0; cs->contact_names && k < n; k++) {
        const char *s = cs->names + (size_t)k * VT_NAME_MAX;
        if (!s[0]) s = cs->frames + (size_t)k * VT_NAME_MAX; /* unnamed: its frame's name, or "" */
        PyObject *u = PyUnicode_DecodeUTF8(s, (Py_ssize_t)strlen(s), "replace");
        if (!u) Py_CLEAR(cs->contact_names);
        else PyTuple_SET_ITEM(cs->contact_names, k, u);
    }
    if (!cs->contact_names) return Py_DECREF(cs), NULL;
    return (PyObject *)cs;
}

/* a bool array of n ints (1: True) */
static PyObject *bools(int nd, npy_intp *dims, const int *src, size_t stride, size_t len, size_t rows)
{
    PyObject *o = PyArray_SimpleNew(nd, dims, NPY_BOOL);
    if (!o) return NULL;
    npy_bool *b = PyArray_DATA((PyArrayObject *)o);
    for (size_t r = 0; r < rows; r++)
        for (size_t k = 0; k < len; k++) b[r * len + k] = src[r * stride + k] != 0;
    return o;
}

/* ContactSet.unique(q, v, a, active=None): the instant on its contacts, then which results the
 * motion and the contacts fix (vt_contacts_unique), on a data and a set of the call's own */
static PyObject *contacts_unique(ContactSetObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"q", "v", "a", "active", NULL};
    PyObject *oq, *ov, *oa, *oact = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "OOO|O:unique", kwlist, &oq, &ov, &oa, &oact)) return NULL;
    const vt_model *m = self->model->m;
    PyArrayObject *q = vtpy_as_rows(oq, "q", m->nq), *v = q ? vtpy_as_rows(ov, "v", m->nv) : NULL;
    PyArrayObject *a = v ? vtpy_as_rows(oa, "a", m->nv) : NULL;
    PyObject *res = NULL, *e = NULL, *f = NULL, *r = NULL;
    int *active = NULL, *eu = NULL, *fu = NULL;
    vt_data *d = NULL;
    vt_contacts *c = NULL;
    if (!a) goto done;
    if (PyArray_NDIM(q) != 1 || PyArray_NDIM(v) != 1 || PyArray_NDIM(a) != 1) {
        PyErr_SetString(PyExc_ValueError, "q: one state (1-D q, v and a)");
        goto done;
    }
    active = PyMem_Malloc((size_t)self->n * sizeof(int));
    eu = PyMem_Malloc((size_t)(m->nv > 0 ? m->nv : 1) * sizeof(int));
    fu = PyMem_Malloc(3 * (size_t)self->n * sizeof(int));
    if (!active || !eu || !fu) {
        PyErr_NoMemory();
        goto done;
    }
    for (int k = 0; k < self->n; k++) active[k] = 1;
    if (oact && oact != Py_None) {
        PyObject *seq = PySequence_Fast(oact, "active: 0 or 1 per contact");
        if (!seq) goto done;
        const int bad = PySequence_Fast_GET_SIZE(seq) != self->n;
        for (int k = 0; !bad && k < self->n; k++) {
            const long x = PyLong_AsLong(PySequence_Fast_GET_ITEM(seq, k));
            if ((x != 0 && x != 1) || PyErr_Occurred()) {
                PyErr_Clear();
                Py_DECREF(seq);
                PyErr_Format(PyExc_ValueError, "active: entry %d is not 0 or 1", k);
                goto done;
            }
            active[k] = (int)x;
        }
        Py_DECREF(seq);
        if (bad) {
            PyErr_Format(PyExc_ValueError, "active: %d entries expected (one a contact)", self->n);
            goto done;
        }
    }
    char msg[VT_MESSAGE_SIZE] = "";
    vt_status st = vt_contacts_create(&c, m, self->defs, self->n, self->effort_weight, msg);
    if (!st && vt_data_create(&d, m)) st = VT_ERR_NO_MEMORY, snprintf(msg, sizeof msg, "vt_data_create: out of memory");
    if (!st) {
        memcpy(d->q, PyArray_DATA(q), (size_t)m->nq * sizeof(double));
        memcpy(d->qd, PyArray_DATA(v), (size_t)m->nv * sizeof(double));
        memcpy(d->qdd, PyArray_DATA(a), (size_t)m->nv * sizeof(double));
        Py_BEGIN_ALLOW_THREADS
        st = vt_inverse_dynamics_contacts(m, d, c, active, NULL);
        if (!st) st = vt_contacts_unique(m, d, c, active, eu, fu);
        Py_END_ALLOW_THREADS
        if (st) snprintf(msg, sizeof msg, "%s", d->message);
    }
    if (st) {
        vtpy_raise(st, msg, -1);
        goto done;
    }
    npy_intp de[1] = {m->nv}, df[2] = {self->n, 3}, dr[2] = {m->nbody, 6};
    e = bools(1, de, eu, 0, (size_t)m->nv, 1);
    f = e ? bools(2, df, fu, 3, 3, (size_t)self->n) : NULL;
    r = f ? bools(2, dr, d->jnt_unique + 6, 6, 6, (size_t)m->nbody) : NULL;
    if (r) res = PyTuple_Pack(3, e, f, r);
done:
    Py_XDECREF(e);
    Py_XDECREF(f);
    Py_XDECREF(r);
    vt_contacts_free(c);
    vt_data_free(d);
    PyMem_Free(active);
    PyMem_Free(eu);
    PyMem_Free(fu);
    Py_XDECREF(q);
    Py_XDECREF(v);
    Py_XDECREF(a);
    return res;
}

static PyMethodDef contacts_methods[] = {
    {"unique", (PyCFunction)(void (*)(void))contacts_unique, METH_VARARGS | METH_KEYWORDS,
     "unique(q, v, a, active=None) -> (effort, force, reaction): at one state on these contacts, which\n"
     "results the motion and the contacts fix (True) and which the distribution rule decides (False):\n"
     "each rate's effort (nv), each contact's force component (ncontact x 3, world axes; an inactive\n"
     "contact's True), each body's joint reaction component (nbody x 6: force, moment, world axes)\n"
     "(vt_inverse_dynamics_contacts, then vt_contacts_unique)"},
    {NULL, NULL, 0, NULL},
};

static Py_ssize_t contacts_len(ContactSetObject *self) { return self->n; }
static PyObject *get_names(ContactSetObject *s, void *c) { (void)c; return Py_NewRef(s->contact_names); }
static PyObject *get_model(ContactSetObject *s, void *c) { (void)c; return Py_NewRef((PyObject *)s->model); }

static PyObject *contacts_repr(ContactSetObject *self)
{
    return PyUnicode_FromFormat("<vtdyn.ContactSet: %d contacts %R>", self->n, self->contact_names);
}

static PyGetSetDef contacts_getset[] = {
    {"names", (getter)get_names, NULL, "each contact's name (its frame's where it has none; \"\" for a body's point)", NULL},
    {"model", (getter)get_model, NULL, "the Model the set was made for", NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

static PySequenceMethods contacts_seq = {.sq_length = (lenfunc)contacts_len};

PyTypeObject vtpy_contacts_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "vtdyn.ContactSet",
    .tp_basicsize = sizeof(ContactSetObject),
    .tp_dealloc = (destructor)contacts_dealloc,
    .tp_repr = (reprfunc)contacts_repr,
    .tp_as_sequence = &contacts_seq,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A Model's contacts with the ground, validated once (Model.contacts; no public constructor): "
              "pass it to Model.inverse(..., contacts=set). len() is the number of contacts.",
    .tp_getset = contacts_getset,
    .tp_methods = contacts_methods,
};
