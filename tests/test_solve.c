/* The test file of src/dense/solve.c (the dispatcher, vt_solve); through it also of the files cut
 * from it that have no test file of their own: dense/routes.c (the five routes), numeric/roundoff.c
 * (round-off of exact zeros), numeric/rank.c (the scalings, grip and rank decision) and
 * numeric/route.c (the diagnostics every route ends with); numeric/kkt.c has tests/test_kkt.c.
 * The augmented system (5) against second methods (a fully joint-driven chain:
 * q̈ = f'', λ = M* q̈ − Q; a free tree: M* q̈ = Q by Cholesky), and every failure status:
 * singular system, dependent rows, bad drive and cut-joint definitions. */
#include "base/lapack.h"
#include "dense/solve.h" /* vt_solve_run: the ODE form's solve with its band */
#include "model/model.h" /* the rows' kinds */

#include "vt_test.h"

static void dpotrs_solve(int n, double *A, double *b)
{
    int info = 0, one = 1;
    dpotrf_("L", &n, A, &n, &info, 1);
    assert_int_equal(info, 0);
    extern void dpotrs_(const char *, const int *, const int *, const double *, const int *, double *,
                        const int *, int *, size_t);
    dpotrs_("L", &n, &one, A, &n, b, &n, &info, 1);
    assert_int_equal(info, 0);
}

/* every coordinate of a spatial chain driven by a sine: q̈ = f'' and efforts = M* q̈ − Q */
static void test_fully_joint_driven_chain(void **state)
{
    (void)state;
    const int n = 7;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    assert_ok(vt_scene_random_bodies(b, 21, n, VT_SCENE_SCALAR_JOINTS));
    vt_model *probe;
    assert_ok(vt_scene_random_tree(&probe, 21, n, VT_SCENE_SCALAR_JOINTS));
    for (int i = 1; i <= n; i++)
        for (int k = 0; k < probe->body_nv[i]; k++) {
            vt_drive_def dr = vt_default_drive_def();
            dr.body = i;
            dr.index = k;
            dr.f = vt_function_sine(0.1 * i, 0.5 + 0.1 * k, 1.0 + i, 0.2 * k);
            assert_int_equal(vt_builder_add_drive(b, &dr), probe->body_vadr[i] + k);
        }
    vt_model_free(probe);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    const int nv = m->nv;
    for (double t = 0.0; t < 1.0; t += 0.23) {
        double f[3];
        d->time = t;
        for (int k = 0; k < m->ndrive; k++) {
            assert_ok(vt_function_eval(f, &m->drive[k].f, t));
            d->q[k] = f[0];
            d->qd[k] = f[1];
        }
        assert_ok(vt_inverse_dynamics(m, d));
        assert_int_equal(d->route, VT_ROUTE_SQUARE); /* as many rows as rates */
        for (int k = 0; k < nv; k++) {
            assert_ok(vt_function_eval(f, &m->drive[k].f, t));
            assert_near(d->qdd[k], f[2], 1e-12 * (1 + fabs(f[2])));
        }
        const double scale = 1.0 + vt_test_maxabs(d->Q, nv);
        for (int a = 0; a < nv; a++) {
            double s = -d->Q[a];
            for (int c = 0; c < nv; c++) s += d->Mstar[a + (size_t)c * (size_t)nv] * d->qdd[c];
            assert_near(d->drive_effort[a], s, 1e-11 * scale);
        }
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* without constraints (5) is M* q̈ = Q: against a Cholesky solve */
static void test_free_tree(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_random_tree(&m, 8, 12, VT_SCENE_NO_BASE));
    assert_int_equal(m->nc, 0);
    assert_ok(vt_data_create(&d, m));
    uint64_t s = 4;
    vt_scene_random_state(m, d, &s);
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->route, VT_ROUTE_AUGMENTED); /* no rows: M* alone, LDL^T */
    const int nv = m->nv;
    double *A = malloc((size_t)nv * (size_t)nv * sizeof(double)), *x = malloc((size_t)nv * sizeof(double));
    memcpy(A, d->Mstar, (size_t)nv * (size_t)nv * sizeof(double));
    memcpy(x, d->Q, (size_t)nv * sizeof(double));
    dpotrs_solve(nv, A, x);
    for (int k = 0; k < nv; k++) assert_near(d->qdd[k], x[k], 1e-10 * (1 + vt_test_maxabs(x, nv)));
    assert_true(d->rcond > 1e-6);
    free(A); free(x);
    vt_data_free(d);
    vt_model_free(m);
}

static vt_model *pendulum_with(int ndrives_on_joint, double inertia)
{
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def(); /* point mass on the axis: no inertia about it */
    body.inertia[0] = body.inertia[4] = body.inertia[8] = inertia;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    for (int k = 0; k < ndrives_on_joint; k++) {
        vt_drive_def dr = vt_default_drive_def();
        assert_int_equal(vt_builder_add_drive(b, &dr), k);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

static void test_failures(void **state)
{
    (void)state;
    /* singular: a body that nothing drives and that has no inertia about its free axis */
    vt_model *m = pendulum_with(0, 0.0);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    d->qdd[0] = 42.0;
    assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_SINGULAR);
    /* what was found: M* = 0, the rate named, not an ill-conditioned matrix */
    assert_non_null(strstr(d->message, "singular"));
    assert_non_null(strstr(d->message, "rate 0 (body 1) has no inertia"));
    assert_null(strstr(d->message, "ill-conditioned"));
    assert_int_equal(d->route, VT_ROUTE_NONE);
    assert_near(d->qdd[0], 42.0, 0.0); /* untouched */
    vt_data_free(d);
    vt_model_free(m);

    /* dependent rows: the same coordinate driven twice; the message names the row */
    m = pendulum_with(2, 1.0);
    assert_ok(vt_data_create(&d, m));
    d->lambda[0] = 7.0;
    assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_DEPENDENT_CONSTRAINTS);
    assert_non_null(strstr(d->message, "rank 1 of 2"));
    assert_non_null(strstr(d->message, "drive"));
    assert_near(d->lambda[0], 7.0, 0.0);
    vt_data_free(d);
    vt_model_free(m);

    /* the same body driven well: solvable */
    m = pendulum_with(1, 1.0);
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->route, VT_ROUTE_SQUARE);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_bad_definitions(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    body.parent = 1;
    body.joint = VT_JOINT_SPHERICAL;
    assert_int_equal(vt_builder_add_body(b, &body), 2);
    body.parent = 0;
    body.joint = VT_JOINT_BASE;
    assert_int_equal(vt_builder_add_body(b, &body), 3);

    vt_drive_def dr = vt_default_drive_def();
    dr.body = 4;
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_INDEX);
    dr.body = 1; dr.index = 1; /* a revolute joint has one rate */
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    dr.body = 2; dr.index = 0; /* spherical */
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    assert_non_null(strstr(vt_builder_message(b), "orientation drive"));
    dr.body = 3; dr.index = 4; /* a base body's Euler parameter */
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    dr = vt_default_drive_def();
    dr.type = VT_DRIVE_POINT; dr.index = 3;
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    dr.index = 0; dr.point[1] = NAN;
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_NONFINITE);
    dr = vt_default_drive_def();
    dr.f = vt_function_polynomial(VT_POLY_MAX + 1, NULL);
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    dr.f = vt_function_user(NULL, NULL);
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);
    dr = vt_default_drive_def();
    dr.type = VT_DRIVE_ORIENTATION; dr.axis[2] = 0.0;
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_AXIS_ZERO);
    dr.type = (vt_drive_type)9;
    assert_int_equal(vt_builder_add_drive(b, &dr), VT_ERR_BAD_DRIVE);

    vt_cut_joint_def cj = vt_default_cut_joint_def();
    cj.joint = VT_JOINT_BASE;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_BAD_CUT_JOINT);
    cj.joint = VT_JOINT_REVOLUTE; cj.body_a = 1; cj.body_b = 1;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_BAD_CUT_JOINT);
    cj.body_b = 7;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_BAD_INDEX);
    cj.body_b = 2; cj.axis1[2] = 0.0;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_AXIS_ZERO);
    cj = vt_default_cut_joint_def();
    cj.joint = VT_JOINT_UNIVERSAL; cj.axis2[2] = 1.0;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), VT_ERR_AXES_NOT_PERPENDICULAR);

    /* refused definitions left nothing behind: the first good ones get index 0 */
    assert_int_equal(vt_builder_add_drive(b, &(vt_drive_def){.type = VT_DRIVE_POINT, .body = 2, .index = 1,
                                                             .f = vt_function_constant(0.0)}), 0);
    cj = vt_default_cut_joint_def();
    cj.body_b = 2;
    assert_int_equal(vt_builder_add_cut_joint(b, &cj), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    assert_int_equal(m->ndrive, 1);
    assert_int_equal(m->ncut, 1);
    assert_int_equal(m->nc, 1 + 5 + 1); /* point drive, revolute cut, p^T p of the base body */
    vt_builder_free(b);
    vt_model_free(m);
}

/* A planar four-bar closed by a spatial revolute cut joint: rank 3 of 6 rows. Refused by
 * default; with allow_redundant the motion and the crank torque equal those of the exactly
 * constrained RSUR build of the same mechanism, the in-plane reactions too, and the
 * out-of-plane reaction components are reported as not unique (Wojtyra 2005). */
static void test_redundant_fourbar(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5};
    vt_model *strict, *red, *rsur;
    assert_ok(vt_scene_fourbar_planar(&strict, vt_function_polynomial(3, coef), 0));
    assert_ok(vt_scene_fourbar_planar(&red, vt_function_polynomial(3, coef), 1));
    assert_ok(vt_scene_fourbar(&rsur, vt_function_polynomial(3, coef)));
    vt_data *ds, *dr, *du;
    assert_ok(vt_data_create(&ds, strict));
    assert_ok(vt_data_create(&dr, red));
    assert_ok(vt_data_create(&du, rsur));
    for (double t = 0.0; t < 1.5; t += 0.31) {
        const double th2 = coef[0] + coef[1] * t + coef[2] * t * t, w2 = coef[1] + 2 * coef[2] * t;
        assert_int_equal(vt_scene_fourbar_planar_assemble(strict, ds, th2, w2), 0);
        assert_int_equal(vt_scene_fourbar_planar_assemble(red, dr, th2, w2), 0);
        double th[2], w[2];
        assert_int_equal(vt_scene_fourbar_assemble(rsur, du, th2, w2, th, w), 0);
        ds->time = dr->time = du->time = t;
        assert_int_equal(vt_inverse_dynamics(strict, ds), VT_ERR_DEPENDENT_CONSTRAINTS);
        assert_non_null(strstr(ds->message, "rank 3 of 6"));
        assert_ok(vt_inverse_dynamics(red, dr));
        assert_ok(vt_inverse_dynamics(rsur, du));
        assert_int_equal(dr->rank, 3);
        assert_int_equal(dr->route, VT_ROUTE_REDUNDANT);
        assert_int_equal(du->route, VT_ROUTE_SQUARE);
        assert_true(dr->warning & VT_WARN_REDUNDANT);
        assert_true(dr->residual < 1e-12);
        /* the motion: crank, coupler and rocker angular accelerations */
        const double a2 = dr->qdd[0], a3 = dr->qdd[0] + dr->qdd[1], a4 = a3 + dr->qdd[2];
        assert_near(a2, du->qdd[0], 1e-10);
        assert_near(a3, du->qdd[0] + du->qdd[3], 1e-10); /* RSUR: crank + spherical's z rate */
        assert_near(a4, du->qdd[4], 1e-10);
        /* the effort */
        assert_near(dr->drive_effort[0], du->drive_effort[0], 1e-9 * (1 + fabs(du->drive_effort[0])));
        assert_int_equal(dr->lambda_unique[0], 1); /* the drive's multiplier is unique */
        /* in-plane reactions: ground on crank, crank on coupler, ground on rocker */
        const double tol = 1e-9 * (1 + vt_test_maxabs(du->jnt_force, 12));
        for (int e = 0; e < 2; e++) {
            assert_near(dr->jnt_force[3 + e], du->jnt_force[3 + e], tol);
            assert_near(dr->jnt_force[6 + e], du->jnt_force[6 + e], tol);
            assert_near(dr->cut_force[e], du->jnt_force[9 + e], tol);
        }
        /* which components are unique: in-plane force and the moment about z are; the force
         * along z and the moments in the plane are not (at the cut and along the loop) */
        for (int i = 1; i <= 3; i++) {
            assert_int_equal(dr->jnt_unique[6 * i + 0], 1);
            assert_int_equal(dr->jnt_unique[6 * i + 1], 1);
            assert_int_equal(dr->jnt_unique[6 * i + 5], 1);
        }
        assert_int_equal(dr->cut_unique[2], 0);
        assert_true(dr->cut_unique[3] == 0 || dr->cut_unique[4] == 0);
        int free_rows = 0;
        for (int r = 0; r < red->nc; r++) free_rows += dr->lambda_unique[r] == 0;
        assert_true(free_rows >= 3);
    }
    vt_data_free(ds);
    vt_data_free(dr);
    vt_data_free(du);
    vt_model_free(strict);
    vt_model_free(red);
    vt_model_free(rsur);
}

