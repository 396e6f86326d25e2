"""Rocking spectrum of recorded earthquakes: beta against Tp/Tm.

For every record, every block size (half-width ``b``) and every wall
setting, the blocks of a grid of slenderness values ``b/h`` are run under
the record, and the minimum stable slenderness ``(b/h)_min`` of that size is
read off the grid (Mennitti et al. 2021, after Maiorano et al.).  It is
reported as

    beta = (b/h)_min * g / PGA          against          Tp / Tm,

where ``Tp = 2 pi / p`` is the period parameter of the block at
``(b, (b/h)_min)`` and ``Tm`` the record's mean period (Rathje et al. 1998).
``beta = 1`` is the pseudo-static rule ``b/h >= PGA/g`` (a block that
satisfies it never uplifts); ``beta < 1`` means the dynamic analysis needs a
smaller base than that rule.

Definitions (the same in the table, the plot and the docs)
----------------------------------------------------------
* **Stable**: the run's outcome is in ``stable_outcomes`` (default only
  ``"safe"``: never uplifted, came back to rest, or proven unable to
  overturn).  "leaning" (resting against a wall) is *not* stable by default
  and is counted apart in ``n_leaning``; "failed" runs are not stable and are
  counted in ``n_failed``.
* **(b/h)_min on a grid** ``s_1 < ... < s_n``: the smallest grid value
  ``s_k`` such that every block with ``s_j >= s_k`` is stable ("stable from
  there up").  This is the threshold a designer can use; it is
  conservative when stability is not monotone.
* ``beta_bound``:

  - ``"exact"``: ``s_{k-1}`` is unstable and ``s_k..s_n`` are stable, so the
    true threshold lies in ``(s_{k-1}, s_k]``; ``beta`` is exact to the grid
    resolution.
  - ``"upper"``: every block of the grid is stable, so the true
    ``(b/h)_min <= s_1``; ``slenderness_min = s_1`` and ``beta`` are upper
    bounds.
  - ``"lower"``: the stoutest block ``s_n`` is not stable, so
    ``(b/h)_min > s_n``; ``slenderness_min = s_n`` and ``beta`` are (strict)
    lower bounds.
  - ``"incomplete"``: some runs of the cell did not finish (Ctrl-C);
    ``beta`` is NaN.

  ``beta = slenderness_min * g / PGA`` holds in every row (except
  "incomplete"), and ``Tp`` is always that of the block at
  ``slenderness_min``.
* ``non_monotone``: some grid slenderness above the first stable one is not
  stable (a block survives at one b/h and falls at a larger one).  Then
  ``slenderness_first_stable < slenderness_min``.

References
----------
Mennitti, Maiorano, Aversa (2021), rocking of rigid blocks with a rear wall.
Rathje, Abrahamson, Bray (1998), J. Geotech. Geoenviron. Eng. 124(2):150-159,
doi:10.1061/(ASCE)1090-0241(1998)124:2(150).
"""
