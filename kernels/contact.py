"""Contact core: a planar rigid body with a set of contact points, the
contact mode picked by the generic mode solve (physics.md 4.2, 4.6; issue
#13 item 5).  First version: rigid block on rigid ground with Coulomb
friction and free flight (stage 1), and a rear wall touched by the top
corner on its side (stage 2).

Body (per unit mass)
--------------------
Centroidal i_G = I_G / M (par[C_IG]); contact points, body frame, relative
to the centre of mass (CM):

    0  left base corner   (-b1, -h1)
    1  right base corner  ( b2, -h2)
    2  wall corner: the top corner on the wall side w, (w b_w, ht_w), with
       b_w = b2 (w = +1) or b1 (w = -1), ht_w = par[C_HT2] or par[C_HT1];
       beside a wall lower than it (par[C_H_WALL] > 0), the body's point
       nearest the wall's top edge E, a fixed point: on the wall-side face
       (E against the face, whose normal turns with the body), the top face
       or the top corner (``wall_geom``), so it moves over the body; a
       rounded top corner (par[C_TOP_R] = rho > 0): the arc's point
       nearest the wall, its centre C fixed in the body (``body_point``,
       ``arc_front``; docs: theory/wall)

Body-frame (a, c) maps to world (a cos th + c sin th, -a sin th + c cos th)
(physics.md 0).  Gravity is the vector (0, -G), G = g + a_v, written in one
place only (``free_acc``); the horizontal ground acceleration enters as the
d'Alembert force -a_g.  The base is level (h1 = h2: the flat configuration
and the rocking ground-impact map ``corner_impact`` assume it); the two
sides may differ in width (b1 != b2, an asymmetric body, issue #17), each
pivot with its own alpha and restitution.

State
-----
``y = (theta, theta', x, x', z, z')``: rotation [rad] and the position
[m] of the base reference point P relative to the ground: P is the body
point (0, -hm) below the CM, hm = (h1 + h2) / 2 (for the symmetric block
the base midpoint); x = 0, z = 0 at rest at the origin.  The CM is at
(x + hm sin th, z + hm cos th).  Every phase integrates all six entries:
in contact modes the accelerations come from the mode solve, so they are
consistent with the contact constraints (the corner stays on the ground up
to the integration error); z, z' (and x' for a sticking contact) are
re-projected onto the active constraints at every transition, so no
constraint drift builds up over phases.  No event depends on x.  In flight
x'' = -a_g - hm(...), i.e. the CM follows x_G'' = -a_g, y_G'' = -G,
theta'' = 0.

Discrete state: D_MODE (REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT,
WALL_REST), D_PIVOT s (rocking corner; 0 left = -1, 1 right = +1),
D_STATIC, D_SLIP_DIR sigma (ground slip direction), and the state of each
contact point in disc[D_CS0 + k]: CS_OPEN, CS_STICK, CS_SLIP_P
(sigma = +1), CS_SLIP_N (sigma = -1), CS_FREE (frictionless: normal force
only).  The wall contact (k = 2) is the top corner (CS_FREE) or the
wall-side base corner (CS_WALL_BASE) with a normal force only, or, on a
frictional wall (mu_w > 0), slipping along it (CS_TOP_SLIP_P/N,
CS_BASE_SLIP_P/N: friction -mu_w sigma_w N_w along the tangent (0, 1)) or
sticking (CS_TOP_STICK, CS_BASE_STICK: impulse solves only).

Wall friction (mu_w = par[C_MU_W] > 0; mu_w = 0 runs the frictionless
code unchanged).  With a base corner and the wall contact both closed the
body has one degree of freedom: a sticking pivot holds the wall point
too (a static phase whose wall force is statically indeterminate: it
holds while some F_w, |F_w| <= mu_w N_w, makes every force admissible,
``wall_stick_lp``), and a slipping pivot slips the wall point with it (the
ladders, ``wall_ladder``: both directions from the mode solve, both stop
together).  Wall impacts: ``wall_pivot_impact_fr`` (pivot on the ground)
and ``point_impulse`` (in flight: Routh with Poisson's restitution e_w,
plastic where that would add energy).  The face impact is unchanged (the
block ends flat: the wall's vertical impulse only shares the ground's).

Mode solve (``solve_contacts``)
-------------------------------
Unknowns: the contact forces of the closed contacts (a normal force N_k
per contact, a friction force F_k per sticking contact; a slipping contact
has F_k = -mu_k sigma_k N_k).  Equations: one row per constraint (normal
acceleration of a closed contact 0; tangential acceleration of a sticking
one 0), with the CM and rotation accelerations eliminated through
M a = f: a small dense system (<= 6 x 6, Gaussian elimination with partial
pivoting), then the admissibility checks (N >= 0, |F| <= mu_s N, rocking
away from the ground, slip not reversed).  The same routine solves the
impulse problem of a landing (velocities instead of accelerations).

Modes and transitions
---------------------
REST (static phase, ended by ``static_margin``), SLIDE, ROCK, SLIDE_ROCK,
FLIGHT.  Flight starts when the normal force of the active contact(s)
reaches 0 (event K_LIFT) and ends with a landing at the corner that
reaches the ground first moving down (K_LAND0, K_LAND1): plastic normal
impact with Coulomb friction (stick if |L_t| <= mu_s L_n, else Routh's
incremental slipping impact), flat two-point landing when the other
corner is on the ground and would penetrate (or reaches it together with
the landing corner).  In flight, wall impacts that chatter (closer than
eps_t, or a rebound below eps_omega times the size) close the wall
contact (``close_wall_in_flight``): the flight goes on with it closed
(mode solve, both base corners open) until the wall's force reaches 0
(K_WALL, K_WALL_BASE) or a landing (at zero speed with the top corner's
contact closed on a frictionless wall, one plastic impact at both
contacts, ``landing_at_wall``); the face reaching the wall in flight
stops turning and, pushed, slides down it (face flight, ended by the push
reaching 0 or the flat landing).  Ground impacts while rocking
(theta crosses 0) use the map of kernels/friction.py with the sides apart
(``corner_impact``: restitution e of the impact, algebraic slip rule,
Routh's method where it fails), so mu = inf reproduces kernels/rigid.py
(its rigid_body entries for b1 != b2) and finite mu kernels/friction.py.
Gap 0 (C_GAP = 0, the face on the wall at the start: face rest): back at
theta = 0 on the far corner the base corner meets ground and wall
together, Hogan's impact (``hogan_impact``: pivot kept, theta'+ = -e_w
theta'-), so mu = inf reproduces kernels/wall.py at gap 0.  After every
impact the mode is picked again.  Stick-slip and impact chatter end by the
rest rule (O_EPS_OMEGA, O_EPS_T) as in kernels/friction.py.

Events (g > 0 admissible; inactive ones return inf)
---------------------------------------------------
  0 K_IMPACT      s theta                 ROCK, SLIDE_ROCK
  1 K_OVERTURN    theta_over - s theta    (FLIGHT: theta_over - |theta|)
  2 K_SLIP        mu_s N - |F|            ROCK (FLIGHT, wall point sticking
                                          on a frictional wall: mu_w N_w - |F_w|)
  3 K_STICK       sigma v_t               SLIDE, SLIDE_ROCK (FLIGHT, wall
                                          point slipping: sigma_w v_tw)
  4 K_LIFT        N (SLIDE: min N_k)      contact modes
  5 K_PEAK        s theta'                observer
  6 K_PASS_ALPHA  alpha - s theta         observer (FLIGHT: alpha - |theta|)
  7 K_LAND0       height of corner 0 while it moves down (inf otherwise)
  8 K_LAND1       height of corner 1 while it moves down
  9 K_APEX        vertical CM velocity    FLIGHT observer (jump height)
 10 K_WALL        wall gap of the wall corner while it approaches (closed
                  in a ladder or in flight: the wall's force)
 11 K_WALL_BASE   the same for the wall-side base corner (face flight: the
                  push toward the wall, -w a_g)

Parameters (``par``, N_PAR entries)
-----------------------------------
 0-4 as kernels/rigid.py: P_ALPHA, P_P, P_E (ground restitution e),
     P_G, P_THETA_OVER (so rigid.overturned etc. apply); as in its
     rigid_body entries P_ALPHA and P_E belong to the right pivot (+1:
     its alpha, the impact leaving it), C_ALPHA_NEG, C_E_NEG to the left
 5   P_WALL_SIDE w = +-1 (kernels/rigid.py index)
 7   P_E_W wall restitution e_w (kernels/rigid.py index)
 10  C_B1  m, half-width left of the CM  (= friction Q_B)
 11  C_H1  m, CM height above the left corner (= friction Q_H)
 12  C_IG  m^2, I_G / M                  (= friction Q_IG)
 13  C_MU_S static friction (inf allowed) (= friction Q_MU_S)
 14  C_MU_K kinetic friction              (= friction Q_MU_K)
 15  C_B2  m, half-width right of the CM
 16  C_H2  m, CM height above the right corner
 17  C_GAP m, wall gap d (inf or nan: no wall)
 18  C_MU_W wall friction mu_w (0: frictionless; static = kinetic)
 19  C_HT1 m, height of the top-left corner above the CM
 20  C_HT2 m, height of the top-right corner above the CM
 21  C_E_NEG     restitution of a ground impact from pivot -1 onto +1
 22  C_ALPHA_NEG rad, alpha of the left pivot
 23  C_H_WALL    m, height of a wall lower than the wall-side top corner
                 (0: a tall wall)
 24  C_TOP_R     m, radius rho of a rounded wall-side top corner (0: the
                 square corner)
A friction parameter vector (kernels/friction.py) extended to N_PAR with
C_B2 = Q_B, C_H2 = Q_H, C_E_NEG = P_E, C_ALPHA_NEG = P_ALPHA is a valid
contact parameter vector.

Metrics
-------
The layout metrics (max |theta|, impacts, times, M_MAX_SLIDE,
M_RESIDUAL_SLIDE, M_T_SLIDE, M_T_SLIDE_ROCK, M_T_ROCK, M_T_CONTACT (REST
and SLIDE), M_N_STICK_SLIP, wall impacts), plus, in slots the rigid
friction model does not use:
  M_N_FLIGHTS   = M_N_LIFT_OFF (27)  number of flights
  M_T_FLIGHT    = M_T_UNLOADED (26)  s, time in flight
  M_MAX_JUMP    = 31                 m, largest rise of the CM above its
                                     rest height during a flight
Landings count as ground impacts (M_IMPACTS).  The slide is the horizontal
displacement of the active base contact from its rest position (of x at
rest), tracked in contact modes only.
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import excitation_end, ground
from .friction import kinetic as fr_kinetic
from .friction import routh_general
from .hybrid import (check_energy, elastic_below_resolution, init_metrics,
                     integrate_hybrid, log_event, sweep_rows)
from .layout import (D_MODE, D_PIVOT, D_SLIP_DIR, D_STATIC, D_WALL_REST,
                     EV_CONTACT, EV_FLIGHT, EV_IMPACT, EV_REST, EV_SLIP,
                     EV_STICK, EV_UPLIFT, EV_WALL_IMPACT, EV_WALL_RELEASE,
                     EV_WALL_REST, FAIL_FACE_CONTACT, FAIL_INCONSISTENT, LEANING, M_IMPACTS,
                     M_MAX_SLIDE, M_N_STICK_SLIP,
                     M_RESIDUAL_SLIDE, M_T_CONTACT, M_T_LAST_IMPACT, M_T_PREV,
                     M_T_ROCK, M_T_SLIDE, M_T_SLIDE_ROCK,
                     M_T_UPLIFT, M_WALL_IMPACTS, MODE_FLIGHT, MODE_REST,
                     MODE_ROCK, MODE_SLIDE, MODE_SLIDE_ROCK, MODE_WALL_REST,
                     N_DISC, N_MET, O_EPS_OMEGA, O_EPS_T, O_T0, RUNNING,
                     SAFE_MOVING, SAFE_NO_UPLIFT, SAFE_REST)
from .rigid import (P_ALPHA, P_E, P_E_W, P_G, P_THETA_OVER, P_WALL_SIDE,
                    UPLIFT_RTOL, initial_pivot, overturned, passed_alpha,
                    track_rotation)

# ---- parameters and flight metrics: kernels/layout.py ----------------------
from .layout import (C_ALPHA_NEG, C_B1, C_B2, C_E_NEG, C_GAP, C_H1, C_H_WALL,  # noqa: E402,F401
                     C_H2, C_HT1, C_HT2, C_IG, C_MU_K, C_MU_S, C_MU_W, C_TOP_R,
                     M_MAX_JUMP, M_N_FLIGHTS,
                     M_T_FLIGHT, N_PAR_CONTACT as N_PAR)
N_STATE = 6
assert M_MAX_JUMP < N_MET
# the feature of a short wall's contact (``wall_geom``)
WG_CORNER = 0     # the top corner against the wall's face (below E)
WG_EDGE = 1       # E against the body's wall-side face
WG_VERTEX = 2     # the top corner against E itself (the body above E)
WG_TOP = 3        # E against the body's top face (the body over the wall)
WG_BOTTOM = 4     # E against the body's bottom face (the base over the wall)
WG_BASE = 5       # the wall-side base corner against E itself

# ---- discrete state: one contact state per contact point -------------------
D_CS0 = 5
D_CS1 = 6
D_CS2 = 7
assert D_CS2 < N_DISC
CS_OPEN = 0
CS_STICK = 1
CS_SLIP_P = 2
CS_SLIP_N = 3
CS_FREE = 4       # frictionless: normal force only
# the wall contact (slot 2) taken by the wall-side base corner instead of
# the top corner: the face (or the lower corner) against the wall
CS_WALL_BASE = 5
# the wall contact slipping along a frictional wall (mu_w > 0: C_MU_W),
# sigma_w = sign of its velocity along the wall's tangent (0, 1), friction
# -mu_w sigma_w N_w: the top corner (_TOP_) or the wall-side base corner
# (_BASE_); the wall contact sticking (its tangential velocity 0: impulse
# solves only, a sticking wall with a closed ground contact is static)
CS_TOP_SLIP_P = 6
CS_TOP_SLIP_N = 7
CS_BASE_SLIP_P = 8
CS_BASE_SLIP_N = 9
CS_TOP_STICK = 10
CS_BASE_STICK = 11
# body point index of the wall-side base corner seen as a wall contact
K_NEAR = 3
# the wall-side base corner counts as at the wall below this gap [m]
# (relative to the half-width)
FACE_RTOL = 1e-6
# a closed base-corner wall contact is projected back at this drift into
# the wall (relative to the half-width; half the guard's FACE_RTOL band)
DRIFT_BAND = 0.5 * FACE_RTOL
EPS_ROUND = 2.220446049250313e-16

# ---- events ----------------------------------------------------------------
K_IMPACT = 0
K_OVERTURN = 1
K_SLIP = 2
K_STICK = 3
K_LIFT = 4
K_PEAK = 5
K_PASS_ALPHA = 6
K_LAND0 = 7
K_LAND1 = 8
K_APEX = 9
K_WALL = 10
K_WALL_BASE = 11
N_EVENTS = 12

# iteration cap of the sequential impulses of a frictional wall impact
PGS_MAX = 20000
# a tangential contact velocity below this [m/s] counts as zero (stick test)
V_TOL = 1e-12
# the other base corner counts as on the ground at a landing below this [m]
# (relative to the base width): the landing is then flat
FLAT_RTOL = 1e-9
MAX_N = 6
# D_SLIP_DIR in ROCK: the pivot is held although N < 0 (no consistent mode)
JAM = 2
# D_SLIP_DIR in ROCK: the pivot sticks with |F| above mu_s N by rounding
EDGE = 3


# ---------------------------------------------------------------- geometry
@jit
def body_point(k, par):
    """Body-frame coordinates of contact point k relative to the CM
    (k = K_NEAR: the wall-side base corner, as a wall contact; k = 2: the
    wall-side top corner, or the centre of a rounded one's arc,
    (w (b_w - rho), ht_w - rho), rho = par[C_TOP_R])."""
    if k == 0:
        return -par[C_B1], -par[C_H1]
    if k == 1:
        return par[C_B2], -par[C_H2]
    if k == K_NEAR:
        if par[P_WALL_SIDE] > 0.0:
            return par[C_B2], -par[C_H2]
        return -par[C_B1], -par[C_H1]
    # the wall-side top corner, or a rounded one's arc centre
    rho = par[C_TOP_R]
    if par[P_WALL_SIDE] > 0.0:
        return par[C_B2] - rho, par[C_HT2] - rho
    return -(par[C_B1] - rho), par[C_HT1] - rho


@jit
def frame(k, par):
    """(nx, ny, tx, ty): contact normal (toward the body) and tangent."""
    if k < 2:
        return 0.0, 1.0, 1.0, 0.0
    return -par[P_WALL_SIDE], 0.0, 0.0, 1.0


@jit
def hmid(par):
    return 0.5 * (par[C_H1] + par[C_H2])


@jit
def alpha_of(s, par):
    """alpha of pivot s (+1 right: P_ALPHA, -1 left: C_ALPHA_NEG)."""
    return par[P_ALPHA] if s > 0 else par[C_ALPHA_NEG]


@jit
def cm_velocity(y, par):
    """(v_Gx, v_Gy) from the state."""
    hm = hmid(par)
    c = math.cos(y[0])
    sn = math.sin(y[0])
    return y[3] + y[1] * hm * c, y[5] - y[1] * hm * sn


@jit
def point_offset(k, theta, par):
    """World vector from the CM to contact point k."""
    cx, cy = body_point(k, par)
    c = math.cos(theta)
    sn = math.sin(theta)
    return cx * c + cy * sn, -cx * sn + cy * c


@jit
def short_wall(par):
    """The wall is lower than the body's wall-side top corner."""
    return par[C_H_WALL] > 0.0


@jit
def arc_front(th, par):
    """World offset from ``body_point(2)`` to the body's point farthest
    toward the wall near the top: the front point (w rho, 0) of a rounded
    corner's arc while the horizontal lies within the arc's normals (the
    body turned toward the wall, w theta >= 0: rolling is True, the point
    moves over the arc), else the straight face's top end, body-fixed.
    0 for the square corner (rho = 0)."""
    rho = par[C_TOP_R]
    w = par[P_WALL_SIDE]
    if w * th >= 0.0:
        return w * rho, 0.0, rho > 0.0
    return w * rho * math.cos(th), -w * rho * math.sin(th), False