/* IFToMM A04, Bricard's mechanism: six revolute joints on a loop of six links, Grübler count
 * 0, mobility 1. Closed by a revolute cut joint its Φ_q has rank 4 of 5 rows (5 of 6 with rod
 * 1 driven): refused by default, solved with allow_redundant; closed by a universal joint (4
 * independent rows) it is the non-redundant model of the same motion. Along a driven motion
 * (the positions by the kinematic solve, continued from the cube pose) the accelerations,
 * the drive's torque and every reaction component reported unique agree between the two;
 * the cut joint's moments about the axes the universal joint leaves free are not unique. */
static void test_bricard(void **state)
{
    (void)state;
    const vt_function f = vt_function_sine(0.0, -0.3, 1.5, 0.0);
    vt_model *red, *uni;
    vt_data *dr, *du;
    assert_ok(vt_scene_bricard(&red, VT_JOINT_REVOLUTE, 1, f));
    assert_ok(vt_scene_bricard(&uni, VT_JOINT_UNIVERSAL, 1, f));
    assert_int_equal(red->nc, 6);
    assert_int_equal(uni->nc, 5);
    assert_ok(vt_data_create(&dr, red));
    assert_ok(vt_data_create(&du, uni));
    for (int k = 0; k <= 20; k++) {
        dr->time = du->time = 0.05 * k;
        assert_ok(vt_kinematic_solve(red, dr, 1e-13, 30));
        assert_ok(vt_kinematic_solve(uni, du, 1e-13, 30));
        for (int j = 0; j < 5; j++) {
            assert_near(dr->q[j], du->q[j], 1e-10);
            assert_near(dr->qd[j], du->qd[j], 1e-10);
        }
        assert_ok(vt_inverse_dynamics(red, dr));
        assert_ok(vt_inverse_dynamics(uni, du));
        assert_int_equal(dr->rank, 5);
        assert_int_equal(dr->route, VT_ROUTE_REDUNDANT);
        assert_int_equal(du->route, VT_ROUTE_SQUARE);
        assert_true(dr->warning & VT_WARN_REDUNDANT);
        assert_false(du->warning & VT_WARN_REDUNDANT);
        assert_true(dr->residual < 1e-12);
        for (int j = 0; j < 5; j++) assert_near(dr->qdd[j], du->qdd[j], 1e-9 * (1 + vt_test_maxabs(du->qdd, 5)));
        assert_near(dr->drive_effort[0], du->drive_effort[0], 1e-9 * (1 + fabs(du->drive_effort[0])));
        assert_int_equal(dr->lambda_unique[0], 1);
        const double tol = 1e-8 * (1 + vt_test_maxabs(du->jnt_force, 18) + vt_test_maxabs(du->jnt_moment, 18));
        int nonunique = 0;
        for (int i = 1; i <= 5; i++)
            for (int c = 0; c < 3; c++) {
                if (dr->jnt_unique[6 * i + c]) assert_near(dr->jnt_force[3 * i + c], du->jnt_force[3 * i + c], tol);
                if (dr->jnt_unique[6 * i + 3 + c]) assert_near(dr->jnt_moment[3 * i + c], du->jnt_moment[3 * i + c], tol);
                nonunique += !dr->jnt_unique[6 * i + c] + !dr->jnt_unique[6 * i + 3 + c];
            }
        for (int c = 0; c < 3; c++)
            if (dr->cut_unique[c]) assert_near(dr->cut_force[c], du->cut_force[c], tol);
        assert_true(nonunique > 0);
        assert_true(dr->cut_unique[3 + 1] == 0 || dr->cut_unique[3 + 2] == 0);
        for (int c = 0; c < 6; c++) assert_int_equal(du->cut_unique[c], 1);
    }
    vt_data_free(dr);
    vt_data_free(du);
    vt_model_free(red);
    vt_model_free(uni);
}

/* as many rows as rates (the RSUR four-bar, the crank driven): (5) is solved through an LU of
 * Φ_q alone; against the whole augmented matrix by a general LU (dgesv), and its condition
 * reciprocal condition against the exact one of the scaled Φ_q (explicit inverse), squared */
/* a row that measures a length (a point or line row, or a joint drive on a translation); the
 * four-bar's and the arms' rows here: point rows of drives and cut joints, dot rows, rotation drives */
static int test_row_is_length(const vt_model *m, int r)
{
    return m->con_kind[r] == VT_ROW_POINT || m->con_kind[r] == VT_ROW_LINE;
}

static void test_square_constraints(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_fourbar(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0)));
    assert_int_equal(m->nc, m->nv);
    assert_ok(vt_data_create(&d, m));
    const int nv = m->nv, N = 2 * nv, one = 1;
    double K[400], x[20], A[100], Ainv[100];
    int ipiv[20], info = 0;
    for (double th = 0.2; th < 6.2; th += 0.7) {
        assert_int_equal(vt_scene_fourbar_assemble(m, d, th, 1.3, NULL, NULL), 0);
        assert_ok(vt_inverse_dynamics(m, d));
        assert_int_equal(d->route, VT_ROUTE_SQUARE);
        for (int c = 0; c < N; c++)
            for (int r = 0; r < N; r++) {
                double v = 0.0;
                if (r < nv && c < nv) v = d->Mstar[r + c * nv];
                else if (r >= nv && c < nv) v = d->Phiq[(r - nv) + c * nv];
                else if (r < nv && c >= nv) v = d->Phiq[(c - nv) + r * nv];
                K[r + c * N] = v;
            }
        for (int k = 0; k < nv; k++) {
            x[k] = d->Q[k];
            x[nv + k] = d->gamma[k];
        }
        dgesv_(&N, &one, K, &N, ipiv, x, &N, &info);
        assert_int_equal(info, 0);
        const double qs = 1.0 + vt_test_maxabs(x, nv), ls = 1.0 + vt_test_maxabs(x + nv, nv);
        for (int k = 0; k < nv; k++) {
            assert_near(d->qdd[k], x[k], 1e-11 * qs);
            assert_near(d->lambda[k], -x[nv + k], 1e-11 * ls);
        }
        /* exact 1-norm condition of G Φ_q C: rows in lengths by 1, in angles by ℓ; rates that turn
         * by 1/ℓ; ℓ the rows' lever arm (all of the four-bar's rates turn; its rows: the
         * crank's joint drive an angle, the cut joint's point rows lengths, its dot rows angles) */
        const double rho = vt_test_rows_length(m, d);
        double an = 0.0, in = 0.0;
        for (int c = 0; c < nv; c++) {
            double cs = 0.0;
            for (int r = 0; r < nv; r++) {
                A[r + c * nv] = d->Phiq[r + c * nv] / rho * (test_row_is_length(m, r) ? 1.0 : rho);
                Ainv[r + c * nv] = r == c;
                cs += fabs(A[r + c * nv]);
            }
            an = fmax(an, cs);
        }
        dgesv_(&nv, &nv, A, &nv, ipiv, Ainv, &nv, &info);
        assert_int_equal(info, 0);
        for (int c = 0; c < nv; c++) {
            double cs = 0.0;
            for (int r = 0; r < nv; r++) cs += fabs(Ainv[r + c * nv]);
            in = fmax(in, cs);
        }
        const double exact = 1.0 / (an * in);
        /* small systems get the exact condition (from the inverse), not an estimate */
        assert_near(d->rcond, exact * exact, 1e-9 * exact * exact);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* the augmented path's reciprocal condition (a free tree, nc = 0: M* q̈ = Q by the symmetric
 * indefinite factorization) against the exact 1-norm condition of the scaled matrix D M* D */
static void test_augmented_condition(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_random_tree(&m, 5, 5, VT_SCENE_SCALAR_JOINTS));
    assert_int_equal(m->nc, 0);
    assert_ok(vt_data_create(&d, m));
    uint64_t seed = 9;
    vt_scene_random_state(m, d, &seed);
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->route, VT_ROUTE_AUGMENTED);
    const int N = m->nv;
    assert_true(N <= 16);
    double K[256], X[256], an = 0.0, xn = 0.0;
    int ipiv[16], info = 0;
    for (int c = 0; c < N; c++)
        for (int r = 0; r < N; r++) {
            K[r + c * N] = d->Mstar[r + c * N] / sqrt(d->Mstar[r + r * N] * d->Mstar[c + c * N]);
            X[r + c * N] = r == c;
        }
    for (int c = 0; c < N; c++) {
        double cs = 0.0;
        for (int r = 0; r < N; r++) cs += fabs(K[r + c * N]);
        an = fmax(an, cs);
    }
    dgesv_(&N, &N, K, &N, ipiv, X, &N, &info);
    assert_int_equal(info, 0);
    for (int c = 0; c < N; c++) {
        double cs = 0.0;
        for (int r = 0; r < N; r++) cs += fabs(X[r + c * N]);
        xn = fmax(xn, cs);
    }
    assert_near(d->rcond, 1.0 / (an * xn), 1e-9 / (an * xn));
    vt_data_free(d);
    vt_model_free(m);
}

/* fewer rows than rates (a chain with a point drive at its tip: one row, S a number; a random
 * tree with two point drives, and the same tree with four, past the rows whose S is formed by
 * loops rather than BLAS; a chain with a joint drive beside a point drive, and one whose M* is
 * singular on a joint-driven rate): the Schur-complement solve against the whole augmented
 * matrix by a general LU (dgesv), and its reported condition against its definition computed
 * independently by LAPACK (vt_test_known_rcond: the joint-driven rates known, the exact 1-norm
 * condition of the other rows' S = Φ_oF M*_FF^-1 Φ_oF^T at unit diagonal times the squared ratio
 * of the smallest to the largest Cholesky pivot of M*_FF at unit diagonal, leaf first, times the
 * point drives' grip²); with no joint drive, by its formulas here too: S = Φ̃ M̃^-1 Φ̃^T, M̃ = D M* D,
 * Φ̃ = c Φ_q D */
