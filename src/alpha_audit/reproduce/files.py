"""What ``reproduce --out`` writes: ``results.json``, ``report.md`` and the sweep figures.

The names are known before anything runs (:func:`planned_files`), so every
target is checked first; the files are then written together, atomically
(:func:`write_results`), once everything has been computed.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from alpha_audit.output import Output, check_targets, make_folder, write_files
from alpha_audit.reproduce.figures import FIGURES, figure_outputs
from alpha_audit.reproduce.report import reproduction_json, reproduction_markdown
from alpha_audit.reproduce.run import Experiment, Reproduction
from alpha_audit.reproduce.runtime import RUNTIME_FIGURE, runtime_figure_output

__all__ = [
    "RESULTS_JSON",
    "RESULTS_MARKDOWN",
    "check_results_folder",
    "planned_files",
    "write_results",
]

RESULTS_JSON = "results.json"
RESULTS_MARKDOWN = "report.md"


def planned_files(folder: str | Path, only: Iterable[Experiment] = ()) -> list[Path]:
    """The files a run of ``only`` (all experiments when empty) writes into ``folder``."""
    folder = Path(folder)
    names = [RESULTS_JSON, RESULTS_MARKDOWN]
    if not set(only) or Experiment.SWEEP in set(only):
        names += list(FIGURES)
    if Experiment.RUNTIME in set(only):
        names.append(RUNTIME_FIGURE)
    return [folder / n for n in names]


def check_results_folder(
    folder: str | Path, only: Iterable[Experiment] = (), *, overwrite: bool
) -> None:
    """Refuse, before the run, a folder whose files cannot all be written."""
    folder = Path(folder)
    if folder.is_dir():  # a folder still to be made holds nothing to overwrite
        check_targets(planned_files(folder, only), overwrite=overwrite)


def write_results(run: Reproduction, folder: str | Path, *, overwrite: bool = False) -> list[Path]:
    """Write every result file of ``run`` into ``folder`` (created if needed), all or none."""
    folder = Path(folder)
    outputs = [
        Output.text(folder / RESULTS_JSON, reproduction_json(run)),
        Output.text(folder / RESULTS_MARKDOWN, reproduction_markdown(run)),
    ]
    if run.sweep is not None:
        outputs += figure_outputs(run.sweep, folder)
    if run.runtime is not None:
        outputs.append(runtime_figure_output(run.runtime, folder / RUNTIME_FIGURE))
    make_folder(folder)
    return write_files(outputs, overwrite=overwrite)
