"""Independent SciPy references for the contact core (kernels/contact.py),
written from physics.md (sections 1, 4.3 and 4.6), not from the kernel.

Rectangle 2b x 2h, per unit mass, i_G = (b^2 + h^2) / 3, gravity g, no
ground motion.  Angles clockwise-positive, pivot s = +1 the right corner.
"""
import math

import numpy as np
from scipy.integrate import solve_ivp


def flight_landing_rocking(b, h, g, theta0, omega0, vx0, vy0, yg0, rtol=1e-12):
    """Free flight from (theta0, theta0' = omega0, CM velocity (vx0, vy0),
    CM height yg0), landing on the first base corner that reaches the
    ground with a plastic sticking impact (mu = inf: angular momentum about
    the corner conserved, physics.md 4.6), then Housner rocking about that
    corner (physics.md 1) until theta = 0.

    Returns dict(t_land, s (landing corner), omega_post, t_impact,
    omega_pre (theta' at the ground impact))."""
    iG = (b * b + h * h) / 3.0

    # flight: state (x_G, y_G, theta, vx, vy, omega); x_G'' = 0, y_G'' = -g
    def f(t, u):
        return [u[3], u[4], u[5], 0.0, -g, 0.0]

    def corner_height(s):
        def ev(t, u):
            th = u[2]
            # body (s b, -h) -> world y offset: -s b sin(th) - h cos(th)
            return u[1] - s * b * math.sin(th) - h * math.cos(th)
        ev.terminal = True
        ev.direction = -1
        return ev

    evs = [corner_height(-1), corner_height(1)]
    sol = solve_ivp(f, (0.0, 20.0), [0.0, yg0, theta0, vx0, vy0, omega0],
                    events=evs, rtol=rtol, atol=1e-14, method="DOP853")
    hits = [(sol.t_events[i][0], i) for i in range(2) if len(sol.t_events[i])]
    t_land, i = min(hits)
    s = -1 if i == 0 else 1
    u = sol.y_events[i][0]
    th, vx, vy, om = u[2], u[3], u[4], u[5]
    # CM offset from the corner (world): G - c = -(R(th) (s b, -h))
    rx = s * b * math.cos(th) - h * math.sin(th)
    ry = -s * b * math.sin(th) - h * math.cos(th)
    gx, gy = -rx, -ry
    # clockwise angular momentum about the corner: iG om + (gy vx - gx vy)
    H = iG * om + gy * vx - gx * vy
    i0 = iG + b * b + h * h
    om_post = H / i0
    # Housner rocking about s: theta'' = -p^2 sin(s alpha - theta)
    R = math.hypot(b, h)
    alpha = math.atan2(b, h)
    p2 = g * R / i0

    def rock(t, u):
        return [u[1], -p2 * math.sin(s * alpha - u[0])]

    def impact(t, u):
        return u[0]
    impact.terminal = True
    impact.direction = -s

    sol2 = solve_ivp(rock, (0.0, 50.0), [th, om_post], events=[impact],
                     rtol=rtol, atol=1e-14, method="DOP853")
    return dict(t_land=t_land, s=s, omega_post=om_post,
                t_impact=t_land + sol2.t_events[0][0],
                omega_pre=sol2.y_events[0][0][1])


def slide_rock_solve(theta, omega, s, sigma, stick, b, h, g, mu_k):
    """physics.md 4.3, per unit mass, no ground motion: unknowns
    (theta'', d'', N) with F = -mu_k sigma N (slip) or (theta'', F, N) with
    d'' = 0 (stick).  Returns (theta'', d'', F, N)."""
    iG = (b * b + h * h) / 3.0
    X = -s * b * math.cos(theta) + h * math.sin(theta)
    Y = s * b * math.sin(theta) + h * math.cos(theta)
    w2 = omega * omega
    G = g
    if stick:
        # Y th'' - F = X w2 ; -X th'' - N = Y w2 - G ; iG th'' + Y F - X N = 0
        A = np.array([[Y, -1.0, 0.0], [-X, 0.0, -1.0], [iG, Y, -X]])
        rhs = np.array([X * w2, Y * w2 - G, 0.0])
        tdd, F, N = np.linalg.solve(A, rhs)
        return tdd, 0.0, F, N
    m = mu_k * sigma
    # d'' + Y th'' + m N = X w2 ; -X th'' - N = Y w2 - G ; iG th'' - (m Y + X) N = 0
    A = np.array([[Y, 1.0, m], [-X, 0.0, -1.0], [iG, 0.0, -(m * Y + X)]])
    rhs = np.array([X * w2, Y * w2 - G, 0.0])
    tdd, dd, N = np.linalg.solve(A, rhs)
    return tdd, dd, -m * N, N


