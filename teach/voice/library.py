"""An outside library voice needs, imported on first use: a missing one is one line naming its package."""

from __future__ import annotations

import importlib
from types import ModuleType

from teach.errors import TeachError


class VoiceUnavailable(TeachError):
    """Voice cannot work here: a library is missing, or a language cannot be heard."""


def require(module: str, package: str) -> ModuleType:
    """``module`` imported, or ``VoiceUnavailable`` naming the package to install."""
    try:
        return importlib.import_module(module)
    except (ImportError, OSError) as error:  # OSError: a wheel whose shared library cannot load
        raise VoiceUnavailable(f"voice needs the Python package {package!r} "
                               f"(pip install {package}): {error}") from None
