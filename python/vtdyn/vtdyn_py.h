/* The extension module vtdyn._vtdyn's private header: what its C files share (the Model and
 * contact-set objects, the error and array helpers). Not installed; the files are
 *   module.c    the module, vtdyn.Error, the Result type, argument and array helpers
 *   model.c     the Model type, load_urdf, Model.inverse and its batch cache
 *   contacts.c  the contact set (Model.contacts) and its reading of vtdyn.Contact
 *   builder.c   vtdyn.Builder: bodies, frames, drives and their time functions, cut joints
 *   analysis.c  Model.kinematic_analysis and Model.dynamic_analysis, the Trajectory type */
#ifndef VTDYN_PY_H
#define VTDYN_PY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
/* one NumPy API table for the module's files: defined in module.c, imported there */
#define PY_ARRAY_UNIQUE_SYMBOL vtdyn_py_ARRAY_API
#ifndef VTDYN_PY_MODULE_C
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include <stdint.h>
#include <string.h>

#include "vtdyn.h"

#define NCACHE 8   /* batches kept per Model (distinct thread counts and contact sets) */
#define NRESULT 12 /* Result's arrays (vtpy_result_fields) */
extern PyStructSequence_Field vtpy_result_fields[]; /* Result's field names, in order (module.c) */

typedef struct {
    PyObject_HEAD
    vt_model *m;
    PyThread_type_lock lock;
    int nbatch;
    int batch_threads[NCACHE];
    long batch_contacts[NCACHE]; /* the contact set's serial (ContactSetObject.serial), 0: none */
    vt_batch *batch[NCACHE];
    int next;                    /* the cache slot replaced next once full */
    long contact_serial;         /* the last serial given to a contact set of this Model */
    int *status;                 /* per-row statuses, grown as needed (under the lock) */
    size_t status_cap;
    PyObject *body_names, *joint_names, *frame_names, *body_joint_names; /* tuples, made at load */
} ModelObject;

/* a Model's contact set (contacts.c): the validated definitions, kept to make batches from */
typedef struct {
    PyObject_HEAD
    ModelObject *model;      /* the Model it was made for (a reference) */
    long serial;             /* its key in the Model's batch cache, unique in the Model */
    int n;
    vt_contact_def *defs;    /* n, name and frame pointing into names and frames */
    char *names, *frames;    /* n x VT_NAME_MAX each */
    double *effort_weight;   /* nv, or NULL (1 each) */
    PyObject *contact_names; /* a tuple of n str */
} ContactSetObject;

extern PyObject *vtpy_error;          /* vtdyn.Error */
extern PyTypeObject vtpy_result_type; /* vtdyn.Result */
extern PyTypeObject vtpy_model_type;
extern PyTypeObject vtpy_contacts_type;
extern PyTypeObject vtpy_builder_type;
extern PyTypeObject vtpy_trajectory_type;
extern PyStructSequence_Desc vtpy_trajectory_desc;

/* module.c */
const char *vtpy_status_name(int s);
PyObject *vtpy_raise(int status, const char *message, long row);
int vtpy_doubles(PyObject *o, int n, double *out, const char *what);
int vtpy_name(PyObject *o, char *out, const char *what);
PyObject *vtpy_new_array(int nd, npy_intp *dims);
PyArrayObject *vtpy_as_rows(PyObject *obj, const char *name, int n);
size_t vtpy_row_stride(PyArrayObject *a);

/* model.c */
PyObject *vtpy_model_new(vt_model *m);
PyObject *vtpy_load_urdf(PyObject *mod, PyObject *args, PyObject *kw);

/* contacts.c */
PyObject *vtpy_model_contacts(ModelObject *self, PyObject *args, PyObject *kw);

/* frames.c */
PyObject *vtpy_frame_poses(ModelObject *self, PyObject *args, PyObject *kw);
/* what (an argument's name): None (every frame) or frame names as indices (a new array of *n,
 * PyMem_Free), or NULL with ValueError naming the argument (frames.c) */
int *vtpy_frame_indices(const vt_model *m, PyObject *o, int *n, const char *what);

/* analysis.c */
PyObject *vtpy_kinematic_analysis(ModelObject *self, PyObject *args, PyObject *kw);
PyObject *vtpy_dynamic_analysis(ModelObject *self, PyObject *args, PyObject *kw);

#endif
