/* The Delta robot of examples/delta.c in MuJoCo: how far its soft equality constraints put the
 * reactions from vtdyn's exact ones at the same motion.
 *
 * vtdyn first: the path's kinematic analysis (vt_scene_delta, VT_DELTA_PATH; 201 rows over one
 * turn), and at every row the motor torques and reactions of the machine driven by its motors
 * (VT_DELTA_MOTORS, vt_inverse_dynamics_motion), as examples/delta.c computes them.
 *
 * MuJoCo then builds the same geometry in MJCF (mujoco_scenes.c, shared with the benchmark
 * peer): the arms on hinges, each rod on two hinges (the arm's y, then the rod's x: vtdyn's
 * universal joint, MuJoCo applying a body's joints in order),
 * the platform on a free joint, and the six ball joints as equality `connect` constraints between
 * a site at each rod's lower end (site1) and its point on the platform (site2): sites, since the
 * loops are open at qpos0. At every row: qpos and qvel set from vtdyn's state (the free joint's
 * angular velocity in the platform's axes, as MuJoCo keeps it), vtdyn's motor torques applied as
 * qfrc_applied on the motor hinges, mj_forward (MuJoCo's own constrained forward dynamics at the
 * same state and actuation), then mj_rnePostConstraint for the bearing forces. MuJoCo's qacc and
 * reactions are then compared with vtdyn's q̈ and reactions: with exact constraints they would
 * agree to round-off; what is left is MuJoCo's constraint model (soft rows: an impedance below 1
 * leaves part of the unconstrained acceleration, and the reactions shrink with it).
 *
 * Two settings of the constraints:
 *   tight    timestep 1e-4, solref "2e-4 1", solimp "0.9999 0.9999 0.001 0.5 2" (as
 *            bench/peers/mujoco_peer.c: the stiffest MuJoCo allows at that step)
 *   default  MuJoCo's defaults: timestep 0.002, solref "0.02 1", solimp "0.9 0.95 0.001 0.5 2"
 * Both with the Newton solver to tolerance 1e-14 (100 iterations): the solver's own error out of
 * the comparison.
 *
 * Forces compared: a ball joint's — MuJoCo's efc_force of its connect row (the force on site1's
 * body, the rod, in world axes) against vtdyn's cut_force (the platform on the rod, global); a
 * motor bearing's — MuJoCo's cfrc_int force part of the arm (the parent on the body, world axes;
 * the hinge's torque is in the moment part only) against vtdyn's jnt_force of the arm.
 *
 * Writes delta_mujoco.csv into the directory given as its argument (default "."), one row per
 * vtdyn row:
 *   t_s, tau1_Nm..tau3_Nm (vtdyn's motor torques, applied in MuJoCo),
 *   vt_ball1a_N (|force| of ball joint 1a in vtdyn), vt_mot1_N (|force| of motor bearing 1),
 *   then for S in tight, default:
 *   mj_ball1a_N_S, mj_mot1_N_S (MuJoCo's), ball_err_N_S (largest |f_mj − f_vt| over the six ball
 *   joints), mot_err_N_S (over the three motor bearings), acc_err_S (largest |q̈_mj − q̈_vt| over
 *   every rate, rad/s² or m/s²), and prints the largest of each. Plot with delta_mujoco.gp
 * (`meson test -C build --benchmark delta_mujoco` runs both: build/bench/delta_mujoco.{csv,png}).
 * Build: meson with -Dmujoco_dir (bench/peers/install.sh prints it): build/bench/delta_mujoco.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mujoco/mujoco.h>

#include "mujoco_scenes.h"
#include "scenes.h"

#define PERIOD 1.0
#define NOUT 200

typedef struct {
    mjModel *m;
    mjData *d;
    vt_mj_map map; /* vtdyn's coordinates, rates and bodies in MuJoCo's model */
} mj_delta;

static int mj_delta_open(mj_delta *s, int tight)
{
    s->m = vt_mj_scene_model(VT_MJ_DELTA, tight ? 0 : VT_MJ_DEFAULT_SOFT);
    if (!s->m) return -1;
    s->d = mj_makeData(s->m);
    if (!s->d || vt_mj_scene_map(VT_MJ_DELTA, s->m, &s->map)) return -1;
    return 0;
}

/* vtdyn's state in, vtdyn's motor torques applied; MuJoCo's forward dynamics and reactions */
static void mj_delta_forward(mj_delta *s, const double *q, const double *qd, const double *tau)
{
    mjData *d = s->d;
    vt_mj_scene_state(s->m, &s->map, d, q, qd, NULL);
    for (int v = 0; v < s->m->nv; v++) d->qfrc_applied[v] = 0.0;
    for (int i = 0; i < 3; i++) d->qfrc_applied[s->map.vadr[i]] = tau[i];
    mj_forward(s->m, d);
    mj_rnePostConstraint(s->m, d);
}

static double norm3(const double *v)
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

