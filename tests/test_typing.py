"""Static typing rules that mypy itself does not enforce (mypy --strict runs in `make lint`)."""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import alpha_audit

SRC = Path(alpha_audit.__file__).resolve().parent

# A silenced error names its code and says why on the same line:
# "# type: ignore[code]  # reason".
_IGNORE = re.compile(r"#\s*type:\s*ignore\b(?P<rest>.*)")
_WITH_REASON = re.compile(r"^\[[a-z-]+(,\s*[a-z-]+)*\]\s+#\s*\S")


def _ignores(text: str) -> list[tuple[int, str]]:
    """(line, comment) of every ``type: ignore`` comment (comments only, not strings)."""
    out = []
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.COMMENT and _IGNORE.search(tok.string):
            out.append((tok.start[0], tok.string))
    return out


def test_the_checker_finds_comments_only() -> None:
    text = 'x = "# type: ignore"  # type: ignore[misc]  # why\ny = 1  # type: ignore\n'
    assert [line for line, _ in _ignores(text)] == [1, 2]


def test_every_type_ignore_names_its_code_and_reason() -> None:
    bad = []
    for path in sorted(SRC.rglob("*.py")):
        for line, comment in _ignores(path.read_text(encoding="utf-8")):
            match = _IGNORE.search(comment)
            assert match is not None
            if not _WITH_REASON.match(match["rest"]):
                bad.append(f"{path.relative_to(SRC)}:{line}: {comment}")
    assert not bad, "type: ignore without [code]  # reason:\n" + "\n".join(bad)


def test_the_reason_rule_rejects_bare_and_codeless_ignores() -> None:
    assert _WITH_REASON.match("[attr-defined]  # typeshed omits it")
    assert not _WITH_REASON.match("[attr-defined]")
    assert not _WITH_REASON.match("  # no code")
    assert not _WITH_REASON.match("")
