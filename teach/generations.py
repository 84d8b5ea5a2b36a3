"""Tree generations on disk: ``gen-NN.xml`` in a folder, numbered one way for every writer."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from teach.bt.nodes import Node


def generation_path(folder: Path, number: int) -> Path:
    return folder / f"gen-{number:02d}.xml"


def last_generation(folder: Path) -> int:
    """The highest ``gen-NN.xml`` number in a folder (0 when there is none)."""
    numbers = [int(p.stem[4:]) for p in folder.glob("gen-*.xml") if p.stem[4:].isdecimal()]
    return max(numbers, default=0)


def write_generation(folder: Path, number: int, tree: Node) -> Path:
    """Write one generation atomically and return its path."""
    from teach.bt.xml import write_tree

    path = generation_path(folder, number)
    write_tree(path, tree)
    return path


def write_generations(folder: str | Path, generations: Sequence[Node], first: int = 0) -> list[Path]:
    """Write each generation, numbered from ``first``, and return the paths; generations an
    earlier run left in the folder are removed, so the highest number is this run's result."""
    folder = Path(folder)
    if folder.is_dir():
        for stale in folder.glob("gen-*.xml"):
            stale.unlink()
    return [write_generation(folder, number, tree) for number, tree in enumerate(generations, start=first)]
