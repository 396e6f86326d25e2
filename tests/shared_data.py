"""Where the tests find the shared recorded accelerograms.  Not a test module."""
from __future__ import annotations

import os
from pathlib import Path


def records_dir() -> Path:
    """``FASTROCK_RECORDS_DIR``, or shared/data/records beside the repository."""
    env = os.environ.get("FASTROCK_RECORDS_DIR")
    if env:
        return Path(env)
    return Path(__file__).resolve().parents[2] / "shared" / "data" / "records"