int main(int argc, char **argv)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/delta_mujoco.csv", argc > 1 ? argv[1] : ".");
    vt_model *m = NULL, *mm = NULL;
    vt_data *d = NULL, *dm = NULL;
    vt_trajectory *tr = NULL;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = PERIOD;
    opt.nout = NOUT;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.forward_check = 0; /* examples/delta.c runs it; here only the motion is needed */
    double p0[3];
    vt_scene_delta_path(0.0, PERIOD, p0, NULL, NULL);
    vt_status st = vt_scene_delta(&m, PERIOD, VT_DELTA_PATH);
    if (!st) st = vt_scene_delta(&mm, PERIOD, VT_DELTA_MOTORS);
    if (!st) st = vt_data_create(&d, m);
    if (!st) st = vt_data_create(&dm, mm);
    if (!st) st = vt_trajectory_create(&tr, m, opt.nout + 1);
    if (!st && vt_scene_delta_assemble(m, d, p0)) st = VT_ERR_NEWTON;
    if (!st) st = vt_kinematic_analysis(m, d, &opt, tr);
    if (st) {
        fprintf(stderr, "delta_mujoco: %s%s%s\n", vt_status_string(st), d ? ": " : "", d ? d->message : "");
        return 1;
    }
    mj_delta peer[2];
    memset(peer, 0, sizeof peer);
    if (mj_delta_open(&peer[0], 1) || mj_delta_open(&peer[1], 0)) return 1;
    if (peer[0].m->neq != 6 || peer[0].m->nv != 21) {
        fprintf(stderr, "delta_mujoco: MuJoCo's model has %d equalities and %d dofs (6 and 21 expected)\n",
                (int)peer[0].m->neq, (int)peer[0].m->nv);
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    static const char *const set[2] = {"tight", "default"};
    fprintf(f, "t_s,tau1_Nm,tau2_Nm,tau3_Nm,vt_ball1a_N,vt_mot1_N");
    for (int p = 0; p < 2; p++)
        fprintf(f, ",mj_ball1a_N_%s,mj_mot1_N_%s,ball_err_N_%s,mot_err_N_%s,acc_err_%s", set[p], set[p], set[p], set[p],
                set[p]);
    fprintf(f, "\n");
    double worst[2][3] = {{0}}, ball_max = 0.0, mot_max = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + (size_t)k * (size_t)m->nq, *qd = tr->qd + (size_t)k * (size_t)m->nv;
        memcpy(dm->q, q, (size_t)m->nq * sizeof(double));
        memcpy(dm->qd, qd, (size_t)m->nv * sizeof(double));
        memcpy(dm->qdd, tr->qdd + (size_t)k * (size_t)m->nv, (size_t)m->nv * sizeof(double));
        if ((st = vt_inverse_dynamics_motion(mm, dm))) {
            fprintf(stderr, "delta_mujoco: %s: %s\n", vt_status_string(st), dm->message);
            return 1;
        }
        for (int c = 0; c < 6; c++) ball_max = fmax(ball_max, norm3(dm->cut_force + 3 * c));
        for (int i = 1; i <= 3; i++) mot_max = fmax(mot_max, norm3(dm->jnt_force + 3 * i));
        fprintf(f, "%.6f,%.15g,%.15g,%.15g,%.15g,%.15g", tr->t[k], dm->drive_effort[0], dm->drive_effort[1],
                dm->drive_effort[2], norm3(dm->cut_force), norm3(dm->jnt_force + 3));
        for (int p = 0; p < 2; p++) {
            mj_delta *s = &peer[p];
            mj_delta_forward(s, q, qd, dm->drive_effort);
            const mjData *md = s->d;
            if (md->nefc != 18) { /* the six connects' rows, nothing else */
                fprintf(stderr, "delta_mujoco: %d constraint rows at t = %g (18 expected)\n", (int)md->nefc, tr->t[k]);
                return 1;
            }
            double eb = 0.0, em = 0.0, ea = 0.0;
            for (int c = 0; c < 6; c++) { /* connect c: efc rows 3c .. 3c + 2, the force on the rod */
                const double df[3] = {md->efc_force[3 * c] - dm->cut_force[3 * c],
                                      md->efc_force[3 * c + 1] - dm->cut_force[3 * c + 1],
                                      md->efc_force[3 * c + 2] - dm->cut_force[3 * c + 2]};
                eb = fmax(eb, norm3(df));
            }
            for (int i = 0; i < 3; i++) {
                const mjtNum *w = md->cfrc_int + 6 * s->map.body[1 + i];
                const double df[3] = {w[3] - dm->jnt_force[3 * (1 + i)], w[4] - dm->jnt_force[3 * (1 + i) + 1],
                                      w[5] - dm->jnt_force[3 * (1 + i) + 2]};
                em = fmax(em, norm3(df));
            }
            for (int v = 0; v < 15; v++) ea = fmax(ea, fabs(md->qacc[s->map.vadr[v]] - dm->qdd[v]));
            for (int c = 0; c < 3; c++) /* the platform's linear acceleration (its rotation stays 0) */
                ea = fmax(ea, fabs(md->qacc[s->map.vadr[15 + c]] - dm->qdd[mm->body_vadr[10] + c]));
            const mjtNum *w1 = md->cfrc_int + 6 * s->map.body[1];
            fprintf(f, ",%.15g,%.15g,%.6e,%.6e,%.6e", norm3(md->efc_force), norm3(w1 + 3), eb, em, ea);
            worst[p][0] = fmax(worst[p][0], eb);
            worst[p][1] = fmax(worst[p][1], em);
            worst[p][2] = fmax(worst[p][2], ea);
        }
        fprintf(f, "\n");
    }
    fclose(f);
    printf("Delta robot, MuJoCo %s against vtdyn: %d rows -> %s\n", mj_versionString(), tr->nfilled, path);
    printf("largest forces in vtdyn: ball joint %.4g N, motor bearing %.4g N\n", ball_max, mot_max);
    for (int p = 0; p < 2; p++)
        printf("%-8s ball joints off by up to %.3g N, motor bearings %.3g N, accelerations %.3g\n", set[p],
               worst[p][0], worst[p][1], worst[p][2]);
    for (int p = 0; p < 2; p++) {
        mj_deleteData(peer[p].d);
        mj_deleteModel(peer[p].m);
    }
    vt_trajectory_free(tr);
    vt_data_free(dm);
    vt_data_free(d);
    vt_model_free(mm);
    vt_model_free(m);
    return 0;
}
