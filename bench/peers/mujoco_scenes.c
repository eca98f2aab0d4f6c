/* MuJoCo's models of the Delta robot, the Stewart–Gough platform and the knee four-bar
 * (mujoco_scenes.h). Every model: no geoms, contacts, limits, friction, springs, dampers or
 * sensors; zero damping, armature and friction; `jacobian="dense"` (efc_J is nefc × nv, row by
 * row); semi-implicit Euler. Each loop is an equality `connect` between a site on each side: its
 * 3 rows are efc rows 3c .. 3c + 2 of connect c (x, y, z, world axes; the force on site1's body).
 *
 * Delta (vt_scene_delta): the arms on hinges about their y (the motors, m0..m2), each rod on two
 * hinges (the arm's y, then the rod's x: vtdyn's universal joint, MuJoCo applying a body's joints
 * in order), the platform on a free joint, six connects (rod i k's lower end = its point on the
 * platform). Gravity −9.81 z; Newton's solver to 1e-14 in 100 iterations (for mj_forward).
 * Stewart platform (vt_scene_stewart): the platform on a free joint; each leg two hinges at its
 * base point, x then the cylinder's y, as vtdyn's universal joint, and a slide along the
 * cylinder's z whose coordinate is the leg length; six connects (platform point = the piston's
 * top). Gravity −9.81 z.
 * Knee (vt_scene_knee): hinges about z at the hip for the thigh and the crank, at the crank's tip
 * for the coupler and at the knee for the shank; one connect (the coupler's far end = the shank's
 * lever point): 3 rows, of which the z row is zero in this planar model (vtdyn closes it with its
 * planar revolute cut joint's 2 rows). Gravity −9.81 y. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mujoco_scenes.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define NLEG 6

typedef struct {
    char *s;
    size_t len, cap;
    int failed;
} mbuf;

static void X(mbuf *b, const char *fmt, ...)
{
    if (b->failed) return;
    va_list ap;
    va_start(ap, fmt);
    const int w = vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    if (w < 0 || (size_t)w >= b->cap - b->len) b->failed = 1;
    else b->len += (size_t)w;
}

/* ---- Delta ---- */
static void delta_xml(mbuf *b, int tight)
{
    const double Ia = VT_DELTA_MA * VT_DELTA_LA * VT_DELTA_LA / 12.0, Ir = VT_DELTA_MR * VT_DELTA_LF * VT_DELTA_LF / 12.0;
    X(b, "<mujoco model=\"vt_delta\">\n"
         "  <compiler angle=\"radian\" inertiafromgeom=\"false\" autolimits=\"true\"/>\n");
    X(b, "  <option gravity=\"0 0 -9.81\" timestep=\"%s\" integrator=\"Euler\" jacobian=\"dense\""
         " solver=\"Newton\" iterations=\"100\" tolerance=\"1e-14\">\n"
         "    <flag contact=\"disable\" limit=\"disable\" frictionloss=\"disable\" spring=\"disable\""
         " damper=\"disable\" sensor=\"disable\"/>\n  </option>\n",
      tight ? "1e-4" : "0.002");
    X(b, "  <default>\n    <joint type=\"hinge\" damping=\"0\" armature=\"0\" frictionloss=\"0\""
         " stiffness=\"0\" limited=\"false\"/>\n");
    if (tight) X(b, "    <equality solref=\"2e-4 1\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/>\n");
    X(b, "  </default>\n  <worldbody>\n");
    for (int i = 0; i < 3; i++) {
        const double phi = 2.0 * PI * i / 3.0;
        X(b, "    <body name=\"arm%d\" pos=\"%.17g %.17g 0\" quat=\"%.17g 0 0 %.17g\">\n", i, VT_DELTA_RB * cos(phi),
          VT_DELTA_RB * sin(phi), cos(0.5 * phi), sin(0.5 * phi));
        X(b, "      <joint name=\"m%d\" axis=\"0 1 0\"/>\n", i);
        X(b, "      <inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"1e-4 %.17g %.17g\"/>\n", 0.5 * VT_DELTA_LA,
          VT_DELTA_MA, Ia, Ia);
        for (int k = 0; k < 2; k++) {
            X(b, "      <body name=\"rod%d%d\" pos=\"%.17g %.17g 0\">\n", i, k, VT_DELTA_LA,
              k ? VT_DELTA_H : -VT_DELTA_H);
            X(b, "        <joint name=\"u%d%da\" axis=\"0 1 0\"/>\n", i, k);
            X(b, "        <joint name=\"u%d%db\" axis=\"1 0 0\"/>\n", i, k);
            X(b, "        <inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
              -0.5 * VT_DELTA_LF, VT_DELTA_MR, Ir, Ir, 0.5 * VT_DELTA_MR * 0.008 * 0.008);
            X(b, "        <site name=\"r%d%d\" pos=\"0 0 %.17g\"/>\n      </body>\n", i, k, -VT_DELTA_LF);
        }
        X(b, "    </body>\n");
    }
    X(b, "    <body name=\"platform\" pos=\"0 0 0\">\n      <freejoint name=\"free\"/>\n");
    X(b, "      <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"1e-3 1e-3 %.17g\"/>\n", VT_DELTA_MP,
      0.5 * VT_DELTA_MP * VT_DELTA_RP * VT_DELTA_RP);
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 2; k++) {
            const double phi = 2.0 * PI * i / 3.0, c = cos(phi), s = sin(phi), h = k ? VT_DELTA_H : -VT_DELTA_H;
            X(b, "      <site name=\"p%d%d\" pos=\"%.17g %.17g 0\"/>\n", i, k, VT_DELTA_RP * c - h * s,
              VT_DELTA_RP * s + h * c);
        }
    X(b, "    </body>\n  </worldbody>\n  <equality>\n");
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 2; k++) X(b, "    <connect site1=\"r%d%d\" site2=\"p%d%d\"/>\n", i, k, i, k);
    X(b, "  </equality>\n</mujoco>\n");
}

