/* The knee four-bar of examples/scenes.c (vt_scene_knee, docs/knee.md) in MuJoCo, following
 * vtdyn's motion: the same bodies, masses, inertias and joints in MJCF (mujoco_scenes.c, shared
 * with the benchmark peer: hinges about z at the hip for the thigh and the crank, at the crank's
 * tip for the coupler and at the knee for the shank), the loop closed by a connect equality (the
 * coupler's far end = the shank's lever point: 3 rows, which with the planar tree's 4 hinges are
 * dependent, as MuJoCo's soft constraints allow; vtdyn closes it with its planar revolute cut
 * joint's 2 rows), the hip and the motor held on their prescribed angles by joint equalities
 * whose constant terms are set before every step with the feed-forward of stewart_mujoco.c
 * (c = f + (f'' + b f')/k, so that MuJoCo's reference acceleration on the exact motion is the
 * drive's; --no-feed-forward: c = f). The equality
 * settings are the benchmark peer's (solref "2e-4 1", solimp "0.9999 0.9999 0.001 0.5 2");
 * semi-implicit Euler, 1e-4 s, from vtdyn's consistent state at t = 0.
 *
 * Every 0.005 s over t ∈ [0, 1] s (the example's two strides): MuJoCo's hip and motor torques
 * (the joint equalities' efc_force), its force of the shank on the coupler (the connect's
 * efc_force: MuJoCo's force on body1, the coupler) and every hinge's bearing force (cfrc_int
 * after mj_rnePostConstraint) against vtdyn's exact ones at the prescribed motion at that time.
 *
 * Writes CSV (default knee_mujoco.csv, first argument):
 *   t_s, tau_hip_Nm, tau_motor_Nm (MuJoCo's), dtau_hip_Nm, dtau_motor_Nm (MuJoCo − vtdyn),
 *   dlever_N, dhip_N, dmotor_N, dcrank_N, dknee_N (|MuJoCo − vtdyn| of the cut's and each
 *   joint's force, N), knee_dev_rad (MuJoCo's knee angle from vtdyn's)
 * Plot with bench/peers/knee_mujoco.gp. Built with the MuJoCo peer (-Dmujoco_dir).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mujoco/mujoco.h>

#include "mujoco_scenes.h"
#include "scenes.h"

#define PI 3.14159265358979323846

/* the joint equalities' constant terms (equalities 1 and 2): see stewart_mujoco.c */
static void set_targets(mjModel *m, const vt_model *vm, double t, int ff)
{
    const double tau = 2e-4, dmax = 0.9999, b = 2.0 / (dmax * tau), k = dmax / (dmax * dmax * tau * tau);
    for (int i = 0; i < 2; i++) {
        double f[3];
        vt_function_eval(f, &vm->drive[i].f, t);
        m->eq_data[mjNEQDATA * (1 + i)] = ff ? f[0] + (f[2] + b * f[1]) / k : f[0];
    }
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "knee_mujoco.csv";
    const int ff = !(argc > 2 && strcmp(argv[2], "--no-feed-forward") == 0);
    mjModel *m = vt_mj_scene_model(VT_MJ_KNEE, VT_MJ_DRIVE_EQUALITIES);
    if (!m) return 1;
    mjData *d = mj_makeData(m);

    const double om = 4.0 * PI;
    vt_model *vm = NULL;
    vt_data *vd = NULL;
    vt_status st = vt_scene_knee(&vm, vt_function_sine(-0.25 * PI, 0.35, om, 0.0), vt_function_sine(0.5 * PI, 0.4, om, 0.8), 1);
    if (!st) st = vt_data_create(&vd, vm);
    if (st) return fprintf(stderr, "knee_mujoco: %s\n", vt_status_string(st)), 1;
    if (m->nq != vm->nq || m->nv != vm->nv) return fprintf(stderr, "knee_mujoco: coordinates differ\n"), 1;

    FILE *f = fopen(path, "w");
    if (!f) return perror(path), 1;
    fprintf(f, "t_s,tau_hip_Nm,tau_motor_Nm,dtau_hip_Nm,dtau_motor_Nm,dlever_N,dhip_N,dmotor_N,dcrank_N,dknee_N,knee_dev_rad\n");
    const double dt = m->opt.timestep, t1 = 1.0;
    const int every = 50, nstep = (int)lround(t1 / dt);
    double dtmax = 0.0, dfmax = 0.0, devmax = 0.0, tref = 0.0;
    for (int n = 0; n <= nstep; n++) {
        const double t = n * dt;
        /* vtdyn's exact state at t: the start, and the reference of every row */
        double hip[3], mot[3];
        vt_function_eval(hip, &vm->drive[0].f, t);
        vt_function_eval(mot, &vm->drive[1].f, t);
        if (n == 0 || n % every == 0) {
            if (vt_scene_knee_assemble(vm, vd, hip[0], hip[1], mot[0], mot[1], NULL))
                return fprintf(stderr, "knee_mujoco: the loop does not close at t = %g\n", t), 1;
            vd->time = t;
        }
        if (n == 0) {
            for (int k = 0; k < m->nq; k++) d->qpos[k] = vd->q[k];
            for (int k = 0; k < m->nv; k++) d->qvel[k] = vd->qd[k];
        }
        set_targets(m, vm, t, ff);
        if (n % every) {
            mj_step(m, d);
            continue;
        }
        mj_forward(m, d);
        mj_rnePostConstraint(m, d);
        double tau[2] = {0, 0}, lever[3] = {0, 0, 0};
        int nrow = 0;
        for (int e = 0; e < d->nefc; e++) {
            if (d->efc_type[e] != mjCNSTR_EQUALITY) continue;
            if (d->efc_id[e] == 0 && nrow < 3) lever[nrow++] = d->efc_force[e];
            else if (d->efc_id[e] > 0) tau[d->efc_id[e] - 1] = d->efc_force[e];
        }
        if ((st = vt_inverse_dynamics(vm, vd)) != VT_OK)
            return fprintf(stderr, "knee_mujoco: %s: %s\n", vt_status_string(st), vd->message), 1;
        double dF[5];
        double s2 = 0.0;
        for (int c = 0; c < 3; c++) s2 += (lever[c] - vd->cut_force[c]) * (lever[c] - vd->cut_force[c]);
        dF[0] = sqrt(s2);
        for (int b = 1; b <= 4; b++) { /* MuJoCo's bodies are numbered as vtdyn's */
            const mjtNum *F = d->cfrc_int + 6 * b + 3;
            const double *V = vd->jnt_force + 3 * b;
            dF[b] = sqrt((F[0] - V[0]) * (F[0] - V[0]) + (F[1] - V[1]) * (F[1] - V[1]) + (F[2] - V[2]) * (F[2] - V[2]));
        }
        const int kq = vm->body_qadr[4];
        const double dev = fabs(remainder(d->qpos[kq] - vd->q[kq], 2.0 * PI));
        for (int j = 0; j < 2; j++) {
            dtmax = fmax(dtmax, fabs(tau[j] - vd->drive_effort[j]));
            tref = fmax(tref, fabs(vd->drive_effort[j]));
        }
        for (int j = 0; j < 5; j++) dfmax = fmax(dfmax, dF[j]);
        devmax = fmax(devmax, dev);
        fprintf(f, "%.4f,%.12g,%.12g,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e\n", t, tau[0], tau[1],
                tau[0] - vd->drive_effort[0], tau[1] - vd->drive_effort[1], dF[0], dF[1], dF[2], dF[3], dF[4], dev);
        mj_Euler(m, d);
    }
    fclose(f);
    printf("MuJoCo %s, knee four-bar following vtdyn's hip and motor angles, t in [0, %g] s -> %s\n", mj_versionString(),
           t1, path);
    printf("torques:        max |MuJoCo - vtdyn| %.3g N m (largest torque %.4g N m)\n", dtmax, tref);
    printf("bearing forces: max |MuJoCo - vtdyn| %.3g N\n", dfmax);
    printf("knee angle:     max |MuJoCo - vtdyn| %.3g rad\n", devmax);
    vt_data_free(vd);
    vt_model_free(vm);
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
