"""Keys typed while the robot runs, read at once instead of echoed and queued: Ctrl-C stops the
robot, and a line typed meanwhile gets "wait, or press Ctrl-C" (it is not kept for after the
run, where it would start something nobody meant any more). Only on a real terminal: a pipe's
input is the lines after 'run', read in their turn."""

from __future__ import annotations

import contextlib
import os
import select
from collections.abc import Callable, Iterator

from prompt_toolkit.input import Input
from prompt_toolkit.keys import Keys

_ENTER = (Keys.ControlM, Keys.ControlJ, Keys.Enter)


def is_terminal(keyboard: Input) -> bool:
    try:
        return os.isatty(keyboard.fileno())
    except (OSError, ValueError, NotImplementedError):
        return False


class RunKeys:
    """Polled while the robot runs (with the interrupt flag): reads what was typed since."""

    def __init__(self, keyboard: Input, interrupt: Callable[[], None], typed: Callable[[str], None]):
        self.keyboard, self.interrupt, self.typed = keyboard, interrupt, typed
        self._line = ""

    @contextlib.contextmanager
    def reading(self) -> Iterator[None]:
        """Raw mode for the run: nothing typed is echoed, Ctrl-C comes as a key."""
        with self.keyboard.raw_mode():
            yield

    def poll(self) -> None:
        if not select.select([self.keyboard.fileno()], [], [], 0)[0]:
            return
        for press in self.keyboard.read_keys():
            if press.key == Keys.ControlC:
                self.interrupt()
            elif press.key in _ENTER:
                line, self._line = self._line.strip(), ""
                if line:
                    self.typed(line)
            elif len(press.data) == 1 and press.data.isprintable():
                self._line += press.data
