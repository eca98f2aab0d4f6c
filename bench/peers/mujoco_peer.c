/* MuJoCo peer (C API). Scenes: chain, double link (joint 2 locked by a joint equality),
 * four-bar (loop closed by a connect equality), the spatial RUSR four-bar (two hinges on the
 * coupler, loop closed by a connect equality), chain tip (the chain model, driven only by a
 * force at the tip), and the Delta robot, the Stewart platform and the knee four-bar
 * (mujoco_scenes.c: each loop a connect equality, the motors' dofs free).
 *
 * Methods
 *   chain
 *     0 mujoco_inverse       qpos, qvel, qacc set; mj_inverse; mj_rnePostConstraint;
 *                            torques = qfrc_inverse
 *     1 mujoco_rne_post      mj_kinematics, mj_comPos, mj_comVel, mj_rne(flg_acc = 1) into a
 *                            preallocated vector (= torques), then mj_rnePostConstraint
 *     2 mujoco_post_project  mj_kinematics, mj_comPos, mj_comVel, mj_rnePostConstraint; torques
 *                            = projection of cfrc_int on each dof's axis (cdof . cfrc_int), the
 *                            leanest MuJoCo path to both torques and reactions
 *   double link: 0 mujoco_inverse (as above)
 *   four-bar
 *     0 mujoco_inverse       as above: with a consistent state the loop force is 0 and all three
 *                            hinges carry torque (the open tree's torques)
 *     1 mujoco_inverse_loop  mj_inverse, then the connect force lambda that makes the coupler and
 *                            rocker hinge torques zero (crank-only actuation) is solved from the
 *                            2x2 in-plane system, written into efc_force, qfrc_inverse -= J^T lambda,
 *                            then mj_rnePostConstraint (reactions see the loop force via cfrc_ext)
 *   RUSR four-bar
 *     0 mujoco_inverse_loop  mj_inverse, then the connect force lambda (all 3 rows) that makes the
 *                            torques of dofs 1, 2, 3 (coupler about z, coupler tilt, rocker) zero,
 *                            from the 3x3 system J[:, 1:4]^T lambda = (M qacc + bias)[1:4]; the
 *                            rest as for the four-bar: tau = M qacc + bias - J^T lambda,
 *                            efc_force = lambda, then mj_rnePostConstraint
 *   Delta, Stewart, knee
 *     0 mujoco_inverse_loop  as for the four-bars: mj_inverse, then the connects' force lambda
 *                            that leaves only the motors' dofs actuated (Delta: the 3 arm hinges;
 *                            Stewart: the 6 slides; knee: the hip and the motor hinges), from
 *                            J[rows, F]^T lambda = (M qacc + bias)[F], F the other dofs (Delta 18,
 *                            Stewart 18, knee 2), rows every connect row (Delta, Stewart: 18) or
 *                            the knee's x and y (its z row is zero); then tau, efc_force and
 *                            mj_rnePostConstraint as above. The loop forces of every four-bar and
 *                            machine come from one k x k solve (Gaussian elimination, partial
 *                            pivoting; k = 2, 3, 18, 18, 2)
 *   chain tip
 *     0 mujoco_inverse_tip   mj_inverse (qfrc_inverse = M qacc + bias, no constraint), then the
 *                            tip force F along global y that produces all of it: least squares
 *                            F = J_y . qfrc_inverse / J_y . J_y, J_y the y row of mj_jac at the
 *                            tip; the residual qfrc_inverse - J_y^T F (round-off when qacc is
 *                            vtdyn's solution) are the torques, F the extra value; F goes into
 *                            xfrc_applied of the last body (force and its moment about the body's
 *                            COM), which mj_rnePostConstraint includes in cfrc_ext, so the
 *                            reactions carry it; mj_inverse does not read xfrc_applied. This
 *                            is handed qacc, vtdyn's solution: the free motion is not solved
 *     1 mujoco_solve_tip     the same problem as vtdyn's: given only the tip's y acceleration a
 *                            (the drive's, computed once from the given state), solve the free
 *                            motion exactly with MuJoCo's own factorization of M:
 *                            mj_fwdPosition (kinematics, M, its L'DL factor), mj_fwdVelocity
 *                            (qfrc_bias), mj_jac and mj_jacDot at the tip, mj_solveM for
 *                            x = M^-1 (-bias) and y = M^-1 J_y^T, then
 *                            F = (a - Jdot_y qvel - J_y x) / (J_y y), qacc = x + y F; F into
 *                            xfrc_applied as above, then mj_rnePostConstraint
 *
 * Reactions: mjData.cfrc_int[b] (after mj_rnePostConstraint) is the wrench the parent exerts on
 * body b through its joint, "com-based": 6 numbers [moment(3); force(3)], world axes, the moment
 * taken about subtree_com of b's root body (the body of b's tree that hangs from the world), not
 * about b's own COM. reaction() converts: f = force, n_joint = moment + (c - p) x f with c that
 * subtree COM and p the joint anchor (xanchor). The actuator/joint torque is inside n (the
 * projection of cfrc_int on the joint axis is the whole joint-space force).
 *
 * Model options: no geoms (no contacts), contact/limit/frictionloss/spring/damper/actuation/
 * sensor disabled, zero damping, armature, friction; gravity (0, -9.81, 0); the chain also has
 * the constraint solver disabled. Equality constraints: timestep 1e-4, solref = "2e-4 1"
 * (time constant 2 * timestep, the smallest refsafe allows, critical damping), solimp =
 * "0.9999 0.9999 0.001 0.5 2" (impedance at mjMAXIMP everywhere).
 *
 * Forward simulation (vt_peer_mujoco_simulate, the work-precision benchmark): the same model and
 * constraint settings, with opt.timestep = dt and opt.integrator = Euler (MuJoCo's default,
 * semi-implicit) or RK4 for the run. solref's time constant 2e-4 is kept: for dt > 1e-4 refsafe
 * raises it to 2 dt, so the lock gets softer as the step grows (MuJoCo's own behaviour). Each
 * step is mj_step; on the output rows it is split into its parts, mj_forward, then (for the
 * reactions at that state) mj_rnePostConstraint, then mj_Euler or mj_RungeKutta(m, d, 4): what
 * mj_step does, without its mj_check* tests, so no dynamics is evaluated twice.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mujoco/mujoco.h>

#include "mujoco_scenes.h"
#include "peer_impl.h"

/* the loop-force solve: at most this many unknowns (the Delta's and the Stewart platform's 18) */
enum { LOOP_MAX = 18 };

