/* src/analysis/data.c, caller-provided memory (vt_data_init): the data of a model laid out in a static
 * buffer, and no allocator call at all while instants run in it (a firmware build never calls
 * malloc after start-up).
 *
 * This file is its own executable because it replaces malloc, calloc, realloc and free for the
 * whole process: its definitions come before the C library's (and AddressSanitizer's) in the
 * dynamic symbol search, so every call, from vtdyn, BLAS/LAPACK or the C library, reaches them;
 * they forward to the next definition (dlsym(RTLD_NEXT): glibc's, ASan's, or the one valgrind
 * substitutes for glibc's), so the test runs the same under the sanitizers and memcheck. While
 * armed they count every call and make every allocation fail (NULL), so an allocation in an
 * instant would show both as a count and as a failed call. A deliberate malloc through the
 * replaced symbol checks that the replacement is live before anything is trusted to it, and
 * the test fails if it is not. Two tools take malloc over themselves:
 * - valgrind memcheck replaces malloc in the executable too, unless told
 *   --soname-synonyms=somalloc=nouserintercepts: tests/meson.build puts that in VALGRIND_OPTS,
 *   so under `meson test --wrap=valgrind` the calls are counted and failed as without it. Run
 *   under valgrind without it (LD_PRELOAD names valgrind's vgpreload), the test says so and
 *   keeps every check but the counts.
 * - AddressSanitizer's interceptors (strdup and the like) allocate inside ASan without calling
 *   malloc: under ASan only direct calls are seen, which includes every call vtdyn could make.
 * ThreadSanitizer keeps its own allocator in the executable, which the replacement would take
 * over: under it the test is skipped (exit 77), said so (the plain, ASan and valgrind runs hold it).
 *
 * BLAS/LAPACK: this project uses reference BLAS/LAPACK (Debian libblas3/liblapack3), which does
 * not allocate. OpenBLAS, if it is the active alternative, may allocate its buffers at its
 * first call: every scene runs one instant (and the first test many LAPACK calls) before the
 * allocator is armed around instants.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>

#include "vt_test.h"

#if defined(__SANITIZE_THREAD__)
#define UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define UNDER_TSAN 1
#endif
#endif

#ifndef UNDER_TSAN

/* ---- the allocator, counted and made to fail ----------------------------------------- */

static void *(*real_malloc)(size_t);
static void *(*real_calloc)(size_t, size_t);
static void *(*real_realloc)(void *, size_t);
static void (*real_free)(void *);
static int armed;  /* count calls and fail allocations */
static int counting; /* count calls, and serve them */
static long calls; /* allocator calls while armed or counting */

/* dlsym may allocate (its error buffer) before the real functions are known: such calls are
 * served from this arena, and never freed to the real free. */
static _Alignas(max_align_t) unsigned char boot[4096];
static size_t boot_used;
static int resolving;

static void *boot_alloc(size_t n)
{
    const size_t a = (boot_used + 15u) & ~(size_t)15u;
    if (n > sizeof boot - a) return NULL;
    boot_used = a + n;
    return memset(boot + a, 0, n);
}

static int in_boot(const void *p)
{
    return (const unsigned char *)p >= boot && (const unsigned char *)p < boot + sizeof boot;
}

/* ISO C has no conversion from void * to a function pointer: copy the bits (POSIX guarantees
 * they are the address) */
static void next_symbol(void *fn, const char *name)
{
    void *p = dlsym(RTLD_NEXT, name);
    memcpy(fn, &p, sizeof p);
}

static int resolve(void)
{
    if (real_free) return 1;
    if (resolving) return 0;
    resolving = 1;
    next_symbol(&real_malloc, "malloc");
    next_symbol(&real_calloc, "calloc");
    next_symbol(&real_realloc, "realloc");
    next_symbol(&real_free, "free");
    resolving = 0;
    return real_malloc && real_calloc && real_realloc && real_free;
}

void *malloc(size_t n)
{
    if (counting) calls++;
    if (armed) {
        calls++;
        return NULL;
    }
    return resolve() ? real_malloc(n) : boot_alloc(n);
}

void *calloc(size_t k, size_t n)
{
    if (counting) calls++;
    if (armed) {
        calls++;
        return NULL;
    }
    if (!resolve()) return n && k > sizeof boot / n ? NULL : boot_alloc(k * n);
    return real_calloc(k, n);
}

