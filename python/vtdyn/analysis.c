/* Model.kinematic_analysis and Model.dynamic_analysis: the analyses over time of a model with
 * drives (vt_kinematic_analysis: a fully driven model, Newton-Raphson at each output time;
 * vt_dynamic_analysis: SUNDIALS IDA on the index-1 form of (5), where the drives fix part of
 * the motion), each with its forward check (the drives removed, their efforts applied). The
 * options are vt_run_options's fields as keyword arguments with the C defaults (contacts: a
 * ContactSet; active: a Python function of t for the contact schedule; loads with load_frames:
 * wrenches at frames, constant or a Python function of t); the run has its
 * own vt_data and vt_trajectory, made, run and freed with the GIL released (the Model is only
 * read, so runs on one Model proceed in parallel). The trajectory's column-major arrays (one
 * column a row) are copied into row-major NumPy arrays of the rows the run filled: the Trajectory
 * struct sequence. */
#include "vtdyn_py.h"

PyTypeObject vtpy_trajectory_type;

enum { /* the Trajectory's fields, in order */
    T_TIME, T_Q, T_QD, T_QDD, T_LAMBDA, T_QFRC, T_DEFF, T_DFORCE, T_DMOMENT, T_REACTION, T_CUT, T_PHI, T_PHID, T_RCOND,
    T_NWARN, T_TWARN, T_QFWD, T_QDFWD, T_REACTION_FWD, T_CUT_FWD, T_ERR_Q, T_ERR_QD, T_ERR_FORCE, T_ERR_MOMENT,
    T_INTERP, T_STEPS, T_RES, T_STEPS_FWD, T_RES_FWD, T_WROW, T_WQ, T_WQD, T_WFORCE, T_WMOMENT, T_CONTACT, T_COUNT
};

static PyStructSequence_Field trajectory_fields[] = {
    {"time", "s, the output times (n)"},
    {"q", "the driven run's coordinates (n x nq)"},
    {"qd", "its rates (n x nv)"},
    {"qdd", "its accelerations (n x nv)"},
    {"lambda_", "the constraint rows' multipliers (n x nc): drives, cut joints, couplings, base bodies"},
    {"qfrc_drive", "the drives' generalized force Phi_q^T lambda a rate, N m or N (n x nv)"},
    {"drive_effort", "each drive's effort, N m or N (n x ndrive)"},
    {"drive_force", "the force each drive exerts on its body, N, world axes (n x ndrive x 3)"},
    {"drive_moment", "its moment about the drive's point, N m, world axes (n x ndrive x 3)"},
    {"reaction", "each body's joint reaction, force then moment about the joint point, world axes (n x nbody x 6)"},
    {"cut_reaction", "each cut joint's reaction on body_b, force then moment about point_b, world axes (n x ncut x 6)"},
    {"phi_norm", "max |Phi| of the driven run (n)"},
    {"phid_norm", "max |Phi_q qd + Phi_t| of the driven run (n)"},
    {"rcond", "the condition estimate of (5) at each row (n)"},
    {"nwarn", "rows whose solve warned of ill-conditioning"},
    {"t_warn", "s, the first such row's time (nan if none)"},
    {"q_fwd", "the forward check's coordinates (n x nq); None without the forward check"},
    {"qd_fwd", "its rates (n x nv); None without the forward check"},
    {"reaction_fwd", "its joint reactions, as reaction (n x nbody x 6); None without the forward check"},
    {"cut_reaction_fwd", "its cut joints' reactions (n x ncut x 6); None without the forward check"},
    {"fwd_err_q", "max |q_fwd - q| over the rows"},
    {"fwd_err_qd", "max |qd_fwd - qd|"},
    {"fwd_err_force", "max difference of the reaction forces, forward less driven, N"},
    {"fwd_err_moment", "the same for the reaction moments, N m"},
    {"fwd_interp_err", "independent forward check: the interpolated driven state's largest error"},
    {"steps", "IDA steps of the driven run (0 for a kinematic analysis)"},
    {"res_evals", "IDA residual evaluations of the driven run"},
    {"steps_fwd", "IDA steps of the forward check"},
    {"res_evals_fwd", "its residual evaluations"},
    {"fwd_window_row", "the row each forward-check window restarts from (nwindow, int64)"},
    {"fwd_window_err_q", "each window's max |q_fwd - q| (nwindow)"},
    {"fwd_window_err_qd", "each window's max |qd_fwd - qd| (nwindow)"},
    {"fwd_window_err_force", "each window's max reaction force difference, N (nwindow)"},
    {"fwd_window_err_moment", "each window's max reaction moment difference, N m (nwindow)"},
    {"contact_force", "the ground's force at each contact, N, world axes (n x ncontact x 3); None without contacts"},
    {NULL, NULL},
};

