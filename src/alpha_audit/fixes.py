"""A fix for every failing (colour, canvas): three answers a reviewer can act on.

For each palette colour that fails a gate rule on a canvas:

1. **the largest safe alpha** for that colour (its icons moving together), which
   is :func:`alpha_audit.suggest.largest_safe_alpha` -- reused, not restated
   (over the policy's rules but the paint rules, which suggest does not answer yet);
2. **the smallest alpha at or above 1 that reaches the threshold on every
   canvas of the failing canvas's mode** -- exact, from events: on ``[1,
   alpha_max]`` each canvas's luminance ``Y(a)`` of ``clip(b + a (s - b))`` is
   piecewise linear (:func:`alpha_audit.suggest.events.luminance_band_pieces`), so the
   set where contrast is below the threshold is a union of open intervals
   known in closed form, and the answer is the smallest point of ``[1,
   alpha_max]`` outside all of them.  It is reported rounded *up* to
   ``precision`` decimals and re-checked there by direct compositing;
3. **the nearest passing source colour**: the colour closest in CIEDE2000 to
   the source, at the source's OKLCH hue and inside the sRGB gamut, whose
   output passes on every canvas of the theme at the set's alpha(s).  "Passes"
   means contrast at least the threshold and, when the policy has the ``loss``
   rule, no loss beyond ``max_loss`` (the rules of one colour against its
   canvases; collisions and separation depend on the other colours and are
   left to re-running the gate).  See :func:`nearest_passing_color` for the
   search and its precision.

Pure computation: nothing is printed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from decimal import ROUND_CEILING, Decimal
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.audit import AuditResult
from alpha_audit.color import (
    composite_extended,
    contrast_ratio,
    delta_e_2000,
    from_8bit,
    linear_to_hex,
    relative_luminance,
    to_8bit,
)
from alpha_audit.color.oklch import linear_to_oklch, oklch_to_linear
from alpha_audit.gate import CheckReport, Finding
from alpha_audit.policy import CONTRAST_RULES, Policy, Rule, contrast_breaks
from alpha_audit.suggest import SafeAlpha, largest_safe_alpha
from alpha_audit.suggest.events import luminance_band, luminance_band_pieces

__all__ = [
    "ACHROMATIC_CHROMA",
    "RAYS",
    "RAY_SAMPLES",
    "ColorFix",
    "NearestColor",
    "ReachAlpha",
    "color_key",
    "describe_fix",
    "fix_lookup",
    "fix_to_dict",
    "fixes_capped",
    "fixes_for",
    "nearest_passing_color",
    "passes_everywhere",
    "report_fixes",
    "safe_span",
    "smallest_alpha_reaching",
    "with_fixes",
]

ALPHA_LO = 1.0  # the reference coefficient: a fix never asks for less
# Below this OKLCH chroma a colour has no meaningful hue (sRGB white has
# C ~ 1.3e-4 through colour-science's Oklab matrices): only lightness moves.
ACHROMATIC_CHROMA = 1e-3
# Search resolution of nearest_passing_color: rays from the source in the
# (L, C) half-plane, samples per ray, and angular refinement rounds.
RAYS = 180
RAY_SAMPLES = 200
REFINE_ROUNDS = 4
REFINE_RAYS = 24
BISECTION_STEPS = 48  # along a ray of length <= ~1.2: 1.2 / 2**48 < 1e-14
_CHUNK = 1 << 15  # colours per vectorised evaluation (bounded memory)


@dataclass(frozen=True)
class ReachAlpha:
    """The smallest alpha >= 1 at which a colour reaches the threshold on every canvas of a mode.

    ``alpha`` is rounded up to the precision and re-checked (``None``: no
    alpha up to ``alpha_max`` reaches it); ``exact`` is the infimum itself.
    """

    mode: str
    canvases: tuple[str, ...]
    threshold: float
    alpha: float | None
    exact: float | None


@dataclass(frozen=True)
class NearestColor:
    """The nearest passing colour at the source's OKLCH hue.

    ``color`` is the 8-bit hex to write (checked to pass); ``delta_e`` is its
    CIEDE2000 from the source.  ``lightness``/``chroma``/``hue`` are the OKLCH
    of the continuous optimum the hex rounds (hue in degrees).
    """

    color: str
    delta_e: float
    lightness: float
    chroma: float
    hue: float


@dataclass(frozen=True)
class ColorFix:
    """How to fix one palette colour failing on one canvas."""

    theme: str
    iconset: str
    color: str  # palette name, or the hex when the colour has none
    source: str
    canvas: str
    mode: str
    icons: tuple[str, ...]  # every icon of the colour
    rules: tuple[Rule, ...]  # the rules it fails on this canvas
    largest_safe: SafeAlpha
    reach: ReachAlpha
    nearest: NearestColor | None
    manifest: Path | None = None
    line: int | None = None  # manifest line that sets the colour (first icon), if known


def _round_up(value: float, precision: int) -> float:
    step = Decimal(1).scaleb(-precision)
    return float(Decimal(repr(value)).quantize(step, rounding=ROUND_CEILING))


def _reaches(
    source: NDArray[np.float64], backgrounds: NDArray[np.float64], a: float, t: float
) -> bool:
    out = composite_extended(source, backgrounds, a)
    return bool(np.all(contrast_ratio(out, backgrounds) >= t))


def smallest_alpha_reaching(
    source: ArrayLike,
    backgrounds: ArrayLike,
    threshold: float,
    *,
    alpha_max: float = 2.0,
    precision: int = 3,
) -> tuple[float | None, float | None]:
    """``(rounded, exact)``: the smallest ``a >= 1`` reaching the threshold on every canvas.

    ``source`` is one linear colour ``(3,)``, ``backgrounds`` the canvases
    ``(m, 3)``.  Exact: the bad set (contrast below the threshold on some
    canvas) is a finite union of open intervals, one per canvas and linear
    piece; the infimum of its complement is ``1`` or a right end of one of
    them, so only those candidates are tested.  ``rounded`` is ``exact``
    rounded up to ``precision`` decimals, stepped up until a direct composite
    passes everywhere; both are ``None`` when nothing up to ``alpha_max`` does.

    >>> # Linear grey 0.4 on white: 2.33:1 at alpha 1; darker with a > 1 (moved away from white).
    >>> rounded, exact = smallest_alpha_reaching([0.4] * 3, [[1.0, 1.0, 1.0]], 3.0)
    >>> rounded, round(exact, 9)  # Y = 1 - 0.6 a reaches 0.3 at a = 7/6
    (1.167, 1.166666667)
    """
    s = np.asarray(source, dtype=np.float64).reshape(3)
    bgs = np.asarray(backgrounds, dtype=np.float64).reshape(-1, 3)
    t = float(threshold)
    lo, hi = luminance_band(t, relative_luminance(bgs))
    pieces = luminance_band_pieces(s[np.newaxis, :], bgs, lo, hi, ALPHA_LO, alpha_max)
    p = np.stack([pc[0] for pc in pieces])  # (4, m)
    q = np.stack([pc[1] for pc in pieces])
    lower = np.stack([pc[2] for pc in pieces])
    upper = np.stack([pc[3] for pc in pieces])
    ends = np.concatenate([[ALPHA_LO], upper.ravel(), q.ravel()])
    candidates = np.unique(ends[np.isfinite(ends) & (ends >= ALPHA_LO) & (ends <= alpha_max)])
    c = candidates[:, np.newaxis, np.newaxis]
    bad = np.any((p <= c) & (c <= q) & (lower < c) & (c < upper), axis=(1, 2))
    good = candidates[~bad]
    if good.size == 0:
        return None, None
    exact = float(good[0])
    unit = 10.0**-precision
    rounded = _round_up(exact, precision)
    while rounded <= alpha_max + unit / 2 and not _reaches(s, bgs, rounded, t):
        # A later bad interval, or float noise exactly at the crossing.
        rounded = _round_up(rounded + unit / 2, precision)
    if rounded > alpha_max + unit / 2:
        return None, exact
    return rounded, exact


def passes_everywhere(
    colors: ArrayLike,
    backgrounds: ArrayLike,
    alphas: ArrayLike,
    threshold: float,
    policy: Policy | None = None,
) -> NDArray[np.bool_]:
    """Which linear colours ``(..., 3)`` pass on every canvas at every alpha.

    In gamut (every channel in [0, 1]), contrast at least ``threshold`` at
    each alpha, and no contrast loss beyond ``max_loss`` when the policy has
    the ``loss`` rule (the gate's own test: a gain below ``-max(max_loss,
    1e-10)`` is a loss).  Evaluated in chunks, so memory stays bounded.
    """
    col = np.asarray(colors, dtype=np.float64)
    shape = col.shape[:-1]
    flat = col.reshape(-1, 3)
    bgs = np.asarray(backgrounds, dtype=np.float64).reshape(-1, 3)
    a = np.asarray(alphas, dtype=np.float64).reshape(-1)
    pol = policy or Policy()
    # "Passes": the threshold always, plus every contrast rule the policy enables
    # (policy.contrast_breaks is their one statement).
    rules = {Rule.BELOW_THRESHOLD, *pol.contrast_rules}
    out = np.empty(flat.shape[0], dtype=bool)
    step = max(1, _CHUNK // max(1, bgs.shape[0] * a.size))
    for start in range(0, flat.shape[0], step):
        chunk = flat[start : start + step]
        ok = np.all((chunk >= 0.0) & (chunk <= 1.0), axis=-1)
        src = np.clip(chunk, 0.0, 1.0)[:, np.newaxis, np.newaxis, :]
        composite = composite_extended(
            src, bgs[np.newaxis, np.newaxis], a[np.newaxis, :, np.newaxis]
        )
        contrast = contrast_ratio(composite, bgs[np.newaxis, np.newaxis])  # (N, k, m)
        ref = contrast_ratio(src[:, 0], bgs[np.newaxis])[:, np.newaxis, :]  # (N, 1, m)
        for rule in rules:
            ok &= ~np.any(contrast_breaks(rule, pol, ref, contrast, threshold), axis=(1, 2))
        out[start : start + step] = ok
    return out.reshape(shape)


def _ray_ends(l0: float, c0: float, theta: NDArray[np.float64]) -> NDArray[np.float64]:
    """Length of each ray from ``(l0, c0)`` until it leaves ``0 <= L <= 1``, ``C >= 0``."""
    dl, dc = np.cos(theta), np.sin(theta)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_l = np.where(dl > 0, (1.0 - l0) / dl, np.where(dl < 0, -l0 / dl, np.inf))
        t_c = np.where(dc < 0, -c0 / dc, np.where(dc > 0, 0.5 / dc, np.inf))  # C <= 0.5 > sRGB
    return np.minimum(t_l, t_c)


def nearest_passing_color(
    source: ArrayLike,
    backgrounds: ArrayLike,
    alphas: ArrayLike,
    threshold: float,
    policy: Policy | None = None,
) -> NearestColor | None:
    """The colour of the source's OKLCH hue nearest in CIEDE2000 that passes everywhere.

    The search runs in the OKLCH (L, C) half-plane at the source's hue:
    :data:`RAYS` rays leave the source, each sampled at :data:`RAY_SAMPLES`
    points; on every ray the first passing sample is bisected against the one
    before it down to ~1e-14 in OKLab, giving the nearest passing point along
    that ray.  The best ray's neighbourhood is then searched again with finer
    rays (:data:`REFINE_ROUNDS` rounds of :data:`REFINE_RAYS`), so the angle
    is resolved to about ``2 pi / 180 / 12**4``.  A passing region thinner
    than a sample step (``1/200`` of a ray: at most 0.006 OKLab, about 0.6
    CIEDE2000) can be missed.  The optimum is finally written as 8-bit hex:
    of the passing codes within +-3 steps per channel of it, the one nearest
    (CIEDE2000) to the optimum, so the hue drifts only by rounding.
    An achromatic source (chroma below :data:`ACHROMATIC_CHROMA`) only moves
    in lightness.  ``None`` when nothing of that hue passes.

    >>> white = [[1.0, 1.0, 1.0]]
    >>> fix = nearest_passing_color([0.4, 0.4, 0.4], white, [1.0], 3.0)  # 2.33:1 -> 3:1
    >>> fix.color, round(fix.delta_e, 1)
    ('#949494', 6.7)
    """
    src = np.asarray(source, dtype=np.float64).reshape(3)
    bgs = np.asarray(backgrounds, dtype=np.float64).reshape(-1, 3)
    a = np.asarray(alphas, dtype=np.float64).reshape(-1)

    def passing(lin: NDArray[np.float64]) -> NDArray[np.bool_]:
        return passes_everywhere(lin, bgs, a, threshold, policy)

    l0, c0, hue = (float(v) for v in linear_to_oklch(src))
    achromatic = c0 < ACHROMATIC_CHROMA
    if achromatic:
        c0 = 0.0

    def to_linear(ll: NDArray[np.float64], cc: NDArray[np.float64]) -> NDArray[np.float64]:
        return oklch_to_linear(np.stack([ll, cc, np.full_like(ll, hue)], axis=-1))

    if passing(src[np.newaxis])[0]:
        lch = linear_to_oklch(src)
        return NearestColor(linear_to_hex(src), 0.0, float(lch[0]), float(lch[1]), _deg(hue))

    def best_on_rays(theta: NDArray[np.float64]) -> tuple[float, float, float, float] | None:
        """(delta_e, theta, L, C) of the best ray's nearest passing point."""
        length = _ray_ends(l0, c0, theta)  # (R,)
        frac = np.linspace(0.0, 1.0, RAY_SAMPLES + 1)[1:]
        t = length[:, np.newaxis] * frac  # (R, S)
        dl, dc = np.cos(theta)[:, np.newaxis], np.sin(theta)[:, np.newaxis]
        ok = passing(to_linear(l0 + t * dl, c0 + t * dc))
        found = ok.any(axis=1)
        if not found.any():
            return None
        rows = np.flatnonzero(found)
        first = np.argmax(ok[rows], axis=1)
        hi = t[rows, first]
        lo = np.where(first > 0, t[rows, np.maximum(first - 1, 0)], 0.0)
        dl, dc = dl[rows, 0], dc[rows, 0]
        for _ in range(BISECTION_STEPS):  # every ray at once
            mid = 0.5 * (lo + hi)
            good = passing(to_linear(l0 + mid * dl, c0 + mid * dc))
            hi, lo = np.where(good, mid, hi), np.where(good, lo, mid)
        ll, cc = l0 + hi * dl, c0 + hi * dc
        de = delta_e_2000(to_linear(ll, cc), src)
        k = int(np.argmin(de))
        return float(de[k]), float(theta[rows[k]]), float(ll[k]), float(cc[k])

    if achromatic:
        best = best_on_rays(np.array([0.0, math.pi]))
    else:
        step = 2.0 * math.pi / RAYS
        theta = (np.arange(RAYS, dtype=np.float64) + 0.5) * step - math.pi
        best = best_on_rays(theta)
        for _ in range(REFINE_ROUNDS if best is not None else 0):
            assert best is not None
            fine = best[1] + np.linspace(-step, step, REFINE_RAYS + 1)
            candidate = best_on_rays(fine)
            if candidate is not None and candidate[0] < best[0]:
                best = candidate
            step /= REFINE_RAYS / 2
    if best is None:
        return None
    _, _, ll, cc = best
    point = to_linear(np.array(ll), np.array(cc))
    hexed = _passing_code(point, passing, grey=achromatic)
    if hexed is None:
        return None
    return NearestColor(
        color=linear_to_hex(hexed),
        delta_e=float(delta_e_2000(hexed, src)),
        lightness=ll,
        chroma=cc,
        hue=_deg(hue),
    )


