"""Every name a benchmark imports from alpha_audit exists: a benchmark runs by hand
(``make bench``), so a renamed or moved name would otherwise go unseen until then."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

BENCHMARKS = sorted((Path(__file__).resolve().parents[2] / "benchmarks").glob("*.py"))
IMPORTS = [
    (script.name, node.module, alias.name)
    for script in BENCHMARKS
    for node in ast.walk(ast.parse(script.read_text()))
    if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("alpha_audit")
    for alias in node.names
]


def test_the_benchmarks_import_from_alpha_audit() -> None:
    assert len({script for script, _, _ in IMPORTS}) >= 10


@pytest.mark.parametrize(("script", "module", "name"), IMPORTS)
def test_a_benchmark_s_import_exists(script: str, module: str, name: str) -> None:
    found = importlib.import_module(module)
    assert hasattr(found, name) or importlib.util.find_spec(f"{module}.{name}"), (
        f"{script}: from {module} import {name}"
    )
