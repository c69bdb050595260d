"""Validated, immutable inputs: canvases, themes, icons and icon sets.

Loaders in :mod:`alpha_audit.load` build these from files; they can also be
built directly from Python.  Colours are stored as encoded sRGB hex (what the
user wrote, normalised) plus linear-light float64 triples for the maths.
"""

from __future__ import annotations

from collections.abc import Container
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import (
    NON_TEXT_THRESHOLD,
    GamutPolicy,
    Pipeline,
    composite_paint,
    parse_color,
    relative_luminance,
    srgb_decode,
)
from alpha_audit.errors import InputError

__all__ = [
    "Canvas",
    "Edit",
    "GamutAdjustment",
    "Icon",
    "IconProblem",
    "IconSet",
    "Location",
    "Mode",
    "Span",
    "Theme",
    "infer_mode",
]

Mode = Literal["light", "dark"]

# Luminance at which a colour has equal WCAG contrast against black and white:
# (Y + 0.05) / 0.05 == 1.05 / (Y + 0.05)  =>  Y = sqrt(0.0525) - 0.05.
_LIGHT_DARK_SPLIT = 0.0525**0.5 - 0.05


def infer_mode(linear: NDArray[np.float64]) -> Mode:
    """``light`` when the canvas contrasts more with black than with white."""
    return "light" if float(relative_luminance(linear)) >= _LIGHT_DARK_SPLIT else "dark"


def _normalise(obj: object, color: str) -> None:
    """Store ``color`` as ``#rrggbb`` and its linear-light triple on a frozen dataclass.

    The colour as given is kept in ``exact``, so ``dataclasses.replace`` (which
    re-runs this with the normalised hex) does not round an ``oklch()`` or
    ``color(srgb ...)`` colour to 8 bits.
    """
    spec = color
    exact = getattr(obj, "exact", None)
    encoded = parse_color(color)
    if exact is not None and exact != color:
        kept = parse_color(exact)
        if np.array_equal(np.rint(kept * 255), np.rint(encoded * 255)):  # not a new colour
            spec, encoded = exact, kept
    r, g, b = (int(v) for v in np.rint(encoded * 255))
    object.__setattr__(obj, "exact", spec)
    object.__setattr__(obj, "color", f"#{r:02x}{g:02x}{b:02x}")
    object.__setattr__(obj, "linear", tuple(float(c) for c in srgb_decode(encoded)))


# How a file writes the scalar a fix rewrites; see Span.replacement.
Syntax = Literal["yaml", "json", "css"]
_QUOTES = ("'", '"')


@dataclass(frozen=True, slots=True)  # one per token value: a large token file has many
class Span:
    """Where one scalar value is written: its file, region and the text there.

    The region follows SARIF 2.1.0 section 3.30: lines and columns 1-based,
    columns counting Unicode code points (``run.columnKind``
    ``unicodeCodePoints``, 3.14.27), lines ended by ``\\n`` or ``\\r\\n``
    (the default ``newlineSequences``, 3.14.26), ``end_column`` the column
    after the last character (3.30.8).  ``text`` is exactly what the file holds
    there, quotes included; loaders record a span only where it is exact.
    """

    file: Path
    start_line: int
    start_column: int
    end_line: int
    end_column: int
    text: str
    syntax: Syntax

    def replacement(self, value: str) -> str:
        """``value`` written as the file writes this scalar: same quotes, else as needed.

        A quoted original keeps its quote character; JSON strings are always
        double-quoted; a YAML plain scalar that would start with ``#`` (a
        comment there) is double-quoted; CSS and numbers go in bare.

        >>> Span(Path("m.yaml"), 1, 8, 1, 17, "'#ee7733'", "yaml").replacement("#cc5511")
        "'#cc5511'"
        >>> Span(Path("m.yaml"), 1, 8, 1, 11, "red", "yaml").replacement("#cc5511")
        '"#cc5511"'
        """
        text = self.text
        if len(text) >= 2 and text[0] in _QUOTES and text[-1] == text[0]:
            return f"{text[0]}{value}{text[0]}"
        if self.syntax == "yaml" and value.startswith("#"):
            return f'"{value}"'
        return value


@dataclass(frozen=True)
class Location:
    """A line that sets a value a finding is about: ``what`` says which value.

    ``what`` is ``alpha`` (the ``alpha:`` that applies: the icon's own or
    override, its palette entry's, the set's, or the project config's),
    ``colour`` (the palette entry or colour written on the icon), ``token``
    (the design token at the end of the colour's alias chain), ``paint`` (an
    SVG element's hard-coded colour), ``svg`` (the drawing itself), and on a
    page ``css-colour``/``css-backdrop`` (the CSS declaration that sets the
    paint's colour or its backdrop), ``story`` or ``page`` (the source file).
    ``span`` is the value's exact region where the loader knows it.
    """

    file: Path
    line: int
    what: str
    span: Span | None = None


