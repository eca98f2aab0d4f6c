# Typed stubs of the extension module vtdyn._vtdyn (python/vtdyn/*.c).
import os
from typing import Any, Callable, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_F64 = npt.NDArray[np.float64]
_OF64 = Optional[_F64]
VT_HAVE_SUNDIALS: int
VT_CONTACT_WEIGHT: float

class Error(RuntimeError):
    """A status of the library: .status its name ("VT_ERR_NONFINITE"), .code the int,
    .row the failing row of N states (None otherwise); str() is the library's message."""
    status: str
    code: int
    row: Optional[int]

class Result(Tuple[_OF64, _OF64, _OF64, _OF64, _OF64, _OF64, _OF64, _OF64, _OF64, _OF64]):
    """Model.inverse's arrays; N states give a leading N axis, one state none; a field that
    Model.inverse(outputs=...) left out is None."""
    @property
    def effort(self) -> _OF64:
        """every rate's generalized force (N x nv), N m or N; a floating root's six: world force
        then moment about the root link frame's origin, world axes"""
    @property
    def reaction(self) -> _OF64:
        """each body's joint reaction (N x nbody x 6): force (N) then moment (N m) about the joint
        point (the child link frame's origin), world axes; actuation not included"""
    @property
    def reaction_body(self) -> _OF64:
        """the same in the body's axes (the link's inertial axes)"""
    @property
    def total(self) -> _OF64:
        """each joint's total wrench, reaction plus actuation, world axes"""
    @property
    def total_body(self) -> _OF64:
        """the same in the body's axes"""
    @property
    def reaction_joint(self) -> _OF64:
        """each body's joint reaction in the joint's frame, the child link's URDF axes (N x nbody x 6)"""
    @property
    def bearing(self) -> _OF64:
        """each joint's bearing split (N x nbody x 4): the reaction force along the joint's URDF
        axis (signed) and its magnitude across it, N; the moment about it (signed) and across it, N m"""
    @property
    def limit_excess(self) -> _OF64:
        """each rate's excess beyond its position, velocity and effort limits (N x nv x 3): the value
        less the limit it passes, 0 within or exactly at it"""
    @property
    def effort_parts(self) -> _OF64:
        """the parts of each rate's effort its joint's armature, damping and friction take
        (N x 3 x nv: armature q'', damping q', friction sign(q')); effort less their sum is the
        rigid-body part"""
    @property
    def contact_force(self) -> _OF64:
        """with contacts: the ground's force on the body at each contact (N x ncontact x 3), N, world
        axes, 0 at an inactive contact; without: N x 0 x 3"""

class ContactSet:
    """A Model's contacts with the ground, validated once (Model.contacts; no public constructor).
    len() is the number of contacts."""
    @property
    def names(self) -> Tuple[str, ...]:
        """each contact's name (its frame's where it has none; "" for a body's point)"""
    @property
    def model(self) -> "Model":
        """the Model the set was made for"""
    def __len__(self) -> int: ...
    def unique(
        self, q: npt.ArrayLike, v: npt.ArrayLike, a: npt.ArrayLike, active: Optional[Sequence[int]] = None
    ) -> Tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
        """at one state on these contacts, which results the motion and the contacts fix (True)
        and which the distribution rule decides (False): each rate's effort (nv), each contact's
        force component (ncontact x 3, world axes), each body's joint reaction component
        (nbody x 6)"""

