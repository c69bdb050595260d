"""Headless browser engines behind one small interface (:class:`Browser`).

``ENGINES`` is the registry, in the paper's order (Chrome, Firefox, WebKit);
:func:`installed_engines` lists those present on this machine and
:func:`open_browser` starts one by name.  A new engine is one module and one
registry line.  The loopback servers a browser loads pages from, and the proxy
that refuses everything else, are :mod:`alpha_audit.browser.server`.
"""

from __future__ import annotations

from alpha_audit.browser.chromium import Chromium
from alpha_audit.browser.firefox import Firefox
from alpha_audit.browser.interface import (
    COLOR_SCHEMES,
    Browser,
    BrowserError,
    Clip,
    ColorScheme,
    Installation,
    JSONValue,
    LaunchOptions,
)
from alpha_audit.browser.webkit import WebKit
from alpha_audit.errors import UsageError

__all__ = [
    "COLOR_SCHEMES",
    "ENGINES",
    "Browser",
    "BrowserError",
    "Chromium",
    "Clip",
    "ColorScheme",
    "Firefox",
    "Installation",
    "JSONValue",
    "LaunchOptions",
    "WebKit",
    "engine_class",
    "installed_engines",
    "open_browser",
]

ENGINES: dict[str, type[Browser]] = {cls.NAME: cls for cls in (Chromium, Firefox, WebKit)}


def engine_class(name: str) -> type[Browser]:
    """The :class:`Browser` subclass registered as ``name``.

    >>> engine_class("firefox").LABEL
    'Firefox'
    """
    try:
        return ENGINES[name]
    except KeyError:
        raise UsageError(
            f"unknown browser engine {name!r}; choose from {', '.join(ENGINES)}"
        ) from None


def installed_engines() -> dict[str, Installation]:
    """Engines whose programs are present here, by name, in registry order."""
    found = {name: cls.find() for name, cls in ENGINES.items()}
    return {name: where for name, where in found.items() if where is not None}


def open_browser(
    name: str, *, timeout: float = 60.0, options: LaunchOptions | None = None
) -> Browser:
    """Start engine ``name``; raises :class:`BrowserError` when it is not installed."""
    return engine_class(name)(timeout=timeout, options=options)
