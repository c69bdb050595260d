"""Every numeric option of every command is range-checked like its file key: exit 2, one line."""

from __future__ import annotations

import math
import typing

import pytest
import typer
from typer.testing import CliRunner

from alpha_audit.cli import app

# The allowed ranges, written out here rather than imported: the test states what the
# theme, config and manifest keys accept (docs/config.md) and the flags must match.
CONTRAST = (1, 21, "a contrast ratio between 1 and 21")
DELTA_E = (0, 200, "a CIEDE2000 difference between 0 and 200")
ALPHA = (-100, 100, "a finite coefficient between -100 and 100")
# The gate policy's limits, which check and suggest both take.
POLICY = {
    "--threshold": CONTRAST,
    "--max-loss": (0, 21, "a contrast loss between 0 and 21"),
    "--min-delta-e": DELTA_E,
    "--max-drift": DELTA_E,
    "--min-size-contrast": CONTRAST,
    "--visibility-floor": CONTRAST,
    "--loss-tolerance": (0, 1, "a relative tolerance between 0 and 1"),
    "--near-duplicate-delta-e": DELTA_E,
}
EXPECTED = {
    **{
        (command, flag): allowed
        for command in ("check", "suggest")
        for flag, allowed in POLICY.items()
    },
    ("check", "--alpha"): ALPHA,
    ("check", "--max-combinations"): (1, 10**9, "whole paint x canvas rows, 1 to 1,000,000,000"),
    ("suggest", "--alpha-max"): (1, 100, "a coefficient between 1 and 100"),
    ("suggest", "--precision"): (0, 9, "0-9 decimals"),
    ("preview", "--alpha"): ALPHA,
    ("preview", "--size"): (1, 1024, "whole pixels 1-1024"),
    ("preview", "--threshold"): CONTRAST,
    ("pair", "--alpha"): ALPHA,
    ("export", "--alpha"): ALPHA,
    ("reproduce", "--alpha"): ALPHA,
    ("render", "--workers"): (1, 16, "whole pages in parallel, 1-16"),
    ("render", "--timeout"): (1, 600, "seconds between 1 and 600"),
}
WHOLE = ("--precision", "--size", "--workers", "--max-combinations")  # integer flags
# What a command needs besides the bad flag to get as far as checking it.
REQUIRED = {"preview": ["t.yaml", "i.yaml"], "pair": ["red", "--on", "white"]}


def _numeric_options() -> set[tuple[str, str]]:
    """(command, longest flag) of every option whose values are numbers, from the signatures."""
    found = set()
    for info in app.registered_commands:
        assert info.callback is not None and info.name is not None
        hints = typing.get_type_hints(info.callback, include_extras=True)
        for param, hint in hints.items():
            if typing.get_origin(hint) is not typing.Annotated:
                continue
            base, *extras = typing.get_args(hint)
            option = next((e for e in extras if isinstance(e, typer.models.OptionInfo)), None)
            if option is None:
                continue
            kinds = {a for a in typing.get_args(base) or (base,) if a is not type(None)}
            kinds = {typing.get_args(k)[0] if typing.get_origin(k) is list else k for k in kinds}
            if kinds & {int, float}:
                decls = [option.default, *option.param_decls]
                flags = [d for d in decls if isinstance(d, str) and d.startswith("--")]
                found.add((info.name, flags[0] if flags else "--" + param.replace("_", "-")))
    return found


def test_the_table_names_every_numeric_option() -> None:
    # A new numeric flag must join EXPECTED, and so be range-checked and tested below.
    assert _numeric_options() == set(EXPECTED)


def _bad_values(low: float, high: float, integer: bool) -> list[float]:
    step = 1 if integer else 0.5
    # A whole number too large for %g's six digits is named as given, not as 9e+06.
    return [low - step, high + step] + (
        [int(high) * 1_000_000 + 1] if integer else [math.nan, math.inf]
    )


CASES = [
    (command, flag, value, what)
    for (command, flag), (low, high, what) in EXPECTED.items()
    for value in _bad_values(low, high, flag in WHOLE)
]


@pytest.mark.parametrize(("command", "flag", "value", "what"), CASES)
def test_a_bad_value_exits_2_naming_the_flag_and_the_range(
    command: str, flag: str, value: float, what: str
) -> None:
    shown = str(int(value)) if flag in WHOLE else f"{value:g}"
    res = CliRunner().invoke(app, [command, *REQUIRED.get(command, []), flag, shown])
    assert res.exit_code == 2, res.output
    assert res.stderr.strip().splitlines() == [
        f"alpha-audit: error: {flag} {shown} is out of range; expected {what}"
    ]
    assert res.stdout == ""
