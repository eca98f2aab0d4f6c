/* src/base/arena.c: the scratch arena inside the data. A stack: allocations on cache lines, released
 * to a mark in order, the same addresses again after a release; an allocation that does not fit
 * fails (and every later one until the release) with a message naming it, instead of writing
 * past the arena; every public entry point releases all it took, on success and on failure, on
 * every route; in AddressSanitizer builds what is not taken is poisoned (checked here with ASan's
 * own query; tests/arena_overrun.c overruns on purpose and must be stopped). */
#include "vt_test.h"

#include "base/arena.h"

#ifdef VT_ASAN
int __asan_address_is_poisoned(void const volatile *addr);
#endif

static void test_stack(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_chain(&m, 5, VT_CHAIN_TIP_DRIVE));
    assert_ok(vt_data_create(&d, m));
    const size_t m0 = vt_scratch_mark(d);
    assert_int_equal(m0, 0);
    double *a = VT_SCRATCH(d, double, 10, "a");
    int *b = VT_SCRATCH(d, int, 3, "b");
    assert_non_null(a);
    assert_non_null(b);
    assert_int_equal((uintptr_t)a % VT_DATA_ALIGN, 0);
    assert_int_equal((uintptr_t)b % VT_DATA_ALIGN, 0);
    assert_true((char *)b >= (char *)(a + 10)); /* no overlap */
    assert_int_equal((size_t)((char *)b - (char *)a), VT_SCRATCH_BYTES(10, sizeof(double)));
    for (int k = 0; k < 10; k++) a[k] = k; /* all of it is usable */
    for (int k = 0; k < 3; k++) b[k] = k;
    const size_t m1 = vt_scratch_mark(d);
    double *c = VT_SCRATCH(d, double, 1, "c");
    assert_ptr_equal(c, (double *)((char *)a + m1)); /* on top */
    vt_scratch_release(d, m1);
    assert_ptr_equal(VT_SCRATCH(d, double, 1, "c again"), c); /* the same place after a release */
    vt_scratch_release(d, m0);
    assert_int_equal(vt_scratch_mark(d), 0);
    assert_ptr_equal(VT_SCRATCH(d, double, 1, "a again"), a);
    vt_scratch_release(d, m0);
    vt_data_free(d);
    vt_model_free(m);
}

static void test_exhausted(void **state)
{
    (void)state;
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    const size_t size = d->arena->size;
    double *a = VT_SCRATCH(d, double, 4, "first");
    assert_non_null(a);
    assert_null(VT_SCRATCH(d, char, size, "too big")); /* does not fit beside `first` */
    assert_non_null(strstr(d->message, "too big"));
    assert_false(vt_scratch_ok(d));
    assert_null(VT_SCRATCH(d, double, 1, "small")); /* failed until the release */
    assert_null(VT_SCRATCH(d, double, (size_t)-1 / 4, "overflowing count"));
    vt_scratch_release(d, 0);
    assert_true(vt_scratch_ok(d));
    assert_non_null(VT_SCRATCH(d, char, size, "exactly all"));
    assert_null(VT_SCRATCH(d, char, 1, "one more"));
    vt_scratch_release(d, 0);
    /* the library keeps working after such a failure */
    d->q[0] = -0.7;
    assert_ok(vt_inverse_dynamics(m, d));
    assert_near(fabs(d->drive_effort[0]), 245.25 * cos(-0.7), 1e-10); /* the lock's torque, |τ2| of (29) */
    vt_data_free(d);
    vt_model_free(m);
}

/* after every entry point the arena is empty again: nothing stays taken, on any route, also
 * when the call fails */
static void assert_empty(const vt_data *d, const char *what)
{
    if (d->arena->top != 0) fail_msg("%s left %zu bytes taken", what, d->arena->top);
}