@jit
def wall_geom(y, par):
    """The wall contact (k = 2) in state y: (gap, rx, ry, nx, ny, tx, ty,
    kind), r the world vector from the CM to the body's contact point, n
    the contact normal (toward the body), t = (w n_y, -w n_x) its tangent.
    A tall wall: the top corner against the wall's face, n = (-w, 0).  A
    short wall (height h_w = par[C_H_WALL]), top edge E = (w (b_w + d),
    h_w), against the body's nearest feature, by E's place in the body
    frame: while E projects onto the wall-side face, the face (WG_EDGE: its
    point at E's projection, n its inward normal, which turns with the
    body; the gap is E's signed distance to the face line); past the top
    corner, the top face (WG_TOP: the body over the wall), or the top
    corner against the wall's face below E (WG_CORNER) or against E itself
    (WG_VERTEX, gap their distance); below the base's line, the bottom
    face (WG_BOTTOM: the base over the wall) or, past the base corner, that
    corner against E (WG_BASE, gap their distance; the corner against the
    wall's face below E is the K_NEAR contact's).  Inside the body the
    nearest of the face, the top and the bottom: the gap is E's signed
    distance to the body near them, continuous, so a crossing, or a pass
    through the body inside one flight step (a minimum), is located.
    (The face's line continued past the base corner is no contact: E
    there, outside the body, read gap 0, and its impacts took most of a
    sliding block's energy, contact:2027:251.)

    A rounded top corner (radius rho = par[C_TOP_R] > 0, centre C =
    ``body_point(2)``; docs: theory/wall): the face ends at ht_w - rho and
    the top face at b_w - rho; against the wall's face (WG_CORNER) the gap
    is C's minus rho and the contact point the arc's front point
    (``arc_front``); against E (WG_VERTEX) the gap is |C - E| - rho, n along
    C - E and the contact point C - rho n.  rho = 0 is the square corner
    bit for bit."""
    th = y[0]
    w = par[P_WALL_SIDE]
    bw = par[C_B2] if w > 0.0 else par[C_B1]
    rx, ry = point_offset(2, th, par)
    fx, fy, _rolling = arc_front(th, par)
    hm = hmid(par)
    gx = y[2] + hm * math.sin(th)
    if not short_wall(par):
        return bw + par[C_GAP] - w * (gx + rx + fx), rx + fx, ry + fy, \
            -w, 0.0, 0.0, 1.0, WG_CORNER
    rho = par[C_TOP_R]
    gy = y[4] + hm * math.cos(th)
    ex = w * (bw + par[C_GAP]) - gx
    ey = par[C_H_WALL] - gy
    c = math.cos(th)
    sn = math.sin(th)
    # E's coordinate along the face (body frame, up from the CM)
    cE = sn * ex + c * ey
    ht = par[C_HT2] if w > 0.0 else par[C_HT1]
    # E's coordinate across the face, toward the wall side
    u = w * (c * ex - sn * ey)
    hs = par[C_H2] if w > 0.0 else par[C_H1]
    d_bot = -hs - cE
    if d_bot > 0.0 or (d_bot > u - bw and d_bot > cE - ht):
        if u <= bw:
            # E below the bottom face (or inside the body nearest to it)
            qx = u * w * c - hs * sn
            qy = -u * w * sn - hs * c
            return d_bot, qx, qy, sn, c, w * c, -w * sn, WG_BOTTOM
        rx, ry = point_offset(K_NEAR, th, par)
        dx = rx - ex
        dy = ry - ey
        dist = math.hypot(dx, dy)
        if dist == 0.0:
            return 0.0, rx, ry, -w * c, w * sn, sn, c, WG_BASE
        nx = dx / dist
        ny = dy / dist
        return dist, rx, ry, nx, ny, w * ny, -w * nx, WG_BASE
    if cE <= ht - rho and u - bw >= cE - ht:
        # face point Q = b_w n_f + cE t_f, n_f = (w c, -w sn), t_f = (sn, c)
        qx = w * bw * c + cE * sn
        qy = -w * bw * sn + cE * c
        return u - bw, qx, qy, -w * c, w * sn, sn, c, WG_EDGE
    if u <= bw - rho:
        # above the top face (the body over the wall), or inside the body
        # nearer the top than the face: E against the top face
        qx = u * w * c + ht * sn
        qy = -u * w * sn + ht * c
        return cE - ht, qx, qy, -sn, -c, -w * c, w * sn, WG_TOP
    # E past the corner (the arc's centre) along and across the face
    if gy + ry + fy <= par[C_H_WALL]:
        return bw + par[C_GAP] - w * (gx + rx + fx), rx + fx, ry + fy, \
            -w, 0.0, 0.0, 1.0, WG_CORNER
    dx = rx - ex
    dy = ry - ey
    dist = math.hypot(dx, dy)
    nx = dx / dist
    ny = dy / dist
    return dist - rho, rx - rho * nx, ry - rho * ny, nx, ny, w * ny, \
        -w * nx, WG_VERTEX


@jit
def geom(k, y, par):
    """(rx, ry, nx, ny, tx, ty) of contact point k in state y."""
    if k == 2:
        _g, rx, ry, nx, ny, tx, ty, _kind = wall_geom(y, par)
        return rx, ry, nx, ny, tx, ty
    rx, ry = point_offset(k, y[0], par)
    nx, ny, tx, ty = frame(k, par)
    return rx, ry, nx, ny, tx, ty


@jit
def point_kin(k, y, par):
    """(gap, normal velocity, tangential velocity) of contact point k; the
    gap is the height above the ground (k < 2) or the clear distance to the
    wall (k = 2: the wall contact of ``wall_geom``, k = K_NEAR: the
    wall-side base corner)."""
    th = y[0]
    om = y[1]
    hm = hmid(par)
    if k == 2:
        gap, rx, ry, nx, ny, tx, ty, _kind = wall_geom(y, par)
    else:
        rx, ry = point_offset(k, th, par)
        nx, ny, tx, ty = frame(k, par)
    gx = y[2] + hm * math.sin(th)
    gy = y[4] + hm * math.cos(th)
    vgx, vgy = cm_velocity(y, par)
    vx = vgx + om * ry
    vy = vgy - om * rx
    if k < 2:
        gap = gy + ry
    elif k == K_NEAR:
        w = par[P_WALL_SIDE]
        bw = par[C_B2] if w > 0.0 else par[C_B1]
        gap = bw + par[C_GAP] - w * (gx + rx)
    return gap, nx * vx + ny * vy, tx * vx + ty * vy


@jit
def wall_normal_rate(y, par):
    """The normal acceleration of the wall contact's gap beyond that of
    its body point (the velocity-product term of the mode solve's wall
    row): 2 n'.v, n' = theta' (n_y, -n_x) for a normal fixed in the body
    (E on the face or on the top), 0 for the corner on the wall's face;
    for the corner on E (|v_t|^2 / gap, infinite at contact) 0: that
    contact is an impact only.  A rounded top's arc (docs: theory/wall):
    the gap follows the centre C, whose acceleration differs from the
    contact point's by the centripetal rho theta'^2 along n: -rho
    theta'^2 on the wall's face while the contact point rolls over the arc;
    on E the curvature term (t.v_C)^2 / |C - E| - rho theta'^2, finite."""
    rho = par[C_TOP_R]
    if not short_wall(par) and rho == 0.0:
        return 0.0
    g, rx, ry, nx, ny, tx, ty, kind = wall_geom(y, par)
    om = y[1]
    if kind == WG_CORNER:
        _fx, _fy, rolling = arc_front(y[0], par)
        return -rho * om * om if rolling else 0.0
    vgx, vgy = cm_velocity(y, par)
    if kind == WG_BASE:
        return 0.0
    if kind == WG_VERTEX:
        if rho == 0.0:
            return 0.0
        cx = rx + rho * nx
        cy = ry + rho * ny
        vt = tx * (vgx + om * cy) + ty * (vgy - om * cx)
        return vt * vt / (g + rho) - rho * om * om
    return 2.0 * om * (ny * (vgx + om * ry) - nx * (vgy - om * rx))


@jit
def free_acc(t, par, hdr, smp):
    """Generalized acceleration (x_G'', y_G'', theta'') with no contact
    force: the only place where gravity (0, -G) enters."""
    ag, av = ground(t, hdr, smp)
    return -ag, -(par[P_G] + av), 0.0


@jit
def state_from_cm(y, par, agx, agy, alpha):
    """(x'', z'') of P from the CM accelerations and theta''."""
    hm = hmid(par)
    th = y[0]
    om2 = y[1] * y[1]
    c = math.cos(th)
    sn = math.sin(th)
    return agx - hm * (c * alpha - sn * om2), agy + hm * (sn * alpha + c * om2)


@jit
def set_cm_velocity(y, par, vgx, vgy, om):
    """Write the velocity part of y from (v_Gx, v_Gy, theta')."""
    hm = hmid(par)
    c = math.cos(y[0])
    sn = math.sin(y[0])
    y[1] = om
    y[3] = vgx - om * hm * c
    y[5] = vgy + om * hm * sn


# ---------------------------------------------------------------- wall states
@jit
def wall_base(st2):
    """The wall contact state st2 is the wall-side base corner's."""
    return (st2 == CS_WALL_BASE or st2 == CS_BASE_SLIP_P
            or st2 == CS_BASE_SLIP_N or st2 == CS_BASE_STICK)


@jit
def wall_top(st2):
    """The wall contact state st2 is the top corner's (closed)."""
    return (st2 == CS_FREE or st2 == CS_TOP_SLIP_P or st2 == CS_TOP_SLIP_N
            or st2 == CS_TOP_STICK)


@jit
def wall_sigma(st2):
    """Slip direction sigma_w of a slipping wall contact (0 otherwise)."""
    if st2 == CS_TOP_SLIP_P or st2 == CS_BASE_SLIP_P:
        return 1
    if st2 == CS_TOP_SLIP_N or st2 == CS_BASE_SLIP_N:
        return -1
    return 0


@jit
def wall_state(kw, mode):
    """Wall contact state of wall point kw (2 or K_NEAR): mode 0 normal
    force only, 1 sticking, +-2 slipping with sigma_w = +-1."""
    if kw == K_NEAR:
        if mode == 1:
            return CS_BASE_STICK
        if mode == 2:
            return CS_BASE_SLIP_P
        if mode == -2:
            return CS_BASE_SLIP_N
        return CS_WALL_BASE
    if mode == 1:
        return CS_TOP_STICK
    if mode == 2:
        return CS_TOP_SLIP_P
    if mode == -2:
        return CS_TOP_SLIP_N
    return CS_FREE


@jit
def wall_frictional(par):
    return par[C_MU_W] > 0.0


# ---------------------------------------------------------------- mode solve
@jit
def contact_mu(k, par, kinetic):
    if k == 2:
        return par[C_MU_W]
    return par[C_MU_K] if kinetic else par[C_MU_S]


@jit
def solve_contacts(y, b0x, b0y, b0w, om2, par, st0, st1, st2, out):
    """``solve_targets`` with every target 0."""
    return solve_targets(y, b0x, b0y, b0w, om2, par, st0, st1, st2, 0.0,
                         out)


@jit
def solve_targets(y, b0x, b0y, b0w, om2, par, st0, st1, st2, tgt2, out):
    """The generic mode solve of physics.md 4.2 (and its impulse form).

    Contact k is in state st_k (CS_*).  With ``b0`` the generalized
    acceleration without contact forces and om2 = theta'^2, solves for the
    contact forces that keep every closed contact's normal acceleration
    (and a sticking one's tangential acceleration) zero; with ``b0`` the
    pre-impact generalized velocity and om2 = 0, for the impulses that make
    those velocities zero.  ``out`` receives b0 + M^-1 Q (x_G'', y_G'',
    theta'' or the post-impact velocities).  Returns (ok, N0, F0, N1, F1,
    N2, F2); ok is False for a singular system (e.g. both base corners
    sticking: REST is a static phase, never solved here).  ``tgt2`` is the
    target of the wall contact's normal row (impulse form: the post-impact
    normal velocity -e_w v_n-; acceleration form: ``wall_normal_rate``'s
    term, for a short wall or a rounded top).  The geometry is that of the state y (theta =
    y[0]; a short wall's contact also moves with the position).  The wall
    contact is the top corner or a short wall's edge (st2 = CS_FREE,
    CS_TOP_*: ``wall_geom``) or the wall-side base corner (st2 =
    CS_WALL_BASE, CS_BASE_*); slipping on a frictional wall its friction is
    -mu_w sigma_w N_w along its tangent, sticking it adds a tangential row.
    """
    iG = par[C_IG]
    c = math.cos(y[0])
    sn = math.sin(y[0])
    # ws[i]: 0-2 constraint row J, 3-5 force column, 6-11 matrix row,
    # 12 right-hand side, 13 owner contact, 14 kind (0 N, 1 F), 15 -mu sigma
    ws = np.zeros((MAX_N, 16))
    n = 0
    for k in range(3):
        st = st0 if k == 0 else (st1 if k == 1 else st2)
        if st == CS_OPEN:
            continue
        kk = K_NEAR if (k == 2 and wall_base(st)) else k
        if kk == 2:
            _g, rx, ry, nx, ny, tx, ty, _kind = wall_geom(y, par)
        else:
            cx, cy = body_point(kk, par)
            rx = cx * c + cy * sn
            ry = -cx * sn + cy * c
            nx, ny, tx, ty = frame(kk, par)
        jn2 = ry * nx - rx * ny
        jt2 = ry * tx - rx * ty
        m = 0.0
        if k == 2:
            sw = wall_sigma(st)
            if sw != 0:
                m = -sw * par[C_MU_W]
            stick = st == CS_TOP_STICK or st == CS_BASE_STICK
        else:
            stick = st == CS_STICK
            if st == CS_SLIP_P:
                m = -contact_mu(k, par, True)
            elif st == CS_SLIP_N:
                m = contact_mu(k, par, True)
        # normal row, normal-force column
        ws[n, 0] = nx
        ws[n, 1] = ny
        ws[n, 2] = jn2
        ws[n, 3] = nx + m * tx
        ws[n, 4] = ny + m * ty
        ws[n, 5] = jn2 + m * jt2
        ws[n, 12] = om2 * (nx * rx + ny * ry) - (nx * b0x + ny * b0y
                                                  + jn2 * b0w)
        if k == 2:
            ws[n, 12] += tgt2
        ws[n, 13] = k
        ws[n, 14] = 0.0
        ws[n, 15] = m
        n += 1
        if stick:
            ws[n, 0] = tx
            ws[n, 1] = ty
            ws[n, 2] = jt2
            ws[n, 3] = tx
            ws[n, 4] = ty
            ws[n, 5] = jt2
            ws[n, 12] = om2 * (tx * rx + ty * ry) - (tx * b0x + ty * b0y
                                                      + jt2 * b0w)
            ws[n, 13] = k
            ws[n, 14] = 1.0
            n += 1
    scale = 0.0
    for i in range(n):
        for j in range(n):
            a = ws[i, 0] * ws[j, 3] + ws[i, 1] * ws[j, 4] + \
                ws[i, 2] * ws[j, 5] / iG
            ws[i, 6 + j] = a
            scale = max(scale, abs(a))
    # Gaussian elimination with partial pivoting on ws[:, 6:6+n | 12]
    ok = True
    for col in range(n):
        piv = col
        for i in range(col + 1, n):
            if abs(ws[i, 6 + col]) > abs(ws[piv, 6 + col]):
                piv = i
        if not abs(ws[piv, 6 + col]) > 1e-12 * scale:
            ok = False
            break
        if piv != col:
            for j in range(6, 13):
                tmp = ws[col, j]
                ws[col, j] = ws[piv, j]
                ws[piv, j] = tmp
        for i in range(col + 1, n):
            f = ws[i, 6 + col] / ws[col, 6 + col]
            if f != 0.0:
                for j in range(6 + col, 13):
                    ws[i, j] -= f * ws[col, j]
    lam = np.zeros(MAX_N)
    if ok:
        for i in range(n - 1, -1, -1):
            s = ws[i, 12]
            for j in range(i + 1, n):
                s -= ws[i, 6 + j] * lam[j]
            lam[i] = s / ws[i, 6 + i]
    qx = 0.0
    qy = 0.0
    qw = 0.0
    N0 = F0 = N1 = F1 = N2 = F2 = 0.0
    for j in range(n):
        qx += ws[j, 3] * lam[j]
        qy += ws[j, 4] * lam[j]
        qw += ws[j, 5] * lam[j]
        k = int(ws[j, 13])
        if ws[j, 14] == 0.0:
            Nk = lam[j]
            Fk = ws[j, 15] * lam[j]
            if k == 0:
                N0 = Nk
                F0 += Fk
            elif k == 1:
                N1 = Nk
                F1 += Fk
            else:
                N2 = Nk
                F2 += Fk
        else:
            if k == 0:
                F0 += lam[j]
            elif k == 1:
                F1 += lam[j]
            else:
                F2 += lam[j]
    out[0] = b0x + qx
    out[1] = b0y + qy
    out[2] = b0w + qw / iG
    return ok, N0, F0, N1, F1, N2, F2


@jit
def mode_solve(t, y, par, st0, st1, st2, hdr, smp, acc):
    """Accelerations (x_G'', y_G'', theta'') and contact forces at time t
    for the contact states st_k (physics.md 4.2)."""
    bx, by, bw = free_acc(t, par, hdr, smp)
    tgt2 = 0.0
    if wall_top(st2):
        tgt2 = -wall_normal_rate(y, par)
    return solve_targets(y, bx, by, bw, y[1] * y[1], par, st0, st1, st2,
                         tgt2, acc)


@jit
def contact_acc(k, y, par, acc):
    """(normal, tangential) acceleration of contact point k for the
    generalized acceleration acc (of its gap and slip for the wall
    contact: ``wall_normal_rate`` added)."""
    rx, ry, nx, ny, tx, ty = geom(k, y, par)
    om2 = y[1] * y[1]
    ax = acc[0] + acc[2] * ry - om2 * rx
    ay = acc[1] - acc[2] * rx - om2 * ry
    an = nx * ax + ny * ay
    if k == 2:
        an += wall_normal_rate(y, par)
    return an, tx * ax + ty * ay


@jit
def free_normal_acc(j, t, y, par, hdr, smp):
    """Normal acceleration of base corner j with no contact force."""
    ag, av = ground(t, hdr, smp)
    rx, ry = point_offset(j, y[0], par)
    return -(par[P_G] + av) - y[1] * y[1] * ry


@jit
def stick_holds(N, j, t, y, par, hdr, smp):
    """A sticking base corner j stays on the ground: N >= 0, or, with
    mu_s = inf, while flight is inconsistent (the free corner would
    accelerate into the ground): the pivot is held as in kernels/rigid.py
    (with N = 0 and F != 0 no finite friction could stick)."""
    if N >= 0.0:
        return True
    if np.isfinite(par[C_MU_S]):
        return False
    return free_normal_acc(j, t, y, par, hdr, smp) < 0.0


@jit
def slip_state(sigma):
    return CS_SLIP_P if sigma > 0 else CS_SLIP_N


@jit
def sign_of(v):
    return 1 if v > 0.0 else -1


# ---------------------------------------------------------------- rhs
@jit
def rhs(t, y, par, disc, hdr, smp, out):
    acc = np.empty(3)
    if (disc[D_MODE] == MODE_FLIGHT and disc[D_CS2] == CS_OPEN) or \
            disc[D_STATIC] == 1 or face_flight(disc):
        bx, by, bw = free_acc(t, par, hdr, smp)
        acc[0] = bx
        acc[1] = by
        acc[2] = bw
        if disc[D_STATIC] == 1:
            acc[0] = 0.0
            acc[1] = 0.0
            acc[2] = 0.0
        elif face_flight(disc):
            # the face on the wall holds x and theta
            acc[0] = 0.0
            acc[2] = 0.0
    else:
        mode_solve(t, y, par, disc[D_CS0], disc[D_CS1], disc[D_CS2], hdr, smp,
                   acc)
    xdd, zdd = state_from_cm(y, par, acc[0], acc[1], acc[2])
    out[0] = y[1]
    out[1] = acc[2]
    out[2] = y[3]
    out[3] = xdd
    out[4] = y[5]
    out[5] = zdd


# ---------------------------------------------------------------- events
@jit
def wall_active(par):
    return np.isfinite(par[C_GAP])


@jit
def near_index(par):
    """Index (0, 1) of the wall-side base corner."""
    return 1 if par[P_WALL_SIDE] > 0.0 else 0


@jit
def near_gap(y, par):
    """Clear distance of the wall-side base corner to the wall and its
    rate: to the wall's face, or, above a short wall's top by more than
    that, the height above the top (the corner passes over the wall; its
    contact with the edge E is the wall contact's, WG_BASE and WG_BOTTOM
    of ``wall_geom``).  Continuous where the corner is outside the face."""
    gap, vn, _vt = point_kin(K_NEAR, y, par)
    if not short_wall(par):
        return gap, vn
    rx, ry = point_offset(K_NEAR, y[0], par)
    above = y[4] + hmid(par) * math.cos(y[0]) + ry - par[C_H_WALL]
    if above <= gap:
        return gap, vn
    _vgx, vgy = cm_velocity(y, par)
    return above, vgy - y[1] * rx


