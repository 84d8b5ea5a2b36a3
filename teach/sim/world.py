"""The ball-in-bin world: a MuJoCo scene whose symbolic state is read from physics.

The robot is a mobile base (planar joints x, y, yaw under velocity actuators), a lift with an
arm, and a two-finger gripper whose grasp point lies ``GRASP_OFFSET`` ahead of the base centre.
A camera on the mast ("eye", what perception uses) looks ahead, pitched 5 degrees down (vertical
field of view 36 degrees, horizontal about 47 degrees), so the floor closer than about 1.2 m is a
blind spot. The camera a recording shows as the robot's own ("shoulder", on a post at the chassis's
left edge, pitched 38 degrees down, 70 degrees wide) sees what the eye sees ahead and also the
gripper, the ball in it and the bin under it: people reviewing a run see the task, while perception
(and so every recorded demonstration) stays as it was.

Conditions and their thresholds (distances horizontal unless said otherwise):

- BallFound: the ball's centre is inside the camera's view frustum, within ``VIEW_RANGE`` and
  not occluded (a ray from the camera hits the ball first); or it was localised before and not
  lost since. The robot keeps the last seen position; while the ball is held or lies within
  ``TRACK_RADIUS`` of the grasp point the gripper keeps that position up to date; the ball is
  lost once it is more than ``LOST_DISTANCE`` from the remembered position and out of view.
- BallClose: the ball is within ``CLOSE_RADIUS`` of the grasp point (horizontally) and its
  centre below ``LOW_HEIGHT``, i.e. within the gripper's reach: on the floor in front of it, or
  held and carried (so no skill flips it halfway, and a reactive tree sees the states the
  demonstrations recorded). A ball held at the lift's top (``LIFT_TOP``) is out of reach:
  that is how ``arrange`` makes BallGrasped without BallClose, which Δ2's start states need.
- BallGrasped: the ball touches both fingers (pads or the hooks at their tips).
- BinClose: the bin's centre is within ``BIN_RADIUS`` of the grasp point (PlaceBall reaches it).
- BallPlaced: the ball's centre is inside the bin's walls, below their top, and the gripper
  has let go of it.

Physically impossible states (``arrange`` raises DomainError): BallPlaced with BallGrasped (a
ball cannot be in the bin and in the hand), and BallPlaced with BallClose but not BinClose (a
ball in the bin is within ``CLOSE_RADIUS`` of the grasp point only if the bin is within
``BIN_RADIUS``). Every state with BallPlaced false can be arranged.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from teach.domain import Domain, State, load_domain
from teach.errors import DomainError
from teach.observe.scene import SceneShape

ASSETS = Path(str(resources.files("teach.sim") / "assets"))
SCENE_FILE = ASSETS / "ball_in_bin.xml"
DOMAIN_FILE = ASSETS / "ball_in_bin.toml"

CONDITIONS = ("BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced")
CONTROL_STEPS = 10          # physics steps (2 ms) per control period: skills act at 50 Hz
GRASP_OFFSET = 0.42         # grasp point ahead of the base centre (m)
BALL_RADIUS = 0.035
VIEW_RANGE = 6.0            # the camera sees the ball this far (m): the whole room
CLOSE_RADIUS = 0.25         # BallClose: ball within this of the grasp point (m)
LOW_HEIGHT = 0.31           # BallClose: ball centre below this height (m): carried balls count
LIFT_TOP = 0.3              # the lift's top; a ball held up there is out of reach (not BallClose)
TRACK_RADIUS = 0.25         # the gripper tracks a known ball this close to the grasp point (m)
LOST_DISTANCE = 0.2         # a remembered ball farther than this from memory is lost (m)
BIN_RADIUS = 0.4            # BinClose: bin centre within this of the grasp point (m)
BIN_INNER = 0.12            # inner half width of the bin (m)
BIN_TOP = 0.16              # height of the bin's walls (m)
VIEWER_DISTANCE = 6.0      # m from the robot: the 4 m room in view
VIEWER_ELEVATION = -50.0   # degrees: looking down on it
LIFT_CARRY = 0.26           # lift height for driving and carrying (m above grasp height)
LIFT_PLACE = 0.075          # lift height that holds the ball inside the bin, the arm just above its walls
FINGER_RELEASE = 0.025      # finger closure that lets go of the ball without touching the bin's walls
FINGER_OPEN, FINGER_CLOSED = 0.0, 0.085
ROOM = 2.0                  # the room's walls stand at +-ROOM (m)
SETTLE_SECONDS = 0.3


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


class World:
    """The ball-in-bin scene, its robot, and the robot's memory of where the ball is."""

    def __init__(self, seed: int = 0, domain: Domain | None = None, cameras: bool = True):
        self.domain = domain if domain is not None else load_domain(DOMAIN_FILE)
        unknown = [n for n in self.domain.condition_names if n not in CONDITIONS]
        if unknown:
            raise DomainError(f"the ball-in-bin world cannot compute condition {unknown[0]!r} "
                              f"(it knows {', '.join(CONDITIONS)})", self.domain.path)
        self.model = mujoco.MjModel.from_xml_path(str(SCENE_FILE))
        self.data = mujoco.MjData(self.model)
        m = self.model
        self._ids = {name: m.body(name).id for name in ("base", "ball", "bin")}
        self._ball_geom = m.geom("ball").id
        self._fingers = (m.body("finger_left").id, m.body("finger_right").id)
        self._cam = m.camera("eye").id
        self._grasp_site = m.site("grasp").id
        self._qadr = {name: int(m.joint(name).qposadr[0]) for name in
                      ("base_x", "base_y", "base_yaw", "lift", "finger_left", "finger_right", "ball", "bin")}
        self._vadr = {name: int(m.joint(name).dofadr[0]) for name in ("base_x", "ball", "bin")}
        self._act = {name: m.actuator(name).id for name in
                     ("drive_x", "drive_y", "turn", "lift", "finger_left", "finger_right")}
        tan_v = math.tan(math.radians(m.cam_fovy[self._cam]) / 2)
        self._tan_view = (tan_v * 4 / 3, tan_v)  # the 4:3 image of camera_image's default size
        # None: no offscreen rendering here (``cameras`` False: nothing records the images)
        self._renderers: dict[tuple[int, int], Any] | None = {} if cameras else None
        self._cameras = {"robot": m.camera("shoulder").id, "overview": m.camera("overview").id}
        """The images a recording shows: the robot's (its shoulder camera, not the eye) and the room's."""
        self._time_before_reset = 0.0
        self._memory: np.ndarray | None = None
        self.rng = np.random.default_rng(seed)
        self.reset(seed)

    # --- time -------------------------------------------------------------------------------

    @property
    def sim_time(self) -> float:
        """Simulated seconds since the world was made; it keeps running across resets."""
        return self._time_before_reset + float(self.data.time)

    def step(self, n: int = 1) -> None:
        """Advance physics by ``n`` steps of 2 ms; the robot's perception updates afterwards."""
        mujoco.mj_step(self.model, self.data, nstep=n)
        self._perceive()

    def settle(self, seconds: float = SETTLE_SECONDS) -> None:
        self.step(max(1, round(seconds / self.model.opt.timestep)))

    # --- geometry -----------------------------------------------------------------------------

    def base_pose(self) -> tuple[float, float, float]:
        q, a = self.data.qpos, self._qadr
        return float(q[a["base_x"]]), float(q[a["base_y"]]), float(q[a["base_yaw"]])

    def grasp_point(self) -> np.ndarray:
        return self.data.site_xpos[self._grasp_site].copy()

    def ball_position(self) -> np.ndarray:
        return self.data.xpos[self._ids["ball"]].copy()

    def bin_position(self) -> np.ndarray:
        return self.data.xpos[self._ids["bin"]].copy()

    def ball_speed(self) -> float:
        v = self._vadr["ball"]
        return float(np.linalg.norm(self.data.qvel[v:v + 3]))

    def lift_height(self) -> float:
        return float(self.data.qpos[self._qadr["lift"]])

    def finger_closure(self) -> float:
        q, a = self.data.qpos, self._qadr
        return float(min(q[a["finger_left"]], q[a["finger_right"]]))

    def known_ball(self) -> np.ndarray | None:
        """Where the robot believes the ball is (None: not localised)."""
        return None if self._memory is None else self._memory.copy()

    # --- predicates -------------------------------------------------------------------------

    def ball_visible(self) -> bool:
        """The ball's centre is in the camera's frustum and range, and nothing hides it."""
        d = self.data
        cam = d.cam_xpos[self._cam]
        offset = d.xpos[self._ids["ball"]] - cam
        distance = float(np.linalg.norm(offset))
        local = d.cam_xmat[self._cam].reshape(3, 3).T @ offset
        depth = -local[2]
        if depth <= 0 or distance > VIEW_RANGE:
            return False
        if abs(local[0]) > self._tan_view[0] * depth or abs(local[1]) > self._tan_view[1] * depth:
            return False
        hit = np.zeros(1, dtype=np.int32)
        mujoco.mj_ray(self.model, d, cam, offset, None, 1, self._ids["base"], hit)
        return int(hit[0]) == self._ball_geom

    def ball_grasped(self) -> bool:
        """Both fingers (pad or hook) touch the ball."""
        body_of = self.model.geom_bodyid
        touching = {int(body_of[b if a == self._ball_geom else a])
                    for a, b in self.data.contact.geom[: self.data.ncon] if self._ball_geom in (a, b)}
        return self._fingers[0] in touching and self._fingers[1] in touching

    def _near_gripper(self, point: np.ndarray, radius: float) -> bool:
        return float(np.linalg.norm(point[:2] - self.grasp_point()[:2])) < radius

    def ball_close(self) -> bool:
        ball = self.ball_position()
        return bool(ball[2] < LOW_HEIGHT) and self._near_gripper(ball, CLOSE_RADIUS)

    def bin_close(self) -> bool:
        return self._near_gripper(self.bin_position(), BIN_RADIUS)

    def ball_placed(self) -> bool:
        offset = self.ball_position() - self.bin_position()
        local = self.data.xmat[self._ids["bin"]].reshape(3, 3).T @ offset
        inside = abs(local[0]) < BIN_INNER and abs(local[1]) < BIN_INNER and 0 < local[2] < BIN_TOP
        return bool(inside) and not self.ball_grasped()

    def ball_found(self) -> bool:
        return self._memory is not None or self.ball_visible()

    def conditions(self) -> dict[str, bool]:
        """The domain's conditions, in domain order, computed from the simulation."""
        values = {"BallFound": self.ball_found, "BallClose": self.ball_close, "BallGrasped": self.ball_grasped,
                  "BinClose": self.bin_close, "BallPlaced": self.ball_placed}
        return {name: values[name]() for name in self.domain.condition_names}

    def state(self) -> State:
        return tuple(self.conditions().values())

    def _perceive(self) -> None:
        """Update the robot's memory of the ball: seen, tracked by the gripper, or lost."""
        ball = self.ball_position()
        if self.ball_visible():
            self._memory = ball
        elif self._memory is not None:
            if self.ball_grasped() or (ball[2] < LIFT_CARRY + 0.2 and self._near_gripper(ball, TRACK_RADIUS)):
                self._memory = ball
            elif float(np.linalg.norm(ball - self._memory)) > LOST_DISTANCE:
                self._memory = None

    def localise_by_touch(self) -> bool:
        """A ball between the fingers is localised by touch (FindBall uses this)."""
        if self.ball_grasped():
            self._memory = self.ball_position()
            return True
        return False

    # --- commands -----------------------------------------------------------------------------

    def drive(self, forward: float, turn: float) -> None:
        """Command the base: forward speed (m/s) along its heading and turn rate (rad/s)."""
        yaw = self.base_pose()[2]
        ctrl, act = self.data.ctrl, self._act
        ctrl[act["drive_x"]] = forward * math.cos(yaw)
        ctrl[act["drive_y"]] = forward * math.sin(yaw)
        ctrl[act["turn"]] = turn

    def set_lift(self, height: float) -> None:
        self.data.ctrl[self._act["lift"]] = height

    def set_fingers(self, closure: float) -> None:
        self.data.ctrl[self._act["finger_left"]] = closure
        self.data.ctrl[self._act["finger_right"]] = closure

    # --- the teacher's hand (perturbations) --------------------------------------------------

    def put_ball(self, position: np.ndarray, velocity: np.ndarray | None = None) -> None:
        """Put the ball somewhere (optionally thrown with ``velocity``), as a hand would."""
        q, v = self._qadr["ball"], self._vadr["ball"]
        self.data.qpos[q:q + 7] = (*position, 1, 0, 0, 0)
        self.data.qvel[v:v + 6] = (*(np.zeros(3) if velocity is None else velocity), 0, 0, 0)
        mujoco.mj_forward(self.model, self.data)

    def put_bin(self, xy: np.ndarray) -> None:
        q, v = self._qadr["bin"], self._vadr["bin"]
        self.data.qpos[q:q + 2] = xy
        self.data.qvel[v:v + 6] = 0
        mujoco.mj_forward(self.model, self.data)

    def push_base(self, force_xy: np.ndarray, torque: float) -> None:
        """An external force on the robot's base until called again with zeros."""
        self.data.xfrc_applied[self._ids["base"]] = (*force_xy, 0.0, 0.0, 0.0, torque)

    def clear_of_robot(self, point: np.ndarray, clearance: float) -> bool:
        return self._clear_of_robot(self.base_pose(), point, clearance)

    # --- poses ----------------------------------------------------------------------------------

    def reset(self, seed: int | None = None) -> None:
        """Random start poses: robot anywhere facing anywhere, ball on the floor, bin anywhere."""
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        rng = self.rng
        for _ in range(1000):
            robot = (*rng.uniform(-1.5, 1.5, 2), rng.uniform(-math.pi, math.pi))
            grasp = self._grasp_xy(robot)
            bin_xy = rng.uniform(-1.7, 1.7, 2)
            ball_xy = rng.uniform(-1.8, 1.8, 2)
            if (self._inside(grasp, 1.9) and self._clear_of_robot(robot, bin_xy, 0.2)
                    and self._clear_of_robot(robot, ball_xy, 0.06) and _far(ball_xy, bin_xy, 0.3)
                    and _far(grasp, bin_xy, 0.25) and _far(ball_xy, grasp, CLOSE_RADIUS + 0.1)):
                break
        self._place(robot, bin_xy, ball=(*ball_xy, BALL_RADIUS), lift=LIFT_CARRY, fingers=FINGER_OPEN)
        self._memory = None
        self.settle()

    def arrange(self, state: Mapping[str, bool] | State, seed: int | None = None) -> None:
        """Pose robot, ball and bin so that exactly ``state`` holds, then let physics settle.

        ``state`` is a mapping (missing conditions are false) or a tuple in domain order.
        For BallFound the robot is given the ball's position, as if it had seen it before.
        """
        wanted = self._wanted(state)
        reason = impossible_reason(wanted)
        if reason is not None:
            raise DomainError(f"impossible state: {reason}")
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        target = tuple(wanted[name] for name in self.domain.condition_names)
        for _ in range(200):
            if self._try_arrange(wanted) and self.state() == target:
                return
        raise DomainError(f"could not arrange the state {self.domain.describe(target)}")

    def can_arrange(self, state: Mapping[str, bool] | State) -> bool:
        """Whether some pose makes exactly ``state`` hold (``arrange`` would not refuse it)."""
        return impossible_reason(self._wanted(state)) is None

    def _wanted(self, state: Mapping[str, bool] | State) -> dict[str, bool]:
        names = self.domain.condition_names
        if isinstance(state, Mapping):
            for name in state:
                self.domain.index(name)
            given = {name: bool(state.get(name, False)) for name in names}
        else:
            if len(state) != len(names):
                raise DomainError(f"a state needs {len(names)} values ({', '.join(names)}), got {len(state)}")
            given = dict(zip(names, map(bool, state), strict=True))
        return {name: given.get(name, False) for name in CONDITIONS}

    def _try_arrange(self, want: dict[str, bool]) -> bool:
        rng = self.rng
        robot = (*rng.uniform(-1.45, 1.45, 2), rng.uniform(-math.pi, math.pi))
        grasp = self._grasp_xy(robot)
        if not self._inside(grasp, 1.85):
            return False
        if want["BinClose"]:
            low = 0.3 if want["BallClose"] and not want["BallPlaced"] else 0.0
            bin_xy = grasp + _polar(rng, low, BIN_RADIUS - 0.05)
        else:
            bin_xy = rng.uniform(-1.7, 1.7, 2)
            if not _far(bin_xy, grasp, BIN_RADIUS + 0.15):
                return False
        if not (self._inside(bin_xy, 1.75) and self._clear_of_robot(robot, bin_xy, 0.2)):
            return False
        lift, fingers = LIFT_CARRY, FINGER_OPEN
        if want["BallPlaced"]:
            ball = (*(bin_xy + _polar(rng, 0.0, 0.05)), 0.06)
        elif want["BallGrasped"]:
            lift = 0.0 if want["BallClose"] else LIFT_TOP
            fingers = FINGER_CLOSED
            ball = (*grasp, BALL_RADIUS + lift)
        else:
            if want["BallClose"]:
                ball_xy = grasp + _polar(rng, 0.0, CLOSE_RADIUS - 0.05)
            else:
                ball_xy = rng.uniform(-1.8, 1.8, 2)
                if not _far(ball_xy, grasp, CLOSE_RADIUS + 0.1):
                    return False
            if not (self._inside(ball_xy, 1.85) and self._clear_of_robot(robot, ball_xy, 0.06)
                    and _far(ball_xy, bin_xy, 0.3)):
                return False
            ball = (*ball_xy, BALL_RADIUS)
        self._place(robot, bin_xy, ball, lift, fingers)
        self._memory = None
        if want["BallFound"]:
            self._memory = self.ball_position()
        elif self.ball_visible():
            return False
        self.settle()
        return True

    def _place(self, robot: tuple[float, float, float], bin_xy: np.ndarray, ball: tuple[float, float, float],
               lift: float, fingers: float) -> None:
        """Put every body at rest in the given poses (the set-up before physics takes over)."""
        m, d, a = self.model, self.data, self._qadr
        self._time_before_reset += float(d.time)
        mujoco.mj_resetData(m, d)
        q = d.qpos
        q[a["base_x"]], q[a["base_y"]], q[a["base_yaw"]] = robot
        q[a["lift"]] = lift
        grip = FINGER_OPEN if fingers == FINGER_OPEN else 0.09 - BALL_RADIUS - 0.001
        q[a["finger_left"]] = q[a["finger_right"]] = grip
        q[a["ball"]:a["ball"] + 7] = (*ball, 1, 0, 0, 0)
        turn = float(self.rng.uniform(-math.pi, math.pi))
        q[a["bin"]:a["bin"] + 7] = (*bin_xy, 0, math.cos(turn / 2), 0, 0, math.sin(turn / 2))
        self.set_lift(lift)
        self.set_fingers(fingers)
        mujoco.mj_forward(m, d)

    def _grasp_xy(self, robot: tuple[float, float, float]) -> np.ndarray:
        x, y, yaw = robot
        return np.array([x + GRASP_OFFSET * math.cos(yaw), y + GRASP_OFFSET * math.sin(yaw)])

    @staticmethod
    def _inside(point: np.ndarray, limit: float) -> bool:
        return bool(np.all(np.abs(point) < limit))

    @staticmethod
    def _clear_of_robot(robot: tuple[float, float, float], point: np.ndarray, clearance: float) -> bool:
        """``point`` is at least ``clearance`` from the chassis (the raised arm passes over things)."""
        x, y, yaw = robot
        dx, dy = point[0] - x, point[1] - y
        ahead = dx * math.cos(yaw) + dy * math.sin(yaw)
        side = -dx * math.sin(yaw) + dy * math.cos(yaw)
        return math.hypot(max(abs(ahead) - 0.2, 0.0), max(abs(side) - 0.16, 0.0)) >= clearance

    # --- output -------------------------------------------------------------------------------

    def shapes(self) -> list[SceneShape]:
        """Every visible geom as a neutral shape with its world pose (floor as a thin box)."""
        m, d = self.model, self.data
        kinds = {mujoco.mjtGeom.mjGEOM_BOX: "box", mujoco.mjtGeom.mjGEOM_SPHERE: "sphere",
                 mujoco.mjtGeom.mjGEOM_CAPSULE: "capsule", mujoco.mjtGeom.mjGEOM_CYLINDER: "cylinder",
                 mujoco.mjtGeom.mjGEOM_PLANE: "box"}
        shapes = []
        quat = np.zeros(4)
        for g in range(m.ngeom):
            kind = kinds.get(int(m.geom_type[g]))
            if kind is None:
                continue
            size = m.geom_size[g]
            if int(m.geom_type[g]) == mujoco.mjtGeom.mjGEOM_PLANE:
                dims: tuple[float, ...] = (float(size[0]), float(size[1]), 0.001)
            else:
                dims = tuple(float(s) for s in size[: {"box": 3, "sphere": 1}.get(kind, 2)])
            mujoco.mju_mat2Quat(quat, d.geom_xmat[g])
            shapes.append(SceneShape(m.geom(g).name or f"geom{g}", kind, dims,
                                     tuple(float(v) for v in d.geom_xpos[g]),  # type: ignore[arg-type]
                                     tuple(float(v) for v in quat),  # type: ignore[arg-type]
                                     tuple(float(v) for v in m.geom_rgba[g])))  # type: ignore[arg-type]
        return shapes

    def camera_image(self, width: int = 320, height: int = 240, camera: str = "robot") -> np.ndarray | None:
        """A camera's view (height x width x 3, uint8): the robot's own ("robot", its shoulder camera
        looking at the task) or the room's fixed "overview"; None without offscreen rendering. One
        renderer per image size, kept."""
        if self._renderers is None:
            return None
        try:
            renderer = self._renderers.get((width, height))
            if renderer is None:
                renderer = self._renderers[(width, height)] = mujoco.Renderer(self.model, height, width)
            renderer.update_scene(self.data, camera=self._cameras[camera])
            return renderer.render().copy()
        except Exception:  # noqa: BLE001 - any GL failure means "no rendering here"
            self.close()
            return None

    def open_viewer(self) -> Any:
        """The interactive MuJoCo viewer on this world (needs a display); ``.sync()`` redraws it.
        For guiding by hand: no panels, and a camera that follows the robot from above and
        behind, high and far enough to show the room (ball and bin) from the first frame."""
        import mujoco.viewer

        viewer = mujoco.viewer.launch_passive(self.model, self.data, show_left_ui=False, show_right_ui=False)
        with viewer.lock():
            viewer.cam.type = mujoco.mjtCamera.mjCAMERA_TRACKING
            viewer.cam.trackbodyid = self._ids["base"]
            viewer.cam.distance, viewer.cam.elevation = VIEWER_DISTANCE, VIEWER_ELEVATION
            viewer.cam.azimuth = math.degrees(self.base_pose()[2])  # behind the robot, looking its way
        viewer.sync()
        return viewer

    def close(self) -> None:
        for renderer in (self._renderers or {}).values():
            renderer.close()
        self._renderers = None

    def __enter__(self) -> World:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _polar(rng: np.random.Generator, low: float, high: float) -> np.ndarray:
    radius, angle = rng.uniform(low, high), rng.uniform(-math.pi, math.pi)
    return np.array([radius * math.cos(angle), radius * math.sin(angle)])


def _far(a: np.ndarray, b: np.ndarray, distance: float) -> bool:
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b))) >= distance


def impossible_reason(wanted: Mapping[str, bool]) -> str | None:
    """Why no pose makes every condition of ``wanted`` take its value (None: one does)."""
    if wanted["BallPlaced"] and wanted["BallGrasped"]:
        return "the ball cannot be in the bin and in the gripper"
    if wanted["BallPlaced"] and wanted["BallClose"] and not wanted["BinClose"]:
        return "a ball in the bin is close only when the bin is close"
    return None
