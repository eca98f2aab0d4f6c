/* src/recursive.c: the recursive evaluation's routes and behaviour. A table of scenes (random
 * trees with every joint kind, with and without drives and cut joints; fully joint-driven chains
 * and trees, the path that factorizes nothing; the paper's scenes; square systems, the four-bars;
 * partly driven trees, articulated bodies; couplings), each at its states against the dense
 * reference path to 1e-12 relative (vt_test_both) and held to the routes and fallback flags it
 * must take; then dependent rows, the motion given (vt_inverse_dynamics_motion), free joints
 * against base bodies, the fused passes' overflow checks and their scans. The accuracy under
 * mass ratios, far poses, large angles, long chains and round-off: test_accuracy.c. */
#include <float.h>

#include "base/scan.h"   /* vt_finite_scan, vt_max_scan: tested here */
#include "model/model.h"
#include "recursive/fused.h" /* vt_motion_add_loads: tested here */ /* the rows' kinds (VT_ROW_JOINT, and vt_test.h's vt_test_known_rcond) */

#include "vt_test.h"

/* ---- the route table: a scene, its states, and the routes the two paths must take ---- */

static vt_model *tree_with(uint64_t seed, int n, unsigned kinds, int drives, int cuts)
{
    vt_builder *b;
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, seed, n, kinds));
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, seed, n, kinds));
    for (int i = 2; drives && i <= n; i += 2) {
        const int jt = probe->body_joint[i];
        if (jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_BASE) continue;
        vt_test_add_joint_drive(b, i, 0, vt_function_sine(0.1, 0.3, 2.0, 0.5));
    }
    if (cuts && (probe->body_joint[7] == VT_JOINT_BASE || probe->body_joint[7] == VT_JOINT_FREE)) {
        vt_cut_joint_def cj = vt_default_cut_joint_def();
        cj.joint = VT_JOINT_SPHERICAL;
        cj.body_a = 0;
        cj.body_b = 7;
        assert_true(vt_builder_add_cut_joint(b, &cj) >= 0);
    }
    vt_model *m = vt_test_build(b);
    vt_model_free(probe);
    return m;
}

/* a random tree of 8 bodies, rate 7 coupled to rate 3 (q_7 = 1.3 q_3 − 0.1), body 5 joint-driven */
static vt_model *coupled_tree(uint64_t seed)
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, seed, 8, VT_SCENE_SCALAR_JOINTS));
    vt_coupling_def c = vt_default_coupling_def();
    c.body_a = 7;
    c.body_b = 3;
    c.ratio = 1.3;
    c.offset = -0.1;
    assert_int_equal(vt_builder_add_coupling(b, &c), 0);
    vt_test_add_joint_drive(b, 5, 0, vt_function_sine(0.1, 0.3, 2.0, 0.5));
    vt_model *m = vt_test_build(b);
    return m;
}

/* applied loads on every body (within ±3) and rate (±1), in that order from s */
static void random_loads(const vt_model *m, vt_data *d, uint64_t *s)
{
    for (int i = 1; i <= m->nbody; i++)
        for (int k = 0; k < 6; k++) d->xfrc[6 * i + k] = vt_rand_uniform(s, -3, 3);
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = vt_rand_uniform(s, -1, 1);
}

/* random trees with every joint kind, with and without drives and cut joints: seeds 1..18
 * (13..18: free joints, the square and articulated routes), every output against the dense path */
static vt_model *random_tree(int v)
{
    const uint64_t seed = (uint64_t)v + 1;
    const unsigned kinds = seed > 12 ? VT_SCENE_WITH_FREE : seed % 3 ? VT_SCENE_ALL_JOINTS : VT_SCENE_NO_BASE;
    return tree_with(seed, 9 + (int)seed, kinds, seed % 2, seed % 4 == 1);
}

static void random_tree_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)k;
    uint64_t s = ((uint64_t)v + 1) * 11;
    vt_scene_random_state(m, d, &s);
    random_loads(m, d, &s); /* applied loads too */
    d->time = 0.4;
}

/* every rate driven: the inward pass alone, against the dense solve; chains of n = 1, 14, 27, 40 */
static vt_model *joint_driven_chain(int v)
{
    vt_model *m;
    assert_ok(vt_scene_chain(&m, 1 + 13 * v, VT_CHAIN_JOINT_DRIVEN));
    return m;
}

static void joint_driven_chain_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)v, (void)k;
    vt_test_chain_state(m, d, 0);
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = 0.1 * c;
    d->xfrc[6 * m->nbody + 1] = -2.0; /* a load on the last link */
}

static void prescribed_qdd(const vt_model *m, const vt_data *dr, const vt_data *dd, int v)
{
    (void)dd, (void)v;
    for (int k = 0; k < m->nv; k++) { /* and q̈ is the prescribed one */
        double q, qd, qdd;
        vt_scene_chain_state(k, &q, &qd, &qdd);
        assert_near(dr->qdd[k], qdd, 1e-15);
    }
}

/* a random tree of scalar joints (seed 5, 12 bodies), every rate driven */
static vt_model *joint_driven_tree(int v)
{
    (void)v;
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, 5, 12, VT_SCENE_SCALAR_JOINTS));
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, 5, 12, VT_SCENE_SCALAR_JOINTS));
    for (int c = 0; c < probe->nv; c++) {
        const int i = probe->dof_body[c];
        vt_test_add_joint_drive(b, i, c - probe->body_vadr[i], vt_function_sine(0.2, 0.5, 1.0 + c, 0.1 * c));
    }
    vt_model *m = vt_test_build(b);
    vt_model_free(probe);
    return m;
}

static void joint_driven_tree_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)v, (void)k;
    uint64_t s = 3;
    vt_scene_random_state(m, d, &s);
    d->time = 0.7;
}

/* the paper's scenes: the double link, the chain of 12 links driven at its tip */
static vt_model *double_link(int v)
{
    (void)v;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 1));
    return m;
}

static void double_link_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)m, (void)v, (void)k;
    d->q[0] = -0.7;
    d->qd[0] = -1.5;
}

static vt_model *tip_driven_chain(int v)
{
    (void)v;
    vt_model *m;
    assert_ok(vt_scene_chain(&m, 12, VT_CHAIN_TIP_DRIVE));
    return m;
}

static void chain_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)v, (void)k;
    vt_test_chain_state(m, d, 0);
}

/* square Φ_q: the four-bar built both ways (v = 1: RUSR), through five crank angles k */
static vt_model *fourbar(int v)
{
    vt_model *m;
    const vt_function crank = vt_function_sine(0.3, 1.0, 2.0, 0.0);
    assert_ok(v ? vt_scene_fourbar_rusr(&m, crank) : vt_scene_fourbar(&m, crank));
    assert_int_equal(m->nc, m->nv);
    return m;
}

static void fourbar_state(const vt_model *m, vt_data *d, int v, int k)
{
    const double th = 0.3 + 1.1 * k, w = 1.0 - 0.4 * k;
    assert_int_equal(v ? vt_scene_fourbar_rusr_assemble(m, d, th, w, NULL, NULL) : vt_scene_fourbar_assemble(m, d, th, w, NULL, NULL),
                     0);
    /* applied loads: a torque on every rate (the coupler's act between two moving bodies) and a
     * force on the coupler */
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = 0.7 - 0.3 * c;
    d->xfrc[6 * 2 + 2] = -3.0;
}

/* planar pins (2 rows each): the four-bar (v = 0) and the slider-crank (1), square with the crank
 * driven, and without the drive (the loop moving freely) by articulated bodies */
static vt_model *planar_loop(int v)
{
    vt_model *m;
    const vt_function crank = vt_function_sine(0.3, 1.0, 2.0, 0.0);
    assert_ok(v ? vt_scene_slider_crank(&m, crank, 1) : vt_scene_fourbar_pin(&m, crank));
    return m;
}

static vt_model *planar_loop_undriven(int v)
{
    vt_model *m, *md = planar_loop(v);
    assert_ok(vt_model_without_drives(&m, md));
    vt_model_free(md);
    return m;
}

static void planar_loop_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)k;
    assert_int_equal(v ? vt_scene_slider_crank_assemble(m, d, 0.9, 1.3) : vt_scene_fourbar_planar_assemble(m, d, 0.9, 1.3), 0);
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = 0.4 - 0.3 * c;
}

/* fewer rows than rates, no base body (the articulated path), every other joint kind: random
 * trees (seeds 1..8) with joint drives, a point drive, an orientation drive (absolute, or relative
 * to another body or to its joint's parent) and a spherical cut joint, loads on every body and rate */