def _deg(radians: float) -> float:
    return math.degrees(radians) % 360.0


def _passing_code(
    point: NDArray[np.float64],
    passing: Callable[[NDArray[np.float64]], NDArray[np.bool_]],
    *,
    grey: bool,
) -> NDArray[np.float64] | None:
    """The linear colour of the passing 8-bit code nearest (CIEDE2000) to ``point``.

    Nearest to the continuous optimum, not to the source, so the code keeps
    the optimum's hue as well as 8 bits can; a grey stays grey.
    """
    code = to_8bit(np.clip(point, 0.0, 1.0)).astype(np.int64)
    steps = np.arange(-3, 4)
    if grey:
        code = np.full(3, int(np.rint(code.mean())))
        offsets = np.repeat(steps[:, np.newaxis], 3, axis=1)
    else:
        offsets = np.stack(np.meshgrid(steps, steps, steps, indexing="ij"), axis=-1).reshape(-1, 3)
    codes = np.unique(np.clip(code + offsets, 0, 255), axis=0)
    lin = from_8bit(codes)
    ok = passing(lin)
    if not ok.any():
        return None
    lin = lin[ok]
    nearest: NDArray[np.float64] = lin[int(np.argmin(delta_e_2000(lin, point)))]
    return nearest


# Fixes cost about 0.1 s per failing colour (a suggest run and, for contrast
# failures, a nearest-colour search).  A brand set can fail thousands of colours
# at once; the first MAX_FIXED_COLORS per check (audits in order, colours in icon
# order) get one, the rest are counted (:func:`fixes_left_out`) and answered by
# ``alpha-audit suggest``.  No report shows more than a few dozen groups anyway.
MAX_FIXED_COLORS = 50


