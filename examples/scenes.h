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
/* the same with the model's data layout chosen (vt_scene_chain: VT_LAYOUT_FULL) */
vt_status vt_scene_chain_layout(vt_model **model, int n, int drives, vt_layout layout);
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

/* A Delta robot (ABB FlexPicker / Codian-like), z up, gravity (0, 0, −9.81), the base at z = 0
 * and the platform below. Arm i = 0, 1, 2 sits at φ_i = 2π i/3 with radial unit u_i =
 * (cos φ_i, sin φ_i, 0) and tangential unit t_i = (−sin φ_i, cos φ_i, 0):
 *   upper arm i (body 1 + i)   revolute about t_i at VT_DELTA_RB u_i (the motor), VT_DELTA_LA
 *                              long, VT_DELTA_MA kg, a uniform rod along its body x (body axes:
 *                              the base's turned by φ_i about z, then by the motor angle θ_i);
 *                              θ_i = 0 horizontal, θ_i > 0 down
 *   rods (i, ∓) (bodies 4 + 2i, 5 + 2i)  the forearm's parallelogram: two uniform rods
 *                              VT_DELTA_LF long, VT_DELTA_MR kg each, hung from the elbow at
 *                              ∓VT_DELTA_H along the arm's y by universal joints (first axis the
 *                              arm's y, parallel to the motor's; second the rod's x), along the
 *                              rod's −z at zero angles
 *   platform (body 10)         a free joint from the ground (q: its centre's global position and
 *                              its Euler parameters), VT_DELTA_MP kg (gripper and load), its
 *                              centre at its centre of mass; frame 0 "tool", the gripper's tip,
 *                              VT_DELTA_TOOL below that centre (body z)
 * Cut joints 2i, 2i + 1: spherical, rod (i, ∓)'s lower end to the platform at
 * VT_DELTA_RP u_i ∓ VT_DELTA_H t_i. Rates 3 + 12 + 6 = 21, cut rows 6 × 3 = 18: three degrees
 * of freedom (Grübler's count is the mobility: the rods' universal joints leave no spin), the
 * platform kept parallel to the base by the parallelograms. With three drives the model is
 * square and exactly constrained (no redundant rows) away from the Delta's singular poses.
 *   drives = VT_DELTA_PATH    three point drives on the platform's centre, x, y, z (drives 0..2)
 *                             following vt_scene_delta_path() with period `period` s
 *            VT_DELTA_MOTORS  three joint drives on the motor angles (drive i on arm i),
 *                             constant 0: the motion is given to vt_inverse_dynamics_motion(),
 *                             whose efforts are then the motor torques
 *            VT_DELTA_IK      three joint drives on the motor angles (drive i on arm i) following
 *                             the path's inverse kinematics θ_i(t) (vt_scene_delta_motor() of
 *                             vt_scene_delta_path()): one model whose drive efforts are the motor
 *                             torques. Its callbacks need data that outlives the model: build it
 *                             with vt_scene_delta_ik(); here it is refused.
 * VT_ERR_BAD_OPTION for a period that is not > 0 and finite, or drives not VT_DELTA_PATH or
 * VT_DELTA_MOTORS. */
