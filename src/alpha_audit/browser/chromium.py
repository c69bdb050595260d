"""Chromium over the DevTools protocol on ``--remote-debugging-pipe`` (standard library only).

The pipe carries NUL-terminated JSON on the child's fds 3 (commands) and 4
(replies): no port is opened at all.  WebGL2 runs on SwiftShader, on the CPU,
so results do not depend on a GPU.
"""

from __future__ import annotations

import base64
import binascii
import contextlib
import fcntl
import json
import os
import select
import shutil
import sys
import time
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any, cast

from alpha_audit.browser.interface import (
    Browser,
    BrowserError,
    Clip,
    ColorScheme,
    Installation,
    JSONValue,
    deadline_after,
    time_left,
)
from alpha_audit.browser.matched import declarations, sheet_entry

__all__ = ["Chromium"]

# Chromium's switches: https://peter.sh/experiments/chromium-command-line-switches/
_FLAGS = (
    "--headless",
    "--no-sandbox",  # root in CI containers cannot use the setuid sandbox
    "--disable-gpu",
    "--use-angle=swiftshader",  # WebGL2 on the CPU: no GPU on CI machines
    "--enable-unsafe-swiftshader",
    "--disable-quic",
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
    "--mute-audio",
    "--force-color-profile=srgb",  # no colour management: CSS colours reach pixels as codes
    # The browser's own traffic (network time, updates, sign-in, hints): none, so that
    # what the blocking proxy sees is the page's.
    "--disable-features=NetworkTimeServiceQuerying,OptimizationHints,"
    "OptimizationGuideModelDownloading,MediaRouter,Translate,AutofillServerCommunication,"
    "CertificateTransparencyComponentUpdater,AccountConsistency,SigninInterception",
    "--disable-client-side-phishing-detection",
    "--disable-domain-reliability",
    "--disable-default-apps",
    "--no-pings",
    "--no-service-autorun",
    "--remote-debugging-pipe",
)
# Put the child's pipe ends on fds 3 and 4 after fork; Popen cannot place fds itself.
_TRAMPOLINE = (
    "import os, sys; os.dup2(int(sys.argv[1]), 3); os.dup2(int(sys.argv[2]), 4); "
    "os.close(int(sys.argv[1])); os.close(int(sys.argv[2])); "
    "os.execv(sys.argv[3], sys.argv[3:])"
)


# At most this many elements asked for their matched styles, per page: a page of thousands
# of icons in a deep tree gets no CSS locations rather than a timed-out audit.  A count, not
# a clock: the same page gets the same locations however busy the machine (the page's own
# time limit still bounds the whole page).
MAX_STYLED_ELEMENTS = 2000


class _ProtocolError(BrowserError):
    """Chromium answered a command with an error (the browser itself is fine)."""


