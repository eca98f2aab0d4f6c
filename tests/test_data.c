/* src/analysis/data.c: data creation and reset, and data of another model refused. */
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




int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_reset_mismatch),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
