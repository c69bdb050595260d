"""8-bit collisions of source pairs, shared by the sweep and the palette experiment."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import srgb_decode, to_8bit
from alpha_audit.reproduce import kernels
from alpha_audit.reproduce.grids import code_channels

__all__ = ["pair_collisions"]


def _byte_tables(
    backgrounds: NDArray[np.float64], alphas: NDArray[np.float64]
) -> NDArray[np.uint8]:
    """8-bit output code per (alpha, canvas, channel, source byte): (A, m, 3, 256)."""
    lev = srgb_decode(np.arange(256) / 255)
    m = backgrounds.shape[0]
    tables = kernels.channel_tables(
        lev, np.tile(backgrounds, (alphas.size, 1)), np.repeat(alphas, m)
    )
    return to_8bit(tables).reshape(alphas.size, m, 3, 256)


def pair_collisions(
    backgrounds: NDArray[np.float64], alphas: NDArray[np.float64], pairs: NDArray[np.integer[Any]]
) -> NDArray[np.int64]:
    """Per (alpha, canvas), how many source pairs get identical 8-bit outputs.

    ``pairs`` (n, 2) holds 24-bit ``0xRRGGBB`` codes.  A clipped channel
    depends only on its source byte, so each channel is a 256-entry table
    lookup; a pair collides when all three channels' codes agree.
    """
    codes = _byte_tables(backgrounds, np.asarray(alphas, dtype=np.float64))
    channels = code_channels(pairs)  # (n, 2, 3)
    out = np.zeros(codes.shape[:2], dtype=np.int64)
    for a in range(codes.shape[0]):
        same = np.logical_and.reduce(
            [
                np.take(codes[a, :, k, :], channels[:, 0, k], axis=1)
                == np.take(codes[a, :, k, :], channels[:, 1, k], axis=1)
                for k in range(3)
            ]
        )
        out[a] = np.count_nonzero(same, axis=1)
    return out
