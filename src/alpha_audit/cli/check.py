"""``alpha-audit check``: audit icon sets on themes and apply the CI gate."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from alpha_audit.cli.console import emit, progress_bar, stderr_note, stdout_options
from alpha_audit.cli.options import (
    ARGS,
    AlphaOption,
    ConfigOption,
    ExitZeroOption,
    ForceOption,
    FormatsOption,
    GamutOption,
    IconsetArgument,
    MaxCombinationsOption,
    NoCacheOption,
    OutputsOption,
    PipelineOption,
    PolicyFlags,
    StrictSvgOption,
    ThemeArgument,
    WriteBaselineOption,
    baseline_option,
    given_options,
    input_overrides,
    path_option,
    with_policy_flags,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.render.common import check_suffix

if TYPE_CHECKING:
    from alpha_audit.gate import Baseline, GateResult
    from alpha_audit.load.config import Overrides, ProjectConfig
    from alpha_audit.results import CheckReport

__all__ = ["check_command", "gate_status", "pair_outputs", "report_targets", "write_reports"]


def pair_outputs(
    formats: list[CheckFormat], outputs: list[Path], order: list[str] | None = None
) -> list[tuple[CheckFormat, Path | None]]:
    """Give each ``--output`` to the ``--format`` before it (``-`` or none: stdout).

    ``order`` is ``"format"`` / ``"output"`` per option as given on the command
    line (:func:`~alpha_audit.cli.options.given_options`); without it, the n-th
    output goes with the n-th format.  One ``-o`` with one ``-f`` pair in either
    order.  Refused: an output whose extension belongs to another format (``-f
    junit -o a.sarif``), an output with no format before it, two outputs for one
    format, and two formats on stdout.
    """
    from alpha_audit.errors import UsageError

    formats = formats or [CheckFormat.TABLE]
    targets: list[Path | None] = [None] * len(formats)
    if (len(outputs) <= 1 and len(formats) == 1) or order is None:
        if len(outputs) > len(formats):
            raise UsageError(
                f"{len(outputs)} --output for {len(formats)} --format; give one format per output"
            )
        targets[: len(outputs)] = outputs
    else:
        f = o = 0
        for kind in order:
            if kind == "format":
                f += 1
            elif kind == "output":
                if f == 0 or targets[f - 1] is not None:
                    where = f"after --format {formats[f - 1].value}" if f else "before any --format"
                    raise UsageError(
                        f"--output {outputs[o]} has no --format of its own ({where}); "
                        "put each --output right after its --format"
                    )
                targets[f - 1] = outputs[o]
                o += 1
    pairs = [
        (fmt, None if out is None or str(out) == "-" else out)
        for fmt, out in zip(formats, targets, strict=True)
    ]
    for fmt, out in pairs:
        if out is not None:
            check_suffix(fmt.value, out)
    to_stdout = [fmt.value for fmt, out in pairs if out is None]
    if len(to_stdout) > 1:
        raise UsageError(
            f"formats {' and '.join(to_stdout)} would both go to stdout; "
            "give each but one an --output"
        )
    return pairs


_ORDER = {"format": ("-f", "--format"), "output": ("-o", "--output")}


def report_targets(
    ctx: typer.Context,
    formats: Sequence[CheckFormat] | None,
    outputs: Sequence[Path] | None,
    write_baseline: Path | None,
    force: bool,
) -> list[tuple[CheckFormat, Path | None]]:
    """Each report's format and file (check's and render's), every file checked writable
    before the work starts (an existing one is refused without ``force``)."""
    from alpha_audit.output import check_targets

    order = [key for key, _ in given_options(ctx.meta.get(ARGS, ()), _ORDER)]
    pairs = pair_outputs(list(formats or []), list(outputs or []), order)
    files = [out for _, out in pairs if out is not None] + [write_baseline] * bool(write_baseline)
    check_targets([f for f in files if f is not None], overwrite=force)
    return pairs


# check's own options (the gate's shared ones are in cli/options.py).
_Themes = Annotated[
    list[Path] | None,
    path_option("--theme", metavar="PATH", help="Another theme to audit (repeatable)."),
]
_Iconsets = Annotated[
    list[Path] | None,
    path_option("--iconset", metavar="PATH", help="Another icon set (repeatable)."),
]
_Base = Annotated[
    str | None,
    typer.Option(
        "--base",
        metavar="REF",
        help="Fail only on what this change adds to git revision REF (a branch, tag or "
        "commit, audited from git; the checkout is not touched).",
        show_default="no base: every finding counts",
    ),
]


@with_policy_flags
def check_command(
    ctx: typer.Context,
    policy_flags: PolicyFlags,  # the policy flags, handed over by with_policy_flags
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    themes: _Themes = None,
    iconsets: _Iconsets = None,
    config: ConfigOption = None,
    alpha: AlphaOption = None,
    max_combinations: MaxCombinationsOption = None,
    pipeline: PipelineOption = None,
    gamut: GamutOption = None,
    exit_zero: ExitZeroOption = False,
    fmt: FormatsOption = None,
    output: OutputsOption = None,
    baseline: Annotated[Path | None, baseline_option("the config's baseline:")] = None,
    write_baseline: WriteBaselineOption = None,
    base: _Base = None,
    force: ForceOption = False,
    strict_svg: StrictSvgOption = False,
    no_cache: NoCacheOption = False,
) -> ExitStatus:
    """Audit icon sets on themes and fail the build on the findings the policy names.

    Per canvas: mean contrast gain against a = 1, paints at or above the threshold
    (at a = 1 -> at a), paints that newly pass, contrast losses, 8-bit collisions
    between distinct colours, and the smallest CIEDE2000 between the set's colours.
    With no THEME ICONSET, audits what the project config names.

    THEME may name a bundled theme (see [bold]alpha-audit themes[/]) and ICONSET the
    bundled example set [bold]vibrant[/].

    Exit codes: 0 the gate passed, 1 the gate failed, 2 bad input or usage, 3 a bug.

    Example:
    [bold]alpha-audit check themes/github-primer.yaml examples/vibrant/iconset.yaml -a 1.2[/]
    """
    from alpha_audit.errors import UsageError
    from alpha_audit.load.config import resolve_config
    from alpha_audit.pipeline import check_project

    if base is not None and (baseline is not None or write_baseline is not None):
        raise UsageError("give --base or a baseline file (--baseline, --write-baseline), not both")
    pairs = report_targets(ctx, fmt, output, write_baseline, force)
    overrides = input_overrides(
        theme,
        iconset,
        themes=themes or (),
        iconsets=iconsets or (),
        config=config,
        alpha=alpha,
        **policy_flags.overrides(),
        max_combinations=max_combinations,
        pipeline=pipeline,
        gamut=gamut,
        baseline=baseline,
        strict_svg=strict_svg,
    )
    project = resolve_config(overrides, Path.cwd())
    known = _known_findings(ctx, overrides, project, base, write_baseline)
    with progress_bar("Rendering icons") as progress:
        report = check_project(
            project,
            pool=ctx.obj,
            progress=progress,
            baseline=known,
            use_baseline=False,
            record=write_baseline is not None,
        )
    for note in report.notes:  # the token modes found, the tokens skipped
        stderr_note(note)
    write_reports(report, pairs, write_baseline, force)
    return gate_status(
        report.gate, writing_baseline=write_baseline is not None, exit_zero=exit_zero
    )


def _known_findings(
    ctx: typer.Context,
    overrides: Overrides,
    project: ProjectConfig,
    base: str | None,
    write_baseline: Path | None,
) -> Baseline | None:
    """The findings the gate accepts: those at git revision ``base``, else the baseline
    file's (unless one is being written), else none; what it found said on stderr."""
    from alpha_audit.baseline import read_baseline
    from alpha_audit.gate import LEGACY_BASELINE_SCHEMA
    from alpha_audit.pipeline import base_baseline

    if base is not None:
        audit = base_baseline(overrides, Path.cwd(), base, pool=ctx.obj)
        for note in audit.notes:
            stderr_note(note)
        if audit.audited:
            stderr_note(f"base {base}: {len(audit.baseline.keys)} failing root cause(s) there")
        return audit.baseline
    if project.baseline is None or write_baseline is not None:
        return None
    known = read_baseline(project.baseline)
    if known.legacy:
        stderr_note(
            f"{project.baseline} is a per-canvas baseline ({LEGACY_BASELINE_SCHEMA}): "
            "a root cause is covered when each of its canvases is; rewrite it with "
            "--write-baseline --force to record root causes"
        )
    return known


