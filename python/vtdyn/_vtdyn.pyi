# Typed stubs of the extension module vtdyn._vtdyn (python/vtdyn/_vtdyn.c).
import os
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_F64 = npt.NDArray[np.float64]
VT_HAVE_SUNDIALS: int

class Error(RuntimeError):
    """A status of the library: .status its name ("VT_ERR_NONFINITE"), .code the int,
    .row the failing row of N states (None otherwise); str() is the library's message."""
    status: str
    code: int
    row: Optional[int]

class Result(Tuple[_F64, _F64, _F64, _F64, _F64, _F64, _F64, _F64, _F64]):
    """Model.inverse's arrays; N states give a leading N axis, one state none."""
    @property
    def effort(self) -> _F64:
        """every rate's generalized force (N x nv), N m or N; a floating root's six: world force
        then moment about the root link frame's origin, world axes"""
    @property
    def reaction(self) -> _F64:
        """each body's joint reaction (N x nbody x 6): force (N) then moment (N m) about the joint
        point (the child link frame's origin), world axes; actuation not included"""
    @property
    def reaction_body(self) -> _F64:
        """the same in the body's axes (the link's inertial axes)"""
    @property
    def total(self) -> _F64:
        """each joint's total wrench, reaction plus actuation, world axes"""
    @property
    def total_body(self) -> _F64:
        """the same in the body's axes"""
    @property
    def reaction_joint(self) -> _F64:
        """each body's joint reaction in the joint's frame, the child link's URDF axes (N x nbody x 6)"""
    @property
    def bearing(self) -> _F64:
        """each joint's bearing split (N x nbody x 4): the reaction force along the joint's URDF
        axis (signed) and its magnitude across it, N; the moment about it (signed) and across it, N m"""
    @property
    def limit_excess(self) -> _F64:
        """each rate's excess beyond its position, velocity and effort limits (N x nv x 3): the value
        less the limit it passes, 0 within or exactly at it"""
    @property
    def effort_parts(self) -> _F64:
        """the parts of each rate's effort its joint's armature, damping and friction take
        (N x 3 x nv: armature q'', damping q', friction sign(q')); effort less their sum is the
        rigid-body part"""

class Model:
    """A robot loaded by load_urdf (no public constructor)."""
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
    def inverse(self, q: npt.ArrayLike, v: npt.ArrayLike, a: npt.ArrayLike, threads: int = 0) -> Result: ...

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
