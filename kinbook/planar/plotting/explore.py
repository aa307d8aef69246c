"""The explorer: move a mechanism's driver by hand and watch max|Φ| and the condition number of Φ_q.

A slider in JupyterLab (a live kernel with ipywidgets), or a still grid of configurations elsewhere. Every
configuration is found by continuation (:func:`kinbook.core.sweep.follow`) from the assembly at the driver's
start value, so the drawings stay on one assembly branch; where the mechanism stops (a dead point), the
explorer says so and shows the limit configuration, the last one that assembles. Rotations are shown in
degrees.
"""

from __future__ import annotations

import io
import math

import numpy as np
import sympy as sp

from ...core._animation import degrees_as_read, swings_about_zero
from ...core.sweep import follow, follow_times
from ...errors import InputError
from ._common import pyplot, style_axes
from .joints import drawing_size, driver_symbol
from .scene import Scene

__all__ = ["explorer"]


class _DriverAxis:
    """Maps the value of one driver to the time at which it takes that value (linear drivers), or uses t; shows
    angles in degrees."""

    def __init__(self, mech, driver):
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
        self.angle = False
        self.signed = False  # angles read in (−180°, 180°): set by the explorer for values swinging about zero
        if self.linear:
            self.a, self.b = float(driver.f.subs(t, 0)), float(slope)
            self.symbol = driver_symbol(mech, driver)
            self.unicode = driver_symbol(mech, driver, unicode=True)
            self.angle = (driver.measures or (None,))[-1] == "angle"
            self.v0 = self.a
            self.step = 0.05 if self.angle else 0.01 * drawing_size(mech, [mech.q0])
            self.default = (self.a + np.pi * np.arange(-3, 5) / 4 if self.angle
                            else self.a + drawing_size(mech, [mech.q0]) * np.linspace(-0.4, 0.4, 8))
        else:
            self.a, self.b = 0.0, 1.0
            self.symbol, self.unicode, self.v0, self.step = "$t$", "t", 0.0, 0.01
            self.default = np.linspace(0.0, 1.0, 8)

    def time(self, v):
        return (float(v) - self.a) / self.b

    def value(self, t):
        return self.a + self.b * float(t)

    def shown(self, v):
        """A driver value as a person reads it: degrees for a rotation."""
        return math.degrees(v) if self.angle else float(v)

    def text(self, v, digits=4):
        """A driver value as text: a rotation in degrees in [0°, 360°) as the book gives angles (a value the
        continuation reached by turning on past a full turn, or back below zero, names the same position)."""
        return f"{degrees_as_read(v, digits, self.signed)[0]}°" if self.angle else f"{float(v):.{digits}g}"

    @property
    def max_step(self):
        return abs(self.step / self.b)


def _status(mech, q, t):
    """max|Φ| as text (below the solver's tolerance, as a bound: the digits there are round-off, different on
    another machine) and the diagnosis of Φ_q."""
    res = float(np.max(np.abs(mech.Phi(q, t)))) if mech.m else 0.0
    return ("max|Φ| < 1e-10" if res < 1e-10 else f"max|Φ| = {res:.2e}"), mech.diagnose(q, t)


def _verdict(d, reached):
    """What the status line calls Φ_q: the diagnosis when Φ_q is singular; "near-singular" where the mechanism
    stopped short of the value asked for (the driver's dead point is within the last step: the continuation could
    not get past it) or the condition number has passed 1000 — "regular" there would contradict the number
    beside it."""
    if d.singular:
        return d.kind
    if not reached:
        return "near-singular: the driver's dead point"
    return "near-singular" if d.cond >= 1e3 else "regular"


def _live_kernel():
    try:
        from IPython import get_ipython  # optional dependency
    except ImportError:
        return False
    ip = get_ipython()
    return ip is not None and getattr(ip, "kernel", None) is not None


