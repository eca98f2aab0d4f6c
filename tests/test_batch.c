/* src/analysis/batch.c: a batch's rows bitwise those of vt_inverse_dynamics_motion() called on
 * each state alone (on a data of its own), on 1, 2 and 8 threads: a random tree with free joints
 * (q in a wider table: strides), the RUSR four-bar (a loop: the drive's effort and the solved
 * q̈), failing rows in the middle (reported by index, status and message, their outputs
 * untouched, the others solved; or the call stopped), a quadruped on its contacts (against
 * vt_inverse_dynamics_contacts() alone), wrenches at frames (against the single call with them
 * in xfrc), the arguments refused before any row, and one batch
 * called 300 times in turn (its workers asleep between some calls, spinning between others), and
 * vt_batch_run (the caller's own work on the batch's threads: every item once; a call on the
 * batch from inside its work refused), and a batch
 * whose threads the system refuses in part (fewer threads, the same rows). */
#define _GNU_SOURCE /* nanosleep; pthread_getattr_default_np: the threads' stack size */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "vt_test.h"

#define NROW 203 /* not a multiple of the threads */

/* the batch's outputs of one call */
typedef struct {
    double *effort, *drive_effort, *qdd, *reaction, *reaction_body, *total, *total_body, *reaction_joint, *bearing,
        *excess, *parts;
    int *status;
} outputs;

static void outputs_alloc(outputs *o, const vt_model *m, int nrow)
{
    const size_t nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody, nd = m->ndrive > 0 ? (size_t)m->ndrive : 1;
    o->effort = calloc(nv * (size_t)nrow, sizeof(double));
    o->drive_effort = calloc(nd * (size_t)nrow, sizeof(double));
    o->qdd = calloc(nv * (size_t)nrow, sizeof(double));
    o->reaction = calloc(nb6 * (size_t)nrow, sizeof(double));
    o->reaction_body = calloc(nb6 * (size_t)nrow, sizeof(double));
    o->total = calloc(nb6 * (size_t)nrow, sizeof(double));
    o->total_body = calloc(nb6 * (size_t)nrow, sizeof(double));
    o->reaction_joint = calloc(nb6 * (size_t)nrow, sizeof(double));
    o->bearing = calloc(4 * (size_t)m->nbody * (size_t)nrow, sizeof(double));
    o->excess = calloc(3 * nv * (size_t)nrow, sizeof(double));
    o->parts = calloc(3 * nv * (size_t)nrow, sizeof(double));
    o->status = calloc((size_t)nrow, sizeof(int));
    assert_non_null(o->status);
}

static void outputs_free(outputs *o)
{
    free(o->effort);
    free(o->drive_effort);
    free(o->qdd);
    free(o->reaction);
    free(o->reaction_body);
    free(o->total);
    free(o->total_body);
    free(o->reaction_joint);
    free(o->bearing);
    free(o->excess);
    free(o->parts);
    free(o->status);
}

static void outputs_fill(outputs *o, const vt_model *m, int nrow, double v)
{
    const size_t nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody, nd = m->ndrive > 0 ? (size_t)m->ndrive : 1;
    for (size_t k = 0; k < nv * (size_t)nrow; k++) o->effort[k] = o->qdd[k] = v;
    for (size_t k = 0; k < 3 * nv * (size_t)nrow; k++) o->excess[k] = v;
    for (size_t k = 0; k < 4 * (size_t)m->nbody * (size_t)nrow; k++) o->bearing[k] = v;
    for (size_t k = 0; k < nd * (size_t)nrow; k++) o->drive_effort[k] = v;
    for (size_t k = 0; k < nb6 * (size_t)nrow; k++) o->reaction[k] = o->reaction_body[k] = o->total[k] = o->total_body[k] = o->reaction_joint[k] = v;
}

static vt_batch_io io_of(const outputs *o, int nrow, const double *q, size_t q_stride, const double *qd,
                         const double *qdd)
{
    vt_batch_io io = {0};
    io.nrow = nrow;
    io.q = q;
    io.q_stride = q_stride;
    io.qd = qd;
    io.qdd = qdd;
    io.effort = o->effort;
    io.drive_effort = o->drive_effort;
    io.qdd_out = o->qdd;
    io.reaction = o->reaction;
    io.reaction_body = o->reaction_body;
    io.total = o->total;
    io.total_body = o->total_body;
    io.reaction_joint = o->reaction_joint;
    io.bearing = o->bearing;
    io.limit_excess = o->excess;
    io.effort_parts = o->parts;
    io.status = o->status;
    return io;
}

/* two doubles the same bits (NaN never expected here) */
static int same(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* row r of the batch's outputs against vt_inverse_dynamics_motion on a fresh data, with nl loads
 * w (6 each) at frames put into xfrc by vt_add_frame_load() after vt_kinematics(): bitwise */
static void check_row_loaded(const vt_model *m, const outputs *o, int r, const double *q, const double *qd,
                             const double *qdd, int nl, const int *frame, const double *w)
{
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    const int nv = m->nv, nb = m->nbody;
    memcpy(d->q, q, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, qd, (size_t)nv * sizeof(double));
    memcpy(d->qdd, qdd, (size_t)nv * sizeof(double));
    if (nl > 0) assert_ok(vt_kinematics(m, d));
    for (int k = 0; k < nl; k++) assert_ok(vt_add_frame_load(m, d, frame[k], w + 6 * k, w + 6 * k + 3));
    assert_ok(vt_inverse_dynamics_motion(m, d));
    assert_ok(vt_reactions_joint_frame(m, d));
    assert_int_equal(o->status[r], VT_OK);
    for (int k = 0; k < nv; k++) {
        assert_true(same(o->effort[(size_t)r * nv + k], d->qfrc_drive[k]));
        assert_true(same(o->qdd[(size_t)r * nv + k], d->qdd[k]));
        const double *p = o->parts + (size_t)r * 3 * nv;
        assert_true(same(p[k], d->effort_armature[k]) && same(p[nv + k], d->effort_damping[k]) &&
                    same(p[2 * nv + k], d->effort_friction[k]));
    }
    for (int k = 0; k < m->ndrive; k++) assert_true(same(o->drive_effort[(size_t)r * m->ndrive + k], d->drive_effort[k]));
    for (int i = 1; i <= nb; i++)
        for (int c = 0; c < 3; c++) {
            const size_t at = (size_t)r * 6 * nb + 6 * (size_t)(i - 1) + c;
            assert_true(same(o->reaction[at], d->jnt_force[3 * i + c]));
            assert_true(same(o->reaction[at + 3], d->jnt_moment[3 * i + c]));
            assert_true(same(o->reaction_body[at], d->jnt_force_body[3 * i + c]));
            assert_true(same(o->reaction_body[at + 3], d->jnt_moment_body[3 * i + c]));
            assert_true(same(o->total[at], d->jnt_force_total[3 * i + c]));
            assert_true(same(o->total[at + 3], d->jnt_moment_total[3 * i + c]));
            assert_true(same(o->total_body[at], d->jnt_force_total_body[3 * i + c]));
            assert_true(same(o->total_body[at + 3], d->jnt_moment_total_body[3 * i + c]));
            assert_true(same(o->reaction_joint[at], d->jnt_force_joint[3 * i + c]));
            assert_true(same(o->reaction_joint[at + 3], d->jnt_moment_joint[3 * i + c]));
        }
    for (int k = 0; k < 4 * nb; k++) assert_true(same(o->bearing[(size_t)r * 4 * nb + k], d->jnt_bearing[4 + k]));
    for (int k = 0; k < 3 * nv; k++) assert_true(same(o->excess[(size_t)r * 3 * nv + k], d->limit_excess[k]));
    vt_data_free(d);
}

/* row r of the batch's outputs against vt_inverse_dynamics_motion on a fresh data: bitwise */
static void check_row(const vt_model *m, const outputs *o, int r, const double *q, const double *qd, const double *qdd)
{
    check_row_loaded(m, o, r, q, qd, qdd, 0, NULL, NULL);
}

/* a batch of m on that many threads, stopping at a failure or not */
static vt_batch *batch_of(const vt_model *m, int threads, int stop_on_error)
{
    vt_batch_def def = vt_default_batch_def();
    def.threads = threads;
    def.stop_on_error = stop_on_error;
    vt_batch *b = NULL;
    assert_ok(vt_batch_create(&b, m, &def));
    return b;
}

/* NROW random states of m: q in rows of qs ≥ nq doubles (NaN beside each row: never read), q̇,
 * and q̈ uniform in [−3, 3] */
typedef struct {
    double *q, *qd, *qdd;
    size_t qs;
} states;

static states random_states(const vt_model *m, uint64_t seed, size_t qs)
{
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    const int nq = m->nq, nv = m->nv;
    states st = {malloc(qs * NROW * sizeof(double)), malloc((size_t)nv * NROW * sizeof(double)),
                 malloc((size_t)nv * NROW * sizeof(double)), qs};
    assert_non_null(st.qdd);
    for (int r = 0; r < NROW; r++) {
        vt_scene_random_state(m, d, &seed);
        memcpy(st.q + r * qs, d->q, (size_t)nq * sizeof(double));
        for (size_t c = (size_t)nq; c < qs; c++) st.q[r * qs + c] = NAN;
        memcpy(st.qd + (size_t)r * nv, d->qd, (size_t)nv * sizeof(double));
        for (int k = 0; k < nv; k++) st.qdd[(size_t)r * nv + k] = vt_rand_uniform(&seed, -3.0, 3.0);
    }
    vt_data_free(d);
    return st;
}

static void states_free(states *st)
{
    free(st->q);
    free(st->qd);
    free(st->qdd);
}

/* a random tree with free joints: NROW random states, q in a table 3 columns wider than nq */
static void test_tree_bitwise(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_random_tree(&m, 11, 9, VT_SCENE_WITH_FREE));
    const int nv = m->nv;
    const size_t qs = (size_t)m->nq + 3;
    states st = random_states(m, 3, qs);
    double *q = st.q, *qd = st.qd, *qdd = st.qdd;
    const int threads[3] = {1, 2, 8};
    for (int t = 0; t < 3; t++) {
        vt_batch *b = batch_of(m, threads[t], 0);
        assert_int_equal(vt_batch_threads(b), threads[t]);
        outputs o;
        outputs_alloc(&o, m, NROW);
        vt_batch_io io = io_of(&o, NROW, q, qs, qd, qdd);
        assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
        assert_int_equal(vt_batch_failed_row(b), -1);
        assert_string_equal(vt_batch_message(b), "");
        for (int r = 0; r < NROW; r++) check_row(m, &o, r, q + r * qs, qd + (size_t)r * nv, qdd + (size_t)r * nv);
        outputs_free(&o);
        vt_batch_free(b);
    }
    states_free(&st);
    vt_model_free(m);
}

