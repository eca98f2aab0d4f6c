/* Speed of one inverse-dynamics instant: joint torques (efforts) and every joint reaction.
 *
 * Scenes (examples/scenes.h): the spatial chain of n revolute joints with axes cycling x, y, z,
 * every joint driven (n = 2 .. 200); the paper's double link with its lock; the four-bar (RSUR);
 * the same four-bar built RUSR (universal joint on the coupler, spherical cut joint), which is
 * literally MuJoCo's model of it; the chain with a point-position drive at its tip (n = 10, 20, 50,
 * 100); the five-link arm; and three machines driven at their motors, each at an instant of its
 * motion (vt_kinematic_solve at t = 0.1 s: q, q̇ consistent with the loops and the drives): the
 * Delta robot (vt_scene_delta_ik, period 1 s: 21 rates, 18 cut rows, 3 motor drives), the
 * Stewart–Gough platform (vt_scene_stewart, period 2 s: 24 rates, 18 cut rows, 6 leg drives)
 * and the knee four-bar (vt_scene_knee, planar cut: 4 rates, 2 cut rows, hip and motor drives).
 * n is the number of rates. Methods:
 * vtdyn_dense (vt_inverse_dynamics: dense S, the reference) and vtdyn_recursive
 * (vt_inverse_dynamics_recursive), and the peers when they are built in (bench/peers/):
 * Pinocchio and MuJoCo, on the same chain and the same q, q̇, q̈, their torques checked against
 * ours before they are timed (MuJoCo also on the double link, both four-bars, the three machines
 * and the tip-driven chain, there both handed our q̈ and solving q̈ itself from the tip's
 * acceleration). On the loops MuJoCo's model is the same mechanism with its loops closed by
 * equality constraints, handed our q, q̇, q̈; mj_inverse, then the loop forces that leave only the
 * motors acting (bench/peers/mujoco_peer.c, mujoco_inverse_loop). Every peer's torques must
 * equal ours to 1e-8 of the largest before it is timed (a machine: every rate's, the motors'
 * torques or forces and zero on the others), else it is reported and not timed.
 *
 * Robots (the rows "ur5", "panda" with their bases welded, "solo12", "talos" floating; n = the
 * number of rates): URDF files of example-robot-data, read from the robots directory given as
 * the third argument or in VT_BENCH_ROBOTS (bench/peers/install.sh prints it; without it, or
 * in a build without URDF loading, the rows are skipped with a message). vtdyn_motion is
 * vt_inverse_dynamics_motion on vt_urdf_builder's model (floating roots: a VT_JOINT_FREE joint,
 * options.floating = 1; mimic joints independent, as Pinocchio loads them; the joints'
 * <dynamics> left out, as rnea and MuJoCo's inverse leave them), efforts and every
 * reaction in both frames, at a random state (q, q̇, q̈); Pinocchio's rnea (free flyer root) and
 * rnea with every reaction mapped to world (pinocchio_rnea_world), and MuJoCo's leanest path
 * (mujoco_post_project) on the same state, each peer loading the file itself. Every peer's
 * torques are compared with vtdyn's at that state and two more, to 1e-8 of the largest, before
 * it is timed.
 *
 * Timing: every method of a row is run in turn, round after round, in one process (interleaved,
 * so that the machine's slow stretches hit all of them alike; the order is turned every round:
 * forwards, backwards); a round times a batch of calls sized to take about 2 ms; the figure is
 * the median over the rounds of µs per call, and each ratio vtdyn / method (vtdyn_recursive on
 * the scenes, vtdyn_motion on the robots) is the median of the rounds' ratios, printed with
 * their range. Prints the date, the CPU (/proc/cpuinfo), the compiler and the command first. Writes <outdir>/inverse_speed.csv (scene,
 * n, method, median_us, ratio_median, ratio_min, ratio_max) and prints the ratios.
 * Usage: bench_inverse [outdir] [rounds] [robots_dir]   (41 rounds by default, at most 201);
 * VT_BENCH_ONLY=<scene> (e.g. talos) runs that scene's rows alone; VT_BENCH_COUNT=<calls> runs
 * every method that many times untimed, for instruction counts (callgrind, docs/performance.md).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpuinfo.h"
#include "scenes.h"
#if defined(VT_HAVE_MUJOCO) || defined(VT_HAVE_PINOCCHIO)
#define VT_HAVE_PEERS 1
#include "peers.h"
#endif

#define MAX_METHODS 12

typedef struct {
    const char *name;
    void (*run)(void *ctx, int method);
    void *ctx;
    int method;
} timed;

typedef struct {
    const vt_model *m;
    vt_data *d;
    int recursive;
} vt_ctx;

static void run_vt(void *ctx, int method)
{
    (void)method;
    vt_ctx *c = ctx;
    const vt_status st = c->recursive ? vt_inverse_dynamics_recursive(c->m, c->d) : vt_inverse_dynamics(c->m, c->d);
    if (st) {
        fprintf(stderr, "bench_inverse: %s: %s\n", vt_status_string(st), c->d->message);
        exit(1);
    }
}

#ifdef VT_HAVE_PEERS
static void run_peer(void *ctx, int method)
{
    vt_peer_run(ctx, method);
}
#endif

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec * 1e-3;
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#define MAX_ROUNDS 201

static double median_of(double *a, int n)
{
    qsort(a, (size_t)n, sizeof(double), cmp);
    return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

/* median µs per call of each method, interleaved rounds (order reversed every other round), and
 * for every method k the median, smallest and largest of the rounds' ratios t_ref / t_k (method
 * ref is vtdyn's: vtdyn_recursive, vtdyn_motion) into ratio[3 k .. 3 k + 2] */
