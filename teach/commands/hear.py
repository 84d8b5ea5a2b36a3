"""Hear what a WAV file says, as a line the teaching session understands (English, offline).

Example:
    teach hear grasp.wav                                  # prints: grasp the ball
    teach hear a.wav b.wav --domain demos/ball/domain.toml   # prints: a.wav: ..., one line a file

Recognition (pocketsphinx) is restricted to a grammar made from the domain: its action phrases
and their pronoun forms ("grasp it"), the command words, condition labels after "start" and
"why", and the answer words. A file in which nothing of that fits is named on one line
(``FILE: nothing fits``) and the exit status is 2.

Several files are heard one after another by one recogniser, in the order given (pocketsphinx's
acoustic model carries a little state from file to file: the same call gives the same lines, but a
file heard after others may, rarely, be heard differently than alone).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "hear"
HELP = "recognise the line a WAV file says (English, with a grammar from the domain)"
ORDER = 61


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("files", type=Path, nargs="+", metavar="FILE.wav", help="16-bit PCM WAV files")
    parser.add_argument("--domain", type=Path, help="domain.toml (default: the ball-in-bin domain)")


def run(args: argparse.Namespace) -> int:
    from teach.domain import load_domain
    from teach.session.setup import default_domain
    from teach.voice.audio import read_wav
    from teach.voice.recognise import Recogniser

    domain = load_domain(args.domain) if args.domain else default_domain()
    sounds = [(path, read_wav(path)) for path in args.files]  # every file read and checked before any is heard
    recogniser = Recogniser(domain)
    status = 0
    for path, audio in sounds:
        heard = recogniser.hear(audio)
        if heard is None:
            print(f"{path}: nothing fits", file=sys.stderr)
            status = 2
        else:
            print(heard.line if len(args.files) == 1 else f"{path}: {heard.line}")
    return status
