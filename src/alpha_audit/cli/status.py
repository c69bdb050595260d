"""Process exit codes of ``alpha-audit``, documented in ``--help`` and the README."""

from __future__ import annotations

from enum import IntEnum

__all__ = ["ExitStatus"]


class ExitStatus(IntEnum):
    """What the exit code tells CI: a finding is never confused with a crash."""

    OK = 0
    """The command ran; for ``check``, the gate passed."""
    GATE_FAILED = 1
    """``check`` ran and the gate failed (a finding the policy names)."""
    INPUT_ERROR = 2
    """Bad usage or input, or a resource limit was hit; one line says which."""
    INTERNAL_ERROR = 3
    """A bug in alpha-audit: an exception nobody raised on purpose."""
