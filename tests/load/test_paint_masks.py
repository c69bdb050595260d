"""Per-paint masks through the sandboxed pool, against masks rendered and reduced independently."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from alpha_audit.load.paint_masks import MAX_PAINT_GROUPS, measure_paints
from alpha_audit.load.paints import CURRENT_COLOR, isolate_paints
from alpha_audit.load.svg import rasterize

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
        first = pool.map([(svg, (8,))])
        second = pool.map([(svg, (8,)), (svg, (8,))])
    assert all(not isinstance(o, str) for o in [*first, *second])
    np.testing.assert_array_equal(first[0][0], second[1][0])


def test_batches_of_one_job_give_the_same_figures(
    icons: list[tuple[str, Path]], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A tiny mask budget sends one job per pool.map call; nothing changes but memory."""
    import alpha_audit.load.paint_masks as pm

    together = measure_paints(icons, [16, 48])
    monkeypatch.setattr(pm, "_BATCH_BYTES", 1)
    apart = measure_paints(icons, [16, 48])
    assert together == apart
