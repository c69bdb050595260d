"""The stderr line for blocked requests names the hosts, a few at most, and no raw text."""

from __future__ import annotations

from dataclasses import replace

from alpha_audit.observed import BlockedRequest
from alpha_audit.render.pages import blocked_line as blocked_summary


def _blocked(*urls: str) -> list[BlockedRequest]:
    """Requests Chromium refused; its own hosts marked as the run marks them."""
    own = {"update.googleapis.com", "accounts.google.com"}
    out = [BlockedRequest("stories/a", "dark", "chromium", u) for u in urls]
    return [replace(b, own="Chromium") if b.host in own else b for b in out]


def test_one_host_is_named_once_however_many_requests() -> None:
    line = blocked_summary(_blocked(*(f"http://fonts.example/{k}.woff2" for k in range(7))))
    assert line.startswith("7 requests ")
    assert "to fonts.example (" in line


def test_many_hosts_are_cut_to_three_with_a_count() -> None:
    line = blocked_summary(_blocked(*(f"https://h{k}.example/x" for k in range(5))))
    assert "to h0.example, h1.example, h2.example and 2 more hosts (" in line


def test_https_tunnels_are_named_by_host() -> None:
    line = blocked_summary(_blocked("tracker.example:443"))
    assert "to tracker.example (" in line


def test_one_host_over_http_and_https_is_one_host() -> None:
    """Chromium's own update check goes out over both (seen on a real Storybook run)."""
    line = blocked_summary(
        _blocked("https://update.googleapis.com:443", "http://update.googleapis.com/service/u")
    )
    assert line.startswith("2 requests ")
    assert "to update.googleapis.com (" in line


def test_an_unusual_port_is_named() -> None:
    line = blocked_summary(_blocked("http://cdn.example:8080/x.js", "cdn.example:443"))
    assert "to cdn.example and cdn.example:8080 (" in line


def test_chromium_s_own_hosts_are_said_to_be_its_own() -> None:
    """A page that requests nothing still shows Chromium's update and sign-in checks."""
    line = blocked_summary(
        _blocked("https://update.googleapis.com:443", "https://accounts.google.com:443")
    )
    assert line.endswith(
        "to accounts.google.com and update.googleapis.com (every one in the JSON report; "
        "Chromium asks accounts.google.com and update.googleapis.com by itself, whatever the page)"
    )


def test_a_host_another_engine_asked_is_not_called_chromium_s_own() -> None:
    firefox = BlockedRequest("stories/a", "dark", "firefox", "https://accounts.google.com/x")
    line = blocked_summary([*_blocked("https://update.googleapis.com:443"), firefox])
    assert "Chromium asks update.googleapis.com by itself" in line
    assert "asks accounts" not in line and "and update.googleapis.com by itself" not in line
    assert "by itself" not in blocked_summary(_blocked("https://fonts.example/a.css"))
