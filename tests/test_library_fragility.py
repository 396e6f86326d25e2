"""Fragility fits through SciPy (issue #16, item 4): the probit MLE by scipy.optimize and the
normal CDF by scipy.special give what the hand-written Newton MLE and math.erfc gave
(tests/probit_reference.py), to 1e-6 relative."""
import numpy as np
import pandas as pd
import pytest
from scipy import stats

import fastrock.analyses.fragility as S
import probit_reference as R


def _frame(seed, n_rec=12, levels=(0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0), theta=0.4, beta=0.5):
    rng = np.random.default_rng(seed)
    rows = []
    for r in range(n_rec):
        for lv in levels:
            p = stats.norm.cdf(np.log(lv / theta) / beta)
            rows.append({"record": f"r{r}", "pga_g": lv, "outcome": "mode1" if rng.random() < p else "safe"})
    return pd.DataFrame(rows)


def _with_reference(call):
    saved = {k: getattr(S, k) for k in ("_probit_mle", "_fragility")}
    S._probit_mle, S._fragility = R._probit_mle, R._fragility
    try:
        return call()
    finally:
        for k, v in saved.items():
            setattr(S, k, v)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fragility_fit_and_bootstrap_as_before(seed):
    df = _frame(seed)
    new = S.fit_fragility(df, n_boot=40, seed=seed)
    old = _with_reference(lambda: S.fit_fragility(df, n_boot=40, seed=seed))
    assert new.theta == pytest.approx(old.theta, rel=1e-6)
    assert new.beta == pytest.approx(old.beta, rel=1e-6)
    assert new.loglik == pytest.approx(old.loglik, rel=1e-9)
    assert new.se_beta == pytest.approx(old.se_beta, rel=1e-5)
    assert new.n_boot_failed == old.n_boot_failed
    np.testing.assert_allclose(new.boot_theta, old.boot_theta, rtol=1e-6)
    np.testing.assert_allclose(new.boot_beta, old.boot_beta, rtol=1e-6)


def test_normal_cdf_and_mills_ratio_in_both_tails():
    z = np.array([-60.0, -38.5, -20.0, -3.0, 0.0, 2.5, 9.0])
    np.testing.assert_allclose(S._fragility(np.exp(z), 1.0, 1.0), R._ndtr(z), rtol=1e-12, atol=0)
    np.testing.assert_allclose(S._mills(z), R._mills(z), rtol=1e-6)
    assert np.isfinite(S._mills(np.array([-1e3]))).all()
