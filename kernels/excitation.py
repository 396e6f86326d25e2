"""Ground-motion evaluation for kernels.

The excitation of one run is a header ``hdr`` (layout.N_EXC floats: one
block for the horizontal and one for the vertical channel) plus a shared
sample array ``smp`` holding every sampled record of a sweep.  Pulses are
closed-form; sampled motions are linearly interpolated and zero outside
their span.  Units: s, m/s^2.  At a breakpoint the value is the left limit
(intervals are closed), so the driver evaluates the rhs just after a
breakpoint when it restarts.
"""
import math

import numpy as np

from .config import jit
from .layout import (EXC_HALF_SINE, EXC_NONE, EXC_ONE_COSINE, EXC_ONE_SINE,
                     EXC_RECTANGULAR, EXC_SAMPLED, N_HDR, S_CM, S_G_N, S_G_T,
                     S_ON, S_SM, X_AMP, X_DT, X_DUR, X_KIND, X_N, X_OFFSET,
                     X_OMEGA, X_SIGN, X_T0)


@jit
def channel_value(t, hdr, c, smp):
    """Acceleration and its time derivative of channel block ``c`` at t."""
    kind = int(hdr[c + X_KIND])
    if kind == EXC_NONE:
        return 0.0, 0.0
    tau = t - hdr[c + X_T0]
    if tau < 0.0 or tau > hdr[c + X_DUR]:
        return 0.0, 0.0
    amp = hdr[c + X_SIGN] * hdr[c + X_AMP]
    w = hdr[c + X_OMEGA]
    if kind == EXC_ONE_SINE or kind == EXC_HALF_SINE:
        return amp * math.sin(w * tau), amp * w * math.cos(w * tau)
    if kind == EXC_ONE_COSINE:
        return amp * math.cos(w * tau), -amp * w * math.sin(w * tau)
    if kind == EXC_RECTANGULAR:
        return amp, 0.0
    # sampled, piecewise linear
    dt = hdr[c + X_DT]
    n = int(hdr[c + X_N])
    off = int(hdr[c + X_OFFSET])
    x = tau / dt
    i = int(math.floor(x))
    if i >= n - 1:
        i = n - 2
    if i < 0:
        i = 0
    fr = x - i
    a0 = smp[off + i]
    a1 = smp[off + i + 1]
    return amp * (a0 + fr * (a1 - a0)), amp * (a1 - a0) / dt


@jit
def ground(t, hdr, smp):
    """(a_g, a_v): the ground's acceleration along and normal to the ground
    surface at t, gravity's component along a slope included (layout.S_ON):
    on level ground the horizontal and vertical channels."""
    ah, _ = channel_value(t, hdr, 0, smp)
    av, _ = channel_value(t, hdr, N_HDR, smp)
    if hdr[S_ON] != 0.0:
        cm = hdr[S_CM]
        sm = hdr[S_SM]
        return (ah * cm - av * sm - hdr[S_G_T],
                av * cm + ah * sm + hdr[S_G_N])
    return ah, av


@jit
def ground_rates(t, hdr, smp):
    """(a_g, da_g/dt, a_v, da_v/dt) at t, in the frame of ``ground``."""
    ah, dah = channel_value(t, hdr, 0, smp)
    av, dav = channel_value(t, hdr, N_HDR, smp)
    if hdr[S_ON] != 0.0:
        cm = hdr[S_CM]
        sm = hdr[S_SM]
        return (ah * cm - av * sm - hdr[S_G_T], dah * cm - dav * sm,
                av * cm + ah * sm + hdr[S_G_N], dav * cm + dah * sm)
    return ah, dah, av, dav


@jit
def on_slope(hdr):
    """True on sloping ground: a_v' is then not zero even without a
    vertical channel."""
    return hdr[S_ON] != 0.0


@jit
def channel_end(hdr, c):
    if int(hdr[c + X_KIND]) == EXC_NONE:
        return -np.inf
    return hdr[c + X_T0] + hdr[c + X_DUR]


@jit
def excitation_start(hdr):
    """Time before which both channels are identically zero."""
    t = np.inf
    for c in (0, N_HDR):
        if int(hdr[c + X_KIND]) != EXC_NONE:
            t = min(t, hdr[c + X_T0])
    return t


@jit
def excitation_end(hdr):
    """Time after which both channels are identically zero."""
    return max(channel_end(hdr, 0), channel_end(hdr, N_HDR), 0.0)


@jit
def channel_next_break(t, hdr, c, sample_breaks):
    kind = int(hdr[c + X_KIND])
    if kind == EXC_NONE:
        return np.inf
    t0 = hdr[c + X_T0]
    t1 = t0 + hdr[c + X_DUR]
    if t < t0:
        return t0
    if t >= t1:
        return np.inf
    if kind == EXC_SAMPLED and sample_breaks:
        dt = hdr[c + X_DT]
        k = math.floor((t - t0) / dt) + 1.0
        tb = t0 + k * dt
        # guard against t sitting on a sample time up to round-off
        if tb <= t * (1.0 + 1e-15) + 1e-15:
            tb = t0 + (k + 1.0) * dt
        return min(tb, t1)
    return t1


@jit
def next_breakpoint(t, hdr, sample_breaks):
    """Earliest excitation breakpoint strictly after t (inf if none)."""
    return min(channel_next_break(t, hdr, 0, sample_breaks),
               channel_next_break(t, hdr, N_HDR, sample_breaks))


@jit
def scan_step(hdr):
    """Grid spacing for scanning a static phase: pulse extrema and record
    samples fall on grid points, so a threshold is never stepped over."""
    h = np.inf
    for c in (0, N_HDR):
        kind = int(hdr[c + X_KIND])
        if kind == EXC_NONE:
            continue
        if kind == EXC_SAMPLED:
            h = min(h, hdr[c + X_DT])
        elif kind == EXC_RECTANGULAR:
            h = min(h, hdr[c + X_DUR])
        else:
            h = min(h, hdr[c + X_DUR] / 64.0)
    return h


@jit
def scan_origin(hdr):
    if int(hdr[X_KIND]) != EXC_NONE:
        return hdr[X_T0]
    return hdr[N_HDR + X_T0]
