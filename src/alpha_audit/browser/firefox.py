"""Firefox (ESR) over WebDriver BiDi on a loopback WebSocket (the ``websockets`` client).

Firefox is started headless with a fresh profile and
``--remote-debugging-port=0``; it picks a free port and prints
``WebDriver BiDi listening on ws://127.0.0.1:PORT`` on stderr.  Commands
follow the W3C WebDriver BiDi draft: ``session.new``,
``browsingContext.navigate`` (waiting for ``complete``) and
``script.evaluate`` with ``awaitPromise``.  Without an X server, WebGL needs
EGL (``MOZ_WEBGL_FORCE_EGL=1``) and the ``webgl.force-enabled`` pref.
"""

from __future__ import annotations

import base64
import binascii
import contextlib
import json
import os
import re
import shutil
import time
from pathlib import Path
from typing import Any

from websockets.exceptions import WebSocketException
from websockets.sync.client import ClientConnection, connect

from alpha_audit.browser.interface import (
    Browser,
    BrowserError,
    Clip,
    Installation,
    JSONValue,
    deadline_after,
    time_left,
)

__all__ = ["Firefox"]

# A message larger than this is refused rather than buffered (our pages send a few tens of MB).
MAX_MESSAGE_BYTES = 512 * 1024 * 1024
_LISTENING = re.compile(rb"WebDriver BiDi listening on (ws://127\.0\.0\.1:\d+)")
# Profile preferences (about:config names).  WebGL without a GPU or display, and no
# background traffic: the remote agent's recommended prefs already stop most of it.
_PREFS = {
    "webgl.force-enabled": True,
    "webgl.disabled": False,
    "browser.shell.checkDefaultBrowser": False,
    "browser.startup.homepage": "about:blank",
    "browser.startup.page": 0,
    "app.update.enabled": False,
    "app.normandy.enabled": False,
    "datareporting.policy.dataSubmissionEnabled": False,
    "datareporting.healthreport.uploadEnabled": False,
    "toolkit.telemetry.enabled": False,
    "browser.safebrowsing.malware.enabled": False,
    "browser.safebrowsing.phishing.enabled": False,
    "extensions.update.enabled": False,
    "network.captive-portal-service.enabled": False,
    "network.connectivity-service.enabled": False,
}