/* the RUSR four-bar, crank given: the drive's effort and the solved q̈ of the loop */
static void test_loop_bitwise(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_fourbar_rusr(&m, vt_function_constant(0.0)));
    assert_ok(vt_data_create(&d, m));
    const int nq = m->nq, nv = m->nv, n = 60;
    double *q = malloc((size_t)nq * n * sizeof(double)), *qd = malloc((size_t)nv * n * sizeof(double)),
           *qdd = calloc((size_t)nv * n, sizeof(double));
    for (int r = 0; r < n; r++) {
        assert_int_equal(vt_scene_fourbar_rusr_assemble(m, d, 0.1 * r, 1.0 + 0.05 * r, NULL, NULL), 0);
        memcpy(q + (size_t)r * nq, d->q, (size_t)nq * sizeof(double));
        memcpy(qd + (size_t)r * nv, d->qd, (size_t)nv * sizeof(double));
        qdd[(size_t)r * nv + m->body_vadr[1]] = 0.3 * sin(0.2 * r); /* the crank's: the others solved */
    }
    for (int threads = 1; threads <= 8; threads *= 2) {
        vt_batch *b = batch_of(m, threads, 0);
        outputs o;
        outputs_alloc(&o, m, n);
        vt_batch_io io = io_of(&o, n, q, 0, qd, qdd);
        assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
        for (int r = 0; r < n; r++) check_row(m, &o, r, q + (size_t)r * nq, qd + (size_t)r * nv, qdd + (size_t)r * nv);
        outputs_free(&o);
        vt_batch_free(b);
    }
    free(q);
    free(qd);
    free(qdd);
    vt_data_free(d);
    vt_model_free(m);
}

/* the knee four-bar with armature, damping and friction on its joints, both drives given: the
 * efforts' parts as the single call's, and not all zero */
static void test_effects_bitwise(void **state)
{
    (void)state;
    static const double mass[4] = {1.5, 0.1, 0.08, 0.5}, effects[4][3] = {{0.2, 1.0, 0.5}, {0.1, 0.4, 0.2}, {0, 0, 0}, {0, 0.3, 0.1}};
    vt_model *m = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_knee_with(&m, vt_function_constant(-0.8), vt_function_constant(1.4), 1, mass, 3, effects));
    assert_ok(vt_data_create(&d, m));
    const int nq = m->nq, nv = m->nv, n = 40;
    double *q = malloc((size_t)nq * n * sizeof(double)), *qd = malloc((size_t)nv * n * sizeof(double)),
           *qdd = calloc((size_t)nv * n, sizeof(double));
    for (int r = 0; r < n; r++) {
        assert_int_equal(vt_scene_knee_assemble(m, d, -0.8 + 0.01 * r, 0.5 - 0.03 * r, 1.4 - 0.005 * r, 0.7, NULL), 0);
        memcpy(q + (size_t)r * nq, d->q, (size_t)nq * sizeof(double));
        memcpy(qd + (size_t)r * nv, d->qd, (size_t)nv * sizeof(double));
        qdd[(size_t)r * nv] = 0.3 * sin(0.2 * r), qdd[(size_t)r * nv + 1] = -0.2 * r; /* the driven rates' */
    }
    vt_batch *b = batch_of(m, 2, 0);
    outputs o;
    outputs_alloc(&o, m, n);
    vt_batch_io io = io_of(&o, n, q, 0, qd, qdd);
    assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
    double most = 0.0;
    for (int r = 0; r < n; r++) {
        check_row(m, &o, r, q + (size_t)r * nq, qd + (size_t)r * nv, qdd + (size_t)r * nv);
        for (int k = 0; k < 3 * nv; k++) most = fmax(most, fabs(o.parts[(size_t)r * 3 * nv + k]));
    }
    assert_true(most > 0.1);
    outputs_free(&o);
    vt_batch_free(b);
    free(q);
    free(qd);
    free(qdd);
    vt_data_free(d);
    vt_model_free(m);
}

/* rows 37 and 101 with a NaN: reported (the lowest first), their outputs untouched, the others
 * solved bitwise; with stop_on_error on one thread the rows after 37 are skipped */
