"""The one way files come in and go out.

Reading: every input (domain, demonstration, tree, dialogue, journal) goes through
``read_bytes``/``read_text``, which refuse anything that is not a regular file without blocking
on it, read at most a stated number of bytes whatever the file system claims, and give one
line ``file:line: what is wrong`` for text that is not UTF-8 or holds NUL bytes.
``check_nesting`` bounds TOML and JSON nesting before a recursive parser sees it, and
``read_json`` with ``validate`` is a typed JSON reader (a schema, not ``dict.get``).

Writing: every output goes through ``atomic_write_bytes``: a temporary file in the same folder,
fsynced, renamed over the target, the folder fsynced; it refuses to replace anything that is
not a regular file and to write through a symbolic link inside the project, removes its
temporary file on every error and turns OS errors into one line naming the file.
``append_durably`` adds to a file written that way (the session journal's saves): fsynced, and
cut back to where it was on an error, so no half line stays.
"""

from __future__ import annotations

import errno
import json
import os
import re
import stat
import tempfile
from collections.abc import Mapping
from pathlib import Path

from teach import limits
from teach.errors import FormatError, TeachError

_BOM = b"\xef\xbb\xbf"


# --- reading ------------------------------------------------------------------------------------

def _kind(mode: int) -> str:
    """What a non-regular file is, in words."""
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISLNK(mode):
        return "a symbolic link"
    return "not a regular file"


def open_regular(path: str | Path, what: str, links: bool = True) -> int:
    """A read-only descriptor of a regular file, or a one-line ``FormatError``. Special files
    (pipes, devices, sockets, folders; with ``links`` False, symbolic links too) are refused
    before they are opened (``lstat``, then the link's target), the open never blocks (a FIFO
    swapped in cannot hang it) and what was opened is checked again."""
    try:
        before = os.lstat(path)
        if stat.S_ISLNK(before.st_mode) and links:
            before = os.stat(path)
        if not stat.S_ISREG(before.st_mode):
            raise FormatError(f"is {_kind(before.st_mode)}, not a {what}", path)
        nofollow = 0 if links else os.O_NOFOLLOW
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC | nofollow)
    except OSError as exc:
        raise FormatError(f"cannot read {what}: {exc.strerror}", path) from None
    opened = os.fstat(fd)
    if not stat.S_ISREG(opened.st_mode):  # replaced between lstat and open
        os.close(fd)
        raise FormatError(f"is {_kind(opened.st_mode)}, not a {what}", path)
    return fd


