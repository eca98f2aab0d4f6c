/* The accuracy of the two inverse dynamics paths, the recursive (src/recursive.c) and the dense
 * one, where round-off decides: mechanisms far from the origin and from o (translation
 * invariance), far base bodies and point masses, huge loads at fixed points, mass ratios of 1e24
 * and inertia spreads of 1e11, a 1e154 kg link, long chains of 200 links, joint angles beyond
 * 2^15 rad, and the motions without inertia or rows without effect that round-off hides (both
 * paths must refuse alike). The routes themselves and the recursive path's other behaviour:
 * test_recursive.c. */
#include <float.h>

#include "base/vec3.h"    /* vt_dot3 */
#include "model/model.h" /* the rows' kinds (vt_test.h's vt_test_known_rcond, vt_test_rows_length) */

#include "vt_test.h"

/* Two free-flying base bodies (the paper's 7 rates and p^T p − 1 each), the second D from the
 * first (o): the recursive path has only its general route for base bodies, whose composite
 * inertias about o hold m D² terms, so the second body's own rotational inertia (6 kg m²) is
 * round-off of them beyond D ~ 1e8 m and the route refused the instant as singular. Its
 * refusals are now the dense stages' (about each joint): the answer, exact here, is r̈ = g and
 * p̈ = −¼ |ω|² p (torque-free, ω about a principal axis of an isotropic body). */
