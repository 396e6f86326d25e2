"""Flexible body with Coulomb friction (issue #6; physics.md 3 and 4.4).

Oracles, none of them the kernel under test:

1. a sympy Lagrangian of (u, theta, d) with the rigid base (mass m_b, inertia I_b, CM height h_b):
   its mass matrix against physics.md 4.4, and its accelerations and normal force against
   ``stick_rock`` / ``slip_rock`` / ``contact_*`` at random states;
2. momentum: while the body slides in one direction in full contact, the horizontal centre of mass
   of column mass + base obeys x'' = -a_g - mu_k sigma G whatever the column does (closed form);
3. the plain flexible kernel (no sliding degree of freedom, same base mass) where friction never
   lets go: identical histories while no slip occurs;
4. energy: free motion with friction never gains energy;
5. the initiation criteria at the located events (slip: |F| = mu_s N; uplift: 3.3 with m_b);
6. the impact rule of 4.4 applied to a state; 7. rest without drift, bounded stick-slip chatter;
8. bad input.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import sympy as sp

import fastrock as fr
from fastrock import FlexibleBody, Friction, Pulse, SampledMotion
from fastrock.model import excitation as X
from fastrock.kernels import flexible as KF
from fastrock.kernels import flexible_friction as K
from fastrock.kernels import layout as L
from fastrock.running.models import flexible_friction_par
from fastrock.running.registry import select

ALPHA = 0.3
P = 2.0
WR = 9.0
ZETA = 0.05


def body(mb=0.1, hb=0.0, wr=WR, zeta=ZETA, **kw):
    return FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=wr, zeta=zeta, base_mass_ratio=mb,
                        base_cm_height=hb, **kw)


def pulse(amplitude_ratio, frequency_ratio):
    return Pulse(amplitude_ratio, frequency_ratio, amplitude_unit="g_tan_alpha",
                 frequency_unit="omega_p/p")


def constant_ground(b, a_g, a_v=0.0):
    """Header and samples of a constant horizontal (and vertical) acceleration."""
    h = Pulse(kind="rectangular", amplitude=abs(a_g), sign=1 if a_g >= 0 else -1, amplitude_unit="m/s2",
              duration=100.0)
    v = Pulse(kind="rectangular", amplitude=abs(a_v), sign=1 if a_v >= 0 else -1, amplitude_unit="m/s2",
              duration=100.0) if a_v else None
    return X.to_header(b, X.as_excitation(h), X.as_excitation(v))


# ---------------------------------------------------------------- 1. sympy Lagrangian
@functools.lru_cache(maxsize=1)
def lagrangian_model():
    """Per unit mass m: q = (u, theta, d); returns lambdified (M, rhs_without_F, N)."""
    t = sp.symbols("t")
    s, B, H, hb, mb, ib, im, wn, z, G, ag, F = sp.symbols("s B H h_b m_b i_b i_m w_n zeta G a_g F",
                                                          real=True)
    u, th, d = (sp.Function(n)(t) for n in ("u", "theta", "d"))
    q = [u, th, d]
    dq = [sp.diff(x, t) for x in q]
    r = u - s * B
    # positions relative to the pivot (physics.md 3.1), pivot at x = d on the ground
    X = r * sp.cos(th) + H * sp.sin(th)
    Y = -r * sp.sin(th) + H * sp.cos(th)
    Xb = -s * B * sp.cos(th) + hb * sp.sin(th)
    Yb = s * B * sp.sin(th) + hb * sp.cos(th)
    vx, vy = sp.diff(d + X, t), sp.diff(Y, t)
    vbx, vby = sp.diff(d + Xb, t), sp.diff(Yb, t)
    T = (vx ** 2 + vy ** 2) / 2 + mb * (vbx ** 2 + vby ** 2) / 2 + (im + ib) * dq[1] ** 2 / 2
    # gravity, the column spring and the ground's pseudo force a_g (constant here)
    V = G * (Y + mb * Yb) + wn ** 2 * u ** 2 / 2 + ag * ((d + X) + mb * (d + Xb))
    Rd = z * wn * dq[0] ** 2           # Rayleigh: c/m = 2 zeta w_n
    Lg = T - V
    acc = sp.symbols("udd tdd ddd")
    vel = sp.symbols("ud td dd")
    pos = sp.symbols("uu tt")
    sub = {}
    for x, a, v in zip(q, acc, vel):
        sub[sp.diff(x, t, 2)] = a
        sub[sp.diff(x, t)] = v
    sub2 = {u: pos[0], th: pos[1], d: 0}
    Qf = [0, 0, F]
    eqs = []
    for x, dx, Q in zip(q, dq, Qf):
        e = sp.diff(sp.diff(Lg, dx), t) - sp.diff(Lg, x) + sp.diff(Rd, dx) - Q
        eqs.append(sp.expand(e.subs(sub).subs(sub2)))
    M = sp.Matrix([[sp.diff(e, a) for a in acc] for e in eqs])
    rest = sp.Matrix([-(e.subs({a: 0 for a in acc})) for e in eqs])   # M acc = rest
    # vertical Newton: N = G (1 + m_b) + Y'' + m_b Yb''
    ay = sp.diff(Y + mb * Yb, t, 2).subs(sub).subs(sub2)
    N = G * (1 + mb) + ay
    syms = (s, B, H, hb, mb, ib, im, wn, z, G, ag, F, *pos, *vel, *acc)
    return (sp.lambdify(syms, M, "numpy"), sp.lambdify(syms, rest, "numpy"),
            sp.lambdify(syms, N, "numpy"), M, (s, B, H, hb, mb, ib, im, pos))


def test_sympy_mass_matrix_is_the_one_of_physics_md():
    *_, M, (s, B, H, hb, mb, ib, im, pos) = lagrangian_model()
    u, th = pos
    c, sn = sp.cos(th), sp.sin(th)
    Y = -(u - s * B) * sn + H * c
    Yb = s * B * sn + hb * c
    m22 = (u - s * B) ** 2 + H ** 2 + im + ib + mb * (B ** 2 + hb ** 2)
    expected = sp.Matrix([[1, H, c], [H, m22, Y + mb * Yb], [c, Y + mb * Yb, 1 + mb]])
    for pivot in (1, -1):
        assert sp.simplify((M - expected).subs(s, pivot)) == sp.zeros(3, 3)


def _kernel_vs_sympy(rng, b, mode):
    Mf, rf, Nf, *_ = lagrangian_model()
    friction = Friction(0.6, 0.5)
    par = flexible_friction_par(b, friction)
    s = int(rng.choice([-1, 1]))
    ag = float(rng.uniform(-5, 5))
    hdr, smp = constant_ground(b, ag)
    G = b.g
    uy = b.uplift_deformation
    y = np.array([rng.uniform(-3, 3) * uy, rng.uniform(-0.5, 0.5), s * rng.uniform(0, 1.2),
                  rng.uniform(-2, 2), 0.0, rng.uniform(-0.5, 0.5)])
    if mode.startswith("contact"):
        y[2] = y[3] = 0.0
    prm = (s, b.B, b.H, b.base_cm_height, par[KF.F_MB], par[KF.F_IB], 0.0, b.omega_n, b.zeta, G, ag)
    vel = (y[1], y[3], y[5])

    def solve(F, free):
        """Accelerations of the free coordinates with the others zero, for friction F."""
        M = np.array(Mf(*prm, F, y[0], y[2], *vel, 0, 0, 0), float)
        rhs = np.array(rf(*prm, F, y[0], y[2], *vel, 0, 0, 0), float).ravel()
        a = np.zeros(3)
        a[free] = np.linalg.solve(M[np.ix_(free, free)], rhs[free])
        return a, M, rhs

    t = 1.0
    if mode == "stick":
        a, M, rhs = solve(0.0, [0, 1])
        F = (M @ a - rhs)[2]          # the d row gives the friction force stick needs
        N = Nf(*prm, F, y[0], y[2], *vel, *a)
        got = K.stick_rock(t, y, s, par, hdr, smp)
        np.testing.assert_allclose(got, (a[0], a[1], F, N), rtol=1e-9, atol=1e-9)
    elif mode == "slip":
        sigma = 1 if y[5] > 0 else -1
        mu_k = friction.mu_k
        # F = -mu_k sigma N(acc) is linear in acc: solve by fixed point on N (contraction here)
        F = 0.0
        for _ in range(200):
            a, _M, _r = solve(F, [0, 1, 2])
            F = -mu_k * sigma * Nf(*prm, F, y[0], y[2], *vel, *a)
        got = K.slip_rock(t, y, s, sigma, par, hdr, smp)
        N = Nf(*prm, F, y[0], y[2], *vel, *a)
        np.testing.assert_allclose(got, (a[0], a[1], a[2], N), rtol=1e-8, atol=1e-8)
    elif mode == "contact-stick":
        a, M, rhs = solve(0.0, [0])
        F = (M @ a - rhs)[2]
        got = K.contact_stick(t, y, par, hdr, smp)
        np.testing.assert_allclose(got, (a[0], F, (1 + par[KF.F_MB]) * G), rtol=1e-9, atol=1e-9)
    else:
        sigma = 1 if y[5] > 0 else -1
        N = (1 + par[KF.F_MB]) * G
        a, _M, _r = solve(-friction.mu_k * sigma * N, [0, 2])
        got = K.contact_slip(t, y, sigma, par, hdr, smp)
        np.testing.assert_allclose(got, (a[0], a[2], N), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("mode", ["stick", "slip", "contact-stick", "contact-slip"])
@pytest.mark.parametrize("hb", [0.0, 0.3])
def test_kernel_modes_match_the_sympy_lagrangian(mode, hb):
    rng = np.random.default_rng(7)
    for _ in range(15):
        _kernel_vs_sympy(rng, body(mb=0.1, hb=hb), mode)


# ---------------------------------------------------------------- 2. momentum closed form
def test_sliding_centre_of_mass_follows_the_closed_form():
    """Rectangular pulse A >> mu g, too small to uplift: the base slides one way while the column
    rings; the CM of column mass + base moves exactly as x'' = -A - mu_k G (sigma = -1)."""
    b = body(mb=0.1)
    mu = 0.03
    A = 1.0
    T = 1.0
    res = fr.simulate(b, Pulse(kind="rectangular", amplitude=A, amplitude_unit="m/s2", duration=T),
                      friction=Friction(mu), duration=T, rtol=1e-11, atol=1e-13)
    h = res.history
    assert res.metrics["time_uplift"] != res.metrics["time_uplift"]      # nan: never uplifted
    slip = res.events[res.events.event == "slip"]
    assert len(slip) == 1
    t0 = slip.t.iloc[0]
    # the base slips once the column's force F = -(w^2 u + 2 zeta w u') + m_b a_g reaches mu N
    assert 0.0 < t0 < 0.2
    w = h[(h.t > t0) & (h.contact == "slide")]
    assert len(w) > 20
    mb = 0.1
    at0 = h[h.t == t0].iloc[0]
    x0 = at0.u / (1 + mb)
    v0 = at0.u_dot / (1 + mb)
    x_cm = (w.u + (1 + mb) * w.d) / (1 + mb)
    # sliding toward -x: friction pushes +x (sigma = -1), on the whole weight (1 + m_b) G
    expected = x0 + v0 * (w.t - t0) - (A - mu * b.g) * (w.t - t0) ** 2 / 2
    assert (w.d_dot < 0).all()
    np.testing.assert_allclose(x_cm, expected, rtol=0, atol=1e-9)


# ---------------------------------------------------------------- 3. no slip = no sliding DOF
def test_high_friction_reproduces_the_no_sliding_kernel():
    b = body(mb=0.1)
    exc = pulse(1.5, 5.0)          # 13 impacts, N > 0 throughout
    te = np.linspace(0.0, 4.0, 401)
    ref = fr.simulate(b, exc, t_eval=te, rtol=1e-10, atol=1e-12)
    res = fr.simulate(b, exc, friction=Friction(1.5), t_eval=te, rtol=1e-10, atol=1e-12)
    assert ref.kernel == "flexible" and res.kernel == "flexible_friction"
    assert res.metrics["stick_slip"] == 0 and res.metrics["max_slide"] == 0.0
    assert ref.metrics["impacts"] > 0 and res.outcome == ref.outcome
    np.testing.assert_allclose(res.history.theta, ref.history.theta, atol=1e-8)
    np.testing.assert_allclose(res.history.u, ref.history.u, atol=1e-9)


def test_high_friction_spectrum_matches_the_no_sliding_spectrum_where_nothing_slips():
    b = body(mb=0.1)
    amps = np.linspace(1.0, 6.0, 8)
    freqs = np.linspace(1.0, 8.0, 8)
    ref = fr.overturning_spectrum(b, amps, freqs, progress=False)
    fri = fr.overturning_spectrum(b, amps, freqs, friction=Friction(1.0, lift_off="hold"),
                                  progress=False)
    quiet = (fri.stick_slip == 0) & (fri.lift_offs == 0)
    assert quiet.sum() >= 10
    assert (fri.outcome[quiet] == ref.outcome[quiet]).all()
    np.testing.assert_allclose(fri.max_rotation_ratio[quiet], ref.max_rotation_ratio[quiet],
                               rtol=1e-5)
    # and mu = inf is the plain kernel, bit for bit
    inf = fr.overturning_spectrum(b, amps, freqs, friction=Friction(math.inf), progress=False)
    assert inf.attrs["kernel"] == "flexible"
    assert (inf.max_rotation_ratio.values == ref.max_rotation_ratio.values).all()


# ---------------------------------------------------------------- 4. energy
def energy(h, b, mb):
    """Mechanical energy per unit mass from a history (free motion, no ground motion)."""
    G = b.g
    s = np.where(h["pivot"] == 0, 1, h["pivot"])
    B, H = b.B, b.H
    ib = mb * B * B / 3
    th, dth, u, du, dd = h.theta, h.theta_dot, h.u, h.u_dot, h.d_dot
    r = u - s * B
    c, sn = np.cos(th), np.sin(th)
    X = r * c + H * sn
    Y = -r * sn + H * c
    Xb = -s * B * c
    Yb = s * B * sn
    vx = dd + du * c + Y * dth
    vy = -du * sn - X * dth
    vbx = dd + Yb * dth
    vby = -Xb * dth
    T = (vx ** 2 + vy ** 2) / 2 + mb * (vbx ** 2 + vby ** 2) / 2 + ib * dth ** 2 / 2
    V = G * (Y + mb * Yb) + b.omega_n ** 2 * u ** 2 / 2
    return (T + V).to_numpy()


@pytest.mark.parametrize("mu,theta0", [(0.05, 0.2), (0.15, 0.25), (0.3, 0.28), (0.6, 0.2)])
def test_free_motion_with_friction_never_gains_energy(mu, theta0):
    b = body(mb=0.1, zeta=0.0)
    res = fr.simulate(b, None, friction=Friction(mu, lift_off="hold"), theta0=theta0, duration=4.0,
                      rtol=1e-11, atol=1e-13)
    assert res.outcome in ("safe", "slide"), res.status
    E = energy(res.history, b, 0.1)
    assert np.isfinite(E).all()
    E0 = E[0]
    scale = abs(E0 - b.g * (b.H))                       # energy above the upright rest state
    assert np.all(np.diff(E) <= 1e-7 * scale), np.diff(E).max() / scale
    assert E[-1] < E0


# ---------------------------------------------------------------- 5. initiation criteria
def test_slip_onset_is_located_where_friction_saturates():
    b = body(mb=0.1)
    mu = 0.1
    res = fr.simulate(b, Pulse(0.2, 0.5, kind="half-sine"), friction=Friction(mu), rtol=1e-10,
                      atol=1e-12)
    slip = res.events[res.events.event == "slip"]
    assert len(slip) >= 1
    t = slip.t.iloc[0]
    row = res.history[res.history.t == t].iloc[0]
    wn, z = b.omega_n, b.zeta
    F = -(wn * wn * row.u + 2 * z * wn * row.u_dot) + 0.1 * row.a_g
    N = 1.1 * b.g
    assert abs(abs(F) / N - mu) < 1e-7


def test_uplift_is_located_on_the_base_mass_criterion():
    """Large mu: the body rocks without sliding; at uplift the 3.3 test with m_b holds with equality."""
    mb = 0.3
    b = body(mb=mb)
    res = fr.simulate(b, pulse(1.6, 2.0), friction=Friction(2.0), rtol=1e-10, atol=1e-12)
    up = res.events[res.events.event == "uplift"]
    assert len(up) >= 1
    t = up.t.iloc[0]
    row = res.history[res.history.t == t].iloc[0]
    s = int(up["pivot"].iloc[0])
    wn, z = b.omega_n, b.zeta
    g = b.g * (b.B - s * row.u) + mb * b.g * b.B - s * b.H * (wn * wn * row.u + 2 * z * wn * row.u_dot)
    assert abs(g) < 1e-7 * b.g * b.B
    # the massless-base test would have lifted earlier
    assert b.g * (b.B - s * row.u) - s * b.H * (wn * wn * row.u + 2 * z * wn * row.u_dot) < -1e-3


def test_slide_initiation_from_rest_not_rocking_when_friction_is_low():
    b = body(mb=0.1)
    res = fr.simulate(b, pulse(3.0, 2.0), friction=Friction(0.1))
    ev = res.events.event.tolist()
    assert ev[0] == "slip"          # friction fails before the column can lift the base
    assert res.metrics["time_sliding"] > 0


# ---------------------------------------------------------------- 6. impact rule
def test_impact_rule_of_4_4_in_its_general_form():
    hb = 0.2
    b = body(mb=0.1, hb=hb)
    par = flexible_friction_par(b, Friction(0.5))
    hdr, smp = constant_ground(b, 0.0)
    y = np.array([0.001, 0.05, 0.0, -0.7, 0.01, 0.3])
    disc = np.zeros(L.N_DISC, np.int64)
    disc[L.D_MODE] = L.MODE_SLIDE_ROCK
    disc[L.D_PIVOT] = 1
    disc[L.D_SLIP_DIR] = 1
    met = np.zeros(L.N_MET)
    met[L.M_T_UPLIFT] = 0.0
    log = np.zeros((10, L.N_LOG))
    cnt = np.zeros(4, np.int64)
    y_pre = y.copy()
    K.impact(1.0, y, par, disc, hdr, smp, met, log, cnt)
    assert y[3] == 0.0 and y[2] == 0.0
    # both horizontal momenta kept (physics.md 4.4 printed u'+ = u'- + H theta'-, which counts
    # the base's share twice: test_impact_with_a_raised_base_keeps_both_horizontal_momenta)
    assert y[1] == pytest.approx(y_pre[1] + (b.H - hb) * y_pre[3], abs=1e-15)
    assert y[5] == pytest.approx(y_pre[5] + hb * y_pre[3], abs=1e-15)
    assert met[L.M_IMPACTS] == 1


# ---------------------------------------------------------------- 7. rest and chatter
def test_no_drift_at_rest():
    b = body(mb=0.1)
    res = fr.simulate(b, pulse(0.05, 2.0), friction=Friction(0.5), duration=20.0)
    assert res.status == "safe:no-uplift"
    assert res.metrics["max_slide"] == 0.0 and res.metrics["stick_slip"] == 0
    assert (res.history.d == 0.0).all()


def test_stick_slip_chatter_is_bounded():
    """Harmonic ground motion just above the slip level for 20 s: back-and-forth sliding with a
    finite number of transitions, no failure, no NaN."""
    b = body(mb=0.1)
    mu = 0.1
    dt = 0.01
    t = np.arange(0, 20, dt)
    acc = 1.3 * mu * b.g * np.sin(2 * np.pi * 1.0 * t)
    res = fr.simulate(b, SampledMotion(acc, dt), friction=Friction(mu, 0.08), t_after=2.0)
    assert res.outcome in ("safe", "slide"), res.status
    n = res.metrics["stick_slip"]
    assert 20 <= n <= 200           # a few transitions per cycle, 20 cycles
    assert np.isfinite(res.history[["u", "d", "d_dot"]].to_numpy()).all()
    assert res.metrics["max_slide"] > 0


# ---------------------------------------------------------------- 8. selection and bad input
def test_selection_and_defaults():
    b = FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=WR, zeta=ZETA)
    assert b.base_mass(sliding=False) == 0.0 and b.base_mass(sliding=True) == 0.1
    assert select(b, friction=Friction(0.5)).name == "flexible_friction"
    assert select(b, friction=Friction(math.inf)).name == "flexible"
    assert select(b).name == "flexible"


@pytest.mark.parametrize("kw,match", [
    (dict(base_mass_ratio=0.0), "base_mass_ratio must be > 0"),
    (dict(base_mass_ratio=0.0, impact="pivot-switch"), "impact"),
])
def test_massless_base_or_pivot_switch_with_sliding_is_refused(kw, match):
    b = FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=WR, zeta=ZETA, **kw)
    with pytest.raises(ValueError, match=match):
        fr.simulate(b, pulse(2.0, 2.0), friction=Friction(0.5))


def test_bad_base_parameters_are_refused():
    with pytest.raises(ValueError, match="base_mass_ratio"):
        body(mb=-0.1)
    with pytest.raises(ValueError, match="base_cm_height"):
        body(hb=-1.0)
    with pytest.raises(ValueError, match="pivot-switch"):
        body(mb=0.1, impact="pivot-switch")
    with pytest.raises(ValueError, match="lift_off"):
        Friction(0.5, lift_off="fly")
    with pytest.raises(ValueError, match="FlexibleBody only"):
        fr.simulate(fr.RigidBlock(alpha=0.2, p=2.0), pulse(2.0, 2.0), friction=Friction(0.5, lift_off="hold"))


# ---------------------------------------------------------------- 9. scene, TOML and CLI
def test_example_scene_runs_the_sliding_kernel():
    from pathlib import Path

    from fastrock.running.scene import Scene
    path = Path(__file__).resolve().parents[1] / "examples" / "scenes" / "flexible_sliding.toml"
    scene = Scene.from_toml(path)
    assert scene.kernel == "flexible_friction"
    assert set(scene.effects) >= {"flexible", "friction"}
    res = scene.run()
    assert res.kernel == "flexible_friction" and res.outcome != "failed"
    assert res.metrics["max_slide"] > 0.0


def test_cli_spectrum_with_a_sliding_flexible_body(tmp_path):
    from fastrock.cli.app import main
    png, csv = tmp_path / "s.png", tmp_path / "s.csv"
    main(["spectrum", "--alpha", "0.3", "--omega-n-over-p", "9", "--zeta", "0.05", "--mu-s", "0.5",
          "--lift-off", "hold", "--n-amp", "3", "--n-freq", "3", "--png", str(png), "--csv", str(csv),
          "--quiet"])
    import pandas as pd
    df = pd.read_csv(csv)
    assert len(df) == 9 and {"max_slide", "residual_slide", "lift_offs"} <= set(df.columns)
    assert png.stat().st_size > 0


def test_held_lift_offs_are_named_and_counted():
    b = body(mb=0.1)
    held = fr.simulate(b, pulse(3.0, 3.0), friction=Friction(0.8, lift_off="hold"))
    ev = held.events.event.tolist()
    n = held.metrics["lift_offs"]
    assert n >= 1 and ev.count("lift-off-held") == n and "flight" not in ev
    assert held.metrics["time_unloaded"] > 0.0
    stop = fr.simulate(b, pulse(3.0, 3.0), friction=Friction(0.8))
    assert stop.outcome == "flight" and stop.events.event.iloc[-1] == "flight"
    # the stopped run ends where the held one first lifted off
    t_held = held.events.t[held.events.event == "lift-off-held"].iloc[0]
    assert stop.events.t.iloc[-1] == pytest.approx(t_held, abs=1e-9)


def test_impact_with_a_raised_base_keeps_both_horizontal_momenta():
    """theta -> 0 with h_b != 0: the frictionless plastic impact keeps the base's horizontal
    momentum d' + h_b theta' and the mass's d' + u' + H theta', so u'+ = u'- + (H - h_b)
    theta'-.  physics.md 4.4's u'+ = u'- + H theta'- added energy (0.920 -> 0.981 J/kg);
    500 random states: no gain, both momenta kept."""
    import numpy as np
    from fastrock import FlexibleBody, Friction
    from fastrock.kernels import flexible_friction as K
    from fastrock.kernels import layout as L
    from fastrock.kernels.hybrid import N_COUNTERS
    from fastrock.running.models import flexible_friction_par
    rng = np.random.default_rng(4)
    for _ in range(500):
        b = FlexibleBody(alpha=rng.uniform(0.1, 0.5), p=rng.uniform(1, 4), omega_n_over_p=rng.uniform(2, 30),
                         zeta=0.05, base_mass_ratio=rng.uniform(0.05, 1.0), base_cm_height=rng.uniform(0.0, 0.5))
        par = flexible_friction_par(b, Friction(0.5))
        s = int(rng.choice([-1, 1]))
        y = np.array([rng.normal() * 1e-3, rng.normal() * 0.1, 0.0, -s * rng.uniform(0.01, 2.0),
                      0.0, rng.normal() * 0.1])
        disc = np.zeros(L.N_DISC, np.int64)
        disc[L.D_MODE] = L.MODE_ROCK
        disc[L.D_PIVOT] = s
        met = np.zeros(L.N_MET)
        before = K.kinetic(y, s, par)
        y0 = y.copy()
        K.impact(1.0, y, par, disc, np.zeros(L.N_EXC), np.zeros(1), met, np.empty((8, L.N_LOG)),
                 np.zeros(N_COUNTERS, np.int64))
        H, hb = b.H, b.base_cm_height
        assert y[5] + 0.0 == pytest.approx(y0[5] + hb * y0[3], abs=1e-12)
        assert y[5] + y[1] == pytest.approx(y0[5] + y0[1] + H * y0[3], abs=1e-12)
        y_after = y0.copy()
        y_after[1], y_after[3], y_after[5] = y0[1] + (H - hb) * y0[3], 0.0, y0[5] + hb * y0[3]
        assert K.kinetic(y_after, s, par) <= before * (1 + 1e-12)
