/* The command's robot: the URDF loaded with the command's options, and the joint types' names. */
#include "robot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "message.h"

int cmd_load_urdf(vt_builder **b, const char *path, int floating, int dynamics, double inertia_tol)
{
    char msg[VT_MESSAGE_SIZE] = "";
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = floating;
    if (inertia_tol >= 0.0) opt.model.inertia_tol = inertia_tol;
    opt.dynamics = dynamics; /* the joints' <dynamics damping friction>, unless --ideal-joints */
    opt.mimic = 0; /* every joint its own column: a mimic joint's effort is what it needs itself */
    opt.model.layout = VT_LAYOUT_RECURSIVE; /* the rows' given motion and kinematic solve: O(n) data */
    const vt_status st = vt_urdf_builder(b, path, &opt, msg);
    const int inertia = st == VT_ERR_INERTIA_ASYMMETRIC || st == VT_ERR_INERTIA_NOT_PSD || st == VT_ERR_INERTIA_TRIANGLE;
    if (st)
        return cmd_fail("%s: %s (%s)%s", path, msg, vt_status_string(st),
                        inertia ? "; the command's --inertia-tol TOL sets that tolerance" : "");
    return 0;
}

int cmd_add_payload(vt_builder *b, const char *spec, const char *path)
{
    const char *comma = strchr(spec, ',');
    char link[VT_NAME_MAX];
    const size_t n = comma ? (size_t)(comma - spec) : 0;
    if (!comma || n == 0 || n >= sizeof link)
        return cmd_fail("--payload '%s': LINK,mass,x,y,z[,Ixx,Iyy,Izz,Ixy,Ixz,Iyz], LINK a link of %s", spec, path);
    memcpy(link, spec, n);
    link[n] = '\0';
    double v[10] = {0.0}; /* mass, x, y, z, Ixx, Iyy, Izz, Ixy, Ixz, Iyz */
    int count = 0;
    for (const char *p = comma + 1;; count++) {
        char *end;
        const double x = strtod(p, &end);
        if (count == 10 || end == p || (*end && *end != ',') || !isfinite(x))
            return cmd_fail("--payload '%s': after the link, 4 or 10 finite numbers separated by commas: mass (kg), "
                            "x, y, z (m), and optionally Ixx, Iyy, Izz, Ixy, Ixz, Iyz (kg m^2)", spec);
        v[count] = x;
        if (!*end) {
            count++;
            break;
        }
        p = end + 1;
    }
    if (count != 4 && count != 10)
        return cmd_fail("--payload '%s': %d numbers after the link; 4 (mass, x, y, z) or 10 (and Ixx, Iyy, Izz, Ixy, "
                        "Ixz, Iyz)", spec, count);
    if (vt_builder_find_frame(b, link) < 0)
        return cmd_fail("--payload '%s': '%s' is not a link of %s", spec, link, path);
    vt_payload_def p = vt_default_payload_def();
    p.frame = link;
    p.mass = v[0];
    memcpy(p.point, v + 1, sizeof p.point);
    const double J[9] = {v[4], v[7], v[8], v[7], v[5], v[9], v[8], v[9], v[6]};
    memcpy(p.inertia, J, sizeof J);
    const int st = vt_builder_add_payload(b, &p);
    if (st < 0) return cmd_fail("--payload '%s': %s", spec, vt_builder_message(b));
    return 0;
}

const char *cmd_joint_kind(int jt)
{
    static const char *const kinds[VT_JOINT_TYPE_COUNT] = {"base",      "revolute",    "universal", "spherical",
                                                           "prismatic", "cylindrical", "floating"};
    return jt >= 0 && jt < VT_JOINT_TYPE_COUNT ? kinds[jt] : "?";
}

const char *cmd_empty_hint(vt_status st, int floating)
{
    return st == VT_ERR_EMPTY_MODEL && !floating
               ? " (every link is fixed to the world; with --floating the root link floats)"
               : "";
}

/* a side file's cells of one line (the joint parameters, the contacts), split at its commas,
 * spaces around a cell trimmed; a cell in double quotes (RFC 4180, as spreadsheets write headers)
 * is its text between them, "" a quote, a comma inside kept; the count, -1 past max, -2 at a
 * quote left open or text after a closing one */
