/* A Stewart–Gough platform (6-UPS, vt_scene_stewart() in scenes.h) follows a pose trajectory:
 * its centre moves 0.08 / 0.06 / 0.05 m in x / y / z and it tilts 0.15 rad about a slanted
 * axis, period 2 s. The six prismatic actuators are driven by joint drives whose f(t) is the
 * closed-form inverse kinematics of that pose (leg lengths with their exact rates and
 * accelerations); the platform floats on a free joint and each leg closes on it by a spherical
 * cut joint. Fully driven: a kinematic analysis; the six drive efforts are the leg forces, the
 * universal joints' reactions and the cut joints' forces the bearing loads.
 *
 * Checks printed: the platform's pose against the prescribed one (the forward kinematics the
 * Newton solves, against the inverse kinematics the drives were made from); the forward check
 * (drives removed, the leg forces applied, the same start: IDA must follow the same motion);
 * the power balance Σ f_i L̇_i = d(T + V)/dt at every row, T and V from the bodies' velocities
 * and accelerations.
 *
 * Writes CSV (default stewart.csv; first argument to change it), t ∈ [0, 2] s, 201 rows:
 *   t_s, L1_m .. L6_m, f1_N .. f6_N, U1x_N U1y_N U1z_N .. U6z_N (ground on cylinder i at its
 *   universal joint, global), S1x_N .. S6z_N (platform on piston i at its spherical joint,
 *   global), pose_err_m, fwd_dev_m, power_W, power_err_W
 * Plot with examples/stewart.gp.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "stewart.csv";
    vt_stewart sg = {3.14159265358979323846, 0.0, {{0}}}; /* period 2 s */
    vt_model *m = NULL;
    vt_data *d = NULL, *dt = NULL;
    vt_trajectory *tr = NULL;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 2.0;
    opt.nout = 200;
    opt.rtol = 1e-12;
    opt.atol = 1e-14;
    vt_status st = vt_scene_stewart(&m, &sg);
    if (!st) st = vt_data_create(&d, m);
    if (!st) st = vt_data_create(&dt, m);
    if (!st) st = vt_trajectory_create(&tr, m, opt.nout + 1);
    if (!st) {
        vt_scene_stewart_assemble(m, d, &sg, 0.0);
        st = vt_kinematic_analysis(m, d, &opt, tr);
    }
    if (st) {
        fprintf(stderr, "stewart: %s%s%s\n", vt_status_string(st), d ? ": " : "", d ? d->message : "");
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "t_s");
    for (int i = 1; i <= 6; i++) fprintf(f, ",L%d_m", i);
    for (int i = 1; i <= 6; i++) fprintf(f, ",f%d_N", i);
    for (int i = 1; i <= 6; i++) fprintf(f, ",U%dx_N,U%dy_N,U%dz_N", i, i, i);
    for (int i = 1; i <= 6; i++) fprintf(f, ",S%dx_N,S%dy_N,S%dz_N", i, i, i);
    fprintf(f, ",pose_err_m,fwd_dev_m,power_W,power_err_W\n");
    double pose = 0.0, fwd = 0.0, pmax = 0.0, perr = 0.0, flo = INFINITY, fhi = -INFINITY, umax = 0.0, smax = 0.0;
    const int nq = m->nq, nv = m->nv, nb = m->nbody + 1;
    for (int k = 0; k < tr->nfilled; k++) {
        const double t = tr->t[k], *q = tr->q + nq * k, *qf = tr->q_fwd + nq * k;
        double r[9], p[4], w[6];
        vt_scene_stewart_pose(&sg, t, r, p, w);
        /* the free joint's q is the platform's pose: centre (m), Euler parameters */
        double pe = 0.0, fe = 0.0;
        for (int c = 0; c < 3; c++) {
            pe = fmax(pe, fabs(q[c] - r[c]));
            fe = fmax(fe, fabs(qf[c] - q[c]));
        }
        for (int c = 0; c < 4; c++) pe = fmax(pe, VT_SG_PLAT_R * fabs(q[3 + c] - p[c])); /* radians × radius */
        pose = fmax(pose, pe);
        fwd = fmax(fwd, fe);
        /* the instant again on a second data: the velocities and accelerations of every body */
        dt->time = t;
        for (int c = 0; c < nq; c++) dt->q[c] = q[c];
        for (int c = 0; c < nv; c++) dt->qd[c] = tr->qd[nv * k + c];
        if ((st = vt_inverse_dynamics(m, dt)) != VT_OK) {
            fprintf(stderr, "stewart: %s: %s\n", vt_status_string(st), dt->message);
            return 1;
        }
        const double *fl = tr->drive_effort + m->ndrive * k;
        double P = 0.0;
        for (int i = 0; i < 6; i++) P += fl[i] * dt->qd[m->body_vadr[3 + 2 * i]];
        const double dE = vt_scene_energy_rate(m, dt);
        pmax = fmax(pmax, fabs(P));
        perr = fmax(perr, fabs(P - dE));
        fprintf(f, "%.6f", t);
        for (int i = 0; i < 6; i++) fprintf(f, ",%.15g", q[m->body_qadr[3 + 2 * i]]);
        for (int i = 0; i < 6; i++) {
            fprintf(f, ",%.15g", fl[i]);
            flo = fmin(flo, fl[i]);
            fhi = fmax(fhi, fl[i]);
        }
        for (int i = 0; i < 6; i++) {
            const double *F = tr->jnt_force + 3 * nb * k + 3 * (2 + 2 * i);
            fprintf(f, ",%.15g,%.15g,%.15g", F[0], F[1], F[2]);
            umax = fmax(umax, sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]));
        }
        for (int i = 0; i < 6; i++) {
            const double *F = tr->cut_force + 3 * m->ncut * k + 3 * i;
            fprintf(f, ",%.15g,%.15g,%.15g", F[0], F[1], F[2]);
            smax = fmax(smax, sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]));
        }
        fprintf(f, ",%.3e,%.3e,%.15g,%.3e\n", pe, fe, P, P - dE);
    }
    fclose(f);
    printf("vtdyn Stewart-Gough platform: kinematic analysis over one period, %d rows -> %s\n", tr->nfilled, path);
    printf("leg forces:                                     %.4g .. %.4g N\n", flo, fhi);
    printf("largest bearing load: universal %.4g N, spherical %.4g N\n", umax, smax);
    printf("platform pose against the prescribed one:       max error %.3g m\n", pose);
    printf("forward check (leg forces applied, drives removed): centre deviation %.3g m, max |q_fwd - q| %.3g"
           " (%ld IDA steps)\n", fwd, tr->fwd_err_q, tr->steps_fwd);
    printf("power balance sum f_i L'_i = d(T+V)/dt:         max error %.3g W = %.3g of the largest power %.4g W\n",
           perr, perr / pmax, pmax);
    const int ok = pose <= 1e-9 && tr->fwd_err_q <= 1e-6 && perr <= 1e-9 * pmax;
    vt_trajectory_free(tr);
    vt_data_free(dt);
    vt_data_free(d);
    vt_model_free(m);
    return ok ? 0 : 1;
}