def color_key(result: AuditResult) -> dict[str, str]:
    """Each icon's colour as fixes name it: its palette name, else its colour."""
    return {i.name: i.color_name or i.color for i in result.iconset.icons}


def fixes_for(
    report: CheckReport,
    *,
    alpha_max: float = 2.0,
    precision: int = 3,
) -> tuple[ColorFix, ...]:
    """One :class:`ColorFix` per failing (colour, canvas) of every audit in ``report``.

    Failing means a finding that fails the gate (not exempt, not baselined)
    on a canvas; each icon it names puts its colour on that canvas.  Order is
    stable: audits in order, then colours in icon order, then canvases in
    theme order.  Each colour's largest safe alpha and nearest colour are
    computed once; the smallest reaching alpha once per mode.
    """
    policy = report.gate.policy
    out: list[ColorFix] = []
    budget = [MAX_FIXED_COLORS]
    for result in report.audits:
        failures = [
            f
            for f in report.gate.failures
            if f.theme == result.theme.name
            and f.iconset == result.iconset.name
            and f.canvas is not None
        ]
        if failures:
            out.extend(_audit_fixes(result, failures, policy, alpha_max, precision, budget))
    return tuple(out)


def failing_colors(report: CheckReport) -> int:
    """How many (audit, colour) pairs fail the gate on some canvas."""
    total = 0
    for result in report.audits:
        key_of = color_key(result)
        names = {
            key_of[n]
            for f in report.gate.failures
            if f.theme == result.theme.name
            and f.iconset == result.iconset.name
            and f.canvas is not None
            for n in f.icons
            if n in key_of
        }
        total += len(names)
    return total


