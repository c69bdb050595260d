"""A revision's files from git, for ``check --base``: read-only, bounded, in a folder of ours.

:func:`export_revision` writes the tree of one commit into a folder the caller
owns (``git archive`` piped into :mod:`tarfile` with its ``data`` filter:
no absolute paths, no ``..``, no links leaving the folder, no devices), so the
user's checkout, index and ``.git`` are never written.  git runs as a
subprocess with a clean environment (no ``GIT_DIR`` or other ``GIT_*`` from
the caller, no user or system config, no prompts), and the revision, which may
come from a pull request's event, is validated before git sees it
(:func:`check_ref`).  An entry the filter refuses (a link to an absolute
path) is left out and reported, not fatal: the rest of the revision is audited.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import tarfile
from pathlib import Path
from typing import IO

from alpha_audit.errors import InputError, UsageError
from alpha_audit.safe_text import safe_text

__all__ = [
    "MAX_EXPORT_BYTES",
    "MAX_EXPORT_FILES",
    "check_ref",
    "export_revision",
    "git_toplevel",
    "resolve_commit",
]

# A design repository's tree at one commit: icons, themes, tokens.  Bounds what a
# base revision may put on disk (git archive streams it; nothing is kept in memory).
MAX_EXPORT_BYTES = 2 << 30  # 2 GiB
MAX_EXPORT_FILES = 500_000
GIT_SECONDS = 300  # one git command (an archive of a large repository included)

# What a revision may be spelt with: branch and tag names (git check-ref-format),
# commit ids, and the suffixes ~N and ^N.  ".." (a range), ":" (a path in a
# tree), "@{" (reflogs), spaces and a leading "-" (an option) are refused.
_REF = re.compile(r"[A-Za-z0-9][A-Za-z0-9._/+-]*(?:[~^][0-9]*)*")
_MAX_REF = 255


def check_ref(ref: str) -> str:
    """``ref`` if it is a plain revision name (branch, tag, commit id, ``~N``/``^N``).

    >>> check_ref("origin/main"), check_ref("HEAD~1")
    ('origin/main', 'HEAD~1')
    >>> check_ref("--output=x")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    alpha_audit.errors.UsageError: `base` '--output=x' is not a revision: ...
    """
    bad = (
        not ref
        or len(ref) > _MAX_REF
        or not _REF.fullmatch(ref)
        or ".." in ref
        or "//" in ref
        or ref.endswith((".", "/", ".lock"))
    )
    if bad:
        shown = ref[:60].encode("unicode_escape").decode("ascii")
        raise UsageError(f"`base` {shown!r} is not a revision: give a branch, tag or commit")
    return ref


def _environment(home: Path) -> dict[str, str]:
    """A clean environment for git: none of the caller's GIT_* variables or config."""
    return {
        "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
        "HOME": str(home),
        "LC_ALL": "C",
        "GIT_CONFIG_NOSYSTEM": "1",
        "GIT_CONFIG_GLOBAL": os.devnull,
        "GIT_TERMINAL_PROMPT": "0",
        "GIT_ATTR_NOSYSTEM": "1",
        "GIT_NO_REPLACE_OBJECTS": "1",
    }


def _git(repo: Path, home: Path, *args: str) -> list[str]:
    """The argument list of one git command in ``repo``: hooks and fsmonitor off."""
    return [
        "git",
        "-c",
        f"safe.directory={repo}",  # the repository we were run in, even if another user owns it
        "-c",
        "core.fsmonitor=false",
        "-c",
        "core.hooksPath=" + os.devnull,
        "-C",
        str(repo),
        *args,
    ]


def _run(repo: Path, home: Path, *args: str) -> str:
    try:
        done = subprocess.run(
            _git(repo, home, *args),
            env=_environment(home),
            capture_output=True,
            text=True,
            timeout=GIT_SECONDS,
            check=False,
            stdin=subprocess.DEVNULL,
        )
    except FileNotFoundError as exc:
        raise UsageError("`base` needs git on PATH") from exc
    except subprocess.TimeoutExpired as exc:
        raise InputError(f"git {args[0]} took more than {GIT_SECONDS} s", path=repo) from exc
    if done.returncode != 0:
        first = (done.stderr.strip().splitlines() or ["failed"])[0][:200]
        raise UsageError(f"git {args[0]}: {first}", path=repo)
    return done.stdout.strip()


