"""Pair rules, bracketed: separation, confusion, cvd-confusion and cvd-collision.

CIEDE2000 and the CVD simulation have no closed form in the coefficient, so
each pair's first unsafe alpha is bracketed on a grid of
:data:`~alpha_audit.suggest.scene.GRID_STEP` (plus every clip breakpoint) and
bisected; pairs the lightness bound of :mod:`alpha_audit.color.nearest` keeps
apart are never evaluated.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    DEFICIENCIES,
    Deficiency,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_lab,
    pack_8bit,
    simulate_cvd,
    to_8bit,
)
from alpha_audit.color.nearest import (
    delta_e_2000_lightness_key,
    iter_pairs,
    lightness_weight_max,
    pairs_below,
)
from alpha_audit.findings import cvd_collision_groups
from alpha_audit.policy import confusion_possible
from alpha_audit.rules import Rule
from alpha_audit.suggest.events import Floats, Indices, first_below
from alpha_audit.suggest.scene import ALPHA_LO, CHUNK, Found, Scene, Tracks, alpha_grid


def separation_limits(scene: Scene, tracks: Tracks, caps: Floats) -> list[Found]:
    """Per canvas, where CIEDE2000 between two paints first drops below the minimum."""
    if Rule.SEPARATION not in scene.policy.rules or len(tracks.label) < 2:
        return []
    if not tracks.moving.any():
        return []
    breaks = scene.breaks(tracks.source[tracks.moving])
    return _pair_limits(
        scene, tracks, Rule.SEPARATION, caps, lambda cap: alpha_grid(ALPHA_LO, cap, breaks)
    )


def confusion_limits(
    scene: Scene, roles: Tracks, caps: Floats, deficiency: Deficiency | None, shrink: bool
) -> list[Found]:
    """Per canvas, where two roles told apart at alpha 1 first drop below the minimum."""
    rule = Rule.CONFUSION if deficiency is None else Rule.CVD_CONFUSION
    if len(roles.label) < 2 or not roles.moving.any():
        return []
    full = alpha_grid(ALPHA_LO, float(caps.max()), scene.breaks(roles.source))
    return _pair_limits(
        scene, roles, rule, caps, lambda cap: full[full <= cap], _viewer(deficiency), shrink
    )


def _pair_limits(
    scene: Scene,
    tracks: Tracks,
    rule: Rule,
    caps: Floats,
    grid_to: Callable[[float], Floats],
    view: Callable[[Floats], Floats] = lambda c: c,
    shrink: bool = False,
) -> list[Found]:
    """Per canvas, where two tracks first drop below the minimum CIEDE2000 (as ``view`` sees
    them) on ``grid_to(cap)``; with ``shrink``, each limit found caps the canvases after it.

    Canvas by canvas and a chunk of pairs at a time (bounded memory for any
    number of colours).  Only the grid points where the lightness bound
    (``dE00 >= |dL| / S_L,max``) cannot keep a pair at or above the minimum are
    evaluated; elsewhere the distance is at least the minimum.  A role rule
    (confusion) judges only the pairs told apart at alpha 1, as the gate does.
    """
    level = scene.policy.min_delta_e
    every = np.arange(len(tracks.label))
    out: list[Found] = []
    for j in range(len(scene.canvases)):
        if caps[j] <= ALPHA_LO:
            continue
        grid = grid_to(float(caps[j]))
        chunk = max(1, CHUNK // grid.size)
        # The rule's reference is every role at alpha 1, as the gate has it, not the
        # others at their configured alpha: a pair the others confuse is this one's too.
        lab_ref = None
        if rule is not Rule.SEPARATION:
            solid = scene.ship(tracks.source, scene.backgrounds[j], 1.0, 1.0)
            lab_ref = linear_to_lab(view(solid))
        lightness = linear_to_lab(view(scene.shown(tracks, every, grid, j)))[..., 0]
        s_l = lightness_weight_max(lightness)
        for first, second in iter_pairs(len(tracks.label), tracks.label, chunk=chunk):
            moved = tracks.moving[first] | tracks.moving[second]
            first, second = first[moved], second[moved]
            if lab_ref is not None:
                keep = confusion_possible(delta_e_2000_lab(lab_ref[first], lab_ref[second]), level)
                first, second = first[keep], second[keep]
            close = np.abs(lightness[first] - lightness[second]) / s_l < level * (1 + 1e-9)
            near = close.any(axis=1)
            first, second, close = first[near], second[near], close[near]
            if first.size == 0:
                continue

            def delta_e(
                a: Floats,
                f: Indices = first,
                g: Indices = second,
                j: int = j,
                close: NDArray[np.bool_] = close,
            ) -> Floats:
                if a.ndim > 1:  # bisecting: every pair at its own points
                    ff, gg = np.repeat(f, a.shape[1]), np.repeat(g, a.shape[1])
                    fa = view(scene.shown_at(tracks, ff, a.reshape(-1), j))
                    ga = view(scene.shown_at(tracks, gg, a.reshape(-1), j))
                    return delta_e_2000(fa, ga).reshape(a.shape)
                values = np.full(close.shape, np.inf)
                p, k = np.nonzero(close)
                values[p, k] = delta_e_2000(
                    view(scene.shown_at(tracks, f[p], a[k], j)),
                    view(scene.shown_at(tracks, g[p], a[k], j)),
                )
                return values

            _, unsafe = first_below(delta_e, grid, level)
            for p in np.flatnonzero(np.isfinite(unsafe)).tolist():
                icons = scene.exempt(rule, j, [*tracks.icons[first[p]], *tracks.icons[second[p]]])
                if icons is not None:
                    pair = () if lab_ref is None else scene.role_pair(tracks, first[p], second[p])
                    out.append(Found(rule, j, icons, float(unsafe[p]), True, pair))
                    if shrink:
                        caps = np.minimum(caps, float(unsafe[p]))
    return out


def cvd_collision_limits(scene: Scene, roles: Tracks, cap: float) -> list[Found]:
    n = len(roles.label)
    if n < 2 or not roles.moving.any():
        return []
    sources = _sources(roles)
    grid = alpha_grid(ALPHA_LO, cap, scene.breaks(roles.source))
    every = np.arange(n)
    out: list[Found] = []
    for deficiency in DEFICIENCIES:
        for j in range(len(scene.canvases)):
            ref = to_8bit(
                simulate_cvd(scene.shown(roles, every, np.array([ALPHA_LO]), j)[:, 0], deficiency)
            )

            def unsafe(
                a: float, j: int = j, ref: NDArray[np.uint8] = ref, d: Deficiency = deficiency
            ) -> tuple[int, ...] | None:
                seen = to_8bit(simulate_cvd(scene.shown(roles, every, np.array([a]), j)[:, 0], d))
                return _cvd_group(scene, roles, seen, ref, sources, j)

            codes = to_8bit(simulate_cvd(scene.shown(roles, every, grid, j), deficiency))
            packed = pack_8bit(codes)  # (T, N)
            ordered = np.sort(packed, axis=0)
            shared = np.flatnonzero((ordered[1:] == ordered[:-1]).any(axis=0))
            for k in shared.tolist():
                icons = unsafe(float(grid[k]))
                if icons is None:
                    continue
                lo, hi = (float(grid[k - 1]), float(grid[k])) if k > 0 else (ALPHA_LO, ALPHA_LO)
                while hi - lo > 1e-9:
                    mid = 0.5 * (lo + hi)
                    if unsafe(mid) is None:
                        lo = mid
                    else:
                        hi = mid
                out.append(Found(Rule.CVD_COLLISION, j, icons, hi, True))
                break
    return out


def _cvd_group(
    scene: Scene,
    roles: Tracks,
    seen: NDArray[np.uint8],
    ref: NDArray[np.uint8],
    sources: Sequence[str],
    j: int,
) -> tuple[int, ...] | None:
    for _, members in cvd_collision_groups(seen, ref, sources):
        if not any(roles.moving[m] for m in members):
            continue
        icons = scene.exempt(Rule.CVD_COLLISION, j, [i for m in members for i in roles.icons[m]])
        if icons is not None:
            return icons
    return None


def pairs_below_at(
    scene: Scene, tracks: Tracks, a: float, deficiency: Deficiency | None, rule: Rule
) -> Found | None:
    """A pair involving a moving track below ``min_delta_e`` at ``a`` (confusion: and
    told apart at alpha 1), found by the pruned pair search."""
    n = len(tracks.label)
    if n < 2 or not tracks.moving.any():
        return None
    level = scene.policy.min_delta_e
    every = np.arange(n)
    view = _viewer(deficiency)
    for j in range(len(scene.canvases)):
        both = scene.shown(tracks, every, np.array([a, ALPHA_LO]), j)
        lab = linear_to_lab(view(both[:, 0]))

        def distance(f: Indices, g: Indices, lab: Floats = lab) -> Floats:
            return delta_e_2000_lab(lab[f], lab[g])

        first, second, _ = pairs_below(
            delta_e_2000_lightness_key(lab), distance, level, tracks.label
        )
        keep = tracks.moving[first] | tracks.moving[second]
        if rule is not Rule.SEPARATION:
            solid = scene.ship(tracks.source, scene.backgrounds[j], 1.0, 1.0)
            lab_ref = linear_to_lab(view(solid))
            keep &= confusion_possible(delta_e_2000_lab(lab_ref[first], lab_ref[second]), level)
        for f, g in zip(first[keep].tolist(), second[keep].tolist(), strict=True):
            icons = scene.exempt(rule, j, [*tracks.icons[f], *tracks.icons[g]])
            if icons is not None:
                pair = () if rule is Rule.SEPARATION else scene.role_pair(tracks, f, g)
                return Found(rule, j, icons, a, True, pair)
    return None


# -- one question ------------------------------------------------------------


def pair_objection(scene: Scene, moving_icons: NDArray[np.bool_], a: float) -> Found | None:
    """A pair rule broken at exactly ``a`` by a moving icon (an answer's re-check)."""
    rules = scene.policy.rules
    roles = scene.tracks(moving_icons, roles=True)
    checks: list[tuple[Rule, Deficiency | None]] = [(Rule.SEPARATION, None), (Rule.CONFUSION, None)]
    checks += [(Rule.CVD_CONFUSION, d) for d in DEFICIENCIES]
    for rule, deficiency in checks:
        if rule in rules:
            tracks = scene.tracks(moving_icons) if rule is Rule.SEPARATION else roles
            found = pairs_below_at(scene, tracks, a, deficiency, rule)
            if found is not None:
                return found
    if Rule.CVD_COLLISION in rules and len(roles.label) > 1 and roles.moving.any():
        sources = _sources(roles)
        every = np.arange(len(roles.label))
        for deficiency in DEFICIENCIES:
            for j in range(len(scene.canvases)):
                shown = scene.shown(roles, every, np.array([a, ALPHA_LO]), j)
                seen = to_8bit(simulate_cvd(shown[:, 0], deficiency))
                ref = to_8bit(simulate_cvd(shown[:, 1], deficiency))
                cvd = _cvd_group(scene, roles, seen, ref, sources, j)
                if cvd is not None:
                    return Found(Rule.CVD_COLLISION, j, cvd, a, True)
    return None


def _sources(roles: Tracks) -> list[str]:
    """Each role track's colour as a key (what :func:`cvd_collision_groups` compares)."""
    return [roles.source[t].tobytes().hex() for t in range(len(roles.label))]


def _viewer(deficiency: Deficiency | None) -> Callable[[Floats], Floats]:
    """How colours look to a viewer with ``deficiency`` (``None``: as they are)."""
    if deficiency is None:
        return lambda c: c
    return lambda c: simulate_cvd(c, deficiency)
