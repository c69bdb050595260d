"""The figures a finding carries: one small typed record per rule family.

A :class:`~alpha_audit.findings.Finding` holds the figures of its worst
canvas as one of these frozen records; fixes, the gate's ordering and the
renderers read their fields.  A record's :meth:`to_dict` is its one wire form
(the ``numbers`` object of the JSON report, SARIF result properties, JUnit
details), in a stable key order; nothing reads a figure back from it.

A row a browser drew carries its :class:`~alpha_audit.observed.MeasuredPaint`
itself (``observed``), never a copy of its fields.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import TypeAlias

from alpha_audit.color import Deficiency
from alpha_audit.observed import MeasuredPaint

__all__ = [
    "CollisionFigures",
    "ConfusionFigures",
    "ContrastFigures",
    "CvdCollisionFigures",
    "DriftFigures",
    "ElementFigures",
    "Figures",
    "FixedPaintFigures",
    "NoFigures",
    "RenderDriftFigures",
    "SeparationFigures",
    "ThinStrokeFigures",
]

# A figure as written out: a number or a name.
Value: TypeAlias = float | str


def _observed(o: MeasuredPaint) -> dict[str, Value]:
    """What every finding of a row a browser drew writes out besides the row's own figures."""
    out: dict[str, Value] = {
        "story" if o.source_kind == "storybook" else "page": o.source,
        "state": o.state,
        "engine": o.engine,
        "dom_path": o.dom_path,
        "element": o.element,
        "match": str(o.match),
    }
    optional: dict[str, Value | None] = {
        "drawn": o.drawn,
        "basis": None if o.basis is None else str(o.basis),
        "around": o.around,
        "contrast_worst": o.contrast_worst,
        "contrast_median": o.contrast_median,
        "declared": o.declared,
        "declared_opacity": o.declared_opacity,
        "model_source": o.model_source,
        "model_alpha": o.model_alpha,
        "model_opacity": o.model_opacity,
        "render_drift": o.render_drift,
    }
    near = o.nearer
    if near is not None:
        optional |= {
            "model_contrast": near.contrast,
            "model_output": near.output,
            "model_pipeline": near.pipeline,
        }
    return out | {k: v for k, v in optional.items() if v is not None}


class _Plain:
    """A record written out as its fields in order, a tuple of names joined by ", "."""

    __slots__ = ()

    def to_dict(self) -> dict[str, Value]:
        """The figures as written out (JSON ``numbers``, SARIF properties)."""
        out: dict[str, Value] = {}
        for f in fields(self):  # type: ignore[arg-type]  # every subclass is a dataclass
            value = getattr(self, f.name)
            out[f.name] = ", ".join(value) if isinstance(value, tuple) else value
        return out


@dataclass(frozen=True, slots=True)
class ContrastFigures:
    """``loss``, ``below-threshold``, ``newly-failing``: one paint on its worst canvas.

    ``contrast_ref`` at alpha 1, ``contrast`` at ``alpha``, ``gain`` their
    difference; ``background`` the canvas colour, ``source`` the paint's
    colour, ``paint`` what the SVG paints with (``currentColor`` or its
    colour) at ``opacity``.  ``observed``: the paint a browser drew (the row
    is a page's).  ``gated`` is false for a loss reported, not gated.
    """

    alpha: float
    contrast_ref: float
    contrast: float
    gain: float
    threshold: float
    background: str
    source: str
    paint: str
    opacity: float
    observed: MeasuredPaint | None = None
    gated: bool = True

    def to_dict(self) -> dict[str, Value]:
        """The figures as written out (JSON ``numbers``, SARIF properties)."""
        out: dict[str, Value] = {
            "alpha": self.alpha,
            "contrast_ref": self.contrast_ref,
            "contrast": self.contrast,
            "gain": self.gain,
            "threshold": self.threshold,
            "background": self.background,
            "source": self.source,
            "paint": self.paint,
            "opacity": self.opacity,
        }
        if self.observed is not None:
            out |= _observed(self.observed)
        return out if self.gated else out | {"gated": "false"}


@dataclass(frozen=True, slots=True)
class RenderDriftFigures:
    """``render-drift``: a page draws another colour than the model predicts.

    ``drift`` is the CIEDE2000 from the drawn colour to the nearer prediction
    (``observed.render_drift``), ``tolerance`` the rule's limit.
    """

    observed: MeasuredPaint
    drift: float
    tolerance: float
    background: str
    source: str
    paint: str
    opacity: float

    def to_dict(self) -> dict[str, Value]:
        """The figures as written out (JSON ``numbers``, SARIF properties)."""
        return _observed(self.observed) | {
            "drift": self.drift,
            "tolerance": self.tolerance,
            "background": self.background,
            "source": self.source,
            "paint": self.paint,
            "opacity": self.opacity,
        }


