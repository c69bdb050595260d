"""Package attributes imported on first use (PEP 562), for packages the command line touches.

A command registers its options at start-up, which imports the package of each
option's enum; the package's heavy modules (Pillow, the experiments) load only
when one of its names is used.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(package: str, modules: Mapping[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` for ``package``: ``name`` from ``modules[name]`` on first use.

    The value is then kept on the package, so later lookups are plain attributes.
    """

    def __getattr__(name: str) -> Any:
        try:
            module = modules[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        value = getattr(importlib.import_module(module), name)
        setattr(sys.modules[package], name, value)
        return value

    return __getattr__