static void test_failing_rows(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_random_tree(&m, 5, 6, VT_SCENE_NO_BASE));
    const int nq = m->nq, nv = m->nv;
    states st = random_states(m, 9, (size_t)nq);
    double *q = st.q, *qd = st.qd, *qdd = st.qdd;
    q[37 * (size_t)nq] = NAN;
    qdd[101 * (size_t)nv + 1] = INFINITY;
    /* the message the batch gives: row 37's own, whichever thread met it and whatever it solved
     * after (row 101's message differs: another array) */
    char want37[VT_MESSAGE_SIZE + 16], want101[VT_MESSAGE_SIZE];
    vt_data *d1 = NULL;
    assert_ok(vt_data_create(&d1, m));
    memcpy(d1->q, q + 101 * (size_t)nq, (size_t)nq * sizeof(double));
    memcpy(d1->qd, qd + 101 * (size_t)nv, (size_t)nv * sizeof(double));
    memcpy(d1->qdd, qdd + 101 * (size_t)nv, (size_t)nv * sizeof(double));
    assert_int_equal(vt_inverse_dynamics_motion(m, d1), VT_ERR_NONFINITE);
    snprintf(want101, sizeof want101, "%s", d1->message);
    memcpy(d1->q, q + 37 * (size_t)nq, (size_t)nq * sizeof(double));
    memcpy(d1->qd, qd + 37 * (size_t)nv, (size_t)nv * sizeof(double));
    memcpy(d1->qdd, qdd + 37 * (size_t)nv, (size_t)nv * sizeof(double));
    assert_int_equal(vt_inverse_dynamics_motion(m, d1), VT_ERR_NONFINITE);
    snprintf(want37, sizeof want37, "row 37: %s", d1->message);
    assert_string_not_equal(want37 + 8, want101);
    vt_data_free(d1);
    for (int threads = 1; threads <= 8; threads *= 2) {
        vt_batch *b = batch_of(m, threads, 0);
        outputs o;
        outputs_alloc(&o, m, NROW);
        outputs_fill(&o, m, NROW, 42.0);
        vt_batch_io io = io_of(&o, NROW, q, 0, qd, qdd);
        assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NONFINITE);
        assert_int_equal(vt_batch_failed_row(b), 37);
        assert_string_equal(vt_batch_message(b), want37);
        assert_int_equal(o.status[37], VT_ERR_NONFINITE);
        assert_int_equal(o.status[101], VT_ERR_NONFINITE);
        for (int k = 0; k < nv; k++) {
            assert_true(same(o.effort[37 * (size_t)nv + k], 42.0));
            assert_true(same(o.effort[101 * (size_t)nv + k], 42.0));
        }
        for (int k = 0; k < 6 * m->nbody; k++) assert_true(same(o.reaction[101 * 6 * (size_t)m->nbody + k], 42.0));
        for (int k = 0; k < 4 * m->nbody; k++) assert_true(same(o.bearing[101 * 4 * (size_t)m->nbody + k], 42.0));
        for (int k = 0; k < 3 * nv; k++) assert_true(same(o.excess[101 * 3 * (size_t)nv + k], 42.0));
        for (int r = 0; r < NROW; r++)
            if (r != 37 && r != 101) check_row(m, &o, r, q + (size_t)r * nq, qd + (size_t)r * nv, qdd + (size_t)r * nv);
        outputs_free(&o);
        vt_batch_free(b);
    }
    /* stop_on_error, one thread: rows before 37 solved, 37 failed, the rest skipped */
    vt_batch *b = batch_of(m, 1, 1);
    outputs o;
    outputs_alloc(&o, m, NROW);
    vt_batch_io io = io_of(&o, NROW, q, 0, qd, qdd);
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NONFINITE);
    for (int r = 0; r < NROW; r++)
        assert_int_equal(o.status[r], r < 37 ? VT_OK : r == 37 ? VT_ERR_NONFINITE : VT_ERR_SKIPPED);
    vt_batch_free(b);
    /* two threads taking blocks of rows in turn: each stops at a failure, its own or the other's,
     * whichever comes first; the failing row reported is the lowest of those reached, and every
     * row reported solved is right */
    b = batch_of(m, 2, 1);
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NONFINITE);
    const int failed = vt_batch_failed_row(b);
    assert_true(failed == 37 || failed == 101);
    for (int r = 0; r < NROW; r++) {
        const int bad = r == 37 || r == 101;
        assert_true(o.status[r] == VT_ERR_SKIPPED || o.status[r] == (bad ? VT_ERR_NONFINITE : VT_OK));
        if (o.status[r] == VT_OK) check_row(m, &o, r, q + (size_t)r * nq, qd + (size_t)r * nv, qdd + (size_t)r * nv);
        if (r < failed && bad) assert_int_equal(o.status[r], VT_ERR_SKIPPED);
    }
    assert_int_equal(o.status[failed], VT_ERR_NONFINITE);
    vt_batch_free(b);
    outputs_free(&o);
    states_free(&st);
    vt_model_free(m);
}

/* contacts: the quadruped near its stand, each row its own active feet (all, one lifted, a
 * diagonal pair, none: free fall refused) and motion (some it cannot carry): each
 * row's status, efforts, reactions and forces bitwise those of vt_inverse_dynamics_contacts()
 * alone, on 1, 2 and 8 threads; a refused row's forces untouched */
/* NROW states of the quadruped near its stand (a random height), q̇ uniform in [−0.5, 0.5] and q̈
 * in [−1, 1] times root (the root's three translations) or joints (the other rates) */
static void quadruped_states(const vt_model *m, vt_data *d, uint64_t *seed, double root, double joints, double *q,
                             double *qd, double *qdd)
{
    const int nq = m->nq, nv = m->nv;
    for (int r = 0; r < NROW; r++) {
        vt_scene_quadruped_stand(m, d, 0.5 + 0.2 * vt_rand_uniform(seed, 0, 1));
        memcpy(q + (size_t)r * nq, d->q, (size_t)nq * sizeof(double));
        for (int a = 0; a < nv; a++) {
            qd[(size_t)r * nv + a] = vt_rand_uniform(seed, -0.5, 0.5);
            qdd[(size_t)r * nv + a] = vt_rand_uniform(seed, -1.0, 1.0) * (a < 3 ? root : joints);
        }
    }
}

static void test_contacts_bitwise(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_quadruped(&m));
    const int nq = m->nq, nv = m->nv, nb6 = 6 * m->nbody;
    vt_contact_def def[4];
    static const char *const feet[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};
    for (int k = 0; k < 4; k++) {
        def[k] = vt_default_contact_def();
        def[k].frame = feet[k];
        def[k].mu = 0.6;
    }
    double *q = malloc((size_t)NROW * (size_t)nq * sizeof(double)), *qd = malloc((size_t)NROW * (size_t)nv * sizeof(double)),
           *qdd = malloc((size_t)NROW * (size_t)nv * sizeof(double));
    int *active = malloc((size_t)NROW * 4 * sizeof(int));
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    uint64_t seed = 17;
    quadruped_states(m, d, &seed, 1.5, 0.5, q, qd, qdd);
    for (int r = 0; r < NROW; r++) {
        /* all four feet, one front foot lifted (either), a trot's diagonal pair, none */
        static const int pattern[5][4] = {{1, 1, 1, 1}, {0, 1, 1, 1}, {1, 0, 1, 1}, {0, 1, 1, 0}, {0, 0, 0, 0}};
        for (int k = 0; k < 4; k++) active[4 * r + k] = pattern[r % 5][k];
    }
    /* the rows one by one */
    vt_contacts *c = NULL;
    assert_ok(vt_contacts_create(&c, m, def, 4, NULL, NULL));
    int *st1 = malloc(NROW * sizeof(int));
    double *e1 = malloc((size_t)NROW * (size_t)nv * sizeof(double)), *r1 = malloc((size_t)NROW * (size_t)nb6 * sizeof(double)),
           *f1 = malloc((size_t)NROW * 12 * sizeof(double));
    int ok = 0, refused = 0;
    for (int r = 0; r < NROW; r++) {
        memcpy(d->q, q + (size_t)r * nq, (size_t)nq * sizeof(double));
        memcpy(d->qd, qd + (size_t)r * nv, (size_t)nv * sizeof(double));
        memcpy(d->qdd, qdd + (size_t)r * nv, (size_t)nv * sizeof(double));
        for (int k = 0; k < 12; k++) f1[12 * r + k] = -7.0;
        st1[r] = vt_inverse_dynamics_contacts(m, d, c, active + 4 * r, f1 + 12 * r);
        if (st1[r] == VT_OK) {
            ok++;
            memcpy(e1 + (size_t)r * nv, d->qfrc_drive, (size_t)nv * sizeof(double));
            for (int i = 1; i <= m->nbody; i++) {
                memcpy(r1 + (size_t)r * nb6 + 6 * (i - 1), d->jnt_force + 3 * i, 3 * sizeof(double));
                memcpy(r1 + (size_t)r * nb6 + 6 * (i - 1) + 3, d->jnt_moment + 3 * i, 3 * sizeof(double));
            }
        } else {
            assert_int_equal(st1[r], VT_ERR_CONTACT);
            refused++;
        }
    }
    assert_true(ok > NROW / 4 && refused > 0); /* both kinds of row */
    for (int threads = 1; threads <= 8; threads *= 2) {
        vt_batch_def def_b = vt_default_batch_def();
        def_b.threads = threads;
        def_b.contacts = def;
        def_b.ncontact = 4;
        vt_batch *b = NULL;
        assert_ok(vt_batch_create(&b, m, &def_b));
        double *e = malloc((size_t)NROW * (size_t)nv * sizeof(double)), *re = malloc((size_t)NROW * (size_t)nb6 * sizeof(double)),
               *f = malloc((size_t)NROW * 12 * sizeof(double));
        int *st = malloc(NROW * sizeof(int));
        for (int k = 0; k < NROW * 12; k++) f[k] = -7.0;
        vt_batch_io io = {.nrow = NROW, .q = q, .qd = qd, .qdd = qdd, .effort = e, .reaction = re, .status = st,
                          .contact_active = active, .contact_force = f};
        assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_CONTACT);
        for (int r = 0; r < NROW; r++) {
            assert_int_equal(st[r], st1[r]);
            for (int k = 0; k < 12; k++) assert_true(same(f[12 * r + k], f1[12 * r + k]));
            if (st1[r] != VT_OK) continue;
            for (int a = 0; a < nv; a++) assert_true(same(e[(size_t)r * nv + a], e1[(size_t)r * nv + a]));
            for (int k = 0; k < nb6; k++) assert_true(same(re[(size_t)r * nb6 + k], r1[(size_t)r * nb6 + k]));
        }
        free(e), free(re), free(f), free(st);
        vt_batch_free(b);
    }
    /* refused definitions: no batch */
    vt_batch_def bad = vt_default_batch_def();
    bad.ncontact = 4;
    vt_batch *b = (vt_batch *)def;
    assert_int_equal(vt_batch_create(&b, m, &bad), VT_ERR_BAD_OPTION);
    assert_null(b);
    def[2].frame = "no_such_foot";
    bad.contacts = def;
    assert_int_equal(vt_batch_create(&b, m, &bad), VT_ERR_NOT_FOUND);
    assert_null(b);
    vt_contacts_free(c);
    free(st1), free(e1), free(r1), free(f1), free(active), free(q), free(qd), free(qdd);
    vt_data_free(d);
    vt_model_free(m);
}