static void time_methods(timed *t, int nt, int ref, int rounds, double *median, double *ratio)
{
    long reps[MAX_METHODS];
    static double samples[MAX_METHODS][MAX_ROUNDS];
    const char *count = getenv("VT_BENCH_COUNT");
    if (count && atol(count) > 0) { /* for callgrind: every method count times, nothing timed */
        for (int k = 0; k < nt; k++)
            for (long i = 0; i < atol(count); i++) t[k].run(t[k].ctx, t[k].method);
        for (int k = 0; k < nt; k++) median[k] = ratio[3 * k] = ratio[3 * k + 1] = ratio[3 * k + 2] = 0.0;
        return;
    }
    for (int k = 0; k < nt; k++) { /* warm up and size a batch to about 2 ms */
        long r = 1;
        for (;;) {
            const double t0 = now_us();
            for (long i = 0; i < r; i++) t[k].run(t[k].ctx, t[k].method);
            const double dt = now_us() - t0;
            if (dt > 2000.0 || r > (1L << 24)) break;
            r *= dt < 200.0 ? 8 : 2;
        }
        reps[k] = r;
    }
    for (int round = 0; round < rounds; round++)
        for (int j = 0; j < nt; j++) {
            const int k = round % 2 ? nt - 1 - j : j;
            const double t0 = now_us();
            for (long i = 0; i < reps[k]; i++) t[k].run(t[k].ctx, t[k].method);
            samples[k][round] = (now_us() - t0) / (double)reps[k];
        }
    double r[MAX_ROUNDS];
    for (int k = 0; k < nt; k++) {
        double lo = 1e300, hi = 0.0;
        for (int round = 0; round < rounds; round++) {
            r[round] = samples[ref][round] / samples[k][round];
            lo = r[round] < lo ? r[round] : lo;
            hi = r[round] > hi ? r[round] : hi;
        }
        ratio[3 * k] = median_of(r, rounds);
        ratio[3 * k + 1] = lo;
        ratio[3 * k + 2] = hi;
    }
    for (int k = 0; k < nt; k++) median[k] = median_of(samples[k], rounds);
}

/* the chain's reference q and q̇ (its q̈ is the drives' or the solve's) */
static void set_chain_state(const vt_model *m, vt_data *d)
{
    for (int k = 0; k < m->nv; k++) {
        double qdd;
        vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
    }
    d->time = 0.0;
}

static FILE *csv;
static double fit_n[16], fit_t[16];
static int nfit;

