"""The render cache: what rendering an icon gave, kept between runs in one SQLite file.

Rendering is most of a check's time, and pre-commit and CI check the same icons
run after run.  An entry is keyed by a hash of what decides its value: the
SVG's bytes, what was rendered (the icon's paints, one size of every paint
group's mask, or the whole icon's mask), the size, and the versions of
cairosvg, cairocffi, the cairo library and alpha-audit (plus a hash of the
modules that read paints and render, so a development checkout never reads
entries an edit made stale).

Every entry is verified on read: its checksum covers its key and its value,
so a flipped bit, a truncated or swapped value or a row copied under another
key reads as a miss, is dropped, and the icon is rendered again; a file that
is not a database is replaced.  Results are therefore the same with a
poisoned cache as with an empty one.  (A value forged *with* a matching
checksum by someone who can write the user's cache folder is not detected;
such a person can replace alpha-audit itself.)

The file lives in the user cache folder (``$ALPHA_AUDIT_CACHE_DIR``, else
``$XDG_CACHE_HOME/alpha-audit``, else ``~/.cache/alpha-audit``).  A folder
that cannot be named (``~nosuchuser/x``, no home) or made, and a folder or
file that is a symbolic link, has several hard links, belongs to another user
or is writable by others, is not used: the run goes on without a cache, and
:func:`take_notes` says why.  A file that is not alpha-audit's (another
schema, a view or trigger a crafted file could make loop, a size far over the
bound) is replaced by an empty one, and every statement's work is bounded
(:data:`MAX_STEPS` virtual-machine steps, counted by SQLite's progress
handler): past it the run goes on without the cache.  Writes
are transactions in WAL mode, so two runs may share the file (a run that finds
it busy for long skips its writes); the file is kept under
:data:`DEFAULT_MAX_BYTES` by dropping the entries used least recently.
``$ALPHA_AUDIT_NO_CACHE`` (any value) or :func:`disable` turns it off.
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
import hashlib
import os
import re
import sqlite3
import stat
import struct
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from pathlib import Path

__all__ = [
    "CACHE_DIR_ENV",
    "DEFAULT_MAX_BYTES",
    "MAX_STEPS",
    "NO_CACHE_ENV",
    "RenderCache",
    "default_cache_dir",
    "disable",
    "open_default",
    "probably_warm",
    "renderer_fingerprint",
    "take_notes",
]

CACHE_DIR_ENV = "ALPHA_AUDIT_CACHE_DIR"
NO_CACHE_ENV = "ALPHA_AUDIT_NO_CACHE"
FILE_NAME = "render.sqlite3"
DEFAULT_MAX_BYTES = 256 << 20  # 2,176 Lucide icons at 16/24/48 px take about 3 MB
_SCHEMA = 1  # PRAGMA user_version; another value: the table is rebuilt
_BUSY_SECONDS = 2.0  # a writer waits this long for another run's transaction
_CHUNK = 500  # keys per statement (SQLite allows 999 variables before 3.32)
_TOUCH_AFTER = 3600  # seconds: a read refreshes an entry's last use at most hourly
_SIDE_FILES = ("", "-wal", "-shm", "-journal")
# SQLite virtual-machine steps one cache operation may take: the progress handler is
# called every _STEP_CALL of them and stops the statement past the bound.  Evicting from
# a full 256 MiB file takes a few million; a crafted file could loop for ever.
MAX_STEPS = 1_000_000_000
_STEP_CALL = 10_000
# A file this many times over its bound is no cache of ours (eviction keeps it under).
_OVERSIZE = 4
# What the file's schema is (sqlite_master), exactly; anything else is not ours.
_TABLE_SQL = (
    "CREATE TABLE entries (key BLOB PRIMARY KEY, value BLOB NOT NULL, "
    "checksum BLOB NOT NULL, used INTEGER NOT NULL, size INTEGER NOT NULL)"
)
_INDEX_SQL = "CREATE INDEX entries_used ON entries (used)"
_SCHEMA_ROWS = frozenset(
    {
        ("table", "entries", "entries", _TABLE_SQL),
        ("index", "entries_used", "entries", _INDEX_SQL),
        ("index", "sqlite_autoindex_entries_1", "entries", None),
    }
)

_enabled: contextvars.ContextVar[bool] = contextvars.ContextVar(
    "alpha_audit_render_cache", default=True
)
_notes: list[str] = []  # why the user's cache was not used or was replaced (take_notes)


def _note(text: str) -> None:
    if text not in _notes:
        _notes.append(text)


def take_notes() -> list[str]:
    """What happened to the user's cache since the last call, one line each (then cleared):
    why a run went without it, or that an unusable file was replaced."""
    taken = list(_notes)
    _notes.clear()
    return taken


def disable() -> Callable[[], None]:
    """Run without the cache from here on in this context (the CLI's ``--no-cache``);
    the function returned turns it back on."""
    token = _enabled.set(False)
    return lambda: _enabled.reset(token)


def default_cache_dir() -> Path:
    """``$ALPHA_AUDIT_CACHE_DIR``, else the platform's user cache folder + ``alpha-audit``.

    Raises :class:`OSError` when the folder cannot be named (``~nosuchuser``, no
    home folder): the run then goes without a cache.
    """
    try:
        return _cache_dir()
    except (RuntimeError, KeyError) as exc:  # pathlib: "Could not determine home directory."
        raise OSError(f"the cache folder cannot be named: {exc}") from exc


def _cache_dir() -> Path:
    if chosen := os.environ.get(CACHE_DIR_ENV):
        return Path(chosen).expanduser()
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "alpha-audit"
    if sys.platform == "win32" and (local := os.environ.get("LOCALAPPDATA")):
        return Path(local) / "alpha-audit" / "Cache"
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    base = Path(xdg) if os.path.isabs(xdg) else Path.home() / ".cache"  # XDG: relative is invalid
    return base / "alpha-audit"


def open_default() -> RenderCache | None:
    """The user's render cache, or None when it is turned off or cannot be used safely."""
    if not _enabled.get() or os.environ.get(NO_CACHE_ENV):
        return None
    try:
        folder = default_cache_dir()
    except OSError as exc:
        _note(f"render cache not used ({exc}); this run renders every icon")
        return None
    return RenderCache.open(folder)


def probably_warm() -> bool:
    """Whether the user's cache is on and has a file with entries in it (a guess, for
    deciding whether to start the renderer before knowing what a run will render)."""
    if not _enabled.get() or os.environ.get(NO_CACHE_ENV):
        return False
    try:
        return (default_cache_dir() / FILE_NAME).stat().st_size > 8192
    except (OSError, ValueError):  # ValueError: a NUL in the variable
        return False


@functools.cache
def renderer_fingerprint() -> bytes:
    """What a cached render depends on besides its input: versions and the render code.

    Read without importing the renderer (the run may need none): cairosvg's
    ``VERSION`` file, cairocffi's version line, the cairo library's own
    version string, alpha-audit's version and a hash of its modules that
    read paints, render and reduce masks.
    """
    import importlib.util
    import platform

    # The package is initialised before any of its modules: read, not imported (no cycle).
    version = sys.modules["alpha_audit"].__version__
    parts = [f"schema {_SCHEMA}", f"alpha-audit {version}", platform.machine()]
    for package, pattern in (
        ("cairosvg", None),
        ("cairocffi", rb"VERSION = __version__ = '([^']+)'"),
    ):
        spec = importlib.util.find_spec(package)
        folder = Path(spec.origin).parent if spec and spec.origin else None
        try:
            if folder is None:
                found = b"missing"
            elif pattern is None:
                found = (folder / "VERSION").read_bytes().strip()
            else:
                text = (folder / "__init__.py").read_bytes()
                match = re.search(pattern, text)
                found = match.group(1) if match else hashlib.sha256(text).digest()
        except OSError:
            found = b"unreadable"
        parts.append(f"{package} {found!r}")
    parts.append(f"cairo {_cairo_version()}")
    here = Path(__file__).parent
    code = hashlib.sha256()
    for module in (
        here / "paints.py",
        here / "_svg_worker.py",
        here / "paint_masks.py",
        here / "render_cache.py",
        here.parent / "color" / "coverage.py",
    ):
        with contextlib.suppress(OSError):
            code.update(module.read_bytes())
    parts.append(code.hexdigest())
    return "\n".join(parts).encode()


def _cairo_version() -> str:
    """The cairo library's version, loaded by the file name the render worker uses."""
    import ctypes

    for name in ("libcairo.so.2", "libcairo.2.dylib", "libcairo-2.dll"):
        try:
            library = ctypes.CDLL(name)
        except OSError:
            continue
        library.cairo_version_string.restype = ctypes.c_char_p
        return str(library.cairo_version_string().decode("ascii", "replace"))
    return "unknown"


def entry_key(kind: str, digest: bytes, *extra: int) -> bytes:
    """The key of one entry: ``kind`` of result for the SVG with sha256 ``digest``."""
    h = hashlib.blake2b(digest_size=20, person=b"alpha-audit-key")
    h.update(renderer_fingerprint())
    h.update(kind.encode() + b"\0" + digest)
    h.update(struct.pack(f">{len(extra)}Q", *extra))
    return h.digest()


def _checksum(key: bytes, value: bytes) -> bytes:
    return hashlib.blake2b(key + value, digest_size=16, person=b"alpha-audit-sum").digest()


class RenderCache:
    """One open cache file; reads are verified, writes wait in memory until :meth:`flush`."""

    def __init__(self, connection: sqlite3.Connection, path: Path, max_bytes: int) -> None:
        self._db = connection
        self._steps = _Steps(connection)
        self.path = path
        self.max_bytes = max_bytes
        self._pending: dict[bytes, bytes] = {}
        self._bad: set[bytes] = set()  # keys whose rows failed verification
        self._read: set[bytes] = set()  # keys read: their last use is refreshed
        self.broken = False  # a database error: the rest of the run goes without

    @classmethod
    def open(cls, folder: Path, *, max_bytes: int = DEFAULT_MAX_BYTES) -> RenderCache | None:
        """The cache file in ``folder`` (made if missing), or None if it cannot be used safely
        (why is noted: :func:`take_notes`)."""
        try:
            _safe_folder(folder)
        except (OSError, ValueError) as exc:  # ValueError: a NUL in the name
            _note(f"render cache not used ({_reason(exc)}); this run renders every icon")
            return None
        path = folder / FILE_NAME
        for attempt in range(2):
            try:
                _safe_files(path, max_bytes * _OVERSIZE)
                return cls(_connect(path), path, max_bytes)
            except sqlite3.OperationalError as exc:  # busy, locked, no space: not the file's fault
                _note(f"render cache {path} not used ({exc}); this run renders every icon")
                return None
            except (sqlite3.DatabaseError, _NotOurs) as exc:
                if attempt:
                    _note(f"render cache {path} not used ({exc}); this run renders every icon")
                    return None
                # Not a database (truncated, overwritten) or not ours: start afresh.
                _note(f"render cache {path} was unusable ({exc}); replaced by an empty one")
                _remove(path)
            except OSError as exc:
                _note(f"render cache not used ({_reason(exc)}); this run renders every icon")
                return None
        return None

    def close(self) -> None:
        with contextlib.suppress(sqlite3.Error):
            self._db.close()

    def __enter__(self) -> RenderCache:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def get(self, keys: Iterable[bytes]) -> dict[bytes, bytes]:
        """The verified values of those ``keys`` that have one."""
        wanted = list(dict.fromkeys(keys))
        found: dict[bytes, bytes] = {}
        if self.broken or not wanted:
            return found
        self._steps.reset()
        try:
            for chunk in _chunks(wanted):
                marks = ",".join("?" * len(chunk))
                rows = self._db.execute(
                    f"SELECT key, value, checksum FROM entries WHERE key IN ({marks})", chunk
                )
                for key, value, checksum in rows:
                    key, value = bytes(key), bytes(value)
                    if _checksum(key, value) == bytes(checksum):
                        found[key] = value
                    else:
                        self._bad.add(key)
        except sqlite3.Error as exc:
            self._fail(exc)
            return {}
        self._read.update(found)
        return found

    def put(self, key: bytes, value: bytes) -> None:
        """Keep ``value`` under ``key`` (written by :meth:`flush`)."""
        self._pending[key] = value
        self._bad.discard(key)

    def forget(self, key: bytes) -> None:
        """Drop an entry whose value did not make sense (written by :meth:`flush`)."""
        self._bad.add(key)
        self._read.discard(key)

    def flush(self) -> None:
        """Write what was put, drop bad rows, refresh last uses, evict; in one transaction.

        A run that cannot get the file within :data:`_BUSY_SECONDS` (another
        run writing) or meets a database error leaves it as it was.
        """
        if self.broken or not (self._pending or self._bad or self._read):
            return
        now = int(time.time())
        pending, bad, read = self._pending, self._bad, self._read
        self._pending, self._bad, self._read = {}, set(), set()
        self._steps.reset()
        try:
            with _transaction(self._db):
                for chunk in _chunks(list(bad)):
                    marks = ",".join("?" * len(chunk))
                    self._db.execute(f"DELETE FROM entries WHERE key IN ({marks})", chunk)
                self._db.executemany(
                    "INSERT OR REPLACE INTO entries (key, value, checksum, used, size) "
                    "VALUES (?, ?, ?, ?, ?)",
                    (
                        (k, v, _checksum(k, v), now, len(k) + len(v) + 16)
                        for k, v in pending.items()
                    ),
                )
                for chunk in _chunks([k for k in read if k not in pending]):
                    marks = ",".join("?" * len(chunk))
                    self._db.execute(
                        f"UPDATE entries SET used = ? WHERE used < ? AND key IN ({marks})",
                        (now, now - _TOUCH_AFTER, *chunk),
                    )
                if pending:
                    self._evict()
        except sqlite3.Error as exc:
            self._fail(exc)
            return
        if pending:
            with contextlib.suppress(sqlite3.Error):
                self._db.execute("PRAGMA incremental_vacuum")

    def _fail(self, exc: sqlite3.Error) -> None:
        """After a database error the run goes on without the cache; a damaged file is
        removed, so the next run starts an empty one (so is one whose statements take
        more than :data:`MAX_STEPS`: no cache of ours does)."""
        self.broken = True
        if self._steps.exceeded:
            _note(
                f"render cache {self.path} took more than {MAX_STEPS:,} steps for one "
                "operation; this run goes on without it, and it is replaced"
            )
        elif isinstance(exc, sqlite3.OperationalError):
            return  # busy (another run writing), out of space ...: the file itself is fine
        self.close()
        _remove(self.path)

    def _evict(self) -> None:
        """Drop the entries used least recently until the file is back under its bound."""
        (total,) = self._db.execute("SELECT coalesce(sum(size), 0) FROM entries").fetchone()
        if total <= self.max_bytes:
            return
        excess = total - int(self.max_bytes * 0.8)  # room for a few runs before the next
        doomed: list[bytes] = []
        for key, size in self._db.execute("SELECT key, size FROM entries ORDER BY used, key"):
            if excess <= 0:
                break
            doomed.append(key)
            excess -= size
        for chunk in _chunks(doomed):
            marks = ",".join("?" * len(chunk))
            self._db.execute(f"DELETE FROM entries WHERE key IN ({marks})", chunk)

    def entries(self) -> int:
        """How many entries the file holds (for tests and diagnostics)."""
        (n,) = self._db.execute("SELECT count(*) FROM entries").fetchone()
        return int(n)

    def size(self) -> int:
        """The bytes the entries account for."""
        (n,) = self._db.execute("SELECT coalesce(sum(size), 0) FROM entries").fetchone()
        return int(n)


class _NotOurs(Exception):
    """The file is a database, but not alpha-audit's render cache."""


class _Steps:
    """A bound on the SQLite virtual-machine steps of one operation (the progress handler)."""

    def __init__(self, db: sqlite3.Connection) -> None:
        self.calls = 0
        self.exceeded = False
        db.set_progress_handler(self._tick, _STEP_CALL)

    def reset(self) -> None:
        self.calls = 0

    def _tick(self) -> int:
        self.calls += 1
        if self.calls * _STEP_CALL > MAX_STEPS:
            self.exceeded = True
            return 1  # a non-zero answer interrupts the statement (sqlite3.OperationalError)
        return 0


def _reason(exc: BaseException) -> str:
    """An OS error in one line, without the errno prefix: ``file: Permission denied``."""
    strerror, filename = getattr(exc, "strerror", None), getattr(exc, "filename", None)
    if strerror and filename is not None:
        return f"{filename}: {strerror}"
    return str(strerror or exc)


def _chunks(items: Sequence[bytes]) -> Iterator[Sequence[bytes]]:
    for start in range(0, len(items), _CHUNK):
        yield items[start : start + _CHUNK]


@contextlib.contextmanager
def _transaction(db: sqlite3.Connection) -> Iterator[None]:
    db.execute("BEGIN IMMEDIATE")
    try:
        yield
    except BaseException:
        with contextlib.suppress(sqlite3.Error):
            db.execute("ROLLBACK")
        raise
    db.execute("COMMIT")


def _connect(path: Path) -> sqlite3.Connection:
    """The cache file, opened; :class:`_NotOurs` when its schema is anything but ours.

    The schema is read from ``sqlite_master`` (which runs nothing) before any
    statement touches ``entries``: a crafted file's view or trigger of that name
    never runs, and every statement is bounded anyway (:class:`_Steps`).
    """
    db = sqlite3.connect(path, timeout=_BUSY_SECONDS, isolation_level=None)
    try:
        steps = _Steps(db)
        db.execute("PRAGMA trusted_schema = OFF")  # no function runs from a schema
        schema = frozenset(db.execute("SELECT type, name, tbl_name, sql FROM sqlite_master"))
        if schema and schema != _SCHEMA_ROWS:
            kinds = sorted({f"{kind} {name}" for kind, name, _, _ in schema - _SCHEMA_ROWS})
            raise _NotOurs(f"its schema is not alpha-audit's: {', '.join(kinds)[:120]}")
        db.execute("PRAGMA auto_vacuum = INCREMENTAL")  # takes effect on a new file only
        db.execute("PRAGMA journal_mode = WAL")
        db.execute("PRAGMA synchronous = NORMAL")
        (version,) = db.execute("PRAGMA user_version").fetchone()
        if version != _SCHEMA or not schema:
            with _transaction(db):
                db.execute("DROP TABLE IF EXISTS entries")
                db.execute(_TABLE_SQL)
                db.execute(_INDEX_SQL)
                db.execute(f"PRAGMA user_version = {_SCHEMA}")
        db.execute("SELECT count(*) FROM entries LIMIT 1").fetchone()
        if steps.exceeded:
            raise _NotOurs(f"opening it took more than {MAX_STEPS:,} steps")
    except sqlite3.OperationalError as exc:
        db.close()
        if "interrupted" in str(exc):
            raise _NotOurs(f"opening it took more than {MAX_STEPS:,} steps") from exc
        raise
    except BaseException:
        db.close()
        raise
    _safe_files(path)  # what SQLite made is ours too (nothing raced in a link)
    return db


def _safe_folder(folder: Path) -> None:
    """Make ``folder`` (mode 0700) if missing; OSError unless it is ours and not a link."""
    try:
        info = os.lstat(folder)
    except FileNotFoundError:
        folder.parent.mkdir(parents=True, exist_ok=True)
        with contextlib.suppress(FileExistsError):
            os.mkdir(folder, 0o700)
        info = os.lstat(folder)
    if not stat.S_ISDIR(info.st_mode):  # a symbolic link is not a folder here
        raise OSError(f"{folder} is not a plain folder")
    _owned(info, folder)
    if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        raise OSError(f"{folder} is writable by others")


def _safe_files(path: Path, max_bytes: int | None = None) -> None:
    """OSError if the database or one of SQLite's side files is anything but our own file;
    :class:`_NotOurs` if one is over ``max_bytes`` (no cache of ours grows so large).

    Their mode is not checked: inside our own folder, no one else reaches them.
    """
    for suffix in _SIDE_FILES:
        try:
            info = os.lstat(f"{path}{suffix}")
        except FileNotFoundError:
            continue
        if not stat.S_ISREG(info.st_mode):  # a symbolic link is not a regular file here
            raise OSError(f"{path}{suffix} is not a plain file")
        _owned(info, path)
        if info.st_nlink != 1:
            raise OSError(f"{path}{suffix} has other hard links")
        if max_bytes is not None and info.st_size > max_bytes:
            raise _NotOurs(f"{info.st_size:,} bytes, far over the cache's bound")


def _owned(info: os.stat_result, path: Path) -> None:
    if hasattr(os, "getuid") and info.st_uid != os.getuid():
        raise OSError(f"{path} belongs to another user")


def _remove(path: Path) -> None:
    for suffix in _SIDE_FILES:
        with contextlib.suppress(OSError):
            info = os.lstat(f"{path}{suffix}")
            if stat.S_ISREG(info.st_mode):
                os.unlink(f"{path}{suffix}")
