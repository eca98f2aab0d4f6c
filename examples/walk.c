/* A quadruped walking (docs/contact.md): the ground's forces on its feet and its motors' torques,
 * instant by instant, by vt_inverse_dynamics_contacts.
 *
 * The robot is vt_scene_quadruped (17.2 kg). It walks a crawl: one foot in the air at a time, in
 * the order FL, HR, FR, HL, each slot SHIFT s on four feet while the torso sways toward the
 * middle of the next three feet (SWAY of the way to their centroid), then SWING s with that
 * foot in the air; the torso moves forward
 * at V, level, at the stand's height. A stance foot stays where it landed (μ 0.8, a 4-face
 * pyramid); a swing foot moves one stride S = V T forward along a quintic (at rest at lift-off and
 * touchdown) and lifts LIFT (sin²). Each leg's angles follow from its foot by inverse kinematics:
 * the abduction φ = atan2(d_y, −d_z) turns the leg's plane onto the foot, whose distance in it
 * ρ = √(d_y² + d_z²) the two flexion angles reach as a planar two-link arm (the knee forward on the
 * front legs, backward on the hind); their rates and accelerations are the exact derivatives,
 * q̇ = J⁻¹ ṗ, q̈ = J⁻¹ (p̈ − J̇ q̇) in the leg's plane, with φ̇, φ̈, ρ̇, ρ̈ by the chain rule.
 *
 *   build/examples/walk [out.csv]        (default walk.csv)
 *
 * Writes one row per 10 ms over one period (T = 4 (SHIFT + SWING)): t, each foot's force (N, world
 * axes), each joint's torque (N·m); prints the largest root effort (round-off: the feet carry the
 * torso), the lowest normal force of a foot on the ground, the friction used and the peak torques;
 * exits 1 if the feet had to pull or slip. Plot with examples/walk.gp. Here the torso's motion is
 * given whole, which three feet or more allow; on two (a trot's diagonal pair) the ground's forces
 * pass through the line between them, so the torso's turn about it follows from the dynamics:
 * examples/trot.c solves it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vtdyn.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define SHIFT 0.6      /* s, four feet on the ground, the torso swaying */
#define SWING 0.6      /* s, one foot in the air */
#define T (4 * (SHIFT + SWING))
#define V 0.04         /* m/s */
#define S (V * T)      /* m, a foot's stride */
#define THETA0 0.6     /* the stand's hip flexion */
#define L 0.2          /* m, thigh and shank */
#define H (2 * L * cos(THETA0)) /* m, the hips' height */
#define LIFT 0.04      /* m */
#define MU 0.8
#define SWAY 0.6       /* of the way to the support triangle's centroid */

static const double hip[4][2] = {{0.3, 0.15}, {0.3, -0.15}, {-0.3, 0.15}, {-0.3, -0.15}}; /* FL FR HL HR */
static const int slot_of[4] = {0, 2, 3, 1}; /* FL first, then HR, FR, HL */

/* s(u) = 10u³ − 15u⁴ + 6u⁵ and its derivatives: 0 to 1 with zero rate and acceleration at both ends */
/* foot k's place (world), velocity and acceleration at t; *air: 1 while it swings */
static void foot(int k, double t, double p[3], double v[3], double a[3], int *air)
{
    const double slot = SHIFT + SWING, lift = slot_of[k] * slot + SHIFT; /* its lift-off in a period */
    const double base = hip[k][0] + S * ((lift + 0.5 * SWING) / T - 0.5); /* under its hip mid-swing */
    const double n = floor((t - lift) / T), tau = t - lift - n * T; /* since its last lift-off */
    *air = tau < SWING;
    p[1] = hip[k][1];
    vt_scene_foot_step(base, n, tau, SWING, S, LIFT, *air, p, v, a);
}

/* the torso's sway target while foot k swings (from the centre's forward march V t): SWAY of the
 * way to the centroid of the other three feet, where they stand at its lift-off */
static void sway_target(int k, double c[2])
{
    const double lift = slot_of[k] * (SHIFT + SWING) + SHIFT;
    c[0] = c[1] = 0.0;
    for (int j = 0; j < 4; j++) {
        if (j == k) continue;
        double p[3], v[3], a[3];
        int air;
        foot(j, lift, p, v, a, &air);
        c[0] += SWAY * (p[0] - V * lift) / 3.0;
        c[1] += SWAY * p[1] / 3.0;
    }
}