static void test_far_base_body(void **state)
{
    (void)state;
    const double D[3] = {1e3, 1e9, 1e34};
    for (int k = 0; k < 3; k++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def body = vt_default_body_def();
        body.joint = VT_JOINT_BASE;
        body.mass = 1.2;
        body.inertia[0] = body.inertia[4] = body.inertia[8] = 6.9;
        assert_int_equal(vt_builder_add_body(b, &body), 1);
        body.mass = 6.2;
        body.inertia[0] = body.inertia[4] = body.inertia[8] = 6.0;
        assert_int_equal(vt_builder_add_body(b, &body), 2);
        vt_model *m = vt_test_build(b);
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        const double p[4] = {0.5, 0.5, -0.5, 0.5};
        memcpy(d->q + 3, p, sizeof p);
        d->q[7] = 1.8, d->q[8] = D[k], d->q[9] = 1.8;
        memcpy(d->q + 10, p, sizeof p);
        /* ṗ = ½ E^T ω, E = [−p1 p0 −p3 p2; −p2 p3 p0 −p1; −p3 −p2 p1 p0] (rows) */
        const double w[3] = {0.3, -0.2, 0.5};
        const double E[3][4] = {{-p[1], p[0], -p[3], p[2]}, {-p[2], p[3], p[0], -p[1]}, {-p[3], -p[2], p[1], p[0]}};
        double pd[4];
        for (int c = 0; c < 4; c++) pd[c] = 0.5 * (E[0][c] * w[0] + E[1][c] * w[1] + E[2][c] * w[2]);
        memcpy(d->qd + 10, pd, sizeof pd);
        const vt_status st = vt_inverse_dynamics_recursive(m, d);
        print_message("second base body %g m from o: %s (%s), fallback %d\n", D[k], vt_status_string(st), d->message, d->fallback);
        assert_ok(st);
        if (k > 0) assert_int_equal(d->fallback & VT_FALLBACK_COMPOSITE_ROUNDOFF, VT_FALLBACK_COMPOSITE_ROUNDOFF);
        const double w2 = vt_dot3(w, w);
        for (int c = 0; c < 3; c++) assert_near(d->qdd[7 + c], m->gravity[c], 1e-14);
        for (int c = 0; c < 4; c++) assert_near(d->qdd[10 + c], -0.25 * w2 * p[c], 1e-14);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* A point mass 1e6 m out along its revolute axis (6.3 m off it) on a universal joint's body, a
 * point drive on that body (a fuzz input, crash-175b…): the articulated route's elimination of
 * the light rate cancels terms of 1e12 far beyond the composite inertia's round-off bound, and
 * its pivot for the universal joint came out negative, -1.5e7 of 1.1e12: the route refused the
 * instant as singular ("negative beyond round-off") where the dense path solves it (rcond 0.014).
 * Such a pivot is now one the route cannot trust: the general route, then the dense stages,
 * decide, and the answer is the dense one. */
static void test_far_point_mass_pivot(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def d = vt_default_body_def();
    d.joint = VT_JOINT_UNIVERSAL;
    d.mass = 4.1875;
    d.inertia[0] = d.inertia[4] = d.inertia[8] = 0.6875;
    d.joint_parent[0] = -6.3125, d.joint_parent[1] = -5.3125, d.joint_parent[2] = -5.625;
    d.joint_child[0] = -4.75, d.joint_child[1] = 0.1875, d.joint_child[2] = -3.5625;
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    d = vt_default_body_def();
    d.parent = 1;
    d.mass = 1.85;
    d.joint_parent[0] = -2.9375, d.joint_parent[1] = -1.5, d.joint_parent[2] = 3.6875;
    d.joint_child[0] = -3.75, d.joint_child[1] = -5.0625, d.joint_child[2] = 1e6;
    assert_int_equal(vt_builder_add_body(b, &d), 2);
    vt_drive_def dr = vt_default_drive_def();
    dr.type = VT_DRIVE_POINT;
    dr.body = 1;
    dr.index = 0;
    dr.point[0] = 7.25, dr.point[1] = -2.125, dr.point[2] = 2.0;
    dr.f = vt_function_polynomial(3, (const double[3]){-2.0, 1.0, 0.5});
    assert_int_equal(vt_builder_add_drive(b, &dr), 0);
    vt_model *m = vt_test_build(b);
    vt_data *dd, *dv;
    assert_ok(vt_data_create(&dd, m));
    assert_ok(vt_data_create(&dv, m));
    const double q[3] = {1.81875, -2.25, -7.5}, qd[3] = {-7.5, -7.5, -7.5};
    memcpy(dd->q, q, sizeof q), memcpy(dv->q, q, sizeof q);
    memcpy(dd->qd, qd, sizeof qd), memcpy(dv->qd, qd, sizeof qd);
    dd->time = dv->time = -7.5;
    assert_ok(vt_inverse_dynamics(m, dd));
    const vt_status st = vt_inverse_dynamics_recursive(m, dv);
    print_message("dense rcond %.3g; recursive %s (%s), route %d, fallback %d\n", dd->rcond, vt_status_string(st), dv->message,
                  dv->route, dv->fallback);
    assert_ok(st);
    /* left for its pivot; where FMA contracts the elimination (a -march=native build), its
     * estimate already fails (VT_FALLBACK_ARTICULATED_CONDITION) before the pivot is judged */
    assert_true(dv->fallback & (VT_FALLBACK_ARTICULATED_PIVOT | VT_FALLBACK_ARTICULATED_CONDITION));
    for (int c = 0; c < 3; c++) {
        assert_near(dv->qdd[c], dd->qdd[c], 1e-9 * fabs(dd->qdd[c]) + 1e-12);
        assert_near(dv->qfrc_drive[c], dd->qfrc_drive[c], 1e-9 * vt_test_maxabs(dd->qfrc_drive, 3));
    }
    vt_data_free(dd);
    vt_data_free(dv);
    vt_model_free(m);
}


/* Translation invariance: the same mechanism at D = 1 km and 1e6 m from the global origin as at
 * the origin. The mechanism at D is the reference one translated exactly: each ground point p
 * (a root's joint point on the ground, the ground side of a constraint row: a point drive's
 * reference, a cut joint's point) and each free or base root's position is fl(p + D) there and
 * fl(p + D) − D in the reference (exact, by Sterbenz's lemma), so any change in the results is
 * the evaluation's, not the data's rounding. q̈, λ, every effort and every reaction (both frames)
 * must agree to 1e-13 of each array's largest entry at 1 km and 1e-10 at 1e6 m and 1e9 m, for the dense
 * evaluation, the recursive one and, on trees, the motion given. */
static void shift3(double *p, const double D[3], int back)
{
    for (int k = 0; k < 3; k++) {
        const double x = p[k] + D[k];
        p[k] = back ? x - D[k] : x;
    }
}

static void place_model(vt_model *m, const double D[3], int back)
{
    for (int i = 1; i <= m->nbody; i++)
        if (m->body_parent[i] == 0 && m->body_joint[i] != VT_JOINT_FREE && m->body_joint[i] != VT_JOINT_BASE)
            shift3(m->body_jpar + 3 * i, D, back);
    for (int r = 0; r < m->nc; r++) /* a row's point on the ground, global (rows without points ignore it) */
        for (int side = 0; side < 2; side++)
            if (m->con_body[2 * r + side] == 0) shift3(m->con_point + 6 * r + 3 * side, D, back);
}

static void place_state(const vt_model *m, vt_data *d, const double D[3], int back)
{
    for (int i = 1; i <= m->nbody; i++) /* a free root's translation is in the ground's axes */
        if (m->body_parent[i] == 0 && (m->body_joint[i] == VT_JOINT_FREE || m->body_joint[i] == VT_JOINT_BASE))
            shift3(d->q + m->body_qadr[i], D, back);
}

/* the largest change of an output array from the reference's, over the larger of the reference's
 * largest entry and floor (a moment that is zero in exact arithmetic, as a point drive's about
 * its own point, is measured against the moments through the joints) */
static double change(const double *a, const double *ref, int n, double floor)
{
    double num = 0.0, den = floor;
    for (int k = 0; k < n; k++) {
        num = fmax(num, fabs(a[k] - ref[k]));
        den = fmax(den, fabs(ref[k]));
    }
    return den > 0.0 ? num / den : num;
}

static double outputs_change(const vt_model *m, const vt_data *a, const vt_data *b, const char **what)
{
    const int nb3 = 3 * (m->nbody + 1), nd3 = 3 * m->ndrive, nk3 = 3 * m->ncut;
    const struct { const char *name; const double *x, *y; int n, kind; /* 0 own, 1 force, 2 moment */ } out[] = {
        {"qdd", a->qdd, b->qdd, m->nv, 0}, {"lambda", a->lambda, b->lambda, m->nc, 0},
        {"qfrc_drive", a->qfrc_drive, b->qfrc_drive, m->nv, 2}, {"drive_effort", a->drive_effort, b->drive_effort, m->ndrive, 0},
        {"drive_force", a->drive_force, b->drive_force, nd3, 1}, {"drive_moment", a->drive_moment, b->drive_moment, nd3, 2},
        {"jnt_force", a->jnt_force, b->jnt_force, nb3, 1}, {"jnt_moment", a->jnt_moment, b->jnt_moment, nb3, 2},
        {"jnt_force_body", a->jnt_force_body, b->jnt_force_body, nb3, 1},
        {"jnt_moment_body", a->jnt_moment_body, b->jnt_moment_body, nb3, 2},
        {"cut_force", a->cut_force, b->cut_force, nk3, 1}, {"cut_moment", a->cut_moment, b->cut_moment, nk3, 2},
        {"cut_force_body", a->cut_force_body, b->cut_force_body, nk3, 1},
        {"cut_moment_body", a->cut_moment_body, b->cut_moment_body, nk3, 2}};
    const size_t nout = sizeof out / sizeof out[0];
    double floor[3] = {0.0, 0.0, 0.0}, worst = 0.0;
    for (size_t k = 0; k < nout; k++)
        if (out[k].kind) floor[out[k].kind] = fmax(floor[out[k].kind], vt_test_maxabs(out[k].y, out[k].n));
    for (size_t k = 0; k < nout; k++) {
        const double c = change(out[k].x, out[k].y, out[k].n, floor[out[k].kind]);
        if (c > worst) worst = c, *what = out[k].name;
    }
    return worst;
}

/* the benchmark's chain of n links with every other joint driven (1, 3, 5…: joint rows only) */
static vt_model *partly_driven_chain(int n)
{
    vt_model *mc;
    assert_ok(vt_scene_chain(&mc, n, VT_CHAIN_FREE));
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    for (int i = 1; i <= mc->nbody; i++) {
        const vt_body_def d = vt_test_body_of(mc, i);
        assert_int_equal(vt_builder_add_body(b, &d), i);
        if (i % 2) vt_test_add_joint_drive(b, i, 0, vt_function_sine(0.2, 0.3, 1.5, 0.1 * i));
    }
    vt_model *m = vt_test_build(b);
    vt_model_free(mc);
    return m;
}

enum { INV_CHAIN, INV_FREE_TREE, INV_BASE_TREE, INV_FOURBAR, INV_FOURBAR_RUSR, INV_PARTLY_CHAIN, INV_RUSR_UNDRIVEN, INV_RATIO, INV_SCENES };

static vt_model *inv_model(int scene)
{
    vt_model *m = NULL;
    const double c[3] = {0.1, -0.05, 0.2};
    const vt_function crank = vt_function_sine(0.3, 1.0, 2.0, 0.0);
    switch (scene) {
    case INV_CHAIN: assert_ok(vt_scene_chain(&m, 12, VT_CHAIN_TIP_DRIVE)); break;
    case INV_FREE_TREE: m = vt_test_floating_tree(7, 10, 1, c); break;
    case INV_BASE_TREE: m = vt_test_floating_tree(7, 10, 0, c); break;
    case INV_FOURBAR: assert_ok(vt_scene_fourbar(&m, crank)); break;
    case INV_PARTLY_CHAIN: m = partly_driven_chain(12); break;
    case INV_RATIO: m = vt_test_ratio_chain(1, 3, 6.0); break; /* the maximal route (masses rise by 1e6 a rod) */
    default: assert_ok(vt_scene_fourbar_rusr(&m, crank)); break;
    }
    if (scene == INV_RUSR_UNDRIVEN) {
        vt_model *m0 = m;
        assert_ok(vt_model_without_drives(&m, m0));
        vt_model_free(m0);
    }
    return m;
}

/* the scene's state (time 0), loads and, for the motion given, q̈ */
static void inv_state(const vt_model *m, vt_data *d, int scene)
{
    uint64_t s = 11;
    if (scene == INV_CHAIN || scene == INV_PARTLY_CHAIN) {
        vt_test_chain_state(m, d, 1);
    } else if (scene == INV_RATIO) {
        for (int k = 0; k < m->nv; k++) d->q[k] = 0.3 + 0.25 * k, d->qd[k] = 0.5 - 0.2 * k, d->qdd[k] = 0.1 * k;
    } else if (scene == INV_FOURBAR || scene == INV_FOURBAR_RUSR || scene == INV_RUSR_UNDRIVEN) {
        assert_int_equal(scene == INV_FOURBAR ? vt_scene_fourbar_assemble(m, d, 0.9, 1.3, NULL, NULL)
                                              : vt_scene_fourbar_rusr_assemble(m, d, 0.9, 1.3, NULL, NULL), 0);
    } else {
        vt_scene_random_state(m, d, &s);
        for (int c = 0; c < m->nv; c++) d->qdd[c] = vt_rand_uniform(&s, -3, 3);
    }
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = vt_rand_uniform(&s, -1, 1);
    for (int i = 1; i <= m->nbody; i++)
        for (int k = 0; k < 6; k++) d->xfrc[6 * i + k] = vt_rand_uniform(&s, -2, 2);
}

static void test_translation_invariance(void **state)
{
    (void)state;
    static const char *scene_name[] = {"tip-driven chain", "free-rooted tree", "base-rooted tree", "four-bar RSUR",
                                       "four-bar RUSR", "partly joint-driven chain", "four-bar RUSR without its drive",
                                       "chain rising by 1e6 a rod, driven at joint 1"};
    static const char *path_name[] = {"dense", "recursive", "motion"};
    /* 1e9 m: where the chain came back as −1004 N instead of 4.98 N */
    const double dist[3] = {1e3, 1e6, 1e9}, tol[3] = {1e-13, 1e-10, 1e-10}, u[3] = {0.48, -0.6, 0.64};
    for (int scene = 0; scene < INV_SCENES; scene++)
        for (int k = 0; k < 3; k++) {
            const double D[3] = {dist[k] * u[0], dist[k] * u[1], dist[k] * u[2]};
            vt_model *mr = inv_model(scene), *mt = inv_model(scene);
            place_model(mr, D, 1);
            place_model(mt, D, 0);
            const int trees = mr->ncut == 0 && mr->body_joint[1] != VT_JOINT_BASE;
            for (int path = 0; path < 2 + trees; path++) {
                vt_data *dr, *dt;
                assert_ok(vt_data_create(&dr, mr));
                assert_ok(vt_data_create(&dt, mt));
                inv_state(mr, dr, scene);
                inv_state(mt, dt, scene);
                place_state(mr, dr, D, 1);
                place_state(mt, dt, D, 0);
                vt_status (*f)(const vt_model *, vt_data *) =
                    path == 0 ? vt_inverse_dynamics : path == 1 ? vt_inverse_dynamics_recursive : vt_inverse_dynamics_motion;
                assert_ok(f(mr, dr));
                assert_ok(f(mt, dt));
                assert_int_equal(dt->route, dr->route);
                if (scene == INV_RATIO && path < 2) assert_int_equal(dt->route, VT_ROUTE_MAXIMAL);
                const char *what = "";
                const double c = outputs_change(mr, dt, dr, &what);
                print_message("%s, %s, D = %g m: largest change %.3g (%s)\n", scene_name[scene], path_name[path], dist[k],
                              c, what);
                if (!(c <= tol[k]))
                    fail_msg("%s, %s, D = %g m: %s changed by %.3g of its largest entry (> %g)", scene_name[scene],
                             path_name[path], dist[k], what, c, tol[k]);
                vt_data_free(dr);
                vt_data_free(dt);
            }
            vt_model_free(mr);
            vt_model_free(mt);
        }
}

/* The scene m0 D from o: body 1 a pendulum at the global origin (a revolute root, its rate free),
 * bodies 2.. m0's own, their roots and the ground points of m0's rows moved by D as in
 * place_model; m0's drives and cut joints on the same bodies. */
static vt_model *beside_pendulum(const vt_model *m0, const double D[3])
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def pend = vt_default_body_def();
    pend.mass = 0.8;
    pend.inertia[0] = 0.01, pend.inertia[4] = 0.02, pend.inertia[8] = 0.015;
    pend.joint_child[0] = -0.3, pend.joint_child[1] = 0.05;
    assert_int_equal(vt_builder_add_body(b, &pend), 1);
    for (int i = 1; i <= m0->nbody; i++) {
        vt_body_def d = vt_test_body_of(m0, i);
        d.parent = d.parent ? d.parent + 1 : 0;
        assert_int_equal(vt_builder_add_body(b, &d), i + 1);
    }
    for (int k = 0; k < m0->ndrive; k++) {
        vt_drive_def dr = m0->drive[k];
        dr.body += 1;
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    for (int k = 0; k < m0->ncut; k++) {
        vt_cut_joint_def c = m0->cut[k];
        c.body_a = c.body_a ? c.body_a + 1 : 0;
        c.body_b = c.body_b ? c.body_b + 1 : 0;
        assert_true(vt_builder_add_cut_joint(b, &c) >= 0);
    }
    vt_model *m = vt_test_build(b);
    for (int i = 2; i <= m->nbody; i++)
        if (m->body_parent[i] == 0) shift3(m->body_jpar + 3 * i, D, 0);
    for (int r = 0; r < m->nc; r++)
        for (int side = 0; side < 2; side++)
            if (m->con_body[2 * r + side] == 0) shift3(m->con_point + 6 * r + 3 * side, D, 0);
    return m;
}

/* A huge load at a fixed point (the fuzzer's crash-31ead535): a point mass of 0.1 kg without
 * inertia on a spherical joint at the origin, closed by a cylindrical cut joint to a body on a
 * cylindrical joint 7 m away (o is that body's joint point), a force of 1e50 N and a moment of a
 * few N·m applied to the point mass. The force acts where the mass cannot move: it reaches only
 * the spherical joint's reaction, and the moment must be carried by the cut joint (a spherical
 * joint carries none). The recursive general route forms Q about o, where the force's ω · (c − o)
 * × f and v · f are 7e50 each and cancel, taking the moment with them; it must see that Q has no
 * digit there and hand the instant to the dense stages (VT_FALLBACK_COMPOSITE_ROUNDOFF), so that
 * both paths give the same q̈ and λ (1e-10) and the spherical joint's reaction moment is zero
 * (to 1e-12 of the moments). */
static void test_load_at_fixed_point(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def one = vt_default_body_def();
    one.joint = VT_JOINT_CYLINDRICAL;
    one.axis1[0] = 0.0, one.axis1[1] = -1.0, one.axis1[2] = 0.0;
    one.mass = 7.475;
    one.inertia[0] = one.inertia[4] = one.inertia[8] = 0.5;
    const double jp[3] = {6.25, -1.6875, 2.6875}, jc[3] = {2.0, 2.9375, 7.1875};
    memcpy(one.joint_parent, jp, sizeof jp);
    memcpy(one.joint_child, jc, sizeof jc);
    assert_int_equal(vt_builder_add_body(b, &one), 1);
    vt_body_def dot = vt_default_body_def(); /* at its joint: no lever, no inertia */
    dot.joint = VT_JOINT_SPHERICAL;
    dot.mass = 0.1;
    dot.inertia[0] = dot.inertia[4] = dot.inertia[8] = 0.0;
    assert_int_equal(vt_builder_add_body(b, &dot), 2);
    vt_cut_joint_def cut = vt_default_cut_joint_def();
    cut.joint = VT_JOINT_CYLINDRICAL;
    cut.body_a = 2, cut.body_b = 1;
    cut.point_b[0] = 0.5;
    assert_true(vt_builder_add_cut_joint(b, &cut) >= 0);
    vt_model *m = vt_test_build(b);
    assert_int_equal(m->nv, 5);
    assert_int_equal(m->nc, 4);
    vt_data *d[2];
    for (int k = 0; k < 2; k++) {
        assert_ok(vt_data_create(&d[k], m));
        const double q[6] = {1.14375, 0.4125, 0.813193, -0.0139804, 0.475333, -0.335529};
        const double qd[5] = {-6.125, -1.0, 0.625, 0.0, 0.0};
        const double xf[12] = {-6.3125, 2.9375, -7.1875, -1.0, 5.5625, 4.375, -1e50, 1.375, 5.5625, 1.5625, 2.3125, 5.8125};
        memcpy(d[k]->q, q, sizeof q);
        memcpy(d[k]->qd, qd, sizeof qd);
        memcpy(d[k]->xfrc + 6, xf, sizeof xf);
        const vt_status st = k ? vt_inverse_dynamics_recursive(m, d[k]) : vt_inverse_dynamics(m, d[k]);
        if (st) fail_msg("%s: %s", k ? "recursive" : "dense", d[k]->message);
    }
    if (!(d[1]->fallback & VT_FALLBACK_COMPOSITE_ROUNDOFF)) fail_msg("recursive fallback %d: kept Q about o", d[1]->fallback);
    vt_test_compare(d[1]->qdd, d[0]->qdd, m->nv, 1e-10, "qdd");
    vt_test_compare(d[1]->lambda, d[0]->lambda, m->nc, 1e-10, "lambda");
    for (int k = 0; k < 2; k++) {
        const double ms = vt_test_maxabs(d[k]->jnt_moment, 9);
        for (int c = 0; c < 3; c++) assert_near(d[k]->jnt_moment[6 + c], 0.0, 1e-12 * ms);
        vt_data_free(d[k]);
    }
    vt_model_free(m);
}

/* A mechanism standing D = 1 km and 1e6 m from o (body 1's joint point, the twists' and the
 * routes' reference): a pendulum at the global origin is body 1, and beside it, D away,
 *   0  the tip-driven chain (12 links: one point row, articulated bodies with a row),
 *   1  the same chain with every other joint driven (joint rows only: the free rates' solve),
 *   2  the RSUR four-bar without its crank drive (a loop: 4 rows, 5 rates),
 *   3  a floating robot (free root, 12 links of masses 1e-9 to 1e2 kg, every joint driven).
 * The mechanism's rates, rows and joints are decoupled from the pendulum's (M* and Φ_q block
 * diagonal, no shared body): its q̈, λ, efforts and reactions must be those of the same mechanism
 * alone at the origin (there o is its own first joint point), on both paths and with the motion
 * given (the trees: vt_inverse_dynamics_motion's fused passes), to 1e-13
 * at 1 km and 1e-10 at 1e6 m of each array's largest entry. Both paths form their lever arms
 * from the joints' own vectors (S, Φ_q, ẍ, the subtrees' wrenches about each joint point, the
 * reactions' arms): scenes 0-2 come out bitwise the same, the robot to 5e-14 at either distance.
 * About o they lost digits with D (the recursive articulated route's pivots about o sent the
 * tip-driven chain at 1e6 m to the dense stages, changed by 3e-8; its wrenches about o left
 * 4e-12 and 2e-10, the dense path 9e-11 and 5e-8). */
static vt_model *spread_tree(uint64_t seed, int n, int root_free, int drive_all);

static void test_far_from_o(void **state)
{
    (void)state;
    const double dist[2] = {1e3, 1e6}, tol[2] = {1e-13, 1e-10};
    const double u[3] = {0.48, -0.6, 0.64};
    static const char *name[4] = {"tip-driven chain", "partly joint-driven chain", "RUSR four-bar without its drive",
                                  "floating robot, joints driven"};
    for (int scene = 0; scene < 4; scene++)
        for (int k = 0; k < 2; k++) {
            const double D[3] = {dist[k] * u[0], dist[k] * u[1], dist[k] * u[2]};
            vt_model *m0 = scene == 0 ? inv_model(INV_CHAIN)
                         : scene == 1 ? inv_model(INV_PARTLY_CHAIN)
                         : scene == 2 ? inv_model(INV_RUSR_UNDRIVEN)
                                      : spread_tree(11, 12, 1, 1);
            vt_model *m = beside_pendulum(m0, D);
            const vt_model *alone = m0;
            vt_data *d, *da;
            assert_ok(vt_data_create(&d, m));
            assert_ok(vt_data_create(&da, alone));
            /* the state: the chain's reference state or the assembled four-bar, random loads */
            if (scene < 3) inv_state(alone, da, scene == 0 ? INV_CHAIN : scene == 1 ? INV_PARTLY_CHAIN : INV_RUSR_UNDRIVEN);
            else { /* the free root at (0.1, 0.2, 0.3) from its ground point, turned; every rate moving */
                const double nq = sqrt(0.81 + 0.01 + 0.04 + 0.09);
                const double root[7] = {0.1, 0.2, 0.3, 0.9 / nq, 0.1 / nq, -0.2 / nq, 0.3 / nq};
                memcpy(da->q, root, sizeof root);
                for (int c = 7; c < alone->nq; c++) da->q[c] = 0.8 * sin(1.3 * c);
                for (int c = 0; c < alone->nv; c++) da->qd[c] = 0.5 * cos(0.7 * c);
            }
            d->q[0] = 0.4, d->qd[0] = 0.7;
            memcpy(d->q + 1, da->q, (size_t)alone->nq * sizeof(double));
            memcpy(d->qd + 1, da->qd, (size_t)alone->nv * sizeof(double));
            memcpy(d->qfrc + 1, da->qfrc, (size_t)alone->nv * sizeof(double));
            memcpy(d->xfrc + 12, da->xfrc + 6, 6 * (size_t)alone->nbody * sizeof(double));
            for (int path = 0; path < 3; path++) {
                const int dense = path == 1;
                if (path == 2) { /* the motion given (trees): the fused passes */
                    if (alone->ncut > 0) continue;
                    d->qdd[0] = 0.0;
                    memcpy(d->qdd + 1, da->qdd, (size_t)alone->nv * sizeof(double));
                    assert_ok(vt_inverse_dynamics_motion(alone, da));
                    assert_ok(vt_inverse_dynamics_motion(m, d));
                } else if (dense) {
                    assert_ok(vt_inverse_dynamics(alone, da));
                    assert_ok(vt_inverse_dynamics(m, d));
                } else {
                    assert_ok(vt_inverse_dynamics_recursive(alone, da));
                    assert_ok(vt_inverse_dynamics_recursive(m, d));
                }
                const int nb3 = 3 * alone->nbody, nv = alone->nv, nc = alone->nc, nk3 = 3 * alone->ncut;
                const struct { const char *what; const double *x, *y; int n; } out[] = {
                    {"qdd", d->qdd + 1, da->qdd, nv}, {"lambda", d->lambda, da->lambda, nc},
                    {"qfrc_drive", d->qfrc_drive + 1, da->qfrc_drive, nv},
                    {"jnt_force", d->jnt_force + 6, da->jnt_force + 3, nb3}, {"jnt_moment", d->jnt_moment + 6, da->jnt_moment + 3, nb3},
                    {"jnt_force_body", d->jnt_force_body + 6, da->jnt_force_body + 3, nb3},
                    {"jnt_moment_body", d->jnt_moment_body + 6, da->jnt_moment_body + 3, nb3},
                    {"cut_force", d->cut_force, da->cut_force, nk3}, {"cut_moment", d->cut_moment, da->cut_moment, nk3}};
                const double mfloor = fmax(vt_test_maxabs(da->jnt_moment, 3 * (alone->nbody + 1)), vt_test_maxabs(da->qfrc_drive, nv));
                double worst = 0.0;
                const char *what = "";
                for (size_t o = 0; o < sizeof out / sizeof out[0]; o++) {
                    const double c = change(out[o].x, out[o].y, out[o].n, strstr(out[o].what, "moment") ? mfloor : 0.0);
                    if (c > worst) worst = c, what = out[o].what;
                }
                print_message("%s, %s, D = %g m from o: route %d (alone %d), fallback %d, largest change %.3g (%s)\n",
                              path == 2 ? "motion" : dense ? "dense" : "recursive", name[scene], dist[k], d->route, da->route,
                              d->fallback, worst, what);
                assert_int_equal(d->route, da->route);
                if (path == 0) assert_int_equal(d->route, VT_ROUTE_ARTICULATED);
                const double t = tol[k];
                if (!(worst <= t))
                    fail_msg("%s, D = %g m from o: %s changed by %.3g of its largest entry (> %g)", name[scene], dist[k], what, worst, t);
            }
            vt_data_free(d);
            vt_data_free(da);
            vt_model_free(m);
            vt_model_free(m0);
        }
}

/* A floating robot with an inertia spread like Talos' and beyond: a root (free joint or the
 * paper's base body) and a random tree of scalar joints whose masses are log-uniform in
 * [1e-9, 1e2] kg, inertias in proportion; every joint rate driven (drive_all) or every other
 * body's. */
static vt_model *spread_tree(uint64_t seed, int n, int root_free, int drive_all)
{
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, seed, n, VT_SCENE_SCALAR_JOINTS));
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def root = vt_default_body_def();
    root.joint = root_free ? VT_JOINT_FREE : VT_JOINT_BASE;
    root.mass = 30.0;
    const double J[9] = {1.5, 0.05, -0.02, 0.05, 1.7, 0.03, -0.02, 0.03, 0.9};
    memcpy(root.inertia, J, sizeof J);
    const double c[3] = {0.02, -0.05, 0.1};
    if (root_free) memcpy(root.joint_child, c, sizeof c);
    assert_int_equal(vt_builder_add_body(b, &root), 1);
    uint64_t s = seed * 977;
    for (int i = 1; i <= probe->nbody; i++) {
        vt_body_def d = vt_test_body_of(probe, i);
        d.parent += 1;
        d.mass = pow(10.0, vt_rand_uniform(&s, -9.0, 2.0));
        for (int k = 0; k < 9; k++) d.inertia[k] = probe->body_inertia[9 * i + k] * d.mass / probe->body_mass[i];
        assert_int_equal(vt_builder_add_body(b, &d), i + 1);
        for (int k = 0; k < probe->body_nv[i] && (drive_all || i % 2); k++)
            vt_test_add_joint_drive(b, i + 1, k, vt_function_sine(0.1 + 0.01 * k, 0.3, 2.0, 0.5));
    }
    vt_model *m = vt_test_build(b);
    vt_model_free(probe);
    return m;
}

