/* The contact set (analysis/contact.c) against a second method and its definitions:
 * - which results the rule decides (vt_contacts_unique) against a second method: the same feet
 *   as spherical cut joints solved as redundant loops (vt_scene_quadruped_feet, allow_redundant),
 *   whose flags of drive efforts, cut forces and reactions come from the null space of Φ_qᵀ: the
 *   flags equal, and every result both call unique has the same value (1e-12), with the torso
 *   moving and the feet held still by the legs' inverse kinematics, on four feet and on three
 *   (the fourth leg swinging: its torques and reactions fixed by its motion alone);
 * - the definitions refused, named, and a model with a loop (contacts take a tree's given motion);
 * - points given on a frame, in its axes from its origin (test_frame_points): the same forces as
 *   the body points written here, and at rest the box's minimum-norm statics.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vt_test.h"
#include "scenes.h"

#define G0 9.81

/* |a − b| within rel times the problem's scale */
#define assert_near_rel(a, b, rel, scale) assert_near(a, b, (rel) * (scale))

/* the quadruped's torso moving level (position, velocity, acceleration), the legs by inverse
 * kinematics: the feet of the mask still under their hips, the others moving, into d */
static void moving_state(const vt_model *m, vt_data *d, unsigned mask)
{
    vt_scene_quadruped_stand(m, d, 0.6);
    const double tp[3] = {0.02, -0.01, 0.4 * cos(0.6) + 0.01}, tv[3] = {0.1, 0.05, -0.02}, ta[3] = {0.3, -0.2, 0.1};
    for (int e = 0; e < 3; e++) d->q[e] = tp[e], d->qd[e] = tv[e], d->qdd[e] = ta[e];
    for (int k = 0; k < 4; k++) {
        const double hx = k < 2 ? 0.3 : -0.3, hy = k % 2 == 0 ? 0.15 : -0.15;
        const int still = mask >> k & 1u;
        const double fp[3] = {hx + (still ? 0.0 : 0.03), hy, still ? 0.0 : 0.05};
        const double fv[3] = {still ? 0.0 : 0.2, 0.0, still ? 0.0 : 0.1}, fa[3] = {still ? 0.0 : 1.0, 0.0, still ? 0.0 : -1.0};
        double r[3], rv[3], ra[3], q[3], qd[3], qdd[3];
        for (int e = 0; e < 3; e++) {
            r[e] = fp[e] - (e == 0 ? tp[0] + hx : e == 1 ? tp[1] + hy : tp[2]);
            rv[e] = fv[e] - tv[e];
            ra[e] = fa[e] - ta[e];
        }
        vt_scene_leg_ik(0.2, r, rv, ra, k < 2 ? -1.0 : 1.0, q, qd, qdd);
        for (int j = 0; j < 3; j++) {
            const int body = 2 + 3 * k + j, a = m->body_vadr[body];
            d->q[m->body_qadr[body]] = q[j];
            d->qd[a] = qd[j];
            d->qdd[a] = qdd[j];
        }
    }
}