static void test_schur(void **state)
{
    (void)state;
    for (int scene = 0; scene < 4; scene++) {
        vt_model *m;
        vt_data *d;
        if (scene == 0) {
            assert_ok(vt_scene_chain(&m, 6, VT_CHAIN_TIP_DRIVE));
        } else if (scene == 2) {
            /* M* singular: the third body is a point mass on its own joint's axis, its rate
             * fixed by a joint drive only, known: the Schur route solves on the other two */
            vt_builder *b;
            assert_ok(vt_builder_create(&b, NULL));
            vt_test_add_rods(b, 2, 1.0, (const double[2]){1.0, 1.0});
            vt_body_def dot = vt_default_body_def();
            dot.parent = 2;
            dot.joint_parent[0] = 0.5;
            assert_int_equal(vt_builder_add_body(b, &dot), 3);
            vt_drive_def dr = vt_default_drive_def();
            dr.body = 3;
            dr.f = vt_function_sine(0.0, 0.3, 2.0, 0.0);
            assert_int_equal(vt_builder_add_drive(b, &dr), 0);
            dr = vt_default_drive_def();
            dr.type = VT_DRIVE_POINT;
            dr.body = 2;
            dr.index = 1;
            dr.point[0] = 0.5;
            dr.f = vt_function_sine(0.5, 0.2, 1.0, 0.0);
            assert_int_equal(vt_builder_add_drive(b, &dr), 1);
            assert_ok(vt_builder_build(&m, b));
            vt_builder_free(b);
        } else {
            vt_builder *b;
            assert_ok(vt_builder_create(&b, NULL));
            assert_ok(vt_scene_random_bodies(b, 31, 6, VT_SCENE_SCALAR_JOINTS));
            for (int k = 0; k < (scene == 3 ? 4 : 2); k++) { /* scene 3: body 6's x, y, z and body 4's x */
                vt_drive_def dr = vt_default_drive_def();
                dr.type = VT_DRIVE_POINT;
                dr.body = k < 3 ? 6 : 4;
                dr.index = k % 3;
                dr.f = vt_function_sine(0.1, 0.2, 1.0 + k, 0.0);
                assert_true(vt_builder_add_drive(b, &dr) >= 0);
            }
            assert_ok(vt_builder_build(&m, b));
            vt_builder_free(b);
        }
        assert_ok(vt_data_create(&d, m));
        const int nv = m->nv, nc = m->nc, N = nv + nc, one = 1;
        assert_true(nc > 0 && nc < nv && N <= 20);
        if (scene == 3) assert_int_equal(nc, 4);
        if (scene == 0) {
            for (int k = 0; k < nv; k++) {
                double qdd;
                vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
            }
        } else if (scene == 2) {
            d->q[0] = 0.4;
            d->q[1] = 0.9;
            d->qd[0] = 0.3;
            d->qd[1] = -0.5;
            d->qd[2] = 0.6;
        } else {
            uint64_t seed = 3;
            vt_scene_random_state(m, d, &seed);
        }
        assert_ok(vt_inverse_dynamics(m, d));
        /* M* singular (scene 2) on the joint-driven rate only: the Schur route, no fallback */
        assert_int_equal(d->route, VT_ROUTE_SCHUR);
        assert_int_equal(d->fallback, 0);
        /* the augmented system, solved whole */
        double K[400], x[20], sc[20], L[256], P[64];
        int ipiv[20], info = 0;
        for (int c = 0; c < N; c++)
            for (int r = 0; r < N; r++) {
                double v = 0.0;
                if (r < nv && c < nv) v = d->Mstar[r + c * nv];
                else if (r >= nv && c < nv) v = d->Phiq[(r - nv) + c * nc];
                else if (r < nv) v = d->Phiq[(c - nv) + r * nc];
                K[r + c * N] = v;
            }
        for (int k = 0; k < nv; k++) x[k] = d->Q[k];
        for (int k = 0; k < nc; k++) x[nv + k] = d->gamma[k];
        dgesv_(&N, &one, K, &N, ipiv, x, &N, &info);
        assert_int_equal(info, 0);
        for (int k = 0; k < nv; k++) assert_near(d->qdd[k], x[k], 1e-10 * (1 + vt_test_maxabs(x, nv)));
        for (int k = 0; k < nc; k++) assert_near(d->lambda[k], -x[nv + k], 1e-10 * (1 + vt_test_maxabs(x + nv, nc)));
        /* its condition, by definition: with the joint-driven rates known */
        if (scene == 2) assert_true(d->Mstar[2 + 2 * nv] == 0.0);
        const double known = vt_test_known_rcond(m, d);
        assert_near(d->rcond, known, 1e-8 * known);
        if (scene == 1 || scene == 2) {
            vt_data_free(d);
            vt_model_free(m);
            continue;
        }
        /* and with no joint drive, from the formulas themselves */
        double rmax = 0.0;
        for (int a = 0; a < nv; a++) sc[a] = 1.0 / sqrt(d->Mstar[a + a * nv]);
        for (int r = 0; r < nc; r++) {
            double rn = 0.0;
            for (int c = 0; c < nv; c++) rn += pow(d->Phiq[r + c * nc] * sc[c], 2);
            rmax = fmax(rmax, sqrt(rn));
        }
        /* M* scaled to unit diagonal, its rates in descending order (leaf first: the articulated
         * pivots' order, the same number on the recursive path) */
        for (int c = 0; c < nv; c++)
            for (int r = 0; r < nv; r++) {
                const int rr = nv - 1 - r, cc = nv - 1 - c;
                L[r + c * nv] = d->Mstar[rr + cc * nv] * sc[rr] * sc[cc];
            }
        dpotrf_("L", &nv, L, &nv, &info, 1);
        assert_int_equal(info, 0);
        double lmin = 1e300, lmax = 0.0;
        for (int k = 0; k < nv; k++) {
            lmin = fmin(lmin, L[k + k * nv]);
            lmax = fmax(lmax, L[k + k * nv]);
        }
        /* S = P M̃^-1 P^T with P = Φ̃ (vt_test_schur_rcond: dgesv on copies) */
        double Mt[256];
        for (int c = 0; c < nv; c++)
            for (int r = 0; r < nv; r++) Mt[r + c * nv] = d->Mstar[r + c * nv] * sc[r] * sc[c];
        for (int r = 0; r < nc; r++)
            for (int a = 0; a < nv; a++) P[r + a * nc] = d->Phiq[r + a * nc] * sc[a] / rmax;
        const double expect = (lmin / lmax) * (lmin / lmax) * vt_test_schur_rcond(Mt, P, nv, nc) *
                              vt_test_grip2(m, d, vt_test_rows_length(m, d));
        assert_near(d->rcond, expect, 1e-8 * expect);
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* A spatial arm of three 1 m rods, 1 kg each (yaw about z at the origin, then two pitches about
 * the rods' y), its tip driven in x, y and z from rest with accelerations acc: the tip's
 * position at q is the closed form below, so the drives start on the pose. allow_redundant as
 * given. */
static vt_model *tip_driven_arm(const double q[3], const double acc[3], int allow_redundant)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = allow_redundant;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    for (int k = 0; k < 3; k++) {
        vt_body_def rod = vt_default_body_def();
        rod.parent = k;
        rod.mass = 1.0;
        rod.inertia[0] = 1e-3;
        rod.inertia[4] = rod.inertia[8] = 1.0 / 12.0;
        rod.joint_child[0] = -0.5;
        rod.joint_parent[0] = k ? 0.5 : 0.0;
        if (k) rod.axis1[1] = 1.0, rod.axis1[2] = 0.0;
        assert_int_equal(vt_builder_add_body(b, &rod), k + 1);
    }
    /* the tip in body 1's axes, (1 + cos q2 + cos(q2+q3), 0, −sin q2 − sin(q2+q3)), then the yaw */
    const double u = 1.0 + cos(q[1]) + cos(q[1] + q[2]), w = -sin(q[1]) - sin(q[1] + q[2]);
    const double p[3] = {cos(q[0]) * u, sin(q[0]) * u, w};
    for (int k = 0; k < 3; k++) {
        vt_drive_def tip = vt_default_drive_def();
        tip.type = VT_DRIVE_POINT;
        tip.body = 3;
        tip.index = k;
        tip.point[0] = 0.5;
        const double c[3] = {p[k], 0.0, 0.5 * acc[k]};
        tip.f = vt_function_polynomial(3, c);
        assert_int_equal(vt_builder_add_drive(b, &tip), k);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    return m;
}

/* The arm near (not at) full stretch, elbow bent by 1 mrad: a regular pose, ill-conditioned
 * (the scaled Φ_q's condition about 1e4). allow_redundant must not change the answer: the same
 * q̈ and drive forces as without it, to round-off, rank 3, the exact route; both against the
 * block rows of (5) solved by LAPACK's dgesv (Φ_q q̈ = γ, Φ_q^T λ = M* q̈ − Q), and the recursive
 * evaluation the same. (The former band of 1e-3 on singular values gave rank 2 and drive forces
 * of a few N instead of tens of kN.) */
static void test_regular_pose_with_redundant_option(void **state)
{
    (void)state;
    const double q[3] = {0.4, 0.3, 1e-3}, acc[3] = {0.3, -0.2, 0.5};
    vt_model *m[2];
    vt_data *d[2];
    for (int k = 0; k < 2; k++) {
        m[k] = tip_driven_arm(q, acc, k);
        assert_ok(vt_data_create(&d[k], m[k]));
        memcpy(d[k]->q, q, sizeof q);
        assert_ok(vt_inverse_dynamics(m[k], d[k]));
        assert_int_equal(d[k]->rank, 3);
        assert_int_equal(d[k]->route, VT_ROUTE_SQUARE);
        assert_false(d[k]->warning & (VT_WARN_REDUNDANT | VT_WARN_BAND));
    }
    if (!(d[0]->rcond < 1e-6)) fail_msg("rcond %g", d[0]->rcond); /* ill-conditioned indeed: below rcond_warn */
    assert_true(d[1]->warning & VT_WARN_ILL_CONDITIONED);
    /* the block rows of (5) by dgesv */
    const int n = 3, one = 1;
    int ipiv[3], info = 0;
    double A[9], x[3], At[9], lam[3];
    for (int k = 0; k < 9; k++) A[k] = d[0]->Phiq[k];
    memcpy(x, d[0]->gamma, sizeof x);
    dgesv_(&n, &one, A, &n, ipiv, x, &n, &info);
    assert_int_equal(info, 0);
    for (int r = 0; r < 3; r++) {
        lam[r] = -d[0]->Q[r];
        for (int c = 0; c < 3; c++) {
            lam[r] += d[0]->Mstar[r + 3 * c] * x[c];
            At[r + 3 * c] = d[0]->Phiq[c + 3 * r];
        }
    }
    dgesv_(&n, &one, At, &n, ipiv, lam, &n, &info);
    assert_int_equal(info, 0);
    const double qs = vt_test_maxabs(x, 3), fs = vt_test_maxabs(lam, 3);
    assert_true(fs > 1e3); /* tens of kN: what the nearly stretched arm needs */
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 3; c++) {
            assert_near(d[k]->qdd[c], x[c], 1e-9 * qs);
            assert_near(d[k]->drive_effort[c], lam[c], 1e-9 * fs);
            assert_near(d[1]->qdd[c], d[0]->qdd[c], 1e-12 * qs);
            assert_near(d[1]->drive_effort[c], d[0]->drive_effort[c], 1e-12 * fs);
        }
    /* the recursive evaluation decides alike */
    vt_data *dr;
    assert_ok(vt_data_create(&dr, m[1]));
    memcpy(dr->q, q, sizeof q);
    assert_ok(vt_inverse_dynamics_recursive(m[1], dr));
    assert_int_equal(dr->rank, 3);
    assert_false(dr->warning & (VT_WARN_REDUNDANT | VT_WARN_BAND));
    for (int c = 0; c < 3; c++) assert_near(dr->drive_effort[c], lam[c], 1e-9 * fs);
    vt_data_free(dr);
    for (int k = 0; k < 2; k++) {
        vt_data_free(d[k]);
        vt_model_free(m[k]);
    }
}

/* A planar two-link arm (1 m, 1 kg rods about z) whose tip is pulled along a line at angle th
 * from x, near full stretch (elbow e): the whole scene turned by th about z (the arm's first
 * angle, the gravity, the drives' targets). Into m and d, the state set. */
static void turned_arm(vt_model **m, vt_data **d, double th, double e)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = 1;
    md.gravity[0] = 9.81 * sin(th); /* (0, −9.81, 0) turned by th */
    md.gravity[1] = -9.81 * cos(th);
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    vt_test_add_rods(b, 2, 1.0, (const double[2]){1.0, 1.0});
    /* in the unturned scene the tip at (2 cos(e/2), 0) moves with velocity v and acceleration a;
     * the elbow's rate w2 and the first one's w1 give v */
    const double w1 = 0.3, w2 = -0.2, L = 2.0 * cos(0.5 * e);
    const double q1 = -0.5 * e, q2 = e;
    const double v[2] = {-(sin(q1) + sin(q1 + q2)) * w1 - sin(q1 + q2) * w2,
                         (cos(q1) + cos(q1 + q2)) * w1 + cos(q1 + q2) * w2};
    const double a[2] = {0.4, -0.7}, P[2] = {L, 0.0};
    for (int k = 0; k < 2; k++) {
        vt_drive_def tip = vt_default_drive_def();
        tip.type = VT_DRIVE_POINT;
        tip.body = 2;
        tip.index = k;
        tip.point[0] = 0.5;
        const double sgn = k ? 1.0 : -1.0, cs = cos(th), sn = sin(th);
        /* component k of R(th) (P + v t + a t²/2) */
        const double c[3] = {(k ? sn : cs) * P[0] + sgn * (k ? cs : sn) * P[1],
                             (k ? sn : cs) * v[0] + sgn * (k ? cs : sn) * v[1],
                             0.5 * ((k ? sn : cs) * a[0] + sgn * (k ? cs : sn) * a[1])};
        tip.f = vt_function_polynomial(3, c);
        assert_int_equal(vt_builder_add_drive(b, &tip), k);
    }
    assert_ok(vt_builder_build(m, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(d, *m));
    (*d)->q[0] = q1 + th;
    (*d)->q[1] = q2;
    (*d)->qd[0] = w1;
    (*d)->qd[1] = w2;
}

/* The decision does not depend on how the global axes lie: the two-link arm pulled along x and
 * the same scene turned by 0.5 rad have the same rank (2: regular, if ill-conditioned), the same
 * q̈, and drive forces turned by 0.5 rad. (The former rank test on Φ_q's row-normalized rows
 * dropped a direction in the turned scene only.) */
static void test_redundant_decision_frame_independent(void **state)
{
    (void)state;
    const double ths[2] = {0.0, 0.5}, e = 1e-3;
    vt_model *m[2];
    vt_data *d[2];
    for (int k = 0; k < 2; k++) {
        turned_arm(&m[k], &d[k], ths[k], e);
        assert_ok(vt_inverse_dynamics(m[k], d[k]));
        assert_int_equal(d[k]->rank, 2);
        assert_false(d[k]->warning & (VT_WARN_REDUNDANT | VT_WARN_BAND));
    }
    const double qs = vt_test_maxabs(d[0]->qdd, 2), fs = vt_test_maxabs(d[0]->drive_effort, 2);
    const double cs = cos(ths[1]), sn = sin(ths[1]), *F = d[0]->drive_effort;
    assert_true(fs > 10.0);
    for (int c = 0; c < 2; c++) assert_near(d[1]->qdd[c], d[0]->qdd[c], 1e-9 * qs);
    assert_near(d[1]->drive_effort[0], cs * F[0] - sn * F[1], 1e-9 * fs);
    assert_near(d[1]->drive_effort[1], sn * F[0] + cs * F[1], 1e-9 * fs);
    for (int k = 0; k < 2; k++) {
        vt_data_free(d[k]);
        vt_model_free(m[k]);
    }
}

/* The ODE form's band (vt_solve_run with vt_run_options.redundant_band) decides alike whatever
 * the global axes and the units: the two-link arm 1 mrad from stretch, pulled along x, along a
 * line at 0.5 rad, and along x in millimetres (lengths ×1e3, inertias ×1e6, gravity ×1e3), with
 * a band of 1e-2 that holds its nearly dependent direction: each drops it (VT_WARN_BAND, rank
 * still 2), with the same q̈ and the same drive forces, turned (and ×1e3 in mm: kg·mm/s²). With
 * band 0 each is solved exactly. */
static void test_band_frame_and_unit_independent(void **state)
{
    (void)state;
    vt_model *m[3];
    vt_data *d[3];
    turned_arm(&m[0], &d[0], 0.0, 1e-3);
    turned_arm(&m[1], &d[1], 0.5, 1e-3);
    { /* the first one in millimetres */
        vt_model_def md = vt_default_model_def();
        md.allow_redundant = 1;
        md.gravity[1] = -9810.0;
        vt_builder *b;
        assert_ok(vt_builder_create(&b, &md));
        for (int k = 0; k < 2; k++) {
            vt_body_def link = vt_default_body_def();
            link.parent = k;
            link.mass = 1.0;
            link.inertia[4] = link.inertia[8] = 1e6 / 12.0;
            link.joint_child[0] = -500.0;
            link.joint_parent[0] = k ? 500.0 : 0.0;
            assert_int_equal(vt_builder_add_body(b, &link), k + 1);
        }
        for (int k = 0; k < 2; k++) {
            vt_drive_def tip = m[0]->drive[k];
            tip.name = NULL;
            tip.point[0] = 500.0;
            for (int j = 0; j < 3; j++) tip.f.c[j] *= 1e3;
            assert_int_equal(vt_builder_add_drive(b, &tip), k);
        }
        assert_ok(vt_builder_build(&m[2], b));
        vt_builder_free(b);
        assert_ok(vt_data_create(&d[2], m[2]));
        memcpy(d[2]->q, d[0]->q, 2 * sizeof(double));
        memcpy(d[2]->qd, d[0]->qd, 2 * sizeof(double));
    }
    const double scale[3] = {1.0, 1.0, 1e3}, th[3] = {0.0, 0.5, 0.0};
    for (int band = 0; band < 2; band++) {
        double qdd[3][2], F[3][2];
        for (int k = 0; k < 3; k++) {
            assert_ok(vt_kinematics(m[k], d[k]));
            assert_ok(vt_mass_matrix(m[k], d[k]));
            assert_ok(vt_forces(m[k], d[k]));
            assert_ok(vt_constraints(m[k], d[k]));
            assert_ok(vt_solve_run(m[k], d[k], band ? 1e-2 : 0.0));
            assert_ok(vt_reactions(m[k], d[k]));
            assert_int_equal(d[k]->rank, 2);
            assert_int_equal((d[k]->warning & VT_WARN_BAND) != 0, band);
            /* forces back to N, along the unturned axes */
            const double c = cos(th[k]), s = sin(th[k]), *f = d[k]->drive_effort;
            F[k][0] = (c * f[0] + s * f[1]) / scale[k];
            F[k][1] = (-s * f[0] + c * f[1]) / scale[k];
            memcpy(qdd[k], d[k]->qdd, sizeof qdd[k]);
        }
        const double fs = fmax(fabs(F[0][0]), fabs(F[0][1])), qs = fmax(fabs(qdd[0][0]), fabs(qdd[0][1]));
        for (int k = 1; k < 3; k++)
            for (int c = 0; c < 2; c++) {
                assert_near(qdd[k][c], qdd[0][c], 1e-8 * qs);
                assert_near(F[k][c], F[0][c], 1e-8 * fs);
            }
    }
    for (int k = 0; k < 3; k++) {
        vt_data_free(d[k]);
        vt_model_free(m[k]);
    }
}

/* A planar arm of three rods (1 kg, 1 m, times u in length), its first joint driven (a row in
 * radians) and its tip in x and y (rows in length), links 2 and 3 10 mrad from stretch. */
static void mixed_arm(vt_model **m, vt_data **d, double u)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = 1;
    md.gravity[1] = -9.81 * u;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    for (int k = 0; k < 3; k++) {
        vt_body_def link = vt_default_body_def();
        link.parent = k;
        link.mass = 1.0;
        link.inertia[4] = link.inertia[8] = u * u / 12.0;
        link.joint_child[0] = -0.5 * u;
        link.joint_parent[0] = k ? 0.5 * u : 0.0;
        assert_int_equal(vt_builder_add_body(b, &link), k + 1);
    }
    const double q[3] = {0.3, 0.2, 1e-2}, w[3] = {0.5, -0.3, 0.2};
    const double a1 = q[0], a2 = q[0] + q[1], a3 = a2 + q[2], w1 = w[0], w2 = w1 + w[1], w3 = w2 + w[2];
    const double P[2] = {cos(a1) + cos(a2) + cos(a3), sin(a1) + sin(a2) + sin(a3)};
    const double V[2] = {-sin(a1) * w1 - sin(a2) * w2 - sin(a3) * w3, cos(a1) * w1 + cos(a2) * w2 + cos(a3) * w3};
    const double A[2] = {0.4, -0.7};
    vt_drive_def jd = vt_default_drive_def();
    const double cj[3] = {q[0], w[0], 0.5 * 0.9};
    jd.f = vt_function_polynomial(3, cj);
    assert_int_equal(vt_builder_add_drive(b, &jd), 0);
    for (int k = 0; k < 2; k++) {
        vt_drive_def tip = vt_default_drive_def();
        tip.type = VT_DRIVE_POINT;
        tip.body = 3;
        tip.index = k;
        tip.point[0] = 0.5 * u;
        const double c[3] = {u * P[k], u * V[k], 0.5 * u * A[k]};
        tip.f = vt_function_polynomial(3, c);
        assert_int_equal(vt_builder_add_drive(b, &tip), k + 1);
    }
    assert_ok(vt_builder_build(m, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(d, *m));
    memcpy((*d)->q, q, sizeof q);
    memcpy((*d)->qd, w, sizeof w);
}

/* Rows in radians and rows in metres weigh alike whatever the length unit: the arm above in
 * metres and in millimetres, with a band of 1e-2 that holds its nearly dependent direction in
 * the least-squares sense (a solution that depends on how the rows are weighted): the same q̈,
 * the tip forces ×1e3 and the joint torque ×1e6 in mm; and the same with no band (exact), with
 * the same condition estimate (the square route's G Φ_q C: it was 3.0e-6 in m and 4.7e-11 in mm
 * when the rates were scaled by the mass metric and the rows not at all). */
static void test_band_unit_independent_mixed_rows(void **state)
{
    (void)state;
    vt_model *m[2];
    vt_data *d[2];
    mixed_arm(&m[0], &d[0], 1.0);
    mixed_arm(&m[1], &d[1], 1e3);
    for (int band = 0; band < 2; band++) {
        for (int k = 0; k < 2; k++) {
            assert_ok(vt_kinematics(m[k], d[k]));
            assert_ok(vt_mass_matrix(m[k], d[k]));
            assert_ok(vt_forces(m[k], d[k]));
            assert_ok(vt_constraints(m[k], d[k]));
            const vt_status st = vt_solve_run(m[k], d[k], band ? 1e-2 : 0.0);
            if (st) fail_msg("unit %d band %d: %s", k, band, d[k]->message);
            assert_ok(vt_reactions(m[k], d[k]));
            assert_int_equal(d[k]->rank, 3);
            assert_int_equal((d[k]->warning & VT_WARN_BAND) != 0, band);
        }
        const double qs = vt_test_maxabs(d[0]->qdd, 3), fs = vt_test_maxabs(d[0]->drive_effort, 3);
        if (!band) assert_near(d[1]->rcond, d[0]->rcond, 1e-9 * d[0]->rcond); /* the estimate too */
        for (int c = 0; c < 3; c++) assert_near(d[1]->qdd[c], d[0]->qdd[c], 1e-8 * qs);
        assert_near(d[1]->drive_effort[0] * 1e-6, d[0]->drive_effort[0], 1e-8 * fs);
        for (int c = 1; c < 3; c++) assert_near(d[1]->drive_effort[c] * 1e-3, d[0]->drive_effort[c], 1e-8 * fs);
    }
    for (int k = 0; k < 2; k++) {
        vt_data_free(d[k]);
        vt_model_free(m[k]);
    }
}

/* After a failed solve no diagnostic of the previous call remains (rank, warning, rcond,
 * residual), on the dense and the recursive entry points: the redundant four-bar solved
 * (rank 3, VT_WARN_REDUNDANT), then a failing call on the same data. */
static void test_stale_diagnostics_cleared(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5};
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_fourbar_planar(&m, vt_function_polynomial(3, coef), 1));
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, 0.7, 1.1), 0);
    for (int entry = 0; entry < 2; entry++) {
        assert_ok(entry ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d));
        assert_int_equal(d->rank, 3);
        assert_true(d->warning & VT_WARN_REDUNDANT);
        assert_true(d->rcond > 0.0);
        vt_status st;
        if (entry == 0) { /* vt_solve itself, on a γ with a NaN */
            d->gamma[0] = NAN;
            st = vt_solve(m, d);
        } else {
            d->xfrc[6] = NAN;
            st = vt_inverse_dynamics_recursive(m, d);
            d->xfrc[6] = 0.0;
        }
        assert_int_equal(st, VT_ERR_NONFINITE);
        assert_int_equal(d->route, VT_ROUTE_NONE);
        assert_int_equal(d->warning, 0);
        assert_int_equal(d->rank, 0);
        assert_true(d->rcond == 0.0);
        assert_true(d->residual == 0.0);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* An ill-conditioned free chain (no rows: M* alone) is refused as such, not as a motion
 * without inertia: twelve planar rods, every other one 1 mm long and of 1 g (its two joints
 * turn the rest of the chain almost alike). With rcond_warn at 1e-11 the route on M* keeps
 * the instant: its reciprocal condition against the exact 1-norm one of D M* D (explicit
 * inverse by dgesv). With the defaults that estimate (1.6e-10) is below rcond_warn and the
 * maximal route solves too, with a higher estimate: its answer is kept, without a warning, and
 * agrees with the first to what the first's estimate allows. With rcond_min above both,
 * VT_ERR_SINGULAR says "ill-conditioned" with the first route's condition and names no body. */
