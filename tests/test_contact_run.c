/* Contacts over time (analysis/contact_run.c): a kinematic analysis of the quadruped swaying on
 * its four feet (vt_scene_quadruped_sway: the torso driven, each foot held by point drives), the
 * ground's forces at every row, against identities, closed forms and the forward check:
 * - the whole robot's Newton law at every row, Σ_c f_c + Σ_b m_b g + F = Σ_b m_b a_b, with the
 *   bodies' accelerations a_b of the row's motion (vt_inverse_dynamics_motion's ẍ) and F a push
 *   the caller applies to the torso (xfrc), which the run leaves as it was;
 * - the free root's efforts zero at every row (the feet carry the torso; without contacts its
 *   vertical effort is the weight and more), and each row's forces and efforts those of
 *   vt_inverse_dynamics_contacts at the row's q, q̇, q̈;
 * - the sway slowed to a standstill (a period of 1e9 s): by symmetry each foot carries M g / 4;
 * - the forward check: the model without drives under the motors' efforts and the ground's forces
 *   as loads reproduces the motion and, with the efforts as joint torques, the reactions; with
 *   each drive's own load applied instead (forward_as_loads), the motion;
 * - the schedule: a fifth contact never on the ground changes nothing (its force zero, the others'
 *   bitwise those of the four-contact run), the flags kept per row; a hind foot lifted mid-sway is
 *   carried on three feet until the front foot across would have to pull: refused at that time,
 *   the contact named; a failing schedule is the callback's error;
 * - refused: contacts of another model, a trajectory without room for them, a dynamic analysis.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vt_test.h"
#include "scenes.h"

#define G0 9.81

static const char *const foot[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};

/* the four feet as unilateral contacts (μ 1, 4 faces), and with five a point under the torso's
 * centre that never touches */
static vt_contacts *feet(const vt_model *m, int n)
{
    vt_contact_def def[5];
    for (int k = 0; k < 4; k++) {
        def[k] = vt_default_contact_def();
        def[k].frame = foot[k];
        def[k].name = foot[k];
    }
    def[4] = vt_default_contact_def();
    def[4].body = 1;
    def[4].point[2] = -0.05;
    def[4].name = "belly";
    vt_contacts *c = NULL;
    char msg[VT_MESSAGE_SIZE];
    assert_ok(vt_contacts_create(&c, m, def, n, NULL, msg));
    return c;
}

/* a sway of `period` s over [0, 1], nout rows, on n contacts; its trajectory into *tr */
static vt_status sway(const vt_model *m, vt_data *d, vt_contacts *c, vt_trajectory **tr, int nout, int forward,
                      vt_contact_schedule schedule)
{
    vt_scene_quadruped_stand(m, d, VT_SWAY_THETA);
    assert_ok(vt_trajectory_create_contacts(tr, m, c, nout + 1));
    vt_run_options o = vt_default_run_options();
    o.nout = nout;
    o.contacts = c;
    o.contact_schedule = schedule;
    o.forward_check = forward;
    return vt_kinematic_analysis(m, d, &o, *tr);
}

static void test_sway(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL, *e = NULL;
    vt_trajectory *tr = NULL;
    assert_ok(vt_scene_quadruped_sway(&m, 1.0));
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_data_create(&e, m));
    vt_contacts *c = feet(m, 4), *ce = feet(m, 4);
    const double push[3] = {5.0, -8.0, 0.0}; /* the caller's push on the torso's centre, N */
    const size_t nxf = 6 * ((size_t)m->nbody + 1);
    memcpy(d->xfrc + 6, push, sizeof push);
    double xfrc[6 * 14];
    assert_true(nxf <= 6 * 14);
    memcpy(xfrc, d->xfrc, nxf * sizeof(double));
    assert_ok(sway(m, d, c, &tr, 40, VT_HAVE_SUNDIALS, NULL));
    assert_memory_equal(d->xfrc, xfrc, nxf * sizeof(double));
    assert_int_equal(tr->nfilled, 41);
    const int nv = m->nv, nq = m->nq;
    const double W = VT_QUADRUPED_MASS * G0;
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *f = tr->contact_force + 12 * (size_t)k, *tau = tr->qfrc_drive + (size_t)nv * (size_t)k;
        for (int a = 0; a < 6; a++) assert_near(tau[a], 0.0, 1e-12 * W); /* the free root: no motor */
        /* Newton's law for the whole robot, the accelerations of the row's motion */
        memcpy(e->q, tr->q + (size_t)nq * (size_t)k, (size_t)nq * sizeof(double));
        memcpy(e->qd, tr->qd + (size_t)nv * (size_t)k, (size_t)nv * sizeof(double));
        memcpy(e->qdd, tr->qdd + (size_t)nv * (size_t)k, (size_t)nv * sizeof(double));
        memcpy(e->xfrc, xfrc, nxf * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(m, e));
        double need[3] = {0, 0, 0};
        for (int b = 1; b <= m->nbody; b++)
            for (int r = 0; r < 3; r++)
                need[r] += m->body_mass[b] * (e->xdd[7 * (b - 1) + r] - (r == 2 ? -G0 : 0.0));
        for (int r = 0; r < 3; r++) {
            const double sum = f[r] + f[3 + r] + f[6 + r] + f[9 + r] + push[r];
            assert_near(sum, need[r], 1e-10 * W);
        }
        double fz = 0.0;
        for (int j = 0; j < 4; j++) {
            assert_true(f[3 * j + 2] > 0.0); /* each foot pushes */
            fz += f[3 * j + 2];
        }
        lo = fmin(lo, fz), hi = fmax(hi, fz);
        /* the row's forces and motors are the given motion's on the contacts */
        double fc[12];
        assert_ok(vt_inverse_dynamics_contacts(m, e, ce, NULL, fc));
        for (int r = 0; r < 12; r++) assert_near(f[r], fc[r], 1e-9 * W);
        for (int a = 6; a < nv; a++) assert_near(tau[a], e->qfrc_drive[a], 1e-9 * W);
        for (int j = 0; j < 4; j++) assert_int_equal(tr->contact_active[4 * k + j], 1);
    }
    assert_true(lo < 0.7 * W && hi > 1.3 * W); /* the sway moves the load: the rows are not a stand */
