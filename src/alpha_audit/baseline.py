"""Baseline files (``--baseline``): today's accepted findings, read back as a :class:`Baseline`.

``alpha-audit.baseline/2`` entries are finding keys (theme, icon set, rule,
icons: one per root cause, whatever the canvases).  ``alpha-audit.baseline/1``
files, written when findings were per canvas, are still read: their entries
keep their canvas, and a finding is covered when every canvas of it is
(:meth:`~alpha_audit.gate.Baseline.covers`).
"""

from __future__ import annotations

import json
from pathlib import Path

from alpha_audit.errors import AlphaAuditError, InputError, UsageError
from alpha_audit.findings import FindingKey
from alpha_audit.gate import BASELINE_SCHEMA, LEGACY_BASELINE_SCHEMA, Baseline, CanvasKey
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.paths import PathRefused, contain_argument
from alpha_audit.rules import Rule

__all__ = ["MAX_BASELINE_BYTES", "parse_baseline", "read_baseline"]

MAX_BASELINE_BYTES = 16 << 20  # 16 MiB: a few hundred bytes per entry


def parse_baseline(text: str, path: Path) -> Baseline:
    """The entries of a baseline file written by :func:`~alpha_audit.gate.baseline_document`."""

    def bad(message: str) -> InputError:
        return InputError(f"not an alpha-audit baseline: {message}", path=path)

    try:
        doc = json.loads(text)
    except (ValueError, RecursionError) as exc:  # ValueError: also the int-digits limit
        raise bad(f"invalid JSON ({str(exc)[:100]})") from exc
    schema = doc.get("schema") if isinstance(doc, dict) else None
    if schema not in (BASELINE_SCHEMA, LEGACY_BASELINE_SCHEMA):
        raise bad(f'expected {{"schema": "{BASELINE_SCHEMA}", "entries": [...]}}')
    legacy = schema == LEGACY_BASELINE_SCHEMA
    entries = doc.get("entries")
    if not isinstance(entries, list):
        raise bad("entries must be a list")
    keys: set[FindingKey] = set()
    cells: set[CanvasKey] = set()
    needs = "theme, iconset, rule, canvas and icons" if legacy else "theme, iconset, rule and icons"
    for n, e in enumerate(entries):
        ok = (
            isinstance(e, dict)
            and all(isinstance(e.get(k), str) for k in ("theme", "iconset", "rule"))
            and isinstance(e.get("icons"), list)
            and all(isinstance(i, str) for i in e["icons"])
            and (
                not legacy
                or ("canvas" in e and (e["canvas"] is None or isinstance(e["canvas"], str)))
            )
        )
        if not ok:
            raise bad(f"entries[{n}] needs {needs}")
        try:
            rule = Rule.parse(e["rule"]).value
        except (AlphaAuditError, ValueError) as exc:
            raise bad(f"entries[{n}].rule: {getattr(exc, 'message', exc)}") from exc
        if legacy:
            cells.add((e["theme"], e["iconset"], rule, e["canvas"], tuple(e["icons"])))
        else:
            keys.add((e["theme"], e["iconset"], rule, tuple(e["icons"])))
    return Baseline(keys=frozenset(keys), cells=frozenset(cells), kind="file", name=str(path))


def read_baseline(path: str | Path) -> Baseline:
    """Read a baseline file (at most :data:`MAX_BASELINE_BYTES`)."""
    p = Path(path)
    if not p.exists() and not p.is_symlink():
        raise UsageError("baseline file not found (record one with `baseline_document`)", path=p)
    try:
        contain_argument(p)  # before a byte is read
    except PathRefused as err:
        raise InputError(str(err), path=p) from err
    text = read_text_capped(p, MAX_BASELINE_BYTES, InputError, "an alpha-audit baseline")
    return parse_baseline(text, p)
