"""Drawings, plots and animations of planar mechanisms (textbook chapter 13).

The textbook is printed without its figures; these drawings replace them. Everything here uses matplotlib
only, imports it lazily, and changes no global pyplot state beyond creating figures::

    from kinbook.planar import plotting
    ax = plotting.draw(mech, q, frames=True, vectors=[("crank", "A")])

Conventions of the drawings
---------------------------
* A body with two points is a thick line between them; with more points, a translucent convex polygon; the
  ground (a body fixed by a ``ground`` constraint or by three simple constraints) is drawn as hatched
  supports at its joint points.
* Revolute joints are small white circles, translational joints a slider box on its guide, revolute-revolute
  joints the (massless) link between their two points, revolute-translational joints a pin in a slot, gears
  and pinions their dashed pitch circles with a spoke that shows their rotation.
* Bodies carry the book's numbers ("1", "2", …: the subscript of x_i, y_i, φ_i) in a circle; points carry
  their names (``OA`` is written O_A).

Every drawing is made of artists that are created once and then moved, so :func:`animate` only updates data.

In notebooks
------------
:func:`animation_html` and the still figure of :func:`explorer` render themselves (the figures are closed so
they are not shown twice). :func:`explorer` returns a live ipywidgets slider when a kernel is running — also
under nbval, whose stored output would then be a widget model; a notebook checked by nbval should call
``explorer(mech, static=True)`` (or tag the cell ``nbval-ignore-output``).
"""

from __future__ import annotations

import math
import re

import numpy as np

from .._animation import AnimationHTML
from ..errors import InputError, KinbookError

__all__ = [
    "draw",
    "draw_frame",
    "draw_point_vectors",
    "plot_trajectories",
    "plot_history",
    "animate",
    "animation_html",
    "explorer",
]

MAX_FRAMES = 120
"""Default cap on the number of frames of an animation."""

_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#bcbd22")
_GROUND = "#555555"
_TRACES = ("#6a3d9a", "#b15928", "#000000", "#e7298a")
_RHO = 0.025
"""Radius of the joint circles, as a fraction of the drawing's size."""
_GREEK = {"ξ": r"\xi", "η": r"\eta", "φ": r"\varphi", "Φ": r"\Phi"}
_SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


# ============================================================================================== small helpers
def _plt():
    import matplotlib.pyplot as plt

    return plt


def _new_axes(ax, figsize=(6.4, 4.8)):
    if ax is not None:
        return ax
    _, ax = _plt().subplots(figsize=figsize)
    return ax


def _math(text):
    """'ξ_2' → '$\\xi_{2}$'; plain words and text already in $…$ pass through."""
    text = str(text)
    if text.startswith("$") or not (set(text) & set(_GREEK) or "_" in text or "^" in text):
        return text
    out = text
    for g, tex in _GREEK.items():
        out = out.replace(g, tex + " ")
    out = re.sub(r"_([^_^{}\s$]+)", r"_{\1}", out)
    out = re.sub(r"\^([^_^{}\s$]+)", r"^{\1}", out)
    return f"${out.replace(' _', '_').replace(' ^', '^').strip()}$"


def _point_text(name):
    """Point names as the book writes them: 'OA' → O_A (reference points O_i), others unchanged."""
    m = re.fullmatch(r"O([A-Za-z0-9]+)", str(name))
    return rf"$O_{{{m.group(1)}}}$" if m else str(name)


def _rotate(phi, v):
    c, s = math.cos(phi), math.sin(phi)
    v = np.asarray(v, dtype=float)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


def _unit(v):
    v = np.asarray(v, dtype=float)
    n = float(np.hypot(*v))
    return v / n if n > 0 else np.array([1.0, 0.0])


def _body_q(mech, q, body):
    k = 3 * (mech.body(body).number - 1)
    return q[k : k + 3]


def _convex_hull(points):
    """Indices of the convex hull of 2-D points, counter-clockwise (Andrew's monotone chain)."""
    order = sorted(range(len(points)), key=lambda k: (points[k][0], points[k][1]))

    def half(idx):
        h = []
        for k in idx:
            while len(h) >= 2:
                (ax_, ay), (bx, by), (cx, cy) = points[h[-2]], points[h[-1]], points[k]
                if (bx - ax_) * (cy - ay) - (by - ay) * (cx - ax_) > 1e-12:
                    break
                h.pop()
            h.append(k)
        return h

    lower, upper = half(order), half(order[::-1])
    return lower[:-1] + upper[:-1]


def _fixed_bodies(mech):
    """Names of the bodies fixed to the ground: a ``ground`` constraint or simple constraints on x, y and φ."""
    fixed, simple = set(), {}
    for c in mech.constraints:
        if c.type_name == "ground":
            fixed.add(c.bodies[0].name)
        elif c.type_name == "simple":
            simple.setdefault(c.bodies[0].name, set()).add(c.coordinate)
    fixed |= {b for b, coords in simple.items() if coords >= {"x", "y", "phi"}}
    return fixed


def _all_points(mech, q):
    """Global positions of every body point and reference point at q, shape (k, 2)."""
    out = []
    for b in mech.bodies:
        x, y, phi = _body_q(mech, q, b.name)
        out.append([[x, y]])
        if b.points:
            s = np.array([[float(v) for v in p] for p in b.points.values()])
            out.append(np.array([x, y]) + _rotate(phi, s))
    return np.concatenate([np.asarray(o, dtype=float) for o in out])


def _size(mech, qs):
    """A length scale of the drawing: the largest side of the bounding box of the points over ``qs``."""
    pts = np.concatenate([_all_points(mech, q) for q in qs])
    span = float(np.max(np.ptp(pts, axis=0))) if len(pts) > 1 else 0.0
    for c in mech.constraints:
        for attr in ("radius_i", "radius_j", "radius"):
            if hasattr(c, attr):
                span = max(span, 2 * abs(float(getattr(c, attr))))
    return span if span > 1e-9 else 1.0


def _coordinate_label(mech, name, derivative=0):
    """'phi3' → φ₃ in mathtext, with dots for derivatives."""
    if isinstance(name, tuple):
        body, coord = name
        number = mech.body(body).number
    else:
        m = re.fullmatch(r"(x|y|phi)(\d+)", str(name))
        if not m:
            raise InputError(f"coordinate names look like 'x2', 'y2' or 'phi3', got {name!r}")
        coord, number = m.group(1), int(m.group(2))
    base = r"\varphi" if coord == "phi" else coord
    base = (base, rf"\dot{{{base}}}", rf"\ddot{{{base}}}")[derivative]
    return rf"${base}_{{{number}}}$"


