"""The 3D drawing and animation put their artists where the mechanism's points are."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from kinbook import examples  # noqa: E402
from kinbook.errors import InputError  # noqa: E402
from kinbook.spatial.plotting import animate, animation_png, draw  # noqa: E402


@pytest.fixture(scope="module")
def fourbar():
    mech = examples.load("spatial_fourbar")
    return mech, mech.simulate(np.linspace(0, 1, 25))


def line_points(line):
    x, y, z = line.get_data_3d()
    return np.column_stack([x, y, z])


def test_draw_puts_every_body_line_through_its_points(fourbar):
    mech, res = fourbar
    q = res.q[5]
    d = draw(mech, q, frames=True, labels=True)
    try:
        assert set(d.lines) == {b.name for b in mech.bodies}
        for body in mech.bodies:
            expected = np.array([mech.point_position(q, body.name, p) for p in body.points])
            np.testing.assert_allclose(line_points(d.lines[body.name]), expected, atol=1e-12)
            # the ζ axis of each body's frame points along A[:, 2]
            zeta = line_points(d.frames[body.name][2])
            np.testing.assert_allclose(zeta[1] - zeta[0], d.frame_size * mech.A(q, body.name)[:, 2], atol=1e-12)
        assert d.lines["ground"].get_linestyle() == "--"
        d.ax.figure.canvas.draw()
    finally:
        plt.close("all")


def test_animation_frames_follow_the_sweep(fourbar):
    mech, res = fourbar
    anim = animate(res, every=3, frames=True)
    try:
        for k in (0, 2, 5):
            anim.update_frame(k)
            expected = res.position("coupler", "A"), res.position("coupler", "B")
            pts = line_points(anim.drawing.lines["coupler"])
            np.testing.assert_allclose(pts, [expected[0][3 * k], expected[1][3 * k]], atol=1e-12)
        anim.drawing.ax.figure.canvas.draw()
    finally:
        plt.close("all")


def test_animation_png_is_reproducible_with_the_paths_drawn(fourbar):
    mech, res = fourbar
    h = animation_png(res, max_frames=5, trace=[("coupler", "B")])
    fig = h.anim.drawing.ax.figure
    assert not plt.fignum_exists(fig.number)  # closed: the notebook shows only the animation
    assert repr(h) == "<Animation: 5 frames, 40 ms each>"  # 25 instants, every 5th
    png = h.to_png()
    assert png.startswith(b"\x89PNG") and png == animation_png(res, max_frames=5, trace=[("coupler", "B")]).to_png()
    path = [line for line in h.anim.drawing.ax.lines if line.get_color() == "tab:purple"]
    np.testing.assert_allclose(line_points(path[0]), res.position("coupler", "B"))


def test_the_box_has_the_drawing_s_proportions_with_equal_scales(fourbar):
    mech, res = fourbar
    d = draw(mech, res.q[0])
    ax = d.ax
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    np.testing.assert_allclose(ax.get_box_aspect() / ax.get_box_aspect().max(), spans / spans.max(), rtol=1e-9)
    pts = np.vstack([line_points(line) for line in d.lines.values()])
    for k, lim in enumerate((ax.get_xlim(), ax.get_ylim(), ax.get_zlim())):
        assert lim[0] < pts[:, k].min() and pts[:, k].max() < lim[1]
    plt.close("all")


def test_vectors_drawn_later_keep_equal_scales(fourbar):
    from kinbook.spatial.plotting import draw_vector, equal_scales

    mech, res = fourbar
    ax = draw(mech, res.q[0]).ax
    draw_vector(ax, [0, 0, 0], [0, 0, 6.0])  # taller than the mechanism: the limits grow along z
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    assert ax.get_zlim()[1] >= 6.0
    np.testing.assert_allclose(ax.get_box_aspect() / ax.get_box_aspect().max(), spans / spans.max(), rtol=1e-9)
    ax.set_xlim(-10, 10)
    equal_scales(ax, zoom=1.2)
    spans[0] = 20
    np.testing.assert_allclose(ax.get_box_aspect() / ax.get_box_aspect().max(), spans / spans.max(), rtol=1e-9)
    plt.close("all")


def test_draw_rejects_a_batch_or_a_2d_axes(fourbar):
    mech, res = fourbar
    with pytest.raises(InputError, match="one configuration"):
        draw(mech, res.q[:2])
    fig, ax = plt.subplots()
    try:
        with pytest.raises(InputError, match="3D axes"):
            draw(mech, res.q[0], ax=ax)
    finally:
        plt.close("all")


# ------------------------------------------------------------------------------------------- draw_vector, draw_frame
from kinbook.spatial import A_from_p, draw_frame, draw_vector, p_from_axis_angle  # noqa: E402


@pytest.fixture
def ax3d():
    ax = plt.figure().add_subplot(projection="3d")
    yield ax
    plt.close("all")


def projected(ax, xyz):
    """Display coordinates of 3D points, through the axes' current projection."""
    from mpl_toolkits.mplot3d import proj3d

    xs, ys, _ = proj3d.proj_transform(*np.asarray(xyz, float).T, ax.get_proj())
    return ax.transData.transform(np.column_stack([xs, ys]))


