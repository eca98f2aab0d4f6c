/* Speed against accuracy, and constraint drift, of the analyses over time.
 *
 * Work-precision (<outdir>/work_precision.csv: scene, formulation, rtol, cpu_s, steps,
 * residual_evals, error): IDA's rtol swept 1e-3 .. 1e-12 (atol = rtol / 100) for
 *   double_link  dynamic analysis + forward check over [0, 1.9] s; error = the larger of the
 *                joint-1 reaction's error against (29) over the weight and the first integral's
 *                error θ̇² − 7.3575 sin θ over 7.3575 (relative, worst row)
 *   five_link    kinematic analysis + forward check over one period; error = the forward
 *                run's largest tip deviation from the driven run, m (its forward model has no
 *                constraint, so the four formulations coincide there)
 * for each formulation: index1, baumgarte (α = β = 10/s), projection, ggl.
 * With MuJoCo (built with -Dmujoco_dir=..., VT_HAVE_MUJOCO): its forward simulation of the same
 * double link (bench/peers/mujoco_peer.c: two hinges, joint 2 locked by MuJoCo's soft joint
 * equality, solref "2e-4 1" raised by refsafe to 2 dt for dt > 1e-4, solimp "0.9999 0.9999 0.001
 * 0.5 2"), from the same start (horizontal, at rest), rows double_link,mujoco_rk4 and
 * double_link,mujoco_euler (semi-implicit Euler, MuJoCo's default): for these the rtol column
 * holds the time step dt (1e-2 .. 1e-5 s), steps = mj_step calls, residual_evals = dynamics
 * evaluations (4 a step for RK4, 1 for Euler), cpu_s = the whole stepping loop; the error is
 * vtdyn's, on the same rows t = 0, 0.01, .., 1.9 s (the reaction is MuJoCo's cfrc_int of link 1
 * after mj_rnePostConstraint at that state, moved to the joint point as for bench_inverse).
 * The soft lock puts a floor of about 1.1e-5 under MuJoCo's error, whatever dt: its impedance
 * (at most 0.9999) lets joint 2 take 1e-4 of its free acceleration, so the joint-1 reaction at
 * t = 0 is 490.479 N against 490.5 N; the first integral alone (printed, not in the CSV) goes
 * down as dt^2 with RK4 (the lock's deviation, time constant 2 dt) to ~2e-11 at dt <= 1e-4.
 *
 * Drift (<outdir>/drift.csv: scene, formulation, t_s, phi_norm, phidot_norm, energy_error) at
 * rtol 1e-6, atol 1e-8, one row every 0.5 s:
 *   double_link  the paper's double link, 100 s (its lock q2 = 0 is linear: nothing to drift)
 *   fourbar      the four-bar swinging freely, started with the crank at 12 rad/s, 100 crank
 *                revolutions
 *   pendulum     IFToMM A01, 2000 s (joint coordinates: no constraint, energy drift only)
 * energy_error = (T + V)(t) − (T + V)(0), J; for the double link the lock's torque does no work
 * (q̇2 = 0), so T + V is conserved there too.
 * Usage: bench_precision [outdir]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes.h"
#ifdef VT_HAVE_MUJOCO
#include "peers.h"
#endif

static const char *form_name[VT_FORMULATION_COUNT] = {"index1", "baumgarte", "projection", "ggl", "ode"};

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void die(const char *what, vt_status st, const vt_data *d)
{
    fprintf(stderr, "bench_precision: %s: %s: %s\n", what, vt_status_string(st), d ? d->message : "");
    exit(1);
}

/* T + V of the state in d */
static double energy(const vt_model *m, vt_data *d)
{
    vt_status st = vt_kinematics(m, d);
    if (st) die("kinematics", st, d);
    double E = 0.0;
    for (int i = 1; i <= m->nbody; i++) {
        const double *v = d->xd + 7 * (i - 1), *w = d->omega + 3 * i, *A = d->A + 9 * i, *J = m->body_inertia + 9 * i;
        double wb[3], Jw[3];
        for (int r = 0; r < 3; r++) wb[r] = A[3 * r] * w[0] + A[3 * r + 1] * w[1] + A[3 * r + 2] * w[2];
        for (int r = 0; r < 3; r++) Jw[r] = J[r] * wb[0] + J[r + 3] * wb[1] + J[r + 6] * wb[2];
        E += 0.5 * m->body_mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
             0.5 * (wb[0] * Jw[0] + wb[1] * Jw[1] + wb[2] * Jw[2]);
        for (int k = 0; k < 3; k++) E -= m->body_mass[i] * m->gravity[k] * d->x[7 * (i - 1) + k];
    }
    return E;
}