@jit
def approach_gap(kw, y, par):
    """Wall gap of wall point kw (2 or K_NEAR) and its rate.  Unlike the
    top corner's event (inf while it moves away) the gap is always
    returned, so that a crossing inside a step whose end moves away again
    (the slip reversing after a stick event, a rebound) is still seen
    (grazing search); a phase that starts at the wall moving away is no
    root (g0 <= 0 < g1)."""
    if not wall_active(par):
        return np.inf, 0.0
    if kw == K_NEAR:
        return near_gap(y, par)
    gap, vn, _vt = point_kin(kw, y, par)
    return gap, vn


@jit
def closed_wall_force(t, y, par, disc, hdr, smp):
    """Normal force of the closed wall contact (the base corner's ladder or
    the top corner's) in the current contact mode; the phase ends at 0."""
    acc = np.empty(3)
    _ok, _N0, _F0, _N1, _F1, N2, _F2 = mode_solve(
        t, y, par, disc[D_CS0], disc[D_CS1], disc[D_CS2], hdr, smp, acc)
    return N2


@jit
def near_half_width(par):
    return par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]


@jit
def closed_base_margin(t, y, par, disc, hdr, smp):
    """Event of the closed base-corner wall contact: its normal force
    reaching 0, or the corner drifting into the wall by DRIFT_BAND of the
    half-width.  The closed contact holds at acceleration level only, so
    its gap drifts at the integration tolerance; with a millimetre-wide
    block and rtol 1e-4 that crossed the bug guard's FACE_RTOL band
    (failed:face-contact, contact:2027:2).  At the band the transition
    projects the state back onto the contacts (``project_wall_point``)."""
    N2 = closed_wall_force(t, y, par, disc, hdr, smp)
    gap, _vn, _vt = point_kin(K_NEAR, y, par)
    band = DRIFT_BAND * near_half_width(par)
    return min(N2, par[P_G] * (gap + band) / band)


@jit
def drifted_into_wall(y, par):
    gap, _vn, _vt = point_kin(K_NEAR, y, par)
    return gap < -0.5 * DRIFT_BAND * near_half_width(par)


@jit
def project_wall_point(kw, y, par):
    """Put wall point kw on the wall with zero normal velocity (the wall
    gap and its rate depend on x and x' alone, with unit weight)."""
    gap, vn, _vt = point_kin(kw, y, par)
    w = par[P_WALL_SIDE]
    y[2] += w * gap
    y[3] += w * vn


@jit
def wall_flight_event(k, t, y, par, disc, hdr, smp):
    """Flight with the wall contact closed on a frictional wall: K_STICK,
    the slip along the wall stopping (sigma_w v_tw); K_SLIP, a sticking
    wall point leaving its cone (mu_w N_w - |F_w|)."""
    cs2 = disc[D_CS2]
    kw = K_NEAR if wall_base(cs2) else 2
    acc = np.empty(3)
    _ok, _N0, _F0, _N1, _F1, N2, F2 = mode_solve(
        t, y, par, CS_OPEN, CS_OPEN, cs2, hdr, smp, acc)
    sw = wall_sigma(cs2)
    if k == K_STICK and sw != 0:
        _an, atw = contact_acc(kw, y, par, acc)
        _g, _vn, vtw = point_kin(kw, y, par)
        return sw * vtw, sw * atw, True
    if k == K_SLIP and (cs2 == CS_TOP_STICK or cs2 == CS_BASE_STICK):
        return par[C_MU_W] * N2 - abs(F2), 0.0, True
    return np.inf, 0.0, True


@jit
def event(k, t, y, par, disc, hdr, smp):
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    if k == K_WALL_BASE:
        # the wall-side base corner reaching the wall (flight; rocking or
        # slide-rocking on the far corner); while it rests on the wall
        # (ladder mode), the wall's normal force reaching 0
        if mode == MODE_FLIGHT:
            if face_flight(disc):
                return face_push(t, par, hdr, smp), 0.0, True
            if wall_base(disc[D_CS2]):
                return closed_base_margin(t, y, par, disc, hdr, smp), 0.0, True
            g, gd = approach_gap(K_NEAR, y, par)
            # within the contact band and not approaching beyond rounding:
            # no root (a face stopped flat at the wall by a face impact in
            # flight, with nothing pushing it there, kept gap 0 and fired
            # zero-velocity face impacts at one instant for ever)
            if (abs(g) <= FACE_RTOL * near_half_width(par)
                    and gd >= -1e-12 * velocity_scale(y, par)):
                return np.inf, 0.0, True
            return g, gd, True
        if mode != MODE_ROCK and mode != MODE_SLIDE_ROCK:
            return np.inf, 0.0, True
        if wall_base(disc[D_CS2]):
            return closed_base_margin(t, y, par, disc, hdr, smp), 0.0, True
        if (1 if s > 0 else 0) == near_index(par):
            return np.inf, 0.0, True
        g, gd = approach_gap(K_NEAR, y, par)
        if mode == MODE_ROCK:
            # pivot fixed on the far corner: the near corner lies at
            # (b1 + b2) cos(theta) from it along the wall normal, nearest
            # to the wall at theta = 0 (physics.md 2: tilting away from the
            # wall no point approaches it).  g_flat, its gap at theta = 0,
            # is exact geometry; within the contact band (FACE_RTOL,
            # near_at_wall) the corner reaches the wall only with the base
            # flat, the ground impact K_IMPACT (a face impact there).  The
            # rounded gap of a corner that starts at the wall and tilts
            # away read <= 0 for several steps: a wall impact at zero
            # approach velocity fired at once, changed nothing, for ever
            # (issue #14); and a drift of 1e-12 m put the corner on the
            # wall at theta ~ 1e-5, an ill-conditioned impact that gained
            # energy.
            g_face, _vn, _vt = point_kin(K_NEAR, y, par)
            sh = math.sin(0.5 * y[0])
            g_flat = g_face - 2.0 * (par[C_B1] + par[C_B2]) * sh * sh
            bw = par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]
            if g_flat >= -FACE_RTOL * bw:
                return np.inf, 0.0, True
        return g, gd, True
    if mode == MODE_FLIGHT:
        if k == K_OVERTURN:
            sg = 1.0 if y[0] >= 0.0 else -1.0
            return par[P_THETA_OVER] - abs(y[0]), -sg * y[1], True
        if k == K_PASS_ALPHA:
            sg = 1.0 if y[0] >= 0.0 else -1.0
            return alpha_of(sg, par) - abs(y[0]), -sg * y[1], False
        cs2 = disc[D_CS2]
        if k == K_WALL and wall_top(cs2):
            # flight with the top corner on the wall: the wall's force
            # reaching 0
            return closed_wall_force(t, y, par, disc, hdr, smp), 0.0, True
        if (k == K_STICK or k == K_SLIP) and cs2 != CS_OPEN:
            return wall_flight_event(k, t, y, par, disc, hdr, smp)
        if k == K_LAND0 or k == K_LAND1 or k == K_WALL:
            if k == K_WALL and not wall_active(par):
                return np.inf, 0.0, True
            j = k - K_LAND0 if k != K_WALL else 2
            gap, vn, _vt = point_kin(j, y, par)
            # moving toward the surface beyond rounding: a flight entered
            # with a corner at rest on the ground (N = 0 with the free
            # corner not falling) keeps vn ~ -1e-17, and a landing at that
            # speed changed nothing and flew again at once (zero-time loop)
            if vn < -1e-12 * velocity_scale(y, par):
                return gap, vn, True
            band = FACE_RTOL * (par[C_B1] + par[C_B2])
            if k == K_WALL and (gap < -band or
                                (short_wall(par) and gap > band)):
                # moving away: inside the wall beyond the contact band
                # (crossed and turned back inside the step), located; and
                # clear of a short wall's edge, kept for the grazing search
                # (a flight step is long: E can pass through the body's
                # corner region inside one)
                return gap, vn, True
            return np.inf, 0.0, True
        if k == K_APEX:
            _ag, av = ground(t, hdr, smp)
            _vx, vy = cm_velocity(y, par)
            return vy, -(par[P_G] + av), False
        return np.inf, 0.0, True
    if mode == MODE_SLIDE:
        if k == K_WALL:
            if not wall_active(par):
                return np.inf, 0.0, True
            gap, vn, _vt = point_kin(2, y, par)
            if vn < 0.0:
                return gap, vn, True
            # at rest or moving away: no root, unless the face is in the
            # wall beyond the contact band (a slide that reached the wall
            # and stopped inside one step, whose end is at rest: located)
            bw = par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]
            if gap < -FACE_RTOL * bw:
                return gap, vn, True
            return np.inf, 0.0, True
        if k == K_STICK or k == K_LIFT:
            acc = np.empty(3)
            _ok, N0, _F0, N1, _F1, _N2, _F2 = mode_solve(
                t, y, par, disc[D_CS0], disc[D_CS1], disc[D_CS2], hdr, smp,
                acc)
            if k == K_LIFT:
                # the trailing corner's N = G (b - mu_k h) / (2b) (for the
                # rectangle) is 0 at mu_k = b/h: it lifts only when N is
                # negative beyond the rounding (friction.py: SLIDE while
                # mu_k <= b/h)
                return min(N0, N1) + UPLIFT_RTOL * (N0 + N1), 0.0, True
            sig = disc[D_SLIP_DIR]
            _an, at = contact_acc(0, y, par, acc)
            _g, _vn, vt = point_kin(0, y, par)
            return sig * vt, sig * at, True
        return np.inf, 0.0, True
    if mode != MODE_ROCK and mode != MODE_SLIDE_ROCK:
        return np.inf, 0.0, True
    if k == K_IMPACT:
        return s * y[0], s * y[1], True
    if k == K_OVERTURN:
        return par[P_THETA_OVER] - s * y[0], -s * y[1], True
    if k == K_PASS_ALPHA:
        return alpha_of(s, par) - s * y[0], -s * y[1], False
    if k == K_SLIP and mode != MODE_ROCK:
        return np.inf, 0.0, True
    if k == K_STICK and mode != MODE_SLIDE_ROCK:
        return np.inf, 0.0, True
    if k == K_WALL:
        if not wall_active(par) or wall_base(disc[D_CS2]):
            return np.inf, 0.0, True
        if wall_top(disc[D_CS2]):
            # top-corner ladder (top_ladder): the wall's force reaching 0
            return closed_wall_force(t, y, par, disc, hdr, smp), 0.0, True
        if par[C_GAP] == 0.0 and (1 if s > 0 else 0) != near_index(par) \
                and (mode == MODE_ROCK or not short_wall(par)):
            # gap 0, rocking on the far corner: the wall-side face is
            # vertical, so the top corner reaches the wall with the base
            # corner below it, at theta = 0 (K_IMPACT: Hogan's impact), or
            # after it (K_WALL_BASE).  A short wall's edge, at the near
            # corner's place at rest, is off the base turning about a fixed
            # pivot; a pivot sliding toward the wall can carry the raised
            # base over it (WG_BOTTOM)
            return np.inf, 0.0, True
        gap, vn, _vt = point_kin(2, y, par)
        if vn < 0.0:
            return gap, vn, True
        # moving away but inside the wall beyond the contact band: a rock
        # toward the wall that crossed it and turned back inside one step
        # (a block slid to within 2h theta of the wall), located; not a
        # tangency at rounding level (a gap of exactly 2h touched at
        # theta = pi / 2)
        bw = par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]
        if gap < -FACE_RTOL * bw:
            return gap, vn, True
        return np.inf, 0.0, True
    if k > K_PASS_ALPHA:
        return np.inf, 0.0, True
    acc = np.empty(3)
    _ok, N0, F0, N1, F1, _N2, _F2 = mode_solve(
        t, y, par, disc[D_CS0], disc[D_CS1], disc[D_CS2], hdr, smp, acc)
    if k == K_PEAK:
        return s * y[1], s * acc[2], False
    j = 1 if s > 0 else 0
    N = N1 if j == 1 else N0
    F = F1 if j == 1 else F0
    jam = mode == MODE_ROCK and disc[D_SLIP_DIR] == JAM
    if k == K_LIFT:
        if jam:
            return -free_normal_acc(j, t, y, par, hdr, smp), 0.0, True
        if mode == MODE_ROCK and not np.isfinite(par[C_MU_S]):
            return max(N, -free_normal_acc(j, t, y, par, hdr, smp)), 0.0, True
        return N, 0.0, True
    if k == K_SLIP:
        mu = par[C_MU_S]
        if not np.isfinite(mu):
            return np.inf, 0.0, True
        if jam:
            # the jam ends when N returns clearly >= 0
            return 1e-9 * par[P_G] - N, 0.0, True
        if disc[D_SLIP_DIR] == EDGE:
            # stuck at the cone's edge to rounding: the slip starts once
            # the demand clears that rounding band
            return mu * N - abs(F) + 1e-12 * (abs(F) + mu * N), 0.0, True
        return mu * N - abs(F), 0.0, True
    # K_STICK (SLIDE_ROCK)
    sig = disc[D_SLIP_DIR]
    _an, at = contact_acc(j, y, par, acc)
    _g, _vn, vt = point_kin(j, y, par)
    return sig * vt, sig * at, True


@jit
def rest_margin(t, par, hdr, smp):
    """Full contact (both base corners sticking) holds while the friction
    demand |a_g| <= mu_s G and neither corner's normal force is negative:
    N_left = (b2 G + h a_g)/(b1 + b2) >= 0, N_right = (b1 G - h a_g) /
    (b1 + b2) >= 0 (physics.md 1, 4.3), with kernels/friction.py's
    tolerance; negative also for G < 0 (flight)."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    h = hmid(par)
    tol = 1.0 + UPLIFT_RTOL
    m = min(G * par[C_B2] / h * tol + ag, G * par[C_B1] / h * tol - ag)
    mu = par[C_MU_S]
    if np.isfinite(mu):
        m = min(m, mu * G * tol - abs(ag))
    return min(m, G)


@jit
def face_rest_margin(t, par, hdr, smp):
    """Flat on the ground with the face against the wall (face rest): the
    wall (its force anywhere on the face, never pulling) and the ground
    hold the block while G > 0 and either the d'Alembert force -a_g pushes
    it toward the wall (q = -w a_g >= 0: any tipping toward the wall or
    slide into it is blocked by the wall) or the free block would rest
    anyway (``rest_margin``: no tipping away, friction holds).  Derivation:
    equilibrium with N_near, N_far >= 0, |F| <= mu_s (N_near + N_far),
    wall forces W_base, W_top >= 0 at the base and top of the face: with
    q >= 0 the choice W_top = max(0, (q h - G b + 2 b N_far) / (2h)),
    W_base = q - W_top, F = 0 is admissible; with q < 0 the wall force is
    0 and the conditions are the free rest's.  Beside a wall lower than
    the CM the same balance with the upper wall force at the edge E would
    let a push q (h - h_w) > G (b_w + mu_s h_w) turn the block over E
    (the near corner slipping away); that motion is not modelled: the
    rest holds (a limit of the short wall)."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    q = -par[P_WALL_SIDE] * ag
    return min(G, max(q, rest_margin(t, par, hdr, smp)))


@jit
def static_margin(t, y, par, disc, hdr, smp):
    if disc[D_MODE] == MODE_WALL_REST:
        if disc[D_SLIP_DIR] == JAM:
            return wall_jam_margin(t, y, par, disc, hdr, smp)
        return wall_rest_margin(t, y, par, disc, hdr, smp)
    if disc[D_CS2] == CS_WALL_BASE:
        return face_rest_margin(t, par, hdr, smp)
    return rest_margin(t, par, hdr, smp)


# ---------------------------------------------------------------- bookkeeping
@jit
def book_time(t, disc, met):
    """Time spent in the current mode since the last bookkeeping."""
    dt = t - met[M_T_PREV]
    if dt > 0.0:
        m = disc[D_MODE]
        if m == MODE_SLIDE:
            met[M_T_SLIDE] += dt
            met[M_T_CONTACT] += dt
        elif m == MODE_REST:
            met[M_T_CONTACT] += dt
        elif m == MODE_SLIDE_ROCK:
            met[M_T_SLIDE_ROCK] += dt
        elif m == MODE_ROCK:
            met[M_T_ROCK] += dt
        elif m == MODE_FLIGHT:
            met[M_T_FLIGHT] += dt
    met[M_T_PREV] = t


@jit
def slide_of(y, par, disc):
    """Horizontal displacement of the active base contact from its rest
    position (nan in flight)."""
    m = disc[D_MODE]
    if m == MODE_FLIGHT:
        return np.nan
    if m == MODE_ROCK or m == MODE_SLIDE_ROCK or m == MODE_WALL_REST:
        j = 1 if disc[D_PIVOT] > 0 else 0
        cx, _cy = body_point(j, par)
        rx, _ry = point_offset(j, y[0], par)
        hm = hmid(par)
        return y[2] + hm * math.sin(y[0]) + rx - cx
    return y[2]


@jit
def track_slide(y, par, disc, met):
    d = slide_of(y, par, disc)
    if np.isnan(d):
        return
    if abs(d) > met[M_MAX_SLIDE]:
        met[M_MAX_SLIDE] = abs(d)
    met[M_RESIDUAL_SLIDE] = d


@jit
def track_jump(y, par, met):
    rise = y[4] + hmid(par) * (math.cos(y[0]) - 1.0)
    if rise > met[M_MAX_JUMP]:
        met[M_MAX_JUMP] = rise


@jit
def set_contacts(disc, st0, st1, st2):
    """Contact states -> mode, pivot, slip direction, static flag."""
    disc[D_CS0] = st0
    disc[D_CS1] = st1
    disc[D_CS2] = st2
    disc[D_STATIC] = 0
    disc[D_WALL_REST] = 0
    c0 = st0 != CS_OPEN
    c1 = st1 != CS_OPEN
    if c0 and c1:
        if st0 == CS_STICK and st1 == CS_STICK:
            disc[D_MODE] = MODE_REST
            disc[D_STATIC] = 1
            disc[D_SLIP_DIR] = 0
        else:
            disc[D_MODE] = MODE_SLIDE
            disc[D_SLIP_DIR] = 1 if st0 == CS_SLIP_P else -1
        return
    if c0 or c1:
        j = 1 if c1 else 0
        st = st1 if c1 else st0
        disc[D_PIVOT] = 1 if j == 1 else -1
        if st2 != CS_OPEN and st == CS_STICK:
            disc[D_MODE] = MODE_WALL_REST
            disc[D_STATIC] = 1
            disc[D_WALL_REST] = 1
            disc[D_SLIP_DIR] = 0
        elif st == CS_STICK:
            disc[D_MODE] = MODE_ROCK
            disc[D_SLIP_DIR] = 0
        else:
            disc[D_MODE] = MODE_SLIDE_ROCK
            disc[D_SLIP_DIR] = 1 if st == CS_SLIP_P else -1
        return
    disc[D_MODE] = MODE_FLIGHT
    disc[D_SLIP_DIR] = 0


@jit
def project_single(j, y, par, stick):
    """Put base corner j on the ground with zero normal velocity (and zero
    tangential velocity when it sticks)."""
    gap, vn, vt = point_kin(j, y, par)
    y[4] -= gap
    y[5] -= vn
    if stick:
        y[3] -= vt


@jit
def project_flat(y, stick):
    y[0] = 0.0
    y[1] = 0.0
    y[4] = 0.0
    y[5] = 0.0
    if stick:
        y[3] = 0.0