PyStructSequence_Desc vtpy_trajectory_desc = {
    "vtdyn.Trajectory",
    "The results of Model.kinematic_analysis and Model.dynamic_analysis (vt_trajectory), one row an "
    "output time: NumPy arrays with a leading row axis, and the run's scalars.",
    trajectory_fields, T_COUNT,
};

/* rows x n of a column-major (n x nrow) table, row-major: the columns are the rows */
static PyObject *table(const double *src, int rows, int n)
{
    npy_intp d[2] = {rows, n};
    PyObject *a = vtpy_new_array(2, d);
    if (a && rows && n) memcpy(PyArray_DATA((PyArrayObject *)a), src, (size_t)rows * (size_t)n * sizeof(double));
    return a;
}

/* rows x count x 6 from two tables of 3 a thing and a row (force, moment), skipping `skip` things
 * at the start of each row (the ground's entry of the joint tables) */
static PyObject *wrenches(const double *f, const double *mo, int rows, int count, int skip)
{
    npy_intp d[3] = {rows, count, 6};
    PyObject *a = vtpy_new_array(3, d);
    if (!a) return NULL;
    double *p = PyArray_DATA((PyArrayObject *)a);
    const size_t per = 3 * (size_t)(count + skip);
    for (int k = 0; k < rows; k++)
        for (int i = 0; i < count; i++) {
            memcpy(p + 6 * ((size_t)k * count + i), f + per * k + 3 * (size_t)(i + skip), 3 * sizeof(double));
            memcpy(p + 6 * ((size_t)k * count + i) + 3, mo + per * k + 3 * (size_t)(i + skip), 3 * sizeof(double));
        }
    return a;
}

static PyObject *vector(const double *src, int n)
{
    npy_intp d = n;
    PyObject *a = vtpy_new_array(1, &d);
    if (a && n) memcpy(PyArray_DATA((PyArrayObject *)a), src, (size_t)n * sizeof(double));
    return a;
}

