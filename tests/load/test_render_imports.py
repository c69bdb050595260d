"""The render side is on no import cycle, not even through ``if TYPE_CHECKING:`` imports."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

RENDER_SIDE = [
    "alpha_audit.load.svg",
    "alpha_audit.load.sandbox",
    "alpha_audit.load._svg_worker",
    "alpha_audit.load.paints",
    "alpha_audit.load.paint_masks",
    "alpha_audit.load.render_cache",
    "alpha_audit.color.coverage",
]


def _graph_with_type_checking_imports() -> dict[str, set[str]]:
    path = Path(__file__).resolve().parents[1] / "test_imports.py"
    spec = importlib.util.spec_from_file_location("package_imports", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module._is_type_checking = lambda node: False  # count what only type checkers import
    graph: dict[str, set[str]] = module.import_graph()
    return graph


@pytest.mark.parametrize("name", RENDER_SIDE)
def test_no_cycle_through_the_render_side(name: str) -> None:
    graph = _graph_with_type_checking_imports()
    seen: set[str] = set()
    stack = [name]
    while stack:
        for target in graph[stack.pop()]:
            if target not in seen:
                seen.add(target)
                stack.append(target)
    assert name not in seen
    if name == "alpha_audit.load.svg":
        assert "alpha_audit.load.sandbox" in seen  # svg renders with the sandbox ...
    if name == "alpha_audit.load.sandbox":
        assert seen == {"alpha_audit.load.render_cache"}  # ... which imports only the cache's
    if name == "alpha_audit.load.render_cache":  # ... which imports nothing of the package
        assert seen == set()
