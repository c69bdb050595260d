"""What a page audit finds: measured paints, page problems and blocked requests.

Plain frozen dataclasses, the end of :mod:`alpha_audit.pages`: one
:class:`MeasuredPaint` per (source, state, icon instance, paint), ready to
become paint rows.  Colours are given both as 8-bit sRGB hex and as linear
sRGB (float64 triples); contrast ratios are WCAG 2.2's.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "MEASURED",
    "UNMEASURED",
    "Basis",
    "BlockedRequest",
    "Coverage",
    "IconCrop",
    "IconMatch",
    "MeasuredPaint",
    "PageProblem",
    "Prediction",
    "RenderResult",
]

Linear = tuple[float, float, float]


class IconMatch(enum.StrEnum):
    """How a found icon was tied to the manifest's icon (or that it was not)."""

    DATA_ATTRIBUTE = "data-attribute"
    SPRITE_ID = "sprite-id"
    FILE_NAME = "file-name"
    PATH_HASH = "path-hash"
    NONE = "none"


# A measured paint's status: whether it has a gated contrast.
MEASURED = "measured"
# No pixel shows the paint at full coverage (a hairline): nothing to judge, no failure.
UNMEASURED = "could not measure"


class Basis(enum.StrEnum):
    """What a paint's fully covered pixels were found by (:mod:`alpha_audit.pages.measure`).

    ``declared``: their drawn colour is the colour the engine computed for the
    paint, at its opacity, composited over the backdrop at that pixel (within
    :data:`~alpha_audit.pages.measure.FULL_TOLERANCE`); ``plateau``: that colour
    does not explain the pixels (a CSS filter, a blend mode, an ``<img>`` whose
    paints are unknown), so they are the drawn colour furthest from the
    backdrop that a plateau of pixels shares.
    """

    DECLARED = "declared"
    PLATEAU = "plateau"


@dataclass(frozen=True)
class Coverage:
    """The paint's coverage measured from the difference of the two captures.

    ``pixels`` device pixels differ between the captures; ``full`` of them are
    fully covered (the drawn colour and the gated contrast come from those:
    ``basis`` of :class:`MeasuredPaint`); ``q50`` and
    ``full_share`` as in :func:`alpha_audit.color.coverage_stats`, ``ink`` the
    sum of coverage in device pixels.
    """

    pixels: int
    full: int
    ink: float
    q50: float
    full_share: float


@dataclass(frozen=True)
class Prediction:
    """The model's displayed colour and contrast for the same paint and backdrop."""

    pipeline: str  # "linear" or "css"
    output: str
    output_linear: Linear
    contrast: float
    drift: float  # CIEDE2000 between the drawn colour and this output


