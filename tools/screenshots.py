"""Screenshots of a recording in rerun's own web viewer, so people can see what a reviewer sees.

Run: make screenshots (installs playwright into build/screenshots-lib, uses the system's chromium).

Serves the recording with ``rerun --serve-web``, opens the web viewer in headless Chromium with
the software renderer at the first step (the viewer URL's ``#when=`` fragment), moves the time
cursor to a few steps (typed into the time panel's time field) and writes
``docs/screenshots/NAME.png``. The steps come from the recording itself: the first tick, the
last tick where the robot grasps the ball, and the last step. Stops the server it started (its
process group).
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.parse
from pathlib import Path

from playwright.sync_api import Page, sync_playwright

ROOT = Path(__file__).resolve().parent.parent
VIEWER_PORT = 9090
GRPC_PORT = 9876
LOAD_SECONDS = 150.0  # the software renderer on a loaded machine needs this long to load the viewer and the data
DRAW_SECONDS = 20.0  # and this long to draw every panel at a new time
TIME_FIELD = (1515, 886)  # the time panel's time field (bottom right of a 1600x900 viewer)


def viewer_url(step: int) -> str:
    data = urllib.parse.quote(f"rerun+http://127.0.0.1:{GRPC_PORT}/proxy", safe="")
    return f"http://127.0.0.1:{VIEWER_PORT}/?url={data}&renderer=webgl#when=step@{step}"


def shrink(png: Path) -> None:
    """A 256-colour palette keeps a viewer screenshot under 300 KB and loses nothing one can read."""
    import PIL.Image

    with PIL.Image.open(png) as image:
        small = image.convert("RGB").quantize(256, method=PIL.Image.Quantize.FASTOCTREE)
    small.save(png, optimize=True)


def move_time_cursor(page: Page, step: int) -> None:
    """Type the step into the time panel's time field, as a person would."""
    page.mouse.click(*TIME_FIELD)
    page.keyboard.press("Control+A")
    page.keyboard.type(str(step))
    page.keyboard.press("Enter")
    page.mouse.move(800, 450)
    time.sleep(DRAW_SECONDS)


def interesting_steps(recording: Path) -> dict[str, int]:
    """Steps worth a picture, found in the recording: a grasp in a run, its first tick, its last step."""
    sys.path.insert(0, str(ROOT))
    from teach.observe.reader import read_recording

    contents = read_recording(recording)
    steps: dict[str, int] = {}
    ticked = [t for t in contents.ticks if t.step is not None]
    if ticked:
        steps["first-tick"] = ticked[0].step  # type: ignore[assignment]
    grasps = [t.step for t in ticked if t.action == "GraspBall"]
    if grasps:
        steps["grasp"] = grasps[-1]  # type: ignore[assignment]
    last = max((s.step for s in contents.states if s.step is not None), default=None)
    if last is not None:
        steps["end"] = last
    return steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recording", type=Path, nargs="?", default=ROOT / "recordings" / "quickstart.rrd")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "screenshots")
    parser.add_argument("--rerun", default=str(ROOT / ".venv" / "bin" / "rerun"))
    args = parser.parse_args()
    chromium = shutil.which("chromium")
    if chromium is None:
        sys.exit("screenshots: no chromium on PATH (apt-get install -y chromium)")
    steps = interesting_steps(args.recording)
    args.out.mkdir(parents=True, exist_ok=True)
    for port in (VIEWER_PORT, GRPC_PORT):
        with socket.socket() as probe:
            if probe.connect_ex(("127.0.0.1", port)) == 0:
                sys.exit(f"screenshots: port {port} is in use (another rerun server?)")
    server = subprocess.Popen([args.rerun, "--serve-web", "--web-viewer-port", str(VIEWER_PORT),
                               "--port", str(GRPC_PORT), str(args.recording)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        time.sleep(3.0)
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=chromium, headless=True,
                                                 args=["--use-gl=angle", "--use-angle=swiftshader",
                                                       "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"])
            page = browser.new_page(viewport={"width": 1600, "height": 900})
            first = next(iter(steps.values()))
            page.goto(viewer_url(first))
            time.sleep(LOAD_SECONDS)
            for name, step in steps.items():
                move_time_cursor(page, step)
                target = args.out / f"{name}.png"
                page.screenshot(path=str(target), type="png")
                shrink(target)
                print(f"{target}: step {step}")
            browser.close()
    finally:
        os.killpg(server.pid, signal.SIGTERM)  # its own group: the rerun wrapper and the viewer server it runs
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)


if __name__ == "__main__":
    main()
