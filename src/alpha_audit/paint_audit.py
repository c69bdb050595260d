"""Audit what ships: every (icon, paint, canvas) with its pipeline, size and colour drift.

Builds on :mod:`alpha_audit.load.paint_masks`: each icon's paints grouped by
colour and opacity, with their coverage at every raster size.  For a paint of
source ``Cs`` at opacity ``o`` on canvas ``Cb`` with coefficient ``a``:

* displayed colour -- :func:`~alpha_audit.color.composite.composite_paint`
  (``linear``: ``o clip(Cb + a (Cs - Cb)) + (1 - o) Cb``; ``css``: the encoded
  blend with ``a o``, then 8-bit);
* contrast at ``a`` and at ``a = 1`` (the reference), against the canvas;
* drift -- CIEDE2000 between the colour shown at ``a = 1`` and at ``a``, and
  the OKLCH hue shift between them.  For an opaque paint the colour at
  ``a = 1`` is the source itself; for a translucent one, measuring from the
  source would charge the paint's own opacity to alpha;
* per size, ``q50``, the full share and the size contrast
  (:mod:`alpha_audit.color.coverage`).

Rules over these figures (:func:`paint_findings`, rules of
:data:`~alpha_audit.policy.PAINT_RULES`): ``fixed-colour``,
``not-audited``, ``drift``, ``lock``, ``confusion``, ``thin-strokes``,
``cvd-collision`` and ``cvd-confusion`` (docs/model.md).  Pure computation:
nothing is printed.  Shapes: ``p`` paint rows (icon x paint group) by ``m``
canvases by ``k`` sizes.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from alpha_audit.audit import MAX_COMBINATIONS
from alpha_audit.color import (
    CONTRAST_TOLERANCE,
    DEFICIENCIES,
    PIPELINES,
    Deficiency,
    Pipeline,
    composite_paint,
    contrast_ratio,
    delta_e_2000,
    delta_e_2000_lab,
    hex_to_linear,
    hue_shift,
    linear_to_hex,
    linear_to_lab,
    simulate_cvd,
    to_8bit,
)
from alpha_audit.color.nearest import delta_e_2000_lightness_key, pairs_below
from alpha_audit.errors import InputError, UsageError
from alpha_audit.load.paint_masks import PaintSet
from alpha_audit.load.paints import CURRENT_COLOR
from alpha_audit.model import Icon, IconSet, Theme
from alpha_audit.policy import (
    PAINT_RULES,
    Policy,
    Rule,
    confusion_breaks,
    drift_breaks,
    size_contrast_floor,
)

__all__ = [
    "LOCK_TOLERANCE",
    "MAX_SIZE_CELLS",
    "PaintAudit",
    "PaintFinding",
    "PaintRow",
    "SizeFigures",
    "audit_paints",
    "check_pipeline",
    "paint_findings",
    "resolve_pipeline",
]

# Bounds on one paint audit.  Rows are the manifest audit's combinations cap
# (alpha_audit.audit.MAX_COMBINATIONS) counted per paint; size figures hold a
# (rows, sizes, 3) float64 array and its temporaries, ~200 MB at the cap.
MAX_SIZE_CELLS = 2_000_000

# A locked (brand) colour may move by less than one just-noticeable
# difference: CIEDE2000 = 1 is the usual reading of one JND.
LOCK_TOLERANCE = 1.0


def resolve_pipeline(*choices: str | None) -> Pipeline:
    """The first pipeline given, in precedence order (``--pipeline``, config, icon set, theme).

    ``linear`` when none is given; unknown names raise :class:`UsageError`.

    >>> resolve_pipeline(None, "css", "linear")
    'css'
    """
    for choice in choices:
        if choice is None:
            continue
        name = choice.strip().lower()
        if name not in PIPELINES:
            raise UsageError(f"unknown pipeline {choice!r}; use one of: {', '.join(PIPELINES)}")
        return name
    return "linear"


_CSS_WAY_OUT = (
    "CSS opacity is limited to [0, 1]; use pipeline: linear (WebGL, an SVG filter in "
    "linearRGB) or export per-theme colours (docs/model.md, 'Pipelines')"
)


def check_pipeline(iconset: IconSet, pipeline: Pipeline, alpha: float | None = None) -> None:
    """Refuse coefficients ``pipeline`` cannot draw: under ``css``, alpha outside [0, 1].

    ``alpha`` is the override of every icon's (``--alpha``), a usage error; else the
    error names the icon and its manifest line.  Both name the pipeline and the
    way out.
    """
    if pipeline != "css":
        return
    if alpha is not None:
        if not 0.0 <= alpha <= 1.0:
            raise UsageError(f"`alpha` {alpha:g} cannot be drawn by pipeline css: {_CSS_WAY_OUT}")
        return
    for icon in iconset.icons:
        if not 0.0 <= icon.alpha <= 1.0:
            raise InputError(
                f"icon {icon.name!r} has alpha {icon.alpha:g}, which pipeline css cannot "
                f"draw: {_CSS_WAY_OUT}",
                path=iconset.path,
                line=icon.alpha_line,
            )


@dataclass(frozen=True)
class SizeFigures:
    """One paint on one canvas at one raster size."""

    q50: float
    full_share: float
    contrast: float


@dataclass(frozen=True)
class PaintRow:
    """One paint group of one icon on one canvas (JSON schema ``alpha-audit.check/2``)."""

    icon: str
    paint: str  # "currentColor" or the element's own "#rrggbb"
    kinds: tuple[str, ...]  # "fill", "stroke"
    source: str  # the colour drawn: the manifest's for currentColor
    opacity: float
    canvas: str
    background: str
    alpha: float
    pipeline: Pipeline
    output: str
    contrast_ref: float
    contrast: float
    gain: float
    drift: float
    hue_shift: float | None  # None where the hue is powerless (achromatic)
    sizes: Mapping[int, SizeFigures] = field(default_factory=dict)
    passes_ref: bool = False
    passes: bool = False
    loss: bool = False

    @property
    def fixed(self) -> bool:
        """Whether the paint is hard-coded in the SVG (it will not follow the theme)."""
        return self.paint != CURRENT_COLOR

    @property
    def newly_passes(self) -> bool:
        """Below the threshold at alpha = 1, at or above it at the icon's alpha."""
        return self.passes and not self.passes_ref

    @property
    def newly_fails(self) -> bool:
        """At or above the threshold at alpha = 1, below it at the icon's alpha."""
        return self.passes_ref and not self.passes


