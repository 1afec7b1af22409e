"""A griffe extension for the API reference (mkdocs.yml): vjax's docstrings are Google-style
sections written with a few reStructuredText habits, which Markdown would show as written.

- ``:class:`~vjax.Material``` (and ``:func:``, ``:meth:``, ``:mod:``, ``:data:``, ``:attr:``,
  ``:exc:``): a link to the name's entry when the reference has one, else the name in code.
  A bare name (``:class:`PinResult```) is taken as ``vjax.PinResult``. These are optional
  links: a name without an entry is not an error (the ``::: vjax.<name>`` directives of
  docs/api/ are what breaks the build when a public name goes away).
- A doctest (lines from ``>>>`` to the next blank line): a ``pycon`` code block, not nested
  quotes.
- A paragraph ending in ``::`` before an indented block: one colon (the block is already
  Markdown's indented code).

The docstrings themselves stay as they are: pytest runs their doctests.
"""
from __future__ import annotations

import re

import griffe

ROLE = re.compile(r":(?:py:)?(?:class|func|meth|mod|data|attr|obj|exc):`(~?)([\w.]+)`")


def _link(match: re.Match) -> str:
    tilde, target = match.groups()
    title = target.rsplit(".", 1)[-1] if tilde else target
    identifier = target if target.startswith("vjax") else f"vjax.{target}"
    return f'<autoref identifier="{identifier}" optional><code>{title}</code></autoref>'


def _fence_doctests(text: str) -> str:
    out, lines, i = [], text.split("\n"), 0
    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith(">>>"):
            indent = line[: len(line) - len(line.lstrip())]
            out.append(f"{indent}```pycon")
            while i < len(lines) and lines[i].strip():
                out.append(lines[i])
                i += 1
            out.append(f"{indent}```")
            continue
        out.append(line[:-1] if line.endswith("::") else line)
        i += 1
    return "\n".join(out)


def convert(text: str) -> str:
    """The docstring ``text`` in Markdown (the three conversions of the module docstring)."""
    return _fence_doctests(ROLE.sub(_link, text))


class RstHabits(griffe.Extension):
    def on_instance(self, *, obj, **kwargs) -> None:
        if obj.docstring is not None:
            obj.docstring.value = convert(obj.docstring.value)
