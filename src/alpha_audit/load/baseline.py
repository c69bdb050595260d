"""Baseline files (``--baseline``): today's accepted findings, read back as finding keys."""

from __future__ import annotations

import json
from pathlib import Path

from alpha_audit.errors import AlphaAuditError, InputError, UsageError
from alpha_audit.findings import FindingKey
from alpha_audit.gate import BASELINE_SCHEMA
from alpha_audit.load.files import read_text_capped
from alpha_audit.rules import Rule

__all__ = ["MAX_BASELINE_BYTES", "parse_baseline", "read_baseline"]

MAX_BASELINE_BYTES = 16 << 20  # 16 MiB: a few hundred bytes per entry


def parse_baseline(text: str, path: Path) -> frozenset[FindingKey]:
    """Finding keys from a baseline file written by :func:`~alpha_audit.gate.baseline_document`."""

    def bad(message: str) -> InputError:
        return InputError(f"not an alpha-audit baseline: {message}", path=path)

    try:
        doc = json.loads(text)
    except (ValueError, RecursionError) as exc:  # ValueError: also the int-digits limit
        raise bad(f"invalid JSON ({str(exc)[:100]})") from exc
    if not isinstance(doc, dict) or doc.get("schema") != BASELINE_SCHEMA:
        raise bad(f'expected {{"schema": "{BASELINE_SCHEMA}", "entries": [...]}}')
    entries = doc.get("entries")
    if not isinstance(entries, list):
        raise bad("entries must be a list")
    keys = set()
    for n, e in enumerate(entries):
        ok = (
            isinstance(e, dict)
            and all(isinstance(e.get(k), str) for k in ("theme", "iconset", "rule"))
            and "canvas" in e
            and (e["canvas"] is None or isinstance(e["canvas"], str))
            and isinstance(e.get("icons"), list)
            and all(isinstance(i, str) for i in e["icons"])
        )
        if not ok:
            raise bad(f"entries[{n}] needs theme, iconset, rule, canvas and icons")
        try:
            rule = Rule.parse(e["rule"]).value
        except (AlphaAuditError, ValueError) as exc:
            raise bad(f"entries[{n}].rule: {getattr(exc, 'message', exc)}") from exc
        keys.add((e["theme"], e["iconset"], rule, e["canvas"], tuple(e["icons"])))
    return frozenset(keys)


def read_baseline(path: str | Path) -> frozenset[FindingKey]:
    """Read a baseline file (at most :data:`MAX_BASELINE_BYTES`)."""
    p = Path(path)
    if not p.exists() and not p.is_symlink():
        raise UsageError("baseline file not found (record one with `baseline_document`)", path=p)
    text = read_text_capped(p, MAX_BASELINE_BYTES, InputError, "an alpha-audit baseline")
    return parse_baseline(text, p)