class Trajectory(Tuple[Any, ...]):
    """An analysis over time (vt_trajectory): one row an output time, n rows in all."""
    @property
    def time(self) -> _F64:
        """s, the output times (n)"""
    @property
    def q(self) -> _F64:
        """the driven run's coordinates (n x nq)"""
    @property
    def qd(self) -> _F64:
        """its rates (n x nv)"""
    @property
    def qdd(self) -> _F64:
        """its accelerations (n x nv)"""
    @property
    def lambda_(self) -> _F64:
        """the constraint rows' multipliers (n x nc): drives, cut joints, couplings, base bodies"""
    @property
    def qfrc_drive(self) -> _F64:
        """the drives' generalized force Phi_q^T lambda a rate, N m or N (n x nv)"""
    @property
    def drive_effort(self) -> _F64:
        """each drive's effort, N m or N (n x ndrive)"""
    @property
    def drive_force(self) -> _F64:
        """the force each drive exerts on its body, N, world axes (n x ndrive x 3)"""
    @property
    def drive_moment(self) -> _F64:
        """its moment about the drive's point, N m, world axes (n x ndrive x 3)"""
    @property
    def reaction(self) -> _F64:
        """each body's joint reaction: force, then moment about the joint point, world axes (n x nbody x 6)"""
    @property
    def cut_reaction(self) -> _F64:
        """each cut joint's reaction on body_b: force, then moment about point_b, world axes (n x ncut x 6)"""
    @property
    def phi_norm(self) -> _F64:
        """max |Phi| of the driven run (n)"""
    @property
    def phid_norm(self) -> _F64:
        """max |Phi_q qd + Phi_t| of the driven run (n)"""
    @property
    def rcond(self) -> _F64:
        """the condition estimate of (5) at each row (n)"""
    @property
    def nwarn(self) -> int:
        """rows whose solve warned of ill-conditioning"""
    @property
    def t_warn(self) -> float:
        """s, the first such row's time (nan if none)"""
    @property
    def q_fwd(self) -> Optional[_F64]:
        """the forward check's coordinates (n x nq); None without the forward check"""
    @property
    def qd_fwd(self) -> Optional[_F64]:
        """its rates (n x nv)"""
    @property
    def reaction_fwd(self) -> Optional[_F64]:
        """its joint reactions, as reaction (n x nbody x 6)"""
    @property
    def cut_reaction_fwd(self) -> Optional[_F64]:
        """its cut joints' reactions (n x ncut x 6)"""
    @property
    def fwd_err_q(self) -> float:
        """max |q_fwd - q| over the rows"""
    @property
    def fwd_err_qd(self) -> float:
        """max |qd_fwd - qd|"""
    @property
    def fwd_err_force(self) -> float:
        """max difference of the reaction forces, forward less driven, N"""
    @property
    def fwd_err_moment(self) -> float:
        """the same for the reaction moments, N m"""
    @property
    def fwd_interp_err(self) -> float:
        """independent forward check of a dynamic analysis: the interpolated driven state's largest error"""
    @property
    def steps(self) -> int:
        """IDA steps of the driven run (0 for a kinematic analysis)"""
    @property
    def res_evals(self) -> int:
        """IDA residual evaluations of the driven run"""
    @property
    def steps_fwd(self) -> int:
        """IDA steps of the forward check"""
    @property
    def res_evals_fwd(self) -> int:
        """its residual evaluations"""
    @property
    def fwd_window_row(self) -> npt.NDArray[np.int64]:
        """the row each forward-check window restarts from (nwindow)"""
    @property
    def fwd_window_err_q(self) -> _F64:
        """each window's max |q_fwd - q| (nwindow)"""
    @property
    def fwd_window_err_qd(self) -> _F64:
        """each window's max |qd_fwd - qd| (nwindow)"""
    @property
    def fwd_window_err_force(self) -> _F64:
        """each window's max reaction force difference, N (nwindow)"""
    @property
    def fwd_window_err_moment(self) -> _F64:
        """each window's max reaction moment difference, N m (nwindow)"""
    @property
    def contact_force(self) -> _OF64:
        """the ground's force at each contact, N, world axes (n x ncontact x 3); None without contacts"""

