"""Studies: record suites x bodies x scene variants x intensity levels,
run in chunks on this machine or on a Dask cluster, with incremental
dynamic analysis (IDA) and lognormal fragility curves.

A :class:`Study` describes every run in one call.  :func:`run_study` cuts it
into chunks (deterministic: the same study and ``chunk_size`` always give the
same chunks), runs each chunk with the parallel Numba sweep kernel of its
model, and writes each finished chunk as one Parquet file of a partitioned
dataset in the output folder (atomically: a temporary name, then
``os.replace``).  A ``manifest.json`` holds the study's hash and its chunk
list; a rerun into the same folder skips the chunks whose file exists, so an
interrupted study resumes where it stopped.  :func:`load_results` reads the
dataset back as one DataFrame.  The hash covers what the runs depend on
(record samples and names, bodies, variants, levels, measure, solver,
``t_after``, ``early_exit``), not the fastrock version: after an upgrade
start a new folder rather than mixing the results of two versions.

Backends
--------
``"local"`` (default) runs the chunks one after the other in this process;
each chunk is one call of the ``prange`` sweep kernel on all cores.
``"dask"`` submits one task per chunk to a ``dask.distributed`` cluster (a
``Client``, a scheduler address, or, with neither, a ``LocalCluster`` started
here).  The task function :func:`run_chunk` is top level, takes plain data
(NumPy arrays and strings), is pure and idempotent, and runs the kernel in
the worker.  The client writes each chunk's file as soon as its future
completes (``as_completed``), so a finished chunk is on disk before anything
else can go wrong, and a worker that dies loses only the chunks it was still
computing: the scheduler reruns them elsewhere (``retries`` covers exceptions
raised by a task).  Both backends run the same payloads through the same
kernels, so their tables are identical bit for bit.

Intensity measures (one row per record x body x variant x level)
----------------------------------------------------------------
The record is scaled by a factor ``scale`` so that the study's measure equals
the level:

* ``"pga"``: the level is the PGA [g];  ``scale = level g / PGA``;
* ``"pgv"``: the level is the PGV [m/s];  ``scale = level / PGV``;
* ``"pga_over_g_tan_alpha"``: the level is PGA / (g tan alpha) of the body
  (dimensionless; 1 is the static uplift threshold), so the scale differs
  from body to body;
* ``"scale"``: the level is the factor itself.

Every row carries all the measures of its scaled record: ``pga_g``, ``pgv``,
``pga_over_g_tan_alpha`` and ``omega_p_over_p`` (= (2 pi / Tm) / p, the
dimensionless frequency of the literature on pulse-like records, Dimitrakopoulos
& DeJong 2012, doi:10.1098/rspa.2012.0026, with the record's mean period Tm
(Rathje et al. 1998) as the proxy of the pulse period: the record is not
decomposed into pulses; ``omega_p_over_p`` does not depend on the scale).

Fragility
---------
:func:`fit_fragility` fits ``P(collapse | IM) = Phi(ln(IM / theta) / beta)``
by maximum likelihood over all rows (each row a Bernoulli trial: Baker 2015,
doi:10.1193/021113EQS025M), for overturning or for exceeding a threshold of
``max |theta| / alpha``, with bootstrap confidence bands that resample whole
records (the rows of one record are correlated).  NumPy only; Phi from
``math.erf``.


Modules: definition (Study), plan (rows and chunks), worker (one chunk), output (the
folder), run (run_study); the fragility fit is fastrock.analyses.fragility, its figure
fastrock.plotting.fragility.
"""
