"""``eccjump explore``: the interactive explorer as a local web page (the user guide's page
"The explorer").

Serves the page on http://127.0.0.1:PORT/ until Ctrl-C, and opens it in the browser unless
``--no-browser``. Needs nothing beyond the standard library and eccjump itself.
"""

from __future__ import annotations

import argparse
import os
import sys
import threading
import webbrowser

from eccjump.cli._args import int_in
from eccjump.cli._output import OutputError
from eccjump.explorer.probability import checked_map
from eccjump.explorer.server import DEFAULT_PORT, ExplorerServer


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "explore",
        help="explore the jump interactively in a web browser (a local page)",
        description="Serve the explorer on this machine (127.0.0.1): sliders for the point, "
        "the JARM region slice, the animated full motion and its numbers. Prints the address; "
        "Ctrl-C stops it.",
    )
    p.add_argument(
        "--port",
        type=int_in(0, 65535),
        default=DEFAULT_PORT,
        help=f"port on 127.0.0.1 (default {DEFAULT_PORT}; 0: any free port)",
    )
    p.add_argument(
        "--uncertainty",
        metavar="FILE",
        help="an uncertainty map (eccjump map --kind uncertainty -o FILE): its P(JARM) is "
        "shown beside the JARM region, with the 0.5 and 0.95 contours",
    )
    p.add_argument(
        "--no-browser", action="store_true", help="print the address, do not open a browser"
    )
    p.set_defaults(func=_cmd_explore)


def _cmd_explore(args: argparse.Namespace) -> int:
    # the map first: a bad file is refused before the port is taken
    umap = None if args.uncertainty is None else checked_map(args.uncertainty, "--uncertainty")
    try:
        server = ExplorerServer(args.port, uncertainty=umap)
    except OSError as err:
        why = err.strerror or type(err).__name__
        raise OutputError(
            f"--port {args.port}: cannot listen on 127.0.0.1 ({why}); --port 0 takes a free port"
        ) from err
    print(f"eccjump explorer at {server.url}  (Ctrl-C stops it)", flush=True)
    if not args.no_browser:
        _open(server.url)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("eccjump explorer stopped", file=sys.stderr)
    return 0


def _open(url: str) -> None:
    """Open ``url`` in a graphical browser, from a thread (a browser can take its time to
    start). Without a display on Linux, say so instead: Python would start a text browser
    (lynx, w3m) in this terminal."""
    if sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    ):
        print("no display here: open the address in a browser yourself", flush=True)
        return
    threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()
