/* vtdyn — public types: statuses, definition structs, the model and the data.
 *
 * Conventions, stated once:
 * - SI units: m, kg, s, N, N·m, rad.
 * - Euler parameters are scalar first, p = [p0 p1 p2 p3], unit norm.
 * - Matrices are column-major; a matrix argument or field names its leading dimension.
 * - Body 0 is the ground. Moving bodies are numbered 1..nbody and every body's reference
 *   (parent) body has a smaller number, so outward passes count up and inward passes down.
 * - Per-body arrays have nbody+1 entries, entry 0 being the ground. The paper's stacked
 *   Cartesian vectors (x, ẋ, F, rows of S, columns of R) have 7*nbody entries and skip the
 *   ground: body i occupies entries 7*(i-1) .. 7*(i-1)+6, r^i first, then p^i.
 * - The position vector q (nq entries) and the velocity vector q̇ (nv entries) differ in
 *   length: a spherical joint keeps its relative orientation as 4 Euler parameters but has 3
 *   rates (relative angular velocity in the reference body's axes); a base (floating) body
 *   has q = x^i (7) and q̇ = ẋ^i (7).
 * - A joint reaction is the force and moment that the reference body exerts on the body at
 *   the joint point; actuating efforts are reported beside reactions, never inside them.
 */
#ifndef VTDYN_TYPES_H
#define VTDYN_TYPES_H

#include <stddef.h>

#include "vtdyn/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Status of a call: 0 is success, negative values are errors.
typedef enum vt_status {
    VT_OK = 0,                         ///< success
    VT_ERR_NULL = -1,                  ///< a required pointer argument is NULL
    VT_ERR_NO_MEMORY = -2,             ///< an allocation failed
    VT_ERR_NONFINITE = -3,             ///< NaN or Inf in a definition or state, or finite inputs whose
                                       ///< results overflow (past DBL_MAX): the message says which
    VT_ERR_MASS = -4,                  ///< mass negative
    VT_ERR_INERTIA_ASYMMETRIC = -5,    ///< inertia matrix not symmetric (to vt_model_def.inertia_tol)
    VT_ERR_INERTIA_NOT_PSD = -6,       ///< inertia matrix has a negative principal moment (to vt_model_def.inertia_tol)
    VT_ERR_INERTIA_TRIANGLE = -7,      ///< principal moments violate I1 + I2 >= I3 (to vt_model_def.inertia_tol)
    VT_ERR_AXIS_ZERO = -8,             ///< a joint or drive axis is the zero vector
    VT_ERR_AXES_NOT_PERPENDICULAR = -9,///< universal joint axes not perpendicular
    VT_ERR_PARENT = -10,               ///< reference body is not an earlier body (base: not ground)
    VT_ERR_JOINT_TYPE = -11,           ///< unknown joint type
    VT_ERR_TOO_MANY_BODIES = -12,      ///< a count or size beyond what the library can index (int) or
                                       ///< address (size_t): more than VT_COUNT_MAX bodies, coordinates,
                                       ///< rates, rows, drives, cut joints, frames or couplings (the
                                       ///< message names the count), or a model or data whose bytes do
                                       ///< not fit in size_t
    VT_ERR_QUATERNION = -13,           ///< Euler parameters of (near) zero norm
    VT_ERR_EMPTY_MODEL = -14,          ///< a model needs at least one moving body
    VT_ERR_BAD_INDEX = -15,            ///< a body or coordinate index out of range
    VT_ERR_MODEL_MISMATCH = -16,       ///< the data struct was made for another model
    VT_ERR_LAPACK = -17,               ///< LAPACK reported an error (info in the message)
    VT_ERR_BAD_DRIVE = -18,            ///< a drive definition that cannot be used (message says why)
    VT_ERR_BAD_CUT_JOINT = -19,        ///< a cut-joint definition that cannot be used
    VT_ERR_CALLBACK = -20,             ///< a user time function or orientation callback returned an error
    VT_ERR_SINGULAR = -21,             ///< augmented system (5) singular (a rate or body without inertia
                                       ///< that nothing fixes, named, an inertia that is round-off of 0
                                       ///< included; an exactly zero pivot) or only ill-conditioned
                                       ///< (rcond below rcond_min); the message says which
    VT_ERR_DEPENDENT_CONSTRAINTS = -22,///< constraint rows Φ_q linearly dependent, a row that is
                                       ///< round-off of 0 included (rows named in the message)
    VT_ERR_NEWTON = -23,               ///< Newton–Raphson on Φ(q, t) = 0 did not converge (residual in message)
    VT_ERR_NOT_FULLY_DRIVEN = -24,     ///< a kinematic analysis needs as many constraint rows as rates
    VT_ERR_IDA = -25,                  ///< SUNDIALS IDA failed: its return code in ida_flag, its message
                                       ///< in the data's message
    VT_ERR_ABORTED = -26,              ///< the progress callback asked to stop
    VT_ERR_BAD_OPTION = -27,           ///< a run option out of range (message says which)
    VT_ERR_BAD_SIZE = -28,             ///< a caller-provided buffer is too small (see vt_data_size())
    VT_ERR_BAD_NAME = -29,             ///< a name too long (VT_NAME_MAX) or already used by another of its kind
    VT_ERR_NOT_FOUND = -30,            ///< no body, joint, drive, cut joint or frame of that name
    VT_ERR_FILE = -31,                 ///< a file cannot be opened or read (the message names it and why)
    VT_ERR_XML = -32,                  ///< malformed XML, or not the document expected (no <robot>); the
                                       ///< message gives the parser's reason and the line
    VT_ERR_LAYOUT = -33,               ///< the data does not hold what the call needs: a dense stage, or an
                                       ///< instant that needs M*, on data laid out VT_LAYOUT_RECURSIVE
                                       ///< (the message says what needed it; vt_model_def.layout)
    VT_ERR_SKIPPED = -34,              ///< a batch row not solved: the batch stopped at a failing row
                                       ///< (vt_batch_def.stop_on_error)
    VT_ERR_CONTACT = -35               ///< the contacts cannot carry the motion: a unilateral contact
                                       ///< would have to pull or slip, or the active contacts cannot
                                       ///< give the unactuated rates' forces (the message names the
                                       ///< contact and the instant's need)
} vt_status;

/// Names of bodies, joints, drives, cut joints and frames: at most VT_NAME_MAX − 1 bytes, unique
/// among their kind; an empty name (or NULL in a definition) leaves the object unnamed.
#define VT_NAME_MAX 64

/// Bytes of a message buffer (a data's or builder's message, vt_urdf_builder's): part of the ABI, stays 256.
#define VT_MESSAGE_SIZE 256

/// Default relative tolerance of a body's inertia checks (vt_model_def.inertia_tol): symmetric,
/// positive semi-definite and within the triangle inequality to it times its largest entry (what
/// files that print inertias to a few digits are off by); the model keeps the symmetric part.
#define VT_INERTIA_TOL 1e-6
/// Absolute floor of those tolerances, kg·m²: a point mass written with moments of −5e-20.
#define VT_INERTIA_ABS_TOL 1e-15
/// Largest magnitude of an inertia entry, kg·m²: the rotational mass 4 GᵀJ'G has entries up to 12
/// times it, which must not overflow. An inertia beyond it is refused with VT_ERR_NONFINITE.
#define VT_INERTIA_MAX 1e307

/// Largest count of each kind in a model (2^24 = 16,777,216): bodies, coordinates (nq), rates (nv),
/// constraint rows (nc), drives, cut joints, frames and couplings; beyond it the builder refuses
/// with VT_ERR_TOO_MANY_BODIES, naming the count. Not a limit on memory (a model is bounded by
/// what memory holds, its sizes counted in size_t and checked): the bound on what the library
/// indexes with int, so that every count times a constant below 128 (7 nbody, 6 nv, 14 nc, ...)
/// fits an int; products of two counts (nc x nv, nv x nv) are formed in size_t.
#define VT_COUNT_MAX (1 << 24)

/// Joint of a body to its reference body: the six rows of the paper's Table 1, and a 6-rate
/// floating joint (VT_JOINT_FREE) beside the paper's 7-rate base body.
typedef enum vt_joint_type {
    VT_JOINT_BASE = 0,       ///< floating: q = x = [r; p] (7), q̇ = ẋ (7); reference must be ground
    VT_JOINT_REVOLUTE,       ///< 1 angle about axis1
    VT_JOINT_UNIVERSAL,      ///< angle about axis1 (fixed on reference), then about axis2 (fixed on body)
    VT_JOINT_SPHERICAL,      ///< q: relative Euler parameters (4); q̇: relative angular velocity (3)
    VT_JOINT_TRANSLATIONAL,  ///< 1 translation along axis1
    VT_JOINT_CYLINDRICAL,    ///< angle about axis1, then translation along axis1
    VT_JOINT_FREE,           ///< floating with 6 rates and no constraint row, any reference body:
                             ///< q (7) = the translation of the body's joint point (joint_child) from
                             ///< the reference body's joint point (joint_parent), reference-body axes,
                             ///< m (3), then the relative Euler parameters (4), as a spherical joint's;
                             ///< q̇ (6) = that translation's rate in reference-body axes, m/s (3), then
                             ///< the relative angular velocity in reference-body axes, rad/s (3). With
                             ///< the ground as reference: the joint point's global position and
                             ///< velocity and the global angular velocity. Joint drives on rates 0..2
                             ///< only (an orientation drive turns it); its reaction is zero by
                             ///< definition, its six efforts are its rates' generalized forces (force
                             ///< in reference axes, moment about the joint point in reference axes)
    VT_JOINT_TYPE_COUNT      ///< number of joint kinds (not a kind)
} vt_joint_type;