/* ---- Stewart–Gough platform ---- */
static void cylinder_diag(double J[3], double mass, double length, double radius)
{
    J[0] = J[1] = mass * (3.0 * radius * radius + length * length) / 12.0;
    J[2] = 0.5 * mass * radius * radius;
}

static void stewart_xml(mbuf *b, int drives)
{
    double Jp[3], Jc[3], Js[3];
    cylinder_diag(Jp, VT_SG_M_PLAT, 0.03, VT_SG_PLAT_R);
    cylinder_diag(Jc, VT_SG_M_CYL, 0.5, 0.04);
    cylinder_diag(Js, VT_SG_M_PIST, 0.5, 0.02);
    X(b, "<mujoco model=\"vt_stewart\">\n");
    X(b, "  <compiler angle=\"radian\" inertiafromgeom=\"false\" autolimits=\"true\"/>\n");
    X(b, "  <option gravity=\"0 0 -9.81\" timestep=\"1e-4\" integrator=\"Euler\" jacobian=\"dense\">\n");
    X(b, "    <flag contact=\"disable\" limit=\"disable\" frictionloss=\"disable\" spring=\"disable\""
         " damper=\"disable\" actuation=\"disable\" sensor=\"disable\"/>\n  </option>\n");
    X(b, "  <default>\n    <joint damping=\"0\" armature=\"0\" frictionloss=\"0\" stiffness=\"0\" limited=\"false\"/>\n");
    X(b, "    <equality solref=\"2e-4 1\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/>\n  </default>\n");
    X(b, "  <worldbody>\n");
    X(b, "    <body name=\"platform\" pos=\"0 0 %.17g\">\n      <freejoint name=\"free\"/>\n", VT_SG_HEIGHT);
    X(b, "      <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n", VT_SG_M_PLAT, Jp[0], Jp[1],
      Jp[2]);
    for (int i = 0; i < NLEG; i++) {
        double a[3], p[3];
        vt_scene_stewart_points(i, a, p);
        X(b, "      <site name=\"b%d\" pos=\"%.17g %.17g %.17g\"/>\n", i, p[0], p[1], p[2]);
    }
    X(b, "    </body>\n");
    for (int i = 0; i < NLEG; i++) {
        double a[3], p[3];
        vt_scene_stewart_points(i, a, p);
        X(b, "    <body name=\"cyl%d\" pos=\"%.17g %.17g %.17g\">\n", i, a[0], a[1], a[2]);
        X(b, "      <joint name=\"ua%d\" type=\"hinge\" axis=\"1 0 0\"/>\n", i);
        X(b, "      <joint name=\"ub%d\" type=\"hinge\" axis=\"0 1 0\"/>\n", i);
        X(b, "      <inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n", VT_SG_HALF,
          VT_SG_M_CYL, Jc[0], Jc[1], Jc[2]);
        X(b, "      <body name=\"pis%d\" pos=\"0 0 0\">\n", i);
        X(b, "        <joint name=\"p%d\" type=\"slide\" axis=\"0 0 1\"/>\n", i);
        X(b, "        <inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n", -VT_SG_HALF,
          VT_SG_M_PIST, Js[0], Js[1], Js[2]);
        X(b, "        <site name=\"top%d\" pos=\"0 0 0\"/>\n      </body>\n    </body>\n", i);
    }
    X(b, "  </worldbody>\n  <equality>\n");
    for (int i = 0; i < NLEG; i++) X(b, "    <connect site1=\"b%d\" site2=\"top%d\"/>\n", i, i);
    if (drives)
        for (int i = 0; i < NLEG; i++) X(b, "    <joint joint1=\"p%d\" polycoef=\"1 0 0 0 0\"/>\n", i);
    X(b, "  </equality>\n</mujoco>\n");
}

