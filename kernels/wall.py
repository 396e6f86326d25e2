"""Rigid block rocking against a rear wall: one-sided rocking (physics.md 2).

Hogan (1992); Mennitti, Maiorano & Aversa (2021).  The block of
:mod:`.rigid` (state ``y = (theta, theta')`` [rad, rad/s], the same
equations of motion, Housner ground impacts) with a rigid wall on side
``w = par[P_WALL_SIDE]`` (+1 / -1): ``w*theta > 0`` tilts toward the wall.
While pivoting on the corner near the wall (``s == w``) the block touches
the wall at ``w*theta = theta_w = par[P_THETA_W]`` [rad] (the front end
computes it from the gap and the wall height; ``inf`` means the wall is
never reached).  Tilting away from the wall (``s == -w``) is plain Housner
rocking.  Parameters are those of :mod:`.rigid`'s asymmetric body (both
pivots' alpha, p and ground restitution, N_PAR_WALL; the symmetric block
fills both sides with its own) plus P_WALL_SIDE, P_THETA_W, P_E_W (wall
restitution e_w) and P_HOGAN.

Events while rocking (0-4 are :func:`.rigid.event`):

0 ground impact  g = s*theta                    terminal
1 overturn       g = theta_over - s*theta       terminal
2 peak           g = s*theta'                   observer
3 pass alpha     g = alpha - s*theta            observer
4 flight         g = G                          terminal
5 wall contact   g = theta_w - w*theta (s == w) terminal

Maps and states
---------------
* Wall impact: pivot kept, ``theta'+ = -e_w theta'-``; counted in
  ``met[M_WALL_IMPACTS]``.  Wall impacts with e_w <= 1 never add energy.
* Chatter against the wall (``|theta'+| < eps_omega`` or two impacts closer
  than ``eps_t``, physics.md 7) settles the block on the wall:
  ``theta = w theta_w``, ``theta' = 0``, mode MODE_WALL_REST, a static phase
  whose margin is ``w theta''`` at rest on the wall (the moments press the
  block on the wall while it is >= 0).  It is released (pivot w,
  ``theta' = 0``) when the margin becomes negative.  At and after the end of the
  excitation the margin uses the excitation's right limit (zero), so a
  pulse ending with a jump (rectangular, one-cosine, a record) releases the
  block exactly at its end.
* Gap d = 0 (``par[P_HOGAN] = 1``, ``theta_w = 0``): Hogan's one-sided
  rocking.  The block only pivots on the far corner; at theta = 0 ground
  and wall impacts coincide and ``theta'+ = -r theta'-`` with the pivot
  kept, where r = e_w (the wall restitution is Hogan's r).  Each such
  impact counts as a ground and as a wall impact.  From rest the block
  uplifts only away from the wall (``w a_g > G tan(alpha)``).
* Small-gap limit (``0 < theta_w < SMALL_GAP_ANGLE``, the flexible wall's
  threshold): the wall is taken at theta = 0 and the block rocks as
  Hogan's, with r = e^2 e_w.  Derivation: arriving at theta = 0 on the
  far corner with theta'-, the Housner impact gives e theta'- on the near
  corner, the wall (reached after theta_w / |theta'| s) -e_w e theta'-,
  and the return to theta = 0 a second Housner impact, -e^2 e_w theta'-
  back on the far corner; the moments act over a rotation theta_w only, so
  as theta_w -> 0 the three impacts become one map, and an uplift toward
  the wall is stopped at once (the block stays in contact, the wall takes
  the push).  A bounce too slow to reach the wall (|theta'|^2 below about
  2 p^2 theta_w) gives -e^2 theta'- instead: the same for e_w = 1, and
  an energy below theta_w [M g R] otherwise.  Without the limit a wall at
  a gap of nanometres (1e-10 rad) makes the block cycle through the three
  impacts every few microseconds until the step budget runs out.  Such a
  start on the near corner (0 < w theta0 <= theta_w) runs the d > 0 model
  until its first ground impact, which puts it on the far corner.  The
  combined impact counts as a ground and a wall impact; max rotations
  toward the wall are 0 instead of theta_w (< 1e-7 rad).
* Elastic bounces below the resolution: a wall impact elastic at the
  tolerance (restitution r, e_w or Hogan's, with 1 - r^2 <= rtol) whose
  rebound kinetic energy theta'+^2 / (2 p^2) is below rtol (1 - cos alpha)
  [M g R] ends the sequence as chatter does (rest on the wall, or at d = 0
  and small gaps the rest test at theta = 0).  An elastic wall does not
  shorten the bounces, so under a steady push or after the excitation the
  block bounces at a constant tiny speed for ever (one impact every
  microsecond or so) and the chatter rule never fires.  Such a motion's
  energy is below the error the solver's tolerance allows on the energy
  (rtol times its scale, the barrier 1 - cos alpha): at the resolution
  asked for the block is at rest, and resting drops that energy, never
  adds any.  With 1 - r^2 > rtol the bounces converge (Zeno) and end by
  the chatter rule, as before.

Asymmetric body
---------------
An asymmetric RigidBody (:mod:`.rigid`, "Asymmetric body") runs the same
maps with each side's numbers: on pivot k it rocks by Housner's EOM with
alpha_k, p_k; a ground impact from pivot k onto j is theta'+ = e_k theta'-
(angular momentum about the new pivot, P_E / P_E_NEG); a wall impact keeps
the pivot (w) and multiplies theta' by -e_w; theta_w comes from the body's
wall-side face (the front end).  Energies E_k are in units of M g R_k
(zero at rest), E_k = theta'^2 / (2 p_k^2) + cos(alpha_k - k theta) -
cos(alpha_k); a ground impact turns E_k at theta = 0 into
E_j = rho_k E_k, rho_k = e_k^2 p_k^2 / p_j^2 (= e_k^2 I_O,j / I_O,k <= 1).
At gap 0 the body rests on both pivots, uplifts only onto the far pivot
-w (w a_g > G tan alpha_-w) and stays on it; Hogan's combined impact keeps
that pivot, so its inertia is the same before and after and the energy
ratio is r^2 whatever the sides: r = e_w (the per-side ground factor is 1;
the symmetric block's rule).  In the small-gap limit the three impacts
compose to r = e_-w e_w e_w(wall) = e_1 e_2 e_w: a ground impact onto the
near pivot, the wall, a ground impact back; r^2 = rho_-w rho_w e_w^2 =
e_1^2 e_2^2 e_w^2 <= 1 (e_1 e_2 = (I_G + M r_1 . r_2)^2 / (I_O,1 I_O,2)
<= 1 by Cauchy-Schwarz, or a given e <= 1).  Early decisions are per side:
safe once E_s is below the barrier 1 - cos(alpha_s) inside the well and,
on two-sided rocking, rho_s E_s below the other side's barrier.

Outcomes
--------
LEANING: at rest on the wall at the end of the run with theta_w > alpha,
or (exact, also used as an early decision) after the excitation, pivoting
on the near corner past alpha with free-rocking energy below the barrier
``1 - cos(alpha)``: the block can then never come back over alpha (wall
impacts do not add energy); with e_w < 1 it settles on the wall, with
e_w = 1 it bounces in the wall's well forever.  Leaning is never decided
early while the ground still shakes (a run whose t_end comes before the end
of the excitation reports the state at t_end).  Early safe decision: the
rule of :func:`.rigid.bounded_after_excitation` (inside the well,
``s*theta < alpha``, energy below the barrier), with the toward-wall peak
capped at theta_w and the energy lost at that wall impact folded exactly
into the next peak away from the wall (:func:`fold_peaks`).
"""
import math