@jit
def mark_uplift(t, met):
    if np.isnan(met[M_T_UPLIFT]):
        met[M_T_UPLIFT] = t


@jit
def enter_flight(t, y, par, disc, met, log, cnt):
    """Flight from a contact mode: the base corners that were closed are
    put on the ground with no downward velocity (they were on it up to the
    integration error), so that no landing fires at the lift-off itself."""
    s = disc[D_PIVOT]
    for k in range(2):
        if disc[D_CS0 + k] != CS_OPEN:
            gap, vn, _vt = point_kin(k, y, par)
            y[4] -= gap
            if vn < 0.0:
                y[5] -= vn
    set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
    disc[D_PIVOT] = s
    met[M_N_FLIGHTS] += 1
    mark_uplift(t, met)
    track_jump(y, par, met)
    log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], s)
    return RUNNING


# ---------------------------------------------------------------- mode pick
@jit
def stop_slip_impulsively(j, y, par):
    """mu_k = inf: a contact that slips is stopped at once by a tangential
    (plastic, sticking) impulse with its normal velocity kept 0; this only
    dissipates.  j = 0 or 1 (one corner) or 2 (both base corners, flat)."""
    vgx, vgy = cm_velocity(y, par)
    post = np.empty(3)
    if j == 2:
        solve_contacts(y, vgx, vgy, y[1], 0.0, par, CS_STICK, CS_FREE,
                       CS_OPEN, post)
    else:
        solve_contacts(y, vgx, vgy, y[1], 0.0, par,
                       CS_STICK if j == 0 else CS_OPEN,
                       CS_STICK if j == 1 else CS_OPEN, CS_OPEN, post)
    set_cm_velocity(y, par, post[0], post[1], post[2])


@jit
def pick_flat(t, y, par, disc, hdr, smp, met, log, cnt):
    """Both base corners on the ground, theta = theta' = 0 (rest, end of a
    slide phase, flat landing, chatter): pick REST, ROCK, SLIDE_ROCK,
    SLIDE or FLIGHT by the mode solve (physics.md 4.2-4.3, 4.6).

    With the face against the wall (the wall-side base corner at the
    wall): a slip into the wall is stopped (plastic face, dissipative),
    rocking on the wall-side corner is blocked (the face would enter the
    wall), and the block rests on the ground and the wall (face rest, a
    static phase ended by ``face_rest_margin``) unless it is pulled away
    from the wall (then the free block's pick, which moves it away)."""
    _g, _vn, v = point_kin(0, y, par)
    if abs(v) <= V_TOL or not np.isfinite(par[C_MU_K]):
        v = 0.0
    at_wall = near_at_wall(y, par)
    w = par[P_WALL_SIDE]
    if at_wall and w * v > 0.0:
        v = 0.0
    project_flat(y, v == 0.0)
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    if G <= 0.0:
        return enter_flight(t, y, par, disc, met, log, cnt)
    acc = np.empty(3)
    if v != 0.0:
        sig = sign_of(v)
        st = slip_state(sig)
        ok, N0, _F0, N1, _F1, _N2, _F2 = mode_solve(t, y, par, st, st,
                                                    CS_OPEN, hdr, smp, acc)
        ntol = -UPLIFT_RTOL * (N0 + N1)
        if ok and N0 >= ntol and N1 >= ntol:
            set_contacts(disc, st, st, CS_OPEN)
            return RUNNING
        for s in (sig, -sig):
            if at_wall and s == w:
                continue
            j = 1 if s > 0 else 0
            ok, N0, _F0, N1, _F1, _N2, _F2 = mode_solve(
                t, y, par, st if j == 0 else CS_OPEN,
                st if j == 1 else CS_OPEN, CS_OPEN, hdr, smp, acc)
            N = N1 if j == 1 else N0
            if ok and N >= 0.0 and s * acc[2] > 0.0:
                set_contacts(disc, st if j == 0 else CS_OPEN,
                             st if j == 1 else CS_OPEN, CS_OPEN)
                mark_uplift(t, met)
                log_event(log, cnt, t, EV_UPLIFT, 0.0, 0.0, 0.0, s)
                return RUNNING
        if not at_wall:
            log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sig)
            return FAIL_INCONSISTENT
        # sliding away from the wall with its face at it, tipping toward
        # the wall demanded (blocked by the wall): no consistent mode; the
        # slip is stopped (plastic tangential impulse, dissipative)
        y[3] = 0.0
        v = 0.0
        log_event(log, cnt, t, EV_STICK, 0.0, 0.0, 0.0, 0)
    if at_wall and face_rest_margin(t, par, hdr, smp) >= 0.0:
        y[2] = w * par[C_GAP]
        set_contacts(disc, CS_STICK, CS_STICK, CS_WALL_BASE)
        disc[D_WALL_REST] = 1
        return RUNNING
    if rest_margin(t, par, hdr, smp) >= 0.0:
        set_contacts(disc, CS_STICK, CS_STICK, CS_OPEN)
        return RUNNING
    h = hmid(par)
    tol = 1.0 + UPLIFT_RTOL
    s = -1 if ag > 0.0 else 1
    bs = par[C_B2] if s > 0 else par[C_B1]
    j = 1 if s > 0 else 0
    if abs(ag) > G * bs / h * tol:
        # rocking demanded about s: stick-rock if friction holds
        st0 = CS_STICK if j == 0 else CS_OPEN
        st1 = CS_STICK if j == 1 else CS_OPEN
        ok, N0, F0, N1, F1, _N2, _F2 = mode_solve(t, y, par, st0, st1,
                                                  CS_OPEN, hdr, smp, acc)
        N = N1 if j == 1 else N0
        F = F1 if j == 1 else F0
        if ok and N >= 0.0 and abs(F) <= par[C_MU_S] * N:
            set_contacts(disc, st0, st1, CS_OPEN)
            mark_uplift(t, met)
            log_event(log, cnt, t, EV_UPLIFT, 0.0, 0.0, 0.0, s)
            return RUNNING
        sig = -1 if F > 0.0 else 1
        sp = sig
        jp = 1 if sp > 0 else 0
        st = slip_state(sig)
        st0 = st if jp == 0 else CS_OPEN
        st1 = st if jp == 1 else CS_OPEN
        ok, N0, _F0, N1, _F1, _N2, _F2 = mode_solve(t, y, par, st0, st1,
                                                    CS_OPEN, hdr, smp, acc)
        N = N1 if jp == 1 else N0
        _an, at = contact_acc(jp, y, par, acc)
        # slip-rock from flat rest needs mu_k h > b (the friction's moment
        # about the CM beats the normal force's: s theta'' ~ N (mu_k h -
        # b)); at mu_k = b/h exactly the block slides flat, as in
        # kernels/friction.py (mu_k > b/h), not on the rounding of theta''
        bp = par[C_B2] if jp == 1 else par[C_B1]
        hp = par[C_H2] if jp == 1 else par[C_H1]
        tips = par[C_MU_K] * hp > bp * (1.0 + UPLIFT_RTOL)
        if (ok and N >= 0.0 and sp * acc[2] > 0.0 and sig * at >= 0.0
                and tips):
            set_contacts(disc, st0, st1, CS_OPEN)
            mark_uplift(t, met)
            met[M_N_STICK_SLIP] += 1
            log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sig)
            return RUNNING
        st = slip_state(sig)
        set_contacts(disc, st, st, CS_OPEN)
        met[M_N_STICK_SLIP] += 1
        log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sig)
        return RUNNING
    # friction fails first: slide against the ground acceleration
    sig = -1 if ag > 0.0 else 1
    st = slip_state(sig)
    set_contacts(disc, st, st, CS_OPEN)
    met[M_N_STICK_SLIP] += 1
    log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sig)
    return RUNNING


@jit
def near_at_wall(y, par):
    """The wall-side base corner is at the wall (to FACE_RTOL of the
    half-width)."""
    if not wall_active(par):
        return False
    bw = par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]
    gap, _vn = near_gap(y, par)
    return gap <= FACE_RTOL * bw


@jit
def set_single(j, st, disc):
    """Base corner j alone on the ground in contact state st."""
    set_contacts(disc, st if j == 0 else CS_OPEN, st if j == 1 else CS_OPEN,
                 CS_OPEN)
    disc[D_PIVOT] = 1 if j == 1 else -1


@jit
def pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, forbid_stick):
    """``pick_single_ground``, or ``pick_wall_corner`` when j is the far
    corner and the wall-side base corner is at the wall."""
    if j != near_index(par) and near_at_wall(y, par):
        return pick_wall_corner(j, t, y, par, disc, hdr, smp, met, log, cnt,
                                forbid_stick)
    return pick_single_ground(j, t, y, par, disc, hdr, smp, met, log, cnt,
                              forbid_stick)


@jit
def velocity_scale(y, par):
    """A speed scale of the state [m/s] for rounding tolerances."""
    return abs(y[1]) * (par[C_B1] + par[C_H1]) + abs(y[3]) + abs(y[5])


@jit
def into_wall(t, y, par, disc, hdr, smp):
    """In the current mode the wall-side base corner (on the wall) moves or
    accelerates into the wall."""
    _g, vn, _vt = point_kin(K_NEAR, y, par)
    scale_v = abs(y[1]) * (par[C_B1] + par[C_H1]) + abs(y[3]) + abs(y[5])
    if vn < -1e-9 * scale_v:
        return True
    if vn > 1e-9 * scale_v:
        return False
    acc = np.empty(3)
    if disc[D_MODE] == MODE_FLIGHT:
        bx, by, bw = free_acc(t, par, hdr, smp)
        acc[0] = bx
        acc[1] = by
        acc[2] = bw
    elif disc[D_STATIC] == 1:
        return False
    else:
        mode_solve(t, y, par, disc[D_CS0], disc[D_CS1], disc[D_CS2], hdr,
                   smp, acc)
    an, _at = contact_acc(K_NEAR, y, par, acc)
    return an < -1e-12 * (par[P_G] + abs(acc[0]) + abs(acc[1]))


@jit
def pick_wall_corner(j, t, y, par, disc, hdr, smp, met, log, cnt,
                     forbid_stick):
    """Far base corner j on the ground, the wall-side base corner at the
    wall (block tilted away from the wall): the ground-only pick when it
    keeps the corner off the wall; else the wall contact closes: pivot
    sticking (the block wedged between ground and wall: a static phase,
    MODE_WALL_REST, any remaining rotation stopped, dissipative) or
    slipping (the 'ladder': the corner slides along the wall, SLIDE_ROCK
    with the wall contact CS_WALL_BASE, ended by the wall's normal force
    reaching 0, the pivot sticking, or theta reaching 0: a face impact)."""
    y0 = y.copy()
    d0 = disc.copy()
    m0 = met.copy()
    c0 = cnt.copy()
    st = pick_single_ground(j, t, y, par, disc, hdr, smp, met, log, cnt,
                            forbid_stick)
    if st != RUNNING or not into_wall(t, y, par, disc, hdr, smp):
        return st
    y[:] = y0
    disc[:] = d0
    met[:] = m0
    cnt[:] = c0
    project_single(j, y, par, False)
    _g, vnw, _vt = point_kin(K_NEAR, y, par)
    _g, _vn, vt = point_kin(j, y, par)
    if abs(vt) <= V_TOL or not np.isfinite(par[C_MU_K]):
        y[3] -= vt
        vt = 0.0
    if vnw < -1e-9 * velocity_scale(y, par):
        # the corner moves into the wall (a landing of the far corner with
        # the near one at the wall): a ladder would keep that normal
        # velocity and drive the corner into the wall (failed:face-contact);
        # it is stopped with the rest below, as a corner at rest pressed
        # into the wall (all velocities 0: plastic, dissipative)
        y[3] -= vt
        vt = 0.0
    acc = np.empty(3)
    mu = par[C_MU_S]
    fr_w = wall_frictional(par)
    if vt != 0.0:
        sig = sign_of(vt)
        st = slip_state(sig)
        stw = CS_WALL_BASE
        if fr_w:
            # the corner's slip along the wall goes with the pivot's (one
            # degree of freedom with both contacts closed)
            _g, _vnw, vtw = point_kin(K_NEAR, y, par)
            stw = wall_state(K_NEAR, 2 * sign_of(vtw))
        ok, N0, _F0, N1, _F1, N2, _F2 = mode_solve(
            t, y, par, st if j == 0 else CS_OPEN, st if j == 1 else CS_OPEN,
            stw, hdr, smp, acc)
        N = N1 if j == 1 else N0
        if ok and N >= 0.0 and N2 >= 0.0:
            set_single(j, st, disc)
            disc[D_CS2] = stw
            return RUNNING
        # no slip along the wall: the slip stops (plastic, dissipative)
        y[3] -= vt
    # pivot at rest on the ground, corner on the wall: wedged (all
    # velocities 0: dissipative) if the forces allow it
    y[1] = 0.0
    project_single(j, y, par, True)
    o = 1 - j
    gap_o, _vn, _vt = point_kin(o, y, par)
    if gap_o <= FLAT_RTOL * (par[C_B1] + par[C_B2]):
        # flat (the wall-side corner on the ground too, as a flat landing):
        # the wall and the pivot's friction are parallel there, so the
        # wedge and ladder solves are singular (zero slip acceleration:
        # stick and slip alternated at one instant); at rest now, the flat
        # pick decides (face rest while pushed toward the wall)
        return pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    st0 = CS_STICK if j == 0 else CS_OPEN
    st1 = CS_STICK if j == 1 else CS_OPEN
    ok, N0, F0, N1, F1, N2, _F2 = mode_solve(t, y, par, st0, st1,
                                             CS_WALL_BASE, hdr, smp, acc)
    N = N1 if j == 1 else N0
    F = F1 if j == 1 else F0
    wedged = ok and N >= 0.0 and N2 >= 0.0 and (abs(F) <= mu * N
                                                 or not np.isfinite(mu))
    if fr_w:
        # frictional wall: wedged while some admissible wall friction holds
        bx, by, bw = free_acc(t, par, hdr, smp)
        okl, m, _P, _N, F, _Nw = wall_stick_lp(y, bx, by, bw,
                                               y[1] * y[1], par, j, K_NEAR,
                                               0.0, acc)
        wedged = okl and m >= 0.0
    if wedged:
        set_contacts(disc, st0, st1, CS_WALL_BASE)
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[0], disc[D_PIVOT])
        return RUNNING
    if fr_w and np.isfinite(par[C_MU_K]):
        tol = 1e-12 * (par[P_G] + abs(acc[0]) + abs(acc[1]))
        if wall_ladder(j, K_NEAR, t, y, par, disc, hdr, smp, -tol):
            met[M_N_STICK_SLIP] += 1
            log_event(log, cnt, t, EV_SLIP, y[1], y[1], y[0],
                      disc[D_SLIP_DIR])
            return RUNNING
    elif np.isfinite(par[C_MU_K]):
        sig1 = -1 if F > 0.0 else 1
        for sig in (sig1, -sig1):
            st = slip_state(sig)
            ok, N0, _F0, N1, _F1, N2, _F2 = mode_solve(
                t, y, par, st if j == 0 else CS_OPEN,
                st if j == 1 else CS_OPEN, CS_WALL_BASE, hdr, smp, acc)
            N = N1 if j == 1 else N0
            _an, at = contact_acc(j, y, par, acc)
            if ok and N >= 0.0 and N2 >= 0.0 and sig * at >= -1e-12 * (
                    par[P_G] + abs(acc[0]) + abs(acc[1])):
                set_single(j, st, disc)
                disc[D_CS2] = CS_WALL_BASE
                met[M_N_STICK_SLIP] += 1
                log_event(log, cnt, t, EV_SLIP, y[1], y[1], y[0], sig)
                return RUNNING
    # neither wedged nor a ladder: where those need the pivot to pull the
    # ground (nearly flat against the wall, pushed into it: the wedge's
    # forces grow like 1 / theta), the pivot lifts off with the corner on
    # the wall; the ground-only pick would slide it into the wall, whose
    # event fired again at once (contact:2027:494, failed:transition-loop)
    if lift_off_at_wall(j, K_NEAR, t, y, par, disc, hdr, smp, met, log, cnt):
        return RUNNING
    # from rest (velocities 0 now) the ground-only pick
    return pick_single_ground(j, t, y, par, disc, hdr, smp, met, log, cnt,
                              False)


@jit
def pick_single_ground(j, t, y, par, disc, hdr, smp, met, log, cnt,
                       forbid_stick):
    """Base corner j on the ground (after an impact or landing, or at a
    stick / slip / lift event), the other one off it: pick ROCK, SLIDE_ROCK
    or FLIGHT by the mode solve (physics.md 4.2, 4.5, 4.6).

    Order: stick (N >= 0, |F| <= mu_s N; mu_s = inf: the held pivot of
    ``stick_holds``), slip from rest in sigma = -sgn F_req, then in -sigma
    (N >= 0 and the slip not reversed, sigma a_t >= 0), flight if the free
    corner does not accelerate into the ground.  With no consistent mode
    (Painleve, mu large) the pivot is held as with mu = inf (ROCK with
    D_SLIP_DIR = JAM) until the flight becomes consistent or N returns
    >= 0.  A slipping corner with no consistent mode is stopped by a
    plastic tangential impulse first (dissipative)."""
    project_single(j, y, par, False)
    _g, _vn, vt = point_kin(j, y, par)
    if vt != 0.0 and not np.isfinite(par[C_MU_K]):
        stop_slip_impulsively(j, y, par)
        project_single(j, y, par, True)
        vt = 0.0
    if abs(vt) <= V_TOL:
        y[3] -= vt
        vt = 0.0
    acc = np.empty(3)
    if vt != 0.0:
        sig = sign_of(vt)
        st = slip_state(sig)
        ok, N0, _F0, N1, _F1, _N2, _F2 = mode_solve(
            t, y, par, st if j == 0 else CS_OPEN, st if j == 1 else CS_OPEN,
            CS_OPEN, hdr, smp, acc)
        N = N1 if j == 1 else N0
        if ok and N >= 0.0:
            set_single(j, st, disc)
            return RUNNING
        if free_normal_acc(j, t, y, par, hdr, smp) >= 0.0:
            return enter_flight(t, y, par, disc, met, log, cnt)
        # Painleve: the slip has no consistent continuation; a tangential
        # impact stops it (plastic, dissipative), then pick from stick
        stop_slip_impulsively(j, y, par)
        project_single(j, y, par, True)
        forbid_stick = False
    st0 = CS_STICK if j == 0 else CS_OPEN
    st1 = CS_STICK if j == 1 else CS_OPEN
    ok, N0, F0, N1, F1, _N2, _F2 = mode_solve(t, y, par, st0, st1,
                                              CS_OPEN, hdr, smp, acc)
    N = N1 if j == 1 else N0
    F = F1 if j == 1 else F0
    if not np.isfinite(par[C_MU_S]):
        if ok and stick_holds(N, j, t, y, par, hdr, smp):
            set_single(j, CS_STICK, disc)
            return RUNNING
        return enter_flight(t, y, par, disc, met, log, cnt)
    if ok and not forbid_stick and N >= 0.0 and abs(F) <= par[C_MU_S] * N:
        set_single(j, CS_STICK, disc)
        return RUNNING
    # the cone's edge to rounding: |F| above mu_s N by 1e-12 of it
    edge = ok and not forbid_stick and N >= 0.0 and \
        abs(F) - par[C_MU_S] * N <= 1e-12 * (abs(F) + par[C_MU_S] * N)
    sig1 = -1 if F > 0.0 else 1
    if np.isfinite(par[C_MU_K]):
        for sig in (sig1, -sig1):
            st = slip_state(sig)
            ok2, N0, _F0, N1, _F1, _N2, _F2 = mode_solve(
                t, y, par, st if j == 0 else CS_OPEN,
                st if j == 1 else CS_OPEN, CS_OPEN, hdr, smp, acc)
            Ns = N1 if j == 1 else N0
            _an, at = contact_acc(j, y, par, acc)
            # (a_t = 0 up to rounding at the stick / slip boundary)
            if ok2 and Ns >= 0.0 and sig * at >= -1e-12 * (
                    par[P_G] + abs(acc[0]) + abs(acc[1])):
                if edge and sig * at < 0.0:
                    # both at the edge to rounding, and the slip would
                    # stop at once: stick and slip alternated at one
                    # instant (contact:2027:243, |F| - mu_s N = 1.2e-14 N,
                    # sigma a_t = -3e-13 m/s^2, failed:transition-loop).
                    # It sticks, and K_SLIP waits for the demand to clear
                    # the same band (EDGE)
                    set_single(j, CS_STICK, disc)
                    disc[D_SLIP_DIR] = EDGE
                    return RUNNING
                set_single(j, st, disc)
                met[M_N_STICK_SLIP] += 1
                log_event(log, cnt, t, EV_SLIP, y[1], y[1], y[0], sig)
                return RUNNING
    if free_normal_acc(j, t, y, par, hdr, smp) >= 0.0:
        return enter_flight(t, y, par, disc, met, log, cnt)
    set_single(j, CS_STICK, disc)
    disc[D_SLIP_DIR] = JAM
    return RUNNING


