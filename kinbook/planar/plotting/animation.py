"""Animations of a planar sweep: :func:`animate` (a matplotlib FuncAnimation whose artists are created once
and moved) and :func:`animation_png` (an animated PNG that plays in every notebook front end)."""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...core._animation import Animation, degrees_as_read
from ...errors import InputError
from ._common import TRACES, pyplot, style_axes
from .joints import drawing_size, driver_symbol
from .scene import Scene

__all__ = ["animate", "animation_png", "MAX_FRAMES"]

MAX_FRAMES = 120
"""Default cap on the number of frames of an animation."""


def animate(result, *, every=1, interval=40, frames=False, trace=None, max_frames=MAX_FRAMES, labels=True,
            figsize=(6.4, 4.8), dpi=None):
    """Animate a sweep: the mechanism at its solved instants.

    Parameters
    ----------
    result : SimulationResult
        Only the solved instants are shown (a truncated sweep stops at the dead point).
    every : int
        Show every ``every``-th instant; raised as needed so there are at most ``max_frames`` frames.
    interval : int
        Milliseconds between frames.
    frames : bool
        Draw the bodies' local frames.
    trace : list of (body, point), optional
        Points whose paths are drawn faintly and traced as the mechanism moves.
    max_frames : int
    labels : bool
        Body numbers and point names.
    figsize, dpi
        Of the new figure.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Its figure is a pyplot figure (``plt.show()`` plays it in a script).

    Notes
    -----
    The artists are created once and moved (blitting), so the animation renders quickly. The overlay shows t and
    the first driver's value; an angle in degrees as the book gives it, in [0°, 360°) — a crank driven on past a
    full turn reads 45° again, not 405° — or signed when it swings about zero
    (:func:`kinbook.core._animation.degrees_as_read`).
    """
    from matplotlib.animation import FuncAnimation  # import time: matplotlib only when needed

    mech = result.mechanism
    N = len(result.t)
    if N == 0:
        raise InputError("the sweep has no solved instant to animate")
    every = max(1, int(every), math.ceil(N / max(1, int(max_frames))))
    idx = np.arange(0, N, every)
    fig, ax = pyplot().subplots(figsize=figsize, dpi=dpi)
    qs = result.q[idx]
    scene = Scene(ax, mech, qs[0], frames=frames, labels=labels, size=drawing_size(mech, qs))
    traces = _traces(ax, result, trace, idx)
    box = scene.observe(qs)
    scene.set_limits(box)
    style_axes(ax, getattr(mech, "title", None))
    sym, values, unit = _driver_values(result, idx)
    clock = ax.text(0.02, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9, zorder=10,
                    bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="#bbbbbb", alpha=0.9))

    def update(k):
        artists = scene.update(qs[k])
        text = f"t = {result.t[idx[k]]:.4g}"  # plain text: mathtext would be parsed anew every frame
        if values is not None:
            text += f"    {sym} = {values[k]}{unit}"
        if k == len(idx) - 1 and result.failure is not None:
            text += "   (last instant that assembles)"
        clock.set_text(text)
        for line, xy in traces:
            line.set_data(xy[: k + 1, 0], xy[: k + 1, 1])
        return artists + [clock] + [line for line, _ in traces]

    update(0)
    anim = FuncAnimation(fig, update, frames=len(idx), init_func=lambda: update(0), interval=interval,
                         blit=True, repeat=True)
    anim.kinbook_indices = idx
    return anim


def _traces(ax, result, trace, idx):
    """(line, path) of each traced point: its whole path drawn faintly, and the line that follows it."""
    traces = []
    for k, (body, point) in enumerate(trace or []):
        xy = result.position(body, point)[idx]
        ax.plot(xy[:, 0], xy[:, 1], ":", color="#888888", lw=1.0, zorder=1)
        (line,) = ax.plot([], [], "-", color=TRACES[k % len(TRACES)], lw=1.5, zorder=1)
        traces.append((line, xy))
    return traces


def _driver_values(result, idx):
    """(symbol, values at the instants ``idx`` as text, unit) of the first driver; (None, None, "") without one.
    An angle is read in degrees, in the range the text gives it (:func:`~kinbook.core._animation.degrees_as_read`):
    a crank that has turned on from 45° past a full turn reads 45° again, not 405°."""
    mech = result.mechanism
    driver = mech.drivers[0] if mech.drivers else None
    sym = driver_symbol(mech, driver, unicode=True) if driver is not None else None
    values, unit = None, ""
    if driver is not None:
        f = sp.lambdify(mech.t, driver.f, "numpy")
        values = np.broadcast_to(np.asarray(f(result.t[idx]), dtype=float), idx.shape)
        if (driver.measures or (None,))[-1] == "angle":
            values, unit = degrees_as_read(values), "°"
        else:
            values = [f"{v:.4g}" for v in values]
    return sym, values, unit


def animation_png(result, colors=256, **kwargs):
    """:func:`animate` for notebooks: an object that shows itself as an animated PNG.

    An image needs no notebook trust: it plays in JupyterLab, VS Code, the live site and the book alike (a
    JavaScript player plays only in a trusted notebook). The figure is closed so the notebook does not also show
    it as a still image. Keyword arguments go to :func:`animate`; the defaults here are smaller (72 frames at
    most, 72 dpi) because every frame is stored in the notebook. The same sweep gives the same bytes.

    Parameters
    ----------
    colors : int or None
        Store the frames with a shared palette of this many colours (a third of the size of full colour for these
        drawings; see :func:`kinbook.core._animation.apng`); None keeps full colour.

    Returns
    -------
    kinbook.core._animation.Animation
        ``_repr_png_()`` is the animated PNG; ``.anim`` is the FuncAnimation; ``.save(path)`` writes the file.
    """
    kwargs.setdefault("figsize", (6.0, 4.5))
    kwargs.setdefault("dpi", 72)
    kwargs.setdefault("max_frames", 72)
    anim = animate(result, **kwargs)
    pyplot().close(anim._fig)
    return Animation(anim, colors)