/* one row: our two methods (and the peers on the chain); prints and writes the medians */
static void bench_row(const char *scene, int n, vt_model *m, vt_data *dd, vt_data *dr, int rounds)
{
    timed t[MAX_METHODS];
    vt_ctx cd = {m, dd, 0}, cr = {m, dr, 1};
    int nt = 0;
    t[nt++] = (timed){"vtdyn_dense", run_vt, &cd, 0};
    t[nt++] = (timed){"vtdyn_recursive", run_vt, &cr, 0};
#ifdef VT_HAVE_PEERS
    /* the peers on the same scene and state: the chain (both), the double link and the
     * four-bars (MuJoCo, with its equality constraints), the tip-driven chain (MuJoCo, the tip
     * force solved from mj_inverse); q̈ from our own solve */
    vt_peer *peers[2] = {NULL, NULL};
    int pscene = -1, np = n;
    enum { NMAX = 1024 }; /* the peers' state and torques: a chain up to NMAX − 1 links */
    double q[NMAX], qd[NMAX], qdd[NMAX], ours[NMAX], tau[NMAX];
    run_vt(&cr, 0);
    if (n >= NMAX) {
        printf("  peers skipped: n = %d beyond the benchmark's %d\n", n, NMAX - 1);
    } else if (strcmp(scene, "chain") == 0) {
        pscene = VT_PEER_CHAIN;
        for (int k = 0; k < n; k++) {
            vt_scene_chain_state(k, &q[k], &qd[k], &qdd[k]);
            ours[k] = dr->qfrc_drive[k];
        }
    } else if (strcmp(scene, "double_link") == 0) {
        pscene = VT_PEER_DOUBLE_LINK;
        np = 2;
        q[0] = dr->q[0]; qd[0] = dr->qd[0]; qdd[0] = dr->qdd[0];
        q[1] = qd[1] = qdd[1] = 0.0;
        ours[0] = 0.0;
        ours[1] = dr->drive_effort[0]; /* the locking torque */
    } else if (strcmp(scene, "fourbar") == 0) {
        pscene = VT_PEER_FOURBAR;
        np = 3;
        const double *p = dr->q + m->body_qadr[2];
        const double rel = 2.0 * atan2(p[3], p[0]); /* the spherical joint turns about z only */
        q[0] = dr->q[0]; q[1] = rel; q[2] = dr->q[m->body_qadr[3]];
        qd[0] = dr->qd[0]; qd[1] = dr->qd[3]; qd[2] = dr->qd[4];
        qdd[0] = dr->qdd[0]; qdd[1] = dr->qdd[3]; qdd[2] = dr->qdd[4];
        ours[0] = dr->drive_effort[0];
        ours[1] = ours[2] = 0.0;
    } else if (strcmp(scene, "fourbar_rusr") == 0) {
        /* the same coordinates: crank, the universal's two angles (about z, then the tilt), rocker */
        pscene = VT_PEER_FOURBAR_RUSR;
        np = 4;
        const int qi[4] = {m->body_qadr[1], m->body_qadr[2], m->body_qadr[2] + 1, m->body_qadr[3]};
        const int vi[4] = {m->body_vadr[1], m->body_vadr[2], m->body_vadr[2] + 1, m->body_vadr[3]};
        for (int k = 0; k < 4; k++) {
            q[k] = dr->q[qi[k]];
            qd[k] = dr->qd[vi[k]];
            qdd[k] = dr->qdd[vi[k]];
            ours[k] = 0.0; /* only the crank is actuated */
        }
        ours[0] = dr->drive_effort[0];
    } else if (strcmp(scene, "delta") == 0 || strcmp(scene, "stewart") == 0 || strcmp(scene, "knee") == 0) {
        /* vtdyn's own layout: the peer maps it to MuJoCo's; every rate compared */
        pscene = scene[0] == 'd' ? VT_PEER_DELTA : scene[0] == 's' ? VT_PEER_STEWART : VT_PEER_KNEE;
        np = m->nv;
        for (int k = 0; k < m->nq; k++) q[k] = dr->q[k];
        for (int k = 0; k < m->nv; k++) {
            qd[k] = dr->qd[k];
            qdd[k] = dr->qdd[k];
            ours[k] = dr->qfrc_drive[k]; /* the motors' efforts on their rates, zero elsewhere */
        }
    } else if (strcmp(scene, "chain_tip") == 0) {
        pscene = VT_PEER_CHAIN_TIP;
        for (int k = 0; k < n; k++) {
            q[k] = dr->q[k];
            qd[k] = dr->qd[k];
            qdd[k] = dr->qdd[k];
            ours[k] = 0.0; /* no joint is actuated */
        }
        ours[n] = dr->drive_effort[0]; /* the tip force along global y */
    }
    if (pscene >= 0) {
#ifdef VT_HAVE_PINOCCHIO
        peers[0] = vt_peer_pinocchio(pscene, np, q, qd, qdd);
#endif
#ifdef VT_HAVE_MUJOCO
        peers[1] = vt_peer_mujoco(pscene, np, q, qd, qdd);
#endif
        for (int p = 0; p < 2; p++) {
            if (!peers[p]) continue;
            for (int k = 0; k < vt_peer_nmethods(peers[p]) && nt < MAX_METHODS; k++) {
                vt_peer_run(peers[p], k);
                vt_peer_torques(peers[p], tau);
                double err = 0.0, scale = 1e-300;
                /* the four-bar: the crank torque; the RUSR four-bar: the crank torque and the 3 torques
                 * left (zero); the chain tip: the n joint torques left (zero) and the tip force */
                const int ncmp = pscene == VT_PEER_FOURBAR ? 1 : pscene == VT_PEER_CHAIN_TIP ? np + 1 : np;
                for (int j = 0; j < ncmp; j++) {
                    err = fmax(err, fabs(tau[j] - ours[j]));
                    scale = fmax(scale, fabs(ours[j]));
                }
                /* the same dynamics: round-off apart (MuJoCo's soft constraints do not enter: the
                 * state satisfies them, and the loop forces are solved exactly) */
                const double tol = 1e-8;
                if (!(err <= tol * scale) && strstr(vt_peer_method(peers[p], k), "crba") == NULL) {
                    printf("  %s disagrees with vtdyn: max torque difference %.3g (scale %.3g): not timed\n",
                           vt_peer_method(peers[p], k), err, scale);
                    continue;
                }
                if (pscene != VT_PEER_CHAIN) printf("  %s agrees with vtdyn to %.2g relative\n", vt_peer_method(peers[p], k), err / scale);
                t[nt++] = (timed){vt_peer_method(peers[p], k), run_peer, peers[p], k};
            }
        }
    }
#endif
    double med[MAX_METHODS], ratio[3 * MAX_METHODS];
    time_methods(t, nt, 1, rounds, med, ratio);
    printf("%-12s n=%3d", scene, n);
    for (int k = 0; k < nt; k++) {
        printf("  %s %.3f us", t[k].name, med[k]);
        fprintf(csv, "%s,%d,%s,%.6g,%.4g,%.4g,%.4g\n", scene, n, t[k].name, med[k], ratio[3 * k], ratio[3 * k + 1],
                ratio[3 * k + 2]);
    }
    for (int k = 2; k < nt; k++)
        printf("  [recursive/%s %.2f (%.2f-%.2f)]", t[k].name, ratio[3 * k], ratio[3 * k + 1], ratio[3 * k + 2]);
    printf("  [recursive/dense %.3f (%.3f-%.3f)]\n", ratio[0], ratio[1], ratio[2]);
    if (strcmp(scene, "chain") == 0 && nfit < 16) {
        fit_n[nfit] = n;
        fit_t[nfit++] = med[1];
    }
#ifdef VT_HAVE_PEERS
    for (int p = 0; p < 2; p++)
        if (peers[p]) vt_peer_free(peers[p]);
#endif
}

