"""The ``alpha-audit`` command line: a thin typer layer over the library.

:mod:`.root` holds the application, ``main`` and the one exit boundary;
:mod:`.status` the exit codes; :mod:`.console`, :mod:`.options` and
:mod:`.flags` what the command modules share (they never import :mod:`.root`).
"""

from typing import TYPE_CHECKING

from alpha_audit.cli.root import main
from alpha_audit.cli.status import ExitStatus
from alpha_audit.lazy import lazy_exports

if TYPE_CHECKING:
    from alpha_audit.cli.root import app

__all__ = ["ExitStatus", "app", "main"]

# ``app`` imports every command; ``main`` only the one it runs.
__getattr__ = lazy_exports(__name__, {"app": "alpha_audit.cli.root"})
