"""A Jupyter server extension: kernel messages reach the browser without waiting.

jupyter_server leaves Nagle's algorithm on for the websocket that carries a
kernel's messages to the browser.  An explorer's move sends several small
messages back to back (the kernel's "busy", the widget's echo, the figure's
picture, the description, "idle"); with Nagle's algorithm each waits for the
browser to acknowledge the one before, and the browser delays its
acknowledgements by up to 40 ms (Linux).  Measured on these machines, a
websocket client's ``execute("pass")`` took a median 44 ms to its "idle"
through the server, 5 ms with this extension (4.6 ms straight to the kernel).

The extension turns Nagle's algorithm off (``TCP_NODELAY``) on every kernel
websocket the server opens, as tornado's documentation advises for
interactive traffic.  ``make lab``, the browser tests and
``benchmarks/bench_widgets.py`` load it::

    PYTHONPATH=tools/lab_server jupyter lab \\
        --ServerApp.jpserver_extensions=twolink_nodelay=True

Without it everything works, only slower; nothing in the package needs it.
"""

from __future__ import annotations

import functools
from typing import Any

from jupyter_server.services.kernels.websocket import KernelWebsocketHandler

#: Marks the wrapped ``open`` so that loading the extension twice wraps once.
_MARK = "_twolink_nodelay"


def _jupyter_server_extension_points() -> list[dict[str, str]]:
    return [{"module": "twolink_nodelay"}]


def nodelay_open(open_handler: Any) -> Any:
    """``open_handler`` (a websocket's ``open``), turning Nagle's algorithm off first."""

    @functools.wraps(open_handler)
    async def open_without_delay(self: Any, *args: Any, **kwargs: Any) -> Any:
        self.set_nodelay(True)
        return await open_handler(self, *args, **kwargs)

    setattr(open_without_delay, _MARK, True)
    return open_without_delay


def _load_jupyter_server_extension(server_app: Any) -> None:
    if not getattr(KernelWebsocketHandler.open, _MARK, False):
        KernelWebsocketHandler.open = nodelay_open(KernelWebsocketHandler.open)
    server_app.log.info("twolink_nodelay: kernel websockets send without Nagle's delay")
