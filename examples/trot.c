/* A quadruped trotting (docs/contact.md): diagonal pairs of feet alternate on the ground, the
 * torso's angular acceleration about the support line follows from the dynamics, and the ground's
 * forces and the motors' torques come from vt_inverse_dynamics_contacts.
 *
 * The robot is vt_scene_quadruped (17.2 kg). A period T = 2 (D + S): D s on four feet, S s on the
 * pair FL + HR (FR and HL swinging), D s on four feet, S s on FR + HL. A swing foot moves one
 * stride V T forward along a quintic (at rest at lift-off and touchdown) and lifts LIFT (sin²); a
 * stance foot stays where it landed (μ 0.8, a 4-face pyramid), under its hip at mid-stance. Each
 * leg's angles follow from its foot by the inverse kinematics of walk.c (vt_scene_leg_ik), here
 * from the foot's place in the torso's axes, which turn: with r = p_foot − o (o the torso's centre),
 *     r_b = Rᵀ r,  ṙ_b = Rᵀ (ṙ − ω × r),  r̈_b = Rᵀ (r̈ − α × r − 2 ω × ṙ + ω × (ω × r)),
 * so the legs' q̈ is affine in the torso's angular acceleration α.
 *
 * What is given: every foot's path; the torso's centre o = (V t, y(t), H), steady forward at the
 * stand's height, y a sideways sway (below) that keeps the robot's weight from turning it about the
 * support line; and two of the three components of the torso's angular acceleration α, those across
 * the current support line, as α_g = −KP θ − KD ω (θ the torso's rotation vector from level, ω its
 * angular velocity): a correction, part of the motion given, that pulls the torso back to level.
 * On four feet all of α is α_g.
 *
 * What follows: on two feet at p1, p2 their forces make no moment about the line u = (p2 − p1)/|·|,
 * so the root's efforts τ_root = (F, M_o) (the force and the moment about o the ground would have
 * to give) must satisfy u · (M_o + (o − p1) × F) = 0: one of the root's six equations is a
 * condition on the motion. With α = α_g − (α_g·u) u + s u that moment is affine in s (the instant
 * of vt_inverse_dynamics_motion is linear in q̈, q̈ affine in s): two instants, s = 0 and s = 1,
 * give the s that makes it zero, and vt_inverse_dynamics_contacts solves that instant with the two
 * stance feet active. The torso's orientation and ω are integrated from these α by RK4 (step H_STEP;
 * each step within one piece of the gait, its formulas extended to the step's ends; halving the step
 * changes the roll by 5e-9 deg). Whether an instant can be carried does not depend on the
 * integration's accuracy, since s is solved at each instant's own state; the motion (the roll
 * reached) does.
 *
 * The roll: the torso's centre crosses each support line at mid-stance (behind it before, ahead
 * after), and the pair swinging forward carries momentum about the line that the stance pair cannot
 * balance; both turn the torso about u. The sway removes the first for a point mass at the robot's
 * centre of mass (largest roll 7.8 deg without it, 5.5 with); what is left comes from the legs and
 * scales with the stride (0.23 deg at 0.01 m/s). Without the correction (KP = KD = 0) what one
 * pair's stance leaves of the turn carries into the next and the roll grows period by period
 * (6.0 deg after 2 periods, 13.2 after 8, 16.2 after 16, and the legs' inverse kinematics fail at
 * 4.2 s); with it the roll and pitch stay bounded (the same largest values over 4, 8 or 16 periods),
 * and the program prints them.
 *
 *   build/examples/trot [out.csv]        (default trot.csv)
 *
 * Writes one row per 10 ms over PERIODS periods: t, each foot's force (N, world axes), each joint's
 * torque (N·m), the torso's roll and pitch (deg) and s (rad/s²); prints the largest root effort
 * (round-off), the lowest normal force of a foot on the ground, the friction used, the peak torques
 * and the largest roll and pitch. Checks at every row: the root's efforts vanish (1e-9 of the
 * weight), a swing foot carries exactly nothing, the stance feet push inside their pyramids, and,
 * independently of the contacts' code, τ⁰ − Σ J_cᵀ f (τ⁰ the instant without the feet) is every
 * joint's effort with J_c by central differences of vt_frame_pose, and zero on the root with
 * J_cᵀ f = (f, (p_c − o) × f) there (1e-8 of the weight). Exits 1 on VT_ERR_CONTACT or a failed
 * check. Plot with examples/trot.gp. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vtdyn.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define D 0.05         /* s, four feet on the ground */
