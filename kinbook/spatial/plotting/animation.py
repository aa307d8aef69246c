"""Animations of a spatial sweep: :func:`animate` (a matplotlib FuncAnimation that moves one :class:`Drawing`)
and :func:`animation_png` (an animated PNG that plays in every notebook front end)."""

from __future__ import annotations

import numpy as np

from ...core._animation import Animation
from ...errors import InputError
from .scene import draw

__all__ = ["animate", "animation_png"]


def animate(result, ax=None, *, frames=False, every=1, interval=40, max_frames=None, figsize=None, dpi=None,
            trace=None, view=None):
    """Animate a sweep (:meth:`Mechanism.simulate`'s result) with matplotlib.

    Parameters
    ----------
    result : SimulationResult
    ax : Axes3D, optional
    frames : bool
        Draw the bodies' local axes too.
    every : int
        Use every ``every``-th instant; raised as needed so there are at most ``max_frames`` frames.
    interval : float
        Milliseconds between frames.
    max_frames : int, optional
    figsize, dpi : optional
        Of the figure created when ``ax`` is not given.
    trace : list of (body, point), optional
        Draw the whole path of these points (thin lines), so the animation shows where they go.
    view : (elev, azim), optional
        Viewing angles in degrees.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Show it in a notebook with :func:`animation_png`. Its ``drawing`` attribute is
        the :class:`Drawing` it updates.
    """
    from matplotlib.animation import FuncAnimation  # import time: matplotlib only when needed

    mech = result.mechanism
    if len(result) == 0:
        raise InputError("the sweep has no solved instant to animate")
    every = int(every)
    if every < 1:
        raise InputError(f"`every` must be a positive integer, got {every}")
    if max_frames is not None:
        if int(max_frames) < 1:
            raise InputError(f"`max_frames` must be a positive integer, got {max_frames}")
        every = max(every, -(-len(result) // int(max_frames)))
    idx = np.arange(0, len(result), every)
    extent = np.vstack([result.position(b.name, p) for b in mech.bodies for p in b.points] or [np.zeros((1, 3))])
    drawing = draw(mech, result.q[idx[0]], ax=ax, frames=frames, limits=extent, figsize=figsize, dpi=dpi)
    for body, point in trace or ():
        path = result.position(body, point)
        drawing.ax.plot(path[:, 0], path[:, 1], path[:, 2], color="tab:purple", linewidth=1.0)
    if view is not None:
        drawing.ax.view_init(elev=view[0], azim=view[1])
    title = drawing.ax.set_title(f"{mech.title}   t = {result.t[idx[0]]:.3f}", fontsize=9)

    def update(k):
        artists = drawing.update(result.q[idx[k]])
        title.set_text(f"{mech.title}   t = {result.t[idx[k]]:.3f}")
        return artists

    anim = FuncAnimation(drawing.ax.figure, update, frames=len(idx), interval=interval, blit=False)
    anim.drawing = drawing
    anim.update_frame = update
    anim.kinbook_indices = idx
    return anim


def animation_png(result, colors=256, **kwargs):
    """:func:`animate` for notebooks: an object that shows itself as an animated PNG (no notebook trust needed).

    The figure is closed so the notebook does not also show it as a still image. Keyword arguments go to
    :func:`animate`; the defaults here are smaller (60 frames at most, 72 dpi, a 256-colour palette for the
    shaded view) because every frame is stored in the notebook. The same sweep gives the same bytes.

    Returns
    -------
    kinbook.core._animation.Animation
        ``_repr_png_()`` is the animated PNG; ``.anim`` is the FuncAnimation; ``.save(path)`` writes the file.
    """
    import matplotlib.pyplot as plt  # import time: matplotlib only when needed

    if kwargs.get("ax") is None:
        kwargs.setdefault("figsize", (5.6, 4.6))
        kwargs.setdefault("dpi", 72)
    kwargs.setdefault("max_frames", 60)
    anim = animate(result, **kwargs)
    anim.drawing.ax.figure.subplots_adjust(left=0, right=1, bottom=0, top=0.93)
    plt.close(anim.drawing.ax.figure)
    return Animation(anim, colors)