void *realloc(void *p, size_t n)
{
    if (counting) calls++;
    if (armed) {
        calls++;
        return NULL;
    }
    if (in_boot(p)) { /* a boot block moves to the real heap (at most n bytes of it are kept) */
        const size_t left = (size_t)(boot + sizeof boot - (unsigned char *)p);
        void *q = malloc(n);
        if (q) memcpy(q, p, n < left ? n : left);
        return q;
    }
    return resolve() ? real_realloc(p, n) : NULL;
}

void free(void *p)
{
    if (armed || counting) calls++;
    if (!p || in_boot(p)) return;
    if (resolve()) real_free(p);
}

static int uncounted; /* valgrind took this file's malloc over: nothing can be counted */

/* Arms the allocator; checks first that a malloc call reaches this file's malloc. */
static void arm(void)
{
    void *(*volatile through)(size_t) = malloc; /* not a builtin call the compiler may drop */
    calls = 0;
    armed = 1;
    void *p = through(64);
    const long seen = calls;
    armed = 0;
    if (seen == 0 && under_valgrind()) {
        /* memcheck replaces malloc in the executable too, unless run with
         * --soname-synonyms=somalloc=nouserintercepts (tests/meson.build sets it in
         * VALGRIND_OPTS); without it the calls cannot be counted here, and the test keeps its
         * other checks (and memcheck's) */
        if (!uncounted)
            fprintf(stderr, "note: valgrind replaced this test's malloc (no "
                            "--soname-synonyms=somalloc=nouserintercepts): allocator calls not counted\n");
        uncounted = 1;
        free(p);
        calls = 0;
        return;
    }
    assert_null(p);
    assert_int_equal(seen, 1); /* the replacement is live */
    calls = 0;
    armed = 1;
}

/* Disarms and returns the calls seen while armed (assert only after this: CMocka's messages
 * may allocate). */
static long disarm(void)
{
    armed = 0;
    return calls;
}

/* ---- the scenes' buffers ------------------------------------------------------------- */

/* Generous: the double link needs about 12 KB, the four-bar about 22 KB (asserted below). */
static unsigned char buf_a[1 << 16], buf_b[1 << 16];

/* The outputs of an instant, copied out for a bitwise comparison. */
typedef struct outputs {
    double v[256];
    int n;
} outputs;

static void put(outputs *o, const double *a, int n)
{
    for (int k = 0; k < n && o->n < 256; k++) o->v[o->n++] = a[k];
}

static void collect(outputs *o, const vt_model *m, const vt_data *d)
{
    o->n = 0;
    const int nb = m->nbody + 1;
    put(o, d->qdd, m->nv);
    put(o, d->lambda, m->nc);
    put(o, d->drive_effort, m->ndrive);
    put(o, d->drive_force, 3 * m->ndrive);
    put(o, d->drive_moment, 3 * m->ndrive);
    put(o, d->jnt_force, 3 * nb);
    put(o, d->jnt_moment, 3 * nb);
    put(o, d->cut_force, 3 * m->ncut);
    put(o, d->cut_moment, 3 * m->ncut);
    put(o, d->q, m->nq);
    put(o, d->qd, m->nv);
}

static void assert_outputs_equal(const outputs *a, const outputs *b)
{
    assert_int_equal(a->n, b->n);
    assert_true(a->n < 256);
    for (int k = 0; k < a->n; k++)
        if (memcmp(&a->v[k], &b->v[k], sizeof(double)) != 0)
            fail_msg("output %d: %.17g (static buffer) != %.17g (vt_data_create)", k, a->v[k], b->v[k]);
}

/* ---- tests ---------------------------------------------------------------------------- */

