"""Memory of big spectra (issue #15, item 5): the grid values come from each row's id (no
full-grid input arrays), the filled columns become the table without a copy, and ``columns=``
keeps only the result columns asked for, with the same values."""
import tracemalloc

import numpy as np
import pandas as pd
import pytest

import fastrock as fr

BLOCK = fr.RigidBlock(alpha=0.25, p=2.0)
AMPS, FREQS = np.linspace(0.5, 8, 11), np.linspace(0.25, 10, 7)


def test_grid_columns_are_those_of_the_meshgrid():
    """Rows in (sign, frequency, amplitude) order, with chunks that cut the grid anywhere."""
    signs = [1, -1, 1]
    df = fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign=signs, pulse="half-sine", chunk_size=13,
                                 progress=False)
    S, F, A = (a.ravel() for a in np.meshgrid(np.array(signs, float), FREQS, AMPS, indexing="ij"))
    amp = A * BLOCK.g * np.tan(BLOCK.alpha)
    np.testing.assert_array_equal(df["amplitude_ratio"], A)
    np.testing.assert_array_equal(df["frequency_ratio"], F)
    np.testing.assert_array_equal(df["sign"], S.astype(int))
    np.testing.assert_array_equal(df["amplitude"], amp)
    np.testing.assert_array_equal(df["amplitude_g"], amp / BLOCK.g)
    np.testing.assert_array_equal(df["frequency_hz"], F * BLOCK.p / (2 * np.pi))
    one = fr.simulate(BLOCK, fr.Pulse(A[50], F[50], sign=int(S[50]), kind="half-sine",
                                      amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"))
    assert df["status"][50] == one.status


def test_columns_keeps_the_grid_and_the_asked_columns_with_the_same_values():
    full = fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign="both", progress=False)
    slim = fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign="both", progress=False,
                                   columns=["max_rotation_ratio", "outcome"])
    assert list(slim.columns) == ["amplitude_ratio", "frequency_ratio", "sign", "outcome", "max_rotation_ratio"]
    pd.testing.assert_frame_equal(slim, full[list(slim.columns)], check_exact=True)
    assert slim.attrs == full.attrs
    only = fr.overturning_spectrum(BLOCK, AMPS, FREQS, progress=False, columns="status")
    assert list(only.columns) == ["amplitude_ratio", "frequency_ratio", "sign", "status"]


def test_columns_streams_and_checks_boundaries(tmp_path):
    kw = dict(sign="both", progress=False, chunk_size=20, columns=["outcome", "time_end"])
    mem = fr.overturning_spectrum(BLOCK, AMPS, FREQS, **kw)
    back = fr.load_spectrum(fr.overturning_spectrum(BLOCK, AMPS, FREQS, out=tmp_path / "s", **kw))
    pd.testing.assert_frame_equal(back, mem, check_exact=True)
    full = fr.overturning_spectrum(BLOCK, AMPS[:4], FREQS[:3], progress=False, boundary_check=True)
    slim = fr.overturning_spectrum(BLOCK, AMPS[:4], FREQS[:3], progress=False, boundary_check=True,
                                   columns=["outcome"])
    pd.testing.assert_frame_equal(slim, full[list(slim.columns)], check_exact=True)
    assert "boundary" in slim


@pytest.mark.parametrize("columns, match", [
    (["outcome", "max_slide"], r"columns: \['max_slide'\] are not columns of this spectrum"),
    (3, "columns must be a list of column names"),
])
def test_columns_refuses_a_name_the_table_has_not(columns, match):
    with pytest.raises(ValueError, match=match):
        fr.overturning_spectrum(BLOCK, AMPS, FREQS, progress=False, columns=columns)


def test_boundary_check_needs_the_outcome():
    with pytest.raises(ValueError, match="boundary_check compares the outcomes; keep 'outcome'"):
        fr.overturning_spectrum(BLOCK, AMPS, FREQS, progress=False, boundary_check=True,
                                columns=["max_rotation"])


def _peak_over_table(n_freq):
    tracemalloc.start()
    try:
        df = fr.overturning_spectrum(BLOCK, np.linspace(0.5, 8, 100), np.linspace(0.25, 10, n_freq),
                                     progress=False, chunk_size=4096)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return peak - df.memory_usage(deep=True).sum(), len(df)


def test_peak_allocation_beyond_the_table_does_not_grow_with_the_grid():
    """Python-side allocations peak at the table plus one chunk's arrays, whatever the grid's
    size: no full-grid input arrays (48 bytes per row before) and no copy of the table when it
    is assembled."""
    fr.overturning_spectrum(BLOCK, [1.0], [1.0], progress=False)     # the kernel loaded
    (small, n_small), (big, n_big) = _peak_over_table(150), _peak_over_table(450)
    assert (n_small, n_big) == (15_000, 45_000)
    assert 0 < small < 4096 * 2000
    assert big - small < 8 * (n_big - n_small), (small, big)