static void test_ill_conditioned_message(void **state)
{
    (void)state;
    enum { N = 12 };
    double rc = 0.0, rcmax = 0.0, qdd[N];
    for (int pass = 0; pass < 3; pass++) {
        vt_model_def md = vt_default_model_def();
        if (pass == 0) md.rcond_warn = 1e-11;
        if (pass == 2) md.rcond_min = md.rcond_warn = fmin(1.0, 10.0 * fmax(rc, rcmax));
        vt_builder *b;
        assert_ok(vt_builder_create(&b, &md));
        for (int k = 0; k < N; k++) {
            const double L = k % 2 ? 1e-3 : 1.0, Lp = k % 2 ? 1.0 : 1e-3, mk = k % 2 ? 1e-3 : 1.0;
            vt_body_def link = vt_default_body_def();
            link.parent = k;
            link.mass = mk;
            link.inertia[4] = link.inertia[8] = mk * L * L / 12.0;
            link.joint_child[0] = -0.5 * L;
            link.joint_parent[0] = k ? 0.5 * Lp : 0.0;
            assert_int_equal(vt_builder_add_body(b, &link), k + 1);
        }
        vt_model *m;
        assert_ok(vt_builder_build(&m, b));
        vt_builder_free(b);
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        for (int k = 0; k < N; k++) d->q[k] = 0.3 * sin(k + 1.0);
        const vt_status st = vt_inverse_dynamics(m, d);
        if (pass == 0) {
            assert_ok(st);
            rc = d->rcond;
            double A[N * N], X[N * N], an = 0.0, xn = 0.0;
            int ipiv[N], info = 0;
            const int n = N;
            for (int c = 0; c < N; c++) {
                double cs = 0.0;
                for (int r = 0; r < N; r++) {
                    A[r + c * N] = d->Mstar[r + c * N] / sqrt(d->Mstar[r + r * N] * d->Mstar[c + c * N]);
                    X[r + c * N] = r == c;
                    cs += fabs(A[r + c * N]);
                }
                an = fmax(an, cs);
            }
            dgesv_(&n, &n, A, &n, ipiv, X, &n, &info);
            assert_int_equal(info, 0);
            for (int c = 0; c < N; c++) {
                double cs = 0.0;
                for (int r = 0; r < N; r++) cs += fabs(X[r + c * N]);
                xn = fmax(xn, cs);
            }
            assert_near(rc, 1.0 / (an * xn), 1e-6 * rc);
            if (!(rc < 1e-6)) fail_msg("rcond %g", rc);
            assert_int_equal(d->route, VT_ROUTE_AUGMENTED); /* no rows: (5) is M* alone */
            memcpy(qdd, d->qdd, sizeof qdd);
        } else if (pass == 1) {
            assert_ok(st);
            assert_int_equal(d->route, VT_ROUTE_MAXIMAL);
            assert_int_equal(d->fallback, VT_FALLBACK_MAXIMAL_CONDITION);
            assert_int_equal(d->warning, 0);
            rcmax = d->rcond;
            if (!(rcmax > 1e-6)) fail_msg("maximal route's rcond %g", rcmax);
            const double qs = vt_test_maxabs(d->qdd, N);
            for (int a = 0; a < N; a++) assert_near(qdd[a], d->qdd[a], 1e-14 / rc * qs);
        } else {
            assert_int_equal(st, VT_ERR_SINGULAR);
            assert_non_null(strstr(d->message, "ill-conditioned"));
            assert_non_null(strstr(d->message, "below rcond_min"));
            assert_null(strstr(d->message, "inertia:"));
            assert_null(strstr(d->message, "body"));
            assert_near(d->rcond, rc, 1e-9 * rc); /* what the failed route measured */
            assert_int_equal(d->warning, 0);
        }
        vt_data_free(d);
        vt_model_free(m);
    }
}

