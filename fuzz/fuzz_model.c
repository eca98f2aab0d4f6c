/* libFuzzer harness: bytes become body, joint, drive, cut-joint and coupling definitions, a
 * state, time functions and run options; the model is built and checked, and every instant is computed by
 * more than one route and compared. Whatever the bytes, the library must answer with a status:
 * no crash, no sanitizer report; and what it answers must hold up:
 *
 * - the model: what the builder accepted satisfies the checks it documents (unit axes and Euler
 *   parameters, finite symmetric positive semi-definite inertias within the triangle inequality,
 *   to VT_INERTIA_TOL);
 * - differential: the dense vt_inverse_dynamics and vt_inverse_dynamics_recursive on separate
 *   data of the same state; vt_inverse_dynamics_motion given the dense q̈ (a tree: every rate's
 *   M* q̈ − Q against the dense Φ_q^T λ; loops and couplings: the whole instant); the same
 *   definitions with allow_redundant = 1 at a clearly regular pose; the state's xfrc given again
 *   as wrenches at frames (one on each body) to the batch (frame_loads): its efforts and unique
 *   reactions as the single call's with xfrc. Where both succeed, q̈, the
 *   efforts and every reaction agree within tol (below), and dense and recursive α and the
 *   joints' totals too; their statuses are consistent (below). The bytes also choose the later
 *   pieces: planar revolute cut joints, relative orientation drives' references, three-angle
 *   sequences (valid and refused ones) and the joints' armature, damping and friction, from bits
 *   the older inputs left unused;
 * - with VT_OK every output array of the call is finite (the instants', and each single stage's:
 *   vt_kinematics, vt_mass_matrix, vt_forces, vt_constraints, vt_inverse_transform,
 *   vt_add_point_load, vt_generalized_force, vt_equivalent_force, vt_drive_cartesian_force,
 *   vt_integrate_q, vt_cartesian_force, the kinematic solve and the analyses' trajectories);
 * - a failure gives a non-empty message and leaves the inputs (q, q̇, xfrc, qfrc, time) as they
 *   were; an option that is not finite is refused; a time function that fails inside an
 *   analysis ends it at once with VT_ERR_CALLBACK or VT_ERR_NONFINITE; an analysis leaves the
 *   caller's xfrc as it was, a kinematic analysis with a wrench at a frame over the run (1, 1e3,
 *   1e300 or NaN times a fixed one) too;
 * - at overflow's edge (motion_edge, the last bytes): the motion given with q̇ and q̈ up to
 *   DBL_MAX, and the two paths at that q̇, each VT_OK with finite outputs or refused as above.
 * A broken promise prints which comparison failed, with the values, and aborts (libFuzzer keeps
 * the input as crash-*). Build and run: bash fuzz/run.sh [seconds]. The bytes' reading, the reports and
 * the checks of every call are in harness.c, the comparison's tolerances in compare.c. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vtdyn.h"
#include "compare.h"
#include "harness.h"

/* a user time function that is smooth until t_fail, then fails (mode 0) or returns NaN (mode 1);
 * it counts its calls from the first failure on */
typedef struct {
    double amp, t_fail;
    int mode;
    long after;
    double first_fail;
} callback_user;

static int fuzz_callback(double t, double out[3], void *user)
{
    callback_user *c = user;
    if (t >= c->t_fail) {
        if (c->after++ == 0) c->first_fail = t;
        if (c->mode == 0) return 1;
        out[0] = out[1] = out[2] = (double)NAN;
        return 0;
    }
    out[0] = c->amp * sin(t);
    out[1] = c->amp * cos(t);
    out[2] = -c->amp * sin(t);
    return 0;
}

static void fill_function(bytes *b, vt_function *f, callback_user *cb)
{
    const unsigned k = byte(b) % 6;
    double c[VT_POLY_MAX];
    for (int i = 0; i < VT_POLY_MAX; i++) c[i] = num(b);
    if (k == 0) *f = vt_function_constant(c[0]);
    else if (k == 1) *f = vt_function_polynomial((int)(byte(b) % 10), c);
    else if (k == 2) *f = vt_function_sine(c[0], c[1], c[2], c[3]);
    else if (k == 3) *f = vt_function_user(NULL, NULL);
    else if (k == 4) {
        cb->amp = c[0];
        cb->t_fail = c[1];
        cb->mode = (int)(byte(b) % 2);
        *f = vt_function_user(fuzz_callback, cb);
    } else {
        *f = vt_function_constant(c[0]);
        f->type = (vt_function_type)(byte(b) % 7);
    }
}

/* ---- the single stages -------------------------------------------------------------------- */

static vt_status stage(const vt_model *m, vt_data *d, vt_status (*fn)(const vt_model *, vt_data *), const char *call)
{
    double *before = malloc((input_count(m) + 1) * sizeof(double));
    if (!before) return VT_ERR_NO_MEMORY;
    save_inputs(m, d, before);
    d->message[0] = '\0';
    const vt_status st = fn(m, d);
    if (st != VT_OK) failed_call(m, d, before, st, call);
    free(before);
    return st;
}

