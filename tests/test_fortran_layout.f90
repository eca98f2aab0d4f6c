! The Fortran mirrors of the C structs (fortran/vtdyn.f90) against the C compiler's layout
! (tests/fortran_layout.c): each struct's size and every field's offset, in declaration order.
! Also the by-value struct returns of the defaults, read through the mirrors. Prints one line
! per struct; exits non-zero (error stop) on the first difference. Preprocessed (-cpp): the
! URDF options exist in C only when VT_HAVE_URDF is 1 (tests/meson.build passes it).
program test_fortran_layout
  use, intrinsic :: iso_c_binding
  use vtdyn
  implicit none
  interface
    function vt_test_layout(which, k) bind(C, name='vt_test_layout')
      import :: c_int, c_size_t
      integer(c_int), value :: which, k
      integer(c_size_t) :: vt_test_layout
    end function
  end interface
  type(vt_model_def), target :: x_model_def
  type(vt_function), target :: x_function
  type(vt_drive_def), target :: x_drive_def
  type(vt_cut_joint_def), target :: x_cut_joint_def
  type(vt_body_def), target :: x_body_def
  type(vt_frame_def), target :: x_frame_def
  type(vt_coupling_def), target :: x_coupling_def
  type(vt_model), target :: x_model
  type(vt_data), target :: x_data
  type(vt_run_options), target :: x_run_options
  type(vt_trajectory), target :: x_trajectory
  type(vt_urdf_options), target :: x_urdf_options
  type(vt_payload_def), target :: x_payload_def
  type(vt_contact_def), target :: x_contact_def
  integer :: nfail

  nfail = 0
    call check(0_c_int, 'vt_model_def', c_sizeof(x_model_def), a(c_loc(x_model_def)), [ &
         a(c_loc(x_model_def%gravity)), a(c_loc(x_model_def%rcond_min)), a(c_loc(x_model_def%rcond_warn)), &
         a(c_loc(x_model_def%allow_redundant)), a(c_loc(x_model_def%layout)), a(c_loc(x_model_def%inertia_tol))])
    call check(1_c_int, 'vt_function', c_sizeof(x_function), a(c_loc(x_function)), [ &
         a(c_loc(x_function%type)), a(c_loc(x_function%ncoef)), a(c_loc(x_function%c)), &
         a(c_loc(x_function%callback)), a(c_loc(x_function%user)), a(c_loc(x_function%nsample)), &
         a(c_loc(x_function%sample_t)), a(c_loc(x_function%sample_y)), a(c_loc(x_function%sample_d2))])
    call check(2_c_int, 'vt_drive_def', c_sizeof(x_drive_def), a(c_loc(x_drive_def)), [ &
         a(c_loc(x_drive_def%type)), a(c_loc(x_drive_def%body)), a(c_loc(x_drive_def%index)), &
         a(c_loc(x_drive_def%point)), a(c_loc(x_drive_def%f)), a(c_loc(x_drive_def%axis)), &
         a(c_loc(x_drive_def%orientation)), a(c_loc(x_drive_def%orientation_callback)), &
         a(c_loc(x_drive_def%user)), a(c_loc(x_drive_def%name)), a(c_loc(x_drive_def%frame)), &
         a(c_loc(x_drive_def%reference)), a(c_loc(x_drive_def%sequence)), a(c_loc(x_drive_def%f2)), &
         a(c_loc(x_drive_def%f3))])
    call check(3_c_int, 'vt_cut_joint_def', c_sizeof(x_cut_joint_def), a(c_loc(x_cut_joint_def)), [ &
         a(c_loc(x_cut_joint_def%joint)), a(c_loc(x_cut_joint_def%body_a)), a(c_loc(x_cut_joint_def%body_b)), &
         a(c_loc(x_cut_joint_def%point_a)), a(c_loc(x_cut_joint_def%point_b)), &
         a(c_loc(x_cut_joint_def%axis1)), a(c_loc(x_cut_joint_def%axis2)), &
         a(c_loc(x_cut_joint_def%orientation)), a(c_loc(x_cut_joint_def%name)), a(c_loc(x_cut_joint_def%frame_a)), &
         a(c_loc(x_cut_joint_def%frame_b)), a(c_loc(x_cut_joint_def%planar))])
    call check(4_c_int, 'vt_body_def', c_sizeof(x_body_def), a(c_loc(x_body_def)), [ &
         a(c_loc(x_body_def%parent)), a(c_loc(x_body_def%joint)), a(c_loc(x_body_def%mass)), &
         a(c_loc(x_body_def%inertia)), a(c_loc(x_body_def%joint_parent)), a(c_loc(x_body_def%joint_child)), &
         a(c_loc(x_body_def%axis1)), a(c_loc(x_body_def%axis2)), a(c_loc(x_body_def%orientation)), &
         a(c_loc(x_body_def%name)), a(c_loc(x_body_def%joint_name)), a(c_loc(x_body_def%limit_lower)), &
         a(c_loc(x_body_def%limit_upper)), a(c_loc(x_body_def%limit_velocity)), a(c_loc(x_body_def%limit_effort)), &
         a(c_loc(x_body_def%armature)), a(c_loc(x_body_def%damping)), a(c_loc(x_body_def%friction)), &
         a(c_loc(x_body_def%friction_velocity)), a(c_loc(x_body_def%gear_ratio)), &
         a(c_loc(x_body_def%joint_frame))])
    call check(5_c_int, 'vt_model', c_sizeof(x_model), a(c_loc(x_model)), [ &
         a(c_loc(x_model%nbody)), a(c_loc(x_model%nq)), a(c_loc(x_model%nv)), a(c_loc(x_model%nx)), &
         a(c_loc(x_model%gravity)), a(c_loc(x_model%body_parent)), a(c_loc(x_model%body_joint)), &
         a(c_loc(x_model%body_qadr)), a(c_loc(x_model%body_nq)), a(c_loc(x_model%body_vadr)), &
         a(c_loc(x_model%body_nv)), a(c_loc(x_model%body_mass)), a(c_loc(x_model%body_inertia)), &
         a(c_loc(x_model%body_jpar)), a(c_loc(x_model%body_jchild)), a(c_loc(x_model%body_axis)), &
         a(c_loc(x_model%body_quat0)), a(c_loc(x_model%body_pathnum)), a(c_loc(x_model%maxpath)), &
         a(c_loc(x_model%dof_body)), a(c_loc(x_model%dof_parent)), a(c_loc(x_model%q0)), a(c_loc(x_model%dof_limit)), &
         a(c_loc(x_model%dof_effects)), &
         a(c_loc(x_model%body_name)), a(c_loc(x_model%joint_name)), a(c_loc(x_model%drive_name)), &
         a(c_loc(x_model%cut_name)), a(c_loc(x_model%coupling_name)), a(c_loc(x_model%nframe)), &
         a(c_loc(x_model%frame_name)), &
         a(c_loc(x_model%frame_body)), a(c_loc(x_model%frame_point)), a(c_loc(x_model%frame_quat)), &
         a(c_loc(x_model%rcond_min)), &
         a(c_loc(x_model%rcond_warn)), a(c_loc(x_model%allow_redundant)), a(c_loc(x_model%layout)), &
         a(c_loc(x_model%ndrive)), &
         a(c_loc(x_model%ncut)), a(c_loc(x_model%nc)), a(c_loc(x_model%drive)), a(c_loc(x_model%drive_row)), &
         a(c_loc(x_model%cut)), a(c_loc(x_model%cut_row)), a(c_loc(x_model%ncoupling)), &
         a(c_loc(x_model%coupling)), a(c_loc(x_model%coupling_row)), a(c_loc(x_model%con_body)), &
         a(c_loc(x_model%con_owner)), a(c_loc(x_model%dof_drive)), a(c_loc(x_model%jnt_frame)), &
         a(c_loc(x_model%jnt_frame_axis)), a(c_loc(x_model%con_kind)), &
         a(c_loc(x_model%con_dof)), a(c_loc(x_model%con_vec)), a(c_loc(x_model%con_point)), &
         a(c_loc(x_model%joint_driven)), a(c_loc(x_model%joint_rows_only)), &
         a(c_loc(x_model%joint_mix)), a(c_loc(x_model%has_quaternions)), &
         a(c_loc(x_model%bound_length)), a(c_loc(x_model%bound_mass)), a(c_loc(x_model%mass_spread)), &
         a(c_loc(x_model%has_effects)), a(c_loc(x_model%bound_effect)), a(c_loc(x_model%jnt_frame_A)), a(c_loc(x_model%any_limit))])
    call check(6_c_int, 'vt_data', c_sizeof(x_data), a(c_loc(x_data)), [ &
         a(c_loc(x_data%model)), a(c_loc(x_data%block)), a(c_loc(x_data%time)), a(c_loc(x_data%q)), &
         a(c_loc(x_data%qd)), a(c_loc(x_data%xfrc)), a(c_loc(x_data%qfrc)), a(c_loc(x_data%x)), &
         a(c_loc(x_data%xd)), a(c_loc(x_data%A)), a(c_loc(x_data%omega)), a(c_loc(x_data%jaxis)), &
         a(c_loc(x_data%jsij)), a(c_loc(x_data%jd)), a(c_loc(x_data%jpoint)), a(c_loc(x_data%twist)), &
         a(c_loc(x_data%xrel)), a(c_loc(x_data%origin)), a(c_loc(x_data%S)), &
         a(c_loc(x_data%Sdqd)), a(c_loc(x_data%R)), a(c_loc(x_data%Mp)), a(c_loc(x_data%Mstar)), &
         a(c_loc(x_data%F)), a(c_loc(x_data%h)), a(c_loc(x_data%Qgen)), a(c_loc(x_data%Phi)), &
         a(c_loc(x_data%Phix)), a(c_loc(x_data%Phiq)), a(c_loc(x_data%Phit)), a(c_loc(x_data%gamma)), &
         a(c_loc(x_data%qdd)), a(c_loc(x_data%lambda)), a(c_loc(x_data%route)), a(c_loc(x_data%fallback)), &
         a(c_loc(x_data%rcond)), a(c_loc(x_data%warning)), a(c_loc(x_data%rank)), a(c_loc(x_data%residual)), &
         a(c_loc(x_data%lambda_unique)), a(c_loc(x_data%lambda_null)), a(c_loc(x_data%xdd)), &
         a(c_loc(x_data%alpha)), a(c_loc(x_data%qfrc_drive)), a(c_loc(x_data%effort_armature)), &
         a(c_loc(x_data%effort_damping)), a(c_loc(x_data%effort_friction)), a(c_loc(x_data%drive_effort)), &
         a(c_loc(x_data%drive_force)), &
         a(c_loc(x_data%drive_moment)), a(c_loc(x_data%jnt_force)), a(c_loc(x_data%jnt_moment)), &
         a(c_loc(x_data%jnt_force_body)), a(c_loc(x_data%jnt_moment_body)), &
         a(c_loc(x_data%jnt_force_total)), a(c_loc(x_data%jnt_moment_total)), &
         a(c_loc(x_data%jnt_force_total_body)), a(c_loc(x_data%jnt_moment_total_body)), a(c_loc(x_data%cut_force)), &
         a(c_loc(x_data%cut_moment)), a(c_loc(x_data%cut_force_body)), a(c_loc(x_data%cut_moment_body)), &
         a(c_loc(x_data%coupling_effort)), &
         a(c_loc(x_data%jnt_unique)), a(c_loc(x_data%cut_unique)), &
         a(c_loc(x_data%jnt_force_joint)), a(c_loc(x_data%jnt_moment_joint)), a(c_loc(x_data%jnt_bearing)), &
         a(c_loc(x_data%limit_excess)), a(c_loc(x_data%nlimit)), a(c_loc(x_data%arena)), &
         a(c_loc(x_data%ida_flag)), a(c_loc(x_data%message))])
    call check(7_c_int, 'vt_run_options', c_sizeof(x_run_options), a(c_loc(x_run_options)), [ &
         a(c_loc(x_run_options%t0)), a(c_loc(x_run_options%t1)), a(c_loc(x_run_options%nout)), &
         a(c_loc(x_run_options%rtol)), a(c_loc(x_run_options%atol)), a(c_loc(x_run_options%max_step)), &
         a(c_loc(x_run_options%max_steps)), a(c_loc(x_run_options%newton_tol)), &
         a(c_loc(x_run_options%newton_maxit)), a(c_loc(x_run_options%forward_check)), &
         a(c_loc(x_run_options%forward_independent)), a(c_loc(x_run_options%history_steps)), &
         a(c_loc(x_run_options%forward_as_loads)), a(c_loc(x_run_options%formulation)), &
         a(c_loc(x_run_options%baumgarte_alpha)), a(c_loc(x_run_options%baumgarte_beta)), &
         a(c_loc(x_run_options%progress)), a(c_loc(x_run_options%user)), a(c_loc(x_run_options%tout)), &
         a(c_loc(x_run_options%ntout)), a(c_loc(x_run_options%redundant_band)), &
         a(c_loc(x_run_options%check_window)), a(c_loc(x_run_options%contacts)), &
         a(c_loc(x_run_options%contact_schedule)), a(c_loc(x_run_options%contact_user)), &
         a(c_loc(x_run_options%nload)), a(c_loc(x_run_options%load_frame)), a(c_loc(x_run_options%loads)), &
         a(c_loc(x_run_options%load_user))])
    call check(8_c_int, 'vt_trajectory', c_sizeof(x_trajectory), a(c_loc(x_trajectory)), [ &
         a(c_loc(x_trajectory%model)), a(c_loc(x_trajectory%nrow)), a(c_loc(x_trajectory%nfilled)), &
         a(c_loc(x_trajectory%t)), a(c_loc(x_trajectory%q)), a(c_loc(x_trajectory%qd)), &
         a(c_loc(x_trajectory%qdd)), a(c_loc(x_trajectory%lambda)), a(c_loc(x_trajectory%qfrc_drive)), &
         a(c_loc(x_trajectory%drive_effort)), a(c_loc(x_trajectory%drive_force)), &
         a(c_loc(x_trajectory%drive_moment)), a(c_loc(x_trajectory%jnt_force)), &
         a(c_loc(x_trajectory%jnt_moment)), a(c_loc(x_trajectory%cut_force)), &
         a(c_loc(x_trajectory%cut_moment)), a(c_loc(x_trajectory%phi_norm)), a(c_loc(x_trajectory%phid_norm)), &
         a(c_loc(x_trajectory%rcond)), a(c_loc(x_trajectory%nwarn)), a(c_loc(x_trajectory%t_warn)), &
         a(c_loc(x_trajectory%q_fwd)), a(c_loc(x_trajectory%qd_fwd)), a(c_loc(x_trajectory%jnt_force_fwd)), &
         a(c_loc(x_trajectory%jnt_moment_fwd)), a(c_loc(x_trajectory%cut_force_fwd)), &
         a(c_loc(x_trajectory%cut_moment_fwd)), a(c_loc(x_trajectory%fwd_err_q)), &
         a(c_loc(x_trajectory%fwd_err_qd)), a(c_loc(x_trajectory%fwd_err_force)), &
         a(c_loc(x_trajectory%fwd_err_moment)), a(c_loc(x_trajectory%fwd_interp_err)), &
         a(c_loc(x_trajectory%steps)), a(c_loc(x_trajectory%res_evals)), a(c_loc(x_trajectory%steps_fwd)), &
         a(c_loc(x_trajectory%res_evals_fwd)), a(c_loc(x_trajectory%nwindow)), &
         a(c_loc(x_trajectory%fwd_window_row)), a(c_loc(x_trajectory%fwd_window_err_q)), &
         a(c_loc(x_trajectory%fwd_window_err_qd)), a(c_loc(x_trajectory%fwd_window_err_force)), &
         a(c_loc(x_trajectory%fwd_window_err_moment)), a(c_loc(x_trajectory%ncontact)), &
         a(c_loc(x_trajectory%contact_force)), a(c_loc(x_trajectory%contact_active))])
    call check(10_c_int, 'vt_coupling_def', c_sizeof(x_coupling_def), a(c_loc(x_coupling_def)), [ &
         a(c_loc(x_coupling_def%body_a)), a(c_loc(x_coupling_def%index_a)), a(c_loc(x_coupling_def%body_b)), &
         a(c_loc(x_coupling_def%index_b)), a(c_loc(x_coupling_def%ratio)), a(c_loc(x_coupling_def%offset)), &
         a(c_loc(x_coupling_def%name))])
    call check(9_c_int, 'vt_frame_def', c_sizeof(x_frame_def), a(c_loc(x_frame_def)), [ &
         a(c_loc(x_frame_def%name)), a(c_loc(x_frame_def%body)), a(c_loc(x_frame_def%point)), &
         a(c_loc(x_frame_def%orientation)), a(c_loc(x_frame_def%reference))])
    call check(12_c_int, 'vt_payload_def', c_sizeof(x_payload_def), a(c_loc(x_payload_def)), [ &
         a(c_loc(x_payload_def%body)), a(c_loc(x_payload_def%frame)), a(c_loc(x_payload_def%mass)), &
         a(c_loc(x_payload_def%point)), a(c_loc(x_payload_def%inertia))])
    call check(13_c_int, 'vt_contact_def', c_sizeof(x_contact_def), a(c_loc(x_contact_def)), [ &
         a(c_loc(x_contact_def%name)), a(c_loc(x_contact_def%body)), a(c_loc(x_contact_def%point)), &
         a(c_loc(x_contact_def%frame)), a(c_loc(x_contact_def%normal)), a(c_loc(x_contact_def%kind)), &
         a(c_loc(x_contact_def%mu)), a(c_loc(x_contact_def%faces)), a(c_loc(x_contact_def%weight)), &
         a(c_loc(x_contact_def%other))])