/// Options of the whole model.
/// Default of vt_run_options.redundant_band: the band of relative singular values within which
/// the ODE formulation of a dynamic analysis drops a constraint direction of a model that allows
/// redundant rows (what carries it through a singular pose). Not used by a single instant, whose
/// dependent rows are those dependent to round-off (see vt_model_def.allow_redundant).
#define VT_REDUNDANT_TOL 5e-4

/// Which arrays a model's data holds (vt_model_def.layout): what a data costs, and which entry
/// points it serves (docs/guide.md, "Memory").
typedef enum vt_layout {
    VT_LAYOUT_FULL = 0,      ///< default: every entry point. The dense stages' S (7n x nv) and R (nv x 7n),
                             ///< M* (nv x nv), the maximal route's matrix and the dense routes' scratch:
                             ///< O(n²) bytes (about 170 MB for a chain of 1,000 bodies)
    VT_LAYOUT_RECURSIVE = 1  ///< O(n) bytes beside what the constraint rows need (nc x nv): for
                             ///< vt_inverse_dynamics_recursive(), vt_inverse_dynamics_motion(),
                             ///< vt_kinematic_solve() and vt_kinematic_analysis() on the routes that
                             ///< form no M* (joint-driven, given motion of a tree, square, articulated).
                             ///< The dense stages, vt_dynamic_analysis() and an instant that needs M*
                             ///< (base bodies, couplings, redundant rows, a loop's given motion, an
                             ///< ill-conditioned shortcut's fallback) are refused with VT_ERR_LAYOUT
} vt_layout;

typedef struct vt_model_def {
    double gravity[3];  ///< m/s², global; default (0, -9.81, 0): y up, as in the paper's Fig. 4
    double rcond_min;   ///< smallest accepted condition estimate of the pose (vt_data.rcond);
                        ///< below it the solve is refused; default 1e-12
    double rcond_warn;  ///< below this (and above rcond_min) vt_solve succeeds but sets
                        ///< VT_WARN_ILL_CONDITIONED in the data's warning: a pose near a singular one,
                        ///< where efforts grow without bound; default 1e-6
    int allow_redundant;///< 1: constraint rows dependent to round-off (redundant cut joints) are
                        ///< solved instead of refused (VT_ERR_DEPENDENT_CONSTRAINTS): on their
                        ///< independent directions, the multipliers of minimum (scaled) norm,
                        ///< VT_WARN_REDUNDANT set, vt_data.rank and residual filled. Which rows are
                        ///< dependent is decided on Φ_q alone, whatever the units, the axes or the
                        ///< masses (docs/method.md, "Redundant rows"); any other pose, however
                        ///< ill-conditioned, is solved exactly as without the option. The motion
                        ///< q̈ stays unique; a multiplier, and so a drive's effort, and a reaction
                        ///< component may not be (a robot standing on four feet: every torque).
                        ///< vt_data.lambda_unique (per row: a drive's effort at its drive_row),
                        ///< jnt_unique and cut_unique say which are. A dynamic analysis in the ODE
                        ///< formulation may also drop nearly dependent directions
                        ///< (vt_run_options.redundant_band); default 0
    vt_layout layout;   ///< which arrays the model's data holds, and so its size (vt_data_size());
                        ///< default VT_LAYOUT_FULL
    double inertia_tol; ///< relative tolerance of the inertia checks (symmetric, positive semi-definite,
                        ///< triangle inequality), a fraction of the inertia's largest entry, ≥ 0 and
                        ///< < 1: a file whose inertias are off by more than round-off (romeo_small's
                        ///< by 0.18 %: 2e-3) is accepted with a larger one, the symmetric part kept;
                        ///< default VT_INERTIA_TOL
} vt_model_def;

/// Warning flags a successful call may leave in vt_data.warning.
enum {
    VT_WARN_ILL_CONDITIONED = 1, ///< the condition estimate of (5) is below rcond_warn
    VT_WARN_REDUNDANT = 2,       ///< dependent rows (to round-off) were solved on their independent
                                 ///< directions (allow_redundant; vt_data.rank < nc)
    VT_WARN_BAND = 4,            ///< a time analysis's band (vt_run_options.redundant_band) dropped a
                                 ///< direction that is not dependent to round-off: its constraint held
                                 ///< in the least-squares sense (vt_data.residual says how well)
    VT_WARN_LIMIT = 8            ///< some rate's coordinate, rate or effort is beyond its limit
                                 ///< (vt_data.limit_excess says which and by how much; nothing clipped)
};

/// The route by which the last solve found q̈ and λ (vt_data.route). Which route a model and an
/// instant take, and when a faster one gives way: docs/method.md, "The augmented system (5)" and
/// "The recursive evaluation".
typedef enum vt_route {
    VT_ROUTE_NONE = 0,       ///< no solve yet, or the last one failed
    VT_ROUTE_JOINT_DRIVEN,   ///< every rate has a joint drive: q̈ = f'', nothing factorized (recursive)
    VT_ROUTE_FREE_RATES,     ///< every row a joint drive, some rates free: Cholesky of the free rates' M*
    VT_ROUTE_SQUARE,         ///< as many rows as rates: LU of Φ_q
    VT_ROUTE_SCHUR,          ///< fewer rows than rates: Cholesky of M*, then of the rows' Schur complement
    VT_ROUTE_ARTICULATED,    ///< fewer rows than rates, or free rates: articulated bodies, O(n) (recursive)
    VT_ROUTE_AUGMENTED,      ///< the augmented matrix of (5): symmetric indefinite LDL^T
    VT_ROUTE_REDUNDANT,      ///< dependent rows (allow_redundant): SVD, least squares, minimum norm
    VT_ROUTE_MOTION,         ///< the motion given for every rate (vt_inverse_dynamics_motion): nothing solved
    VT_ROUTE_MAXIMAL,        ///< every body's accelerations and joint wrench as unknowns beside q̈ and λ:
                             ///< equilibrated LU (where a free-rate route's estimate fell below rcond_warn)
    VT_ROUTE_COUNT           ///< number of routes (not a route)
} vt_route;

/// Flags in vt_data.fallback: a faster route that the last instant tried and left for a more
/// general one, and why. The general route then decides and diagnoses.
enum {
    VT_FALLBACK_SCHUR_PIVOT = 1,          ///< vt_solve's Schur route: a Cholesky pivot of the scaled M*
                                          ///< below 1e-4 (a motion nearly without inertia)
    VT_FALLBACK_ARTICULATED_PIVOT = 2,    ///< recursive articulated route: a pivot of M* below 1e-8 of
                                          ///< its diagonal entry, or round-off of 0 against the terms
                                          ///< it is summed from
    VT_FALLBACK_ARTICULATED_CONDITION = 4,///< recursive articulated route: rcond below rcond_min, or its
                                          ///< pivots' round-off reaching rcond, or below √rcond_warn
                                          ///< where the maximal route may do better (the dense stages
                                          ///< then solve the instant and decide)
    VT_FALLBACK_SQUARE_CONDITION = 8,     ///< recursive square route: rcond below rcond_min
    VT_FALLBACK_COMPOSITE_ROUNDOFF = 16,  ///< recursive general route: M* formed from composite inertias
                                          ///< about o, or Q about o, is not known to one digit at its rcond
                                          ///< (a mechanism long against its bodies' radii of gyration, a
                                          ///< huge load near a rate's axis), or it found the
                                          ///< instant singular (a verdict the dense stages give): the
                                          ///< instant was computed by the dense stages (vt_inverse_dynamics)
    VT_FALLBACK_SCHUR_CONDITION = 32,     ///< vt_solve's Schur route: its estimate below rcond_warn (the
                                          ///< rows' Schur complement can lose digits the whole matrix
                                          ///< keeps); the augmented route's estimate is reported
    VT_FALLBACK_MAXIMAL_CONDITION = 64    ///< a free-rate route's estimate below rcond_warn (M* and Q
                                          ///< sum each subtree's terms: a tiny driven link carrying a
                                          ///< huge free body); the maximal-coordinate route's answer and
                                          ///< estimate, the higher one, are reported (VT_ROUTE_MAXIMAL)
};

/// Prescribed function of time f(t), evaluated exactly with f' and f''.
typedef enum vt_function_type {
    VT_FUNCTION_CONSTANT = 0,  ///< f = c[0]
    VT_FUNCTION_POLYNOMIAL,    ///< f = c[0] + c[1] t + ... + c[ncoef-1] t^(ncoef-1)
    VT_FUNCTION_SINE,          ///< f = c[0] + c[1] sin(c[2] t + c[3])
    VT_FUNCTION_CALLBACK,      ///< f, f', f'' from a user function
    VT_FUNCTION_SPLINE         ///< C2 cubic interpolating spline through samples (t_k, y_k), k = 0..n−1:
                               ///< n = 2 a straight line, n = 3 the parabola through the three, n ≥ 4
                               ///< "not-a-knot" ends (f''' continuous at t_1 and t_{n−2}); outside
                               ///< [t_0, t_{n−1}] the end cubics continued (see vt_function_spline())
} vt_function_type;

