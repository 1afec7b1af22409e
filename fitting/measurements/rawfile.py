"""What the DMA readers share: the error a bad file raises and the rows of one file (or one
TRIOS step) before unit conversion. A leaf module, so that the readers of each format
(:mod:`fitting.measurements.dma`, :mod:`fitting.measurements.eplexor`, :mod:`fitting.measurements.relaxation`) import it and not
each other."""
from __future__ import annotations

import dataclasses

__all__ = ["DMAFormatError", "Block"]


class DMAFormatError(ValueError):
    """A DMA file that cannot be read; the message names the file, the line and the problem."""

    def __init__(self, path, line, problem):
        self.path, self.line, self.problem = str(path), line, problem
        where = f"{self.path}" + (f", line {line}" if line is not None else "")
        super().__init__(f"{where}: {problem}")


@dataclasses.dataclass
class Block:
    """Rows of one file (or one TRIOS step) before unit conversion."""
    path: str
    names: list          # header names (units removed)
    units: list          # one unit per name ('' when none)
    rows: list           # list of lists of float
    lines: list          # 1-based line number of each row
    header_line: int
    T_nominal: float | None = None
    set_hint: int | None = None
    kind_hint: str | None = None