# ---------------------------------------------------------------- impacts
@jit
def kinetic_energy(y, par):
    vx, vy = cm_velocity(y, par)
    return 0.5 * (vx * vx + vy * vy + par[C_IG] * y[1] * y[1])


@jit
def below_rounding(y, par):
    """The kinetic energy [J/kg] is below g times the rounding of the
    centre of mass's height (eps h), the resolution of the potential
    energy in floating point: motion at that level is rounding, not
    physics.  Near an elastic wall (e_w = 1) the pivot slipped at each
    impact and stuck after it, and that cycle held its energy at this
    level for ever: 5e-9 rad/s, 2e-6 s per bounce (contact:2027:26,
    failed:step-budget)."""
    return kinetic_energy(y, par) <= par[P_G] * EPS_ROUND * hmid(par)


@jit
def corner_impact(pre, vs, s, bk, bj, h, iG, e, mu_s, mu_k):
    """(theta'+, d'+) of the ground impact from pivot s (half-width bk) onto
    the new corner -s (half-width bj) of a level base (CM height h), per
    unit mass, from theta'- = pre and the old pivot's slip velocity vs:
    kernels/friction.py's map (physics.md 4.3) with the sides apart.  A
    plastic impact with stick at the new corner, theta'+ = e theta'- +
    (h / i_0j) vs, e the restitution of this impact (the angular-momentum
    map (i_G + h^2 - bk bj) / i_0j, Housner's e for the rectangle, or a
    given one); then the impulse-ratio check, the algebraic slipping impact
    and Routh's incremental impact where the algebraic rule fails.  With
    bk = bj every operation is friction.corner_impact's (bit-identical)."""
    i0 = iG + bj * bj + h * h
    post = e * pre + (h / i0) * vs
    if vs != 0.0 and fr_kinetic(post, 0.0, -s, bj, h, iG) > \
            fr_kinetic(pre, vs, s, bk, h, iG):
        # a given e unlike the plastic one: the plastic stick (angular
        # momentum about the new corner kept), which always dissipates
        post = ((iG + h * h - bk * bj) / i0) * pre + (h / i0) * vs
    # impulses (lam_x, lam_y) of the stick impact; bk / bj = 1 exactly for
    # equal sides, so lam_y rounds as friction.py's -s b (post + pre)
    lam_x = h * post - (vs + h * pre)
    lam_y = -s * bj * (post + (bk / bj) * pre)
    dpost = 0.0
    if abs(lam_x) > mu_s * lam_y:
        sigma = -1.0 if lam_x > 0.0 else 1.0
        k = mu_k * sigma * h + s * bj
        post = pre * (iG - k * s * bk) / (iG + k * s * bj)
        lam_y = -s * bj * (post + (bk / bj) * pre)
        dpost = vs + h * pre - h * post - mu_k * sigma * lam_y
        if (sigma * dpost < 0.0 or lam_y <= 0.0
                or fr_kinetic(post, dpost, -s, bj, h, iG)
                > fr_kinetic(pre, vs, s, bk, h, iG)):
            # Routh's method with the contact velocity of the new corner,
            # (v_t, v_n) = (vs, s (bk + bj) pre)
            w11 = 1.0 + h * h / iG
            w12 = -s * bj * h / iG
            w22 = 1.0 + bj * bj / iG
            pt, pn, vt = routh_general(w11, w12, w22, vs,
                                       s * (bk + bj) * pre, mu_s, mu_k)
            post = pre + (-h * pt + s * bj * pn) / iG
            dpost = vt
    return post, dpost


@jit
def ground_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """theta reached 0 while rocking on s: ``corner_impact`` from pivot s
    onto -s (level base, h1 = h2), with the restitution of that impact
    (P_E leaving pivot +1, C_E_NEG leaving -1)."""
    s = disc[D_PIVOT]
    j_old = 1 if s > 0 else 0
    if 1 - j_old == near_index(par) and near_at_wall(y, par):
        # the block comes down flat with its face on the wall: rocking on
        # the wall-side corner is blocked, a face impact
        met[M_IMPACTS] += 1
        if par[C_GAP] == 0.0 and hogan_impact(t, y, par, disc, opt, met, log,
                                              cnt):
            return pick_after_hogan(t, y, par, disc, hdr, smp, opt, met, log,
                                    cnt)
        log_event(log, cnt, t, EV_IMPACT, y[1], 0.0, 0.0, -s)
        return face_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                           False)
    _g, _vn, vs = point_kin(j_old, y, par)
    pre = y[1]
    if s > 0:
        e = par[P_E]
        bk = par[C_B2]
        bj = par[C_B1]
    else:
        e = par[C_E_NEG]
        bk = par[C_B1]
        bj = par[C_B2]
    h = par[C_H1]
    iG = par[C_IG]
    met[M_IMPACTS] += 1
    chatter = t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    post, dpost = corner_impact(pre, vs, s, bk, bj, h, iG, e, par[C_MU_S],
                                par[C_MU_K])
    check_energy(fr_kinetic(pre, vs, s, bk, h, iG),
                 fr_kinetic(post, dpost, -s, bj, h, iG), met)
    log_event(log, cnt, t, EV_IMPACT, pre, post, 0.0, -s)
    # new pivot -s: theta = 0, its velocity (dpost, 0)
    j = 1 - j_old
    y[0] = 0.0
    y[1] = post
    rx, ry = point_offset(j, 0.0, par)
    hm = hmid(par)
    # v_G = v_c - theta' (ry, -rx)
    vgx = dpost - post * ry
    set_cm_velocity(y, par, vgx, post * rx, post)
    y[4] = -(ry + hm)
    if abs(post) < opt[O_EPS_OMEGA] or chatter:
        # the rest rule stops the rotation and keeps the new corner's slip
        # velocity, unless that exceeds the CM's horizontal speed (a slip
        # against the spin's share of v_Gx): then the CM's velocity, so the
        # rule never adds energy
        y[1] = 0.0
        y[3] = dpost if abs(dpost) <= abs(vgx) else vgx
        st = pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, post, 0.0, 0.0, 0)
        return st
    disc[D_PIVOT] = -s
    if dpost != 0.0:
        st = slip_state(1 if dpost > 0.0 else -1)
        set_contacts(disc, st if j == 0 else CS_OPEN,
                     st if j == 1 else CS_OPEN, CS_OPEN)
        disc[D_PIVOT] = -s
        return RUNNING
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def hogan_impact(t, y, par, disc, opt, met, log, cnt):
    """Gap 0 (Hogan 1992, kernels/wall.py's combined impact): rocking on
    the far corner back to theta = 0, the wall-side base corner meets the
    ground and the wall together; the pivot is kept, theta'+ = -e_w
    theta'-, and its slip velocity too.  Returns False (y untouched) where
    that map does not apply: the pivot slipping toward the wall (the face
    arrives moving into it), or the slip's share of the kinetic energy
    making the map gain energy (theta' and the slip of opposite senses);
    the caller then takes the face impact (plastic, dissipative)."""
    s = disc[D_PIVOT]
    j = 1 if s > 0 else 0
    _g, _vn, vs = point_kin(j, y, par)
    if abs(vs) <= V_TOL or not np.isfinite(par[C_MU_K]):
        vs = 0.0
    if par[P_WALL_SIDE] * vs > 0.0:
        return False
    before = kinetic_energy(y, par)
    pre = y[1]
    post = -par[P_E_W] * pre
    rx, ry = point_offset(j, 0.0, par)
    tmp = y.copy()
    tmp[0] = 0.0
    set_cm_velocity(tmp, par, vs - post * ry, post * rx, post)
    tmp[4] = -(ry + hmid(par))
    # a sticking pivot: Hogan's map scales the rotation's energy by e_w^2
    # (tested on the slipping pivot only: with e_w = 1 the rounding of
    # ``before``, whose pivot velocity is the integration drift, not 0,
    # turned every impact into a face impact)
    after = kinetic_energy(tmp, par)
    if vs != 0.0 and after > before:
        return False
    bj = par[C_B2] if j == 1 else par[C_B1]
    R2 = bj * bj + par[C_H1] * par[C_H1]
    if vs == 0.0:
        # the pre-impact energy of the rotation about the resting pivot
        before = 0.5 * pre * pre * (par[C_IG] + R2)
    check_energy(before, after, met)
    y[:] = tmp
    met[M_WALL_IMPACTS] += 1
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, post, 0.0, s)
    # chatter, or an elastic bounce below the resolution (the wall
    # model's rule: e_w = 1 never shortens the bounces): the rotation stops
    R = math.sqrt(R2)
    rebound = 0.5 * post * post * (par[C_IG] + R2) / (par[P_G] * R)
    chatter = t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    if (chatter or abs(post) < opt[O_EPS_OMEGA]
            or elastic_below_resolution(par[P_E_W], rebound,
                                        1.0 - math.cos(alpha_of(s, par)),
                                        opt)):
        y[1] = 0.0
        y[3] = vs
    return True


@jit
def pick_after_hogan(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """The mode after ``hogan_impact``: rocking on on the same pivot, or,
    with the rotation stopped, the flat pick (face rest)."""
    if y[1] == 0.0:
        st = pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, 0.0, 0.0, 0.0, 0)
        return st
    j = 1 if disc[D_PIVOT] > 0 else 0
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def landing(j, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """Base corner j reached the ground moving down in flight (physics.md
    4.6): plastic normal impact with Coulomb friction at j (stick if
    |L_t| <= mu_s L_n, else Routh's slipping impact), or the flat two-point
    landing when the other corner is on the ground and would penetrate.
    Then the mode is picked again."""
    iG = par[C_IG]
    before = kinetic_energy(y, par)
    vgx, vgy = cm_velocity(y, par)
    om = y[1]
    met[M_IMPACTS] += 1
    met[M_T_LAST_IMPACT] = t
    post = np.empty(3)
    separates = False
    st0 = CS_STICK if j == 0 else CS_OPEN
    st1 = CS_STICK if j == 1 else CS_OPEN
    ok, N0, F0, N1, F1, _N2, _F2 = solve_contacts(
        y, vgx, vgy, om, 0.0, par, st0, st1, CS_OPEN, post)
    Ln = N1 if j == 1 else N0
    Lt = F1 if j == 1 else F0
    if not (ok and Ln >= 0.0 and (abs(Lt) <= par[C_MU_S] * Ln
                                  or not np.isfinite(par[C_MU_S]))):
        rx, ry = point_offset(j, y[0], par)
        # contact-space inverse inertia for (t, n) = ((1, 0), (0, 1))
        wtt = 1.0 + ry * ry / iG
        wtn = -ry * rx / iG
        wnn = 1.0 + rx * rx / iG
        _gap, vn, vt = point_kin(j, y, par)
        if np.isfinite(par[C_MU_S]):
            pt, pn, _vt = routh_general(wtt, wtn, wnn, vt, vn, par[C_MU_S],
                                   par[C_MU_K])
        else:
            # mu = inf and the stick impulse would pull (L_n < 0): the
            # tangential impulse alone stops the slip, after which the
            # corner leaves the ground (v_n+ = -(Schur) L_n > 0): plastic,
            # dissipative
            pt = -vt / wtt
            pn = 0.0
        post[0] = vgx + pt
        post[1] = vgy + pn
        post[2] = om + (ry * pt - rx * pn) / iG
        vn_post = vn + wtn * pt + wnn * pn
        separates = vn_post > 1e-9 * abs(vn)
    # the other corner: on the ground and penetrating -> flat landing; or
    # reaching it together with j (a flat base coming down: a two-point
    # impact, whichever corner's event fired first, so that mirror images
    # land alike)
    o = 1 - j
    bw = par[C_B1] + par[C_B2]
    _g, vn_o_pre, _vt = point_kin(o, y, par)
    tmp = y.copy()
    set_cm_velocity(tmp, par, post[0], post[1], post[2])
    gap_o, vn_o, _vt_o = point_kin(o, tmp, par)
    flat = gap_o <= FLAT_RTOL * bw and (vn_o < 0.0 or vn_o_pre < 0.0)
    if flat:
        _g, _vn, vt = point_kin(0, y, par)
        ok, N0, F0, N1, F1, _N2, _F2 = solve_contacts(
            y, vgx, vgy, om, 0.0, par, CS_STICK, CS_FREE, CS_OPEN, post)
        if not (ok and N0 >= 0.0 and N1 >= 0.0 and
                (abs(F0) <= par[C_MU_S] * (N0 + N1)
                 or not np.isfinite(par[C_MU_S]))):
            sig = sign_of(vt) if vt != 0.0 else (-1 if F0 > 0.0 else 1)
            st = slip_state(sig)
            stick_post = post.copy()
            ok2, N0, F0, N1, F1, _N2, _F2 = solve_contacts(
                y, vgx, vgy, om, 0.0, par, st, st, CS_OPEN, post)
            tmp2 = y.copy()
            set_cm_velocity(tmp2, par, post[0], post[1], post[2])
            _g, _vn, vt2 = point_kin(0, tmp2, par)
            if not (ok2 and N0 >= 0.0 and N1 >= 0.0) or sig * vt2 < 0.0:
                # slip would reverse inside the impact: it ends sticking
                for i in range(3):
                    post[i] = stick_post[i]
    set_cm_velocity(y, par, post[0], post[1], post[2])
    after = kinetic_energy(y, par)
    check_energy(before, after, met)
    log_event(log, cnt, t, EV_CONTACT, om, y[1], y[0], 1 if j == 1 else -1)
    if flat:
        st = pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, om, 0.0, 0.0, 0)
        return st
    if separates:
        # the corner leaves the ground again: the flight goes on
        return RUNNING
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def landing_at_wall(j, t, y, par, met, log, cnt):
    """Base corner j lands at zero speed (to rounding) in flight while wall
    point 2 (the top corner, or a short wall's edge) is held on a
    frictionless wall: a plastic impact at both contacts solved together
    (physics.md 4.6, the wall as a contact point): the normal velocities of
    j and of the wall point to 0, j sticking if |L_t| <= mu_s L_n, else
    slipping in its pre-impact direction (L_t = -mu_k sigma L_n, the slip
    not reversed); admissible with both normal impulses >= 0 and no kinetic
    energy gained.  Then ``pick_at_wall`` keeps both contacts closed.

    A landing with speed is the corner's impulse alone, and a wall impact
    follows if it drives the wall point into the wall: impacts alternating
    at one instant, which converge to the joint impact (projected
    Gauss-Seidel) unless they reach zero speed first.  There nothing is
    left to dissipate, and no single-contact mode need be admissible: the
    ground alone needed N < 0, the flight along the wall drove the corner
    into the ground and free flight the point into the wall, while the
    two-contact mode (the ladder) was admissible; flight, wall impact, wall
    rest and landing repeated at one instant until the step budget
    (contact:2027:430).  Returns False, nothing changed, for a landing with
    speed or where the joint impact is not admissible (the landing is then
    the corner's alone, ``landing``)."""
    mu_s = par[C_MU_S]
    if wall_frictional(par) or not np.isfinite(mu_s):
        return False
    _g, vn, vt = point_kin(j, y, par)
    if vn < -1e-9 * velocity_scale(y, par):
        return False
    before = kinetic_energy(y, par)
    vgx, vgy = cm_velocity(y, par)
    om = y[1]
    post = np.empty(3)
    st = CS_STICK
    ok, N0, F0, N1, F1, N2, _F2 = solve_contacts(
        y, vgx, vgy, om, 0.0, par, st if j == 0 else CS_OPEN,
        st if j == 1 else CS_OPEN, CS_FREE, post)
    Ln = N1 if j == 1 else N0
    Lt = F1 if j == 1 else F0
    stick = ok and Ln >= 0.0 and N2 >= 0.0 and abs(Lt) <= mu_s * Ln
    if not stick:
        if vt == 0.0:
            return False
        st = slip_state(sign_of(vt))
        ok, N0, F0, N1, F1, N2, _F2 = solve_contacts(
            y, vgx, vgy, om, 0.0, par, st if j == 0 else CS_OPEN,
            st if j == 1 else CS_OPEN, CS_FREE, post)
        Ln = N1 if j == 1 else N0
        if not (ok and Ln >= 0.0 and N2 >= 0.0):
            return False
    after, tmp = post_energy(y, par, post)
    if not after <= before * (1.0 + 1e-12):
        return False
    _g, _vn, vt2 = point_kin(j, tmp, par)
    if not stick and sign_of(vt) * vt2 < 0.0:
        return False
    y[:] = tmp
    met[M_IMPACTS] += 1
    met[M_T_LAST_IMPACT] = t
    check_energy(before, after, met)
    if stick:
        y[3] -= vt2
    log_event(log, cnt, t, EV_CONTACT, om, y[1], y[0], 1 if j == 1 else -1)
    return True


@jit
def pick_at_wall(j, t, y, par, disc, hdr, smp, met, log, cnt):
    """Base corner j on the ground and wall point 2 at the wall, both
    normal velocities 0 (after ``landing_at_wall``): at rest if j does not
    slip (``settle_on_wall``: one degree of freedom, the slip), else the
    ladder (SLIDE_ROCK with the wall contact closed) where its mode solve is
    admissible (both normal forces >= 0; a slip not at rest cannot
    reverse), else the ground-only pick."""
    s = 1 if j == 1 else -1
    disc[D_PIVOT] = s
    project_single(j, y, par, False)
    _g, _vn, vt = point_kin(j, y, par)
    if abs(vt) <= V_TOL:
        return settle_on_wall(j, t, y, par, disc, hdr, smp, met, log, cnt)
    st = slip_state(sign_of(vt))
    st0 = st if j == 0 else CS_OPEN
    st1 = st if j == 1 else CS_OPEN
    acc = np.empty(3)
    ok, N0, _F0, N1, _F1, N2, _F2 = mode_solve(t, y, par, st0, st1, CS_FREE,
                                               hdr, smp, acc)
    N = N1 if j == 1 else N0
    if ok and N >= 0.0 and N2 >= 0.0:
        set_contacts(disc, st0, st1, CS_FREE)
        return RUNNING
    set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
    disc[D_PIVOT] = s
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def settle_on_wall(j, t, y, par, disc, hdr, smp, met, log, cnt):
    """Pivot j (disc[D_PIVOT]) comes to rest with the top corner at the
    wall (all velocities 0: dissipative): resting on the wall if the
    sticking rest is admissible, else the ladder from rest, else the
    pivot's lift-off along the wall (mu = inf), else the ground-only
    pick."""
    s = disc[D_PIVOT]
    y[1] = 0.0
    project_single(j, y, par, True)
    disc[D_PIVOT] = s
    if wall_rest_margin(t, y, par, disc, hdr, smp) >= 0.0:
        set_contacts(disc, CS_STICK if j == 0 else CS_OPEN,
                     CS_STICK if j == 1 else CS_OPEN, CS_FREE)
        disc[D_PIVOT] = s
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[0], s)
        return RUNNING
    if top_ladder(j, t, y, par, disc, hdr, smp):
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[0], s)
        return RUNNING
    if tip_off_pivot(j, t, y, par, disc, hdr, smp, met, log, cnt):
        return RUNNING
    if wall_rest_at_cone(j, t, y, par, disc, hdr, smp):
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[0], s)
        return RUNNING
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


