/* C interface to the peer libraries (Pinocchio, MuJoCo) used by the vtdyn benchmarks.
 * Each peer computes inverse dynamics (joint torques) and every joint reaction wrench
 * for the same scenes as vtdyn; MuJoCo also simulates them forward (vt_peer_mujoco_simulate).
 * A peer's constructor exists only when that peer is built (VT_HAVE_PINOCCHIO /
 * VT_HAVE_MUJOCO); the other functions always exist.
 *
 * Scenes and coordinates (q, qd, qdd are copied at construction):
 *   chain        n links, q[k] = angle of joint k + 1 (both peers); torques: n values
 *   double link  MuJoCo only; q = (joint 1, joint 2), joint 2 locked by an equality, so pass
 *                q[1] = qd[1] = qdd[1] = 0; torques: (drive torque, locking torque at joint 2)
 *   four-bar     MuJoCo only; 3 hinge coordinates: q = (crank angle, coupler angle relative to
 *                the crank, rocker angle), angles from +x about +z; the state must satisfy the
 *                loop closure; torques: 3 values (see mujoco_peer.c for the methods); links
 *                k = 1, 2, 3 are crank, coupler, rocker
 *   four-bar RUSR
 *                MuJoCo only; the same links built spatial RUSR, as vtdyn's vt_scene_fourbar_rusr:
 *                crank hinge z, coupler on two hinges at the crank's tip (z, then its own y: a
 *                universal joint), rocker hinge z, loop closed by a connect equality (3 rows);
 *                4 coordinates: q = (crank angle, coupler angle about z relative to the crank,
 *                coupler tilt about the coupler's y, rocker angle); the state must satisfy the
 *                loop closure; torques: 4 values, the crank torque, then the 3 others left once
 *                the loop force is solved (none is actuated: zero up to round-off); links
 *                k = 1, 2, 3 are crank, coupler, rocker
 *   chain tip    MuJoCo only; the chain of n links (same model and q as the chain) whose only
 *                drive is a force along global y at the tip of link n (0.5 m along its x from its
 *                joint); pass q̈ solved by vtdyn; torques: n + 1 values, the n joint torques left
 *                once the tip force is applied (none is actuated: zero up to round-off), then the
 *                tip force F (N, the force on the tip along +y); the reactions include F
 *   Delta, Stewart platform, knee
 *                MuJoCo only; the machines of examples/scenes.h (vt_scene_delta, vt_scene_stewart,
 *                vt_scene_knee with planar = 1), MuJoCo's models in mujoco_scenes.c (n ignored);
 *                the state in vtdyn's layout of that scene: q its nq coordinates (a free joint's
 *                position, then its Euler parameters w x y z), qd and qdd its nv rates (a free
 *                joint's linear, then its angular velocity in world axes) satisfying the loops;
 *                torques: nv values in vtdyn's rates, the motors' torques or forces (the Delta's
 *                arms, the Stewart's legs, the knee's hip and motor) and on every other rate what
 *                is left once the loop forces are solved (none is actuated: zero up to round-off;
 *                a free joint's moment in world axes); links k = 1..nbody are vtdyn's bodies (a
 *                Stewart piston's moment is about MuJoCo's slide anchor, the piston's top, not
 *                vtdyn's joint point: the forces agree, the moments differ by the lever arm) */
#ifndef VT_BENCH_PEERS_H
#define VT_BENCH_PEERS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vt_peer vt_peer;   /* opaque */
/* scene: VT_PEER_CHAIN and VT_PEER_CHAIN_TIP (n links), VT_PEER_DOUBLE_LINK, VT_PEER_FOURBAR,
 * VT_PEER_FOURBAR_RUSR, VT_PEER_DELTA, VT_PEER_STEWART, VT_PEER_KNEE (n ignored for these) */
