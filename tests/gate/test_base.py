"""``check --base REF``: a pull request that changes one manifest line is judged on that line.

A real git repository in a temporary folder: the base commit already has one
failing icon; the change adds one override.  The gate must fail on the new
root cause only, annotate the changed line, lead the comment with it, and
leave the checkout exactly as it was.
"""

from __future__ import annotations

import json
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.errors import UsageError
from alpha_audit.load.git import check_ref

runner = CliRunner()
SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    '<rect x="2" y="2" width="20" height="20" fill="currentColor"/></svg>'
)
MANIFEST = """name: s
icons: "icons/*.svg"
palette:
  navy: "#0000d0"
  ink: "#333333"
color: ink
alpha: 1.0
overrides:
  a: {color: navy, alpha: 1.3}
"""
THEME = """name: t
canvases:
  - {name: white, color: "#ffffff"}
  - {name: sun, color: "#ffff00"}
  - {name: sand, color: "#eeee88"}
"""
CHANGE = "  b: {alpha: 0.85}\n"  # the pull request: one manifest line


def _git(root: Path, *args: str) -> str:
    env = {"PATH": os.environ["PATH"], "HOME": str(root), "GIT_CONFIG_NOSYSTEM": "1"}
    done = subprocess.run(
        ["git", *args], cwd=root, env=env, capture_output=True, text=True, check=True
    )
    return done.stdout


@pytest.fixture
def repo(tmp_path: Path) -> Iterator[Path]:
    root = tmp_path / "design"
    (root / "icons").mkdir(parents=True)
    for name in ("a", "b", "c"):
        (root / "icons" / f"{name}.svg").write_text(SVG)
    (root / "set.yaml").write_text(MANIFEST)
    (root / "theme.yaml").write_text(THEME)
    (root / "alpha-audit.yaml").write_text("theme: theme.yaml\niconset: set.yaml\n")
    _git(root, "init", "-q")
    _git(root, "-c", "user.email=a@b", "-c", "user.name=t", "add", "-A")
    _git(root, "-c", "user.email=a@b", "-c", "user.name=t", "commit", "-qm", "base")
    with (root / "set.yaml").open("a") as fh:
        fh.write(CHANGE)
    old = Path.cwd()
    os.chdir(root)
    try:
        yield root
    finally:
        os.chdir(old)


def _changed_line(root: Path) -> int:
    lines = (root / "set.yaml").read_text().splitlines()
    return lines.index(CHANGE.rstrip("\n")) + 1


def test_the_base_gates_only_the_new_root_cause_at_the_changed_line(repo: Path) -> None:
    status = _git(repo, "status", "--porcelain", "--ignored")
    everything = runner.invoke(app, ["check", "-f", "json"])
    assert everything.exit_code == 1
    assert {tuple(f["icons"]) for f in json.loads(everything.stdout)["gate"]["failures"]} == {
        ("a",),
        ("b",),
    }
    result = runner.invoke(app, ["check", "--base", "HEAD", "-f", "github"])
    assert result.exit_code == 1, result.output
    errors = [line for line in result.stdout.splitlines() if line.startswith("::error file=")]
    (only,) = errors  # a was failing on the base already
    assert only.startswith(f"::error file=set.yaml,line={_changed_line(repo)},")
    assert "title=alpha-audit loss::b on " in only
    # The comment leads with it: the first failing row is b, set at the changed line.
    text = runner.invoke(app, ["check", "--base", "HEAD", "-f", "markdown"]).stdout
    rows = [line for line in text.splitlines() if line.startswith("| ink ")]
    assert rows and f"set.yaml:{_changed_line(repo)}" in rows[0]
    assert "root cause(s) already on the base revision HEAD" in text
    # The checkout is as it was: nothing written, no worktree added.
    assert _git(repo, "status", "--porcelain", "--ignored") == status
    assert len(_git(repo, "worktree", "list").splitlines()) == 1


def test_fixing_a_base_finding_passes_and_counts_it_as_fixed(repo: Path) -> None:
    text = (repo / "set.yaml").read_text().replace("alpha: 1.3", "alpha: 1.0")
    (repo / "set.yaml").write_text(text.replace(CHANGE, ""))
    result = runner.invoke(app, ["check", "--base", "HEAD", "-f", "json"])
    assert result.exit_code == 0, result.output
    gate = json.loads(result.stdout)["gate"]
    assert gate["baseline"] == {"kind": "base", "name": "HEAD"}
    assert gate["stale_baseline"] == [
        {"theme": "t", "iconset": "s", "rule": "loss", "icons": ["a"]}
    ]


def test_a_base_without_the_config_makes_every_finding_new(repo: Path) -> None:
    _git(repo, "rm", "-q", "--cached", "alpha-audit.yaml")
    _git(repo, "-c", "user.email=a@b", "-c", "user.name=t", "commit", "-qm", "no config")
    result = runner.invoke(app, ["check", "--base", "HEAD", "-f", "json"])
    assert result.exit_code == 1
    assert "could not be audited" in result.stderr and "every finding is new" in result.stderr
    assert len(json.loads(result.stdout)["gate"]["failures"]) == 2


def test_a_broken_file_of_the_base_is_named_as_in_the_repository(repo: Path) -> None:
    (repo / "theme.yaml").write_text("name: t\ncanvases: {}\n")
    _git(repo, "add", "theme.yaml")
    _git(repo, "-c", "user.email=a@b", "-c", "user.name=t", "commit", "-qm", "broken")
    (repo / "theme.yaml").write_text(THEME)  # the change repairs it
    result = runner.invoke(app, ["check", "--base", "HEAD", "-f", "json"])
    assert result.exit_code == 1, result.output
    assert "could not be audited (theme.yaml:2: canvases: " in result.stderr, result.stderr
    assert "alpha-audit-base-" not in result.stderr