# ---------------------------------------------------------------- wall
@jit
def wall_rest_margin(t, y, par, disc, hdr, smp):
    """Resting on the wall (either pivot, sticking, disc[D_PIVOT]): the phase
    holds while the wall's normal force and the pivot's are >= 0 and the
    pivot sticks (mode solve with the wall contact closed)."""
    te = np.inf if t >= excitation_end(hdr) else t
    acc = np.empty(3)
    j = 1 if disc[D_PIVOT] > 0 else 0
    st0 = CS_STICK if j == 0 else CS_OPEN
    st1 = CS_STICK if j == 1 else CS_OPEN
    bx, by, bw = free_acc(te, par, hdr, smp)
    st2 = CS_WALL_BASE if disc[D_CS2] == CS_WALL_BASE else CS_FREE
    if wall_frictional(par):
        # a frictional wall: its tangential force is indeterminate, the
        # rest holds while some admissible one exists (``wall_stick_lp``)
        kw = K_NEAR if st2 == CS_WALL_BASE else 2
        ok, m, _P, _N, _F, _Nw = wall_stick_lp(y, bx, by, bw, 0.0, par, j,
                                               kw, 0.0, acc)
        if not ok:
            return -1.0
        return m
    ok, N0, F0, N1, F1, N2, _F2 = solve_contacts(
        y, bx, by, bw, 0.0, par, st0, st1, st2, acc)
    N = N1 if j == 1 else N0
    F = F1 if j == 1 else F0
    mu = par[C_MU_S]
    if np.isfinite(mu):
        m = min(N2, N, mu * N - abs(F))
    else:
        # mu = inf holds the pivot as in a rocking phase (K_LIFT): it lets
        # go only where the flight is consistent, here the flight along the
        # wall (``tip_off_pivot``).  A rest whose pivot needs a pull, with
        # that flight inconsistent, is otherwise no mode at all: the body
        # rocked back into the wall and repeated zero-velocity wall impacts
        # for ever (contact:14:0, a body leaning over a short wall's edge)
        m = min(N2, N)
        if N < 0.0:
            # only then can -a_n decide (for N >= 0 the margin has the sign
            # of min(N2, N) either way): no second mode solve per margin
            # evaluation while the pivot pushes
            an, _N2f = flight_wall_normal_acc(j, 2, t, y, par, hdr, smp)
            if np.isfinite(an):
                m = min(N2, max(N, -an))
    if not ok:
        return -1.0
    return m


@jit
def wall_stick_lp(y, bx, by, bw, om2, par, j, kw, tgt2, acc):
    """Base corner j sticking on the ground and wall point kw (2 or K_NEAR)
    closed on a frictional wall (mu_w > 0): three constraints fix the
    motion, the four forces (N, F at the pivot, N_w, F_w at the wall) are
    statically indeterminate.  With the wall's tangential force F_w = P
    given, the mode solve (the wall row normal only, P added to the free
    acceleration ``b``) gives N, F, N_w affine in P; the margin is the
    largest over P of the least of N, N_w, mu_s N -+ F (finite mu_s) and
    mu_w N_w -+ P, a 1-D linear program solved exactly (the maximum of a
    concave piecewise-linear function: at P = 0, at a crossing of two of
    the lines, or its limit where every line is nondecreasing one way;
    capped at cap).  The same routine serves the impulse form (b: the
    pre-impact velocity, om2 = 0, tgt2: the wall's target velocity): the
    motion (``acc``) does not depend on P.  Returns (ok, margin, P, N, F,
    N_w): P the admissible wall force closest to 0 if there is one (else
    the maximiser).  P is along the wall contact's tangent (``geom``)."""
    st0 = CS_STICK if j == 0 else CS_OPEN
    st1 = CS_STICK if j == 1 else CS_OPEN
    stw = wall_state(kw, 0)
    iG = par[C_IG]
    rx, ry, _nx, _ny, tx, ty = geom(kw, y, par)
    # the response to a unit tangential wall force along the wall's tangent
    # t, i.e. the free acceleration (dx, dy, dw) = (t_x, t_y, j_t / iG), alone
    # (the system is linear: solved on its own, not as a difference of two
    # solves)
    tmp = np.empty(3)
    ok1, N0, F0, N1, F1, bW, _F2 = solve_targets(
        y, tx, ty, (ry * tx - rx * ty) / iG, 0.0, par, st0, st1, stw, 0.0,
        tmp)
    bN = N1 if j == 1 else N0
    bF = F1 if j == 1 else F0
    ok, N0, F0, N1, F1, Nw, _F2 = solve_targets(
        y, bx, by, bw, om2, par, st0, st1, stw, tgt2, acc)
    aN = N1 if j == 1 else N0
    aF = F1 if j == 1 else F0
    if not (ok and ok1):
        return False, -1.0, 0.0, aN, aF, Nw
    mu_s = par[C_MU_S]
    mu_w = par[C_MU_W]
    A = np.empty(6)
    B = np.empty(6)
    A[0] = aN
    B[0] = bN
    A[1] = Nw
    B[1] = bW
    A[2] = mu_w * Nw
    B[2] = mu_w * bW - 1.0
    A[3] = mu_w * Nw
    B[3] = mu_w * bW + 1.0
    n = 4
    if np.isfinite(mu_s):
        A[4] = mu_s * aN - aF
        B[4] = mu_s * bN - bF
        A[5] = mu_s * aN + aF
        B[5] = mu_s * bN + bF
        n = 6
    cap = abs(bx) + abs(by) + abs(bw) * (par[C_B1] + par[C_H1]) + abs(tgt2)
    best = -np.inf
    pbest = 0.0
    # beyond every crossing of two lines and every zero of a line
    far = 1.0 + cap
    for ic in range(n):
        if B[ic] != 0.0:
            far = max(far, 2.0 * abs(A[ic] / B[ic]))
        for k in range(ic + 1, n):
            if B[ic] != B[k]:
                far = max(far, 2.0 * abs((A[ic] - A[k]) / (B[k] - B[ic])))
    for d in (1.0, -1.0):
        # every line nondecreasing toward d: the supremum is the least
        # level of the flat ones (or unbounded: capped)
        up = True
        lim = np.inf
        for i in range(n):
            if B[i] * d < 0.0:
                up = False
            elif B[i] == 0.0:
                lim = min(lim, A[i])
        if up:
            lim = min(lim, cap)
            if lim > best:
                best = lim
                # beyond every crossing and zero: the rising lines are
                # positive and above the flat ones (the limit, or the cap)
                pbest = d * far
    for ic in range(-1, n):
        for k in range(ic + 1, n):
            if ic < 0:
                P = 0.0
            else:
                if B[ic] == B[k]:
                    continue
                P = (A[ic] - A[k]) / (B[k] - B[ic])
            v = np.inf
            for i in range(n):
                v = min(v, A[i] + B[i] * P)
            if v > best:
                best = v
                pbest = P
            if ic < 0:
                break
    best = min(best, cap)
    if best >= 0.0:
        # the forces reported: the admissible P closest to 0 (every line
        # >= 0 on [lo, hi]), the least internal force (a wedge's
        # indeterminate forces can be large)
        lo = -np.inf
        hi = np.inf
        for i in range(n):
            if B[i] > 0.0:
                lo = max(lo, -A[i] / B[i])
            elif B[i] < 0.0:
                hi = min(hi, -A[i] / B[i])
        if lo <= hi:
            pbest = min(max(0.0, lo), hi)
    return True, best, pbest, aN + bN * pbest, aF + bF * pbest, \
        Nw + bW * pbest


@jit
def post_energy(y, par, post):
    tmp = y.copy()
    set_cm_velocity(tmp, par, post[0], post[1], post[2])
    return kinetic_energy(tmp, par), tmp


@jit
def wall_pivot_impact(j, y, par, vgx, vgy, tgt, before, post, kw=2):
    """Wall impact while base corner j is on the ground with Coulomb
    friction mu_s, mu_k (finite): the wall's post-impact normal velocity is
    tgt = -e_w v_n-, the pivot's normal velocity stays 0 and its tangential
    impulse obeys Coulomb.  Candidates, the first admissible one wins:
    stick (L_n >= 0, |L_t| <= mu_s L_n), slip in sigma (the pre-impact
    slip direction, or -sgn L_t of the stick solve from rest; L_t = -mu_k
    sigma L_n, L_n >= 0, the slip not reversed), separation (the wall
    impulse alone, admissible when the pivot then leaves the ground); each
    must not raise the kinetic energy.  Else the sequential impact: the
    wall impulse alone, then the plastic frictional impact of the pivot
    (Routh), both dissipative.  Returns True when the pivot separates.

    A tall-wall impact before the block passes its own instability
    (theta_w < alpha) needs a pulling pivot impulse to keep the pivot down
    (the CM, moving up, must reverse): no friction can provide it, and the
    pivot separates.  kw: the wall point (2 top corner, K_NEAR the
    wall-side base corner)."""
    stw = CS_WALL_BASE if kw == K_NEAR else CS_FREE
    mu_s = par[C_MU_S]
    mu_k = par[C_MU_K]
    th = y[0]
    om = y[1]
    _g, _vn, vt0 = point_kin(j, y, par)
    tol = before * (1.0 + 1e-12) + 1e-300
    ok, N0, F0, N1, F1, N2, _F2 = solve_targets(
        y, vgx, vgy, om, 0.0, par, CS_STICK if j == 0 else CS_OPEN,
        CS_STICK if j == 1 else CS_OPEN, stw, tgt, post)
    N = N1 if j == 1 else N0
    F = F1 if j == 1 else F0
    if ok and N >= 0.0 and N2 >= 0.0 and abs(F) <= mu_s * N:
        E, _tmp = post_energy(y, par, post)
        if E <= tol:
            return False
    if abs(vt0) > V_TOL:
        sig = sign_of(vt0)
    else:
        sig = -1 if F > 0.0 else 1
    cand = np.empty(3)
    st = slip_state(sig)
    ok, N0, _F0, N1, _F1, N2, _F2 = solve_targets(
        y, vgx, vgy, om, 0.0, par, st if j == 0 else CS_OPEN,
        st if j == 1 else CS_OPEN, stw, tgt, cand)
    N = N1 if j == 1 else N0
    if ok and N >= 0.0 and N2 >= 0.0:
        E, tmp = post_energy(y, par, cand)
        _g, _vn, vt1 = point_kin(j, tmp, par)
        if E <= tol and sig * vt1 >= 0.0:
            for i in range(3):
                post[i] = cand[i]
            return False
    solve_targets(y, vgx, vgy, om, 0.0, par, CS_OPEN, CS_OPEN, stw, tgt,
                  cand)
    E, tmp = post_energy(y, par, cand)
    _g, vn1, vt1 = point_kin(j, tmp, par)
    for i in range(3):
        post[i] = cand[i]
    if vn1 >= 0.0:
        return True
    # sequential impulses (projected Gauss-Seidel): the pivot approaches
    # after the wall impulse alone; alternate plastic frictional impacts of
    # the pivot (Routh) and plastic wall impacts while either contact
    # approaches.  Each one is a single-contact impulse that pushes, stays
    # in its Coulomb cone and dissipates, so the sum does too.
    rx, ry = point_offset(j, th, par)
    iG = par[C_IG]
    wtt = 1.0 + ry * ry / iG
    wtn = -ry * rx / iG
    wnn = 1.0 + rx * rx / iG
    rwx, rwy, nwx, nwy, _tx, _ty = geom(kw, y, par)
    jw = rwy * nwx - rwx * nwy
    ww = nwx * nwx + nwy * nwy + jw * jw / iG
    scale = math.sqrt(2.0 * before) + 1e-300
    for _it in range(200):
        tmp = y.copy()
        set_cm_velocity(tmp, par, post[0], post[1], post[2])
        _g, vn1, vt1 = point_kin(j, tmp, par)
        if vn1 < 0.0:
            pt, pn, _vt = routh_general(wtt, wtn, wnn, vt1, vn1, mu_s, mu_k)
            post[0] += pt
            post[1] += pn
            post[2] += (ry * pt - rx * pn) / iG
            set_cm_velocity(tmp, par, post[0], post[1], post[2])
        _g, vn2, _vt2 = point_kin(kw, tmp, par)
        if vn2 >= -1e-12 * scale:
            break
        pw = -vn2 / ww
        post[0] += nwx * pw
        post[1] += nwy * pw
        post[2] += jw * pw / iG
    return False


@jit
def routh_more(wtt, wtn, wnn, vt, vn, mu_s, mu_k, dp):
    """Routh's incremental point impact (as kernels/friction.routh_general)
    continued by a further normal impulse dp >= 0 whatever v_n does (the
    restitution phase of Poisson's rule): slipping against v_t, sticking
    when v_t reaches 0 if mu_s holds, else slipping the other way.  Returns
    (pt, pn, vt, vn)."""
    pt = 0.0
    pn = 0.0
    left = dp
    for _phase in range(4):
        if not left > 0.0:
            break
        if vt == 0.0 and abs(wtn) <= mu_s * wtt:
            rate_t = -wtn / wtt
            at = 0.0
            an = wnn - wtn * wtn / wtt
        else:
            if vt == 0.0:
                sig = 1.0 if wtn > 0.0 else -1.0
            else:
                sig = 1.0 if vt > 0.0 else -1.0
            rate_t = -mu_k * sig
            at = rate_t * wtt + wtn
            an = rate_t * wtn + wnn
        d = left
        if vt * at < 0.0 and -vt / at < d:
            d = -vt / at
            pt += rate_t * d
            pn += d
            vn += an * d
            vt = 0.0
            left -= d
            continue
        pt += rate_t * d
        pn += d
        vt += at * d
        vn += an * d
        left = 0.0
    return pt, pn, vt, vn


@jit
def point_inertia(k, y, par):
    """Contact-space inverse inertia (per unit mass) of point k in its
    (t, n) frame in state y: (wtt, wtn, wnn, jt, jn) with j = r_y d_x -
    r_x d_y the rotation column (theta' clockwise) of direction d."""
    iG = par[C_IG]
    rx, ry, nx, ny, tx, ty = geom(k, y, par)
    jt = ry * tx - rx * ty
    jn = ry * nx - rx * ny
    return (tx * tx + ty * ty + jt * jt / iG, tx * nx + ty * ny + jt * jn / iG,
            nx * nx + ny * ny + jn * jn / iG, jt, jn)


@jit
def point_impulse(k, y, par, post, e, mu_s, mu_k, imp, i0):
    """Frictional impact of point k alone, starting from the CM velocity
    post (v_Gx, v_Gy, theta'), updated in place: Routh's plastic
    compression to v_n = 0, then (e > 0) Poisson's restitution phase, a
    further normal impulse e times the compression's, with the same
    Coulomb rules (``routh_more``).  Poisson's rule with friction can add
    energy where the slip reverses (Stronge, Impact Mechanics, 2000, ch.
    5), and a slip that cannot raise v_n would end it still approaching:
    the restitution phase is then dropped (plastic).  imp[i0],
    imp[i0 + 1] += (normal, tangential) impulse.  Nothing happens when
    the point does not approach."""
    tmp = y.copy()
    set_cm_velocity(tmp, par, post[0], post[1], post[2])
    _g, vn, vt = point_kin(k, tmp, par)
    if not vn < 0.0:
        return
    wtt, wtn, wnn, jt, jn = point_inertia(k, tmp, par)
    _rx, _ry, nx, ny, tx, ty = geom(k, tmp, par)
    iG = par[C_IG]
    pt, pn, vt1 = routh_general(wtt, wtn, wnn, vt, vn, mu_s, mu_k)
    if e > 0.0 and pn > 0.0:
        pt2, pn2, _vt2, vn2 = routh_more(wtt, wtn, wnn, vt1, 0.0, mu_s,
                                         mu_k, e * pn)
        # kinetic energy change of an impulse P: v.P + P.W.P / 2
        dt_ = pt + pt2
        dn_ = pn + pn2
        dE = (vt * dt_ + vn * dn_
              + 0.5 * (wtt * dt_ * dt_ + 2.0 * wtn * dt_ * dn_
                       + wnn * dn_ * dn_))
        if dE <= 0.0 and vn2 >= 0.0:
            pt = dt_
            pn = dn_
    post[0] += tx * pt + nx * pn
    post[1] += ty * pt + ny * pn
    post[2] += (jt * pt + jn * pn) / iG
    imp[i0] += pn
    imp[i0 + 1] += pt