@dataclass(frozen=True)
class PaintFinding:
    """A paint rule's objection; ``rule`` is one of :data:`~alpha_audit.policy.PAINT_RULES`."""

    rule: Rule
    canvas: str | None
    icons: tuple[str, ...]
    message: str
    numbers: Mapping[str, float | str] = field(default_factory=dict)
    paint: str | None = None
    element: str | None = None
    line: int | None = None


@dataclass(frozen=True)
class _Entry:
    icon: Icon
    paint: str
    kinds: tuple[str, ...]
    source: str
    opacity: float


@dataclass(frozen=True)
class PaintAudit:
    """Every number of one theme x icon-set paint audit; see :func:`audit_paints`."""

    theme: Theme
    iconset: IconSet
    paints: PaintSet
    pipeline: Pipeline
    threshold: float
    entries: tuple[_Entry, ...]
    sizes: tuple[int, ...]
    sources: NDArray[np.float64]  # (p, 3) linear
    opacity: NDArray[np.float64]  # (p,)
    alpha: NDArray[np.float64]  # (p,)
    output: NDArray[np.float64]  # (p, m, 3) linear, displayed
    reference: NDArray[np.float64]  # (p, m, 3) displayed at a = 1
    contrast_ref: NDArray[np.float64]  # (p, m)
    contrast: NDArray[np.float64]  # (p, m)
    drift: NDArray[np.float64]  # (p, m)
    hue_shift: NDArray[np.float64]  # (p, m), NaN where achromatic
    q50: NDArray[np.float64]  # (p, k)
    full_share: NDArray[np.float64]  # (p, k)
    size_contrast: NDArray[np.float64]  # (p, m, k)
    tolerance: float = CONTRAST_TOLERANCE

    @property
    def gain(self) -> NDArray[np.float64]:
        """``contrast - contrast_ref``, ``(p, m)``."""
        return self.contrast - self.contrast_ref

    @property
    def passes_ref(self) -> NDArray[np.bool_]:
        """At or above the threshold at alpha = 1."""
        return self.contrast_ref >= self.threshold

    @property
    def passes(self) -> NDArray[np.bool_]:
        """At or above the threshold at the icon's alpha."""
        return self.contrast >= self.threshold

    @property
    def loss(self) -> NDArray[np.bool_]:
        """Contrast decreased by more than the float tolerance."""
        return self.gain < -self.tolerance

    @property
    def newly_fails(self) -> NDArray[np.bool_]:
        """At or above the threshold at alpha = 1, below it at the icon's alpha."""
        return self.passes_ref & ~self.passes

    def rows(self) -> Iterator[PaintRow]:
        """Rows in stable order: canvas order, then icon order, then paint order."""
        # Python lists, indexed once per cell: numpy scalar indexing costs ten times more.
        codes = to_8bit(self.output).tolist()
        contrast_ref, contrast = self.contrast_ref.tolist(), self.contrast.tolist()
        drift, hue_shift, alpha = self.drift.tolist(), self.hue_shift.tolist(), self.alpha.tolist()
        q50, full_share = self.q50.tolist(), self.full_share.tolist()
        size_contrast = self.size_contrast.tolist()
        passes_ref, passes, loss = (a.tolist() for a in (self.passes_ref, self.passes, self.loss))
        for j, canvas in enumerate(self.theme.canvases):
            for p, e in enumerate(self.entries):
                shift = hue_shift[p][j]
                yield PaintRow(
                    icon=e.icon.name,
                    paint=e.paint,
                    kinds=e.kinds,
                    source=e.source,
                    opacity=e.opacity,
                    canvas=canvas.name,
                    background=canvas.color,
                    alpha=alpha[p],
                    pipeline=self.pipeline,
                    output="#{:02x}{:02x}{:02x}".format(*codes[p][j]),
                    contrast_ref=contrast_ref[p][j],
                    contrast=contrast[p][j],
                    gain=contrast[p][j] - contrast_ref[p][j],
                    drift=drift[p][j],
                    hue_shift=None if math.isnan(shift) else shift,
                    sizes={
                        s: SizeFigures(q50[p][k], full_share[p][k], size_contrast[p][j][k])
                        for k, s in enumerate(self.sizes)
                    },
                    passes_ref=passes_ref[p][j],
                    passes=passes[p][j],
                    loss=loss[p][j],
                )

    @cached_property
    def worst_drift(self) -> dict[str, tuple[float, str, str]]:
        """Per canvas: the largest drift with its icon and paint (for the table)."""
        out: dict[str, tuple[float, str, str]] = {}
        if not self.entries:
            return out
        for j, canvas in enumerate(self.theme.canvases):
            p = int(np.argmax(self.drift[:, j]))
            e = self.entries[p]
            out[canvas.name] = (float(self.drift[p, j]), e.icon.name, e.paint)
        return out


