"""The render pool: jobs sent ahead to each worker, and what a failure takes with it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from alpha_audit.load.sandbox import _FORK, _PIPELINE_JOBS, RenderLimits, RenderPool
from helpers import render_all


def sandbox_forks() -> bool:
    return _FORK


HEAD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'


def _good(i: int) -> bytes:
    return f'{HEAD}<rect x="{i}" y="2" width="{3 + i}" height="9"/></svg>'.encode()


def _slow() -> bytes:
    """A <use> fan-out cairosvg takes far longer than a second on."""
    groups = "".join(f'<g id="p{i + 1}">' + f'<use href="#p{i}"/>' * 10 + "</g>" for i in range(5))
    return (
        f'{HEAD}<defs><path id="p0" d="M0 0h1v1z"/>{groups}</defs><use href="#p5"/></svg>'.encode()
    )


def _crash() -> bytes:
    """A pattern tile far beyond the render memory limit."""
    return (
        f'{HEAD}<defs><pattern id="p" width="1e5" height="1e5" patternUnits="userSpaceOnUse">'
        '<rect width="1e5" height="1e5"/></pattern></defs>'
        '<rect width="24" height="24" fill="url(#p)"/></svg>'
    ).encode()


def test_a_job_that_fails_takes_only_itself_not_the_jobs_sent_behind_it() -> None:
    """One worker gets several jobs at once; a timeout and a crash fail just their own job."""
    jobs = [("slow", _slow()), *((f"a{i}", _good(i)) for i in range(5)), ("crash", _crash())]
    jobs += [(f"b{i}", _good(i)) for i in range(5)]
    limits = RenderLimits(timeout=1.5)
    with RenderPool(limits, workers=1) as pool:
        out = dict(pool.stream((tag, [svg], (8, 16)) for tag, svg in jobs))
    assert len(jobs) > _PIPELINE_JOBS  # the good jobs really were queued behind a bad one
    assert out.keys() == {tag for tag, _ in jobs}
    assert isinstance(out["slow"], str) and "took longer than 1.5 s to render" in out["slow"]
    assert isinstance(out["crash"], str) or any(isinstance(m, str) for m in out["crash"][0])
    with RenderPool(limits, workers=1) as pool:
        for tag, svg in jobs:
            if tag[0] in "ab":
                (alone,) = render_all(pool, [([svg], (8, 16))])
                assert not isinstance(alone, str) and not isinstance(out[tag], str)
                for a, b in zip(out[tag][0], alone[0], strict=True):
                    np.testing.assert_array_equal(a, b)


def test_only_small_requests_are_sent_ahead(monkeypatch: pytest.MonkeyPatch) -> None:
    """A worker is sent more jobs only while its pipe holds them unread; a big file waits."""
    from alpha_audit.load import sandbox

    queued_at_send: dict[int, int] = {}  # request size -> most jobs already on the worker
    send = sandbox._Worker.send

    def spy(
        self: sandbox._Worker, job: int, request: bytes, svgs: int, sizes: tuple[int, ...]
    ) -> None:
        n = len(request)
        queued_at_send[n] = max(queued_at_send.get(n, 0), len(self.jobs))
        send(self, job, request, svgs, sizes)

    monkeypatch.setattr(sandbox._Worker, "send", spy)
    pad = "<!--" + "x" * (20 << 10) + "-->"
    big = f"{HEAD}{pad}<rect width='4' height='4'/></svg>".encode()
    small = _good(1)
    jobs = [(i, [big if i >= 6 else small], (8,)) for i in range(12)]
    with RenderPool(RenderLimits(timeout=20.0), workers=1) as pool:
        out = dict(pool.stream(iter(jobs)))
    assert sorted(out) == list(range(12))
    assert all(not isinstance(o, str) and int(o[0][0].sum()) > 0 for o in out.values())
    big_request, small_request = (len(sandbox._request([svg], (8,))[0]) for svg in (big, small))
    assert big_request > sandbox._PIPELINE_BYTES
    assert queued_at_send[big_request] == 0  # only ever sent to a worker with nothing queued
    assert queued_at_send[small_request] >= 1  # small ones were sent ahead


MUTATING = [
    # cairosvg's drawing edits these trees: <use> drops x/y, <mask> and <pattern> become
    # groups, a clip path that is a <path> comes back as a clipPath
    '<defs><rect id="r" width="4" height="4"/></defs><use href="#r" x="3" y="5"/>',
    '<mask id="m"><rect width="12" height="24" fill="#fff"/></mask>'
    '<rect width="24" height="24" mask="url(#m)"/>',
    '<pattern id="p" width="4" height="4" patternUnits="userSpaceOnUse"><rect width="2" '
    'height="2"/></pattern><rect width="24" height="24" fill="url(#p)"/>',
    '<path id="c" d="M0 0h9v9z"/><rect width="24" height="24" clip-path="url(#c)"/>',
    '<text x="2" y="20" font-size="12">ab</text><circle cx="12" cy="12" r="5"/>',
    '<circle cx="12" cy="12" r="7" stroke="#000" stroke-width="3" fill="none"/>',
]


@pytest.mark.parametrize("body", MUTATING)
def test_one_parse_draws_every_size_as_a_fresh_parse_would(body: str) -> None:
    from alpha_audit.load._svg_worker import render_alpha, render_alphas

    svg = f"{HEAD}{body}</svg>".encode()
    sizes = (16, 24, 48, 24)
    together = render_alphas(svg, sizes)
    assert together == [render_alpha(svg, size) for size in sizes]


def test_a_job_holds_several_svgs_each_at_every_size() -> None:
    svgs = [_good(1), _good(4), b"<svg", _good(2)]
    with RenderPool(RenderLimits(timeout=20.0), workers=1) as pool:
        (together,) = render_all(pool, [(svgs, (8, 16))])
        alone = render_all(pool, [([svg], (8, 16)) for svg in svgs])
    assert not isinstance(together, str)
    assert [len(per_svg) for per_svg in together] == [2, 2, 2, 2]
    assert all(isinstance(m, str) and "cannot render" in m for m in together[2])
    for k in (0, 1, 3):
        single = alone[k]
        assert not isinstance(single, str)
        for a, b in zip(together[k], single[0], strict=True):
            np.testing.assert_array_equal(a, b)


def _children(pid: int) -> list[tuple[int, str]]:
    """(pid, command line) of the live processes whose parent is ``pid`` (Linux /proc)."""
    from pathlib import Path

    out = []
    for proc in Path("/proc").iterdir():
        try:
            stat = (proc / "stat").read_text()
            args = (proc / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except (OSError, ValueError):
            continue
        state, ppid = stat.rsplit(")", 1)[1].split()[:2]
        if int(ppid) == pid and state != "Z":
            out.append((int(proc.name), args))
    return out


@pytest.mark.skipif(not sandbox_forks(), reason="workers are forked on Linux only")
def test_workers_are_forked_from_one_server_and_end_with_the_pool() -> None:
    import os

    with RenderPool(RenderLimits(timeout=20.0), workers=2) as pool:
        pool.prestart()
        out = render_all(pool, [([_good(i)], (8,)) for i in range(6)])
        assert all(not isinstance(o, str) for o in out)
        (server,) = [p for p, args in _children(os.getpid()) if "_svg_worker.py" in args]
        workers = [p for p, args in _children(server) if "_svg_worker.py" in args]
        assert len(workers) == 2  # forked, not started as interpreters of their own
    assert not [p for p, args in _children(os.getpid()) if "_svg_worker.py" in args]
    assert not _children(server)


@pytest.mark.skipif(not sandbox_forks(), reason="workers are forked on Linux only")
def test_a_run_that_may_find_everything_cached_loads_no_renderer_until_its_first_job(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import time

    from alpha_audit.load.render_cache import FILE_NAME

    monkeypatch.setenv("ALPHA_AUDIT_CACHE_DIR", str(tmp_path))
    (tmp_path / FILE_NAME).write_bytes(b"\0" * 20000)  # a cache with entries, as far as it shows

    def cairo_loaded(pid: int) -> bool:
        return "libcairo" in Path(f"/proc/{pid}/maps").read_text()

    with RenderPool(RenderLimits(timeout=20.0), workers=2) as pool:
        pool.prestart()
        assert pool._server is not None
        server = pool._server.proc.pid
        time.sleep(0.5)  # time it would have had to load (the assertion does not depend on it)
        assert not cairo_loaded(server)
        assert _children(server) == []  # no worker forked yet
        (out,) = render_all(pool, [([_good(1)], (8,))])
        assert not isinstance(out, str)
        assert cairo_loaded(server)
        assert len(_children(server)) == 2


def test_each_job_gets_its_cpu_seconds_from_what_the_worker_used_so_far() -> None:
    """The budget is CPU time set before each job (RLIMIT_CPU), not what the clock says."""
    import subprocess
    import sys

    code = (
        "import math, resource\n"
        "from alpha_audit.load import _svg_worker as w\n"
        "w._LIFETIME_CPU = 600\n"
        "sum(i * i for i in range(3_000_000))  # some CPU time used already\n"
        "w._allow_cpu(5)\n"
        "u = resource.getrusage(resource.RUSAGE_SELF)\n"
        "soft, _ = resource.getrlimit(resource.RLIMIT_CPU)\n"
        "print(soft - math.ceil(u.ru_utime + u.ru_stime))\n"
        "w._LIFETIME_CPU = 3\n"
        "w._allow_cpu(5)\n"
        "print(resource.getrlimit(resource.RLIMIT_CPU)[0])\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    ahead, capped = out.stdout.split()
    assert int(ahead) in (4, 5)  # 5 s from the whole second it had reached
    assert int(capped) == 3  # never past the worker's own limit
