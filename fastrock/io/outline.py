"""Body outlines from text files: one vertex per row, x and y in metres.

A survey of a rock or a drawing of a tombstone exported as CSV or plain text:
two numbers per row, separated by a comma, a semicolon, a tab or spaces.
Lines starting with ``#`` and a first line of column names (``x,y``) are
skipped.  Anything else -- a row with one or three numbers, a word among the
numbers, NaN or inf, fewer than three vertices -- is refused with the file and
line, rather than guessed.  The outline is not closed: the last vertex must
not repeat the first (a repeated closing vertex is dropped).
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

_SEP = re.compile(r"[,;\s]+")


def read_outline(path) -> np.ndarray:
    """The vertices of a 2D outline file, shape (n, 2) [m].

    Raises
    ------
    ValueError
        A malformed file, naming the file and the line.
    OSError
        The file cannot be read.
    """
    path = Path(path)
    rows = []
    for lineno, line in enumerate(path.read_text(errors="replace").splitlines(), start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        tokens = [t for t in _SEP.split(text) if t]
        try:
            values = [float(t) for t in tokens]
        except ValueError:
            if not rows and all(re.fullmatch(r"[A-Za-z_\[\]()/ ]+", t) for t in tokens):
                continue                          # a header of column names
            raise ValueError(f"outline {path}, line {lineno}: {text!r} is not two numbers x y [m]") from None
        if len(values) != 2:
            raise ValueError(f"outline {path}, line {lineno}: {len(values)} numbers, expected two (x y [m])")
        if not all(math.isfinite(v) for v in values):
            raise ValueError(f"outline {path}, line {lineno}: {text!r} is not finite")
        rows.append(values)
    if len(rows) > 1 and rows[0] == rows[-1]:
        rows.pop()
    if len(rows) < 3:
        raise ValueError(f"outline {path}: {len(rows)} vertices, an outline needs at least 3")
    return np.array(rows, dtype=float)
