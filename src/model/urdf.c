/* URDF robots into a builder: the URDF frames mapped onto vtdyn's bodies and joints
 * (docs/method.md, "URDF robots"; the XML is parsed by libxml2, the numbers by strtod in the C
 * locale, whatever the caller's LC_NUMERIC).
 *
 * Poses T = (R, t) map x_outer = R x_inner + t and compose as T_ab T_bc; rpy is fixed-axis roll,
 * pitch, yaw: R = Rz(y) Ry(p) Rx(r). URDF gives, per link l, its frame L and its inertial frame
 * I_l = T_{L,I} (<inertial><origin>: the centre of mass and the axes of <inertia>), and per
 * joint J its frame T_{Lp,J} in the parent link's frame (<origin>); at q = 0 the child's link
 * frame is J, and the joint turns (or slides) about <axis> a, given in J.
 *
 * Bodies. A fixed joint merges its child into its parent's body, so a body is a primary link P
 * (the child of a moving joint, or a floating root) with the links fixed to it; T_{P,l} is
 * link l's frame in P's, composed from the fixed joints' origins. The body's frame B is its
 * centre of mass c with P's inertial axes R_I (identity without <inertial>):
 *     M = Σ m_l,   c = Σ m_l c_l / M   (c_l = T_{P,l} T_{l,I_l} 0; c = P's inertial origin if M = 0)
 *     T_{P,B} = (R_I, c),   T_{B,l} = T_{P,B}^-1 T_{P,l}
 *     J_B = Σ Q_l I_l Q_l^T + m_l (|d_l|² 1 − d_l d_l^T)   (parallel axes, in B's axes)
 * with (Q_l, d_l) = T_{B,l} T_{l,I_l} (Q_P = 1 exactly: P's inertia needs no rotation), each term
 * by vt_inertia_add (model/builder.c), which merges a payload into a body the same way. The
 * ground is the root "world" (or every root when not floating) with what is fixed to it; its
 * frame is the global one, the roots' frames coincide with it.
 *
 * Joints. A moving joint from link p (on body j, or the ground) to the primary link P of body i:
 *     joint_parent = t of T_{Bj,J} = T_{Bj,p} T_{p,J}          (j's axes from its centre of mass)
 *     joint_child  = t of T_{Bi,P} = −R_I^T c                  (the joint point is P's origin)
 *     axis1        = R of T_{Bj,J} a                           (j's axes at q = 0)
 *     orientation  = R of T_{Bj,J} R_I                         (i's axes relative to j's at q = 0)
 * so that A^i = A^j A_J(q) A0 is the URDF child frame T_{g,J} Rot(a, q) carried to B by R_I, and
 * q has the URDF joint's sign and zero. A floating joint, and a floating root (with the ground as
 * parent, J = identity), is a free joint (VT_JOINT_FREE) with the same joint_parent, joint_child
 * and orientation: its q is the translation of P's origin from J's in j's axes and A_J(p); for a
 * root, P's origin's global position and P's frame's global orientation. Every link is a frame
 * named after it: body its body, point and orientation T_{B,l}.
 * The joint's frame (vt_body_def.joint_frame, where its reactions are read) is P's link frame,
 * the rotation of T_{B,P}: J itself at q = 0, moving with the child; the URDF axis a is its
 * bearing axis, in it.
 *
 * Bad input gives a status and a message naming the element and its line (vt_xml_line). The
 * XML is read by model/xml.c: this library's libxml2 settings only, no entity, nothing printed,
 * the input at most VT_URDF_MAX_BYTES. No count of links or joints is refused below
 * VT_COUNT_MAX: links and joints are found by name through an index (model/names.h) and the
 * tree is walked once, so the loader's work is O(n log n) in them (the builder's, which it
 * calls, too).
 */
#define _POSIX_C_SOURCE 200809L /* newlocale, uselocale */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <limits.h>
#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>

#include "model/urdf.h"
#include "model/inertia.h"
#include "model/builder.h"
#include "model/names.h"
#include "model/xml.h"
#include "base/status.h"
#include "base/vec3.h"

/* x_outer = A(p) x_inner + t */
typedef struct {
    double p[4];
    double t[3];
} pose;

