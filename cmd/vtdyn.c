/* vtdyn — the library's command: a URDF robot's inverse dynamics from a CSV file.
 *
 *   vtdyn info [--floating] MODEL.urdf
 *   vtdyn inverse [--floating] MODEL.urdf STATES.csv [-o OUT.csv]
 *   vtdyn --version
 *
 * `inverse` reads one row per instant. With the columns J, J_vel and J_acc for every moving
 * joint J (and `t` optionally) each row is a state: vt_inverse_dynamics_motion() gives every
 * joint's effort, M* q̈ − Q, and every reaction. With `t` and the positions J alone the rows are
 * samples of a trajectory: each joint follows the cubic spline through its samples
 * (vt_function_spline, exact f' and f''), as a joint drive, and vt_kinematic_solve() at each
 * sample time gives q̇ and q̈ from the splines and the drives' efforts. Out, per row: `t` when
 * given, then per moving joint J the effort `J_effort` (N·m or N), the reaction of the parent
 * link on the child link `J_fx J_fy J_fz J_nx J_ny J_nz` (N, N·m; global axes, the moment about
 * the child link frame's origin, the joint's actuation not included) and the same in the child
 * link's URDF axes, `J_fx_link … J_nz_link`. A floating root (a URDF floating joint from the
 * world, or with --floating a root link no joint attaches to the world: a free joint,
 * VT_JOINT_FREE) is given by its link frame's pose, velocity and acceleration in world axes
 * (R_x … R_alz, R the joint's name, or the root link's when the joint is implicit) and gives
 * the six efforts of its rates: the wrench the world would have to apply at the link frame's
 * origin, `R_effort_fx … R_effort_nz` in world axes and `…_link` in the link's axes.
 * Every input column must be one of these (an unknown one stops the run, named), and -o must
 * name a new path or a regular file that is no input. Errors name the file, the row and the
 * column, and exit 1; an output file is written beside its name and renamed when complete, so a
 * failed run leaves no partial file under that name.
 *
 * This file: the usage, `info` and main. `inverse` is cmd/inverse.c; the CSV table read and the
 * output written beside its name, cmd/csv.c; the URDF loaded, cmd/robot.c; the messages,
 * cmd/message.c.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "inverse.h"
#include "message.h"
#include "robot.h"
#include "vtdyn.h"

static const char usage[] =
    "usage: vtdyn info [--floating] MODEL.urdf\n"
    "       vtdyn inverse [--floating] MODEL.urdf STATES.csv [-o OUT.csv]\n"
    "       vtdyn --version | --help\n"
    "\n"
    "--floating  the robot's root link (one no joint attaches to the world) floats: a free joint\n"
    "            from the world, with the columns below; without it the root is fixed to the world.\n"
    "            A URDF floating joint from the world floats either way.\n"
    "info     the bodies (URDF links), their joints (name, kind, rates), masses and frames.\n"
    "inverse  efforts and joint reactions, one output row per input row (stdout by default).\n"
    "         STATES.csv: a header row, then one row per instant, comma separated. For each\n"
    "         moving joint J of the robot (a revolute, continuous or prismatic URDF joint):\n"
    "           J      position, rad or m (URDF's joint coordinate)\n"
    "           J_vel  velocity, rad/s or m/s\n"
    "           J_acc  acceleration, rad/s^2 or m/s^2\n"
    "         and optionally t (s). Given t and the positions alone, the rows are samples of a\n"
    "         trajectory (t increasing): velocities and accelerations come from the cubic spline\n"
    "         through each joint's samples (not-a-knot ends).\n"
    "         OUT.csv: t (when given), then per moving joint J\n"
    "           J_effort                 the joint's torque or force, N m or N\n"
    "           J_fx J_fy J_fz           the reaction force of the parent link on the child link, N,\n"
    "           J_nx J_ny J_nz           and its moment about the child link frame's origin, N m,\n"
    "                                    in the URDF's world axes; the joint's actuation (the\n"
    "                                    effort) is not part of the reaction\n"
    "           J_fx_link ... J_nz_link  the same in the child link's URDF axes\n"
    "         A floating root R (the floating joint's name; with --floating and no such joint, the\n"
    "         root link's name) has, in place of R, R_vel and R_acc, these input columns:\n"
    "           R_x R_y R_z                 its link frame's origin, world axes, m\n"
    "           R_qw R_qx R_qy R_qz         its link frame's orientation (unit quaternion, scalar\n"
    "                                       first; norm within 1e-6 of 1), link axes to world axes\n"
    "           R_vx R_vy R_vz              the origin's velocity, world axes, m/s\n"
    "           R_wx R_wy R_wz              the link's angular velocity, world axes, rad/s\n"
    "           R_ax R_ay R_az              the origin's acceleration, world axes, m/s^2\n"
    "           R_alx R_aly R_alz           the link's angular acceleration, world axes, rad/s^2\n"
    "         and these output columns (its reaction is zero: a free joint transmits nothing):\n"
    "           R_effort_fx R_effort_fy R_effort_fz  the force, N, and the moment about the link\n"
    "           R_effort_nx R_effort_ny R_effort_nz  frame's origin, N m, that the world would have\n"
    "                                       to apply to the root link for the given motion (zero\n"
    "                                       when it is a free flight), world axes\n"
    "           R_effort_fx_link ... R_effort_nz_link  the same in the root link's URDF axes\n"
    "         A floating root needs the states form: samples (positions alone) are refused, as\n"
    "         there is no spline through orientations here. A floating joint between two links\n"
    "         is refused by this command.\n"
    "         Gravity is -9.81 m/s^2 along z (URDF robots are z up). Numbers are read with a '.'\n"
    "         decimal point whatever the locale.\n";

/* `vtdyn info`: the bodies, joints, limits, frames and couplings of the URDF at path */
static int info(const char *path, int floating)
{
    vt_builder *b;
    vt_model *m;
    if (cmd_load_urdf(&b, path, floating)) return 1;
    const vt_status st = vt_builder_build(&m, b);
    if (st) {
        cmd_fail("%s: %s%s", path, vt_builder_message(b), cmd_empty_hint(st, floating));
        vt_builder_free(b);
        return 1;
    }
    vt_builder_free(b);
    double mass = 0.0;
    for (int i = 1; i <= m->nbody; i++) mass += m->body_mass[i];
    printf("%s: %d moving bodies, %d coordinates, %d rates, %g kg; gravity (%g, %g, %g) m/s^2\n", path, m->nbody, m->nq,
           m->nv, mass, m->gravity[0], m->gravity[1], m->gravity[2]);
    printf("%-4s %-24s %-24s %-10s %5s %10s  %s\n", "id", "body (link)", "joint", "kind", "rates", "mass kg", "parent");
    for (int i = 1; i <= m->nbody; i++) {
        const int j = m->body_parent[i];
        printf("%-4d %-24s %-24s %-10s %5d %10.6g  %s\n", i, m->body_name + VT_NAME_MAX * i,
               m->joint_name + VT_NAME_MAX * i, cmd_joint_kind(m->body_joint[i]), m->body_nv[i], m->body_mass[i],
               j ? m->body_name + VT_NAME_MAX * j : "(world)");
        for (int k = 0; k < m->body_nv[i]; k++) {
            const double *lim = m->dof_limit + 4 * (m->body_vadr[i] + k);
            if (isfinite(lim[0]) || isfinite(lim[1]) || isfinite(lim[2]) || isfinite(lim[3]))
                printf("     rate %d limits: [%g, %g], |velocity| <= %g, |effort| <= %g\n", k, lim[0], lim[1], lim[2], lim[3]);
        }
    }
    printf("%d frames:\n", m->nframe);
    for (int k = 0; k < m->nframe; k++) {
        const int i = m->frame_body[k];
        const double *p = m->frame_point + 3 * k;
        printf("  %-28s on %-24s at (%.6g, %.6g, %.6g) m from its centre of mass\n", m->frame_name + VT_NAME_MAX * k,
               i ? m->body_name + VT_NAME_MAX * i : "(world)", p[0], p[1], p[2]);
    }
    for (int k = 0; k < m->ncoupling; k++)
        printf("coupling %s: %s = %g %s + %g\n", m->coupling_name + VT_NAME_MAX * k,
               m->joint_name + VT_NAME_MAX * m->coupling[k].body_a, m->coupling[k].ratio,
               m->joint_name + VT_NAME_MAX * m->coupling[k].body_b, m->coupling[k].offset);
    vt_model_free(m);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--version") == 0) {
        printf("vtdyn %s\n", vt_version());
        return 0;
    }
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        fputs(usage, stdout);
        return 0;
    }
    if (argc >= 3 && strcmp(argv[1], "inverse") == 0 && (strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0)) {
        fputs(usage, stdout);
        return 0;
    }
    /* --floating anywhere after the command; the rest positional, with -o OUT */
    const char *pos[3] = {NULL, NULL, NULL}, *outpath = NULL;
    int npos = 0, floating = 0;
    for (int k = 2; k < argc; k++) {
        if (strcmp(argv[k], "--floating") == 0) {
            floating = 1;
        } else if (strcmp(argv[k], "-o") == 0 && k + 1 < argc && !outpath) {
            outpath = argv[++k];
        } else if (argv[k][0] == '-' && argv[k][1] != '\0') {
            return cmd_fail("unknown option '%s'\n%s", argv[k], usage);
        } else if (npos < 3) {
            pos[npos++] = argv[k];
        } else {
            npos++;
        }
    }
    if (argc >= 2 && strcmp(argv[1], "info") == 0 && npos == 1 && !outpath) return info(pos[0], floating);
    if (argc >= 2 && strcmp(argv[1], "inverse") == 0 && npos == 2) return cmd_inverse(pos[0], pos[1], outpath, floating);
    fputs(usage, stderr);
    return 2;
}
