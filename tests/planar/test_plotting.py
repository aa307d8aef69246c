"""Drawings put their artists where the mechanism's points are; animations and the explorer behave."""

import re
from functools import lru_cache

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.patches import Circle, FancyArrowPatch, Polygon  # noqa: E402

from kinbook import (  # noqa: E402
    InputError,
    examples,
    planar,  # noqa: E402
)
from kinbook.planar import (  # noqa: E402
    Driver,
    Ground,
    Mechanism,
    Revolute,
    plotting,  # noqa: E402
)
from kinbook.planar.plotting._common import point_text  # noqa: E402

from .zoo import zoo  # noqa: E402

EXAMPLES = ["ch13_example1", "ch13_example2", "ch13_example3", "ch13_example4"]


@lru_cache(maxsize=None)
def _example(name):
    """Each example is loaded (and its numeric model compiled) once for the whole module."""
    return examples.load(name)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def four_bar():
    m = _example("ch13_example1")
    return m, m.solve_position(0.0)


@pytest.fixture(scope="module")
def sweep(four_bar):
    m, _ = four_bar
    return m.simulate(np.linspace(0, 0.06, 200), on_failure="truncate")


def _circles(ax):
    return [p for p in ax.patches if isinstance(p, Circle)]


def _has_circle_at(ax, xy, tol=1e-12):
    return any(np.allclose(c.center, xy, atol=tol, rtol=0) for c in _circles(ax))


def _lines_through(ax, pts, tol=1e-12):
    """Line2D artists whose vertices are exactly ``pts`` (in either order)."""
    pts = np.asarray(pts)
    found = []
    for line in ax.get_lines():
        data = np.column_stack(line.get_data()).astype(float)
        if data.shape == pts.shape and (np.allclose(data, pts, atol=tol) or np.allclose(data[::-1], pts, atol=tol)):
            found.append(line)
    return found


# --------------------------------------------------------------------------------------------- draw
def test_revolute_circles_sit_on_the_joint_points(four_bar):
    m, q = four_bar
    ax = plotting.draw(m, q)
    revolutes = [c for c in m.constraints if c.type_name == "revolute"]
    assert len(_circles(ax)) == len(revolutes) == 4
    for c in revolutes:
        p_i = m.point_position(q, c.bodies[0].name, c.point_i)
        assert np.allclose(p_i, m.point_position(q, c.bodies[1].name, c.point_j), atol=1e-9)
        assert _has_circle_at(ax, p_i), c.describe()


def test_two_point_bodies_are_lines_through_their_points(four_bar):
    m, q = four_bar
    ax = plotting.draw(m, q)
    for body in m.bodies[1:]:
        a, b = body.points
        pts = [m.point_position(q, body.name, a), m.point_position(q, body.name, b)]
        assert len(_lines_through(ax, pts)) == 1, body.name


def test_body_with_three_points_is_its_convex_hull():
    m = Mechanism("plate")
    m.add_body("ground", points={"O": (0, 0)})
    m.add_body("plate", points={"O": (0, 0), "B": (2, 0), "C": (1, 1.5), "D": (1, 0.5)}, q0=(0, 0, 0.3))
    m.add(Ground("ground"))
    m.add(Revolute("ground", "plate", point="O"))
    m.add(Driver("plate", "phi", "0.3 + t"))
    q = m.solve_position(0.0)
    ax = plotting.draw(m, q)
    hull = np.array([m.point_position(q, "plate", p) for p in ("O", "B", "C")])  # D is inside
    polys = [p for p in ax.patches if isinstance(p, Polygon) and p.get_fill() and len(p.get_xy()) == 4]
    matches = [p for p in polys if all(np.isclose(p.get_xy()[:3], v, atol=1e-12).all(axis=1).any() for v in hull)]
    assert len(matches) == 1
    assert point_text("OA") == "$O_{A}$"