/* ---- knee four-bar ---- */
static void rod_diag(double J[3], double mass, double length, double radius)
{
    J[0] = 0.5 * mass * radius * radius;
    J[1] = J[2] = mass * (3.0 * radius * radius + length * length) / 12.0;
}

static void knee_xml(mbuf *b, int drives)
{
    const double ls = VT_KN_C + VT_KN_L, cs = 0.5 * ls - VT_KN_C;
    double Jt[3], Jc[3], Jp[3], Js[3];
    rod_diag(Jt, 1.5, VT_KN_D, 0.01);
    rod_diag(Jc, 0.1, VT_KN_A, 0.01);
    rod_diag(Jp, 0.08, VT_KN_B, 0.01);
    rod_diag(Js, 0.5, ls, 0.01);
    X(b, "<mujoco model=\"vt_knee\">\n");
    X(b, "  <compiler angle=\"radian\" inertiafromgeom=\"false\" autolimits=\"true\"/>\n");
    X(b, "  <option gravity=\"0 -9.81 0\" timestep=\"1e-4\" integrator=\"Euler\" jacobian=\"dense\">\n");
    X(b, "    <flag contact=\"disable\" limit=\"disable\" frictionloss=\"disable\" spring=\"disable\""
         " damper=\"disable\" actuation=\"disable\" sensor=\"disable\"/>\n  </option>\n");
    X(b, "  <default>\n    <joint type=\"hinge\" damping=\"0\" armature=\"0\" frictionloss=\"0\" stiffness=\"0\" limited=\"false\"/>\n");
    X(b, "    <equality solref=\"2e-4 1\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/>\n  </default>\n");
    X(b, "  <worldbody>\n");
    X(b, "    <body name=\"thigh\" pos=\"0 0 0\">\n      <joint name=\"hip\" axis=\"0 0 1\"/>\n");
    X(b, "      <inertial pos=\"%.17g 0 0\" mass=\"1.5\" diaginertia=\"%.17g %.17g %.17g\"/>\n", 0.5 * VT_KN_D, Jt[0], Jt[1],
      Jt[2]);
    X(b, "      <body name=\"crank\" pos=\"0 0 0\">\n        <joint name=\"motor\" axis=\"0 0 1\"/>\n");
    X(b, "        <inertial pos=\"%.17g 0 0\" mass=\"0.1\" diaginertia=\"%.17g %.17g %.17g\"/>\n", 0.5 * VT_KN_A, Jc[0],
      Jc[1], Jc[2]);
    X(b, "        <body name=\"coupler\" pos=\"%.17g 0 0\">\n", VT_KN_A);
    X(b, "          <joint name=\"cz\" axis=\"0 0 1\"/>\n");
    X(b, "          <inertial pos=\"%.17g 0 0\" mass=\"0.08\" diaginertia=\"%.17g %.17g %.17g\"/>\n", 0.5 * VT_KN_B,
      Jp[0], Jp[1], Jp[2]);
    X(b, "          <site name=\"cend\" pos=\"%.17g 0 0\"/>\n        </body>\n      </body>\n", VT_KN_B);
    X(b, "      <body name=\"shank\" pos=\"%.17g 0 0\">\n        <joint name=\"knee\" axis=\"0 0 1\"/>\n", VT_KN_D);
    X(b, "        <inertial pos=\"%.17g 0 0\" mass=\"0.5\" diaginertia=\"%.17g %.17g %.17g\"/>\n", cs, Js[0], Js[1],
      Js[2]);
    X(b, "        <site name=\"lever\" pos=\"%.17g 0 0\"/>\n      </body>\n    </body>\n", -VT_KN_C);
    X(b, "  </worldbody>\n  <equality>\n");
    X(b, "    <connect site1=\"cend\" site2=\"lever\"/>\n");
    if (drives) X(b, "    <joint joint1=\"hip\" polycoef=\"0 0 0 0 0\"/>\n    <joint joint1=\"motor\" polycoef=\"0 0 0 0 0\"/>\n");
    X(b, "  </equality>\n</mujoco>\n");
}

