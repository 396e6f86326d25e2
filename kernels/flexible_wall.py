"""Flexible body rocking against a rear wall: the flexible body of
:mod:`.flexible` (state ``y = (u, u', theta, theta')``, the same equations,
the same ground impact maps) with a rigid wall on side
``w = par[FW_WALL_SIDE]``.

The wall touches the body's outline, the box 2B x 2H that turns with the
rigid base (the box of the rigid block with the same alpha and R0): while
pivoting on the corner near the wall (``s == w``) it is reached at
``w*theta = theta_w = par[FW_THETA_W]`` (the front end computes theta_w
from the gap and the wall height as for the rigid block, with h = H).  The
column's deflection happens inside the outline and does not move the
contact point.

Events: those of :func:`.flexible.event` while rocking (ids R_*), plus
R_WALL ``theta_w - w*theta`` (s == w, terminal); in full contact the
flexible ones (C_*); at rest on the wall W_RELEASE (the wall's reaction
reaches 0, terminal), W_U_MAX / W_U_MIN (extrema of u, observers) and
W_FLIGHT (G reaches 0, terminal).

Wall impact (pivot kept, ``theta'+ = -e_w theta'-``):

* full-contact ground map (I3): the wall's impulse acts on the base, so it
  does no work on u and the mass's horizontal momentum ``u' + H theta'`` is
  kept: ``u'+ = u'- + H (theta'- - theta'+)``.  This is Newton's impact
  law in the kinetic metric along theta; it dissipates
  ``(1 - e_w^2) theta'-^2 / (2 (M^-1)_{theta theta})`` and never adds
  energy.
* pivot-switch ground map (I1): u' is kept, as the I1 map keeps it at the
  ground, so that the map tends to the rigid wall map as the column
  stiffens.  Where keeping u' would raise the kinetic energy
  (``u' theta'- < 0`` and large), the I3 wall map above is used instead:
  the map is capped, never creates energy, and the impact counts in
  ``met[M_WALL_CAPPED]``.

Chatter (physics.md 7: ``|theta'+| < eps_omega`` or two impacts closer
than eps_t; or, as for the rigid block (:mod:`.wall`), an impact elastic at
the tolerance, 1 - e_w^2 <= rtol, whose rebound energy, the kinetic energy
the plastic map below would take, ``((u - s B)^2 + I_b/m) theta'+^2 / 2``,
is below rtol g R0 (1 - cos alpha): an elastic wall under a steady push
otherwise keeps the body bouncing at a constant speed below the
resolution for ever) ends in a plastic wall impact with u' + H theta' kept, and the
body rests on the wall (``theta = w theta_w``, ``theta' = 0``, mode
MODE_WALL_REST) while the wall pushes on it; u keeps vibrating:
``u'' = f_u`` of physics.md 3.4 with theta'' = 0.  The wall's reaction is
``w (f_theta - H f_u)``; the body leaves the wall (pivot w, theta' = 0) when
it becomes negative.

Outcomes: as :mod:`.flexible`, plus LEANING: at rest on the wall at the end
with theta_w > alpha, or (exact, also an early decision after the
excitation) trapped on the near corner past alpha with a total energy below
the lowest energy at which the outline can pass alpha back (see
:func:`trapped_on_wall`).
"""
import math

import numpy as np

from .config import jit, jit_generic, jit_parallel
from .excitation import excitation_end, ground_rates
from .flexible import C_UPLIFT, kinetic, positions, track_u, uplift_margin
from .flexible import decide_after_step, total_energy
from .flexible import event as flexible_event
from .flexible import init_state, static_margin  # no static phase: u vibrates in every mode
from .flexible import rhs as flexible_rhs
from .flexible import transition as flexible_transition
from .hybrid import (book_time, check_energy, elastic_below_resolution,
                     integrate_hybrid, is_chatter, log_event, sweep_rows)
