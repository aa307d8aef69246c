"""The notebooks' animations: an animated PNG (no notebook trust needed), frames rendered by blitting that look
like matplotlib's own, reproducible bytes."""

import base64
import io
import re

import numpy as np
import pytest

import kinbook

matplotlib = pytest.importorskip("matplotlib")
Image = pytest.importorskip("PIL.Image")
ImageSequence = pytest.importorskip("PIL.ImageSequence")


def _html_frames(html):
    data = re.findall(r'data:image/\w+;base64,([^"]+)"', html)
    return [np.asarray(Image.open(io.BytesIO(base64.b64decode(d))).convert("RGB")).astype(int) for d in data]


def _png_frames(png):
    """(frames as RGB arrays, durations in ms, loop count) of an animated PNG, decoded by Pillow."""
    im = Image.open(io.BytesIO(png))
    assert im.format == "PNG"
    frames, durations = [], []
    for frame in ImageSequence.Iterator(im):
        frames.append(np.asarray(frame.convert("RGB")).astype(int))
        durations.append(frame.info.get("duration"))
    return frames, durations, im.info.get("loop")


@pytest.fixture(scope="module")
def sweep():
    m = kinbook.examples.load("ch13_example1")
    return m.simulate(np.linspace(0.0, 0.02, 25), on_failure="truncate")


def test_blitted_frames_match_matplotlibs_player(sweep):
    from matplotlib import rc_context

    from kinbook.core import _animation
    from kinbook.planar import plotting

    ours = _animation.render_frames(plotting.animation_png(sweep, every=4, trace=[("coupler", "B")]).anim)
    with rc_context({"animation.frame_format": "png"}):
        theirs = _html_frames(plotting.animation_png(sweep, every=4, trace=[("coupler", "B")]).anim.to_jshtml())
    assert len(ours) == len(theirs) == 7
    for a, b in zip(ours, theirs):
        assert a.shape == b.shape
        # the moving artists are drawn over the still ones; only pixels where they overlap may differ
        assert (np.abs(a.astype(int) - b).max(axis=-1) > 8).mean() < 1e-3
    assert np.abs(ours[0].astype(int) - ours[-1]).max() > 0  # the frames do move


def test_the_still_part_is_drawn_once(sweep, monkeypatch):
    from matplotlib.figure import Figure

    from kinbook.core import _animation
    from kinbook.planar import plotting

    draws = []
    original = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda self, renderer: draws.append(1) or original(self, renderer))
    frames = _animation.render_frames(plotting.animation_png(sweep, every=4).anim)
    assert len(frames) == 7 and len(draws) <= 2  # matplotlib's player draws the figure once per frame


def test_the_animated_png_holds_every_frame_and_loops(sweep):
    from kinbook.planar import plotting

    h = plotting.animation_png(sweep, every=4, interval=90, colors=None)
    rendered = h.frames()
    frames, durations, loop = _png_frames(h.to_png())
    assert loop == 0  # forever
    # identical frames may be merged (their durations added); the time line is the rendered one
    assert sum(durations) == pytest.approx(90 * len(rendered))
    shown = [f for f, d in zip(frames, durations) for _ in range(round(d / 90))]
    assert len(shown) == len(rendered)
    for a, b in zip(shown, rendered):
        assert np.array_equal(a, b)  # full colour: lossless
    # with a palette, every frame stays close to the rendered one
    frames, durations, _ = _png_frames(plotting.animation_png(sweep, every=4, interval=90).to_png())
    shown = [f for f, d in zip(frames, durations) for _ in range(round(d / 90))]
    assert len(shown) == len(rendered)
    for a, b in zip(shown, rendered):
        assert (np.abs(a - b).max(axis=-1) > 24).mean() < 0.01


def test_an_animation_shows_itself_as_an_image_only(sweep):
    """A notebook stores it as image/png, which every front end shows untrusted: no HTML, no script."""
    from IPython.core.interactiveshell import InteractiveShell

    from kinbook.planar import plotting

    h = plotting.animation_png(sweep, max_frames=3)
    data, _ = InteractiveShell.instance().display_formatter.format(h)
    assert set(data) == {"image/png", "text/plain"}
    assert data["text/plain"] == repr(h) == "<Animation: 3 frames, 40 ms each>"
    # the same sweep gives the same bytes (a re-executed notebook changes only where its content does)
    assert plotting.animation_png(sweep, max_frames=3).to_png() == h.to_png()
    assert plotting.animation_png(sweep, max_frames=4).to_png() != h.to_png()


def test_an_animation_that_does_not_blit_is_drawn_frame_by_frame():
    from kinbook.spatial import plotting

    m = kinbook.examples.load("spatial_fourbar")
    res = m.simulate(np.linspace(0.0, 0.1, 5))
    frames = plotting.animation_png(res, every=2).frames()
    assert len(frames) == 3 and np.abs(frames[0].astype(int) - frames[-1]).max() > 0


def test_overlay_angles_read_in_0_to_360_degrees_and_never_360():
    from kinbook.core._animation import degrees_as_read

    turn = np.radians([45, 405, 765, 360, -90, 289.47, 359.99999, -1e-10])  # a crank's series
    assert degrees_as_read(turn) == ["45", "45", "45", "0", "270", "289.5", "0", "0"]
    swing = 0.5 * np.sin(2 * np.array([0.0, np.pi / 4, 3 * np.pi / 4, np.pi]))  # a steering wheel: ±28.65°
    assert degrees_as_read(swing) == ["0", "28.65", "-28.65", "0"]
    assert degrees_as_read(np.radians(-30), signed=False) == ["330"]
    assert degrees_as_read(np.radians(-30)) == ["-30"]  # alone, within ±180°: read as it swings
