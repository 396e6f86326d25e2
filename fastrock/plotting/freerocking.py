"""Free-rocking figures: period against angle, fitted half-cycles.
"""
from __future__ import annotations

import numpy as np

from fastrock.analyses.freerocking.checks import check_alpha, check_positive
from fastrock.analyses.freerocking.fitting import FreeRockingFit
from fastrock.analyses.freerocking.housner import housner_half_cycle_durations
from fastrock.analyses.freerocking.periods import (pendulum_period, rocking_period_exact,
    rocking_period_linear, vibration_period)


# ----------------------------------------------------------------------------------------
# 6. plots
# ----------------------------------------------------------------------------------------
def _new_axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt
        _, ax = plt.subplots()
    return ax


def plot_period_vs_angle(alpha, p, omega=None, ax=None, n=200):
    """Period against initial angle (cf. Yu et al., Fig. 4).

    Draws the exact (:func:`rocking_period_exact`) and linearised
    (:func:`rocking_period_linear`) rocking periods ``T_C`` for ``0 < theta0 < alpha`` and,
    if ``omega`` is given, the linear vibration period ``T_L = 2 pi/omega`` (constant) and the
    pendulum period ``T_NL`` (:func:`pendulum_period`).

    Parameters
    ----------
    alpha : float
        Slenderness [rad].
    p : float
        Frequency parameter [rad/s].
    omega : float, optional
        Vibration circular frequency [rad/s].
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    n : int
        Number of angles.

    Returns
    -------
    matplotlib.axes.Axes
        Axes with x = initial angle [deg], y = period [s].
    """
    alpha = float(check_alpha(alpha))
    p = float(check_positive("p", p))
    ax = _new_axes(ax)
    th = np.linspace(0.005, 0.98, int(n)) * alpha
    ax.plot(np.degrees(th), rocking_period_exact(th, alpha, p), "-",
            label=r"rocking $T_C$ (exact)")
    ax.plot(np.degrees(th), rocking_period_linear(th, alpha, p), "--",
            label=r"rocking $T_C$ (linearised)")
    if omega is not None:
        omega = float(check_positive("omega", omega))
        ax.axhline(vibration_period(omega), color="k", ls=":", label=r"vibration $T_L$")
        ax.plot(np.degrees(th), pendulum_period(th, omega), "-.",
                label=r"pendulum $T_{NL}$")
    ax.set_xlabel(r"initial angle $\theta_0$ [deg]")
    ax.set_ylabel("period [s]")
    ax.legend()
    return ax


def plot_fit(fit: FreeRockingFit, measured=None, published=None, ax=None):
    """Measured, published-parameter and fitted half-cycle durations in one figure.

    Parameters
    ----------
    fit : FreeRockingFit
        Result of :func:`fit_free_rocking`.
    measured : array_like, optional
        Measured durations [s] in the order of ``fit.half_cycle`` (default ``fit.measured``).
    published : dict, optional
        ``{"p": ..., "e": ...}`` for a Housner prediction with published parameters (e.g.
        ``{"p": YU2019_BLOCK["p"], "e": YU2019_BLOCK["e_housner"]}``), drawn dashed.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes
        x = half-cycle index, y = duration [s]; one colour per release angle.
    """
    ax = _new_axes(ax)
    meas = fit.measured if measured is None else np.asarray(measured, dtype=float)
    if meas.shape != fit.measured.shape:
        raise ValueError(f"measured must have {fit.measured.size} entries")
    for gi, t0 in enumerate(fit.theta0):
        sel = fit.group == gi
        order = np.argsort(fit.half_cycle[sel])
        hc = fit.half_cycle[sel][order]
        lab = rf"$\theta_0$ = {np.degrees(t0):.3g}$^\circ$"
        line = ax.plot(hc, meas[sel][order], "o", ms=4, label=f"measured, {lab}")[0]
        c = line.get_color()
        ax.plot(hc, fit.predicted[sel][order], "-", color=c,
                label=f"fit ({fit.model}: p={fit.p:.3g}, e={fit.e:.3g})" if gi == 0 else None)
        if published is not None:
            pub = housner_half_cycle_durations(t0, fit.alpha, published["p"], published["e"],
                                               hc, fit.definition)
            ax.plot(hc, pub, "--", color=c,
                    label=(f"published (p={published['p']:.3g}, e={published['e']:.3g})"
                           if gi == 0 else None))
    ax.set_xlabel(f"half-cycle ({fit.definition} definition)")
    ax.set_ylabel("duration [s]")
    ax.legend(fontsize="small")
    return ax