static void test_unique(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_quadruped(&m));
    vt_contact_def def[4];
    vt_test_feet(def, 1.0, VT_CONTACT_BILATERAL);
    vt_contacts *c = NULL;
    assert_ok(vt_contacts_create(&c, m, def, 4, NULL, NULL));
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    const double W = VT_QUADRUPED_MASS * G0;
    for (int pass = 0; pass < 2; pass++) {
        const unsigned mask = pass ? 0xEu : 0xFu; /* all four feet; FL swinging */
        vt_model *mc = NULL;
        vt_data *dc = NULL;
        assert_ok(vt_scene_quadruped_feet(&mc, mask));
        assert_ok(vt_data_create(&dc, mc));
        moving_state(m, d, mask);
        moving_state(mc, dc, mask);
        int active[4], eu[18], fu[12];
        for (int k = 0; k < 4; k++) active[k] = mask >> k & 1u;
        double f[12];
        assert_ok(vt_inverse_dynamics_contacts(m, d, c, active, f));
        double tau[18];
        memcpy(tau, d->qfrc_drive, sizeof tau);
        assert_ok(vt_contacts_unique(m, d, c, active, eu, fu));
        for (int a = 0; a < 18; a++) assert_true(d->qfrc_drive[a] == tau[a]); /* the data as it was */
        assert_ok(vt_inverse_dynamics_motion(mc, dc)); /* the loops: q̈ of the driven rates given */
        assert_true(dc->rank < mc->nc);                /* redundant */
        int n_rule = 0;
        for (int a = 6; a < 18; a++) { /* a leg joint: its drive's row */
            const int dr = mc->dof_drive[a], row = mc->drive_row[dr];
            assert_int_equal(eu[a], dc->lambda_unique[row]);
            if (eu[a]) assert_near_rel(d->qfrc_drive[a], dc->drive_effort[dr], 1e-12, W);
            n_rule += !eu[a];
            if (pass == 1 && a < 9) assert_int_equal(eu[a], 1); /* the swinging leg's */
        }
        assert_true(n_rule > 0);
        for (int k = 0, cut = 0; k < 4; k++) {
            if (!active[k]) { /* no contact, no cut joint: zero, fixed */
                for (int e = 0; e < 3; e++) assert_true(f[3 * k + e] == 0.0 && fu[3 * k + e] == 1);
                continue;
            }
            for (int e = 0; e < 3; e++) {
                assert_int_equal(fu[3 * k + e], dc->cut_unique[6 * cut + e]);
                /* the cut joint's force on the foot, b, is the ground's */
                if (fu[3 * k + e]) assert_near_rel(f[3 * k + e], dc->cut_force[3 * cut + e], 1e-12, W);
            }
            cut++;
        }
        for (int i = 1; i <= m->nbody; i++)
            for (int e = 0; e < 6; e++) {
                assert_int_equal(d->jnt_unique[6 * i + e], dc->jnt_unique[6 * i + e]);
                const double x = e < 3 ? d->jnt_force[3 * i + e] : d->jnt_moment[3 * i + e - 3];
                const double y = e < 3 ? dc->jnt_force[3 * i + e] : dc->jnt_moment[3 * i + e - 3];
                if (d->jnt_unique[6 * i + e]) assert_near_rel(x, y, 1e-12, W);
            }
        vt_data_free(dc);
        vt_model_free(mc);
    }
    /* refused: no contacts' instant before, another model's contacts */
    vt_data *e = NULL;
    assert_ok(vt_data_create(&e, m));
    assert_int_equal(vt_contacts_unique(m, e, c, NULL, NULL, NULL), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_contacts_unique(m, e, NULL, NULL, NULL, NULL), VT_ERR_NULL);
    vt_data_free(e);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_refused(void **state)
{
    (void)state;
    vt_model *m = vt_test_contact_box(1.0), *other = vt_test_contact_box(2.0);
    vt_contact_def def[4];
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    vt_contacts *c = (vt_contacts *)def; /* set to NULL by every failure */
    char msg[VT_MESSAGE_SIZE];
    def[1].name = "FL";
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_BAD_NAME);
    assert_null(c);
    assert_non_null(strstr(msg, "FL"));
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    def[1].body = 2;
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_BAD_INDEX);
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    def[0].frame = "nowhere";
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_NOT_FOUND);
    assert_non_null(strstr(msg, "nowhere"));
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    def[0].mu = -0.1;
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_BAD_OPTION);
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    def[0].faces = 2;
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_BAD_OPTION);
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    def[1].weight = 0.0;
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_BAD_OPTION);
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    def[1].point[1] = NAN;
    assert_int_equal(vt_contacts_create(&c, m, def, 2, NULL, msg), VT_ERR_NONFINITE);
    vt_test_box_corners(def, 0.3, -0.3, 1.0);
    const double w[6] = {1, 1, 1, 0, 1, 1};
    assert_int_equal(vt_contacts_create(&c, m, def, 2, w, msg), VT_ERR_BAD_OPTION);
    assert_int_equal(vt_contacts_create(&c, m, def, 0, NULL, msg), VT_ERR_BAD_INDEX);
    assert_int_equal(vt_contacts_create(&c, NULL, def, 2, NULL, msg), VT_ERR_NULL);
    /* made for one model, handed another's data */
    assert_ok(vt_contacts_create(&c, m, def, 2, NULL, msg));
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, other));
    assert_int_equal(vt_inverse_dynamics_contacts(other, d, c, NULL, NULL), VT_ERR_MODEL_MISMATCH);
    { /* a loop: refused, named (its given motion fixes the drives' rates only) */
        vt_model *loop = NULL;
        vt_contacts *cl = NULL;
        assert_ok(vt_scene_fourbar(&loop, vt_function_constant(0.0)));
        vt_contact_def one = vt_default_contact_def();
        assert_int_equal(vt_contacts_create(&cl, loop, &one, 1, NULL, msg), VT_ERR_BAD_OPTION);
        assert_null(cl);
        assert_non_null(strstr(msg, "cut joints"));
        vt_model_free(loop);
    }
    assert_int_equal(vt_inverse_dynamics_contacts(other, d, NULL, NULL, NULL), VT_ERR_NULL);
    vt_data_free(d);
    vt_contacts_free(c);
    vt_contacts_free(NULL);
    assert_int_equal(vt_contacts_count(NULL), 0);
    vt_model_free(other);
    vt_model_free(m);
}

/* Points on a frame: a box (vt_test_contact_box's) with a frame "sole" under it, its origin
 * o = (−0.03, 0, −0.1) from the centre of mass and its axes turned 40° about z, and four
 * contacts at the sole's corners given in the sole's axes, (±a, ±b, 0) unevenly. Each corner's
 * point in the box's axes is o + R_z(40°) p, written here with cos and sin: the contacts at those
 * body points give the same forces (1e-14 of the weight, at rest and moving); at rest the forces
 * are the minimum-norm closed form of the box's statics at those points (1e-10; uneven, 11 to
 * 28 N), and four contacts at the frame's origin alone (every offset dropped), off the centre of
 * mass's line, are refused: they cannot carry the box */
