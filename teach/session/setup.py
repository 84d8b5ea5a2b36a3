"""The composition root: a session built from its settings, with its domain, world and recording."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from teach import messages as m
from teach.domain import Domain, load_domain
from teach.errors import TeachError
from teach.lock import session_lock
from teach.messages import Lang
from teach.observe.hook import Observer, Observers
from teach.observe.merge import print_note
from teach.protect import Input
from teach.session.journal import Journal
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.session.store import SessionStore
from teach.world.hidden import symbolic_world
from teach.world.offline import OfflineWorld
from teach.world.protocol import TeachingWorld

if TYPE_CHECKING:
    from teach.bt.groot import GrootTicker
    from teach.bt.nodes import Node

DEFAULT_DOMAIN = Path("demos/ball/domain.toml")


def default_domain() -> Domain:
    if DEFAULT_DOMAIN.is_file():
        return load_domain(DEFAULT_DOMAIN)
    from importlib.resources import files

    return load_domain(Path(str(files("teach.sim") / "assets" / "ball_in_bin.toml")))


def make_world(settings: Settings, domain: Domain, observer: Observer) -> TeachingWorld:
    if settings.world is WorldKind.MUJOCO:
        from teach.world.mujoco_world import MujocoWorld

        return MujocoWorld(domain, settings.seed, observer, settings.viewer, settings.pace, cameras=settings.record)
    if settings.viewer:
        raise TeachError("--viewer shows the MuJoCo world: use it with --world mujoco")
    if settings.world is WorldKind.SYMBOLIC:
        return symbolic_world(domain, settings.seed, observer)
    return OfflineWorld(domain)


def session_domain(settings: Settings) -> Domain:
    """The domain a new session of these settings teaches in."""
    return load_domain(settings.domain) if settings.domain else default_domain()


def dialogue_events(settings: Settings, domain: Domain) -> dict[str, tuple[tuple[str, ...], tuple[str, ...]]]:
    """Every event a dialogue for this domain may name, without building a world: the MuJoCo
    world's perturbations and the symbolic world's events (a dialogue written for one world is
    still a dialogue when replayed in another, where such a line only gets an error reply)."""
    from teach.sim.perturb import PERTURBATIONS

    events = {name: (tuple(p.en), tuple(p.de)) for name, p in PERTURBATIONS.items()}
    if settings.world is not WorldKind.OFFLINE and domain.has_model:
        events.update({name: (tuple(en), tuple(de)) for name, (en, de) in
                       symbolic_world(domain, settings.seed).events.items()})
    return events


def _world_that_fits(settings: Settings, domain: Domain, note: Callable[[str], None]) -> Settings:
    """A domain the MuJoCo world cannot compute (snacks: 'Requested') is taught in the symbolic
    world, and the teacher is told; without an action model, or with --viewer, the MuJoCo world
    itself says what it cannot compute."""
    if settings.world is not WorldKind.MUJOCO or settings.viewer or not domain.has_model:
        return settings
    from teach.sim.world import CONDITIONS

    unknown = [name for name in domain.condition_names if name not in CONDITIONS]
    if not unknown:
        return settings
    note(m.SYMBOLIC_INSTEAD(settings.lang, condition=domain.condition(unknown[0]).label(settings.lang)))
    return replace(settings, world=WorldKind.SYMBOLIC)


def resumed_settings(settings: Settings, journal: Journal) -> Settings:
    """A resumed session keeps the domain, language, budget, world, seed and learner it was started with."""
    return replace(settings, domain=Path(journal.domain) if journal.domain else None, lang=Lang.parse(journal.lang),
                   questions=journal.questions, world=WorldKind.parse(journal.world), seed=journal.seed,
                   safe=not journal.guess)


def session_inputs(settings: Settings) -> list[Input]:
    """The files a session reads that are not its own: its domain and the world file beside it."""
    if settings.domain is None:
        return []
    return [("domain file", settings.domain), ("world file", settings.domain.parent / "world.toml")]


@contextmanager
def opened_session(settings: Settings, resume: bool = False, fresh: bool = False, domain: Domain | None = None,
                   origin: str = "", note: Callable[[str], None] = print_note,
                   before_clearing: Callable[[SessionStore], None] | None = None,
                   inputs: Sequence[Input] = ()) -> Iterator[SessionManager]:
    """A new or resumed session with its world and its recording, held by this process alone
    from opening to closing. ``fresh`` forgets an earlier session of the same name: the caller
    has read and checked everything the new session needs (``domain`` among it) beforehand,
    and ``before_clearing`` may still refuse, holding the lock. Every path is checked before
    the first folder is made (``SessionStore.check_paths``; ``inputs``: what else the caller reads)."""
    SessionStore(settings.base, settings.session, settings.record).check_paths([*session_inputs(settings), *inputs])
    with session_lock(settings.base, settings.session):
        if before_clearing is not None:
            before_clearing(SessionStore(settings.base, settings.session, settings.record))
        manager = _open(settings, resume, fresh, domain, origin, note)
        try:
            yield manager
        finally:
            manager.close()


def _open(settings: Settings, resume: bool, fresh: bool, domain: Domain | None, origin: str,
          note: Callable[[str], None]) -> SessionManager:
    store = SessionStore(settings.base, settings.session, settings.record)
    leftovers = [] if fresh or store.has_journal() else store.startup_leftovers()  # fresh: cleared below
    if resume and leftovers:  # killed while starting: nothing was taught, so it starts anew
        note(f"{store.journal_path}: no journal, only what a start that was killed leaves "
             f"({', '.join(map(str, leftovers))}): nothing was taught; starting session {settings.session} anew")
        resume = False
    elif leftovers:
        note(f"{store.journal_path}: removing what a start of this session that was killed left "
             f"({', '.join(map(str, leftovers))}; nothing was taught)")
    if resume:
        journal = store.load_journal()
        settings = resumed_settings(settings, journal)
    domain = domain or session_domain(settings)
    settings = _world_that_fits(settings, domain, note)
    store.remove(leftovers)
    if fresh and not resume:
        store.clear()
    elif not resume and store.has_journal():
        raise TeachError(f"session {settings.session!r} exists already: resume it with --resume {settings.session}",
                         store.journal_path)
    missing = store.folders_missing()
    observer = Observers()
    world = make_world(settings, domain, observer)
    if settings.groot is not None:
        from teach.bt.groot import GrootTicker

        world.ticker = groot = GrootTicker(settings.groot)
        observer.observers.append(HaltBetweenRuns(groot))
    recorder = None
    started = None
    try:
        if not resume:  # the journal first: a kill from here on leaves a session --resume explains
            started = Journal(settings.session, str(domain.path or ""), settings.lang, settings.questions,
                              settings.world, settings.seed, origin=origin, guess=not settings.safe)
            store.save_journal(started)
        if store.recording is not None:
            from teach.observe.rerun_writer import RerunLogger

            recorder = RerunLogger(store.recording, settings.session, spawn=settings.spawn, resume=resume, note=note,
                                   lang=settings.lang)
            observer.observers.append(recorder)
            from teach.observe.btlog_writer import BtlogRecorder

            observer.observers.append(BtlogRecorder(store.run_dir, trees=store.tree_dir))
        if resume:
            manager = SessionManager.resume(settings, domain, world, observer)
            manager.store.save_journal(manager.journal)  # its first save writes the journal whole: compacted
        else:
            manager = SessionManager(settings, domain, world, observer, started)
    except BaseException:
        if recorder is not None:
            recorder.abandon()  # a session that did not open adds nothing to its recording
        world.close()
        store.forget_folders(missing)
        if started is not None:
            store.journal_path.unlink(missing_ok=True)
        raise
    if resume:  # only once the journal has been learned again: a failed resume moves nothing
        store.remove_interrupted_writes()
        store.retire_undone(manager.journal)
        store.bring_back_redone(manager.journal)
        for moved in store.set_aside_orphans(manager.journal):
            note(m.ORPHAN_SET_ASIDE(settings.lang, file=moved.name, folder=moved.parent))
    return manager


class HaltBetweenRuns(Observer):
    """Halts the ``--groot`` ticker's BehaviorTree.CPP tree where a run begins and ends (so no run
    inherits another's running nodes) and closes it with the session."""

    def __init__(self, groot: GrootTicker):
        self.groot = groot

    def on_run_start(self, tree: Node) -> None:
        self.groot.halt()

    def on_run_end(self, outcome: str, actions: int) -> None:
        self.groot.halt()

    def close(self) -> None:
        self.groot.close()
