/* The command's `inverse`: a URDF robot's efforts and joint reactions, one output row per row of
 * a CSV or .npy file of states (positions, velocities, accelerations: the library's batch on
 * threads) or of samples of a trajectory (positions and t: splines through each joint's positions,
 * and a floating root's position and quaternion components, give each row's state, solved by
 * the batch as the states are).
 *
 * The jobs in order: the input's header read and its columns mapped to the joints, the model
 * built (and for samples the splines, which read every row first), the output opened
 * beside its name, then chunk after chunk of rows: the numbers parsed and the states laid out in
 * row-major arrays (on the threads, in contiguous blocks; cmd/states.c), the chunk solved by one
 * vt_batch_inverse_dynamics_motion (bitwise the single call's whatever the threads), and its
 * output rows gathered and formatted (on the threads, each block into its own buffer) and written
 * in order. So the output's bytes do not depend on the number of threads, and the resident memory
 * is that of a chunk, whatever the rows. The first failing row of a chunk — a cell, a quaternion,
 * or the solve (the batch's status a row) — stops the run, named. */
#define _POSIX_C_SOURCE 200809L
#include "inverse.h"

#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "message.h"
#include "output.h"
#include "robot.h"
#include "run.h"
#include "samples.h"
#include "states.h"

const char *const free_suffix[NFREE] = {"x",  "y",  "z",  "qw", "qx", "qy", "qz", "vx",  "vy",  "vz",
                                        "wx", "wy", "wz", "ax", "ay", "az", "alx", "aly", "alz"};

/* frees what the run holds (any part not yet made is NULL) */
static void run_free(run *x)
{
    free(x->frames);
    free(x->ts);
    free(x->jc);
    if (x->names)
        for (int k = 0; k < x->nout; k++) free(x->names[k]);
    free(x->names);
    free(x->cells);
    free(x->q);
    free(x->qd);
    free(x->qdd);
    free(x->effort);
    free(x->reac);
    free(x->reac_link);
    free(x->bearing);
    free(x->excess);
    free(x->parts);
    free(x->status);
    free(x->lframe);
    free(x->lcol);
    free(x->load);
    free(x->vals[0]);
    free(x->vals[1]);
    if (x->blk)
        for (int k = 0; k < x->tm.nblock; k++) {
            free(x->blk[k].text[0]);
            free(x->blk[k].text[1]);
            free(x->blk[k].v);
        }
    free(x->blk);
    team_free(&x->tm);
    chunk_free(&x->ch[0]);
    chunk_free(&x->ch[1]);
    vt_batch_free(x->batch);
    vt_contacts_free(x->contacts);
    free(x->cdef);
    free(x->cname);
    free(x->ccol);
    free(x->active);
    free(x->cforce);
    vt_data_free(x->d);
    vt_model_free(x->m);
    vt_model_free(x->splines);
    vt_model_free(x->probe);
    vt_builder_free(x->b);
    input_close(&x->in);
}

/* loads the URDF and builds it once as it is (the probe, whose joints name the columns); 0 or 1 */
static int load_robot(run *x, const inverse_options *o)
{
    const int floating = o->floating;
    if (cmd_load_urdf(&x->b, x->urdf, floating, !o->ideal, o->inertia_tol)) return 1;
    for (int k = 0; k < o->npayload; k++)
        if (cmd_add_payload(x->b, o->payload[k], x->urdf)) return 1;
    if (o->joint_params && cmd_joint_params(x->b, o->joint_params, x->urdf)) return 1;
    const vt_status st = vt_builder_build(&x->probe, x->b);
    if (st) return cmd_fail("%s: %s%s", x->urdf, vt_builder_message(x->b), cmd_empty_hint(st, floating));
    const vt_model *p = x->probe;
    x->jc = calloc((size_t)p->nbody, sizeof *x->jc);
    x->frames = malloc((size_t)(p->nframe > 0 ? p->nframe : 1) * sizeof *x->frames);
    if (!x->jc || !x->frames) return cmd_fail("out of memory");
    for (int k = 0; k < p->nframe; k++) x->frames[k] = (table_key){p->frame_name + (size_t)VT_NAME_MAX * k, k};
    keys_sort(x->frames, p->nframe);
    return 0;
}