/* Inertia spread alone is not ill-conditioning: floating trees with masses from 1e-9 to 1e2 kg at
 * random states, fully and partly driven, free and base roots: no warning and no failure on
 * either path, the results the same (vt_test_both: the dense solve as the second method), and the
 * estimate the same number on both paths where both estimate by the same definition */
static void test_inertia_spread(void **state)
{
    (void)state;
    int states = 0;
    double worst = 1.0;
    for (uint64_t seed = 1; seed <= 8; seed++) {
        vt_model *m = spread_tree(seed, 14, seed % 2, seed % 4 < 2);
        vt_data *dr, *dd;
        assert_ok(vt_data_create(&dr, m));
        assert_ok(vt_data_create(&dd, m));
        for (int k = 0; k < 5; k++, states++) {
            uint64_t s = seed * 31 + (uint64_t)k;
            vt_scene_random_state(m, dd, &s);
            dd->time = 0.1 * k;
            memcpy(dr->q, dd->q, (size_t)m->nq * sizeof(double));
            memcpy(dr->qd, dd->qd, (size_t)m->nv * sizeof(double));
            dr->time = dd->time;
            vt_test_both(m, dr, dd);
            if (dd->warning || dr->warning)
                fail_msg("seed %d state %d: warning (rcond %.3g dense route %d, %.3g recursive route %d)", (int)seed, k,
                         dd->rcond, dd->route, dr->rcond, dr->route);
            if (dr->route == VT_ROUTE_ARTICULATED && dd->route == VT_ROUTE_FREE_RATES)
                assert_near(dr->rcond, dd->rcond, 1e-9 * dd->rcond);
            if (dd->route == VT_ROUTE_FREE_RATES || dd->route == VT_ROUTE_SCHUR) { /* by LAPACK, as the docs define it */
                const double expect = vt_test_known_rcond(m, dd);
                assert_near(dd->rcond, expect, 1e-9 * expect);
            }
            worst = fmin(worst, fmin(dd->rcond, dr->rcond));
        }
        vt_data_free(dr);
        vt_data_free(dd);
        vt_model_free(m);
    }
    print_message("inertia spread 1e-9..1e2 kg: %d states, smallest rcond %.3g\n", states, worst);
}

