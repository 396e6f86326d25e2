"""Fuzz suite of issue #14 (item 2): random scenes for every model family.

Draws random scenes the way a user sweeping parameters would, runs them in batches through
``overturning_spectrum`` (one body per batch, a grid of pulses, both signs) and a sample of
them through ``simulate``, and classifies every run (a *case* is one cell of a batch's main
spectrum grid):

``ok``                    definite status, finite results, every invariant checked on it held
``failed:<reason>``       the run's status is ``failed:*`` (step budget, event location ...)
``nan``                   a definite run with NaN/inf in max_rotation, time_end or the final state
``hang``                  the batch (or a check run on it) took longer than ``--time-limit``
``error:<Exception>``     the front end raised on a scene the draw considers valid
``violated:<invariant>``  an invariant failed on this cell (list below)

Every family: a fixed-step cell that ends ``failed:unstable-step`` is counted under
``reported`` as ``unstable_step_named`` (a numerical limit the user set, not a failure) only when
the error is honest: ``simulate``'s warning names a step that "would be stable" and the cell run
at that step ends definite (``unstable_step_named``); otherwise it stays ``failed:unstable-step``.

Invariants and their tolerance rules
------------------------------------
"Same result" of two runs means: same ``outcome``, and ``max_rotation_ratio`` (max|theta|/alpha)
within ``REL_EXACT`` = 1e-6 relative.  A pair that differs is re-run once with the tight
adaptive solver (rtol = ``TIGHT_RTOL``, ``early_exit=False``); if the tight pair is the same,
the original difference is an integration-error effect at an outcome boundary and is counted
under ``boundary:<invariant>`` (reported, not a failure).  A pair whose outcomes agree at the
tight rtol but whose max rotations still differ is run once more at ``TIGHTER_RTOL`` = 1e-13: if the
outcomes still agree and the difference shrinks at least tenfold (``CONVERGING``) for a hundredfold
tighter tolerance, it is integration error of an ill-conditioned run, not a broken invariant (seed
2027: slender blocks, b/h ~ 0.02, under one-cosine pulses 0.3 % above uplift chatter through ~1 700
impacts at 1e-3 alpha, where the local error control does not bound the global error of the
maximum; the scaled pair differs by 4.6 % at rtol 1e-11 and by 7e-5 at 1e-13), counted under
``boundary:<invariant> (converging)``.  If the pair still differs, or a run of the pair failed, the
cell gets ``violated:<invariant>``.

* ``mirror``: a two-sided body (every family but the wall ones) under sign -1 gives the same
  result as under sign +1 (the one-sine, half-sine and one-cosine pulses of sign -1 are exact
  mirror images), run with ``early_exit=False``.  Wall, flexible_wall, contact and foundation_wall
  families: (wall side s, sign +1) against (side -s, sign -1).
* ``scale``: the same scene with every length scaled by k (p by 1/sqrt(k); wall gap, height and
  slide tolerance scaled; t_after, fixed dt and the chatter thresholds scaled in time), the same
  a_p/(g tan alpha) and omega_p/p.  Not exact in floating point (atol is absolute in rad/s):
  boundary rule.  A pair that still differs at the tight rtol is counted under ``reported`` as
  ``scale_ill_conditioned`` (not a failure) when ``ill_conditioned`` shows the cell's result is
  not determined to REL_EXACT by its input: the unscaled cell at the tight rtol with the
  amplitude changed by 1e-14 and 2e-14 relative spans a range of results that holds the scaled
  run's (flexible_wall:2027:553, :583: elastic wall, undamped column, 60 and 2 000 wall impacts;
  a 1e-14 change moves max|theta|/alpha by 1e-4 and 2e-2).  Not run for the contact family.
* ``mu_inf``: ``Friction(1e6)`` against no friction (friction families; the flexible one with
  ``lift_off="hold"`` and the same base mass; cells where the friction run held a lift-off are
  not comparable and skipped).  Outcome only ("slide" counts as "safe" for mu = 1e6 with a
  residual slip below 1 um).  The frictionless block holds its pivot bilaterally, so the two
  agree only while its pivot force stays in the cone |F| <= 1e6 N: where it needs tension, the
  Coulomb block slips (free corner pressed; as mu -> inf the slip tends to a finite one with
  N -> 0) or lifts off ("stop": outcome "flight").  Friction family: a pair that still differs
  at the tight rtol is counted under ``reported`` as ``mu_inf_tension`` (not a failure) when
  ``mu_inf_tension`` shows, apart from the friction kernel, the frictionless pivot leaving the
  cone and Friction(1e6) parting there; any other difference is ``violated:mu_inf`` (with a
  given e: ``violated:mu_inf:given-e``).  foundation_friction: Friction(1e6) against the
  two-spring model (tests/test_foundation_friction.py: "never slips and reproduces the two-spring
  model"); with no corner on its spring the two-spring model holds the base centre horizontally
  fixed, a horizontal force without a normal one, while the sliding block flies free: a pair
  that still differs at the tight rtol is counted under ``reported`` as ``mu_inf_flight`` when
  ``mu_inf_flight`` shows both runs taking off at the same time, else ``violated:mu_inf``.  A
  Friction(1e6) run that fails (at the drawn rtol the slip just before take-off, with a friction
  force 1e6 N, is too stiff for the step budget: seed 14, bench/README.md) counts as
  ``violated:mu_inf`` by the rule of every check run.
* ``tall_wall``: a wall at gap >= 2h (either side, any height) against no wall (wall family;
  README: "bit for bit"; foundation_wall: out of the top corner's reach on both foundations,
  against the two-spring or switching model without a wall, tests/test_foundation_wall.py "out
  of reach is the no-wall run").  flexible_wall: gap >= 2H (H = body.H) against the flexible
  kernel, the same *status* and max rotation to REL_EXACT (README: "step for step").  contact:
  gap >= 2h against the same friction scene without a wall (rigid_friction, or the contact model
  in flight mode), outcome only; skipped (not comparable): cells where the tall-wall run hit
  the wall (a block that slides or flies can travel to a wall at gap >= 2h), and cells whose reference
  stopped at lift-off (lift_off "stop", outcome "flight": with a wall the contact model always
  flies, README "The contact model").
* ``early_exit``: the spectrum run (``early_exit=True``) against ``simulate`` of the same cell
  (``early_exit=False``): same outcome (README: the early decisions are exact).
* ``energy``: in ``simulate`` runs, after the pulse has ended, the mechanical energy computed
  from the history never rises between two consecutive rows by more than ``ENERGY_TOL`` +
  ``ENERGY_TOL_RTOL`` rtol of the energy scale (max |E| over the run, at least the barrier
  1 - cos(alpha); rigid, wall, friction, contact: per pair of rows at least the size |T| + |V| of E's kinetic and
  potential terms, which the solver's relative error control bounds: in an overturning fall they
  reach M g R while E stays near the barrier).  Rigid, wall: E = theta'^2/(2p^2) +
  cos(alpha - |theta|) - cos(alpha) [M g R].  Friction: (d' + Y_G theta')^2/2 + (X_G theta')^2/2 + I_G theta'^2/(2M) + g Y_G.
  Flexible (all three): kinetic energy of the mass, base and rotary inertias with the base slip,
  + K u^2/2 + gravity (physics.md 3.4, 4.4; flexible_wall: no slip, the base mass of full
  contact).  Contact: the history's d, z are the base midpoint P, the CM is P + h (sin theta,
  cos theta): E = (v_Gx^2 + v_Gy^2)/2 + I_G theta'^2/(2M) + g (y_G - h).  The pivot-switch (I1)
  impact map is checked too since 52be7fd (where it would create energy the impact takes the
  full-contact map).  Two-spring foundation (foundation_wall's two-spring scenes,
  foundation_friction, flexible_foundation: ``two_spring_energy``): T + gravity + k_v
  max(delta, 0)^2/2 of each corner spring, per kg of the carried mass, the kernel's own E
  (kernels/foundation.py: dE/dt <= 0 in free motion, a released corner included; wall impacts
  keep or lose kinetic energy), measured per pair of rows against |T| + |V| as for the sliding
  blocks.  Not checked: the foundation family (its draw and counts predate
  ``two_spring_energy``; its two-spring scenes could use it), and the switching foundation, with or
  without a wall (the switching model gains energy at uplift by design).
* ``stiff``: (flexible family, reported only) omega_n/p = 1000 against ``rigid_equivalent()``:
  outcome mismatches are counted under ``stiff_mismatch``, never a failure.

Families: rigid, wall (rigid_wall), friction (rigid_friction), flexible, flexible_friction
(lift_off "stop" or "hold"), foundation (two-spring, switching, linear; the mass is lowered
where a spring or dashpot constant would pass the front end's 1e12, which changes no
dimensionless number, and a fixed step is coarsened to fit half the default step budget, with
at least 10 steps per period of the fastest mode), flexible_wall (a
FlexibleBody drawn as in flexible with a Wall drawn as in wall, gap > 0 only: gap 0 is refused
for flexible bodies) and contact (RigidBlock.rectangle, a wall with gap > 0 and height None or
>= 2h, Friction(mu) with lift_off "stop" or "flight", mu 0.05-2, or mu = inf with "flight" in
15 % of batches: the contact model).  The newer foundation models, each family a block or body
drawn as above on a foundation drawn as in foundation (mass clipped likewise; a FlexibleBody
carries the drawn mass as its own):

* foundation_wall: RigidBlock.rectangle on TwoSpringFoundation (model two_spring_wall) or
  SwitchingFoundation (switching_wall), half each, with a wall drawn as in wall, gap > 0 only;
  two-spring: height None or >= 2h only (lower walls are refused there), switching: lower walls
  too, the gap doubled (no further random draw) until the wall lies beyond the contact phase's
  uplift rotation theta_y (``_switching_wall_gap``; the front end refuses a nearer wall).
  Checks: mirror (the wall moved to the other side), scale, tall_wall, early_exit, energy on
  the two-spring scenes only.
* foundation_friction: RigidBlock.rectangle on TwoSpringFoundation with Friction(mu) as in
  friction, lift_off "stop" or "flight" (the kernel flies when no corner touches either way):
  model two_spring_friction.  Checks: mirror, scale, mu_inf, early_exit, energy.
* flexible_foundation: a FlexibleBody drawn as in flexible (base_mass_ratio None: the front
  end's 0.1 on a foundation) on TwoSpringFoundation: model flexible_two_spring; a fixed step
  takes the body's frequencies on the springs (``flexible_frequencies``).  Checks: mirror,
  scale, early_exit, energy (column, base and springs).

Usage::

    python bench/fuzz.py --cases 2000 --seed 1               # every family
    python bench/fuzz.py --family wall --cases 500 --out wall.csv
    python bench/fuzz.py --replay 'wall:1:17'                  # one batch, verbose

Every batch has its own seed (``family:seed:batch``); ``--replay`` re-runs it and prints its
parameters and the failing cells.  Run with ``NUMBA_NUM_THREADS=1`` on a shared machine.
"""
from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import math
import re
import signal
import sys
import time
import warnings
from collections import Counter, defaultdict