/* the frame of that name (a link's), or -1: vt_find_frame in log nframe */
static int find_frame(const run *x, const char *name)
{
    const int k = keys_find(x->frames, x->probe->nframe, name);
    return k < 0 ? -1 : x->frames[k].col;
}

/* the one-rate joints' columns J, J_vel, J_acc, and from them the form (states or samples):
 * every joint needs its position, and its rates' columns all or none alike; 0 or 1 */
static int map_joints(run *x)
{
    const vt_model *p = x->probe;
    const table *t = &x->in.t;
    /* a header of one name holding a ';' or a tab: a spreadsheet's export in another separator
     * (a comma is the decimal mark in many locales), which no robot's columns could be */
    const char *sep = t->header_line && t->ncol == 1 ? strpbrk(t->name[0], ";\t") : NULL;
    if (sep)
        return cmd_fail("%s:%d: the header is one column, its names separated by %s (the first '%.*s'): vtdyn reads "
                        "comma-separated values, with a '.' for the decimal point",
                        x->states, t->header_line, *sep == ';' ? "';'" : "tabs", (int)(sep - t->name[0]), t->name[0]);
    x->ct = table_column(t, "t");
    for (int i = 1; i <= p->nbody; i++) {
        const int jt = p->body_joint[i];
        const char *name = p->joint_name + VT_NAME_MAX * i;
        if (jt == VT_JOINT_FREE) continue; /* map_floating_roots, once the form is known */
        if (jt == VT_JOINT_BASE || jt == VT_JOINT_SPHERICAL || p->body_nv[i] != 1)
            return cmd_fail("%s: joint '%s' (%s): only revolute, continuous and prismatic joints are supported here",
                            x->urdf, name, cmd_joint_kind(jt));
        char key[VT_NAME_MAX + 8];
        joint_cols *j = &x->jc[x->nj++];
        j->body = i;
        j->rate = p->body_vadr[i];
        j->name = name;
        j->col = table_column(&x->in.t, name);
        snprintf(key, sizeof key, "%s_vel", name);
        j->col_vel = table_column(&x->in.t, key);
        snprintf(key, sizeof key, "%s_acc", name);
        j->col_acc = table_column(&x->in.t, key);
        if (j->col < 0) return cmd_fail("%s: no column '%s' (the position of joint %s)", x->states, name, name);
        const int full = j->col_vel >= 0 && j->col_acc >= 0, none = j->col_vel < 0 && j->col_acc < 0;
        const form f = full ? FORM_STATES : none ? FORM_SAMPLES : FORM_UNKNOWN;
        if (f == FORM_UNKNOWN || (x->form != FORM_UNKNOWN && f != x->form))
            return cmd_fail("%s: joint '%s': give '%s_vel' and '%s_acc' for every joint, or for none (then with 't', "
                            "samples)",
                            x->states, name, name, name);
        x->form = f;
    }
    return 0;
}

/* the floating roots' columns, after the one-rate joints: R_x ... R_alz for states, R_x ... R_qz
 * for samples (the form the joints gave, or with no joint the root's own: any rate column makes
 * it states); then a column t for samples; 0 or 1 */
