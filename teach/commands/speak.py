"""Say a line with the robot's voice into a WAV file (espeak-ng, offline; English or German).

Example:
    teach speak "grasp the ball" -o grasp.wav
    teach speak --lang de "Ball greifen" -o greifen.wav
"""

from __future__ import annotations

import argparse
from pathlib import Path

from teach.errors import TeachError

NAME = "speak"
HELP = "say TEXT with the robot's voice into a WAV file"
ORDER = 60
MAX_TEXT_CHARS = 2000  # a spoken line, not a book


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("text", help="what to say")
    parser.add_argument("-o", "--output", type=Path, required=True, help="WAV file to write")
    parser.add_argument("--lang", choices=("en", "de"), default="en", help="voice: English or German (default en)")


def outputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    return [("file", args.output)]


def run(args: argparse.Namespace) -> int:
    text = " ".join(args.text.split())
    if not text:
        raise TeachError("there is nothing to say: give the text to speak")
    if len(text) > MAX_TEXT_CHARS:
        raise TeachError(f"the text is {len(text)} characters long: at most {MAX_TEXT_CHARS} are spoken at once")
    from teach.voice.audio import write_wav
    from teach.voice.synth import speak

    write_wav(args.output, speak(text, args.lang))
    return 0