def explorer(mech, driver=None, values=None, *, degrees=False, static=None, frames=False, ncols=4):
    """Explore a mechanism by hand: move its driver and watch max|Φ| and the condition number of Φ_q.

    In JupyterLab (a live kernel with ipywidgets) this is a slider over the driver's value that redraws the
    mechanism; near a dead point the condition number of Φ_q blows up, and past it the mechanism "does not
    assemble": the explorer then shows the limit configuration, the last one that assembles, and says at
    which driver value the mechanism stops. Elsewhere — or with ``static=True`` — it is a still figure: a
    grid of configurations at a few driver values, each titled with its residual and condition number, so a
    stored notebook validates under nbval. A rotation is shown in degrees, on the slider and in the text.

    Parameters
    ----------
    mech : Mechanism
    driver : str or driver constraint, optional
        Which driver to move (default: the first). Its prescribed function f(t) must be linear in t for the
        slider to run over the driver's value; otherwise the slider runs over t.
    values : array_like, optional
        Driver values of the still figure, in the driver's units (radians for a rotation, unless
        ``degrees``); their range is the slider's range. Default for a rotation: the start value −135° …
        +180° in steps of 45°.
    degrees : bool
        ``values`` of a rotation are given in degrees.
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
    Each configuration is solved by continuation (:func:`kinbook.core.sweep.follow_times`) outward from the
    assembly at the driver's start value, so the drawings stay on one assembly branch. Textbook §13.6
    (Newton–Raphson) and the dead points of §13.5.
    """
    axis = _DriverAxis(mech, driver)
    values = axis.default if values is None else np.atleast_1d(np.asarray(values, dtype=float))
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise InputError(f"`values` must be finite driver values, got {values}")
    if degrees and axis.angle:
        values = np.radians(values)
    axis.signed = axis.angle and swings_about_zero(values)
    if static is None:
        static = not _live_kernel()
        if not static:
            try:
                import ipywidgets  # noqa: F401  (optional dependency: the lab extra)
            except ImportError:
                static = True
    if static:
        return _explorer_static(mech, axis, values, frames, ncols)
    return _explorer_widget(mech, axis, values, frames)


def _solve_values(mech, axis, values):
    """Continuations at driver ``values``, outward from the assembly at the driver's start."""
    times = [axis.time(v) for v in values]
    return follow_times(mech, times, t0=axis.time(axis.v0), max_step=axis.max_step)


def _stops(axis, at):
    return f"stops at {axis.unicode} = {axis.text(axis.value(at.t), 5)}"


def _explorer_static(mech, axis, values, frames, ncols):
    found = _solve_values(mech, axis, values)
    good = [c.q for c in found if c.q is not None]
    k = len(values)
    ncols = max(1, min(int(ncols), k))
    nrows = math.ceil(k / ncols)
    fig, axes = pyplot().subplots(nrows, ncols, figsize=(3.6 * ncols, 3.3 * nrows), squeeze=False)
    L = drawing_size(mech, good) if good else drawing_size(mech, [mech.q0])
    box = None
    scenes = []
    for v, at, ax in zip(values, found, axes.flat):
        if at.q is None:
            ax.set_title(f"{axis.symbol} = {axis.text(v)}\ndoes not assemble", fontsize=9, color="#c62828")
            ax.text(0.5, 0.5, "does not assemble", transform=ax.transAxes, ha="center", va="center",
                    color="#c62828", fontsize=10)
            ax.set_xticks([])
            ax.set_yticks([])
            continue
        scene = Scene(ax, mech, at.q, frames=frames, labels=True, size=L)
        b = scene.observe([at.q])
        scene.update(at.q)
        box = b if box is None else (min(box[0], b[0]), max(box[1], b[1]), min(box[2], b[2]), max(box[3], b[3]))
        scenes.append(scene)
        if at.reached:
            res, d = _status(mech, at.q, at.t)
            ax.set_title(f"{axis.symbol} = {axis.text(v)}\n{res}, cond(Φ$_q$) = {d.cond:.3g}", fontsize=9)
        else:  # the limit configuration: where the mechanism stops on its way to v
            ax.set_title(f"{axis.symbol} = {axis.text(v)}: does not assemble\n{_stops(axis, at)} (shown)",
                         fontsize=9, color="#c62828")
        ax.tick_params(labelsize=7)
        ax.grid(True, lw=0.4, alpha=0.4)
    for scene in scenes:
        scene.set_limits(box, margin=0.06)
    for ax in list(axes.flat)[k:]:
        ax.set_visible(False)
    fig.suptitle(getattr(mech, "title", mech.name), fontsize=10)
    fig.tight_layout()
    pyplot().close(fig)  # returned, not also shown by pyplot
    return fig