@dataclass(frozen=True)
class MeasuredPaint:
    """One paint of one icon instance in one source and state, as the browser drew it.

    ``icon`` is the manifest's icon name, or ``None`` when the icon maps to no
    manifest icon (``match`` says how it was mapped); ``label`` names it either
    way (story or page, state, DOM path).  ``drawn`` is the median colour of
    the fully covered pixels; ``behind`` the median backdrop under them (the
    capture with every icon hidden), ``around`` the median backdrop in a ring
    just outside the icon.

    ``contrast`` is the gated figure: the least WCAG 2.2 contrast
    (:func:`~alpha_audit.color.judged_contrast`) of the fully covered pixels
    against the backdrop at the same pixel (on each backdrop colour, the
    paint's most frequent drawn colour there); ``limit_drawn`` on
    ``limit_behind`` is the pair giving it (what a fix must change).  ``basis``
    says how the fully covered pixels were found (:class:`Basis`).  ``status``
    is :data:`MEASURED`, or :data:`UNMEASURED` when no pixel shows the paint at
    full coverage (a hairline): ``contrast`` is then ``None`` and the paint
    neither passes nor fails.  ``contrast_worst`` and ``contrast_median`` are
    kept for diagnosis: over the paint's *candidate* pixels, touched pixels
    whose 3 x 3 neighbourhood is touched, antialiased mixes at concave corners
    and diagonals included, each against the backdrop at the same pixel.
    ``model_source``/``model_alpha``/``model_opacity`` are what the model was
    given (the manifest's colour and alpha for a mapped ``currentColor`` paint,
    else the colour the engine computed, at alpha 1); ``predictions`` holds the
    model's output under ``linear`` and ``css`` (css only where ``alpha *
    opacity`` is in [0, 1]).  ``render_drift`` is the CIEDE2000 from the drawn
    colour to the nearer prediction; ``box`` the icon's crop box in CSS pixels
    of the page (x, y, width, height); ``file`` the story's source file
    (``importPath``) or the HTML page, where known.
    """

    source: str  # story id or page URL path
    source_kind: str  # "storybook", "page", "url"
    url: str
    state: str
    engine: str
    label: str
    icon: str | None
    match: IconMatch
    element: str  # "svg", "use", "img", "mask", "selector"
    dom_path: str
    paint: str  # "currentColor" or the colour the engine computed (#rrggbb), or "image"
    kinds: tuple[str, ...]
    drawn: str | None
    drawn_linear: Linear | None
    behind: str | None
    behind_linear: Linear | None
    around: str | None
    around_linear: Linear | None
    coverage: Coverage
    contrast_worst: float | None
    contrast_median: float | None
    model_source: str | None
    model_alpha: float | None
    model_opacity: float | None
    predictions: tuple[Prediction, ...]
    render_drift: float | None
    box: tuple[float, float, float, float]
    threshold: float = 3.0
    file: Path | None = None
    contrast: float | None = None  # the gated contrast: limit_drawn on limit_behind
    limit_drawn: str | None = None
    limit_drawn_linear: Linear | None = None
    limit_behind: str | None = None
    limit_behind_linear: Linear | None = None
    status: str = MEASURED
    basis: Basis | None = None

    @property
    def passes(self) -> bool | None:
        """Whether the gated ``contrast`` reaches the threshold (None: could not measure)."""
        if self.contrast is None or self.status != MEASURED:
            return None
        return self.contrast >= self.threshold

    def prediction(self, pipeline: str) -> Prediction | None:
        """The model's prediction under ``pipeline``, or None where it has none."""
        return next((p for p in self.predictions if p.pipeline == pipeline), None)


@dataclass(frozen=True)
class IconCrop:
    """One icon instance cut out of both captures, as PNG: what the HTML report shows.

    ``drawn`` and ``hidden`` are PNG files (8-bit sRGB, no colour profile) of
    the same pixels: the icon's box grown by the ring the backdrop "around" it
    is measured in, icons drawn and icons hidden.  Every pixel is a pixel of the
    capture: ``step`` is 1, or for an icon too large for the crop side every
    ``step``-th device pixel of each row and column (nothing is interpolated).
    ``width`` x ``height`` are the PNGs' pixels, ``scale`` the capture's device
    pixels per CSS pixel.  ``source``, ``state``, ``engine`` and ``dom_path``
    name the instance, as in its :class:`MeasuredPaint` records.
    """

    source: str
    state: str
    engine: str
    dom_path: str
    drawn: bytes
    hidden: bytes
    width: int
    height: int
    scale: int
    step: int = 1

    @property
    def key(self) -> tuple[str, str, str, str]:
        """(source, state, engine, DOM path): the instance this crop shows."""
        return self.source, self.state, self.engine, self.dom_path


@dataclass(frozen=True)
class BlockedRequest:
    """A request a page made that was refused: it was not to the page's own server."""

    source: str
    state: str
    engine: str
    url: str  # for HTTPS, the host and port the page tried to reach


@dataclass(frozen=True)
class PageProblem:
    """A source and state that could not be audited, and why (a time or memory limit ...)."""

    source: str
    state: str
    engine: str
    url: str
    message: str


@dataclass(frozen=True)
class RenderResult:
    """Everything one run found, in a stable order (source, state, engine, DOM order).

    ``crops`` (kept only when the run was asked for them) show the paints a
    finding may name as its worst, failing rules' first, at most
    ``RenderConfig.crops`` of them; ``crops_left_out`` counts the rest.
    """

    paints: tuple[MeasuredPaint, ...]
    problems: tuple[PageProblem, ...]
    blocked: tuple[BlockedRequest, ...]
    audited: int  # source x state x engine combinations audited
    icons: int  # icon instances found over all of them
    engines: tuple[tuple[str, str], ...]  # (engine, version)
    pages: tuple[tuple[str, str], ...] = ()  # (source, state) of each audited, in order
    crops: tuple[IconCrop, ...] = ()  # kept only when asked (RenderConfig.crops)
    crops_left_out: int = 0  # crops wanted beyond RenderConfig.crops

    @property
    def failing(self) -> tuple[MeasuredPaint, ...]:
        """Paints whose gated contrast is below the threshold."""
        return tuple(p for p in self.paints if p.passes is False)
