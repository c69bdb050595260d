"""The page server answers a page from a pull request with its own source folder only.

A project holds what CI keeps beside a checkout (``.git/config`` with the job's token,
``.env``, a file outside the project) and a source folder full of ways to reach them
(links out, links to dot files, a dot folder).  Every mount, a URL source's included, is
asked for each of them in every path form a client can send; counted: every answer is
404 but the two files that are the pages, and no answer holds a secret.  Then a page in
a real browser asks the same, writes what it read into its icon's DOM id, and the id
says it read nothing it should not.
"""

from __future__ import annotations

import http.client
import http.server
import threading
from pathlib import Path
from urllib.parse import quote

import pytest

from alpha_audit.browser import Chromium
from alpha_audit.browser.server import PageServer
from alpha_audit.pages import FolderSource, RenderConfig, audit_pages
from alpha_audit.pages.sources import UrlSource

SECRET = "SECRET-"  # every file no page may read holds it
PAGES = {"a.html": "OK-a", "sub/b.html": "OK-b"}  # what the folder serves
# What a page may try to reach, as paths below a mount: dot files and folders, the
# project above, links out of the folder and to dot files inside it.
TARGETS = (
    ".git/config",
    ".env",
    ".hidden/x.html",
    "sub/.env",
    "../.git/config",
    "../.env",
    "../private.txt",
    "../../outside.txt",
    "link-git",
    "link-env",
    "link-up/.git/config",
    "link-up/private.txt",
    "link-abs",
    "link-dot",
    "link-outside",
    "sub/../.env",
    "./.env",
    ".",
    "..",
)


def _forms(target: str) -> set[str]:
    """``target`` in every spelling a request may use for it."""
    encoded_all = "".join(f"%{b:02x}" for b in target.encode())
    return {
        target,
        quote(target, safe=""),  # %2F between the parts
        target.replace(".", "%2e"),
        target.replace(".", "%2E").replace("/", "%2f"),
        encoded_all,
        target.replace("/", "\\"),
        target.replace("/", "%5c"),
        target.replace("/", "//"),
        "./" + target,
        target + "/",
        target + "%00.html",
        target + "?x=1#frag",
    }


def _mount_forms(mount: int) -> list[str]:
    """Ways of naming mount ``mount`` itself, and a few that are no mount."""
    return [
        f"/{mount}/",
        f"/%3{mount}/" if mount < 10 else f"/{mount}/",
        f"//{mount}/",
        f"/0{mount}/",
        f"/{mount}{quote(chr(0xB2))}/",  # SUPERSCRIPT TWO: str.isdigit() says yes
        f"/{quote(chr(0x660))}{mount}/",  # ARABIC-INDIC DIGIT ZERO: int() reads it
    ]


ABSOLUTE = (
    "/etc/hostname",
    "//etc/hostname",
    "/0//etc/hostname",
    "/0/%2fetc%2fhostname",
    "/0/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/hostname",
    "/0/..%2f..%2f..%2f..%2fetc%2fhostname",
    "/0/..\\..\\..\\..\\etc\\hostname",
    "/0/%c0%ae%c0%ae/.env",  # overlong UTF-8 dots
    "/-1/.env",
    "/99999999999/.env",
    "http://127.0.0.1/0/.env",  # the absolute form a proxy is sent
)


@pytest.fixture
def tree(tmp_path: Path) -> tuple[Path, Path]:
    """``(project root, source folder)``: secrets around a folder of two pages."""
    root = tmp_path / "project"
    (root / ".git").mkdir(parents=True)
    (root / ".git" / "config").write_text(f"{SECRET}git-token", encoding="utf-8")
    (root / ".env").write_text(f"{SECRET}env", encoding="utf-8")
    (root / "private.txt").write_text(f"{SECRET}project-file", encoding="utf-8")
    (tmp_path / "outside.txt").write_text(f"{SECRET}outside", encoding="utf-8")
    site = root / "site"
    (site / "sub").mkdir(parents=True)
    (site / ".hidden").mkdir()
    for name, text in PAGES.items():
        (site / name).write_text(text, encoding="utf-8")
    (site / ".hidden" / "x.html").write_text(f"{SECRET}dot-folder", encoding="utf-8")
    (site / ".env").write_text(f"{SECRET}site-env", encoding="utf-8")
    (site / "sub" / ".env").write_text(f"{SECRET}sub-env", encoding="utf-8")
    (site / "link-git").symlink_to(root / ".git" / "config")
    (site / "link-env").symlink_to("../.env")
    (site / "link-up").symlink_to("..")
    (site / "link-abs").symlink_to("/etc/hostname")
    (site / "link-dot").symlink_to(".env")  # inside the folder, to a dot file
    (site / "link-outside").symlink_to(tmp_path / "outside.txt")
    return root, site


