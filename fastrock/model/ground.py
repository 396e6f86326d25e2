"""Ground: level or sloping (issue #17).

On sloping ground every model works in the slope's frame: x along the
surface, positive downhill, z normal to it.  Gravity then has a component
g sin(phi) along the surface, which pushes the body downhill at every
instant, and the normal component g cos(phi) is what holds it down.  The
uplift and slip thresholds therefore differ downhill and uphill, and a
block with Coulomb friction slides one way in all but violent shaking:
Newmark's rigid sliding block is the special case of a stout block.
"""
import math
from dataclasses import dataclass

from .. import _validate as V
from ..constants import G_STANDARD
from ..kernels import layout as L

DIRECTIONS = ("horizontal", "slope")
#: models that never leave the ground (no flight event without a vertical channel)
GROUNDED_MODELS = ("rigid", "rigid_body")


@dataclass(frozen=True)
class Ground:
    """The surface the body stands on.

    Parameters
    ----------
    slope : float
        Inclination phi of the surface [rad], in [0, pi/2).  The surface
        descends toward +x: positive slip and a positive rotation sense of
        the body follow the downhill direction.  0 (the default) is level
        ground, bit for bit the same results as giving no ground at all.
    direction : {"horizontal", "slope"}
        How the excitation's channels are applied.  "horizontal" (default):
        the horizontal channel is horizontal and the vertical one vertical,
        as a free-field record is; "slope": the horizontal channel acts
        along the surface and the vertical one normal to it (the usual
        reading of a Newmark sliding-block analysis, where the record is
        the acceleration parallel to the slope).

    Examples
    --------
    >>> import math
    >>> from fastrock import Ground
    >>> Ground(slope=math.radians(10)).slope_deg
    10.0
    """

    slope: float = 0.0
    direction: str = "horizontal"

    def __post_init__(self):
        phi = V.finite("slope", self.slope)
        if not 0.0 <= phi < 0.5 * math.pi:
            raise ValueError(f"slope must lie in [0, pi/2) rad, got {self.slope!r}")
        object.__setattr__(self, "slope", phi)
        V.choice("direction", self.direction, DIRECTIONS)

    @property
    def slope_deg(self):
        """The inclination in degrees."""
        return math.degrees(self.slope)

    @property
    def is_level(self):
        return self.slope == 0.0

    def fill_header(self, hdr, g=G_STANDARD):
        """Write the slope block of a kernel excitation header (nothing on
        level ground, so level runs see the header they always saw)."""
        if self.is_level:
            return
        phi = self.slope
        hdr[L.S_ON] = 1.0
        if self.direction == "horizontal":
            hdr[L.S_CM] = math.cos(phi)
            hdr[L.S_SM] = math.sin(phi)
        else:
            hdr[L.S_CM] = 1.0
            hdr[L.S_SM] = 0.0
        hdr[L.S_G_T] = g * math.sin(phi)
        hdr[L.S_G_N] = -2.0 * g * math.sin(0.5 * phi) ** 2

    def check_scene(self, body, *, friction=None, flexible=False, foundation=None):
        """Refuse a scene that this slope cannot hold at rest, or that the
        models do not run on a slope yet, with an error naming ``slope``.  A
        block on a flexible foundation is checked again by its foundation's
        ``initial_state`` (a stable static tilt with every spring loaded)."""
        if self.is_level:
            return
        where = f"slope = {self.slope:.6g} rad ({self.slope_deg:.4g} deg)"
        demand = self.static_demand()
        if flexible:
            sliding = friction is not None and friction.sliding_possible
            margin = self.flexible_rest_margin(body, body.base_mass(sliding))
            if margin <= 0.0:
                raise ValueError(f"{where}: the flexible body cannot stand on it: at its static deflection "
                                 f"u = {self.static_deflection(body):.4g} m the column's moment lifts the "
                                 f"downhill corner (uplift margin {margin:.4g} m^2/s^2 per unit mass)")
        else:
            alpha = getattr(body, "alpha2", body.alpha)     # the downhill (+x) side of an asymmetric body
            if demand >= math.tan(alpha):
                raise ValueError(f"{where}: the block cannot stand on it: tan(slope) = {demand:.4g} >= "
                                 f"tan(alpha) = {math.tan(alpha):.4g} of its downhill side (its centre of mass "
                                 "lies beyond the downhill corner)")
        if friction is not None and demand >= friction.mu_s:
            raise ValueError(f"{where}: steeper than friction can hold at rest: tan(slope) = {demand:.4g} >= "
                             f"mu_s = {friction.mu_s:g}")

    def check_lift_off(self, body, peak_horizontal, model=None, vertical=None):
        """The two-sided rocking models (``GROUNDED_MODELS``; ``model`` None:
        check whatever the model) assume the ground pushes: on a slope the
        normal gravity g cos(phi) less the normal part of the horizontal
        shaking, a_h sin(phi), must stay positive.  Refuse stronger shaking
        (the contact model, ``Friction(..., lift_off="flight")``, follows
        the body into flight).  With a vertical channel their flight event
        watches G' itself."""
        if (self.is_level or self.direction == "slope" or vertical is not None
                or (model is not None and model not in GROUNDED_MODELS)):
            return
        limit = body.g * math.cos(self.slope) / math.sin(self.slope)
        if peak_horizontal >= limit:
            raise ValueError(f"slope = {self.slope:.6g} rad: a horizontal peak of {peak_horizontal:.4g} m/s^2 "
                             f">= g / tan(slope) = {limit:.4g} m/s^2 lifts the block off the incline; run it "
                             "with Friction(..., lift_off='flight') (the contact model follows free flight)")

    def static_deflection(self, body):
        """The flexible column's static deflection downhill [m], g sin(phi) / omega_n^2: where it
        rests in full contact on the slope (every flexible run on a slope starts there)."""
        return body.g * math.sin(self.slope) / body.omega_n ** 2

    def flexible_rest_margin(self, body, base_mass_ratio):
        """The uplift test of the flexible body at rest on the slope, about its downhill corner, per
        unit mass [m^2/s^2]: G (B - u) + m_b/m (G B + a_g h_b) - H w^2 u with a_g = -g sin(phi),
        G = g cos(phi) and u the static deflection (> 0: it stands)."""
        g = body.g
        G = g * math.cos(self.slope)
        ag = -g * math.sin(self.slope)
        u = self.static_deflection(body)
        B, H = body.B, body.H
        return (G * (B - u) + base_mass_ratio * (G * B + ag * body.base_cm_height)
                - H * body.omega_n ** 2 * u)

    def initial_state(self, body, spec, y0):
        """``y0`` with a flexible column at its static deflection on the slope (in place)."""
        if "u" in spec.state_names:
            y0[spec.state_names.index("u")] = self.static_deflection(body)
        return y0

    def static_demand(self):
        """tan(phi): the ratio of the along-slope to the normal component of
        gravity, which friction (mu_s) and the body's downhill slenderness
        (tan alpha) must exceed for the body to stand at rest."""
        return math.tan(self.slope)


def as_ground(ground):
    """None or a Ground; anything else is refused naming the field."""
    if ground is None or isinstance(ground, Ground):
        return None if ground is None or ground.is_level else ground
    raise TypeError(f"ground: expected fastrock.Ground or None, got {type(ground).__name__}")
