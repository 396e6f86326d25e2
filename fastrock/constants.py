"""Constants of the front end, defined once."""

#: Standard gravity [m/s^2] (CGPM 1901): the default g of every body, the unit "g" of
#: amplitudes and records, and the g of the published test blocks.
G_STANDARD = 9.80665

#: fastrock's version (pyproject.toml's); here rather than in __init__ so that modules that
#: report it (studies, the CLI) do not import the package root.
VERSION = "0.1.0"
