"""3D drawings and animations of spatial mechanisms with matplotlib (textbook §14.5).

Each body is drawn as the polyline through its named points (in the order they were declared), with a
marker at every point; a body with a :class:`~kinbook.spatial.Ground` constraint is drawn dashed and grey.
Optionally each body's local axes ξ, η, ζ are drawn at its origin (red, green, blue).

In a notebook::

    from IPython.display import HTML
    result = mech.simulate(np.linspace(0, 1, 61))
    HTML(animate(result).to_jshtml())
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError

__all__ = ["Drawing", "draw", "animate"]

_FRAME_COLOURS = ("tab:red", "tab:green", "tab:blue")


@dataclass
class Drawing:
    """What :func:`draw` made: the axes, and the artists by body name (so they can be updated or tested).

    Attributes
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    lines : dict of str -> Line3D
        The polyline (with point markers) of each body.
    frames : dict of str -> list of Line3D
        The three local axes of each body (empty without ``frames=True``).
    labels : dict of str -> list of Text3D
    """

    ax: object
    mechanism: object
    lines: dict = field(default_factory=dict)
    frames: dict = field(default_factory=dict)
    labels: dict = field(default_factory=dict)
    frame_size: float = 0.0

    def update(self, q):
        """Move every artist to the configuration ``q`` (shape (n,))."""
        mech = self.mechanism
        for body in mech.bodies:
            pts = _body_points(mech, q, body)
            line = self.lines[body.name]
            line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
            for text, xyz in zip(self.labels.get(body.name, []), pts):
                text.set_position_3d(xyz)
            if self.frames.get(body.name):
                r = mech.r(q, body.name)
                A = mech.A(q, body.name)
                for k, axis_line in enumerate(self.frames[body.name]):
                    end = r + self.frame_size * A[:, k]
                    axis_line.set_data_3d([r[0], end[0]], [r[1], end[1]], [r[2], end[2]])
        return [*self.lines.values(), *(a for f in self.frames.values() for a in f),
                *(t for ts in self.labels.values() for t in ts)]


def _body_points(mech, q, body):
    if body.points:
        return np.array([mech.point_position(q, body.name, name) for name in body.points])
    return mech.r(q, body.name)[None, :]


def _grounded(mech):
    return {c.body_names[0] for c in mech.constraints if c.type_name == "ground"}


def _check_single(mech, q):
    q = mech._check_q(q)
    if q.ndim != 1:
        raise InputError(f"`q` must be one configuration of shape ({mech.n},), got {q.shape}")
    return q


def _limits(ax, points, margin=0.1):
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, half = (lo + hi) / 2, max(float(np.max(hi - lo)) / 2, 1e-9) * (1 + margin)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))


def draw(mech, q, ax=None, frames=False, frame_size=None, labels=False, limits=None):
    """Draw a spatial mechanism at one configuration.

    Parameters
    ----------
    mech : kinbook.spatial.Mechanism
    q : array_like, shape (n,)
        An assembled configuration (unit Euler parameters), e.g. from ``mech.solve_position``.
    ax : Axes3D, optional
        Created (with equal scales on the three axes) when not given.
    frames : bool
        Also draw each body's local axes ξ (red), η (green), ζ (blue) at its origin.
    frame_size : float, optional
        Length of those axes; default 15 % of the drawing's size.
    labels : bool
        Write the point names next to the points.
    limits : array_like, shape (N, 3), optional
        Points the axis limits must contain (used by :func:`animate` so the view does not jump).

    Returns
    -------
    Drawing
    """
    import matplotlib.pyplot as plt

    q = _check_single(mech, q)
    if ax is None:
        fig = plt.figure()
        ax = fig.add_subplot(projection="3d")
    elif getattr(ax, "name", "") != "3d":
        raise InputError("`ax` must be a 3D axes: fig.add_subplot(projection='3d')")
    ground = _grounded(mech)
    all_points = []
    drawing = Drawing(ax, mech)
    for k, body in enumerate(mech.bodies):
        pts = _body_points(mech, q, body)
        all_points.append(pts)
        style = dict(color="0.5", linestyle="--", marker="^") if body.name in ground else dict(
            color=f"C{k % 10}", linestyle="-", marker="o")
        (line,) = ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], linewidth=2.5, markersize=5, label=body.name, **style)
        drawing.lines[body.name] = line
        if labels:
            drawing.labels[body.name] = [ax.text(*xyz, f" {name}", fontsize=8) for name, xyz in zip(body.points, pts)]
    pts = np.vstack(all_points + ([np.asarray(limits, dtype=float).reshape(-1, 3)] if limits is not None else []))
    size = float(np.max(pts.max(axis=0) - pts.min(axis=0))) or 1.0
    drawing.frame_size = 0.15 * size if frame_size is None else float(frame_size)
    if frames:
        for body in mech.bodies:
            r, A = mech.r(q, body.name), mech.A(q, body.name)
            drawing.frames[body.name] = [
                ax.plot(*np.column_stack([r, r + drawing.frame_size * A[:, k]]), color=c, linewidth=1)[0]
                for k, c in enumerate(_FRAME_COLOURS)
            ]
    _limits(ax, pts)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(mech.title)
    return drawing


def animate(result, ax=None, frames=False, every=1, interval=40):
    """Animate a sweep (:meth:`Mechanism.simulate`'s result) with matplotlib.

    Parameters
    ----------
    result : SimulationResult
    ax : Axes3D, optional
    frames : bool
        Draw the bodies' local axes too.
    every : int
        Use every ``every``-th instant.
    interval : float
        Milliseconds between frames.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Show it in a notebook with ``IPython.display.HTML(anim.to_jshtml())``. Its ``drawing`` attribute is
        the :class:`Drawing` it updates.
    """
    from matplotlib.animation import FuncAnimation

    mech = result.mechanism
    if len(result) == 0:
        raise InputError("the sweep has no solved instant to animate")
    every = int(every)
    if every < 1:
        raise InputError(f"`every` must be a positive integer, got {every}")
    idx = np.arange(0, len(result), every)
    extent = np.vstack([result.position(b.name, p) for b in mech.bodies for p in b.points] or [np.zeros((1, 3))])
    drawing = draw(mech, result.q[idx[0]], ax=ax, frames=frames, limits=extent)
    title = drawing.ax.set_title(f"{mech.title}   t = {result.t[idx[0]]:.3f}")

    def update(k):
        artists = drawing.update(result.q[idx[k]])
        title.set_text(f"{mech.title}   t = {result.t[idx[k]]:.3f}")
        return artists

    anim = FuncAnimation(drawing.ax.figure, update, frames=len(idx), interval=interval, blit=False)
    anim.drawing = drawing
    anim.update_frame = update
    return anim
