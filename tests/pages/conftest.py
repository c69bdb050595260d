"""The real Storybook and static page (tools/page_fixtures.py), copied into a project root.

The build is made once by ``make test`` (``make fixtures``) and cached outside the
repository; here a missing build is made on demand.  Without npm the tests skip,
except on CI (``$CI`` set), where a missing build fails.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
from pathlib import Path

import pytest

from alpha_audit.browser import Chromium
from alpha_audit.pages import StorybookSource

REPO = Path(__file__).resolve().parents[2]
ICONS = ("bell", "search", "settings", "check", "info", "triangle-alert", "star", "heart")


def _tool():
    spec = importlib.util.spec_from_file_location("page_fixtures", REPO / "tools/page_fixtures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _missing(reason: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(reason, pytrace=False)
    pytest.skip(reason)


@pytest.fixture(scope="session")
def site() -> Path:
    """The cached build: ``storybook-static/``, ``page/`` and ``node_modules/``."""
    if Chromium.find() is None:
        _missing(f"Chromium not installed: {Chromium.INSTALL_HINT}")
    if shutil.which("npm") is None:
        _missing("npm (Node.js 20.19+) is needed to build the test Storybook")
    return _tool().build_site()


@pytest.fixture(scope="module")
def project(site: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A project root holding the Storybook, the page and a manifest of the Lucide icons used.

    The manifest gives each icon a colour of the Storybook's light theme, so the
    dark theme's CSS override shows as render drift.
    """
    root = tmp_path_factory.mktemp("project")
    (root / ".git").mkdir()
    shutil.copytree(site / "storybook-static", root / "storybook-static")
    shutil.copytree(site / "page", root / "page")
    # The stories' sources, where index.json's importPath names them (findings point there).
    shutil.copytree(site / "stories", root / "stories")
    (root / "icons" / "svg").mkdir(parents=True)
    for name in ICONS:
        shutil.copy(site / "node_modules/lucide-static/icons" / f"{name}.svg", root / "icons/svg")
    (root / "icons" / "iconset.yaml").write_text(
        "name: Lucide excerpt\nicons: svg/*.svg\ncolor: '#57606a'\nalpha: 1\n"
        "overrides:\n  triangle-alert: {color: '#cf222e'}\n",
        encoding="utf-8",
    )
    return root


@pytest.fixture(scope="module")
def icon_stories(project: Path) -> StorybookSource:
    """The ``icons--*`` stories (stories/icons.stories.js), what most tests audit.

    ``gallery--*`` (stories/gallery.stories.js: many icons) is test_gallery.py's.
    """
    return StorybookSource(project / "storybook-static", ("icons--*",))
