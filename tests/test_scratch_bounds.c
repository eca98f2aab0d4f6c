/* Each source file's scratch bound (vt_<file>_scratch, the bytes it may take from the arena at
 * once) against what the arena measures (its peak, base/arena.h), over every scene of
 * examples/scenes.h and every route those scenes take: dense and recursive instants, the given
 * motion, the kinematic solve, fully and partly driven, trees and loops, redundant rows, free
 * bodies, couplings, planar pins. The bounds are hand-written from each file's allocations; the
 * peak is what the code really took. Per entry point (the public stage a file offers), the test
 * asserts
 *   peak ≤ Σ bounds of the files that entry point may pass through (the bound covers the use),
 *   the file's own bound ≤ factor × peak on the scene where it is tightest (not a gross
 *   over-estimate everywhere),
 * with factor 2 unless the row says why it is looser. A bound below its peak would let an
 * instant fail with "a sizing bug in vtdyn" on some other scene; one far above it costs every
 * data (every thread) memory for nothing. */
#include "vt_test.h"

#include "analysis/kinematic_solve.h"
#include "base/arena.h"
#include "dense/constraints.h"
#include "dense/forces.h"
#include "dense/mass.h"
#include "dense/reactions.h"
#include "dense/routes.h"
#include "dense/solve.h"
#include "kinematics/inverse_transform.h"
#include "kinematics/kinematics.h"
#include "numeric/kkt.h"
#include "numeric/maximal.h"
#include "numeric/rank.h"
#include "numeric/roundoff.h"
#include "recursive/recursive.h"

typedef size_t (*bound_fn)(const vt_model *m);
typedef vt_status (*entry_fn)(const vt_model *m, vt_data *d);

static vt_status kinematic_solve(const vt_model *m, vt_data *d)
{
    return vt_kinematic_solve(m, d, 1e-12, 30);
}

/* the maximal-coordinate route on its own (the solve offers it only at singular poses) */
static vt_status maximal(const vt_model *m, vt_data *d)
{
    if (!vt_maximal_size(m)) return VT_OK;
    double *sol = malloc(((size_t)m->nv + (size_t)m->nc) * sizeof(double)), rcond;
    assert_non_null(sol);
    const int r = vt_maximal_solve(m, d, sol, &rcond);
    free(sol);
    return r < 0 ? (vt_status)r : VT_OK;
}

enum { MAX_CHAIN = 16 };
typedef struct {
    const char *name;
    entry_fn entry;
    int dense_first;         /* run the dense stages before it (the stage reads their results) */
    bound_fn own[MAX_CHAIN]; /* the bounds of the entry point's own files (none: it takes no scratch itself) */
    bound_fn chain[MAX_CHAIN]; /* the files below it whose scratch it may hold at once */
    double factor;           /* its own bound ≤ factor × peak */
    const char *why;         /* where factor > 2 */
} entry_row;

/* clang-format off */
static const entry_row rows[] = {
    {"kinematics", vt_kinematics, 0, {vt_kinematics_scratch}, {NULL}, 2, NULL},
    {"inverse_transform", vt_inverse_transform, 1, {vt_inverse_transform_scratch}, {NULL}, 2, NULL},
    {"mass", vt_mass_matrix, 1, {vt_mass_scratch}, {NULL}, 2, NULL},
    {"forces", vt_forces, 1, {vt_forces_scratch}, {NULL}, 2, NULL},
    {"constraints", vt_constraints, 1, {vt_constraints_scratch}, {NULL}, 2, NULL},
    /* the solve's files together: its routes call the numeric kernels, none of which has an entry
     * point of its own */
    {"solve", vt_solve, 1, {vt_solve_scratch, vt_routes_scratch, vt_kkt_scratch, vt_rank_scratch, vt_roundoff_scratch},
     {vt_maximal_scratch}, 3,
     "the files' bounds are summed although a call holds the round-off check's and the rank decision's scratch "
     "only beside some routes, and the routes' bound is the largest route's with LAPACK's largest workspace query "
     "(dgelsd's) though each scene takes one route"},
    {"maximal", maximal, 1, {vt_maximal_scratch}, {NULL}, 2, NULL},
    {"reactions", vt_reactions, 1, {vt_reactions_scratch}, {NULL}, 2, NULL},
    {"instant (dense)", vt_inverse_dynamics, 0, {NULL}, {vt_kinematics_scratch, vt_inverse_transform_scratch,
        vt_mass_scratch, vt_forces_scratch, vt_constraints_scratch, vt_solve_scratch, vt_routes_scratch, vt_kkt_scratch,
        vt_rank_scratch, vt_roundoff_scratch, vt_maximal_scratch, vt_reactions_scratch}, 2, NULL},
    {"recursive", vt_inverse_dynamics_recursive, 0, {vt_recursive_scratch}, {vt_kinematics_scratch,
        vt_inverse_transform_scratch, vt_mass_scratch, vt_forces_scratch, vt_constraints_scratch, vt_solve_scratch,
        vt_routes_scratch, vt_kkt_scratch, vt_rank_scratch, vt_roundoff_scratch, vt_maximal_scratch,
        vt_reactions_scratch}, 2, NULL},
    {"kinematic_solve", kinematic_solve, 0, {vt_kinematic_solve_scratch}, {vt_recursive_scratch, vt_kinematics_scratch,
        vt_inverse_transform_scratch, vt_mass_scratch, vt_forces_scratch, vt_constraints_scratch, vt_solve_scratch,
        vt_routes_scratch, vt_kkt_scratch, vt_rank_scratch, vt_roundoff_scratch, vt_maximal_scratch,
        vt_reactions_scratch}, 2, NULL},
};
/* clang-format on */
enum { NROWS = (int)(sizeof rows / sizeof rows[0]), RECURSIVE_ROW = 9 };