static vt_model *partly_driven_tree(int v)
{
    vt_model *m = vt_test_partly_driven_tree((uint64_t)v + 1, VT_SCENE_NO_BASE, 0);
    int joint_rows = 0; /* joint drives among other rows: their rates known, their efforts from
                         * the subtrees' wrenches (vt_test_both: against the dense path's λ and reactions) */
    for (int r = 0; r < m->nc; r++) joint_rows += m->con_kind[r] == VT_ROW_JOINT;
    assert_true(joint_rows > 0 && joint_rows < m->nc);
    /* the articulated route itself: random poses whose estimate falls below √rcond_warn
     * would have the maximal route solve them (vt_maximal_wanted) */
    m->rcond_warn = m->rcond_min;
    return m;
}

static void partly_driven_tree_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)k;
    uint64_t s = ((uint64_t)v + 1) * 7;
    vt_scene_random_state(m, d, &s);
    random_loads(m, d, &s);
    d->time = 0.3;
}

/* point drives on five points of four bodies, in an order that revisits points (the recursive
 * Φ_q keeps each point's Jacobian columns for the drives on it, four points at a time): the
 * tip's x, y and z, two points of the tip's body, and points further in, one after another
 * and back; Φ_q and every output against the dense path (Φ_q = Φ_x S). Seeds 1..12, those whose
 * tree is deep enough (NULL for the others; at least 4 must be). */
static vt_model *shared_points_tree(int v)
{
    static const struct { int back, pt, comp; } rows[] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 0},
                                                          {0, 4, 1}, {0, 0, 2}, {1, 1, 0}};
    static const double pts[5][3] = {{0.2, 0.0, 0.05}, {0.1, -0.1, 0.0}, {-0.05, 0.15, 0.1}, {0.0, 0.0, 0.2}, {-0.2, 0.1, 0.0}};
    const uint64_t seed = (uint64_t)v + 1;
    const int n = 14;
    vt_model *probe, *m;
    assert_ok(vt_scene_random_tree(&probe, seed, n, VT_SCENE_NO_BASE));
    int line[4], tip = 1; /* the body with the most rates on its path, and three bodies up it */
    for (int i = 2; i <= n; i++)
        if (probe->body_pathnum[i] > probe->body_pathnum[tip]) tip = i;
    line[0] = tip;
    for (int k = 1; k < 4; k++) line[k] = line[k - 1] ? probe->body_parent[line[k - 1]] : 0;
    const int deep = line[3] > 0 && probe->body_pathnum[line[3]] >= 2 && probe->body_pathnum[tip] >= 9;
    vt_model_free(probe);
    if (!deep) return NULL;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, seed, n, VT_SCENE_NO_BASE));
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        vt_drive_def pd = vt_default_drive_def();
        pd.type = VT_DRIVE_POINT;
        pd.body = line[rows[k].back];
        pd.index = rows[k].comp;
        memcpy(pd.point, pts[rows[k].pt], sizeof pd.point);
        pd.f = vt_function_sine(0.05 * (double)k, 0.2, 1.5, 0.1 * (double)k);
        assert_true(vt_builder_add_drive(b, &pd) >= 0);
    }
    m = vt_test_build(b);
    /* the articulated route itself: random poses whose estimate falls below √rcond_warn
     * would be handed to the dense stages (vt_maximal_wanted) */
    m->rcond_warn = m->rcond_min;
    return m;
}

static void shared_points_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)k;
    uint64_t s = ((uint64_t)v + 1) * 11;
    vt_scene_random_state(m, d, &s);
}

/* a coupling of two coordinates (the general route: M* and Q formed, vt_solve) against the dense
 * path, on random trees (seeds 2..6) with a joint drive and loads */
static vt_model *coupled(int v)
{
    return coupled_tree((uint64_t)v + 2);
}

static void coupled_state(const vt_model *m, vt_data *d, int v, int k)
{
    (void)k;
    uint64_t s = ((uint64_t)v + 2) * 3;
    vt_scene_random_state(m, d, &s);
    for (int c = 0; c < m->nv; c++) d->qfrc[c] = vt_rand_uniform(&s, -1, 1);
    d->time = 0.3;
}

static void coupling_effort_agrees(const vt_model *m, const vt_data *dr, const vt_data *dd, int v)
{
    (void)m, (void)v;
    vt_test_compare(dr->coupling_effort, dd->coupling_effort, 1, 1e-12, "coupling_effort");
}

/* One row: `models` scenes (build(v), v = 0 .. models − 1; NULL: a seed the row passes over, at
 * least min_built of them built), `states` instants of each (set(m, d, v, k): q, q̇, loads, time,
 * into fresh data, then data reused from state to state). At every instant vt_test_both (every
 * output and intermediate against the dense path), then what the row holds the paths to:
 * m->joint_driven (−1: not held), the dense path's route and the recursive one's (VT_ROUTE_NONE:
 * not held), the recursive path's fallback flags (−1: not held), and check (NULL: nothing more). */
typedef struct {
    const char *name;
    vt_model *(*build)(int v);
    void (*set)(const vt_model *m, vt_data *d, int v, int k);
    int models, states, min_built, joint_driven;
    vt_route dense, recursive;
    int fallback;
    void (*check)(const vt_model *m, const vt_data *dr, const vt_data *dd, int v);
} route_case;

#define ANY VT_ROUTE_NONE
#define FREE_RATES VT_ROUTE_FREE_RATES
#define SQUARE VT_ROUTE_SQUARE
#define SCHUR VT_ROUTE_SCHUR
#define ARTICULATED VT_ROUTE_ARTICULATED
#define INWARD VT_ROUTE_JOINT_DRIVEN
static const route_case route_table[] = {
    /* name                       build                 set                       models states built
     *                                                                            joint_driven dense recursive fallback check */
    {"random trees",              random_tree,          random_tree_state,        18, 1, 18, 0, ANY, ANY, -1, NULL},
    /* every rate joint-driven: the dense path's square Φ_q, the recursive inward pass alone */
    {"joint-driven chains",       joint_driven_chain,   joint_driven_chain_state, 4, 1, 4, 1, SQUARE, INWARD, 0, prescribed_qdd},
    {"joint-driven tree",         joint_driven_tree,    joint_driven_tree_state,  1, 1, 1, 1, SQUARE, INWARD, -1, NULL},
    /* the paper's scenes: the double link (rows of joint drives, a rate free), the tip's one row */
    {"double link",               double_link,          double_link_state,        1, 1, 1, 0, FREE_RATES, ARTICULATED, 0, NULL},
    {"tip-driven chain",          tip_driven_chain,     chain_state,              1, 1, 1, 0, SCHUR, ARTICULATED, 0, NULL},
    {"four-bars (square)",        fourbar,              fourbar_state,            2, 5, 2, 0, SQUARE, SQUARE, 0, NULL},
    {"planar loops, driven",      planar_loop,          planar_loop_state,        2, 1, 2, 0, SQUARE, SQUARE, 0, NULL},
    {"planar loops, undriven",    planar_loop_undriven, planar_loop_state,        2, 1, 2, 0, SCHUR, ARTICULATED, 0, NULL},
    {"partly driven trees",       partly_driven_tree,   partly_driven_tree_state, 8, 1, 8, 0, SCHUR, ARTICULATED, 0, NULL},
    {"point drives share points", shared_points_tree,   shared_points_state,      12, 1, 4, 0, SCHUR, ARTICULATED, 0, NULL},
    /* the general route (M* and Q formed, vt_solve's Schur route) */
    {"coupled trees",             coupled,              coupled_state,            5, 1, 5, 0, SCHUR, SCHUR, 0, coupling_effort_agrees},
};
#undef ANY
#undef FREE_RATES
#undef SQUARE
#undef SCHUR
#undef ARTICULATED
#undef INWARD

static void test_route(void **state)
{
    const route_case *row = *state;
    int built = 0;
    for (int v = 0; v < row->models; v++) {
        vt_model *m = row->build(v);
        if (!m) continue;
        built++;
        if (row->joint_driven >= 0) assert_int_equal(m->joint_driven, row->joint_driven);
        vt_data *dr, *dd;
        assert_ok(vt_data_create(&dr, m));
        assert_ok(vt_data_create(&dd, m));
        for (int k = 0; k < row->states; k++) {
            row->set(m, dd, v, k);
            vt_test_copy_inputs(m, dr, dd);
            vt_test_both(m, dr, dd);
            if (row->recursive != VT_ROUTE_NONE) assert_int_equal(dr->route, row->recursive);
            if (row->dense != VT_ROUTE_NONE) assert_int_equal(dd->route, row->dense);
            if (row->fallback >= 0) assert_int_equal(dr->fallback, row->fallback);
            if (row->check) row->check(m, dr, dd, v);
        }
        vt_data_free(dr);
        vt_data_free(dd);
        vt_model_free(m);
    }
    print_message("%s: %d scenes of %d\n", row->name, built, row->models);
    assert_true(built >= row->min_built);
}