import numpy as np

from .config import jit, jit_generic, jit_parallel
from .excitation import excitation_end, ground
from .hybrid import (check_energy, elastic_below_resolution, final_status,
                     integrate_hybrid, is_chatter, log_event, sweep_rows)
from .layout import SMALL_GAP_ANGLE
from .layout import (P_ALPHA, P_ALPHA_NEG, P_E, P_E_NEG, P_E_W, P_G, P_HOGAN,
                     P_P, P_P_NEG, P_THETA_OVER, P_THETA_W, P_WALL_SIDE)
from .layout import (D_MODE, D_PIVOT, D_STATIC, D_WALL_REST, EV_FLIGHT,
                     EV_REST, EV_WALL_IMPACT, EV_WALL_RELEASE, EV_WALL_REST,
                     FLIGHT, LEANING, MODE_REST, MODE_ROCK, MODE_WALL_REST,
                     M_IMPACTS, M_WALL_IMPACTS, N_DISC, O_EARLY_EXIT, O_RTOL,
                     O_T0, RUNNING, SAFE_BOUNDED, SAFE_REST)
from .rigid import (K_FLIGHT, K_IMPACT, K_OVERTURN, UPLIFT_RTOL, body_event,
                    body_ground_impact, body_rhs, body_start_rocking_or_rest,
                    body_static_margin, housner, impact_energy_factor, rhs,
                    init_state as rigid_init_state, observe, overturned,
                    peak_from_energy, track_rotation)
