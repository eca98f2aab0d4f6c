! vtdyn — Fortran bindings to the C library (ISO_C_BINDING, Fortran 2018).
!
! One module, `vtdyn`, that mirrors include/vtdyn.h: every public function of the C API as a
! bind(C) interface with the C name, and every public struct as a bind(C) derived type with
! the same name, the same fields in the same order (tests/test_fortran_layout checks each
! field's offset against the C compiler's). Compile this file with your program and link the
! C library:
!
!     gfortran -c vtdyn.f90 && gfortran my_program.f90 vtdyn.o $(pkg-config --libs vtdyn)
!
! Conventions are C's, stated once in include/vtdyn/types.h (units SI, Euler parameters scalar
! first, column-major matrices). Values inside the structs keep the C numbering: body ids are
! 1..n with 0 the ground, drive and cut-joint indices and a drive's `index` start at 0.
!
!   - The model, the data, a builder and a trajectory are C objects: hold them as type(c_ptr)
!     and pass those by value. To read their fields, c_f_pointer the type(c_ptr) to the mirror:
!         type(vt_data), pointer :: d;   call c_f_pointer(dp, d)
!     and the arrays they point to with vt_array / vt_body_array (the shapes are in types.h):
!         call vt_array(q, d%q, m%nq)                        ! q(1:nq)
!         call vt_body_array(jf, d%jnt_force, 3, m%nbody)    ! jf(1:3, 0:nbody), column i = body i
!     These are views of the C memory: writing q(1) sets the C data's q[0].
!     The data's arena (the stages' scratch, an opaque vt_arena) is a type(c_ptr) to leave
!     alone, and the model's internal fields (con_kind ... any_limit, last in vt_model)
!     are mirrored only to keep the layout: their meaning may change in any release.
!   - Definition structs are plain values: start from the defaults and set what you need,
!         type(vt_body_def) :: link;   link = vt_default_body_def();   link%mass = 100
!     (2-D fields are flat as in C: inertia(1:9) is the 3x3 column-major matrix).
!   - Fortran names ignore case, so two C names change: vt_data's Q (the generalized force,
!     beside q) is Qgen here, and the vt_function_type values VT_FUNCTION_CONSTANT ... are
!     VT_FUNC_CONSTANT, VT_FUNC_POLYNOMIAL, VT_FUNC_SINE, VT_FUNC_CALLBACK, VT_FUNC_SPLINE
!     (beside the functions vt_function_constant() ...).
!   - Optional C pointers are OPTIONAL arguments (vt_builder_create's def, vt_add_point_load's
!     f and n): leave them out for NULL.
!   - Strings: vt_string() turns a C string (vt_status_string, vt_builder_message, vt_version)
!     into a Fortran one; vt_message(d) gives d%message.
! vt_dynamic_analysis exists only in a library built with SUNDIALS (VT_HAVE_SUNDIALS), and
! vt_default_urdf_options, vt_urdf_builder and vt_urdf_builder_string only in one built with
! libxml2 (VT_HAVE_URDF): calling them links only against such a library.
module vtdyn
  use, intrinsic :: iso_c_binding
  implicit none

  ! ---- constants of include/vtdyn/types.h -----------------------------------------------
  ! vt_status: 0 is success, negative values are errors (vt_status_string names them)
  integer(c_int), parameter :: VT_OK = 0, VT_ERR_NULL = -1, VT_ERR_NO_MEMORY = -2, &
      VT_ERR_NONFINITE = -3, VT_ERR_MASS = -4, VT_ERR_INERTIA_ASYMMETRIC = -5, &
      VT_ERR_INERTIA_NOT_PSD = -6, VT_ERR_INERTIA_TRIANGLE = -7, VT_ERR_AXIS_ZERO = -8, &
      VT_ERR_AXES_NOT_PERPENDICULAR = -9, VT_ERR_PARENT = -10, VT_ERR_JOINT_TYPE = -11, &
      VT_ERR_TOO_MANY_BODIES = -12, VT_ERR_QUATERNION = -13, VT_ERR_EMPTY_MODEL = -14, &
      VT_ERR_BAD_INDEX = -15, VT_ERR_MODEL_MISMATCH = -16, VT_ERR_LAPACK = -17, &
      VT_ERR_BAD_DRIVE = -18, VT_ERR_BAD_CUT_JOINT = -19, VT_ERR_CALLBACK = -20, &
      VT_ERR_SINGULAR = -21, VT_ERR_DEPENDENT_CONSTRAINTS = -22, VT_ERR_NEWTON = -23, &
      VT_ERR_NOT_FULLY_DRIVEN = -24, VT_ERR_IDA = -25, VT_ERR_ABORTED = -26, &
      VT_ERR_BAD_OPTION = -27, VT_ERR_BAD_SIZE = -28, VT_ERR_BAD_NAME = -29, VT_ERR_NOT_FOUND = -30, &
      VT_ERR_FILE = -31, VT_ERR_XML = -32, VT_ERR_LAYOUT = -33, &
      VT_ERR_SKIPPED = -34, VT_ERR_CONTACT = -35
  integer(c_int), parameter :: VT_LAYOUT_FULL = 0, VT_LAYOUT_RECURSIVE = 1
  integer(c_int), parameter :: VT_CONTACT_UNILATERAL = 0, VT_CONTACT_BILATERAL = 1
  real(c_double), parameter :: VT_CONTACT_WEIGHT = 1d-4
  integer(c_int), parameter :: VT_RUN_LOADS_MAX = 64
  integer(c_int), parameter :: VT_NAME_MAX = 64
  integer(c_int), parameter :: VT_MESSAGE_SIZE = 256
  real(c_double), parameter :: VT_INERTIA_TOL = 1.0e-6_c_double
  real(c_double), parameter :: VT_INERTIA_ABS_TOL = 1.0e-15_c_double
  real(c_double), parameter :: VT_INERTIA_MAX = 1.0e307_c_double
  integer(c_int), parameter :: VT_COUNT_MAX = 16777216
  integer(c_int), parameter :: VT_URDF_MAX_BYTES = 256 * 1024 * 1024
  ! vt_joint_type
  integer(c_int), parameter :: VT_JOINT_BASE = 0, VT_JOINT_REVOLUTE = 1, VT_JOINT_UNIVERSAL = 2, &
      VT_JOINT_SPHERICAL = 3, VT_JOINT_TRANSLATIONAL = 4, VT_JOINT_CYLINDRICAL = 5, &
      VT_JOINT_FREE = 6, VT_JOINT_TYPE_COUNT = 7
  ! warning flags in vt_data%warning
  integer(c_int), parameter :: VT_WARN_ILL_CONDITIONED = 1, VT_WARN_REDUNDANT = 2, VT_WARN_BAND = 4
  ! vt_route: the route by which the last solve found qdd and lambda (vt_data%route)
  integer(c_int), parameter :: VT_ROUTE_NONE = 0, VT_ROUTE_JOINT_DRIVEN = 1, VT_ROUTE_FREE_RATES = 2, &
      VT_ROUTE_SQUARE = 3, VT_ROUTE_SCHUR = 4, VT_ROUTE_ARTICULATED = 5, VT_ROUTE_AUGMENTED = 6, &
      VT_ROUTE_REDUNDANT = 7, VT_ROUTE_MOTION = 8, VT_ROUTE_MAXIMAL = 9, VT_ROUTE_COUNT = 10
  ! fallback flags in vt_data%fallback: faster routes the last instant left, and why
  integer(c_int), parameter :: VT_FALLBACK_SCHUR_PIVOT = 1, VT_FALLBACK_ARTICULATED_PIVOT = 2, &
      VT_FALLBACK_ARTICULATED_CONDITION = 4, VT_FALLBACK_SQUARE_CONDITION = 8, &
      VT_FALLBACK_COMPOSITE_ROUNDOFF = 16, VT_FALLBACK_SCHUR_CONDITION = 32, &
      VT_FALLBACK_MAXIMAL_CONDITION = 64
  ! redundant rows: directions below this fraction of the largest singular value are dropped
  real(c_double), parameter :: VT_REDUNDANT_TOL = 5.0e-4_c_double
  real(c_double), parameter :: VT_CHECK_WINDOW = 5.0_c_double
  ! vt_function_type, renamed VT_FUNC_*: VT_FUNCTION_SINE would be vt_function_sine()
  integer(c_int), parameter :: VT_FUNC_CONSTANT = 0, VT_FUNC_POLYNOMIAL = 1, VT_FUNC_SINE = 2, &
      VT_FUNC_CALLBACK = 3, VT_FUNC_SPLINE = 4
  integer(c_int), parameter :: VT_POLY_MAX = 8, VT_SPLINE_EVAL_MAX = 64
  ! vt_drive_type
  integer(c_int), parameter :: VT_DRIVE_JOINT = 0, VT_DRIVE_POINT = 1, VT_DRIVE_ORIENTATION = 2, &
      VT_DRIVE_RELATIVE_ORIENTATION = 3, VT_DRIVE_TYPE_COUNT = 4
  ! vt_formulation
  integer(c_int), parameter :: VT_FORMULATION_INDEX1 = 0, VT_FORMULATION_BAUMGARTE = 1, &
      VT_FORMULATION_PROJECTION = 2, VT_FORMULATION_GGL = 3, VT_FORMULATION_ODE = 4, &
      VT_FORMULATION_COUNT = 5
  integer(c_int), parameter :: VT_DATA_ALIGN = 64

  ! ---- the structs: same names, fields and order as include/vtdyn/types.h, where each
  ! field's meaning, unit and shape are stated. Enumerations are integer(c_int), pointers
  ! type(c_ptr), callbacks type(c_funptr) (make them with c_funloc of a bind(C) procedure).

  type, bind(C) :: vt_model_def
    real(c_double)         :: gravity(3)
    real(c_double)         :: rcond_min
    real(c_double)         :: rcond_warn
    integer(c_int)         :: allow_redundant
    integer(c_int)         :: layout
    real(c_double)         :: inertia_tol
  end type vt_model_def

  ! include/vtdyn.h (VT_HAVE_URDF): the options of vt_urdf_builder; mirrored in every build
  type, bind(C) :: vt_urdf_options
    type(vt_model_def)     :: model
    integer(c_int)         :: floating
    integer(c_int)         :: mimic
    integer(c_int)         :: dynamics
  end type vt_urdf_options

  type, bind(C) :: vt_function
    integer(c_int)         :: type
    integer(c_int)         :: ncoef
    real(c_double)         :: c(VT_POLY_MAX)
    type(c_funptr)         :: callback
    type(c_ptr)            :: user
    integer(c_int)         :: nsample
    type(c_ptr)            :: sample_t
    type(c_ptr)            :: sample_y
    type(c_ptr)            :: sample_d2
  end type vt_function

  type, bind(C) :: vt_drive_def
    integer(c_int)         :: type
    integer(c_int)         :: body
    integer(c_int)         :: index
    real(c_double)         :: point(3)
    type(vt_function)      :: f
    real(c_double)         :: axis(3)
    real(c_double)         :: orientation(4)
    type(c_funptr)         :: orientation_callback
    type(c_ptr)            :: user
    type(c_ptr)            :: name
    type(c_ptr)            :: frame
    integer(c_int)         :: reference
    type(c_ptr)            :: sequence
    type(vt_function)      :: f2
    type(vt_function)      :: f3
  end type vt_drive_def

  type, bind(C) :: vt_cut_joint_def
    integer(c_int)         :: joint
    integer(c_int)         :: body_a
    integer(c_int)         :: body_b
    real(c_double)         :: point_a(3)
    real(c_double)         :: point_b(3)
    real(c_double)         :: axis1(3)
    real(c_double)         :: axis2(3)
    real(c_double)         :: orientation(4)
    type(c_ptr)            :: name
    type(c_ptr)            :: frame_a
    type(c_ptr)            :: frame_b
    integer(c_int)         :: planar
  end type vt_cut_joint_def

  type, bind(C) :: vt_coupling_def
    integer(c_int)         :: body_a
    integer(c_int)         :: index_a
    integer(c_int)         :: body_b
    integer(c_int)         :: index_b
    real(c_double)         :: ratio
    real(c_double)         :: offset
    type(c_ptr)            :: name
  end type vt_coupling_def

  type, bind(C) :: vt_body_def
    integer(c_int)         :: parent
    integer(c_int)         :: joint
    real(c_double)         :: mass
    real(c_double)         :: inertia(9)
    real(c_double)         :: joint_parent(3)
    real(c_double)         :: joint_child(3)
    real(c_double)         :: axis1(3)
    real(c_double)         :: axis2(3)
    real(c_double)         :: orientation(4)
    type(c_ptr)            :: name
    type(c_ptr)            :: joint_name
    real(c_double)         :: limit_lower(2)
    real(c_double)         :: limit_upper(2)
    real(c_double)         :: limit_velocity(2)
    real(c_double)         :: limit_effort(2)
    real(c_double)         :: armature(2)
    real(c_double)         :: damping(2)
    real(c_double)         :: friction(2)
    real(c_double)         :: friction_velocity(2)
    real(c_double)         :: gear_ratio(2)
    real(c_double)         :: joint_frame(4)
  end type vt_body_def

  type, bind(C) :: vt_frame_def
    type(c_ptr)            :: name
    integer(c_int)         :: body
    real(c_double)         :: point(3)
    real(c_double)         :: orientation(4)
    type(c_ptr)            :: reference
  end type vt_frame_def

  type, bind(C) :: vt_payload_def
    integer(c_int)         :: body
    type(c_ptr)            :: frame
    real(c_double)         :: mass
    real(c_double)         :: point(3)
    real(c_double)         :: inertia(9)
  end type vt_payload_def

  type, bind(C) :: vt_contact_def
    type(c_ptr)            :: name
    integer(c_int)         :: body
    real(c_double)         :: point(3)  ! m: the body's axes from its centre of mass, or with frame its axes from its origin
    type(c_ptr)            :: frame
    real(c_double)         :: normal(3)
    integer(c_int)         :: kind
    real(c_double)         :: mu
    integer(c_int)         :: faces
    real(c_double)         :: weight
    integer(c_int)         :: other
  end type vt_contact_def

  type, bind(C) :: vt_model
    integer(c_int)         :: nbody
    integer(c_int)         :: nq
    integer(c_int)         :: nv
    integer(c_int)         :: nx
    real(c_double)         :: gravity(3)
    type(c_ptr)            :: body_parent
    type(c_ptr)            :: body_joint
    type(c_ptr)            :: body_qadr
    type(c_ptr)            :: body_nq
    type(c_ptr)            :: body_vadr
    type(c_ptr)            :: body_nv
    type(c_ptr)            :: body_mass
    type(c_ptr)            :: body_inertia
    type(c_ptr)            :: body_jpar
    type(c_ptr)            :: body_jchild
    type(c_ptr)            :: body_axis
    type(c_ptr)            :: body_quat0
    type(c_ptr)            :: body_pathnum
    integer(c_int)         :: maxpath
    type(c_ptr)            :: dof_body
    type(c_ptr)            :: dof_parent
    type(c_ptr)            :: q0
    type(c_ptr)            :: dof_limit
    type(c_ptr)            :: dof_effects
    type(c_ptr)            :: body_name
    type(c_ptr)            :: joint_name
    type(c_ptr)            :: drive_name
    type(c_ptr)            :: cut_name
    type(c_ptr)            :: coupling_name
    integer(c_int)         :: nframe
    type(c_ptr)            :: frame_name
    type(c_ptr)            :: frame_body
    type(c_ptr)            :: frame_point
    type(c_ptr)            :: frame_quat
    real(c_double)         :: rcond_min
    real(c_double)         :: rcond_warn
    integer(c_int)         :: allow_redundant
    integer(c_int)         :: layout
    integer(c_int)         :: ndrive
    integer(c_int)         :: ncut
    integer(c_int)         :: nc
    type(c_ptr)            :: drive
    type(c_ptr)            :: drive_row
    type(c_ptr)            :: cut
    type(c_ptr)            :: cut_row
    integer(c_int)         :: ncoupling
    type(c_ptr)            :: coupling
    type(c_ptr)            :: coupling_row
    type(c_ptr)            :: con_body
    type(c_ptr)            :: con_owner
    type(c_ptr)            :: dof_drive
    type(c_ptr)            :: jnt_frame
    type(c_ptr)            :: jnt_frame_axis
    ! internal (types.h): read by the C library only, mirrored for the layout
    type(c_ptr)            :: con_kind
    type(c_ptr)            :: con_dof
    type(c_ptr)            :: con_vec
    type(c_ptr)            :: con_point
    integer(c_int)         :: joint_driven
    integer(c_int)         :: joint_rows_only
    integer(c_int)         :: joint_mix
    integer(c_int)         :: has_quaternions
    real(c_double)         :: bound_length
    real(c_double)         :: bound_mass
    real(c_double)         :: mass_spread
    integer(c_int)         :: has_effects
    real(c_double)         :: bound_effect(3)
    type(c_ptr)            :: jnt_frame_A
    integer(c_int)         :: any_limit
  end type vt_model

  type, bind(C) :: vt_data
    type(c_ptr)            :: model
    type(c_ptr)            :: block
    real(c_double)         :: time
    type(c_ptr)            :: q
    type(c_ptr)            :: qd
    type(c_ptr)            :: xfrc
    type(c_ptr)            :: qfrc
    type(c_ptr)            :: x
    type(c_ptr)            :: xd
    type(c_ptr)            :: A
    type(c_ptr)            :: omega
    type(c_ptr)            :: jaxis
    type(c_ptr)            :: jsij
    type(c_ptr)            :: jd
    type(c_ptr)            :: jpoint
    type(c_ptr)            :: twist
    type(c_ptr)            :: xrel
    real(c_double)         :: origin(3)
    type(c_ptr)            :: S
    type(c_ptr)            :: Sdqd
    type(c_ptr)            :: R
    type(c_ptr)            :: Mp
    type(c_ptr)            :: Mstar
    type(c_ptr)            :: F
    type(c_ptr)            :: h
    type(c_ptr)            :: Qgen
    type(c_ptr)            :: Phi
    type(c_ptr)            :: Phix
    type(c_ptr)            :: Phiq
    type(c_ptr)            :: Phit
    type(c_ptr)            :: gamma
    type(c_ptr)            :: qdd
    type(c_ptr)            :: lambda
    integer(c_int)         :: route
    integer(c_int)         :: fallback
    real(c_double)         :: rcond
    integer(c_int)         :: warning
    integer(c_int)         :: rank
    real(c_double)         :: residual
    type(c_ptr)            :: lambda_unique
    type(c_ptr)            :: lambda_null
    type(c_ptr)            :: xdd
    type(c_ptr)            :: alpha
    type(c_ptr)            :: qfrc_drive
    type(c_ptr)            :: effort_armature
    type(c_ptr)            :: effort_damping
    type(c_ptr)            :: effort_friction
    type(c_ptr)            :: drive_effort
    type(c_ptr)            :: drive_force
    type(c_ptr)            :: drive_moment
    type(c_ptr)            :: jnt_force
    type(c_ptr)            :: jnt_moment
    type(c_ptr)            :: jnt_force_body
    type(c_ptr)            :: jnt_moment_body
    type(c_ptr)            :: jnt_force_total
    type(c_ptr)            :: jnt_moment_total
    type(c_ptr)            :: jnt_force_total_body
    type(c_ptr)            :: jnt_moment_total_body
    type(c_ptr)            :: cut_force
    type(c_ptr)            :: cut_moment
    type(c_ptr)            :: cut_force_body
    type(c_ptr)            :: cut_moment_body
    type(c_ptr)            :: coupling_effort
    type(c_ptr)            :: jnt_unique
    type(c_ptr)            :: cut_unique
    type(c_ptr)            :: jnt_force_joint
    type(c_ptr)            :: jnt_moment_joint
    type(c_ptr)            :: jnt_bearing
    type(c_ptr)            :: limit_excess
    integer(c_int)         :: nlimit
    type(c_ptr)            :: arena
    integer(c_int)         :: ida_flag
    character(kind=c_char) :: message(VT_MESSAGE_SIZE)
  end type vt_data

  type, bind(C) :: vt_run_options
    real(c_double)         :: t0
    real(c_double)         :: t1
    integer(c_int)         :: nout
    real(c_double)         :: rtol
    real(c_double)         :: atol
    real(c_double)         :: max_step
    integer(c_long)        :: max_steps
    real(c_double)         :: newton_tol
    integer(c_int)         :: newton_maxit
    integer(c_int)         :: forward_check
    integer(c_int)         :: forward_independent
    integer(c_int)         :: history_steps
    integer(c_int)         :: forward_as_loads
    integer(c_int)         :: formulation
    real(c_double)         :: baumgarte_alpha
    real(c_double)         :: baumgarte_beta
    type(c_funptr)         :: progress
    type(c_ptr)            :: user
    type(c_ptr)            :: tout      ! the address of a TARGET real(c_double) array, or c_null_ptr
    integer(c_int)         :: ntout
    real(c_double)         :: redundant_band
    real(c_double)         :: check_window
    type(c_ptr)            :: contacts  ! a vt_contacts (vt_contacts_create), or c_null_ptr
    type(c_funptr)         :: contact_schedule
    type(c_ptr)            :: contact_user
    integer(c_int)         :: nload      ! wrenches at frames over a kinematic analysis (0..VT_RUN_LOADS_MAX)
    type(c_ptr)            :: load_frame ! the address of a TARGET integer(c_int) array of nload frame indices
    type(c_funptr)         :: loads      ! int loads(double t, double *w, void *user): 6 nload values at t
    type(c_ptr)            :: load_user
  end type vt_run_options

  type, bind(C) :: vt_trajectory
    type(c_ptr)            :: model
    integer(c_int)         :: nrow
    integer(c_int)         :: nfilled
    type(c_ptr)            :: t
    type(c_ptr)            :: q
    type(c_ptr)            :: qd
    type(c_ptr)            :: qdd
    type(c_ptr)            :: lambda
    type(c_ptr)            :: qfrc_drive
    type(c_ptr)            :: drive_effort
    type(c_ptr)            :: drive_force
    type(c_ptr)            :: drive_moment
    type(c_ptr)            :: jnt_force
    type(c_ptr)            :: jnt_moment
    type(c_ptr)            :: cut_force
    type(c_ptr)            :: cut_moment
    type(c_ptr)            :: phi_norm
    type(c_ptr)            :: phid_norm
    type(c_ptr)            :: rcond
    integer(c_int)         :: nwarn
    real(c_double)         :: t_warn
    type(c_ptr)            :: q_fwd
    type(c_ptr)            :: qd_fwd
    type(c_ptr)            :: jnt_force_fwd
    type(c_ptr)            :: jnt_moment_fwd
    type(c_ptr)            :: cut_force_fwd
    type(c_ptr)            :: cut_moment_fwd
    real(c_double)         :: fwd_err_q
    real(c_double)         :: fwd_err_qd
    real(c_double)         :: fwd_err_force
    real(c_double)         :: fwd_err_moment
    real(c_double)         :: fwd_interp_err
    integer(c_long)        :: steps
    integer(c_long)        :: res_evals
    integer(c_long)        :: steps_fwd
    integer(c_long)        :: res_evals_fwd
    integer(c_int)         :: nwindow
    type(c_ptr)            :: fwd_window_row
    type(c_ptr)            :: fwd_window_err_q
    type(c_ptr)            :: fwd_window_err_qd
    type(c_ptr)            :: fwd_window_err_force
    type(c_ptr)            :: fwd_window_err_moment
    integer(c_int)         :: ncontact
    type(c_ptr)            :: contact_force
    type(c_ptr)            :: contact_active
  end type vt_trajectory


  ! ---- the functions of include/vtdyn.h and include/vtdyn/euler.h -------------------------
  interface
    ! text for a status code (a C string: vt_string() converts it)
    function vt_status_string(status) bind(C, name='vt_status_string')
      import :: c_int, c_ptr
      integer(c_int), value :: status
      type(c_ptr) :: vt_status_string
    end function
    function vt_version() bind(C, name='vt_version')
      import :: c_ptr
      type(c_ptr) :: vt_version
    end function

    ! model building
    function vt_default_model_def() bind(C, name='vt_default_model_def')
      import :: vt_model_def
      type(vt_model_def) :: vt_default_model_def
    end function
    function vt_default_body_def() bind(C, name='vt_default_body_def')
      import :: vt_body_def
      type(vt_body_def) :: vt_default_body_def
    end function
    function vt_builder_create(builder, def) bind(C, name='vt_builder_create')
      import :: c_int, c_ptr, vt_model_def
      type(c_ptr), intent(out) :: builder
      type(vt_model_def), intent(in), optional :: def
      integer(c_int) :: vt_builder_create
    end function
    function vt_builder_add_body(builder, def) bind(C, name='vt_builder_add_body')
      import :: c_int, c_ptr, vt_body_def
      type(c_ptr), value :: builder
      type(vt_body_def), intent(in) :: def
      integer(c_int) :: vt_builder_add_body
    end function
    function vt_builder_message(builder) bind(C, name='vt_builder_message')
      import :: c_ptr
      type(c_ptr), value :: builder
      type(c_ptr) :: vt_builder_message
    end function
    function vt_builder_build(model, builder) bind(C, name='vt_builder_build')
      import :: c_int, c_ptr
      type(c_ptr), intent(out) :: model
      type(c_ptr), value :: builder
      integer(c_int) :: vt_builder_build
    end function
    subroutine vt_builder_free(builder) bind(C, name='vt_builder_free')
      import :: c_ptr
      type(c_ptr), value :: builder
    end subroutine
    subroutine vt_model_free(model) bind(C, name='vt_model_free')
      import :: c_ptr
      type(c_ptr), value :: model
    end subroutine
    function vt_model_without_drives(out, model) bind(C, name='vt_model_without_drives')
      import :: c_int, c_ptr
      type(c_ptr), intent(out) :: out
      type(c_ptr), value :: model
      integer(c_int) :: vt_model_without_drives
    end function
    function vt_data_create(data, model) bind(C, name='vt_data_create')
      import :: c_int, c_ptr
      type(c_ptr), intent(out) :: data
      type(c_ptr), value :: model
      integer(c_int) :: vt_data_create
    end function
    function vt_data_reset(model, data) bind(C, name='vt_data_reset')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_data_reset
    end function
    subroutine vt_data_free(data) bind(C, name='vt_data_free')
      import :: c_ptr
      type(c_ptr), value :: data
    end subroutine
    function vt_data_size(model) bind(C, name='vt_data_size')
      import :: c_size_t, c_ptr
      type(c_ptr), value :: model
      integer(c_size_t) :: vt_data_size
    end function
    function vt_data_init(data, model, buffer, size) bind(C, name='vt_data_init')
      import :: c_int, c_ptr, c_size_t
      type(c_ptr), intent(out) :: data
      type(c_ptr), value :: model, buffer
      integer(c_size_t), value :: size
      integer(c_int) :: vt_data_init
    end function
    function vt_add_point_load(model, data, body, point, f, n) bind(C, name='vt_add_point_load')
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model, data
      integer(c_int), value :: body
      real(c_double), intent(in) :: point(3)
      real(c_double), intent(in), optional :: f(3), n(3)
      integer(c_int) :: vt_add_point_load
    end function
    function vt_integrate_q(q_out, model, q, v, h) bind(C, name='vt_integrate_q')
      import :: c_int, c_ptr, c_double
      real(c_double), intent(inout) :: q_out(*)
      type(c_ptr), value :: model
      real(c_double), intent(in) :: q(*), v(*)
      real(c_double), value :: h
      integer(c_int) :: vt_integrate_q
    end function

    ! time functions
    function vt_function_constant(c) bind(C, name='vt_function_constant')
      import :: c_double, vt_function
      real(c_double), value :: c
      type(vt_function) :: vt_function_constant
    end function
    function vt_function_polynomial(ncoef, c) bind(C, name='vt_function_polynomial')
      import :: c_int, c_double, vt_function
      integer(c_int), value :: ncoef
      real(c_double), intent(in) :: c(*)
      type(vt_function) :: vt_function_polynomial
    end function
    function vt_function_sine(a, b, omega, phase) bind(C, name='vt_function_sine')
      import :: c_double, vt_function
      real(c_double), value :: a, b, omega, phase
      type(vt_function) :: vt_function_sine
    end function
    function vt_function_user(callback, user) bind(C, name='vt_function_user')
      import :: c_funptr, c_ptr, vt_function
      type(c_funptr), value :: callback
      type(c_ptr), value :: user
      type(vt_function) :: vt_function_user
    end function
    ! t and y are kept by address until the function is added to a drive (or evaluated):
    ! pass arrays with the TARGET attribute that stay alive until then
    function vt_function_spline(n, t, y) bind(C, name='vt_function_spline')
      import :: c_int, c_double, vt_function
      integer(c_int), value :: n
      real(c_double), intent(in) :: t(*), y(*)
      type(vt_function) :: vt_function_spline
    end function
    function vt_function_eval(out, f, t) bind(C, name='vt_function_eval')
      import :: c_int, c_double, vt_function
      real(c_double), intent(out) :: out(3)
      type(vt_function), intent(in) :: f
      real(c_double), value :: t
      integer(c_int) :: vt_function_eval
    end function

    ! drives and cut joints
    function vt_default_drive_def() bind(C, name='vt_default_drive_def')
      import :: vt_drive_def
      type(vt_drive_def) :: vt_default_drive_def
    end function
    function vt_default_cut_joint_def() bind(C, name='vt_default_cut_joint_def')
      import :: vt_cut_joint_def
      type(vt_cut_joint_def) :: vt_default_cut_joint_def
    end function
    function vt_builder_add_drive(builder, def) bind(C, name='vt_builder_add_drive')
      import :: c_int, c_ptr, vt_drive_def
      type(c_ptr), value :: builder
      type(vt_drive_def), intent(in) :: def
      integer(c_int) :: vt_builder_add_drive
    end function
    function vt_builder_add_cut_joint(builder, def) bind(C, name='vt_builder_add_cut_joint')
      import :: c_int, c_ptr, vt_cut_joint_def
      type(c_ptr), value :: builder
      type(vt_cut_joint_def), intent(in) :: def
      integer(c_int) :: vt_builder_add_cut_joint
    end function

    function vt_default_coupling_def() bind(C, name='vt_default_coupling_def')
      import :: vt_coupling_def
      type(vt_coupling_def) :: vt_default_coupling_def
    end function
    function vt_builder_add_coupling(builder, def) bind(C, name='vt_builder_add_coupling')
      import :: c_int, c_ptr, vt_coupling_def
      type(c_ptr), value :: builder
      type(vt_coupling_def), intent(in) :: def
      integer(c_int) :: vt_builder_add_coupling
    end function
    function vt_find_coupling(model, name) bind(C, name='vt_find_coupling')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: model
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_coupling
    end function
    ! URDF robots: only in a library built with libxml2 (VT_HAVE_URDF). path and xml are C
    ! strings (end them with c_null_char); message, if given, receives VT_MESSAGE_SIZE C characters
    function vt_default_urdf_options() bind(C, name='vt_default_urdf_options')
      import :: vt_urdf_options
      type(vt_urdf_options) :: vt_default_urdf_options
    end function
    function vt_urdf_builder(builder, path, options, message) bind(C, name='vt_urdf_builder')
      import :: c_int, c_ptr, c_char, vt_urdf_options
      type(c_ptr), intent(out) :: builder
      character(kind=c_char), intent(in) :: path(*)
      type(vt_urdf_options), intent(in), optional :: options
      character(kind=c_char), intent(out), optional :: message(*)
      integer(c_int) :: vt_urdf_builder
    end function
    function vt_urdf_builder_string(builder, xml, options, message) bind(C, name='vt_urdf_builder_string')
      import :: c_int, c_ptr, c_char, vt_urdf_options
      type(c_ptr), intent(out) :: builder
      character(kind=c_char), intent(in) :: xml(*)
      type(vt_urdf_options), intent(in), optional :: options
      character(kind=c_char), intent(out), optional :: message(*)
      integer(c_int) :: vt_urdf_builder_string
    end function

    ! frames and names: a name is a C string (a character(kind=c_char) array ending in c_null_char)
    function vt_default_frame_def() bind(C, name='vt_default_frame_def')
      import :: vt_frame_def
      type(vt_frame_def) :: vt_default_frame_def
    end function
    function vt_builder_add_frame(builder, def) bind(C, name='vt_builder_add_frame')
      import :: c_int, c_ptr, vt_frame_def
      type(c_ptr), value :: builder
      type(vt_frame_def), intent(in) :: def
      integer(c_int) :: vt_builder_add_frame
    end function
    function vt_builder_find_body(builder, name) bind(C, name='vt_builder_find_body')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: builder
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_builder_find_body
    end function
    function vt_builder_find_frame(builder, name) bind(C, name='vt_builder_find_frame')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: builder
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_builder_find_frame
    end function

    ! payloads and mass properties
    function vt_default_payload_def() bind(C, name='vt_default_payload_def')
      import :: vt_payload_def
      type(vt_payload_def) :: vt_default_payload_def
    end function
    function vt_builder_add_payload(builder, def) bind(C, name='vt_builder_add_payload')
      import :: c_int, c_ptr, vt_payload_def
      type(c_ptr), value :: builder
      type(vt_payload_def), intent(in) :: def
      integer(c_int) :: vt_builder_add_payload
    end function
    function vt_builder_set_mass(builder, def) bind(C, name='vt_builder_set_mass')
      import :: c_int, c_ptr, vt_payload_def
      type(c_ptr), value :: builder
      type(vt_payload_def), intent(in) :: def
      integer(c_int) :: vt_builder_set_mass
    end function
    ! contacts (a C object: hold it as type(c_ptr))
    function vt_default_contact_def() bind(C, name='vt_default_contact_def')
      import :: vt_contact_def
      type(vt_contact_def) :: vt_default_contact_def
    end function
    function vt_contacts_create(contacts, model, defs, n, effort_weight, message) bind(C, name='vt_contacts_create')
      import :: c_int, c_ptr, c_double, c_char, vt_contact_def
      type(c_ptr), intent(out) :: contacts
      type(c_ptr), value :: model
      type(vt_contact_def), intent(in) :: defs(*)
      integer(c_int), value :: n
      real(c_double), intent(in), optional :: effort_weight(*)
      character(kind=c_char), intent(out), optional :: message(*)
      integer(c_int) :: vt_contacts_create
    end function
    subroutine vt_contacts_free(contacts) bind(C, name='vt_contacts_free')
      import :: c_ptr
      type(c_ptr), value :: contacts
    end subroutine
    function vt_contacts_count(contacts) bind(C, name='vt_contacts_count')
      import :: c_int, c_ptr
      type(c_ptr), value :: contacts
      integer(c_int) :: vt_contacts_count
    end function
    function vt_find_contact(contacts, name) bind(C, name='vt_find_contact')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: contacts
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_contact
    end function
    function vt_inverse_dynamics_contacts(model, data, contacts, active, force) &
        bind(C, name='vt_inverse_dynamics_contacts')
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model, data, contacts
      integer(c_int), intent(in), optional :: active(*)
      real(c_double), intent(out), optional :: force(*)
      integer(c_int) :: vt_inverse_dynamics_contacts
    end function
    function vt_contacts_unique(model, data, contacts, active, effort_unique, force_unique) &
        bind(C, name='vt_contacts_unique')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data, contacts
      integer(c_int), intent(in), optional :: active(*)
      integer(c_int), intent(out), optional :: effort_unique(*), force_unique(*)
      integer(c_int) :: vt_contacts_unique
    end function
    function vt_find_body(model, name) bind(C, name='vt_find_body')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: model
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_body
    end function
    function vt_find_joint(model, name) bind(C, name='vt_find_joint')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: model
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_joint
    end function
    function vt_find_drive(model, name) bind(C, name='vt_find_drive')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: model
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_drive
    end function
    function vt_find_cut_joint(model, name) bind(C, name='vt_find_cut_joint')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: model
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_cut_joint
    end function
    function vt_find_frame(model, name) bind(C, name='vt_find_frame')
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: model
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int) :: vt_find_frame
    end function
    function vt_add_frame_load(model, data, frame, f, n) bind(C, name='vt_add_frame_load')
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model, data
      integer(c_int), value :: frame
      real(c_double), intent(in), optional :: f(3), n(3)
      integer(c_int) :: vt_add_frame_load
    end function
    function vt_frame_pose(model, data, frame, position, rotation) bind(C, name='vt_frame_pose')
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model, data
      integer(c_int), value :: frame
      real(c_double), intent(out), optional :: position(3), rotation(9)
      integer(c_int) :: vt_frame_pose
    end function

    ! stages: each reads the model and fills its part of the data
    function vt_kinematics(model, data) bind(C, name='vt_kinematics')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_kinematics
    end function
    function vt_inverse_transform(model, data) bind(C, name='vt_inverse_transform')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_inverse_transform
    end function
    function vt_mass_matrix(model, data) bind(C, name='vt_mass_matrix')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_mass_matrix
    end function
    function vt_forces(model, data) bind(C, name='vt_forces')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_forces
    end function
    function vt_constraints(model, data) bind(C, name='vt_constraints')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_constraints
    end function
    function vt_solve(model, data) bind(C, name='vt_solve')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_solve
    end function
    function vt_reactions(model, data) bind(C, name='vt_reactions')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_reactions
    end function
    function vt_inverse_dynamics(model, data) bind(C, name='vt_inverse_dynamics')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_inverse_dynamics
    end function
    function vt_inverse_dynamics_recursive(model, data) bind(C, name='vt_inverse_dynamics_recursive')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_inverse_dynamics_recursive
    end function
    function vt_inverse_dynamics_motion(model, data) bind(C, name='vt_inverse_dynamics_motion')
      import :: c_int, c_ptr
      type(c_ptr), value :: model, data
      integer(c_int) :: vt_inverse_dynamics_motion
    end function
    ! the first drive the given motion evaluates at the data's time, or -1 (vt_batch_io%time then optional)
    function vt_motion_time_drive(model) bind(C, name='vt_motion_time_drive')
      import :: c_int, c_ptr
      type(c_ptr), value :: model
      integer(c_int) :: vt_motion_time_drive
    end function
    function vt_drive_cartesian_force(F, model, data, drive) bind(C, name='vt_drive_cartesian_force')
      import :: c_int, c_ptr, c_double
      real(c_double), intent(out) :: F(*)
      type(c_ptr), value :: model, data
      integer(c_int), value :: drive
      integer(c_int) :: vt_drive_cartesian_force
    end function

    ! analyses over time
    function vt_default_run_options() bind(C, name='vt_default_run_options')
      import :: vt_run_options
      type(vt_run_options) :: vt_default_run_options
    end function
    function vt_trajectory_create(trajectory, model, nrow) bind(C, name='vt_trajectory_create')
      import :: c_int, c_ptr
      type(c_ptr), intent(out) :: trajectory
      type(c_ptr), value :: model
      integer(c_int), value :: nrow
      integer(c_int) :: vt_trajectory_create
    end function
    function vt_trajectory_create_contacts(trajectory, model, contacts, nrow) &
        bind(C, name='vt_trajectory_create_contacts')
      import :: c_int, c_ptr
      type(c_ptr), intent(out) :: trajectory
      type(c_ptr), value :: model
      type(c_ptr), value :: contacts
      integer(c_int), value :: nrow
      integer(c_int) :: vt_trajectory_create_contacts
    end function
    subroutine vt_trajectory_free(trajectory) bind(C, name='vt_trajectory_free')
      import :: c_ptr
      type(c_ptr), value :: trajectory
    end subroutine
    function vt_kinematic_solve(model, data, tol, maxit) bind(C, name='vt_kinematic_solve')
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model, data
      real(c_double), value :: tol
      integer(c_int), value :: maxit
      integer(c_int) :: vt_kinematic_solve
    end function
    function vt_kinematic_analysis(model, data, opt, trajectory) bind(C, name='vt_kinematic_analysis')
      import :: c_int, c_ptr, vt_run_options
      type(c_ptr), value :: model, data
      type(vt_run_options), intent(in) :: opt
      type(c_ptr), value :: trajectory
      integer(c_int) :: vt_kinematic_analysis
    end function
    function vt_dynamic_analysis(model, data, opt, trajectory) bind(C, name='vt_dynamic_analysis')
      import :: c_int, c_ptr, vt_run_options
      type(c_ptr), value :: model, data
      type(vt_run_options), intent(in) :: opt
      type(c_ptr), value :: trajectory
      integer(c_int) :: vt_dynamic_analysis
    end function

    ! force transforms
    function vt_cartesian_force(F, p, s, f_, n) bind(C, name='vt_cartesian_force')
      import :: c_int, c_double
      real(c_double), intent(inout) :: F(7)
      real(c_double), intent(in) :: p(4), s(3), f_(3), n(3)
      integer(c_int) :: vt_cartesian_force
    end function
    function vt_generalized_force(Q, model, data, F) bind(C, name='vt_generalized_force')
      import :: c_int, c_ptr, c_double
      real(c_double), intent(out) :: Q(*)
      type(c_ptr), value :: model, data
      real(c_double), intent(in) :: F(*)
      integer(c_int) :: vt_generalized_force
    end function
    function vt_equivalent_force(Feq, model, data, Q) bind(C, name='vt_equivalent_force')
      import :: c_int, c_ptr, c_double
      real(c_double), intent(out) :: Feq(*)
      type(c_ptr), value :: model, data
      real(c_double), intent(in) :: Q(*)
      integer(c_int) :: vt_equivalent_force
    end function

    ! Euler parameters (include/vtdyn/euler.h)
    subroutine vt_euler_E(E, p) bind(C, name='vt_euler_E')
      import :: c_double
      real(c_double), intent(out) :: E(12)
      real(c_double), intent(in) :: p(4)
    end subroutine
    subroutine vt_euler_G(G, p) bind(C, name='vt_euler_G')
      import :: c_double
      real(c_double), intent(out) :: G(12)
      real(c_double), intent(in) :: p(4)
    end subroutine
    subroutine vt_euler_A(A, p) bind(C, name='vt_euler_A')
      import :: c_double
      real(c_double), intent(out) :: A(9)
      real(c_double), intent(in) :: p(4)
    end subroutine
    subroutine vt_quat_mul(r, a, b) bind(C, name='vt_quat_mul')
      import :: c_double
      real(c_double), intent(out) :: r(4)
      real(c_double), intent(in) :: a(4), b(4)
    end subroutine
    subroutine vt_quat_axis_angle(p, u, angle) bind(C, name='vt_quat_axis_angle')
      import :: c_double
      real(c_double), intent(out) :: p(4)
      real(c_double), intent(in) :: u(3)
      real(c_double), value :: angle
    end subroutine
  end interface

  ! views of the C data's arrays (see the top of this file)
  interface vt_array
    module procedure vt_array_real1, vt_array_real2, vt_array_int1
  end interface vt_array