/* dependent rows (one joint driven twice), square (2 rods) and with a free rate (3 rods): the
 * square and articulated shortcuts hand the ill-conditioned system to the general path, which
 * names the rows, as the dense path does, and leaves q̈ and λ as they were */
static void test_dependent(void **state)
{
    (void)state;
    for (int nrod = 2; nrod <= 3; nrod++) {
        vt_builder *b;
        vt_model *m;
        vt_data *d;
        assert_ok(vt_builder_create(&b, NULL));
        vt_test_add_rods(b, nrod, 1.0, (const double[3]){1.0, 1.0, 1.0});
        for (int k = 0; k < 2; k++)
            vt_test_add_joint_drive(b, 1, 0, vt_function_sine(0.2, 1.0, 2.0, 0.0));
        m = vt_test_build(b);
        assert_ok(vt_data_create(&d, m));
        for (int recursive = 0; recursive < 2; recursive++) {
            memset(d->q, 0, (size_t)m->nq * sizeof(double));
            d->qdd[0] = 42.0;
            d->lambda[1] = 7.0;
            const vt_status st = recursive ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
            assert_int_equal(st, VT_ERR_DEPENDENT_CONSTRAINTS);
            assert_non_null(strstr(d->message, "rank 1 of 2"));
            assert_near(d->qdd[0], 42.0, 0.0);
            assert_near(d->lambda[1], 7.0, 0.0);
            assert_int_equal(d->route, VT_ROUTE_NONE); /* no route solved it */
            /* the recursive shortcut (square for two rods, articulated for three) gave way on its
             * condition: the dependent rows make Φ_q (and S) singular; the general route's refusal
             * is the dense stages' (VT_FALLBACK_COMPOSITE_ROUNDOFF beside the shortcut's flag) */
            if (recursive)
                assert_int_equal(d->fallback, VT_FALLBACK_COMPOSITE_ROUNDOFF | (nrod == 2 ? VT_FALLBACK_SQUARE_CONDITION
                                                                                          : VT_FALLBACK_ARTICULATED_CONDITION));
            else
                assert_int_equal(d->fallback, 0);
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* A row that only a joint-driven rate moves: body 1 on a universal joint (axis1 z, axis2 x on
 * the body), its first rate joint-driven, and a point drive on its y at a point on the second
 * axis, which that axis turns about itself (an exact zero on rate 1, round-off once rotated).
 * A second link on it gives more rates than rows. Both rows fix rate 0: dependent, on both
 * paths. The articulated route takes rate 0 as known
 * and sees the point drive on rate 1 alone, a round-off entry: it once solved that (q̈ of 1e17). */
static void test_row_on_known_rates(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_UNIVERSAL;
    body.axis1[0] = 0.0, body.axis1[1] = 0.0, body.axis1[2] = 1.0;
    body.axis2[0] = 1.0, body.axis2[1] = 0.0, body.axis2[2] = 0.0;
    body.joint_child[0] = -0.3, body.joint_child[1] = 0.4; /* the centre of mass off the axes */
    body.mass = 2.0;
    body.inertia[0] = body.inertia[4] = body.inertia[8] = 0.5;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    body.parent = 1; /* a second link: more rates than rows, the articulated route */
    body.joint_parent[0] = 0.5, body.joint_parent[1] = -0.2;
    assert_int_equal(vt_builder_add_body(b, &body), 2);
    vt_drive_def jd = vt_default_drive_def();
    jd.body = 1;
    jd.index = 0;
    jd.f = vt_function_polynomial(3, (const double[3]){0.7, 0.4, 0.3});
    assert_int_equal(vt_builder_add_drive(b, &jd), 0);
    vt_drive_def pd = vt_default_drive_def();
    pd.type = VT_DRIVE_POINT;
    pd.body = 1;
    pd.index = 1;
    pd.point[0] = -0.3 + 1.3, pd.point[1] = 0.4; /* the joint point plus 1.3 along axis2 (body x) */
    pd.f = vt_function_polynomial(3, (const double[3]){0.2, 0.1, 0.0});
    assert_int_equal(vt_builder_add_drive(b, &pd), 1);
    vt_model *m = vt_test_build(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    int roundoff = 0;
    for (int k = 0; k < 20; k++) {
        for (int c = 0; c < 4; c++) d->q[c] = 0.7 + 0.37 * k - 0.9 * c, d->qd[c] = 0.4 - 0.3 * c;
        d->time = 0.1 * k;
        for (int recursive = 0; recursive < 2; recursive++) {
            const vt_status st = recursive ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
            if (st != VT_ERR_DEPENDENT_CONSTRAINTS)
                fail_msg("state %d, %s: %s (%s), q̈ %g %g", k, recursive ? "recursive" : "dense", vt_status_string(st),
                         d->message, d->qdd[0], d->qdd[1]);
        }
        roundoff += d->Phiq[1 + 1 * m->nc] != 0.0; /* the point drive's entry on rate 1 */
    }
    print_message("the point drive's round-off entry on rate 1 was non-zero at %d of 20 states\n", roundoff);
    assert_true(roundoff > 0); /* else the states test nothing */
    vt_data_free(d);
    vt_model_free(m);
}

/* The fused outward pass of vt_inverse_dynamics_motion (a revolute body by its own code, other
 * joints by the general code body by body) leaves every kinematic output of the data as
 * vt_kinematics, the general code in its separate loops, computes it: on all-revolute trees
 * (every body by the revolute code, non-unit axes, turned joint frames) and on trees of every
 * kind but base */
static void test_fused_kinematics(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 8; seed++) {
        vt_model *m;
        vt_data *d, *dk;
        const unsigned kinds = seed <= 4 ? (1u << VT_JOINT_REVOLUTE) : VT_SCENE_WITH_FREE;
        assert_ok(vt_scene_random_tree(&m, seed, 5 + (int)seed, kinds));
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&dk, m));
        uint64_t s = seed * 7;
        vt_scene_random_state(m, d, &s);
        for (int c = 0; c < m->nv; c++) d->qdd[c] = vt_rand_uniform(&s, -3, 3);
        memcpy(dk->q, d->q, (size_t)m->nq * sizeof(double));
        memcpy(dk->qd, d->qd, (size_t)m->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_motion(m, d));
        assert_ok(vt_kinematics(m, dk));
        const int nb = m->nbody + 1;
        vt_test_compare(d->x, dk->x, m->nx, 1e-14, "x");
        vt_test_compare(d->A, dk->A, 9 * nb, 1e-14, "A");
        vt_test_compare(d->xd, dk->xd, m->nx, 1e-14, "xd");
        vt_test_compare(d->omega, dk->omega, 3 * nb, 1e-14, "omega");
        vt_test_compare(d->twist, dk->twist, 6 * m->nv, 1e-14, "twist");
        vt_test_compare(d->jaxis, dk->jaxis, 9 * nb, 1e-14, "jaxis");
        vt_test_compare(d->jsij, dk->jsij, 3 * nb, 1e-14, "jsij");
        vt_test_compare(d->jd, dk->jd, 3 * nb, 1e-14, "jd");
        vt_test_compare(d->jpoint, dk->jpoint, 3 * nb, 1e-14, "jpoint");
        vt_test_compare(d->xrel, dk->xrel, 6 * nb, 1e-14, "xrel");
        vt_test_compare(d->origin, dk->origin, 3, 1e-14, "origin");
        for (int i = 1; i <= m->nbody; i++) { /* the rows past the joint's own axes are 0 (types.h) */
            const int jt = m->body_joint[i];
            const int nax = jt == VT_JOINT_UNIVERSAL ? 2 : jt == VT_JOINT_SPHERICAL || jt == VT_JOINT_FREE ? 3 : 1;
            for (int k = 3 * nax; k < 9; k++) assert_true(d->jaxis[9 * i + k] == 0.0);
        }
        vt_data_free(d);
        vt_data_free(dk);
        vt_model_free(m);
    }
}

/* The fused passes (every rate joint-driven, or the motion given, no base body) check their
 * results once after both loops: finite inputs whose results overflow are refused with
 * VT_ERR_NONFINITE, a message and no route, the inputs left as they were. (a) the joint-driven
 * chain and (b) the motion of trees with free joints under 1.5e308 N on a body and its parent
 * (the subtree sum overflows the reactions, or a free joint's total wrench); (c) the chain's motion with every q̈ at 1e308 (α and ẍ overflow
 * down the chain). */
static void test_fused_overflow(void **state)
{
    (void)state;
    for (int c = 0; c < 4; c++) {
        vt_model *m;
        vt_data *d;
        if (c == 0) assert_ok(vt_scene_chain(&m, 6, VT_CHAIN_JOINT_DRIVEN));
        else if (c < 3) assert_ok(vt_scene_random_tree(&m, (uint64_t)c + 4, 7, VT_SCENE_WITH_FREE));
        else assert_ok(vt_scene_chain(&m, 6, VT_CHAIN_FREE));
        assert_ok(vt_data_create(&d, m));
        uint64_t s = 11u + (uint64_t)c;
        if (c == 0 || c == 3) vt_test_chain_state(m, d, 1);
        else vt_scene_random_state(m, d, &s);
        d->time = 0.3;
        for (int k = 0; k < m->nv; k++) d->qdd[k] = c == 3 ? 1e308 : vt_rand_uniform(&s, -2, 2);
        if (c < 3) { /* the last body and its parent */
            const int j = m->body_parent[m->nbody];
            assert_true(j > 0);
            d->xfrc[6 * m->nbody + 1] = d->xfrc[6 * j + 1] = 1.5e308;
        }
        double *in = malloc(((size_t)m->nq + 2 * (size_t)m->nv + 6 * ((size_t)m->nbody + 1)) * sizeof(double));
        double *k0 = in, *k1 = k0 + m->nq, *k2 = k1 + m->nv, *k3 = k2 + m->nv;
        memcpy(k0, d->q, (size_t)m->nq * sizeof(double));
        memcpy(k1, d->qd, (size_t)m->nv * sizeof(double));
        memcpy(k2, d->qdd, (size_t)m->nv * sizeof(double));
        memcpy(k3, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        d->message[0] = '\0';
        const vt_status st = c == 0 ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics_motion(m, d);
        if (st != VT_ERR_NONFINITE) fail_msg("case %d: status %d (%s)", c, (int)st, d->message);
        print_message("case %d: %s\n", c, d->message);
        assert_non_null(strstr(d->message, "overflow"));
        assert_int_equal(d->route, VT_ROUTE_NONE);
        assert_memory_equal(k0, d->q, (size_t)m->nq * sizeof(double));
        assert_memory_equal(k1, d->qd, (size_t)m->nv * sizeof(double));
        if (c > 0) assert_memory_equal(k2, d->qdd, (size_t)m->nv * sizeof(double));
        assert_memory_equal(k3, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        free(in);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* The motion given for every rate of a tree (vt_inverse_dynamics_motion), held to two things it
 * does not compute itself: the efforts equal M* q̈ − Q from the dense stages (2), and applied as
 * generalized forces to the same tree without drives, the dense path's forward solve gives back
 * the given q̈ and the same reactions (the actuation is not reaction either way) */
static void test_motion(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 16; seed++) { /* 11..16: with free joints */
        vt_model *m;
        vt_data *d, *ds, *df;
        assert_ok(vt_scene_random_tree(&m, seed, 6 + (int)seed, seed > 10 ? VT_SCENE_WITH_FREE : VT_SCENE_NO_BASE));
        assert_int_equal(m->ndrive + m->ncut, 0);
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&ds, m));
        assert_ok(vt_data_create(&df, m));
        uint64_t s = seed * 5;
        vt_scene_random_state(m, d, &s);
        for (int c = 0; c < m->nv; c++) {
            d->qdd[c] = vt_rand_uniform(&s, -3, 3);
            d->qfrc[c] = vt_rand_uniform(&s, -1, 1);
        }
        for (int i = 1; i <= m->nbody; i++)
            for (int k = 0; k < 6; k++) d->xfrc[6 * i + k] = vt_rand_uniform(&s, -2, 2);
        const size_t nq = (size_t)m->nq * sizeof(double), nv = (size_t)m->nv * sizeof(double);
        double *qdd = malloc(nv);
        memcpy(qdd, d->qdd, nv);
        assert_ok(vt_inverse_dynamics_motion(m, d));
        assert_int_equal(d->route, VT_ROUTE_MOTION);
        assert_memory_equal(d->qdd, qdd, nv); /* an input: not changed */
        /* (2) with the efforts as the generalized force: τ = M* q̈ − Q, M* and Q from the dense stages */
        memcpy(ds->q, d->q, nq);
        memcpy(ds->qd, d->qd, nv);
        memcpy(ds->qfrc, d->qfrc, nv);
        memcpy(ds->xfrc, d->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        assert_ok(vt_kinematics(m, ds));
        assert_ok(vt_mass_matrix(m, ds));
        assert_ok(vt_forces(m, ds));
        const double scale = 1.0 + vt_test_maxabs(d->qfrc_drive, m->nv);
        for (int a = 0; a < m->nv; a++) {
            double t = -ds->Q[a];
            for (int b = 0; b < m->nv; b++) t += ds->Mstar[a + (size_t)b * (size_t)m->nv] * qdd[b];
            assert_near(d->qfrc_drive[a], t, 1e-11 * scale);
        }
        /* forward: the same state, the efforts added to qfrc, q̈ solved by the dense path */
        memcpy(df->q, d->q, nq);
        memcpy(df->qd, d->qd, nv);
        memcpy(df->xfrc, ds->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        for (int c = 0; c < m->nv; c++) df->qfrc[c] = d->qfrc[c] + d->qfrc_drive[c];
        assert_ok(vt_inverse_dynamics(m, df));
        vt_test_compare(df->qdd, qdd, m->nv, 1e-9, "forward q̈");
        const int nb3 = 3 * (m->nbody + 1);
        vt_test_compare(d->jnt_force, df->jnt_force, nb3, 1e-10, "jnt_force");
        vt_test_compare(d->jnt_moment, df->jnt_moment, nb3, 1e-10, "jnt_moment");
        vt_test_compare(d->jnt_force_body, df->jnt_force_body, nb3, 1e-10, "jnt_force_body");
        vt_test_compare(d->jnt_moment_body, df->jnt_moment_body, nb3, 1e-10, "jnt_moment_body");
        vt_test_compare(d->xdd, df->xdd, m->nx, 1e-9, "xdd");
        free(qdd);
        vt_data_free(d);
        vt_data_free(ds);
        vt_data_free(df);
        vt_model_free(m);
    }
}

/* vt_motion_add_loads against the instant itself: the given motion with loads L in xfrc (and
 * random qfrc) equals the instant without L plus L added afterwards, on random trees of every
 * joint kind but the base body's (free joints among them) and on the quadruped; the limits'
 * excess follows the efforts; refused where no tree instant came before or the model has loops */
static void test_motion_add_loads(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 13; seed++) {
        vt_model *m;
        vt_data *d, *e;
        if (seed == 13) assert_ok(vt_scene_quadruped(&m));
        else assert_ok(vt_scene_random_tree(&m, seed, 5 + (int)seed, seed > 6 ? VT_SCENE_WITH_FREE : VT_SCENE_NO_BASE));
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&e, m));
        uint64_t s = seed * 7;
        vt_scene_random_state(m, d, &s);
        for (int c = 0; c < m->nv; c++) {
            d->qdd[c] = vt_rand_uniform(&s, -3, 3);
            d->qfrc[c] = vt_rand_uniform(&s, -1, 1);
        }
        const size_t nx = 6 * ((size_t)m->nbody + 1);
        double *L = calloc(nx, sizeof(double));
        for (int i = 1; i <= m->nbody; i++)
            for (int k = 0; k < 6; k++) L[6 * i + k] = vt_rand_uniform(&s, -5, 5);
        vt_test_copy_inputs(m, e, d);
        memcpy(e->qdd, d->qdd, (size_t)m->nv * sizeof(double));
        for (size_t k = 0; k < nx; k++) e->xfrc[k] = d->xfrc[k] + L[k];
        assert_ok(vt_inverse_dynamics_motion(m, e)); /* the reference: the loads in the instant */
        assert_int_equal(vt_motion_add_loads(m, d, L), VT_ERR_BAD_OPTION); /* no instant yet */
        assert_ok(vt_inverse_dynamics_motion(m, d));
        assert_ok(vt_motion_add_loads(m, d, L));
        const int nb3 = 3 * (m->nbody + 1);
        vt_test_compare(d->qfrc_drive, e->qfrc_drive, m->nv, 1e-12, "efforts");
        vt_test_compare(d->jnt_force, e->jnt_force, nb3, 1e-12, "jnt_force");
        vt_test_compare(d->jnt_moment, e->jnt_moment, nb3, 1e-12, "jnt_moment");
        vt_test_compare(d->jnt_force_body, e->jnt_force_body, nb3, 1e-12, "jnt_force_body");
        vt_test_compare(d->jnt_moment_body, e->jnt_moment_body, nb3, 1e-12, "jnt_moment_body");
        vt_test_compare(d->jnt_force_total, e->jnt_force_total, nb3, 1e-12, "jnt_force_total");
        vt_test_compare(d->jnt_moment_total, e->jnt_moment_total, nb3, 1e-12, "jnt_moment_total");
        vt_test_compare(d->jnt_force_total_body, e->jnt_force_total_body, nb3, 1e-12, "jnt_force_total_body");
        vt_test_compare(d->jnt_moment_total_body, e->jnt_moment_total_body, nb3, 1e-12, "jnt_moment_total_body");
        vt_test_compare(d->limit_excess, e->limit_excess, 3 * m->nv, 1e-12, "limit_excess");
        assert_int_equal(d->nlimit, e->nlimit);
        free(L);
        vt_data_free(d);
        vt_data_free(e);
        vt_model_free(m);
    }
    vt_model *m; /* a loop: its multipliers change with the loads too */
    vt_data *d;
    assert_ok(vt_scene_fourbar(&m, vt_function_constant(0.0)));
    assert_ok(vt_data_create(&d, m));
    double *L = calloc(6 * ((size_t)m->nbody + 1), sizeof(double));
    assert_int_equal(vt_motion_add_loads(m, d, L), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(d->message, "vt_motion_add_loads"));
    free(L);
    vt_data_free(d);
    vt_model_free(m);
}

/* A loop's or a coupling's motion given through the data: the joint-driven rates' q̈ from
 * d->qdd. The reference is vt_inverse_dynamics at the time t whose drive function gives the
 * same q, q̇ and q̈ (f''(t) = the given q̈); the given motion is evaluated at another time, where
 * the function's f'' differs, with every other rate's q̈ garbage: the outputs must agree. */
static void motion_matches(const vt_model *m, const vt_data *ref, double t_other, int overflow)
{
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    memcpy(d->q, ref->q, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, ref->qd, (size_t)m->nv * sizeof(double));
    memcpy(d->qfrc, ref->qfrc, (size_t)m->nv * sizeof(double));
    memcpy(d->xfrc, ref->xfrc, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    for (int c = 0; c < m->nv; c++) d->qdd[c] = 1e3 * (c + 1); /* not given: not used */
    for (int k = 0; k < m->ndrive; k++)
        if (m->drive[k].type == VT_DRIVE_JOINT) {
            const int c = m->con_dof[m->drive_row[k]];
            d->qdd[c] = ref->qdd[c];
        }
    d->time = t_other;
    assert_ok(vt_inverse_dynamics_motion(m, d));
    assert_int_equal(d->route, ref->route);
    const int nb3 = 3 * (m->nbody + 1);
    vt_test_compare(d->qdd, ref->qdd, m->nv, 1e-12, "q̈");
    vt_test_compare(d->drive_effort, ref->drive_effort, m->ndrive, 1e-12, "drive_effort");
    vt_test_compare(d->coupling_effort, ref->coupling_effort, m->ncoupling, 1e-12, "coupling_effort");
    vt_test_compare(d->lambda, ref->lambda, m->nc, 1e-12, "λ");
    vt_test_compare(d->jnt_force, ref->jnt_force, nb3, 1e-12, "jnt_force");
    vt_test_compare(d->jnt_moment, ref->jnt_moment, nb3, 1e-12, "jnt_moment");
    vt_test_compare(d->cut_force, ref->cut_force, 3 * m->ncut, 1e-12, "cut_force");
    /* a failed call leaves the given q̈ as it was: refused by the forces, or (overflow) the load
     * on the last body overflowing the reactions after the solve has written q̈ */
    double *given = malloc((size_t)m->nv * sizeof(double));
    memcpy(given, d->qdd, (size_t)m->nv * sizeof(double));
    for (int k = 0; k < 1 + overflow; k++) {
        memset(d->xfrc, 0, 6 * ((size_t)m->nbody + 1) * sizeof(double));
        d->xfrc[6 * m->nbody + 1] = k ? 1.7e308 : NAN;
        assert_int_equal(vt_inverse_dynamics_motion(m, d), VT_ERR_NONFINITE);
        assert_non_null(strstr(d->message, k ? "vt_reactions" : "vt_forces"));
        assert_memory_equal(d->qdd, given, (size_t)m->nv * sizeof(double));
    }
    free(given);
    vt_data_free(d);
}

static void test_motion_loops(void **state)
{
    (void)state;
    const vt_function crank = vt_function_sine(0.4, 0.9, 2.5, 0.3);
    for (int rusr = 0; rusr <= 1; rusr++)
        for (double t = 0.1; t < 2.6; t += 0.6) {
            vt_model *m;
            vt_data *ref;
            assert_ok(rusr ? vt_scene_fourbar_rusr(&m, crank) : vt_scene_fourbar(&m, crank));
            assert_ok(vt_data_create(&ref, m));
            double f[3];
            assert_ok(vt_function_eval(f, &crank, t));
            const int closed = rusr ? vt_scene_fourbar_rusr_assemble(m, ref, f[0], f[1], NULL, NULL)
                                    : vt_scene_fourbar_assemble(m, ref, f[0], f[1], NULL, NULL);
            assert_int_equal(closed, 0);
            ref->time = t;
            ref->xfrc[6 * 2 + 1] = 0.7; /* a load on the coupler */
            assert_ok(vt_inverse_dynamics(m, ref));
            motion_matches(m, ref, t + 0.77, !rusr); /* the rocker's load overflows the reactions */
            vt_data_free(ref);
            vt_model_free(m);
        }
    for (uint64_t seed = 2; seed <= 6; seed++) { /* a coupling on a random tree (test_coupled's) */
        vt_model *m = coupled_tree(seed);
        vt_data *ref;
        assert_ok(vt_data_create(&ref, m));
        uint64_t s = seed * 7;
        vt_scene_random_state(m, ref, &s);
        for (int cc = 0; cc < m->nv; cc++) ref->qfrc[cc] = vt_rand_uniform(&s, -1, 1);
        ref->time = 0.3;
        assert_ok(vt_inverse_dynamics(m, ref));
        motion_matches(m, ref, 1.9, 0);
        vt_data_free(ref);
        vt_model_free(m);
    }
}

/* what vt_inverse_dynamics_motion refuses: loops, base bodies, non-finite q̈; the inputs are
 * left as they were */
static void test_motion_refused(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_bricard(&m, VT_JOINT_UNIVERSAL, 0, vt_function_constant(0.0))); /* a loop, no drive */
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_inverse_dynamics_motion(m, d), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(d->message, "no joint drive"));
    assert_int_equal(d->route, VT_ROUTE_NONE);
    vt_data_free(d);
    vt_model_free(m);
    { /* a coupling (a URDF mimic joint's) and no drive: the message says what is missing (a drive
       * on the coupling's leader, named) and the way to load the file as Pinocchio does */
        vt_builder *b;
        assert_ok(vt_builder_create(&b, NULL));
        vt_body_def bd = vt_default_body_def();
        bd.name = "a";
        bd.joint_name = "shoulder";
        assert_int_equal(vt_builder_add_body(b, &bd), 1);
        bd.parent = 1;
        bd.joint_parent[0] = 1.0;
        bd.name = "b";
        bd.joint_name = "finger";
        assert_int_equal(vt_builder_add_body(b, &bd), 2);
        vt_coupling_def c = vt_default_coupling_def();
        assert_int_equal(vt_builder_add_coupling(b, &c), 0);
        m = vt_test_build(b);
        assert_ok(vt_data_create(&d, m));
        assert_int_equal(vt_inverse_dynamics_motion(m, d), VT_ERR_BAD_OPTION);
        static const char *const words[] = {"no joint drive", "leader", "\"finger\" follows \"shoulder\"",
                                            "vt_urdf_options.mimic = 0", "Pinocchio"};
        for (int k = 0; k < 5; k++)
            if (!strstr(d->message, words[k])) fail_msg("\"%s\" not in the message \"%s\"", words[k], d->message);
        vt_data_free(d);
        vt_model_free(m);
    }
    uint64_t seed = 1;
    for (;; seed++) { /* a random tree with a base body */
        assert_ok(vt_scene_random_tree(&m, seed, 6, VT_SCENE_ALL_JOINTS));
        int base = 0;
        for (int i = 1; i <= m->nbody; i++) base |= m->body_joint[i] == VT_JOINT_BASE;
        if (base) break;
        vt_model_free(m);
    }
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_inverse_dynamics_motion(m, d), VT_ERR_BAD_OPTION);
    assert_non_null(strstr(d->message, "base"));
    vt_data_free(d);
    vt_model_free(m);
    assert_ok(vt_scene_random_tree(&m, 3, 5, VT_SCENE_NO_BASE));
    assert_ok(vt_data_create(&d, m));
    d->qdd[2] = NAN;
    const double before = d->q[0];
    assert_int_equal(vt_inverse_dynamics_motion(m, d), VT_ERR_NONFINITE);
    assert_non_null(strstr(d->message, "qdd[2]"));
    assert_near(d->q[0], before, 0.0);
    vt_model *other;
    assert_ok(vt_scene_double_link(&other, 1));
    assert_int_equal(vt_inverse_dynamics_motion(other, d), VT_ERR_MODEL_MISMATCH);
    assert_int_equal(vt_inverse_dynamics_motion(NULL, d), VT_ERR_NULL);
    vt_model_free(other);
    vt_data_free(d);
    vt_model_free(m);
}