/// User time function: writes f, f' and f'' at time t (s) into out; returns 0 on success,
/// anything else is an error that the library reports as VT_ERR_CALLBACK.
typedef int (*vt_function_callback)(double t, double out[3], void *user);

#define VT_POLY_MAX 8  ///< most coefficients of a polynomial time function
/// Most samples of a spline that vt_function_eval() evaluates before the spline is added to a
/// drive (it then solves for the second derivatives in a fixed local buffer); a model's drives
/// carry their own second derivatives and have no limit.
#define VT_SPLINE_EVAL_MAX 64

/// A time function; make it with vt_function_constant() and friends.
typedef struct vt_function {
    vt_function_type type;        ///< which kind (the meaning of c)
    int ncoef;                    ///< polynomial: number of coefficients (1..VT_POLY_MAX)
    double c[VT_POLY_MAX];        ///< coefficients, see vt_function_type
    vt_function_callback callback;///< VT_FUNCTION_CALLBACK only
    void *user;                   ///< passed to callback
    int nsample;                  ///< spline: number of samples n (≥ 2)
    const double *sample_t;       ///< spline: sample times t_k, s, strictly increasing (n)
    const double *sample_y;       ///< spline: sample values y_k, the drive's unit (n)
    const double *sample_d2;      ///< spline: f''(t_k) (n); set by the library in a model's drives (the
                                  ///< samples and these then live in the model), NULL from
                                  ///< vt_function_spline() and ignored when a drive is added
} vt_function;

/// User orientation: writes the prescribed Euler parameters p (global, unit), angular
/// velocity w (rad/s, global) and angular acceleration wdot (rad/s², global) at time t;
/// returns 0 on success.
typedef int (*vt_orientation_callback)(double t, double p[4], double w[3], double wdot[3], void *user);

/// Kinds of drive (driving constraint).
typedef enum vt_drive_type {
    VT_DRIVE_JOINT = 0,    ///< a rate's coordinate of a body's joint follows f(t): q_k − f(t) = 0
    VT_DRIVE_POINT,        ///< one global component of a body point follows f(t), (30)-(34)
    VT_DRIVE_ORIENTATION,  ///< a body's orientation follows p_d(t): 2 G(p_d) p = 0 (3 rows)
    VT_DRIVE_RELATIVE_ORIENTATION, ///< body's orientation relative to body `reference` follows p_d(t):
                           ///< 2 G(p_d) (p_a* ⊗ p_b) = 0 (3 rows), reacting on both bodies; with
                           ///< reference −1 a joint's drive (a spherical joint's q follows p_d)
    VT_DRIVE_TYPE_COUNT    ///< number of drive kinds (not a kind)
} vt_drive_type;

/// A drive. Fill from vt_default_drive_def().
typedef struct vt_drive_def {
    vt_drive_type type;    ///< default VT_DRIVE_JOINT
    int body;              ///< driven body (joint drive: the body whose joint is driven); default 1
    int index;             ///< joint drive: which rate of the joint (0-based; not a spherical joint's
                           ///< nor a base body's Euler parameters nor a free joint's rotation rates
                           ///< 3..5); point drive: component 0 = x,
                           ///< 1 = y, 2 = z; default 0
    double point[3];       ///< point drive: the point, m, body axes from the centre of mass; default 0
    vt_function f;         ///< joint drive: rad or m; point drive: m; orientation drives: the angle (rad)
                           ///< turned about `axis`, or the first angle of `sequence`; default constant 0
    double axis[3];        ///< orientation drives: axis of the prescribed turn (absolute: global; relative:
                           ///< the reference body's axes); normalized; default z; unused with `sequence`
    double orientation[4]; ///< orientation drives: orientation at angle 0 (Euler parameters, global or
                           ///< relative to the reference body's axes): p_d(t) = [rotation f(t) about
                           ///< axis] ⊗ orientation, or R_1(f) ⊗ R_2(f2) ⊗ R_3(f3) ⊗ orientation with
                           ///< `sequence`; default identity
    vt_orientation_callback orientation_callback; ///< orientation drives: if set, gives p_d(t) (and its
                           ///< ω, ω̇: global, or in the reference body's axes for a relative drive)
    void *user;            ///< passed to orientation_callback
    const char *name;      ///< the drive's name (copied; in a model: its own copy); default NULL
    const char *frame;     ///< point drive: the name of a frame added so far; its body and origin
                           ///< replace body and point (in a model: NULL); default NULL
    int reference;         ///< relative orientation drive: body a, relative to whose axes body `body`'s
                           ///< orientation is prescribed: 0 = ground, 1..n a body added so far, ≠ body;
                           ///< −1 (default) = the body's joint: a = its parent and p_d is the joint's
                           ///< own rotation p_J (a spherical joint's q), the body's `orientation` at
                           ///< q = 0 appended by the builder (a model stores a and that orientation)
    const char *sequence;  ///< orientation drives: NULL (default) a turn about `axis` by f; or three
                           ///< angles f, f2, f3 (rad) about the named axes in turn: "ZYX", "XYZ", "ZXZ"…
                           ///< (upper case: body-fixed, each turn about the axis as already turned,
                           ///< R_1 ⊗ R_2 ⊗ R_3; lower case "zyx"…: about the fixed axes, first f about
                           ///< the first letter, so R_3 ⊗ R_2 ⊗ R_1); no letter twice in a row; in a
                           ///< model the library's own copy
    vt_function f2;        ///< with `sequence`: the second angle (rad); default constant 0
    vt_function f3;        ///< with `sequence`: the third angle (rad); default constant 0
} vt_drive_def;

/// A cut joint: closes a loop between body_a (in the role of the reference body) and body_b,
/// with the joint kinds of Table 1 except base (and not free: neither constrains anything). Equations: spherical 3 (points coincide),
/// revolute 5 (and axes parallel), universal 4 (points coincide, axis1 on a ⟂ axis2 on b),
/// cylindrical 4 (axes parallel, b's point on a's axis line), translational 5 (cylindrical and
/// no turn about the axis), and with `planar` a revolute's 2 in-plane equations alone (planar
/// loops). Fill from vt_default_cut_joint_def().
typedef struct vt_cut_joint_def {
    vt_joint_type joint;   ///< default VT_JOINT_REVOLUTE
    int body_a;            ///< 0 = ground allowed; default 0
    int body_b;            ///< ≠ body_a; default 1
    double point_a[3];     ///< m, joint point on a, a's axes from its centre of mass (global for ground);
                           ///< default 0
    double point_b[3];     ///< m, joint point on b, b's axes from its centre of mass; default 0
    double axis1[3];       ///< first axis, a's axes; normalized; default z
    double axis2[3];       ///< universal: second axis (on b) in a's axes when assembled; default x
    double orientation[4]; ///< b's axes relative to a's when assembled (carries the axes onto b);
                           ///< default identity
    const char *name;      ///< the cut joint's name (copied; in a model: its own copy); default NULL
    const char *frame_a;   ///< the name of a frame added so far: its body and origin replace body_a
                           ///< and point_a (the axes stay in a's body axes); NULL: as given; default NULL
    const char *frame_b;   ///< the same for body_b and point_b; default NULL
    int planar;            ///< 1: a planar loop's pin (joint VT_JOINT_REVOLUTE only; the builder refuses
                           ///< it with another kind): the two equations of the joint point in the plane
                           ///< ⟂ axis1, [u1 u2]^T (P_b − P_a) = 0 with u1, u2 ⟂ axis1 fixed on a, so a
                           ///< planar loop is exactly constrained (no allow_redundant). The points may
                           ///< part along axis1 and b may tilt: the reaction is the in-plane force alone
                           ///< (cut_force ⟂ axis1; its component along axis1 and cut_moment zero), the
                           ///< out-of-plane loads go through the tree joints. On a loop that is not
                           ///< planar the rows fix less than a full pin would. Default 0 (all 5 rows)
} vt_cut_joint_def;

/// A coupling of two joint coordinates, q_a = ratio q_b + offset (a URDF mimic joint, a gear
/// pair, a belt): one constraint row, Φ = q_a − ratio q_b − offset, whose multiplier is the
/// generalized force the coupling exerts on rate a (−ratio times it on rate b), reported in
/// vt_data.coupling_effort; like an applied generalized force it is not part of the joint
/// reactions. Both coordinates must be scalar (not a spherical joint's or a base body's, nor a
/// free joint's rotation).
/// Fill from vt_default_coupling_def().
typedef struct vt_coupling_def {
    int body_a;            ///< the body whose joint's coordinate follows; default 2
    int index_a;           ///< which rate of that joint (0-based); default 0
    int body_b;            ///< the body whose joint's coordinate leads; default 1
    int index_b;           ///< which rate of that joint; default 0
    double ratio;          ///< q_a per q_b (a rad/rad, m/m, m/rad or rad/m ratio); default 1
    double offset;         ///< q_a at q_b = 0, rad or m; default 0
    const char *name;      ///< the coupling's name (copied; in a model: its own copy); default NULL
} vt_coupling_def;