from .layout import SMALL_GAP_ANGLE
from .layout import (D_MODE, D_PIVOT, D_WALL_REST, EV_FLIGHT, EV_WALL_IMPACT,
                     EV_WALL_RELEASE, EV_WALL_REST, FLIGHT, F_ALPHA, F_B,
                     F_G, F_H, F_HB, F_IMPACT, F_MB, F_THETA_OVER, F_WN,
                     F_ZETA, FW_E_W,
                     FW_THETA_W, FW_WALL_SIDE, IMPACT_PIVOT_SWITCH, LEANING,
                     MODE_REST, MODE_ROCK, MODE_WALL_REST, M_WALL_CAPPED,
                     M_WALL_IMPACTS, N_DISC, O_EARLY_EXIT, O_T0, RUNNING,
                     SAFE_MOVING)
from .rigid import track_rotation

N_EVENTS = 9
# small-gap limit (layout.SMALL_GAP_ANGLE, 0.2 um for 2H = 2 m): a
# closer wall blocks every uplift toward it; the body then only rocks away
# from the wall, as Hogan's gap-0 block does.  Without it an elastic wall
# at a gap of nanometres makes the body bounce in that gap thousands of
# times a second until the step budget runs out.
R_WALL = 8          # while rocking on the near corner: w theta reaches theta_w
# events at rest on the wall
W_RELEASE = 0       # the wall's reaction reaches 0 (terminal)
W_U_MAX = 1         # extrema of u (observers)
W_U_MIN = 2
W_FLIGHT = 3        # G reaches 0 (terminal)


@jit
def wall_rest_forces(t, y, par, hdr, smp):
    """(f_u, reaction, d reaction/dt) at rest on the wall (theta' = 0,
    pivot w): u'' = f_u; the wall pushes while the reaction is >= 0."""
    ag, dag, av, dav = ground_rates(t, hdr, smp)
    G = par[F_G] + av
    w = par[FW_WALL_SIDE]
    s = 1 if w > 0.0 else -1
    wn = par[F_WN]
    z = par[F_ZETA]
    H = par[F_H]
    mb = par[F_MB]
    u = y[0]
    du = y[1]
    th = y[2]
    c = math.cos(th)
    sn = math.sin(th)
    X, Y, Xb, Yb = positions(u - s * par[F_B], c, sn, s, par)
    fe = -wn * wn * u - 2.0 * z * wn * du
    fu = fe + G * sn - ag * c
    ft = G * (X + mb * Xb) - ag * (Y + mb * Yb)
    dfe = -wn * wn * du - 2.0 * z * wn * fu
    dfu = dfe + dav * sn - dag * c
    dft = dav * (X + mb * Xb) + G * c * du - dag * (Y + mb * Yb) + ag * sn * du
    return fu, w * (ft - H * fu), w * (dft - H * dfu)


@jit
def rhs(t, y, par, disc, hdr, smp, out):
    if disc[D_MODE] == MODE_WALL_REST:
        fu, _r, _dr = wall_rest_forces(t, y, par, hdr, smp)
        out[0] = y[1]
        out[1] = fu
        out[2] = 0.0
        out[3] = 0.0
        return
    flexible_rhs(t, y, par, disc, hdr, smp, out)


