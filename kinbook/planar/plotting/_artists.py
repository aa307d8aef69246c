"""The pieces a planar drawing is made of, other than joints: frames, bodies, the ground's supports, pins,
point names and the vectors r_i, s_i^P, r_i^P. Each is a small class whose matplotlib artists are created once
and moved by ``update(q)`` (so animations only update data)."""

from __future__ import annotations

import numpy as np

from ._common import GROUND, RHO, body_q, convex_hull, math_text, point_text, pt, rotate, unit_vector

__all__ = ["Glyph", "FrameGlyph", "BodyFrame", "BodyGlyph", "GroundGlyph", "PinGlyph", "PointLabels", "VectorGlyph", "GlobalFrame"]


class Glyph:
    """A piece of a drawing: artists created once, moved by :meth:`update`."""

    artists: list

    def observe(self, q):
        """Points (k, 2) this glyph covers at q (for the axes limits); may also widen guide lines."""
        return np.zeros((0, 2))

    def update(self, q):
        raise NotImplementedError


class FrameGlyph(Glyph):
    """A reference frame: two arrows along the rotated axes, axis names at their tips, an origin label."""

    def __init__(self, ax, length, label=None, axes=("ξ", "η"), color="k", lw=1.3, zorder=6, fontsize=10):
        from matplotlib.patches import FancyArrowPatch  # import time: matplotlib only when needed

        self.length = float(length)
        style = dict(arrowstyle="-|>", mutation_scale=12, color=color, lw=lw, zorder=zorder, shrinkA=0, shrinkB=0)
        self.arrows = [FancyArrowPatch((0, 0), (1, 0), **style), FancyArrowPatch((0, 0), (0, 1), **style)]
        for a in self.arrows:
            ax.add_patch(a)
        kw = dict(color=color, fontsize=fontsize, zorder=zorder, ha="center", va="center")
        self.names = [ax.text(0, 0, math_text(a), **kw) for a in axes]
        self.origin = ax.text(0, 0, math_text(label), color=color, fontsize=fontsize, zorder=zorder,
                              ha="right", va="top") if label else None
        self.artists = self.arrows + self.names + ([self.origin] if self.origin else [])

    def place(self, r, phi):
        r = np.asarray(r, dtype=float)
        e = rotate(phi, np.eye(2)) * self.length
        for a, n, d in zip(self.arrows, self.names, e):
            a.set_positions(tuple(r), tuple(r + d))
            n.set_position(tuple(r + 1.15 * d))
        if self.origin is not None:
            self.origin.set_position(tuple(r - 0.12 * e[0] + 0.22 * e[1]))

    def extent(self, r, phi):
        e = rotate(phi, np.eye(2)) * self.length * 1.25
        return np.array([r, r + e[0], r + e[1]])


class BodyFrame(Glyph):
    def __init__(self, ax, mech, body, length):
        self.mech, self.body = mech, body
        n = body.number
        self.frame = FrameGlyph(ax, length, label=f"O_{n}", axes=(f"ξ_{n}", f"η_{n}"), color="#333333",
                                 lw=1.0, fontsize=9)
        self.artists = self.frame.artists

    def observe(self, q):
        x, y, phi = body_q(self.mech, q, self.body.name)
        return self.frame.extent((x, y), phi)

    def update(self, q):
        x, y, phi = body_q(self.mech, q, self.body.name)
        self.frame.place((x, y), phi)


class BodyGlyph(Glyph):
    """A moving body: a line (two points), a convex polygon (three or more), a dot (one) and its number."""

    def __init__(self, ax, mech, body, colour, L, labels):
        from matplotlib.patches import Polygon  # import time: matplotlib only when needed

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
            hull = convex_hull(local)
            if len(hull) >= 3:
                self.kind = "polygon"
                self.outline = self.local[hull]
                self.patch = Polygon(self.outline, closed=True, facecolor=colour, alpha=0.28,
                                     edgecolor=colour, lw=2.0, zorder=2)
                ax.add_patch(self.patch)
                self.artists.append(self.patch)
        if self.kind == "line":
            d = self.local - self.local.mean(axis=0)
            axis = np.linalg.svd(d)[2][0] if k > 2 else unit_vector(self.local[1] - self.local[0])
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
        x, y, phi = body_q(self.mech, q, self.body.name)
        return np.array([x, y]) + rotate(phi, s)

    def observe(self, q):
        return self._global(q, self.outline)

    def update(self, q):
        pts = self._global(q, self.outline)
        if self.kind == "polygon":
            self.patch.set_xy(pts)
        else:
            self.line.set_data(pts[:, 0], pts[:, 1])
        if self.number is not None:
            phi = body_q(self.mech, q, self.body.name)[2]
            centre = pts.mean(axis=0)
            if self.kind == "line":
                # mid-point of the longest segment, pushed off the line to one side
                seg = np.argmax(np.hypot(*np.diff(pts, axis=0).T))
                centre = pts[seg : seg + 2].mean(axis=0) - rotate(phi, self.normal) * 0.06 * self.L
            elif self.kind == "dot":
                centre = centre + np.array([0.0, 0.085]) * self.L
            self.number.set_position(tuple(centre))