@pytest.mark.parametrize(
    "ref", ["-x", "--output=/tmp/x", "HEAD..main", "main:set.yaml", "HEAD@{1}", "a b", "", "x/"]
)
def test_refs_are_validated_before_git_sees_them(ref: str) -> None:
    with pytest.raises(UsageError, match="is not a revision"):
        check_ref(ref)


def test_an_unknown_ref_or_no_repository_is_a_usage_error(repo: Path, tmp_path: Path) -> None:
    unknown = runner.invoke(app, ["check", "--base", "no-such-branch"])
    assert unknown.exit_code == 2 and "names no commit" in unknown.output
    both = runner.invoke(app, ["check", "--base", "HEAD", "--baseline", "b.json"])
    assert both.exit_code == 2 and "not both" in both.output
    elsewhere = tmp_path / "plain"
    elsewhere.mkdir()
    os.chdir(elsewhere)
    (elsewhere / "alpha-audit.yaml").write_text("theme: t.yaml\niconset: s.yaml\n")
    (elsewhere / "t.yaml").write_text(THEME)
    (elsewhere / "s.yaml").write_text('icons: "*.svg"\ncolor: "#000000"\n')
    (elsewhere / "x.svg").write_text(SVG)
    outside = runner.invoke(app, ["check", "--base", "HEAD"])
    assert outside.exit_code == 2 and "needs a git repository" in outside.output


def _commit_links(repo: Path) -> None:
    """Links a repository may hold beside its icons: to an absolute path, and up and out."""
    (repo / "tools").mkdir()
    (repo / "tools" / "python").symlink_to("/usr/bin/python3")
    (repo / "tools" / "up").symlink_to("../../../..")
    _git(repo, "add", "tools")
    _git(repo, "-c", "user.email=a@b", "-c", "user.name=t", "commit", "-qm", "links")


def test_a_base_holding_links_out_is_audited_without_them(repo: Path) -> None:
    _commit_links(repo)
    result = runner.invoke(app, ["check", "--base", "HEAD", "-f", "json"])
    assert result.exit_code == 1, result.output
    assert "2 entries left out as unsafe to write" in result.stderr
    assert "could not be audited" not in result.stderr
    failures = json.loads(result.stdout)["gate"]["failures"]
    assert [f["icons"] for f in failures] == [["b"]]  # a is on the base: only b is new


def test_a_base_that_cannot_be_exported_gates_on_every_finding(
    repo: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from alpha_audit.load import git

    monkeypatch.setattr(git, "MAX_EXPORT_FILES", 2)  # the revision holds 6 files
    result = runner.invoke(app, ["check", "--base", "HEAD", "-f", "json"])
    assert result.exit_code == 1, result.output
    assert "could not be audited" in result.stderr and "every finding is new" in result.stderr
    assert "more than 2 files" in result.stderr
    assert len(json.loads(result.stdout)["gate"]["failures"]) == 2


@pytest.mark.parametrize("hang", ["exec sleep 300", "sleep 300"], ids=["exec", "child"])
def test_sigterm_during_the_base_removes_the_exported_revision(
    repo: Path, tmp_path: Path, hang: str
) -> None:
    """git archive is made to hang once it has written the tree (a wrapper on PATH): the run
    is signalled while the revision sits exported in its TMPDIR, and must leave nothing.
    The wrapper hangs as itself (``exec``) or in a child of its own, which dies with
    git's process group."""
    import shutil
    import signal
    import sys
    import time

    real = shutil.which("git")
    assert real is not None
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    wrapper = bin_dir / "git"
    # The real git exits before the wrapper hangs, and says so: signalled any earlier,
    # that git (the wrapper's child, not ours) could still be exiting when pgrep looks.
    hanging = tmp_path / "hanging"
    wrapper.write_text(
        f'#!/bin/sh\ncase " $* " in *" archive "*) "{real}" "$@"; : > "{hanging}"; '
        f"{hang};; esac\n"
        f'exec "{real}" "$@"\n'
    )
    wrapper.chmod(0o755)
    temp = tmp_path / "run-tmp"
    temp.mkdir()
    exe = Path(sys.executable).with_name("alpha-audit")
    env = {**os.environ, "TMPDIR": str(temp), "PATH": f"{bin_dir}:{os.environ['PATH']}"}
    run = subprocess.Popen(
        [str(exe), "check", "--base", "HEAD", "--no-cache"],
        cwd=repo,
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    deadline = time.monotonic() + 60
    while not (hanging.exists() and list(temp.glob("alpha-audit-base-*/revision/design/set.yaml"))):
        assert run.poll() is None and time.monotonic() < deadline, run.stderr.read()
        time.sleep(0.05)
    run.send_signal(signal.SIGTERM)
    assert run.wait(timeout=30) == -signal.SIGTERM, run.stderr.read()
    assert list(temp.iterdir()) == []  # the exported revision is gone
    # And the hanging git with it: no live process left in the run's session (one just
    # killed may show as a zombie until it is reaped).
    deadline = time.monotonic() + 10
    while (alive := _alive_in_session(run.pid)) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert alive == []


def _alive_in_session(session: int) -> list[str]:
    """The processes of ``session`` that are not zombies (``pgrep`` lists both)."""
    found = subprocess.run(["pgrep", "-s", str(session)], capture_output=True, text=True)
    alive = []
    for pid in found.stdout.split():
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except (OSError, IndexError):
            continue  # gone already
        if state != "Z":
            alive.append(pid)
    return alive
