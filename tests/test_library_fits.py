"""Fits through SciPy (issue #16, item 4): scipy.optimize.least_squares gives the parameters
of the hand-written Levenberg-Marquardt fitter it replaced (tests/lm_reference.py) to 1e-6
relative, on the packaged measurements and on synthetic foundation data."""
import math

import numpy as np
import pytest

from fastrock.analyses.freerocking import csv_input
from fastrock.analyses.freerocking import fitting
from fastrock.analyses.freerocking import housner
from fastrock.analyses.freerocking import periods
from fastrock.analyses.freerocking import yu2019
from fastrock.analyses.foundation_predictors import two_spring_predictor
from lm_reference import _levenberg_marquardt

YU_CSV = yu2019._DATA_DIR / "yu2019_halfcycles.csv"


def _both(fit):
    new = fit()
    library = fitting._minimise
    fitting._minimise = _levenberg_marquardt
    try:
        old = fit()
    finally:
        fitting._minimise = library
    return new, old


def _same_parameters(new, old, rel=1e-6):
    assert new.success and old.success
    assert set(new.params) == set(old.params)
    for k in new.params:
        assert new.params[k] == pytest.approx(old.params[k], rel=rel), k
    assert new.cost <= old.cost * (1 + 1e-6) + 1e-30


@pytest.mark.parametrize("definition", ["impact", "peak"])
def test_the_measured_series_fits_as_before(definition):
    new, old = _both(lambda: csv_input.fit_from_csv(YU_CSV, alpha=math.radians(14.8), definition=definition))
    _same_parameters(new, old)
    for k in ("p", "e"):
        assert new.params_std[k] == pytest.approx(old.params_std[k], rel=1e-4)


def test_one_release_angle_with_peaks_fits_as_before():
    rng = np.random.default_rng(16)
    alpha, theta0 = 0.25, 0.15
    d = housner.housner_half_cycle_durations(theta0, alpha, 3.0, 0.9, 12)
    peaks = housner.housner_amplitudes(theta0, alpha, 0.9, 12)[1:13]
    d = d * (1 + 0.01 * rng.standard_normal(d.size))
    new, old = _both(lambda: fitting.fit_free_rocking(d, theta0, alpha, peaks=peaks, p0=2.5, e0=0.8))
    _same_parameters(new, old)


def test_a_foundation_model_fits_as_before():
    alpha, t0s = 0.25, [0.1, 0.15]
    true = {"p": 3.0, "omega": 30.0, "zeta": 0.08}
    rng = np.random.default_rng(4)
    ds = [np.asarray(two_spring_predictor({**true, "theta0": t, "alpha": alpha, "definition": "impact"}, 10))
          * (1 + 0.002 * rng.standard_normal(10)) for t in t0s]
    kw = dict(model="two-spring", params0={"p": 2.8, "omega": 27.0, "zeta": 0.06},
              bounds={"omega": (0, np.inf), "zeta": (0, 2)})
    new, old = _both(lambda: fitting.fit_free_rocking(ds, t0s, alpha, **kw))
    _same_parameters(new, old)


def test_elliptic_integral_equals_the_arithmetic_geometric_mean():
    """K(k) from scipy.special (ellipkm1 of 1 - k^2) against the AGM it replaced,
    K = pi / (2 AGM(1, sqrt(1 - k^2))), up to k = 1 - 1e-12."""
    k = np.array([0.0, 1e-8, 0.3, 0.5, 0.9, 0.999, 1 - 1e-9, 1 - 1e-12])
    a, b = np.ones_like(k), np.sqrt((1.0 - k) * (1.0 + k))
    for _ in range(64):
        a, b = 0.5 * (a + b), np.sqrt(a * b)
    np.testing.assert_allclose(periods.ellipk_agm(k), 0.5 * np.pi / a, rtol=1e-14)
    with pytest.raises(ValueError, match="k must"):
        periods.ellipk_agm(1.0)
