"""What every suggest question of one audit reads: canvases, paints grouped into tracks.

A *track* is what one group of rows shows: the rows of one paint when they
move with the coefficient being chosen, the rows of one paint at one alpha
when they stay.  The per-row limits (:mod:`~alpha_audit.suggest.per_row`),
the 8-bit collisions (:mod:`~alpha_audit.suggest.collisions`) and the pair
rules (:mod:`~alpha_audit.suggest.pairs`) all read a :class:`Scene`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import composite_paint, relative_luminance, shipped
from alpha_audit.findings import findings_for, locked_rows
from alpha_audit.policy import Policy
from alpha_audit.rows import AuditResult
from alpha_audit.rules import RULES, Family, Rule
from alpha_audit.suggest.events import Floats, Indices, clip_breakpoints

# The bracketing grid for rules without a closed form in alpha; a dip below a
# limit narrower than this can be missed (the answer is re-checked directly).
GRID_STEP = 1e-3
# Item x grid-point evaluations held at once (~8 MB per float64 intermediate).
CHUNK = 1 << 20
ALPHA_LO = 1.0  # the reference coefficient; the safe interval starts here


class Found(NamedTuple):
    """A limit found: a rule broken on a canvas (-1: every canvas) by some icons."""

    rule: Rule
    canvas: int
    icons: tuple[int, ...]
    at: float  # the first unsafe alpha
    attained: bool
    roles: tuple[str, ...] = ()  # the two roles of a role rule (confusion, cvd-confusion)


class TrackIcons:
    """Each track's icon indices, built when asked for (most tracks never are)."""

    def __init__(self, icons: Indices, bounds: Indices) -> None:
        self._icons, self._bounds = icons, bounds  # track t: icons[bounds[t]:bounds[t + 1]]

    def __getitem__(self, t: int | np.integer[Any]) -> tuple[int, ...]:
        return tuple(self._icons[self._bounds[t] : self._bounds[t + 1]].tolist())

    def __len__(self) -> int:
        return len(self._bounds) - 1


@dataclass(frozen=True)
class Tracks:
    """Rows grouped by what they show: moving ones by paint, fixed ones by (paint, alpha)."""

    source: Floats  # (T, 3) linear
    opacity: Floats  # (T,)
    alpha: Floats  # (T,) nan when moving
    moving: NDArray[np.bool_]  # (T,)
    label: Indices  # (T,) equal labels are never a pair (one paint, or one role)
    icons: TrackIcons  # icon indices per track
    first: Indices  # (T,) each track's first row: what it shows is that row's
    row_track: Indices  # (rows,) each row's track, -1 for a row not chosen


def alpha_grid(a_lo: float, a_hi: float, breaks: Floats) -> Floats:
    steps = max(1, math.ceil((a_hi - a_lo) / GRID_STEP))
    inner = breaks[(breaks > a_lo) & (breaks < a_hi)]
    return np.unique(np.concatenate([np.linspace(a_lo, a_hi, steps + 1), inner]))