/* The fuzzer's finding fuzz/corpus/motion-euler-rates-overflow: one body on
 * a spherical joint, inertia DBL_MIN, q̈ = 1.5e308 on every rate, p = (½, ½, ½, ½) (A a cyclic
 * permutation: α = (1.5e308, 1.5e308, 1.5e308) in body axes stays finite, and so does every
 * wrench of a body this light). The Euler parameters' p̈ = ½ E^T α − ¼ |ω|² p sums p_1 α_1 + p_2 α_2 +
 * p_3 α_3 = 2.25e308: Inf. The given motion returned VT_OK with ẍ = Inf (nothing scanned p̈);
 * it must refuse with VT_ERR_NONFINITE and a message, and leave its inputs as they were. */
static void test_motion_euler_rates_overflow(void **state)
{
    (void)state;
    vt_builder *b;
    vt_model_def md = vt_default_model_def();
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def bd = vt_default_body_def();
    bd.joint = VT_JOINT_SPHERICAL;
    bd.mass = 1e-300;
    bd.inertia[0] = bd.inertia[4] = bd.inertia[8] = 2.2250738585072014e-308; /* DBL_MIN, as the fuzzer's */
    assert_int_equal(vt_builder_add_body(b, &bd), 1);
    vt_model *m = vt_test_build(b);
    assert_int_equal(m->nv, 3);
    assert_true(m->body_inertia[9] == bd.inertia[0]); /* accepted as given */
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    for (int k = 0; k < 4; k++) d->q[k] = 0.5;
    for (int k = 0; k < 3; k++) d->qd[k] = 0.25 * (k + 1), d->qdd[k] = 1.5e308;
    d->time = 0.3;
    const size_t nq = (size_t)m->nq * sizeof(double), nv = (size_t)m->nv * sizeof(double),
                 nf = 6 * ((size_t)m->nbody + 1) * sizeof(double);
    double q[4], qd[3], qdd[3], xfrc[12], qfrc[3];
    memcpy(q, d->q, nq);
    memcpy(qd, d->qd, nv);
    memcpy(qdd, d->qdd, nv);
    memcpy(xfrc, d->xfrc, nf);
    memcpy(qfrc, d->qfrc, nv);
    d->message[0] = '\0';
    const vt_status st = vt_inverse_dynamics_motion(m, d);
    if (st == VT_OK) { /* what the bug gave: name the entry that is not finite */
        for (int k = 0; k < m->nx; k++)
            if (!isfinite(d->xdd[k])) fail_msg("VT_OK with xdd[%d] = %g", k, d->xdd[k]);
        fail_msg("VT_OK (the Euler parameters' p̈ should overflow)");
    }
    assert_int_equal(st, VT_ERR_NONFINITE);
    print_message("%s\n", d->message);
    assert_true(d->message[0] != '\0');
    assert_non_null(strstr(d->message, "overflow"));
    assert_int_equal(d->route, VT_ROUTE_NONE); /* no route claims the outputs */
    assert_memory_equal(q, d->q, nq);
    assert_memory_equal(qd, d->qd, nv);
    assert_memory_equal(qdd, d->qdd, nv);
    assert_memory_equal(xfrc, d->xfrc, nf);
    assert_memory_equal(qfrc, d->qfrc, nv);
    assert_true(d->time == 0.3);
    /* the same model at q̈ 1e300: every output finite, VT_OK */
    for (int k = 0; k < 3; k++) d->qdd[k] = 1e300;
    assert_ok(vt_inverse_dynamics_motion(m, d));
    assert_int_equal(d->route, VT_ROUTE_MOTION);
    for (int k = 0; k < m->nx; k++) assert_true(isfinite(d->xdd[k]));
    for (int k = 0; k < 3 * (m->nbody + 1); k++) assert_true(isfinite(d->alpha[k]));
    vt_data_free(d);
    vt_model_free(m);
}