/* VT_BENCH_ONLY=<scene>: only that scene's rows (e.g. "talos", for callgrind) */
static int skip_row(const char *scene)
{
    const char *only = getenv("VT_BENCH_ONLY");
    return only && only[0] && strcmp(only, scene) != 0;
}

static void scene_row(const char *scene, int n, vt_status (*make)(vt_model **, int), void (*state)(const vt_model *, vt_data *),
                      int rounds)
{
    if (skip_row(scene)) return;
    vt_model *m;
    vt_data *dd, *dr;
    if (make(&m, n) || vt_data_create(&dd, m) || vt_data_create(&dr, m)) {
        fprintf(stderr, "bench_inverse: cannot build %s\n", scene);
        exit(1);
    }
    state(m, dd);
    state(m, dr);
    bench_row(scene, n, m, dd, dr, rounds);
    vt_data_free(dd);
    vt_data_free(dr);
    vt_model_free(m);
}

static vt_status make_chain(vt_model **m, int n) { return vt_scene_chain(m, n, VT_CHAIN_JOINT_DRIVEN); }
static vt_status make_chain_tip(vt_model **m, int n) { return vt_scene_chain(m, n, VT_CHAIN_TIP_DRIVE); }
static vt_status make_double_link(vt_model **m, int n) { (void)n; return vt_scene_double_link(m, 1); }
static vt_status make_fourbar(vt_model **m, int n) { (void)n; return vt_scene_fourbar(m, vt_function_sine(0.3, 1.0, 2.0, 0.0)); }
static vt_status make_fourbar_rusr(vt_model **m, int n)
{
    (void)n;
    return vt_scene_fourbar_rusr(m, vt_function_sine(0.3, 1.0, 2.0, 0.0));
}
static vt_status make_five_link(vt_model **m, int n) { (void)n; return vt_scene_five_link(m); }
/* the machines' drive data outlive their models */
static vt_delta_ik delta_ik;
static vt_stewart stewart = {3.14159265358979323846, 0.0, {{0}}}; /* period 2 s, as examples/stewart.c */
static vt_status make_delta(vt_model **m, int n) { (void)n; return vt_scene_delta_ik(m, &delta_ik, 1.0); }
static vt_status make_stewart(vt_model **m, int n) { (void)n; return vt_scene_stewart(m, &stewart); }
static vt_status make_knee(vt_model **m, int n) /* examples/knee.c's gait: two strides a second */
{
    (void)n;
    const double pi = 3.14159265358979323846;
    return vt_scene_knee(m, vt_function_sine(-0.25 * pi, 0.35, 4.0 * pi, 0.0),
                         vt_function_sine(0.5 * pi, 0.4, 4.0 * pi, 0.8), 1);
}

