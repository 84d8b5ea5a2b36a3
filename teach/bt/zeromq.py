"""ZeroMQ sockets through the libzmq that ``behaviortreepy`` ships, for serving Groot2 ourselves.

No Python ZeroMQ binding is a dependency, but ``behaviortreepy``'s wheel bundles libzmq (4.1.4,
in ``behaviortreepy.libs/``, loaded by its extension module): this module calls the few
functions of its C API a request-reply server needs through ``ctypes``. behaviortreepy is
imported first, so the library and the ones it needs (libsodium) are already loaded.
A socket is used by one thread at a time (ZeroMQ's rule); binding happens in the caller's
thread, so a taken port is an error there.
"""

from __future__ import annotations

import ctypes
from functools import cache
from pathlib import Path

from teach.errors import TeachError

PUB, REQ, REP = 1, 3, 4
"""Socket types (``zmq.h``)."""
_LINGER, _RCVTIMEO, _SNDTIMEO = 17, 27, 28
_SNDMORE = 2
_EAGAIN = 11
_MSG_BYTES = 64
"""``zmq_msg_t`` is an opaque 64-byte, pointer-aligned block."""


@cache
def _lib() -> ctypes.CDLL:
    import behaviortreepy

    folder = Path(behaviortreepy.__file__).resolve().parent.parent / "behaviortreepy.libs"
    found = sorted(folder.glob("libzmq*.so*"))
    if not found:
        raise TeachError(f"--groot: no libzmq in {folder} (behaviortreepy's wheel bundles one)")
    lib = ctypes.CDLL(str(found[0]))
    lib.zmq_ctx_new.restype = ctypes.c_void_p
    lib.zmq_ctx_term.argtypes = [ctypes.c_void_p]
    lib.zmq_socket.restype = ctypes.c_void_p
    lib.zmq_socket.argtypes = [ctypes.c_void_p, ctypes.c_int]
    lib.zmq_setsockopt.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p, ctypes.c_size_t]
    lib.zmq_bind.argtypes = lib.zmq_connect.argtypes = [ctypes.c_void_p, ctypes.c_char_p]
    lib.zmq_close.argtypes = [ctypes.c_void_p]
    lib.zmq_send.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int]
    lib.zmq_msg_init.argtypes = lib.zmq_msg_close.argtypes = [ctypes.c_void_p]
    lib.zmq_msg_recv.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int]
    lib.zmq_msg_data.restype = ctypes.c_void_p
    lib.zmq_msg_data.argtypes = lib.zmq_msg_size.argtypes = lib.zmq_msg_more.argtypes = [ctypes.c_void_p]
    lib.zmq_msg_size.restype = ctypes.c_size_t
    lib.zmq_strerror.restype = ctypes.c_char_p
    return lib


def _error() -> str:
    lib = _lib()
    return (lib.zmq_strerror(lib.zmq_errno()) or b"unknown error").decode()


class Context:
    """A ZeroMQ context; ``close`` it after closing its sockets."""

    def __init__(self) -> None:
        self._handle = _lib().zmq_ctx_new()

    def socket(self, kind: int, timeout_ms: int = 100) -> Socket:
        return Socket(self._handle, kind, timeout_ms)

    def close(self) -> None:
        if self._handle:
            _lib().zmq_ctx_term(self._handle)
            self._handle = None


class Socket:
    """One socket: no linger, receives and sends give up after ``timeout_ms``."""

    def __init__(self, context: int, kind: int, timeout_ms: int):
        lib = _lib()
        self._handle = lib.zmq_socket(context, kind)
        for option, value in ((_LINGER, 0), (_RCVTIMEO, timeout_ms), (_SNDTIMEO, 1000)):
            number = ctypes.c_int(value)
            lib.zmq_setsockopt(self._handle, option, ctypes.byref(number), ctypes.sizeof(number))

    def bind(self, address: str) -> None:
        if _lib().zmq_bind(self._handle, address.encode()) != 0:
            raise OSError(f"cannot bind {address}: {_error()}")

    def connect(self, address: str) -> None:
        if _lib().zmq_connect(self._handle, address.encode()) != 0:
            raise OSError(f"cannot connect to {address}: {_error()}")

    def receive(self) -> list[bytes] | None:
        """The next multipart message, or None when none came within the timeout."""
        lib, parts = _lib(), list[bytes]()
        message = ctypes.create_string_buffer(_MSG_BYTES)
        while True:
            lib.zmq_msg_init(message)
            if lib.zmq_msg_recv(message, self._handle, 0) < 0:
                lib.zmq_msg_close(message)
                if lib.zmq_errno() == _EAGAIN and not parts:
                    return None
                raise OSError(f"receiving failed: {_error()}")
            parts.append(ctypes.string_at(lib.zmq_msg_data(message), lib.zmq_msg_size(message)))
            more = lib.zmq_msg_more(message)
            lib.zmq_msg_close(message)
            if not more:
                return parts

    def send(self, parts: list[bytes]) -> None:
        lib = _lib()
        for index, part in enumerate(parts):
            flags = _SNDMORE if index < len(parts) - 1 else 0
            if lib.zmq_send(self._handle, part, len(part), flags) < 0:
                raise OSError(f"sending failed: {_error()}")

    def close(self) -> None:
        if self._handle:
            _lib().zmq_close(self._handle)
            self._handle = None
