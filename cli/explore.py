"""``baranov explore``: a local web page where every assembly mode of a scene or robot is
redrawn while its dimensions are dragged (:mod:`baranov.explore`)."""

from __future__ import annotations

import argparse
import signal
import sys
from pathlib import Path


def add_explore_parser(commands) -> None:
    explore = commands.add_parser("explore", help="every assembly mode redrawn live while dimensions are dragged, "
                                                  "in a local web page")
    explore.add_argument("scene", type=Path, help="scene JSON file, or a robot file (see examples/)")
    explore.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    explore.add_argument("--method", default="numeric",
                         help="solving backend of every redraw (default numeric; the page can switch)")
    explore.add_argument("--no-browser", action="store_true",
                         help="print the address, do not open a browser (none opens without a display either)")


def run_explore(args: argparse.Namespace) -> int:
    from baranov.explore.server import serve
    from baranov.solvers import available_backends

    from .main import UsageError

    if args.method not in available_backends():
        raise UsageError(f"--method {args.method}: choose from {', '.join(available_backends())}")
    if not 0 <= args.port < 65536:
        raise UsageError(f"--port {args.port}: a port number from 0 (a free one) to 65535")

    def announce(url: str) -> None:
        print(f"baranov explore: {args.scene} at {url} (Ctrl-C stops)", flush=True)

    def stop(signum: int, frame) -> None:
        raise KeyboardInterrupt  # SIGTERM stops the server like Ctrl-C

    # installed, not inherited: a process started in the background of a script (or by a test
    # runner's worker) ignores SIGINT, and Ctrl-C would not stop it
    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, stop)

    try:
        serve(args.scene, args.port, args.method, open_browser=not args.no_browser, announce=announce)
    except OSError as error:  # the port taken
        raise UsageError(f"--port {args.port}: {error.strerror}") from None
    except KeyboardInterrupt:
        print("baranov explore: stopped", file=sys.stderr)
    return 0