static void test_released_everywhere(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 9; seed++) { /* random trees: base bodies, every joint kind */
        vt_model *m;
        vt_data *d;
        assert_ok(vt_scene_random_tree(&m, seed, 10, seed % 2 ? VT_SCENE_ALL_JOINTS : VT_SCENE_NO_BASE));
        assert_ok(vt_data_create(&d, m));
        uint64_t s = seed;
        vt_scene_random_state(m, d, &s);
        assert_ok(vt_inverse_dynamics(m, d));
        assert_empty(d, "vt_inverse_dynamics");
        assert_ok(vt_inverse_dynamics_recursive(m, d));
        assert_empty(d, "vt_inverse_dynamics_recursive");
        if (seed % 2 == 0) { /* no base body: a given motion too */
            assert_ok(vt_inverse_dynamics_motion(m, d));
            assert_empty(d, "vt_inverse_dynamics_motion");
        }
        assert_ok(vt_inverse_transform(m, d));
        double *F = calloc((size_t)m->nx, sizeof(double)), *Q = calloc((size_t)m->nv, sizeof(double));
        assert_ok(vt_generalized_force(Q, m, d, d->F));
        assert_ok(vt_equivalent_force(F, m, d, Q));
        assert_empty(d, "the force transforms");
        free(F);
        free(Q);
        d->q[0] = NAN; /* a failure */
        assert_int_equal(vt_inverse_dynamics(m, d), VT_ERR_NONFINITE);
        assert_empty(d, "a failed instant");
        vt_data_free(d);
        vt_model_free(m);
    }
    const struct {
        int n, drives;
    } chains[] = {{6, VT_CHAIN_JOINT_DRIVEN}, {6, VT_CHAIN_TIP_DRIVE}};
    for (size_t c = 0; c < sizeof chains / sizeof *chains; c++) {
        vt_model *m;
        vt_data *d;
        assert_ok(vt_scene_chain(&m, chains[c].n, chains[c].drives));
        assert_ok(vt_data_create(&d, m));
        for (int k = 0; k < m->nv; k++) {
            double qdd;
            vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
        }
        assert_ok(vt_inverse_dynamics_recursive(m, d));
        assert_empty(d, "recursive chain");
        assert_ok(vt_inverse_dynamics(m, d));
        assert_empty(d, "dense chain");
        vt_data_free(d);
        vt_model_free(m);
    }
    /* the square route and the kinematic solve (Newton, dgels) */
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_fourbar(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0)));
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_scene_fourbar_assemble(m, d, 0.8, 1.1, NULL, NULL), 0);
    assert_ok(vt_inverse_dynamics_recursive(m, d));
    assert_int_equal(d->route, VT_ROUTE_SQUARE);
    assert_empty(d, "square route");
    d->time = 0.2;
    assert_ok(vt_kinematic_solve(m, d, 1e-12, 30));
    assert_empty(d, "vt_kinematic_solve");
    assert_int_equal(vt_kinematic_solve(m, d, 1e-12, 0), VT_ERR_BAD_OPTION);
    assert_empty(d, "a refused vt_kinematic_solve");
    vt_data_free(d);
    vt_model_free(m);
    /* the redundant route (SVD, dgelsd) */
    assert_ok(vt_scene_fourbar_planar(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0), 1));
    assert_ok(vt_data_create(&d, m));
    assert_int_equal(vt_scene_fourbar_planar_assemble(m, d, 0.7, 1.2), 0);
    assert_ok(vt_inverse_dynamics(m, d));
    assert_int_equal(d->route, VT_ROUTE_REDUNDANT);
    assert_empty(d, "redundant route");
    vt_data_free(d);
    vt_model_free(m);
}

/* AddressSanitizer builds: what is not taken is poisoned, what is taken is not, and the padding
 * after an allocation up to the next cache line stays poisoned */
static void test_poisoned(void **state)
{
    (void)state;
#ifdef VT_ASAN
    vt_model *m;
    vt_data *d;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_ok(vt_data_create(&d, m));
    double *a = VT_SCRATCH(d, double, 10, "a");
    assert_non_null(a);
    assert_false(__asan_address_is_poisoned(a));
    assert_false(__asan_address_is_poisoned(a + 9));
    assert_true(__asan_address_is_poisoned(a + 10)); /* past the end, in the cache line's padding */
    assert_true(__asan_address_is_poisoned(a + 16)); /* above the top */
    const size_t mark = vt_scratch_mark(d);
    double *b = VT_SCRATCH(d, double, 8, "b");
    assert_false(__asan_address_is_poisoned(b + 7));
    vt_scratch_release(d, mark);
    assert_true(__asan_address_is_poisoned(b)); /* released */
    assert_false(__asan_address_is_poisoned(a)); /* still taken */
    vt_scratch_release(d, 0);
    assert_true(__asan_address_is_poisoned(a));
    vt_data_free(d);
    vt_model_free(m);
#else
    skip(); /* an AddressSanitizer build checks this (CI's second run) */
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stack),
        cmocka_unit_test(test_exhausted),
        cmocka_unit_test(test_released_everywhere),
        cmocka_unit_test(test_poisoned),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
