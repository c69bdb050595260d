"""A render refused for its resource limits says which limit, with its value."""

from __future__ import annotations

from pathlib import Path

from alpha_audit.load._svg_worker import describe_failure
from alpha_audit.load.svg import RenderLimits, rasterize_icons

HUGE_PATTERN = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    '<defs><pattern id="p" width="1e5" height="1e5" patternUnits="userSpaceOnUse">'
    '<rect width="1e5" height="1e5"/></pattern></defs>'
    '<rect width="24" height="24" fill="url(#p)"/></svg>'
)


def test_a_memory_error_names_the_limit() -> None:
    assert describe_failure(MemoryError(), 512 << 20) == (
        "needs more memory than the render limit of 512 MiB allows"
    )
    assert describe_failure(MemoryError()) == "needs more memory than the render limit allows"


def test_a_render_over_the_memory_limit_names_it(tmp_path: Path) -> None:
    svg = tmp_path / "huge.svg"
    svg.write_text(HUGE_PATTERN)
    limits = RenderLimits(timeout=20.0, memory=768 << 20, workers=1)
    masks = rasterize_icons([("huge", svg)], (24,), limits=limits)
    (problem,) = masks.problems
    assert "768 MiB" in problem.message and "memory" in problem.message, problem.message
