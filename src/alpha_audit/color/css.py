"""CSS Color 4 colours to sRGB, with an explicit policy for colours outside sRGB.

Parsing and conversion are coloraide's (``Color``): it implements every CSS
Color 4 syntax (hex 3/4/6/8, ``rgb()``, ``hsl()``, ``hwb()``, ``lab()``,
``lch()``, ``oklab()``, ``oklch()``, ``color(<space> ...)`` and ``none``
components).  The CSS Color 4 gamut-mapping algorithm (section 13.2.2, what
coloraide calls ``minde-chroma`` in OKLCH with a JND of 0.02) runs vectorised
in :mod:`alpha_audit.color.gamut` with coloraide's matrices, so a design
system's thousands of colours map in one batch (:func:`map_parsed`).

A colour outside sRGB follows a :data:`GamutPolicy`:

``clip``
    clip each encoded sRGB channel to [0, 1] (what browsers do today);
``map``
    CSS Color 4 gamut mapping in OKLCH (chroma reduction, then clip);
``error``
    refuse it, naming the colour and the policies that would accept it.

:class:`ParsedColor` keeps the colour before and after that step and the
CIEDE2000 between them, so a report can say which colours moved and how far.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Literal, get_args

import numpy as np
from numpy.typing import NDArray

from alpha_audit.errors import ColorSyntaxError

if TYPE_CHECKING:  # coloraide is imported on first use (import alpha_audit.color stays light)
    from coloraide import Color

__all__ = [
    "CSS_SPACES",
    "GAMUT_POLICIES",
    "GamutPolicy",
    "ParsedColor",
    "color_from_components",
    "gamut_delta_e",
    "map_parsed",
    "parse_css_color",
]

GamutPolicy = Literal["clip", "map", "error"]
GAMUT_POLICIES: tuple[GamutPolicy, ...] = get_args(GamutPolicy)

# The colour spaces of CSS Color 4 (sections 8-10 and the predefined spaces of
# 10.1-10.8), named as CSS and the DTCG Color Module 2025.10 name them; the
# value is coloraide's space name.
CSS_SPACES: dict[str, str] = {
    "srgb": "srgb",
    "srgb-linear": "srgb-linear",
    "hsl": "hsl",
    "hwb": "hwb",
    "lab": "lab",
    "lch": "lch",
    "oklab": "oklab",
    "oklch": "oklch",
    "display-p3": "display-p3",
    "a98-rgb": "a98-rgb",
    "prophoto-rgb": "prophoto-rgb",
    "rec2020": "rec2020",
    "xyz-d50": "xyz-d50",
    "xyz-d65": "xyz-d65",
    "xyz": "xyz-d65",  # CSS Color 4, 10.8: "xyz" is an alias of xyz-d65
}

# coloraide's default in-gamut tolerance (``Color.in_gamut``): 0.000075 per
# channel, about 1/50 of an 8-bit step, so rounding noise of a conversion
# (a display-p3 white gives 1.0000000000000002) is not "out of gamut".
_GAMUT_TOLERANCE = 0.000075

_ALLOWED = (
    "use a CSS Color 4 colour: #rgb, #rrggbb, rgb(), hsl(), hwb(), lab(), lch(), "
    "oklab(), oklch(), color(srgb|display-p3|rec2020|... r g b) or a CSS colour name"
)

_OWN_ALPHA = "carries its own alpha; give an opaque colour and set the coefficient with alpha:"


@dataclass(frozen=True)
class ParsedColor:
    """A CSS colour resolved to sRGB under a gamut policy.

    ``encoded`` is the displayed sRGB (encoded, each channel in [0, 1]);
    ``unmapped`` the same colour before the gamut step (may lie outside
    [0, 1]); ``delta_e`` the CIEDE2000 between the two (0 when in gamut).
    """

    text: str
    space: str
    encoded: tuple[float, float, float]
    unmapped: tuple[float, float, float]
    alpha: float
    in_gamut: bool
    gamut: GamutPolicy

    @cached_property
    def delta_e(self) -> float:
        """CIEDE2000 between the colour before and after the gamut step (0 in gamut).

        Computed on first use; :func:`gamut_delta_e` does many at once.
        """
        return 0.0 if self.in_gamut else float(gamut_delta_e([self])[0])

    @property
    def adjusted(self) -> bool:
        """Whether the gamut policy changed the colour (it was outside sRGB)."""
        return not self.in_gamut

    @property
    def css(self) -> str:
        """``color(srgb r g b)`` with exact float64 channels: re-parses to the same numbers."""
        r, g, b = (repr(float(c)) for c in self.encoded)
        return f"color(srgb {r} {g} {b})"

    @property
    def array(self) -> NDArray[np.float64]:
        """``encoded`` as a float64 array (what :func:`alpha_audit.color.parse_color` returns)."""
        return np.array(self.encoded, dtype=np.float64)


def _color_class() -> type[Color]:
    from coloraide import Color

    return Color


def _rgb(values: Sequence[float]) -> tuple[float, float, float]:
    r, g, b = (float(v) for v in values)
    return r, g, b


def _resolve(
    color: Color, text: str, space: str, *, gamut: GamutPolicy, allow_alpha: bool
) -> ParsedColor:
    """Apply the alpha rule and the gamut policy to a coloraide colour."""
    if gamut not in GAMUT_POLICIES:
        raise ColorSyntaxError(
            f"gamut {gamut!r} is not a policy; use one of {', '.join(GAMUT_POLICIES)}"
        )
    alpha = float(color.alpha(nans=False))
    if not math.isfinite(alpha):
        raise ColorSyntaxError(f"{text!r} has an alpha that is not a number")
    if alpha < 1.0 and not allow_alpha:
        raise ColorSyntaxError(f"{text!r} {_OWN_ALPHA}")
    srgb = color.convert("srgb", norm=False)
    unmapped = _rgb(srgb.coords(nans=False))
    if not all(math.isfinite(v) for v in unmapped):
        raise ColorSyntaxError(f"{text!r} has a channel that is not a finite number")
    in_gamut = bool(srgb.in_gamut(tolerance=_GAMUT_TOLERANCE))
    if in_gamut or gamut == "clip":
        fitted = unmapped
    elif gamut == "map":
        from alpha_audit.color.gamut import map_to_srgb

        fitted = _rgb(map_to_srgb(unmapped).tolist())
    else:
        shown = ", ".join(f"{v:.4f}" for v in unmapped)
        raise ColorSyntaxError(
            f"{text!r} is outside sRGB (sRGB channels {shown}); give an sRGB colour, or "
            "set gamut: clip or gamut: map (in this file, the config or its tokens: table, "
            "or `gamut`)"
        )
    encoded = _rgb(np.clip(np.array(fitted, dtype=np.float64), 0.0, 1.0).tolist())
    return ParsedColor(
        text=text,
        space=space,
        encoded=encoded,
        unmapped=unmapped,
        alpha=alpha,
        in_gamut=in_gamut,
        gamut=gamut,
    )


def map_parsed(colors: Sequence[ParsedColor]) -> list[ParsedColor]:
    """The same colours with every one outside sRGB gamut-mapped, in one vectorised call.

    For colours parsed under ``clip`` (cheap) that a ``map`` policy covers:
    equal to parsing each under ``map``, thousands at a time.

    >>> [c.encoded for c in map_parsed([parse_css_color("#fff", gamut="clip")])]
    [(1.0, 1.0, 1.0)]
    """
    from dataclasses import replace

    from alpha_audit.color.gamut import map_to_srgb

    out = list(colors)
    moved = [i for i, c in enumerate(out) if not c.in_gamut]
    if moved:
        unmapped = np.array([out[i].unmapped for i in moved], dtype=np.float64)
        fitted = np.clip(map_to_srgb(unmapped), 0.0, 1.0)
        for i, row in zip(moved, fitted, strict=True):
            encoded = (float(row[0]), float(row[1]), float(row[2]))
            out[i] = replace(out[i], encoded=encoded, gamut="map")
    return out


def gamut_delta_e(colors: Sequence[ParsedColor]) -> NDArray[np.float64]:
    """CIEDE2000 of each colour's gamut step, in one vectorised call.

    >>> gamut_delta_e([parse_css_color("#fff")]).tolist()
    [0.0]
    """
    from alpha_audit.color.metrics import delta_e_2000
    from alpha_audit.color.transfer import srgb_decode

    before = srgb_decode(np.array([c.unmapped for c in colors], dtype=np.float64).reshape(-1, 3))
    after = srgb_decode(np.array([c.encoded for c in colors], dtype=np.float64).reshape(-1, 3))
    return np.asarray(delta_e_2000(before, after), dtype=np.float64).reshape(-1)


def parse_css_color(
    text: str, *, gamut: GamutPolicy = "error", allow_alpha: bool = False
) -> ParsedColor:
    """Parse any CSS Color 4 colour string to sRGB under ``gamut``.

    A colour with alpha below 1 raises :class:`ColorSyntaxError` unless
    ``allow_alpha`` (only where the alpha means an opacity).

    >>> parse_css_color("oklch(62.8% 0.2577 29.23)", gamut="clip").encoded[0]
    1.0
    >>> c = parse_css_color("color(display-p3 1 0 0)", gamut="map")
    >>> c.in_gamut, round(c.delta_e, 1) > 0
    (False, True)
    """
    if not isinstance(text, str):
        raise ColorSyntaxError(f"{text!r} is not a colour string; {_ALLOWED}")
    value = text.strip()
    if len(value) > 200 or "--" in value:  # "--" is coloraide's non-CSS space syntax
        raise ColorSyntaxError(f"{value[:40]!r} is not a colour; {_ALLOWED}")
    color_cls = _color_class()
    try:
        match = color_cls.match(value, fullmatch=True)
    except (ValueError, TypeError, IndexError):
        match = None
    if match is None:
        raise ColorSyntaxError(f"{value!r} is not a colour; {_ALLOWED}")
    color = match.color
    space = color.space()
    if space not in CSS_SPACES.values():
        raise ColorSyntaxError(f"{value!r} uses colour space {space!r}; {_ALLOWED}")
    return _resolve(color, value, space, gamut=gamut, allow_alpha=allow_alpha)


# DTCG Color Module 2025.10 gives hsl/hwb percentages as 0-100 numbers;
# coloraide keeps them as fractions.
_PERCENT_COMPONENTS = {"hsl": (1, 2), "hwb": (1, 2)}


def color_from_components(
    space: str,
    components: Sequence[float | str],
    alpha: float = 1.0,
    *,
    gamut: GamutPolicy = "error",
    allow_alpha: bool = False,
    text: str | None = None,
) -> ParsedColor:
    """A colour from a DTCG colour object: ``colorSpace``, ``components`` (``"none"`` allowed).

    >>> color_from_components("srgb", [1, 0, "none"]).encoded
    (1.0, 0.0, 0.0)
    >>> color_from_components("hsl", [120, 100, 50]).encoded
    (0.0, 1.0, 0.0)
    """
    shown = text or f"{space} {list(components)}"
    if space not in CSS_SPACES or space == "xyz":
        allowed = ", ".join(s for s in CSS_SPACES if s != "xyz")
        raise ColorSyntaxError(f"colorSpace {space!r} is not one of {allowed}")
    if len(components) != 3:
        raise ColorSyntaxError(f"{shown} needs 3 components, got {len(components)}")
    coords: list[float] = []
    for i, c in enumerate(components):
        if c == "none":
            coords.append(math.nan)  # coloraide's representation of CSS "none"
            continue
        if isinstance(c, bool) or not isinstance(c, int | float) or not math.isfinite(c):
            raise ColorSyntaxError(f"{shown}: component {i} is {c!r}; expected a number or 'none'")
        coords.append(float(c) / 100 if i in _PERCENT_COMPONENTS.get(space, ()) else float(c))
    if isinstance(alpha, bool) or not isinstance(alpha, int | float) or not 0 <= alpha <= 1:
        raise ColorSyntaxError(f"{shown}: alpha {alpha!r} is not a number from 0 to 1")
    color = _color_class()(CSS_SPACES[space], coords, float(alpha))
    return _resolve(color, shown, CSS_SPACES[space], gamut=gamut, allow_alpha=allow_alpha)
