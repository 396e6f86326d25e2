"""Ground excitations: closed-form pulses and sampled accelerograms.

Amplitudes may be given in ``"g"``, ``"m/s2"`` or as ``"g_tan_alpha"`` (the
ratio a_p/(g tan alpha) of the body); frequencies in ``"Hz"``, ``"rad/s"``
or ``"omega_p/p"``.  ``to_header`` converts to the kernels' SI header.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastrock import _validate as V
from fastrock.constants import G_STANDARD
from fastrock.kernels import layout as L

PULSE_KINDS = {
    "one-sine": L.EXC_ONE_SINE,
    "half-sine": L.EXC_HALF_SINE,
    "one-cosine": L.EXC_ONE_COSINE,
    "rectangular": L.EXC_RECTANGULAR,
}
AMPLITUDE_UNITS = ("g", "m/s2", "g_tan_alpha")
FREQUENCY_UNITS = ("Hz", "rad/s", "omega_p/p")
ACCELERATION_UNITS = {"g": None, "m/s2": 1.0, "cm/s2": 0.01, "gal": 0.01, "mm/s2": 0.001}


@dataclass(frozen=True)
class Pulse:
    """A one-sine (default), half-sine, one-cosine or rectangular pulse.

    One-sine: a_g(t) = sign * a_p * sin(omega_p (t - t_start)) for
    0 <= t - t_start <= 2 pi / omega_p, zero otherwise.  Half-sine lasts
    pi/omega_p, one-cosine 2 pi/omega_p, rectangular ``duration`` seconds.

    A positive sign accelerates the ground toward +x, which tips the block
    toward negative theta (docs: theory, conventions).
    """

    amplitude: float
    frequency: float = 1.0
    sign: int = 1
    kind: str = "one-sine"
    amplitude_unit: str = "g"
    frequency_unit: str = "Hz"
    t_start: float = 0.0
    duration: float | None = None

    def __post_init__(self):
        V.choice("kind", self.kind, PULSE_KINDS)
        V.choice("amplitude_unit", self.amplitude_unit, AMPLITUDE_UNITS)
        V.choice("frequency_unit", self.frequency_unit, FREQUENCY_UNITS)
        amp = V.non_negative("amplitude", self.amplitude)
        if self.amplitude_unit != "g_tan_alpha":     # that one is checked with the body (check)
            V.acceleration("amplitude", amp * (G_STANDARD if self.amplitude_unit == "g" else 1.0),
                           G_STANDARD, "the pulse amplitude")
        V.sign("sign", self.sign)
        V.non_negative("t_start", self.t_start)
        if self.kind == "rectangular":
            if self.duration is None:
                raise ValueError("duration [s] is required for a rectangular pulse")
            V.run_time("duration", V.positive("duration", self.duration), "the pulse")
        else:
            f = V.positive("frequency", self.frequency)
            if self.frequency_unit != "omega_p/p":
                w = 2 * math.pi * f if self.frequency_unit == "Hz" else f
                V.run_time("frequency", (math.pi if self.kind == "half-sine" else 2 * math.pi) / w, "the pulse")

    def check(self, body):
        """Bounds that need the body: the amplitude in m/s^2 and the pulse length."""
        V.acceleration("amplitude", self.amplitude_si(body), body.g, "the pulse amplitude")
        V.run_time("duration" if self.kind == "rectangular" else "frequency", self.pulse_duration(body),
                   "the pulse")

    def amplitude_si(self, body):
        if self.amplitude_unit == "g":
            return self.amplitude * body.g
        if self.amplitude_unit == "m/s2":
            return float(self.amplitude)
        return self.amplitude * body.g * math.tan(body.alpha)

    def omega_si(self, body):
        if self.frequency_unit == "Hz":
            return 2 * math.pi * self.frequency
        if self.frequency_unit == "rad/s":
            return float(self.frequency)
        return self.frequency * body.p

    def pulse_duration(self, body):
        if self.kind == "rectangular":
            return float(self.duration)
        w = self.omega_si(body)
        return (math.pi if self.kind == "half-sine" else 2 * math.pi) / w

    def fill_header(self, hdr, c, body):
        hdr[c + L.X_KIND] = PULSE_KINDS[self.kind]
        hdr[c + L.X_AMP] = self.amplitude_si(body)
        hdr[c + L.X_OMEGA] = 0.0 if self.kind == "rectangular" else self.omega_si(body)
        hdr[c + L.X_SIGN] = self.sign
        hdr[c + L.X_T0] = self.t_start
        hdr[c + L.X_DUR] = self.pulse_duration(body)

    def end_time(self, body):
        return self.t_start + self.pulse_duration(body)


@dataclass(frozen=True, eq=False)
class SampledMotion:
    """A sampled acceleration history, linearly interpolated between samples.

    Parameters
    ----------
    acc : array
        Samples, the first at ``t_start``.
    dt : float
        Sample spacing [s].
    unit : str
        "m/s2" (default), "g", "cm/s2" / "gal" or "mm/s2".
    scale : float
        Factor applied to the samples (e.g. for incremental dynamic analysis).
    """

    acc: np.ndarray
    dt: float
    unit: str = "m/s2"
    scale: float = 1.0
    t_start: float = 0.0
    name: str = ""

    def __post_init__(self):
        a = V.finite_array("acc", self.acc)
        if a.size < 2:
            raise ValueError("acc must have at least 2 samples")
        V.positive("dt", self.dt)
        V.choice("unit", self.unit, ACCELERATION_UNITS)
        V.finite("scale", self.scale)
        V.non_negative("t_start", self.t_start)
        object.__setattr__(self, "acc", a)

    @classmethod
    def from_record(cls, record, scale=1.0, t_start=0.0):
        """From a :class:`fastrock.GroundMotion` (acc in m/s^2)."""
        return cls(np.asarray(record.acc, float), record.dt, "m/s2", scale, t_start,
                   getattr(record, "name", ""))

    def check(self, body):
        """Bounds that need the body (its g): the peak acceleration and the record length."""
        peak = float(np.max(np.abs(self.samples_si(body)))) * abs(float(self.scale))
        V.acceleration("acc * scale", peak, body.g, "the peak ground acceleration")
        V.run_time("dt", (self.acc.size - 1) * self.dt, "the record")

    def samples_si(self, body):
        f = ACCELERATION_UNITS[self.unit]
        return self.acc * (body.g if f is None else f)

    def fill_header(self, hdr, c, body, offset):
        hdr[c + L.X_KIND] = L.EXC_SAMPLED
        hdr[c + L.X_AMP] = self.scale
        hdr[c + L.X_SIGN] = 1.0
        hdr[c + L.X_T0] = self.t_start
        hdr[c + L.X_DUR] = (self.acc.size - 1) * self.dt
        hdr[c + L.X_DT] = self.dt
        hdr[c + L.X_OFFSET] = offset
        hdr[c + L.X_N] = self.acc.size

    def end_time(self, body):
        return self.t_start + (self.acc.size - 1) * self.dt


def as_excitation(obj, name="excitation"):
    """Accept a Pulse, SampledMotion, GroundMotion or None."""
    if obj is None or isinstance(obj, (Pulse, SampledMotion)):
        return obj
    if hasattr(obj, "acc") and hasattr(obj, "dt"):
        return SampledMotion.from_record(obj)
    raise ValueError(f"{name} must be a Pulse, SampledMotion or GroundMotion, got {type(obj).__name__}")


#: float64 must resolve time at the end of an excitation to this fraction of
#: its time scale (a record's dt, 1/64 of a pulse)
TIME_RESOLUTION = 1e-9


def _check_time_resolution(exc, body):
    """Refuse a t_start so late that float64 time cannot resolve the motion."""
    scale = exc.dt if isinstance(exc, SampledMotion) else exc.pulse_duration(body) / 64.0
    t_end = exc.end_time(body)
    if np.spacing(t_end) > TIME_RESOLUTION * scale:
        limit = TIME_RESOLUTION * scale / np.finfo(float).eps
        raise ValueError(f"t_start = {exc.t_start:g} s is too late: at t = {t_end:.4g} s float64 resolves time "
                         f"only to {np.spacing(t_end):.2g} s, too coarse for an excitation whose time scale is "
                         f"{scale:.3g} s; start it before about {limit:.3g} s (the physics does not depend on "
                         f"the time origin)")


def to_header(body, horizontal, vertical=None, ground=None):
    """Kernel header (float64[N_EXC]) and sample array for one run;
    ``ground`` (a sloping :class:`fastrock.Ground`) fills the slope block."""
    hdr = np.zeros(L.N_EXC)
    if ground is not None:
        ground.fill_header(hdr, body.g)
    chunks = []
    offset = 0
    for c, exc in ((L.H_CHANNEL, as_excitation(horizontal)),
                   (L.V_CHANNEL, as_excitation(vertical, "vertical"))):
        if exc is None:
            continue
        _check_time_resolution(exc, body)
        exc.check(body)
        if isinstance(exc, SampledMotion):
            s = exc.samples_si(body)
            exc.fill_header(hdr, c, body, offset)
            chunks.append(s)
            offset += s.size
        else:
            exc.fill_header(hdr, c, body)
    smp = np.concatenate(chunks) if chunks else np.zeros(1)
    return hdr, smp


def match_components(horizontal, vertical, resample=False):
    """The vertical excitation, checked against the horizontal one.

    Two records (SampledMotion or GroundMotion) must share dt, length and
    start: one recorded with another instrument or filtered differently is
    refused rather than silently paired.  With ``resample=True`` the
    vertical record is interpolated linearly onto the horizontal record's
    samples (zero outside its own span, so vertical motion after the
    horizontal record ends is dropped).
    """
    h, v = as_excitation(horizontal), as_excitation(vertical, "vertical")
    if not (isinstance(h, SampledMotion) and isinstance(v, SampledMotion)):
        return v
    if math.isclose(h.dt, v.dt, rel_tol=1e-12) and h.acc.size == v.acc.size and h.t_start == v.t_start:
        return v
    if not resample:
        raise ValueError(
            f"vertical: its record (dt = {v.dt:g} s, {v.acc.size} samples, t_start = {v.t_start:g} s) "
            f"does not match the horizontal one (dt = {h.dt:g} s, {h.acc.size} samples, t_start = "
            f"{h.t_start:g} s); pass resample_vertical=True to interpolate it onto the horizontal samples")
    t_h = h.t_start + h.dt * np.arange(h.acc.size)
    t_v = v.t_start + v.dt * np.arange(v.acc.size)
    acc = np.interp(t_h, t_v, v.acc, left=0.0, right=0.0)
    return SampledMotion(acc, h.dt, unit=v.unit, scale=v.scale, t_start=h.t_start, name=v.name)


def end_time(body, horizontal, vertical=None):
    t = 0.0
    for exc in (as_excitation(horizontal), as_excitation(vertical, "vertical")):
        if exc is not None:
            t = max(t, exc.end_time(body))
    return t


def channel_peak(hdr, smp, c=L.H_CHANNEL):
    """Peak |acceleration| [m/s^2] of header channel ``c`` (0 if empty)."""
    kind = int(hdr[c + L.X_KIND])
    if kind == L.EXC_NONE:
        return 0.0
    amp = abs(float(hdr[c + L.X_AMP]))
    if kind == L.EXC_SAMPLED:
        off, n = int(hdr[c + L.X_OFFSET]), int(hdr[c + L.X_N])
        return amp * float(np.max(np.abs(smp[off:off + n])))
    return amp