static const pose pose_identity = {{1.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};

/* r = a b (r may alias neither) */
static void pose_mul(pose *r, const pose *a, const pose *b)
{
    double A[9], v[3];
    vt_euler_A(A, a->p);
    vt_mulmat3(v, A, b->t);
    for (int k = 0; k < 3; k++) r->t[k] = a->t[k] + v[k];
    vt_quat_mul(r->p, a->p, b->p);
}

/* r = a^-1 b */
static void pose_inv_mul(pose *r, const pose *a, const pose *b)
{
    double A[9], d[3];
    vt_euler_A(A, a->p);
    for (int k = 0; k < 3; k++) d[k] = b->t[k] - a->t[k];
    vt_mulmat3t(r->t, A, d);
    const double ac[4] = {a->p[0], -a->p[1], -a->p[2], -a->p[3]};
    vt_quat_mul(r->p, ac, b->p);
}

/* Euler parameters of the fixed-axis roll, pitch, yaw: Rz(y) Ry(p) Rx(r) */
static void quat_rpy(double q[4], const double rpy[3])
{
    static const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    double qx[4], qy[4], qz[4], t[4];
    vt_quat_axis_angle(qx, ex, rpy[0]);
    vt_quat_axis_angle(qy, ey, rpy[1]);
    vt_quat_axis_angle(qz, ez, rpy[2]);
    vt_quat_mul(t, qy, qx);
    vt_quat_mul(q, qz, t);
}

enum { J_FIXED, J_REVOLUTE, J_CONTINUOUS, J_PRISMATIC, J_FLOATING };

typedef struct {
    xmlNodePtr node, inertial_node;
    xmlChar *name;
    int parent_joint;   /* index of the joint whose child it is, or -1 (a root) */
    int has_inertial;
    double mass, inertia[9];
    pose inertial;      /* T_{L,I} */
    int body;           /* its body, 0 the ground; -1 not reached from a root yet */
    pose in_primary;    /* T_{P,l} (the ground: its root's frame, the global one) */
    pose in_body;       /* T_{B,l} */
} urdf_link;

typedef struct {
    xmlNodePtr node;
    xmlChar *name;
    int type, parent, child;
    pose origin;        /* T_{Lp,J} */
    double axis[3];     /* in J */
    int has_limit;
    double lower, upper, effort, velocity;
    double damping, friction;  /* <dynamics>: 0 without */
    xmlNodePtr mimic;          /* <mimic joint multiplier offset>, or NULL */
    double multiplier, offset; /* q = multiplier q_other + offset */
} urdf_joint;

typedef struct {
    int primary;        /* its primary link */
    int joint;          /* the moving joint to it, or -1 (a floating root) */
    double mass, mc[3]; /* M and Σ m_l c_l (P's frame) */
    pose frame;         /* T_{P,B} */
    double inertia[9];  /* about c, B's axes */
} urdf_body;

typedef struct {
    char *msg;          /* VT_MESSAGE_SIZE bytes or NULL */
    int mimic;          /* vt_urdf_options.mimic */
    int dynamics;       /* vt_urdf_options.dynamics */
    urdf_link *link;
    urdf_joint *joint;
    urdf_body *body;
    int nlink, njoint, nbody;
    vt_names link_index, joint_index; /* the links and joints by name (model/names.h) */
} urdf;

static const char *link_name(const void *links, int k)
{
    return (const char *)((const urdf_link *)links)[k].name;
}

static const char *joint_name(const void *joints, int k)
{
    return (const char *)((const urdf_joint *)joints)[k].name;
}

/* "<kind> "<name>" (line L): ..." when node is the link or joint itself, else
 * "<kind> "<name>", <element> (line L): ..." */
static vt_status fail_at(const urdf *u, vt_status st, const char *kind, const xmlChar *name, xmlNodePtr node,
                         const char *fmt, ...)
{
    if (!u->msg) return st;
    char what[224];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    const long line = node ? vt_xml_line(node) : -1;
    const char *who = name ? (const char *)name : "";
    if (!name)
        snprintf(u->msg, VT_MESSAGE_SIZE, "<%.24s> (line %ld): ", node ? (const char *)node->name : kind, line);
    else if (node && strcmp((const char *)node->name, kind) != 0)
        snprintf(u->msg, VT_MESSAGE_SIZE, "%s \"%.64s\", <%.24s> (line %ld): ", kind, who, (const char *)node->name, line);
    else
        snprintf(u->msg, VT_MESSAGE_SIZE, "%s \"%.64s\" (line %ld): ", kind, who, line);
    const size_t n = strlen(u->msg), w = strlen(what), room = 255 - n; /* the reason after the place */
    memcpy(u->msg + n, what, w < room ? w : room);
    u->msg[n + (w < room ? w : room)] = '\0';
    return st;
}

/* attribute attr of node in *value (xmlFree it), or NULL when the node has none; VT_ERR_NO_MEMORY
 * when libxml2 could not copy one that is there (xmlGetNoNsProp says NULL for both) */
static vt_status attr_value(const urdf *u, xmlNodePtr node, const char *attr, xmlChar **value)
{
    *value = node ? xmlGetNoNsProp(node, (const xmlChar *)attr) : NULL;
    if (!*value && node && xmlHasNsProp(node, (const xmlChar *)attr, NULL))
        return vt_fail(u->msg, VT_ERR_NO_MEMORY, "out of memory (libxml2, the attribute %s on line %ld)", attr,
                       vt_xml_line(node));
    return VT_OK;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/* The n numbers of attribute `attr` of node into out (strtod; separated by white space, nothing
 * else around them); out untouched when the attribute is absent. VT_ERR_NONFINITE for a number
 * that is not finite or not a number ("1.0abc"), or too few or too many of them. */
static vt_status numbers(const urdf *u, const char *kind, const xmlChar *owner, xmlNodePtr node, const char *attr,
                         int n, double *out)
{
    xmlChar *text;
    const vt_status got = attr_value(u, node, attr, &text);
    if (got || !text) return got;
    const char *p = (const char *)text;
    double v[6];
    vt_status st = VT_OK;
    for (int k = 0; k < n && st == VT_OK; k++) {
        while (is_space(*p)) p++;
        char *end;
        v[k] = strtod(p, &end);
        if (end == p || (*end && !is_space(*end)))
            st = fail_at(u, VT_ERR_NONFINITE, kind, owner, node, "%s=\"%.40s\" is not %s", attr, (const char *)text,
                         n > 1 ? "three numbers" : "a number");
        else if (!isfinite(v[k]))
            st = fail_at(u, VT_ERR_NONFINITE, kind, owner, node, "%s=\"%.40s\": a number that is not finite", attr,
                         (const char *)text);
        p = end;
    }
    while (st == VT_OK && is_space(*p)) p++;
    if (st == VT_OK && *p)
        st = fail_at(u, VT_ERR_NONFINITE, kind, owner, node, "%s=\"%.40s\" is not %s", attr, (const char *)text,
                     n > 1 ? "three numbers" : "a number");
    if (st == VT_OK) memcpy(out, v, (size_t)n * sizeof(double));
    xmlFree(text);
    return st;
}

/* The first child element of that name, or NULL. */
static xmlNodePtr child(xmlNodePtr node, const char *name)
{
    for (xmlNodePtr c = node->children; c; c = c->next)
        if (c->type == XML_ELEMENT_NODE && xmlStrcmp(c->name, (const xmlChar *)name) == 0) return c;
    return NULL;
}

/* <origin xyz rpy> of node into *T (identity when absent) */
static vt_status origin(const urdf *u, const char *kind, const xmlChar *owner, xmlNodePtr node, pose *T)
{
    *T = pose_identity;
    xmlNodePtr o = child(node, "origin");
    if (!o) return VT_OK;
    double rpy[3] = {0.0, 0.0, 0.0};
    vt_status st = numbers(u, kind, owner, o, "xyz", 3, T->t);
    if (st == VT_OK) st = numbers(u, kind, owner, o, "rpy", 3, rpy);
    if (st == VT_OK) quat_rpy(T->p, rpy);
    return st;
}

static vt_status read_link(urdf *u, urdf_link *l)
{
    l->parent_joint = -1;
    l->body = -1;
    l->inertial = pose_identity;
    xmlNodePtr in = child(l->node, "inertial");
    l->inertial_node = in;
    if (!in) return VT_OK; /* massless */
    l->has_inertial = 1;
    vt_status st = origin(u, "link", l->name, in, &l->inertial);
    if (st) return st;
    xmlNodePtr m = child(in, "mass");
    if (m && (st = numbers(u, "link", l->name, m, "value", 1, &l->mass))) return st;
    if (!(l->mass >= 0.0)) return fail_at(u, VT_ERR_MASS, "link", l->name, m, "mass %g kg is negative", l->mass);
    xmlNodePtr I = child(in, "inertia");
    if (I) {
        static const char *const attr[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
        double v[6] = {0, 0, 0, 0, 0, 0};
        for (int k = 0; k < 6; k++)
            if ((st = numbers(u, "link", l->name, I, attr[k], 1, &v[k]))) return st;
        const double J[9] = {v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5]};
        memcpy(l->inertia, J, sizeof J);
        /* checked where it counts, on the body the link is merged into (vt_builder_add_body):
         * files carry placeholder inertias on links fixed to a heavier one (e.g. 1e-6 in all six
         * entries, rank one), which the body's sum makes sound, and Pinocchio takes as they are;
         * a link that is a body of its own is refused there, naming its joint */
    }
    return VT_OK;
}

static int joint_type(const xmlChar *t)
{
    static const char *const names[] = {"fixed", "revolute", "continuous", "prismatic", "floating"};
    for (int k = 0; t && k < 5; k++)
        if (xmlStrcmp(t, (const xmlChar *)names[k]) == 0) return k;
    return -1;
}

static int find_link(const urdf *u, const xmlChar *name)
{
    return vt_names_find(&u->link_index, u->link, link_name, (const char *)name);
}

/* Mimic joints (<mimic joint multiplier offset>): a joint coordinate tied to another's,
 * q = multiplier q_other + offset (defaults 1 and 0), read here and turned into a coupling
 * (vt_builder_add_coupling) once the bodies are in the builder (add_couplings). With
 * vt_urdf_options.mimic = 0, and on a fixed joint (no coordinate), the tag is ignored. */
static vt_status mimic_joint(const urdf *u, urdf_joint *j, xmlNodePtr mimic)
{
    j->multiplier = 1.0;
    j->offset = 0.0;
    if (!u->mimic || j->type == J_FIXED) return VT_OK;
    vt_status st;
    if (xmlHasProp(mimic, (const xmlChar *)"multiplier") &&
        (st = numbers(u, "joint", j->name, mimic, "multiplier", 1, &j->multiplier)))
        return st;
    if (xmlHasProp(mimic, (const xmlChar *)"offset") && (st = numbers(u, "joint", j->name, mimic, "offset", 1, &j->offset)))
        return st;
    j->mimic = mimic;
    return VT_OK;
}

/* <parent link> or <child link> of a joint: the link's index, or a status */
static vt_status joint_link(const urdf *u, const urdf_joint *j, const char *which, int *index)
{
    xmlNodePtr e = child(j->node, which);
    xmlChar *name;
    vt_status st = attr_value(u, e, "link", &name);
    if (st) return st;
    *index = find_link(u, name);
    if (!name) st = fail_at(u, VT_ERR_NOT_FOUND, "joint", j->name, e ? e : j->node, "no <%s link=\"...\">", which);
    else if (*index < 0)
        st = fail_at(u, VT_ERR_NOT_FOUND, "joint", j->name, e, "%s link \"%.64s\" is not a link of the robot", which,
                     (const char *)name);
    xmlFree(name);
    return st;
}

static vt_status read_joint(urdf *u, int k)
{
    urdf_joint *j = &u->joint[k];
    xmlChar *type;
    vt_status st = attr_value(u, j->node, "type", &type);
    if (st) return st;
    j->type = joint_type(type);
    if (j->type < 0)
        st = fail_at(u, VT_ERR_JOINT_TYPE, "joint", j->name, j->node, "joint type \"%.32s\" %s",
                     type ? (const char *)type : "", type && xmlStrcmp(type, (const xmlChar *)"planar") == 0
                                                         ? "is not supported" : "unknown");
    xmlFree(type);
    if (st) return st;
    xmlNodePtr mimic = child(j->node, "mimic");
    if (mimic && (st = mimic_joint(u, j, mimic))) return st;
    if ((st = joint_link(u, j, "parent", &j->parent)) || (st = joint_link(u, j, "child", &j->child))) return st;
    urdf_link *c = &u->link[j->child];
    if (c->parent_joint >= 0) {
        const urdf_joint *o = &u->joint[c->parent_joint];
        return fail_at(u, VT_ERR_PARENT, "joint", j->name, j->node,
                       "link \"%.64s\" has two parents: joint \"%.64s\" (line %ld) and this one", (const char *)c->name,
                       (const char *)o->name, vt_xml_line(o->node));
    }
    c->parent_joint = k;
    if ((st = origin(u, "joint", j->name, j->node, &j->origin))) return st;
    j->axis[0] = 1.0;
    j->axis[1] = j->axis[2] = 0.0;
    xmlNodePtr axis = child(j->node, "axis");
    if (axis && (st = numbers(u, "joint", j->name, axis, "xyz", 3, j->axis))) return st;
    xmlNodePtr lim = child(j->node, "limit");
    if (lim) { /* URDF: lower and upper default to 0; effort and velocity are required (else: none) */
        j->has_limit = 1;
        j->effort = j->velocity = HUGE_VAL;
        if ((st = numbers(u, "joint", j->name, lim, "lower", 1, &j->lower)) ||
            (st = numbers(u, "joint", j->name, lim, "upper", 1, &j->upper)) ||
            (st = numbers(u, "joint", j->name, lim, "effort", 1, &j->effort)) ||
            (st = numbers(u, "joint", j->name, lim, "velocity", 1, &j->velocity)))
            return st;
    }
    xmlNodePtr dyn = child(j->node, "dynamics");
    if (dyn && u->dynamics) { /* URDF: both optional, 0 by default; the builder refuses negative ones */
        if ((st = numbers(u, "joint", j->name, dyn, "damping", 1, &j->damping)) ||
            (st = numbers(u, "joint", j->name, dyn, "friction", 1, &j->friction)))
            return st;
    }
    return VT_OK;
}

/* Links and joints of <robot>: names unique (each kind's index), every joint's links found, one
 * parent each. */
static vt_status read_robot(urdf *u, xmlNodePtr robot)
{
    int nl = 0, nj = 0;
    for (xmlNodePtr c = robot->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE) continue;
        nl += xmlStrcmp(c->name, (const xmlChar *)"link") == 0;
        nj += xmlStrcmp(c->name, (const xmlChar *)"joint") == 0;
        if (nl > VT_COUNT_MAX || nj > VT_COUNT_MAX) /* each link a frame, each joint at most a body */
            return fail_at(u, VT_ERR_TOO_MANY_BODIES, "robot", NULL, robot, "more than VT_COUNT_MAX (%d) %s",
                           VT_COUNT_MAX, nl > VT_COUNT_MAX ? "links" : "joints");
    }
    u->link = calloc((size_t)nl + 1, sizeof *u->link);
    u->joint = calloc((size_t)nj + 1, sizeof *u->joint);
    u->body = calloc((size_t)nl + 1, sizeof *u->body);
    if (!u->link || !u->joint || !u->body || vt_names_reserve(&u->link_index, nl) ||
        vt_names_reserve(&u->joint_index, nj))
        return vt_fail(u->msg, VT_ERR_NO_MEMORY, "out of memory");
    for (xmlNodePtr c = robot->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE) continue;
        const int is_link = xmlStrcmp(c->name, (const xmlChar *)"link") == 0;
        if (!is_link && xmlStrcmp(c->name, (const xmlChar *)"joint") != 0) continue;
        xmlChar *name;
        const vt_status got = attr_value(u, c, "name", &name);
        if (got) return got;
        const char *kind = is_link ? "link" : "joint";
        if (is_link) {
            u->link[u->nlink].node = c;
            u->link[u->nlink++].name = name;
        } else {
            u->joint[u->njoint].node = c;
            u->joint[u->njoint++].name = name;
        }
        if (!name || !name[0]) return fail_at(u, VT_ERR_BAD_NAME, kind, name, c, "a %s needs a name", kind);
        vt_names *index = is_link ? &u->link_index : &u->joint_index;
        const void *list = is_link ? (const void *)u->link : (const void *)u->joint;
        const vt_name_at at = is_link ? link_name : joint_name;
        const int n = is_link ? u->nlink - 1 : u->njoint - 1, k = vt_names_find(index, list, at, (const char *)name);
        if (k >= 0)
            return fail_at(u, VT_ERR_BAD_NAME, kind, name, c, "name already taken by the %s on line %ld", kind,
                           vt_xml_line(is_link ? u->link[k].node : u->joint[k].node));
        vt_names_insert(index, list, at, n);
    }
    if (u->nlink == 0) return fail_at(u, VT_ERR_EMPTY_MODEL, "robot", NULL, robot, "no <link>");
    vt_status st = VT_OK;
    for (int k = 0; k < u->nlink && st == VT_OK; k++) st = read_link(u, &u->link[k]);
    for (int k = 0; k < u->njoint && st == VT_OK; k++) st = read_joint(u, k);
    return st;
}