/* refusals before any row: nothing written */
static void test_arguments(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_double_link(&m, 0));
    vt_batch *b = NULL;
    vt_batch_def def = vt_default_batch_def();
    def.threads = -1;
    assert_int_equal(vt_batch_create(&b, m, &def), VT_ERR_BAD_OPTION);
    assert_null(b);
    def.threads = 0;
    def.stop_on_error = 2;
    assert_int_equal(vt_batch_create(&b, m, &def), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_batch_create(&b, NULL, NULL), VT_ERR_NULL);
    assert_int_equal(vt_batch_create(NULL, m, NULL), VT_ERR_NULL);
    assert_ok(vt_batch_create(&b, m, NULL));
    assert_true(vt_batch_threads(b) >= 1); /* 0: the CPUs counted */
    double q[4] = {0.1, 0.2, 0.3, 0.4}, qd[4] = {0}, qdd[4] = {0}, effort[4] = {7, 7, 7, 7};
    int status[2] = {5, 5};
    vt_batch_io io = {0};
    io.nrow = 2;
    io.q = q;
    io.qd = qd;
    io.qdd = qdd;
    io.effort = effort;
    io.status = status;
    io.effort_stride = 1; /* below nv = 2 */
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_SIZE);
    assert_non_null(strstr(vt_batch_message(b), "effort_stride"));
    io.effort_stride = 0;
    io.qd = NULL;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NULL);
    io.qd = qd;
    io.nrow = -1;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_SIZE);
    for (int k = 0; k < 4; k++) assert_true(same(effort[k], 7.0));
    assert_int_equal(status[0], 5);
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, NULL), VT_ERR_NULL);
    assert_int_equal(vt_batch_inverse_dynamics_motion(NULL, &io), VT_ERR_NULL);
    io.nrow = 0;
    assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
    io.nrow = 2;
    assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
    assert_int_equal(status[0], VT_OK);
    assert_int_equal(status[1], VT_OK);
    vt_batch_free(b);
    vt_batch_free(NULL);
    vt_model_free(m);
}

/* row r of the states into d, the n loads w (6 each) at frames put into xfrc by vt_add_frame_load()
 * at its pose: the single call's way to the loads the batch adds after the instant */
static void loaded_state(const vt_model *m, vt_data *d, const double *q, const double *qd, const double *qdd, int r,
                         int n, const int *frame, const double *w)
{
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv;
    assert_ok(vt_data_reset(m, d));
    memcpy(d->q, q + (size_t)r * nq, nq * sizeof(double));
    memcpy(d->qd, qd + (size_t)r * nv, nv * sizeof(double));
    memcpy(d->qdd, qdd + (size_t)r * nv, nv * sizeof(double));
    assert_ok(vt_kinematics(m, d));
    for (int k = 0; k < n; k++) assert_ok(vt_add_frame_load(m, d, frame[k], w + 6 * k, w + 6 * k + 3));
}

/* wrenches at frames (io->load) on the quadruped's free root and legs: each row against the same
 * state solved alone with the loads put into xfrc by vt_add_frame_load() before the instant (the
 * passes then carry them; the batch adds them after, by linearity: equal to round-off), a foot
 * named twice (the sum); bitwise alike on 1, 2 and 8 threads; a NaN load, and two of 1e308 on
 * one foot whose sum overflows, refuse their row alone;
 * on three feet with a load at the fourth, against vt_inverse_dynamics_contacts() with the load in
 * xfrc (efforts and the ground's forces); loads refused before any row at a frame out of range or
 * on the ground, NULL, or a stride below 6 nload */