from .rigid import event as rigid_event
from .rigid import static_margin as rigid_static_margin

N_EVENTS = 6
K_WALL = 5


@jit
def side_alpha_p(par, s):
    """alpha and p of pivot s (P_* for +1, P_*_NEG for -1)."""
    if s > 0:
        return par[P_ALPHA], par[P_P]
    return par[P_ALPHA_NEG], par[P_P_NEG]


@jit
def block_alpha_p(par, s):
    """alpha and p of the symmetric block (either pivot)."""
    return par[P_ALPHA], par[P_P]


@jit
def block_energy_ratio(par, s):
    """rho of the symmetric block: e^2."""
    return par[P_E] * par[P_E]


@jit
def side_energy(theta, dtheta, s, alpha, p):
    """Free-rocking energy on pivot s / (M g R_s), zero at rest (as
    :func:`.rigid.free_energy`, with the side's alpha and p)."""
    return 0.5 * dtheta * dtheta / (p * p) + math.cos(alpha - s * theta) - math.cos(alpha)


@jit
def impact_energy_ratio(par, s):
    """rho_s: a ground impact leaving pivot s turns E_s into rho_s E_s
    (each in units of its side's M g R), rho_s = e_s^2 p_s^2 / p_-s^2."""
    if s > 0:
        return impact_energy_factor(par[P_E], par[P_P], par[P_P_NEG])
    return impact_energy_factor(par[P_E_NEG], par[P_P_NEG], par[P_P])


@jit
def one_sided(par):
    """Hogan's one-sided rocking: gap 0, or the small-gap limit."""
    return par[P_HOGAN] != 0.0 or par[P_THETA_W] < SMALL_GAP_ANGLE


@jit
def hogan_r(par):
    """Restitution of the combined ground and wall impact: Hogan's r = e_w
    at gap 0, e_1 e_2 e_w in the small-gap limit (e^2 e_w for the block)."""
    if par[P_HOGAN] != 0.0:
        return par[P_E_W]
    return par[P_E_NEG] * par[P_E] * par[P_E_W]


@jit
def rigid_bounce_unresolved(r, post, alpha, p, opt):
    """:func:`elastic_below_resolution` on a pivot of alpha, p: rebound
    energy theta'+^2 / (2 p^2) [M g R], scale the barrier 1 - cos(alpha)."""
    return elastic_below_resolution(r, 0.5 * post * post / (p * p),
                                    1.0 - math.cos(alpha), opt)


@jit_generic
def wall_events(k, t, y, par, disc, hdr, smp, ground_events):
    # Inlined at the Numba-IR level: a separately compiled wrapper around
    # the rigid events adds a call layer to the hottest function of the
    # driver (every event at every step) and cost ~25% with an inert wall.
    # The K_WALL root is written out here: an inlined helper returning it
    # cost the block's spectra another ~15% per run.
    if k == K_WALL:
        w = par[P_WALL_SIDE]
        if disc[D_PIVOT] == w:
            return par[P_THETA_W] - w * y[0], -w * y[1], True
        return np.inf, 0.0, True
    return ground_events(k, t, y, par, disc, hdr, smp)


@jit_generic
def event(k, t, y, par, disc, hdr, smp):
    return wall_events(k, t, y, par, disc, hdr, smp, body_event)


@jit_generic
def block_event(k, t, y, par, disc, hdr, smp):
    # The symmetric block's events read one alpha, p (rigid.event): the
    # per-side choice of body_event costs it ~14% per run.
    return wall_events(k, t, y, par, disc, hdr, smp, rigid_event)