/* Sizes, alignment, the too-small buffer, NULL arguments and vt_data_free. */
static void test_init_bounds(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_int_equal(vt_data_size(NULL), 0);
    const size_t need = vt_data_size(m);
    assert_true(need > sizeof(vt_data));
    assert_true(need <= sizeof buf_a - VT_DATA_ALIGN);
    const size_t exact = need - (VT_DATA_ALIGN - 1); /* what a VT_DATA_ALIGN-aligned start needs */
    unsigned char *aligned = buf_a + (VT_DATA_ALIGN - (uintptr_t)buf_a % VT_DATA_ALIGN) % VT_DATA_ALIGN;
    static unsigned char snapshot[sizeof buf_a];
    vt_data *d = (vt_data *)&d; /* not NULL: a failure must set it to NULL */

    /* too small, by one byte, at an aligned and at a misaligned start: status, nothing written */
    memset(buf_a, 0xA5, sizeof buf_a);
    memcpy(snapshot, buf_a, sizeof buf_a);
    assert_int_equal(vt_data_init(&d, m, aligned, exact - 1), VT_ERR_BAD_SIZE);
    assert_null(d);
    assert_int_equal(vt_data_init(&d, m, aligned + 1, need - 1), VT_ERR_BAD_SIZE);
    assert_int_equal(vt_data_init(&d, m, aligned + 1, 10), VT_ERR_BAD_SIZE); /* less than the padding */
    assert_int_equal(vt_data_init(&d, m, aligned, 0), VT_ERR_BAD_SIZE);
    assert_memory_equal(buf_a, snapshot, sizeof buf_a);
    assert_string_not_equal(vt_status_string(VT_ERR_BAD_SIZE), "unknown status");

    /* NULL arguments */
    d = (vt_data *)&d;
    assert_int_equal(vt_data_init(NULL, m, aligned, need), VT_ERR_NULL);
    assert_int_equal(vt_data_init(&d, NULL, aligned, need), VT_ERR_NULL);
    assert_null(d);
    assert_int_equal(vt_data_init(&d, m, NULL, need), VT_ERR_NULL);
    assert_memory_equal(buf_a, snapshot, sizeof buf_a);

    /* exactly enough at an aligned start; vt_data_size() enough at the worst start (one byte
     * past a boundary). Nothing outside [start, start + size) is written. */
    assert_ok(vt_data_init(&d, m, aligned, exact));
    assert_ptr_equal(d, aligned);
    assert_memory_equal(buf_a, snapshot, (size_t)(aligned - buf_a));
    assert_memory_equal(aligned + exact, snapshot + (aligned - buf_a) + exact, sizeof buf_a - (size_t)(aligned - buf_a) - exact);
    memset(buf_a, 0xA5, sizeof buf_a);
    assert_ok(vt_data_init(&d, m, aligned + 1, need));
    assert_ptr_equal(d, aligned + VT_DATA_ALIGN);
    assert_int_equal((uintptr_t)d % VT_DATA_ALIGN, 0);
    assert_memory_equal(buf_a, snapshot, (size_t)(aligned + 1 - buf_a));
    assert_memory_equal(aligned + 1 + need, snapshot + (aligned + 1 - buf_a) + need,
                        sizeof buf_a - (size_t)(aligned + 1 - buf_a) - need);
    /* every array inside the block, aligned for a double */
    const unsigned char *lo = (const unsigned char *)d, *hi = aligned + 1 + need;
    const void *arrays[] = {d->q, d->qd, d->xfrc, d->S, d->R, d->Mstar, d->lambda_null, d->jnt_unique, d->cut_unique, d->arena};
    for (size_t k = 0; k < sizeof arrays / sizeof *arrays; k++) {
        assert_true((const unsigned char *)arrays[k] > lo && (const unsigned char *)arrays[k] < hi);
        assert_int_equal((uintptr_t)arrays[k] % 16, 0);
    }

    /* the same data as vt_data_create(): state, the ground at identity, the same layout */
    vt_data *dc;
    assert_ok(vt_data_create(&dc, m));
    assert_ptr_equal(d->model, m);
    assert_null(d->block);
    assert_non_null(dc->block);
    for (int k = 0; k < m->nq; k++) assert_near(d->q[k], m->q0[k], 0.0);
    for (int k = 0; k < m->nv; k++) assert_near(d->qd[k], 0.0, 0.0);
    for (int k = 0; k < 9; k++) assert_near(d->A[k], k % 4 == 0 ? 1.0 : 0.0, 0.0);
    assert_near(d->time, 0.0, 0.0);
    assert_int_equal(d->message[0], '\0');
    assert_int_equal((char *)d->arena - (char *)d, (char *)dc->arena - (char *)dc); /* the scratch arena last */
    assert_int_equal((char *)d->cut_unique - (char *)d, (char *)dc->cut_unique - (char *)dc);
    assert_int_equal((char *)d->S - (char *)d, (char *)dc->S - (char *)dc);
    for (int k = 0; k < m->nx * m->nv; k++) assert_near(d->S[k], 0.0, 0.0); /* zeroed, the 0xA5 gone */

    /* vt_data_free on the caller's data releases nothing and writes nothing: the data stays usable */
    memcpy(snapshot, buf_a, sizeof buf_a);
    arm();
    vt_data_free(d);
    vt_data_free(NULL);
    assert_int_equal(disarm(), 0);
    assert_memory_equal(buf_a, snapshot, sizeof buf_a);
    assert_ok(vt_inverse_dynamics(m, d));
    vt_data_free(dc);
    vt_model_free(m);
}

