"""Issue 21: a folder committed as a link cannot aim a report, or a read, outside the checkout."""

from __future__ import annotations

import errno
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.cli.root import _classify
from alpha_audit.cli.status import ExitStatus


@pytest.fixture
def project(tmp_path: Path) -> Path:
    (tmp_path / "proj" / ".git").mkdir(parents=True)
    (tmp_path / "outside").mkdir()
    (tmp_path / "proj" / "reports").symlink_to("../outside")
    (tmp_path / "proj" / "deep").mkdir()
    (tmp_path / "proj" / "deep" / "out").symlink_to("../../outside")
    return tmp_path


def _run(args: list[str], cwd: Path):  # type: ignore[no-untyped-def]
    old = Path.cwd()
    os.chdir(cwd)
    try:
        return CliRunner().invoke(app, args)
    finally:
        os.chdir(old)


@pytest.mark.parametrize(
    "target", ["reports/r.json", "deep/out/r.json", "reports/../reports/r.json"]
)
def test_a_linked_folder_leading_out_is_refused_before_anything_is_written(
    project: Path, target: str
) -> None:
    result = _run(["check", "paper16", "vibrant", "-f", "json", "-o", target], project / "proj")
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "leads outside the project" in result.stderr and result.stderr.count("\n") == 1
    assert list((project / "outside").iterdir()) == []


def test_a_path_given_outside_the_project_is_the_users_choice(project: Path) -> None:
    target = project / "outside" / "r.json"
    result = _run(
        ["check", "paper16", "vibrant", "-f", "json", "-o", str(target)], project / "proj"
    )
    assert result.exit_code == 0, result.output
    assert target.is_file()


def test_a_linked_folder_is_refused_when_run_from_outside_the_project(project: Path) -> None:
    # The project is where the name lies, not only the working folder's: run from above it.
    for args in (
        ["check", "paper16", "vibrant", "-f", "json", "-o", "proj/reports/r.json"],
        ["export", "--config", "proj/alpha-audit.yaml", "-o", "proj/reports"],
    ):
        (project / "proj" / "alpha-audit.yaml").write_text(TOKENS_CONFIG)
        (project / "proj" / "t.tokens.json").write_text(TOKENS)
        result = _run(args, project)
        assert result.exit_code == ExitStatus.INPUT_ERROR, (args, result.output)
        assert "leads outside the project" in result.stderr
        assert list((project / "outside").iterdir()) == []


@pytest.mark.parametrize(
    "args",
    [
        ["export", "-f", "dtcg", "-o", "reports/new/deeper"],
        ["preview", "paper16", "vibrant", "-o", "reports/sheets"],
    ],
    ids=["export", "preview"],
)
def test_an_output_folder_to_create_through_a_link_is_refused_before_it_is_made(
    project: Path, args: list[str]
) -> None:
    (project / "proj" / "alpha-audit.yaml").write_text(TOKENS_CONFIG)
    (project / "proj" / "t.tokens.json").write_text(TOKENS)
    result = _run(args, project / "proj")
    assert result.exit_code == ExitStatus.INPUT_ERROR, result.output
    assert "leads outside the project" in result.stderr
    assert list((project / "outside").iterdir()) == []  # not even an empty folder


def test_make_folder_refuses_a_link_on_the_way_before_making_anything(project: Path) -> None:
    from alpha_audit.errors import UsageError
    from alpha_audit.output import make_folder

    old = Path.cwd()
    os.chdir(project / "proj")
    try:
        with pytest.raises(UsageError, match="leads outside the project"):
            make_folder("reports/results/figures")  # reproduce --out, preview -o, export -o
        assert make_folder("deep/results").is_dir()
    finally:
        os.chdir(old)
    assert list((project / "outside").iterdir()) == []


TOKENS = '{"bg": {"$type": "color", "$value": "#fff"}, "c": {"$type": "color", "$value": "#000"}}'
TOKENS_CONFIG = "tokens:\n  file: t.tokens.json\n  canvases: bg\n  colors: c\nalpha: 1.1\n"


@pytest.mark.parametrize(
    "args",
    [
        ["check", "reports/t.yaml", "vibrant"],
        ["check", "paper16", "reports/s.yaml"],
        ["check", "paper16", "vibrant", "--baseline", "reports/b.json"],
        ["check", "--config", "reports/c.yaml"],
    ],
    ids=["theme", "manifest", "baseline", "config"],
)
def test_a_file_named_through_a_linked_folder_is_refused_before_reading(
    project: Path, args: list[str]
) -> None:
    outside = project / "outside"
    (outside / "t.yaml").write_text("name: t\ncanvases: [{color: '#fff'}]\n")
    (outside / "s.yaml").write_text("icons: svg/*.svg\ncolor: '#000'\n")
    (outside / "b.json").write_text('{"schema": "alpha-audit.baseline/2", "entries": []}')
    (outside / "c.yaml").write_text("themes: [paper16]\niconsets: [vibrant]\n")
    result = _run(args, project / "proj")
    assert result.exit_code == ExitStatus.INPUT_ERROR, result.output
    assert "leads through a symlink to a file outside the project root" in result.stderr


@pytest.mark.parametrize("code", [errno.ENOSPC, errno.EIO, errno.EPIPE])
def test_a_failing_output_stream_is_exit_2_not_a_bug(code: int) -> None:
    status, line = _classify(OSError(code, os.strerror(code)))
    assert status is ExitStatus.INPUT_ERROR and line.startswith("cannot write the output")


def test_a_file_name_in_an_os_error_is_shown_escaped() -> None:
    status, line = _classify(PermissionError(13, "Permission denied", "a\x1b]52;c;x\x07b"))
    assert status is ExitStatus.INPUT_ERROR and "\x1b" not in line and "\x07" not in line


def _closed_pipe() -> int:
    read, write = os.pipe()
    os.close(read)  # every write now fails with EPIPE, as into `| head -c 10` once head is gone
    return write


CASES = [
    (args, stream)
    for args in (["check", "paper16", "vibrant", "-f", "json"], ["themes"], ["--version"])
    for stream in ("closed pipe", "/dev/full")
]
CASES += [(["check", "--help"], "/dev/full"), (["check", "--help"], "closed pipe")]
CASES += [(["--help"], "closed pipe")]  # help is printed through rich: its own pipe handling


@pytest.mark.parametrize(("args", "stream"), CASES, ids=lambda v: str(v))
def test_stdout_that_cannot_be_written_is_exit_2_with_one_line(
    tmp_path: Path, args: list[str], stream: str
) -> None:
    if stream == "/dev/full" and not Path("/dev/full").exists():
        pytest.skip("no /dev/full here")
    out = _closed_pipe() if stream == "closed pipe" else os.open("/dev/full", os.O_WRONLY)
    exe = Path(sys.executable).with_name("alpha-audit")
    try:
        run = subprocess.run(
            [str(exe), *args],
            cwd=tmp_path,
            stdout=out,
            stderr=subprocess.PIPE,
            text=True,
            env={**os.environ, "NO_COLOR": "1"},
            timeout=120,
        )
    finally:
        os.close(out)
    assert run.returncode == ExitStatus.INPUT_ERROR, run.stderr
    assert run.stderr.startswith("alpha-audit: error: cannot write the output: "), run.stderr
    assert "Traceback" not in run.stderr and "Exception ignored" not in run.stderr
