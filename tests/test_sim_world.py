"""The ball-in-bin world: predicates agree with the geometry, arrange reaches every state, determinism."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from conftest import BALL_DOMAIN

from teach.errors import DomainError
from teach.sim.world import BIN_RADIUS, CLOSE_RADIUS, DOMAIN_FILE, World

NON_GOAL_STATES = [(*map(bool, bits), False) for bits in itertools.product((0, 1), repeat=4)]


@pytest.fixture(scope="module")
def world() -> World:
    with World(seed=0) as w:
        yield w


def test_packaged_domain_is_the_ball_domain() -> None:
    assert DOMAIN_FILE.read_bytes() == BALL_DOMAIN.read_bytes()


@pytest.mark.parametrize("state", NON_GOAL_STATES, ids=lambda s: "".join(str(int(v)) for v in s))
def test_arrange_reaches_every_non_goal_state(world: World, state: tuple[bool, ...]) -> None:
    world.arrange(state, seed=7)
    # the state is read back from physics after settling
    assert world.state() == state


def test_impossible_states_are_refused(world: World) -> None:
    with pytest.raises(DomainError, match="impossible"):
        world.arrange({"BallPlaced": True, "BallGrasped": True})
    with pytest.raises(DomainError, match="impossible"):
        world.arrange({"BallPlaced": True, "BallClose": True})
    with pytest.raises(DomainError, match="unknown condition"):
        world.arrange({"BallLost": True})


def test_predicates_agree_with_geometry(world: World) -> None:
    for seed in range(15):
        world.reset(seed=seed)
        grasp = world.grasp_point()[:2]
        ball, bin_xy = world.ball_position(), world.bin_position()[:2]
        conditions = world.conditions()
        # a ball resting on the floor is close iff it lies within CLOSE_RADIUS of the grasp point
        assert conditions["BallClose"] == (np.linalg.norm(ball[:2] - grasp) < CLOSE_RADIUS)
        assert conditions["BinClose"] == (np.linalg.norm(bin_xy - grasp) < BIN_RADIUS)
        # at a reset the robot knows nothing, so BallFound is exactly "the camera sees the ball"
        assert conditions["BallFound"] == world.ball_visible()
        # a ball seen straight ahead at 1.5 m and then hidden far away behind the robot
        x, y, yaw = world.base_pose()
        ahead = np.array([x + 1.5 * np.cos(yaw), y + 1.5 * np.sin(yaw), 0.035])
        if np.all(np.abs(ahead[:2]) < 1.8) and np.linalg.norm(ahead[:2] - bin_xy) > 0.4:
            world.put_ball(ahead)
            world.step(1)
            assert world.ball_visible() and world.conditions()["BallFound"]


def test_ball_in_the_bin_is_placed_and_lost_when_moved(world: World) -> None:
    world.arrange({"BallPlaced": True, "BinClose": True, "BallFound": True})
    assert world.conditions()["BallPlaced"]
    behind = world.grasp_point() - 2 * (world.grasp_point() - np.array([*world.base_pose()[:2], 0.0]))
    world.put_ball(np.array([*np.clip(behind[:2], -1.8, 1.8), 0.035]))
    world.settle(0.2)
    conditions = world.conditions()
    assert not conditions["BallPlaced"]
    # the remembered position is now wrong by far more than LOST_DISTANCE
    assert conditions["BallFound"] == world.ball_visible()


def test_same_seed_same_world() -> None:
    a, b = World(seed=3), World(seed=3)
    a.reset(seed=11)
    b.reset(seed=11)
    assert np.array_equal(a.data.qpos, b.data.qpos)
    assert a.shapes() == b.shapes()


def test_shapes_cover_robot_ball_bin_floor(world: World) -> None:
    names = {s.name for s in world.shapes()}
    assert {"floor", "chassis", "pad_left", "pad_right", "ball", "bin_bottom"} <= names
    ball = next(s for s in world.shapes() if s.name == "ball")
    assert ball.kind == "sphere" and np.allclose(ball.pos, world.ball_position())


def test_camera_image_when_rendering_is_available(world: World) -> None:
    world.reset(seed=2)
    image = world.camera_image(64, 48)
    if image is None:
        pytest.skip("no offscreen OpenGL here")
    assert image.shape == (48, 64, 3) and image.dtype == np.uint8
    assert image.std() > 0


def test_a_session_that_records_nothing_renders_no_camera_image(tmp_path) -> None:
    """Rendering costs more than the physics: where nothing records the images, none is made."""
    from teach.bt.nodes import Action
    from teach.observe.hook import Observer
    from teach.session.settings import Settings, WorldKind
    from teach.session.setup import opened_session
    from teach.world.mujoco_world import MujocoWorld

    class Cameras(Observer):
        def __init__(self) -> None:
            self.images = 0

        def on_camera(self, image: object, camera: str = "robot") -> None:
            self.images += 1

    shown, unseen = Cameras(), Cameras()
    recorded, unrecorded = MujocoWorld(World(seed=0).domain, 0, shown), MujocoWorld(World(seed=0).domain, 0, unseen,
                                                                                      cameras=False)
    try:
        for world in (recorded, unrecorded):
            world.run(Action("FindBall"), max_actions=1)
        if recorded.world.camera_image(8, 6) is None:
            pytest.skip("no offscreen OpenGL here")
        assert shown.images > 0 and unseen.images == 0
    finally:
        recorded.close()
        unrecorded.close()
    settings = Settings("quiet", world=WorldKind.MUJOCO, base=tmp_path, record=False)
    with opened_session(settings, note=lambda _: None) as manager:
        assert manager.world.world.camera_image(8, 6) is None  # type: ignore[attr-defined]