def read_bytes(path: str | Path, what: str, limit: int, links: bool = True) -> bytes:
    """At most ``limit`` bytes of a regular file opened by ``open_regular``; the size is counted
    while reading, never taken from st_size."""
    fd = open_regular(path, what, links)
    try:
        chunks: list[bytes] = []
        total = 0
        while total <= limit:
            chunk = os.read(fd, min(1 * limits.MIB, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
    except OSError as exc:
        raise FormatError(f"cannot read {what}: {exc.strerror}", path) from None
    finally:
        os.close(fd)
    if total > limit:
        raise FormatError(f"{what} is more than the {limit} bytes accepted", path)
    return b"".join(chunks)


def decode_text(data: bytes, what: str, path: str | Path) -> str:
    """UTF-8 text without a byte-order mark; invalid UTF-8 and NUL bytes are refused with their line."""
    if data.startswith(_BOM):
        data = data[len(_BOM):]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise FormatError(f"not a UTF-8 text file (binary data or another encoding?): expected a {what}",
                          path, line) from None
    nul = text.find("\x00")
    if nul >= 0:
        raise FormatError(f"holds NUL bytes, so it is not a text file: expected a {what}", path,
                          text.count("\n", 0, nul) + 1)
    return text


def read_text(path: str | Path, what: str, limit: int = limits.MAX_JSON_BYTES, links: bool = True) -> str:
    """A UTF-8 text file of at most ``limit`` bytes, or a one-line ``FormatError`` naming ``what``
    it should have been."""
    return decode_text(read_bytes(path, what, limit, links), what, path)


_JSON_TOKENS = re.compile(r'"(?:[^"\\]|\\.)*"|[\[\]{}]', re.DOTALL)
_TOML_TOKENS = (r'"""(?:[^\\]|\\.)*?"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*|[\[\]{}]')
_TOML_KEY_PART = r'(?:[A-Za-z0-9_-]+|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\')[ \t]*\.[ \t]*'


def check_nesting(text: str, path: str | Path, syntax: str, limit: int = limits.MAX_NESTING) -> None:
    """Refuse ``text`` (``syntax`` "json" or "toml") whose arrays, tables or objects nest deeper
    than ``limit``, before a recursive parser can run out of stack on it."""
    if syntax == "json":
        tokens = _JSON_TOKENS
    else:  # a dotted key a.b.c nests tables too
        tokens = re.compile(f"(?P<dotted>(?:{_TOML_KEY_PART}){{{limit},}})|{_TOML_TOKENS}", re.DOTALL)
    depth = 0
    for match in tokens.finditer(text):
        token = match.group()
        if match.groupdict().get("dotted"):
            line = text.count("\n", 0, match.start()) + 1
            raise FormatError(f"a dotted key nests more than {limit} levels deep", path, line)
        if token in ("[", "{"):
            depth += 1
            if depth > limit:
                line = text.count("\n", 0, match.start()) + 1
                raise FormatError(f"nested more than {limit} levels deep", path, line)
        elif token in ("]", "}"):
            depth = max(0, depth - 1)


_JSON_CONSTANTS = re.compile(r'"(?:[^"\\]|\\.)*"|(-?Infinity|NaN)', re.DOTALL)


def parse_json(text: str, path: str | Path, what: str = "JSON file", depth: int = limits.MAX_NESTING) -> object:
    """JSON with bounded nesting and without NaN or Infinity (which JSON does not have)."""
    check_nesting(text, path, "json", depth)
    for match in _JSON_CONSTANTS.finditer(text):
        if match.group(1):
            line = text.count("\n", 0, match.start()) + 1
            raise FormatError(f"{what} holds {match.group(1)}, which is not a JSON number", path, line)
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise FormatError(f"{what} is not valid JSON: {exc.msg}", path, exc.lineno) from None


def read_json(path: str | Path, what: str = "JSON file", limit: int = limits.MAX_JSON_BYTES,
              depth: int = limits.MAX_NESTING) -> object:
    """A bounded JSON file (size, nesting, no NaN/Infinity); check its shape with ``validate``."""
    return parse_json(read_text(path, what, limit), path, what, depth)


_TYPE_NAMES = {str: "a string", int: "an integer", float: "a number", bool: "true or false", list: "a list",
               dict: "an object", type(None): "null"}
Types = type | tuple[type, ...]


def _is(value: object, types: Types) -> bool:
    """``isinstance`` where a bool is not an integer and an integer is a number."""
    kinds = types if isinstance(types, tuple) else (types,)
    for kind in kinds:
        if kind is int and isinstance(value, bool):
            continue
        if kind is float and isinstance(value, (int, float)) and not isinstance(value, bool):
            return True
        if isinstance(value, kind):
            return True
    return False


def _type_name(types: Types) -> str:
    kinds = types if isinstance(types, tuple) else (types,)
    return " or ".join(_TYPE_NAMES.get(kind, kind.__name__) for kind in kinds)


def validate(data: object, path: str | Path, required: Mapping[str, Types],
             optional: Mapping[str, Types] | None = None, where: str = "", extra: bool = False) -> dict[str, object]:
    """``data`` as an object whose ``required`` keys are present with the given types and whose
    ``optional`` keys, where present, have theirs; other keys are refused unless ``extra``.
    Errors read ``file: where.key: what is wrong``."""
    prefix = f"{where}: " if where else ""
    if not isinstance(data, dict):
        raise FormatError(f"{prefix}must be {_type_name(dict)}, got {_shown(data)}", path)
    optional = optional or {}
    for key, types in required.items():
        if key not in data:
            raise FormatError(f"{prefix}{key}: missing (it must be {_type_name(types)})", path)
    for key, value in data.items():
        expected = required[key] if key in required else optional.get(key)
        if expected is None:
            if extra:
                continue
            raise FormatError(f"{prefix}{key}: unknown key (known: {', '.join(sorted({**required, **optional}))})",
                              path)
        if not _is(value, expected):
            raise FormatError(f"{prefix}{key}: must be {_type_name(expected)}, got {_shown(value)}", path)
    return data


def _shown(value: object) -> str:
    text = json.dumps(value, ensure_ascii=False) if not isinstance(value, float) else repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


# --- writing ------------------------------------------------------------------------------------

def _project_root(target: Path, root: str | Path | None) -> Path | None:
    """The folder below which no component of ``target``'s path may be a symbolic link: ``root``
    if given, else the working folder when ``target`` lies in it; None outside the project."""
    base = Path(os.path.abspath(root if root is not None else os.curdir))
    absolute = Path(os.path.abspath(target))
    if absolute == base or base in absolute.parents:
        return base
    return None


def check_output(path: str | Path, root: str | Path | None = None) -> Path:
    """Refuse an output path before anything is written: the target must be a regular file or
    not exist, and no folder between the project root and it may be a symbolic link or a file.
    Leaves nothing behind (writability is probed with a file created and removed at once)."""
    target = Path(path)
    check_output_folder(target.parent, root, _for=target)
    _refuse_special(target)
    return target


def _refuse_special(target: Path) -> None:
    """Only a regular file (or nothing) may be replaced: never a link, pipe, device or folder."""
    try:
        info = os.lstat(target)
    except FileNotFoundError:
        return
    except OSError as exc:
        raise TeachError(f"cannot write here: {exc.strerror}", target) from None
    if stat.S_ISDIR(info.st_mode):
        raise TeachError("is a folder: give a file name to write", target)
    if not stat.S_ISREG(info.st_mode):
        raise TeachError(f"is {_kind(info.st_mode)}: refusing to replace it with a file", target)


def check_output_folder(folder: str | Path, root: str | Path | None = None, _for: Path | None = None) -> Path:
    """Refuse a folder that outputs are to be written into: it and every folder between the project
    root and it must be a real folder (not a symbolic link, not a file) or not exist yet, and the
    nearest existing one must be writable. Leaves nothing behind."""
    folder = Path(folder)
    named = _for if _for is not None else folder
    base = _project_root(folder, root)
    absolute = Path(os.path.abspath(folder))
    chain = [absolute, *absolute.parents]
    inside = [p for p in chain if base is not None and (p == base or base in p.parents) and p != base]
    for part in reversed(inside):
        try:
            info = os.lstat(part)
        except FileNotFoundError:
            break
        except OSError as exc:
            raise TeachError(f"cannot write here: {exc.strerror}", named) from None
        if stat.S_ISLNK(info.st_mode):
            raise TeachError(f"the folder {_display(part)} is a symbolic link: refusing to write through it", named)
        if not stat.S_ISDIR(info.st_mode):
            raise TeachError(f"{_display(part)} is not a folder", named)
    existing = next((p for p in chain if os.path.lexists(p)), None)
    if existing is not None:
        if not os.path.isdir(existing):
            raise TeachError(f"{_display(existing)} is not a folder", named)
        _probe(existing, named)
    return folder


def _probe(folder: Path, named: Path) -> None:
    """Create and remove a file in ``folder``: the only test of writability that also holds for
    root, read-only mounts and virtual file systems."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".teach-probe-", dir=folder)
    except OSError as exc:
        raise TeachError(f"cannot write here: {exc.strerror} (in {_display(folder)})", named) from None
    os.close(fd)
    os.unlink(probe)


def _display(part: Path) -> str:
    """A path as the user would name it: relative inside the working folder, else absolute."""
    here = Path(os.path.abspath(os.curdir))
    return os.path.relpath(part, here) if part == here or here in part.parents else str(part)


def atomic_write_text(path: str | Path, text: str, root: str | Path | None = None) -> None:
    """Write ``text`` to ``path`` as UTF-8 through ``atomic_write_bytes``."""
    atomic_write_bytes(path, text.encode("utf-8"), root)


def atomic_write_bytes(path: str | Path, data: bytes, root: str | Path | None = None) -> None:
    """Write via a fsynced temporary file and a rename, so a crash or a full disk leaves the old
    file or the new one, never half of either. The file gets the mode a plain write would give
    (the umask's); ``check_output`` decides what may be replaced; every OS error is one
    ``TeachError`` naming the file, and the temporary file is removed."""
    target = check_output(path, root)
    tmp: str | None = None
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(tmp, 0o666 & ~_umask())
        _refuse_special(target)  # again, just before replacing it
        os.replace(tmp, target)
        tmp = None
        _fsync_folder(target.parent)
    except OSError as exc:
        raise TeachError(f"cannot write: {exc.strerror or exc}", target) from None
    finally:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


def append_durably(path: str | Path, data: bytes) -> None:
    """Append ``data`` to an existing regular file (never through a symbolic link) and fsync it,
    so a save costs what it adds. An OS error is one ``TeachError`` naming the file, and the file
    is cut back to its length before, so what follows is never appended to half of this."""
    target = Path(path)
    try:
        fd = os.open(target, os.O_WRONLY | os.O_APPEND | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError as exc:
        raise TeachError(f"cannot write: {exc.strerror or exc}", target) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise TeachError(f"is {_kind(info.st_mode)}: refusing to append to it", target)
        try:
            rest = memoryview(data)
            while rest:
                rest = rest[os.write(fd, rest):]
            os.fsync(fd)
        except OSError as exc:
            try:
                os.ftruncate(fd, info.st_size)
            except OSError:
                pass
            raise TeachError(f"cannot write: {exc.strerror or exc}", target) from None
    finally:
        os.close(fd)


def _fsync_folder(folder: Path) -> None:
    """Make a rename in ``folder`` durable (file systems that cannot fsync a folder are let be)."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        os.fsync(fd)
    except OSError as exc:
        if exc.errno not in (errno.EINVAL, errno.ENOTSUP):
            raise
    finally:
        os.close(fd)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
