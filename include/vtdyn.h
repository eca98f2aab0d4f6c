/* vtdyn — inverse dynamic analysis of rigid multibody systems by the velocity
 * transformation technique (Lee, Yang, Jeon, KSME 1996). The umbrella header.
 *
 * Use:
 *     vt_builder *b;  vt_builder_create(&b, NULL);
 *     vt_body_def link = vt_default_body_def();
 *     link.mass = 100;  ...;  int id = vt_builder_add_body(b, &link);
 *     vt_model *m;  vt_builder_build(&m, b);  vt_builder_free(b);
 *     vt_data *d;   vt_data_create(&d, m);
 *     ... set d->q, d->qd ...
 *     vt_kinematics(m, d); vt_mass_matrix(m, d); vt_forces(m, d);
 *
 * Every function that can fail returns a vt_status (0 ok, negative error); the detail is in
 * vt_builder_message() or d->message (functions given neither, such as vt_integrate_q(), return the
 * status alone). The library never prints, exits or aborts; finite inputs whose results overflow
 * are refused (VT_ERR_NONFINITE), not returned as Inf. A failed call
 * leaves the caller's inputs (a builder's definitions, d->q, d->qd, d->xfrc, d->qfrc, d->time)
 * as they were (vt_kinematic_solve restores q and q̇ it would have corrected; the analyses over
 * time use q, q̇ and time as their working state); the outputs of the failed stage are
 * undefined, except vt_solve's q̈ and λ, which are left as they were. Warnings of successful
 * calls are flags in d->warning. One model may be shared by threads, each with its
 * own vt_data: there is no global state.
 * Conventions (units, frames, layouts) are stated at the top of vtdyn/types.h; docs/guide.md
 * walks through the whole use with tested programs, docs/method.md states the method.
 */
#ifndef VTDYN_H
#define VTDYN_H

#include "vtdyn/version.h"
#include "vtdyn/types.h"
#include "vtdyn/euler.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- statuses and the version ---------------------------------------------------------------- */

/// Text for a status code (never NULL).
VT_API const char *vt_status_string(vt_status status);
/// The library's semantic version, "MAJOR.MINOR.PATCH" (never NULL). Equals VT_VERSION_STRING
/// when the headers and the library come from the same build.
VT_API const char *vt_version(void);

/* ---- model building -------------------------------------------------------------------------- */

/// Defaults: gravity (0, -9.81, 0), rcond_min 1e-12, rcond_warn 1e-6, allow_redundant 0, layout
/// VT_LAYOUT_FULL, inertia_tol VT_INERTIA_TOL.
VT_API vt_model_def vt_default_model_def(void);
/// Defaults: revolute joint about z (axis1; axis2 x) to the ground, both joint points (0, 0, 0),
/// orientation identity, 1 kg point mass (inertia 0).
VT_API vt_body_def vt_default_body_def(void);

/// Starts a builder. def may be NULL for the defaults.
/// Statuses: VT_ERR_NULL, VT_ERR_NO_MEMORY, VT_ERR_NONFINITE (gravity, thresholds),
/// VT_ERR_BAD_OPTION (rcond_min outside (0, 1] or rcond_warn below it, layout not a vt_layout,
/// inertia_tol outside [0, 1)).
VT_API vt_status vt_builder_create(vt_builder **builder, const vt_model_def *def);
/// Validates and adds a body. Returns its id (1, 2, ...) or a negative vt_status, with the
/// reason in vt_builder_message(). Non-unit axes and orientations are normalized; zero ones
/// are refused (directions: normalized by their largest component first, so any finite non-zero
/// length works). An inertia entry beyond VT_INERTIA_MAX is refused (VT_ERR_NONFINITE). A refused
/// body leaves the builder as it was.
VT_API int vt_builder_add_body(vt_builder *builder, const vt_body_def *def);
/// Message of the last failure (empty string if none).
VT_API const char *vt_builder_message(const vt_builder *builder);
/// Builds the immutable model (one allocation, the caller's: vt_model_free()); the builder
/// stays valid (it may build again, or be freed). On failure *model is NULL.
/// Statuses: VT_ERR_NULL, VT_ERR_EMPTY_MODEL, VT_ERR_NO_MEMORY.
VT_API vt_status vt_builder_build(vt_model **model, vt_builder *builder);
/// Frees a builder; NULL does nothing. Models built from it stay valid. As with free(), freeing
/// the same builder twice is undefined (the memory is no longer the library's to check).
VT_API void vt_builder_free(vt_builder *builder);
/// Frees a model; NULL does nothing. Data and trajectories made for it must not be used after.
/// As with free(), freeing the same model twice is undefined.
VT_API void vt_model_free(vt_model *model);
/// A new model with the same bodies and cut joints and no drives: the model of the forward
/// check, laid out VT_LAYOUT_FULL (a forward run integrates M*) whatever the model's layout.
/// Free it with vt_model_free(). Statuses: VT_ERR_NULL, VT_ERR_NO_MEMORY.
VT_API vt_status vt_model_without_drives(vt_model **out, const vt_model *model);

/// Defaults: body 1, at its centre of mass, its axes; no name (a frame needs one), no reference.
VT_API vt_frame_def vt_default_frame_def(void);
/// Validates and adds a frame on a body already added (or the ground), or at a pose on a frame
/// added so far (vt_frame_def.reference: a tool frame on a URDF link's frame). Returns its index
/// (0, 1, ...) or a negative vt_status: VT_ERR_BAD_NAME (missing, too long, or taken),
/// VT_ERR_BAD_INDEX, VT_ERR_NOT_FOUND (no such reference frame), VT_ERR_NONFINITE,
/// VT_ERR_QUATERNION. A refused frame leaves the builder as it was.
VT_API int vt_builder_add_frame(vt_builder *builder, const vt_frame_def *def);
/// The id of the body added so far under this name, or VT_ERR_NOT_FOUND (VT_ERR_NULL).
VT_API int vt_builder_find_body(const vt_builder *builder, const char *name);
/// The id of the body added so far whose joint has this name, or VT_ERR_NOT_FOUND (VT_ERR_NULL).
VT_API int vt_builder_find_joint(const vt_builder *builder, const char *name);
/// Defaults: no armature, damping or friction, the sign law (friction_velocity 0), gear ratio 1.
VT_API vt_joint_effects_def vt_default_joint_effects_def(void);
/// Sets a body's joint's own effects (its vt_body_def's armature … gear_ratio: docs/guide.md,
/// "Real joints") in a builder, a URDF robot's for instance, before vt_builder_build(); they
/// replace what the body had (a URDF's <dynamics>). VT_ERR_BAD_INDEX, VT_ERR_BAD_OPTION
/// (negative or non-finite values, a zero gear ratio); a refusal leaves the builder as it was.
VT_API vt_status vt_builder_set_joint_effects(vt_builder *builder, int body, const vt_joint_effects_def *def);
/// A body's joint's own effects as the builder holds them, into *out (to change one and set them
/// back): VT_ERR_BAD_INDEX, VT_ERR_NULL.
VT_API vt_status vt_builder_joint_effects(const vt_builder *builder, int body, vt_joint_effects_def *out);
/// The index of the frame added so far under this name (a URDF robot's link frames are named
/// after the links), or VT_ERR_NOT_FOUND (VT_ERR_NULL).
VT_API int vt_builder_find_frame(const vt_builder *builder, const char *name);

