"""The ``render:`` table of ``alpha-audit.yaml``, and the same settings from flags.

```yaml
render:
  storybook: storybook-static      # a built Storybook (or a list of them)
  stories: ["icons--*"]            # globs over story ids or Title/Name (default: all)
  pages: site/                     # a folder of HTML pages, served on loopback
  urls: ["http://localhost:6006/iframe.html?id=icons--toolbar"]
  states:                          # sweeps, combined into every state (or a list of states)
    globals: {theme: [light, dark]}
    color-scheme: [light, dark]
    html-attribute: {data-theme: [light, dark]}
    html-class: ["", dark]
  selector: ".icon"                # more elements to treat as icons
  engines: [chromium]              # firefox and webkit on request
  iconset: icons/iconset.yaml      # the manifest icons are mapped to
  rules: {render-drift: fail}      # the gate, over render's defaults (or fail-on: [...])
  baseline: render-baseline.json   # findings accepted (alpha-audit.baseline/2)
```

The gate's rules are render's own (``below-threshold`` fails, ``render-drift``
is reported: each rule's ``render`` level in :mod:`alpha_audit.rules`); the
top-level ``rules:``, ``fail-on:`` and ``baseline:`` are ``check``'s.

Paths are relative to the config file and must stay inside its folder.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path, PurePosixPath
from typing import Any

from alpha_audit.browser import COLOR_SCHEMES, ENGINES, ColorScheme
from alpha_audit.errors import UsageError
from alpha_audit.load.fields import check_keys, describe, read_mapping, read_name, read_number
from alpha_audit.load.paths import PathRefused, contain_argument, project_root
from alpha_audit.load.yamldoc import KeyPath, YamlDoc, load_yaml
from alpha_audit.pages.sources import (
    FolderSource,
    Source,
    StorybookSource,
    UrlSource,
    check_loopback_url,
)
from alpha_audit.pages.states import State, state_matrix
from alpha_audit.policy import RENDER_POLICY, Policy
from alpha_audit.rules import RENDER_RULES, Rule

__all__ = [
    "RENDER_KEYS",
    "RenderConfig",
    "config_from_yaml",
    "resolve_render_config",
    "source_from_argument",
]

RENDER_KEYS = (
    "attribute",
    "baseline",
    "engines",
    "fail-on",
    "iconset",
    "max-icon-size",
    "memory-mb",
    "pages",
    "rules",
    "scale",
    "selector",
    "states",
    "stories",
    "storybook",
    "timeout",
    "urls",
    "viewport",
    "workers",
)
_SWEEP_KEYS = ("color-scheme", "globals", "html-attribute", "html-class")
_STATE_KEYS = ("color-scheme", "globals", "html-attribute", "html-class", "name")


def _default_workers() -> int:
    return max(1, min(4, os.cpu_count() or 1))


@dataclass(frozen=True)
class RenderConfig:
    """What ``alpha-audit render`` audits and how; every bound has a default.

    ``scale`` is the device pixel ratio of the captures (2 or more resolves
    antialiasing finely enough for "fully covered" to mean something);
    ``timeout`` bounds each page and state in seconds, ``memory_mb`` each
    browser's resident memory (every process of it); ``max_icon_size`` in CSS
    pixels keeps illustrations out of the icons.  ``policy`` is the gate's
    (render's defaults, the table's ``rules:`` or ``fail-on:``, ``--fail-on``)
    and ``baseline`` the file of accepted findings.  ``crops`` is how many icon
    crops the run keeps for a report to show (:mod:`alpha_audit.pages.crops`;
    ``alpha-audit render -f html`` asks for
    :data:`~alpha_audit.pages.crops.MAX_CROPS`); 0 cuts none.
    """

    sources: tuple[Source, ...]
    states: tuple[State, ...] = (State("default"),)
    root: Path = field(default_factory=Path.cwd)
    selector: str | None = None
    engines: tuple[str, ...] = ("chromium",)
    iconset: Path | None = None
    attribute: str = "data-icon"
    scale: int = 2
    viewport: tuple[int, int] = (1280, 800)
    max_icon_size: int = 128
    timeout: float = 30.0
    memory_mb: int = 2048
    workers: int = field(default_factory=_default_workers)
    threshold: float = 3.0
    policy: Policy = RENDER_POLICY
    baseline: Path | None = None
    crops: int = 0

    def with_overrides(self, **changes: Any) -> RenderConfig:
        """A copy with the given fields replaced where the value is not ``None``."""
        return replace(self, **{k: v for k, v in changes.items() if v is not None})


def source_from_argument(text: str, root: Path) -> Source:
    """A source named on the command line: a loopback URL, a built Storybook or a folder."""
    if not text.strip():  # Path("") is the current folder: never what an empty value meant
        raise UsageError(
            "an empty source: give a built Storybook folder, a folder of HTML pages or a "
            "loopback URL"
        )
    if "://" in text:
        return UrlSource(check_loopback_url(text))
    try:
        folder = contain_argument(text, root)
    except PathRefused as exc:
        raise UsageError(str(exc), path=text) from exc
    if not folder.is_dir():
        raise UsageError(
            "not found: give a built Storybook folder, a folder of HTML pages or a loopback URL",
            path=text,
        )
    if (folder / "index.json").is_file() and (folder / "iframe.html").is_file():
        return StorybookSource(folder)
    return FolderSource(folder)


def _list(doc: YamlDoc, keys: KeyPath, value: Any) -> list[Any]:
    items = value if isinstance(value, list) else [value]
    if not items:
        raise doc.error(keys, "expected at least one value, got an empty list")
    return items


def _folder(doc: YamlDoc, keys: KeyPath, value: Any, base: Path, what: str = "folder") -> Path:
    if not isinstance(value, str) or not value.strip() or "\x00" in value:
        raise doc.error(keys, f"expected a {what} relative to the config, got {describe(value)}")
    pure = PurePosixPath(value.replace("\\", "/"))
    resolved = (base / pure).resolve()
    if pure.is_absolute() or not resolved.is_relative_to(base):
        raise doc.error(keys, f"{value!r} is outside {base}; give a {what} inside it")
    return resolved


def _text_list(doc: YamlDoc, keys: KeyPath, value: Any) -> list[str]:
    return [read_name(doc, (*keys, i), v) for i, v in enumerate(_list(doc, keys, value))]


def _schemes(doc: YamlDoc, keys: KeyPath, value: Any) -> list[ColorScheme]:
    out: list[ColorScheme] = []
    for i, v in enumerate(_list(doc, keys, value)):
        if v not in COLOR_SCHEMES:
            raise doc.error((*keys, i), f"expected light or dark, got {describe(v)}")
        out.append(v)
    return out


def _globals_sweep(doc: YamlDoc, keys: KeyPath, value: Any) -> list[list[tuple[str, str]]]:
    """``{theme: [light, dark], density: compact}`` -> every combination of the values."""
    sweep = read_mapping(doc, keys, value, "Storybook globals")
    combos: list[list[tuple[str, str]]] = [[]]
    for name, values in sweep.items():
        options = _text_list(doc, (*keys, name), values)
        combos = [[*c, (str(name), v)] for c in combos for v in options]
    return combos


def _attribute_sweep(doc: YamlDoc, keys: KeyPath, value: Any) -> list[tuple[str, str]]:
    sweep = read_mapping(doc, keys, value, "an <html> attribute and its values")
    if len(sweep) != 1:
        raise doc.error(keys, "give one attribute name with its list of values")
    ((name, values),) = sweep.items()
    return [(read_name(doc, keys, name), v) for v in _text_list(doc, (*keys, name), values)]


def _classes(doc: YamlDoc, keys: KeyPath, value: Any) -> list[str]:
    out = []
    for i, v in enumerate(_list(doc, keys, value)):
        if v in ("", None):
            out.append("")
        else:
            out.append(read_name(doc, (*keys, i), v))
    return out


def _one_state(doc: YamlDoc, keys: KeyPath, value: Any, index: int) -> State:
    data = read_mapping(doc, keys, value, "a state")
    check_keys(doc, keys, data, _STATE_KEYS)
    built = state_matrix(
        _globals_sweep(doc, (*keys, "globals"), data["globals"])[:1] if "globals" in data else (),
        _schemes(doc, (*keys, "color-scheme"), data["color-scheme"])[:1]
        if "color-scheme" in data
        else (),
        _attribute_sweep(doc, (*keys, "html-attribute"), data["html-attribute"])[:1]
        if "html-attribute" in data
        else (),
        _classes(doc, (*keys, "html-class"), data["html-class"])[:1]
        if "html-class" in data
        else (),
    )[0]
    name = read_name(doc, (*keys, "name"), data["name"]) if "name" in data else built.name
    return replace(built, name=name if built.name != "default" or "name" in data else "default")


def _states(doc: YamlDoc, keys: KeyPath, value: Any) -> tuple[State, ...]:
    if isinstance(value, list):
        states = tuple(_one_state(doc, (*keys, i), v, i) for i, v in enumerate(value))
        names = [s.name for s in states]
        if len(set(names)) != len(names):
            raise doc.error(keys, "two states have the same name; name each one")
        return states
    data = read_mapping(doc, keys, value, "state sweeps (or a list of states)")
    check_keys(doc, keys, data, _SWEEP_KEYS)
    return state_matrix(
        _globals_sweep(doc, (*keys, "globals"), data["globals"]) if "globals" in data else (),
        _schemes(doc, (*keys, "color-scheme"), data["color-scheme"])
        if "color-scheme" in data
        else (),
        _attribute_sweep(doc, (*keys, "html-attribute"), data["html-attribute"])
        if "html-attribute" in data
        else (),
        _classes(doc, (*keys, "html-class"), data["html-class"]) if "html-class" in data else (),
    )


def render_rules(rules: frozenset[Rule], where: str) -> frozenset[Rule]:
    """``rules`` if render can raise each of them, else a usage error naming ``where``."""
    for rule in rules:
        if rule not in RENDER_RULES:
            raise UsageError(
                f"{where}: {rule.value} is a rule of check; render's rules are "
                f"{', '.join(r.value for r in RENDER_RULES)}"
            )
    return rules


def _policy(doc: YamlDoc, keys: KeyPath, data: dict[str, Any]) -> Policy:
    """The gate of the render table: render's defaults, its ``rules:`` or ``fail-on:``."""
    from alpha_audit.load.config import read_levels, read_rules

    if "fail-on" in data and "rules" in data:
        raise doc.error((*keys, "rules"), "give fail-on: or rules:, not both")
    policy = RENDER_POLICY
    try:
        if "fail-on" in data:
            rules = read_rules(doc, (*keys, "fail-on"), data["fail-on"])
            policy = replace(policy, rules=render_rules(rules, "fail-on"))
        if "rules" in data:
            defaults = (RENDER_POLICY.rules, RENDER_POLICY.warnings)
            fail, warn = read_levels(doc, (*keys, "rules"), data["rules"], defaults)
            policy = replace(
                policy, rules=render_rules(fail, "rules"), warnings=render_rules(warn, "rules")
            )
    except UsageError as exc:
        if exc.path is not None:
            raise
        key = "fail-on" if "fail-on" in data else "rules"
        raise doc.error((*keys, key), exc.message) from exc
    return policy


