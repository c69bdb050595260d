"""WebKitGTK over W3C WebDriver HTTP (``WebKitWebDriver`` + MiniBrowser) on a private Xvfb.

WebKitGTK needs an X display even for automation, so each browser starts its
own Xvfb (``-displayfd`` reports the display number it chose; no TCP
listener), then ``WebKitWebDriver`` on a free loopback port, and drives
MiniBrowser in automation mode with the capability
``webkitgtk:browserOptions``.  Requests go through :mod:`urllib` with proxies
disabled: nothing leaves the machine.
"""

from __future__ import annotations

import base64
import binascii
import glob
import io
import json
import os
import select
import shutil
import socket
import time
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

from alpha_audit.browser.interface import (
    Browser,
    BrowserError,
    Clip,
    Installation,
    deadline_after,
    time_left,
)

__all__ = ["WebKit"]

# Debian's webkit2gtk-driver: WebKitWebDriver on PATH, MiniBrowser in the library directory.
_MINIBROWSER_GLOBS = (
    "/usr/lib/*/webkit2gtk-4.*/MiniBrowser",
    "/usr/libexec/webkit2gtk-4.*/MiniBrowser",
    "/usr/lib/webkit2gtk-4.*/MiniBrowser",
)
# The script for execute/async: its last argument is the callback (WebDriver, section 13.2.2).
_ASYNC = (
    "const done = arguments[arguments.length - 1];"
    "({expression}).then((v) => done({{ok: v}}), (e) => done({{error: String(e)}}));"
)
_NO_PROXY = urllib.request.build_opener(urllib.request.ProxyHandler({}))