import numpy as np
import pandas as pd

FAMILIES = ("rigid", "wall", "friction", "flexible", "flexible_friction", "foundation", "flexible_wall",
            "contact", "foundation_wall", "foundation_friction", "flexible_foundation")
WALL_FAMILIES = ("wall", "flexible_wall", "contact", "foundation_wall")
# the draw takes a fixed dt per period of the fastest frequency it knows (omega_p, omega_n), but
# scenes have stiffer modes it does not see: a flexible body's light base sliding on a held
# lift-off (sqrt((1 + mb)/mb) omega_n) or turning about its pivot where the mass passes near the
# column line through it (u ~ sB; flexible_wall:2026:136), a contact model's stick-slip: whether
# such a failed:unstable-step is a limit the user set is decided by unstable_step_named
PULSES = ("one-sine", "half-sine", "one-cosine")
REL_EXACT = 1e-6
TIGHT_RTOL = 1e-11
TIGHTER_RTOL = 1e-13       # the convergence test of a pair that still differs at TIGHT_RTOL
CONVERGING = 0.1           # ... its difference must shrink at least this much
ENERGY_TOL = 1e-6          # relative to the energy scale, plus ENERGY_TOL_RTOL * rtol
ENERGY_TOL_RTOL = 100.0
T_AFTER = 10.0
FAILURE_PREFIXES = ("failed", "nan", "hang", "error", "violated")


# --------------------------------------------------------------------------- draws
def _logu(rng, lo, hi):
    return float(10 ** rng.uniform(math.log10(lo), math.log10(hi)))


def batch_seed(family, seed, batch):
    """The integer seed of one batch, from its name ``family:seed:batch``."""
    h = hashlib.sha256(f"{family}:{seed}:{batch}".encode()).digest()
    return int.from_bytes(h[:8], "little")


def _alpha(rng, hi=0.9):
    u = rng.uniform()
    if u < 0.3:
        return _logu(rng, 0.01, 0.1)          # slender
    if u < 0.8:
        return float(rng.uniform(0.1, 0.45))
    return float(rng.uniform(0.45, hi))       # stout


def _rect(rng, alpha):
    R = _logu(rng, 0.05, 20.0)
    return {"kind": "rectangle", "b": R * math.sin(alpha), "h": R * math.cos(alpha)}


def _rigid_body(rng, rect_only=False):
    alpha = _alpha(rng)
    d = _rect(rng, alpha) if (rect_only or rng.uniform() < 0.75) else \
        {"kind": "alpha_p", "alpha": alpha, "p": _logu(rng, 0.5, 20.0)}
    d["e"] = None if rng.uniform() < 0.7 else float(rng.uniform(0.0, 1.0))
    return d


def _flex_body(rng, friction=False):
    d = {"kind": "flexible", "alpha": float(rng.uniform(0.05, 0.6)), "p": _logu(rng, 0.5, 10.0),
         "omega_n_over_p": _logu(rng, 2.0, 300.0),
         "zeta": 0.0 if rng.uniform() < 0.3 else float(rng.uniform(0.0, 0.1)),
         "impact": "full-contact", "e": None, "rotary_inertia_ratio": 0.0,
         "base_mass_ratio": None, "base_cm_height": 0.0}
    if not friction and rng.uniform() < 0.15:
        d["impact"] = "pivot-switch"
        d["e"] = float(rng.uniform(0.8, 1.0))
    elif rng.uniform() < 0.4:
        d["base_mass_ratio"] = float(rng.uniform(0.02, 0.5))
    if rng.uniform() < 0.3:
        d["rotary_inertia_ratio"] = float(rng.uniform(0.0, 0.5))
    if friction and rng.uniform() < 0.3:
        R0 = 9.80665 / (d["p"] ** 2 * (1 + d["rotary_inertia_ratio"]))
        d["base_cm_height"] = float(rng.uniform(0.0, 0.3)) * R0 * math.cos(d["alpha"])
    return d


def _flex_H(B):
    """Half-height H of the flexible body drawn by ``_flex_body`` (R0 cos alpha)."""
    return 9.80665 / (B["p"] ** 2 * (1 + B["rotary_inertia_ratio"])) * math.cos(B["alpha"])


def _wall_draw(rng, h, gap_zero=True, low=True):
    """A wall as the wall family draws it (h: the body's half-height).  ``gap_zero=False``: gap > 0
    only (the 5 % of gap-0 draws go to the small gaps); ``low=False``: height None or >= 2h."""
    u = rng.uniform()
    if gap_zero and u < 0.05:
        gap = 0.0
    elif u < 0.15:
        gap = 2 * h * _logu(rng, 1.0, 3.0)
    else:
        gap = _logu(rng, 1e-9, 2 * h)
    return {"gap": gap, "side": int(rng.choice([-1, 1])),
            "height": None if rng.uniform() < 0.7 else 2 * h * _logu(rng, 0.1 if low else 1.0, 2.0),
            "restitution": 1.0 if rng.uniform() < 0.5 else float(rng.uniform(0.0, 1.0))}


def _friction(rng):
    mu_s = _logu(rng, 0.05, 2.0)
    return {"mu_s": mu_s, "mu_k": mu_s if rng.uniform() < 0.5 else mu_s * float(rng.uniform(0.5, 1.0))}


def draw_batch(family, seed, batch, chunk=32):
    """Parameters of one batch (JSON-serialisable): body, effects, solver, pulse kind and grid."""
    s = batch_seed(family, seed, batch)
    rng = np.random.default_rng(s)
    P = {"family": family, "id": f"{family}:{seed}:{batch}", "wall": None, "friction": None,
         "foundation": None, "mass": 1.0}
    if family == "rigid":
        P["body"] = _rigid_body(rng)
    elif family == "wall":
        P["body"] = _rigid_body(rng, rect_only=True)
        P["wall"] = _wall_draw(rng, P["body"]["h"])
    elif family == "flexible_wall":
        P["body"] = _flex_body(rng)
        P["wall"] = _wall_draw(rng, _flex_H(P["body"]), gap_zero=False)
    elif family == "contact":
        P["body"] = _rigid_body(rng, rect_only=True)
        # gap 0 and walls lower than the body since the contact model takes them (e82a3c9, cfc1efa);
        # batches drawn before (ids in bench/README.md up to then) had gap > 0 and tall walls
        P["wall"] = _wall_draw(rng, P["body"]["h"])
        if rng.uniform() < 0.15:
            P["friction"] = {"mu_s": math.inf, "mu_k": math.inf, "lift_off": "flight"}
        else:
            P["friction"] = _friction(rng)
            P["friction"]["lift_off"] = "stop" if rng.uniform() < 0.5 else "flight"
    elif family == "friction":
        P["body"] = _rigid_body(rng)
        P["friction"] = _friction(rng)
    elif family == "flexible":
        P["body"] = _flex_body(rng)
    elif family == "flexible_friction":
        P["body"] = _flex_body(rng, friction=True)
        P["friction"] = _friction(rng)
        P["friction"]["lift_off"] = "stop" if rng.uniform() < 0.5 else "hold"
    elif family == "foundation":
        P["body"] = _rigid_body(rng, rect_only=True)
        P["body"]["e"] = None
        _foundation_draw(rng, P, ["two-spring", "switching", "linear"], [0.4, 0.3, 0.3])
    elif family == "foundation_wall":
        P["body"] = _rigid_body(rng, rect_only=True)
        P["body"]["e"] = None
        _foundation_draw(rng, P, ["two-spring", "switching"], [0.5, 0.5])
        # two-spring: gap > 0 and walls at least as tall as the body only (the front end refuses
        # the rest, fastrock.model.foundation.wall_limit_angle); switching: lower walls too (its
        # rocking phase is the rigid wall model's), gap > 0; the gap is raised past the contact
        # phase's reach after the mass is clipped (_switching_wall_gap)
        P["wall"] = _wall_draw(rng, P["body"]["h"], gap_zero=False,
                               low=P["foundation"]["type"] == "switching")
    elif family == "foundation_friction":
        P["body"] = _rigid_body(rng, rect_only=True)
        P["body"]["e"] = None
        _foundation_draw(rng, P, ["two-spring"], [1.0])
        P["friction"] = _friction(rng)
        # the two_spring_friction kernel slides and flies whatever lift_off says: both are drawn
        P["friction"]["lift_off"] = "stop" if rng.uniform() < 0.5 else "flight"
    elif family == "flexible_foundation":
        P["body"] = _flex_body(rng)
        # on springs the base moves: base_mass_ratio None is the front end's default 0.1, and the
        # impact law is not used (soft contact); a pivot-switch draw keeps its e, which is unused
        _foundation_draw(rng, P, ["two-spring"], [1.0])
    else:
        raise ValueError(f"unknown family {family!r}")
    P["pulse"] = str(rng.choice(PULSES))
    n = max(1, int(round(math.sqrt(chunk / 2))))
    amps = []
    for _ in range(n):
        u = rng.uniform()
        amps.append(float(rng.uniform(0.995, 1.005)) if u < 0.1 else
                    (float(rng.uniform(0.3, 1.0)) if u < 0.25 else _logu(rng, 1.0, 40.0)))
    P["amps"] = amps
    P["freqs"] = [_logu(rng, 0.1, 60.0) for _ in range(n)]
    P["rtol"] = _logu(rng, 1e-10, 1e-4)
    P["dt_per"] = float(rng.uniform(30, 300)) if rng.uniform() < 0.1 else None
    P["sim_cells"] = [int(i) for i in rng.choice(2 * n * n, size=min(2, 2 * n * n), replace=False)]
    P["stiff"] = family == "flexible" and rng.uniform() < 0.25
    P["scale_k"] = _logu(rng, 0.03, 30.0)
    P["tall_side"] = int(rng.choice([-1, 1]))
    P["tall_gap"] = float(rng.uniform(1.0, 3.0))
    if P["foundation"] is not None:
        _clip_foundation_mass(P)
    if family == "foundation_wall" and P["foundation"]["type"] == "switching":
        _switching_wall_gap(P)
    return P


