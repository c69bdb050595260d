"""The HTML report on the real two-theme Storybook (tools/page_fixtures.py), and on hostile names.

One library run of every story in both themes, with crops, feeds the checks of
the page; the crops are checked against the figures measured from the same
captures (the capture is exact, so the drawn colour is a pixel of the crop).
The Storybook's CSS is the independent source: the dark theme's alert draws
``--danger`` too dark on its surface, and it is the only failing icon there
drawn by an inline SVG.
"""

from __future__ import annotations

import base64
import html
import io
import os
import re
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.color import hex_to_linear, to_8bit
from alpha_audit.load.iconset import load_iconset
from alpha_audit.observed import IconCrop, IconMatch, PageRun
from alpha_audit.pages import RenderConfig, StorybookSource, audit_pages, page_report, state_matrix
from alpha_audit.pages.crops import MAX_CROPS
from alpha_audit.pages.measure import ring_width
from alpha_audit.policy import RENDER_POLICY
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.render.common import finding_fix
from alpha_audit.render.html import CSP
from alpha_audit.rules import Rule
from helpers import measured_paint

THEMES = [[("theme", "light")], [("theme", "dark")]]
PNG = "data:image/png;base64,"


class Page(HTMLParser):
    """The parts of the report a reader sees: articles with their images and text."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags: list[str] = []
        self.attributes: list[tuple[str, str, str | None]] = []
        self.articles: list[dict[str, object]] = []
        self.text: list[str] = []
        self.meta: list[dict[str, str | None]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append(tag)
        self.attributes += [(tag, k, v) for k, v in attrs]
        a = dict(attrs)
        if tag == "meta":
            self.meta.append(a)
        if tag == "article":
            self.articles.append({"class": a.get("class"), "images": [], "text": []})
        if tag == "img" and self.articles:
            self.articles[-1]["images"].append(a)  # type: ignore[attr-defined]

    def handle_data(self, data: str) -> None:
        self.text.append(data)
        if self.articles:
            self.articles[-1]["text"].append(data)  # type: ignore[attr-defined]


def parse(text: str) -> Page:
    page = Page()
    page.feed(text)
    page.close()
    return page


def pixels(src: str) -> np.ndarray:
    assert src.startswith(PNG)
    with Image.open(io.BytesIO(base64.b64decode(src[len(PNG) :], validate=True))) as image:
        assert image.format == "PNG"
        return np.asarray(image.convert("RGB"), dtype=np.int64)


def code(hex_color: str) -> np.ndarray:
    return np.asarray(to_8bit(hex_to_linear(hex_color)), dtype=np.int64)


def has_colour(image: np.ndarray, hex_color: str) -> bool:
    """Whether some pixel is within 1/255 per channel of ``hex_color``."""
    return bool((np.abs(image - code(hex_color)).max(axis=-1) <= 1).any())


def instances(found) -> set[tuple[str, str, str, str]]:
    """The icon instance each finding takes its figures from: what its crop shows."""
    return {(f.iconset, f.theme, f.observed.engine, f.observed.dom_path) for f in found}


@pytest.fixture(scope="module")
def report(project: Path, icon_stories: StorybookSource):
    manifest = load_iconset(project / "icons/iconset.yaml")
    config = RenderConfig(
        (icon_stories,),
        states=state_matrix(THEMES),
        root=project,
        workers=2,
        crops=MAX_CROPS,
    )
    run, paints = audit_pages(config, manifest)
    return page_report(run, paints, RENDER_POLICY, manifest)


@pytest.fixture(scope="module")
def page(report, project: Path) -> tuple[str, Page]:
    text = CheckFormat.HTML.renderer()(report, RenderOptions(base=project))
    return text, parse(text)


def _article(page: Page, kind: str, *needles: str) -> dict[str, object]:
    found = [
        a
        for a in page.articles
        if a["class"] == kind and all(n in "".join(a["text"]) for n in needles)  # type: ignore[arg-type]
    ]
    assert len(found) == 1, [" ".join(a["text"])[:80] for a in found]  # type: ignore[arg-type]
    return found[0]


def test_the_dark_alert_failure_shows_both_crops_holding_the_colours_reported(report, page):
    _, parsed = page
    (f,) = [f for f in report.gate.failures if f.iconset == "icons--alert"]
    drawn, behind = f.observed.drawn, f.figures.background
    article = _article(parsed, "fail", "triangle-alert", "icons--alert", "theme:dark")
    shown, hidden = (pixels(i["src"]) for i in article["images"])  # type: ignore[attr-defined]
    assert shown.shape == hidden.shape and shown.shape[0] >= 48  # a 24 px icon at scale 2
    assert has_colour(shown, drawn) and not has_colour(hidden, drawn)
    assert has_colour(hidden, behind)
    # The crop is the box measured, grown by the ring: the icon is inside it, the ring
    # (2 CSS px at scale 2) is backdrop in both.
    ring = ring_width(2)
    differs = np.abs(shown - hidden).max(axis=-1) > 0
    inside = differs[ring:-ring, ring:-ring]
    assert inside.sum() > 100 and inside.sum() == differs.sum()
    # The figures beside the crops are the finding's.
    text = " ".join(article["text"])  # type: ignore[arg-type]
    assert f"{f.figures.contrast:.2f}:1; threshold 3:1" in text
    assert drawn in text and behind in text
    assert f.observed.nearer.output in text  # the model's prediction
    assert finding_fix(f, report) in text
    assert "icons/iconset.yaml:6" in text and re.search(r"stories/icons\.stories\.js:\d+", text)


def test_a_crop_is_kept_for_each_finding(report):
    run = report.pages
    wanted = instances(report.gate.findings) | instances(report.gate.warnings)
    assert wanted <= {c.key for c in run.crops}  # every finding's instance is cropped
    assert run.crops_left_out == 0
    assert all(max(c.width, c.height) <= 128 and c.step == 1 for c in run.crops)


def test_the_crop_cap_holds_and_keeps_the_failing_icons_first(
    project: Path, icon_stories: StorybookSource
):
    manifest = load_iconset(project / "icons/iconset.yaml")
    config = RenderConfig(
        (icon_stories,),
        states=state_matrix([[("theme", "dark")]]),
        root=project,
        workers=2,
        crops=2,
    )
    run, paints = audit_pages(config, manifest)
    gate = page_report(run, paints, RENDER_POLICY, manifest).gate
    every = instances(gate.failures) | instances(gate.warnings)
    assert len(gate.failures) == 2 and len(every) > 2  # the alert and the <img> star
    assert len(run.crops) == 2 and run.crops_left_out >= len(every) - 2
    assert {c.key for c in run.crops} == instances(gate.failures)


def test_every_finding_is_listed_failing_first_then_reported(report, page):
    _, parsed = page
    kinds = [a["class"] for a in parsed.articles]
    gate = report.gate
    assert kinds == ["fail"] * len(gate.failures) + ["reported"] * len(gate.warnings)
    assert len(gate.warnings) > 0
    assert all(len(a["images"]) == 2 for a in parsed.articles)  # type: ignore[arg-type]


def test_the_matrix_is_the_comments(page):
    text, _ = page
    rows = re.findall(r"<tr><th>([^<]*)</th>(.*?)</tr>", text)
    cells = {name: re.findall(r">([^<]*)</td>", rest) for name, rest in rows}
    assert cells["icons--alert"] == ["pass", "1 failing"]
    assert cells["icons--toolbar"] == ["pass", "pass"]


def test_the_page_runs_nothing_and_loads_nothing(page):
    text, parsed = page
    assert "<script" not in text.lower() and "script" not in parsed.tags
    csp = [m for m in parsed.meta if m.get("http-equiv") == "Content-Security-Policy"]
    assert [m["content"] for m in csp] == [CSP]
    assert CSP == "default-src 'none'; img-src data:; style-src 'unsafe-inline'"
    assert parsed.tags.index("meta") < parsed.tags.index("style")  # the policy comes first
    for tag, name, value in parsed.attributes:
        assert not name.startswith("on"), (tag, name)
        if name in ("src", "href", "srcset", "action", "formaction"):
            assert tag == "img" and name == "src" and str(value).startswith(PNG)
    assert not {"iframe", "object", "embed", "link", "form", "base"} & set(parsed.tags)


# ------------------------------------------------------------------ hostile names

HOSTILE_STORY = "icons--<script>alert(1)</script>"
HOSTILE_ICON = "x\"'><script>alert(2)</script></style>"
HOSTILE_STATE = 'theme:"dark"</style><img src=x onerror=alert(3)>'
HOSTILE_PATH = "div#a' onmouseover='alert(4)' > svg</style>"


def _hostile() -> tuple[str, Page]:
    p = measured_paint(
        source=HOSTILE_STORY, state=HOSTILE_STATE, name=HOSTILE_ICON, icon=HOSTILE_ICON,
        match=IconMatch.DATA_ATTRIBUTE, dom_path=HOSTILE_PATH, drawn="#6e1a1f",
        behind="#0d1117",
    )  # fmt: skip
    image = io.BytesIO()
    Image.new("RGB", (4, 4), (13, 17, 23)).save(image, "PNG")
    crop = IconCrop(
        HOSTILE_STORY, HOSTILE_STATE, "chromium", HOSTILE_PATH, image.getvalue(),
        image.getvalue(), 4, 4, 2,
    )  # fmt: skip
    run = PageRun(
        (), (), 1, 1, 1, (("chromium", "1"),), ((HOSTILE_STORY, HOSTILE_STATE),), crops=(crop,)
    )
    report = page_report(run, [p], RENDER_POLICY)
    assert [f.rule for f in report.gate.failures] == [Rule.BELOW_THRESHOLD]
    text = CheckFormat.HTML.renderer()(report, RenderOptions())
    return text, parse(text)


def test_hostile_story_state_icon_and_dom_path_stay_text():
    text, parsed = _hostile()
    assert "<script" not in text.lower() and "script" not in parsed.tags
    assert text.count("</style>") == 1  # the report's own
    assert parsed.tags.count("img") == 2  # the two crops, none from the state's name
    for tag, name, _ in parsed.attributes:
        assert not name.startswith("on"), (tag, name)
    shown = "".join(parsed.text)
    for name in (HOSTILE_STORY, HOSTILE_ICON, HOSTILE_STATE, HOSTILE_PATH):
        assert name in shown  # read back as the text it is
        assert html.escape(name) in text
    alts = [v for t, k, v in parsed.attributes if t == "img" and k == "alt"]
    assert alts and all(HOSTILE_ICON in str(a) for a in alts)


# ------------------------------------------------------------------ the command


def test_render_writes_the_html_report_with_crops(project: Path):
    cwd = Path.cwd()
    os.chdir(project)
    try:
        result = CliRunner().invoke(
            app,
            ["render", "storybook-static", "--stories", "icons--alert", "--globals",
             "theme:dark", "--iconset", "icons/iconset.yaml", "--workers", "1",
             "-f", "html", "-o", "render.html"],
        )  # fmt: skip
    finally:
        os.chdir(cwd)
    assert result.exit_code == 1, result.output  # the dark alert fails
    parsed = parse((project / "render.html").read_text(encoding="utf-8"))
    article = _article(parsed, "fail", "triangle-alert")
    assert len(article["images"]) == 2  # type: ignore[arg-type]
