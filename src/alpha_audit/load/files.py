"""Bounded reads of untrusted files: one place for the size cap and the error wording."""

from __future__ import annotations

from pathlib import Path

from alpha_audit.errors import InputError

__all__ = ["read_capped", "read_text_capped"]

_FIRST_READ = 64 << 10  # bytes: most inputs (icons, themes, manifests) fit in one read


def read_capped(path: str | Path, limit: int, error: type[InputError], kind: str) -> bytes:
    """At most ``limit`` bytes of ``path``; larger, missing or unreadable files raise ``error``.

    ``kind`` completes the messages: "larger than 1024 KiB; not <kind>".
    """
    p = Path(path)
    try:
        with open(p, "rb") as fh:
            # A small first read: ``read(limit + 1)`` would allocate the whole limit (a
            # megabyte for an icon of a few kilobytes) for every file of a set.
            data = fh.read(min(limit + 1, _FIRST_READ))
            if len(data) == _FIRST_READ:
                data += fh.read(limit + 1 - len(data))
    except FileNotFoundError as exc:
        raise error("file not found", path=p) from exc
    except IsADirectoryError as exc:
        raise error(f"is a directory, expected {kind}", path=p) from exc
    except OSError as exc:
        raise error(f"cannot read: {exc.strerror}", path=p) from exc
    if len(data) > limit:
        raise error(f"larger than {limit // 1024} KiB; not {kind}", path=p)
    return data


def read_text_capped(path: str | Path, limit: int, error: type[InputError], kind: str) -> str:
    """:func:`read_capped`, decoded as UTF-8 (a leading BOM kept: parsers drop it and count it).

    Text that is not UTF-8 or holds NUL bytes raises ``error`` naming the byte.
    """
    raw = read_capped(path, limit, error, kind)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"not UTF-8 text (byte {exc.start}); not {kind}", path=Path(path)) from exc
    if "\x00" in text:
        raise error(f"contains NUL bytes; not {kind}", path=Path(path))
    return text
