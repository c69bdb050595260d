"""Fuzzing the commands in-process: mutated inputs end in exit 0, 1 or 2, never a crash.

Valid theme, manifest, config, baseline and SVG texts are mutated (bytes
deleted, inserted or replaced; lines duplicated) and ``check`` (table, JSON
with a baseline, GitHub) or ``suggest`` runs on them.  Every run must exit
0, 1 or 2, say why on one line when it is 2, print no traceback and create
no file (there is no ``--output``).  ``ALPHA_AUDIT_FUZZ_EXAMPLES`` raises the
example count for a longer local run.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from alpha_audit.cli import app

CI = os.environ.get("CI", "").lower() in ("1", "true", "yes")
EXAMPLES = int(os.environ.get("ALPHA_AUDIT_FUZZ_EXAMPLES", 15 if CI else 40))

FILES = {
    "theme.yaml": (
        "name: t\nthreshold: 3\ncanvases:\n  - {name: paper, color: '#ffffff'}\n"
        "  - {name: ink, color: '#0d1117', mode: dark}\n"
    ),
    "iconset.yaml": (
        "name: s\nicons: svg/*.svg\ncolor: cycle\nalpha: 1.1\nsizes: [16, 24]\n"
        "palette: {orange: '#ee7733', blue: '#0077bb'}\noverrides:\n  a: {alpha: 1.2}\n"
    ),
    "alpha-audit.yaml": (
        "fail-on: [loss, new-collision]\nmax-loss: 0.1\nexempt:\n"
        "  - {icon: a, rule: loss, reason: brand colour}\n"
    ),
    "svg/a.svg": '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    '<path d="M4 4h16v16H4z"/></svg>',
    "baseline.json": (
        '{"schema": "alpha-audit.baseline/1", "entries": [{"theme": "t", "iconset": "s", '
        '"rule": "loss", "canvas": "ink", "icons": ["a"]}]}'
    ),
}
COMMANDS = [
    ["check", "theme.yaml", "iconset.yaml"],
    ["check", "theme.yaml", "iconset.yaml", "--baseline", "baseline.json", "-f", "json"],
    ["check", "theme.yaml", "iconset.yaml", "-f", "github"],
    ["suggest", "theme.yaml", "iconset.yaml", "-f", "markdown"],
]
INSERTS = [
    # bytes and YAML structure
    *(b"\x00", b"\x1b[2J", b"\xe2\x80\xae", b"!!float ''", b"&a", b"*a", b"{", b"- ", b"\n  "),
    *(b"!!timestamp x", b"\n  - {name: x, color: '#000'}", b'\n  - {icon: a, reason: "\\ud800"}'),
    # SVG structure: references, external resources, entities, text
    *(b'<use href="#a"/>', b'<g id="a"><use href="#a"/></g>', b"<!DOCTYPE x [<!ENTITY e 'b'>]>"),
    *(b'<image href="file:///etc/passwd" width="9" height="9"/>', b"<text>\xe2\x80\xae</text>"),
]


@st.composite
def mutated(draw: st.DrawFn) -> tuple[str, bytes]:
    name = draw(st.sampled_from(sorted(FILES)))
    data = bytearray(FILES[name].encode())
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(data)))
        kind = draw(st.sampled_from(["delete", "insert", "replace", "dup-line"]))
        if kind == "delete":
            del data[at : at + draw(st.integers(1, 8))]
        elif kind == "insert":
            piece = draw(st.one_of(st.sampled_from(INSERTS), st.binary(min_size=1, max_size=4)))
            data[at:at] = piece
        elif kind == "replace" and at < len(data):
            data[at] = draw(st.integers(0, 255))
        else:
            lines = bytes(data).split(b"\n")
            k = draw(st.integers(0, len(lines) - 1))
            lines.insert(k, lines[k])
            data = bytearray(b"\n".join(lines))
    return name, bytes(data)


def _snapshot(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


@settings(
    max_examples=EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(mutated(), st.sampled_from(COMMANDS))
def test_commands_on_mutated_inputs_exit_cleanly(
    case: tuple[str, bytes], command: list[str]
) -> None:
    name, data = case
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp).resolve()
        (root / ".git").mkdir()
        for file, text in FILES.items():
            (root / file).parent.mkdir(parents=True, exist_ok=True)
            (root / file).write_text(text)
        (root / name).write_bytes(data)
        before = _snapshot(root)
        cwd = os.getcwd()
        os.chdir(root)
        try:
            result = CliRunner().invoke(app, command)
        finally:
            os.chdir(cwd)
        assert _snapshot(root) == before  # nothing written
    output = result.output
    assert result.exit_code in (0, 1, 2), (result.exit_code, output, result.exception)
    assert "Traceback" not in output
    if result.exit_code == 2:
        errors = [line for line in output.splitlines() if "error" in line.lower()]
        assert len(errors) == 1, output
