"""The CI gate: rules, exemptions, exit codes, repeatable formats, several themes x sets,
and a design repository wired as docs/ci.md says, run the way pre-commit runs the hook."""

from __future__ import annotations

import json
import os
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from alpha_audit.cli import ExitStatus, app
from alpha_audit.cli.check import pair_outputs
from alpha_audit.errors import UsageError
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Exemption, Policy
from alpha_audit.render import CheckFormat
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

REPO = Path(__file__).resolve().parents[2]
SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24" fill="none" '
    'stroke="currentColor" stroke-width="2"><circle cx="12" cy="12" r="8"/></svg>'
)
# The paper's worked worst case: sRGB (0, 0, 0.8125) on yellow loses contrast for a > 1.
LOSING_BLUE, YELLOW = "#0000cf", "#ffff00"
# On black at a = 2 both clip to white: a collision that does not exist at a = 1.
PALE_A, PALE_B = "#eeeeee", "#dddddd"


def _theme(*canvases: tuple[str, str]) -> Theme:
    return Theme("t", tuple(Canvas(n, c) for n, c in canvases))


def _set(*icons: tuple[str, str, float]) -> IconSet:
    return IconSet("s", tuple(Icon(n, Path(f"{n}.svg"), c, a) for n, c, a in icons))


def _rules(gate) -> list[tuple[str, str | None, tuple[str, ...]]]:
    return [(f.rule.value, f.canvas, f.icons) for f in gate.failures]


# --- gate evaluation, table-driven ---------------------------------------------------------
CASES = [
    # (canvases, icons, rules, expected failures)
    (
        [("yellow", YELLOW)],
        [("dot", LOSING_BLUE, 1.1)],
        {Rule.LOSS},
        [("loss", "yellow", ("dot",))],
    ),
    ([("yellow", YELLOW)], [("dot", LOSING_BLUE, 1.0)], {Rule.LOSS}, []),
    ([("white", "#ffffff")], [("dot", "#0077bb", 1.1)], {Rule.LOSS}, []),  # pure white: no loss
    (
        [("black", "#000000")],
        [("a", PALE_A, 2.0), ("b", PALE_B, 2.0)],
        {Rule.NEW_COLLISION},
        [("new-collision", "black", ("a", "b"))],
    ),
    (
        [("black", "#000000")],
        [("a", PALE_A, 2.0), ("b", PALE_B, 2.0)],
        {Rule.COLLISION, Rule.NEW_COLLISION},  # reported once, under the broader rule
        [("collision", "black", ("a", "b"))],
    ),
    (
        [("white", "#ffffff")],
        [("g", "#bbbbbb", 1.0)],
        {Rule.BELOW_THRESHOLD},
        [("below-threshold", "white", ("g",))],
    ),
    ([("white", "#ffffff")], [("g", "#bbbbbb", 1.0)], {Rule.LOSS, Rule.NEWLY_FAILING}, []),
    (
        [("white", "#ffffff")],
        [("a", "#777777", 1.0), ("b", "#787878", 1.0)],
        {Rule.SEPARATION},
        [("separation", "white", ("a", "b"))],
    ),
]


@pytest.mark.parametrize(("canvases", "icons", "rules", "expected"), CASES)
def test_rules(canvases, icons, rules, expected) -> None:
    result = audit(_theme(*canvases), _set(*icons))
    gate = evaluate([result], Policy(rules=frozenset(rules)))
    assert _rules(gate) == expected
    assert gate.passed is (not expected)


def test_newly_failing_numbers() -> None:
    # Near the paper's worked case (10.28 at a = 1 -> 8.64 at a = 1.4): it crosses 9:1.
    result = audit(_theme(("yellow", YELLOW)), _set(("dot", LOSING_BLUE, 1.4)), threshold=9.0)
    (f,) = evaluate([result], Policy(rules=frozenset({Rule.NEWLY_FAILING}))).failures
    assert f.figures.contrast_ref >= 9.0 > f.figures.contrast
    assert f.figures.alpha == 1.4 and f.figures.background == YELLOW


