"""Options shared by several commands, declared once (typer ``Annotated`` aliases)."""

from __future__ import annotations

import difflib
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, TypeVar

import typer
from typer.core import TyperCommand

from alpha_audit import ranges
from alpha_audit.color.css import GAMUT_POLICIES, GamutPolicy
from alpha_audit.errors import UsageError

__all__ = [
    "OPTION_ORDER",
    "ConfigOption",
    "ForceOption",
    "GamutOption",
    "IconsetArgument",
    "MaxDriftOption",
    "MaxLossOption",
    "MinDeltaEOption",
    "MinSizeContrastOption",
    "NoCacheOption",
    "OrderedOptionsCommand",
    "PipelineOption",
    "StrictSvgOption",
    "ThemeArgument",
    "ThresholdOption",
    "in_range",
    "read_gamut_option",
]

ThemeArgument = Annotated[
    Path | None,
    typer.Argument(
        help="Theme YAML or a bundled theme name (default: what the project config names)."
    ),
]
IconsetArgument = Annotated[
    Path | None,
    typer.Argument(
        help="Icon-set manifest YAML or vibrant, the bundled example "
        "(default: what the project config names)."
    ),
]
ConfigOption = Annotated[
    Path | None,
    typer.Option(
        "--config",
        help="Project config (default: alpha-audit.yaml, .alpha-audit.yaml or "
        "\\[tool.alpha-audit] in pyproject.toml, found from here upwards).",
    ),
]


# A flag's value: one number, a repeatable flag's list of them, or not given.
Given = TypeVar("Given", bound=float | list[int] | list[float] | None)


def in_range(flag: str, allowed: ranges.NumberRange) -> Callable[[Given], Given]:
    """A typer callback refusing a value of ``flag`` outside ``allowed`` (each, if repeatable).

    The range is the one the theme or config key of the same meaning obeys
    (:mod:`alpha_audit.ranges`), so the flag and the file refuse alike.
    """

    def check(value: Given) -> Given:
        for number in value if isinstance(value, list) else () if value is None else (value,):
            if not allowed.allows(number):
                raise UsageError(allowed.refusal(f"{flag} {number:g}"))
        return value

    return check


ThresholdOption = Annotated[
    float | None,
    typer.Option(
        help="Contrast threshold (default: the theme's, else 3.0 = WCAG 1.4.11).",
        callback=in_range("--threshold", ranges.CONTRAST_RATIO),
    ),
]


def rules_flag(
    flag: str, refused: tuple[str, ...] = (), why: str = ""
) -> Callable[[list[str] | None], list[str] | None]:
    """A typer callback parsing rule names, naming ``flag``; ``refused`` rules are errors."""

    def check(values: list[str] | None) -> list[str] | None:
        from alpha_audit.errors import UsageError
        from alpha_audit.policy import Rule

        allowed = [r.value for r in Rule if r.value not in refused]
        for value in values or []:
            name = value.strip().lower()
            if name in refused:
                raise UsageError(f"{flag} {value} is not allowed here: {why}")
            if name not in allowed:
                close = difflib.get_close_matches(name, allowed, n=1)
                hint = f"did you mean {close[0]!r}? " if close else ""
                raise UsageError(
                    f"{flag}: unknown rule {value!r}; {hint}use one of: {', '.join(allowed)}"
                )
        return values

    return check


MaxLossOption = Annotated[
    float | None,
    typer.Option(
        "--max-loss",
        help="Contrast loss tolerated by the loss rule. [default: 0]",
        callback=in_range("--max-loss", ranges.CONTRAST_LOSS),
    ),
]
MinDeltaEOption = Annotated[
    float | None,
    typer.Option(
        "--min-delta-e",
        help="Smallest CIEDE2000 for separation and confusion. [default: 10]",
        callback=in_range("--min-delta-e", ranges.DELTA_E),
    ),
]
MaxDriftOption = Annotated[
    float | None,
    typer.Option(
        "--max-drift",
        help="Largest CIEDE2000 colour drift for drift. [default: 10]",
        callback=in_range("--max-drift", ranges.DELTA_E),
    ),
]
MinSizeContrastOption = Annotated[
    float | None,
    typer.Option(
        "--min-size-contrast",
        help="Smallest size contrast for thin-strokes. [default: the threshold]",
        callback=in_range("--min-size-contrast", ranges.CONTRAST_RATIO),
    ),
]
PipelineOption = Annotated[
    str | None,
    typer.Option(
        "--pipeline",
        metavar="linear|css",
        help="How icons are drawn: linear (the paper: WebGL, linearRGB filter, exported "
        "colours) or css (browser opacity, alpha in [0, 1]). [default: the config's, the "
        "icon set's, the theme's, else linear]",
        show_default=False,
    ),
]
GamutOption = Annotated[
    str | None,
    typer.Option(
        "--gamut",
        metavar="clip|map|error",
        help="Colours outside sRGB in themes, manifests and tokens: clip (per channel, as "
        "browsers do), map (CSS Color 4 gamut mapping) or error. [default: the config's, "
        "else each file's gamut:, else error]",
        show_default=False,
    ),
]
StrictSvgOption = Annotated[
    bool,
    typer.Option("--strict-svg", help="Treat an SVG that cannot be rendered as an input error."),
]
ForceOption = Annotated[bool, typer.Option("--force", help="Replace existing output files.")]


def _no_cache(ctx: typer.Context, value: bool) -> bool:
    """``--no-cache``: this command neither reads nor writes the render cache."""
    if value:
        from alpha_audit.load.render_cache import disable

        ctx.call_on_close(disable())
    return value


NoCacheOption = Annotated[
    bool,
    typer.Option(
        "--no-cache",
        help="Render every icon afresh: neither read nor write the render cache "
        "($ALPHA_AUDIT_CACHE_DIR, else the user cache folder; ALPHA_AUDIT_NO_CACHE=1 "
        "does the same).",
        callback=_no_cache,
    ),
]


def read_gamut_option(value: str | None) -> GamutPolicy | None:
    """``--gamut`` checked against the policies, or a usage error listing them."""
    if value is None:
        return None
    if value not in GAMUT_POLICIES:
        allowed = ", ".join(GAMUT_POLICIES)
        raise UsageError(f"--gamut {value!r} is not a policy; use one of: {allowed}")
    return value


OPTION_ORDER = "alpha_audit.option_order"


def hide_flag_types(params: list[Any]) -> list[Any]:
    """``params`` with no type shown after a flag.

    typer's rich help prints ``<bool>`` after every flag (``--force <bool>``),
    which reads as if it took a value; a flag shows no type, as in click.
    """
    for param in params:
        if getattr(param, "is_flag", False) and param.metavar is None:
            param.metavar = ""
    return params


class Command(TyperCommand):
    """Every alpha-audit command: typer's, with flags shown as flags in its help."""

    def get_params(self, ctx: Any) -> list[Any]:
        return hide_flag_types(super().get_params(ctx))


class OrderedOptionsCommand(Command):
    """A command that records the order its options were given in (``ctx.meta``).

    Click hands each repeatable option over as one list, which loses which
    ``--output`` followed which ``--format``; the parser knows, so ask it once.
    """

    def parse_args(self, ctx: typer.Context, args: list[str]) -> list[str]:  # type: ignore[override]  # the base names typer's private click Context; typer.Context is its public subclass
        """Record ``[param name, ...]`` per option occurrence, then parse as usual."""
        _, _, order = self.make_parser(ctx).parse_args(args=list(args))
        ctx.meta[OPTION_ORDER] = [p.name for p in order]
        return super().parse_args(ctx, args)
