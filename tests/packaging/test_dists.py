"""What ``python -m build`` makes installs and works on its own: wheel and sdist.

Each distribution goes into a fresh virtual environment, offline, from a
wheelhouse holding only what ``pyproject.toml`` declares (the dependencies and,
for the sdist, the build backend), then runs from an empty folder: no checkout,
no ``themes/`` folder beside it.  This is what ``pipx install`` or ``pip
install`` from the repository gives a user; the bundled themes and example icon
set must come from the package itself.  Slow (one dependency download, two
installs), part of ``make test``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tomllib
import venv
from pathlib import Path

import pytest

from alpha_audit import __version__

REPO = Path(__file__).resolve().parents[2]


def _run(args: list[str], cwd: Path, *, offline: bool = False) -> subprocess.CompletedProcess[str]:
    """Run ``args`` outside this venv; ``offline``: pip sees no config, index or find-links."""
    env = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    if offline:
        env = {k: v for k, v in env.items() if not k.startswith("PIP_")}
        env["PIP_CONFIG_FILE"] = os.devnull  # pip then reads no configuration file
    return subprocess.run(
        args, cwd=cwd, capture_output=True, text=True, timeout=600, env=env, check=False
    )


def _ok(proc: subprocess.CompletedProcess[str]) -> subprocess.CompletedProcess[str]:
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """``python -m build``'s sdist and wheel, and a wheelhouse of what they declare.

    ``make test`` has just built them (``make dist``: ``python -m build``, then ``twine
    check``) and names the folder in ``$ALPHA_AUDIT_DIST``, so they are not built twice;
    run alone, the test builds them itself.
    """
    root = tmp_path_factory.mktemp("dist")
    dist, house = root / "dist", root / "wheelhouse"
    if os.environ.get("ALPHA_AUDIT_DIST"):
        dist = Path(os.environ["ALPHA_AUDIT_DIST"])
    else:
        _ok(_run([sys.executable, "-m", "build", "--outdir", str(dist), str(REPO)], cwd=root))
    (sdist,) = dist.glob(f"alpha_audit-{__version__}.tar.gz")
    (wheel,) = dist.glob(f"alpha_audit-{__version__}-py3-none-any.whl")
    backend = tomllib.loads((REPO / "pyproject.toml").read_text())["build-system"]["requires"]
    pip = [sys.executable, "-m", "pip"]
    _ok(_run([*pip, "wheel", "-q", "-w", str(house), str(wheel)], cwd=root))
    _ok(_run([*pip, "download", "-q", "-d", str(house), *backend], cwd=root))
    return {"sdist": sdist, "wheel": wheel, "wheelhouse": house}


@pytest.fixture(scope="module", params=["wheel", "sdist"])
def installed(request: pytest.FixtureRequest, built: dict[str, Path]) -> Path:
    """``bin/`` of a fresh venv with one distribution (and its dependencies) installed."""
    root = built["wheelhouse"].parent / request.param
    venv.create(root, with_pip=True)
    bin_dir = root / "bin"
    pip = [str(bin_dir / "pip"), "install", "-q", "--no-compile", "--no-index"]
    wheelhouse = ["--find-links", str(built["wheelhouse"])]
    _ok(_run([*pip, *wheelhouse, str(built[request.param])], root, offline=True))
    return bin_dir


@pytest.fixture
def empty(tmp_path: Path) -> Path:
    folder = tmp_path / "empty"
    folder.mkdir()
    return folder


def test_version(installed: Path, empty: Path) -> None:
    proc = _ok(_run([str(installed / "alpha-audit"), "--version"], cwd=empty))
    assert proc.stdout.strip() == f"alpha-audit {__version__}"


def test_check_on_bundled_names(installed: Path, empty: Path) -> None:
    proc = _run(
        [str(installed / "alpha-audit"), "check", "github-primer", "vibrant", "-f", "json"],
        cwd=empty,
    )
    assert proc.returncode in (0, 1), proc.stderr
    report = json.loads(proc.stdout)
    assert report["schema"].startswith("alpha-audit.check/")
    assert report["rows"] and report["problems"] == []  # every SVG rendered: cairo works
    assert list(empty.iterdir()) == []


def test_themes_lists_the_bundled_themes(installed: Path, empty: Path) -> None:
    proc = _ok(_run([str(installed / "alpha-audit"), "themes"], cwd=empty))
    for name in ("paper16", "github-primer", "material3"):
        assert name in proc.stdout


def test_reproduce_finds_paper16_anywhere(installed: Path, empty: Path) -> None:
    proc = _ok(
        _run(
            [str(installed / "alpha-audit"), "reproduce", "--only", "palette", "--format", "json"],
            cwd=empty,
        )
    )
    doc = json.loads(proc.stdout)
    assert doc["theme"]["name"] == "paper16"
    assert doc["palette"]["random"]["collisions"]["1.4"] == 15098  # paper, Section 4.3


def test_the_install_does_not_import_the_checkout(installed: Path, empty: Path) -> None:
    code = "import alpha_audit, pathlib; print(pathlib.Path(alpha_audit.__file__).resolve())"
    proc = _ok(_run([str(installed / "python"), "-c", code], cwd=empty))
    assert str(REPO) not in proc.stdout
