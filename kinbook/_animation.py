"""Animations that play inside a notebook, for the planar and the spatial plotting modules.

matplotlib's ``to_jshtml`` names the player's HTML elements and JavaScript objects with a random
``uuid4``, so a notebook re-executed without any change still differs in every animation (megabytes of
diff in a stored notebook). :class:`AnimationHTML` replaces that name with a digest of the animation's
own content: the same frames give the same HTML, and two different animations in one notebook still get
different names.

Rendering the frames is most of an animation's cost. matplotlib's player draws the whole figure for every
frame (axes, tick labels, every text); :class:`_BlitHTMLWriter` draws the still part once and then, for each
frame, only the artists the animation moves (those its update function returns, as for blitting on screen)
— several times faster, with the same HTML player.
"""

from __future__ import annotations

import base64
import hashlib
import re
from io import BytesIO
from pathlib import Path
from tempfile import TemporaryDirectory

__all__ = ["AnimationHTML"]

_PLAYER_ID = re.compile(r'id="_anim_img([0-9a-f]+)"')
_ICON_FONT = re.compile(r'<link rel="stylesheet"\s*href="[^"]*font-awesome[^"]*">')
# The player's buttons are Font Awesome icons loaded from a CDN: without internet (an HTML export opened offline,
# a lab without network) they are blank. Plain text symbols need no font and no network — as long as the fonts a
# browser already has draw them: the media symbols ⏮ ⏸ ⏭ (U+23ED–23F8) are missing from DejaVu, the fallback font
# of a Linux desktop, and showed as empty boxes; ⇤ ❚❚ ⇥ are in DejaVu Sans as in the Windows and macOS fonts.
_ICONS = {"fa fa-minus": "−", "fa fa-fast-backward": "⇤", "fa fa-step-backward": "◂", "fa fa-play fa-flip-horizontal": "◀",
          "fa fa-pause": "❚❚", "fa fa-play": "▶", "fa fa-step-forward": "▸", "fa fa-fast-forward": "⇥", "fa fa-plus": "+"}


def _offline_buttons(html):
    html = _ICON_FONT.sub("", html)
    for cls, text in _ICONS.items():
        html = html.replace(f'<i class="{cls}"></i>', f"<span>{text}</span>")
    return html


def _blit_writer_class():
    from matplotlib.animation import HTMLWriter
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.image import imsave

    class _BlitHTMLWriter(HTMLWriter):
        """matplotlib's HTML writer, with each frame rendered by blitting.

        The figure without the animation's moving artists is drawn once; every frame restores that picture
        and draws only the artists the update function returned (``anim._drawn_artists``, in z-order), then
        encodes the canvas as matplotlib's ``savefig`` would. An animation that does not blit, or a figure
        not on an Agg canvas, falls back to ``savefig`` per frame.
        """

        def __init__(self, anim, **kwargs):
            super().__init__(**kwargs)
            self.anim = anim
            self._background = None

        def _moving(self):
            artists = getattr(self.anim, "_drawn_artists", None) or []
            return sorted(artists, key=lambda a: a.get_zorder()) if getattr(self.anim, "_blit", False) else []

        def _plain(self, savefig_kwargs):
            """True when savefig would draw the figure as it is (Animation.save passes its face colour)."""
            from matplotlib.colors import same_color

            extra = set(savefig_kwargs) - {"facecolor", "transparent"}
            face = savefig_kwargs.get("facecolor", self.fig.get_facecolor())
            return not extra and not savefig_kwargs.get("transparent") and same_color(face, self.fig.get_facecolor())

        def grab_frame(self, **savefig_kwargs):
            moving = self._moving()
            if not (self.embed_frames and moving and self._plain(savefig_kwargs) and self.dpi == self.fig.dpi):
                return super().grab_frame(**savefig_kwargs)
            if self._hit_limit:
                return None
            canvas = self.fig.canvas
            if not isinstance(canvas, FigureCanvasAgg):
                return super().grab_frame(**savefig_kwargs)
            if self._background is None:
                shown = [a.get_visible() for a in moving]
                for a in moving:
                    a.set_visible(False)
                canvas.draw()
                self._background = canvas.copy_from_bbox(self.fig.bbox)
                for a, v in zip(moving, shown):
                    a.set_visible(v)
            canvas.restore_region(self._background)
            for a in moving:
                a.axes.draw_artist(a)
            f = BytesIO()
            imsave(f, canvas.buffer_rgba(), format=self.frame_format, origin="upper", dpi=self.fig.dpi)
            data = base64.encodebytes(f.getvalue()).decode("ascii")
            self._total_bytes += len(data)
            if self._total_bytes >= self._bytes_limit:
                self._hit_limit = True  # as matplotlib's writer: the frames beyond the size limit are dropped
            else:
                self._saved_frames.append(data)
            return None

    return _BlitHTMLWriter


def jshtml(anim):
    """The HTML player of a FuncAnimation, as ``anim.to_jshtml()`` makes it, with the frames rendered by
    blitting when the animation blits (:class:`_BlitHTMLWriter`) and without a full redraw between frames."""
    from matplotlib import cbook
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fps = 1000 / anim._interval
    mode = "loop" if getattr(anim, "_repeat", False) else "once"
    if not isinstance(anim._fig.canvas, FigureCanvasAgg):  # a closed pyplot figure: savefig would do the same
        FigureCanvasAgg(anim._fig)
    with TemporaryDirectory() as tmp:
        path = Path(tmp, "animation.html")
        writer = _blit_writer_class()(anim, fps=fps, embed_frames=True, default_mode=mode)
        # Animation.save redraws the whole figure after every frame (draw_idle) before the writer grabs it;
        # the writer draws what it needs itself.
        with cbook._setattr_cm(anim._fig.canvas, draw_idle=lambda *args, **kwargs: None):
            anim.save(str(path), writer=writer)
        return path.read_text()


def stable_jshtml(anim, frame_format="png"):
    """The animation's HTML player (:func:`jshtml`) with frames stored as ``frame_format`` ("png" or "jpeg"), a
    player id that depends only on the content, and buttons drawn with text symbols instead of a web icon font
    (they show offline)."""
    from matplotlib import rc_context

    with rc_context({"animation.frame_format": frame_format}):
        html = _offline_buttons(jshtml(anim))
    match = _PLAYER_ID.search(html)
    if match is None:  # a matplotlib whose template changed: keep its own id
        return html
    uid = match.group(1)
    digest = hashlib.sha1(html.replace(uid, "").encode()).hexdigest()[: len(uid)]
    return html.replace(uid, digest)


class AnimationHTML:
    """An animation that plays inside a notebook: ``_repr_html_`` is the animation's JavaScript player.

    Attributes
    ----------
    anim : matplotlib.animation.FuncAnimation
    frame_format : {"png", "jpeg"}
        How each frame is stored in the notebook (JPEG is several times smaller for shaded 3D views).
    """

    def __init__(self, anim, frame_format="png", frames=None):
        self.anim = anim
        self.frame_format = frame_format
        self.frames = frames
        self._html = None

    def to_html(self):
        """The player's HTML (computed once)."""
        if self._html is None:
            self._html = stable_jshtml(self.anim, self.frame_format)
        return self._html

    def _repr_html_(self):
        return self.to_html()

    def __repr__(self):
        n = self.frames if self.frames is not None else len(getattr(self.anim, "kinbook_indices", ()))
        return f"<AnimationHTML: {n} frames>"
