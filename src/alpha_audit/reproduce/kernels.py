"""Fast exact kernels for the paper's source-grid experiments.

Every experiment enumerates a *product* source grid: the same ``C`` encoded
levels on each channel, so ``C**3`` sources.  With a background and a
coefficient fixed, a clipped output channel depends only on the source level
of that channel, so three ``C``-entry tables replace the per-combination power
function, and relative luminance is

    Y = (0.2126 T_R[r] + 0.7152 T_G[g]) + 0.0722 T_B[b] = P[r, g] + Q[b]

summed in the same order as :func:`alpha_audit.color.relative_luminance`, so
it is bit-identical to the straightforward computation.  A *problem* below is
one (canvas, coefficient) pair; a *row* is one ``(r, g)``; a *column* one ``b``.

For ``alpha >= 0`` the tables rise with the level, so along a row ``Y`` is
monotone in ``b`` and every contrast predicate of the form "on the far side of
a threshold" holds on an interval of ``b``.  Its end points come from a
vectorised bisection that evaluates the *exact* float expression of the
straightforward implementation, so counts are identical to it, not merely
close.  Sums of contrast ratios split at the background's luminance: above
it the ratio is linear in ``Y`` (suffix sums), below it ``(Yb + .05)/(Y + .05)``
is summed with a convergent series in precomputed power moments of ``Q``.

Increase and decrease need the sign of ``CR(Yo) - CR(Ys)``.  Where source and
output lie on the same side of ``Yb`` the sign is that of ``Yo - Ys``
(reversed below ``Yb``), i.e. of ``(Po - Ps) + (Qo[b] - Qs[b])``: one threshold
per row against one sorted array per problem, counted with a 2-D rank table.
Combinations on opposite sides, and the rare ones within ``_BAND`` of a tie,
are evaluated one by one with the straightforward float expression.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import LUMINANCE_WEIGHTS, contrast_from_luminance

Floats = NDArray[np.float64]
Indices = NDArray[np.intp]

__all__ = [
    "ChangeCounts",
    "change_counts",
    "change_counts_any_order",
    "channel_tables",
    "contrast_sums",
    "first_at_or_above",
    "luminance_parts",
    "reach_thresholds",
]

_WR, _WG, _WB = LUMINANCE_WEIGHTS
# Luminance gap outside which the float sign of CR(Yo) - CR(Ys) is certain and
# its magnitude exceeds CONTRAST_TOLERANCE: |dCR| >= |Yo - Ys| / 1.05 for both
# sides of Yb, and float rounding of Y is below 1e-15.
_BAND = 1e-7
# Terms of the reciprocal series: |Q - q0| / (P + .05 + q0) <= 0.0361 / 0.0861
# = 0.42 (the blue weight bounds the spread of Q), and 0.42**48 < 1e-17.
_SERIES_TERMS = 48
# Rows per block: larger temporaries fall out of cache, which costs more than
# the per-call overhead saved (measured on the 2-core reference machine).
_BLOCK = 32768


def channel_tables(levels: Floats, backgrounds: Floats, alphas: Floats) -> Floats:
    """Clipped output per (problem, channel, level): shape ``(m, 3, C)``.

    ``levels`` are the linear source levels (C,), ``backgrounds`` (m, 3) and
    ``alphas`` (m,) one per problem.  Same expression as ``composite_extended``.
    """
    b = backgrounds[:, :, np.newaxis]
    a = alphas[:, np.newaxis, np.newaxis]
    return np.clip(b + a * (levels[np.newaxis, np.newaxis, :] - b), 0.0, 1.0)


def luminance_parts(tables: Floats) -> tuple[Floats, Floats]:
    """``(P, Q)``: ``P[m, r*C + g] = wr T_R[r] + wg T_G[g]`` and ``Q[m, b] = wb T_B[b]``."""
    red = _WR * tables[:, 0, :]
    green = _WG * tables[:, 1, :]
    p = (red[:, :, np.newaxis] + green[:, np.newaxis, :]).reshape(tables.shape[0], -1)
    return p, _WB * tables[:, 2, :]


def _take(table: Floats, cols: Indices) -> Floats:
    """``table[i, cols[i, r]]`` for a (m, n) table and (m, R) column indices."""
    offsets = (np.arange(table.shape[0]) * table.shape[1])[:, np.newaxis]
    # np.take: n-d fancy indexing is several times slower for the same gather.
    gathered: Floats = np.take(table.ravel(), cols + offsets)
    return gathered


def _bsearch(table: Floats, p: Floats | None, theta: Floats, *, strict: bool) -> Indices:
    """Per row, the first column ``c`` with ``fl(p + table[c]) >= theta`` (``>`` if strict).

    ``table`` (m, C) is non-decreasing per problem, ``p`` and ``theta`` are
    (m, R) or broadcast to it (``p=None`` searches ``table`` itself, i.e.
    ``np.searchsorted``).  A branchless binary search: the table is padded
    with ``inf`` to a power of two so no step needs clamping, ``found`` counts
    the leading columns that fail, and the search runs on flat indices.
    """
    m, n_cols = table.shape
    width = 1 << n_cols.bit_length()
    padded = np.full((m, width), np.inf)
    padded[:, :n_cols] = table
    flat = padded.ravel()
    shape = np.broadcast_shapes(theta.shape, (m, 1) if p is None else p.shape)
    start = (np.arange(m) * width)[:, np.newaxis]
    found = np.broadcast_to(start, shape).copy()
    fails = np.less_equal if strict else np.less
    step = width >> 1
    while step:
        value = np.take(flat, found + (step - 1))
        if p is not None:
            value += p
        found += fails(value, theta) * step
        step >>= 1
    found -= start
    return found


def first_at_or_above(p: Floats, q: Floats, theta: Floats) -> Indices:
    """Per row, the first column where ``fl(P + Q[b]) >= theta`` (Q ascending per problem)."""
    return _bsearch(q, p, theta[:, np.newaxis], strict=False)


@dataclass(frozen=True)
class _SumTables:
    """Per-problem column data for :func:`contrast_sums` (see the module docstring)."""

    q: Floats  # (m, C) ascending
    suffix: Floats  # (m, C + 1): sum of q[b] for b >= k
    moments: Floats  # (N, m, C + 1): sum over b < k of (q0 - q[b])**n
    q0: Floats  # (m, 1)
    yb: Floats  # (m,)


def _sum_tables(q: Floats, yb: Floats) -> _SumTables:
    q = np.sort(q, axis=1)
    m, n_cols = q.shape
    suffix = np.zeros((m, n_cols + 1))
    suffix[:, :-1] = np.cumsum(q[:, ::-1], axis=1)[:, ::-1]
    q0 = 0.5 * (q[:, :1] + q[:, -1:])
    minus_d = q0 - q
    moments = np.zeros((_SERIES_TERMS, m, n_cols + 1))
    power = np.ones_like(q)
    for n in range(_SERIES_TERMS):
        np.cumsum(power, axis=1, out=moments[n, :, 1:])
        power = power * minus_d
    return _SumTables(q, suffix, moments, q0, yb)


def _sum_rows(t: _SumTables, problems: slice, p: Floats) -> Floats:
    """Per problem of ``problems``, the sum of CR over the rows ``p`` and all columns."""
    q, yb = t.q[problems], t.yb[problems]
    n_cols = q.shape[1]
    k = first_at_or_above(p, q, yb)
    cb = yb + 0.05
    linear = ((n_cols - k) * (p + 0.05) + _take(t.suffix[problems], k)) / cb[:, np.newaxis]
    # Below Yb: cb * sum_{b<k} 1 / (u + d_b) with u = P + .05 + q0, d = Q - q0,
    # expanded as sum_n (-d)^n / u^(n+1) with prefix moments of (-d)^n (Horner
    # in 1/u), over the rows that have columns below Yb at all.
    u = p + 0.05 + t.q0[problems]
    flat_k = k + (np.arange(q.shape[0]) * (n_cols + 1))[:, np.newaxis]
    weight = np.broadcast_to(cb[:, np.newaxis], k.shape)
    below = k > 0
    if not below.any():
        only_linear: Floats = linear.sum(axis=1)
        return only_linear
    u, flat_k, weight = u[below], flat_k[below], weight[below]
    spread = float(np.max(np.abs(t.q0[problems] - q)))
    ratio = spread / float(u.min())
    terms = (
        _SERIES_TERMS
        if ratio >= 0.42
        else int(np.clip(np.ceil(-39.2 / np.log(max(ratio, 1e-300))), 1, _SERIES_TERMS))
    )
    v = 1.0 / u
    moments = t.moments[:, problems]
    series = np.take(moments[terms - 1].ravel(), flat_k)
    for n in range(terms - 2, -1, -1):
        series *= v
        series += np.take(moments[n].ravel(), flat_k)
    series *= v * weight
    reciprocal = np.zeros(k.shape)
    reciprocal[below] = series  # summed pairwise per problem, like the straightforward sum
    sums: Floats = linear.sum(axis=1) + reciprocal.sum(axis=1)
    return sums


def contrast_sums(p: Floats, q: Floats, yb: Floats) -> Floats:
    """Per problem, the sum over rows and columns of ``CR(P + Q[b], Yb)``.

    ``p`` (m, R), ``q`` (m, C) in any order (the sum does not depend on it),
    ``yb`` (m,).  Agrees with the straightforward float sum to about 1e-15
    relative.
    """
    tables = _sum_tables(q, yb)
    return _over_blocks(p.shape, lambda pr, rows: _sum_rows(tables, pr, p[pr, rows]))


def _float_bits(x: Floats) -> NDArray[np.int64]:
    return np.asarray(x, dtype=np.float64).view(np.int64)


def _smallest_float(
    predicate: Callable[[Floats], NDArray[np.bool_]], lo: Floats, hi: Floats
) -> Floats:
    """Per problem, the smallest float in ``[lo, hi]`` (>= 0) where a monotone predicate holds.

    Bisects on the bit patterns, which order non-negative floats; ``inf`` where
    the predicate fails even at ``hi``.
    """
    lo_bits = _float_bits(lo).copy()
    hi_bits = _float_bits(hi).copy()
    holds_hi = predicate(hi)
    while np.any(lo_bits < hi_bits):
        mid = lo_bits + (hi_bits - lo_bits) // 2
        holds = predicate(mid.view(np.float64))
        hi_bits = np.where(holds, mid, hi_bits)
        lo_bits = np.where(holds, lo_bits, mid + 1)
    return np.where(holds_hi, hi_bits.view(np.float64), np.inf)


def _luminance_band(
    yb: Floats, inside: Callable[[Floats], NDArray[np.bool_]]
) -> tuple[Floats, Floats]:
    """Luminances ``(low, high)``: ``inside(CR(Y, Yb))`` holds exactly when ``low <= Y < high``.

    Found on the float expression itself, so a luminance comparison decides
    as computing the contrast ratio would.
    """
    yb = np.asarray(yb, dtype=np.float64)
    low = _smallest_float(
        lambda y: (y >= yb) | inside(contrast_from_luminance(y, yb)), np.zeros_like(yb), yb
    )
    high = _smallest_float(
        lambda y: (y >= yb) & ~inside(contrast_from_luminance(y, yb)), yb, np.full_like(yb, 4.0)
    )
    return low, high


def reach_thresholds(yb: Floats, threshold: float) -> tuple[Floats, Floats]:
    """Luminances ``(low, high)``: ``CR(Y, Yb) < threshold`` exactly when ``low <= Y < high``."""
    return _luminance_band(yb, lambda cr: cr < threshold)


@dataclass(frozen=True)
class ChangeCounts:
    """Per-problem counts of contrast increases, decreases and newly reaching a threshold."""

    increase: NDArray[np.int64]
    decrease: NDArray[np.int64]
    newly_reach: NDArray[np.int64]
    exact_evaluations: int


def _rank_table(dq: Floats) -> tuple[Floats, Indices]:
    """Sorted ``dq`` and ``G[m, k, j] = #{b >= k : rank(b) >= j}``."""
    m, n_cols = dq.shape
    order = np.argsort(dq, axis=1, kind="stable")
    rank = np.empty_like(order)
    np.put_along_axis(rank, order, np.arange(n_cols)[np.newaxis, :], axis=1)
    marks = np.zeros((m, n_cols + 1, n_cols + 1), dtype=np.int32)
    problem = np.repeat(np.arange(m), n_cols)
    marks[problem, np.tile(np.arange(n_cols), m), rank.ravel()] = 1
    counts = np.cumsum(marks[:, ::-1, :], axis=1)[:, ::-1, :]
    counts = np.cumsum(counts[:, :, ::-1], axis=2)[:, :, ::-1]
    return np.take_along_axis(dq, order, axis=1), counts