/// Defaults: body 1, no frame, mass 0, at the body's centre of mass, inertia 0.
VT_API vt_payload_def vt_default_payload_def(void);
/// Fixes a rigid body (a payload, a tool) to a body added so far, merged into it as the URDF
/// loader merges a link fixed to its parent: the masses added, the centre of mass their
/// weighted mean, the inertias carried to it by the parallel axes and summed, in the body's
/// axes, which keep their orientation. A body's points are stored from its centre of mass,
/// which moves: every point on the body added so far (its joint point, its children's joint
/// points, its frames, its point drives', its cut joints') is moved with it, so that each stays
/// where it is on the body; a base body's (VT_JOINT_BASE) coordinates are its centre of mass's
/// position, the new one's after the call. Returns the body's id or a negative vt_status:
/// VT_ERR_NULL, VT_ERR_NONFINITE (NaN or Inf, or a result that overflows), VT_ERR_MASS,
/// VT_ERR_BAD_INDEX (no such body, or a frame on the ground), VT_ERR_NOT_FOUND (no such frame),
/// the inertia checks' statuses (the payload's inertia, and the body's result). A refused
/// payload leaves the builder as it was.
VT_API int vt_builder_add_payload(vt_builder *builder, const vt_payload_def *def);
/// Replaces a body's mass, centre of mass and inertia by the def's (point: the new centre of
/// mass, in the body's axes from its present one, or in the frame's axes from its origin;
/// inertia about it), moving the body's points as vt_builder_add_payload() does. Returns the
/// body's id or a negative vt_status, as vt_builder_add_payload(); a refusal leaves the builder
/// as it was.
VT_API int vt_builder_set_mass(vt_builder *builder, const vt_payload_def *def);

/// Lookups by name in a model: the id or index, or VT_ERR_NOT_FOUND (VT_ERR_NULL for NULL
/// arguments). vt_find_joint gives the id of the body whose joint has that name.
VT_API int vt_find_body(const vt_model *model, const char *name);
VT_API int vt_find_joint(const vt_model *model, const char *name);
VT_API int vt_find_drive(const vt_model *model, const char *name);
VT_API int vt_find_cut_joint(const vt_model *model, const char *name);
VT_API int vt_find_frame(const vt_model *model, const char *name);

/* ---- URDF robots (only in builds with libxml2, VT_HAVE_URDF) --------------------------------- */

#if VT_HAVE_URDF
/// Largest URDF input, in bytes (256 MiB), a file's or a string's: larger ones are refused before
/// they are read whole (a file by its size, or after reading VT_URDF_MAX_BYTES + 1 bytes of a
/// device or pipe; a string after as many), VT_ERR_FILE for a file and VT_ERR_XML for a string,
/// the message naming the bound. Robot descriptions are far smaller (UR5 14 kB, Talos 190 kB); a
/// chain of 100,000 links with inertial elements is 32 MB. Links and joints are not refused for
/// their number below VT_COUNT_MAX (the loader's work is O(n log n) in them): the bound is on
/// memory, libxml2's tree taking about 15 times the text of dense markup (the 32 MB chain parses
/// in 550 MB), so a file at the bound may need some 4 GB; an allocation that fails on the way is
/// VT_ERR_NO_MEMORY.
#define VT_URDF_MAX_BYTES (256 * 1024 * 1024)
/// Options of vt_urdf_builder(). Fill from vt_default_urdf_options().
typedef struct vt_urdf_options {
    vt_model_def model;   ///< the builder's model options; default vt_default_model_def() with gravity
                          ///< (0, 0, −9.81): URDF robots are z up
    int floating;         ///< 1: a root link that no joint attaches to the world gets a free joint
                          ///< (VT_JOINT_FREE) from the ground at its link frame's origin: q = that
                          ///< origin's global position and the link frame's Euler parameters, q̇ = its
                          ///< global velocity and angular velocity; 0 (default): it is welded to the ground
    int mimic;            ///< 1 (default): a mimic joint's coordinate is coupled to the joint it mimics
                          ///< (vt_coupling_def, named after the mimic joint); 0: the tag is ignored and
                          ///< the joint moves on its own (as Pinocchio's default loads it)
    int dynamics;         ///< 1 (default): a joint's <dynamics damping friction> become its rate's
                          ///< damping and Coulomb friction (vt_body_def.damping, friction; URDF has no
                          ///< armature); 0: the tag is ignored (ideal joints)
} vt_urdf_options;
/// Defaults: vt_default_model_def() with gravity (0, 0, −9.81) m/s², floating 0, mimic 1, dynamics 1.
VT_API vt_urdf_options vt_default_urdf_options(void);
/// Reads a URDF file into a new builder (drives, cut joints and frames may be added after, then
/// vt_builder_build()). Links become bodies named after the link and their joints are named after
/// the URDF joint: revolute and continuous → VT_JOINT_REVOLUTE, prismatic → VT_JOINT_TRANSLATIONAL,
/// floating → VT_JOINT_FREE (the joint point at the child link frame's origin, its q that frame's
/// translation from the joint origin in the parent body's axes and its Euler parameters as a
/// spherical joint's: docs/method.md, "URDF robots"); a fixed joint merges its child into its parent
/// (masses, centre of mass and inertia combined). The ground is the link "world" (or the root,
/// welded, with floating 0) and what fixed joints attach to it. Every link is also a frame named
/// after it, at its link frame. Bodies are numbered breadth-first from the root, so the joint
/// coordinates are the URDF joints' in that order, with the same sign and zero. Body axes are
/// the link's inertial frame (docs/method.md, "URDF robots"). options may be NULL (the defaults).
/// On failure *builder is NULL and message (VT_MESSAGE_SIZE bytes, may be NULL) says why, naming the element
/// and its line. The XML is parsed with this loader's settings whatever the process's libxml2
/// defaults are (xmlSubstituteEntitiesDefault(), xmlLoadExtDtdDefaultValue, ...), which it leaves
/// as they were: nothing but the input is read (no external DTD, entity or XInclude, no network),
/// a document that declares or refers to an entity (other than &lt; &gt; &amp; &apos; &quot;) is
/// refused, and libxml2's errors go to the message, never to standard error (those libxml2
/// reports outside a parser context, such as a failed allocation, reach the loader through the
/// calling thread's structured error handler, which is the loader's during the call only).
/// Statuses: VT_ERR_NULL (builder, path), VT_ERR_FILE (missing or unreadable, or larger than
/// VT_URDF_MAX_BYTES), VT_ERR_XML (malformed XML; an entity; no <robot>; a string larger than
/// VT_URDF_MAX_BYTES), VT_ERR_PARENT (a link with two parents, a loop),
/// VT_ERR_NOT_FOUND (a joint names a missing link),
/// VT_ERR_JOINT_TYPE (planar, unknown, mimic), VT_ERR_MASS, VT_ERR_NONFINITE (a non-finite or
/// malformed number), VT_ERR_BAD_NAME (a missing or duplicate link or joint name), the builder's
/// statuses (an inertia, an axis of zero length, limits), VT_ERR_BAD_OPTION (options),
/// VT_ERR_NO_MEMORY (also when libxml2 runs out of memory while parsing).
VT_API vt_status vt_urdf_builder(vt_builder **builder, const char *path, const vt_urdf_options *options, char *message);
/// The same from a string holding the XML (for tests and embedded use); line numbers are the
/// string's.
VT_API vt_status vt_urdf_builder_string(vt_builder **builder, const char *xml, const vt_urdf_options *options,
                                 char *message);
