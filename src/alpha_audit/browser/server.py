"""alpha-audit's own loopback servers: the pages' files, and a proxy that refuses the rest.

:class:`PageServer` serves each source folder under ``/<n>/`` on
``127.0.0.1`` (GET and HEAD only, no directory listings, every path resolved
and kept inside its folder *and* the project root, files capped in size).
:class:`BlockingProxy` is the proxy every browser is told to use for anything
but the page server: it answers each request with ``403`` without opening a
connection anywhere, and records what was asked, so a page's attempts to reach
the network (or another loopback port, such as a WebDriver endpoint) are
refused and reported.
"""

from __future__ import annotations

import contextlib
import mimetypes
import re
import socketserver
import threading
from collections.abc import Sequence
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from types import TracebackType
from typing import Self
from urllib.parse import unquote, urlsplit

__all__ = ["MAX_FILE_BYTES", "BlockingProxy", "PageServer"]

MAX_FILE_BYTES = 64 << 20  # a page's script bundle is a few MB; larger is refused
_TYPES = {
    ".js": "text/javascript",
    ".mjs": "text/javascript",
    ".css": "text/css",
    ".svg": "image/svg+xml",
    ".json": "application/json",
    ".html": "text/html; charset=utf-8",
    ".woff2": "font/woff2",
    ".wasm": "application/wasm",
}
_MOUNT = re.compile(r"[0-9]{1,6}")  # ASCII digits only: str.isdigit() takes "²" and "١"


def _plain(part: str) -> bool:
    """A path part that names a visible entry: not ``.``/``..``, no dot file, no separator."""
    return bool(part) and not part.startswith(".") and not any(c in part for c in "\\/\x00")


class _Quiet(BaseHTTPRequestHandler):
    """Request handling shared by both servers: no logging to stderr (see ``_Server``)."""

    protocol_version = "HTTP/1.1"
    server_version = "alpha-audit"
    sys_version = ""

    def log_message(self, format: str, *args: object) -> None:
        return

    def _refuse(self, status: HTTPStatus) -> None:
        body = status.phrase.encode()
        self.send_response(status)
        self.send_header("Content-Type", "text/plain")
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Connection", "close")
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)
        self.close_connection = True


def _served_file(mounts: Sequence[Path | None], root: Path, target: str) -> Path | None:
    """The file served at ``target`` (a request's path, query allowed), or ``None``.

    See the module's docstring: a plain file of the mount's own folder, checked as
    requested and as resolved (no dot file or folder, no ``..``, nothing outside the
    folder or the project root); a ``None`` mount (a URL source) serves nothing.
    """
    try:
        path = unquote(urlsplit(target).path, errors="strict")
    except (ValueError, UnicodeError):  # not UTF-8 once decoded, a bad IPv6 host ...
        return None
    parts = path.split("/")[1:]
    if len(parts) < 2 or not _MOUNT.fullmatch(parts[0]):
        return None
    mount = int(parts[0])
    folder = mounts[mount] if mount < len(mounts) else None
    names = parts[1:] if parts[-1] else [*parts[1:-1], "index.html"]
    if folder is None or not all(_plain(p) for p in names):
        return None
    try:
        resolved = folder.joinpath(*names).resolve(strict=True)
    except (OSError, RuntimeError, ValueError):
        return None
    # As resolved too: a link may lead out of the folder, or to a dot file inside it.
    if not (resolved.is_relative_to(folder) and resolved.is_relative_to(root)):
        return None
    if not all(_plain(p) for p in resolved.relative_to(folder).parts):
        return None
    return resolved if resolved.is_file() else None


