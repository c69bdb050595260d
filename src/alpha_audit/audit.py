"""Composite every icon on every canvas and measure what the coefficient changes.

Pure computation: :func:`audit` returns an :class:`AuditResult` of numpy arrays
and findings; it never prints.  Shapes: ``n`` icons x ``m`` canvases.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    CONTRAST_TOLERANCE,
    DELTA_E_TOLERANCE,
    composite_extended,
    contrast_from_luminance,
    delta_e_2000,
    pack_8bit,
    relative_luminance,
    to_8bit,
)
from alpha_audit.load.svg import IconProblem
from alpha_audit.model import IconSet, Theme

__all__ = [
    "AuditResult",
    "CanvasSummary",
    "Collision",
    "Row",
    "Separation",
    "Summary",
    "audit",
    "find_collisions",
]


@dataclass(frozen=True)
class Row:
    """One icon on one canvas."""

    icon: str
    canvas: str
    source: str
    background: str
    alpha: float
    output: str
    contrast_ref: float
    contrast: float
    gain: float
    passes_ref: bool
    passes: bool
    newly_passes: bool
    loss: bool
    newly_fails: bool


@dataclass(frozen=True)
class Collision:
    """Distinct source colours that give the same 8-bit output on one canvas."""

    canvas: str
    output: str
    sources: tuple[str, ...]
    icons: tuple[str, ...]
    new: bool = True  # False when the same sources already collide at alpha = 1


@dataclass(frozen=True)
class Separation:
    """The closest pair of distinct source colours on one canvas (CIEDE2000)."""

    canvas: str
    delta_e: float
    delta_e_ref: float
    icons: tuple[str, str]
    sources: tuple[str, str]
    decreases: int  # pairs whose CIEDE2000 is smaller than at alpha = 1
    pairs: int


@dataclass(frozen=True)
class CanvasSummary:
    """Per-canvas figures for the summary table."""

    canvas: str
    background: str
    mode: str
    icons: int
    mean_gain: float
    passing_ref: int
    passing: int
    newly_pass: int
    newly_fail: int
    losses: int
    max_loss: float
    worst_icon: str | None
    collisions: int
    separation: Separation | None


@dataclass(frozen=True)
class Summary:
    """Whole-audit figures (the JSON ``summary``)."""

    combinations: int
    increase_pct: float
    decrease_pct: float
    unchanged_pct: float
    mean_gain: float
    newly_pass: int
    newly_fail: int
    losses: int
    max_loss: float
    collisions: int
    new_collisions: int
    min_delta_e: float | None


def _hex(packed: int) -> str:
    return f"#{packed:06x}"


def find_collisions(
    output_codes: NDArray[np.uint8],
    source_keys: NDArray[np.int64],
) -> list[tuple[int, int, NDArray[np.intp]]]:
    """Groups of icons whose distinct sources share one 8-bit output, per canvas.

    ``output_codes`` is ``(n, m, 3)``, ``source_keys`` identifies each icon's
    source colour ``(n,)``.  Returns ``(canvas index, packed output, icon indices)``.
    """
    m = output_codes.shape[1]
    packed = pack_8bit(output_codes)  # (n, m)
    found = []
    for j in range(m):
        outputs = packed[:, j]
        order = np.lexsort((source_keys, outputs))
        sorted_out = outputs[order]
        starts = np.flatnonzero(np.r_[True, sorted_out[1:] != sorted_out[:-1]])
        for group in np.split(order, starts[1:]):
            if len(np.unique(source_keys[group])) > 1:
                found.append((j, int(outputs[group[0]]), np.sort(group)))
    return found


@dataclass(frozen=True)
class AuditResult:
    """Every number of one theme x icon-set audit; see :func:`audit`."""

    theme: Theme
    iconset: IconSet
    threshold: float
    alpha: NDArray[np.float64]  # (n,)
    output: NDArray[np.float64]  # (n, m, 3) linear, clipped
    output_codes: NDArray[np.uint8]  # (n, m, 3)
    contrast_ref: NDArray[np.float64]  # (n, m), alpha = 1
    contrast: NDArray[np.float64]  # (n, m)
    collisions: tuple[Collision, ...]
    separations: tuple[Separation, ...]
    problems: tuple[IconProblem, ...] = ()
    tolerance: float = CONTRAST_TOLERANCE

    @property
    def gain(self) -> NDArray[np.float64]:
        """``contrast - contrast_ref``."""
        return self.contrast - self.contrast_ref

    @property
    def loss(self) -> NDArray[np.bool_]:
        """Contrast decreased by more than the tolerance."""
        return self.gain < -self.tolerance

    @property
    def increase(self) -> NDArray[np.bool_]:
        """Contrast increased by more than the tolerance."""
        return self.gain > self.tolerance

    @property
    def passes_ref(self) -> NDArray[np.bool_]:
        """At or above the threshold at alpha = 1."""
        return self.contrast_ref >= self.threshold

    @property
    def passes(self) -> NDArray[np.bool_]:
        """At or above the threshold at the icon's alpha."""
        return self.contrast >= self.threshold

    @property
    def newly_passes(self) -> NDArray[np.bool_]:
        """Below the threshold at alpha = 1, at or above it at the icon's alpha."""
        return self.passes & ~self.passes_ref

    @property
    def newly_fails(self) -> NDArray[np.bool_]:
        """At or above the threshold at alpha = 1, below it at the icon's alpha."""
        return self.passes_ref & ~self.passes

    def rows(self) -> Iterator[Row]:
        """Icon x canvas rows in stable order (canvas order, then icon order)."""
        icons, canvases = self.iconset.icons, self.theme.canvases
        packed = pack_8bit(self.output_codes)
        gain = self.gain
        flags = (self.passes_ref, self.passes, self.newly_passes, self.loss, self.newly_fails)
        for j, canvas in enumerate(canvases):
            for i, icon in enumerate(icons):
                pr, p, npass, loss, nfail = (bool(f[i, j]) for f in flags)
                yield Row(
                    icon=icon.name,
                    canvas=canvas.name,
                    source=icon.color,
                    background=canvas.color,
                    alpha=float(self.alpha[i]),
                    output=_hex(int(packed[i, j])),
                    contrast_ref=float(self.contrast_ref[i, j]),
                    contrast=float(self.contrast[i, j]),
                    gain=float(gain[i, j]),
                    passes_ref=pr,
                    passes=p,
                    newly_passes=npass,
                    loss=loss,
                    newly_fails=nfail,
                )

    @cached_property
    def summary(self) -> Summary:
        """Whole-audit summary figures."""
        gain = self.gain
        total = gain.size
        losses = self.loss
        separations = [s.delta_e for s in self.separations]
        pct = (lambda k: 100.0 * float(k) / total) if total else (lambda k: 0.0)
        n_inc, n_dec = int(self.increase.sum()), int(losses.sum())
        return Summary(
            combinations=int(total),
            increase_pct=pct(n_inc),
            decrease_pct=pct(n_dec),
            unchanged_pct=pct(total - n_inc - n_dec),
            mean_gain=float(gain.mean()) if total else 0.0,
            newly_pass=int(self.newly_passes.sum()),
            newly_fail=int(self.newly_fails.sum()),
            losses=n_dec,
            max_loss=float(-gain[losses].min()) if n_dec else 0.0,
            collisions=len(self.collisions),
            new_collisions=sum(c.new for c in self.collisions),
            min_delta_e=min(separations) if separations else None,
        )

    def canvas_summaries(self) -> list[CanvasSummary]:
        """One :class:`CanvasSummary` per canvas, in theme order."""
        out = []
        gain = self.gain
        by_canvas = {s.canvas: s for s in self.separations}
        for j, canvas in enumerate(self.theme.canvases):
            g = gain[:, j]
            losses = self.loss[:, j]
            worst = int(np.argmin(g)) if losses.any() else None
            out.append(
                CanvasSummary(
                    canvas=canvas.name,
                    background=canvas.color,
                    mode=str(canvas.mode),
                    icons=int(g.size),
                    mean_gain=float(g.mean()) if g.size else 0.0,
                    passing_ref=int(self.passes_ref[:, j].sum()),
                    passing=int(self.passes[:, j].sum()),
                    newly_pass=int(self.newly_passes[:, j].sum()),
                    newly_fail=int(self.newly_fails[:, j].sum()),
                    losses=int(losses.sum()),
                    max_loss=float(-g[worst]) if worst is not None else 0.0,
                    worst_icon=self.iconset.icons[worst].name if worst is not None else None,
                    collisions=sum(c.canvas == canvas.name for c in self.collisions),
                    separation=by_canvas.get(canvas.name),
                )
            )
        return out


