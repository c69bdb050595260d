"""Documentation stays true: every command is in the README, docs/cli.md matches --help."""

from __future__ import annotations

import importlib.util
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def _tool():
    spec = importlib.util.spec_from_file_location("cli_reference", REPO / "tools/cli_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_command_is_in_the_readme() -> None:
    readme = (REPO / "README.md").read_text()
    for name in _tool().commands():
        assert f"alpha-audit {name}" in readme, f"README does not show `alpha-audit {name}`"


def test_cli_reference_is_generated_from_the_real_help() -> None:
    tool = _tool()
    assert tool.DOC.read_text() == tool.reference(), (
        "docs/cli.md is stale: run `python tools/cli_reference.py`"
    )


def test_readme_links_resolve() -> None:
    import re

    readme = (REPO / "README.md").read_text()
    for target in re.findall(r"\]\(((?:docs|themes|examples)/[^)#]+)\)", readme):
        assert (REPO / target).exists(), target


def test_the_rules_table_is_the_registrys() -> None:
    from alpha_audit.rules import rules_table

    assert rules_table() in (REPO / "docs" / "rules.md").read_text(), (
        "docs/rules.md is stale: paste alpha_audit.rules.rules_table() into it"
    )