static void row_state(const vt_model *m, vt_data *d, const vt_trajectory *tr, int k, int fwd)
{
    memcpy(d->q, (fwd ? tr->q_fwd : tr->q) + (size_t)k * (size_t)m->nq, (size_t)m->nq * sizeof(double));
    memcpy(d->qd, (fwd ? tr->qd_fwd : tr->qd) + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
}

/* double link, one output row: the larger of the joint-1 reaction f1's (world) error against (29)
 * over the weight and the first integral θ̇² − 7.3575 sin θ's error over 7.3575 (this one also in
 * *motion when not NULL); θ = −q1 (the link falls) */
static double dl_row_error(double q1, double qd1, const double *f1, double *motion)
{
    const double th = -q1, thd = -qd1, s = sin(th), c = cos(th);
    const double e = fmax(fabs(f1[0] + 2207.25 * sin(2 * th)), fabs(f1[1] - 4905.0 * s * s - 490.5 * c * c)) / 1962.0;
    const double em = fabs(thd * thd - 7.3575 * s) / 7.3575;
    if (motion) *motion = em;
    return fmax(e, em);
}

#ifdef VT_HAVE_MUJOCO
/* MuJoCo's forward simulation of the double link, dt swept, Euler and RK4 */
static void work_precision_mujoco(FILE *f)
{
    enum { NOUT = 190 };
    static const double dts[] = {1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5};
    static double q[2 * (NOUT + 1)], qd[2 * (NOUT + 1)], fr[6 * (NOUT + 1)];
    const double zero[2] = {0.0, 0.0}; /* vtdyn's start: q = 0 (horizontal), at rest */
    vt_peer *p = vt_peer_mujoco(VT_PEER_DOUBLE_LINK, 2, zero, zero, zero);
    if (!p) {
        fprintf(stderr, "bench_precision: MuJoCo double link: no model\n");
        return;
    }
    for (int integ = VT_PEER_RK4; integ >= VT_PEER_EULER; integ--)
        for (size_t i = 0; i < sizeof dts / sizeof dts[0]; i++) {
            const double c0 = cpu_now();
            const long steps = vt_peer_mujoco_simulate(p, dts[i], integ, 1.9, NOUT, q, qd, fr);
            const double cpu = cpu_now() - c0;
            if (steps < 0) {
                fprintf(stderr, "bench_precision: MuJoCo double link: simulation refused dt %g\n", dts[i]);
                exit(1);
            }
            double err = 0.0, motion = 0.0, em;
            for (int k = 0; k <= NOUT; k++) {
                err = fmax(err, dl_row_error(q[2 * k], qd[2 * k], fr + 6 * k, &em));
                motion = fmax(motion, em);
            }
            const char *name = integ == VT_PEER_RK4 ? "mujoco_rk4" : "mujoco_euler";
            fprintf(f, "double_link,%s,%.0e,%.6g,%ld,%ld,%.6e\n", name, dts[i], cpu, steps,
                    steps * (integ == VT_PEER_RK4 ? 4 : 1), err);
            printf("  %-12s dt %.0e: double link error %.2e (first integral alone %.2e), %.4f s cpu\n", name,
                   dts[i], err, motion, cpu);
        }
    vt_peer_free(p);
}
#endif

static void work_precision(FILE *f)
{
    vt_model *dl, *fl;
    vt_status st;
    if ((st = vt_scene_double_link(&dl, 1)) || (st = vt_scene_five_link(&fl))) die("scenes", st, NULL);
    for (int form = 0; form < VT_FORMULATION_COUNT; form++)
        for (int e = 3; e <= 12; e++) {
            const double rtol = pow(10.0, -e);
            vt_run_options o = vt_default_run_options();
            o.rtol = rtol;
            o.atol = rtol * 1e-2;
            o.formulation = form;
            /* double link */
            o.t1 = 1.9;
            o.nout = 190;
            vt_data *d, *dt;
            vt_trajectory *tr;
            if ((st = vt_data_create(&d, dl)) || (st = vt_data_create(&dt, dl)) ||
                (st = vt_trajectory_create(&tr, dl, o.nout + 1)))
                die("double link set-up", st, NULL);
            double c0 = cpu_now();
            if ((st = vt_dynamic_analysis(dl, d, &o, tr))) die("double link", st, d);
            double cpu = cpu_now() - c0, err = 0.0, err_dl;
            for (int k = 0; k < tr->nfilled; k++)
                err = fmax(err, dl_row_error(tr->q[2 * k], tr->qd[2 * k], tr->jnt_force + 9 * k + 3, NULL));
            fprintf(f, "double_link,%s,%.0e,%.6g,%ld,%ld,%.6e\n", form_name[form], rtol, cpu, tr->steps, tr->res_evals, err);
            err_dl = err;
            vt_trajectory_free(tr);
            vt_data_free(dt);
            vt_data_free(d);
            /* five-link arm */
            o.t1 = 1.0;
            o.nout = 100;
            if ((st = vt_data_create(&d, fl)) || (st = vt_data_create(&dt, fl)) ||
                (st = vt_trajectory_create(&tr, fl, o.nout + 1)))
                die("five link set-up", st, NULL);
            vt_scene_five_link_guess(fl, d, 0.0);
            c0 = cpu_now();
            if ((st = vt_kinematic_analysis(fl, d, &o, tr))) die("five link", st, d);
            cpu = cpu_now() - c0;
            err = 0.0;
            for (int k = 0; k < tr->nfilled; k++) {
                double p[3], pf[3];
                for (int fwd = 0; fwd < 2; fwd++) {
                    row_state(fl, dt, tr, k, fwd);
                    if ((st = vt_kinematics(fl, dt))) die("five link tip", st, dt);
                    for (int j = 0; j < 3; j++) (fwd ? pf : p)[j] = dt->x[7 * 4 + j] + 0.1 * dt->A[9 * 5 + j];
                }
                err = fmax(err, sqrt((p[0] - pf[0]) * (p[0] - pf[0]) + (p[1] - pf[1]) * (p[1] - pf[1]) + (p[2] - pf[2]) * (p[2] - pf[2])));
            }
            fprintf(f, "five_link,%s,%.0e,%.6g,%ld,%ld,%.6e\n", form_name[form], rtol, cpu, tr->steps_fwd, tr->res_evals_fwd, err);
            printf("  %-10s rtol %.0e: double link error %.2e; five link forward %.2e m\n", form_name[form], rtol, err_dl,
                   err);
            vt_trajectory_free(tr);
            vt_data_free(dt);
            vt_data_free(d);
        }
    vt_model_free(dl);
    vt_model_free(fl);
#ifdef VT_HAVE_MUJOCO
    work_precision_mujoco(f);
#endif
}

static void drift_run(FILE *f, const char *scene, const vt_model *m, double t1, int form, void (*start)(const vt_model *, vt_data *))
{
    vt_run_options o = vt_default_run_options();
    o.t1 = t1;
    o.nout = (int)(2.0 * t1);
    o.rtol = 1e-6;
    o.atol = 1e-8;
    o.forward_check = 0;
    o.formulation = form;
    o.max_steps = 1000000;
    vt_data *d, *de;
    vt_trajectory *tr;
    vt_status st;
    if ((st = vt_data_create(&d, m)) || (st = vt_data_create(&de, m)) || (st = vt_trajectory_create(&tr, m, o.nout + 1)))
        die("drift set-up", st, NULL);
    start(m, d);
    const double c0 = cpu_now();
    if ((st = vt_dynamic_analysis(m, d, &o, tr))) die(scene, st, d);
    const double cpu = cpu_now() - c0;
    double E0 = 0.0, emax = 0.0, pmax = 0.0, pdmax = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        row_state(m, de, tr, k, 0);
        const double E = energy(m, de);
        if (k == 0) E0 = E;
        fprintf(f, "%s,%s,%.3f,%.6e,%.6e,%.6e\n", scene, form_name[form], tr->t[k], tr->phi_norm[k], tr->phid_norm[k], E - E0);
        emax = fmax(emax, fabs(E - E0));
        pmax = fmax(pmax, tr->phi_norm[k]);
        pdmax = fmax(pdmax, tr->phid_norm[k]);
    }
    const double turns = (tr->q[(size_t)(tr->nfilled - 1) * (size_t)m->nq] - tr->q[0]) / (2.0 * 3.14159265358979323846);
    printf("  %-11s %-10s t = %6.0f s: max |Phi| %.2e, max |Phi'| %.2e, max |dE| %.2e J, %ld steps, %.2f s cpu, "
           "first joint turned %.1f revolutions\n",
           scene, form_name[form], t1, pmax, pdmax, emax, tr->steps, cpu, turns);
    vt_trajectory_free(tr);
    vt_data_free(de);
    vt_data_free(d);
}