/* Bodies breadth-first from the roots (parents before children): each link's body and T_{P,l}.
 * The joints grouped by parent link (a counting sort, each link's joints in the file's order),
 * so that the walk is linear in the links and joints. */
static vt_status order_tree(urdf *u, int floating)
{
    const size_t nl = (size_t)u->nlink, nj = (size_t)u->njoint;
    int *queue = malloc((nl > 0 ? nl : 1) * sizeof *queue), head = 0, tail = 0;
    int *first = calloc(nl + 1, sizeof *first), *by_parent = malloc((nj > 0 ? nj : 1) * sizeof *by_parent);
    if (!queue || !first || !by_parent) {
        free(queue);
        free(first);
        free(by_parent);
        return vt_fail(u->msg, VT_ERR_NO_MEMORY, "out of memory");
    }
    /* link p's joints are by_parent[first[p] .. first[p + 1] − 1] */
    for (int k = 0; k < u->njoint; k++) first[u->joint[k].parent + 1]++;
    for (int p = 0; p < u->nlink; p++) first[p + 1] += first[p];
    for (int k = 0; k < u->njoint; k++) by_parent[first[u->joint[k].parent]++] = k; /* first[p] ends at p + 1's start */
    for (int p = u->nlink; p > 0; p--) first[p] = first[p - 1];
    first[0] = 0;
    for (int k = 0; k < u->nlink; k++) {
        urdf_link *l = &u->link[k];
        if (l->parent_joint >= 0) continue;
        l->in_primary = pose_identity;
        if (floating && xmlStrcmp(l->name, (const xmlChar *)"world") != 0) {
            l->body = ++u->nbody; /* a floating root: a base body */
            u->body[l->body].primary = k;
            u->body[l->body].joint = -1;
        } else {
            l->body = 0;          /* the ground */
        }
        queue[tail++] = k;
    }
    while (head < tail) {
        const int p = queue[head++];
        for (int e = first[p]; e < first[p + 1]; e++) {
            const int k = by_parent[e];
            const urdf_joint *j = &u->joint[k];
            urdf_link *c = &u->link[j->child], *l = &u->link[p];
            if (j->type == J_FIXED) {
                c->body = l->body;
                pose_mul(&c->in_primary, &l->in_primary, &j->origin);
            } else {
                c->body = ++u->nbody;
                c->in_primary = pose_identity;
                u->body[c->body].primary = j->child;
                u->body[c->body].joint = k;
            }
            queue[tail++] = j->child;
        }
    }
    free(queue);
    free(first);
    free(by_parent);
    vt_status st = VT_OK;
    for (int k = 0; k < u->nlink && st == VT_OK; k++) /* one parent each: what no root reaches is a loop */
        if (u->link[k].body < 0) {
            const urdf_joint *j = &u->joint[u->link[k].parent_joint];
            st = fail_at(u, VT_ERR_PARENT, "joint", j->name, j->node,
                         "the links form a loop through link \"%.64s\" (no root reaches it)",
                         (const char *)u->link[k].name);
        }
    return st;
}