/// A moving body and the joint that connects it to its reference body.
/// Fill from vt_default_body_def() and set only what the scene needs.
typedef struct vt_body_def {
    int parent;                 ///< reference body id, 0 = ground, else an earlier body; default 0
    vt_joint_type joint;        ///< joint to the reference body; default VT_JOINT_REVOLUTE
    double mass;                ///< kg, ≥ 0 (0: a massless link; a solve it leaves without inertia on a
                                ///< free rate fails, naming it); default 1
    double inertia[9];          ///< kg·m², about the centre of mass in body axes, 3x3 column-major;
                                ///< default 0 (a point mass)
    double joint_parent[3];     ///< m, joint point on the reference body, in its body axes from its
                                ///< centre of mass (global coordinates if the reference is ground); default 0
    double joint_child[3];      ///< m, joint point on this body, in its body axes from its centre of mass;
                                ///< default 0
    double axis1[3];            ///< first joint axis, reference-body axes at q = 0; normalized; default (0,0,1)
    double axis2[3];            ///< universal only: second axis (fixed on this body), reference-body axes at
                                ///< q = 0, perpendicular to axis1 (a cosine up to 1e-9 is accepted and
                                ///< removed: axis2 less its part along axis1); normalized; default (1,0,0)
    double orientation[4];      ///< Euler parameters of this body's axes relative to the reference body's
                                ///< at q = 0 (for a base body: ignored); normalized; default (1,0,0,0)
    const char *name;           ///< the body's name (copied); NULL or "": unnamed; default NULL
    const char *joint_name;     ///< its joint's name (copied); NULL or "": unnamed; default NULL
    double limit_lower[2];      ///< the joint's first two rates (revolute, translational: the first one;
                                ///< universal, cylindrical: both): lowest coordinate, rad or m; kept in
                                ///< the model (vt_model.dof_limit), not enforced; default −∞
    double limit_upper[2];      ///< highest coordinate (≥ limit_lower); default +∞
    double limit_velocity[2];   ///< largest |rate|, rad/s or m/s (≥ 0); default +∞
    double limit_effort[2];     ///< largest |effort|, N·m or N (≥ 0); default +∞
    /* The joint's own effects on its first two rates (as the limits), which the efforts include
     * (docs/guide.md, "Real joints"): a rate's effort is its rigid-body part plus
     * armature q̈ + damping q̇ + friction s(q̇), and a rate no drive fixes feels them as passive
     * forces. Spherical, free and base joints have none. */
    double armature[2];         ///< reflected rotor inertia, kg·m² (turning) or kg (sliding), ≥ 0; default 0
    double damping[2];          ///< viscous damping, N·m·s/rad or N·s/m, ≥ 0; default 0
    double friction[2];         ///< Coulomb friction, N·m or N, ≥ 0: s(q̇) = sign(q̇), 0 at q̇ = 0; default 0
    double friction_velocity[2];///< rad/s or m/s, ≥ 0: where > 0 the smooth law s(q̇) = tanh(q̇ / v) (for a
                                ///< forward run: no jump at rest); default 0 (the sign)
    double gear_ratio[2];       ///< N ≠ 0: armature, damping and friction are stated on the motor's side of
                                ///< a gear of ratio N (motor turns per joint turn) and taken as N² J, N² b
                                ///< and |N| f on the joint's; default 1
    double joint_frame[4];      ///< the joint's frame: its axes relative to this body's axes (Euler
                                ///< parameters), its origin the joint point; it moves with the body and
                                ///< is where vt_data.jnt_force_joint and the bearing split are read (a
                                ///< URDF joint: the child link's frame, the URDF joint frame at q = 0).
                                ///< Normalized; all zero (default): the frame that vt_model.jnt_frame
                                ///< documents for the joint's kind
} vt_body_def;

/// A joint's own effects on its first two rates, as vt_body_def's fields of the same names, to set
/// on a body already in a builder (vt_builder_set_joint_effects()). Fill from
/// vt_default_joint_effects_def().
typedef struct vt_joint_effects_def {
    double armature[2];          ///< kg·m² or kg, ≥ 0; default 0
    double damping[2];           ///< N·m·s/rad or N·s/m, ≥ 0; default 0
    double friction[2];          ///< N·m or N, ≥ 0; default 0
    double friction_velocity[2]; ///< rad/s or m/s, ≥ 0 (0: the sign); default 0
    double gear_ratio[2];        ///< ≠ 0: the values above on the motor's side; default 1
} vt_joint_effects_def;

/// A frame: a named point and orientation moving with a body (a tool point, a sensor, a file's
/// link frame). Fill from vt_default_frame_def().
typedef struct vt_frame_def {
    const char *name;           ///< required, unique among the frames (copied); default NULL
    int body;                   ///< the body it moves with, 0 = ground; default 1
    double point[3];            ///< m, its origin: body axes from the centre of mass (global for the
                                ///< ground); default 0
    double orientation[4];      ///< its axes relative to the body's (Euler parameters); normalized;
                                ///< default identity
    const char *reference;      ///< the name of a frame added so far (a tool frame on a URDF link's):
                                ///< point and orientation are then in that frame's axes from its
                                ///< origin, and body is its body (in a model: NULL); NULL (default):
                                ///< as given
} vt_frame_def;

/// A rigid body fixed to a body of the builder (a payload, a tool), or that body's own mass
/// properties (vt_builder_add_payload(), vt_builder_set_mass()). Fill from vt_default_payload_def().
typedef struct vt_payload_def {
    int body;                   ///< the body it is fixed to, 1..n (vt_builder_find_body() finds it by
                                ///< name); default 1; unused with `frame`
    const char *frame;          ///< the name of a frame added so far (a URDF link's): its body is the
                                ///< body, and point and inertia are in the frame's axes from its
                                ///< origin; NULL (default): in the body's axes from its centre of mass
    double mass;                ///< kg, ≥ 0; default 0
    double point[3];            ///< m, its centre of mass; default 0
    double inertia[9];          ///< kg·m², about its centre of mass, 3x3 column-major, checked as a
                                ///< body's (vt_model_def.inertia_tol); default 0 (a point mass)
} vt_payload_def;

