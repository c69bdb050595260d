"""The paint rules for ``suggest``: where each first objects as alpha grows from 1.

Every rule is the gate's own statement (:mod:`alpha_audit.policy`:
``contrast_floor``, ``size_contrast_floor``, ``drift_breaks``,
``confusion_possible``; :func:`alpha_audit.paint_audit.cvd_collision_groups`)
applied to the same figures the gate computes, on the paint rows the gate
judges: each paint of each icon (``currentColor`` takes the manifest colour,
fixed colours are themselves) at its opacity ``o``, composited in the
coverage form ``o clip(Cb + a (Cs - Cb)) + (1 - o) Cb`` (linear pipeline).

Exact, from events (:mod:`alpha_audit.suggest.events`):

* the contrast rules on paint rows and ``thin-strokes``: the displayed
  luminance is ``o Y(clip(...)) + (1 - o) Yb`` (``q50 o`` at a size), so a
  contrast band on it is a luminance band on the clipped composite, which is
  piecewise linear in ``a``.

Bracketed on a grid of :data:`GRID_STEP` (plus every clip breakpoint), then
bisected to :data:`~alpha_audit.suggest.events.BISECTION_TOLERANCE` and
re-checked at the answer (CIEDE2000 and the CVD simulation have no closed
form in ``a``):

* ``drift`` and ``lock`` per paint;
* ``confusion`` and ``cvd-confusion`` per pair of roles, pruned by the
  lightness bound of :mod:`alpha_audit.color.nearest` and chunked (bounded
  memory for thousands of colours);
* ``cvd-collision``, grid point by grid point.

``fixed-colour`` and ``not-audited`` do not depend on alpha: when one fails,
not even alpha = 1 is safe.  Pure computation: nothing is printed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    DEFICIENCIES,
    Deficiency,
    Pipeline,
    composite_coverage,
    composite_extended,
    composite_paint,
    contrast_ratio,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_lab,
    relative_luminance,
    simulate_cvd,
    to_8bit,
)
from alpha_audit.color.nearest import (
    delta_e_2000_lightness_key,
    iter_pairs,
    lightness_weight_max,
    pairs_below,
)
from alpha_audit.load.paint_masks import PaintSet
from alpha_audit.load.paints import CURRENT_COLOR
from alpha_audit.model import IconSet, Theme
from alpha_audit.paint_audit import (
    LOCK_TOLERANCE,
    audit_paints,
    cvd_collision_groups,
    has_role,
    locked_entries,
    paint_findings,
    role_of,
)
from alpha_audit.policy import (
    Policy,
    Rule,
    confusion_possible,
    contrast_floor,
    drift_breaks,
    drift_ceiling,
    size_contrast_floor,
)
from alpha_audit.suggest.events import (
    clip_breakpoints,
    first_below,
    first_in_luminance_band,
    luminance_band,
)

__all__ = ["BRACKETED_RULES", "GRID_STEP", "PaintRules", "PaintScenario"]

# The bracketing grid for rules without a closed form in alpha; a dip below a
# limit narrower than this can be missed (the answer is re-checked directly).
GRID_STEP = 1e-3
# Item x grid-point evaluations held at once (~8 MB per float64 intermediate).
_CHUNK = 1 << 20
ALPHA_LO = 1.0
BRACKETED_RULES = frozenset(
    {
        Rule.SEPARATION,
        Rule.DRIFT,
        Rule.LOCK,
        Rule.CONFUSION,
        Rule.CVD_CONFUSION,
        Rule.CVD_COLLISION,
    }
)
_STATIC_RULES = frozenset({Rule.FIXED_COLOUR, Rule.NOT_AUDITED})


@dataclass(frozen=True)
class PaintScenario:
    """Tracks as the engine groups them: what the paint rules need of one question."""

    source: NDArray[np.float64]  # (T, 3) linear
    alpha: NDArray[np.float64]  # (T,), nan when moving
    moving: NDArray[np.bool_]  # (T,)
    icons: tuple[tuple[int, ...], ...]  # icon indices per track


# A limit found: (rule, canvas index, icon indices, first unsafe alpha, attained).
Found = tuple[Rule, int, tuple[int, ...], float, bool]


def _grid(a_lo: float, a_hi: float, breaks: NDArray[np.float64]) -> NDArray[np.float64]:
    steps = max(1, math.ceil((a_hi - a_lo) / GRID_STEP))
    inner = breaks[(breaks > a_lo) & (breaks < a_hi)]
    return np.unique(np.concatenate([np.linspace(a_lo, a_hi, steps + 1), inner]))


class PaintRules:
    """Per-paint limits (computed once) and pairwise limits (per question)."""

    def __init__(
        self,
        theme: Theme,
        iconset: IconSet,
        paints: PaintSet | None,
        policy: Policy,
        threshold: float,
        a_hi: float,
        exempt: Callable[[Rule, str, tuple[str, ...]], bool],
        pipeline: Pipeline = "linear",
    ) -> None:
        self.policy, self.threshold, self.a_hi = policy, threshold, a_hi
        self.pipeline = pipeline
        self.exempt = exempt
        self.names = tuple(i.name for i in iconset.icons)
        self.canvases = tuple(c.name for c in theme.canvases)
        self.backgrounds = theme.backgrounds
        self.y_bg = relative_luminance(self.backgrounds)
        index = {name: n for n, name in enumerate(self.names)}
        roles = [role_of(i) for i in iconset.icons]
        self.static: list[tuple[Rule, tuple[int, ...]]] = []
        if paints is None:
            # Without the SVGs read, every icon is one currentColor paint at opacity 1.
            n = len(self.names)
            self.icon = np.arange(n)
            self.source = iconset.sources
            self.opacity = np.ones(n)
            self.locked = np.array(
                [i.name in iconset.locked or i.color_name in iconset.locked for i in iconset.icons],
                dtype=bool,
            ).reshape(n)
            self.q50 = np.zeros((n, 0))
            self.sizes: tuple[int, ...] = ()
            self.current = np.ones(n, dtype=bool)
        else:
            result = audit_paints(theme, iconset, paints, threshold=threshold, pipeline=pipeline)
            self.icon = np.array([index[e.icon.name] for e in result.entries], dtype=np.intp)
            self.source = result.sources
            self.opacity = result.opacity
            self.locked = locked_entries(result)
            self.q50 = result.q50
            self.sizes = result.sizes
            entries = result.entries
            self.current = np.array([e.paint == CURRENT_COLOR for e in entries], dtype=bool)
            static = policy.rules & _STATIC_RULES
            if static:
                only = Policy(rules=frozenset(static), min_delta_e=policy.min_delta_e)
                for f in paint_findings(result, only):
                    if not exempt(f.rule, f.canvas or "", f.icons):
                        self.static.append((f.rule, tuple(index[i] for i in f.icons)))
        self.current = self.current.reshape(-1)
        # Icons taking part in confusion: those with a currentColor paint (the gate's styles).
        self.in_roles = np.zeros(len(self.names), dtype=bool)
        self.in_roles[self.icon[self.current]] = True
        self.in_roles &= np.array([has_role(i) for i in iconset.icons], dtype=bool)
        self.roles = roles
        self._per_paint: list[Found] | None = None

    # -- per paint: independent of every other icon, computed once -------------

    def per_paint(self) -> list[Found]:
        """First unsafe alpha of every per-paint rule, each paint moving from 1 to ``a_hi``."""
        if self._per_paint is None:
            found: list[Found] = []
            found += self._contrast()
            if Rule.THIN_STROKES in self.policy.rules:
                found += self._thin_strokes()
            if Rule.DRIFT in self.policy.rules:
                found += self._drift(Rule.DRIFT, self.policy.max_drift, np.ones_like(self.locked))
            if Rule.LOCK in self.policy.rules:
                found += self._drift(Rule.LOCK, LOCK_TOLERANCE, self.locked)
            self._per_paint = found
        return self._per_paint

    def _band_starts(
        self, floor: NDArray[np.float64], coverage: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Where the displayed contrast first drops below ``floor``, (P, m[, k]).

        Displayed luminance is ``o Y(clip) + (1 - o) Yb``; solving the band for
        ``Y(clip)`` leaves :func:`first_in_luminance_band`'s exact problem.
        """
        extra = floor.ndim - 2
        y_bg = self.y_bg.reshape(1, -1, *([1] * extra))
        lo, hi = luminance_band(floor, y_bg)
        o = coverage
        with np.errstate(divide="ignore", invalid="ignore"):
            lo_c = np.where(o > 0, (lo - (1.0 - o) * y_bg) / o, np.inf)
            hi_c = np.where(o > 0, (hi - (1.0 - o) * y_bg) / o, -np.inf)
        shape = (len(self.icon), len(self.canvases), *([1] * extra), 3)
        s = self.source.reshape(len(self.icon), 1, *([1] * extra), 3)
        b = self.backgrounds.reshape(1, len(self.canvases), *([1] * extra), 3)
        s, b = np.broadcast_to(s, shape), np.broadcast_to(b, shape)
        return first_in_luminance_band(s, b, lo_c, hi_c, ALPHA_LO, self.a_hi)

    def _contrast(self) -> list[Found]:
        rules = self.policy.contrast_rules
        if not rules or self.icon.size == 0:
            return []
        o = self.opacity[:, np.newaxis]
        reference = composite_coverage(
            self.source[:, np.newaxis, :], self.backgrounds[np.newaxis], 1.0, o
        )
        c_ref = contrast_ratio(reference, self.backgrounds[np.newaxis])
        out: list[Found] = []
        for rule in rules:
            floor = contrast_floor(rule, self.policy, c_ref, self.threshold)
            start, attained = self._band_starts(floor, np.broadcast_to(o, floor.shape))
            out += self._collect(rule, start, attained)
        return out

    def _thin_strokes(self) -> list[Found]:
        if not self.sizes or self.icon.size == 0:
            return []
        limit = self.threshold
        if self.policy.min_size_contrast is not None:
            limit = self.policy.min_size_contrast
        p, m, k = len(self.icon), len(self.canvases), len(self.sizes)
        coverage = (np.nan_to_num(self.q50, nan=0.0) * self.opacity[:, np.newaxis])[:, None, :]
        floor = np.full((p, m, k), size_contrast_floor(limit))
        start, attained = self._band_starts(floor, np.broadcast_to(coverage, (p, m, k)))
        start = np.where(np.isnan(self.q50)[:, np.newaxis, :], np.nan, start)  # no ink
        first = np.nanmin(np.where(np.isnan(start), np.inf, start), axis=2)
        hit = np.isfinite(first)
        att = np.any(attained & (start == first[..., np.newaxis]), axis=2)
        return self._collect(Rule.THIN_STROKES, np.where(hit, first, np.nan), att)

    def _drift(self, rule: Rule, limit: float, selected: NDArray[np.bool_]) -> list[Found]:
        rows = np.flatnonzero(selected)
        m = len(self.canvases)
        start = np.full((len(self.icon), m), np.nan)
        if rows.size == 0:
            return []
        breaks = clip_breakpoints(
            self.source[rows][:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        grid = _grid(ALPHA_LO, self.a_hi, breaks)
        per = max(1, _CHUNK // (grid.size * m))
        bg = self.backgrounds[np.newaxis, :, np.newaxis, :]
        for lo in range(0, rows.size, per):
            r = rows[lo : lo + per]
            s = self.source[r][:, np.newaxis, np.newaxis, :]
            o = self.opacity[r][:, np.newaxis, np.newaxis]
            ref = composite_coverage(s, bg, 1.0, o)  # (q, m, 1, 3)

            def minus_drift(
                a: NDArray[np.float64],
                s: NDArray[np.float64] = s,
                o: NDArray[np.float64] = o,
                ref: NDArray[np.float64] = ref,
            ) -> NDArray[np.float64]:
                a = a.reshape(1, 1, -1) if a.ndim == 1 else a.reshape(len(s), m, -1)
                return -delta_e_2000(ref, composite_coverage(s, bg, a, o))

            # drift_breaks(d, limit) is d > drift_ceiling(limit), i.e. -d < -ceiling.
            _, unsafe = first_below(minus_drift, grid, -drift_ceiling(limit))
            start[r] = unsafe
        return self._collect(rule, start, np.isfinite(start))

    def _collect(
        self, rule: Rule, start: NDArray[np.float64], attained: NDArray[np.bool_]
    ) -> list[Found]:
        out: list[Found] = []
        for p, j in zip(*np.nonzero(np.isfinite(start)), strict=True):
            icon = int(self.icon[p])
            if not self.exempt(rule, self.canvases[j], (self.names[icon],)):
                out.append((rule, int(j), (icon,), float(start[p, j]), bool(attained[p, j])))
        return out

    # -- one question ----------------------------------------------------------

    def limits(
        self,
        moving_icons: NDArray[np.bool_],
        tracks: PaintScenario,
        cap: float | NDArray[np.float64],
        *,
        shrink: bool = False,
    ) -> list[Found]:
        """Every paint-rule limit of one question up to ``cap`` (per canvas, or one for all).

        Nothing beyond a canvas's cap can be its first limit.  With ``shrink``
        only the question's earliest limit matters (not each canvas's), so a
        limit found on one canvas caps the search on the next.
        """
        if self.pipeline == "css":
            # CSS cannot draw alpha above 1 (a_hi is 1): the question is alpha 1 itself.
            first = self.first_objection(moving_icons, tracks, ALPHA_LO)
            return [] if first is None else [first]
        found: list[Found] = []
        for rule, icons in self.static:
            if any(moving_icons[i] for i in icons):
                found.append((rule, -1, icons, ALPHA_LO, True))  # -1: on every canvas
        found += [f for f in self.per_paint() if moving_icons[f[2][0]]]
        caps = np.broadcast_to(np.asarray(cap, dtype=np.float64), (len(self.canvases),)).copy()
        for _, j, _, at, _ in found:
            if j < 0 or shrink:
                caps[:] = np.minimum(caps, at)
            else:
                caps[j] = min(caps[j], at)
        if np.all(caps <= ALPHA_LO):
            return found
        rules = self.policy.rules
        if Rule.CONFUSION in rules:
            found += self._confusion(tracks, caps, None, shrink)
        if Rule.CVD_CONFUSION in rules:
            for deficiency in DEFICIENCIES:
                found += self._confusion(tracks, caps, deficiency, shrink)
        if Rule.CVD_COLLISION in rules:
            found += self._cvd_collision(tracks, float(caps.max()))
        return found

    def _track_roles(self, tracks: PaintScenario) -> tuple[NDArray[np.bool_], NDArray[np.intp]]:
        """Which tracks take part in role rules, and a label per track (equal: never a pair).

        A track's icons share a source; when they hold one role, pairs within
        that role are skipped; a track of several roles pairs with everyone.
        """
        part = np.array([any(self.in_roles[i] for i in t) for t in tracks.icons], dtype=bool)
        labels: dict[object, int] = {}
        out = []
        for k, t in enumerate(tracks.icons):
            roles = {self.roles[i] for i in t if self.in_roles[i]}
            key: object = next(iter(roles)) if len(roles) == 1 else ("track", k)
            out.append(labels.setdefault(key, len(labels)))
        return part.reshape(-1), np.array(out, dtype=np.intp).reshape(-1)

    def _shown(
        self, tracks: PaintScenario, t: NDArray[np.intp], a: NDArray[np.float64], j: int
    ) -> NDArray[np.float64]:
        """Tracks ``t`` on canvas ``j`` at coefficients ``a`` (moving) as (len(t), N, 3)."""
        coef = np.where(tracks.moving[t][:, np.newaxis], a, tracks.alpha[t][:, np.newaxis])
        source = tracks.source[t][:, np.newaxis, :]
        if self.pipeline == "css":
            return composite_paint(source, self.backgrounds[j], coef, 1.0, "css")
        return composite_extended(source, self.backgrounds[j], coef)

    def _at(
        self, tracks: PaintScenario, t: NDArray[np.intp], a: NDArray[np.float64], j: int
    ) -> NDArray[np.float64]:
        """Track ``t[k]`` at coefficient ``a[k]`` on canvas ``j``, elementwise: (K, 3)."""
        coef = np.where(tracks.moving[t], a, tracks.alpha[t])
        source = tracks.source[t]
        if self.pipeline == "css":
            return composite_paint(source, self.backgrounds[j], coef, 1.0, "css")
        return composite_extended(source, self.backgrounds[j], coef)

    def _confusion(
        self,
        tracks: PaintScenario,
        caps: NDArray[np.float64],
        deficiency: str | None,
        shrink: bool,
    ) -> list[Found]:
        rule = Rule.CONFUSION if deficiency is None else Rule.CVD_CONFUSION
        part, labels = self._track_roles(tracks)
        idx = np.flatnonzero(part)
        if idx.size < 2 or not tracks.moving[idx].any():
            return []
        level = self.policy.min_delta_e
        breaks = clip_breakpoints(
            tracks.source[idx][:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        full = _grid(ALPHA_LO, float(caps.max()), breaks)

        def view(c: NDArray[np.float64]) -> NDArray[np.float64]:
            return c if deficiency is None else simulate_cvd(c, deficiency)  # type: ignore[arg-type]  # a name from DEFICIENCIES

        out: list[Found] = []
        for j in range(len(self.canvases)):
            if caps[j] <= ALPHA_LO:
                continue
            grid = full[full <= caps[j]]
            chunk = max(1, _CHUNK // grid.size)
            # The rule's reference is every role at alpha 1, as the gate has it
            # (paint_audit._confusion), not the others at their configured alpha: a
            # pair the others already confuse is this colour's problem too.
            solid = composite_paint(
                tracks.source[idx], self.backgrounds[j], 1.0, 1.0, self.pipeline
            )
            lab_ref = linear_to_lab(view(solid))  # (T', 3)
            lightness = linear_to_lab(view(self._shown(tracks, idx, grid, j)))[..., 0]
            s_l = lightness_weight_max(lightness)
            for first, second in iter_pairs(idx.size, labels[idx], chunk=chunk):
                moved = tracks.moving[idx[first]] | tracks.moving[idx[second]]
                first, second = first[moved], second[moved]
                keep = confusion_possible(delta_e_2000_lab(lab_ref[first], lab_ref[second]), level)
                first, second = first[keep], second[keep]
                if first.size == 0:
                    continue
                # dE00 >= |dL| / S_L,max (alpha_audit.color.nearest): far pairs never drop.
                # Grid points where the bound cannot rule the pair out: only these
                # are evaluated; elsewhere the distance is provably >= the level.
                close = np.abs(lightness[first] - lightness[second]) / s_l < level * (1 + 1e-9)
                near = close.any(axis=1)
                first, second, close = first[near], second[near], close[near]
                if first.size == 0:
                    continue

                def delta_e(
                    a: NDArray[np.float64],
                    f: NDArray[np.intp] = idx[first],
                    g: NDArray[np.intp] = idx[second],
                    j: int = j,
                    close: NDArray[np.bool_] = close,
                ) -> NDArray[np.float64]:
                    if a.ndim > 1:  # bisecting: (pairs, 1), every pair at its own point
                        shown_f = view(self._shown(tracks, f, a, j))
                        return delta_e_2000(shown_f, view(self._shown(tracks, g, a, j)))
                    out = np.full(close.shape, np.inf)
                    p, n = np.nonzero(close)
                    out[p, n] = delta_e_2000(
                        view(self._at(tracks, f[p], a[n], j)), view(self._at(tracks, g[p], a[n], j))
                    )
                    return out

                _, unsafe = first_below(delta_e, grid, level)
                for p in np.flatnonzero(np.isfinite(unsafe)):
                    icons = tuple(
                        sorted({*tracks.icons[idx[first[p]]], *tracks.icons[idx[second[p]]]})
                    )
                    names = tuple(self.names[i] for i in icons)
                    if not self.exempt(rule, self.canvases[j], names):
                        out.append((rule, j, icons, float(unsafe[p]), True))
                        if shrink:
                            caps = np.minimum(caps, float(unsafe[p]))
        return out

    def _cvd_collision(self, tracks: PaintScenario, cap: float) -> list[Found]:
        part, _ = self._track_roles(tracks)
        idx = np.flatnonzero(part)
        if idx.size < 2 or not tracks.moving[idx].any():
            return []
        sources = [tracks.source[t].tobytes().hex() for t in idx]
        breaks = clip_breakpoints(
            tracks.source[idx][:, np.newaxis, :], self.backgrounds[np.newaxis]
        ).reshape(-1)
        grid = _grid(ALPHA_LO, cap, breaks)
        one = np.array([ALPHA_LO])
        out: list[Found] = []
        for deficiency in DEFICIENCIES:
            for j in range(len(self.canvases)):
                ref = to_8bit(simulate_cvd(self._shown(tracks, idx, one, j)[:, 0], deficiency))

                def unsafe(
                    a: float, j: int = j, ref: NDArray[np.uint8] = ref, d: Deficiency = deficiency
                ) -> tuple[int, ...] | None:
                    seen = to_8bit(
                        simulate_cvd(self._shown(tracks, idx, np.array([a]), j)[:, 0], d)
                    )
                    for _, members in cvd_collision_groups(seen, ref, sources):
                        if not any(tracks.moving[idx[r]] for r in members):
                            continue
                        icons = tuple(sorted(i for r in members for i in tracks.icons[idx[r]]))
                        if not self.exempt(
                            Rule.CVD_COLLISION,
                            self.canvases[j],
                            tuple(self.names[i] for i in icons),
                        ):
                            return icons
                    return None

                codes = to_8bit(simulate_cvd(self._shown(tracks, idx, grid, j), deficiency))
                packed = (codes[..., 0] << 16) | (codes[..., 1] << 8) | codes[..., 2]  # (T', N)
                ordered = np.sort(packed, axis=0)
                shared = np.flatnonzero((ordered[1:] == ordered[:-1]).any(axis=0))
                for n in shared.tolist():
                    icons = unsafe(float(grid[n]))
                    if icons is None:
                        continue
                    lo, hi = (float(grid[n - 1]), float(grid[n])) if n > 0 else (ALPHA_LO, ALPHA_LO)
                    while hi - lo > 1e-9:
                        mid = 0.5 * (lo + hi)
                        if unsafe(mid) is None:
                            lo = mid
                        else:
                            hi = mid
                    out.append((Rule.CVD_COLLISION, j, icons, hi, True))
                    break
        return out

    # -- direct check of one coefficient ----------------------------------------

    def first_objection(
        self, moving_icons: NDArray[np.bool_], tracks: PaintScenario, a: float
    ) -> Found | None:
        """A paint rule's objection at exactly ``a`` (the re-check of a rounded answer)."""
        for rule, icons in self.static:
            if any(moving_icons[i] for i in icons):
                return (rule, -1, icons, a, True)
        rows = np.flatnonzero(moving_icons[self.icon])
        bg = self.backgrounds[np.newaxis]
        if rows.size:
            s = self.source[rows][:, np.newaxis, :]
            o = self.opacity[rows][:, np.newaxis]
            shown = composite_paint(s, bg, a, o, self.pipeline)
            ref = composite_paint(s, bg, 1.0, o, self.pipeline)
            c_ref, c_now = contrast_ratio(ref, bg), contrast_ratio(shown, bg)
            checks: list[tuple[Rule, NDArray[np.bool_]]] = [
                (rule, c_now < contrast_floor(rule, self.policy, c_ref, self.threshold))
                for rule in self.policy.contrast_rules
            ]
            rules = self.policy.rules
            if Rule.DRIFT in rules or Rule.LOCK in rules:
                d = delta_e_2000(ref, shown)
                if Rule.DRIFT in rules:
                    checks.append((Rule.DRIFT, drift_breaks(d, self.policy.max_drift)))
                if Rule.LOCK in rules:
                    lock = drift_breaks(d, LOCK_TOLERANCE) & self.locked[rows][:, np.newaxis]
                    checks.append((Rule.LOCK, lock))
            if Rule.THIN_STROKES in rules and self.sizes:
                limit = self.policy.min_size_contrast or self.threshold
                q = (self.q50[rows] * self.opacity[rows][:, np.newaxis])[:, np.newaxis, :]
                at = composite_paint(s[:, :, None], bg[..., None, :], a, q, self.pipeline)
                sc = contrast_ratio(at, bg[..., np.newaxis, :])
                checks.append(
                    (Rule.THIN_STROKES, np.asarray((sc < size_contrast_floor(limit)).any(axis=2)))
                )
            for rule, broken in checks:
                for r, j in zip(*np.nonzero(broken), strict=True):
                    icon = int(self.icon[rows[r]])
                    if not self.exempt(rule, self.canvases[j], (self.names[icon],)):
                        return (rule, int(j), (icon,), a, True)
        found = None
        if Rule.CONFUSION in self.policy.rules:
            found = self._confused_at(tracks, a, None)
        for deficiency in DEFICIENCIES if Rule.CVD_CONFUSION in self.policy.rules else ():
            found = found or self._confused_at(tracks, a, deficiency)
        if Rule.CVD_COLLISION in self.policy.rules:
            found = found or self._cvd_collides_at(tracks, a)
        return found

    def _confused_at(self, tracks: PaintScenario, a: float, deficiency: str | None) -> Found | None:
        """Direct check at ``a``: the pruned pair search below ``min_delta_e``, then the rule."""
        rule = Rule.CONFUSION if deficiency is None else Rule.CVD_CONFUSION
        part, labels = self._track_roles(tracks)
        idx = np.flatnonzero(part)
        if idx.size < 2 or not tracks.moving[idx].any():
            return None
        level = self.policy.min_delta_e

        def view(c: NDArray[np.float64]) -> NDArray[np.float64]:
            return c if deficiency is None else simulate_cvd(c, deficiency)  # type: ignore[arg-type]  # a name from DEFICIENCIES

        for j in range(len(self.canvases)):
            lab = linear_to_lab(view(self._shown(tracks, idx, np.array([a]), j)[:, 0]))
            lab_ref = linear_to_lab(view(self._shown(tracks, idx, np.array([ALPHA_LO]), j)[:, 0]))

            def distance(
                f: NDArray[np.intp], g: NDArray[np.intp], lab: NDArray[np.float64] = lab
            ) -> NDArray[np.float64]:
                return delta_e_2000_lab(lab[f], lab[g])

            mv = np.flatnonzero(tracks.moving[idx])
            if mv.size * idx.size <= _CHUNK:
                # Few moving tracks (per colour, per icon): only their pairs can object.
                grid_f, grid_g = np.meshgrid(mv, np.arange(idx.size), indexing="ij")
                f, g = grid_f.reshape(-1), grid_g.reshape(-1)
                lo, hi = np.minimum(f, g), np.maximum(f, g)
                pairs = np.unique(np.stack([lo, hi], axis=1)[lo != hi], axis=0).reshape(-1, 2)
                lo, hi = pairs[:, 0], pairs[:, 1]
                lo, hi = (
                    lo[labels[idx][lo] != labels[idx][hi]],
                    hi[labels[idx][lo] != labels[idx][hi]],
                )
                below = distance(lo, hi) < level
                first, second = lo[below], hi[below]
            else:
                key = delta_e_2000_lightness_key(lab)
                first, second, _ = pairs_below(key, distance, level, labels[idx])
            keep = confusion_possible(delta_e_2000_lab(lab_ref[first], lab_ref[second]), level)
            keep &= tracks.moving[idx[first]] | tracks.moving[idx[second]]
            for f, g in zip(first[keep].tolist(), second[keep].tolist(), strict=True):
                icons = tuple(sorted({*tracks.icons[idx[f]], *tracks.icons[idx[g]]}))
                if not self.exempt(rule, self.canvases[j], icon_names(self.names, icons)):
                    return (rule, j, icons, a, True)
        return None

    def _cvd_collides_at(self, tracks: PaintScenario, a: float) -> Found | None:
        part, _ = self._track_roles(tracks)
        idx = np.flatnonzero(part)
        if idx.size < 2 or not tracks.moving[idx].any():
            return None
        sources = [tracks.source[t].tobytes().hex() for t in idx]
        for deficiency in DEFICIENCIES:
            for j in range(len(self.canvases)):
                shown = self._shown(tracks, idx, np.array([a, ALPHA_LO]), j)
                seen = to_8bit(simulate_cvd(shown[:, 0], deficiency))
                ref = to_8bit(simulate_cvd(shown[:, 1], deficiency))
                for _, members in cvd_collision_groups(seen, ref, sources):
                    if not any(tracks.moving[idx[r]] for r in members):
                        continue
                    icons = tuple(i for r in members for i in tracks.icons[idx[r]])
                    names = icon_names(self.names, icons)
                    if not self.exempt(Rule.CVD_COLLISION, self.canvases[j], names):
                        return (Rule.CVD_COLLISION, j, tuple(sorted(icons)), a, True)
        return None


def icon_names(names: Sequence[str], icons: tuple[int, ...]) -> tuple[str, ...]:
    """Icon indices as sorted names."""
    return tuple(sorted(names[i] for i in icons))