static void stages(const vt_model *m, vt_data *d, bytes *b)
{
    const int n1 = m->nbody + 1, nx = m->nx, nv = m->nv, nc = m->nc;
    if (stage(m, d, vt_kinematics, "vt_kinematics")) return;
    finite(d->x, nx, "vt_kinematics", "x");
    finite(d->xd, nx, "vt_kinematics", "xd");
    finite(d->A, 9 * n1, "vt_kinematics", "A");
    finite(d->omega, 3 * n1, "vt_kinematics", "omega");
    finite(d->jaxis, 9 * n1, "vt_kinematics", "jaxis");
    finite(d->jsij, 3 * n1, "vt_kinematics", "jsij");
    finite(d->jd, 3 * n1, "vt_kinematics", "jd");
    finite(d->jpoint, 3 * n1, "vt_kinematics", "jpoint");
    finite(d->twist, 6 * nv, "vt_kinematics", "twist");
    finite(d->S, nx * nv, "vt_kinematics", "S");
    finite(d->Sdqd, nx, "vt_kinematics", "Sdqd");
    if (!stage(m, d, vt_mass_matrix, "vt_mass_matrix")) {
        finite(d->Mp, 16 * n1, "vt_mass_matrix", "Mp");
        finite(d->Mstar, nv * nv, "vt_mass_matrix", "Mstar");
    }
    if (!stage(m, d, vt_forces, "vt_forces")) {
        finite(d->F, nx, "vt_forces", "F");
        finite(d->h, nx, "vt_forces", "h");
        finite(d->Q, nv, "vt_forces", "Q");
    }
    if (!stage(m, d, vt_constraints, "vt_constraints")) {
        finite(d->Phi, nc, "vt_constraints", "Phi");
        finite(d->Phix, 14 * nc, "vt_constraints", "Phix");
        finite(d->Phiq, nc * nv, "vt_constraints", "Phiq");
        finite(d->Phit, nc, "vt_constraints", "Phit");
        finite(d->gamma, nc, "vt_constraints", "gamma");
    }
    if (!stage(m, d, vt_inverse_transform, "vt_inverse_transform")) finite(d->R, nv * nx, "vt_inverse_transform", "R");

    /* a point load at a point of the bytes' choosing */
    double pt[3], f[3], n[3];
    for (int k = 0; k < 3; k++) {
        pt[k] = num(b);
        f[k] = num(b);
        n[k] = num(b);
    }
    const unsigned pick = byte(b);
    const int body = (int)(pick % (unsigned)(m->nbody + 2)) - (pick & 64 ? 1 : 0);
    double *before = malloc((input_count(m) + 1) * sizeof(double));
    if (!before) return;
    save_inputs(m, d, before);
    d->message[0] = '\0';
    vt_status st = vt_add_point_load(m, d, body, pt, pick & 128 ? NULL : f, pick & 32 ? NULL : n);
    if (st == VT_OK) finite(d->xfrc + 6 * body, 6, "vt_add_point_load", "xfrc of its body"); /* the rest is the caller's */
    else failed_call(m, d, before, st, "vt_add_point_load");
    free(before);

    /* Q = S^T F and F_eq = R^T Q for a Cartesian force and a generalized force of the bytes */
    double *F = malloc((size_t)(2 * nx + 2 * nv + 2 * m->nq) * sizeof(double));
    if (!F) return;
    double *Q = F + nx, *Feq = Q + nv, *Qin = Feq + nx, *qout = Qin + nv, *qcopy = qout + m->nq;
    for (int k = 0; k < nx; k++) F[k] = byte(b) % 4 ? d->F[k] : num(b);
    for (int k = 0; k < nv; k++) Qin[k] = byte(b) % 4 ? d->Q[k] : num(b);
    d->message[0] = '\0';
    st = vt_generalized_force(Q, m, d, F);
    if (st == VT_OK) finite(Q, nv, "vt_generalized_force", "Q");
    else if (d->message[0] == '\0') fail("vt_generalized_force failed (%s) with an empty message", vt_status_string(st));
    d->message[0] = '\0';
    st = vt_equivalent_force(Feq, m, d, Qin);
    if (st == VT_OK) finite(Feq, nx, "vt_equivalent_force", "Feq");
    else if (d->message[0] == '\0') fail("vt_equivalent_force failed (%s) with an empty message", vt_status_string(st));

    /* q advanced by q̇ over h (no message in this API: the inputs must stay as they were) */
    const double h = num(b);
    memcpy(qcopy, d->q, (size_t)m->nq * sizeof(double));
    st = vt_integrate_q(qout, m, d->q, d->qd, h);
    if (st == VT_OK) finite(qout, m->nq, "vt_integrate_q", "q_out");
    if (memcmp(qcopy, d->q, (size_t)m->nq * sizeof(double)) != 0) fail("vt_integrate_q changed its input q");

    /* eq (7) for one body: p from the kinematics, s, f and n of the bytes; f or n may be NULL */
    if (m->nbody >= 1) {
        double Fc[7];
        const int i = 1 + (int)(pick % (unsigned)m->nbody);
        unsigned nulls = byte(b) % 4;
        if (excluded("vt_cartesian_force(NULL)")) nulls = 0; /* the NULL moment's finding: set aside */
        const vt_status cst = vt_cartesian_force(Fc, d->x + 7 * (i - 1) + 3, pt, nulls & 1 ? NULL : f, nulls & 2 ? NULL : n);
        if (cst == VT_OK) finite(Fc, 7, "vt_cartesian_force", "F");
        if (nulls && cst != VT_ERR_NULL) fail("vt_cartesian_force with a NULL argument returned %s", vt_status_string(cst));
        /* finite inputs whose products cannot overflow give a finite force */
        int modest = !nulls;
        for (int k = 0; k < 4; k++)
            if (!(fabs(d->x[7 * (i - 1) + 3 + k]) < 1e100)) modest = 0;
        for (int k = 0; k < 3; k++)
            if (!(fabs(pt[k]) < 1e100) || !(fabs(f[k]) < 1e100) || !(fabs(n[k]) < 1e100)) modest = 0;
        if (modest && cst != VT_OK) fail("vt_cartesian_force refused modest finite inputs (%s)", vt_status_string(cst));
    }
    free(F);
}