class GroundGlyph(Glyph):
    """The fixed body: a support (triangle on a hatched base) at each joint point, its number by the first."""

    def __init__(self, ax, mech, body, L, labels, support_points, other_points):
        from matplotlib.patches import Polygon  # import time: matplotlib only when needed

        self.mech, self.body = mech, body
        rho = RHO * L
        self.rho = rho
        self.supports = np.array(support_points, dtype=float).reshape(-1, 2)
        self.others = np.array(other_points, dtype=float).reshape(-1, 2)
        self.tri = np.array([[0, 0], [-1.3 * rho, -2.2 * rho], [1.3 * rho, -2.2 * rho]])
        self.base = np.array([[-2.0 * rho, -2.2 * rho], [2.0 * rho, -2.2 * rho],
                              [2.0 * rho, -3.1 * rho], [-2.0 * rho, -3.1 * rho]])
        self.tris, self.bases = [], []
        self.artists = []
        for _ in self.supports:
            t = Polygon(self.tri, closed=True, fc="#dddddd", ec=GROUND, lw=1.2, zorder=3)
            b = Polygon(self.base, closed=True, fill=False, hatch="////", ec=GROUND, lw=0.0, zorder=3)
            (line,) = ax.plot([], [], "-", color=GROUND, lw=1.5, zorder=3)
            ax.add_patch(t)
            ax.add_patch(b)
            self.tris.append(t)
            self.bases.append((b, line))
            self.artists += [t, b, line]
        (self.dots,) = ax.plot([], [], "o", color=GROUND, ms=3, zorder=3)
        self.artists.append(self.dots)
        self.number = None
        if labels:
            self.number = ax.text(0, 0, str(body.number), fontsize=9, ha="center", va="center", zorder=7,
                                  color=GROUND, fontweight="bold",
                                  bbox=dict(boxstyle="circle,pad=0.25", fc="white", ec=GROUND, lw=1.2))
            self.artists.append(self.number)

    def _xy(self, q):
        x, y, phi = body_q(self.mech, q, self.body.name)
        return np.array([x, y]), phi

    def observe(self, q):
        r, phi = self._xy(q)
        pts = [r[None]]
        for s in self.supports:
            p = r + rotate(phi, s)
            pts.append(p + rotate(phi, self.base))
        if len(self.others):
            pts.append(r + rotate(phi, self.others))
        return np.concatenate(pts)

    def update(self, q):
        r, phi = self._xy(q)
        for s, t, (b, line) in zip(self.supports, self.tris, self.bases):
            p = r + rotate(phi, s)
            t.set_xy(p + rotate(phi, self.tri))
            base = p + rotate(phi, self.base)
            b.set_xy(base)
            line.set_data(base[:2, 0], base[:2, 1])
        if len(self.others):
            o = r + rotate(phi, self.others)
            self.dots.set_data(o[:, 0], o[:, 1])
        if self.number is not None:
            anchor = r + rotate(phi, self.supports[0]) if len(self.supports) else r
            self.number.set_position(tuple(anchor + rotate(phi, np.array([0.0, -4.6]) * self.rho)))


class PinGlyph(Glyph):
    """A small white circle at a body point (revolute joints, pins of composite joints)."""

    def __init__(self, ax, mech, body, s, rho, zorder=5):
        from matplotlib.patches import Circle  # import time: matplotlib only when needed

        self.mech, self.body, self.s = mech, body, np.array([float(v) for v in s])
        self.circle = Circle((0, 0), rho, fc="white", ec="black", lw=1.5, zorder=zorder)
        ax.add_patch(self.circle)
        self.artists = [self.circle]

    def position(self, q):
        x, y, phi = body_q(self.mech, q, self.body.name)
        return np.array([x, y]) + rotate(phi, self.s)

    def observe(self, q):
        return self.position(q)[None]

    def update(self, q):
        self.circle.center = tuple(self.position(q))