def _fixed_colors(report: CheckReport) -> int:
    """How many (audit, colour) pairs have a computed fix."""
    return len({(f.theme, f.iconset, f.color) for f in report_fixes(report)})


def fixes_left_out(report: CheckReport) -> int:
    """Failing colours without a computed fix (beyond :data:`MAX_FIXED_COLORS`)."""
    return failing_colors(report) - _fixed_colors(report)


def fixes_capped(report: CheckReport) -> bool:
    """Whether :data:`MAX_FIXED_COLORS` stopped the fixes: some failing colours have none."""
    return _fixed_colors(report) >= MAX_FIXED_COLORS and fixes_left_out(report) > 0


def _audit_fixes(
    result: AuditResult,
    failures: Sequence[Finding],
    policy: Policy,
    alpha_max: float,
    precision: int,
    budget: list[int],
) -> list[ColorFix]:
    """The fixes of one audit; ``budget[0]`` counts the colours still allowed a fix."""
    theme, iconset = result.theme, result.iconset
    key_of = color_key(result)
    members: dict[str, list[int]] = {}
    for i, icon in enumerate(iconset.icons):
        members.setdefault(key_of[icon.name], []).append(i)
    canvas_index = {c.name: j for j, c in enumerate(theme.canvases)}
    failing: dict[tuple[str, int], set[Rule]] = {}
    for f in failures:
        j = canvas_index.get(f.canvas or "")
        if j is None:
            continue
        for name in f.icons:
            if name in key_of:
                failing.setdefault((key_of[name], j), set()).add(f.rule)
    order = {k: n for n, k in enumerate(members)}
    backgrounds = theme.backgrounds
    safe_cache: dict[str, SafeAlpha] = {}
    near_cache: dict[str, NearestColor | None] = {}
    reach_cache: dict[tuple[str, str], ReachAlpha] = {}
    out = []
    for color, j in sorted(failing, key=lambda cj: (order[cj[0]], cj[1])):
        idx = members[color]
        first = iconset.icons[idx[0]]
        src = np.array(first.linear)
        if color not in safe_cache:
            if budget[0] <= 0:
                continue
            budget[0] -= 1
            safe_cache[color] = largest_safe_alpha(
                theme,
                iconset,
                policy,
                icons=[iconset.icons[i].name for i in idx],
                alpha_max=alpha_max,
                precision=precision,
                threshold=result.threshold,
            )
            alphas = np.unique(iconset.alphas[idx])
            # The nearest colour answers contrast failures only (describe_fix).
            contrast = any(
                r in CONTRAST_RULES for (c, _), rs in failing.items() if c == color for r in rs
            )
            near_cache[color] = (
                nearest_passing_color(src, backgrounds, alphas, result.threshold, policy)
                if contrast
                else None
            )
        mode = str(theme.canvases[j].mode)
        if (color, mode) not in reach_cache:
            same = [k for k, c in enumerate(theme.canvases) if c.mode == mode]
            rounded, exact = smallest_alpha_reaching(
                src, backgrounds[same], result.threshold, alpha_max=alpha_max, precision=precision
            )
            reach_cache[color, mode] = ReachAlpha(
                mode=mode,
                canvases=tuple(theme.canvases[k].name for k in same),
                threshold=result.threshold,
                alpha=rounded,
                exact=exact,
            )
        out.append(
            ColorFix(
                theme=theme.name,
                iconset=iconset.name,
                color=color,
                source=first.color,
                canvas=theme.canvases[j].name,
                mode=mode,
                icons=tuple(iconset.icons[i].name for i in idx),
                rules=tuple(sorted(failing[color, j], key=list(Rule).index)),
                largest_safe=safe_cache[color],
                reach=reach_cache[color, mode],
                nearest=near_cache[color],
                manifest=iconset.path,
                line=first.color_line,
            )
        )
    return out


