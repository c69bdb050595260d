"""The ``alpha-audit`` command line (see :mod:`alpha_audit.cli.app`)."""

from alpha_audit.cli.app import ExitStatus, app, main

__all__ = ["ExitStatus", "app", "main"]
