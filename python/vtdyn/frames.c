/* Model.frame_poses: where the model's frames are at one or N configurations (vt_kinematics, or
 * on a recursive layout the instant at rest, then vt_frame_pose for each frame asked for), on a
 * data of its own made for the call, the rows
 * solved in C with the GIL released. The frame's axes come as a 3 x 3 rotation R with
 * R[i][j] = (column-major) rotation[i + 3 j]: a vector's frame coordinates v give R v in world
 * axes, NumPy's R @ v. */
#include "vtdyn_py.h"

/* what (an argument's name): None (every frame of the model) or names of its frames; the indices
 * into a new int array (*n of them, PyMem_Free), or NULL with ValueError naming the argument */
int *vtpy_frame_indices(const vt_model *m, PyObject *o, int *n, const char *what)
{
    if (!o || o == Py_None) {
        int *idx = PyMem_Malloc((size_t)(m->nframe > 0 ? m->nframe : 1) * sizeof(int));
        if (!idx) return (int *)PyErr_NoMemory();
        for (int k = 0; k < m->nframe; k++) idx[k] = k;
        *n = m->nframe;
        return idx;
    }
    if (PyUnicode_Check(o)) o = Py_BuildValue("(O)", o); /* one name */
    else Py_INCREF(o);
    PyObject *seq = o ? PySequence_Fast(o, "a frame's name or a sequence of them") : NULL;
    Py_XDECREF(o);
    if (!seq) {
        PyErr_Format(PyExc_ValueError, "%s: a frame's name or a sequence of them", what);
        return NULL;
    }
    const Py_ssize_t len = PySequence_Fast_GET_SIZE(seq);
    int *idx = PyMem_Malloc((size_t)(len > 0 ? len : 1) * sizeof(int));
    if (!idx) {
        Py_DECREF(seq);
        return (int *)PyErr_NoMemory();
    }
    for (Py_ssize_t k = 0; k < len; k++) {
        PyObject *x = PySequence_Fast_GET_ITEM(seq, k);
        const char *name = PyUnicode_Check(x) ? PyUnicode_AsUTF8(x) : NULL;
        const int f = name ? vt_find_frame(m, name) : -1;
        if (f < 0) {
            PyErr_Format(PyExc_ValueError, "%s: %R is not a frame of the model (Model.frame_names)", what, x);
            PyMem_Free(idx);
            Py_DECREF(seq);
            return NULL;
        }
        idx[k] = f;
    }
    *n = (int)len;
    Py_DECREF(seq);
    return idx;
}

PyObject *vtpy_frame_poses(ModelObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"q", "frames", NULL};
    PyObject *oq, *of = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|O:frame_poses", kwlist, &oq, &of)) return NULL;
    const vt_model *m = self->m;
    if (m->layout != VT_LAYOUT_FULL && (m->ncut > 0 || m->ncoupling > 0))
        return PyErr_Format(PyExc_ValueError, "frame_poses: a model with cut joints or couplings needs the full "
                            "layout (Builder(layout='full'); load_urdf with mimic=True has it)");
    int nf = 0;
    int *idx = vtpy_frame_indices(m, of, &nf, "frames");
    if (!idx) return NULL;
    PyArrayObject *q = vtpy_as_rows(oq, "q", m->nq);
    PyObject *pos = NULL, *rot = NULL, *res = NULL;
    vt_data *d = NULL;
    if (!q) goto done;
    const int nd = PyArray_NDIM(q);
    const npy_intp N = nd == 2 ? PyArray_DIMS(q)[0] : 1;
    npy_intp dp[3] = {N, nf, 3}, dr[4] = {N, nf, 3, 3};
    pos = nd == 2 ? vtpy_new_array(3, dp) : vtpy_new_array(2, dp + 1);
    rot = pos ? (nd == 2 ? vtpy_new_array(4, dr) : vtpy_new_array(3, dr + 1)) : NULL;
    if (!rot) goto done;
    if (vt_data_create(&d, m)) {
        PyErr_NoMemory();
        goto done;
    }
    const char *qb = PyArray_BYTES(q);
    const size_t qs = vtpy_row_stride(q); /* doubles */
    double *P = PyArray_DATA((PyArrayObject *)pos), *R = PyArray_DATA((PyArrayObject *)rot);
    vt_status st = VT_OK;
    npy_intp failed = -1;
    Py_BEGIN_ALLOW_THREADS
    for (npy_intp r = 0; r < N && !st; r++) {
        memcpy(d->q, (const double *)(const void *)qb + (size_t)r * qs, (size_t)m->nq * sizeof(double));
        /* the positions: the dense stage where the model lays it out, else the recursive
         * instant at rest (its outward pass; q̇, q̈ and the loads zero in this data) */
        st = m->layout == VT_LAYOUT_FULL ? vt_kinematics(m, d) : vt_inverse_dynamics_motion(m, d);
        for (int k = 0; k < nf && !st; k++) {
            double p[3], c[9];
            st = vt_frame_pose(m, d, idx[k], p, c);
            double *pp = P + ((size_t)r * (size_t)nf + (size_t)k) * 3, *rr = R + ((size_t)r * (size_t)nf + (size_t)k) * 9;
            for (int i = 0; i < 3; i++) {
                pp[i] = p[i];
                for (int j = 0; j < 3; j++) rr[3 * i + j] = c[i + 3 * j]; /* row-major R[i][j] */
            }
        }
        if (st) failed = r;
    }
    Py_END_ALLOW_THREADS
    if (st) {
        char msg[VT_MESSAGE_SIZE + 32];
        if (nd == 2) snprintf(msg, sizeof msg, "row %ld: %s", (long)failed, d->message);
        else snprintf(msg, sizeof msg, "%s", d->message);
        vtpy_raise(st, msg, nd == 2 ? (long)failed : -1);
        goto done;
    }
    res = PyTuple_Pack(2, pos, rot);
done:
    vt_data_free(d);
    PyMem_Free(idx);
    Py_XDECREF(q);
    Py_XDECREF(pos);
    Py_XDECREF(rot);
    return res;
}