/* A planar arm of three 1 m, 1 kg rods along x, its last joint bent by e (q = (0, 0, e)), with
 *   square  its first joint driven and its tip in x and y: the rows fix the motion
 *   lone    its tip driven in x alone, two rates free
 * As e falls to 0 the rows lose their grip on the tip along x: both estimates fall (the square
 * route's with Φ_q's condition, about e²; the lone row's with its grip, e·V along x over |V|
 * for the rates' velocities V of the tip, about e²), warn below rcond_warn and fail at e = 0;
 * dense and recursive give the same estimate, the same in millimetres, and each against an
 * independent computation (vt_test_grip2 from the dense S; G Φ_q C by dgesv in
 * test_square_constraints). */
static void reach_arm(vt_model **m, vt_data **d, int lone, double e, double u)
{
    vt_model_def md = vt_default_model_def();
    md.gravity[1] = -9.81 * u;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    const double mass[3] = {1.0, 1.0, 1.0};
    vt_test_add_rods(b, 3, u, mass);
    if (!lone) {
        vt_drive_def jd = vt_default_drive_def();
        jd.f = vt_function_sine(0.0, 0.3, 1.0, 0.0);
        assert_int_equal(vt_builder_add_drive(b, &jd), 0);
    }
    for (int k = 0; k < (lone ? 1 : 2); k++) {
        vt_drive_def tip = vt_default_drive_def();
        tip.type = VT_DRIVE_POINT;
        tip.body = 3;
        tip.index = k;
        tip.point[0] = 0.5 * u;
        tip.f = vt_function_sine(0.0, 0.2 * u, 1.3, 0.4 * k);
        assert_true(vt_builder_add_drive(b, &tip) >= 0);
    }
    assert_ok(vt_builder_build(m, b));
    vt_builder_free(b);
    assert_ok(vt_data_create(d, *m));
    const double q[3] = {0.0, 0.0, e}, w[3] = {0.2, -0.1, 0.3};
    memcpy((*d)->q, q, sizeof q);
    memcpy((*d)->qd, w, sizeof w);
    (*d)->time = 0.3;
}

static void test_reach(void **state)
{
    (void)state;
    const double es[5] = {0.3, 1e-2, 1e-3, 1e-4, 0.0};
    for (int lone = 0; lone < 2; lone++) {
        double prev = 2.0;
        for (int k = 0; k < 5; k++) {
            vt_model *m, *mm;
            vt_data *d, *dr, *dm;
            reach_arm(&m, &d, lone, es[k], 1.0);
            reach_arm(&mm, &dm, lone, es[k], 1e3);
            assert_ok(vt_data_create(&dr, m));
            memcpy(dr->q, d->q, 3 * sizeof(double));
            memcpy(dr->qd, d->qd, 3 * sizeof(double));
            dr->time = d->time;
            const vt_status st = vt_inverse_dynamics(m, d), sr = vt_inverse_dynamics_recursive(m, dr);
            const vt_status sm = vt_inverse_dynamics(mm, dm);
            print_message("%s e = %g: rcond %.3g (%s), recursive %.3g, mm %.3g\n", lone ? "lone row" : "square", es[k],
                          d->rcond, vt_status_string(st), dr->rcond, dm->rcond);
            assert_int_equal(st, sr);
            assert_int_equal(st, sm);
            if (es[k] == 0.0) { /* at reach: refused */
                assert_true(st == VT_ERR_SINGULAR || st == VT_ERR_DEPENDENT_CONSTRAINTS);
            } else {
                assert_ok(st);
                assert_near(dr->rcond, d->rcond, 1e-6 * d->rcond);
                assert_near(dm->rcond, d->rcond, 1e-6 * d->rcond);
                assert_true(d->rcond < prev);
                prev = d->rcond;
                /* warns where it should: near reach, not at a bent pose */
                assert_int_equal((d->warning & VT_WARN_ILL_CONDITIONED) != 0, es[k] <= (lone ? 1e-3 : 1e-2));
                assert_int_equal(dr->warning, d->warning);
                if (lone) { /* the grip against its independent computation: the estimate is at most it */
                    const double g2 = vt_test_grip2(m, d, vt_test_rows_length(m, d));
                    assert_true(d->rcond <= g2 * (1.0 + 1e-9));
                    assert_true(g2 < 10.0 * es[k] * es[k] + 1e-300 || es[k] > 0.1);
                }
            }
            vt_data_free(d);
            vt_data_free(dr);
            vt_data_free(dm);
            vt_model_free(m);
            vt_model_free(mm);
        }
    }
}

/* q̈ by the null-space method, independent of vt_solve's routes: the first `rows` rows of Φ_q
 * by LAPACK's SVD (rank: σ above 1e-12 σ_max), q̈ = q_p + Z y with q_p the least-norm solution
 * of Φ_q q̈ = γ and Z its null space, (Z^T M* Z) y = Z^T (Q − M* q_p) by Cholesky. Returns the rank. */
static int nullspace_qdd(const vt_model *m, const vt_data *d, int rows, double *qdd)
{
    const int nv = m->nv, nc = m->nc;
    double A[64 * 16], S[16], U[64 * 64], VT[16 * 16], work[2048], qp[16], y[16], MZ[16 * 16], ZMZ[16 * 16];
    assert_true(nv <= 16 && rows <= 64 && rows >= 1);
    for (int c = 0; c < nv; c++)
        for (int r = 0; r < rows; r++) A[r + c * rows] = d->Phiq[r + c * nc];
    const int lw = 2048, k = rows < nv ? rows : nv;
    int info = 0;
    dgesvd_("A", "A", &rows, &nv, A, &rows, S, U, &rows, VT, &nv, work, &lw, &info, 1, 1);
    assert_int_equal(info, 0);
    int rank = 0;
    while (rank < k && S[rank] > 1e-12 * S[0]) rank++;
    for (int c = 0; c < nv; c++) qp[c] = 0.0;
    for (int i = 0; i < rank; i++) {
        double t = 0.0;
        for (int r = 0; r < rows; r++) t += U[r + i * rows] * d->gamma[r];
        for (int c = 0; c < nv; c++) qp[c] += VT[i + c * nv] * t / S[i];
    }
    const int nz = nv - rank; /* Z = rows rank.. of V^T, transposed */
    for (int c = 0; c < nv; c++) {
        double t = d->Q[c];
        for (int j = 0; j < nv; j++) t -= d->Mstar[c + j * nv] * qp[j];
        work[c] = t;
    }
    for (int i = 0; i < nz; i++) {
        double t = 0.0;
        for (int c = 0; c < nv; c++) t += VT[rank + i + c * nv] * work[c];
        y[i] = t;
        for (int c = 0; c < nv; c++) {
            double v = 0.0;
            for (int j = 0; j < nv; j++) v += d->Mstar[c + j * nv] * VT[rank + i + j * nv];
            MZ[c + i * nv] = v;
        }
    }
    for (int i = 0; i < nz; i++)
        for (int j = 0; j < nz; j++) {
            double v = 0.0;
            for (int c = 0; c < nv; c++) v += VT[rank + i + c * nv] * MZ[c + j * nv];
            ZMZ[i + j * nz] = v;
        }
    if (nz > 0) dpotrs_solve(nz, ZMZ, y);
    for (int c = 0; c < nv; c++) {
        double v = qp[c];
        for (int i = 0; i < nz; i++) v += VT[rank + i + c * nv] * y[i];
        qdd[c] = v;
    }
    return rank;
}