def gate_status(gate: GateResult, *, writing_baseline: bool, exit_zero: bool) -> ExitStatus:
    """The gate's verdict on stderr and as the exit status (check's and render's one tail).

    Writing a baseline always passes (today's findings are what it records).
    """
    if writing_baseline:
        stderr_note("gate passed" if gate.passed else "baseline written")
        return ExitStatus.OK
    if gate.passed:
        stderr_note("gate passed")
        return ExitStatus.OK
    counts = gate.counts_text()
    stderr_note(f"gate failed: {counts}" + (" (--exit-zero)" if exit_zero else ""))
    return ExitStatus.OK if exit_zero else ExitStatus.GATE_FAILED


def write_reports(
    report: CheckReport,
    pairs: Sequence[tuple[CheckFormat, Path | None]],
    write_baseline: Path | None,
    force: bool,
) -> None:
    """Each ``(format, file)`` rendered and written (None: stdout, last), and the baseline.

    Paths in reports are relative to the repository (the folder with .git): what
    GitHub annotations, SARIF's %SRCROOT% and GitLab expect, from any subfolder.
    """
    from alpha_audit.gate import baseline_document
    from alpha_audit.load.paths import project_root
    from alpha_audit.output import Output, write_files
    from alpha_audit.render.common import dumps

    root = project_root(Path.cwd())
    outputs, stdout_text = [], None
    for kind, out in pairs:
        if out is None:
            stdout_text = kind.renderer()(report, replace(stdout_options(), base=root))
        else:
            outputs.append(Output.text(out, kind.renderer()(report, RenderOptions(base=root))))
    if write_baseline is not None:
        outputs.append(Output.text(write_baseline, dumps(baseline_document(report.gate))))
    for path in write_files(outputs, overwrite=force):
        stderr_note(f"wrote {'baseline ' if path == write_baseline else ''}{path}")
    if stdout_text is not None:
        emit(stdout_text, None, force)
