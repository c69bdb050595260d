"""The experiments: the paper's printed broad-grid figures, exactness and properties."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.color import composite_extended, from_8bit, to_8bit
from alpha_audit.errors import UsageError
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Canvas, Theme
from alpha_audit.reproduce import (
    broad_grid,
    full_gamut,
    palette_separation,
    sweep,
    sweep_alphas,
)
from alpha_audit.reproduce.experiments import pair_collisions
from alpha_audit.reproduce.grids import (
    PAPER_SEED,
    code_channels,
    encoded_levels,
    random_source_pairs,
)
from alpha_audit.reproduce.reference import reference_broad_grid

BLACK_WHITE = Theme("bw", (Canvas("white", "#ffffff", "light"), Canvas("black", "#000000", "dark")))


@pytest.fixture(scope="module")
def paper16():
    from pathlib import Path

    return load_theme(Path(__file__).resolve().parents[2] / "themes" / "paper16.yaml")


@pytest.fixture(scope="module")
def paper_broad_grid():
    """The paper's full 17**3 x 33**3 grid at 1.1 and 1.4 (about a second)."""
    return {r.alpha: r for r in broad_grid([1.1, 1.4])}


# Paper, Table 1 and Section 4.2, as printed.
PRINTED = {
    1.1: {"increase": 90.3672, "decrease": 9.3318, "max_loss": 0.4655, "small": 99.34},
    1.4: {"increase": 86.7022, "decrease": 12.9968, "max_loss": 1.6394, "small": 81.53},
}


@pytest.mark.parametrize("alpha", [1.1, 1.4])
def test_broad_grid_matches_every_printed_digit(paper_broad_grid, alpha: float) -> None:
    r = paper_broad_grid[alpha]
    printed = PRINTED[alpha]
    assert r.combinations == 17**3 * 33**3
    assert round(r.increase_pct, 4) == printed["increase"]
    assert round(r.decrease_pct, 4) == printed["decrease"]
    assert round(r.max_loss, 4) == printed["max_loss"]
    assert round(r.loss_le_0_25_pct, 2) == printed["small"]


@pytest.mark.parametrize("alpha", [1.1, 1.4])
def test_broad_grid_worst_case_is_the_papers(paper_broad_grid, alpha: float) -> None:
    """Dark blue (0, 0, 0.8125) on yellow: 10.2773 -> 9.8118 (1.1) -> 8.6379 (1.4)."""
    r = paper_broad_grid[alpha]
    assert r.worst_source == (0.0, 0.0, 0.8125)
    assert r.worst_background == (1.0, 1.0, 0.0)
    assert [round(r.worst_contrast[a], 4) for a in (1.0, 1.1, 1.4)] == [10.2773, 9.8118, 8.6379]
    assert r.worst_contrast[1.0] - r.worst_contrast[alpha] == pytest.approx(r.max_loss, abs=1e-12)


@pytest.mark.parametrize("alpha", [0.5, 1.1, 1.4, 2.0])
def test_broad_grid_matches_reference_on_a_small_grid(alpha: float) -> None:
    (r,) = broad_grid([alpha], source_levels=5, background_levels=9)
    want = reference_broad_grid(encoded_levels(5), encoded_levels(9), alpha)
    assert (r.increase, r.decrease, r.loss_le_0_25) == (
        want["increase"],
        want["decrease"],
        want["loss_le_0_25"],
    )
    assert r.max_loss == want["max_loss"]


@pytest.mark.parametrize("alpha", [1.05, 1.1, 1.4, 2.0])
def test_black_and_white_canvases_never_decrease(alpha: float) -> None:
    """Paper, Section 3.4: per-channel distance implies no loss on black or white."""
    (r,) = full_gamut(BLACK_WHITE, [alpha])
    for canvas in r.canvases:
        assert canvas.change.decrease == 0
        assert canvas.change.increase > 0.99 * canvas.change.combinations


def test_alpha_one_changes_nothing(paper16) -> None:
    (r,) = full_gamut(paper16, [1.0], levels=33)
    t = r.total
    assert (t.increase, t.decrease, t.newly_reach) == (0, 0, 0)
    assert abs(t.mean_change) < 1e-12


def test_other_canvases_admit_decreases_and_groups_pool(paper16) -> None:
    """Paper, Section 4.2: predefined canvases other than black and white admit decreases."""
    (r,) = full_gamut(paper16, [1.4], levels=33)
    tinted = [c for c in r.canvases if c.color not in ("#000000", "#ffffff")]
    assert any(c.change.decrease > 0 for c in tinted)
    light, dark = r.group("light"), r.group("dark")
    assert light is not None and dark is not None
    assert light.combinations + dark.combinations == r.total.combinations
    assert light.increase + dark.increase == r.total.increase


