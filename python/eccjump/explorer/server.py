"""The explorer as a local web page: a small HTTP server of the standard library that serves
the static page (``static/``) and answers its requests through :func:`api.handle`.

It listens on 127.0.0.1 only and fetches nothing from the internet: the page is one HTML
file, one script and one style sheet, all served from here.

What a client of this machine may do to it is bounded (the user guide's page "The explorer",
"Safety"): :data:`BACKLOG` connections wait for :data:`WORKERS` handlers, a request must
arrive within :data:`REQUEST_TIMEOUT` seconds, and a request whose ``Host`` (or ``Origin``)
is not this server is refused with 403 before any route runs (a page of another site that
rebinds its name to 127.0.0.1 cannot read the answers).
"""

from __future__ import annotations

import io
import json
import os
import socket
import sys
import threading
import time
from email.message import Message
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from types import TracebackType
from typing import Any
from urllib.parse import parse_qsl

from eccjump.explorer import api
from eccjump.explorer.probability import checked_map
from eccjump.studies.uncertainty.map import UncertaintyMap

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
#: Connections that may wait to be taken (the listen backlog; the standard library's is 5,
#: and a sixth client waiting was reset or retried its connection for up to 100 s).
BACKLOG = 256
#: Requests handled at once; the next clients wait in the backlog (answers take milliseconds,
#: so a handler is held long only by a client that is slow to send or to read).
WORKERS = 16
#: Seconds a client has to send its request line and headers, counted from when a handler
#: takes the connection; then it is closed (an idle or half-open connection, a slowloris).
REQUEST_TIMEOUT = 5.0
#: Seconds each write of an answer may take (a client that does not read it).
SEND_TIMEOUT = 10.0
#: The names this server answers to (the Host header, without the port or with it).
LOCAL_NAMES = ("127.0.0.1", "localhost", "[::1]")


def static_file(name: str) -> bytes:
    """The bytes of one of the page's files (inside the installed package)."""
    return resources.files("eccjump.explorer").joinpath("static", name).read_bytes()


def refusal(headers: Message, port: int) -> str | None:
    """Why a request with these headers is not for this server (None: it is). The Host must
    be one of :data:`LOCAL_NAMES` with this ``port`` or none, given once; an Origin, when the
    browser sends one, must be ``http://`` and such a host. A page of another site whose name
    now points to 127.0.0.1 (DNS rebinding) sends its own name as Host."""
    hosts = headers.get_all("Host") or []
    local = {*LOCAL_NAMES, *(f"{name}:{port}" for name in LOCAL_NAMES)}
    if len(hosts) != 1 or hosts[0].lower() not in local:
        shown = ", ".join(repr(h[:40]) for h in hosts[:2]) or "none"
        return f"this server answers only requests to 127.0.0.1:{port} (Host: {shown})"
    origin = headers.get("Origin")
    if origin is not None and origin.lower() not in {f"http://{h}" for h in local}:
        return f"this server answers only its own page (Origin: {origin[:40]!r})"
    return None


class _Deadline(io.RawIOBase):
    """The connection's incoming bytes, all due by one deadline (a per-read timeout alone
    would let a client that sends a byte every few seconds hold a handler for ever)."""

    def __init__(self, sock: socket.socket, seconds: float) -> None:
        self._sock = sock
        self._end = time.monotonic() + seconds

    def readable(self) -> bool:
        return True

    def readinto(self, buffer: Any) -> int:
        left = self._end - time.monotonic()
        if left <= 0:
            raise TimeoutError("the request did not arrive in time")
        self._sock.settimeout(left)
        return self._sock.recv_into(buffer)


