"""Crops of the icons a report may show, from synthetic captures (no browser).

What is pinned: a crop is the measured box grown by the ring, pixel for pixel
(every pixel of the capture, or every step-th one for a large icon); only
paints a finding may take its figures from are cut; a run keeps at most its
limit, the same ones whichever order the pages finish in, and counts the rest.
"""

from __future__ import annotations

import io
import random
import threading
from dataclasses import replace

import numpy as np
import pytest
from PIL import Image

from alpha_audit.browser import Clip
from alpha_audit.pages.capture import Capture
from alpha_audit.pages.crops import CROP_SIDE, CropStore, crop_icon
from alpha_audit.policy import RENDER_POLICY, Policy
from alpha_audit.rules import Rule
from helpers import measured_paint


def capture(width: int = 200, height: int = 120, scale: int = 2) -> Capture:
    """Distinct pixels everywhere (so a crop's place in the capture can be read back)."""
    rng = np.random.default_rng(7)
    drawn = rng.integers(0, 256, (height * scale, width * scale, 3), dtype=np.uint8)
    hidden = rng.integers(0, 256, drawn.shape, dtype=np.uint8)
    return Capture((), Clip(10, 20, width, height), scale, drawn, hidden)


def paint(source: str = "icons--a", x: float = 20, y: float = 30, **changes: object):
    """A dark red icon on the dark surface (1.65:1): below the threshold unless changed."""
    base = measured_paint(
        source=source, state="theme:dark", drawn="#6e1a1f", behind="#0d1117",
        dom_path=f"div > svg:nth-of-type({int(x)})", box=(x, y, 24.0, 24.0), render_drift=None,
    )  # fmt: skip
    return replace(base, **changes)


def png(data: bytes) -> np.ndarray:
    with Image.open(io.BytesIO(data)) as image:
        return np.asarray(image.convert("RGB"))


def test_a_crop_is_the_box_grown_by_the_ring_pixel_for_pixel():
    cap = capture()
    crop = crop_icon(cap, paint(x=20.5, y=30))
    assert crop is not None and crop.step == 1 and crop.scale == 2
    # Box x 20.5..44.5, y 30..54 (CSS) in a capture from (10, 20): device columns
    # floor(21)=21..ceil(69)=69, rows 20..68, each grown by the ring of 4 device px.
    rows, cols = slice(20 - 4, 68 + 4), slice(21 - 4, 69 + 4)
    assert np.array_equal(png(crop.drawn), cap.drawn[rows, cols])
    assert np.array_equal(png(crop.hidden), cap.hidden[rows, cols])
    assert (crop.width, crop.height) == (56, 56)


def test_a_large_icon_keeps_every_step_th_pixel_within_the_crop_side():
    cap = capture(width=300, height=300)
    crop = crop_icon(cap, paint(x=20, y=30, box=(20.0, 30.0, 128.0, 100.0)))
    assert crop is not None and max(crop.width, crop.height) <= CROP_SIDE
    assert crop.step == 3  # 256 + 8 device px: two steps would leave 132
    rows, cols = slice(20 - 4, 220 + 4), slice(20 - 4, 276 + 4)
    assert np.array_equal(png(crop.drawn), cap.drawn[rows, cols][::3, ::3])


def test_a_box_off_the_capture_has_no_crop():
    assert crop_icon(capture(), paint(box=(900.0, 900.0, 24.0, 24.0))) is None


def test_only_what_may_become_a_finding_is_cut():
    store = CropStore(10, RENDER_POLICY)
    passing = paint(x=20, contrast=4.5)
    failing = paint(x=60)
    drifting = paint(x=100, contrast=4.5, render_drift=12.0)
    store.keep(capture(), [passing, failing, drifting], rank=0)
    assert [c.dom_path for c in store.crops] == [failing.dom_path, drifting.dom_path]
    # A policy that reports neither rule cuts nothing.
    quiet = CropStore(10, Policy(rules=frozenset(), warnings=frozenset()))
    quiet.keep(capture(), [passing, failing, drifting], rank=0)
    assert quiet.crops == () and quiet.wanted == 0


def test_the_cap_holds_and_keeps_the_same_crops_whatever_order_pages_finish_in():
    cap = capture()
    pages = [
        [paint(f"icons--{k:02d}", x=20 + 40 * i) for i in range(3)] for k in range(12)
    ]  # 12 page states of 3 failing icons each: 36 crops wanted
    kept = []

    def work(store: CropStore, ranks: list[int]) -> None:
        for k in ranks:
            store.keep(cap, pages[k], k)

    for seed in (1, 2):
        store = CropStore(5, RENDER_POLICY)
        order = list(range(len(pages)))
        random.Random(seed).shuffle(order)
        threads = [threading.Thread(target=work, args=(store, order[n::2])) for n in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert len(store.crops) == 5 and store.left_out == 31 and store.wanted == 36
        kept.append([c.key for c in store.crops])
    assert kept[0] == kept[1]
    assert [k[0] for k in kept[0]] == ["icons--00"] * 3 + ["icons--01"] * 2  # report order


def test_failing_rules_crops_come_before_reported_ones():
    store = CropStore(1, RENDER_POLICY)
    drifting = paint("icons--a", x=20, contrast=4.5, render_drift=12.0)
    failing = paint("icons--b", x=60)
    store.keep(capture(), [drifting], rank=0)
    store.keep(capture(), [failing], rank=1)
    assert [c.source for c in store.crops] == ["icons--b"] and store.left_out == 1


@pytest.mark.parametrize("limit", [0, 1])
def test_one_crop_per_instance_even_when_it_is_the_worst_for_two_rules(limit):
    both = paint(render_drift=12.0)
    store = CropStore(limit, Policy(rules=frozenset({Rule.BELOW_THRESHOLD, Rule.RENDER_DRIFT})))
    store.keep(capture(), [both], rank=0)
    assert len(store.crops) == limit and store.wanted == 1