def test_sweep_shape(paper16) -> None:
    """Contraction lowers contrast, expansion raises it; collisions vanish at alpha 1."""
    result = sweep(paper16, sweep_alphas(0.0, 2.0, 0.25), levels=9, pairs=2048)
    alphas = np.array(result.alphas)
    for group in ("light", "dark"):
        mean = np.array(result.mean_change[group])
        assert np.all(mean[(alphas > 0) & (alphas < 1)] < 0)
        assert np.all(mean[alphas > 1] > 0)
        assert np.all(np.diff(mean) > 0)
        share = np.array(result.decrease_share[group])
        assert share[alphas == 1.0] == 0.0
        assert np.all(share[(alphas > 0) & (alphas < 1)] > 0.9)
        collisions = np.array(result.collision_rate[group])
        assert collisions[alphas == 0.0] == 1.0  # every output is the canvas
        assert collisions[alphas == 1.0] == 0.0
    assert result.mean_change["all"][0] == pytest.approx(
        (result.mean_change["light"][0] + result.mean_change["dark"][0]) / 2
    )


def test_sweep_rejects_negative_alphas(paper16) -> None:
    with pytest.raises(UsageError, match="alpha >= 0"):
        sweep(paper16, [-0.5, 1.0], levels=5, pairs=16)


def test_sweep_alphas_are_the_decimal_values() -> None:
    alphas = sweep_alphas()
    assert len(alphas) == 81
    assert alphas[40] == 1.0 and alphas[44] == 1.1 and alphas[56] == 1.4 and alphas[-1] == 2.0


def test_random_pairs_are_distinct_and_reproducible() -> None:
    pairs = random_source_pairs(5000)
    assert pairs.shape == (5000, 2)
    assert np.all(pairs[:, 0] < pairs[:, 1])
    assert np.unique(pairs, axis=0).shape[0] == 5000
    assert np.all((pairs >= 0) & (pairs < 1 << 24))
    np.testing.assert_array_equal(pairs, random_source_pairs(5000))
    assert not np.array_equal(pairs, random_source_pairs(5000, seed=1))


def test_the_papers_pairs_are_one_plain_draw() -> None:
    """At seed 20260913 no pair is dropped: the pairs are the first ``integers`` draw, sorted."""
    draw = np.random.default_rng(PAPER_SEED).integers(0, 1 << 24, size=(65536, 2), dtype=np.int64)
    np.testing.assert_array_equal(random_source_pairs(65536), np.sort(draw, axis=1))


def test_pair_collisions_match_direct_quantisation(paper16) -> None:
    pairs = random_source_pairs(3000)
    alphas = np.array([0.2, 1.0, 1.4, 2.0])
    counts = pair_collisions(paper16.backgrounds, alphas, pairs)
    sources = from_8bit(code_channels(pairs))  # (n, 2, 3)
    for i, a in enumerate(alphas):
        for j, bg in enumerate(paper16.backgrounds):
            out = to_8bit(composite_extended(sources, bg, a))
            assert counts[i, j] == np.count_nonzero(np.all(out[:, 0] == out[:, 1], axis=-1))
    assert counts[1].sum() == 0  # distinct 8-bit sources never collide at alpha 1


def test_palette_separation_counts(paper16) -> None:
    r = palette_separation(paper16, [1.1, 1.4], pairs=4096)
    assert r.combinations == 21 * 16  # the paper's 336
    assert r.random_combinations == 4096 * 16
    assert r.random_collisions[1.0] == 0
    assert r.smaller[1.1] <= r.smaller[1.4]
    assert r.collisions[1.1] <= r.collisions[1.4] <= r.smaller[1.4]
    assert r.random_collisions[1.1] <= r.random_collisions[1.4]
    assert sum(r.smaller_per_canvas[1.4]) == r.smaller[1.4]
    # Black and white canvases: outputs only move away from the canvas, and the
    # paper's Vibrant colours keep their separation there at 1.1.
    names = [c.name for c in paper16.canvases]
    assert r.collisions_per_canvas[1.1][names.index("white")] == 0


def test_unknown_inputs_raise() -> None:
    with pytest.raises(UsageError, match="finite"):
        broad_grid([float("nan")], source_levels=3, background_levels=3)
    with pytest.raises(UsageError, match="at least one"):
        full_gamut(BLACK_WHITE, [])
    with pytest.raises(ValueError, match="at least 2 levels"):
        encoded_levels(1)


def test_progress_adds_up_to_one(paper16) -> None:
    for run in (
        lambda step: full_gamut(paper16, [1.1, -0.2], levels=5, progress=step),
        lambda step: broad_grid([1.1], source_levels=3, background_levels=3, progress=step),
        lambda step: sweep(paper16, [0.0, 1.5], levels=5, pairs=64, progress=step),
        lambda step: palette_separation(paper16, [1.1], pairs=64, progress=step),
    ):
        steps: list[float] = []
        run(steps.append)
        assert sum(steps) == pytest.approx(1.0)


@settings(max_examples=25, deadline=None)
@given(
    alpha=st.floats(-1.0, 3.0, allow_nan=False),
    source_levels=st.integers(2, 6),
    background_levels=st.integers(2, 6),
)
def test_broad_grid_matches_reference_for_any_alpha(
    alpha: float, source_levels: int, background_levels: int
) -> None:
    (r,) = broad_grid([alpha], source_levels=source_levels, background_levels=background_levels)
    want = reference_broad_grid(
        encoded_levels(source_levels), encoded_levels(background_levels), alpha
    )
    assert (r.increase, r.decrease, r.loss_le_0_25) == (
        want["increase"],
        want["decrease"],
        want["loss_le_0_25"],
    )
    assert r.max_loss == (want["max_loss"] if r.decrease else 0.0)
