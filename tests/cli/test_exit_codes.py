"""One test per exit code, and the boundary's one-line messages (``alpha_audit.cli.root``)."""

from __future__ import annotations

from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from alpha_audit.cli import ExitStatus, app

runner = CliRunner()

PAIR = ["pair", "#ee7733", "--on", "white"]


def _lines(output: str) -> list[str]:
    return [line for line in output.splitlines() if line.strip()]


def test_exit_codes_are_the_documented_ones() -> None:
    assert [(s.name, int(s)) for s in ExitStatus] == [
        ("OK", 0),
        ("GATE_FAILED", 1),
        ("INPUT_ERROR", 2),
        ("INTERNAL_ERROR", 3),
    ]


def test_exit_0_when_the_gate_passes() -> None:
    result = runner.invoke(app, ["check", "github-primer", "vibrant", "-f", "json"])
    assert result.exit_code == ExitStatus.OK, result.output
    assert "gate passed" in result.stderr


def test_exit_1_when_the_gate_fails() -> None:
    args = ["check", "github-primer", "vibrant", "--fail-on", "separation", "--min-delta-e", "12"]
    result = runner.invoke(app, args)
    assert result.exit_code == ExitStatus.GATE_FAILED, result.output
    assert "gate failed: 1 separation" in result.stderr


def test_exit_zero_reports_but_exits_0() -> None:
    args = ["check", "github-primer", "vibrant", "--fail-on", "separation", "--min-delta-e", "12"]
    args.append("--exit-zero")
    result = runner.invoke(app, args)
    assert result.exit_code == ExitStatus.OK
    assert "gate failed" in result.stderr


def test_exit_2_on_bad_input_in_one_line() -> None:
    result = runner.invoke(app, ["check", "missing.yaml", "vibrant"])
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert _lines(result.output) == ["alpha-audit: error: missing.yaml: file not found"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["check", "--zzz"], "No such option: --zzz (see 'alpha-audit check --help')"),
        (["nope"], "No such command 'nope' (see 'alpha-audit --help')"),
        (["--bogus"], "No such option: --bogus (see 'alpha-audit --help')"),
        (["pair"], "Missing argument 'COLOR'"),
    ],
)
def test_exit_2_on_usage_errors_in_one_line(args: list[str], message: str) -> None:
    result = runner.invoke(app, args, prog_name="alpha-audit")
    assert result.exit_code == ExitStatus.INPUT_ERROR
    lines = _lines(result.output)
    assert len(lines) == 1 and lines[0].startswith("alpha-audit: error: "), result.output
    assert message.lower() in lines[0].lower()


def _crash(*args: object, **kwargs: object) -> None:
    raise RuntimeError("boom\nsecond line")


