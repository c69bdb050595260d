"""Build (once) the real Storybook and static page that tests/pages and the benchmark audit.

The sources are small files in ``tests/pages/site`` (package.json and its lock,
``.storybook/``, ``stories/``, ``page/``); ``npm ci`` brings Storybook, Vite,
lucide-static and tailwindcss from the npm registry.  The result is cached in
``$ALPHA_AUDIT_TEST_CACHE`` (default ``~/.cache/alpha-audit-tests``) under a key
that hashes every source file, so it is built again only when they change:

    site-<key>/storybook-static/   the Storybook build (index.json, iframe.html ...)
    site-<key>/page/               index.html + theme.css (Tailwind v4 colours)
    site-<key>/node_modules/       what npm installed (lucide-static's SVGs among it)

``make test`` runs this before the suite; run it by hand to see where the build is.
``extra`` files (name -> text, written under ``stories/``) make a variant with its
own key, as the benchmark's many-story Storybook.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from collections.abc import Mapping
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SITE = REPO / "tests" / "pages" / "site"
SOURCES = ("package.json", "package-lock.json", ".storybook", "stories", "page")


def cache_root() -> Path:
    """Where builds are kept (outside the repository)."""
    configured = os.environ.get("ALPHA_AUDIT_TEST_CACHE")
    return Path(configured) if configured else Path.home() / ".cache" / "alpha-audit-tests"


def _files() -> list[Path]:
    out: list[Path] = []
    for name in SOURCES:
        path = SITE / name
        out += sorted(p for p in path.rglob("*") if p.is_file()) if path.is_dir() else [path]
    return out


def site_key(extra: Mapping[str, str] | None = None) -> str:
    """16 hex digits of SHA-256 over every source file (and ``extra``)."""
    digest = hashlib.sha256()
    for path in _files():
        digest.update(path.relative_to(SITE).as_posix().encode() + b"\0" + path.read_bytes())
    for name, text in sorted((extra or {}).items()):
        digest.update(name.encode() + b"\0" + text.encode())
    return digest.hexdigest()[:16]


def build_site(extra: Mapping[str, str] | None = None, *, quiet: bool = True) -> Path:
    """The cached build for the current sources, built first when missing."""
    key = site_key(extra)
    target = cache_root() / f"site-{key}"
    if (target / "storybook-static" / "index.json").is_file() and (
        target / "page" / "index.html"
    ).is_file():
        return target
    npm = shutil.which("npm")
    if npm is None:
        raise RuntimeError("npm is not installed: Node.js 20.19+ and npm build the test Storybook")
    work = cache_root() / f".site-{key}-{os.getpid()}"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    try:
        for name in SOURCES:
            source = SITE / name
            if source.is_dir():
                shutil.copytree(source, work / name)
            else:
                shutil.copy2(source, work / name)
        for name, text in (extra or {}).items():
            (work / "stories" / name).write_text(text, encoding="utf-8")
        out = subprocess.DEVNULL if quiet else None
        env = {**os.environ, "STORYBOOK_DISABLE_TELEMETRY": "1", "CI": "1"}
        steps = (
            [npm, "ci", "--no-audit", "--no-fund", "--loglevel=error"],
            [npm, "run", "build-storybook"],
            [npm, "run", "build-page", "--", "page-out"],
        )
        for step in steps:
            subprocess.run(step, cwd=work, check=True, stdout=out, env=env, timeout=900)
        shutil.rmtree(work / "page")
        (work / "page-out").rename(work / "page")
        if target.exists():  # built meanwhile by another run
            shutil.rmtree(work, ignore_errors=True)
        else:
            work.rename(target)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return target


if __name__ == "__main__":
    try:
        print(build_site(quiet=False))
    except (RuntimeError, subprocess.CalledProcessError) as exc:
        print(f"page fixtures: {exc}", file=sys.stderr)
        sys.exit(1)
