"""Hostile input from a stranger's pull request: only clean, bounded, local failures.

The corpus is generated here (nothing large is committed).  Each SVG case must
become a one-line per-file problem within the render time limit, never a
traceback; no URL may be fetched (network or file); YAML and path tricks exit
2 with one line naming the file.
"""

from __future__ import annotations

import os
import resource
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.errors import AlphaAuditError
from alpha_audit.load.config import config_from_doc
from alpha_audit.load.iconset import iconset_from_doc
from alpha_audit.load.svg import MAX_SVG_BYTES, RenderLimits, rasterize_icons
from alpha_audit.load.theme import theme_from_doc
from alpha_audit.load.yamldoc import load_yaml, parse_yaml

HEAD = (
    '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
    'viewBox="0 0 24 24">'
)
DOT = '<rect x="10" y="10" width="4" height="4"/>'  # 16 of 576 pixels at 24 px
LIMITS = RenderLimits(timeout=3.0)


def _fanout(depth: int, width: int) -> str:
    groups = "".join(
        f'<g id="p{i + 1}">' + f'<use href="#p{i}"/>' * width + "</g>" for i in range(depth)
    )
    return f'{HEAD}<defs><path id="p0" d="M0 0h1v1z"/>{groups}</defs><use href="#p{depth}"/></svg>'


# name -> (file bytes, expected problem fragment)
SVG_CASES: dict[str, tuple[bytes, str]] = {
    "billion-laughs": (
        (
            '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa">'
            '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;"><!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;">]>'
            f"{HEAD}<text>&c;</text></svg>"
        ).encode(),
        "entities",
    ),
    "external-entity": (
        (
            '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
            f"{HEAD}<text>&x;</text></svg>"
        ).encode(),
        "entit",
    ),
    "recursive-use": (f'{HEAD}<g id="a"><use href="#a"/></g></svg>'.encode(), "nested too deeply"),
    "deep-nesting": (
        (HEAD + "<g>" * 30000 + DOT + "</g>" * 30000 + "</svg>").encode(),
        "nested too deeply",
    ),
    "use-fanout": (_fanout(5, 10).encode(), "took longer than 3 s"),
    "huge-pattern": (
        (
            f'{HEAD}<defs><pattern id="p" width="1e5" height="1e5" patternUnits="userSpaceOnUse">'
            '<rect width="1e5" height="1e5"/></pattern></defs>'
            '<rect width="24" height="24" fill="url(#p)"/></svg>'
        ).encode(),
        "memory",
    ),
    "png-renamed": (b"\x89PNG\r\n\x1a\n" + bytes(64), "PNG image"),
    "gzip": (b"\x1f\x8b\x08\x00" + bytes(64), "gzip"),
    "binary": (b"<svg>\x00\x01\x02</svg>", "NUL"),
    "latin-1": ("<svg>é</svg>".encode("latin-1"), "not UTF-8"),
    "not-svg": (b"<html><body>hi</body></html>", "no <svg>"),
    "too-big": (HEAD.encode() + b" " * MAX_SVG_BYTES + b"</svg>", "larger than"),
    "empty": (f"{HEAD}</svg>".encode(), "renders nothing"),
    "broken-xml": (f"{HEAD}<rect".encode(), "cannot render SVG"),
}


@pytest.fixture(scope="module")
def rendered(tmp_path_factory: pytest.TempPathFactory):
    folder = tmp_path_factory.mktemp("hostile")
    icons = []
    for name, (data, _) in SVG_CASES.items():
        (folder / f"{name}.svg").write_bytes(data)
        icons.append((name, folder / f"{name}.svg"))
    # The render workers' CPU time (the fork server reaps them, and is reaped when the
    # pool closes), not wall time: a loaded machine stretches the one, not the other.
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    masks = rasterize_icons(icons, (16, 24), limits=LIMITS)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return masks, cpu


@pytest.mark.parametrize("name", list(SVG_CASES))
def test_hostile_svg_is_one_clean_problem(rendered, name: str) -> None:
    masks, _ = rendered
    problems = {p.icon: p.message for p in masks.problems}
    assert SVG_CASES[name][1] in problems[name]
    assert "\n" not in problems[name] and "Traceback" not in problems[name]
    assert not any(key[0] == name for key in masks.masks)


