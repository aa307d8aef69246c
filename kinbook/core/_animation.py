"""Animations that play in every notebook front end: an animated PNG (APNG), which needs no trust.

matplotlib's notebook player (``to_jshtml``) is HTML with JavaScript. A front end runs a notebook's stored
JavaScript only when the notebook is trusted: opened in plain JupyterLab, VS Code, JupyterLite (the live site)
or from a copy handed out by an LMS, the player showed a broken image, a dead slider and, in JupyterLite,
stray commas. An animated PNG is an image: every front end shows ``image/png`` outputs untrusted, the book
site and ``nbconvert --to html`` write it as an ``<img>``, and every current browser plays it, looping.

The frames are rendered by blitting (:func:`render_frames`): the still part of the figure is drawn once, then
for each frame only the artists the animation moves (those its update function returns, as when blitting on
screen) — several times faster than a full redraw per frame. Frames that do not change are merged by the PNG
writer, and each frame stores only the box that changed, so a stored animation stays small. The same frames
give the same bytes: no random ids, no time stamps.
"""

from __future__ import annotations

from io import BytesIO

import numpy as np

from .atomic import atomic_write

__all__ = ["Animation", "render_frames", "apng", "degrees_as_read", "swings_about_zero"]


def degrees_as_read(radians, digits=4, signed=None):
    """Angles (radians) as a person reads them in an overlay or a title: degrees in [0°, 360°), the range the
    book gives a body's angle in (φ₄ = 240.8° in §13.5's example 1, never −119.2° or 600.8°), as text.

    A driver that turns a crank on past a full turn reads 45° again, not 405°. A series of angles that swings
    about zero within ±180° (a steering angle, 0.5 sin 2t) keeps its sign, as the text writes it. The text has
    ``digits`` significant digits and is checked after rounding, so an angle a hair below 360° reads 0°, not
    360°.

    Parameters
    ----------
    radians : array_like
        One angle or a series of them (one animation's, one explorer's): the range is chosen for the series.
    digits : int
    signed : bool, optional
        Read in (−180°, 180°) instead of [0°, 360°); default: when the series swings about zero as above.

    Returns
    -------
    list of str
        One text per angle, without the degree sign.
    """
    deg = _degrees(radians)
    if signed is None:
        signed = swings_about_zero(radians)
    lo = -180.0 if signed else 0.0
    out = []
    for d in deg:
        d = (d - lo) % 360.0 + lo
        text = f"{d:.{digits}g}"
        if float(text) == 0.0 or float(text) >= 360.0:  # −0, or 359.99… rounded to 360 at this precision
            text = "0"
        out.append(text)
    return out


def swings_about_zero(radians):
    """Whether a series of angles is read signed (:func:`degrees_as_read`): all within ±180°, some below zero."""
    deg = _degrees(radians)
    return bool(np.all(np.abs(deg) < 180.0) and np.any(deg < 0.0))


def _degrees(radians):
    """Degrees to a millionth (round-off is not a sign: −1e-12 is 0)."""
    return np.round(np.degrees(np.atleast_1d(np.asarray(radians, dtype=float))), 6) + 0.0


def _agg_canvas(fig):
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # import time: matplotlib only when needed

    if not isinstance(fig.canvas, FigureCanvasAgg):  # a closed pyplot figure: savefig would do the same
        FigureCanvasAgg(fig)
    return fig.canvas


def render_frames(anim):
    """Every frame of a FuncAnimation as an RGB array (height, width, 3) of uint8, as ``savefig`` draws it.

    An animation that blits (``blit=True``, its update function returning the artists it moves) is drawn
    without those artists once; each frame then restores that picture and draws only them, in z-order. Any
    other animation is drawn whole for every frame.
    """
    fig = anim._fig
    canvas = _agg_canvas(fig)
    anim._draw_was_started = True  # (matplotlib warns about an animation deleted "without rendering anything")
    blit = bool(getattr(anim, "_blit", False))
    background = None
    frames = []
    for data in anim.new_frame_seq():
        moving = anim._func(data, *anim._args) if anim._args else anim._func(data)
        moving = sorted(moving or [], key=lambda a: a.get_zorder()) if blit else []
        if not moving:
            canvas.draw()
        else:
            if background is None:
                shown = [a.get_visible() for a in moving]
                for a in moving:
                    a.set_visible(False)
                canvas.draw()
                background = canvas.copy_from_bbox(fig.bbox)
                for a, visible in zip(moving, shown):
                    a.set_visible(visible)
            canvas.restore_region(background)
            for a in moving:
                a.axes.draw_artist(a)
        frames.append(np.asarray(canvas.buffer_rgba())[..., :3].copy())
    return frames


def apng(frames, interval, colors=None):
    """The frames as one looping animated PNG (bytes).

    Parameters
    ----------
    frames : list of ndarray, shape (height, width, 3), uint8
    interval : float
        Milliseconds per frame.
    colors : int, optional
        Reduce every frame to one shared palette of this many colours (at most 256; no dithering): smaller for
        shaded 3D views. The palette is taken from the first, middle and last frames side by side.
    """
    from PIL import Image  # import time: PIL only when needed

    images = [Image.fromarray(np.ascontiguousarray(f), "RGB") for f in frames]
    if colors:
        picks = [images[0], images[len(images) // 2], images[-1]]
        sheet = Image.new("RGB", (sum(i.width for i in picks), max(i.height for i in picks)), "white")
        x = 0
        for i in picks:
            sheet.paste(i, (x, 0))
            x += i.width
        palette = sheet.quantize(colors=min(int(colors), 256), method=Image.Quantize.MEDIANCUT)
        images = [i.quantize(palette=palette, dither=Image.Dither.NONE) for i in images]
    out = BytesIO()
    images[0].save(out, format="PNG", save_all=True, append_images=images[1:], duration=float(interval), loop=0,
                   compress_level=9)
    return out.getvalue()


class Animation:
    """A matplotlib animation that shows itself in a notebook as an animated PNG (``_repr_png_``).

    Attributes
    ----------
    anim : matplotlib.animation.FuncAnimation
    colors : int or None
        Palette size of the stored frames (None: full colour).
    """

    def __init__(self, anim, colors=None):
        self.anim = anim
        self.colors = colors
        self._png = None

    @property
    def interval(self):
        """Milliseconds per frame."""
        return float(self.anim._interval)

    def frames(self):
        """The frames as RGB arrays (rendered again at each call)."""
        return render_frames(self.anim)

    def to_png(self):
        """The animated PNG (computed once)."""
        if self._png is None:
            self._png = apng(self.frames(), self.interval, self.colors)
        return self._png

    def save(self, path):
        """Write the animated PNG to ``path`` (a ``.png`` file any browser plays), whole or not at all."""
        atomic_write(path, self.to_png())

    def _repr_png_(self):
        return self.to_png()

    def __repr__(self):
        n = len(getattr(self.anim, "kinbook_indices", ()))
        return f"<Animation: {n} frames, {self.interval:g} ms each>"
