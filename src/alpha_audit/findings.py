"""What each rule objects to in one audit's rows: :class:`Finding` objects.

:func:`findings_for` applies every rule a :class:`~alpha_audit.policy.Policy`
fails on or reports (:attr:`~alpha_audit.policy.Policy.reported`) to an
:class:`~alpha_audit.rows.AuditResult` and returns one :class:`Finding` per
*root cause*: a rule's objection to one paint of one icon, one pair of roles,
or one group of colours, folded over every canvas where it occurs (naming
them, and the worst, whose figures it carries).  Each finding says where the
failing value is written (:attr:`Finding.locations`: the ``alpha:`` or colour
that sets it, the palette entries of both roles ...), the SVG being a related
place.  Every figure comes from the audit's rows (its pipeline's colours).
Exemptions are applied here (a canvas exempted apart is a finding apart);
baselines and the verdict are :mod:`alpha_audit.gate`'s.  Pure computation.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    DEFICIENCIES,
    Deficiency,
    composite_paint,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_hex,
    linear_to_lab,
    shipped,
    simulate_cvd,
    to_8bit,
)
from alpha_audit.color.nearest import delta_e_2000_lightness_key, pairs_below
from alpha_audit.figures import (
    CollisionFigures,
    ConfusionFigures,
    ContrastFigures,
    CvdCollisionFigures,
    DriftFigures,
    ElementFigures,
    Figures,
    FixedPaintFigures,
    NoFigures,
    RenderDriftFigures,
    SeparationFigures,
    ThinStrokeFigures,
)
from alpha_audit.model import Edit, Icon, Location
from alpha_audit.observed import MeasuredPaint
from alpha_audit.policy import (
    RENDER_DRIFT_TOLERANCE,
    Exemption,
    Policy,
    confusion_breaks,
    contrast_breaks,
    drift_breaks,
    loss_reported,
    size_contrast_floor,
)
from alpha_audit.rows import AuditResult, Collision, PaintEntry, Separation
from alpha_audit.rules import Level, Rule

__all__ = [
    "LOCK_TOLERANCE",
    "MAX_LOCATIONS",
    "Finding",
    "FindingKey",
    "alpha_location",
    "colour_location",
    "cvd_collision_groups",
    "findings_for",
    "locked_rows",
    "ranked",
    "role_rows",
    "severity",
]

# A locked (brand) colour may move by less than one just-noticeable
# difference: CIEDE2000 = 1 is the usual reading of one JND.
LOCK_TOLERANCE = 1.0

# Where a finding between many colours is written: the first few places (a
# collision of 353 brand colours names the alpha and a dozen entries, not 353).
MAX_LOCATIONS = 12

# (theme, icon set, rule, icons): what a baseline matches on, the identity of a
# root cause.  Never a canvas (a finding folds every canvas where it occurs), a
# line number or a value, so editing a manifest does not invalidate a baseline.
FindingKey = tuple[str, str, str, tuple[str, ...]]


@dataclass(frozen=True)
class Finding:
    """One root cause a rule objects to.

    ``canvas`` is the worst canvas, whose figures ``figures`` (a typed record
    per rule family, :mod:`alpha_audit.figures`) and ``message`` give (contrast
    before and after, threshold, CIEDE2000, 8-bit output ...); ``rows`` are the
    audit's paint rows it came from (a paint's, or every row of two confused
    roles or of colours alike under a deficiency; empty for an 8-bit
    collision, a separation or a broken icon, judged over colours);
    ``canvases`` every canvas where it occurs, in theme order (empty for a
    rule judging icons, not canvases).  ``locations`` say where the failing
    values are written, the one to edit first (:class:`Location`); ``files``
    are the icons' SVG files, ``lines`` the manifest lines that set each
    icon's colour or alpha, ``sources`` the (file, line) of each design token
    setting a colour of the finding.  ``level`` is what the gate does with it
    (a loss on an already invisible paint is reported, not gated, whatever the
    rule's level); ``fixes`` index the report's fixes that answer it and
    ``edits`` are those known to clear it as exact text edits (both from
    :mod:`alpha_audit.fixes`).
    """

    rule: Rule
    theme: str
    iconset: str
    canvas: str | None
    icons: tuple[str, ...]
    message: str
    figures: Figures = field(default_factory=NoFigures)
    files: tuple[Path, ...] = ()
    manifest: Path | None = None
    lines: tuple[int, ...] = ()
    exemption: Exemption | None = None
    sources: tuple[tuple[Path, int], ...] = ()
    baselined: bool = False
    level: Level = Level.FAIL
    fixes: tuple[int, ...] = ()
    edits: tuple[Edit, ...] = ()
    canvases: tuple[str, ...] = ()
    locations: tuple[Location, ...] = ()
    rows: tuple[int, ...] = ()

    @property
    def key(self) -> FindingKey:
        """Identity for baselines and ``--base``: theme, icon set, rule and icons."""
        return (self.theme, self.iconset, self.rule.value, self.icons)

    @property
    def observed(self) -> MeasuredPaint | None:
        """The paint a browser drew, for a finding of a page's row; else ``None``."""
        match self.figures:
            case ContrastFigures(observed=o) | RenderDriftFigures(observed=o):
                return o
        return None

    @property
    def quiet(self) -> bool:
        """Whether this is a loss reported, never gated (an invisible paint, a small loss)."""
        return isinstance(self.figures, ContrastFigures) and not self.figures.gated

    @property
    def fails(self) -> bool:
        """Whether this finding fails the gate (a failing rule, not exempt, not in the baseline)."""
        return self.level is Level.FAIL and self.exemption is None and not self.baselined


def alpha_location(icon: Icon, manifest: Path | None) -> Location | None:
    """Where ``icon``'s alpha is written: its own or override's, palette's, set's, config's."""
    if icon.alpha_span is not None:
        s = icon.alpha_span
        return Location(s.file, s.start_line, "alpha", s)
    if icon.alpha_line is not None and manifest is not None:
        return Location(manifest, icon.alpha_line, "alpha")
    return None


def colour_location(icon: Icon, manifest: Path | None) -> Location | None:
    """Where ``icon``'s colour is written: its design token, else its manifest value."""
    span = icon.color_span
    if icon.token_file is not None and icon.token_line is not None:
        file = Path(icon.token_file)
        exact = span if span is not None and span.file == file else None
        return Location(file, icon.token_line, "token", exact)
    if span is not None:
        return Location(span.file, span.start_line, "colour", span)
    if icon.color_line is not None and manifest is not None:
        return Location(manifest, icon.color_line, "colour")
    return None


def _icon_refs(
    by_name: Mapping[str, Icon], names: Sequence[str]
) -> tuple[tuple[Path, ...], tuple[int, ...]]:
    files: list[Path] = []
    lines: list[int] = []
    for name in names:
        icon = by_name.get(name)
        if icon is None:
            continue
        files.append(Path(icon.file))
        lines.extend(n for n in (icon.color_line, icon.alpha_line) if n is not None)
    return tuple(files), tuple(sorted(set(lines)))


# Given the index of a root cause's worst cell, its message and figures: how a
# rule hands one root cause to the collector (:meth:`_Collector.fold`).
Build = Callable[[int], tuple[str, Figures]]


class _Collector:
    """Builds the findings of one audit, each with its locations and exemption."""

    def __init__(self, result: AuditResult, policy: Policy) -> None:
        self.result, self.policy = result, policy
        self.by_name = {i.name: i for i in result.iconset.icons}  # once: a brand set has thousands
        self.canvas_names = [c.name for c in result.theme.canvases]
        self.out: list[Finding] = []
        self._alpha_at: dict[str, Location | None] = {}
        self._colour_at: dict[str, Location | None] = {}

    # -------------------------------------------------------------- locations

    def alpha_at(self, name: str) -> Location | None:
        """Where the alpha of icon ``name`` is written (its own, palette's, set's, config's)."""
        if name not in self._alpha_at:
            icon = self.by_name.get(name)
            found = None if icon is None else alpha_location(icon, self.result.iconset.path)
            self._alpha_at[name] = found
        return self._alpha_at[name]

    def colour_at(self, name: str) -> Location | None:
        """Where the colour of icon ``name`` is written: its token, else its manifest value."""
        if name not in self._colour_at:
            icon = self.by_name.get(name)
            found = None if icon is None else colour_location(icon, self.result.iconset.path)
            self._colour_at[name] = found
        return self._colour_at[name]

    def paint_locations(self, e: PaintEntry, *, colour_first: bool = False) -> tuple[Location, ...]:
        """Where one paint's alpha and colour are set (a hard-coded colour: its SVG element),
        then the places the rows know besides (a page's CSS declarations, its story)."""
        colour = (
            Location(Path(e.icon.file), e.line or 1, "paint")
            if e.fixed and not e.where
            else self.colour_at(e.icon.name)
        )
        alpha = self.alpha_at(e.icon.name)
        found = (colour, alpha) if colour_first else (alpha, colour)
        return tuple(dict.fromkeys([*(loc for loc in found if loc is not None), *e.where]))

    def group_locations(
        self, names: Iterable[str], *, colour_first: bool = False
    ) -> tuple[Location, ...]:
        """The alphas and colours of several icons, each place once, at most MAX_LOCATIONS."""
        names = list(names)
        alphas = [self.alpha_at(n) for n in names]
        colours = [self.colour_at(n) for n in names]
        found = [*colours, *alphas] if colour_first else [*alphas, *colours]
        unique: dict[tuple[Path, int], Location] = {}
        for loc in found:
            if loc is not None:
                unique.setdefault((loc.file, loc.line), loc)
            if len(unique) >= MAX_LOCATIONS:
                break
        return tuple(unique.values())

    def token_sources(
        self, names: Sequence[str], canvases: Sequence[str]
    ) -> tuple[tuple[Path, int], ...]:
        """(file, line) of the design tokens setting the icons' colours, then the canvases'."""
        out: list[tuple[Path, int]] = []
        for name in names[:MAX_LOCATIONS]:
            icon = self.by_name.get(name)
            if icon is not None and icon.token_file is not None and icon.token_line is not None:
                out.append((Path(icon.token_file), icon.token_line))
        wanted = set(canvases)
        for c in self.result.theme.canvases:
            if c.name in wanted and c.file is not None and c.line is not None:
                out.append((Path(c.file), c.line))
        return tuple(dict.fromkeys(out))[: 2 * MAX_LOCATIONS]  # unique, first-seen order

    # -------------------------------------------------------------- findings

    def add(
        self,
        rule: Rule,
        icons: tuple[str, ...],
        message: str,
        figures: Figures,
        *,
        files: tuple[Path, ...] | None = None,
        locations: tuple[Location, ...] = (),
        canvases: Sequence[str] = (),
        canvas: str | None = None,
        level: Level | None = None,
        rows: tuple[int, ...] = (),
    ) -> None:
        """One finding (``canvas`` the worst of ``canvases``; none: a rule judging icons)."""
        own_files, lines = _icon_refs(self.by_name, icons[:MAX_LOCATIONS])
        self.out.append(
            Finding(
                rule=rule,
                theme=self.result.theme.name,
                iconset=self.result.iconset.name,
                canvas=canvas,
                icons=icons,
                message=message,
                figures=figures,
                files=own_files if files is None else files,
                manifest=self.result.iconset.path,
                lines=lines,
                exemption=self.policy.exempt(rule, canvas, icons),
                sources=self.token_sources(icons, canvases),
                level=self.policy.level(rule) if level is None else level,
                canvases=tuple(canvases),
                locations=locations,
                rows=rows,
            )
        )

    def fold(
        self,
        rule: Rule,
        icons: tuple[str, ...],
        cells: Sequence[int],
        badness: Sequence[float],
        build: Build,
        *,
        locations: tuple[Location, ...] = (),
        level: Level | None = None,
        rows: tuple[int, ...] = (),
    ) -> None:
        """One finding for the cells (canvas indices) of one root cause.

        ``badness[k]`` ranks cell ``cells[k]`` (higher is worse); the finding
        carries the worst cell's figures (``build(k)``) and names every canvas.
        Canvases an exemption covers fold apart, so an exemption still names
        exactly what it covers.
        """
        parts: dict[Exemption | None, list[int]] = {}
        for k, j in enumerate(cells):
            parts.setdefault(self.policy.exempt(rule, self.canvas_names[j], icons), []).append(k)
        for ks in parts.values():  # the worst canvas of a part has the part's exemption
            worst = max(ks, key=lambda k: (badness[k], -k))
            message, figures = build(worst)
            names = [self.canvas_names[j] for j in sorted({cells[k] for k in ks})]
            canvas = self.canvas_names[cells[worst]]
            self.add(
                rule,
                icons,
                message,
                figures,
                locations=locations,
                canvases=names,
                canvas=canvas,
                level=level,
                rows=rows,
            )


def findings_for(result: AuditResult, policy: Policy) -> list[Finding]:
    """Every finding of the rules ``policy`` fails on or reports, exemptions applied.

    One finding per root cause, folded over canvases.  Order is stable: rules
    in :class:`~alpha_audit.rules.Rule` order; within a rule, row (icon,
    paint) order or the order of the first canvas where a group occurs.
    :func:`ranked` orders them by severity.
    """
    c = _Collector(result, policy)
    reported = policy.reported
    for rule in Rule:
        if rule in reported and rule in _RULES:
            _RULES[rule](c, rule)
    return c.out


_CONTRAST_TEMPLATES = {
    Rule.LOSS: "contrast drops {ref:.3f} -> {now:.3f} ({gain:+.4f}) at alpha {a:g}",
    Rule.NEWLY_FAILING: "passes {t:g}:1 at alpha 1 ({ref:.3f}) but not at alpha {a:g} ({now:.3f})",
    Rule.BELOW_THRESHOLD: "contrast {now:.3f} is below {t:g}:1 at alpha {a:g}",
}


def _contrast(c: _Collector, rule: Rule) -> None:
    """The per paint contrast rules, one finding per paint over the canvases it fails on.

    A loss on a paint below the visibility floor at alpha 1, or within the
    relative tolerance, is reported (level ``warn``), never gated.
    """
    r, policy = c.result, c.policy
    mask = contrast_breaks(rule, policy, r.contrast_ref, r.contrast, r.threshold, r.tolerance)
    quiet = np.zeros_like(mask)
    if rule is Rule.LOSS:
        quiet = loss_reported(policy, r.contrast_ref, r.contrast, r.tolerance)
    canvases = r.theme.canvases
    worse = -r.gain if rule is Rule.LOSS else -r.contrast  # (p, m), higher is worse
    for p in np.flatnonzero((mask | quiet).any(axis=1)).tolist():
        e = r.entries[p]
        colour_first = rule is Rule.BELOW_THRESHOLD and bool(
            (r.contrast_ref[p] < r.threshold).all()
        )
        locations = c.paint_locations(e, colour_first=colour_first)
        for cells_mask, level in ((mask[p], None), (quiet[p], Level.WARN)):
            cells = np.flatnonzero(cells_mask).tolist()
            if not cells:
                continue

            def figures(
                k: int, p: int = p, e: PaintEntry = e, cells: list[int] = cells
            ) -> tuple[str, Figures]:
                j = cells[k]
                fig = ContrastFigures(
                    alpha=float(r.alpha[p]),
                    contrast_ref=float(r.contrast_ref[p, j]),
                    contrast=float(r.contrast[p, j]),
                    gain=float(r.gain[p, j]),
                    threshold=float(r.threshold),
                    background=canvases[j].color,
                    source=e.source,
                    paint=e.paint,
                    opacity=e.opacity,
                    observed=r.observed[p] if r.observed else None,
                )
                if fig.observed is not None:
                    return _observed_message(fig.observed, fig), fig
                message = _CONTRAST_TEMPLATES[rule].format(
                    ref=fig.contrast_ref,
                    now=fig.contrast,
                    gain=fig.gain,
                    a=fig.alpha,
                    t=r.threshold,
                )
                if e.fixed or e.opacity != 1.0:
                    message += f" (paint {e.paint} at opacity {e.opacity:g})"
                return message, fig

            build: Build = figures
            if level is Level.WARN:
                build = _quiet(figures, r.contrast_ref[p], cells, policy.visibility_floor)
            c.fold(
                rule,
                (e.icon.name,),
                cells,
                worse[p, cells].tolist(),
                build,
                locations=locations,
                level=level,
                rows=(p,),
            )


def _observed_message(o: MeasuredPaint, fig: ContrastFigures) -> str:
    """``below-threshold`` of a row a browser drew: the pair that limits, and the model."""
    message = f"draws {o.drawn} on {o.behind}: {fig.contrast:.2f}:1 is below {fig.threshold:g}:1"
    if o.declared_opacity < 1.0:
        message += f" (at opacity {o.declared_opacity:g})"
    near = o.nearer
    if near is not None:
        message += f"; the model predicts {near.contrast:.2f}:1 ({near.pipeline})"
    return message


def _render_drift(c: _Collector, rule: Rule) -> None:
    """A page draws another colour than the model predicts for its manifest colour."""
    r = c.result
    for p, o in enumerate(r.observed):
        near = o.nearer
        if near is None or o.render_drift is None:
            continue
        if not drift_breaks(o.render_drift, RENDER_DRIFT_TOLERANCE):
            continue
        e = r.entries[p]
        message = (
            f"draws {o.drawn} where the model predicts {near.output} ({near.pipeline}, from "
            f"{o.model_source} at alpha {o.model_alpha:g}; CIEDE2000 {o.render_drift:.1f} > "
            f"{RENDER_DRIFT_TOLERANCE:g})"
        )
        fig = RenderDriftFigures(
            observed=o,
            drift=o.render_drift,
            tolerance=RENDER_DRIFT_TOLERANCE,
            background=r.theme.canvases[0].color,
            source=e.source,
            paint=e.paint,
            opacity=e.opacity,
        )

        def build(k: int, message: str = message, fig: Figures = fig) -> tuple[str, Figures]:
            return message, fig

        c.fold(
            rule,
            (e.icon.name,),
            list(range(len(r.theme.canvases))),
            [o.render_drift] * len(r.theme.canvases),
            build,
            locations=c.paint_locations(e, colour_first=True),
            rows=(p,),
        )


def _quiet(build: Build, ref: NDArray[np.float64], cells: list[int], floor: float) -> Build:
    """``build`` with the reason a loss is reported, not gated, added to its message."""

    def quiet(k: int) -> tuple[str, Figures]:
        message, fig = build(k)
        if ref[cells[k]] < floor:
            why = f"already below the visibility floor {floor:g}:1 at alpha 1"
        else:
            why = "within the loss tolerance"
        if isinstance(fig, ContrastFigures):
            fig = replace(fig, gated=False)
        return f"{message} ({why}: reported, not gated)", fig

    return quiet


def _colours(colours: Sequence[str], limit: int = 8) -> str:
    """The colours a message names: all of a few, the first ``limit`` and a count of many.

    (The JSON's ``sources`` keeps every one.)

    >>> _colours(["#000000", "#010101"])
    'distinct colours #000000, #010101'
    >>> _colours([f"#0000{k:02x}" for k in range(10)], 2)
    '10 distinct colours (#000000, #000001 +8 more)'
    """
    if len(colours) <= limit:
        return f"distinct colours {', '.join(colours)}"
    head = ", ".join(colours[:limit])
    return f"{len(colours)} distinct colours ({head} +{len(colours) - limit} more)"


def _collisions(c: _Collector, rule: Rule) -> None:
    """``collision``, ``new-collision`` and ``near-duplicate``: colours sharing an 8-bit output.

    Each collision is reported under one rule (:meth:`~alpha_audit.policy.Policy.collision_rule`,
    from how far apart its colours were at alpha 1): every collision is a
    ``collision``; one alpha made between colours told apart at alpha 1 is a
    ``new-collision``; one between colours that already look the same there is a
    ``near-duplicate``.  One finding per set of colliding colours, over the
    canvases where exactly they collide.
    """
    policy = c.policy
    index = {name: j for j, name in enumerate(c.canvas_names)}
    groups: dict[tuple[str, ...], list[Collision]] = {}
    for col in c.result.collisions:
        if policy.collision_rule(col.delta_e_ref) is rule:
            groups.setdefault(col.sources, []).append(col)
    limit = policy.near_duplicate_delta_e
    for cols in groups.values():
        icons = tuple(sorted({n for col in cols for n in col.icons}))

        def build(k: int, cols: list[Collision] = cols) -> tuple[str, Figures]:
            col = cols[k]
            give = "both give" if len(col.sources) == 2 else "all give"
            if not col.new:
                how = " (already at alpha 1)"
            elif col.delta_e_ref < limit:
                widest = max(x.delta_e_ref for x in cols)
                how = (
                    f": they already look the same at alpha 1 (CIEDE2000 {widest:.3g} < "
                    f"{limit:g}); alpha only rounds them together"
                )
            else:
                how = ""
            fig = CollisionFigures(col.output, col.sources, col.new, col.delta_e_ref)
            return f"{_colours(col.sources)} {give} {col.output}{how}", fig

        c.fold(
            rule,
            icons,
            [index[col.canvas] for col in cols],
            [float(len(col.icons)) for col in cols],
            build,
            locations=c.group_locations(icons),
        )


def _separation(c: _Collector, rule: Rule) -> None:
    """The closest pair of colours below ``min_delta_e``, one finding per pair of colours."""
    limit = c.policy.min_delta_e
    index = {name: j for j, name in enumerate(c.canvas_names)}
    pairs: dict[tuple[str, ...], list[Separation]] = {}
    for s in c.result.separations:
        if s.delta_e < limit:
            pairs.setdefault(tuple(sorted(s.sources)), []).append(s)
    for found in pairs.values():
        icons = tuple(sorted({n for s in found for n in s.icons}))

        def build(k: int, found: list[Separation] = found) -> tuple[str, Figures]:
            s = found[k]
            message = (
                f"closest colours are CIEDE2000 {s.delta_e:.2f} apart "
                f"(at alpha 1: {s.delta_e_ref:.2f}); minimum {limit:g}"
            )
            return message, SeparationFigures(s.delta_e, s.delta_e_ref, limit, s.sources)

        c.fold(
            rule,
            icons,
            [index[s.canvas] for s in found],
            [-s.delta_e for s in found],
            build,
            locations=c.group_locations(icons, colour_first=True),
        )


def _unrenderable(c: _Collector, rule: Rule) -> None:
    for p in c.result.problems:  # broken icons are not in the audited set: name the file
        c.add(
            rule,
            (p.icon,),
            p.message,
            NoFigures(),
            files=(Path(p.file),),
            locations=(Location(Path(p.file), 1, "svg"),),
        )


def _fixed_colour(c: _Collector, rule: Rule) -> None:
    for p, e in enumerate(c.result.entries):
        if not e.fixed:
            continue
        element = e.element or "an element"
        where = f" (line {e.line})" if e.line else ""
        c.add(
            rule,
            (e.icon.name,),
            f"{'/'.join(e.kinds)} {e.paint} of {element}{where} is hard-coded: it is audited "
            "as itself and will not follow the theme",
            FixedPaintFigures(e.paint, element + where),
            locations=(Location(Path(e.icon.file), e.line or 1, "paint"),),
            rows=(p,),
        )


def _not_audited(c: _Collector, rule: Rule) -> None:
    for u in c.result.unaudited:
        where = f" (line {u.line})" if u.line else ""
        icon = c.by_name.get(u.icon)
        at = () if icon is None else (Location(Path(icon.file), u.line or 1, "svg"),)
        c.add(
            rule,
            (u.icon,),
            f"{u.element}: {u.reason}",
            ElementFigures(u.element + where),
            locations=at,
        )


def _drift(c: _Collector, rule: Rule) -> None:
    r = c.result
    if rule is Rule.LOCK:
        limit, selected = LOCK_TOLERANCE, locked_rows(r)
    else:
        limit, selected = c.policy.max_drift, np.ones(len(r.entries), dtype=bool)
    over = drift_breaks(r.drift, limit) & selected[:, np.newaxis]
    what = "locked colour" if rule is Rule.LOCK else "colour"
    for p in np.flatnonzero(over.any(axis=1)).tolist():
        e = r.entries[p]
        cells = np.flatnonzero(over[p]).tolist()

        def build(
            k: int, p: int = p, e: PaintEntry = e, cells: list[int] = cells
        ) -> tuple[str, Figures]:
            j = cells[k]
            d = float(r.drift[p, j])
            shown = linear_to_hex(r.output[p, j])
            message = (
                f"{what} {e.source} is shown as {shown} at alpha {r.alpha[p]:g}: "
                f"CIEDE2000 {d:.1f} > {limit:g}"
            )
            return message, DriftFigures(d, limit, e.source, shown, e.paint)

        c.fold(
            rule,
            (e.icon.name,),
            cells,
            r.drift[p, cells].tolist(),
            build,
            locations=c.paint_locations(e),
            rows=(p,),
        )


def _thin_strokes(c: _Collector, rule: Rule) -> None:
    r = c.result
    limit = c.policy.size_contrast_limit(r.threshold)
    below = np.any(r.size_contrast < size_contrast_floor(limit), axis=2)  # (p, m); NaN never is
    for p in np.flatnonzero(below.any(axis=1)).tolist():
        e = r.entries[p]
        cells = np.flatnonzero(below[p]).tolist()
        worst = np.nanmin(r.size_contrast[p][cells], axis=1)

        def build(
            k: int, p: int = p, e: PaintEntry = e, cells: list[int] = cells
        ) -> tuple[str, Figures]:
            j = cells[k]
            m = int(np.nanargmin(r.size_contrast[p, j]))
            size, sc = r.sizes[m], float(r.size_contrast[p, j, m])
            message = (
                f"at {size}px half the ink of {e.paint} is at coverage <= {r.q50[p, m]:.2f}: "
                f"size contrast {sc:.2f} < {limit:g}:1 (colour contrast {r.contrast[p, j]:.2f})"
            )
            return message, ThinStrokeFigures(size, float(r.q50[p, m]), sc, e.paint)

        c.fold(
            rule,
            (e.icon.name,),
            cells,
            (-worst).tolist(),
            build,
            locations=c.paint_locations(e, colour_first=True),
            rows=(p,),
        )


def locked_rows(result: AuditResult) -> NDArray[np.bool_]:
    """Which rows ``lock`` judges: a locked icon's, or a locked palette colour's ``(p,)``."""
    names = result.iconset.locked
    return np.array(
        [
            e.icon.name in names or (not e.fixed and e.icon.color_name in names)
            for e in result.entries
        ],
        dtype=bool,
    ).reshape(len(result.entries))


def role_rows(result: AuditResult) -> list[int]:
    """One row per distinct (role, source, alpha) among the palette roles' paints.

    ``confusion`` compares palette roles (issue 11: "two palette colours"): the
    ``currentColor`` paints of icons whose colour the palette names, as solid
    colours (opacity 1: confusion is about the palette, not about one icon's
    translucent details).  Unnamed colours (a brand set where every logo has its
    own hex) are no roles, so thousands of brand colours never make millions of pairs.
    """
    seen: dict[tuple[str, str, float], int] = {}
    for p, e in enumerate(result.entries):
        if not e.fixed and e.icon.color_name is not None:
            seen.setdefault((e.role, e.source, e.icon.alpha), p)
    return sorted(seen.values())


def _confusion(c: _Collector, rule: Rule) -> None:
    """One finding per pair of roles, over the canvases (and simulated deficiencies)."""
    pairs: dict[tuple[str, str], list[_Confused]] = {}
    for deficiency in (None,) if rule is Rule.CONFUSION else DEFICIENCIES:
        for one in _confusions(c, deficiency):
            pairs.setdefault(one.roles, []).append(one)
    min_delta_e = c.policy.min_delta_e
    # A confusion is between the roles: every icon drawing either colour at an alpha
    # that is confused (all of both roles' icons when they share one alpha each).
    icons_of: dict[tuple[str, str, float], set[str]] = {}
    rows_of: dict[tuple[str, str, float], list[int]] = {}
    for p, e in enumerate(c.result.entries):
        if not e.fixed and e.icon.color_name is not None:
            icons_of.setdefault(_drawn(e), set()).add(e.icon.name)
            rows_of.setdefault(_drawn(e), []).append(p)
    for (r1, r2), found in sorted(pairs.items()):
        drawn = {d for f in found for d in f.drawn}
        icons = tuple(sorted({n for d in drawn for n in icons_of[d]}))
        # The palette entries of both roles are where the confusion is written.
        locations = c.group_locations(icons, colour_first=True)

        def build(
            k: int, found: list[_Confused] = found, r1: str = r1, r2: str = r2
        ) -> tuple[str, Figures]:
            f = found[k]
            under = "" if f.deficiency is None else f" under simulated {f.deficiency}"
            message = (
                f"{r1} and {r2} are told apart at alpha 1 (CIEDE2000 {f.ref:.1f}) but not at "
                f"alpha {f.alphas[0]:g}/{f.alphas[1]:g} ({f.de:.1f} < {min_delta_e:g}){under}"
            )
            every = tuple(sorted({g.deficiency for g in found if g.deficiency is not None}))
            return message, ConfusionFigures(
                f.ref, f.de, min_delta_e, (r1, r2), f.deficiency, every if f.deficiency else ()
            )

        c.fold(
            rule,
            icons,
            [f.canvas for f in found],
            [-f.de for f in found],
            build,
            locations=locations,
            rows=tuple(sorted(p for d in drawn for p in rows_of[d])),
        )


@dataclass(frozen=True)
class _Confused:
    """Two roles confused on one canvas (under one simulated deficiency, or none)."""

    roles: tuple[str, str]
    icons: tuple[str, str]
    alphas: tuple[float, float]
    canvas: int
    ref: float
    de: float
    deficiency: Deficiency | None
    # Every (role, colour, alpha) of the two roles confused on this canvas: the icons
    # drawing them are the finding's (a role's icons at another alpha may not be).
    drawn: frozenset[tuple[str, str, float]] = frozenset()


def _confusions(c: _Collector, deficiency: Deficiency | None) -> list[_Confused]:
    """Roles distinct at alpha 1 (CIEDE2000 >= min_delta_e) but not at the icons' alpha."""
    r, min_delta_e = c.result, c.policy.min_delta_e
    reps = np.array(role_rows(r), dtype=np.intp)
    if reps.size < 2:
        return []
    entries = [r.entries[p] for p in reps]
    roles = np.unique(np.array([e.role for e in entries], dtype=object), return_inverse=True)[1]
    roles = roles.reshape(-1)
    bg = r.theme.backgrounds[np.newaxis, :, :]
    src = r.sources[reps][:, None, :]
    # Judged as they ship: the 8-bit colours (docs/model.md, "What ships is what is judged").
    solid = shipped(composite_paint(src, bg, 1.0, 1.0, r.pipeline))
    shown = shipped(composite_paint(src, bg, r.alpha[reps][:, None], 1.0, r.pipeline))
    if deficiency is not None:
        solid, shown = simulate_cvd(solid, deficiency), simulate_cvd(shown, deficiency)
    out: list[_Confused] = []
    for j in range(len(r.theme.canvases)):
        # Only pairs closer than min_delta_e at alpha can be confused: found by the
        # exact lightness-pruned search (dE00 >= |dL|/S_L), never all pairs at once.
        lab = linear_to_lab(shown[:, j, :])

        def distance(
            x: NDArray[np.intp], y: NDArray[np.intp], lab: NDArray[np.float64] = lab
        ) -> NDArray[np.float64]:
            return delta_e_2000_lab(lab[x], lab[y])

        i, k, de = pairs_below(delta_e_2000_lightness_key(lab), distance, min_delta_e, roles)
        if i.size == 0:
            continue
        ref = np.asarray(delta_e_2000(solid[i, j, :], solid[k, j, :])).reshape(-1)
        keep = np.flatnonzero(confusion_breaks(ref, de, min_delta_e))
        worst: dict[tuple[str, str], int] = {}
        drawn: dict[tuple[str, str], set[tuple[str, str, float]]] = {}
        for h in keep.tolist():
            one, two = sorted((entries[i[h]].role, entries[k[h]].role))
            if (one, two) not in worst or de[h] < de[worst[one, two]]:
                worst[one, two] = h
            drawn.setdefault((one, two), set()).update(
                (_drawn(entries[i[h]]), _drawn(entries[k[h]]))
            )
        for pair, h in sorted(worst.items()):
            a, b = entries[i[h]], entries[k[h]]
            out.append(
                _Confused(
                    pair,
                    (a.icon.name, b.icon.name),
                    (a.icon.alpha, b.icon.alpha),
                    j,
                    float(ref[h]),
                    float(de[h]),
                    deficiency,
                    frozenset(drawn[pair]),
                )
            )
    return out


def _drawn(e: PaintEntry) -> tuple[str, str, float]:
    """What a role row stands for (:func:`role_rows`): its role, colour and alpha."""
    return (e.role, e.source, e.icon.alpha)


def cvd_collision_groups(
    seen: NDArray[np.integer], ref: NDArray[np.integer], sources: Sequence[str]
) -> list[tuple[tuple[int, ...], list[int]]]:
    """The one statement of ``cvd-collision`` on one canvas: (code, members) that object.

    ``seen`` and ``ref`` are the simulated 8-bit codes ``(n, 3)`` at the icons'
    alpha and at alpha 1.  A group of one simulated code objects when it holds
    two distinct sources that did not already share a simulated code at alpha 1.
    Sorted by code.
    """
    groups: dict[tuple[int, ...], list[int]] = {}
    for r, code in enumerate(seen.tolist()):
        groups.setdefault(tuple(code), []).append(r)
    out = []
    for code, members in sorted(groups.items()):
        if len({sources[r] for r in members}) < 2:
            continue
        if len({tuple(ref[r].tolist()) for r in members}) == 1:
            continue  # already one colour at alpha 1
        out.append((code, members))
    return out


def _cvd_collision(c: _Collector, rule: Rule) -> None:
    """Distinct roles' colours whose simulated outputs newly share an 8-bit code.

    One finding per set of colours, over the canvases and deficiencies where
    exactly they look alike.
    """
    r = c.result
    reps = role_rows(r)
    if len(reps) < 2:
        return
    idx = np.array(reps, dtype=np.intp)
    bg = r.theme.backgrounds[np.newaxis, :, :]
    src = r.sources[idx][:, None, :]
    shown = shipped(composite_paint(src, bg, r.alpha[idx][:, None], 1.0, r.pipeline))
    solid = shipped(composite_paint(src, bg, 1.0, 1.0, r.pipeline))
    sources = [r.entries[p].source for p in idx]
    groups: dict[tuple[str, ...], list[tuple[int, str, Deficiency, tuple[str, ...]]]] = {}
    rows_of: dict[tuple[str, ...], set[int]] = {}
    for deficiency in DEFICIENCIES:
        seen = to_8bit(simulate_cvd(shown, deficiency))
        ref = to_8bit(simulate_cvd(solid, deficiency))
        for j in range(len(r.theme.canvases)):
            for code, members in cvd_collision_groups(seen[:, j], ref[:, j], sources):
                colours = tuple(sorted({sources[m] for m in members}))
                out = "#{:02x}{:02x}{:02x}".format(*code)
                names = tuple(sorted({r.entries[idx[m]].icon.name for m in members}))
                groups.setdefault(colours, []).append((j, out, deficiency, names))
                rows_of.setdefault(colours, set()).update(int(idx[m]) for m in members)
    for colours, found in groups.items():
        icons = tuple(sorted({n for *_, names in found for n in names}))

        def build(
            k: int,
            found: list[tuple[int, str, Deficiency, tuple[str, ...]]] = found,
            colours: tuple[str, ...] = colours,
        ) -> tuple[str, Figures]:
            _, out, deficiency, _ = found[k]
            message = f"{_colours(colours)} all look like {out} under simulated {deficiency}"
            every = tuple(sorted({d for _, _, d, _ in found}))
            return message, CvdCollisionFigures(out, deficiency, every, colours)

        c.fold(
            rule,
            icons,
            [j for j, *_ in found],
            [float(len(names)) for *_, names in found],
            build,
            locations=c.group_locations(icons, colour_first=True),
            rows=tuple(sorted(rows_of[colours])),
        )


def severity(finding: Finding) -> tuple[int, float]:
    """How bad a root cause is, for ordering: smaller first.

    Collisions of many colours lead (the more colours, the worse), then
    confusions of roles, then paints newly failing or below the threshold
    (least contrast first), then losses by size, then the other rules.
    """
    match finding.figures:
        case CollisionFigures(colours=n) | CvdCollisionFigures(colours=n):
            return 0, -float(n) - len(finding.icons) / 1e9
        case ConfusionFigures(delta_e=de):
            return 1, de
        case ContrastFigures(gain=gain) if finding.rule is Rule.LOSS:
            return 3, gain
        case ContrastFigures(contrast=contrast):
            return 2, contrast
        case DriftFigures(drift=d) | RenderDriftFigures(drift=d):
            return 4, -d
        case SeparationFigures(delta_e=de):
            return 5, de
        case ThinStrokeFigures(size_contrast=sc):
            return 5, sc
        case _:
            return 6, 0.0


def ranked(findings: Iterable[Finding]) -> list[Finding]:
    """``findings`` worst root cause first (:func:`severity`); ties keep their order."""
    return sorted(findings, key=severity)


_RULES = {
    Rule.LOSS: _contrast,
    Rule.BELOW_THRESHOLD: _contrast,
    Rule.NEWLY_FAILING: _contrast,
    Rule.COLLISION: _collisions,
    Rule.NEW_COLLISION: _collisions,
    Rule.SEPARATION: _separation,
    Rule.UNRENDERABLE: _unrenderable,
    Rule.FIXED_COLOUR: _fixed_colour,
    Rule.NOT_AUDITED: _not_audited,
    Rule.DRIFT: _drift,
    Rule.LOCK: _drift,
    Rule.CONFUSION: _confusion,
    Rule.THIN_STROKES: _thin_strokes,
    Rule.CVD_COLLISION: _cvd_collision,
    Rule.CVD_CONFUSION: _confusion,
    Rule.RENDER_DRIFT: _render_drift,
    Rule.NEAR_DUPLICATE: _collisions,
}