@jit_generic
def wall_rest_margin(t, par, hdr, smp, sides):
    """w * theta'' at rest on the wall (>= 0: pressed on it; the resting
    phase ends when it becomes negative), physics.md 2.

    From the end of the excitation on, the right limit (no excitation) is
    used.  Negative as well when G <= 0, so that the flight event can fire
    after the release."""
    te = np.inf if t >= excitation_end(hdr) else t
    w = par[P_WALL_SIDE]
    tw = par[P_THETA_W]
    g = par[P_G]
    alpha, p = sides(par, w)
    ag, av = ground(te, hdr, smp)
    m = w * housner(w * tw, w, alpha, p, g, ag, av)
    return min(m, g + av)


@jit_generic
def hogan_rest_margin(t, par, hdr, smp, sides):
    """d = 0: full contact holds while w a_g <= G tan(alpha_-w) (uplift
    onto the far pivot only); the wall blocks any uplift toward it."""
    w = par[P_WALL_SIDE]
    alpha, _p = sides(par, -w)
    g = par[P_G]
    ag, av = ground(t, hdr, smp)
    G = g + av
    return min(G * math.tan(alpha) * (1.0 + UPLIFT_RTOL) - w * ag, G)


@jit_generic
def wall_static_margin(t, y, par, disc, hdr, smp, sides, two_sided_margin):
    if disc[D_MODE] == MODE_WALL_REST:
        return wall_rest_margin(t, par, hdr, smp, sides)
    if one_sided(par):
        return hogan_rest_margin(t, par, hdr, smp, sides)
    return two_sided_margin(t, y, par, disc, hdr, smp)


# The block's per-step callbacks read one alpha and p (the rigid module's
# symmetric functions), the asymmetric body's choose them per side: the
# choice, paid at every step, slowed the block's spectra by ~15%.
@jit
def block_static_margin(t, y, par, disc, hdr, smp):
    return wall_static_margin(t, y, par, disc, hdr, smp, block_alpha_p,
                              rigid_static_margin)


@jit
def static_margin(t, y, par, disc, hdr, smp):
    return wall_static_margin(t, y, par, disc, hdr, smp, side_alpha_p,
                              body_static_margin)


@jit
def start_from_rest(t, y, par, disc, hdr, smp, met, log, cnt):
    """Uplift test from theta = theta' = 0 (d = 0 or a small gap: away from
    the wall only)."""
    if one_sided(par):
        w = par[P_WALL_SIDE]
        alpha, _p = side_alpha_p(par, -w)
        ag, av = ground(t, hdr, smp)
        G = par[P_G] + av
        if G > 0.0 and w * ag <= G * math.tan(alpha) * (1.0 + UPLIFT_RTOL):
            disc[D_MODE] = MODE_REST
            disc[D_STATIC] = 1
            return RUNNING
    return body_start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log, cnt)


@jit_generic
def settle_on_wall_of(t, y, par, disc, hdr, smp, log, cnt, sides):
    """End of a chatter sequence at the wall: rest on it if pressed (``sides``:
    alpha and p of a pivot, side_alpha_p or block_alpha_p)."""
    w = par[P_WALL_SIDE]
    y[0] = w * par[P_THETA_W]
    y[1] = 0.0
    if wall_rest_margin(t, par, hdr, smp, sides) >= 0.0:
        disc[D_MODE] = MODE_WALL_REST
        disc[D_STATIC] = 1
        disc[D_WALL_REST] = 1
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[0], disc[D_PIVOT])
    # otherwise the moments already pull it off the wall: keep rocking


@jit
def release_from_wall(t, y, par, disc, log, cnt):
    w = par[P_WALL_SIDE]
    disc[D_MODE] = MODE_ROCK
    disc[D_STATIC] = 0
    disc[D_WALL_REST] = 0
    disc[D_PIVOT] = 1 if w > 0.0 else -1
    y[0] = w * par[P_THETA_W]
    y[1] = 0.0
    log_event(log, cnt, t, EV_WALL_RELEASE, 0.0, 0.0, y[0], disc[D_PIVOT])