/* The paper's double link with joint 2 locked, from a static buffer: many instants by both
 * evaluations with every allocation failing, bitwise equal to a vt_data_create()d run and to
 * the exact solution (29). */
static void test_double_link_no_allocation(void **state)
{
    (void)state;
    /* start-up: the model, the buffer, and a heap-allocated twin for the comparison */
    vt_model *m;
    vt_data *d, *dc;
    assert_ok(vt_scene_double_link(&m, 1));
    assert_true(vt_data_size(m) <= sizeof buf_a);
    arm();
    const vt_status init = vt_data_init(&d, m, buf_a, sizeof buf_a); /* allocates nothing either */
    assert_int_equal(disarm(), 0);
    assert_ok(init);
    assert_ok(vt_data_create(&dc, m));
    assert_ok(vt_inverse_dynamics(m, d)); /* warm-up (OpenBLAS would allocate here) */
    assert_ok(vt_inverse_dynamics_recursive(m, d));

    const int repeats = 100;
    for (double th = 0.0; th <= 1.5; th += 0.125) {
        const double s = sin(th), c = cos(th);
        outputs dense, rec, dense_c, rec_c;
        vt_status st[4] = {VT_OK, VT_OK, VT_OK, VT_OK};
        arm();
        for (int r = 0; r < repeats; r++) {
            vt_data *dd[2] = {d, dc};
            for (int k = 0; k < 2; k++) {
                dd[k]->q[0] = -th;
                dd[k]->q[1] = 0.0;
                dd[k]->qd[0] = -sqrt(7.3575 * s); /* θ̇² = 7.3575 sin θ */
                dd[k]->qd[1] = 0.0;
                st[2 * k] |= vt_inverse_dynamics(m, dd[k]);
                collect(k ? &dense_c : &dense, m, dd[k]);
                st[2 * k + 1] |= vt_inverse_dynamics_recursive(m, dd[k]);
                collect(k ? &rec_c : &rec, m, dd[k]);
                st[2 * k + 1] |= vt_inverse_dynamics_motion(m, dd[k]); /* q̈ of the recursive instant, given */
            }
        }
        const long n = disarm();
        assert_int_equal(n, 0);
        for (int k = 0; k < 4; k++) assert_ok(st[k]);
        assert_outputs_equal(&dense, &dense_c);
        assert_outputs_equal(&rec, &rec_c);
        /* independent: θ̈ = 3.67875 cos θ, (29), the locking torque 245.25 cos θ */
        const outputs *o[2] = {&dense, &rec};
        for (int k = 0; k < 2; k++) {
            const double *qdd = o[k]->v, *effort = qdd + 3, *f1 = effort + 7 + 3;
            assert_near(-qdd[0], 3.67875 * c, 1e-10 * 3.67875);
            assert_near(qdd[1], 0.0, 1e-10 * 3.67875);
            assert_near(fabs(effort[0]), 245.25 * c, 1e-10 * 245.25);
            assert_near(f1[0], -2207.25 * sin(2 * th), 1e-10 * 4905.0);
            assert_near(f1[1], 4905.0 * s * s + 490.5 * c * c, 1e-10 * 4905.0);
            assert_near(f1[2], 0.0, 1e-10 * 4905.0);
        }
    }
    vt_data_free(d); /* a no-op, as for any caller's buffer */
    vt_data_free(dc);
    vt_model_free(m);
}

/* The four-bar (a loop: LAPACK's symmetric indefinite solve of (5)) from a static buffer:
 * both evaluations and the kinematic solve with every allocation failing, bitwise equal to a
 * vt_data_create()d run; the kinematic solve, started off the loop, lands on the planar
 * closed-form assembly. */