/* Each body's mass, centre of mass, axes and inertia (the header's equations), and T_{B,l}. */
static void mass_properties(urdf *u)
{
    for (int k = 0; k < u->nlink; k++) { /* M and Σ m c */
        urdf_link *l = &u->link[k];
        if (l->body <= 0) continue;
        urdf_body *b = &u->body[l->body];
        pose I;
        pose_mul(&I, &l->in_primary, &l->inertial);
        b->mass += l->mass;
        vt_axpy3(b->mc, l->mass, I.t);
    }
    for (int i = 1; i <= u->nbody; i++) {
        urdf_body *b = &u->body[i];
        const urdf_link *P = &u->link[b->primary];
        b->frame = pose_identity;
        memcpy(b->frame.p, P->inertial.p, sizeof b->frame.p);
        if (b->mass > 0.0)
            for (int e = 0; e < 3; e++) b->frame.t[e] = b->mc[e] / b->mass;
        else
            vt_copy3(b->frame.t, P->inertial.t);
    }
    for (int k = 0; k < u->nlink; k++) {
        urdf_link *l = &u->link[k];
        if (l->body <= 0) {
            l->in_body = l->in_primary; /* the ground: global axes */
            continue;
        }
        urdf_body *b = &u->body[l->body];
        pose_inv_mul(&l->in_body, &b->frame, &l->in_primary);
        pose I;
        double Q[9];
        pose_mul(&I, &l->in_body, &l->inertial); /* (Q_l, d_l) */
        if (k != b->primary) vt_euler_A(Q, I.p);
        vt_inertia_add(b->inertia, l->mass, l->inertia, k == b->primary ? NULL : Q, I.t);
    }
}