typedef struct {
    mjModel *m;
    mjData *d;
    int scene, n;            /* n = nv = number of hinges = links (the RUSR four-bar: 4 hinges, 3 links;
                              * Delta, Stewart, knee: vtdyn's rates) */
    mjtNum *q, *qd, *qdd;    /* the state in MuJoCo's qpos, qvel, qacc, copied into mjData by every run */
    mjtNum *tau;             /* torques of the last run (chain tip: n + 1, the tip force last) */
    mjtNum *jac;             /* chain tip: mj_jac's translation rows (3 x n) */
    mjtNum *jacd;            /* chain tip: mj_jacDot's translation rows (3 x n) */
    mjtNum *rhs, *xy;        /* chain tip, solved: right sides and solutions of M x = y (2 x n each) */
    mjtNum ades;             /* chain tip: the tip's y acceleration that the drive prescribes */
    const int *body;         /* body of link k (k = 1..n) is body[k - 1]; joint of link k is k - 1 */
    int bodyids[3];
    /* the loop scenes: the dofs whose force the loop force cancels (nloop of them) and the efc
     * rows that carry it, in the same number */
    int nloop, loopdof[LOOP_MAX], looprow[LOOP_MAX];
    vt_mj_map map;           /* Delta, Stewart, knee: vtdyn's layout in MuJoCo's model */
} mj_peer;

static const char *const chain_methods[] = {"mujoco_inverse", "mujoco_rne_post", "mujoco_post_project"};
static const char *const dl_methods[] = {"mujoco_inverse"};
static const char *const fb_methods[] = {"mujoco_inverse", "mujoco_inverse_loop"};
static const char *const rusr_methods[] = {"mujoco_inverse_loop"};
static const char *const machine_methods[] = {"mujoco_inverse_loop"};
static const char *const tip_methods[] = {"mujoco_inverse_tip", "mujoco_solve_tip"};

/* ---- XML text ---- */
typedef struct {
    char *s;
    size_t len, cap;
    int failed;
} xbuf;

static void xcat(xbuf *b, const char *fmt, ...)
{
    if (b->failed) return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        const int w = vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
        va_end(ap);
        if (w < 0) { b->failed = 1; return; }
        if ((size_t)w < b->cap - b->len) { b->len += (size_t)w; return; }
        const size_t cap = 2 * b->cap + (size_t)w + 1;
        char *s = realloc(b->s, cap);
        if (!s) { b->failed = 1; return; }
        b->s = s;
        b->cap = cap;
    }
}

static void xml_header(xbuf *b, const char *name, int constrained)
{
    xcat(b, "<mujoco model=\"%s\">\n", name);
    xcat(b, "  <compiler angle=\"radian\" inertiafromgeom=\"false\" autolimits=\"true\"/>\n");
    xcat(b, "  <option gravity=\"0 -9.81 0\" timestep=\"1e-4\" integrator=\"Euler\" jacobian=\"dense\">\n");
    xcat(b, "    <flag contact=\"disable\" limit=\"disable\" frictionloss=\"disable\" spring=\"disable\""
            " damper=\"disable\" actuation=\"disable\" sensor=\"disable\"%s/>\n",
         constrained ? "" : " constraint=\"disable\"");
    xcat(b, "  </option>\n");
    xcat(b, "  <default>\n");
    xcat(b, "    <joint type=\"hinge\" damping=\"0\" armature=\"0\" frictionloss=\"0\" stiffness=\"0\" limited=\"false\"/>\n");
    xcat(b, "    <equality solref=\"2e-4 1\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/>\n");
    xcat(b, "  </default>\n");
}

/* chain: body k's frame is at joint k, aligned with the world at q = 0. The bodies are added
 * to the parsed header's spec (mjs_addBody), not nested in the XML: MuJoCo's XML parser refuses
 * elements nested deeper than 500 (a 500-link chain) */
static void xml_chain(xbuf *b)
{
    xml_header(b, "vt_chain", 0);
    xcat(b, "  <worldbody/>\n</mujoco>\n");
}

static int spec_chain(mjSpec *spec, int n)
{
    mjsBody *parent = mjs_findBody(spec, "world");
    for (int k = 1; k <= n && parent; k++) {
        char name[32];
        mjsBody *body = mjs_addBody(parent, NULL);
        if (!body) return -1;
        snprintf(name, sizeof name, "b%d", k);
        mjs_setName(body->element, name);
        body->pos[0] = k > 1 ? 0.5 : 0.0;
        body->mass = 1.0;
        body->ipos[0] = 0.25;
        body->inertia[0] = 2e-4;
        body->inertia[1] = body->inertia[2] = 1.0 / 48.0;
        body->explicitinertial = 1;
        mjsJoint *joint = mjs_addJoint(body, NULL);
        if (!joint) return -1;
        snprintf(name, sizeof name, "j%d", k);
        mjs_setName(joint->element, name);
        joint->type = mjJNT_HINGE;
        joint->axis[0] = joint->axis[1] = joint->axis[2] = 0.0;
        joint->axis[(k - 1) % 3] = 1.0;
        parent = body;
    }
    return parent ? 0 : -1;
}

/* double link: 2 m, 100 kg uniform rods along x; axial inertia 1e-6 (MuJoCo needs a positive one) */
static void xml_double_link(xbuf *b)
{
    const double J = 100.0 * 4.0 / 12.0;
    xml_header(b, "vt_double_link", 1);
    xcat(b, "  <worldbody>\n");
    xcat(b, "<body name=\"b1\" pos=\"0 0 0\">\n<joint name=\"j1\" axis=\"0 0 1\"/>\n");
    xcat(b, "<inertial pos=\"1 0 0\" mass=\"100\" diaginertia=\"1e-6 %.17g %.17g\"/>\n", J, J);
    xcat(b, "<body name=\"b2\" pos=\"2 0 0\">\n<joint name=\"j2\" axis=\"0 0 1\"/>\n");
    xcat(b, "<inertial pos=\"1 0 0\" mass=\"100\" diaginertia=\"1e-6 %.17g %.17g\"/>\n", J, J);
    xcat(b, "</body>\n</body>\n  </worldbody>\n");
    xcat(b, "  <equality>\n    <joint joint1=\"j2\" polycoef=\"0 0 0 0 0\"/>\n  </equality>\n</mujoco>\n");
}