@jit_generic
def event(k, t, y, par, disc, hdr, smp):
    if disc[D_MODE] == MODE_WALL_REST:
        if k == W_RELEASE:
            _fu, r, dr = wall_rest_forces(t, y, par, hdr, smp)
            return r, dr, True
        if k == W_U_MAX or k == W_U_MIN:
            sg = 1.0 if k == W_U_MAX else -1.0
            fu, _r, _dr = wall_rest_forces(t, y, par, hdr, smp)
            return sg * y[1], sg * fu, False
        if k == W_FLIGHT:
            _ag, _dag, av, dav = ground_rates(t, hdr, smp)
            return par[F_G] + av, dav, True
        return np.inf, 0.0, False
    if k == C_UPLIFT and disc[D_MODE] != MODE_ROCK and \
            par[FW_THETA_W] < SMALL_GAP_ANGLE:
        # small gap: only the uplift away from the wall
        g, gd = uplift_margin(t, y, -1 if par[FW_WALL_SIDE] > 0.0 else 1,
                              par, hdr, smp)
        return g, gd, True
    if k == R_WALL:
        w = par[FW_WALL_SIDE]
        if disc[D_MODE] == MODE_ROCK and disc[D_PIVOT] == w:
            return par[FW_THETA_W] - w * y[2], -w * y[3], True
        return np.inf, 0.0, True
    return flexible_event(k, t, y, par, disc, hdr, smp)


@jit
def wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    w = par[FW_WALL_SIDE]
    s = disc[D_PIVOT]
    pre = y[3]
    y[2] = w * par[FW_THETA_W]
    before = kinetic(y, s, True, par)
    post = -par[FW_E_W] * pre
    du = y[1]
    y[3] = post
    if par[F_IMPACT] == IMPACT_PIVOT_SWITCH and \
            kinetic(y, s, True, par) <= before:
        pass                                   # I1: u' kept
    else:
        if par[F_IMPACT] == IMPACT_PIVOT_SWITCH:
            met[M_WALL_CAPPED] += 1
        y[1] = du + par[F_H] * (pre - post)    # I3: u' + H theta' kept
    met[M_WALL_IMPACTS] += 1
    check_energy(before, kinetic(y, s, True, par), met)
    track_rotation(y[2], met)
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, post, y[2], s)
    rebound = kinetic(y, s, True, par) - 0.5 * (y[1] + par[F_H] * post) ** 2
    scale = par[F_G] * math.hypot(par[F_B], par[F_H]) * \
        (1.0 - math.cos(par[F_ALPHA]))
    if is_chatter(t, post, opt, met) or \
            elastic_below_resolution(par[FW_E_W], rebound, scale, opt):
        settle_on_wall(t, y, par, disc, hdr, smp, log, cnt, pre == 0.0)
    return RUNNING


@jit
def settle_on_wall(t, y, par, disc, hdr, smp, log, cnt, stay):
    """End of a chatter sequence: plastic wall impact (u' + H theta'
    kept), then rest on the wall if it pushes, or if ``stay``: an impact
    at theta' = 0, i.e. a body released at a zero of the reaction that
    the column brought back within one step, below the resolution in
    theta (rocking again would meet the wall at the same t, for ever)."""
    y[1] += par[F_H] * y[3]
    y[3] = 0.0
    _fu, r, _dr = wall_rest_forces(t, y, par, hdr, smp)
    if r >= 0.0 or stay:
        disc[D_MODE] = MODE_WALL_REST
        disc[D_WALL_REST] = 1
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[2], disc[D_PIVOT])
    # otherwise the moments pull it off the wall already: keep rocking


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if disc[D_MODE] == MODE_WALL_REST:
        if k == W_RELEASE:
            disc[D_MODE] = MODE_ROCK
            disc[D_WALL_REST] = 0
            log_event(log, cnt, t, EV_WALL_RELEASE, 0.0, 0.0, y[2],
                      disc[D_PIVOT])
            return RUNNING
        if k == W_U_MAX or k == W_U_MIN:
            track_u(y[0], met)
            return RUNNING
        log_event(log, cnt, t, EV_FLIGHT, 0.0, 0.0, y[2], disc[D_PIVOT])
        return FLIGHT
    if k == R_WALL and disc[D_MODE] == MODE_ROCK:
        book_time(t, disc, met)
        return wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)
    st = flexible_transition(k, t, y, par, disc, hdr, smp, opt, met, log,
                             cnt)
    w = par[FW_WALL_SIDE]
    if st == RUNNING and par[FW_THETA_W] < SMALL_GAP_ANGLE and \
            disc[D_MODE] == MODE_ROCK and disc[D_PIVOT] == w and \
            y[2] == 0.0:
        small_gap_block(t, y, par, disc, opt, met, log, cnt)
    return st