#define VT_DELTA_RB 0.2   /* base radius (motor axes), m */
#define VT_DELTA_LA 0.35  /* upper arm, m */
#define VT_DELTA_LF 0.8   /* forearm rods, m */
#define VT_DELTA_RP 0.05  /* platform radius (middle of each rod pair), m */
#define VT_DELTA_H 0.05   /* half the spacing of a parallelogram's rods, m */
#define VT_DELTA_MA 1.2   /* upper arm, kg */
#define VT_DELTA_MR 0.2   /* each forearm rod, kg */
#define VT_DELTA_MP 1.5   /* platform with gripper and load, kg */
#define VT_DELTA_TOOL 0.06 /* the gripper's tip below the platform's centre, m */
#define VT_DELTA_RHO 0.15 /* radius of the path's circle, m */
#define VT_DELTA_Z0 (-0.85) /* height of the circle's centre, m */
#define VT_DELTA_DZ 0.05  /* the path's rise and fall, m */
enum { VT_DELTA_PATH, VT_DELTA_MOTORS, VT_DELTA_IK };
vt_status vt_scene_delta(vt_model **model, double period, int drives);
/* The Delta driven at its motors by the path's inverse kinematics (VT_DELTA_IK): drive i holds
 * arm i's motor angle at θ_i(t), the closed form of vt_scene_delta_motor() at the platform centre
 * p(t) = vt_scene_delta_path(t, period) with θ̇_i and θ̈_i exact. The drives' efforts are the
 * motor torques (N·m about t_i, positive turning the arm down), the reactions those of the
 * machine driven by its motors. The struct must outlive the model (its arms are the drives'
 * callback data, as vt_scene_stewart's legs); vt_scene_delta_ik fills it. A callback fails
 * (VT_ERR_CALLBACK from the analyses) where the path leaves the reach or meets a singular pose.
 * VT_ERR_NULL for a NULL ik; VT_ERR_BAD_OPTION for a period that is not > 0 and finite. */
typedef struct vt_delta_arm {
    const struct vt_delta_ik *ik;
    int arm;
} vt_delta_arm;
typedef struct vt_delta_ik {
    double period;         /* s, the path's period */
    vt_delta_arm arm[3];   /* filled by vt_scene_delta_ik: the drives' callback data */
} vt_delta_ik;
vt_status vt_scene_delta_ik(vt_model **model, vt_delta_ik *ik, double period);
/* Arm `arm`'s motor angle θ (rad, > 0 down) with the platform's centre at p (m), elbow out, and
 * when pd and pdd are not NULL its time derivatives θ̇, θ̈ for the centre's velocity pd (m/s)
 * and acceleration pdd (m/s²): th[0..2] = θ, θ̇, θ̈ (th[1], th[2] untouched without pd, pdd).
 * The elbow lies on the circle of radius VT_DELTA_LA about the motor axis, VT_DELTA_LF from the
 * rods' platform end: F(θ, p) = A cos θ + B sin θ − K = 0 (scenes.c); θ̇ = −F_t / F_θ and θ̈ from
 * F's second derivative, by implicit differentiation. Returns 0, or −1 where p is out of reach
 * or (with derivatives) F_θ = 0, the arm and its rods in line. */
int vt_scene_delta_motor(int arm, const double p[3], const double pd[3], const double pdd[3], double th[3]);
/* The platform centre's path, p, ṗ, p̈ at time t (any of them may be NULL): a circle of radius
 * VT_DELTA_RHO about the z axis at height VT_DELTA_Z0, rising and falling by VT_DELTA_DZ twice
 * a turn: p = (ρ cos ωt, ρ sin ωt, z0 + Δz sin 2ωt), ω = 2π/period. */
void vt_scene_delta_path(double t, double period, double p[3], double pd[3], double pdd[3]);
/* The assembly with the platform's centre at p (the Delta's inverse kinematics, elbows out, the
 * platform parallel to the base): sets d->q; q̇ = 0. Returns 0, or −1 where p is out of reach. */
int vt_scene_delta_assemble(const vt_model *model, vt_data *data, const double p[3]);

/* A quadruped (contacts, docs/contact.md): a 10 kg box torso 0.6 x 0.3 x 0.1 m on a free joint
 * ("root", its point the torso's centre of mass) and four legs FL, FR, HL, HR (front/hind,
 * left/right) with hips at (±0.3, ±0.15, 0) in torso axes: a 0.3 kg hip body on an abduction
 * joint about x (L_HAA), a 1 kg thigh on a flexion joint about y (L_HFE) and a 0.5 kg shank on a
 * knee about y (L_KFE), thigh and shank uniform 0.2 m rods along −z at q = 0; a frame L_foot at
 * each shank's end. Symmetric front to hind and left to right; 17.2 kg in all; gravity −9.81 z.
 * vt_scene_quadruped_stand: the standing pose with hip flexion θ and knee −2θ on the front legs,
 * −θ and 2θ on the hind ones (each foot under its hip, the robot symmetric front to hind too),
 * the torso at rest at height 0.4 cos θ: q into d->q, q̇ and q̈ zero. */