#if VT_HAVE_URDF
    call check(11_c_int, 'vt_urdf_options', c_sizeof(x_urdf_options), a(c_loc(x_urdf_options)), [ &
         a(c_loc(x_urdf_options%model)), a(c_loc(x_urdf_options%floating)), &
         a(c_loc(x_urdf_options%mimic)), a(c_loc(x_urdf_options%dynamics))])
#else
    print '(a, i0, a)', 'vt_urdf_options: not in this build (', c_sizeof(x_urdf_options), ' bytes in Fortran)'
#endif

  ! a struct returned by value below writes C's size into the Fortran variable: with a layout
  ! that differs, that would overwrite what lies beside it (nfail too), so stop here first
  if (nfail > 0) then
    print '(i0, a)', nfail, ' layout mismatches'
    error stop 1
  end if

  ! the defaults, returned by value from C (a struct return through bind(C))
  x_body_def = vt_default_body_def()
  call expect(same([x_body_def%mass], [1]) .and. x_body_def%joint == VT_JOINT_REVOLUTE .and. x_body_def%parent == 0 &
      .and. same(x_body_def%axis1, [0, 0, 1]) .and. same(x_body_def%orientation, [1, 0, 0, 0]) &
      .and. same(x_body_def%inertia, [0, 0, 0, 0, 0, 0, 0, 0, 0]), 'vt_default_body_def')
  x_model_def = vt_default_model_def()
  call expect(same(x_model_def%gravity, [0.0_c_double, -9.81_c_double, 0.0_c_double]) &
      .and. same([x_model_def%rcond_min], [1e-12_c_double]) .and. x_model_def%allow_redundant == 0 &
      .and. same([x_model_def%inertia_tol], [1e-6_c_double]), &
      'vt_default_model_def')
  x_drive_def = vt_default_drive_def()
  call expect(x_drive_def%type == VT_DRIVE_JOINT .and. x_drive_def%body == 1 .and. x_drive_def%index == 0 &
      .and. x_drive_def%f%type == VT_FUNC_CONSTANT .and. same(x_drive_def%axis, [0, 0, 1]) &
      .and. .not. c_associated(x_drive_def%orientation_callback) .and. x_drive_def%reference == -1 &
      .and. .not. c_associated(x_drive_def%sequence) .and. x_drive_def%f3%type == VT_FUNC_CONSTANT, &
      'vt_default_drive_def')
  x_function = vt_function_sine(1.0_c_double, 2.0_c_double, 3.0_c_double, 4.0_c_double)
  call expect(x_function%type == VT_FUNC_SINE .and. same(x_function%c(1:4), [1, 2, 3, 4]), 'vt_function_sine')
  x_function = vt_function_spline(3_c_int, [0.0_c_double, 1.0_c_double, 2.0_c_double], &
      [1.0_c_double, 2.0_c_double, 4.0_c_double])
  call expect(x_function%type == VT_FUNC_SPLINE .and. x_function%nsample == 3 &
      .and. .not. c_associated(x_function%sample_d2), 'vt_function_spline')
  x_cut_joint_def = vt_default_cut_joint_def()
  call expect(x_cut_joint_def%joint == VT_JOINT_REVOLUTE .and. x_cut_joint_def%body_a == 0 &
      .and. x_cut_joint_def%body_b == 1 .and. same(x_cut_joint_def%axis2, [1, 0, 0]), 'vt_default_cut_joint_def')
  x_frame_def = vt_default_frame_def()
  call expect(x_frame_def%body == 1 .and. same(x_frame_def%orientation, [1, 0, 0, 0]) &
      .and. .not. c_associated(x_frame_def%name) .and. .not. c_associated(x_frame_def%reference), 'vt_default_frame_def')
  x_payload_def = vt_default_payload_def()
  call expect(x_payload_def%body == 1 .and. .not. c_associated(x_payload_def%frame) &
      .and. same([x_payload_def%mass], [0]) .and. same(x_payload_def%inertia, [0, 0, 0, 0, 0, 0, 0, 0, 0]), &
      'vt_default_payload_def')
  x_contact_def = vt_default_contact_def()
  call expect(x_contact_def%body == 1 .and. x_contact_def%kind == VT_CONTACT_UNILATERAL .and. x_contact_def%faces == 4 &
      .and. same([x_contact_def%mu], [1]) .and. same([x_contact_def%weight], [VT_CONTACT_WEIGHT]) &
      .and. same(x_contact_def%normal, [0, 0, 0]) .and. .not. c_associated(x_contact_def%frame), &
      'vt_default_contact_def')
  x_coupling_def = vt_default_coupling_def()
  call expect(x_coupling_def%body_a == 2 .and. x_coupling_def%body_b == 1 .and. same([x_coupling_def%ratio], [1]), &
      'vt_default_coupling_def')
