"""3D drawings and animations of spatial mechanisms with matplotlib (textbook §14.5).

Each body is drawn as the polyline through its named points (in the order they were declared), with a
marker at every point; a body with a :class:`~kinbook.spatial.Ground` constraint is drawn dashed and grey.
Optionally each body's local axes ξ, η, ζ are drawn at its origin (red, green, blue).

:func:`draw_vector` and :func:`draw_frame` add a single arrow (s_i, d, r_i …) or a frame (the axes of a rotation
matrix A at a point) to any 3D axes, e.g. on top of a :func:`draw` (textbook §14.1, §14.4).

In a notebook::

    result = mech.simulate(np.linspace(0, 1, 61))
    animation_png(result)           # an animated PNG: plays in every notebook front end, trusted or not
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError

__all__ = ["Drawing", "draw", "animate", "animation_png", "equal_scales", "make_3d_axes", "joint_figure", "DrawnVector", "DrawnFrame", "draw_vector",
           "draw_frame"]

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
    return set(mech.fixed_bodies())


def _check_single(mech, q):
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
    _check_ax(ax)
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    ax.set_box_aspect(tuple(spans / spans.max()), zoom=zoom)


def _limits(ax, points, margin=0.1):
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
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(4))


def draw(mech, q, ax=None, frames=False, frame_size=None, labels=False, limits=None, figsize=None, dpi=None):
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
    import matplotlib.pyplot as plt

    q = _check_single(mech, q)
    if ax is None:
        fig = plt.figure(figsize=figsize, dpi=dpi)
        ax = fig.add_subplot(projection="3d")
    else:
        _check_ax(ax)
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
    if not ax.get_title():  # an axes titled by the caller (make_3d_axes, joint_figure) keeps its title
        ax.set_title(mech.title)
    return drawing


def animate(result, ax=None, frames=False, every=1, interval=40, max_frames=None, figsize=None, dpi=None,
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
    from matplotlib.animation import FuncAnimation

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
    import matplotlib.pyplot as plt

    from ..core._animation import Animation

    if kwargs.get("ax") is None:
        kwargs.setdefault("figsize", (5.6, 4.6))
        kwargs.setdefault("dpi", 72)
    kwargs.setdefault("max_frames", 60)
    anim = animate(result, **kwargs)
    anim.drawing.ax.figure.subplots_adjust(left=0, right=1, bottom=0, top=0.93)
    plt.close(anim.drawing.ax.figure)
    return Animation(anim, colors)


# ------------------------------------------------------------------------------------------- vectors and frames
def _check_ax(ax):
    if getattr(ax, "name", "") != "3d":
        raise InputError(f"`ax` must be a 3D axes: fig.add_subplot(projection='3d'), got {type(ax).__name__}")


def _point3(v, name):
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


def _arrow_class():
    """The arrow patch class, built on first use so that importing kinbook.spatial does not import matplotlib.

    An arrow is a :class:`matplotlib.patches.FancyArrowPatch` between two 3D points, drawn with a flat arrowhead
    facing the viewer; ``get_data_3d()`` returns its start and end (shape (2, 3)), ``set_data_3d(start, end)``
    moves it.
    """
    if _ARROW_CLASS:
        return _ARROW_CLASS[0]
    from matplotlib.patches import FancyArrowPatch
    from mpl_toolkits.mplot3d import proj3d

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


def _include(ax, points, had_data):
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
    _check_ax(ax)
    origin = _point3(origin, "origin")
    vector = _point3(vector, "vector")
    offset = np.zeros(3) if label_offset is None else _point3(label_offset, "label_offset")
    if color is None:
        color = ax._get_lines.get_next_color()
    had_data = ax.has_data()
    arrow = _arrow_class()(origin, origin + vector, color=color, linewidth=linewidth, **arrow_kwargs)
    ax.add_artist(arrow)
    _include(ax, [origin, origin + vector], had_data)
    text = None
    if label is not None:
        text = ax.text(*(origin + float(label_at) * vector + offset), label, color=color, fontsize=fontsize)
    return DrawnVector(arrow, text, origin, vector)


def draw_frame(ax, origin, A, size=1.0, label=None, names=(r"\xi", r"\eta", r"\zeta"), colors=_FRAME_COLOURS,
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
    from .rotations import check_rotation

    _check_ax(ax)
    origin = _point3(origin, "origin")
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
    had_data = ax.has_data()
    arrow_cls = _arrow_class()
    tips = origin + size * A.T  # row k: tip of axis k
    axes = []
    for tip, colour in zip(tips, colors):
        arrow = arrow_cls(origin, tip, color=colour, linewidth=linewidth, mutation_scale=10)
        ax.add_artist(arrow)
        axes.append(arrow)
    _include(ax, np.vstack([origin, tips]), had_data)
    labels = []
    if axis_labels:
        sub = "" if label is None else f"_{{{label}}}"
        labels = [ax.text(*(origin + 1.12 * (tip - origin)), f"${name}{sub}$", color=colour, fontsize=fontsize,
                          ha="center", va="center")
                  for name, tip, colour in zip(names, tips, colors)]
    return DrawnFrame(axes, labels, origin, A, size)


# ------------------------------------------------------------------------------------------------- layout
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
        import matplotlib.pyplot as plt

        fig = fig if fig is not None else plt.figure(figsize=figsize)
        ax = fig.add_subplot(*(subplot if isinstance(subplot, tuple) else (subplot,)), projection="3d")
    _check_ax(ax)
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
