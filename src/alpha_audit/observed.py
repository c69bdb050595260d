"""What a browser drew: measured paints, and what a page run saw besides them.

Plain frozen dataclasses of the core, so that rows, findings and renderers
read a browser's measurements without importing the browser audit
(:mod:`alpha_audit.pages` builds them; nothing here imports it).  One
:class:`MeasuredPaint` per (source, state, engine, icon instance, paint): it
becomes a paint row (:func:`alpha_audit.rows.observed_audit`), and the row
keeps it as its :attr:`~alpha_audit.rows.AuditResult.observed` record.  A
:class:`PageRun` holds what a run saw that is not a paint: the pages and states
audited, those that could not be, the requests refused and the crops the HTML
report shows.  Colours are given both as 8-bit sRGB hex and as linear sRGB
(float64 triples); contrast ratios are WCAG 2.2's.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import urlsplit

from alpha_audit.model import Location

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
    "PageRun",
    "Prediction",
]

Linear = tuple[float, float, float]


class IconMatch(enum.StrEnum):
    """How a found icon was tied to the manifest's icon (or that it was not)."""

    DATA_ATTRIBUTE = "data-attribute"
    SPRITE_ID = "sprite-id"
    FILE_NAME = "file-name"
    PATH_HASH = "path-hash"
    NONE = "none"


