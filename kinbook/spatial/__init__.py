"""Spatial kinematics in body coordinates with Euler parameters (textbook chapter 14).

- :mod:`~kinbook.spatial.rotations` — direction cosines, z-x-z Euler angles, Euler parameters, E and G (§14.1–14.3)
- :mod:`~kinbook.spatial.transforms` — point position, velocity and acceleration from r, p and their rates
- :mod:`~kinbook.spatial.constraints` — n1, n2, p1, p2, spherical, universal, revolute, cylindrical,
  translational, ground and drivers, each with a symbolic Φ and a fast kernel (§14.4, Table 14.1)
- :mod:`~kinbook.spatial.mechanism` — bodies q_i = [x, y, z, e0, e1, e2, e3], normalization rows, analysis (§14.5)
- :mod:`~kinbook.spatial.plotting` — 3D drawings and animations

Conventions (frames, active rotations, z-x-z, radians, unit p): docs/conventions.md.
"""

from . import constraints, plotting, random, rotations, transforms
from .constraints import (
    CONSTRAINT_TYPES,
    Constraint,
    Cylindrical,
    DistanceDriver,
    Ground,
    Normal1,
    Normal2,
    Normalization,
    Parallel1,
    Parallel2,
    Revolute,
    RevoluteDriver,
    Spherical,
    SphericalSpherical,
    Translational,
    Universal,
)
from .mechanism import Body, ConstraintTable, Mechanism
from .plotting import draw_frame, draw_vector, joint_figure, make_3d_axes
from .random import random_p, random_p_rates
from .rotations import (
    A_ddot,
    A_dot,
    A_from_axes,
    A_from_euler,
    A_from_p,
    E,
    G,
    a_bar,
    alpha_from_p,
    axis_angle_from_p,
    check_rotation,
    dAa_dp,
    euler_from_A,
    euler_rates_from_omega,
    normalization,
    normalize_p,
    omega_from_euler_rates,
    omega_from_p_dot,
    p_dot_from_omega,
    p_from_A,
    p_from_axis_angle,
    skew,
)
from .transforms import point_acceleration, point_position, point_velocity

__all__ = [
    "plotting",
    "draw_vector",
    "draw_frame",
    "make_3d_axes",
    "joint_figure",
    "random_p",
    "random_p_rates",
    "Body",
    "Mechanism",
    "ConstraintTable",
    *transforms.__all__,
    *constraints.__all__,
    *rotations.__all__,
]
