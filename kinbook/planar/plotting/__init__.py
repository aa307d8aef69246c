"""Drawings, plots and animations of planar mechanisms (textbook chapter 13).

The textbook is printed without its figures; these drawings replace them. Everything here uses matplotlib
only, imports it lazily, and changes no global pyplot state beyond creating figures::

    from kinbook.planar import plotting
    ax = plotting.draw(mech, q, frames=True, vectors=[("crank", "A")])

One module per job: :mod:`~kinbook.planar.plotting.scene` (a configuration), :mod:`~.plots` (paths and
time histories of a sweep), :mod:`~.animation`, :mod:`~.explore` (the driver moved by hand), and
:mod:`~.joints`, which says how each constraint type is drawn (drawings keyed by class, a default for
types without one).

Conventions of the drawings
---------------------------
* A body with two points is a thick line between them; with more points, a translucent convex polygon; the
  ground (a body fixed by constraints of its own: a ``ground`` constraint or three simple constraints) is
  drawn as hatched supports at its joint points.
* Revolute joints are small white circles, translational joints a slider box on its guide, revolute-revolute
  joints the (massless) link between their two points, revolute-translational joints a pin in a slot, gears
  and pinions their dashed pitch circles with a spoke that shows their rotation; a type without a drawing of
  its own shows the points it names, joined, with a pin at each.
* Bodies carry the book's numbers ("1", "2", …: the subscript of x_i, y_i, φ_i) in a circle; points carry
  their names (``OA`` is written O_A).

Every drawing is made of artists that are created once and then moved, so :func:`animate` only updates data.

In notebooks
------------
:func:`animation_png` and the still figure of :func:`explorer` render themselves (the figures are closed so
they are not shown twice). :func:`explorer` returns a live ipywidgets slider when a kernel is running — also
under nbval, whose stored output would then be a widget model; a notebook checked by nbval should call
``explorer(mech, static=True)`` (or tag the cell ``nbval-ignore-output``).
"""

from . import animation, explore, joints, plots, scene
from .animation import MAX_FRAMES, animate, animation_png
from .explore import explorer
from .joints import JointDrawing, drawing_for
from .plots import plot_history, plot_trajectories
from .scene import draw, draw_frame, draw_point_vectors

__all__ = [
    "draw",
    "draw_frame",
    "draw_point_vectors",
    "plot_trajectories",
    "plot_history",
    "animate",
    "animation_png",
    "explorer",
    "JointDrawing",
    "drawing_for",
    "MAX_FRAMES",
]
