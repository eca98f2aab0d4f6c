/* Scenes written once and shared by the tests, the examples and the benchmarks. */
#ifndef VT_SCENES_H
#define VT_SCENES_H

#include <stdint.h>

#include "vtdyn.h"

/* The paper's double link (Fig. 4): two uniform slender links, 2 m and 100 kg each, joined
 * to the ground and to each other by revolute joints about z; body frames at the links'
 * centres with x along the link; at q = 0 both lie along +x from the origin; y up,
 * gravity (0, −9.81, 0). The angle fallen below x is θ = −q1. With lock != 0, drive 0 keeps
 * joint 2 at q2 = 0 (the paper's "q² = const.") and the pair falls as one 4 m rod. */
#define VT_DL_LENGTH 2.0
#define VT_DL_MASS 100.0
vt_status vt_scene_double_link(vt_model **model, int lock);
/* The double link with drive 0 turning joint 2 by f(t) (q2 = f, rad): partly driven (one drive,
 * two rates); f = constant 0 is vt_scene_double_link(model, 1). */
vt_status vt_scene_double_link_driven(vt_model **model, vt_function f);

/* A free joint driven whole: body 1 on a hinge about z driven by 0.2 + 0.7 sin(1.1 t + 0.3)
 * (drive 0); body 2 on a free joint from body 1's tip (joint point (0.5, 0, 0) on body 1,
 * (0.2, −0.1, 0.3) on body 2), its translation by joint drives 1..3 (0.1 k + (0.3 + 0.1 k)
 * sin((0.9 + 0.4 k) t + 0.2 k), m) and its orientation by drive 4, a turn of
 * 0.1 + 0.5 sin 1.3t about (0, 0.6, 0.8): 7 rows, 7 rates. 1 kg bodies, 0.1 kg m² inertias. */
vt_status vt_scene_free_joint_driven(vt_model **model);

/* A spatial serial chain of n links joined by revolute joints whose axes cycle x, y, z (joint
 * k = 1..n about body axis (k−1) mod 3, given in the parent's axes; all axes aligned at q = 0).
 * Link k: 1 kg, 0.5 m along its x, centre of mass at its middle, inertia about it
 * diag(2e-4, 1/48, 1/48) kg·m² (a slender rod of radius 0.02 m); joint 1 at the origin, joint
 * k > 1 at the far end of link k−1; gravity (0, −9.81, 0). The benchmarks' scene.
 *   drives = VT_CHAIN_FREE          no drive
 *            VT_CHAIN_JOINT_DRIVEN  every joint driven: q_k(t) = q + q̇ t + ½ q̈ t² with the
 *                                   values of vt_scene_chain_state() (so at t = 0 the state
 *                                   and accelerations are exactly those)
 *            VT_CHAIN_TIP_DRIVE     one point drive: the y of the last link's tip follows
 *                                   y0 + 0.05 sin(2π t) with y0 its value at the state */
enum { VT_CHAIN_FREE, VT_CHAIN_JOINT_DRIVEN, VT_CHAIN_TIP_DRIVE };
vt_status vt_scene_chain(vt_model **model, int n, int drives);
/* the chain's reference state of joint k = 0..n−1: q = 0.3 sin(1.3 k + 0.2),
 * q̇ = 0.5 cos(0.7 k), q̈ = 0.4 sin(0.9 k + 1) */
void vt_scene_chain_state(int k, double *q, double *qd, double *qdd);

/* A four-bar linkage laid out in the XY plane, built exactly constrained in space as RSUR:
 * crank (body 1, revolute about z at the origin), coupler (body 2, spherical joint at the
 * crank's tip), rocker (body 3, revolute about z at (VT_FB_D, 0, 0)); the loop is closed by a
 * universal cut joint (cut 0) from the rocker's tip (axis z on the rocker) to the coupler's
 * tip (axis y of the coupler). Uniform rods along their body x: crank VT_FB_A m, 1 kg;
 * coupler VT_FB_B m, 3 kg; rocker VT_FB_C m, 2 kg (a crank-rocker). Drive 0 turns the crank:
 * q1 = crank(t). */
#define VT_FB_A 0.5
#define VT_FB_B 1.5
#define VT_FB_C 1.0
#define VT_FB_D 1.2
vt_status vt_scene_fourbar(vt_model **model, vt_function crank);

/* The same four-bar built the planar way, RRRR: crank, coupler and rocker in a chain of
 * revolute joints about z, the loop closed by a revolute cut joint from the ground at
 * (VT_FB_D, 0, 0) to the rocker's far end. In space its 5 cut rows and the crank drive have
 * rank 3: redundant (the Grübler count says −2, the mobility is 1). With allow_redundant the
 * model solves them in the least-squares sense (vt_model_def.allow_redundant). */
vt_status vt_scene_fourbar_planar(vt_model **model, vt_function crank, int allow_redundant);
/* its q and q̇ at crank angle th2 and rate w2 (the planar assembly of vt_scene_fourbar); also
 * vt_scene_fourbar_pin's */