/* The bodies, then every link's frame, into the builder. */
static vt_status add_to_builder(const urdf *u, vt_builder *bld)
{
    for (int i = 1; i <= u->nbody; i++) {
        const urdf_body *b = &u->body[i];
        const urdf_link *P = &u->link[b->primary];
        vt_body_def def = vt_default_body_def();
        def.mass = b->mass;
        memcpy(def.inertia, b->inertia, sizeof def.inertia);
        def.name = (const char *)P->name;
        /* the joint frame: P's link frame, J at q = 0, moving with the child */
        memcpy(def.joint_frame, P->in_body.p, sizeof def.joint_frame);
        const urdf_joint *j = b->joint >= 0 ? &u->joint[b->joint] : NULL;
        if (!j) { /* a floating root: a free joint from the ground at the link frame's origin */
            def.joint = VT_JOINT_FREE;
            vt_copy3(def.joint_child, P->in_body.t);
            memcpy(def.orientation, b->frame.p, sizeof def.orientation);
        } else {
            const urdf_link *p = &u->link[j->parent];
            pose J; /* T_{Bj,J} */
            pose_mul(&J, &p->in_body, &j->origin);
            double A[9];
            vt_euler_A(A, J.p);
            def.parent = p->body;
            def.joint = j->type == J_PRISMATIC ? VT_JOINT_TRANSLATIONAL
                        : j->type == J_FLOATING ? VT_JOINT_FREE
                                                : VT_JOINT_REVOLUTE;
            vt_copy3(def.joint_parent, J.t);
            vt_copy3(def.joint_child, P->in_body.t);
            vt_mulmat3(def.axis1, A, j->axis);
            vt_quat_mul(def.orientation, J.p, b->frame.p);
            if (j->has_limit && j->type != J_FLOATING) {
                if (j->type != J_CONTINUOUS) { /* continuous: no position limits */
                    def.limit_lower[0] = j->lower;
                    def.limit_upper[0] = j->upper;
                }
                def.limit_effort[0] = j->effort;
                def.limit_velocity[0] = j->velocity;
            }
            if (j->type != J_FLOATING) def.damping[0] = j->damping, def.friction[0] = j->friction;
        }
        if (j) def.joint_name = (const char *)j->name;
        const int id = vt_builder_add_body(bld, &def);
        if (id < 0) {
            if (j) return fail_at(u, (vt_status)id, "joint", j->name, j->node, "%s", vt_builder_message(bld));
            return fail_at(u, (vt_status)id, "link", P->name, P->node, "%s", vt_builder_message(bld));
        }
    }
    for (int k = 0; k < u->nlink; k++) {
        const urdf_link *l = &u->link[k];
        vt_frame_def f = vt_default_frame_def();
        f.name = (const char *)l->name;
        f.body = l->body;
        vt_copy3(f.point, l->in_body.t);
        memcpy(f.orientation, l->in_body.p, sizeof f.orientation);
        const int id = vt_builder_add_frame(bld, &f);
        if (id < 0) return fail_at(u, (vt_status)id, "link", l->name, l->node, "%s", vt_builder_message(bld));
    }
    return VT_OK;
}

