"""The package's import structure: no cycles, a lazy top level, a complete ``__all__``."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

import alpha_audit
from alpha_audit.cli.root import COMMANDS

SRC = Path(alpha_audit.__file__).resolve().parent


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _imports(tree: ast.AST) -> list[ast.Import | ast.ImportFrom]:
    """Every import statement, inside functions too, except ``if TYPE_CHECKING:`` blocks
    (they never run, so they cannot make a cycle at run time)."""
    found: list[ast.Import | ast.ImportFrom] = []
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node):
            stack.extend(node.orelse)
            continue
        if isinstance(node, ast.Import | ast.ImportFrom):
            found.append(node)
        stack.extend(ast.iter_child_nodes(node))
    return found


def import_graph() -> dict[str, set[str]]:
    """Module -> the package modules it imports.

    A lazy package's stub (``__init__.pyi``) counts as its imports.
    ``from a.b import c`` points at ``a.b.c`` when that is a module, else at
    ``a.b``.  The implicit import of parent packages is not an edge (as in
    pylint's cyclic-import check): a parent is always initialised first.
    """
    files = {_module_name(p): p for p in SRC.rglob("*.py")}
    graph: dict[str, set[str]] = {name: set() for name in files}
    for name, path in files.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        # A lazy package imports what its stub lists, on first use of each name.
        stub = path.with_suffix(".pyi")
        sources = [path, stub] if stub.exists() else [path]
        for node in (n for p in sources for n in _imports(ast.parse(p.read_text(), str(p)))):
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            else:
                base = node.module or ""
                if node.level:
                    anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join([*anchor, base] if base else anchor)
                targets = [
                    f"{base}.{alias.name}" if f"{base}.{alias.name}" in files else base
                    for alias in node.names
                ]
            # Importing from an ancestor package is not an edge either: it is initialised
            # before any of its submodules (``from alpha_audit import __version__``).
            graph[name].update(
                t for t in targets if t in files and t != name and not name.startswith(f"{t}.")
            )
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle as a list of modules (first repeated at the end), or None."""
    state: dict[str, int] = {}  # 1 on the current path, 2 done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                return [*path[path.index(nxt) :], nxt]
            if nxt not in state and (cycle := visit(nxt)):
                return cycle
        path.pop()
        state[node] = 2
        return None

    for start in sorted(graph):
        if start not in state and (cycle := visit(start)):
            return cycle
    return None


def test_the_graph_sees_imports_inside_functions() -> None:
    graph = import_graph()
    assert "alpha_audit.cli.root" in graph["alpha_audit.cli"]
    assert "alpha_audit.output" in graph["alpha_audit.cli.console"]
    # check_command imports the pipeline inside its body
    assert "alpha_audit.pipeline" in graph["alpha_audit.cli.check"]


def test_the_cycle_finder_finds_a_cycle() -> None:
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_no_import_cycle_in_the_package() -> None:
    assert find_cycle(import_graph()) is None


def test_command_modules_never_import_the_app() -> None:
    graph = import_graph()
    importers = {m for m, targets in graph.items() if targets & {"alpha_audit.cli.root"}}
    assert importers == {"alpha_audit.cli"}


def _loaded_after(statement: str) -> list[str]:
    code = f"import json, sys; {statement}; print(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def test_import_color_loads_only_color_and_errors() -> None:
    loaded = _loaded_after("import alpha_audit.color")
    ours = {m for m in loaded if m.split(".")[0] == "alpha_audit"}
    assert ours == {
        "alpha_audit",
        "alpha_audit.color",
        "alpha_audit.color.composite",
        "alpha_audit.color.css",
        "alpha_audit.color.coverage",
        "alpha_audit.color.cvd",
        "alpha_audit.color.drift",
        "alpha_audit.color.judge",
        "alpha_audit.color.oklch",
        "alpha_audit.color.metrics",
        "alpha_audit.color.srgb",
        "alpha_audit.color.transfer",
        "alpha_audit.constants",
        "alpha_audit.errors",
    }
    assert not {"typer", "rich", "yaml", "cairosvg"} & {m.split(".")[0] for m in loaded}


def test_import_alpha_audit_loads_nothing_else() -> None:
    loaded = _loaded_after("import alpha_audit")
    assert [m for m in loaded if m.split(".")[0] in ("alpha_audit", "typer", "rich", "numpy")] == [
        "alpha_audit"
    ]


def test_a_command_imports_only_its_own_module() -> None:
    """``alpha-audit check`` starts without the browser drivers, the page audit or coloraide."""
    code = (
        "import sys\n"
        "from alpha_audit.cli import main\n"
        "try:\n"
        "    main(['check', '--help'])\n"
        "except SystemExit:\n"
        "    pass\n"
        "print(','.join(sorted(sys.modules)), file=sys.stderr)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    loaded = set(done.stderr.strip().split(","))
    assert "alpha_audit.cli.check" in loaded and "Usage: alpha-audit check" in done.stdout
    commands = {f"alpha_audit.cli.{name}" for name in ("render", "preview", "reproduce", "export")}
    assert not loaded & commands
    assert not {"alpha_audit.pages", "alpha_audit.browser", "coloraide", "websockets"} & loaded


def _imported_by(args: list[str]) -> set[str]:
    """Every module ``python -m alpha_audit ARGS`` has loaded when it exits.

    Read from ``sys.modules`` at exit, not from ``-X importtime``: that only sees
    ``import`` statements, not ``importlib.import_module`` (how lazy names load).
    """
    code = (
        "import atexit, json, runpy, sys\n"
        "atexit.register(lambda: sys.stderr.write('\\n' + json.dumps(sorted(sys.modules))))\n"
        f"sys.argv = ['alpha-audit', *{args!r}]\n"
        "runpy.run_module('alpha_audit', run_name='__main__')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    return set(json.loads(done.stderr.strip().splitlines()[-1]))


@pytest.mark.parametrize(
    "args",
    [["--version"], ["--help"], *([name, "--help"] for name in COMMANDS)],
    ids=" ".join,
)
def test_version_and_help_start_without_the_maths(args: list[str]) -> None:
    """``--version`` and every ``--help`` import neither numpy nor a colour library:
    they answer in a fraction of the time a check takes to start (issue 31)."""
    imported = _imported_by(args)
    assert "alpha_audit.cli.root" in imported  # the measurement sees our own imports
    heavy = {"numpy", "colour", "coloraide", "PIL", "cairosvg", "yaml"}
    assert not {m for m in imported if m.split(".")[0] in heavy}


def test_the_import_measurement_sees_numpy_where_it_is_imported() -> None:
    """The same measurement on a command that computes: numpy is there (the test above
    could not pass by seeing nothing)."""
    imported = _imported_by(["pair", "#ee7733", "--on", "#ffffff", "-f", "json"])
    assert {"numpy", "colour"} <= imported


def _stub_names(stub: Path) -> dict[str, tuple[str, str]]:
    """Public name -> (module, attribute), read from a package's ``__init__.pyi``."""
    package = _module_name(stub.with_suffix(".py"))
    return {
        alias.asname or alias.name: (f"{package}.{node.module}", alias.name)
        for node in ast.parse(stub.read_text()).body
        if isinstance(node, ast.ImportFrom)
        for alias in node.names
    }


STUBS = sorted(SRC.rglob("__init__.pyi"))


def test_every_lazy_package_has_a_stub_and_nothing_else_lists_its_names() -> None:
    """A package's names are written once: in its stub, which the ``.py`` only loads."""
    lazy = sorted(p for p in SRC.rglob("__init__.py") if "attach_stub" in p.read_text())
    assert [p.with_suffix(".pyi") for p in lazy] == STUBS
    assert len(STUBS) >= 7
    for path in lazy:
        body = [n for n in ast.parse(path.read_text()).body if not isinstance(n, ast.Expr)]
        assigned = {
            t.id
            for n in body
            if isinstance(n, ast.Assign)
            for t in n.targets
            if isinstance(t, ast.Name)
        }
        assert assigned <= {"__version__"}, path  # no second list of names


@pytest.mark.parametrize("stub", STUBS, ids=lambda p: str(p.parent.relative_to(SRC.parent)))
def test_every_stub_name_is_exported_and_is_the_named_attribute(stub: Path) -> None:
    import importlib

    package = importlib.import_module(_module_name(stub.with_suffix(".py")))
    names = _stub_names(stub)
    assert names, stub
    assert sorted(package.__all__) == sorted(names)
    assert set(names) <= set(dir(package))
    for name, (module, attribute) in names.items():
        assert getattr(package, name) is getattr(importlib.import_module(module), attribute)


def test_unknown_names_raise_attribute_error() -> None:
    try:
        alpha_audit.no_such_name  # noqa: B018
    except AttributeError as exc:
        assert "no_such_name" in str(exc)
    else:  # pragma: no cover
        raise AssertionError("expected AttributeError")


def test_every_command_is_reachable_from_the_public_api() -> None:
    commands = {
        "check": ("check_project", "Policy", "CheckFormat", "render_check", "read_baseline"),
        "suggest": ("largest_safe_alpha", "render_suggest", "apply_alpha"),
        "pair": ("pair_table", "pair_report", "PairFormat"),
        "preview": ("preview_files", "Layout"),
        "reproduce": ("Reproduction", "reproduction_json", "write_figures"),
        "themes": ("bundled_themes", "load_bundled_themes"),
    }
    for command, names in commands.items():
        assert set(names) <= set(alpha_audit.__all__), command


def test_one_version_source() -> None:
    from importlib.metadata import version

    assert version("alpha-audit") == alpha_audit.__version__
    pyproject = (SRC.parents[1] / "pyproject.toml").read_text()
    assert 'dynamic = ["version"]' in pyproject and "\nversion =" not in pyproject.split("[tool")[0]


def test_no_public_name_shadows_a_submodule_and_every_attribute_path_works() -> None:
    """After importing any submodule, ``alpha_audit.x.y`` is that module (issue 18)."""
    modules = sorted(
        ".".join(("alpha_audit", *p.relative_to(SRC).with_suffix("").parts)).removesuffix(
            ".__init__"
        )
        for p in SRC.rglob("*.py")
        if p.name != "__main__.py" and "bundled" not in p.parts
    )
    top = {m.split(".")[1] for m in modules if m.count(".") >= 1}
    assert not top & set(alpha_audit.__all__), "a public name hides a submodule"
    code = (
        "import importlib, functools, alpha_audit\n"
        f"for name in {modules!r}:\n"
        "    importlib.import_module(name)\n"
        "    parts = name.split('.')\n"
        "    assert functools.reduce(getattr, parts[1:], alpha_audit).__name__ == name, name\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
