/* A Delta robot (vt_scene_delta() in scenes.h: FlexPicker-like, three motor-driven upper arms,
 * forearms of two rods each with a universal joint at the elbow and a spherical joint at the
 * platform, the platform on a free joint) whose platform centre follows a path: a circle of
 * radius 0.15 m that rises and falls by 0.05 m twice a turn, one turn a second.
 *
 * 1. The path: three point drives on the platform's centre (the model VT_DELTA_PATH) fix every
 *    rate; a kinematic analysis (Newton–Raphson on Φ(q, t) = 0 at every output time, q̈ and λ
 *    from (5)) with the forward check: the drives removed, their generalized forces applied, the
 *    same start, IDA — the platform must follow the same path.
 * 2. The motors: one model driven at its motor angles (vt_scene_delta_ik(), VT_DELTA_IK) by the
 *    path's closed-form inverse kinematics θ_i(t), with θ̇_i and θ̈_i exact; its kinematic
 *    analysis gives the drives' efforts, which are the motor torques, and the reactions of the
 *    machine driven by its motors (a point drive would push the platform instead). Its forward
 *    check applies the motor torques alone, the motors' drives removed.
 *    Checks: its platform on the path, its q̈ against the path's run (the same motion from two
 *    models), and the power of the motors equal to the point drives' (both move the machine the
 *    same way).
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
 *   fwd_err_m                   the motor model's forward check (the torques applied, the motor
 *                               drives removed): |platform centre (forward) − (driven)|, m
 * (the platform's free joint carries nothing by definition) and prints its checks. Plot with
 * examples/delta.gp.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

#define PERIOD 1.0
#define NOUT 200

static int fail(vt_status st, const vt_data *d)
{
    fprintf(stderr, "delta: %s%s%s\n", vt_status_string(st), d ? ": " : "", d ? d->message : "");
    return 1;
}

/* the largest distance of a run's platform centre from the path, and from its forward run's */
static void platform_errors(const vt_trajectory *tr, double *path_err, double *fwd)
{
    const vt_model *m = tr->model;
    const int pq = m->body_qadr[10];
    *path_err = *fwd = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double *q = tr->q + (size_t)k * (size_t)m->nq, *qf = tr->q_fwd + (size_t)k * (size_t)m->nq;
        double want[3], e = 0.0, ef = 0.0;
        vt_scene_delta_path(tr->t[k], PERIOD, want, NULL, NULL);
        for (int c = 0; c < 3; c++) {
            e += (q[pq + c] - want[c]) * (q[pq + c] - want[c]);
            ef += (qf[pq + c] - q[pq + c]) * (qf[pq + c] - q[pq + c]);
        }
        *path_err = fmax(*path_err, sqrt(e));
        *fwd = fmax(*fwd, sqrt(ef));
    }
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "delta.csv";
    vt_model *m = NULL, *mi = NULL;
    vt_data *d = NULL, *di = NULL;
    vt_trajectory *tr = NULL, *ti = NULL;
    vt_delta_ik ik; /* the motor drives' callback data: outlives mi */
    vt_run_options opt = vt_default_run_options();
    opt.t1 = PERIOD;
    opt.nout = NOUT;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    double p0[3];
    vt_scene_delta_path(0.0, PERIOD, p0, NULL, NULL);
    vt_status st = vt_scene_delta(&m, PERIOD, VT_DELTA_PATH);
    if (!st) st = vt_scene_delta_ik(&mi, &ik, PERIOD);
    if (!st) st = vt_data_create(&d, m);
    if (!st) st = vt_data_create(&di, mi);
    if (!st) st = vt_trajectory_create(&tr, m, opt.nout + 1);
    if (!st) st = vt_trajectory_create(&ti, mi, opt.nout + 1);
    if (!st && (vt_scene_delta_assemble(m, d, p0) || vt_scene_delta_assemble(mi, di, p0))) st = VT_ERR_NEWTON;
    if (!st && (st = vt_kinematic_analysis(m, d, &opt, tr))) return fail(st, d);
    if (!st && (st = vt_kinematic_analysis(mi, di, &opt, ti))) return fail(st, di);
    if (st) return fail(st, NULL);
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

    const int pq = mi->body_qadr[10];
    const size_t nb = 3 * (size_t)(mi->nbody + 1), nc = 3 * (size_t)mi->ncut;
    double path_err, fwd, path_err_i, fwd_i, qdd_err = 0.0, pow_err = 0.0, pow_max = 0.0;
    double tau_max = 0.0, mot_max = 0.0, elb_max = 0.0, ball_max = 0.0;
    platform_errors(tr, &path_err, &fwd);
    platform_errors(ti, &path_err_i, &fwd_i);
    for (int k = 0; k < ti->nfilled; k++) {
        const double *q = ti->q + (size_t)k * (size_t)mi->nq, *qf = ti->q_fwd + (size_t)k * (size_t)mi->nq;
        const double *qd = ti->qd + (size_t)k * (size_t)mi->nv, *qdd = ti->qdd + (size_t)k * (size_t)mi->nv;
        const double *qd_p = tr->qd + (size_t)k * (size_t)m->nv, *qdd_p = tr->qdd + (size_t)k * (size_t)m->nv;
        const double *tau = ti->drive_effort + (size_t)k * 3;
        /* the same motion as the path's run; the motors' power equal to the point drives' (the
         * same motion, the same kinetic and potential energy) */
        for (int c = 0; c < mi->nv; c++) qdd_err = fmax(qdd_err, fabs(qdd[c] - qdd_p[c]) / (1.0 + fabs(qdd_p[c])));
        double pm = 0.0, pp = 0.0, pa = 0.0;
        for (int i = 0; i < 3; i++) {
            pm += tau[i] * qd[mi->body_vadr[1 + i]];
            pp += tr->drive_effort[(size_t)k * 3 + (size_t)i] * qd_p[m->body_vadr[10] + i];
            pa += fabs(tau[i] * qd[mi->body_vadr[1 + i]]);
        }
        pow_err = fmax(pow_err, fabs(pm - pp));
        pow_max = fmax(pow_max, pa);
        double ef = 0.0;
        for (int c = 0; c < 3; c++) ef += (qf[pq + c] - q[pq + c]) * (qf[pq + c] - q[pq + c]);

        fprintf(f, "%.6f,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g", ti->t[k], tau[0], tau[1], tau[2], q[pq], q[pq + 1],
                q[pq + 2]);
        for (int b = 1; b <= 9; b++) {
            const double *fo = ti->jnt_force + (size_t)k * nb + 3 * (size_t)b;
            const double *mo = ti->jnt_moment + (size_t)k * nb + 3 * (size_t)b;
            fprintf(f, ",%.15g,%.15g,%.15g,%.15g,%.15g,%.15g", fo[0], fo[1], fo[2], mo[0], mo[1], mo[2]);
            const double n = sqrt(fo[0] * fo[0] + fo[1] * fo[1] + fo[2] * fo[2]);
            if (b <= 3) mot_max = fmax(mot_max, n);
            else elb_max = fmax(elb_max, n);
        }
        for (int c = 0; c < 6; c++) {
            const double *fo = ti->cut_force + (size_t)k * nc + 3 * (size_t)c;
            fprintf(f, ",%.15g,%.15g,%.15g", fo[0], fo[1], fo[2]);
            ball_max = fmax(ball_max, sqrt(fo[0] * fo[0] + fo[1] * fo[1] + fo[2] * fo[2]));
        }
        fprintf(f, ",%.3e\n", sqrt(ef));
        for (int i = 0; i < 3; i++) tau_max = fmax(tau_max, fabs(tau[i]));
    }
    fclose(f);
    printf("vtdyn Delta robot: kinematic analysis over one turn of the path, %d rows -> %s\n", ti->nfilled, path);
    printf("driven on the path (point drives on the platform):\n");
    printf("  platform centre on the prescribed path:           max error %.3g m\n", path_err);
    printf("  forward check (drive forces applied, drives removed): platform deviation %.3g m (%ld IDA steps)\n", fwd,
           tr->steps_fwd);
    printf("driven at the motors by the path's inverse kinematics (one model):\n");
    printf("  platform centre on the prescribed path:           max error %.3g m\n", path_err_i);
    printf("  forward check (motor torques applied, drives removed): platform deviation %.3g m (%ld IDA steps)\n",
           fwd_i, ti->steps_fwd);
    printf("  q̈ against the path's run:                         max relative difference %.3g\n", qdd_err);
    printf("  motor power against the point drives' power:      max difference %.3g W (of %.4g W)\n", pow_err,
           pow_max);
    printf("largest motor torque:                                 %.4g N m\n", tau_max);
    printf("largest bearing force: motor %.4g N, elbow %.4g N, ball joint %.4g N\n", mot_max, elb_max, ball_max);
    double rc = 1.0;
    for (int k = 0; k < tr->nfilled; k++) rc = fmin(rc, tr->rcond[k]);
    printf("smallest condition estimate on the path:              %.3g\n", rc);
    vt_trajectory_free(ti);
    vt_trajectory_free(tr);
    vt_data_free(di);
    vt_data_free(d);
    vt_model_free(mi);
    vt_model_free(m);
    return (fwd <= 1e-6 && fwd_i <= 1e-6 && path_err <= 1e-9 && path_err_i <= 1e-9 && qdd_err <= 1e-9 &&
            pow_err <= 1e-9 * (1.0 + pow_max))
               ? 0
               : 1;
}
