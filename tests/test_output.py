"""The one writer: all targets checked first, all or nothing, never through a link."""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path
from typing import BinaryIO

import pytest

from alpha_audit.errors import UsageError
from alpha_audit.output import Output, check_targets, write_bytes, write_files, write_text


def test_writes_text_and_bytes_with_an_ordinary_mode(tmp_path: Path) -> None:
    write_text(tmp_path / "a.txt", "é\r\nx")
    write_bytes(tmp_path / "b.bin", b"\x00\xff")
    assert (tmp_path / "a.txt").read_bytes() == "é\r\nx".encode()  # line endings as given
    assert (tmp_path / "b.bin").read_bytes() == b"\x00\xff"
    mask = os.umask(0o022)
    os.umask(mask)
    assert stat.S_IMODE((tmp_path / "a.txt").stat().st_mode) == 0o666 & ~mask


def test_a_kept_mode_is_kept(tmp_path: Path) -> None:
    write_bytes(tmp_path / "m.yaml", b"x", mode=0o600)
    assert stat.S_IMODE((tmp_path / "m.yaml").stat().st_mode) == 0o600


@pytest.mark.parametrize(
    ("names", "setup", "words"),
    [
        (["a.json", "b.json"], {"b.json": "file"}, ["b.json", "already exists"]),
        (["a.json", "./a.json"], {}, ["two outputs"]),
        (["a.json", "missing/b.json"], {}, ["missing", "does not exist"]),
        (["d"], {"d": "dir"}, ["not a regular file"]),
    ],
)
def test_targets_are_all_checked_before_any_is_written(
    tmp_path: Path, names: list[str], setup: dict[str, str], words: list[str]
) -> None:
    for name, kind in setup.items():
        (tmp_path / name).mkdir() if kind == "dir" else (tmp_path / name).write_text("mine")
    outputs = [Output.text(tmp_path / n, "new") for n in names]
    with pytest.raises(UsageError) as err:
        write_files(outputs)
    for word in words:
        assert word in str(err.value)
    assert not (tmp_path / "a.json").exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_overwrite_replaces_existing_files(tmp_path: Path) -> None:
    (tmp_path / "a.json").write_text("old")
    write_text(tmp_path / "a.json", "new", overwrite=True)
    assert (tmp_path / "a.json").read_text() == "new"


def test_a_symlink_is_replaced_never_written_through(tmp_path: Path) -> None:
    victim = tmp_path / "victim"
    victim.write_text("keep")
    link = tmp_path / "report.json"
    link.symlink_to(victim)
    with pytest.raises(UsageError):
        write_text(link, "new")  # it exists (through the link): refused without overwrite
    write_text(link, "new", overwrite=True)
    assert victim.read_text() == "keep"
    assert not link.is_symlink() and link.read_text() == "new"
    dangling = tmp_path / "dangling.json"
    dangling.symlink_to(tmp_path / "nowhere" / "x")
    write_text(dangling, "new")
    assert not dangling.is_symlink() and not (tmp_path / "nowhere").exists()


def test_a_full_disk_is_a_usage_error_naming_the_file_and_leaves_nothing(tmp_path: Path) -> None:
    def full(fh: BinaryIO) -> None:
        fh.write(b"half")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    outputs = [Output.text(tmp_path / "a.json", "{}"), Output(tmp_path / "b.png", full)]
    with pytest.raises(UsageError) as err:
        write_files(outputs)
    assert "b.png" in str(err.value) and "nothing was written" in str(err.value)
    assert list(tmp_path.iterdir()) == []


def test_check_targets_accepts_a_fresh_set(tmp_path: Path) -> None:
    check_targets([tmp_path / "a", tmp_path / "b"], overwrite=False)
