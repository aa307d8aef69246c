"""Planar kinematics in body coordinates (textbook chapter 13)."""

from ..analysis import Diagnosis, SimulationResult
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

__all__ = [
    "A",
    "B",
    "point_position",
    "point_velocity",
    "point_acceleration",
    "Body",
    "Mechanism",
    "ConstraintTable",
    "Constraint",
    "Simple",
    "Ground",
    "Revolute",
    "Translational",
    "RevoluteRevolute",
    "RevoluteTranslational",
    "Gear",
    "RackPinion",
    "Driver",
    "RelativeAngleDriver",
    "DistanceDriver",
    "CONSTRAINT_TYPES",
    "Diagnosis",
    "SimulationResult",
]
