"""Helpers for the tests of the 3D pages: Debian's chromium, headless, driven by Playwright, and a probe of what a page
did once opened (errors on its console, requests that tried to leave the file it was opened from).

The fixture ``chromium`` is one for the whole session (tests/conftest.py imports it, so that every module shares the
one browser: Playwright's sync API runs one instance at a time); test modules import ``open_page``. The fixture
skips when /usr/bin/chromium (Debian's ``chromium`` package) or Playwright (the ``browser`` extra, Python 3.9+) is
not installed. Playwright's own browsers are never used nor downloaded.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator, List, Tuple

import pytest

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    # WebGL on the CPU (SwiftShader): chromium falls back to it by itself today, but the fallback is deprecated
    # behind this flag; the pages draw through three.js's WebGL2 renderer.
    "--enable-unsafe-swiftshader",
]
LOCAL_SCHEMES = ("file:", "data:", "blob:")
TIMEOUT_MS = 30_000


@pytest.fixture(scope="session")
def chromium() -> Iterator[Any]:
    """A headless chromium (a Playwright ``Browser``) for the whole session. Each ``launch`` runs on a fresh empty
    user-data-dir of Playwright's making, removed when the browser closes."""
    # In CI (.ci/run installs both) a missing browser fails, but on Python 3.8, which Playwright no longer supports
    missing = pytest.fail if os.environ.get("CI") and sys.version_info >= (3, 9) else pytest.skip
    if not CHROMIUM.is_file() or not os.access(str(CHROMIUM), os.X_OK):
        missing(f"no {CHROMIUM} (Debian's chromium package: apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        missing("Playwright is not installed (pip install -e '.[browser]'; Python 3.9+)")
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=str(CHROMIUM), headless=True, args=CHROMIUM_ARGS,
                                             timeout=TIMEOUT_MS)
        try:
            yield browser
        finally:
            browser.close()


@dataclass
class Probe:
    """An open page and what it did: ``console_errors`` (console messages of type error, and uncaught exceptions,
    as ``"console: …"`` and ``"pageerror: …"``) and ``left_file`` (the URL of every request not to a file:, data:
    or blob: URL; each was aborted)."""

    page: Any
    console_errors: List[str] = field(default_factory=list)
    left_file: List[str] = field(default_factory=list)

    def wait_until(self, predicate: Callable[[], bool], seconds: float = 5.0) -> bool:
        """Poll ``predicate`` while Playwright delivers the page's events (a plain sleep would hold them back, the
        sync API handles them only inside its own calls); its last value."""
        end = time.monotonic() + seconds
        while not predicate():
            if time.monotonic() >= end:
                return False
            self.page.wait_for_timeout(50)
        return True


def _is_local(url: str) -> bool:
    return url.lower().startswith(LOCAL_SCHEMES)


@contextlib.contextmanager
def open_page(browser: Any, path: Path, viewport: Tuple[int, int] = (1000, 750)) -> Iterator[Probe]:
    """Open ``path`` in a context of its own (no cookies or cache shared with other pages) and wait for its
    ``load`` event; every request that would leave the local file is recorded and aborted."""
    width, height = viewport
    context = browser.new_context(viewport={"width": width, "height": height}, service_workers="block")
    context.set_default_timeout(TIMEOUT_MS)
    try:
        page = context.new_page()
        probe = Probe(page)

        def route(route: Any) -> None:
            url = route.request.url
            if _is_local(url):
                route.continue_()
            else:
                probe.left_file.append(url)
                route.abort()

        def console(message: Any) -> None:
            if message.type == "error":
                where = message.location or {}
                at = f" ({where.get('url')}:{where.get('lineNumber')})" if where.get("url") else ""
                probe.console_errors.append(f"console: {message.text}{at}")

        context.route("**/*", route)
        page.on("console", console)
        page.on("pageerror", lambda error: probe.console_errors.append(f"pageerror: {error}"))
        if hasattr(context, "route_web_socket"):   # Playwright 1.48+: a socket not connected on is never opened
            context.route_web_socket(re.compile(".*"), lambda socket: (probe.left_file.append(socket.url),
                                                                       socket.close()))
        else:
            page.on("websocket", lambda socket: probe.left_file.append(socket.url))   # recorded, not stopped
        page.goto(Path(path).resolve().as_uri(), wait_until="load")
        yield probe
    finally:
        context.close()
