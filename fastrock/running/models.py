"""Parameter vectors of the rigid, wall, friction and flexible models, built by the entries of
:mod:`fastrock.running.registry` (whose :func:`~fastrock.running.registry.select` is the
scene-to-kernel choice).

A kernel module is imported only when a scene needs it, so a rigid scene
never imports (let alone compiles) the wall, flexible or friction kernels.
"""
from __future__ import annotations

import numpy as np

from fastrock.model.bodies import IMPACT_MAPS, FlexibleBody, RigidBlock
from fastrock.model.friction import LIFT_OFF
from fastrock.model.rigid_body import level_base_height


def rigid_par(body: RigidBlock):
    from fastrock.kernels import layout as K
    par = np.zeros(K.N_PAR_RIGID)
    par[K.P_ALPHA] = body.alpha
    par[K.P_P] = body.p
    par[K.P_E] = body.e
    par[K.P_G] = body.g
    par[K.P_THETA_OVER] = body.theta_over
    return par


def rigid_body_par(body):
    """Parameters of an asymmetric RigidBody (kernels/rigid.py, the rigid_body entries): the rigid
    entries hold side 2 (the right pivot, theta > 0, pivot +1) and the impact leaving it, the
    P_*_NEG entries side 1 (pivot -1)."""
    from fastrock.kernels import layout as K
    par = np.zeros(K.N_PAR_RIGID_BODY)
    par[K.P_ALPHA] = body.alpha2
    par[K.P_P] = body.p2
    par[K.P_E] = body.e21
    par[K.P_G] = body.g
    par[K.P_THETA_OVER] = body.theta_over
    par[K.P_ALPHA_NEG] = body.alpha1
    par[K.P_P_NEG] = body.p1
    par[K.P_E_NEG] = body.e12
    par[K.P_IO_RATIO] = body.inertia_about_pivot1 / body.inertia_about_pivot2
    return par


def wall_par(body, wall):
    """Parameters of the wall model (kernels/wall.py): both sides' alpha, p and ground restitution
    as in ``rigid_body_par`` (a RigidBlock fills both with its own), and the wall entries; the
    contact angle from the body's wall-side face (:meth:`Wall.limit_angle`)."""
    from fastrock.kernels import layout as K
    from fastrock.model.rigid_body import RigidBody
    if isinstance(body, RigidBody):
        level_base_height(body, "wall= needs", "the wall-side face stands vertical above its pivot in "
                          "the rest pose on both pivots, as the outline gives it")
        par = rigid_body_par(body)
    else:
        par = np.zeros(K.N_PAR_WALL)
        par[: K.N_PAR_RIGID] = rigid_par(body)
        par[K.P_ALPHA_NEG] = par[K.P_ALPHA]
        par[K.P_P_NEG] = par[K.P_P]
        par[K.P_E_NEG] = par[K.P_E]
        par[K.P_IO_RATIO] = 1.0
    return wall.fill_par(par, body)


def flexible_par(body: FlexibleBody, sliding=False, n_par=None):
    from fastrock.kernels import layout as K
    par = np.zeros(n_par or K.N_PAR_FLEXIBLE)
    par[K.F_ALPHA] = body.alpha
    par[K.F_P] = body.p
    par[K.F_E] = body.e
    par[K.F_G] = body.g
    par[K.F_THETA_OVER] = body.theta_over
    par[K.F_B] = body.B
    par[K.F_H] = body.H
    par[K.F_WN] = body.omega_n
    par[K.F_ZETA] = body.zeta
    par[K.F_IM] = body.rotary_inertia_ratio * body.R0 ** 2
    par[K.F_IMPACT] = IMPACT_MAPS[body.impact]
    mb = body.base_mass(sliding)
    par[K.F_MB] = mb
    par[K.F_IB] = mb * body.B ** 2 / 3.0
    par[K.F_HB] = body.base_cm_height
    return par


def flexible_friction_par(body: FlexibleBody, friction):
    from fastrock.kernels import layout as K
    if body.impact != "full-contact":
        raise ValueError("friction= with a FlexibleBody needs impact='full-contact' (the slide-rock impact "
                         "rule of the docs' theory page 'Flexible body with a sliding base')")
    if body.base_mass(sliding=True) <= 0.0:
        raise ValueError("base_mass_ratio must be > 0 with sliding on: with a massless base the sliding "
                         "problem is a differential-algebraic system (docs, theory: 'Flexible body with a "
                         "sliding base', 'Why the base needs a mass'); use e.g. 0.1")
    par = flexible_par(body, sliding=True, n_par=K.N_PAR_FLEXIBLE_FRICTION)
    par[K.F_MU_S] = friction.mu_s
    par[K.F_MU_K] = friction.mu_k
    par[K.F_LIFT_OFF] = LIFT_OFF[friction.lift_off]
    return par


def flexible_flight_par(body: FlexibleBody, friction):
    """Parameters of the flexible body with friction and free flight (kernels/flexible_flight.py):
    the flexible-friction vector with lift_off = "flight"; mu_s may be inf (it never slips)."""
    from fastrock.kernels import layout as K
    if friction.lift_off != "flight":
        raise ValueError("the flexible_flight model needs Friction(lift_off='flight')")
    par = flexible_friction_par(body, friction)
    return par[: K.N_PAR_FLEXIBLE_FLIGHT].copy()


