"""The ``alpha-audit`` command line: a thin typer layer over the library.

:mod:`.root` holds the application, ``main`` and the one exit boundary;
:mod:`.status` the exit codes; :mod:`.console`, :mod:`.options` and
:mod:`.flags` what the command modules share (they never import :mod:`.root`).
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
