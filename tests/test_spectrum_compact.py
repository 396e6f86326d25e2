"""Compact spectrum tables (issue #15, item 5): categorical outcome and status with every label,
int8 sign and side, int32 impact counts, exact values; streamed tables have the same dtypes."""
import numpy as np
import pandas as pd

import fastrock as fr
from fastrock.analyses.spectrum import CATEGORIES, COMPACT_INTEGERS
from fastrock.running.outcomes import outcome_of, status_of

BLOCK = fr.RigidBlock.rectangle(0.2, 0.8)
AMPS, FREQS = np.linspace(0.5, 8, 7), np.linspace(0.25, 10, 6)


def test_dtypes_and_every_label():
    df = fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign="both", progress=False)
    for name, cats in CATEGORIES.items():
        assert isinstance(df[name].dtype, pd.CategoricalDtype)
        assert tuple(df[name].cat.categories) == cats
    for name, dtype in COMPACT_INTEGERS.items():
        assert df[name].dtype == dtype
    assert df["max_rotation"].dtype == np.float64 and df["time_end"].dtype == np.float64
    assert set(df["outcome"]) >= {"safe", "mode1", "mode2"}
    assert df["outcome"].value_counts()["leaning"] == 0


def test_values_are_those_of_the_kernel_statuses():
    """The categorical labels are outcome_of / status_of of each run's own status."""
    df = fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign="both", progress=False, early_exit=False)
    for i in (0, 17, 40, len(df) - 1):
        r = fr.simulate(BLOCK, fr.Pulse(df["amplitude_ratio"][i], df["frequency_ratio"][i], sign=int(df["sign"][i]),
                                        amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"))
        assert df["status"][i] == r.status and df["outcome"][i] == r.outcome
    assert outcome_of(0) in CATEGORIES["outcome"] and status_of(0) in CATEGORIES["status"]


def test_two_spectra_compare_cell_by_cell():
    a = fr.overturning_spectrum(BLOCK, AMPS, FREQS, progress=False)
    b = fr.overturning_spectrum(BLOCK, AMPS, FREQS, wall=fr.Wall(0.01), progress=False)
    same = (a["outcome"] == b["outcome"]).to_numpy()
    assert same.dtype == bool and 0 < same.sum() < len(a)


def test_streamed_table_has_the_same_dtypes(tmp_path):
    df = fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign="both", progress=False)
    fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign="both", progress=False, out=tmp_path / "s", chunk_size=20)
    pd.testing.assert_frame_equal(fr.load_spectrum(tmp_path / "s"), df, check_like=False)
