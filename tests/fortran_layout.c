/* The C side of tests/test_fortran_layout.f90: each public struct's size and the offset of
 * every field, in declaration order, as the C compiler lays them out. The Fortran side lists
 * the same for its bind(C) mirrors in fortran/vtdyn.f90; a field added, removed, reordered or
 * retyped in include/vtdyn/types.h without the same change there makes the test fail. */
#include <stddef.h>

#include "vtdyn.h"

#define VT_END ((size_t)-1)

static const size_t vt_model_def_layout[] = {sizeof(vt_model_def),
    offsetof(vt_model_def, gravity), offsetof(vt_model_def, rcond_min), offsetof(vt_model_def, rcond_warn),
    offsetof(vt_model_def, allow_redundant), offsetof(vt_model_def, layout), offsetof(vt_model_def, inertia_tol),
    VT_END};
static const size_t vt_function_layout[] = {sizeof(vt_function),
    offsetof(vt_function, type), offsetof(vt_function, ncoef), offsetof(vt_function, c),
    offsetof(vt_function, callback), offsetof(vt_function, user), offsetof(vt_function, nsample),
    offsetof(vt_function, sample_t), offsetof(vt_function, sample_y), offsetof(vt_function, sample_d2), VT_END};
static const size_t vt_drive_def_layout[] = {sizeof(vt_drive_def),
    offsetof(vt_drive_def, type), offsetof(vt_drive_def, body), offsetof(vt_drive_def, index),
    offsetof(vt_drive_def, point), offsetof(vt_drive_def, f), offsetof(vt_drive_def, axis),
    offsetof(vt_drive_def, orientation), offsetof(vt_drive_def, orientation_callback),
    offsetof(vt_drive_def, user), offsetof(vt_drive_def, name), offsetof(vt_drive_def, frame),
    offsetof(vt_drive_def, reference), offsetof(vt_drive_def, sequence), offsetof(vt_drive_def, f2),
    offsetof(vt_drive_def, f3), VT_END};
static const size_t vt_cut_joint_def_layout[] = {sizeof(vt_cut_joint_def),
    offsetof(vt_cut_joint_def, joint), offsetof(vt_cut_joint_def, body_a), offsetof(vt_cut_joint_def, body_b),
    offsetof(vt_cut_joint_def, point_a), offsetof(vt_cut_joint_def, point_b),
    offsetof(vt_cut_joint_def, axis1), offsetof(vt_cut_joint_def, axis2),
    offsetof(vt_cut_joint_def, orientation), offsetof(vt_cut_joint_def, name), offsetof(vt_cut_joint_def, frame_a),
    offsetof(vt_cut_joint_def, frame_b), offsetof(vt_cut_joint_def, planar), VT_END};
static const size_t vt_body_def_layout[] = {sizeof(vt_body_def),
    offsetof(vt_body_def, parent), offsetof(vt_body_def, joint), offsetof(vt_body_def, mass),
    offsetof(vt_body_def, inertia), offsetof(vt_body_def, joint_parent), offsetof(vt_body_def, joint_child),
    offsetof(vt_body_def, axis1), offsetof(vt_body_def, axis2), offsetof(vt_body_def, orientation),
    offsetof(vt_body_def, name), offsetof(vt_body_def, joint_name), offsetof(vt_body_def, limit_lower),
    offsetof(vt_body_def, limit_upper), offsetof(vt_body_def, limit_velocity), offsetof(vt_body_def, limit_effort),
    offsetof(vt_body_def, armature), offsetof(vt_body_def, damping), offsetof(vt_body_def, friction),
    offsetof(vt_body_def, friction_velocity), offsetof(vt_body_def, gear_ratio),
    offsetof(vt_body_def, joint_frame), VT_END};
static const size_t vt_coupling_def_layout[] = {sizeof(vt_coupling_def),
    offsetof(vt_coupling_def, body_a), offsetof(vt_coupling_def, index_a), offsetof(vt_coupling_def, body_b),
    offsetof(vt_coupling_def, index_b), offsetof(vt_coupling_def, ratio), offsetof(vt_coupling_def, offset),
    offsetof(vt_coupling_def, name), VT_END};
