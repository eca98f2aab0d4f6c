/* vtdyn — the library's command: a URDF robot's inverse dynamics from a CSV or NumPy file.
 *
 *   vtdyn info [--floating] MODEL.urdf
 *   vtdyn inverse [--floating] [-j N] [--columns LIST] [--precision P]
 *                 [--normalize-quaternions TOL] [--format csv|npy] [--times]
 *                 [--payload LINK,mass,x,y,z[,Ixx,Iyy,Izz,Ixy,Ixz,Iyz]]... [--contacts FILE]
 *                 [--loads FRAME[,FRAME...]] MODEL.urdf STATES.csv|STATES.npy [-o OUT.csv|OUT.npy]
 *   vtdyn --version
 *
 * `inverse` reads one row per instant (a CSV row, or a record of a .npy structured array whose
 * fields are named as the CSV columns). With the columns J, J_vel and J_acc for every moving
 * joint J (and `t` optionally) each row is a state: vt_inverse_dynamics_motion() gives every
 * joint's effort, M* q̈ − Q, and every reaction. With `t` and the positions J alone the rows are
 * samples of a trajectory: each joint follows the cubic spline through its samples
 * (vt_function_spline, exact f' and f''), which gives q̇ and q̈ at each sample time (with a
 * floating root, the splines through its position and its quaternion's components, normalised),
 * and each row's state is solved as a state is. Out, per row: `t` when
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
 * States are read and solved in chunks on threads (the library's batch), so that the memory is
 * flat in the number of rows and the output's bytes the same for any -j.
 *
 * This file: the usage, the options, `info` and main. `inverse` is cmd/inverse.c; the input read
 * in chunks, cmd/input.c; the CSV header and rows parsed and the output written beside its name,
 * cmd/csv.c; the .npy header, cmd/npy.c; the threads, cmd/parallel.c; the URDF loaded,
 * cmd/robot.c; the messages, cmd/message.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "input.h"
#include "inverse.h"
#include "message.h"
#include "robot.h"
#include "vtdyn.h"

static const char usage[] =
    "usage: vtdyn info [--floating] [--inertia-tol TOL] MODEL.urdf\n"
    "       vtdyn inverse [--floating] [-j N] [--columns LIST] [--precision P]\n"
    "                     [--normalize-quaternions TOL] [--format csv|npy] [--times]\n"
    "                     [--payload LINK,mass,x,y,z[,Ixx,Iyy,Izz,Ixy,Ixz,Iyz]]...\n"
    "                     [--joint-params FILE] [--ideal-joints] [--inertia-tol TOL]\n"
    "                     [--contacts FILE] [--loads FRAME[,FRAME...]]\n"
    "                     MODEL.urdf STATES.csv|STATES.npy [-o OUT.csv|OUT.npy]\n"
    "       vtdyn --version | --help\n"
    "\n"
    "--floating  the robot's root link (one no joint attaches to the world) floats: a free joint\n"
    "            from the world, with the columns below; without it the root is fixed to the world.\n"
    "            A URDF floating joint from the world floats either way.\n"
    "info     the bodies (URDF links), their joints (name, kind, rates), masses and frames; then\n"
    "         the input columns of a states file for this robot on one line (a header to paste)\n"
    "         and the frames' names on one line.\n"
    "inverse  efforts and joint reactions, one output row per input row (stdout by default).\n"
    "         STATES.csv: a header row, then one row per instant, comma separated. For each\n"
    "         moving joint J of the robot (a revolute, continuous or prismatic URDF joint):\n"
    "           J      position, rad or m (URDF's joint coordinate)\n"
    "           J_vel  velocity, rad/s or m/s\n"
    "           J_acc  acceleration, rad/s^2 or m/s^2\n"
    "         and optionally t (s). Given t and the positions alone, the rows are samples of a\n"
    "         trajectory (t increasing): velocities and accelerations come from the cubic spline\n"
    "         through each joint's samples (not-a-knot ends).\n"
    "         STATES.npy: the same columns as the fields of a NumPy structured array of shape\n"
    "         (N,), each '<f8' (little-endian float64), C order: numpy.save of\n"
    "         numpy.rec.fromarrays([...], names='t,joint1,...') or of a structured zeros array.\n"
    "         OUT.csv: t (when given), then per moving joint J\n"
    "           J_effort                 the joint's torque or force, N m or N (with its joint's\n"
    "                                    armature, damping and friction: --joint-params)\n"
    "           J_fx J_fy J_fz           the reaction force of the parent link on the child link, N,\n"
    "           J_nx J_ny J_nz           and its moment about the child link frame's origin, N m,\n"
    "                                    in the URDF's world axes; the joint's actuation (the\n"
    "                                    effort) is not part of the reaction\n"
    "           J_fx_link ... J_nz_link  the same in the child link's URDF axes (the joint's frame)\n"
    "         and on request (--columns):\n"
    "           J_axial_force J_radial_force    the reaction force along the joint's URDF axis (N,\n"
    "                                    signed) and its magnitude across it (N)\n"
    "           J_axial_moment J_tilt_moment     the reaction moment about the axis (N m, signed;\n"
    "                                    zero for a revolute joint: its torque is the effort) and\n"
    "                                    its magnitude across it (N m)\n"
    "           J_position_excess J_vel_excess J_effort_excess  how far beyond the URDF <limit> the\n"
    "                                    position, velocity and effort are (value minus the limit\n"
    "                                    passed, signed), 0 within or exactly at it; nothing clipped\n"
    "         OUT.npy: the same columns as the fields of a structured array (as STATES.npy):\n"
    "         numpy.load(OUT.npy)['J_effort'].\n";
static const char usage_root[] =
    "         A floating root R (the floating joint's name; with --floating and no such joint, the\n"
    "         root link's name) has, in place of R, R_vel and R_acc, these input columns:\n"
    "           R_x R_y R_z                 its link frame's origin, world axes, m\n"
    "           R_qw R_qx R_qy R_qz         its link frame's orientation (unit quaternion, scalar\n"
    "                                       first; norm within 1e-6 of 1, normalised), link axes\n"
    "                                       to world axes\n"
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
    "         As samples (t and the positions alone) a floating root has R_x ... R_qz alone (each\n"
    "         quaternion's norm within TOL of 1, --normalize-quaternions; q and -q alike): its\n"
    "         velocities and accelerations come from the cubic splines through R_x, R_y, R_z and\n"
    "         through the quaternion's components (signs made continuous, then normalised), and\n"
    "         each row is solved as a state. A floating joint between two links is refused.\n"
    "         Gravity is -9.81 m/s^2 along z (URDF robots are z up). Numbers are read with a '.'\n"
    "         decimal point whatever the locale.\n";
/* (three strings: C's bound on one literal's length) */
static const char usage_options[] =
    "\n"
    "options of inverse:\n"
    "  -j N             threads: 0 (default) every CPU the process may use, 1 the calling thread\n"
    "                   alone; the output's bytes are the same for any N\n"
    "  --columns LIST   the output's groups, comma separated (each joint's in this order whatever\n"
    "                   LIST's): effort (J_effort; a floating root's R_effort_*, both axes),\n"
    "                   world (J_fx ... J_nz), link (J_fx_link ... J_nz_link), bearing\n"
    "                   (J_axial_force ... J_tilt_moment), limits (J_position_excess ...\n"
    "                   J_effort_excess), parts (J_effort_rigid, J_effort_armature,\n"
    "                   J_effort_damping, J_effort_friction: J_effort's rigid-body part and the\n"
    "                   parts its joint's own effects take);\n"
    "                   default effort,world,link\n"
    "  --precision P    a CSV number's significant digits, 1 to 17 (printf's %.Pg); default the\n"
    "                   fewest that read back as the double written (a .npy output holds the\n"
    "                   doubles themselves)\n"
    "  --normalize-quaternions TOL\n"
    "                   a floating root's quaternion whose norm is within TOL of 1 is normalised,\n"
    "                   further off the row is refused; 0 <= TOL < 1, default 1e-6\n"
    "  --format csv|npy the output's format; default by -o's name (.npy: NumPy, else CSV), CSV on\n"
    "                   standard output (npy there needs the row count ahead: a .npy or samples\n"
    "                   input)\n"
    "  --times          the rows, and the seconds spent reading, solving and writing, on stderr\n"
    "  --payload LINK,mass,x,y,z[,Ixx,Iyy,Izz,Ixy,Ixz,Iyz]\n"
    "                   a rigid body fixed to the link LINK: its mass (kg), its centre of mass\n"
    "                   (m) and its inertia about it (kg m^2, default 0: a point mass), both in\n"
    "                   LINK's URDF frame; merged into LINK as a link fixed to it in the file\n"
    "                   would be. Repeatable (at most 64)\n"
    "  --joint-params FILE\n"
    "                   the joints' armature (kg m^2 or kg), viscous damping (N m s/rad or N s/m)\n"
    "                   and Coulomb friction (N m or N), joint side: a CSV file with the header\n"
    "                   joint,armature,damping,friction and a row per joint named, which takes\n"
    "                   all three from it (in place of its URDF <dynamics>); each J_effort then\n"
    "                   adds armature J_acc + damping J_vel + friction sign(J_vel) (0 at rest)\n"
    "  --ideal-joints   the URDF's <dynamics damping friction> ignored (read by default)\n"
    "  --inertia-tol TOL\n"
    "                   the inertia checks' relative tolerance (symmetry, positive, triangle\n"
    "                   inequality), 0 <= TOL < 1; default the library's 1e-6 (also for info)\n";

