"""Every public name of alpha_audit, each written once; ``__init__.py`` loads them on first use."""

__version__: str

from .baseline import (
    parse_baseline as parse_baseline,
    read_baseline as read_baseline,
)
from .bundled import (
    bundled_iconset as bundled_iconset,
    bundled_iconsets as bundled_iconsets,
    bundled_theme as bundled_theme,
    bundled_themes as bundled_themes,
    iconset_source as iconset_source,
    theme_source as theme_source,
)
from .color import (
    composite_extended as composite_extended,
    contrast_ratio as contrast_ratio,
    delta_e_2000 as delta_e_2000,
    hex_to_linear as hex_to_linear,
    linear_to_hex as linear_to_hex,
    parse_color as parse_color,
    relative_luminance as relative_luminance,
    srgb_decode as srgb_decode,
    srgb_encode as srgb_encode,
    to_8bit as to_8bit,
)
from .errors import (
    AlphaAuditError as AlphaAuditError,
    ColorSyntaxError as ColorSyntaxError,
    InputError as InputError,
    SvgError as SvgError,
    UsageError as UsageError,
)
from .export import (
    export_project as export_project,
    export_table as export_table,
    render_export as render_export,
)
from .findings import (
    Finding as Finding,
    FindingKey as FindingKey,
    findings_for as findings_for,
)
from .fixes import (
    with_fixes as with_fixes,
)
from .gate import (
    GateResult as GateResult,
    baseline_document as baseline_document,
    evaluate as evaluate,
)
from .load.config import (
    Overrides as Overrides,
    ProjectConfig as ProjectConfig,
    load_config as load_config,
    project_config as project_config,
    resolve_config as resolve_config,
)
from .load.iconset import (
    load_iconset as load_iconset,
)
from .load.svg import (
    MaskSet as MaskSet,
    RenderLimits as RenderLimits,
    rasterize as rasterize,
    rasterize_icons as rasterize_icons,
)
from .load.theme import (
    load_bundled_themes as load_bundled_themes,
    load_theme as load_theme,
)
from .load.tokens import (
    load_token_modes as load_token_modes,
)
from .load.tokens.themes import (
    load_token_themes as load_token_themes,
)
from .model import (
    Canvas as Canvas,
    Icon as Icon,
    IconProblem as IconProblem,
    IconSet as IconSet,
    Theme as Theme,
)
from .output import (
    write_text as write_text,
)
from .pair import (
    PairReport as PairReport,
    PairRow as PairRow,
    pair_report as pair_report,
    pair_table as pair_table,
)
from .pipeline import (
    check_project as check_project,
)
from .policy import (
    Exemption as Exemption,
    Policy as Policy,
)
from .preview.files import (
    PreviewResult as PreviewResult,
    preview_files as preview_files,
)
from .preview.sheets import (
    Layout as Layout,
)
from .render import (
    CheckFormat as CheckFormat,
    PairFormat as PairFormat,
    RenderOptions as RenderOptions,
    SuggestFormat as SuggestFormat,
    render_check as render_check,
    render_suggest as render_suggest,
)
from .render.suggest import (
    suggest_document as suggest_document,
)
from .reproduce.figures import (
    write_figures as write_figures,
)
from .reproduce.formats import (
    ReproduceFormat as ReproduceFormat,
)
from .reproduce.report import (
    reproduction_json as reproduction_json,
    reproduction_markdown as reproduction_markdown,
)
from .reproduce.run import (
    Experiment as Experiment,
    Reproduction as Reproduction,
)
from .results import (
    CheckReport as CheckReport,
    SafeAlpha as SafeAlpha,
    SuggestResult as SuggestResult,
)
from .rows import (
    AuditResult as AuditResult,
    CanvasSummary as CanvasSummary,
    Collision as Collision,
    Row as Row,
    Separation as Separation,
    Summary as Summary,
    audit as audit,
)
from .rules import (
    DEFAULT_RULES as DEFAULT_RULES,
    RULES as RULES,
    Rule as Rule,
)
from .suggest.apply import (
    apply_alpha as apply_alpha,
)
from .suggest.engine import (
    largest_safe_alpha as largest_safe_alpha,
)
