/* src/analysis/data.c: data creation and reset, data of another model refused, and the layouts:
 * VT_LAYOUT_RECURSIVE's data O(n) bytes (against the full data's O(n²)), the same answers as the
 * full data's on the routes it serves, and every call that needs the dense arrays refused. */
#include "vt_test.h"

static void test_create_reset_mismatch(void **state)
{
    (void)state;
    vt_model *m1 = NULL, *m2 = NULL;
    vt_data *d = NULL;
    assert_ok(vt_scene_random_tree(&m1, 7, 8, VT_SCENE_ALL_JOINTS));
    assert_ok(vt_scene_double_link(&m2, 0));
    assert_ok(vt_data_create(&d, m1));
    for (int k = 0; k < m1->nq; k++) assert_near(d->q[k], m1->q0[k], 0.0);
    uint64_t s = 5;
    vt_scene_random_state(m1, d, &s);
    d->time = 3.0;
    assert_ok(vt_data_reset(m1, d));
    for (int k = 0; k < m1->nq; k++) assert_near(d->q[k], m1->q0[k], 0.0);
    for (int k = 0; k < m1->nv; k++) assert_near(d->qd[k], 0.0, 0.0);
    assert_near(d->time, 0.0, 0.0);
    /* a data struct used with another model is refused, naming the call */
    assert_int_equal(vt_kinematics(m2, d), VT_ERR_MODEL_MISMATCH);
    assert_non_null(strstr(d->message, "vt_kinematics"));
    assert_int_equal(vt_mass_matrix(m2, d), VT_ERR_MODEL_MISMATCH);
    assert_int_equal(vt_forces(m2, d), VT_ERR_MODEL_MISMATCH);
    assert_int_equal(vt_inverse_transform(m2, d), VT_ERR_MODEL_MISMATCH);
    assert_int_equal(vt_kinematics(NULL, d), VT_ERR_NULL);
    assert_int_equal(vt_data_create(NULL, m1), VT_ERR_NULL);
    vt_data_free(d);
    vt_model_free(m1);
    vt_model_free(m2);
}




/* vt_data_size of the chain (vt_scene_chain) of n links, its drives and layout */
static size_t chain_bytes(int n, int drives, vt_layout layout)
{
    vt_model *m = NULL;
    assert_ok(vt_scene_chain_layout(&m, n, drives, layout));
    const size_t bytes = vt_data_size(m);
    vt_model_free(m);
    return bytes;
}

/* The recursive layout's bytes per body at n = 1000 under 4 KB on the joint-driven, tip-driven
 * and free chains (the full data's are above 100 KB: S, R, M*), and linear in n: from 250 to 1000
 * links the bytes grow by at most 4.2 (n² would be 16) */
static void test_recursive_layout_linear(void **state)
{
    (void)state;
    const int drives[] = {VT_CHAIN_JOINT_DRIVEN, VT_CHAIN_TIP_DRIVE, VT_CHAIN_FREE};
    for (int k = 0; k < 3; k++) {
        const size_t lean = chain_bytes(1000, drives[k], VT_LAYOUT_RECURSIVE);
        const size_t quarter = chain_bytes(250, drives[k], VT_LAYOUT_RECURSIVE);
        const size_t full = chain_bytes(1000, drives[k], VT_LAYOUT_FULL);
        print_message("chain %d: %.2f KB a body (recursive), %.1f KB (full); 250 to 1000 links: x %.2f\n", drives[k],
                      (double)lean / 1024e3, (double)full / 1024e3, (double)lean / (double)quarter);
        assert_true(lean <= 4096 * 1000);
        assert_true(full > 100 * 1024 * 1000);
        assert_true((double)lean <= 4.2 * (double)quarter);
    }
}