#endif

/* ---- the data -------------------------------------------------------------------------------- */

/// Allocates the data of a model (one block of vt_data_size() bytes) and lays it out with
/// vt_data_init(). Free it with vt_data_free(). On failure *data is NULL. Which arrays it holds,
/// and so its size, is the model's layout (vt_model_def.layout): VT_LAYOUT_FULL for every entry
/// point, O(n²) bytes; VT_LAYOUT_RECURSIVE O(n) bytes beside the constraint rows' (nc x nv), for
/// the recursive and given-motion instants and the kinematic solve and analysis (S, R, M* and
/// lambda_null then NULL, and Φ_q too for a model whose every rate has a joint drive of its own).
/// Statuses: VT_ERR_NULL, VT_ERR_NO_MEMORY, VT_ERR_TOO_MANY_BODIES (a size beyond size_t).
VT_API vt_status vt_data_create(vt_data **data, const vt_model *model);
/// The state at rest in the reference configuration: q = q0, q̇ = 0, xfrc = 0, qfrc = 0,
/// time = 0; clears the diagnostics (route, fallback, warning, rank, rcond, residual), ida_flag
/// and message. Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH.
VT_API vt_status vt_data_reset(const vt_model *model, vt_data *data);
/// Releases data made by vt_data_create(); does nothing for NULL or for data laid out by
/// vt_data_init() in the caller's buffer (that memory stays the caller's to reuse or drop).
/// As with free(), freeing the same data twice is undefined.
VT_API void vt_data_free(vt_data *data);

/// Alignment, in bytes, of the start of a vt_data laid out by vt_data_init().
#define VT_DATA_ALIGN 64
/// Bytes a model's data needs in a caller-provided buffer, including up to VT_DATA_ALIGN − 1
/// bytes of alignment slack: a buffer of this size at any address is enough (one aligned to
/// VT_DATA_ALIGN needs VT_DATA_ALIGN − 1 bytes fewer). Fixed by the model and its layout. 0 for
/// a NULL model, or one whose data's size cannot be counted in size_t.
VT_API size_t vt_data_size(const vt_model *model);
/// Lays the data of a model out in `buffer` (size bytes, owned by the caller) for builds that
/// must not allocate after start-up: the same data as vt_data_create() (zeroed, the ground at
/// identity, then vt_data_reset()), starting at the buffer's first VT_DATA_ALIGN boundary, and
/// allocates nothing. *data points into the buffer, which must outlive it and not be used for
/// anything else meanwhile; vt_data_free() on it does nothing. Instants (vt_inverse_dynamics(),
/// vt_inverse_dynamics_recursive(), vt_kinematic_solve() and the stages) then allocate nothing;
/// the analyses over time allocate only at their start (IDA's memory, the forward check's
/// model and data, the driven steps' history), as many calls however long the run, and free
/// it at their end.
/// Statuses: VT_ERR_NULL (data, model or buffer NULL), VT_ERR_BAD_SIZE (the buffer cannot hold
/// the data: nothing is written to it), VT_ERR_TOO_MANY_BODIES (its size beyond size_t). On failure *data is NULL (if data is not NULL).
VT_API vt_status vt_data_init(vt_data **data, const vt_model *model, void *buffer, size_t size);

/* ---- state helpers --------------------------------------------------------------------------- */

/// Adds to d->xfrc a force f (N) and moment n (N·m), both global, applied at the point
/// `point` of body `body` (m, body axes from its centre of mass); f or n may be NULL.
/// Needs the body's orientation: call after vt_kinematics(). Statuses: VT_ERR_NULL (point NULL
/// with f given), VT_ERR_MODEL_MISMATCH, VT_ERR_BAD_INDEX (body not in 1..nbody), VT_ERR_NONFINITE
/// (NaN or Inf in the load, or the body's xfrc would overflow: xfrc is then left as it was).
VT_API vt_status vt_add_point_load(const vt_model *model, vt_data *data, int body,
                            const double point[3], const double f[3], const double n[3]);

/// vt_add_point_load() at a frame's origin (its body, its point). Statuses: those of
/// vt_add_point_load(), VT_ERR_BAD_INDEX (frame not in 0..nframe−1, or on the ground).
VT_API vt_status vt_add_frame_load(const vt_model *model, vt_data *data, int frame, const double f[3], const double n[3]);

/// Where a frame is: its origin (m) and its axes (rotation frame → global, 3x3 column-major),
/// both global, either may be NULL. Needs vt_kinematics() (or any instant). Statuses: VT_ERR_NULL,
/// VT_ERR_MODEL_MISMATCH, VT_ERR_BAD_INDEX, VT_ERR_NONFINITE (the position overflows: position is
/// then left as it was).
VT_API vt_status vt_frame_pose(const vt_model *model, vt_data *data, int frame, double position[3], double rotation[9]);