@dataclass(frozen=True)
class Edit:
    """Replace the text at ``span`` by ``value`` (written as the file writes it).

    ``kind`` says which fix it applies (``largest-safe-alpha``,
    ``smallest-alpha-reaching``, ``nearest-color``), ``description`` in words.
    """

    kind: str
    description: str
    span: Span
    value: str

    @property
    def inserted(self) -> str:
        """The replacement text, quoted as the original was (:meth:`Span.replacement`)."""
        return self.span.replacement(self.value)


@dataclass(frozen=True)
class GamutAdjustment:
    """A colour outside sRGB and what the gamut policy made of it.

    ``token`` is the design-token path, or for a theme or manifest colour the
    YAML key (``canvases[2].color``); ``mode`` the token mode, or the theme or
    icon set's name.  ``text`` is the colour as written, ``output`` the sRGB
    hex it became and ``delta_e`` the CIEDE2000 between the two.
    """

    mode: str
    token: str
    text: str
    policy: GamutPolicy
    output: str
    delta_e: float
    file: Path | None
    line: int | None


@dataclass(frozen=True)
class Canvas:
    """A background of a theme: an opaque colour, or a translucent layer over another canvas.

    A layer (``opacity`` below 1) names the canvas it sits ``over``: a surface or
    hover tint at 8% over the page.  The audit sees it as the stack it is,
    composited in its pipeline (:meth:`Theme.flattened`), or in ``blend`` when
    the layer says how it is drawn whatever draws the icons (a surface from a
    CSS sheet is painted by the browser: ``css``); ``stack`` then says what it
    was made of.
    """

    name: str
    color: str
    mode: Mode | None = None
    line: int | None = field(default=None, compare=False)
    # The file ``line`` is in when it is not the theme's own (a design token
    # set in another file of a Resolver document); None: the theme file.
    file: Path | None = field(default=None, compare=False)
    exact: str | None = field(default=None, compare=False, repr=False)
    # Where the colour's value is written (a design token's), when exactly known.
    span: Span | None = field(default=None, compare=False, repr=False)
    over: str | None = None  # the canvas a translucent layer sits on
    opacity: float = 1.0  # the layer's own alpha (1: an opaque canvas)
    blend: Pipeline | None = None  # how the layer is composited; None: the audit's pipeline
    stack: str | None = field(default=None, compare=False)  # "8% #0969da over paper"
    linear: tuple[float, float, float] = field(init=False, compare=False)

    def __post_init__(self) -> None:
        _normalise(self, self.color)
        if self.mode is None and self.over is None:  # a layer's mode is its stack's
            object.__setattr__(self, "mode", infer_mode(np.array(self.linear)))


@dataclass(frozen=True)
class Theme:
    """A named set of canvases with a contrast threshold."""

    name: str
    canvases: tuple[Canvas, ...]
    threshold: float = NON_TEXT_THRESHOLD
    path: Path | None = field(default=None, compare=False)
    pipeline: Pipeline | None = None  # how this platform draws icons; None: not said
    adjusted: tuple[GamutAdjustment, ...] = field(default=(), compare=False)  # out-of-sRGB

    @property
    def backgrounds(self) -> NDArray[np.float64]:
        """Linear canvas colours, shape ``(n_canvases, 3)`` (layers: :meth:`flattened` first)."""
        return np.array([c.linear for c in self.canvases], dtype=np.float64).reshape(-1, 3)

    def flattened(self, pipeline: Pipeline = "linear") -> Theme:
        """Every translucent layer composited over its canvas, as ``pipeline`` draws it.

        ``linear``: ``o Cl + (1 - o) Cb`` in linear light; ``css``: what a browser
        does with an ``rgba()`` surface, the encoded blend rounded to 8 bits.  A
        layer with its own ``blend`` (a CSS surface: ``css``) is drawn that way
        in every pipeline.  A layer over a layer is composited from the bottom
        up.  Each flattened canvas is opaque, keeps its name and says in
        ``stack`` what it is.

        >>> t = Theme("t", (Canvas("page", "#ffffff"), Canvas("chip", "#0969da", over="page",
        ...     opacity=0.5)))
        >>> t.flattened("css").canvases[1].color, t.flattened("css").canvases[1].stack
        ('#84b4ec', '50% #0969da over page')
        >>> muted = Canvas("muted", "rgb(101 108 118)", over="page", opacity=0.2, blend="css")
        >>> Theme("t", (Canvas("page", "#212830"), muted)).flattened("linear").canvases[1].color
        '#2f363e'
        """
        if all(c.over is None for c in self.canvases):
            return self
        by_name = {c.name: c for c in self.canvases}
        done: dict[str, Canvas] = {}

        def flat(canvas: Canvas, below: tuple[str, ...] = ()) -> Canvas:
            if canvas.over is None or canvas.name in done:
                return done.get(canvas.name, canvas)
            if canvas.over not in by_name or canvas.name in below:
                why = "names no canvas" if canvas.over not in by_name else "makes a loop of layers"
                raise InputError(
                    f"canvas {canvas.name!r} is over {canvas.over!r}, which {why}",
                    path=canvas.file or self.path,
                    line=canvas.line,
                )
            base = flat(by_name[canvas.over], (*below, canvas.name))
            drawn = canvas.blend or pipeline
            shown = composite_paint(
                np.array(canvas.linear), np.array(base.linear), 1.0, canvas.opacity, drawn
            )
            r, g, b = (float(v) for v in shown)
            done[canvas.name] = replace(
                canvas,
                color=f"color(srgb-linear {r!r} {g!r} {b!r})",
                exact=None,
                mode=canvas.mode or infer_mode(shown),
                over=None,
                opacity=1.0,
                blend=None,
                stack=f"{canvas.opacity:.0%} {canvas.color} over {canvas.over}",
            )
            return done[canvas.name]

        return replace(self, canvases=tuple(flat(c) for c in self.canvases))