def _point_label(mech, body, point, component, derivative=0):
    base = (component, rf"\dot{{{component}}}", rf"\ddot{{{component}}}")[derivative]
    name = point if isinstance(point, str) else "P"
    sup = _point_text(name).strip("$")
    return rf"${base}_{{{mech.body(body).number}}}^{{{sup}}}$"


def _driver_symbol(mech, driver, unicode=False):
    """The quantity a driver prescribes, as the book writes it (mathtext, or plain Unicode for widgets)."""
    tn = driver.type_name
    nums = [b.number for b in driver.bodies]
    if tn == "driver":
        base = {"phi": ("φ", r"\varphi"), "x": ("x", "x"), "y": ("y", "y")}[driver.coordinate]
        u, tex = f"{base[0]}{str(nums[0]).translate(_SUBSCRIPTS)}", rf"${base[1]}_{{{nums[0]}}}$"
    elif tn == "relative-driver":
        i, j = nums
        u = f"φ{str(j).translate(_SUBSCRIPTS)} − φ{str(i).translate(_SUBSCRIPTS)}"
        tex = rf"$\varphi_{{{j}}} - \varphi_{{{i}}}$"
    else:
        i, j = nums
        u, tex = f"d{str(i).translate(_SUBSCRIPTS)}{str(j).translate(_SUBSCRIPTS)}", rf"$d_{{{i}{j}}}$"
    return u if unicode else tex


# ============================================================================================== glyphs
class _Glyph:
    """A piece of a drawing: artists created once, moved by :meth:`update`."""

    artists: list

    def observe(self, q):
        """Points (k, 2) this glyph covers at q (for the axes limits); may also widen guide lines."""
        return np.zeros((0, 2))

    def update(self, q):
        raise NotImplementedError


class _FrameGlyph(_Glyph):
    """A reference frame: two arrows along the rotated axes, axis names at their tips, an origin label."""

    def __init__(self, ax, length, label=None, axes=("ξ", "η"), color="k", lw=1.3, zorder=6, fontsize=10):
        from matplotlib.patches import FancyArrowPatch

        self.length = float(length)
        style = dict(arrowstyle="-|>", mutation_scale=12, color=color, lw=lw, zorder=zorder, shrinkA=0, shrinkB=0)
        self.arrows = [FancyArrowPatch((0, 0), (1, 0), **style), FancyArrowPatch((0, 0), (0, 1), **style)]
        for a in self.arrows:
            ax.add_patch(a)
        kw = dict(color=color, fontsize=fontsize, zorder=zorder, ha="center", va="center")
        self.names = [ax.text(0, 0, _math(a), **kw) for a in axes]
        self.origin = ax.text(0, 0, _math(label), color=color, fontsize=fontsize, zorder=zorder,
                              ha="right", va="top") if label else None
        self.artists = self.arrows + self.names + ([self.origin] if self.origin else [])

    def place(self, r, phi):
        r = np.asarray(r, dtype=float)
        e = _rotate(phi, np.eye(2)) * self.length
        for a, n, d in zip(self.arrows, self.names, e):
            a.set_positions(tuple(r), tuple(r + d))
            n.set_position(tuple(r + 1.15 * d))
        if self.origin is not None:
            self.origin.set_position(tuple(r - 0.12 * e[0] + 0.22 * e[1]))

    def extent(self, r, phi):
        e = _rotate(phi, np.eye(2)) * self.length * 1.25
        return np.array([r, r + e[0], r + e[1]])


class _BodyFrame(_Glyph):
    def __init__(self, ax, mech, body, length):
        self.mech, self.body = mech, body
        n = body.number
        self.frame = _FrameGlyph(ax, length, label=f"O_{n}", axes=(f"ξ_{n}", f"η_{n}"), color="#333333",
                                 lw=1.0, fontsize=9)
        self.artists = self.frame.artists

    def observe(self, q):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        return self.frame.extent((x, y), phi)

    def update(self, q):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        self.frame.place((x, y), phi)


class _BodyGlyph(_Glyph):
    """A moving body: a line (two points), a convex polygon (three or more), a dot (one) and its number."""

    def __init__(self, ax, mech, body, colour, L, labels):
        from matplotlib.patches import Polygon

        self.mech, self.body, self.L = mech, body, L
        local = []
        for p in body.points.values():
            v = (float(p[0]), float(p[1]))
            if not any(abs(v[0] - w[0]) + abs(v[1] - w[1]) < 1e-9 for w in local):
                local.append(v)
        self.local = np.array(local, dtype=float).reshape(-1, 2)
        k = len(local)
        self.kind = "dot" if k <= 1 else "line"
        self.normal = np.array([0.0, 1.0])
        self.artists = []
        if k >= 3:
            hull = _convex_hull(local)
            if len(hull) >= 3:
                self.kind = "polygon"
                self.outline = self.local[hull]
                self.patch = Polygon(self.outline, closed=True, facecolor=colour, alpha=0.28,
                                     edgecolor=colour, lw=2.0, zorder=2)
                ax.add_patch(self.patch)
                self.artists.append(self.patch)
        if self.kind == "line":
            d = self.local - self.local.mean(axis=0)
            axis = np.linalg.svd(d)[2][0] if k > 2 else _unit(self.local[1] - self.local[0])
            order = np.argsort(d @ axis)
            self.outline = self.local[order]
            self.normal = np.array([-axis[1], axis[0]])
            (self.line,) = ax.plot([], [], "-", color=colour, lw=6, alpha=0.85, solid_capstyle="round", zorder=2)
            self.artists.append(self.line)
        if self.kind == "dot":
            self.outline = self.local if k else np.zeros((1, 2))
            (self.line,) = ax.plot([], [], "s", color=colour, ms=7, alpha=0.85, zorder=2)
            self.artists.append(self.line)
        self.number = None
        if labels:
            self.number = ax.text(0, 0, str(body.number), fontsize=9, ha="center", va="center", zorder=7,
                                  color=colour, fontweight="bold",
                                  bbox=dict(boxstyle="circle,pad=0.25", fc="white", ec=colour, lw=1.2))
            self.artists.append(self.number)

    def _global(self, q, s):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        return np.array([x, y]) + _rotate(phi, s)

    def observe(self, q):
        return self._global(q, self.outline)

    def update(self, q):
        pts = self._global(q, self.outline)
        if self.kind == "polygon":
            self.patch.set_xy(pts)
        else:
            self.line.set_data(pts[:, 0], pts[:, 1])
        if self.number is not None:
            phi = _body_q(self.mech, q, self.body.name)[2]
            centre = pts.mean(axis=0)
            if self.kind == "line":
                # mid-point of the longest segment, pushed off the line to one side
                seg = np.argmax(np.hypot(*np.diff(pts, axis=0).T))
                centre = pts[seg : seg + 2].mean(axis=0) - _rotate(phi, self.normal) * 0.06 * self.L
            elif self.kind == "dot":
                centre = centre + np.array([0.0, 0.085]) * self.L
            self.number.set_position(tuple(centre))


