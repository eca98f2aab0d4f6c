"""vtdyn: inverse dynamics of URDF robots and of models built by hand, NumPy arrays in and out
(docs/python.md).

    import numpy as np, vtdyn
    robot = vtdyn.load_urdf("ur5_robot.urdf")
    r = robot.inverse(q, v, a)          # one state (1-D) or N states (N x nq, N x nv)
    r.effort, r.reaction                # N x nv, N x nbody x 6 (world axes)

The work is the C library's vt_batch_inverse_dynamics_motion, on threads, with the GIL released.
"""
from typing import Any, NamedTuple, Optional, Sequence

from ._vtdyn import VT_CONTACT_WEIGHT, VT_HAVE_SUNDIALS, Builder, ContactSet, Error, Model, Result, Trajectory, load_urdf
from ._vtdyn import version as _c_version

__version__: str = _c_version()
"""The C library's version (the package is built from the same source)."""


class Contact(NamedTuple):
    """A point of the robot on the ground (vt_contact_def; docs/contact.md), for Model.contacts.

    frame: a frame of the model (a URDF link's name: the point is its origin), or None to give
    body (1..nbody) and point (m, the body's axes from its centre of mass). normal: the ground's
    normal, world axes, into the body ((0, 0, 0): opposite to gravity). kind: "unilateral" (pushes
    only, Coulomb friction mu on a pyramid of `faces` faces, 3..64) or "bilateral" (any force).
    weight: w_c of the rule's 1/2 w_c |f_c|^2, N^-2. name: unique among the contacts (None: none).
    other: what the point touches, 0 the ground, or a moving body (1..nbody, not `body`): the force
    acts on it too, opposite, and the normal is in its axes, turning with it.
    """

    frame: Optional[str] = None
    body: int = 1
    point: Sequence[float] = (0.0, 0.0, 0.0)
    normal: Sequence[float] = (0.0, 0.0, 0.0)
    kind: str = "unilateral"
    mu: float = 1.0
    faces: int = 4
    weight: float = VT_CONTACT_WEIGHT
    name: Optional[str] = None
    other: int = 0


class Function(NamedTuple):
    """A drive's function of time (vt_function), for Builder.add_drive's f, f2 and f3 (a plain
    number is a constant). Make it with the constructors, which mirror vt_function_*:

    Function.constant(c)                 f = c
    Function.polynomial(c0, c1, ...)     f = c0 + c1 t + ... (1 to 8 coefficients)
    Function.sine(a, b, omega, phase=0)  f = a + b sin(omega t + phase)
    Function.spline(t, y)                the C2 cubic spline through the samples (t strictly
                                         increasing, 2 or more; not-a-knot ends from 4 samples)

    f, f' and f'' are exact for each kind. A Python callable is not offered: the library would
    call it without the GIL, from IDA's inner loop.
    """

    kind: str
    params: Any

    @classmethod
    def constant(cls, c: float) -> "Function":
        return cls("constant", (float(c),))

    @classmethod
    def polynomial(cls, *c: float) -> "Function":
        return cls("polynomial", tuple(float(x) for x in c))

    @classmethod
    def sine(cls, a: float, b: float, omega: float, phase: float = 0.0) -> "Function":
        return cls("sine", (float(a), float(b), float(omega), float(phase)))

    @classmethod
    def spline(cls, t: Sequence[float], y: Sequence[float]) -> "Function":
        return cls("spline", (t, y))


__all__ = ["Builder", "Contact", "ContactSet", "Error", "Function", "Model", "Result", "Trajectory", "load_urdf",
           "VT_HAVE_SUNDIALS", "__version__"]