def test_exit_3_on_an_unexpected_exception_without_traceback(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr("alpha_audit.pair.pair_table", _crash)
    result = runner.invoke(app, PAIR)
    assert result.exit_code == ExitStatus.INTERNAL_ERROR
    lines = _lines(result.output)
    assert len(lines) == 1, result.output
    assert "bug in alpha-audit" in lines[0] and "RuntimeError: boom" in lines[0]
    assert "--debug" in lines[0]
    assert "Traceback" not in result.output and "second line" not in result.output


@pytest.mark.parametrize("how", ["flag", "env"])
def test_debug_adds_the_traceback(monkeypatch: pytest.MonkeyPatch, how: str) -> None:
    monkeypatch.setattr("alpha_audit.pair.pair_table", _crash)
    if how == "flag":
        result = runner.invoke(app, ["--debug", *PAIR])
    else:
        result = runner.invoke(app, PAIR, env={"ALPHA_AUDIT_DEBUG": "1"})
    assert result.exit_code == ExitStatus.INTERNAL_ERROR
    assert "Traceback (most recent call last)" in result.output
    assert "in _crash" in result.output and "RuntimeError: boom" in result.output


def test_a_crash_in_check_is_3_never_the_gate_code(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("alpha_audit.pipeline.check_project", _crash)
    result = runner.invoke(app, ["check", "github-primer", "vibrant"])
    assert result.exit_code == ExitStatus.INTERNAL_ERROR


def test_out_of_memory_is_2_naming_the_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    def exhausted(*args: object, **kwargs: object) -> None:
        raise MemoryError

    monkeypatch.setattr("alpha_audit.pair.pair_table", exhausted)
    result = runner.invoke(app, PAIR)
    assert result.exit_code == ExitStatus.INPUT_ERROR
    lines = _lines(result.output)
    assert len(lines) == 1 and "out of memory" in lines[0]
    assert "address-space limit" in lines[0]
    assert "bug" not in lines[0]


def test_the_memory_limit_in_force_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    resource = pytest.importorskip("resource")
    monkeypatch.setattr(resource, "getrlimit", lambda which: (512 << 20, resource.RLIM_INFINITY))

    def exhausted(*args: object, **kwargs: object) -> None:
        raise MemoryError

    monkeypatch.setattr("alpha_audit.pair.pair_table", exhausted)
    result = runner.invoke(app, PAIR)
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "the address-space limit of 512 MiB" in result.output


def test_an_os_error_on_a_file_is_2_naming_it(monkeypatch: pytest.MonkeyPatch) -> None:
    def refused(*args: object, **kwargs: object) -> None:
        raise PermissionError(13, "Permission denied", "/ro/report.json")

    monkeypatch.setattr("alpha_audit.pair.pair_table", refused)
    result = runner.invoke(app, PAIR)
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert _lines(result.output) == ["alpha-audit: error: /ro/report.json: Permission denied"]


def test_library_parameters_are_worded_as_flags(tmp_path: Path) -> None:
    target = tmp_path / "r.json"
    target.write_text("mine")
    args = ["check", "github-primer", "vibrant", "-f", "json", "-o", str(target)]
    result = runner.invoke(app, args)
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "already exists; pass --force to replace it" in result.output
    assert "overwrite" not in result.output and target.read_text() == "mine"


def test_missing_baseline_names_the_flag(tmp_path: Path) -> None:
    missing = tmp_path / "none.json"
    result = runner.invoke(app, ["check", "github-primer", "vibrant", "--baseline", str(missing)])
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "record one with --write-baseline" in result.output


def test_help_and_version_exit_0() -> None:
    assert runner.invoke(app, ["--help"]).exit_code == 0
    version = runner.invoke(app, ["--version"])
    assert version.exit_code == 0 and version.output.startswith("alpha-audit ")


def test_no_arguments_shows_the_help_not_an_error() -> None:
    result = runner.invoke(app, [], prog_name="alpha-audit")
    assert result.exit_code == ExitStatus.INPUT_ERROR  # typer's convention, as before
    assert "Usage: alpha-audit" in result.output and "error:" not in result.output


def test_a_command_must_return_an_exit_status() -> None:
    # The boundary enforces the contract: a command returning None is a bug (exit 3), so every
    # command's own tests (exit 0 or 1 expected) also check that it returns its status.
    from alpha_audit.cli.root import _Group

    probe = typer.Typer(cls=_Group)
    probe.command("ok")(lambda: ExitStatus.GATE_FAILED)
    probe.command("none")(lambda: None)
    assert runner.invoke(probe, ["ok"]).exit_code == ExitStatus.GATE_FAILED
    result = runner.invoke(probe, ["none"])
    assert result.exit_code == ExitStatus.INTERNAL_ERROR
    assert "command returned None, not an ExitStatus" in result.output


def test_an_internal_error_line_stays_short(monkeypatch: pytest.MonkeyPatch) -> None:
    def verbose(*args: object, **kwargs: object) -> None:
        raise ValueError("x" * 5000)

    monkeypatch.setattr("alpha_audit.pair.pair_table", verbose)
    result = runner.invoke(app, PAIR)
    assert result.exit_code == ExitStatus.INTERNAL_ERROR
    (line,) = _lines(result.output)
    assert "ValueError: " in line and len(line) < 400
