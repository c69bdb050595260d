"""The paper's numerical evaluation ("Opacity Is Not Just Opacity", Section 4 and Appendix A).

Library API: :func:`full_gamut`, :func:`broad_grid`, :func:`sweep` and
:func:`palette_separation` return frozen dataclasses of unrounded numbers and
work on any theme.  Never imported by the audit path.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