static void test_frame_loads(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_quadruped(&m));
    const int nq = m->nq, nv = m->nv, nb6 = 6 * m->nbody, NL = 3;
    int frame[3];
    static const char *const at[3] = {"FL_foot", "HR_foot", "FL_foot"};
    for (int k = 0; k < NL; k++) {
        frame[k] = -1;
        for (int f = 0; f < m->nframe; f++)
            if (strcmp(m->frame_name + (size_t)VT_NAME_MAX * f, at[k]) == 0) frame[k] = f;
        assert_true(frame[k] >= 0);
    }
    double *q = malloc((size_t)NROW * (size_t)nq * sizeof(double)), *qd = malloc((size_t)NROW * (size_t)nv * sizeof(double)),
           *qdd = malloc((size_t)NROW * (size_t)nv * sizeof(double)), *load = malloc((size_t)NROW * 6 * NL * sizeof(double));
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    uint64_t seed = 23;
    quadruped_states(m, d, &seed, 1.0, 1.0, q, qd, qdd);
    for (int k = 0; k < NROW * 6 * NL; k++) load[k] = vt_rand_uniform(&seed, -20.0, 20.0);
    outputs o[3];
    const int threads[3] = {1, 2, 8};
    for (int t = 0; t < 3; t++) {
        vt_batch *b = batch_of(m, threads[t], 0);
        outputs_alloc(&o[t], m, NROW);
        vt_batch_io io = io_of(&o[t], NROW, q, 0, qd, qdd);
        io.nload = NL;
        io.load_frame = frame;
        io.load = load;
        assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
        vt_batch_free(b);
    }
    for (int t = 1; t < 3; t++) /* whatever the threads: the same bits */
        for (int k = 0; k < NROW * nv; k++) assert_true(same(o[t].effort[k], o[0].effort[k]));
    for (int t = 1; t < 3; t++)
        for (int k = 0; k < NROW * nb6; k++)
            assert_true(same(o[t].reaction[k], o[0].reaction[k]) && same(o[t].total_body[k], o[0].total_body[k]));
    double worst = 0.0;
    for (int r = 0; r < NROW; r++) {
        loaded_state(m, d, q, qd, qdd, r, NL, frame, load + (size_t)r * 6 * NL);
        assert_ok(vt_inverse_dynamics_motion(m, d));
        double scale = 1.0;
        for (int a = 0; a < nv; a++) scale = fmax(scale, fabs(d->qfrc_drive[a]));
        for (int a = 0; a < nv; a++) worst = fmax(worst, fabs(o[0].effort[(size_t)r * nv + a] - d->qfrc_drive[a]) / scale);
        for (int i = 1; i <= m->nbody; i++)
            for (int c = 0; c < 3; c++) {
                const double *R = o[0].reaction + (size_t)r * nb6 + 6 * (i - 1), *T = o[0].total_body + (size_t)r * nb6 + 6 * (i - 1);
                worst = fmax(worst, fabs(R[c] - d->jnt_force[3 * i + c]) / scale);
                worst = fmax(worst, fabs(R[3 + c] - d->jnt_moment[3 * i + c]) / scale);
                worst = fmax(worst, fabs(T[c] - d->jnt_force_total_body[3 * i + c]) / scale);
                worst = fmax(worst, fabs(T[3 + c] - d->jnt_moment_total_body[3 * i + c]) / scale);
            }
    }
    printf("frame loads: largest difference from the loads in xfrc %.2e of the row's largest effort\n", worst);
    assert_true(worst < 1e-13);
    for (int t = 0; t < 3; t++) outputs_free(&o[t]);
    /* a NaN load: that row alone refused, named */
    load[(size_t)7 * 6 * NL + 4] = NAN;
    vt_batch *b = batch_of(m, 2, 0);
    outputs_alloc(&o[0], m, NROW);
    vt_batch_io io = io_of(&o[0], NROW, q, 0, qd, qdd);
    io.nload = NL;
    io.load_frame = frame;
    io.load = load;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NONFINITE);
    assert_int_equal(vt_batch_failed_row(b), 7);
    assert_non_null(strstr(vt_batch_message(b), "load"));
    for (int r = 0; r < NROW; r++) assert_int_equal(o[0].status[r], r == 7 ? VT_ERR_NONFINITE : VT_OK);
    /* finite loads whose sum overflows: refused with their row, never Inf with VT_OK */
    load[(size_t)7 * 6 * NL + 4] = 0.0;
    load[(size_t)11 * 6 * NL + 0] = load[(size_t)11 * 6 * NL + 12] = 1e308; /* FL_foot twice: 2e308 */
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NONFINITE);
    assert_int_equal(vt_batch_failed_row(b), 11);
    for (int r = 0; r < NROW; r++) assert_int_equal(o[0].status[r], r == 11 ? VT_ERR_NONFINITE : VT_OK);
    load[(size_t)11 * 6 * NL + 0] = load[(size_t)11 * 6 * NL + 12] = 1.0;
    /* refused before any row, nothing written */
    outputs_fill(&o[0], m, NROW, 7.0);
    int bad[1] = {m->nframe};
    io.load_frame = bad;
    io.nload = 1;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_INDEX);
    bad[0] = -1;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_INDEX);
    io.load_frame = frame;
    io.load = NULL;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NULL);
    io.load = load;
    io.load_stride = 5;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_SIZE);
    assert_non_null(strstr(vt_batch_message(b), "load_stride"));
    io.load_stride = 0;
    io.nload = -1;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_SIZE);
    for (int k = 0; k < NROW * nv; k++) assert_true(same(o[0].effort[k], 7.0));
    vt_batch_free(b);
    /* on three feet, a load at the fourth (a leg pushing): the ground's forces balance it too; each
     * row against vt_inverse_dynamics_contacts() with the load put into xfrc before it */
    for (int r = 0; r < NROW; r++)
        for (int k = 0; k < 6; k++) load[(size_t)r * 6 * NL + k] *= 0.1; /* within what three feet can carry */
    vt_contact_def cd[3];
    static const char *const feet[3] = {"FR_foot", "HL_foot", "HR_foot"};
    for (int k = 0; k < 3; k++) {
        cd[k] = vt_default_contact_def();
        cd[k].frame = feet[k];
    }
    vt_batch_def def = vt_default_batch_def();
    def.contacts = cd;
    def.ncontact = 3;
    def.threads = 2;
    assert_ok(vt_batch_create(&b, m, &def));
    double *force = malloc((size_t)NROW * 9 * sizeof(double));
    io.nload = 1;
    io.load_stride = 6 * NL;
    io.contact_force = force;
    const vt_status bst = vt_batch_inverse_dynamics_motion(b, &io); /* rows the three feet cannot carry fail */
    assert_true(bst == VT_OK || bst == VT_ERR_CONTACT);
    vt_contacts *c = NULL;
    assert_ok(vt_contacts_create(&c, m, cd, 3, NULL, NULL));
    double wc = 0.0;
    int carried = 0;
    for (int r = 0; r < NROW; r++) {
        loaded_state(m, d, q, qd, qdd, r, 1, frame, load + (size_t)r * 6 * NL);
        double f1[9];
        const vt_status st1 = vt_inverse_dynamics_contacts(m, d, c, NULL, f1);
        assert_int_equal(st1, o[0].status[r]); /* carried, or not, alike */
        if (st1) continue;
        carried++;
        double scale = 1.0;
        for (int a = 0; a < nv; a++) scale = fmax(scale, fabs(d->qfrc_drive[a]));
        for (int a = 0; a < nv; a++) wc = fmax(wc, fabs(o[0].effort[(size_t)r * nv + a] - d->qfrc_drive[a]) / scale);
        for (int k = 0; k < 9; k++) wc = fmax(wc, fabs(force[(size_t)r * 9 + k] - f1[k]) / scale);
    }
    printf("frame loads on three feet: %d rows carried, largest difference from the loads in xfrc %.2e\n", carried, wc);
    assert_true(carried >= NROW / 4 && wc < 1e-12);
    free(force);
    vt_contacts_free(c);
    vt_batch_free(b);
    outputs_free(&o[0]);
    vt_data_free(d);
    vt_model_free(m);
    /* at a frame on the ground */
    int zero[1] = {0};
    io = (vt_batch_io){.nrow = 0, .nload = 1, .load_frame = zero, .load = load};
    vt_builder *bl = NULL;
    assert_ok(vt_builder_create(&bl, NULL));
    vt_body_def body = vt_default_body_def();
    assert_true(vt_builder_add_body(bl, &body) == 1);
    vt_frame_def fd = vt_default_frame_def();
    fd.name = "floor";
    fd.body = 0;
    assert_int_equal(vt_builder_add_frame(bl, &fd), 0);
    assert_ok(vt_builder_build(&m, bl));
    vt_builder_free(bl);
    b = batch_of(m, 1, 0);
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_BAD_INDEX);
    assert_non_null(strstr(vt_batch_message(b), "on the ground"));
    vt_batch_free(b);
    vt_model_free(m);
    free(q);
    free(qd);
    free(qdd);
    free(load);
}

/* 3x3 J^T x = b by Cramer's rule (J column-major 3x3); the determinant */
static double solve3t(const double J[9], const double b[3], double x[3])
{
    /* the rows of J^T are J's columns */
    const double *c0 = J, *c1 = J + 3, *c2 = J + 6;
    const double det = c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c0[1] * (c1[0] * c2[2] - c1[2] * c2[0]) +
                       c0[2] * (c1[0] * c2[1] - c1[1] * c2[0]);
    for (int k = 0; k < 3; k++) {
        double M[9];
        memcpy(M, J, sizeof M);
        M[k] = b[0], M[3 + k] = b[1], M[6 + k] = b[2]; /* column k of J^T: row k of J */
        const double *m0 = M, *m1 = M + 3, *m2 = M + 6;
        x[k] = (m0[0] * (m1[1] * m2[2] - m1[2] * m2[1]) - m0[1] * (m1[0] * m2[2] - m1[2] * m2[0]) +
                m0[2] * (m1[0] * m2[1] - m1[1] * m2[0])) / det;
    }
    return det;
}

/* wrenches at the Delta's gripper tip, a loop's given motion (the motors' q̈, the dense stages):
 * each row bitwise as the single call with the loads put into xfrc by vt_add_frame_load() after
 * vt_kinematics(), on 1, 2 and 8 threads; and the motors' torques less the unloaded batch's
 * against the statics of the Delta's closed-form inverse kinematics: with θ̇ = J ṗ (J = ∂θ/∂p,
 * vt_scene_delta_motor's θ̇ at unit ṗ) the loads' power f·ṗ is the motors' −Δτ·θ̇ for every ṗ,
 * Δτ = −J^-T f. The platform only translates, so neither the moment nor the tip's lever arm
 * below the platform reaches a motor (they load the parallelograms' reactions). Two loads whose
 * sum overflows refuse their row alone, and the rows after it on the same data are the single
 * call's (xfrc put back) */