/* the options' help, cont'd (one C string holds at most 4095 characters): the loads from outside */
static const char usage_loads[] =
    "  --contacts FILE  the robot on the ground (docs/contact.md): a CSV file with the header\n"
    "                   frame,mu and a row per contact, a link whose frame's origin touches the\n"
    "                   ground and its Coulomb friction (empty: bilateral); optional columns\n"
    "                   faces (the friction pyramid's, 3 to 64; default 4), nx,ny,nz (the\n"
    "                   ground's normal, world axes; default against gravity, +z), weight\n"
    "                   (the rule's w_c, N^-2; default 1e-4), x,y,z (the point in the link's\n"
    "                   frame, m; default 0: a sole's corners, a row each) and name (the\n"
    "                   contact's, default the link's; needed for several points on one\n"
    "                   link); an empty cell takes the default.\n"
    "                   A floating root is then not actuated: the ground's forces carry it,\n"
    "                   shared by the least squared motor efforts.\n"
    "                   A states column C_active (0 or 1) per contact C says when it is on the\n"
    "                   ground (without it, always); the output adds C_fx C_fy C_fz, the\n"
    "                   ground's force on the link (N, world axes). States or samples\n"
    "                   (C_active read as it is, not splined).\n"
    "  --loads FRAME[,FRAME...]\n"
    "                   wrenches the environment applies at link frames (a tool's measured\n"
    "                   force): the states columns F_fx F_fy F_fz (N) and F_nx F_ny F_nz (N m,\n"
    "                   about the frame's origin), world axes, for each frame F named; the\n"
    "                   efforts and reactions (and with --contacts the ground's forces) then\n"
    "                   carry them. States or samples (each sample's own, not splined).\n";

