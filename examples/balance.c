/* A humanoid shifting its weight and standing on one foot (docs/contact.md): the ground's forces
 * under each foot's four corners and the legs' torques, instant by instant, by
 * vt_inverse_dynamics_contacts.
 *
 * The robot is vt_scene_humanoid (33.4 kg, flat feet with a contact at each sole corner, μ 0.7).
 * Double support: both feet flat under the hips, the trunk level at its stand height; over the
 * first second the trunk moves Y sideways over the left foot (a quintic, at rest at both ends).
 * Single support: the right foot rises 3 cm (1.2–1.6 s), stays up, and comes down (2.4–2.8 s),
 * its four corners inactive while it is off the ground. Then the trunk moves back (3–4 s). Each
 * leg's hip roll, hip pitch and knee follow from its ankle by vt_scene_leg_ik (the knee in front),
 * and the ankle's pitch and roll keep the foot flat: −(hip pitch + knee) and −hip roll, with
 * their rates and accelerations.
 *
 *   build/examples/balance [out.csv]        (default balance.csv)
 *
 * Writes one row per 10 ms: t, each foot's total normal force and centre of pressure (x, y,
 * world), each joint's torque; prints the largest root effort (round-off), the lowest corner
 * force on the ground, the centre of pressure's margin inside the left sole in single support,
 * and the peak torques; exits 1 if a corner had to pull or slip. Plot with examples/balance.gp. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vtdyn.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define Y 0.12        /* m, the trunk's shift over the left foot */
#define LIFT 0.03     /* m */
#define HIP_Z 0.78    /* m, the hips' height */
#define MU 0.7
#define LEG 0.4       /* m, thigh and shank */

