"""Every install instruction installs alpha-audit from the repository, never by name from PyPI.

alpha-audit is not on PyPI, so ``pip install alpha-audit`` would install whatever
someone registers under that name.  In the code blocks of the README and docs, in
``action.yml`` and in CHANGELOG.md, each ``pip install`` / ``pipx install`` must name
the repository pinned to the ``<commit>`` placeholder or an existing tag, a path, or
another package.
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
DOCS = [REPO / "README.md", REPO / "CHANGELOG.md", *sorted((REPO / "docs").glob("*.md"))]
BLOCK = re.compile(r"^```[^\n]*\n(.*?)^```", re.S | re.M)
INSTALL = re.compile(r"\bpipx? install\b(?P<args>[^\n;&|]*)")
OUR_NAME = re.compile(r"^alpha[-_.]audit(\[[^\]]*\])?([<>=!~ @].*)?$", re.I)
OUR_URL = re.compile(r"^git\+https://github\.com/<owner>/alpha-audit(?:\.git)?@(?P<ref>[^#\s]+)$")


def _tags() -> set[str]:
    git = shutil.which("git")
    if git is None or not (REPO / ".git").exists():
        pytest.skip("needs the git checkout to list its tags")
    out = subprocess.run([git, "tag"], cwd=REPO, capture_output=True, text=True, check=True)
    return set(out.stdout.split())


def _installs() -> list[tuple[str, list[str]]]:
    """``(where, arguments)`` of every install command in a code block or the action."""
    texts = [(doc.name, block) for doc in DOCS for block in BLOCK.findall(doc.read_text("utf-8"))]
    texts.append(("action.yml", (REPO / "action.yml").read_text("utf-8")))
    found = []
    for where, text in texts:
        for match in INSTALL.finditer(text):
            args = shlex.split(match["args"], comments=True)
            found.append((where, [a for a in args if not a.startswith("-")]))
    return found


def test_install_commands_name_the_repository_or_a_path() -> None:
    installs = _installs()
    assert len(installs) >= 4  # README's pipx, install.md's pipx and pip, the action, GitLab
    tags = _tags()
    for where, args in installs:
        for arg in args:
            assert not OUR_NAME.match(arg), f"{where}: `install {arg}` would fetch it from PyPI"
            url = OUR_URL.match(arg)
            if url:
                assert url["ref"] == "<commit>" or url["ref"] in tags, (where, arg)
            elif "alpha-audit" in arg:
                # Anything else naming us must be a path: a checkout or a built distribution.
                assert arg.startswith((".", "/", "dist/", "$")), (where, arg)