def slide_rock_until_impact(b, h, g, mu_s, mu_k, theta0, omega0, v0, s,
                            rtol=1e-12, t_max=20.0):
    """Rocking on pivot s with the pivot slipping at v0 (SLIDE_ROCK), no
    ground motion, until the first ground impact (theta = 0): slip until
    d' = 0, then stick if |F| <= mu_s N (ROCK; slip again at |F| = mu_s N).
    Returns the list of events [(kind, t, theta, theta', d, d')], kind in
    "stick", "slip", "impact"."""
    out = []
    t = 0.0
    u = np.array([theta0, omega0, 0.0, v0])
    sigma = 1 if v0 > 0 else -1
    stick = v0 == 0.0
    for _ in range(20):
        def f(t, u, sig=sigma, st=stick):
            tdd, dd, _F, _N = slide_rock_solve(u[0], u[1], s, sig, st, b, h,
                                               g, mu_k)
            return [u[1], tdd, u[3], dd]

        def impact(t, u):
            return s * u[0]
        impact.terminal = True
        impact.direction = -1

        def stop_slip(t, u, sig=sigma):
            return sig * u[3]
        stop_slip.terminal = True
        stop_slip.direction = -1

        def start_slip(t, u):
            _tdd, _dd, F, N = slide_rock_solve(u[0], u[1], s, 0, True, b, h,
                                               g, mu_k)
            return mu_s * N - abs(F)
        start_slip.terminal = True
        start_slip.direction = -1
        evs = [impact, start_slip if stick else stop_slip]
        sol = solve_ivp(f, (t, t_max), u, events=evs, rtol=rtol, atol=1e-14,
                        method="DOP853")
        hits = [(sol.t_events[i][0], i) for i in range(2)
                if len(sol.t_events[i])]
        if not hits:
            break
        t, i = min(hits)
        u = np.array(sol.y_events[i][0])
        if i == 0:
            out.append(("impact", t, *u))
            break
        if stick:
            _tdd, _dd, F, N = slide_rock_solve(u[0], u[1], s, 0, True, b, h,
                                               g, mu_k)
            sigma = -1 if F > 0 else 1
            stick = False
            out.append(("slip", t, *u))
        else:
            u[3] = 0.0
            _tdd, _dd, F, N = slide_rock_solve(u[0], u[1], s, 0, True, b, h,
                                               g, mu_k)
            if abs(F) <= mu_s * N:
                stick = True
            else:
                sigma = -1 if F > 0 else 1
            out.append(("stick", t, *u))
    return out


def ladder_on_wall(b, h, g, theta0, mu, mu_w, rtol=1e-12, t_max=20.0):
    """A rectangle 2b x 2h leaning at rest on a rigid wall on its right
    (side +1) with its top right corner, pivoting on its bottom right
    corner, friction mu at the ground and mu_w at the wall (physics.md 4.6,
    "Wall as a contact point"): the pivot slips away from the wall while
    the top corner slides down the wall (a ladder).  One degree of freedom
    theta (clockwise, toward the wall), derived here by hand: the pivot at
    x_P = X_w - 2h sin(theta) on the ground, the CM at
    (X_w - h sin - b cos, h cos + b sin); unknowns (theta'', N, N_w) from
    Newton-Euler with F = -mu sigma N (sigma = sgn x_P'), F_w = -mu_w
    sigma_w N_w (sigma_w = sgn y_T', y_T = 2h cos theta).

    Integrates until the wall force reaches 0 (the top corner leaves the
    wall), the pivot's normal force reaches 0 or the slip stops.  Returns
    dict(kind ("release", "lift", "stop"), t, theta, omega, N, N_w,
    start=(theta'', N, N_w) at t = 0)."""
    iG = (b * b + h * h) / 3.0

    def forces(th, om):
        c, s = math.cos(th), math.sin(th)
        # directions of the slips for theta' > 0 (from rest: theta'' > 0)
        sig = -1.0            # x_P' = -2h cos(theta) theta' < 0
        sig_w = -1.0          # y_T' = -2h sin(theta) theta' < 0
        f, f_w = -mu * sig, -mu_w * sig_w
        rPx, rPy = -h * s + b * c, -h * c - b * s
        rTx, rTy = h * s + b * c, h * c - b * s
        A = np.array([[-h * c + b * s, -f, 1.0],
                      [-h * s + b * c, -1.0, -f_w],
                      [iG, -(rPy * f - rPx), -(-rTy - rTx * f_w)]])
        rhs = np.array([-(h * s + b * c) * om * om,
                        -g + (h * c + b * s) * om * om,
                        0.0])
        return np.linalg.solve(A, rhs)

    def f(t, u):
        return [u[1], forces(u[0], u[1])[0]]

    def release(t, u):
        return forces(u[0], u[1])[2]
    release.terminal = True
    release.direction = -1

    def lift(t, u):
        return forces(u[0], u[1])[1]
    lift.terminal = True
    lift.direction = -1

    def stop(t, u):
        return u[1]
    stop.terminal = True
    stop.direction = -1
    start = forces(theta0, 0.0)
    sol = solve_ivp(f, (0.0, t_max), [theta0, 0.0], events=[release, lift, stop],
                    rtol=rtol, atol=1e-14, method="DOP853")
    hits = [(sol.t_events[i][0], i) for i in range(3) if len(sol.t_events[i])]
    t, i = min(hits)
    th, om = sol.y_events[i][0]
    _tdd, N, N_w = forces(th, om)
    return dict(kind=("release", "lift", "stop")[i], t=t, theta=th, omega=om, N=N, N_w=N_w,
                start=tuple(start))