/// The immutable model. Built by vt_builder_build(); read-only afterwards.
typedef struct vt_model {
    int nbody;               ///< number of moving bodies n (ids 1..n)
    int nq;                  ///< length of q
    int nv;                  ///< length of q̇ (and of Q, rows of M*)
    int nx;                  ///< 7 * nbody: length of the Cartesian vector x
    double gravity[3];       ///< m/s², global

    /* per body, nbody+1 entries, entry 0 = ground */
    int *body_parent;        ///< reference body id (nbody+1); -1 for the ground
    int *body_joint;         ///< vt_joint_type of the joint to the reference body (nbody+1)
    int *body_qadr;          ///< first index of the joint's coordinates in q (nbody+1)
    int *body_nq;            ///< number of joint position coordinates (nbody+1)
    int *body_vadr;          ///< first index of the joint's rates in q̇ (nbody+1)
    int *body_nv;            ///< number of joint rates (nbody+1)
    double *body_mass;       ///< kg (nbody+1)
    double *body_inertia;    ///< kg·m², body axes about the centre of mass, 3x3 col-major (9 x (nbody+1))
    double *body_jpar;       ///< m, joint point on the reference body, its axes (3 x (nbody+1))
    double *body_jchild;     ///< m, joint point on the body, its axes (3 x (nbody+1))
    double *body_axis;       ///< unit axis1 and axis2 in reference axes at q = 0 (6 x (nbody+1))
    double *body_quat0;      ///< orientation relative to the reference at q = 0 (4 x (nbody+1))

    /* the tree's reference (path) structure: body i's path is the rates of its own joint and of
     * every joint between it and the ground, the columns of S non-zero in its rows. The model
     * keeps each path's length and each rate's link to the rate before it, not the lists
     * (n(n+1)/2 rates for a chain of n), so that it is O(n): i's path is dof_parent walked from
     * its joint's last rate, body_vadr[i] + body_nv[i] − 1, down to −1 (descending) */
    int *body_pathnum;       ///< number of rates on the path from the root to the body (nbody+1)
    int maxpath;             ///< largest body_pathnum
    int *dof_body;           ///< body whose joint owns each rate (nv)
    int *dof_parent;         ///< the rate before each on its path: its joint's previous rate, or for a
                             ///< joint's first the last rate of its reference body's joint; −1 at
                             ///< the ground (nv)

    double *q0;              ///< reference configuration: zero angles and translations, unit
                             ///< Euler parameters (nq)
    double *dof_limit;       ///< per rate: lowest and highest coordinate, largest |rate| and |effort|
                             ///< from the body definitions, ±∞ where none (4 x nv)
    double *dof_effects;     ///< per rate: armature, damping, friction and friction velocity on the
                             ///< joint's side (gear ratio applied), 0 where none (4 x nv)

    /* names (VT_NAME_MAX bytes each, "" where unnamed) and frames */
    char *body_name;         ///< body i's name at body_name + VT_NAME_MAX i; the ground's is "" (nbody+1)
    char *joint_name;        ///< the name of body i's joint, the same way (nbody+1)
    char *drive_name;        ///< (ndrive)
    char *cut_name;          ///< (ncut)
    char *coupling_name;     ///< (ncoupling)
    int nframe;              ///< number of frames
    char *frame_name;        ///< (nframe)
    int *frame_body;         ///< the body each frame moves with (nframe)
    double *frame_point;     ///< m, its origin, the body's axes from its centre of mass (3 x nframe)
    double *frame_quat;      ///< its axes relative to the body's (4 x nframe)

    /* drives, cut joints and constraint rows */
    double rcond_min;        ///< see vt_model_def
    double rcond_warn;       ///< see vt_model_def
    int allow_redundant;     ///< see vt_model_def
    vt_layout layout;        ///< see vt_model_def
    int ndrive;              ///< number of drives
    int ncut;                ///< number of cut joints
    int nc;                  ///< number of constraint rows (drives, cut joints, couplings, one p^T p − 1
                             ///< per base body, in that order)
    vt_drive_def *drive;     ///< the drives, validated and normalized (ndrive)
    int *drive_row;          ///< first constraint row of each drive (ndrive)
    vt_cut_joint_def *cut;   ///< the cut joints, validated and normalized (ncut)
    int *cut_row;            ///< first constraint row of each cut joint (ncut)
    int ncoupling;           ///< number of couplings
    vt_coupling_def *coupling; ///< the couplings, validated (ncoupling)
    int *coupling_row;       ///< the constraint row of each coupling (ncoupling)
    int *con_body;           ///< the two bodies of each row: a (0 = ground) then b (2 x nc)
    int *con_owner;          ///< the drive, cut joint or base body a row belongs to (nc)
    int *dof_drive;          ///< the joint drive of each rate, −1 if none (nv)
    double *jnt_frame;       ///< each joint's frame (vt_body_def.joint_frame): its axes relative to the
                             ///< body's axes, Euler parameters (4 x (nbody+1)); origin the joint point,
                             ///< fixed on the body. Where the definition gave none (all zero), with a
                             ///< the joint's axis in body axes (axis1 carried by the orientation at
                             ///< q = 0; fixed on the body): revolute, translational and cylindrical
                             ///< joints: z along a, x the body axis least aligned with a (the first of
                             ///< x, y, z on a tie) less its part along a, y = z × x (the body's axes
                             ///< when a is its z); universal: z along axis1 and x along axis2 as at
                             ///< q = 0, y = z × x; spherical, free and base: the body's axes. The
                             ///< ground's: identity
    double *jnt_frame_axis;  ///< the joint's bearing axis, unit, in its frame (3 x (nbody+1)): revolute,
                             ///< translational, cylindrical: axis1; universal: axis2, the axis fixed on
                             ///< the body (its own pin of the cross); spherical, free, base and the
                             ///< ground: 0 (no axis: vt_data.jnt_bearing then holds the magnitudes)

    /* internal: the implementation's row tables and route selectors, read by src/ only; not
     * part of the API (their meaning may change in any release) */
    int *con_kind;           ///< internal: kind of each row (nc)
    int *con_dof;            ///< internal: joint-drive rows: the driven rate; orientation rows: 0..2 (nc)
    double *con_vec;         ///< internal: direction on a then on b (6 x nc)
    double *con_point;       ///< internal: point on a then on b (6 x nc)
    int joint_driven;        ///< internal: every rate has exactly one joint drive, no other row
    int joint_rows_only;     ///< internal: every row a joint drive on a rate of its own, some rates free
    int joint_mix;           ///< internal: 1 every joint revolute, 0 some other but no base body, −1 a base body
    int has_quaternions;     ///< internal: 1 if some joint's q holds Euler parameters (spherical, free, base)
    double bound_length;     ///< internal: m, Σ of the joints' offsets |s^{ij}| + |s^{ji}| over the bodies
    double bound_mass;       ///< internal: the largest m + 3 max |J_kl| of a body
    double mass_spread;      ///< internal: the largest body mass over the smallest positive one
    int has_effects;         ///< internal: some rate has armature, damping or friction
    double bound_effect[3];  ///< internal: the largest armature, damping and friction of a rate
    double *jnt_frame_A;     ///< internal: jnt_frame as a rotation, joint frame → body axes, 3x3
                             ///< col-major (9 x (nbody+1))
    int any_limit;           ///< internal: 1 if some entry of dof_limit is finite (else no instant
                             ///< compares with them: vt_data.limit_excess stays 0)
} vt_model;

/// Scratch space of the stages, inside the data (opaque; its size is fixed by the model).
typedef struct vt_arena vt_arena;