def _foundation_draw(rng, P, kinds, p):
    """The foundation family's draw of a foundation (kind, mass, omega/p, zeta, e_f) into P."""
    kind = rng.choice(kinds, p=p)
    P["mass"] = _logu(rng, 1.0, 1e4)
    P["foundation"] = {"type": str(kind), "omega_over_p": _logu(rng, 3.0, 300.0),
                       "zeta": float(rng.uniform(0.0, 0.2)),
                       "e_f": 1.0 if rng.uniform() < 0.5 else float(rng.uniform(0.5, 1.0))}


SWITCHING_WALL_MARGIN = 1.05


def _switching_wall_gap(P):
    """A switching foundation beside a wall needs the wall beyond its contact phase's reach:
    theta_w > theta_y = M g b / k_t (else the front end refuses the scene,
    ``switching_wall_par``).  theta_y/alpha is about (p/omega)^2, so a gap drawn down to 1e-9 m
    usually puts the wall inside it: the gap is doubled (no random draw) until theta_w >=
    SWITCHING_WALL_MARGIN theta_y.  Both angles are dimensionless, so the scale check's gap k
    times as large keeps the order."""
    from fastrock.kernels.layout import P_THETA_Y
    from fastrock.model.foundation import foundation_par
    fr = _fr()
    kw = build_scene(dict(P, wall=None), 1.0)
    theta_y = float(foundation_par(kw["body"], kw["foundation"], P["mass"])[P_THETA_Y])
    W = P["wall"]
    for _ in range(200):
        tw = fr.Wall(W["gap"], W["side"], W["height"], W["restitution"]).limit_angle(kw["body"])
        if tw >= SWITCHING_WALL_MARGIN * theta_y:
            break
        W["gap"] *= 2.0


def _clip_foundation_mass(P):
    """Lower the mass of a foundation batch whose spring or dashpot constants would exceed 1e12,
    the largest magnitude the front end accepts, at scale 1 or at the scale check's k (two-spring
    k_v goes as M/k, k_t and c_t of the others as M k and M k^1.5).  The constants come from
    ``from_vibration``, so every force is proportional to M and M changes no dimensionless number
    of the run (omega/p, zeta, e_f, the uplift rotation M g b / k_t): only the units.  The front
    end is right to refuse more: k_v = 1e12 N/m is five times the axial stiffness of a steel
    column 1 m^2 in section and 1 m high (2e11 N/m), and the draw's mass does not follow its size
    (foundation:2026:20 put 1.8 t on a block 6 mm wide and 17 cm tall, 230 m deep in steel, on
    corner springs of 1.9e12 N/m)."""
    unit = dict(P, mass=1.0)
    per_kg = 0.0
    for k in (1.0, P["scale_k"]):
        fd = build_scene(unit, k)["foundation"]
        per_kg = max([per_kg] + [abs(float(getattr(fd, f.name))) for f in dataclasses.fields(fd)])
    P["mass"] = min(P["mass"], 0.999e12 / per_kg)


# ----------------------------------------------------------------------- building
def _fr():
    import fastrock
    return fastrock


def build_body(B, scale=1.0, stiff=False):
    fr = _fr()
    if B["kind"] == "rectangle":
        return fr.RigidBlock.rectangle(B["b"] * scale, B["h"] * scale, e=B["e"])
    if B["kind"] == "alpha_p":
        return fr.RigidBlock(B["alpha"], B["p"] / math.sqrt(scale), e=B["e"])
    kw = {k: B[k] for k in ("alpha", "zeta", "impact", "e", "rotary_inertia_ratio", "base_mass_ratio")}
    kw["base_cm_height"] = B["base_cm_height"] * scale
    return fr.FlexibleBody(p=B["p"] / math.sqrt(scale), omega_n_over_p=1000.0 if stiff else B["omega_n_over_p"],
                           **kw)


def body_frequency(body):
    """Largest natural frequency of the body alone [rad/s] (for the fixed step)."""
    w = body.p
    if getattr(body, "kind", "") == "flexible":
        w = max(w, body.omega_n)
    return w


def build_scene(P, scale=1.0, variant=None):
    """Keyword arguments of overturning_spectrum / simulate for batch ``P``.

    ``variant``: None, "stiff", "rigid_equiv", "mu_inf", "no_friction", "tall_wall", "no_wall",
    "mirror_wall" (wall on the other side), "tight" (adaptive rtol TIGHT_RTOL)."""
    fr = _fr()
    body = build_body(P["body"], scale, stiff=variant in ("stiff", "rigid_equiv"))
    if variant == "rigid_equiv":
        body = body.rigid_equivalent()
    if variant == "no_friction" and P["family"] == "flexible_friction":
        body = dataclasses.replace(body, base_mass_ratio=body.base_mass(sliding=True))
    if P["foundation"] is not None and P["body"]["kind"] == "flexible":
        # a FlexibleBody carries its own (column) mass onto the foundation: the drawn one
        body = dataclasses.replace(body, mass=P["mass"])
    kw = {"body": body, "pulse": P["pulse"], "mass": P["mass"]}
    if P["wall"] is not None and variant != "no_wall":
        W = P["wall"]
        kw["wall"] = fr.Wall(W["gap"] * scale, -W["side"] if variant == "mirror_wall" else W["side"],
                             None if W["height"] is None else W["height"] * scale, W["restitution"])
    if variant == "tall_wall":
        h = body.H if P["body"]["kind"] == "flexible" else body.h
        kw["wall"] = fr.Wall(2 * h * P["tall_gap"], P["tall_side"], None, 1.0)
    if P["friction"] is not None and variant != "no_friction":
        F = P["friction"]
        lift = F.get("lift_off", "stop")
        if variant == "mu_inf":
            kw["friction"] = fr.Friction(1e6, slide_tolerance=1e-6,
                                         lift_off="hold" if P["family"] == "flexible_friction" else lift)
        else:
            kw["friction"] = fr.Friction(F["mu_s"], F["mu_k"], slide_tolerance=1e-3 * scale, lift_off=lift)
    if P["foundation"] is not None:
        from fastrock.model import foundation as FD
        D = P["foundation"]
        om = D["omega_over_p"] * body.p
        if D["type"] == "two-spring":
            kw["foundation"] = FD.TwoSpringFoundation.from_vibration(body, om, D["zeta"], P["mass"])
        elif D["type"] == "switching":
            kw["foundation"] = FD.SwitchingFoundation.from_vibration(body, om, D["zeta"], D["e_f"], P["mass"])
        else:
            kw["foundation"] = FD.LinearVibration.from_vibration(body, om, D["zeta"], P["mass"])
    tscale = math.sqrt(scale)       # time scales as 1/p = sqrt(length)
    if variant == "tight":
        kw["solver"] = fr.Solver(rtol=TIGHT_RTOL)
    elif P["dt_per"]:
        w = max(body_frequency(body), max(P["freqs"]) * body.p)
        fd = kw.get("foundation")
        if fd is not None:      # contact vibration, and the vertical mode of the corner springs
            w = max(w, P["foundation"]["omega_over_p"] * body.p)
            if hasattr(fd, "k_v") and P["body"]["kind"] == "flexible":
                # the vertical mode and the two coupled ones of column and rocking on the springs
                w = max([w] + [x for x in fd.flexible_frequencies(body) if math.isfinite(x)])
            elif hasattr(fd, "k_v"):
                I0 = P["mass"] * body.g * math.hypot(body.b, body.h) / body.p ** 2
                w = max(w, math.sqrt(2 * fd.k_v / P["mass"]), math.sqrt(4 * fd.k_v * body.b ** 2 / I0))
        steps_per_period = P["dt_per"]
        if fd is not None:
            # The corner springs' vertical mode sets w far above the rocking ones (sqrt(2 k_v/M) =
            # 3.2e3 rad/s, p = 1.6 rad/s in foundation:2026:15), and dt_per steps per period of it
            # over the longest run (pulse + t_after) can exceed the default step budget, which the
            # front end refuses up front naming max_steps (2.8e6 steps there).  A user who fixes a
            # step takes one the budget allows: here half of it (events add a few steps), with at
            # least 10 steps per period of w (the fixed-step DP5 is stable up to w dt = 3.3).
            span = max(fr.Pulse(1.0, f, 1, P["pulse"], amplitude_unit="g_tan_alpha",
                                frequency_unit="omega_p/p").end_time(body) for f in P["freqs"]) + T_AFTER * tscale
            budget = 0.5 * fr.Solver().max_steps
            steps_per_period = max(10.0, min(steps_per_period, budget * 2 * math.pi / (w * span)))
        kw["solver"] = fr.Solver(dt=2 * math.pi / w / steps_per_period)
    else:
        kw["solver"] = fr.Solver(rtol=P["rtol"], eps_t=1e-9 * tscale, eps_omega=1e-9 / tscale)
    kw["t_after"] = T_AFTER * tscale
    return kw


# ------------------------------------------------------------------------ running
class _Hang(Exception):
    pass


class _Alarm:
    """Interrupt the running kernel after ``limit`` s (the kernels stop within one step on
    Ctrl-C; ``run_sweep`` then returns the finished rows)."""

    def __init__(self, limit):
        self.limit = limit

    def __enter__(self):
        self.t0 = time.perf_counter()
        if self.limit and hasattr(signal, "setitimer"):
            def handler(signum, frame):
                raise KeyboardInterrupt
            self.old = signal.signal(signal.SIGALRM, handler)
            signal.setitimer(signal.ITIMER_REAL, self.limit)
        return self

    def __exit__(self, *exc):
        if self.limit and hasattr(signal, "setitimer"):
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, self.old)
        self.elapsed = time.perf_counter() - self.t0
        if exc[0] is KeyboardInterrupt:
            raise _Hang(f"interrupted after {self.elapsed:.1f} s")
        return False