def test_slider_box_is_centred_on_the_slider_point():
    m = _example("ch13_example2")
    q = m.solve_position(0.01)
    ax = plotting.draw(m, q)
    P = m.point_position(q, "slider", "P")
    boxes = [p for p in ax.patches if isinstance(p, Polygon) and p.get_fill()
             and np.allclose(p.get_xy()[:4].mean(axis=0), P, atol=1e-12)]
    assert len(boxes) == 1
    # the rail lies along the ground's axis P-Q (the global x axis) and reaches past the slider
    rail = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 2 and np.ptp(ln.get_ydata()) < 1e-12
            and max(ln.get_xdata()) > P[0]]
    assert rail


def test_revolute_revolute_link_joins_its_two_points():
    m = _example("ch13_example3")
    q = m.solve_position(0.0)
    ax = plotting.draw(m, q)
    A, B = m.point_position(q, "crank", "A"), m.point_position(q, "rocker", "B")
    assert np.isclose(np.hypot(*(A - B)), 6.0)
    assert len(_lines_through(ax, [A, B])) == 1
    assert _has_circle_at(ax, A) and _has_circle_at(ax, B)


def test_revolute_translational_pin_is_on_the_rod_end():
    m = _example("ch13_example4")
    q = m.solve_position(0.005)
    ax = plotting.draw(m, q)
    B = m.point_position(q, "rod", "B")
    assert _has_circle_at(ax, B)
    slot = [p for p in ax.patches if isinstance(p, Polygon) and len(p.get_xy()) == 5
            and p.get_xy()[:4, 0].min() < B[0] < p.get_xy()[:4, 0].max()]
    assert slot, "the slot must reach the pin"


def test_labels_aspect_and_limits(four_bar):
    m, q = four_bar
    ax = plotting.draw(m, q)
    texts = [t.get_text() for t in ax.texts]
    assert texts.count("$O_{A}$") == 1  # a joint point shared by two bodies is named once
    assert {"1", "2", "3", "4"} <= set(texts)
    assert ax.get_aspect() == 1.0
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for b in m.bodies:
        for p in b.points:
            x, y = m.point_position(q, b.name, p)
            assert x0 < x < x1 and y0 < y < y1
    assert not plotting.draw(m, q, labels=False).texts


def test_frames_and_point_vectors(four_bar):
    m, q = four_bar
    ax = plotting.draw(m, q, frames=True, vectors=[("coupler", "B")])
    texts = {t.get_text() for t in ax.texts}
    assert {r"$\xi_{3}$", r"$\eta_{3}$", r"$\mathbf{r}_{3}^{B}$", r"$\mathbf{s}_{3}^{B}$", "x", "y"} <= texts
    fig, ax = plt.subplots()
    arts = plotting.draw_point_vectors(ax, m, q, "coupler", "B", projections=True)
    r_i, s_i, r_P = [a for a in arts if isinstance(a, FancyArrowPatch)]
    B, O3 = m.point_position(q, "coupler", "B"), q[6:8]
    assert np.allclose(r_i._posA_posB, [(0, 0), O3])
    assert np.allclose(s_i._posA_posB, [O3, B])
    assert np.allclose(r_P._posA_posB, [(0, 0), B])
    frame = plotting.draw_frame(ax, (1.0, 2.0), np.pi / 2, label="O_2", axes=("ξ_2", "η_2"), length=0.5)
    xi, eta = frame[:2]
    assert np.allclose(xi._posA_posB, [(1, 2), (1, 2.5)])
    assert np.allclose(eta._posA_posB, [(1, 2), (0.5, 2)])
    assert [t.get_text() for t in frame[2:]] == [r"$\xi_{2}$", r"$\eta_{2}$", "$O_{2}$"]


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_example_draws(name):
    m = _example(name)
    q = m.solve_position(0.0)
    body = m.bodies[1].name
    ax = plotting.draw(m, q, frames=True, vectors=[(body, next(iter(m.bodies[1].points)))], projections=True)
    ax.figure.set_dpi(40)
    ax.figure.canvas.draw()  # mathtext is parsed only when drawn