#define VT_QUADRUPED_MASS 17.2
vt_status vt_scene_quadruped(vt_model **model);
void vt_scene_quadruped_stand(const vt_model *model, vt_data *data, double theta);
/* The same quadruped with the feet of the mask (bit k: FL, FR, HL, HR) held to the ground by
 * spherical cut joints at the points under their hips ((±0.3, ±0.15, 0): the stand's feet),
 * every leg joint driven (joint drives, the motion given through the data), allow_redundant:
 * the feet as bilateral contacts, solved as redundant loops (test_contact's second method). */
vt_status vt_scene_quadruped_feet(vt_model **model, unsigned feet);
/* The same quadruped swaying on its four feet, fully driven (a kinematic analysis on contacts):
 * the torso's centre of mass at (a sin ωt, 0, h + a sin 2ωt) by joint drives on the root's
 * translation (a = VT_SWAY_AMPLITUDE m, h = 0.4 cos θ, θ = VT_SWAY_THETA: the stand's height),
 * its roll about x by a sin ωt rad (an orientation drive), and each foot frame held at the point
 * under its hip on the ground, (±0.3, ±0.15, 0), by three point drives: 18 rows for 18 rates.
 * ω = 2π / period. vt_scene_quadruped_stand(model, data, VT_SWAY_THETA) is the pose at t = 0
 * (q̇ not: the torso moves). */
#define VT_SWAY_AMPLITUDE 0.03
#define VT_SWAY_THETA 0.5
vt_status vt_scene_quadruped_sway(vt_model **model, double period);

/* A humanoid's lower body (contacts, docs/contact.md): a 20 kg pelvis and trunk (a box
 * 0.3 x 0.3 x 0.5 m, its centre of mass 0.2 m above the hips) on a free joint ("root", its point
 * the centre of mass), and two legs L and R with hips at (0, ±0.1, −0.2) from it: a 0.5 kg hip
 * body on a roll joint about x (S_hip_roll), a 3 kg thigh on a pitch joint about y (S_hip_pitch),
 * a 2 kg shank on a knee about y (S_knee), thigh and shank uniform 0.4 m rods along −z at q = 0,
 * a 0.2 kg ankle body on a pitch joint about y (S_ankle_pitch) and a 1 kg foot, a box 0.2 x 0.1
 * x 0.05 m, on a roll joint about x (S_ankle_roll) at the shank's end, its sole 0.05 m below the
 * ankle with a frame at each corner: S_toe_in, S_toe_out, S_heel_in, S_heel_out (toes at
 * x = 0.1, heels at −0.1, in and out at y = ∓0.05 for L, ±0.05 for R). 33.4 kg in all; gravity
 * −9.81 z. */
#define VT_HUMANOID_MASS 33.4

/* s = 10u³ − 15u⁴ + 6u⁵ (0 to 1 on u in [0, 1], at rest at both ends) and its first two
 * derivatives in u */
void vt_scene_quintic(double u, double *s, double *sd, double *sdd);
/* A foot's step along x (examples/walk.c, examples/trot.c): n strides done from base, then, while
 * in the air (air), τ s into a swing of `swing` s, one more stride by the quintic 10u³ − 15u⁴ + 6u⁵
 * (u = τ / swing: at rest at lift-off and touchdown) and a lift of `lift` m as lift sin²(π u): p[0],
 * p[2] and their rates and accelerations (v[1], a[1] zero; p[1] left to the caller) */
void vt_scene_foot_step(double base, double n, double tau, double swing, double stride, double lift, int air,
                        double p[3], double v[3], double a[3]);
/* A leg of a roll joint about x and two pitch joints about y (hip roll, hip pitch, knee), two links
 * of length L, reaching the point d from the hip (x forward, z up; the roll turns the leg's plane
 * onto it, the two links reach its distance ρ = √(d_y² + d_z²) in that plane; knee −1 puts the
 * knee behind the line from hip to foot, +1 in front of it, a human's; a link at angle α points
 * along (−sin α, −cos α)):
 * the three angles into q, their rates and accelerations from d's velocity dd and acceleration
 * ddd (exact: the chain rule for the roll and ρ, q̇ = J⁻¹ ṗ, q̈ = J⁻¹ (p̈ − J̇ q̇) in the plane).
 * Used by examples/walk.c and examples/balance.c. */
