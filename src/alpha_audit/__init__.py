"""alpha-audit: audit icon sets across themes with extended-alpha compositing.

Everything a command does can be done from Python, and every name below is
importable from here::

    from alpha_audit import audit, bundled_theme, load_iconset, load_theme, rasterize_icons

    theme = load_theme(bundled_theme("paper16"))
    result = audit(theme, load_iconset("examples/vibrant/iconset.yaml"))

Names are imported on first use (PEP 562 module ``__getattr__``), so
``import alpha_audit`` or ``import alpha_audit.color`` loads neither the gate,
the loaders nor the command line.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"
"""The one version source: ``pyproject.toml`` reads it (``[tool.setuptools.dynamic]``)."""

# name -> (module, attribute); keep the TYPE_CHECKING imports below the same (a test checks).
_EXPORTS: dict[str, tuple[str, str]] = {
    "AlphaAuditError": ("alpha_audit.errors", "AlphaAuditError"),
    "ColorSyntaxError": ("alpha_audit.errors", "ColorSyntaxError"),
    "InputError": ("alpha_audit.errors", "InputError"),
    "SvgError": ("alpha_audit.errors", "SvgError"),
    "UsageError": ("alpha_audit.errors", "UsageError"),
    "Canvas": ("alpha_audit.model", "Canvas"),
    "Icon": ("alpha_audit.model", "Icon"),
    "IconSet": ("alpha_audit.model", "IconSet"),
    "Theme": ("alpha_audit.model", "Theme"),
    "composite_extended": ("alpha_audit.color", "composite_extended"),
    "contrast_ratio": ("alpha_audit.color", "contrast_ratio"),
    "delta_e_2000": ("alpha_audit.color", "delta_e_2000"),
    "hex_to_linear": ("alpha_audit.color", "hex_to_linear"),
    "linear_to_hex": ("alpha_audit.color", "linear_to_hex"),
    "parse_color": ("alpha_audit.color", "parse_color"),
    "relative_luminance": ("alpha_audit.color", "relative_luminance"),
    "srgb_decode": ("alpha_audit.color", "srgb_decode"),
    "srgb_encode": ("alpha_audit.color", "srgb_encode"),
    "to_8bit": ("alpha_audit.color", "to_8bit"),
    "load_theme": ("alpha_audit.load.theme", "load_theme"),
    "load_iconset": ("alpha_audit.load.iconset", "load_iconset"),
    "ProjectConfig": ("alpha_audit.load.config", "ProjectConfig"),
    "Overrides": ("alpha_audit.load.config", "Overrides"),
    "resolve_config": ("alpha_audit.load.config", "resolve_config"),
    "load_config": ("alpha_audit.load.config", "load_config"),
    "project_config": ("alpha_audit.load.config", "project_config"),
    "IconProblem": ("alpha_audit.model", "IconProblem"),
    "MaskSet": ("alpha_audit.load.svg", "MaskSet"),
    "RenderLimits": ("alpha_audit.load.svg", "RenderLimits"),
    "rasterize": ("alpha_audit.load.svg", "rasterize"),
    "rasterize_icons": ("alpha_audit.load.svg", "rasterize_icons"),
    "bundled_iconset": ("alpha_audit.bundled", "bundled_iconset"),
    "bundled_iconsets": ("alpha_audit.bundled", "bundled_iconsets"),
    "bundled_theme": ("alpha_audit.bundled", "bundled_theme"),
    "bundled_themes": ("alpha_audit.bundled", "bundled_themes"),
    "iconset_source": ("alpha_audit.bundled", "iconset_source"),
    "load_bundled_themes": ("alpha_audit.load.theme", "load_bundled_themes"),
    "theme_source": ("alpha_audit.bundled", "theme_source"),
    "AuditResult": ("alpha_audit.rows", "AuditResult"),
    "CanvasSummary": ("alpha_audit.rows", "CanvasSummary"),
    "Collision": ("alpha_audit.rows", "Collision"),
    "Row": ("alpha_audit.rows", "Row"),
    "Separation": ("alpha_audit.rows", "Separation"),
    "Summary": ("alpha_audit.rows", "Summary"),
    "audit": ("alpha_audit.rows", "audit"),
    "DEFAULT_RULES": ("alpha_audit.rules", "DEFAULT_RULES"),
    "RULES": ("alpha_audit.rules", "RULES"),
    "Rule": ("alpha_audit.rules", "Rule"),
    "Exemption": ("alpha_audit.policy", "Exemption"),
    "Policy": ("alpha_audit.policy", "Policy"),
    "CheckReport": ("alpha_audit.results", "CheckReport"),
    "Finding": ("alpha_audit.findings", "Finding"),
    "FindingKey": ("alpha_audit.findings", "FindingKey"),
    "findings_for": ("alpha_audit.findings", "findings_for"),
    "GateResult": ("alpha_audit.gate", "GateResult"),
    "baseline_document": ("alpha_audit.gate", "baseline_document"),
    "evaluate": ("alpha_audit.gate", "evaluate"),
    "parse_baseline": ("alpha_audit.baseline", "parse_baseline"),
    "read_baseline": ("alpha_audit.baseline", "read_baseline"),
    "with_fixes": ("alpha_audit.fixes", "with_fixes"),
    "check_project": ("alpha_audit.pipeline", "check_project"),
    "CheckFormat": ("alpha_audit.render", "CheckFormat"),
    "RenderOptions": ("alpha_audit.render", "RenderOptions"),
    "render_check": ("alpha_audit.render", "render_check"),
    "SafeAlpha": ("alpha_audit.results", "SafeAlpha"),
    "SuggestResult": ("alpha_audit.results", "SuggestResult"),
    "largest_safe_alpha": ("alpha_audit.suggest.engine", "largest_safe_alpha"),
    "SuggestFormat": ("alpha_audit.render", "SuggestFormat"),
    "render_suggest": ("alpha_audit.render", "render_suggest"),
    "suggest_document": ("alpha_audit.render.suggest", "suggest_document"),
    "apply_alpha": ("alpha_audit.suggest.apply", "apply_alpha"),
    "PairRow": ("alpha_audit.pair", "PairRow"),
    "pair_table": ("alpha_audit.pair", "pair_table"),
    "PairReport": ("alpha_audit.pair", "PairReport"),
    "pair_report": ("alpha_audit.pair", "pair_report"),
    "PairFormat": ("alpha_audit.render", "PairFormat"),
    "ReproduceFormat": ("alpha_audit.reproduce.formats", "ReproduceFormat"),
    "PreviewResult": ("alpha_audit.preview.files", "PreviewResult"),
    "preview_files": ("alpha_audit.preview.files", "preview_files"),
    "Layout": ("alpha_audit.preview.sheets", "Layout"),
    "Experiment": ("alpha_audit.reproduce.run", "Experiment"),
    "Reproduction": ("alpha_audit.reproduce.run", "Reproduction"),
    "write_figures": ("alpha_audit.reproduce.figures", "write_figures"),
    "write_text": ("alpha_audit.output", "write_text"),
    "reproduction_json": ("alpha_audit.reproduce.report", "render_json"),
    "export_project": ("alpha_audit.export", "export_project"),
    "export_table": ("alpha_audit.export", "export_table"),
    "render_export": ("alpha_audit.export", "render_export"),
    "load_token_modes": ("alpha_audit.load.tokens", "load_token_modes"),
    "load_token_themes": ("alpha_audit.load.tokens.themes", "load_token_themes"),
    "reproduction_markdown": ("alpha_audit.reproduce.report", "render_markdown"),
}

__all__ = [
    "DEFAULT_RULES",
    "RULES",
    "AlphaAuditError",
    "AuditResult",
    "Canvas",
    "CanvasSummary",
    "CheckFormat",
    "CheckReport",
    "Collision",
    "ColorSyntaxError",
    "Exemption",
    "Experiment",
    "Finding",
    "FindingKey",
    "GateResult",
    "Icon",
    "IconProblem",
    "IconSet",
    "InputError",
    "Layout",
    "MaskSet",
    "Overrides",
    "PairFormat",
    "PairReport",
    "PairRow",
    "Policy",
    "PreviewResult",
    "ProjectConfig",
    "RenderLimits",
    "RenderOptions",
    "ReproduceFormat",
    "Reproduction",
    "Row",
    "Rule",
    "SafeAlpha",
    "Separation",
    "SuggestFormat",
    "SuggestResult",
    "Summary",
    "SvgError",
    "Theme",
    "UsageError",
    "__version__",
    "apply_alpha",
    "audit",
    "baseline_document",
    "bundled_iconset",
    "bundled_iconsets",
    "bundled_theme",
    "bundled_themes",
    "check_project",
    "composite_extended",
    "contrast_ratio",
    "delta_e_2000",
    "evaluate",
    "export_project",
    "export_table",
    "findings_for",
    "hex_to_linear",
    "iconset_source",
    "largest_safe_alpha",
    "linear_to_hex",
    "load_bundled_themes",
    "load_config",
    "load_iconset",
    "load_theme",
    "load_token_modes",
    "load_token_themes",
    "pair_report",
    "pair_table",
    "parse_baseline",
    "parse_color",
    "preview_files",
    "project_config",
    "rasterize",
    "rasterize_icons",
    "read_baseline",
    "relative_luminance",
    "render_check",
    "render_export",
    "render_suggest",
    "reproduction_json",
    "reproduction_markdown",
    "resolve_config",
    "srgb_decode",
    "srgb_encode",
    "suggest_document",
    "theme_source",
    "to_8bit",
    "with_fixes",
    "write_figures",
    "write_text",
]

if TYPE_CHECKING:  # for type checkers only; at run time __getattr__ imports on demand
    from alpha_audit.baseline import (
        parse_baseline,
        read_baseline,
    )
    from alpha_audit.bundled import (
        bundled_iconset,
        bundled_iconsets,
        bundled_theme,
        bundled_themes,
        iconset_source,
        theme_source,
    )
    from alpha_audit.color import (
        composite_extended,
        contrast_ratio,
        delta_e_2000,
        hex_to_linear,
        linear_to_hex,
        parse_color,
        relative_luminance,
        srgb_decode,
        srgb_encode,
        to_8bit,
    )
    from alpha_audit.errors import (
        AlphaAuditError,
        ColorSyntaxError,
        InputError,
        SvgError,
        UsageError,
    )
    from alpha_audit.export import (
        export_project,
        export_table,
        render_export,
    )
    from alpha_audit.findings import (
        Finding,
        FindingKey,
        findings_for,
    )
    from alpha_audit.fixes import (
        with_fixes,
    )
    from alpha_audit.gate import (
        GateResult,
        baseline_document,
        evaluate,
    )
    from alpha_audit.load.config import (
        Overrides,
        ProjectConfig,
        load_config,
        project_config,
        resolve_config,
    )
    from alpha_audit.load.iconset import (
        load_iconset,
    )
    from alpha_audit.load.svg import MaskSet, RenderLimits, rasterize, rasterize_icons
    from alpha_audit.load.theme import (
        load_bundled_themes,
        load_theme,
    )
    from alpha_audit.load.tokens import (
        load_token_modes,
    )
    from alpha_audit.load.tokens.themes import (
        load_token_themes,
    )
    from alpha_audit.model import (
        Canvas,
        Icon,
        IconProblem,
        IconSet,
        Theme,
    )
    from alpha_audit.output import (
        write_text,
    )
    from alpha_audit.pair import (
        PairReport,
        PairRow,
        pair_report,
        pair_table,
    )
    from alpha_audit.pipeline import (
        check_project,
    )
    from alpha_audit.policy import (
        Exemption,
        Policy,
    )
    from alpha_audit.preview.files import (
        PreviewResult,
        preview_files,
    )
    from alpha_audit.preview.sheets import (
        Layout,
    )
    from alpha_audit.render import (
        CheckFormat,
        PairFormat,
        RenderOptions,
        SuggestFormat,
        render_check,
        render_suggest,
    )
    from alpha_audit.render.suggest import (
        suggest_document,
    )
    from alpha_audit.reproduce.figures import (
        write_figures,
    )
    from alpha_audit.reproduce.formats import (
        ReproduceFormat,
    )
    from alpha_audit.reproduce.report import (
        render_json as reproduction_json,
    )
    from alpha_audit.reproduce.report import (
        render_markdown as reproduction_markdown,
    )
    from alpha_audit.reproduce.run import (
        Experiment,
        Reproduction,
    )
    from alpha_audit.results import (
        CheckReport,
        SafeAlpha,
        SuggestResult,
    )
    from alpha_audit.rows import (
        AuditResult,
        CanvasSummary,
        Collision,
        Row,
        Separation,
        Summary,
        audit,
    )
    from alpha_audit.rules import (
        DEFAULT_RULES,
        RULES,
        Rule,
    )
    from alpha_audit.suggest.apply import (
        apply_alpha,
    )
    from alpha_audit.suggest.engine import (
        largest_safe_alpha,
    )


def __getattr__(name: str) -> Any:
    """Import a public name's module on first use and cache the name here."""
    try:
        module, attribute = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'alpha_audit' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(module), attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})
