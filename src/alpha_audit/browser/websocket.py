"""A minimal RFC 6455 WebSocket client for loopback text messages (WebDriver BiDi).

No WebSocket library is among alpha-audit's dependencies and BiDi needs only a
small part of the protocol: one client connection to ``127.0.0.1``, text
messages (possibly fragmented), pings answered, close.  Frames we send are
masked as RFC 6455 section 5.3 requires of clients; frames we receive are not.
"""

from __future__ import annotations

import base64
import contextlib
import hashlib
import os
import socket
import struct
import time
from urllib.parse import urlsplit

from alpha_audit.browser.interface import BrowserError

__all__ = ["WebSocket", "accept_key"]

# RFC 6455, section 1.3: the GUID appended to the client's key.
_GUID = b"258EAFA5-E914-47DA-95CA-C5AB0DC85B11"
_CONTINUATION, _TEXT, _BINARY, _CLOSE, _PING, _PONG = 0x0, 0x1, 0x2, 0x8, 0x9, 0xA
# A message larger than this is refused rather than buffered (our pages send a few tens of MB).
MAX_MESSAGE_BYTES = 512 * 1024 * 1024


def accept_key(key: str) -> str:
    """``Sec-WebSocket-Accept`` for a ``Sec-WebSocket-Key`` (RFC 6455, section 4.2.2).

    >>> accept_key("dGhlIHNhbXBsZSBub25jZQ==")  # the RFC's own example
    's3pPLMBiTxaQ9kYGzzhZRbK+xOo='
    """
    return base64.b64encode(hashlib.sha1(key.encode("ascii") + _GUID).digest()).decode("ascii")


class WebSocket:
    """One client connection to a ``ws://127.0.0.1:PORT/path`` URL."""

    def __init__(self, url: str, *, timeout: float = 10.0) -> None:
        parts = urlsplit(url)
        if parts.scheme != "ws" or parts.hostname not in ("127.0.0.1", "localhost", "::1"):
            raise BrowserError(f"refusing WebSocket URL {url!r}: only ws:// on loopback")
        self._sock = socket.create_connection((parts.hostname, parts.port or 80), timeout=timeout)
        self._buffer = bytearray()
        try:
            self._handshake(parts.netloc, parts.path or "/", timeout)
        except BaseException:
            self._sock.close()
            raise

    def _handshake(self, host: str, path: str, timeout: float) -> None:
        key = base64.b64encode(os.urandom(16)).decode("ascii")
        request = (
            f"GET {path} HTTP/1.1\r\nHost: {host}\r\nUpgrade: websocket\r\n"
            f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n"
        )
        self._sock.sendall(request.encode("ascii"))
        deadline = time.monotonic() + timeout
        while b"\r\n\r\n" not in self._buffer:
            self._fill(deadline)
        end = self._buffer.index(b"\r\n\r\n")
        head = bytes(self._buffer[:end])
        del self._buffer[: end + 4]
        lines = head.decode("latin-1").split("\r\n")
        if len(lines[0].split()) < 2 or lines[0].split()[1] != "101":
            raise BrowserError(f"WebSocket handshake refused: {lines[0]!r}")
        headers = {
            k.strip().lower(): v.strip() for k, _, v in (x.partition(":") for x in lines[1:])
        }
        if headers.get("sec-websocket-accept") != accept_key(key):
            raise BrowserError("WebSocket handshake: wrong Sec-WebSocket-Accept")

    def _fill(self, deadline: float) -> None:
        left = deadline - time.monotonic()
        if left <= 0:
            raise BrowserError("WebSocket peer did not answer in time")
        self._sock.settimeout(left)
        try:
            chunk = self._sock.recv(1 << 20)
        except TimeoutError as exc:
            raise BrowserError("WebSocket peer did not answer in time") from exc
        except OSError as exc:
            raise BrowserError(f"WebSocket connection lost: {exc}") from exc
        if not chunk:
            raise BrowserError("WebSocket connection closed by the browser")
        self._buffer += chunk

    def _take(self, count: int, deadline: float) -> bytes:
        while len(self._buffer) < count:
            self._fill(deadline)
        data = bytes(self._buffer[:count])
        del self._buffer[:count]  # cheap: bytearray deletes from the front in place
        return data

    def _send_frame(self, opcode: int, payload: bytes) -> None:
        head = bytes([0x80 | opcode])
        n = len(payload)
        if n < 126:
            head += bytes([0x80 | n])
        elif n < 1 << 16:
            head += bytes([0x80 | 126]) + struct.pack("!H", n)
        else:
            head += bytes([0x80 | 127]) + struct.pack("!Q", n)
        mask = os.urandom(4)
        # XOR with the repeated 4-byte key, via one big-integer operation (fast for MBs).
        repeated = (mask * (n // 4 + 1))[:n]
        masked = (int.from_bytes(payload, "big") ^ int.from_bytes(repeated, "big")).to_bytes(
            n, "big"
        )
        try:
            self._sock.sendall(head + mask + masked)
        except OSError as exc:
            raise BrowserError(f"WebSocket connection lost: {exc}") from exc

    def send_text(self, text: str) -> None:
        """Send one text message."""
        self._send_frame(_TEXT, text.encode("utf-8"))

    def receive_text(self, timeout: float) -> str:
        """The next complete text message (pings are answered on the way)."""
        deadline = time.monotonic() + timeout
        parts: list[bytes] = []
        size = 0
        while True:
            b0, b1 = self._take(2, deadline)
            fin, opcode, n = b0 & 0x80, b0 & 0x0F, b1 & 0x7F
            if n == 126:
                (n,) = struct.unpack("!H", self._take(2, deadline))
            elif n == 127:
                (n,) = struct.unpack("!Q", self._take(8, deadline))
            if b1 & 0x80:  # servers must not mask (RFC 6455, section 5.1)
                raise BrowserError("WebSocket protocol error: masked frame from the server")
            if size + n > MAX_MESSAGE_BYTES:
                raise BrowserError(f"WebSocket message larger than {MAX_MESSAGE_BYTES} bytes")
            payload = self._take(n, deadline)
            if opcode == _PING:
                self._send_frame(_PONG, payload)
            elif opcode == _CLOSE:
                raise BrowserError("WebSocket closed by the browser")
            elif opcode in (_TEXT, _BINARY, _CONTINUATION):
                parts.append(payload)
                size += n
                if fin:
                    return b"".join(parts).decode("utf-8")

    def close(self) -> None:
        """Send a close frame (best effort) and close the socket."""
        with contextlib.suppress(BrowserError, OSError):
            self._send_frame(_CLOSE, struct.pack("!H", 1000))
        self._sock.close()