@jit_generic
def wall_impact_of(t, y, par, disc, hdr, smp, opt, met, log, cnt, sides):
    """Wall impact: pivot kept, theta'+ = -e_w theta'- (physics.md 2); a
    chatter settles on the wall (``sides`` as :func:`settle_on_wall_of`)."""
    w = par[P_WALL_SIDE]
    alpha, p = sides(par, w)
    pre = y[1]
    post = -par[P_E_W] * pre
    y[0] = w * par[P_THETA_W]
    y[1] = post
    met[M_WALL_IMPACTS] += 1
    check_energy(pre * pre, post * post, met)
    track_rotation(y[0], met)
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, post, y[0], disc[D_PIVOT])
    if is_chatter(t, post, opt, met) or \
            rigid_bounce_unresolved(par[P_E_W], post, alpha, p, opt):
        settle_on_wall_of(t, y, par, disc, hdr, smp, log, cnt, sides)
    return RUNNING


@jit
def wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    return wall_impact_of(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                          side_alpha_p)


@jit
def hogan_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """d = 0 or a small gap: ground and wall impacts coincide at theta = 0;
    pivot kept on the far corner, theta'+ = -r theta'- (Hogan 1992; r of
    :func:`hogan_r`)."""
    alpha, p = side_alpha_p(par, disc[D_PIVOT])
    pre = y[1]
    r = hogan_r(par)
    post = -r * pre
    y[0] = 0.0
    y[1] = post
    met[M_IMPACTS] += 1
    met[M_WALL_IMPACTS] += 1
    check_energy(pre * pre, post * post, met)
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, post, 0.0, disc[D_PIVOT])
    if is_chatter(t, post, opt, met) or \
            rigid_bounce_unresolved(r, post, alpha, p, opt):
        y[1] = 0.0
        st = start_from_rest(t, y, par, disc, hdr, smp, met, log, cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, post, 0.0, 0.0, disc[D_PIVOT])
        return st
    return RUNNING


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        if disc[D_MODE] == MODE_WALL_REST:
            release_from_wall(t, y, par, disc, log, cnt)
            return RUNNING
        return start_from_rest(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == K_IMPACT:
        # on the near corner (a start inside a small gap) the first ground
        # impact is Housner's, to the far corner
        if par[P_HOGAN] != 0.0 or (one_sided(par) and
                                   disc[D_PIVOT] != par[P_WALL_SIDE]):
            return hogan_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)
        return body_ground_impact(t, y, par, disc, hdr, smp, opt, met, log,
                                  cnt)
    if k == K_WALL:
        return wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)
    if k == K_OVERTURN:
        return overturned(t, y[0], y[1], disc[D_PIVOT], met, log, cnt)
    if k == K_FLIGHT:
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], disc[D_PIVOT])
        return FLIGHT
    observe(k, t, y, disc, met, log, cnt)
    return RUNNING


@jit_generic
def trapped_on_wall(y, par, disc, sides):
    """Free motion (no excitation) can never bring the block back: it
    pivots on the near corner past alpha (so theta_w > alpha) with energy
    below the barrier, and wall impacts never add energy."""
    w = par[P_WALL_SIDE]
    if disc[D_PIVOT] != w or not par[P_THETA_W] < par[P_THETA_OVER]:
        return False
    a, p = sides(par, w)
    return w * y[0] > a and side_energy(y[0], y[1], w, a, p) < \
        1.0 - math.cos(a)


@jit_generic
def fold_peaks(y, par, disc, met, sides, energy_ratio):
    """Closed-form next peak on each side of free rocking with energy below
    the barrier (exact: energy is conserved between impacts, a ground
    impact leaving pivot k multiplies it by rho_k (e^2 for the block), a
    wall impact multiplies the kinetic part at theta_w by e_w^2); later
    peaks are lower."""
    w = par[P_WALL_SIDE]
    tw = par[P_THETA_W]
    hogan = one_sided(par)
    ew2 = par[P_E_W] * par[P_E_W]
    r2 = hogan_r(par) ** 2
    s = disc[D_PIVOT]
    a, p = sides(par, s)
    E = side_energy(y[0], y[1], s, a, p)
    if s * y[1] > 0.0:
        side = s
    elif hogan:
        side = s
        E *= r2
    else:
        side = -s
        E *= energy_ratio(par, s)
    for _ in range(2):
        a, p = sides(par, side)
        pk = peak_from_energy(a, E)
        if side == w and pk >= tw:
            pk = tw
            pe = math.cos(a - tw) - math.cos(a)
            E = pe + ew2 * (E - pe)
        track_rotation(side * pk, met)
        if hogan:
            E *= r2
        else:
            E *= energy_ratio(par, side)
            side = -side