/* Every mimic joint's coupling: its coordinate (on its child body) follows the mimicked joint's */
static vt_status add_couplings(const urdf *u, vt_builder *bld)
{
    for (int k = 0; k < u->njoint; k++) {
        const urdf_joint *j = &u->joint[k];
        if (!j->mimic) continue;
        xmlChar *other;
        vt_status st = attr_value(u, j->mimic, "joint", &other);
        if (st) return st;
        const int o = vt_names_find(&u->joint_index, u->joint, joint_name, (const char *)other);
        if (!other) st = fail_at(u, VT_ERR_NOT_FOUND, "joint", j->name, j->mimic, "<mimic> names no joint");
        else if (o < 0)
            st = fail_at(u, VT_ERR_NOT_FOUND, "joint", j->name, j->mimic, "mimics \"%.64s\", not a joint of the robot",
                         (const char *)other);
        else if (u->joint[o].type == J_FIXED || u->joint[o].type == J_FLOATING || o == k)
            st = fail_at(u, VT_ERR_JOINT_TYPE, "joint", j->name, j->mimic, "mimics \"%.64s\", which has no scalar coordinate",
                         (const char *)other);
        xmlFree(other);
        if (st) return st;
        vt_coupling_def c = vt_default_coupling_def();
        c.body_a = u->link[j->child].body;
        c.body_b = u->link[u->joint[o].child].body;
        c.ratio = j->multiplier;
        c.offset = j->offset;
        c.name = (const char *)j->name;
        const int id = vt_builder_add_coupling(bld, &c);
        if (id < 0) return fail_at(u, (vt_status)id, "joint", j->name, j->mimic, "%s", vt_builder_message(bld));
    }
    return VT_OK;
}