/// The data of one model: inputs, every result, and one scratch arena. Allocated once by
/// vt_data_create(), or laid out in the caller's buffer by vt_data_init(); no stage allocates.
/// Fields are grouped by the stage that fills them.
typedef struct vt_data {
    const vt_model *model;   ///< the model this data was made for
    void *block;             ///< the allocation vt_data_free() releases (vt_data_create()); NULL when
                             ///< the memory is the caller's (vt_data_init()): vt_data_free() then does nothing

    /* state and loads: set by the caller */
    double time;             ///< s, the instant: drives' time functions are evaluated here
    double *q;               ///< generalized positions (nq): each body's joint coordinates from
                             ///< body_qadr (a spherical joint's and a free joint's Euler parameters
                             ///< among them, vt_joint_type)
    double *qd;              ///< generalized velocities (nv): each body's joint rates from body_vadr (a
                             ///< spherical or free joint's: angular velocity components, not q's
                             ///< derivatives)
    double *xfrc;            ///< applied force (N) and moment (N·m) on each body, global, moment about
                             ///< the centre of mass: [f; n] (6 x (nbody+1)); see vt_add_point_load()
    double *qfrc;            ///< applied generalized force per rate (N·m or N), added to Q; acts on
                             ///< the rate's body and, opposite, on its reference body (nv); default 0

    /* vt_kinematics(): positions, velocities, S and Ṡq̇ */
    double *x;               ///< Cartesian coordinates [r; p] (7n), eq (1)
    double *xd;              ///< Cartesian velocities ẋ = S q̇ (7n)
    double *A;               ///< rotation body → global, 3x3 col-major (9 x (nbody+1))
    double *omega;           ///< angular velocity, global, rad/s (3 x (nbody+1))
    double *jaxis;           ///< current global unit axes e_k of each body's joint (9 x (nbody+1));
                             ///< the rows past the joint's own axes are 0
    double *jsij;            ///< s^{ij}: reference origin → joint point on reference, global (3 x (nbody+1))
    double *jd;              ///< d^i = -s^{ji} + Σ ε_k q_k e_k, eq (17), global (3 x (nbody+1))
    double *jpoint;          ///< joint point on the body, global position (3 x (nbody+1))
    double *twist;           ///< twist of each rate about the reference point o (origin), [ω; v] (6 x nv):
                             ///< v is the velocity of the point at o; body i's S column is
                             ///< ṙ = v + ω × (r^i − o), ṗ = ½ E^T ω (15)-(16) (vt_kinematics)
    double *xrel;            ///< m, body i's centre of mass and joint point from o, [r^i − o; P_i − o]
                             ///< (6 x (nbody+1); the ground's [−o; −o]): the lever arms of the twists
                             ///< and wrenches, exact to their own size whatever |o|
    double origin[3];        ///< m, the reference point o of twist and xrel: body 1's joint point at this
                             ///< instant (its position for a base joint; 0 without bodies), so that lever
                             ///< arms stay short when the mechanism stands far from the global origin
    double *S;               ///< velocity transformation, ẋ = S q̇ (7n x nv, leading dimension 7n)
    double *Sdqd;            ///< Ṡ q̇ (7n): the Cartesian accelerations at q̈ = 0

    /* vt_inverse_transform(): R */
    double *R;               ///< inverse velocity transformation, q̇ = R ẋ (nv x 7n, leading dimension nv)

    /* vt_mass_matrix(): M and M* */
    double *Mp;              ///< rotational block 4 G^T J' G of each body's M^i (16 x (nbody+1))
    double *Mstar;           ///< M* = S^T M S, eq (3) (nv x nv, leading dimension nv)

    /* vt_forces(): F, h and Q */
    double *F;               ///< Cartesian applied force: gravity and xfrc, eq (7),(9) (7n)
    double *h;               ///< -Ṁẋ + (∂T/∂x)^T: per body [0; -8 Ġ^T J' G ṗ] (7n)
    double *Q;               ///< Q = S^T [F - M Ṡq̇ + h], eq (4) (nv)

    /* vt_constraints(): Φ(x, t), Φ_x, Φ_q = Φ_x S (22), Φ_t, γ (23) */
    double *Phi;             ///< constraint values (nc)
    double *Phix;            ///< Φ_x of each row on its bodies a and b: [Φ_{x^a} Φ_{x^b}] (14 x nc)
    double *Phiq;            ///< Φ_q (nc x nv, leading dimension nc)
    double *Phit;            ///< ∂Φ/∂t (nc)
    double *gamma;           ///< γ = −Φ̈ at q̈ = 0 (nc)

    /* vt_solve(): the augmented system (5) */
    double *qdd;             ///< q̈ (nv)
    double *lambda;          ///< Lagrange multipliers λ of M* q̈ = Q + Φ_q^T λ (2), one per constraint
                             ///< row: drives, then cut joints, then base bodies' p^T p − 1 (nc)
    vt_route route;          ///< the route by which the last solve found q̈ and λ (VT_ROUTE_NONE after a failure)
    int fallback;            ///< VT_FALLBACK_* flags: faster routes the last instant left, and why (0: none)
    double rcond;            ///< condition estimate of the pose, in (0, 1]: 1 when joint drives fix every
                             ///< rate, falling toward 0 as the pose nears a singular one; below
                             ///< rcond_warn the solve warns, below rcond_min it refuses. Independent of
                             ///< the units and of the scene's frame; the same on the dense and recursive
                             ///< paths (its definition on each route: docs/method.md, "The condition
                             ///< estimate"). After a failure: what the failed route measured, 0 if
                             ///< nothing
    int warning;             ///< VT_WARN_* flags of the last vt_solve (0: none, and after a failure)
    int rank;                ///< rank of Φ_q found by the last solve (nc when the rows are independent;
                             ///< after a failure what it found, 0 if nothing)
    double residual;         ///< max |Φ_q q̈ − γ| over all rows after a redundant solve (0 otherwise)
    int *lambda_unique;      ///< 0 where a multiplier is not unique (redundant rows), else 1 (nc)
    double *lambda_null;     ///< redundant rows: the nc − rank multiplier directions z with Φ_q^T z = 0,
                             ///< one column each (nc x nc, leading dimension nc; the first nc − rank used)

    /* vt_reactions(): efforts (24) and joint reactions (25)-(28); all global unless "body" */
    double *xdd;             ///< ẍ = S q̈ + Ṡ q̇ (7n)
    double *alpha;           ///< angular acceleration of each body, global, rad/s²: α = ω̇ = 2 E p̈ (3 x
                             ///< (nbody+1); the ground's 0); every instant path fills it
    double *qfrc_drive;      ///< generalized force of all drives, Φ_q^T λ over the drives' rows (nv):
                             ///< the joint torques and forces that produce the motion; with the motion
                             ///< given (vt_inverse_dynamics_motion), every rate's: M* q̈ − Q (a free
                             ///< joint's six: the force and the moment about its joint point, in the
                             ///< reference body's axes, N and N·m)
    double *effort_armature; ///< the part of each rate's effort (qfrc_drive) its joint's armature takes,
                             ///< armature q̈ (nv); 0 without joint effects (vt_body_def.armature)
    double *effort_damping;  ///< the part damping takes, damping q̇ (nv)
    double *effort_friction; ///< the part friction takes, friction s(q̇) (nv). On a rate no drive
                             ///< fixes they are passive forces, −(the three), in its dynamics
    double *drive_effort;    ///< joint drive: generalized force along its coordinate Φ_q^T λ (N·m or N);
                             ///< point drive: force along its component (N); orientation drives: 0 (ndrive)
    double *drive_force;     ///< force the drive exerts on its body (3 x ndrive), N
    double *drive_moment;    ///< moment the drive exerts on its body about the drive's point (the joint
                             ///< point for a joint drive, the body point for a point drive, the centre
                             ///< of mass for an orientation drive) (3 x ndrive), N·m; a relative
                             ///< orientation drive exerts a pure moment: this on `body`, its opposite on
                             ///< `reference` (its drive_force is 0)
    double *jnt_force;       ///< reaction force of the reference body on the body at the joint point
                             ///< (3 x (nbody+1)), N; zero for a free joint (it transmits nothing)
    double *jnt_moment;      ///< reaction moment, about the joint point (3 x (nbody+1)), N·m
    double *jnt_force_body;  ///< the same in the body's axes, (27) (3 x (nbody+1))
    double *jnt_moment_body; ///< the same in the body's axes, (28) (3 x (nbody+1))
    double *jnt_force_total; ///< the total the joint transmits: its reaction plus its actuation, force of
                             ///< the reference body on the body at the joint point (3 x (nbody+1)), N,
                             ///< global. Actuation: the generalized forces along the joint's own rates —
                             ///< its joint drives' efforts (every rate's qfrc_drive with the motion given,
                             ///< vt_inverse_dynamics_motion), the applied qfrc and the couplings' forces —
                             ///< each as a force along a translational axis or a moment about a rotational
                             ///< one (a free joint: its six efforts; a base body's: at its centre of mass,
                             ///< moved to the joint point). Point and orientation drives act on bodies,
                             ///< not along rates: not included. Equals the Newton–Euler wrench of the
                             ///< subtree outboard of the joint less the loads on it from outside
                             ///< (gravity, xfrc, cut joints, point and orientation drives)
    double *jnt_moment_total;///< its moment about the joint point (3 x (nbody+1)), N·m, global
    double *jnt_force_total_body;  ///< jnt_force_total in the body's axes (3 x (nbody+1)), N
    double *jnt_moment_total_body; ///< jnt_moment_total in the body's axes (3 x (nbody+1)), N·m
    double *cut_force;       ///< cut joint: force of body_a on body_b at point_b (3 x ncut), N
    double *cut_moment;      ///< cut joint: moment of body_a on body_b about point_b (3 x ncut), N·m
    double *cut_force_body;  ///< the same in body_b's axes (3 x ncut)
    double *cut_moment_body; ///< the same in body_b's axes (3 x ncut)
    double *coupling_effort; ///< each coupling's generalized force on its rate a, N·m or N; −ratio times
                             ///< it acts on rate b (ncoupling)
    int *jnt_unique;         ///< per reaction component (fx fy fz nx ny nz, global): 0 where a tree
                             ///< joint's reaction is not unique (redundant rows), else 1 (6 x (nbody+1))
    int *cut_unique;         ///< the same for the cut joints (6 x ncut)
    double *jnt_force_joint; ///< jnt_force in the joint's frame (vt_model.jnt_frame) (3 x (nbody+1)), N;
                             ///< filled by vt_reactions_joint_frame() after an instant (on demand)
    double *jnt_moment_joint;///< jnt_moment (about the joint point) in the joint's frame (3 x (nbody+1)), N·m
    double *jnt_bearing;     ///< each joint's reaction split along its bearing axis a (vt_model.jnt_frame_axis),
                             ///< 4 x (nbody+1): axial force a · f (N, signed), radial force |f − (a · f) a|
                             ///< (N, ≥ 0), axial moment a · n (N·m, signed), tilting moment
                             ///< |n − (a · n) a| (N·m, ≥ 0), f and n the reaction (jnt_force,
                             ///< jnt_moment). Without an axis (spherical, free, base): 0, |f|, 0, |n|
    double *limit_excess;    ///< per rate, how far beyond its limits (vt_model.dof_limit) the instant is
                             ///< (3 x nv): the coordinate (q − upper above it, q − lower below it; a
                             ///< spherical, free or base joint's rates have none), the rate (q̇ − max
                             ///< above max, q̇ + max below −max) and the effort qfrc_drive (the same
                             ///< with the effort limit); 0 within, a value exactly at a limit
                             ///< included. Filled by every call that fills qfrc_drive; nothing is
                             ///< clipped
    int nlimit;              ///< number of non-zero entries of limit_excess (VT_WARN_LIMIT set when > 0)

    vt_arena *arena;         ///< scratch of the stages: internal, sized when the data is laid out
    int ida_flag;            ///< return code of the last failing IDA call (0 if none)

    char message[VT_MESSAGE_SIZE]; ///< detail of the last failed call on this data (a successful
                                   ///< call need not clear it: read it after a failure)
} vt_data;

/// Progress of a run: called at every output time; a non-zero return stops the run
/// (VT_ERR_ABORTED).
typedef int (*vt_progress_callback)(double t, double t_end, void *user);

/// Which contacts are on the ground at time t (vt_run_options.contact_schedule): sets active[c]
/// (nonzero: on the ground, its force free; 0: in the air, its force zero) for each of the run's
/// contacts, in the order of their definitions (every entry is 1 on the call); returns 0 on
/// success, anything else is an error that the library reports as VT_ERR_CALLBACK.
typedef int (*vt_contact_schedule)(double t, int *active, void *user);

/// The wrenches the environment applies at a run's frames at time t (vt_run_options.loads): writes
/// w[6 k .. 6 k + 5] for each of the nload frames, the force (N) then the moment about the frame's
/// origin (N·m), global axes (a tool pressing a part, a measured process force); returns 0 on
/// success, anything else is an error that the library reports as VT_ERR_CALLBACK.
typedef int (*vt_load_callback)(double t, double *w, void *user);

/// The most wrenches at frames a run takes (vt_run_options.nload).
#define VT_RUN_LOADS_MAX 64

/// How a dynamic analysis hands (5) to IDA (docs/method.md, "Analyses over time").
typedef enum vt_formulation {
    VT_FORMULATION_INDEX1 = 0,  ///< (5) as it stands: acceleration-level constraints; Φ and Φ̇ drift
    VT_FORMULATION_BAUMGARTE,   ///< Φ̈ + 2α Φ̇ + β² Φ = 0 in place of Φ̈ = 0
    VT_FORMULATION_PROJECTION,  ///< index-1, with q and q̇ projected onto Φ = 0 and Φ_q q̇ = −Φ_t at
                                ///< every output time (least-norm corrections; IDA restarted)
    VT_FORMULATION_GGL,         ///< stabilized index-2 (Gear–Gupta–Leimkuhler): Φ = 0 and Φ_q q̇ = −Φ_t
                                ///< enforced, q' = T (q̇ + Φ_q^T μ); λ and μ out of the error test
    VT_FORMULATION_ODE,         ///< q̈ from vt_solve at every residual (Baumgarte's terms in γ), IDA on
                                ///< q and q̇ only: carries through poses where rows become dependent
                                ///< when the model allows redundant rows (vt_run_options.redundant_band)
    VT_FORMULATION_COUNT        ///< number of formulations (not one)
} vt_formulation;