int vt_scene_fourbar_planar_assemble(const vt_model *model, vt_data *data, double th2, double w2);
/* The same RRRR four-bar closed by a planar revolute cut joint (vt_cut_joint_def.planar): 2 cut
 * rows and the drive on 3 rates, exactly constrained without allow_redundant. */
vt_status vt_scene_fourbar_pin(vt_model **model, vt_function crank);

/* An offset slider-crank in the XY plane: crank (body 1, VT_SC_R m, 1 kg uniform rod, revolute
 * about z at the origin), rod (body 2, VT_SC_L m, 2 kg uniform rod, revolute at the crank's tip),
 * slider (body 3, 1.5 kg, inertia 0.01 I kg·m², translational along x; its joint point
 * (VT_SC_JX, VT_SC_JY) from its centre of mass slides on the line y = VT_SC_H). The rod's far end
 * is pinned to the slider at (VT_SC_PX, VT_SC_PY) from its centre of mass by a revolute cut joint
 * (cut 0, body_a the slider, body_b the rod): planar = 1 its two in-plane rows (3 rows on 3
 * rates: exact); 0 the full 5 rows with allow_redundant. Drive 0 turns the crank: q1 = crank(t);
 * gravity −9.81 y. */
#define VT_SC_R 0.3
#define VT_SC_L 1.0
#define VT_SC_H 0.1
#define VT_SC_JX (-0.03)
#define VT_SC_JY (-0.01)
#define VT_SC_PX 0.05
#define VT_SC_PY 0.02
vt_status vt_scene_slider_crank(vt_model **model, vt_function crank, int planar);
/* its q and q̇ at crank angle th and rate w (the rod toward +x); 0, or -1 where it cannot close */
int vt_scene_slider_crank_assemble(const vt_model *model, vt_data *data, double th, double w);

/* Planar assembly of that four-bar at crank angle th2 and rate w2 (open branch, rocker tip
 * above the ground line): sets d->q, d->qd. Writes the coupler and rocker angles and rates
 * (global, about z) into th[2], w[2] if not NULL. Returns 0, or -1 where the loop cannot close. */
int vt_scene_fourbar_assemble(const vt_model *model, vt_data *data, double th2, double w2, double th[2], double w[2]);

/* The same four-bar built RUSR, the mechanism MuJoCo's peer models (bench/peers): crank (body 1,
 * revolute about z at the origin), coupler (body 2, universal joint at the crank's tip: first
 * axis z on the crank, then the coupler's y, which tilts the coupler out of the plane), rocker
 * (body 3, revolute about z at (VT_FB_D, 0, 0)); the loop is closed by a spherical cut joint
 * (cut 0) from the rocker's tip to the coupler's tip. The same links, masses, inertias and
 * gravity as vt_scene_fourbar. Drive 0 turns the crank: q1 = crank(t). 4 rates, 3 cut rows and
 * the drive: square, and of full rank in the planar poses (the tilt rate alone moves the
 * coupler's tip along z). */
vt_status vt_scene_fourbar_rusr(vt_model **model, vt_function crank);
/* its q and q̇ at crank angle th2 and rate w2 (the planar assembly of vt_scene_fourbar_assemble):
 * the universal's angles are the coupler's angle about z relative to the crank and tilt 0.
 * Writes th[2], w[2] as vt_scene_fourbar_assemble does; returns 0, or -1 where the loop cannot
 * close. */
int vt_scene_fourbar_rusr_assemble(const vt_model *model, vt_data *data, double th2, double w2, double th[2],
                                   double w[2]);

/* The paper's five-link arm (Figs. 9-10). The paper gives no geometry; this one is ours:
 *   link 1  column along its z, 0.4 m, 2 kg, revolute about the global z at the origin (yaw)
 *   link 2  along its x, 0.5 m, 1.5 kg, revolute about link 1's y at its top (pitch)
 *   link 3  along its x, 0.5 m, 1.5 kg, revolute about link 2's y at its end (pitch)
 *   link 4  along its x, 0.2 m, 0.5 kg, revolute about link 3's y at its end (pitch)
 *   link 5  along its x, 0.2 m, 0.5 kg, revolute about link 4's z at its end (yaw)
 * all uniform slender rods, at q = 0 straight out along +x at height 0.4 m; gravity −9.81 z.
 * The five point drives (30)-(34), (31) corrected: the tip (end of link 5) and the point
 * joining links 4 and 5 share y = 0.3 sin 2πt and z = C_e, and the tip's x = C_1 + 0.3 cos 2πt:
 * link 5 stays parallel to X while the tip draws a circle of radius 0.3 m in the plane
 * z = C_e, with C_1 = 0.8 m and C_e = 0.1 m. On that circle the joint point is 0.3..0.9 m from
 * the yaw axis and the elbow (links 2 and 3) reaches 0.32..0.76 m of its 1 m: never stretched,
 * never folded, so the drives fix the motion everywhere (no singular pose). */