static int map_floating_roots(run *x)
{
    const vt_model *p = x->probe;
    for (int i = 1; i <= p->nbody; i++) {
        if (p->body_joint[i] != VT_JOINT_FREE) continue;
        const char *name = p->joint_name + VT_NAME_MAX * i;
        if (!name[0]) name = p->body_name + VT_NAME_MAX * i; /* an implicit root joint: the link's name */
        if (p->body_parent[i] != 0)
            return cmd_fail("%s: floating joint '%s' from link '%s': only a floating root (from the world) is "
                            "supported here",
                            x->urdf, name, p->body_name + VT_NAME_MAX * p->body_parent[i]);
        joint_cols *j = &x->jc[x->nj++];
        j->body = i;
        j->rate = p->body_vadr[i];
        j->name = name;
        j->free = 1;
        x->nfree++;
        int rate = -1; /* its first rate column given */
        for (int k = 0; k < NFREE; k++) {
            char key[VT_NAME_MAX + 8];
            snprintf(key, sizeof key, "%s_%s", name, free_suffix[k]);
            j->fcol[k] = table_column(&x->in.t, key);
            if (k >= 7 && j->fcol[k] >= 0 && rate < 0) rate = k;
        }
        /* without R_x: the joints' form (states when there is none), the missing R_x named below */
        form f = rate >= 0 ? FORM_STATES : FORM_SAMPLES;
        if (rate < 0 && j->fcol[0] < 0) f = x->form == FORM_SAMPLES ? FORM_SAMPLES : FORM_STATES;
        if (x->form == FORM_SAMPLES && f == FORM_STATES)
            return cmd_fail("%s: column '%s_%s': a floating root's rate, but the joints have their positions alone "
                            "(samples): give every joint's _vel and _acc and %s_x ... %s_alz (states), or t, the "
                            "positions and %s_x ... %s_qz alone (samples)",
                            x->states, name, free_suffix[rate], name, name, name, name);
        if (x->form == FORM_STATES && f == FORM_SAMPLES)
            return cmd_fail("%s: no column '%s_vx' (floating root %s): the joints have their rates (states), so "
                            "give %s_x ... %s_alz; or t, the positions and %s_x ... %s_qz alone (samples)",
                            x->states, name, name, name, name, name, name);
        x->form = f;
        const int need = f == FORM_STATES ? NFREE : 7;
        for (int k = 0; k < need; k++) {
            if (j->fcol[k] >= 0) continue;
            const int implicit = p->joint_name[VT_NAME_MAX * i] == '\0';
            return cmd_fail("%s: no column '%s_%s' (floating root %s: %s_x ... %s_%s, see --help%s)", x->states,
                            name, free_suffix[k], name, name, name, f == FORM_STATES ? "alz" : "qz as samples",
                            implicit ? "; without --floating the root link is fixed to the world" : "");
        }
    }
    if (x->form == FORM_SAMPLES && x->ct < 0)
        return cmd_fail("%s: positions without velocities and accelerations are samples of a trajectory: a column "
                        "'t' is needed",
                        x->states);
    return 0;
}

/* the suffix of a floating root's input column that name ends with after its '_', or NULL */
static const char *free_column_suffix(const char *name)
{
    const char *us = strrchr(name, '_');
    if (!us) return NULL;
    for (int k = 0; k < NFREE; k++)
        if (strcmp(us + 1, free_suffix[k]) == 0) return us + 1;
    return NULL;
}

/* every input column is one of the robot's (nothing ignored): an unknown column stops the run,
 * named, with the way out where it is a floating root's on a robot loaded fixed; 0 or 1 */
static int check_columns(const run *x, int floating)
{
    const vt_model *p = x->probe;
    char head[ROW_MESSAGE]; /* the header's place: its line, or the .npy file */
    if (x->in.t.header_line) snprintf(head, sizeof head, "%s:%d", x->states, x->in.t.header_line);
    else snprintf(head, sizeof head, "%s", x->states);
    for (int c = 0; c < x->in.t.ncol; c++) {
        if (x->in.t.used[c]) continue;
        const char *name = x->in.t.name[c], *sfx = free_column_suffix(name);
        if (!floating && sfx) { /* P_x ... with P a link fixed to the world: the root, floating in the file */
            char root[VT_NAME_MAX];
            const size_t len = (size_t)(sfx - 1 - name);
            if (len < sizeof root) {
                memcpy(root, name, len);
                root[len] = '\0';
                const int f = find_frame(x, root);
                if (f >= 0 && p->frame_body[f] == 0)
                    return cmd_fail("%s: column %d '%s': a floating root's column, but %s is loaded with its root "
                                    "link '%s' fixed to the world: run with --floating",
                                    head, c + 1, name, x->urdf, root);
            }
        }
        return cmd_fail("%s: column %d '%s' is none of the robot's (%s): every column must be t, a moving joint J's "
                        "J, J_vel or J_acc, a floating root R's R_x ... R_alz (vtdyn info lists the joints), or with "
                        "--contacts a contact C's C_active",
                        head, c + 1, name, x->urdf);
    }
    return 0;
}

