/* A Delta robot (vt_scene_delta() in scenes.h: FlexPicker-like, three motor-driven upper arms,
 * forearms of two rods each with a universal joint at the elbow and a spherical joint at the
 * platform, the platform on a free joint) whose platform centre follows a path: a circle of
 * radius 0.15 m that rises and falls by 0.05 m twice a turn, one turn a second.
 *
 * 1. The path: three point drives on the platform's centre (the model VT_DELTA_PATH) fix every
 *    rate; a kinematic analysis (Newton–Raphson on Φ(q, t) = 0 at every output time, q̈ and λ
 *    from (5)) with the forward check: the drives removed, their generalized forces applied, the
 *    same start, IDA — the platform must follow the same path.
 * 2. The motors: the same motion given to the model driven at its motors (VT_DELTA_MOTORS) by
 *    vt_inverse_dynamics_motion(): the motor angles' accelerations are the given ones, the cut
 *    joints give the rest, and the drives' efforts are the motor torques; the reactions are those
 *    of the machine driven by its motors (a point drive would push the platform instead).
 *    Checks: the rest of q̈ as the path's run found it, and the virtual power of the motors equal
 *    to the point drives' (both move the machine the same way).
 *
 * Writes CSV (default delta.csv; first argument to change it), t ∈ [0, 1] s, 201 rows:
 *   t_s                         time, s
 *   tau1_Nm .. tau3_Nm          motor torques about the motor axes t_i (θ_i > 0 down), N m
 *   x_m, y_m, z_m               the platform centre, m
 *   mot<i>_f{x,y,z}_N, mot<i>_n{x,y,z}_Nm     motor bearing i (revolute): the base on arm i at
 *                               its joint point, force and moment (about the joint point), global
 *   elb<i><a|b>_f{x,y,z}_N, elb<i><a|b>_n{x,y,z}_Nm   elbow universal joints: arm i on rod a (at
 *                               −h along the motor axis) or b (+h), global
 *   ball<i><a|b>_f{x,y,z}_N     ball joints (spherical: no moment): the platform on the rod's
 *                               lower end, global
 *   fwd_err_m                   forward check: |platform centre (forward) − (driven)|, m
 * (the platform's free joint carries nothing by definition) and prints its checks. Plot with
 * examples/delta.gp.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

#define PERIOD 1.0
#define NOUT 200

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "delta.csv";
    vt_model *m = NULL, *mm = NULL;
    vt_data *d = NULL, *dm = NULL;
    vt_trajectory *tr = NULL;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = PERIOD;
    opt.nout = NOUT;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
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
        fprintf(stderr, "delta: %s%s%s\n", vt_status_string(st), d ? ": " : "", d ? d->message : "");
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "t_s,tau1_Nm,tau2_Nm,tau3_Nm,x_m,y_m,z_m");
    static const char *const xyz = "xyz";
    for (int i = 1; i <= 3; i++) {
        for (int c = 0; c < 3; c++) fprintf(f, ",mot%d_f%c_N", i, xyz[c]);
        for (int c = 0; c < 3; c++) fprintf(f, ",mot%d_n%c_Nm", i, xyz[c]);
    }
    for (int i = 1; i <= 3; i++)
        for (int k = 0; k < 2; k++) {
            for (int c = 0; c < 3; c++) fprintf(f, ",elb%d%c_f%c_N", i, "ab"[k], xyz[c]);
            for (int c = 0; c < 3; c++) fprintf(f, ",elb%d%c_n%c_Nm", i, "ab"[k], xyz[c]);
        }
    for (int i = 1; i <= 3; i++)
        for (int k = 0; k < 2; k++)
            for (int c = 0; c < 3; c++) fprintf(f, ",ball%d%c_f%c_N", i, "ab"[k], xyz[c]);
    fprintf(f, ",fwd_err_m\n");

    const int pq = m->body_qadr[10];
    double path_err = 0.0, fwd = 0.0, qdd_err = 0.0, pow_err = 0.0, pow_max = 0.0;
    double tau_max = 0.0, mot_max = 0.0, elb_max = 0.0, ball_max = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + (size_t)k * (size_t)m->nq, *qd = tr->qd + (size_t)k * (size_t)m->nv;
        const double *qdd = tr->qdd + (size_t)k * (size_t)m->nv, *qf = tr->q_fwd + (size_t)k * (size_t)m->nq;
        for (int c = 0; c < m->nq; c++) dm->q[c] = q[c];
        for (int c = 0; c < m->nv; c++) {
            dm->qd[c] = qd[c];
            dm->qdd[c] = qdd[c];
        }
        dm->time = tr->t[k];
        if ((st = vt_inverse_dynamics_motion(mm, dm))) {
            fprintf(stderr, "delta: %s: %s\n", vt_status_string(st), dm->message);
            fclose(f);
            return 1;
        }
        /* the motion of every rate as the path's run found it; the motors' virtual power equal to
         * the point drives' (the same motion, the same kinetic and potential energy) */
        for (int c = 0; c < m->nv; c++) qdd_err = fmax(qdd_err, fabs(dm->qdd[c] - qdd[c]) / (1.0 + fabs(qdd[c])));
        double pm = 0.0, pp = 0.0, pa = 0.0;
        for (int i = 0; i < 3; i++) {
            pm += dm->drive_effort[i] * qd[mm->body_vadr[1 + i]];
            pp += tr->drive_effort[(size_t)k * 3 + (size_t)i] * qd[m->body_vadr[10] + i];
            pa += fabs(dm->drive_effort[i] * qd[mm->body_vadr[1 + i]]);
        }
        pow_err = fmax(pow_err, fabs(pm - pp));
        pow_max = fmax(pow_max, pa);
        double want[3], e = 0.0, ef = 0.0;
        vt_scene_delta_path(tr->t[k], PERIOD, want, NULL, NULL);
        for (int c = 0; c < 3; c++) {
            e += (q[pq + c] - want[c]) * (q[pq + c] - want[c]);
            ef += (qf[pq + c] - q[pq + c]) * (qf[pq + c] - q[pq + c]);
        }
        path_err = fmax(path_err, sqrt(e));
        fwd = fmax(fwd, sqrt(ef));

        fprintf(f, "%.6f,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g", tr->t[k], dm->drive_effort[0], dm->drive_effort[1],
                dm->drive_effort[2], q[pq], q[pq + 1], q[pq + 2]);
        for (int b = 1; b <= 9; b++) {
            const double *fo = dm->jnt_force + 3 * b, *mo = dm->jnt_moment + 3 * b;
            fprintf(f, ",%.15g,%.15g,%.15g,%.15g,%.15g,%.15g", fo[0], fo[1], fo[2], mo[0], mo[1], mo[2]);
            const double n = sqrt(fo[0] * fo[0] + fo[1] * fo[1] + fo[2] * fo[2]);
            if (b <= 3) mot_max = fmax(mot_max, n);
            else elb_max = fmax(elb_max, n);
        }
        for (int c = 0; c < 6; c++) {
            const double *fo = dm->cut_force + 3 * c;
            fprintf(f, ",%.15g,%.15g,%.15g", fo[0], fo[1], fo[2]);
            ball_max = fmax(ball_max, sqrt(fo[0] * fo[0] + fo[1] * fo[1] + fo[2] * fo[2]));
        }
        fprintf(f, ",%.3e\n", sqrt(ef));
        for (int i = 0; i < 3; i++) tau_max = fmax(tau_max, fabs(dm->drive_effort[i]));
    }
    fclose(f);
    printf("vtdyn Delta robot: kinematic analysis over one turn of the path, %d rows -> %s\n", tr->nfilled, path);
    printf("platform centre on the prescribed path:             max error %.3g m\n", path_err);
    printf("forward check (drive forces applied, drives removed): platform deviation %.3g m (%ld IDA steps)\n", fwd,
           tr->steps_fwd);
    printf("driven at the motors: q̈ against the path's run:      max relative difference %.3g\n", qdd_err);
    printf("motor power against the point drives' power:          max difference %.3g W (of %.4g W)\n", pow_err,
           pow_max);
    printf("largest motor torque:                                 %.4g N m\n", tau_max);
    printf("largest bearing force: motor %.4g N, elbow %.4g N, ball joint %.4g N\n", mot_max, elb_max, ball_max);
    double rc = 1.0;
    for (int k = 0; k < tr->nfilled; k++) rc = fmin(rc, tr->rcond[k]);
    printf("smallest condition estimate on the path:              %.3g\n", rc);
    vt_trajectory_free(tr);
    vt_data_free(dm);
    vt_data_free(d);
    vt_model_free(mm);
    vt_model_free(m);
    return (fwd <= 1e-6 && path_err <= 1e-9 && qdd_err <= 1e-9 && pow_err <= 1e-9 * (1.0 + pow_max)) ? 0 : 1;
}