class _GroundGlyph(_Glyph):
    """The fixed body: a support (triangle on a hatched base) at each joint point, its number by the first."""

    def __init__(self, ax, mech, body, L, labels, support_points, other_points):
        from matplotlib.patches import Polygon

        self.mech, self.body = mech, body
        rho = _RHO * L
        self.rho = rho
        self.supports = np.array(support_points, dtype=float).reshape(-1, 2)
        self.others = np.array(other_points, dtype=float).reshape(-1, 2)
        self.tri = np.array([[0, 0], [-1.3 * rho, -2.2 * rho], [1.3 * rho, -2.2 * rho]])
        self.base = np.array([[-2.0 * rho, -2.2 * rho], [2.0 * rho, -2.2 * rho],
                              [2.0 * rho, -3.1 * rho], [-2.0 * rho, -3.1 * rho]])
        self.tris, self.bases = [], []
        self.artists = []
        for _ in self.supports:
            t = Polygon(self.tri, closed=True, fc="#dddddd", ec=_GROUND, lw=1.2, zorder=3)
            b = Polygon(self.base, closed=True, fill=False, hatch="////", ec=_GROUND, lw=0.0, zorder=3)
            (line,) = ax.plot([], [], "-", color=_GROUND, lw=1.5, zorder=3)
            ax.add_patch(t)
            ax.add_patch(b)
            self.tris.append(t)
            self.bases.append((b, line))
            self.artists += [t, b, line]
        (self.dots,) = ax.plot([], [], "o", color=_GROUND, ms=3, zorder=3)
        self.artists.append(self.dots)
        self.number = None
        if labels:
            self.number = ax.text(0, 0, str(body.number), fontsize=9, ha="center", va="center", zorder=7,
                                  color=_GROUND, fontweight="bold",
                                  bbox=dict(boxstyle="circle,pad=0.25", fc="white", ec=_GROUND, lw=1.2))
            self.artists.append(self.number)

    def _xy(self, q):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        return np.array([x, y]), phi

    def observe(self, q):
        r, phi = self._xy(q)
        pts = [r[None]]
        for s in self.supports:
            p = r + _rotate(phi, s)
            pts.append(p + _rotate(phi, self.base))
        if len(self.others):
            pts.append(r + _rotate(phi, self.others))
        return np.concatenate(pts)

    def update(self, q):
        r, phi = self._xy(q)
        for s, t, (b, line) in zip(self.supports, self.tris, self.bases):
            p = r + _rotate(phi, s)
            t.set_xy(p + _rotate(phi, self.tri))
            base = p + _rotate(phi, self.base)
            b.set_xy(base)
            line.set_data(base[:2, 0], base[:2, 1])
        if len(self.others):
            o = r + _rotate(phi, self.others)
            self.dots.set_data(o[:, 0], o[:, 1])
        if self.number is not None:
            anchor = r + _rotate(phi, self.supports[0]) if len(self.supports) else r
            self.number.set_position(tuple(anchor + _rotate(phi, np.array([0.0, -4.6]) * self.rho)))


class _PinGlyph(_Glyph):
    """A small white circle at a body point (revolute joints, pins of composite joints)."""

    def __init__(self, ax, mech, body, s, rho, zorder=5):
        from matplotlib.patches import Circle

        self.mech, self.body, self.s = mech, body, np.array([float(v) for v in s])
        self.circle = Circle((0, 0), rho, fc="white", ec="black", lw=1.5, zorder=zorder)
        ax.add_patch(self.circle)
        self.artists = [self.circle]

    def position(self, q):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        return np.array([x, y]) + _rotate(phi, self.s)

    def observe(self, q):
        return self.position(q)[None]

    def update(self, q):
        self.circle.center = tuple(self.position(q))


def _pt(mech, q, body, s):
    x, y, phi = _body_q(mech, q, body.name)
    return np.array([x, y]) + _rotate(phi, np.array([float(v) for v in s]))


class _Guide:
    """A straight guide (rail or slot) along body ``body``'s line P→Q, long enough for what slides on it."""

    def __init__(self, mech, body, sP, sQ, margin):
        self.mech, self.body, self.sP, self.sQ = mech, body, sP, sQ
        self.margin = margin
        length = float(np.hypot(float(sQ[0]) - float(sP[0]), float(sQ[1]) - float(sP[1])))
        self.lo, self.hi = min(0.0, length), max(0.0, length)

    def frame(self, q):
        P, Q = _pt(self.mech, q, self.body, self.sP), _pt(self.mech, q, self.body, self.sQ)
        u = _unit(Q - P)
        return P, u, np.array([-u[1], u[0]])

    def cover(self, q, point):
        P, u, _ = self.frame(q)
        s = float((point - P) @ u)
        self.lo, self.hi = min(self.lo, s), max(self.hi, s)

    def ends(self, q):
        P, u, _ = self.frame(q)
        return P + (self.lo - self.margin) * u, P + (self.hi + self.margin) * u


class _TranslationalGlyph(_Glyph):
    """Slider box of body j on the guide line P_i Q_i of body i (hatched when body i is the ground)."""

    def __init__(self, ax, mech, c, L, colours, fixed):
        from matplotlib.patches import Polygon

        self.mech, self.c = mech, c
        bi, bj = c.bodies
        rho = _RHO * L
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
        Pj = _pt(self.mech, q, self.c.bodies[1], self.c.s_Pj)
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


