"""The composition root: a session built from its settings, with its domain, world and recording."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from teach.domain import Domain, load_domain
from teach.errors import TeachError
from teach.observe.hook import Observer, Observers
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.session.store import SessionStore
from teach.world.hidden import symbolic_world
from teach.world.offline import OfflineWorld
from teach.world.protocol import TeachingWorld

DEFAULT_DOMAIN = Path("demos/ball/domain.toml")


def default_domain() -> Domain:
    if DEFAULT_DOMAIN.is_file():
        return load_domain(DEFAULT_DOMAIN)
    from importlib.resources import files

    return load_domain(Path(str(files("teach.sim") / "assets" / "ball_in_bin.toml")))


def make_world(settings: Settings, domain: Domain, observer: Observer) -> TeachingWorld:
    if settings.world is WorldKind.MUJOCO:
        from teach.world.mujoco_world import MujocoWorld

        return MujocoWorld(domain, settings.seed, observer, settings.viewer, settings.pace)
    if settings.viewer:
        raise TeachError("--viewer shows the MuJoCo world: use it with --world mujoco")
    if settings.world is WorldKind.SYMBOLIC:
        return symbolic_world(domain, settings.seed, observer)
    return OfflineWorld(domain)


def open_session(settings: Settings, resume: bool = False, fresh: bool = False) -> SessionManager:
    """A new or resumed session with its world and its recording. A resumed session keeps the
    domain, language, budget, world and seed it was started with; ``fresh`` forgets an earlier
    session of the same name."""
    store = SessionStore(settings.base, settings.session, settings.record)
    if resume:
        journal = store.load_journal()
        settings = replace(settings, domain=Path(journal.domain) if journal.domain else None, lang=journal.lang,
                           questions=journal.questions, world=WorldKind.parse(journal.world), seed=journal.seed)
    domain = load_domain(settings.domain) if settings.domain else default_domain()
    if fresh and not resume:
        store.clear()
    elif not resume and store.has_journal():
        raise TeachError(f"session {settings.session!r} exists already: resume it with --resume {settings.session}",
                         store.journal_path)
    observer = Observers()
    world = make_world(settings, domain, observer)
    if store.recording is not None:
        from teach.observe.rerun_writer import RerunLogger

        observer.observers.append(RerunLogger(store.recording, settings.session, spawn=settings.spawn, resume=resume))
    if resume:
        return SessionManager.resume(settings, domain, world, observer)
    return SessionManager(settings, domain, world, observer)