static void test_loop_loads(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_delta(&m, 2.0, VT_DELTA_MOTORS));
    assert_ok(vt_data_create(&d, m));
    assert_true(m->nframe == 1 && strcmp(m->frame_name, "tool") == 0);
    const int nq = m->nq, nv = m->nv, n = 24, tool[1] = {0};
    double *q = malloc((size_t)nq * n * sizeof(double)), *qd = calloc((size_t)nv * n, sizeof(double)),
           *qdd = calloc((size_t)nv * n, sizeof(double)), *load = malloc(6 * (size_t)n * sizeof(double)),
           *pos = malloc(3 * (size_t)n * sizeof(double));
    uint64_t seed = 41;
    for (int r = 0; r < n; r++) {
        double *p = pos + 3 * r;
        vt_scene_delta_path(0.09 * r, 2.0, p, NULL, NULL);
        assert_int_equal(vt_scene_delta_assemble(m, d, p), 0);
        memcpy(q + (size_t)r * nq, d->q, (size_t)nq * sizeof(double));
        for (int i = 0; i < 3; i++) qdd[(size_t)r * nv + m->body_vadr[1 + i]] = vt_rand_uniform(&seed, -3.0, 3.0);
        for (int k = 0; k < 6; k++) load[6 * r + k] = vt_rand_uniform(&seed, -40.0, 40.0);
    }
    outputs o[3], bare;
    const int threads[3] = {1, 2, 8};
    for (int t = 0; t < 3; t++) {
        vt_batch *b = batch_of(m, threads[t], 0);
        outputs_alloc(&o[t], m, n);
        vt_batch_io io = io_of(&o[t], n, q, 0, qd, qdd);
        io.nload = 1;
        io.load_frame = tool;
        io.load = load;
        assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
        if (t == 0) {
            outputs_alloc(&bare, m, n);
            io = io_of(&bare, n, q, 0, qd, qdd);
            assert_ok(vt_batch_inverse_dynamics_motion(b, &io));
        }
        vt_batch_free(b);
        for (int r = 0; r < n; r++) check_row_loaded(m, &o[t], r, q + (size_t)r * nq, qd + (size_t)r * nv, qdd + (size_t)r * nv, 1, tool, load + 6 * r);
    }
    double worst = 0.0, moved = 0.0;
    for (int r = 0; r < n; r++) {
        double J[9], th[3], e[3] = {0, 0, 0}, zero[3] = {0, 0, 0}, dtau[3];
        for (int k = 0; k < 3; k++) { /* column k: θ̇ for ṗ = e_k */
            e[k] = 1.0;
            for (int i = 0; i < 3; i++) {
                assert_int_equal(vt_scene_delta_motor(i, pos + 3 * r, e, zero, th), 0);
                J[3 * k + i] = th[1];
                if (k == 0) /* the assembly's motor angle is the closed form's */
                    assert_true(fabs(q[(size_t)r * nq + m->body_qadr[1 + i]] - th[0]) < 1e-12);
            }
            e[k] = 0.0;
        }
        const double f[3] = {-load[6 * r], -load[6 * r + 1], -load[6 * r + 2]};
        assert_true(fabs(solve3t(J, f, dtau)) > 1e-3);
        double scale = 1.0;
        for (int i = 0; i < 3; i++) scale = fmax(scale, fabs(dtau[i]));
        for (int i = 0; i < 3; i++) {
            const size_t at = (size_t)r * nv + m->body_vadr[1 + i];
            worst = fmax(worst, fabs(o[0].effort[at] - bare.effort[at] - dtau[i]) / scale);
            moved = fmax(moved, fabs(o[0].effort[at] - bare.effort[at]) / scale);
        }
    }
    printf("Delta, a wrench at the tool: the motors' torques less the unloaded ones against -J^-T f: %.2e\n", worst);
    assert_true(worst < 1e-12 && moved > 0.1);
    /* the tool named twice, row 5's two forces 1e308 each: their sum overflows, that row alone is
     * refused, and the rows after it on the same data (one thread) are the single call's: xfrc
     * was put back */
    double *load2 = malloc(12 * (size_t)n * sizeof(double));
    for (int r = 0; r < n; r++) memcpy(load2 + 12 * r, load + 6 * r, 6 * sizeof(double)), memcpy(load2 + 12 * r + 6, load + 6 * r, 6 * sizeof(double));
    load2[12 * 5] = load2[12 * 5 + 6] = 1e308;
    const int tool2[2] = {0, 0};
    vt_batch *b = batch_of(m, 1, 0);
    outputs_fill(&o[0], m, n, -7.0);
    vt_batch_io io = io_of(&o[0], n, q, 0, qd, qdd);
    io.nload = 2;
    io.load_frame = tool2;
    io.load = load2;
    assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), VT_ERR_NONFINITE);
    assert_int_equal(vt_batch_failed_row(b), 5);
    assert_non_null(strstr(vt_batch_message(b), "load 1 at frame 'tool'"));
    for (int r = 0; r < n; r++) {
        if (r == 5) {
            assert_int_equal(o[0].status[r], VT_ERR_NONFINITE);
            assert_true(o[0].effort[(size_t)r * nv] == -7.0);
            continue;
        }
        check_row_loaded(m, &o[0], r, q + (size_t)r * nq, qd + (size_t)r * nv, qdd + (size_t)r * nv, 2, tool2, load2 + 12 * r);
    }
    vt_batch_free(b);
    free(load2);
    for (int t = 0; t < 3; t++) outputs_free(&o[t]);
    outputs_free(&bare);
    free(q);
    free(qd);
    free(qdd);
    free(load);
    free(pos);
    vt_data_free(d);
    vt_model_free(m);
}

/* a planar arm of n links (hinges about z, link i L[i] long along its body x, 1 + 0.5 i kg) into b,
 * joint 2 following joint 1 by a coupling q2 = r q1 + c0, joint 1 driven */
static void coupled_arm(vt_builder *b, int n, const double *L, double r, double c0)
{
    for (int i = 0; i < n; i++) {
        vt_body_def bd = vt_default_body_def();
        bd.parent = i;
        bd.mass = 1.0 + 0.5 * i;
        bd.inertia[0] = 0.01, bd.inertia[4] = bd.inertia[8] = bd.mass * L[i] * L[i] / 12.0;
        bd.axis1[0] = bd.axis1[1] = 0.0, bd.axis1[2] = 1.0;
        if (i) bd.joint_parent[0] = L[i - 1] / 2.0;
        bd.joint_child[0] = -L[i] / 2.0;
        assert_int_equal(vt_builder_add_body(b, &bd), i + 1);
    }
    vt_coupling_def cp = vt_default_coupling_def();
    cp.ratio = r, cp.offset = c0;
    assert_int_equal(vt_builder_add_coupling(b, &cp), 0);
    vt_drive_def dr = vt_default_drive_def();
    dr.body = 1;
    assert_true(vt_builder_add_drive(b, &dr) >= 0);
}

/* a planar two-link arm (coupled_arm: L1 = 0.7 m, L2 = 0.5 m) whose joint 2 follows joint 1 by a
 * coupling, q2 = r q1 + c (a gear train), joint 1 driven; a
 * wrench at link 2's tip: each row bitwise the single call with it put into xfrc by
 * vt_add_frame_load() after vt_kinematics(), and the drive's effort less the unloaded one
 * against the virtual work of the load along the coupled motion, with the tip's velocity
 * (∂p/∂q1 + r ∂p/∂q2) q̇1 and link 2's rate (1 + r) q̇1:
 *   Δτ1 = −((∂p/∂q1 + r ∂p/∂q2) · f + (1 + r) n_z) */
static void test_coupling_loads(void **state)
{
    (void)state;
    const double L1 = 0.7, L2 = 0.5, r = -0.6, c0 = 0.4, L[2] = {L1, L2};
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, NULL));
    coupled_arm(b, 2, L, r, c0);
    vt_frame_def tip = vt_default_frame_def();
    tip.name = "tip";
    tip.body = 2;
    tip.point[0] = L2 / 2.0;
    assert_int_equal(vt_builder_add_frame(b, &tip), 0);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    const int n = 40, frame[1] = {0};
    double q[2 * 40], qd[2 * 40], qdd[2 * 40], load[6 * 40];
    uint64_t seed = 43;
    for (int k = 0; k < n; k++) {
        q[2 * k] = vt_rand_uniform(&seed, -3.0, 3.0), q[2 * k + 1] = r * q[2 * k] + c0;
        qd[2 * k] = vt_rand_uniform(&seed, -2.0, 2.0), qd[2 * k + 1] = r * qd[2 * k];
        qdd[2 * k] = vt_rand_uniform(&seed, -5.0, 5.0), qdd[2 * k + 1] = r * qdd[2 * k];
        for (int h = 0; h < 6; h++) load[6 * k + h] = vt_rand_uniform(&seed, -30.0, 30.0);
    }
    outputs o, bare;
    outputs_alloc(&o, m, n);
    outputs_alloc(&bare, m, n);
    assert_int_equal(vt_motion_time_drive(m), -1); /* a coupling and a joint drive: no time read */
    vt_batch *bt = batch_of(m, 2, 0);
    vt_batch_io io = io_of(&bare, n, q, 0, qd, qdd);
    assert_ok(vt_batch_inverse_dynamics_motion(bt, &io));
    io = io_of(&o, n, q, 0, qd, qdd);
    io.nload = 1;
    io.load_frame = frame;
    io.load = load;
    assert_ok(vt_batch_inverse_dynamics_motion(bt, &io));
    vt_batch_free(bt);
    double worst = 0.0, moved = 0.0;
    for (int k = 0; k < n; k++) {
        check_row_loaded(m, &o, k, q + 2 * k, qd + 2 * k, qdd + 2 * k, 1, frame, load + 6 * k);
        const double q1 = q[2 * k], q12 = q1 + q[2 * k + 1], *w = load + 6 * k;
        const double d1[2] = {-L1 * sin(q1) - L2 * sin(q12), L1 * cos(q1) + L2 * cos(q12)};
        const double d2[2] = {-L2 * sin(q12), L2 * cos(q12)};
        const double want = -((d1[0] + r * d2[0]) * w[0] + (d1[1] + r * d2[1]) * w[1] + (1.0 + r) * w[5]);
        const double got = o.drive_effort[k] - bare.drive_effort[k];
        const double scale = 1.0 + fabs(want);
        worst = fmax(worst, fabs(got - want) / scale);
        moved = fmax(moved, fabs(got));
    }
    printf("coupled arm, a wrench at the tip: the drive's effort less the unloaded one against virtual work: %.2e\n",
           worst);
    assert_true(worst < 1e-12 && moved > 1.0);
    outputs_free(&o);
    outputs_free(&bare);
    vt_model_free(m);
}

