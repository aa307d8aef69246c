"""How each constraint type is drawn: drawings keyed by constraint class, with a default for types that have
none (the points the constraint names, joined), and the symbol of the quantity each driver prescribes.

A drawing is registered for a class with :func:`drawing_for` and found by :func:`drawing_class` through the
class hierarchy, so a subclass is drawn like its base unless it registers a drawing of its own::

    @drawing_for(CamFollower)
    class CamDrawing(JointDrawing):
        ...

Besides its artists, a drawing tells the scene which points of the constraint it marks: ``pins`` (drawn as
pins; on a fixed body they become supports) and ``guides`` (used by a guide or a slot), and ``span``, a
size the drawing needs beyond the bodies' points (a pitch circle).
"""

from __future__ import annotations

import math

import numpy as np

from .. import constraints as planar
from ._artists import Glyph, PinGlyph
from ._common import GROUND, RHO, SUBSCRIPTS, all_points, body_q, pt, rotate, unit_vector

__all__ = ["JointDrawing", "drawing_for", "drawing_class", "drawing_size", "driver_symbol", "symbol_for"]

_DRAWINGS = {}
_SYMBOLS = {}


def drawing_for(*classes):
    """Class decorator: draw constraints of ``classes`` (and their subclasses) with the decorated drawing."""
    def register(drawing):
        for cls in classes:
            _DRAWINGS[cls] = drawing
        return drawing

    return register


def drawing_class(constraint):
    """The drawing of a constraint: registered for its class or the nearest base, else :class:`PointsDrawing`."""
    for cls in type(constraint).__mro__:
        if cls in _DRAWINGS:
            return _DRAWINGS[cls]
    return PointsDrawing


class JointDrawing(Glyph):
    """How one constraint is drawn: artists created in ``__init__(ax, constraint, scene)`` (the scene gives
    ``mech``, the size ``L``, the bodies' ``colours`` and the ``fixed`` bodies) and moved by ``update(q)``."""

    artists = ()

    @classmethod
    def pins(cls, c):
        """(body, local point) pairs the drawing marks with a pin."""
        return []

    @classmethod
    def guides(cls, c):
        """(body, local point) pairs the drawing uses otherwise (a guide, a slot): not drawn as loose points."""
        return []

    @classmethod
    def span(cls, c):
        """A size the drawing needs around its bodies (a pitch circle's diameter)."""
        return 0.0

    def __init__(self, ax, c, scene):
        self.artists = []

    def update(self, q):
        pass


@drawing_for(planar.Simple, planar.Ground, planar.Driver, planar.RelativeAngleDriver)
class NoDrawing(JointDrawing):
    """Constraints that are not drawn: the ground is drawn as supports, drivers by the motion they give."""


@drawing_for(planar.DistanceDriver)
class AxisDriverDrawing(JointDrawing):
    """A distance driver is not drawn; its points lie on the translational joint it drives."""

    @classmethod
    def guides(cls, c):
        return [(c.bodies[0], c.s_Pi), (c.bodies[0], c.s_Qi), (c.bodies[1], c.s_Pj)]


@drawing_for(planar.Revolute)
class RevoluteDrawing(JointDrawing):
    """A small white circle at the joint point."""

    @classmethod
    def pins(cls, c):
        return [(c.bodies[0], c.s_i), (c.bodies[1], c.s_j)]

    def __init__(self, ax, c, scene):
        self.pin = PinGlyph(ax, scene.mech, c.bodies[0], c.s_i, RHO * scene.L)
        self.artists = self.pin.artists

    def observe(self, q):
        return self.pin.observe(q)

    def update(self, q):
        self.pin.update(q)


class _Guide:
    """A straight guide (rail or slot) along body ``body``'s line P→Q, long enough for what slides on it."""

    def __init__(self, mech, body, sP, sQ, margin):
        self.mech, self.body, self.sP, self.sQ = mech, body, sP, sQ
        self.margin = margin
        length = float(np.hypot(float(sQ[0]) - float(sP[0]), float(sQ[1]) - float(sP[1])))
        self.lo, self.hi = min(0.0, length), max(0.0, length)

    def frame(self, q):
        P, Q = pt(self.mech, q, self.body, self.sP), pt(self.mech, q, self.body, self.sQ)
        u = unit_vector(Q - P)
        return P, u, np.array([-u[1], u[0]])

    def cover(self, q, point):
        P, u, _ = self.frame(q)
        s = float((point - P) @ u)
        self.lo, self.hi = min(self.lo, s), max(self.hi, s)

    def ends(self, q):
        P, u, _ = self.frame(q)
        return P + (self.lo - self.margin) * u, P + (self.hi + self.margin) * u