/* four-bar: crank (0.5 m, 1 kg) at the origin, coupler (1.5 m, 3 kg) at the crank's tip, rocker
 * (1.0 m, 2 kg) at (1.2, 0, 0); uniform rods along their x, hinges about z. Loop: coupler tip =
 * rocker tip (connect: 3 rows). Planar (rusr = 0): q = (crank angle, coupler angle relative to
 * the crank, rocker angle). RUSR (rusr = 1): the coupler carries two hinges at the crank's tip, z
 * and then y. MuJoCo applies a body's joints in order, each about its axis in the body's frame as
 * turned by the joints before it: the coupler's orientation relative to the crank is
 * R(z, q1) R(y, q2), the y axis turned by the first angle, as vtdyn's universal joint (first axis
 * on the crank, second on the coupler); q = (crank angle, coupler angle about z relative to the
 * crank, coupler tilt about its y, rocker angle). */
static void xml_fourbar(xbuf *b, int rusr)
{
    static const double len[3] = {0.5, 1.5, 1.0}, mass[3] = {1.0, 3.0, 2.0};
    double J[3];
    for (int k = 0; k < 3; k++) J[k] = mass[k] * len[k] * len[k] / 12.0;
    xml_header(b, rusr ? "vt_fourbar_rusr" : "vt_fourbar", 1);
    xcat(b, "  <worldbody>\n");
    xcat(b, "<body name=\"crank\" pos=\"0 0 0\">\n<joint name=\"j1\" axis=\"0 0 1\"/>\n");
    xcat(b, "<inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"1e-6 %.17g %.17g\"/>\n",
         0.5 * len[0], mass[0], J[0], J[0]);
    xcat(b, "<body name=\"coupler\" pos=\"%.17g 0 0\">\n<joint name=\"j2\" axis=\"0 0 1\"/>\n", len[0]);
    if (rusr) xcat(b, "<joint name=\"j2y\" axis=\"0 1 0\"/>\n");
    xcat(b, "<inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"1e-6 %.17g %.17g\"/>\n",
         0.5 * len[1], mass[1], J[1], J[1]);
    xcat(b, "<site name=\"coupler_tip\" pos=\"%.17g 0 0\"/>\n", len[1]);
    xcat(b, "</body>\n</body>\n");
    xcat(b, "<body name=\"rocker\" pos=\"1.2 0 0\">\n<joint name=\"j3\" axis=\"0 0 1\"/>\n");
    xcat(b, "<inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"1e-6 %.17g %.17g\"/>\n",
         0.5 * len[2], mass[2], J[2], J[2]);
    xcat(b, "<site name=\"rocker_tip\" pos=\"%.17g 0 0\"/>\n", len[2]);
    xcat(b, "</body>\n  </worldbody>\n");
    /* sites, not body1 + anchor: the loop is open at q = 0, where MuJoCo would take body2's point */
    xcat(b, "  <equality>\n    <connect site1=\"coupler_tip\" site2=\"rocker_tip\"/>\n"
            "  </equality>\n</mujoco>\n");
}

/* ---- evaluation ---- */
static void set_state(mj_peer *s)
{
    const size_t nv = (size_t)s->m->nv * sizeof(mjtNum);
    memcpy(s->d->qpos, s->q, (size_t)s->m->nq * sizeof(mjtNum));
    memcpy(s->d->qvel, s->qd, nv);
    memcpy(s->d->qacc, s->qdd, nv);
}

static void run_inverse(mj_peer *s)
{
    set_state(s);
    mj_inverse(s->m, s->d);
    mj_rnePostConstraint(s->m, s->d);
    memcpy(s->tau, s->d->qfrc_inverse, (size_t)s->n * sizeof(mjtNum));
}

static void run_rne_post(mj_peer *s)
{
    set_state(s);
    mj_kinematics(s->m, s->d);
    mj_comPos(s->m, s->d);
    mj_comVel(s->m, s->d);
    mj_rne(s->m, s->d, 1, s->tau);
    mj_rnePostConstraint(s->m, s->d);
}

static void run_post_project(mj_peer *s)
{
    const mjModel *m = s->m;
    mjData *d = s->d;
    set_state(s);
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_comVel(m, d);
    mj_rnePostConstraint(m, d);
    for (int i = 0; i < m->nv; i++) {
        const mjtNum *c = d->cdof + 6 * i, *f = d->cfrc_int + 6 * m->dof_bodyid[i];
        s->tau[i] = c[0] * f[0] + c[1] * f[1] + c[2] * f[2] + c[3] * f[3] + c[4] * f[4] + c[5] * f[5];
    }
}

/* Solves A x = b in place (b becomes x) for the k x k matrix A, by Gaussian elimination with
 * partial pivoting; a zero pivot leaves the x it meets infinite or NaN (the check against
 * vtdyn's torques then refuses the row). */
static void solve_small(int k, mjtNum A[][LOOP_MAX], mjtNum *b)
{
    for (int c = 0; c < k; c++) {
        int p = c;
        for (int r = c + 1; r < k; r++)
            if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
        if (p != c) {
            for (int j = c; j < k; j++) {
                const mjtNum t = A[c][j];
                A[c][j] = A[p][j];
                A[p][j] = t;
            }
            const mjtNum t = b[c];
            b[c] = b[p];
            b[p] = t;
        }
        for (int r = c + 1; r < k; r++) {
            const mjtNum f = A[r][c] / A[c][c];
            for (int j = c + 1; j < k; j++) A[r][j] -= f * A[c][j];
            b[r] -= f * b[c];
        }
    }
    for (int c = k - 1; c >= 0; c--) {
        mjtNum x = b[c];
        for (int j = c + 1; j < k; j++) x -= A[c][j] * b[j];
        b[c] = x / A[c][c];
    }
}

