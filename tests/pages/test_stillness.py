"""A moving page gets the same verdict on every run, in every engine; one that keeps moving
is a problem, not a verdict.

The same page is audited three times in one run, each copy starting its animations at
another random phase (a negative ``animation-delay`` drawn by ``Math.random``), so a
capture taken at whatever moment the page happened to be in would differ between the
copies.  Counted: the three copies' measured paints are identical, and each is the
colour the page shows at rest (a colour animation at its first keyframe, a transition
at its end, a fade-in shown).  A backdrop that is an animated image, which no page
interface can pause, makes every copy a problem naming the change.
"""

from __future__ import annotations

import base64
import os
from pathlib import Path

import pytest

from alpha_audit.browser import ENGINES
from alpha_audit.pages import FolderSource, RenderConfig, audit_pages
from alpha_audit.pages.stillness import check_still

COPIES = 3


def _svg(ident: str, fill: str) -> str:
    return (
        f'<svg id="{ident}" data-icon="{ident}" width="24" height="24" viewBox="0 0 24 24">'
        f'<rect x="2" y="2" width="20" height="20" fill="{fill}"/></svg>'
    )


# Four icons on white, each moving another way; the script draws each copy's phase.
MOVING = f"""<!doctype html><html><head><style>
body {{ margin: 0; background: #fff; }}
span {{ display: inline-block; margin: 8px; }}
@keyframes pulse {{ from {{ fill: #777777; }} to {{ fill: #111111; }} }}
@keyframes fade {{ from {{ opacity: 0; }} to {{ opacity: 1; }} }}
#pulse rect {{ animation: pulse 1.7s ease-in-out infinite alternate; }}
#fade {{ opacity: 0; animation: fade 20s linear forwards; }}
#slow rect {{ transition: fill 20s linear !important; }}
#slow.late rect {{ fill: #0a3d91; }}
</style></head><body>
<span>{_svg("pulse", "#777777")}</span>
<span>{_svg("fade", "#1b5e20")}</span>
<span>{_svg("slow", "#b00020")}</span>
<span>{_svg("spin", "#4a148c")}</span>
<script>
const phase = -Math.random() * 10;
document.querySelector("#pulse rect").style.animationDelay = phase + "s";
document.getElementById("fade").style.animationDelay = (phase * 2) + "s";
document.getElementById("spin").animate(
  [{{ opacity: 1 }}, {{ opacity: 0.2 }}],
  {{ duration: 900, iterations: Infinity, delay: phase * 1000 }});
requestAnimationFrame(() => requestAnimationFrame(() =>
  document.getElementById("slow").classList.add("late")));
// A script that keeps changing the page: stopped with the page's timers.
let n = 0;
setInterval(() => {{ document.body.dataset.tick = String(++n);
  document.querySelector("#spin rect").setAttribute("fill", n % 2 ? "#4a148c" : "#ff6f00"); }},
  7);
</script></body></html>"""

# What each icon shows at rest (8-bit sRGB of the fully covered pixels); svg#spin, an
# endless scripted opacity animation held at its start (opacity 1), is left out below.
AT_REST = {
    "svg#pulse": "#777777",  # the first keyframe of an endless animation
    "svg#fade": "#1b5e20",  # a fade-in that ends shown
    "svg#slow": "#0a3d91",  # a transition at its end (despite the page's !important)
}


def _animated_backdrop() -> str:
    """An icon over an animated image: CSS animations inside an image reach no page API."""
    image = (
        '<svg xmlns="http://www.w3.org/2000/svg" width="64" height="64"><style>'
        "@keyframes a { from { fill: #000; } to { fill: #fff; } }"
        "#a { animation: a 0.7s linear infinite; } #b { animation: a 1.1s linear infinite; }"
        '</style><rect id="a" width="64" height="32"/><rect id="b" y="32" width="64" '
        'height="32"/></svg>'
    )
    uri = "data:image/svg+xml;base64," + base64.b64encode(image.encode()).decode()
    return (
        "<!doctype html><body style='margin:0'><div style='position:relative'>"
        f"<img src='{uri}' width='64' height='64'>"
        "<div style='position:absolute;left:20px;top:20px'>"
        f"{_svg('over', '#ffcc00')}</div></div>"
    )


@pytest.fixture(params=list(ENGINES))
def engine(request: pytest.FixtureRequest) -> str:
    """Each registered engine; a missing one skips (fails on CI, as tests/browser's do)."""
    cls = ENGINES[request.param]
    if cls.find() is None:
        reason = f"{cls.LABEL} not installed: {cls.INSTALL_HINT}"
        if os.environ.get("CI"):
            pytest.fail(reason, pytrace=False)
        pytest.skip(reason)
    return str(request.param)


@pytest.fixture
def pages(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    folder = tmp_path / "pages"
    folder.mkdir()
    for k in range(COPIES):
        (folder / f"moving-{k}.html").write_text(MOVING, encoding="utf-8")
    (folder / "unstable.html").write_text(_animated_backdrop(), encoding="utf-8")
    return tmp_path


def test_moving_pages_are_judged_at_rest_and_a_page_that_keeps_moving_is_a_problem(engine, pages):
    name = engine
    config = RenderConfig(
        (FolderSource(pages / "pages"),), root=pages, engines=(name,), workers=1, timeout=60
    )
    result = audit_pages(config)
    problems = {p.source: p.message for p in result.run.problems}
    assert set(problems) == {"unstable.html"}, problems
    assert "kept changing between two captures" in problems["unstable.html"]
    by_copy: dict[str, dict[str, tuple[object, ...]]] = {}
    for paint in result.paints:
        figures = (paint.drawn, paint.behind, paint.contrast_worst, paint.contrast_median)
        by_copy.setdefault(paint.source, {})[paint.dom_path] = figures
    assert sorted(by_copy) == [f"moving-{k}.html" for k in range(COPIES)]
    # The icon the page's own timer recolours stops on whichever tick came last: the
    # page's state, not a phase of ours; that its timer was stopped shows above (no
    # copy is a problem).  Every other figure is the same in every copy.
    ticked = {copy.pop("svg#spin")[0] for copy in by_copy.values()}
    assert ticked <= {"#4a148c", "#ff6f00"}, ticked
    first = by_copy["moving-0.html"]
    assert all(copy == first for copy in by_copy.values()), by_copy
    assert {path: figures[0] for path, figures in first.items()} == AT_REST


def test_check_still_counts_the_pixels_that_moved():
    import numpy as np

    from alpha_audit.pages.stillness import PageUnstable

    still = np.zeros((4, 5, 3), dtype=np.uint8)
    check_still(still, still.copy())
    moved = still.copy()
    moved[1, 2, 0] = 1
    moved[3, 4] = 255
    with pytest.raises(PageUnstable, match=r"\(2 of 20 pixels differ\)"):
        check_still(still, moved)