class _RevoluteTranslationalGlyph(_Glyph):
    """Pin P_i of body i in a slot along the line P_j Q_j of body j."""

    def __init__(self, ax, mech, c, L, colours, fixed):
        from matplotlib.patches import Polygon

        self.mech, self.c = mech, c
        bi, bj = c.bodies
        rho = _RHO * L
        self.w = 1.25 * rho
        self.guide = _Guide(mech, bj, c.s_Pj, c.s_Qj, margin=3 * rho)
        cj = _GROUND if bj.name in fixed else colours[bj.name]
        self.slot = Polygon(np.zeros((4, 2)), closed=True, fc="#f2f2f2", ec=cj, lw=1.5, zorder=1)
        ax.add_patch(self.slot)
        self.pin = _PinGlyph(ax, mech, bi, c.s_Pi, rho, zorder=5)
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


class _LinkGlyph(_Glyph):
    """Revolute-revolute joint: the massless link between P_i and P_j, with a pin at each end."""

    def __init__(self, ax, mech, c, L):
        self.mech, self.c = mech, c
        rho = _RHO * L
        (self.line,) = ax.plot([], [], "-", color="#444444", lw=2.2, zorder=3, solid_capstyle="round")
        self.pins = [_PinGlyph(ax, mech, c.bodies[0], c.s_i, rho), _PinGlyph(ax, mech, c.bodies[1], c.s_j, rho)]
        self.artists = [self.line] + [a for p in self.pins for a in p.artists]

    def observe(self, q):
        return np.array([p.position(q) for p in self.pins])

    def update(self, q):
        a, b = (p.position(q) for p in self.pins)
        self.line.set_data([a[0], b[0]], [a[1], b[1]])
        for p in self.pins:
            p.update(q)


class _WheelGlyph(_Glyph):
    """A dashed pitch circle of radius |ρ| about a body's reference point, with a spoke along its ξ axis."""

    def __init__(self, ax, mech, body, radius, colour):
        from matplotlib.patches import Circle

        self.mech, self.body, self.r = mech, body, abs(float(radius))
        self.circle = Circle((0, 0), self.r, fill=False, ec=colour, lw=1.5, ls="--", zorder=2)
        ax.add_patch(self.circle)
        (self.spoke,) = ax.plot([], [], "-", color=colour, lw=1.5, zorder=2)
        (self.hub,) = ax.plot([], [], "o", color=colour, ms=3, zorder=2)
        self.artists = [self.circle, self.spoke, self.hub]

    def observe(self, q):
        x, y, _ = _body_q(self.mech, q, self.body.name)
        return np.array([[x - self.r, y - self.r], [x + self.r, y + self.r]])

    def update(self, q):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        self.circle.center = (x, y)
        tip = np.array([x, y]) + _rotate(phi, np.array([self.r, 0.0]))
        self.spoke.set_data([x, tip[0]], [y, tip[1]])
        self.hub.set_data([x], [y])


class _RackGlyph(_Glyph):
    """Pinion i (pitch circle) on rack j: the rack's pitch line at y_i − ρ, with teeth marks that move with x_j."""

    def __init__(self, ax, mech, c, L, colours):
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
        x, y, _ = _body_q(self.mech, q, self.c.bodies[0].name)
        self.lo, self.hi = min(self.lo, x - 2.5 * self.r), max(self.hi, x + 2.5 * self.r)
        return np.concatenate([self.wheel.observe(q), [[self.lo, y - 1.4 * self.r], [self.hi, y - self.r]]])

    def update(self, q):
        self.wheel.update(q)
        x, y, _ = _body_q(self.mech, q, self.c.bodies[0].name)
        xj = _body_q(self.mech, q, self.c.bodies[1].name)[0]
        lo, hi = (self.lo, self.hi) if np.isfinite(self.lo) else (x - 2.5 * self.r, x + 2.5 * self.r)
        yl = y - self.r
        self.line.set_data([lo, hi], [yl, yl])
        k0, k1 = math.ceil((lo - xj) / self.pitch), math.floor((hi - xj) / self.pitch)
        xs = xj + self.pitch * np.arange(k0, k1 + 1)
        tx = np.column_stack([xs, xs, np.full_like(xs, np.nan)]).ravel()
        ty = np.column_stack([np.full_like(xs, yl), np.full_like(xs, yl - 0.3 * self.r),
                              np.full_like(xs, np.nan)]).ravel()
        self.teeth.set_data(tx, ty)


class _PointLabels(_Glyph):
    """Point names next to the points; points that coincide (joint points) are named once."""

    def __init__(self, ax, mech, q, L, fixed):
        self.mech, self.L = mech, L
        entries = []
        for b in mech.bodies:
            for name, s in b.points.items():
                entries.append((b, name, np.array([float(v) for v in s])))
        clusters = []  # [representative (body, s), names, member bodies]
        for b, name, s in entries:
            p = _pt(mech, q, b, s)
            for cl in clusters:
                if np.hypot(*(cl["p"] - p)) < 1e-6 * L:
                    if name not in cl["names"]:
                        cl["names"].append(name)
                    cl["bodies"].append(b)
                    break
            else:
                clusters.append({"p": p, "body": b, "s": s, "names": [name], "bodies": [b]})
        self.clusters = clusters
        self.fixed = fixed
        self.texts = [ax.text(*cl["p"], ", ".join(_point_text(n) for n in cl["names"]), fontsize=9, zorder=8,
                              color="#111111")
                      for cl in clusters]
        self.artists = list(self.texts)
        self.centres = {}
        for b in mech.bodies:
            if b.points:
                self.centres[b.name] = np.mean([[float(v) for v in s] for s in b.points.values()], axis=0)

    def update(self, q):
        allp = np.array([_pt(self.mech, q, cl["body"], cl["s"]) for cl in self.clusters])
        centre = allp.mean(axis=0)
        for cl, text, p in zip(self.clusters, self.texts, allp):
            d = np.zeros(2)
            for b in cl["bodies"]:
                if b.name in self.fixed:
                    continue
                c = _pt(self.mech, q, b, self.centres[b.name])
                if np.hypot(*(p - c)) > 1e-9 * self.L:
                    d += _unit(p - c)
            if all(x.name in self.fixed for x in cl["bodies"]):
                d = np.array([-1.0, 0.25])  # ground points: left of the joint, above the support below it
            if np.hypot(*d) < 1e-6:
                d = p - centre if np.hypot(*(p - centre)) > 1e-9 * self.L else np.array([1.0, 1.0])
            d = _unit(d)
            if any(x.name in self.fixed for x in cl["bodies"]):
                d = _unit(np.array([d[0] if abs(d[0]) > 0.2 else -1.0, max(d[1], 0.3)]))  # clear of the support
            text.set_position(tuple(p + 1.7 * _RHO * self.L * d))
            text.set_ha("left" if d[0] > 0.3 else ("right" if d[0] < -0.3 else "center"))
            text.set_va("bottom" if d[1] > 0.3 else ("top" if d[1] < -0.3 else "center"))