static void test_fourbar_no_allocation(void **state)
{
    (void)state;
    const double coef[3] = {0.3, 2.0, 1.5}; /* θ2 = 0.3 + 2 t + 1.5 t² */
    vt_model *m;
    vt_data *d, *dc;
    assert_ok(vt_scene_fourbar(&m, vt_function_polynomial(3, coef)));
    assert_int_equal(m->nc, m->nv); /* fully driven: vt_kinematic_solve applies */
    assert_true(vt_data_size(m) <= sizeof buf_b);
    assert_true(m->nq + m->nv <= 64);
    assert_ok(vt_data_init(&d, m, buf_b, sizeof buf_b));
    assert_ok(vt_data_create(&dc, m));
    assert_int_equal(vt_scene_fourbar_assemble(m, d, 0.3, 2.0, NULL, NULL), 0);
    assert_ok(vt_kinematic_solve(m, d, 1e-13, 30)); /* warm-up */

    for (double t = 0.0; t < 2.0; t += 0.17) {
        const double th2 = coef[0] + coef[1] * t + coef[2] * t * t, w2 = coef[1] + 2 * coef[2] * t;
        double q_exact[64], qd_exact[64];
        assert_int_equal(vt_scene_fourbar_assemble(m, d, th2, w2, NULL, NULL), 0);
        memcpy(q_exact, d->q, (size_t)m->nq * sizeof(double));
        memcpy(qd_exact, d->qd, (size_t)m->nv * sizeof(double));
        outputs dense, rec, kin, dense_c, rec_c, kin_c;
        vt_status st[6] = {VT_OK, VT_OK, VT_OK, VT_OK, VT_OK, VT_OK};
        arm();
        for (int r = 0; r < 20; r++) {
            vt_data *dd[2] = {d, dc};
            for (int k = 0; k < 2; k++) {
                memcpy(dd[k]->q, q_exact, (size_t)m->nq * sizeof(double));
                memcpy(dd[k]->qd, qd_exact, (size_t)m->nv * sizeof(double));
                dd[k]->time = t;
                st[3 * k] |= vt_inverse_dynamics(m, dd[k]);
                collect(k ? &dense_c : &dense, m, dd[k]);
                st[3 * k + 1] |= vt_inverse_dynamics_recursive(m, dd[k]);
                collect(k ? &rec_c : &rec, m, dd[k]);
                /* off the loop by a few mm and mrad, then Newton back onto it */
                for (int j = 0; j < m->nq; j++) dd[k]->q[j] += 3e-3 * sin(1.0 + j);
                for (int j = 0; j < m->nv; j++) dd[k]->qd[j] += 1e-2 * cos(1.0 + j);
                st[3 * k + 2] |= vt_kinematic_solve(m, dd[k], 1e-13, 30);
                collect(k ? &kin_c : &kin, m, dd[k]);
            }
        }
        assert_int_equal(disarm(), 0);
        for (int k = 0; k < 6; k++) assert_ok(st[k]);
        assert_outputs_equal(&dense, &dense_c);
        assert_outputs_equal(&rec, &rec_c);
        assert_outputs_equal(&kin, &kin_c);
        /* the two evaluations agree (tests/test_recursive.c holds them to 1e-12) */
        for (int k = 0; k < dense.n; k++) assert_near(rec.v[k], dense.v[k], 1e-12 * (1 + fabs(dense.v[k])));
        /* independent: Newton lands on the closed-form assembly, in q and in q̇; and leaves the
         * inverse dynamics of that state */
        for (int j = 0; j < m->nq; j++) assert_near(d->q[j], q_exact[j], 1e-12);
        for (int j = 0; j < m->nv; j++) assert_near(d->qd[j], qd_exact[j], 1e-12);
        for (int k = 0; k < kin.n - m->nq - m->nv; k++)
            assert_near(kin.v[k], dense.v[k], 1e-11 * (1 + fabs(dense.v[k])));
    }
    vt_data_free(d);
    vt_data_free(dc);
    vt_model_free(m);
}

#if VT_HAVE_SUNDIALS
/* Allocator calls of one dynamic analysis of the double link (joint 2 locked) over `seconds`,
 * ten rows a second; its steps in *steps. Counted, not failed: the analysis allocates at its
 * start (IDA's memory, the forward model and data, the history) and frees it at its end. */
static long analysis_calls(const vt_model *m, int form, int forward, double seconds, long *steps)
{
    vt_data *d;
    vt_trajectory *tr;
    vt_run_options opt = vt_default_run_options();
    opt.formulation = form;
    opt.forward_check = forward > 0;
    opt.forward_independent = forward == 2;
    opt.t1 = seconds;
    opt.nout = (int)(10.0 * seconds);
    opt.max_step = 1e-3;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    calls = 0;
    counting = 1;
    const vt_status st = vt_dynamic_analysis(m, d, &opt, tr);
    counting = 0;
    const long n = calls;
    if (st) fail_msg("formulation %d, forward %d, %g s: %s", form, forward, seconds, d->message);
    assert_int_equal(tr->nfilled, opt.nout + 1);
    *steps = tr->steps;
    vt_trajectory_free(tr);
    vt_data_free(d);
    return n;
}