class Scene:
    """What every question of one audit reads: its canvases, paints, roles and exemptions."""

    def __init__(self, result: AuditResult, policy: Policy, alpha_max: float) -> None:
        r = result
        self.result, self.policy = r, policy
        self.threshold = r.threshold
        self.pipeline = r.pipeline
        # CSS opacity cannot exceed 1 (CSS Color 4 clamps alpha): the only
        # coefficient above the reference is none, so the question is alpha 1.
        self.a_hi = ALPHA_LO if r.pipeline == "css" else float(alpha_max)
        self.names = tuple(i.name for i in r.iconset.icons)
        index = {name: n for n, name in enumerate(self.names)}
        self.row_icon = np.array([index[e.icon.name] for e in r.entries], dtype=np.intp)
        self.canvases = tuple(c.name for c in r.theme.canvases)
        self.backgrounds = r.theme.backgrounds
        self.y_bg = relative_luminance(self.backgrounds)
        self.y_screen = relative_luminance(shipped(self.backgrounds))  # the canvas as shipped
        self.keys = r.paint_keys
        self.locked = locked_rows(r)
        rules = policy.rules
        # What an SVG draws objects whatever the alpha (an unrenderable icon is in no row).
        static = {r for r in rules if RULES[r].family is Family.SVG}
        self.static: list[tuple[Rule, tuple[int, ...]]] = []
        if static:
            only = Policy(
                rules=frozenset(static), warnings=frozenset(), exemptions=policy.exemptions
            )
            for f in findings_for(r, only):
                if f.exemption is None:
                    self.static.append((f.rule, tuple(index[i] for i in f.icons if i in index)))
        # Palette roles: currentColor paints of named colours, compared as solid colours.
        roles = [e.role for e in r.entries]
        self.role_row = np.array(
            [not e.fixed and e.icon.color_name is not None for e in r.entries], dtype=bool
        ).reshape(-1)
        names, label = np.unique(np.array(roles or [""], dtype=object), return_inverse=True)
        self.role_names = tuple(str(n) for n in names.tolist())
        self.role_label = label.reshape(-1)[: len(roles)]
        # The colours suggest and the fixes name: a palette name, else the colour itself.
        self.colour_of = tuple(i.color_name or i.color for i in r.iconset.icons)
        self.colours = tuple(dict.fromkeys([*r.iconset.palette, *self.colour_of]))
        self._last_tracks: dict[bool, tuple[bytes, Tracks]] = {}
        self._group_ids: dict[bool, tuple[Indices, ...]] = {}

    def exempt(self, rule: Rule, j: int, icons: Iterable[int]) -> tuple[int, ...] | None:
        """``icons`` sorted, or ``None`` when an exemption of ``rule`` on canvas ``j`` holds."""
        found = tuple(sorted(set(icons)))
        names = tuple(sorted(self.names[i] for i in found))
        return None if self.policy.exempt(rule, self.canvases[j], names) is not None else found

    def breaks(self, sources: Floats) -> Floats:
        """Every coefficient where a channel of ``sources`` (n, 3) clips on some canvas."""
        return clip_breakpoints(sources[:, np.newaxis, :], self.backgrounds[np.newaxis]).reshape(-1)

    def icon_names(self, icons: Iterable[int]) -> tuple[str, ...]:
        return tuple(sorted({self.names[i] for i in icons}))

    def role_pair(self, roles: Tracks, f: int, g: int) -> tuple[str, str]:
        """The names of the roles of role tracks ``f`` and ``g``, sorted."""
        one, two = (self.role_names[int(roles.label[t])] for t in (f, g))
        return (one, two) if one <= two else (two, one)

    def tracks(self, moving_icons: NDArray[np.bool_], roles: bool = False) -> Tracks:
        """Rows grouped: moving rows by paint, fixed rows by (paint, alpha); moving first.

        With ``roles``, the roles' rows for the role rules, grouped by role as
        well, drawn solid.  A question asks for the same grouping again when it
        re-checks its answer, so the last one of each kind is kept.
        """
        key = moving_icons.tobytes()
        kept = self._last_tracks.get(roles)
        if kept is None or kept[0] != key:
            kept = (key, self._group(moving_icons, roles))
            self._last_tracks[roles] = kept
        return kept[1]

    def _ids(self, roles: bool) -> tuple[Indices, ...]:
        """The chosen rows and, per row, its (role, paint) and (role, paint, alpha) group ids.

        The same for every question (only which rows move changes), so computed once.
        """
        found = self._group_ids.get(roles)
        if found is None:
            r = self.result
            chosen = np.flatnonzero(self.role_row) if roles else np.arange(len(r.entries))
            role = self.role_label[chosen] if roles else np.full(chosen.size, -1)
            columns = np.stack([role, self.keys[chosen]]).astype(np.float64)
            by_paint = np.unique(columns.T, axis=0, return_inverse=True)[1].reshape(-1)
            with_alpha = np.vstack([columns, r.alpha[chosen]]).T
            by_alpha = np.unique(with_alpha, axis=0, return_inverse=True)[1].reshape(-1)
            found = (chosen, by_paint, by_alpha)
            self._group_ids[roles] = found
        return found

    def _group(self, moving_icons: NDArray[np.bool_], roles: bool) -> Tracks:
        r = self.result
        chosen, by_paint, by_alpha = self._ids(roles)
        moving = moving_icons[self.row_icon[chosen]]
        role = self.role_label[chosen] if roles else np.full(chosen.size, -1)
        alpha = np.where(moving, -math.inf, r.alpha[chosen])
        # One group per moving (role, paint) and per fixed (role, paint, alpha); ``first``
        # is each group's first row in order.
        ids = np.where(moving, by_paint, by_paint.size + by_alpha)
        _, first_at, group = np.unique(ids, return_index=True, return_inverse=True)
        group = group.reshape(-1)
        is_moving = moving[first_at]
        order = np.lexsort((first_at, ~is_moving))  # moving groups first, then by first row
        rank = np.empty_like(order)
        rank[order] = np.arange(order.size)
        track = rank[group]  # each chosen row's track
        first = chosen[first_at[order]]
        row_track = np.full(len(r.entries), -1, dtype=np.intp)
        row_track[chosen] = track
        n_icons = len(self.names)
        pairs = np.unique(track * n_icons + self.row_icon[chosen])  # sorted (track, icon)
        bounds = np.searchsorted(pairs // n_icons, np.arange(order.size + 1))
        return Tracks(
            source=r.sources[first].reshape(-1, 3),
            opacity=np.ones(first.size) if roles else r.opacity[first],
            alpha=np.where(is_moving[order], math.nan, alpha[first_at[order]]),
            moving=is_moving[order],
            label=(role if roles else self.keys[chosen])[first_at[order]].astype(np.intp),
            icons=TrackIcons(pairs % n_icons, bounds),
            first=first,
            row_track=row_track,
        )

    def shown(self, tracks: Tracks, t: Indices, a: Floats, j: int) -> Floats:
        """What tracks ``t`` ship on canvas ``j`` at coefficients ``a`` (moving), (len(t), N, 3)."""
        return self.shown_at(tracks, t[:, np.newaxis], a, j)

    def shown_at(self, tracks: Tracks, t: Indices, a: Floats, j: int) -> Floats:
        """What track ``t[k]`` ships at coefficient ``a[k]`` on canvas ``j`` (broadcast): (K, 3)."""
        coef = np.where(tracks.moving[t], a, tracks.alpha[t])
        return self.ship(tracks.source[t], self.backgrounds[j], coef, tracks.opacity[t])

    def ship(
        self,
        source: Floats,
        background: Floats,
        alpha: Floats | float,
        opacity: Floats | float,
    ) -> Floats:
        """The 8-bit colour a paint ships at ``alpha`` (what the gate judges), as linear light."""
        return shipped(composite_paint(source, background, alpha, opacity, self.pipeline))

    # -- per row: independent of every other icon, computed once ----------------
