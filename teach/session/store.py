"""Where a session's files live, built once from its settings, and the only code of the session
that reads or writes them: demonstrations, tree generations, the journal, action definitions."""

from __future__ import annotations

import os
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from teach import limits
from teach.bt.nodes import Node
from teach.demos import Demonstration, read_demonstration, write_demonstration
from teach.domain import Domain, load_domain
from teach.errors import FormatError, TeachError
from teach.fsutil import append_durably, atomic_write_text, check_output, check_output_folder, read_bytes, read_text
from teach.generations import last_generation, write_generation
from teach.protect import Input, Output, refuse_inputs
from teach.session.journal import DemoLearned, Journal, Saved, effective_events

if TYPE_CHECKING:
    from teach.sim.guided_skill import GuidedMotion

UNDONE = "undone"
ORPHANED = "orphaned"


def session_root(base: Path) -> Path:
    """The folder below which no part of a session's paths may be a symbolic link: the working
    folder when ``base`` lies in it, else the one holding ``base``; so ``--base LINK`` (and
    ``--base LINK/sub``) is refused as a link inside the project would be."""
    here, absolute = Path(os.path.abspath(os.curdir)), Path(os.path.abspath(base))
    return here if absolute == here or here in absolute.parents else absolute.parent


class SessionStore:
    def __init__(self, base: Path, session: str, record: bool):
        self.base = base
        self.demo_dir = base / "demos" / session
        self.tree_dir = base / "trees" / session
        self.journal_path = base / "recordings" / f"{session}.journal.json"
        self.recording = base / "recordings" / f"{session}.rrd" if record else None
        self.run_dir = base / "recordings" / session  # run-NNN.btlog, each run for Groot2
        self._saved: Saved | None = None
        """What this store last wrote to the journal file; None: its next save writes it whole."""

    def outputs(self) -> list[Output]:
        """Everything the session may write: its folders whole, its journal, its recording and the
        files a resume merges it through."""
        files = [self.journal_path]
        if self.recording is not None:
            files += [self.recording.with_name(self.recording.name + suffix)
                      for suffix in ("", ".part", ".crashed", ".merged")]
            files += [self.recording.with_name(self.recording.stem + suffix) for suffix in (".damaged.rrd",
                                                                                            ".resumed.rrd")]
        return [("owned", folder) for folder in (self.demo_dir, self.tree_dir, self.run_dir)] + \
            [("file", file) for file in files]

    def check_paths(self, inputs: Sequence[Input]) -> None:
        """Refuse, before anything is created, a session whose files could not be written safely:
        a symbolic link, a special file or a file where a folder belongs anywhere from ``--base``
        down (the journal, read back on resume, included), or an input (the domain, its world,
        a dialogue, an oracle) inside the session's folders or equal to one of its files."""
        refuse_inputs(self.outputs(), inputs)
        root = session_root(self.base)
        for kind, path in self.outputs():
            if kind == "file":
                check_output(path, root)
            else:
                check_output_folder(path, root)
                _no_links_inside(path)

    def prepare(self, domain: Domain) -> None:
        """Create the session's folders; keep a copy of the domain beside its demonstrations."""
        self.demo_dir.mkdir(parents=True, exist_ok=True)
        self.tree_dir.mkdir(parents=True, exist_ok=True)
        if domain.path is not None and not (self.demo_dir / "domain.toml").exists():
            atomic_write_text(self.demo_dir / "domain.toml", read_text(domain.path, "domain file",
                                                                       limits.MAX_DOMAIN_BYTES))

    def clear(self) -> None:
        """Forget an earlier session of the same name (a replay starts afresh; only called once
        everything the new session needs has been read and checked)."""
        for stale in (self.demo_dir, self.tree_dir, self.run_dir):
            shutil.rmtree(stale, ignore_errors=True)
        self.journal_path.unlink(missing_ok=True)
        self._saved = None

    def startup_leftovers(self) -> list[Path]:
        """What a start killed before the session's first journal leaves: its folders holding
        at most the domain copy, an unfinished recording. Taught data without a journal (a
        demonstration, a generation, a run) is not a start's, and is refused rather than touched."""
        found: list[Path] = []
        for folder, allowed in ((self.demo_dir, {"domain.toml"}), (self.tree_dir, set()), (self.run_dir, set())):
            if not folder.is_dir():
                continue
            extra = sorted(p.name for p in folder.iterdir() if p.name not in allowed and not _interrupted(p.name))
            if extra:
                raise TeachError(f"holds {extra[0]}, but the session has no journal: it was not left by a start "
                                 "that was killed; move it away or choose another session name", folder)
            found.append(folder)
        part = self.journal_path.with_name(f"{self.demo_dir.name}.rrd.part")  # recorded or not this time
        return found + ([part] if part.is_file() else [])

    def remove(self, leftovers: list[Path]) -> None:
        """Remove what ``startup_leftovers`` found."""
        for path in leftovers:
            if path.is_dir():
                shutil.rmtree(path)
            else:
                path.unlink(missing_ok=True)

    def exists(self) -> bool:
        """Whether anything of a session of this name is on disk."""
        return any(place.exists() for place in (self.demo_dir, self.tree_dir, self.journal_path))

    def folders_missing(self) -> list[Path]:
        """The session's folders not yet on disk (``forget_folders`` removes them again)."""
        return [folder for folder in (self.demo_dir, self.tree_dir) if not folder.exists()]

    def forget_folders(self, folders: list[Path]) -> None:
        """Remove folders a session that failed to open had just created."""
        for folder in folders:
            shutil.rmtree(folder, ignore_errors=True)

    def set_aside_orphans(self, journal: Journal) -> list[Path]:
        """Move demonstrations the journal does not name (written just before a kill, never
        acknowledged) into ``orphaned/``, so the folder holds exactly the session's demonstrations."""
        named = {event.file for event in journal.events if isinstance(event, DemoLearned)}
        return self._move_aside([p for p in sorted(self.demo_dir.glob("demo-*.csv")) if p.name not in named],
                                ORPHANED)

    def remove_interrupted_writes(self) -> None:
        """Delete what atomic writes a kill cut short left (``.NAME.*.tmp``, never renamed onto
        NAME): no reader takes them, and left alone they pile up beside the session's files.
        Only called holding the session's lock, so no write of this session is under way."""
        found = sorted(self.journal_path.parent.glob(f".{self.journal_path.name}.*.tmp"))
        for folder in (self.demo_dir, self.tree_dir):
            found += sorted(folder.glob(".*.tmp"))
        for path in found:
            path.unlink(missing_ok=True)

    def retire_undone(self, journal: Journal) -> list[Path]:
        """Move the demonstrations an undo took back into ``undone/``, so ``teach learn`` on the
        folder trains only on what the session learned (also on resume, after a kill between the
        journal line and the move)."""
        kept = _learned_files(journal)
        undone = {event.file for event in journal.events if isinstance(event, DemoLearned)} - kept
        return self._move_aside([self.demo_dir / name for name in sorted(undone) if (self.demo_dir / name).is_file()],
                                UNDONE)

    def bring_back_redone(self, journal: Journal) -> list[Path]:
        """Move the demonstrations a redo brought back out of ``undone/`` again (the reverse of
        ``retire_undone``; also on resume, after a kill between the journal line and the move)."""
        back = []
        for name in sorted(_learned_files(journal)):
            aside, home = self.demo_dir / UNDONE / name, self.demo_dir / name
            if aside.is_file() and not home.exists():
                aside.replace(home)
                back.append(home)
        return back

    def _move_aside(self, paths: list[Path], folder: str) -> list[Path]:
        if not paths:
            return []
        aside = self.demo_dir / folder
        aside.mkdir(exist_ok=True)
        moved = []
        for path in paths:
            target = aside / path.name
            if target.exists():
                target = aside / f"{path.stem}-{len(list(aside.iterdir()))}{path.suffix}"
            path.replace(target)
            moved.append(target)
        return moved

    def places(self) -> list[Path]:
        """Everything the session keeps, as a 'save' reports it."""
        places = [self.demo_dir, self.tree_dir, self.journal_path]
        return places + ([self.recording] if self.recording is not None else [])

    # --- demonstrations and generations ----------------------------------------------------

    def next_demo_path(self) -> Path:
        """The next ``demo-NNN.csv``, never a number an undone or orphaned demonstration had (the
        journal names files, so a number is never reused)."""
        used = [int(p.stem[5:]) for folder in (self.demo_dir, self.demo_dir / UNDONE, self.demo_dir / ORPHANED)
                for p in folder.glob("demo-*.csv") if p.stem[5:].isdecimal()]
        return self.demo_dir / f"demo-{max(used, default=0) + 1:03d}.csv"

    def write_demonstration(self, path: Path, demo: Demonstration) -> None:
        write_demonstration(path, demo)

    def read_demonstration(self, file: str, domain: Domain) -> Demonstration:
        return read_demonstration(_own(self.demo_dir / file), domain)

    def last_generation(self) -> int:
        return last_generation(self.tree_dir)

    def write_generation(self, number: int, tree: Node) -> Path:
        return write_generation(self.tree_dir, number, tree)

    def read_model(self, path: Path) -> Domain:
        """Action definitions a teacher loads with 'model FILE'."""
        return load_domain(path)

    # --- actions taught by guidance (issue 12) ---------------------------------------------

    def add_action(self, block: str) -> Domain:
        """Append an ``[[action]]`` table to the session's copy of its domain (atomically) and
        read the domain back, checked as every domain file is."""
        copy = self.demo_dir / "domain.toml"
        if not copy.is_file():
            raise FormatError("the session keeps no copy of its domain to add an action to", copy)
        atomic_write_text(copy, read_text(copy, "domain file", limits.MAX_DOMAIN_BYTES, links=False).rstrip("\n")
                          + "\n\n" + block)
        return load_domain(copy)

    def session_domain(self) -> Domain:
        """The session's own domain copy, with the actions taught by guidance."""
        return load_domain(_own(self.demo_dir / "domain.toml"))

    def write_motion(self, motion: GuidedMotion) -> str:
        """Save a guided motion beside the domain copy; its file name, for the journal."""
        from teach.sim.guided_skill import save_motion

        path = self.demo_dir / f"{motion.name}.motion.json"
        save_motion(motion, path)
        return path.name

    def read_motion(self, file: str, domain: Domain) -> GuidedMotion:
        from teach.sim.guided_skill import load_motion

        return load_motion(_own(self.demo_dir / file), domain)

    # --- the journal -----------------------------------------------------------------------

    def save_journal(self, journal: Journal) -> None:
        """The journal on disk, durably: this store's first save writes it whole as one line,
        atomically (which compacts a resumed session's file), every later one appends and fsyncs
        the line of what changed since (nothing when nothing did), so a save's cost does not grow
        with the session. After a failed write the next save writes the file whole again."""
        line = journal.changes_since(self._saved) if self._saved is not None else None
        if line == "":
            return
        self._saved = None
        if line is None:
            atomic_write_text(self.journal_path, journal.snapshot_text())
        else:
            append_durably(self.journal_path, line.encode("utf-8"))
        self._saved = journal.saved()

    def has_journal(self) -> bool:
        return self.journal_path.exists()

    def load_journal(self) -> Journal:
        """The journal, read through the bounded reader and checked against its schema."""
        if not self.journal_path.exists() and not self.journal_path.is_symlink():
            raise FormatError("no such session journal (was the session id right?)", self.journal_path)
        return Journal.from_bytes(read_bytes(self.journal_path, "session journal", limits.MAX_JSON_BYTES, links=False),
                                  self.journal_path)


def _no_links_inside(folder: Path) -> None:
    """Refuse a symbolic link anywhere in one of the session's folders: all it holds the session
    wrote itself, and reads back or moves."""
    for top, folders, files in os.walk(folder):
        for name in folders + files:
            if os.path.islink(os.path.join(top, name)):
                raise FormatError("is a symbolic link: a session's own files are never read or written through "
                                  "one", Path(top) / name)


def _own(path: Path) -> Path:
    """``path``, a file of the session's own, refused when it is a symbolic link: what a session
    reads back it wrote itself, never through a link to somewhere else."""
    if path.is_symlink():
        raise FormatError("is a symbolic link: a session's own files are never read through one", path)
    return path


def _interrupted(name: str) -> bool:
    """A temporary file of an atomic write a kill cut short (``.NAME.*.tmp``)."""
    return name.startswith(".") and name.endswith(".tmp")


def _learned_files(journal: Journal) -> set[str]:
    """The demonstration files the journal's learning holds (undone ones left out, redone ones in)."""
    return {event.file for event in effective_events(journal.events) if isinstance(event, DemoLearned)}