/* the torso's centre (x, y; z = H), its velocity and acceleration at t */
static void torso(double t, double p[2], double v[2], double a[2])
{
    const double slot = SHIFT + SWING, tau = fmod(t, T);
    const int j = (int)(tau / slot); /* this slot's swing leg sways the torso first */
    int k = 0, prev = 0;
    for (int i = 0; i < 4; i++) {
        if (slot_of[i] == j) k = i;
        if (slot_of[i] == (j + 3) % 4) prev = i;
    }
    double from[2], to[2], s, sd, sdd;
    sway_target(prev, from);
    sway_target(k, to);
    const double u = (tau - j * slot) / SHIFT;
    if (u < 1.0) vt_scene_quintic(u, &s, &sd, &sdd);
    else s = 1.0, sd = sdd = 0.0;
    for (int e = 0; e < 2; e++) {
        p[e] = from[e] + (to[e] - from[e]) * s;
        v[e] = (to[e] - from[e]) * sd / SHIFT;
        a[e] = (to[e] - from[e]) * sdd / (SHIFT * SHIFT);
    }
    p[0] += V * t;
    v[0] += V;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "walk.csv";
    vt_model *m = NULL;
    vt_data *d = NULL;
    if (vt_scene_quadruped(&m) || vt_data_create(&d, m)) return 1;
    static const char *const name[4] = {"FL", "FR", "HL", "HR"};
    vt_contact_def def[4];
    char foot_name[4][16];
    for (int k = 0; k < 4; k++) {
        snprintf(foot_name[k], sizeof foot_name[k], "%s_foot", name[k]);
        def[k] = vt_default_contact_def();
        def[k].name = def[k].frame = foot_name[k];
        def[k].mu = MU;
    }
    vt_contacts *c = NULL;
    char msg[VT_MESSAGE_SIZE];
    if (vt_contacts_create(&c, m, def, 4, NULL, msg)) {
        fprintf(stderr, "walk: %s\n", msg);
        return 1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "t_s");
    for (int k = 0; k < 4; k++) fprintf(f, ",%s_fx_N,%s_fy_N,%s_fz_N", name[k], name[k], name[k]);
    for (int k = 0; k < 4; k++) fprintf(f, ",%s_HAA_Nm,%s_HFE_Nm,%s_KFE_Nm", name[k], name[k], name[k]);
    fputc('\n', f);
    const double weight = VT_QUADRUPED_MASS * 9.81;
    double root = 0.0, low = weight, use = 0.0, peak[3] = {0, 0, 0};
    const int nstep = (int)(T / 0.01 + 0.5);
    for (int s = 0; s <= nstep; s++) {
        const double t = T * s / nstep;
        double tp[2], tv[2], ta[2];
        torso(t, tp, tv, ta);
        memset(d->q, 0, (size_t)m->nq * sizeof(double));
        d->q[0] = tp[0], d->q[1] = tp[1], d->q[2] = H, d->q[3] = 1.0; /* level */
        for (int e = 0; e < 6; e++) d->qd[e] = d->qdd[e] = 0.0;
        d->qd[0] = tv[0], d->qd[1] = tv[1], d->qdd[0] = ta[0], d->qdd[1] = ta[1];
        int active[4];
        for (int k = 0; k < 4; k++) {
            double fp[3], fv[3], fa[3], q[3], qd[3], qdd[3], r[3], rv[3], ra[3];
            int air;
            foot(k, t, fp, fv, fa, &air);
            active[k] = !air;
            /* the foot from its hip (the torso level: its offsets turn with nothing) */
            const double hp[3] = {tp[0] + hip[k][0], tp[1] + hip[k][1], H}, hv[3] = {tv[0], tv[1], 0}, ha[3] = {ta[0], ta[1], 0};
            for (int e = 0; e < 3; e++) r[e] = fp[e] - hp[e], rv[e] = fv[e] - hv[e], ra[e] = fa[e] - ha[e];
            vt_scene_leg_ik(L, r, rv, ra, k < 2 ? -1.0 : 1.0, q, qd, qdd);
            for (int j = 0; j < 3; j++) {
                const int body = 2 + 3 * k + j, a = m->body_vadr[body];
                d->q[m->body_qadr[body]] = q[j];
                d->qd[a] = qd[j];
                d->qdd[a] = qdd[j];
            }
        }
        double force[12];
        const vt_status st = vt_inverse_dynamics_contacts(m, d, c, active, force);
        if (st) {
            fprintf(stderr, "walk: t = %g s: %s\n", t, d->message);
            fclose(f);
            return 1;
        }
        fprintf(f, "%.4f", t);
        for (int k = 0; k < 12; k++) fprintf(f, ",%.9g", force[k]);
        for (int a = 6; a < m->nv; a++) fprintf(f, ",%.9g", d->qfrc_drive[a]);
        fputc('\n', f);
        for (int a = 0; a < 6; a++) root = fmax(root, fabs(d->qfrc_drive[a]));
        for (int k = 0; k < 4; k++) {
            const double *fk = force + 3 * k;
            if (!active[k]) continue;
            low = fmin(low, fk[2]);
            use = fmax(use, fmax(fabs(fk[0]), fabs(fk[1])) / (MU * cos(PI / 4) * fk[2]));
        }
        for (int a = 6; a < m->nv; a++) peak[(a - 6) % 3] = fmax(peak[(a - 6) % 3], fabs(d->qfrc_drive[a]));
    }
    fclose(f);
    printf("walk: %d instants over %.2f s (a stride of %.2f m) written to %s\n", nstep + 1, T, S, path);
    printf("largest root effort %.3g (round-off: the feet carry the torso's %.1f N)\n", root, weight);
    printf("lowest normal force of a foot on the ground %.2f N; friction used at most %.0f %%\n", low, 100.0 * use);
    printf("peak torques: abduction %.2f, hip %.2f, knee %.2f N m\n", peak[0], peak[1], peak[2]);
    vt_contacts_free(c);
    vt_data_free(d);
    vt_model_free(m);
    return root > 1e-9 * weight || low < 0.0 || use > 1.0 + 1e-12;
}
