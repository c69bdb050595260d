"""Options shared by several commands, declared once (typer ``Annotated`` aliases).

Defaults shown in ``--help`` come from the library (the rule registry,
:class:`~alpha_audit.policy.Policy`'s fields, the WCAG threshold), never typed
by hand.  A flag shows no type after it (``metavar=""``), as in click.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, TypeVar, cast, get_type_hints

import typer
from typer.core import TyperCommand

from alpha_audit import ranges
from alpha_audit.constants import GAMUT_POLICIES, NON_TEXT_THRESHOLD, GamutPolicy
from alpha_audit.errors import UsageError
from alpha_audit.render import CheckFormat
from alpha_audit.rules import CHECK_RULES, DEFAULT_RULES, RULES, Rule

if TYPE_CHECKING:
    from alpha_audit.load.config import Overrides

__all__ = [
    "ARGS",
    "AlphaOption",
    "Command",
    "ConfigOption",
    "ExitZeroOption",
    "FailOnOption",
    "ForceOption",
    "FormatsOption",
    "GamutOption",
    "IconsetArgument",
    "LossToleranceOption",
    "MaxCombinationsOption",
    "MaxDriftOption",
    "MaxLossOption",
    "MinDeltaEOption",
    "MinSizeContrastOption",
    "NearDuplicateOption",
    "NoCacheOption",
    "PipelineOption",
    "PolicyFlags",
    "StrictSvgOption",
    "ThemeArgument",
    "ThresholdOption",
    "VisibilityFloorOption",
    "baseline_option",
    "fail_on_option",
    "flag",
    "given_options",
    "in_range",
    "input_overrides",
    "one_of",
    "path_option",
    "path_value",
    "ranged",
    "read_gamut_option",
    "rules_flag",
    "untyped_flags",
    "with_policy_flags",
]

ARGS = "alpha_audit.args"
"""``ctx.meta`` key: the command's arguments as given (the group records them)."""


def path_value(value: str) -> Path:
    """A path option's value; an empty one is a usage error naming the option.

    ``Path("")`` is the current folder: an empty value (an unset variable in a CI
    script, ``--baseline ""``) would otherwise be read as ``.`` and fail far from
    its cause ("is a directory").
    """
    if not value:
        raise typer.BadParameter("an empty path; give a file name")
    return Path(value)


def path_option(*names: str, **options: Any) -> Any:
    """An option naming a file (metavar ``<path>`` unless told; an empty one refused)."""
    options.setdefault("metavar", "<path>")
    return typer.Option(*names, parser=path_value, **options)


def ranged(*names: str, allowed: ranges.NumberRange, **options: Any) -> Any:
    """A number option refusing a value outside ``allowed`` (:func:`in_range`)."""
    return typer.Option(*names, callback=in_range(names[0], allowed), **options)


ThemeArgument = Annotated[
    Path | None,
    typer.Argument(
        help="Theme YAML or a bundled theme name.",
        show_default="what the project config names",
    ),
]
IconsetArgument = Annotated[
    Path | None,
    typer.Argument(
        help="Icon-set manifest YAML, or vibrant (the bundled example).",
        show_default="what the project config names",
    ),
]
# The report files of check and render: each --output belongs to the --format before it.
OutputsOption = Annotated[
    list[Path] | None,
    path_option(
        "--output",
        "-o",
        metavar="PATH",
        help="File for the --format before it ('-' = stdout; repeatable).",
        show_default="stdout",
    ),
]
WriteBaselineOption = Annotated[
    Path | None,
    path_option("--write-baseline", help="Record today's findings as a baseline file."),
]

ConfigOption = Annotated[
    Path | None,
    path_option(
        "--config",
        help="Project config file.",
        show_default="alpha-audit.yaml, .alpha-audit.yaml or [tool.alpha-audit] in "
        "pyproject.toml, found from here upwards",
    ),
]


