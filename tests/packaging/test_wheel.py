"""The built wheel works on its own: a fresh virtual environment, an empty folder.

This is what ``pipx install alpha-audit`` gives a user: no checkout, no
``themes/`` folder beside them.  The bundled themes and example icon set must
come from the package itself.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import venv
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def _run(args: list[str], cwd: Path, **kwargs: object) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    return subprocess.run(
        args, cwd=cwd, capture_output=True, text=True, timeout=600, env=env, check=False, **kwargs
    )


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``bin/`` of a fresh venv with only the built wheel (and its dependencies) installed."""
    root = tmp_path_factory.mktemp("wheel")
    dist = root / "dist"
    built = _run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(dist), str(REPO)],
        cwd=root,
    )
    assert built.returncode == 0, built.stderr
    (wheel,) = dist.glob("alpha_audit-*.whl")
    venv.create(root / "venv", with_pip=True)
    bin_dir = root / "venv" / "bin"
    install = _run([str(bin_dir / "pip"), "install", "-q", str(wheel)], cwd=root)
    assert install.returncode == 0, install.stderr
    return bin_dir


@pytest.fixture
def empty(tmp_path: Path) -> Path:
    folder = tmp_path / "empty"
    folder.mkdir()
    return folder


def test_check_on_bundled_names(installed: Path, empty: Path) -> None:
    proc = _run(
        [str(installed / "alpha-audit"), "check", "github-primer", "vibrant", "-f", "json"],
        cwd=empty,
    )
    assert proc.returncode in (0, 1), proc.stderr
    report = json.loads(proc.stdout)
    assert report["schema"].startswith("alpha-audit.check/")
    assert list(empty.iterdir()) == []


def test_themes_lists_the_bundled_themes(installed: Path, empty: Path) -> None:
    proc = _run([str(installed / "alpha-audit"), "themes"], cwd=empty)
    assert proc.returncode == 0, proc.stderr
    for name in ("paper16", "github-primer", "material3"):
        assert name in proc.stdout


def test_reproduce_finds_paper16_anywhere(installed: Path, empty: Path) -> None:
    proc = _run(
        [str(installed / "alpha-audit"), "reproduce", "--only", "palette", "--format", "json"],
        cwd=empty,
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)
    quick = _run([str(installed / "alpha-audit"), "reproduce", "--quick"], cwd=empty)
    assert quick.returncode == 0, quick.stderr


def test_the_wheel_does_not_import_the_checkout(installed: Path, empty: Path) -> None:
    code = "import alpha_audit, pathlib; print(pathlib.Path(alpha_audit.__file__).resolve())"
    proc = _run([str(installed / "python"), "-c", code], cwd=empty)
    assert proc.returncode == 0, proc.stderr
    assert str(REPO) not in proc.stdout