def test_hostile_corpus_is_bounded_by_counts_and_one_budget(rendered) -> None:
    """Every case but the fan-out is stopped by a counted bound (entities, depth, bytes,
    memory), before any time budget; the fan-out by its own CPU budget.  So the verdicts
    do not move on a loaded machine, and the whole corpus costs at most a budget per icon."""
    masks, cpu = rendered
    timed = {p.icon for p in masks.problems if "took longer than" in p.message}
    assert timed == {"use-fanout"}
    assert cpu < LIMITS.job_cpu * len(SVG_CASES)


def test_declared_size_is_ignored(tmp_path: Path) -> None:
    svg = tmp_path / "huge.svg"
    svg.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="1e9" height="1e9" '
        'viewBox="0 0 1e9 1e9"><rect width="5e8" height="1e9"/></svg>'
    )
    masks = rasterize_icons([("huge", svg)], (24,), limits=LIMITS)
    assert not masks.problems
    assert masks.masks[("huge", 24)].shape == (24, 24)
    assert masks.masks[("huge", 24)].mean() == pytest.approx(0.5, abs=0.05)


def test_no_file_or_network_access(tmp_path: Path) -> None:
    from PIL import Image

    secret = tmp_path / "outside" / "secret.png"
    secret.parent.mkdir()
    Image.new("RGBA", (24, 24), (0, 0, 0, 255)).save(secret)
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(0.2)
    port = listener.getsockname()[1]
    root = tmp_path / "repo"
    root.mkdir()
    refs = {
        "file-url": f'<image href="{secret.as_uri()}" width="24" height="24"/>',
        "relative": '<image href="../outside/secret.png" width="24" height="24"/>',
        "xlink": f'<image xlink:href="{secret}" width="24" height="24"/>',
        "http-image": f'<image href="http://127.0.0.1:{port}/a.png" width="24" height="24"/>',
        "http-use": f'<use href="http://127.0.0.1:{port}/a.svg#x"/>',
        "css-import": f"<style>@import url(http://127.0.0.1:{port}/a.css);</style>",
        "data-url": (
            '<image href="data:image/svg+xml;utf8,%3Csvg xmlns=%22http://www.w3.org/2000/svg%22%3E'
            '%3Crect width=%2299%22 height=%2299%22/%3E%3C/svg%3E" width="24" height="24"/>'
        ),
    }
    icons = []
    for name, ref in refs.items():
        (root / f"{name}.svg").write_text(f"{HEAD}{ref}{DOT}</svg>")
        icons.append((name, root / f"{name}.svg"))
    masks = rasterize_icons(icons, (24,), limits=LIMITS)
    assert not masks.problems
    for name in refs:  # only the dot: nothing referenced was drawn
        assert masks.masks[(name, 24)].sum() == pytest.approx(16, abs=1), name
    with pytest.raises(TimeoutError):
        listener.accept()
    listener.close()


# --- YAML, paths and numbers through the CLI: exit 2, one line, no traceback ---------------
SVG = f"{HEAD}{DOT}</svg>"
THEME = 'name: t\ncanvases:\n  - {name: paper, color: "#ffffff"}\n'
SET = 'name: s\nicons: svg/*.svg\ncolor: "#0077bb"\n'

