"""Make docs/screenshots/viewer-guiding.png: MuJoCo's viewer while the teacher turns the robot by
hand (``guide hand``), under Xvfb, captured with ImageMagick's ``import -window root``.

Run: ``.venv/bin/python tools/viewer_screenshot.py [OUT.png]``. Needs Xvfb, Mesa's software
OpenGL and ImageMagick. The session runs in a child process on the fresh display (the viewer's
thread holds the display until that process ends), driven by the tests' scripted mouse.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "screenshots" / "viewer-guiding.png"
SIZE = "1024x768"
CROP = "683x512+0+0"  # the viewer's window: GLFW opens it at two thirds of the screen, top left
SHOT_AT = 1.6  # simulated seconds into the drag: the robot is well round, the ball in view


def main(argv: list[str]) -> int:
    out = Path(argv[1]) if len(argv) > 1 else OUT
    missing = [tool for tool in ("Xvfb", "import") if shutil.which(tool) is None]
    if missing:
        print(f"viewer_screenshot: {' and '.join(missing)} not installed (apt-get install xvfb imagemagick)",
              file=sys.stderr)
        return 2
    number = next(n for n in range(160, 360) if not Path(f"/tmp/.X{n}-lock").exists())
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", f":{number}", "-displayfd", str(write), "-screen", "0", f"{SIZE}x24",
                               "-nolisten", "tcp", "-noreset"], pass_fds=(write,), stderr=subprocess.DEVNULL)
    os.close(write)
    try:
        os.read(read, 16)  # Xvfb writes its number once it takes clients
        display = f":{number}"
        env = {**os.environ, "DISPLAY": display, "MUJOCO_GL": "glfw"}
        return subprocess.run([sys.executable, __file__, "--child", str(out)], env=env).returncode
    finally:
        server.terminate()
        server.wait()


def child(out: Path) -> None:
    """In the child process: a session with the viewer, the robot turned by hand, one shot."""
    sys.path.insert(0, str(ROOT / "tests"))
    import mujoco
    from conftest import BALL_DOMAIN
    from viewer_mouse import ViewerMouse

    from teach.domain import load_domain
    from teach.session.machine import SessionManager
    from teach.session.settings import Settings
    from teach.world.mujoco_world import MujocoWorld

    loaded = load_domain(BALL_DOMAIN)
    world = MujocoWorld(loaded, 0, viewer=True)
    manager = SessionManager(Settings("shot", domain=BALL_DOMAIN, base=Path(tempfile.mkdtemp()), record=False),
                             loaded, world)
    world.world.arrange({c: False for c in loaded.condition_names}, seed=11)
    viewer = world.viewer
    x, y, _ = world.world.base_pose()
    with viewer.lock():
        viewer.cam.lookat[:] = (x + 0.3, y - 0.5, 0.1)
        viewer.cam.distance, viewer.cam.azimuth, viewer.cam.elevation = 3.2, 150.0, -35.0
    mouse = ViewerMouse(viewer, world.world.model, world.world.data)
    start = world.world.sim_time
    taken: list[bool] = []

    def shoot() -> None:
        if not taken and world.world.sim_time - start >= SHOT_AT:
            taken.append(True)  # (the viewer opens without its side panels: Tab would show them)
            time.sleep(1.0)  # the viewer's render thread redraws at its own pace
            viewer.sync()
            subprocess.run(["import", "-window", "root", "-crop", CROP, "-colors", "128", str(out)], check=True)

    world.after_each_frame(mouse.frame)
    world.after_each_frame(shoot)
    mouse.grab("base", mujoco.mjtMouse.mjMOUSE_ROTATE_V, (-0.008, 0.0))
    for reply in manager.handle("guide hand 2"):
        print(reply.text)
    print(f"wrote {out} ({out.stat().st_size // 1024} KB)", flush=True)
    os._exit(0 if taken else 1)  # the viewer's thread still holds the display: leave without tearing it down


if __name__ == "__main__":
    if sys.argv[1:2] == ["--child"]:
        child(Path(sys.argv[2]))
    sys.exit(main(sys.argv))