class Model:
    """A model: a robot loaded by load_urdf, or built by Builder.build (no public constructor)."""
    @property
    def nq(self) -> int: ...
    @property
    def nv(self) -> int: ...
    @property
    def nbody(self) -> int: ...
    @property
    def body_names(self) -> Tuple[str, ...]: ...
    @property
    def body_joint_names(self) -> Tuple[str, ...]: ...
    @property
    def joint_names(self) -> Tuple[str, ...]: ...
    @property
    def frame_names(self) -> Tuple[str, ...]: ...
    @property
    def masses(self) -> _F64: ...
    @property
    def gravity(self) -> _F64: ...
    @property
    def q0(self) -> _F64: ...
    @property
    def limits(self) -> _F64: ...
    @property
    def body_index(self) -> npt.NDArray[np.int64]: ...
    @property
    def floating(self) -> bool: ...
    def inverse(
        self,
        q: npt.ArrayLike,
        v: npt.ArrayLike,
        a: npt.ArrayLike,
        threads: int = 0,
        contacts: Optional[ContactSet] = None,
        active: Optional[npt.ArrayLike] = None,
        outputs: Optional[Sequence[str]] = None,
        out: Optional[Result] = None,
        qfrc: Optional[npt.ArrayLike] = None,
        loads: Optional[npt.ArrayLike] = None,
        load_frames: Union[None, str, Sequence[str]] = None,
        t: Optional[npt.ArrayLike] = None,
    ) -> Result:
        """the given motion's efforts and joint reactions on one state (1-D) or N states (N x n);
        with contacts the ground's forces at them carry the free root; active: None (all) or 0/1
        per contact (ncontact, or N x ncontact); outputs: None (every field) or the names of the
        Result fields wanted, the others None and neither computed nor written; out: an earlier
        Result of the same shapes whose arrays are written again; qfrc: applied generalized forces
        (v's shape), which the efforts then need not give; loads (F x 6, or N x F x 6) with
        load_frames (F frame names): wrenches the environment applies at those frames, the force
        (N) then the moment about the frame's origin (N m), world axes (with contacts the ground's
        forces balance them too); t: the states' time (s; a number, or one a state), which a
        loop's or coupling's point and orientation drives read (needed there: without it they are
        refused; elsewhere it changes nothing)"""
    def frame_poses(
        self, q: npt.ArrayLike, frames: Union[None, str, Sequence[str]] = None
    ) -> Tuple[_F64, _F64]:
        """the frames' origins (m, world axes; N x F x 3) and axes (rotation R, frame to world,
        R @ v; N x F x 3 x 3) at one configuration (nq) or N (N x nq), for every frame (None) or
        the named ones"""
    def contacts(self, contacts: Sequence[Any], effort_weight: Optional[npt.ArrayLike] = None) -> ContactSet:
        """the robot's contacts with the ground (each a vtdyn.Contact), validated once;
        effort_weight: each rate's weight in the rule (nv; None: 1 each)"""
    def kinematic_analysis(
        self,
        t1: float,
        nout: int = 100,
        t0: float = 0.0,
        *,
        tout: Optional[npt.ArrayLike] = None,
        q: Optional[npt.ArrayLike] = None,
        qd: Optional[npt.ArrayLike] = None,
        rtol: float = 1e-8,
        atol: float = 1e-10,
        max_step: float = 0.0,
        max_steps: int = 100000,
        newton_tol: float = 1e-12,
        newton_maxit: int = 30,
        forward_check: bool = ...,
        forward_independent: bool = True,
        forward_as_loads: bool = False,
        formulation: str = "ggl",
        baumgarte_alpha: float = 10.0,
        baumgarte_beta: float = 10.0,
        history_steps: int = 100000,
        redundant_band: float = 5e-4,
        check_window: float = 5.0,
        contacts: Optional[ContactSet] = None,
        active: Optional[Callable[[float], Sequence[Any]]] = None,
        loads: Union[None, npt.ArrayLike, Callable[[float], npt.ArrayLike]] = None,
        load_frames: Union[None, str, Sequence[str]] = None,
    ) -> Trajectory:
        """a fully driven model's motion, efforts and reactions at each output time
        (vt_kinematic_analysis); forward_check defaults to True where SUNDIALS is built in;
        contacts: the robot on the ground (the forces in Trajectory.contact_force, the free
        root's efforts zero); active(t): one flag a contact, which are on the ground at t
        (None: all, all the time); loads (F x 6, or a function of t giving them) with
        load_frames (F frame names): wrenches the environment applies at those frames over the
        run, force (N) then moment about the frame's origin (N m), world axes, in every row and
        in the forward check"""
    def dynamic_analysis(
        self,
        t1: float,
        nout: int = 100,
        t0: float = 0.0,
        *,
        tout: Optional[npt.ArrayLike] = None,
        q: Optional[npt.ArrayLike] = None,
        qd: Optional[npt.ArrayLike] = None,
        rtol: float = 1e-8,
        atol: float = 1e-10,
        max_step: float = 0.0,
        max_steps: int = 100000,
        newton_tol: float = 1e-12,
        newton_maxit: int = 30,
        forward_check: bool = True,
        forward_independent: bool = True,
        forward_as_loads: bool = False,
        formulation: str = "ggl",
        baumgarte_alpha: float = 10.0,
        baumgarte_beta: float = 10.0,
        history_steps: int = 100000,
        redundant_band: float = 5e-4,
        check_window: float = 5.0,
        contacts: Optional[ContactSet] = None,
        active: Optional[Callable[[float], Sequence[Any]]] = None,
        loads: Union[None, npt.ArrayLike, Callable[[float], npt.ArrayLike]] = None,
        load_frames: Union[None, str, Sequence[str]] = None,
    ) -> Trajectory:
        """the motion the drives leave free, integrated by SUNDIALS IDA (vt_dynamic_analysis) from
        q, qd at t0 (None: the reference configuration, at rest); vtdyn.Error without SUNDIALS"""