/// q_out = q advanced by the velocity v over h: scalar coordinates move by h v, spherical
/// relative Euler parameters by the exact rotation exp(h ω) (normalized), a base body's
/// x by h ẋ (then its Euler parameters normalized). q_out may alias q. q and q_out have nq
/// entries, v has nv. Statuses: VT_ERR_NULL, VT_ERR_NONFINITE (q, v or h, or a result that
/// overflows). q_out is untouched on failure. (No data: no message.)
VT_API vt_status vt_integrate_q(double *q_out, const vt_model *model, const double *q,
                         const double *v, double h);

/* ---- time functions -------------------------------------------------------------------------- */

/// f = c (a time function is a value: copy it into a drive's f).
VT_API vt_function vt_function_constant(double c);
/// c[0] + c[1] t + ... + c[ncoef-1] t^(ncoef-1); ncoef in 1..VT_POLY_MAX (checked when a drive
/// using it is added).
VT_API vt_function vt_function_polynomial(int ncoef, const double *c);
/// a + b sin(omega t + phase)
VT_API vt_function vt_function_sine(double a, double b, double omega, double phase);
/// f, f', f'' from callback(t, out, user)
VT_API vt_function vt_function_user(vt_function_callback callback, void *user);
/// The C2 cubic interpolating spline through the n samples (t[k], y[k]), k = 0..n−1: t in s,
/// strictly increasing, y in the drive's unit (rad or m), n ≥ 2. Ends: n = 2 the straight line,
/// n = 3 the parabola through the three samples, n ≥ 4 "not-a-knot" (f''' continuous at t[1]
/// and t[n−2]: no condition imposed on the end slopes or curvatures, and every cubic polynomial
/// is reproduced exactly). f, f', f'' are those of the piecewise cubic (f'' piecewise linear and
/// continuous). Outside [t[0], t[n−1]] the first and last pieces' cubics are continued.
/// The function refers to the caller's arrays, which must stay valid until it is added to a
/// drive (vt_builder_add_drive() validates the samples, copies them and computes the second
/// derivatives by LAPACK into the builder, and vt_builder_build() into the model: the arrays may
/// then be freed) or while it is evaluated by vt_function_eval(). Refusals (when added or
/// evaluated): VT_ERR_BAD_DRIVE (n < 2, t or y NULL, t not strictly increasing; the message
/// names the sample), VT_ERR_NONFINITE (a sample not finite).
VT_API vt_function vt_function_spline(int n, const double *t, const double *y);
/// out = [f(t), f'(t), f''(t)], exact for the built-in kinds. A spline not yet in a model
/// (sample_d2 NULL) has its second derivatives solved at each call in a fixed local buffer:
/// at most VT_SPLINE_EVAL_MAX samples. A model's drives, m->drive[k].f, have no limit and are
/// evaluated in O(log n) (bisection): their samples were checked when the drive was added.
/// Statuses: VT_ERR_NULL, VT_ERR_BAD_DRIVE (malformed function), VT_ERR_CALLBACK,
/// VT_ERR_NONFINITE (a value that is not finite), VT_ERR_BAD_SIZE (a spline not in a model with
/// more than VT_SPLINE_EVAL_MAX samples), VT_ERR_LAPACK. out is untouched on failure.
VT_API vt_status vt_function_eval(double out[3], const vt_function *f, double t);

/* ---- drives and cut joints ------------------------------------------------------------------- */

/// Defaults: joint drive of body 1's first rate, constant 0; axis z; identity orientation.
VT_API vt_drive_def vt_default_drive_def(void);
/// Defaults: revolute cut joint between the ground (a) and body 1 (b), at the origins, axis z.
VT_API vt_cut_joint_def vt_default_cut_joint_def(void);
/// Validates and adds a drive on bodies already added. Returns the drive's index (0, 1, ...)
/// or a negative vt_status (VT_ERR_BAD_DRIVE, VT_ERR_BAD_INDEX, VT_ERR_NONFINITE, ...).
/// A spline time function's samples are copied into the builder with their second derivatives
/// (its sample_d2 is ignored): the caller's arrays are free after the call. A refused drive
/// leaves the builder as it was.
VT_API int vt_builder_add_drive(vt_builder *builder, const vt_drive_def *def);
/// Defaults: body 2's first rate follows body 1's, ratio 1, offset 0.
VT_API vt_coupling_def vt_default_coupling_def(void);
/// Validates and adds a coupling between two scalar coordinates of bodies already added. Returns
/// its index or a negative vt_status (VT_ERR_BAD_INDEX, VT_ERR_BAD_DRIVE: a coordinate that is
/// not scalar, or the same one twice; VT_ERR_NONFINITE, VT_ERR_BAD_NAME). A refused coupling
/// leaves the builder as it was.
VT_API int vt_builder_add_coupling(vt_builder *builder, const vt_coupling_def *def);
/// The coupling of that name, or VT_ERR_NOT_FOUND (VT_ERR_NULL).
VT_API int vt_find_coupling(const vt_model *model, const char *name);

/// Validates and adds a cut joint between bodies already added. Returns its index or a
/// negative vt_status (VT_ERR_BAD_CUT_JOINT, VT_ERR_BAD_INDEX, VT_ERR_AXIS_ZERO, ...).
VT_API int vt_builder_add_cut_joint(vt_builder *builder, const vt_cut_joint_def *def);

/* ---- stages: each reads the model and fills its part of the data ------------------ */
/* The stages below (vt_kinematics to vt_reactions), vt_inverse_dynamics(), the force transforms
 * and vt_dynamic_analysis() need the dense arrays: on data laid out VT_LAYOUT_RECURSIVE they return
 * VT_ERR_LAYOUT, naming the call, and write nothing else; so do vt_inverse_dynamics_recursive()
 * and vt_inverse_dynamics_motion() for an instant that needs M* (the message says why). */
/* The diagnostics in vt_data (route, fallback, warning, rank, rcond, residual) are those of the
 * last instant or solve: vt_solve, vt_inverse_dynamics, vt_inverse_dynamics_recursive,
 * vt_inverse_dynamics_motion, vt_kinematic_solve and the analyses clear them at their start
 * (after the NULL and model check), so that a call refused before its solve (NaN in q, an
 * option out of range) leaves none of an earlier call's; the other stages neither write nor
 * clear them. */

