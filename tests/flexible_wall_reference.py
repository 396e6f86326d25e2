"""Independent SciPy reference for a flexible rocking body against a rear
wall (the scene of kernels/flexible_wall.py), written from the model's
specification, not from the kernel: it imports nothing from fastrock.

Per unit mass: a point mass at height H on a massless elastic column
(frequency w_n, damping ratio zeta) on a massless rigid base of half-width
B.  State (u, u', theta, theta'): u the column's deflection perpendicular to
the column, theta the rocking angle, pivot s = +1 (right corner, theta > 0)
or -1.  Gravity G = g (no vertical excitation), horizontal ground
acceleration a_g(t) (positive a_g tips the body toward -theta).

* Full contact (theta = 0): u'' = -w_n^2 u - 2 zeta w_n u' - a_g.  Uplift
  about corner s when s H (w_n^2 u + 2 zeta w_n u') > G (B - s u).
* Rocking on s, r = u - s B, X = r cos th + H sin th, Y = -r sin th + H cos th:
  [[1, H], [H, r^2 + H^2]] [u'', th''] = [f_u, f_th],
  f_u = -w_n^2 u - 2 zeta w_n u' + r th'^2 + G sin th - a_g cos th,
  f_th = G X - a_g Y - 2 r th' u'.
* Ground impact (s theta reaches 0): full-contact map th'+ = 0,
  u'+ = u'- + H th'-, then the uplift test at once; or pivot-switch map
  (u' kept, th'+ = e (H^2 + u^2 - B^2) / (H^2 + (u + s B)^2) th'-, s -> -s).
* Overturn when s theta reaches theta_over (pi/2).
* Wall on side w at w theta = theta_w, reached while pivoting on s == w:
  th'+ = -e_w th'-, pivot kept; full-contact map: u' + H th' kept;
  pivot-switch map: u' kept unless that raises the kinetic energy
  T = (u'^2 + 2 H u' th' + (r^2 + H^2) th'^2) / 2, then the full-contact
  wall map.

Events are located by ``solve_ivp`` (DOP853, terminal events with a
direction) on each smooth segment; segments also stop at the pulse's end
(where a_g has a kink).  No chatter rule: the caller picks cases without
chatter.
"""
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp


@dataclass
class Segment:
    t0: float
    t1: float
    mode: str          # "contact" or "rock"
    pivot: int         # 0 in full contact
    sol: object        # OdeSolution on [t0, t1]: (u, u') in contact, (u, u', th, th') rocking


@dataclass
class Result:
    events: list = field(default_factory=list)     # (t, name, pivot, theta, pre, post)
    segments: list = field(default_factory=list)
    outcome: str = "running"
    capped: int = 0    # pivot-switch wall impacts that took the full-contact wall map
    ag: object = None  # the ground acceleration a_g(t) used

    def event_table(self, names=("uplift", "wall-impact", "impact", "overturn")):
        return [e for e in self.events if e[1] in names]

    def state(self, t):
        """(u, theta) at the times t (array), from the segments' dense output."""
        t = np.atleast_1d(np.asarray(t, float))
        u = np.full(t.shape, np.nan)
        th = np.full(t.shape, np.nan)
        starts = np.array([s.t0 for s in self.segments])
        for i, ti in enumerate(t):
            j = int(np.searchsorted(starts, ti, side="right")) - 1
            j = max(j, 0)
            seg = self.segments[j]
            if ti > seg.t1 + 1e-6:     # past the end of the run
                continue
            y = seg.sol(ti)             # (a hair past t1 at the end: the last step's interpolant)
            u[i] = y[0]
            th[i] = y[2] if seg.mode == "rock" else 0.0
        return u, th


def one_sine(amp, omega, sign=1):
    """a_g(t) = sign amp sin(omega t) on [0, 2 pi / omega], zero after."""
    t_end = 2.0 * math.pi / omega

    def ag(t):
        if 0.0 <= t <= t_end:
            return sign * amp * math.sin(omega * t)
        return 0.0
    return ag, t_end