/* The fuzzer's four round-off findings (fuzz/findings/new-*), each with an exact zero that the
 * paths compute as round-off: an arm (a heavy revolute link hung 30 m from the origin) carrying
 *   0  (beside it) a body on a spherical joint to the ground with a point drive at the joint's
 *      centre: a zero row
 *   1  a point mass on a cylindrical joint through it: its spin has no inertia
 *   2  a point mass on a spherical joint at its centre: three rates without inertia
 *   3  a point mass on a spherical joint off its centre: it spins freely about the joint–mass
 *      line (M* singular, no single rate without inertia)
 * Both paths must refuse, with the same status: 0 dependent rows, 1-3 singular. */
static vt_model *roundoff_model(int which)
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def arm = vt_default_body_def();
    arm.mass = 3.0;
    arm.inertia[0] = 0.2, arm.inertia[4] = 0.3, arm.inertia[8] = 0.25;
    arm.joint_parent[0] = 30.0, arm.joint_parent[1] = 20.0, arm.joint_parent[2] = -10.0;
    /* 3 near the origin: M* about O, 36 m away, carries round-off of 1e-12 of its size in the free
     * spin's direction (no single rate's: not judged per rate), and the general route's estimate
     * stays just above rcond_min there: that is translation invariance's part */
    if (which == 3) arm.joint_parent[0] = 0.3, arm.joint_parent[1] = 0.2, arm.joint_parent[2] = -0.1;
    arm.joint_child[0] = -0.4, arm.joint_child[1] = 0.1;
    arm.axis1[0] = 0.3, arm.axis1[1] = 0.5, arm.axis1[2] = 0.8;
    assert_int_equal(vt_builder_add_body(b, &arm), 1);
    vt_body_def e = vt_default_body_def();
    e.parent = which == 0 ? 0 : 1; /* the zero row: a spherical root, far from the origin */
    e.joint = which == 1 ? VT_JOINT_CYLINDRICAL : VT_JOINT_SPHERICAL;
    e.mass = 0.7;
    if (which == 0) e.inertia[0] = 0.01, e.inertia[4] = 0.02, e.inertia[8] = 0.015;
    e.joint_parent[0] = 0.5, e.joint_parent[1] = -0.2, e.joint_parent[2] = 0.1;
    if (which == 0) e.joint_parent[0] = 29.0, e.joint_parent[1] = 21.0, e.joint_parent[2] = -11.0;
    if (which == 0 || which == 3) e.joint_child[0] = 0.3, e.joint_child[1] = -0.1, e.joint_child[2] = 0.2;
    e.axis1[0] = 0.6, e.axis1[1] = -0.3, e.axis1[2] = 0.74;
    assert_int_equal(vt_builder_add_body(b, &e), 2);
    if (which == 0) {
        vt_drive_def pd = vt_default_drive_def();
        pd.type = VT_DRIVE_POINT;
        pd.body = 2;
        pd.index = 1;
        memcpy(pd.point, e.joint_child, sizeof pd.point); /* the joint's centre */
        pd.f = vt_function_sine(0.0, 0.2, 1.5, 0.0);
        assert_true(vt_builder_add_drive(b, &pd) >= 0);
    }
    vt_model *m = vt_test_build(b);
    return m;
}