@jit_generic
def wall_after_step(t, y, par, disc, hdr, smp, opt, met, at_end, sides,
                    energy_ratio):
    track_rotation(y[0], met)
    mode = disc[D_MODE]
    if at_end:
        if mode == MODE_WALL_REST:
            a_w, _p = sides(par, par[P_WALL_SIDE])
            if par[P_THETA_W] > a_w:
                return LEANING
            return SAFE_REST
        if mode != MODE_REST and t >= excitation_end(hdr) and \
                trapped_on_wall(y, par, disc, sides):
            track_rotation(par[P_WALL_SIDE] * par[P_THETA_W], met)
            return LEANING
        return final_status(disc, met)
    if opt[O_EARLY_EXIT] != 0.0 and mode == MODE_ROCK and \
            t >= excitation_end(hdr):
        s = disc[D_PIVOT]
        a, p = sides(par, s)
        hogan = one_sided(par)
        if hogan and s == par[P_WALL_SIDE]:
            return RUNNING      # a start inside a small gap: until its impact
        E = side_energy(y[0], y[1], s, a, p)
        if E < 1.0 - math.cos(a):
            # two-sided: the other side's barrier too (implied for the block)
            a_o, _p = sides(par, -s)
            if s * y[0] < a and (hogan or energy_ratio(par, s) * E <
                                 1.0 - math.cos(a_o)):
                fold_peaks(y, par, disc, met, sides, energy_ratio)
                return SAFE_BOUNDED
            if trapped_on_wall(y, par, disc, sides):
                track_rotation(par[P_WALL_SIDE] * par[P_THETA_W], met)
                return LEANING
    return RUNNING


@jit
def block_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    return wall_after_step(t, y, par, disc, hdr, smp, opt, met, at_end,
                           block_alpha_p, block_energy_ratio)


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    return wall_after_step(t, y, par, disc, hdr, smp, opt, met, at_end,
                           side_alpha_p, impact_energy_ratio)


@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    """As :func:`.rigid.init_state`; with d = 0 the pivot is the far corner
    (a start at theta = 0 moving toward the wall impacts at once)."""
    rigid_init_state(t0, y, par, disc, hdr, smp, met, log, cnt)
    w = par[P_WALL_SIDE]
    if par[P_HOGAN] != 0.0 and disc[D_MODE] == MODE_ROCK and \
            disc[D_PIVOT] == w:
        disc[D_PIVOT] = -1 if w > 0.0 else 1


@jit
def run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
        cnt):
    """A run of the asymmetric body (each side's alpha, p in the rhs)."""
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_hybrid(body_rhs, event, transition, static_margin,
                            after_step, N_EVENTS, y, par, disc, hdr, smp,
                            opt, t_eval, met, hist_t, hist_y, hist_d, log,
                            cnt)


@jit
def block_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
              log, cnt):
    """A run of the symmetric block: the same maps, with the one-sided rhs
    and events of :mod:`.rigid` (both sides' slots hold the same values)."""
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_hybrid(rhs, block_event, transition,
                            block_static_margin, block_after_step, N_EVENTS,
                            y, par, disc, hdr, smp, opt, t_eval, met, hist_t,
                            hist_y, hist_d, log, cnt)


# ---------------------------------------------------------------- entries
@jit
def rigid_wall_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                        hist_d, log, cnt):
    """One run against a wall, with time history and event log (see
    :func:`.rigid.rigid_simulate` for the arguments)."""
    return block_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                     hist_d, log, cnt)


@jit_parallel
def rigid_wall_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """One-sided runs in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(block_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)


@jit
def wall_body_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                       hist_d, log, cnt):
    """One run of the asymmetric RigidBody against a wall (model
    "wall_body"; the parameter vector carries both sides)."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def wall_body_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Runs of the asymmetric body against a wall in parallel."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