def _separations(
    theme: Theme,
    iconset: IconSet,
    output: NDArray[np.float64],
) -> list[Separation]:
    """Closest pair of distinct source colours per canvas, at alpha and at 1."""
    icons = iconset.icons
    # One representative icon per distinct (source colour, alpha) style.
    styles: dict[tuple[str, float], int] = {}
    for i, icon in enumerate(icons):
        styles.setdefault((icon.color, icon.alpha), i)
    reps = np.array(sorted(styles.values()), dtype=np.intp)
    colors = [icons[i].color for i in reps]
    first, second = np.triu_indices(len(reps), k=1)
    distinct = np.array([colors[a] != colors[b] for a, b in zip(first, second, strict=True)], bool)
    first, second = first[distinct], second[distinct]
    if first.size == 0:
        return []
    sources = iconset.sources[reps]
    de_ref = delta_e_2000(sources[first], sources[second])  # (p,)
    out_reps = output[reps]  # (k, m, 3)
    de = delta_e_2000(out_reps[first], out_reps[second])  # (p, m)
    result = []
    for j, canvas in enumerate(theme.canvases):
        k = int(np.argmin(de[:, j]))
        a, b = int(reps[first[k]]), int(reps[second[k]])
        result.append(
            Separation(
                canvas=canvas.name,
                delta_e=float(de[k, j]),
                delta_e_ref=float(de_ref[k]),
                icons=(icons[a].name, icons[b].name),
                sources=(icons[a].color, icons[b].color),
                decreases=int((de[:, j] < de_ref - DELTA_E_TOLERANCE).sum()),
                pairs=int(first.size),
            )
        )
    return result