def input_overrides(
    theme: Path | None,
    iconset: Path | None,
    *,
    themes: Sequence[Path] = (),
    iconsets: Sequence[Path] = (),
    **more: Any,
) -> Overrides:
    """THEME ICONSET (both, or neither: the config's) and any more given, with ``more``
    overrides (:class:`~alpha_audit.load.config.Overrides`' fields)."""
    from alpha_audit.load.config import Overrides

    if (theme is None) != (iconset is None):
        raise UsageError("give both THEME and ICONSET, or neither (to use the project config)")
    return Overrides(
        themes=(*([theme] if theme else []), *themes),
        iconsets=(*([iconset] if iconset else []), *iconsets),
        **more,
    )


def flag(*names: str, help: str) -> Any:
    """A boolean flag: no value, shown without a type (click's convention)."""
    return typer.Option(*names, help=help, metavar="")


# A flag's value: one number, a repeatable flag's list of them, or not given.
Given = TypeVar("Given", bound=float | list[int] | list[float] | None)  # int is a float here


def in_range(name: str, allowed: ranges.NumberRange) -> Callable[[Given], Given]:
    """A typer callback refusing a value of ``name`` outside ``allowed`` (each, if repeatable).

    The range is the one the theme or config key of the same meaning obeys
    (:mod:`alpha_audit.ranges`), so the flag and the file refuse alike.
    """

    def check(value: Given) -> Given:
        for number in value if isinstance(value, list) else () if value is None else (value,):
            if not allowed.allows(number):
                shown = number if isinstance(number, int) else f"{number:g}"  # 100000000, not 1e+08
                raise UsageError(allowed.refusal(f"{name} {shown}"))
        return value

    return check


def rules_flag(
    name: str, refused: tuple[str, ...] = (), why: str = ""
) -> Callable[[list[str] | None], list[str] | None]:
    """A typer callback parsing rule names, naming ``name``; ``refused`` rules are errors."""

    def check(values: list[str] | None) -> list[str] | None:
        for value in values or []:
            if value.strip().lower() in refused:
                raise UsageError(f"{name} {value} is not allowed here: {why}")
            Rule.parse(value, name)
        return values

    return check


def _policy_default(field: str) -> str:
    from alpha_audit.policy import Policy

    value = getattr(Policy(), field)
    return f"the config's, else {'the threshold' if value is None else f'{value:g}'}"


ThresholdOption = Annotated[
    float | None,
    ranged(
        "--threshold",
        allowed=ranges.CONTRAST_RATIO,
        help="Contrast threshold.",
        show_default=f"the theme's, else {NON_TEXT_THRESHOLD:g}: WCAG 2.2 SC 1.4.11",
    ),
]


def fail_on_option(
    rules: Iterable[str], defaults: Iterable[str], where: str, others: Iterable[str], why: str
) -> Any:
    """``--fail-on RULE`` over ``rules`` (``defaults`` when ``where`` names none); the rules
    of ``others`` are refused with ``why`` (check's and render's are not the same)."""
    return typer.Option(
        "--fail-on",
        metavar="RULE",
        help="Rule that fails the gate (repeatable; replaces the policy): "
        + ", ".join(rules)
        + " (docs/rules.md).",
        show_default=f"{where}, else " + ", ".join(defaults),
        callback=rules_flag("--fail-on", tuple(others), why),
    )


AlphaOption = Annotated[
    float | None,
    ranged(
        "--alpha",
        "-a",
        allowed=ranges.ALPHA,
        help="Coefficient for every icon colour (overrides the config, manifests and tokens).",
        show_default="the config's, else the manifest's and tokens'",
    ),
]
FailOnOption = Annotated[
    list[str] | None,
    fail_on_option(
        CHECK_RULES,
        (r for r in RULES if r in DEFAULT_RULES),
        "the config's",
        (r.value for r in RULES if r not in CHECK_RULES),
        "only render raises it (from a browser's pixels)",
    ),
]


def baseline_option(default: str) -> Any:
    """``--baseline PATH`` (check's and render's; ``default`` says where it is else read)."""
    return path_option(
        "--baseline",
        help="Fail only on findings not in this baseline file.",
        show_default=default,
    )


