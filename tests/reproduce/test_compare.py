"""Which printed figures a run is held to: the paper's canvases, grids, pairs and palette."""

from __future__ import annotations

from dataclasses import replace

import pytest

from alpha_audit.bundled import bundled_theme
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Canvas, Theme
from alpha_audit.render.common import RenderOptions
from alpha_audit.reproduce import CanvasChange, ContrastChange, FullGamutResult, PaletteResult
from alpha_audit.reproduce.compare import comparisons, is_paper_canvases, setup_differences
from alpha_audit.reproduce.grids import PAPER_SEED, VIBRANT
from alpha_audit.reproduce.paper import Setup
from alpha_audit.reproduce.report import render_table, reproduction_markdown
from alpha_audit.reproduce.run import Reproduction, Settings

# The sixteen canvases of the authors' public evaluation protocol for "Opacity
# Is Not Just Opacity" (Zhang & Li, 2026), as published there.
PROTOCOL = {
    "light": ["#FFFFFF", "#FAFAFA", "#F5F5F5", "#EEEEEE",
              "#FAF7F2", "#F2F6FA", "#F3F8F4", "#FAF3F6"],
    "dark": ["#000000", "#111111", "#181818", "#242424",
             "#201C18", "#182028", "#19221C", "#241B21"],
}  # fmt: skip


@pytest.fixture(scope="module")
def paper16() -> Theme:
    return load_theme(bundled_theme("paper16"))


def test_paper16_holds_exactly_the_protocols_canvases(paper16: Theme) -> None:
    for mode, colors in PROTOCOL.items():
        assert [c.color for c in paper16.canvases if c.mode == mode] == [x.lower() for x in colors]
    assert len(paper16.canvases) == 16
    assert len({c.name for c in paper16.canvases}) == 16
    assert paper16.threshold == 3.0


def test_the_paper_canvases_are_recognised_by_colour_not_name_or_order(paper16: Theme) -> None:
    assert is_paper_canvases(paper16)
    renamed = Theme("mine", tuple(Canvas(f"c{i}", c.color) for i, c in enumerate(paper16.canvases)))
    assert is_paper_canvases(Theme("mine", renamed.canvases[::-1]))
    one_off = (*paper16.canvases[:-1], Canvas("plum", "#241b22"))
    assert not is_paper_canvases(Theme("mine", one_off))
    assert not is_paper_canvases(Theme("mine", paper16.canvases[:15]))


def _gamut(theme: Theme, increase: int, levels: int = 256) -> FullGamutResult:
    """A fabricated full-gamut result: every canvas with the same counts."""
    n = levels**3
    change = ContrastChange(n, increase, n - increase, 0, 0.0, 0.0, 0.0)
    canvases = tuple(CanvasChange(c.name, c.color, str(c.mode), change) for c in theme.canvases)
    return FullGamutResult(theme.name, 1.1, levels, 3.0, canvases)


def _palette(theme: Theme, pairs: int = 65536, seed: int = PAPER_SEED) -> PaletteResult:
    m = len(theme.canvases)
    return PaletteResult(
        theme.name, VIBRANT, (1.1,), 21 * m, {1.1: 32}, {1.1: 0}, {1.1: (2,) * m},
        {1.1: (0,) * m}, pairs, seed, pairs * m, (1.1,), {1.1: 617},
    )  # fmt: skip


def _run(theme: Theme, **results: object) -> Reproduction:
    return Reproduction(theme, Settings.paper(), False, (1.1,), **results)  # type: ignore[arg-type]


def test_a_mismatch_on_the_papers_setup_is_shown_as_no(paper16: Theme) -> None:
    n = 256**3
    exact = round(0.998145 * n)  # rounds to the printed 99.8145 %
    good = _run(paper16, full_gamut=(_gamut(paper16, exact),))
    bad = _run(paper16, full_gamut=(_gamut(paper16, exact - 200),))

    def increase(run: Reproduction) -> bool | None:
        key = ("full_gamut", "1.1", "increase_pct")
        (c,) = (c for c in comparisons(run) if (c.experiment, c.group, c.name) == key)
        return c.matches

    assert increase(good) is True
    assert increase(bad) is False
    table = render_table(bad, RenderOptions(width=80))
    assert "NOT matching: full_gamut 1.1 increase_pct" in " ".join(table.split())
    assert "| alpha 1.1: increase % | 99.8145 | 99.8133 | yes (abstract, Table 1) | **NO** |" in (
        reproduction_markdown(bad)
    )


def test_other_canvases_are_shown_but_never_compared(paper16: Theme) -> None:
    other = Theme("other", (*paper16.canvases[:15], Canvas("grey", "#808080")))
    run = _run(other, full_gamut=(_gamut(other, 256**3),), palette=_palette(other))
    differences = setup_differences(run)
    for setup in (Setup.FULL_GAMUT, Setup.PALETTE, Setup.RANDOM_PAIRS):
        assert "canvases of theme 'other', not the paper's sixteen (paper16)" in (
            differences[setup] or ""
        )
    assert differences[Setup.BROAD_GRID] == "not run"
    assert not any(c.comparable for c in comparisons(run))
    text = reproduction_markdown(run)
    assert "**yes**" not in text and "**NO**" not in text
    assert "No printed figure of the paper is comparable in digits in this run." in text


def test_random_pairs_need_the_papers_count_and_seed(paper16: Theme) -> None:
    differences = setup_differences(_run(paper16, palette=_palette(paper16, 4096, seed=1)))
    assert differences[Setup.PALETTE] is None  # the palette pairs do not depend on them
    assert differences[Setup.RANDOM_PAIRS] == "4,096 random pairs, not 65,536; seed 1, not 20260913"


def test_full_gamut_needs_every_8_bit_source(paper16: Theme) -> None:
    run = _run(paper16, full_gamut=(_gamut(paper16, 33**3, levels=33),))
    assert setup_differences(run)[Setup.FULL_GAMUT] == "33^3 sources, not 256^3"
    run = replace(run, full_gamut=(_gamut(paper16, 256**3),))
    assert setup_differences(run)[Setup.FULL_GAMUT] is None
