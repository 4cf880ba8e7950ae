"""The explorer's local web server: the page and its static files, and a small JSON API
the page calls while a dimension is dragged (standard library only: ``http.server``).

Routes (every POST body and answer is JSON, unless said otherwise):

* ``GET /`` — the page; ``GET /static/<file>`` — its script and style sheet.
* ``GET /api/document`` — the document's title, kind, controls, methods, and the first
  redraw (``frame``) with its ``view`` box.
* ``POST /api/solve`` ``{"values", "method", "previous", "next_id"}`` — a redraw
  (:func:`~baranov.explore.frames.solve_frame`).
* ``POST /api/profile`` ``{"values", "name", "samples"}`` — the number of modes across a
  dimension's range (:func:`~baranov.explore.frames.dimension_profile`).
* ``POST /api/trace`` ``{"values"}`` — a moving linkage's traced motion
  (:func:`~baranov.explore.traced_motion.traced_motion`).
* ``POST /api/export/scene`` ``{"values"}`` — the scene (or robot) file with the current
  dimensions; ``/api/export/modes`` ``{"values", "method", "format"}`` — the modes as
  ``baranov solve --format json`` or ``csv`` writes them; ``/api/export/png`` — the
  drawing ``baranov solve --plot`` makes.

Solves run one at a time (:data:`baranov.explore.frames.SOLVING`): the backends' caches
are shared by the process; a long request (a profile, a trace) lets redraws in between.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import traceback
import webbrowser
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from pathlib import Path

from baranov.scene import SceneError
from baranov.solvers import SolverError, available_backends

from .document import Document, document_data, load_document
from .frames import dimension_profile, solve_document, solve_frame, view_box

#: The static files the page needs, and their content types.
STATIC_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
                ".css": "text/css; charset=utf-8"}
#: The longest request body taken (a redraw's ``previous`` of a few hundred modes).
LARGEST_BODY = 8 * 2**20


class ExplorerServer(ThreadingHTTPServer):
    """An HTTP server of one document (``document``), on 127.0.0.1."""

    daemon_threads = True

    def __init__(self, document: Document, port: int = 0, method: str = "numeric"):
        super().__init__(("127.0.0.1", port), ExplorerHandler)
        self.document = document
        self.method = method

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.server_address[1]}/"


class ExplorerHandler(BaseHTTPRequestHandler):
    """Routes of :mod:`baranov.explore.server`."""

    server: ExplorerServer
    protocol_version = "HTTP/1.1"  # keep-alive: one connection for a drag's redraws (every answer has a length)
    disable_nagle_algorithm = True  # else headers and body wait for a delayed ACK: 40 ms a redraw

    def log_message(self, format: str, *args) -> None:  # noqa: A002 - the base class's name
        pass  # a request line per redraw would flood the terminal

    def do_GET(self) -> None:
        if self.path in ("/", "/index.html"):
            self._static("index.html")
        elif self.path.startswith("/static/"):
            self._static(self.path.removeprefix("/static/"))
        elif self.path == "/api/document":
            self._json(self._document())
        elif self.path == "/favicon.ico":
            self._send(b"", "image/x-icon", status=HTTPStatus.NO_CONTENT)
        else:
            self._fail(HTTPStatus.NOT_FOUND, f"{self.path}: no such page")

    def do_POST(self) -> None:
        routes = {"/api/solve": self._solve, "/api/profile": self._profile, "/api/trace": self._trace,
                  "/api/export/scene": self._export_scene,
                  "/api/export/modes": self._export_modes, "/api/export/png": self._export_png}
        route = routes.get(self.path)
        if route is None:
            self._fail(HTTPStatus.NOT_FOUND, f"{self.path}: no such request")
            return
        try:
            length = int(self.headers.get("Content-Length", 0))
            if length > LARGEST_BODY:
                raise ValueError(f"request of {length} bytes: too large")
            body = json.loads(self.rfile.read(length) or b"{}")
            if not isinstance(body, dict):
                raise ValueError("expected a JSON object")
            route(body)
        except (SceneError, SolverError, ValueError) as error:
            self._fail(HTTPStatus.BAD_REQUEST, str(error))
        except Exception as error:  # a fault of ours: the page says so and the server goes on
            traceback.print_exc()
            self._fail(HTTPStatus.INTERNAL_SERVER_ERROR, f"internal error ({type(error).__name__}: {error}); the "
                                                         "server printed the traceback: please report it")

    def _document(self) -> dict:
        document = self.server.document
        values = {control.name: control.value for control in document.controls}
        frame = solve_frame(document, values, self.server.method)
        return {"title": document.title, "kind": document.kind, "ground": document.scene.ground,
                "mobility": document.scene.mobility,
                "controls": [control.to_dict() for control in document.controls],
                "methods": available_backends(), "method": self.server.method, "frame": frame,
                "view": view_box(document, frame)}

    def _solve(self, body: dict) -> None:
        method = self._method(body)
        previous = body.get("previous")
        if previous is not None:
            if not isinstance(previous, dict):
                raise ValueError("previous: expected the last redraw, {\"values\": {...}, \"modes\": [...]}")
            self._values(previous)
            if not isinstance(previous.get("modes"), list) or not all(
                    isinstance(mode, dict) and {"id", "joints"} <= mode.keys() for mode in previous["modes"]):
                raise ValueError("previous: expected {\"values\": {...}, \"modes\": [{\"id\": 0, \"joints\": {...}}]}")
        self._json(solve_frame(self.server.document, self._values(body), method, previous,
                               int(body.get("next_id", 0))))

    def _profile(self, body: dict) -> None:
        samples = min(max(int(body.get("samples", 101)), 3), 1001)
        self._json(dimension_profile(self.server.document, self._values(body), str(body.get("name")), samples))

    def _trace(self, body: dict) -> None:
        from .traced_motion import traced_motion

        self._json(traced_motion(self.server.document, self._values(body)))

    def _values(self, body: dict) -> dict:
        """The request's values, every name a control of the document (else ControlError:
        a page that asks for another document's dimension, not a value to draw)."""
        values = body.get("values", {})
        if not isinstance(values, dict):
            raise ValueError("values: expected an object such as {\"P1,P2\": 17}")
        for name in values:
            self.server.document.control(name)
        return values

    def _export_scene(self, body: dict) -> None:
        document = self.server.document
        data = document_data(document, body.get("values", {}))
        self._send(json.dumps(data, indent=1).encode(), "application/json", _exported_name(document, ".json"))

    def _export_modes(self, body: dict) -> None:
        _, solution, _ = solve_document(self.server.document, body.get("values", {}), self._method(body))
        if body.get("format") == "csv":
            self._send(solution.to_csv().encode(), "text/csv", _exported_name(self.server.document, "-modes.csv"))
        else:
            self._send(json.dumps(solution.to_dict(), indent=1).encode(), "application/json",
                       _exported_name(self.server.document, "-modes.json"))

    def _export_png(self, body: dict) -> None:
        from baranov.solvers.drawing import render_modes

        scene, solution, _ = solve_document(self.server.document, body.get("values", {}), self._method(body))
        self._send(render_modes(scene, solution), "image/png", _exported_name(self.server.document, ".png"))

    def _method(self, body: dict) -> str:
        method = str(body.get("method", self.server.method))
        if method not in available_backends():
            raise ValueError(f"method {method!r}: choose from {', '.join(available_backends())}")
        return method

    def _static(self, name: str) -> None:
        suffix = Path(name).suffix
        if "/" in name or suffix not in STATIC_TYPES:
            self._fail(HTTPStatus.NOT_FOUND, f"{name}: no such file")
            return
        try:
            content = resources.files("baranov.explore").joinpath("static", name).read_bytes()
        except (FileNotFoundError, IsADirectoryError):
            self._fail(HTTPStatus.NOT_FOUND, f"{name}: no such file")
            return
        self._send(content, STATIC_TYPES[suffix])

    def _json(self, value) -> None:
        self._send(json.dumps(value, allow_nan=False, default=_jsonable).encode(), "application/json")

    def _fail(self, status: HTTPStatus, message: str) -> None:
        self._send(json.dumps({"error": message}).encode(), "application/json", status=status)

    def _send(self, content: bytes, kind: str, filename: str | None = None, status: HTTPStatus = HTTPStatus.OK) -> None:
        self.send_response(status)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(content)))
        self.send_header("Cache-Control", "no-store")
        if filename:
            self.send_header("Content-Disposition", f'attachment; filename="{filename}"')
        self.end_headers()
        self.wfile.write(content)


def _jsonable(value):
    """Numbers JSON has no literal for (a Fraction in a robot's pose, numpy floats)."""
    return float(value)


def _exported_name(document: Document, suffix: str) -> str:
    return Path(document.title).stem + "-explored" + suffix


def _graphical() -> bool:
    """Whether a graphical browser can open here: macOS, Windows, or a display on Linux.
    Without one, Python's ``webbrowser`` would start a text browser in the terminal."""
    return sys.platform in ("darwin", "win32") or bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def serve(path: str | Path, port: int = 0, method: str = "numeric", open_browser: bool = True,
          announce=print) -> None:
    """Serve the explorer of the scene or robot file ``path`` on 127.0.0.1 (``port``, 0:
    a free one) until interrupted; ``announce`` is given the address, and the user's
    browser opens it where there is a display (``open_browser``). The file is read and
    checked before the server starts."""
    document = load_document(path)
    server = ExplorerServer(document, port, method)
    announce(server.url)
    if open_browser and _graphical():
        threading.Thread(target=webbrowser.open, args=(server.url,), daemon=True).start()
    try:
        server.serve_forever()
    finally:
        server.server_close()