@jit
def wall_pivot_impact_fr(j, y, par, vgx, vgy, tgt, before, post, kw, imp):
    """``wall_pivot_impact`` on a frictional wall (mu_w > 0): the wall
    point kw's tangential impulse P_t obeys Coulomb with mu_w, P_n >= 0.
    Candidates, the first admissible one that does not raise the kinetic
    energy wins:
      1. pivot sticking: the motion is the frictionless wall's (three
         constraints), the impulses are indeterminate and admissible if
         some P_t in the cone makes the pivot's admissible
         (``wall_stick_lp``);
      2. pivot slipping in sigma (pre-impact slip direction, else -sgn L_t
         of 1) with the wall point sticking (|P_t| <= mu_w P_n), then
         slipping in sigma_w (pre-impact direction, else -sgn P_t of the
         sticking solve), then in -sigma_w; neither slip reversed;
      3. separation: the wall's frictional impact alone
         (``point_impulse``), admissible when the pivot then leaves the
         ground;
      4. else sequential plastic frictional impulses of the pivot and the
         wall point (Routh each, dissipative) while either approaches.
    imp receives (L_n, L_t) of the pivot and (P_n, P_t) of the wall (per
    unit mass; P_t along the wall contact's tangent, (0, 1) for a tall
    wall).  Returns True when the pivot separates."""
    mu_s = par[C_MU_S]
    mu_k = par[C_MU_K]
    mu_w = par[C_MU_W]
    om = y[1]
    for i in range(4):
        imp[i] = 0.0
    _g, _vn, vt0 = point_kin(j, y, par)
    _g, _vnw, vtw0 = point_kin(kw, y, par)
    tol = before * (1.0 + 1e-12) + 1e-300
    okl, m, P, N, F, Nw = wall_stick_lp(y, vgx, vgy, om, 0.0, par, j, kw,
                                        tgt, post)
    if okl and m >= 0.0:
        E, _tmp = post_energy(y, par, post)
        if E <= tol:
            imp[0] = N
            imp[1] = F
            imp[2] = Nw
            imp[3] = P
            return False
    if abs(vt0) > V_TOL:
        sig = sign_of(vt0)
    else:
        sig = -1 if F > 0.0 else 1
    st = slip_state(sig)
    st0 = st if j == 0 else CS_OPEN
    st1 = st if j == 1 else CS_OPEN
    cand = np.empty(3)
    sw = sign_of(vtw0)
    for c in range(3):
        wm = 1 if c == 0 else (2 * sw if c == 1 else -2 * sw)
        ok, N0, F0, N1, F1, N2, F2 = solve_targets(
            y, vgx, vgy, om, 0.0, par, st0, st1, wall_state(kw, wm), tgt,
            cand)
        if c == 0 and abs(vtw0) <= V_TOL:
            sw = -1 if F2 > 0.0 else 1
        N = N1 if j == 1 else N0
        F = F1 if j == 1 else F0
        if not (ok and N >= 0.0 and N2 >= 0.0):
            continue
        if c == 0 and abs(F2) > mu_w * N2:
            continue
        E, tmp = post_energy(y, par, cand)
        _g, _vn, vt1 = point_kin(j, tmp, par)
        _g, _vn, vtw1 = point_kin(kw, tmp, par)
        if E <= tol and sig * vt1 >= 0.0 and (c == 0 or
                                              (wm // 2) * vtw1 >= 0.0):
            for i in range(3):
                post[i] = cand[i]
            imp[0] = N
            imp[1] = F
            imp[2] = N2
            imp[3] = F2
            return False
    post[0] = vgx
    post[1] = vgy
    post[2] = om
    # the wall's impulse alone: the normal target is -e_w v_n- (tgt)
    _g, vnw, _vt = point_kin(kw, y, par)
    e_w = -tgt / vnw if vnw < 0.0 else 0.0
    point_impulse(kw, y, par, post, e_w, mu_w, mu_w, imp, 2)
    tmp = y.copy()
    set_cm_velocity(tmp, par, post[0], post[1], post[2])
    _g, vn1, _vt1 = point_kin(j, tmp, par)
    if vn1 >= 0.0:
        return True
    # sequential impulses (projected Gauss-Seidel), each a plastic
    # frictional point impact (Routh): pushing, in its cone, dissipative;
    # it ends with the pivot's impulse, so only the wall point can keep a
    # residual approach (below 1e-12 of the speed scale) unless the
    # iteration cap is reached (slow where friction nearly jams the pivot)
    scale = math.sqrt(2.0 * before) + 1e-300
    for _it in range(PGS_MAX):
        point_impulse(j, y, par, post, 0.0, mu_s, mu_k, imp, 0)
        set_cm_velocity(tmp, par, post[0], post[1], post[2])
        _g, vn2, _vt2 = point_kin(kw, tmp, par)
        if vn2 >= -1e-12 * scale:
            break
        point_impulse(kw, y, par, post, 0.0, mu_w, mu_w, imp, 2)
    return False


@jit
def face_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt, count_wall):
    """The block arrives flat with its face at the wall (slid flat into it,
    or rocked / flew down flat onto the ground with the wall-side base
    corner at the wall): a face impact.  The face is a line contact with
    the wall (its resultant anywhere between the base and the top corner)
    and the base a line contact with the ground, so the impulse is
    statically indeterminate; the rule: the block ends flat (theta =
    theta' = 0, z = z' = 0: a plastic ground impact, rocking on the
    wall-side corner being blocked by the wall), its CM's horizontal
    velocity toward the wall reversed with the wall restitution (v_x+ =
    -e_w v_x-), a velocity away from the wall kept, then reduced by the
    ground friction impulse mu_k L_n, L_n = max(0, -v_Gy-) (the vertical
    impulse of the ground; mu_k = inf: stopped); below the rest rule's
    speed (O_EPS_OMEGA h, or chatter within O_EPS_T) it stops.  The
    kinetic energy becomes v_x+^2 / 2 <= v_Gx-^2 / 2: never more.  Then
    ``pick_flat`` (face rest, or sliding / rocking away)."""
    w = par[P_WALL_SIDE]
    s = disc[D_PIVOT]
    before = kinetic_energy(y, par)
    vgx, vgy = cm_velocity(y, par)
    pre = y[1]
    chatter = t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    if count_wall:
        met[M_WALL_IMPACTS] += 1
    met[M_T_LAST_IMPACT] = t
    vx = vgx
    if w * vx > 0.0:
        vx = -par[P_E_W] * vx
    g0, _vn, _vt = point_kin(0, y, par)
    g1, _vn, _vt = point_kin(1, y, par)
    if (disc[D_MODE] == MODE_FLIGHT and not wall_frictional(par)
            and min(g0, g1) > FLAT_RTOL * (par[C_B1] + par[C_B2])):
        return face_impact_in_flight(t, y, par, disc, hdr, smp, opt, met, log,
                                     cnt, vx, vgy, before, chatter, pre,
                                     count_wall)
    ln = max(0.0, -vgy)
    if not np.isfinite(par[C_MU_K]):
        vx = 0.0
    elif abs(vx) <= par[C_MU_K] * ln:
        vx = 0.0
    else:
        vx -= par[C_MU_K] * ln * (1.0 if vx > 0.0 else -1.0)
    if chatter or abs(vx) < opt[O_EPS_OMEGA] * hmid(par):
        vx = 0.0
    y[0] = 0.0
    y[1] = 0.0
    y[2] = w * par[C_GAP]
    y[3] = vx
    y[4] = 0.0
    y[5] = 0.0
    check_energy(before, kinetic_energy(y, par), met)
    if count_wall:
        log_event(log, cnt, t, EV_WALL_IMPACT, pre, 0.0, 0.0, s)
    st = pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    if disc[D_MODE] == MODE_REST:
        log_event(log, cnt, t, EV_WALL_REST, pre, 0.0, 0.0, 0)
    return st


@jit
def face_impact_in_flight(t, y, par, disc, hdr, smp, opt, met, log, cnt, vx,
                          vgy, before, chatter, pre, count_wall):
    """The face reaches the wall in flight, the base above the ground (a
    frictionless wall): the face stops turning (theta = theta' = 0, the
    CM's height and vertical velocity kept), its horizontal velocity vx
    (toward the wall reversed with e_w by the caller; below the rest
    rule's speed, or in chatter, 0).  The kinetic energy becomes
    (vx^2 + v_Gy^2) / 2: never more.  Pushed toward the wall (q = -w a_g
    > 0) at vx = 0, the body flies on with the face on the wall (face
    flight: x_G'' = 0, theta'' = 0, y_G'' = -G), until the push ends
    (K_WALL_BASE) or the base lands flat (then ``pick_flat``, face
    rest); else free flight."""
    w = par[P_WALL_SIDE]
    s = disc[D_PIVOT]
    if chatter or abs(vx) < opt[O_EPS_OMEGA] * hmid(par):
        vx = 0.0
    hm = hmid(par)
    zg = y[4] + hm * math.cos(y[0])
    y[0] = 0.0
    y[1] = 0.0
    y[2] = w * par[C_GAP]
    y[3] = vx
    y[4] = zg - hm
    y[5] = vgy
    check_energy(before, kinetic_energy(y, par), met)
    if count_wall:
        log_event(log, cnt, t, EV_WALL_IMPACT, pre, 0.0, 0.0, s)
    set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
    disc[D_PIVOT] = s
    if vx == 0.0 and face_push(t, par, hdr, smp) > 0.0:
        set_contacts(disc, CS_OPEN, CS_OPEN, CS_WALL_BASE)
        disc[D_PIVOT] = s
        disc[D_WALL_REST] = 1
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, 0.0, s)
    return RUNNING


@jit
def face_push(t, par, hdr, smp):
    """The d'Alembert force's component toward the wall, -w a_g."""
    ag, _av = ground(t, hdr, smp)
    return -par[P_WALL_SIDE] * ag


@jit
def face_flight(disc):
    """Flight with the face on the wall (``face_impact_in_flight``)."""
    return (disc[D_MODE] == MODE_FLIGHT and disc[D_CS2] == CS_WALL_BASE
            and disc[D_WALL_REST] == 1)


@jit
def at_face(y, par):
    """Both the wall-side base corner and the top corner at the wall: the
    face touches it."""
    if not near_at_wall(y, par):
        return False
    bw = par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]
    if short_wall(par) and \
            abs(math.sin(y[0])) * par[C_H_WALL] > FACE_RTOL * bw:
        # a short wall's edge at the base corner itself (the body leaning
        # on the edge by that corner, tilted): no face contact, which the
        # face impact would make flat at once (contact:2027:430)
        return False
    gap, _vn, _vt = point_kin(2, y, par)
    return gap <= FACE_RTOL * bw


@jit
def pick_wall_flight(kw, t, y, par, disc, hdr, smp, stick):
    """In flight with wall point kw (2 top corner, K_NEAR the wall-side
    base corner) at the wall and not approaching it: the wall contact
    closed while the wall pushes (N_w > 0 in the mode solve with both base
    corners open), else free flight.  On a frictional wall the point
    sticks if its tangential velocity is 0 (stick = 1: it has just
    reached 0; stick = -1: it has just left the cone, no stick) and
    |F_w| <= mu_w N_w, else slips (along its velocity, or from rest in
    -sgn F_w, then the other way, not reversed)."""
    s = disc[D_PIVOT]
    acc = np.empty(3)
    cand = np.empty(3, dtype=np.int64)
    nc = 1
    cand[0] = wall_state(kw, 0)
    if wall_frictional(par):
        _g, _vn, vtw = point_kin(kw, y, par)
        if stick == 1 or (stick == 0 and abs(vtw) <= V_TOL):
            ok, _N0, _F0, _N1, _F1, N2, F2 = mode_solve(
                t, y, par, CS_OPEN, CS_OPEN, wall_state(kw, 1), hdr, smp,
                acc)
            sw = -1 if F2 > 0.0 else 1
            if stick == 1 and ok and N2 > 0.0 and \
                    abs(F2) <= par[C_MU_W] * N2:
                nc = 0
                cand[0] = wall_state(kw, 1)
            else:
                cand[0] = wall_state(kw, 2 * sw)
                cand[1] = wall_state(kw, -2 * sw)
                nc = 2
        else:
            cand[0] = wall_state(kw, 2 * sign_of(vtw))
    if nc == 0:
        set_contacts(disc, CS_OPEN, CS_OPEN, cand[0])
        disc[D_PIVOT] = s
        return
    for i in range(nc):
        ok, _N0, _F0, _N1, _F1, N2, _F2 = mode_solve(
            t, y, par, CS_OPEN, CS_OPEN, cand[i], hdr, smp, acc)
        sw = wall_sigma(cand[i])
        _an, atw = contact_acc(kw, y, par, acc)
        if ok and N2 > 0.0 and (nc == 1 or sw * atw >= 0.0):
            set_contacts(disc, CS_OPEN, CS_OPEN, cand[i])
            disc[D_PIVOT] = s
            return
    set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
    disc[D_PIVOT] = s


@jit
def close_wall_in_flight(kw, t, y, par, disc, hdr, smp, log, cnt):
    """The rest rule of physics.md 7 for wall impacts in flight: wall
    impacts closer than eps_t, or a rebound slower than eps_omega times
    the body's size, close the wall contact.  Under a push toward the wall
    the rebounds of e_w < 1 shrink geometrically and accumulate at a finite
    time (a Zeno sequence; at e_w = 0, or at the accumulation point, the
    free flight pushes the point back into the wall at once); the rule cuts
    that tail.  A plastic impact of the wall point (its normal velocity to
    0, Routh's with mu_w on a frictional wall) only dissipates; then
    ``pick_wall_flight``."""
    post = np.empty(3)
    vgx, vgy = cm_velocity(y, par)
    post[0] = vgx
    post[1] = vgy
    post[2] = y[1]
    imp = np.zeros(4)
    point_impulse(kw, y, par, post, 0.0, par[C_MU_W], par[C_MU_W], imp, 0)
    set_cm_velocity(y, par, post[0], post[1], post[2])
    pick_wall_flight(kw, t, y, par, disc, hdr, smp, 0)
    if disc[D_CS2] != CS_OPEN:
        log_event(log, cnt, t, EV_WALL_REST, y[1], y[1], y[0], disc[D_PIVOT])
    return RUNNING


@jit
def wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt, kw=2):
    """Wall point kw (2: the top corner, K_NEAR: the wall-side base corner)
    reached the wall (frictionless; mu_w > 0: ``wall_pivot_impact_fr``, and
    in flight ``point_impulse``; the held pivot of mu = inf fixes the
    motion whatever the wall's friction): impulse solve with the wall's
    post-impact normal velocity -e_w v_n- and, while rocking, the pivot
    held (ROCK: its velocity 0, which gives theta'+ = -e_w theta'- about
    the pivot as kernels/wall.py) or frictionless during the impact
    (SLIDE_ROCK: its normal velocity 0); in flight the wall alone.  Flat
    sliding into the wall, or the face reaching it, is a face impact
    (``face_impact``)."""
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    j = 1 if s > 0 else 0
    if mode == MODE_SLIDE or at_face(y, par):
        return face_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                           True)
    if kw == K_NEAR and mode != MODE_FLIGHT:
        gap, vn, _vt = point_kin(K_NEAR, y, par)
        if gap <= 0.0 and abs(vn) <= 1e-12 * velocity_scale(y, par) and \
                not into_wall(t, y, par, disc, hdr, smp):
            # at rest on the wall inside the rounding band and accelerating
            # away: no impact.  The corner is put on the wall, else the
            # phase starts inside it and the event fires again at once
            # (failed:transition-loop, contact:2027:180)
            y[2] += par[P_WALL_SIDE] * gap
            return RUNNING
    if mode == MODE_FLIGHT and disc[D_CS2] != CS_OPEN:
        # the other wall point reached the wall: the closed one opens (the
        # impact below is the new point's alone)
        set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
        disc[D_PIVOT] = s
    stw = CS_WALL_BASE if kw == K_NEAR else CS_FREE
    if mode == MODE_ROCK:
        # the pivot sticks: its velocity is 0 up to the integration drift,
        # which the impulse solve (conditioned like 1 / sin(theta) for the
        # wall-side base corner) would amplify into theta' (contact:14:7:
        # a 1e-3 m/s drift at theta = 1.7e-3 gained 5e-4 of the energy)
        project_single(j, y, par, True)
    before = kinetic_energy(y, par)
    pre = y[1]
    _gap, vn2, _vt2 = point_kin(kw, y, par)
    e_w = par[P_E_W]
    met[M_WALL_IMPACTS] += 1
    chatter = t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    vgx, vgy = cm_velocity(y, par)
    post = np.empty(3)
    tgt = -e_w * vn2
    separated = False
    if vn2 > 0.0:
        # found at the wall moving away from it (a grazing root located
        # after the turn): the wall cannot pull, so no impulse (the map
        # -e_w v_n would drive the corner back into the wall)
        post[0] = vgx
        post[1] = vgy
        post[2] = y[1]
    elif mode == MODE_FLIGHT and wall_frictional(par):
        # a frictional wall alone: Routh's impact with Poisson's restitution
        post[0] = vgx
        post[1] = vgy
        post[2] = y[1]
        imp = np.zeros(4)
        point_impulse(kw, y, par, post, e_w, par[C_MU_W], par[C_MU_W], imp,
                      2)
    elif mode == MODE_FLIGHT:
        solve_targets(y, vgx, vgy, y[1], 0.0, par, CS_OPEN, CS_OPEN,
                      stw, tgt, post)
    elif mode == MODE_ROCK and not np.isfinite(par[C_MU_S]):
        # mu = inf: the pivot is held (bilateral), whatever the sign of its
        # normal impulse.  One degree of freedom, in which the wall's normal
        # velocity is linear in theta': the map is theta'+ = -e_w theta'-
        # exactly, as in kernels/wall.py, with the CM velocity of the held
        # pivot.  (The impulse solve gave the same map to rounding amplified
        # like 1 / sin(theta): energy rises of 8e-12 at e_w = 1.)
        tmp = y.copy()
        tmp[1] = -e_w * y[1]
        project_single(j, tmp, par, True)
        post[0], post[1] = cm_velocity(tmp, par)
        post[2] = tmp[1]
    elif wall_frictional(par):
        imp = np.zeros(4)
        separated = wall_pivot_impact_fr(j, y, par, vgx, vgy, tgt, before,
                                         post, kw, imp)
    else:
        separated = wall_pivot_impact(j, y, par, vgx, vgy, tgt, before, post,
                                      kw)
    set_cm_velocity(y, par, post[0], post[1], post[2])
    check_energy(before, kinetic_energy(y, par), met)
    track_rotation(y[0], met)
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, y[1], y[0], s)
    if kw == K_NEAR and chatter:
        gj, _vn, _vt = point_kin(j, y, par)
        if gj <= FACE_RTOL * (par[C_B1] + par[C_B2]):
            # the rest rule, as for the top corner below: base-corner wall
            # impacts closer than eps_t (a Zeno sequence of wall impacts
            # and landings, or micro-bounces off the wall under a push
            # toward it) end at rest, all velocities 0 (dissipative),
            # with pivot j on the ground; the pick closes the wall contact
            y[1] = 0.0
            project_single(j, y, par, True)
            disc[D_PIVOT] = s
            return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt,
                               False)
    if mode == MODE_FLIGHT:
        _g, vn_post, _vt = point_kin(kw, y, par)
        if chatter or abs(vn_post) < opt[O_EPS_OMEGA] * hmid(par):
            return close_wall_in_flight(kw, t, y, par, disc, hdr, smp, log,
                                        cnt)
        return RUNNING
    if kw == K_NEAR:
        if separated:
            return enter_flight(t, y, par, disc, met, log, cnt)
        return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt,
                           False)
    _g, _vn, vt = point_kin(j, y, par)
    settle = abs(y[1]) < opt[O_EPS_OMEGA] or chatter
    if separated and (settle or abs(pre) < opt[O_EPS_OMEGA]):
        # wall chatter through short flights (the wall impact lifts the
        # pivot, the landing brings it back): it ends by the rest rule,
        # resting on the wall (all velocities 0: dissipative)
        vt = 0.0
        settle = True
    elif separated:
        return enter_flight(t, y, par, disc, met, log, cnt)
    floor = not separated and below_rounding(y, par)
    if (settle and (abs(vt) <= V_TOL or chatter)) or floor:
        disc[D_PIVOT] = s
        return settle_on_wall(j, t, y, par, disc, hdr, smp, met, log, cnt)
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def flight_wall_normal_acc(j, kw, t, y, par, hdr, smp):
    """Normal acceleration of base corner j (> 0: off the ground) in flight
    with wall point kw's contact closed (frictionless), and that mode's
    wall force (-inf and NaN if the solve fails)."""
    acc = np.empty(3)
    ok, _N0, _F0, _N1, _F1, N2, _F2 = mode_solve(
        t, y, par, CS_OPEN, CS_OPEN, wall_state(kw, 0), hdr, smp, acc)
    if not ok:
        return -np.inf, np.nan
    an, _at = contact_acc(j, y, par, acc)
    return an, N2


@jit
def lift_off_at_wall(j, kw, t, y, par, disc, hdr, smp, met, log, cnt):
    """Base corner j on the ground and wall point kw at the wall, where no
    contact mode with j closed is admissible: if, in flight with kw's
    contact closed, the wall pushes and j accelerates off the ground, j
    lifts off and the body flies along the wall (``pick_wall_flight``).
    Returns False if that flight is not consistent."""
    an, N2 = flight_wall_normal_acc(j, kw, t, y, par, hdr, smp)
    if not (N2 > 0.0 and an > 0.0):
        return False
    enter_flight(t, y, par, disc, met, log, cnt)
    pick_wall_flight(kw, t, y, par, disc, hdr, smp, 0)
    if disc[D_CS2] != CS_OPEN:
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[0], disc[D_PIVOT])
    return True


@jit
def tip_off_pivot(j, t, y, par, disc, hdr, smp, met, log, cnt):
    """At rest with the top corner on the wall, where neither the sticking
    rest nor ``top_ladder`` is admissible: if pivot j would have to pull
    the ground (a body leaning over a short wall's edge with its CM beyond
    it see-saws on the edge) and flight with the top corner on the wall is
    consistent, the pivot lifts off (``lift_off_at_wall``).  The test is
    the sign of wall_rest_margin's -a_n, so a rest that ends there finds
    that flight consistent.  Returns False if it is not, or for a finite
    mu (whose rest ends by the normal force itself: ``pick_single``)."""
    if np.isfinite(par[C_MU_S]):
        return False
    return lift_off_at_wall(j, 2, t, y, par, disc, hdr, smp, met, log, cnt)