/* per entry point, the scene where the bound is tightest (the smallest bound / peak) */
typedef struct {
    double ratio[NROWS]; /* 0: not measured yet */
    size_t peak[NROWS], bound[NROWS], sum[NROWS];
    const char *scene[NROWS];
} record;

static size_t own_bound(const entry_row *r, const vt_model *m)
{
    size_t s = 0;
    for (int k = 0; k < MAX_CHAIN && r->own[k]; k++) s += r->own[k](m);
    return s;
}

static size_t chain_bound(const entry_row *r, const vt_model *m)
{
    size_t s = own_bound(r, m);
    for (int k = 0; k < MAX_CHAIN && r->chain[k]; k++) s += r->chain[k](m);
    return s;
}

/* every entry point on d's state, each from an empty arena with the peak reset; the state is
 * restored before each so that every entry point sees the same input */
static void measure(record *rec, const char *scene, const vt_model *m, vt_data *d)
{
    const size_t nq = (size_t)m->nq, nv = (size_t)m->nv;
    double *q = malloc(nq * sizeof(double)), *qd = malloc(nv * sizeof(double)), *qdd = malloc(nv * sizeof(double));
    assert_non_null(q);
    assert_non_null(qd);
    assert_non_null(qdd);
    memcpy(q, d->q, nq * sizeof(double));
    memcpy(qd, d->qd, nv * sizeof(double));
    memcpy(qdd, d->qdd, nv * sizeof(double));
    const double t = d->time;
    for (int r = 0; r < NROWS; r++) {
        memcpy(d->q, q, nq * sizeof(double));
        memcpy(d->qd, qd, nv * sizeof(double));
        memcpy(d->qdd, qdd, nv * sizeof(double));
        d->time = t;
        if (rows[r].dense_first) {
            (void)vt_kinematics(m, d);
            (void)vt_inverse_transform(m, d);
            (void)vt_mass_matrix(m, d);
            (void)vt_forces(m, d);
            (void)vt_constraints(m, d);
            (void)vt_solve(m, d);
        }
        assert_int_equal(vt_scratch_mark(d), 0); /* every entry point released what it took */
        vt_scratch_peak_reset(d);
        (void)rows[r].entry(m, d); /* a failing instant takes scratch too: measured as well */
        assert_int_equal(vt_scratch_mark(d), 0);
        const size_t peak = vt_scratch_peak(d), bound = own_bound(&rows[r], m);
        const double ratio = peak ? (double)bound / (double)peak : 0.0;
        /* the tightest scene of its own bound; an entry point without one: its largest peak */
        if (rows[r].own[0] ? peak && (rec->ratio[r] == 0.0 || ratio < rec->ratio[r]) : peak > rec->peak[r]) {
            rec->ratio[r] = ratio;
            rec->peak[r] = peak;
            rec->bound[r] = bound;
            rec->sum[r] = chain_bound(&rows[r], m);
            rec->scene[r] = scene;
        }
        /* the coverage, at every scene (not only the worst one) */
        if (peak > chain_bound(&rows[r], m))
            fail_msg("%s on %s: the arena's peak %zu bytes exceeds the bounds' sum %zu", rows[r].name, scene, peak,
                     chain_bound(&rows[r], m));
    }
    /* the motion given (vt_inverse_dynamics_motion): the recursive file's bound covers it */
    memcpy(d->q, q, nq * sizeof(double));
    memcpy(d->qd, qd, nv * sizeof(double));
    memcpy(d->qdd, qdd, nv * sizeof(double));
    d->time = t;
    vt_scratch_peak_reset(d);
    (void)vt_inverse_dynamics_motion(m, d);
    assert_int_equal(vt_scratch_mark(d), 0);
    if (vt_scratch_peak(d) > chain_bound(&rows[RECURSIVE_ROW], m))
        fail_msg("motion on %s: the arena's peak %zu bytes exceeds the recursive bounds' sum %zu", scene,
                 vt_scratch_peak(d), chain_bound(&rows[RECURSIVE_ROW], m));
    /* the whole arena covers every entry point */
    assert_true(vt_scratch_peak(d) <= d->arena->size);
    memcpy(d->q, q, nq * sizeof(double));
    memcpy(d->qd, qd, nv * sizeof(double));
    memcpy(d->qdd, qdd, nv * sizeof(double));
    d->time = t;
    free(q);
    free(qd);
    free(qdd);
}