@dataclass(frozen=True)
class IconProblem:
    """An icon that could not be used, with the reason."""

    icon: str
    file: Path
    message: str


@dataclass(frozen=True)
class Icon:
    """One icon: an SVG file with a fixed source colour and coefficient."""

    name: str
    file: Path
    color: str
    alpha: float
    color_name: str | None = None
    color_line: int | None = field(default=None, compare=False)
    alpha_line: int | None = field(default=None, compare=False)
    # Where a design token sets this icon's colour (the end of its alias
    # chain), so reports point at the line to edit, not only the manifest's.
    token_file: Path | None = field(default=None, compare=False)
    token_line: int | None = field(default=None, compare=False)
    # The exact text a fix rewrites: the value that sets the colour (the palette
    # entry, the colour written on the icon, or the design token's value) and the
    # value that sets the alpha (the icon's own or override, else the set-wide
    # ``alpha:``).  None where the value is not written in a file (a default, a
    # token's coefficient, ``--alpha``) or its place is not exactly known.
    color_span: Span | None = field(default=None, compare=False, repr=False)
    alpha_span: Span | None = field(default=None, compare=False, repr=False)
    exact: str | None = field(default=None, compare=False, repr=False)
    linear: tuple[float, float, float] = field(init=False, compare=False)

    def __post_init__(self) -> None:
        _normalise(self, self.color)


@dataclass(frozen=True)
class IconSet:
    """Icons with their palette and raster sizes, as named by a manifest."""

    name: str
    icons: tuple[Icon, ...]
    palette: dict[str, str] = field(default_factory=dict)
    sizes: tuple[int, ...] = (24,)
    path: Path | None = field(default=None, compare=False)
    root: Path | None = field(default=None, compare=False)
    pipeline: Pipeline | None = None  # how these icons are drawn; None: not said
    locked: frozenset[str] = frozenset()  # icon and palette names with lock (brand colours)
    adjusted: tuple[GamutAdjustment, ...] = field(default=(), compare=False)  # out-of-sRGB

    @property
    def sources(self) -> NDArray[np.float64]:
        """Linear source colours, shape ``(n_icons, 3)``."""
        return np.array([i.linear for i in self.icons], dtype=np.float64).reshape(-1, 3)

    @property
    def alphas(self) -> NDArray[np.float64]:
        """Coefficients, shape ``(n_icons,)``."""
        return np.array([i.alpha for i in self.icons], dtype=np.float64)

    def with_alpha(self, alpha: float) -> IconSet:
        """The same set with every icon's coefficient replaced (``--alpha``).

        The coefficient then comes from no file, so no icon keeps an ``alpha_span``.
        """
        icons = tuple(replace(i, alpha=float(alpha), alpha_span=None) for i in self.icons)
        return replace(self, icons=icons)

    def without(self, names: Container[str]) -> IconSet:
        """The same set without the icons named (those that could not be rendered)."""
        return replace(self, icons=tuple(i for i in self.icons if i.name not in names))