/* The rows' lever arm ℓ cannot collapse with the component a row measures (fuzz crash-cffa): a
 * point mass on a cylindrical joint whose axis n = (0, 1, δ)/|·| lies δ = 1e-3 off y, driven by
 * the y coordinates of two points 0.5 and 0.625 m from the axis along x. A turn about n moves a
 * point by |n × r| (0.5, 0.625 m a radian) but its y by only n_z r_x: Φ_q = [n_z 0.5, n_y;
 * n_z 0.625, n_y] is nearly singular, det −0.125 n_y n_z. The expected estimate is written here
 * from that closed form and the geometry's own length L = 0.625 m (the far point's distance from
 * the axis): κ₁(Φ_q diag(1/L, 1))^-2 (point rows measure lengths: G = 1). The old ℓ, the norm of
 * Φ_q's turning column (0.8 δ m), scaled that column to unit size and reported rcond 2e-2 without
 * a warning. Both paths must warn and report the same estimate. */
static void test_lever_arm_across_rows(void **state)
{
    (void)state;
    const double delta = 1e-3, xs[2] = {0.0, 0.125};
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    vt_body_def body = vt_default_body_def();
    body.joint = VT_JOINT_CYLINDRICAL;
    body.mass = 2.0;
    body.inertia[0] = body.inertia[4] = body.inertia[8] = 0.0; /* a point mass */
    body.axis1[0] = 0.0;
    body.axis1[1] = 1.0;
    body.axis1[2] = delta;
    body.joint_child[0] = -0.5;
    assert_int_equal(vt_builder_add_body(b, &body), 1);
    for (int k = 0; k < 2; k++) {
        vt_drive_def dr = vt_default_drive_def();
        dr.type = VT_DRIVE_POINT;
        dr.body = 1;
        dr.index = 1;
        dr.point[0] = xs[k];
        dr.f = vt_function_sine(0.0, 0.1, 2.0, 0.3 * k);
        assert_int_equal(vt_builder_add_drive(b, &dr), k);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    const double nn = sqrt(1.0 + delta * delta), ny = 1.0 / nn, nz = delta / nn, L = 0.625;
    const double P[4] = {nz * 0.5 / L, nz * 0.625 / L, ny, ny}; /* Φ_q diag(1/L, 1), column-major */
    const double det = P[0] * P[3] - P[2] * P[1];
    const double an = fmax(fabs(P[0]) + fabs(P[1]), fabs(P[2]) + fabs(P[3]));
    const double xn = fmax(fabs(P[3]) + fabs(P[1]), fabs(P[2]) + fabs(P[0])) / fabs(det); /* ‖P^-1‖₁ */
    const double expect = 1.0 / (an * xn * an * xn);
    for (int path = 0; path < 2; path++) {
        vt_data *d;
        assert_ok(vt_data_create(&d, m));
        d->qd[0] = 0.4;
        d->qd[1] = -0.1;
        const vt_status st = path ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
        if (st) fail_msg("path %d: %s (%s)", path, vt_status_string(st), d->message);
        assert_int_equal(d->route, VT_ROUTE_SQUARE);
        if (!(d->warning & VT_WARN_ILL_CONDITIONED)) fail_msg("path %d: no warning, rcond %.3g (expected %.3g)", path, d->rcond, expect);
        assert_near(d->rcond, expect, 1e-6 * expect);
        vt_data_free(d);
    }
    vt_model_free(m);
}

/* The fuzzer's three findings of the redundant route's rank (fuzz/corpus/crash-2690988dbc…,
 * crash-ee7f3a7f4a…, crash-28375274a4…), each with allow_redundant and without, against the
 * null-space method above:
 *  - a point mass on a free joint (no inertia, no extent: the radius of gyration that weighted the
 *    rows was round-off of zero, 9e-16 m), one translation joint-driven and its orientation driven: 4
 *    independent rows, solved alike with and without the option (it called them rank 1);
 *  - two base bodies falling freely, one turned by π about z with Euler parameters of 1e-100
 *    beside 1 (the Euler parameters' radial rate then has an inertia of 1e-198: the mass metric
 *    that weighted the rows made its p^T p − 1 row 1e99 and the other one dependent): 2
 *    independent rows, r̈ = g;
 *  - two links on spherical joints, a universal cut joint from the ground to link 2 whose
 *    axes are parallel at this state (link 2 turned by 90° about y): its dot row is round-off of
 *    zero (Φ_x itself a cross product of parallel vectors), a zero row. Without the option it is
 *    refused as dependent (it was scaled to a unit row and solved, q̈ of 1e15); with it q̈ holds
 *    the three point rows. */
static void test_redundant_rank_fuzz_findings(void **state)
{
    (void)state;
    for (int ex = 0; ex < 3; ex++)
        for (int red = 0; red < 2; red++) {
            vt_model_def md = vt_default_model_def();
            md.allow_redundant = red;
            vt_builder *b;
            assert_ok(vt_builder_create(&b, &md));
            vt_body_def bd = vt_default_body_def();
            if (ex == 0) {
                bd.joint = VT_JOINT_FREE;
                bd.mass = 0.7; /* m c / m rounds: a radius of gyration of 9e-16 m */
                bd.joint_child[0] = 0.5625, bd.joint_child[1] = 7.1875, bd.joint_child[2] = -3.375;
                assert_int_equal(vt_builder_add_body(b, &bd), 1);
                vt_drive_def jd = vt_default_drive_def();
                jd.body = 1;
                jd.index = 1;
                jd.f = vt_function_polynomial(3, (const double[3]){3.0, 0.5, -0.75});
                assert_int_equal(vt_builder_add_drive(b, &jd), 0);
                vt_drive_def od = vt_default_drive_def();
                od.type = VT_DRIVE_ORIENTATION;
                od.body = 1;
                od.axis[0] = 0.6, od.axis[1] = 0.0, od.axis[2] = 0.8;
                od.f = vt_function_polynomial(3, (const double[3]){0.0, 0.3, 0.2});
                assert_int_equal(vt_builder_add_drive(b, &od), 1);
            } else if (ex == 1) {
                bd.joint = VT_JOINT_BASE;
                bd.mass = 4.6;
                bd.inertia[0] = bd.inertia[4] = bd.inertia[8] = 7.3125;
                assert_int_equal(vt_builder_add_body(b, &bd), 1);
                bd.mass = 7.6;
                bd.inertia[0] = bd.inertia[4] = bd.inertia[8] = 1.8125;
                assert_int_equal(vt_builder_add_body(b, &bd), 2);
            } else {
                bd.joint = VT_JOINT_SPHERICAL;
                bd.inertia[0] = 0.1, bd.inertia[4] = 0.2, bd.inertia[8] = 0.25;
                bd.joint_child[0] = -0.5;
                assert_int_equal(vt_builder_add_body(b, &bd), 1);
                bd.parent = 1;
                bd.joint_parent[0] = 0.5;
                assert_int_equal(vt_builder_add_body(b, &bd), 2);
                vt_cut_joint_def cut = vt_default_cut_joint_def();
                cut.joint = VT_JOINT_UNIVERSAL;
                cut.body_a = 0;
                cut.body_b = 2;
                cut.point_a[0] = 2.0; /* global */
                cut.point_b[0] = 0.5;
                assert_int_equal(vt_builder_add_cut_joint(b, &cut), 0);
            }
            vt_model *m;
            assert_ok(vt_builder_build(&m, b));
            vt_builder_free(b);
            vt_data *d;
            assert_ok(vt_data_create(&d, m));
            for (int c = 0; c < m->nv; c++) d->qd[c] = 0.3 + 0.1 * c;
            if (ex == 0) {
                const double q[7] = {3, 3, 3, 0.5, 0.5, 0.5, 0.5};
                memcpy(d->q, q, sizeof q);
                d->time = 0.4;
            } else if (ex == 1) {
                const double q[14] = {-1.96875, 0.1125, -1.875, -0.957584, -0.245439, 0.0306799, 0.147821,
                                      0.95625, 0.2625, 0.39375, -7.4375e-100, -1.63125e-100, -2.25e-100, 1.0};
                memcpy(d->q, q, sizeof q);
            } else {
                /* link 1 turned generically (a), link 2 turned by 90° about y in all (g): its x axis
                 * along −z, the cut's axis1 on the ground, to round-off (q2 = a* ⊗ g, rounded) */
                const double h = sqrt(0.5), n1 = sqrt(0.9 * 0.9 + 0.04 + 0.09 + 0.0625);
                const double a[4] = {0.9 / n1, 0.2 / n1, -0.3 / n1, 0.25 / n1}, g[4] = {h, 0.0, h, 0.0};
                const double c[4] = {a[0], -a[1], -a[2], -a[3]};
                const double q[8] = {a[0], a[1], a[2], a[3],
                                     c[0] * g[0] - c[1] * g[1] - c[2] * g[2] - c[3] * g[3],
                                     c[0] * g[1] + g[0] * c[1] + c[2] * g[3] - c[3] * g[2],
                                     c[0] * g[2] + g[0] * c[2] + c[3] * g[1] - c[1] * g[3],
                                     c[0] * g[3] + g[0] * c[3] + c[1] * g[2] - c[2] * g[1]};
                memcpy(d->q, q, sizeof q);
            }
            const vt_status st = vt_inverse_dynamics(m, d);
            double ref[16];
            if (ex < 2) {
                if (st) fail_msg("example %d, allow_redundant %d: %s", ex, red, d->message);
                assert_int_equal(d->rank, m->nc);
                assert_int_equal(nullspace_qdd(m, d, m->nc, ref), m->nc);
            } else if (!red) {
                if (st != VT_ERR_DEPENDENT_CONSTRAINTS)
                    fail_msg("example 2 without the option: status %d (%s), q̈[0] %g", st, d->message, d->qdd[0]);
            } else {
                if (st) fail_msg("example 2, allow_redundant: %s", d->message);
                assert_int_equal(d->rank, 3);
                assert_int_equal(nullspace_qdd(m, d, 3, ref), 3); /* the point rows alone */
            }
            if (st == VT_OK) {
                const double qs = vt_test_maxabs(ref, m->nv);
                assert_true(qs > 0.1);
                for (int c = 0; c < m->nv; c++) assert_near(d->qdd[c], ref[c], 1e-10 * qs);
                if (ex == 1)
                    for (int bdy = 0; bdy < 2; bdy++) /* free fall */
                        for (int k = 0; k < 3; k++) assert_near(d->qdd[7 * bdy + k], md.gravity[k], 1e-12);
            }
            vt_data_free(d);
            vt_model_free(m);
        }
}

/* The Schur route's estimate below rcond_warn: the augmented route solves too and the answer with
 * the higher estimate is kept. Five planar rods of 0.4 m whose masses rise by 1e3 a rod (1e-6 …
 * 1e6 kg), the far end of rod 2 and the tip driven in x and y by point drives (4 rows, 5 rates:
 * vt_test_ratio_chain's drive 4): the rows fix the light rods' rates, whose pivots in the leaf-first Cholesky
 * of the whole M* are tiny, so the Schur estimate is 3.9e-10, the whole augmented matrix's
 * 1.5e-3: the augmented route's answer, flagged, no warning; and the Schur route's own answer,
 * with rcond_warn and rcond_min set below its estimate so that it is kept, agrees with it to
 * 1e-11 of q̈ and λ (two factorizations). A 100-link chain driven at its tip keeps the Schur route
 * (its estimate, 6.7e-7, above the whole matrix's): no fallback, and it warns. */
static void test_schur_condition_fallback(void **state)
{
    (void)state;
    vt_model *m = vt_test_ratio_chain(1, 4, 3.0);
    vt_data *d[2];
    for (int k = 0; k < 2; k++) {
        assert_ok(vt_data_create(&d[k], m));
        for (int a = 0; a < m->nv; a++) {
            d[k]->q[a] = 0.3 + 0.25 * a; /* test_mass_ratios' first state */
            d[k]->qd[a] = 0.5 - 0.2 * a;
        }
        if (k) m->rcond_warn = 1e-20, m->rcond_min = 1e-21; /* the Schur route keeps the instant (and no
                                                               * maximal route, from √rcond_warn down) */
        assert_ok(vt_inverse_dynamics(m, d[k]));
    }
    assert_int_equal(d[0]->route, VT_ROUTE_AUGMENTED);
    assert_int_equal(d[0]->fallback, VT_FALLBACK_SCHUR_CONDITION);
    assert_int_equal(d[0]->warning, 0);
    assert_true(d[0]->rcond > 1e-3);
    assert_int_equal(d[1]->route, VT_ROUTE_SCHUR);
    assert_int_equal(d[1]->fallback, 0);
    assert_true(d[1]->rcond < 1e-9);
    const double qs = vt_test_maxabs(d[0]->qdd, m->nv), ls = vt_test_maxabs(d[0]->lambda, m->nc);
    for (int a = 0; a < m->nv; a++) assert_near(d[1]->qdd[a], d[0]->qdd[a], 1e-11 * qs);
    for (int r = 0; r < m->nc; r++) assert_near(d[1]->lambda[r], d[0]->lambda[r], 1e-11 * ls);
    for (int k = 0; k < 2; k++) vt_data_free(d[k]);
    vt_model_free(m);

    assert_ok(vt_scene_chain(&m, 100, VT_CHAIN_TIP_DRIVE));
    assert_ok(vt_data_create(&d[0], m));
    for (int a = 0; a < m->nv; a++) {
        double qdd;
        vt_scene_chain_state(a, &d[0]->q[a], &d[0]->qd[a], &qdd);
    }
    assert_ok(vt_inverse_dynamics(m, d[0]));
    assert_int_equal(d[0]->route, VT_ROUTE_SCHUR);
    assert_int_equal(d[0]->fallback, 0);
    assert_int_equal(d[0]->warning, VT_WARN_ILL_CONDITIONED);
    vt_data_free(d[0]);
    vt_model_free(m);
}

/* A builder (allow_redundant as given) with body 1 on a spherical joint at the origin, its centre
 * at (1, 0, 0), 2 kg; its definition in one (the far-apart tests' first body) */
static vt_builder *sphere_at_origin(int allow_redundant, vt_body_def *one)
{
    vt_model_def md = vt_default_model_def();
    md.allow_redundant = allow_redundant;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, &md));
    *one = vt_default_body_def();
    one->joint = VT_JOINT_SPHERICAL;
    one->mass = 2.0;
    one->inertia[0] = 0.1, one->inertia[4] = one->inertia[8] = 0.5;
    one->joint_child[0] = -1.0;
    assert_int_equal(vt_builder_add_body(b, one), 1);
    return b;
}