class _VectorGlyph(_Glyph):
    """r_i, s_i^P and r_i^P of one body point (Fig. 13.18), optionally with the projections of Fig. 13.20."""

    def __init__(self, ax, mech, body, point, L, origin=(0.0, 0.0), projections=False):
        from matplotlib.patches import FancyArrowPatch

        self.mech, self.body = mech, mech.body(body)
        self.s = mech.point_local(body, point)
        self.origin = np.asarray(origin, dtype=float)
        self.L = L
        n = self.body.number
        pname = _point_text(point if isinstance(point, str) else "P").strip("$")
        self.pname = pname
        spec = [("#1a5fb4", rf"$\mathbf{{r}}_{{{n}}}$"), ("#e66100", rf"$\mathbf{{s}}_{{{n}}}^{{{pname}}}$"),
                ("#26a269", rf"$\mathbf{{r}}_{{{n}}}^{{{pname}}}$")]
        self.arrows, self.labels = [], []
        for colour, tex in spec:
            a = FancyArrowPatch((0, 0), (1, 0), arrowstyle="-|>", mutation_scale=14, color=colour, lw=1.8,
                                zorder=6, shrinkA=0, shrinkB=0)
            ax.add_patch(a)
            self.arrows.append(a)
            self.labels.append(ax.text(0, 0, tex, color=colour, fontsize=11, ha="center", va="center", zorder=8))
        self.artists = self.arrows + self.labels
        self.projections = None
        if projections:
            kw = dict(color="#777777", lw=0.9, ls=":", zorder=5)
            (self.proj_lines,) = ax.plot([], [], **kw)
            (self.axes_lines,) = ax.plot([], [], color="#999999", lw=0.8, ls="--", zorder=1)
            self.proj_text = [ax.text(0, 0, "", fontsize=9, color=c, ha="center", va="center", zorder=8)
                              for c in ("#333333", "#333333", "#777777", "#777777")]
            self.projections = True
            self.artists += [self.proj_lines, self.axes_lines] + self.proj_text

    def _geometry(self, q):
        x, y, phi = _body_q(self.mech, q, self.body.name)
        r = np.array([x, y])
        return r, r + _rotate(phi, self.s), phi

    def observe(self, q):
        r, p, phi = self._geometry(q)
        return np.array([self.origin, r, p])

    def update(self, q):
        r, p, phi = self._geometry(q)
        o = self.origin
        for a, lab, (s0, s1) in zip(self.arrows, self.labels, ((o, r), (r, p), (o, p))):
            a.set_positions(tuple(s0), tuple(s1))
            d = s1 - s0
            nrm = np.array([-d[1], d[0]])
            nrm = _unit(nrm) if np.hypot(*nrm) > 0 else np.array([0.0, 1.0])
            # r_i and s_i^P on the outside of the triangle, r_i^P inside it
            side = 1.0 if lab is not self.labels[2] else -1.0
            other = p if lab is self.labels[0] else (o if lab is self.labels[1] else r)
            if (other - (s0 + s1) / 2) @ nrm > 0:
                nrm = -nrm
            lab.set_position(tuple((s0 + s1) / 2 + side * nrm * 0.06 * self.L))
        if self.projections:
            e_xi, e_eta = _rotate(phi, np.eye(2))
            s = p - r
            f_xi, f_eta = r + (s @ e_xi) * e_xi, r + (s @ e_eta) * e_eta
            f_x, f_y = r + np.array([s[0], 0.0]), r + np.array([0.0, s[1]])
            segs = [(p, f_xi), (p, f_eta), (p, f_x), (p, f_y)]
            xs, ys = [], []
            for a, b in segs:
                xs += [a[0], b[0], np.nan]
                ys += [a[1], b[1], np.nan]
            self.proj_lines.set_data(xs, ys)
            ext = 1.25 * max(np.hypot(*s), 1e-9)
            ax_x = [r[0], r[0] + ext, np.nan, r[0], r[0]]
            ax_y = [r[1], r[1], np.nan, r[1], r[1] + ext]
            self.axes_lines.set_data(ax_x, ax_y)
            n = self.body.number
            P = self.pname
            names = [rf"$\xi_{{{n}}}^{{{P}}}$", rf"$\eta_{{{n}}}^{{{P}}}$", rf"$x_{{{n}}}^{{{P}}}$", rf"$y_{{{n}}}^{{{P}}}$"]
            off = 0.035 * self.L
            for t, name, foot, toward in zip(self.proj_text, names, (f_xi, f_eta, f_x, f_y),
                                             (-e_eta, -e_xi, np.array([0, -1.0]), np.array([-1.0, 0]))):
                t.set_text(name)
                t.set_position(tuple(foot + off * toward))