/* ---- the whole input ---------------------------------------------------------------------- */

#define MAX_BODY 6
#define MAX_DRIVE 4
#define MAX_CUT 2

/* orientation drives' sequences: body-fixed, fixed-axes, and names the builder refuses (a
 * letter twice in a row, not axes, mixed case) */
static const char *const SEQUENCES[8] = {"ZYX", "xyz", "ZXZ", "zyz", "XYZ", "ZZX", "abc", "zYx"};

typedef struct {
    vt_model_def md;
    int nbody, ndrive, ncut, ncoupling;
    vt_body_def body[MAX_BODY];
    vt_coupling_def coupling;
    vt_drive_def drive[MAX_DRIVE];
    vt_cut_joint_def cut[MAX_CUT];
    callback_user cb[MAX_DRIVE];
} definitions;

static vt_model *build(const definitions *defs, int allow_redundant)
{
    vt_model_def md = defs->md;
    md.allow_redundant = allow_redundant;
    vt_builder *builder;
    if (vt_builder_create(&builder, &md)) return NULL;
    for (int i = 0; i < defs->nbody; i++) {
        const int id = vt_builder_add_body(builder, &defs->body[i]); /* refusals are fine, with a reason */
        if (id < 0 && vt_builder_message(builder)[0] == '\0') fail("vt_builder_add_body refused with an empty message");
        if (id < 0) continue;
        /* a frame on each body, halfway from its centre of mass to its joint (within the body's
         * own lengths): where frame_loads puts the state's xfrc as loads at frames */
        char name[16];
        snprintf(name, sizeof name, "f%d", id);
        vt_frame_def fd = vt_default_frame_def();
        fd.name = name;
        fd.body = id;
        for (int k = 0; k < 3; k++) fd.point[k] = 0.5 * defs->body[i].joint_child[k];
        if (vt_builder_add_frame(builder, &fd) < 0 && vt_builder_message(builder)[0] == '\0')
            fail("vt_builder_add_frame refused with an empty message");
    }
    const int show = getenv("FUZZ_DESCRIBE") != NULL;
    for (int k = 0; k < defs->ndrive; k++)
        if (vt_builder_add_drive(builder, &defs->drive[k]) < 0) {
            if (vt_builder_message(builder)[0] == '\0') fail("vt_builder_add_drive refused with an empty message");
            if (show) fprintf(stderr, "fuzz_model: drive refused: %s\n", vt_builder_message(builder));
        }
    for (int k = 0; k < defs->ncut; k++)
        if (vt_builder_add_cut_joint(builder, &defs->cut[k]) < 0) {
            if (vt_builder_message(builder)[0] == '\0') fail("vt_builder_add_cut_joint refused with an empty message");
            if (show) fprintf(stderr, "fuzz_model: cut joint refused: %s\n", vt_builder_message(builder));
        }
    if (defs->ncoupling && vt_builder_add_coupling(builder, &defs->coupling) < 0) {
        if (vt_builder_message(builder)[0] == '\0') fail("vt_builder_add_coupling refused with an empty message");
        if (show) fprintf(stderr, "fuzz_model: coupling refused: %s\n", vt_builder_message(builder));
    }
    vt_model *m = NULL;
    const vt_status st = vt_builder_build(&m, builder);
    if (st && getenv("FUZZ_DESCRIBE")) fprintf(stderr, "fuzz_model: the builder refused: %s\n", vt_builder_message(builder));
    vt_builder_free(builder);
    return st ? NULL : m;
}