@jit
def top_ladder(j, t, y, par, disc, hdr, smp):
    """At rest with the top corner on the wall and base corner j on the
    ground, where friction cannot hold the pivot (the sticking wall rest is
    inadmissible): the pivot slips while the top corner stays on the wall
    (SLIDE_ROCK with the wall contact closed, CS_FREE), in the direction
    whose mode solve is consistent (both normal forces >= 0, the slip
    accelerating its own way).  Without it, a block pressed into the wall
    by the ground's push and tipping onto it repeated zero-velocity wall
    impacts and slip starts for ever (a step-budget failure).  The phase
    ends when the wall's force reaches 0 (K_WALL), the slip stops (K_STICK)
    or the block lands flat (K_IMPACT).  Returns False if neither slip
    direction is consistent."""
    if not np.isfinite(par[C_MU_S]):
        return False
    acc = np.empty(3)
    tol = 1e-12 * (par[P_G] + abs(y[1]))
    if wall_frictional(par):
        return wall_ladder(j, 2, t, y, par, disc, hdr, smp, tol)
    for sig in (1, -1):
        st = slip_state(sig)
        st0 = st if j == 0 else CS_OPEN
        st1 = st if j == 1 else CS_OPEN
        ok, N0, _F0, N1, _F1, N2, _F2 = mode_solve(t, y, par, st0, st1,
                                                   CS_FREE, hdr, smp, acc)
        N = N1 if j == 1 else N0
        _an, at = contact_acc(j, y, par, acc)
        if ok and N >= 0.0 and N2 >= 0.0 and sig * at > tol:
            set_contacts(disc, st0, st1, CS_FREE)
            return True
    return False


@jit
def wall_jam_values(t, y, par, disc, hdr, smp):
    """At rest with the top corner (or a short wall's edge) on a
    frictionless wall, pivot disc[D_PIVOT] sticking: (ok, N, N_w, c, v,
    sigma) with N, N_w the sticking rest's normal forces, c = mu_s N - |F|
    its friction margin, and v = min(N, N_w, sigma a_t) of the better slip
    direction sigma with the wall contact held (v > 0: that ladder is
    consistent).  Forces per unit mass."""
    te = np.inf if t >= excitation_end(hdr) else t
    acc = np.empty(3)
    j = 1 if disc[D_PIVOT] > 0 else 0
    bx, by, bw = free_acc(te, par, hdr, smp)
    st0 = CS_STICK if j == 0 else CS_OPEN
    st1 = CS_STICK if j == 1 else CS_OPEN
    ok, N0, F0, N1, F1, N2, _F2 = solve_contacts(y, bx, by, bw, 0.0, par,
                                                 st0, st1, CS_FREE, acc)
    N = N1 if j == 1 else N0
    F = F1 if j == 1 else F0
    v = -np.inf
    sigma = 0
    for sig in (1, -1):
        st = slip_state(sig)
        oks, M0, _G0, M1, _G1, M2, _G2 = solve_contacts(
            y, bx, by, bw, 0.0, par, st if j == 0 else CS_OPEN,
            st if j == 1 else CS_OPEN, CS_FREE, acc)
        _an, at = contact_acc(j, y, par, acc)
        vs = min(M1 if j == 1 else M0, M2, sig * at)
        if oks and vs > v:
            v = vs
            sigma = sig
    return ok, N, N2, par[C_MU_S] * N - abs(F), v, sigma


@jit
def wall_rest_at_cone(j, t, y, par, disc, hdr, smp):
    """Pivot j at rest with the top corner (or a short wall's edge) on a
    frictionless wall, both normal forces pushing, whose stick exceeds the
    friction cone: that slip with the wall contact held (the ladder from
    rest) if one is consistent (near the cone's edge its acceleration is 0
    to rounding, so ``top_ladder``'s strict test can miss it), else
    jammed.  Jammed, no slip is consistent: the slip's normal force grows
    with its acceleration (Painleve), so the slip toward the wall
    decelerates while sticking exceeds the cone, and the other way needs a
    pull (contact:2026:2, a block pressed at 6.9 g onto a short wall's
    edge, mu_s = 1.47).  The rigid model has no motion there; the body
    stays jammed (a rest with D_SLIP_DIR = JAM, as the rocking pivot's jam)
    until the push lets the stick hold again or a slip becomes consistent
    (``wall_jam_margin``, ``leave_wall_jam``).  The ground-only pick rocked
    it back into the wall at zero speed, an impact and a rest at one
    instant for ever.  Returns False (nothing set) off these conditions."""
    if (not np.isfinite(par[C_MU_S]) or wall_frictional(par)
            or wall_base(disc[D_CS2])):
        return False
    s = disc[D_PIVOT]
    ok, N, N2, c, v, sig = wall_jam_values(t, y, par, disc, hdr, smp)
    if not (ok and N > 0.0 and N2 > 0.0 and c < 0.0):
        return False
    if v < 0.0:
        set_contacts(disc, CS_STICK if j == 0 else CS_OPEN,
                     CS_STICK if j == 1 else CS_OPEN, CS_FREE)
        disc[D_SLIP_DIR] = JAM
    else:
        st = slip_state(sig)
        set_contacts(disc, st if j == 0 else CS_OPEN,
                     st if j == 1 else CS_OPEN, CS_FREE)
    disc[D_PIVOT] = s
    return True


@jit
def wall_jam_margin(t, y, par, disc, hdr, smp):
    """Static margin of the jam (``wall_rest_at_cone``): it holds while both
    normal forces push, the stick exceeds the cone and no slip is
    consistent."""
    ok, N, N2, c, v, _sig = wall_jam_values(t, y, par, disc, hdr, smp)
    if not ok:
        return -1.0
    return min(N, N2, -c, -v)


@jit
def leave_wall_jam(j, t, y, par, disc, hdr, smp, met, log, cnt):
    """The jam's end: the sticking rest again if it holds, else the
    consistent slip with the wall contact held (the ladder, from rest),
    else the ground-only pick (a normal force reached 0)."""
    s = disc[D_PIVOT]
    ok, N, N2, c, v, sig = wall_jam_values(t, y, par, disc, hdr, smp)
    if ok and N > 0.0 and N2 > 0.0:
        if c >= 0.0:
            disc[D_SLIP_DIR] = 0
            return RUNNING
        if v >= 0.0:
            st = slip_state(sig)
            set_contacts(disc, st if j == 0 else CS_OPEN,
                         st if j == 1 else CS_OPEN, CS_FREE)
            disc[D_PIVOT] = s
            return RUNNING
    log_event(log, cnt, t, EV_WALL_RELEASE, 0.0, 0.0, y[0], s)
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def wall_ladder(j, kw, t, y, par, disc, hdr, smp, tol):
    """Frictional wall (mu_w > 0): from rest, base corner j slipping on the
    ground in sigma and wall point kw (2 or K_NEAR) slipping along the wall
    in sigma_w (friction -mu_w sigma_w N_w), the first of the four
    direction pairs whose mode solve is consistent: both normal forces >= 0
    and both contacts accelerating their own way (sigma a_t > tol, sigma_w
    a_tw > tol).  With both contacts closed the body has one degree of
    freedom, so the two slips start, and stop, together (K_STICK of the
    pivot ends the phase).  Sets the contact states and returns True, or
    False when no pair is consistent."""
    acc = np.empty(3)
    for sig in (1, -1):
        st = slip_state(sig)
        st0 = st if j == 0 else CS_OPEN
        st1 = st if j == 1 else CS_OPEN
        for sw in (1, -1):
            stw = wall_state(kw, 2 * sw)
            ok, N0, _F0, N1, _F1, N2, _F2 = mode_solve(t, y, par, st0, st1,
                                                       stw, hdr, smp, acc)
            N = N1 if j == 1 else N0
            _an, at = contact_acc(j, y, par, acc)
            _anw, atw = contact_acc(kw, y, par, acc)
            if (ok and N >= 0.0 and N2 >= 0.0 and sig * at > tol
                    and sw * atw > tol):
                set_contacts(disc, st0, st1, stw)
                return True
    return False


@jit
def trapped_on_wall(t, y, par, disc, hdr):
    """After the excitation: pivoting on the corner near the wall past that
    side's instability with mechanical energy below the barrier g (R - h)
    (R: corner-to-CM distance), so that the block can never come back
    (impacts and friction never add energy): LEANING."""
    if not wall_active(par) or t < excitation_end(hdr):
        return False
    w = par[P_WALL_SIDE]
    mode = disc[D_MODE]
    if mode != MODE_ROCK and mode != MODE_SLIDE_ROCK:
        return False
    if disc[D_PIVOT] != w:
        return False
    j = 1 if w > 0.0 else 0
    cx, cy = body_point(j, par)
    if not w * y[0] > math.atan2(abs(cx), abs(cy)):
        return False
    hm = hmid(par)
    E = kinetic_energy(y, par) + par[P_G] * (y[4] + hm * math.cos(y[0]) - hm)
    return E < par[P_G] * (math.hypot(cx, cy) - hm)


# ---------------------------------------------------------------- transition
@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        book_time(t, disc, met)
        if disc[D_MODE] == MODE_WALL_REST:
            s = disc[D_PIVOT]
            j = 1 if s > 0 else 0
            if disc[D_SLIP_DIR] == JAM:
                return leave_wall_jam(j, t, y, par, disc, hdr, smp, met, log,
                                      cnt)
            if wall_rest_at_cone(j, t, y, par, disc, hdr, smp):
                return RUNNING
            log_event(log, cnt, t, EV_WALL_RELEASE, 0.0, 0.0, y[0], s)
            if tip_off_pivot(j, t, y, par, disc, hdr, smp, met, log, cnt):
                return RUNNING
            return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt,
                               False)
        return pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == K_PEAK:
        track_rotation(y[0], met)
        return RUNNING
    if k == K_PASS_ALPHA:
        s = disc[D_PIVOT]
        if disc[D_MODE] == MODE_FLIGHT:
            s = 1 if y[0] > 0.0 else -1
        passed_alpha(t, y[0], y[1], s, met, log, cnt)
        return RUNNING
    if k == K_APEX:
        track_jump(y, par, met)
        return RUNNING
    book_time(t, disc, met)
    track_slide(y, par, disc, met)
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    j = 1 if s > 0 else 0
    if k == K_OVERTURN:
        if mode == MODE_FLIGHT:
            s = 1 if y[0] > 0.0 else -1
        return overturned(t, y[0], y[1], s, met, log, cnt)
    if k == K_IMPACT:
        return ground_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)
    if mode == MODE_FLIGHT and disc[D_CS2] != CS_OPEN:
        kw = K_NEAR if wall_base(disc[D_CS2]) else 2
        if k == K_WALL_BASE and kw == K_NEAR and drifted_into_wall(y, par):
            project_wall_point(K_NEAR, y, par)
            return RUNNING
        if (k == K_WALL and kw == 2) or (k == K_WALL_BASE and kw == K_NEAR):
            # the wall's force reached 0: free flight
            set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
            disc[D_PIVOT] = s
            log_event(log, cnt, t, EV_WALL_RELEASE, y[1], y[1], y[0], s)
            return RUNNING
        if k == K_STICK:
            _g, _vn, vtw = point_kin(kw, y, par)
            # the slip along the wall stopped: v_tw = 0 (up to the event's
            # location), taken as the wall's tangential impulse stopping it
            vgx, vgy = cm_velocity(y, par)
            wtt, wtn, wnn, jt, jn = point_inertia(kw, y, par)
            _rx, _ry, _nx, _ny, tx, ty = geom(kw, y, par)
            pt = -vtw / wtt
            set_cm_velocity(y, par, vgx + tx * pt, vgy + ty * pt,
                            y[1] + jt * pt / par[C_IG])
            pick_wall_flight(kw, t, y, par, disc, hdr, smp, 1)
            return RUNNING
        if k == K_SLIP:
            pick_wall_flight(kw, t, y, par, disc, hdr, smp, -1)
            return RUNNING
        if k == K_LAND0 or k == K_LAND1:
            if kw == 2 and landing_at_wall(k - K_LAND0, t, y, par, met, log,
                                           cnt):
                return pick_at_wall(k - K_LAND0, t, y, par, disc, hdr, smp,
                                    met, log, cnt)
            # the landing's impulse is the base corner's alone; a wall
            # contact it closes again is a wall impact
            set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
            disc[D_PIVOT] = s
    if k == K_LAND0 or k == K_LAND1:
        return landing(k - K_LAND0, t, y, par, disc, hdr, smp, opt, met, log,
                       cnt)
    if k == K_WALL:
        if mode == MODE_SLIDE_ROCK and wall_top(disc[D_CS2]):
            # top-corner ladder: the wall's force reached 0
            log_event(log, cnt, t, EV_WALL_RELEASE, y[1], y[1], y[0], s)
            return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt,
                               False)
        return wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)
    if k == K_WALL_BASE:
        if mode != MODE_FLIGHT and wall_base(disc[D_CS2]):
            if drifted_into_wall(y, par):
                project_wall_point(K_NEAR, y, par)
                project_single(j, y, par, False)
                return RUNNING
            # the wall's normal force reached 0: the corner leaves the wall
            log_event(log, cnt, t, EV_WALL_RELEASE, y[1], y[1], y[0], s)
            return pick_single_ground(j, t, y, par, disc, hdr, smp, met, log,
                                      cnt, False)
        return wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                           K_NEAR)
    if k == K_LIFT:
        if mode == MODE_SLIDE:
            return pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
        if free_normal_acc(j, t, y, par, hdr, smp) >= 0.0:
            return enter_flight(t, y, par, disc, met, log, cnt)
        # N = 0 but the free corner would fall into the ground: re-pick
        # (not stick again: N has just reached 0)
        return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, True)
    if k == K_SLIP:
        jam = mode == MODE_ROCK and disc[D_SLIP_DIR] == JAM
        return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt,
                           not jam)
    # K_STICK: the slip velocity reached zero
    if mode == MODE_SLIDE_ROCK and wall_top(disc[D_CS2]) and \
            near_at_wall(y, par):
        _g, vnw, _vt = point_kin(K_NEAR, y, par)
        if vnw < -1e-9 * velocity_scale(y, par):
            # a ladder on a short wall's edge whose contact point reached
            # the face's end, the base corner: there the edge's constraint
            # has no lever arm about the pivot and stops its slip, while
            # the corner meets the wall's face below the edge moving into
            # it: a wall impact of that corner.  (The ground pick stopped
            # the body dead on the edge's vertex, a singular rest that
            # repeated zero-velocity wall impacts: contact:2027:430)
            set_single(j, disc[D_CS0 + j], disc)
            return wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                               K_NEAR)
    met[M_N_STICK_SLIP] += 1
    if mode == MODE_SLIDE:
        y[3] = 0.0
        log_event(log, cnt, t, EV_STICK, 0.0, 0.0, 0.0, 0)
        return pick_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    _g, _vn, vt = point_kin(j, y, par)
    y[3] -= vt
    log_event(log, cnt, t, EV_STICK, y[1], y[1], y[0], s)
    return pick_single(j, t, y, par, disc, hdr, smp, met, log, cnt, False)


@jit
def base_in_wall(y, par):
    """The wall-side base corner is inside the wall by more than FACE_RTOL
    of the half-width: the face contact was missed (a bug guard; the
    events K_WALL, K_WALL_BASE and the face modes keep it out)."""
    if not wall_active(par):
        return False
    bw = par[C_B2] if par[P_WALL_SIDE] > 0.0 else par[C_B1]
    gap, _vn = near_gap(y, par)
    return gap < -FACE_RTOL * bw


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    book_time(t, disc, met)
    mode = disc[D_MODE]
    if base_in_wall(y, par):
        return FAIL_FACE_CONTACT
    if mode == MODE_FLIGHT:
        track_jump(y, par, met)
    else:
        track_slide(y, par, disc, met)
    if mode != MODE_SLIDE:
        track_rotation(y[0], met)
    if at_end:
        if mode == MODE_REST:
            if np.isnan(met[M_T_UPLIFT]):
                return SAFE_NO_UPLIFT
            return SAFE_REST
        if mode == MODE_WALL_REST:
            if abs(y[0]) > alpha_of(disc[D_PIVOT], par):
                return LEANING
            return SAFE_REST
        if trapped_on_wall(t, y, par, disc, hdr):
            return LEANING
        return SAFE_MOVING
    return RUNNING


# ---------------------------------------------------------------- run
@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    """Initial mode from y = (theta, theta', x, x', z, z'): flight if both
    base corners are above the ground; else full contact at theta =
    theta' = 0 (REST, or SLIDE if x' != 0) or rocking on the pivot of
    kernels/rigid.initial_pivot (sticking if its slip velocity is 0), with
    z, z' projected onto the contact."""
    init_metrics(t0, met)
    met[M_MAX_JUMP] = 0.0
    for i in range(N_DISC):
        disc[i] = 0
    disc[D_PIVOT] = 1
    g0, _v0, _t0 = point_kin(0, y, par)
    g1, _v1, _t1 = point_kin(1, y, par)
    tol = FLAT_RTOL * (par[C_B1] + par[C_B2])
    if g0 > tol and g1 > tol:
        disc[D_PIVOT] = 1 if y[0] >= 0.0 else -1
        set_contacts(disc, CS_OPEN, CS_OPEN, CS_OPEN)
        met[M_T_UPLIFT] = t0
        track_rotation(y[0], met)
        return
    if y[0] == 0.0 and y[1] == 0.0:
        project_flat(y, not np.isfinite(par[C_MU_K]))
        if y[3] != 0.0:
            st = slip_state(sign_of(y[3]))
            set_contacts(disc, st, st, CS_OPEN)
        elif par[C_GAP] == 0.0:
            # gap 0: the face stands on the wall from the start (face rest)
            set_contacts(disc, CS_STICK, CS_STICK, CS_WALL_BASE)
            disc[D_WALL_REST] = 1
        else:
            set_contacts(disc, CS_STICK, CS_STICK, CS_OPEN)
        track_slide(y, par, disc, met)
        return
    s = initial_pivot(y[0], y[1])
    j = 1 if s > 0 else 0
    project_single(j, y, par, False)
    _g, _vn, vt = point_kin(j, y, par)
    if vt != 0.0 and not np.isfinite(par[C_MU_K]):
        stop_slip_impulsively(j, y, par)
        project_single(j, y, par, True)
        vt = 0.0
    if abs(vt) <= V_TOL:
        y[3] -= vt
        st = CS_STICK
    else:
        st = slip_state(sign_of(vt))
    set_contacts(disc, st if j == 0 else CS_OPEN, st if j == 1 else CS_OPEN,
                 CS_OPEN)
    disc[D_PIVOT] = s
    met[M_T_UPLIFT] = t0
    track_rotation(y[0], met)
    track_slide(y, par, disc, met)


@jit
def run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
        cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_hybrid(rhs, event, transition, static_margin,
                            after_step, N_EVENTS, y, par, disc, hdr, smp,
                            opt, t_eval, met, hist_t, hist_y, hist_d, log,
                            cnt)


@jit
def contact_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                     hist_d, log, cnt):
    """One run of the contact-core rigid body (time history, events)."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def contact_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Independent runs in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)


# the asymmetric RigidBody's registry entry (model "contact_body") runs the
# same kernel; its own entry names keep the plug-in contract (rule 2)
contact_body_simulate = contact_simulate
contact_body_sweep = contact_sweep