/* the usage, whole, on f */
static void print_usage(FILE *f)
{
    fputs(usage, f);
    fputs(usage_root, f);
    fputs(usage_options, f);
    fputs(usage_loads, f);
}

/* `vtdyn info`: the bodies, joints, limits, frames and couplings of the URDF at path */
static int info(const char *path, int floating, double inertia_tol)
{
    vt_builder *b;
    vt_model *m;
    if (cmd_load_urdf(&b, path, floating, 1, inertia_tol)) return 1;
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
    cmd_states_header(m, stdout);
    printf("frames (their names):\n");
    for (int k = 0; k < m->nframe; k++) printf("%s%s", m->frame_name + VT_NAME_MAX * k, k + 1 < m->nframe ? "," : "\n");
    printf("a wrench at frame F (inverse --loads F): the states columns F_fx,F_fy,F_fz,F_nx,F_ny,F_nz\n");
    vt_model_free(m);
    return 0;
}

/* an option's value: the next argument, or the text after '=' in --opt=VALUE; NULL when missing */
static const char *option_value(int argc, char **argv, int *k, const char *eq)
{
    if (eq) return eq + 1;
    if (*k + 1 < argc) return argv[++*k];
    return NULL;
}

/* --columns LIST into *groups; 0 or 1 */
static int parse_columns(const char *list, unsigned *groups)
{
    *groups = 0;
    const char *p = list;
    for (;;) {
        const char *comma = strchr(p, ',');
        const size_t n = comma ? (size_t)(comma - p) : strlen(p);
        unsigned g = 0;
        if (n == 6 && strncmp(p, "effort", 6) == 0) g = COLS_EFFORT;
        else if (n == 5 && strncmp(p, "world", 5) == 0) g = COLS_WORLD;
        else if (n == 4 && strncmp(p, "link", 4) == 0) g = COLS_LINK;
        else if (n == 7 && strncmp(p, "bearing", 7) == 0) g = COLS_BEARING;
        else if (n == 6 && strncmp(p, "limits", 6) == 0) g = COLS_LIMITS;
        else if (n == 5 && strncmp(p, "parts", 5) == 0) g = COLS_PARTS;
        if (!g)
            return cmd_fail("--columns '%s': '%.*s' is none of effort, world, link, bearing, limits, parts", list,
                            (int)n, p);
        if (*groups & g) return cmd_fail("--columns '%s': '%.*s' twice", list, (int)n, p);
        *groups |= g;
        if (!comma) return 0;
        p = comma + 1;
    }
}

/* the options of `inverse` (and `info`'s --floating) and the positional arguments (the first 3,
 * all counted in *npos), -o OUT; 0, or 1 with the message printed */
