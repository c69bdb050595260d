"""Options shared by several commands, declared once (typer ``Annotated`` aliases)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

__all__ = [
    "ConfigOption",
    "ForceOption",
    "IconsetArgument",
    "MaxDriftOption",
    "MaxLossOption",
    "MinDeltaEOption",
    "MinSizeContrastOption",
    "PipelineOption",
    "StrictSvgOption",
    "ThemeArgument",
    "ThresholdOption",
]

ThemeArgument = Annotated[
    Path | None,
    typer.Argument(help="Theme YAML (default: what the project config names)."),
]
IconsetArgument = Annotated[
    Path | None,
    typer.Argument(help="Icon-set manifest YAML (default: what the project config names)."),
]
ConfigOption = Annotated[
    Path | None,
    typer.Option(
        "--config",
        help="Project config (default: alpha-audit.yaml, .alpha-audit.yaml or "
        "\\[tool.alpha-audit] in pyproject.toml, found from here upwards).",
    ),
]
ThresholdOption = Annotated[
    float | None,
    typer.Option(help="Contrast threshold (default: the theme's, else 3.0 = WCAG 1.4.11)."),
]
MaxLossOption = Annotated[
    float | None,
    typer.Option("--max-loss", help="Contrast loss tolerated by the loss rule. [default: 0]"),
]
MinDeltaEOption = Annotated[
    float | None,
    typer.Option(
        "--min-delta-e",
        help="Smallest CIEDE2000 for separation and confusion. [default: 10]",
    ),
]
MaxDriftOption = Annotated[
    float | None,
    typer.Option("--max-drift", help="Largest CIEDE2000 colour drift for drift. [default: 10]"),
]
MinSizeContrastOption = Annotated[
    float | None,
    typer.Option(
        "--min-size-contrast",
        help="Smallest size contrast for thin-strokes. [default: the threshold]",
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
StrictSvgOption = Annotated[
    bool,
    typer.Option("--strict-svg", help="Treat an SVG that cannot be rendered as an input error."),
]
ForceOption = Annotated[bool, typer.Option("--force", help="Replace existing output files.")]
