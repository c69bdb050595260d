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
