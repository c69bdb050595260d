"""Shared fixtures; the terminal environment is scrubbed so output is deterministic."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

from alpha_audit.browser import ENGINES, Installation

REPO = Path(__file__).resolve().parents[1]

# CI must not flake: no per-example deadline on a loaded 2-core machine, and the
# same examples on every run (locally, hypothesis keeps exploring).
settings.register_profile(
    "ci", deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile("dev", deadline=None)
settings.load_profile("ci" if os.environ.get("CI") else "dev")


# Parallel runs (`make test`: pytest-xdist's `-n auto --dist loadfile`) keep each test file
# on one worker, so what a module-scoped fixture builds (the distributions and their venvs, an
# engine, a reproduction run, the hostile corpus's render) is built once.  (`loadgroup` with
# `xdist_group` marks no longer groups anything under pytest 9.2: pytest-xdist issue 1386.)


@pytest.fixture(params=list(ENGINES), scope="module")
def engine(request: pytest.FixtureRequest) -> tuple[str, Installation]:
    """``(name, installation)`` of each registered engine, in the paper's order.

    A missing engine is a visible skip; on CI (``$CI`` set) it fails instead, so
    a broken install cannot pass as a skipped test (``make test`` installs the
    engines when missing and running as root).
    """
    cls = ENGINES[request.param]
    found = cls.find()
    if found is None:
        reason = f"{cls.LABEL} not installed: {cls.INSTALL_HINT}"
        if os.environ.get("CI"):
            pytest.fail(reason, pytrace=False)
        pytest.skip(reason)
    return request.param, found


@pytest.fixture(autouse=True, scope="session")
def _own_render_cache(tmp_path_factory: pytest.TempPathFactory) -> None:
    """The suite's render cache: one folder for the session, never the user's."""
    os.environ.pop("ALPHA_AUDIT_NO_CACHE", None)
    os.environ["ALPHA_AUDIT_CACHE_DIR"] = str(tmp_path_factory.mktemp("render-cache"))


@pytest.fixture(autouse=True)
def _plain_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("NO_COLOR", "FORCE_COLOR", "COLUMNS", "LINES", "TERM", "CLICOLOR_FORCE"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("COLUMNS", "80")


@pytest.fixture
def repo() -> Path:
    """The repository root (themes/, examples/)."""
    return REPO