@dataclass(frozen=True, slots=True)
class CollisionFigures:
    """``collision``, ``new-collision``, ``near-duplicate``: colours sharing one 8-bit output.

    ``delta_e_ref`` is the widest CIEDE2000 between two of ``sources`` at
    alpha 1; ``new`` whether they were told apart there.
    """

    output: str
    sources: tuple[str, ...]
    new: bool
    delta_e_ref: float

    @property
    def colours(self) -> int:
        """How many distinct colours collide."""
        return len(self.sources)

    def to_dict(self) -> dict[str, Value]:
        """The figures as written out (JSON ``numbers``, SARIF properties)."""
        return {
            "output": self.output,
            "sources": ", ".join(self.sources),
            "colours": self.colours,
            "new": str(self.new).lower(),
            "delta_e_ref": self.delta_e_ref,
        }


@dataclass(frozen=True, slots=True)
class CvdCollisionFigures:
    """``cvd-collision``: colours that look alike (``output``) under simulated ``deficiency``.

    ``deficiencies`` are every deficiency under which exactly these colours
    collide (sorted), ``sources`` the colours.
    """

    output: str
    deficiency: Deficiency
    deficiencies: tuple[Deficiency, ...]
    sources: tuple[str, ...]

    @property
    def colours(self) -> int:
        """How many distinct colours look alike."""
        return len(self.sources)

    def to_dict(self) -> dict[str, Value]:
        """The figures as written out (JSON ``numbers``, SARIF properties)."""
        return {
            "output": self.output,
            "deficiency": self.deficiency,
            "deficiencies": ", ".join(self.deficiencies),
            "colours": self.colours,
        }


@dataclass(frozen=True, slots=True)
class SeparationFigures(_Plain):
    """``separation``: the closest pair of ``sources``, CIEDE2000 ``delta_e`` apart."""

    delta_e: float
    delta_e_ref: float
    min_delta_e: float
    sources: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class ConfusionFigures:
    """``confusion``, ``cvd-confusion``: two palette ``roles`` no longer told apart.

    ``deficiency`` is the simulated deficiency of the worst canvas (``None``
    for ``confusion``), ``deficiencies`` every one under which the roles are
    confused (sorted; empty for ``confusion``).
    """

    delta_e_ref: float
    delta_e: float
    min_delta_e: float
    roles: tuple[str, str]
    deficiency: Deficiency | None = None
    deficiencies: tuple[Deficiency, ...] = ()

    def to_dict(self) -> dict[str, Value]:
        """The figures as written out (JSON ``numbers``, SARIF properties)."""
        out: dict[str, Value] = {
            "delta_e_ref": self.delta_e_ref,
            "delta_e": self.delta_e,
            "min_delta_e": self.min_delta_e,
            "roles": ",".join(self.roles),
        }
        if self.deficiency is not None:
            out |= {"deficiency": self.deficiency, "deficiencies": ", ".join(self.deficiencies)}
        return out


@dataclass(frozen=True, slots=True)
class DriftFigures(_Plain):
    """``drift``, ``lock``: a paint's ``source`` shown as ``output``, ``drift`` CIEDE2000 away."""

    drift: float
    limit: float
    source: str
    output: str
    paint: str


@dataclass(frozen=True, slots=True)
class ThinStrokeFigures(_Plain):
    """``thin-strokes``: at ``size`` px half the ink is at coverage <= ``q50``."""

    size: int
    q50: float
    size_contrast: float
    paint: str


@dataclass(frozen=True, slots=True)
class FixedPaintFigures(_Plain):
    """``fixed-colour``: the hard-coded ``paint`` and the element drawing it."""

    paint: str
    element: str


@dataclass(frozen=True, slots=True)
class ElementFigures(_Plain):
    """``not-audited``: the element the audit cannot judge (with its line)."""

    element: str


@dataclass(frozen=True, slots=True)
class NoFigures(_Plain):
    """A finding with no figures (``unrenderable``: the message says why)."""


Figures: TypeAlias = (
    ContrastFigures
    | RenderDriftFigures
    | CollisionFigures
    | CvdCollisionFigures
    | SeparationFigures
    | ConfusionFigures
    | DriftFigures
    | ThinStrokeFigures
    | FixedPaintFigures
    | ElementFigures
    | NoFigures
)
