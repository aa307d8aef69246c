"""Helpers shared by the planar drawings, plots, animations and the explorer: colours, mathtext labels in the
book's notation, 2-D rotations, sizes and axes layout."""

from __future__ import annotations

import math
import re
import textwrap

import numpy as np

from ...errors import InputError

__all__ = ["COLOURS", "GROUND", "TRACES", "RHO", "SUBSCRIPTS", "pyplot", "new_axes", "math_text", "point_text", "rotate", "unit_vector", "body_q", "convex_hull", "pt", "all_points", "coordinate_label", "point_label", "set_axes_limits", "fit_figure", "style_axes"]

COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#bcbd22")
GROUND = "#555555"
TRACES = ("#6a3d9a", "#b15928", "#000000", "#e7298a")
RHO = 0.025
"""Radius of the joint circles, as a fraction of the drawing's size."""
_GREEK = {"ξ": r"\xi", "η": r"\eta", "φ": r"\varphi", "Φ": r"\Phi"}
SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")

def pyplot():
    import matplotlib.pyplot as plt  # import time: matplotlib only when needed

    return plt


def new_axes(ax, figsize=(6.4, 4.8)):
    if ax is not None:
        return ax
    _, ax = pyplot().subplots(figsize=figsize)
    return ax


def math_text(text):
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


def point_text(name):
    """Point names as the book writes them: 'OA' → O_A (reference points O_i), others unchanged."""
    m = re.fullmatch(r"O([A-Za-z0-9]+)", str(name))
    return rf"$O_{{{m.group(1)}}}$" if m else str(name)


def rotate(phi, v):
    c, s = math.cos(phi), math.sin(phi)
    v = np.asarray(v, dtype=float)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


def unit_vector(v):
    v = np.asarray(v, dtype=float)
    n = float(np.hypot(*v))
    return v / n if n > 0 else np.array([1.0, 0.0])


def body_q(mech, q, body):
    k = 3 * (mech.body(body).number - 1)
    return q[k : k + 3]


def convex_hull(points):
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


def pt(mech, q, body, s):
    x, y, phi = body_q(mech, q, body.name)
    return np.array([x, y]) + rotate(phi, np.array([float(v) for v in s]))


def all_points(mech, q):
    """Global positions of every body point and reference point at q, shape (k, 2)."""
    out = []
    for b in mech.bodies:
        x, y, phi = body_q(mech, q, b.name)
        out.append([[x, y]])
        if b.points:
            s = np.array([[float(v) for v in p] for p in b.points.values()])
            out.append(np.array([x, y]) + rotate(phi, s))
    return np.concatenate([np.asarray(o, dtype=float) for o in out])


def coordinate_label(mech, name, derivative=0):
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


def point_label(mech, body, point, component, derivative=0):
    base = (component, rf"\dot{{{component}}}", rf"\ddot{{{component}}}")[derivative]
    name = point if isinstance(point, str) else "P"
    sup = point_text(name).strip("$")
    return rf"${base}_{{{mech.body(body).number}}}^{{{sup}}}$"


def set_axes_limits(ax, box, margin=0.1):
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


def fit_figure(ax, box, width=6.4):
    """Give a figure made for one drawing a height that suits the drawing's proportions."""
    x0, x1, y0, y1 = box
    ratio = (y1 - y0 + 0.2 * max(x1 - x0, y1 - y0)) / max(x1 - x0 + 0.2 * max(x1 - x0, y1 - y0), 1e-9)
    fig = ax.figure
    height = round(float(np.clip(width * 0.8 * ratio + 1.3, 3.6, 7.5)), 1)
    fig.set_size_inches(width, height)
    # margins in inches, as tight_layout would leave them, without its cost of a full render
    fig.subplots_adjust(left=0.75 / width, right=1 - 0.2 / width, bottom=0.6 / height, top=1 - 0.75 / height)


def style_axes(ax, title=None):
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.grid(True, lw=0.4, alpha=0.4)
    if title:
        ax.set_title("\n".join(textwrap.wrap(str(title), 58)), fontsize=10)