/* by hand, not the library's: y = A x (3x3 column-major), c = a × b */
static void mul3(double y[3], const double A[9], const double x[3])
{
    for (int r = 0; r < 3; r++) y[r] = A[r] * x[0] + A[r + 3] * x[1] + A[r + 6] * x[2];
}

static void cross3(double c[3], const double a[3], const double b[3])
{
    const double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(c, t, sizeof t);
}

/* The same floating tree with a free root and with the paper's base root: the base model's
 * forward dynamics (dense) under a wrench (f, n about the free joint's point P) applied through
 * its root's generalized forces, Q_r = f, Q_p = 2 E^T (n + (P − r) × f), against the free model:
 * its rates converted by hand (P = r + A c', Ṗ = ṙ + ω × s, P̈ = r̈ + α × s + ω × (ω × s),
 * ω = 2 E ṗ, α = 2 E p̈), its forward dynamics under (f, n) as its root's generalized forces
 * (dense and recursive), and vt_inverse_dynamics_motion at the converted q̈, whose root efforts
 * must be (f, n) and whose other efforts zero; the child joints' reactions agree throughout. */
static void test_free_vs_base(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        const double c[3] = {0.3, -0.2, 0.15};
        vt_model *mb = vt_test_floating_tree(seed, 4 + (int)seed, 0, c), *mf = vt_test_floating_tree(seed, 4 + (int)seed, 1, c);
        assert_int_equal(mf->nv, mb->nv - 1);
        assert_int_equal(mf->nc, 0);
        vt_data *db, *df, *dr, *dm;
        assert_ok(vt_data_create(&db, mb));
        assert_ok(vt_data_create(&df, mf));
        assert_ok(vt_data_create(&dr, mf));
        assert_ok(vt_data_create(&dm, mf));
        uint64_t s = seed * 13 + 5;
        vt_scene_random_state(mb, db, &s); /* base: r, p, ṙ, ṗ tangent */
        const int nvb = mb->nv, nvf = mf->nv, nqf = mf->nq;
        double f[3], n[3];
        for (int k = 0; k < 3; k++) f[k] = vt_rand_uniform(&s, -20, 20), n[k] = vt_rand_uniform(&s, -5, 5);
        for (int c2 = 7; c2 < nvb; c2++) db->qfrc[c2] = vt_rand_uniform(&s, -1, 1);
        /* the base's own generalized forces of the wrench */
        double A[9], E[12], sp[3], nc[3];
        const double *r = db->q, *p = db->q + 3;
        vt_euler_A(A, p);
        vt_euler_E(E, p);
        mul3(sp, A, c);
        cross3(nc, sp, f);
        for (int k = 0; k < 3; k++) nc[k] += n[k]; /* about the centre of mass: n + (P − r) × f */
        for (int k = 0; k < 3; k++) db->qfrc[k] = f[k];
        for (int k = 0; k < 4; k++) db->qfrc[3 + k] = 2.0 * (E[3 * k] * nc[0] + E[3 * k + 1] * nc[1] + E[3 * k + 2] * nc[2]);
        assert_ok(vt_inverse_dynamics(mb, db));
        /* the free model's state */
        double w[3], al[3], P[3], Pd[3], Pdd[3], t[3];
        for (int k = 0; k < 3; k++) {
            w[k] = al[k] = 0.0;
            for (int l = 0; l < 4; l++) {
                w[k] += 2.0 * E[k + 3 * l] * db->qd[3 + l];
                al[k] += 2.0 * E[k + 3 * l] * db->qdd[3 + l];
            }
        }
        cross3(t, w, sp);
        for (int k = 0; k < 3; k++) P[k] = r[k] + sp[k], Pd[k] = db->qd[k] + t[k];
        double u[3], u2[3];
        cross3(u, al, sp);
        cross3(u2, w, t);
        for (int k = 0; k < 3; k++) Pdd[k] = db->qdd[k] + u[k] + u2[k];
        memcpy(df->q, P, sizeof P);
        memcpy(df->q + 3, p, 4 * sizeof(double));
        memcpy(df->q + 7, db->q + 7, (size_t)(nqf - 7) * sizeof(double));
        memcpy(df->qd, Pd, sizeof Pd);
        memcpy(df->qd + 3, w, sizeof w);
        memcpy(df->qd + 6, db->qd + 7, (size_t)(nvf - 6) * sizeof(double));
        memcpy(df->qfrc, f, sizeof f);
        memcpy(df->qfrc + 3, n, sizeof n);
        memcpy(df->qfrc + 6, db->qfrc + 7, (size_t)(nvf - 6) * sizeof(double));
        double *qdd = malloc((size_t)nvf * sizeof(double));
        memcpy(qdd, Pdd, sizeof Pdd);
        memcpy(qdd + 3, al, sizeof al);
        memcpy(qdd + 6, db->qdd + 7, (size_t)(nvf - 6) * sizeof(double));
        vt_data *all[3] = {df, dr, dm};
        for (int k = 1; k < 3; k++) {
            memcpy(all[k]->q, df->q, (size_t)nqf * sizeof(double));
            memcpy(all[k]->qd, df->qd, (size_t)nvf * sizeof(double));
            memcpy(all[k]->qfrc, df->qfrc, (size_t)nvf * sizeof(double));
        }
        memset(dm->qfrc, 0, 6 * sizeof(double)); /* the motion call finds the root's wrench */
        memcpy(dm->qdd, qdd, (size_t)nvf * sizeof(double));
        assert_ok(vt_inverse_dynamics(mf, df));
        assert_ok(vt_inverse_dynamics_recursive(mf, dr));
        assert_int_equal(dr->route, VT_ROUTE_ARTICULATED);
        assert_ok(vt_inverse_dynamics_motion(mf, dm));
        assert_int_equal(dm->route, VT_ROUTE_MOTION);
        const int nb = mf->nbody, nb3 = 3 * (nb + 1);
        vt_test_compare(df->qdd, qdd, nvf, 1e-11, "dense free q̈ against the base's converted");
        vt_test_compare(dr->qdd, qdd, nvf, 1e-11, "recursive free q̈ against the base's converted");
        double tau[6];
        memcpy(tau, f, sizeof f);
        memcpy(tau + 3, n, sizeof n);
        vt_test_compare(dm->qfrc_drive, tau, 6, 1e-11, "the root's efforts against the wrench applied");
        const double zero[64] = {0};
        assert_true(nvf - 6 <= 64);
        vt_test_compare_at(dm->qfrc_drive + 6, zero, nvf - 6, 1e-11, 1.0 + vt_test_maxabs(tau, 6), "the other efforts");
        for (int k = 1; k < 3; k++) { /* every body's motion and the joints' reactions: bodies 2.. */
            vt_test_compare(all[k]->x, db->x, mf->nx, 1e-12, "x");
            vt_test_compare(all[k]->xdd, db->xdd, mf->nx, 1e-10, "xdd");
            vt_test_compare(all[k]->jnt_force + 6, db->jnt_force + 6, nb3 - 6, 1e-11, "jnt_force");
            vt_test_compare(all[k]->jnt_moment + 6, db->jnt_moment + 6, nb3 - 6, 1e-11, "jnt_moment");
            vt_test_compare(all[k]->jnt_force_body + 6, db->jnt_force_body + 6, nb3 - 6, 1e-11, "jnt_force_body");
            vt_test_compare(all[k]->jnt_moment_body + 6, db->jnt_moment_body + 6, nb3 - 6, 1e-11, "jnt_moment_body");
        }
        vt_test_compare(df->xdd, db->xdd, mf->nx, 1e-10, "dense xdd");
        vt_test_compare(df->jnt_force + 6, db->jnt_force + 6, nb3 - 6, 1e-11, "dense jnt_force");
        vt_test_compare(df->jnt_moment + 6, db->jnt_moment + 6, nb3 - 6, 1e-11, "dense jnt_moment");
        for (int k = 0; k < 3; k++) /* the free joint transmits nothing */
            assert_true(dm->jnt_force[3 + k] == 0.0 && dm->jnt_moment[3 + k] == 0.0 && df->jnt_force[3 + k] == 0.0);
        free(qdd);
        vt_data_free(db);
        vt_data_free(df);
        vt_data_free(dr);
        vt_data_free(dm);
        vt_model_free(mb);
        vt_model_free(mf);
    }
}