static vt_status from_doc(vt_builder **builder, xmlDocPtr doc, const vt_urdf_options *options, char *msg)
{
    urdf u;
    memset(&u, 0, sizeof u);
    u.msg = msg;
    u.mimic = options->mimic != 0;
    u.dynamics = options->dynamics != 0;
    xmlNodePtr robot = xmlDocGetRootElement(doc);
    if (!robot || xmlStrcmp(robot->name, (const xmlChar *)"robot") != 0)
        return robot ? fail_at(&u, VT_ERR_XML, "robot", NULL, robot, "not a URDF file: the root element is not <robot>")
                     : vt_fail(msg, VT_ERR_XML, "not a URDF file: no <robot>");
    vt_builder *b = NULL;
    vt_status st = vt_builder_create(&b, &options->model);
    if (st) vt_fail(msg, st, "options: the model options are refused (%s)", vt_status_string(st));
    if (st == VT_OK) st = read_robot(&u, robot);
    if (st == VT_OK) st = order_tree(&u, options->floating != 0);
    if (st == VT_OK) {
        mass_properties(&u);
        st = add_to_builder(&u, b);
    }
    if (st == VT_OK) st = add_couplings(&u, b);
    for (int k = 0; k < u.nlink; k++) xmlFree(u.link[k].name);
    for (int k = 0; k < u.njoint; k++) xmlFree(u.joint[k].name);
    free(u.link);
    free(u.joint);
    free(u.body);
    vt_names_free(&u.link_index);
    vt_names_free(&u.joint_index);
    if (st) {
        vt_builder_free(b);
        return st;
    }
    if (msg) msg[0] = '\0';
    *builder = b;
    return VT_OK;
}

