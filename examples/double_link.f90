! The paper's double link (Fig. 4) built from Fortran through the C API (fortran/vtdyn.f90):
! two uniform links, 2 m and 100 kg, revolute joints about z, y up, joint 2 locked by a drive
! (q2 = 0) — the same model as the C scene builder vt_scene_double_link(&m, 1) — and one
! instant of the inverse dynamics: the pair falls as one 4 m rod from the horizontal, and at
! the angle θ fallen below x it has θ̇² = 7.3575 sin θ (the first integral, from rest).
!
! Usage: double_link_f [theta_rad]   (default 0.6)
!
! Prints the state, then one line per result, name then values (full precision):
!   qdd       q̈ (rad/s²), 2 rates
!   effort    the lock's torque along joint 2, Φ_q^T λ (N·m)
!   drive_f   the force and moment the lock exerts on link 2 at joint 2 (N, N·m)
!   drive_n
!   f1 n1     reaction of the ground on link 1 at joint 1, global (N, N·m)
!   f2 n2     reaction of link 1 on link 2 at joint 2, global
! and, for a reader, the closed forms (29): f1 = [−2207.25 sin 2θ, 4905 sin²θ + 490.5 cos²θ] N,
! |τ2| = 245.25 cos θ N·m. tests/check_fortran.c compares every line with the C library's own
! scene at the same state.
program double_link_f
  use, intrinsic :: iso_c_binding
  use vtdyn
  implicit none
  real(c_double), parameter :: length = 2.0_c_double, mass = 100.0_c_double
  type(c_ptr) :: b, mp, dp
  type(vt_body_def) :: link
  type(vt_drive_def) :: lock
  type(vt_model), pointer :: m
  type(vt_data), pointer :: d
  real(c_double), pointer :: q(:), qd(:), qdd(:), effort(:), jf(:, :), jm(:, :), df(:, :), dm(:, :)
  real(c_double) :: th
  integer(c_int) :: id, st
  character(len=64) :: arg

  th = 0.6_c_double
  if (command_argument_count() >= 1) then
    call get_command_argument(1, arg)
    read (arg, *) th
  end if

  ! the model: gravity (0, −9.81, 0) by default
  call check(vt_builder_create(b), 'vt_builder_create')
  link = vt_default_body_def()            ! revolute about z to the ground
  link%mass = mass
  link%inertia(5) = mass * length**2 / 12 ! slender rod along body x: J_yy = J_zz = m L²/12
  link%inertia(9) = link%inertia(5)
  link%joint_child(1) = -0.5_c_double * length   ! joint 1 at link 1's left end, at the origin
  id = vt_builder_add_body(b, link)
  if (id < 0) call fail(id, 'link 1: ' // vt_string(vt_builder_message(b)))
  link%parent = id                        ! link 2 on link 1's right end
  link%joint_parent(1) = 0.5_c_double * length
  id = vt_builder_add_body(b, link)
  if (id < 0) call fail(id, 'link 2: ' // vt_string(vt_builder_message(b)))
  lock = vt_default_drive_def()           ! joint drive, constant 0
  lock%body = 2                           ! q2 = 0
  id = vt_builder_add_drive(b, lock)
  if (id < 0) call fail(id, 'lock: ' // vt_string(vt_builder_message(b)))
  call check(vt_builder_build(mp, b), 'vt_builder_build')
  call vt_builder_free(b)
  call c_f_pointer(mp, m)

  ! the state, and the instant
  call check(vt_data_create(dp, mp), 'vt_data_create')
  call c_f_pointer(dp, d)
  call vt_array(q, d%q, m%nq)
  call vt_array(qd, d%qd, m%nv)
  q = [-th, 0.0_c_double]
  qd = [-sqrt(7.3575_c_double * sin(th)), 0.0_c_double]
  st = vt_inverse_dynamics(mp, dp)
  if (st /= VT_OK) call fail(st, 'vt_inverse_dynamics: ' // vt_message(d))

  call vt_array(qdd, d%qdd, m%nv)
  call vt_array(effort, d%drive_effort, m%ndrive)
  call vt_array(df, d%drive_force, 3_c_int, m%ndrive)
  call vt_array(dm, d%drive_moment, 3_c_int, m%ndrive)
  call vt_body_array(jf, d%jnt_force, 3_c_int, m%nbody)
  call vt_body_array(jm, d%jnt_moment, 3_c_int, m%nbody)

  print '(a, i0, a, i0, a, i0, a)', 'vtdyn double link from Fortran: ', m%nbody, ' bodies, ', m%nv, &
      ' rates, ', m%nc, ' constraint row'
  print '(a, es24.16e3)', 'theta ', th
  print '(a, 2es26.17e3)', 'q ', q
  print '(a, 2es26.17e3)', 'qd ', qd
  print '(a, 2es26.17e3)', 'qdd ', qdd
  print '(a, es26.17e3)', 'effort ', effort(1)
  print '(a, 3es26.17e3)', 'drive_f ', df(:, 1)
  print '(a, 3es26.17e3)', 'drive_n ', dm(:, 1)
  print '(a, 3es26.17e3)', 'f1 ', jf(:, 1)
  print '(a, 3es26.17e3)', 'n1 ', jm(:, 1)
  print '(a, 3es26.17e3)', 'f2 ', jf(:, 2)
  print '(a, 3es26.17e3)', 'n2 ', jm(:, 2)
  print '(a, 2f14.6, a, f12.6, a)', '# (29): f1 = ', -2207.25_c_double * sin(2 * th), &
      4905.0_c_double * sin(th)**2 + 490.5_c_double * cos(th)**2, ' N, |tau2| = ', &
      245.25_c_double * cos(th), ' N m'

  call vt_data_free(dp)
  call vt_model_free(mp)

contains

  subroutine check(status, what)
    integer(c_int), intent(in) :: status
    character(len=*), intent(in) :: what
    if (status /= VT_OK) call fail(status, what)
  end subroutine check

  subroutine fail(status, what)
    integer(c_int), intent(in) :: status
    character(len=*), intent(in) :: what
    write (0, '(a)') 'double_link_f: ' // what // ': ' // vt_string(vt_status_string(status))
    error stop 1
  end subroutine fail

end program double_link_f
