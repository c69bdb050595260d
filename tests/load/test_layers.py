"""Issue 20, item 4: translucent surfaces are canvas stacks, audited as the pipeline draws them.

References are written from the specs with coloraide, not with alpha-audit's compositing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from coloraide import Color

from alpha_audit.errors import InputError
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Icon, IconSet
from alpha_audit.rows import audit

THEME = """name: layered
canvases:
  - {name: page, color: "#ffffff"}
  - {name: chip, color: "rgb(9 105 218 / 0.08)", over: page}
  - {name: chip-hover, color: "#0969da1f", over: chip}
"""


def _theme(tmp_path: Path, text: str = THEME):  # type: ignore[no-untyped-def]
    path = tmp_path / "theme.yaml"
    path.write_text(text)
    return load_theme(path)


def _css_over(layer: str, alpha: float, base: str) -> str:
    """What a browser draws: the encoded channels blended, rounded to 8 bits."""
    top, bottom = Color(layer).convert("srgb"), Color(base).convert("srgb")
    mixed = [
        alpha * t + (1 - alpha) * b for t, b in zip(top.coords(), bottom.coords(), strict=True)
    ]
    return "#" + "".join(f"{round(v * 255):02x}" for v in mixed)


def _linear_over(layer: str, alpha: float, base: str) -> np.ndarray:
    top = np.array(Color(layer).convert("srgb-linear").coords())
    bottom = np.array(Color(base).convert("srgb-linear").coords())
    return alpha * top + (1 - alpha) * bottom


def test_a_layer_is_composited_over_its_canvas_in_each_pipeline(tmp_path: Path) -> None:
    theme = _theme(tmp_path)
    chip = next(c for c in theme.canvases if c.name == "chip")
    assert chip.over == "page" and chip.opacity == pytest.approx(0.08)
    icons = IconSet("s", (Icon("a", Path("a.svg"), "#cf222e", 1.0),))
    css = {r.canvas: r for r in audit(theme, icons, pipeline="css").rows()}
    lin = audit(theme, icons)
    # css: as a browser draws an rgba() surface, layer on layer, each step in 8 bits.
    chip_css = _css_over("#0969da", 0.08, "#ffffff")
    assert css["chip"].background == chip_css
    assert css["chip-hover"].background == _css_over("#0969da", 0x1F / 255, chip_css)
    # linear: the paper's linear light.
    np.testing.assert_allclose(
        lin.theme.backgrounds[1], _linear_over("#0969da", 0.08, "#ffffff"), atol=1e-12
    )
    stacks = {c.name: c.stack for c in lin.theme.canvases}
    assert stacks == {
        "page": None,
        "chip": "8% #0969da over page",
        "chip-hover": stacks["chip-hover"],
    }
    assert stacks["chip-hover"] is not None and stacks["chip-hover"].endswith("over chip")
    assert all(c.mode == "light" for c in lin.theme.canvases)


@pytest.mark.parametrize(
    ("canvases", "message"),
    [
        ('  - {name: chip, color: "#0969da14", over: nowhere}\n', "names no canvas"),
        (
            '  - {name: a, color: "#0969da14", over: b}\n'
            '  - {name: b, color: "#0969da14", over: a}\n',
            "loop",
        ),
        ('  - {name: chip, color: "rgb(9 105 218 / 0.08)"}\n', "alpha"),
    ],
)
def test_a_bad_layer_is_one_clear_input_error(tmp_path: Path, canvases: str, message: str) -> None:
    with pytest.raises(InputError, match=message):
        _theme(tmp_path, 'name: t\ncanvases:\n  - {name: page, color: "#ffffff"}\n' + canvases)
