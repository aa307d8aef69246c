"""A mechanism with every planar constraint type, at random geometry, for invariant tests.

It is not meant to assemble: the tests evaluate Φ, Φ_q, ν and γ at arbitrary configurations.
"""

import numpy as np

from kinbook.planar import (
    DistanceDriver,
    Driver,
    Gear,
    Ground,
    Mechanism,
    RackPinion,
    RelativeAngleDriver,
    Revolute,
    RevoluteRevolute,
    RevoluteTranslational,
    Simple,
    Translational,
)


def zoo(seed=0):
    rng = np.random.default_rng(seed)

    def pt():
        return tuple(float(v) for v in rng.uniform(-2, 2, 2).round(3))

    m = Mechanism(f"zoo{seed}")
    for b in ("a", "b", "c"):
        m.add_body(b, points={"P": pt(), "Q": pt(), "R": pt()}, q0=tuple(rng.uniform(-1, 1, 3).round(3)))
    m.add(Ground("a"))
    m.add(Simple("b", "y", 0.25))
    m.add(Revolute("a", "b", point_i="P", point_j="Q"))
    m.add(Translational("b", "c", axis=("P", "Q"), point_j="R", phi0=0.3))
    m.add(RevoluteRevolute("a", "c", point_i="Q", point_j="P", length=1.7))
    m.add(RevoluteTranslational("c", "b", point_i="Q", axis=("R", "P")))
    m.add(Gear("b", "c", "a", radius_i=0.5, radius_j=1.25))
    m.add(RackPinion("b", "c", radius=0.4))
    m.add(RackPinion("c", "b", radius=0.7, sliding=True))
    m.add(Driver("b", "phi", "0.5 + 2*t + sin(3*t)"))
    m.add(RelativeAngleDriver("a", "c", "t**2/2"))
    m.add(DistanceDriver("c", "a", axis=("P", "R"), point_j="Q", f="1 + cos(t)"))
    return m
