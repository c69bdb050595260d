"""``suggest --apply set|colour|icon``: per-icon edits that keep explicit choices and layout."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.gate import evaluate
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.theme import load_theme
from alpha_audit.policy import Policy
from alpha_audit.rows import audit
from alpha_audit.suggest import suggest
from alpha_audit.suggest.apply import (
    apply_suggestion,
    edit_alphas,
    explicit_alpha_icons,
)


def _alphas(text: str) -> dict[str, object]:
    """Per-icon alphas the override section of ``text`` sets (parsed, so layout-independent)."""
    doc = yaml.safe_load(text)
    return {k: (v or {}).get("alpha") for k, v in (doc.get("overrides") or {}).items()}


EDITS = [
    # (manifest, icons to set, expected text)
    (
        "overrides:\n  a: {color: red}   # why\n",
        {"a": "1.3"},
        "overrides:\n  a: {color: red, alpha: 1.3}   # why\n",
    ),
    (
        "overrides:\n  a:\n    color: red  # block\nname: x\n",
        {"a": "1.3"},
        "overrides:\n  a:\n    color: red  # block\n    alpha: 1.3\nname: x\n",
    ),
    (  # a block entry followed by a sibling: its alpha goes under it, not under the sibling
        "overrides:\n  a:\n    color: red\n  b: {color: red}\n",
        {"a": "1.3"},
        "overrides:\n  a:\n    color: red\n    alpha: 1.3\n  b: {color: red}\n",
    ),
    ("overrides:\n  a:\n", {"a": "1.3"}, "overrides:\n  a: {alpha: 1.3}\n"),
    ("overrides: {}\n", {"a": "1.3"}, "overrides: {a: {alpha: 1.3}}\n"),
    ("overrides:  # none yet\n", {"a": "1.3"}, "overrides:  # none yet\n  a: {alpha: 1.3}\n"),
    ("name: x", {"a": "1.3"}, "name: x\noverrides:\n  a: {alpha: 1.3}\n"),
    (
        "overrides:\n    alert:   {alpha: 1.2}\n    ok:      {color: red}\n",
        {"new": "1.4", "a-very-long-name": "1.5"},
        "overrides:\n    alert:   {alpha: 1.2}\n    ok:      {color: red}\n"
        "    new:     {alpha: 1.4}\n    a-very-long-name: {alpha: 1.5}\n",
    ),
    ("overrides:\n  a: {alpha: 1.2}\n", {"odd: name": "1.4"}, None),
]


@pytest.mark.parametrize(("text", "icons", "expected"), EDITS)
def test_edit_alphas_adds_alpha_where_the_manifest_keeps_overrides(
    text: str, icons: dict[str, str], expected: str | None
) -> None:
    edited = edit_alphas(text, icons=icons)
    if expected is not None:
        assert edited == expected
    # Whatever the layout, the YAML now says exactly this, and nothing else moved.
    got = _alphas(edited)
    for name, value in icons.items():
        assert got[name] == float(value)
    before = _alphas(text) if yaml.safe_load(text) else {}
    for name, value in before.items():
        if name not in icons:
            assert got[name] == value


def test_edit_alphas_replaces_explicit_values_in_place_keeping_comment_columns() -> None:
    text = "icons:\n  - {file: a.svg, alpha: 1.05}   # explicit\n  - b.svg\nalpha: 1.1  # all\n"
    assert explicit_alpha_icons(text) == {"a"}
    edited = edit_alphas(text, top="1.25", icons={"a": "1.3"})
    assert (
        edited
        == "icons:\n  - {file: a.svg, alpha: 1.3}    # explicit\n  - b.svg\nalpha: 1.25 # all\n"
    )


def _project(tmp_path: Path, repo: Path) -> tuple[Path, str]:
    target = tmp_path / "vibrant"
    shutil.copytree(repo / "examples" / "vibrant", target)
    (tmp_path / ".git").mkdir()
    return target / "iconset.yaml", str(repo / "themes" / "paper16.yaml")


@pytest.mark.parametrize("scope", ["colour", "icon"])
def test_apply_per_colour_and_icon_passes_the_gate_and_keeps_alert(
    tmp_path: Path, repo: Path, scope: str
) -> None:
    manifest, theme_path = _project(tmp_path, repo)
    original = manifest.read_text()
    theme, before = load_theme(theme_path), load_iconset(manifest)
    result = suggest(audit(theme, before), Policy())
    plan, changed = apply_suggestion(manifest, result, scope)
    assert changed and plan.passes and plan.kept == ("alert",)
    after = load_iconset(manifest)
    by_name = {i.name: i.alpha for i in after.icons}
    assert by_name["alert"] == 1.18  # the explicit choice is kept
    assert {n: by_name[n] for n in plan.icons} == plan.icons
    colours = {i.color_name: i.alpha for i in after.icons if i.name != "alert"}
    assert {c: colours[c] for c in plan.palette} == plan.palette  # one alpha per colour
    assert (scope == "colour") == bool(plan.palette) and (scope == "icon") == bool(plan.icons)
    # Independently: the gate passes on the manifest as written.
    assert evaluate([audit(theme, after)], Policy()).passed
    # Every original line is still there, in order, but the palette entries given an alpha.
    given = {f"  {c}:" for c in plan.palette}
    kept = [line for line in original.splitlines() if not line.startswith(tuple(given))]
    lines = iter(manifest.read_text().splitlines())
    assert all(any(line == got for got in lines) for line in kept)


def test_apply_replace_explicit_overwrites_alert(tmp_path: Path, repo: Path) -> None:
    manifest, theme = _project(tmp_path, repo)
    res = CliRunner().invoke(
        app, ["suggest", theme, str(manifest), "--apply", "set", "--replace-explicit"]
    )
    assert res.exit_code == 0, res.output
    assert {i.alpha for i in load_iconset(manifest).icons} == {1.193}


def test_apply_unknown_scope_is_a_usage_error(tmp_path: Path, repo: Path) -> None:
    manifest, theme = _project(tmp_path, repo)
    res = CliRunner().invoke(app, ["suggest", theme, str(manifest), "--apply", "everything"])
    assert res.exit_code == 2
    assert manifest.read_text() == (repo / "examples" / "vibrant" / "iconset.yaml").read_text()


def test_apply_icon_replace_explicit_rewrites_list_entries_too(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    svg = (Path(__file__).parents[2] / "examples" / "vibrant" / "svg").resolve()
    (tmp_path / "svg").mkdir()
    for name in ("alert", "bell", "check"):
        shutil.copy(svg / f"{name}.svg", tmp_path / "svg" / f"{name}.svg")
    manifest = tmp_path / "iconset.yaml"
    manifest.write_text(
        "name: x  # keep\n"
        "icons:\n"
        "  - {file: svg/alert.svg, alpha: 1.05}   # explicit\n"
        "  - svg/bell.svg\n"
        "  - svg/check.svg\n"
        "palette: {o: '#ee7733', b: '#0077bb'}\n"
        "color: cycle\n"
        "alpha: 1.1\n"
    )
    theme = load_theme(Path(__file__).parents[2] / "themes" / "paper16.yaml")
    result = suggest(audit(theme, load_iconset(manifest)), Policy())
    kept, _ = apply_suggestion(manifest, result, "icon")
    assert kept.kept == ("alert",) and "alert" not in kept.icons
    text = manifest.read_text()
    assert "{file: svg/alert.svg, alpha: 1.05}   # explicit" in text
    plan, _ = apply_suggestion(
        manifest,
        suggest(audit(theme, load_iconset(manifest)), Policy()),
        "icon",
        replace_explicit=True,
    )
    assert plan.kept == () and "alert" in plan.icons
    after = {i.name: i.alpha for i in load_iconset(manifest).icons}
    assert after["alert"] == plan.icons["alert"]
    assert manifest.read_text().startswith("name: x  # keep\n")
    assert evaluate([audit(theme, load_iconset(manifest))], Policy()).passed == plan.passes
