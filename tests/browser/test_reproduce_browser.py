"""``reproduce --only browser`` and ``--only runtime`` on the bundled icons, in every engine."""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from alpha_audit.browser import ENGINES, installed_engines
from alpha_audit.errors import UsageError
from alpha_audit.preview.html import page_script
from alpha_audit.reproduce.browser import select_icons
from alpha_audit.reproduce.runtime import (
    EngineTiming,
    RuntimeResult,
    RuntimeSettings,
    _round_orders,
    runtime_figure,
    runtime_script,
)

ROOT = Path(__file__).resolve().parents[2]
ICONS = ROOT / "examples" / "vibrant" / "svg"


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "alpha_audit", *args],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )


@pytest.fixture(scope="module")
def reproduced(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict, Path]:
    """One run of both experiments (runtime quick) in every installed engine."""
    if not installed_engines():
        pytest.skip("no browser engine installed: `make browser` as root installs them")
    out = tmp_path_factory.mktemp("reproduce") / "out"
    done = _cli(
        "reproduce", "--only", "browser", "--only", "runtime", "--quick",
        "--icons", str(ICONS), "--format", "json", "--out", str(out),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout), out


def test_browser_validation_counts_and_errors_per_engine(reproduced):
    doc, out = reproduced
    browser = doc["browser"]
    icons = len(list(ICONS.glob("*.svg")))
    assert browser["icons"] == icons and browser["failed_icons"] == 0
    assert browser["sizes"] == [16, 24, 48] and browser["canvases"] == 16
    assert [e["engine"] for e in browser["engines"]] == list(installed_engines())
    for engine in browser["engines"]:
        configs = [c["configuration"] for c in engine["configurations"]]
        assert configs == [
            *(f"alpha {a}" for a in ("0.6", "0.9", "1", "1.05", "1.1", "1.2", "1.4")),
            "difference",
            "exclusion",
        ]
        for c in engine["configurations"]:
            assert c["instances"] == icons * 3 * 16  # icons x sizes x canvases
            assert c["max_error_codes"] <= 1
            assert c["max_error_uncovered_codes"] == 0
        assert engine["instances"] == icons * 3 * 16 * 9
    assert browser["instances"] == icons * 3 * 16 * 9 * len(browser["engines"])
    assert browser["paper"] == {"instances": 388_800, "max_error_codes": 1}
    assert "388,800" in (out / "report.md").read_text(encoding="utf-8")


def test_runtime_quick_in_every_engine(reproduced):
    doc, out = reproduced
    runtime = doc["runtime"]
    quick = RuntimeSettings.quick()
    assert runtime["alphas"] == list(quick.alphas)
    assert runtime["icons_per_frame"] == 300 and runtime["canvas"] == [1280, 960]
    for engine in runtime["engines"]:
        blocks = np.array(engine["block_means_ms"])
        assert blocks.shape == (quick.rounds, len(quick.alphas))
        assert (blocks > 0).all()  # every block took time: the frames really ran
        assert np.allclose(engine["median_ms"], np.median(blocks, axis=0))
        assert (np.array(engine["p10_ms"]) <= np.array(engine["p90_ms"])).all()
    with Image.open(out / "runtime.png") as figure:
        assert figure.width == 420 * len(runtime["engines"])


def test_select_icons_orders_by_sha256_of_the_relative_path(tmp_path):
    (tmp_path / "sub").mkdir()
    names = ["a.svg", "b.svg", "sub/c.svg", "d.svg", "e.svg"]
    for name in names:
        (tmp_path / name).write_text("<svg/>")
    (tmp_path / "notes.txt").write_text("not an icon")
    expected = sorted(names, key=lambda n: hashlib.sha256(n.encode()).hexdigest())
    chosen = select_icons(tmp_path, 3)
    assert [p.relative_to(tmp_path).as_posix() for p in chosen] == expected[:3]