def audit_paints(
    theme: Theme,
    iconset: IconSet,
    paints: PaintSet,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    pipeline: Pipeline = "linear",
) -> PaintAudit:
    """Composite every paint of every icon on every canvas under ``pipeline``.

    ``currentColor`` paints take the icon's manifest colour; fixed colours are
    audited as themselves.  Icons missing from ``paints`` (problems) are left
    out.  Under ``css``, alpha outside [0, 1] raises :class:`InputError`.
    """
    check_pipeline(iconset, pipeline, alpha)
    if alpha is not None:
        iconset = iconset.with_alpha(alpha)
    threshold = theme.threshold if threshold is None else float(threshold)
    sizes = tuple(iconset.sizes)
    entries: list[_Entry] = []
    linear: list[NDArray[np.float64]] = []  # the exact source (a token's oklch is not its hex)
    q50_rows, share_rows = [], []
    for icon in iconset.icons:
        measured = paints.icons.get(icon.name)
        if measured is None:
            continue
        for cov in measured.coverage:
            g = cov.group
            kinds = tuple(sorted({p.kind for p in g.paints}))
            source = icon.color if g.color == CURRENT_COLOR else g.color
            entries.append(_Entry(icon, g.color, kinds, source, g.opacity))
            own = g.color == CURRENT_COLOR
            linear.append(np.array(icon.linear) if own else hex_to_linear(g.color))
            q50_rows.append([cov.sizes[s].q50 if s in cov.sizes else np.nan for s in sizes])
            share_rows.append(
                [cov.sizes[s].full_share if s in cov.sizes else np.nan for s in sizes]
            )
    p, m, k = len(entries), len(theme.canvases), len(sizes)
    if p * m > MAX_COMBINATIONS or p * m * k > MAX_SIZE_CELLS:
        raise InputError(
            f"{p} paints x {m} canvases x {k} sizes is more than this check audits "
            f"({MAX_COMBINATIONS:,} paint rows, {MAX_SIZE_CELLS:,} paint x canvas x size "
            "figures); split the theme or the icon set, or give fewer sizes",
            path=iconset.path,
        )
    sources = np.array(linear, dtype=np.float64).reshape(p, 3)
    opacity = np.array([e.opacity for e in entries], dtype=np.float64)
    alphas = np.array([e.icon.alpha for e in entries], dtype=np.float64)
    q50 = np.array(q50_rows, dtype=np.float64).reshape(p, k)
    full = np.array(share_rows, dtype=np.float64).reshape(p, k)
    bg = theme.backgrounds[np.newaxis, :, :]  # (1, m, 3)
    s3 = sources[:, np.newaxis, :]
    output = composite_paint(s3, bg, alphas[:, None], opacity[:, None], pipeline)
    reference = composite_paint(s3, bg, np.ones((p, 1)), opacity[:, None], pipeline)
    # Size contrast: the paint at opacity o * q50, sizes on the last axis.
    q = np.nan_to_num(q50, nan=0.0)[:, np.newaxis, :] * opacity[:, None, None]  # (p, 1, k)
    at_size = composite_paint(
        s3[:, :, np.newaxis, :], bg[:, :, np.newaxis, :], alphas[:, None, None], q, pipeline
    )  # (p, m, k, 3)
    size_contrast = contrast_ratio(at_size, bg[:, :, np.newaxis, :])
    size_contrast = np.where(np.isnan(q50)[:, np.newaxis, :], np.nan, size_contrast)
    return PaintAudit(
        theme=theme,
        iconset=iconset,
        paints=paints,
        pipeline=pipeline,
        threshold=threshold,
        entries=tuple(entries),
        sizes=sizes,
        sources=sources,
        opacity=opacity,
        alpha=alphas,
        output=output,
        reference=reference,
        contrast_ref=contrast_ratio(reference, bg),
        contrast=contrast_ratio(output, bg),
        drift=delta_e_2000(reference, output).reshape(p, m),
        hue_shift=hue_shift(reference, output).reshape(p, m),
        q50=q50,
        full_share=full,
        size_contrast=size_contrast.reshape(p, m, k),
    )