static PyObject *trajectory(const vt_model *m, const vt_trajectory *tr, int forward)
{
    const int n = tr->nfilled, nb = m->nbody;
    PyObject *f[T_COUNT] = {NULL};
    f[T_TIME] = vector(tr->t, n);
    f[T_Q] = table(tr->q, n, m->nq);
    f[T_QD] = table(tr->qd, n, m->nv);
    f[T_QDD] = table(tr->qdd, n, m->nv);
    f[T_LAMBDA] = table(tr->lambda, n, m->nc);
    f[T_QFRC] = table(tr->qfrc_drive, n, m->nv);
    f[T_DEFF] = table(tr->drive_effort, n, m->ndrive);
    npy_intp dd[3] = {n, m->ndrive, 3};
    for (int k = 0; k < 2; k++) { /* drive_force, drive_moment: (3 ndrive x nrow) */
        PyObject *a = vtpy_new_array(3, dd);
        if (a && n && m->ndrive)
            memcpy(PyArray_DATA((PyArrayObject *)a), k ? tr->drive_moment : tr->drive_force,
                   (size_t)n * 3 * (size_t)m->ndrive * sizeof(double));
        f[T_DFORCE + k] = a;
    }
    f[T_REACTION] = wrenches(tr->jnt_force, tr->jnt_moment, n, nb, 1);
    f[T_CUT] = wrenches(tr->cut_force, tr->cut_moment, n, m->ncut, 0);
    f[T_PHI] = vector(tr->phi_norm, n);
    f[T_PHID] = vector(tr->phid_norm, n);
    f[T_RCOND] = vector(tr->rcond, n);
    f[T_NWARN] = PyLong_FromLong(tr->nwarn);
    f[T_TWARN] = PyFloat_FromDouble(tr->t_warn);
    if (forward) {
        f[T_QFWD] = table(tr->q_fwd, n, m->nq);
        f[T_QDFWD] = table(tr->qd_fwd, n, m->nv);
        f[T_REACTION_FWD] = wrenches(tr->jnt_force_fwd, tr->jnt_moment_fwd, n, nb, 1);
        f[T_CUT_FWD] = wrenches(tr->cut_force_fwd, tr->cut_moment_fwd, n, m->ncut, 0);
    } else {
        for (int k = T_QFWD; k <= T_CUT_FWD; k++) f[k] = Py_NewRef(Py_None);
    }
    const double errs[] = {tr->fwd_err_q, tr->fwd_err_qd, tr->fwd_err_force, tr->fwd_err_moment, tr->fwd_interp_err};
    for (int k = 0; k < 5; k++) f[T_ERR_Q + k] = PyFloat_FromDouble(errs[k]);
    const long counts[] = {tr->steps, tr->res_evals, tr->steps_fwd, tr->res_evals_fwd};
    for (int k = 0; k < 4; k++) f[T_STEPS + k] = PyLong_FromLong(counts[k]);
    npy_intp nw = tr->nwindow;
    f[T_WROW] = PyArray_SimpleNew(1, &nw, NPY_INT64);
    if (f[T_WROW])
        for (npy_intp w = 0; w < nw; w++) ((int64_t *)PyArray_DATA((PyArrayObject *)f[T_WROW]))[w] = tr->fwd_window_row[w];
    f[T_WQ] = vector(tr->fwd_window_err_q, tr->nwindow);
    f[T_WQD] = vector(tr->fwd_window_err_qd, tr->nwindow);
    f[T_WFORCE] = vector(tr->fwd_window_err_force, tr->nwindow);
    f[T_WMOMENT] = vector(tr->fwd_window_err_moment, tr->nwindow);
    if (tr->ncontact) {
        npy_intp dc[3] = {n, tr->ncontact, 3};
        PyObject *a = vtpy_new_array(3, dc);
        if (a && n) memcpy(PyArray_DATA((PyArrayObject *)a), tr->contact_force, (size_t)n * 3 * (size_t)tr->ncontact * sizeof(double));
        f[T_CONTACT] = a;
    } else {
        f[T_CONTACT] = Py_NewRef(Py_None);
    }
    PyObject *res = NULL;
    int ok = 1;
    for (int k = 0; k < T_COUNT; k++) ok = ok && f[k];
    if (ok) res = PyStructSequence_New(&vtpy_trajectory_type);
    for (int k = 0; k < T_COUNT; k++) {
        if (res) PyStructSequence_SET_ITEM(res, k, f[k]);
        else Py_XDECREF(f[k]);
    }
    return res;
}

static const char *formulations[] = {"index1", "baumgarte", "projection", "ggl", "ode"};

/* a Python callable as the run's contact schedule: active(t) -> a sequence of ncontact truth
 * values; called with the GIL taken (the run holds none), its first exception kept to raise */
typedef struct {
    PyObject *fn;
    int n;
    PyObject *type, *value, *tb;
} schedule;

