"""``suggest``: the exact largest safe coefficient over the audit's paint rows.

:mod:`~alpha_audit.suggest.engine` answers the question from *events*
(:mod:`~alpha_audit.suggest.events`) and :mod:`~alpha_audit.suggest.apply`
writes an answer into a manifest.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
