"""Render SVG bytes to alpha masks; run as a script, the sandboxed render worker.

This file imports only the standard library and cairosvg so that
:mod:`alpha_audit.load.svg` can start it as ``python -I <this file>``
without importing alpha-audit (or numpy) in the worker.  In the worker:

* resource limits cap address space, CPU time and file size
  (``RLIMIT_AS``, ``RLIMIT_CPU``, ``RLIMIT_FSIZE = 0``);
* an audit hook (PEP 578) refuses sockets, subprocesses and any file
  opened outside the Python installation, once start-up imports are done;
* cairosvg gets a URL fetcher that refuses every URL (``http:``, ``file:``,
  ``data:`` alike), so external images, stylesheets and ``<use>`` targets
  render as nothing.

Protocol on stdin/stdout, all integers unsigned big-endian:
request ``u32 n_sizes, n x u32 size, u32 n_bytes, bytes`` (``n_sizes = 0``
ends the worker); reply, per size, ``u8 status, u32 n, n bytes`` where status
0 carries ``size * size`` alpha bytes and status 1 a UTF-8 error message.
"""

from __future__ import annotations

import os
import struct
import sys
from typing import BinaryIO

EMPTY_SVG = b'<svg xmlns="http://www.w3.org/2000/svg" width="1" height="1"/>'
OK, FAILED = 0, 1
MAX_MESSAGE = 300  # characters of an error message sent back


def refuse_url(url: str, resource_type: str) -> bytes:
    """cairosvg URL fetcher that fetches nothing: every reference renders empty."""
    return EMPTY_SVG


def render_alpha(svg: bytes, size: int) -> bytes:
    """Render ``svg`` at ``size x size`` px; the alpha channel as ``size * size`` bytes.

    The SVG's own width, height and viewBox only set the aspect ratio: the
    output surface is always ``size x size`` (a non-square drawing is
    centred).  No URL is ever fetched.
    """
    import cairosvg.parser
    import cairosvg.surface

    tree = cairosvg.parser.Tree(bytestring=svg, unsafe=False, url_fetcher=refuse_url)
    surface = cairosvg.surface.PNGSurface(tree, None, 96, output_width=size, output_height=size)
    image = surface.cairo
    image.flush()
    stride, height, width = image.get_stride(), image.get_height(), image.get_width()
    data = bytes(image.get_data())
    surface.finish()
    # ARGB32 is native-endian with alpha in the top byte.
    offset = 3 if sys.byteorder == "little" else 0
    rows = [data[y * stride + offset : y * stride + 4 * width : 4] for y in range(height)]
    if (height, width) == (size, size):
        return b"".join(rows)
    square = bytearray(size * size)
    h, w = min(size, height), min(size, width)
    top, left = (size - h) // 2, (size - w) // 2
    for y in range(h):
        start = (top + y) * size + left
        square[start : start + w] = rows[y][:w]
    return bytes(square)


def describe_failure(exc: BaseException, memory_bytes: int | None = None) -> str:
    """A one-line reason for a failed render (``memory_bytes``: the limit, to name it)."""
    if isinstance(exc, RecursionError):
        return "nested too deeply (recursive or deeply nested <use>/groups)"
    if isinstance(exc, MemoryError):
        limit = "" if memory_bytes is None else f" of {memory_bytes >> 20} MiB"
        return f"needs more memory than the render limit{limit} allows"
    name = type(exc).__name__
    if name == "EntitiesForbidden":
        return "declares XML entities, which are refused (entity expansion)"
    if name in ("DTDForbidden", "ExternalReferenceForbidden"):
        return "refers to an external DTD or entity, which is refused"
    text = " ".join(str(exc).split())[:MAX_MESSAGE]
    return f"cannot render SVG: {name}: {text}" if text else f"cannot render SVG: {name}"