static int split_cells(char *line, char **cell, int max)
{
    int n = 0;
    for (char *p = line; p;) {
        if (n == max) return -1;
        while (*p == ' ' || *p == '\t') p++;
        char *end; /* the cell's last character + 1, before its comma */
        if (*p == '"') { /* the quoted text, unescaped in place */
            char *w = ++p, *r = p;
            for (;; r++) {
                if (*r == '\0') return -2;
                if (*r == '"' && r[1] == '"') *w++ = '"', r++;
                else if (*r == '"') break;
                else *w++ = *r;
            }
            *w = '\0';
            end = r + 1; /* after the closing quote: spaces, then a comma or the line's end */
            while (*end == ' ' || *end == '\t' || *end == '\r' || *end == '\n') end++;
            if (*end != ',' && *end != '\0') return -2;
            cell[n++] = p;
            p = *end == ',' ? end + 1 : NULL;
            continue;
        }
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        end = p + strlen(p);
        while (end > p && (end[-1] == ' ' || end[-1] == '\t' || end[-1] == '\r' || end[-1] == '\n')) *--end = '\0';
        cell[n++] = p;
        p = comma ? comma + 1 : NULL;
    }
    return n;
}

int cmd_joint_params(vt_builder *b, const char *file, const char *path)
{
    FILE *f = fopen(file, "r");
    if (!f) return cmd_fail("--joint-params %s: %s", file, strerror(errno));
    static const char *const names[4] = {"joint", "armature", "damping", "friction"};
    enum { LINE = 4096 };
    char line[LINE], *cell[8];
    int col[4] = {-1, -1, -1, -1}, lineno = 0, rows = 0, bad = 0;
    int *seen = NULL; /* the bodies set so far, to refuse a joint twice */
    while (!bad && fgets(line, sizeof line, f)) {
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) {
            bad = cmd_fail("--joint-params %s: line %d is longer than %d bytes", file, lineno, LINE - 2);
            break;
        }
        const int n = split_cells(line, cell, 8);
        if (n == -2) {
            bad = cmd_fail("--joint-params %s: line %d: a double quote left open, or text after a closing one", file,
                           lineno);
            break;
        }
        if (n == 1 && !cell[0][0]) continue; /* a blank line */
        if (col[0] < 0) { /* the header: the four names, in any order, nothing else */
            for (int k = 0; k < n; k++)
                for (int c = 0; c < 4; c++)
                    if (strcmp(cell[k], names[c]) == 0 && col[c] < 0) col[c] = k;
            if (n != 4 || col[0] < 0 || col[1] < 0 || col[2] < 0 || col[3] < 0)
                bad = cmd_fail("--joint-params %s: line %d: the header is joint,armature,damping,friction (in any "
                               "order)", file, lineno);
            continue;
        }
        if (n != 4) {
            bad = cmd_fail("--joint-params %s: line %d: %d cells, not 4", file, lineno, n < 0 ? 8 : n);
            break;
        }
        const int body = vt_builder_find_joint(b, cell[col[0]]);
        if (body < 0) {
            bad = cmd_fail("--joint-params %s: line %d: '%s' is not a moving joint of %s", file, lineno, cell[col[0]],
                           path);
            break;
        }
        int twice = 0;
        for (int k = 0; k < rows; k++) twice |= seen[k] == body;
        if (twice) {
            bad = cmd_fail("--joint-params %s: line %d: joint '%s' twice", file, lineno, cell[col[0]]);
            break;
        }
        int *grown = realloc(seen, (size_t)(rows + 1) * sizeof *seen);
        if (!grown) {
            bad = cmd_fail("out of memory");
            break;
        }
        seen = grown;
        seen[rows] = body;
        vt_joint_effects_def e = vt_default_joint_effects_def();
        double *v[3] = {&e.armature[0], &e.damping[0], &e.friction[0]};
        for (int c = 1; c <= 3 && !bad; c++) {
            char *end;
            errno = 0;
            *v[c - 1] = strtod(cell[col[c]], &end);
            if (end == cell[col[c]] || *end || errno == ERANGE || !isfinite(*v[c - 1]) || *v[c - 1] < 0.0)
                bad = cmd_fail("--joint-params %s: line %d: %s '%s' is not a finite number >= 0", file, lineno,
                               names[c], cell[col[c]]);
        }
        if (!bad && vt_builder_set_joint_effects(b, body, &e))
            bad = cmd_fail("--joint-params %s: line %d: %s", file, lineno, vt_builder_message(b));
        rows++;
    }
    if (!bad && ferror(f)) bad = cmd_fail("--joint-params %s: %s", file, strerror(errno));
    if (!bad && col[0] < 0) bad = cmd_fail("--joint-params %s: no header joint,armature,damping,friction", file);
    free(seen);
    fclose(f);
    return bad;
}