/* The loops with only the motors acting. After mj_inverse (efc_force = 0 for a consistent
 * state), M qacc + bias = qfrc_inverse + qfrc_constraint; the connects' force lambda on the
 * efc rows looprow[] leaves the dofs loopdof[] unactuated: (M qacc + bias − J^T lambda)[dof] = 0,
 * the k x k system A lambda = r, A[i][j] = J[looprow[j]][loopdof[i]], r_i = (M qacc +
 * bias)[loopdof[i]]. lambda goes into efc_force (the other rows 0), J^T lambda into
 * qfrc_constraint, the rest into qfrc_inverse and tau; then the reactions. */
static void run_inverse_loop(mj_peer *s)
{
    const mjModel *m = s->m;
    mjData *d = s->d;
    const int nv = m->nv, k = s->nloop;
    set_state(s);
    mj_inverse(m, d);
    if (d->nefc < k) { /* the connect rows are missing: leave the plain mj_inverse result */
        mj_rnePostConstraint(m, d);
        memcpy(s->tau, d->qfrc_inverse, (size_t)nv * sizeof(mjtNum));
        return;
    }
    const mjtNum *J = d->efc_J; /* dense (option jacobian="dense"): nefc x nv */
    mjtNum A[LOOP_MAX][LOOP_MAX], l[LOOP_MAX];
    for (int i = 0; i < k; i++) {
        const int dof = s->loopdof[i];
        for (int j = 0; j < k; j++) A[i][j] = J[s->looprow[j] * nv + dof];
        l[i] = d->qfrc_inverse[dof] + d->qfrc_constraint[dof];
    }
    solve_small(k, A, l);
    for (int e = 0; e < d->nefc; e++) d->efc_force[e] = 0.0;
    for (int j = 0; j < k; j++) d->efc_force[s->looprow[j]] = l[j];
    for (int i = 0; i < nv; i++) {
        mjtNum qc = 0.0;
        for (int j = 0; j < k; j++) qc += J[s->looprow[j] * nv + i] * l[j];
        s->tau[i] = d->qfrc_inverse[i] + d->qfrc_constraint[i] - qc;
        d->qfrc_constraint[i] = qc;
        d->qfrc_inverse[i] = s->tau[i];
    }
    mj_rnePostConstraint(m, d);
}

/* chain tip: the tip of the last link, 0.5 m along its x from its joint (the body's origin) */
static void tip_point(const mj_peer *s, mjtNum tip[3])
{
    const int b = s->body[s->n - 1];
    const mjtNum *o = s->d->xpos + 3 * b, *R = s->d->xmat + 9 * b;
    tip[0] = o[0] + 0.5 * R[0];
    tip[1] = o[1] + 0.5 * R[3];
    tip[2] = o[2] + 0.5 * R[6];
}

/* the force (0, F, 0) at the tip into xfrc_applied of the last body: the force at its COM and
 * its moment (tip - COM) x (0, F, 0); then the reactions */
static void tip_force_post(mj_peer *s, const mjtNum tip[3], mjtNum F)
{
    const int b = s->body[s->n - 1];
    mjtNum *x = s->d->xfrc_applied + 6 * b;
    const mjtNum *c = s->d->xipos + 3 * b;
    x[0] = 0.0;
    x[1] = F;
    x[2] = 0.0;
    x[3] = -(tip[2] - c[2]) * F;
    x[4] = 0.0;
    x[5] = (tip[0] - c[0]) * F;
    s->tau[s->n] = F;
    mj_rnePostConstraint(s->m, s->d);
}

/* chain tip: the force F along global y at the tip that, alone, produces qfrc_inverse = M qacc +
 * bias (qacc given) */
static void run_inverse_tip(mj_peer *s)
{
    const mjModel *m = s->m;
    mjData *d = s->d;
    const int nv = m->nv;
    set_state(s);
    mj_inverse(m, d);
    mjtNum tip[3];
    tip_point(s, tip);
    mj_jac(m, d, s->jac, NULL, tip, s->body[nv - 1]);
    const mjtNum *Jy = s->jac + nv;
    mjtNum jj = 0.0, jf = 0.0;
    for (int i = 0; i < nv; i++) {
        jj += Jy[i] * Jy[i];
        jf += Jy[i] * d->qfrc_inverse[i];
    }
    tip_force_post(s, tip, jf / jj);
}

/* chain tip: MuJoCo's forward pipeline up to the accelerations (kinematics, M and its factor,
 * qfrc_bias), then the tip, its Jacobian and the Jacobian's derivative */
static void tip_forward(mj_peer *s, mjtNum tip[3])
{
    const mjModel *m = s->m;
    mjData *d = s->d;
    set_state(s);
    mj_fwdPosition(m, d);
    mj_fwdVelocity(m, d);
    tip_point(s, tip);
    mj_jac(m, d, s->jac, NULL, tip, s->body[m->nv - 1]);
    mj_jacDot(m, d, s->jacd, NULL, tip, s->body[m->nv - 1]);
}

/* chain tip, solved: qacc from the tip's y acceleration s->ades (the method is said at the top) */
static void run_solve_tip(mj_peer *s)
{
    const mjModel *m = s->m;
    mjData *d = s->d;
    const int nv = m->nv;
    mjtNum tip[3];
    tip_forward(s, tip);
    const mjtNum *Jy = s->jac + nv, *Jdy = s->jacd + nv;
    for (int i = 0; i < nv; i++) {
        s->rhs[i] = -d->qfrc_bias[i];
        s->rhs[nv + i] = Jy[i];
    }
    mj_solveM(m, d, s->xy, s->rhs, 2);
    const mjtNum *x = s->xy, *y = s->xy + nv;
    mjtNum r = s->ades, jy = 0.0;
    for (int i = 0; i < nv; i++) {
        r -= Jdy[i] * d->qvel[i] + Jy[i] * x[i];
        jy += Jy[i] * y[i];
    }
    const mjtNum F = r / jy;
    for (int i = 0; i < nv; i++) d->qacc[i] = x[i] + y[i] * F;
    tip_force_post(s, tip, F);
}

/* chain tip: the drive's acceleration at the given state, J_y qacc + Jdot_y qvel (once, at setup) */
static mjtNum tip_acceleration(mj_peer *s)
{
    const int nv = s->m->nv;
    mjtNum tip[3], a = 0.0;
    tip_forward(s, tip);
    for (int i = 0; i < nv; i++) a += s->jac[nv + i] * s->qdd[i] + s->jacd[nv + i] * s->qd[i];
    return a;
}

