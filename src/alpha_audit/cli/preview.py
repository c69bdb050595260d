"""``alpha-audit preview``: PNG sheets and an interactive WebGL2 page."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import progress_bar, stderr_line
from alpha_audit.cli.options import (
    ForceOption,
    GamutOption,
    NoCacheOption,
    PipelineOption,
    StrictSvgOption,
    ThresholdOption,
    ranged,
    read_gamut_option,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.preview.sheets import ImageFormat, Layout
from alpha_audit.ranges import ALPHA, ICON_SIZE

__all__ = ["preview_command"]


# preview's options of its own (the shared ones are in cli/options.py).
_Theme = Annotated[
    Path, typer.Argument(help="Theme YAML (canvases, light and dark) or a bundled theme name.")
]
_Iconset = Annotated[Path, typer.Argument(help="Icon-set manifest YAML, or vibrant (bundled).")]
_Output = Annotated[
    Path | None, typer.Option("--output", "-o", help="Folder for the sheets (created if missing).")
]
_Html = Annotated[
    Path | None,
    typer.Option("--html", help="Write one self-contained interactive WebGL2 page here."),
]
_Alphas = Annotated[
    list[float] | None,
    ranged(
        "--alpha",
        "-a",
        allowed=ALPHA,
        metavar="A",
        help="Coefficient row, any real value in [-100, 100] (repeatable). "
        "[default: 1 and the set's own; swatches: 0.6 1 1.1 1.2 1.4 2]",
    ),
]
_Sizes = Annotated[
    list[int] | None,
    ranged(
        "--size",
        "-s",
        allowed=ICON_SIZE,
        metavar="PX",
        help="Icon size in px (repeatable). [default: 48; page: set's + 48]",
    ),
]
_ImageFormat = Annotated[
    ImageFormat,
    typer.Option(
        "--format",
        "-f",
        help="Sheet files: png, or webp (lossless, about a third of the size, "
        "twice as long to write).",
        case_sensitive=False,
    ),
]
_Layout = Annotated[
    Layout,
    typer.Option(
        "--layout",
        "-l",
        help="grid: a sheet per canvas and size; swatches: palette x alpha per canvas; "
        "compare: alpha 1 beside alpha X, a row per canvas.",
        case_sensitive=False,
    ),
]
_NearSource = Annotated[
    bool,
    typer.Option(
        "--near-source",
        help="Use the paper's gallery canvases instead of the theme's: each palette colour "
        "mixed with 10% white (encoded sRGB), plus a dark grey.",
    ),
]


def preview_command(
    theme: _Theme,
    iconset: _Iconset,
    output: _Output = None,
    html: _Html = None,
    alpha: _Alphas = None,
    size: _Sizes = None,
    image_format: _ImageFormat = ImageFormat.PNG,
    layout: _Layout = Layout.GRID,
    near_source: _NearSource = False,
    threshold: ThresholdOption = None,
    pipeline: PipelineOption = None,
    force: ForceOption = False,
    strict_svg: StrictSvgOption = False,
    gamut: GamutOption = None,
    no_cache: NoCacheOption = False,
) -> ExitStatus:
    """Draw the icons on the theme's canvases: PNG sheets (-o DIR) and/or a WebGL2 page (--html).

    Each icon is drawn as its audit rows draw it: every paint (an SVG's own fills
    and strokes, currentColor in the manifest colour) in its own colour and opacity,
    in painter's order, under the pipeline check uses. Linear: P = o q clip(Cb +
    a(Cs - Cb)) + (1 - o q) P in linear sRGB; css: source-over on encoded values;
    8 bits rounded half to even. Under each icon: its rows' size contrast at the
    drawn size (the number check --format json gives); a small square marks an
    icon that hard-codes a colour. Labels never cover an icon.

    Example:
    [bold]alpha-audit preview themes/paper16.yaml examples/vibrant/iconset.yaml -o previews
    --html previews/vibrant.html[/]
    """
    from alpha_audit.bundled import iconset_source, theme_source
    from alpha_audit.load.config import Overrides, resolve_config
    from alpha_audit.preview.files import preview_files

    gamut_policy = read_gamut_option(gamut)
    # The pipeline as check decides it: the flag, else the project config's; preview_files
    # goes on to the icon set's, the theme's, else linear.
    project = resolve_config(Overrides(pipeline=pipeline), Path.cwd())
    with progress_bar("Rendering previews") as progress:
        result = preview_files(
            theme_source(theme),
            iconset_source(iconset),
            out_dir=output,
            html_path=html,
            layout=layout,
            alphas=alpha or (),
            sizes=size or (),
            near_source=near_source,
            threshold=threshold,
            overwrite=force,
            strict_svg=strict_svg,
            progress=progress,
            gamut=gamut_policy,
            pipeline=project.pipeline,
            image_format=image_format,
        )
    for problem in result.problems:
        stderr_line(f"skipped {problem.icon}: {problem.file}: {problem.message}")
    for path in result.written:
        stderr_line(f"wrote {path}")
    return ExitStatus.OK