_Vec = Optional[Sequence[float]]
_Pair = Optional[Union[float, Sequence[float]]]
_Fn = Union[float, Tuple[str, Any]]

class Builder:
    """A model built by hand (vt_builder): keyword arguments mirror vt_model_def, vt_body_def,
    vt_frame_def, vt_drive_def, vt_cut_joint_def, vt_payload_def and vt_coupling_def with the C
    defaults (None: the default). Joint kinds: 'base', 'revolute', 'universal', 'spherical',
    'translational' (or 'prismatic'), 'cylindrical', 'free'."""
    def __init__(
        self,
        *,
        gravity: _Vec = None,
        rcond_min: float = 1e-12,
        rcond_warn: float = 1e-6,
        allow_redundant: bool = False,
        layout: str = "full",
        inertia_tol: float = 1e-6,
    ) -> None: ...
    def add_body(
        self,
        *,
        parent: int = 0,
        joint: str = "revolute",
        mass: float = 1.0,
        inertia: Optional[npt.ArrayLike] = None,
        joint_parent: _Vec = None,
        joint_child: _Vec = None,
        axis1: _Vec = None,
        axis2: _Vec = None,
        orientation: _Vec = None,
        name: Optional[str] = None,
        joint_name: Optional[str] = None,
        limit_lower: _Pair = None,
        limit_upper: _Pair = None,
        limit_velocity: _Pair = None,
        limit_effort: _Pair = None,
        armature: _Pair = None,
        damping: _Pair = None,
        friction: _Pair = None,
        friction_velocity: _Pair = None,
        gear_ratio: _Pair = None,
        joint_frame: _Vec = None,
    ) -> int:
        """a body and its joint (vt_body_def); inertia: 3 principal moments or 3 x 3 about the
        centre of mass; the two-rate fields: a number (the first rate) or two; its id 1, 2, ..."""
    def add_frame(
        self, name: str, *, body: int = 1, point: _Vec = None, orientation: _Vec = None, reference: Optional[str] = None
    ) -> int:
        """a named frame on a body (vt_frame_def); its index"""
    def add_drive(
        self,
        *,
        body: int = 1,
        kind: str = "joint",
        index: int = 0,
        f: _Fn = 0.0,
        point: _Vec = None,
        axis: _Vec = None,
        orientation: _Vec = None,
        name: Optional[str] = None,
        frame: Optional[str] = None,
        reference: int = -1,
        sequence: Optional[str] = None,
        f2: _Fn = 0.0,
        f3: _Fn = 0.0,
    ) -> int:
        """a drive (vt_drive_def): kind 'joint', 'point', 'orientation' or 'relative_orientation';
        f, f2, f3 a number or a vtdyn.Function; its index"""
    def add_cut_joint(
        self,
        *,
        body_a: int = 0,
        body_b: int = 1,
        joint: str = "revolute",
        point_a: _Vec = None,
        point_b: _Vec = None,
        axis1: _Vec = None,
        axis2: _Vec = None,
        orientation: _Vec = None,
        name: Optional[str] = None,
        frame_a: Optional[str] = None,
        frame_b: Optional[str] = None,
        planar: bool = False,
    ) -> int:
        """a loop's cut joint (vt_cut_joint_def; planar: a planar loop's pin, two rows); its index"""
    def add_payload(
        self, *, body: int = 1, mass: float = 0.0, point: _Vec = None, inertia: Optional[npt.ArrayLike] = None,
        frame: Optional[str] = None
    ) -> int:
        """a rigid body fixed to a body (vt_payload_def); the body's id"""
    def add_coupling(
        self, *, body_a: int = 2, index_a: int = 0, body_b: int = 1, index_b: int = 0, ratio: float = 1.0,
        offset: float = 0.0, name: Optional[str] = None
    ) -> int:
        """q_a = ratio q_b + offset (vt_coupling_def); its index"""
    def find_body(self, name: str) -> int: ...
    def find_joint(self, name: str) -> int: ...
    def find_frame(self, name: str) -> int: ...
    def build(self) -> Model:
        """the model (vt_builder_build); the builder stays usable"""

def load_urdf(
    path: Union[str, bytes, os.PathLike[str]],
    floating: bool = False,
    mimic: bool = False,
    dynamics: bool = True,
    joint_params: Optional[Mapping[str, Sequence[float]]] = None,
    payloads: Optional[Sequence[Sequence[Any]]] = None,
    inertia_tol: Optional[float] = None,
) -> Model: ...
def version() -> str: ...
