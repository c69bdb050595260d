"""CSS Color 4 colours to sRGB, with an explicit policy for colours outside sRGB.

Parsing and conversion are coloraide's (``Color``): it implements every CSS
Color 4 syntax (hex 3/4/6/8, ``rgb()``, ``hsl()``, ``hwb()``, ``lab()``,
``lch()``, ``oklab()``, ``oklch()``, ``color(<space> ...)`` and ``none``
components).  Two CSS Color 5 forms that design tokens use for translucency
are read too, their structure tokenised by tinycss2 and their maths done by
coloraide: ``color-mix(in <space>, <color> [p%], <color> [p%])`` (Tailwind's
opacity modifiers write ``color-mix(in oklab, X 50%, transparent)``) and the
relative colour syntax ``oklch(from <color> l c h / a)``.

The CSS Color 4 gamut-mapping algorithm (section 13.2.2, what
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
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from alpha_audit.constants import GAMUT_POLICIES, GamutPolicy
from alpha_audit.errors import ColorSyntaxError

if TYPE_CHECKING:  # coloraide is imported on first use (import alpha_audit.color stays light)
    from coloraide import Color

__all__ = [
    "CSS_SPACES",
    "MAX_CHANNEL",
    "MAX_COLOR_TEXT",
    "ParsedColor",
    "color_from_components",
    "gamut_delta_e",
    "map_parsed",
    "parse_css_color",
]


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
# The largest sRGB channel (gamma-encoded) a colour may have before any policy applies.
# CSS Color 4 leaves lab()/oklch()/color() channels unbounded, but colours within its
# reference ranges land within a few units of [0, 1] (lab(100 -125 -125) is about
# srgb(-1.9 1.1 2.3)); beyond 1000 a value is no colour, and its linear light
# (|c|^2.4, IEC 61966-2-1) would overflow float64 further down.
MAX_CHANNEL = 1000.0

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


@contextmanager
def _too_large(text: str) -> Iterator[None]:
    """Arithmetic on finite but huge channels as a colour error, not a crash.

    ``lab(50 1e308 1e308)`` overflows its conversion and a hue of ``1e400``
    (inf) is a domain error: bad input, which coloraide reports as
    ``OverflowError`` or ``ValueError``.
    """
    try:
        yield
    except ColorSyntaxError:
        raise
    except (ArithmeticError, ValueError) as exc:
        raise ColorSyntaxError(
            f"{text[:60]!r} has a channel too large to convert to sRGB; give channels "
            "in their CSS Color 4 ranges"
        ) from exc


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
    with _too_large(text):
        srgb = color.convert("srgb", norm=False)
        unmapped = _rgb(srgb.coords(nans=False))
    if not all(math.isfinite(v) for v in unmapped):
        raise ColorSyntaxError(f"{text!r} has a channel that is not a finite number")
    if not all(abs(v) <= MAX_CHANNEL for v in unmapped):
        shown = ", ".join(f"{v:.4g}" for v in unmapped)
        raise ColorSyntaxError(
            f"{text[:60]!r} is no colour (sRGB channels {shown}, beyond +-{MAX_CHANNEL:g}); "
            "give channels in their CSS Color 4 ranges"
        )
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


# A colour written out is short; a var()-substituted color-mix() of relative
# colours stays under a few hundred characters.  Longer text is refused
# before any parsing (the nested forms below recurse once per level).
MAX_COLOR_TEXT = 1000
_MAX_NESTING = 8

# color-mix() and the relative syntax name their space as CSS does.
_MIX_SPACES = {**CSS_SPACES, "xyz": "xyz-d65"}
# Relative colour syntax (CSS Color 5, section 4): the channel keywords of
# each function and the scale from coloraide's coordinates to the numbers
# the function takes (rgb() channels are 0-255, hsl()/hwb() percentages 0-100).
_RELATIVE: dict[str, tuple[str, tuple[str, str, str], tuple[float, float, float]]] = {
    "rgb": ("srgb", ("r", "g", "b"), (255.0, 255.0, 255.0)),
    "rgba": ("srgb", ("r", "g", "b"), (255.0, 255.0, 255.0)),
    "hsl": ("hsl", ("h", "s", "l"), (1.0, 100.0, 100.0)),
    "hsla": ("hsl", ("h", "s", "l"), (1.0, 100.0, 100.0)),
    "hwb": ("hwb", ("h", "w", "b"), (1.0, 100.0, 100.0)),
    "lab": ("lab", ("l", "a", "b"), (1.0, 1.0, 1.0)),
    "lch": ("lch", ("l", "c", "h"), (1.0, 1.0, 1.0)),
    "oklab": ("oklab", ("l", "a", "b"), (1.0, 1.0, 1.0)),
    "oklch": ("oklch", ("l", "c", "h"), (1.0, 1.0, 1.0)),
}
_HUE_METHODS = ("shorter", "longer", "increasing", "decreasing")


def _match(value: str, depth: int) -> Color:
    """A coloraide colour for CSS ``value``: CSS Color 4, ``color-mix()`` or relative syntax."""
    color_cls = _color_class()
    try:
        match = color_cls.match(value, fullmatch=True)
    except (ValueError, TypeError, IndexError):
        match = None
    if match is not None:
        return match.color
    if depth < _MAX_NESTING and "(" in value:
        import tinycss2

        try:
            node = tinycss2.parse_one_component_value(value)
        except RecursionError as exc:
            raise ColorSyntaxError(f"{value[:40]!r} is nested too deeply; {_ALLOWED}") from exc
        if node.type == "function":
            args = [t for t in node.arguments if t.type not in ("whitespace", "comment")]
            if node.lower_name == "color-mix":
                return _color_mix(value, node.arguments, depth)
            if args and args[0].type == "ident" and args[0].lower_value == "from":
                return _relative(value, node.lower_name, args[1:], depth)
    raise ColorSyntaxError(f"{value!r} is not a colour; {_ALLOWED}")


def _split_commas(tokens: Sequence[Any]) -> list[list[Any]]:
    parts: list[list[Any]] = [[]]
    for t in tokens:
        if t.type == "literal" and t.value == ",":
            parts.append([])
        elif t.type not in ("whitespace", "comment"):
            parts[-1].append(t)
    return parts


def _color_mix(text: str, arguments: Sequence[Any], depth: int) -> Color:
    """``color-mix(in <space> [<hue> hue], c1 [p1], c2 [p2])`` (CSS Color 5, section 3)."""
    import tinycss2

    parts = _split_commas(arguments)
    head = [t.lower_value if t.type == "ident" else None for t in parts[0]]
    if len(parts) != 3 or len(head) < 2 or head[0] != "in" or head[1] not in _MIX_SPACES:
        raise ColorSyntaxError(
            f"{text[:60]!r}: color-mix() takes (in <space>, <color> [p%], <color> [p%]) "
            f"with a space of {', '.join(_MIX_SPACES)}"
        )
    hue = "shorter"
    if len(head) == 4 and head[2] in _HUE_METHODS and head[3] == "hue":
        hue = str(head[2])
    elif len(head) != 2:
        raise ColorSyntaxError(f"{text[:60]!r}: color-mix()'s hue method is <method> hue")
    colors = []
    weights: list[float | None] = []
    for part in parts[1:]:
        pcts = [t for t in part if t.type == "percentage"]
        rest = [t for t in part if t.type != "percentage"]
        if len(pcts) > 1 or len(rest) != 1 or not all(0 <= p.value <= 100 for p in pcts):
            raise ColorSyntaxError(f"{text[:60]!r}: each color-mix() item is <color> [0-100%]")
        colors.append(_match(tinycss2.serialize(rest).strip(), depth + 1))
        weights.append(float(pcts[0].value) if pcts else None)
    # CSS Color 5, 3.1: a missing percentage is 100% minus the other (50% both);
    # the two are scaled to sum to 100%, and a smaller sum scales the alpha.
    w1, w2 = weights
    p1 = w1 if w1 is not None else 100.0 - (w2 if w2 is not None else 50.0)
    p2 = w2 if w2 is not None else 100.0 - p1
    total = p1 + p2
    if total <= 0:
        raise ColorSyntaxError(f"{text[:60]!r}: color-mix() percentages sum to zero")
    space = _MIX_SPACES[str(head[1])]
    mixed = colors[0].mix(colors[1], p2 / total, space=space, premultiplied=True, hue=hue)
    mixed = mixed.convert(space)
    if total < 100:
        mixed.set("alpha", mixed.alpha(nans=False) * total / 100)
    return mixed


def _relative(text: str, name: str, args: Sequence[Any], depth: int) -> Color:
    """``<fn>(from <color> c1 c2 c3 [/ a])`` with channel keywords (CSS Color 5, section 4)."""
    import tinycss2

    if not args:
        raise ColorSyntaxError(f"{text[:60]!r}: relative colour syntax needs an origin colour")
    origin = _match(tinycss2.serialize([args[0]]).strip(), depth + 1)
    rest = list(args[1:])
    if name == "color":
        if not rest or rest[0].type != "ident" or rest[0].lower_value not in CSS_SPACES:
            raise ColorSyntaxError(f"{text[:60]!r}: color(from <color> <space> ...) needs a space")
        css_space = rest.pop(0).lower_value
        space = CSS_SPACES[css_space]
        keys = ("x", "y", "z") if space.startswith("xyz") else ("r", "g", "b")
        scale = (1.0, 1.0, 1.0)
        prefix = f"color({css_space} "
    elif name in _RELATIVE:
        space, keys, scale = _RELATIVE[name]
        prefix = f"{name.removesuffix('a') if name in ('rgba', 'hsla') else name}("
    else:
        raise ColorSyntaxError(f"{text[:60]!r}: relative colour syntax in {name}() is not read")
    coords = origin.convert(space).coords(nans=False)
    values = dict(zip(keys, (c * k for c, k in zip(coords, scale, strict=True)), strict=True))
    values["alpha"] = origin.alpha(nans=False)
    slash = next((i for i, t in enumerate(rest) if t.type == "literal" and t.value == "/"), None)
    channels, alpha = (rest, []) if slash is None else (rest[:slash], rest[slash + 1 :])
    if len(channels) != 3 or len(alpha) > 1:
        raise ColorSyntaxError(f"{text[:60]!r}: relative colour syntax takes 3 channels [/ alpha]")

    def term(token: Any) -> str:
        if token.type == "ident" and token.lower_value in values:
            return repr(float(values[token.lower_value]))
        if token.type in ("number", "percentage", "dimension") or (
            token.type == "ident" and token.lower_value == "none"
        ):
            return str(tinycss2.serialize([token]))
        raise ColorSyntaxError(
            f"{text[:60]!r}: a relative channel is a keyword ({', '.join(values)}), a number, "
            "a percentage or none (calc() is not read)"
        )

    shown = " ".join(term(t) for t in channels)
    shown += f" / {term(alpha[0]) if alpha else repr(float(values['alpha']))}"
    return _match(f"{prefix}{shown})", depth + 1)


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
    if len(value) > MAX_COLOR_TEXT or "--" in value:  # "--": coloraide's non-CSS space syntax
        raise ColorSyntaxError(f"{value[:40]!r} is not a colour; {_ALLOWED}")
    with _too_large(value):
        color = _match(value, 0)
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
    if not isinstance(space, str) or space not in CSS_SPACES or space == "xyz":
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
