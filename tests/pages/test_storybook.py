"""A real Storybook build with two themes (addon-themes globals), audited in one run."""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest

from alpha_audit.load.iconset import load_iconset
from alpha_audit.observed import IconMatch
from alpha_audit.pages import RenderConfig, StorybookSource, audit_pages, state_matrix

THEMES = [[("theme", "light")], [("theme", "dark")]]
# Icons each story draws (stories/icons.stories.js).
PER_STORY = {
    "icons--toolbar": 3,
    "icons--chip": 2,
    "icons--alert": 1,
    "icons--sprite": 2,
    "icons--images": 2,
}


@pytest.fixture(scope="module")
def result(project: Path, icon_stories: StorybookSource):
    config = RenderConfig(
        (icon_stories,),
        states=state_matrix(THEMES),
        root=project,
        workers=2,
    )
    return audit_pages(config, load_iconset(project / "icons/iconset.yaml"))


def _theme_colours(project: Path, theme: str) -> dict[str, str]:
    """The theme's custom properties, read from the Storybook's own CSS as shipped."""
    css = "".join(p.read_text() for p in (project / "storybook-static/assets").glob("*.css"))
    block = re.search(r'html\[data-theme="?' + theme + r'"?\]\{([^}]*)\}', css.replace(" ", ""))
    assert block, f"no {theme} block in the built CSS"
    return dict(re.findall(r"--([a-z]+):(#[0-9a-f]{6})", block.group(1)))


def test_every_story_in_both_themes_is_audited_with_every_icon(result):
    assert result.run.problems == ()
    assert result.run.audited == len(PER_STORY) * 2
    instances = Counter((p.source, p.state, p.dom_path) for p in result.paints)
    per = Counter((source, state) for source, state, _ in instances)
    for story, count in PER_STORY.items():
        for state in ("theme:light", "theme:dark"):
            assert per[(story, state)] == count, (story, state)


def test_icons_map_by_attribute_sprite_id_file_name_and_path_hash(result):
    how = {(p.source, p.element): (p.icon, p.match) for p in result.paints}
    assert how[("icons--toolbar", "svg")][1] is IconMatch.DATA_ATTRIBUTE
    assert how[("icons--sprite", "use")][1] is IconMatch.SPRITE_ID
    assert how[("icons--images", "mask")] == ("heart", IconMatch.FILE_NAME)  # heart-<hash>.svg
    assert how[("icons--images", "img")] == ("star", IconMatch.PATH_HASH)  # an inlined data: URL


def test_the_dark_only_failure_is_found_with_its_colours(result, project):
    alert = {p.state: p for p in result.paints if p.source == "icons--alert"}
    light, dark = _theme_colours(project, "light"), _theme_colours(project, "dark")
    assert alert["theme:dark"].drawn == dark["danger"]
    assert alert["theme:dark"].behind == dark["surface"]
    assert alert["theme:light"].drawn == light["danger"]
    assert alert["theme:dark"].contrast < 3.0 and alert["theme:light"].contrast >= 3.0
    # The manifest says #cf222e (the light colour): in dark the page overrides it.
    assert alert["theme:light"].render_drift < 1.0
    assert alert["theme:dark"].render_drift > 10.0
    assert alert["theme:dark"].icon == "triangle-alert"


def test_solid_icons_on_flat_surfaces_measure_exact_colours(result, project):
    for theme in ("light", "dark"):
        colours = _theme_colours(project, theme)
        toolbar = [p for p in result.paints if p.source == "icons--toolbar" and theme in p.state]
        assert {p.drawn for p in toolbar} == {colours["icon"]}
        assert {p.behind for p in toolbar} == {colours["raised"]}
        assert all(p.coverage.full > 0 and 0 < p.coverage.q50 <= 1 for p in toolbar)
        # Flat backdrop and an opaque paint: every fully covered pixel has the same contrast.
        assert all(
            abs(p.contrast_worst - p.contrast_median) < 1e-9 or p.contrast_worst < p.contrast_median
            for p in toolbar
        )


def test_nothing_reaches_the_pages_own_server_through_the_proxy(result):
    assert not [b for b in result.run.blocked if "127.0.0.1" in b.url or "localhost" in b.url]