/* Motions without inertia that round-off hides, found by the differential fuzzer. (a) A base body
 * that is a point mass turns without inertia: its M* rows are exactly zero in the dense path and
 * round-off in the recursive one, which once scaled to unit diagonal passed for inertia (a
 * state a little off p^T p = 1 made it so). (b) A point mass on a spherical joint 1e6 m from its
 * centre of mass does not resist turning about the line from the joint to the mass: the
 * articulated pivot of that direction came out negative (round-off of terms of 1e11), and the
 * general route's M* passed for regular. Both paths must refuse both as singular. */
static void test_roundoff_singular(void **state)
{
    (void)state;
    for (int c = 0; c < 2; c++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def body = vt_default_body_def();
        if (c == 0) {
            body.joint = VT_JOINT_UNIVERSAL;
            body.mass = 4.1875;
            body.inertia[0] = body.inertia[4] = body.inertia[8] = 0.6875;
            body.axis1[2] = -1.0;
            assert_int_equal(vt_builder_add_body(b, &body), 1);
            body = vt_default_body_def();
            body.joint = VT_JOINT_BASE;
            body.mass = 0.1;
            assert_int_equal(vt_builder_add_body(b, &body), 2);
        } else {
            body.joint = VT_JOINT_TRANSLATIONAL;
            body.mass = 2.5;
            body.inertia[0] = body.inertia[4] = body.inertia[8] = 2.4;
            assert_int_equal(vt_builder_add_body(b, &body), 1);
            body = vt_default_body_def();
            body.parent = 1;
            body.joint = VT_JOINT_SPHERICAL;
            body.mass = 0.1;
            body.joint_child[0] = 3.2e5, body.joint_child[1] = 1.2e5, body.joint_child[2] = 9.4e5;
            assert_int_equal(vt_builder_add_body(b, &body), 2);
        }
        vt_model *m = vt_test_build(b);
        vt_data *dd, *dr;
        assert_ok(vt_data_create(&dd, m));
        assert_ok(vt_data_create(&dr, m));
        const double q0[9] = {1.875, 1.875, -2.1, -7.5, -7.5, -0.643563, 0.536303, -0.386138, -0.386138};
        const double qd0[9] = {-4.5, -4.5, -4.5, -4.5, -4.5, -1.98389, -6.59676, -2.99034, -2.86534};
        const double q1[5] = {-0.5, -0.5, -0.5, -0.5, -0.5}, qd1[4] = {-7.5, -7.5, -7.5, -7.5};
        memcpy(dd->q, c ? q1 : q0, (size_t)m->nq * sizeof(double));
        memcpy(dd->qd, c ? qd1 : qd0, (size_t)m->nv * sizeof(double));
        memcpy(dr->q, dd->q, (size_t)m->nq * sizeof(double));
        memcpy(dr->qd, dd->qd, (size_t)m->nv * sizeof(double));
        const vt_status sd = vt_inverse_dynamics(m, dd), sr = vt_inverse_dynamics_recursive(m, dr);
        print_message("case %d: dense %s (%s), recursive %s (%s)\n", c, vt_status_string(sd), dd->message,
                      vt_status_string(sr), dr->message);
        assert_int_equal(sd, VT_ERR_SINGULAR);
        assert_int_equal(sr, VT_ERR_SINGULAR);
        vt_data_free(dd);
        vt_data_free(dr);
        vt_model_free(m);
    }
}

/* A pivot at the bottom of the normal range (the fuzzer's crash-bad72ed5…): a body on a spherical
 * joint at its centre of mass, inertia DBL_MIN I, spinning freely. S^T Ī S rounds M*_aa just below
 * DBL_MIN, where a number has lost its digits: the dense path refused, the articulated route took
 * its own pivot (DBL_MIN) and returned VT_OK. Both paths must refuse it alike (the recursive one
 * hands pivots below DBL_MIN / ε to the dense stages); at 1e-300 I (there too) and 1e-280 I (on
 * the articulated route) both solve it, and an isotropic inertia spinning at its centre feels no
 * moment: q̈ = 0. */
static void test_subnormal_pivot(void **state)
{
    (void)state;
    const double k[3] = {DBL_MIN, 1e-300, 1e-280};
    for (int c = 0; c < 3; c++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def body = vt_default_body_def();
        body.joint = VT_JOINT_SPHERICAL;
        body.mass = 7.5375;
        body.inertia[0] = body.inertia[4] = body.inertia[8] = k[c];
        body.joint_parent[0] = 1.0;
        assert_int_equal(vt_builder_add_body(b, &body), 1);
        vt_model *m = vt_test_build(b);
        vt_data *dd, *dr;
        assert_ok(vt_data_create(&dd, m));
        assert_ok(vt_data_create(&dr, m));
        const double q[4] = {0.0652584, -0.171303, -0.978876, 0.090546}, qd[3] = {2.3125, 2.3125, 2.3125};
        const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (int i = 0; i < 4; i++) dd->q[i] = dr->q[i] = q[i] / n;
        memcpy(dd->qd, qd, sizeof qd);
        memcpy(dr->qd, qd, sizeof qd);
        const vt_status sd = vt_inverse_dynamics(m, dd), sr = vt_inverse_dynamics_recursive(m, dr);
        print_message("inertia %.3g I: dense %s (%s), recursive %s (%s)\n", k[c], vt_status_string(sd), dd->message,
                      vt_status_string(sr), dr->message);
        if (c == 0) {
            assert_int_equal(sd, VT_ERR_SINGULAR);
            assert_int_equal(sr, VT_ERR_SINGULAR);
            assert_non_null(strstr(dr->message, "below the smallest normal number"));
        } else {
            assert_ok(sd);
            assert_ok(sr);
            assert_int_equal(dr->route == VT_ROUTE_ARTICULATED, c == 2);
            for (int a = 0; a < 3; a++) {
                assert_true(fabs(dd->qdd[a]) <= 1e-12);
                assert_true(fabs(dr->qdd[a]) <= 1e-12);
            }
        }
        vt_data_free(dd);
        vt_data_free(dr);
        vt_model_free(m);
    }
}