#define S 0.2          /* s, one diagonal pair on the ground, the other swinging */
#define T (2 * (D + S))
#define V 0.25         /* m/s */
#define STRIDE (V * T) /* m */
#define THETA0 0.6     /* the stand's hip flexion */
#define L 0.2          /* m, thigh and shank */
#define H (2 * L * cos(THETA0)) /* m, the hips' height */
#define LIFT 0.04      /* m */
#define MU 0.8
#define OMEGA0 sqrt(9.81 / HC) /* 1/s, the sway's pendulum */
#define HC 0.282       /* m, its height: the standing robot's centre of mass */
#define KP 100.0       /* 1/s², the correction's pull to level */
#define KD 20.0        /* 1/s, its damping */
#define H_STEP 0.001   /* s, RK4's step */
#define PERIODS 4
#define ROW 10         /* steps a row */
#define PIECE 1e-9     /* s, the time in a piece of the gait that decides which piece an instant is in */

static const double hip[4][3] = {{0.3, 0.15, 0}, {0.3, -0.15, 0}, {-0.3, 0.15, 0}, {-0.3, -0.15, 0}}; /* FL FR HL HR */
/* the lift-off in a period: FR, HL (pair B) after the first four-feet time; FL, HR (pair A) after the second */
static const double lift_of[4] = {2 * D + S, D, D, 2 * D + S};

/* the torso's sideways sway y(t) (with ẏ, ÿ): on pair A (FL + HR, its line of slope K = 0.15 / 0.3
 * through the torso's place at mid-stance) y = K V τ − K V sinh(ω₀ τ) / (ω₀ cosh(ω₀ S / 2)), τ the
 * time from mid-stance; on pair B its mirror, −y; on four feet still at the last stance's end. Its
 * distance from the line, d = (K V τ − y) / √(1 + K²) = K V sinh(ω₀ τ) / (ω₀ cosh(ω₀ S/2) √(1 + K²)),
 * obeys d̈ = ω₀² d: a point mass at height g / ω₀² on the line would need no moment about it (the
 * linear inverted pendulum), and the sideways speed is zero where the pairs change */
static void sway(double t, double tp, double *y, double *yd, double *ydd)
{
    tp += PIECE; /* an instant where the pieces meet belongs to the one it starts */
    const double K = 0.5, c = cosh(OMEGA0 * 0.5 * S), n = floor(tp / T), tau = tp - n * T, x0 = t - n * T;
    const int still = tau < D || (tau >= D + S && tau < 2 * D + S);
    const double sg = tau >= D && tau < 2 * D + S ? 1.0 : -1.0; /* pair A (and the four feet after it), or B */
    const double x = still ? 0.5 * S : tau < D + S ? x0 - (D + 0.5 * S) : x0 - (2 * D + 1.5 * S);
    *y = sg * K * V * (x - sinh(OMEGA0 * x) / (OMEGA0 * c));
    *yd = still ? 0.0 : sg * K * V * (1.0 - cosh(OMEGA0 * x) / c);
    *ydd = still ? 0.0 : -sg * K * V * OMEGA0 * sinh(OMEGA0 * x) / c;
}

/* s(u) = 10u³ − 15u⁴ + 6u⁵ and its derivatives: 0 to 1 with zero rate and acceleration at both ends */
/* foot k's place (world), velocity and acceleration at t; *air: 1 while it swings (from its lift-off,
 * inclusive, to its touchdown). Whether it swings, and which swing, is that of the time tp: a step of the
 * integration keeps its pieces (tp its middle), the motion's formulas extended to its ends */
