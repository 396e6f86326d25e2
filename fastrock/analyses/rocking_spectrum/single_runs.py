"""One run of a block under a record, as the spectrum runs it.
"""
from __future__ import annotations

from fastrock import _validate as V
from fastrock.analyses.rocking_spectrum.inputs import load_records


# ------------------------------------------------------------ single runs
#: Most fixed steps per record interval in simulate_record.
MAX_SUBSTEPS = 1_000_000


def simulate_record(body, record, fixed_step=False, *, substeps=1, unit=None, **kw):
    """Simulate ``body`` under a record; the fixed step can follow the record.

    Parameters
    ----------
    body : RigidBlock
    record : GroundMotion, SampledMotion or path
    fixed_step : bool
        True: fixed-step DP5 with ``dt = record.dt / substeps`` (steps end
        on the record samples, where the interpolated signal has its kinks).
        False: adaptive RK45 (``rtol``...).
    substeps : int
        Fixed steps per record interval (with ``fixed_step``).
    **kw
        Passed to :func:`fastrock.simulate` (wall, rtol, t_after, ...).

    Returns
    -------
    SimulationResult
    """
    from fastrock.running.simulate import simulate
    (rec,) = load_records(record, unit)
    if fixed_step:
        if kw.get("dt") is not None or kw.get("solver") is not None:
            raise ValueError("give either fixed_step=True or dt=/solver=, not both")
        substeps = V.integer("substeps", substeps, 1, MAX_SUBSTEPS)
        kw["dt"] = rec.dt / substeps
    return simulate(body, rec, **kw)