class _FileHandler(_Quiet):
    server: _FileServer

    def do_GET(self) -> None:
        self._serve(body=True)

    def do_HEAD(self) -> None:
        self._serve(body=False)

    def _serve(self, *, body: bool) -> None:
        file = _served_file(self.server.mounts, self.server.root, self.path)
        if file is None:
            self._refuse(HTTPStatus.NOT_FOUND)
            return
        size = file.stat().st_size
        if size > MAX_FILE_BYTES:
            self._refuse(HTTPStatus.REQUEST_ENTITY_TOO_LARGE)
            return
        kind = _TYPES.get(file.suffix.lower()) or mimetypes.guess_type(file.name)[0]
        self.send_response(HTTPStatus.OK)
        self.send_header("Content-Type", kind or "application/octet-stream")
        self.send_header("Content-Length", str(size))
        self.send_header("Cache-Control", "max-age=3600")  # one browser loads many stories
        self.send_header("X-Content-Type-Options", "nosniff")
        self.end_headers()
        if body:
            with contextlib.suppress(OSError), file.open("rb") as fh:
                while chunk := fh.read(1 << 20):
                    self.wfile.write(chunk)


class _Server(ThreadingHTTPServer):
    """A loopback server whose failed requests print nothing (socketserver prints a traceback).

    What a page sends cannot write to alpha-audit's stderr: a request that
    fails (a client that hangs up mid-file) just ends its connection.
    """

    daemon_threads = True

    def handle_error(self, request: object, client_address: object) -> None:
        return


class _FileServer(_Server):
    mounts: tuple[Path | None, ...]
    root: Path


class _Background:
    """A server running in a daemon thread until ``close``."""

    def __init__(self, server: socketserver.TCPServer) -> None:
        self._server = server
        self._thread = threading.Thread(target=server.serve_forever, daemon=True)
        self._thread.start()

    @property
    def address(self) -> str:
        """``127.0.0.1:PORT``."""
        host, port = self._server.server_address[:2]
        return f"{host!s}:{port}"

    def close(self) -> None:
        """Stop serving and release the port (idempotent)."""
        if self._thread.is_alive():
            self._server.shutdown()
            self._thread.join()
        self._server.server_close()

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()


class PageServer(_Background):
    """Serves ``mounts[n]`` at ``http://127.0.0.1:PORT/n/`` (nothing outside ``root``).

    A ``None`` mount (a source that is a URL) serves nothing.
    """

    def __init__(self, mounts: Sequence[Path | None], root: Path) -> None:
        server = _FileServer(("127.0.0.1", 0), _FileHandler)
        server.mounts = tuple(None if m is None else m.resolve() for m in mounts)
        server.root = root.resolve()
        super().__init__(server)
        self._mounts, self._root = server.mounts, server.root
        port = self.address.rsplit(":", 1)[1]
        self._origins = (f"127.0.0.1:{port}", f"localhost:{port}")

    def url(self, mount: int, path: str) -> str:
        """The URL of ``path`` (query included) in folder ``mount``."""
        return f"http://{self.address}/{mount}/{path}"

    def local_file(self, url: str) -> Path | None:
        """The file this server serves (or served) at ``url``; ``None`` for any other URL.

        What :meth:`url` gives, resolved as a request for it is: inside its
        folder and the project root, symlinks followed; another origin (a
        page's own loopback server) is none of ours.
        """
        parts = urlsplit(url)
        if parts.scheme != "http" or parts.netloc not in self._origins:
            return None
        return _served_file(self._mounts, self._root, parts.path)


class _ProxyHandler(_Quiet):
    server: _ProxyServer

    def _record(self) -> None:
        target = self.path if self.command != "CONNECT" else f"https://{self.path}"
        with self.server.lock:
            self.server.requests.append(target[:2000])
        self._refuse(HTTPStatus.FORBIDDEN)

    do_GET = do_POST = do_PUT = do_DELETE = do_HEAD = do_OPTIONS = do_PATCH = _record
    do_CONNECT = _record


class _ProxyServer(_Server):
    lock: threading.Lock
    requests: list[str]


class BlockingProxy(_Background):
    """A proxy that refuses every request and remembers it (:meth:`take`)."""

    def __init__(self) -> None:
        server = _ProxyServer(("127.0.0.1", 0), _ProxyHandler)
        server.lock = threading.Lock()
        server.requests = []
        self._proxy = server
        super().__init__(server)

    def take(self) -> list[str]:
        """The requests refused since the last call, in order, without repeats."""
        with self._proxy.lock:
            taken = list(dict.fromkeys(self._proxy.requests))
            self._proxy.requests.clear()
        return taken