def test_every_joint_type_draws():
    m = zoo(3)
    ax = plotting.draw(m, m.q0, frames=True)
    ax.figure.canvas.draw()
    # gears and pinions: a pitch circle about the reference point of each gear body
    centres = [c.center for c in _circles(ax) if c.get_linestyle() == "--"]
    for body in ("b", "c"):
        x, y, _ = m.q0[3 * (m.body(body).number - 1):][:3]
        assert any(np.allclose(c, (x, y)) for c in centres)


# --------------------------------------------------------------------------------------------- plots
def test_trajectories_and_history(sweep):
    ax = plotting.plot_trajectories(sweep, [("coupler", "B")])
    B = sweep.position("coupler", "B")
    assert _lines_through(ax, B)
    ax = plotting.plot_history(sweep, ["phi3", ("rocker", "B", "x")], derivative=1)
    lines = ax.get_lines()
    assert np.allclose(lines[0].get_ydata(), sweep.coordinate("phi3", 1))
    assert np.allclose(lines[1].get_ydata(), sweep.velocity("rocker", "B")[:, 0])
    assert [ln.get_label() for ln in lines] == [r"$\dot{\varphi}_{3}$", r"$\dot{x}_{4}^{B}$"]
    ax = plotting.plot_history(sweep, "phi2")
    assert ax.get_ylabel() == r"$\varphi_{2}$" and ax.get_xlabel() == "$t$"
    with pytest.raises(InputError, match="derivative"):
        plotting.plot_history(sweep, "phi2", derivative=3)


