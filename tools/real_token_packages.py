"""Load real public token packages as shipped and compare every colour with coloraide.

Not part of the suite (it downloads): ``python tools/real_token_packages.py``
runs ``npm pack`` for each package (tools/token_fixtures.py, cached outside the repository),
loads each file with :func:`alpha_audit.load_token_modes` and resolves the same
colours independently: JSON by a plain walk that follows ``{a.b}`` aliases
(and Style Dictionary's ``{a.b.value}``), CSS by collecting the declarations of
the selectors named below in source order and substituting ``var()`` by hand;
both parsed by coloraide.  A colour matches when the encoded sRGB channels
(clipped) agree within 1e-9.  The figures go into docs/tokens.md.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import tinycss2
from coloraide import Color

from alpha_audit.load.tokens import load_token_modes, token_color

sys.path.insert(0, str(Path(__file__).resolve().parent))
from token_fixtures import fetch  # a tool beside this one

# (package, version, file in the package, {mode: [selectors in cascade order]} for CSS)
PACKAGES: list[tuple[str, str, str, dict[str, list[str]]]] = [
    ("tailwindcss", "4.3.5", "theme.css", {"default": ["@theme"]}),
    ("@radix-ui/colors", "3.0.0", "blue.css", {"default": [":root, .light, .light-theme"]}),
    ("@radix-ui/colors", "3.0.0", "blue-dark.css", {"dark": [".dark, .dark-theme"]}),
    (
        "@picocss/pico",
        "2.1.1",
        "css/pico.css",
        {
            "default": [
                ":root, :host",
                "[data-theme=light], :root:not([data-theme=dark]), :host(:not([data-theme=dark]))",
            ],
            "dark": [":root, :host", "[data-theme=dark]"],
        },
    ),
    (
        "daisyui",
        "5.8.1",
        "themes.css",
        {
            "default": [
                ":root,:root:has(input.theme-controller[value=light]:checked),[data-theme=light]"
            ],
            "dark": [
                ":root,:root:has(input.theme-controller[value=light]:checked),[data-theme=light]",
                ":root:has(input.theme-controller[value=dark]:checked),[data-theme=dark]",
            ],
        },
    ),
    (
        "@primer/primitives",
        "11.10.0",
        "dist/css/functional/themes/dark.css",
        {
            "dark": [
                '[data-color-mode="dark"][data-dark-theme="dark"], '
                '[data-color-mode="auto"][data-light-theme="dark"]'
            ]
        },
    ),
    ("open-props", "1.7.23", "open-props.tokens.json", {}),
    ("open-props", "1.7.23", "open-props.resolver.json", {}),
    ("open-props", "1.7.23", "open-props.style-dictionary-tokens.json", {}),
    ("open-props", "1.7.23", "open-props.figma-tokens.json", {}),
    ("@terrazzo/tokens", "0.1.0", "tokens.json", {}),
    ("@altinn/figma-design-tokens", "6.0.1", "dist/tokens.json", {}),
]


def srgb(color: Color) -> tuple[float, ...]:
    return tuple(min(max(c, 0.0), 1.0) for c in color.convert("srgb").coords(nans=False))


# ------------------------------------------------------------ independent JSON
def json_colours(data: Any) -> dict[str, Any]:
    flat: dict[str, dict[str, Any]] = {}

    def walk(node: Any, path: list[str], gtype: Any) -> None:
        if not isinstance(node, dict):
            return
        gtype = node.get("$type", gtype)
        if "$value" in node or "value" in node:
            flat[".".join(path)] = {
                "value": node.get("$value", node.get("value")),
                "type": node.get("$type", node.get("type", gtype)),
            }
            return
        for k, v in node.items():
            if not k.startswith("$"):
                walk(v, [*path, k], gtype)

    if "resolutionOrder" in data:
        for entry in data["resolutionOrder"]:
            for source in entry.get("sources", []):
                walk(source, [], None)
    else:
        walk(data, [], None)

    def value(path: str, depth: int = 0) -> Any:
        v = flat[path]["value"]
        if isinstance(v, str) and v.startswith("{") and v.endswith("}") and depth < 64:
            target = v[1:-1]
            if target not in flat and target.endswith(".value"):
                target = target[: -len(".value")]
            return value(target, depth + 1)
        return v

    out = {}
    for path, t in flat.items():
        if t["type"] != "color":
            continue
        v = value(path)
        if isinstance(v, dict):
            comps = [float("nan") if c == "none" else c for c in v["components"]]
            if v["colorSpace"] in ("hsl", "hwb"):
                comps = [comps[0], comps[1] / 100, comps[2] / 100]
            out[path] = srgb(Color(v["colorSpace"], comps, v.get("alpha", 1)))
        else:
            out[path] = srgb(Color(v))
    return out


# ------------------------------------------------------------- independent CSS
def css_colours(text: str, selectors: list[str]) -> dict[str, Any]:
    props: dict[str, list[Any]] = {}

    def walk(rules: Any) -> None:
        for rule in rules:
            if rule.type == "at-rule" and rule.content is not None:
                if rule.lower_at_keyword == "theme" and "@theme" in selectors:
                    take(rule.content)
                elif rule.lower_at_keyword == "layer":
                    walk(tinycss2.parse_rule_list(rule.content, True, True))
            elif rule.type == "qualified-rule":
                prelude = "".join(tinycss2.serialize(rule.prelude).split())
                if prelude in ["".join(s.split()) for s in selectors]:
                    take(rule.content)

    def take(content: Any) -> None:
        for d in tinycss2.parse_blocks_contents(content, True, True):
            if d.type == "declaration" and d.name.startswith("--"):
                props[d.name] = list(d.value)

    ordered = [s for s in selectors if s != "@theme"]
    rules = tinycss2.parse_stylesheet(text, True, True)
    for sel in (["@theme"] if "@theme" in selectors else []) + ordered:
        walk_one = [sel] if sel != "@theme" else ["@theme"]
        saved = list(selectors)
        selectors[:] = walk_one
        walk(rules)
        selectors[:] = saved

    def sub(tokens: list[Any], depth: int = 0) -> str:
        out = []
        for t in tokens:
            if t.type == "function" and t.lower_name == "var" and depth < 64:
                args = [a for a in t.arguments if a.type != "whitespace"]
                name = args[0].value
                if name in props:
                    out.append(sub(props[name], depth + 1))
                else:
                    comma = next(i for i, a in enumerate(t.arguments) if a.type == "literal")
                    out.append(sub(list(t.arguments[comma + 1 :]), depth + 1))
            elif t.type == "function":
                out.append(f"{t.name}({sub(list(t.arguments), depth)})")
            else:
                out.append(tinycss2.serialize([t]))
        return "".join(out).strip()

    found = {}
    for name, value in props.items():
        try:
            found[name[2:].replace("-", ".")] = srgb(Color(sub(value)))
        except (ValueError, StopIteration, KeyError):
            continue
    return found


def main() -> int:
    total = matched = 0
    for package, version, file, css_modes in PACKAGES:
        path = fetch(package, version) / file
        modes = load_token_modes(path, root=path.parent)
        ours = {
            (m, p): token_color(t, gamut="clip", allow_alpha=True).encoded
            for m, tokens in modes.modes.items()
            for p, t in tokens.items()
            if t.type == "color" and t.problem is None
        }
        if path.suffix == ".css":
            text = path.read_text()
            theirs = {
                (m, p): v
                for m, sels in css_modes.items()
                for p, v in css_colours(text, list(sels)).items()
            }
        else:
            flat = json_colours(json.loads(path.read_text()))
            theirs = {(m, p): v for m in modes.modes for p, v in flat.items()}
        common = [k for k in theirs if k in ours]
        same = sum(
            all(abs(a - b) <= 1e-9 for a, b in zip(ours[k], theirs[k], strict=True)) for k in common
        )
        total += len(common)
        matched += same
        print(
            f"{package}@{version} {file}: {modes.kind}, modes {', '.join(modes.modes)}; "
            f"{len(ours)} colours loaded, {len(common)} compared, {same} match"
        )
        for k in common:
            if not all(abs(a - b) <= 1e-9 for a, b in zip(ours[k], theirs[k], strict=True)):
                print("   differs:", k, ours[k], theirs[k])
                break
    print(f"total: {matched} of {total} compared colours match")
    return 0 if matched == total else 1


if __name__ == "__main__":
    sys.exit(main())
