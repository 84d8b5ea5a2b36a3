"""What observers are given: camera images only when one of them keeps them (a world renders
nothing for a session that records nothing)."""

from __future__ import annotations

from typing import Any

from teach.observe.hook import Observer, Observers
from teach.sim.recorder import record
from teach.sim.world import World


class Cameras(Observer):
    def __init__(self, keeps: bool) -> None:
        self.keeps = keeps
        self.images = 0

    @property
    def records_images(self) -> bool:
        return self.keeps

    def on_camera(self, image: Any, camera: str = "robot") -> None:
        self.images += 1


def test_camera_images_are_rendered_only_for_an_observer_that_keeps_them() -> None:
    for keeps in (False, True):
        world = World(seed=1)
        world.arrange({}, seed=1)
        watcher = Cameras(keeps)
        record(world, ["FindBall", "ApproachBall"], Observers(Observer(), watcher))
        assert (watcher.images > 0) is keeps
        assert Observers(Observer(), watcher).records_images is keeps and not Observers().records_images