static void start_rest(const vt_model *m, vt_data *d)
{
    (void)m;
    (void)d; /* q = 0, at rest */
}
static void start_fourbar(const vt_model *m, vt_data *d)
{
    vt_scene_fourbar_assemble(m, d, 0.3, 12.0, NULL, NULL);
}

int main(int argc, char **argv)
{
    const char *outdir = argc > 1 ? argv[1] : ".";
    char path[4096];
    snprintf(path, sizeof path, "%s/work_precision.csv", outdir);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "scene,formulation,rtol,cpu_s,steps,residual_evals,error\n");
    printf("work-precision:\n");
    work_precision(f);
    fclose(f);
    printf("wrote %s\n", path);

    snprintf(path, sizeof path, "%s/drift.csv", outdir);
    f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "scene,formulation,t_s,phi_norm,phidot_norm,energy_error\n");
    vt_model *dl, *fb_driven, *fb, *pd;
    vt_status st;
    if ((st = vt_scene_double_link(&dl, 1)) || (st = vt_scene_fourbar(&fb_driven, vt_function_constant(0.0))) ||
        (st = vt_model_without_drives(&fb, fb_driven)) || (st = vt_scene_pendulum(&pd)))
        die("drift scenes", st, NULL);
    /* how long 100 crank revolutions take, from a first run */
    printf("drift (rtol 1e-6):\n");
    for (int form = 0; form < VT_FORMULATION_COUNT; form++) {
        drift_run(f, "double_link", dl, 100.0, form, start_rest);
        drift_run(f, "fourbar", fb, 95.0, form, start_fourbar);
        drift_run(f, "pendulum", pd, 2000.0, form, start_rest);
    }
    fclose(f);
    printf("wrote %s\n", path);
    vt_model_free(dl);
    vt_model_free(fb);
    vt_model_free(fb_driven);
    vt_model_free(pd);
    return 0;
}
