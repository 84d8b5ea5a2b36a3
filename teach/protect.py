"""Outputs never replace inputs: a command refuses, before it writes anything, an output path
that is one of the files it reads or lies inside a demonstration set it reads.

A successful command must not destroy taught data (``teach learn SET -o SET/a-good.csv`` once
replaced a demonstration with XML). Every writing command names what it reads (``Input``) and
``refuse_inputs`` compares each output with them twice: by the path with every symbolic link
resolved, and by device and inode (a hard link or a link outside the project is the same file).
A demonstration set is protected whole: its folder, everything inside it, and its domain file
(in the folder or its parent).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from teach.errors import TeachError

Input = tuple[str, Path]
"""What a command reads: ("set", folder of demonstrations) or (what the file is, path), e.g.
("tree file", tree.xml), ("domain file", domain.toml)."""

Output = tuple[str, Path]
"""What a command writes: ("file", path), ("folder", path) written into, ("set", folder recorded
into), or ("owned", folder) a command may empty whole (a session's folders)."""


def resolved(path: str | Path) -> Path:
    """``path`` absolute, with every symbolic link of its existing part resolved (a link loop is
    left as it is: its reader refuses it)."""
    return Path(os.path.realpath(path))


def _identity(path: Path) -> tuple[int, int] | None:
    try:
        info = os.stat(path)
    except (OSError, ValueError):
        return None
    return info.st_dev, info.st_ino


@dataclass
class Protected:
    """Everything a command reads, as paths and as (device, inode) pairs."""

    files: dict[Path, tuple[str, Path]] = field(default_factory=dict)
    """Resolved path -> (what it is, the path as given)."""
    inodes: dict[tuple[int, int], tuple[str, Path]] = field(default_factory=dict)
    sets: dict[Path, Path] = field(default_factory=dict)
    """Resolved set folder -> the folder as given."""

    def add_file(self, what: str, path: Path) -> None:
        self.files.setdefault(resolved(path), (what, path))
        if (identity := _identity(path)) is not None:
            self.inodes.setdefault(identity, (what, path))

    def add_set(self, folder: Path) -> None:
        self.sets.setdefault(resolved(folder), folder)
        if (identity := _identity(folder)) is not None:
            self.inodes.setdefault(identity, ("demonstration set", folder))
        domain = _set_domain(Path(folder))
        if domain is not None:
            self.add_file("domain file", domain)
        try:
            with os.scandir(folder) as entries:
                for entry in entries:
                    if entry.is_file(follow_symlinks=False):  # a link inside is refused by the set's reader
                        what = "demonstration" if entry.name.endswith(".csv") else "file of the demonstration set"
                        self.add_file(what, Path(folder) / entry.name)
        except OSError:  # not a folder after all, or unreadable: its reader says so
            pass


def _set_domain(folder: Path) -> Path | None:
    """The domain file a set is read with (in the folder or its parent), if there is one."""
    for candidate in (folder / "domain.toml", folder.parent / "domain.toml"):
        if os.path.isfile(candidate):
            return candidate
    return None


def protected(inputs: Iterable[Input]) -> Protected:
    """What ``inputs`` protect (missing paths too: the command's reader refuses those itself)."""
    found = Protected()
    for what, path in inputs:
        if what == "set" or os.path.isdir(path):
            found.add_set(Path(path))
        else:
            found.add_file(what, Path(path))
    return found


def refuse_inputs(outputs: Sequence[Output], inputs: Iterable[Input]) -> None:
    """Raise a one-line ``TeachError`` naming the first output that is an input, or lies in a
    demonstration set the command reads, or (a folder written into) holds an input directly, or
    (a folder the command owns) holds one anywhere."""
    guard = protected(inputs)
    for kind, path in outputs:
        target = resolved(path)
        same = guard.files.get(target) or guard.inodes.get(_identity(path) or (-1, -1))
        if same is not None and same[0] == "demonstration set":
            raise TeachError(f"is the demonstration set {same[1]} that this command reads: "
                             f"write the output elsewhere", path)
        if same is not None:
            raise TeachError(f"is the {same[0]} {same[1]} that this command reads: write the output elsewhere",
                             path)
        inside = next((given for folder, given in guard.sets.items()
                       if target == folder or folder in target.parents), None)
        if inside is not None:
            raise TeachError(f"lies inside the demonstration set {inside} that this command reads: "
                             f"write the output outside it", path)
        if kind != "file":
            held = next((given for file, (_, given) in guard.files.items()
                         if file.parent == target or (kind == "owned" and target in file.parents)), None)
            if held is not None:
                raise TeachError(f"holds {held}, which this command reads: write into another folder", path)
