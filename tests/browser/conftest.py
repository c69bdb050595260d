"""Engines for the browser tests: each installed engine runs, a missing one is a visible skip.

``make test`` installs the engines when missing and running as root; on CI
(``$CI`` set) a missing engine fails instead, so a broken install cannot
pass as a skipped test.
"""

from __future__ import annotations

import os

import pytest

from alpha_audit.browser import ENGINES, Installation


@pytest.fixture(params=list(ENGINES), scope="module")
def engine(request: pytest.FixtureRequest) -> tuple[str, Installation]:
    """``(name, installation)`` of each registered engine, in the paper's order."""
    cls = ENGINES[request.param]
    found = cls.find()
    if found is None:
        reason = f"{cls.LABEL} not installed: {cls.INSTALL_HINT}"
        if os.environ.get("CI"):
            pytest.fail(reason, pytrace=False)
        pytest.skip(reason)
    return request.param, found
