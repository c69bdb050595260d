"""The render cache: warm runs render nothing, and a poisoned cache changes nothing."""

from __future__ import annotations

import hashlib
import math
import os
import random
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from alpha_audit.load import render_cache, sandbox
from alpha_audit.load.paint_masks import measure_paints, paint_masks
from alpha_audit.load.render_cache import FILE_NAME, RenderCache, entry_key
from alpha_audit.load.svg import rasterize_icons
from alpha_audit.paints import PaintSet

NS = 'xmlns="http://www.w3.org/2000/svg"'
ICONS = {
    "alert": (
        f'<svg {NS} viewBox="0 0 24 24" fill="none" stroke="currentColor" stroke-width="2">'
        '<circle cx="12" cy="12" r="10"/><path d="M12 8v4"/><path d="M3 3l18 18" stroke="#f00"/>'
        "</svg>"
    ),
    "flag": (
        f'<svg {NS} viewBox="0 0 6 4"><rect width="6" height="4" fill="#fff"/>'
        '<rect width="2" height="4" fill="#002395"/><rect x="4" width="2" height="4" '
        'fill="#ed2939" opacity=".5"/><text>x</text></svg>'
    ),
    "disc": f'<svg {NS} viewBox="0 0 24 24"><circle cx="12" cy="12" r="9" opacity=".3"/></svg>',
    "blank": f'<svg {NS} viewBox="0 0 24 24"><text x="1" y="9">a</text></svg>',
    "broken": "<svg",
}
SIZES = (8, 16, 24)


@pytest.fixture
def icons(tmp_path: Path) -> list[tuple[str, Path]]:
    folder = tmp_path / "icons"
    folder.mkdir()
    for name, text in ICONS.items():
        (folder / f"{name}.svg").write_text(text)
    return [(name, folder / f"{name}.svg") for name in ICONS]