/* a cell of the contacts file: a finite number (*x), or empty (keeps *x); 1 if neither */
static int contact_number(const char *cell, double *x)
{
    if (!cell[0]) return 0;
    char *end;
    errno = 0;
    const double v = strtod(cell, &end);
    if (end == cell || *end || errno == ERANGE || !isfinite(v)) return 1;
    *x = v;
    return 0;
}

/* a contact's name: 1 to VT_NAME_MAX − 1 bytes, none of them a comma, a double quote, a space or
 * a control character (it names the columns C_active, C_fx, ...); 1 if not */
static int bad_contact_name(const char *name)
{
    if (!name[0] || strlen(name) >= VT_NAME_MAX) return 1;
    for (const unsigned char *c = (const unsigned char *)name; *c; c++)
        if (*c <= ' ' || *c == ',' || *c == '"' || *c == 127) return 1;
    return 0;
}

int cmd_contacts(const vt_model *m, const char *file, vt_contact_def **defs, char (**names)[VT_NAME_MAX], int *n)
{
    *defs = NULL;
    *names = NULL;
    *n = 0;
    FILE *f = fopen(file, "r");
    if (!f) return cmd_fail("--contacts %s: %s", file, strerror(errno));
    enum { LINE = 4096, NCOL = 11 };
    /* the columns: frame and mu required, the rest optional (empty cells: the defaults) */
    static const char *const colname[NCOL] = {"frame", "mu", "faces", "nx", "ny", "nz", "weight", "name", "x", "y", "z"};
    char line[LINE], *cell[NCOL + 1];
    int col[NCOL], ncol = 0, lineno = 0, bad = 0;
    /* each contact's name and frame while the file is read (2 a contact) */
    char(*nf)[VT_NAME_MAX] = NULL;
    for (int k = 0; k < NCOL; k++) col[k] = -1;
    while (!bad && fgets(line, sizeof line, f)) {
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) {
            bad = cmd_fail("--contacts %s: line %d is longer than %d bytes", file, lineno, LINE - 2);
            break;
        }
        const int nc = split_cells(line, cell, NCOL + 1);
        if (nc == -2) {
            bad = cmd_fail("--contacts %s: line %d: a double quote left open, or text after a closing one", file, lineno);
            break;
        }
        if (nc == 1 && !cell[0][0]) continue; /* a blank line */
        if (ncol == 0) { /* the header: each a known column, once */
            for (int k = 0; k < nc && !bad; k++) {
                int j = 0;
                while (j < NCOL && strcmp(cell[k], colname[j]) != 0) j++;
                if (j == NCOL || col[j] >= 0)
                    bad = cmd_fail("--contacts %s: line %d: column '%s' %s (the header is frame,mu and optionally "
                                   "faces, nx,ny,nz, weight, name, x,y,z)", file, lineno, cell[k],
                                   j == NCOL ? "unknown" : "twice");
                else col[j] = k;
            }
            if (!bad && nc < 0) bad = cmd_fail("--contacts %s: line %d: more than %d columns", file, lineno, NCOL);
            if (!bad && (col[0] < 0 || col[1] < 0))
                bad = cmd_fail("--contacts %s: line %d: the header is frame,mu (in any order, with optional faces, "
                               "nx,ny,nz, weight, name, x,y,z)", file, lineno);
            if (!bad && ((col[3] >= 0) != (col[4] >= 0) || (col[3] >= 0) != (col[5] >= 0)))
                bad = cmd_fail("--contacts %s: line %d: the normal needs all of nx, ny, nz", file, lineno);
            if (!bad && ((col[8] >= 0) != (col[9] >= 0) || (col[8] >= 0) != (col[10] >= 0)))
                bad = cmd_fail("--contacts %s: line %d: the point needs all of x, y, z", file, lineno);
            ncol = nc;
            continue;
        }
        if (nc != ncol) {
            bad = cmd_fail("--contacts %s: line %d: %d cells, not %d", file, lineno, nc < 0 ? NCOL + 1 : nc, ncol);
            break;
        }
        const char *frame = cell[col[0]], *mu = cell[col[1]];
        const char *name = col[7] >= 0 && cell[col[7]][0] ? cell[col[7]] : frame;
        if (vt_find_frame(m, frame) < 0) {
            bad = cmd_fail("--contacts %s: line %d: '%s' is not a link of the robot (vtdyn info lists its frames)",
                           file, lineno, frame);
            break;
        }
        if (bad_contact_name(name)) {
            bad = cmd_fail("--contacts %s: line %d: the name '%s' is not 1 to %d bytes without commas, quotes or "
                           "spaces", file, lineno, name, VT_NAME_MAX - 1);
            break;
        }
        for (int k = 0; k < *n && !bad; k++)
            if (strcmp(nf[2 * k], name) == 0)
                bad = cmd_fail(name == frame ? "--contacts %s: line %d: '%s' twice (several points on one link: give "
                                               "each its name, column name)"
                                             : "--contacts %s: line %d: the name '%s' twice",
                               file, lineno, name);
        if (bad) break;
        vt_contact_def d = vt_default_contact_def();
        if (mu[0]) {
            if (contact_number(mu, &d.mu) || d.mu < 0.0) {
                bad = cmd_fail("--contacts %s: line %d: mu '%s' is not a finite number >= 0 (empty: bilateral)", file,
                               lineno, mu);
                break;
            }
        } else {
            d.kind = VT_CONTACT_BILATERAL;
        }
        if (col[2] >= 0 && cell[col[2]][0]) {
            double k = 0.0;
            if (contact_number(cell[col[2]], &k) || k != floor(k) || k < 3 || k > 64) {
                bad = cmd_fail("--contacts %s: line %d: faces '%s' is not a whole number from 3 to 64 (empty: 4)", file,
                               lineno, cell[col[2]]);
                break;
            }
            d.faces = (int)k;
        }
        if (col[3] >= 0 && (cell[col[3]][0] || cell[col[4]][0] || cell[col[5]][0])) {
            double nv[3] = {0.0, 0.0, 0.0};
            for (int e = 0; e < 3 && !bad; e++)
                if (contact_number(cell[col[3 + e]], &nv[e]))
                    bad = cmd_fail("--contacts %s: line %d: %s '%s' is not a finite number", file, lineno,
                                   colname[3 + e], cell[col[3 + e]]);
            if (!bad && nv[0] == 0.0 && nv[1] == 0.0 && nv[2] == 0.0)
                bad = cmd_fail("--contacts %s: line %d: the normal (nx, ny, nz) is zero (all empty: the world's up)",
                               file, lineno);
            if (bad) break;
            memcpy(d.normal, nv, sizeof nv);
        }
        if (col[6] >= 0 && cell[col[6]][0] && (contact_number(cell[col[6]], &d.weight) || !(d.weight > 0.0))) {
            bad = cmd_fail("--contacts %s: line %d: weight '%s' is not a finite number > 0 (empty: %g)", file, lineno,
                           cell[col[6]], VT_CONTACT_WEIGHT);
            break;
        }
        for (int e = 0; e < 3 && col[8] >= 0 && !bad; e++) /* the point in the link's frame, m (empty: 0) */
            if (contact_number(cell[col[8 + e]], &d.point[e]))
                bad = cmd_fail("--contacts %s: line %d: %s '%s' is not a finite number (m, in the link's frame)", file,
                               lineno, colname[8 + e], cell[col[8 + e]]);
        if (bad) break;
        vt_contact_def *gd = realloc(*defs, (size_t)(*n + 1) * sizeof **defs);
        if (gd) *defs = gd;
        char(*gn)[VT_NAME_MAX] = gd ? realloc(nf, 2 * (size_t)(*n + 1) * sizeof *nf) : NULL;
        if (!gd || !gn) {
            bad = cmd_fail("out of memory");
            break;
        }
        nf = gn;
        snprintf(nf[2 * *n], VT_NAME_MAX, "%s", name);
        snprintf(nf[2 * *n + 1], VT_NAME_MAX, "%s", frame);
        (*defs)[(*n)++] = d;
    }
    if (!bad && ferror(f)) bad = cmd_fail("--contacts %s: %s", file, strerror(errno));
    if (!bad && ncol == 0) bad = cmd_fail("--contacts %s: no header frame,mu", file);
    if (!bad && *n == 0) bad = cmd_fail("--contacts %s: no contact", file);
    fclose(f);
    /* the names first (the caller's columns), then the frames, each definition pointing at both */
    if (!bad && !(*names = malloc(2 * (size_t)*n * sizeof **names))) bad = cmd_fail("out of memory");
    for (int k = 0; !bad && k < *n; k++) {
        memcpy((*names)[k], nf[2 * k], VT_NAME_MAX);
        memcpy((*names)[*n + k], nf[2 * k + 1], VT_NAME_MAX);
        (*defs)[k].name = (*names)[k];
        (*defs)[k].frame = (*names)[*n + k];
    }
    free(nf);
    return bad;
}
