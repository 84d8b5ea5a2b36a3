"""The ``teach`` command. Subcommands live one per module in ``teach.commands``.

Start-up stays fast: command modules import only the standard library at top level and
pull in heavy libraries (mujoco, rerun, networkx) inside ``run``.
"""

from __future__ import annotations

import argparse
import importlib
import io
import os
import pkgutil
import sys
from types import ModuleType
from typing import NoReturn

import teach
import teach.commands
from teach.errors import TeachError, printable

DESCRIPTION = """Teach a robot a high-level behaviour by demonstration.

Start with `make run` (a scripted teaching session) or `teach session` (live)."""


_READS_STDIN = ("session",)
"""Commands that read the teacher's lines from standard input."""


class _Parser(argparse.ArgumentParser):
    """Usage errors as every other error: one line ``teach: COMMAND: what is wrong``, exit 2."""

    def error(self, message: str) -> NoReturn:
        command = self.prog.removeprefix("teach").strip()
        where = f"{command}: " if command else ""
        self.exit(2, f"teach: {printable(where + message)} (see {self.prog} --help)\n")


def _command_modules() -> list[ModuleType]:
    names = sorted(m.name for m in pkgutil.iter_modules(teach.commands.__path__) if not m.name.startswith("_"))
    modules = [importlib.import_module(f"teach.commands.{name}") for name in names]
    return sorted(modules, key=lambda m: getattr(m, "ORDER", 50))


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="teach", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"teach {teach.__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for module in _command_modules():
        command = sub.add_parser(module.NAME, help=module.HELP, description=module.__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
        module.add_arguments(command)
        command.set_defaults(run=module.run, outputs=getattr(module, "outputs", None),
                             inputs=getattr(module, "inputs", None))
    return parser


def _safe_streams() -> bool:
    """Make printing safe whatever the terminal: text the output encoding cannot hold is written
    as escapes (``PYTHONIOENCODING=ascii``), and closed standard streams are opened on the null
    device, so no file teach opens later takes their place. Whether standard input was closed."""
    closed = sys.stdin is None
    for fd, name in ((0, "stdin"), (1, "stdout"), (2, "stderr")):
        try:
            os.fstat(fd)
        except OSError:
            closed |= fd == 0
            os.open(os.devnull, os.O_RDWR)  # takes the lowest free descriptor: this one
        if getattr(sys, name) is None:  # closed when Python started: print() would write elsewhere
            setattr(sys, name, open(fd, "r" if fd == 0 else "w", encoding="utf-8", closefd=False))
    for stream in (sys.stdout, sys.stderr):
        if isinstance(stream, io.TextIOWrapper):
            stream.reconfigure(errors="backslashreplace")
    return closed


def main(argv: list[str] | None = None) -> int:
    stdin_closed = _safe_streams()
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return 0
    from teach.lock import claim_outputs

    try:
        if stdin_closed and args.command in _READS_STDIN:
            raise TeachError(f"standard input is closed: teach {args.command} reads the teacher's lines from it "
                             "(run it in a terminal, or replay a dialogue with teach replay)", "<stdin>")
        with claim_outputs(args.outputs(args) if args.outputs else (), args.inputs(args) if args.inputs else ()):
            return int(args.run(args) or 0)
    except TeachError as error:
        print(f"teach: {printable(str(error))}", file=sys.stderr)
        return 2
    except OSError as error:  # a file the command needed could not be read or written
        where = f"{error.filename}: " if error.filename else ""
        print(f"teach: {printable(f'{where}{error.strerror or error}')}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("teach: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
