"""Asymmetric rigid bodies: two base pivots with their own slenderness and
size, from numbers, a polygon or a 3D mesh (issue #17)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from fastrock import _validate as V
from fastrock.constants import G_STANDARD
from fastrock.model import geometry as geo
from fastrock.model.bodies import RigidBlock

#: Two sides whose b and h agree to this relative tolerance make a symmetric body.
SYMMETRY_RTOL = 1e-12

TOP_PROFILES = ("flat", "rounded")


@dataclass(frozen=True)
class RigidBody:
    """A rigid body rocking on two base pivots, each with its own slenderness.

    Side 1 is the left pivot at (-b1, -h1) from the centre of mass, side 2 the
    right pivot at (b2, -h2) (x to the right, y up).  The body rocks on pivot 2
    when theta > 0 (tilted to the right) and on pivot 1 when theta < 0.  Each
    side k has its own Housner parameters: alpha_k = atan(b_k / h_k),
    R_k = sqrt(b_k^2 + h_k^2), I_O,k = I_G + m R_k^2, p_k^2 = m g R_k / I_O,k,
    and the uplift threshold g tan(alpha_k) of a ground acceleration that tips
    the body onto that side (a_g > 0 tips it onto side 1).

    An impact from pivot k onto pivot j keeps the angular momentum about the
    new pivot: theta'+ = e_kj theta'-, e_kj = (I_G + m r_k . r_j) / I_O,j, with
    r_k, r_j the vectors from each pivot to the centre of mass at theta = 0.
    For a rectangle this is Housner's e = 1 - 1.5 sin^2(alpha).  A given ``e``
    replaces both ratios.

    A body whose two sides agree (b1 = b2 and h1 = h2 to 1e-12 relative) is
    symmetric: every model runs it as its equivalent :class:`RigidBlock`
    (:meth:`to_block`).  An asymmetric body runs in the two-sided rocking
    model (``simulate``, ``overturning_spectrum``) and, with walls, friction
    or flight, in the contact model (a level base, h1 = h2), and on a
    :class:`TwoSpringFoundation` (a level base; the switching and linear
    foundation models refuse it), carrying its own mass.  Its early decisions (``early_exit``)
    hold per side: a run stops as safe once the energy is below the barrier
    of both the side it rocks on next and the other side after the impact,
    and a fall past alpha_k completes in closed form on that side.

    Parameters
    ----------
    mass : float
        m [kg].
    inertia : float
        I_G [kg m^2], about the out-of-plane axis through the centre of mass.
    b1, h1 : float
        The left pivot is at (-b1, -h1) from the centre of mass [m]; b1 > 0
        (the centre of mass lies above the base, between the pivots), h1 > 0.
    b2, h2 : float
        The right pivot is at (b2, -h2) [m]; b2 > 0, h2 > 0.
    e : float, optional
        Restitution of every impact, theta'+ = e theta'-, in [0, 1] and no
        larger than sqrt(I_O,k / I_O,j) (an impact must not add energy).
        Default: the angular-momentum map, side by side.
    g : float
        Gravity [m/s^2].
    theta_over : float
        Rotation [rad] counted as overturning, above both alphas (default pi/2).
    top : str
        Top profile for wall contact: "flat" (default: the top corner of
        the wall-side face touches the wall) or "rounded" (with
        ``top_radius`` [m]: the top corner on the wall side is a quarter
        circle, which touches a wall later; in the wall model and the
        contact model).
    top_radius : float, optional
    outline : array, shape (n, 2), optional
        The body's outline relative to the centre of mass [m], for
        :meth:`describe` and :meth:`plot` (set by the constructors below).

    Examples
    --------
    >>> body = RigidBody.from_polygon([(0, 0), (0.6, 0), (0.6, 2.0), (0, 2.0)], mass=100.0)
    >>> round(body.alpha1, 6), round(body.alpha2, 6), body.is_symmetric
    (0.291457, 0.291457, True)
    >>> wedge = RigidBody.from_polygon([(0, 0), (1.0, 0), (0.2, 2.0)], density=2500, thickness=0.5)
    >>> round(wedge.alpha1, 4), round(wedge.alpha2, 4)    # the centre of mass is left of the middle
    (0.5404, 0.7328)
    """

    mass: float
    inertia: float
    b1: float
    h1: float
    b2: float
    h2: float
    e: float | None = None
    g: float = G_STANDARD
    theta_over: float = math.pi / 2
    top: str = "flat"
    top_radius: float | None = None
    outline: np.ndarray | None = field(default=None, compare=False, repr=False)
    kind: str = field(default="rigid_body", init=False)
    source_block: RigidBlock | None = field(default=None, init=False, compare=False, repr=False)

    def __post_init__(self):
        for nm in ("mass", "inertia", "b1", "h1", "b2", "h2"):
            v = getattr(self, nm)
            if isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool):
                object.__setattr__(self, nm, float(v))
        V.positive("mass", self.mass)
        V.positive("inertia", self.inertia)
        for nm in ("h1", "h2"):
            V.positive(nm, getattr(self, nm))
        for nm in ("b1", "b2"):
            v = V.finite(nm, getattr(self, nm))
            if v <= 0.0:
                raise ValueError(f"{nm} must be > 0, got {v}: the body cannot stand (its centre of mass "
                                 f"projects outside the support between the pivots (-b1, -h1) and (b2, -h2))")
        V.positive("g", self.g)
        V.in_open("theta_over", self.theta_over, max(self.alpha1, self.alpha2), math.pi,
                  lo_label="the larger alpha", hi_label="pi")
        V.choice("top", self.top, TOP_PROFILES)
        if self.top == "rounded":
            if self.top_radius is None:
                raise ValueError("top_radius [m] is needed with top='rounded'")
            V.positive("top_radius", self.top_radius)
        elif self.top_radius is not None:
            raise ValueError("top_radius is for top='rounded' only")
        if self.outline is not None:
            object.__setattr__(self, "outline", np.array(self.outline, dtype=float))
        if self.e is None:
            e12, e21 = self.e12, self.e21
            if min(e12, e21) < 0.0:
                raise ValueError(f"the angular-momentum impact map gives a negative restitution (e12 = "
                                 f"{e12:.3f}, e21 = {e21:.3f}) for this squat body; give e explicitly")
        else:
            e = V.in_closed("e", self.e, 0.0, 1.0)
            io1, io2 = self.inertia_about_pivot1, self.inertia_about_pivot2
            cap = math.sqrt(min(io1 / io2, io2 / io1))
            if e > cap * (1.0 + 1e-12):
                raise ValueError(f"e = {e} would add energy at the impact onto the pivot of larger inertia: "
                                 f"e^2 I_O,j / I_O,k <= 1 needs e <= {cap:.6g} for this body")

    # ------------------------------------------------------------- derived
    @property
    def R1(self):
        """Distance from the left pivot to the centre of mass [m]."""
        return math.hypot(self.b1, self.h1)

    @property
    def R2(self):
        """Distance from the right pivot to the centre of mass [m]."""
        return math.hypot(self.b2, self.h2)

    @property
    def alpha1(self):
        """Slenderness of side 1 (rocking on the left pivot, theta < 0) [rad]."""
        return math.atan2(self.b1, self.h1)

    @property
    def alpha2(self):
        """Slenderness of side 2 (rocking on the right pivot, theta > 0) [rad]."""
        return math.atan2(self.b2, self.h2)

    @property
    def inertia_about_pivot1(self):
        """I_O,1 = I_G + m R1^2 [kg m^2]."""
        return self.inertia + self.mass * (self.b1 * self.b1 + self.h1 * self.h1)

    @property
    def inertia_about_pivot2(self):
        """I_O,2 = I_G + m R2^2 [kg m^2]."""
        return self.inertia + self.mass * (self.b2 * self.b2 + self.h2 * self.h2)

    @property
    def p1(self):
        """Frequency parameter of side 1, p1^2 = m g R1 / I_O,1 [rad/s]."""
        return math.sqrt(self.mass * self.g * self.R1 / self.inertia_about_pivot1)

    @property
    def p2(self):
        """Frequency parameter of side 2, p2^2 = m g R2 / I_O,2 [rad/s]."""
        return math.sqrt(self.mass * self.g * self.R2 / self.inertia_about_pivot2)

    def _shared_momentum(self):
        # I_G + m r_1 . r_2, r_1 = (b1, h1), r_2 = (-b2, h2) from each pivot to the CM
        return self.inertia + self.mass * (self.h1 * self.h2 - self.b1 * self.b2)

    @property
    def e12(self):
        """Restitution of an impact from pivot 1 onto pivot 2 (``e``, or the
        angular-momentum map (I_G + m r_1 . r_2) / I_O,2)."""
        if self.e is not None:
            return self.e
        return self._shared_momentum() / self.inertia_about_pivot2

    @property
    def e21(self):
        """Restitution of an impact from pivot 2 onto pivot 1."""
        if self.e is not None:
            return self.e
        return self._shared_momentum() / self.inertia_about_pivot1

    @property
    def uplift_acceleration1(self):
        """g tan(alpha1) [m/s^2]: a ground acceleration a_g > 0 above it tips the body onto pivot 1."""
        return self.g * math.tan(self.alpha1)

    @property
    def uplift_acceleration2(self):
        """g tan(alpha2) [m/s^2]: a_g < 0 with ``|a_g|`` above it tips the body onto pivot 2."""
        return self.g * math.tan(self.alpha2)

    @property
    def smaller_side(self):
        """1 or 2: the side of the smaller alpha (1 on a tie), to which spectra refer their ratios."""
        return 1 if self.alpha1 <= self.alpha2 else 2

    @property
    def alpha(self):
        """The smaller slenderness, min(alpha1, alpha2) [rad] (the ratios of spectra refer to it)."""
        return self.alpha1 if self.smaller_side == 1 else self.alpha2

    @property
    def p(self):
        """p of the side of the smaller alpha [rad/s]."""
        return self.p1 if self.smaller_side == 1 else self.p2

    @property
    def uplift_acceleration(self):
        """g tan(alpha) of the smaller alpha: the lower uplift threshold [m/s^2]."""
        return self.g * math.tan(self.alpha)

    @property
    def tan_alpha(self):
        return math.tan(self.alpha)

    @property
    def is_symmetric(self):
        """True when b1 = b2 and h1 = h2 (to SYMMETRY_RTOL): the body is a :class:`RigidBlock`."""
        return (math.isclose(self.b1, self.b2, rel_tol=SYMMETRY_RTOL, abs_tol=0.0) and
                math.isclose(self.h1, self.h2, rel_tol=SYMMETRY_RTOL, abs_tol=0.0))

    @property
    def pivots(self):
        """((-b1, -h1), (b2, -h2)): the pivots relative to the centre of mass [m]."""
        return (-self.b1, -self.h1), (self.b2, -self.h2)

    def wall_face_top(self, side):
        """Height [m] above the centre of mass of the top of the body's face toward a wall on
        ``side`` (+1 right, -1 left): the top of its outline, the face taken vertical above that
        side's pivot, so no point of the body reaches the wall before that corner does (a face
        leaning back from the wall touches it later: this contact angle is the conservative one).

        Raises ValueError without an outline, or when the outline overhangs the pivot toward the
        wall."""
        if self.outline is None:
            raise ValueError("wall: a RigidBody needs its outline (RigidBody.from_polygon, from_mesh or "
                             "outline=) for the wall contact: its top corner on the wall side")
        P = np.asarray(self.outline, float)
        bw = self.b2 if side > 0 else self.b1
        reach = float((side * P[:, 0]).max())
        if reach > bw * (1.0 + 1e-9):
            raise ValueError(f"wall: the outline reaches {reach:.6g} m past the centre of mass on the wall "
                             f"side (side={side:+d}), beyond its pivot at {bw:.6g} m: an overhang toward the "
                             f"wall is not in the contact model (its wall-side face is vertical above the "
                             f"pivot); put the wall on the other side or use a body without the overhang")
        return float(P[:, 1].max())

    # -------------------------------------------------------- reductions
    def to_block(self):
        """The equivalent :class:`RigidBlock` of a symmetric body (side 1's
        alpha, p and restitution; the block it was made from by
        :meth:`from_block`, unchanged)."""
        if not self.is_symmetric:
            raise ValueError(f"the body is not symmetric (b1 = {self.b1:.6g}, b2 = {self.b2:.6g}, "
                             f"h1 = {self.h1:.6g}, h2 = {self.h2:.6g} m): it has no equivalent RigidBlock")
        if self.source_block is not None:
            return self.source_block
        return RigidBlock(alpha=self.alpha1, p=self.p1, e=self.e12, g=self.g, theta_over=self.theta_over,
                          b=self.b1, h=self.h1, top_radius=self.top_radius if self.top == "rounded" else None)

    @property
    def has_level_base(self):
        """True when the two pivots are at one height (h1 = h2 to 1e-9 relative): the body
        stands on one plane on both pivots."""
        return abs(self.h1 - self.h2) <= LEVEL_BASE_RTOL * max(self.h1, self.h2)

    def on_level_ground(self):
        """This body as it rests on one plane: turned about its centre of mass until its two
        pivots are at one height (h1 = h2), as :meth:`from_polygon` lays an outline's lowest
        facet flat.

        Pivots at different heights (h1 != h2) stand on a step: the rocking and wall models take
        them so, with theta = 0 the pose on both pivots.  Sliding, flight and a flexible foundation
        have one ground plane, which such a body touches on both pivots only in this turned pose.
        Mass, I_G, the restitution and the pivots' distances from the centre of mass (hence
        R1, R2 and the impact map) are unchanged; alpha1 and alpha2 change by the turn.  A body
        with a level base is returned as it is.

        Raises ValueError naming ``h1``/``h2`` when the centre of mass does not project between
        the pivots in the turned pose (the body cannot stand on level ground), ``top`` for a
        rounded top (its arc is defined on an upright face), and ``theta_over`` when it is no
        longer above both new alphas.

        Examples
        --------
        >>> step = RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=0.8, b2=0.3, h2=0.9)
        >>> flat = step.on_level_ground()
        >>> flat.has_level_base, round(flat.b1, 6), round(flat.b2, 6), round(flat.h1, 6)
        (True, 0.039223, 0.470679, 0.823688)
        """
        if self.has_level_base:
            return self
        if self.top == "rounded":
            raise ValueError("top: a rounded top is defined on an upright wall-side face; turning a body with "
                             "pivots at different heights (h1 != h2) onto level ground would tilt it. Give the "
                             "body in its resting pose (from_polygon with the outline) instead")
        # P1 -> P2 is (b1 + b2, h1 - h2); a clockwise turn by its angle lays it flat (geo.rotate)
        tilt = math.atan2(self.h1 - self.h2, self.b1 + self.b2)
        (x1, y1), (x2, y2) = geo.rotate(np.array(self.pivots), tilt)
        y0 = 0.5 * (y1 + y2)
        if not x1 < 0.0 < x2:
            raise ValueError(f"h1, h2: the body cannot stand on level ground: turned by {tilt:.6g} rad to put "
                             f"its pivots at one height, its centre of mass projects at 0 outside the "
                             f"support [{x1:.6g}, {x2:.6g}] m")
        outline = None if self.outline is None else geo.rotate(self.outline, tilt)
        return RigidBody(mass=self.mass, inertia=self.inertia, b1=-x1, h1=-y0, b2=x2, h2=-y0, e=self.e,
                         g=self.g, theta_over=self.theta_over, outline=outline)

    # ------------------------------------------------------- constructors
    @classmethod
    def from_block(cls, block, mass=1.0):
        """The symmetric body of a :class:`RigidBlock` (its b and h, or the
        rectangle of its alpha and p), of mass ``mass`` [kg]; :meth:`to_block`
        gives the block back unchanged."""
        if not isinstance(block, RigidBlock):
            raise ValueError(f"block must be a fastrock.RigidBlock, got {type(block).__name__}")
        m = V.positive("mass", mass)
        if block.b is not None and block.h is not None:
            b, h = block.b, block.h
            R = math.hypot(b, h)
        else:
            R = 3.0 * block.g / (4.0 * block.p ** 2)
            b, h = R * math.sin(block.alpha), R * math.cos(block.alpha)
        k2 = block.g * R / block.p ** 2 - R * R          # I_G / m from p^2 = g R / (k^2 + R^2)
        body = cls(mass=m, inertia=m * k2, b1=b, h1=h, b2=b, h2=h, e=block.e, g=block.g,
                   theta_over=block.theta_over, top="flat" if block.top_radius is None else "rounded",
                   top_radius=block.top_radius,
                   outline=np.array([(-b, -h), (b, -h), (b, h), (-b, h)]))
        object.__setattr__(body, "source_block", block)
        return body

    @classmethod
    def from_polygon(cls, vertices, *, density=None, thickness=None, mass=None, pose=0.0, e=None,
                     g=G_STANDARD, theta_over=math.pi / 2):
        """A body from its 2D outline.

        Area, centre of mass and I_G come from the polygon (a plate of
        uniform density); the pivots are the two end points of the facet of
        the convex hull that rests on the ground in the pose.

        Parameters
        ----------
        vertices : array_like, shape (n, 2)
            The outline [m], once around, in either orientation; it must not
            cross itself.
        density, thickness : float
            [kg/m^3] and the out-of-plane thickness [m]: mass = density *
            thickness * area.  Or give ``mass``.
        mass : float
            m [kg] (then I_G = m J / A).
        pose : float
            Rotation of the outline [rad], clockwise positive (as theta):
            the body then settles on the hull facet facing most nearly down.
            Raises ValueError (naming ``pose``) if the centre of mass does not
            project inside that facet: the body cannot stand.
        e, g, theta_over :
            As in the class.
        """
        props = geo.polygon_properties(vertices)
        m = _mass(mass, density, props.area, thickness)
        sup = geo.resting_support(geo.as_polygon(vertices), props.centroid, pose)
        return cls(mass=m, inertia=m * props.polar_moment / props.area,
                   b1=-sup.left[0], h1=-sup.left[1], b2=sup.right[0], h2=-sup.right[1],
                   e=e, g=g, theta_over=theta_over, outline=sup.outline)

    @classmethod
    def from_mesh(cls, path, axis=(0.0, 1.0, 0.0), *, up=(0.0, 0.0, 1.0), density=None, mass=None,
                  pose=0.0, e=None, g=G_STANDARD, theta_over=math.pi / 2):
        """A body from a closed triangulated 3D surface (OBJ or STL).

        Volume, centre of mass and the inertia about the axis through the
        centre of mass along ``axis`` come from the mesh (uniform density);
        the pivots from the section of the mesh by the shaking plane (normal to
        ``axis``, through the centre of mass), as in :meth:`from_polygon`.

        Parameters
        ----------
        path : str or Path
            OBJ or STL file [m]; the surface must be closed (watertight).
        axis : 3-vector
            Unit normal of the shaking plane (the rocking axis).
        up : 3-vector
            Unit vertical of the file's coordinates (default z), normal to
            ``axis``; the plane's x axis is ``axis x up``.
        density : float
            [kg/m^3]: mass = density * volume.  Or give ``mass`` [kg].
        pose, e, g, theta_over :
            As in :meth:`from_polygon`.
        """
        sec = geo.mesh_section(path, axis, up)
        m = _mass(mass, density, sec.volume, plate=False)
        sup = geo.resting_support(np.vstack(sec.loops), (0.0, 0.0), pose)
        return cls(mass=m, inertia=m * sec.inertia / sec.volume,
                   b1=-sup.left[0], h1=-sup.left[1], b2=sup.right[0], h2=-sup.right[1],
                   e=e, g=g, theta_over=theta_over, outline=geo.rotate(sec.outline, sup.pose))

    # ------------------------------------------------------------- output
    def describe(self):
        """The derived 2D body, side by side, as text."""
        rows = [("pivot [m] (from the centre of mass)", f"(-{self.b1:.6g}, -{self.h1:.6g})",
                 f"({self.b2:.6g}, -{self.h2:.6g})"),
                ("alpha [rad]", f"{self.alpha1:.6g}", f"{self.alpha2:.6g}"),
                ("R [m]", f"{self.R1:.6g}", f"{self.R2:.6g}"),
                ("I_O [kg m^2]", f"{self.inertia_about_pivot1:.6g}", f"{self.inertia_about_pivot2:.6g}"),
                ("p [rad/s]", f"{self.p1:.6g}", f"{self.p2:.6g}"),
                ("uplift g tan(alpha) [m/s^2]", f"{self.uplift_acceleration1:.6g}",
                 f"{self.uplift_acceleration2:.6g}"),
                ("restitution of the impact leaving it", f"{self.e12:.6g}", f"{self.e21:.6g}")]
        w = max(len(r[0]) for r in rows)
        lines = [f"RigidBody: mass {self.mass:.6g} kg, I_G {self.inertia:.6g} kg m^2, g {self.g:.6g} m/s^2, "
                 f"{'symmetric (runs as a RigidBlock)' if self.is_symmetric else 'asymmetric'}",
                 f"{'':{w}}  {'side 1 (left, theta < 0)':>26}  {'side 2 (right, theta > 0)':>26}"]
        lines += [f"{a:{w}}  {b:>26}  {c:>26}" for a, b, c in rows]
        lines.append(f"restitution: {'given e = %g' % self.e if self.e is not None else 'angular-momentum map'}; "
                     f"spectra refer to side {self.smaller_side} (alpha {self.alpha:.6g} rad); "
                     f"top {self.top}")
        return "\n".join(lines)

    def __str__(self):
        return self.describe()

    def plot(self, ax=None):
        """Draw the outline, the centre of mass and the two pivots (matplotlib);
        returns the Axes."""
        import matplotlib.pyplot as plt
        if ax is None:
            _fig, ax = plt.subplots()
        P = self.outline
        if P is None:
            (x1, y1), (x2, y2) = self.pivots
            P = np.array([(x1, y1), (x2, y2), (0.0, 0.0)])
        Q = np.vstack([P, P[:1]])
        ax.fill(Q[:, 0], Q[:, 1], color="0.85", zorder=1)
        ax.plot(Q[:, 0], Q[:, 1], color="0.2", lw=1.2, zorder=2, label="outline")
        ax.axhline(-0.5 * (self.h1 + self.h2), color="0.5", lw=0.8, ls="--", zorder=0)
        ax.plot([0.0], [0.0], marker="+", color="C3", ms=12, mew=2, ls="none", zorder=3,
                label="centre of mass")
        for k, (x, y) in enumerate(self.pivots, start=1):
            ax.plot([0.0, x], [0.0, y], color="C0", lw=0.8, zorder=2)
            ax.plot([x], [y], marker="o", color="C0", ls="none", zorder=3)
            alpha = self.alpha1 if k == 1 else self.alpha2
            ax.annotate(f"pivot {k}\nalpha{k} = {alpha:.3g} rad", (x, y), textcoords="offset points",
                        xytext=(-10 if k == 1 else 10, -28), ha="right" if k == 1 else "left", fontsize=8)
        ax.set_aspect("equal")
        ax.set_xlabel("x from the centre of mass [m]")
        ax.set_ylabel("y from the centre of mass [m]")
        ax.set_title("RigidBody" + (" (symmetric)" if self.is_symmetric else ""))
        return ax


def _mass(mass, density, measure, thickness=None, plate=True):
    """m [kg] from ``mass``, or from ``density`` times the volume: ``measure`` (an area [m^2]
    times ``thickness`` [m] for a plate, a volume [m^3] for a solid)."""
    if (mass is None) == (density is None):
        raise ValueError("give either mass [kg] or density [kg/m^3]" + (" with thickness [m]" if plate else "")
                         + ", not " + ("both" if mass is not None else "neither"))
    if mass is not None:
        if thickness is not None:
            raise ValueError("thickness goes with density; with mass give no thickness")
        return V.positive("mass", mass)
    V.positive("density", density)
    if not plate:
        return density * measure
    if thickness is None:
        raise ValueError("thickness [m] (out of the plane) is needed with density")
    return density * V.positive("thickness", thickness) * measure


#: A RigidBody's two base heights h1, h2 count as one level base within this relative tolerance
#: (a polygon's lowest facet gives them equal up to rounding).
LEVEL_BASE_RTOL = 1e-9


def level_base_height(body, needs, why):
    """h of a RigidBody with a level base (h1 = h2 to LEVEL_BASE_RTOL), else a ValueError saying
    what ``needs`` it and ``why``."""
    h1, h2 = body.h1, body.h2
    if not body.has_level_base:
        raise ValueError(f"h1 = {h1:.6g} m and h2 = {h2:.6g} m differ: {needs} a level base (h1 = h2; {why}). "
                         f"Pivots at different heights stand on a step, which the rocking model takes; on one "
                         f"ground plane the body rests turned: body.on_level_ground() gives it in that pose "
                         f"(on_level_ground = true in a scene's [body] table). A RigidBody from a polygon or a "
                         f"mesh rests on its lowest facet and has a level base")
    return 0.5 * (h1 + h2)
