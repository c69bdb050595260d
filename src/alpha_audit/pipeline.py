"""Files in, audit out: load a theme and an icon set, rasterise, audit."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from alpha_audit.audit import AuditResult, audit
from alpha_audit.errors import SvgError
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.svg import rasterize_icons
from alpha_audit.load.theme import load_theme

__all__ = ["check_files"]


def check_files(
    theme_path: str | Path,
    iconset_path: str | Path,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    strict_svg: bool = False,
    on_start: Callable[[int], None] | None = None,
    on_icon: Callable[[], None] | None = None,
) -> AuditResult:
    """Load both files, rasterise every icon at every size and audit.

    Icons that cannot be rendered are left out and listed in
    ``result.problems``; with ``strict_svg`` the first one raises
    :class:`~alpha_audit.errors.SvgError`.  ``on_start(n)`` and ``on_icon()``
    report progress.
    """
    theme = load_theme(theme_path)
    iconset = load_iconset(iconset_path)
    if on_start is not None:
        on_start(len(iconset.icons))
    masks = rasterize_icons(
        [(i.name, i.file) for i in iconset.icons], iconset.sizes, progress=on_icon
    )
    if strict_svg and masks.problems:
        first = masks.problems[0]
        raise SvgError(first.message, path=first.file)
    return audit(theme, iconset, alpha=alpha, threshold=threshold, problems=masks.problems)