YAML_CASES = [
    # (theme text, manifest text, expected message fragment)
    (
        "a: &a [x, x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
        "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c]\n"
        "e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]\nf: [*e, *e, *e, *e, *e, *e, *e, *e]\n",
        SET,
        "alias bomb",
    ),
    ("name: t\nname: u\ncanvases: []\n", SET, "duplicate key 'name'"),
    ("canvases:\n  - {name: p, color: #fff}\n", SET, "quote"),
    ("threshold: .nan\n" + THEME[8:], SET, "out of range"),
    ("threshold: -1e308\n" + THEME[8:], SET, "out of range"),
    ("threshold: '4.5'\n" + THEME[8:], SET, "expected a contrast ratio"),
    ("name: t\ncanvases: []\n", SET, "non-empty list of canvases"),
    (THEME + '  - {name: paper, color: "#000000"}\n', SET, "duplicate canvas name"),
    (THEME, SET + "alpha: .inf\n", "out of range"),
    (THEME, SET + "alpha: yes\n", "expected a finite coefficient"),
    (THEME, "icons: [svg/a.svg, {file: svg/a.svg}]\ncolor: red\n", "duplicate icon name"),
    (THEME, "icons: ../*.svg\ncolor: red\n", "leaves the manifest's folder"),
    (THEME, "icons: [../../etc/passwd]\ncolor: red\n", "outside the project root"),
    (THEME, "icons: [/etc/passwd]\ncolor: red\n", "absolute"),
    (THEME, "icons: [svg/link.svg]\ncolor: red\n", "outside the project root"),
    (THEME, "icons: !!python/object/apply:os.system [touch pwned]\n", "tag"),
    (THEME, "icon: svg/*.svg\n", "did you mean 'icons'"),
]


@pytest.fixture
def project(tmp_path: Path) -> Path:
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    (root / "svg").mkdir()
    (root / "svg" / "a.svg").write_text(SVG)
    secret = tmp_path / "secret.svg"
    secret.write_text(SVG)
    (root / "svg" / "link.svg").symlink_to(secret)
    return root


@pytest.mark.parametrize(("theme", "manifest", "message"), YAML_CASES)
def test_hostile_yaml_and_paths_exit_2(
    project: Path, theme: str, manifest: str, message: str
) -> None:
    (project / "theme.yaml").write_text(theme)
    (project / "set.yaml").write_text(manifest)
    old = Path.cwd()
    os.chdir(project)
    try:
        result = CliRunner().invoke(app, ["check", "theme.yaml", "set.yaml"])
    finally:
        os.chdir(old)
    assert result.exit_code == 2, result.output
    assert message in result.output
    assert "Traceback" not in result.output
    line = result.output.strip()
    assert line.startswith("alpha-audit: error: ") and ".yaml" in line


def test_hostile_icons_are_findings_not_crashes(project: Path) -> None:
    (project / "svg" / "bomb.svg").write_bytes(SVG_CASES["billion-laughs"][0])
    (project / "svg" / "png.svg").write_bytes(SVG_CASES["png-renamed"][0])
    (project / "theme.yaml").write_text(THEME)
    (project / "set.yaml").write_text(SET.replace("svg/*.svg", "svg/[abp]*.svg"))
    old = Path.cwd()
    os.chdir(project)
    try:
        runner = CliRunner()
        ok = runner.invoke(app, ["check", "theme.yaml", "set.yaml", "-f", "markdown"])
        gated = runner.invoke(app, ["check", "theme.yaml", "set.yaml", "--fail-on", "unrenderable"])
        strict = runner.invoke(app, ["check", "theme.yaml", "set.yaml", "--strict-svg"])
    finally:
        os.chdir(old)
    assert ok.exit_code == 0 and "- bomb: declares XML entities" in ok.stdout
    assert gated.exit_code == 1
    assert strict.exit_code == 2 and "Traceback" not in strict.output


# --- generated garbage: the loaders raise AlphaAuditError and nothing else -----------------
_scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.sampled_from(["#fff", "cycle", "red", "svg/*.svg", "../x", "/etc/passwd", "loss", "1e999"]),
)
_keys = st.sampled_from(
    [
        "name",
        "canvases",
        "color",
        "mode",
        "threshold",
        "icons",
        "palette",
        "alpha",
        "sizes",
        "overrides",
        "file",
        "themes",
        "fail-on",
        "exempt",
        "reason",
        "canvas",
        "icon",
        "x",
    ]
)
_values = st.recursive(
    _scalars,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(_keys, inner, max_size=5),
    max_leaves=20,
)