/// From d->q and d->qd: x, A, ω, joint axes and points, S (15)-(18), ẋ = S q̇ and Ṡq̇.
/// A spherical joint's Euler parameters are normalized (scaled first: any length works).
/// Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH, VT_ERR_NONFINITE (NaN or Inf in q or q̇, or an
/// output that overflows: the message names the body), VT_ERR_QUATERNION (a spherical joint's or
/// base body's Euler parameters of norm below 1e-12).
VT_API vt_status vt_kinematics(const vt_model *model, vt_data *data);

/// R, q̇ = R ẋ, assembled from Table 1 (20)-(21). Needs vt_kinematics().
/// Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH (as every stage).
VT_API vt_status vt_inverse_transform(const vt_model *model, vt_data *data);

/// M^i = diag(m I, 4 G^T J' G) and M* = S^T M S (3). Needs vt_kinematics().
VT_API vt_status vt_mass_matrix(const vt_model *model, vt_data *data);

/// F (gravity and d->xfrc, (7)), h and Q = S^T [F - M Ṡq̇ + h] (4), plus d->qfrc.
/// Needs vt_kinematics(). Statuses: VT_ERR_NONFINITE (xfrc or qfrc, or F, h or Q overflows).
VT_API vt_status vt_forces(const vt_model *model, vt_data *data);

/// Φ, Φ_x, Φ_q = Φ_x S (22), Φ_t and γ (23) of every constraint row at d->time.
/// Needs vt_kinematics(). Statuses: VT_ERR_CALLBACK, VT_ERR_NONFINITE (a time function's value, or
/// a row's values that overflow: the message names the row and its owner),
/// VT_ERR_QUATERNION (an orientation callback's p_d of zero norm).
VT_API vt_status vt_constraints(const vt_model *model, vt_data *data);

/// Solves (5), [M* Φ_q^T; Φ_q 0][q̈; −λ] = [Q; γ], for q̈ and λ, scaled by the mass metric, by
/// the cheapest route the rows allow (LAPACK); d->route records the route, d->fallback a faster
/// route that gave way, d->rcond the reciprocal condition of what the route factorized (rank,
/// warning, residual and lambda_unique as documented in vt_data).
/// Needs vt_mass_matrix(), vt_forces(), vt_constraints().
/// Statuses: VT_ERR_DEPENDENT_CONSTRAINTS (the message names the rows), VT_ERR_SINGULAR,
/// VT_ERR_NONFINITE (Q or γ), VT_ERR_LAPACK. On failure qdd and lambda are left as they were.
VT_API vt_status vt_solve(const vt_model *model, vt_data *data);

/// ẍ, the drives' efforts (24) and the joint reactions (25)-(28), inward from the tree's ends,
/// cut joints from their multipliers. Needs vt_solve(). Statuses: VT_ERR_NONFINITE (an effort
/// or reaction overflowed: an ill-posed instant).
VT_API vt_status vt_reactions(const vt_model *model, vt_data *data);
/// Every joint's reaction in its own frame (vt_model.jnt_frame: a URDF joint's frame) and its
/// bearing split, from the reactions of the instant just computed (any entry point): fills
/// vt_data.jnt_force_joint, jnt_moment_joint and jnt_bearing, O(n). On demand, so that the
/// instants do not carry its cost; the batch calls it where its io asks for reaction_joint or
/// bearing. VT_ERR_NULL, VT_ERR_MODEL_MISMATCH.
VT_API vt_status vt_reactions_joint_frame(const vt_model *model, vt_data *data);

/// The whole instant: vt_kinematics, vt_mass_matrix, vt_forces, vt_constraints, vt_solve,
/// vt_reactions (R is left to vt_inverse_transform, which only (14) needs). Statuses: those of
/// the stages; the first failure stops it. q, q̇ must satisfy the constraints (not corrected).
VT_API vt_status vt_inverse_dynamics(const vt_model *model, vt_data *data);

/// The same instant by the recursive evaluation, O(n) where the rows allow it: no dense S (and
/// R), Φ_q from the rates' twists, M* and Q formed only on the general route. Fills what
/// vt_inverse_dynamics() fills (q̈, λ, efforts, reactions, ẍ, x, A, ω, ẋ; Ṡq̇, Φ, Φ_x, Φ_q, γ
/// when anything is solved; M* and Q when vt_data.route is one of vt_solve's) except S and R,
/// and agrees with it to round-off; d->route says which route it took. Statuses: those of
/// vt_inverse_dynamics().
VT_API vt_status vt_inverse_dynamics_recursive(const vt_model *model, vt_data *data);

/// One instant of a motion given for every rate: q in d->q, q̇ in d->qd and q̈ in d->qdd (read,
/// not changed), at any instant, without drives or time functions (the model's drives are
/// ignored, d->time is not read). Fills every rate's generalized force d->qfrc_drive = M* q̈ − Q
/// (N·m or N: the joint torques and forces that produce the motion, with d->xfrc and d->qfrc
/// applied), ẍ, x, A, ω, ẋ and every joint reaction in both frames (the actuation not
/// included, as in vt_reactions()); d->route = VT_ROUTE_MOTION. The drives' outputs and λ are
/// not written. A tree with a base body is refused (VT_ERR_BAD_OPTION).
/// With loops (cut joints) or couplings the rates are not independent: the rates that carry a
/// joint drive are the given ones — each such drive's row takes its acceleration from d->qdd
/// instead of f''(t), every other row is as in vt_inverse_dynamics() — the rest follows, and
/// the outputs, the route and the statuses are vt_inverse_dynamics()'s (the drives' efforts,
/// q̈ of every rate in d->qdd; q and q̇ must satisfy the constraints). Such a model without a
/// joint drive is refused (VT_ERR_BAD_OPTION), the message saying what is missing: with
/// couplings, a joint drive on each coupling's leader (body_b's rate, named) and each free rate;
/// a URDF robot's mimic joints are couplings unless loaded with vt_urdf_options.mimic = 0 (each
/// joint then moves on its own, as Pinocchio loads it).
/// Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH, VT_ERR_BAD_OPTION, VT_ERR_NONFINITE (q, q̇, q̈,
/// xfrc, qfrc; a reaction overflowed), VT_ERR_QUATERNION, and with loops those of the stages.
VT_API vt_status vt_inverse_dynamics_motion(const vt_model *model, vt_data *data);

/// The first drive whose rows vt_inverse_dynamics_motion() evaluates at d->time: a point or
/// orientation drive of a model with cut joints or couplings, whose given motion keeps every row
/// but the joint drives' (γ = f''(t)); −1 when the given motion does not depend on the time (a
/// tree, or joint drives alone); VT_ERR_NULL for NULL. A batch of such a model needs each row's
/// time (vt_batch_io.time).
VT_API int vt_motion_time_drive(const vt_model *model);

