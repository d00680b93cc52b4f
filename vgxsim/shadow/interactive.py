"""The interactive ``shadows`` program's view state: trackball, translation, dolly, spin.

README of the 1991 program: "Holding the middle mouse down lets the viewer rotate the
scene trackball style.  If the middle mouse button is released while the mouse is
moving, the scene will continue to spin.  The left mouse button translates the scene,
and the left and middle buttons held down together track into and out of the scene
with the vertical mouse motion."

:class:`View` turns mouse positions (IRIS screen coordinates, read with
``getvaluator(MOUSEX/MOUSEY)`` once per frame) into that motion; it knows nothing of
windows or events, so the same session runs on screen and headless from a script.
:class:`InteractiveShadows` is :class:`~vgxsim.shadow.program.Shadows` with the view
applied after the scene's ``lookat``.  The main loop, which reads the event queue like
the 1991 program, is ``vgxsim/examples/shadows_interactive.py``.

The motion is in eye space (x right, y up, z towards the viewer): the trackball turns
the scene about the look-at target, translation shifts it parallel to the screen so the
target plane follows the mouse, and dolly moves it along the line of sight by twice the
eye-target distance over a drag of the window's height.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vgxsim.gl import getmatrix, loadmatrix

from .program import Shadows
from .trackball import IDENTITY, add_quats, rotation_matrix, trackball

__all__ = ["View", "InteractiveShadows"]


def _translation(t) -> np.ndarray:
    m = np.eye(4)
    m[3, :3] = t  # row vectors: v @ M adds the bottom row
    return m


@dataclass
class View:
    """The user's view of the scene.

    Attributes
    ----------
    quat : tuple of 4 float
        Accumulated trackball rotation (unit quaternion x, y, z, w).
    shift : (float, float)
        Eye-space translation of the scene, scene units.
    dolly : float
        Eye-space motion towards the viewer (positive: the scene comes closer).
    spin : tuple of 4 float or None
        The rotation added every frame while the scene spins on.
    last : tuple of 4 float
        The rotation of the latest frame's drag (what a release while moving spins).
    mouse : (int, int) or None
        Mouse position at the previous frame while a button is held.
    """

    distance: float
    height_at_target: float
    quat: tuple = IDENTITY
    shift: tuple = (0.0, 0.0)
    dolly: float = 0.0
    spin: tuple | None = None
    last: tuple = IDENTITY
    mouse: tuple | None = None

    def press(self, x: int, y: int) -> None:
        """A mouse button went down at screen position (x, y): motion restarts there and
        a spin stops (the user has caught the scene)."""
        self.mouse = (x, y)
        self.spin = None
        self.last = IDENTITY

    def release(self, middle_was_down: bool, left_down: bool, middle_down: bool) -> None:
        """A button went up: releasing the middle button while the latest frame moved
        keeps the scene spinning by that frame's rotation."""
        if middle_was_down and not middle_down and not left_down and self.last != IDENTITY:
            self.spin = self.last
        if not (left_down or middle_down):
            self.mouse = None

    def drag(self, x: int, y: int, left: bool, middle: bool, origin: tuple[int, int],
             size: tuple[int, int]) -> bool:
        """Apply this frame's mouse motion; returns whether the view changed.

        Parameters
        ----------
        x, y : int
            MOUSEX, MOUSEY (screen coordinates, origin lower left).
        left, middle : bool
            LEFTMOUSE and MIDDLEMOUSE held.
        origin : (int, int)
            The window's lower-left corner on the screen (getorigin).
        size : (int, int)
            Its width and height (getsize).
        """
        if self.mouse is None or not (left or middle):
            self.last = IDENTITY
            return False
        (x0, y0), self.mouse = self.mouse, (x, y)
        if (x0, y0) == (x, y):
            self.last = IDENTITY
            return False
        w, h = size
        if middle and not left:
            def unit(px: int, py: int) -> tuple[float, float]:
                return ((2.0 * (px - origin[0]) - w) / w, (2.0 * (py - origin[1]) - h) / h)

            q = trackball(*unit(x0, y0), *unit(x, y))
            self.quat = add_quats(self.quat, q)
            self.last = q
            return True
        self.last = IDENTITY
        per_pixel = self.height_at_target / h
        if left and middle:
            self.dolly += 2.0 * self.distance * (y - y0) / h
        else:
            self.shift = (self.shift[0] + (x - x0) * per_pixel,
                          self.shift[1] + (y - y0) * per_pixel)
        return True

    def step_spin(self) -> bool:
        """One frame of continued spin; returns whether the scene is spinning."""
        if self.spin is None:
            return False
        self.quat = add_quats(self.quat, self.spin)
        return True

    def matrix(self) -> np.ndarray:
        """The eye-space matrix applied after ``lookat`` (row vectors, (4, 4) float64):
        turn about the target, then shift and dolly."""
        to_target = _translation((0.0, 0.0, self.distance))
        back = _translation((0.0, 0.0, -self.distance))
        move = _translation((self.shift[0], self.shift[1], self.dolly))
        return to_target @ rotation_matrix(self.quat) @ back @ move


class InteractiveShadows(Shadows):
    """:class:`Shadows` whose viewing matrix carries a :class:`View`.

    Parameters
    ----------
    view : View
    **kw
        As for :class:`Shadows`.
    """

    def __init__(self, *args, view: View, **kw):
        super().__init__(*args, **kw)
        self.view = view

    def viewing(self) -> None:
        """The scene's projection and ``lookat`` (:meth:`Shadows.viewing`), then the
        user's view in eye space; lights bound later follow the scene."""
        super().viewing()
        looking = np.array(getmatrix(), np.float64).reshape(4, 4)
        loadmatrix((looking @ self.view.matrix()).reshape(-1).tolist())


def view_for(shadows_scene) -> View:
    """A :class:`View` of the scene's camera: its eye-target distance and the height of
    the view at the target (the scale of translation)."""
    cam = shadows_scene.camera
    d = float(np.linalg.norm(np.subtract(cam.eye, cam.target)))
    if cam.near_height is not None:
        height = cam.near_height * d / cam.near
    else:
        height = 2.0 * d * math.tan(math.radians(cam.fovy / 20.0))
    return View(distance=d, height_at_target=height)
