/* A legged robot's knee four-bar (vt_scene_knee() in scenes.h): the knee motor sits at the hip
 * and turns the knee through a crank, a coupler along the thigh and a lever on the shank, the
 * closed chain Pinocchio cannot express (pinocchio #2729): a planar loop of revolute joints
 * closed by a revolute joint, which a set of 3D/6D point and frame constraints cannot state.
 * The hip swings the thigh by 0.35 rad and the motor turns the crank by 0.4 rad, 2 Hz (a trot):
 * hip and motor joint drives, every joint of the loop a revolute, the loop closed by a planar
 * revolute cut joint at the lever (vt_cut_joint_def.planar = 1: its 2 in-plane rows, so the
 * rows are independent: no redundant option). Fully driven: a kinematic analysis; the two drive
 * efforts are the hip and motor torques.
 *
 * Checks printed: the knee angle from the Newton solve against the loop's closed-form closure;
 * the forward check (drives removed, the torques applied, the same start: IDA must follow the
 * same motion); the power balance τ_hip q̇1 + τ_motor q̇2 = d(T + V)/dt at every row, T and V
 * from the bodies' velocities and accelerations.
 *
 * Writes CSV (default knee.csv; first argument to change it), t ∈ [0, 1] s, 201 rows:
 *   t_s, hip_rad, motor_rad, knee_rad, tau_hip_Nm, tau_motor_Nm, hip_fx_N, hip_fy_N (ground on
 *   thigh), motor_fx_N, motor_fy_N (thigh on crank at the hip), knee_fx_N, knee_fy_N (thigh on
 *   shank), crank_fx_N, crank_fy_N (crank on coupler at their revolute), lever_fx_N, lever_fy_N
 *   (shank on coupler at the planar revolute cut), foot_x_m, foot_y_m, knee_err_rad, fwd_dev_rad,
 *   power_W, power_err_W; all forces global, z components zero (a planar motion)
 * Plot with examples/knee.gp.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

#define PI 3.14159265358979323846

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "knee.csv";
    const double om = 4.0 * PI;
    vt_model *m = NULL;
    vt_data *d = NULL, *dt = NULL;
    vt_trajectory *tr = NULL;
    vt_run_options opt = vt_default_run_options();
    opt.t1 = 1.0;
    opt.nout = 200;
    opt.rtol = 1e-11;
    opt.atol = 1e-13;
    vt_status st = vt_scene_knee(&m, vt_function_sine(-0.25 * PI, 0.35, om, 0.0), vt_function_sine(0.5 * PI, 0.4, om, 0.8), 1);
    if (!st) st = vt_data_create(&d, m);
    if (!st) st = vt_data_create(&dt, m);
    if (!st) st = vt_trajectory_create(&tr, m, opt.nout + 1);
    if (!st) {
        if (vt_scene_knee_assemble(m, d, -0.25 * PI, 0.35 * om, 0.5 * PI + 0.4 * sin(0.8), 0.4 * om * cos(0.8), NULL)) {
            fprintf(stderr, "knee: the loop does not close at t = 0\n");
            return 1;
        }
        st = vt_kinematic_analysis(m, d, &opt, tr);
    }
    if (st) {
        fprintf(stderr, "knee: %s%s%s\n", vt_status_string(st), d ? ": " : "", d ? d->message : "");
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "t_s,hip_rad,motor_rad,knee_rad,tau_hip_Nm,tau_motor_Nm,hip_fx_N,hip_fy_N,motor_fx_N,motor_fy_N,"
               "knee_fx_N,knee_fy_N,crank_fx_N,crank_fy_N,lever_fx_N,lever_fy_N,foot_x_m,foot_y_m,knee_err_rad,"
               "fwd_dev_rad,power_W,power_err_W\n");
    const int nq = m->nq, nv = m->nv, nb = m->nbody + 1, knee = m->body_qadr[4];
    double kerr = 0.0, fwd = 0.0, pmax = 0.0, perr = 0.0, tmax[2] = {0, 0}, fmax_ = 0.0;
    for (int k = 0; k < tr->nfilled; k++) {
        const double t = tr->t[k], *q = tr->q + nq * k, *qf = tr->q_fwd + nq * k, *tau = tr->drive_effort + 2 * k;
        /* the knee angle of the closed-form closure at the row's hip and motor angles */
        double kn[2];
        if (vt_scene_knee_assemble(m, dt, q[0], 0.0, q[1], 0.0, kn)) {
            fprintf(stderr, "knee: the loop does not close at t = %g\n", t);
            return 1;
        }
        const double ke = fabs(remainder(q[knee] - kn[0], 2.0 * PI));
        double fe = 0.0;
        for (int c = 0; c < nq; c++) fe = fmax(fe, fabs(qf[c] - q[c]));
        kerr = fmax(kerr, ke);
        fwd = fmax(fwd, fe);
        dt->time = t;
        for (int c = 0; c < nq; c++) dt->q[c] = q[c];
        for (int c = 0; c < nv; c++) dt->qd[c] = tr->qd[nv * k + c];
        if ((st = vt_inverse_dynamics(m, dt)) != VT_OK) {
            fprintf(stderr, "knee: %s: %s\n", vt_status_string(st), dt->message);
            return 1;
        }
        const double P = tau[0] * dt->qd[0] + tau[1] * dt->qd[1], dE = vt_scene_energy_rate(m, dt);
        pmax = fmax(pmax, fabs(P));
        perr = fmax(perr, fabs(P - dE));
        for (int j = 0; j < 2; j++) tmax[j] = fmax(tmax[j], fabs(tau[j]));
        const double *F = tr->jnt_force + 3 * nb * k, *L = tr->cut_force + 3 * m->ncut * k;
        /* the foot: the shank's far end, VT_KN_L − its centre's distance from the knee along its x */
        const double *r4 = dt->x + 7 * 3, *A4 = dt->A + 9 * 4, s = VT_KN_L - (0.5 * (VT_KN_C + VT_KN_L) - VT_KN_C);
        fprintf(f, "%.6f,%.15g,%.15g,%.15g,%.15g,%.15g", t, q[0], q[1], q[knee], tau[0], tau[1]);
        for (int b = 1; b <= 4; b++) {
            const int body = b == 3 ? 4 : b == 4 ? 3 : b; /* hip, motor, knee, crank-coupler */
            fprintf(f, ",%.15g,%.15g", F[3 * body], F[3 * body + 1]);
            fmax_ = fmax(fmax_, hypot(F[3 * body], F[3 * body + 1]));
        }
        fprintf(f, ",%.15g,%.15g,%.15g,%.15g,%.3e,%.3e,%.15g,%.3e\n", L[0], L[1], r4[0] + s * A4[0], r4[1] + s * A4[1],
                ke, fe, P, P - dE);
        fmax_ = fmax(fmax_, hypot(L[0], L[1]));
    }
    fclose(f);
    printf("vtdyn knee four-bar: kinematic analysis over two strides, %d rows -> %s\n", tr->nfilled, path);
    printf("largest torques: hip %.4g N m, knee motor %.4g N m; largest bearing force %.4g N\n", tmax[0], tmax[1], fmax_);
    printf("knee angle against the loop's closed form:      max error %.3g rad\n", kerr);
    printf("forward check (torques applied, drives removed): max |q_fwd - q| %.3g rad (%ld IDA steps)\n", fwd,
           tr->steps_fwd);
    printf("power balance: max |sum tau q' - d(T+V)/dt| %.3g W = %.3g of the largest power %.4g W\n", perr, perr / pmax,
           pmax);
    const int ok = kerr <= 1e-10 && tr->fwd_err_q <= 1e-6 && perr <= 1e-9 * pmax;
    vt_trajectory_free(tr);
    vt_data_free(dt);
    vt_data_free(d);
    vt_model_free(m);
    return ok ? 0 : 1;
}
