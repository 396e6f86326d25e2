"""Free rocking of a rigid block: periods, half-cycle analysis and parameter fitting.

This module is the "rocking against vibration" toolbox (Yu, Gutschmidt & MacRae):

* closed-form and quadrature periods of free rocking, of a linear oscillator and of a
  pendulum (:func:`rocking_period_linear`, :func:`rocking_period_exact`,
  :func:`vibration_period`, :func:`pendulum_period`, :func:`pendulum_period_small`);
* extraction of half-cycles (durations, peaks, peak ratios) from any rotation history
  (:func:`half_cycles`);
* the reading of a body-mounted accelerometer (:func:`accelerometer`);
* least-squares identification of the frequency parameter ``p`` and the restitution ``e``
  from measured half-cycle durations (:func:`fit_free_rocking`, :func:`fit_from_csv`), with a
  pluggable ``predictor`` so that foundation models (two-spring, switching; docs: theory/foundation) can
  be fitted with the same machinery later;
* the measured half-cycle durations of Yu et al. (:func:`load_yu2019`);
* plot helpers and the ``fastrock fit`` sub-command (:func:`add_fit_subcommand`,
  :func:`run_fit_command`).

Conventions follow the docs (theory, conventions): SI units, angles in radians unless a name ends in
``_deg``, ``theta > 0`` = tilted to the right, pivot sign ``s = +1`` right corner, ``-1`` left.
``alpha`` is the slenderness angle, ``p = sqrt(M g R / I_0)`` [rad/s] the frequency parameter
and ``e`` Housner's (angular-velocity) coefficient of restitution, ``theta'+ = e theta'-``.

Only numpy, pandas and (lazily) matplotlib are used at run time.

References
----------
Housner, G. W. (1963). The behavior of inverted pendulum structures during earthquakes.
Bull. Seismol. Soc. Am. 53(2), 403-417.

Yu, Gutschmidt & MacRae: experiments on rocking against vibration of a block on felt
(half-cycle durations reproduced in ``fastrock/data/yu2019_halfcycles.csv``).
"""