static int call_schedule(double t, int *active, void *user)
{
    schedule *s = user;
    const PyGILState_STATE g = PyGILState_Ensure();
    int bad = 1;
    PyObject *r = PyObject_CallFunction(s->fn, "d", t);
    PyObject *seq = r ? PySequence_Fast(r, "active: the schedule returns a sequence of one flag a contact") : NULL;
    if (seq && PySequence_Fast_GET_SIZE(seq) != s->n) {
        char ts[32]; /* PyErr_Format has no %g */
        snprintf(ts, sizeof ts, "%.17g", t);
        PyErr_Format(PyExc_ValueError, "active(%s): %zd flags for %d contacts", ts, PySequence_Fast_GET_SIZE(seq), s->n);
    }
    else if (seq) {
        bad = 0;
        for (int k = 0; k < s->n && !bad; k++) {
            const int v = PyObject_IsTrue(PySequence_Fast_GET_ITEM(seq, k));
            if (v < 0) bad = 1;
            else active[k] = v;
        }
    }
    Py_XDECREF(seq);
    Py_XDECREF(r);
    if (bad && !s->type) PyErr_Fetch(&s->type, &s->value, &s->tb);
    PyErr_Clear();
    PyGILState_Release(g);
    return bad;
}

/* the run's wrenches at frames (loads=, load_frames=): a constant F x 6 array, or a Python callable
 * loads(t) -> F x 6 called with the GIL taken, its first exception kept to raise */
typedef struct {
    PyObject *fn;      /* the callable, or NULL: w constant */
    const double *w;   /* 6 n values (constant) */
    int n;
    PyObject *type, *value, *tb;
} run_loads;

static int call_loads(double t, double *w, void *user)
{
    run_loads *L = user;
    if (!L->fn) {
        memcpy(w, L->w, 6 * (size_t)L->n * sizeof(double));
        return 0;
    }
    const PyGILState_STATE g = PyGILState_Ensure();
    int bad = 1;
    PyObject *r = PyObject_CallFunction(L->fn, "d", t);
    PyArrayObject *x = r ? (PyArrayObject *)PyArray_FromAny(r, PyArray_DescrFromType(NPY_DOUBLE), 1, 2,
                                                            NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED, NULL)
                         : NULL;
    if (x && PyArray_SIZE(x) != 6 * (npy_intp)L->n) {
        char ts[32]; /* PyErr_Format has no %g */
        snprintf(ts, sizeof ts, "%.17g", t);
        PyErr_Format(PyExc_ValueError, "loads(%s): %zd values, expected %d x 6 (a wrench for each of load_frames)", ts,
                     (Py_ssize_t)PyArray_SIZE(x), L->n);
    } else if (x) {
        memcpy(w, PyArray_DATA(x), 6 * (size_t)L->n * sizeof(double));
        bad = 0;
    }
    Py_XDECREF(x);
    Py_XDECREF(r);
    if (bad && !L->type) PyErr_Fetch(&L->type, &L->value, &L->tb);
    PyErr_Clear();
    PyGILState_Release(g);
    return bad;
}