def _searchsorted(sorted_rows: Floats, values: Floats, side: str) -> Indices:
    """``np.searchsorted`` per problem: (m, C) ascending rows, (m, R) values."""
    return _bsearch(sorted_rows, None, values, strict=side == "right")


def _exact_changes(
    ps: Floats,
    qs: Floats,
    po: Floats,
    qo: Floats,
    yb: Floats,
    tol: float,
    problem: Indices,
    row: Indices,
    col: Indices,
) -> tuple[Indices, Indices]:
    """Per-problem (increase, decrease) counts of listed combinations, straightforward floats."""
    y_b = yb[problem]
    cr_s = contrast_from_luminance(ps[problem, row] + qs[problem, col], y_b)
    cr_o = contrast_from_luminance(po[problem, row] + qo[problem, col], y_b)
    change = cr_o - cr_s
    m = ps.shape[0]
    inc = np.bincount(problem[change > tol], minlength=m)
    dec = np.bincount(problem[change < -tol], minlength=m)
    return inc, dec


def _count_rows(
    ps: Floats,
    qs: Floats,
    po: Floats,
    qo: Floats,
    yb: Floats,
    rank_tables: list[tuple[Floats, Indices]],
    thresholds: tuple[Floats, ...],
    quiet: NDArray[np.bool_],
    tol: float,
) -> NDArray[np.int64]:
    """(4, A, m) counts for a block of rows: increase, decrease, newly reach, exact evaluations.

    ``ps`` (m, R) and ``qs`` (m, C) are the source parts of m canvases, ``po``
    (A, m, R) and ``qo`` (A, m, C) the outputs at A coefficients; ``quiet``
    (A, m) marks problems proven to have no change beyond ``tol``.

    Along a row the columns split into: both below Yb ``[0, lo)``; output
    exactly at Yb ``[ko, ko_eq)`` (contrast 1, so a decrease exactly when
    the source's contrast exceeds a threshold: luminance thresholds ``keep``);
    both above ``[hi, C)``; and at most one run on opposite sides, evaluated
    one by one.  Rows with a near-tie in a same-side part are evaluated whole.
    """
    m, n_cols = qs.shape
    low, high, keep_low, keep_high = thresholds
    reach = bool(np.isfinite(low).all())  # no threshold: low is +inf
    ks = first_at_or_above(ps, qs, yb)
    if reach:
        s1, s2 = first_at_or_above(ps, qs, low), first_at_or_above(ps, qs, high)
    keep: tuple[Indices, Indices] | None = None  # searched once some output sits at Yb
    above_yb = np.nextafter(yb, np.inf)
    side = n_cols + 1
    base = (np.arange(m) * side * side)[:, np.newaxis]
    result = np.zeros((4, po.shape[0], m), dtype=np.int64)
    for i, (po_a, qo_a, (sorted_dq, ranks)) in enumerate(zip(po, qo, rank_tables, strict=True)):
        if reach:
            o1, o2 = first_at_or_above(po_a, qo_a, low), first_at_or_above(po_a, qo_a, high)
            overlap = np.maximum(0, np.minimum(s2, o2) - np.maximum(s1, o1))
            result[2, i] = ((s2 - s1) - overlap).sum(axis=1)
        if quiet[i].all():
            continue
        ko = first_at_or_above(po_a, qo_a, yb)
        # Outputs exactly at Yb are rare except at alpha 0: search only rows with one.
        at_yb = (po_a + _take(qo_a, np.minimum(ko, n_cols - 1)) == yb[:, np.newaxis]) & (
            ko < n_cols
        )
        ko_eq = ko.copy()
        if at_yb.any():
            ko_eq[at_yb] = first_at_or_above(po_a, qo_a, above_yb)[at_yb]
            if keep is None:
                keep = first_at_or_above(ps, qs, keep_low), first_at_or_above(ps, qs, keep_high)
        lo = np.minimum(ks, ko)
        hi = np.maximum(ks, ko_eq)
        dp = po_a - ps
        j_hi = _searchsorted(sorted_dq, -dp + _BAND, "right")  # rank >= j_hi: dq > t
        j_lo = _searchsorted(sorted_dq, -dp - _BAND, "left")  # rank < j_lo: dq < t
        inc_below, dec_below, inc_above, dec_above = _same_side(
            ranks.ravel(), base, side, (lo, hi), (j_lo, j_hi), n_cols
        )
        # Output exactly at Yb: contrast 1, never an increase.
        dec_equal: int | Indices = 0
        if keep is not None:
            sk1, sk2 = keep
            dec_equal = np.maximum(0, np.minimum(ko_eq, sk1) - ko) + np.maximum(
                0, ko_eq - np.maximum(ko, sk2)
            )
        uncertain = (lo - inc_below - dec_below) + (n_cols - hi - inc_above - dec_above)
        tied = (uncertain > 0) & ~quiet[i][:, np.newaxis]
        fast = ~tied & ~quiet[i][:, np.newaxis]
        inc = np.where(fast, inc_below + inc_above, 0).sum(axis=1)
        dec = np.where(fast, dec_below + dec_above + dec_equal, 0).sum(axis=1)
        problem, row, col = _opposite_side(ks, ko, ko_eq, tied, fast, n_cols)
        exact_inc, exact_dec = _exact_changes(ps, qs, po_a, qo_a, yb, tol, problem, row, col)
        result[0, i] = inc + exact_inc
        result[1, i] = dec + exact_dec
        result[3, i] = np.bincount(problem, minlength=m)
    return result


