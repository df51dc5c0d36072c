"""The explorer's page from Python: the static site's page and engine (WebAssembly), bundled in
the package and served to this machine alone, shown in a notebook or opened in a browser.

Everything is computed in the browser by the same engine as the command line's; Python only
serves the page's files, so the page works offline and keeps no process of its own busy.
"""

from __future__ import annotations

import functools
import http.server
import os
import threading
import urllib.parse
import webbrowser
from typing import Any, Dict, Optional

#: Where the package holds the static site (`cargo xtask site` writes it there when the package
#: is built for release).
PAGE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "page")

#: The types of the site's files, whatever this machine's own table says (a browser compiles
#: WebAssembly as it arrives only when it is served as application/wasm).
_TYPES = {
    ".html": "text/html; charset=utf-8",
    ".js": "text/javascript; charset=utf-8",
    ".css": "text/css; charset=utf-8",
    ".wasm": "application/wasm",
    ".json": "application/json",
    ".png": "image/png",
    ".svg": "image/svg+xml",
}


class _PageHandler(http.server.SimpleHTTPRequestHandler):
    """The site's files, read-only, to this machine; nothing is logged to the notebook."""

    extensions_map = {"": "application/octet-stream", **_TYPES}

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 (the base's name)
        pass

    def end_headers(self) -> None:
        # The service worker keeps the page offline; the files it lists are checked by hash.
        self.send_header("Cache-Control", "no-cache")
        super().end_headers()

    def list_directory(self, path: Any) -> None:
        self.send_error(404, "No listing")
        return None


_lock = threading.Lock()
_server: Optional[http.server.ThreadingHTTPServer] = None


def page_available() -> bool:
    """Whether this install holds the explorer's page."""
    return os.path.isfile(os.path.join(PAGE_DIR, "index.html")) and os.path.isdir(
        os.path.join(PAGE_DIR, "pkg")
    )


def serve() -> str:
    """The address of the page's files, served from a thread of this process to this machine
    alone (127.0.0.1, a free port), started at the first call and kept for the process's life."""
    global _server
    if not page_available():
        raise RuntimeError(
            "this install of bentstraw holds no explorer page: the released wheels and source "
            "archive carry it; a package built from the repository gets it with "
            "`cargo xtask site crates/bentstraw-py/python/bentstraw/page` before `pip install`"
        )
    with _lock:
        if _server is None:
            handler = functools.partial(_PageHandler, directory=PAGE_DIR)
            _server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
            _server.daemon_threads = True
            threading.Thread(target=_server.serve_forever, name="bentstraw-page", daemon=True).start()
        port = _server.server_address[1]
    return f"http://127.0.0.1:{port}/"


def address(query: Dict[str, str]) -> str:
    """The page's address opening the view ``query`` (its names the command line's flags)."""
    return serve() + "index.html#" + urllib.parse.urlencode(query, quote_via=urllib.parse.quote)


class Explorer:
    """The explorer's page for one view: shown in a notebook cell as an embedded frame, or opened
    in a browser with :meth:`open`. ``url`` is its address on this machine."""

    def __init__(self, url: str, height: int) -> None:
        self.url = url
        self.height = height

    def _repr_html_(self) -> str:
        import html

        return (
            f'<iframe src="{html.escape(self.url)}" width="100%" height="{self.height}" '
            'style="border:1px solid #ccc" allow="clipboard-write; fullscreen" '
            'title="bentstraw explorer"></iframe>'
        )

    def open(self) -> bool:
        """Opens the page in this machine's web browser; whether one was found."""
        return webbrowser.open(self.url)

    def __repr__(self) -> str:
        return f"<bentstraw explorer at {self.url}>"