static void state_chain(const vt_model *m, vt_data *d)
{
    set_chain_state(m, d);
}
static void state_double_link(const vt_model *m, vt_data *d)
{
    (void)m;
    d->q[0] = -0.6;
    d->qd[0] = -sqrt(7.3575 * sin(0.6));
}
static void state_fourbar(const vt_model *m, vt_data *d)
{
    vt_scene_fourbar_assemble(m, d, 0.3, 1.0, NULL, NULL);
}
static void state_fourbar_rusr(const vt_model *m, vt_data *d)
{
    vt_scene_fourbar_rusr_assemble(m, d, 0.3, 1.0, NULL, NULL);
}
static void state_five_link(const vt_model *m, vt_data *d)
{
    vt_scene_five_link_guess(m, d, 0.1);
    d->time = 0.1;
    vt_kinematic_solve(m, d, 1e-13, 30);
}
/* the machines at t = 0.1 s: the closed-form assembly, then vtdyn's kinematic solve (q, q̇) */
#define MACHINE_T 0.1
static void machine_solve(const vt_model *m, vt_data *d, const char *scene, int bad)
{
    d->time = MACHINE_T;
    const vt_status st = bad ? VT_ERR_NEWTON : vt_kinematic_solve(m, d, 1e-13, 30);
    if (st) {
        fprintf(stderr, "bench_inverse: %s at t = %g: %s: %s\n", scene, MACHINE_T, vt_status_string(st),
                bad ? "no assembly" : d->message);
        exit(1);
    }
}
static void state_delta(const vt_model *m, vt_data *d)
{
    double p[3];
    vt_scene_delta_path(MACHINE_T, delta_ik.period, p, NULL, NULL);
    machine_solve(m, d, "delta", vt_scene_delta_assemble(m, d, p));
}
static void state_stewart(const vt_model *m, vt_data *d)
{
    vt_scene_stewart_assemble(m, d, &stewart, MACHINE_T);
    machine_solve(m, d, "stewart", 0);
}
static void state_knee(const vt_model *m, vt_data *d)
{
    double hip[3], mot[3];
    vt_function_eval(hip, &m->drive[0].f, MACHINE_T);
    vt_function_eval(mot, &m->drive[1].f, MACHINE_T);
    machine_solve(m, d, "knee", vt_scene_knee_assemble(m, d, hip[0], hip[1], mot[0], mot[1], NULL));
}