def _same_side(
    flat: Indices,
    base: NDArray[np.int64],
    side: int,
    lo_hi: tuple[Indices, Indices],
    j_lo_hi: tuple[Indices, Indices],
    n_cols: int,
) -> tuple[Indices, ...]:
    """Increases and decreases read off the rank tables ``flat`` where source and
    output lie on one side of Yb: (below increase, below decrease, above increase,
    above decrease), each (m, R); columns within the tie band are left uncounted."""
    (lo, hi), (j_lo, j_hi) = lo_hi, j_lo_hi
    lo_row, hi_row = base + lo * side, base + hi * side
    # Both below Yb: a lower output luminance raises the contrast.
    inc_below = lo - (np.take(flat, base + j_lo) - np.take(flat, lo_row + j_lo))
    dec_below = np.take(flat, base + j_hi) - np.take(flat, lo_row + j_hi)
    # Both above Yb: a higher output luminance raises it.
    inc_above = np.take(flat, hi_row + j_hi)
    dec_above = (n_cols - hi) - np.take(flat, hi_row + j_lo)
    return inc_below, dec_below, inc_above, dec_above


def _opposite_side(
    ks: Indices,
    ko: Indices,
    ko_eq: Indices,
    tied: NDArray[np.bool_],
    fast: NDArray[np.bool_],
    n_cols: int,
) -> tuple[Indices, Indices, Indices]:
    """The (problem, row, column) combinations to evaluate one by one: those with
    source and output on opposite sides of Yb, and every column of a tied row."""
    m, n_rows = ks.shape
    opposite = ks < ko
    start = np.where(opposite, ks, ko_eq)
    stop = np.where(opposite, ko, ks)
    start = np.where(tied, 0, start).ravel()
    width = np.where(tied, n_cols, np.where(fast, stop, 0)).ravel() - start
    some = width > 0
    problem = np.repeat(np.arange(m), n_rows)[some]
    row = np.tile(np.arange(n_rows), m)[some]
    start, width = start[some], width[some]
    offsets = np.repeat(np.cumsum(width) - width, width)
    col = np.repeat(start, width) + (np.arange(width.sum()) - offsets)
    return np.repeat(problem, width), np.repeat(row, width), col