def _allowed_roots() -> tuple[str, ...]:
    """Folders the worker may open files in: the Python installation and its packages."""
    roots = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix}
    roots.update(p for p in sys.path if p and os.path.isdir(p))
    return tuple(sorted(os.path.realpath(r) + os.sep for r in roots))


def install_sandbox(memory_bytes: int, cpu_seconds: int) -> None:
    """Limit this process's resources and refuse network, subprocesses and foreign files."""
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX; the time limit still applies
        resource = None  # type: ignore[assignment]  # no resource module off POSIX: None says so
    if resource is not None:
        for limit, value in (
            (resource.RLIMIT_AS, memory_bytes),
            (resource.RLIMIT_CPU, cpu_seconds),
            (resource.RLIMIT_FSIZE, 0),
            (resource.RLIMIT_CORE, 0),
        ):
            try:
                _, hard = resource.getrlimit(limit)
                value = value if hard == resource.RLIM_INFINITY else min(value, hard)
                resource.setrlimit(limit, (value, hard))
            except (ValueError, OSError):
                pass
    roots = _allowed_roots()
    blocked_prefixes = ("socket.", "subprocess.", "os.exec", "os.posix_spawn", "os.spawn")
    blocked = {"os.system", "os.fork", "os.forkpty", "urllib.Request", "ctypes.dlopen"}

    def hook(event: str, args: tuple[object, ...]) -> None:
        if event in blocked or event.startswith(blocked_prefixes):
            raise PermissionError(f"alpha-audit render sandbox: {event} refused")
        if event == "open" and args and isinstance(args[0], str | bytes):
            path = os.fsdecode(args[0])
            if not os.path.realpath(path).startswith(roots):
                raise PermissionError(f"alpha-audit render sandbox: open({path!r}) refused")

    sys.addaudithook(hook)


def _read_exact(stream: BinaryIO, n: int) -> bytes:
    data = stream.read(n)
    if len(data) != n:
        raise EOFError
    return data


def serve(stdin: BinaryIO, stdout: BinaryIO, memory_bytes: int | None = None) -> None:
    """Answer render requests until a request with no sizes or end of input."""
    u32 = struct.Struct(">I")
    while True:
        try:
            (n_sizes,) = u32.unpack(_read_exact(stdin, 4))
            if n_sizes == 0:
                return
            sizes = struct.unpack(f">{n_sizes}I", _read_exact(stdin, 4 * n_sizes))
            (n_bytes,) = u32.unpack(_read_exact(stdin, 4))
            svg = _read_exact(stdin, n_bytes)
        except EOFError:
            return
        reply = bytearray()
        for size in sizes:
            try:
                payload, status = render_alpha(svg, size), OK
            except BaseException as exc:  # every failure of a hostile file is a reply
                if isinstance(exc, KeyboardInterrupt | SystemExit):
                    raise
                reason = describe_failure(exc, memory_bytes)
                payload, status = reason.encode("utf-8", "replace"), FAILED
            reply += struct.pack(">BI", status, len(payload)) + payload
        stdout.write(reply)
        stdout.flush()


def main() -> None:
    """Worker entry point: ``python -I _svg_worker.py MEMORY_BYTES CPU_SECONDS``."""
    memory_bytes, cpu_seconds = int(sys.argv[1]), int(sys.argv[2])
    sys.setrecursionlimit(2000)
    # cairocffi looks cairo up with ctypes.util.find_library, which runs
    # ldconfig and gcc (subprocesses writing files in /tmp).  Without it
    # cairocffi dlopens "libcairo.so.2" through the loader cache instead.
    import ctypes.util

    ctypes.util.find_library = lambda name: None
    # Warm up before sandboxing: imports open files, and fontconfig loads for text.
    render_alpha(
        b'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 4"><text>a</text>'
        b'<image href="x.png" width="1" height="1"/><rect width="2" height="2"/></svg>',
        4,
    )
    install_sandbox(memory_bytes, cpu_seconds)
    serve(sys.stdin.buffer, sys.stdout.buffer, memory_bytes)


if __name__ == "__main__":
    main()