/* --contacts: the file's contacts on the probe's frames, and each one's column C_active (or none:
 * always on the ground); states or samples (each row solved as a state); 0 or 1 */
static int map_contacts(run *x)
{
    if (!x->o->contacts) return 0;
    if (cmd_contacts(x->probe, x->o->contacts, &x->cdef, &x->cname, &x->ncontact)) return 1;
    if (!(x->ccol = malloc((size_t)x->ncontact * sizeof *x->ccol))) return cmd_fail("out of memory");
    for (int k = 0; k < x->ncontact; k++) {
        char key[VT_NAME_MAX + 8];
        snprintf(key, sizeof key, "%s_active", x->cname[k]);
        x->ccol[k] = table_column(&x->in.t, key);
    }
    return 0;
}

/* --loads F1,F2,...: each frame's wrench columns F_fx F_fy F_fz F_nx F_ny F_nz (the force, then the
 * moment about the frame's origin, world axes: what the environment applies to the link), each
 * row's own, of states or samples (the batch adds them to each row's instant, before the
 * contacts' forces are shared);
 * the frames' indices in the probe, those of the model solved set by build_model; 0 or 1 */
static int map_loads(run *x)
{
    static const char *const sfx[6] = {"_fx", "_fy", "_fz", "_nx", "_ny", "_nz"};
    const char *list = x->o->loads;
    if (!list) return 0;
    int n = 1;
    for (const char *p = list; *p; p++) n += *p == ',';
    if (!(x->lframe = malloc((size_t)n * sizeof *x->lframe)) || !(x->lcol = malloc(6 * (size_t)n * sizeof *x->lcol)))
        return cmd_fail("out of memory");
    for (const char *p = list;; p++) {
        const char *e = strchr(p, ',');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        char name[VT_NAME_MAX];
        if (len == 0 || len >= sizeof name)
            return cmd_fail("--loads '%s': frame names separated by commas (%s)", list, len ? "one too long" : "one empty");
        memcpy(name, p, len);
        name[len] = '\0';
        const int f = find_frame(x, name);
        if (f < 0) return cmd_fail("--loads: '%s' is no frame of %s (vtdyn info lists them)", name, x->urdf);
        if (x->probe->frame_body[f] == 0)
            return cmd_fail("--loads: frame '%s' is fixed to the world: a load there moves nothing", name);
        const int k = x->nload++;
        x->lframe[k] = f;
        for (int c = 0; c < 6; c++) {
            char key[VT_NAME_MAX + 8];
            snprintf(key, sizeof key, "%s%s", name, sfx[c]);
            if ((x->lcol[6 * k + c] = table_column(&x->in.t, key)) < 0)
                return cmd_fail("%s: no column '%s' (--loads %s: %s_fx ... %s_nz, world axes)", x->states, key, name,
                                name, name);
        }
        if (!e) break;
        p = e;
    }
    return 0;
}

/* the model solved (the robot) and its data, for samples the splines, and the batch on the run's
 * threads; 0 or 1 */
static int build_model(run *x)
{
    if (x->form == FORM_SAMPLES && spline_model(x)) return 1;
    if (vt_builder_build(&x->m, x->b) || vt_data_create(&x->d, x->m))
        return cmd_fail("%s: %s", x->urdf, vt_builder_message(x->b));
    for (int k = 0; k < x->nj; k++) x->jc[k].qadr = x->m->body_qadr[x->jc[k].body];
    for (int k = 0; k < x->nload; k++) /* the probe's frames found again in the model solved */
        x->lframe[k] = vt_find_frame(x->m, x->probe->frame_name + (size_t)VT_NAME_MAX * x->lframe[k]);
    /* the batch counts the CPUs for -j 0 */
    vt_batch_def def = vt_default_batch_def();
    def.threads = x->o->threads;
    if (x->ncontact) {
        char msg[VT_MESSAGE_SIZE];
        if (vt_contacts_create(&x->contacts, x->m, x->cdef, x->ncontact, NULL, msg))
            return cmd_fail("--contacts %s: %s", x->o->contacts, msg);
        def.contacts = x->cdef;
        def.ncontact = x->ncontact;
    }
    const vt_status st = vt_batch_create(&x->batch, x->m, &def);
    if (st) return cmd_fail("%s: %d threads: %s", x->urdf, x->o->threads, vt_status_string(st));
    x->T = vt_batch_threads(x->batch);
    if (team_make(&x->tm, x->batch)) return cmd_fail("out of memory (the C locale)");
    return 0;
}

