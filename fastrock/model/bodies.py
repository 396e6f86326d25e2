"""Bodies: rigid blocks (docs: theory/rigid)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from fastrock import _validate as V
from fastrock.constants import G_STANDARD
from fastrock.kernels import layout as _L


def housner_restitution(alpha, mass_ratio=1.5):
    """Housner's angular-velocity ratio e = 1 - (M R^2/I0)(1 - cos 2 alpha).

    ``mass_ratio`` = 1.5 corresponds to M R^2/I0 = 3/4 (rectangle), giving
    e = 1 - 1.5 sin^2(alpha).  The energy ratio per impact is e^2.

    Examples
    --------
    >>> from fastrock import housner_restitution
    >>> round(housner_restitution(0.3), 4)     # 1 - 1.5 sin^2(0.3)
    0.869
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
        Gravity [m/s^2], default standard gravity (``fastrock.G_STANDARD``).
    theta_over : float
        Rotation [rad] at which the block counts as overturned (default pi/2).
    b, h : float, optional
        Half-width and half-height [m], when known (rectangle).
    top_radius : float, optional
        Radius rho [m] of rounded top corners, 0 < rho <= min(2b, 2h) (a
        tombstone, a weathered rock).  It changes the wall contact only:
        the rounded corner touches a wall later than the square one
        (:meth:`Wall.limit_angle`).  alpha, p and e stay as given (a
        rectangle's from :meth:`rectangle`); for the exact inertia of the
        rounded outline use ``RigidBody.from_polygon``.

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
    # a field added after studies were hashed: left out of a study's hash at its default
    top_radius: float | None = field(default=None, metadata={"hash_default": True})
    kind: str = field(default="rigid", init=False)

    def __post_init__(self):
        a = V.in_open("alpha", self.alpha, 0.0, math.pi / 2, hi_label="pi/2")
        V.positive("p", self.p)
        V.positive("g", self.g)
        V.in_open("theta_over", self.theta_over, a, math.pi, lo_label="alpha", hi_label="pi")
        if self.e is None:
            e = housner_restitution(a)
            if e < 0.0:
                raise ValueError(f"Housner's default restitution e = 1 - 1.5 sin^2(alpha) = {e:.3f} is negative "
                                 f"for alpha = {a} > 0.955 rad (a squat block); give e explicitly")
            object.__setattr__(self, "e", e)
        V.in_closed("e", self.e, 0.0, 1.0)
        for nm in ("b", "h"):
            if getattr(self, nm) is not None:
                V.positive(nm, getattr(self, nm))
        if self.top_radius is not None:
            rho = V.positive("top_radius", self.top_radius)
            if self.b is None or self.h is None:
                raise ValueError("top_radius needs the block's b and h (RigidBlock.rectangle or from_inertia)")
            if rho > 2.0 * min(self.b, self.h):
                raise ValueError(f"top_radius = {rho:.6g} m must be at most min(2b, 2h) = "
                                 f"{2.0 * min(self.b, self.h):.6g} m (the rounded corners fit on the block)")

    @classmethod
    def rectangle(cls, b=None, h=None, e=None, g=G_STANDARD, theta_over=math.pi / 2, *, width=None,
                  height=None, top_radius=None):
        """Rectangular block of half-width ``b`` and half-height ``h`` [m], or of full
        dimensions ``width`` = 2b and ``height`` = 2h [m] by keyword; ``top_radius``: rounded
        top corners for wall contact (see the class).

        R = sqrt(b^2 + h^2), alpha = atan(b/h), p = sqrt(3 g / (4 R)).

        >>> RigidBlock.rectangle(width=0.5, height=2.0) == RigidBlock.rectangle(0.25, 1.0)
        True
        """
        b = cls._half_size("b", b, "width", width)
        h = cls._half_size("h", h, "height", height)
        g = V.positive("g", g)
        R = math.hypot(b, h)
        return cls(alpha=math.atan2(b, h), p=math.sqrt(3.0 * g / (4.0 * R)), e=e,
                   g=g, theta_over=theta_over, b=b, h=h, top_radius=top_radius)

    @staticmethod
    def _half_size(half_name, half, full_name, full):
        if (half is None) == (full is None):
            raise ValueError(f"give either {half_name} (half size) or {full_name} (full size) [m], "
                             f"not {'both' if half is not None else 'neither'}")
        if half is not None:
            return V.positive(half_name, half)
        return V.positive(full_name, full) / 2.0

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


IMPACT_MAPS = {"full-contact": _L.IMPACT_FULL_CONTACT, "pivot-switch": _L.IMPACT_PIVOT_SWITCH}


DEFAULT_BASE_MASS_RATIO = 0.1


@dataclass(frozen=True)
class FlexibleBody:
    """Lumped mass on an elastic column on a rigid rocking base (docs: theory/flexible).

    The parameters are the literature's dimensionless groups.

    Parameters
    ----------
    alpha : float
        Slenderness atan(B/H) [rad], 0 < alpha < pi/2.
    p : float
        Frequency parameter [rad/s], p^2 = m g R0 / (m R0^2 + I_m).
    omega_n_over_p : float
        omega_n/p, omega_n = sqrt(K/m) the fixed-base column frequency (finite:
        use RigidBlock for a rigid body).
    zeta : float
        Column damping ratio c / (2 m omega_n), >= 0.
    e : float, optional
        Restitution factor applied to theta'+ by the pivot-switch (I1) map
        (default 1: the bare I1 map).  Not used by the full-contact map.
    impact : str
        "full-contact" (I3, default: theta'+ = 0, u'+ = u'- + H theta'-, then
        the uplift test at once) or "pivot-switch" (I1, u' continuous, angular
        momentum about the new corner conserved; where that would create
        energy the impact takes the full-contact map instead, counted in the
        ``energy_gains`` metric).
    rotary_inertia_ratio : float
        I_m / (m R0^2) (default 0: point mass).
    mass : float
        m [kg], only scales forces in the time history (default 1).
    base_mass_ratio : float, optional
        m_b / m, a rigid base block under the column (docs: theory/flexible_friction),
        with inertia I_b = m_b B^2 / 3 about its own centre of mass.  Default
        (None): 0 (the classic massless base) without sliding, and
        ``DEFAULT_BASE_MASS_RATIO`` = 0.1 with friction, where a base mass is
        needed: with m_b = 0 the sliding problem is a differential-algebraic
        system (ill-posed without column damping).  Pass the same value
        explicitly to compare sliding and non-sliding runs of one body.
    base_cm_height : float
        h_b [m], height of the base's centre of mass (default 0).
    """

    alpha: float
    p: float
    omega_n_over_p: float
    zeta: float = 0.0
    e: float | None = None
    impact: str = "full-contact"
    g: float = G_STANDARD
    theta_over: float = math.pi / 2
    rotary_inertia_ratio: float = 0.0
    mass: float = 1.0
    base_mass_ratio: float | None = None
    base_cm_height: float = 0.0
    kind: str = field(default="flexible", init=False)

    def __post_init__(self):
        a = V.in_open("alpha", self.alpha, 0.0, math.pi / 2, hi_label="pi/2")
        V.positive("p", self.p)
        w = self.omega_n_over_p
        if V._is_number(w) and not isinstance(w, bool) and math.isinf(float(w)):
            raise ValueError("omega_n_over_p must be finite; use fastrock.RigidBlock for a rigid body")
        V.positive("omega_n_over_p", w)
        V.non_negative("zeta", self.zeta)
        V.choice("impact", self.impact, IMPACT_MAPS)
        V.positive("g", self.g)
        V.non_negative("rotary_inertia_ratio", self.rotary_inertia_ratio)
        V.positive("mass", self.mass)
        V.in_open("theta_over", self.theta_over, a, math.pi, lo_label="alpha", hi_label="pi")
        if self.e is None:
            object.__setattr__(self, "e", 1.0)
        V.in_closed("e", self.e, 0.0, 1.0)
        if self.base_mass_ratio is not None:
            V.non_negative("base_mass_ratio", self.base_mass_ratio)
        V.non_negative("base_cm_height", self.base_cm_height)
        if self.impact == "pivot-switch" and (self.base_mass_ratio or self.base_cm_height):
            raise ValueError("impact='pivot-switch' is available for a massless base only "
                             "(base_mass_ratio=0, base_cm_height=0)")

    @classmethod
    def from_dimensions(cls, m, K, c, B, H, I_m=0.0, impact="full-contact", e=None, g=G_STANDARD,
                        theta_over=math.pi / 2, m_b=None, h_b=0.0):
        """From mass m [kg], column stiffness K [N/m] and dashpot c [N s/m],
        base half-width B [m], mass height H [m], rotary inertia I_m [kg m^2],
        base mass m_b [kg] and its CM height h_b [m]."""
        m = V.positive("m", m)
        K = V.positive("K", K)
        c = V.non_negative("c", c)
        B = V.positive("B", B)
        H = V.positive("H", H)
        I_m = V.non_negative("I_m", I_m)
        V.positive("g", g)
        R0 = math.hypot(B, H)
        p = math.sqrt(m * g * R0 / (m * R0 * R0 + I_m))
        wn = math.sqrt(K / m)
        return cls(alpha=math.atan2(B, H), p=p, omega_n_over_p=wn / p, zeta=c / (2 * m * wn), e=e,
                   impact=impact, g=g, theta_over=theta_over, rotary_inertia_ratio=I_m / (m * R0 * R0),
                   mass=m, base_mass_ratio=None if m_b is None else V.non_negative("m_b", m_b) / m,
                   base_cm_height=h_b)

    @property
    def R0(self):
        return self.g / (self.p ** 2 * (1.0 + self.rotary_inertia_ratio))

    @property
    def B(self):
        return self.R0 * math.sin(self.alpha)

    @property
    def H(self):
        return self.R0 * math.cos(self.alpha)

    @property
    def omega_n(self):
        return self.omega_n_over_p * self.p

    def base_mass(self, sliding=False):
        """m_b / m in effect: ``base_mass_ratio``, or its default (0 without
        sliding, DEFAULT_BASE_MASS_RATIO with it)."""
        if self.base_mass_ratio is not None:
            return self.base_mass_ratio
        return DEFAULT_BASE_MASS_RATIO if sliding else 0.0

    @property
    def uplift_deformation(self):
        """Static deflection at uplift u_y [m] of the massless-base column:
        H K u = m g (B - u)."""
        wn = self.omega_n
        return self.g * self.B / (wn * wn * self.H + self.g)

    @property
    def tan_alpha(self):
        return math.tan(self.alpha)

    def rigid_equivalent(self):
        """The rigid block of the same alpha and p, with the restitution the
        impact map tends to as omega_n/p -> infinity: cos^2(alpha) for the
        full-contact map, cos(2 alpha) (times e) for the pivot switch (point
        mass; docs: theory/flexible, impact maps).  Its outline is the body's, b = B and h = H
        (where a wall touches it)."""
        if self.impact == "full-contact":
            e = math.cos(self.alpha) ** 2
        else:
            k = self.rotary_inertia_ratio
            e = self.e * (math.cos(2 * self.alpha) + k) / (1.0 + k)
        return RigidBlock(alpha=self.alpha, p=self.p, e=e, g=self.g, theta_over=self.theta_over,
                          b=self.B, h=self.H)