static void read_definitions(bytes *b, definitions *defs)
{
    defs->md = vt_default_model_def();
    if (byte(b) % 4 == 0) {
        defs->md.gravity[1] = num(b);
        defs->md.rcond_min = fabs(num(b)) * 1e-12;
        defs->md.rcond_warn = defs->md.rcond_min * 10.0;
        defs->md.allow_redundant = (int)(byte(b) % 2);
    }
    defs->nbody = 1 + (int)(byte(b) % MAX_BODY);
    for (int i = 1; i <= defs->nbody; i++) {
        vt_body_def d = vt_default_body_def();
        d.parent = (int)(byte(b) % (unsigned)(i + 1)) - (byte(b) % 16 == 0);
        d.joint = (vt_joint_type)(byte(b) % 7); /* 6: the free joint (an unknown kind before it) */
        d.mass = byte(b) % 8 ? fabs(num(b)) + 0.1 : num(b);
        const unsigned sb = byte(b), shape = sb % 4, effects = sb >> 2 & 3;
        /* the joint's own effects from the shape byte's high bits (older inputs read the same
         * bytes): armature, damping and friction of the body's size, the sign or the tanh law */
        const double size = isfinite(d.mass) ? fabs(d.mass) : 1.0;
        for (int k = 0; k < 2 && effects; k++) {
            d.armature[k] = effects & 1 ? 0.5 * size : 0.0;
            d.damping[k] = effects & 2 ? 0.3 * size : 0.0;
            d.friction[k] = effects & 2 ? 0.2 * size : 0.0;
            d.friction_velocity[k] = effects == 3 ? 0.05 : 0.0;
        }
        if (shape == 0)
            for (int k = 0; k < 9; k++) d.inertia[k] = num(b);
        else if (shape == 1)
            d.inertia[0] = d.inertia[4] = d.inertia[8] = fabs(num(b));
        for (int k = 0; k < 3; k++) {
            d.joint_parent[k] = num(b);
            d.joint_child[k] = num(b);
            if (byte(b) % 2) d.axis1[k] = num(b);
            if (byte(b) % 4 == 0) d.axis2[k] = num(b);
        }
        if (byte(b) % 4 == 0)
            for (int k = 0; k < 4; k++) d.orientation[k] = num(b);
        defs->body[i - 1] = d;
    }
    defs->ndrive = (int)(byte(b) % (MAX_DRIVE + 1));
    for (int k = 0; k < defs->ndrive; k++) {
        vt_drive_def d = vt_default_drive_def();
        const unsigned kind = byte(b), who = byte(b);
        d.type = (vt_drive_type)(kind % 4);
        d.body = (int)(who % 8);
        d.index = (int)(byte(b) % 5) - 1;
        for (int c = 0; c < 3; c++) {
            d.point[c] = num(b);
            d.axis[c] = num(b);
        }
        fill_function(b, &d.f, &defs->cb[k]);
        /* the later pieces from the kind and body bytes' unused high bits (the older inputs
         * still read the same bytes): a relative drive's reference (-1 its joint, the ground,
         * another body or, refused, 1 in 8, the body itself); a sequence of three angles on an
         * orientation drive (3 in 8), on another kind 1 in 64 (refused), from SEQUENCES (valid
         * and invalid names); f2 and f3 the first angle's function rescaled (no bytes read) */
        const unsigned rb = who >> 3, hi = kind >> 2;
        const int which = (int)(rb >> 2) % 7;
        d.reference = (rb & 3) == 0 ? -1 : (rb & 3) == 1 ? 0 : (rb & 3) == 2 ? which : rb & 4 ? d.body : -1;
        if (hi == 63 || ((hi & 7) >= 5 && (d.type == VT_DRIVE_ORIENTATION || d.type == VT_DRIVE_RELATIVE_ORIENTATION)))
            d.sequence = SEQUENCES[(hi >> 3) & 7];
        d.f2 = d.f3 = d.f;
        for (int c = 0; c < VT_POLY_MAX; c++) {
            d.f2.c[c] *= -0.6;
            d.f3.c[c] *= c % 2 ? 1.7 : 0.3;
        }
        defs->drive[k] = d;
    }
    const unsigned cb = byte(b), hc = cb / (MAX_CUT + 1);
    defs->ncut = (int)(cb % (MAX_CUT + 1));
    /* a coupling from the same byte's unused high part (older inputs read the same bytes), 1 in 4:
     * body a's first coordinate follows body b's (a ≠ b unless the bits say so: refused), with a
     * ratio and an offset of the byte's choosing; a gear train, a URDF mimic joint */
    defs->ncoupling = hc % 4 == 3;
    if (defs->ncoupling) {
        vt_coupling_def c = vt_default_coupling_def();
        c.body_a = 1 + (int)(hc / 4 % (unsigned)defs->nbody);
        c.body_b = hc / 4 % 5 == 4 ? c.body_a : 1 + (int)((hc / 4 + 1) % (unsigned)defs->nbody);
        c.ratio = hc / 8 % 2 ? -0.7 : 1.3;
        c.offset = hc / 16 % 2 ? 0.25 : 0.0;
        defs->coupling = c;
    }
    for (int k = 0; k < defs->ncut; k++) {
        vt_cut_joint_def c = vt_default_cut_joint_def();
        const unsigned kind = byte(b), hi = kind / 7;
        c.joint = (vt_joint_type)(kind % 7);
        /* planar from the kind byte's unused high part: a revolute's pin half the time (2, not
         * 0 or 1, refused, 1 in 16); another kind's 1 in 8 (refused) */
        if (c.joint == VT_JOINT_REVOLUTE) c.planar = hi % 16 == 15 ? 2 : (int)(hi & 1);
        else c.planar = hi % 8 == 7;
        c.body_a = (int)(byte(b) % 8);
        c.body_b = (int)(byte(b) % 8);
        for (int e = 0; e < 3; e++) {
            c.point_a[e] = num(b);
            c.point_b[e] = num(b);
            if (byte(b) % 2) c.axis1[e] = num(b);
        }
        defs->cut[k] = c;
    }
}

static void copy_state(const vt_model *m, vt_data *to, const vt_data *from)
{
    memcpy(to->q, from->q, (size_t)m->nq * sizeof(double));
    memcpy(to->qd, from->qd, (size_t)m->nv * sizeof(double));
    memcpy(to->xfrc, from->xfrc, 6 * (size_t)(m->nbody + 1) * sizeof(double));
    memcpy(to->qfrc, from->qfrc, (size_t)m->nv * sizeof(double));
    to->time = from->time;
}

/* one instant of one route on fresh data: status, message and inputs on failure, finiteness on
 * success */
static vt_status instant(const vt_model *m, vt_data *d, vt_status (*fn)(const vt_model *, vt_data *), const char *call)
{
    const vt_status st = stage(m, d, fn, call);
    if (st == VT_OK) data_finite(m, d, call);
    return st;
}

static int all_joint_drives(const vt_model *m)
{
    for (int k = 0; k < m->ndrive; k++)
        if (m->drive[k].type != VT_DRIVE_JOINT) return 0;
    return 1;
}

/* the state's xfrc as wrenches at the bodies' frames through the batch (vt_batch_io.load, whose
 * row has xfrc zero): body b's entry [f; n], n about its centre of mass, is the force f at its
 * frame F with the moment n − s × f about F's origin (s = A_b p_F, dm's poses). The given
 * motion's efforts and unique reactions again (dm: the single call with xfrc), within the
 * tolerances of s; a refusal where the single call succeeded is a failure */
