"""What the two chapters share: the engine under :mod:`kinbook.planar` and :mod:`kinbook.spatial`.

It imports nothing above it (no chapter, no grading, no book); each name has one home, imported from its module:

- :mod:`~kinbook.core.reader` — the one reader of untrusted text (a whitelist, bounds checked before arithmetic)
- :mod:`~kinbook.core.arrays` — numeric input checks shared by every entry point
- :mod:`~kinbook.core.symbolic` — Φ_q, ν and γ derived from a symbolic Φ; drivers' functions of time
- :mod:`~kinbook.core.kernels` — the numeric kernels compiled from Φ
- :mod:`~kinbook.core.constraint` — the constraint family: the base class that binds declared keys, composites
- :mod:`~kinbook.core.registry` — the registry of types; the keys a type declares and its generated constructor
- :mod:`~kinbook.core.assembly` — constraints grouped by kernel, the vectorized evaluation of Φ, Φ_q, ν, γ
- :mod:`~kinbook.core.mechanism` — the mechanism base: bodies, names, its one cache, the constraint table
- :mod:`~kinbook.core.solve` — position (Newton–Raphson), velocity and acceleration at one instant
- :mod:`~kinbook.core.diagnose` — why Φ_q is singular: redundant constraints or a dead point
- :mod:`~kinbook.core.sweep` — sweeps over many instants and continuation along one assembly branch
- :mod:`~kinbook.core._linalg` — the linear solve and the scaled conditioning the analyses share
- :mod:`~kinbook.core._animation` — the animation writer both chapters' plotting uses
- :mod:`~kinbook.core.atomic` — the one writer of files: whole or not at all, never over a command's own inputs
"""

__all__ = []  # nothing is imported from the package itself: each name from its module