def _whole(doc: YamlDoc, keys: KeyPath, value: Any, low: int, high: int) -> int:
    number = read_number(doc, keys, value, low=low, high=high, what=f"a whole number {low}-{high}")
    if number != int(number):
        raise doc.error(keys, f"expected a whole number {low}-{high}, got {describe(value)}")
    return int(number)


def config_from_yaml(path: Path) -> RenderConfig | None:
    """The ``render:`` table of a YAML config, or None when it has none."""
    doc = load_yaml(path)
    if not isinstance(doc.data, dict) or "render" not in doc.data:
        return None
    keys: KeyPath = ("render",)
    data = read_mapping(doc, keys, doc.data["render"], "the render table")
    data = {str(k).replace("_", "-"): v for k, v in data.items()}
    check_keys(doc, keys, data, RENDER_KEYS)
    base = doc.path.absolute().parent.resolve()

    def at(key: str) -> KeyPath:
        return (*keys, key)

    sources: list[Source] = []
    stories = tuple(_text_list(doc, at("stories"), data["stories"])) if "stories" in data else None
    for i, v in enumerate(
        _list(doc, at("storybook"), data["storybook"]) if "storybook" in data else []
    ):
        sources.append(
            StorybookSource(_folder(doc, (*at("storybook"), i), v, base), stories or ("*",))
        )
    if stories is not None and not any(isinstance(s, StorybookSource) for s in sources):
        raise doc.error(at("stories"), "stories select from a storybook: give storybook too")
    for i, v in enumerate(_list(doc, at("pages"), data["pages"]) if "pages" in data else []):
        sources.append(FolderSource(_folder(doc, (*at("pages"), i), v, base)))
    for i, v in enumerate(_list(doc, at("urls"), data["urls"]) if "urls" in data else []):
        try:
            sources.append(UrlSource(check_loopback_url(str(v))))
        except UsageError as exc:
            raise doc.error((*at("urls"), i), exc.message) from None
    config = RenderConfig(tuple(sources), root=project_root(base))
    changes: dict[str, Any] = {"policy": _policy(doc, keys, data)}
    if "baseline" in data:
        changes["baseline"] = _folder(doc, at("baseline"), data["baseline"], base, "file")
    if "states" in data:
        changes["states"] = _states(doc, at("states"), data["states"])
    if "selector" in data:
        changes["selector"] = read_name(doc, at("selector"), data["selector"])
    if "engines" in data:
        engines = _text_list(doc, at("engines"), data["engines"])
        for i, name in enumerate(engines):
            if name not in ENGINES:
                raise doc.error(
                    (*at("engines"), i),
                    f"unknown engine {name!r}; choose from {', '.join(ENGINES)}",
                )
        changes["engines"] = tuple(dict.fromkeys(engines))
    if "iconset" in data:
        changes["iconset"] = _folder(doc, at("iconset"), data["iconset"], base)
    if "attribute" in data:
        changes["attribute"] = read_name(doc, at("attribute"), data["attribute"])
    if "scale" in data:
        changes["scale"] = _whole(doc, at("scale"), data["scale"], 2, 4)
    if "max-icon-size" in data:
        changes["max_icon_size"] = _whole(doc, at("max-icon-size"), data["max-icon-size"], 4, 1024)
    if "memory-mb" in data:
        changes["memory_mb"] = _whole(doc, at("memory-mb"), data["memory-mb"], 256, 65536)
    if "workers" in data:
        changes["workers"] = _whole(doc, at("workers"), data["workers"], 1, 16)
    if "timeout" in data:
        changes["timeout"] = read_number(
            doc, at("timeout"), data["timeout"], low=1, high=600, what="seconds, 1 to 600"
        )
    if "viewport" in data:
        size = _list(doc, at("viewport"), data["viewport"])
        if len(size) != 2:
            raise doc.error(at("viewport"), "expected [width, height] in CSS pixels")
        changes["viewport"] = tuple(
            _whole(doc, (*at("viewport"), i), v, 64, 4096) for i, v in enumerate(size)
        )
    return replace(config, **changes)