static void test_frame_points(void **state)
{
    (void)state;
    const double mass = 8.0, yaw = 40.0 * 3.14159265358979323846 / 180.0, o[3] = {-0.03, 0.0, -0.1};
    vt_builder *b = NULL;
    vt_model_def md = vt_default_model_def();
    md.gravity[0] = md.gravity[1] = 0.0, md.gravity[2] = -G0;
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_FREE;
    body.mass = mass;
    body.inertia[0] = mass * 0.2 / 12.0, body.inertia[4] = mass * 0.4 / 12.0, body.inertia[8] = mass * 0.52 / 12.0;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    vt_frame_def fr = vt_default_frame_def();
    fr.name = "sole";
    memcpy(fr.point, o, sizeof o);
    fr.orientation[0] = cos(yaw / 2.0), fr.orientation[1] = fr.orientation[2] = 0.0, fr.orientation[3] = sin(yaw / 2.0);
    assert_int_equal(vt_builder_add_frame(b, &fr), 0);
    vt_model *m = NULL;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    static const char *const name[4] = {"FL", "FR", "HL", "HR"};
    const double corner[4][3] = {{0.12, 0.07, 0.0}, {0.12, -0.06, 0.0}, {-0.09, 0.07, 0.0}, {-0.09, -0.06, 0.0}};
    vt_contact_def on_frame[4], on_body[4], origin[4];
    for (int k = 0; k < 4; k++) {
        on_frame[k] = vt_default_contact_def();
        on_frame[k].name = name[k];
        on_frame[k].frame = "sole";
        memcpy(on_frame[k].point, corner[k], sizeof corner[k]);
        on_body[k] = on_frame[k];
        on_body[k].frame = NULL;
        on_body[k].body = 1;
        on_body[k].point[0] = o[0] + cos(yaw) * corner[k][0] - sin(yaw) * corner[k][1];
        on_body[k].point[1] = o[1] + sin(yaw) * corner[k][0] + cos(yaw) * corner[k][1];
        on_body[k].point[2] = o[2] + corner[k][2];
        origin[k] = on_frame[k];
        origin[k].point[0] = origin[k].point[1] = origin[k].point[2] = 0.0;
    }
    vt_contacts *cf = NULL, *cb = NULL, *co = NULL;
    char msg[VT_MESSAGE_SIZE];
    assert_ok(vt_contacts_create(&cf, m, on_frame, 4, NULL, msg));
    assert_ok(vt_contacts_create(&cb, m, on_body, 4, NULL, msg));
    assert_ok(vt_contacts_create(&co, m, origin, 4, NULL, msg));
    vt_data *d = NULL;
    assert_ok(vt_data_create(&d, m));
    const double W = mass * G0;
    for (int t = 0; t < 2; t++) {
        /* at rest, level, 0.1 m up; then turned, moving and accelerating (within the pyramids) */
        memcpy(d->q, m->q0, (size_t)m->nq * sizeof(double));
        memset(d->qd, 0, (size_t)m->nv * sizeof(double));
        memset(d->qdd, 0, (size_t)m->nv * sizeof(double));
        d->q[2] = 0.1;
        if (t == 1) {
            const double p[4] = {0.98, 0.05, -0.08, 0.17}, n = sqrt(0.98 * 0.98 + 0.05 * 0.05 + 0.08 * 0.08 + 0.17 * 0.17);
            for (int e = 0; e < 4; e++) d->q[3 + e] = p[e] / n;
            const double v[6] = {0.1, -0.05, 0.02, 0.2, -0.1, 0.3}, a[6] = {0.4, 0.3, -0.5, 0.3, 0.2, -0.4};
            memcpy(d->qd, v, sizeof v);
            memcpy(d->qdd, a, sizeof a);
        }
        double ff[12], fb[12], fo[12];
        assert_ok(vt_inverse_dynamics_contacts(m, d, cf, NULL, ff));
        assert_ok(vt_inverse_dynamics_contacts(m, d, cb, NULL, fb));
        for (int k = 0; k < 12; k++) assert_near_rel(ff[k], fb[k], 1e-14, W);
        if (t == 1) continue;
        double want[12];
        const double acc[3] = {0.0, 0.0, 0.0};
        vt_test_min_norm_forces(on_body, mass, acc, want);
        for (int k = 0; k < 4; k++) assert_true(want[3 * k + 2] > 0.1 * W && fabs(want[3 * k]) + fabs(want[3 * k + 1]) < 1e-9 * W);
        for (int k = 0; k < 12; k++) assert_near_rel(ff[k], want[k], 1e-10, W);
        assert_int_equal(vt_inverse_dynamics_contacts(m, d, co, NULL, fo), VT_ERR_CONTACT);
    }
    vt_data_free(d);
    vt_contacts_free(cf);
    vt_contacts_free(cb);
    vt_contacts_free(co);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unique),
        cmocka_unit_test(test_refused),
        cmocka_unit_test(test_frame_points),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