def spectrum(P, amps, freqs, signs="both", early_exit=True, scale=1.0, variant=None, limit=None):
    """overturning_spectrum of batch P (or a variant); returns (df, seconds, hang)."""
    from fastrock.analyses.spectrum import overturning_spectrum
    kw = build_scene(P, scale, variant)
    body = kw.pop("body")
    kind = kw.pop("pulse")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with _Alarm(limit) as al:
            df = overturning_spectrum(body, amps, freqs, signs, pulse=kind, early_exit=early_exit,
                                      progress=False, **kw)
    n = len(amps) * len(freqs) * (2 if signs == "both" else 1)
    hang = len(df) < n or (limit is not None and al.elapsed > limit)
    return df, al.elapsed, hang


def _key(r):
    return (float(r["amplitude_ratio"]), float(r["frequency_ratio"]), int(r["sign"]))


def _bad_numbers(r):
    vals = [r["max_rotation"], r["time_end"], r["theta_end"], r["theta_dot_end"]]
    return not all(np.isfinite(float(v)) for v in vals)


def _same(a, b, outcome_only=False, status=False):
    """The tolerance rule: same outcome and max|theta|/alpha within REL_EXACT (``status``: the same
    status too, e.g. safe:rest against safe:moving)."""
    oa, ob = a["outcome"], b["outcome"]
    if oa != ob:
        return False
    if status and a["status"] != b["status"]:
        return False
    if outcome_only:
        return True
    ra, rb = float(a["max_rotation_ratio"]), float(b["max_rotation_ratio"])
    return abs(ra - rb) <= REL_EXACT * max(1.0, abs(ra), abs(rb))


def _mirror_pair_rows(df_a, df_b, flip=True):
    """Pairs (row_a, row_b) of cells with the same amplitude/frequency and opposite sign."""
    ib = {_key(r): r for _, r in df_b.iterrows()}
    out = []
    for _, r in df_a.iterrows():
        a, f, s = _key(r)
        other = ib.get((a, f, -s if flip else s))
        if other is not None:
            out.append((r, other))
    return out


class BatchResult:
    def __init__(self, P):
        self.P = P
        self.cases = {}            # key -> dict (row summary + tags)
        self.tags = defaultdict(set)
        self.details = defaultdict(list)
        self.times = {}
        self.boundary = Counter()
        self.reported = Counter()
        self.skipped = Counter()
        self.checked = Counter()

    def tag(self, key, kind, detail=""):
        self.tags[key].add(kind)
        if detail:
            self.details[key].append(f"{kind}: {detail}")


def _pair_check(res, name, P, cells, run_a, run_b, outcome_only=False, skip=None, limit=None, status=False,
                explain=None, variants=None):
    """Run two variants on ``cells`` and compare them row by row (with the tight re-run rule).

    run_a / run_b: functions (tight: False, True or an rtol) -> dict key -> row (key of the main
    grid cell).
    ``explain(key, row_a, row_b)``: for a pair that still differs at the tight rtol (its tight
    rows given, or None), (tag, detail) when an independent check shows the two variants are not
    comparable on that cell (counted under ``reported`` as ``<name>_<tag>``, not a failure), else
    None."""
    try:
        A, ta, ha = run_a(False)
        B, tb, hb = run_b(False)
    except _Hang as e:
        for k in cells:
            res.tag(k, "hang", f"{name} check: {e}")
        return
    except Exception as e:  # noqa: BLE001
        for k in cells:
            res.tag(k, f"error:{type(e).__name__}", f"{name} check: {e}")
        return
    res.times[name] = ta + tb
    if ha or hb:
        for k in cells:
            res.tag(k, "hang", f"{name} check took {ta + tb:.1f} s")
    diff = []
    for k in cells:
        if k not in A or k not in B:
            continue
        if any(t.startswith(("failed", "hang", "error")) for t in res.tags.get(k, ())) or \
                any(d.startswith("unstable_step_named") for d in res.details.get(k, ())):
            # the main run failed already (counted there) or stopped at the unstable fixed step
            # that its error names (reported): no result to compare
            res.skipped[name] += 1
            continue
        a, b = A[k], B[k]
        if skip is not None and skip(a, b):
            res.skipped[name] += 1
            continue
        res.checked[name] += 1
        if a["status"].startswith("failed") or b["status"].startswith("failed"):
            # a check run (variants: the build_scene variants of run_a, run_b) that stops at an
            # unstable fixed step its error names honestly is the user's limit, as for main runs
            why = [unstable_step_named(P, k, limit, v) for r, v in zip((a, b), variants or (None, None))
                   if r["status"].startswith("failed")] if variants else [None]
            if all(w is not None for w in why):
                res.checked[name] -= 1
                res.skipped[name] += 1
                res.reported[f"{name}_unstable_step_named"] += 1
                res.details[k].append(f"{name}_unstable_step_named: {'; '.join(why)}")
                continue
            res.tag(k, f"violated:{name}", f"check run status {a['status']} / {b['status']}")
            continue
        if not _same(a, b, outcome_only, status):
            diff.append(k)
    if not diff:
        return
    try:
        At, _, _ = run_a(True)
        Bt, _, _ = run_b(True)
    except Exception as e:  # noqa: BLE001
        At, Bt = {}, {}
        for k in diff:
            res.tag(k, f"violated:{name}", f"tight re-run raised {e!r}")
        return
    converging = _converging(name, diff, At, Bt, run_a, run_b, outcome_only, status)
    for k in diff:
        a, b = A[k], B[k]
        what = (f"{a['status'] if status else a['outcome']} {float(a['max_rotation_ratio']):.9g} vs "
                f"{b['status'] if status else b['outcome']} {float(b['max_rotation_ratio']):.9g}")
        if k in At and k in Bt and _same(At[k], Bt[k], outcome_only, status) \
                and not At[k]["status"].startswith("failed"):
            res.boundary[name] += 1
            continue
        if k in converging:
            res.boundary[f"{name} (converging)"] += 1
            res.details[k].append(f"{name} converging ({what}): {converging[k]}")
            continue
        why = explain(k, At.get(k), Bt.get(k)) if explain is not None else None
        if why:
            # not comparable, for a physical reason checked independently (``explain``)
            res.reported[f"{name}_{why[0]}"] += 1
            res.details[k].append(f"{name}_{why[0]} ({what}): {why[1]}")
        elif name == "mu_inf" and P["body"].get("e") is not None:
            # README (friction): a given e that friction cannot hold is not applied, so mu -> inf
            # tends to the frictionless block only with Housner's e; kept apart
            res.tag(k, "violated:mu_inf:given-e", what)
        else:
            tw = (f"; tight: {At[k]['outcome']} {float(At[k]['max_rotation_ratio']):.9g} vs {Bt[k]['outcome']} "
                  f"{float(Bt[k]['max_rotation_ratio']):.9g}" if k in At and k in Bt else "")
            res.tag(k, f"violated:{name}", what + tw)


def _converging(name, diff, At, Bt, run_a, run_b, outcome_only, status):
    """Cells of ``diff`` whose pair agrees in outcome at the tight rtol and whose max-rotation
    difference shrinks at least CONVERGING-fold at TIGHTER_RTOL with the outcomes still equal:
    {key: detail} (module docstring)."""
    def rot(row):
        return float(row["max_rotation_ratio"])
    cand = [k for k in diff if k in At and k in Bt and not outcome_only
            and _same(At[k], Bt[k], True, status) and not At[k]["status"].startswith("failed")]
    if not cand:
        return {}
    try:
        A2, _, _ = run_a(TIGHTER_RTOL)
        B2, _, _ = run_b(TIGHTER_RTOL)
    except Exception:  # noqa: BLE001
        return {}
    out = {}
    for k in cand:
        if k not in A2 or k not in B2 or not _same(A2[k], B2[k], True, status):
            continue
        d1, d2 = abs(rot(At[k]) - rot(Bt[k])), abs(rot(A2[k]) - rot(B2[k]))
        if d2 <= CONVERGING * d1:
            out[k] = (f"difference {d1:.3g} at rtol {TIGHT_RTOL:g}, {d2:.3g} at {TIGHTER_RTOL:g} "
                      f"({rot(A2[k]):.9g} vs {rot(B2[k]):.9g})")
    return out


MU_INF = 1e6              # the "mu -> inf" friction of the mu_inf check


def pivot_forces(body, theta, w, s, ag, G):
    """Friction force F and normal force N per unit mass [m/s^2] that the pivot s of a rigid
    block rocking without slip needs (arrays), from Newton-Euler of physics.md 4.3 with d'' = 0
    (the frictionless kernel's motion); computed here in numpy, apart from the kernels."""
    from fastrock.running.models import rigid_friction_par
    from fastrock import Friction
    from fastrock.kernels import layout as L
    par = rigid_friction_par(body, Friction(1.0))
    b, h, iG = par[L.Q_B], par[L.Q_H], par[L.Q_IG]
    X = -s * b * np.cos(theta) + h * np.sin(theta)
    Y = s * b * np.sin(theta) + h * np.cos(theta)
    tdd = (G * X - ag * Y) / (iG + X * X + Y * Y)
    return ag + Y * tdd - X * w * w, G - X * tdd - Y * w * w


def first_cone_exit(body, run, rerun=None, mu=MU_INF):
    """First time at which the bilateral pivot of a frictionless ``run`` (rigid kernel) needs a
    force outside the cone |F| <= mu N (for mu = 1e6: N <~ 0, tension), the time of the row
    before it, and the smallest N seen [m/s^2]; (inf, inf, N_min) if never.  The history rows are
    scanned, and with ``rerun`` (t_eval -> history of the same run) also 128 points inside the
    steps next to every row with N < 0.05 g, where a dip between two rows hides (grazing)."""
    def scan(hh):
        t = hh["t"].to_numpy()
        s = hh["pivot"].to_numpy()
        rock = s != 0
        F, N = pivot_forces(body, hh["theta"].to_numpy(), hh["theta_dot"].to_numpy(), np.where(rock, s, 1),
                            hh["a_g"].to_numpy(), body.g + hh["a_v"].to_numpy())
        return t, rock, F, N

    t, rock, F, N = scan(run.history)
    if rerun is not None:
        low = np.flatnonzero(rock & (N < 0.05 * body.g))
        if low.size:
            te = np.unique(np.concatenate([np.linspace(t[max(i - 1, 0)], t[min(i + 1, t.size - 1)], 129)
                                           for i in low]))
            td, rd, Fd, Nd = scan(rerun(te))
            keep = rd & (td > t[0])
            order = np.argsort(np.concatenate([t, td[keep]]), kind="stable")
            t = np.concatenate([t, td[keep]])[order]
            rock = np.concatenate([rock, rd[keep]])[order]
            F = np.concatenate([F, Fd[keep]])[order]
            N = np.concatenate([N, Nd[keep]])[order]
    n_min = float(np.min(np.where(rock, N, np.inf)))
    bad = rock & (np.abs(F) > mu * N)
    if not bad.any():
        return np.inf, np.inf, n_min
    i = int(np.argmax(bad))
    return float(t[i]), float(t[max(i - 1, 0)]), n_min


