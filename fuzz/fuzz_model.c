/* libFuzzer harness: bytes become body, joint, drive and cut-joint definitions, a state, time
 * functions and run options; the model is built and an instant (dense and recursive), a
 * kinematic solve and a short dynamic analysis are run. Whatever the bytes, the library must
 * answer with a status: no crash, no sanitizer report, no non-finite result after VT_OK.
 * Build and run: bash fuzz/run.sh [seconds]. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vtdyn.h"

typedef struct {
    const uint8_t *p;
    size_t n;
} bytes;

static unsigned byte(bytes *b)
{
    if (b->n == 0) return 0;
    b->n--;
    return *b->p++;
}

/* mostly ordinary numbers, sometimes the awkward ones */
static double num(bytes *b)
{
    static const double special[16] = {0.0, 1.0, -1.0, 1e-9, 1e9, 1e300, -1e300, 1e-300,
                                       NAN, INFINITY, -INFINITY, 0.5, 2.0, 1e-6, 1e6, -0.0};
    const unsigned v = byte(b);
    if (v < 240) return ((double)v - 120.0) / 16.0;
    return special[v - 240];
}

static int fill_function(bytes *b, vt_function *f)
{
    const unsigned k = byte(b) % 5;
    double c[VT_POLY_MAX];
    for (int i = 0; i < VT_POLY_MAX; i++) c[i] = num(b);
    if (k == 0) *f = vt_function_constant(c[0]);
    else if (k == 1) *f = vt_function_polynomial((int)(byte(b) % 10), c);
    else if (k == 2) *f = vt_function_sine(c[0], c[1], c[2], c[3]);
    else if (k == 3) *f = vt_function_user(NULL, NULL);
    else { *f = vt_function_constant(c[0]); f->type = (vt_function_type)(byte(b) % 7); }
    return 0;
}

static void check_finite(const double *a, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i])) abort(); /* a VT_OK result must be finite */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    vt_model_def md = vt_default_model_def();
    if (byte(&b) % 4 == 0) {
        md.gravity[1] = num(&b);
        md.rcond_min = fabs(num(&b)) * 1e-12;
        md.rcond_warn = md.rcond_min * 10.0;
        md.allow_redundant = (int)(byte(&b) % 2);
    }
    vt_builder *builder;
    if (vt_builder_create(&builder, &md)) return 0;
    const int nbody = 1 + (int)(byte(&b) % 6);
    for (int i = 1; i <= nbody; i++) {
        vt_body_def d = vt_default_body_def();
        d.parent = (int)(byte(&b) % (unsigned)(i + 1)) - (byte(&b) % 16 == 0);
        d.joint = (vt_joint_type)(byte(&b) % 7);
        d.mass = byte(&b) % 8 ? fabs(num(&b)) + 0.1 : num(&b);
        const unsigned shape = byte(&b) % 4;
        if (shape == 0)
            for (int k = 0; k < 9; k++) d.inertia[k] = num(&b);
        else if (shape == 1)
            d.inertia[0] = d.inertia[4] = d.inertia[8] = fabs(num(&b));
        for (int k = 0; k < 3; k++) {
            d.joint_parent[k] = num(&b);
            d.joint_child[k] = num(&b);
            if (byte(&b) % 2) d.axis1[k] = num(&b);
            if (byte(&b) % 4 == 0) d.axis2[k] = num(&b);
        }
        if (byte(&b) % 4 == 0)
            for (int k = 0; k < 4; k++) d.orientation[k] = num(&b);
        vt_builder_add_body(builder, &d); /* refusals are fine */
    }
    const int ndrive = (int)(byte(&b) % 5);
    for (int k = 0; k < ndrive; k++) {
        vt_drive_def d = vt_default_drive_def();
        d.type = (vt_drive_type)(byte(&b) % 4);
        d.body = (int)(byte(&b) % 8);
        d.index = (int)(byte(&b) % 5) - 1;
        for (int c = 0; c < 3; c++) {
            d.point[c] = num(&b);
            d.axis[c] = num(&b);
        }
        fill_function(&b, &d.f);
        vt_builder_add_drive(builder, &d);
    }
    const int ncut = (int)(byte(&b) % 3);
    for (int k = 0; k < ncut; k++) {
        vt_cut_joint_def c = vt_default_cut_joint_def();
        c.joint = (vt_joint_type)(byte(&b) % 7);
        c.body_a = (int)(byte(&b) % 8);
        c.body_b = (int)(byte(&b) % 8);
        for (int e = 0; e < 3; e++) {
            c.point_a[e] = num(&b);
            c.point_b[e] = num(&b);
            if (byte(&b) % 2) c.axis1[e] = num(&b);
        }
        vt_builder_add_cut_joint(builder, &c);
    }
    vt_model *m = NULL;
    const vt_status st = vt_builder_build(&m, builder);
    vt_builder_free(builder);
    if (st) return 0;
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
    if (vt_inverse_dynamics(m, d) == VT_OK) {
        check_finite(d->qdd, m->nv);
        check_finite(d->jnt_force, 3 * (m->nbody + 1));
        check_finite(d->drive_effort, m->ndrive);
    }
    if (vt_inverse_dynamics_recursive(m, d) == VT_OK) check_finite(d->jnt_moment, 3 * (m->nbody + 1));
    vt_kinematic_solve(m, d, 1e-10, 8);
    if (byte(&b) % 2) {
        vt_trajectory *tr = NULL;
        vt_run_options o = vt_default_run_options();
        o.t1 = o.t0 + 0.01 + fabs(num(&b)) * 1e-3;
        o.nout = 2;
        o.max_steps = 60;
        o.formulation = (int)(byte(&b) % 6);
        o.forward_check = (int)(byte(&b) % 2);
        o.forward_independent = (int)(byte(&b) % 2);
        if (vt_trajectory_create(&tr, m, 3) == VT_OK) {
            if (m->nc == m->nv && byte(&b) % 2) vt_kinematic_analysis(m, d, &o, tr);
            else vt_dynamic_analysis(m, d, &o, tr);
            vt_trajectory_free(tr);
        }
    }
    vt_data_free(d);
    vt_model_free(m);
    return 0;
}