def simulate_reference(B, H, wn, zeta, g, ag, t_breaks, duration, *, impact="full-contact", e=1.0,
                       wall_side=-1, theta_w=math.inf, e_w=1.0, theta_over=math.pi / 2,
                       rtol=1e-10, atol=1e-12, method="DOP853", max_events=10_000):
    """Run the hybrid system from rest (u = u' = theta = theta' = 0) at t = 0
    to ``duration``; ``ag(t)`` the ground acceleration, ``t_breaks`` times
    where it is not smooth (segments stop there)."""
    breaks = sorted(tb for tb in t_breaks if 0.0 < tb < duration) + [duration]
    res = Result()

    def col(u, du):
        return wn * wn * u + 2.0 * zeta * wn * du

    def margin(s, u, du):
        # uplift about s when this becomes negative
        return g * (B - s * u) - s * H * col(u, du)

    def kinetic(u, du, dth, s):
        r = u - s * B
        return 0.5 * (du * du + 2.0 * H * du * dth + (r * r + H * H) * dth * dth)

    def f_contact(t, y):
        return [y[1], -col(y[0], y[1]) - ag(t)]

    def f_rock(s):
        def f(t, y):
            u, du, th, dth = y
            a = ag(t)
            r = u - s * B
            c, sn = math.cos(th), math.sin(th)
            X = r * c + H * sn
            Y = -r * sn + H * c
            fu = -col(u, du) + r * dth * dth + g * sn - a * c
            ft = g * X - a * Y - 2.0 * r * dth * du
            det = r * r        # det [[1, H], [H, r^2 + H^2]]
            udd = ((r * r + H * H) * fu - H * ft) / det
            tdd = (ft - H * fu) / det
            return [du, udd, dth, tdd]
        return f

    def ev_uplift(s):
        def ev(t, y):
            return margin(s, y[0], y[1])
        ev.terminal = True
        ev.direction = -1
        return ev

    def ev_impact(s, t0, y0):
        """s theta reaches 0.  A segment that starts on theta = 0 (after an
        uplift or a ground impact) uses s theta / (t - t0)^k, k the order of
        the first nonzero derivative of theta at t0 (1, or 2 from rest):
        the same roots for t > t0, but positive at t0 where s theta starts to
        grow, so that a fall back within the first step (a short uplift) is
        located inside the step, not at its start."""
        if y0[2] != 0.0:
            def ev(t, y):
                return s * y[2]
        else:
            k = 1 if y0[3] != 0.0 else 2
            g0 = s * y0[3] if k == 1 else 0.5 * s * f_rock(s)(t0, y0)[3]

            def ev(t, y):
                if t <= t0:
                    return g0
                return s * y[2] / (t - t0) ** k
        ev.terminal = True
        ev.direction = -1
        return ev

    def ev_overturn(s):
        def ev(t, y):
            return theta_over - s * y[2]
        ev.terminal = True
        ev.direction = -1
        return ev

    def ev_wall(t0, y0):
        """wall_side theta reaches theta_w; on leaving the wall (theta' != 0)
        divided by t - t0 as ``ev_impact``."""
        if theta_w - wall_side * y0[2] != 0.0 or y0[3] == 0.0:
            def ev(t, y):
                return theta_w - wall_side * y[2]
        else:
            g0 = -wall_side * y0[3]

            def ev(t, y):
                if t <= t0:
                    return g0
                return (theta_w - wall_side * y[2]) / (t - t0)
        ev.terminal = True
        ev.direction = -1
        return ev

    def log(t, name, pivot, theta, pre, post):
        res.events.append((float(t), name, int(pivot), float(theta), float(pre), float(post)))

    def uplift_test(t, u, du):
        """Full contact at t: the corner that uplifts at once, or 0."""
        mp, mm = margin(1, u, du), margin(-1, u, du)
        if min(mp, mm) <= 0.0:
            return 1 if mp <= mm else -1
        return 0

    t = 0.0
    mode, s = "contact", 0
    y = np.zeros(4)          # (u, u', theta, theta')
    n_ev = 0
    while t < duration:
        t_stop = next(tb for tb in breaks if tb > t)
        if mode == "contact":
            evs = [ev_uplift(1), ev_uplift(-1)]
            sol = solve_ivp(f_contact, (t, t_stop), y[:2], method=method, rtol=rtol, atol=atol,
                            events=evs, dense_output=True)
        else:
            evs = [ev_impact(s, t, y), ev_overturn(s)]
            if s == wall_side and math.isfinite(theta_w):
                evs.append(ev_wall(t, y))
            sol = solve_ivp(f_rock(s), (t, t_stop), y, method=method, rtol=rtol, atol=atol,
                            events=evs, dense_output=True)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
        res.segments.append(Segment(t, float(sol.t[-1]), mode, s, sol.sol))
        hit = [(te[0], k) for k, te in enumerate(sol.t_events) if len(te)]
        if not hit:
            t = float(sol.t[-1])
            if mode == "contact":
                y = np.array([sol.y[0, -1], sol.y[1, -1], 0.0, 0.0])
            else:
                y = sol.y[:, -1].copy()
            continue
        t_ev, k = min(hit)
        t = float(t_ev)
        n_ev += 1
        if n_ev > max_events:
            raise RuntimeError(f"more than {max_events} events by t = {t} (chatter?)")
        ye = sol.y_events[k][0]
        if mode == "contact":
            y = np.array([ye[0], ye[1], 0.0, 0.0])
            s = 1 if k == 0 else -1
            mode = "rock"
            log(t, "uplift", s, 0.0, y[1], y[1])
            continue
        y = np.array(ye, float)
        if k == 0:                  # ground impact
            pre = y[3]
            y[2] = 0.0
            if impact == "pivot-switch":
                u = y[0]
                post = e * (H * H + u * u - B * B) / (H * H + (u + s * B) ** 2) * pre
                y[3] = post
                s = -s
                log(t, "impact", s, 0.0, pre, post)
            else:
                y[1] = y[1] + H * pre
                y[3] = 0.0
                log(t, "impact", -s, 0.0, pre, 0.0)
                s_up = uplift_test(t, y[0], y[1])
                if s_up:
                    s = s_up
                    log(t, "uplift", s, 0.0, y[1], y[1])
                else:
                    mode, s = "contact", 0
        elif k == 1:                # overturn
            log(t, "overturn", s, y[2], y[3], y[3])
            res.outcome = "overturn"
            return res
        else:                       # wall impact
            pre = y[3]
            y[2] = wall_side * theta_w
            post = -e_w * pre
            u, du = y[0], y[1]
            before = kinetic(u, du, pre, s)
            y[3] = post
            if not (impact == "pivot-switch" and kinetic(u, du, post, s) <= before):
                y[1] = du + H * (pre - post)       # u' + H theta' kept
                res.capped += impact == "pivot-switch"
            log(t, "wall-impact", s, y[2], pre, post)
    res.outcome = "contact" if mode == "contact" else "rocking"
    return res


