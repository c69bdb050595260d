"""The SARIF 2.1.0 JSON schema for the tests, fetched once from the npm registry and cached.

The OASIS schema (``sarif-schema-2.1.0.json``, errata 01) is published under
the OASIS IPR policy, not a licence that lets us ship it, and no registry
package carries it.  Microsoft's ``@microsoft/jest-sarif`` (MIT) ships the
2.1.0 release-candidate schema it validates against,
``lib/schemas/sarif-2.1.0-rtm.5.json``: the standard's schema but for one
constraint errata 01 added, which :func:`sarif_schema` adds back (a
``region`` must have ``startLine``, ``charOffset`` or ``byteOffset``); the
other differences are a ``type: string`` beside enums, ``runs`` allowing
``null`` and a looser language-tag pattern, none of which loosens what a log
may hold.  Cached in ``$ALPHA_AUDIT_TEST_CACHE`` (default
``~/.cache/alpha-audit-tests``) as ``sarif-2.1.0-rtm.5.json``.

    python tools/sarif_schema.py    # fetch (if needed) and print where it is
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path
from typing import Any

PACKAGE = "@microsoft/jest-sarif@1.0.0-beta.0"
MEMBER = "package/lib/schemas/sarif-2.1.0-rtm.5.json"
# OASIS SARIF 2.1.0 errata 01 (sarif-schema-2.1.0.json), definitions.region.anyOf.
REGION_ANY_OF = [
    {"required": ["startLine"]},
    {"required": ["charOffset"]},
    {"required": ["byteOffset"]},
]


def cache_root() -> Path:
    configured = os.environ.get("ALPHA_AUDIT_TEST_CACHE")
    return Path(configured) if configured else Path.home() / ".cache" / "alpha-audit-tests"


def schema_file() -> Path:
    """The cached schema file, fetched with ``npm pack`` when missing."""
    target = cache_root() / "sarif-2.1.0-rtm.5.json"
    if target.is_file():
        return target
    npm = shutil.which("npm")
    if npm is None:
        raise RuntimeError("npm is needed to fetch the SARIF schema (@microsoft/jest-sarif)")
    with tempfile.TemporaryDirectory() as work:
        subprocess.run(
            [npm, "pack", PACKAGE, "--silent"],
            cwd=work,
            check=True,
            capture_output=True,
            timeout=300,
        )
        (tarball,) = Path(work).glob("*.tgz")
        with tarfile.open(tarball) as archive:
            member = archive.extractfile(MEMBER)
            if member is None:
                raise RuntimeError(f"{PACKAGE} has no {MEMBER}")
            data = member.read()
    json.loads(data)  # a schema, not an error page
    target.parent.mkdir(parents=True, exist_ok=True)
    partial = target.with_suffix(f".{os.getpid()}.tmp")
    partial.write_bytes(data)
    partial.replace(target)
    return target


def sarif_schema() -> dict[str, Any]:
    """The SARIF 2.1.0 schema (draft 4), with errata 01's constraint on regions."""
    schema: dict[str, Any] = json.loads(schema_file().read_text(encoding="utf-8"))
    schema["definitions"]["region"]["anyOf"] = REGION_ANY_OF
    return schema


if __name__ == "__main__":
    try:
        print(schema_file())
    except (RuntimeError, subprocess.CalledProcessError) as exc:
        print(f"sarif schema: {exc}", file=sys.stderr)
        sys.exit(1)
