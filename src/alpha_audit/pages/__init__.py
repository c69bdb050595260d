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

from __future__ import annotations

from typing import TYPE_CHECKING

from alpha_audit.lazy import lazy_exports

if TYPE_CHECKING:
    from alpha_audit.pages.audit import page_audits, page_report
    from alpha_audit.pages.config import RenderConfig, config_from_yaml, source_from_argument
    from alpha_audit.pages.run import audit_pages
    from alpha_audit.pages.sources import FolderSource, StorybookSource, UrlSource
    from alpha_audit.pages.states import State, state_matrix

__all__ = [
    "FolderSource",
    "RenderConfig",
    "State",
    "StorybookSource",
    "UrlSource",
    "audit_pages",
    "config_from_yaml",
    "page_audits",
    "page_report",
    "source_from_argument",
    "state_matrix",
]

# Names load on first use: the CLI reads the states at start-up without the page audit
# (Pillow, coloraide, the YAML reader).
__getattr__ = lazy_exports(
    __name__,
    {
        "page_audits": "alpha_audit.pages.audit",
        "page_report": "alpha_audit.pages.audit",
        "RenderConfig": "alpha_audit.pages.config",
        "config_from_yaml": "alpha_audit.pages.config",
        "source_from_argument": "alpha_audit.pages.config",
        "audit_pages": "alpha_audit.pages.run",
        "FolderSource": "alpha_audit.pages.sources",
        "StorybookSource": "alpha_audit.pages.sources",
        "UrlSource": "alpha_audit.pages.sources",
        "State": "alpha_audit.pages.states",
        "state_matrix": "alpha_audit.pages.states",
    },
)