# ============================================================================================== the scene
class _Scene:
    """Every glyph of a mechanism drawing; :meth:`update` moves them all to a new q."""

    def __init__(self, ax, mech, q, *, frames=False, labels=True, joints=True, vectors=None, size=None,
                 projections=False):
        self.ax, self.mech = ax, mech
        q = np.asarray(mech._check_q(q), dtype=float)
        if q.ndim != 1:
            raise InputError(f"`q` must have shape ({mech.n},) for one configuration, got {q.shape}")
        L = float(size) if size else _size(mech, [q])
        self.L = L
        rho = _RHO * L
        fixed = _fixed_bodies(mech)
        colours, k = {}, 0
        for b in mech.bodies:
            if b.name in fixed:
                colours[b.name] = _GROUND
            else:
                colours[b.name] = _COLOURS[k % len(_COLOURS)]
                k += 1
        self.colours = colours
        glyphs = []
        # ground supports: fixed-body points used by pins
        for b in mech.bodies:
            if b.name not in fixed:
                continue
            supports, used = [], set()
            for c in mech.constraints:
                if c.type_name in ("revolute", "revolute-revolute"):
                    for body, s in zip(c.bodies, (c.s_i, c.s_j)):
                        if body is b:
                            supports.append(tuple(float(v) for v in s))
                for attr in ("s_Pi", "s_Qi", "s_Pj", "s_Qj"):
                    if hasattr(c, attr):
                        used.add(tuple(float(v) for v in getattr(c, attr)))
            supports = list(dict.fromkeys(supports))
            others = [tuple(float(v) for v in s) for s in b.points.values()]
            others = [s for s in dict.fromkeys(others) if s not in supports and s not in used]
            glyphs.append(_GroundGlyph(ax, mech, b, L, labels, supports, others))
        for b in mech.bodies:
            if b.name not in fixed:
                glyphs.append(_BodyGlyph(ax, mech, b, colours[b.name], L, labels))
        if joints:
            for c in mech.constraints:
                tn = c.type_name
                if tn == "revolute":
                    glyphs.append(_PinGlyph(ax, mech, c.bodies[0], c.s_i, rho))
                elif tn == "translational":
                    glyphs.append(_TranslationalGlyph(ax, mech, c, L, colours, fixed))
                elif tn == "revolute-revolute":
                    glyphs.append(_LinkGlyph(ax, mech, c, L))
                elif tn == "revolute-translational":
                    glyphs.append(_RevoluteTranslationalGlyph(ax, mech, c, L, colours, fixed))
                elif tn == "gear":
                    for body, radius in zip(c.bodies[:2], (c.radius_i, c.radius_j)):
                        glyphs.append(_WheelGlyph(ax, mech, body, radius, colours[body.name]))
                elif tn == "rack-pinion":
                    glyphs.append(_RackGlyph(ax, mech, c, L, colours))
        if frames:
            for b in mech.bodies:
                glyphs.append(_BodyFrame(ax, mech, b, 0.12 * L))
        if vectors:
            glyphs.append(_GlobalFrame(ax, 0.15 * L))
            for body, point in vectors:
                glyphs.append(_VectorGlyph(ax, mech, body, point, L, projections=projections))
        if labels:
            glyphs.append(_PointLabels(ax, mech, q, L, fixed))
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
        _set_limits(self.ax, box, margin)

    def update(self, q):
        for g in self.glyphs:
            g.update(q)
        return self.artists


class _GlobalFrame(_Glyph):
    def __init__(self, ax, length):
        self.frame = _FrameGlyph(ax, length, label="O", axes=("x", "y"), color="k", lw=1.3)
        self.artists = self.frame.artists

    def observe(self, q):
        return self.frame.extent((0.0, 0.0), 0.0)

    def update(self, q):
        self.frame.place((0.0, 0.0), 0.0)


def _set_limits(ax, box, margin=0.1):
    """Limits covering ``box`` with a margin, widened to the axes' shape so that equal aspect cuts nothing."""
    x0, x1, y0, y1 = (float(v) for v in box)
    m = margin * max(x1 - x0, y1 - y0, 1e-9)
    x0, x1, y0, y1 = x0 - m, x1 + m, y0 - m, y1 + m
    pos = ax.get_position()
    w, h = ax.figure.get_size_inches()
    shape = (pos.height * h) / max(pos.width * w, 1e-9)  # height / width of the axes box
    dx, dy = x1 - x0, y1 - y0
    if dy / dx < shape:
        grow = (shape * dx - dy) / 2
        y0, y1 = y0 - grow, y1 + grow
    else:
        grow = (dy / shape - dx) / 2
        x0, x1 = x0 - grow, x1 + grow
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")


def _fit_figure(ax, box, width=6.4):
    """Give a figure made for one drawing a height that suits the drawing's proportions."""
    x0, x1, y0, y1 = box
    ratio = (y1 - y0 + 0.2 * max(x1 - x0, y1 - y0)) / max(x1 - x0 + 0.2 * max(x1 - x0, y1 - y0), 1e-9)
    fig = ax.figure
    height = round(float(np.clip(width * 0.8 * ratio + 1.3, 3.6, 7.5)), 1)
    fig.set_size_inches(width, height)
    # margins in inches, as tight_layout would leave them, without its cost of a full render
    fig.subplots_adjust(left=0.75 / width, right=1 - 0.2 / width, bottom=0.6 / height, top=1 - 0.75 / height)


def _style_axes(ax, title=None):
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.grid(True, lw=0.4, alpha=0.4)
    if title:
        import textwrap

        ax.set_title("\n".join(textwrap.wrap(str(title), 58)), fontsize=10)


# ============================================================================================== public: drawings
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
    ax = _new_axes(ax)
    scene = _Scene(ax, mech, q, frames=frames, labels=labels, joints=joints, vectors=vectors,
                   projections=projections)
    box = scene.observe([scene.q])  # first: it sizes the guides
    scene.update(scene.q)
    _style_axes(ax, title if title is not None else getattr(mech, "title", None))
    if fit:
        _fit_figure(ax, box)
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
    g = _FrameGlyph(ax, length, label=label, axes=axes, color=color)
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
    q = np.asarray(mech._check_q(q), dtype=float)
    L = _size(mech, [q])
    g = _VectorGlyph(ax, mech, body, point, L, origin=origin, projections=projections)
    g.update(q)
    ax.update_datalim(g.observe(q))
    ax.autoscale_view()
    return g.artists


# ============================================================================================== public: plots
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
    ax = _new_axes(ax)
    mech = result.mechanism
    if len(result.t) == 0:
        raise InputError("the sweep has no solved instant to plot")
    x0 = y0 = np.inf
    x1 = y1 = -np.inf
    if mechanism:
        scene = _Scene(ax, mech, result.q[0], labels=False)
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
        name = _point_text(point if isinstance(point, str) else "P").strip("$")
        (line,) = ax.plot(xy[:, 0], xy[:, 1], "-", lw=1.8, label=rf"${name}_{{{n}}}$ (body {n})", zorder=9)
        ax.plot(xy[:1, 0], xy[:1, 1], "o", color=line.get_color(), ms=4, zorder=9)
    _set_limits(ax, (min(lo[0], x0), max(hi[0], x1), min(lo[1], y0), max(hi[1], y1)), margin=0.05)
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
        return data[:, "xy".index(comp)], _point_label(mech, body, point, comp, derivative)
    name = tuple(name) if isinstance(name, list) else name
    return result.coordinate(name, derivative), _coordinate_label(mech, name, derivative)


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
    ax = _new_axes(ax)
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