def test_select_icons_leaves_out_links_leaving_the_directory(tmp_path):
    outside = tmp_path / "outside.svg"
    outside.write_text("<svg/>")
    icons = tmp_path / "icons"
    icons.mkdir()
    (icons / "inside.svg").write_text("<svg/>")
    (icons / "link.svg").symlink_to(outside)
    assert [p.name for p in select_icons(icons)] == ["inside.svg"]


@pytest.mark.parametrize("make", [lambda p: p / "missing", lambda p: p])
def test_select_icons_needs_a_directory_with_svgs(tmp_path, make):
    with pytest.raises(UsageError, match="`icons`"):
        select_icons(make(tmp_path))


def test_runtime_needs_icons():
    done = _cli("reproduce", "--only", "runtime")
    assert done.returncode == 2
    assert "--icons" in done.stderr and "Traceback" not in done.stderr


def test_paper_design():
    paper = RuntimeSettings.paper()
    assert len(paper.alphas) == 161 and paper.alphas[0] == -2.0 and paper.alphas[-1] == 2.0
    assert 1.1 in paper.alphas and 0.0 in paper.alphas
    assert (paper.warmups, paper.rounds, paper.frames, paper.icons) == (2, 25, 20, 300)
    # Paper, Section 4.4: 161 x 25 blocks of 20 frames = 80,500 timed frames per browser.
    assert len(paper.alphas) * paper.rounds * paper.frames * 3 == 241_500


def test_round_orders_are_seeded_permutations():
    settings = RuntimeSettings.paper()
    orders = _round_orders(settings)
    assert len(orders) == 25
    assert all(sorted(o) == list(range(161)) for o in orders)
    assert orders == _round_orders(settings)  # the same orders in every engine
    assert len({tuple(o) for o in orders}) == 25


def test_timing_is_the_preview_pages_renderer():
    # Timing the very code people see: the preview's renderer is inlined as shipped, and
    # the runtime loop only drives it (no WebGL context, program or shader of its own).
    renderer = resources.files("alpha_audit.preview").joinpath("page_shader.js").read_text()
    loop = resources.files("alpha_audit.reproduce").joinpath("runtime.js").read_text()
    script = runtime_script()
    assert renderer in script and renderer in page_script()
    for setup in ("getContext", "createProgram", "createShader", "#version", "texImage3D"):
        assert setup not in loop, setup
        assert script.count(setup) == renderer.count(setup) >= 1, setup
    assert "u_alpha * (s - b)" in script  # the paper's expression, Appendix A.2


def _timing(samples) -> EngineTiming:
    alphas = (-1.0, 0.0, 0.5, 1.0, 2.0)
    return EngineTiming("chromium", "v", "r", alphas, tuple(map(tuple, samples)))


def test_timing_summary_statistics():
    rng = np.random.default_rng(1)
    samples = rng.uniform(1, 2, (25, 5))
    t = _timing(samples)
    assert np.allclose(t.median, np.median(samples, axis=0))
    assert np.allclose(t.p10, np.percentile(samples, 10, axis=0))
    assert np.allclose(t.p90, np.percentile(samples, 90, axis=0))
    flat = _timing(np.ones((3, 5)))
    assert flat.outside_vs_inside == 1.0 and flat.worst_vs_inside == 1.0
    slower = _timing(np.ones((3, 5)) * [2, 1, 1, 1, 1])  # alpha = -1 twice as slow
    assert slower.outside_vs_inside == 1.5 and slower.worst_vs_inside == 2.0


def test_runtime_figure_one_panel_per_engine_with_lines_and_bands():
    rng = np.random.default_rng(2)
    timings = tuple(
        EngineTiming(
            name, "v", "r", (-1.0, 0.0, 1.0, 2.0), tuple(map(tuple, rng.uniform(1, 2, (5, 4))))
        )
        for name in ENGINES
    )
    result = RuntimeResult(RuntimeSettings.quick(), 300, 12, timings, ())
    image = np.asarray(runtime_figure(result))
    assert image.shape == (320, 420 * len(ENGINES), 3)
    chromium_blue = (image[:, :420] == (0, 119, 187)).all(axis=-1)
    assert chromium_blue.sum() > 100  # the median line is drawn
