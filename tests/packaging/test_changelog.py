"""The package version, CHANGELOG.md and release tags agree (the rule of docs/releasing.md).

``__version__`` is either the newest released version in the changelog (the
tree is that release) or a higher one that the ``[Unreleased]`` changes will
be released as; a ``vX.Y.Z`` tag on the checked-out commit names ``__version__``.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

from alpha_audit import __version__

REPO = Path(__file__).resolve().parents[2]
CHANGELOG = REPO / "CHANGELOG.md"
# Keep a Changelog 1.1.0: "## [Unreleased]", then "## [X.Y.Z] - YYYY-MM-DD", newest first.
HEADING = re.compile(r"^## \[(?P<name>[^\]]+)\](?: - (?P<date>\d{4}-\d{2}-\d{2}))?\s*$", re.M)
VERSION = re.compile(r"^(\d+)\.(\d+)\.(\d+)$")


def _version(text: str) -> tuple[int, int, int]:
    match = VERSION.match(text)
    assert match, f"{text!r} is not an X.Y.Z version"
    major, minor, patch = (int(g) for g in match.groups())
    return major, minor, patch


def _headings() -> list[tuple[str, str | None]]:
    return [(m["name"], m["date"]) for m in HEADING.finditer(CHANGELOG.read_text("utf-8"))]


def test_the_changelog_is_in_keep_a_changelog_form() -> None:
    headings = _headings()
    assert headings, "CHANGELOG.md has no '## [...]' section"
    assert headings[0] == ("Unreleased", None), "the first section must be ## [Unreleased]"
    released = headings[1:]
    for name, date in released:
        _version(name)
        assert date is not None, f"## [{name}] needs its release date: ## [{name}] - YYYY-MM-DD"
    versions = [_version(name) for name, _ in released]
    assert versions == sorted(versions, reverse=True), "releases must be newest first"
    dates = [date for _, date in released]
    assert dates == sorted(dates, reverse=True)


def test_the_package_version_is_the_newest_release_or_the_next_one() -> None:
    ours = _version(__version__)
    released = [_version(name) for name, _ in _headings()[1:]]
    if released and ours == released[0]:
        return  # this tree is the newest release
    assert not released or ours > released[0], (
        f"__version__ {__version__} is below the newest release in CHANGELOG.md"
    )
    assert ours not in released[1:], f"{__version__} was released already"


def test_a_release_tag_here_names_the_package_version() -> None:
    git = shutil.which("git")
    if git is None or not (REPO / ".git").exists():
        pytest.skip("needs the git checkout to read its tags")
    tags = subprocess.run(
        [git, "tag", "--points-at", "HEAD", "--list", "v*"],
        cwd=REPO, capture_output=True, text=True, check=True,
    ).stdout.split()  # fmt: skip
    released = {name for name, _ in _headings()[1:]}
    for tag in tags:
        assert tag == f"v{__version__}", f"tag {tag} on HEAD, but __version__ is {__version__}"
        assert __version__ in released, f"tag {tag}: CHANGELOG.md has no ## [{__version__}]"