static void foot(int k, double t, double tp, double p[3], double v[3], double a[3], int *air)
{
    tp += PIECE; /* an instant where the pieces meet belongs to the one it starts */
    const double lift = lift_of[k], base = hip[k][0] + STRIDE * ((lift + 0.5 * S) / T - 0.5);
    const double n = floor((tp - lift) / T), tau = t - lift - n * T; /* since its last lift-off */
    *air = tp - lift - n * T < S;
    p[1] = hip[k][1];
    vt_scene_foot_step(base, n, tau, S, STRIDE, LIFT, *air, p, v, a);
}

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* R of Euler parameters e = (e0, e1, e2, e3), row-major */
static void rotation(const double e[4], double R[9])
{
    const double w = e[0], x = e[1], y = e[2], z = e[3];
    R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

/* the instant at t: the torso at o(t) with orientation e and angular velocity w (world), angular
 * acceleration al; the legs by inverse kinematics; active[k] = the foot on the ground */
static void instant(const vt_model *m, vt_data *d, double t, double tp, const double e[4], const double w[3], const double al[3],
                    int active[4])
{
    double y, yd, ydd;
    sway(t, tp, &y, &yd, &ydd);
    const double o[3] = {V * t, y, H}, ov[3] = {V, yd, 0.0}, oa[3] = {0.0, ydd, 0.0};
    double R[9];
    rotation(e, R);
    memset(d->q, 0, (size_t)m->nq * sizeof(double));
    memcpy(d->q, o, sizeof o);
    memcpy(d->q + 3, e, 4 * sizeof(double));
    for (int i = 0; i < 3; i++) {
        d->qd[i] = ov[i], d->qdd[i] = oa[i];
        d->qd[3 + i] = w[i], d->qdd[3 + i] = al[i];
    }
    for (int k = 0; k < 4; k++) {
        double fp[3], fv[3], fa[3], r[3], rv[3], c1[3], c2[3], c3[3], c4[3], g[3], ga[3], x[3], xv[3], xa[3];
        int air;
        foot(k, t, tp, fp, fv, fa, &air);
        active[k] = !air;
        for (int i = 0; i < 3; i++) r[i] = fp[i] - o[i], rv[i] = fv[i] - ov[i], fa[i] -= oa[i];
        cross(w, r, c1);
        cross(al, r, c2);
        cross(w, rv, c3);
        cross(w, c1, c4);
        for (int i = 0; i < 3; i++) g[i] = rv[i] - c1[i], ga[i] = fa[i] - c2[i] - 2 * c3[i] + c4[i];
        for (int i = 0; i < 3; i++) { /* Rᵀ, less the hip's place */
            x[i] = R[i] * r[0] + R[3 + i] * r[1] + R[6 + i] * r[2] - hip[k][i];
            xv[i] = R[i] * g[0] + R[3 + i] * g[1] + R[6 + i] * g[2];
            xa[i] = R[i] * ga[0] + R[3 + i] * ga[1] + R[6 + i] * ga[2];
        }
        double q[3], qd[3], qdd[3];
        vt_scene_leg_ik(L, x, xv, xa, k < 2 ? -1.0 : 1.0, q, qd, qdd);
        for (int j = 0; j < 3; j++) {
            const int body = 2 + 3 * k + j, a = m->body_vadr[body];
            d->q[m->body_qadr[body]] = q[j];
            d->qd[a] = qd[j];
            d->qdd[a] = qdd[j];
        }
    }
}

/* the root's moment about the support line through p1 along u: u · (M_o + (o − p1) × F) */
static double line_moment(const vt_data *d, const double u[3], const double p1[3])
{
    double r[3], c[3];
    for (int i = 0; i < 3; i++) r[i] = d->q[i] - p1[i];
    cross(r, d->qfrc_drive, c);
    return u[0] * (d->qfrc_drive[3] + c[0]) + u[1] * (d->qfrc_drive[4] + c[1]) + u[2] * (d->qfrc_drive[5] + c[2]);
}

/* the torso's angular acceleration at t (the pair on the ground taken at time tp): the given α_g,
 * and on two feet its component along their line solved; d holds that instant on return, s the
 * component (0 on four feet) */
static vt_status accel(const vt_model *m, vt_data *d, double t, double tp, const double e[4], const double w[3],
                       double al[3], int active[4], double *s)
{
    /* θ: the rotation vector of e (e0 ≥ 0 taken: the short way) */
    const double sg = e[0] < 0 ? -1.0 : 1.0, vn = sqrt(e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
    const double f = vn > 1e-300 ? 2.0 * atan2(vn, sg * e[0]) / vn * sg : 2.0;
    for (int i = 0; i < 3; i++) al[i] = -KP * f * e[1 + i] - KD * w[i];
    int on[4], n = 0, pair[2] = {0, 0};
    for (int k = 0; k < 4; k++) {
        double p[3], v[3], a[3];
        int air;
        foot(k, tp, tp, p, v, a, &air);
        if (!air && n < 2) pair[n] = k;
        n += !air;
    }
    *s = 0.0;
    if (n == 2) {
        double p1[3], p2[3], v[3], a[3], u[3];
        int air;
        foot(pair[0], t, tp, p1, v, a, &air);
        foot(pair[1], t, tp, p2, v, a, &air);
        const double len = sqrt((p2[0] - p1[0]) * (p2[0] - p1[0]) + (p2[1] - p1[1]) * (p2[1] - p1[1]) +
                                (p2[2] - p1[2]) * (p2[2] - p1[2]));
        for (int i = 0; i < 3; i++) u[i] = (p2[i] - p1[i]) / len;
        const double along = al[0] * u[0] + al[1] * u[1] + al[2] * u[2];
        double r[2];
        for (int j = 0; j < 2; j++) { /* s = 0, then s = 1 */
            double b[3];
            for (int i = 0; i < 3; i++) b[i] = al[i] + (j - along) * u[i];
            instant(m, d, t, tp, e, w, b, on);
            const vt_status st = vt_inverse_dynamics_motion(m, d);
            if (st) return st;
            r[j] = line_moment(d, u, p1);
        }
        *s = -r[0] / (r[1] - r[0]);
        for (int i = 0; i < 3; i++) al[i] += (*s - along) * u[i];
    }
    instant(m, d, t, tp, e, w, al, active ? active : on);
    return VT_OK;
}

/* ė = ½ (0, ω) ⊗ e (ω global) */
static void edot(const double e[4], const double w[3], double de[4])
{
    de[0] = -0.5 * (w[0] * e[1] + w[1] * e[2] + w[2] * e[3]);
    de[1] = 0.5 * (w[0] * e[0] + w[1] * e[3] - w[2] * e[2]);
    de[2] = 0.5 * (w[1] * e[0] + w[2] * e[1] - w[0] * e[3]);
    de[3] = 0.5 * (w[2] * e[0] + w[0] * e[2] - w[1] * e[1]);
}

/* one RK4 step of (e, ω) from t; the pair on the ground that of the step's middle */
static vt_status step(const vt_model *m, vt_data *d, double t, double e[4], double w[3])
{
    static const double c[4] = {0.0, 0.5, 0.5, 1.0}, b[4] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
    double ke[4][4], kw[4][3], es[4], ws[3], s;
    for (int j = 0; j < 4; j++) {
        for (int i = 0; i < 4; i++) es[i] = e[i] + (j ? c[j] * H_STEP * ke[j - 1][i] : 0.0);
        for (int i = 0; i < 3; i++) ws[i] = w[i] + (j ? c[j] * H_STEP * kw[j - 1][i] : 0.0);
        const vt_status st = accel(m, d, t + c[j] * H_STEP, t + 0.5 * H_STEP, es, ws, kw[j], NULL, &s);
        if (st) return st;
        edot(es, ws, ke[j]);
    }
    double n = 0.0;
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) e[i] += H_STEP * b[j] * ke[j][i];
        n += e[i] * e[i];
    }
    for (int i = 0; i < 4; i++) e[i] /= sqrt(n);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) w[i] += H_STEP * b[j] * kw[j][i];
    return VT_OK;
}

