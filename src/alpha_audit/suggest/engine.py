"""The largest safe coefficient, exactly, over the audit's paint rows.

For a gate :class:`~alpha_audit.policy.Policy` ``P`` and an audit's rows the
largest safe alpha of a set of icons is

    a* = sup { a <= a_max : every a' in [1, a] satisfies P }

when those icons share the coefficient ``a'`` and every other icon keeps its
own; only objections involving a moved icon count (the others do not depend
on the coefficient being chosen).  The rows are the gate's: each paint of each
icon at its opacity under the audit's pipeline, so every rule means what
:mod:`alpha_audit.findings` means by it.

Exact, from events (:mod:`alpha_audit.suggest.events`):

* the contrast rules and ``thin-strokes`` per row: a paint's displayed
  luminance is ``o Y(clip(...)) + (1 - o) Yb`` (``q50 o`` at a size), so a
  contrast band on it is a luminance band on the clipped composite, piecewise
  linear in ``a``;
* 8-bit collisions: every track's codes are step functions of ``a`` known
  exactly (:func:`~alpha_audit.suggest.events.code_timelines`).

Bracketed on a grid of :data:`GRID_STEP` (plus every clip breakpoint), bisected
to :data:`~alpha_audit.suggest.events.BISECTION_TOLERANCE` and re-checked
(CIEDE2000 and the CVD simulation have no closed form in ``a``): separation,
drift and lock, confusion and cvd-confusion (pruned by the lightness bound of
:mod:`alpha_audit.color.nearest`), cvd-collision.  ``fixed-colour`` and
``not-audited`` do not depend on alpha: when one fails, not even 1 is safe.

The answer is ``a*`` rounded *down* to ``precision`` decimals and re-checked
there by direct compositing.  Under the ``css`` pipeline no coefficient above 1
can be drawn, so the question is alpha 1 itself.  Pure computation.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from decimal import ROUND_FLOOR, Decimal
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import DEFICIENCIES
from alpha_audit.errors import UsageError
from alpha_audit.figures import ConfusionFigures
from alpha_audit.findings import findings_for
from alpha_audit.policy import Policy
from alpha_audit.ranges import ALPHA_MAX, PRECISION
from alpha_audit.results import (
    CanvasLimit,
    ColorSuggestion,
    GroupSuggestion,
    IconSuggestion,
    Limit,
    Progress,
    SafeAlpha,
    SuggestResult,
)
from alpha_audit.rows import AuditResult
from alpha_audit.rules import RULES, Family, Rule
from alpha_audit.suggest.collisions import Collisions
from alpha_audit.suggest.pairs import (
    confusion_limits,
    cvd_collision_limits,
    pair_objection,
    separation_limits,
)
from alpha_audit.suggest.per_row import per_row_limits, row_objection
from alpha_audit.suggest.scene import ALPHA_LO, GRID_STEP, Found, Scene
from alpha_audit.suggest.scope import SCOPES

__all__ = [
    "GRID_STEP",
    "SafeAlphas",
    "confusion_groups",
    "connected",
    "largest_safe_alpha",
    "suggest",
]

_RULE_ORDER = {rule: k for k, rule in enumerate(Rule)}


def _round_down(value: float, precision: int) -> float:
    """``value`` rounded towards minus infinity to ``precision`` decimals, exactly."""
    step = Decimal(1).scaleb(-precision)
    return float(Decimal(repr(value)).quantize(step, rounding=ROUND_FLOOR))


class SafeAlphas(Scene):
    """Largest-safe-alpha questions on one audit, sharing their work (per-row limits, timelines).

    ``answers(icons)`` is :func:`largest_safe_alpha` for those icons (all when ``None``).
    """

    def __init__(
        self, result: AuditResult, policy: Policy, *, alpha_max: float = 2.0, precision: int = 3
    ) -> None:
        if not ALPHA_MAX.allows(alpha_max):
            raise UsageError(ALPHA_MAX.refusal(f"alpha_max {alpha_max:g}"))
        if (
            isinstance(precision, bool)
            or not isinstance(precision, int)
            or precision not in PRECISION
        ):
            raise UsageError(PRECISION.refusal(f"precision {precision!r}"))
        if not result.iconset.icons:
            why = "could be rendered" if result.problems else "is in it"
            raise UsageError(f"no icon of {result.iconset.name!r} {why}: nothing to suggest for")
        if not result.theme.canvases:
            raise UsageError(f"theme {result.theme.name!r} has no canvases")
        super().__init__(result, policy, alpha_max)
        self.precision = precision
        self.collisions = Collisions(self)
        self._answers: dict[tuple[bytes, bool], SafeAlpha] = {}

    def __call__(self, icons: Iterable[str] | None = None) -> SafeAlpha:
        return self.answer(_moving(self, icons), per_canvas_needed=icons is None)

    @cached_property
    def per_row(self) -> list[Found]:
        """First unsafe alpha of every per-row rule (:func:`per_row_limits`), once per audit."""
        return per_row_limits(self)

    def objection_at(self, moving_icons: NDArray[np.bool_], a: float) -> Found | None:
        """An objection at exactly ``a`` involving a moving icon (the re-check of an answer)."""
        for rule, icons in self.static:
            if any(moving_icons[i] for i in icons):
                return Found(rule, -1, icons, a, True)
        return (
            row_objection(self, moving_icons, a)
            or self.collisions.at(self.tracks(moving_icons), a)
            or pair_objection(self, moving_icons, a)
        )

    def answer(self, moving_icons: NDArray[np.bool_], per_canvas_needed: bool = True) -> SafeAlpha:
        """Largest safe alpha when the icons in ``moving_icons`` share one coefficient.

        The same question is answered once: a colour with one icon asks what
        that icon asks (most brand colours have one logo).
        """
        moving = hashlib.blake2b(np.packbits(moving_icons).tobytes(), digest_size=16).digest()
        key = (moving, per_canvas_needed)  # 16 bytes a question, whatever the set
        found = self._answers.get(key)
        if found is None:
            found = self._answer(moving_icons, per_canvas_needed)
            self._answers[key] = found
        return found

    def _answer(self, moving_icons: NDArray[np.bool_], per_canvas_needed: bool) -> SafeAlpha:
        precision = self.precision
        m = len(self.canvases)
        found: list[Found] = []
        for rule, icons in self.static:
            if any(moving_icons[i] for i in icons):
                found.append(Found(rule, -1, icons, ALPHA_LO, True))
        found += [f for f in self.per_row if moving_icons[f.icons[0]]]
        tracks = self.tracks(moving_icons)
        found += self.collisions.collision_limits(tracks)
        caps = np.full(m, self.a_hi)
        for f in found:
            if f.canvas < 0 or not per_canvas_needed:
                caps = np.minimum(caps, f.at)
            else:
                caps[f.canvas] = min(caps[f.canvas], f.at)
        rules = self.policy.rules
        if self.a_hi > ALPHA_LO:
            found += separation_limits(self, tracks, caps)
            roles = self.tracks(moving_icons, roles=True)
            shrink = not per_canvas_needed
            if Rule.CONFUSION in rules:
                found += confusion_limits(self, roles, caps, None, shrink)
            if Rule.CVD_CONFUSION in rules:
                for deficiency in DEFICIENCIES:
                    found += confusion_limits(self, roles, caps, deficiency, shrink)
            if Rule.CVD_COLLISION in rules:
                found += cvd_collision_limits(self, roles, float(caps.max()))
        limits = [self._limit(f) for f in found]
        per_canvas_limit: list[Limit | None] = []
        for j in range(len(self.canvases)):
            here = [lim for f, lim in zip(found, limits, strict=True) if f.canvas in (j, -1)]
            per_canvas_limit.append(min(here, key=_limit_order) if here else None)
        per_canvas = tuple(
            CanvasLimit(name, self.rounded(limit), limit)
            for name, limit in zip(self.canvases, per_canvas_limit, strict=True)
        )
        limit = min(limits, key=_limit_order) if limits else None
        alpha = self.rounded(limit)
        unit = 10.0**-precision
        while alpha is not None and self.objection_at(moving_icons, alpha) is not None:
            # Only a float disagreement exactly at the rounded point gets here.
            stepped = _round_down(alpha - unit + unit / 2, precision)
            alpha = stepped if stepped >= ALPHA_LO else None
        if limit is None:
            exact: float | None = self.a_hi
        elif limit.attained and limit.at <= ALPHA_LO:
            exact = None
        else:
            exact = limit.at
        return SafeAlpha(alpha=alpha, exact=exact, limit=limit, per_canvas=per_canvas)

    def joint(
        self,
        colours: Iterable[str],
        held: Iterable[str] = (),
        *,
        grow: bool = True,
    ) -> tuple[tuple[str, ...], SafeAlpha]:
        """The joint answer of a group of colours, and the group it has to grow into.

        Every icon of the group's colours moves (but those named in ``held``, which
        keep their alpha although their colour moves); the
        others keep their alpha.  What limits the answer may lie outside the group:
        a role the group pulls under the separation floor (the two roles of a
        ``confusion`` or ``cvd-confusion`` limit), or, when not even alpha 1 is safe,
        the colours of the icons that stop it there (a collision with a colour held
        at its own alpha).  Those colours join the group and the grown group is
        asked again, until its limit lies inside it.  So a group's answer names the
        pair that really limits it, and "no safe alpha" means alpha 1 itself fails
        for its icons.  Without ``grow`` only a group with no safe alpha grows, and
        one that has none after growing gives the last answer a smaller group had
        (``--apply``: every answer holds with the others at their alpha).  The
        group comes back in palette order.
        """
        group = set(colours)
        keep = set(held)
        index = {name: i for i, name in enumerate(self.names)}
        order = {c: k for k, c in enumerate(self.colours)}
        last: tuple[tuple[str, ...], SafeAlpha] | None = None
        while True:
            moving = [
                c in group and n not in keep
                for c, n in zip(self.colour_of, self.names, strict=True)
            ]
            safe = self.answer(np.array(moving, dtype=bool), per_canvas_needed=False)
            answer = tuple(sorted(group, key=lambda c: order.get(c, len(order)))), safe
            limit = safe.limit
            joins: set[str] = set()
            if limit is not None and safe.alpha is None:
                joins = set(limit.roles) or {self.colour_of[index[n]] for n in limit.icons}
            elif limit is not None and grow:
                joins = set(limit.roles)
            if joins <= group:
                return last if safe.alpha is None and last is not None else answer
            if safe.alpha is not None and not grow:
                last = answer
            group |= joins

    def joint_groups(
        self, seeds: Iterable[Iterable[str]]
    ) -> list[tuple[tuple[str, ...], SafeAlpha, tuple[str, ...]]]:
        """Disjoint groups grown from ``seeds`` (:meth:`joint`), with their answers and seeds.

        Two groups that grow into each other are one group: their seeds are joined
        and asked again, until no two share a colour.  Each comes with the seed
        colours it grew from, in palette order; groups in order of their first seed.
        """
        order = {c: k for k, c in enumerate(self.colours)}
        pending = [set(seed) for seed in seeds]
        while True:
            grown = [self.joint(seed) for seed in pending]
            for k, (colours, _) in enumerate(grown):
                other = next((h for h in range(k) if set(grown[h][0]) & set(colours)), None)
                if other is not None:
                    pending[other] |= pending.pop(k)
                    break
            else:
                return [
                    (colours, safe, tuple(sorted(seed, key=lambda c: order.get(c, len(order)))))
                    for (colours, safe), seed in zip(grown, pending, strict=True)
                ]

    def _limit(self, found: Found) -> Limit:
        canvas = "(every canvas)" if found.canvas < 0 else self.canvases[found.canvas]
        grid = None if RULES[found.rule].closed_form else GRID_STEP
        icons = self.icon_names(found.icons)
        return Limit(found.rule, canvas, icons, found.at, found.attained, grid, found.roles)

    def rounded(self, limit: Limit | None) -> float | None:
        """``limit.at`` (or alpha_max) rounded down, stepping off an unsafe point."""
        precision = self.precision
        if limit is None:
            return _round_down(self.a_hi, precision)
        if limit.attained and limit.at <= ALPHA_LO:
            return None
        alpha = _round_down(limit.at, precision)
        if limit.attained and alpha >= limit.at:
            alpha = _round_down(limit.at - 10.0**-precision, precision)
        return alpha if alpha >= ALPHA_LO else None


def _limit_order(limit: Limit) -> tuple[float, bool, int, str, tuple[str, ...]]:
    """Earliest first; at a tie an unsafe point before an open interval; then rule, canvas."""
    return (limit.at, not limit.attained, _RULE_ORDER[limit.rule], limit.canvas, limit.icons)


def _swap_names(safe: SafeAlpha, old: str, new: str) -> SafeAlpha:
    """The same answer for another icon of the same style: swap the two names."""
    if old == new:
        return safe

    def swap(limit: Limit | None) -> Limit | None:
        if limit is None:
            return None
        names = {old: new, new: old}
        return replace(limit, icons=tuple(sorted(names.get(i, i) for i in limit.icons)))

    return replace(
        safe,
        limit=swap(safe.limit),
        per_canvas=tuple(replace(c, limit=swap(c.limit)) for c in safe.per_canvas),
    )


def largest_safe_alpha(
    result: AuditResult,
    policy: Policy,
    *,
    icons: Sequence[str] | None = None,
    alpha_max: float = 2.0,
    precision: int = 3,
) -> SafeAlpha:
    """The largest safe alpha when ``icons`` (default: all) share one coefficient.

    The other icons keep their alpha in ``result``.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> from alpha_audit.rows import audit
    >>> theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    >>> dots = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.0),))
    >>> largest_safe_alpha(audit(theme, dots), Policy()).limit.rule.value  # dark blue on yellow
    'loss'
    """
    engine = SafeAlphas(result, policy, alpha_max=alpha_max, precision=precision)
    return engine.answer(_moving(engine, icons))


def _moving(engine: SafeAlphas, icons: Iterable[str] | None) -> NDArray[np.bool_]:
    if icons is None:
        return np.ones(len(engine.names), dtype=bool)
    wanted = set(icons)
    unknown = sorted(wanted - set(engine.names))
    if unknown:
        raise UsageError(f"no icon named {unknown[0]!r} in {engine.result.iconset.name}")
    return np.isin(np.array(engine.names), sorted(wanted)).reshape(-1)


def connected(groups: Iterable[Iterable[str]]) -> list[tuple[str, ...]]:
    """The connected components of colours joined by ``groups`` (each sorted), in order
    of first appearance; a colour alone is no group.

    >>> connected([("red", "orange"), ("amber", "yellow"), ("orange", "amber"), ("blue",)])
    [('amber', 'orange', 'red', 'yellow')]
    """
    parent: dict[str, str] = {}

    def find(x: str) -> str:
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for group in groups:
        colours = list(group)
        for other in colours:
            parent[find(other)] = find(colours[0])
    out: dict[str, list[str]] = {}
    for colour in parent:
        out.setdefault(find(colour), []).append(colour)
    return [tuple(sorted(g)) for g in out.values() if len(g) > 1]


def confusion_groups(
    result: AuditResult, policy: Policy, extra: Iterable[Iterable[str]] = ()
) -> list[tuple[str, ...]]:
    """The roles the gate finds confused at their alphas, as connected groups.

    Two roles a failing ``confusion`` or ``cvd-confusion`` finding names are
    joined (on any canvas), and so are the colours of each of ``extra``
    (:func:`connected`).

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> from alpha_audit.rows import audit
    >>> pal = {"a": "#ee7733", "b": "#ee3377", "c": "#0077bb"}
    >>> icons = IconSet("s", tuple(Icon(k, f"{k}.svg", v, 1.5, k) for k, v in pal.items()), pal)
    >>> confusion_groups(audit(Theme("t", (Canvas("w", "#ffffff"),)), icons), Policy())
    [('a', 'b')]
    """
    role_rules = frozenset(r for r in policy.rules if RULES[r].family is Family.CONFUSION)
    pairs: list[Iterable[str]] = []
    if role_rules:
        only = Policy(
            rules=role_rules,
            warnings=frozenset(),
            min_delta_e=policy.min_delta_e,
            exemptions=policy.exemptions,
        )
        for f in findings_for(result, only):
            if f.exemption is None and isinstance(f.figures, ConfusionFigures):
                pairs.append(f.figures.roles)
    return connected([*pairs, *extra])


def suggest(
    result: AuditResult,
    policy: Policy,
    *,
    alpha_max: float = 2.0,
    precision: int = 3,
    scopes: Iterable[str] = SCOPES,
    groups: Iterable[Iterable[str]] = (),
    progress: Progress | None = None,
) -> SuggestResult:
    """The largest safe alpha for the whole set, per colour, per group of roles and per icon.

    Set-wide, every icon takes the same coefficient; per colour, the icons of
    that colour (palette name, else the colour) move together; per group, the
    roles the gate finds confused at their alphas, connected through confusion
    (:func:`confusion_groups`; ``groups`` adds more), move together and take in
    every role their joint answer finds pulled under the floor
    (:meth:`SafeAlphas.joint`); per icon, one icon moves.  Others keep their alpha.
    ``policy`` is the gate's.  Icons that could not be rendered are left out, as
    ``check`` leaves them out (``left_out``).  ``progress`` is told how many
    questions there are, then each one answered.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> from alpha_audit.rows import audit
    >>> theme = Theme("t", (Canvas("ink", "#0d1117"),))
    >>> orange, other = Icon("o", "o.svg", "#ee7733", 1.0), Icon("x", "x.svg", "#ff7f36", 1.0)
    >>> result = suggest(audit(theme, IconSet("s", (orange, other))), Policy())
    >>> result.alpha  # together, the two never share an 8-bit output up to 2
    2.0
    >>> alone = result.per_icon[0].safe  # orange alone passes through #ff7f36
    >>> alone.alpha, alone.limit.rule.value, alone.limit.icons, round(alone.limit.at, 6)
    (1.165, 'new-collision', ('o', 'x'), 1.165168)
    """
    engine = SafeAlphas(result, policy, alpha_max=alpha_max, precision=precision)
    wanted = set(scopes)
    unknown = wanted - set(SCOPES)
    if unknown:
        raise UsageError(f"unknown scope {sorted(unknown)[0]!r}; use one of: {', '.join(SCOPES)}")
    n = len(engine.names)
    start, tick = progress or ((lambda total: None), (lambda: None))
    members: dict[str, list[int]] = {name: [] for name in engine.colours}
    for i, colour in enumerate(engine.colour_of):
        members[colour].append(i)
    seeds = confusion_groups(result, policy, groups) if "group" in wanted else []
    start(
        ("set" in wanted)
        + len(members) * ("colour" in wanted)
        + len(seeds)
        + n * ("icon" in wanted)
    )
    overall = None
    if "set" in wanted:
        overall = engine.answer(np.ones(n, dtype=bool))
        tick()
    per_color = _per_colour(engine, members, tick) if "colour" in wanted else []
    per_group = []
    for colours, safe, seed in engine.joint_groups(seeds):
        icons = sorted(i for c in colours for i in members.get(c, []))
        per_group.append(
            GroupSuggestion(colours, tuple(engine.names[i] for i in icons), safe, seed)
        )
    for _ in seeds:
        tick()
    per_icon = _per_icon(engine, tick) if "icon" in wanted else []
    return SuggestResult(
        audit=result,
        policy=policy,
        alpha_max=engine.a_hi,
        precision=precision,
        overall=overall if overall is not None else SafeAlpha(None, None, None, ()),
        per_color=tuple(per_color),
        per_icon=tuple(per_icon),
        per_group=tuple(per_group),
        left_out=tuple(p.icon for p in result.problems),
    )


def _per_colour(
    engine: SafeAlphas, members: dict[str, list[int]], tick: Callable[[], None]
) -> list[ColorSuggestion]:
    """The answer for the icons of each colour moving together (a colour without icons has none)."""
    out = []
    for name, icons in members.items():
        if icons:
            out.append(
                ColorSuggestion(
                    color=name,
                    source=engine.result.iconset.icons[icons[0]].color,
                    icons=tuple(engine.names[i] for i in icons),
                    safe=engine.answer(_only(engine, icons), per_canvas_needed=False),
                )
            )
        tick()
    return out


def _only(engine: SafeAlphas, icons: list[int]) -> NDArray[np.bool_]:
    """Which icons move: those at ``icons``."""
    moving = np.zeros(len(engine.names), dtype=bool)
    moving[icons] = True
    return moving


def _per_icon(engine: SafeAlphas, tick: Callable[[], None]) -> list[IconSuggestion]:
    """The answer for each icon moving alone.

    Icons of one style (the same paints at the same alpha) get the same answer,
    unless an exemption names an icon; then every icon is asked on its own.
    """
    share = not any(e.icon is not None for e in engine.policy.exemptions)
    styles: dict[int, list[tuple[int, float]]] = {}
    for p, i in enumerate(engine.row_icon.tolist()):
        styles.setdefault(i, []).append((int(engine.keys[p]), float(engine.result.alpha[p])))
    cache: dict[tuple[tuple[int, float], ...], tuple[str, SafeAlpha]] = {}
    out = []
    for i, icon in enumerate(engine.result.iconset.icons):
        style = tuple(sorted(styles.get(i, [])))
        if share and style in cache:
            rep, safe = cache[style]
            safe = _swap_names(safe, rep, icon.name)
        else:
            safe = engine.answer(_only(engine, [i]), per_canvas_needed=False)
            cache[style] = (icon.name, safe)
        out.append(IconSuggestion(icon.name, icon.color_name or icon.color, icon.alpha, safe))
        tick()
    return out