/* One free body, its joint point c' off the centre of mass, falling and spinning: at the exact
 * free motion (a = g, J α + ω × J ω = 0, so P̈ = g + α × s + ω × (ω × s)) the motion call's six
 * efforts vanish; at a given q̈ they are m (a − g) and the moment J α + ω × J ω + (r − P) × m (a − g)
 * about P, written by hand. */
static void test_free_body(void **state)
{
    (void)state;
    vt_builder *b;
    vt_model_def md = vt_default_model_def();
    assert_ok(vt_builder_create(&b, &md));
    vt_body_def d = vt_default_body_def();
    d.joint = VT_JOINT_FREE;
    d.mass = 2.5;
    const double J0[9] = {0.4, 0.02, 0.01, 0.02, 0.5, -0.04, 0.01, -0.04, 0.6};
    memcpy(d.inertia, J0, sizeof J0);
    d.joint_child[0] = 0.4, d.joint_child[1] = -0.1, d.joint_child[2] = 0.25;
    assert_int_equal(vt_builder_add_body(b, &d), 1);
    vt_model *m = vt_test_build(b);
    vt_data *dm;
    assert_ok(vt_data_create(&dm, m));
    uint64_t s = 17;
    for (int trial = 0; trial < 10; trial++) {
        double *q = dm->q, *v = dm->qd;
        for (int k = 0; k < 3; k++) q[k] = vt_rand_uniform(&s, -5, 5), v[k] = vt_rand_uniform(&s, -3, 3);
        vt_rand_unit(q + 3, 4, &s);
        for (int k = 0; k < 3; k++) v[3 + k] = vt_rand_uniform(&s, -4, 4);
        double A[9], J[9], T[9], sp[3], w[3], Jw[3], wJw[3], al[3], rhs[3];
        vt_euler_A(A, q + 3);
        for (int c = 0; c < 3; c++) mul3(T + 3 * c, A, J0 + 3 * c);
        for (int c = 0; c < 3; c++) /* J = A J0 A^T */
            for (int r = 0; r < 3; r++) J[r + 3 * c] = T[r] * A[c] + T[r + 3] * A[c + 3] + T[r + 6] * A[c + 6];
        mul3(sp, A, m->body_jchild + 3);
        memcpy(w, v + 3, sizeof w);
        mul3(Jw, J, w);
        cross3(wJw, w, Jw);
        /* α = −J^-1 (ω × J ω) by LAPACK */
        double Jc[9];
        memcpy(Jc, J, sizeof J);
        for (int k = 0; k < 3; k++) rhs[k] = -wJw[k];
        int three = 3, one = 1, ipiv[3], info = 0;
        dgesv_(&three, &one, Jc, &three, ipiv, rhs, &three, &info);
        assert_int_equal(info, 0);
        memcpy(al, rhs, sizeof al);
        double t[3], u[3], u2[3];
        cross3(t, w, sp);
        cross3(u, al, sp);
        cross3(u2, w, t);
        for (int k = 0; k < 3; k++) dm->qdd[k] = m->gravity[k] + u[k] + u2[k], dm->qdd[3 + k] = al[k];
        assert_ok(vt_inverse_dynamics_motion(m, dm));
        const double scale = m->body_mass[1] * 9.81 + vt_test_maxabs(wJw, 3);
        for (int k = 0; k < 6; k++) assert_near(dm->qfrc_drive[k], 0.0, 1e-13 * scale);
        /* a given q̈: a = P̈ − α × s − ω × (ω × s) */
        double a[3], fexp[3], nexp[3], Ja[3];
        for (int k = 0; k < 6; k++) dm->qdd[k] = vt_rand_uniform(&s, -10, 10);
        memcpy(al, dm->qdd + 3, sizeof al);
        cross3(u, al, sp);
        for (int k = 0; k < 3; k++) a[k] = dm->qdd[k] - u[k] - u2[k];
        for (int k = 0; k < 3; k++) fexp[k] = m->body_mass[1] * (a[k] - m->gravity[k]);
        mul3(Ja, J, al);
        cross3(u, sp, fexp); /* (r − P) × f = −s × f */
        for (int k = 0; k < 3; k++) nexp[k] = Ja[k] + wJw[k] - u[k];
        assert_ok(vt_inverse_dynamics_motion(m, dm));
        const double sc = 1.0 + vt_test_maxabs(fexp, 3) + vt_test_maxabs(nexp, 3);
        for (int k = 0; k < 3; k++) {
            assert_near(dm->qfrc_drive[k], fexp[k], 1e-13 * sc);
            assert_near(dm->qfrc_drive[3 + k], nexp[k], 1e-13 * sc);
        }
    }
    vt_data_free(dm);
    vt_model_free(m);
}

