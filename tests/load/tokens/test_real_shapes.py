"""The structures of real token packages, in small excerpts written here (no third-party file).

Each case reproduces how one package ships its tokens (docs/tokens.md lists them
with the figures tools/real_token_packages.py measured on the real files); the
expected colour of every (mode, token) is the literal it must resolve to, parsed
independently by coloraide, not by our loader.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from coloraide import Color

from alpha_audit.load.tokens import load_token_modes, token_color

CASES = {
    # tailwindcss 4: @theme with oklch, a namespace reset
    "tailwind.css": (
        "@theme default {\n  --color-*: initial;\n  --color-red-500: oklch(63.7% 0.237 25.331);\n"
        "  --color-white: #fff;\n  --spacing: 0.25rem;\n  --font-sans: ui-sans-serif;\n}\n",
        {
            ("default", "color.red.500"): "oklch(63.7% 0.237 25.331)",
            ("default", "color.white"): "#fff",
        },
    ),
    # @radix-ui/colors 3: a dark-only file with a P3 variant
    "radix-dark.css": (
        ".dark, .dark-theme {\n  --blue-9: #0090ff;\n}\n"
        "@supports (color: color(display-p3 1 1 1)) {\n  @media (color-gamut: p3) {\n"
        "    .dark, .dark-theme { --blue-9: color(display-p3 0.2 0.55 1); }\n  }\n}\n",
        {("dark", "blue.9"): "#0090ff", ("dark-p3", "blue.9"): "color(display-p3 0.2 0.55 1)"},
    ),
    # @picocss/pico 2: :root:not(), media dark, [data-theme], element and width rules
    "pico.css": (
        ":root, :host { --pico-spacing: 1rem; }\n"
        "@media (min-width: 576px) { :root, :host { --pico-font-size: 106%; } }\n"
        "[data-theme=light], :root:not([data-theme=dark]) { --pico-background-color: #fff; }\n"
        "[role=search] { --pico-background-color: #f00; }\n"
        "@media only screen and (prefers-color-scheme: dark) {\n"
        "  :root:not([data-theme]) { --pico-background-color: rgb(19, 22.5, 30.5); }\n}\n"
        "[data-theme=dark] { --pico-background-color: rgb(19, 22.5, 30.5); }\n",
        {
            ("default", "pico.background.color"): "#fff",
            ("dark", "pico.background.color"): "rgb(19 22.5 30.5)",
        },
    ),
    # daisyui 5: :has() theme controllers beside [data-theme]
    "daisy.css": (
        ":root,:root:has(input.theme-controller[value=light]:checked),[data-theme=light] {\n"
        "  color-scheme: light; --color-base-100: oklch(100% 0 0); }\n"
        ":root:has(input.theme-controller[value=dark]:checked),[data-theme=dark] {\n"
        "  color-scheme: dark; --color-base-100: oklch(25.33% 0.016 252.42); }\n",
        {
            ("default", "color.base.100"): "oklch(100% 0 0)",
            ("dark", "color.base.100"): "oklch(25.33% 0.016 252.42)",
        },
    ),
    # @primer/primitives 11: one theme per file, compound data attributes
    "primer-dark.css": (
        '[data-color-mode="dark"][data-dark-theme="dark"],\n'
        '[data-color-mode="auto"][data-light-theme="dark"] {\n'
        "  --bgColor-default: #0d1117; /** comment */\n  --fgColor-accent: var(--blue-4);\n"
        "  --blue-4: #4493f8;\n}\n",
        {("dark", "bgColor.default"): "#0d1117", ("dark", "fgColor.accent"): "#4493f8"},
    ),
    # @digdir/designsystemet-theme 1: layers, [data-color-scheme], [data-color] families
    "designsystemet.css": (
        "@layer ds.theme.color-scheme.light {\n"
        '  :root, [data-color-scheme="light"] { --ds-color-neutral-background-default: #fefeff;'
        " --ds-size: var(--ds-size--md); --ds-size--md: var(--ds-size,); }\n}\n"
        "@layer ds.theme.color-scheme.dark {\n"
        '  [data-color-scheme="dark"] { --ds-color-neutral-background-default: #0e1013; }\n}\n'
        "@layer ds.theme.color {\n"
        '  :root, [data-color-scheme], [data-color="accent"] {\n'
        "    --ds-color-background-default: var(--ds-color-neutral-background-default); }\n}\n",
        {
            ("default", "ds.color.background.default"): "#fefeff",
            ("dark", "ds.color.background.default"): "#0e1013",
        },
    ),
    # open-props 1.7: normalize's :where(html) and prefers-color-scheme
    "open-props.css": (
        ":where(html){--gray-0:#f8f9fa;--gray-9:#212529;--surface-1:var(--gray-0);"
        "--shadow-strength:2%}\n"
        "@media (prefers-color-scheme:dark){:where(html){--surface-1:var(--gray-9)}}\n",
        {("default", "surface.1"): "#f8f9fa", ("dark", "surface.1"): "#212529"},
    ),
    # open-props 1.7: a Resolver with one inline set and DTCG colour objects
    "open-props.resolver.json": (
        json.dumps(
            {
                "version": "2025.10",
                "resolutionOrder": [
                    {
                        "type": "set",
                        "name": "Open Props",
                        "sources": [
                            {
                                "gray": {
                                    "0": {
                                        "$type": "color",
                                        "$value": {
                                            "colorSpace": "srgb",
                                            "components": [0.9725, 0.9765, 0.9804],
                                            "hex": "#f8f9fa",
                                        },
                                    }
                                },
                                "size": {
                                    "1": {
                                        "$type": "dimension",
                                        "$value": {"value": 0.25, "unit": "rem"},
                                    }
                                },
                            }
                        ],
                    }
                ],
            }
        ),
        {("default", "gray.0"): "color(srgb 0.9725 0.9765 0.9804)"},
    ),
    # open-props 1.7: Style Dictionary and Tokens Studio ("figma-tokens") shapes
    "open-props.style-dictionary.json": (
        json.dumps({"color": {"yellow": {"0": {"value": "#fff9db", "type": "color"}}}}),
        {("default", "color.yellow.0"): "#fff9db"},
    ),
    # @terrazzo/tokens 0.1: DTCG with per-mode values in $extensions
    "terrazzo.tokens.json": (
        json.dumps(
            {
                "color": {
                    "$type": "color",
                    "blue": {"$value": "#001925", "$extensions": {"mode": {"dark": "#001925"}}},
                    "text": {"$value": "{color.blue}"},
                }
            }
        ),
        {("default", "color.text"): "#001925"},
    ),
    # @altinn/figma-design-tokens 6: Tokens Studio flattened by Style Dictionary
    "altinn.json": (
        json.dumps(
            {
                "tokenSetOrder": {"0": {"value": "Base", "type": "other"}},
                "Felles": {
                    "id": "x",
                    "selectedTokenSets": {"Base": "source"},
                    "type": "other",
                    "value": "[object Object]",
                },
                "panel": {"background": {"value": "#e6eff8", "type": "color"}},
            }
        ),
        {("default", "panel.background"): "#e6eff8"},
    ),
}


def _srgb(text: str) -> tuple[float, ...]:
    return tuple(min(max(c, 0.0), 1.0) for c in Color(text).convert("srgb").coords(nans=False))


@pytest.mark.parametrize("name", list(CASES))
def test_real_package_shapes_load_as_shipped(tmp_path: Path, name: str) -> None:
    text, expected = CASES[name]
    path = tmp_path / name
    path.write_text(text)
    modes = load_token_modes(path, root=tmp_path).modes
    for (mode, token), literal in expected.items():
        got = token_color(modes[mode][token], gamut="clip").encoded
        assert got == pytest.approx(_srgb(literal), abs=1e-12), (mode, token)
