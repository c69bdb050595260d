"""``alpha-audit check``: audit icon sets on themes and apply the CI gate."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, progress_bar, stderr_note, stdout_options
from alpha_audit.cli.options import (
    ConfigOption,
    ForceOption,
    IconsetArgument,
    MaxLossOption,
    MinDeltaEOption,
    StrictSvgOption,
    ThemeArgument,
    ThresholdOption,
    require_finite,
    rules_flag,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.render import CheckFormat, RenderOptions

__all__ = ["check_command", "pair_outputs"]


def pair_outputs(
    formats: list[CheckFormat], outputs: list[Path]
) -> list[tuple[CheckFormat, Path | None]]:
    """Pair each ``--format`` with the ``--output`` in the same position.

    Formats without an output (or with ``-``) go to stdout; only one may.
    """
    from alpha_audit.errors import UsageError

    formats = formats or [CheckFormat.TABLE]
    if len(outputs) > len(formats):
        raise UsageError(
            f"{len(outputs)} --output for {len(formats)} --format; give one format per output"
        )
    pairs = [
        (fmt, None if i >= len(outputs) or str(outputs[i]) == "-" else outputs[i])
        for i, fmt in enumerate(formats)
    ]
    to_stdout = [fmt.value for fmt, out in pairs if out is None]
    if len(to_stdout) > 1:
        raise UsageError(
            f"formats {', '.join(to_stdout)} would all go to stdout; give each but one an --output"
        )
    return pairs


def check_command(
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    themes: Annotated[
        list[Path] | None,
        typer.Option(
            "--theme",
            metavar="PATH",
            help="Another theme to audit (repeatable).",
            show_default=False,
        ),
    ] = None,
    iconsets: Annotated[
        list[Path] | None,
        typer.Option(
            "--iconset", metavar="PATH", help="Another icon set (repeatable).", show_default=False
        ),
    ] = None,
    config: ConfigOption = None,
    alpha: Annotated[
        float | None,
        typer.Option("--alpha", "-a", help="Coefficient for every icon (overrides the manifest)."),
    ] = None,
    threshold: ThresholdOption = None,
    fail_on: Annotated[
        list[str] | None,
        typer.Option(
            "--fail-on",
            metavar="RULE",
            help="Rule that fails the gate (repeatable; replaces the policy): loss, "
            "below-threshold, newly-failing, collision, new-collision, separation, unrenderable. "
            "[default: loss, newly-failing, new-collision]",
            show_default=False,
            callback=rules_flag("--fail-on"),
        ),
    ] = None,
    max_loss: MaxLossOption = None,
    min_delta_e: MinDeltaEOption = None,
    exit_zero: Annotated[
        bool, typer.Option("--exit-zero", help="Report findings but exit 0 even if the gate fails.")
    ] = False,
    fmt: Annotated[
        list[CheckFormat] | None,
        typer.Option(
            "--format",
            "-f",
            metavar="FORMAT",
            help=f"Report format (repeatable): {', '.join(CheckFormat)}.",
            case_sensitive=False,
            show_default=False,
        ),
    ] = None,
    output: Annotated[
        list[Path] | None,
        typer.Option(
            "--output",
            "-o",
            metavar="PATH",
            help="File for the --format in the same position ('-' = stdout; repeatable).",
            show_default=False,
        ),
    ] = None,
    baseline: Annotated[
        Path | None,
        typer.Option("--baseline", help="Fail only on findings not in this baseline file."),
    ] = None,
    write_baseline: Annotated[
        Path | None,
        typer.Option("--write-baseline", help="Record today's findings as a baseline file."),
    ] = None,
    force: ForceOption = False,
    strict_svg: StrictSvgOption = False,
) -> ExitStatus:
    """Audit icon sets on themes and fail the build on the findings the policy names.

    Per canvas: mean contrast gain against a = 1, icons at or above the threshold
    (at a = 1 -> at a), icons that newly pass, contrast losses, 8-bit collisions
    between distinct colours, and the smallest CIEDE2000 between the set's colours.
    With no THEME ICONSET, audits what the project config names.

    THEME may name a bundled theme (see [bold]alpha-audit themes[/]) and ICONSET the
    bundled example set [bold]vibrant[/].

    Exit codes: 0 the gate passed, 1 the gate failed, 2 bad input or usage, 3 a bug.

    Example:
    [bold]alpha-audit check themes/github-primer.yaml examples/vibrant/iconset.yaml -a 1.2[/]
    """
    from alpha_audit.bundled import iconset_source, theme_source
    from alpha_audit.errors import UsageError
    from alpha_audit.gate import baseline_document, read_baseline
    from alpha_audit.load.config import project_config
    from alpha_audit.output import write_text
    from alpha_audit.pipeline import check_project
    from alpha_audit.render.json import dumps

    require_finite(alpha, "--alpha")
    require_finite(threshold, "--threshold")
    pairs = pair_outputs(list(fmt or []), list(output or []))
    if (theme is None) != (iconset is None):
        raise UsageError("give both THEME and ICONSET, or neither (to use the project config)")

    project = project_config(config, Path.cwd())
    cli_themes = [theme_source(t) for t in ([theme] if theme else []) + list(themes or [])]
    cli_sets = [iconset_source(s) for s in ([iconset] if iconset else []) + list(iconsets or [])]
    policy = project.policy.with_overrides(
        rules=fail_on, max_loss=max_loss, min_delta_e=min_delta_e
    )
    baseline_path = baseline if baseline is not None else project.baseline
    known = read_baseline(baseline_path) if baseline_path is not None else None

    with progress_bar("Rendering icons") as (on_start, on_icon):
        report = check_project(
            cli_themes or project.themes,
            cli_sets or project.iconsets,
            policy=policy,
            alpha=alpha if alpha is not None else project.alpha,
            threshold=threshold if threshold is not None else project.threshold,
            baseline=known,
            strict_svg=strict_svg or project.strict_svg,
            on_start=on_start,
            on_icon=on_icon,
        )
    base = Path.cwd().resolve()
    for kind, out in pairs:
        options = replace(stdout_options(), base=base) if out is None else RenderOptions(base=base)
        emit(kind.renderer()(report, options), out, force)
    if write_baseline is not None:
        write_text(write_baseline, dumps(baseline_document(report.gate)), overwrite=force)
        stderr_note(f"wrote baseline {write_baseline}")
        return ExitStatus.OK
    gate = report.gate
    if gate.passed:
        stderr_note("gate passed")
        return ExitStatus.OK
    counts = ", ".join(f"{n} {rule}" for rule, n in gate.counts().items())
    stderr_note(f"gate failed: {counts}" + (" (--exit-zero)" if exit_zero else ""))
    return ExitStatus.OK if exit_zero else ExitStatus.GATE_FAILED
