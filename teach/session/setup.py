"""Building a session from command-line choices: domain, world, recording, resume."""

from __future__ import annotations

import re
import shutil
from dataclasses import dataclass, replace
from pathlib import Path

from teach.session.journal import Journal
from teach.session.machine import SessionConfig, SessionManager
from teach.world.offline import OfflineWorld
from teach.world.protocol import TeachingWorld
from teach.world.symbolic import SymbolicWorld
from teach.domain import Domain, load_domain
from teach.errors import TeachError
from teach.observe.hook import Observer, Observers

DEFAULT_DOMAIN = Path("demos/ball/domain.toml")
WORLDS = ("mujoco", "symbolic", "offline")


@dataclass
class SessionOptions:
    session: str
    domain: Path | None = None
    lang: str = "en"
    questions: int = 5
    seed: int = 0
    world: str = "mujoco"
    base: Path = Path(".")
    record: bool = True
    spawn: bool = False
    resume: bool = False
    fresh: bool = False
    viewer: bool = False
    pace: float = 0.0


def default_domain() -> Domain:
    if DEFAULT_DOMAIN.is_file():
        return load_domain(DEFAULT_DOMAIN)
    from importlib.resources import files

    return load_domain(Path(str(files("teach.sim") / "assets" / "ball_in_bin.toml")))


def make_world(kind: str, domain: Domain, seed: int, observer: Observer, viewer: bool = False,
               pace: float = 0.0) -> TeachingWorld:
    if kind == "mujoco":
        from teach.world.mujoco_world import MujocoWorld

        return MujocoWorld(domain, seed, observer, viewer, pace)
    if viewer:
        raise TeachError("--viewer shows the MuJoCo world: use it with --world mujoco")
    if kind == "symbolic":
        return SymbolicWorld(domain, seed, observer)
    if kind == "offline":
        return OfflineWorld(domain)
    raise TeachError(f"unknown world {kind!r} (choose from {', '.join(WORLDS)})")


SESSION_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]*$")


def open_session(options: SessionOptions) -> SessionManager:
    """A new or resumed session with its world and its recording. A resumed session keeps the
    domain, language, budget, world and seed it was started with."""
    if not SESSION_NAME.match(options.session):
        raise TeachError(f"session name {options.session!r} must be letters, digits, '-' and '_' "
                         "(it names folders under demos/ and trees/)")
    if options.resume:
        journal = Journal.load(options.base / "recordings" / f"{options.session}.journal.json")
        options = replace(options, domain=Path(journal.domain) if journal.domain else None, lang=journal.lang,
                          questions=journal.questions, world=journal.world, seed=journal.seed)
    domain = load_domain(options.domain) if options.domain else default_domain()
    if options.lang not in ("en", "de"):
        raise TeachError(f"unknown language {options.lang!r} (choose en or de)")
    if options.questions < 0:
        raise TeachError("--questions must be 0 or more")
    rrd = options.base / "recordings" / f"{options.session}.rrd"
    config = SessionConfig(options.session, domain, options.lang, options.questions, options.seed,
                           options.world, options.base, rrd if options.record else None)
    if options.fresh and not options.resume:
        for stale in (config.demo_dir, config.tree_dir):
            shutil.rmtree(stale, ignore_errors=True)
        config.journal_path.unlink(missing_ok=True)
    elif not options.resume and config.journal_path.exists():
        raise TeachError(f"session {options.session!r} exists already: resume it with --resume {options.session}",
                         config.journal_path)
    observer = Observers()
    world = make_world(options.world, domain, options.seed, observer, options.viewer, options.pace)
    if options.record:
        from teach.observe.rerun_writer import RerunLogger

        rrd.parent.mkdir(parents=True, exist_ok=True)
        observer.observers.append(RerunLogger(rrd, options.session, spawn=options.spawn, resume=options.resume))
    if options.resume:
        return SessionManager.resume(config, world, observer)
    return SessionManager(config, world, observer)