def test_max_loss_tolerates_small_losses() -> None:
    result = audit(_theme(("yellow", YELLOW)), _set(("dot", LOSING_BLUE, 1.1)))
    loss = -float(result.gain.min())
    assert not evaluate([result], Policy(max_loss=loss * 1.01)).failures
    assert evaluate([result], Policy(max_loss=loss * 0.99)).failures


def test_exemptions_need_reasons_and_keep_findings_visible() -> None:
    result = audit(_theme(("yellow", YELLOW)), _set(("dot", LOSING_BLUE, 1.1)))
    exempt = Exemption(reason="brand colour, reviewed", canvas="yellow")
    gate = evaluate([result], Policy(exemptions=(exempt,)))
    assert gate.passed
    assert [f.exemption for f in gate.findings] == [exempt]
    other = Exemption(reason="x", canvas="yellow", rule=Rule.COLLISION)
    assert not evaluate([result], Policy(exemptions=(other,))).passed
    with pytest.raises(UsageError, match="reason"):
        Policy(exemptions=(Exemption(reason=" ", icon="dot"),))


def test_rule_names() -> None:
    assert Rule.parse(" Loss ") is Rule.LOSS
    with pytest.raises(UsageError, match="new-collision"):
        Rule.parse("colision")


@pytest.mark.parametrize(
    ("formats", "outputs", "expected"),
    [
        ([], [], [(CheckFormat.TABLE, None)]),
        ([CheckFormat.JSON], ["r.json"], [(CheckFormat.JSON, Path("r.json"))]),
        (
            [CheckFormat.TABLE, CheckFormat.SARIF],
            ["-", "r.sarif"],
            [(CheckFormat.TABLE, None), (CheckFormat.SARIF, Path("r.sarif"))],
        ),
        (
            [CheckFormat.JUNIT, CheckFormat.TABLE],
            ["j.xml"],
            [
                (CheckFormat.JUNIT, Path("j.xml")),
                (CheckFormat.TABLE, None),
            ],
        ),
        ([CheckFormat.JSON, CheckFormat.TABLE], [], None),  # two on stdout
        ([CheckFormat.JSON], ["a", "b"], None),  # more outputs than formats
    ],
)
def test_pair_outputs(formats, outputs, expected) -> None:
    if expected is None:
        with pytest.raises(UsageError):
            pair_outputs(formats, [Path(o) for o in outputs])
    else:
        assert pair_outputs(formats, [Path(o) for o in outputs]) == expected


# --- the CLI: one test per exit code -------------------------------------------------------
def write_repo(root: Path, colors: dict[str, str], *, alpha: float = 1.1, config: bool = True):
    """A small design repository: a theme, a manifest, SVGs and alpha-audit.yaml."""
    (root / "icons").mkdir(parents=True, exist_ok=True)
    (root / "themes").mkdir(exist_ok=True)
    for name in colors:
        (root / "icons" / f"{name}.svg").write_text(SVG)
    theme = {
        "name": "brand",
        "canvases": [
            {"name": "paper", "color": "#ffffff"},
            {"name": "ink", "color": "#000000"},
            {"name": "sun", "color": YELLOW},
        ],
    }
    (root / "themes" / "brand.yaml").write_text(yaml.safe_dump(theme, sort_keys=False))
    manifest = {
        "name": "brand-icons",
        "icons": [{"file": f"{n}.svg", "color": c} for n, c in colors.items()],
        "color": "#000000",  # the manifest wants a default even when every icon sets one
        "alpha": alpha,
        "sizes": [16, 24],
    }
    (root / "icons" / "iconset.yaml").write_text(yaml.safe_dump(manifest, sort_keys=False))
    if config:
        (root / "alpha-audit.yaml").write_text(
            "themes: [themes/brand.yaml]\niconsets: [icons/iconset.yaml]\n"
        )
    return root