def flexible_wall_par(body: FlexibleBody, wall):
    """Parameters of the flexible body against a wall (kernels/flexible_wall.py)."""
    from fastrock.kernels import layout as K
    kind = wall.contact(body)
    if kind == "hogan":
        raise ValueError("wall: gap = 0 (Hogan's one-sided rocking) is available for RigidBlock and RigidBody only; "
                         "a FlexibleBody needs gap > 0")
    if wall.friction != 0.0:
        raise ValueError("wall: friction > 0 at the wall contact is not modelled yet (the wall is "
                         "frictionless)")
    par = flexible_par(body, n_par=K.N_PAR_FLEXIBLE_WALL)
    par[K.FW_WALL_SIDE] = float(wall.side)
    par[K.FW_THETA_W] = wall.limit_angle(body)
    par[K.FW_E_W] = wall.restitution
    return par


def rigid_friction_par(body: RigidBlock, friction):
    from fastrock.kernels import layout as K
    if friction.lift_off != "stop":
        raise ValueError("lift_off='hold' is available for FlexibleBody only; a rigid block with friction "
                         "stops with outcome 'flight' when N reaches 0")
    par = np.zeros(K.N_PAR_FRICTION)
    par[: len(rigid_par(body))] = rigid_par(body)
    b, h = _rectangle(body)
    R2 = b * b + h * h
    par[K.Q_B] = b
    par[K.Q_H] = h
    par[K.Q_IG] = body.g * np.sqrt(R2) / body.p ** 2 - R2
    par[K.Q_MU_S] = friction.mu_s
    par[K.Q_MU_K] = friction.mu_k
    return par


def _rectangle(body):
    """(b, h): half-width and CM height of the block (a rectangle of the given alpha and p
    when it was built from them)."""
    if body.b is not None and body.h is not None:
        return body.b, body.h
    R = 3.0 * body.g / (4.0 * body.p ** 2)
    return R * np.sin(body.alpha), R * np.cos(body.alpha)


def contact_par(body, friction, wall=None):
    """Parameters of the contact model (kernels/contact.py): a RigidBlock, or an asymmetric
    RigidBody on a level base, whose base corners touch the ground with ``friction`` (mu_s may be
    inf), and a wall (its Coulomb coefficient ``wall.friction``, 0: frictionless), tall or lower than
    the body's wall-side top corner (its top edge touched by the body's face), the top corner on the
    wall side square or rounded (``top_radius``: the arc's radius in C_TOP_R)."""
    from fastrock.kernels import layout as K
    from fastrock.model.rigid_body import RigidBody
    par = np.zeros(K.N_PAR_CONTACT)
    if isinstance(body, RigidBody):
        _contact_body_geometry(par, body, wall)
    else:
        par[: K.N_PAR_RIGID] = rigid_par(body)
        b, h = _rectangle(body)
        R2 = b * b + h * h
        par[K.C_B1] = par[K.C_B2] = b
        par[K.C_H1] = par[K.C_H2] = h
        par[K.C_HT1] = par[K.C_HT2] = h
        par[K.C_IG] = body.g * np.sqrt(R2) / body.p ** 2 - R2
        par[K.C_E_NEG] = par[K.P_E]
        par[K.C_ALPHA_NEG] = par[K.P_ALPHA]
    par[K.C_MU_S] = friction.mu_s
    par[K.C_MU_K] = friction.mu_k
    par[K.C_GAP] = np.inf
    if wall is not None:
        from fastrock.kernels.layout import C_H_WALL
        top = par[K.C_HT2] if wall.side > 0 else par[K.C_HT1]
        if wall.height is not None and wall.height < par[K.C_H1] + top:
            # lower than the wall-side top corner: its top edge is a contact feature
            par[C_H_WALL] = wall.height
        par[K.P_WALL_SIDE] = float(wall.side)
        par[K.P_E_W] = wall.restitution
        par[K.C_GAP] = wall.gap
        par[K.C_MU_W] = wall.friction
        # a rounded wall-side top corner (0: the square corner); its radius fits the wall-side face
        par[K.C_TOP_R] = wall.top_radius(body)
    return par


def _contact_body_geometry(par, body, wall):
    """The body entries of the contact model for an asymmetric RigidBody: each pivot its own
    half-width, alpha and impact restitution (P_* for the right pivot as in ``rigid_body_par``,
    C_*_NEG for the left).  The base must be level (h1 = h2).  With a wall, the wall-side face is
    taken vertical above its pivot, up to the top of the outline."""
    from fastrock.kernels import layout as K
    h = level_base_height(body, "friction=, wall= and flight need",
                          "the contact model's flat contact and sliding are on one line through both pivots")
    par[K.P_ALPHA] = body.alpha2
    par[K.P_P] = body.p2
    par[K.P_E] = body.e21
    par[K.P_G] = body.g
    par[K.P_THETA_OVER] = body.theta_over
    par[K.C_ALPHA_NEG] = body.alpha1
    par[K.C_E_NEG] = body.e12
    par[K.C_B1] = body.b1
    par[K.C_B2] = body.b2
    par[K.C_H1] = par[K.C_H2] = h
    par[K.C_IG] = body.inertia / body.mass
    par[K.C_HT1] = par[K.C_HT2] = h
    if wall is not None:
        par[K.C_HT1] = par[K.C_HT2] = body.wall_face_top(wall.side)
    return par