/* ---- URDF robots ---- */
#if VT_HAVE_URDF
typedef struct {
    const vt_model *m;
    vt_data *d;
} motion_ctx;

static void run_motion(void *ctx, int method)
{
    (void)method;
    motion_ctx *c = ctx;
    const vt_status st = vt_inverse_dynamics_motion(c->m, c->d);
    if (st) {
        fprintf(stderr, "bench_inverse: %s: %s\n", vt_status_string(st), c->d->message);
        exit(1);
    }
}

static double uniform(unsigned long long *s, double lo, double hi) /* splitmix64 */
{
    unsigned long long z = (*s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return lo + (hi - lo) * (double)(z >> 11) * 0x1.0p-53;
}

/* a random state: joint coordinates in [-1.5, 1.5] (rad or m: within every joint's range is not
 * needed for the dynamics), rates and accelerations in [-2, 2]; a free joint's position in
 * [-1, 1]^3 m and a random unit quaternion */
static void robot_state(const vt_model *m, vt_data *d, unsigned long long seed)
{
    for (int i = 1; i <= m->nbody; i++) {
        double *q = d->q + m->body_qadr[i];
        if (m->body_joint[i] == VT_JOINT_FREE) {
            double nrm = 0.0;
            for (int k = 0; k < 3; k++) q[k] = uniform(&seed, -1.0, 1.0);
            for (int k = 3; k < 7; k++) {
                q[k] = uniform(&seed, -1.0, 1.0);
                nrm += q[k] * q[k];
            }
            for (int k = 3; k < 7; k++) q[k] /= sqrt(nrm);
        } else {
            for (int k = 0; k < m->body_nq[i]; k++) q[k] = uniform(&seed, -1.5, 1.5);
        }
        for (int k = 0; k < m->body_nv[i]; k++) {
            d->qd[m->body_vadr[i] + k] = uniform(&seed, -2.0, 2.0);
            d->qdd[m->body_vadr[i] + k] = uniform(&seed, -2.0, 2.0);
        }
    }
    d->time = 0.0;
}

#ifdef VT_HAVE_PEERS
/* the state packed body by body (peers.h's layout), the names of the joints, vtdyn's efforts */
static void robot_pack(const vt_model *m, const vt_data *d, double *q, double *qd, double *qdd, double *ours)
{
    int iq = 0, iv = 0;
    for (int i = 1; i <= m->nbody; i++) {
        for (int k = 0; k < m->body_nq[i]; k++) q[iq++] = d->q[m->body_qadr[i] + k];
        for (int k = 0; k < m->body_nv[i]; k++, iv++) {
            qd[iv] = d->qd[m->body_vadr[i] + k];
            qdd[iv] = d->qdd[m->body_vadr[i] + k];
            ours[iv] = d->qfrc_drive[m->body_vadr[i] + k];
        }
    }
}
#endif

static void robot_row(const char *dir, const char *scene, const char *rel, int floating, int rounds)
{
    if (skip_row(scene)) return;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = floating;
    opt.mimic = 0; /* as Pinocchio and MuJoCo load the file: a mimic joint moves on its own */
    opt.dynamics = 0; /* as Pinocchio's rnea and MuJoCo's inverse leave <dynamics> out: like for like */
    char msg[256] = "";
    vt_builder *b;
    vt_model *m;
    vt_data *d;
    if (vt_urdf_builder(&b, path, &opt, msg)) {
        printf("%-12s skipped: %s\n", scene, msg);
        return;
    }
    if (vt_builder_build(&m, b) || vt_data_create(&d, m)) {
        printf("%-12s skipped: %s\n", scene, vt_builder_message(b));
        vt_builder_free(b);
        return;
    }
    vt_builder_free(b);
    const unsigned long long seed = 0x5EEDULL + (unsigned long long)strlen(scene);
    robot_state(m, d, seed);
    motion_ctx c = {m, d};
    run_motion(&c, 0);
    timed t[MAX_METHODS];
    int nt = 0;
    t[nt++] = (timed){"vtdyn_motion", run_motion, &c, 0};
#ifdef VT_HAVE_PEERS
    /* the peers, each at three states (the last the timed one): torques to 1e-8 of the largest */
    vt_peer *peers[2] = {NULL, NULL};
    const int nj = m->nbody, nv = m->nv;
    const char **names = malloc((size_t)nj * sizeof *names);
    double *buf = malloc((size_t)(m->nq + 4 * nv) * sizeof *buf);
    double *q = buf, *qd = buf + m->nq, *qdd = qd + nv, *ours = qdd + nv, *tau = ours + nv;
    for (int i = 1; i <= nj; i++) names[i - 1] = m->joint_name + VT_NAME_MAX * i;
    for (int p = 0; p < 2; p++) {
        double worst = 0.0;
        for (int s = 2; s >= 0; s--) {
            robot_state(m, d, seed + (unsigned long long)s);
            run_motion(&c, 0);
            robot_pack(m, d, q, qd, qdd, ours);
            vt_peer *peer = NULL;
            int built = 0;
#ifdef VT_HAVE_PINOCCHIO
            if (p == 0) peer = vt_peer_pinocchio_robot(path, floating, nj, names, q, qd, qdd, msg), built = 1;
#endif
#ifdef VT_HAVE_MUJOCO
            if (p == 1) peer = vt_peer_mujoco_robot(path, floating, nj, names, q, qd, qdd, msg), built = 1;
#endif
            if (!peer) {
                if (built) printf("  %s cannot load %s: %s\n", p ? "MuJoCo" : "Pinocchio", rel, msg);
                break;
            }
            int ok = 1;
            for (int k = 0; k < vt_peer_nmethods(peer); k++) {
                vt_peer_run(peer, k);
                vt_peer_torques(peer, tau);
                double err = 0.0, scale = 1e-300;
                for (int j = 0; j < nv; j++) {
                    err = fmax(err, fabs(tau[j] - ours[j]));
                    scale = fmax(scale, fabs(ours[j]));
                }
                worst = fmax(worst, err / scale);
                if (!(err <= 1e-8 * scale)) {
                    printf("  %s disagrees with vtdyn on %s: max torque difference %.3g (scale %.3g): not timed\n",
                           vt_peer_method(peer, k), scene, err, scale);
                    ok = 0;
                }
            }
            if (!ok || s > 0) vt_peer_free(peer);
            else peers[p] = peer;
            if (!ok) break;
        }
        if (peers[p]) {
            printf("  %s agrees with vtdyn on %s to %.2g relative (3 states)\n", p ? "MuJoCo" : "Pinocchio", scene, worst);
            for (int k = 0; k < vt_peer_nmethods(peers[p]) && nt < MAX_METHODS; k++)
                t[nt++] = (timed){vt_peer_method(peers[p], k), run_peer, peers[p], k};
        }
    }
    free(names);
    free(buf);
#endif
    double med[MAX_METHODS], ratio[3 * MAX_METHODS];
    time_methods(t, nt, 0, rounds, med, ratio);
    printf("%-12s n=%3d", scene, m->nv);
    for (int k = 0; k < nt; k++) {
        printf("  %s %.3f us", t[k].name, med[k]);
        fprintf(csv, "%s,%d,%s,%.6g,%.4g,%.4g,%.4g\n", scene, m->nv, t[k].name, med[k], ratio[3 * k], ratio[3 * k + 1],
                ratio[3 * k + 2]);
    }
    for (int k = 1; k < nt; k++)
        printf("  [vtdyn_motion/%s %.2f (%.2f-%.2f)]", t[k].name, ratio[3 * k], ratio[3 * k + 1], ratio[3 * k + 2]);
    printf("\n");
    fflush(stdout);
#ifdef VT_HAVE_PEERS
    for (int p = 0; p < 2; p++)
        if (peers[p]) vt_peer_free(peers[p]);
#endif
    vt_data_free(d);
    vt_model_free(m);
}
#endif

int main(int argc, char **argv)
{
    const char *outdir = argc > 1 ? argv[1] : ".";
    const int rounds = argc > 2 ? atoi(argv[2]) : 41;
    if (rounds < 1 || rounds > MAX_ROUNDS) {
        fprintf(stderr, "bench_inverse: rounds must be 1..%d\n", MAX_ROUNDS);
        return 1;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/inverse_speed.csv", outdir);
    csv = fopen(path, "w");
    if (!csv) {
        perror(path);
        return 1;
    }
    fprintf(csv, "scene,n,method,median_us,ratio_median,ratio_min,ratio_max\n");
    printf("vtdyn inverse-dynamics instant: median of %d interleaved rounds, us per call\n", rounds);
    char date[64];
    const time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S %Z", localtime(&now));
    printf("date: %s\n", date);
    vt_bench_cpu_line();
    printf("compiler: %s\ncommand:", __VERSION__);
    for (int i = 0; i < argc; i++) printf(" %s", argv[i]);
    printf("\n");
#ifndef VT_HAVE_PEERS
    printf("(peers not built: see bench/peers/install.sh and the README to compare with Pinocchio and MuJoCo)\n");
#endif
    static const int ns[] = {2, 5, 10, 20, 50, 100, 200, 500};
    for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++) scene_row("chain", ns[k], make_chain, state_chain, rounds);
    scene_row("double_link", 2, make_double_link, state_double_link, rounds);
    scene_row("fourbar", 3, make_fourbar, state_fourbar, rounds);
    scene_row("fourbar_rusr", 4, make_fourbar_rusr, state_fourbar_rusr, rounds);
    static const int ntip[] = {10, 20, 50, 100}; /* partly driven: the free rates' solve grows too */
    for (size_t k = 0; k < sizeof ntip / sizeof ntip[0]; k++)
        scene_row("chain_tip", ntip[k], make_chain_tip, state_chain, rounds);
    scene_row("five_link", 5, make_five_link, state_five_link, rounds);
    scene_row("delta", 21, make_delta, state_delta, rounds);
    scene_row("stewart", 24, make_stewart, state_stewart, rounds);
    scene_row("knee", 4, make_knee, state_knee, rounds);
    const char *robots = argc > 3 ? argv[3] : getenv("VT_BENCH_ROBOTS");
#if VT_HAVE_URDF
    if (robots && robots[0]) {
        robot_row(robots, "ur5", "ur_description/urdf/ur5_robot.urdf", 0, rounds);
        robot_row(robots, "panda", "panda_description/urdf/panda.urdf", 0, rounds);
        robot_row(robots, "solo12", "solo_description/robots/solo12.urdf", 1, rounds);
        robot_row(robots, "talos", "talos_data/robots/talos_reduced.urdf", 1, rounds);
    } else {
        printf("robots skipped: no robots directory (third argument or VT_BENCH_ROBOTS; bench/peers/install.sh prints it)\n");
    }
#else
    (void)robots;
    printf("robots skipped: this build has no URDF loading (libxml2)\n");
#endif
    fclose(csv);
    /* growth of the recursive chain: least-squares slope of log t against log n */
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < nfit; k++) {
        const double x = log(fit_n[k]), y = log(fit_t[k]);
        sx += x; sy += y; sxx += x * x; sxy += x * y;
    }
    const double slope = (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx);
    if (nfit > 1) printf("vtdyn_recursive on the chain grows as n^%.3f (n = 2..500)\n", slope);
    printf("wrote %s\n", path);
    return 0;
}