/* the outputs of one instant on two data of models that differ only in their layout: bitwise */
static void same_outputs(const vt_model *m, const vt_data *a, const vt_data *b)
{
    const size_t nb3 = 3 * ((size_t)m->nbody + 1);
    assert_memory_equal(a->qdd, b->qdd, (size_t)m->nv * sizeof(double));
    assert_memory_equal(a->qfrc_drive, b->qfrc_drive, (size_t)m->nv * sizeof(double));
    assert_memory_equal(a->xdd, b->xdd, (size_t)m->nx * sizeof(double));
    assert_memory_equal(a->jnt_force, b->jnt_force, nb3 * sizeof(double));
    assert_memory_equal(a->jnt_moment, b->jnt_moment, nb3 * sizeof(double));
    assert_memory_equal(a->jnt_force_total_body, b->jnt_force_total_body, nb3 * sizeof(double));
    assert_memory_equal(a->alpha, b->alpha, nb3 * sizeof(double));
    if (m->nc) assert_memory_equal(a->lambda, b->lambda, (size_t)m->nc * sizeof(double));
    if (m->ndrive) assert_memory_equal(a->drive_effort, b->drive_effort, (size_t)m->ndrive * sizeof(double));
    assert_int_equal(a->route, b->route);
    assert_true(a->rcond == b->rcond);
}

/* The recursive and given-motion instants on the recursive layout's data: the full data's answers,
 * bit for bit (the same routes over other memory), on the joint-driven chain (fused passes), the
 * tip-driven chain (articulated), the free chain's given motion, and a kinematic analysis of the
 * joint-driven chain (its first row by the recursive instant there, the dense one on the full
 * data: within round-off; the rows after it bitwise) */
static void test_recursive_layout_same_answers(void **state)
{
    (void)state;
    const int drives[] = {VT_CHAIN_JOINT_DRIVEN, VT_CHAIN_TIP_DRIVE, VT_CHAIN_FREE};
    for (int k = 0; k < 3; k++) {
        vt_model *mf = NULL, *ml = NULL;
        vt_data *df = NULL, *dl = NULL;
        assert_ok(vt_scene_chain_layout(&mf, 12, drives[k], VT_LAYOUT_FULL));
        assert_ok(vt_scene_chain_layout(&ml, 12, drives[k], VT_LAYOUT_RECURSIVE));
        assert_int_equal(ml->layout, VT_LAYOUT_RECURSIVE);
        assert_ok(vt_data_create(&df, mf));
        assert_ok(vt_data_create(&dl, ml));
        vt_test_chain_state(mf, df, drives[k] == VT_CHAIN_FREE);
        vt_test_chain_state(ml, dl, drives[k] == VT_CHAIN_FREE);
        if (drives[k] == VT_CHAIN_FREE) {
            assert_ok(vt_inverse_dynamics_motion(mf, df));
            assert_ok(vt_inverse_dynamics_motion(ml, dl));
        } else {
            assert_ok(vt_inverse_dynamics_recursive(mf, df));
            assert_ok(vt_inverse_dynamics_recursive(ml, dl));
        }
        same_outputs(mf, df, dl);
        if (drives[k] == VT_CHAIN_JOINT_DRIVEN) {
            vt_run_options opt = vt_default_run_options();
            opt.t1 = 0.5;
            opt.nout = 20;
            vt_trajectory *tf = NULL, *tl = NULL;
            assert_ok(vt_trajectory_create(&tf, mf, opt.nout + 1));
            assert_ok(vt_trajectory_create(&tl, ml, opt.nout + 1));
            assert_ok(vt_kinematic_analysis(mf, df, &opt, tf));
            assert_ok(vt_kinematic_analysis(ml, dl, &opt, tl)); /* its forward check on full data of its own */
            const size_t nv = (size_t)mf->nv;
            vt_test_compare(tl->qfrc_drive, tf->qfrc_drive, (int)nv, 1e-13, "row 0's efforts");
            assert_memory_equal(tl->qfrc_drive + nv, tf->qfrc_drive + nv, (size_t)opt.nout * nv * sizeof(double));
            /* the forward checks (from first rows apart by round-off) both at round-off: the
             * efforts reproduce the motion */
            print_message("forward check: %.3g (recursive layout), %.3g (full)\n", tl->fwd_err_q, tf->fwd_err_q);
            assert_true(tf->fwd_err_q < 1e-9 && tl->fwd_err_q < 1e-9);
            assert_true(tl->phid_norm[opt.nout] == 0.0 && tl->phi_norm[opt.nout] == 0.0);
            vt_trajectory_free(tf);
            vt_trajectory_free(tl);
        }
        vt_data_free(df);
        vt_data_free(dl);
        vt_model_free(mf);
        vt_model_free(ml);
    }
}

/* A planar two-link arm about z whose tip's x and y follow drives (the square route: as many
 * rows as rates), and a random tree of every joint kind with a point drive at its last body
 * (the articulated route), on the given layout */
