"""A spatial mechanism drawn at one configuration (:func:`draw`, the :class:`Drawing` it returns), the single
arrows and frames of the book's figures (:func:`draw_vector`, :func:`draw_frame`), and axes set up for them
(:func:`make_3d_axes`, :func:`joint_figure`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...errors import InputError
from ..rotations import check_rotation
from ._common import (
    FRAME_COLOURS,
    arrow_class,
    body_points,
    check_ax,
    check_single,
    equal_scales,
    grounded,
    include,
    point3,
    set_limits,
)

__all__ = ["Drawing", "draw", "DrawnVector", "DrawnFrame", "draw_vector", "draw_frame", "make_3d_axes", "joint_figure"]


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
            pts = body_points(mech, q, body)
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


def draw(mech, q, ax=None, *, frames=False, frame_size=None, labels=False, limits=None, figsize=None, dpi=None):
    """Draw a spatial mechanism at one configuration.

    Parameters
    ----------
    mech : kinbook.spatial.Mechanism
    q : array_like, shape (n,)
        An assembled configuration (unit Euler parameters), e.g. from ``mech.solve_position``.
    ax : Axes3D, optional
        Created (with equal scales on the three axes) when not given. Titled with the mechanism's title unless
        it already has a title.
    frames : bool
        Also draw each body's local axes ξ (red), η (green), ζ (blue) at its origin.
    frame_size : float, optional
        Length of those axes; default 15 % of the drawing's size.
    labels : bool
        Write the point names next to the points.
    limits : array_like, shape (N, 3), optional
        Points the axis limits must contain (used by :func:`animate` so the view does not jump).
    figsize, dpi : optional
        Of the figure created when ``ax`` is not given.

    Returns
    -------
    Drawing
    """
    import matplotlib.pyplot as plt  # import time: matplotlib only when needed

    q = check_single(mech, q)
    if ax is None:
        fig = plt.figure(figsize=figsize, dpi=dpi)
        ax = fig.add_subplot(projection="3d")
    else:
        check_ax(ax)
    ground = grounded(mech)
    all_points = []
    drawing = Drawing(ax, mech)
    for k, body in enumerate(mech.bodies):
        pts = body_points(mech, q, body)
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
                for k, c in enumerate(FRAME_COLOURS)
            ]
    set_limits(ax, pts)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    if not ax.get_title():  # an axes titled by the caller (make_3d_axes, joint_figure) keeps its title
        ax.set_title(mech.title)
    return drawing


@dataclass
class DrawnVector:
    """What :func:`draw_vector` drew.

    Attributes
    ----------
    arrow : matplotlib.patches.FancyArrowPatch
        The arrow; ``arrow.get_data_3d()`` is ``[origin, origin + vector]``.
    label : Text3D or None
    origin, vector : ndarray, shape (3,)
    """

    arrow: object
    label: object
    origin: np.ndarray
    vector: np.ndarray


@dataclass
class DrawnFrame:
    """What :func:`draw_frame` drew.

    Attributes
    ----------
    axes : list of 3 matplotlib.patches.FancyArrowPatch
        The ξ, η and ζ axes: from ``origin`` to ``origin + size * A[:, k]``.
    labels : list of Text3D
        The axis names at the tips (empty with ``axis_labels=False``).
    origin : ndarray, shape (3,)
    A : ndarray, shape (3, 3)
    size : float
    """

    axes: list
    labels: list
    origin: np.ndarray
    A: np.ndarray
    size: float


def draw_vector(ax, origin, vector, label=None, color=None, linewidth=2.0, label_at=0.5, label_offset=None,
                fontsize=12, **arrow_kwargs):
    """Draw one vector as an arrow from ``origin`` to ``origin + vector`` on a 3D axes.

    Parameters
    ----------
    ax : Axes3D
    origin : array_like, shape (3,)
        Global coordinates of the tail.
    vector : array_like, shape (3,)
        Global components of the vector (e.g. s_i = A_i s'_i, or d = r_j^P − r_i^P). A zero vector draws
        nothing visible but is accepted.
    label : str, optional
        Text (matplotlib mathtext allowed, e.g. ``r"$\\mathbf{s}_i$"``) written beside the arrow.
    color : matplotlib colour, optional
        Default: the axes' next colour in its cycle.
    linewidth : float
    label_at : float
        Where along the arrow the label sits: 0 at the tail, 1 at the tip (default the middle).
    label_offset : array_like, shape (3,), optional
        Shift of the label from that point, global coordinates (default none).
    fontsize : float
    **arrow_kwargs
        Passed to :class:`matplotlib.patches.FancyArrowPatch` (``arrowstyle``, ``mutation_scale``,
        ``linestyle``, ``alpha`` …).

    Returns
    -------
    DrawnVector

    Raises
    ------
    InputError
        ``ax`` is not a 3D axes, or ``origin``, ``vector`` or ``label_offset`` are not three finite numbers.

    Notes
    -----
    The axis limits grow to contain the arrow (as for a line drawn with ``ax.plot``). Components are global
    (docs/conventions.md): draw a body vector s'_i as ``draw_vector(ax, r_i, A_i @ s_i_local)``.

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> ax = plt.figure().add_subplot(projection="3d")
    >>> v = draw_vector(ax, [1, 0, 0], [0, 2, 0], label="$\\\\mathbf{d}$")
    >>> v.arrow.get_data_3d()
    array([[1., 0., 0.],
           [1., 2., 0.]])
    >>> plt.close("all")
    """
    check_ax(ax)
    origin = point3(origin, "origin")
    vector = point3(vector, "vector")
    offset = np.zeros(3) if label_offset is None else point3(label_offset, "label_offset")
    if color is None:
        color = ax._get_lines.get_next_color()
    had_data = ax.has_data()
    arrow = arrow_class()(origin, origin + vector, color=color, linewidth=linewidth, **arrow_kwargs)
    ax.add_artist(arrow)
    include(ax, [origin, origin + vector], had_data)
    text = None
    if label is not None:
        text = ax.text(*(origin + float(label_at) * vector + offset), label, color=color, fontsize=fontsize)
    return DrawnVector(arrow, text, origin, vector)


def _frame_args(ax, origin, A, size, names, colors):
    """:func:`draw_frame`'s arguments checked: (origin, A, size, names, colors)."""
    check_ax(ax)
    origin = point3(origin, "origin")
    A = check_rotation(A, "A")
    if A.shape != (3, 3):
        raise InputError(f"`A` must be one rotation matrix of shape (3, 3), got {A.shape}")
    try:
        size = float(size)
    except (TypeError, ValueError):
        raise InputError(f"`size` must be a positive number, got {size!r}") from None
    if not (np.isfinite(size) and size > 0):
        raise InputError(f"`size` must be a positive number, got {size!r}")
    names, colors = list(names), list(colors)
    if len(names) != 3:
        raise InputError(f"`names` must have 3 entries (ξ, η, ζ), got {len(names)}")
    if len(colors) != 3:
        raise InputError(f"`colors` must have 3 entries (ξ, η, ζ), got {len(colors)}")
    return origin, A, size, names, colors


def draw_frame(ax, origin, A, label=None, *, size=1.0, names=(r"\xi", r"\eta", r"\zeta"), colors=FRAME_COLOURS,
               linewidth=1.5, axis_labels=True, fontsize=11):
    """Draw a body frame: the three local axes ξ, η, ζ of a rotation matrix at a point.

    Parameters
    ----------
    ax : Axes3D
    origin : array_like, shape (3,)
        Global position of the frame's origin (a body's r_i).
    A : array_like, shape (3, 3)
        Rotation matrix, local → global (docs/conventions.md): axis k is drawn along its column ``A[:, k]``.
    size : float
        Length of each axis arrow.
    label : str, optional
        Subscript added to the axis names: ``label="i"`` writes ξ_i, η_i, ζ_i.
    names : 3 str
        The axis names, matplotlib mathtext without the dollars.
    colors : 3 matplotlib colours
        Default red, green, blue (as :func:`draw` with ``frames=True``).
    linewidth : float
    axis_labels : bool
        Write the names at the tips.
    fontsize : float

    Returns
    -------
    DrawnFrame

    Raises
    ------
    InputError
        ``ax`` is not a 3D axes; ``origin`` is not three finite numbers; ``A`` is not a rotation matrix
        (shape (3, 3), AᵀA = I, det A = +1, see :func:`kinbook.spatial.check_rotation`); ``size`` is not a
        positive number; ``names`` or ``colors`` do not have three entries.

    Notes
    -----
    Textbook §14.1: the columns of A are the body's unit vectors u_ξ, u_η, u_ζ in global components.

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from kinbook.spatial import A_from_euler
    >>> ax = plt.figure().add_subplot(projection="3d")
    >>> f = draw_frame(ax, [0, 0, 1], A_from_euler(90, 0, 0, degrees=True), size=2, label="i")
    >>> f.axes[0].get_data_3d().round(12) + 0.0      # ξ_i: 2 units along global Y
    array([[0., 0., 1.],
           [0., 2., 1.]])
    >>> plt.close("all")
    """
    origin, A, size, names, colors = _frame_args(ax, origin, A, size, names, colors)
    had_data = ax.has_data()
    arrow_cls = arrow_class()
    tips = origin + size * A.T  # row k: tip of axis k
    axes = []
    for tip, colour in zip(tips, colors):
        arrow = arrow_cls(origin, tip, color=colour, linewidth=linewidth, mutation_scale=10)
        ax.add_artist(arrow)
        axes.append(arrow)
    include(ax, np.vstack([origin, tips]), had_data)
    labels = []
    if axis_labels:
        sub = "" if label is None else f"_{{{label}}}"
        labels = [ax.text(*(origin + 1.12 * (tip - origin)), f"${name}{sub}$", color=colour, fontsize=fontsize,
                          ha="center", va="center")
                  for name, tip, colour in zip(names, tips, colors)]
    return DrawnFrame(axes, labels, origin, A, size)


def make_3d_axes(ax=None, *, figsize=(7.0, 5.6), view=(24, -60), title=None, global_frame=0.0, subplot=111,
                 fig=None):
    """A 3D axes ready for kinbook's drawings: created (or checked), viewed from ``view`` = (elevation, azimuth)
    in degrees, titled, optionally with the global frame X, Y, Z drawn at the origin.

    Parameters
    ----------
    ax : Axes3D, optional
        Use this axes instead of a new figure.
    figsize : (float, float)
    view : (float, float)
        ``ax.view_init(elev, azim)``.
    title : str, optional
    global_frame : float
        Length of the global X, Y, Z arrows drawn at the origin (0: none).
    subplot : int or (int, int, int)
        Where in ``fig`` a new axes goes (several drawings side by side share one figure).
    fig : matplotlib Figure, optional

    Returns
    -------
    Axes3D
    """
    if ax is None:
        import matplotlib.pyplot as plt  # import time: matplotlib only when needed

        fig = fig if fig is not None else plt.figure(figsize=figsize)
        ax = fig.add_subplot(*(subplot if isinstance(subplot, tuple) else (subplot,)), projection="3d")
    check_ax(ax)
    ax.view_init(elev=view[0], azim=view[1])
    if title:
        ax.set_title(title)
    if global_frame:
        draw_frame(ax, [0, 0, 0], np.eye(3), size=global_frame, names=("X", "Y", "Z"), colors=("k", "k", "k"))
    return ax


def joint_figure(mech, q, vectors=(), *, title=None, view=(24, -60), frame_size=0.45, figsize=(7.6, 6.0), zoom=1.15,
                 ax=None):
    """A joint between bodies as §14.4 draws it: the bodies with their point labels, each body's frame, and the
    vectors the constraint speaks of.

    Parameters
    ----------
    mech : Mechanism
    q : array_like, shape (n,)
    vectors : sequence of (origin, vector, label, color) or (origin, vector, label, color, options)
        Drawn with :func:`draw_vector` (options: its keyword arguments, e.g. ``label_offset``).
    title : str, optional
    view : (float, float)
        Elevation and azimuth in degrees.
    frame_size : float
        Length of the body-frame arrows (0: no frames).
    figsize, zoom, ax
        As :func:`make_3d_axes` and :func:`equal_scales`.

    Returns
    -------
    Axes3D
    """
    ax = make_3d_axes(ax, figsize=figsize, view=view, title=title)
    draw(mech, q, ax=ax, labels=True)
    for b in mech.bodies if frame_size else ():
        draw_frame(ax, mech.r(q, b.name), mech.A(q, b.name), size=frame_size, label=b.name)
    for origin, vector, label, color, *options in vectors:
        draw_vector(ax, origin, vector, label, color, **(options[0] if options else {}))
    equal_scales(ax, zoom=zoom)
    return ax
