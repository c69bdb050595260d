"""Audit icons as a browser draws them: Storybook stories and HTML pages, in every state.

The library behind ``alpha-audit render``: sources (:mod:`.sources`) x states
(:mod:`.states`) x engines are loaded in real browsers, each page and state
captured twice (icons drawn, icons hidden: :mod:`.capture`), and every paint
of every icon measured from the pixels (:mod:`.measure`) into
:class:`~alpha_audit.observed.MeasuredPaint` records beside the model's
prediction for the same paint and backdrop; asked for (``RenderConfig.crops``),
the icons a finding may show are cropped from both captures for the HTML report
(:mod:`.crops`).  :func:`page_report` makes the paints paint rows and judges
them as ``check`` judges its rows (:mod:`.audit`).  Pages are untrusted:
:mod:`.server` serves them on loopback and refuses every other request,
:mod:`.run` bounds time and memory.

Example (a built Storybook in the current folder)::

    from pathlib import Path
    from alpha_audit.pages import RenderConfig, StorybookSource, audit_pages, page_report
    run, paints = audit_pages(RenderConfig((StorybookSource(Path("storybook-static")),)))
    report = page_report(run, paints)
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
