/* No global mutable state: two threads, each with its own data struct on one shared model,
 * give results bitwise equal to a single-threaded run (an instant on a random tree with every
 * joint kind, and a dynamic analysis with IDA and its forward check); repeated runs are
 * bitwise reproducible. */
#include <pthread.h>

#include "vt_test.h"

typedef struct {
    const vt_model *tree, *dl;
    double *out;   /* results of this thread */
    int nout;
    int ok;
} job;

/* the work, writing everything it computes into out */
static int work(const vt_model *tree, const vt_model *dl, double *out)
{
    int k = 0;
    vt_data *d;
    if (vt_data_create(&d, tree)) return -1;
    for (int rep = 0; rep < 20; rep++) {
        uint64_t s = 5 + (uint64_t)rep;
        vt_scene_random_state(tree, d, &s);
        if (vt_inverse_dynamics(tree, d) || vt_inverse_transform(tree, d)) return -1;
        for (int c = 0; c < tree->nv; c++) out[k++] = d->qdd[c];
        for (int c = 0; c < 3 * (tree->nbody + 1); c++) out[k++] = d->jnt_force[c];
        for (int c = 0; c < tree->nv * tree->nv; c++) out[k++] = d->Mstar[c];
    }
    vt_data_free(d);
    vt_trajectory *tr;
    if (vt_data_create(&d, dl) || vt_trajectory_create(&tr, dl, 41)) return -1;
    vt_run_options o = vt_default_run_options();
    o.t1 = 1.0;
    o.nout = 40;
    if (vt_dynamic_analysis(dl, d, &o, tr)) return -1;
    for (int r = 0; r < tr->nfilled; r++) {
        out[k++] = tr->q[2 * r];
        out[k++] = tr->jnt_force[9 * r + 3];
        out[k++] = tr->q_fwd[2 * r];
    }
    vt_trajectory_free(tr);
    vt_data_free(d);
    return k;
}

static void *thread_main(void *arg)
{
    job *j = arg;
    j->nout = work(j->tree, j->dl, j->out);
    j->ok = j->nout > 0;
    return NULL;
}

static void test_two_threads_bitwise(void **state)
{
    (void)state;
    vt_model *tree, *dl;
    assert_ok(vt_scene_random_tree(&tree, 3, 12, VT_SCENE_ALL_JOINTS));
    assert_ok(vt_scene_double_link(&dl, 1));
    const size_t cap = 200000;
    double *ref = malloc(cap * sizeof(double)), *again = malloc(cap * sizeof(double));
    double *o1 = malloc(cap * sizeof(double)), *o2 = malloc(cap * sizeof(double));
    const int n = work(tree, dl, ref);
    assert_true(n > 0 && (size_t)n < cap);
    assert_int_equal(work(tree, dl, again), n); /* reproducible */
    assert_memory_equal(ref, again, (size_t)n * sizeof(double));
    job j1 = {tree, dl, o1, 0, 0}, j2 = {tree, dl, o2, 0, 0};
    pthread_t t1, t2;
    assert_int_equal(pthread_create(&t1, NULL, thread_main, &j1), 0);
    assert_int_equal(pthread_create(&t2, NULL, thread_main, &j2), 0);
    pthread_join(t1, NULL);
    pthread_join(t2, NULL);
    assert_true(j1.ok && j2.ok);
    assert_int_equal(j1.nout, n);
    assert_int_equal(j2.nout, n);
    assert_memory_equal(ref, o1, (size_t)n * sizeof(double));
    assert_memory_equal(ref, o2, (size_t)n * sizeof(double));
    free(ref); free(again); free(o1); free(o2);
    vt_model_free(tree);
    vt_model_free(dl);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_threads_bitwise),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