static int parse_args(int argc, char **argv, inverse_options *o, const char **pos, int *npos, const char **outpath,
                      int info_only)
{
    int seen[14] = {0};
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        const char *eq = strncmp(a, "--", 2) == 0 ? strchr(a, '=') : NULL;
        const size_t len = eq ? (size_t)(eq - a) : strlen(a);
        static const char *const named[] = {"--floating", "-o", "-j", "--columns", "--precision",
                                            "--normalize-quaternions", "--format", "--times", "--payload",
                                            "--joint-params", "--ideal-joints", "--inertia-tol", "--contacts",
                                            "--loads"};
        const int flag = 1 << 0 | 1 << 7 | 1 << 10; /* no value: --floating, --times, --ideal-joints */
        int which = -1;
        for (int w = 0; w < 14; w++)
            if (strlen(named[w]) == len && strncmp(a, named[w], len) == 0) which = w;
        if (which < 0 && strncmp(a, "-j", 2) == 0 && a[2] >= '0' && a[2] <= '9') { /* -j4 */
            which = 2;
            eq = a + 1;
        }
        if (which < 0) {
            if (a[0] == '-' && a[1] != '\0') {
                cmd_fail("unknown option '%s'", a);
                print_usage(stderr);
                return 1;
            }
            if (*npos < 3) pos[*npos] = a;
            (*npos)++;
            continue;
        }
        if (seen[which]++ && which != 8) return cmd_fail("option %s given twice", named[which]);
        if (info_only && which != 0 && which != 11)
            return cmd_fail("info takes --floating and --inertia-tol alone, not %s", named[which]);
        const int bare = flag >> which & 1;
        if (bare && eq) return cmd_fail("%s takes no value", named[which]);
        const char *v = bare ? NULL : option_value(argc, argv, &k, eq);
        if (!bare && !v) return cmd_fail("%s needs a value", named[which]);
        char *end = NULL;
        switch (which) {
        case 0: o->floating = 1; break;
        case 1: *outpath = v; break;
        case 2: {
            const long n = strtol(v, &end, 10);
            if (end == v || *end || n < 0 || n > 1024)
                return cmd_fail("-j '%s': a number of threads, 0 (every CPU the process may use) to 1024", v);
            o->threads = (int)n;
            break;
        }
        case 3:
            if (parse_columns(v, &o->groups)) return 1;
            break;
        case 4: {
            const long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > 17)
                return cmd_fail("--precision '%s': significant digits, 1 to 17 (without it, the fewest "
                                "that read back as the double written)",
                                v);
            o->precision = (int)n;
            o->precision_given = 1;
            break;
        }
        case 5: {
            const double t = strtod(v, &end);
            if (end == v || *end || !(t >= 0.0 && t < 1.0))
                return cmd_fail("--normalize-quaternions '%s': a tolerance on the norm, 0 <= TOL < 1", v);
            o->quat_tol = t;
            break;
        }
        case 6:
            if (strcmp(v, "csv") == 0) o->format = FMT_CSV;
            else if (strcmp(v, "npy") == 0) o->format = FMT_NPY;
            else return cmd_fail("--format '%s': csv or npy", v);
            break;
        case 7: o->times = 1; break;
        case 8:
            if (o->npayload == CMD_PAYLOAD_MAX) return cmd_fail("--payload: at most %d of them", CMD_PAYLOAD_MAX);
            o->payload[o->npayload++] = v;
            break;
        case 9: o->joint_params = v; break;
        case 10: o->ideal = 1; break;
        case 12: o->contacts = v; break;
        case 13: o->loads = v; break;
        case 11: {
            const double t = strtod(v, &end);
            if (end == v || *end || !(t >= 0.0 && t < 1.0))
                return cmd_fail("--inertia-tol '%s': the inertia checks' relative tolerance, 0 <= TOL < 1", v);
            o->inertia_tol = t;
            break;
        }
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--version") == 0) {
        printf("vtdyn %s\n", vt_version());
        return 0;
    }
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        print_usage(stdout);
        return 0;
    }
    if (argc >= 3 && (strcmp(argv[1], "inverse") == 0 || strcmp(argv[1], "info") == 0) &&
        (strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0)) {
        print_usage(stdout);
        return 0;
    }
    const int is_info = argc >= 2 && strcmp(argv[1], "info") == 0;
    const int is_inverse = argc >= 2 && strcmp(argv[1], "inverse") == 0;
    inverse_options o = {.floating = 0, .threads = 0, .groups = COLS_EFFORT | COLS_WORLD | COLS_LINK, .precision = 0,
                         .quat_tol = 1e-6, .format = -1, .inertia_tol = -1.0};
    const char *pos[3] = {NULL, NULL, NULL}, *outpath = NULL;
    int npos = 0;
    if (is_info || is_inverse) {
        if (parse_args(argc, argv, &o, pos, &npos, &outpath, is_info)) return 1;
    }
    if (is_info && npos == 1) return info(pos[0], o.floating, o.inertia_tol);
    if (is_inverse && npos == 2) return cmd_inverse(pos[0], pos[1], outpath, &o);
    print_usage(stderr);
    return 2;
}
