"""Fetch (once) the real design-token packages that tests/load/tokens compares with a browser.

``npm pack NAME@VERSION`` downloads the package's tarball from the npm registry
(no install, no scripts run); it is unpacked into ``$ALPHA_AUDIT_TEST_CACHE``
(default ``~/.cache/alpha-audit-tests``) under ``tokens/<name>-<version>/``,
outside the repository, and never fetched again.  Nothing from it is committed.

    python tools/token_fixtures.py            fetch every package the suite uses
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tarfile
from pathlib import Path

# (package, version): the pinned releases the suite compares, mode by mode.
PACKAGES: tuple[tuple[str, str], ...] = (
    ("@patternfly/patternfly", "6.6.1"),
    ("@mantine/core", "9.8.1"),
    ("@carbon/styles", "1.116.0"),
    ("@twilio-paste/design-tokens", "10.15.0"),
    ("@primer/primitives", "11.10.0"),
    ("@tokens-studio/sd-transforms", "2.0.3"),
)


def cache_root() -> Path:
    """Where packages are kept (outside the repository)."""
    configured = os.environ.get("ALPHA_AUDIT_TEST_CACHE")
    base = Path(configured) if configured else Path.home() / ".cache" / "alpha-audit-tests"
    return base / "tokens"


def fetch(package: str, version: str) -> Path:
    """The unpacked ``package/`` folder of ``package@version``, fetched first when missing."""
    folder = cache_root() / f"{package.replace('@', '').replace('/', '-')}-{version}"
    if (folder / "package" / "package.json").is_file():
        return folder / "package"
    npm = shutil.which("npm")
    if npm is None:
        raise RuntimeError("npm is not installed: it fetches the real token packages")
    work = cache_root() / f".{folder.name}-{os.getpid()}"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    try:
        out = subprocess.run(
            [npm, "pack", f"{package}@{version}", "--silent", "--ignore-scripts"],
            cwd=work,
            check=True,
            capture_output=True,
            text=True,
            timeout=300,
        ).stdout.split()
        with tarfile.open(work / out[-1]) as tar:
            tar.extractall(work / "unpacked", filter="data")
        if folder.exists():  # fetched meanwhile by another worker
            shutil.rmtree(work, ignore_errors=True)
        else:
            (work / "unpacked").rename(folder)
            shutil.rmtree(work, ignore_errors=True)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return folder / "package"


if __name__ == "__main__":
    try:
        for name, version in PACKAGES:
            print(fetch(name, version))
    except (RuntimeError, subprocess.SubprocessError) as exc:
        print(f"token fixtures: {exc}", file=sys.stderr)
        sys.exit(1)
