"""The record shipped with the package (fastrock/data).
"""
from __future__ import annotations

from importlib import resources

from fastrock.io.ground_motion import GroundMotion
from fastrock.io.readers import read_record


_DEFAULT_RECORD_NAME = "El Centro 1940 N-S (USC&GS)"


def load_default_record() -> GroundMotion:
    """The packaged 1940 El Centro N-S record (USC&GS, 1559 points, dt 0.02 s).

    Public-domain US federal data; PGA 0.319 g.  Samples are in g in the
    file and returned in m/s².

    Returns
    -------
    GroundMotion
    """
    res = resources.files("fastrock") / "data" / "elcentro_ns.at2"
    with resources.as_file(res) as path:
        return read_record(path, name=_DEFAULT_RECORD_NAME)