/* ---- vtable ---- */
static void mjp_run(void *p, int method)
{
    mj_peer *s = p;
    if (s->scene == VT_PEER_CHAIN) {
        if (method == 0) run_inverse(s);
        else if (method == 1) run_rne_post(s);
        else run_post_project(s);
    } else if ((s->scene == VT_PEER_FOURBAR && method == 1) || s->scene == VT_PEER_FOURBAR_RUSR || s->map.nv > 0) {
        run_inverse_loop(s);
    } else if (s->scene == VT_PEER_CHAIN_TIP) {
        if (method == 0) run_inverse_tip(s);
        else run_solve_tip(s);
    } else {
        run_inverse(s);
    }
}

static void mjp_torques(const void *p, double *tau)
{
    const mj_peer *s = p;
    if (s->scene == VT_PEER_CHAIN_TIP) { /* no joint is actuated: what is left, M qacc + bias − J_y^T F */
        const int nv = s->n;
        mj_mulM(s->m, s->d, tau, s->d->qacc);
        for (int i = 0; i < nv; i++) tau[i] += s->d->qfrc_bias[i] - s->jac[nv + i] * s->tau[nv];
        tau[nv] = s->tau[nv];
        return;
    }
    if (s->map.nv > 0) { /* vtdyn's rates; a free joint's moment from the body's axes to the world's */
        const vt_mj_map *mp = &s->map;
        for (int k = 0; k < mp->nv; k++) tau[k] = s->tau[mp->vadr[k]];
        for (int b = 1; b <= mp->nbody; b++) {
            if (!mp->free[b]) continue;
            const mjtNum *R = s->d->xmat + 9 * mp->body[b], *t = s->tau + mp->vadr[mp->bvadr[b] + 3];
            for (int c = 0; c < 3; c++)
                tau[mp->bvadr[b] + 3 + c] = R[3 * c] * t[0] + R[3 * c + 1] * t[1] + R[3 * c + 2] * t[2];
        }
        return;
    }
    for (int i = 0; i < s->n; i++) tau[i] = s->tau[i];
}

