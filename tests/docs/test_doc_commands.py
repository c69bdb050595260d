"""Every ``alpha-audit ...`` command shown in the README and docs runs as written.

Commands are taken from fenced shell blocks (``sh``, ``console``, ``bash`` or
unlabelled), joined across ``\\`` continuations, with ``$`` prompts and trailing
``#`` comments removed.  Commands with placeholders (``THEME``, ``ours.yaml``,
``[options]`` ...) are left out: they are templates, not examples.  Each runs in a
fresh copy of the bundled inputs; it must exit 0 or 1 (1 is a gate that fails on
purpose), never 2 or 3, and every file it writes must parse as its format.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from PIL import Image

from alpha_audit.load.render_cache import CACHE_DIR_ENV

REPO = Path(__file__).resolve().parents[2]
DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
# docs/cli.md is generated from --help: its usage lines are templates.
GENERATED = {REPO / "docs" / "cli.md"}
FENCE = re.compile(r"^```(\w*)\s*$")
SHELL_FENCES = {"", "sh", "shell", "bash", "console"}
# Upper-case words, brackets and ellipses mark a usage template, not an example.
PLACEHOLDER = re.compile(r"\b[A-Z]{3,}\b|\[|\.\.\.|<[^>]*>|\bours\.yaml\b")
INPUTS = ("themes", "examples")
# What a design repository would hold for the commands that read the project config.
PROJECT_CONFIG = """\
themes: [themes/github-primer.yaml]
iconsets: [examples/vibrant/iconset.yaml]
"""


def doc_commands() -> list[tuple[str, str, str]]:
    """``(where, folder, command)`` for every runnable ``alpha-audit`` example in the docs.

    ``folder`` is where the command runs, relative to the project root: a
    ``cd DIR`` line in the same block moves the commands after it.
    """
    found: list[tuple[str, str, str]] = []
    for doc in DOCS:
        if doc in GENERATED:
            continue
        in_block = in_shell = False
        pending, folder = "", "."
        for number, line in enumerate(doc.read_text(encoding="utf-8").splitlines(), 1):
            fence = FENCE.match(line.strip())
            if fence:
                in_block = not in_block
                in_shell = in_block and fence.group(1) in SHELL_FENCES
                pending, folder = "", "."
                continue
            if not in_shell:
                continue
            text = line.strip().removeprefix("$ ").strip()
            if pending:
                text = pending + " " + text
            if text.endswith("\\"):
                pending = text[:-1].strip()
                continue
            pending = ""
            if text.startswith("cd "):
                folder = shlex.split(text, comments=True)[1]
                continue
            if not text.startswith("alpha-audit "):
                continue
            words = shlex.split(text, comments=True)
            command = shlex.join(words)
            if PLACEHOLDER.search(command.replace("#", "")):
                continue
            found.append((f"{doc.relative_to(REPO)}:{number}", folder, command))
    return found


COMMANDS = doc_commands()


def _check_file(path: Path) -> None:
    suffix = path.suffix.lower()
    data = path.read_bytes()
    assert data, f"{path.name} is empty"
    if suffix in {".json", ".sarif"}:
        json.loads(data)
    elif suffix == ".xml":
        ET.fromstring(data)
    elif suffix == ".png":
        with Image.open(path) as image:
            image.verify()
    elif suffix in {".md", ".txt", ".css"}:
        data.decode("utf-8")
    elif suffix == ".html":
        text = data.decode("utf-8")
        assert "<html" in text.lower()
        assert "src=" not in text.lower().split("<script", 1)[-1].split(">", 1)[0]


def _snapshot(folder: Path) -> dict[Path, float]:
    return {p: p.stat().st_mtime_ns for p in folder.rglob("*") if p.is_file()}


def test_the_docs_show_commands() -> None:
    # Guards the extractor itself: the README's examples must be found.
    assert len(COMMANDS) >= 10
    assert any(" check " in f" {c} " for _, _, c in COMMANDS)


@pytest.mark.parametrize(("where", "folder", "command"), COMMANDS, ids=[w for w, _, _ in COMMANDS])
def test_documented_command_runs(where: str, folder: str, command: str, tmp_path: Path) -> None:
    for name in INPUTS:
        shutil.copytree(REPO / name, tmp_path / name, symlinks=False)
    (tmp_path / ".git").mkdir()  # the project root, as in a checkout
    (tmp_path / "alpha-audit.yaml").write_text(PROJECT_CONFIG, encoding="utf-8")
    before = _snapshot(tmp_path)
    argv = shlex.split(command)
    exe = Path(sys.executable).with_name("alpha-audit")
    proc = subprocess.run(
        [str(exe), *argv[1:]],
        cwd=tmp_path / folder,
        capture_output=True,
        text=True,
        timeout=300,
        # The session's render cache (conftest.py), so that the same icons are not drawn
        # again for every command; HOME is the fresh folder, so nothing else carries over.
        env={
            "PATH": "/usr/bin:/bin",
            "HOME": str(tmp_path),
            "NO_COLOR": "1",
            CACHE_DIR_ENV: os.environ[CACHE_DIR_ENV],
        },
    )
    assert proc.returncode in (0, 1), f"{where}: {command}\n{proc.stderr}"
    assert "Traceback" not in proc.stderr
    after = _snapshot(tmp_path)
    for path, mtime in after.items():
        if before.get(path) != mtime and ".git" not in path.parts:
            _check_file(path)