void vt_scene_leg_ik(double L, const double d[3], const double dd[3], const double ddd[3], double knee, double q[3],
                     double qd[3], double qdd[3]);
vt_status vt_scene_humanoid(vt_model **model);

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

/* A chain ground –revolute– 1 –spherical– 2 –revolute– 3: masses and inertias with products,
 * joints off the centres of mass, body 2 assembled turned (its orientation at q = 0 not the
 * identity). Drive 0 turns joint 1 (sine), drive 1 the spherical joint by three angles "ZYX"
 * (sines): relative = 1 a relative orientation drive with reference −1 (the joint's own
 * rotation q = R_z(f) ⊗ R_y(f2) ⊗ R_x(f3)), relative = 0 the same drive absolute (body 2's
 * global orientation, another motion); drive 2 turns joint 3. 5 rates, 5 rows: fully driven. */
vt_status vt_scene_spherical_chain(vt_model **model, int relative);

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

/* A Stewart–Gough platform, 6-UPS: six legs from the ground to a platform. Leg i (0..5): a
 * cylinder (body 2 + 2i) on a universal joint at the base point a_i (first axis the global x,
 * then the cylinder's y; at q = 0 the cylinder lies along the global z), a piston (body 3 + 2i)
 * on a translational joint along the cylinder's z whose coordinate is the leg length L_i (the
 * distance from the universal's centre to the piston's top), and a spherical cut joint (cut i)
 * from the platform (body_a) at b_i to the piston's top (body_b): the cut's force is the
 * platform's on the leg. The platform (body 1) floats on a free joint from the ground at its
 * centre. Gravity (0, 0, −9.81), z up. 24 rates, 18 cut rows and six joint drives (drive i:
 * the piston of leg i, L_i = the leg length of the prescribed pose, exact with both
 * derivatives): fully driven, a kinematic analysis; the six drive efforts are the actuators'
 * forces (N, along the leg, positive pushing the platform away from the base).
 * Geometry: base points on a circle of VT_SG_BASE_R m at z = 0, at angles 120k ∓ 15°; platform
 * points on a circle of VT_SG_PLAT_R m in the platform's plane through its centre, at
 * 120k − 45° and 120k + 45° (leg 2k at 120k − 15° on the base to 120k − 45° on the platform,
 * leg 2k+1 at 120k + 15° to 120k + 45°). Platform: 10 kg disc (radius 0.3 m, 0.03 m thick),
 * centre of mass at its centre. Cylinder: 2 kg, 0.5 m, radius 0.04 m, centre of mass 0.25 m
 * from the universal's centre; piston: 1 kg, 0.5 m, radius 0.02 m, centre of mass 0.25 m below
 * the top (solid cylinders' inertias).
 * The pose: with φ = phase + ω t, the centre r = (0.08 sin φ, 0.06 sin 2φ, VT_SG_HEIGHT +
 * 0.05 sin φ) and the orientation a turn of 0.15 sin φ about the slanted axis (1, 1, 2)/√6 from
 * the base's axes; legs 0.86..1.04 m long over a period. ω = 0 holds the platform still at
 * the pose of phase (the static case). The struct must outlive the model (its legs are the
 * drives' callback data). */
#define VT_SG_BASE_R 0.5
#define VT_SG_PLAT_R 0.3
#define VT_SG_HEIGHT 0.9
#define VT_SG_M_PLAT 10.0
#define VT_SG_M_CYL 2.0
#define VT_SG_M_PIST 1.0
#define VT_SG_HALF 0.25 /* m, centres of mass from the universal's centre and from the top */
typedef struct vt_stewart_leg {
    const struct vt_stewart *sg;
    int leg;
} vt_stewart_leg;
typedef struct vt_stewart {
    double omega;          /* rad/s, the pose's phase rate */
    double phase;          /* rad, its phase at t = 0 */
    vt_stewart_leg leg[6]; /* filled by vt_scene_stewart: the drives' callback data */
} vt_stewart;
vt_status vt_scene_stewart(vt_model **model, vt_stewart *sg);
/* the base point a_i (global, m) and the platform point b_i (platform axes from its centre, m) */
void vt_scene_stewart_points(int leg, double a[3], double b[3]);
/* the prescribed pose at t: r[0..8] the centre, its velocity and acceleration (m, m/s, m/s²);
 * p the platform's Euler parameters; w[0..5] its angular velocity and acceleration (global) */