# --------------------------------------------------------------------------------------------- animation
def test_animation_frames_follow_the_sweep(sweep):
    N = len(sweep.t)
    assert sweep.failure is not None and 50 < N < 120  # stopped at the dead point
    anim = plotting.animate(sweep, trace=[("coupler", "B")])
    assert len(list(anim.new_frame_seq())) == N
    anim = plotting.animate(sweep, every=4, max_frames=10)
    idx = anim.kinbook_indices
    assert len(list(anim.new_frame_seq())) == len(idx) == len(range(0, N, -(-N // 10))) <= 10
    k = len(idx) - 1
    anim._func(k)  # move to the last frame: the crank pin follows the sweep
    A = sweep.position("crank", "A")[idx[k]]
    assert _has_circle_at(anim._fig.axes[0], A)


def test_animation_png_closes_its_figure_and_shows_the_driver_in_degrees(sweep):
    h = plotting.animation_png(sweep, max_frames=2, labels=False)
    assert not plt.fignum_exists(h.anim._fig.number)
    assert h.to_png().startswith(b"\x89PNG")
    h.anim._func(1)
    clock = [t.get_text() for t in h.anim._fig.axes[0].texts if t.get_text().startswith("t = ")]
    phi2 = np.degrees(sweep.q[h.anim.kinbook_indices[1], 5])  # the crank's angle, driven
    assert clock and f"    φ₂ = {phi2:.4g}°" in clock[0], clock


def _overlays(anim):
    """The overlay text of every frame of an animation, frame by frame."""
    texts = []
    for k in range(len(anim.kinbook_indices)):
        anim._func(k)
        texts += [t.get_text() for t in anim._fig.axes[0].texts if t.get_text().startswith("t = ")]
    return texts


def _read(deg):
    """An angle as the text gives it, to 4 significant digits, in [0°, 360°): Python's floor modulo, not kinbook."""
    return f"{round(deg, 6) % 360:.4g}"


def test_animation_reads_a_crank_past_a_full_turn_in_0_to_360_degrees():
    # example 2's crank turns from φ₂ = 45° once round to 405°: from frame 21 (360°) on, the same angles as 0°, 15°…
    m = _example("ch13_example2")
    sweep = m.simulate(np.linspace(0.0, 2 * np.pi / 100, 73))
    anim = plotting.animate(sweep, every=3, labels=False)
    A, O = sweep.position("crank", "A"), sweep.position("crank", "OA")
    # the crank's direction O_A → A measured from the geometry, never from the driver's function
    phi2 = [np.degrees(np.arctan2(*(A[i] - O[i])[::-1])) for i in anim.kinbook_indices]
    texts = _overlays(anim)
    assert len(texts) == 25 and np.degrees(sweep.q[-1, 5]) > 404.9  # the sweep went past a full turn
    shown = [float(re.search("φ₂ = (-?[0-9.]+)°", t).group(1)) for t in texts]
    assert shown[-1] == 45 and shown[21] == 0 and max(shown) == 345  # never 360°, 375° or 405°
    assert [f"φ₂ = {_read(d)}°" in t for d, t in zip(phi2, texts)] == [True] * 25, texts


def test_animation_keeps_the_sign_of_an_angle_that_swings_about_zero():
    # the steering pinion turns φ₂ = 0.5 sin 2t: about ±28.6°, read signed (−28.65°, not 331.4°)
    m = _example("steering")
    sweep = m.simulate(np.linspace(0.0, np.pi, 25))
    anim = plotting.animate(sweep, labels=False)
    texts = _overlays(anim)
    phi2 = np.degrees(sweep.coordinate("phi2")[anim.kinbook_indices])
    assert phi2.min() < -28 and phi2.max() > 28
    for d, t in zip(phi2, texts):
        assert f"φ₂ = {round(d, 6) + 0.0:.4g}°" in t, t


# --------------------------------------------------------------------------------------------- explorer
def _residual(title):
    m = re.search(r"max\|Φ\| [=<] ([0-9.e+-]+)", title)
    return float(m.group(1)) if m else None


# example 1 (crank 2, coupler 6, rocker 3, ground 3) stops where coupler and rocker fold: |A − O_B| = 6 − 3,
# 2² + 3² − 12 cos φ₂ = 3², so φ₂ = arccos(1/3) = 70.53° or 360° − 70.53° = 289.47°
LIMITS = (np.degrees(np.arccos(1 / 3)), 360 - np.degrees(np.arccos(1 / 3)))


def _stops_at(text):
    return float(re.search(r"stops at φ₂ = ([0-9.]+)°", text).group(1))


def test_explorer_static_marks_the_reachable_range_and_shows_the_limits(four_bar):
    m, _ = four_bar
    values = [0.5, 1.5, 3 * np.pi / 4, 4.5, 5.6]  # reachable crank angles: about 1.24 ... 5.04
    fig = plotting.explorer(m, values=values, static=True)
    axes = [ax for ax in fig.axes if ax.get_visible()]
    titles = [ax.get_title() for ax in axes]
    assert len(titles) == 5
    assert titles[2].startswith("$\\varphi_{2}$ = 135°")  # in degrees
    for v, title in zip(values, titles):
        if 1.3 < v < 5.0:
            assert _residual(title) < 1e-9, title
            assert "cond" in title
        else:
            assert "does not assemble" in title and _residual(title) is None
            limit = LIMITS[0] if v < 1 else LIMITS[1]
            assert abs(_stops_at(title) - limit) < 0.01, title
    # past the dead point the panel shows the limit configuration: the crank pin A at φ₂ = 289.47°
    A = 2 * np.array([np.cos(np.radians(LIMITS[1])), np.sin(np.radians(LIMITS[1]))])
    assert _has_circle_at(axes[4], A, tol=1e-3)
    same = plotting.explorer(m, values=np.degrees(values), degrees=True, static=True)
    assert [ax.get_title() for ax in same.axes if ax.get_visible()] == titles


def test_explorer_reads_angles_beyond_a_turn_in_0_to_360_degrees():
    # example 2's crank turns fully: 400° and −30° are reached by continuation from 45° and read 40° and 330°
    m = _example("ch13_example2")
    fig = plotting.explorer(m, values=[-30, 100, 400], degrees=True, static=True)
    titles = [ax.get_title() for ax in fig.axes if ax.get_visible()]
    assert [t.split("\n")[0] for t in titles] == [f"$\\varphi_{{2}}$ = {_read(d)}°" for d in (-30, 100, 400)]
    pytest.importorskip("ipywidgets")
    box = plotting.explorer(m, values=np.radians([-30, 400]), static=False)
    box.kinbook_slider.value = 390.0
    assert "φ₂ = 30°: max|Φ|" in box.kinbook_status.value
    assert box.kinbook_slider.readout is False  # its own readout would say 390


def test_explorer_widget_works_in_degrees_and_shows_the_limit(four_bar):
    pytest.importorskip("ipywidgets")
    m, _ = four_bar
    box = plotting.explorer(m, values=[1.0, 5.5], static=False)
    slider, status = box.kinbook_slider, box.kinbook_status
    assert (slider.min, slider.max, slider.value) == pytest.approx((np.degrees(1.0), np.degrees(5.5), 135.0))
    assert "φ₂ = 135°: max|Φ|" in status.value and "(regular)" in status.value
    slider.value = 285.0  # near the dead point: still assembles, Φ_q badly conditioned
    assert "φ₂ = 285°: max|Φ|" in status.value
    slider.value = 300.0  # a jump past the dead point: the limit configuration, and where it is
    assert "does not assemble</b> at φ₂ = 300°" in status.value
    assert abs(_stops_at(status.value) - LIMITS[1]) < 0.01
    # beside a condition number in the thousands the limit is called near-singular, never "regular"
    cond = float(re.search(r"cond\(Φ<sub>q</sub>\) = ([0-9.e+]+)", status.value).group(1))
    assert cond > 1e3 and "(regular)" not in status.value and "near-singular" in status.value
    slider.value = 200.0  # from the limit back into the range
    assert "φ₂ = 200°: max|Φ|" in status.value


def test_explorer_names_an_unknown_driver(four_bar):
    m, _ = four_bar
    with pytest.raises(InputError, match="no driver 'motor'.*'driver 1'"):
        plotting.explorer(m, driver="motor", static=True)


# --------------------------------------------------------------------------------------------- drawings by class
class _Slot(planar.Constraint):
    """Pin P of body i in a circular slot of radius ρ about C of body j: a type without a drawing of its own."""

    type_name = "test-plot-slot"
    n_eq = 1
    points = {"pin": "i", "centre": "j"}
    numbers = ("radius",)

    def phi(self, Q, t=None):
        d = self.point(Q, "pin") - self.point(Q, "centre")
        return [d.dot(d) - self.radius**2]


def _slot_mechanism():
    m = Mechanism("slot")
    m.add_body("ground", points={"O": (0, 0), "C": (1, 0)})
    m.add_body("bar", points={"O": (0, 0), "P": (2, 0)}, q0=(0, 0, 0.6))
    m.add(Ground("ground"))
    m.add(Revolute("ground", "bar", point="O"))
    m.add(_Slot("bar", "ground", pin="P", centre="C", radius=1.5))
    return m


def test_a_type_without_a_drawing_shows_the_points_it_names_joined():
    m = _slot_mechanism()
    q = m.solve_position(0.0)
    ax = plotting.draw(m, q)
    P, C = m.point_position(q, "bar", "P"), m.point_position(q, "ground", "C")
    assert _lines_through(ax, [P, C]) and _has_circle_at(ax, P) and _has_circle_at(ax, C)


def test_a_drawing_registered_for_a_class_draws_it_and_its_subclasses():
    class Bigger(_Slot):  # no type name of its own: not registered, drawn like its base
        pass

    calls = []

    @plotting.drawing_for(_Slot)
    class SlotDrawing(plotting.JointDrawing):
        def __init__(self, ax, c, scene):
            calls.append(type(c))
            (line,) = ax.plot([], [], ":")
            self.artists = [line]

    try:
        m = _slot_mechanism()
        m.remove(m.constraints[-1].name)
        m.add(Bigger("bar", "ground", pin="P", centre="C", radius=1.5))
        ax = plotting.draw(m, m.solve_position(0.0))
        assert calls == [Bigger]
        assert not _lines_through(ax, [m.point_position(m.q0, "bar", "P"), m.point_position(m.q0, "ground", "C")])
    finally:
        from kinbook.planar.plotting import joints

        del joints._DRAWINGS[_Slot]