def _free_port() -> int:
    """A port free on loopback right now (the driver has no 'pick one yourself')."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


class WebKit(Browser):
    """WebKitGTK's MiniBrowser through ``WebKitWebDriver`` (``$ALPHA_AUDIT_WEBKIT_DRIVER``)."""

    NAME = "webkit"
    LABEL = "WebKitGTK"
    INSTALL_HINT = (
        "install Debian's packages (`sudo apt-get install -y webkit2gtk-driver xvfb "
        "libgl1-mesa-dri`, or `make browser` as root)"
    )

    @classmethod
    def find(cls) -> Installation | None:
        """``WebKitWebDriver``, MiniBrowser and ``Xvfb``, or ``None`` when any is missing."""
        driver = os.environ.get("ALPHA_AUDIT_WEBKIT_DRIVER") or shutil.which("WebKitWebDriver")
        xvfb = shutil.which("Xvfb")
        browsers = sorted(p for pattern in _MINIBROWSER_GLOBS for p in glob.glob(pattern))
        if not (driver and Path(driver).is_file() and xvfb and browsers):
            return None
        return Installation(cls.NAME, Path(browsers[-1]), (Path(driver), Path(xvfb)))

    def _start(self) -> None:
        driver, xvfb = self.installation.helpers
        display = self._start_xvfb(xvfb)
        port = _free_port()
        env = self.child_env({k: v for k, v in os.environ.items() if k != "WAYLAND_DISPLAY"})
        env["DISPLAY"] = f":{display}"
        env["GDK_SCALE"] = str(self.options.scale)  # devicePixelRatio, fixed for the process
        if self.options.color_scheme is not None:
            # WebKitGTK's prefers-color-scheme follows the GTK theme's variant.
            env["GTK_THEME"] = f"Adwaita:{self.options.color_scheme}"
        log = self.workdir / "driver.log"
        with log.open("wb") as stderr:
            self.processes.start(
                [str(driver), f"--port={port}", "--host=127.0.0.1"],
                env=env,
                stderr=stderr.fileno(),
                stdout=stderr.fileno(),
            )
        self._base = f"http://127.0.0.1:{port}"
        deadline = deadline_after(self.timeout)
        while True:
            try:
                if self._request("GET", "/status", timeout=2).get("ready", True):
                    break
            except BrowserError:
                pass
            time_left(deadline, "WebKitWebDriver")
            time.sleep(0.05)
        options = {"binary": str(self.installation.binary), "args": ["--automation"]}
        capabilities: dict[str, Any] = {"webkitgtk:browserOptions": options}
        if self.options.proxy is not None:  # W3C WebDriver, section 7.1 (proxy configuration)
            capabilities["proxy"] = {
                "proxyType": "manual",
                "httpProxy": self.options.proxy,
                "sslProxy": self.options.proxy,
                "noProxy": list(self.options.direct),
            }
        session = self._request("POST", "/session", {"capabilities": {"alwaysMatch": capabilities}})
        self._session = session["sessionId"]
        caps = session.get("capabilities", {})
        self.version = f"{caps.get('browserName', 'WebKitGTK')} {caps.get('browserVersion', '')}"
        self._script_timeout: float | None = None

    def _start_xvfb(self, xvfb: Path) -> int:
        read_end, write_end = os.pipe()
        try:
            self.processes.start(
                [str(xvfb), "-displayfd", str(write_end), "-nolisten", "tcp", "-screen", "0",
                 f"{1280 * self.options.scale}x{1024 * self.options.scale}x24"],
                env=self.child_env(),
                pass_fds=(write_end,),
            )  # fmt: skip
        finally:
            os.close(write_end)
        deadline = deadline_after(self.timeout)
        text = b""
        try:
            while not text.endswith(b"\n"):
                left = time_left(deadline, "Xvfb")
                if select.select([read_end], [], [], left)[0]:
                    chunk = os.read(read_end, 64)
                    if not chunk:
                        raise BrowserError("Xvfb exited before reporting its display")
                    text += chunk
        finally:
            os.close(read_end)
        return int(text.strip())

    def _request(
        self,
        method: str,
        path: str,
        body: dict[str, Any] | None = None,
        *,
        timeout: float | None = None,
    ) -> Any:
        data = None if body is None else json.dumps(body).encode("utf-8")
        request = urllib.request.Request(
            self._base + path,
            data=data,
            method=method,
            headers={"Content-Type": "application/json; charset=utf-8"},
        )
        try:
            with _NO_PROXY.open(request, timeout=timeout or self.timeout) as response:
                payload = json.loads(response.read())
        except urllib.error.HTTPError as exc:
            try:
                value = json.loads(exc.read()).get("value", {})
                detail = f"{value.get('error')}: {value.get('message')}"
            except (ValueError, AttributeError):
                detail = str(exc)
            raise BrowserError(f"WebKitWebDriver {method} {path}: {detail}") from exc
        except (OSError, ValueError) as exc:
            raise BrowserError(f"WebKitWebDriver {method} {path}: {exc}") from exc
        return payload.get("value")

    def _session_path(self, tail: str) -> str:
        return f"/session/{self._session}/{tail}"

    def _navigate(self, url: str) -> None:
        self._request("POST", self._session_path("url"), {"url": url})

    def _evaluate_text(self, expression: str, timeout: float, isolated: bool) -> str:
        # WebDriver classic has no isolated worlds: scripts run beside the page's own.
        if self._script_timeout != timeout:
            self._request("POST", self._session_path("timeouts"), {"script": int(timeout * 1000)})
            self._script_timeout = timeout
        reply = self._request(
            "POST",
            self._session_path("execute/async"),
            {"script": _ASYNC.format(expression=expression), "args": []},
            timeout=timeout + 10,
        )
        if not isinstance(reply, dict) or "error" in reply:
            detail = reply.get("error") if isinstance(reply, dict) else reply
            raise BrowserError(f"script error in WebKitGTK: {detail}")
        value: str = reply["ok"]  # JSON text (evaluate() refuses anything else)
        return value

    def _inner_size(self) -> tuple[int, int]:
        """The viewport once it has settled: two reads 50 ms apart agree (at most ~2 s).

        The X server resizes the window asynchronously, so a read right after
        a resize can still show the old size.
        """
        last: tuple[int, int] | None = None
        for _ in range(40):
            got = self.evaluate("[innerWidth, innerHeight]")
            if not (isinstance(got, list) and all(isinstance(v, int | float) for v in got[:2])):
                raise BrowserError(f"WebKitGTK reported no viewport size: {got}")
            size = (int(got[0]), int(got[1]))  # type: ignore[arg-type]  # numbers, checked
            if size == last:
                return size
            last = size
            time.sleep(0.05)
        assert last is not None
        return last

    def _set_viewport(self, width: int, height: int, scale: float) -> None:
        if scale != self.options.scale:
            raise BrowserError(
                f"WebKitGTK fixes its device scale at start (GDK_SCALE={self.options.scale}); "
                f"asked for {scale:g}"
            )
        # WebDriver sizes the window, not the viewport (section 11.8.2): size it, let it
        # settle, measure what the window's own frame takes, and size it again with that
        # added, until the viewport is what was asked (the frame is the same each time).
        path = self._session_path("window/rect")
        extra_w = extra_h = 0
        for _ in range(4):
            self._request("POST", path, {"width": width + extra_w, "height": height + extra_h})
            inner_w, inner_h = self._inner_size()
            if (inner_w, inner_h) == (width, height):
                return
            extra_w = max(0, extra_w + width - inner_w)
            extra_h = max(0, extra_h + height - inner_h)

    def _screenshot(self, clip: Clip | None) -> bytes:
        data = self._request("GET", self._session_path("screenshot"))
        try:
            png = base64.b64decode(str(data), validate=True)
        except binascii.Error as exc:
            raise BrowserError("WebKitWebDriver returned no screenshot") from exc
        if clip is None:
            return png
        # WebDriver classic screenshots the whole viewport: cut the box out here.
        from PIL import Image

        s = self.options.scale
        with Image.open(io.BytesIO(png)) as image:
            box = (clip.x * s, clip.y * s, (clip.x + clip.width) * s, (clip.y + clip.height) * s)
            out = io.BytesIO()
            image.crop(box).save(out, format="PNG", compress_level=1)
        return out.getvalue()

    def _shutdown(self) -> None:
        self._request("DELETE", f"/session/{self._session}", timeout=5)