mjModel *vt_mj_scene_model(int machine, int flags)
{
    mbuf b = {NULL, 0, 1 << 15, 0};
    b.s = malloc(b.cap);
    if (!b.s) return NULL;
    b.s[0] = '\0';
    if (machine == VT_MJ_DELTA) delta_xml(&b, !(flags & VT_MJ_DEFAULT_SOFT));
    else if (machine == VT_MJ_STEWART) stewart_xml(&b, flags & VT_MJ_DRIVE_EQUALITIES);
    else if (machine == VT_MJ_KNEE) knee_xml(&b, flags & VT_MJ_DRIVE_EQUALITIES);
    else b.failed = 1;
    mjModel *m = NULL;
    if (b.failed) {
        fprintf(stderr, "vt_mj_scene_model: no model %d, or its MJCF beyond %zu bytes\n", machine, b.cap);
    } else {
        char err[1024] = "";
        mjSpec *spec = mj_parseXMLString(b.s, NULL, err, (int)sizeof err);
        if (!spec) fprintf(stderr, "vt_mj_scene_model: %s\n", err);
        m = spec ? mj_compile(spec, NULL) : NULL;
        if (spec && !m) fprintf(stderr, "vt_mj_scene_model: %s\n", mjs_getError(spec));
        if (spec) mj_deleteSpec(spec);
    }
    free(b.s);
    return m;
}

/* vtdyn's body b on MuJoCo's joint j (its first): coordinates and rates from vtdyn's next ones */
static void map_body(const mjModel *m, vt_mj_map *map, int b, int j, int *iq, int *iv)
{
    const int body = m->jnt_bodyid[j];
    int nq = 0, nv = 0;
    for (int k = j; k < m->njnt && m->jnt_bodyid[k] == body; k++) {
        const int t = m->jnt_type[k], cq = t == mjJNT_FREE ? 7 : t == mjJNT_BALL ? 4 : 1;
        const int cv = t == mjJNT_FREE ? 6 : t == mjJNT_BALL ? 3 : 1;
        for (int c = 0; c < cq; c++) map->qadr[*iq + nq + c] = m->jnt_qposadr[k] + c;
        for (int c = 0; c < cv; c++) map->vadr[*iv + nv + c] = m->jnt_dofadr[k] + c;
        nq += cq;
        nv += cv;
    }
    map->body[b] = body;
    map->free[b] = m->jnt_type[j] == mjJNT_FREE;
    map->bvadr[b] = *iv;
    *iq += nq;
    *iv += nv;
}

int vt_mj_scene_map(int machine, const mjModel *m, vt_mj_map *map)
{
    memset(map, 0, sizeof *map);
    int iq = 0, iv = 0;
    if (machine == VT_MJ_DELTA) { /* vtdyn: arms 1..3, rods (i, k) 4 + 2i + k, platform 10 */
        char name[16];
        map->nbody = 10;
        for (int b = 1; b <= 10; b++) {
            if (b <= 3) snprintf(name, sizeof name, "m%d", b - 1);
            else if (b <= 9) snprintf(name, sizeof name, "u%d%da", (b - 4) / 2, (b - 4) % 2);
            else snprintf(name, sizeof name, "free");
            const int j = mj_name2id(m, mjOBJ_JOINT, name);
            if (j < 0) return -1;
            map_body(m, map, b, j, &iq, &iv);
        }
    } else if (machine == VT_MJ_STEWART || machine == VT_MJ_KNEE) { /* MuJoCo's bodies are vtdyn's */
        map->nbody = m->nbody - 1;
        if (map->nbody >= VT_MJ_MAXB) return -1;
        for (int b = 1; b <= map->nbody; b++) {
            if (m->body_jntnum[b] < 1) return -1;
            map_body(m, map, b, m->body_jntadr[b], &iq, &iv);
        }
    } else {
        return -1;
    }
    map->nq = iq;
    map->nv = iv;
    return iq == m->nq && iv == m->nv ? 0 : -1;
}

void vt_mj_scene_state(const mjModel *m, const vt_mj_map *map, mjData *d, const double *q, const double *qd,
                       const double *qdd)
{
    for (int k = 0; k < map->nq; k++) d->qpos[map->qadr[k]] = q[k];
    for (int k = 0; k < map->nv; k++) {
        d->qvel[map->vadr[k]] = qd[k];
        if (qdd) d->qacc[map->vadr[k]] = qdd[k];
    }
    for (int b = 1; b <= map->nbody; b++) {
        if (!map->free[b]) continue;
        /* the angular part (rates 3..5 of the body): A(p)ᵀ ω, MuJoCo's quaternion is vtdyn's p */
        const int v = map->bvadr[b] + 3, a = map->vadr[v];
        mjtNum R[9], p[4];
        for (int c = 0; c < 4; c++) p[c] = d->qpos[m->jnt_qposadr[m->body_jntadr[map->body[b]]] + 3 + c];
        mju_normalize4(p);
        mju_quat2Mat(R, p); /* row-major, body to world */
        for (int c = 0; c < 3; c++) {
            d->qvel[a + c] = R[c] * qd[v] + R[3 + c] * qd[v + 1] + R[6 + c] * qd[v + 2];
            if (qdd) d->qacc[a + c] = R[c] * qdd[v] + R[3 + c] * qdd[v + 1] + R[6 + c] * qdd[v + 2];
        }
    }
}
