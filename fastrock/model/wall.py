"""A rigid rear wall beside the block: one-sided rocking (docs: theory/wall).

References: Hogan (1992), *Proc. R. Soc. A* 439, 35-45 (d = 0);
Mennitti, Maiorano & Aversa (2021), one-sided rocking of rigid blocks next to
a wall (tall elastic wall, gaps of 1 and 10 cm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from fastrock import _validate as V


@dataclass(frozen=True)
class Wall:
    """A rigid vertical wall parallel to one face of a block or a RigidBody.

    Parameters
    ----------
    gap : float
        Clear gap d [m] between the block's face and the wall at rest, >= 0.
        ``gap=0`` is Hogan's one-sided rocking (the block rests against the
        wall and only rocks away from it, on the pivot away from the wall).
    side : {-1, +1}
        Side of the wall.  ``-1`` (default) puts it on the negative-theta
        side: a positive ground acceleration (which tips the block toward
        -theta; docs: theory, conventions) throws the block toward the wall.
    height : float, optional
        Wall height h_w [m], > 0.  None (default): taller than the block.
    restitution : float
        Wall restitution e_w in [0, 1]: a wall impact keeps the pivot and sets
        theta'+ = -e_w theta'-.  Default 1 (elastic, as Mennitti et al.).  With
        ``gap=0`` it is Hogan's r in theta'+ = -r theta'- (ground and wall
        impacts coincide, the pivot stays on the far corner).  Note that the
        small-gap limit of the d > 0 model is Hogan's map with r = e^2 e_w
        (a ground impact, a wall impact and a second ground impact in quick
        succession): pass ``restitution = e**2 * e_w`` at d = 0 for a model
        continuous in d (``e12 * e21 * e_w`` for an asymmetric RigidBody).
        Gaps with theta_w < 1e-7 rad run that limit (docs: guide/models/wall).
    friction : float
        Coulomb coefficient mu_w of the wall contact (static = kinetic),
        >= 0.  Default 0 (frictionless).  A positive value needs the contact
        model, i.e. ``friction=Friction(...)`` in the scene (``Friction(inf,
        lift_off="flight")`` for a pivot that never slips); the wall model
        (no ``friction=``) and the flexible body's keep a frictionless wall
        and refuse it.  In the contact model the wall friction acts while
        the block rests or slides on the wall (a block leaning on the wall,
        or wedged between ground and wall, holds while some wall force
        within the cone makes every contact force admissible; sliding along
        the wall costs mu_w N_w) and in wall impacts (Coulomb's cone for
        the wall impulse; restitution e_w: Poisson's rule in flight, plastic
        where it would add energy).  The face impact (flat into the wall)
        is not changed by it.

    Notes
    -----
    Outcomes: besides "safe", "mode1" and "mode2" (overturning away from the
    wall, or toward it when the wall is out of reach), "leaning": the block
    came to rest on the wall past its own instability (theta_w > alpha), or,
    after the excitation, is trapped there (past alpha toward the wall with
    too little energy to come back; with e_w = 1 it then bounces on the wall
    for ever).  Leaning is never decided early while the ground still shakes
    (a run cut short by ``duration`` reports the state at its end).

    The limit angle theta_w needs the block's half-height h, so the body must
    be built with :meth:`RigidBlock.rectangle` or
    :meth:`RigidBlock.from_inertia` (whose outline is taken as a rectangle of
    half-dimensions R sin(alpha), R cos(alpha)).  Ground impacts keep the
    body's Housner restitution e.  An asymmetric :class:`RigidBody` needs
    its outline: the face toward the wall is taken vertical above that side's
    pivot, up to the top of the outline (:meth:`RigidBody.wall_face_top`);
    it rocks with each side's alpha, p and impact map, the wall as above.
    A rounded top (``RigidBlock(top_radius=...)``, ``RigidBody(top="rounded",
    top_radius=...)``: the top corner on the wall side is a quarter circle of
    radius rho) touches the wall with its arc, later than the flat top's
    corner would (:meth:`limit_angle`); the impact map is the same.  The
    contact model (``friction=``, flight) takes it too: the arc rests,
    rolls, slides on and strikes the wall's face or a short wall's top
    edge (docs: theory/wall).

    Examples
    --------
    A wall 5 cm away on the side the block falls to catches it:

    >>> from fastrock import Pulse, RigidBlock, Wall, simulate
    >>> block = RigidBlock.rectangle(b=0.2, h=0.8)
    >>> pulse = Pulse(amplitude=0.4, frequency=1.5)
    >>> simulate(block, pulse).outcome
    'mode1'
    >>> run = simulate(block, pulse, wall=Wall(0.05, side=+1))
    >>> run.outcome, run.metrics["wall_impacts"]
    ('safe', 2)
    """

    gap: float
    side: int = -1
    height: float | None = None
    restitution: float = 1.0
    # a field added after studies were hashed: left out of a study's hash at its default
    friction: float = field(default=0.0, metadata={"hash_default": True})

    def __post_init__(self):
        object.__setattr__(self, "gap", V.non_negative("gap", self.gap))
        if isinstance(self.side, bool):
            raise ValueError(f"side must be +1 or -1, got {self.side!r}")
        object.__setattr__(self, "side", V.sign("side", self.side))
        if self.height is not None:
            object.__setattr__(self, "height", V.positive("height", self.height))
        object.__setattr__(self, "restitution",
                           V.in_closed("restitution", self.restitution, 0.0, 1.0))
        object.__setattr__(self, "friction", V.non_negative("friction", self.friction))

    @property
    def toward_sign(self):
        """Pulse sign whose first half-cycle throws the block toward the wall."""
        return -self.side

    def _face_height(self, body):
        """Height [m] of the body's face toward the wall above its pivot: 2h for a block, 2H for a
        flexible body (the 2B x 2H box turning with the base), h + the face's top for an
        asymmetric RigidBody (:meth:`RigidBody.wall_face_top`)."""
        kind = getattr(body, "kind", "")
        if kind == "flexible":
            return 2.0 * float(body.H)
        if kind == "rigid_body" and not body.is_symmetric:
            h = body.h2 if self.side > 0 else body.h1
            return h + body.wall_face_top(self.side)
        if kind == "rigid_body":
            body = body.to_block()
        h = getattr(body, "h", None)
        if h is None:
            raise ValueError("a wall needs the block's half-height h to find the contact angle: build "
                             "the body with RigidBlock.rectangle(b, h) or RigidBlock.from_inertia(...)")
        return 2.0 * float(h)

    @staticmethod
    def _top_radius(body, face):
        """Radius rho [m] of the body's rounded top corner on the wall side (0: a flat top)."""
        rho = getattr(body, "top_radius", None)         # set only with a rounded top (validated)
        if rho is None:
            return 0.0
        if rho > face:
            raise ValueError(f"top_radius = {rho:.6g} m is larger than the height of the body's face toward the "
                             f"wall ({face:.6g} m): the rounded corner must fit on that face")
        return float(rho)

    def top_radius(self, body):
        """Radius rho [m] of the body's rounded top corner on the wall side, checked against the
        height of its face toward the wall (0: a flat top)."""
        if getattr(body, "top_radius", None) is None:
            return 0.0
        return self._top_radius(body, self._face_height(body))

    def _geometry(self, body):
        """(branch, theta_w) of :meth:`contact` and :meth:`limit_angle`."""
        d = self.gap
        if d == 0.0:
            return "hogan", 0.0
        face = self._face_height(body)
        if d >= face:
            return "none", math.inf
        rho = self._top_radius(body, face)
        a = face - rho                      # the straight part of the face, from the pivot up
        # the arc's centre is at (-rho, a) from the pivot (x toward the wall); turned by theta
        # its front point is at x = -rho cos(theta) + a sin(theta) + rho, y = rho sin(theta)
        # + a cos(theta), both increasing in theta up to pi/2
        c = math.hypot(a, rho)
        theta = math.atan2(rho, a) + math.asin((d - rho) / c)
        if self.height is None or self.height >= rho * math.sin(theta) + a * math.cos(theta):
            return "tall", theta
        # that point passes above a short wall: the face or the arc touches the wall's top edge
        # E = (d, h_w), with the body's point at E's distance from the pivot (monotone along face,
        # arc and top, so unique; it lies below that front point, hence on the face or the arc)
        r = math.hypot(d, self.height)
        if r <= a:
            return "short", math.atan2(d, self.height)
        phi = math.atan2(rho, a) + math.asin((r * r - a * a - 2.0 * rho * rho) / (2.0 * rho * c))
        x, y = -rho + rho * math.cos(phi), a + rho * math.sin(phi)
        return "short", math.atan2(d, self.height) - math.atan2(x, y)

    def contact(self, body):
        """Which geometry branch sets the limit angle: "hogan" (d = 0),
        "tall" (the top corner on the wall side touches the wall), "short"
        (the face, or a rounded top's arc, touches the wall's top edge) or
        "none" (d >= the face height: never reached)."""
        return self._geometry(body)[0]

    def limit_angle(self, body):
        """Rotation theta_w [rad] toward the wall at which the block touches it.

        Tilting toward the wall about the near bottom corner, the face
        toward the wall (height 2h for a block) rotates about its bottom
        point.  Tall wall (h_w >= 2h cos theta_w): the top corner touches
        it, sin(theta_w) = d / (2h).  Short wall (h_w < 2h cos theta_w, i.e.
        d^2 + h_w^2 < 4h^2): the face touches the wall's top edge,
        tan(theta_w) = d / h_w.  Exactly one branch is admissible (they meet
        at d^2 + h_w^2 = 4h^2).  If d >= 2h the block cannot reach the wall
        before lying flat: ``math.inf`` is returned and the run is the
        two-sided one.

        A rounded top corner of radius rho on a face of height H: the arc
        touches a tall wall when -rho cos(theta) + (H - rho) sin(theta) +
        rho = d; a short wall's top edge at distance r = sqrt(d^2 + h_w^2)
        from the pivot is touched by the face (r <= H - rho, as above) or by
        the arc's point at that distance.  rho = 0 is the flat top.
        """
        return self._geometry(body)[1]

    def fill_par(self, par, body):
        """Write the wall entries of the rigid kernel's parameter vector."""
        from fastrock.kernels import layout as K
        if self.friction != 0.0:
            raise ValueError("wall: friction > 0 at the wall contact needs the contact model: add "
                             "friction=Friction(mu) (or Friction(inf, lift_off='flight') for a pivot "
                             "that never slips); the wall model's wall is frictionless")
        par[K.P_WALL_SIDE] = float(self.side)
        par[K.P_THETA_W] = self.limit_angle(body)
        par[K.P_E_W] = self.restitution
        par[K.P_HOGAN] = 1.0 if self.gap == 0.0 else 0.0
        return par

    def check_initial(self, theta0, body):
        """Reject an initial rotation that penetrates the wall."""
        tw = self.limit_angle(body)
        if self.side * theta0 > tw:
            raise ValueError(f"theta0 = {theta0!r} penetrates the wall: with the wall on side {self.side:+d} "
                             f"the block must satisfy side*theta0 <= theta_w = {tw:.6g} rad")