def paint_findings(result: PaintAudit, policy: Policy) -> list[PaintFinding]:
    """Findings of ``policy``'s paint rules, in rule order, then canvas and icon order.

    Limits come from the policy (``min_delta_e``, ``max_drift``,
    ``min_size_contrast``, default the threshold); locked names from the icon
    set (``lock:``).  Exemptions are the gate's business.
    """
    rules = policy.rules & PAINT_RULES
    out: list[PaintFinding] = []
    if Rule.FIXED_COLOUR in rules:
        out += _fixed_colour(result)
    if Rule.NOT_AUDITED in rules:
        out += _not_audited(result)
    if Rule.DRIFT in rules:
        everything = np.ones(len(result.entries), dtype=bool)
        out += _drift(result, Rule.DRIFT, policy.max_drift, everything)
    if Rule.LOCK in rules:
        out += _drift(result, Rule.LOCK, LOCK_TOLERANCE, locked_entries(result))
    if Rule.CONFUSION in rules:
        out += _confusion(result, policy.min_delta_e, None)
    if Rule.THIN_STROKES in rules:
        limit = result.threshold if policy.min_size_contrast is None else policy.min_size_contrast
        out += _thin_strokes(result, limit)
    if Rule.CVD_COLLISION in rules:
        for deficiency in DEFICIENCIES:
            out += _cvd_collisions(result, deficiency)
    if Rule.CVD_CONFUSION in rules:
        for deficiency in DEFICIENCIES:
            out += _confusion(result, policy.min_delta_e, deficiency)
    return out


def locked_entries(result: PaintAudit) -> NDArray[np.bool_]:
    """Which paint rows ``lock`` judges: a locked icon's, or a locked palette colour's."""
    names = result.iconset.locked
    return np.array(
        [
            e.icon.name in names or (e.paint == CURRENT_COLOR and e.icon.color_name in names)
            for e in result.entries
        ],
        dtype=bool,
    ).reshape(len(result.entries))


def _role(icon: Icon) -> str:
    """The palette role of an icon's colour: its palette name, else the colour itself."""
    return icon.color_name or icon.color


def _fixed_colour(result: PaintAudit) -> Iterator[PaintFinding]:
    seen: set[tuple[str, str]] = set()
    for e in result.entries:
        if e.paint == CURRENT_COLOR or (e.icon.name, e.paint) in seen:
            continue
        seen.add((e.icon.name, e.paint))
        first = next(
            p
            for c in result.paints.icons[e.icon.name].coverage
            for p in c.group.paints
            if p.color == e.paint
        )
        yield PaintFinding(
            Rule.FIXED_COLOUR,
            None,
            (e.icon.name,),
            f"{first.kind} {e.paint} of {first.element} is hard-coded: it is audited as itself "
            "and will not follow the theme",
            {"paint": e.paint},
            paint=e.paint,
            element=first.element,
            line=first.line,
        )