static const size_t vt_frame_def_layout[] = {sizeof(vt_frame_def),
    offsetof(vt_frame_def, name), offsetof(vt_frame_def, body), offsetof(vt_frame_def, point),
    offsetof(vt_frame_def, orientation), offsetof(vt_frame_def, reference), VT_END};
static const size_t vt_payload_def_layout[] = {sizeof(vt_payload_def),
    offsetof(vt_payload_def, body), offsetof(vt_payload_def, frame), offsetof(vt_payload_def, mass),
    offsetof(vt_payload_def, point), offsetof(vt_payload_def, inertia), VT_END};
static const size_t vt_contact_def_layout[] = {sizeof(vt_contact_def),
    offsetof(vt_contact_def, name), offsetof(vt_contact_def, body), offsetof(vt_contact_def, point),
    offsetof(vt_contact_def, frame), offsetof(vt_contact_def, normal), offsetof(vt_contact_def, kind),
    offsetof(vt_contact_def, mu), offsetof(vt_contact_def, faces), offsetof(vt_contact_def, weight),
    offsetof(vt_contact_def, other), VT_END};
static const size_t vt_model_layout[] = {sizeof(vt_model),
    offsetof(vt_model, nbody), offsetof(vt_model, nq), offsetof(vt_model, nv), offsetof(vt_model, nx),
    offsetof(vt_model, gravity), offsetof(vt_model, body_parent), offsetof(vt_model, body_joint),
    offsetof(vt_model, body_qadr), offsetof(vt_model, body_nq), offsetof(vt_model, body_vadr),
    offsetof(vt_model, body_nv), offsetof(vt_model, body_mass), offsetof(vt_model, body_inertia),
    offsetof(vt_model, body_jpar), offsetof(vt_model, body_jchild), offsetof(vt_model, body_axis),
    offsetof(vt_model, body_quat0), offsetof(vt_model, body_pathnum), offsetof(vt_model, maxpath),
    offsetof(vt_model, dof_body), offsetof(vt_model, dof_parent), offsetof(vt_model, q0), offsetof(vt_model, dof_limit),
    offsetof(vt_model, dof_effects),
    offsetof(vt_model, body_name), offsetof(vt_model, joint_name), offsetof(vt_model, drive_name),
    offsetof(vt_model, cut_name), offsetof(vt_model, coupling_name), offsetof(vt_model, nframe), offsetof(vt_model, frame_name),
    offsetof(vt_model, frame_body), offsetof(vt_model, frame_point), offsetof(vt_model, frame_quat),
    offsetof(vt_model, rcond_min),
    offsetof(vt_model, rcond_warn), offsetof(vt_model, allow_redundant), offsetof(vt_model, layout), offsetof(vt_model, ndrive),
    offsetof(vt_model, ncut), offsetof(vt_model, nc), offsetof(vt_model, drive),
    offsetof(vt_model, drive_row), offsetof(vt_model, cut), offsetof(vt_model, cut_row),
    offsetof(vt_model, ncoupling), offsetof(vt_model, coupling), offsetof(vt_model, coupling_row),
    offsetof(vt_model, con_body), offsetof(vt_model, con_owner), offsetof(vt_model, dof_drive),
    offsetof(vt_model, jnt_frame), offsetof(vt_model, jnt_frame_axis), offsetof(vt_model, con_kind), offsetof(vt_model, con_dof), offsetof(vt_model, con_vec),
    offsetof(vt_model, con_point), offsetof(vt_model, joint_driven), offsetof(vt_model, joint_rows_only),
    offsetof(vt_model, joint_mix), offsetof(vt_model, has_quaternions), offsetof(vt_model, bound_length), offsetof(vt_model, bound_mass),
    offsetof(vt_model, mass_spread), offsetof(vt_model, has_effects), offsetof(vt_model, bound_effect), offsetof(vt_model, jnt_frame_A),
    offsetof(vt_model, any_limit), VT_END};