#if VT_HAVE_SUNDIALS
    /* the forward check: the motors' torques and the ground's forces give the motion back */
    assert_true(tr->fwd_err_q < 1e-9);
    assert_true(tr->fwd_err_qd < 1e-8);
    assert_true(tr->fwd_err_force < 1e-9 * W);
    assert_true(tr->fwd_err_moment < 1e-9 * W);
    assert_true(tr->steps_fwd > 0);
    { /* each drive's own load applied instead (the feet's point drives' forces at the feet): the
       * same generalized forces, so the motion comes back too */
        vt_trajectory *ta = NULL;
        vt_run_options o = vt_default_run_options();
        o.nout = 10;
        o.contacts = c;
        o.forward_as_loads = 1;
        vt_scene_quadruped_stand(m, d, VT_SWAY_THETA);
        assert_ok(vt_trajectory_create_contacts(&ta, m, c, 11));
        assert_ok(vt_kinematic_analysis(m, d, &o, ta));
        assert_true(ta->fwd_err_q < 1e-9);
        vt_trajectory_free(ta);
    }
#endif
    { /* the control: without contacts the torso's drives carry it, the free root's efforts the
       * robot's weight and more */
        vt_trajectory *t0 = NULL;
        vt_run_options o = vt_default_run_options();
        o.nout = 10;
        o.forward_check = 0;
        vt_scene_quadruped_stand(m, d, VT_SWAY_THETA);
        assert_ok(vt_trajectory_create(&t0, m, 11));
        assert_ok(vt_kinematic_analysis(m, d, &o, t0));
        for (int k = 0; k < t0->nfilled; k++) assert_true(fabs(t0->qfrc_drive[(size_t)nv * (size_t)k + 2]) > 0.5 * W);
        vt_trajectory_free(t0);
    }
    vt_trajectory_free(tr);
    vt_contacts_free(ce);
    vt_contacts_free(c);
    vt_data_free(e);
    vt_data_free(d);
    vt_model_free(m);
}

/* the sway slowed to a standstill: each foot carries M g / 4 */
static void test_still(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL;
    vt_trajectory *tr = NULL;
    assert_ok(vt_scene_quadruped_sway(&m, 1e9));
    assert_ok(vt_data_create(&d, m));
    vt_contacts *c = feet(m, 4);
    assert_ok(sway(m, d, c, &tr, 4, 0, NULL));
    const double W = VT_QUADRUPED_MASS * G0;
    for (int k = 0; k < tr->nfilled; k++)
        for (int j = 0; j < 4; j++) assert_near(tr->contact_force[12 * k + 3 * j + 2], W / 4.0, 1e-9 * W);
    vt_trajectory_free(tr);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(m);
}

static int belly_never(double t, int *active, void *user)
{
    (void)t, (void)user;
    active[4] = 0;
    return 0;
}

static int hind_lifted(double t, int *active, void *user)
{
    (void)user;
    if (t >= 0.5) active[3] = 0;
    return 0;
}

static int failing(double t, int *active, void *user)
{
    (void)active;
    *(double *)user = t;
    return t > 0.25;
}