def lean_critical_mu_w(b, h, theta, mu):
    """Least wall friction mu_w that holds a rectangle at rest leaning on
    the wall at theta (> alpha) with ground friction mu < tan(theta)
    (statics by hand: the ladder of the block's wall-side face; moments
    about the pivot 2h (cos N_w + sin F_w) = g (h sin - b cos), F = N_w,
    N = g - F_w; the best wall friction is F_w = mu_w N_w, upward):
        mu_w* = (tan theta - tan alpha - 2 mu) / (mu (tan theta + tan alpha)),
    0 where the frictionless wall holds already (mu >= (tan theta -
    tan alpha) / 2)."""
    ta = b / h
    tt = math.tan(theta)
    return max(0.0, (tt - ta - 2.0 * mu) / (mu * (tt + ta)))


def flight_on_wall(b, h, g, theta0, yg0, a_g, t_out, rtol=1e-12):
    """A rectangle 2b x 2h in flight with its top right corner on a
    frictionless rigid wall on its right (side +1), released at rest at
    theta0 (> 0, toward the wall) with its CM at height yg0, under a
    constant horizontal ground acceleration a_g (< 0: the d'Alembert force
    -a_g pushes it toward the wall).  Derived here by hand (Lagrange, two
    degrees of freedom theta and y_G): the corner's x is fixed, so
    x_G = X_w - b cos(theta) - h sin(theta), x_G' = c1 theta' with
    c1 = b sin(theta) - h cos(theta), c1' = c2 = b cos(theta) + h sin(theta);
    T = ((c1^2 + i_G) theta'^2 + y_G'^2) / 2, generalized forces -a_g c1
    and -g:
        (c1^2 + i_G) theta'' + c1 c2 theta'^2 = -a_g c1,   y_G'' = -g,
    wall force (toward -x) N_w = -(x_G'' + a_g) >= 0.

    Returns dict(t, theta, omega, x_G - x_G(0), y_G, N_w) at the times
    t_out (all before the face reaches the wall or a corner the ground)."""
    iG = (b * b + h * h) / 3.0

    def acc(th, om):
        c1 = b * math.sin(th) - h * math.cos(th)
        c2 = b * math.cos(th) + h * math.sin(th)
        tdd = (-a_g * c1 - c1 * c2 * om * om) / (c1 * c1 + iG)
        return tdd, -((c1 * tdd + c2 * om * om) + a_g)

    def f(t, u):
        return [u[1], acc(u[0], u[1])[0], u[3], -g]

    sol = solve_ivp(f, (0.0, max(t_out)), [theta0, 0.0, yg0, 0.0], t_eval=t_out,
                    rtol=rtol, atol=1e-14, method="DOP853")
    th, om, yg = sol.y[0], sol.y[1], sol.y[2]
    xg = -(b * np.cos(th) + h * np.sin(th)) + (b * math.cos(theta0) + h * math.sin(theta0))
    nw = np.array([acc(a, w)[1] for a, w in zip(th, om)])
    return dict(t=sol.t, theta=th, omega=om, x_G=xg, y_G=yg, N_w=nw)