/* A line row's lever arm includes the distance between its two points: two bodies on spherical
 * joints, one at the origin and one hung from a ground point D along y, joined by a cylindrical
 * cut joint whose axis (y) runs from one to the other, its points D − 2 m apart (4 rows: two
 * angles, two lines; 6 rates). Turning body 1 turns the line, which moves the measure at body 2's
 * point by D per radian: ℓ must hold D, else Φ̂'s line rows come out D/ℓ larger than its angle
 * rows and, past 1/ε, their directions drop out of the rank (D = 3e43: rank 2 of 4 with
 * allow_redundant, where the plain model solves). For D = 10, 1e6 and 1e20, at rest under
 * gravity and applied torques on the six rates: allow_redundant finds rank 4 and gives the plain model's q̈ and λ (to 1e-9 of
 * their largest), with the plain model's route and estimate. */
static void test_line_rows_far_apart(void **state)
{
    (void)state;
    const double Ds[3] = {10.0, 1e6, 1e20};
    for (int k = 0; k < 3; k++) {
        const double D = Ds[k];
        vt_model *m[2];
        vt_data *d[2];
        for (int red = 0; red < 2; red++) {
            vt_body_def one;
            vt_builder *b = sphere_at_origin(red, &one);
            vt_body_def two = one; /* centre at (0, D − 1, 0), joint at (0, D, 0) on the ground */
            two.mass = 3.0;
            two.joint_child[0] = 0.0, two.joint_child[1] = 1.0;
            two.joint_parent[1] = D;
            assert_int_equal(vt_builder_add_body(b, &two), 2);
            vt_cut_joint_def cut = vt_default_cut_joint_def();
            cut.joint = VT_JOINT_CYLINDRICAL;
            cut.body_a = 1, cut.body_b = 2;
            cut.point_a[0] = 1.0;                          /* (2, 0, 0) */
            cut.point_b[0] = 2.0, cut.point_b[1] = -1.0;   /* (2, D − 2, 0) */
            cut.axis1[0] = 0.0, cut.axis1[1] = 1.0, cut.axis1[2] = 0.0;
            cut.axis2[0] = 1.0, cut.axis2[1] = 0.0, cut.axis2[2] = 0.0;
            assert_true(vt_builder_add_cut_joint(b, &cut) >= 0);
            assert_ok(vt_builder_build(&m[red], b));
            vt_builder_free(b);
            assert_ok(vt_data_create(&d[red], m[red]));
            const double tau[6] = {1.0, -2.0, 0.5, 0.3, 0.0, 1.0}; /* N·m about the joints' axes */
            memcpy(d[red]->qfrc, tau, sizeof tau);
            const vt_status st = vt_inverse_dynamics(m[red], d[red]);
            if (st) fail_msg("D = %g, allow_redundant %d: %s", D, red, d[red]->message);
            assert_int_equal(m[red]->nc, 4);
            assert_int_equal(d[red]->rank, 4);
        }
        assert_int_equal(d[1]->route, d[0]->route);
        assert_near(d[1]->rcond, d[0]->rcond, 1e-9 * d[0]->rcond);
        const double qs = vt_test_maxabs(d[0]->qdd, m[0]->nv), ls = vt_test_maxabs(d[0]->lambda, 4);
        if (!(qs > 0.1 && ls > 1.0)) fail_msg("D = %g: q̈ %g, λ %g (route %d rcond %g)", D, qs, ls, d[0]->route, d[0]->rcond);
        for (int a = 0; a < m[0]->nv; a++) assert_near(d[1]->qdd[a], d[0]->qdd[a], 1e-9 * qs);
        for (int r = 0; r < 4; r++) assert_near(d[1]->lambda[r], d[0]->lambda[r], 1e-9 * ls);
        for (int red = 0; red < 2; red++) {
            vt_data_free(d[red]);
            vt_model_free(m[red]);
        }
    }
}

/* Point rows whose lever arms differ by 1e17 (the fuzzer's crash-7a3c08a1…): one body on a
 * spherical joint at the origin, two point drives, y of the body point (D, 0, 0.3) and x of
 * (0.2, 0.5, −0.4): rows [−0.3, 0, D] and [0, −0.4, −0.5] on the three turning rates, independent
 * at every D. The rank decision once scaled every row by one factor, the largest row's: the
 * second row came out 1e-17 of the first and fell below the rank's round-off (rank 1 with
 * allow_redundant, refused, where the plain model solves). Each row is now scaled by the size of
 * its own terms. For D = 10, 1e6 and 1e17: allow_redundant finds rank 2 and gives the plain
 * model's q̈ (to 1e-9 of its largest) and each drive's effort (to 1e-9 of itself). */
static void test_point_rows_far_apart(void **state)
{
    (void)state;
    const double Ds[3] = {10.0, 1e6, 1e17};
    for (int k = 0; k < 3; k++) {
        const double D = Ds[k];
        vt_model *m[2];
        vt_data *d[2];
        for (int red = 0; red < 2; red++) {
            vt_body_def one;
            vt_builder *b = sphere_at_origin(red, &one);
            const double pts[2][3] = {{D - 1.0, 0.0, 0.3}, {-0.8, 0.5, -0.4}}; /* from the centre */
            for (int j = 0; j < 2; j++) {
                vt_drive_def pd = vt_default_drive_def();
                pd.type = VT_DRIVE_POINT;
                pd.body = 1;
                pd.index = j ? 0 : 1;
                memcpy(pd.point, pts[j], sizeof pd.point);
                pd.f = vt_function_sine(0.0, 0.2, 1.5, 0.0);
                assert_int_equal(vt_builder_add_drive(b, &pd), j);
            }
            assert_ok(vt_builder_build(&m[red], b));
            vt_builder_free(b);
            assert_ok(vt_data_create(&d[red], m[red]));
            const double tau[3] = {1.0, -2.0, 0.5}, w[3] = {0.3, -0.2, 0.1};
            memcpy(d[red]->qfrc, tau, sizeof tau);
            memcpy(d[red]->qd, w, sizeof w);
            const vt_status st = vt_inverse_dynamics(m[red], d[red]);
            if (st) fail_msg("D = %g, allow_redundant %d: %s", D, red, d[red]->message);
            assert_int_equal(d[red]->rank, 2);
        }
        const double qs = vt_test_maxabs(d[0]->qdd, 3);
        print_message("D = %g: route %d, rcond %.3g; efforts %.17g %.17g and %.17g %.17g\n", D, d[0]->route, d[0]->rcond,
                      d[0]->drive_effort[0], d[1]->drive_effort[0], d[0]->drive_effort[1], d[1]->drive_effort[1]);
        for (int a = 0; a < 3; a++) assert_near(d[1]->qdd[a], d[0]->qdd[a], 1e-9 * qs);
        for (int j = 0; j < 2; j++) {
            assert_true(fabs(d[0]->drive_effort[j]) > 0.0);
            assert_near(d[1]->drive_effort[j], d[0]->drive_effort[j], 1e-9 * fabs(d[0]->drive_effort[j]));
        }
        for (int red = 0; red < 2; red++) {
            vt_data_free(d[red]);
            vt_model_free(m[red]);
        }
    }
}

/* A rate driven twice beside a point drive, on sliding joints along skew axes (the fuzzer's
 * crash-07a0f942 in a smaller tree): the dense Φ_q's joint rows are R S, exact to round-off only,
 * so the second drive's row keeps round-off on the other rates, and with the driven rate known
 * that round-off alone would be its row on the free rates, scaled to a unit row (VT_OK with q̈ of
 * 1e13 before). The rows are dependent by their kind: both paths refuse, naming them, and leave
 * q̈ and λ as they were. */
static void test_driven_twice_beside_rows(void **state)
{
    (void)state;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, NULL));
    const vt_joint_type joint[4] = {VT_JOINT_REVOLUTE, VT_JOINT_TRANSLATIONAL, VT_JOINT_TRANSLATIONAL, VT_JOINT_REVOLUTE};
    const double axis[4][3] = {{0, 0, 1}, {-1, -1, -1}, {-0.702145, -0.702145, 0.118256}, {1, 0, 0}};
    for (int i = 0; i < 4; i++) {
        vt_body_def body = vt_default_body_def();
        body.parent = i;
        body.joint = joint[i];
        body.mass = 1.0 + i;
        body.inertia[0] = body.inertia[4] = body.inertia[8] = 0.1 * (1 + i);
        memcpy(body.axis1, axis[i], sizeof axis[i]);
        body.joint_parent[0] = i ? 0.3 : 0.0, body.joint_parent[1] = i ? 0.2 : 0.0, body.joint_parent[2] = 0.1 * i;
        body.joint_child[0] = -0.2, body.joint_child[1] = 0.1, body.joint_child[2] = 0.3;
        assert_int_equal(vt_builder_add_body(b, &body), i + 1);
    }
    for (int k = 0; k < 3; k++) {
        vt_drive_def dr = vt_default_drive_def();
        dr.body = k < 2 ? 2 : 4;
        dr.type = k < 2 ? VT_DRIVE_JOINT : VT_DRIVE_POINT;
        dr.f = vt_function_sine(0.1, 0.2, 1.0 + k, 0.0);
        assert_int_equal(vt_builder_add_drive(b, &dr), k);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nv, 4);
    assert_int_equal(m->nc, 3);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    for (int recursive = 0; recursive < 2; recursive++) {
        const double q[4] = {0.3, 0.1, -0.2, 0.4}, qd[4] = {0.5, 0.2, -0.1, 0.3};
        memcpy(d->q, q, sizeof q);
        memcpy(d->qd, qd, sizeof qd);
        d->qdd[2] = 42.0;
        d->lambda[1] = 7.0;
        const vt_status st = recursive ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
        if (!recursive) { /* the case: round-off beside the second drive's unit entry */
            double off = 0.0;
            for (int c = 0; c < 4; c++)
                if (c != 1) off = fmax(off, fabs(d->Phiq[1 + 3 * c]));
            if (!(off > 0.0)) fail_msg("the dense joint row is exact here: the test does not test");
        }
        if (st != VT_ERR_DEPENDENT_CONSTRAINTS)
            fail_msg("recursive %d: %s (%s), q̈ %g", recursive, vt_status_string(st), d->message, d->qdd[2]);
        assert_non_null(strstr(d->message, "drive 0"));
        assert_non_null(strstr(d->message, "drive 1"));
        assert_near(d->qdd[2], 42.0, 0.0);
        assert_near(d->lambda[1], 7.0, 0.0);
    }
    vt_data_free(d);
    vt_model_free(m);
}