static PyObject *run(ModelObject *self, PyObject *args, PyObject *kw, int dynamic)
{
    static char *kwlist[] = {"t1", "nout", "t0", "tout", "q", "qd", "rtol", "atol", "max_step", "max_steps",
                             "newton_tol", "newton_maxit", "forward_check", "forward_independent", "forward_as_loads",
                             "formulation", "baumgarte_alpha", "baumgarte_beta", "history_steps", "redundant_band",
                             "check_window", "contacts", "active", "loads", "load_frames", NULL};
    vt_run_options opt = vt_default_run_options();
    PyObject *otout = NULL, *oq = NULL, *oqd = NULL, *oform = NULL, *ocontacts = NULL, *oactive = NULL;
    PyObject *oloads = NULL, *olf = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, dynamic ? "d|id$OOOdddldipppOddiddOOOO:dynamic_analysis"
                                                       : "d|id$OOOdddldipppOddiddOOOO:kinematic_analysis",
                                     kwlist, &opt.t1, &opt.nout, &opt.t0, &otout, &oq, &oqd, &opt.rtol, &opt.atol,
                                     &opt.max_step, &opt.max_steps, &opt.newton_tol, &opt.newton_maxit,
                                     &opt.forward_check, &opt.forward_independent, &opt.forward_as_loads, &oform,
                                     &opt.baumgarte_alpha, &opt.baumgarte_beta, &opt.history_steps,
                                     &opt.redundant_band, &opt.check_window, &ocontacts, &oactive, &oloads, &olf))
        return NULL;
    if (oloads == Py_None) oloads = NULL;
    if (olf == Py_None) olf = NULL;
    if (!oloads != !olf)
        return PyErr_Format(PyExc_ValueError, "%s given without %s: loads (F x 6, or a function of t giving them: "
                            "force, then moment about the frame's origin, world axes) and load_frames (F frame "
                            "names) go together", oloads ? "loads" : "load_frames", oloads ? "load_frames" : "loads");
    ContactSetObject *cs = NULL; /* the contact set (its vt_contacts made with the run) */
    if (ocontacts && ocontacts != Py_None) {
        if (!PyObject_TypeCheck(ocontacts, &vtpy_contacts_type) || ((ContactSetObject *)ocontacts)->model != self)
            return PyErr_Format(PyExc_ValueError, "contacts: a ContactSet of this Model (Model.contacts)");
        cs = (ContactSetObject *)ocontacts;
    }
    schedule sch = {.fn = NULL};
    if (oactive && oactive != Py_None) {
        if (!cs || !PyCallable_Check(oactive))
            return PyErr_Format(PyExc_ValueError, "active: a function of t giving one flag a contact, with contacts");
        sch.fn = oactive;
        sch.n = cs->n;
        opt.contact_schedule = call_schedule;
        opt.contact_user = &sch;
    }
#if !VT_HAVE_SUNDIALS
    if (dynamic)
        return vtpy_raise(VT_ERR_BAD_OPTION, "dynamic_analysis: this build has no SUNDIALS IDA (VT_HAVE_SUNDIALS 0)", -1);