#if VT_HAVE_URDF
  x_urdf_options = vt_default_urdf_options()
  call expect(same(x_urdf_options%model%gravity, [0.0_c_double, 0.0_c_double, -9.81_c_double]) &
      .and. same([x_urdf_options%model%rcond_min], [1e-12_c_double]) .and. x_urdf_options%floating == 0 &
      .and. x_urdf_options%mimic == 1, &
      'vt_default_urdf_options')
#endif
  x_run_options = vt_default_run_options()
  call expect(same([x_run_options%t1], [1]) .and. x_run_options%nout == 100 .and. x_run_options%max_steps == 100000 &
      .and. x_run_options%newton_maxit == 30 .and. x_run_options%formulation == VT_FORMULATION_GGL &
      .and. .not. c_associated(x_run_options%tout) .and. x_run_options%ntout == 0 &
      .and. same([x_run_options%redundant_band], [5e-4_c_double]) &
      .and. same([x_run_options%check_window], [VT_CHECK_WINDOW]), &
      'vt_default_run_options')
  call expect(vt_string(vt_status_string(VT_ERR_BAD_SIZE)) /= vt_string(vt_status_string(VT_ERR_BAD_OPTION)), &
      'vt_status_string')

  if (nfail > 0) then
    print '(i0, a)', nfail, ' mismatches'
    error stop 1
  end if
  print '(a)', 'all layouts and defaults agree'

