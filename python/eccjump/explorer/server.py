"""The explorer as a local web page: a small HTTP server of the standard library that serves
the static page (``static/``) and answers its requests through :func:`api.handle`.

It listens on 127.0.0.1 only and fetches nothing from the internet: the page is one HTML
file, one script and one style sheet, all served from here.
"""

from __future__ import annotations

import json
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from types import TracebackType
from typing import Any
from urllib.parse import parse_qsl, urlsplit

from eccjump.explorer import api

#: The files of the page: URL path -> (file in static/, content type).
FILES = {
    "/": ("index.html", "text/html; charset=utf-8"),
    "/index.html": ("index.html", "text/html; charset=utf-8"),
    "/explorer.js": ("explorer.js", "text/javascript; charset=utf-8"),
    "/explorer.css": ("explorer.css", "text/css; charset=utf-8"),
}
#: The host it listens on: this machine only.
HOST = "127.0.0.1"
#: The default port of ``eccjump explore``.
DEFAULT_PORT = 8050


def static_file(name: str) -> bytes:
    """The bytes of one of the page's files (inside the installed package)."""
    return resources.files("eccjump.explorer").joinpath("static", name).read_bytes()


class _Handler(BaseHTTPRequestHandler):
    server_version = "eccjump-explorer"
    server: _Server

    def do_GET(self) -> None:
        url = urlsplit(self.path)
        if url.path.startswith("/api/"):
            query = dict(parse_qsl(url.query, keep_blank_values=True))
            status, answer = api.handle(url.path.removeprefix("/api/"), query)
            self._send(status, _json(answer), "application/json")
        elif url.path in FILES:
            name, kind = FILES[url.path]
            self._send(200, static_file(name), kind)
        else:
            self._send(404, b"not found", "text/plain; charset=utf-8")

    def _send(self, status: int, body: bytes, kind: str) -> None:
        self.send_response(status)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, format: str, *args: Any) -> None:
        if self.server.verbose:
            super().log_message(format, *args)


class _Server(ThreadingHTTPServer):
    # Requests in progress must not hold up Ctrl-C: their threads die with the process.
    daemon_threads = True
    block_on_close = False
    verbose = False


def _warm_up() -> None:
    """Answer the page's first requests once in the background: the first map of a process
    pays for starting the core's threads (about 0.1 s), and the default one is then cached."""
    for endpoint in ("region", "motion"):
        threading.Thread(target=api.handle, args=(endpoint, {}), daemon=True).start()


def _json(answer: dict[str, Any]) -> bytes:
    try:
        return json.dumps(answer, allow_nan=False, separators=(",", ":")).encode()
    except ValueError:  # a NaN that api did not turn into null: say so, do not send bad JSON
        return b'{"error":"internal error (a number that JSON cannot carry)"}'


class ExplorerServer:
    """The explorer's page and requests on ``http://127.0.0.1:port/``.

    ``port=0`` takes any free port (:attr:`url` tells which). Use :meth:`start` to serve
    from a background thread (a notebook, a test) and :meth:`stop` to end it, or
    :meth:`serve_forever` to serve from this thread until Ctrl-C. Also a context manager
    (``with ExplorerServer(0) as server: ...`` serves in the background while inside).

    Raises
    ------
    OSError
        When the port cannot be had (in use, or not allowed).
    """

    def __init__(self, port: int = DEFAULT_PORT, *, verbose: bool = False) -> None:
        self._httpd = _Server((HOST, port), _Handler)
        self._httpd.verbose = verbose
        self._thread: threading.Thread | None = None

    @property
    def port(self) -> int:
        return int(self._httpd.server_address[1])

    @property
    def url(self) -> str:
        return f"http://{HOST}:{self.port}/"

    def serve_forever(self) -> None:
        """Serve from this thread until Ctrl-C (KeyboardInterrupt, which the caller handles)
        or :meth:`stop` from another thread; the socket is closed either way."""
        _warm_up()
        try:
            self._httpd.serve_forever(poll_interval=0.2)
        finally:
            self._httpd.server_close()

    def start(self) -> ExplorerServer:
        """Serve from a daemon thread; returns self."""
        if self._thread is None:
            _warm_up()
            self._thread = threading.Thread(
                target=self._httpd.serve_forever, kwargs={"poll_interval": 0.2}, daemon=True
            )
            self._thread.start()
        return self

    def stop(self) -> None:
        """End the background thread of :meth:`start` and close the socket."""
        if self._thread is not None:
            self._httpd.shutdown()  # waits for serve_forever to return
            self._thread.join()
            self._thread = None
        self._httpd.server_close()

    def __enter__(self) -> ExplorerServer:
        return self.start()

    def __exit__(
        self,
        kind: type[BaseException] | None,
        value: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.stop()