/* the document into a builder, its numbers read in the C locale whatever the caller's
 * LC_NUMERIC ("0.5", not "0,5"): this thread's locale for the read only, the caller's put back */
typedef struct {
    vt_builder **builder;
    const vt_urdf_options *options;
} urdf_read;

static vt_status read_doc(xmlDocPtr doc, void *user, char *msg)
{
    const urdf_read *r = user;
    locale_t c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!c) return vt_fail(msg, VT_ERR_NO_MEMORY, "out of memory (the C locale for the numbers)");
    const locale_t old = uselocale(c);
    const vt_status st = from_doc(r->builder, doc, r->options, msg);
    uselocale(old);
    freelocale(c);
    return st;
}

/* Parses size bytes of XML (url names them in the messages) and reads the robot. */
static vt_status parse(vt_builder **builder, const char *xml, size_t size, const char *url,
                       const vt_urdf_options *options, char *msg)
{
    const vt_urdf_options opt = options ? *options : vt_default_urdf_options();
    urdf_read r = {.builder = builder, .options = &opt};
    return vt_xml_read(xml, size, url, read_doc, &r, msg);
}

vt_urdf_options vt_default_urdf_options(void)
{
    vt_urdf_options o;
    memset(&o, 0, sizeof o);
    o.model = vt_default_model_def();
    o.model.gravity[1] = 0.0;
    o.model.gravity[2] = -9.81;
    o.floating = 0;
    o.mimic = 1;
    o.dynamics = 1;
    return o;
}

vt_status vt_urdf_builder_string(vt_builder **builder, const char *xml, const vt_urdf_options *options, char *message)
{
    if (!builder) return vt_fail(message, VT_ERR_NULL, "builder is NULL");
    *builder = NULL;
    if (!xml) return vt_fail(message, VT_ERR_NULL, "xml is NULL");
    const size_t size = strnlen(xml, (size_t)VT_URDF_MAX_BYTES + 1); /* not past the bound */
    if (size > (size_t)VT_URDF_MAX_BYTES)
        return vt_fail(message, VT_ERR_XML, "the XML string is longer than VT_URDF_MAX_BYTES (%d bytes)",
                       VT_URDF_MAX_BYTES);
    return parse(builder, xml, size, "string", options, message);
}

vt_status vt_urdf_builder(vt_builder **builder, const char *path, const vt_urdf_options *options, char *message)
{
    if (!builder) return vt_fail(message, VT_ERR_NULL, "builder is NULL");
    *builder = NULL;
    if (!path) return vt_fail(message, VT_ERR_NULL, "path is NULL");
    char *text;
    size_t size;
    vt_status st = vt_xml_read_file(&text, &size, path, message);
    if (!st) st = parse(builder, text, size, path, options, message);
    free(text);
    return st;
}
