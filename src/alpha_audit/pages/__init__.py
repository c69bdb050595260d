"""Audit icons as a browser draws them: Storybook stories and HTML pages, in every state.

The library behind ``alpha-audit render``: sources (:mod:`.sources`) x states
(:mod:`.states`) x engines are loaded in real browsers, each page and state
captured twice (icons drawn, icons hidden: :mod:`.capture`), and every paint
of every icon measured from the pixels (:mod:`.measure`) into
:class:`MeasuredPaint` records beside the model's prediction for the same
paint and backdrop; asked for (``RenderConfig.crops``), the icons a finding
may show are cropped from both captures for the HTML report (:mod:`.crops`).
Pages are untrusted: :mod:`.server` serves them on loopback and refuses every
other request, :mod:`.run` bounds time and memory.

Example (a built Storybook in the current folder)::

    from pathlib import Path
    from alpha_audit.pages import RenderConfig, StorybookSource, audit_pages
    result = audit_pages(RenderConfig((StorybookSource(Path("storybook-static")),)))
"""

from alpha_audit.pages.config import RenderConfig, config_from_yaml, source_from_argument
from alpha_audit.pages.measured import (
    MEASURED,
    UNMEASURED,
    Basis,
    BlockedRequest,
    Coverage,
    IconCrop,
    IconMatch,
    MeasuredPaint,
    PageProblem,
    Prediction,
    RenderResult,
)
from alpha_audit.pages.run import audit_pages
from alpha_audit.pages.sources import FolderSource, StorybookSource, UrlSource
from alpha_audit.pages.states import State, state_matrix

__all__ = [
    "MEASURED",
    "UNMEASURED",
    "Basis",
    "BlockedRequest",
    "Coverage",
    "FolderSource",
    "IconCrop",
    "IconMatch",
    "MeasuredPaint",
    "PageProblem",
    "Prediction",
    "RenderConfig",
    "RenderResult",
    "State",
    "StorybookSource",
    "UrlSource",
    "audit_pages",
    "config_from_yaml",
    "source_from_argument",
    "state_matrix",
]
