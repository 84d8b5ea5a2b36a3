"""Voice (issue 22): how soon a shown line is heard, and what voice costs a session that does not use it.

    .venv/bin/python bench/bench_voice.py

1. First spoken line: from ``Speaker.say`` (the terminal has just shown the greeting) to the
   moment its sound is handed to the player, for English and German, the synthesizer cold (a new
   process, as at a session's start) and warm. Target: under 1 s.
2. Start-up without ``--voice``: ``teach session``'s parser built in a fresh process, with the
   session command's imports, against the same with ``teach.voice.session`` imported too (what
   ``--voice`` adds), side by side; the first must not import any of the voice libraries.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

FIRST_LINE = """
import sys, tempfile, threading, time
from pathlib import Path
from teach import messages as m
from teach.voice.lines import Line
from teach.voice.speaker import Speaker
lang = sys.argv[1]
heard = []
def player(audio, stop):
    heard.append(time.perf_counter())
greeting = m.HELLO(lang, actions="find the ball, go to the ball, grasp the ball")
with tempfile.TemporaryDirectory() as folder:
    speaker = Speaker(lang, Path(folder), player)
    for _ in range(2):  # cold, then warm
        shown = time.perf_counter()
        speaker.say(Line(greeting))
        while len(heard) < _ + 1:
            time.sleep(0.001)
        print(f"{heard[-1] - shown:.4f}")
    speaker.close()
"""

START = "import sys; from teach.cli import build_parser; build_parser(); import teach.commands.session{extra}; " \
        "print(any(m.startswith(('teach.voice', 'pocketsphinx', 'espeakng', 'sounddevice')) for m in sys.modules))"


def _python(code: str, *args: str) -> str:
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, check=True,
                          cwd=ROOT).stdout


def main() -> int:
    ok = True
    for lang in ("en", "de"):
        cold, warm = (float(x) for x in _python(FIRST_LINE, lang).split())
        print(f"first spoken line ({lang}): {cold * 1000:.0f} ms cold, {warm * 1000:.0f} ms warm (target < 1000 ms)")
        ok &= cold < 1.0
    times: dict[str, list[float]] = {"without voice": [], "with teach.voice": []}
    for _ in range(10):
        for name, extra in (("without voice", ""), ("with teach.voice", "; import teach.voice.session")):
            began = time.perf_counter()
            imported_voice = _python(START.format(extra=extra)).strip() == "True"
            times[name].append(time.perf_counter() - began)
            if name == "without voice" and imported_voice:
                print("a session without --voice imported a voice library")
                ok = False
    without, with_voice = (statistics.median(t) for t in times.values())
    print(f"start-up without --voice: {without * 1000:.0f} ms; with teach.voice imported: {with_voice * 1000:.0f} ms "
          f"(ratio {with_voice / without:.2f}; medians of 10, side by side)")
    print("targets met" if ok else "targets NOT met")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