class _Handler(BaseHTTPRequestHandler):
    server_version = "eccjump-explorer"
    # The standard library's errors (a bad request line, too long a line, too many headers,
    # an unknown method) with a status line even for a garbled request line (not as
    # HTTP/0.9) and as one line of text rather than a page of HTML.
    default_request_version = "HTTP/1.0"
    error_message_format = "%(code)d %(message)s\n"
    error_content_type = "text/plain; charset=utf-8"
    server: _Server
    #: Seconds for the whole request head (:data:`REQUEST_TIMEOUT`).
    timeout = REQUEST_TIMEOUT

    def version_string(self) -> str:
        return self.server_version  # not Python's version

    def setup(self) -> None:
        super().setup()
        self.rfile = io.BufferedReader(_Deadline(self.connection, self.timeout))

    def parse_request(self) -> bool:
        """The standard checks of the request line and headers, then :func:`refusal`: a
        request for another host is answered 403 before any route (or method) runs."""
        if not super().parse_request():
            return False
        self.connection.settimeout(SEND_TIMEOUT)
        why = refusal(self.headers, self.server.server_address[1])
        if why is not None:
            self._send(403, f"403 Forbidden: {why}\n".encode(), "text/plain; charset=utf-8")
            return False
        if not self.path.startswith("/"):  # "*", or a full URL as sent to a proxy
            self.send_error(400, "the request target must be a path")
            return False
        return True

    def do_GET(self) -> None:
        path, _, query = self.path.partition("?")
        if path.startswith("/api/"):
            fields = dict(parse_qsl(query, keep_blank_values=True))
            status, answer = api.handle(
                path.removeprefix("/api/"), fields, self.server.uncertainty_map
            )
            self._send(status, _json(answer), "application/json")
        elif path in FILES:
            name, kind = FILES[path]
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
    request_queue_size = BACKLOG
    # Requests in progress must not hold up Ctrl-C: their threads die with the process.
    daemon_threads = True
    block_on_close = False
    verbose = False
    #: The map of the P(JARM) panel (None: no panel).
    uncertainty_map: UncertaintyMap | None = None

    def __init__(self, address: tuple[str, int], handler: type[_Handler]) -> None:
        super().__init__(address, handler)
        self._workers = threading.BoundedSemaphore(WORKERS)
        self._stopping = False

    def process_request(self, request: Any, client_address: Any) -> None:
        """Hand the connection to a handler thread once one of the :data:`WORKERS` is free;
        until then this loop accepts nobody and new clients wait in the backlog. The wait
        is in short steps, so that Ctrl-C and :meth:`shutdown` end it at once."""
        while not self._workers.acquire(timeout=0.1):
            if self._stopping:
                self.shutdown_request(request)
                return
        try:
            super().process_request(request, client_address)
        except BaseException:
            self._workers.release()
            raise

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self._workers.release()

    def shutdown(self) -> None:
        self._stopping = True
        super().shutdown()

    def handle_error(self, request: Any, client_address: Any) -> None:
        """A client that went away or was too slow (an OSError) is no error of the server:
        nothing to print. Anything else is a bug, and its traceback goes to stderr."""
        if isinstance(sys.exc_info()[1], OSError):
            if self.verbose:
                print(f"{client_address}: {sys.exc_info()[1]}", file=sys.stderr)
            return
        super().handle_error(request, client_address)


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

    ``port=0`` takes any free port (:attr:`url` tells which). ``uncertainty``: an
    :class:`~eccjump.UncertaintyMap` (or the path of its file) whose P(JARM) the page shows
    beside the JARM region, on the slice of the current k_m. Use :meth:`start` to serve
    from a background thread (a notebook, a test) and :meth:`stop` to end it, or
    :meth:`serve_forever` to serve from this thread until Ctrl-C. Also a context manager
    (``with ExplorerServer(0) as server: ...`` serves in the background while inside).

    Raises
    ------
    OSError
        When the port cannot be had (in use, or not allowed), or the uncertainty map's file
        cannot be read.
    ValueError
        For an ``uncertainty`` file that is no uncertainty map (a map of another kind is
        named).
    """

    def __init__(
        self,
        port: int = DEFAULT_PORT,
        *,
        verbose: bool = False,
        uncertainty: UncertaintyMap | str | os.PathLike | None = None,
    ) -> None:
        # the map first: a bad file is refused before the port is taken
        umap = None if uncertainty is None else checked_map(uncertainty, "uncertainty")
        self._httpd = _Server((HOST, port), _Handler)
        self._httpd.verbose = verbose
        self._httpd.uncertainty_map = umap
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