/* The redundant-row tests' body: one body on a cylindrical joint (isotropic inertia J about its
 * centre), allow_redundant, gravity −6.875 m/s² along y; md and bd as built, for the closed forms */
static vt_builder *cylinder_body(vt_model_def *md, vt_body_def *bd, double mass, double J, const double axis[3],
                                 const double jp[3], const double jc[3])
{
    *md = vt_default_model_def();
    md->allow_redundant = 1;
    md->gravity[0] = 0.0, md->gravity[1] = -6.875, md->gravity[2] = 0.0;
    vt_builder *b;
    assert_ok(vt_builder_create(&b, md));
    *bd = vt_default_body_def();
    bd->joint = VT_JOINT_CYLINDRICAL;
    bd->mass = mass;
    for (int k = 0; k < 9; k++) bd->inertia[k] = k % 4 == 0 ? J : 0.0;
    memcpy(bd->axis1, axis, 3 * sizeof(double));
    memcpy(bd->joint_parent, jp, 3 * sizeof(double));
    memcpy(bd->joint_child, jc, 3 * sizeof(double));
    assert_int_equal(vt_builder_add_body(b, bd), 1);
    return b;
}

/* A row far smaller than the rows it depends on (the fuzzer's crash-cf08ebee): one point mass on
 * a cylindrical joint whose axis is (8e-10, −0.6, 0.8), held by an orientation drive (three rows,
 * ω_x, ω_y, ω_z, all on the turning rate: rank 1), at rest; allow_redundant. The closed form:
 * the turning rate still, the sliding one falls with g · u, and the drive holds gravity's moment
 * about the axis: qfrc_drive = −u · (r × m g) on the turning rate (r from the axis to the mass),
 * 0 on the sliding one. The route once scaled each kept row to unit norm and took the multipliers
 * back through the dropped directions: the 8e-10 row grew 1e9-fold and the moment carried 1e9 ε
 * of round-off (1e-10 of itself; the fuzzer's state 1.9e-8 N·m on 200). */
static void test_redundant_tiny_dependent_row(void **state)
{
    (void)state;
    const double u0[3] = {8e-10, -0.6, 0.8}, jp[3] = {-7.0625, -4.1875, -7.0625}, jc[3] = {4.875, -4.875, 6.125};
    vt_model_def md;
    vt_body_def bd;
    vt_builder *b = cylinder_body(&md, &bd, 6.85, 0.0, u0, jp, jc);
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    od.body = 1;
    assert_int_equal(vt_builder_add_drive(b, &od), 0);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nv, 2);
    assert_int_equal(m->nc, 3);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->rank, 1);
    const double nu = sqrt(u0[0] * u0[0] + u0[1] * u0[1] + u0[2] * u0[2]);
    const double u[3] = {u0[0] / nu, u0[1] / nu, u0[2] / nu};
    double f[3], r[3], rf[3];
    for (int k = 0; k < 3; k++) f[k] = bd.mass * md.gravity[k], r[k] = -jc[k];
    rf[0] = r[1] * f[2] - r[2] * f[1], rf[1] = r[2] * f[0] - r[0] * f[2], rf[2] = r[0] * f[1] - r[1] * f[0];
    const double moment = u[0] * rf[0] + u[1] * rf[1] + u[2] * rf[2], fall = u[1] * md.gravity[1];
    if (!(fabs(d->qfrc_drive[0] + moment) <= 1e-13 * fabs(moment)))
        fail_msg("drive's moment %.17g, exact %.17g (%.3g apart)", d->qfrc_drive[0], -moment, d->qfrc_drive[0] + moment);
    assert_near(d->qfrc_drive[1], 0.0, 0.0);
    assert_near(d->qdd[0], 0.0, 1e-15);
    assert_near(d->qdd[1], fall, 1e-14 * fabs(fall));
    vt_data_free(d);
    vt_model_free(m);
}

/* Two equal point drives whose point lies on a turning rate's axis (the fuzzer's crash-0bd142b6):
 * a body on a cylindrical joint, both drives on the y of a point of the axis; allow_redundant
 * (rank 1 of 2). The dense Φ_q has round-off (1e-16) where the turning rate's entries are zero,
 * and the rows' lever arm ℓ that scales turning rates by 1/ℓ in the rank decision is round-off
 * too. The closed form: the point moves along the axis alone, q̈_1 = f'' / u_y; the sliding
 * rate's equation m q̈_1 − m g · u is the drives' generalized force on it; on the turning rate
 * the drives act by round-off only (the turning rate is free: J_u q̈_0 = u · (r × m g)). The
 * multipliers taken as Σ_k^-1 V_k^T C (M* q̈ − Q) carried the turning rate's round-off 1/ℓ-fold:
 * 4e-6 of the effort. */
static void test_redundant_rows_through_axis(void **state)
{
    (void)state;
    const double u0[3] = {0.606938, -0.513082, 0.606938}, jp[3] = {6.0625, -6.25, -4.8125}, jc[3] = {6.0625, 6.0625, 6.0625};
    vt_model_def md;
    vt_body_def bd;
    vt_builder *b = cylinder_body(&md, &bd, 5.1625, 6.0625, u0, jp, jc);
    const double nu = sqrt(u0[0] * u0[0] + u0[1] * u0[1] + u0[2] * u0[2]);
    const double u[3] = {u0[0] / nu, u0[1] / nu, u0[2] / nu};
    const double c2 = 1.4e5; /* f = 0.3 + 0.2 t + c2 t²: f'' = 2 c2 */
    for (int k = 0; k < 2; k++) {
        vt_drive_def dr = vt_default_drive_def();
        dr.type = VT_DRIVE_POINT;
        dr.body = 1;
        dr.index = 1;
        for (int c = 0; c < 3; c++) dr.point[c] = jc[c] + 2.5 * u[c]; /* on the axis (A = I at q = 0: body axes) */
        dr.f = vt_function_polynomial(3, (const double[3]){0.3, 0.2, c2});
        assert_int_equal(vt_builder_add_drive(b, &dr), k);
    }
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    d->q[0] = 1.81875, d->q[1] = 1.81875;
    d->qd[0] = 6.0625, d->qd[1] = 6.0625;
    d->time = 6.0625;
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->route, VT_ROUTE_REDUNDANT);
    assert_int_equal(d->rank, 1);
    const double g_u = md.gravity[1] * u[1], qdd1 = 2.0 * c2 / u[1], effort = bd.mass * (qdd1 - g_u);
    if (!(fabs(d->qdd[1] - qdd1) <= 1e-13 * fabs(qdd1))) fail_msg("q̈_1 %.17g, exact %.17g", d->qdd[1], qdd1);
    if (!(fabs(d->qfrc_drive[1] - effort) <= 1e-12 * fabs(effort)))
        fail_msg("the drives' force on the sliding rate %.17g, exact %.17g (%.3g apart)", d->qfrc_drive[1], effort,
                 d->qfrc_drive[1] - effort);
    /* on the turning rate: round-off of the drives' force times their lever about the axis */
    if (!(fabs(d->qfrc_drive[0]) <= 1e-12 * fabs(effort) * 12.0)) fail_msg("on the turning rate %.3g", d->qfrc_drive[0]);
    vt_data_free(d);
    vt_model_free(m);
}

/* A point mass on a cylindrical joint's axis, held by an orientation drive (three rows on the
 * turning rate) and a point drive on a point of the axis (the fuzzer's crash-1cff7a3e):
 * allow_redundant, rank 2 of 4. The point drive's entry on the turning rate is round-off (the
 * point lies on the axis), and so was the rows' lever arm ℓ (1e-15) until rows_length judged it
 * against its terms: the angle rows, weighed by ℓ, made the multipliers a cancellation of 1e15
 * (1 % of the efforts). The closed form: M*'s turning rate has no inertia, the orientation drive
 * takes the applied moment about the axis, −u · N; the sliding rate moves the point along the
 * axis, q̈_1 = f'' / u_y, its force m q̈_1 − m g · u. */
static void test_redundant_point_on_axis(void **state)
{
    (void)state;
    const double u0[3] = {-0.57735, -0.57735, -0.57735}, jpc[3] = {-2.8125, -2.8125, -2.8125};
    vt_model_def md;
    vt_body_def bd;
    vt_builder *b = cylinder_body(&md, &bd, 2.9125, 0.0, u0, jpc, jpc);
    const double nu = sqrt(u0[0] * u0[0] + u0[1] * u0[1] + u0[2] * u0[2]);
    const double u[3] = {u0[0] / nu, u0[1] / nu, u0[2] / nu}, c2 = -0.625;
    vt_drive_def pd = vt_default_drive_def();
    pd.type = VT_DRIVE_POINT;
    pd.body = 1;
    pd.index = 1;
    for (int k = 0; k < 3; k++) pd.point[k] = 6.0625; /* on the axis */
    pd.f = vt_function_polynomial(3, (const double[3]){0.1, 0.2, c2});
    assert_int_equal(vt_builder_add_drive(b, &pd), 0);
    vt_drive_def od = vt_default_drive_def();
    od.type = VT_DRIVE_ORIENTATION;
    od.body = 1;
    memcpy(od.axis, u0, sizeof u0);
    assert_int_equal(vt_builder_add_drive(b, &od), 1);
    vt_model *m;
    assert_ok(vt_builder_build(&m, b));
    vt_builder_free(b);
    assert_int_equal(m->nc, 4);
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    d->q[0] = -7.5, d->q[1] = -7.5;
    const double N[3] = {0.4, -1.1, 1.7};
    memcpy(d->xfrc + 9, N, sizeof N); /* body 1's applied moment */
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->route, VT_ROUTE_REDUNDANT);
    assert_int_equal(d->rank, 2);
    const double uN = u[0] * N[0] + u[1] * N[1] + u[2] * N[2];
    const double qdd1 = 2.0 * c2 / u[1], force = bd.mass * (qdd1 - md.gravity[1] * u[1]);
    if (!(fabs(d->qfrc_drive[0] + uN) <= 1e-12 * (fabs(uN) + fabs(force))))
        fail_msg("the drives' moment about the axis %.17g, exact %.17g", d->qfrc_drive[0], -uN);
    if (!(fabs(d->qfrc_drive[1] - force) <= 1e-12 * fabs(force)))
        fail_msg("the drives' force along the axis %.17g, exact %.17g", d->qfrc_drive[1], force);
    assert_near(d->qdd[1], qdd1, 1e-13 * fabs(qdd1));
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fully_joint_driven_chain),
        cmocka_unit_test(test_free_tree),
        cmocka_unit_test(test_square_constraints),
        cmocka_unit_test(test_augmented_condition),
        cmocka_unit_test(test_schur),
        cmocka_unit_test(test_failures),
        cmocka_unit_test(test_bad_definitions),
        cmocka_unit_test(test_redundant_fourbar),
        cmocka_unit_test(test_bricard),
        cmocka_unit_test(test_regular_pose_with_redundant_option),
        cmocka_unit_test(test_redundant_decision_frame_independent),
        cmocka_unit_test(test_band_frame_and_unit_independent),
        cmocka_unit_test(test_band_unit_independent_mixed_rows),
        cmocka_unit_test(test_line_rows_far_apart),
        cmocka_unit_test(test_point_rows_far_apart),
        cmocka_unit_test(test_driven_twice_beside_rows),
        cmocka_unit_test(test_redundant_tiny_dependent_row),
        cmocka_unit_test(test_redundant_rows_through_axis),
        cmocka_unit_test(test_redundant_point_on_axis),
        cmocka_unit_test(test_stale_diagnostics_cleared),
        cmocka_unit_test(test_ill_conditioned_message),
        cmocka_unit_test(test_reach),
        cmocka_unit_test(test_redundant_rank_fuzz_findings),
        cmocka_unit_test(test_lever_arm_across_rows),
        cmocka_unit_test(test_schur_condition_fallback),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
