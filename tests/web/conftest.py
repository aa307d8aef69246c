"""Browser tests of the static site (make test-web): headless Debian Chromium driven by Playwright, offline.

The site is served from 127.0.0.1 by a plain static server that answers like a static host (GitHub Pages:
``Cache-Control: max-age=600``). Chromium sends every request for another host to a refusing proxy on
127.0.0.1, which counts it and answers 403: pages, web workers and service workers alike (Playwright's own
request routing would miss workers and switch the browser cache off). Each test fails if that count is not 0.

These tests need `make book` and `make lite` (the live site serves Pyodide itself: web/pyodide_site.py); `make test`
does not collect them (KINBOOK_TEST_WEB=1 is set by `make test-web`).
"""

from __future__ import annotations

import functools
import http.server
import os
import shutil
import socketserver
import threading
import time
from pathlib import Path
from urllib.parse import urlsplit

import pytest

if not os.environ.get("KINBOOK_TEST_WEB"):
    collect_ignore_glob = ["*"]
else:  # run by .venv's Python (kinbook, numpy, the corpora), not by .venv-web's: not a module of this run
    collect_ignore = ["instant_cases.py"]

ROOT = Path(__file__).resolve().parents[2]
SITE = ROOT / "build" / "site"
SCREENSHOTS = ROOT / "build" / "web" / "screenshots"
# Debian's chromium. /usr/bin/chromium is a wrapper script that adds Debian's desktop defaults (Google API keys,
# remote extension updates: the browser's own requests to Google); the browser it starts is launched directly.
CHROMIUM = os.environ.get("KINBOOK_CHROMIUM") or next(
    (p for p in ("/usr/lib/chromium/chromium", "/usr/bin/chromium") if Path(p).exists()), "/usr/bin/chromium")


class _Handler(http.server.SimpleHTTPRequestHandler):
    log = None  # list of (path, status, bytes), set per server

    def end_headers(self):
        self.send_header("Cache-Control", "max-age=600")
        super().end_headers()

    def log_request(self, code="-", size="-"):
        try:
            n = int(size)
        except (TypeError, ValueError):
            n = 0
        self.log.append((self.path, int(code) if str(code).isdigit() else code, n))

    def copyfile(self, source, outputfile):
        # count the body bytes actually sent (log_request is called before the body with size "-")
        data = source.read()
        outputfile.write(data)
        self.log.append((self.path, "body", len(data)))

    def log_message(self, *args):
        pass


# The browser's own services (component updates, Google accounts, form autofill) call Google whatever the page;
# they are pointed at a closed local port so that whatever reaches the proxy comes from the site.
BROWSER_SERVICES_OFF = [f"--{switch}=http://127.0.0.1:9/"
                        for switch in ("gaia-url", "google-apis-url", "lso-url", "autofill-server-url")]
BROWSER_SERVICES_OFF.append("--component-updater=url-source=http://127.0.0.1:9/")


class _QuietServer(http.server.ThreadingHTTPServer):
    def handle_error(self, request, client_address):
        pass  # a browser that closes a connection early (a 404 it no longer wants) is not an error here


class StaticServer:
    """A static file server for one folder on 127.0.0.1, recording what it served."""

    def __init__(self, folder):
        self.log = []
        handler = functools.partial(type("H", (_Handler,), {"log": self.log}), directory=str(folder))
        self.httpd = _QuietServer(("127.0.0.1", 0), handler)
        self.httpd.daemon_threads = True
        self.url = f"http://127.0.0.1:{self.httpd.server_address[1]}"
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)
        self.thread.start()

    def bytes_sent(self, prefix=""):
        return sum(n for path, kind, n in self.log if kind == "body" and path.startswith(prefix))

    def close(self):
        self.httpd.shutdown()
        self.httpd.server_close()


class RefusingProxy(socketserver.ThreadingTCPServer):
    """Where Chromium sends every request that is not for 127.0.0.1: record its first line, answer 403."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self):
        self.requests = []

        class Handler(socketserver.StreamRequestHandler):
            def handle(inner):
                line = inner.rfile.readline(8192).decode("latin-1").strip()
                if line:
                    self.requests.append(line)
                inner.wfile.write(b"HTTP/1.1 403 Forbidden\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")

        super().__init__(("127.0.0.1", 0), Handler)
        self.port = self.server_address[1]
        threading.Thread(target=self.serve_forever, daemon=True).start()


@pytest.fixture(scope="session")
def proxy():
    p = RefusingProxy()
    yield p
    p.shutdown()
    p.server_close()


@pytest.fixture(scope="session")
def playwright(proxy):
    sync_api = pytest.importorskip("playwright.sync_api")
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: apt-get install chromium (make test-web does it as root)")
    with sync_api.sync_playwright() as pw:
        yield pw


def _browser_args(proxy):
    return dict(executable_path=CHROMIUM, headless=True,
                args=[f"--proxy-server=http://127.0.0.1:{proxy.port}", "--proxy-bypass-list=127.0.0.1",
                      *BROWSER_SERVICES_OFF])


@pytest.fixture(scope="session")
def browser(playwright, proxy):
    b = playwright.chromium.launch(**_browser_args(proxy))
    yield b
    b.close()


@pytest.fixture(scope="module")
def profile(playwright, proxy, tmp_path_factory):
    """A browser with a profile on disk, as a student's: its HTTP cache is kept on disk (a private context
    keeps a small one in memory, which large files such as Pyodide's packages do not fit)."""
    context = playwright.chromium.launch_persistent_context(
        tmp_path_factory.mktemp("chromium-profile"), viewport={"width": 1280, "height": 1000}, **_browser_args(proxy))
    yield context
    context.close()


