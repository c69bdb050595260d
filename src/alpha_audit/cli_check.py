"""``alpha-audit check``: audit an icon set on a theme."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.render import CheckFormat, RenderOptions, render_check

__all__ = ["check_command"]


def check_command(
    theme: Annotated[Path, typer.Argument(help="Theme YAML: canvases (light and dark).")],
    iconset: Annotated[Path, typer.Argument(help="Icon-set manifest YAML.")],
    alpha: Annotated[
        float | None,
        typer.Option("--alpha", "-a", help="Coefficient for every icon (overrides the manifest)."),
    ] = None,
    threshold: Annotated[
        float | None,
        typer.Option(help="Contrast threshold (default: the theme's, else 3.0 = WCAG 1.4.11)."),
    ] = None,
    fmt: Annotated[
        CheckFormat, typer.Option("--format", "-f", help="Report format.", case_sensitive=False)
    ] = CheckFormat.TABLE,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="Write the report here instead of stdout.")
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="Replace an existing --output file.")
    ] = False,
    strict_svg: Annotated[
        bool,
        typer.Option(
            "--strict-svg", help="Treat an SVG that cannot be rendered as an input error."
        ),
    ] = False,
) -> None:
    """Composite every icon on every canvas and report what the coefficient changes.

    Per canvas: mean contrast gain against a = 1, icons at or above the threshold
    (at a = 1 -> at a), icons that newly pass, contrast losses, 8-bit collisions
    between distinct colours, and the smallest CIEDE2000 between the set's colours.

    Example:
    [bold]alpha-audit check themes/github-primer.yaml examples/vibrant/iconset.yaml -a 1.2[/]
    """
    from alpha_audit.cli import emit, progress_bar, require_finite, stdout_options
    from alpha_audit.pipeline import check_files

    require_finite(alpha, "--alpha")
    require_finite(threshold, "--threshold")
    with progress_bar("Rendering icons") as (on_start, on_icon):
        result = check_files(
            theme,
            iconset,
            alpha=alpha,
            threshold=threshold,
            strict_svg=strict_svg,
            on_start=on_start,
            on_icon=on_icon,
        )
    options = stdout_options() if output is None else RenderOptions()
    emit(render_check(result, fmt, options), output, force)
