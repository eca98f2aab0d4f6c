/* The error contract of the public interface, function by function (issue "Hardening"):
 * NULL pointers, a data struct made for another model, NaN or Inf in every state input and in
 * time functions, user callbacks that fail, bad indices and run options. Each call must
 * return its distinct status (never crash), say why in the message, and leave the caller's
 * inputs bitwise as they were. Every status has its own text. */
#include "vt_test.h"

/* the caller-owned inputs of a data struct, to compare bitwise after a failed call */
typedef struct {
    double q[64], qd[64], xfrc[64], qfrc[64], qdd[64], lambda[64], time;
} inputs;

static void snapshot(inputs *s, const vt_model *m, const vt_data *d)
{
    memset(s, 0, sizeof *s);
    memcpy(s->q, d->q, (size_t)m->nq * sizeof(double));
    memcpy(s->qd, d->qd, (size_t)m->nv * sizeof(double));
    memcpy(s->xfrc, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    memcpy(s->qfrc, d->qfrc, (size_t)m->nv * sizeof(double));
    memcpy(s->qdd, d->qdd, (size_t)m->nv * sizeof(double));
    memcpy(s->lambda, d->lambda, (size_t)m->nc * sizeof(double));
    s->time = d->time;
}

static void assert_unchanged(const inputs *before, const vt_model *m, const vt_data *d)
{
    inputs now;
    snapshot(&now, m, d);
    assert_memory_equal(before, &now, sizeof now);
}

/* every function that takes a model and its data, called the same way */
typedef vt_status (*stage_fn)(const vt_model *, vt_data *);
static vt_status kinematic_solve(const vt_model *m, vt_data *d) { return vt_kinematic_solve(m, d, 1e-12, 20); }
static vt_status point_load(const vt_model *m, vt_data *d)
{
    const double p[3] = {0, 0, 0}, f[3] = {1, 0, 0};
    return vt_add_point_load(m, d, 1, p, f, NULL);
}
static vt_status drive_force(const vt_model *m, vt_data *d)
{
    double F[64];
    return vt_drive_cartesian_force(F, m, d, 0);
}
static vt_status generalized(const vt_model *m, vt_data *d)
{
    double F[64] = {0}, Q[64];
    return vt_generalized_force(Q, m, d, F);
}
static vt_status equivalent(const vt_model *m, vt_data *d)
{
    double Q[64] = {0}, F[64];
    return vt_equivalent_force(F, m, d, Q);
}
static const struct {
    const char *name;
    stage_fn fn;
} stages[] = {
    {"vt_kinematics", vt_kinematics},
    {"vt_inverse_transform", vt_inverse_transform},
    {"vt_mass_matrix", vt_mass_matrix},
    {"vt_forces", vt_forces},
    {"vt_constraints", vt_constraints},
    {"vt_solve", vt_solve},
    {"vt_reactions", vt_reactions},
    {"vt_inverse_dynamics", vt_inverse_dynamics},
    {"vt_inverse_dynamics_recursive", vt_inverse_dynamics_recursive},
    {"vt_inverse_dynamics_motion", vt_inverse_dynamics_motion},
    {"vt_kinematic_solve", kinematic_solve},
    {"vt_data_reset", vt_data_reset},
    {"vt_add_point_load", point_load},
    {"vt_drive_cartesian_force", drive_force},
    {"vt_generalized_force", generalized},
    {"vt_equivalent_force", equivalent},
};
#define NSTAGES (sizeof stages / sizeof stages[0])

/* the double link with its lock: one drive, a consistent state */
static void make(vt_model **m, vt_data **d)
{
    assert_ok(vt_scene_double_link(m, 1));
    assert_ok(vt_data_create(d, *m));
    (*d)->q[0] = -0.6;
    (*d)->qd[0] = -sqrt(7.3575 * sin(0.6));
    assert_ok(vt_inverse_dynamics(*m, *d));
}

static void test_null_and_mismatch(void **state)
{
    (void)state;
    vt_model *m, *other;
    vt_data *d, *od;
    make(&m, &d);
    assert_ok(vt_scene_fourbar(&other, vt_function_constant(0.3)));
    assert_ok(vt_data_create(&od, other));
    for (size_t k = 0; k < NSTAGES; k++) {
        inputs before;
        snapshot(&before, m, d);
        assert_int_equal(stages[k].fn(NULL, d), VT_ERR_NULL);
        assert_int_equal(stages[k].fn(m, NULL), VT_ERR_NULL);
        d->message[0] = '\0';
        const vt_status st = stages[k].fn(m, od);
        if (st != VT_ERR_MODEL_MISMATCH) fail_msg("%s with another model's data: %d", stages[k].name, (int)st);
        assert_non_null(strstr(od->message, "another model"));
        assert_unchanged(&before, m, d);
    }
    /* outputs and other pointers */
    double buf[64] = {0};
    const double p[3] = {0, 0, 0};
    assert_int_equal(vt_generalized_force(NULL, m, d, buf), VT_ERR_NULL);
    assert_int_equal(vt_generalized_force(buf, m, d, NULL), VT_ERR_NULL);
    assert_int_equal(vt_equivalent_force(NULL, m, d, buf), VT_ERR_NULL);
    assert_int_equal(vt_equivalent_force(buf, m, d, NULL), VT_ERR_NULL);
    assert_int_equal(vt_drive_cartesian_force(NULL, m, d, 0), VT_ERR_NULL);
    assert_int_equal(vt_integrate_q(NULL, m, d->q, d->qd, 0.1), VT_ERR_NULL);
    assert_int_equal(vt_integrate_q(buf, m, NULL, d->qd, 0.1), VT_ERR_NULL);
    assert_int_equal(vt_integrate_q(buf, m, d->q, NULL, 0.1), VT_ERR_NULL);
    assert_int_equal(vt_integrate_q(buf, NULL, d->q, d->qd, 0.1), VT_ERR_NULL);
    assert_int_equal(vt_add_point_load(m, d, 1, NULL, p, NULL), VT_ERR_NULL);
    const vt_function f = vt_function_constant(1.0);
    assert_int_equal(vt_function_eval(NULL, &f, 0.0), VT_ERR_NULL);
    assert_int_equal(vt_function_eval(buf, NULL, 0.0), VT_ERR_NULL);
    vt_trajectory *tr = NULL;
    assert_int_equal(vt_trajectory_create(NULL, m, 3), VT_ERR_NULL);
    assert_int_equal(vt_trajectory_create(&tr, NULL, 3), VT_ERR_NULL);
    assert_ok(vt_trajectory_create(&tr, m, 3));
    vt_run_options opt = vt_default_run_options();
    opt.nout = 2;
    assert_int_equal(vt_kinematic_analysis(NULL, d, &opt, tr), VT_ERR_NULL);
    assert_int_equal(vt_kinematic_analysis(m, NULL, &opt, tr), VT_ERR_NULL);
    assert_int_equal(vt_kinematic_analysis(m, d, NULL, tr), VT_ERR_NULL);
    assert_int_equal(vt_kinematic_analysis(m, d, &opt, NULL), VT_ERR_NULL);
#if VT_HAVE_SUNDIALS
    assert_int_equal(vt_dynamic_analysis(NULL, d, &opt, tr), VT_ERR_NULL);
    assert_int_equal(vt_dynamic_analysis(m, NULL, &opt, tr), VT_ERR_NULL);
    assert_int_equal(vt_dynamic_analysis(m, d, NULL, tr), VT_ERR_NULL);
    assert_int_equal(vt_dynamic_analysis(m, d, &opt, NULL), VT_ERR_NULL);
    assert_int_equal(vt_dynamic_analysis(m, od, &opt, tr), VT_ERR_MODEL_MISMATCH);
#endif
    vt_model *md = NULL;
    assert_int_equal(vt_model_without_drives(NULL, m), VT_ERR_NULL);
    assert_int_equal(vt_model_without_drives(&md, NULL), VT_ERR_NULL);
    assert_int_equal(vt_data_create(NULL, m), VT_ERR_NULL);
    vt_data *dn = (vt_data *)buf;
    assert_int_equal(vt_data_create(&dn, NULL), VT_ERR_NULL);
    /* the free functions accept NULL */
    vt_builder_free(NULL);
    vt_model_free(NULL);
    vt_data_free(NULL);
    vt_trajectory_free(NULL);
    assert_non_null(vt_builder_message(NULL));
    vt_trajectory_free(tr);
    vt_data_free(od);
    vt_model_free(other);
    vt_data_free(d);
    vt_model_free(m);
}

/* NaN and Inf in each state input: the entry points that read it refuse with
 * VT_ERR_NONFINITE and leave every input, and q̈ and λ, as they were */
static void test_nonfinite_states(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    make(&m, &d);
    const double bad[2] = {NAN, INFINITY};
    stage_fn entry[3] = {vt_inverse_dynamics, vt_inverse_dynamics_recursive, kinematic_solve};
    for (int which = 0; which < 5; which++)
        for (int b = 0; b < 2; b++)
            for (int e = 0; e < 3; e++) {
                double *slot = which == 0 ? &d->q[0] : which == 1 ? &d->qd[0] : which == 2 ? &d->xfrc[6 + 1]
                             : which == 3 ? &d->qfrc[1] : &d->time;
                const double keep = *slot;
                *slot = bad[b];
                inputs before;
                snapshot(&before, m, d);
                const vt_status st = entry[e](m, d);
                if (st != VT_ERR_NONFINITE)
                    fail_msg("input %d = %g, entry %d: status %d (%s)", which, bad[b], e, (int)st, d->message);
                assert_true(strlen(d->message) > 0);
                assert_unchanged(&before, m, d);
                *slot = keep;
            }
    /* the stages on their own refuse a non-finite q or q̇ as well */
    for (int which = 0; which < 2; which++) {
        double *slot = which ? &d->qd[0] : &d->q[0];
        const double keep = *slot;
        *slot = NAN;
        assert_int_equal(vt_kinematics(m, d), VT_ERR_NONFINITE);
        *slot = keep;
    }
    double out[8];
    assert_int_equal(vt_integrate_q(out, m, d->q, d->qd, NAN), VT_ERR_NONFINITE);
    vt_data_free(d);
    vt_model_free(m);
}

/* a time function that fails, one that returns NaN, and a polynomial with NaN coefficients */
static int failing(double t, double out[3], void *user)
{
    (void)t;
    (void)out;
    (void)user;
    return 7;
}
static int nan_at_half(double t, double out[3], void *user)
{
    (void)user;
    out[0] = t > 0.5 ? NAN : 0.1 * t;
    out[1] = 0.1;
    out[2] = 0.0;
    return 0;
}

static void test_time_functions(void **state)
{
    (void)state;
    double out[3] = {1, 2, 3};
    const vt_function f1 = vt_function_user(failing, NULL), f2 = vt_function_user(nan_at_half, NULL);
    assert_int_equal(vt_function_eval(out, &f1, 0.0), VT_ERR_CALLBACK);
    assert_int_equal(vt_function_eval(out, &f2, 0.7), VT_ERR_NONFINITE);
    assert_true(out[0] == 1 && out[1] == 2 && out[2] == 3); /* untouched */
    const double c[2] = {NAN, 1.0};
    const vt_function p = vt_function_polynomial(2, c);
    assert_int_not_equal(vt_function_eval(out, &p, 0.0), VT_OK);
    const double many[VT_POLY_MAX + 1] = {0};
    const vt_function big = vt_function_polynomial(VT_POLY_MAX + 1, many);
    assert_int_equal(vt_function_eval(out, &big, 0.0), VT_ERR_BAD_DRIVE);

    /* in a model: the drive's failure reaches the caller with the drive named, inputs kept */
    for (int k = 0; k < 2; k++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def link = vt_default_body_def();
        link.inertia[4] = link.inertia[8] = 0.1;
        assert_int_equal(vt_builder_add_body(b, &link), 1);
        vt_drive_def dr = vt_default_drive_def();
        dr.f = k ? f2 : f1;
        assert_int_equal(vt_builder_add_drive(b, &dr), 0);
        vt_model *m;
        vt_data *d;
        assert_ok(vt_builder_build(&m, b));
        vt_builder_free(b);
        assert_ok(vt_data_create(&d, m));
        d->time = 0.7;
        d->qdd[0] = 42.0;
        d->lambda[0] = -42.0;
        inputs before;
        snapshot(&before, m, d);
        const stage_fn entry[3] = {vt_inverse_dynamics, vt_inverse_dynamics_recursive, kinematic_solve};
        for (int e = 0; e < 3; e++) {
            const vt_status st = entry[e](m, d);
            assert_int_equal(st, k ? VT_ERR_NONFINITE : VT_ERR_CALLBACK);
            assert_non_null(strstr(d->message, "drive 0"));
            assert_unchanged(&before, m, d);
        }
        vt_trajectory *tr;
        assert_ok(vt_trajectory_create(&tr, m, 11));
        vt_run_options opt = vt_default_run_options();
        opt.nout = 10;
        opt.forward_check = 0;
        assert_int_equal(vt_kinematic_analysis(m, d, &opt, tr), k ? VT_ERR_NONFINITE : VT_ERR_CALLBACK);
        vt_trajectory_free(tr);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* a spline drive with bad samples: refused with its status and a message naming the sample,
 * the builder as it was (the next drive added gets index 0, the model has that one only) */
static void test_spline_drives(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def link = vt_default_body_def();
    link.inertia[4] = link.inertia[8] = 0.1;
    assert_int_equal(vt_builder_add_body(b, &link), 1);
    const double t[4] = {0.0, 0.5, 0.5, 1.5}, tn[4] = {0.0, 0.5, INFINITY, 1.5}, y[4] = {0.0, 0.1, 0.3, 0.2},
                 yn[4] = {0.0, NAN, 0.3, 0.2}, tok[4] = {0.0, 0.5, 1.0, 1.5};
    const struct {
        vt_function f;
        vt_status st;
        const char *says;
    } bad[6] = {{vt_function_spline(1, tok, y), VT_ERR_BAD_DRIVE, "1 samples"},
                {vt_function_spline(4, t, y), VT_ERR_BAD_DRIVE, "not strictly increasing at sample 2"},
                {vt_function_spline(4, tn, y), VT_ERR_NONFINITE, "sample 2 not finite"},
                {vt_function_spline(4, tok, yn), VT_ERR_NONFINITE, "sample 1 not finite"},
                {vt_function_spline(4, NULL, y), VT_ERR_BAD_DRIVE, "NULL"},
                {vt_function_spline(4, tok, NULL), VT_ERR_BAD_DRIVE, "NULL"}};
    vt_drive_def dr = vt_default_drive_def();
    for (int k = 0; k < 6; k++) {
        dr.f = bad[k].f;
        const vt_drive_def keep = dr;
        assert_int_equal(vt_builder_add_drive(b, &dr), bad[k].st);
        assert_memory_equal(&dr, &keep, sizeof dr); /* the caller's definition untouched */
        if (!strstr(vt_builder_message(b), bad[k].says) || !strstr(vt_builder_message(b), "drive 0"))
            fail_msg("case %d: message \"%s\" lacks \"%s\"", k, vt_builder_message(b), bad[k].says);
    }
    dr.f = vt_function_spline(4, tok, y);
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->ndrive, 1);
    assert_int_equal(m->drive[0].f.nsample, 4);
    for (int k = 0; k < 4; k++) assert_true(m->drive[0].f.sample_t[k] == tok[k] && m->drive[0].f.sample_y[k] == y[k]);
    assert_true(m->drive[0].f.sample_t != tok); /* the model's own copy */
    vt_model_free(m);
}

/* indices out of range and run options out of range */
static void test_indices_and_options(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    make(&m, &d);
    const double p[3] = {0, 0, 0}, f[3] = {1, 0, 0};
    double F[64];
    inputs before;
    snapshot(&before, m, d);
    assert_int_equal(vt_add_point_load(m, d, 0, p, f, NULL), VT_ERR_BAD_INDEX);
    assert_int_equal(vt_add_point_load(m, d, m->nbody + 1, p, f, NULL), VT_ERR_BAD_INDEX);
    assert_int_equal(vt_drive_cartesian_force(F, m, d, -1), VT_ERR_BAD_INDEX);
    assert_int_equal(vt_drive_cartesian_force(F, m, d, m->ndrive), VT_ERR_BAD_INDEX);
    const double fnan[3] = {NAN, 0, 0};
    assert_int_equal(vt_add_point_load(m, d, 1, p, fnan, NULL), VT_ERR_NONFINITE);
    assert_unchanged(&before, m, d);
    vt_trajectory *tr;
    assert_ok(vt_trajectory_create(&tr, m, 11));
    vt_trajectory *none = tr;
    assert_int_equal(vt_trajectory_create(&none, m, 0), VT_ERR_BAD_OPTION);
    assert_null(none);
    vt_run_options bad[8];
    for (int k = 0; k < 8; k++) {
        bad[k] = vt_default_run_options();
        bad[k].nout = 10;
    }
    bad[0].t1 = bad[0].t0;        /* empty interval */
    bad[1].t1 = NAN;
    bad[2].nout = 0;
    bad[3].nout = 11;             /* more rows than the trajectory has */
    bad[4].rtol = 0.0;
    bad[5].atol = -1.0;
    bad[6].max_steps = 0;
    bad[7].rtol = NAN;
    for (int k = 0; k < 8; k++) {
        snapshot(&before, m, d);
        assert_int_equal(vt_kinematic_analysis(m, d, &bad[k], tr), VT_ERR_BAD_OPTION);
        assert_true(strlen(d->message) > 0);
#if VT_HAVE_SUNDIALS
        assert_int_equal(vt_dynamic_analysis(m, d, &bad[k], tr), VT_ERR_BAD_OPTION);
#endif
        assert_unchanged(&before, m, d);
    }
    /* bad lists of output times: refused naming the entry, the data and the trajectory as they were */
    const double t_nan[3] = {0.1, NAN, 0.5}, t_down[3] = {0.1, 0.4, 0.3}, t_at0[2] = {0.0, 0.5},
                 t_past[3] = {0.1, 0.5, 1.5}, t_ok[3] = {0.1, 0.4, 0.9}, many[11] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6,
                                                                                    0.7, 0.8, 0.9, 0.95, 1.0};
    const struct {
        const double *tout;
        int ntout;
        const char *says;
    } list[7] = {{t_nan, 3, "tout[1] is not finite"}, {t_down, 3, "tout[2] = 0.3 is not after the previous"},
                 {t_at0, 2, "tout[0] = 0 is not after t0"}, {t_past, 3, "tout[2] = 1.5 is after t1"},
                 {many, 11, "ntout 11 needs 12"}, {NULL, 3, "tout NULL"}, {t_ok, 0, "ntout 0"}};
    for (int k = 0; k < 7; k++) {
        vt_run_options o = vt_default_run_options();
        o.tout = list[k].tout;
        o.ntout = list[k].ntout;
        tr->nfilled = 5;
        tr->t[3] = 42.0;
        snapshot(&before, m, d);
        for (int a = 0; a < 1 + VT_HAVE_SUNDIALS; a++) {
            d->message[0] = '\0';
#if VT_HAVE_SUNDIALS
            const vt_status st = a ? vt_dynamic_analysis(m, d, &o, tr) : vt_kinematic_analysis(m, d, &o, tr);
#else
            const vt_status st = vt_kinematic_analysis(m, d, &o, tr);
#endif
            assert_int_equal(st, VT_ERR_BAD_OPTION);
            if (!strstr(d->message, list[k].says))
                fail_msg("list %d: message \"%s\" lacks \"%s\"", k, d->message, list[k].says);
            assert_unchanged(&before, m, d);
            assert_true(tr->nfilled == 5 && tr->t[3] == 42.0);
        }
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* the diagnostics of the last instant or solve, all cleared */
static void assert_no_diagnostics(const vt_data *d, const char *who, const char *what)
{
    if (d->route != VT_ROUTE_NONE || d->fallback != 0 || d->warning != 0 || d->rank != 0 || d->rcond != 0.0 ||
        d->residual != 0.0)
        fail_msg("%s, %s: stale diagnostics: route %d, fallback %d, warning %d, rank %d, rcond %.3g, residual %.3g", who,
                 what, (int)d->route, d->fallback, d->warning, d->rank, d->rcond, d->residual);
}

/* Every entry point that owns the diagnostics (the instants, vt_kinematic_solve, vt_solve, the
 * analyses, vt_data_reset) clears route, fallback, warning, rank, rcond and residual at its
 * start: after a successful ill-conditioned instant (the five-rod chain with masses rising over
 * 12 orders, driven at two points: the Schur route gives way to the augmented one, which warns
 * below rcond_warn), a call that fails before its solve (NaN in q, in a load or in Q; an
 * option out of range; a model not fully driven) leaves none of that instant's diagnostics. */
static void test_stale_diagnostics(void **state)
{
    (void)state;
    vt_model *m = vt_test_ratio_chain(1, 4, 3.0);
    m->rcond_warn = 0.5; /* its estimate, about 1e-3, warns */
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    vt_trajectory *tr;
    assert_ok(vt_trajectory_create(&tr, m, 3));
    vt_run_options opt = vt_default_run_options(), badopt = opt;
    opt.nout = 2;
    badopt.nout = 0;
    enum { NAN_Q, NAN_XFRC, NAN_QSTAR, BAD_OPTION, AS_IS };
    const struct {
        const char *who;
        int how;
    } calls[] = {{"vt_inverse_dynamics", NAN_Q},           {"vt_inverse_dynamics", NAN_XFRC},
                 {"vt_inverse_dynamics_recursive", NAN_Q}, {"vt_inverse_dynamics_recursive", NAN_XFRC},
                 {"vt_inverse_dynamics_motion", NAN_Q},    {"vt_inverse_dynamics_motion", NAN_XFRC},
                 {"vt_kinematic_solve", NAN_Q},            {"vt_kinematic_solve", BAD_OPTION},
                 {"vt_solve", NAN_QSTAR},                  {"vt_kinematic_analysis", AS_IS},
                 {"vt_kinematic_analysis", BAD_OPTION},    {"vt_dynamic_analysis", NAN_Q},
                 {"vt_dynamic_analysis", BAD_OPTION},      {"vt_data_reset", AS_IS}};
    const char *what[] = {"NaN in q", "NaN in xfrc", "NaN in Q", "an option out of range", "as it is"};
    for (size_t c = 0; c < sizeof calls / sizeof calls[0]; c++) {
        const char *who = calls[c].who;
#if !VT_HAVE_SUNDIALS
        if (!strcmp(who, "vt_dynamic_analysis")) continue;
#endif
        vt_data_reset(m, d);
        for (int a = 0; a < m->nv; a++) {
            d->q[a] = 0.3 + 0.25 * a;
            d->qd[a] = 0.5 - 0.2 * a;
        }
        assert_ok(vt_inverse_dynamics(m, d));
        if (d->route == VT_ROUTE_NONE || !d->fallback || !(d->warning & VT_WARN_ILL_CONDITIONED) || d->rank != m->nc ||
            !(d->rcond > 0.0))
            fail_msg("the ill-conditioned instant: route %d, fallback %d, warning %d, rank %d, rcond %.3g", (int)d->route,
                     d->fallback, d->warning, d->rank, d->rcond);
        const int how = calls[c].how;
        if (how == NAN_Q) d->q[2] = NAN;
        if (how == NAN_XFRC) d->xfrc[6 * 3 + 1] = NAN;
        if (how == NAN_QSTAR) d->Q[1] = NAN;
        vt_status st = VT_OK;
        if (!strcmp(who, "vt_inverse_dynamics")) st = vt_inverse_dynamics(m, d);
        else if (!strcmp(who, "vt_inverse_dynamics_recursive")) st = vt_inverse_dynamics_recursive(m, d);
        else if (!strcmp(who, "vt_inverse_dynamics_motion")) st = vt_inverse_dynamics_motion(m, d);
        else if (!strcmp(who, "vt_kinematic_solve")) st = vt_kinematic_solve(m, d, how == BAD_OPTION ? -1.0 : 1e-12, 20);
        else if (!strcmp(who, "vt_solve")) st = vt_solve(m, d);
        else if (!strcmp(who, "vt_kinematic_analysis")) st = vt_kinematic_analysis(m, d, how == BAD_OPTION ? &badopt : &opt, tr);
#if VT_HAVE_SUNDIALS
        else if (!strcmp(who, "vt_dynamic_analysis")) st = vt_dynamic_analysis(m, d, how == BAD_OPTION ? &badopt : &opt, tr);
#endif
        else st = vt_data_reset(m, d) == VT_OK ? VT_ERR_ABORTED : VT_OK; /* its success is what clears */
        if (st == VT_OK) fail_msg("%s, %s: succeeded", who, what[how]);
        assert_no_diagnostics(d, who, what[how]);
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    vt_model_free(m);
}

/* every status has a text of its own; unknown codes get one too */
static void test_status_strings(void **state)
{
    (void)state;
    const char *seen[64];
    int n = 0;
    for (int s = VT_OK; s >= VT_ERR_BAD_SIZE; s--) {
        const char *t = vt_status_string((vt_status)s);
        assert_non_null(t);
        assert_true(strlen(t) > 1);
        for (int k = 0; k < n; k++)
            if (strcmp(t, seen[k]) == 0) fail_msg("status %d shares its text with another: %s", s, t);
        seen[n++] = t;
    }
    assert_non_null(vt_status_string((vt_status)-1000));
    assert_non_null(vt_status_string((vt_status)1000));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_null_and_mismatch),
        cmocka_unit_test(test_nonfinite_states),
        cmocka_unit_test(test_time_functions),
        cmocka_unit_test(test_spline_drives),
        cmocka_unit_test(test_indices_and_options),
        cmocka_unit_test(test_stale_diagnostics),
        cmocka_unit_test(test_status_strings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
