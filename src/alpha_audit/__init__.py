"""alpha-audit: audit icon sets across themes with extended-alpha compositing.

Everything a command does can be done from Python, and every name below is
importable from here (each is written once, in ``__init__.pyi``)::

    from alpha_audit import audit, bundled_theme, load_iconset, load_theme, rasterize_icons

    theme = load_theme(bundled_theme("paper16"))
    result = audit(theme, load_iconset("examples/vibrant/iconset.yaml"))

Names are imported on first use (PEP 562, through ``lazy_loader``), so
``import alpha_audit`` or ``import alpha_audit.color`` loads neither the gate,
the loaders nor the command line.
"""

import lazy_loader

__version__ = "0.1.0"
"""The one version source: ``pyproject.toml`` reads it (``[tool.setuptools.dynamic]``)."""

# Names load on first use from the stub beside this file (__init__.pyi), so
# ``import alpha_audit`` loads neither numpy, the gate, the loaders nor the command line.
__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