contains

  ! a C string (NUL-terminated) as a Fortran string; '' for a NULL pointer
  function vt_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: k, n
    interface
      function c_strlen(str) bind(C, name='strlen')
        import :: c_ptr, c_size_t
        type(c_ptr), value :: str
        integer(c_size_t) :: c_strlen
      end function
    end interface
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: s)
    do k = 1, n
      s(k:k) = chars(k)
    end do
  end function vt_string

  ! the data's message (detail of its last failed call)
  function vt_message(d) result(s)
    type(vt_data), intent(in) :: d
    character(len=:), allocatable :: s
    integer :: k, n
    n = 0
    do k = 1, size(d%message)
      if (d%message(k) == c_null_char) exit
      n = k
    end do
    allocate(character(len=n) :: s)
    do k = 1, n
      s(k:k) = d%message(k)
    end do
  end function vt_message

  ! a(1:n) viewing the n doubles at p
  subroutine vt_array_real1(a, p, n)
    real(c_double), pointer, intent(out) :: a(:)
    type(c_ptr), intent(in) :: p
    integer(c_int), intent(in) :: n
    call c_f_pointer(p, a, [n])
  end subroutine vt_array_real1

  ! a(1:rows, 1:cols) viewing a column-major matrix at p (leading dimension rows)
  subroutine vt_array_real2(a, p, rows, cols)
    real(c_double), pointer, intent(out) :: a(:, :)
    type(c_ptr), intent(in) :: p
    integer(c_int), intent(in) :: rows, cols
    call c_f_pointer(p, a, [rows, cols])
  end subroutine vt_array_real2

  ! a(1:n) viewing the n ints at p
  subroutine vt_array_int1(a, p, n)
    integer(c_int), pointer, intent(out) :: a(:)
    type(c_ptr), intent(in) :: p
    integer(c_int), intent(in) :: n
    call c_f_pointer(p, a, [n])
  end subroutine vt_array_int1

  ! a(1:rows, 0:nbody) viewing a per-body array (rows x (nbody+1)): column i is body i, 0 the ground
  subroutine vt_body_array(a, p, rows, nbody)
    real(c_double), pointer, intent(out) :: a(:, :)
    type(c_ptr), intent(in) :: p
    integer(c_int), intent(in) :: rows, nbody
    real(c_double), pointer :: flat(:, :)
    call c_f_pointer(p, flat, [rows, nbody + 1])
    a(1:, 0:) => flat
  end subroutine vt_body_array

end module vtdyn
