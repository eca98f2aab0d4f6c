/* src/analysis/dae.c: the pieces of the DAE handed to IDA. The Hermite interpolant of recorded
 * steps reproduces a cubic; the blocks' sizes and ids per formulation; the residual F(t, y, y')
 * vanishes (to round-off) at a consistent state of the four-bar in every formulation that
 * takes y' from the state, and sees a wrong y'. */
#include <nvector/nvector_serial.h>

#include "vt_test.h"
#include "analysis/dae.h"

/* a cubic in t, one per coordinate, and its derivative */
static double cubic(int c, double t) { return 0.3 + c - 1.2 * t + (0.5 + c) * t * t - 0.7 * t * t * t; }
static double cubic_dt(int c, double t) { return -1.2 + 2.0 * (0.5 + c) * t - 2.1 * t * t; }

static void test_hermite_reproduces_a_cubic(void **state)
{
    (void)state;
    enum { CAP = 5, DIM = 2 };
    const double ts[CAP] = {0.0, 0.1, 0.35, 0.4, 1.0};
    double t[CAP], y[DIM * CAP], yp[DIM * CAP], tmp[DIM];
    vt_dae_history h = {.cap = CAP, .n = CAP, .dim = DIM, .t = t, .y = y, .yp = yp, .tmp = tmp};
    for (int k = 0; k < CAP; k++) {
        t[k] = ts[k];
        for (int c = 0; c < DIM; c++) {
            y[DIM * k + c] = cubic(c, ts[k]);
            yp[DIM * k + c] = cubic_dt(c, ts[k]);
        }
    }
    /* inside every interval, at the steps themselves and past both ends (extrapolated) */
    const double at[] = {-0.2, 0.0, 0.05, 0.1, 0.2, 0.36, 0.4, 0.77, 1.0, 1.3};
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        vt_dae_hermite(&h, at[i], tmp);
        for (int c = 0; c < DIM; c++) assert_near(tmp[c], cubic(c, at[i]), 1e-14);
    }
}

static void test_block_sizes_and_ids(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_fourbar(&m, vt_function_constant(0.0)));
    const int nq = m->nq, nv = m->nv, nc = m->nc;
    const int want[VT_FORMULATION_COUNT] = {nq + nv + nc, nq + nv + nc, nq + nv + nc, nq + nv + 2 * nc, nq + nv};
    double id[64];
    for (int form = 0; form < VT_FORMULATION_COUNT; form++) {
        const int n = vt_dae_block_size(m, form);
        assert_int_equal(n, want[form]);
        assert_true(n <= 64);
        vt_dae_block_ids(m, form, id);
        for (int k = 0; k < n; k++) assert_true(id[k] == (k < nq + nv ? 1.0 : 0.0));
    }
    vt_model_free(m);
}

/* the driven four-bar at a consistent state (Newton, then (5)): y, y' from it make F = 0 */
static void test_residual_at_a_consistent_state(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    SUNContext ctx;
    assert_ok(vt_scene_fourbar(&m, vt_function_sine(0.5, 0.6, 1.0, 0.0)));
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_scene_fourbar_assemble(m, d, 0.6, 1.0, NULL, NULL), 0);
    d->time = 0.0;
    assert_ok(vt_kinematic_solve(m, d, 1e-12, 30));
    assert_int_equal(SUNContext_Create(NULL, &ctx), 0);
    const int forms[3] = {VT_FORMULATION_INDEX1, VT_FORMULATION_BAUMGARTE, VT_FORMULATION_GGL};
    for (int f = 0; f < 3; f++) {
        const int n = vt_dae_block_size(m, forms[f]);
        double w[64];
        vt_dae p = {.m = m, .d = d, .msg = d, .form = forms[f], .alpha = 10.0, .beta = 10.0, .w = w};
        N_Vector y = N_VNew_Serial(n, ctx), yp = N_VNew_Serial(n, ctx), r = N_VNew_Serial(n, ctx);
        assert_non_null(r);
        vt_dae_block_initial(m, d, forms[f], N_VGetArrayPointer(y), N_VGetArrayPointer(yp));
        vt_dae_fresh(&p);
        assert_int_equal(vt_dae_residual(d->time, y, yp, r, &p), 0);
        for (int k = 0; k < n; k++) assert_near(N_VGetArrayPointer(r)[k], 0.0, 1e-9);
        /* a wrong acceleration shows in the equations of motion */
        N_VGetArrayPointer(yp)[m->nq] += 1.0;
        assert_int_equal(vt_dae_residual(d->time, y, yp, r, &p), 0);
        double worst = 0.0;
        for (int k = m->nq; k < m->nq + m->nv; k++) worst = fmax(worst, fabs(N_VGetArrayPointer(r)[k]));
        assert_true(worst > 1e-3);
        N_VDestroy(r);
        N_VDestroy(yp);
        N_VDestroy(y);
    }
    SUNContext_Free(&ctx);
    vt_data_free(d);
    vt_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hermite_reproduces_a_cubic),
        cmocka_unit_test(test_block_sizes_and_ids),
        cmocka_unit_test(test_residual_at_a_consistent_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