/* the largest difference between the efforts of d (an instant with contact forces f) and τ⁰ − Σ J_cᵀ f,
 * τ⁰ the instant alone in z and J_c by central differences of the feet's positions on each leg joint;
 * on the root's six rates (the point's velocity and ω, global) J_cᵀ f is (f, (p_c − o) × f), and
 * τ⁰ − Σ J_cᵀ f must vanish */
static double check_efforts(const vt_model *m, const vt_data *d, vt_data *z, const double f[12], const int fr[4])
{
    memcpy(z->q, d->q, (size_t)m->nq * sizeof(double));
    memcpy(z->qd, d->qd, (size_t)m->nv * sizeof(double));
    memcpy(z->qdd, d->qdd, (size_t)m->nv * sizeof(double));
    if (vt_inverse_dynamics_motion(m, z)) return INFINITY;
    double worst = 0.0, root[6];
    memcpy(root, z->qfrc_drive, sizeof root);
    for (int k = 0; k < 4; k++) {
        double p[3], R[9], r[3], c[3];
        if (vt_frame_pose(m, z, fr[k], p, R)) return INFINITY;
        for (int i = 0; i < 3; i++) r[i] = p[i] - z->q[i];
        cross(r, f + 3 * k, c);
        for (int i = 0; i < 3; i++) root[i] -= f[3 * k + i], root[3 + i] -= c[i];
    }
    for (int i = 0; i < 6; i++) worst = fmax(worst, fabs(root[i]));
    for (int a = 6; a < m->nv; a++) {
        const int qa = m->body_qadr[m->dof_body[a]];
        double tau = z->qfrc_drive[a];
        for (int k = 0; k < 4; k++) {
            double pp[3], pm[3], R[9];
            const double h = 1e-6, q0 = z->q[qa];
            z->q[qa] = q0 + h;
            if (vt_kinematics(m, z) || vt_frame_pose(m, z, fr[k], pp, R)) return INFINITY;
            z->q[qa] = q0 - h;
            if (vt_kinematics(m, z) || vt_frame_pose(m, z, fr[k], pm, R)) return INFINITY;
            z->q[qa] = q0;
            for (int i = 0; i < 3; i++) tau -= (pp[i] - pm[i]) / (2 * h) * f[3 * k + i];
        }
        worst = fmax(worst, fabs(d->qfrc_drive[a] - tau));
    }
    return worst;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "trot.csv";
    vt_model *m = NULL;
    vt_data *d = NULL, *z = NULL;
    if (vt_scene_quadruped(&m) || vt_data_create(&d, m) || vt_data_create(&z, m)) return 1;
    static const char *const name[4] = {"FL", "FR", "HL", "HR"};
    vt_contact_def def[4];
    char foot_name[4][16];
    int fr[4];
    for (int k = 0; k < 4; k++) {
        snprintf(foot_name[k], sizeof foot_name[k], "%s_foot", name[k]);
        def[k] = vt_default_contact_def();
        def[k].name = def[k].frame = foot_name[k];
        def[k].mu = MU;
        fr[k] = vt_find_frame(m, foot_name[k]);
    }
    vt_contacts *c = NULL;
    char msg[VT_MESSAGE_SIZE];
    if (vt_contacts_create(&c, m, def, 4, NULL, msg)) {
        fprintf(stderr, "trot: %s\n", msg);
        return 1;
    }
    FILE *out = fopen(path, "w");
    if (!out) {
        perror(path);
        return 1;
    }
    fprintf(out, "t_s");
    for (int k = 0; k < 4; k++) fprintf(out, ",%s_fx_N,%s_fy_N,%s_fz_N", name[k], name[k], name[k]);
    for (int k = 0; k < 4; k++) fprintf(out, ",%s_HAA_Nm,%s_HFE_Nm,%s_KFE_Nm", name[k], name[k], name[k]);
    fprintf(out, ",roll_deg,pitch_deg,s_rad_s2\n");
    const double weight = VT_QUADRUPED_MASS * 9.81;
    double root = 0.0, low = weight, use = 0.0, peak[3] = {0, 0, 0}, roll = 0.0, pitch = 0.0, swing = 0.0, eff = 0.0;
    double e[4] = {1.0, 0.0, 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0};
    const int nstep = (int)(PERIODS * T / H_STEP + 0.5);
    int rows = 0, status = 0;
    for (int i = 0; i <= nstep; i++) {
        const double t = i * H_STEP;
        if (i % ROW == 0) {
            double al[3], s, force[12];
            int active[4];
            vt_status st = accel(m, d, t, t, e, w, al, active, &s);
            for (int k = 0; k < 12; k++) force[k] = NAN;
            if (!st) st = vt_inverse_dynamics_contacts(m, d, c, active, force);
            if (st) {
                fprintf(stderr, "trot: t = %g s: %s\n", t, d->message);
                status = 1;
                break;
            }
            double R[9];
            rotation(e, R);
            const double rl = atan2(R[7], R[8]) * 180 / PI, pt = -asin(R[6]) * 180 / PI;
            fprintf(out, "%.4f", t);
            for (int k = 0; k < 12; k++) fprintf(out, ",%.9g", force[k]);
            for (int a = 6; a < m->nv; a++) fprintf(out, ",%.9g", d->qfrc_drive[a]);
            fprintf(out, ",%.6g,%.6g,%.6g\n", rl, pt, s);
            rows++;
            roll = fmax(roll, fabs(rl)), pitch = fmax(pitch, fabs(pt));
            for (int a = 0; a < 6; a++) root = fmax(root, fabs(d->qfrc_drive[a]));
            for (int k = 0; k < 4; k++) {
                const double *fk = force + 3 * k;
                if (!active[k]) {
                    swing = fmax(swing, fmax(fabs(fk[0]), fmax(fabs(fk[1]), fabs(fk[2]))));
                    if (fk[0] != 0.0 || fk[1] != 0.0 || fk[2] != 0.0) status = 1;
                    continue;
                }
                low = fmin(low, fk[2]);
                use = fmax(use, fmax(fabs(fk[0]), fabs(fk[1])) / (MU * cos(PI / 4) * fk[2]));
            }
            for (int a = 6; a < m->nv; a++) peak[(a - 6) % 3] = fmax(peak[(a - 6) % 3], fabs(d->qfrc_drive[a]));
            eff = fmax(eff, check_efforts(m, d, z, force, fr));
        }
        if (i < nstep && step(m, d, t, e, w)) {
            fprintf(stderr, "trot: t = %g s: %s\n", t, d->message);
            status = 1;
            break;
        }
    }
    fclose(out);
    printf("trot: %d instants over %.2f s (%d periods of %.2f s, a stride of %.2f m at %.2f m/s) written to %s\n", rows,
           PERIODS * T, PERIODS, T, STRIDE, V, path);
    printf("largest root effort %.3g (round-off: the feet carry the torso's %.1f N); swing feet's forces %g\n", root,
           weight, swing);
    printf("efforts against tau0 - sum J_c^T f (J_c by central differences; the root's in closed form): %.2g\n", eff);
    printf("lowest normal force of a foot on the ground %.2f N; friction used at most %.0f %%\n", low, 100.0 * use);
    printf("peak torques: abduction %.2f, hip %.2f, knee %.2f N m\n", peak[0], peak[1], peak[2]);
    printf("largest torso roll %.2f deg, pitch %.2f deg\n", roll, pitch);
    vt_contacts_free(c);
    vt_data_free(z);
    vt_data_free(d);
    vt_model_free(m);
    return status || root > 1e-9 * weight || low < 0.0 || use > 1.0 + 1e-12 || eff > 1e-8 * weight;
}
