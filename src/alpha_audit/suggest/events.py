"""Where, exactly, a coefficient sweep changes something: the event maths behind ``suggest``.

For a source ``s`` and canvas ``b`` in linear sRGB, each channel of the output
``clip(b + a (s - b), 0, 1)`` is linear in ``a`` until it reaches 0 or 1 and
constant after (paper, Section 3; for ``a >= 1`` each channel clips at most
once).  So, on ``[a_lo, a_hi]``:

* relative luminance is piecewise linear with at most three breakpoints, and a
  contrast condition "``C(Y, Yb) < L``" is an open band ``y_lo < Y < y_hi``
  whose crossings are closed-form on each piece (:func:`first_in_luminance_band`);
* an 8-bit code changes exactly where the linear channel crosses
  ``decode((n + 0.5) / 255)``, i.e. at ``a = (decode((n + 0.5)/255) - b) / (s - b)``;
  between consecutive events every code is constant and *at* an event the code
  is the even neighbour (``np.rint`` rounds half to even), see :func:`code_timelines`;
* CIEDE2000 has no closed form: :func:`first_below` brackets a crossing on a
  sampling grid and bisects it.

Everything is float64 and vectorised over leading axes; nothing here knows
about icons, themes or policies.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color import LUMINANCE_WEIGHTS, pack_8bit, srgb_decode, to_8bit

Floats = NDArray[np.float64]
Indices = NDArray[np.intp]

__all__ = [
    "BISECTION_TOLERANCE",
    "CODE_THRESHOLDS",
    "clip_breakpoints",
    "code_crossings",
    "code_timelines",
    "first_below",
    "first_in_luminance_band",
    "luminance_band",
    "luminance_band_pieces",
]

# Linear value at which the 8-bit code steps from n to n + 1 (n = 0..254): the
# encoded value is then exactly (n + 0.5) / 255 (CSS Color 4 transfer, x255).
CODE_THRESHOLDS: Floats = srgb_decode((np.arange(255, dtype=np.float64) + 0.5) / 255)
# The bar for crossings without a closed form (CIEDE2000).
BISECTION_TOLERANCE = 1e-9
# first_below samples each bracket at up to _MAX_REFINE inner points per call,
# and at most about _REFINE_POINTS points per call in all.
_MAX_REFINE = 15
_REFINE_POINTS = 4096


def clip_breakpoints(source: ArrayLike, background: ArrayLike) -> Floats:
    """Coefficient at which each channel of ``b + a (s - b)`` reaches 0 or 1.

    Channels are on the last axis; a channel with ``s == b`` never clips (``inf``).
    For ``s`` in [0, 1] the breakpoint is ``>= 1``.

    >>> clip_breakpoints([0.5, 0.25, 0.5], [0.0, 0.5, 0.5]).tolist()
    [2.0, 2.0, inf]
    """
    s = np.asarray(source, dtype=np.float64)
    b = np.asarray(background, dtype=np.float64)
    d = s - b
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # tiny d -> inf
        up = (1.0 - b) / d
        down = -b / d
    return np.where(d > 0, up, np.where(d < 0, down, np.inf))


def luminance_band(limit: ArrayLike, y_background: ArrayLike) -> tuple[Floats, Floats]:
    """The open band ``(y_lo, y_hi)`` of luminances whose contrast with ``Yb`` is below ``limit``.

    ``(max(Y, Yb) + 0.05) / (min(Y, Yb) + 0.05) < L`` holds exactly for
    ``(Yb + 0.05) / L - 0.05 < Y < L (Yb + 0.05) - 0.05`` (WCAG 2.2 contrast
    ratio); for ``L <= 1`` the band is empty (returned as ``(inf, -inf)``).

    >>> lo, hi = luminance_band(3.0, 1.0)
    >>> round(float(lo), 12), round(float(hi), 12)
    (0.3, 3.1)
    """
    limit = np.asarray(limit, dtype=np.float64)
    yb = np.asarray(y_background, dtype=np.float64)
    empty = limit <= 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        lo = (yb + 0.05) / limit - 0.05
    hi = limit * (yb + 0.05) - 0.05
    return np.where(empty, np.inf, lo), np.where(empty, -np.inf, hi)


def _luminance(channels: Floats) -> Floats:
    # Summed left to right, exactly as relative_luminance does.
    wr, wg, wb = LUMINANCE_WEIGHTS
    return wr * channels[..., 0] + wg * channels[..., 1] + wb * channels[..., 2]


def _broadcast_band(
    source: ArrayLike, background: ArrayLike, y_lo: ArrayLike, y_hi: ArrayLike
) -> tuple[
    Floats,
    Floats,
    Floats,
    Floats,
    tuple[int, ...],
]:
    s = np.asarray(source, dtype=np.float64)
    b = np.asarray(background, dtype=np.float64)
    s, b = np.broadcast_arrays(s, b)
    lo = np.asarray(y_lo, dtype=np.float64)
    hi = np.asarray(y_hi, dtype=np.float64)
    shape = np.broadcast_shapes(s.shape[:-1], lo.shape, hi.shape)
    s = np.broadcast_to(s, (*shape, 3))
    b = np.broadcast_to(b, (*shape, 3))
    return s, b, np.broadcast_to(lo, shape), np.broadcast_to(hi, shape), shape


def luminance_band_pieces(
    source: ArrayLike,
    background: ArrayLike,
    y_lo: ArrayLike,
    y_hi: ArrayLike,
    a_lo: float,
    a_hi: float,
) -> list[tuple[Floats, ...]]:
    """Where ``y_lo < Y(a) < y_hi`` on each linear piece of ``[a_lo, a_hi]``, exactly.

    Returns four ``(p, q, lower, upper)`` tuples, one per piece ``[p, q]``
    between consecutive clip breakpoints (a piece may be empty, ``p == q``):
    on it ``Y`` is linear and lies inside the open band exactly for ``a`` in
    the open interval ``(lower, upper)`` (``lower >= upper``: never).  So the
    set ``{a in [a_lo, a_hi] : Y(a) in band}`` is the union over pieces of
    ``(lower, upper)`` intersected with ``[p, q]``.  Shapes as in
    :func:`first_in_luminance_band`.

    >>> (p, q, lower, upper), *_ = luminance_band_pieces([0.5] * 3, [0.0] * 3, 0.0, 0.25, 0, 1)
    >>> float(p), float(q), float(lower), float(upper)  # Y(a) = a / 2 on [0, 1]
    (0.0, 1.0, 0.0, 0.5)
    """
    s, b, lo, hi, shape = _broadcast_band(source, background, y_lo, y_hi)
    d = s - b
    # Piece boundaries: a_lo, the (up to three) clip points inside, a_hi.
    inner = np.clip(clip_breakpoints(s, b), a_lo, a_hi)
    ends = np.concatenate(
        [np.full((*shape, 1), a_lo), np.sort(inner, axis=-1), np.full((*shape, 1), a_hi)],
        axis=-1,
    )
    pieces: list[tuple[Floats, ...]] = []
    for k in range(ends.shape[-1] - 1):  # four pieces, whatever the leading shape
        p, q = ends[..., k], ends[..., k + 1]
        mid = 0.5 * (p + q)
        raw = b + mid[..., np.newaxis] * d
        free = (raw > 0.0) & (raw < 1.0)
        # On this piece Y(a) = c0 + c1 a: free channels move, clipped ones are 0 or 1.
        c0 = _luminance(np.where(free, b, np.where(raw >= 1.0, 1.0, 0.0)))
        c1 = _luminance(np.where(free, d, 0.0))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            t_lo, t_hi = (lo - c0) / c1, (hi - c0) / c1
        flat_in = (lo < c0) & (c0 < hi)
        lower = np.where(c1 > 0, t_lo, np.where(c1 < 0, t_hi, np.where(flat_in, -np.inf, np.inf)))
        upper = np.where(c1 > 0, t_hi, np.where(c1 < 0, t_lo, np.where(flat_in, np.inf, -np.inf)))
        pieces.append((p, q, lower, upper))
    return pieces


def first_in_luminance_band(
    source: ArrayLike,
    background: ArrayLike,
    y_lo: ArrayLike,
    y_hi: ArrayLike,
    a_lo: float,
    a_hi: float,
    *,
    pieces: list[tuple[Floats, ...]] | None = None,
) -> tuple[Floats, NDArray[np.bool_]]:
    """Infimum of ``{a in [a_lo, a_hi] : y_lo < Y(a) < y_hi}`` and whether it is attained.

    ``Y(a)`` is the relative luminance of ``clip(b + a (s - b))``; ``source`` and
    ``background`` broadcast with channels last, the bands over the leading
    shape.  The infimum is ``nan`` when the set is empty.  Because the band is
    open and ``Y`` continuous, the set is open in ``[a_lo, a_hi]`` and its
    infimum is attained only at ``a_lo`` itself.  ``pieces``: what
    :func:`luminance_band_pieces` gives for the same arguments, if the caller has it.

    >>> # Paper, Section 4: sRGB (0, 0, 0.8125) on yellow loses contrast as soon as a > 1.
    >>> from alpha_audit.color import contrast_ratio, relative_luminance, srgb_decode
    >>> s, b = srgb_decode([0, 0, 0.8125]), np.array([1.0, 1.0, 0.0])
    >>> lo, hi = luminance_band(contrast_ratio(s, b) - 1e-10, relative_luminance(b))
    >>> start, attained = first_in_luminance_band(s, b, lo, hi, 1.0, 2.0)
    >>> round(float(start), 6), bool(attained)
    (1.0, False)
    """
    s, b, lo, hi, shape = _broadcast_band(source, background, y_lo, y_hi)
    d = s - b
    if pieces is None:
        pieces = luminance_band_pieces(s, b, lo, hi, a_lo, a_hi)
    start = np.full(shape, np.inf)
    for p, q, lower, upper in pieces:
        hit = (q > p) & (lower < q) & (upper > p) & (lower < upper)
        start = np.where(hit, np.minimum(start, np.maximum(lower, p)), start)

    y0 = _luminance(np.clip(b + a_lo * d, 0.0, 1.0))
    at_lo = (lo < y0) & (y0 < hi)
    start = np.where(at_lo, a_lo, start)
    return np.where(np.isinf(start), np.nan, start), at_lo


def code_crossings(source: ArrayLike, background: ArrayLike, opacity: ArrayLike = 1.0) -> Floats:
    """Coefficients at which a channel's displayed value crosses each code threshold.

    The displayed channel is ``b + o (clip(b + a (s - b)) - b)`` (a paint at
    opacity ``o``, :func:`~alpha_audit.color.composite.composite_coverage`):
    linear in ``a`` with slope ``o (s - b)`` until the raw value clips, then
    constant.  Returns shape ``(..., 255)`` for scalar channels (any matching
    shape): entry ``n`` is ``(decode((n + 0.5)/255) - b) / (o (s - b))``;
    ``nan`` where the channel never moves (``s == b`` or ``o == 0``), ``inf``
    for a threshold the channel never reaches because it clips (or saturates
    at ``b + o (1 - b)`` / ``(1 - o) b``) first.

    >>> a = code_crossings(0.5, 0.0)
    >>> bool(np.all(np.diff(a) > 0))
    True
    """
    s = np.asarray(source, dtype=np.float64)[..., np.newaxis]
    b = np.asarray(background, dtype=np.float64)[..., np.newaxis]
    o = np.asarray(opacity, dtype=np.float64)[..., np.newaxis]
    d = o * (s - b)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # subnormal d -> inf
        at = np.where(d != 0, (CODE_THRESHOLDS - b) / d, np.nan)
        # Past the clip point the channel stops: thresholds beyond it are never crossed.
        clip = np.where(s > b, (1.0 - b) / (s - b), np.where(s < b, -b / (s - b), np.inf))
    return np.where(np.isfinite(at) & (at > clip), np.inf, at)


def code_timelines(
    sources: ArrayLike, background: ArrayLike, a_lo: float, a_hi: float, opacities: ArrayLike = 1.0
) -> list[tuple[Floats, NDArray[np.int64]]]:
    """Exact 8-bit colours of many paints along ``[a_lo, a_hi]``, each as it ships.

    ``sources`` are linear colours ``(P, 3)`` on ``background`` ``(3,)`` (or one
    each, ``(P, 3)``), at ``opacities`` ``(P,)``; each channel shows
    ``b + o (clip(b + a (s - b)) - b)``.
    Returns, per paint, its sorted event points (every :func:`code_crossings`
    inside, with ``a_lo`` and ``a_hi``) and the packed 8-bit colour
    (:func:`~alpha_audit.color.pack_8bit`) of its elements in order: point,
    gap, point, ..., ``2K + 1`` for ``K + 1`` points.  Channel codes are
    monotone step functions of ``a`` that change only at crossings, so on a gap
    every code is constant; at an event the encoded value is exactly half-way
    and the code is the even neighbour, as ``np.rint``.  Crossings are counted
    (one sort per paint row, all paints at once), never searched.

    >>> points, codes = code_timelines([[0.5, 0.0, 0.0]], [0.0] * 3, 1.0, 1.02)[0]
    >>> [round(a, 6) for a in points.tolist()], [f"{c:06x}" for c in codes.tolist()]
    ([1.0, 1.011757, 1.02], ['bc0000', 'bc0000', 'bc0000', 'bd0000', 'bd0000'])
    """
    s = np.asarray(sources, dtype=np.float64).reshape(-1, 3)
    b = np.broadcast_to(np.asarray(background, dtype=np.float64), s.shape)
    o = np.broadcast_to(np.asarray(opacities, dtype=np.float64).reshape(-1), (s.shape[0],))
    out: list[tuple[Floats, NDArray[np.int64]]] = []
    for first in range(0, s.shape[0], _TIMELINE_CHUNK):
        chunk = slice(first, first + _TIMELINE_CHUNK)
        out += _timelines(s[chunk], b[chunk], a_lo, a_hi, o[chunk])
    return out


_TIMELINE_CHUNK = 256  # paints a sort holds at once (~6 MB of counts)


def _timelines(
    s: Floats, b: Floats, a_lo: float, a_hi: float, o: Floats
) -> list[tuple[Floats, NDArray[np.int64]]]:
    n = s.shape[0]
    o = o[:, np.newaxis]
    crossings = code_crossings(s, b, o)  # (n, 3, 255)
    d = o * (s - b)  # (n, 3)
    inside = (crossings >= a_lo) & (crossings <= a_hi)
    with np.errstate(invalid="ignore"):
        below = np.sum(crossings < a_lo, axis=2)  # (n, 3)
        above = np.sum(crossings > a_hi, axis=2)
    # Every crossing inside and both ends, one row per paint, sorted with its channel
    # (3 for an end): equal values sit together, so counts up to a value's last copy
    # are the crossings at or before it.
    values = np.concatenate(
        [np.where(inside, crossings, np.inf).reshape(n, -1), np.full((n, 2), [a_lo, a_hi])],
        axis=1,
    )
    channel = np.concatenate([np.repeat(np.arange(3), 255), [3, 3]])
    order = np.argsort(values, axis=1, kind="stable")
    values = np.take_along_axis(values, order, axis=1)
    counts = np.cumsum(channel[order][..., np.newaxis] == np.arange(3), axis=1)  # (n, E, 3)
    finite = np.isfinite(values)
    first = finite & np.concatenate([np.ones((n, 1), bool), values[:, 1:] != values[:, :-1]], 1)
    last = finite & np.concatenate([values[:, :-1] != values[:, 1:], np.ones((n, 1), bool)], 1)
    # Each point's paint and its first and last copy, in row-major order (by paint, then
    # value): M points in all, K_p + 1 for paint p.
    row, at_last = np.nonzero(last)
    _, at_first = np.nonzero(first)
    upto = counts[row, at_last]  # (M, 3): crossings at or before each point
    events = upto - np.where((at_first > 0)[:, None], counts[row, np.maximum(at_first - 1, 0)], 0)
    sizes = last.sum(axis=1)
    ends = np.cumsum(sizes) - 1  # each paint's last point
    total = upto[ends][row]
    rising, falling = (d > 0)[row], (d < 0)[row]
    lo_k, hi_k = below[row], above[row]
    strictly_before = np.where(rising, lo_k + upto - events, hi_k + total - upto)
    between = np.where(rising, lo_k + upto, hi_k + total - upto)  # the gap after each point
    at_points = np.where(events > 0, strictly_before + strictly_before % 2, strictly_before)
    moves = rising | falling
    still = to_8bit(b).astype(np.int64)[row]
    elements = np.stack(
        [
            pack_8bit(np.where(moves, at_points, still)),
            pack_8bit(np.where(moves, between, still)),
        ],
        axis=1,
    ).reshape(-1)
    keep = np.ones(elements.size, dtype=bool)
    keep[2 * ends + 1] = False  # no gap after a paint's last point
    codes = np.split(elements[keep], np.cumsum(2 * sizes - 1)[:-1])
    points = np.split(values[row, at_first], np.cumsum(sizes)[:-1])
    return list(zip(points, codes, strict=True))


def _pick(values: Floats, index: Indices) -> Floats:
    """``values[..., index]`` item by item (one index per item)."""
    return np.take_along_axis(values, index[..., np.newaxis], axis=-1)[..., 0]


def first_below(
    func: Callable[[Floats], Floats],
    grid: ArrayLike,
    level: ArrayLike,
    *,
    tolerance: float = BISECTION_TOLERANCE,
) -> tuple[Floats, Floats]:
    """First ``a`` on ``grid`` where ``func(a) < level``, refined to ``tolerance``.

    ``func`` maps coefficients of shape ``(N,)`` -- or ``(..., K)``, K points
    per item -- to values of shape ``(..., N)`` (resp. ``(..., K)``).  Returns
    ``(safe, unsafe)`` of shape ``(...)``: the last coefficient known not to be
    below ``level`` and the first known to be, at most ``tolerance`` apart;
    both ``nan`` where nothing on the grid is below, and both ``grid[0]`` when
    the first grid point already is.  A dip narrower than the grid spacing can
    be missed: CIEDE2000 has no closed form, so this brackets, it is not exact.

    Each refinement step samples every bracket at ``K`` inner points at once
    and keeps the first sub-interval that crosses: with few items ``K`` is up
    to 15, so a 1e-3 bracket needs 5 calls of ``func`` instead of bisection's
    20 (each call of colour-science costs far more than its arithmetic); with
    many items ``K`` falls to 1, plain bisection, bounding the points per call.

    >>> f = lambda a: 2.0 - np.broadcast_to(a, (1, np.shape(a)[-1]))
    >>> safe, unsafe = first_below(f, np.linspace(0, 2, 21), 0.5)
    >>> abs(float(unsafe[0]) - 1.5) < 1e-9 and float(safe[0]) <= 1.5
    True
    """
    a = np.asarray(grid, dtype=np.float64)
    values = np.asarray(func(a), dtype=np.float64)
    level = np.broadcast_to(np.asarray(level, dtype=np.float64), values.shape[:-1])
    below = values < level[..., np.newaxis]
    found = below.any(axis=-1)
    first = np.argmax(below, axis=-1)
    hi = np.where(found, a[first], np.nan)
    lo = np.where(found, a[np.maximum(first - 1, 0)], np.nan)
    todo = np.isfinite(lo) & (lo < hi)
    k = int(np.clip(_REFINE_POINTS // max(1, int(np.count_nonzero(todo))), 1, _MAX_REFINE))
    steps = np.arange(1, k + 1, dtype=np.float64) / (k + 1)
    while np.any(todo & (hi - lo > tolerance)):
        width = np.where(todo, hi - lo, 0.0)
        inner = np.where(todo, lo, a[0])[..., np.newaxis] + width[..., np.newaxis] * steps
        is_below = np.asarray(func(inner), dtype=np.float64) < level[..., np.newaxis]
        crossed = is_below.any(axis=-1)
        at = np.argmax(is_below, axis=-1)  # the first inner point below, where one is
        new_hi = np.where(crossed, _pick(inner, at), hi)
        new_lo = np.where(
            crossed, np.where(at > 0, _pick(inner, np.maximum(at - 1, 0)), lo), inner[..., -1]
        )
        hi, lo = np.where(todo, new_hi, hi), np.where(todo, new_lo, lo)
        todo = todo & (hi - lo > tolerance)
    return lo, hi