/* A point mass on a spherical joint turns freely about the joint–mass line: M* is exactly
 * singular (the rates along u = (c − P)/|c − P| have no inertia, M* u = 0). Beside it a revolute
 * body whose joint point, the reference point o of the twists, stands D from it. Near (D = 10)
 * both paths refuse; at D = 1e6 the recursive general route's composite inertias about o hold
 * m D² terms, their round-off (64 ε of them, 0.03 of the spherical rates' M*_aa) hid the
 * singularity, and it returned VT_OK with rcond 2.6e-5 and q̈ of 1e5 (the fuzzer's
 * crash-5bde61aefa…): now it hands the instant to the dense stages, whose rcond refuses. The dense M*
 * is checked against the identity M* u = 0 (to 64 ε of its largest entry × D/|c − P|: S's
 * lever arms from o). */
static void test_roundoff_hides_singular(void **state)
{
    (void)state;
    const double Ds[2] = {10.0, 1e6};
    for (int k = 0; k < 2; k++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def body = vt_default_body_def();
        body.joint = VT_JOINT_REVOLUTE;
        body.mass = 1.6;
        body.axis1[0] = 0.0, body.axis1[1] = 0.0, body.axis1[2] = -1.0;
        body.joint_parent[1] = Ds[k], body.joint_parent[2] = -4.5;
        body.joint_child[0] = -7.5, body.joint_child[1] = 6.125, body.joint_child[2] = 4.1875;
        assert_int_equal(vt_builder_add_body(b, &body), 1);
        body = vt_default_body_def();
        body.joint = VT_JOINT_SPHERICAL;
        body.mass = 0.1;
        body.joint_parent[2] = -1.75;
        body.joint_child[1] = -1.3125, body.joint_child[2] = -4.25;
        assert_int_equal(vt_builder_add_body(b, &body), 2);
        vt_model *m = vt_test_build(b);
        vt_data *dd, *dr;
        assert_ok(vt_data_create(&dd, m));
        assert_ok(vt_data_create(&dr, m));
        for (int c = 0; c < m->nv; c++) dd->qfrc[c] = dr->qfrc[c] = -7.0;
        const vt_status sd = vt_inverse_dynamics(m, dd), sr = vt_inverse_dynamics_recursive(m, dr);
        print_message("D = %g: dense %s (%s), recursive %s (%s)\n", Ds[k], vt_status_string(sd), dd->message,
                      vt_status_string(sr), dr->message);
        assert_int_equal(sd, VT_ERR_SINGULAR);
        assert_int_equal(sr, VT_ERR_SINGULAR);
        assert_int_equal(dr->route, VT_ROUTE_NONE);
        /* the identity: u along the joint–mass line (global = the spherical rates' axes at p = 1) */
        assert_ok(vt_kinematics(m, dd));
        assert_ok(vt_mass_matrix(m, dd));
        const double u[3] = {0.0, -1.3125 / hypot(1.3125, 4.25), -4.25 / hypot(1.3125, 4.25)};
        double big = 0.0;
        for (int e = 0; e < m->nv * m->nv; e++) big = fmax(big, fabs(dd->Mstar[e]));
        for (int r = 0; r < m->nv; r++) {
            double mu = 0.0;
            for (int c = 0; c < 3; c++) mu += dd->Mstar[r + (size_t)(1 + c) * (size_t)m->nv] * -u[c];
            assert_true(fabs(mu) <= 64.0 * 2.220446049250313e-16 * big * (1.0 + Ds[k] / 4.45));
        }
        vt_data_free(dd);
        vt_data_free(dr);
        vt_model_free(m);
    }
}

static void test_roundoff_zeros(void **state)
{
    (void)state;
    const vt_status expect[4] = {VT_ERR_DEPENDENT_CONSTRAINTS, VT_ERR_SINGULAR, VT_ERR_SINGULAR, VT_ERR_SINGULAR};
    for (int which = 0; which < 4; which++) {
        vt_model *m = roundoff_model(which);
        vt_data *dr, *dd;
        assert_ok(vt_data_create(&dr, m));
        assert_ok(vt_data_create(&dd, m));
        for (int k = 0; k < 20; k++) {
            uint64_t s = 101 * (uint64_t)which + (uint64_t)k + 1;
            vt_scene_random_state(m, dd, &s);
            dd->time = 0.05 * k;
            memcpy(dr->q, dd->q, (size_t)m->nq * sizeof(double));
            memcpy(dr->qd, dd->qd, (size_t)m->nv * sizeof(double));
            dr->time = dd->time;
            const vt_status sd = vt_inverse_dynamics(m, dd), sr = vt_inverse_dynamics_recursive(m, dr);
            if (sd != expect[which] || sr != expect[which])
                fail_msg("case %d state %d: dense %s (%s, rcond %.3g), recursive %s (%s, rcond %.3g, route %d)", which, k,
                         vt_status_string(sd), dd->message, dd->rcond, vt_status_string(sr), dr->message, dr->rcond, dr->route);
        }
        vt_data_free(dr);
        vt_data_free(dd);
        vt_model_free(m);
    }
}

static void residuals_hold(const vt_model *m, const vt_data *d, double tol)
{
    const int nv = m->nv, nc = m->nc;
    const double qmax = vt_test_maxabs(d->qdd, nv); /* the rows are kinematic: q̈ normwise */
    for (int r = 0; r < nc; r++) {
        double v = -d->gamma[r], t = fabs(d->gamma[r]);
        for (int a = 0; a < nv; a++) {
            v += d->Phiq[r + a * nc] * d->qdd[a];
            t += fabs(d->Phiq[r + a * nc]) * qmax;
        }
        if (!(fabs(v) <= tol * t + 1e-300)) fail_msg("row %d: Φ_q q̈ − γ = %.3g of terms %.3g", r, v, t);
    }
    for (int a = 0; a < nv; a++) {
        double v = -d->Q[a], t = fabs(d->Q[a]);
        for (int b = 0; b < nv; b++) {
            v += d->Mstar[a + b * nv] * d->qdd[b];
            t += fabs(d->Mstar[a + b * nv] * d->qdd[b]);
        }
        for (int r = 0; r < nc; r++) {
            v -= d->Phiq[r + a * nc] * d->lambda[r];
            t += fabs(d->Phiq[r + a * nc] * d->lambda[r]);
        }
        if (!(fabs(v) <= tol * t + 1e-300)) fail_msg("rate %d: M* q̈ − Q − Φ_q^T λ = %.3g of terms %.3g", a, v, t);
    }
}

/* Mass ratios of 1e24 along a chain (vt_test_ratio_chain: five planar rods whose masses fall
 * from 1e12 to 1e-12 kg, or rise; and of 1e12, 1e3 a rod), driven in four ways, at three states
 * each. No failure on
 * either path, no warning where the rows fix the motion (the estimate is the pose's alone); each
 * path's q̈ and λ satisfy (5) in the dense M*, Q and Φ_q, Φ_q q̈ = γ against ‖Φ_q,r‖ max|q̈| and
 * each rate's M* q̈ − Q − Φ_q^T λ = 0 against the size of its own terms (a backward error that
 * the light rods' rates, 1e24 below the heavy ones', cannot hide in) to 1e-14 / rcond; the paths
 * agree (vt_test_both; with free motion q̈ to 1e-14 / rcond, and the same estimate). With free motion
 * the free-rate routes' estimate falls below √rcond_warn = 1e-3 on some of these chains (a
 * 1e12 kg tip on links of 1e-12 … 1e6 kg with joint 1 driven, 6e-8; the chain falling from
 * 1e12 kg with joints 1-2 and the tip driven, 5e-7), where they lose digits the problem keeps:
 * both paths take the maximal route there (VT_FALLBACK_MAXIMAL_CONDITION) and do not warn; the
 * test ratio_oracle holds every answer against the exact ones (mpmath). */