enum {
    VT_PEER_CHAIN = 0, VT_PEER_DOUBLE_LINK = 1, VT_PEER_FOURBAR = 2, VT_PEER_CHAIN_TIP = 3, VT_PEER_FOURBAR_RUSR = 4,
    VT_PEER_DELTA = 5, VT_PEER_STEWART = 6, VT_PEER_KNEE = 7
};
/* NULL if the scene is not supported by that peer */
vt_peer *vt_peer_pinocchio(int scene, int n, const double *q, const double *qd, const double *qdd);
vt_peer *vt_peer_mujoco(int scene, int n, const double *q, const double *qd, const double *qdd);
/* A URDF robot (the bench's robot rows), each peer loading the file itself: Pinocchio's model as
 * its URDF loader builds it, MuJoCo's from the URDF without its geometry (mj_parseXMLString).
 * The state comes in vtdyn's layout (vt_urdf_builder's model): nj joints in vtdyn's body order,
 * names[k] the URDF joint's name, or NULL or "" for the free root joint (floating = 1); q, qd,
 * qdd packed joint by joint: one value for a revolute or prismatic joint; for the free root
 * q = (x, y, z, q_w, q_x, q_y, q_z), the root link frame's origin and orientation, qd = its
 * origin's velocity and its angular velocity, world axes, qdd their derivatives (the classical
 * acceleration of the origin). torques() in the same layout (the root's six: the world force and
 * the world moment about the root origin that the free joint transmits); reaction(k), k = 1..nj,
 * of joint k in world axes about its origin, the actuation inside. NULL on failure, with a reason
 * in message (256 bytes, may be NULL). Methods: Pinocchio "pinocchio_rnea",
 * "pinocchio_rnea_world"; MuJoCo "mujoco_post_project" (see mujoco_peer.c). */
vt_peer *vt_peer_pinocchio_robot(const char *urdf, int floating, int nj, const char *const *names, const double *q,
                                 const double *qd, const double *qdd, char *message);
vt_peer *vt_peer_mujoco_robot(const char *urdf, int floating, int nj, const char *const *names, const double *q,
                              const double *qd, const double *qdd, char *message);
int vt_peer_nmethods(const vt_peer *p);
const char *vt_peer_method(const vt_peer *p, int method);   /* e.g. "pinocchio_rnea", "pinocchio_rnea_world", "pinocchio_crba_cholesky", "mujoco_inverse", "mujoco_rne_post", "mujoco_inverse_tip" */
void vt_peer_run(vt_peer *p, int method);                    /* one full evaluation; no allocation */
void vt_peer_torques(const vt_peer *p, double *tau);         /* joint torques of the last run (n; chain tip n + 1; RUSR four-bar 4; the machines nv) */
/* reaction of the parent on link k (1-based) at that link's joint point, world axes: force f, moment n about the joint point; includes whatever the peer includes (say in a comment whether the actuator torque is inside n)
 * Both peers: n is the whole moment transmitted through the joint, so the actuator (joint) torque
 * IS inside n: its component along the joint axis equals the joint torque of link k's joint.
 * Gravity and inertia of the subtree carried by link k are inside f and n (both peers). */
void vt_peer_reaction(const vt_peer *p, int k, double f[3], double n[3]);
void vt_peer_free(vt_peer *p);

/* MuJoCo only (exists when VT_HAVE_MUJOCO): forward simulation of a MuJoCo peer's scene from its
 * q and qd (qdd unused) with mj_step, time step dt, integrator VT_PEER_EULER (MuJoCo's default,
 * semi-implicit Euler) or VT_PEER_RK4, up to t1. Rows k = 0..nout at t = k t1 / nout (t1 / nout
 * must be a whole number of steps), each after mj_forward and mj_rnePostConstraint at that state:
 * q and qd ((nout + 1) x n, MuJoCo's qpos and qvel) and f ((nout + 1) x 3n: for links 1..n the
 * reaction force of vt_peer_reaction); any of the three may be NULL. Returns the number of steps
 * (mj_step equivalents; RK4 evaluates the dynamics 4 times a step, Euler once), or -1 when p is not
 * a MuJoCo peer, is a chain-tip one (its drive is not modelled forward), an RUSR four-bar or a
 * machine one (not supported) or an argument is bad. The model's timestep and integrator are restored afterwards;
 * the peer's last-run results (torques, reactions) are overwritten. */
enum { VT_PEER_EULER = 0, VT_PEER_RK4 = 1 };
long vt_peer_mujoco_simulate(vt_peer *p, double dt, int integrator, double t1, int nout, double *q, double *qd,
                             double *f);

#ifdef __cplusplus
}
#endif

#endif /* VT_BENCH_PEERS_H */
