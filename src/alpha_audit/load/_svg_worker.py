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

Protocol on stdin/stdout, all integers unsigned big-endian.  A request is one
icon: ``u8 kind, u32 n_sizes, n_sizes x u32 size`` (``n_sizes = 0`` ends the
worker), then

* kind 0 (*render*): ``u32 n_svgs``, then per SVG ``u32 n_bytes, bytes``; the
  reply holds, per SVG and per size, an *entry* ``u8 status, u32 n, n bytes``
  where status 0 carries ``size * size`` alpha bytes and status 1 a UTF-8
  error message;
* kind 1 (*paints*): ``u32 max_groups, u32 n_bytes, bytes``: the worker reads
  the SVG's paints (:mod:`alpha_audit.load.paints`, within its counted bounds),
  splits it into one SVG per paint group and renders each.  The reply is one
  entry with the paints as JSON (status 0, :func:`~alpha_audit.load.paints.encode_paints`)
  followed by ``u32 n_groups`` and, per group and per size, an entry as above;
  or one entry saying why the paints could not be read: status 3 when the
  paint reader refused the file (as it always will), 1 for any other failure.

Each SVG is parsed once for all its sizes (:func:`render_alphas`).  Before the
first reply the worker says it is ready (status 2, no bytes): a job's time
counts from then, not from a start-up slowed by a busy machine.  Reading the
paints here keeps that work off the parent's critical path and inside the
sandbox's time and memory limits.

On Linux the pool starts one *fork server* (``--fork-server FD``): it imports
and warms up the renderer once, then forks each worker on the pipes it is sent
over a Unix socket (``S`` + worker id + the two descriptors), so a pool of
workers costs one start-up instead of one each.  The server itself never
reads an SVG; each forked worker drops the socket, dies with the server
(``PR_SET_PDEATHSIG``) and installs the sandbox before reading its first
request.  ``K`` + id kills and reaps a worker; ``R`` + id reaps one that
ended and answers ``u32 id, i32 exit code`` (negative: the signal).  Started
with ``--hold``, the server warms up and forks only once sent ``G``.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import struct
import sys
from collections.abc import Sequence
from typing import Any, BinaryIO

EMPTY_SVG = b'<svg xmlns="http://www.w3.org/2000/svg" width="1" height="1"/>'
# Reply statuses: READY (with no bytes) once, before the first reply; REFUSED, a
# paints job's file refused by the paint reader (the same file always is).
OK, FAILED, READY, REFUSED = 0, 1, 2, 3
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
    return _draw(_parse(svg), size)


def render_alphas(svg: bytes, sizes: Sequence[int]) -> list[bytes | BaseException]:
    """:func:`render_alpha` at every size from one parse; a failure is its exception.

    cairosvg's drawing may change the tree it draws (``<use>`` drops its
    ``x`` and ``y``, a ``<mask>`` becomes a group ...), so the tree is compared
    with its state before the first drawing after each one and parsed again
    when it changed: every size is drawn from a tree as the parser made it,
    which is what a fresh parse per size would draw.
    """
    try:
        tree = _parse(svg)
    except Exception as exc:
        return [exc] * len(sizes)
    pristine = _state(tree)
    out: list[bytes | BaseException] = []
    for k, size in enumerate(sizes):
        try:
            out.append(_draw(tree, size))
        except Exception as exc:
            out.append(exc)
        if k + 1 < len(sizes) and _state(tree) != pristine:
            try:
                tree = _parse(svg)
            except Exception as exc:  # parsed once already: only a resource can fail now
                return out + [exc] * (len(sizes) - k - 1)
    return out


def _parse(svg: bytes) -> Any:
    import cairosvg.parser

    return cairosvg.parser.Tree(bytestring=svg, unsafe=False, url_fetcher=refuse_url)


def _state(tree: Any) -> list[tuple[object, dict[str, object], int]]:
    """Every node's tag, attributes and child count: what a drawing may have changed."""
    out = []
    stack = [tree]
    while stack:
        node = stack.pop()
        out.append((node.tag, dict(node), len(node.children)))
        stack.extend(node.children)
    return out


def _draw(tree: Any, size: int) -> bytes:
    import cairosvg.surface

    surface = cairosvg.surface.PNGSurface(tree, None, 96, output_width=size, output_height=size)
    image = surface.cairo
    image.flush()
    stride, height, width = image.get_stride(), image.get_height(), image.get_width()
    data = bytes(image.get_data())
    surface.finish()
    # ARGB32 is native-endian with alpha in the top byte.
    offset = 3 if sys.byteorder == "little" else 0
    if (height, width, stride) == (size, size, 4 * size):  # rows back to back: one slice
        return data[offset::4]
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
        global _LIFETIME_CPU
        _LIFETIME_CPU = cpu_seconds
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


