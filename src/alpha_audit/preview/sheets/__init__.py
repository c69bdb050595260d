"""PNG sheets: icons composited on canvases, laid out like the paper's figures.

- :mod:`~alpha_audit.preview.sheets.plan`: which sheets, their names and rows;
- :mod:`~alpha_audit.preview.sheets.surface`: the drawing surface and spacing;
- one module per layout: :mod:`~alpha_audit.preview.sheets.grid` (a sheet per
  canvas and size, a row of icons per coefficient, each icon's contrast ratio
  underneath), :mod:`~alpha_audit.preview.sheets.swatches` (a sheet per canvas,
  palette across, coefficients down: the paper's figure "Outputs for all seven
  Vibrant source colors") and :mod:`~alpha_audit.preview.sheets.compare` (a
  sheet per size, a row per canvas, ``alpha = 1`` beside each other
  coefficient: the paper's gallery figures);
- :mod:`~alpha_audit.preview.sheets.pages` splits sheets over
  :data:`PIXEL_BUDGET` into pages, :mod:`~alpha_audit.preview.sheets.render`
  picks the layout,
  :mod:`~alpha_audit.preview.sheets.write` writes the files.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