def reference_for(body, pulse, wall, duration, rtol=1e-10, atol=1e-12, method="DOP853"):
    """The reference run of a fastrock scene, reading only plain numbers from
    the front-end objects (a one-sine Pulse in g tan(alpha) and omega_p/p
    units, starting at 0; a tall Wall)."""
    assert pulse.kind == "one-sine" and pulse.t_start == 0.0
    assert pulse.amplitude_unit == "g_tan_alpha" and pulse.frequency_unit == "omega_p/p"
    assert getattr(body, "rotary_inertia_ratio", 0.0) == 0.0
    g = body.g
    B, H = body.B, body.H
    R0 = g / body.p ** 2                    # point mass: p^2 = g / R0
    assert math.isclose(B, R0 * math.sin(body.alpha), rel_tol=1e-13)
    assert math.isclose(H, R0 * math.cos(body.alpha), rel_tol=1e-13)
    assert math.isclose(body.omega_n, body.omega_n_over_p * body.p, rel_tol=1e-13)
    amp = pulse.amplitude * g * math.tan(body.alpha)
    omega = pulse.frequency * body.p
    ag, t_end = one_sine(amp, omega, pulse.sign)
    d = wall.gap
    assert wall.height is None and 0.0 < d < 2.0 * H
    theta_w = math.asin(d / (2.0 * H))
    res = simulate_reference(B, H, body.omega_n, body.zeta, g, ag, [t_end], duration,
                             impact=body.impact, e=body.e, wall_side=wall.side, theta_w=theta_w,
                             e_w=wall.restitution, theta_over=body.theta_over, rtol=rtol, atol=atol,
                             method=method)
    res.ag = ag
    return res