/* a scene at a few states: random rates and accelerations on its q (loops are assembled first by
 * the kinematic solve at t, where it converges; where it does not, the unassembled state still
 * exercises the stages) */
static void scene_states(record *rec, const char *scene, vt_model *m)
{
    vt_data *d;
    assert_ok(vt_data_create(&d, m));
    uint64_t seed = 0x9e3779b97f4a7c15u;
    for (int k = 0; k < 3; k++) {
        if (k > 0) vt_scene_random_state(m, d, &seed);
        d->time = 0.25 * k;
        if (m->nc > 0) (void)vt_kinematic_solve(m, d, 1e-12, 30);
        for (int a = 0; a < m->nv; a++) d->qdd[a] = 0.3 * (a % 5) - 0.5;
        measure(rec, scene, m, d);
    }
    vt_data_free(d);
    vt_model_free(m);
}

static void test_bounds(void **state)
{
    (void)state;
    static record rec; /* zeroed */
    vt_model *m;
    const vt_function crank = vt_function_polynomial(3, (const double[]){0.3, 2.0, 0.5});
#define SCENE(name, call)                                                                                              \
    do {                                                                                                               \
        assert_ok(call);                                                                                               \
        scene_states(&rec, name, m);                                                                                   \
    } while (0)
    SCENE("double link", vt_scene_double_link(&m, 0));
    SCENE("double link locked", vt_scene_double_link(&m, 1));
    SCENE("free joint driven", vt_scene_free_joint_driven(&m));
    for (int n = 1; n <= 40; n = n < 10 ? n + 3 : n * 2) {
        SCENE("chain free", vt_scene_chain(&m, n, VT_CHAIN_FREE));
        SCENE("chain joint-driven", vt_scene_chain(&m, n, VT_CHAIN_JOINT_DRIVEN));
        SCENE("chain tip-driven", vt_scene_chain(&m, n, VT_CHAIN_TIP_DRIVE));
    }
    SCENE("fourbar", vt_scene_fourbar(&m, crank));
    SCENE("fourbar planar", vt_scene_fourbar_planar(&m, crank, 0));
    SCENE("fourbar planar redundant", vt_scene_fourbar_planar(&m, crank, 1));
    SCENE("fourbar pin", vt_scene_fourbar_pin(&m, crank));
    SCENE("fourbar RUSR", vt_scene_fourbar_rusr(&m, crank));
    SCENE("slider crank", vt_scene_slider_crank(&m, crank, 0));
    SCENE("slider crank planar", vt_scene_slider_crank(&m, crank, 1));
    SCENE("five link", vt_scene_five_link(&m));
    SCENE("five link payload", vt_scene_five_link_payload(&m, 2.0, 1.0));
    SCENE("delta", vt_scene_delta(&m, 1.0, 1));
    SCENE("delta free", vt_scene_delta(&m, 1.0, 0));
    SCENE("pendulum", vt_scene_pendulum(&m));
    SCENE("nfourbar 3", vt_scene_nfourbar(&m, 3));
    SCENE("bricard universal", vt_scene_bricard(&m, VT_JOINT_UNIVERSAL, 1, crank));
    SCENE("bricard revolute", vt_scene_bricard(&m, VT_JOINT_REVOLUTE, 1, crank));
    SCENE("spherical chain", vt_scene_spherical_chain(&m, 0));
    SCENE("spherical chain relative", vt_scene_spherical_chain(&m, 1));
    for (uint64_t s = 1; s <= 12; s++) SCENE("random tree", vt_scene_random_tree(&m, s, 3 + (int)(s % 7), ~0u));
    vt_stewart sg = {2.0, 0.3, {{0}}}; /* the pose's phase rate and phase; the legs filled by the scene */
    SCENE("stewart", vt_scene_stewart(&m, &sg));
    SCENE("knee", vt_scene_knee(&m, crank, crank, 0));
    SCENE("knee planar", vt_scene_knee(&m, crank, crank, 1));
#undef SCENE
    print_message("%-18s %10s %10s %10s %6s  %s\n", "entry point", "own bound", "all bounds", "peak", "ratio",
                  "tightest scene");
    for (int r = 0; r < NROWS; r++) {
        const double ratio = rec.ratio[r];
        print_message("%-18s %10zu %10zu %10zu %6.2f  %s\n", rows[r].name, rec.bound[r], rec.sum[r], rec.peak[r], ratio,
                      rec.scene[r] ? rec.scene[r] : "-");
        if (rec.peak[r] && ratio > rows[r].factor)
            fail_msg("%s: its own bound %zu is %.2f times the peak %zu even where tightest (%s), more than %.1f", rows[r].name,
                     rec.bound[r], ratio, rec.peak[r], rec.scene[r], rows[r].factor);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