static void test_schedule(void **state)
{
    (void)state;
    vt_model *m = NULL;
    vt_data *d = NULL;
    vt_trajectory *t4 = NULL, *t5 = NULL, *tl = NULL;
    assert_ok(vt_scene_quadruped_sway(&m, 1.0));
    assert_ok(vt_data_create(&d, m));
    vt_contacts *c4 = feet(m, 4), *c5 = feet(m, 5);
    assert_ok(sway(m, d, c4, &t4, 20, 0, NULL));
    assert_ok(sway(m, d, c5, &t5, 20, 0, belly_never));
    for (int k = 0; k < t5->nfilled; k++) {
        assert_memory_equal(t5->contact_force + 15 * (size_t)k, t4->contact_force + 12 * (size_t)k, 12 * sizeof(double));
        for (int r = 0; r < 3; r++) assert_true(t5->contact_force[15 * k + 12 + r] == 0.0);
        for (int j = 0; j < 5; j++) assert_int_equal(t5->contact_active[5 * k + j], j < 4);
    }
    /* a hind foot lifted mid-sway: carried at first, then the front foot across would have to
     * pull on the ground as the torso sways away from it: refused there, named, with its time */
    assert_int_equal(sway(m, d, c4, &tl, 20, 0, hind_lifted), VT_ERR_CONTACT);
    assert_non_null(strstr(d->message, "t = 0.55:"));
    assert_non_null(strstr(d->message, "FL_foot"));
    assert_non_null(strstr(d->message, "pull"));
    assert_int_equal(tl->nfilled, 11); /* the rows before it */
    assert_int_equal(tl->contact_active[4 * 10 + 3], 0); /* t = 0.5: on three feet, the lifted one's force zero */
    for (int r = 0; r < 3; r++) assert_true(tl->contact_force[12 * 10 + 9 + r] == 0.0);
    vt_trajectory_free(tl);
    tl = NULL;
    /* the schedule's own failure */
    double when = 0.0;
    vt_run_options o = vt_default_run_options();
    o.nout = 20;
    o.forward_check = 0;
    o.contacts = c4;
    o.contact_schedule = failing;
    o.contact_user = &when;
    vt_scene_quadruped_stand(m, d, VT_SWAY_THETA);
    assert_ok(vt_trajectory_create_contacts(&tl, m, c4, 21));
    assert_int_equal(vt_kinematic_analysis(m, d, &o, tl), VT_ERR_CALLBACK);
    assert_true(when == 0.3);
    assert_non_null(strstr(d->message, "schedule"));
    vt_trajectory_free(tl);
    vt_trajectory_free(t5);
    vt_trajectory_free(t4);
    vt_contacts_free(c5);
    vt_contacts_free(c4);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_refused(void **state)
{
    (void)state;
    vt_model *m = NULL, *other = NULL;
    vt_data *d = NULL;
    vt_trajectory *plain = NULL, *tr = NULL;
    assert_ok(vt_scene_quadruped_sway(&m, 1.0));
    assert_ok(vt_scene_quadruped(&other));
    assert_ok(vt_data_create(&d, m));
    vt_contacts *c = feet(m, 4), *co = feet(other, 4);
    vt_run_options o = vt_default_run_options();
    o.forward_check = 0;
    o.nout = 4;
    o.contacts = c;
    /* a trajectory without room for the forces */
    assert_ok(vt_trajectory_create(&plain, m, 5));
    vt_scene_quadruped_stand(m, d, VT_SWAY_THETA);
    assert_int_equal(vt_kinematic_analysis(m, d, &o, plain), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(d->message, "vt_trajectory_create_contacts"));
    assert_int_equal(plain->nfilled, 0);
    /* contacts of another model */
    assert_int_equal(vt_trajectory_create_contacts(&tr, m, co, 5), VT_ERR_MODEL_MISMATCH);
    assert_null(tr);
    assert_int_equal(vt_trajectory_create_contacts(&tr, m, NULL, 5), VT_ERR_NULL);
    assert_ok(vt_trajectory_create_contacts(&tr, m, c, 5));
    assert_int_equal(tr->ncontact, 4);
    o.contacts = co;
    assert_int_equal(vt_kinematic_analysis(m, d, &o, tr), VT_ERR_MODEL_MISMATCH);
#if VT_HAVE_SUNDIALS
    /* a dynamic analysis: its free rates would follow from the forces */
    vt_model *full = NULL;
    vt_data *df = NULL;
    assert_ok(vt_scene_quadruped(&full));
    assert_ok(vt_data_create(&df, full));
    vt_contacts *cf = feet(full, 4);
    vt_trajectory *tf = NULL;
    assert_ok(vt_trajectory_create_contacts(&tf, full, cf, 5));
    o.contacts = cf;
    vt_scene_quadruped_stand(full, df, VT_SWAY_THETA);
    assert_int_equal(vt_dynamic_analysis(full, df, &o, tf), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(df->message, "contacts"));
    vt_trajectory_free(tf);
    vt_contacts_free(cf);
    vt_data_free(df);
    vt_model_free(full);
#endif
    vt_trajectory_free(tr);
    vt_trajectory_free(plain);
    vt_contacts_free(co);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(other);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sway),
        cmocka_unit_test(test_still),
        cmocka_unit_test(test_schedule),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
