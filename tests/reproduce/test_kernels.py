"""Fast kernels against the straightforward float64 implementation, on reduced grids.

Counts must be identical and sums agree to 1e-12 relative: the kernels are
an exact reformulation, not an approximation.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.color import CONTRAST_TOLERANCE, relative_luminance, srgb_decode
from alpha_audit.model import Canvas, Theme
from alpha_audit.reproduce import full_gamut, kernels
from alpha_audit.reproduce.experiments.common import source_parts as _source_parts
from alpha_audit.reproduce.grids import encoded_levels
from alpha_audit.reproduce.reference import reference_full_gamut

# Canvases that stress both sides of the luminance split and clipping in every
# direction: the extremes, primaries, mid greys, yellow (the paper's worst case),
# and near-black, near-white and tinted canvases of the paper's sixteen.
STRESS = Theme(
    "stress",
    tuple(
        Canvas(f"c{i}", color)
        for i, color in enumerate(
            ["#000000", "#ffffff", "#ff0000", "#00ff00", "#0000ff", "#ffff00", "#808080",
             "#777777", "#111111", "#fafafa", "#201c18", "#f2f6fa", "#3a7f21", "#c0ffee"]
        )
    ),
)  # fmt: skip


def check_against_reference(theme: Theme, encoded: np.ndarray, alpha: float) -> None:
    """Run the kernels on an arbitrary level set and compare with the reference."""
    lev = srgb_decode(encoded)
    backgrounds = theme.backgrounds
    m = backgrounds.shape[0]
    yb = relative_luminance(backgrounds)
    ps, qs = _source_parts(lev, m)
    po, qo = kernels.luminance_parts(kernels.channel_tables(lev, backgrounds, np.full(m, alpha)))
    counts = kernels.change_counts(
        ps, qs, po[np.newaxis], qo[np.newaxis], yb, tol=CONTRAST_TOLERANCE, threshold=3.0
    )
    sums = kernels.contrast_sums(po, qo, yb) - kernels.contrast_sums(ps, qs, yb)
    want = reference_full_gamut(encoded, backgrounds, alpha, controls=False)
    np.testing.assert_array_equal(counts.increase[0], want["increase"])
    np.testing.assert_array_equal(counts.decrease[0], want["decrease"])
    np.testing.assert_array_equal(counts.newly_reach[0], want["newly_reach"])
    np.testing.assert_allclose(sums, want["sum_change"], rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("alpha", [0.0, 0.3, 1.0, 1.025, 1.1, 1.4, 2.0, 3.5])
def test_uniform_grid_matches_reference(alpha: float) -> None:
    check_against_reference(STRESS, encoded_levels(21), alpha)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_byte_subsets_match_reference(seed: int) -> None:
    """Irregular level sets (random 8-bit values) on random canvases."""
    rng = np.random.default_rng(seed)
    encoded = np.sort(rng.choice(256, size=24, replace=False)) / 255
    canvases = tuple(
        Canvas(f"r{i}", "#" + "".join(f"{v:02x}" for v in rng.integers(0, 256, 3)))
        for i in range(6)
    )
    check_against_reference(Theme("random", canvases), encoded, float(rng.uniform(1.0, 2.0)))


def test_full_gamut_api_matches_reference_with_controls() -> None:
    """The public API, controls included, on a 17-level grid and two alphas."""
    results = full_gamut(STRESS, [1.1, 0.6], levels=17)
    for result in results:
        want = reference_full_gamut(encoded_levels(17), STRESS.backgrounds, result.alpha)
        for i, canvas in enumerate(result.canvases):
            c = canvas.change
            assert (c.increase, c.decrease, c.newly_reach) == (
                want["increase"][i],
                want["decrease"][i],
                want["newly_reach"][i],
            )
            for key in ("sum_change", "sum_difference", "sum_exclusion"):
                assert getattr(c, key) == pytest.approx(want[key][i], rel=1e-12, abs=1e-9)


def test_negative_alpha_uses_the_reference_path() -> None:
    (result,) = full_gamut(STRESS, [-0.5], levels=9)
    want = reference_full_gamut(encoded_levels(9), STRESS.backgrounds, -0.5)
    assert [c.change.decrease for c in result.canvases] == list(want["decrease"])


def test_contrast_sums_match_direct_summation() -> None:
    rng = np.random.default_rng(7)
    p = rng.uniform(0.0, 0.93, size=(3, 500))
    q = rng.uniform(0.0, 0.0722, size=(3, 40))
    yb = np.array([0.0, 0.2, 1.0])
    y = p[:, :, np.newaxis] + q[:, np.newaxis, :]
    cb = (yb + 0.05)[:, np.newaxis, np.newaxis]
    direct = (np.maximum(y + 0.05, cb) / np.minimum(y + 0.05, cb)).sum(axis=(1, 2))
    np.testing.assert_allclose(kernels.contrast_sums(p, q, yb), direct, rtol=1e-13)


def test_first_at_or_above_is_the_first_true_column() -> None:
    rng = np.random.default_rng(3)
    q = np.sort(rng.uniform(0, 0.07, size=(2, 33)), axis=1)
    q[:, 5:9] = q[:, 5:6]  # runs of equal values, as clipping produces
    p = rng.uniform(0, 0.9, size=(2, 300))
    theta = np.array([0.4, 0.8])
    found = kernels.first_at_or_above(p, q, theta)
    holds = (p[:, :, np.newaxis] + q[:, np.newaxis, :]) >= theta[:, np.newaxis, np.newaxis]
    want = np.where(holds.any(axis=2), holds.argmax(axis=2), q.shape[1])
    np.testing.assert_array_equal(found, want)


def test_reach_thresholds_decide_like_the_contrast_ratio() -> None:
    """Luminance thresholds reproduce ``CR < 3`` on every float near them."""
    yb = np.array([0.0, 0.05, 0.5, 1.0])
    low, high = kernels.reach_thresholds(yb, 3.0)
    for i, y_b in enumerate(yb):
        for edge in (low[i], high[i]):
            if not np.isfinite(edge):
                continue
            ys = np.array([np.nextafter(edge, -1), edge, np.nextafter(edge, 2)])
            ys = ys[ys >= 0]  # luminances are never negative
            cb = y_b + 0.05
            cr = np.maximum(ys + 0.05, cb) / np.minimum(ys + 0.05, cb)
            np.testing.assert_array_equal(cr < 3.0, (ys >= low[i]) & (ys < high[i]))


@settings(max_examples=40, deadline=None)
@given(
    canvas=st.tuples(*[st.integers(0, 255)] * 3),
    alpha=st.floats(0.0, 3.0, allow_nan=False),
    levels=st.integers(2, 11),
)
def test_any_canvas_and_alpha_match_reference(canvas, alpha: float, levels: int) -> None:
    """Property: for every canvas, alpha >= 0 and grid, counts equal the reference's."""
    color = "#" + "".join(f"{v:02x}" for v in canvas)
    check_against_reference(Theme("h", (Canvas("h", color),)), encoded_levels(levels), alpha)