static void frame_loads(const vt_model *m, const vt_data *state, const vt_data *dm, const double *given, const scales *s)
{
    const int nl = m->nframe, nb = m->nbody, nv = m->nv;
    if (nl == 0 || maxabs(state->xfrc, 6 * (nb + 1)) == 0.0) return;
    int *frame = malloc((size_t)nl * sizeof(int));
    double *w = malloc(6 * (size_t)nl * sizeof(double)), *effort = malloc(((size_t)nv + 1) * sizeof(double));
    double *reaction = malloc((6 * (size_t)nb + 1) * sizeof(double));
    int status = 0;
    vt_batch *bt = NULL;
    vt_batch_def def = vt_default_batch_def();
    def.threads = 1;
    if (!frame || !w || !effort || !reaction || vt_batch_create(&bt, m, &def)) goto out;
    if (nl != nb) goto out; /* a frame on each body: each body's xfrc once */
    for (int k = 0; k < nl; k++) {
        const int b = m->frame_body[k];
        const double *x = state->xfrc + 6 * b, *A = dm->A + 9 * b, *p = m->frame_point + 3 * k;
        double sv[3];
        for (int r = 0; r < 3; r++) sv[r] = A[r] * p[0] + A[r + 3] * p[1] + A[r + 6] * p[2];
        frame[k] = k;
        w[6 * k] = x[0], w[6 * k + 1] = x[1], w[6 * k + 2] = x[2];
        w[6 * k + 3] = x[3] - (sv[1] * x[2] - sv[2] * x[1]);
        w[6 * k + 4] = x[4] - (sv[2] * x[0] - sv[0] * x[2]);
        w[6 * k + 5] = x[5] - (sv[0] * x[1] - sv[1] * x[0]);
    }
    if (!(maxabs(w, 6 * nl) < HUGE_VAL)) goto out; /* the moments converted overflow */
    vt_batch_io io = {0};
    io.nrow = 1;
    io.q = state->q;
    io.qd = state->qd;
    io.qdd = given;
    io.qfrc = state->qfrc;
    io.time = &state->time; /* a loop's or coupling's point and orientation drives read it */
    io.effort = effort;
    io.reaction = reaction;
    io.status = &status;
    io.nload = nl;
    io.load_frame = frame;
    io.load = w;
    const vt_status st = vt_batch_inverse_dynamics_motion(bt, &io);
    if (st != VT_OK)
        fail("the batch with the state's xfrc as loads at frames: %s (%s) where the single call with xfrc succeeded",
             vt_status_string(st), vt_batch_message(bt));
    agree("xfrc and loads at frames", "qfrc_drive", dm->qfrc_drive, effort, nv, s->tg, s);
    for (int i = 1; i <= nb; i++)
        for (int c = 0; c < 3; c++) {
            if (dm->jnt_unique[6 * i + c])
                agree("xfrc and loads at frames", "jnt_force", dm->jnt_force + 3 * i + c, reaction + 6 * (i - 1) + c, 1, s->tf, s);
            if (dm->jnt_unique[6 * i + 3 + c])
                agree("xfrc and loads at frames", "jnt_moment", dm->jnt_moment + 3 * i + c, reaction + 6 * (i - 1) + 3 + c, 1,
                      s->tn, s);
        }
out:
    vt_batch_free(bt);
    free(frame);
    free(w);
    free(effort);
    free(reaction);
}