static const size_t vt_data_layout[] = {sizeof(vt_data),
    offsetof(vt_data, model), offsetof(vt_data, block), offsetof(vt_data, time), offsetof(vt_data, q),
    offsetof(vt_data, qd), offsetof(vt_data, xfrc), offsetof(vt_data, qfrc), offsetof(vt_data, x),
    offsetof(vt_data, xd), offsetof(vt_data, A), offsetof(vt_data, omega), offsetof(vt_data, jaxis),
    offsetof(vt_data, jsij), offsetof(vt_data, jd), offsetof(vt_data, jpoint), offsetof(vt_data, twist),
    offsetof(vt_data, xrel), offsetof(vt_data, origin),
    offsetof(vt_data, S),
    offsetof(vt_data, Sdqd), offsetof(vt_data, R), offsetof(vt_data, Mp), offsetof(vt_data, Mstar),
    offsetof(vt_data, F), offsetof(vt_data, h), offsetof(vt_data, Q), offsetof(vt_data, Phi),
    offsetof(vt_data, Phix), offsetof(vt_data, Phiq), offsetof(vt_data, Phit), offsetof(vt_data, gamma),
    offsetof(vt_data, qdd), offsetof(vt_data, lambda), offsetof(vt_data, route), offsetof(vt_data, fallback),
    offsetof(vt_data, rcond), offsetof(vt_data, warning), offsetof(vt_data, rank), offsetof(vt_data, residual),
    offsetof(vt_data, lambda_unique), offsetof(vt_data, lambda_null), offsetof(vt_data, xdd),
    offsetof(vt_data, alpha), offsetof(vt_data, qfrc_drive), offsetof(vt_data, effort_armature),
    offsetof(vt_data, effort_damping), offsetof(vt_data, effort_friction), offsetof(vt_data, drive_effort), offsetof(vt_data, drive_force),
    offsetof(vt_data, drive_moment), offsetof(vt_data, jnt_force), offsetof(vt_data, jnt_moment),
    offsetof(vt_data, jnt_force_body), offsetof(vt_data, jnt_moment_body),
    offsetof(vt_data, jnt_force_total), offsetof(vt_data, jnt_moment_total), offsetof(vt_data, jnt_force_total_body),
    offsetof(vt_data, jnt_moment_total_body), offsetof(vt_data, cut_force),
    offsetof(vt_data, cut_moment), offsetof(vt_data, cut_force_body), offsetof(vt_data, cut_moment_body), offsetof(vt_data, coupling_effort),
    offsetof(vt_data, jnt_unique), offsetof(vt_data, cut_unique),
    offsetof(vt_data, jnt_force_joint), offsetof(vt_data, jnt_moment_joint), offsetof(vt_data, jnt_bearing),
    offsetof(vt_data, limit_excess), offsetof(vt_data, nlimit), offsetof(vt_data, arena),
    offsetof(vt_data, ida_flag), offsetof(vt_data, message), VT_END};
static const size_t vt_run_options_layout[] = {sizeof(vt_run_options),
    offsetof(vt_run_options, t0), offsetof(vt_run_options, t1), offsetof(vt_run_options, nout),
    offsetof(vt_run_options, rtol), offsetof(vt_run_options, atol), offsetof(vt_run_options, max_step),
    offsetof(vt_run_options, max_steps), offsetof(vt_run_options, newton_tol),
    offsetof(vt_run_options, newton_maxit), offsetof(vt_run_options, forward_check),
    offsetof(vt_run_options, forward_independent), offsetof(vt_run_options, history_steps),
    offsetof(vt_run_options, forward_as_loads), offsetof(vt_run_options, formulation),
    offsetof(vt_run_options, baumgarte_alpha), offsetof(vt_run_options, baumgarte_beta),
    offsetof(vt_run_options, progress), offsetof(vt_run_options, user), offsetof(vt_run_options, tout),
    offsetof(vt_run_options, ntout), offsetof(vt_run_options, redundant_band),
    offsetof(vt_run_options, check_window), offsetof(vt_run_options, contacts),
    offsetof(vt_run_options, contact_schedule), offsetof(vt_run_options, contact_user),
    offsetof(vt_run_options, nload), offsetof(vt_run_options, load_frame), offsetof(vt_run_options, loads),
    offsetof(vt_run_options, load_user), VT_END};