/* the rows' time (io->time): a planar three-link arm (hinges about z, L = 0.7, 0.5, 0.4 m), joint 2
 * following joint 1 by a coupling (q2 = r q1 + c), joint 1 driven and link 3's end's x following
 * a point drive x(t) = 0.3 sin 2t: the given motion's q̈3 comes from the point drive's row at the
 * row's time. Each row bitwise the single call with d->time = t; the end's ẍ from the planar
 * closed form, ẍ = −Σ_k L_k (cos θ_k θ̇_k² + sin θ_k θ̈_k) with θ_k the summed angles, equal to
 * x''(t) = −1.2 sin 2t (1e-12); without io->time the call is refused, the drive named
 * (vt_motion_time_drive), and the rows at t = 0 given are others (another q̈3) */
static void test_batch_time(void **state)
{
    (void)state;
    static const double L[3] = {0.7, 0.5, 0.4};
    const double r = 1.4, c0 = -0.2;
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, NULL));
    coupled_arm(b, 3, L, r, c0);
    vt_drive_def dr = vt_default_drive_def();
    dr.type = VT_DRIVE_POINT;
    dr.body = 3;
    dr.index = 0;
    dr.point[0] = L[2] / 2.0;
    dr.f = vt_function_sine(0.0, 0.3, 2.0, 0.0);
    assert_true(vt_builder_add_drive(b, &dr) >= 0);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_true(m->nv == 3 && m->nc == 3);
    enum { N = 30 };
    double q[3 * N], qd[3 * N], qdd[3 * N], t[N];
    uint64_t seed = 47;
    for (int k = 0; k < N; k++) {
        double *qk = q + 3 * k, *vk = qd + 3 * k, *ak = qdd + 3 * k;
        t[k] = vt_rand_uniform(&seed, 0.0, 3.0);
        qk[0] = vt_rand_uniform(&seed, -2.0, 2.0), qk[1] = r * qk[0] + c0, qk[2] = vt_rand_uniform(&seed, -2.0, 2.0);
        vk[0] = vt_rand_uniform(&seed, -1.0, 1.0), vk[1] = r * vk[0], vk[2] = vt_rand_uniform(&seed, -1.0, 1.0);
        ak[0] = vt_rand_uniform(&seed, -3.0, 3.0), ak[1] = r * ak[0], ak[2] = 0.0; /* q̈3: the point drive's */
    }
    outputs o, zero;
    outputs_alloc(&o, m, N);
    outputs_alloc(&zero, m, N);
    vt_batch *bt = batch_of(m, 2, 0);
    vt_batch_io io = io_of(&o, N, q, 0, qd, qdd);
    io.time = t;
    assert_ok(vt_batch_inverse_dynamics_motion(bt, &io));
    io = io_of(&zero, N, q, 0, qd, qdd);
    /* without the rows' time: refused, the drive named (the rows would be t = 0's) */
    assert_int_equal(vt_motion_time_drive(m), 1);
    assert_int_equal(vt_motion_time_drive(NULL), VT_ERR_NULL);
    assert_int_equal(vt_batch_inverse_dynamics_motion(bt, &io), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(vt_batch_message(bt), "drive 1"));
    assert_non_null(strstr(vt_batch_message(bt), "io.time"));
    const double t0[N] = {0.0};
    io.time = t0;
    assert_ok(vt_batch_inverse_dynamics_motion(bt, &io));
    vt_batch_free(bt);
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    double worst = 0.0, apart = 0.0;
    for (int k = 0; k < N; k++) {
        memcpy(d->q, q + 3 * k, sizeof(double[3]));
        memcpy(d->qd, qd + 3 * k, sizeof(double[3]));
        memcpy(d->qdd, qdd + 3 * k, sizeof(double[3]));
        d->time = t[k];
        assert_ok(vt_inverse_dynamics_motion(m, d));
        for (int a = 0; a < 3; a++) {
            assert_true(same(o.qdd[3 * k + a], d->qdd[a]) && same(o.effort[3 * k + a], d->qfrc_drive[a]));
            apart = fmax(apart, fabs(o.qdd[3 * k + a] - zero.qdd[3 * k + a]));
        }
        for (int h = 0; h < 2; h++) assert_true(same(o.drive_effort[2 * k + h], d->drive_effort[h]));
        double th = 0.0, w = 0.0, al = 0.0, xdd = 0.0;
        for (int i = 0; i < 3; i++) {
            th += q[3 * k + i], w += qd[3 * k + i], al += o.qdd[3 * k + i];
            xdd -= L[i] * (cos(th) * w * w + sin(th) * al);
        }
        worst = fmax(worst, fabs(xdd + 1.2 * sin(2.0 * t[k])));
    }
    printf("the rows' time: the end's x'' against the point drive's at t: %.2e m/s^2; q'' at t = 0 apart by %.3g\n",
           worst, apart);
    assert_true(worst < 1e-12 && apart > 0.1);
    vt_data_free(d);
    outputs_free(&o);
    outputs_free(&zero);
    vt_model_free(m);
}

/* one batch, call after call (the workers asleep between some, spinning between others): 300
 * calls of 0 to 203 rows, each from another first row of the states (so that every call's inputs
 * and outputs move), one row NaN: each call's efforts and reactions bitwise those of
 * vt_inverse_dynamics_motion() on each state alone, the NaN row reported at its index within the
 * call whenever the call holds it; then batches freed with their workers asleep, and one freed
 * without a call */
static void test_calls_in_turn(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_random_tree(&m, 7, 8, VT_SCENE_NO_BASE));
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv, nb6 = 6 * (size_t)m->nbody;
    states st = random_states(m, 21, nq);
    const int bad = 150;
    st.qd[bad * nv] = NAN;
    /* the single call's answers, each state on its own data */
    double *effort = malloc(NROW * nv * sizeof(double)), *reaction = malloc(NROW * nb6 * sizeof(double));
    assert_non_null(effort);
    assert_non_null(reaction);
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    for (int r = 0; r < NROW; r++) {
        if (r == bad) continue;
        memcpy(d->q, st.q + r * nq, nq * sizeof(double));
        memcpy(d->qd, st.qd + r * nv, nv * sizeof(double));
        memcpy(d->qdd, st.qdd + r * nv, nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(m, d));
        memcpy(effort + r * nv, d->qfrc_drive, nv * sizeof(double));
        for (int i = 1; i <= m->nbody; i++) {
            memcpy(reaction + r * nb6 + 6 * (size_t)(i - 1), d->jnt_force + 3 * i, 3 * sizeof(double));
            memcpy(reaction + r * nb6 + 6 * (size_t)(i - 1) + 3, d->jnt_moment + 3 * i, 3 * sizeof(double));
        }
    }
    vt_data_free(d);
    double *e = malloc(NROW * nv * sizeof(double)), *rw = malloc(NROW * nb6 * sizeof(double));
    int *status = malloc(NROW * sizeof(int));
    assert_non_null(e);
    assert_non_null(rw);
    assert_non_null(status);
    const int threads[2] = {2, 8}, sizes[7] = {0, 1, 16, 17, 33, 64, NROW};
    for (int t = 0; t < 2; t++) {
        vt_batch *b = batch_of(m, threads[t], 0);
        uint64_t seed = 5;
        for (int call = 0; call < 300; call++) {
            const int n = sizes[call % 7], first = (int)vt_rand_uniform(&seed, 0.0, (double)(NROW - n) + 0.999);
            for (size_t k = 0; k < NROW * nv; k++) e[k] = 42.0;
            vt_batch_io io = {0};
            io.nrow = n;
            io.q = st.q + first * nq;
            io.qd = st.qd + first * nv;
            io.qdd = st.qdd + first * nv;
            io.effort = e;
            io.reaction = rw;
            io.status = status;
            const int holds = first <= bad && bad < first + n;
            assert_int_equal(vt_batch_inverse_dynamics_motion(b, &io), holds ? VT_ERR_NONFINITE : VT_OK);
            assert_int_equal(vt_batch_failed_row(b), holds ? bad - first : -1);
            for (int r = n - 1; r >= 0; r--) { /* the last rows first: those a worker finishes last */
                if (first + r == bad) {
                    assert_int_equal(status[r], VT_ERR_NONFINITE);
                    assert_true(same(e[(size_t)r * nv], 42.0));
                    continue;
                }
                assert_int_equal(status[r], VT_OK);
                for (size_t k = 0; k < nv; k++) assert_true(same(e[r * nv + k], effort[(first + r) * nv + k]));
                for (size_t k = 0; k < nb6; k++) assert_true(same(rw[r * nb6 + k], reaction[(first + r) * nb6 + k]));
            }
            if (call % 50 == 49) { /* long enough for the workers to sleep */
                const struct timespec pause = {0, 2000000};
                nanosleep(&pause, NULL);
            }
        }
        vt_batch_free(b);
    }
    vt_batch_free(batch_of(m, 8, 0)); /* its workers never called */
    free(e);
    free(rw);
    free(status);
    free(effort);
    free(reaction);
    states_free(&st);
    vt_model_free(m);
}

