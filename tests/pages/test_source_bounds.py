"""Sources from a pull request: URLs that do not parse, IPv6 loopback, and one bound on the
pages, stories and URLs of a run."""

from __future__ import annotations

import http.server
import json
import os
import socket
import threading
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.browser import ENGINES
from alpha_audit.cli import app
from alpha_audit.errors import InputError, UsageError
from alpha_audit.pages import FolderSource, RenderConfig, audit_pages, sources
from alpha_audit.pages.sources import StorybookSource, UrlSource, targets


@pytest.mark.parametrize(
    ("url", "said"),
    [
        ("http://localhost:99999/iframe.html", "Port out of range"),
        ("http://localhost:abc/", "could not be cast"),
        ("http://[::1/", "Invalid IPv6 URL"),
        ("http://[::1]:0/", "not a loopback page"),
        ("http://127.0.0.1/", "not a loopback page"),  # no port
        ("https://localhost:6006/", "not a loopback page"),
        ("http://example.com:80/", "not a loopback page"),
        ("http://127.0.0.2:80/", "not a loopback page"),
        ("http://user:pw@localhost:6006/", "user name or password"),
    ],
)
def test_a_url_that_is_no_loopback_page_is_exit_2_naming_it(url, said, tmp_path, monkeypatch):
    (tmp_path / ".git").mkdir()
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(app, ["render", url])
    assert result.exit_code == 2, result.output
    errors = [line for line in result.output.splitlines() if "error" in line]
    assert len(errors) == 1 and repr(url) in errors[0] and said in errors[0], result.output


def test_an_empty_source_is_refused(tmp_path, monkeypatch):
    (tmp_path / ".git").mkdir()
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(app, ["render", ""])
    assert result.exit_code == 2 and "an empty source" in result.output, result.output


def _storybook(folder: Path, entries: dict[str, dict[str, object]]) -> Path:
    folder.mkdir(parents=True)
    (folder / "iframe.html").write_text("<html></html>")
    (folder / "index.json").write_text(json.dumps({"v": 5, "entries": entries}))
    return folder


def test_a_storybook_of_more_stories_than_the_bound_is_refused_before_any_is_read(tmp_path):
    count = sources.MAX_PAGES + 1
    # Each entry would be refused if it were read (an id with a newline): the bound comes first.
    entries = {f"s{k}": {"type": "story", "id": f"x\n{k}"} for k in range(count)}
    build = _storybook(tmp_path / "sb", entries)
    with pytest.raises(InputError, match=f"lists {count:,} entries; a run audits at most") as info:
        targets([StorybookSource(build)])
    assert info.value.path == build / "index.json"


def test_pages_stories_and_urls_share_one_bound(tmp_path, monkeypatch):
    monkeypatch.setattr(sources, "MAX_PAGES", 5)
    build = _storybook(
        tmp_path / "sb",
        {f"a--{k}": {"type": "story", "id": f"a--{k}", "title": "A", "name": str(k)}
         for k in range(3)},
    )  # fmt: skip
    pages = tmp_path / "pages"
    pages.mkdir()
    for k in range(2):
        (pages / f"{k}.html").write_text("<p>x</p>")
    (pages / ".hidden.html").write_text("<p>never served, so no page</p>")
    url = UrlSource("http://localhost:1/a")
    folder, storybook = FolderSource(pages, "*.html"), StorybookSource(build)
    assert len(targets([folder, storybook])) == 5  # the dot file is no page
    with pytest.raises(UsageError, match="more than 5 pages and stories"):
        targets([folder, storybook, url])
    with pytest.raises(UsageError, match="more than 5 pages and stories"):
        targets([storybook, url, url, url])
    with pytest.raises(UsageError, match="matches more than 1 files"):
        targets([storybook, url, folder])


@pytest.mark.parametrize(
    ("field", "value", "said"),
    [("title", "T" * 201, "longer than 200"), ("name", "n\x1b[2J", r"U\+001B")],
)
def test_story_titles_and_names_pass_the_name_policy(tmp_path, field, value, said):
    build = _storybook(
        tmp_path / "sb", {"a--b": {"type": "story", "id": "a--b", "title": "A", field: value}}
    )
    with pytest.raises(InputError, match=said) as info:
        targets([StorybookSource(build)])
    assert info.value.key == f"a--b.{field}"


def _ipv6_loopback() -> bool:
    try:
        with socket.socket(socket.AF_INET6, socket.SOCK_STREAM) as probe:
            probe.bind(("::1", 0))
    except OSError:
        return False
    return True


class _V6(http.server.ThreadingHTTPServer):
    address_family = socket.AF_INET6


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: object) -> None:
        return


@pytest.mark.parametrize("name", list(ENGINES))
def test_an_ipv6_loopback_page_is_audited_in_every_engine(name, tmp_path):
    cls = ENGINES[name]
    if cls.find() is None:
        if os.environ.get("CI"):
            pytest.fail(f"{cls.LABEL} not installed", pytrace=False)
        pytest.skip(f"{cls.LABEL} not installed: {cls.INSTALL_HINT}")
    if not _ipv6_loopback():
        pytest.skip("this machine has no IPv6 loopback (::1)")
    (tmp_path / ".git").mkdir()
    (tmp_path / "index.html").write_text(
        "<!doctype html><body style='margin:0;background:#fff'><svg width=24 height=24>"
        "<rect width=24 height=24 fill='#333333'/></svg>",
        encoding="utf-8",
    )
    server = _V6(("::1", 0), lambda *a: _Quiet(*a, directory=str(tmp_path)))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        url = f"http://[::1]:{server.server_address[1]}/index.html"
        config = RenderConfig((UrlSource(url),), root=tmp_path, engines=(name,), workers=1)
        result = audit_pages(config)
    finally:
        server.shutdown()
        server.server_close()
    assert not result.run.problems, result.run.problems
    assert [p.drawn for p in result.paints] == ["#333333"]
    assert not [b.url for b in result.run.blocked if "[::1]" in b.url]  # not sent to the proxy