def with_fixes(report: CheckReport, *, alpha_max: float = 2.0, precision: int = 3) -> CheckReport:
    """``report`` carrying its fixes (:func:`fixes_for`), computed once for every renderer."""
    return replace(report, fixes=fixes_for(report, alpha_max=alpha_max, precision=precision))


def report_fixes(report: CheckReport) -> tuple[ColorFix, ...]:
    """The report's fixes: as carried (:func:`with_fixes`), else computed now (defaults)."""
    return report.fixes if report.fixes is not None else fixes_for(report)


def fix_lookup(
    report: CheckReport, fixes: Sequence[ColorFix] | None = None
) -> Callable[[Finding], tuple[ColorFix, ...]]:
    """A function giving the fixes of one finding: those of its icons' colours on its canvas.

    Renderers use it to put each fix next to the finding it answers;
    ``fixes`` defaults to :func:`report_fixes`.
    """
    known = report_fixes(report) if fixes is None else fixes
    by_key = {(f.theme, f.iconset, f.color, f.canvas): f for f in known}
    colors = {
        (a.theme.name, a.iconset.name, i.name): i.color_name or i.color
        for a in report.audits
        for i in a.iconset.icons
    }

    def lookup(finding: Finding) -> tuple[ColorFix, ...]:
        found: list[ColorFix] = []
        for icon in finding.icons:
            color = colors.get((finding.theme, finding.iconset, icon))
            fix = by_key.get((finding.theme, finding.iconset, color or "", finding.canvas or ""))
            if fix is not None and fix not in found:
                found.append(fix)
        return tuple(found)

    return lookup


