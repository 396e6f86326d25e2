"""An independent SciPy reference of the two-spring block beside a wall (free motion): the
Lagrange equations written out here, corner contact states switched by solve_ivp events, the
wall impact as the impulse solve with the mass matrix (numpy), for tests/test_foundation_wall.py.

Corner s (x_s = s b): compression delta = -(y - x_s sin q), law f = k delta + c delta'. A corner
in contact lets go when f reaches 0; a free corner touches again when min(k delta, f) reaches 0
from below (delta >= 0 and the law pushing). Wall on side w at the top corner (w b, 2h) from the
base point: w x = b cos(wq) + 2h sin(wq) reaches b + d."""
import math

import numpy as np
from scipy.integrate import solve_ivp


def reference_run(blk, k, c, w, gap, e_w, y0, t_end, n_impacts, rtol=1e-12, atol=1e-15, log=None):
    """Wall impacts [(t, pre (y', q'), post (y', q'))] of the free motion from y0 = (y, y', q, q'),
    up to n_impacts, t_end or overturning (|q| = pi/2); ``log`` (a list) gets every phase end
    (t, events, corner states, state)."""
    M, IG, b, h, g = blk.M, blk.I_G, blk.b, blk.h, blk.g
    H = 2.0 * h

    def law(y, s):
        x = s * b
        d = -(y[0] - x * math.sin(y[2]))
        dd = -(y[1] - x * math.cos(y[2]) * y[3])
        return d, k * d + c * dd

    def rhs(t, y, on):
        fR = law(y, 1.0)[1] if on[0] else 0.0
        fL = law(y, -1.0)[1] if on[1] else 0.0
        q, qd = y[2], y[3]
        A = np.array([[M, -M * h * math.sin(q)], [-M * h * math.sin(q), IG + M * h * h]])
        Q = np.array([fR + fL - M * g + M * h * math.cos(q) * qd * qd,
                      M * g * h * math.sin(q) - b * math.cos(q) * (fR - fL)])
        ydd, qdd = np.linalg.solve(A, Q)
        return [y[1], ydd, qd, qdd]

    def wall_gap(t, y, on):
        p = w * y[2]
        return b + gap - (b * math.cos(p) + H * math.sin(p))

    def corner_event(s, i):
        def ev(t, y, on):
            d, f = law(y, s)
            return f if on[i] else min(k * d, f)
        return ev

    def overturn(t, y, on):
        return math.pi / 2 - abs(y[2])

    overturn.terminal = True
    on = [law(y0, 1.0)[0] >= 0 and law(y0, 1.0)[1] > 0, law(y0, -1.0)[0] >= 0 and law(y0, -1.0)[1] > 0]
    t, y = 0.0, np.array(y0, float)
    impacts = []
    while t < t_end and len(impacts) < n_impacts:
        evs = [wall_gap, corner_event(1.0, 0), corner_event(-1.0, 1)]
        for i, ev in enumerate(evs):
            ev.terminal = True
            # the wall's gap closing; a contact corner's force falling to 0; a free corner's
            # min(k delta, f) rising to 0 (a root at the phase start leaves in the other direction)
            ev.direction = -1 if (i == 0 or on[i - 1]) else 1
        sol = solve_ivp(rhs, (t, t_end), y, method="DOP853", events=evs + [overturn], args=(on,), rtol=rtol,
                        atol=atol, max_step=1e-3)
        t, y = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1 or (sol.t_events[3].size and sol.t_events[3][-1] == t):
            break
        hit = [i for i in range(3) if sol.t_events[i].size and sol.t_events[i][-1] == t]
        if 0 in hit:
            q = y[2]
            A = np.array([[M, -M * h * math.sin(q)], [-M * h * math.sin(q), IG + M * h * h]])
            J = np.array([0.0, -w * b * math.sin(q) + H * math.cos(q)])
            vm = y[[1, 3]].copy()
            S = np.zeros((3, 3))
            S[:2, :2], S[:2, 2], S[2, :2] = A, -J, J
            vp = np.linalg.solve(S, np.concatenate([A @ vm, [-e_w * (J @ vm)]]))[:2]
            y[1], y[3] = vp
            impacts.append((t, vm, vp))
            # the dashpots' forces jump with the corners' velocities: a corner whose law pulls
            # lets go, a free one pressed (delta >= 0, law > 0) touches
            for i, s in ((0, 1.0), (1, -1.0)):
                d, f = law(y, s)
                on[i] = f > 0.0 and (on[i] or d >= 0.0)
            continue
        for i in (1, 2):
            if i in hit:
                on[i - 1] = not on[i - 1]
        if log is not None:
            log.append((t, hit, tuple(on), y.copy()))
    return impacts
