"""The render pool: jobs sent ahead to each worker, and what a failure takes with it."""

from __future__ import annotations

import numpy as np
import pytest

from alpha_audit.load.sandbox import _PIPELINE_JOBS, RenderPool
from alpha_audit.load.svg import RenderLimits

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
        out = dict(pool.stream((tag, svg, (8, 16)) for tag, svg in jobs))
    assert len(jobs) > _PIPELINE_JOBS  # the good jobs really were queued behind a bad one
    assert out.keys() == {tag for tag, _ in jobs}
    assert isinstance(out["slow"], str) and "longer than 1.5 s" in out["slow"]
    assert isinstance(out["crash"], str) or any(isinstance(m, str) for m in out["crash"])
    with RenderPool(limits, workers=1) as pool:
        for tag, svg in jobs:
            if tag[0] in "ab":
                (alone,) = pool.map([(svg, (8, 16))])
                assert not isinstance(alone, str) and not isinstance(out[tag], str)
                for a, b in zip(out[tag], alone, strict=True):
                    np.testing.assert_array_equal(a, b)


def test_only_small_requests_are_sent_ahead(monkeypatch: pytest.MonkeyPatch) -> None:
    """A worker is sent more jobs only while its pipe holds them unread; a big file waits."""
    from alpha_audit.load import sandbox

    queued_at_send: dict[int, int] = {}  # request size -> most jobs already on the worker
    send = sandbox._Worker.send

    def spy(self: sandbox._Worker, job: int, svg: bytes, sizes: tuple[int, ...]) -> None:
        queued_at_send[len(svg)] = max(queued_at_send.get(len(svg), 0), len(self.jobs))
        send(self, job, svg, sizes)

    monkeypatch.setattr(sandbox._Worker, "send", spy)
    pad = "<!--" + "x" * (20 << 10) + "-->"
    big = f"{HEAD}{pad}<rect width='4' height='4'/></svg>".encode()
    small = _good(1)
    jobs = [(i, big if i >= 6 else small, (8,)) for i in range(12)]
    with RenderPool(RenderLimits(timeout=20.0), workers=1) as pool:
        out = dict(pool.stream(iter(jobs)))
    assert sorted(out) == list(range(12))
    assert all(not isinstance(o, str) and int(o[0].sum()) > 0 for o in out.values())
    assert len(big) > sandbox._PIPELINE_BYTES
    assert queued_at_send[len(big)] == 0  # only ever sent to a worker with nothing queued
    assert queued_at_send[len(small)] >= 1  # small ones were sent ahead