int cmd_inverse(const char *urdf, const char *states, const char *outpath, const inverse_options *o)
{
    run x = {.urdf = urdf, .states = states, .o = o, .form = FORM_UNKNOWN};
    /* numbers read and written with a '.' whatever LC_NUMERIC: this thread in the C locale (the
     * threads' blocks set their own) */
    locale_t cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!cloc) return cmd_fail("out of memory (the C locale)");
    const locale_t oldloc = uselocale(cloc);
    int status = input_open(&x.in, states) || load_robot(&x, o) || map_joints(&x) ||
                 map_floating_roots(&x) || map_contacts(&x) || map_loads(&x) || check_columns(&x, o->floating) ||
                 build_model(&x) ||
                 output_columns(&x) || output_format(&x, outpath) || chunk_arrays(&x);
    if (!status) {
        const char *inputs[2] = {urdf, states};
        status = output_open(&x.out, outpath, inputs, 2);
        if (!status) {
            static char obuf[1 << 20];
            setvbuf(x.out.f, obuf, _IOFBF, sizeof obuf);
            const double t0 = run_clock();
            const int ok = !(x.form == FORM_SAMPLES ? run_samples(&x) : run_states(&x)) &&
                           !finish_output(&x);
            status = output_close(&x.out, ok);
            if (o->times && ok) {
                const double all = run_clock() - t0;
                fprintf(stderr,
                        "vtdyn: %lld rows in %.3f s (%.0f rows/s, %d threads): read %.3f s, solve %.3f s, "
                        "write %.3f s\n",
                        x.written, all, all > 0 ? (double)x.written / all : 0.0, x.T, x.t_read, x.t_solve, x.t_write);
            }
        }
    }
    run_free(&x);
    uselocale(oldloc);
    freelocale(cloc);
    return status;
}

/* ---- info: the states file's header ---------------------------------------------------------- */

int cmd_states_header(const vt_model *p, FILE *out)
{
    for (int i = 1; i <= p->nbody; i++) {
        const int jt = p->body_joint[i];
        if ((jt == VT_JOINT_FREE && p->body_parent[i] != 0) ||
            (jt != VT_JOINT_FREE && (jt == VT_JOINT_BASE || jt == VT_JOINT_SPHERICAL || p->body_nv[i] != 1))) {
            fprintf(out, "states columns: none: `inverse` does not take joint '%s' (%s)\n",
                    p->joint_name + VT_NAME_MAX * i, cmd_joint_kind(jt));
            return 1;
        }
    }
    fputs("states columns (a header for `inverse`; t may come first):\n", out);
    const char *sep = "";
    for (int i = 1; i <= p->nbody; i++) {
        if (p->body_joint[i] == VT_JOINT_FREE) continue;
        const char *n = p->joint_name + VT_NAME_MAX * i;
        fprintf(out, "%s%s,%s_vel,%s_acc", sep, n, n, n);
        sep = ",";
    }
    for (int i = 1; i <= p->nbody; i++) { /* the floating roots last, as `inverse` lists them */
        if (p->body_joint[i] != VT_JOINT_FREE) continue;
        const char *n = p->joint_name + VT_NAME_MAX * i;
        if (!n[0]) n = p->body_name + VT_NAME_MAX * i;
        for (int k = 0; k < NFREE; k++) {
            fprintf(out, "%s%s_%s", sep, n, free_suffix[k]);
            sep = ",";
        }
    }
    fputc('\n', out);
    return 0;
}