#define VT_FL_C1 0.8
#define VT_FL_CE 0.1
vt_status vt_scene_five_link(vt_model **model);
/* The same arm carrying a payload: a point mass of `payload` kg (>= 0) fixed at the tip, so that
 * link 5 becomes the rod and the point together (mass 0.5 + payload, centre of mass moved
 * c = 0.1 payload / (0.5 + payload) m toward the tip, inertia by parallel axes; its joint and
 * drive points keep their places on the link), and the circle drawn in `period` s (the drives'
 * ω = 2π/period). vt_scene_five_link() is vt_scene_five_link_payload(m, 0, 1), bitwise.
 * VT_ERR_BAD_OPTION for a negative or non-finite payload or a period that is not > 0. Its q at
 * time t: vt_scene_five_link_guess(m, d, t / period). */
vt_status vt_scene_five_link_payload(vt_model **model, double payload, double period);
/* q of the five-link arm at time t from its inverse kinematics (elbow up): a start for Newton. */
void vt_scene_five_link_guess(const vt_model *model, vt_data *data, double t);

/* The IFToMM multibody benchmark's simple pendulum (problem A01): a 1 kg point mass on a
 * massless 1 m link, revolute about z at the origin, gravity (0, −9.81, 0); at q = 0 the link
 * lies along +x (horizontal): released from rest there. In joint coordinates it has no
 * constraint row: only the integration's energy drift is left to measure. */
vt_status vt_scene_pendulum(vt_model **model);

/* The IFToMM multibody benchmark's N-four-bar (problem A02): N parallelogram four-bars in a
 * row sharing links, every link a 1 m, 1 kg uniform rod, revolute joints about z, gravity
 * (0, −9.81, 0). Cranks 0..N hang from ground pivots at (k, 0, 0); the couplers 1..N join their
 * tips. Tree: crank 0 (body 1), couplers 1..N (bodies 2..N+1) in a chain from its tip, cranks
 * 1..N (bodies N+2..2N+1) from the ground; cut joint k−1 (revolute) joins crank k's tip to
 * coupler k's far end. Every cut row set is redundant in space (planar mechanism) and the
 * horizontal pose (cranks and couplers in one line) is singular: the model allows redundant
 * rows. vt_scene_nfourbar_start(): cranks vertical, turning at w rad/s, couplers horizontal. */
vt_status vt_scene_nfourbar(vt_model **model, int N);
void vt_scene_nfourbar_start(const vt_model *model, vt_data *data, int N, double w);

/* IFToMM benchmark A04, Bricard's mechanism: five 1 m, 1 kg rods (square section 0.1 m) and
 * six revolute joints, consecutive axes perpendicular, gravity (0, −9.81, 0). At q = 0 the
 * joints sit on six corners of the unit cube, (0,0,0) → (1,0,0) → (1,1,0) → (1,1,1) → (0,1,1)
 * → (0,0,1), axes y, z, x, y, z and x; rods 1..5 run between consecutive corners, the ground
 * link from (0,0,1) to (0,0,0). Grübler counts 0 degrees of freedom, the mechanism has 1.
 * cut: VT_JOINT_REVOLUTE closes the loop at (0,0,1) as the sixth revolute (5 rows for 5 rates:
 * one dependent, the model allows redundant rows); VT_JOINT_UNIVERSAL closes it with a
 * universal joint (axes x on the ground, z on rod 5: 4 independent rows), the non-redundant
 * model of the same motion. drive: when nonzero, rod 1's joint angle follows f. */
vt_status vt_scene_bricard(vt_model **model, vt_joint_type cut, int drive, vt_function f);

/* A random tree of n bodies whose joints cycle through the kinds in `kinds` (a mask of
 * 1 << vt_joint_type; base bodies hang from the ground): random parents, masses, principal
 * inertias, joint points, axes and orientations at q = 0. Deterministic in seed. */
#define VT_SCENE_ALL_JOINTS 0x3Fu
#define VT_SCENE_NO_BASE (VT_SCENE_ALL_JOINTS & ~(1u << VT_JOINT_BASE))
/* the paper's six kinds but base, and the 6-rate free joint (any reference body) */
#define VT_SCENE_WITH_FREE (VT_SCENE_NO_BASE | (1u << VT_JOINT_FREE))
/* joints whose coordinates are all scalar (q̇ is the time derivative of q) */
#define VT_SCENE_SCALAR_JOINTS ((1u << VT_JOINT_REVOLUTE) | (1u << VT_JOINT_UNIVERSAL) | \
                                (1u << VT_JOINT_TRANSLATIONAL) | (1u << VT_JOINT_CYLINDRICAL))
vt_status vt_scene_random_tree(vt_model **model, uint64_t seed, int n, unsigned kinds);
/* The same bodies added to a builder, to add drives and cut joints before building. */
vt_status vt_scene_random_bodies(vt_builder *builder, uint64_t seed, int n, unsigned kinds);

/* A random state: angles in [−π, π], translations in [−1, 1], random unit Euler parameters,
 * rates in [−2, 2] (base bodies: ṗ = ½ E^T ω, tangent to the unit sphere). */
void vt_scene_random_state(const vt_model *model, vt_data *data, uint64_t *seed);

/* Random numbers for scenes and tests: splitmix64 on a caller-held state. */
double vt_rand_uniform(uint64_t *state, double lo, double hi);
void vt_rand_unit(double *v, int n, uint64_t *state); /* uniform direction in R^n */

#endif