class PointLabels(Glyph):
    """Point names next to the points; points that coincide (joint points) are named once."""

    def __init__(self, ax, mech, q, L, fixed):
        self.mech, self.L = mech, L
        entries = []
        for b in mech.bodies:
            for name, s in b.points.items():
                entries.append((b, name, np.array([float(v) for v in s])))
        clusters = []  # [representative (body, s), names, member bodies]
        for b, name, s in entries:
            p = pt(mech, q, b, s)
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
        self.texts = [ax.text(*cl["p"], ", ".join(point_text(n) for n in cl["names"]), fontsize=9, zorder=8,
                              color="#111111")
                      for cl in clusters]
        self.artists = list(self.texts)
        self.centres = {}
        for b in mech.bodies:
            if b.points:
                self.centres[b.name] = np.mean([[float(v) for v in s] for s in b.points.values()], axis=0)

    def update(self, q):
        allp = np.array([pt(self.mech, q, cl["body"], cl["s"]) for cl in self.clusters])
        centre = allp.mean(axis=0)
        for cl, text, p in zip(self.clusters, self.texts, allp):
            d = np.zeros(2)
            for b in cl["bodies"]:
                if b.name in self.fixed:
                    continue
                c = pt(self.mech, q, b, self.centres[b.name])
                if np.hypot(*(p - c)) > 1e-9 * self.L:
                    d += unit_vector(p - c)
            if all(x.name in self.fixed for x in cl["bodies"]):
                d = np.array([-1.0, 0.25])  # ground points: left of the joint, above the support below it
            if np.hypot(*d) < 1e-6:
                d = p - centre if np.hypot(*(p - centre)) > 1e-9 * self.L else np.array([1.0, 1.0])
            d = unit_vector(d)
            if any(x.name in self.fixed for x in cl["bodies"]):
                d = unit_vector(np.array([d[0] if abs(d[0]) > 0.2 else -1.0, max(d[1], 0.3)]))  # clear of the support
            text.set_position(tuple(p + 1.7 * RHO * self.L * d))
            text.set_ha("left" if d[0] > 0.3 else ("right" if d[0] < -0.3 else "center"))
            text.set_va("bottom" if d[1] > 0.3 else ("top" if d[1] < -0.3 else "center"))


class VectorGlyph(Glyph):
    """r_i, s_i^P and r_i^P of one body point (Fig. 13.18), optionally with the projections of Fig. 13.20."""

    def __init__(self, ax, mech, body, point, L, origin=(0.0, 0.0), projections=False):
        from matplotlib.patches import FancyArrowPatch  # import time: matplotlib only when needed

        self.mech, self.body = mech, mech.body(body)
        self.s = mech.point_local(body, point)
        self.origin = np.asarray(origin, dtype=float)
        self.L = L
        n = self.body.number
        pname = point_text(point if isinstance(point, str) else "P").strip("$")
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
        x, y, phi = body_q(self.mech, q, self.body.name)
        r = np.array([x, y])
        return r, r + rotate(phi, self.s), phi

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
            nrm = unit_vector(nrm) if np.hypot(*nrm) > 0 else np.array([0.0, 1.0])
            # r_i and s_i^P on the outside of the triangle, r_i^P inside it
            side = 1.0 if lab is not self.labels[2] else -1.0
            other = p if lab is self.labels[0] else (o if lab is self.labels[1] else r)
            if (other - (s0 + s1) / 2) @ nrm > 0:
                nrm = -nrm
            lab.set_position(tuple((s0 + s1) / 2 + side * nrm * 0.06 * self.L))
        if self.projections:
            e_xi, e_eta = rotate(phi, np.eye(2))
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


class GlobalFrame(Glyph):
    def __init__(self, ax, length):
        self.frame = FrameGlyph(ax, length, label="O", axes=("x", "y"), color="k", lw=1.3)
        self.artists = self.frame.artists

    def observe(self, q):
        return self.frame.extent((0.0, 0.0), 0.0)

    def update(self, q):
        self.frame.place((0.0, 0.0), 0.0)
