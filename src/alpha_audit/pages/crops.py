"""Crops of the icons a report may show, cut while a page state's captures exist.

The two captures of a page state live only while it is measured; the HTML
report shows, beside each finding, its worst instance as drawn and its
backdrop.  So while the captures exist, the paints a finding may be about
(:func:`~alpha_audit.pages.audit.shown_rule`: the rules' own statements, not a
second test) are cut out of both, the icon's box grown by the ring its
surroundings are measured in, and kept as two small PNGs
(:class:`~alpha_audit.observed.IconCrop`).

Memory stays bounded whatever the number of stories: a crop is at most
:data:`CROP_SIDE` pixels a side, and a run keeps at most its limit of them
(:class:`CropStore`), failing rules' first, then in report order (story,
state, engine, DOM order), whichever order the pages finish in; the rest are
counted.  A run asked for no crops (any format but ``html``) cuts none.
"""

from __future__ import annotations

import heapq
import io
import math
import threading
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray
from PIL import Image

from alpha_audit.observed import IconCrop, MeasuredPaint
from alpha_audit.pages.audit import shown_rule
from alpha_audit.pages.capture import Capture
from alpha_audit.pages.measure import icon_region, ring_width
from alpha_audit.policy import Policy
from alpha_audit.rules import Level

__all__ = ["CROP_SIDE", "MAX_CROPS", "CropStore", "crop_icon"]

# A crop's longest side in pixels: a 48 CSS px icon at device scale 2 and its ring
# (2 x 2 CSS px) fits whole; larger icons keep every step-th device pixel.
CROP_SIDE = 128
# Crops a run keeps: at most 2 x 128 x 128 x 3 bytes of pixels each (96 KiB, far
# less as PNG), so the HTML report stays a few MB whatever the number of stories.
MAX_CROPS = 500


def _png(pixels: NDArray[np.uint8]) -> bytes:
    out = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(pixels), "RGB").save(out, "PNG")
    return out.getvalue()


def crop_icon(capture: Capture, paint: MeasuredPaint) -> IconCrop | None:
    """``paint``'s icon instance cut out of both captures (None when its box is off them).

    The box is the one measured (:func:`~alpha_audit.pages.measure.icon_region`
    grown by :func:`~alpha_audit.pages.measure.ring_width`), so the crop shows
    exactly the pixels the figures come from.
    """
    _, _, rows, cols = icon_region(capture, paint.box, ring_width(capture.scale))
    drawn, hidden = capture.drawn[rows, cols], capture.hidden[rows, cols]
    height, width = drawn.shape[:2]
    if height == 0 or width == 0:
        return None
    step = max(1, math.ceil(max(height, width) / CROP_SIDE))
    drawn, hidden = drawn[::step, ::step], hidden[::step, ::step]
    return IconCrop(
        paint.source,
        paint.state,
        paint.engine,
        paint.dom_path,
        _png(drawn),
        _png(hidden),
        drawn.shape[1],
        drawn.shape[0],
        capture.scale,
        step,
    )


class CropStore:
    """At most ``limit`` crops of a run, shared by its workers (thread-safe).

    :meth:`keep` is called once per page state with its rank in the report's
    order; whichever order the pages finish in, the store ends holding the
    first ``limit`` crops by (failing rule first, rank, order in the page), so
    the same run keeps the same crops.  ``wanted`` counts every crop asked for.
    """

    def __init__(self, limit: int, policy: Policy, threshold: float = 3.0) -> None:
        self.limit = limit
        self.policy = policy
        self.threshold = threshold
        self.wanted = 0
        # A max-heap of the kept crops by order (each key negated): the top leaves first.
        self._heap: list[tuple[tuple[int, int, int], IconCrop]] = []
        self._lock = threading.Lock()

    def keep(self, capture: Capture, paints: Sequence[MeasuredPaint], rank: int) -> None:
        """Crop the paints of one page state that a finding may show (``rank``: its order)."""
        orders: dict[tuple[str, str, str, str], tuple[tuple[int, int, int], MeasuredPaint]] = {}
        for k, paint in enumerate(paints):
            rule = shown_rule(paint, self.policy, self.threshold)
            if rule is None:
                continue
            order = (int(self.policy.level(rule) is not Level.FAIL), rank, k)
            key = (paint.source, paint.state, paint.engine, paint.dom_path)
            if key not in orders or order < orders[key][0]:
                orders[key] = (order, paint)
        for order, paint in orders.values():
            with self._lock:
                self.wanted += 1
                if self.limit <= 0 or (len(self._heap) >= self.limit and order > _last(self._heap)):
                    continue
            crop = crop_icon(capture, paint)  # outside the lock: PNG encoding takes a while
            if crop is None:
                with self._lock:
                    self.wanted -= 1
                continue
            with self._lock:
                heapq.heappush(self._heap, ((-order[0], -order[1], -order[2]), crop))
                if len(self._heap) > self.limit:
                    heapq.heappop(self._heap)

    @property
    def crops(self) -> tuple[IconCrop, ...]:
        """The crops kept, first to last."""
        with self._lock:
            return tuple(crop for _, crop in sorted(self._heap, reverse=True))

    @property
    def left_out(self) -> int:
        """Crops asked for and not kept (the limit was reached)."""
        with self._lock:
            return self.wanted - len(self._heap)


def _last(heap: list[tuple[tuple[int, int, int], IconCrop]]) -> tuple[int, int, int]:
    """The order of the last crop kept (the heap's top, its key negated back)."""
    a, b, c = heap[0][0]
    return -a, -b, -c