@pytest.fixture
def renders(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """SVGs sent to render workers during the test (one entry per job, its SVG count)."""
    sent: list[int] = []
    send = sandbox._Worker.send

    def spy(self: sandbox._Worker, job: int, request: bytes, svgs: int, sizes: object) -> None:
        sent.append(svgs)
        send(self, job, request, svgs, sizes)  # type: ignore[arg-type]  # the sizes given

    monkeypatch.setattr(sandbox._Worker, "send", spy)
    return sent


def comparable(result: PaintSet) -> object:
    """A PaintSet as plain values, NaN written as a string (NaN != NaN)."""

    def number(x: float) -> object:
        return "nan" if isinstance(x, float) and math.isnan(x) else x

    return (
        {
            name: (
                str(icon.file),
                icon.paints,
                [
                    (c.group, {s: tuple(map(number, vars(v).values())) for s, v in c.sizes.items()})
                    for c in icon.coverage
                ],
            )
            for name, icon in result.icons.items()
        },
        result.problems,
    )


def measure(icons: list[tuple[str, Path]], folder: Path) -> PaintSet:
    with RenderCache.open(folder) as cache:  # type: ignore[union-attr]  # a usable folder
        return measure_paints(icons, SIZES, cache=cache)


def test_a_warm_run_renders_nothing_and_gives_the_same_result(
    icons: list[tuple[str, Path]], tmp_path: Path, renders: list[int]
) -> None:
    reference = measure_paints(icons, SIZES, cache=False)
    renders.clear()
    cold = measure(icons, tmp_path / "cache")
    assert len(renders) == len(ICONS)  # one job per icon (its paints read in the worker)
    warm = measure(icons, tmp_path / "cache")
    assert len(renders) == len(ICONS)  # nothing more was read or rendered, broken included
    assert comparable(reference) == comparable(cold) == comparable(warm)
    assert [p.icon for p in warm.problems] == ["broken"]
    # a size not seen before renders only what is missing, from the same paints
    with RenderCache.open(tmp_path / "cache") as cache:  # type: ignore[union-attr]
        wider = measure_paints(icons, (*SIZES, 32), cache=cache)
    assert comparable(wider) == comparable(measure_paints(icons, (*SIZES, 32), cache=False))


def test_masks_for_previews_come_from_the_audits_cache(
    icons: list[tuple[str, Path]], tmp_path: Path, renders: list[int]
) -> None:
    from alpha_audit.load.paints import isolate_paints
    from alpha_audit.load.svg import rasterize

    measure(icons, tmp_path / "cache")
    rendered = len(renders)
    with RenderCache.open(tmp_path / "cache") as cache:  # type: ignore[union-attr]
        masks = paint_masks(icons, SIZES, cache=cache)
    assert len(renders) == rendered  # every mask came from the cache
    flag = masks.icons["flag"]
    data = ICONS["flag"].encode()
    assert [g.color for g in flag.groups] == ["#ffffff", "#002395", "#ed2939"]
    for k, group in enumerate(flag.groups):
        for size in SIZES:
            alone = rasterize(
                isolate_paints(data, lambda p, g=group: (p.color, p.opacity) == g.key), size
            )
            np.testing.assert_array_equal(flag.masks[size][k], np.rint(alone * 255))
    assert masks.icons["blank"].groups == () and masks.icons["blank"].masks[8] == ()


def _filled(icons: list[tuple[str, Path]], folder: Path) -> Path:
    measure(icons, folder)
    return folder / FILE_NAME


def _rows(db: Path) -> list[tuple[bytes, bytes, bytes]]:
    with sqlite3.connect(db) as con:
        return [
            tuple(map(bytes, r)) for r in con.execute("SELECT key, value, checksum FROM entries")
        ]  # type: ignore[misc]


POISONS = ["bit flips", "wrong blobs", "truncated", "row for another key", "not a database"]


@pytest.mark.parametrize("poison", POISONS)
def test_a_poisoned_cache_gives_what_an_empty_one_gives(
    poison: str, icons: list[tuple[str, Path]], tmp_path: Path
) -> None:
    reference = comparable(measure_paints(icons, SIZES, cache=False))
    rng = random.Random(poison)
    for trial in range(4 if poison == "bit flips" else 1):
        folder = tmp_path / f"cache{trial}"
        db = _filled(icons, folder)
        if poison == "bit flips":
            data = bytearray(db.read_bytes())
            for _ in range(40):
                at = rng.randrange(len(data))
                data[at] ^= 1 << rng.randrange(8)
            db.write_bytes(bytes(data))
        elif poison == "wrong blobs":
            with sqlite3.connect(db) as con:
                rows = con.execute("SELECT key, value FROM entries").fetchall()
                values = [v for _, v in rows]
                rng.shuffle(values)
                con.executemany(
                    "UPDATE entries SET value = ? WHERE key = ?",
                    [(v, k) for (k, _), v in zip(rows, values, strict=True)],
                )
                con.execute(
                    "UPDATE entries SET value = zeroblob(length(value)) WHERE rowid % 3 = 0"
                )
        elif poison == "truncated":
            with open(db, "r+b") as f:
                f.truncate(db.stat().st_size // 2)
        elif poison == "row for another key":
            rows = _rows(db)
            with sqlite3.connect(db) as con:
                # every row's key given another row's value and checksum
                for (key, _, _), (_, value, checksum) in zip(
                    rows, rows[1:] + rows[:1], strict=True
                ):
                    con.execute(
                        "UPDATE entries SET value = ?, checksum = ? WHERE key = ?",
                        (value, checksum, key),
                    )
        else:
            db.write_bytes(b"not a database at all" * 100)
        assert comparable(measure(icons, folder)) == reference
        # and the cache repaired itself: the next run is right too
        assert comparable(measure(icons, folder)) == reference


def test_values_with_a_right_checksum_but_no_sense_are_dropped(
    icons: list[tuple[str, Path]], tmp_path: Path, renders: list[int]
) -> None:
    """What another version or a bug may have written is verified field by field."""
    reference = comparable(measure_paints(icons, SIZES, cache=False))
    db = _filled(icons, tmp_path / "cache")
    with RenderCache.open(tmp_path / "cache") as cache:  # type: ignore[union-attr]
        for _, path in icons[:3]:
            digest = hashlib.sha256(path.read_bytes()).digest()
            cache.put(entry_key("paints", digest), b'{"paints": [["red", "fill", 2, 1, 0]]}')
            cache.put(entry_key("masks", digest, 8), b"\0\0\0\x07" + b"\0" * 40)
        cache.flush()
    rendered = len(renders)
    assert comparable(measure(icons, tmp_path / "cache")) == reference
    assert len(renders) == rendered + 3  # those three were rendered again
    assert db.exists()


def test_entries_are_keyed_by_the_renderer_and_tool_versions(
    icons: list[tuple[str, Path]],
    tmp_path: Path,
    renders: list[int],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    measure(icons, tmp_path / "cache")
    first = len(renders)
    assert b"cairosvg" in render_cache.renderer_fingerprint()
    assert b"cairo " in render_cache.renderer_fingerprint()
    monkeypatch.setattr(render_cache, "renderer_fingerprint", lambda: b"cairo 9.9 (another)")
    measure(icons, tmp_path / "cache")
    assert len(renders) == 2 * first  # nothing matched: every icon rendered again


@pytest.mark.parametrize("link", ["folder", "file", "wal", "hard link"])
def test_a_cache_that_is_a_link_is_not_used(
    link: str, icons: list[tuple[str, Path]], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir(mode=0o700)
    target = elsewhere / "precious"
    target.write_bytes(b"keep me")
    folder = tmp_path / "cache"
    if link == "folder":
        folder.symlink_to(elsewhere, target_is_directory=True)
    else:
        folder.mkdir(mode=0o700)
        name = FILE_NAME + ("-wal" if link == "wal" else "")
        if link == "hard link":
            os.link(target, folder / name)
        else:
            (folder / name).symlink_to(target)
    assert RenderCache.open(folder) is None
    reference = comparable(measure_paints(icons, SIZES, cache=False))
    monkeypatch.setenv("ALPHA_AUDIT_CACHE_DIR", str(folder))
    assert comparable(measure_paints(icons, SIZES)) == reference  # the run goes on without
    assert target.read_bytes() == b"keep me"
    assert sorted(p.name for p in elsewhere.iterdir()) == ["precious"]


def test_a_folder_others_may_write_is_not_used(tmp_path: Path) -> None:
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    assert RenderCache.open(shared) is None
    made = tmp_path / "new" / "cache"
    with RenderCache.open(made) as cache:  # type: ignore[union-attr]
        assert cache.entries() == 0
    assert made.stat().st_mode & 0o777 == 0o700


def test_disabled_cache_is_neither_read_nor_written(
    icons: list[tuple[str, Path]], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import contextvars

    monkeypatch.setenv("ALPHA_AUDIT_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("ALPHA_AUDIT_NO_CACHE", "1")
    measure_paints(icons, SIZES)
    assert not (tmp_path / "cache").exists()
    monkeypatch.delenv("ALPHA_AUDIT_NO_CACHE")

    def without() -> None:
        render_cache.disable()
        measure_paints(icons, SIZES)

    contextvars.copy_context().run(without)
    assert not (tmp_path / "cache").exists()
    measure_paints(icons, SIZES)  # outside that context the cache is on again
    assert (tmp_path / "cache" / FILE_NAME).exists()


def test_eviction_drops_the_entries_used_least_recently(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    clock = [1_000_000]
    monkeypatch.setattr(render_cache.time, "time", lambda: clock[0])
    value = bytes(range(256)) * 4  # 1 KiB
    with RenderCache.open(tmp_path, max_bytes=10_000) as cache:  # type: ignore[union-attr]
        for k in range(8):
            clock[0] += 10_000
            cache.put(b"key%d" % k, value)
            cache.flush()
        assert cache.entries() == 8
        clock[0] += 10_000
        assert cache.get([b"key0"]) == {b"key0": value}  # used again: now the most recent
        cache.flush()
        for k in range(8, 12):
            clock[0] += 10_000
            cache.put(b"key%d" % k, value)
            cache.flush()
            assert cache.size() <= 10_000
        left = set(cache.get(b"key%d" % k for k in range(12)))
    assert b"key0" in left and b"key11" in left
    assert b"key1" not in left and b"key2" not in left  # the oldest unused went first


SCRIPT = """
import pickle, sys
from pathlib import Path
from alpha_audit.load.paint_masks import measure_paints
from alpha_audit.load.render_cache import RenderCache
icons = [(p.stem, p) for p in sorted(Path(sys.argv[1]).glob("*.svg"))]
with RenderCache.open(Path(sys.argv[2])) as cache:
    result = measure_paints(icons, (8, 16, 24), cache=cache)
sys.stdout.buffer.write(pickle.dumps(result))
"""


def test_two_runs_can_share_the_cache(icons: list[tuple[str, Path]], tmp_path: Path) -> None:
    import pickle

    many = tmp_path / "many"
    many.mkdir()
    for k in range(40):
        (many / f"i{k:02d}.svg").write_text(
            f'<svg {NS} viewBox="0 0 24 24"><circle cx="12" cy="12" r="{2 + k % 9}" '
            f'fill="#{k:02x}{k:02x}{k:02x}"/><rect width="{k % 7 + 1}" height="3"/></svg>'
        )
    files = [(p.stem, p) for p in sorted(many.glob("*.svg"))]
    reference = comparable(measure_paints(files, (8, 16, 24), cache=False))
    runs = [
        subprocess.Popen(
            [sys.executable, "-c", SCRIPT, str(many), str(tmp_path / "shared")],
            stdout=subprocess.PIPE,
        )
        for _ in range(2)
    ]
    outputs = [run.communicate(timeout=300)[0] for run in runs]
    assert all(run.returncode == 0 for run in runs)
    for output in outputs:
        assert comparable(pickle.loads(output)) == reference
    with sqlite3.connect(tmp_path / "shared" / FILE_NAME) as con:
        assert con.execute("PRAGMA integrity_check").fetchone() == ("ok",)
    with RenderCache.open(tmp_path / "shared") as cache:  # type: ignore[union-attr]
        assert cache.entries() == 40 * 4  # each icon's paints and 3 sizes, once
    assert comparable(measure(files, tmp_path / "shared")) == reference


def test_whole_icon_masks_are_cached_too(
    icons: list[tuple[str, Path]], tmp_path: Path, renders: list[int]
) -> None:
    cold = rasterize_icons(icons, SIZES, cache=False)
    with RenderCache.open(tmp_path / "cache") as cache:  # type: ignore[union-attr]
        first = rasterize_icons(icons, SIZES, cache=cache)
    rendered = len(renders)
    with RenderCache.open(tmp_path / "cache") as cache:  # type: ignore[union-attr]
        warm = rasterize_icons(icons, SIZES, cache=cache)
    assert len(renders) == rendered + 1  # only "broken" again: failures are not kept
    assert [p.icon for p in warm.problems] == ["broken"]
    for result in (first, warm):
        assert result.problems == cold.problems
        assert list(result.masks) == list(cold.masks)
        for key in cold.masks:
            np.testing.assert_array_equal(result.masks.codes(key), cold.masks.codes(key))


# A view and a trigger that would never end if anything ran them: a crafted file in the
# cache folder (a CI cache restored from a pull request's run) must not hang the audit.
_ENDLESS = "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n) SELECT i FROM n"
CRAFTED = {
    "a view named entries": [
        f"CREATE VIEW entries AS {_ENDLESS}",
        "PRAGMA user_version = 1",
    ],
    "a trigger on entries": [
        "CREATE TABLE entries (key BLOB PRIMARY KEY, value BLOB NOT NULL, checksum BLOB NOT "
        "NULL, used INTEGER NOT NULL, size INTEGER NOT NULL)",
        "CREATE INDEX entries_used ON entries (used)",
        f"CREATE TRIGGER t AFTER INSERT ON entries BEGIN SELECT count(*) FROM ({_ENDLESS}); END",
        "PRAGMA user_version = 1",
    ],
    "another table": [
        "CREATE TABLE entries (key TEXT, value TEXT)",
        "CREATE TABLE other (x)",
    ],
    "an old schema with a view": [f"CREATE VIEW entries AS {_ENDLESS}"],
}


def _round_trip(folder: Path) -> None:
    """The cache in ``folder`` takes an entry and gives it back."""
    with RenderCache.open(folder) as cache:  # type: ignore[union-attr]
        cache.put(b"k" * 20, b"value")
        cache.flush()
        assert cache.get([b"k" * 20]) == {b"k" * 20: b"value"} and not cache.broken


@pytest.mark.parametrize("craft", list(CRAFTED))
def test_a_crafted_cache_file_is_replaced_and_never_run(
    craft: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Were a statement run for ever, the step bound would stop it: this test cannot hang.
    monkeypatch.setattr(render_cache, "MAX_STEPS", 5_000_000)
    folder = tmp_path / "cache"
    folder.mkdir(mode=0o700)
    con = sqlite3.connect(folder / FILE_NAME)
    for statement in CRAFTED[craft]:
        con.execute(statement)
    con.commit()
    con.close()
    render_cache.take_notes()
    monkeypatch.setenv("ALPHA_AUDIT_CACHE_DIR", str(folder))
    opened = render_cache.open_default()
    assert opened is not None and opened.entries() == 0
    opened.close()
    (note,) = render_cache.take_notes()
    assert "replaced by an empty one" in note and "not alpha-audit's" in note, note
    _round_trip(folder)
    assert render_cache.take_notes() == []


def test_an_operation_over_its_step_bound_leaves_the_run_uncached(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Counted, not timed: SQLite's progress handler counts the steps of each operation."""
    folder = tmp_path / "cache"
    with RenderCache.open(folder) as cache:  # type: ignore[union-attr]
        for k in range(2_000):
            cache.put(k.to_bytes(20, "big"), b"v" * 64)
        cache.flush()
    render_cache.take_notes()
    monkeypatch.setattr(render_cache, "MAX_STEPS", 20_000)  # opening fits, a large read not
    monkeypatch.setattr(render_cache, "_STEP_CALL", 100)
    cache = RenderCache.open(folder)
    assert cache is not None
    assert cache.get(k.to_bytes(20, "big") for k in range(2_000)) == {} and cache.broken
    cache.put(b"x" * 20, b"y")
    cache.flush()  # a broken cache writes nothing, and raises nothing
    (note,) = render_cache.take_notes()
    assert "took more than 20,000 steps" in note and "goes on without it" in note
    monkeypatch.setattr(render_cache, "MAX_STEPS", 1_000_000_000)
    _round_trip(folder)  # the file was replaced: the next run has a working cache


def test_a_cache_folder_that_cannot_be_named_leaves_the_run_uncached_with_a_note(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from typer.testing import CliRunner

    from alpha_audit.cli import app

    assert RenderCache.open(Path("cache\x00dir")) is None  # a NUL: no folder has that name
    assert "render cache not used" in render_cache.take_notes()[0]
    monkeypatch.setenv("ALPHA_AUDIT_CACHE_DIR", "~no-such-user-alpha-audit/cache")
    assert not render_cache.probably_warm() and render_cache.open_default() is None
    assert "cannot be named" in render_cache.take_notes()[0]
    (tmp_path / ".git").mkdir()
    (tmp_path / "t.yaml").write_text("name: t\ncanvases:\n  - {name: white, color: '#fff'}\n")
    (tmp_path / "a.svg").write_text(ICONS["disc"])
    (tmp_path / "s.yaml").write_text("name: s\nicons: ['a.svg']\ncolor: '#333333'\n")
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(app, ["check", "t.yaml", "s.yaml"])
    assert result.exit_code == 0, result.output
    assert "alpha-audit: render cache not used (the cache folder cannot be named" in (result.stderr)
