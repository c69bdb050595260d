"""action.yml: the sticky comment is found by the Markdown report's marker; the gate decides."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from alpha_audit.render.markdown import MARKER

ACTION = Path(__file__).resolve().parents[2] / "action.yml"


def _steps() -> dict[str, dict[str, Any]]:
    doc = yaml.safe_load(ACTION.read_text(encoding="utf-8"))
    return {step.get("name", step.get("uses")): step for step in doc["runs"]["steps"]}


def test_the_comment_step_looks_for_the_markdown_marker() -> None:
    step = _steps()["Post or update the pull-request comment"]
    assert step["env"]["MARKER"] == MARKER
    assert "inputs.github-token != ''" in step["if"] and "pull_request.number" in step["if"]
    assert "--method PATCH" in step["run"] and "--method POST" in step["run"]


def test_the_report_goes_to_the_job_summary_and_the_gate_exits_last() -> None:
    steps = _steps()
    check = steps["alpha-audit check"]["run"]
    assert "--format markdown --output" in check and "GITHUB_STEP_SUMMARY" in check
    assert "--format github --output -" in check
    names = list(steps)
    assert names[-1] == "Gate verdict" and "exit" in steps["Gate verdict"]["run"]


def test_the_render_cache_is_kept_between_runs_where_the_check_looks_for_it() -> None:
    steps = _steps()
    names = list(steps)
    cache = steps["Restore the render cache"]
    check = steps["alpha-audit check"]
    assert cache["uses"].startswith("actions/cache@")
    assert names.index("Restore the render cache") < names.index("alpha-audit check")
    assert cache["with"]["path"] == check["env"]["ALPHA_AUDIT_CACHE_DIR"]
    assert cache["with"]["restore-keys"] in cache["with"]["key"]  # the newest one is restored
    assert "inputs.cache != 'false'" in cache["if"]
    assert "inputs.cache == 'false'" in check["env"]["ALPHA_AUDIT_NO_CACHE"]


def test_on_a_pull_request_the_check_step_gates_against_the_base_commit(tmp_path: Path) -> None:
    """The step's own script, run in a real repository: only the change's finding fails."""
    import os
    import shutil
    import subprocess
    import sys

    svg = (
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
        '<rect x="2" y="2" width="20" height="20" fill="currentColor"/></svg>'
    )
    repo = tmp_path / "design"
    (repo / "icons").mkdir(parents=True)
    for name in ("a", "b"):
        (repo / "icons" / f"{name}.svg").write_text(svg)
    (repo / "set.yaml").write_text(
        'icons: "icons/*.svg"\ncolor: "#333333"\noverrides:\n  a: {color: "#0000d0", alpha: 1.3}\n'
    )
    (repo / "theme.yaml").write_text('canvases: [{name: sun, color: "#ffff00"}]\n')
    (repo / "alpha-audit.yaml").write_text("theme: theme.yaml\niconset: set.yaml\n")
    git = ["git", "-c", "user.email=a@b", "-c", "user.name=t"]
    env = {"PATH": os.environ["PATH"], "HOME": str(tmp_path), "GIT_CONFIG_NOSYSTEM": "1"}
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-qm", "base"]):
        subprocess.run([*git, *args], cwd=repo, env=env, check=True)
    sha = subprocess.run(
        ["git", "rev-parse", "HEAD"], cwd=repo, env=env, check=True, capture_output=True, text=True
    ).stdout.strip()
    with (repo / "set.yaml").open("a") as fh:
        fh.write("  b: {alpha: 0.85}\n")  # the pull request
    summary, outputs = tmp_path / "summary.md", tmp_path / "outputs.txt"
    step = _steps()["alpha-audit check"]
    bin_dir = str(Path(sys.executable).parent)
    assert shutil.which("alpha-audit", path=bin_dir)
    done = subprocess.run(
        ["bash", "-c", step["run"]],
        cwd=repo,
        env={
            **env,
            "PATH": f"{bin_dir}:{env['PATH']}",
            "ARGS": "",
            "SARIF": "",
            "BASE": "auto",
            "PR_BASE_SHA": sha,
            "RUNNER_TEMP": str(tmp_path),
            "GITHUB_STEP_SUMMARY": str(summary),
            "GITHUB_OUTPUT": str(outputs),
        },
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert "exit-code=1" in outputs.read_text(), done.stderr
    errors = [line for line in done.stdout.splitlines() if line.startswith("::error file=")]
    assert len(errors) == 1 and "b on sun" in errors[0] and "line=5" in errors[0]
    assert "already on the base revision" in summary.read_text()