/* vt_batch_run: the caller's own work on the batch's threads, on 1, 2 and 8 threads, call after
 * call: every item of each call run once, parts numbered below the batch's threads, part 0 on
 * the calling thread; a NULL batch or work refused */
typedef struct {
    atomic_int next, runs[300], bad_part, off_caller;
    pthread_t caller;
    int threads;
} items;

static void take_items(void *ctx, int k)
{
    items *it = ctx;
    if (k < 0 || k >= it->threads) atomic_fetch_add(&it->bad_part, 1);
    if (k == 0 && !pthread_equal(pthread_self(), it->caller)) atomic_fetch_add(&it->off_caller, 1);
    for (int i; (i = atomic_fetch_add(&it->next, 1)) < 300;) atomic_fetch_add(&it->runs[i], 1);
}

static void test_run(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_double_link(&m, 0));
    const int threads[3] = {1, 2, 8};
    items *it = malloc(sizeof *it);
    assert_non_null(it);
    for (int t = 0; t < 3; t++) {
        vt_batch *b = batch_of(m, threads[t], 0);
        for (int call = 0; call < 200; call++) {
            memset(it, 0, sizeof *it);
            it->caller = pthread_self();
            it->threads = vt_batch_threads(b);
            assert_ok(vt_batch_run(b, take_items, it));
            for (int i = 0; i < 300; i++) assert_int_equal(atomic_load(&it->runs[i]), 1);
            assert_int_equal(atomic_load(&it->bad_part), 0);
            assert_int_equal(atomic_load(&it->off_caller), 0);
        }
        assert_int_equal(vt_batch_run(NULL, take_items, it), VT_ERR_NULL);
        assert_int_equal(vt_batch_run(b, NULL, it), VT_ERR_NULL);
        vt_batch_free(b);
    }
    free(it);
    vt_model_free(m);
}

/* a call on the batch from inside vt_batch_run's work (each part tries both entry points) and
 * the outer call unharmed: every item once, then the batch usable again */
typedef struct {
    vt_batch *batch;
    vt_batch_io io;
    atomic_int next, runs[64], refused, other;
} nested;

static void nested_part(void *ctx, int k)
{
    (void)k;
    nested *n = ctx;
    for (int i; (i = atomic_fetch_add(&n->next, 1)) < 64;) {
        atomic_fetch_add(&n->runs[i], 1);
        if (i % 16 == 0) {
            const vt_status a = vt_batch_inverse_dynamics_motion(n->batch, &n->io);
            const vt_status b = vt_batch_run(n->batch, take_items, NULL);
            if (a == VT_ERR_BAD_OPTION && b == VT_ERR_BAD_OPTION) atomic_fetch_add(&n->refused, 1);
            else atomic_fetch_add(&n->other, 1);
        }
    }
}

static void test_nested_refused(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_double_link(&m, 0));
    double q[2] = {0.1, 0.2}, qd[2] = {0}, qdd[2] = {0}, effort[2] = {7, 7};
    for (int threads = 1; threads <= 8; threads *= 2) {
        vt_batch *b = batch_of(m, threads, 0);
        nested *n = calloc(1, sizeof *n);
        assert_non_null(n);
        n->batch = b;
        n->io.nrow = 1;
        n->io.q = q;
        n->io.qd = qd;
        n->io.qdd = qdd;
        n->io.effort = effort;
        assert_ok(vt_batch_run(b, nested_part, n));
        for (int i = 0; i < 64; i++) assert_int_equal(atomic_load(&n->runs[i]), 1);
        assert_int_equal(atomic_load(&n->refused), 4);
        assert_int_equal(atomic_load(&n->other), 0);
        assert_true(same(effort[0], 7.0)); /* the refused calls wrote nothing */
        assert_ok(vt_batch_inverse_dynamics_motion(b, &n->io)); /* the batch taken back */
        assert_false(same(effort[0], 7.0));
        effort[0] = effort[1] = 7.0;
        free(n);
        vt_batch_free(b);
    }
    vt_model_free(m);
}

/* a batch whose threads the system refuses in part (a child process whose address space cannot
 * hold eight threads' stacks): fewer threads, every row still bitwise the single call's, and the
 * batch freed whole (its data for every thread asked for) */
static void test_threads_refused(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_random_tree(&m, 4, 5, VT_SCENE_NO_BASE));
    states st = random_states(m, 13, (size_t)m->nq);
    const pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        /* room above what is mapped now for the data and two threads' stacks and a half */
        pthread_attr_t attr;
        size_t stack = 0;
        if (pthread_getattr_default_np(&attr) || pthread_attr_getstacksize(&attr, &stack)) _exit(2);
        pthread_attr_destroy(&attr);
        FILE *f = fopen("/proc/self/statm", "r");
        unsigned long pages = 0;
        const int got = f && fscanf(f, "%lu", &pages) == 1;
        if (f) fclose(f);
        const struct rlimit lim = {(rlim_t)pages * (rlim_t)sysconf(_SC_PAGESIZE) + (rlim_t)(5 * stack / 2) +
                                       ((rlim_t)2 << 20),
                                   RLIM_INFINITY};
        if (!got || setrlimit(RLIMIT_AS, &lim)) _exit(2);
        vt_batch_def def = vt_default_batch_def();
        def.threads = 8;
        vt_batch *b = NULL;
        if (vt_batch_create(&b, m, &def)) _exit(3);
        const int T = vt_batch_threads(b);
        outputs o;
        outputs_alloc(&o, m, NROW);
        vt_batch_io io = io_of(&o, NROW, st.q, 0, st.qd, st.qdd);
        int ok = vt_batch_inverse_dynamics_motion(b, &io) == VT_OK;
        vt_data *d = NULL;
        ok = ok && vt_data_create(&d, m) == VT_OK;
        const size_t nq = (size_t)m->nq, nv = (size_t)m->nv;
        for (int r = 0; r < NROW && ok; r++) {
            memcpy(d->q, st.q + r * nq, nq * sizeof(double));
            memcpy(d->qd, st.qd + r * nv, nv * sizeof(double));
            memcpy(d->qdd, st.qdd + r * nv, nv * sizeof(double));
            ok = vt_inverse_dynamics_motion(m, d) == VT_OK;
            for (size_t k = 0; k < nv && ok; k++) ok = same(o.effort[r * nv + k], d->qfrc_drive[k]);
        }
        vt_data_free(d);
        outputs_free(&o);
        vt_batch_free(b);
        _exit(!ok ? 4 : T >= 8 ? 5 : 0);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    states_free(&st);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        /* first, before any thread has run: the threads' stacks glibc keeps for reuse after a
         * thread ends would need no new address space */
        cmocka_unit_test(test_threads_refused),
        cmocka_unit_test(test_tree_bitwise),
        cmocka_unit_test(test_loop_bitwise),
        cmocka_unit_test(test_effects_bitwise),
        cmocka_unit_test(test_failing_rows),
        cmocka_unit_test(test_contacts_bitwise),
        cmocka_unit_test(test_arguments),
        cmocka_unit_test(test_frame_loads),
        cmocka_unit_test(test_loop_loads),
        cmocka_unit_test(test_coupling_loads),
        cmocka_unit_test(test_batch_time),
        cmocka_unit_test(test_calls_in_turn),
        cmocka_unit_test(test_run),
        cmocka_unit_test(test_nested_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