void vt_scene_stewart_pose(const vt_stewart *sg, double t, double r[9], double p[4], double w[6]);
/* q and q̇ of the model at t from the closed-form inverse kinematics */
void vt_scene_stewart_assemble(const vt_model *model, vt_data *data, const vt_stewart *sg, double t);

/* A legged robot's knee four-bar: the knee motor sits at the hip and turns the knee through a
 * crank, a coupler along the thigh and a lever on the shank. All in the XY plane, every joint a
 * revolute about z, gravity (0, −9.81, 0). Thigh (body 1): at the hip (the origin), VT_KN_D m
 * from hip to knee along its x, 1.5 kg; crank (body 2): on the thigh at the hip, VT_KN_A m,
 * 0.1 kg; coupler (body 3): at the crank's tip, VT_KN_B m, 0.08 kg; shank (body 4): on the thigh
 * at the knee, a uniform rod from the lever point VT_KN_C m behind the knee to the foot VT_KN_L m
 * ahead of it, 0.5 kg. The loop is closed by a revolute cut joint about z (cut 0) from the
 * shank's lever point (body_a) to the coupler's far end (body_b): its force is the shank's on
 * the coupler. Rods of radius 0.01 m (solid-cylinder inertias). Drive 0: the hip, q1 = hip(t)
 * (the thigh's angle from the global x); drive 1: the knee motor, q2 = motor(t) (the crank's
 * angle from the thigh). planar = 1: the cut is a planar pin (vt_cut_joint_def.planar), its 2
 * in-plane rows and the 2 drives on 4 rates, square and of full rank, no redundant option;
 * planar = 0: the full 5-row revolute, 7 rows of rank 4, with allow_redundant. q4, the shank's
 * angle from the thigh, is the knee angle. */
#define VT_KN_A 0.05   /* crank */
#define VT_KN_B 0.30   /* coupler */
#define VT_KN_C 0.045  /* lever on the shank, behind the knee */
#define VT_KN_D 0.30   /* thigh, hip to knee */
#define VT_KN_L 0.30   /* shank, knee to foot */
vt_status vt_scene_knee(vt_model **model, vt_function hip, vt_function motor, int planar);
/* the same loop with the links' masses mass[4] (thigh, crank, coupler, shank, kg; each link's
 * inertia its rod's at that mass), the drives a mask: 1 the hip, 2 the knee motor (3: both, as
 * vt_scene_knee), and each link's joint's armature, damping and friction (effects[4][3]; NULL:
 * none) */
vt_status vt_scene_knee_with(vt_model **model, vt_function hip, vt_function motor, int planar, const double mass[4],
                             int drives, const double effects[][3]);
/* q and q̇ of the knee at hip angle th1 (rad, rate w1) and motor angle thm (rad, rate wm): the
 * loop closed on the branch where the lever follows the crank (ψ near thm). Writes the knee
 * angle and rate into knee[2] if not NULL. Returns 0, or -1 where the loop cannot close. */
int vt_scene_knee_assemble(const vt_model *model, vt_data *data, double th1, double w1, double thm, double wm,
                           double knee[2]);

/* d(T + V)/dt of the whole mechanism at the data's last instant (W, for the power balance of the
 * examples): Σ m v·a + ω·(J ω̇) − m g·v over the bodies (J global: ω·(J̇ ω) = 0), from ẋ, ẍ,
 * ω and α (vt_data.alpha) of an instant that has run. */
double vt_scene_energy_rate(const vt_model *model, const vt_data *data);

#endif