@dataclass(frozen=True)
class Coverage:
    """The paint's coverage measured from the difference of the two captures.

    ``pixels`` device pixels differ between the captures; ``full`` of them are
    fully covered (the drawn colour comes from those); ``q50`` and
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
    """The model's displayed colour for the same paint on the measured backdrop.

    ``contrast`` is judged as every row is (:func:`~alpha_audit.color.judged_contrast`:
    the 8-bit colours that ship), ``contrast_float`` of the float colours beside it.
    """

    pipeline: str  # "linear" or "css"
    output: str
    output_linear: Linear
    contrast: float
    drift: float  # CIEDE2000 between the drawn colour and this output
    contrast_float: float = math.nan


# A measured paint's status: what its figures are.
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
class MeasuredPaint:
    """One paint of one icon instance in one source, state and engine, as the browser drew it.

    ``name`` is what reports call the icon: the manifest's icon (``icon``, when it
    maps to one; ``match`` says how), else the page's ``data-icon``,
    ``aria-label``, ``<title>``, ``alt`` or ``id``, else a short DOM path.
    ``paint`` is ``currentColor``, the colour the engine computed (``#rrggbb``)
    or ``image`` (an ``<img>``: its paints are not declared); ``declared`` is
    the colour the engine computed for it (hex, ``None`` for an image) and
    ``declared_opacity`` the opacity it is drawn at (every ancestor's ``opacity``,
    the paint's own and its colour's alpha).

    ``drawn`` and ``behind`` are the pair that limits: the paint's colour at full
    coverage and the backdrop under it (the capture with every icon hidden) at
    the pixel where their contrast is least; ``contrast`` is that pair judged
    (:func:`~alpha_audit.color.judged_contrast`), the figure the gate reads
    through the paint's row.  ``contrast_worst`` and ``contrast_median`` are over
    the pixels the measurement considered, for diagnosis only.  ``around`` is
    the median backdrop in a ring just outside the icon.  ``status`` is
    :data:`MEASURED`, or :data:`UNMEASURED` when no pixel shows the paint at
    full coverage (its colour and contrast are then ``None``: it cannot be judged);
    ``basis`` says how its fully covered pixels were found (:class:`Basis`).

    ``model_source``/``model_alpha``/``model_opacity`` are what the model was
    given (the manifest's colour and alpha for a mapped ``currentColor`` paint,
    else the colour the engine computed, at alpha 1); ``predictions`` holds the
    model's output on ``behind`` under ``linear`` and ``css`` (css only where
    ``alpha * opacity`` is in [0, 1]); ``render_drift`` is the CIEDE2000 from
    the drawn colour to the nearer prediction.  ``box`` is the icon's box in CSS
    pixels of the page (x, y, width, height); ``file`` the story's source file
    (``importPath``) or the HTML page, where known; ``locations`` where the
    page sets the paint's colour and its backdrop (CSS declarations, the story
    file), most specific first.
    """

    source: str  # story id or page path
    source_kind: str  # "storybook", "page", "url"
    state: str
    engine: str
    name: str
    icon: str | None
    match: IconMatch
    element: str  # "svg", "use", "img", "mask", "selector"
    dom_path: str
    paint: str  # "currentColor" or the colour the engine computed (#rrggbb), or "image"
    kinds: tuple[str, ...]
    declared: str | None
    declared_opacity: float
    drawn: str | None
    drawn_linear: Linear | None
    behind: str | None
    behind_linear: Linear | None
    around: str | None
    around_linear: Linear | None
    coverage: Coverage
    contrast: float | None
    contrast_worst: float | None
    contrast_median: float | None
    model_source: str | None
    model_alpha: float | None
    model_opacity: float | None
    predictions: tuple[Prediction, ...]
    render_drift: float | None
    box: tuple[float, float, float, float]
    status: str = MEASURED
    basis: Basis | None = None
    file: Path | None = None
    locations: tuple[Location, ...] = ()

    def prediction(self, pipeline: str) -> Prediction | None:
        """The model's prediction under ``pipeline``, or None where it has none."""
        return next((p for p in self.predictions if p.pipeline == pipeline), None)

    @property
    def nearer(self) -> Prediction | None:
        """The model's prediction nearest (CIEDE2000) to what the browser drew, if any."""
        return min(self.predictions, key=lambda p: p.drift) if self.predictions else None


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
    """A request a page made that was refused: it was not to the page's own server.

    ``own`` is the engine's name when the engine asks that host by itself, whatever
    the page (Debian's Chromium: its updater and sign-in check), else ``None``.
    """

    source: str
    state: str
    engine: str
    url: str  # for HTTPS, the host and port the page tried to reach
    own: str | None = None

    @property
    def host(self) -> str:
        """The host asked, its port only when not the scheme's usual one (an HTTPS tunnel
        is recorded as ``host:443``, with or without a scheme).

        >>> BlockedRequest("s", "dark", "chromium", "http://cdn.example:8080/x.js").host
        'cdn.example:8080'
        >>> BlockedRequest("s", "dark", "chromium", "tracker.example:443").host
        'tracker.example'
        """
        parts = urlsplit(self.url if "://" in self.url else f"//{self.url}")
        host = parts.hostname or self.url
        try:
            port = parts.port
        except ValueError:  # a port that is not a number: name what was recorded
            return self.url
        return host if port in (None, 80, 443) else f"{host}:{port}"


@dataclass(frozen=True)
class PageProblem:
    """A source and state that could not be audited, and why (a time or memory limit ...)."""

    source: str
    state: str
    engine: str
    message: str


@dataclass(frozen=True)
class PageRun:
    """What one page run saw besides its measured paints (those are rows).

    ``pages`` are the (source, state) pairs audited, in report order, with the
    source file of each source (``files``); ``problems`` the page states that
    could not be audited; ``blocked`` every request refused.  ``crops`` (kept only
    when the run was asked for them) show the paints a finding may name, failing
    rules' first; ``crops_left_out`` counts the rest.
    """

    problems: tuple[PageProblem, ...]
    blocked: tuple[BlockedRequest, ...]
    audited: int  # source x state x engine combinations audited
    icons: int  # icon instances found over all of them
    paints: int  # paints measured over all of them
    engines: tuple[tuple[str, str], ...]  # (engine, version)
    pages: tuple[tuple[str, str], ...] = ()  # (source, state) of each audited, in order
    files: tuple[tuple[str, Path | None], ...] = ()  # (source, its story or page file)
    crops: tuple[IconCrop, ...] = ()
    crops_left_out: int = 0
