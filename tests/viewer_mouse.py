"""A scripted mouse for the MuJoCo viewer: Ctrl+drag as the viewer itself turns it into a
perturbation (``mjv_initPerturb`` when the drag begins, ``mjv_movePerturb`` as the mouse moves),
on the viewer's own ``perturb`` and camera, so its ``sync`` applies the force as for a hand."""

from __future__ import annotations

from typing import Any

import mujoco

_MOUSE, _PERT = mujoco.mjtMouse, mujoco.mjtPertBit
_BITS = {_MOUSE.mjMOUSE_MOVE_H: _PERT.mjPERT_TRANSLATE, _MOUSE.mjMOUSE_MOVE_V: _PERT.mjPERT_TRANSLATE,
         _MOUSE.mjMOUSE_ROTATE_H: _PERT.mjPERT_ROTATE, _MOUSE.mjMOUSE_ROTATE_V: _PERT.mjPERT_ROTATE}


class ViewerMouse:
    """Grabs a body in the viewer, moves the mouse a step each frame, lets go."""

    def __init__(self, viewer: Any, model: mujoco.MjModel, data: mujoco.MjData):
        self.viewer, self.model, self.data = viewer, model, data
        self.scene = mujoco.MjvScene(model, maxgeom=2000)
        self.action: mujoco.mjtMouse | None = None
        self.step = (0.0, 0.0)

    def grab(self, body: str, action: mujoco.mjtMouse, step: tuple[float, float]) -> None:
        """Double-click ``body`` (select it), then hold Ctrl and a button; ``step`` is the mouse's
        move per frame, in the viewer's units (a fraction of the window's height)."""
        with self.viewer.lock():
            mujoco.mjv_updateScene(self.model, self.data, self.viewer.opt, self.viewer.perturb, self.viewer.cam,
                                   mujoco.mjtCatBit.mjCAT_ALL, self.scene)
            pert = self.viewer.perturb
            pert.select, pert.localpos[:] = self.model.body(body).id, 0.0
            mujoco.mjv_initPerturb(self.model, self.data, self.scene, pert)
            pert.active = int(_BITS[action])
        self.action, self.step = action, step

    def frame(self) -> None:
        """After a scene frame: the mouse moves on while a button is held."""
        if self.action is None:
            return
        with self.viewer.lock():
            mujoco.mjv_movePerturb(self.model, self.data, self.action, self.step[0], self.step[1], self.scene,
                                   self.viewer.perturb)

    def release(self) -> None:
        with self.viewer.lock():
            self.viewer.perturb.active = 0
        self.action = None