def safe_span(alpha: float) -> str:
    """A largest safe alpha as the range it guarantees, ``[1, alpha]``.

    Not "at most": a colour failing at 0.9 would be sent nowhere ("at most 2").

    >>> safe_span(1.178), safe_span(1.0)
    ('alpha 1 to 1.178', 'alpha 1')
    """
    return f"alpha {ALPHA_LO:g}" if alpha <= ALPHA_LO else f"alpha {ALPHA_LO:g} to {alpha:g}"


def describe_fix(fix: ColorFix) -> str:
    """The fix in one plain line (no markup), alternatives joined by "or"; "" when none.

    The smallest reaching alpha and the nearest colour answer a contrast
    failure, so they are offered only when the colour fails a contrast rule
    there; the largest safe alpha answers every rule.

    >>> from alpha_audit.suggest import SafeAlpha
    >>> fix = ColorFix("t", "s", "warn", "#ffcc00", "white", "light", ("a",),
    ...     (Rule.BELOW_THRESHOLD,), SafeAlpha(None, None, None, ()),
    ...     ReachAlpha("light", ("white",), 3.0, 1.25, 1.2491),
    ...     NearestColor("#c9a000", 12.33, 0.7, 0.14, 90.0))
    >>> describe_fix(fix)
    'warn: alpha 1.25 or above (every light canvas) or colour #c9a000 (CIEDE2000 12.33 away)'
    """
    contrast = any(r in CONTRAST_RULES for r in fix.rules)
    options = []
    safe = fix.largest_safe.alpha
    if safe is not None:
        options.append(safe_span(safe))
    # Reaching the threshold at 1 itself is already inside that range.
    reach = fix.reach.alpha
    if contrast and reach is not None and not (safe is not None and reach <= ALPHA_LO):
        options.append(f"alpha {reach:g} or above (every {fix.mode} canvas)")
    if contrast and fix.nearest is not None and fix.nearest.delta_e > 0:
        near = fix.nearest
        options.append(f"colour {near.color} (CIEDE2000 {near.delta_e:.2f} away)")
    return f"{fix.color}: {' or '.join(options)}" if options else ""


