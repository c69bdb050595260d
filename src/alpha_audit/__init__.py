"""alpha-audit: audit icon sets across themes with extended-alpha compositing.

The library is usable without the CLI::

    from alpha_audit import audit, load_iconset, load_theme

    result = audit(load_theme("themes/paper16.yaml"), load_iconset("examples/vibrant/iconset.yaml"))
    print(result.summary)
"""

from alpha_audit.audit import AuditResult, Collision, Row, Separation, Summary, audit
from alpha_audit.errors import AlphaAuditError, InputError, SvgError, UsageError
from alpha_audit.export import export_table, render_export
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.svg import rasterize, rasterize_icons
from alpha_audit.load.theme import load_theme
from alpha_audit.load.tokens import load_token_modes
from alpha_audit.load.tokens.themes import load_token_themes
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.pair import pair_table
from alpha_audit.pipeline import check_files

__version__ = "0.1.0"

__all__ = [
    "AlphaAuditError",
    "AuditResult",
    "Canvas",
    "Collision",
    "Icon",
    "IconSet",
    "InputError",
    "Row",
    "Separation",
    "Summary",
    "SvgError",
    "Theme",
    "UsageError",
    "__version__",
    "audit",
    "check_files",
    "export_table",
    "load_iconset",
    "load_theme",
    "load_token_modes",
    "load_token_themes",
    "pair_table",
    "rasterize",
    "rasterize_icons",
    "render_export",
]
