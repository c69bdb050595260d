"""Every colour of every CSS mode of real token packages, against Chromium's computed styles.

The packages are fetched as shipped (``npm pack``, tools/token_fixtures.py, cached
outside the repository; never committed).  For each mode the loader finds, and
each alias, a page holding the sheet is put in the mode's state: its classes and
``data-*`` attributes on ``<html>`` and ``<body>``, ``prefers-color-scheme``
emulated.  Chromium then computes every custom property on ``<body>``; a value
``CSS.supports("color", ...)`` accepts is painted as a ``background-color`` and
read back with ``getComputedStyle``, and coloraide parses what Chromium
serialised.  The loader must give exactly the browser's colours: the same set
of colour properties, each the same 8-bit sRGB colour and alpha.

Without npm or Chromium these tests skip, except on CI (``$CI`` set), where they fail.
"""

from __future__ import annotations

import importlib.util
import json
import os
import shutil
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from coloraide import Color

from alpha_audit.browser import Chromium
from alpha_audit.load.tokens import load_token_modes, token_color
from alpha_audit.load.tokens.model import ModeConditions, TokenModes

from .test_css_modes import MINIMAL

REPO = Path(__file__).resolve().parents[3]


def _missing(reason: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(reason, pytrace=False)
    pytest.skip(reason)


def _tool() -> Any:
    spec = importlib.util.spec_from_file_location(
        "token_fixtures", REPO / "tools/token_fixtures.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def fetch() -> Any:
    if shutil.which("npm") is None:
        _missing("npm is needed to fetch the real token packages")
    return _tool().fetch


@pytest.fixture(scope="module")
def chromium() -> Iterator[Chromium]:
    if Chromium.find() is None:
        _missing(f"Chromium not installed: {Chromium.INSTALL_HINT}")
    with Chromium() as browser:
        yield browser


# Every custom property of the sheet (CSSOM, any depth of @media / @layer / @supports),
# then, in the current state, the colour each computes on <body>.
_READ = """
((state) => {
  const names = new Set();
  const walk = (rules) => {
    for (const rule of rules) {
      const style = rule.style;
      for (let i = 0; style && i < style.length; i++) {
        const p = style.item(i);
        if (p && p.startsWith("--")) names.add(p);
      }
      if (rule.cssRules) walk(rule.cssRules);
    }
  };
  for (const sheet of document.styleSheets) walk(sheet.cssRules);
  const html = document.documentElement, body = document.body;
  for (const el of [html, body]) for (const a of [...el.attributes]) el.removeAttribute(a.name);
  const put = (el, classes, attributes) => {
    for (const c of classes) el.classList.add(c);
    for (const [k, v] of attributes) el.setAttribute(k, v);
  };
  put(html, state.root_classes, state.root_attributes);
  put(body, state.body_classes, state.body_attributes);
  const probe = document.createElement("div");
  body.appendChild(probe);
  const computed = getComputedStyle(body);
  const out = {};
  for (const name of names) {
    const raw = computed.getPropertyValue(name).trim();
    if (!raw || !CSS.supports("color", raw) || /currentcolor/i.test(raw)) continue;
    probe.style.backgroundColor = raw;
    const shown = getComputedStyle(probe).backgroundColor;
    // The alpha with 6 digits (rgba() serialises it to 2 when that names the same byte).
    probe.style.backgroundColor = `color(from ${raw} srgb alpha 0 0)`;
    out[name] = [shown, getComputedStyle(probe).backgroundColor];
  }
  probe.remove();
  return out;
})(%s)
"""


def _eight_bit(color: Color) -> tuple[int, ...]:
    srgb = color.convert("srgb")
    channels = [min(max(c, 0.0), 1.0) for c in srgb.coords(nans=False)]
    return (*(round(c * 255) for c in channels), round(srgb.alpha(nans=False) * 255))


def _same(ours: tuple[float, ...] | None, theirs: tuple[int, ...] | None) -> bool:
    """The same 8-bit colour; Chromium keeps the alpha as a byte (0.3 is 77/255, rounded
    half up), so our exact alpha must round to that byte."""
    if ours is None or theirs is None:
        return ours is theirs
    return ours[:3] == theirs[:3] and abs(ours[3] - theirs[3]) <= 0.5


@dataclass
class Compared:
    modes: int
    colours: int
    exact: int
    wrong: list[str]


def browser_colours(browser: Chromium, state: ModeConditions) -> dict[str, tuple[int, ...]]:
    """``{token path: 8-bit RGBA}`` of every colour property Chromium computes on <body>."""
    browser.emulate_color_scheme(state.scheme)
    arg = json.dumps(
        {
            "root_classes": state.root_classes,
            "root_attributes": state.root_attributes,
            "body_classes": state.body_classes,
            "body_attributes": state.body_attributes,
        }
    )
    got = browser.evaluate(_READ % arg, timeout=120)
    assert isinstance(got, dict)
    out = {}
    for name, value in got.items():
        assert isinstance(value, list)
        shown, alpha = (Color(str(v)) for v in value)
        out[name[2:].replace("-", ".")] = (*_eight_bit(shown)[:3], round(alpha["red"] * 255))
    return out


def compare(browser: Chromium, sheet: Path) -> tuple[TokenModes, Compared]:
    """Load ``sheet`` and compare every mode (and alias) with Chromium."""
    modes = load_token_modes(sheet)
    (browser.workdir / "sheet.css").write_bytes(sheet.read_bytes())
    text = sheet.read_text(encoding="utf-8")
    browser.open_html(
        f"<!doctype html><html><head><style>{text}</style></head><body></body></html>"
    )
    total = exact = 0
    wrong: list[str] = []
    for name, state in modes.conditions.items():
        assert not state.p3, "Chromium cannot emulate a wide-gamut display"
        tokens = modes.modes[modes.aliases.get(name, name)]
        ours = {}
        for path, token in tokens.items():
            if token.type == "color" and token.problem is None:
                parsed = token_color(token, gamut="clip", allow_alpha=True)
                ours[path] = (*(round(c * 255) for c in parsed.encoded), parsed.alpha * 255)
        theirs = browser_colours(browser, state)
        for path in sorted(ours.keys() | theirs.keys()):
            total += 1
            if _same(ours.get(path), theirs.get(path)):
                exact += 1
            elif len(wrong) < 5:
                wrong.append(f"{name}: {path}: ours {ours.get(path)}, Chromium {theirs.get(path)}")
    return modes, Compared(len(modes.conditions), total, exact, wrong)


# (package, version, files concatenated into one sheet, modes a browser shows, aliases)
PACKAGES = {
    "patternfly": (
        "@patternfly/patternfly",
        "6.6.1",
        ["base/patternfly-variables.css"],
    ),
    "mantine": ("@mantine/core", "9.8.1", ["styles.css"]),
    "carbon": ("@carbon/styles", "1.116.0", ["css/styles.css"]),
    "twilio-paste": (
        "@twilio-paste/design-tokens",
        "10.15.0",
        [
            "dist/tokens.data-theme.css",
            *(
                f"dist/themes/{t}/tokens.data-theme.css"
                for t in ("dark", "evergreen", "sendgrid", "twilio", "twilio-dark")
            ),
        ],
    ),
    **{
        f"primer-{theme}": (
            "@primer/primitives",
            "11.10.0",
            [f"dist/css/functional/themes/{theme}.css"],
        )
        for theme in (
            "light",
            "light-high-contrast",
            "light-colorblind",
            "light-colorblind-high-contrast",
            "light-tritanopia",
            "light-tritanopia-high-contrast",
            "dark",
            "dark-dimmed",
            "dark-dimmed-high-contrast",
            "dark-high-contrast",
            "dark-colorblind",
            "dark-colorblind-high-contrast",
            "dark-tritanopia",
            "dark-tritanopia-high-contrast",
        )
    },
}


@pytest.mark.parametrize("case", sorted(PACKAGES))
def test_every_colour_of_every_mode_is_what_chromium_computes(
    case: str, fetch: Any, chromium: Chromium, tmp_path: Path
) -> None:
    package, version, files = PACKAGES[case]
    root = fetch(package, version)
    sheet = tmp_path / f"{case}.css"
    sheet.write_text("\n".join((root / f).read_text(encoding="utf-8") for f in files))
    modes, result = compare(chromium, sheet)
    print(
        f"{case}: {len(modes.modes)} modes ({result.modes} with aliases), "
        f"{result.exact} / {result.colours} colours exact"
    )
    assert result.wrong == []
    assert result.exact == result.colours > 0


@pytest.mark.parametrize("case", sorted(MINIMAL))
def test_minimal_sheets_are_what_chromium_computes(
    case: str, chromium: Chromium, tmp_path: Path
) -> None:
    sheet = tmp_path / f"{case}.css"
    sheet.write_text(MINIMAL[case][0], encoding="utf-8")
    _, result = compare(chromium, sheet)
    assert result.wrong == []
    assert result.exact == result.colours > 0


# (canvases, colours, audited modes) of a check on each package: every mode a browser
# shows is audited or named as an alias of an audited one; none is refused.
AUDITS = {
    "patternfly": (
        (
            "pf.t..global..background..color..100",
            "pf.t..global..background..color..primary..default",
        ),
        ("pf.t..global..icon..color..regular",),
        12,
    ),
    "mantine": (("mantine.color.body",), ("mantine.color.text",), 2),
    "carbon": (("cds.background",), ("cds.icon.primary",), 5),
    "twilio-paste": (("color.background.body",), ("color.text.icon",), 6),
    "primer-dark-dimmed": (("bgColor.default", "bgColor.neutral.muted"), ("fgColor.muted",), 3),
}


@pytest.mark.parametrize("case", sorted(AUDITS))
def test_check_audits_every_mode_of_the_real_sheet(case: str, fetch: Any, tmp_path: Path) -> None:
    from alpha_audit.load.tokens.themes import TokenConfig, token_themes

    package, version, files = PACKAGES[case]
    root = fetch(package, version)
    sheet = tmp_path / f"{case}.css"
    sheet.write_text("\n".join((root / f).read_text(encoding="utf-8") for f in files))
    canvases, colors, count = AUDITS[case]
    source = load_token_modes(sheet)
    themes = token_themes(source, TokenConfig(sheet, canvases, colors))
    audited = [m.name for m in themes.modes]
    named = set(audited) | set(themes.aliases) | set(themes.skipped)
    assert named == set(source.conditions)  # every state is accounted for
    assert len(set(audited) | set(themes.aliases)) == count
    for mode in themes.modes:
        for canvas in mode.theme.canvases:
            assert canvas.blend == ("css" if canvas.over else None)