def resolve_render_config(
    arguments: Sequence[str],
    *,
    config_path: Path | None,
    start: Path,
    stories: Sequence[str] = (),
    states: tuple[State, ...] | None = None,
    fail_on: Sequence[str] = (),
    **overrides: Any,
) -> RenderConfig:
    """The settings of one run: the project config's ``render:`` table, then the flags.

    ``arguments`` (folders or loopback URLs) replace the configured sources;
    ``stories`` globs apply to every Storybook source; ``fail_on`` rule names
    replace the gate's failing rules; other ``overrides`` replace a field when
    not None.
    """
    from alpha_audit.load.config import find_config

    found = config_path if config_path is not None else find_config(start)
    config = None
    if found is not None and Path(found).suffix in (".yaml", ".yml"):
        config = config_from_yaml(Path(found))
    root = config.root if config is not None else project_root(start)
    if config is None:
        config = RenderConfig((), root=root)
    if arguments:
        config = replace(config, sources=tuple(source_from_argument(a, root) for a in arguments))
    if stories:
        config = replace(
            config,
            sources=tuple(
                replace(s, stories=tuple(stories)) if isinstance(s, StorybookSource) else s
                for s in config.sources
            ),
        )
    if not config.sources:
        raise UsageError(
            "nothing to render: give a built Storybook folder, a folder of HTML pages or a "
            "loopback URL, or a render: table in alpha-audit.yaml"
        )
    if states is not None:
        config = replace(config, states=states)
    if fail_on:
        rules = frozenset(Rule.parse(r, "--fail-on") for r in fail_on)
        config = replace(
            config, policy=replace(config.policy, rules=render_rules(rules, "--fail-on"))
        )
    for engine in overrides.get("engines") or ():
        if engine not in ENGINES:
            raise UsageError(f"`engines` {engine!r}: choose from {', '.join(ENGINES)}")
    if overrides.get("iconset") is not None:
        try:
            overrides["iconset"] = contain_argument(overrides["iconset"], root)
        except PathRefused as exc:
            raise UsageError(str(exc), path=overrides["iconset"]) from exc
    return config.with_overrides(**overrides)