@drawing_for(planar.Translational)
class TranslationalDrawing(JointDrawing):
    """Slider box of body j on the guide line P_i Q_i of body i (hatched when body i is the ground)."""

    @classmethod
    def guides(cls, c):
        return [(c.bodies[0], c.s_Pi), (c.bodies[0], c.s_Qi), (c.bodies[1], c.s_Pj)]

    def __init__(self, ax, c, scene):
        from matplotlib.patches import Polygon  # import time: matplotlib only when needed

        mech, L, colours, fixed = scene.mech, scene.L, scene.colours, scene.fixed
        self.mech, self.c = mech, c
        bi, bj = c.bodies
        rho = RHO * L
        self.a, self.b = 2.4 * rho, 1.4 * rho
        self.guide = _Guide(mech, bi, c.s_Pi, c.s_Qi, margin=self.a + 2 * rho)
        self.hatched = bi.name in fixed
        ci, cj = colours[bi.name], colours[bj.name]
        (self.rail,) = ax.plot([], [], "-", color=ci, lw=1.5, zorder=1)
        self.hatch = Polygon(np.zeros((4, 2)), closed=True, fill=False, hatch="////", ec=ci, lw=0.0, zorder=1)
        self.hatch.set_visible(self.hatched)
        ax.add_patch(self.hatch)
        self.box = Polygon(np.zeros((4, 2)), closed=True, fc=cj, alpha=0.45, ec=cj, lw=1.8, zorder=4)
        ax.add_patch(self.box)
        self.artists = [self.rail, self.hatch, self.box]

    def _geometry(self, q):
        Pj = pt(self.mech, q, self.c.bodies[1], self.c.s_Pj)
        P, u, n = self.guide.frame(q)
        corners = np.array([Pj + sa * self.a * u + sb * self.b * n for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
        return Pj, u, n, corners

    def observe(self, q):
        Pj, u, n, corners = self._geometry(q)
        self.guide.cover(q, Pj)
        e0, e1 = self.guide.ends(q)
        return np.concatenate([corners, [e0, e1, e0 - 2 * self.b * n]])

    def update(self, q):
        Pj, u, n, corners = self._geometry(q)
        e0, e1 = self.guide.ends(q)
        off = -self.b * n  # the rail runs under the box
        self.rail.set_data([e0[0] + off[0], e1[0] + off[0]], [e0[1] + off[1], e1[1] + off[1]])
        self.hatch.set_xy(np.array([e0 + off, e1 + off, e1 + 1.9 * off, e0 + 1.9 * off]))
        self.box.set_xy(corners)


@drawing_for(planar.RevoluteTranslational)
class RevoluteTranslationalDrawing(JointDrawing):
    """Pin P_i of body i in a slot along the line P_j Q_j of body j."""

    @classmethod
    def guides(cls, c):
        return [(c.bodies[0], c.s_Pi), (c.bodies[1], c.s_Pj), (c.bodies[1], c.s_Qj)]

    def __init__(self, ax, c, scene):
        from matplotlib.patches import Polygon  # import time: matplotlib only when needed

        mech, L, colours, fixed = scene.mech, scene.L, scene.colours, scene.fixed
        self.mech, self.c = mech, c
        bi, bj = c.bodies
        rho = RHO * L
        self.w = 1.25 * rho
        self.guide = _Guide(mech, bj, c.s_Pj, c.s_Qj, margin=3 * rho)
        cj = GROUND if bj.name in fixed else colours[bj.name]
        self.slot = Polygon(np.zeros((4, 2)), closed=True, fc="#f2f2f2", ec=cj, lw=1.5, zorder=1)
        ax.add_patch(self.slot)
        self.pin = PinGlyph(ax, mech, bi, c.s_Pi, rho, zorder=5)
        self.artists = [self.slot] + self.pin.artists

    def observe(self, q):
        p = self.pin.position(q)
        self.guide.cover(q, p)
        e0, e1 = self.guide.ends(q)
        return np.array([p, e0, e1])

    def update(self, q):
        P, u, n = self.guide.frame(q)
        e0, e1 = self.guide.ends(q)
        w = self.w * n
        self.slot.set_xy(np.array([e0 - w, e1 - w, e1 + w, e0 + w]))
        self.pin.update(q)


class PointsDrawing(JointDrawing):
    """The drawing of a type with no drawing of its own: the points it names (its declared ``points``), joined
    by a line, each with a pin."""

    @classmethod
    def pins(cls, c):
        return [(c.bodies[c.roles.index(role)], getattr(c, key)) for key, role in c.points.items()]

    def __init__(self, ax, c, scene):
        self.mech, self.c = scene.mech, c
        rho = RHO * scene.L
        (self.line,) = ax.plot([], [], "-", color="#444444", lw=2.2, zorder=3, solid_capstyle="round")
        self.pin_glyphs = [PinGlyph(ax, scene.mech, body, s, rho) for body, s in self.pins(c)]
        self.artists = [self.line] + [a for p in self.pin_glyphs for a in p.artists]

    def observe(self, q):
        return np.array([p.position(q) for p in self.pin_glyphs]).reshape(-1, 2)

    def update(self, q):
        pts = self.observe(q)
        self.line.set_data(pts[:, 0], pts[:, 1])
        for p in self.pin_glyphs:
            p.update(q)


@drawing_for(planar.RevoluteRevolute)
class LinkDrawing(PointsDrawing):
    """Revolute-revolute joint: the massless link between P_i and P_j, with a pin at each end."""

    @classmethod
    def pins(cls, c):
        return [(c.bodies[0], c.s_i), (c.bodies[1], c.s_j)]


class _WheelGlyph(Glyph):
    """A dashed pitch circle of radius |ρ| about a body's reference point, with a spoke along its ξ axis."""

    def __init__(self, ax, mech, body, radius, colour):
        from matplotlib.patches import Circle  # import time: matplotlib only when needed

        self.mech, self.body, self.r = mech, body, abs(float(radius))
        self.circle = Circle((0, 0), self.r, fill=False, ec=colour, lw=1.5, ls="--", zorder=2)
        ax.add_patch(self.circle)
        (self.spoke,) = ax.plot([], [], "-", color=colour, lw=1.5, zorder=2)
        (self.hub,) = ax.plot([], [], "o", color=colour, ms=3, zorder=2)
        self.artists = [self.circle, self.spoke, self.hub]

    def observe(self, q):
        x, y, _ = body_q(self.mech, q, self.body.name)
        return np.array([[x - self.r, y - self.r], [x + self.r, y + self.r]])

    def update(self, q):
        x, y, phi = body_q(self.mech, q, self.body.name)
        self.circle.center = (x, y)
        tip = np.array([x, y]) + rotate(phi, np.array([self.r, 0.0]))
        self.spoke.set_data([x, tip[0]], [y, tip[1]])
        self.hub.set_data([x], [y])


@drawing_for(planar.Gear)
class GearDrawing(JointDrawing):
    """Gears i and j: their dashed pitch circles, each with a spoke that shows its rotation."""

    @classmethod
    def span(cls, c):
        return 2 * max(abs(float(c.radius_i)), abs(float(c.radius_j)))

    def __init__(self, ax, c, scene):
        self.wheels = [_WheelGlyph(ax, scene.mech, body, radius, scene.colours[body.name])
                       for body, radius in zip(c.bodies[:2], (c.radius_i, c.radius_j))]
        self.artists = [a for w in self.wheels for a in w.artists]

    def observe(self, q):
        return np.concatenate([w.observe(q) for w in self.wheels])

    def update(self, q):
        for w in self.wheels:
            w.update(q)


@drawing_for(planar.RackPinion)
class RackDrawing(JointDrawing):
    """Pinion i (pitch circle) on rack j: the rack's pitch line at y_i − ρ, with teeth marks that move with x_j."""

    @classmethod
    def span(cls, c):
        return 2 * abs(float(c.radius))

    def __init__(self, ax, c, scene):
        mech, colours = scene.mech, scene.colours
        self.mech, self.c = mech, c
        bi, bj = c.bodies
        self.r = abs(float(c.radius))
        self.wheel = _WheelGlyph(ax, mech, bi, self.r, colours[bi.name])
        (self.line,) = ax.plot([], [], "-", color=colours[bj.name], lw=2.0, zorder=2)
        (self.teeth,) = ax.plot([], [], "-", color=colours[bj.name], lw=1.0, zorder=2)
        self.pitch = max(self.r * 0.5, 1e-6)
        self.lo, self.hi = np.inf, -np.inf
        self.artists = self.wheel.artists + [self.line, self.teeth]

    def observe(self, q):
        x, y, _ = body_q(self.mech, q, self.c.bodies[0].name)
        self.lo, self.hi = min(self.lo, x - 2.5 * self.r), max(self.hi, x + 2.5 * self.r)
        return np.concatenate([self.wheel.observe(q), [[self.lo, y - 1.4 * self.r], [self.hi, y - self.r]]])

    def update(self, q):
        self.wheel.update(q)
        x, y, _ = body_q(self.mech, q, self.c.bodies[0].name)
        xj = body_q(self.mech, q, self.c.bodies[1].name)[0]
        lo, hi = (self.lo, self.hi) if np.isfinite(self.lo) else (x - 2.5 * self.r, x + 2.5 * self.r)
        yl = y - self.r
        self.line.set_data([lo, hi], [yl, yl])
        k0, k1 = math.ceil((lo - xj) / self.pitch), math.floor((hi - xj) / self.pitch)
        xs = xj + self.pitch * np.arange(k0, k1 + 1)
        tx = np.column_stack([xs, xs, np.full_like(xs, np.nan)]).ravel()
        ty = np.column_stack([np.full_like(xs, yl), np.full_like(xs, yl - 0.3 * self.r),
                              np.full_like(xs, np.nan)]).ravel()
        self.teeth.set_data(tx, ty)


# ============================================================================================== driver symbols
def symbol_for(*classes):
    """Decorator: ``f(mech, driver) -> (unicode, mathtext)``, the quantity drivers of ``classes`` prescribe."""
    def register(f):
        for cls in classes:
            _SYMBOLS[cls] = f
        return f

    return register


def _sub(k):
    return str(k).translate(SUBSCRIPTS)


@symbol_for(planar.Driver)
def _coordinate_symbol(mech, driver):
    k = driver.bodies[0].number
    base = {"phi": ("φ", r"\varphi"), "x": ("x", "x"), "y": ("y", "y")}[driver.coordinate]
    return f"{base[0]}{_sub(k)}", rf"${base[1]}_{{{k}}}$"


@symbol_for(planar.RelativeAngleDriver)
def _relative_symbol(mech, driver):
    i, j = (b.number for b in driver.bodies)
    return f"φ{_sub(j)} − φ{_sub(i)}", rf"$\varphi_{{{j}}} - \varphi_{{{i}}}$"


def driver_symbol(mech, driver, unicode=False):
    """The quantity a driver prescribes, as the book writes it (mathtext, or plain Unicode for widgets): φ₂,
    φ₃ − φ₂, d₂₃ (a distance), θ₂₃ (another angle)."""
    for cls in type(driver).__mro__:
        if cls in _SYMBOLS:
            u, tex = _SYMBOLS[cls](mech, driver)
            break
    else:
        nums = "".join(str(b.number) for b in driver.bodies)
        angle = (driver.measures or (None,))[-1] == "angle"
        u = ("θ" if angle else "d") + _sub(nums)
        tex = (r"$\theta" if angle else "$d") + f"_{{{nums}}}$"
    return u if unicode else tex


def drawing_size(mech, qs):
    """A length scale of the drawing: the largest side of the bounding box of the points over ``qs``, or of
    what a joint drawing adds around its bodies (a pitch circle)."""
    pts = np.concatenate([all_points(mech, q) for q in qs])
    span = float(np.max(np.ptp(pts, axis=0))) if len(pts) > 1 else 0.0
    for c in mech.constraints:
        span = max(span, drawing_class(c).span(c))
    return span if span > 1e-9 else 1.0
