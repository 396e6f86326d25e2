"""Bodies: rigid blocks (physics.md section 1)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from . import _validate as V

G_STANDARD = 9.80665


def housner_restitution(alpha, mass_ratio=1.5):
    """Housner's angular-velocity ratio e = 1 - (M R^2/I0)(1 - cos 2 alpha).

    ``mass_ratio`` = 1.5 corresponds to M R^2/I0 = 3/4 (rectangle), giving
    e = 1 - 1.5 sin^2(alpha).  The energy ratio per impact is e^2.
    """
    return 1.0 - mass_ratio * math.sin(alpha) ** 2


@dataclass(frozen=True)
class RigidBlock:
    """A rigid block rocking on its bottom corners (Housner 1963).

    Parameters
    ----------
    alpha : float
        Slenderness angle [rad], 0 < alpha < pi/2 (rectangle: atan(b/h)).
    p : float
        Frequency parameter [rad/s], p^2 = M g R / I0.
    e : float, optional
        Angular-velocity restitution per impact, in [0, 1].  Default:
        Housner's value for a rectangle, 1 - 1.5 sin^2(alpha).
    g : float
        Gravity [m/s^2], default 9.80665.
    theta_over : float
        Rotation [rad] at which the block counts as overturned (default pi/2).
    b, h : float, optional
        Half-width and half-height [m], when known (rectangle).

    Examples
    --------
    >>> RigidBlock.rectangle(b=0.5, h=2.5)          # doctest: +SKIP
    """

    alpha: float
    p: float
    e: float | None = None
    g: float = G_STANDARD
    theta_over: float = math.pi / 2
    b: float | None = None
    h: float | None = None
    kind: str = field(default="rigid", init=False)

    def __post_init__(self):
        a = V.in_open("alpha", self.alpha, 0.0, math.pi / 2, hi_label="pi/2")
        V.positive("p", self.p)
        V.positive("g", self.g)
        V.in_open("theta_over", self.theta_over, a, math.pi, lo_label="alpha", hi_label="pi")
        if self.e is None:
            object.__setattr__(self, "e", housner_restitution(a))
        V.in_closed("e", self.e, 0.0, 1.0)
        for nm in ("b", "h"):
            if getattr(self, nm) is not None:
                V.positive(nm, getattr(self, nm))

    @classmethod
    def rectangle(cls, b, h, e=None, g=G_STANDARD, theta_over=math.pi / 2):
        """Rectangular block of half-width ``b`` and half-height ``h`` [m].

        R = sqrt(b^2 + h^2), alpha = atan(b/h), p = sqrt(3 g / (4 R)).
        """
        b = V.positive("b", b)
        h = V.positive("h", h)
        g = V.positive("g", g)
        R = math.hypot(b, h)
        return cls(alpha=math.atan2(b, h), p=math.sqrt(3.0 * g / (4.0 * R)), e=e,
                   g=g, theta_over=theta_over, b=b, h=h)

    @classmethod
    def from_inertia(cls, R, alpha, I0, m, e=None, g=G_STANDARD, theta_over=math.pi / 2):
        """Any body from corner-to-CM distance ``R`` [m], ``alpha`` [rad],
        inertia about the corner ``I0`` [kg m^2] and mass ``m`` [kg].

        p^2 = m g R / I0; default e = 1 - (m R^2 / I0)(1 - cos 2 alpha).
        """
        R = V.positive("R", R)
        alpha = V.in_open("alpha", alpha, 0.0, math.pi / 2, hi_label="pi/2")
        I0 = V.positive("I0", I0)
        m = V.positive("m", m)
        g = V.positive("g", g)
        if I0 < m * R * R:
            raise ValueError(f"I0 must be >= m R^2 (parallel-axis theorem), got I0={I0}, m R^2={m * R * R}")
        if e is None:
            e = 1.0 - (m * R * R / I0) * (1.0 - math.cos(2 * alpha))
        return cls(alpha=alpha, p=math.sqrt(m * g * R / I0), e=e, g=g, theta_over=theta_over,
                   b=R * math.sin(alpha), h=R * math.cos(alpha))

    @property
    def tan_alpha(self):
        return math.tan(self.alpha)

    @property
    def uplift_acceleration(self):
        """g tan(alpha) [m/s^2]: static uplift threshold."""
        return self.g * math.tan(self.alpha)

    @property
    def housner_e(self):
        return housner_restitution(self.alpha)

    @property
    def size(self):
        """R [m] if known (rectangle: from p), else None."""
        if self.b is not None and self.h is not None:
            return math.hypot(self.b, self.h)
        return None