def mu_inf_tension(P, key, limit=None):
    """Why ``Friction(1e6)`` and the frictionless block (friction family) may differ on cell
    ``key``: the frictionless block holds its pivot bilaterally, and a unilateral Coulomb contact
    follows it only while the pivot force stays in the cone |F| <= mu N.  Where the frictionless
    pivot needs |F| > 1e6 N (tension, N < 0, in every case seen), the friction block must part
    from it there: it slips (the free corner pressed, A > 0: N -> 0 and a finite F as mu -> inf)
    or lifts off (A < 0; lift_off "stop" ends the run "flight").  Checked at the tight rtol,
    independently of the friction kernel: the first row of the frictionless history outside the
    cone (numpy forces, dense near N ~ 0), and the friction run's first slip or flight lying
    between that row and the one before it.  Returns ("tension", detail) then, else None."""
    from fastrock import Friction, Pulse, simulate
    kw = build_scene(P, 1.0, "tight")
    body = kw["body"]
    a, f, s = key
    pulse = Pulse(a, f, s, kw["pulse"], amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    run_kw = {"solver": kw["solver"], "t_after": kw["t_after"]}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with _Alarm(limit):
                r0 = simulate(body, pulse, **run_kw)
                t_bad, t_ok, n_min = first_cone_exit(
                    body, r0, rerun=lambda te: simulate(body, pulse, t_eval=te, **run_kw).history)
                r1 = simulate(body, pulse, friction=Friction(MU_INF, slide_tolerance=1e-6), **run_kw)
    except _Hang:
        return None
    if r0.status.startswith("failed") or r1.status.startswith("failed") or not np.isfinite(t_bad):
        return None
    ev = r1.events
    part = ev[ev["event"].isin(["slip", "flight"])]
    if not len(part):
        return None
    tp = float(part["t"].iloc[0])
    tol = 1e-9 * max(1.0, abs(t_bad))
    if not t_ok - tol <= tp <= t_bad + tol:
        return None
    return "tension", (f"the frictionless pivot needs |F| > {MU_INF:g} N from t = {t_bad:.9g} s (N down to "
                       f"{n_min / body.g:.3g} g); Friction({MU_INF:g}) parts there by a "
                       f"{part['event'].iloc[0]} at t = {tp:.9g} s")


ILL_PERTURB = (1e-14, -1e-14, 2e-14, -2e-14)   # relative amplitude changes of ``ill_conditioned``


def ill_conditioned(P, key, row_a, row_b, limit=None):
    """Why a pair (the scale check's) may differ on cell ``key`` at every rtol: the cell's result
    is not determined to REL_EXACT by its input.  The unscaled scene is run at the tight rtol
    (``early_exit=False``, as the tight pair) with the amplitude changed by ``ILL_PERTURB``
    (1e-14 and 2e-14 relative, tens of ulps, far below any physical meaning and of the order of
    the scale transform's own rounding); the cell counts as ill-conditioned when those runs and
    the tight unscaled run ``row_a`` are not all the same result (``_same``), every one is
    definite, and the tight scaled run ``row_b`` lies inside what they span: its outcome among
    theirs and its max rotation between their least and largest.  Seen with elastic walls and undamped columns
    (flexible_wall:2027:553, :583, bench/README.md): thousands of wall impacts amplify a 1e-14
    change of the input into 0.1-10 % of the max rotation.  Returns ("ill_conditioned", detail)
    then, else None."""
    from fastrock import Pulse, simulate
    if row_a is None or row_b is None:
        return None
    kw = build_scene(P, 1.0, "tight")
    body = kw.pop("body")
    kind = kw.pop("pulse")
    a, f, s = key
    rows = []
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with _Alarm(limit):
                for d in ILL_PERTURB:
                    pulse = Pulse(a * (1.0 + d), f, s, kind, amplitude_unit="g_tan_alpha",
                                  frequency_unit="omega_p/p")
                    r = simulate(body, pulse, early_exit=False, **kw)
                    rows.append({"status": r.status, "outcome": r.outcome,
                                 "max_rotation_ratio": r.metrics["max_rotation_ratio"]})
    except _Hang:
        return None
    rows.append(row_a)
    if any(str(r["status"]).startswith("failed") for r in rows) or \
            all(_same(row_a, r) for r in rows):
        return None
    rot = [float(r["max_rotation_ratio"]) for r in rows]
    b = float(row_b["max_rotation_ratio"])
    if row_b["outcome"] not in {r["outcome"] for r in rows} or not min(rot) <= b <= max(rot):
        return None
    return "ill_conditioned", (f"amplitude x (1 + {', '.join(f'{d:g}' for d in ILL_PERTURB)}) and the "
                               f"tight run at rtol {TIGHT_RTOL:g}: {', '.join(r['outcome'] for r in rows)}, max "
                               f"rotation {min(rot):.9g} to {max(rot):.9g}, the scaled run's {b:.9g} inside")


def mu_inf_flight(P, key, limit=None):
    """Why ``Friction(1e6)`` and the frictionless block on the two-spring foundation
    (foundation_friction family) may differ on cell ``key``: with no corner on its spring the
    frictionless model holds the base centre horizontally fixed (kernels/foundation.py, MODE_FLIGHT),
    a horizontal force with no normal force under it, which no finite mu gives; the sliding model
    flies free (kernels/foundation_friction.py).  Checked at the tight rtol: the frictionless run
    has a flight, and the Friction(1e6) run flies at the same time (both integrate the same
    equations until then).  Returns ("flight", detail) then, else None."""
    from fastrock import Friction, Pulse, simulate
    kw = build_scene(dict(P, friction=None), 1.0, "tight")
    body = kw.pop("body")
    a, f, s = key
    pulse = Pulse(a, f, s, kw.pop("pulse"), amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    short = {k: v for k, v in kw.items() if k != "t_after"}

    def first_flight(r):
        f = r.events[r.events["event"] == "flight"]
        return float(f["t"].iloc[0]) if len(f) else None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with _Alarm(limit):
                # cost: only as far as the first flight (the pulse first, most take off in it)
                r0 = simulate(body, pulse, duration=pulse.end_time(body), **short)
                if first_flight(r0) is None and not r0.status.startswith("failed"):
                    r0 = simulate(body, pulse, **kw)
                t0 = first_flight(r0)
                if t0 is None or r0.status.startswith("failed"):
                    return None
                r1 = simulate(body, pulse, friction=Friction(MU_INF, slide_tolerance=1e-6),
                              duration=t0 * (1 + 1e-5) + 1e-9, **short)
    except _Hang:
        return None
    t1 = first_flight(r1)
    if r1.status.startswith("failed") or t1 is None:
        return None
    if abs(t0 - t1) > 1e-6 * max(1.0, abs(t0)):
        return None
    return "flight", (f"the frictionless block flies at t = {t0:.9g} s with its base centre held "
                      f"horizontally; Friction({MU_INF:g}) flies free there (t = {t1:.9g} s)")


_DT_NAMED = re.compile(r"dt <= ([0-9.eE+-]+) s would be stable")
_STEPS_NAMED = re.compile(r"needs ([0-9.eE+-]+) fixed steps for .* more than the step budget max_steps")


def unstable_step_named(P, key, limit=None, variant=None):
    """A fixed-step cell that ended ``failed:unstable-step`` is a numerical limit the user set,
    not a failure, when the error says so and is honest: ``simulate`` of the cell warns with a
    step that "would be stable" (the kernel's M_DT_STABLE), and the same cell at that step ends
    with a definite status.  Returns the detail then, else None (flexible_friction family: its
    held lift-offs slide the light base, whose mode is about sqrt((1 + mb)/mb) times stiffer than
    omega_n, the frequency the fuzz draws dt from; contact family: contact:2026:27, a pulse of
    29 g at dt = 2 pi/omega_p/111, unstable in the first step after the uplift, definite at the
    named dt)."""
    from fastrock import Pulse, simulate
    kw = build_scene(P, 1.0, variant)
    body = kw.pop("body")
    a, f, s = key
    pulse = Pulse(a, f, s, kw.pop("pulse"), amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    dt = kw["solver"].dt
    try:
        with _Alarm(limit):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                r0 = simulate(body, pulse, **kw)
            named = [m for w in caught for m in _DT_NAMED.findall(str(w.message))]
            if r0.status != "failed:unstable-step" or not named:
                return None
            dt_ok = float(named[0])
            if not 0.0 < dt_ok < dt:
                return None
            kw["solver"] = dataclasses.replace(kw["solver"], dt=dt_ok)
            budget = ""
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    r1 = simulate(body, pulse, **kw)
                except ValueError as e:
                    # the stable step needs more fixed steps than the budget: the front end
                    # refuses it naming max_steps (foundation:2027:215, the two-spring corners'
                    # dashpot mode); a user takes the budget it names
                    n = _STEPS_NAMED.findall(str(e))
                    if not n:
                        raise
                    steps = int(1.05 * float(n[0])) + 1000
                    kw["solver"] = dataclasses.replace(kw["solver"], max_steps=steps)
                    budget = f" with max_steps = {steps} (the budget its error names)"
                    r1 = simulate(body, pulse, **kw)
    except _Hang:
        return None
    if r1.status.startswith("failed") or not np.isfinite(float(r1.metrics["max_rotation"])):
        return None
    return (f"dt = {dt:.6g} s; the error names dt <= {dt_ok:.3g} s, where the cell ends {r1.status}"
            f"{budget}")


def _rows(df, flip_sign=False):
    out = {}
    for _, r in df.iterrows():
        a, f, s = _key(r)
        out[(a, f, -s if flip_sign else s)] = r
    return out


# ------------------------------------------------------------------------- energy
def energy(history, body, scene, family):
    """Mechanical energy per unit mass [J/kg] along a simulate() history (see module docstring);
    None when not checked for this scene."""
    g = body.g
    th = history["theta"].to_numpy()
    w = history["theta_dot"].to_numpy()
    if family in ("rigid", "wall"):
        R = g / body.p ** 2            # any body: E in units of M g R, scaled back by g R
        return g * R * (w * w / (2 * body.p ** 2) + np.cos(body.alpha - np.abs(th)) - np.cos(body.alpha))
    s = history["pivot"].to_numpy().astype(float)
    s = np.where(s == 0, 1.0, s)
    dd = history["d_dot"].to_numpy() if "d_dot" in history else np.zeros_like(th)
    if family in ("friction", "contact"):
        kin, pot = rigid_sliding_energy(history, body, scene, family)
        return kin + pot
    if family in FOUNDATION_ENERGY:
        if scene["foundation"].model != "two-spring":
            return None         # the switching model gains energy at uplift by design
        kin, pot = two_spring_energy(history, body, scene)
        return kin + pot
    if family in ("flexible", "flexible_friction", "flexible_wall"):
        u = history["u"].to_numpy()
        du = history["u_dot"].to_numpy()
        Bw, H = body.B, body.H
        mb = body.base_mass(sliding=family == "flexible_friction")
        Ib = mb * Bw * Bw / 3.0
        Im = body.rotary_inertia_ratio * body.R0 ** 2
        hb = body.base_cm_height
        X = (u - s * Bw) * np.cos(th) + H * np.sin(th)
        Y = -(u - s * Bw) * np.sin(th) + H * np.cos(th)
        Xd = du * np.cos(th) + Y * w
        Yd = -du * np.sin(th) - X * w
        Xb = -s * Bw * np.cos(th) + hb * np.sin(th)
        Yb = s * Bw * np.sin(th) + hb * np.cos(th)
        kin = 0.5 * ((dd + Xd) ** 2 + Yd ** 2) + 0.5 * mb * ((dd + Yb * w) ** 2 + (Xb * w) ** 2) \
            + 0.5 * (Im + Ib) * w * w
        pot = 0.5 * body.omega_n ** 2 * u * u + g * (Y - H) + mb * g * (Yb - hb)
        return kin + pot
    return None


#: families whose two-spring scenes have their energy checked (``two_spring_energy``)
FOUNDATION_ENERGY = ("foundation_wall", "foundation_friction", "flexible_foundation")


def two_spring_energy(history, body, scene):
    """(T, V) per history row [J/kg of the carried mass M] of a body on the two-spring foundation
    (models two_spring_wall, two_spring_friction, flexible_two_spring): y is the base point below
    the centre of mass (0: springs unloaded), the corner springs push only while compressed,
    ``k_v max(x sin(theta) - y, 0)^2 / 2`` at x = +-b; T of the centre of mass (with the slide
    d' if any) and the rotary inertia; a flexible body: column mass m at (u, H) in the body frame
    plus the base m_b at h_b, strain m w_n^2 u^2/2 (tests/test_foundation_wall.py,
    test_foundation_friction.py, test_foundation_flexible.py: their energies, there in J).  V is
    measured from the upright body with unloaded springs."""
    from fastrock.model.foundation import block_inertia, flexible_inertia
    fnd = scene["foundation"]
    flexible = _is_flexible(body)
    blk = flexible_inertia(body) if flexible else block_inertia(body, scene["mass"])
    y, yd, q, qd = (history[c].to_numpy() for c in ("y", "y_dot", "theta", "theta_dot"))
    dd = history["d_dot"].to_numpy() if "d_dot" in history else np.zeros_like(q)
    c, sn = np.cos(q), np.sin(q)
    g = blk.g
    if flexible:
        u, ud = history["u"].to_numpy(), history["u_dot"].to_numpy()
        m, mb, H, hb = blk.m, blk.m_b, blk.H, blk.h_b
        vx = ud * c - u * sn * qd + H * c * qd
        vy = yd - ud * sn - u * c * qd - H * sn * qd
        bx, by = hb * c * qd, yd - hb * sn * qd
        T = 0.5 * (m * (vx ** 2 + vy ** 2) + mb * (bx ** 2 + by ** 2) + (blk.I_m + blk.I_b) * qd ** 2)
        V = g * (m * (y - u * sn + H * c - H) + mb * (y + hb * c - hb)) + 0.5 * m * blk.wn ** 2 * u ** 2
    else:
        vx = dd + blk.h * c * qd
        vy = yd - blk.h * sn * qd
        T = 0.5 * blk.M * (vx ** 2 + vy ** 2) + 0.5 * blk.I_G * qd ** 2
        V = blk.M * g * (y + blk.h * c - blk.h)
    for x in (blk.b, -blk.b):
        V = V + 0.5 * fnd.k_v * np.maximum(x * sn - y, 0.0) ** 2
    return T / blk.M, V / blk.M


def _is_flexible(body):
    return getattr(body, "kind", "") == "flexible"


def rigid_sliding_energy(history, body, scene, family):
    """(T, V) per history row [J/kg] of a rigid block that can slide (friction: d along the
    ground, the pivot s; contact: d, z the position of the base midpoint, CM = P + h (sin, cos))."""
    g = body.g
    th = history["theta"].to_numpy()
    w = history["theta_dot"].to_numpy()
    dd = history["d_dot"].to_numpy()
    if family == "friction":
        from fastrock.running.models import rigid_friction_par
        from fastrock.kernels import friction as K
        s = history["pivot"].to_numpy().astype(float)
        s = np.where(s == 0, 1.0, s)
        par = rigid_friction_par(body, scene["friction"])
        b, h, IG = par[K.Q_B], par[K.Q_H], par[K.Q_IG]
        XG = -s * b * np.cos(th) + h * np.sin(th)
        YG = s * b * np.sin(th) + h * np.cos(th)
        return 0.5 * (dd + YG * w) ** 2 + 0.5 * (XG * w) ** 2 + 0.5 * IG * w * w, g * (YG - h)
    from fastrock.running.models import contact_par
    from fastrock.kernels import layout as L
    par = contact_par(body, scene["friction"], scene.get("wall"))
    hm, IG = par[L.C_H1], par[L.C_IG]
    z = history["z"].to_numpy()
    dz = history["z_dot"].to_numpy()
    vx = dd + hm * np.cos(th) * w
    vy = dz - hm * np.sin(th) * w
    return 0.5 * (vx * vx + vy * vy) + 0.5 * IG * w * w, g * (z + hm * np.cos(th) - hm)


def energy_terms(history, body, family, scene=None):
    """Per history row, the size of the terms that make up E, |T| + |V| [J/kg] (rigid, wall,
    friction, contact; None for the other families): the scale of the integration error of E (see
    ``_sim_checks``)."""
    if family in ("friction", "contact"):
        kin, pot = rigid_sliding_energy(history, body, scene, family)
        return np.abs(kin) + np.abs(pot)
    if family in FOUNDATION_ENERGY:
        if scene["foundation"].model != "two-spring":
            return None
        kin, pot = two_spring_energy(history, body, scene)
        return np.abs(kin) + np.abs(pot)
    if family not in ("rigid", "wall"):
        return None
    g = body.g
    R = g / body.p ** 2
    th = history["theta"].to_numpy()
    w = history["theta_dot"].to_numpy()
    return g * R * (w * w / (2 * body.p ** 2) + np.abs(np.cos(body.alpha - np.abs(th)) - np.cos(body.alpha)))


def energy_growth(t, E, t_free, scale, theta=None, alpha=None):
    """Largest rise of E between consecutive history rows after t_free, relative to ``scale``:
    (upright, fall), where "fall" are the pairs of rows with |theta| > alpha in either (past the
    unstable equilibrium, on the way to overturning), and "upright" all others.  ``scale`` is a
    number or one per row (a pair is then measured by the larger of its two rows)."""
    m = t > t_free
    if m.sum() < 2:
        return 0.0, 0.0
    if np.ndim(scale):
        sc = np.asarray(scale)[m]
        scale = np.maximum(sc[1:], sc[:-1])
    de = np.diff(E[m]) / scale
    if theta is None:
        fall = np.zeros(de.size, bool)
    else:
        big = np.abs(theta[m]) > alpha
        fall = big[1:] | big[:-1]
    up = float(max(de[~fall].max(initial=0.0), 0.0))
    fl = float(max(de[fall].max(initial=0.0), 0.0))
    return up, fl


def _simulate_cell(P, key, variant=None, early_exit=False, limit=None):
    from fastrock import Pulse, simulate
    kw = build_scene(P, 1.0, variant)
    body = kw.pop("body")
    a, f, s = key
    pulse = Pulse(a, f, s, kw.pop("pulse"), amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with _Alarm(limit) as al:
            run = simulate(body, pulse, early_exit=early_exit, **kw)
    return run, al.elapsed, pulse.end_time(body), body, kw


# ---------------------------------------------------------------------------- batch
def run_batch(P, time_limit=120.0, checks=True, sims=True):
    """Run one batch and its checks; returns a BatchResult."""
    res = BatchResult(P)
    amps, freqs = P["amps"], P["freqs"]
    try:
        df, el, hang = spectrum(P, amps, freqs, "both", limit=time_limit)
    except _Hang as e:
        for a in amps:
            for f in freqs:
                for s in (1, -1):
                    k = (a, f, s)
                    res.cases[k] = {"status": "hang", "outcome": "", "max_rotation_ratio": np.nan}
                    res.tag(k, "hang", str(e))
        res.times["spectrum"] = time_limit
        return res
    except Exception as e:  # noqa: BLE001
        for a in amps:
            for f in freqs:
                for s in (1, -1):
                    k = (a, f, s)
                    res.cases[k] = {"status": "error", "outcome": "", "max_rotation_ratio": np.nan}
                    res.tag(k, f"error:{type(e).__name__}", str(e)[:200])
        return res
    res.times["spectrum"] = el
    main = _rows(df)
    for a in amps:
        for f in freqs:
            for s in (1, -1):
                k = (float(a), float(f), s)
                r = main.get(k)
                if r is None:
                    res.cases[k] = {"status": "hang", "outcome": "", "max_rotation_ratio": np.nan}
                    res.tag(k, "hang", f"unfinished when the batch was stopped at {el:.1f} s")
                    continue
                res.cases[k] = {"status": r["status"], "outcome": r["outcome"],
                                "max_rotation_ratio": float(r["max_rotation_ratio"]),
                                "time_end": float(r["time_end"])}
                if r["status"] == "failed:unstable-step":
                    why = unstable_step_named(P, k, time_limit)
                    if why is not None:
                        res.reported["unstable_step_named"] += 1
                        res.details[k].append(f"unstable_step_named: {why}")
                        continue
                    res.tag(k, r["status"])
                elif r["status"].startswith("failed"):
                    res.tag(k, r["status"])
                elif _bad_numbers(r):
                    res.tag(k, "nan", f"max_rotation={r['max_rotation']} time_end={r['time_end']} "
                                      f"theta_end={r['theta_end']} theta_dot_end={r['theta_dot_end']}")
    if hang:
        for k in main:
            res.tag(k, "hang", f"batch took {el:.1f} s > {time_limit} s")
    if checks:
        _checks(res, P, main, time_limit)
    if sims:
        _sim_checks(res, P, main, time_limit)
    return res


def _checks(res, P, main, limit):
    fam = P["family"]
    sa, sf = P["amps"][:2], P["freqs"][:2]
    cells = [(float(a), float(f), s) for a in sa for f in sf for s in (1, -1)]

    def spec_rows(variant=None, scale=1.0, early_exit=True, flip=False):
        def run(tight):
            if tight:
                rtol = TIGHT_RTOL if tight is True else tight
                df, el, hang = _spectrum_variant_tight(P, sa, sf, variant, scale, limit, rtol)
            else:
                df, el, hang = spectrum(P, sa, sf, "both", early_exit=early_exit, scale=scale, variant=variant,
                                        limit=limit)
            return _rows(df, flip), el, hang
        return run

    # mirror symmetry (early_exit=False)
    if fam in WALL_FAMILIES:
        _pair_check(res, "mirror", P, cells, spec_rows(early_exit=False),
                    spec_rows("mirror_wall", early_exit=False, flip=True), limit=limit)
    else:
        _pair_check(res, "mirror", P, cells, spec_rows(early_exit=False),
                    spec_rows(early_exit=False, flip=True), limit=limit)
    # scale invariance (not for the contact family: not in its brief, issue #14)
    if fam != "contact":
        _pair_check(res, "scale", P, cells, spec_rows(), spec_rows(scale=P["scale_k"]), limit=limit,
                    explain=lambda k, a, b: ill_conditioned(P, k, a, b, limit))
    if fam in ("friction", "flexible_friction"):
        def not_comparable(a, b):
            return int(a.get("lift_offs", 0) or 0) > 0
        _pair_check(res, "mu_inf", P, cells, spec_rows("mu_inf"), spec_rows("no_friction"),
                    variants=("mu_inf", "no_friction"), outcome_only=True, skip=not_comparable if fam == "flexible_friction" else None,
                    limit=limit, explain=(lambda k, *_: mu_inf_tension(P, k, limit)) if fam == "friction" else None)
    if fam in ("wall", "foundation_wall"):
        _pair_check(res, "tall_wall", P, cells, spec_rows("tall_wall"), spec_rows("no_wall"), limit=limit)
    if fam == "foundation_friction":     # tests/test_foundation_friction.py: mu = 1e6 never slips
        _pair_check(res, "mu_inf", P, cells, spec_rows("mu_inf"), spec_rows("no_friction"),
                    variants=("mu_inf", "no_friction"), outcome_only=True, limit=limit,
                    explain=lambda k, *_: mu_inf_flight(P, k, limit))
    if fam == "flexible_wall":     # README: the flexible kernel step for step
        _pair_check(res, "tall_wall", P, cells, spec_rows("tall_wall"), spec_rows("no_wall"), limit=limit,
                    status=True)
    if fam == "contact":           # the contact model against rigid_friction / contact without a wall
        def not_comparable(a, b):
            # a block that slides or flies can reach a wall at gap >= 2h; and a wall with friction
            # always runs in flight (README), so a reference stopped at lift-off ("stop") is not it
            return int(a.get("wall_impacts", 0) or 0) > 0 or b["outcome"] == "flight"
        _pair_check(res, "tall_wall", P, cells, spec_rows("tall_wall"), spec_rows("no_wall"), limit=limit,
                    outcome_only=True, skip=not_comparable)
    if fam == "flexible" and P["stiff"]:
        try:
            A, ta, _ = spec_rows("stiff")(False)
            B, tb, _ = spec_rows("rigid_equiv")(False)
            res.times["stiff"] = ta + tb
            for k in cells:
                if k in A and k in B:
                    res.checked["stiff"] += 1
                    if A[k]["outcome"] != B[k]["outcome"]:
                        res.reported["stiff_mismatch"] += 1
                        res.details[k].append(f"stiff_mismatch: {A[k]['status']} vs rigid {B[k]['status']}")
        except _Hang as e:
            res.reported["stiff_hang"] += 1
            res.details[cells[0]].append(f"stiff check hang: {e}")
        except ValueError as e:
            # a fixed step drawn for the body is far too fine for the stiff column (omega_n/p =
            # 1000) within the step budget: the front end refuses it up front, naming max_steps
            res.skipped["stiff"] += 1
            res.details[cells[0]].append(f"stiff check skipped: {e}")


def _spectrum_variant_tight(P, amps, freqs, variant, scale, limit, rtol=TIGHT_RTOL):
    """A variant with the tight adaptive solver (and early_exit=False)."""
    from fastrock.analyses.spectrum import overturning_spectrum
    fr = _fr()
    kw = build_scene(P, scale, variant)
    body = kw.pop("body")
    kind = kw.pop("pulse")
    tscale = math.sqrt(scale)
    kw["solver"] = fr.Solver(rtol=rtol, eps_t=1e-9 * tscale, eps_omega=1e-9 / tscale)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with _Alarm(limit) as al:
            df = overturning_spectrum(body, amps, freqs, "both", pulse=kind, early_exit=False,
                                      progress=False, **kw)
    return df, al.elapsed, False


def _sim_checks(res, P, main, limit):
    """simulate() of a sample of cells: status, NaN, energy in the free phase, early exit."""
    fam = P["family"]
    keys = list(res.cases)
    for i in P["sim_cells"]:
        if i >= len(keys):
            continue
        k = keys[i]
        try:
            run, el, t_free, body, scene = _simulate_cell(P, k, limit=limit)
        except _Hang as e:
            res.tag(k, "hang", f"simulate: {e}")
            continue
        except Exception as e:  # noqa: BLE001
            res.tag(k, f"error:{type(e).__name__}", f"simulate: {str(e)[:200]}")
            continue
        res.times["simulate"] = res.times.get("simulate", 0.0) + el
        if limit is not None and el > limit:
            res.tag(k, "hang", f"simulate took {el:.1f} s")
        res.checked["simulate"] += 1
        if run.status == "failed:unstable-step" and \
                any(d.startswith("unstable_step_named") for d in res.details.get(k, ())):
            # the same cell at the same fixed step: the limit its error names (the rule above)
            res.reported["simulate_unstable_step_named"] += 1
            continue
        if run.status.startswith("failed"):
            res.tag(k, run.status, "simulate (early_exit=False)")
            continue
        h = run.history
        if not (np.isfinite(run.metrics["max_rotation"]) and np.isfinite(run.metrics["time_end"])
                and np.isfinite(h["theta"].to_numpy()).all()):
            res.tag(k, "nan", "simulate history/metrics")
            continue
        # early exit against the full run
        r = main.get(k)
        if r is not None and not r["status"].startswith("failed"):
            res.checked["early_exit"] += 1
            if r["outcome"] != run.outcome:
                try:
                    tight, _, _, _, _ = _simulate_cell(P, k, variant="tight", limit=limit)
                    tight_e, _, _, _, _ = _simulate_cell(P, k, variant="tight", early_exit=True, limit=limit)
                    if tight.outcome == tight_e.outcome:
                        res.boundary["early_exit"] += 1
                    else:
                        res.tag(k, "violated:early_exit", f"spectrum {r['status']} vs simulate {run.status}; "
                                                          f"tight {tight_e.status} vs {tight.status}")
                except Exception as e:  # noqa: BLE001
                    res.tag(k, "violated:early_exit", f"spectrum {r['status']} vs simulate {run.status} "
                                                      f"(tight re-run: {e!r})")
        # energy in the free phase
        E = energy(h, body, scene, fam)
        if E is None:
            res.skipped["energy"] += 1
            continue
        res.checked["energy"] += 1
        g = body.g
        R = g / body.p ** 2
        escale = max(float(np.nanmax(np.abs(E))), g * R * (1 - math.cos(body.alpha)))
        # The solver bounds the error of theta' relative to theta' itself, so a step's energy error
        # is about rtol times the kinetic and potential terms, not rtol times their sum E.  In an
        # overturning fall the two terms reach ~ M g R while E stays near the barrier 1 - cos(alpha):
        # seed 2026 had falls ending at E/(|T| + |V|) = 3e-5..3e-3, where 1e-6 + 100 rtol of E
        # flagged rises of 0.16..0.57 rtol of |T| + |V| (up to 3.9e3 rtol of E).  So each pair of rows is
        # measured against the larger of E's scale and the size of its terms (rigid, wall, and the
        # sliding blocks: friction, contact; friction:2027:355 flagged 2.3e-5 of |T| + |V| in a fall).
        terms = energy_terms(h, body, fam, scene)
        if terms is not None:
            escale = np.maximum(escale, terms)
        rtol = TIGHT_RTOL if scene["solver"].dt else scene["solver"].rtol
        tol = ENERGY_TOL + ENERGY_TOL_RTOL * rtol
        grow, fall = energy_growth(h["t"].to_numpy(), E, t_free, escale, h["theta"].to_numpy(), body.alpha)
        res.details.setdefault("_energy", []).append((fam, run.outcome, rtol, bool(scene["solver"].dt), grow, fall))
        for g_, kind in ((grow, "energy"), (fall, "energy:fall")):
            if g_ > tol and not scene["solver"].dt:
                res.tag(k, f"violated:{kind}", f"rise {g_:.3g} x energy scale between two history rows after "
                                               f"the pulse (tol {tol:.3g}, rtol {rtol:.3g})")
            elif g_ > tol:
                res.reported[f"{kind}_rise_fixed_dt"] += 1


# ------------------------------------------------------------------------- driver
def case_kinds(res):
    """Per case: the list of failure kinds (empty: ok)."""
    return {k: sorted(res.tags.get(k, ())) for k in res.cases}


def run_family(family, cases, seed, chunk=32, time_limit=120.0, checks=True, sims=True, start=0,
               on_batch=None, max_seconds=None):
    """Run batches of ``family`` until ``cases`` main-grid cases are done (or, with
    ``max_seconds``, until that much time has passed: no new batch starts after it).

    Returns (rows, summary): rows = one dict per case; summary = dict of counters."""
    rows = []
    summ = {"family": family, "cases": 0, "kinds": Counter(), "boundary": Counter(),
            "reported": Counter(), "checked": Counter(), "skipped": Counter(), "first": {},
            "batch_times": [], "energy_growth": []}
    b = start
    t_family = time.perf_counter()
    while summ["cases"] < cases:
        if max_seconds is not None and time.perf_counter() - t_family > max_seconds:
            break
        P = draw_batch(family, seed, b, chunk)
        t0 = time.perf_counter()
        res = run_batch(P, time_limit, checks, sims)
        wall = time.perf_counter() - t0
        summ["batch_times"].append(wall)
        summ["energy_growth"].extend(res.details.pop("_energy", []))
        for k, kinds in case_kinds(res).items():
            c = res.cases[k]
            rows.append({"family": family, "batch": P["id"], "amplitude_ratio": k[0], "frequency_ratio": k[1],
                         "sign": k[2], "status": c["status"], "outcome": c["outcome"],
                         "max_rotation_ratio": c["max_rotation_ratio"],
                         "result": ";".join(kinds) if kinds else "ok",
                         "detail": " | ".join(res.details.get(k, []))})
            summ["cases"] += 1
            for kd in kinds:
                summ["kinds"][kd] += 1
                if kd not in summ["first"]:
                    summ["first"][kd] = {"batch": P["id"], "cell": k, "detail": res.details.get(k, []),
                                         "params": P}
        for name, C in (("boundary", res.boundary), ("reported", res.reported), ("checked", res.checked),
                        ("skipped", res.skipped)):
            summ[name].update(C)
        summ["batch_times_max"] = max(summ["batch_times"])
        if on_batch:
            on_batch(P, res, wall)
        b += 1
    summ["batches"] = b - start
    summ["failing_cases"] = sum(1 for r in rows if r["result"] != "ok")
    return rows, summ


def failure_kinds(summ):
    return {k: v for k, v in summ["kinds"].items() if k.startswith(FAILURE_PREFIXES)}


def format_table(summaries):
    kinds = sorted({k for s in summaries for k in s["kinds"]})
    lines = ["| family | cases | batches | failing cases | " + "".join(f"{k} | " for k in kinds) + "time [s] |",
             "|---|---:|---:|---:|" + "---:|" * len(kinds) + "---:|"]
    for s in summaries:
        lines.append(f"| {s['family']} | {s['cases']} | {s['batches']} | {s['failing_cases']} | "
                     + "".join(f"{s['kinds'].get(k, 0)} | " for k in kinds)
                     + f"{sum(s['batch_times']):.0f} |")
    return "\n".join(lines)


def format_checks(summaries):
    lines = ["| family | checked (pairs / runs) | boundary (tight re-run agrees) | reported | skipped | "
             "slowest batch [s] |", "|---|---|---|---|---|---:|"]
    for s in summaries:
        fmt = lambda C: ", ".join(f"{k} {v}" for k, v in sorted(C.items())) or "-"  # noqa: E731
        lines.append(f"| {s['family']} | {fmt(s['checked'])} | {fmt(s['boundary'])} | {fmt(s['reported'])} | "
                     f"{fmt(s['skipped'])} | {s.get('batch_times_max', 0):.1f} |")
    return "\n".join(lines)


def format_first(summaries, n_params=True):
    out = []
    for s in summaries:
        for kd, f in sorted(s["first"].items()):
            if not kd.startswith(FAILURE_PREFIXES):
                continue
            P = f["params"]
            a, fr_, sg = f["cell"]
            out.append(f"- {s['family']} `{kd}`: batch `{f['batch']}` (replay: `python bench/fuzz.py --replay "
                       f"{f['batch']}`), cell a_p/(g tan a) = {a:.6g}, omega_p/p = {fr_:.6g}, sign {sg:+d}; "
                       f"{scene_text(P)}" + (f"; {'; '.join(f['detail'])[:300]}" if f["detail"] else ""))
    return "\n".join(out)


def scene_text(P):
    B = P["body"]
    if B["kind"] == "rectangle":
        body = f"RigidBlock.rectangle(b={B['b']:.6g}, h={B['h']:.6g}, e={B['e'] if B['e'] is None else round(B['e'], 6)})"
    elif B["kind"] == "alpha_p":
        body = f"RigidBlock(alpha={B['alpha']:.6g}, p={B['p']:.6g}, e={B['e'] if B['e'] is None else round(B['e'], 6)})"
    else:
        body = (f"FlexibleBody(alpha={B['alpha']:.6g}, p={B['p']:.6g}, omega_n_over_p={B['omega_n_over_p']:.6g}, "
                f"zeta={B['zeta']:.4g}, impact={B['impact']!r}, rotary_inertia_ratio={B['rotary_inertia_ratio']:.4g}, "
                f"base_mass_ratio={B['base_mass_ratio']}, base_cm_height={B['base_cm_height']:.4g})")
    parts = [body, f"pulse={P['pulse']!r}"]
    if P["wall"]:
        W = P["wall"]
        parts.append(f"Wall(gap={W['gap']:.6g}, side={W['side']}, height={W['height']}, "
                     f"restitution={W['restitution']:.4g})")
    if P["friction"]:
        F = P["friction"]
        parts.append(f"Friction({F['mu_s']:.6g}, {F['mu_k']:.6g}" +
                     (f", lift_off={F['lift_off']!r})" if "lift_off" in F else ")"))
    if P["foundation"]:
        D = P["foundation"]
        parts.append(f"foundation {D['type']} omega/p={D['omega_over_p']:.5g} zeta={D['zeta']:.4g} "
                     f"e_f={D['e_f']:.4g} mass={P['mass']:.5g}")
    parts.append(f"dt=2pi/w_max/{P['dt_per']:.4g}" if P["dt_per"] else f"rtol={P['rtol']:.3g}")
    return ", ".join(parts)


def replay(batch_id, time_limit=120.0, chunk=32):
    fam, seed, b = batch_id.split(":")
    P = draw_batch(fam, int(seed), int(b), chunk)
    print(json.dumps(P, indent=1))
    res = run_batch(P, time_limit)
    for k, kinds in case_kinds(res).items():
        c = res.cases[k]
        print(k, c["status"], c["outcome"], f"{c['max_rotation_ratio']:.9g}", kinds or "ok",
              " | ".join(res.details.get(k, [])))
    print("times", res.times, "boundary", dict(res.boundary), "reported", dict(res.reported),
          "checked", dict(res.checked))
    return res


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--family", default="all", help="one of " + ", ".join(FAMILIES) + ", or all, or a comma list")
    ap.add_argument("--cases", type=int, default=1000, help="main-grid cases per family")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--chunk", type=int, default=32, help="runs per batch (a sqrt(chunk/2) square grid x 2 signs)")
    ap.add_argument("--out", default=None, help="CSV of every case")
    ap.add_argument("--time-limit", type=float, default=120.0, help="seconds per batch (and per check run)")
    ap.add_argument("--no-checks", action="store_true", help="status and NaN only (no invariants, no simulate)")
    ap.add_argument("--replay", default=None, help="re-run one batch, e.g. wall:1:17")
    ap.add_argument("--max-seconds", type=float, default=None,
                    help="per family: start no new batch after this many seconds (fewer cases than --cases)")
    ap.add_argument("--quiet", action="store_true")
    a = ap.parse_args(argv)
    if a.replay:
        replay(a.replay, a.time_limit, a.chunk)
        return 0
    fams = FAMILIES if a.family == "all" else tuple(a.family.split(","))
    for f in fams:
        if f not in FAMILIES:
            ap.error(f"unknown family {f!r}")
    t_start = time.perf_counter()
    all_rows, sums = [], []
    for fam in fams:
        t0 = time.perf_counter()

        def progress(P, res, wall, _fam=fam, _t0=t0):
            if not a.quiet:
                n_bad = sum(1 for k in res.cases if res.tags.get(k))
                sys.stderr.write(f"\r{_fam}: batch {P['id']} {wall:6.2f} s, {n_bad} failing, "
                                 f"{time.perf_counter() - _t0:7.1f} s total   ")
                sys.stderr.flush()
        rows, summ = run_family(fam, a.cases, a.seed, a.chunk, a.time_limit, not a.no_checks, not a.no_checks,
                                on_batch=progress, max_seconds=a.max_seconds)
        if not a.quiet:
            sys.stderr.write("\n")
        summ["seconds"] = time.perf_counter() - t0
        all_rows.extend(rows)
        sums.append(summ)
        if a.out:
            pd.DataFrame(all_rows).to_csv(a.out, index=False)
    total = time.perf_counter() - t_start
    print(f"\nfastrock fuzz: seed {a.seed}, chunk {a.chunk}, time limit {a.time_limit} s, "
          f"{time.strftime('%Y-%m-%d %H:%M')}, total {total:.0f} s\n")
    print(format_table(sums))
    print()
    print(format_checks(sums))
    eg = [g for s in sums for g in s["energy_growth"] if not g[3]]
    if eg:
        up = np.array([g[4] / g[2] for g in eg])
        fl = np.array([g[5] / g[2] for g in eg])
        print(f"\nenergy rise between history rows after the pulse, / rtol (adaptive runs): upright median "
              f"{np.median(up):.2g}, max {up.max():.3g}; fall past alpha median {np.median(fl):.2g}, max "
              f"{fl.max():.3g} (over {len(eg)} simulate runs)")
    first = format_first(sums)
    if first:
        print("\nfirst failure of each kind:\n" + first)
    return 1 if any(s["failing_cases"] for s in sums) else 0


if __name__ == "__main__":
    sys.exit(main())
