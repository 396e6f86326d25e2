"""Compiled layer of fastrock (installed as ``fastrock.kernels``).

Kernels take flat float64/int64 arrays and scalars, return integer status
codes and never import the front end.  Importing this package compiles
nothing: every kernel is compiled (or loaded from the on-disk cache) at its
first call.
"""