static void differential(const definitions *defs, const vt_model *m, const vt_data *state, int compare)
{
    vt_data *dd = NULL, *dr = NULL, *dm = NULL;
    if (vt_data_create(&dd, m) || vt_data_create(&dr, m) || vt_data_create(&dm, m)) goto out;
    copy_state(m, dd, state);
    copy_state(m, dr, state);
    copy_state(m, dm, state);
    const double in_mag = input_magnitude(m, state);
    context.m = m, context.a = dd, context.b = dr;
    const vt_status sd = instant(m, dd, vt_inverse_dynamics, "vt_inverse_dynamics");
    const vt_status sr = instant(m, dr, vt_inverse_dynamics_recursive, "vt_inverse_dynamics_recursive");
    if (!compare) goto out; /* off the constraints: statuses and finiteness only */
    if (perturb != 0.0 && sr == VT_OK) { /* FUZZ_PERTURB: a wrong route, for the tolerances' power */
        for (int c = 0; c < m->nv; c++) dr->qdd[c] *= 1.0 + perturb;
        dr->jnt_force[3 * m->nbody] *= 1.0 + perturb;
    }
    if (consistent("dense and recursive", m, sd, dd, sr, dr, in_mag)) {
        const scales s = pair_scales(m, dd, dd, dr, fmin(dd->rcond, dr->rcond));
        /* at overflow's edge (inputs ≥ EDGE_INPUT) products of four inputs overflow and the
         * round-off bound behind the tolerance no longer holds: statuses and finiteness only; nor
         * where redundant rows hold only in the least-squares sense (rows_hold: inconsistent γ, a
         * residual beyond round-off), whose answers move with the residual times the condition
         * squared, not with round-off alone */
        if (isfinite(s.e) && in_mag < EDGE_INPUT && rows_hold(m, dd, s.e) && rows_hold(m, dr, s.e)) {
            agree_qdd("dense and recursive", m, dd, dd->qdd, dr->qdd, &s);
            agree_loads("dense and recursive", m, dd, dr, &s, 1, 1);
            agree_totals("dense and recursive", m, dd, dd, dr, &s);
        }
    }
    if (sd != VT_OK) goto out;
    for (int k = 0; k < m->ndrive; k++) {
        double *F = calloc((size_t)m->nx + 1, sizeof(double));
        if (!F) break;
        dd->message[0] = '\0';
        const vt_status st = vt_drive_cartesian_force(F, m, dd, k);
        if (st == VT_OK) finite(F, m->nx, "vt_drive_cartesian_force", "F");
        else if (dd->message[0] == '\0') fail("vt_drive_cartesian_force failed (%s) with an empty message", vt_status_string(st));
        free(F);
    }

    /* the motion given: the dense q̈ for every rate */
    memcpy(dm->qdd, dd->qdd, (size_t)m->nv * sizeof(double));
    double *given = malloc((size_t)m->nv * sizeof(double) + 1);
    if (!given) goto out;
    memcpy(given, dd->qdd, (size_t)m->nv * sizeof(double));
    context.b = dm;
    const vt_status sm = instant(m, dm, vt_inverse_dynamics_motion, "vt_inverse_dynamics_motion");
    const int tree = m->ncut == 0 && m->ncoupling == 0;
    if (tree && memcmp(given, dm->qdd, (size_t)m->nv * sizeof(double)) != 0) fail("vt_inverse_dynamics_motion changed the given q̈");
    if (!tree && sm != VT_OK && memcmp(given, dm->qdd, (size_t)m->nv * sizeof(double)) != 0)
        fail("vt_inverse_dynamics_motion failed (%s) and did not put the given q̈ back", vt_status_string(sm));
    if (sm != VT_ERR_BAD_OPTION && consistent("dense and given-motion", m, sd, dd, sm, dm, in_mag)) {
        /* the motion's rcond is 1 (nothing solved in a tree): the dense one decides */
        const scales s = pair_scales(m, dd, dd, dm, fmin(dd->rcond, dm->rcond));
        if (sm == VT_OK && isfinite(s.e) && in_mag < EDGE_INPUT && rows_hold(m, dd, s.e)) frame_loads(m, state, dm, given, &s);
        if (!isfinite(s.e) || !rows_hold(m, dd, s.e)) {
        } else if (tree) {
            /* every rate's M* q̈ − Q is Φ_q^T λ of the drives (a tree's only rows); reactions
             * alike when every drive acts through its joint (point and orientation drives load
             * the body, not the joint) */
            agree_loads("dense and given-motion", m, dd, dm, &s, 0, all_joint_drives(m));
        } else {
            agree_qdd("dense and given-motion", m, dd, dd->qdd, dm->qdd, &s);
            agree_loads("dense and given-motion", m, dd, dm, &s, 1, 1);
        }
    }

    free(given);
    /* the same definitions with allow_redundant: at a clearly regular pose (rcond ≥ 1e-8, far
     * above any round-off rank decision) the redundant route must give the unique answer; not at
     * overflow's edge (inputs ≥ EDGE_INPUT: a 1e154 kg body of 6 kg m² has a radius of gyration
     * of 1e-77 m, which weighs its orientation rows to nothing) */
    if (!m->allow_redundant && m->nc > 0 && dd->rcond >= 1e-8 && in_mag < EDGE_INPUT) {
        vt_model *m1 = build(defs, 1);
        vt_data *d1 = NULL;
        if (m1 && m1->nc == m->nc && vt_data_create(&d1, m1) == VT_OK) {
            copy_state(m1, d1, state);
            context.b = d1;
            const vt_status s1 = instant(m1, d1, vt_inverse_dynamics, "vt_inverse_dynamics (allow_redundant)");
            const int refused = s1 == VT_ERR_SINGULAR && beyond_lever_arms(d1); /* its general route's */
            if (s1 != VT_OK && !refused)
                fail("allow_redundant: %s (%s) at a regular pose that the plain model solves (rcond %.3g)",
                     vt_status_string(s1), d1->message, dd->rcond);
            const scales s = pair_scales(m, dd, dd, d1, dd->rcond);
            if (!refused && isfinite(s.e)) {
                agree_qdd("allow_redundant 0 and 1", m, dd, dd->qdd, d1->qdd, &s);
                agree_loads("allow_redundant 0 and 1", m, dd, d1, &s, 1, 0);
            }
        }
        vt_data_free(d1);
        vt_model_free(m1);
    }
out:
    context.a = context.b = NULL;
    vt_data_free(dd);
    vt_data_free(dr);
    vt_data_free(dm);
}

static void reset_callbacks(definitions *defs)
{
    for (int k = 0; k < MAX_DRIVE; k++) defs->cb[k].after = 0;
}

/* a wrench at a frame over a run: a fixed one times scale, turning with t */
typedef struct {
    double scale;
} run_press;

static int press_at(double t, double *w, void *user)
{
    const run_press *p = user;
    const double base[6] = {10.0, -5.0, 3.0, 1.0, 0.5, -2.0};
    for (int k = 0; k < 6; k++) w[k] = p->scale * base[k] * (1.0 + 0.5 * sin(7.0 * t + k));
    return 0;
}

static void callbacks_stopped(const definitions *defs, vt_status st, const char *call)
{
    for (int k = 0; k < defs->ndrive; k++) {
        const callback_user *c = &defs->cb[k];
        if (c->after == 0) continue;
        if (c->after > 100)
            fail("%s: a time function failed from t = %g on, and was called %ld times after (%s)", call, c->first_fail,
                 c->after, vt_status_string(st));
        if (st != VT_ERR_CALLBACK && st != VT_ERR_NONFINITE)
            fail("%s: a time function failed at t = %g and the analysis ended with %s (%s)", call, c->first_fail,
                 vt_status_string(st), st ? "" : "VT_OK");
    }
}

