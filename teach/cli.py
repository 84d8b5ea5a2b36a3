"""The ``teach`` command. Subcommands live one per module in ``teach.commands``.

Start-up stays fast: command modules import only the standard library at top level and
pull in heavy libraries (mujoco, rerun, networkx) inside ``run``.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
from types import ModuleType

import teach
import teach.commands
from teach.errors import TeachError

DESCRIPTION = """Teach a robot a high-level behaviour by demonstration.

Start with `make run` (a scripted teaching session) or `teach session` (live)."""


def _command_modules() -> list[ModuleType]:
    names = sorted(m.name for m in pkgutil.iter_modules(teach.commands.__path__) if not m.name.startswith("_"))
    modules = [importlib.import_module(f"teach.commands.{name}") for name in names]
    return sorted(modules, key=lambda m: getattr(m, "ORDER", 50))


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="teach", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"teach {teach.__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for module in _command_modules():
        command = sub.add_parser(module.NAME, help=module.HELP, description=module.__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
        module.add_arguments(command)
        command.set_defaults(run=module.run, outputs=getattr(module, "outputs", None),
                             inputs=getattr(module, "inputs", None))
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return 0
    from teach.lock import claim_outputs

    try:
        with claim_outputs(args.outputs(args) if args.outputs else (), args.inputs(args) if args.inputs else ()):
            return int(args.run(args) or 0)
    except TeachError as error:
        print(f"teach: {error}", file=sys.stderr)
        return 2
    except OSError as error:  # a file the command needed could not be read or written
        where = f"{error.filename}: " if error.filename else ""
        print(f"teach: {where}{error.strerror or error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("teach: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
