"""What the two chapters share: the engine under :mod:`kinbook.planar` and :mod:`kinbook.spatial`.

It imports nothing above it (no chapter, no grading, no book); each name has one home, imported from its module:

- :mod:`~kinbook.core.reader` — the one reader of untrusted text (a whitelist, bounds checked before arithmetic)
- :mod:`~kinbook.core.arrays` — numeric input checks shared by every entry point
- :mod:`~kinbook.core.symbolic` — Φ_q, ν and γ derived from a symbolic Φ; drivers' functions of time
- :mod:`~kinbook.core.kernels` — the numeric kernels compiled from Φ
- :mod:`~kinbook.core.mechanism` — the constraint family and registry, the mechanism base with its cache and table
- :mod:`~kinbook.core.solve` — position, velocity and acceleration analysis, diagnosis and sweeps
- :mod:`~kinbook.core._animation` — the animation writer both chapters' plotting uses
"""