class Firefox(Browser):
    """Headless Firefox ESR (Debian's ``firefox-esr``, or ``$ALPHA_AUDIT_FIREFOX``)."""

    NAME = "firefox"
    LABEL = "Firefox"
    ISOLATED_SCRIPTS = True
    INSTALL_HINT = (
        "install Debian's packages (`sudo apt-get install -y firefox-esr libegl1 libegl-mesa0 "
        "libgl1-mesa-dri`, or `make browser` as root), or point ALPHA_AUDIT_FIREFOX at a binary"
    )

    @classmethod
    def find(cls) -> Installation | None:
        """``$ALPHA_AUDIT_FIREFOX`` or ``firefox-esr``/``firefox`` on ``PATH``."""
        configured = os.environ.get("ALPHA_AUDIT_FIREFOX")
        if configured:
            return Installation(cls.NAME, Path(configured)) if Path(configured).is_file() else None
        for name in ("firefox-esr", "firefox"):
            if found := shutil.which(name):
                return Installation(cls.NAME, Path(found))
        return None

    def _start(self) -> None:
        profile = self.workdir / "profile"
        profile.mkdir()
        prefs = {**_PREFS, **self._launch_prefs()}
        (profile / "user.js").write_text(
            "".join(f"user_pref({json.dumps(k)}, {json.dumps(v)});\n" for k, v in prefs.items()),
            encoding="utf-8",
        )
        log = self.workdir / "stderr.log"
        env = self.child_env(
            {
                **os.environ,
                "MOZ_WEBGL_FORCE_EGL": "1",
                "MOZ_HEADLESS": "1",
                "MOZ_CRASHREPORTER_DISABLE": "1",  # no crash reporter, no "Crash Reports"
            }
        )
        env.pop("DISPLAY", None)  # headless and EGL: never an X server that is not ours
        with log.open("wb") as stderr:  # a file, never a pipe nobody drains
            self.processes.start(
                [
                    str(self.installation.binary),
                    "--headless",
                    "--no-remote",
                    "--profile",
                    str(profile),
                    "--remote-debugging-port=0",
                    "about:blank",
                ],
                env=env,
                stderr=stderr.fileno(),
            )
        deadline = deadline_after(self.timeout)
        while not (match := _LISTENING.search(log.read_bytes())):
            time_left(deadline, "Firefox (no WebDriver BiDi line on stderr)")
            time.sleep(0.02)
        self._connection = contextlib.ExitStack()
        self._socket = self._connection.enter_context(
            _connect(match.group(1).decode() + "/session", self.timeout)
        )
        self._next_id = 0
        session = self._call("session.new", {"capabilities": {}})
        caps = session.get("capabilities", {})
        self.version = f"{caps.get('browserName', 'firefox')} {caps.get('browserVersion', '')}"
        self._context = self._call("browsingContext.getTree", {})["contexts"][0]["context"]

    def _launch_prefs(self) -> dict[str, JSONValue]:
        """The colour scheme and, for untrusted pages, the proxy (about:config names)."""
        prefs: dict[str, JSONValue] = {}
        if self.options.color_scheme is not None:
            dark = self.options.color_scheme == "dark"
            prefs["layout.css.prefers-color-scheme.content-override"] = 0 if dark else 1
            prefs["ui.systemUsesDarkTheme"] = 1 if dark else 0
        prefs["ui.prefersReducedMotion"] = 1
        if self.options.proxy is not None:
            host, _, port = self.options.proxy.rpartition(":")
            prefs.update(
                {
                    "network.proxy.type": 1,  # manual
                    "network.proxy.http": host,
                    "network.proxy.http_port": int(port),
                    "network.proxy.ssl": host,
                    "network.proxy.ssl_port": int(port),
                    "network.proxy.no_proxies_on": ", ".join(self.options.direct),
                    "network.proxy.allow_hijacking_localhost": True,  # loopback via proxy too
                    "network.proxy.socks_remote_dns": True,
                    "network.dns.disablePrefetch": True,
                    "network.prefetch-next": False,
                    "network.http.speculative-parallel-limit": 0,
                    "media.peerconnection.enabled": False,  # WebRTC's UDP ignores proxies
                }
            )
        return prefs

    def _call(
        self, method: str, params: dict[str, Any], *, timeout: float | None = None
    ) -> dict[str, Any]:
        self._next_id += 1
        deadline = deadline_after(timeout or self.timeout)
        try:
            self._socket.send(json.dumps({"id": self._next_id, "method": method, "params": params}))
            while True:
                message = json.loads(self._socket.recv(time_left(deadline, self.LABEL)))
                if message.get("id") == self._next_id:
                    break  # anything else is an event, which we never subscribe to
        except TimeoutError as exc:
            raise BrowserError(f"{self.LABEL} {method} did not answer in time") from exc
        except (OSError, WebSocketException) as exc:
            raise BrowserError(
                f"{self.LABEL} {method}: the WebDriver BiDi connection: {exc}"
            ) from exc
        if message.get("type") == "error":
            raise BrowserError(f"Firefox {method}: {message.get('message')}")
        result: dict[str, Any] = message["result"]
        return result

    def _navigate(self, url: str) -> None:
        self._call(
            "browsingContext.navigate", {"context": self._context, "url": url, "wait": "complete"}
        )

    def _evaluate_text(self, expression: str, timeout: float, isolated: bool) -> str:
        target: dict[str, str] = {"context": self._context}
        if isolated:
            target["sandbox"] = "alpha-audit"
        reply = self._call(
            "script.evaluate",
            {
                "expression": expression,
                "target": target,
                "awaitPromise": True,
                "resultOwnership": "none",
            },
            timeout=timeout,
        )
        if reply.get("type") == "exception":
            details = reply.get("exceptionDetails", {})
            raise BrowserError(f"script error in Firefox: {details.get('text')}")
        value: str = reply["result"].get("value")  # JSON text (evaluate() refuses anything else)
        return value

    def _set_viewport(self, width: int, height: int, scale: float) -> None:
        self._call(
            "browsingContext.setViewport",
            {
                "context": self._context,
                "viewport": {"width": width, "height": height},
                "devicePixelRatio": scale,
            },
        )

    def _screenshot(self, clip: Clip | None) -> bytes:
        params: dict[str, Any] = {
            "context": self._context,
            "origin": "viewport",
            "format": {"type": "image/png"},
        }
        if clip is not None:
            params["clip"] = {"type": "box", "x": clip.x, "y": clip.y}
            params["clip"].update({"width": clip.width, "height": clip.height})
        reply = self._call("browsingContext.captureScreenshot", params)
        try:
            return base64.b64decode(reply["data"], validate=True)
        except (KeyError, TypeError, binascii.Error) as exc:
            raise BrowserError("Firefox returned no screenshot") from exc

    def _shutdown(self) -> None:
        try:
            self._call("browser.close", {}, timeout=5)
        finally:
            self._connection.close()


def _connect(url: str, timeout: float) -> ClientConnection:
    """The BiDi WebSocket on loopback: no proxy from the environment, no size cap of 1 MiB.

    Screenshots and pixel batches arrive as one message of tens of MB; a
    message above :data:`MAX_MESSAGE_BYTES` is refused rather than buffered.
    """
    try:
        return connect(
            url,
            proxy=None,  # websockets >= 15 would read HTTP(S)_PROXY; this socket is loopback only
            open_timeout=timeout,
            max_size=MAX_MESSAGE_BYTES,
            compression=None,
            ping_interval=None,  # no keep-alive pings: a busy page must not cost the link
            close_timeout=2,
        )
    except (OSError, TimeoutError, WebSocketException) as exc:
        raise BrowserError(f"cannot connect to Firefox's WebDriver BiDi at {url}: {exc}") from exc
