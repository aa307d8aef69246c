"""The 3D drawing and animation put their artists where the mechanism's points are."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from kinbook import examples  # noqa: E402
from kinbook.errors import InputError  # noqa: E402
from kinbook.spatial.plotting import animate, draw  # noqa: E402


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
