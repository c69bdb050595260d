"""Plain ``:root`` palette sheets (the Radix Colors shape) through the CSS reader."""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit.errors import InputError
from alpha_audit.load.tokens import load_token_modes

# Minimal reproduction of Radix Colors 3: the light scale on ":root, .light",
# the dark one on ".dark, .dark-theme", each followed by its P3 variant inside
# @supports + @media (color-gamut: p3); a length and a keyword are not colours.
SHEET = """\
:root, .light, .light-theme {
  --blue-1: #fbfdff;
  --blue-9: #0090ff;
  --radius-2: 4px;
  --blue-link: var(--blue-9);
}

@supports (color: color(display-p3 1 1 1)) {
  @media (color-gamut: p3) {
    :root, .light, .light-theme {
      --blue-9: color(display-p3 0.247 0.556 0.969);
    }
  }
}

.dark, .dark-theme {
  --blue-1: #0d1520;
  --cursor: pointer;
}

@supports (color: color(display-p3 1 1 1)) {
  @media (color-gamut: p3) {
    .dark, .dark-theme {
      --blue-1: color(display-p3 0.05 0.08 0.12);
    }
  }
}
"""


def _line(text: str, needle: str) -> int:
    return next(n for n, t in enumerate(text.splitlines(), 1) if needle in t)


def _modes(tmp_path: Path, text: str = SHEET):
    path = tmp_path / "palette.css"
    path.write_text(text)
    return load_token_modes(path, root=tmp_path)


def test_root_dark_and_their_p3_variants_are_modes_in_cascade_order(tmp_path) -> None:
    modes = _modes(tmp_path).modes
    assert list(modes) == ["default", "p3", "dark", "dark-p3"]
    value = {m: {k: t.value for k, t in tokens.items()} for m, tokens in modes.items()}
    assert value["default"]["blue.9"] == "#0090ff"
    assert value["p3"]["blue.9"] == "color(display-p3 0.247 0.556 0.969)"
    assert value["dark"]["blue.9"] == "#0090ff"  # dark does not set it: the light value cascades
    assert value["dark-p3"]["blue.9"] == "color(display-p3 0.247 0.556 0.969)"
    assert value["dark"]["blue.1"] == "#0d1520"
    assert value["dark-p3"]["blue.1"] == "color(display-p3 0.05 0.08 0.12)"
    assert value["p3"]["blue.1"] == "#fbfdff"


def test_only_colour_values_become_colour_tokens(tmp_path) -> None:
    modes = _modes(tmp_path).modes
    for tokens in modes.values():
        assert tokens["radius.2"].type == "css" and "not a colour" in str(
            tokens["radius.2"].problem
        )
        assert tokens["blue.9"].type == "color" and tokens["blue.9"].problem is None
    assert modes["dark"]["cursor"].type == "css" and "cursor" not in modes["default"]


def test_aliases_and_lines_point_at_the_declaration_that_sets_the_colour(tmp_path) -> None:
    modes = _modes(tmp_path).modes
    link = modes["p3"]["blue.link"]
    assert link.value == "color(display-p3 0.247 0.556 0.969)"
    assert link.line == _line(SHEET, "--blue-9: color(display-p3")
    assert link.alias_line == _line(SHEET, "--blue-link")
    assert modes["default"]["blue.link"].line == _line(SHEET, "--blue-9: #0090ff")


def test_a_sheet_without_colours_names_what_it_looked_for(tmp_path) -> None:
    with pytest.raises(
        InputError, match=r"palette\.css: has no custom property that is a colour.*:root"
    ):
        _modes(tmp_path, ":root { --radius: 4px; }\n")