/* The motion given at overflow's edge (fuzz/corpus/motion-euler-rates-overflow): the instants above give the motion call
 * the dense q̈, which a modest input keeps far from DBL_MAX, so the call met q̈ and q̇ near
 * overflow only rarely. Here the last bytes (after every other piece: older inputs end before
 * them and read 0, which skips this step) pick them: a selector byte, q̇'s mode in its bits 0–1
 * and q̈'s in bits 2–3, each 0 the state's q̇ (q̈: a number of the bytes), 1 a number times 10^k,
 * k = 150..308 from a byte (clamped to ±DBL_MAX), 2 an edge of the double range (EDGES, sign from
 * the byte's top bit), 3 a number times 1e300 (clamped). vt_inverse_dynamics_motion, then
 * vt_inverse_dynamics_recursive and vt_inverse_dynamics at that q̇, each on fresh data: VT_OK with
 * every output finite, or a failure with a message and its inputs as they were; the given q̈
 * left as it was (a tree) or put back (a failure with loops). No comparison: at this edge one
 * route's intermediate may overflow where another's does not. */
static const double EDGES[8] = {DBL_MAX, 1.5e308, 1e308, 8.98846567431158e307 /* DBL_MAX / 2 */,
                                1e300, 1.3407807929942596e154 /* sqrt(DBL_MAX) */, 1e154, 1.0};

static double clamped(double x)
{
    return isnan(x) ? x : fmax(-DBL_MAX, fmin(DBL_MAX, x));
}

static double edge_number(bytes *b, unsigned mode, double keep)
{
    switch (mode & 3) {
    case 0: return keep;
    case 1: {
        const double x = num(b);
        return clamped(x * pow(10.0, 150.0 + (double)(byte(b) % 159)));
    }
    case 2: {
        const unsigned k = byte(b);
        return (k & 128 ? -1.0 : 1.0) * EDGES[k % 8];
    }
    default: return clamped(num(b) * 1e300);
    }
}

static void edge_instant(const vt_model *m, const vt_data *state, const double *qd, const double *qdd,
                         vt_status (*fn)(const vt_model *, vt_data *), const char *call)
{
    vt_data *d = NULL;
    double *given = malloc((size_t)m->nv * sizeof(double) + 1);
    if (!given || vt_data_create(&d, m)) {
        free(given);
        return;
    }
    copy_state(m, d, state);
    memcpy(d->qd, qd, (size_t)m->nv * sizeof(double));
    memcpy(d->qdd, qdd, (size_t)m->nv * sizeof(double));
    memcpy(given, qdd, (size_t)m->nv * sizeof(double));
    context.b = d;
    const vt_status st = instant(m, d, fn, call);
    if (fn == vt_inverse_dynamics_motion && (st != VT_OK || (m->ncut == 0 && m->ncoupling == 0)) &&
        memcmp(given, d->qdd, (size_t)m->nv * sizeof(double)) != 0)
        fail("%s (%s) changed the given q̈ or did not put it back", call, vt_status_string(st));
    context.b = NULL;
    free(given);
    vt_data_free(d);
}

