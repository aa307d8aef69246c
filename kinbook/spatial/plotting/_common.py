"""What the spatial drawings share: checks of their arguments, the bodies' points, limits with equal scales on
the three axes, and the arrow patch (built on first use, so importing kinbook.spatial does not import
matplotlib)."""

from __future__ import annotations

import numpy as np

from ...errors import InputError

__all__ = ["FRAME_COLOURS", "body_points", "grounded", "check_single", "equal_scales", "set_limits", "check_ax",
           "point3", "arrow_class", "include"]

FRAME_COLOURS = ("tab:red", "tab:green", "tab:blue")


def body_points(mech, q, body):
    if body.points:
        return np.array([mech.point_position(q, body.name, name) for name in body.points])
    return mech.r(q, body.name)[None, :]


def grounded(mech):
    return set(mech.fixed_bodies())


def check_single(mech, q):
    q = mech.check_q(q)
    if q.ndim != 1:
        raise InputError(f"`q` must be one configuration of shape ({mech.n},), got {q.shape}")
    return q


def equal_scales(ax, zoom=1.0):
    """Shape the box of a 3D axes like its current limits, so that a unit has the same length along x, y
    and z (a circle looks round, a right angle looks right). Call it after changing the limits by hand;
    :func:`draw`, :func:`draw_vector` and :func:`draw_frame` call it themselves.

    Parameters
    ----------
    ax : Axes3D
    zoom : float
        matplotlib's zoom of the box in its figure (``set_box_aspect(..., zoom=)``).
    """
    check_ax(ax)
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    ax.set_box_aspect(tuple(spans / spans.max()), zoom=zoom)


def set_limits(ax, points, margin=0.1):
    """Limits that contain ``points`` with equal scales on the three axes and a box shaped like the
    drawing (a flat or long mechanism is not drawn in a mostly empty cube); no side is thinner than a
    fifth of the longest, so a planar-looking view keeps some depth."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    size = max(float(np.max(hi - lo)), 1e-9)
    half = np.maximum((hi - lo) / 2, 0.1 * size) + margin * size / 2
    centre = (lo + hi) / 2
    ax.set_xlim(centre[0] - half[0], centre[0] + half[0])
    ax.set_ylim(centre[1] - half[1], centre[1] + half[1])
    ax.set_zlim(centre[2] - half[2], centre[2] + half[2])
    equal_scales(ax)
    from matplotlib.ticker import MaxNLocator  # import time: matplotlib only when needed

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(4))


def check_ax(ax):
    if getattr(ax, "name", "") != "3d":
        raise InputError(f"`ax` must be a 3D axes: fig.add_subplot(projection='3d'), got {type(ax).__name__}")


def point3(v, name):
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"`{name}` must be three numbers (x, y, z), got {v!r}") from None
    if a.shape != (3,):
        raise InputError(f"`{name}` must have shape (3,), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"`{name}` must be finite (no NaN or inf), got {a}")
    return a


_ARROW_CLASS = []


def arrow_class():
    """The arrow patch class, built on first use so that importing kinbook.spatial does not import matplotlib.

    An arrow is a :class:`matplotlib.patches.FancyArrowPatch` between two 3D points, drawn with a flat arrowhead
    facing the viewer; ``get_data_3d()`` returns its start and end (shape (2, 3)), ``set_data_3d(start, end)``
    moves it.
    """
    if _ARROW_CLASS:
        return _ARROW_CLASS[0]
    from matplotlib.patches import FancyArrowPatch  # import time: matplotlib only when needed
    from mpl_toolkits.mplot3d import proj3d  # import time: matplotlib only when plotting

    class Arrow3D(FancyArrowPatch):
        def __init__(self, start, end, **kwargs):
            kwargs.setdefault("arrowstyle", "-|>")
            kwargs.setdefault("mutation_scale", 14)
            kwargs.setdefault("shrinkA", 0)
            kwargs.setdefault("shrinkB", 0)
            super().__init__((0.0, 0.0), (0.0, 0.0), **kwargs)
            self._xyz = np.array([start, end], dtype=float)

        def get_data_3d(self):
            return self._xyz.copy()

        def set_data_3d(self, start, end):
            self._xyz = np.array([start, end], dtype=float)
            self.stale = True

        def do_3d_projection(self, renderer=None):
            xs, ys, zs = proj3d.proj_transform(*self._xyz.T, self.axes.M)
            self.set_positions((xs[0], ys[0]), (xs[1], ys[1]))
            return float(np.min(zs))

    _ARROW_CLASS.append(Arrow3D)
    return Arrow3D


def include(ax, points, had_data):
    """Grow the limits (never shrink them) so they contain ``points``, then keep equal scales."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    if had_data:
        limits = np.array([ax.get_xlim(), ax.get_ylim(), ax.get_zlim()])
        lo, hi = np.minimum(limits[:, 0], points.min(axis=0)), np.maximum(limits[:, 1], points.max(axis=0))
        if np.any(lo < limits[:, 0]) or np.any(hi > limits[:, 1]):
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[1], hi[1])
            ax.set_zlim(lo[2], hi[2])
    else:
        ax.auto_scale_xyz(points[:, 0], points[:, 1], points[:, 2], had_data)
    equal_scales(ax)