/// Options of an analysis over time. Fill from vt_default_run_options().
typedef struct vt_run_options {
    double t0;               ///< s, start; default 0
    double t1;               ///< s, end (> t0); default 1
    int nout;                ///< output intervals: rows at t0 + k (t1 − t0)/nout, k = 0..nout; default 100
                             ///< (ignored when tout is given)
    double rtol;             ///< IDA relative tolerance; default 1e-8
    double atol;             ///< IDA absolute tolerance; default 1e-10
    double max_step;         ///< s, IDA's largest step; 0 = no limit (default)
    long max_steps;          ///< IDA's most steps between two outputs; default 100000
    double newton_tol;       ///< Newton–Raphson stops at max |Φ| ≤ newton_tol (m or rad); default 1e-12
    int newton_maxit;        ///< most Newton iterations per instant; default 30
    int forward_check;       ///< 1: also run the forward check (drives removed, efforts applied); default 1
    int forward_independent; ///< forward check of a dynamic analysis: 1 runs it after the driven run, as
                             ///< a separate IDA integration with the efforts taken from the driven run's
                             ///< steps (cubic Hermite interpolation; its error, measured against IDA's own
                             ///< interpolant, in vt_trajectory.fwd_interp_err) (default); 0 integrates both
                             ///< in one IDA system, the efforts from the driven λ at the same time
    int history_steps;       ///< most driven steps kept for an independent forward check (≥ 2); default
                             ///< 100000 (memory: 8 (1 + 2 (nq + nv)) bytes a step). A capacity, not a
                             ///< limit on the run: the history keeps the steps from the forward run's
                             ///< time on (one window at most), and when it fills the forward run first
                             ///< catches up with the driven run's last step
    int forward_as_loads;    ///< forward check: 0 applies the drives' generalized force Φ_q^T λ (joint
                             ///< torques, the paper's check; default); 1 applies each drive's own load
                             ///< (a point drive's force at its point), so the reactions compare too.
                             ///< With 0 and a body drive (point or orientation) the driven rows'
                             ///< reactions count its force at its body and the forward run's do not:
                             ///< fwd_err_force and fwd_err_moment then measure that difference, not
                             ///< an error (the motion's fwd_err_q still does); a run on contacts keeps
                             ///< the contacts' instant's reactions, which compare with 0
    int formulation;         ///< vt_formulation of the dynamic analysis; default VT_FORMULATION_GGL
    double baumgarte_alpha;  ///< 1/s, Baumgarte's damping term 2α Φ̇; default 10
    double baumgarte_beta;   ///< 1/s, Baumgarte's stiffness term β² Φ; default 10
    vt_progress_callback progress; ///< optional, NULL by default
    void *user;              ///< passed to progress
    const double *tout;      ///< s, optional output times (ntout), in place of the uniform rows: the run
                             ///< starts at t0, row 0 is t0 and rows 1..ntout are tout[0..ntout−1], strictly
                             ///< increasing, in (t0, t1]; the run ends at tout[ntout−1]. The trajectory
                             ///< needs ntout + 1 rows. Default NULL (the uniform rows of nout)
    int ntout;               ///< number of entries of tout (≥ 1 with tout); default 0
    double redundant_band;   ///< ODE formulation, models that allow redundant rows: at every residual,
                             ///< constraint directions whose singular value (of the scaled Φ_q of
                             ///< vt_model_def.allow_redundant) is below this fraction of the largest
                             ///< are dropped, their constraints held in the least-squares sense and
                             ///< closed afterwards by Baumgarte's terms: what carries a run through a
                             ///< singular pose instead of amplifying the drift there by 1/σ². 0 drops
                             ///< only rows dependent to round-off; in [0, 1); default VT_REDUNDANT_TOL
    double check_window;     ///< s, the forward check's window (> 0; +Inf: the whole run one window): the
                             ///< forward run restarts from the driven state at the first output row at
                             ///< least check_window after its window's start, so that each window's
                             ///< deviation measures the efforts' error over a bounded time (over a long
                             ///< run the deviation of a chaotic or unstable motion grows exponentially
                             ///< whatever the efforts' accuracy); vt_trajectory.fwd_window_* per window,
                             ///< fwd_err_* the worst. Windows end at output rows. Default
                             ///< VT_CHECK_WINDOW (5 s: every run of a few seconds is one window)
    struct vt_contacts *contacts; ///< a kinematic analysis on contacts (docs/contact.md, "Over time"):
                             ///< at every row the ground's forces of vt_inverse_dynamics_contacts() at
                             ///< the driven state, and the drives' efforts with those forces applied
                             ///< (qfrc_drive the motors', zero on a free root); the forward check
                             ///< integrates under the same efforts and forces. The trajectory is
                             ///< made by vt_trajectory_create_contacts(). NULL (default): none.
                             ///< vt_dynamic_analysis() refuses contacts (VT_ERR_BAD_OPTION)
    vt_contact_schedule contact_schedule; ///< the contacts on the ground at each time; NULL (default):
                             ///< every contact, all the time
    void *contact_user;      ///< passed to contact_schedule
    int nload;               ///< wrenches at frames over a kinematic analysis (0..VT_RUN_LOADS_MAX;
                             ///< default 0): at each row, and wherever the forward check asks, the
                             ///< instant carries them as it carries xfrc (with contacts, before the
                             ///< ground's forces are shared, which then balance them too).
                             ///< vt_dynamic_analysis() refuses them (VT_ERR_BAD_OPTION)
    const int *load_frame;   ///< nload frame indices (vt_model.frame_name's order), each on a moving
                             ///< body; a frame may be named more than once (the sum)
    vt_load_callback loads;  ///< the wrenches at time t (6 nload values, global axes)
    void *load_user;         ///< passed to loads
} vt_run_options;

/// Default of vt_run_options.check_window, s.
#define VT_CHECK_WINDOW 5.0

/// Options of a batch (vt_batch_create). Fill from vt_default_batch_def().
typedef struct vt_batch_def {
    int threads;       ///< threads of each call, the caller's own counted: 0 = every CPU the process may
                       ///< run on (default), else 1 or more (1: the caller's thread alone, none created)
    int stop_on_error; ///< 0 (default): a failing row is reported and every other row solved; 1: the call
                       ///< stops at a failure, the rows it did not solve reported VT_ERR_SKIPPED (with
                       ///< more than one thread, which ones depends on the threads' timing)
    const struct vt_contact_def *contacts; ///< ncontact contacts (read at vt_batch_create, not kept):
                       ///< every row is then vt_inverse_dynamics_contacts() on them; NULL (default): none
    int ncontact;      ///< default 0
    const double *effort_weight; ///< the rule's nv effort weights for the contacts (NULL: 1 each)
} vt_batch_def;

