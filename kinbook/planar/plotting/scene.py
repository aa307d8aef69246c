"""Drawings of a planar mechanism in one configuration: the scene (bodies, the ground's supports, joints,
frames, vectors and point names, all moved together) and the public :func:`draw`, :func:`draw_frame` and
:func:`draw_point_vectors`."""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from ._artists import BodyFrame, BodyGlyph, FrameGlyph, GlobalFrame, GroundGlyph, PointLabels, VectorGlyph
from ._common import COLOURS, GROUND, fit_figure, new_axes, set_axes_limits, style_axes
from .joints import drawing_class, drawing_size

__all__ = ["draw", "draw_frame", "draw_point_vectors"]


class Scene:
    """Every glyph of a mechanism drawing; :meth:`update` moves them all to a new q."""

    def __init__(self, ax, mech, q, *, frames=False, labels=True, joints=True, vectors=None, size=None,
                 projections=False):
        self.ax, self.mech = ax, mech
        q = np.asarray(mech.check_q(q), dtype=float)
        if q.ndim != 1:
            raise InputError(f"`q` must have shape ({mech.n},) for one configuration, got {q.shape}")
        L = float(size) if size else drawing_size(mech, [q])
        self.L = L
        fixed = set(mech.fixed_bodies())
        self.fixed = fixed
        colours, k = {}, 0
        for b in mech.bodies:
            if b.name in fixed:
                colours[b.name] = GROUND
            else:
                colours[b.name] = COLOURS[k % len(COLOURS)]
                k += 1
        self.colours = colours
        glyphs = []
        drawings = [(c, drawing_class(c)) for c in mech.constraints]
        # ground supports: fixed-body points where joints put pins
        for b in mech.bodies:
            if b.name not in fixed:
                continue
            supports, used = [], set()
            for c, drawing in drawings:
                supports += [tuple(float(v) for v in s) for body, s in drawing.pins(c) if body is b]
                used |= {tuple(float(v) for v in s) for _, s in drawing.guides(c)}
            supports = list(dict.fromkeys(supports))
            others = [tuple(float(v) for v in s) for s in b.points.values()]
            others = [s for s in dict.fromkeys(others) if s not in supports and s not in used]
            glyphs.append(GroundGlyph(ax, mech, b, L, labels, supports, others))
        for b in mech.bodies:
            if b.name not in fixed:
                glyphs.append(BodyGlyph(ax, mech, b, colours[b.name], L, labels))
        if joints:
            glyphs += [drawing(ax, c, self) for c, drawing in drawings]
        if frames:
            for b in mech.bodies:
                glyphs.append(BodyFrame(ax, mech, b, 0.12 * L))
        if vectors:
            glyphs.append(GlobalFrame(ax, 0.15 * L))
            for body, point in vectors:
                glyphs.append(VectorGlyph(ax, mech, body, point, L, projections=projections))
        if labels:
            glyphs.append(PointLabels(ax, mech, q, L, fixed))
        self.glyphs = glyphs
        self.q = q

    @property
    def artists(self):
        return [a for g in self.glyphs for a in g.artists]

    def observe(self, qs):
        """Bounding box (xmin, xmax, ymin, ymax) of the drawing over the configurations ``qs``."""
        pts = [g.observe(q) for q in qs for g in self.glyphs]
        pts = np.concatenate([p for p in pts if len(p)])
        return pts[:, 0].min(), pts[:, 0].max(), pts[:, 1].min(), pts[:, 1].max()

    def set_limits(self, box, margin=0.1):
        set_axes_limits(self.ax, box, margin)

    def update(self, q):
        for g in self.glyphs:
            g.update(q)
        return self.artists


def draw(mech, q, ax=None, *, frames=False, labels=True, joints=True, vectors=None, title=None,
         projections=False):
    """Draw a mechanism in one configuration.

    Parameters
    ----------
    mech : Mechanism
    q : array_like, shape (n,)
        Body coordinates [x1, y1, φ1, x2, …], e.g. from ``mech.solve_position(t)``.
    ax : matplotlib Axes, optional
        Where to draw; a new figure is created when omitted.
    frames : bool
        Draw each body's local ξ-η frame at its reference point O_i.
    labels : bool
        Write body numbers (in circles) and point names.
    joints : bool
        Draw the joints (revolute circles, slider boxes, links, slots, pitch circles).
    vectors : list of (body, point), optional
        For each, draw r_i, s_i^P and r_i^P with the global frame at the origin (the book's Fig. 13.18).
    title : str, optional
    projections : bool
        With ``vectors``: also the projections of P on the local and on the (translated) global axes
        (Fig. 13.20).

    Returns
    -------
    matplotlib.axes.Axes

    Notes
    -----
    Textbook §13.5. Equal aspect; the limits cover the drawing with a 10 % margin.
    """
    fit = ax is None
    ax = new_axes(ax)
    scene = Scene(ax, mech, q, frames=frames, labels=labels, joints=joints, vectors=vectors,
                   projections=projections)
    box = scene.observe([scene.q])  # first: it sizes the guides
    scene.update(scene.q)
    style_axes(ax, title if title is not None else getattr(mech, "title", None))
    if fit:
        fit_figure(ax, box)
    scene.set_limits(box)
    return ax


def draw_frame(ax, r, phi, label=None, *, axes=("ξ", "η"), length=1.0, color="k"):
    """Draw a reference frame: two arrows along its rotated axes from origin ``r``.

    Parameters
    ----------
    ax : matplotlib Axes
    r : array_like, shape (2,)
        Global position of the frame's origin.
    phi : float
        Angle of the frame, radians.
    label : str, optional
        Name of the origin, e.g. ``"O_2"`` (written in math: O₂).
    axes : (str, str)
        Names of the axes: ``("ξ_2", "η_2")`` for a body frame, ``("x", "y")`` for the global frame.
    length : float
        Length of the arrows, in data units.
    color : colour

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> ax = Figure().add_subplot()
    >>> arrows_and_names = draw_frame(ax, (0, 0), 0.0, label="O", axes=("x", "y"))
    >>> [a.get_text() for a in arrows_and_names[2:]]
    ['x', 'y', 'O']
    """
    g = FrameGlyph(ax, length, label=label, axes=axes, color=color)
    r = np.asarray(r, dtype=float)
    g.place(r, float(phi))
    ax.update_datalim(g.extent(r, float(phi)))
    ax.autoscale_view()
    return g.artists


def draw_point_vectors(ax, mech, q, body, point, *, projections=False, origin=(0.0, 0.0)):
    """Draw r_i (origin → O_i), s_i^P (O_i → P) and r_i^P (origin → P) of a body point.

    Parameters
    ----------
    ax : matplotlib Axes
    mech : Mechanism
    q : array_like, shape (n,)
    body : str
        Body name.
    point : str or (ξ, η)
        Point name or local coordinates.
    projections : bool
        Also draw the projections of P on the local axes ξ_i, η_i and on the global axes translated to O_i,
        with their names ξ_i^P, η_i^P, x_i^P, y_i^P (Fig. 13.20; eq. 3 reads them off).
    origin : array_like, shape (2,)
        Origin of the global frame.

    Returns
    -------
    list of matplotlib artists

    Notes
    -----
    Textbook §13.5, Fig. 13.18 and eq. 5: r_i^P = r_i + A_i s'_i^P.
    """
    q = np.asarray(mech.check_q(q), dtype=float)
    L = drawing_size(mech, [q])
    g = VectorGlyph(ax, mech, body, point, L, origin=origin, projections=projections)
    g.update(q)
    ax.update_datalim(g.observe(q))
    ax.autoscale_view()
    return g.artists