def fix_to_dict(
    fix: ColorFix, display: Callable[[Path | None], str | None] | None = None
) -> dict[str, Any]:
    """One fix as plain JSON data (finite floats only; ``None`` where there is no answer).

    ``display`` shows the manifest path (renderers pass their relative-path
    helper); by default it is written in POSIX form as stored.
    """
    show = display or (lambda p: None if p is None else p.as_posix())

    safe = fix.largest_safe
    limit = safe.limit
    near = fix.nearest
    return {
        "theme": fix.theme,
        "iconset": fix.iconset,
        "color": fix.color,
        "source": fix.source,
        "canvas": fix.canvas,
        "mode": fix.mode,
        "icons": list(fix.icons),
        "rules": [r.value for r in fix.rules],
        "largest_safe_alpha": {
            "alpha": safe.alpha,
            "exact": safe.exact,
            "limit": None
            if limit is None
            else {
                "rule": limit.rule.value,
                "canvas": limit.canvas,
                "icons": list(limit.icons),
                "at": limit.at,
                "attained": limit.attained,
            },
        },
        "smallest_alpha_reaching": {
            "alpha": fix.reach.alpha,
            "exact": fix.reach.exact,
            "threshold": fix.reach.threshold,
            "mode": fix.reach.mode,
            "canvases": list(fix.reach.canvases),
        },
        "nearest_color": None
        if near is None
        else {
            "color": near.color,
            "delta_e": near.delta_e,
            "oklch": {"l": near.lightness, "c": near.chroma, "h": near.hue},
        },
        "manifest": show(fix.manifest),
        "line": fix.line,
    }