def git_toplevel(start: Path, home: Path) -> Path:
    """The top folder of the git work tree holding ``start``."""
    try:
        top = _run(start, home, "rev-parse", "--show-toplevel")
    except UsageError as exc:
        raise UsageError(f"`base` needs a git repository ({exc.message})") from exc
    return Path(top).resolve()


def resolve_commit(repo: Path, ref: str, home: Path) -> str:
    """The full commit id ``ref`` names in ``repo`` (after :func:`check_ref`)."""
    check_ref(ref)
    try:
        commit = _run(
            repo, home, "rev-parse", "--verify", "--quiet", "--end-of-options", ref + "^{commit}"
        )
    except UsageError as exc:
        raise UsageError(
            f"`base` {ref!r} names no commit of this repository (fetch it first, e.g. "
            f"`git fetch origin {ref}`)"
        ) from exc
    if not re.fullmatch(r"[0-9a-f]{40}|[0-9a-f]{64}", commit):
        raise UsageError(f"`base` {ref!r} names no commit of this repository")
    return commit


def export_revision(repo: Path, commit: str, into: Path, home: Path) -> list[str]:
    """Write the tree of ``commit`` (a full id) into the empty folder ``into``.

    At most :data:`MAX_EXPORT_FILES` entries and :data:`MAX_EXPORT_BYTES`;
    extracted with tarfile's ``data`` filter (PEP 706), which refuses absolute
    names, ``..``, links pointing out of ``into`` and special files.  A refused
    entry is left out (the revision's other files are all there); returns what
    was left out, one line each, for the caller to say.
    """
    if not re.fullmatch(r"[0-9a-f]{40}|[0-9a-f]{64}", commit):
        raise UsageError(f"not a commit id: {commit[:80]!r}")
    if not hasattr(tarfile, "data_filter"):  # Python 3.11.4 added it
        raise UsageError("`base` needs Python 3.11.4 or newer (tarfile's data filter)")
    with subprocess.Popen(
        _git(repo, home, "archive", "--format=tar", commit),
        env=_environment(home),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        stdin=subprocess.DEVNULL,
        process_group=0,  # git and what it starts (a wrapper's children) die together
    ) as proc:
        assert proc.stdout is not None and proc.stderr is not None
        try:
            try:
                skipped = _extract(proc.stdout, into)
            finally:
                proc.stdout.close()  # a git still writing stops at once (SIGPIPE)
            proc.wait(timeout=GIT_SECONDS)
        except tarfile.ReadError as exc:
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=10)  # git said why on stderr and exited
            _kill(proc)
            said = proc.stderr.read().decode("utf-8", "replace").strip().splitlines()
            raise UsageError(f"git archive: {(said or [str(exc)])[0][:200]}", path=repo) from exc
        except subprocess.TimeoutExpired as exc:
            _kill(proc)
            raise InputError(f"git archive took more than {GIT_SECONDS} s", path=repo) from exc
        except BaseException:
            _kill(proc)  # any other failure, or a signal unwinding: git is not waited for
            raise
        if proc.returncode != 0:
            said = proc.stderr.read().decode("utf-8", "replace").strip().splitlines()
            raise UsageError(f"git archive: {(said or ['failed'])[0][:200]}", path=repo)
    return skipped


def _kill(proc: subprocess.Popen[bytes]) -> None:
    """Kill git's process group: git, and any process a wrapper on PATH started for it."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(proc.pid, signal.SIGKILL)


def _extract(stream: IO[bytes], into: Path) -> list[str]:
    """Members of a tar stream into ``into``, within the bounds, each through the filter;
    returns the members the filter refused (each left out), as ``name: reason``."""
    skipped: list[str] = []
    total = files = 0
    with tarfile.open(fileobj=stream, mode="r|") as archive:
        for member in archive:
            files += 1
            total += max(member.size, 0)
            if files > MAX_EXPORT_FILES or total > MAX_EXPORT_BYTES:
                raise InputError(
                    f"the base revision holds more than {MAX_EXPORT_FILES:,} files or "
                    f"{MAX_EXPORT_BYTES >> 30} GiB; `base` cannot audit it"
                )
            try:
                archive.extract(member, into, filter="data")
            except tarfile.FilterError as exc:
                # A link to an absolute path is common (a tool's config, a vendored folder)
                # and never needed to audit: left out, not written, and said.
                skipped.append(safe_text(str(exc))[:200])
    return skipped
