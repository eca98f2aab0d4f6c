/* A URDF robot in flight: a free root (vt_urdf_options.floating), every joint driven, at 20
 * random states — the partly driven route (the root's six rates free). What the condition
 * estimate must not do (issue: it warned at every state of Talos with exact answers): warn or
 * fail from the robot's inertia spread alone. Checked, on vt_inverse_dynamics (dense) and
 * vt_inverse_dynamics_recursive:
 *   - VT_OK, no warning of the estimate (VT_WARN_LIMIT aside: random states pass the URDF's
 *     limits), the same rcond on both paths (1e-9 relative), and rcond > 1e-3;
 *   - the answer by a second method: the motion found (q̈) given to vt_inverse_dynamics_motion on
 *     the model without drives must need no effort on the root (its six, against the largest
 *     effort: 1e-10) and the joint drives' efforts on every joint rate (1e-10);
 *   - the dense and recursive efforts and reactions agree (1e-10 of the largest).
 *     robots_in_flight ROBOT.urdf                                            exit 0 when all hold */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vtdyn.h>

static double maxabs(const double *a, int n)
{
    double m = 0.0;
    for (int k = 0; k < n; k++) m = fmax(m, fabs(a[k]));
    return m;
}

int main(int argc, char **argv)
{
    if (argc != 2) return fprintf(stderr, "usage: robots_in_flight ROBOT.urdf\n"), 2;
    vt_urdf_options opt = vt_default_urdf_options();
    opt.mimic = 0;
    opt.floating = 1;
    char msg[256] = "";
    vt_builder *b;
    vt_model *bare, *m;
    if (vt_urdf_builder(&b, argv[1], &opt, msg)) return fprintf(stderr, "%s: %s\n", argv[1], msg), 1;
    if (vt_builder_build(&bare, b)) return fprintf(stderr, "%s: %s\n", argv[1], vt_builder_message(b)), 1;
    int root = 0;
    for (int i = 1; i <= bare->nbody; i++) {
        if (bare->body_joint[i] == VT_JOINT_FREE) {
            root = i;
            continue;
        }
        for (int k = 0; k < bare->body_nv[i]; k++) {
            vt_drive_def dr = vt_default_drive_def();
            dr.body = i;
            dr.index = k;
            dr.f = vt_function_sine(0.1 * i, 0.3, 1.0 + 0.1 * i, 0.2 * k);
            if (vt_builder_add_drive(b, &dr) < 0) return fprintf(stderr, "drive: %s\n", vt_builder_message(b)), 1;
        }
    }
    if (!root) return fprintf(stderr, "%s: no free root\n", argv[1]), 1;
    vt_model_free(bare);
    if (vt_builder_build(&m, b) || vt_model_without_drives(&bare, m))
        return fprintf(stderr, "%s: %s\n", argv[1], vt_builder_message(b)), 1;
    vt_builder_free(b);
    vt_data *d[2], *g;
    if (vt_data_create(&d[0], m) || vt_data_create(&d[1], m) || vt_data_create(&g, bare)) return fprintf(stderr, "no memory\n"), 1;
    srand(7);
    int bad = 0;
    double lo = 1.0, worst_root = 0.0, worst_tau = 0.0, worst_paths = 0.0;
    const int r6 = m->body_vadr[root];
    for (int s = 0; s < 20; s++) {
        for (int a = 0; a < m->nq; a++) d[0]->q[a] = 2.0 * rand() / RAND_MAX - 1.0;
        for (int a = 0; a < m->nv; a++) d[0]->qd[a] = 2.0 * rand() / RAND_MAX - 1.0;
        double *e = d[0]->q + m->body_qadr[root] + 3, n = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
        for (int k = 0; k < 4; k++) e[k] /= n;
        memcpy(d[1]->q, d[0]->q, sizeof(double) * (size_t)m->nq);
        memcpy(d[1]->qd, d[0]->qd, sizeof(double) * (size_t)m->nv);
        d[0]->time = d[1]->time = 0.05 * s;
        for (int p = 0; p < 2; p++) {
            const vt_status st = p ? vt_inverse_dynamics_recursive(m, d[p]) : vt_inverse_dynamics(m, d[p]);
            if (st || (d[p]->warning & ~VT_WARN_LIMIT)) {
                fprintf(stderr, "state %d, %s path: %s, warning %d, rcond %.3g (%s)\n", s, p ? "recursive" : "dense",
                        vt_status_string(st), d[p]->warning, d[p]->rcond, d[p]->message);
                bad = 1;
            }
            lo = fmin(lo, d[p]->rcond);
        }
        if (bad) break;
        if (!(fabs(d[1]->rcond - d[0]->rcond) <= 1e-9 * d[0]->rcond) || !(d[0]->rcond > 1e-3)) {
            fprintf(stderr, "state %d: rcond dense %.17g, recursive %.17g\n", s, d[0]->rcond, d[1]->rcond);
            bad = 1;
        }
        const double big = fmax(1.0, maxabs(d[0]->qfrc_drive, m->nv)), fbig = fmax(big, maxabs(d[0]->jnt_force, 3 * (m->nbody + 1)));
        for (int a = 0; a < m->nv; a++) worst_paths = fmax(worst_paths, fabs(d[1]->qfrc_drive[a] - d[0]->qfrc_drive[a]) / big);
        for (int k = 0; k < 3 * (m->nbody + 1); k++)
            worst_paths = fmax(worst_paths, fmax(fabs(d[1]->jnt_force[k] - d[0]->jnt_force[k]),
                                                 fabs(d[1]->jnt_moment[k] - d[0]->jnt_moment[k])) / fbig);
        memcpy(g->q, d[1]->q, sizeof(double) * (size_t)m->nq);
        memcpy(g->qd, d[1]->qd, sizeof(double) * (size_t)m->nv);
        memcpy(g->qdd, d[1]->qdd, sizeof(double) * (size_t)m->nv);
        if (vt_inverse_dynamics_motion(bare, g)) return fprintf(stderr, "motion: %s\n", g->message), 1;
        for (int a = 0; a < m->nv; a++) {
            const double diff = fabs(g->qfrc_drive[a] - d[1]->qfrc_drive[a]) / big;
            if (a >= r6 && a < r6 + 6) worst_root = fmax(worst_root, fabs(g->qfrc_drive[a]) / big);
            else worst_tau = fmax(worst_tau, diff);
        }
    }
    printf("%s in flight (%d rates, %d driven): 20 states, lowest rcond %.3g, no warning; root's efforts of the motion %.2g, "
           "joint efforts against the motion path %.2g, dense against recursive %.2g (of the largest)\n",
           argv[1], m->nv, m->nc, lo, worst_root, worst_tau, worst_paths);
    if (worst_root > 1e-10 || worst_tau > 1e-10 || worst_paths > 1e-10) bad = 1;
    vt_data_free(d[0]);
    vt_data_free(d[1]);
    vt_data_free(g);
    vt_model_free(m);
    vt_model_free(bare);
    return bad;
}