static void motion_edge(const vt_model *m, const vt_data *state, bytes *b)
{
    const unsigned sel = byte(b);
    if (sel == 0 || m->nv == 0) return;
    double *qd = malloc(2 * (size_t)m->nv * sizeof(double));
    if (!qd) return;
    double *qdd = qd + m->nv;
    for (int c = 0; c < m->nv; c++) qd[c] = edge_number(b, sel, state->qd[c]);
    for (int c = 0; c < m->nv; c++) qdd[c] = ((sel >> 2) & 3) == 0 ? num(b) : edge_number(b, sel >> 2, 0.0);
    edge_instant(m, state, qd, qdd, vt_inverse_dynamics_motion, "vt_inverse_dynamics_motion (q̇, q̈ at overflow's edge)");
    edge_instant(m, state, qd, qdd, vt_inverse_dynamics_recursive, "vt_inverse_dynamics_recursive (q̇ at overflow's edge)");
    edge_instant(m, state, qd, qdd, vt_inverse_dynamics, "vt_inverse_dynamics (q̇ at overflow's edge)");
    free(qd);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    if (setjmp(skip_input)) { /* an excluded reason (FUZZ_EXCLUDE) */
        context.m = NULL, context.a = context.b = NULL;
        return 0;
    }
    definitions defs;
    memset(&defs, 0, sizeof defs);
    read_definitions(&b, &defs);
    vt_model *m = build(&defs, defs.md.allow_redundant);
    if (!m) return 0;
    context.m = m;
    if (getenv("FUZZ_DESCRIBE")) describe(); /* FUZZ_DESCRIBE=1: the model each input makes (seeds) */
    if (getenv("FUZZ_PERTURB")) perturb = atof(getenv("FUZZ_PERTURB"));
    model_check(m);
    vt_data *d = NULL;
    if (vt_data_create(&d, m)) {
        vt_model_free(m);
        return 0;
    }
    for (int k = 0; k < m->nq; k++) d->q[k] = byte(&b) % 8 ? d->q[k] + num(&b) * 0.3 : num(&b);
    for (int k = 0; k < m->nv; k++) d->qd[k] = num(&b);
    if (byte(&b) % 3 == 0)
        for (int k = 0; k < 6 * (m->nbody + 1); k++) d->xfrc[k] = num(&b);
    d->time = num(&b);
    if (byte(&b) % 4 == 0)
        for (int k = 0; k < m->nv; k++) d->qfrc[k] = num(&b);
    /* Euler parameters in q are unit and a base body's ṗ is normal to p (the constraints the
     * instants take as given, not corrected): made so unless the bytes say otherwise, and only
     * such states are compared between routes (off the constraint the routes may legitimately
     * differ: one reads |p|, another assumes 1) */
    const int raw = byte(&b) % 16 == 0;
    int unit_state = 1;
    for (int i = 1; i <= m->nbody; i++) {
        const int jt = m->body_joint[i];
        if (jt != VT_JOINT_SPHERICAL && jt != VT_JOINT_BASE && jt != VT_JOINT_FREE) continue;
        double *p = d->q + m->body_qadr[i] + (jt == VT_JOINT_SPHERICAL ? 0 : 3);
        const double big = maxabs(p, 4);
        double n2 = 0.0;
        for (int k = 0; k < 4; k++) n2 += (p[k] / big) * (p[k] / big);
        if (!raw && big > 0.0 && isfinite(big) && isfinite(n2))
            for (int k = 0; k < 4; k++) p[k] = (p[k] / big) / sqrt(n2);
        if (jt == VT_JOINT_BASE && !raw) {
            double *pd = d->qd + m->body_vadr[i] + 3, c = 0.0;
            for (int k = 0; k < 4; k++) c += p[k] * pd[k];
            if (isfinite(c))
                for (int k = 0; k < 4; k++) pd[k] -= c * p[k];
        }
        double u = 0.0, v = 0.0;
        for (int k = 0; k < 4; k++) u += p[k] * p[k];
        if (jt == VT_JOINT_BASE)
            for (int k = 0; k < 4; k++) v += p[k] * d->qd[m->body_vadr[i] + 3 + k];
        /* p · ṗ against ṗ's own size (a base body's ṙ may be far larger) */
        if (!(fabs(u - 1.0) <= 1e-12) ||
            !(fabs(v) <= 1e-12 * (1.0 + (jt == VT_JOINT_BASE ? maxabs(d->qd + m->body_vadr[i] + 3, 4) : 0.0))))
            unit_state = 0;
    }

    differential(&defs, m, d, unit_state);

    vt_data *ds = NULL;
    if (vt_data_create(&ds, m) == VT_OK) {
        copy_state(m, ds, d);
        stages(m, ds, &b);
        vt_data_free(ds);
    }

    /* the kinematic solve: a tolerance that is not finite must be refused; VT_OK finite; a failure
     * restores q and q̇ and says why */
    const double tol = byte(&b) % 8 ? 1e-10 : num(&b);
    double *before = malloc((input_count(m) + 1) * sizeof(double));
    if (before) {
        save_inputs(m, d, before);
        d->message[0] = '\0';
        reset_callbacks(&defs);
        const vt_status st = vt_kinematic_solve(m, d, tol, 8);
        if (st == VT_OK) {
            if (!isfinite(tol)) fail("vt_kinematic_solve accepted tol = %g", tol);
            data_finite(m, d, "vt_kinematic_solve");
        } else {
            failed_call(m, d, before, st, "vt_kinematic_solve");
        }
        free(before);
    }
    if (byte(&b) % 2) {
        vt_trajectory *tr = NULL;
        run_press press = {0.0};
        vt_run_options o = vt_default_run_options();
        o.t1 = o.t0 + 0.01 + fabs(num(&b)) * 1e-3;
        o.nout = 2;
        o.max_steps = 60;
        o.formulation = (int)(byte(&b) % 6);
        o.forward_check = (int)(byte(&b) % 2);
        o.forward_independent = (int)(byte(&b) % 2);
        const unsigned wb = byte(&b), which = wb % 16;
        if (which == 1) o.rtol = num(&b);
        if (which == 2) o.atol = num(&b);
        if (which == 3) o.newton_tol = num(&b);
        if (vt_trajectory_create(&tr, m, 3) == VT_OK) {
            const int kin = m->nc == m->nv && byte(&b) % 2;
            /* a kinematic analysis with a wrench at the first frame over the run, from the byte's
             * high bits (0: none): NaN (1), 1e300 times a fixed one (2: its moments overflow),
             * else 1 or 1e3 times it, the run going through */
            if (kin && wb >> 4 && m->nframe > 0) {
                static const int frame0[1] = {0};
                const unsigned h = wb >> 4;
                press.scale = h == 1 ? (double)NAN : h == 2 ? 1e300 : h % 2 ? 1e3 : 1.0;
                o.nload = 1, o.load_frame = frame0, o.loads = press_at, o.load_user = &press;
            }
            const char *call = kin ? "vt_kinematic_analysis" : "vt_dynamic_analysis";
            d->message[0] = '\0';
            reset_callbacks(&defs);
            double *xfrc0 = malloc(6 * ((size_t)m->nbody + 1) * sizeof(double));
            if (xfrc0) memcpy(xfrc0, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
            const vt_status st = kin ? vt_kinematic_analysis(m, d, &o, tr) : vt_dynamic_analysis(m, d, &o, tr);
            if (xfrc0 && memcmp(xfrc0, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double)) != 0)
                fail("%s (%s) left the caller's xfrc changed", call, vt_status_string(st));
            free(xfrc0);
            if (st == VT_OK) {
                if (!isfinite(o.newton_tol) || (!kin && (!isfinite(o.rtol) || !isfinite(o.atol))))
                    fail("%s accepted rtol %g, atol %g, newton_tol %g", call, o.rtol, o.atol, o.newton_tol);
                trajectory_finite(m, tr, call);
            } else if (d->message[0] == '\0') {
                fail("%s failed (%s) with an empty message", call, vt_status_string(st));
            }
            callbacks_stopped(&defs, st, call);
            vt_trajectory_free(tr);
        }
    }
    motion_edge(m, d, &b);
    context.m = NULL;
    vt_data_free(d);
    vt_model_free(m);
    if (getenv("FUZZ_STATS") && worst_ratio > 0.0) fprintf(stderr, "worst ratio %.3g\n", worst_ratio);
    return 0;
}