static void test_mass_ratios(void **state)
{
    (void)state;
    double worst = 1.0;
    for (int chain = 0; chain < 4; chain++)
        for (int drive = 0; drive < 4; drive++) {
            const int rising = chain % 2, step = chain < 2 ? 6 : 3; /* 1e6 a rod, then 1e3 */
            vt_model *m = vt_test_ratio_chain(rising, drive, step);
            vt_data *dr, *dd;
            assert_ok(vt_data_create(&dr, m));
            assert_ok(vt_data_create(&dd, m));
            for (int k = 0; k < 3; k++) {
                for (int c = 0; c < m->nv; c++) {
                    dd->q[c] = 0.3 + 0.25 * c + 0.4 * k; /* bent: a regular pose */
                    dd->qd[c] = 0.5 - 0.2 * c + 0.1 * k;
                }
                dd->time = 0.2 * k;
                memcpy(dr->q, dd->q, (size_t)m->nq * sizeof(double));
                memcpy(dr->qd, dd->qd, (size_t)m->nv * sizeof(double));
                dr->time = dd->time;
                assert_ok(vt_inverse_dynamics(m, dd));
                assert_ok(vt_inverse_dynamics_recursive(m, dr));
                /* both paths' answers in the dense equations, to what the estimate promises */
                const double tol = fmax(1e-12, 1e-14 / fmin(dd->rcond, dr->rcond));
                residuals_hold(m, dd, tol);
                vt_data *dx;
                assert_ok(vt_data_create(&dx, m));
                memcpy(dx->q, dd->q, (size_t)m->nq * sizeof(double));
                memcpy(dx->qd, dd->qd, (size_t)m->nv * sizeof(double));
                dx->time = dd->time;
                assert_ok(vt_inverse_dynamics(m, dx));
                memcpy(dx->qdd, dr->qdd, (size_t)m->nv * sizeof(double));
                memcpy(dx->lambda, dr->lambda, (size_t)m->nc * sizeof(double));
                residuals_hold(m, dx, tol);
                vt_data_free(dx);
                /* 1e3 a rod: no warning on any (the rising chain with joints 1-2 and the tip driven:
                 * both paths know the driven rates' q̈ and keep only the tip's rows in S, 8.5e-3 on
                 * the dense Schur route; over the whole M* the light driven rods' pivots give
                 * 6.6e-13) */
                if (step == 3 && (dd->warning || dr->warning))
                    fail_msg("1e3 a rod, rising %d drive %d state %d: warning (rcond %.3g)", rising, drive, k, dd->rcond);
                if (step == 3 && rising && drive == 2) {
                    assert_int_equal(dd->route, VT_ROUTE_SCHUR);
                    assert_int_equal(dd->fallback, 0);
                }
                if (drive < 2) { /* the rows fix the motion: the estimate is the pose's, 1e24 or not */
                    vt_test_both(m, dr, dd);
                    if (dd->warning || dr->warning) fail_msg("rising %d drive %d state %d: warning", rising, drive, k);
                } else { /* free motion: the paths agree to what the estimate says */
                    for (int a = 0; a < m->nv; a++)
                        assert_near(dr->qdd[a], dd->qdd[a], tol * (1.0 + vt_test_maxabs(dd->qdd, m->nv)));
                    /* the free-rate routes' estimate (the system left once the joint-driven
                     * rates are known) below rcond_warn, or below √rcond_warn with the joint-1
                     * effort the difference of the tip's terms (rising, joint 1 driven): both
                     * paths take the maximal route, and neither warns (its answers against the
                     * exact ones: ratio_oracle) */
                    const double expect = vt_test_known_rcond(m, dd);
                    if (expect < 1e-6 || (rising && drive == 3)) {
                        assert_int_equal(dd->route, VT_ROUTE_MAXIMAL);
                        assert_int_equal(dr->route, VT_ROUTE_MAXIMAL);
                        assert_true(dd->fallback & VT_FALLBACK_MAXIMAL_CONDITION);
                        assert_true(dr->fallback & VT_FALLBACK_MAXIMAL_CONDITION);
                        if (dd->warning || dr->warning) fail_msg("rising %d drive %d state %d: warning", rising, drive, k);
                    }
                    /* joint and point drives mixed: the articulated route itself, the joint
                     * drives' efforts from the subtrees' wrenches, as the dense path's */
                    else if (drive == 2 && dr->route != VT_ROUTE_ARTICULATED) {
                        /* below √rcond_warn: handed to the dense stages, which kept their route */
                        assert_true(expect < 1e-3);
                        assert_int_equal(dr->fallback, VT_FALLBACK_ARTICULATED_CONDITION);
                        assert_int_equal(dr->route, dd->route);
                    } else if (drive == 2) {
                        assert_int_equal(dr->fallback, 0);
                        for (int r = 0; r < m->nc; r++)
                            assert_near(dr->lambda[r], dd->lambda[r], tol * (1.0 + vt_test_maxabs(dd->lambda, m->nc)));
                    }
                    /* both estimates measure the system left once the joint-driven rates are
                     * known (vt_test_known_rcond): the articulated route's and the dense Schur
                     * route's */
                    if (dr->route == VT_ROUTE_ARTICULATED) assert_near(dr->rcond, expect, tol * expect); /* itself computed to that */
                    if (dd->route == VT_ROUTE_SCHUR) assert_near(dd->rcond, expect, tol * expect);
                }
                worst = fmin(worst, fmin(dd->rcond, dr->rcond));
            }
            vt_data_free(dr);
            vt_data_free(dd);
            vt_model_free(m);
        }
    print_message("mass ratios 1e24 and 1e12: smallest rcond %.3g\n", worst);
}

/* A 1e154 kg link (6 kg·m²) in a planar chain of 1 kg rods, fully driven (joints 1-3 and the
 * tip's x, y: the square route) and with a rate free (joints 1-2 and the tip: Schur, articulated):
 * no failure and no warning on either path (a radius of gyration of 1e-77 m weighted the rows
 * before: the square route refused, calling three joint drives dependent); both paths' answers in
 * the dense equations (residuals_hold), and the square route's estimate against its definition,
 * κ₁(G Φ_q C)^-2 with ℓ from vt_test_rows_length, the inverse by LAPACK's dgesv. */
static void test_heavy_link(void **state)
{
    (void)state;
    for (int drive = 1; drive < 3; drive++) {
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        for (int k = 0; k < 5; k++) {
            vt_body_def link = vt_default_body_def();
            link.parent = k;
            link.mass = k == 2 ? 1e154 : 1.0;
            link.inertia[0] = k == 2 ? 3.0 : 0.0; /* the heavy one: 3, 3, 6 kg·m² */
            link.inertia[4] = k == 2 ? 3.0 : 0.4 * 0.4 / 12.0;
            link.inertia[8] = k == 2 ? 6.0 : 0.4 * 0.4 / 12.0;
            link.joint_child[0] = -0.2;
            link.joint_parent[0] = k ? 0.2 : 0.0;
            assert_int_equal(vt_builder_add_body(b, &link), k + 1);
        }
        for (int k = 0; k < (drive == 1 ? 3 : 2); k++)
            vt_test_add_joint_drive(b, k + 1, 0, vt_function_sine(0.3 + 0.2 * k, 0.4, 1.5, 0.2 * k));
        for (int c = 0; c < 2; c++) {
            vt_drive_def tip = vt_default_drive_def();
            tip.type = VT_DRIVE_POINT;
            tip.body = 5;
            tip.index = c;
            tip.point[0] = 0.2;
            tip.f = vt_function_sine(0.0, 0.05, 1.0, 0.3 * c);
            assert_true(vt_builder_add_drive(b, &tip) >= 0);
        }
        vt_model *m = vt_test_build(b);
        vt_data *dd, *dr;
        assert_ok(vt_data_create(&dd, m));
        assert_ok(vt_data_create(&dr, m));
        for (int a = 0; a < 5; a++) {
            dd->q[a] = dr->q[a] = 0.3 + 0.25 * a;
            dd->qd[a] = dr->qd[a] = 0.5 - 0.2 * a;
        }
        const vt_status sd = vt_inverse_dynamics(m, dd), sr = vt_inverse_dynamics_recursive(m, dr);
        if (sd || sr) fail_msg("drive %d: dense %s (%s), recursive %s (%s)", drive, vt_status_string(sd), dd->message,
                               vt_status_string(sr), dr->message);
        if (dd->warning || dr->warning) fail_msg("drive %d: warning (rcond %.3g, %.3g)", drive, dd->rcond, dr->rcond);
        /* the square route's estimate is vt_solve's; the articulated one's the system left once
         * the joint-driven rates are known (vt_test_known_rcond), not the dense path's */
        const double expect = dr->route == VT_ROUTE_ARTICULATED ? vt_test_known_rcond(m, dd) : dd->rcond;
        assert_near(dr->rcond, expect, 1e-9 * expect);
        const double tol = fmax(1e-12, 1e-14 / dd->rcond);
        residuals_hold(m, dd, tol);
        memcpy(dd->qdd, dr->qdd, sizeof(double) * 5);
        memcpy(dd->lambda, dr->lambda, sizeof(double) * (size_t)m->nc);
        residuals_hold(m, dd, tol);
        if (drive == 1) { /* κ₁(G Φ_q C)^-2: all rates turn (C = 1/ℓ); the joint rows measure angles (G = ℓ) */
            assert_int_equal(dd->route, VT_ROUTE_SQUARE);
            const double l = vt_test_rows_length(m, dd);
            double A[25], X[25], an = 0.0, xn = 0.0;
            int ipiv[5], info = 0;
            const int n = 5;
            for (int c = 0; c < 5; c++) {
                double cs = 0.0;
                for (int r = 0; r < 5; r++) {
                    A[r + 5 * c] = dd->Phiq[r + 5 * c] / l * (r < 3 ? l : 1.0);
                    X[r + 5 * c] = r == c;
                    cs += fabs(A[r + 5 * c]);
                }
                an = fmax(an, cs);
            }
            dgesv_(&n, &n, A, &n, ipiv, X, &n, &info);
            assert_int_equal(info, 0);
            for (int c = 0; c < 5; c++) {
                double cs = 0.0;
                for (int r = 0; r < 5; r++) cs += fabs(X[r + 5 * c]);
                xn = fmax(xn, cs);
            }
            const double expect = 1.0 / (an * xn * an * xn);
            assert_near(dd->rcond, expect, 1e-9 * expect);
        }
        vt_data_free(dd);
        vt_data_free(dr);
        vt_model_free(m);
    }
}