RENDER, PAINTS = 0, 1  # request kinds


def serve(
    stdin: BinaryIO,
    stdout: BinaryIO,
    memory_bytes: int | None = None,
    job_cpu: int | None = None,
) -> None:
    """Say ready, then answer requests until a request with no sizes or end of input.

    With ``job_cpu``, each request may use that many more seconds of CPU time
    (:func:`_allow_cpu`): past it the kernel ends this process (``SIGXCPU``).
    """
    stdout.write(struct.pack(">BI", READY, 0))
    stdout.flush()
    u32 = struct.Struct(">I")
    while True:
        try:
            kind, n_sizes = struct.unpack(">BI", _read_exact(stdin, 5))
            if n_sizes == 0:
                return
            sizes = struct.unpack(f">{n_sizes}I", _read_exact(stdin, 4 * n_sizes))
            (count,) = u32.unpack(_read_exact(stdin, 4))  # SVGs, or the most paint groups
            svgs = []
            for _ in range(1 if kind == PAINTS else count):
                (n_bytes,) = u32.unpack(_read_exact(stdin, 4))
                svgs.append(_read_exact(stdin, n_bytes))
        except EOFError:
            return
        if job_cpu is not None:
            _allow_cpu(job_cpu)
        reply = bytearray()
        if kind == PAINTS:
            paints, svgs, problem, lasting = read_paints(svgs[0], count, memory_bytes)
            if problem is not None:
                reply += _entry(REFUSED if lasting else FAILED, problem.encode("utf-8", "replace"))
            else:
                reply += _entry(OK, paints) + u32.pack(len(svgs))
        for svg in svgs:
            for rendered in render_alphas(svg, sizes):
                if isinstance(rendered, bytes):
                    reply += _entry(OK, rendered)
                else:  # every failure of a hostile file is a reply
                    reason = describe_failure(rendered, memory_bytes)
                    reply += _entry(FAILED, reason.encode("utf-8", "replace"))
        stdout.write(reply)
        stdout.flush()


def _allow_cpu(seconds: int) -> None:
    """Let the next job use ``seconds`` more CPU time (rounded up to whole seconds of this
    process's total, RLIMIT_CPU's unit), within the worker's own limit.

    CPU time, unlike wall-clock time, does not shrink when the machine is busy:
    an icon is refused for what rendering it costs, not for what else runs.
    """
    import math
    import resource

    used = resource.getrusage(resource.RUSAGE_SELF)
    _, hard = resource.getrlimit(resource.RLIMIT_CPU)
    want = math.ceil(used.ru_utime + used.ru_stime) + seconds
    for cap in (_LIFETIME_CPU, None if hard == resource.RLIM_INFINITY else hard):
        if cap is not None:
            want = min(want, cap)
    with contextlib.suppress(ValueError, OSError):
        resource.setrlimit(resource.RLIMIT_CPU, (want, hard))


_LIFETIME_CPU: int | None = None  # the worker's own CPU limit, set by install_sandbox


def _entry(status: int, payload: bytes) -> bytes:
    return struct.pack(">BI", status, len(payload)) + payload


def read_paints(
    svg: bytes, max_groups: int, memory_bytes: int | None = None
) -> tuple[bytes, list[bytes], str | None, bool]:
    """``(paints JSON, one SVG per paint group, None, False)``, or ``(b"", [], why not,
    lasting)`` where ``lasting`` says the paint reader refused the file (it always will:
    its bounds are counted, not timed), not a resource limit of this process."""
    from alpha_audit.errors import SvgError
    from alpha_audit.load.paints import encode_paints, paints_and_isolates

    try:
        paints, variants = paints_and_isolates(svg, max_groups=max_groups)
    except SvgError as exc:
        reason = f"line {exc.line}: {exc.message}" if exc.line else exc.message
        return b"", [], reason, True
    except Exception as exc:  # a hostile file's every other failure is a reply too
        return b"", [], describe_failure(exc, memory_bytes), False
    return encode_paints(paints), variants, None, False


def _warm_up() -> None:
    """Import and exercise the renderer and the paint reader before any sandbox:
    imports open files, and fontconfig loads for text."""
    svg = (
        b'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 4"><text>a</text>'
        b'<image href="x.png" width="1" height="1"/><rect width="2" height="2"/>'
        b"<style>rect { fill: #f00 }</style></svg>"
    )
    render_alpha(svg, 4)
    read_paints(svg, 1)


