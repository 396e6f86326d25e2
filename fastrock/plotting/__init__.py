"""Figures (matplotlib, imported lazily with the Agg backend when no display is set).

Importing this package registers :func:`plot_history` as the figure of
``SimulationResult.plot()`` (fastrock's ``__init__`` imports it), so that the running layer
never imports the plotting layer.
"""
from fastrock.plotting.figures import describe_body, describe_excitation, plot_history, plot_spectrum
from fastrock.plotting.rocking_spectrum import plot_rocking_spectrum
from fastrock.plotting.freerocking import plot_fit, plot_period_vs_angle
from fastrock.plotting.fragility import plot_fragility
from fastrock.plotting.accuracy import plot_work_precision
from fastrock.running.result import PLOTTERS

PLOTTERS["history"] = plot_history

__all__ = ["describe_body", "describe_excitation", "plot_fit", "plot_fragility", "plot_history",
           "plot_period_vs_angle", "plot_rocking_spectrum", "plot_spectrum", "plot_work_precision"]
