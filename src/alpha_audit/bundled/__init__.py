"""The themes and example icon set that ship inside the package, found by name.

``themes/`` and ``iconsets/vibrant/`` here are symbolic links to the
repository's top-level ``themes/`` and ``examples/vibrant/`` (where the README's
commands read them); a wheel or sdist holds real copies, read through
:mod:`importlib.resources` wherever the package is installed.

>>> "paper16" in bundled_themes()
True
>>> bundled_theme("paper16").name
'paper16.yaml'
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

from alpha_audit.errors import UsageError

__all__ = [
    "bundled_iconset",
    "bundled_iconsets",
    "bundled_theme",
    "bundled_themes",
    "iconset_source",
    "theme_source",
]

MANIFEST = "iconset.yaml"
"""File name of a bundled icon set's manifest inside its folder."""


def _root(kind: str) -> Path:
    root = files(__name__) / kind
    if not isinstance(root, Path):  # pragma: no cover - only a zipped install gets here
        raise UsageError(f"bundled {kind} are not on the file system; give a file path instead")
    return root


def bundled_themes() -> tuple[str, ...]:
    """Names of the bundled themes, sorted (``github-primer``, ``material3``, ``paper16``)."""
    return tuple(sorted(p.stem for p in _root("themes").glob("*.yaml") if p.is_file()))


def bundled_iconsets() -> tuple[str, ...]:
    """Names of the bundled example icon sets, sorted (``vibrant``)."""
    return tuple(sorted(p.name for p in _root("iconsets").iterdir() if (p / MANIFEST).is_file()))


def bundled_theme(name: str) -> Path:
    """The theme file of bundled theme ``name``; unknown names list the valid ones."""
    if name not in bundled_themes():
        raise UsageError(f"no bundled theme {name!r}; bundled: {', '.join(bundled_themes())}")
    return _root("themes") / f"{name}.yaml"


def bundled_iconset(name: str) -> Path:
    """The manifest of bundled icon set ``name``; unknown names list the valid ones."""
    if name not in bundled_iconsets():
        raise UsageError(f"no bundled icon set {name!r}; bundled: {', '.join(bundled_iconsets())}")
    return _root("iconsets") / name / MANIFEST


def theme_source(arg: str | Path) -> Path:
    """``arg`` if it is an existing path, else the bundled theme it names, else ``arg`` as is.

    A file always wins over a bundled name, so a project's own ``paper16`` is
    never shadowed; a path that exists nowhere is left for the loader to report.
    """
    path = Path(arg)
    if not path.exists() and str(arg) in bundled_themes():
        return bundled_theme(str(arg))
    return path


def iconset_source(arg: str | Path) -> Path:
    """Like :func:`theme_source`, for icon-set manifests and the bundled ``vibrant`` set."""
    path = Path(arg)
    if not path.exists() and str(arg) in bundled_iconsets():
        return bundled_iconset(str(arg))
    return path
