"""vtdyn: inverse dynamics of URDF robots, NumPy arrays in and out (docs/python.md).

    import numpy as np, vtdyn
    robot = vtdyn.load_urdf("ur5_robot.urdf")
    r = robot.inverse(q, v, a)          # one state (1-D) or N states (N x nq, N x nv)
    r.effort, r.reaction                # N x nv, N x nbody x 6 (world axes)

The work is the C library's vt_batch_inverse_dynamics_motion, on threads, with the GIL released.
"""
from ._vtdyn import Error, Model, Result, load_urdf
from ._vtdyn import version as _c_version

__version__: str = _c_version()
"""The C library's version (the package is built from the same source)."""

__all__ = ["Error", "Model", "Result", "load_urdf", "__version__"]
