"""Screenshots of a recording in rerun's own web viewer, so people can see what a reviewer sees.

Run: make screenshots (installs playwright into build/screenshots-lib, uses the system's chromium).

Serves the recording with ``rerun --serve-web``, opens the web viewer in headless Chromium with
the software renderer, and for each moment ``teach.observe.pictures`` picks (the first tick of
the first run, its grasp, the last answer, the end) types the moment into the time panel's time
field, reads the viewer's own state back from the page (``WebHandle.viewer_state()``, the Viewer
Control API's ``GetStateResponse``) until its time cursor is on that moment, waits until the
picture stops changing, and takes it. The pictures go to a scratch folder first and into
``docs/screenshots/`` (with ``pictures.json``: each one's moment and caption) only when every one
was taken at its moment; otherwise one line says which was not, exit status 1. Stops the server
it started (its process group).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.parse
from pathlib import Path

from playwright.sync_api import Page, sync_playwright

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from teach.observe.pictures import Picture, pictures  # noqa: E402
from teach.observe.reader import read_recording  # noqa: E402

VIEWER_PORT = 9090
GRPC_PORT = 9876
LOAD_SECONDS = 600.0  # the most the software renderer may take to load the viewer and the whole recording
MOVE_SECONDS = 120.0  # the most it may take to move the time cursor
STILL_SECONDS = 4.0  # a picture is taken once it has not changed for this long
STILL_LIMIT = 180.0
TIME_FIELD = (1515, 886)  # the time panel's time field (bottom right of a 1600x900 viewer)
PAUSE_BUTTON = (26, 886)  # its pause button (bottom left)


class NotShown(Exception):
    """The viewer did not show what was asked in time (the message says what)."""


# --- the viewer's state, read back from the page --------------------------------------------

def _varint(data: bytes, at: int) -> tuple[int, int]:
    value = shift = 0
    while True:
        byte = data[at]
        at += 1
        value |= (byte & 0x7F) << shift
        shift += 7
        if byte < 0x80:
            return value, at


def _fields(data: bytes) -> list[tuple[int, int | bytes]]:
    """A protobuf message's (field number, value) pairs: integers for varints, bytes otherwise."""
    at, fields = 0, []
    while at < len(data):
        key, at = _varint(data, at)
        number, kind = key >> 3, key & 7
        value: int | bytes
        if kind == 0:
            value, at = _varint(data, at)
        elif kind == 2:
            length, at = _varint(data, at)
            value, at = data[at:at + length], at + length
        elif kind in (1, 5):
            size = 8 if kind == 1 else 4
            value, at = data[at:at + size], at + size
        else:
            raise ValueError(f"protobuf wire type {kind}")
        fields.append((number, value))
    return fields


def _field(data: bytes, number: int) -> bytes | int | None:
    return next((value for n, value in _fields(data) if n == number), None)


PAUSED = 1


def cursor(state: bytes) -> tuple[str, int, int, int] | None:
    """From ``GetStateResponse``: the active recording's (timeline, time under the cursor, last time
    of that timeline, play state), or None while nothing is loaded. (recording = 3; in it
    timelines = 2 with name = 1.1 and range = 3.2, the cursor = 3 with timeline name = 1.1 and
    time = 3.1, the play state = 5: 1 paused, 2 playing, 3 following; protobuf leaves out zeros.)"""
    recording = _field(state, 3)
    if not isinstance(recording, bytes):
        return None
    current = _field(recording, 3)
    if not isinstance(current, bytes):
        return None
    name = _field(current, 1)
    timeline = _field(name, 1) if isinstance(name, bytes) else None
    if not isinstance(timeline, bytes):
        return None
    time_value = _field(current, 3)
    at = _field(time_value, 1) if isinstance(time_value, bytes) else 0
    last = 0
    for number, value in _fields(recording):
        if number == 2 and isinstance(value, bytes):
            label = _field(value, 1)
            if isinstance(label, bytes) and _field(label, 1) == timeline:
                span = _field(value, 3)
                end = _field(span, 2) if isinstance(span, bytes) else 0
                last = end if isinstance(end, int) else 0
    play = _field(recording, 5)
    return timeline.decode(), at if isinstance(at, int) else 0, last, play if isinstance(play, int) else 0


def viewer_cursor(page: Page) -> tuple[str, int, int, int] | None:
    try:
        state = page.evaluate("window._handle ? Array.from(window._handle.viewer_state()) : null")
    except Exception:  # the page is still starting the viewer
        return None
    return None if state is None else cursor(bytes(state))


# --- driving the viewer ---------------------------------------------------------------------

def wait_loaded(page: Page, last: int) -> None:
    """Until the viewer has the whole recording: the tick timeline reaches the recording's last moment."""
    deadline = time.monotonic() + LOAD_SECONDS
    seen = None
    while time.monotonic() < deadline:
        seen = viewer_cursor(page)
        if seen is not None and seen[0] == "tick" and seen[2] >= last:
            break
        time.sleep(2.0)
    else:
        raise NotShown(f"the viewer did not load the recording in {LOAD_SECONDS:.0f} s (it shows {seen})")
    while time.monotonic() < deadline:  # it follows the recording to its end: pause it there
        if seen is not None and seen[3] == PAUSED:
            return
        page.mouse.click(*PAUSE_BUTTON)
        time.sleep(3.0)
        seen = viewer_cursor(page)
    raise NotShown(f"the viewer could not be paused (it shows {seen})")


