/* The Stewart–Gough platform of examples/scenes.c (vt_scene_stewart, docs/stewart.md) in MuJoCo,
 * following vtdyn's motion: the same bodies, masses, inertias and joints in MJCF
 * (mujoco_scenes.c, shared with the benchmark peer; the platform
 * on a free joint; each leg two hinges at its base point, x then the cylinder's y, as vtdyn's
 * universal joint, and a slide along the cylinder's z whose coordinate is the leg length), each
 * leg closed on the platform by a connect equality (site on the platform = site at the piston's
 * top) and its slide held on the leg length of the prescribed pose by a joint equality whose
 * constant term is set before every step (MuJoCo's way of prescribing a coordinate), with the
 * feed-forward of set_targets() so that its reference acceleration is the target's
 * (second argument --no-feed-forward: the plain target L_i(t)). The equality settings are
 * the benchmark peer's (mujoco_peer.c): solref "2e-4 1" (the smallest time constant refsafe
 * allows at the 1e-4 s step), solimp "0.9999 0.9999 0.001 0.5 2"; semi-implicit Euler, 1e-4 s.
 * Start: vtdyn's consistent state at t = 0 (vt_scene_stewart_assemble).
 *
 * Every 0.01 s over t ∈ [0, 2] s (the example's period): MuJoCo's leg forces (the joint
 * equalities' efc_force: the generalized force on each slide), its spherical-joint forces (the
 * connects' efc_force; MuJoCo's force on the platform, so minus vtdyn's platform-on-piston
 * force), its universal-joint forces (cfrc_int of each cylinder after mj_rnePostConstraint: the
 * world's force on it) against vtdyn's exact ones at the prescribed pose at that time
 * (vt_inverse_dynamics at vt_scene_stewart_assemble's state), and how far MuJoCo's platform
 * drifts from the prescribed pose.
 *
 * Writes CSV (default stewart_mujoco.csv, first argument):
 *   t_s, f1_N .. f6_N (MuJoCo's leg forces), df1_N .. df6_N (MuJoCo − vtdyn, N),
 *   dS1_N .. dS6_N, dU1_N .. dU6_N (|MuJoCo − vtdyn| of each spherical and universal force, N),
 *   pose_dev_m (MuJoCo's platform centre from the prescribed one, m)
 * Plot with bench/peers/stewart_mujoco.gp. Built with the MuJoCo peer (-Dmujoco_dir).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mujoco/mujoco.h>

#include "mujoco_scenes.h"
#include "scenes.h"

#define NLEG 6

/* MuJoCo's reference acceleration of a row is aref = −b v − k r (v = J q̇, r the residual), with
 * b = 2/(dmax τ), k = d/(dmax² τ² ζ²) for solref (τ, ζ) = (2e-4, 1) and solimp's d = dmax =
 * 0.9999. A joint equality's residual is q − c (c its constant term): on the exact motion
 * (q = L, q̇ = L̇) aref is L̈ when c = L + (L̈ + b L̇)/k, the feed-forward that gives MuJoCo the
 * target's rates it does not otherwise see. ff = 0: c = L (the slide lags by b/k L̇ and the
 * start brakes the moving slides). */