def _not_audited(result: PaintAudit) -> Iterator[PaintFinding]:
    for icon in result.iconset.icons:
        measured = result.paints.icons.get(icon.name)
        if measured is None:
            continue
        for u in measured.paints.unaudited:
            yield PaintFinding(
                Rule.NOT_AUDITED,
                None,
                (icon.name,),
                f"{u.element}: {u.reason}",
                element=u.element,
                line=u.line,
            )


def _drift(
    result: PaintAudit, rule: Rule, limit: float, selected: NDArray[np.bool_]
) -> Iterator[PaintFinding]:
    over = drift_breaks(result.drift, limit) & selected[:, np.newaxis]
    for j, canvas in enumerate(result.theme.canvases):
        for p in np.flatnonzero(over[:, j]):
            e = result.entries[int(p)]
            d = float(result.drift[p, j])
            shown = linear_to_hex(result.output[p, j])
            what = "locked colour" if rule is Rule.LOCK else "colour"
            yield PaintFinding(
                rule,
                canvas.name,
                (e.icon.name,),
                f"{what} {e.source} is shown as {shown} at alpha {result.alpha[p]:g}: "
                f"CIEDE2000 {d:.1f} > {limit:g}",
                {"drift": d, "limit": limit, "source": e.source, "output": shown},
                paint=e.paint,
            )


def _thin_strokes(result: PaintAudit, limit: float) -> Iterator[PaintFinding]:
    below = result.size_contrast < size_contrast_floor(limit)  # (p, m, k); NaN never is
    for j, canvas in enumerate(result.theme.canvases):
        for p in np.flatnonzero(below[:, j, :].any(axis=1)):
            e = result.entries[int(p)]
            k = int(np.nanargmin(result.size_contrast[p, j]))
            size = result.sizes[k]
            c = float(result.size_contrast[p, j, k])
            yield PaintFinding(
                Rule.THIN_STROKES,
                canvas.name,
                (e.icon.name,),
                f"at {size}px half the ink of {e.paint} is at coverage <= "
                f"{result.q50[p, k]:.2f}: size contrast {c:.2f} < {limit:g}:1 "
                f"(colour contrast {result.contrast[p, j]:.2f})",
                {"size": size, "q50": float(result.q50[p, k]), "size_contrast": c},
                paint=e.paint,
            )


def has_role(icon: Icon) -> bool:
    """Whether the icon's colour is a palette role ``confusion`` compares (issue 11: "two
    palette colours"): a colour the manifest names in its palette.  Unnamed colours (a
    brand set where every logo has its own hex) are no roles, so thousands of brand
    colours never turn into millions of pairs."""
    return icon.color_name is not None


def role_of(icon: Icon) -> str:
    """The palette role ``confusion`` compares: the palette name, else the colour itself."""
    return _role(icon)


def _styles(result: PaintAudit) -> list[int]:
    """One entry per distinct (role, source, alpha) among currentColor paints.

    Roles are compared as solid colours (opacity 1): confusion is about the
    palette, not about one icon's translucent details.
    """
    seen: dict[tuple[str, str, float], int] = {}
    for p, e in enumerate(result.entries):
        if e.paint == CURRENT_COLOR and has_role(e.icon):
            seen.setdefault((_role(e.icon), e.source, e.icon.alpha), p)
    return sorted(seen.values())


