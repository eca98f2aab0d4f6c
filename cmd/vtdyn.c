/* vtdyn — the library's command: a URDF robot's inverse dynamics from a CSV file.
 *
 *   vtdyn info [--floating] MODEL.urdf
 *   vtdyn inverse [--floating] MODEL.urdf STATES.csv [-o OUT.csv]
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
 * Errors name the file, the row and the column, and exit 1; an output file is written beside
 * its name and renamed when complete, so a failed run leaves no partial file under that name.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "vtdyn.h"

static const char usage[] =
    "usage: vtdyn info [--floating] MODEL.urdf\n"
    "       vtdyn inverse [--floating] MODEL.urdf STATES.csv [-o OUT.csv]\n"
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

/* ---- messages ----------------------------------------------------------------------------- */

static int fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("vtdyn: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return 1;
}

/* ---- CSV: the whole file, split into rows of numeric cells under a header ----------------- */

typedef struct {
    int ncol, nrow;
    char **name;   /* header cells (ncol) */
    double *cell;  /* nrow x ncol, row-major */
} table;

static void table_free(table *t)
{
    for (int c = 0; c < t->ncol; c++) free(t->name[c]);
    free(t->name);
    free(t->cell);
    memset(t, 0, sizeof *t);
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) *--e = '\0';
    return s;
}

/* reads a CSV file of numbers under a header; 0, or 1 with the message printed */
static int read_table(table *t, const char *path)
{
    memset(t, 0, sizeof *t);
    /* numbers with a '.' whatever LC_NUMERIC: this thread in the C locale while reading */
    locale_t cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!cloc) return fail("out of memory (the C locale)");
    const locale_t oldloc = uselocale(cloc);
    FILE *f = fopen(path, "r");
    if (!f) {
        const int e = errno;
        uselocale(oldloc);
        freelocale(cloc);
        return fail("%s: %s", path, strerror(e));
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    int row = 0, cap_rows = 0, status = 0;
    while ((len = getline(&line, &cap, f)) >= 0) {
        row++;
        (void)len;
        char *s = trim(line);
        if (row == 1 && (unsigned char)s[0] == 0xEF && (unsigned char)s[1] == 0xBB && (unsigned char)s[2] == 0xBF)
            s = trim(s + 3); /* a UTF-8 byte-order mark */
        if (!*s) continue; /* blank lines */
        if (!t->ncol) { /* the header */
            for (char *p = s;;) {
                char *comma = strchr(p, ',');
                if (comma) *comma = '\0';
                char **nn = realloc(t->name, (size_t)(t->ncol + 1) * sizeof *nn);
                if (!nn) { status = fail("out of memory"); goto done; }
                t->name = nn;
                t->name[t->ncol] = strdup(trim(p));
                if (!t->name[t->ncol]) { status = fail("out of memory"); goto done; }
                t->ncol++;
                const char *nm = t->name[t->ncol - 1];
                if (!nm[0]) { status = fail("%s:%d: column %d has no name", path, row, t->ncol); goto done; }
                for (int c = 0; c + 1 < t->ncol; c++)
                    if (strcmp(t->name[c], nm) == 0) { status = fail("%s:%d: column '%s' twice", path, row, nm); goto done; }
                if (!comma) break;
                p = comma + 1;
            }
            continue;
        }
        if (t->nrow == cap_rows) {
            cap_rows = cap_rows ? 2 * cap_rows : 256;
            double *nc = realloc(t->cell, (size_t)cap_rows * (size_t)t->ncol * sizeof *nc);
            if (!nc) { status = fail("out of memory"); goto done; }
            t->cell = nc;
        }
        double *out = t->cell + (size_t)t->nrow * (size_t)t->ncol;
        int c = 0;
        for (char *p = s;; c++) {
            char *comma = strchr(p, ',');
            if (comma) *comma = '\0';
            if (c >= t->ncol) { status = fail("%s:%d: more cells than the %d columns of the header", path, row, t->ncol); goto done; }
            char *cell = trim(p), *end = NULL;
            errno = 0;
            out[c] = strtod(cell, &end);
            if (!*cell || *end || (errno == ERANGE && fabs(out[c]) == HUGE_VAL) || !isfinite(out[c])) {
                status = fail("%s:%d: column '%s': '%s' is not a finite number", path, row, t->name[c], cell);
                goto done;
            }
            if (!comma) break;
            p = comma + 1;
        }
        if (c + 1 != t->ncol) { status = fail("%s:%d: %d cells for the %d columns of the header", path, row, c + 1, t->ncol); goto done; }
        t->nrow++;
    }
    if (!t->ncol) status = fail("%s: no header row", path);
    else if (!t->nrow) status = fail("%s: no data rows under the header", path);
done:
    free(line);
    fclose(f);
    uselocale(oldloc);
    freelocale(cloc);
    if (status) table_free(t);
    return status;
}