/* s(u) = 10u³ − 15u⁴ + 6u⁵ from a to b over [t0, t1], and its derivatives */
static void ramp(double t, double t0, double t1, double a, double b, double *p, double *v, double *acc)
{
    const double T = t1 - t0, u = t < t0 ? 0.0 : t > t1 ? 1.0 : (t - t0) / T;
    const int moving = t > t0 && t < t1;
    *p = a + (b - a) * u * u * u * (10 - 15 * u + 6 * u * u);
    *v = moving ? (b - a) * 30 * u * u * (1 - u) * (1 - u) / T : 0.0;
    *acc = moving ? (b - a) * 60 * u * (1 - u) * (1 - 2 * u) / (T * T) : 0.0;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "balance.csv";
    vt_model *m = NULL;
    vt_data *d = NULL;
    if (vt_scene_humanoid(&m) || vt_data_create(&d, m)) return 1;
    static const char *const side[2] = {"L", "R"}, *const corner[4] = {"toe_in", "toe_out", "heel_in", "heel_out"};
    static const char *const joint[5] = {"hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll"};
    vt_contact_def def[8];
    char name[8][24];
    for (int k = 0; k < 8; k++) {
        snprintf(name[k], sizeof name[k], "%s_%s", side[k / 4], corner[k % 4]);
        def[k] = vt_default_contact_def();
        def[k].name = def[k].frame = name[k];
        def[k].mu = MU;
    }
    vt_contacts *c = NULL;
    char msg[VT_MESSAGE_SIZE];
    if (vt_contacts_create(&c, m, def, 8, NULL, msg)) {
        fprintf(stderr, "balance: %s\n", msg);
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "t_s,L_fz_N,L_cop_x_m,L_cop_y_m,R_fz_N,R_cop_x_m,R_cop_y_m");
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 5; j++) fprintf(f, ",%s_%s_Nm", side[k], joint[j]);
    fputc('\n', f);
    const double weight = VT_HUMANOID_MASS * 9.81;
    double root = 0.0, low = weight, margin = 1.0, use = 0.0, peak[5] = {0, 0, 0, 0, 0};
    for (int s = 0; s <= 400; s++) {
        const double t = 0.01 * s;
        double ty, tv, ta, rz, rv, ra;
        if (t < 2.0) ramp(t, 0.0, 1.0, 0.0, Y, &ty, &tv, &ta);
        else ramp(t, 3.0, 4.0, Y, 0.0, &ty, &tv, &ta);
        if (t < 2.0) ramp(t, 1.2, 1.6, 0.0, LIFT, &rz, &rv, &ra);
        else ramp(t, 2.4, 2.8, LIFT, 0.0, &rz, &rv, &ra);
        memset(d->q, 0, (size_t)m->nq * sizeof(double));
        memset(d->qd, 0, (size_t)m->nv * sizeof(double));
        memset(d->qdd, 0, (size_t)m->nv * sizeof(double));
        d->q[1] = ty, d->q[2] = HIP_Z + 0.2, d->q[3] = 1.0; /* the trunk: level, its centre 0.2 m above the hips */
        d->qd[1] = tv, d->qdd[1] = ta;
        for (int k = 0; k < 2; k++) { /* the ankle from the hip: the ankle 0.05 m above the sole */
            const double hy = ty + (k == 0 ? 0.1 : -0.1), fy = k == 0 ? 0.1 : -0.1;
            const double r[3] = {0.0, fy - hy, 0.05 + (k == 1 ? rz : 0.0) - HIP_Z};
            const double rdot[3] = {0.0, -tv, k == 1 ? rv : 0.0}, racc[3] = {0.0, -ta, k == 1 ? ra : 0.0};
            double q[3], qd[3], qdd[3];
            vt_scene_leg_ik(LEG, r, rdot, racc, 1.0, q, qd, qdd);
            const double qa[5] = {q[0], q[1], q[2], -(q[1] + q[2]), -q[0]};
            const double va[5] = {qd[0], qd[1], qd[2], -(qd[1] + qd[2]), -qd[0]};
            const double aa[5] = {qdd[0], qdd[1], qdd[2], -(qdd[1] + qdd[2]), -qdd[0]};
            for (int j = 0; j < 5; j++) {
                const int body = 2 + 5 * k + j, a = m->body_vadr[body];
                d->q[m->body_qadr[body]] = qa[j];
                d->qd[a] = va[j];
                d->qdd[a] = aa[j];
            }
        }
        const int up = t > 1.2 && t < 2.8; /* the right foot off the ground */
        int active[8];
        for (int k = 0; k < 8; k++) active[k] = k < 4 || !up;
        double force[24];
        const vt_status st = vt_inverse_dynamics_contacts(m, d, c, active, force);
        if (st) {
            fprintf(stderr, "balance: t = %g s: %s\n", t, d->message);
            fclose(f);
            return 1;
        }
        fprintf(f, "%.2f", t);
        for (int k = 0; k < 2; k++) { /* each foot's normal force and centre of pressure */
            double fz = 0.0, mx = 0.0, my = 0.0;
            for (int h = 4 * k; h < 4 * k + 4; h++) {
                double p[3];
                vt_frame_pose(m, d, vt_find_frame(m, name[h]), p, NULL);
                fz += force[3 * h + 2];
                mx += p[0] * force[3 * h + 2];
                my += p[1] * force[3 * h + 2];
                if (active[h]) { /* a corner the rule leaves unloaded carries 0 to round-off, sideways too */
                    const double ft = fmax(fabs(force[3 * h]), fabs(force[3 * h + 1]));
                    low = fmin(low, force[3 * h + 2]);
                    use = fmax(use, ft <= 1e-9 * weight ? 0.0 : ft / (MU * cos(PI / 4) * force[3 * h + 2]));
                }
            }
            const double cx = fz > 0 ? mx / fz : 0.0, cy = fz > 0 ? my / fz : 0.0;
            fprintf(f, ",%.9g,%.9g,%.9g", fz, cx, cy);
            if (k == 0 && up) margin = fmin(margin, fmin(0.1 - fabs(cx), 0.05 - fabs(cy - 0.1)));
        }
        for (int a = 6; a < m->nv; a++) fprintf(f, ",%.9g", d->qfrc_drive[a]);
        fputc('\n', f);
        for (int a = 0; a < 6; a++) root = fmax(root, fabs(d->qfrc_drive[a]));
        for (int a = 6; a < m->nv; a++) peak[(a - 6) % 5] = fmax(peak[(a - 6) % 5], fabs(d->qfrc_drive[a]));
    }
    fclose(f);
    printf("balance: 401 instants over 4 s written to %s\n", path);
    printf("largest root effort %.3g (round-off: the feet carry the robot's %.1f N)\n", root, weight);
    printf("lowest corner force on the ground %.3g N; friction used at most %.0f %%\n", low, 100.0 * use);
    printf("on one foot, the centre of pressure at least %.1f mm inside the left sole's edges\n", 1e3 * margin);
    printf("peak torques: hip roll %.1f, hip pitch %.1f, knee %.1f, ankle pitch %.1f, ankle roll %.1f N m\n", peak[0],
           peak[1], peak[2], peak[3], peak[4]);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(m);
    return root > 1e-9 * weight || low < -1e-9 * weight || use > 1.0 + 1e-9;
}
