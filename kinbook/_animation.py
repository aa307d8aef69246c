"""Animations that play inside a notebook, for the planar and the spatial plotting modules.

matplotlib's ``to_jshtml`` names the player's HTML elements and JavaScript objects with a random
``uuid4``, so a notebook re-executed without any change still differs in every animation (megabytes of
diff in a stored notebook). :class:`AnimationHTML` replaces that name with a digest of the animation's
own content: the same frames give the same HTML, and two different animations in one notebook still get
different names.
"""

from __future__ import annotations

import hashlib
import re

__all__ = ["AnimationHTML"]

_PLAYER_ID = re.compile(r'id="_anim_img([0-9a-f]+)"')
_ICON_FONT = re.compile(r'<link rel="stylesheet"\s*href="[^"]*font-awesome[^"]*">')
# The player's buttons are Font Awesome icons loaded from a CDN: without internet (an HTML export opened offline,
# a lab without network) they are blank. Plain text symbols need no font and no network.
_ICONS = {"fa fa-minus": "−", "fa fa-fast-backward": "⏮", "fa fa-step-backward": "◂", "fa fa-play fa-flip-horizontal": "◀",
          "fa fa-pause": "⏸", "fa fa-play": "▶", "fa fa-step-forward": "▸", "fa fa-fast-forward": "⏭", "fa fa-plus": "+"}


def _offline_buttons(html):
    html = _ICON_FONT.sub("", html)
    for cls, text in _ICONS.items():
        html = html.replace(f'<i class="{cls}"></i>', f"<span>{text}</span>")
    return html


def stable_jshtml(anim, frame_format="png"):
    """``anim.to_jshtml()`` with frames stored as ``frame_format`` ("png" or "jpeg"), a player id that depends
    only on the content, and buttons drawn with text symbols instead of a web icon font (they show offline)."""
    from matplotlib import rc_context

    with rc_context({"animation.frame_format": frame_format}):
        html = _offline_buttons(anim.to_jshtml())
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