def audit(
    theme: Theme,
    iconset: IconSet,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    problems: tuple[IconProblem, ...] = (),
) -> AuditResult:
    """Composite every icon of ``iconset`` on every canvas of ``theme``.

    ``alpha`` overrides every icon's coefficient; ``threshold`` the theme's.
    Icons listed in ``problems`` (failed rasterisation) are left out.

    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("paper", "#ffffff"),))
    >>> icons = IconSet("s", (Icon("alert", "alert.svg", "#ee7733", 1.1),))
    >>> next(audit(theme, icons).rows()).output
    '#ec5a00'
    """
    if alpha is not None:
        iconset = iconset.with_alpha(alpha)
    broken = {p.icon for p in problems}
    if broken:
        iconset = replace(iconset, icons=tuple(i for i in iconset.icons if i.name not in broken))
    threshold = theme.threshold if threshold is None else float(threshold)
    sources = iconset.sources[:, np.newaxis, :]  # (n, 1, 3)
    backgrounds = theme.backgrounds[np.newaxis, :, :]  # (1, m, 3)
    alphas = iconset.alphas
    output = composite_extended(sources, backgrounds, alphas[:, np.newaxis])
    y_bg = relative_luminance(backgrounds)
    contrast_ref = contrast_from_luminance(relative_luminance(sources), y_bg)
    contrast = contrast_from_luminance(relative_luminance(output), y_bg)
    codes = to_8bit(output)

    # Distinct sources at full precision: two rgb() colours may share an 8-bit code.
    source_keys = np.unique(iconset.sources, axis=0, return_inverse=True)[1].reshape(-1)
    ref_codes = to_8bit(np.broadcast_to(sources, output.shape))
    ref_pairs = {
        (j, frozenset(source_keys[g].tolist()))
        for j, _, g in find_collisions(ref_codes, source_keys)
    }
    collisions = []
    for j, packed, group in find_collisions(codes, source_keys):
        icons = [iconset.icons[i] for i in group]
        collisions.append(
            Collision(
                canvas=theme.canvases[j].name,
                output=_hex(packed),
                sources=tuple(sorted({i.color for i in icons})),
                icons=tuple(i.name for i in icons),
                new=(j, frozenset(source_keys[group].tolist())) not in ref_pairs,
            )
        )
    return AuditResult(
        theme=theme,
        iconset=iconset,
        threshold=threshold,
        alpha=alphas,
        output=output,
        output_codes=codes,
        contrast_ref=contrast_ref,
        contrast=contrast,
        collisions=tuple(collisions),
        separations=tuple(_separations(theme, iconset, output)),
        problems=tuple(problems),
    )
