"""Where a session's files live, built once from its settings, and the only code of the session
that reads or writes them: demonstrations, tree generations, the journal, action definitions."""

from __future__ import annotations

import shutil
from pathlib import Path

from teach.bt.nodes import Node
from teach.demos import Demonstration, next_demo_path, read_demonstration, write_demonstration
from teach.domain import Domain, load_domain
from teach.errors import FormatError
from teach.fsutil import atomic_write_text
from teach.generations import last_generation, write_generation
from teach.session.journal import Journal


class SessionStore:
    def __init__(self, base: Path, session: str, record: bool):
        self.demo_dir = base / "demos" / session
        self.tree_dir = base / "trees" / session
        self.journal_path = base / "recordings" / f"{session}.journal.json"
        self.recording = base / "recordings" / f"{session}.rrd" if record else None

    def prepare(self, domain: Domain) -> None:
        """Create the session's folders; keep a copy of the domain beside its demonstrations."""
        self.demo_dir.mkdir(parents=True, exist_ok=True)
        self.tree_dir.mkdir(parents=True, exist_ok=True)
        if domain.path is not None and not (self.demo_dir / "domain.toml").exists():
            shutil.copyfile(domain.path, self.demo_dir / "domain.toml")

    def clear(self) -> None:
        """Forget an earlier session of the same name (a replay starts afresh)."""
        for stale in (self.demo_dir, self.tree_dir):
            shutil.rmtree(stale, ignore_errors=True)
        self.journal_path.unlink(missing_ok=True)

    def places(self) -> list[Path]:
        """Everything the session keeps, as a 'save' reports it."""
        places = [self.demo_dir, self.tree_dir, self.journal_path]
        return places + ([self.recording] if self.recording is not None else [])

    # --- demonstrations and generations ----------------------------------------------------

    def next_demo_path(self) -> Path:
        return next_demo_path(self.demo_dir)

    def write_demonstration(self, path: Path, demo: Demonstration) -> None:
        write_demonstration(path, demo)

    def read_demonstration(self, file: str, domain: Domain) -> Demonstration:
        return read_demonstration(self.demo_dir / file, domain)

    def last_generation(self) -> int:
        return last_generation(self.tree_dir)

    def write_generation(self, number: int, tree: Node) -> Path:
        return write_generation(self.tree_dir, number, tree)

    def read_model(self, path: Path) -> Domain:
        """Action definitions a teacher loads with 'model FILE'."""
        return load_domain(path)

    # --- the journal -----------------------------------------------------------------------

    def save_journal(self, journal: Journal) -> None:
        atomic_write_text(self.journal_path, journal.to_text())

    def has_journal(self) -> bool:
        return self.journal_path.exists()

    def load_journal(self) -> Journal:
        try:
            text = self.journal_path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise FormatError("no such session journal (was the session id right?)", self.journal_path) from None
        except UnicodeDecodeError as exc:
            raise FormatError(f"the session journal is damaged: {exc}", self.journal_path) from None
        return Journal.from_text(text, self.journal_path)
