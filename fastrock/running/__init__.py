"""Running the kernels: solver settings, the model registry, single runs (simulate,
simulate_foundation, scenes), sweeps, outcomes and warm-up."""
