"""Spatial mechanisms with one constraint of each type at random geometry, for invariant tests.

They are not meant to assemble: the tests evaluate Φ, Φ_q, ν and γ at arbitrary configurations.
"""

import numpy as np

from kinbook.spatial import (
    Cylindrical,
    DistanceDriver,
    Ground,
    Mechanism,
    Normal1,
    Normal2,
    Parallel1,
    Parallel2,
    Revolute,
    RevoluteDriver,
    Spherical,
    SphericalSpherical,
    Translational,
    Universal,
    random_p,
)

FACTORIES = {
    "ground": lambda: Ground("a"),
    "normal-1": lambda: Normal1("a", "b", vector_i="u", vector_j="v"),
    "normal-2": lambda: Normal2("a", "b", vector_i="u", point_i="P", point_j="Q"),
    "parallel-1": lambda: Parallel1("a", "b", vector_i="u", vector_j=["P", "Q"]),
    "parallel-2": lambda: Parallel2("a", "b", vector_i="v", point_i="Q", point_j="P"),
    "spherical": lambda: Spherical("a", "b", point_i="P", point_j="Q"),
    "universal": lambda: Universal("a", "b", point="P", vector_i="u", vector_j="v"),
    "revolute": lambda: Revolute("a", "b", point_i="Q", point_j="P", axis_i="u", axis_j="u"),
    "cylindrical": lambda: Cylindrical("a", "b", point="P", axis_i="v", axis_j="u"),
    "translational": lambda: Translational("a", "b", point="Q", axis_i="u", axis_j="v", perp_i="v", perp_j="u"),
    "spherical-spherical": lambda: SphericalSpherical("a", "b", point_i="P", point_j="Q", length=1.3),
    "revolute-driver": lambda: RevoluteDriver("a", "b", axis_i="u", ref_i="v", ref_j="v", f="0.3 + 2*t + t**2"),
    "distance-driver": lambda: DistanceDriver("a", "b", axis_i="v", point_i="P", point_j="Q", f="0.5*sin(3*t)"),
}


def two_bodies(type_name, seed=0, simple=False):
    """Bodies 'a' and 'b' with random points P, Q and vectors u, v, and one constraint of ``type_name``.

    ``simple`` draws the geometry from small half-integers, which keeps symbolic expressions short (the
    symbolic γ of a constraint costs seconds to derive); random orientations either way.
    """
    rng = np.random.default_rng(seed)

    def trip():
        if simple:
            while True:
                v = tuple(float(x) for x in rng.integers(-3, 4, 3) / 2)
                if any(v):
                    return v
        return tuple(float(v) for v in rng.uniform(-2, 2, 3).round(3))

    m = Mechanism(f"{type_name}-{seed}")
    for b in ("a", "b"):
        q0 = trip() + tuple(random_p(rng=rng))
        m.add_body(b, points={"P": trip(), "Q": trip()}, vectors={"u": trip(), "v": trip()}, q0=q0)
    m.add(FACTORIES[type_name]())
    return m


def states(mech, count=4, seed=7):
    """Random (q, q̇, t) with unit p and pᵀṗ = 0 — and also off the unit sphere, where the identities
    between the symbolic and the fast path must hold just as well."""
    rng = np.random.default_rng(seed)
    nb = mech.n // 7
    for k in range(count):
        q = rng.uniform(-2, 2, (nb, 7))
        q[:, 3:] = random_p(nb, rng) * (1.0 if k % 2 == 0 else rng.uniform(0.7, 1.3, (nb, 1)))
        qd = rng.uniform(-3, 3, (nb, 7))
        yield q.ravel(), qd.ravel(), float(rng.uniform(-1, 1))
