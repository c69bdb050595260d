"""Every usage error is one line on stderr, exit 2; help stays rich."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app

CASES = [
    (["check", "a.yaml", "b.yaml", "c.yaml"], "unexpected extra argument"),
    (["chek"], "No such command 'chek'. Did you mean 'check'?"),
    (["--bogus"], "No such option: --bogus"),
    (["check", "-f", "nope"], "'nope' is not one of"),
    (["suggest", "--alpha-max", "x"], "--alpha-max"),
    (["suggest", "--apply", "everything"], "--apply"),
    (["pair"], "Missing argument"),
    # A rule only a browser's pixels raise: check and suggest refuse it (issue 31).
    (["check", "paper16", "vibrant", "--fail-on", "render-drift"], "only render raises it"),
    (["suggest", "paper16", "vibrant", "--fail-on", "render-drift"], "only render raises it"),
    # And render refuses check's rules.
    (["render", "x", "--fail-on", "loss"], "it is a rule of check"),
]


@pytest.mark.parametrize(("args", "says"), CASES)
def test_usage_errors_are_one_line(args: list[str], says: str) -> None:
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert lines[0].startswith("alpha-audit: error: ") and says in lines[0]
    assert "╭" not in res.stderr and "Usage:" not in res.stderr
    assert res.stdout == ""


OSC52 = "\x1b]52;c;SGVsbG8=\x07"


@pytest.mark.parametrize(
    ("args", "says"),
    [
        # A backslash in the value was read as a regex group escape: a traceback, no exit code.
        (["check", "-a", "1\\x2"], "'1\\\\x2' is not a number"),
        (["check", "-f", f"x{OSC52}\n::stop-commands::t"], "'x\\x1b]52;c;SGVsbG8=\\x07\\n::stop"),
        (["check", "--fail-on", f"\u202e{OSC52}"], "unknown rule"),
        ([f"ch{OSC52}eck"], "No such command"),
    ],
)
def test_hostile_values_on_the_command_line_come_back_escaped(args: list[str], says: str) -> None:
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    line = res.stderr.rstrip("\n")
    assert "\n" not in line and line.startswith("alpha-audit: error: ") and says in line
    assert not any(c in line for c in "\x1b\x07\u202e"), repr(line)


def test_help_is_still_rich() -> None:
    res = CliRunner().invoke(app, ["check", "-h"])
    assert res.exit_code == 0
    assert "╭" in res.stdout and "Usage:" in res.stdout


@pytest.mark.parametrize("command", ["check", "suggest", "preview"])
@pytest.mark.parametrize("value", ["25", "0.5", "nan", "-inf"])
def test_threshold_is_range_checked_like_the_themes(command: str, value: str) -> None:
    res = CliRunner().invoke(app, [command, "--threshold", value])
    assert res.exit_code == 2, res.output
    assert res.stderr.strip().splitlines() == [
        f"alpha-audit: error: --threshold {float(value):g} is out of range; "
        "expected a contrast ratio between 1 and 21"
    ]


FLAG_ERRORS = [
    (["check", "--min-delta-e", "-1"], "--min-delta-e -1 is out of range"),
    (["suggest", "--min-delta-e", "nan"], "--min-delta-e nan is out of range"),
    (["check", "--max-loss", "-0.5"], "--max-loss -0.5 is out of range"),
    (["suggest", "--alpha-max", "0.5"], "--alpha-max 0.5 is out of range"),
    (["suggest", "--precision", "12"], "--precision 12 is out of range"),
    (["check", "--fail-on", "seperation"], "--fail-on: unknown rule 'seperation'; did you mean"),
]


@pytest.mark.parametrize(("args", "says"), FLAG_ERRORS)
def test_errors_name_flags_as_flags(args: list[str], says: str) -> None:
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    (line,) = res.stderr.strip().splitlines()
    assert says in line
    assert "min_delta_e" not in line and "max_loss" not in line and "alpha_max" not in line


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["check", "paper16", "vibrant", "-a", "abc"], "'--alpha' / '-a': 'abc' is not a number"),
        (["check", "paper16", "vibrant", "--alpha=x1"], "'x1' is not a number"),
        (["check", "paper16", "vibrant", "--threshold", "high"], "'high' is not a number"),
        (["preview", "paper16", "vibrant", "--size", "1.5"], "'1.5' is not a whole number"),
        (["check", "paper16", "vibrant", "-f", "xml"], "'--format' / '-f': 'xml' is not one of"),
    ],
)
def test_a_value_that_does_not_parse_is_named_in_plain_words(args: list[str], says: str) -> None:
    """typer passes pydantic's wording on ("Input should be a valid number"), without the value."""
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and says in lines[0], result.output
    assert "Input should" not in lines[0] and "Value error" not in lines[0]
