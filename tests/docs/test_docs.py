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


def test_every_rule_id_range_the_docs_state_is_the_registrys() -> None:
    """A range of SARIF rule ids written in prose (``AA001``...``AA0NN``) names every rule
    of the registry, in order, and nothing more (docs/ci.md said AA015 with 16 rules)."""
    import re

    from alpha_audit.rules import RULES

    ids = [spec.sarif_id for spec in RULES.values()]
    stated = [
        (path, match)
        for path in [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
        for match in re.findall(
            r"`(AA\d{3})`\s*(?:\.\.\.|…|-|–|to)\s*`(AA\d{3})`", path.read_text()
        )
    ]
    assert stated, "no rule id range found in the docs"
    for path, (first, last) in stated:
        assert (first, last) == (ids[0], ids[-1]), f"{path.name} states {first}...{last}"
    assert ids == [f"AA{k:03d}" for k in range(1, len(ids) + 1)]  # contiguous, never renumbered