static void mjp_reaction(const void *p, int k, double f[3], double n[3])
{
    const mj_peer *s = p;
    const mjModel *m = s->m;
    const mjData *d = s->d;
    const int b = s->body[k - 1], j = m->body_jntadr[b];
    const mjtNum *w = d->cfrc_int + 6 * b;
    const mjtNum *c = d->subtree_com + 3 * m->body_rootid[b], *o = d->xanchor + 3 * j;
    const mjtNum r[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    f[0] = w[3];
    f[1] = w[4];
    f[2] = w[5];
    n[0] = w[0] + r[1] * f[2] - r[2] * f[1];
    n[1] = w[1] + r[2] * f[0] - r[0] * f[2];
    n[2] = w[2] + r[0] * f[1] - r[1] * f[0];
}

static void mjp_destroy(void *p)
{
    mj_peer *s = p;
    if (!s) return;
    if (s->d) mj_deleteData(s->d);
    if (s->m) mj_deleteModel(s->m);
    free(s->q);
    free(s);
}

static const vt_peer_vtable chain_vtable = {3, chain_methods, mjp_run, mjp_torques, mjp_reaction, mjp_destroy};
static const vt_peer_vtable dl_vtable = {1, dl_methods, mjp_run, mjp_torques, mjp_reaction, mjp_destroy};
static const vt_peer_vtable fb_vtable = {2, fb_methods, mjp_run, mjp_torques, mjp_reaction, mjp_destroy};
static const vt_peer_vtable rusr_vtable = {1, rusr_methods, mjp_run, mjp_torques, mjp_reaction, mjp_destroy};
static const vt_peer_vtable tip_vtable = {2, tip_methods, mjp_run, mjp_torques, mjp_reaction, mjp_destroy};
static const vt_peer_vtable machine_vtable = {1, machine_methods, mjp_run, mjp_torques, mjp_reaction, mjp_destroy};

/* the model of xml; chain > 0: that many chain links added to its worldbody first */
static mjModel *compile_xml(const char *xml, int chain)
{
    char err[1024] = "";
    mjSpec *spec = mj_parseXMLString(xml, NULL, err, (int)sizeof err);
    if (!spec) {
        fprintf(stderr, "vt_peer_mujoco: %s\n", err);
        return NULL;
    }
    mjModel *m = chain > 0 && spec_chain(spec, chain) ? NULL : mj_compile(spec, NULL);
    if (!m) fprintf(stderr, "vt_peer_mujoco: %s\n", mjs_getError(spec));
    mj_deleteSpec(spec);
    return m;
}

/* the scene's model (n = links of the chain), NULL on failure */
static mjModel *scene_model(int scene, int n)
{
    xbuf b = {NULL, 0, 0, 0};
    b.s = malloc(b.cap = 4096);
    if (!b.s) return NULL;
    b.s[0] = '\0';
    const int chain = scene == VT_PEER_CHAIN || scene == VT_PEER_CHAIN_TIP;
    if (chain) xml_chain(&b);
    else if (scene == VT_PEER_DOUBLE_LINK) xml_double_link(&b);
    else if (scene == VT_PEER_FOURBAR_RUSR) xml_fourbar(&b, 1);
    else xml_fourbar(&b, 0);
    mjModel *m = b.failed ? NULL : compile_xml(b.s, chain ? n : 0);
    free(b.s);
    return m;
}

/* the Delta, the Stewart platform and the knee (mujoco_scenes.c): the state in vtdyn's layout */
static vt_peer *machine_peer(int scene, const double *q, const double *qd, const double *qdd)
{
    const int machine = scene == VT_PEER_DELTA ? VT_MJ_DELTA : scene == VT_PEER_STEWART ? VT_MJ_STEWART : VT_MJ_KNEE;
    mjModel *m = vt_mj_scene_model(machine, 0);
    if (!m) return NULL;
    vt_peer *p = malloc(sizeof *p);
    mj_peer *s = calloc(1, sizeof *s);
    if (s) {
        s->m = m;
        s->q = malloc(((size_t)m->nq + 3 * (size_t)m->nv) * sizeof(mjtNum));
        s->d = mj_makeData(m);
    }
    if (!p || !s || !s->q || !s->d || vt_mj_scene_map(machine, m, &s->map)) {
        if (s) mjp_destroy(s);
        else mj_deleteModel(m);
        free(p);
        return NULL;
    }
    const int nv = m->nv;
    s->scene = scene;
    s->n = nv;
    s->qd = s->q + m->nq;
    s->qdd = s->qd + nv;
    s->tau = s->qdd + nv;
    /* the state once in MuJoCo's coordinates, which every run copies */
    vt_mj_scene_state(m, &s->map, s->d, q, qd, qdd);
    memcpy(s->q, s->d->qpos, (size_t)m->nq * sizeof(mjtNum));
    memcpy(s->qd, s->d->qvel, (size_t)nv * sizeof(mjtNum));
    memcpy(s->qdd, s->d->qacc, (size_t)nv * sizeof(mjtNum));
    /* the motors' dofs (vtdyn's bodies: the Delta's arms 1..3, the Stewart's pistons 3 + 2i, the
     * knee's thigh and crank); every other dof is the loop force's */
    int motor[VT_MJ_MAXQ] = {0};
    for (int i = 0; i < 6; i++) {
        const int b = scene == VT_PEER_STEWART ? 3 + 2 * i : i < (scene == VT_PEER_DELTA ? 3 : 2) ? 1 + i : 0;
        if (b > 0) motor[s->map.vadr[s->map.bvadr[b]]] = 1;
    }
    for (int i = 0; i < nv; i++)
        if (!motor[i] && s->nloop < LOOP_MAX) s->loopdof[s->nloop++] = i;
    for (int j = 0; j < s->nloop; j++) s->looprow[j] = j; /* the connects' rows in order (the knee: x, y) */
    if (s->nloop != (scene == VT_PEER_KNEE ? 2 : 18) || m->neq != (scene == VT_PEER_KNEE ? 1 : 6)) {
        mjp_destroy(s);
        free(p);
        return NULL;
    }
    s->body = s->map.body + 1; /* vtdyn's body k is link k */
    p->impl = s;
    p->n = s->map.nbody;
    p->vt = &machine_vtable;
    mjp_run(s, 0);
    return p;
}

vt_peer *vt_peer_mujoco(int scene, int n, const double *q, const double *qd, const double *qdd)
{
    if (!q || !qd || !qdd) return NULL;
    if (scene == VT_PEER_DELTA || scene == VT_PEER_STEWART || scene == VT_PEER_KNEE)
        return machine_peer(scene, q, qd, qdd);
    if (scene == VT_PEER_DOUBLE_LINK) n = 2;
    else if (scene == VT_PEER_FOURBAR) n = 3;
    else if (scene == VT_PEER_FOURBAR_RUSR) n = 4;
    else if ((scene != VT_PEER_CHAIN && scene != VT_PEER_CHAIN_TIP) || n < 1) return NULL;

    mjModel *m = scene_model(scene, n);
    if (!m) return NULL;

    vt_peer *p = malloc(sizeof *p);
    mj_peer *s = calloc(1, sizeof *s);
    if (s) s->q = malloc((14 * (size_t)n + 1) * sizeof(mjtNum));
    if (!p || !s || !s->q || m->nv != n || m->nq != n) {
        free(p);
        if (s) free(s->q);
        free(s);
        mj_deleteModel(m);
        return NULL;
    }
    s->m = m;
    s->scene = scene;
    s->n = n;
    if (scene == VT_PEER_FOURBAR || scene == VT_PEER_FOURBAR_RUSR) { /* the crank alone acts */
        s->nloop = scene == VT_PEER_FOURBAR ? 2 : 3;
        for (int j = 0; j < s->nloop; j++) {
            s->loopdof[j] = 1 + j;
            s->looprow[j] = j;
        }
    }
    s->qd = s->q + n;
    s->qdd = s->qd + n;
    s->tau = s->qdd + n;
    s->jac = s->tau + n + 1;
    s->jacd = s->jac + 3 * n;
    s->rhs = s->jacd + 3 * n;
    s->xy = s->rhs + 2 * n;
    for (int i = 0; i < n; i++) {
        s->q[i] = q[i];
        s->qd[i] = qd[i];
        s->qdd[i] = qdd[i];
    }
    /* link k <-> body k (bodies are numbered in XML order) */
    if (scene == VT_PEER_FOURBAR || scene == VT_PEER_FOURBAR_RUSR) {
        s->bodyids[0] = mj_name2id(m, mjOBJ_BODY, "crank");
        s->bodyids[1] = mj_name2id(m, mjOBJ_BODY, "coupler");
        s->bodyids[2] = mj_name2id(m, mjOBJ_BODY, "rocker");
        s->body = s->bodyids;
    } else {
        s->body = m->jnt_bodyid; /* joint k - 1 is link k's, one joint per body */
    }
    s->d = mj_makeData(m);
    if (!s->d) {
        mjp_destroy(s);
        free(p);
        return NULL;
    }
    p->impl = s;
    p->n = scene == VT_PEER_FOURBAR_RUSR ? 3 : n; /* links: the RUSR coupler has two hinges */
    p->vt = scene == VT_PEER_CHAIN ? &chain_vtable : scene == VT_PEER_DOUBLE_LINK ? &dl_vtable
          : scene == VT_PEER_CHAIN_TIP ? &tip_vtable : scene == VT_PEER_FOURBAR_RUSR ? &rusr_vtable : &fb_vtable;
    if (scene == VT_PEER_CHAIN_TIP) s->ades = tip_acceleration(s);
    mjp_run(s, 0);
    return p;
}

long vt_peer_mujoco_simulate(vt_peer *p, double dt, int integrator, double t1, int nout, double *q, double *qd,
                             double *f)
{
    if (!p || (p->vt != &chain_vtable && p->vt != &dl_vtable && p->vt != &fb_vtable)) return -1;
    if (!(dt > 0.0) || !(t1 > 0.0) || nout < 1 || (integrator != VT_PEER_EULER && integrator != VT_PEER_RK4))
        return -1;
    mj_peer *s = p->impl;
    mjModel *m = s->m;
    mjData *d = s->d;
    const int n = s->n;
    /* whole steps between the rows, and rows that fall on steps */
    const long every = lround(t1 / nout / dt), nsteps = every * nout;
    if (every < 1 || fabs((double)nsteps * dt - t1) > 1e-9 * t1) return -1;

    const mjtNum timestep = m->opt.timestep;
    const int integ = m->opt.integrator;
    m->opt.timestep = dt;
    m->opt.integrator = integrator == VT_PEER_RK4 ? mjINT_RK4 : mjINT_EULER;
    mj_resetData(m, d);
    memcpy(d->qpos, s->q, (size_t)n * sizeof(mjtNum));
    memcpy(d->qvel, s->qd, (size_t)n * sizeof(mjtNum));
    for (long i = 0;; i++) {
        if (i % every) {
            mj_step(m, d);
            continue;
        }
        /* a row: mj_step split into its parts, the reactions taken between them */
        const long k = i / every;
        mj_forward(m, d);
        mj_rnePostConstraint(m, d);
        for (int j = 0; j < n; j++) {
            if (q) q[k * n + j] = d->qpos[j];
            if (qd) qd[k * n + j] = d->qvel[j];
            if (f) {
                double nj[3];
                mjp_reaction(s, j + 1, f + 3 * (k * n + j), nj);
            }
        }
        if (i == nsteps) break;
        if (integrator == VT_PEER_RK4) mj_RungeKutta(m, d, 4);
        else mj_Euler(m, d);
    }
    m->opt.timestep = timestep;
    m->opt.integrator = integ;
    return nsteps;
}

#ifdef VT_PEER_URDF
/* ---- URDF robots (vt_peer_mujoco_robot) ----
 * The file is read with libxml2 and its <visual>, <collision>, <gazebo> and <transmission>
 * elements removed (MuJoCo cannot read the meshes' formats, and the dynamics needs only the
 * inertias and the joints); mj_parseXMLString parses the rest as URDF (fixed joints fused, each
 * link's <inertial> as its inertia), a free joint "root_joint" is added to the root link's body
 * when floating, and the options are set as for the scenes: everything but the dynamics disabled.
 * One method, mujoco_post_project (the leanest path to torques and reactions, as on the chain):
 * mj_kinematics, mj_comPos, mj_comVel, mj_rnePostConstraint, the torques cdof . cfrc_int.
 * MuJoCo's free joint: qpos = (position, quaternion w x y z) of the body frame (the root link's
 * frame), qvel = (world velocity of that origin, angular velocity in the body's axes), qacc their
 * derivatives; its generalized force = (world force, moment about the origin in the body's axes). */
#include <libxml/parser.h>
#include <libxml/tree.h>

typedef struct {
    mjModel *m;
    mjData *d;
    int nj;
    int *qadr, *dadr, *isfree;   /* per vtdyn joint: MuJoCo's qpos and dof address, 1 for the free root */
    int *vadr;                   /* vtdyn's packed rate address of joint k */
    int root_body;               /* MuJoCo's body of the free root (0: none) */
    mjtNum *tau;                 /* MuJoCo's qfrc of the last run (nv) */
} mj_robot;

static const char *const robot_methods[] = {"mujoco_post_project"};

static void strip_geometry(xmlNodePtr n)
{
    static const char *const drop[] = {"visual", "collision", "gazebo", "transmission"};
    for (xmlNodePtr c = n->children, next; c; c = next) {
        next = c->next;
        if (c->type != XML_ELEMENT_NODE) continue;
        int gone = 0;
        for (size_t k = 0; k < sizeof drop / sizeof drop[0]; k++)
            if (strcmp((const char *)c->name, drop[k]) == 0) {
                xmlUnlinkNode(c);
                xmlFreeNode(c);
                gone = 1;
                break;
            }
        if (!gone) strip_geometry(c);
    }
}

static void robot_run(void *p, int method)
{
    (void)method;
    mj_robot *s = p;
    const mjModel *m = s->m;
    mjData *d = s->d;
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_comVel(m, d);
    mj_rnePostConstraint(m, d);
    for (int i = 0; i < m->nv; i++) {
        const mjtNum *c = d->cdof + 6 * i, *f = d->cfrc_int + 6 * m->dof_bodyid[i];
        s->tau[i] = c[0] * f[0] + c[1] * f[1] + c[2] * f[2] + c[3] * f[3] + c[4] * f[4] + c[5] * f[5];
    }
}

static void robot_torques(const void *p, double *tau)
{
    const mj_robot *s = p;
    for (int k = 0; k < s->nj; k++) {
        const mjtNum *t = s->tau + s->dadr[k];
        if (s->isfree[k]) { /* the moment from the body's axes to the world's: R t */
            const mjtNum *R = s->d->xmat + 9 * s->root_body;
            for (int c = 0; c < 3; c++) {
                tau[s->vadr[k] + c] = t[c];
                tau[s->vadr[k] + 3 + c] = R[3 * c] * t[3] + R[3 * c + 1] * t[4] + R[3 * c + 2] * t[5];
            }
        } else {
            tau[s->vadr[k]] = t[0];
        }
    }
}

/* joint k's body: the com-based cfrc_int moved to the joint's anchor (see reaction() above) */
static void robot_reaction(const void *p, int k, double f[3], double n[3])
{
    const mj_robot *s = p;
    const mjModel *m = s->m;
    const int dof = s->dadr[k - 1], b = m->dof_bodyid[dof], j = m->dof_jntid[dof];
    const mjtNum *w = s->d->cfrc_int + 6 * b, *c = s->d->subtree_com + 3 * m->body_rootid[b];
    const mjtNum *a = s->d->xanchor + 3 * j;
    const mjtNum r[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    for (int i = 0; i < 3; i++) f[i] = w[3 + i];
    n[0] = w[0] + r[1] * f[2] - r[2] * f[1];
    n[1] = w[1] + r[2] * f[0] - r[0] * f[2];
    n[2] = w[2] + r[0] * f[1] - r[1] * f[0];
}

static void robot_destroy(void *p)
{
    mj_robot *s = p;
    if (!s) return;
    if (s->d) mj_deleteData(s->d);
    if (s->m) mj_deleteModel(s->m);
    free(s->qadr);
    free(s->tau);
    free(s);
}

static const vt_peer_vtable robot_vtable = {1, robot_methods, robot_run, robot_torques, robot_reaction, robot_destroy};

static vt_peer *robot_fail(char *message, mj_robot *s, const char *fmt, const char *what)
{
    if (message) snprintf(message, 256, fmt, what);
    robot_destroy(s);
    return NULL;
}

vt_peer *vt_peer_mujoco_robot(const char *urdf, int floating, int nj, const char *const *names, const double *q,
                              const double *qd, const double *qdd, char *message)
{
    if (message) message[0] = '\0';
    if (!urdf || nj < 1 || !names || !q || !qd || !qdd) return NULL;
    xmlDocPtr doc = xmlReadFile(urdf, NULL, XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR);
    if (!doc || !xmlDocGetRootElement(doc)) {
        if (doc) xmlFreeDoc(doc);
        return robot_fail(message, NULL, "cannot read %s", urdf);
    }
    xmlNodePtr robot = xmlDocGetRootElement(doc);
    strip_geometry(robot);
    /* the root link: the one link no joint has as its child */
    char root[512] = "";
    for (xmlNodePtr l = robot->children; l; l = l->next) {
        if (l->type != XML_ELEMENT_NODE || strcmp((const char *)l->name, "link") != 0) continue;
        xmlChar *ln = xmlGetProp(l, (const xmlChar *)"name");
        int child = 0;
        for (xmlNodePtr j = robot->children; j && ln && !child; j = j->next) {
            if (j->type != XML_ELEMENT_NODE || strcmp((const char *)j->name, "joint") != 0) continue;
            for (xmlNodePtr c = j->children; c; c = c->next)
                if (c->type == XML_ELEMENT_NODE && strcmp((const char *)c->name, "child") == 0) {
                    xmlChar *cl = xmlGetProp(c, (const xmlChar *)"link");
                    child = cl && strcmp((const char *)cl, (const char *)ln) == 0;
                    xmlFree(cl);
                }
        }
        if (!child && ln && !root[0]) snprintf(root, sizeof root, "%s", (const char *)ln);
        xmlFree(ln);
    }
    xmlChar *text = NULL;
    int len = 0;
    xmlDocDumpMemory(doc, &text, &len);
    xmlFreeDoc(doc);
    char err[1024] = "";
    mjSpec *spec = text ? mj_parseXMLString((const char *)text, NULL, err, (int)sizeof err) : NULL;
    xmlFree(text);
    if (!spec) {
        return robot_fail(message, NULL, "mj_parseXMLString: %s", err);
    }
    spec->compiler.alignfree = 0; /* the free joint at the root link frame, not its inertial frame */
    spec->option.gravity[0] = 0.0;
    spec->option.gravity[1] = 0.0;
    spec->option.gravity[2] = -9.81;
    spec->option.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS |
                                 mjDSBL_SPRING | mjDSBL_DAMPER | mjDSBL_ACTUATION | mjDSBL_SENSOR | mjDSBL_EQUALITY;
    if (floating) {
        mjsBody *body = root[0] ? mjs_findBody(spec, root) : NULL;
        if (!body) {
            mj_deleteSpec(spec);
            return robot_fail(message, NULL, "no body for the root link %s", root);
        }
        mjsJoint *fj = mjs_addJoint(body, NULL);
        fj->type = mjJNT_FREE;
        mjs_setName(fj->element, "root_joint");
    }
    mjModel *m = mj_compile(spec, NULL);
    if (!m) {
        snprintf(err, sizeof err, "%s", mjs_getError(spec));
        mj_deleteSpec(spec);
        return robot_fail(message, NULL, "mj_compile: %s", err);
    }
    mj_deleteSpec(spec);
    mj_robot *s = calloc(1, sizeof *s);
    if (!s) {
        mj_deleteModel(m);
        return NULL;
    }
    s->m = m;
    s->nj = nj;
    s->qadr = malloc(4 * (size_t)nj * sizeof *s->qadr);
    s->tau = calloc((size_t)m->nv + 1, sizeof *s->tau);
    s->d = mj_makeData(m);
    if (!s->qadr || !s->tau || !s->d) return robot_fail(message, s, "%s", "out of memory");
    s->dadr = s->qadr + nj;
    s->isfree = s->dadr + nj;
    s->vadr = s->isfree + nj;
    mj_resetData(m, s->d);
    int iq = 0, iv = 0;
    for (int k = 0; k < nj; k++) {
        const int root_joint = !names[k] || !names[k][0];
        const char *name = root_joint ? "root_joint" : names[k];
        const int j = mj_name2id(m, mjOBJ_JOINT, name);
        if (j < 0) return robot_fail(message, s, "MuJoCo's model has no joint %s", name);
        s->qadr[k] = m->jnt_qposadr[j];
        s->dadr[k] = m->jnt_dofadr[j];
        s->vadr[k] = iv;
        s->isfree[k] = m->jnt_type[j] == mjJNT_FREE;
        mjtNum *qp = s->d->qpos + s->qadr[k], *v = s->d->qvel + s->dadr[k], *a = s->d->qacc + s->dadr[k];
        if (s->isfree[k]) {
            s->root_body = m->jnt_bodyid[j];
            for (int c = 0; c < 7; c++) qp[c] = q[iq + c];
            mjtNum R[9], qn[4] = {q[iq + 3], q[iq + 4], q[iq + 5], q[iq + 6]};
            mju_normalize4(qn);
            mju_quat2Mat(R, qn);
            for (int c = 0; c < 3; c++) { /* linear: world; angular: the body's axes, R^T w */
                v[c] = qd[iv + c];
                a[c] = qdd[iv + c];
                v[3 + c] = R[c] * qd[iv + 3] + R[3 + c] * qd[iv + 4] + R[6 + c] * qd[iv + 5];
                a[3 + c] = R[c] * qdd[iv + 3] + R[3 + c] * qdd[iv + 4] + R[6 + c] * qdd[iv + 5];
            }
            iq += 7;
            iv += 6;
        } else if (m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE) {
            qp[0] = q[iq++];
            v[0] = qd[iv];
            a[0] = qdd[iv++];
        } else {
            return robot_fail(message, s, "joint %s: a type the robot rows do not map", name);
        }
    }
    if (iv != m->nv) return robot_fail(message, s, "%s", "the joints given do not cover MuJoCo's model");
    vt_peer *p = malloc(sizeof *p);
    if (!p) return robot_fail(message, s, "%s", "out of memory");
    robot_run(s, 0);
    p->vt = &robot_vtable;
    p->impl = s;
    p->n = nj;
    return p;
}
#endif
