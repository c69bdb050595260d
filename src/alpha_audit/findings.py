"""What each rule objects to in one audit's rows: :class:`Finding` objects.

:func:`findings_for` applies every rule a :class:`~alpha_audit.policy.Policy`
fails on or reports (:attr:`~alpha_audit.policy.Policy.reported`) to an
:class:`~alpha_audit.rows.AuditResult` and returns one :class:`Finding` per
objection, naming its rule, theme, icon set, canvas, icon(s), numbers and the
files and lines that set the values involved.  Every figure comes from the
audit's rows (its pipeline's colours).  Exemptions are applied here; baselines
and the verdict are :mod:`alpha_audit.gate`'s.  Pure computation.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
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
from alpha_audit.model import Edit, Icon
from alpha_audit.policy import (
    Exemption,
    Policy,
    confusion_breaks,
    contrast_breaks,
    drift_breaks,
    size_contrast_floor,
)
from alpha_audit.rows import AuditResult
from alpha_audit.rules import Level, Rule

__all__ = [
    "LOCK_TOLERANCE",
    "Finding",
    "FindingKey",
    "cvd_collision_groups",
    "findings_for",
    "locked_rows",
    "role_rows",
]

# A locked (brand) colour may move by less than one just-noticeable
# difference: CIEDE2000 = 1 is the usual reading of one JND.
LOCK_TOLERANCE = 1.0

# (theme, icon set, rule, canvas, icons): what a baseline matches on.  Never a
# line number or a value, so editing a manifest does not invalidate a baseline.
FindingKey = tuple[str, str, str, str | None, tuple[str, ...]]


@dataclass(frozen=True)
class Finding:
    """One thing a rule objects to.

    ``numbers`` holds the figures a reviewer needs (contrast before and after,
    threshold, CIEDE2000, 8-bit output ...), ``files`` the icons' SVG files
    and ``lines`` the manifest lines that set each icon's colour or alpha;
    ``sources`` the (file, line) of each design token that sets a colour of
    the finding (icon colour first, then the canvas), where the fix goes.
    ``level`` is what the policy does with the rule; ``fixes`` index the
    report's fixes that answer this finding and ``edits`` are those known to
    clear it as exact text edits (both from :mod:`alpha_audit.fixes`).
    """

    rule: Rule
    theme: str
    iconset: str
    canvas: str | None
    icons: tuple[str, ...]
    message: str
    numbers: Mapping[str, float | str] = field(default_factory=dict)
    files: tuple[Path, ...] = ()
    manifest: Path | None = None
    lines: tuple[int, ...] = ()
    exemption: Exemption | None = None
    sources: tuple[tuple[Path, int], ...] = ()
    baselined: bool = False
    level: Level = Level.FAIL
    fixes: tuple[int, ...] = ()
    edits: tuple[Edit, ...] = ()

    @property
    def key(self) -> FindingKey:
        """Identity for baselines: theme, icon set, rule, canvas and icons."""
        return (self.theme, self.iconset, self.rule.value, self.canvas, self.icons)

    @property
    def fails(self) -> bool:
        """Whether this finding fails the gate (a failing rule, not exempt, not in the baseline)."""
        return self.level is Level.FAIL and self.exemption is None and not self.baselined


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


class _Collector:
    """Builds the findings of one audit, each with its locations and exemption."""

    def __init__(self, result: AuditResult, policy: Policy) -> None:
        self.result, self.policy = result, policy
        self.by_name = {i.name: i for i in result.iconset.icons}  # once: a brand set has thousands
        self.out: list[Finding] = []

    def token_sources(
        self, names: Sequence[str], canvas: str | None
    ) -> tuple[tuple[Path, int], ...]:
        """(file, line) of the design tokens setting the icons' colours, then the canvas's."""
        out: list[tuple[Path, int]] = []
        for name in names:
            icon = self.by_name.get(name)
            if icon is not None and icon.token_file is not None and icon.token_line is not None:
                out.append((Path(icon.token_file), icon.token_line))
        for c in self.result.theme.canvases:
            if c.name == canvas and c.file is not None and c.line is not None:
                out.append((Path(c.file), c.line))
        return tuple(dict.fromkeys(out))  # unique, first-seen order

    def add(
        self,
        rule: Rule,
        canvas: str | None,
        icons: tuple[str, ...],
        message: str,
        numbers: Mapping[str, float | str],
        files: tuple[Path, ...] | None = None,
    ) -> None:
        own_files, lines = _icon_refs(self.by_name, icons)
        self.out.append(
            Finding(
                rule=rule,
                theme=self.result.theme.name,
                iconset=self.result.iconset.name,
                canvas=canvas,
                icons=icons,
                message=message,
                numbers=dict(numbers),
                files=own_files if files is None else files,
                manifest=self.result.iconset.path,
                lines=lines,
                exemption=self.policy.exempt(rule, canvas, icons),
                sources=self.token_sources(icons, canvas),
                level=self.policy.level(rule),
            )
        )


def findings_for(result: AuditResult, policy: Policy) -> list[Finding]:
    """Every finding of the rules ``policy`` fails on or reports, exemptions applied.

    Order is stable: rules in :class:`~alpha_audit.rules.Rule` order; within a
    rule, canvas order, then row (icon, paint) order.
    """
    c = _Collector(result, policy)
    reported = policy.reported
    for rule in Rule:
        if rule in reported:
            _RULES[rule](c, rule)
    return c.out


_CONTRAST_TEMPLATES = {
    Rule.LOSS: "contrast drops {ref:.3f} -> {now:.3f} ({gain:+.4f}) at alpha {a:g}",
    Rule.NEWLY_FAILING: "passes {t:g}:1 at alpha 1 ({ref:.3f}) but not at alpha {a:g} ({now:.3f})",
    Rule.BELOW_THRESHOLD: "contrast {now:.3f} is below {t:g}:1 at alpha {a:g}",
}


def _contrast(c: _Collector, rule: Rule) -> None:
    """The per paint x canvas contrast rules."""
    r = c.result
    mask = contrast_breaks(rule, c.policy, r.contrast_ref, r.contrast, r.threshold, r.tolerance)
    canvases = r.theme.canvases
    for j, p in zip(*np.nonzero(mask.T), strict=True):  # canvas order, then row order
        p, j = int(p), int(j)
        e = r.entries[p]
        numbers: dict[str, float | str] = {
            "alpha": float(r.alpha[p]),
            "contrast_ref": float(r.contrast_ref[p, j]),
            "contrast": float(r.contrast[p, j]),
            "gain": float(r.gain[p, j]),
            "threshold": float(r.threshold),
            "background": canvases[j].color,
            "source": e.source,
            "paint": e.paint,
            "opacity": e.opacity,
        }
        message = _CONTRAST_TEMPLATES[rule].format(
            ref=numbers["contrast_ref"],
            now=numbers["contrast"],
            gain=numbers["gain"],
            a=numbers["alpha"],
            t=r.threshold,
        )
        if e.fixed or e.opacity != 1.0:
            message += f" (paint {e.paint} at opacity {e.opacity:g})"
        c.add(rule, canvases[j].name, (e.icon.name,), message, numbers)


def _collisions(c: _Collector, rule: Rule) -> None:
    """``collision`` (every shared output) or ``new-collision`` (not already at alpha 1).

    With both enabled a new collision is reported once, as ``collision``.
    """
    if rule is Rule.NEW_COLLISION and Rule.COLLISION in c.policy.reported:
        return
    for col in c.result.collisions:
        if rule is Rule.NEW_COLLISION and not col.new:
            continue
        give = "both give" if len(col.sources) == 2 else "all give"
        message = f"distinct colours {', '.join(col.sources)} {give} {col.output}" + (
            "" if col.new else " (already at alpha 1)"
        )
        numbers = {
            "output": col.output,
            "sources": ", ".join(col.sources),
            "new": str(col.new).lower(),
        }
        c.add(rule, col.canvas, col.icons, message, numbers)


def _separation(c: _Collector, rule: Rule) -> None:
    limit = c.policy.min_delta_e
    for s in c.result.separations:
        if s.delta_e < limit:
            message = (
                f"closest colours are CIEDE2000 {s.delta_e:.2f} apart "
                f"(at alpha 1: {s.delta_e_ref:.2f}); minimum {limit:g}"
            )
            numbers: dict[str, float | str] = {
                "delta_e": s.delta_e,
                "delta_e_ref": s.delta_e_ref,
                "min_delta_e": limit,
                "sources": ", ".join(s.sources),
            }
            c.add(rule, s.canvas, tuple(sorted(set(s.icons))), message, numbers)


def _unrenderable(c: _Collector, rule: Rule) -> None:
    for p in c.result.problems:  # broken icons are not in the audited set: name the file
        c.add(rule, None, (p.icon,), p.message, {}, files=(Path(p.file),))


def _fixed_colour(c: _Collector, rule: Rule) -> None:
    for e in c.result.entries:
        if not e.fixed:
            continue
        element = e.element or "an element"
        where = f" (line {e.line})" if e.line else ""
        c.add(
            rule,
            None,
            (e.icon.name,),
            f"{'/'.join(e.kinds)} {e.paint} of {element}{where} is hard-coded: it is audited "
            "as itself and will not follow the theme",
            {"paint": e.paint, "element": element + where},
        )


def _not_audited(c: _Collector, rule: Rule) -> None:
    for u in c.result.unaudited:
        where = f" (line {u.line})" if u.line else ""
        c.add(rule, None, (u.icon,), f"{u.element}: {u.reason}", {"element": u.element + where})


def _drift(c: _Collector, rule: Rule) -> None:
    r = c.result
    if rule is Rule.LOCK:
        limit, selected = LOCK_TOLERANCE, locked_rows(r)
    else:
        limit, selected = c.policy.max_drift, np.ones(len(r.entries), dtype=bool)
    over = drift_breaks(r.drift, limit) & selected[:, np.newaxis]
    what = "locked colour" if rule is Rule.LOCK else "colour"
    for j, canvas in enumerate(r.theme.canvases):
        for p in np.flatnonzero(over[:, j]).tolist():
            e = r.entries[p]
            d = float(r.drift[p, j])
            shown = linear_to_hex(r.output[p, j])
            c.add(
                rule,
                canvas.name,
                (e.icon.name,),
                f"{what} {e.source} is shown as {shown} at alpha {r.alpha[p]:g}: "
                f"CIEDE2000 {d:.1f} > {limit:g}",
                {"drift": d, "limit": limit, "source": e.source, "output": shown, "paint": e.paint},
            )


def _thin_strokes(c: _Collector, rule: Rule) -> None:
    r = c.result
    limit = r.threshold if c.policy.min_size_contrast is None else c.policy.min_size_contrast
    below = r.size_contrast < size_contrast_floor(limit)  # (p, m, k); NaN never is
    for j, canvas in enumerate(r.theme.canvases):
        for p in np.flatnonzero(below[:, j, :].any(axis=1)).tolist():
            e = r.entries[p]
            k = int(np.nanargmin(r.size_contrast[p, j]))
            size, sc = r.sizes[k], float(r.size_contrast[p, j, k])
            c.add(
                rule,
                canvas.name,
                (e.icon.name,),
                f"at {size}px half the ink of {e.paint} is at coverage <= {r.q50[p, k]:.2f}: "
                f"size contrast {sc:.2f} < {limit:g}:1 (colour contrast {r.contrast[p, j]:.2f})",
                {"size": size, "q50": float(r.q50[p, k]), "size_contrast": sc, "paint": e.paint},
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
    if rule is Rule.CONFUSION:
        _confusions(c, rule, None)
    else:
        for deficiency in DEFICIENCIES:
            _confusions(c, rule, deficiency)


def _confusions(c: _Collector, rule: Rule, deficiency: Deficiency | None) -> None:
    """Roles distinct at alpha 1 (CIEDE2000 >= min_delta_e) but not at the icons' alpha."""
    r, min_delta_e = c.result, c.policy.min_delta_e
    reps = np.array(role_rows(r), dtype=np.intp)
    if reps.size < 2:
        return
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
    under = "" if deficiency is None else f" under simulated {deficiency}"
    for j, canvas in enumerate(r.theme.canvases):
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
        for h in keep.tolist():
            one, two = sorted((entries[i[h]].role, entries[k[h]].role))
            if (one, two) not in worst or de[h] < de[worst[one, two]]:
                worst[one, two] = h
        for (r1, r2), h in sorted(worst.items()):
            a, b = entries[i[h]], entries[k[h]]
            c.add(
                rule,
                canvas.name,
                (a.icon.name, b.icon.name),
                f"{r1} and {r2} are told apart at alpha 1 (CIEDE2000 {ref[h]:.1f}) but not at "
                f"alpha {a.icon.alpha:g}/{b.icon.alpha:g} ({de[h]:.1f} < {min_delta_e:g}){under}",
                {
                    "delta_e_ref": float(ref[h]),
                    "delta_e": float(de[h]),
                    "min_delta_e": min_delta_e,
                    "roles": f"{r1},{r2}",
                    **({"deficiency": deficiency} if deficiency else {}),
                },
            )


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
    """Distinct roles' colours whose simulated outputs newly share an 8-bit code."""
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
    for deficiency in DEFICIENCIES:
        seen = to_8bit(simulate_cvd(shown, deficiency))
        ref = to_8bit(simulate_cvd(solid, deficiency))
        for j, canvas in enumerate(r.theme.canvases):
            for code, members in cvd_collision_groups(seen[:, j], ref[:, j], sources):
                colours = sorted({sources[m] for m in members})
                out = "#{:02x}{:02x}{:02x}".format(*code)
                c.add(
                    rule,
                    canvas.name,
                    tuple(sorted({r.entries[idx[m]].icon.name for m in members})),
                    f"{', '.join(colours)} all look like {out} under simulated {deficiency}",
                    {"output": out, "deficiency": deficiency},
                )


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
}
