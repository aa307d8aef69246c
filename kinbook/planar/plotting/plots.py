"""Plots of a planar sweep: paths of body points (:func:`plot_trajectories`) and time histories of coordinates
and point coordinates in the book's notation (:func:`plot_history`)."""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from ._common import coordinate_label, new_axes, point_label, point_text, set_axes_limits
from .scene import Scene

__all__ = ["plot_trajectories", "plot_history"]


def _parse_point(item):
    if not (isinstance(item, (tuple, list)) and len(item) == 2):
        raise InputError(f"points are given as (body, point) pairs, got {item!r}")
    return item


def plot_trajectories(result, points, ax=None, *, mechanism=True):
    """Paths of body points over a sweep, in the global frame.

    Parameters
    ----------
    result : SimulationResult
    points : list of (body, point)
    ax : matplotlib Axes, optional
    mechanism : bool
        Draw the mechanism faintly at the first solved instant, for orientation.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = new_axes(ax)
    mech = result.mechanism
    if len(result.t) == 0:
        raise InputError("the sweep has no solved instant to plot")
    x0 = y0 = np.inf
    x1 = y1 = -np.inf
    if mechanism:
        scene = Scene(ax, mech, result.q[0], labels=False)
        x0, x1, y0, y1 = scene.observe([result.q[0]])
        scene.update(result.q[0])
        for a in scene.artists:
            alpha = a.get_alpha()
            a.set_alpha(0.25 if alpha is None else 0.25 * alpha)
    lo, hi = np.array([np.inf, np.inf]), np.array([-np.inf, -np.inf])
    for body, point in map(_parse_point, points):
        xy = result.position(body, point)
        lo, hi = np.minimum(lo, xy.min(axis=0)), np.maximum(hi, xy.max(axis=0))
        n = mech.body(body).number
        name = point_text(point if isinstance(point, str) else "P").strip("$")
        (line,) = ax.plot(xy[:, 0], xy[:, 1], "-", lw=1.8, label=rf"${name}_{{{n}}}$ (body {n})", zorder=9)
        ax.plot(xy[:1, 0], xy[:1, 1], "o", color=line.get_color(), ms=4, zorder=9)
    set_axes_limits(ax, (min(lo[0], x0), max(hi[0], x1), min(lo[1], y0), max(hi[1], y1)), margin=0.05)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.legend(fontsize=9, loc="best")
    ax.grid(True, lw=0.4, alpha=0.4)
    return ax


def _history(result, name, derivative):
    mech = result.mechanism
    if isinstance(name, (tuple, list)) and len(name) == 3:
        body, point, comp = name
        if comp not in ("x", "y"):
            raise InputError(f"a point quantity is (body, point, 'x' or 'y'), got component {comp!r}")
        data = (result.position, result.velocity, result.acceleration)[derivative](body, point)
        return data[:, "xy".index(comp)], point_label(mech, body, point, comp, derivative)
    name = tuple(name) if isinstance(name, list) else name
    return result.coordinate(name, derivative), coordinate_label(mech, name, derivative)


def plot_history(result, names, derivative=0, ax=None):
    """Time histories of coordinates or of point coordinates over a sweep.

    Parameters
    ----------
    result : SimulationResult
    names : str, tuple or list of them
        Coordinates such as ``"phi3"``, ``"x2"`` or ``("rocker", "phi")``, and point quantities
        ``(body, point, "x")`` / ``(body, point, "y")`` (x_i^P, y_i^P).
    derivative : {0, 1, 2}
        Plot the values, the velocities (ẋ, φ̇) or the accelerations (ẍ, φ̈).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
        Labelled in the book's notation (φ₃, ẋ₂, ẍ₃^B …), units-free.
    """
    if derivative not in (0, 1, 2):
        raise InputError(f"`derivative` must be 0, 1 or 2, got {derivative!r}")
    if isinstance(names, str) or (isinstance(names, tuple) and len(names) in (2, 3)
                                  and isinstance(names[-1], str) and names[-1] in ("x", "y", "phi")):
        names = [names]
    ax = new_axes(ax)
    labels = []
    for name in names:
        y, label = _history(result, name, derivative)
        ax.plot(result.t, y, label=label)
        labels.append(label)
    ax.set_xlabel("$t$")
    ax.set_ylabel(labels[0] if len(labels) == 1 else ", ".join(labels))
    if len(labels) > 1:
        ax.legend(fontsize=9)
    ax.grid(True, lw=0.4, alpha=0.4)
    return ax
