"""Per-paint masks through the sandboxed pool, against masks rendered and reduced independently."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from alpha_audit.load.paint_masks import MAX_PAINT_GROUPS, measure_paints
from alpha_audit.load.paints import isolate_paints
from alpha_audit.load.svg import rasterize
from alpha_audit.paints import CURRENT_COLOR
from helpers import render_all

NS = 'xmlns="http://www.w3.org/2000/svg"'
LUCIDE_LIKE = (
    f'<svg {NS} width="24" height="24" viewBox="0 0 24 24" fill="none" stroke="currentColor" '
    'stroke-width="2" stroke-linecap="round" stroke-linejoin="round">'
    '<circle cx="12" cy="12" r="10"/><path d="M12 8v4"/><path d="M12 16h.01"/>'
    '<path d="M3 3l18 18" stroke="#ff0000"/></svg>'
)


def independent_q50(mask: np.ndarray) -> float:
    codes = np.rint(mask * 255).astype(int).ravel()
    ink_per_level = np.bincount(codes, weights=codes, minlength=256)
    ink_per_level[0] = 0
    cumulative = np.cumsum(ink_per_level)
    return int(np.argmax(cumulative >= cumulative[-1] / 2)) / 255


@pytest.fixture
def icons(tmp_path: Path) -> list[tuple[str, Path]]:
    files = {
        "alert": LUCIDE_LIKE,
        "disc": f'<svg {NS} viewBox="0 0 24 24"><circle cx="12" cy="12" r="9" opacity=".3"/></svg>',
        "broken": "<svg",
        "many": f"<svg {NS}>"
        + "".join(
            f'<rect fill="#{i:06x}" width="1" height="1"/>' for i in range(MAX_PAINT_GROUPS + 1)
        )
        + "</svg>",
    }
    out = []
    for name, text in files.items():
        (tmp_path / f"{name}.svg").write_text(text)
        out.append((name, tmp_path / f"{name}.svg"))
    return out


def test_measure_paints_matches_independent_reduction(icons: list[tuple[str, Path]]) -> None:
    ticks: list[None] = []
    result = measure_paints(icons, [16, 48], progress=lambda: ticks.append(None))
    assert len(ticks) == 4
    assert sorted(p.icon for p in result.problems) == ["broken", "many"]
    assert "not well-formed" in next(p.message for p in result.problems if p.icon == "broken")
    assert "distinct paints" in next(p.message for p in result.problems if p.icon == "many")

    alert = result.icons["alert"]
    assert [(c.group.color, c.group.opacity) for c in alert.coverage] == [
        (CURRENT_COLOR, 1.0),
        ("#ff0000", 1.0),
    ]
    data = LUCIDE_LIKE.encode()
    for cov in alert.coverage:
        for size in (16, 48):
            mask = rasterize(isolate_paints(data, lambda p, c=cov: p.color == c.group.color), size)
            stats = cov.sizes[size]
            assert stats.q50 == pytest.approx(independent_q50(mask), abs=1e-12)
            assert stats.pixels == np.count_nonzero(mask)
            assert stats.full_share == pytest.approx(mask[mask == 1].sum() / mask.sum())
    # thin strokes: less ink is solid at 16 px than at 48 px
    main = alert.coverage[0]
    assert main.sizes[16].full_share < main.sizes[48].full_share

    (disc,) = result.icons["disc"].coverage
    assert disc.group.opacity == pytest.approx(0.3)
    assert disc.sizes[48].q50 == 1.0  # its geometry is solid; the 0.3 lives in the opacity


def test_render_pool_serves_several_map_calls() -> None:
    """measure_paints batches its jobs; workers kept between map() calls must still be heard."""
    from alpha_audit.load.sandbox import RenderPool
    from alpha_audit.load.svg import RenderLimits

    svg = LUCIDE_LIKE.encode()
    with RenderPool(RenderLimits(timeout=20.0), workers=1) as pool:
        first = render_all(pool, [([svg], (8,))])
        second = render_all(pool, [([svg], (8,)), ([svg], (8,))])
    assert all(not isinstance(o, str) for o in [*first, *second])
    np.testing.assert_array_equal(first[0][0][0], second[1][0][0])


def test_stream_pulls_work_only_as_the_workers_need_it() -> None:
    """The pool reads a lazy source a few jobs ahead, never all of it before rendering."""
    from alpha_audit.load.sandbox import _PIPELINE_JOBS, RenderPool
    from alpha_audit.load.svg import RenderLimits

    svg = LUCIDE_LIKE.encode()
    pulled: list[int] = []

    def source() -> Iterator[tuple[int, bytes, tuple[int, ...]]]:
        for i in range(40):
            pulled.append(i)
            yield i, [svg], (8,)

    seen: list[tuple[int, int]] = []  # (tag, jobs pulled when its outcome arrived)
    with RenderPool(RenderLimits(timeout=20.0), workers=2) as pool:
        for tag, outcome in pool.stream(source(), ahead=3):
            assert not isinstance(outcome, str)
            seen.append((tag, len(pulled)))
    assert sorted(t for t, _ in seen) == list(range(40))
    # the first outcome came while at most the jobs sent to 2 workers, 3 read ahead and
    # 1 being read were out: far from all 40
    assert seen[0][1] <= 2 * _PIPELINE_JOBS + 3 + 1 < 40


def test_read_ahead_changes_nothing_but_timing() -> None:
    """Masks do not depend on how far the pool reads ahead or which worker drew them."""
    from alpha_audit.load.sandbox import RenderPool
    from alpha_audit.load.svg import RenderLimits

    jobs = [
        (i, [LUCIDE_LIKE.replace('r="10"', f'r="{3 + i}"').encode()], (8, 16)) for i in range(6)
    ]
    out = []
    for workers, ahead in ((1, 0), (2, 8)):
        with RenderPool(RenderLimits(timeout=20.0), workers=workers) as pool:
            out.append(dict(pool.stream(iter(jobs), ahead=ahead)))
    assert out[0].keys() == out[1].keys() == set(range(6))
    for tag in range(6):
        for a, b in zip(out[0][tag][0], out[1][tag][0], strict=True):
            np.testing.assert_array_equal(a, b)
    assert len({out[0][t][0][1].tobytes() for t in range(6)}) > 1  # the jobs really differ


def test_one_job_per_icon_whatever_its_paint_groups(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A six-group icon is one job: one time budget, not six (issue 21)."""
    from alpha_audit.load import sandbox

    jobs: list[int] = []  # one entry per job sent
    send = sandbox._Worker.send

    def spy(self: sandbox._Worker, job: int, request: bytes, svgs: int, sizes: object) -> None:
        jobs.append(job)
        send(self, job, request, svgs, sizes)  # type: ignore[arg-type]  # the sizes given

    monkeypatch.setattr(sandbox._Worker, "send", spy)
    colours = ["#ff0000", "#00ff00", "#0000ff", "#ffff00", "#00ffff", "#ff00ff"]
    body = "".join(
        f'<rect x="{i}" width="1" height="4" fill="{c}"/>' for i, c in enumerate(colours)
    )
    path = tmp_path / "six.svg"
    path.write_text(f'<svg {NS} viewBox="0 0 6 4">{body}</svg>')
    result = measure_paints([("six", path)], [8, 16], cache=False)
    assert len(result.icons["six"].coverage) == 6
    assert len(jobs) == 1