def run(args: list[str], cwd: Path):
    """Invoke the CLI in-process from ``cwd``."""
    old = Path.cwd()
    os.chdir(cwd)
    try:
        return CliRunner().invoke(app, args, catch_exceptions=False)
    finally:
        os.chdir(old)


def test_exit_0_when_the_gate_passes(tmp_path: Path) -> None:
    write_repo(tmp_path, {"alert": "#ee7733", "info": "#0077bb"})
    result = run(["check"], tmp_path)
    assert result.exit_code == ExitStatus.OK, result.output
    assert "gate passed" in result.output


def test_exit_1_when_the_gate_fails(tmp_path: Path) -> None:
    write_repo(tmp_path, {"alert": "#ee7733", "deep": LOSING_BLUE})
    result = run(["check", "-f", "json"], tmp_path)
    assert result.exit_code == ExitStatus.GATE_FAILED
    doc = json.loads(result.stdout)
    (failure,) = doc["gate"]["failures"]
    assert (failure["rule"], failure["icons"], failure["canvas"]) == ("loss", ["deep"], "sun")
    assert failure["numbers"]["contrast"] < failure["numbers"]["contrast_ref"]
    assert failure["files"] == ["icons/deep.svg"]


def test_exit_2_on_bad_input(tmp_path: Path) -> None:
    write_repo(tmp_path, {"alert": "#ee7733"})
    (tmp_path / "themes" / "brand.yaml").write_text("canvases: []\n")
    result = run(["check"], tmp_path)
    assert result.exit_code == ExitStatus.INPUT_ERROR
    assert "brand.yaml" in result.output and "Traceback" not in result.output


def test_exit_zero_reports_without_failing(tmp_path: Path) -> None:
    write_repo(tmp_path, {"deep": LOSING_BLUE})
    result = run(["check", "--exit-zero", "-f", "markdown"], tmp_path)
    assert result.exit_code == ExitStatus.OK
    assert "gate failed" in result.stdout and "| sun | loss |" in result.stdout


def test_fail_on_replaces_the_default_policy(tmp_path: Path) -> None:
    write_repo(tmp_path, {"deep": LOSING_BLUE, "grey": "#bbbbbb"})
    assert run(["check", "--fail-on", "collision"], tmp_path).exit_code == 0
    result = run(["check", "--fail-on", "below-threshold", "-f", "json"], tmp_path)
    assert result.exit_code == 1
    rules = {f["rule"] for f in json.loads(result.stdout)["gate"]["failures"]}
    assert rules == {"below-threshold"}
    bad = run(["check", "--fail-on", "losss"], tmp_path)
    assert bad.exit_code == 2 and "unknown rule" in bad.output


def test_every_format_to_its_own_output(tmp_path: Path) -> None:
    write_repo(tmp_path, {"deep": LOSING_BLUE})
    args = ["check", "--exit-zero"]
    for fmt in CheckFormat:
        args += ["-f", fmt.value, "-o", f"report.{fmt.value}"]
    result = run(args, tmp_path)
    assert result.exit_code == 0, result.output
    for fmt in CheckFormat:
        assert (tmp_path / f"report.{fmt.value}").stat().st_size > 0
    again = run(["check", "-f", "json", "-o", "report.json"], tmp_path)
    assert again.exit_code == 2 and "--force" in again.output  # never overwritten unasked


def test_many_themes_many_sets(tmp_path: Path) -> None:
    write_repo(tmp_path, {"deep": LOSING_BLUE})
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "a.svg").write_text(SVG)
    (tmp_path / "other" / "set.yaml").write_text('icons: "*.svg"\ncolor: "#ee7733"\n')
    (tmp_path / "themes" / "dark.yaml").write_text(
        'name: dark\ncanvases: [{name: night, color: "#0d1117"}]\n'
    )
    (tmp_path / "alpha-audit.yaml").write_text(
        "themes: [themes/brand.yaml, themes/dark.yaml]\n"
        "iconsets: [icons/iconset.yaml, other/set.yaml]\n"
    )
    result = run(["check", "-f", "json"], tmp_path)
    assert result.exit_code == 1  # only brand-icons on brand fails; any failure fails the gate
    doc = json.loads(result.stdout)
    pairs = [(a["iconset"]["name"], a["theme"]["name"]) for a in doc["audits"]]
    assert pairs == [
        ("brand-icons", "brand"),
        ("brand-icons", "dark"),
        ("other", "brand"),
        ("other", "dark"),
    ]
    assert {(f["iconset"], f["theme"]) for f in doc["gate"]["failures"]} == {
        ("brand-icons", "brand")
    }


