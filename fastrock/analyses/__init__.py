"""Analyses built on runs: overturning and rocking spectra, free rocking, fitting,
fragility and work-precision."""
