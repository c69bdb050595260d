"""Exact closest pair under a pairwise colour difference, in bounded memory.

The all-pairs minimum of ``k`` colours costs ``k (k - 1) / 2`` evaluations
and, done in one array, ``O(k^2)`` memory (3.3 GiB for 2,788 colours on 38
canvases).  Every measure used here has a one-dimensional *lower bound*: a
key ``z`` with ``d(a, b) >= |z_a - z_b|``.  Sorting by ``z`` and walking
outwards in sorted offsets ``1, 2, ...`` then prunes exactly: once every pair
at some offset is farther apart in ``z`` than the best distance found, no
pair at a larger offset can beat it.  Memory is one chunk of pairs at a time.

For CIEDE2000 (Sharma, Wu and Dalal 2005, eq. 1-22) the key is
``L* / S_L,max``:

    dE00^2 = x^2 + y^2 + z^2 + R_T y z,   x = dL' / (k_L S_L), y = dC'/(k_C S_C), z = dH'/(k_H S_H)

with ``R_T = -sin(2 dtheta) R_C`` and ``R_C = 2 sqrt(C'^7 / (C'^7 + 25^7))``
in ``[0, 2)``, so ``|R_T| < 2`` and ``y^2 + z^2 + R_T y z >= (|y| - |z|)^2 >= 0``.
Hence ``dE00 >= |dL'| / S_L`` (``k_L = 1``, ``L' = L*``), and
``S_L = 1 + 0.015 (Lbar - 50)^2 / sqrt(20 + (Lbar - 50)^2)`` grows with
``|Lbar - 50|``: at most ``1 + 37.5 / sqrt(2520) = 1.74702...`` for ``L*`` in
``[0, 100]`` (:data:`S_L_MAX`).  The bound used is computed from the data's
own lightness range, so it stays valid a rounding error outside ``[0, 100]``.

This module is generic in the measure: :func:`closest_pair` takes the key and
a vectorised distance, so other pairwise measures (confusion, colour-vision
deficiency simulations followed by CIEDE2000) reuse it with their own key.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.metrics import delta_e_2000_lab

__all__ = [
    "PAIR_CHUNK",
    "S_L_MAX",
    "ClosestPair",
    "closest_pair",
    "closest_pair_brute_force",
    "closest_pair_delta_e_2000",
    "delta_e_2000_lightness_key",
    "iter_pairs",
    "lightness_weight_max",
    "pairs_below",
]

# Pairs evaluated per call of the distance: 2^16 pairs of Lab triples are a few
# MB of intermediates in colour-science's CIEDE2000, whatever the colour count.
PAIR_CHUNK = 1 << 16
# Sharma et al. 2005, eq. 15, at |Lbar - 50| = 50 (L* in [0, 100]).
S_L_MAX = 1.0 + 0.015 * 50.0**2 / math.sqrt(20.0 + 50.0**2)
# Relative slack on the pruning comparison: the bound is exact in real
# arithmetic; colour-science's float evaluation is good to ~1e-12 relative.
_PRUNE_SLACK = 1e-9

Distance = Callable[[NDArray[np.intp], NDArray[np.intp]], NDArray[np.float64]]


@dataclass(frozen=True)
class ClosestPair:
    """The closest pair ``first < second`` (indices into the input) and its distance."""

    first: int
    second: int
    distance: float


def lightness_weight_max(lightness: ArrayLike) -> float:
    """Largest CIEDE2000 ``S_L`` (Sharma et al. 2005, eq. 15) over these lightnesses.

    ``S_L`` depends on the mean lightness of a pair, which lies between the
    extremes, so the farthest lightness from 50 bounds it.

    >>> round(lightness_weight_max([0.0, 100.0]), 5)
    1.74702
    >>> lightness_weight_max([50.0])
    1.0
    """
    values = np.asarray(lightness, dtype=np.float64)
    if values.size == 0:
        return 1.0
    far = float(np.max(np.abs(values - 50.0)))
    return 1.0 + 0.015 * far**2 / math.sqrt(20.0 + far**2)


def delta_e_2000_lightness_key(lab: ArrayLike) -> NDArray[np.float64]:
    """The key ``L* / S_L,max`` with ``CIEDE2000(a, b) >= |key_a - key_b|``."""
    lab = np.asarray(lab, dtype=np.float64)
    return lab[..., 0] / lightness_weight_max(lab[..., 0])


def _better(value: float, pair: tuple[int, int], best: float, best_pair: tuple[int, int]) -> bool:
    """Smaller distance wins; at an exact tie the lexicographically first pair (as argmin)."""
    return value < best or (value == best and pair < best_pair)


def closest_pair(
    key: ArrayLike,
    distance: Distance,
    labels: ArrayLike | None = None,
    *,
    chunk: int = PAIR_CHUNK,
) -> ClosestPair | None:
    """Exact minimum of ``distance`` over pairs of items with different labels.

    ``key`` (shape ``(k,)``) must satisfy ``distance(a, b) >= |key[a] - key[b]|``;
    ``distance(i, j)`` takes index arrays and returns one value per pair.
    Pairs whose ``labels`` are equal are skipped (default: every pair counts).
    Ties go to the lexicographically smallest ``(first, second)``, as an
    ``argmin`` over ``triu_indices`` would.  Memory is ``O(k + chunk)``;
    ``None`` when no pair qualifies.

    >>> points = np.array([0.0, 10.0, 3.0, 11.5])
    >>> d = lambda i, j: np.abs(points[i] - points[j])
    >>> closest_pair(points, d)
    ClosestPair(first=1, second=3, distance=1.5)
    >>> closest_pair(points, d, labels=[0, 1, 0, 1])  # 0 and 2, 1 and 3 share a label
    ClosestPair(first=1, second=2, distance=7.0)
    """
    z = np.asarray(key, dtype=np.float64).reshape(-1)
    k = z.size
    lab = np.zeros(k, dtype=np.intp) if labels is None else np.asarray(labels).reshape(-1)
    if lab.size != k:
        raise ValueError(f"labels has {lab.size} entries for {k} keys")
    order = np.argsort(z, kind="stable")
    zs, ls = z[order], lab[order] if labels is not None else None
    best, best_pair = math.inf, (k, k)
    offset = 1
    while offset < k:
        # Offset 1 alone first, for a finite bound; then several offsets per
        # pass (one chunk of candidates at most) to spare per-call overhead.
        width = 1 if math.isinf(best) else max(1, min(k - offset, chunk // max(1, k - offset)))
        rows, gaps = [], []
        for d in range(offset, offset + width):
            i = np.arange(k - d)
            gap = zs[i + d] - zs[i]
            keep = gap <= best * (1.0 + _PRUNE_SLACK)
            if ls is not None:
                keep &= ls[i] != ls[i + d]
            rows.append(np.stack([i[keep], i[keep] + d]))
            gaps.append(gap)
        if not any(g.size and g.min() <= best * (1.0 + _PRUNE_SLACK) for g in gaps):
            break  # every pair at these offsets, and so at every larger one, is pruned
        pairs = np.concatenate(rows, axis=1)
        for start in range(0, pairs.shape[1], chunk):
            a = order[pairs[0, start : start + chunk]]
            b = order[pairs[1, start : start + chunk]]
            lo, hi = np.minimum(a, b), np.maximum(a, b)
            values = np.asarray(distance(lo, hi), dtype=np.float64)
            if values.size == 0:
                continue
            m = float(values.min())
            if m > best:
                continue
            # Among the tied minima, the lexicographically first pair.
            tied = np.flatnonzero(values == m)
            t = tied[np.lexsort((hi[tied], lo[tied]))[0]]
            pair = (int(lo[t]), int(hi[t]))
            if _better(m, pair, best, best_pair):
                best, best_pair = m, pair
        offset += width
    if best_pair[0] == k:
        return None
    return ClosestPair(best_pair[0], best_pair[1], best)


def pairs_below(
    key: ArrayLike,
    distance: Distance,
    level: float,
    labels: ArrayLike | None = None,
    *,
    chunk: int = PAIR_CHUNK,
) -> tuple[NDArray[np.intp], NDArray[np.intp], NDArray[np.float64]]:
    """Every pair ``first < second`` with different labels and ``distance < level``.

    The same sorted walk as :func:`closest_pair` with a fixed radius: only
    pairs whose keys are within ``level`` are evaluated, a chunk at a time.
    Returns index arrays and distances, sorted by ``(first, second)``.

    >>> points = np.array([0.0, 10.0, 3.0, 11.5])
    >>> first, second, d = pairs_below(points, lambda i, j: np.abs(points[i] - points[j]), 4.0)
    >>> first.tolist(), second.tolist(), d.tolist()
    ([0, 1], [2, 3], [3.0, 1.5])
    """
    z = np.asarray(key, dtype=np.float64).reshape(-1)
    k = z.size
    lab = None if labels is None else np.asarray(labels).reshape(-1)
    order = np.argsort(z, kind="stable")
    zs = z[order]
    radius = level * (1.0 + _PRUNE_SLACK)
    found_a: list[NDArray[np.intp]] = []
    found_b: list[NDArray[np.intp]] = []
    found_d: list[NDArray[np.float64]] = []
    waiting: list[tuple[NDArray[np.intp], NDArray[np.intp]]] = []  # pairs not yet measured
    held = 0

    def measure() -> None:
        # One distance call for the pairs of several offsets: a call costs more than a pair.
        lo = np.concatenate([w[0] for w in waiting])
        hi = np.concatenate([w[1] for w in waiting])
        waiting.clear()
        for start in range(0, lo.size, chunk):
            values = np.asarray(distance(lo[start : start + chunk], hi[start : start + chunk]))
            below = values < level
            found_a.append(lo[start : start + chunk][below])
            found_b.append(hi[start : start + chunk][below])
            found_d.append(values[below])

    for d in range(1, k):
        i = np.arange(k - d)
        near = zs[i + d] - zs[i] <= radius
        if not near.any():
            break  # keys only drift further apart at larger offsets
        a, b = order[i[near]], order[i[near] + d]
        if lab is not None:
            differ = lab[a] != lab[b]
            a, b = a[differ], b[differ]
        waiting.append((np.minimum(a, b), np.maximum(a, b)))
        held += a.size
        if held >= chunk:
            measure()
            held = 0
    if waiting:
        measure()
    if not found_a:
        empty = np.zeros(0, dtype=np.intp)
        return empty, empty, np.zeros(0)
    first, second = np.concatenate(found_a), np.concatenate(found_b)
    values = np.concatenate(found_d)
    order2 = np.lexsort((second, first))
    return first[order2], second[order2], values[order2]


def iter_pairs(
    k: int, labels: ArrayLike | None = None, *, chunk: int = PAIR_CHUNK
) -> Iterator[tuple[NDArray[np.intp], NDArray[np.intp]]]:
    """Every pair ``i < j`` of ``k`` items with different labels, in ``triu_indices`` order.

    Yields ``(first, second)`` index arrays of at most about ``chunk`` pairs,
    so that a brute-force pass over all pairs holds one chunk at a time.

    >>> [(a.tolist(), b.tolist()) for a, b in iter_pairs(3)]
    [([0, 0, 1], [1, 2, 2])]
    """
    lab = None if labels is None else np.asarray(labels).reshape(-1)
    rows = max(1, chunk // max(1, k))
    for a_start in range(0, k, rows):
        a = np.arange(a_start, min(k, a_start + rows))
        first = np.repeat(a, k)
        second = np.tile(np.arange(k), a.size)
        keep = second > first
        if lab is not None:
            keep &= lab[first] != lab[second]
        if keep.any():
            yield first[keep], second[keep]


def closest_pair_brute_force(
    distance: Distance,
    k: int,
    labels: ArrayLike | None = None,
    *,
    chunk: int = PAIR_CHUNK,
) -> ClosestPair | None:
    """Every pair, in chunks: the reference :func:`closest_pair` must agree with."""
    best, best_pair = math.inf, (k, k)
    for first, second in iter_pairs(k, labels, chunk=chunk):
        values = np.asarray(distance(first, second), dtype=np.float64)
        t = int(np.argmin(values))
        pair = (int(first[t]), int(second[t]))
        if _better(float(values[t]), pair, best, best_pair):
            best, best_pair = float(values[t]), pair
    if best_pair[0] == k:
        return None
    return ClosestPair(best_pair[0], best_pair[1], best)


def closest_pair_delta_e_2000(
    lab: ArrayLike, labels: ArrayLike | None = None, *, chunk: int = PAIR_CHUNK
) -> ClosestPair | None:
    """The closest pair of CIELAB colours ``(k, 3)`` under CIEDE2000, exactly.

    >>> lab = np.array([[50.0, 0, 0], [90.0, 0, 0], [52.0, 0, 0]])
    >>> pair = closest_pair_delta_e_2000(lab)
    >>> (pair.first, pair.second), round(pair.distance, 4)
    ((0, 2), 1.9935)
    """
    lab = np.asarray(lab, dtype=np.float64)

    def distance(i: NDArray[np.intp], j: NDArray[np.intp]) -> NDArray[np.float64]:
        return delta_e_2000_lab(lab[i], lab[j])

    return closest_pair(delta_e_2000_lightness_key(lab), distance, labels, chunk=chunk)