def test_draw_vector_goes_from_origin_to_origin_plus_vector(ax3d):
    origin, vector = np.array([1.0, -2.0, 0.5]), np.array([0.3, 2.0, -1.5])
    v = draw_vector(ax3d, origin, vector, label="$d$", color="tab:purple", label_at=1.0, label_offset=[0, 0, 0.1])
    np.testing.assert_allclose(v.arrow.get_data_3d(), [origin, origin + vector], atol=1e-15)
    np.testing.assert_allclose(v.label.get_position_3d(), origin + vector + [0, 0, 0.1], atol=1e-15)
    assert v.label.get_text() == "$d$"
    assert v.arrow in ax3d.get_children()
    # the axis limits contain the arrow
    for k, (lo, hi) in enumerate((ax3d.get_xlim(), ax3d.get_ylim(), ax3d.get_zlim())):
        assert lo <= min(origin[k], origin[k] + vector[k]) and max(origin[k], origin[k] + vector[k]) <= hi
    # once drawn, the 2D arrow joins the projections of the two 3D ends (FancyArrowPatch keeps its ends in
    # _posA_posB; its stroked path stops short of the tip by the line width, so the path is not compared)
    ax3d.figure.canvas.draw()
    ends_2d = ax3d.transData.transform(np.array(v.arrow._posA_posB))
    np.testing.assert_allclose(ends_2d, projected(ax3d, [origin, origin + vector]), atol=1e-6)
    path = v.arrow.get_path().transformed(v.arrow.get_transform()).vertices
    assert np.min(np.linalg.norm(path - ends_2d[0], axis=1)) < 1e-6


def test_draw_frame_axes_are_the_scaled_columns_of_A(ax3d):
    A = A_from_p(p_from_axis_angle([1, 2, 2], 1.1))
    origin = np.array([0.5, 0.0, -1.0])
    f = draw_frame(ax3d, origin, A, size=0.8, label="i")
    assert len(f.axes) == 3 and len(f.labels) == 3
    for k, arrow in enumerate(f.axes):
        start, end = arrow.get_data_3d()
        np.testing.assert_allclose(start, origin, atol=1e-15)
        np.testing.assert_allclose(end - start, 0.8 * A[:, k], atol=1e-15)
    assert [t.get_text() for t in f.labels] == [r"$\xi_{i}$", r"$\eta_{i}$", r"$\zeta_{i}$"]
    assert [a.get_edgecolor() for a in f.axes] == [matplotlib.colors.to_rgba(c)
                                                     for c in ("tab:red", "tab:green", "tab:blue")]
    ax3d.figure.canvas.draw()


def test_draw_frame_without_labels(ax3d):
    f = draw_frame(ax3d, [0, 0, 0], np.eye(3), axis_labels=False)
    assert f.labels == []
    np.testing.assert_allclose([a.get_data_3d()[1] for a in f.axes], np.eye(3))


@pytest.mark.parametrize("args, kwargs, match", [
    (([0, 0], [1, 0, 0]), {}, r"`origin` must have shape \(3,\), got \(2,\)"),
    (([0, 0, 0], [[1, 0, 0]]), {}, r"`vector` must have shape \(3,\), got \(1, 3\)"),
    (([0, 0, 0], [1, np.nan, 0]), {}, r"`vector` must be finite"),
    (([0, 0, 0], "abc"), {}, r"`vector` must be three numbers"),
    (([0, 0, 0], [1, 0, 0]), {"label_offset": [1, 2]}, r"`label_offset` must have shape"),
])
def test_draw_vector_rejects_bad_input(ax3d, args, kwargs, match):
    with pytest.raises(InputError, match=match):
        draw_vector(ax3d, *args, **kwargs)


@pytest.mark.parametrize("origin, A, kwargs, match", [
    ([0, 0, 0], np.eye(2), {}, r"`A` must have shape \(\.\.\., 3, 3\)"),
    ([0, 0, 0], 2 * np.eye(3), {}, r"`A` is not a rotation matrix"),
    ([0, 0, 0], np.diag([1.0, 1.0, -1.0]), {}, r"`A` is not a rotation matrix: det A = -1"),
    ([0, 0, 0], np.stack([np.eye(3)] * 2), {}, r"`A` must be one rotation matrix of shape \(3, 3\)"),
    ([0, 0], np.eye(3), {}, r"`origin` must have shape \(3,\)"),
    ([0, 0, 0], np.eye(3), {"size": -1}, r"`size` must be a positive number, got -1"),
    ([0, 0, 0], np.eye(3), {"names": ("x", "y")}, r"`names` must have 3 entries"),
])
def test_draw_frame_rejects_bad_input(ax3d, origin, A, kwargs, match):
    with pytest.raises(InputError, match=match):
        draw_frame(ax3d, origin, A, **kwargs)


def test_vector_and_frame_need_a_3d_axes():
    fig, ax = plt.subplots()
    try:
        with pytest.raises(InputError, match="`ax` must be a 3D axes"):
            draw_vector(ax, [0, 0, 0], [1, 0, 0])
        with pytest.raises(InputError, match="`ax` must be a 3D axes"):
            draw_frame(ax, [0, 0, 0], np.eye(3))
    finally:
        plt.close("all")


def test_a_zero_vector_is_accepted(ax3d):
    v = draw_vector(ax3d, [1, 1, 1], [0, 0, 0])
    np.testing.assert_allclose(v.arrow.get_data_3d(), [[1, 1, 1], [1, 1, 1]])
    ax3d.figure.canvas.draw()
