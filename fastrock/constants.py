"""Physical constants of the front end, defined once."""

#: Standard gravity [m/s^2] (CGPM 1901): the default g of every body, the unit "g" of
#: amplitudes and records, and the g of the published test blocks.
G_STANDARD = 9.80665
