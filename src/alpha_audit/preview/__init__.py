"""Previews: PNG sheets and a self-contained WebGL2 page, pixel-exact to the paper's maths."""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
