"""Planar kinematics in body coordinates (textbook chapter 13)."""

from ..core.diagnose import Diagnosis
from ..core.sweep import SimulationResult
from . import constraints, mechanism, transforms
from .constraints import (
    CONSTRAINT_TYPES,
    Constraint,
    DistanceDriver,
    Driver,
    Gear,
    Ground,
    RackPinion,
    RelativeAngleDriver,
    Revolute,
    RevoluteRevolute,
    RevoluteTranslational,
    Simple,
    Translational,
)
from .mechanism import Body, ConstraintTable, Mechanism
from .transforms import A, B, point_acceleration, point_position, point_velocity

__all__ = [*transforms.__all__, *mechanism.__all__, *constraints.__all__, "Diagnosis", "SimulationResult"]