class Chromium(Browser):
    """Headless Chromium (Debian's ``chromium``, or ``$ALPHA_AUDIT_CHROMIUM``)."""

    NAME = "chromium"
    LABEL = "Chromium"
    # Debian's Chromium 156: the component updater and the sign-in check.
    OWN_HOSTS = frozenset({"update.googleapis.com", "accounts.google.com"})
    LIVE_COLOR_SCHEME = True
    ISOLATED_SCRIPTS = True
    INSTALL_HINT = (
        "install Debian's package (`sudo apt-get install -y chromium`, or `make browser` as "
        "root), or point ALPHA_AUDIT_CHROMIUM at a Chromium/Chrome binary"
    )

    @classmethod
    def find(cls) -> Installation | None:
        """``$ALPHA_AUDIT_CHROMIUM`` or a Chromium/Chrome on ``PATH``."""
        configured = os.environ.get("ALPHA_AUDIT_CHROMIUM")
        if configured:
            return Installation(cls.NAME, Path(configured)) if Path(configured).is_file() else None
        for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
            if found := shutil.which(name):
                return Installation(cls.NAME, Path(found))
        return None

    def _start(self) -> None:
        commands_r, commands_w = os.pipe()
        replies_r, replies_w = os.pipe()
        # Move the child's ends above 3 and 4 so that placing them there cannot collide.
        child_r = fcntl.fcntl(commands_r, fcntl.F_DUPFD, 10)
        child_w = fcntl.fcntl(replies_w, fcntl.F_DUPFD, 10)
        os.close(commands_r)
        os.close(replies_w)
        self._writer = os.fdopen(commands_w, "wb")
        self._reader = replies_r
        try:
            self.processes.start(
                [
                    *(sys.executable, "-c", _TRAMPOLINE, str(child_r), str(child_w)),
                    str(self.installation.binary),
                    *_FLAGS,
                    *self._network_flags(),
                    f"--user-data-dir={self.workdir / 'profile'}",
                    # Crash reports go to the browser's folder too (HOME is there as well).
                    f"--crash-dumps-dir={self.workdir / 'crashes'}",
                    "about:blank",
                ],
                env=self.child_env(),
                pass_fds=(child_r, child_w),
            )
        finally:
            os.close(child_r)
            os.close(child_w)
        self._buffer = bytearray()
        self._scanned = 0
        self._sheet_headers: dict[str, dict[str, Any]] | None = None
        self._next_id = 0
        self._session: str | None = None
        self.version = self._call("Browser.getVersion", session=False)["product"]
        target = self._call("Target.createTarget", {"url": "about:blank"}, session=False)
        attached = self._call(
            "Target.attachToTarget", {"targetId": target["targetId"], "flatten": True}
        )
        self._session = attached["sessionId"]
        self._target = target["targetId"]
        self._world: int | None = None
        self.emulate_color_scheme(self.options.color_scheme)

    def _network_flags(self) -> list[str]:
        """Every request through the proxy but those to ``direct`` origins; no DNS, no UDP."""
        if self.options.proxy is None:
            return []
        # <-loopback> ends Chromium's implicit bypass of loopback: the driver ports and any
        # other local service go through the (refusing) proxy too.
        bypass = ";".join(("<-loopback>", *self.options.direct))
        return [
            f"--proxy-server=http://{self.options.proxy}",
            f"--proxy-bypass-list={bypass}",
            # IPv6 loopback is excluded as "::1" (not "[::1]", which Chromium never matches).
            "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE localhost, EXCLUDE 127.0.0.1, "
            "EXCLUDE ::1",
            "--force-webrtc-ip-handling-policy=disable_non_proxied_udp",
            "--dns-prefetch-disable",
        ]

    def emulate_color_scheme(self, scheme: ColorScheme | None) -> None:
        """``prefers-color-scheme`` (and reduced motion, for still pictures) from now on."""
        features = [{"name": "prefers-reduced-motion", "value": "reduce"}]
        features.append({"name": "prefers-color-scheme", "value": scheme or ""})
        self._call("Emulation.setEmulatedMedia", {"features": features})

    def _messages(self, deadline: float) -> Iterator[dict[str, Any]]:
        while True:
            # Only the newest chunk can hold the terminator: scanning it alone keeps a
            # message of tens of MB linear to receive.
            while (end := self._buffer.find(b"\0", self._scanned)) >= 0:
                raw = bytes(self._buffer[:end])
                del self._buffer[: end + 1]
                self._scanned = 0
                yield json.loads(raw)
            self._scanned = len(self._buffer)
            left = time_left(deadline, self.LABEL)
            if not select.select([self._reader], [], [], left)[0]:
                continue  # time_left raises on the next turn
            chunk = os.read(self._reader, 1 << 20)
            if not chunk:
                raise BrowserError("Chromium closed the DevTools pipe (it crashed or quit)")
            self._buffer += chunk

    def _call(
        self,
        method: str,
        params: dict[str, Any] | None = None,
        *,
        session: bool = True,
        timeout: float | None = None,
    ) -> dict[str, Any]:
        self._next_id += 1
        message: dict[str, Any] = {"id": self._next_id, "method": method, "params": params or {}}
        if session and self._session:
            message["sessionId"] = self._session
        try:
            self._writer.write(json.dumps(message).encode() + b"\0")
            self._writer.flush()
        except OSError as exc:
            raise BrowserError(f"Chromium is gone: {exc}") from exc
        for reply in self._messages(deadline_after(timeout or self.timeout)):
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise _ProtocolError(f"Chromium {method}: {reply['error'].get('message')}")
                result: dict[str, Any] = reply["result"]
                return result
            if self._sheet_headers is not None and reply.get("method") == "CSS.styleSheetAdded":
                header = reply.get("params", {}).get("header", {})
                self._sheet_headers[str(header.get("styleSheetId"))] = header
        raise AssertionError("unreachable")

    def _navigate(self, url: str) -> None:
        self._world = None
        reply = self._call("Page.navigate", {"url": url})
        if reply.get("errorText"):
            raise BrowserError(f"Chromium could not open {url}: {reply['errorText']}")
        deadline = deadline_after(self.timeout)
        # The page may rewrite its own query (Storybook writes its globals back): compare
        # the address without it.
        base = url.split("?", 1)[0].split("#", 1)[0]
        check = (
            f"location.href.split('?')[0].split('#')[0] === {json.dumps(base)}"
            " && document.readyState === 'complete'"
        )
        while not self.evaluate(check):
            time_left(deadline, f"Chromium loading {url}")
            time.sleep(0.02)

    def _isolated_world(self) -> int:
        """An execution context of our own in the page's main frame (DOM shared, JS not)."""
        if self._world is None:
            reply = self._call(
                "Page.createIsolatedWorld", {"frameId": self._target, "worldName": "alpha-audit"}
            )
            self._world = int(reply["executionContextId"])
        return self._world

    def _evaluate_text(self, expression: str, timeout: float, isolated: bool) -> str:
        params: dict[str, Any] = {
            "expression": expression,
            "returnByValue": True,
            "awaitPromise": True,
        }
        if isolated:
            params["contextId"] = self._isolated_world()
        try:
            reply = self._call("Runtime.evaluate", params, timeout=timeout)
        except BrowserError as exc:
            if not (isolated and "context" in str(exc).lower()):
                raise
            self._world = None  # the page navigated by itself: a new document, a new world
            params["contextId"] = self._isolated_world()
            reply = self._call("Runtime.evaluate", params, timeout=timeout)
        if "exceptionDetails" in reply:
            details = reply["exceptionDetails"]
            text = details.get("exception", {}).get("description") or details.get("text")
            raise BrowserError(f"script error in Chromium: {text}")
        value: str = reply["result"].get("value")  # JSON text (evaluate() refuses anything else)
        return value

    def matched_styles(
        self, elements: str, pseudos: Sequence[str | None]
    ) -> dict[str, JSONValue] | None:
        """The declarations matching each element, from ``CSS.getMatchedStylesForNode``.

        The CSS domain reports every style sheet of the page when it is enabled
        (``CSS.styleSheetAdded``, before ``CSS.enable`` answers): their URLs and,
        for ``<style>`` elements, where in the page their text starts.  The
        elements are found by reference from the isolated world
        (``DOM.requestNode``), shadow trees included; one whose node is gone
        since has no declarations.
        """
        headers: dict[str, dict[str, Any]] = {}
        self._sheet_headers = headers
        group = "alpha-audit-styles"
        try:
            self._call("DOM.enable")
            self._call("CSS.enable")
            self._call("DOM.getDocument", {"depth": 0})
            found = self._call(
                "Runtime.evaluate",
                {
                    "expression": elements,
                    "contextId": self._isolated_world(),
                    "returnByValue": False,
                    "objectGroup": group,
                },
            )
            if "exceptionDetails" in found or "objectId" not in found.get("result", {}):
                return None  # no elements to ask about: the probe walks the cascade instead
            props = self._call(
                "Runtime.getProperties",
                {"objectId": found["result"]["objectId"], "ownProperties": True},
            )
            handles = {
                int(p["name"]): p["value"]["objectId"]
                for p in props.get("result", ())
                if str(p.get("name", "")).isdigit() and "objectId" in p.get("value", {})
            }
            sheets: dict[str, int] = {}
            nodes: list[JSONValue] = []
            if len(pseudos) > MAX_STYLED_ELEMENTS:
                return {"sheets": [], "nodes": [], "error": "too many elements"}
            for k, pseudo in enumerate(pseudos):
                try:
                    node = self._call("DOM.requestNode", {"objectId": handles[k]})["nodeId"]
                    matched = self._call("CSS.getMatchedStylesForNode", {"nodeId": node})
                    flat = self._call("DOM.getAttributes", {"nodeId": node}).get("attributes", [])
                except (KeyError, _ProtocolError):
                    nodes.append([])
                    continue
                written = {
                    str(n).lower(): str(v) for n, v in zip(flat[::2], flat[1::2], strict=False)
                }
                listed_here = declarations(matched, pseudo, headers, sheets, written)
                nodes.append(cast(JSONValue, listed_here))  # plain JSON data, typed loosely
        finally:
            self._sheet_headers = None
            for method, params in (
                ("Runtime.releaseObjectGroup", {"objectGroup": group}),
                ("CSS.disable", {}),
                ("DOM.disable", {}),
            ):
                with contextlib.suppress(_ProtocolError):
                    self._call(method, params)
        by_index = sorted(sheets.items(), key=lambda item: item[1])
        listed: list[JSONValue] = [sheet_entry(headers.get(sid)) for sid, _ in by_index]
        return {"sheets": listed, "nodes": nodes}

    def _set_viewport(self, width: int, height: int, scale: float) -> None:
        self._call(
            "Emulation.setDeviceMetricsOverride",
            {"width": width, "height": height, "deviceScaleFactor": scale, "mobile": False},
        )

    def _screenshot(self, clip: Clip | None) -> bytes:
        params: dict[str, Any] = {"format": "png", "optimizeForSpeed": True}
        if clip is not None:  # CSS pixels; the image has deviceScaleFactor pixels per CSS px
            params["clip"] = {
                "x": clip.x,
                "y": clip.y,
                "width": clip.width,
                "height": clip.height,
                "scale": 1,
            }
        reply = self._call("Page.captureScreenshot", params)
        try:
            return base64.b64decode(reply["data"], validate=True)
        except (KeyError, TypeError, binascii.Error) as exc:
            raise BrowserError("Chromium returned no screenshot") from exc

    def _shutdown(self) -> None:
        try:
            self._call("Browser.close", session=False, timeout=5)
        finally:
            with contextlib.suppress(OSError):  # the reader may already be gone
                self._writer.close()
            os.close(self._reader)