# --- end to end: the pre-commit hook's entry, run the way pre-commit runs it ---------------
def _hook_command() -> list[str]:
    hooks = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    hook = next(h for h in hooks if h["id"] == "alpha-audit")
    assert hook["pass_filenames"] is False and hook["language"] == "python"
    entry = shlex.split(hook["entry"]) + list(hook.get("args", []))
    # pre-commit installs the package into its own venv and runs the entry from the
    # repository root; ours is installed in the interpreter running the tests.
    entry[0] = str(Path(sys.executable).with_name(entry[0]))
    return entry


def _git(root: Path, *args: str) -> None:
    subprocess.run(["git", *args], cwd=root, check=True, capture_output=True)


def test_pre_commit_hook_fails_on_a_loss_or_collision_and_passes_otherwise(
    tmp_path: Path,
) -> None:
    root = write_repo(tmp_path / "design", {"alert": "#ee7733", "info": "#0077bb"}, alpha=1.1)
    _git(root, "init", "-q")
    cmd = _hook_command()

    def hook(*extra: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([*cmd, *extra], cwd=root, capture_output=True, text=True, timeout=60)

    clean = hook()
    assert clean.returncode == 0, clean.stderr
    assert "Traceback" not in clean.stderr

    # A pull request adds an icon that loses contrast on the yellow canvas.
    write_repo(root, {"alert": "#ee7733", "info": "#0077bb", "deep": LOSING_BLUE}, alpha=1.1)
    loss = hook("--format", "github")
    assert loss.returncode == 1
    # Annotated on the line that sets the failing value (the set-wide alpha), so
    # GitHub shows it in the diff; the SVG is named as a related place.
    lines = (root / "icons" / "iconset.yaml").read_text().splitlines()
    alpha_line = next(n for n, text in enumerate(lines, 1) if text.startswith("alpha:"))
    assert (
        f"::error file=icons/iconset.yaml,line={alpha_line},title=alpha-audit loss::"
        "deep on sun (brand / brand-icons)"
    ) in loss.stdout
    assert "SVG icons/deep.svg" in loss.stdout

    # Another raises alpha so two pale icons collide on black (and nothing loses contrast).
    write_repo(root, {"pale": PALE_A, "paler": PALE_B}, alpha=2.0)
    for name in ("alert", "info", "deep"):
        (root / "icons" / f"{name}.svg").unlink()
    collision = hook("--format", "junit")
    assert collision.returncode == 1
    assert 'type="new-collision"' in collision.stdout and 'classname="brand-icons.ink"' in (
        collision.stdout
    )


@pytest.mark.parametrize(
    ("path", "runs"),
    [
        ("alpha-audit-baseline.json", True),
        ("ci/baseline.json", True),
        ("icons/svg/alert.svg", True),
        ("themes/paper16.yaml", True),
        ("alpha-audit.yml", True),
        ("pyproject.toml", True),
        ("package.json", False),
        ("baseline.json.bak", False),
        ("README.md", False),
    ],
)
def test_pre_commit_hook_reruns_when_the_baseline_changes(path: str, runs: bool) -> None:
    import re

    hooks = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    hook = next(h for h in hooks if h["id"] == "alpha-audit")
    # pre-commit matches `files` with re.search on the repository-relative path.
    assert bool(re.search(hook["files"], path)) is runs