def _confusion(
    result: PaintAudit, min_delta_e: float, deficiency: Deficiency | None
) -> Iterator[PaintFinding]:
    """Roles distinct at alpha 1 (CIEDE2000 >= min_delta_e) but not at the icons' alpha."""
    reps = np.array(_styles(result), dtype=np.intp)
    if reps.size < 2:
        return
    roles = np.unique(
        np.array([_role(result.entries[r].icon) for r in reps], dtype=object), return_inverse=True
    )[1].reshape(-1)
    bg = result.theme.backgrounds[np.newaxis, :, :]
    solid = composite_paint(result.sources[reps][:, None, :], bg, 1.0, 1.0, result.pipeline)
    shown = composite_paint(
        result.sources[reps][:, None, :], bg, result.alpha[reps][:, None], 1.0, result.pipeline
    )
    if deficiency is not None:
        solid, shown = simulate_cvd(solid, deficiency), simulate_cvd(shown, deficiency)
    # Only pairs closer than min_delta_e at alpha can be confused: found per canvas by
    # the exact lightness-pruned search (dE00 >= |dL|/S_L), never all pairs at once.
    hits_first, hits_second, hits_canvas, hits_de, hits_ref = [], [], [], [], []
    for j in range(len(result.theme.canvases)):
        lab = linear_to_lab(shown[:, j, :])

        def distance(
            x: NDArray[np.intp], y: NDArray[np.intp], lab: NDArray[np.float64] = lab
        ) -> NDArray[np.float64]:
            return delta_e_2000_lab(lab[x], lab[y])

        i, k, de_j = pairs_below(delta_e_2000_lightness_key(lab), distance, min_delta_e, roles)
        if i.size == 0:
            continue
        ref_j = delta_e_2000(solid[i, j, :], solid[k, j, :])
        keep = confusion_breaks(ref_j, de_j, min_delta_e)
        hits_first.append(i[keep])
        hits_second.append(k[keep])
        hits_canvas.append(np.full(int(keep.sum()), j))
        hits_de.append(de_j[keep])
        hits_ref.append(np.asarray(ref_j)[keep])
    if not hits_first:
        return
    first, second = reps[np.concatenate(hits_first)], reps[np.concatenate(hits_second)]
    canvas_of = np.concatenate(hits_canvas)
    de_hit, ref_hit = np.concatenate(hits_de), np.concatenate(hits_ref)
    rule = Rule.CONFUSION if deficiency is None else Rule.CVD_CONFUSION
    under = "" if deficiency is None else f" under simulated {deficiency}"
    for j, canvas in enumerate(result.theme.canvases):
        worst: dict[tuple[str, str], int] = {}
        for hit in np.flatnonzero(canvas_of == j):
            a, b = result.entries[first[hit]], result.entries[second[hit]]
            role_a, role_b = sorted((_role(a.icon), _role(b.icon)))
            key = (role_a, role_b)
            if key not in worst or de_hit[hit] < de_hit[worst[key]]:
                worst[key] = int(hit)
        for (r1, r2), q in sorted(worst.items()):
            a, b = result.entries[first[q]], result.entries[second[q]]
            yield PaintFinding(
                rule,
                canvas.name,
                (a.icon.name, b.icon.name),
                f"{r1} and {r2} are told apart at alpha 1 (CIEDE2000 {ref_hit[q]:.1f}) but "
                f"not at alpha {a.icon.alpha:g}/{b.icon.alpha:g} ({de_hit[q]:.1f} < "
                f"{min_delta_e:g}){under}",
                {
                    "delta_e_ref": float(ref_hit[q]),
                    "delta_e": float(de_hit[q]),
                    "min_delta_e": min_delta_e,
                    "roles": f"{r1},{r2}",
                    **({"deficiency": deficiency} if deficiency else {}),
                },
            )


def cvd_collision_groups(
    seen: NDArray[np.integer], ref: NDArray[np.integer], sources: list[str] | tuple[str, ...]
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


def _cvd_collisions(result: PaintAudit, deficiency: Deficiency) -> Iterator[PaintFinding]:
    """Distinct sources whose simulated displayed colours share an 8-bit code, new at alpha."""
    reps = _styles(result)
    if len(reps) < 2:
        return
    idx = np.array(reps, dtype=np.intp)
    bg = result.theme.backgrounds[np.newaxis, :, :]
    src = result.sources[idx][:, None, :]
    shown = composite_paint(src, bg, result.alpha[idx][:, None], 1.0, result.pipeline)
    solid = composite_paint(src, bg, 1.0, 1.0, result.pipeline)
    seen = to_8bit(simulate_cvd(shown, deficiency))
    ref = to_8bit(simulate_cvd(solid, deficiency))
    sources = [result.entries[p].source for p in idx]
    for j, canvas in enumerate(result.theme.canvases):
        for code, members in cvd_collision_groups(seen[:, j], ref[:, j], sources):
            colours = sorted({sources[r] for r in members})
            out = "#{:02x}{:02x}{:02x}".format(*code)
            yield PaintFinding(
                Rule.CVD_COLLISION,
                canvas.name,
                tuple(result.entries[idx[r]].icon.name for r in members),
                f"{', '.join(colours)} all look like {out} under simulated {deficiency}",
                {"output": out, "deficiency": deficiency},
            )