# ============================================================================================== animation
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
    The artists are created once and moved (blitting), so the animation renders quickly.
    """
    from matplotlib.animation import FuncAnimation

    mech = result.mechanism
    N = len(result.t)
    if N == 0:
        raise InputError("the sweep has no solved instant to animate")
    every = max(1, int(every), math.ceil(N / max(1, int(max_frames))))
    idx = np.arange(0, N, every)
    fig, ax = _plt().subplots(figsize=figsize, dpi=dpi)
    qs = result.q[idx]
    scene = _Scene(ax, mech, qs[0], frames=frames, labels=labels, size=_size(mech, qs))
    traces = []
    for k, (body, point) in enumerate(trace or []):
        xy = result.position(body, point)[idx]
        ax.plot(xy[:, 0], xy[:, 1], ":", color="#888888", lw=1.0, zorder=1)
        (line,) = ax.plot([], [], "-", color=_TRACES[k % len(_TRACES)], lw=1.5, zorder=1)
        traces.append((line, xy))
    box = scene.observe(qs)
    scene.set_limits(box)
    _style_axes(ax, getattr(mech, "title", None))
    driver = mech.drivers[0] if mech.drivers else None
    sym = _driver_symbol(mech, driver, unicode=True) if driver is not None else None
    values = None
    if driver is not None:
        import sympy as sp

        f = sp.lambdify(mech.t, driver.f, "numpy")
        values = np.broadcast_to(np.asarray(f(result.t[idx]), dtype=float), idx.shape)
    clock = ax.text(0.02, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9, zorder=10,
                    bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="#bbbbbb", alpha=0.9))

    def update(k):
        artists = scene.update(qs[k])
        text = f"t = {result.t[idx[k]]:.4g}"  # plain text: mathtext would be parsed anew every frame
        if values is not None:
            text += f"    {sym} = {values[k]:.4g}"
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


def animation_html(result, frame_format="png", **kwargs):
    """:func:`animate` for notebooks: an object that renders as an HTML/JavaScript player.

    The figure is closed so the notebook does not also show it as a still image. Keyword arguments go to
    :func:`animate`; the defaults here are smaller (72 frames at most, 72 dpi) because every frame is
    stored in the notebook as an image. The player's HTML is the same on every run (no random ids), so a
    re-executed notebook changes only where its content does.

    Parameters
    ----------
    frame_format : {"png", "jpeg"}
        How the frames are stored.

    Returns
    -------
    kinbook._animation.AnimationHTML
        ``_repr_html_()`` returns the JavaScript player; ``.anim`` is the FuncAnimation.
    """
    kwargs.setdefault("figsize", (6.0, 4.5))
    kwargs.setdefault("dpi", 72)
    kwargs.setdefault("max_frames", 72)
    anim = animate(result, **kwargs)
    _plt().close(anim._fig)
    return AnimationHTML(anim, frame_format)


# ============================================================================================== explorer
class _DriverAxis:
    """Maps the value of one driver to the time at which it takes that value (linear drivers), or uses t."""

    def __init__(self, mech, driver):
        import sympy as sp

        drivers = mech.drivers
        if not drivers:
            raise InputError(f"mechanism '{mech.name}' has no driver to explore")
        if driver is None:
            driver = drivers[0]
        elif isinstance(driver, str):
            match = [d for d in drivers if d.name == driver]
            if not match:
                known = ", ".join(repr(d.name) for d in drivers)
                raise InputError(f"mechanism '{mech.name}' has no driver {driver!r} (its drivers: {known})")
            driver = match[0]
        elif driver not in drivers:
            raise InputError(f"{driver!r} is not a driver of mechanism '{mech.name}'")
        self.driver = driver
        t = mech.t
        slope = sp.diff(driver.f, t)
        self.linear = not slope.free_symbols and slope != 0
        if self.linear:
            self.a, self.b = float(driver.f.subs(t, 0)), float(slope)
            self.symbol = _driver_symbol(mech, driver)
            self.unicode = _driver_symbol(mech, driver, unicode=True)
            rotational = driver.type_name == "relative-driver" or getattr(driver, "coordinate", None) == "phi"
            self.v0 = self.a
            self.step = 0.05 if rotational else 0.01 * _size(mech, [mech.q0])
            self.default = (self.a + np.pi * np.arange(-3, 5) / 4 if rotational
                            else self.a + _size(mech, [mech.q0]) * np.linspace(-0.4, 0.4, 8))
        else:
            self.a, self.b = 0.0, 1.0
            self.symbol, self.unicode, self.v0, self.step = "$t$", "t", 0.0, 0.01
            self.default = np.linspace(0.0, 1.0, 8)

    def time(self, v):
        return (float(v) - self.a) / self.b


def _continue(mech, t_from, q_from, t_to, max_dt):
    """Solve Φ(q, t_to) = 0 by continuation from a solution at t_from, halving the step on trouble."""
    span = t_to - t_from
    q, t, done = np.array(q_from, dtype=float), t_from, 0.0
    step = min(max_dt, abs(span)) if span else 0.0
    if span == 0:
        return mech.solve_position(t_to, q0=q)
    while done < abs(span) - 1e-15:
        h = min(step, abs(span) - done)
        t_next = t_from + math.copysign(done + h, span)
        try:
            q = mech.solve_position(t_next, q0=q, max_iter=15)
        except (KinbookError, np.linalg.LinAlgError, FloatingPointError):
            if step < max_dt / 64:
                raise
            step /= 2
            continue
        done += h
        t = t_next
    return q


def _solve_values(mech, axis, values):
    """Configurations at driver ``values``, by continuation outward from the assembly at the driver's start.

    Returns a list with a q or ``None`` (does not assemble) per value.
    """
    values = [float(v) for v in values]
    t0 = axis.time(axis.v0)
    max_dt = abs(axis.step / axis.b)
    out = [None] * len(values)
    try:
        q_anchor = mech.solve_position(t0)
    except KinbookError:
        q_anchor = None
    if q_anchor is None:  # no anchor: try each value from the initial guess
        for k, v in enumerate(values):
            try:
                out[k] = mech.solve_position(axis.time(v))
            except KinbookError:
                pass
        return out
    up = sorted((k for k, v in enumerate(values) if v >= axis.v0), key=lambda k: values[k])
    down = sorted((k for k, v in enumerate(values) if v < axis.v0), key=lambda k: -values[k])
    for order in (up, down):
        t_prev, q_prev = t0, q_anchor
        for k in order:
            t_k = axis.time(values[k])
            try:
                out[k] = _continue(mech, t_prev, q_prev, t_k, max_dt)
                t_prev, q_prev = t_k, out[k]
            except (KinbookError, np.linalg.LinAlgError, FloatingPointError):
                break  # farther values lie past this one: continuation cannot reach them either
    return out


def _status(mech, q, t):
    res = float(np.max(np.abs(mech.Phi(q, t)))) if mech.m else 0.0
    d = mech.diagnose(q, t)
    return res, d


def _live_kernel():
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    ip = get_ipython()
    return ip is not None and getattr(ip, "kernel", None) is not None


def explorer(mech, driver=None, values=None, *, static=None, frames=False, ncols=4):
    """Explore a mechanism by hand: move its driver and watch max|Φ| and the condition number of Φ_q.

    In JupyterLab (a live kernel with ipywidgets) this is a slider over the driver's value that redraws the
    mechanism; near a dead point the condition number of Φ_q blows up, and past it the mechanism "does not
    assemble". Elsewhere — or with ``static=True`` — it is a still figure: a grid of configurations at a few
    driver values, each titled with its residual and condition number, so a stored notebook validates
    under nbval.

    Parameters
    ----------
    mech : Mechanism
    driver : str or driver constraint, optional
        Which driver to move (default: the first). Its prescribed function f(t) must be linear in t for the
        slider to run over the driver's value; otherwise the slider runs over t.
    values : array_like, optional
        Driver values of the still figure; their range is the slider's range. Default for a rotation: the
        start value −3π/4 … +π in steps of π/4.
    static : bool, optional
        Force the still figure (True) or the widget (False); default: the widget when a live kernel and
        ipywidgets are available.
    frames : bool
        Draw the bodies' local frames.
    ncols : int
        Panels per row of the still figure.

    Returns
    -------
    ipywidgets.VBox or matplotlib.figure.Figure

    Notes
    -----
    Each configuration is solved by continuation (``mech.solve_position(t, q0=previous)`` in small steps)
    outward from the assembly at the driver's start value, so the drawings stay on one assembly branch.
    Textbook §13.6 (Newton–Raphson) and the dead points of §13.5.
    """
    axis = _DriverAxis(mech, driver)
    values = axis.default if values is None else np.atleast_1d(np.asarray(values, dtype=float))
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise InputError(f"`values` must be finite driver values, got {values}")
    if static is None:
        static = not _live_kernel()
        if not static:
            try:
                import ipywidgets  # noqa: F401
            except ImportError:
                static = True
    if static:
        return _explorer_static(mech, axis, values, frames, ncols)
    return _explorer_widget(mech, axis, values, frames)


def _explorer_static(mech, axis, values, frames, ncols):
    qs = _solve_values(mech, axis, values)
    good = [q for q in qs if q is not None]
    k = len(values)
    ncols = max(1, min(int(ncols), k))
    nrows = math.ceil(k / ncols)
    fig, axes = _plt().subplots(nrows, ncols, figsize=(3.6 * ncols, 3.3 * nrows), squeeze=False)
    L = _size(mech, good) if good else _size(mech, [mech.q0])
    box = None
    scenes = []
    for v, q, ax in zip(values, qs, axes.flat):
        if q is None:
            ax.set_title(f"{axis.symbol} = {v:.4g}\ndoes not assemble", fontsize=9, color="#c62828")
            ax.text(0.5, 0.5, "does not assemble", transform=ax.transAxes, ha="center", va="center",
                    color="#c62828", fontsize=10)
            ax.set_xticks([])
            ax.set_yticks([])
            continue
        t = axis.time(v)
        scene = _Scene(ax, mech, q, frames=frames, labels=True, size=L)
        b = scene.observe([q])
        scene.update(q)
        box = b if box is None else (min(box[0], b[0]), max(box[1], b[1]), min(box[2], b[2]), max(box[3], b[3]))
        scenes.append(scene)
        res, d = _status(mech, q, t)
        ax.set_title(f"{axis.symbol} = {v:.4g}\nmax|Φ| = {res:.2e}, cond(Φ$_q$) = {d.cond:.3g}", fontsize=9)
        ax.tick_params(labelsize=7)
        ax.grid(True, lw=0.4, alpha=0.4)
    for scene in scenes:
        scene.set_limits(box, margin=0.06)
    for ax in list(axes.flat)[k:]:
        ax.set_visible(False)
    fig.suptitle(getattr(mech, "title", mech.name), fontsize=10)
    fig.tight_layout()
    _plt().close(fig)  # returned, not also shown by pyplot
    return fig


def _explorer_widget(mech, axis, values, frames):
    import io

    import ipywidgets as widgets
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    lo, hi = float(np.min(values)), float(np.max(values))
    if hi <= lo:
        lo, hi = lo - 1.0, hi + 1.0
    # sweep the slider's range once: the limits of the drawing and the guides' lengths
    grid = np.linspace(lo, hi, 17)
    sweep = [q for q in _solve_values(mech, axis, grid) if q is not None]
    t0 = axis.time(axis.v0)
    q0 = mech.solve_position(t0)
    fig = Figure(figsize=(6.4, 4.8), dpi=90)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    qs = sweep + [q0]
    scene = _Scene(ax, mech, q0, frames=frames, labels=True, size=_size(mech, qs))
    scene.set_limits(scene.observe(qs))
    _style_axes(ax, getattr(mech, "title", mech.name))
    state = {"t": t0, "q": q0}

    def render(q):
        scene.update(q)
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        return buf.getvalue()

    v_start = min(max(axis.v0, lo), hi)
    slider = widgets.FloatSlider(value=v_start, min=lo, max=hi, step=(hi - lo) / 400, description=axis.unicode,
                                 continuous_update=True, readout_format=".4g",
                                 layout=widgets.Layout(width="520px"))
    status = widgets.HTML()
    image = widgets.Image(format="png")

    def show(change=None):
        v = slider.value
        t = axis.time(v)
        try:
            q = _continue(mech, state["t"], state["q"], t, abs(axis.step / axis.b))
        except (KinbookError, np.linalg.LinAlgError, FloatingPointError):
            status.value = (f'<span style="color:#c62828"><b>does not assemble</b> at {axis.unicode} = {v:.4g}'
                            f" (shown: the last configuration that did)</span>")
            return
        state["t"], state["q"] = t, q
        res, d = _status(mech, q, t)
        colour = "#2e7d32" if d.cond < 1e3 else ("#ef6c00" if d.cond < 1e8 else "#c62828")
        status.value = (f"{axis.unicode} = {v:.4g}: max|Φ| = {res:.2e}, "
                        f'<span style="color:{colour}">cond(Φ<sub>q</sub>) = {d.cond:.4g}</span> ({d.kind})')
        image.value = render(q)

    slider.observe(show, names="value")
    show()
    box = widgets.VBox([slider, status, image])
    box.kinbook_slider, box.kinbook_status = slider, status  # handles for tests and notebooks
    return box
