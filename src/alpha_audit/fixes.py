"""A fix for every failing finding, computed once in the pipeline for every renderer.

For a colour failing a rule of one paint on a canvas (contrast, drift, lock,
thin strokes) a :class:`~alpha_audit.results.ColorFix` gives three answers a
reviewer can act on:

1. **the largest safe alpha** for that colour, its icons moving together
   (:class:`~alpha_audit.suggest.engine.SafeAlphas`, the one suggest engine);
2. **the smallest alpha at or above 1 that reaches the threshold on every
   canvas of the failing canvas's mode** -- exact, from events: on ``[1,
   alpha_max]`` each canvas's displayed luminance is piecewise linear in the
   coefficient (:func:`~alpha_audit.suggest.events.luminance_band_pieces`), so
   the set where contrast is below the threshold is a union of open intervals
   known in closed form, and the answer is the smallest point outside all of
   them, rounded *up* to ``precision`` decimals and re-checked there;
3. **the nearest passing source colour**: the colour closest in CIEDE2000 to
   the source, at the source's OKLCH hue and inside the sRGB gamut, whose
   output passes every contrast rule of the policy on every canvas of the
   theme at the colour's alphas and opacities (:func:`nearest_passing_color`).

A finding between several colours (collision, separation, confusion, CVD)
gets a :class:`~alpha_audit.results.GroupFix`: the largest safe alpha for its
rule alone, of the whole set, or for a confusion the joint answer of its group:
the roles the failing findings connect, grown into every role the answer finds
pulled under the floor (:meth:`~alpha_audit.suggest.engine.SafeAlphas.joint`),
one fix for every finding of the group.  Where an answer is an exact edit of a
value the loaders located (:class:`~alpha_audit.model.Span`), the finding
carries it (:attr:`~alpha_audit.findings.Finding.edits`); see :func:`_edits`.
Pure computation: nothing is printed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from decimal import ROUND_CEILING, Decimal
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color import (
    composite_paint,
    delta_e_2000,
    from_8bit,
    judged_contrast,
    linear_to_hex,
    relative_luminance,
    shipped,
    srgb_encode,
    to_8bit,
)
from alpha_audit.color.composite import composite_css_least
from alpha_audit.color.oklch import linear_to_oklch, oklch_to_linear
from alpha_audit.figures import ConfusionFigures, ContrastFigures
from alpha_audit.findings import Finding
from alpha_audit.model import Edit, Icon, Span
from alpha_audit.policy import Policy, contrast_breaks
from alpha_audit.results import (
    CheckReport,
    ColorFix,
    Fix,
    GroupFix,
    NearestColor,
    ReachAlpha,
    SafeAlpha,
)
from alpha_audit.rows import AuditResult
from alpha_audit.rules import RULES, Family, Rule
from alpha_audit.suggest.engine import SafeAlphas, connected
from alpha_audit.suggest.events import code_crossings

__all__ = [
    "ACHROMATIC_CHROMA",
    "MAX_FIXED_COLORS",
    "format_alpha",
    "nearest_passing_color",
    "passes_everywhere",
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
_ELIMINATE_FROM = 2048  # colours judged at once from which failing ones are dropped early
# Fixes cost about 0.1 s per failing colour (a suggest question and, for contrast
# failures, a nearest-colour search).  A brand set can fail thousands of colours at
# once; the first MAX_FIXED_COLORS per check (audits in order, colours in row order)
# get one, the rest are counted and answered by ``alpha-audit suggest``.
MAX_FIXED_COLORS = 50
# How a fix's colours are drawn: an audit's pipeline, or ``css-least`` for a paint a
# browser drew with CSS (of what engines may show, the colour nearest the backdrop:
# :func:`~alpha_audit.color.composite.composite_css_least`), so a page's fix passes in
# every engine, not only in the formula.
Drawn = Literal["linear", "css", "css-least"]


def _composite(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike, opacity: ArrayLike, how: Drawn
) -> NDArray[np.float64]:
    """The shown colour of a paint at ``alpha`` and ``opacity`` drawn ``how``."""
    if how == "linear":
        return composite_paint(source, background, alpha, opacity, "linear")
    # A browser multiplies opacities: only the product is bounded (by 1).
    product = np.asarray(alpha, dtype=np.float64) * np.asarray(opacity, dtype=np.float64)
    if how == "css-least":
        return composite_css_least(source, background, product)
    return composite_paint(source, background, 1.0, product, "css")


def _round_up(value: float, precision: int) -> float:
    step = Decimal(1).scaleb(-precision)
    return float(Decimal(repr(value)).quantize(step, rounding=ROUND_CEILING))


def format_alpha(alpha: float) -> str:
    """The shortest text that reads back as ``alpha``.

    >>> format_alpha(1.042), format_alpha(1.0), format_alpha(0.1 + 0.2)
    ('1.042', '1', '0.30000000000000004')
    """
    short = f"{alpha:g}"
    return short if float(short) == alpha else repr(alpha)


def smallest_alpha_reaching(
    source: ArrayLike,
    backgrounds: ArrayLike,
    threshold: float,
    *,
    opacities: ArrayLike = 1.0,
    alpha_max: float = 2.0,
    precision: int = 3,
    pipeline: Drawn = "linear",
) -> tuple[float | None, float | None]:
    """``(rounded, exact)``: the smallest ``a >= 1`` reaching the threshold on every canvas.

    ``source`` is one linear colour ``(3,)``, ``backgrounds`` the canvases
    ``(m, 3)``, ``opacities`` the paint's opacities (each must reach it).
    Judged on what ships (8-bit colours on the 8-bit canvas), exactly: what
    ships changes only where a displayed channel crosses a code threshold, so
    every crossing and every gap between two is judged, in order; ``exact`` is
    the first good one (a gap's left end is its infimum).  ``rounded`` is
    ``exact`` rounded up to ``precision`` decimals, stepped up until what ships
    passes everywhere; both are ``None`` when nothing up to ``alpha_max`` does.
    Under ``css`` the coefficient multiplies the opacity and a browser clamps the
    product to 1: ``a`` goes no further than ``1 / max(opacities)`` (a paint at
    opacity 0.5 reaches the threshold, if at all, by an opacity up to 1).

    >>> # Linear grey 0.4 on white: 2.33:1 at alpha 1; darker with a > 1 (moved away from white).
    >>> rounded, exact = smallest_alpha_reaching([0.4] * 3, [[1.0, 1.0, 1.0]], 3.0)
    >>> # In float Y = 1 - 0.6 a reaches 0.3 at a = 7/6, but the 8-bit code shown there
    >>> # gives 2.995:1; the next code, from a = 1.169440 on, gives 3.033:1.
    >>> rounded, round(exact, 6)
    (1.17, 1.16944)
    """
    s = np.asarray(source, dtype=np.float64).reshape(3)
    bgs = np.asarray(backgrounds, dtype=np.float64).reshape(-1, 3)
    o = np.asarray(opacities, dtype=np.float64).reshape(-1)
    t = float(threshold)
    bg = np.repeat(bgs, o.size, axis=0)  # every (canvas, opacity)
    q = np.tile(o, bgs.shape[0])
    if pipeline != "linear":
        alpha_max = min(alpha_max, 1.0 / float(o.max()))

    def reaches(a: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Whether what ships at each ``a`` (shape (N,)) reaches ``t`` on every canvas."""
        if pipeline != "linear":
            a = np.minimum(a, 1.0 / q.max())  # float noise at a browser's clamp
        shown = _composite(s, bg[:, None, :], a[None, :], q[:, None], pipeline)
        ok: NDArray[np.bool_] = np.all(judged_contrast(shown, bg[:, None, :]) >= t, axis=0)
        return ok

    # What ships changes only where a displayed channel crosses a code threshold: judge
    # every crossing and every gap between two (the codes are constant on a gap).
    if pipeline == "css-least":
        # The colour shown changes only where the 8-bit alpha does: every a o 255 whole.
        crossings = (np.arange(256)[np.newaxis, :] / (255.0 * q[:, np.newaxis])).reshape(-1)
    elif pipeline == "css":
        crossings = _css_crossings(s, bg, q).reshape(-1)
    else:
        crossings = code_crossings(np.broadcast_to(s, bg.shape), bg, q[:, None]).reshape(-1)
    inside = crossings[np.isfinite(crossings) & (crossings > ALPHA_LO) & (crossings < alpha_max)]
    points = np.unique(np.concatenate([[ALPHA_LO, alpha_max], inside]))
    elements = np.empty(2 * points.size - 1)
    elements[0::2], elements[1::2] = points, 0.5 * (points[:-1] + points[1:])
    good = np.zeros(elements.size, dtype=bool)
    for start in range(0, elements.size, _CHUNK):
        good[start : start + _CHUNK] = reaches(elements[start : start + _CHUNK])
    if not good.any():
        return None, None
    k = int(np.argmax(good))
    exact = float(points[k // 2])  # a point, or the left end of a gap (its infimum)
    unit = 10.0**-precision
    rounded = _round_up(exact, precision)
    while rounded <= alpha_max + unit / 2 and not reaches(np.array([rounded]))[0]:
        # A later bad element, or float noise exactly at a crossing.
        rounded = _round_up(rounded + unit / 2, precision)
    if rounded > alpha_max + unit / 2:
        return None, exact
    return rounded, exact


def _css_crossings(
    source: NDArray[np.float64], backgrounds: NDArray[np.float64], opacity: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Coefficients at which a css-composited channel crosses a code threshold.

    A browser blends encoded values, ``b' + a o (s' - b')``, and rounds to a code:
    linear in ``a``, so the crossing of ``(n + 0.5) / 255`` is at
    ``((n + 0.5) / 255 - b') / (o (s' - b'))`` (``nan`` where the channel never
    moves), shape ``(canvases, 3, 255)``.
    """
    s = srgb_encode(source)[np.newaxis, :, np.newaxis]
    b = srgb_encode(backgrounds)[:, :, np.newaxis]
    d = opacity[:, np.newaxis, np.newaxis] * (s - b)
    edges = (np.arange(255) + 0.5) / 255.0
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(d != 0, (edges - b) / d, np.nan)


def passes_everywhere(
    colors: ArrayLike,
    backgrounds: ArrayLike,
    styles: ArrayLike,
    threshold: float,
    policy: Policy | None = None,
    pipeline: Drawn = "linear",
) -> NDArray[np.bool_]:
    """Which linear colours ``(..., 3)`` pass on every canvas in every style.

    ``styles`` are ``(alpha, opacity)`` pairs ``(k, 2)`` (a plain list of
    alphas means opacity 1).  Passing: in gamut (every channel in [0, 1]),
    contrast at least ``threshold``, and every contrast rule of the policy
    satisfied (:func:`~alpha_audit.policy.contrast_breaks`, their one
    statement), against the same paint at alpha 1, composited as ``pipeline``
    draws it.  Evaluated in chunks, so memory stays bounded.
    """
    col = np.asarray(colors, dtype=np.float64)
    shape = col.shape[:-1]
    flat = col.reshape(-1, 3)
    bgs = np.asarray(backgrounds, dtype=np.float64).reshape(-1, 3)
    st = np.asarray(styles, dtype=np.float64)
    st = np.stack([st, np.ones_like(st)], axis=-1) if st.ndim == 1 else st.reshape(-1, 2)
    a, o = st[:, 0], st[:, 1]
    pol = policy or Policy()
    rules = {Rule.BELOW_THRESHOLD, *pol.contrast_rules}
    out = np.empty(flat.shape[0], dtype=bool)
    step = max(1, _CHUNK // max(1, bgs.shape[0] * a.size))
    screen = shipped(bgs)  # judged as it ships: 8-bit colours on the 8-bit canvas
    # Many colours (a search's scan): a colour failing one canvas is not composited on the
    # others. A few (a bisection step): every canvas at once costs fewer numpy calls.
    every = [np.arange(bgs.shape[0])]
    groups = _hardest_first(screen) if flat.shape[0] >= _ELIMINATE_FROM else every
    for start in range(0, flat.shape[0], step):
        chunk = flat[start : start + step]
        ok = np.all((chunk >= 0.0) & (chunk <= 1.0), axis=-1)
        for group in groups:
            alive = np.flatnonzero(ok)
            if alive.size == 0:
                break
            src = np.clip(chunk[alive], 0.0, 1.0)[:, np.newaxis, np.newaxis, :]
            b = bgs[group][np.newaxis, np.newaxis]  # (1, 1, g, 3)
            shown = _composite(src, b, a[None, :, None], o[None, :, None], pipeline)
            ref = _composite(src, b, 1.0, o[None, :, None], pipeline)
            contrast = judged_contrast(shown, b)
            c_ref = judged_contrast(ref, b)
            for rule in rules:
                breaks = contrast_breaks(rule, pol, c_ref, contrast, threshold)
                ok[alive[np.any(breaks, axis=(1, 2))]] = False
        out[start : start + step] = ok
    return out.reshape(shape)


def _hardest_first(screen: NDArray[np.float64]) -> list[NDArray[np.intp]]:
    """Canvas indices in groups of 1, 2, 4, ...: mid-luminance canvases (which fail most
    colours on contrast) first, so most failing colours are dropped after a few canvases.

    The order only saves work: a colour passes when it passes on every group.
    """
    y = relative_luminance(screen)
    # WCAG contrast with black equals contrast with white at (Y + 0.05)^2 = 0.05 * 1.05.
    order = np.argsort(np.abs(np.log(y + 0.05) - 0.5 * math.log(0.05 * 1.05)), kind="stable")
    groups, start, size = [], 0, 1
    while start < order.size:
        groups.append(order[start : start + size])
        start, size = start + size, size * 2
    return groups


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
    styles: ArrayLike,
    threshold: float,
    policy: Policy | None = None,
    pipeline: Drawn = "linear",
) -> NearestColor | None:
    """The colour of the source's OKLCH hue nearest in CIEDE2000 that passes everywhere.

    The search runs in the OKLCH (L, C) half-plane at the source's hue:
    :data:`RAYS` rays leave the source, each sampled at :data:`RAY_SAMPLES`
    points; on every ray the first passing sample is bisected against the one
    before it down to ~1e-14 in OKLab, giving the nearest passing point along
    that ray.  The best ray's neighbourhood is then searched again with finer
    rays (:data:`REFINE_ROUNDS` rounds of :data:`REFINE_RAYS`).  A passing
    region thinner than a sample step (``1/200`` of a ray: at most 0.006
    OKLab, about 0.6 CIEDE2000) can be missed.  The optimum is finally written
    as 8-bit hex: of the passing codes within +-3 steps per channel of it, the
    one nearest (CIEDE2000) to the optimum.  An achromatic source (chroma
    below :data:`ACHROMATIC_CHROMA`) only moves in lightness.  ``None`` when
    nothing of that hue passes.  ``styles`` as :func:`passes_everywhere`.

    >>> white = [[1.0, 1.0, 1.0]]
    >>> fix = nearest_passing_color([0.4, 0.4, 0.4], white, [1.0], 3.0)  # 2.33:1 -> 3:1
    >>> fix.color, round(fix.delta_e, 1)
    ('#949494', 6.7)
    """
    src = np.asarray(source, dtype=np.float64).reshape(3)
    bgs = np.asarray(backgrounds, dtype=np.float64).reshape(-1, 3)

    def passing(lin: NDArray[np.float64]) -> NDArray[np.bool_]:
        return passes_everywhere(lin, bgs, styles, threshold, policy, pipeline)

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
        return _best_on_rays(theta, l0, c0, src, to_linear, passing)

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


# OKLCH (L, C) at the source's hue -> linear sRGB; which linear colours pass.
_ToLinear = Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]
_Passing = Callable[[NDArray[np.float64]], NDArray[np.bool_]]


def _best_on_rays(
    theta: NDArray[np.float64],
    l0: float,
    c0: float,
    src: NDArray[np.float64],
    to_linear: _ToLinear,
    passing: _Passing,
) -> tuple[float, float, float, float] | None:
    """(delta_e, theta, L, C) of the best ray's nearest passing point, rays from (l0, c0)."""
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


# ------------------------------------------------------------------ per audit


@dataclass
class _Audit:
    """The fixes of one audit, each question asked once."""

    result: AuditResult
    policy: Policy
    alpha_max: float
    precision: int

    def __post_init__(self) -> None:
        r = self.result
        # A paint a browser drew with CSS is fixed for every engine (see Drawn).
        self.drawn: Drawn = "css-least" if r.observed and r.pipeline == "css" else r.pipeline
        self.by_name = {i.name: i for i in r.iconset.icons}
        # Which icons draw each colour, and the (alpha, opacity) styles it is drawn in.
        self.members: dict[str, list[str]] = {}
        self.styles: dict[str, set[tuple[float, float]]] = {}
        self.linear: dict[str, NDArray[np.float64]] = {}
        for p, e in enumerate(r.entries):
            self.members.setdefault(e.role, [])
            if e.icon.name not in self.members[e.role]:
                self.members[e.role].append(e.icon.name)
            self.styles.setdefault(e.role, set()).add((float(r.alpha[p]), e.opacity))
            self.linear.setdefault(e.role, r.sources[p])
        self.answers: dict[Rule | None, SafeAlphas] = {}
        self.safe: dict[tuple[Rule | None, tuple[str, ...]], SafeAlpha] = {}
        self.nearest: dict[str, NearestColor | None] = {}
        self.reach: dict[tuple[str, str], ReachAlpha] = {}
        self.groups: dict[Rule, dict[str, GroupFix]] = {}

    def largest_safe(self, rule: Rule | None, colors: Sequence[str]) -> SafeAlpha:
        """The largest safe alpha of the icons drawing ``colors`` (all: none given)."""
        key = (rule, tuple(colors))
        if key not in self.safe:
            icons = None if not colors else [n for c in colors for n in self.members.get(c, [])]
            self.safe[key] = self.answers_for(rule)(icons)
        return self.safe[key]

    def group_fixes(self, rule: Rule, failures: Sequence[Finding]) -> dict[str, GroupFix]:
        """The fix of each role ``rule``'s failing findings name: the joint answer of its
        group, for ``rule`` alone.  The roles those findings connect (on any canvas,
        :func:`~alpha_audit.suggest.engine.connected`) grow into every role the answer
        finds pulled under the floor, and groups that grow into each other are one
        (:meth:`~alpha_audit.suggest.engine.SafeAlphas.joint_groups`)."""
        if rule not in self.groups:
            r = self.result
            pairs = [
                f.figures.roles
                for f in failures
                if f.rule is rule
                and (f.theme, f.iconset) == (r.theme.name, r.iconset.name)
                and isinstance(f.figures, ConfusionFigures)
            ]
            self.groups[rule] = {
                colour: GroupFix(r.theme.name, r.iconset.name, rule, colours, safe, seed)
                for colours, safe, seed in self.answers_for(rule).joint_groups(connected(pairs))
                for colour in seed
            }
        return self.groups[rule]

    def answers_for(self, rule: Rule | None) -> SafeAlphas:
        """The suggest engine for ``rule`` alone (every rule of the policy: ``None``)."""
        if rule not in self.answers:
            policy = self.policy if rule is None else replace(self.policy, rules=frozenset({rule}))
            self.answers[rule] = SafeAlphas(
                self.result, policy, alpha_max=self.alpha_max, precision=self.precision
            )
        return self.answers[rule]

    def color_fix(self, role: str, canvas: int, rules: set[Rule]) -> ColorFix:
        r = self.result
        theme = r.theme
        mode = str(theme.canvases[canvas].mode)
        icons = self.members[role]
        first = self.by_name[icons[0]]
        styles = sorted(self.styles[role])
        contrast = any(RULES[r].family is Family.CONTRAST for r in rules)
        if role not in self.nearest:
            self.nearest[role] = (
                nearest_passing_color(
                    self.linear[role],
                    theme.backgrounds,
                    styles,
                    r.threshold,
                    self.policy,
                    self.drawn,
                )
                if contrast
                else None
            )
        if (role, mode) not in self.reach:
            same = [k for k, c in enumerate(theme.canvases) if c.mode == mode]
            rounded, exact = smallest_alpha_reaching(
                self.linear[role],
                theme.backgrounds[same],
                r.threshold,
                opacities=sorted({o for _, o in styles}),
                alpha_max=self.alpha_max,
                precision=self.precision,
                pipeline=self.drawn,
            )
            self.reach[role, mode] = ReachAlpha(
                mode=mode,
                canvases=tuple(theme.canvases[k].name for k in same),
                threshold=r.threshold,
                alpha=rounded,
                exact=exact,
            )
        fixed = role.startswith("#") and first.color_name != role and first.color != role
        # A paint a browser drew with CSS: no coefficient above 1 exists there, so the
        # answers are an opacity (the reaching alpha times its opacity) and a colour.
        page = self.drawn == "css-least"
        # A palette role moves with the roles that hold it at alpha 1, if any
        # (SafeAlphas.joint: few roles, few questions).  Any other colour (a brand's hex,
        # a hard-coded paint) moves alone; with no safe alpha, the fix names the colours
        # that hold it, since alpha 1 itself may pass.
        together: tuple[str, ...] = ()
        held: tuple[str, ...] = ()
        if page:
            safe = SafeAlpha(None, None, None)
        elif fixed or role not in r.iconset.palette:
            safe = self.largest_safe(None, [role])
            limit = safe.limit
            if safe.alpha is None and limit is not None:
                of = {n: i.color_name or i.color for n, i in self.by_name.items()}
                held = tuple(dict.fromkeys(c for n in limit.icons if (c := of[n]) != role))
        else:
            colours, safe = self.answers_for(None).joint([role], grow=False)
            together = tuple(c for c in colours if c != role)
        return ColorFix(
            theme=theme.name,
            iconset=r.iconset.name,
            color=role,
            source=role if fixed else first.color,
            canvas=theme.canvases[canvas].name,
            mode=mode,
            icons=tuple(icons),
            rules=tuple(sorted(rules, key=list(Rule).index)),
            largest_safe=safe,
            reach=self.reach[role, mode],
            nearest=self.nearest[role],
            manifest=r.iconset.path,
            line=None if fixed else first.color_line,
            opacity=max(o for _, o in styles) if page else None,
            together=together,
            held=held,
        )


def _role_of(finding: Finding, result: AuditResult) -> str | None:
    """The colour a per-paint finding is about (its row's): its palette name, else its colour."""
    return result.entries[finding.rows[0]].role if finding.rows else None


def _mode_canvases(finding: Finding, result: AuditResult) -> dict[str, int]:
    """For each canvas mode of ``finding``: the canvas its colour fix is computed on.

    The worst canvas for its own mode, else the first canvas of the mode
    where the finding occurs (a colour's reaching alpha is per mode).
    """
    index = {c.name: k for k, c in enumerate(result.theme.canvases)}
    names = [finding.canvas, *finding.canvases] if finding.canvas else list(finding.canvases)
    out: dict[str, int] = {}
    for name in names:
        j = index.get(name or "")
        if j is not None:
            out.setdefault(str(result.theme.canvases[j].mode), j)
    return out


def with_fixes(report: CheckReport, *, alpha_max: float = 2.0, precision: int = 3) -> CheckReport:
    """``report`` with its fixes: each failing finding names the fixes that answer it.

    Order is stable: audits in order, then colours in finding order (worst
    first).  A finding about one colour gets one colour fix per canvas mode
    it occurs in (the worst canvas of the mode).  Each colour's largest safe
    alpha and nearest colour are computed once; the smallest reaching alpha
    once per mode; a group rule's answer once per rule and roles.  At most
    :data:`MAX_FIXED_COLORS` colours get a fix (the rest are counted in
    ``fixes_left_out``).
    """
    gate = report.gate
    policy = gate.policy
    # A finding's audit: its theme, icon set and worst canvas (a page's audits share a
    # state and a story, one audit per backdrop).
    audits = [_Audit(r, policy, alpha_max, precision) for r in report.audits]
    owner = {
        (r.theme.name, r.iconset.name, c.name): k
        for k, r in enumerate(report.audits)
        for c in r.theme.canvases
    }

    def audit_of(f: Finding) -> _Audit | None:
        k = owner.get((f.theme, f.iconset, f.canvas or ""))
        return None if k is None else audits[k]

    # Every written canvas value of every audit: a token that is one mode's icon colour
    # and another mode's canvas (an alias in a dark block) is never rewritten.
    canvas_spans = frozenset(
        c.span for r in report.audits for c in r.theme.canvases if c.span is not None
    )
    fixes: list[Fix] = []
    index: dict[object, int] = {}
    budget = MAX_FIXED_COLORS
    wanted, canvas_of = _colours_wanted(gate.failures, audit_of)
    left_out: set[tuple[str, str, str]] = set()
    colors_fixed: set[tuple[str, str, str]] = set()
    findings = []
    for f in gate.findings:
        if not f.fails or not f.canvases:
            findings.append(f)
            continue
        a = audit_of(f)
        found: list[int] = []
        fixed_by = RULES[f.rule].fixed_by
        role = _role_of(f, a.result) if a is not None and fixed_by == "colour" else None
        if a is not None and role is not None:
            for mode in _mode_canvases(f, a.result):
                color = (f.theme, f.iconset, role)
                key: object = ("colour", f.theme, f.iconset, role, mode)
                if key not in index and (color in colors_fixed or budget > 0):
                    if color not in colors_fixed:
                        budget -= 1
                        colors_fixed.add(color)
                    index[key] = len(fixes)
                    which = (f.theme, f.iconset, role, mode)
                    fixes.append(a.color_fix(role, canvas_of[which], wanted[which]))
                if key in index:
                    found.append(index[key])
                else:
                    left_out.add(color)
        elif a is not None and fixed_by == "group":
            group: GroupFix | None = None
            if isinstance(f.figures, ConfusionFigures):
                group = a.group_fixes(f.rule, gate.failures).get(f.figures.roles[0])
            key = ("group", f.theme, f.iconset, f.rule, group.colors if group else ())
            if key not in index and len(index) < 2 * MAX_FIXED_COLORS:
                index[key] = len(fixes)
                whole = a.largest_safe(f.rule, ()) if group is None else group.safe
                fixes.append(group or GroupFix(f.theme, f.iconset, f.rule, (), whole))
            if key in index:
                found.append(index[key])
        edits = _edits(f, [fixes[k] for k in found], a.result if a else None, canvas_spans)
        findings.append(replace(f, fixes=tuple(found), edits=edits))
    gate = replace(gate, findings=tuple(findings))
    return replace(report, gate=gate, fixes=tuple(fixes), fixes_left_out=len(left_out))


# (theme, icon set, colour, canvas mode): what a colour fix is computed for.
_ColourKey = tuple[str, str, str, str]


def _colours_wanted(
    failures: Sequence[Finding], audit_of: Callable[[Finding], _Audit | None]
) -> tuple[dict[_ColourKey, set[Rule]], dict[_ColourKey, int]]:
    """Which colours fail which per-paint rules in which mode, and on which canvas
    (the first failure's worst of the mode) each colour fix is computed."""
    wanted: dict[_ColourKey, set[Rule]] = {}
    canvas_of: dict[_ColourKey, int] = {}
    for f in failures:
        a = audit_of(f)
        if a is None or not f.canvases or RULES[f.rule].fixed_by != "colour":
            continue
        role = _role_of(f, a.result)
        if role is None:
            continue
        for mode, j in _mode_canvases(f, a.result).items():
            wanted.setdefault((f.theme, f.iconset, role, mode), set()).add(f.rule)
            canvas_of.setdefault((f.theme, f.iconset, role, mode), j)
    return wanted, canvas_of


def _edits(
    finding: Finding,
    fixes: Sequence[Fix],
    result: AuditResult | None,
    canvas_spans: frozenset[Span],
) -> tuple[Edit, ...]:
    """The fixes of ``finding`` as text edits, where applying one is known to clear it.

    Offered only for one icon's contrast on one canvas, judged on its own
    colour (``currentColor`` at opacity 1: the paint the manifest sets) in the
    ``linear`` pipeline, where the fixes' compositing is the audit's: the
    largest safe alpha answers all three contrast rules; the smallest reaching
    alpha ``below-threshold`` and ``newly-failing`` (not ``loss``: contrast can
    stay lower than at 1); the nearest colour all three.  A colour edit is not
    offered for a locked colour, nor for a token value that also sets a canvas
    of any mode audited (``canvas_spans``: the edit would move the canvas).  The
    value must be written in a file: a default alpha, ``--alpha`` or a DTCG
    colour object give no edit.
    """
    icon = None if result is None else _editable_icon(finding, result)
    if icon is None or result is None:
        return ()
    locked = result.iconset.locked
    colour_editable = (
        icon.color_span is not None
        and icon.name not in locked
        and (icon.color_name or "") not in locked
        and icon.color_span not in canvas_spans
    )
    out: list[Edit] = []
    for fix in fixes:
        if not isinstance(fix, ColorFix):
            continue
        out += _alpha_edits(finding, fix, icon)
        near = fix.nearest
        if colour_editable and icon.color_span and near is not None and near.delta_e > 0:
            out.append(
                Edit(
                    "nearest-color",
                    f"use {near.color} for {fix.color}, the nearest passing colour of the same "
                    f"OKLCH hue (CIEDE2000 {near.delta_e:.2f} away)",
                    icon.color_span,
                    near.color,
                )
            )
    return tuple(out)


def _editable_icon(finding: Finding, result: AuditResult) -> Icon | None:
    """The icon whose written values an edit may change: one icon's contrast, judged on
    its own colour (``currentColor`` at opacity 1) in the ``linear`` pipeline."""
    fig = finding.figures
    if (
        not isinstance(fig, ContrastFigures)
        or len(finding.icons) != 1
        or result.pipeline != "linear"
        or fig.paint != "currentColor"
        or fig.opacity != 1.0
    ):
        return None
    icon = next((i for i in result.iconset.icons if i.name == finding.icons[0]), None)
    return icon if icon is not None and fig.source == icon.color else None


def _alpha_edits(finding: Finding, fix: ColorFix, icon: Icon) -> list[Edit]:
    """The alpha edits of one colour fix: its largest safe alpha, its reaching alpha."""
    span = icon.alpha_span
    if span is None:
        return []
    out: list[Edit] = []
    # An answer for several colours together is no edit of this icon's alpha alone.
    safe = None if fix.together else fix.largest_safe.alpha
    if safe is not None and safe != icon.alpha:
        out.append(
            Edit(
                "largest-safe-alpha",
                f"set alpha to {format_alpha(safe)}, the largest safe alpha for {fix.color}",
                span,
                format_alpha(safe),
            )
        )
    reach = fix.reach.alpha
    if (
        reach is not None
        and reach not in (icon.alpha, safe)
        and RULES[finding.rule].reach_clears
        # It reaches the threshold on its mode's canvases: it clears the
        # finding only if every canvas of the finding is one of them.
        and set(finding.canvases) <= set(fix.reach.canvases)
    ):
        out.append(
            Edit(
                "smallest-alpha-reaching",
                f"set alpha to {format_alpha(reach)}, the smallest alpha from 1 reaching "
                f"{fix.reach.threshold:g}:1 on every {fix.mode} canvas",
                span,
                format_alpha(reach),
            )
        )
    return out