def _keep_thresholds(yb: Floats, tol: float) -> tuple[Floats, Floats]:
    """Luminances ``(low, high)``: ``1 - CR(Y, Yb) < -tol`` iff ``Y < low`` or ``Y >= high``.

    The decision for an output exactly at ``Yb`` (contrast 1), on the float
    expression of the straightforward implementation.
    """
    return _luminance_band(yb, lambda cr: 1.0 - cr >= -tol)


# |dCR/dY| <= (Yb + .05) / .05**2 <= 420 for luminances in [0, 1]: a change in
# luminance below tol / 420 cannot move the contrast ratio by tol.
_CR_LIPSCHITZ = 420.0


def change_counts(
    ps: Floats,
    qs: Floats,
    po: Floats,
    qo: Floats,
    yb: Floats,
    *,
    tol: float,
    threshold: float | None,
) -> ChangeCounts:
    """Exact counts of contrast changes between source and output, per (alpha, canvas).

    ``ps`` (m, R) and ``qs`` (m, C) are the source luminance parts on m
    canvases with luminances ``yb`` (m,); ``po`` (A, m, R) and ``qo`` (A, m, C)
    the output parts at A coefficients.  ``qs`` and ``qo`` must be
    non-decreasing in the column (true for ``alpha >= 0``).  A change
    ``CR(Yo) - CR(Ys)`` above ``tol`` is an increase, below ``-tol`` a
    decrease; ``newly_reach`` counts ``CR(Ys) < threshold <= CR(Yo)`` (zero
    without a threshold, which saves two searches per coefficient).
    Arrays in the result have shape (A, m).
    """
    if tol > 1e-8:
        raise ValueError("the tie band assumes a contrast tolerance of at most 1e-8")
    rank_tables = [_rank_table(qo_a - qs) for qo_a in qo]
    never = (np.full_like(yb, np.inf), np.full_like(yb, np.inf))
    reach = never if threshold is None else reach_thresholds(yb, threshold)
    thresholds = (*reach, *_keep_thresholds(yb, tol))
    # Problems whose outputs are within rounding of their sources (alpha = 1):
    # every change is provably within tol, so none is counted.
    spread = np.abs(po - ps).max(axis=2) + np.abs(qo - qs).max(axis=2) + 1e-15
    quiet = _CR_LIPSCHITZ * spread + 1e-13 < tol

    def block(pr: slice, rows: slice) -> NDArray[np.int64]:
        ranks = [(sorted_dq[pr], table[pr]) for sorted_dq, table in rank_tables]
        return _count_rows(
            ps[pr, rows],
            qs[pr],
            po[:, pr, rows],
            qo[:, pr],
            yb[pr],
            ranks,
            tuple(t[pr] for t in thresholds),
            quiet[:, pr],
            tol,
        )

    totals = _over_blocks(ps.shape, block, lead=(4, po.shape[0])).astype(np.int64)
    return ChangeCounts(
        increase=totals[0],
        decrease=totals[1],
        newly_reach=totals[2],
        exact_evaluations=int(totals[3].sum()),
    )


