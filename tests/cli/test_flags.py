"""Library errors name parameters; only the command line words them as flags."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import alpha_audit
from alpha_audit.cli.flags import FLAGS, cli_message
from alpha_audit.errors import InputError, UsageError

SRC = Path(alpha_audit.__file__).resolve().parent
FLAG = re.compile(r"(?<![\w-])--?(?!color-)[a-z][a-z-]*\b")  # not CSS --color-* properties
PHRASE = re.compile(r"`([^`\n]+)`")


def _raised_strings() -> list[tuple[str, str]]:
    """(file:line, text) of every string literal inside a ``raise`` outside ``cli/``."""
    found = []
    for path in SRC.rglob("*.py"):
        if "cli" in path.relative_to(SRC).parts[:1]:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.Raise):
                continue
            for sub in ast.walk(node):
                if isinstance(sub, ast.Constant) and isinstance(sub.value, str):
                    found.append((f"{path.relative_to(SRC)}:{sub.lineno}", sub.value))
    return found


def test_the_scan_sees_library_messages() -> None:
    texts = [text for _, text in _raised_strings()]
    assert any("already exists; pass `overwrite=True`" in t for t in texts)


def test_library_errors_name_no_flags() -> None:
    flagged = [(where, t) for where, t in _raised_strings() if FLAG.search(t)]
    assert flagged == []


def test_every_parameter_phrase_has_a_flag() -> None:
    phrases = {m for _, t in _raised_strings() for m in PHRASE.findall(t)}
    assert phrases <= set(FLAGS), phrases - set(FLAGS)


@pytest.mark.parametrize(
    ("error", "expected"),
    [
        (
            UsageError("already exists; pass `overwrite=True` to replace it", path="out.json"),
            "out.json: already exists; pass --force to replace it",
        ),
        (
            UsageError("`alphas` is empty; give at least one coefficient"),
            "--alpha is empty; give at least one coefficient",
        ),
        (InputError("`unknown` stays as written", key="k"), "k: `unknown` stays as written"),
    ],
)
def test_cli_message_words_parameters_as_flags(error: UsageError, expected: str) -> None:
    assert cli_message(error) == expected


def test_the_python_wording_is_kept_for_library_users() -> None:
    error = UsageError("already exists; pass `overwrite=True` to replace it", path="out.json")
    assert str(error) == "out.json: already exists; pass `overwrite=True` to replace it"