# The gate's shared flags of check and render.
ExitZeroOption = Annotated[
    bool, flag("--exit-zero", help="Report findings but exit 0 even if the gate fails.")
]
FormatsOption = Annotated[
    list[CheckFormat] | None,
    typer.Option(
        "--format",
        "-f",
        metavar="FORMAT",
        help=f"Report format (repeatable): {', '.join(CheckFormat)}.",
        case_sensitive=False,
        show_default=CheckFormat.TABLE.value,
    ),
]


def _policy_option(field: str, help: str, allowed: ranges.NumberRange) -> Any:
    """A float flag named after the :class:`~alpha_audit.policy.Policy` field it sets."""
    name = "--" + field.replace("_", "-")
    return Annotated[
        float | None,
        ranged(name, allowed=allowed, help=help, show_default=_policy_default(field)),
    ]


MaxLossOption = _policy_option(
    "max_loss", "Contrast loss tolerated by the loss rule.", ranges.CONTRAST_LOSS
)
MinDeltaEOption = _policy_option(
    "min_delta_e", "Smallest CIEDE2000 for separation and confusion.", ranges.DELTA_E
)
MaxDriftOption = _policy_option(
    "max_drift", "Largest CIEDE2000 colour drift for drift.", ranges.DELTA_E
)
VisibilityFloorOption = _policy_option(
    "visibility_floor",
    "Contrast at alpha 1 below which a loss is reported, not gated.",
    ranges.CONTRAST_RATIO,
)
NearDuplicateOption = _policy_option(
    "near_duplicate_delta_e",
    "CIEDE2000 at alpha 1 below which colours already look the same: alpha rounding "
    "them onto one 8-bit output is near-duplicate (reported), not new-collision.",
    ranges.DELTA_E,
)
LossToleranceOption = _policy_option(
    "loss_tolerance",
    "Relative loss (loss / contrast at alpha 1) reported, not gated.",
    ranges.LOSS_TOLERANCE,
)


MaxCombinationsOption = Annotated[
    int | None,
    typer.Option(
        "--max-combinations",
        metavar="N",
        help="Most paint x canvas rows one check audits (memory scales with it: docs/ci.md).",
        callback=in_range("--max-combinations", ranges.COMBINATIONS),
        show_default=f"the config's, else {ranges.DEFAULT_COMBINATIONS:,}",
    ),
]
MinSizeContrastOption = _policy_option(
    "min_size_contrast", "Smallest size contrast for thin-strokes.", ranges.CONTRAST_RATIO
)
PipelineOption = Annotated[
    str | None,
    typer.Option(
        "--pipeline",
        metavar="linear|css",
        help="How icons are drawn: linear (the paper: WebGL, linearRGB filter, exported "
        "colours) or css (browser opacity, alpha in [0, 1]).",
        show_default="the config's, the icon set's, the theme's, else linear",
    ),
]
GamutOption = Annotated[
    str | None,
    typer.Option(
        "--gamut",
        metavar="clip|map|error",
        help="Colours outside sRGB in themes, manifests and tokens: clip (per channel, as "
        "browsers do), map (CSS Color 4 gamut mapping) or error.",
        show_default="the config's, else each file's gamut:, else error",
    ),
]
StrictSvgOption = Annotated[
    bool, flag("--strict-svg", help="Treat an SVG that cannot be rendered as an input error.")
]
ForceOption = Annotated[bool, flag("--force", help="Replace existing output files.")]


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
        metavar="",
    ),
]


def one_of(name: str, value: str, allowed: Sequence[str], what: str) -> None:
    """Refuse ``value`` of flag ``name`` unless it is ``allowed`` (``what`` names the kind)."""
    if value not in allowed:
        raise UsageError(f"{name} {value!r} is not {what}; use one of: {', '.join(allowed)}")


def read_gamut_option(value: str | None) -> GamutPolicy | None:
    """``--gamut`` checked against the policies, or a usage error listing them."""
    if value is not None:
        one_of("--gamut", value, GAMUT_POLICIES, "a policy")
    return cast(GamutPolicy | None, value)