static vt_model *driven_tip(vt_layout layout, int tree)
{
    vt_model_def def = vt_default_model_def();
    def.layout = layout;
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, &def));
    if (tree) {
        assert_ok(vt_scene_random_bodies(b, 11, 6, VT_SCENE_NO_BASE));
    } else {
        for (int i = 1; i <= 2; i++) {
            vt_body_def link = vt_default_body_def();
            link.parent = i - 1;
            link.joint_parent[0] = i > 1 ? 0.25 : 0.0;
            link.joint_child[0] = -0.25;
            assert_true(vt_builder_add_body(b, &link) > 0);
        }
    }
    for (int k = 0; k < (tree ? 1 : 2); k++) {
        vt_drive_def dr = vt_default_drive_def();
        dr.type = VT_DRIVE_POINT;
        dr.body = tree ? 6 : 2;
        dr.index = k;
        dr.point[0] = 0.25;
        dr.f = vt_function_sine(0.1, 0.05, 3.0, 0.0);
        assert_true(vt_builder_add_drive(b, &dr) >= 0);
    }
    return vt_test_build(b);
}

/* The square and articulated routes on the recursive layout: the full data's answers, bitwise,
 * at a state the recursive layout's kinematic solve made consistent */
static void test_recursive_layout_rows(void **state)
{
    (void)state;
    for (int tree = 0; tree < 2; tree++) {
        vt_model *mf = driven_tip(VT_LAYOUT_FULL, tree), *ml = driven_tip(VT_LAYOUT_RECURSIVE, tree);
        vt_data *df = NULL, *dl = NULL;
        assert_ok(vt_data_create(&df, mf));
        assert_ok(vt_data_create(&dl, ml));
        assert_true(vt_data_size(ml) < vt_data_size(mf));
        uint64_t seed = 3;
        vt_scene_random_state(mf, df, &seed);
        if (!tree) df->q[0] = 0.3, df->q[1] = 1.2; /* away from the stretched arm */
        vt_test_copy_inputs(mf, dl, df);
        memcpy(dl->q, df->q, (size_t)mf->nq * sizeof(double));
        df->time = dl->time = 0.2;
        /* consistent q and q̇ by the recursive layout's kinematic solve, then the recursive
         * instant on both */
        assert_ok(vt_kinematic_solve(ml, dl, 1e-13, 30));
        memcpy(df->q, dl->q, (size_t)mf->nq * sizeof(double));
        memcpy(df->qd, dl->qd, (size_t)mf->nv * sizeof(double));
        assert_ok(vt_inverse_dynamics_recursive(mf, df));
        assert_ok(vt_inverse_dynamics_recursive(ml, dl));
        assert_int_equal(dl->route, tree ? VT_ROUTE_ARTICULATED : VT_ROUTE_SQUARE);
        same_outputs(mf, df, dl);
        vt_data_free(df);
        vt_data_free(dl);
        vt_model_free(mf);
        vt_model_free(ml);
    }
}

/* a call refused with VT_ERR_LAYOUT, its message naming who, the state left as it was */
static void refused(vt_status st, const vt_model *m, const vt_data *d, const double *q, const char *who)
{
    assert_int_equal(st, VT_ERR_LAYOUT);
    if (!strstr(d->message, who)) fail_msg("message \"%s\" does not name %s", d->message, who);
    assert_non_null(strstr(d->message, "VT_LAYOUT_FULL"));
    assert_memory_equal(d->q, q, (size_t)m->nq * sizeof(double));
}

/* On the recursive layout's data every dense stage, the dense instant, the dynamic analysis, and
 * an instant that needs M* (a coupling; the tip-driven chain of 1000 links, ill-conditioned, where
 * the articulated route gives way) are refused with VT_ERR_LAYOUT, naming the call and the
 * option; caller memory sized by vt_data_size serves vt_data_init; a layout that is not a
 * vt_layout is refused by the builder */
