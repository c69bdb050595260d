"""``suggest``: the exact largest safe coefficient over the audit's paint rows.

:mod:`~alpha_audit.suggest.engine` answers the question from *events*
(:mod:`~alpha_audit.suggest.events`) and :mod:`~alpha_audit.suggest.apply`
writes an answer into a manifest.
"""

from __future__ import annotations

from alpha_audit.lazy import lazy_exports

__all__ = ["SCOPES", "largest_safe_alpha", "suggest"]

# What suggest answers: one coefficient for the set, per colour, per group of roles, per icon.
SCOPES = ("set", "colour", "group", "icon")

__getattr__ = lazy_exports(
    __name__,
    {"largest_safe_alpha": "alpha_audit.suggest.engine", "suggest": "alpha_audit.suggest.engine"},
)
