"""The pre-commit and GitHub Actions snippets in the README and docs work when copied.

Each YAML snippet must parse, name only the hook in ``.pre-commit-hooks.yaml`` and
inputs that ``action.yml`` declares, and pin alpha-audit to either the ``<commit>``
placeholder the text asks the reader to fill in or a tag that exists: a made-up
``v0.1.0`` fails on the reader's first run.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest
import yaml

REPO = Path(__file__).resolve().parents[2]
DOCS = [REPO / "README.md", REPO / "docs" / "ci.md"]
YAML_BLOCK = re.compile(r"^```yaml\n(.*?)^```", re.S | re.M)
PLACEHOLDER = "<commit>"
OUR_REPO = re.compile(r"(?:^|/)alpha-audit$")


def _snippets(key: str) -> list[tuple[str, Any]]:
    """``(doc, parsed block)`` for every YAML block of the docs that mentions ``key``."""
    found = []
    for doc in DOCS:
        for block in YAML_BLOCK.findall(doc.read_text(encoding="utf-8")):
            if key in block:
                found.append((doc.name, yaml.safe_load(block)))
    return found


def _tags() -> set[str]:
    git = shutil.which("git")
    if git is None or not (REPO / ".git").exists():
        pytest.skip("needs the git checkout to list its tags")
    out = subprocess.run([git, "tag"], cwd=REPO, capture_output=True, text=True, check=True)
    return set(out.stdout.split())


def _steps(doc: Any) -> list[dict[str, Any]]:
    """The steps of a snippet: a whole workflow, a ``steps:`` fragment or a bare list."""
    if isinstance(doc, list):
        return doc
    if "steps" in doc:
        return list(doc["steps"])
    return [step for job in doc["jobs"].values() for step in job["steps"]]


def test_pre_commit_snippets_name_the_hook_and_a_real_revision() -> None:
    hooks = {h["id"]: h for h in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())}
    snippets = _snippets("repos:")
    assert len(snippets) >= 3  # README, docs/ci.md remote and local
    tags = _tags()
    for where, doc in snippets:
        for entry in doc["repos"]:
            for hook in entry["hooks"]:
                assert hook["id"] in hooks, (where, hook)
            if entry["repo"] == "local":
                # A local hook must run what the shipped one runs, on the same files.
                shipped = hooks[entry["hooks"][0]["id"]]
                for field in ("entry", "pass_filenames", "files"):
                    assert entry["hooks"][0][field] == shipped[field], (where, field)
            else:
                assert entry["rev"] == PLACEHOLDER or entry["rev"] in tags, (where, entry)


def test_action_snippets_use_declared_inputs_and_a_real_ref() -> None:
    inputs = set(yaml.safe_load((REPO / "action.yml").read_text())["inputs"])
    snippets = _snippets("uses:")  # workflow steps; GitLab jobs install with pip instead
    assert len(snippets) >= 3  # README, docs/ci.md workflow and sticky comment
    tags = _tags()
    for where, doc in snippets:
        ours = [s for s in _steps(doc) if OUR_REPO.search(s.get("uses", "").split("@")[0])]
        assert ours, where
        for step in ours:
            ref = step["uses"].split("@", 1)[1]
            assert ref == PLACEHOLDER or ref in tags, (where, step["uses"])
            assert set(step.get("with", {})) <= inputs, (where, step["with"])