/* The fused passes skip their output scans where the inputs' sizes bound every output below
 * 1e300 (fused_bounded): across that threshold and up to overflow, a result is either VT_OK
 * with every output finite or VT_ERR_NONFINITE, never VT_OK with Inf or NaN. Checked by an
 * identity: without gravity and loads, every acceleration, effort and reaction is homogeneous of
 * degree 2 in time's scale, so at q̇ λ and q̈ λ² (λ = 2^k: exact) each is λ² times the one at
 * λ = 1, bit for bit, as long as nothing overflows. The all-revolute chain and two trees with a
 * free joint, universal, spherical and sliding joints (the general code's bodies). */
static void test_bounded_outputs(void **state)
{
    (void)state;
    for (int c = 0; c < 3; c++) {
        vt_model *m;
        vt_data *d, *d1;
        if (c == 0) assert_ok(vt_scene_chain(&m, 7, VT_CHAIN_JOINT_DRIVEN));
        else assert_ok(vt_scene_random_tree(&m, (uint64_t)c + 21, 8, VT_SCENE_WITH_FREE));
        m->gravity[0] = m->gravity[1] = m->gravity[2] = 0.0; /* degree 0 in time's scale */
        assert_ok(vt_data_create(&d, m));
        assert_ok(vt_data_create(&d1, m));
        uint64_t s = 41u + (uint64_t)c;
        vt_scene_random_state(m, d1, &s);
        for (int k = 0; k < m->nv; k++) d1->qd[k] *= 8.0, d1->qdd[k] = vt_rand_uniform(&s, -128, 128);
        assert_ok(vt_inverse_dynamics_motion(m, d1));
        const int n3 = 3 * (m->nbody + 1);
        double *const out1[] = {d1->xdd, d1->alpha, d1->qfrc_drive, d1->jnt_force, d1->jnt_moment, d1->jnt_force_body,
                                d1->jnt_moment_body, d1->jnt_force_total, d1->jnt_moment_total,
                                d1->jnt_force_total_body, d1->jnt_moment_total_body};
        double *const out[] = {d->xdd, d->alpha, d->qfrc_drive, d->jnt_force, d->jnt_moment, d->jnt_force_body,
                               d->jnt_moment_body, d->jnt_force_total, d->jnt_moment_total,
                               d->jnt_force_total_body, d->jnt_moment_total_body};
        const int len[] = {m->nx, n3, m->nv, n3, n3, n3, n3, n3, n3, n3, n3};
        int ok = 0, refused = 0;
        double largest = 0.0;
        for (int e = 0; e <= 510; e += 2) {
            const double lam = ldexp(1.0, e), lam2 = ldexp(1.0, 2 * e);
            memcpy(d->q, d1->q, (size_t)m->nq * sizeof(double));
            int finite = 1;
            for (int k = 0; k < m->nv; k++) {
                d->qd[k] = lam * d1->qd[k], d->qdd[k] = lam2 * d1->qdd[k];
                finite &= isfinite(d->qdd[k]) != 0;
            }
            if (!finite) break; /* the inputs themselves overflow */
            d->message[0] = '\0';
            const vt_status st = vt_inverse_dynamics_motion(m, d);
            if (st == VT_ERR_NONFINITE) {
                assert_non_null(strstr(d->message, "overflow"));
                refused++;
                continue;
            }
            if (st != VT_OK) fail_msg("case %d, λ = 2^%d: status %d (%s)", c, e, (int)st, d->message);
            ok++;
            for (int a = 0; a < 11; a++)
                for (int k = 0; k < len[a]; k++) {
                    if (!isfinite(out[a][k])) fail_msg("case %d, λ = 2^%d: output %d[%d] = %g with VT_OK", c, e, a, k, out[a][k]);
                    if (a == 0 && k % 7 < 3) continue; /* ẍ's positions part: the same here */
                    if (out[a][k] != lam2 * out1[a][k])
                        fail_msg("case %d, λ = 2^%d: output %d[%d] = %.17g, λ² × %.17g", c, e, a, k, out[a][k], out1[a][k]);
                    largest = fmax(largest, fabs(out[a][k]));
                }
        }
        print_message("case %d: %d scales solved (largest output %.3g), %d refused as overflowing\n", c, ok, largest,
                      refused);
        assert_true(largest > 1e300); /* solved beyond the bound's threshold: the scans decided there */
        assert_true(refused > 0);
        vt_data_free(d1);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* The scans of several arrays as one (vt_finite_add, vt_finite_ok: the fused passes' checks)
 * against isfinite entry by entry: every length 0..13 in one or two arrays, a NaN, +Inf or −Inf
 * at every position of either array (the overlapping last four included), DBL_MAX and the
 * smallest subnormal finite. */
static void test_finite_scan(void **state)
{
    (void)state;
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    double a[13], b[13];
    for (int n = 0; n <= 13; n++)
        for (int nb = 0; nb <= 13; nb += 5) {
            for (int k = 0; k < 13; k++) {
                a[k] = (k % 3 == 0) ? DBL_MAX : (k % 3 == 1 ? -4.9e-324 : 1.0 + k);
                b[k] = -a[k];
            }
            vt_finite_scan s = {0};
            vt_finite_add(&s, a, n);
            vt_finite_add(&s, b, nb);
            assert_true(vt_finite_ok(&s));
            for (int w = 0; w < 2; w++)
                for (int pos = 0; pos < (w ? nb : n); pos++)
                    for (int v = 0; v < 3; v++) {
                        double *x = w ? b : a, keep = x[pos];
                        x[pos] = bad[v];
                        int expect = 1;
                        for (int k = 0; k < n; k++) expect &= isfinite(a[k]) != 0;
                        for (int k = 0; k < nb; k++) expect &= isfinite(b[k]) != 0;
                        vt_finite_scan t = {0};
                        vt_finite_add(&t, a, n);
                        vt_finite_add(&t, b, nb);
                        assert_int_equal(vt_finite_ok(&t), expect);
                        assert_int_equal(expect, 0);
                        x[pos] = keep;
                    }
        }
}

/* vt_max_scan over two arrays of 0..13 entries (the short ones one by one, the others four at a
 * time): the largest magnitude as fmax of fabs says, +Inf with any Inf or NaN among them */
static void test_max_scan(void **state)
{
    (void)state;
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    double a[13], b[13];
    for (int n = 0; n <= 13; n++)
        for (int nb = 0; nb <= 13; nb += 3)
            for (int big = -1; big < n + nb; big++) { /* the largest entry at each place in turn */
                for (int k = 0; k < 13; k++) {
                    a[k] = (k % 3 == 0) ? -4.9e-324 : (k % 3 == 1 ? 0.5 + k : -(1.0 + k));
                    b[k] = -0.75 * a[k];
                }
                if (big >= 0) (big < n ? a : b)[big < n ? big : big - n] = big % 2 ? -1e300 : 1e300;
                double expect = 0.0;
                for (int k = 0; k < n; k++) expect = fmax(expect, fabs(a[k]));
                for (int k = 0; k < nb; k++) expect = fmax(expect, fabs(b[k]));
                vt_max_scan s = {0};
                vt_max_add(&s, a, n);
                vt_max_add(&s, b, nb);
                assert_true(vt_max_result(&s) == expect);
                if (big >= 0) continue;
                for (int w = 0; w < 2; w++)
                    for (int pos = 0; pos < (w ? nb : n); pos++)
                        for (int v = 0; v < 3; v++) {
                            double *x = w ? b : a, keep = x[pos];
                            x[pos] = bad[v];
                            vt_max_scan t = {0};
                            vt_max_add(&t, a, n);
                            vt_max_add(&t, b, nb);
                            assert_true(vt_max_result(&t) == HUGE_VAL);
                            x[pos] = keep;
                        }
            }
}


int main(void)
{
    static const struct CMUnitTest others[] = {
        cmocka_unit_test(test_dependent),
        cmocka_unit_test(test_row_on_known_rates),
        cmocka_unit_test(test_motion),
        cmocka_unit_test(test_motion_add_loads),
        cmocka_unit_test(test_motion_loops),
        cmocka_unit_test(test_motion_refused),
        cmocka_unit_test(test_motion_euler_rates_overflow),
        cmocka_unit_test(test_free_vs_base),
        cmocka_unit_test(test_free_body),
        cmocka_unit_test(test_fused_kinematics),
        cmocka_unit_test(test_fused_overflow),
        cmocka_unit_test(test_finite_scan),
        cmocka_unit_test(test_max_scan),
        cmocka_unit_test(test_bounded_outputs),
    };
    enum { NROW = sizeof route_table / sizeof route_table[0], NOTHER = sizeof others / sizeof others[0] };
    struct CMUnitTest tests[NROW + NOTHER];
    for (int k = 0; k < NROW; k++) /* a test per row of the route table, named by it */
        tests[k] = (struct CMUnitTest){.name = route_table[k].name, .test_func = test_route,
                                       .initial_state = (void *)&route_table[k]};
    for (int k = 0; k < NOTHER; k++) tests[NROW + k] = others[k];
    return _cmocka_run_group_tests("test_recursive", tests, NROW + NOTHER, NULL, NULL);
}
