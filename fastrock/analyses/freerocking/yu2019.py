"""The measured half-cycle durations of Yu et al.
"""
from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from fastrock.analyses.freerocking.csv_input import read_half_cycles_csv


# ----------------------------------------------------------------------------------------
# 5. Yu et al. data
# ----------------------------------------------------------------------------------------
#: Block of Yu et al. as stated (SI units): half-width ``b`` and half-height ``h`` [m],
#: corner-to-CM distance ``R`` [m], slenderness [deg], mass [kg], inertia about a corner [kg m^2].
#: Note: ``I0 = 0.3268`` exceeds ``2 M R^2 = 0.306`` (the largest value any body inside the
#: ``2b x 2h`` rectangle can have) and the uniform value ``4/3 M R^2 = 0.204``; the rig
#: presumably carries attachments. ``p`` below uses the stated ``I0``.
YU2019_BLOCK = {
    "half_width": 0.054,
    "half_height": 0.205,
    "R": 0.212,
    "alpha_deg": 14.8,
    "mass": 3.40,
    "I0": 0.3268,
    "g": 9.81,  # the paper's g: its published p = 4.6516 rad/s uses it
}
YU2019_BLOCK["p"] = math.sqrt(YU2019_BLOCK["mass"] * YU2019_BLOCK["g"] * YU2019_BLOCK["R"]
                              / YU2019_BLOCK["I0"])
YU2019_BLOCK["e_housner"] = 1.0 - (YU2019_BLOCK["mass"] * YU2019_BLOCK["R"] ** 2
                                   / YU2019_BLOCK["I0"]) * (
    1.0 - math.cos(2.0 * math.radians(YU2019_BLOCK["alpha_deg"])))
YU2019_BLOCK["e_housner_rectangle"] = 1.0 - 1.5 * math.sin(
    math.radians(YU2019_BLOCK["alpha_deg"])) ** 2

_DATA_DIR = Path(__file__).resolve().parents[2] / "data"


def load_yu2019() -> pd.DataFrame:
    """Measured half-cycle durations of Yu et al. (block on light felt, free release).

    Half-cycles 1-20 after releases from ``theta0 = 8, 10, 12.8 deg``. Their half-cycle ``n``
    (counted from the release) corresponds to our ``"impact"`` index ``n`` (impact ``n`` to
    impact ``n + 1``; see :func:`half_cycles` for the evidence); the release-to-first-impact
    segment (index 0) is not in the data.

    Notes
    -----
    Consecutive values come in nearly equal pairs (0.478/0.471, 0.386/0.380, ...): the
    duration drops by 15-20 % every *second* half-cycle and by only 1-3 % in between. A
    symmetric block -- rigid or on any symmetric foundation -- loses the same fraction at
    every impact, so its durations decay steadily under either definition ("impact" or
    "peak"); the pairing therefore indicates that dissipation alternates between the two
    corners (asymmetric contact on the felt), which none of the symmetric models reproduces.
    A symmetric fit averages over each pair (residuals alternate in sign), and its ``e`` is
    an effective per-impact value.

    The rigid model also over-predicts how strongly the first durations grow with ``theta0``
    (measured 0.478 / 0.519 / 0.579 s at 8 / 10 / 12.8 deg, exact Housner with the published
    ``p`` and ``e = 0.939``: 0.518 / 0.609 / 0.716 s), presumably the felt foundation. Joint
    Housner fit (shared ``p``, ``e``, ``alpha`` fixed at 14.8 deg): all 60 durations
    ``p = 4.72 +/- 0.11 rad/s``, ``e = 0.928 +/- 0.003``, RMS 0.025 s; rocking part only
    (durations > 0.15 s) ``p = 5.04 +/- 0.14 rad/s``, ``e = 0.939 +/- 0.003``, RMS 0.024 s.

    Returns
    -------
    pandas.DataFrame
        Columns ``theta0_deg`` [deg], ``half_cycle`` [-], ``duration`` [s];
        ``df.attrs`` holds :data:`YU2019_BLOCK` (with ``p`` [rad/s] = 4.652 from the stated
        ``I0``, and Housner's ``e``), ``alpha`` [rad] and ``definition = "impact"``.
    """
    df = read_half_cycles_csv(_DATA_DIR / "yu2019_halfcycles.csv")
    df.attrs.update(YU2019_BLOCK)
    df.attrs["alpha"] = math.radians(YU2019_BLOCK["alpha_deg"])
    df.attrs["definition"] = "impact"
    return df


