"""The notebooks' animation players: frames rendered by blitting look like matplotlib's own, drawn once."""

import base64
import io
import re

import numpy as np
import pytest

import kinbook

matplotlib = pytest.importorskip("matplotlib")
Image = pytest.importorskip("PIL.Image")


def _frames(html):
    data = re.findall(r'data:image/\w+;base64,([^"]+)"', html)
    return [np.asarray(Image.open(io.BytesIO(base64.b64decode(d)))).astype(int) for d in data]


@pytest.fixture(scope="module")
def sweep():
    m = kinbook.examples.load("ch13_example1")
    return m.simulate(np.linspace(0.0, 0.02, 25), on_failure="truncate")


def test_blitted_frames_match_matplotlibs_player(sweep):
    from matplotlib import rc_context

    from kinbook import _animation
    from kinbook.planar import plotting

    ours = _frames(_animation.jshtml(plotting.animation_html(sweep, every=4, trace=[("coupler", "B")]).anim))
    with rc_context({"animation.frame_format": "png"}):
        theirs = _frames(plotting.animation_html(sweep, every=4, trace=[("coupler", "B")]).anim.to_jshtml())
    assert len(ours) == len(theirs) == 7
    for a, b in zip(ours, theirs):
        assert a.shape == b.shape
        # the moving artists are drawn over the still ones; only pixels where they overlap may differ
        assert (np.abs(a - b).max(axis=-1) > 8).mean() < 1e-3
    assert np.abs(ours[0] - ours[-1]).max() > 0  # the frames do move


def test_the_still_part_is_drawn_once(sweep, monkeypatch):
    from matplotlib.figure import Figure

    from kinbook import _animation
    from kinbook.planar import plotting

    draws = []
    original = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda self, renderer: draws.append(1) or original(self, renderer))
    html = _animation.jshtml(plotting.animation_html(sweep, every=4).anim)
    assert len(_frames(html)) == 7 and len(draws) <= 2  # matplotlib's player draws the figure once per frame


def test_an_animation_that_does_not_blit_is_saved_frame_by_frame():
    from kinbook import _animation
    from kinbook.spatial import plotting

    m = kinbook.examples.load("spatial_fourbar")
    res = m.simulate(np.linspace(0.0, 0.1, 5))
    frames = _frames(_animation.stable_jshtml(plotting.animation_html(res, every=2).anim, "jpeg"))
    assert len(frames) == 3 and np.abs(frames[0] - frames[-1]).max() > 0