/// Many states in and their results out (vt_batch_inverse_dynamics_motion). Row r of an array X
/// starts at X + r X_stride, in doubles (X_stride 0: the row's own length, rows packed; else at
/// least that length, so a row may sit in a wider table). The inputs q, qd, qdd are required; the
/// optional input qfrc and every output may be NULL (not read, not written).
typedef struct vt_batch_io {
    int nrow;                       ///< rows (states), ≥ 0
    const double *q; size_t q_stride;       ///< nq coordinates a row, as vt_data.q (Euler parameters unit)
    const double *qd; size_t qd_stride;     ///< nv rates a row, as vt_data.qd
    const double *qdd; size_t qdd_stride;   ///< nv accelerations a row, as vt_data.qdd (with loops or
                                            ///< couplings the jointly driven rates' are read, as
                                            ///< vt_inverse_dynamics_motion() reads them)
    const double *qfrc; size_t qfrc_stride; ///< nv applied generalized forces a row, as vt_data.qfrc (NULL: 0)
    double *effort; size_t effort_stride;   ///< nv a row: every rate's generalized force vt_data.qfrc_drive
    double *drive_effort; size_t drive_effort_stride; ///< ndrive a row: vt_data.drive_effort (with loops)
    double *qdd_out; size_t qdd_out_stride; ///< nv a row: q̈ of every rate (with loops the dependent ones solved)
    double *reaction; size_t reaction_stride;           ///< 6 nbody a row: body i's joint reaction at
                                            ///< 6 (i − 1): force (N) then moment (N·m, about the joint
                                            ///< point), global axes (vt_data.jnt_force, jnt_moment)
    double *reaction_body; size_t reaction_body_stride; ///< the same in the body's axes (jnt_force_body, ...)
    double *total; size_t total_stride;     ///< 6 nbody a row: each joint's total wrench, reaction plus
                                            ///< actuation, global (jnt_force_total, jnt_moment_total)
    double *total_body; size_t total_body_stride;       ///< the same in the body's axes
    double *effort_parts; size_t effort_parts_stride;   ///< 3 nv a row: the parts of each rate's effort
                                            ///< its joint's armature, damping and friction take
                                            ///< (vt_data.effort_armature, effort_damping,
                                            ///< effort_friction: nv each, in that order)
    int *status;                            ///< nrow: each row's vt_status (VT_OK, the row's failure, or
                                            ///< VT_ERR_SKIPPED)
    double *reaction_joint; size_t reaction_joint_stride; ///< 6 nbody a row: the reaction in each joint's
                                            ///< frame (vt_data.jnt_force_joint, jnt_moment_joint)
    double *bearing; size_t bearing_stride; ///< 4 nbody a row: body i's bearing split at 4 (i − 1)
                                            ///< (vt_data.jnt_bearing)
    double *limit_excess; size_t limit_excess_stride; ///< 3 nv a row: vt_data.limit_excess
    const int *contact_active; size_t contact_active_stride; ///< with contacts: ncontact a row, nonzero
                                            ///< where the contact is on the ground (NULL: all, every row);
                                            ///< the stride in ints
    double *contact_force; size_t contact_force_stride; ///< with contacts: 3 ncontact a row, the ground's
                                            ///< force on each contact (global; 0 where inactive)
    int nload;                              ///< wrenches the environment applies at frames (default 0):
                                            ///< a tool's measured force, a push (with contacts the
                                            ///< ground's forces balance them too)
    const int *load_frame;                  ///< nload frame indices (vt_model.frame_name's order); a
                                            ///< frame may be named more than once (the sum)
    const double *load; size_t load_stride; ///< 6 nload a row: at each frame its force (N), then its
                                            ///< moment about the frame's origin (N·m), global axes
    const double *time; size_t time_stride; ///< 1 a row: the row's time t, s, vt_data.time: where a
                                            ///< loop's or coupling's drives other than joint drives
                                            ///< (a point or orientation drive's function of time)
                                            ///< are evaluated; a tree's given motion does not depend
                                            ///< on it. NULL: 0 for every row, and refused
                                            ///< (VT_ERR_BAD_OPTION) for a model whose given motion
                                            ///< reads the time (vt_motion_time_drive() ≥ 0)
} vt_batch_io;

/// A batch: one data per thread for many states of one model (vt_batch_create).
typedef struct vt_batch vt_batch;

/// A caller's work run on a batch's threads (vt_batch_run): one part a thread, thread 0 the
/// caller's.
typedef void (*vt_batch_work)(void *ctx, int thread);

/// Results of an analysis over time, one row per output time; made by vt_trajectory_create().
/// Every array is column-major with one column per row (output time).
typedef struct vt_trajectory {
    const vt_model *model;   ///< the model it was made for
    int nrow;                ///< rows allocated
    int nfilled;             ///< rows written by the last run
    double *t;               ///< s, output times (nrow)
    /* the driven run, each column as the vt_data field of the same name at that time */
    double *q;               ///< (nq x nrow)
    double *qd;              ///< (nv x nrow)
    double *qdd;             ///< (nv x nrow)
    double *lambda;          ///< (nc x nrow)
    double *qfrc_drive;      ///< Φ_q^T λ of the drives, N·m or N (nv x nrow)
    double *drive_effort;    ///< N·m or N (ndrive x nrow)
    double *drive_force;     ///< N, global (3 ndrive x nrow)
    double *drive_moment;    ///< N·m, global (3 ndrive x nrow)
    double *jnt_force;       ///< N, global (3 (nbody+1) x nrow)
    double *jnt_moment;      ///< N·m, global, about the joint point (3 (nbody+1) x nrow)
    double *cut_force;       ///< N, global (3 ncut x nrow)
    double *cut_moment;      ///< N·m, global, about point_b (3 ncut x nrow)
    double *phi_norm;        ///< max |Φ| of the driven run (nrow)
    double *phid_norm;       ///< max |Φ_q q̇ + Φ_t| of the driven run (nrow)
    double *rcond;           ///< condition estimate of (5) at each row of the driven run (nrow)
    int nwarn;               ///< rows whose solve warned VT_WARN_ILL_CONDITIONED
    double t_warn;           ///< s, time of the first such row (NaN if none)
    /* forward check: the drives removed, their efforts applied (vt_run_options.forward_as_loads) */
    double *q_fwd;           ///< the forward run's q (nq x nrow)
    double *qd_fwd;          ///< its q̇ (nv x nrow)
    double *jnt_force_fwd;   ///< its reactions, N (3 (nbody+1) x nrow)
    double *jnt_moment_fwd;  ///< N·m (3 (nbody+1) x nrow)
    double *cut_force_fwd;   ///< N (3 ncut x nrow)
    double *cut_moment_fwd;  ///< N·m (3 ncut x nrow)
    double fwd_err_q;        ///< max over rows and coordinates of |q_fwd − q|
    double fwd_err_qd;       ///< max |q̇_fwd − q̇|
    double fwd_err_force;    ///< max |reaction force (forward) − reaction force (driven)|, N
    double fwd_err_moment;   ///< the same for reaction moments, N·m
    double fwd_interp_err;   ///< independent forward check: largest error of the interpolated driven state
                             ///< (q, q̇) against IDA's own interpolant at the steps' midpoints
    long steps;              ///< IDA steps of the driven run (0 for a kinematic analysis)
    long res_evals;          ///< IDA residual evaluations of the driven run
    long steps_fwd;          ///< IDA steps of the forward check
    long res_evals_fwd;      ///< its residual evaluations
    /* the forward check's windows (vt_run_options.check_window): window w restarts from the driven
     * state at row fwd_window_row[w] and covers the rows after it up to the next window's first row
     * (the last window: to the last row); at most nrow windows */
    int nwindow;             ///< windows of the last run's forward check (1 for a run in one window; 0
                             ///< without the forward check)
    int *fwd_window_row;     ///< the row each window starts from (nrow; the first nwindow used)
    double *fwd_window_err_q;     ///< each window's max |q_fwd − q| over its rows (nrow)
    double *fwd_window_err_qd;    ///< its max |q̇_fwd − q̇| (nrow)
    double *fwd_window_err_force; ///< its max reaction force difference, N (nrow)
    double *fwd_window_err_moment;///< its max reaction moment difference, N·m (nrow)
    /* a run on contacts (vt_run_options.contacts; vt_trajectory_create_contacts) */
    int ncontact;            ///< the contacts it has room for (0: made by vt_trajectory_create())
    double *contact_force;   ///< N, global: the ground's force on the body at each contact, 0 in the
                             ///< air (3 ncontact x nrow; NULL without contacts)
    int *contact_active;     ///< the schedule's flags, 1 on the ground (ncontact x nrow; NULL without)
} vt_trajectory;

/// Incremental model builder (opaque).
typedef struct vt_builder vt_builder;

/// How a contact holds (vt_contact_def.kind).
typedef enum {
    VT_CONTACT_UNILATERAL = 0, ///< pushes only, along its normal, with Coulomb friction mu (a foot on
                               ///< the ground)
    VT_CONTACT_BILATERAL = 1   ///< any force (a point welded to the ground: pulls and holds sideways)
} vt_contact_kind;

/// A contact: a point of a body on the ground. The ground's force on the body at the point is
/// an unknown of the instant (vt_inverse_dynamics_contacts()). Fill from vt_default_contact_def().
typedef struct vt_contact_def {
    const char *name;       ///< unique among the contacts (copied); NULL or "" (default): unnamed
    int body;               ///< the body touching, 1..n; default 1; unused with `frame`
    double point[3];        ///< m, the point: body axes from the centre of mass, or with `frame` the
                            ///< frame's axes from its origin (a sole's corner on the foot link's
                            ///< frame); default 0
    const char *frame;      ///< the name of a frame of the model (a URDF link's): the point is on its
                            ///< body, `point` in its axes from its origin (0: the origin itself);
                            ///< NULL (default): body and point
    double normal[3];       ///< the ground's normal at the point, global, pointing into the body (the
                            ///< direction the ground pushes); normalized; default 0: opposite to
                            ///< the model's gravity (+z without gravity). With `other`, in the
                            ///< other body's axes, turning with it (default 0: −gravity's direction
                            ///< in those axes)
    vt_contact_kind kind;   ///< default VT_CONTACT_UNILATERAL
    double mu;              ///< Coulomb friction coefficient, ≥ 0 (unilateral); default 1
    int faces;              ///< the friction cone as a pyramid of this many faces inscribed in it
                            ///< (unilateral), 3..64; default 4
    double weight;          ///< w_c > 0 of the rule's ½ w_c |f_c|² (N⁻²); default VT_CONTACT_WEIGHT
    int other;              ///< what the point touches: 0 (default) the ground; a moving body 1..n
                            ///< (≠ body: a platform, a box held): the force acts on it too,
                            ///< opposite, at the same point, the normal and pyramid turn with it, and
                            ///< the point's velocity relative to it is what the force works on
} vt_contact_def;

/// The default weight of a contact force in the distribution rule (N⁻², beside the efforts' 1).
#define VT_CONTACT_WEIGHT 1e-4

/// A model's contacts and their solver's workspace (opaque; vt_contacts_create()).
typedef struct vt_contacts vt_contacts;

#ifdef __cplusplus
}
#endif

#endif