def _explorer_widget(mech, axis, values, frames):
    import ipywidgets as widgets  # optional dependency: ipywidgets (the lab extra)
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # import time: matplotlib only when needed
    from matplotlib.figure import Figure  # import time: matplotlib only when needed

    lo, hi = float(np.min(values)), float(np.max(values))
    if hi <= lo:
        lo, hi = lo - 1.0, hi + 1.0
    # sweep the slider's range once: the limits of the drawing and the guides' lengths
    sweep = [c.q for c in _solve_values(mech, axis, np.linspace(lo, hi, 17)) if c.q is not None]
    t0 = axis.time(axis.v0)
    q0 = mech.solve_position(t0)
    fig = Figure(figsize=(6.4, 4.8), dpi=90)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    qs = sweep + [q0]
    scene = Scene(ax, mech, q0, frames=frames, labels=True, size=drawing_size(mech, qs))
    scene.set_limits(scene.observe(qs))
    style_axes(ax, getattr(mech, "title", mech.name))
    state = {"t": t0, "q": q0}

    def render(q):
        scene.update(q)
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        return buf.getvalue()

    v_start = min(max(axis.v0, lo), hi)
    a, b, start = axis.shown(lo), axis.shown(hi), axis.shown(v_start)
    # the slider runs over the continuation's range; where that leaves [0°, 360°) (or ±180° for a swing), its own
    # readout would contradict the status line, which reads the angle as the book gives it
    readout = not axis.angle or axis.signed or (a >= 0.0 and b < 360.0)
    slider = widgets.FloatSlider(value=start, min=a, max=b, step=(b - a) / 400,
                                 description=axis.unicode + (" (°)" if axis.angle else ""), readout=readout,
                                 continuous_update=True, readout_format=".4g", layout=widgets.Layout(width="520px"))
    status = widgets.HTML()
    image = widgets.Image(format="png")

    def show(change=None):
        v = math.radians(slider.value) if axis.angle else slider.value
        at = follow(mech, axis.time(v), t_from=state["t"], q_from=state["q"], max_step=axis.max_step)
        state["t"], state["q"] = at.t, at.q
        res, d = _status(mech, at.q, at.t)
        colour = "#2e7d32" if d.cond < 1e3 else ("#ef6c00" if d.cond < 1e8 else "#c62828")
        cond = f'<span style="color:{colour}">cond(Φ<sub>q</sub>) = {d.cond:.4g}</span> ({_verdict(d, at.reached)})'
        if at.reached:
            status.value = f"{axis.unicode} = {axis.text(v)}: {res}, {cond}"
        else:
            status.value = (f'<span style="color:#c62828"><b>does not assemble</b> at {axis.unicode} = '
                            f"{axis.text(v)}: the mechanism {_stops(axis, at)}</span> (shown: the limit "
                            f"configuration, {cond})")
        image.value = render(at.q)

    slider.observe(show, names="value")
    show()
    box = widgets.VBox([slider, status, image])
    box.kinbook_slider, box.kinbook_status = slider, status  # handles for tests and notebooks
    return box
