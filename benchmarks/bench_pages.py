"""Benchmark: ``alpha-audit render`` story-states per second on a real Storybook, Chromium.

Target (issue 19): 500 story-states (250 stories x light and dark through the themes
addon's globals) in under 5 minutes on 2 cores.  The Storybook is tests/pages/site plus a
generated stories file of ``--stories`` stories, each a toolbar of four Lucide icons, built
once and cached (tools/page_fixtures.py).  The baseline, measured in the same run on the
first ``--baseline`` story-states, is the straightforward loop: one browser, and per icon
one screenshot of its box as drawn and one with that icon alone hidden.

    python benchmarks/bench_pages.py [--stories 250] [--baseline 20]
    /usr/bin/time -v python benchmarks/bench_pages.py   # peak memory (every process)
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import shutil
import tempfile
import time
from pathlib import Path

from alpha_audit.browser import Chromium, Clip, LaunchOptions
from alpha_audit.browser.server import BlockingProxy, PageServer
from alpha_audit.pages import (
    RenderConfig,
    StorybookSource,
    audit_pages,
    page_report,
    state_matrix,
)
from alpha_audit.pages.capture import _PROBE, _SETTLED, _STORY_READY, _probe_source
from alpha_audit.pages.sources import targets

REPO = Path(__file__).resolve().parents[1]
TARGET_S = 300.0
PROBE_OPTIONS = {"selector": None, "attribute": "data-icon", "maxSize": 128}
ICONS = ("Bell", "Check", "Info", "Search", "Settings", "TriangleAlert", "Star", "Heart")


def _site(stories: int) -> Path:
    spec = importlib.util.spec_from_file_location("pf", REPO / "tools/page_fixtures.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    lines = [
        f"import {{ {', '.join(ICONS)} }} from 'lucide-static';",
        "export default { title: 'Many' };",
    ]
    for k in range(stories):
        icons = "".join(f"${{{ICONS[(k + j) % len(ICONS)]}}}" for j in range(4))
        lines.append(
            f"export const S{k:04d} = {{ render: () => `<div class='toolbar'>{icons}</div>` }};"
        )
    built: Path = module.build_site({"many.stories.js": "\n".join(lines) + "\n"})
    return built


def _baseline(folder: Path, root: Path, count: int) -> float:
    """Seconds for ``count`` story-states the straightforward way (one browser, per icon)."""
    config = RenderConfig((StorybookSource(folder, ("many--*",)),), root=root)
    pages = targets(config.sources)[: (count + 1) // 2]
    started = time.perf_counter()
    done = 0
    with PageServer([folder], root) as server, BlockingProxy() as proxy:
        options = LaunchOptions(proxy=proxy.address, direct=(server.address,))
        with Chromium(timeout=30, options=options) as browser:
            browser.set_viewport(1280, 800, 2)
            for target in pages:
                for theme in ("light", "dark"):
                    if done == count:
                        break
                    browser.open(server.url(0, target.path) + f"&globals=theme:{theme}")
                    browser.wait_for(_STORY_READY, isolated=True)
                    browser.evaluate(_SETTLED, isolated=True)
                    browser.evaluate(
                        f"(globalThis.{_PROBE} = {_probe_source()}, true)", isolated=True
                    )
                    found = browser.evaluate(
                        f"{_PROBE}.find({json.dumps(PROBE_OPTIONS)})",
                        isolated=True,
                    )
                    assert isinstance(found, dict)
                    for k, icon in enumerate(found["icons"]):  # type: ignore[arg-type]
                        x, y, w, h = (int(v) for v in icon["box"])  # type: ignore[index]
                        clip = Clip(x, y, w + 1, h + 1)
                        browser.screenshot(clip)
                        hide = f"document.querySelectorAll('svg')[{k}].style.visibility"
                        browser.evaluate(f"({hide} = 'hidden', true)", isolated=True)
                        browser.screenshot(clip)
                        browser.evaluate(f"({hide} = '', true)", isolated=True)
                    done += 1
    return time.perf_counter() - started


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stories", type=int, default=250)
    parser.add_argument("--baseline", type=int, default=20)
    args = parser.parse_args()
    site = _site(args.stories)
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        (root / ".git").mkdir()
        shutil.copytree(site / "storybook-static", root / "storybook-static")
        folder = root / "storybook-static"
        config = RenderConfig(
            (StorybookSource(folder, ("many--*",)),),
            states=state_matrix([[("theme", "light")], [("theme", "dark")]]),
            root=root,
            workers=2,
        )
        started = time.perf_counter()
        run, paints = audit_pages(config)
        report = page_report(run, paints)  # the rows and the gate: what render does after
        ours = time.perf_counter() - started
        states = run.audited
        assert not run.problems, run.problems[:3]
        assert report.audits
        base = _baseline(folder, root, args.baseline)
    rate, base_rate = states / ours, args.baseline / base
    print(
        f"render: {states} story-states, {run.icons} icons in {ours:.1f} s "
        f"({rate:.2f} story-states/s; target {TARGET_S:.0f} s for 500: "
        f"{'met' if 500 / rate < TARGET_S else 'NOT met'}, {500 / rate:.0f} s projected)"
    )
    print(
        f"baseline (per-icon screenshots, one browser): {args.baseline} story-states in "
        f"{base:.1f} s ({base_rate:.2f}/s); ratio {rate / base_rate:.1f}x"
    )


if __name__ == "__main__":
    main()