def move_to(page: Page, moment: int) -> None:
    """Type the moment into the time panel's time field, as a person would, until the viewer's
    cursor reads it back (typed again every 30 s: a slow page may lose keys)."""
    deadline = time.monotonic() + MOVE_SECONDS
    seen = None
    while time.monotonic() < deadline:
        page.mouse.click(*TIME_FIELD)
        page.keyboard.press("Control+A")
        page.keyboard.type(str(moment))
        page.keyboard.press("Enter")
        page.mouse.move(800, 450)
        retype = min(deadline, time.monotonic() + 30.0)
        while time.monotonic() < retype:
            seen = viewer_cursor(page)
            if seen is not None and seen[:2] == ("tick", moment) and seen[3] == PAUSED:
                return
            time.sleep(1.0)
    raise NotShown(f"the viewer's time cursor did not reach tick {moment} in {MOVE_SECONDS:.0f} s (it shows {seen})")


def wait_still(page: Page, moment: int) -> bytes:
    """The picture once two screenshots ``STILL_SECONDS`` apart are the same (the software renderer
    draws the panels one after another), with the cursor still at ``moment``."""
    deadline = time.monotonic() + STILL_LIMIT
    last = page.screenshot(type="png")
    while time.monotonic() < deadline:
        time.sleep(STILL_SECONDS)
        now = page.screenshot(type="png")
        seen = viewer_cursor(page)
        if seen is None or seen[:2] != ("tick", moment):
            raise NotShown(f"the viewer's time cursor left tick {moment} (it shows {seen})")
        if now == last:
            return now
        last = now
    raise NotShown(f"the viewer kept redrawing at tick {moment} for {STILL_LIMIT:.0f} s")


def shrink(png: Path) -> None:
    """A 256-colour palette keeps a viewer screenshot under 300 KB and loses nothing one can read."""
    import PIL.Image

    with PIL.Image.open(png) as image:
        small = image.convert("RGB").quantize(256, method=PIL.Image.Quantize.FASTOCTREE)
    small.save(png, optimize=True)


def viewer_url() -> str:
    data = urllib.parse.quote(f"rerun+http://127.0.0.1:{GRPC_PORT}/proxy", safe="")
    return f"http://127.0.0.1:{VIEWER_PORT}/?url={data}&renderer=webgl"


def take(page: Page, shots: list[Picture], last: int, scratch: Path) -> None:
    page.goto(viewer_url())
    wait_loaded(page, last)
    for shot in shots:
        move_to(page, shot.moment)
        target = scratch / f"{shot.name}.png"
        target.write_bytes(wait_still(page, shot.moment))
        shrink(target)
        print(f"{shot.name}.png: tick {shot.moment}: {shot.caption}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recording", type=Path, nargs="?", default=ROOT / "recordings" / "quickstart.rrd")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "screenshots")
    parser.add_argument("--rerun", default=str(ROOT / ".venv" / "bin" / "rerun"))
    args = parser.parse_args()
    chromium = shutil.which("chromium")
    if chromium is None:
        print("screenshots: no chromium on PATH (apt-get install -y chromium)", file=sys.stderr)
        return 1
    contents = read_recording(args.recording)
    shots = pictures(contents)
    for port in (VIEWER_PORT, GRPC_PORT):
        with socket.socket() as probe:
            if probe.connect_ex(("127.0.0.1", port)) == 0:
                print(f"screenshots: port {port} is in use (another rerun server?)", file=sys.stderr)
                return 1
    server = subprocess.Popen([args.rerun, "--serve-web", "--web-viewer-port", str(VIEWER_PORT),
                               "--port", str(GRPC_PORT), str(args.recording)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    scratch = Path(tempfile.mkdtemp(prefix="screenshots-"))
    try:
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=chromium, headless=True,
                                                 args=["--use-gl=angle", "--use-angle=swiftshader",
                                                       "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"])
            try:
                take(browser.new_page(viewport={"width": 1600, "height": 900}), shots, contents.last_moment, scratch)
            finally:
                browser.close()
    except NotShown as failure:
        print(f"screenshots: {failure}; nothing in {args.out} was changed", file=sys.stderr)
        return 1
    finally:
        os.killpg(server.pid, signal.SIGTERM)  # its own group: the rerun wrapper and the viewer server it runs
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)
    args.out.mkdir(parents=True, exist_ok=True)
    for shot in shots:
        os.replace(scratch / f"{shot.name}.png", args.out / f"{shot.name}.png")
    listing = {shot.name: {"moment": shot.moment, "caption": shot.caption} for shot in shots}
    (args.out / "pictures.json").write_text(json.dumps(listing, indent=2, ensure_ascii=False) + "\n")
    shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
