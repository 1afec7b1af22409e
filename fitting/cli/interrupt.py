"""Ctrl-C in a command-line tool: one line and exit status 130 (128 + SIGINT, as a shell
reports it), not a traceback. What a tool writes is written whole or not at all
(:func:`fitting.shared.files.write_atomic`), so an interrupted run leaves no half-written file."""
from __future__ import annotations

import functools
import sys

INTERRUPTED = 130


def exits_on_interrupt(prog: str):
    """Decorate a tool's ``main(argv=None) -> int``: a KeyboardInterrupt ends it with one line
    on stderr and :data:`INTERRUPTED`."""
    def wrap(main):
        @functools.wraps(main)
        def run(argv=None):
            try:
                return main(argv)
            except KeyboardInterrupt:
                print(f"\n{prog}: interrupted (Ctrl-C); files already written are whole, the rest were not "
                      "written", file=sys.stderr)
                return INTERRUPTED
        return run
    return wrap
