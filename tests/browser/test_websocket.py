"""The RFC 6455 client against a tiny loopback server written from the RFC in this test."""

from __future__ import annotations

import base64
import hashlib
import socket
import struct
import threading

import pytest

from alpha_audit.browser import BrowserError
from alpha_audit.browser.websocket import WebSocket

GUID = b"258EAFA5-E914-47DA-95CA-C5AB0DC85B11"  # RFC 6455, section 1.3


def _frame(opcode: int, payload: bytes, fin: bool = True) -> bytes:
    n = len(payload)
    head = bytes([(0x80 if fin else 0) | opcode])
    if n < 126:
        head += bytes([n])
    elif n < 1 << 16:
        head += bytes([126]) + struct.pack("!H", n)
    else:
        head += bytes([127]) + struct.pack("!Q", n)
    return head + payload


def _read_client_frame(conn: socket.socket) -> tuple[int, bytes, bool]:
    def take(k: int) -> bytes:
        data = b""
        while len(data) < k:
            data += conn.recv(k - len(data))
        return data

    b0, b1 = take(2)
    n = b1 & 0x7F
    if n == 126:
        (n,) = struct.unpack("!H", take(2))
    elif n == 127:
        (n,) = struct.unpack("!Q", take(8))
    masked = bool(b1 & 0x80)
    mask = take(4) if masked else b"\0\0\0\0"
    data = bytes(c ^ mask[i % 4] for i, c in enumerate(take(n)))
    return b0 & 0x0F, data, masked


@pytest.fixture
def server():
    """A one-connection server; the test sets ``script(conn)`` to run after the handshake."""
    listener = socket.create_server(("127.0.0.1", 0))
    state: dict = {"received": []}

    def serve() -> None:
        conn, _ = listener.accept()
        request = b""
        while b"\r\n\r\n" not in request:
            request += conn.recv(4096)
        key = next(
            line.split(b":", 1)[1].strip()
            for line in request.split(b"\r\n")
            if line.lower().startswith(b"sec-websocket-key")
        )
        accept = base64.b64encode(hashlib.sha1(key + GUID).digest())
        if state.get("bad_accept"):
            accept = b"x" + accept
        conn.sendall(
            b"HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
            b"Sec-WebSocket-Accept: " + accept + b"\r\n\r\n"
        )
        state["script"](conn, state)
        conn.close()

    state["start"] = lambda: threading.Thread(target=serve, daemon=True).start()
    yield f"ws://127.0.0.1:{listener.getsockname()[1]}/session", state
    listener.close()


def test_fragmented_large_and_pinged_messages(server):
    url, state = server
    big = ("x" * 100_000).encode()  # needs the 64-bit length form

    def script(conn, state):
        state["received"].append(_read_client_frame(conn))
        conn.sendall(_frame(0x1, b"hel", fin=False) + _frame(0x9, b"p") + _frame(0x0, b"lo"))
        state["received"].append(_read_client_frame(conn))  # the pong
        conn.sendall(_frame(0x1, big))
        conn.sendall(_frame(0x1, "é".encode()))

    state["script"] = script
    state["start"]()
    ws = WebSocket(url, timeout=5)
    ws.send_text("ping me" * 30)  # 210 bytes: the 16-bit length form
    assert ws.receive_text(5) == "hello"
    assert ws.receive_text(5) == big.decode()
    assert ws.receive_text(5) == "é"
    ws.close()
    (op1, data1, masked1), (op2, data2, masked2) = state["received"]
    assert (op1, data1.decode(), masked1) == (0x1, "ping me" * 30, True)
    assert (op2, data2, masked2) == (0xA, b"p", True)  # pong echoes the ping's payload


def test_a_wrong_accept_key_is_refused(server):
    url, state = server
    state["bad_accept"] = True
    state["script"] = lambda conn, state: None
    state["start"]()
    with pytest.raises(BrowserError, match="Accept"):
        WebSocket(url, timeout=5)


def test_a_close_frame_is_an_error(server):
    url, state = server
    state["script"] = lambda conn, state: conn.sendall(_frame(0x8, struct.pack("!H", 1000)))
    state["start"]()
    ws = WebSocket(url, timeout=5)
    with pytest.raises(BrowserError, match="closed"):
        ws.receive_text(5)
    ws.close()


def test_a_silent_peer_times_out(server):
    url, state = server
    release = threading.Event()
    state["script"] = lambda conn, state: release.wait(5)
    state["start"]()
    ws = WebSocket(url, timeout=5)
    with pytest.raises(BrowserError, match="in time"):
        ws.receive_text(0.2)
    release.set()
    ws.close()