/* A chain of n revolute links driven at its tip only (the benchmark's chain_tip), n = 12, 100 and
 * 200, up to 135 m long against links of 0.5 m. Its articulated inertias about o held m L² terms
 * that the pivots of the tip's rates cancel, and the route's round-off bound sent n = 100 and 200
 * to the general route, whose composite inertias about o sent them to the dense stages
 * (VT_FALLBACK_COMPOSITE_ROUNDOFF: 6.5 ms an instant). About each body's own joint point the
 * pivots are differences of the subtree's own terms: the articulated route keeps them (no
 * fallback) and must give the dense path's q̈, λ, effort and reactions (S^T M S, no composite
 * inertia) to what its estimate allows, 1e-13 / rcond relative (rcond 1.7e-3, 6.7e-7, 1.6e-8), and
 * the estimate itself from the dense M* and Φ_q by LAPACK (vt_test_known_rcond) to the larger of
 * 1e-9 and that. The general route, whose M* is still formed about o, still hands n = 100 to the
 * dense stages (VT_FALLBACK_COMPOSITE_ROUNDOFF; taken here by allowing redundant rows). */
/* the chain's reference state in fresh data for each path, solved by the dense path (dd) and
 * the recursive one (dr) */
static void solve_at_chain_state(const vt_model *m, vt_data **dd, vt_data **dr)
{
    assert_ok(vt_data_create(dd, m));
    assert_ok(vt_data_create(dr, m));
    vt_test_chain_state(m, *dd, 0);
    vt_test_copy_inputs(m, *dr, *dd);
    assert_ok(vt_inverse_dynamics(m, *dd));
    assert_ok(vt_inverse_dynamics_recursive(m, *dr));
}

static void test_long_chain(void **state)
{
    (void)state;
    const int ns[3] = {12, 100, 200};
    for (int k = 0; k < 3; k++) {
        vt_model *m;
        assert_ok(vt_scene_chain(&m, ns[k], VT_CHAIN_TIP_DRIVE));
        vt_data *dd, *dr;
        solve_at_chain_state(m, &dd, &dr);
        const int nb3 = 3 * (m->nbody + 1);
        const double tol = 1e-13 / dr->rcond, expect = vt_test_known_rcond(m, dd);
        const struct { const char *name; const double *x, *y; int n; } out[] = {
            {"qdd", dr->qdd, dd->qdd, m->nv}, {"lambda", dr->lambda, dd->lambda, m->nc},
            {"drive_effort", dr->drive_effort, dd->drive_effort, m->ndrive}, {"jnt_force", dr->jnt_force, dd->jnt_force, nb3},
            {"jnt_moment", dr->jnt_moment, dd->jnt_moment, nb3}, {"jnt_force_total", dr->jnt_force_total, dd->jnt_force_total, nb3},
            {"jnt_moment_total", dr->jnt_moment_total, dd->jnt_moment_total, nb3}};
        double worst = 0.0;
        for (size_t o = 0; o < sizeof out / sizeof out[0]; o++) {
            const double c = change(out[o].x, out[o].y, out[o].n, 0.0);
            worst = fmax(worst, c);
            if (!(c <= tol)) fail_msg("n = %d: %s differs from the dense path by %.3g of its largest (> %.3g)", ns[k], out[o].name, c, tol);
        }
        print_message("n = %d: route %d, fallback %d, rcond %.3g (LAPACK %.3g), largest difference from the dense path %.3g\n",
                      ns[k], dr->route, dr->fallback, dr->rcond, expect, worst);
        assert_int_equal(dr->route, VT_ROUTE_ARTICULATED);
        assert_int_equal(dr->fallback, 0);
        assert_near(dr->rcond, expect, fmax(1e-9, tol) * expect); /* an estimate has round-off of its own */
        vt_data_free(dd);
        vt_data_free(dr);
        if (ns[k] == 100) { /* the general route (taken when redundant rows are allowed) still forms M*
                             * from composite inertias about o: it hands the instant to the dense stages */
            m->allow_redundant = 1;
            solve_at_chain_state(m, &dd, &dr);
            print_message("n = %d, redundant rows allowed: route %d, fallback %d\n", ns[k], dr->route, dr->fallback);
            assert_int_equal(dr->fallback, VT_FALLBACK_COMPOSITE_ROUNDOFF);
            assert_int_equal(dr->route, dd->route);
            for (int a = 0; a < m->nv; a++) assert_true(dr->qdd[a] == dd->qdd[a]); /* the same stages */
            assert_true(dr->drive_effort[0] == dd->drive_effort[0]);
            vt_data_free(dd);
            vt_data_free(dr);
        }
        vt_model_free(m);
    }
}


/* Joint angles beyond 2^15 rad (a wheel's or a turntable's after many turns): the fused passes
 * take their loop compiled with the C library's sine and cosine (fused_outward_any), the dense
 * path the same through vt_quat_axis_angle. Against the dense path, and against the same chain
 * with the turns taken off (q − 4π K: the same Euler parameters; q + 4π K itself is known to
 * its ulp, 7e-12 rad at 3.8e4, so to 1e-9 of the efforts), both with angles just inside 2^15
 * (the loop without a call) and beyond it. */
static void test_large_angles(void **state)
{
    (void)state;
    const int n = 6;
    const double turns[2][6] = {{0, 2600, 0, -2600, 0, 1}, {0, 3000, 0, -2700, 0, 1}}; /* |q| < 2^15, > 2^15 */
    for (int c = 0; c < 2; c++) {
        vt_model *m;
        vt_data *dr, *dd, *d0;
        assert_ok(vt_scene_chain(&m, n, VT_CHAIN_JOINT_DRIVEN));
        assert_ok(vt_data_create(&dr, m));
        assert_ok(vt_data_create(&dd, m));
        assert_ok(vt_data_create(&d0, m));
        double qmax = 0.0;
        for (int k = 0; k < n; k++) {
            double qdd;
            vt_scene_chain_state(k, &d0->q[k], &d0->qd[k], &qdd);
            dr->q[k] = dd->q[k] = d0->q[k] + 4.0 * 3.14159265358979323846 * turns[c][k];
            dr->qd[k] = dd->qd[k] = d0->qd[k];
            qmax = fmax(qmax, fabs(dr->q[k]));
        }
        assert_true(c == 0 ? qmax < 0x1p15 : qmax > 0x1p15);
        vt_test_both(m, dr, dd);
        assert_int_equal(dr->route, VT_ROUTE_JOINT_DRIVEN);
        assert_ok(vt_inverse_dynamics_recursive(m, d0));
        const double scale = vt_test_maxabs(d0->qfrc_drive, n);
        for (int k = 0; k < n; k++) assert_near(dr->qfrc_drive[k], d0->qfrc_drive[k], 1e-9 * scale);
        for (int k = 0; k < 3 * (n + 1); k++) {
            assert_near(dr->jnt_force[k], d0->jnt_force[k], 1e-9 * (1.0 + vt_test_maxabs(d0->jnt_force, 3 * (n + 1))));
            assert_near(dr->jnt_moment_body[k], d0->jnt_moment_body[k], 1e-9 * (1.0 + vt_test_maxabs(d0->jnt_moment_body, 3 * (n + 1))));
        }
        vt_data_free(dr);
        vt_data_free(dd);
        vt_data_free(d0);
        vt_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_large_angles),
        cmocka_unit_test(test_far_base_body),
        cmocka_unit_test(test_far_point_mass_pivot),
        cmocka_unit_test(test_translation_invariance),
        cmocka_unit_test(test_far_from_o),
        cmocka_unit_test(test_load_at_fixed_point),
        cmocka_unit_test(test_inertia_spread),
        cmocka_unit_test(test_heavy_link),
        cmocka_unit_test(test_roundoff_zeros),
        cmocka_unit_test(test_roundoff_singular),
        cmocka_unit_test(test_subnormal_pivot),
        cmocka_unit_test(test_roundoff_hides_singular),
        cmocka_unit_test(test_long_chain),
        cmocka_unit_test(test_mass_ratios),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