/// The Cartesian force of one drive, Φ_x^T λ (7n): for a joint drive R^T Φ_q^T λ (14), for a
/// body drive [f_a; 2 E^T s̃ f_a + 2 E^T n_a] (24), into the caller's F (7n entries, body i at
/// 7(i−1)). Needs vt_solve(). Statuses: VT_ERR_NULL, VT_ERR_BAD_INDEX (drive not in 0..ndrive−1).
VT_API vt_status vt_drive_cartesian_force(double *F, const vt_model *model, vt_data *data, int drive);

/* ---- analyses over time ---------------------------------------------------------------------- */

/// Defaults: t in [0, 1], 100 output intervals, IDA rtol 1e-8 and atol 1e-10, Newton to
/// 1e-12 in at most 30 iterations, forward check on (off in a build without SUNDIALS), the ODE
/// form's redundant_band VT_REDUNDANT_TOL. The analyses refuse (VT_ERR_BAD_OPTION) tolerances and
/// max_step that are not finite, as well as out of range.
VT_API vt_run_options vt_default_run_options(void);

/// Allocates a trajectory of nrow rows for the model (all arrays in one block, zeroed); a run
/// with nout output intervals needs nrow ≥ nout + 1, one with ntout output times (tout)
/// nrow ≥ ntout + 1 (row 0 is always t0). On failure *trajectory is NULL.
/// Statuses: VT_ERR_NULL, VT_ERR_BAD_OPTION (nrow < 1), VT_ERR_NO_MEMORY (also a size beyond size_t).
VT_API vt_status vt_trajectory_create(vt_trajectory **trajectory, const vt_model *model, int nrow);
/// vt_trajectory_create() with room for a run on the contacts (vt_run_options.contacts): its
/// ncontact = vt_contacts_count(contacts), contact_force and contact_active.
/// Statuses: those of vt_trajectory_create(); VT_ERR_MODEL_MISMATCH (contacts made for another
/// model).
VT_API vt_status vt_trajectory_create_contacts(vt_trajectory **trajectory, const vt_model *model,
                                               const vt_contacts *contacts, int nrow);
/// Frees a trajectory; NULL does nothing. As with free(), freeing it twice is undefined.
VT_API void vt_trajectory_free(vt_trajectory *trajectory);

/// One instant of a kinematic analysis at d->time: Newton–Raphson on Φ(q, t) = 0 from d->q
/// (steps by LU for as many rows as rates, LAPACK's least-norm dgels for fewer, dgelsd for the
/// dependent rows a model allows), then q̇ corrected to Φ_q q̇ = −Φ_t the same way, then
/// vt_inverse_dynamics(). d->q and d->qd are
/// replaced by the consistent values; on failure they are restored.
/// Statuses: VT_ERR_NEWTON (max |Φ| in the message), VT_ERR_SINGULAR, VT_ERR_BAD_OPTION (tol not
/// finite and positive, maxit not positive), VT_ERR_NONFINITE (a Newton step that overflows q),
/// and those of the stages.
VT_API vt_status vt_kinematic_solve(const vt_model *model, vt_data *data, double tol, int maxit);

/// Kinematic analysis of a fully driven model: its constraint rows fix every rate (as many
/// independent rows as rates, or more of that rank when the model allows redundant rows; the rank
/// decided as vt_solve decides dependent rows, at t0 and d->q before the run for a model that
/// does not allow them, at the first row for one that does). Each output row holds the
/// consistent q, q̇ at its time (vt_kinematic_solve()'s Newton–Raphson to opt->newton_tol) and
/// the instant of vt_inverse_dynamics_recursive() there (S, R, M* and Q are not left in the data).
/// The output times: t0, then opt->tout[0..ntout−1] when given (each row exact at its time), else
/// t0 + k (t1 − t0)/nout. A bad list (not finite, not strictly increasing after t0, beyond t1, or
/// more entries than the trajectory's rows − 1) is refused with VT_ERR_BAD_OPTION, the message
/// naming the entry, before anything is written.
/// With opt->forward_check, the model without drives is integrated (SUNDIALS IDA) under the
/// drives' generalized forces, exact at every time IDA asks for: tr->fwd_err_q and the other
/// forward errors are the deviation those efforts cause, not IDA's error in integrating the
/// motion (docs/method.md, "Analyses over time"). In a build without SUNDIALS
/// (VT_HAVE_SUNDIALS 0) the forward check is refused with VT_ERR_BAD_OPTION.
/// On contacts (opt->contacts, a trajectory of vt_trajectory_create_contacts()): at each row the
/// ground's forces of vt_inverse_dynamics_contacts() at the row's q, q̇, q̈ over the contacts
/// opt->contact_schedule puts on the ground (tr->contact_force, contact_active), the efforts and
/// reactions that instant's (qfrc_drive the motors', zero on a free root), the drives' λ those
/// of the instant with the forces as loads; the forward check applies the forces as loads too
/// (docs/contact.md, "Over time"). A row the contacts cannot carry ends the run with
/// VT_ERR_CONTACT, the time named; d->xfrc is the caller's on return. With wrenches at frames
/// (opt->nload, load_frame, loads) each row's instant and the forward check's efforts carry them
/// at that state's poses (with contacts, before the ground's forces are shared); a loads callback
/// that fails ends the run with VT_ERR_CALLBACK, one that returns NaN with VT_ERR_NONFINITE.
/// d->q, d->qd and d->time are the run's working state: afterwards they hold the last row's.
/// Rows written before a failure stay in the trajectory (tr->nfilled).
/// Statuses: VT_ERR_NOT_FULLY_DRIVEN (fewer rows than rates, or of lower rank),
/// VT_ERR_DEPENDENT_CONSTRAINTS (more rows than rates, of full rank, in a model that does not
/// allow redundant rows), VT_ERR_BAD_OPTION (also a trajectory without room for the contacts'
/// forces), VT_ERR_MODEL_MISMATCH (trajectory or contacts of another model), VT_ERR_NEWTON,
/// VT_ERR_IDA, VT_ERR_ABORTED, VT_ERR_CONTACT, VT_ERR_CALLBACK (also the schedule), and those of
/// the stages. The forward check
/// of a model with dependent cut-joint rows needs VT_FORMULATION_ODE.
VT_API vt_status vt_kinematic_analysis(const vt_model *model, vt_data *data, const vt_run_options *opt,
                                vt_trajectory *trajectory);

