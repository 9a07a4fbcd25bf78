"""The cncc language server (``cncc lsp``): the compiler as a linter and assistant.

``serve(args)`` starts the server on stdio (``--tcp HOST:PORT`` for debugging).
Only the protocol layer is imported at start-up; the compiler, numpy and the
solvers are imported by the first analysis that needs them.
"""

from __future__ import annotations

from collections.abc import Sequence

USAGE = """usage: cncc lsp [--stdio] [--tcp HOST:PORT] [--log FILE]

Start the cncc language server (stdio by default).  Settings come from cncc.toml
in the workspace and from the client's initialization options; see docs/editors.md.
"""


def serve(args: Sequence[str] = ()) -> int:
    """Run the language server until the client disconnects; returns the exit status."""
    import sys

    argv = list(args)
    tcp: str | None = None
    log: str | None = None
    while argv:
        arg = argv.pop(0)
        if arg in ("-h", "--help"):
            sys.stdout.write(USAGE)
            return 0
        if arg == "--stdio":
            continue
        if arg == "--tcp" and argv:
            tcp = argv.pop(0)
        elif arg == "--log" and argv:
            log = argv.pop(0)
        else:
            sys.stderr.write(f"cncc lsp: unknown argument {arg!r}\n{USAGE}")
            return 2
    if log:
        import logging

        logging.basicConfig(filename=log, level=logging.INFO)
    from cncc.lsp.server import build

    server = build()
    if tcp:
        host, _, port = tcp.rpartition(":")
        server.start_tcp(host or "127.0.0.1", int(port))
    else:
        server.start_io()
    return 0