def _get(address: str, path: str) -> tuple[int, bytes]:
    """One raw request (``http.client`` sends the path as given, no normalisation)."""
    host, port = address.split(":")
    conn = http.client.HTTPConnection(host, int(port), timeout=10)
    try:
        conn.putrequest("GET", path, skip_accept_encoding=True)
        conn.endheaders()
        response = conn.getresponse()
        return response.status, response.read()
    finally:
        conn.close()


def test_every_mount_and_path_form_serves_the_folders_pages_and_nothing_else(tree):
    root, site = tree
    mounts = [site, None, root]  # the folder, a URL source (no mount), the project root
    with PageServer(mounts, root) as server:
        served: list[tuple[str, bytes]] = []
        refused = 0
        requests = [f"{m}{f}" for n in range(4) for m in _mount_forms(n)
                    for t in TARGETS for f in _forms(t)]  # fmt: skip
        requests += list(ABSOLUTE)
        requests += [f"/{n}/{quote(page, safe='')}" for n in range(4) for page in PAGES]
        for path in requests:
            status, body = _get(server.address, path)
            assert SECRET.encode() not in body, (path, body)
            if status == 200:
                served.append((path, body))
            else:
                assert status == 404, (path, status)
                refused += 1
    # Only the two pages, through their own mount (the root, mount 2, has them under
    # site/, which no request here names).
    assert served == [("/0/a.html", b"OK-a"), ("/0/sub%2Fb.html", b"OK-b")], served
    assert refused == len(requests) - 2


def test_the_project_root_as_a_source_serves_no_dot_file_and_no_link_out(tree):
    root, _ = tree
    with PageServer([root], root) as server:
        for path in (
            "/0/.git/config",
            "/0/.env",
            "/0/site/.env",
            "/0/site/link-git",
            "/0/site/link-outside",
            "/0/site/link-dot",
            "/0/site/.hidden/x.html",
        ):
            assert _get(server.address, path)[0] == 404, path  # fmt: skip
        assert _get(server.address, "/0/site/a.html") == (200, b"OK-a")
        assert _get(server.address, "/0/private.txt")[0] == 200  # a plain file of the folder


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: object) -> None:
        return


def _probe_page(mounts: int) -> str:
    """A page that asks every mount for every target (synchronous XHR: done before load)
    and writes what it got into its icon's id: ``probe-<pages read>-<secrets read>``."""
    paths = [f"/{n}/{f}" for n in range(mounts) for t in TARGETS for f in _forms(t)]
    paths += [p for p in ABSOLUTE if p.startswith("/")]
    paths += [f"/{n}/{p}" for n in range(mounts) for p in PAGES]
    import json

    return (
        "<!doctype html><body>"
        '<svg id="icon" width="24" height="24" viewBox="0 0 24 24">'
        '<rect x="4" y="4" width="16" height="16" fill="#333"/></svg><script>'
        f"let pages = 0, secrets = 0; for (const path of {json.dumps(paths)}) {{"
        " const xhr = new XMLHttpRequest();"
        " try { xhr.open('GET', path, false); xhr.send(); } catch (e) { continue; }"
        " if (xhr.status === 200 && xhr.responseText.startsWith('OK-')) pages += 1;"
        f" if (xhr.responseText.includes({json.dumps(SECRET)})) secrets += 1; }}"
        " document.getElementById('icon').id = `probe-${pages}-${secrets}`;"
        "</script>"
    )


def test_a_page_in_a_browser_reads_nothing_beyond_its_folder(tree):
    if Chromium.find() is None:
        pytest.skip(f"Chromium not installed: {Chromium.INSTALL_HINT}")
    root, site = tree
    (site / "probe.html").write_text(_probe_page(2), encoding="utf-8")
    # A page served by another loopback server: a URL source, which gets no mount.
    elsewhere = root / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "index.html").write_text("<!doctype html><p>other server</p>", "utf-8")
    server = http.server.ThreadingHTTPServer(
        ("127.0.0.1", 0), lambda *a: _Quiet(*a, directory=str(elsewhere))
    )
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        url = f"http://127.0.0.1:{server.server_address[1]}/index.html"
        config = RenderConfig(
            (FolderSource(site, "probe.html"), UrlSource(url)), root=root, workers=1
        )
        result = audit_pages(config)
    finally:
        server.shutdown()
        server.server_close()
    paths = [p.dom_path for p in result.paints]
    # Mount 0 served its two pages (and itself, probe.html, is not counted: no "OK-");
    # mount 1 (the URL source) served nothing; no answer held a secret.
    assert paths == ["svg#probe-2-0"], paths
    assert not result.run.problems