contains

  pure integer(c_intptr_t) function a(p)
    type(c_ptr), intent(in) :: p
    a = transfer(p, 0_c_intptr_t)
  end function a

  subroutine check(which, name, nbytes, base, field)
    integer(c_int), intent(in) :: which
    character(len=*), intent(in) :: name
    integer(c_size_t), intent(in) :: nbytes
    integer(c_intptr_t), intent(in) :: base, field(:)
    integer(c_int) :: k
    if (nbytes /= vt_test_layout(which, 0_c_int)) then
      print '(a, a, i0, a, i0)', name, ': size ', nbytes, ' in Fortran, C ', vt_test_layout(which, 0_c_int)
      nfail = nfail + 1
    end if
    do k = 1, int(size(field), c_int)
      if (field(k) - base /= int(vt_test_layout(which, k), c_intptr_t)) then
        print '(a, a, i0, a, i0, a, i0)', name, ': field ', k, ' at offset ', field(k) - base, ' in Fortran, C ', &
            vt_test_layout(which, k)
        nfail = nfail + 1
      end if
    end do
    if (vt_test_layout(which, int(size(field), c_int) + 1_c_int) /= -1_c_size_t) then
      print '(a, a, i0, a)', name, ': C has more fields than the ', size(field), ' of the Fortran mirror'
      nfail = nfail + 1
    end if
    print '(a, a, i0, a, i0, a)', name, ': ', size(field), ' fields, ', nbytes, ' bytes'
  end subroutine check

  ! exact equality of values that are exact in binary (written so: -Wcompare-reals flags ==)
  pure logical function same(x, y)
    real(c_double), intent(in) :: x(:)
    class(*), intent(in) :: y(:)
    select type (y)
    type is (integer)
      same = all(abs(x - real(y, c_double)) <= 0)
    type is (real(c_double))
      same = all(abs(x - y) <= 0)
    class default
      same = .false.
    end select
  end function same

  subroutine expect(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      print '(a, a)', what, ': values read through the mirror differ from the C defaults'
      nfail = nfail + 1
    end if
  end subroutine expect

end program test_fortran_layout
