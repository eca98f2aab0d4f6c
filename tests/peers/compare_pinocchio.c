/* vtdyn loading a URDF robot against Pinocchio loading the same file: at every state of a
 * reference CSV written by tests/peers/pinocchio_reference.py (Pinocchio's rnea and data.f),
 * vt_inverse_dynamics_motion() on the model of vt_urdf_builder() must give the same joint
 * torques and every joint's reaction without the actuation, in world axes and in the joint's
 * (the child link's URDF) axes, the moment about the joint's origin, to a relative tolerance
 * of the largest torque or wrench of the state.
 *
 *   compare_pinocchio [--floating] ROBOT.urdf REFERENCE.csv [tolerance]      (default 1e-12)
 *
 * The reference's joints are matched to vtdyn's by name (the URDF joint names); Pinocchio's
 * default treats a mimic joint as an independent joint, and so does the loader here
 * (vt_urdf_options.mimic = 0). With --floating the reference is Pinocchio's free flyer
 * (JointModelFreeFlyer, "root_joint") and vtdyn's root a free joint (vt_urdf_options.floating):
 * vtdyn's q = (x, y, z, q_w, q_x, q_y, q_z) from Pinocchio's (x, y, z, q_x, q_y, q_z, q_w); its
 * q̇ and q̈ are the root origin's velocity and classical acceleration and the angular velocity
 * and acceleration, world axes (the reference's base:* columns; Pinocchio's v and a are in the
 * root frame); its six efforts (world force, moment about the root origin in world axes) are
 * turned into the root frame, R^T f and R^T n, Pinocchio's tau of the free flyer. Its reaction
 * (zero in vtdyn) against Pinocchio's f − S τ (S = I). Prints the largest relative differences;
 * exit 0 when within the tolerance, 1 otherwise. With --effects the reference's torques include
 * Pinocchio's model.armature (its armature:JOINT columns, set here on vtdyn's builder) and
 * model.damping v + model.friction sign(v) (Pinocchio's own reading of <dynamics>, which vtdyn's
 * loader reads too: they must agree exactly). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vtdyn.h"

typedef struct {
    int ncol, nrow;
    char **name;
    double *cell;
} table;

static int read_csv(table *t, const char *path)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "r");
    if (!f) return fprintf(stderr, "%s: %s\n", path, strerror(errno)), 1;
    char *line = NULL;
    size_t cap = 0;
    int caprow = 0;
    while (getline(&line, &cap, f) >= 0) {
        line[strcspn(line, "\r\n")] = '\0';
        if (!line[0]) continue;
        if (!t->ncol) {
            for (char *p = strtok(line, ","); p; p = strtok(NULL, ",")) {
                t->name = realloc(t->name, (size_t)(t->ncol + 1) * sizeof *t->name);
                t->name[t->ncol++] = strdup(p);
            }
            continue;
        }
        if (t->nrow == caprow) {
            caprow = caprow ? 2 * caprow : 64;
            t->cell = realloc(t->cell, (size_t)caprow * (size_t)t->ncol * sizeof *t->cell);
        }
        int c = 0;
        for (char *p = strtok(line, ","); p && c < t->ncol; p = strtok(NULL, ","), c++)
            t->cell[(size_t)t->nrow * (size_t)t->ncol + (size_t)c] = strtod(p, NULL);
        if (c != t->ncol) return fprintf(stderr, "%s: row %d has %d cells\n", path, t->nrow + 2, c), fclose(f), 1;
        t->nrow++;
    }
    free(line);
    fclose(f);
    return t->nrow ? 0 : (fprintf(stderr, "%s: no rows\n", path), 1);
}

static int col(const table *t, const char *quantity, const char *joint, const char *comp)
{
    char key[256];
    snprintf(key, sizeof key, comp ? "%s:%s:%s" : "%s:%s", quantity, joint, comp);
    for (int c = 0; c < t->ncol; c++)
        if (strcmp(t->name[c], key) == 0) return c;
    return -1;
}

int main(int argc, char **argv)
{
    int floating = 0, effects = 0;
    for (; argc > 1 && strncmp(argv[1], "--", 2) == 0; argv++, argc--) {
        if (strcmp(argv[1], "--floating") == 0) floating = 1;
        else if (strcmp(argv[1], "--effects") == 0) effects = 1;
        else return fprintf(stderr, "compare_pinocchio: unknown option %s\n", argv[1]), 2;
    }
    if (argc < 3)
        return fprintf(stderr, "usage: compare_pinocchio [--floating] [--effects] ROBOT.urdf REFERENCE.csv [tolerance]\n"), 2;
    const double tol = argc > 3 ? atof(argv[3]) : 1e-12;
    table t;
    if (read_csv(&t, argv[2])) return 1;
    vt_urdf_options opt = vt_default_urdf_options();
    opt.mimic = 0; /* as Pinocchio's default: a mimic joint is a joint of its own */
    opt.floating = floating;
    opt.dynamics = effects; /* Pinocchio's rnea leaves <dynamics> out: the reference adds them with --effects */
    char msg[256] = "";
    vt_builder *b;
    vt_model *m;
    vt_data *d;
    vt_status st = vt_urdf_builder(&b, argv[1], &opt, msg);
    if (st) return fprintf(stderr, "%s: %s\n", argv[1], msg), 1;
    /* --effects: each joint's armature from the reference (Pinocchio's model.armature), set on the
     * loaded builder; damping and friction stay vtdyn's own reading of <dynamics>, held against
     * Pinocchio's model.damping and model.friction below */
    for (int c = 0; effects && c < t.ncol; c++) {
        if (strncmp(t.name[c], "armature:", 9) != 0) continue;
        const int body = vt_builder_find_joint(b, t.name[c] + 9);
        vt_joint_effects_def e;
        if (body < 0 || vt_builder_joint_effects(b, body, &e))
            return fprintf(stderr, "%s: no joint %s\n", argv[1], t.name[c] + 9), 1;
        e.armature[0] = t.cell[c];
        if ((st = vt_builder_set_joint_effects(b, body, &e))) return fprintf(stderr, "%s\n", vt_builder_message(b)), 1;
    }
    if ((st = vt_builder_build(&m, b)) || (st = vt_data_create(&d, m)))
        return fprintf(stderr, "%s: %s\n", argv[1], vt_builder_message(b)), 1;
    vt_builder_free(b);
    /* Pinocchio's name of each body's joint: the free flyer is "root_joint" */
    const char **jname = calloc((size_t)m->nbody + 1, sizeof *jname);
    int root = 0;
    for (int i = 1; i <= m->nbody; i++) {
        jname[i] = m->joint_name + VT_NAME_MAX * i;
        if (m->body_joint[i] == VT_JOINT_FREE && m->body_parent[i] == 0 && !jname[i][0]) {
            jname[i] = "root_joint";
            root = i;
        }
        if (m->body_joint[i] == VT_JOINT_BASE) return fprintf(stderr, "%s: a base body: not expected\n", argv[1]), 1;
    }
    if (floating != (root > 0)) return fprintf(stderr, "%s: --floating and the model's root disagree\n", argv[1]), 1;
    int bad = 0;
    for (int i = 1; effects && i <= m->nbody; i++) { /* <dynamics> as Pinocchio read them */
        const int cd = col(&t, "damping", jname[i], NULL), cf = col(&t, "friction", jname[i], NULL);
        if (cd < 0 || cf < 0) continue;
        const double *e = m->dof_effects + 4 * m->body_vadr[i];
        if (e[1] != t.cell[cd] || e[2] != t.cell[cf]) {
            printf("joint %s: damping %.17g friction %.17g, Pinocchio's %.17g %.17g\n", jname[i], e[1], e[2], t.cell[cd],
                   t.cell[cf]);
            bad++;
        }
    }
    static const char *xyz[3] = {"x", "y", "z"};
    static const char *fc[6] = {"fx", "fy", "fz", "mx", "my", "mz"};
    double worst_tau = 0.0, worst_w = 0.0, worst_l = 0.0;
    for (int r = 0; r < t.nrow; r++) {
        const double *row = t.cell + (size_t)r * (size_t)t.ncol;
        double scale = 0.0;
        for (int i = 1; i <= m->nbody; i++) { /* the state, joint by joint */
            const char *j = jname[i];
            if (i == root) { /* position, Euler parameters (scalar first), world rates */
                double *q = d->q + m->body_qadr[i], *v = d->qd + m->body_vadr[i], *a = d->qdd + m->body_vadr[i];
                static const char *qk[7] = {"0", "1", "2", "6", "3", "4", "5"};
                for (int k = 0; k < 7; k++) q[k] = row[col(&t, "q", j, qk[k])];
                for (int k = 0; k < 3; k++) {
                    v[k] = row[col(&t, "base", "pdot", xyz[k])];
                    v[3 + k] = row[col(&t, "base", "omega", xyz[k])];
                    a[k] = row[col(&t, "base", "pddot", xyz[k])];
                    a[3 + k] = row[col(&t, "base", "omegadot", xyz[k])];
                }
                static const char *six[6] = {"0", "1", "2", "3", "4", "5"};
                for (int k = 0; k < 6; k++) scale = fmax(scale, fabs(row[col(&t, "tau", j, six[k])]));
                for (int k = 0; k < 6; k++) scale = fmax(scale, fabs(row[col(&t, "frw", j, fc[k])]));
                continue;
            }
            const int cq = col(&t, "q", j, "0"), cv = col(&t, "v", j, "0"), ca = col(&t, "a", j, "0");
            if (cq < 0 || cv < 0 || ca < 0) return fprintf(stderr, "%s: no state of joint '%s'\n", argv[2], j), 1;
            d->q[m->body_qadr[i]] = row[cq];
            d->qd[m->body_vadr[i]] = row[cv];
            d->qdd[m->body_vadr[i]] = row[ca];
            scale = fmax(scale, fabs(row[col(&t, "tau", j, "0")]));
            for (int k = 0; k < 6; k++) scale = fmax(scale, fabs(row[col(&t, "frw", j, fc[k])]));
        }
        if ((st = vt_inverse_dynamics_motion(m, d)))
            return fprintf(stderr, "state %d: %s: %s\n", r, vt_status_string(st), d->message), 1;
        for (int i = 1; i <= m->nbody; i++) {
            const char *j = jname[i];
            double e_tau = 0.0;
            if (i == root) { /* vtdyn's world wrench at the root origin, turned into the root frame */
                const double *tw = d->qfrc_drive + m->body_vadr[i];
                double Rr[9];
                static const char *rc[9] = {"00", "01", "02", "10", "11", "12", "20", "21", "22"};
                for (int k = 0; k < 9; k++) Rr[k] = row[col(&t, "R", j, rc[k])]; /* row-major */
                static const char *six[6] = {"0", "1", "2", "3", "4", "5"};
                for (int k = 0; k < 6; k++) {
                    const double *w = tw + (k < 3 ? 0 : 3);
                    const int c = k % 3; /* (R^T w)_c = Σ_r R[r][c] w_r */
                    const double loc = Rr[c] * w[0] + Rr[3 + c] * w[1] + Rr[6 + c] * w[2];
                    const double e = fabs(loc - row[col(&t, "tau", j, six[k])]) / scale;
                    if (e > tol && bad++ < 10)
                        printf("state %d root_joint tau %d: vtdyn %.17g, Pinocchio %.17g\n", r, k, loc,
                               row[col(&t, "tau", j, six[k])]);
                    e_tau = fmax(e_tau, e);
                }
            } else {
                e_tau = fabs(d->qfrc_drive[m->body_vadr[i]] - row[col(&t, "tau", j, "0")]) / scale;
            }
            worst_tau = fmax(worst_tau, e_tau);
            double R[9];
            const int frame = vt_find_frame(m, m->body_name + VT_NAME_MAX * i); /* the child link's axes */
            if (frame < 0 || vt_frame_pose(m, d, frame, NULL, R))
                return fprintf(stderr, "no link frame for body %s\n", m->body_name + VT_NAME_MAX * i), 1;
            for (int k = 0; k < 6; k++) {
                const double *w = k < 3 ? d->jnt_force + 3 * i : d->jnt_moment + 3 * i;
                const int c = k % 3;
                const double local = R[3 * c] * w[0] + R[3 * c + 1] * w[1] + R[3 * c + 2] * w[2];
                const double ew = fabs(w[c] - row[col(&t, "frw", j, fc[k])]) / scale;
                const double el = fabs(local - row[col(&t, "fr", j, fc[k])]) / scale;
                worst_w = fmax(worst_w, ew);
                worst_l = fmax(worst_l, el);
                if (ew > tol || el > tol) {
                    if (bad++ < 10)
                        printf("state %d joint %s %s: vtdyn %.17g (link %.17g), Pinocchio %.17g (joint frame %.17g)\n", r,
                               j, fc[k], w[c], local, row[col(&t, "frw", j, fc[k])], row[col(&t, "fr", j, fc[k])]);
                }
            }
            if (i != root && e_tau > tol && bad++ < 10)
                printf("state %d joint %s: torque vtdyn %.17g, Pinocchio %.17g\n", r, j, d->qfrc_drive[m->body_vadr[i]],
                       row[col(&t, "tau", j, "0")]);
        }
    }
    printf("%s: %d states, %d joints: largest relative difference: torques %.2g, reactions (world) %.2g, "
           "reactions (joint axes) %.2g (tolerance %.2g)\n",
           argv[1], t.nrow, m->nbody, worst_tau, worst_w, worst_l, tol);
    free(jname);
    vt_data_free(d);
    vt_model_free(m);
    for (int c = 0; c < t.ncol; c++) free(t.name[c]);
    free(t.name);
    free(t.cell);
    return bad ? 1 : 0;
}
