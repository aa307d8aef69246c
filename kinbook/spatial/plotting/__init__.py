"""3D drawings and animations of spatial mechanisms with matplotlib (textbook §14.5), in the shape of
:mod:`kinbook.planar.plotting`: :mod:`~.scene` (a configuration, the book's arrows and frames, axes set up for
them), :mod:`~.animation` (a sweep), :mod:`~._common` (what they share).

Each body is drawn as the polyline through its named points (in the order they were declared), with a
marker at every point; a body with a :class:`~kinbook.spatial.Ground` constraint is drawn dashed and grey.
Optionally each body's local axes ξ, η, ζ are drawn at its origin (red, green, blue).

:func:`draw_vector` and :func:`draw_frame` add a single arrow (s_i, d, r_i …) or a frame (the axes of a rotation
matrix A at a point) to any 3D axes, e.g. on top of a :func:`draw` (textbook §14.1, §14.4).

In a notebook::

    result = mech.simulate(np.linspace(0, 1, 61))
    animation_png(result)           # an animated PNG: plays in every notebook front end, trusted or not
"""

from . import animation, scene
from ._common import equal_scales
from .animation import animate, animation_png
from .scene import Drawing, DrawnFrame, DrawnVector, draw, draw_frame, draw_vector, joint_figure, make_3d_axes

__all__ = ["Drawing", "draw", "animate", "animation_png", "equal_scales", "make_3d_axes", "joint_figure", "DrawnVector",
           "DrawnFrame", "draw_vector", "draw_frame"]
