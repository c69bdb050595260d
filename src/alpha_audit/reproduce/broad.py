"""Broad-grid kernel: every source of one grid on every background of another.

Unlike the full gamut, both colours vary here, and with only 17 source
levels per channel a per-row bisection costs about as much as visiting the
17 columns.  So every combination is visited, but through tables: a clipped
channel depends only on (source level, background level, alpha), so
luminances are sums of table entries in the straightforward summation order
(bit-identical), the source's contrast is computed once for all alphas, and
blocks of one background red/green pair are small enough to stay in cache.
"""

from __future__ import annotations

import os
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import LUMINANCE_WEIGHTS

__all__ = ["BroadCounts", "broad_counts"]

_WR, _WG, _WB = LUMINANCE_WEIGHTS
_LOSS_LIMIT = 0.25  # paper, Section 4.2: share of decreases with loss <= 0.25
# Combinations per block (about 0.5 MB of float64 per temporary, inside L2).
_BLOCK = 1 << 17
_WORKERS = min(2, os.cpu_count() or 1)


@dataclass(frozen=True)
class BroadCounts:
    """Counts over all source x background combinations at one coefficient.

    ``worst`` indexes the combination with the largest loss as
    ``(source r, g, b level, background r, g, b level)``.
    """

    increase: int
    decrease: int
    loss_le_limit: int
    max_loss: float
    worst: tuple[int, int, int, int, int, int]


def _contrast(t: NDArray[np.float64], cb: NDArray[np.float64]) -> NDArray[np.float64]:
    """WCAG ratio from ``Y + 0.05`` values, as ``contrast_from_luminance`` rounds it."""
    return np.maximum(t, cb) / np.minimum(t, cb)


def broad_counts(
    source_levels: NDArray[np.float64],
    background_levels: NDArray[np.float64],
    alphas: NDArray[np.float64],
    *,
    tol: float,
) -> list[BroadCounts]:
    """Contrast changes of every source-grid colour on every background-grid colour.

    ``source_levels`` (S,) and ``background_levels`` (B,) are linear per-channel
    levels; the grids are their cubes.  Returns one :class:`BroadCounts` per alpha.
    """
    s = np.asarray(source_levels, dtype=np.float64)
    b = np.asarray(background_levels, dtype=np.float64)
    alphas = np.asarray(alphas, dtype=np.float64)
    n_s, n_b = s.size, b.size
    # tables[a, i, j]: clipped output channel for source level i on background level j.
    tables = np.clip(
        b[np.newaxis, np.newaxis, :]
        + alphas[:, np.newaxis, np.newaxis] * (s[np.newaxis, :, np.newaxis] - b),
        0.0,
        1.0,
    )
    ts = ((_WR * s[:, np.newaxis] + _WG * s[np.newaxis, :])[:, :, np.newaxis] + _WB * s) + 0.05
    red, green, blue = _WR * tables, _WG * tables, _WB * tables

    n_alpha = alphas.size
    blue_b = _WB * b
    splits = np.array_split(np.arange(n_s), max(1, round(n_s * n_s * n_s * n_b / _BLOCK)))

    local = threading.local()

    def block(jr: int, jg: int, rows: NDArray[np.intp]) -> NDArray[np.float64]:
        """(n_alpha, 4): increase, decrease, big losses, min change."""
        shape = (rows.size, n_s, n_s, n_b)
        if getattr(local, "shape", None) != shape:  # per-thread buffers, reused
            local.shape = shape
            local.y, local.top, local.cr = (np.empty(shape) for _ in range(3))
            local.flag = np.empty(shape, dtype=bool)
        y, top, cr, flag = local.y, local.top, local.cr, local.flag
        out = np.empty((n_alpha, 4))
        cb = ((_WR * b[jr] + _WG * b[jg]) + blue_b) + 0.05  # (B,) over background blue
        t = ts[rows, :, :, np.newaxis]
        np.divide(np.maximum(t, cb, out=top), np.minimum(t, cb, out=y), out=cr)  # source CR
        for a in range(n_alpha):
            p = red[a, rows, jr][:, np.newaxis] + green[a, :, jg][np.newaxis, :]
            np.add(p[:, :, np.newaxis, np.newaxis], blue[a], out=y)  # Yo
            y += 0.05
            np.maximum(y, cb, out=top)
            np.minimum(y, cb, out=y)
            np.divide(top, y, out=y)
            y -= cr  # change in contrast ratio
            out[a, 0] = np.count_nonzero(np.greater(y, tol, out=flag))
            out[a, 1] = np.count_nonzero(np.less(y, -tol, out=flag))
            out[a, 2] = np.count_nonzero(np.less(y, -_LOSS_LIMIT, out=flag))
            out[a, 3] = y.min()
        return out

    tasks = [(jr, jg, rows) for jr in range(n_b) for jg in range(n_b) for rows in splits]
    with ThreadPoolExecutor(max_workers=_WORKERS) as pool:
        results = list(pool.map(lambda task: block(*task), tasks))
    totals = np.stack(results)  # (tasks, n_alpha, 4)
    inc, dec, big = (totals[:, :, i].sum(axis=0).astype(np.int64) for i in range(3))
    summaries = []
    for a in range(n_alpha):
        at = int(np.argmin(totals[:, a, 3]))  # first block holding the smallest change
        min_change = totals[at, a, 3]
        summaries.append(
            BroadCounts(
                increase=int(inc[a]),
                decrease=int(dec[a]),
                loss_le_limit=int(dec[a] - big[a]),
                max_loss=float(-min_change) if min_change < -tol else 0.0,
                worst=_locate_worst(tasks[at], b, ts, (red[a], green[a], blue[a])),
            )
        )
    return summaries


def _locate_worst(
    task: tuple[int, int, NDArray[np.intp]],
    b: NDArray[np.float64],
    ts: NDArray[np.float64],
    weighted: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
) -> tuple[int, int, int, int, int, int]:
    """Where the smallest change of one coefficient lies inside the block ``task`` that
    holds it, in the straightforward expression: (source r, g, b, background r, g, b)."""
    jr, jg, rows = task
    red, green, blue = weighted
    cb = ((_WR * b[jr] + _WG * b[jg]) + _WB * b) + 0.05
    p = red[rows, jr][:, np.newaxis] + green[:, jg][np.newaxis, :]
    y = (p[:, :, np.newaxis, np.newaxis] + blue) + 0.05
    change = _contrast(y, cb) - _contrast(ts[rows, :, :, np.newaxis], cb)
    i_r, i_g, i_b, j_b = np.unravel_index(int(change.argmin()), change.shape)
    return int(rows[i_r]), int(i_g), int(i_b), jr, jg, int(j_b)