static const size_t vt_trajectory_layout[] = {sizeof(vt_trajectory),
    offsetof(vt_trajectory, model), offsetof(vt_trajectory, nrow), offsetof(vt_trajectory, nfilled),
    offsetof(vt_trajectory, t), offsetof(vt_trajectory, q), offsetof(vt_trajectory, qd),
    offsetof(vt_trajectory, qdd), offsetof(vt_trajectory, lambda), offsetof(vt_trajectory, qfrc_drive),
    offsetof(vt_trajectory, drive_effort), offsetof(vt_trajectory, drive_force),
    offsetof(vt_trajectory, drive_moment), offsetof(vt_trajectory, jnt_force),
    offsetof(vt_trajectory, jnt_moment), offsetof(vt_trajectory, cut_force),
    offsetof(vt_trajectory, cut_moment), offsetof(vt_trajectory, phi_norm),
    offsetof(vt_trajectory, phid_norm), offsetof(vt_trajectory, rcond), offsetof(vt_trajectory, nwarn),
    offsetof(vt_trajectory, t_warn), offsetof(vt_trajectory, q_fwd), offsetof(vt_trajectory, qd_fwd),
    offsetof(vt_trajectory, jnt_force_fwd), offsetof(vt_trajectory, jnt_moment_fwd),
    offsetof(vt_trajectory, cut_force_fwd), offsetof(vt_trajectory, cut_moment_fwd),
    offsetof(vt_trajectory, fwd_err_q), offsetof(vt_trajectory, fwd_err_qd),
    offsetof(vt_trajectory, fwd_err_force), offsetof(vt_trajectory, fwd_err_moment),
    offsetof(vt_trajectory, fwd_interp_err), offsetof(vt_trajectory, steps),
    offsetof(vt_trajectory, res_evals), offsetof(vt_trajectory, steps_fwd),
    offsetof(vt_trajectory, res_evals_fwd), offsetof(vt_trajectory, nwindow),
    offsetof(vt_trajectory, fwd_window_row), offsetof(vt_trajectory, fwd_window_err_q),
    offsetof(vt_trajectory, fwd_window_err_qd), offsetof(vt_trajectory, fwd_window_err_force),
    offsetof(vt_trajectory, fwd_window_err_moment), offsetof(vt_trajectory, ncontact),
    offsetof(vt_trajectory, contact_force), offsetof(vt_trajectory, contact_active), VT_END};

#if VT_HAVE_URDF /* only declared in a build with libxml2: without, struct 11 has no entries */
static const size_t vt_urdf_options_layout[] = {sizeof(vt_urdf_options),
    offsetof(vt_urdf_options, model), offsetof(vt_urdf_options, floating), offsetof(vt_urdf_options, mimic),
    offsetof(vt_urdf_options, dynamics), VT_END};
#else
static const size_t vt_urdf_options_layout[] = {VT_END};
#endif

/* entry k of struct `which` (0..13, in the order of table[]): 0 its size, then the fields'
 * offsets; (size_t)-1 past the end */
size_t vt_test_layout(int which, int k);
size_t vt_test_layout(int which, int k)
{
    static const size_t *const table[] = {vt_model_def_layout, vt_function_layout, vt_drive_def_layout,
                                          vt_cut_joint_def_layout, vt_body_def_layout, vt_model_layout,
                                          vt_data_layout, vt_run_options_layout, vt_trajectory_layout,
                                          vt_frame_def_layout, vt_coupling_def_layout, vt_urdf_options_layout,
                                          vt_payload_def_layout, vt_contact_def_layout};
    if (which < 0 || which >= (int)(sizeof table / sizeof table[0]) || k < 0) return VT_END;
    for (int i = 0; i <= k; i++)
        if (table[which][i] == VT_END) return VT_END;
    return table[which][k];
}