static int column(const table *t, const char *name)
{
    for (int c = 0; c < t->ncol; c++)
        if (strcmp(t->name[c], name) == 0) return c;
    return -1;
}

/* ---- the model ---------------------------------------------------------------------------- */

static int load(vt_builder **b, const char *path, int floating)
{
    char msg[256] = "";
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = floating;
    opt.mimic = 0; /* every joint its own column: a mimic joint's effort is what it needs itself */
    const vt_status st = vt_urdf_builder(b, path, &opt, msg);
    if (st) return fail("%s: %s (%s)", path, msg, vt_status_string(st));
    return 0;
}

static const char *joint_kind(int jt)
{
    static const char *kinds[VT_JOINT_TYPE_COUNT] = {"base", "revolute", "universal", "spherical", "prismatic",
                                                     "cylindrical", "floating"};
    return jt >= 0 && jt < VT_JOINT_TYPE_COUNT ? kinds[jt] : "?";
}

static int info(const char *path, int floating)
{
    vt_builder *b;
    vt_model *m;
    if (load(&b, path, floating)) return 1;
    const vt_status st = vt_builder_build(&m, b);
    if (st) {
        fail("%s: %s", path, vt_builder_message(b));
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
               m->joint_name + VT_NAME_MAX * i, joint_kind(m->body_joint[i]), m->body_nv[i], m->body_mass[i],
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

/* ---- inverse ------------------------------------------------------------------------------ */

/* a floating root's input columns, after its name and '_' */
#define NFREE 19
static const char *const free_suffix[NFREE] = {"x",  "y",  "z",  "qw", "qx", "qy", "qz", "vx",  "vy",  "vz",
                                               "wx", "wy", "wz", "ax", "ay", "az", "alx", "aly", "alz"};

typedef struct {
    int body, rate;       /* the joint's body and its (first) rate */
    int col, col_vel, col_acc;
    int free;             /* a floating root: its columns in fcol */
    int fcol[NFREE];
    int frame;            /* the child link's frame (its URDF axes), or -1 */
    const char *name;
} joint_cols;

static void progress(int row, int nrow, double *last)
{
    if (!isatty(2) || nrow < 2000) return;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    const double now = (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
    if (now - *last < 0.5 && row + 1 < nrow) return;
    *last = now;
    fprintf(stderr, "\rvtdyn: row %d of %d", row + 1, nrow);
    if (row + 1 == nrow) fputc('\n', stderr);
}

static void write_row(FILE *out, const vt_model *m, vt_data *d, const joint_cols *jc, int nj, int has_t, double t,
                      const double *effort)
{
    if (has_t) fprintf(out, "%.17g,", t);
    for (int k = 0; k < nj; k++) {
        const int i = jc[k].body;
        if (jc[k].free) { /* the six efforts: world axes, then the link's */
            const double *f = effort + 6 * k, *n = f + 3;
            double R[9], fl[3], nl[3];
            if (jc[k].frame < 0 || vt_frame_pose(m, d, jc[k].frame, NULL, R) != VT_OK)
                memcpy(R, d->A + 9 * i, sizeof R); /* no link frame: the body's own axes */
            for (int c = 0; c < 3; c++) {
                fl[c] = R[3 * c] * f[0] + R[3 * c + 1] * f[1] + R[3 * c + 2] * f[2];
                nl[c] = R[3 * c] * n[0] + R[3 * c + 1] * n[1] + R[3 * c + 2] * n[2];
            }
            fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g%s", f[0], f[1], f[2],
                    n[0], n[1], n[2], fl[0], fl[1], fl[2], nl[0], nl[1], nl[2], k + 1 < nj ? "," : "\n");
            continue;
        }
        const double *f = d->jnt_force + 3 * i, *n = d->jnt_moment + 3 * i;
        double R[9], fl[3], nl[3];
        if (jc[k].frame >= 0 && vt_frame_pose(m, d, jc[k].frame, NULL, R) == VT_OK) {
            for (int c = 0; c < 3; c++) {
                fl[c] = R[3 * c] * f[0] + R[3 * c + 1] * f[1] + R[3 * c + 2] * f[2];
                nl[c] = R[3 * c] * n[0] + R[3 * c + 1] * n[1] + R[3 * c + 2] * n[2];
            }
        } else { /* no link frame: the body's own axes */
            memcpy(fl, d->jnt_force_body + 3 * i, sizeof fl);
            memcpy(nl, d->jnt_moment_body + 3 * i, sizeof nl);
        }
        fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g%s", effort[6 * k], f[0],
                f[1], f[2], n[0], n[1], n[2], fl[0], fl[1], fl[2], nl[0], nl[1], nl[2], k + 1 < nj ? "," : "\n");
    }
}

static int inverse(const char *urdf, const char *states, const char *outpath, int floating)
{
    vt_builder *b = NULL;
    vt_model *m = NULL, *probe = NULL;
    vt_data *d = NULL;
    table t;
    joint_cols *jc = NULL;
    double *effort = NULL;
    FILE *out = NULL;
    char *tmp = NULL;
    int status = 1, created = 0;
    if (read_table(&t, states)) return 1;
    if (load(&b, urdf, floating)) goto done;
    /* the moving joints, in the model's order: one column set each (their names point into probe,
     * kept to the end) */
    if (vt_builder_build(&probe, b)) {
        fail("%s: %s", urdf, vt_builder_message(b));
        goto done;
    }
    int nj = 0;
    jc = calloc((size_t)probe->nbody, sizeof *jc);
    effort = calloc(6 * ((size_t)probe->nbody + 1), sizeof *effort);
    if (!jc || !effort) {
        fail("out of memory");
        goto done;
    }
    const int ct = column(&t, "t");
    int samples = -1; /* 1: positions only (samples of a trajectory), 0: states */
    for (int i = 1; i <= probe->nbody; i++) {
        const int jt = probe->body_joint[i];
        const char *name = probe->joint_name + VT_NAME_MAX * i;
        if (jt == VT_JOINT_FREE) continue; /* below, once the form (states or samples) is known */
        if (jt == VT_JOINT_BASE || jt == VT_JOINT_SPHERICAL || probe->body_nv[i] != 1) {
            fail("%s: joint '%s' (%s): only revolute, continuous and prismatic joints are supported here", urdf, name,
                 joint_kind(jt));
            goto done;
        }
        char key[VT_NAME_MAX + 8];
        joint_cols *j = &jc[nj++];
        j->body = i;
        j->rate = probe->body_vadr[i];
        j->name = name;
        j->col = column(&t, name);
        snprintf(key, sizeof key, "%s_vel", name);
        j->col_vel = column(&t, key);
        snprintf(key, sizeof key, "%s_acc", name);
        j->col_acc = column(&t, key);
        j->frame = vt_find_frame(probe, probe->body_name + VT_NAME_MAX * i);
        if (j->col < 0) {
            fail("%s: no column '%s' (the position of joint %s)", states, name, name);
            goto done;
        }
        const int full = j->col_vel >= 0 && j->col_acc >= 0, none = j->col_vel < 0 && j->col_acc < 0;
        const int mode = full ? 0 : none ? 1 : -1;
        if (mode < 0 || (samples >= 0 && mode != samples)) {
            fail("%s: joint '%s': give '%s_vel' and '%s_acc' for every joint, or for none (then with 't', samples)",
                 states, name, name, name);
            goto done;
        }
        samples = mode;
    }
    for (int i = 1; i <= probe->nbody; i++) { /* floating roots */
        if (probe->body_joint[i] != VT_JOINT_FREE) continue;
        const char *name = probe->joint_name + VT_NAME_MAX * i;
        if (!name[0]) name = probe->body_name + VT_NAME_MAX * i; /* an implicit root joint: the link's name */
        if (probe->body_parent[i] != 0) {
            fail("%s: floating joint '%s' from link '%s': only a floating root (from the world) is supported here", urdf,
                 name, probe->body_name + VT_NAME_MAX * probe->body_parent[i]);
            goto done;
        }
        char kx[VT_NAME_MAX + 8], kv[VT_NAME_MAX + 8], ka[VT_NAME_MAX + 8];
        snprintf(kx, sizeof kx, "%s_x", name);
        snprintf(kv, sizeof kv, "%s_vx", name);
        snprintf(ka, sizeof ka, "%s_ax", name);
        if (samples == 1 || (column(&t, kx) >= 0 && column(&t, kv) < 0 && column(&t, ka) < 0)) {
            fail("%s: positions alone (samples of a trajectory) with a floating root '%s': not supported (no spline "
                 "through orientations); give the states: %s_x ... %s_alz and every joint's _vel and _acc",
                 states, name, name, name);
            goto done;
        }
        joint_cols *j = &jc[nj++];
        j->body = i;
        j->rate = probe->body_vadr[i];
        j->name = name;
        j->free = 1;
        j->frame = vt_find_frame(probe, probe->body_name + VT_NAME_MAX * i);
        for (int k = 0; k < NFREE; k++) {
            char key[VT_NAME_MAX + 8];
            snprintf(key, sizeof key, "%s_%s", name, free_suffix[k]);
            if ((j->fcol[k] = column(&t, key)) < 0) {
                fail("%s: no column '%s' (floating root %s: %s_x ... %s_alz, see --help)", states, key, name, name, name);
                goto done;
            }
        }
    }
    if (samples == 1 && ct < 0) {
        fail("%s: positions without velocities and accelerations are samples of a trajectory: a column 't' is needed",
             states);
        goto done;
    }
    double *ts = NULL, *ys = NULL;
    if (samples == 1) { /* a joint drive on every joint, following the spline through its samples */
        ts = malloc((size_t)t.nrow * sizeof *ts);
        ys = malloc((size_t)t.nrow * sizeof *ys);
        if (!ts || !ys) {
            free(ts);
            free(ys);
            fail("out of memory");
            goto done;
        }
        for (int r = 0; r < t.nrow; r++) ts[r] = t.cell[(size_t)r * (size_t)t.ncol + (size_t)ct];
        for (int k = 0; k < nj; k++) { /* (no floating root here) */
            for (int r = 0; r < t.nrow; r++) ys[r] = t.cell[(size_t)r * (size_t)t.ncol + (size_t)jc[k].col];
            vt_drive_def dr = vt_default_drive_def();
            dr.body = jc[k].body;
            dr.f = vt_function_spline(t.nrow, ts, ys);
            if (vt_builder_add_drive(b, &dr) < 0) {
                fail("%s: column '%s' as samples: %s", states, jc[k].name, vt_builder_message(b));
                free(ts);
                free(ys);
                goto done;
            }
        }
        free(ys);
    }
    if (vt_builder_build(&m, b) || vt_data_create(&d, m)) {
        fail("%s: %s", urdf, vt_builder_message(b));
        free(ts);
        goto done;
    }
    if (outpath) {
        tmp = malloc(strlen(outpath) + 8);
        if (!tmp) {
            free(ts);
            fail("out of memory");
            goto done;
        }
        sprintf(tmp, "%s.part", outpath);
        out = fopen(tmp, "wx"); /* ours alone: an existing one is not overwritten, nor removed below */
        if (!out) {
            free(ts);
            fail("%s: %s%s", tmp, strerror(errno), errno == EEXIST ? " (left by another run? remove it)" : "");
            goto done;
        }
        created = 1;
    } else {
        out = stdout;
    }
    if (ct >= 0) fputs("t,", out);
    for (int k = 0; k < nj; k++) {
        const char *n = jc[k].name;
        if (jc[k].free) {
            fprintf(out, "%s_effort_fx,%s_effort_fy,%s_effort_fz,%s_effort_nx,%s_effort_ny,%s_effort_nz,"
                         "%s_effort_fx_link,%s_effort_fy_link,%s_effort_fz_link,%s_effort_nx_link,%s_effort_ny_link,"
                         "%s_effort_nz_link%s",
                    n, n, n, n, n, n, n, n, n, n, n, n, k + 1 < nj ? "," : "\n");
            continue;
        }
        fprintf(out, "%s_effort,%s_fx,%s_fy,%s_fz,%s_nx,%s_ny,%s_nz,%s_fx_link,%s_fy_link,%s_fz_link,%s_nx_link,"
                     "%s_ny_link,%s_nz_link%s",
                n, n, n, n, n, n, n, n, n, n, n, n, n, k + 1 < nj ? "," : "\n");
    }
    double last = 0.0;
    for (int r = 0; r < t.nrow; r++) {
        const double *row = t.cell + (size_t)r * (size_t)t.ncol;
        vt_status st;
        for (int k = 0; k < nj; k++) {
            if (!jc[k].free) {
                d->q[m->body_qadr[jc[k].body]] = row[jc[k].col];
                continue;
            }
            const int *fc = jc[k].fcol;
            double *q = d->q + m->body_qadr[jc[k].body], *qd = d->qd + jc[k].rate, *qdd = d->qdd + jc[k].rate;
            double nq = 0.0;
            for (int c = 0; c < 3; c++) q[c] = row[fc[c]];
            for (int c = 0; c < 4; c++) nq += row[fc[3 + c]] * row[fc[3 + c]];
            nq = sqrt(nq);
            if (!(fabs(nq - 1.0) <= 1e-6)) {
                fail("%s:%d: columns '%s_qw' ... '%s_qz': a quaternion of norm %.17g, not 1 (within 1e-6)", states, r + 2,
                     jc[k].name, jc[k].name, nq);
                goto done_ts;
            }
            for (int c = 0; c < 4; c++) q[3 + c] = row[fc[3 + c]] / nq;
            for (int c = 0; c < 6; c++) {
                qd[c] = row[fc[7 + c]];
                qdd[c] = row[fc[13 + c]];
            }
        }
        if (samples == 1) {
            d->time = row[ct];
            st = vt_kinematic_solve(m, d, 1e-12, 30);
            for (int k = 0; k < nj && !st; k++) effort[6 * k] = d->drive_effort[k];
        } else {
            for (int k = 0; k < nj; k++) {
                if (jc[k].free) continue;
                d->qd[jc[k].rate] = row[jc[k].col_vel];
                d->qdd[jc[k].rate] = row[jc[k].col_acc];
            }
            st = vt_inverse_dynamics_motion(m, d);
            for (int k = 0; k < nj && !st; k++)
                for (int c = 0; c < (jc[k].free ? 6 : 1); c++) effort[6 * k + c] = d->qfrc_drive[jc[k].rate + c];
        }
        if (st) {
            fail("%s:%d: %s (%s)", states, r + 2, d->message, vt_status_string(st));
            goto done_ts;
        }
        write_row(out, m, d, jc, nj, ct >= 0, ct >= 0 ? row[ct] : 0.0, effort);
        progress(r, t.nrow, &last);
    }
    free(ts);
    ts = NULL;
    if (out != stdout) {
        const int bad = ferror(out);
        const int closed = fclose(out);
        out = NULL;
        if (bad || closed) {
            fail("%s: writing failed", tmp);
            goto done;
        }
        if (rename(tmp, outpath)) {
            fail("%s: %s", outpath, strerror(errno));
            goto done;
        }
    } else if (fflush(stdout) || ferror(stdout)) {
        fail("stdout: %s", strerror(errno));
        goto done;
    }
    status = 0;
done_ts:
    free(ts);
done:
    if (out && out != stdout) fclose(out);
    if (status && created) remove(tmp);
    free(tmp);
    free(jc);
    free(effort);
    vt_data_free(d);
    vt_model_free(m);
    vt_model_free(probe);
    vt_builder_free(b);
    table_free(&t);
    return status;
}

int main(int argc, char **argv)
{
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
            return fail("unknown option '%s'\n%s", argv[k], usage);
        } else if (npos < 3) {
            pos[npos++] = argv[k];
        } else {
            npos++;
        }
    }
    if (argc >= 2 && strcmp(argv[1], "info") == 0 && npos == 1 && !outpath) return info(pos[0], floating);
    if (argc >= 2 && strcmp(argv[1], "inverse") == 0 && npos == 2) return inverse(pos[0], pos[1], outpath, floating);
    fputs(usage, stderr);
    return 2;
}
