"""Hostile names a page supplies, and the static page that supplies them.

For any test of what a page's names reach (reports, the terminal table, CI logs):
``PAGE`` (``tests/pages/hostile/names.html``) draws one 24 px icon per name in
``NAMES``, each name as the icon's ``id``, ``data-icon``, ``class`` and ``<title>``,
none mapped to a manifest.  Audit it as a folder source::

    from hostile_names import PAGE
    config = RenderConfig((FolderSource(PAGE.parent, PAGE.name),), root=PAGE.parent, ...)

``assert_inert(text)`` fails when an output holds what a name must never bring in
raw: a line starting with a workflow command the page wrote, ESC, BEL or the bidi
override, or a name longer than alpha-audit's bounds (the 30,000-character id).
"""

from __future__ import annotations

from pathlib import Path

PAGE = Path(__file__).resolve().parent / "pages" / "hostile" / "names.html"

# In the page's order (names.html sets them from these same JavaScript escapes).
NAMES = (
    "a\n::error::forged by a page",
    "b\n::add-mask::secret-value",
    "c\n::stop-commands::pause-token",
    "d\x1b[31mred\x1b]8;;https://example.com\x07link\x1b]8;;\x07",
    "e\x07bell",
    "f\u202egnp.exe",
    "g" + "x" * 30_000,
)
WORKFLOW_COMMANDS = ("::error::", "::add-mask::", "::stop-commands::")
CONTROLS = ("\x1b", "\x07", "\u202e")
LONGEST = "x" * 1_001  # no output carries more of the long id than a DOM path's bound


def assert_inert(text: str) -> None:
    """``text`` (a report, a table, a log) carries none of the names' instructions."""
    for line in text.splitlines():
        stripped = line.lstrip()
        for command in WORKFLOW_COMMANDS:
            assert not stripped.startswith(command), f"a line starts with {command}: {line[:80]!r}"
    for control in CONTROLS:
        assert control not in text, f"raw U+{ord(control):04X} in the output"
    assert LONGEST not in text, "the 30,000-character id reached the output unbounded"