/* vt_dynamic_analysis allocates only at its start: the same number of allocator calls for runs
 * of 1, 10 and 30 s (tens to thousands of steps), with every formulation, without the forward
 * check and with it (in the same IDA system, and independent). */
static void test_dynamic_analysis_allocates_at_start(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_double_link(&m, 1));
    void *(*volatile through)(size_t) = malloc; /* the replacement is live: a call is counted */
    calls = 0;
    counting = 1;
    free(through(64));
    counting = 0;
    if (calls == 0 && under_valgrind()) {
        fprintf(stderr, "note: valgrind replaced this test's malloc: the dynamic analysis' calls not counted\n");
        vt_model_free(m);
        return;
    }
    assert_int_equal(calls, 2);
    static const double seconds[3] = {1.0, 10.0, 30.0};
    for (int form = 0; form < VT_FORMULATION_COUNT; form++)
        for (int forward = 0; forward < 3; forward++) {
            long n[3], steps[3];
            for (int k = 0; k < 3; k++) n[k] = analysis_calls(m, form, forward, seconds[k], &steps[k]);
            if (!(steps[2] > 10 * steps[0] && n[0] > 0 && n[1] == n[0] && n[2] == n[0]))
                fail_msg("formulation %d, forward %d: %ld / %ld / %ld allocator calls in %ld / %ld / %ld steps", form,
                         forward, n[0], n[1], n[2], steps[0], steps[1], steps[2]);
        }
    vt_model_free(m);
}

/* Allocator calls of one kinematic analysis of the five-link arm over `seconds` with the forward
 * check (exact efforts at every time IDA asks for, the forward model's residual by the recursive
 * pass), ten rows a second, IDA's steps at most 1 ms (the deviation from exact efforts stays at
 * round-off, which IDA would cross in a few long steps); the forward run's steps in *steps */
static long kinematic_calls(const vt_model *m, double seconds, long *steps)
{
    vt_data *d;
    vt_trajectory *tr;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = seconds;
    opt.nout = (int)(10.0 * seconds);
    opt.max_step = 1e-3;
    assert_ok(vt_data_create(&d, m));
    assert_ok(vt_trajectory_create(&tr, m, opt.nout + 1));
    vt_scene_five_link_guess(m, d, 0.0);
    calls = 0;
    counting = 1;
    const vt_status st = vt_kinematic_analysis(m, d, &opt, tr);
    counting = 0;
    const long n = calls;
    if (st) fail_msg("%g s: %s", seconds, d->message);
    assert_int_equal(tr->nfilled, opt.nout + 1);
    *steps = tr->steps_fwd;
    vt_trajectory_free(tr);
    vt_data_free(d);
    return n;
}

/* vt_kinematic_analysis with its forward check allocates only at the check's start: the same
 * number of allocator calls for 0.5, 2 and 6 s (hundreds to thousands of forward steps) */
static void test_kinematic_analysis_allocates_at_start(void **state)
{
    (void)state;
    vt_model *m;
    assert_ok(vt_scene_five_link(&m));
    void *(*volatile through)(size_t) = malloc; /* the replacement is live: a call is counted */
    calls = 0;
    counting = 1;
    free(through(64));
    counting = 0;
    if (calls == 0 && under_valgrind()) {
        fprintf(stderr, "note: valgrind replaced this test's malloc: the kinematic analysis' calls not counted\n");
        vt_model_free(m);
        return;
    }
    static const double seconds[3] = {0.5, 2.0, 6.0};
    long n[3], steps[3];
    for (int k = 0; k < 3; k++) n[k] = kinematic_calls(m, seconds[k], &steps[k]);
    if (!(steps[2] > 10 * steps[0] && n[0] > 0 && n[1] == n[0] && n[2] == n[0]))
        fail_msg("%ld / %ld / %ld allocator calls in %ld / %ld / %ld forward steps", n[0], n[1], n[2], steps[0], steps[1],
                 steps[2]);
    vt_model_free(m);
}
#endif

#endif /* UNDER_TSAN */

int main(void)
{
#ifdef UNDER_TSAN
    printf("test_static_memory: skipped under ThreadSanitizer (its runtime's allocator cannot be "
           "replaced from the executable)\n");
    return 77;
#else
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_bounds),
        cmocka_unit_test(test_double_link_no_allocation),
        cmocka_unit_test(test_fourbar_no_allocation),
#if VT_HAVE_SUNDIALS
        cmocka_unit_test(test_dynamic_analysis_allocates_at_start),
        cmocka_unit_test(test_kinematic_analysis_allocates_at_start),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
#endif
}
