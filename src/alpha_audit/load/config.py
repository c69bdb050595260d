"""Project configuration: what ``alpha-audit check`` audits when given no files.

Discovered from the working directory upwards (stopping at the repository
root, the first folder holding ``.git``): ``alpha-audit.yaml`` or
``.alpha-audit.yaml``, or a ``[tool.alpha-audit]`` table in ``pyproject.toml``.
Keys are kebab-case (``max-loss``); snake_case spellings are accepted too.
Every path in the config is relative to the config file and must stay inside
its folder, because a pull request can change the config as well.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path, PurePosixPath
from typing import Any

from alpha_audit import ranges
from alpha_audit.color import GAMUT_POLICIES, PIPELINES, GamutPolicy, Pipeline
from alpha_audit.errors import InputError, UsageError
from alpha_audit.load.fields import (
    check_keys,
    describe,
    read_gamut,
    read_mapping,
    read_name,
    read_number,
    read_pipeline,
)
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.paths import PathRefused, contain_argument, project_root
from alpha_audit.load.tokens import TOKEN_FORMATS
from alpha_audit.load.tokens.themes import DEFAULT_ALPHA_EXTENSION, TokenConfig
from alpha_audit.load.yamldoc import MAX_YAML_BYTES, KeyPath, YamlDoc, format_key, load_yaml
from alpha_audit.model import Mode, Span
from alpha_audit.policy import Exemption, Policy
from alpha_audit.rules import DEFAULT_RULES, DEFAULT_WARNINGS, Level, Rule
from alpha_audit.safe_text import describe_char, first_unsafe, safe_text

__all__ = [
    "CONFIG_KEYS",
    "CONFIG_NAMES",
    "Overrides",
    "ProjectConfig",
    "config_from_doc",
    "find_config",
    "load_config",
    "project_config",
    "read_levels",
    "read_rules",
    "resolve_config",
]

CONFIG_NAMES = ("alpha-audit.yaml", ".alpha-audit.yaml")
CONFIG_KEYS = (
    "alpha",
    "baseline",
    "exempt",
    "fail-on",
    "gamut",
    "iconset",
    "iconsets",
    "loss-tolerance",
    "max-combinations",
    "max-drift",
    "max-loss",
    "min-delta-e",
    "min-size-contrast",
    "near-duplicate-delta-e",
    "pipeline",
    "render",  # alpha-audit render's table, read by alpha_audit.pages.config
    "rules",
    "strict-svg",
    "theme",
    "themes",
    "threshold",
    "tokens",
    "visibility-floor",
)
_EXEMPT_KEYS = ("canvas", "icon", "reason", "rule")
_TOOL_TABLE = ("tool", "alpha-audit")


@dataclass(frozen=True)
class ProjectConfig:
    """A validated project configuration; paths are absolute."""

    path: Path | None = None
    themes: tuple[Path, ...] = ()
    iconsets: tuple[Path, ...] = ()
    alpha: float | None = None
    threshold: float | None = None
    policy: Policy = field(default_factory=Policy)
    baseline: Path | None = None
    strict_svg: bool = False
    tokens: TokenConfig | None = None
    pipeline: Pipeline | None = None
    gamut: GamutPolicy | None = None  # for theme and manifest colours; None: each file's own
    # Paint rows x canvases one check audits: the resource bound (docs/ci.md says how
    # memory scales with it).
    max_combinations: int = ranges.DEFAULT_COMBINATIONS
    # Where the config writes ``alpha:`` (findings point there); None: not written, or
    # overridden by --alpha.
    alpha_span: Span | None = field(default=None, compare=False)


def _has_tool_table(pyproject: Path) -> bool:
    """Whether ``pyproject`` mentions ``[tool.alpha-audit]`` (cheap text check, parsed later)."""
    try:
        with pyproject.open("rb") as fh:
            head = fh.read(MAX_YAML_BYTES + 1)
    except OSError:
        return False
    return b"alpha-audit" in head and b"tool" in head


def find_config(start: str | Path) -> Path | None:
    """The nearest config file at or above ``start``, or None.

    The search stops at the project root (the first folder holding ``.git``,
    or ``start`` itself when there is none: never ``/tmp`` or ``$HOME``).
    Two configs in one folder are ambiguous and refused.
    """
    start = Path(start).resolve()
    root = project_root(start)
    for folder in (start, *start.parents):
        if not folder.is_relative_to(root):
            break
        found = [_contained(folder / n, root) for n in CONFIG_NAMES if (folder / n).is_file()]
        pyproject = folder / "pyproject.toml"
        # Contained before a byte is read: a pyproject.toml linking outside is never opened.
        if (
            pyproject.is_file()
            and _has_tool_table(_contained(pyproject, root))
            and _load_toml_table(pyproject)
        ):
            found.append(pyproject)
        if len(found) > 1:
            names = " and ".join(p.name for p in found)
            raise UsageError(f"two configurations ({names}); keep one", path=folder)
        if found:
            return found[0]
        if (folder / ".git").exists():
            return None
    return None


def _contained(path: Path, root: Path) -> Path:
    """``path`` if it resolves inside ``root``; a link outside is an input error."""
    try:
        contain_argument(path, root)
    except PathRefused as err:
        raise InputError(str(err), path=path) from err
    return path


def _load_toml_table(path: Path) -> dict[str, Any] | None:
    """The ``[tool.alpha-audit]`` table of a pyproject file, or None if absent."""
    text = read_text_capped(path, MAX_YAML_BYTES, InputError, "a pyproject.toml")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"invalid TOML: {exc}", path=path) from exc
    except RecursionError as exc:
        raise InputError("TOML is nested too deeply", path=path) from exc
    tool = data.get("tool")
    if not isinstance(tool, dict) or "alpha-audit" not in tool:
        return None
    return {"tool": {"alpha-audit": tool["alpha-audit"]}}


def project_config(explicit: str | Path | None, start: str | Path) -> ProjectConfig:
    """``explicit`` if given, else the config found from ``start`` upwards, else defaults."""
    path = explicit if explicit is not None else find_config(start)
    return load_config(path) if path is not None else ProjectConfig()


@dataclass(frozen=True)
class Overrides:
    """What a caller (the command line's flags) sets over the project config.

    ``None`` (and an empty tuple) keeps the config's value.  Themes or icon
    sets given replace the config's, and its ``tokens:`` table with them; each
    may name a bundled theme or the bundled example set.
    """

    config: Path | None = None
    themes: tuple[str | Path, ...] = ()
    iconsets: tuple[str | Path, ...] = ()
    alpha: float | None = None
    threshold: float | None = None
    fail_on: tuple[str, ...] = ()
    max_loss: float | None = None
    min_delta_e: float | None = None
    max_drift: float | None = None
    min_size_contrast: float | None = None
    visibility_floor: float | None = None
    loss_tolerance: float | None = None
    near_duplicate_delta_e: float | None = None
    pipeline: str | None = None
    gamut: str | None = None
    baseline: Path | None = None
    strict_svg: bool = False
    max_combinations: int | None = None


def resolve_config(overrides: Overrides | None = None, start: str | Path = ".") -> ProjectConfig:
    """The project config (given, else found from ``start`` upwards) with ``overrides`` applied.

    The one place every command resolves what it audits: ``check``,
    ``suggest``, ``preview`` and ``export`` call it and nothing else.
    """
    from alpha_audit.bundled import iconset_source, theme_source

    o = overrides or Overrides()
    project = project_config(o.config, start)
    for name, value, allowed, what in (
        ("pipeline", o.pipeline, PIPELINES, "a pipeline"),
        ("gamut", o.gamut, GAMUT_POLICIES, "a policy"),
    ):
        if value is not None and value.strip().lower() not in allowed:
            raise UsageError(f"`{name}` {value!r} is not {what}; use one of: {', '.join(allowed)}")
    given = bool(o.themes or o.iconsets)
    return replace(
        project,
        themes=tuple(theme_source(t) for t in o.themes) if given else project.themes,
        iconsets=tuple(iconset_source(s) for s in o.iconsets) if given else project.iconsets,
        tokens=None if given else project.tokens,
        alpha=project.alpha if o.alpha is None else o.alpha,
        threshold=project.threshold if o.threshold is None else o.threshold,
        policy=project.policy.with_overrides(
            rules=o.fail_on or None,
            max_loss=o.max_loss,
            min_delta_e=o.min_delta_e,
            max_drift=o.max_drift,
            min_size_contrast=o.min_size_contrast,
            visibility_floor=o.visibility_floor,
            loss_tolerance=o.loss_tolerance,
            near_duplicate_delta_e=o.near_duplicate_delta_e,
        ),
        pipeline=project.pipeline if o.pipeline is None else o.pipeline.strip().lower(),  # type: ignore[arg-type]  # checked against PIPELINES above
        gamut=project.gamut if o.gamut is None else o.gamut.strip().lower(),  # type: ignore[arg-type]  # checked against GAMUT_POLICIES above
        baseline=project.baseline if o.baseline is None else o.baseline,
        strict_svg=project.strict_svg or o.strict_svg,
        max_combinations=(
            project.max_combinations if o.max_combinations is None else o.max_combinations
        ),
        alpha_span=project.alpha_span if o.alpha is None else None,
    )


def load_config(path: str | Path) -> ProjectConfig:
    """Load a YAML config or the ``[tool.alpha-audit]`` table of ``pyproject.toml``."""
    p = Path(path)
    if p.exists():
        try:
            contain_argument(p)  # a symlinked config may not point outside the project
        except PathRefused as err:
            raise InputError(str(err), path=p) from err
    if p.name == "pyproject.toml" or p.suffix == ".toml":
        if not p.is_file():
            raise UsageError("config file not found", path=p)
        table = _load_toml_table(p)
        if table is None:
            raise InputError("has no [tool.alpha-audit] table", path=p)
        return config_from_doc(YamlDoc(p, table, {}), prefix=_TOOL_TABLE)
    return config_from_doc(load_yaml(p))


def _normalise_keys(doc: YamlDoc, keys: KeyPath, data: dict[str, Any]) -> dict[str, Any]:
    """snake_case -> kebab-case; the same key spelt both ways is a duplicate."""
    out: dict[str, Any] = {}
    spelt: dict[str, str] = {}  # each normalised key as the file spells it
    for key, value in data.items():
        norm = str(key).replace("_", "-")
        if norm in out:
            raise doc.error((*keys, key), f"{key!r} repeats {spelt[norm]!r}; give it once")
        out[norm], spelt[norm] = value, str(key)
    return out


def _paths(doc: YamlDoc, keys: KeyPath, value: Any, base: Path) -> list[Path]:
    items = [value] if isinstance(value, str) else value
    if not isinstance(items, list) or not items:
        raise doc.error(keys, f"expected a path or a list of paths, got {describe(value)}")
    return [
        _path(doc, (*keys, i) if len(items) > 1 else keys, v, base) for i, v in enumerate(items)
    ]


def _path(doc: YamlDoc, keys: KeyPath, value: Any, base: Path) -> Path:
    """A path relative to the config's folder that must stay inside it."""
    if not isinstance(value, str) or not value.strip() or "\x00" in value:
        raise doc.error(keys, f"expected a relative path, got {describe(value)}")
    pure = PurePosixPath(value.replace("\\", "/"))
    if pure.is_absolute() or value[1:3] in (":/", ":\\"):
        raise doc.error(keys, f"{value!r} is absolute; give a path relative to the config")
    resolved = (base / pure).resolve()
    if not resolved.is_relative_to(base):
        raise doc.error(keys, f"{value!r} resolves outside {base}; not allowed")
    return resolved


def read_rules(doc: YamlDoc, keys: KeyPath, value: Any) -> frozenset[Rule]:
    """A ``fail-on:`` list of rule names (at least one)."""
    items = [value] if isinstance(value, str) else value
    if not isinstance(items, list):
        raise doc.error(keys, f"expected a list of rules, got {describe(value)}")
    if not items:
        # An empty list would pass every gate silently; --exit-zero says so explicitly.
        raise doc.error(keys, "an empty list of rules disables the gate; name at least one rule")
    rules = set()
    for i, item in enumerate(items):
        if not isinstance(item, str):
            raise doc.error((*keys, i), f"expected a rule name, got {describe(item)}")
        try:
            rules.add(Rule.parse(item))
        except UsageError as exc:
            raise doc.error((*keys, i), exc.message) from exc
    return frozenset(rules)


def read_levels(
    doc: YamlDoc,
    keys: KeyPath,
    value: Any,
    defaults: tuple[frozenset[Rule], frozenset[Rule]] = (DEFAULT_RULES, DEFAULT_WARNINGS),
) -> tuple[frozenset[Rule], frozenset[Rule]]:
    """``rules: {loss: fail, drift: warn, unrenderable: off}`` over the defaults.

    Returns the failing and the reported rules.  A rule not named keeps its
    default (``defaults``: failing and reported; docs/rules.md); YAML 1.1 reads
    a bare ``off`` as false, which means ``off`` here too.
    """
    table = read_mapping(doc, keys, value, "rules {rule: off, warn or fail}")
    fail, warn = set(defaults[0]), set(defaults[1])
    allowed = ", ".join(level.value for level in Level)
    for name, level in table.items():
        try:
            rule = Rule.parse(str(name))
        except UsageError as exc:
            raise doc.error((*keys, name), exc.message) from exc
        if level is False:
            level = "off"
        if not isinstance(level, str) or level.strip().lower() not in {v.value for v in Level}:
            raise doc.error((*keys, name), f"expected one of {allowed}, got {describe(level)}")
        chosen = Level(level.strip().lower())
        fail.discard(rule)
        warn.discard(rule)
        {Level.FAIL: fail, Level.WARN: warn, Level.OFF: set()}[chosen].add(rule)
    if not fail:
        # As with fail-on: [], a gate that can never fail must be asked for with --exit-zero.
        raise doc.error(keys, "no rule is left at fail, which disables the gate; keep one")
    return frozenset(fail), frozenset(warn)


def _exemptions(doc: YamlDoc, keys: KeyPath, value: Any) -> tuple[Exemption, ...]:
    if not isinstance(value, list):
        raise doc.error(keys, f"expected a list of {{canvas/icon, reason}}, got {describe(value)}")
    out = []
    for i, item in enumerate(value):
        ikeys = (*keys, i)
        item = read_mapping(doc, ikeys, item, "an exemption {canvas/icon, rule, reason}")
        check_keys(doc, ikeys, item, _EXEMPT_KEYS)
        reason = item.get("reason")
        if not isinstance(reason, str) or not reason.strip():
            raise doc.error((*ikeys, "reason"), "every exemption needs a reason: (why it is fine)")
        bad = first_unsafe(reason)
        if bad is not None or len(reason) > 500:
            # Reasons are printed with findings: the same rule as names.
            raise doc.error(
                (*ikeys, "reason"),
                f"reason '{safe_text(reason[:40])}' has "
                f"{describe_char(bad) if bad else 'more than 500 characters'}; a reason is at "
                "most 500 characters, with no control, bidi or other invisible format character",
            )
        canvas = read_name(doc, (*ikeys, "canvas"), item["canvas"]) if "canvas" in item else None
        icon = read_name(doc, (*ikeys, "icon"), item["icon"]) if "icon" in item else None
        if canvas is None and icon is None:
            raise doc.error(ikeys, "an exemption names a canvas, an icon or both")
        rule = None
        if "rule" in item:
            rule = next(iter(read_rules(doc, (*ikeys, "rule"), [item["rule"]])))
        out.append(
            Exemption(
                reason=reason.strip(),
                canvas=canvas,
                icon=icon,
                rule=rule,
                path=doc.path,
                line=doc.line(ikeys),
                key=format_key(ikeys),
            )
        )
    return tuple(out)


# The config's numbers and the range each is read against (ranges.py).
_NUMBERS = {
    "alpha": ranges.ALPHA,
    "threshold": ranges.CONTRAST_RATIO,
    "visibility-floor": ranges.CONTRAST_RATIO,
    "loss-tolerance": ranges.LOSS_TOLERANCE,
    "near-duplicate-delta-e": ranges.DELTA_E,
    "max-loss": ranges.CONTRAST_LOSS,
    "min-delta-e": ranges.DELTA_E,
    "max-drift": ranges.DELTA_E,
    "min-size-contrast": ranges.CONTRAST_RATIO,
}
# Those that are the gate policy's limits with no default of the config's own.
_POLICY_LIMITS = ("visibility-floor", "loss-tolerance", "near-duplicate-delta-e")


def _max_combinations(doc: YamlDoc, where: KeyPath, data: dict[str, Any]) -> int:
    """``max-combinations``: a whole number in its range, else the default."""
    if "max-combinations" not in data:
        return ranges.DEFAULT_COMBINATIONS
    value = data["max-combinations"]
    number = read_number(doc, where, value, allowed=ranges.COMBINATIONS)
    if number != int(number):
        raise doc.error(where, f"expected {ranges.COMBINATIONS.what}, got {value!r}")
    return int(number)


def _policy(
    doc: YamlDoc,
    at: Callable[[str], KeyPath],
    data: dict[str, Any],
    numbers: dict[str, float],
) -> Policy:
    """The gate policy the config gives: its rules (``fail-on:`` or ``rules:``), limits and
    exemptions, each defaulting as documented (docs/config.md)."""
    rules, warnings = DEFAULT_RULES, DEFAULT_WARNINGS
    if "fail-on" in data and "rules" in data:
        raise doc.error(
            at("rules"), "give fail-on: or rules:, not both (rules: {loss: fail} says the same)"
        )
    if "fail-on" in data:
        rules = read_rules(doc, at("fail-on"), data["fail-on"])
    if "rules" in data:
        rules, warnings = read_levels(doc, at("rules"), data["rules"])
    limits = {k.replace("-", "_"): numbers[k] for k in _POLICY_LIMITS if k in numbers}
    return Policy(
        rules=rules,
        max_loss=numbers.get("max-loss", 0.0),
        min_delta_e=numbers.get("min-delta-e", 10.0),
        exemptions=_exemptions(doc, at("exempt"), data["exempt"]) if "exempt" in data else (),
        max_drift=numbers.get("max-drift", 10.0),
        min_size_contrast=numbers.get("min-size-contrast"),
        warnings=warnings,
        **limits,
    )


def config_from_doc(doc: YamlDoc, *, prefix: KeyPath = ()) -> ProjectConfig:
    """Validate a parsed config; ``prefix`` locates the table (``tool.alpha-audit``)."""
    raw: Any = doc.data
    for k in prefix:
        raw = raw[k]
    data = read_mapping(doc, prefix, raw, "an alpha-audit configuration")
    data = _normalise_keys(doc, prefix, data)
    check_keys(doc, prefix, data, CONFIG_KEYS)
    # The config's own folder (a symlinked config never picks its target's).
    base = doc.path.absolute().parent.resolve()

    def at(key: str) -> KeyPath:
        return (*prefix, key)

    found: dict[str, list[Path]] = {}
    for single, plural in (("theme", "themes"), ("iconset", "iconsets")):
        if single in data and plural in data:
            raise doc.error(at(plural), f"give {single} or {plural}, not both")
        key = plural if plural in data else single
        found[plural] = _paths(doc, at(key), data[key], base) if key in data else []
    numbers = {
        key: read_number(doc, at(key), data[key], allowed=allowed)
        for key, allowed in _NUMBERS.items()
        if key in data
    }
    pipeline = read_pipeline(doc, at("pipeline"), data["pipeline"]) if "pipeline" in data else None
    baseline = _path(doc, at("baseline"), data["baseline"], base) if "baseline" in data else None
    strict_svg = data.get("strict-svg", False)
    if not isinstance(strict_svg, bool):
        raise doc.error(at("strict-svg"), f"expected true or false, got {describe(strict_svg)}")
    gamut = read_gamut(doc, at("gamut"), data["gamut"]) if "gamut" in data else None
    tokens = None
    if "tokens" in data:
        tokens = _tokens_table(doc, at("tokens"), data["tokens"], base)
        own = isinstance(data["tokens"], dict) and "gamut" in data["tokens"]
        if gamut is not None and not own:  # the project's policy, unless tokens: says
            tokens = replace(tokens, gamut=gamut)
    return ProjectConfig(
        path=doc.path,
        themes=tuple(found["themes"]),
        iconsets=tuple(found["iconsets"]),
        alpha=numbers.get("alpha"),
        threshold=numbers.get("threshold"),
        policy=_policy(doc, at, data, numbers),
        baseline=baseline,
        strict_svg=strict_svg,
        tokens=tokens,
        pipeline=pipeline,
        gamut=gamut,
        max_combinations=_max_combinations(doc, at("max-combinations"), data),
        alpha_span=doc.spans.get(at("alpha")),
    )


_TOKEN_KEYS = (
    "file",
    "canvases",
    "colors",
    "modes",
    "modifier",
    "gamut",
    "alpha-extension",
    "format",
    "types",
)
_MODE_KEYS = ("audit", "light", "dark", "groups")


def _tokens_table(doc: YamlDoc, keys: KeyPath, value: Any, base: Path) -> TokenConfig:
    """The ``tokens:`` table; paths are relative to ``base`` and must stay inside it."""
    data = read_mapping(doc, keys, value, "the token settings")
    data = _normalise_keys(doc, keys, data)
    check_keys(doc, keys, data, _TOKEN_KEYS)

    def at(*sub: str) -> KeyPath:
        return (*keys, *sub)

    file = data.get("file")
    if not isinstance(file, str) or not file.strip() or "\x00" in file:
        raise doc.error(at("file"), "expected the token file, a path relative to the config")
    path = (base / file).resolve()
    if Path(file).is_absolute() or not path.is_relative_to(base):
        raise doc.error(at("file"), f"{file!r} resolves outside {base}; not allowed")

    def patterns(key: str, required: bool) -> tuple[str, ...]:
        raw = data.get(key)
        if raw is None and not required:
            return ()
        items = [raw] if isinstance(raw, str) else raw
        if not isinstance(items, list) or not items or not all(isinstance(i, str) for i in items):
            raise doc.error(at(key), 'expected a token-path pattern or a list, e.g. "color.bg.*"')
        return tuple(items)

    schemes, audit, groups = _modes_setting(doc, at("modes"), data.get("modes", {}))
    types = data.get("types", {})
    if not isinstance(types, dict) or not all(
        isinstance(k, str) and isinstance(v, str) and v for k, v in types.items()
    ):
        raise doc.error(
            at("types"), 'expected {token-path glob: type, ...}, e.g. {"color.*": color}'
        )
    ext = data.get("alpha-extension", DEFAULT_ALPHA_EXTENSION)
    if not isinstance(ext, str) or not ext:
        raise doc.error(at("alpha-extension"), "expected a reverse-DNS key such as com.alpha-audit")
    modifier = data.get("modifier")
    if modifier is not None and not isinstance(modifier, str):
        raise doc.error(
            at("modifier"), "expected the name of a Resolver modifier or Figma collection"
        )
    fmt = data.get("format", "auto")
    if fmt not in TOKEN_FORMATS:
        raise doc.error(at("format"), f"{fmt!r} is not one of {', '.join(TOKEN_FORMATS)}")
    return TokenConfig(
        file=path,
        canvases=patterns("canvases", True),
        colors=patterns("colors", False),
        modes=schemes,
        modifier=modifier,
        gamut=read_gamut(doc, at("gamut"), data["gamut"]) if "gamut" in data else "error",
        alpha_extension=ext,
        format=fmt,
        root=base,
        audit=audit,
        groups=groups,
        types=dict(types),
    )


_MODES_HELP = (
    "expected {mode: light|dark, ...} (mode names or globs), a list of the modes to audit, "
    "or {audit: [...], light: [...], dark: [...], groups: [...]}"
)


def _modes_setting(
    doc: YamlDoc, keys: KeyPath, raw: Any
) -> tuple[dict[str, Mode], tuple[str, ...], tuple[str, ...] | None]:
    """``(mode glob -> light|dark, globs to audit, Tokens Studio groups)`` of ``modes:``."""

    def globs(value: Any, *key: str) -> tuple[str, ...]:
        items = [value] if isinstance(value, str) else value
        if not isinstance(items, list) or not all(isinstance(i, str) and i for i in items):
            raise doc.error((*keys, *key), "expected a list of mode names or globs")
        return tuple(items)

    if isinstance(raw, list | str):
        return {}, globs(raw), None
    if not isinstance(raw, dict):
        raise doc.error(keys, _MODES_HELP)
    if all(isinstance(v, str) for v in raw.values()):  # {mode: light|dark}
        if not all(v in ("light", "dark") for v in raw.values()):
            raise doc.error(keys, _MODES_HELP)
        return {str(k): v for k, v in raw.items()}, (), None
    check_keys(doc, keys, raw, _MODE_KEYS)
    schemes: dict[str, Mode] = {}
    for scheme in ("light", "dark"):
        for glob in globs(raw.get(scheme, []), scheme):
            schemes[glob] = "light" if scheme == "light" else "dark"
    groups = None
    if "groups" in raw:
        groups = () if raw["groups"] is False else globs(raw["groups"], "groups")
    return schemes, globs(raw.get("audit", []), "audit") if "audit" in raw else (), groups