/// Dynamic analysis: the index-1 form of (5) handed to SUNDIALS IDA, unknowns q, q̇ and λ,
///   q' − T(q) q̇ = 0,   M* q̈ − Q − Φ_q^T λ = 0,   Φ_q q̈ − γ = 0,
/// from d->q, d->qd at opt->t0, first made consistent (vt_kinematic_solve); rows at t0 and then
/// at opt->tout's times when given (IDA's interpolant, its stop time the last of them), as
/// vt_kinematic_analysis() validates them. With
/// opt->forward_check the forward model (drives removed, their efforts applied) is integrated
/// as well: by default separately, after the driven run, with the efforts of the driven state
/// interpolated (cubic Hermite over the driven run's steps; error in tr->fwd_interp_err); with
/// opt->forward_independent = 0 in the same IDA system, the efforts from the driven λ.
/// d->q, d->qd and d->time are the run's working state: afterwards they hold the last row's
/// (after a failure, a state the run was trying). Rows written before a failure stay in the
/// trajectory (tr->nfilled). A drive's time function or orientation callback that fails or
/// returns NaN or Inf at a time IDA asks for ends the run at once with VT_ERR_CALLBACK or
/// VT_ERR_NONFINITE, the message naming the drive and the time. A trial state a stage refuses
/// (a singular or non-finite solve) makes IDA retry with a smaller step, at most 100 times
/// between two outputs; if IDA then fails, the refusing stage's status and message are returned
/// (IDA's code still in d->ida_flag). The run allocates only at its start: IDA is given its
/// iteration matrix (the difference quotient IDA would form) without allocation.
/// Statuses: VT_ERR_IDA (IDA's code in d->ida_flag, its message in
/// d->message), VT_ERR_BAD_OPTION, VT_ERR_MODEL_MISMATCH, VT_ERR_NEWTON (consistent initial
/// values, or a projection), VT_ERR_ABORTED, VT_ERR_NO_MEMORY, and those of the stages;
/// VT_ERR_BAD_OPTION for contacts (opt->contacts: a kinematic analysis's).
/// Only in builds with SUNDIALS (VT_HAVE_SUNDIALS, vtdyn/version.h).
#if VT_HAVE_SUNDIALS
VT_API vt_status vt_dynamic_analysis(const vt_model *model, vt_data *data, const vt_run_options *opt,
                              vt_trajectory *trajectory);
#endif

/* ---- batches: many states on threads -------------------------------------------------------- */

/// Defaults: threads 0 (every CPU the process may run on), stop_on_error 0, no contacts.
VT_API vt_batch_def vt_default_batch_def(void);
/// A batch of the model (which must outlive it) with the def's threads (NULL: the defaults): one
/// data per thread (and with contacts one vt_contacts per thread), made here once, so that a call
/// allocates nothing per row, and the threads beyond the caller's started here (asleep until a
/// call; vt_batch_free() ends them). A thread the system refuses leaves the batch fewer
/// (vt_batch_threads()). Statuses: VT_ERR_NULL, VT_ERR_BAD_OPTION (threads < 0, stop_on_error
/// not 0 or 1, ncontact < 0 or contacts NULL with some), VT_ERR_NO_MEMORY, and those of
/// vt_data_create() and vt_contacts_create() (which gives a refused contact's message). On failure
/// *batch is NULL.
VT_API vt_status vt_batch_create(vt_batch **batch, const vt_model *model, const vt_batch_def *def);
/// Frees the batch and its data (NULL is allowed).
VT_API void vt_batch_free(vt_batch *batch);
/// The threads a call uses (the def's, or the CPUs counted when it asked for 0; fewer when the
/// system refused to start some).
VT_API int vt_batch_threads(const vt_batch *batch);
/// vt_inverse_dynamics_motion() on every row of io (vt_batch_io: the layout; with the def's contacts
/// vt_inverse_dynamics_contacts(), each row's active contacts from io->contact_active and their
/// forces into io->contact_force), the rows shared among
/// the batch's threads in blocks of 16 taken in turn, so that a thread the machine slows takes
/// fewer (the caller's thread and the batch's workers, started with it and asleep between calls:
/// a call creates no thread and allocates nothing; a call of one block stays on the caller's
/// thread). One call at a time on a batch: threads that solve at once each need their own (a
/// call while another runs on the batch, from another thread or from vt_batch_run's work,
/// returns VT_ERR_BAD_OPTION at once, the running call's message and failed row left as they are).
/// Each row is solved from its own inputs alone (the data's applied loads xfrc zero, qfrc and
/// the time the row's or zero): its results are bitwise those of the single call, whatever the
/// number of threads. With io->nload wrenches at frames the row's instant carries
/// them as it carries xfrc (with contacts, before the ground's forces are shared, which then
/// balance them too): the single call with the same loads put into xfrc by vt_add_frame_load()
/// after vt_kinematics() (bitwise with loops or couplings, to round-off on a tree, whose passes
/// take them in another order), and the same bits whatever the threads.
/// A failing row's outputs are not written; its status goes to
/// io->status, and the other rows are solved (unless stop_on_error). Returns VT_OK when every row
/// succeeded, else the status of the failing row of lowest index (vt_batch_failed_row(), its
/// message vt_batch_message()); a NaN or Inf load fails its row with VT_ERR_NONFINITE. Before
/// any row: VT_ERR_NULL (batch, io, q, qd or qdd NULL with rows, load_frame or load NULL with
/// loads), VT_ERR_BAD_SIZE (nrow or nload < 0, a stride below its row's length), VT_ERR_BAD_INDEX
/// (a load's frame out of range or on the ground), nothing written.
VT_API vt_status vt_batch_inverse_dynamics_motion(vt_batch *batch, const vt_batch_io *io);
/// The failing row of lowest index of the last call, or −1 when every row succeeded.
VT_API int vt_batch_failed_row(const vt_batch *batch);
/// The last call's message: "row R: ..." for its failing row of lowest index, or what the call
/// refused before any row; "" after a success (never NULL).
VT_API const char *vt_batch_message(const vt_batch *batch);
/// The caller's own work around its rows (a log's numbers parsed, results formatted) on the
/// batch's threads, as the batch shares its rows: work(ctx, 0) on the calling thread and
/// work(ctx, k), k = 1 … vt_batch_threads() − 1, on each worker that wakes while the caller's
/// part runs; returns once every part has returned. A worker that wakes after the caller's part
/// is done takes no part, so each part must take the work's items itself, the next from a shared
/// counter (an atomic_int) until none is left, and no part may wait for another. The batch's
/// data are not touched. One call at a time on a batch, this or vt_batch_inverse_dynamics_motion
/// (a call from the work itself, or from another thread while one runs, returns
/// VT_ERR_BAD_OPTION at once). VT_ERR_NULL (batch or work NULL), else VT_OK.
VT_API vt_status vt_batch_run(vt_batch *batch, vt_batch_work work, void *ctx);