#endif
    if (oform && oform != Py_None) {
        int k = 0;
        const char *s = PyUnicode_Check(oform) ? PyUnicode_AsUTF8(oform) : NULL;
        while (s && k < VT_FORMULATION_COUNT && strcmp(s, formulations[k])) k++;
        if (!s || k == VT_FORMULATION_COUNT)
            return PyErr_Format(PyExc_ValueError,
                                "formulation: %R, expected 'index1', 'baumgarte', 'projection', 'ggl' or 'ode'", oform);
        opt.formulation = k;
    }
    const vt_model *m = self->m;
    PyArrayObject *q = NULL, *qd = NULL, *tout = NULL, *lw = NULL;
    PyObject *res = NULL;
    run_loads lds = {.fn = NULL};
    int *lframe = NULL;
    if (oloads) {
        if (!(lframe = vtpy_frame_indices(m, olf, &lds.n, "load_frames"))) goto done;
        if (lds.n > VT_RUN_LOADS_MAX) {
            PyErr_Format(PyExc_ValueError, "load_frames: %d frames, at most %d", lds.n, VT_RUN_LOADS_MAX);
            goto done;
        }
        if (PyCallable_Check(oloads)) {
            lds.fn = oloads;
        } else {
            lw = (PyArrayObject *)PyArray_FromAny(oloads, PyArray_DescrFromType(NPY_DOUBLE), 0, 0,
                                                  NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | NPY_ARRAY_NOTSWAPPED, NULL);
            if (!lw || PyArray_NDIM(lw) != 2 || PyArray_DIMS(lw)[0] != lds.n || PyArray_DIMS(lw)[1] != 6) {
                PyErr_Clear();
                PyErr_Format(PyExc_ValueError, "loads: expected %d x 6 (a wrench for each of the %d load_frames), or "
                             "a function of t giving them", lds.n, lds.n);
                goto done;
            }
            lds.w = PyArray_DATA(lw);
        }
        opt.nload = lds.n;
        opt.load_frame = lframe;
        opt.loads = call_loads;
        opt.load_user = &lds;
    }
    if (oq && oq != Py_None && !(q = vtpy_as_rows(oq, "q", m->nq))) goto done;
    if (oqd && oqd != Py_None && !(qd = vtpy_as_rows(oqd, "qd", m->nv))) goto done;
    if ((q && PyArray_NDIM(q) != 1) || (qd && PyArray_NDIM(qd) != 1)) {
        PyErr_Format(PyExc_ValueError, "%s: one state (1-D), the run's start", q && PyArray_NDIM(q) != 1 ? "q" : "qd");
        goto done;
    }
    if (otout && otout != Py_None) {
        const Py_ssize_t n = PyObject_Size(otout);
        if (n < 1 || n >= INT_MAX) {
            PyErr_Clear();
            PyErr_SetString(PyExc_ValueError, "tout: a 1-D array of one output time or more");
            goto done;
        }
        if (!(tout = vtpy_as_rows(otout, "tout", (int)n))) goto done;
        if (PyArray_NDIM(tout) != 1) {
            PyErr_SetString(PyExc_ValueError, "tout: a 1-D array of output times");
            goto done;
        }
        opt.tout = PyArray_DATA(tout);
        opt.ntout = (int)n;
    }
    const int nrow = opt.tout ? opt.ntout + 1 : (opt.nout >= 1 && opt.nout < INT_MAX ? opt.nout + 1 : 1);
    vt_data *d = NULL;
    vt_trajectory *tr = NULL;
    vt_contacts *c = NULL;
    vt_status st;
    char msg[VT_MESSAGE_SIZE] = "";
    Py_BEGIN_ALLOW_THREADS
    st = vt_data_create(&d, m);
    if (!st && cs) st = vt_contacts_create(&c, m, cs->defs, cs->n, cs->effort_weight, msg);
    if (!st) st = c ? vt_trajectory_create_contacts(&tr, m, c, nrow) : vt_trajectory_create(&tr, m, nrow);
    opt.contacts = c;
    if (!st) {
        if (q) memcpy(d->q, PyArray_DATA(q), (size_t)m->nq * sizeof(double));
        if (qd) memcpy(d->qd, PyArray_DATA(qd), (size_t)m->nv * sizeof(double));
        d->time = opt.t0;
#if VT_HAVE_SUNDIALS
        st = dynamic ? vt_dynamic_analysis(m, d, &opt, tr) : vt_kinematic_analysis(m, d, &opt, tr);
#else
        st = vt_kinematic_analysis(m, d, &opt, tr);
#endif
        if (st) snprintf(msg, sizeof msg, "%s", d->message);
    }
    Py_END_ALLOW_THREADS
    if (sch.type || lds.type) { /* the schedule's or the loads' own exception, not the run's VT_ERR_CALLBACK */
        if (sch.type) {
            PyErr_Restore(sch.type, sch.value, sch.tb);
            Py_XDECREF(lds.type);
            Py_XDECREF(lds.value);
            Py_XDECREF(lds.tb);
        } else {
            PyErr_Restore(lds.type, lds.value, lds.tb);
        }
    } else if (st) {
        char text[VT_MESSAGE_SIZE + 64];
        snprintf(text, sizeof text, "%s: %s", dynamic ? "dynamic_analysis" : "kinematic_analysis",
                 msg[0] ? msg : vt_status_string(st));
        vtpy_raise(st, text, -1);
    } else {
        res = trajectory(m, tr, opt.forward_check);
    }
    vt_trajectory_free(tr);
    vt_contacts_free(c);
    vt_data_free(d);
done:
    Py_XDECREF(q);
    Py_XDECREF(qd);
    Py_XDECREF(tout);
    Py_XDECREF(lw);
    PyMem_Free(lframe);
    return res;
}

PyObject *vtpy_kinematic_analysis(ModelObject *self, PyObject *args, PyObject *kw) { return run(self, args, kw, 0); }
PyObject *vtpy_dynamic_analysis(ModelObject *self, PyObject *args, PyObject *kw) { return run(self, args, kw, 1); }
