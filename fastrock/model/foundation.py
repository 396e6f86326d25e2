"""Rocking against vibration: a rigid block on a flexible foundation (docs: theory/foundation).

Three foundation models, each a scene effect passed to :func:`simulate_foundation`:

* :class:`TwoSpringFoundation` ``(k_v, c_v)`` -- tensionless vertical spring-dashpots at the two
  bottom corners (docs: theory/foundation, the reference model). Lift-off and re-contact happen
  smoothly (soft contact, no impact map); dissipation comes from ``c_v`` only.
* :class:`SwitchingFoundation` ``(k_t, c_t, e_f)`` -- the switching SDOF model used by Yu,
  Gutschmidt & MacRae (docs: theory/foundation, with the P-Delta term kept): linear rotational spring
  while in contact, Housner rocking once ``|k_t theta + c_t theta'| >= M G b``, back to contact
  at ``|theta| <= theta_y = M g b / k_t``, optional restitution ``e_f`` at re-contact.
* :class:`LinearVibration` ``(k_t, c_t)`` -- a linear SDOF ``I_C theta'' + c_t theta' + k_t theta
  = -M h a_g`` that never lifts off (reference).

A rigid-ground scene is :func:`fastrock.simulate` and never imports this module's kernels.

The body is a :class:`fastrock.RigidBlock` with known half-width ``b`` and centre-of-mass
height ``h`` (:meth:`RigidBlock.rectangle` or :meth:`RigidBlock.from_inertia`) plus its mass
``M`` [kg] (default 1 kg; absolute stiffnesses scale with it). The inertia follows from the
block's ``p``: ``I_0 = M g R / p^2`` about a corner, ``I_G = I_0 - M R^2``,
``I_C = I_G + M h^2`` about the base centre.

An asymmetric :class:`fastrock.RigidBody` (b1 != b2, level base h1 = h2 = h) stands on the
two-spring foundation only: its corners at ``x = -b1`` and ``x = b2`` from the base point below
its centre of mass, which the model holds horizontally (the base centre of a symmetric block).
A :class:`fastrock.RigidBody` (symmetric or not) carries its own ``mass`` and ``inertia`` onto
the foundation (a ``mass`` argument that differs is refused: the stiffnesses are absolute). At rest it tilts toward its nearer corner (the corners share
the weight unequally); ``b`` below is then the mean half-width ``(b1 + b2)/2``.

Small-amplitude vibration in full contact (both models, P-Delta kept):
``I_C theta'' + c_t theta' + (k_t - M g h) theta = 0`` with ``k_t = 2 k_v b^2``,
``c_t = 2 c_v b^2`` for the two-spring foundation, so ``omega^2 = (k_t - M g h)/I_C`` and
``zeta = c_t / (2 I_C omega)``; the vibration period is ``T_L = 2 pi/omega`` (undamped).
:meth:`TwoSpringFoundation.from_vibration` and friends build a foundation from ``omega``
and ``zeta``.

The predictors of :mod:`fastrock.analyses.foundation_predictors` let
:func:`fastrock.fit_free_rocking` fit these models to measured half-cycle durations; the runs
are :func:`fastrock.simulate_foundation` (:mod:`fastrock.running.foundation`).

"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastrock import _validate as V
from fastrock.model.bodies import DEFAULT_BASE_MASS_RATIO, FlexibleBody, RigidBlock
from fastrock.model.rigid_body import RigidBody, level_base_height
# the kernels' parameter layout (kernels/layout.py imports no kernel)
from fastrock.kernels.layout import (N_PAR_FOUNDATION as N_PAR, P_ALPHA_LEFT, P_B, P_B_SKEW, P_CT,
                                     P_CV, P_EF, P_H, P_I_0, P_I_C, P_I_G, P_KT, P_KV, P_MASS,
                                     P_THETA_Y, N_PAR_FOUNDATION_FLEXIBLE, PF_H, PF_HB, PF_IB, PF_IM,
                                     PF_M, PF_MB, PF_WN, PF_ZETA)

# discrete-state slots of the two-spring model (kept here as plain ints, checked against the
# kernel in the tests)
D_RIGHT = 6
D_LEFT = 7


# ------------------------------------------------------------------------------ body
@dataclass(frozen=True)
class BlockInertia:
    """Mass properties of a block: ``M`` [kg], ``b``, ``h``, ``R`` [m], inertias [kg m^2].

    An asymmetric body: ``b`` = (b1 + b2)/2, ``skew`` = (b2 - b1)/2 (its corners at
    ``-b + skew`` and ``b + skew`` from the point below the centre of mass), ``R`` and ``I_0``
    about its right corner."""

    M: float
    b: float
    h: float
    R: float
    I_0: float
    I_G: float
    I_C: float
    g: float
    skew: float = 0.0

    @property
    def b1(self):
        """Left half-width [m] (``b`` for a symmetric block)."""
        return self.b - self.skew

    @property
    def b2(self):
        """Right half-width [m]."""
        return self.b + self.skew


def carried_mass(body, mass=None):
    """The mass [kg] a foundation carries: a :class:`RigidBody`'s own ``mass``, a
    :class:`FlexibleBody`'s column mass ``mass`` (its base adds ``base_mass_ratio`` of it,
    :func:`flexible_inertia`), and for a :class:`RigidBlock` (which has no mass) ``mass``,
    default 1 kg.

    Raises
    ------
    ValueError
        Naming ``mass`` if it is not > 0, or if it is given for a RigidBody and differs from
        the body's own mass (the foundation's stiffnesses are absolute: a second mass would
        silently change the response).
    """
    if isinstance(body, (RigidBody, FlexibleBody)):
        own = float(body.mass)
        name = type(body).__name__
        if mass is not None and not math.isclose(V.positive("mass", mass), own, rel_tol=1e-12):
            raise ValueError(f"mass = {mass!r} kg differs from the {name}'s own mass {own!r} kg: "
                             f"a {name} carries its own mass onto a foundation (leave mass unset)")
        return own
    return 1.0 if mass is None else V.positive("mass", mass)


def block_inertia(body, mass=None):
    """Mass properties of ``body`` with mass ``mass`` [kg] (:func:`carried_mass`).

    ``I_0 = M g R / p^2`` (from the block's ``p``), ``I_G = I_0 - M R^2``, ``I_C = I_G + M h^2``.

    A symmetric :class:`RigidBody` is its :class:`RigidBlock`; an asymmetric one (level base)
    has ``I_G = M inertia / mass``, ``I_C = I_G + M h^2`` and ``skew`` = (b2 - b1)/2.

    Raises
    ------
    ValueError
        If the body is not a :class:`RigidBlock` with known ``b`` and ``h`` or a
        :class:`RigidBody` with a level base, or its ``p`` implies ``I_0 < M R^2``.
    """
    mass = carried_mass(body, mass)
    if isinstance(body, FlexibleBody):
        return flexible_inertia(body, mass)
    if isinstance(body, RigidBody):
        if body.is_symmetric:
            body = body.to_block()
        else:
            return _body_inertia(body, mass)
    if not isinstance(body, RigidBlock):
        raise ValueError(f"body must be a fastrock.RigidBlock or RigidBody, got {type(body).__name__}")
    if body.b is None or body.h is None:
        raise ValueError("body must have known b and h (use RigidBlock.rectangle(b, h) or "
                         "RigidBlock.from_inertia(R, alpha, I0, m))")
    M = V.positive("mass", mass)
    b, h, g = float(body.b), float(body.h), float(body.g)
    if abs(math.atan2(b, h) - body.alpha) > 1e-9 * max(1.0, body.alpha):
        raise ValueError(f"body.alpha = {body.alpha} does not match atan(b/h) = "
                         f"{math.atan2(b, h)}")
    R = math.hypot(b, h)
    I0 = M * g * R / body.p ** 2
    I_G = I0 - M * R * R
    if I_G < -1e-12 * I0:
        raise ValueError(f"body.p = {body.p} rad/s implies I_0 = M g R/p^2 < M R^2 "
                         f"(p must be <= sqrt(g/R) = {math.sqrt(g / R)})")
    I_G = max(I_G, 0.0)
    return BlockInertia(M=M, b=b, h=h, R=R, I_0=I0, I_G=I_G, I_C=I_G + M * h * h, g=g)


@dataclass(frozen=True)
class FlexibleInertia(BlockInertia):
    """A :class:`FlexibleBody` on a foundation: the :class:`BlockInertia` of the body with its
    column locked (u = 0; ``M = m + m_b``, ``h`` its centre of mass, ``b = B``), which the
    rigid-block formulas of the foundations use (:meth:`TwoSpringFoundation.from_vibration`,
    ``rotational``, ``uplift_rotation``), plus the column and the base in SI units: ``m`` [kg],
    ``H`` [m], ``wn`` [rad/s], ``zeta``, ``I_m``, ``I_b`` [kg m^2], ``m_b`` [kg], ``h_b`` [m]."""

    m: float = 0.0
    H: float = 0.0
    wn: float = 0.0
    zeta: float = 0.0
    I_m: float = 0.0
    m_b: float = 0.0
    I_b: float = 0.0
    h_b: float = 0.0


def flexible_inertia(body, mass=None):
    """:class:`FlexibleInertia` of a :class:`FlexibleBody` (column mass ``body.mass``).

    The base mass is ``base_mass_ratio`` times m, default ``DEFAULT_BASE_MASS_RATIO`` (0.1):
    on the springs the base moves vertically and turns with the column, and a massless base
    would leave three coordinates moving one point mass (a singular mass matrix), as with
    sliding; ``I_b = m_b B^2 / 3`` about its own centre of mass, as on rigid ground.

    Raises
    ------
    ValueError
        Naming ``base_mass_ratio`` if it is 0.
    """
    m = carried_mass(body, mass)
    ratio = DEFAULT_BASE_MASS_RATIO if body.base_mass_ratio is None else body.base_mass_ratio
    if not ratio > 0.0:
        raise ValueError(f"base_mass_ratio = {body.base_mass_ratio!r}: a FlexibleBody on a foundation needs a "
                         f"base mass (> 0; default {DEFAULT_BASE_MASS_RATIO} when unset): the base moves on the "
                         "springs, and a massless one leaves the equations of motion singular")
    B, H, g = body.B, body.H, float(body.g)
    m_b = ratio * m
    I_b = m_b * B * B / 3.0
    I_m = body.rotary_inertia_ratio * m * body.R0 ** 2
    h_b = float(body.base_cm_height)
    M = m + m_b
    h = (m * H + m_b * h_b) / M
    I_C = m * H * H + I_m + m_b * h_b * h_b + I_b
    I_G = I_C - M * h * h
    R = math.hypot(B, h)
    return FlexibleInertia(M=M, b=B, h=h, R=R, I_0=I_G + M * R * R, I_G=I_G, I_C=I_C, g=g,
                           m=m, H=H, wn=body.omega_n, zeta=float(body.zeta), I_m=I_m, m_b=m_b, I_b=I_b,
                           h_b=h_b)


def _body_inertia(body, mass):
    """BlockInertia of an asymmetric RigidBody with a level base (mass ``mass``)."""
    h = level_base_height(body, "foundation= needs",
                          "the foundation's corner springs stand on one line through both pivots")
    M = mass
    I_G = float(body.inertia)
    R = math.hypot(body.b2, h)
    return BlockInertia(M=M, b=0.5 * (body.b1 + body.b2), h=h, R=R, I_0=I_G + M * R * R, I_G=I_G,
                        I_C=I_G + M * h * h, g=float(body.g), skew=0.5 * (body.b2 - body.b1))


def _rocking_is_lower(blk, k_v):
    """True when the rocking mode is the lower one of the uncoupled (c = 0) pair at k_v: rocking
    (2 k_v b^2 - M g h) / I_C <= vertical 2 k_v / M (a slender body)."""
    return (2.0 * k_v * blk.b ** 2 - blk.M * blk.g * blk.h) / blk.I_C <= 2.0 * k_v / blk.M


def _coupled_omega(blk, k_v):
    """Rocking eigenfrequency [rad/s] of an asymmetric body on the two springs, linearised at its
    rest tilt q (:meth:`TwoSpringFoundation.rest_tilt`): the root w^2 of det(K - w^2 M_q) = 0 with
    the mass matrix M_q = [[M, -M h sin q], [-M h sin q, I_C]] and the Hessian K of
    V = M g (y + h cos q) + k_v/2 sum_s (x_s sin q - y)^2, on the rocking branch (the branches
    never cross for c != 0); NaN when it is not positive or the body has no rest."""
    try:
        q = TwoSpringFoundation(k_v).rest_tilt(blk)
    except ValueError:
        return float("nan")
    k, M, IC, h = k_v, blk.M, blk.I_C, blk.h
    y = blk.skew * math.sin(q) - M * blk.g / (2.0 * k)
    sq, cq = math.sin(q), math.cos(q)
    kyy, kyq, kqq = 2.0 * k, 0.0, -M * blk.g * h * cq
    for x in (blk.b2, -blk.b1):
        kyq -= k * x * cq
        kqq += k * (x * x * cq * cq - (x * sq - y) * x * sq)
    myq = -M * h * sq
    a2 = M * IC - myq * myq
    a1 = kyy * IC + kqq * M - 2.0 * kyq * myq
    a0 = kyy * kqq - kyq * kyq
    hi = (a1 + math.sqrt(a1 * a1 - 4.0 * a2 * a0)) / (2.0 * a2)
    lam = a0 / (a2 * hi) if _rocking_is_lower(blk, k_v) else hi
    return math.sqrt(lam) if lam > 0.0 else float("nan")


def _coupled_k_v(blk, omega):
    """k_v whose rocking eigenfrequency (:func:`_coupled_omega`) is ``omega``: from the upright
    linearisation's root of 4 b^2 k^2 - 2 k (P + Q (b^2 + c^2)) + Q P = 0 (P = M g h +
    omega^2 I_C, Q = omega^2 M; rocking branch, k = P / (2 b^2) at c = 0), then Brent's method
    on the rest-tilt linearisation."""
    from scipy.optimize import brentq
    a, c = blk.b, blk.skew
    P = blk.M * blk.g * blk.h + omega ** 2 * blk.I_C
    Q = omega ** 2 * blk.M
    S = P + Q * (a * a + c * c)
    hi = (S + math.sqrt(S * S - 4.0 * a * a * Q * P)) / (4.0 * a * a)
    k0 = hi if P >= Q * a * a else Q * P / (4.0 * a * a * hi)

    def miss(k):
        w = _coupled_omega(blk, k)
        return -omega if math.isnan(w) else w - omega     # no rest: too soft
    lo, up = k0, k0
    for _ in range(200):
        if miss(lo) < 0.0:
            break
        lo /= 1.05
    for _ in range(200):
        if miss(up) > 0.0:
            break
        up *= 1.05
    if not miss(lo) < 0.0 < miss(up):
        raise ValueError(f"omega = {omega:.6g} rad/s: no corner stiffness gives this body that rocking "
                         "frequency at rest on both springs")
    return brentq(miss, lo, up, xtol=1e-300, rtol=1e-15)


def _symmetric_only(blk, foundation):
    """Refuse an asymmetric body on a foundation model of a symmetric block."""
    if blk.skew != 0.0:
        name = foundation.__name__ if isinstance(foundation, type) else type(foundation).__name__
        raise ValueError(f"foundation={name}: an asymmetric RigidBody (b1 = {blk.b1:.6g} m, "
                         f"b2 = {blk.b2:.6g} m) needs foundation=TwoSpringFoundation: the switching and linear "
                         "SDOF models (Yu et al.) turn a symmetric block about its base centre, and an "
                         "asymmetric body's rest state is tilted, carried unequally by its two corners")
    return blk



# --------------------------------------------------------------------------- slope
def _on_slope(ground):
    return ground is not None and not ground.is_level


def _check_slope_release(ground, theta0, dtheta0):
    if theta0 != 0.0 or dtheta0 != 0.0:
        raise ValueError(f"theta0 = {theta0}, dtheta0 = {dtheta0}: on a slope a block on a flexible "
                         "foundation starts at rest in its static equilibrium (theta0 = dtheta0 = 0)")


def _static_tilt(stiffness, d_stiffness, blk, ground):
    """The static rotation q on a slope phi: ``stiffness(q) = M g h sin(q + phi)`` (the moment of
    gravity about the base centre, which the foundation's restoring moment ``stiffness`` carries),
    by Newton from q = 0; refused, naming ``slope``, if no stable root lies below alpha."""
    phi = ground.slope
    mgh = blk.M * blk.g * blk.h
    q = 0.0
    for _ in range(60):
        f = stiffness(q) - mgh * math.sin(q + phi)
        df = d_stiffness(q) - mgh * math.cos(q + phi)
        if df <= 0.0:
            break
        step = f / df
        q -= step
        if abs(step) <= 1e-15 * max(1.0, abs(q)):
            if d_stiffness(q) - mgh * math.cos(q + phi) > 0.0 and 0.0 <= q < math.atan2(blk.b, blk.h):
                return q
            break
    raise ValueError(f"slope = {phi:.6g} rad ({math.degrees(phi):.4g} deg): the block has no stable "
                     "resting tilt on this foundation (gravity's moment along the slope exceeds what the "
                     "foundation can carry in full contact)")


# ------------------------------------------------------------------------ foundations
def _rotational_from_vibration(body, omega, zeta, mass, p_delta, foundation=None):
    blk = block_inertia(body, mass)
    if foundation is not None:
        _symmetric_only(blk, foundation)
    omega = V.positive("omega", omega)
    zeta = V.non_negative("zeta", zeta)
    k_t = omega ** 2 * blk.I_C + (blk.M * blk.g * blk.h if p_delta else 0.0)
    c_t = 2.0 * zeta * omega * blk.I_C
    return blk, k_t, c_t


def _vibration_of(blk, k_t, c_t, p_delta):
    k_eff = k_t - (blk.M * blk.g * blk.h if p_delta else 0.0)
    if k_eff <= 0.0:
        return float("nan"), float("nan")
    omega = math.sqrt(k_eff / blk.I_C)
    return omega, c_t / (2.0 * blk.I_C * omega)


@dataclass(frozen=True)
class TwoSpringFoundation:
    """Tensionless spring-dashpots at the two bottom corners (docs: theory/foundation).

    It carries a :class:`~fastrock.RigidBlock` or a :class:`~fastrock.RigidBody` (an asymmetric
    one with a level base: its corners at -b1 and b2 from the base point below its centre of
    mass, which stays horizontally fixed; it starts at rest at its static tilt, see
    :meth:`initial_state`).  For an asymmetric body ``b`` in the formulas below is the mean
    half-width (b1 + b2)/2: ``k_t = 2 k_v b^2`` is then the rocking stiffness with the vertical
    motion condensed out (the springs' moment at fixed total force); ``omega`` is the rocking
    mode's frequency of the coupled rocking and vertical vibration (:meth:`vibration`).

    Parameters
    ----------
    k_v : float
        Stiffness of each corner spring [N/m], > 0.
    c_v : float
        Viscous coefficient of each corner dashpot [N s/m], >= 0.
    """

    k_v: float
    c_v: float = 0.0
    model = "two-spring"
    kernel = "two_spring"

    def __post_init__(self):
        V.positive("k_v", self.k_v)
        V.non_negative("c_v", self.c_v)

    @classmethod
    def from_vibration(cls, body, omega, zeta=0.0, mass=None):
        """Corner springs giving rocking vibration ``omega`` [rad/s] with damping ratio ``zeta``.

        ``k_v = (omega^2 I_C + M g h) / (2 b^2)``, ``c_v = 2 zeta omega I_C / (2 b^2)``.
        An asymmetric body: ``k_v`` makes ``omega`` its rocking mode's frequency (see
        :meth:`vibration`), ``c_v`` as above.
        """
        blk, k_t, c_t = _rotational_from_vibration(body, omega, zeta, mass, True)
        if blk.skew != 0.0:
            return cls(k_v=_coupled_k_v(blk, omega), c_v=c_t / (2 * blk.b ** 2))
        return cls(k_v=k_t / (2 * blk.b ** 2), c_v=c_t / (2 * blk.b ** 2))

    def rotational(self, body, mass=None):
        """Small-rotation rotational stiffness and damping ``(k_t, c_t) = 2 b^2 (k_v, c_v)``."""
        b = block_inertia(body, mass).b
        return 2 * self.k_v * b * b, 2 * self.c_v * b * b

    def vibration(self, body, mass=None):
        """``(omega [rad/s], zeta)`` of small rocking vibration in full contact (P-Delta kept);
        NaN if ``k_t <= M g h`` (unstable on the foundation).

        An asymmetric body's springs couple rocking and vertical motion (the stiffness term
        ``-2 k_v c`` between y and q, c = (b2 - b1)/2): ``omega`` is then the eigenfrequency of the
        two-degree-of-freedom vibration about its rest tilt whose mode turns into pure rocking as
        c -> 0, and ``zeta = c_t / (2 I_C omega)`` as for the block."""
        k_t, c_t = self.rotational(body, mass)
        blk = block_inertia(body, mass)
        if blk.skew != 0.0:
            om = _coupled_omega(blk, self.k_v)
            return om, c_t / (2.0 * blk.I_C * om)
        return _vibration_of(blk, k_t, c_t, True)

    def flexible_frequencies(self, body):
        """Undamped small-motion frequencies [rad/s] of a :class:`FlexibleBody` at rest on both
        corners: ``(vertical, lower, upper)``, the vertical mode ``sqrt(2 k_v / (m + m_b))`` and
        the two coupled modes of column and rocking, the eigenvalues of ``K phi = w^2 M phi``
        with ``M = [[m, m H], [m H, m H^2 + m_b h_b^2 + I_m + I_b]]`` and
        ``K = [[m w_n^2, -m g], [-m g, 2 k_v B^2 - m g H - m_b g h_b]]`` (docs:
        theory/foundation_flexible); NaN for a mode that is not stable.  ``vibration`` and
        ``from_vibration`` use the body with its column locked instead."""
        if not isinstance(body, FlexibleBody):
            raise ValueError(f"body must be a FlexibleBody (a rigid body's rocking frequency is vibration()), "
                             f"got {type(body).__name__}")
        f = flexible_inertia(body)
        g = f.g
        m11, m12, m22 = f.m, f.m * f.H, f.m * f.H ** 2 + f.m_b * f.h_b ** 2 + f.I_m + f.I_b
        k11, k12 = f.m * f.wn ** 2, -f.m * g
        k22 = 2.0 * self.k_v * f.b ** 2 - f.m * g * f.H - f.m_b * g * f.h_b
        lam = np.sort(np.linalg.eigvals(np.linalg.solve(np.array([[m11, m12], [m12, m22]]),
                                                       np.array([[k11, k12], [k12, k22]]))).real)
        w = [math.sqrt(v) if v > 0.0 else float("nan") for v in lam]
        return math.sqrt(2.0 * self.k_v / f.M), w[0], w[1]

    def uplift_rotation(self, body, mass=None):
        """Static lift-off rotation ``theta_y = M g / (2 k_v b)`` [rad] (small angles)."""
        blk = block_inertia(body, mass)
        return blk.M * blk.g / (2 * self.k_v * blk.b)

    def fill_par(self, par, blk):
        par[P_KV] = self.k_v
        par[P_CV] = self.c_v
        k_t = 2 * self.k_v * blk.b ** 2
        par[P_KT] = k_t
        par[P_CT] = 2 * self.c_v * blk.b ** 2
        par[P_THETA_Y] = blk.M * blk.g * blk.b / k_t

    def initial_state(self, blk, theta0, dtheta0, ground=None):
        """(y_c, y_c', q, q') of a release from rest in vertical equilibrium: both corners
        share the weight if they both touch, else the lower corner carries it alone.

        On a slope (``ground``) the block starts at rest in its static equilibrium: both
        corners compressed, ``y_c = -M g cos(phi) / (2 k_v)`` and the tilt q of
        ``k_v b^2 sin(2q) = M g h sin(q + phi)`` (downhill, q > 0).

        An asymmetric body (``blk.skew`` = c != 0) released from rest upright (theta0 =
        dtheta0 = 0), or on a slope, starts at rest in its static equilibrium: the tilt q of
        ``cos(q) (2 k_v b^2 sin(q) + c M G) = M g h sin(q + phi)`` (G = g cos(phi); toward its
        nearer corner) and ``y_c = c sin(q) - M G / (2 k_v)``; any other release starts in
        vertical equilibrium at theta0."""
        if isinstance(blk, FlexibleInertia):
            return self._flexible_initial_state(blk, theta0, dtheta0, ground)
        if blk.skew != 0.0:
            return self._body_initial_state(blk, theta0, dtheta0, ground)
        if _on_slope(ground):
            _check_slope_release(ground, theta0, dtheta0)
            kb2 = self.k_v * blk.b ** 2
            q = _static_tilt(lambda q: kb2 * math.sin(2 * q), lambda q: 2 * kb2 * math.cos(2 * q), blk, ground)
            d_s = blk.M * blk.g * math.cos(ground.slope) / (2 * self.k_v)
            if blk.b * math.sin(q) >= d_s:
                raise ValueError(f"slope = {ground.slope:.6g} rad: at its static tilt {q:.4g} rad the block's "
                                 "uphill corner leaves its spring: it cannot rest on this foundation")
            return np.array([-d_s, 0.0, q, 0.0], float)
        return np.array([self._release_height(blk, theta0), 0.0, theta0, dtheta0], float)

    def _release_height(self, blk, theta0):
        """y_c of a symmetric body released at theta0 in vertical equilibrium: both corners
        share the weight if they both touch, else the lower corner carries it alone."""
        d_s = blk.M * blk.g / (2 * self.k_v)
        lift = blk.b * math.sin(abs(theta0))
        return -d_s if lift <= d_s else lift - 2 * d_s

    def _flexible_initial_state(self, blk, theta0, dtheta0, ground):
        """(y_c, y_c', u, u', q, q') of a FlexibleBody: the rigid block's vertical equilibrium
        (:meth:`initial_state`) with the column undeflected, u = u' = 0 (at rest upright this is
        the static equilibrium, y_c = -(m + m_b) g / (2 k_v)).  Level ground only."""
        if _on_slope(ground):
            raise ValueError(f"slope = {ground.slope:.6g} rad: a FlexibleBody on a foundation runs on level "
                             "ground only (its static equilibrium on a slope is not modelled yet)")
        return np.array([self._release_height(blk, theta0), 0.0, 0.0, 0.0, theta0, dtheta0], float)

    def _body_initial_state(self, blk, theta0, dtheta0, ground):
        """initial_state of an asymmetric body (corners at x_s = s b + c, c = blk.skew)."""
        a, c = blk.b, blk.skew
        if _on_slope(ground) or (theta0 == 0.0 and dtheta0 == 0.0):
            phi = ground.slope if _on_slope(ground) else 0.0
            if _on_slope(ground):
                _check_slope_release(ground, theta0, dtheta0)
            q = self.rest_tilt(blk, phi)
            d_s = blk.M * blk.g * math.cos(phi) / (2 * self.k_v)
            return np.array([c * math.sin(q) - d_s, 0.0, q, 0.0], float)
        d_s = blk.M * blk.g / (2 * self.k_v)
        sq = math.sin(theta0)
        if a * abs(sq) <= d_s:          # both corners carry it
            yc = c * sq - d_s
        else:                           # the lower corner alone
            yc = (math.copysign(a, sq) + c) * sq - 2 * d_s
        return np.array([yc, 0.0, theta0, dtheta0], float)

    def rest_tilt(self, blk, slope=0.0):
        """Static rotation q [rad] of the body at rest on both corners (Newton from q = 0):
        ``cos(q) (2 k_v b^2 sin(q) + c M G) = M g h sin(q + slope)``, G = g cos(slope),
        c = (b2 - b1)/2 (q = 0 on level ground for a symmetric block).  Refused, naming
        ``k_v``, if no stable rest with both corners on their springs lies between -alpha1 and
        alpha2."""
        a, c, M, g, h = blk.b, blk.skew, blk.M, blk.g, blk.h
        G = g * math.cos(slope)
        k2 = 2.0 * self.k_v * a * a
        q = 0.0
        for _ in range(60):
            sq, cq = math.sin(q), math.cos(q)
            f = cq * (k2 * sq + c * M * G) - M * g * h * math.sin(q + slope)
            df = k2 * math.cos(2.0 * q) - c * M * G * sq - M * g * h * math.cos(q + slope)
            if df <= 0.0:
                break
            step = f / df
            q -= step
            if abs(step) <= 1e-15 * max(1.0, abs(q)):
                stable = (k2 * math.cos(2.0 * q) - c * M * G * math.sin(q)
                          - M * g * h * math.cos(q + slope)) > 0.0
                on_springs = a * abs(math.sin(q)) < M * G / (2.0 * self.k_v)
                if stable and on_springs and -math.atan2(blk.b1, h) < q < math.atan2(blk.b2, h):
                    return q
                break
        where = f"slope = {slope:.6g} rad: " if slope else ""
        raise ValueError(f"k_v = {self.k_v:.6g} N/m: {where}the body has no stable rest on both corner "
                         f"springs (b1 = {blk.b1:.6g} m, b2 = {blk.b2:.6g} m, h = {h:.6g} m, M = {M:.6g} kg): "
                         "its weight's moment about the base centre lifts a corner; stiffer springs hold it")


@dataclass(frozen=True)
class SwitchingFoundation:
    """Switching SDOF foundation (docs: theory/foundation; Yu et al.'s model with P-Delta kept).

    Parameters
    ----------
    k_t : float
        Rotational stiffness in the contact phase [N m/rad], > 0.
    c_t : float
        Rotational damping in the contact phase [N m s/rad], >= 0.
    e_f : float
        Angular-velocity restitution applied at re-contact, in [0, 1] (default 1: none).
    """

    k_t: float
    c_t: float = 0.0
    e_f: float = 1.0
    model = "switching"
    kernel = "switching"

    def __post_init__(self):
        V.positive("k_t", self.k_t)
        V.non_negative("c_t", self.c_t)
        V.in_closed("e_f", self.e_f, 0.0, 1.0)

    @classmethod
    def from_vibration(cls, body, omega, zeta=0.0, e_f=1.0, mass=None):
        """Contact phase with vibration ``omega`` [rad/s] and damping ratio ``zeta``:
        ``k_t = omega^2 I_C + M g h``, ``c_t = 2 zeta omega I_C``."""
        _blk, k_t, c_t = _rotational_from_vibration(body, omega, zeta, mass, True, cls)
        return cls(k_t=k_t, c_t=c_t, e_f=e_f)

    def vibration(self, body, mass=None):
        """``(omega [rad/s], zeta)`` of the contact phase (P-Delta kept)."""
        return _vibration_of(_symmetric_only(block_inertia(body, mass), self), self.k_t, self.c_t, True)

    def uplift_rotation(self, body, mass=None):
        """``theta_y = M g b / k_t`` [rad]."""
        blk = _symmetric_only(block_inertia(body, mass), self)
        return blk.M * blk.g * blk.b / self.k_t

    def fill_par(self, par, blk):
        _symmetric_only(blk, self)
        par[P_KT] = self.k_t
        par[P_CT] = self.c_t
        par[P_EF] = self.e_f
        par[P_THETA_Y] = blk.M * blk.g * blk.b / self.k_t

    def initial_state(self, blk, theta0, dtheta0, ground=None):
        """(theta, theta'): the release; on a slope (``ground``) the static tilt of
        ``k_t theta = M g h sin(theta + phi)``, in the contact phase (``|k_t theta| < M g cos(phi) b``)."""
        if _on_slope(ground):
            _check_slope_release(ground, theta0, dtheta0)
            q = _static_tilt(lambda q: self.k_t * q, lambda q: self.k_t, blk, ground)
            if self.k_t * q >= blk.M * blk.g * math.cos(ground.slope) * blk.b:
                raise ValueError(f"slope = {ground.slope:.6g} rad: at its static tilt {q:.4g} rad the "
                                 "foundation's moment reaches M g cos(slope) b: the block rocks at once")
            return np.array([q, 0.0], float)
        return np.array([theta0, dtheta0], float)


@dataclass(frozen=True)
class LinearVibration:
    """Linear rotational SDOF ``I_C theta'' + c_t theta' + k_t theta = -M h a_g`` (reference).

    Parameters
    ----------
    k_t : float
        Rotational stiffness [N m/rad], > 0.
    c_t : float
        Rotational damping [N m s/rad], >= 0.
    """

    k_t: float
    c_t: float = 0.0
    model = "linear"
    kernel = "linear_sdof"

    def __post_init__(self):
        V.positive("k_t", self.k_t)
        V.non_negative("c_t", self.c_t)

    @classmethod
    def from_vibration(cls, body, omega, zeta=0.0, mass=None):
        """``k_t = omega^2 I_C``, ``c_t = 2 zeta omega I_C``."""
        _blk, k_t, c_t = _rotational_from_vibration(body, omega, zeta, mass, False, cls)
        return cls(k_t=k_t, c_t=c_t)

    def vibration(self, body, mass=None):
        return _vibration_of(_symmetric_only(block_inertia(body, mass), self), self.k_t, self.c_t, False)

    def fill_par(self, par, blk):
        _symmetric_only(blk, self)
        par[P_KT] = self.k_t
        par[P_CT] = self.c_t
        par[P_THETA_Y] = np.inf

    def initial_state(self, blk, theta0, dtheta0, ground=None):
        """(theta, theta'): the release; on a slope (``ground``) the static rotation
        ``M h g sin(phi) / k_t``."""
        if _on_slope(ground):
            _check_slope_release(ground, theta0, dtheta0)
            return np.array([blk.M * blk.h * blk.g * math.sin(ground.slope) / self.k_t, 0.0], float)
        return np.array([theta0, dtheta0], float)


FOUNDATIONS = (TwoSpringFoundation, SwitchingFoundation, LinearVibration)


def foundation_par(body, foundation, mass=None):
    """Parameter vector of a block on a foundation (registry ``build_par``); an asymmetric
    RigidBody's rigid entries hold its right side (alpha2, p2, e21), as in the rigid_body
    model's, and P_ALPHA_LEFT its alpha1."""
    blk = block_inertia(body, mass)
    flexible = isinstance(blk, FlexibleInertia)
    if flexible and not isinstance(foundation, TwoSpringFoundation):
        raise ValueError(f"foundation={type(foundation).__name__}: a FlexibleBody stands on "
                         "TwoSpringFoundation only (the switching and linear SDOF models turn a rigid block)")
    par = np.zeros(N_PAR_FOUNDATION_FLEXIBLE if flexible else N_PAR)
    if blk.skew != 0.0:
        par[0], par[1], par[2] = body.alpha2, body.p2, body.e21
        par[P_ALPHA_LEFT] = body.alpha1
    else:
        par[0] = body.alpha      # rigid layout: alpha, p, e, g, theta_over
        par[1] = body.p
        par[2] = body.e
        par[P_ALPHA_LEFT] = body.alpha
    par[3] = body.g
    par[4] = body.theta_over
    par[P_B_SKEW] = blk.skew
    par[P_MASS] = blk.M
    par[P_I_G] = blk.I_G
    par[P_B] = blk.b
    par[P_H] = blk.h
    par[P_I_C] = blk.I_C
    par[P_I_0] = blk.I_0
    par[P_EF] = 1.0
    foundation.fill_par(par, blk)
    if flexible:
        par[PF_M] = blk.m
        par[PF_H] = blk.H
        par[PF_WN] = blk.wn
        par[PF_ZETA] = blk.zeta
        par[PF_IM] = blk.I_m
        par[PF_MB] = blk.m_b
        par[PF_IB] = blk.I_b
        par[PF_HB] = blk.h_b
    return par


def foundation_friction_par(body, foundation, friction, mass=None):
    """Parameter vector of a block sliding on the two-spring foundation (registry ``build_par``
    of two_spring_friction): :func:`foundation_par`'s, then mu_s, mu_k."""
    from fastrock.kernels.layout import N_PAR_FOUNDATION
    if not isinstance(foundation, TwoSpringFoundation):
        raise ValueError(f"friction= on a flexible foundation needs foundation=TwoSpringFoundation, got "
                         f"{type(foundation).__name__}")
    if not math.isfinite(friction.mu_s):
        raise ValueError("friction: mu_s must be finite on a flexible foundation (Friction(inf) is no "
                         f"effect there), got mu_s={friction.mu_s}")
    par = np.zeros(N_PAR_FOUNDATION + 2)
    par[:N_PAR_FOUNDATION] = foundation_par(body, foundation, mass)
    par[N_PAR_FOUNDATION] = friction.mu_s
    par[N_PAR_FOUNDATION + 1] = friction.mu_k
    return par




def wall_face(body, blk, wall):
    """(a, H) [m]: the wall-side top corner from the base point below the centre of mass, in the
    body frame: a horizontal (b for a block, b2 or b1 for an asymmetric RigidBody), H up (2h, or
    h + :meth:`RigidBody.wall_face_top`)."""
    a = blk.b + wall.side * blk.skew
    if isinstance(body, RigidBody) and not body.is_symmetric:
        return a, blk.h + body.wall_face_top(wall.side)
    return a, 2.0 * blk.h


def wall_limit_angle(body, blk, wall):
    """Rotation theta_w [rad] toward the wall at which the two-spring block's top corner on the
    wall side touches a tall wall (``math.inf``: never, before the corner's reach a' = hypot(a, H)).

    The base point below the centre of mass is held horizontally, so that corner is at
    ``a cos(theta) + H sin(theta)`` from it (toward the wall), whatever y_c: contact at
    ``a cos(theta_w) + H sin(theta_w) = a + d``, i.e. ``theta_w = asin((a + d)/a') - atan2(a, H)``.
    (The rigid wall model turns about the pivot corner: ``H sin(theta_w) = d``; here the corner
    also comes back by ``a (1 - cos theta)``, so theta_w is a little larger.)

    Raises ValueError for what the model leaves out: gap 0, a wall lower than the body's
    wall-side face, wall friction and a rounded top."""
    if wall.gap == 0.0:
        raise ValueError("wall: gap = 0 is not available on a flexible foundation (the block's base would "
                         "touch the wall as its corner springs compress); give gap > 0")
    a, H = wall_face(body, blk, wall)
    if wall.height is not None and wall.height < H:
        raise ValueError(f"wall: height = {wall.height:.6g} m is lower than the body's face toward the wall "
                         f"({H:.6g} m): on a flexible foundation only a wall at least as tall as the body is "
                         "modelled (its top corner touches the wall); give height=None or height >= "
                         f"{H:.6g}")
    if wall.friction != 0.0:
        raise ValueError("wall: friction > 0 is not available on a flexible foundation (its wall is "
                         "frictionless)")
    if getattr(body, "top_radius", None) is not None:
        raise ValueError("wall: a rounded top (top_radius) is not available on a flexible foundation (its "
                         "wall contact point is the square top corner)")
    reach = math.hypot(a, H)
    if a + wall.gap >= reach:
        return math.inf
    return math.asin((a + wall.gap) / reach) - math.atan2(a, H)


def foundation_wall_par(body, foundation, wall, mass=None):
    """Parameter vector of a block on the two-spring foundation beside a wall (kernels/
    foundation_wall.py): :func:`foundation_par` with the wall side, theta_w
    (:func:`wall_limit_angle`) and e_w in the rigid layout's wall slots."""
    from fastrock.kernels.layout import P_E_W, P_THETA_W, P_WALL_SIDE
    par = foundation_par(body, foundation, mass)
    par[P_WALL_SIDE] = float(wall.side)
    par[P_THETA_W] = wall_limit_angle(body, block_inertia(body, mass), wall)
    par[P_E_W] = wall.restitution
    return par


def switching_wall_par(body, foundation, wall, mass=None):
    """Parameter vector of a block on the switching foundation beside a wall (kernels/
    foundation_wall.py): its rocking phase is Housner's, so the wall is the rigid wall model's
    (:meth:`Wall.limit_angle`: tall or short wall, rounded top), reached while rocking on the pivot
    near the wall.

    Raises ValueError for gap 0, wall friction, and a wall the contact phase could reach
    (theta_w <= theta_y = M g b / k_t: the block turns about its base centre there)."""
    from fastrock.kernels.layout import P_E_W, P_THETA_W, P_THETA_Y, P_WALL_SIDE
    if wall.gap == 0.0:
        raise ValueError("wall: gap = 0 is not available on a flexible foundation (Hogan's one-sided rocking "
                         "needs the block resting against the wall on rigid ground); give gap > 0")
    if wall.friction != 0.0:
        raise ValueError("wall: friction > 0 is not available on a flexible foundation (its wall is "
                         "frictionless)")
    par = foundation_par(body, foundation, mass)
    tw = wall.limit_angle(body)
    if not tw > par[P_THETA_Y]:
        raise ValueError(f"wall: gap = {wall.gap:.6g} m puts the wall at theta_w = {tw:.6g} rad, not beyond the "
                         f"switching model's uplift rotation theta_y = {par[P_THETA_Y]:.6g} rad: its contact phase "
                         "(rotation about the base centre) would reach the wall, which is not modelled; give a "
                         "larger gap or use TwoSpringFoundation")
    par[P_WALL_SIDE] = float(wall.side)
    par[P_THETA_W] = tw
    par[P_E_W] = wall.restitution
    return par
