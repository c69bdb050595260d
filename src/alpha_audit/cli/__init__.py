"""The ``alpha-audit`` command line: a thin typer layer over the library.

:mod:`.root` holds the application, ``main`` and the one exit boundary;
:mod:`.status` the exit codes; :mod:`.console`, :mod:`.options` and
:mod:`.flags` what the command modules share (they never import :mod:`.root`).
"""

from alpha_audit.cli.root import app, main
from alpha_audit.cli.status import ExitStatus

__all__ = ["ExitStatus", "app", "main"]