def serve_forks(
    control: socket.socket,
    memory_bytes: int,
    cpu_seconds: int,
    job_cpu: int | None = None,
    *,
    hold: bool = False,
) -> None:
    """The fork server: fork a sandboxed worker per ``S`` request until the socket closes.

    With ``hold``, the renderer is warmed up only on ``G`` (go): until then the
    server costs no CPU and the workers asked for wait, so a run that finds
    everything in the render cache never pays for the renderer's start-up.
    """
    children: dict[int, int] = {}  # worker id -> pid
    held: list[tuple[int, list[int]]] = []  # (worker id, fds) asked for before go
    server = os.getpid()
    if not hold:
        _warm_up()
    while True:
        try:
            message, fds, _, _ = socket.recv_fds(control, 5, 2)
        except OSError:
            break
        if len(message) != 5:
            for fd in fds:
                os.close(fd)
            break  # end of input (or garbage): the pool is gone
        op, worker = message[:1], struct.unpack(">I", message[1:])[0]
        if op == b"G" and hold:
            hold = False
            _warm_up()
            while held:
                waiting, their_fds = held.pop(0)
                others = [fd for _, later in held for fd in later]  # not the worker's to keep
                children[waiting] = _fork_worker(
                    control, their_fds, server, (memory_bytes, cpu_seconds, job_cpu), others
                )
        elif op == b"S" and len(fds) == 2:
            if hold:
                held.append((worker, fds))
                continue  # their descriptors are kept until the worker is forked
            children[worker] = _fork_worker(
                control, fds, server, (memory_bytes, cpu_seconds, job_cpu)
            )
            continue
        elif op in (b"K", b"R"):
            pid = children.pop(worker, None)
            code = 0
            if pid is not None:
                if op == b"K":
                    _kill(pid)
                code = os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])
            if op == b"R":
                control.sendall(struct.pack(">Ii", worker, code))
        for fd in fds:
            os.close(fd)
    for pid in children.values():
        _kill(pid)
        os.waitpid(pid, 0)


def _fork_worker(
    control: socket.socket,
    fds: list[int],
    server: int,
    limits: tuple[int, int, int | None],
    others: Sequence[int] = (),
) -> int:
    """Fork one worker on ``fds`` (its request and reply pipes), which are then closed
    here; the worker's pid.  ``others`` are descriptors the worker must not hold (other
    workers' pipes: a reply pipe held open elsewhere would hide its worker's end)."""
    pid = os.fork()
    if pid == 0:  # the worker
        try:
            control.close()
            for fd in others:
                os.close(fd)
            _become_worker(fds[0], fds[1], server, *limits)
        finally:
            os._exit(0)
    for fd in fds:
        os.close(fd)
    return pid


def _kill(pid: int) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.kill(pid, signal.SIGKILL)


def _become_worker(
    request_fd: int,
    reply_fd: int,
    server: int,
    memory_bytes: int,
    cpu_seconds: int,
    job_cpu: int | None,
) -> None:
    """In a forked child: take the pipes as stdin/stdout, die with the server, sandbox, serve."""
    os.dup2(request_fd, 0)
    os.dup2(reply_fd, 1)
    import ctypes

    pr_set_pdeathsig = 1  # <linux/prctl.h>
    ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, signal.SIGKILL)
    if os.getppid() != server:  # the server ended before the line above
        return
    install_sandbox(memory_bytes, cpu_seconds)
    with open(0, "rb", closefd=False) as stdin, open(1, "wb", closefd=False) as stdout:
        serve(stdin, stdout, memory_bytes, job_cpu)


def main() -> None:
    """Worker entry point: ``python -I _svg_worker.py MEMORY CPU JOB_CPU [--fork-server FD
    [--hold]]``.

    ``MEMORY`` is the address-space limit in bytes, ``CPU`` a worker's CPU-time
    limit in seconds and ``JOB_CPU`` each job's; with ``--fork-server``, the
    workers are forked from this process (with ``--hold``, once told to go).
    """
    memory_bytes, cpu_seconds, job_cpu = (int(a) for a in sys.argv[1:4])
    sys.setrecursionlimit(2000)
    # cairocffi looks cairo up with ctypes.util.find_library, which runs
    # ldconfig and gcc (subprocesses writing files in /tmp).  Without it
    # cairocffi dlopens "libcairo.so.2" through the loader cache instead.
    import ctypes.util

    ctypes.util.find_library = lambda name: None
    if sys.argv[4:5] == ["--fork-server"]:
        control = socket.socket(fileno=int(sys.argv[5]))
        serve_forks(control, memory_bytes, cpu_seconds, job_cpu, hold="--hold" in sys.argv[6:])
        os._exit(0)  # its workers are reaped; an interpreter shutdown would only cost time
    _warm_up()
    install_sandbox(memory_bytes, cpu_seconds)
    serve(sys.stdin.buffer, sys.stdout.buffer, memory_bytes, job_cpu)


if __name__ == "__main__":
    main()