static void test_recursive_layout_refusals(void **state)
{
    (void)state;
    vt_model *m = NULL;
    assert_ok(vt_scene_chain_layout(&m, 6, VT_CHAIN_TIP_DRIVE, VT_LAYOUT_RECURSIVE));
    const size_t bytes = vt_data_size(m);
    void *buffer = malloc(bytes);
    assert_non_null(buffer);
    vt_data *d = NULL;
    assert_int_equal(vt_data_init(&d, m, buffer, bytes - VT_DATA_ALIGN), VT_ERR_BAD_SIZE);
    assert_ok(vt_data_init(&d, m, buffer, bytes));
    assert_null(d->S);
    assert_null(d->R);
    assert_null(d->Mstar);
    vt_test_chain_state(m, d, 0);
    double q[6], F[42] = {0}, Q[6] = {0}, Fc[42];
    memcpy(q, d->q, sizeof q);
    refused(vt_kinematics(m, d), m, d, q, "vt_kinematics");
    refused(vt_inverse_transform(m, d), m, d, q, "vt_inverse_transform");
    refused(vt_mass_matrix(m, d), m, d, q, "vt_mass_matrix");
    refused(vt_forces(m, d), m, d, q, "vt_forces");
    refused(vt_constraints(m, d), m, d, q, "vt_constraints");
    refused(vt_solve(m, d), m, d, q, "vt_solve");
    refused(vt_reactions(m, d), m, d, q, "vt_reactions");
    refused(vt_inverse_dynamics(m, d), m, d, q, "vt_inverse_dynamics");
    refused(vt_generalized_force(Q, m, d, F), m, d, q, "vt_generalized_force");
    refused(vt_equivalent_force(F, m, d, Q), m, d, q, "vt_equivalent_force");
    refused(vt_drive_cartesian_force(Fc, m, d, 0), m, d, q, "vt_drive_cartesian_force");
#if VT_HAVE_SUNDIALS
    vt_run_options opt = vt_default_run_options();
    vt_trajectory *tr = NULL;
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    refused(vt_dynamic_analysis(m, d, &opt, tr), m, d, q, "vt_dynamic_analysis");
    vt_trajectory_free(tr);
#endif
    assert_ok(vt_inverse_dynamics_recursive(m, d)); /* the articulated route: served */
    assert_int_equal(d->route, VT_ROUTE_ARTICULATED);
    free(buffer);
    vt_model_free(m);

    /* the 1000-link tip-driven chain: the articulated route gives way (the full data's dense
     * stages then refuse it as ill-conditioned) */
    assert_ok(vt_scene_chain_layout(&m, 1000, VT_CHAIN_TIP_DRIVE, VT_LAYOUT_RECURSIVE));
    assert_ok(vt_data_create(&d, m));
    vt_test_chain_state(m, d, 0);
    assert_int_equal(vt_inverse_dynamics_recursive(m, d), VT_ERR_LAYOUT);
    assert_non_null(strstr(d->message, "needs M*"));
    assert_non_null(strstr(d->message, "articulated route gave way"));
    assert_int_equal(d->route, VT_ROUTE_NONE);
    vt_data_free(d);
    vt_model_free(m);

    /* a coupling: the general route, M* formed */
    vt_model_def def = vt_default_model_def();
    def.layout = VT_LAYOUT_RECURSIVE;
    vt_builder *b = NULL;
    assert_ok(vt_builder_create(&b, &def));
    for (int i = 1; i <= 2; i++) {
        vt_body_def link = vt_default_body_def();
        link.parent = i - 1;
        link.joint_child[0] = -0.25;
        link.joint_parent[0] = i > 1 ? 0.25 : 0.0;
        assert_true(vt_builder_add_body(b, &link) > 0);
    }
    vt_coupling_def c = vt_default_coupling_def();
    assert_true(vt_builder_add_coupling(b, &c) >= 0);
    vt_test_add_joint_drive(b, 1, 0, vt_function_sine(0.0, 0.3, 2.0, 0.0));
    m = vt_test_build(b);
    assert_ok(vt_data_create(&d, m));
    memcpy(q, d->q, (size_t)m->nq * sizeof(double));
    refused(vt_inverse_dynamics_recursive(m, d), m, d, q, "needs M* (couplings)");
    refused(vt_inverse_dynamics_motion(m, d), m, d, q, "vt_inverse_dynamics_motion");
    vt_data_free(d);
    vt_model_free(m);

    def.layout = (vt_layout)2;
    assert_int_equal(vt_builder_create(&b, &def), VT_ERR_BAD_OPTION);
    assert_null(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_reset_mismatch),
        cmocka_unit_test(test_recursive_layout_linear),
        cmocka_unit_test(test_recursive_layout_same_answers),
        cmocka_unit_test(test_recursive_layout_rows),
        cmocka_unit_test(test_recursive_layout_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