def _over_blocks(
    shape: tuple[int, int],
    block: Callable[[slice, slice], Floats | NDArray[np.int64]],
    lead: tuple[int, ...] = (),
) -> Floats:
    """Sum ``block(problem_slice, row_slice)`` over cache-sized blocks.

    Per-problem results of shape ``lead + (n,)`` are added into the totals.
    Blocks of about ``_BLOCK`` rows keep temporaries in cache.
    """
    m, n_rows = shape
    rows_per = min(n_rows, _BLOCK)
    problems_per = max(1, _BLOCK // n_rows)
    totals = np.zeros((*lead, m))
    for p in range(0, m, problems_per):
        pr = slice(p, min(p + problems_per, m))
        for r in range(0, n_rows, rows_per):
            totals[..., pr] += block(pr, slice(r, min(r + rows_per, n_rows)))
    return totals


def change_counts_any_order(
    ps: Floats, qs: Floats, po: Floats, qo: Floats, yb: Floats, *, tol: float, threshold: float
) -> ChangeCounts:
    """The counts of :func:`change_counts` for output tables in any order (``alpha < 0``).

    A negative coefficient reverses the output tables (they fall with the
    level), so the interval searches of :func:`change_counts` do not apply.
    Every combination is still formed from the tables, ``Y = P[row] + Q[col]``
    (bit-identical to the straightforward luminance, see the module
    docstring), and judged with the reference's float expressions, in blocks
    of about ``_BLOCK * 8`` combinations: no power function, no compositing,
    bounded memory.  ``ps``, ``po`` are (m, R); ``qs``, ``qo`` (m, C).
    """
    m, n_cols = qs.shape
    n_rows = ps.shape[1]
    rows_per = max(1, (_BLOCK * 8) // n_cols)
    inc = np.zeros(m, dtype=np.int64)
    dec = np.zeros(m, dtype=np.int64)
    reach = np.zeros(m, dtype=np.int64)
    for i in range(m):
        y_b = yb[i]
        for r in range(0, n_rows, rows_per):
            rows = slice(r, min(r + rows_per, n_rows))
            cr_s = contrast_from_luminance(ps[i, rows, np.newaxis] + qs[i, np.newaxis, :], y_b)
            cr_o = contrast_from_luminance(po[i, rows, np.newaxis] + qo[i, np.newaxis, :], y_b)
            change = cr_o - cr_s
            inc[i] += np.count_nonzero(change > tol)
            dec[i] += np.count_nonzero(change < -tol)
            # The reference's expression: source contrast plus change, not cr_o.
            reach[i] += np.count_nonzero((cr_s < threshold) & (change + cr_s >= threshold))
    return ChangeCounts(
        increase=inc, decrease=dec, newly_reach=reach, exact_evaluations=m * n_rows * n_cols
    )