def given_options(
    args: Sequence[str], names: Mapping[str, Sequence[str]]
) -> list[tuple[str, str | None]]:
    """The named options given, in command-line order, each with its value (None: none).

    ``names`` maps a key to the option's spellings (``{"format": ("-f",
    "--format")}``).  Click hands each repeatable option over as one list, which
    loses which ``--output`` followed which ``--format``, and a usage error names
    no value; the arguments as given (:data:`ARGS`) still say.  Values (``-f
    json``, ``-fjson``, ``--format=json``) are read, and ``--`` ends the options.

    >>> given_options(["-f", "json", "-o", "-", "--format=sarif", "-fmd"],
    ...     {"f": ("-f", "--format"), "o": ("-o", "--output")})
    [('f', 'json'), ('o', '-'), ('f', 'sarif'), ('f', 'md')]
    """
    out: list[tuple[str, str | None]] = []
    rest = iter(args)
    for arg in rest:
        if arg == "--":
            break
        for key, spellings in names.items():
            for spelling in spellings:
                glued = spelling + "=" if spelling.startswith("--") else spelling
                if arg == spelling:
                    out.append((key, next(rest, None)))
                elif arg.startswith(glued):
                    out.append((key, arg[len(glued) :]))
    return out


def untyped_flags(params: list[Any]) -> list[Any]:
    """``params`` with no type shown after a flag (``--help``, which typer adds, included)."""
    for param in params:
        if getattr(param, "is_flag", False) and param.metavar is None:
            param.metavar = ""
    return params


class Command(TyperCommand):
    """Every alpha-audit command: typer's, its help option shown without a type."""

    def get_params(self, ctx: Any) -> list[Any]:
        """The command's parameters (click's public hook), ``--help`` with no ``<bool>``."""
        return untyped_flags(super().get_params(ctx))


# ------------------------------------------------------------------ the gate's policy flags

# The flags that set the gate's policy, shared by check and suggest (declared once here;
# with_policy_flags adds them to a command and hands them over as one PolicyFlags).
_POLICY_FLAGS: dict[str, Any] = {
    "threshold": ThresholdOption,
    "fail_on": FailOnOption,
    "max_loss": MaxLossOption,
    "min_delta_e": MinDeltaEOption,
    "max_drift": MaxDriftOption,
    "min_size_contrast": MinSizeContrastOption,
    "visibility_floor": VisibilityFloorOption,
    "loss_tolerance": LossToleranceOption,
    "near_duplicate_delta_e": NearDuplicateOption,
}


@dataclass(frozen=True)
class PolicyFlags:
    """The policy flags a command was given (``None``: the config's value)."""

    threshold: float | None = None
    fail_on: tuple[str, ...] = ()
    max_loss: float | None = None
    min_delta_e: float | None = None
    max_drift: float | None = None
    min_size_contrast: float | None = None
    visibility_floor: float | None = None
    loss_tolerance: float | None = None
    near_duplicate_delta_e: float | None = None

    def overrides(self) -> dict[str, Any]:
        """As :class:`~alpha_audit.load.config.Overrides` fields."""
        return {name: getattr(self, name) for name in _POLICY_FLAGS}


Command_T = TypeVar("Command_T", bound=Callable[..., Any])


def with_policy_flags(command: Command_T) -> Command_T:
    """``command`` with the policy flags added to its options (after its own), handed to
    it as one ``policy_flags: PolicyFlags`` argument (typer reads the new signature)."""
    signature = inspect.signature(command)
    own = [p for p in signature.parameters.values() if p.name != "policy_flags"]
    added = [
        inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=kind)
        for name, kind in _POLICY_FLAGS.items()
    ]

    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        given = {name: kwargs.pop(name) for name in _POLICY_FLAGS}
        given["fail_on"] = tuple(given["fail_on"] or ())
        return command(*args, policy_flags=PolicyFlags(**given), **kwargs)

    hints = {k: v for k, v in get_type_hints(command, include_extras=True).items()}
    hints.pop("policy_flags", None)
    wrapper.__annotations__ = {**hints, **_POLICY_FLAGS}
    wrapper.__signature__ = signature.replace(  # type: ignore[attr-defined]  # read by typer
        parameters=[p.replace(annotation=hints.get(p.name, p.annotation)) for p in own] + added
    )
    return cast(Command_T, wrapper)