static void set_targets(mjModel *m, const vt_model *vm, double t, int ff)
{
    const double tau = 2e-4, dmax = 0.9999, b = 2.0 / (dmax * tau), k = dmax / (dmax * dmax * tau * tau);
    for (int i = 0; i < NLEG; i++) {
        double f[3];
        vt_function_eval(f, &vm->drive[i].f, t);
        m->eq_data[mjNEQDATA * (NLEG + i)] = ff ? f[0] + (f[2] + b * f[1]) / k : f[0];
    }
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "stewart_mujoco.csv";
    const int ff = !(argc > 2 && strcmp(argv[2], "--no-feed-forward") == 0);
    mjModel *m = vt_mj_scene_model(VT_MJ_STEWART, VT_MJ_DRIVE_EQUALITIES);
    if (!m) return 1;
    mjData *d = mj_makeData(m);
    vt_mj_map map;
    if (!d || vt_mj_scene_map(VT_MJ_STEWART, m, &map)) return fprintf(stderr, "stewart_mujoco: no map\n"), 1;

    vt_stewart sg = {3.14159265358979323846, 0.0, {{0}}};
    vt_model *vm = NULL;
    vt_data *vd = NULL;
    vt_status st = vt_scene_stewart(&vm, &sg);
    if (!st) st = vt_data_create(&vd, vm);
    if (st) return fprintf(stderr, "stewart_mujoco: %s\n", vt_status_string(st)), 1;
    if (m->nq != vm->nq || m->nv != vm->nv) return fprintf(stderr, "stewart_mujoco: coordinates differ\n"), 1;

    /* the start: vtdyn's consistent state; the same coordinates but the free joint's angular
     * velocity, which MuJoCo keeps in the platform's axes */
    vt_scene_stewart_assemble(vm, vd, &sg, 0.0);
    if ((st = vt_kinematics(vm, vd)) != VT_OK) return fprintf(stderr, "stewart_mujoco: %s\n", vt_status_string(st)), 1;
    vt_mj_scene_state(m, &map, d, vd->q, vd->qd, NULL);

    FILE *f = fopen(path, "w");
    if (!f) return perror(path), 1;
    fprintf(f, "t_s");
    for (int i = 1; i <= NLEG; i++) fprintf(f, ",f%d_N", i);
    for (int i = 1; i <= NLEG; i++) fprintf(f, ",df%d_N", i);
    for (int i = 1; i <= NLEG; i++) fprintf(f, ",dS%d_N", i);
    for (int i = 1; i <= NLEG; i++) fprintf(f, ",dU%d_N", i);
    fprintf(f, ",pose_dev_m\n");

    const double dt = m->opt.timestep, t1 = 2.0;
    const int every = 100, nstep = (int)lround(t1 / dt);
    double dfmax = 0.0, dsmax = 0.0, dumax = 0.0, devmax = 0.0, fref = 0.0;
    for (int n = 0; n <= nstep; n++) {
        const double t = n * dt;
        set_targets(m, vm, t, ff);
        if (n % every) {
            mj_step(m, d);
            continue;
        }
        mj_forward(m, d);
        mj_rnePostConstraint(m, d);
        double leg[NLEG] = {0}, con[3 * NLEG] = {0};
        int nrow[NLEG] = {0};
        for (int e = 0; e < d->nefc; e++) {
            if (d->efc_type[e] != mjCNSTR_EQUALITY) continue;
            const int id = d->efc_id[e];
            if (id < NLEG) {
                /* a connect's three rows in order x, y, z */
                if (nrow[id] < 3) con[3 * id + nrow[id]++] = d->efc_force[e];
            } else {
                leg[id - NLEG] = d->efc_force[e];
            }
        }
        vt_scene_stewart_assemble(vm, vd, &sg, t);
        if ((st = vt_inverse_dynamics(vm, vd)) != VT_OK)
            return fprintf(stderr, "stewart_mujoco: %s: %s\n", vt_status_string(st), vd->message), 1;
        double dS[NLEG], dU[NLEG], dev = 0.0;
        for (int i = 0; i < NLEG; i++) {
            const double *Sv = vd->cut_force + 3 * i, *Uv = vd->jnt_force + 3 * (2 + 2 * i);
            const mjtNum *Um = d->cfrc_int + 6 * (2 + 2 * i) + 3; /* MuJoCo body 2 + 2i: cylinder i (1 the platform) */
            double s2 = 0.0, u2 = 0.0;
            for (int c = 0; c < 3; c++) {
                s2 += (-con[3 * i + c] - Sv[c]) * (-con[3 * i + c] - Sv[c]);
                u2 += (Um[c] - Uv[c]) * (Um[c] - Uv[c]);
            }
            dS[i] = sqrt(s2);
            dU[i] = sqrt(u2);
            dfmax = fmax(dfmax, fabs(leg[i] - vd->drive_effort[i]));
            dsmax = fmax(dsmax, dS[i]);
            dumax = fmax(dumax, dU[i]);
            fref = fmax(fref, fabs(vd->drive_effort[i]));
        }
        for (int c = 0; c < 3; c++) dev += (d->qpos[c] - vd->q[c]) * (d->qpos[c] - vd->q[c]);
        dev = sqrt(dev);
        devmax = fmax(devmax, dev);
        fprintf(f, "%.4f", t);
        for (int i = 0; i < NLEG; i++) fprintf(f, ",%.12g", leg[i]);
        for (int i = 0; i < NLEG; i++) fprintf(f, ",%.6e", leg[i] - vd->drive_effort[i]);
        for (int i = 0; i < NLEG; i++) fprintf(f, ",%.6e", dS[i]);
        for (int i = 0; i < NLEG; i++) fprintf(f, ",%.6e", dU[i]);
        fprintf(f, ",%.6e\n", dev);
        mj_Euler(m, d);
    }
    fclose(f);
    printf("MuJoCo %s, Stewart-Gough platform following vtdyn's leg lengths, t in [0, %g] s -> %s\n", mj_versionString(),
           t1, path);
    printf("leg forces:        max |MuJoCo - vtdyn| %.3g N (largest leg force %.4g N)\n", dfmax, fref);
    printf("spherical forces:  max |MuJoCo - vtdyn| %.3g N\n", dsmax);
    printf("universal forces:  max |MuJoCo - vtdyn| %.3g N\n", dumax);
    printf("platform centre:   max distance from the prescribed pose %.3g m\n", devmax);
    vt_data_free(vd);
    vt_model_free(vm);
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