@jit
def small_gap_block(t, y, par, disc, opt, met, log, cnt):
    """Small-gap limit (SMALL_GAP_ANGLE): the body has just started to
    rock on the corner near the wall at theta = 0 (an uplift, or the
    pivot-switch map's new pivot), and the wall stops it at once.  From rest
    it stays in full contact, with the wall taking the push.  Moving toward
    the wall, the wall and the ground stop it together: a plastic impact
    that keeps u' + H theta' (the full-contact ground map's projection,
    never more energy), then full contact.  This differs from Hogan's
    rebound with r = e_w, which the rigid block's gap 0 uses."""
    pre = y[3]
    disc[D_MODE] = MODE_REST
    if pre == 0.0:
        return
    before = kinetic(y, disc[D_PIVOT], True, par)
    y[1] += par[F_H] * pre
    y[3] = 0.0
    met[M_WALL_IMPACTS] += 1
    check_energy(before, kinetic(y, disc[D_PIVOT], False, par), met)
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, 0.0, 0.0, disc[D_PIVOT])


@jit
def trapped_on_wall(y, par, disc):
    """Free motion (no excitation) can never bring the body back over
    alpha: it pivots on the near corner past alpha (so theta_w > alpha)
    with a total energy (kinetic, gravity, column strain; per unit mass)
    below the least energy of any state with w theta = alpha, and the wall
    stands before theta_over (else it overturns).  There the
    mass is at height R0 - w u sin(alpha), so gravity plus strain is at
    least g R0 - (g sin(alpha))^2 / (2 w_n^2) over all u.  Column damping,
    wall impacts and resting on the wall never add energy."""
    w = par[FW_WALL_SIDE]
    s = disc[D_PIVOT]
    a = par[F_ALPHA]
    if s != w or not w * y[2] > a or not par[FW_THETA_W] < par[F_THETA_OVER]:
        return False
    g = par[F_G]
    wn = par[F_WN]
    B = par[F_B]
    H = par[F_H]
    mb = par[F_MB]
    hb = par[F_HB]
    sa = math.sin(a)
    ca = math.cos(a)
    E = total_energy(y, s, disc[D_MODE] == MODE_ROCK, par)
    R0 = math.sqrt(B * B + H * H)
    barrier = g * R0 - (g * sa) ** 2 / (2.0 * wn * wn) + \
        mb * g * (B * sa + hb * ca)
    return E < barrier


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    mode = disc[D_MODE]
    if mode == MODE_WALL_REST or (mode == MODE_ROCK and
                                  (at_end or opt[O_EARLY_EXIT] != 0.0)):
        if mode == MODE_WALL_REST:
            book_time(t, disc, met)
            track_u(y[0], met)
            if at_end:
                if par[FW_THETA_W] > par[F_ALPHA]:
                    return LEANING
                return SAFE_MOVING
        if (at_end or (opt[O_EARLY_EXIT] != 0.0 and
                       t >= excitation_end(hdr))) and \
                par[FW_THETA_W] > par[F_ALPHA] and trapped_on_wall(y, par, disc):
            book_time(t, disc, met)
            track_rotation(par[FW_WALL_SIDE] * par[FW_THETA_W], met)
            return LEANING
        if mode == MODE_WALL_REST:
            return RUNNING
    return decide_after_step(t, y, par, disc, hdr, opt, met, at_end,
                             par[FW_WALL_SIDE], par[FW_THETA_W])


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
def flexible_wall_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                           hist_y, hist_d, log, cnt):
    """One flexible-body run against a wall, with time history and event
    log."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def flexible_wall_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Flexible-body runs against a wall in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