@pytest.fixture
def offline(proxy):
    """Asserts, after the test, that no request left 127.0.0.1 (refused by the proxy, or seen by a page)."""
    before = len(proxy.requests)
    seen = []
    yield seen
    external = proxy.requests[before:] + [u for u in seen if urlsplit(u).hostname not in ("127.0.0.1", None)]
    assert external == [], f"{len(external)} request(s) off 127.0.0.1: {external[:10]}"


def watch(page, seen):
    """Record every URL the page or its workers request (for the `offline` check and for diagnosis)."""
    page.on("request", lambda r: seen.append(r.url) if r.url.startswith(("http:", "https:", "ws")) else None)
    return page


def site_copy(copy):
    """Copy the built site (make book + make lite) to ``copy``: hard links, so that a test may change a file of
    the copy (by writing a new one) and build/site/ stays as shipped. Returns ``copy``, or raises RuntimeError
    naming what to build first. (Also used by benchmarks/live_site.py.)"""
    if not (SITE / "index.html").exists() or not (SITE / "live" / "static" / "pyodide" / "pyodide.js").exists():
        raise RuntimeError("build/site/ is incomplete: run `make book` and `make lite` (make test-web does)")
    copy = Path(copy)
    if copy.exists():
        shutil.rmtree(copy)
    shutil.copytree(SITE, copy, copy_function=os.link)
    return copy


@pytest.fixture(scope="session")
def site():
    """The built site served from 127.0.0.1 (a copy: :func:`site_copy`)."""
    try:
        copy = site_copy(ROOT / "build" / "web" / "test-site")
    except RuntimeError as err:
        pytest.fail(str(err))
    server = StaticServer(copy)
    yield server
    server.close()
    shutil.rmtree(copy, ignore_errors=True)


FIGURES = {}
"""Speed figures of this run (issue 35 item 4): each test that measures one records it here — the book page's instant
check (verdict after Check, the page's load and every try-it ready) and the live site's time to interactive (first
and second visit) — and they are printed side by side at the end of the run (the same machine, the same load)."""


def pytest_terminal_summary(terminalreporter):
    if not FIGURES:
        return
    w = terminalreporter.write_line
    w("")
    w(f"Speed, side by side (this run; load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores):")
    for what, value in FIGURES.items():
        if not what.startswith("_"):
            w(f"  {what:66} {value}")


@pytest.fixture(scope="session")
def screenshots():
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    return SCREENSHOTS


def browser_cpu_seconds():
    """CPU time (user + system) used so far by the running chromium processes: a figure that, unlike the
    wall clock, does not grow when other work shares this machine's two cores."""
    total = 0
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:
            continue
        name, fields = text[text.index("(") + 1:text.rindex(")")], text[text.rindex(")") + 2:].split()
        if "chrom" in name:
            total += int(fields[11]) + int(fields[12])   # utime, stime (fields 14 and 15 of stat)
    return total / os.sysconf("SC_CLK_TCK")


class Clock:
    """Wall-clock and browser CPU seconds since it was made."""

    def __init__(self):
        self.t0, self.cpu0 = time.perf_counter(), browser_cpu_seconds()

    def __call__(self):
        return time.perf_counter() - self.t0

    def cpu(self):
        return browser_cpu_seconds() - self.cpu0


# The chapters whose stored notebook has an animation (a cell calling plotting.animation_png), for the tests that
# open one: 13-3 (planar, two) and 14-5 (spatial) at least.
ANIMATED = [p.stem for p in sorted((ROOT / "chapters").glob("*.ipynb")) if "animation_png(" in p.read_text()]


def plays(page, img, shots=4, pause_ms=350):
    """True when an <img> (a stored animated PNG) loaded and shows different pictures over about a second: the
    browser is playing it."""
    img.scroll_into_view_if_needed()
    page.wait_for_function("i => i.complete && i.naturalWidth > 0", arg=img.element_handle())
    pictures = set()
    for _ in range(shots):
        pictures.add(img.screenshot())
        page.wait_for_timeout(pause_ms)
    return len(pictures) > 1