@settings(
    max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(data=_values)
def test_loaders_raise_only_clean_errors_on_generated_documents(tmp_path: Path, data) -> None:
    import yaml

    try:
        text = yaml.safe_dump(data)
    except yaml.YAMLError:
        return
    doc = parse_yaml(text, tmp_path / "x.yaml")
    for load in (
        theme_from_doc,
        lambda d: iconset_from_doc(d, root=tmp_path),
        config_from_doc,
    ):
        try:
            load(doc)
        except AlphaAuditError as exc:
            assert "\n" not in str(exc).strip() or "YAML" in str(exc)


@settings(
    max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(raw=st.binary(max_size=300) | st.text(max_size=300).map(str.encode))
def test_yaml_reader_raises_only_clean_errors_on_garbage_bytes(tmp_path: Path, raw: bytes) -> None:
    path = tmp_path / "garbage.yaml"
    path.write_bytes(raw)
    try:
        doc = load_yaml(path)
        theme_from_doc(doc)
    except AlphaAuditError:
        pass


@pytest.mark.parametrize("value", ['!!float ""', '!!bool ""', '!!timestamp "x"', '!!int "z"'])
def test_explicit_tags_on_bad_scalars_are_clean_input_errors(tmp_path: Path, value: str) -> None:
    path = tmp_path / "theme.yaml"
    path.write_text(f"name: {value}\ncanvases: []\n")
    with pytest.raises(AlphaAuditError, match=r"theme\.yaml:1") as info:
        theme_from_doc(load_yaml(path))
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    ("entries", "message"),
    [
        ('[{"theme": "t", "iconset": "s", "rule": "loss", "canvas": 1' + "0" * 5000 + "}]", "JSON"),
        ('[{"theme": "t", "iconset": "s", "rule": "loss", "icons": [1]}]', "entries\\[0\\]"),
        ('[{"theme": "t", "iconset": "s", "rule": "loss"}]', "entries\\[0\\]"),
        ('[{"theme": "t", "iconset": "s", "rule": "nope", "canvas": null, "icons": []}]', "rule"),
    ],
)
def test_bad_baselines_name_the_file(tmp_path: Path, entries: str, message: str) -> None:
    from alpha_audit.baseline import read_baseline
    from alpha_audit.gate import BASELINE_SCHEMA

    path = tmp_path / "base.json"
    path.write_text(f'{{"schema": "{BASELINE_SCHEMA}", "entries": {entries}}}')
    with pytest.raises(AlphaAuditError, match=message) as info:
        read_baseline(path)
    assert "base.json" in str(info.value) and "\n" not in str(info.value)


def test_empty_fail_on_is_an_error(tmp_path: Path) -> None:
    path = tmp_path / "alpha-audit.yaml"
    path.write_text("fail-on: []\n")
    with pytest.raises(AlphaAuditError, match=r"fail-on.*empty list"):
        config_from_doc(load_yaml(path))


@pytest.mark.skipif(shutil.which("strace") is None, reason="needs strace (apt-get install strace)")
def test_render_workers_open_no_account_database_and_start_no_subprocess(tmp_path: Path) -> None:
    (tmp_path / "a.svg").write_text(HEAD + DOT + "</svg>")
    script = (
        "from pathlib import Path; from alpha_audit.load.svg import rasterize_icons; "
        f"r = rasterize_icons([('a', Path({str(tmp_path / 'a.svg')!r}))], [16]); "
        "assert not r.problems, r.problems"
    )
    trace = tmp_path / "trace.txt"
    strace = ["strace", "-f", "-qq", "-s", "300", "-e", "trace=open,openat,execve"]
    subprocess.run(
        [*strace, "-o", str(trace), sys.executable, "-c", script], check=True, timeout=120
    )
    lines = trace.read_text().splitlines()
    workers = {ln.split()[0] for ln in lines if "execve(" in ln and "_svg_worker" in ln}
    assert workers, "no render worker started"
    worker_lines = [ln for ln in lines if ln.split()[0] in workers]
    assert not any("/etc/passwd" in ln for ln in worker_lines)
    # The only programs run are the workers themselves (no ldconfig, no gcc).
    execs = [ln for ln in lines if "execve(" in ln and "= 0" in ln]
    assert all("_svg_worker" in ln for ln in execs[1:]), execs