/* ---- contacts ------------------------------------------------------------------------ */

/// The defaults of a contact: body 1, point 0, no frame, normal 0 (opposite to gravity),
/// VT_CONTACT_UNILATERAL, mu 1, 4 faces, weight VT_CONTACT_WEIGHT.
VT_API vt_contact_def vt_default_contact_def(void);
/// Validates n contact definitions on a model (a frame's name resolved to its body and point, the
/// normal made a unit vector, the friction pyramid's faces laid out) and makes their solver's
/// workspace, once. effort_weight: w_a > 0 of each rate's effort in the rule (nv; NULL: 1 each,
/// in the effort's own unit, N·m or N). Statuses: VT_ERR_NULL, VT_ERR_BAD_INDEX (a body out of
/// range, n < 1), VT_ERR_NOT_FOUND (a frame), VT_ERR_BAD_NAME (a name twice or too long),
/// VT_ERR_BAD_OPTION (mu < 0, faces out of 3..64, a weight not > 0, a zero normal without gravity
/// to take it from; a model with cut joints or couplings, whose given motion fixes the drives'
/// rates only: contacts take a tree's), VT_ERR_NONFINITE, VT_ERR_NO_MEMORY; the message in
/// message (may be NULL).
/// On failure *contacts is NULL.
VT_API vt_status vt_contacts_create(vt_contacts **contacts, const vt_model *model, const vt_contact_def *defs,
                                    int n, const double *effort_weight, char *message);
/// Frees the contacts (NULL is allowed).
VT_API void vt_contacts_free(vt_contacts *contacts);
/// The number of contacts (0 for NULL).
VT_API int vt_contacts_count(const vt_contacts *contacts);
/// Index of the contact of that name, or VT_ERR_NOT_FOUND.
VT_API int vt_find_contact(const vt_contacts *contacts, const char *name);
/// The given motion of a robot standing on its contacts (docs/contact.md): the instant of
/// vt_inverse_dynamics_motion() (q, q̇, q̈, the data's xfrc and qfrc), where the rates of free
/// joints (VT_JOINT_FREE: a floating root) are not actuated and the ground's forces f_c at the
/// active contacts (active[c] != 0; NULL: all) carry what they cannot. The forces are the
/// solution of the convex problem
///     minimize ½ Σ_a w_a τ_a² + ½ Σ_c w_c |f_c|²  over the active f_c,
///     subject to τ_u = 0 on the unactuated rates, and, for a unilateral contact,
///     n·f_c ≥ 0 and d_j·f_c ≤ μ cos(π/k) n·f_c on each of its pyramid's k faces,
/// where τ = M*(q) q̈ − Q − Σ_c J_cᵀ f_c are the efforts; then the forces are applied to the
/// instant by its inward pass alone (the instant is linear in the loads), so that every effort
/// (qfrc_drive, zero to round-off on the unactuated rates) and every joint reaction in the data
/// include them. force: 3 per contact (in the order
/// of the definitions), the ground's force on the body, global, 0 at an inactive contact.
/// Statuses: those of vt_inverse_dynamics_motion(); VT_ERR_CONTACT where no forces within the
/// contacts' limits give the motion (the message names the contact that would have to pull or
/// slip, or says that the active contacts cannot give the unactuated rates' forces); then force
/// is untouched and the data's efforts are not the answer. VT_ERR_MODEL_MISMATCH: contacts made for
/// another model. The data's xfrc is as the caller left it on return.
VT_API vt_status vt_inverse_dynamics_contacts(const vt_model *model, vt_data *data, vt_contacts *contacts,
                                              const int *active, double *force);

/// Which results of the last successful vt_inverse_dynamics_contacts() on this data (the same
/// state and active contacts) the motion and the contacts fix, and which the distribution rule
/// decides (docs/contact.md#uniqueness): a result is fixed (1) when every set of forces that
/// the unactuated rates' equations allow gives it the same value, the rule only choosing among
/// those (0). effort_unique: nv (NULL: not wanted); force_unique: 3 per contact, world axes
/// (NULL: not wanted; an inactive contact's 1: its force is zero); and the data's jnt_unique,
/// per reaction component as vt_data documents it. The pushing and friction limits do not
/// count: the flags are those of the same contacts made bilateral (what spherical cut joints at
/// the contacts with vt_model_def.allow_redundant flag). The data's efforts, reactions and
/// limits are as the instant left them. Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH,
/// VT_ERR_BAD_OPTION (no contacts' instant on this data before),
/// VT_ERR_LAPACK. Not for the per-instant path: a singular value decomposition and an inward
/// pass per direction the rule chooses along.
VT_API vt_status vt_contacts_unique(const vt_model *model, vt_data *data, vt_contacts *contacts, const int *active,
                                    int *effort_unique, int *force_unique);

/* ---- force transforms ---------------------------------------------------------------- */

/// Eq (7): the Cartesian force on a body with Euler parameters p of a force f and moment n
/// (global) applied at s (global vector from the body's origin to the point):
/// F = [f; 2 E^T s̃ f + 2 E^T n]. F has 7 entries. Statuses: VT_ERR_NULL (any argument NULL: pass
/// zeros for no force or no moment), VT_ERR_NONFINITE (NaN or Inf in p, s, f or n, or F
/// overflows). F is untouched on failure. (No data: no message.)
VT_API vt_status vt_cartesian_force(double F[7], const double p[4], const double s[3],
                                    const double f[3], const double n[3]);

/// Eq (10): Q = S^T F for a Cartesian force F (7n) → Q (nv), the caller's arrays.
/// Needs vt_kinematics(). Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH, VT_ERR_NONFINITE (F, or
/// Q overflows). Q is untouched on failure.
VT_API vt_status vt_generalized_force(double *Q, const vt_model *model, vt_data *data,
                               const double *F);

/// Eq (14): F_eq = R^T Q for a generalized force Q (nv) → F_eq (7n).
/// Needs vt_inverse_transform(). Statuses: VT_ERR_NULL, VT_ERR_MODEL_MISMATCH, VT_ERR_NONFINITE (Q,
/// or F_eq overflows). Feq is untouched on failure.
VT_API vt_status vt_equivalent_force(double *Feq, const vt_model *model, vt_data *data,
                              const double *Q);

#ifdef __cplusplus
}
#endif

#endif
