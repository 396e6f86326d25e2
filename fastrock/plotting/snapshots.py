"""A strip of snapshots: the body's outline at chosen instants of a run.

The picture engineers put in papers beside a time history: where the block
stood, how far it leaned, which corner it pivoted on, how far it slid.
"""
from __future__ import annotations

import math

import numpy as np

from fastrock.plotting.figures import get_pyplot


def block_outline(body):
    """The body's outline as vertices relative to its centre of mass [m]
    and its two base pivots ``{+1: (x, y), -1: (x, y)}`` (right, left).

    A :class:`~fastrock.RigidBody` gives its own outline (a polygon or mesh
    section), or, built from numbers, the box over its pivots up to the
    height of the lower one above the centre of mass; a RigidBlock is its
    rectangle: b, h when given, else the rectangle with the same alpha and
    p (R = 3 g / (4 p^2)); a flexible body the 2B x 2H box of its base."""
    if hasattr(body, "b1"):                       # RigidBody
        pivots = {1: (body.b2, -body.h2), -1: (-body.b1, -body.h1)}
        if getattr(body, "outline", None) is not None:
            return np.asarray(body.outline, float), pivots
        top = max(body.h1, body.h2)
        verts = np.array([[-body.b1, -body.h1], [body.b2, -body.h2], [body.b2, top], [-body.b1, top]], float)
        return verts, pivots
    b, h = getattr(body, "b", None), getattr(body, "h", None)
    if b is None or h is None:
        if getattr(body, "kind", "rigid") == "flexible":
            b, h = float(body.B), float(body.H)
        else:
            R = 3.0 * body.g / (4.0 * body.p ** 2)
            b, h = R * math.sin(body.alpha), R * math.cos(body.alpha)
    verts = np.array([[-b, -h], [b, -h], [b, h], [-b, h]], float)
    return verts, {1: (float(b), -float(h)), -1: (-float(b), -float(h))}


def _rotate(theta, pts):
    """Body frame (a, c) -> world: (a cos th + c sin th, -a sin th + c cos th);
    a positive theta turns the top toward +x."""
    c, s = math.cos(theta), math.sin(theta)
    return np.column_stack([pts[:, 0] * c + pts[:, 1] * s, -pts[:, 0] * s + pts[:, 1] * c])


def pose(body, state):
    """World coordinates [m] of the outline and of the CM for one history row
    (``theta``, ``pivot``, and ``d`` or ``d``/``z`` when the model has them).

    Rocking about corner s, the corner (s b, -h) stays on the ground at
    x = s b + d; in the contact model (columns ``d``, ``z``) the base point
    (0, -h) below the CM is at (d, z)."""
    verts, pivots = block_outline(body)
    theta = float(state["theta"])
    d = float(state.get("d", 0.0) or 0.0)
    if "z" in state:
        h = 0.5 * (-pivots[1][1] - pivots[-1][1])
        origin = np.array([d, float(state["z"])])
        anchor = np.array([0.0, -h])
    else:
        s = int(state.get("pivot", 0) or 0)
        if s == 0:
            s = 1 if theta >= 0 else -1
        anchor = np.array(pivots[s], float)
        origin = np.array([anchor[0] + d, 0.0])
    world = origin + _rotate(theta, verts - anchor)
    cm = origin + _rotate(theta, -anchor[None, :])[0]
    return world, cm


def plot_snapshots(result, times=None, n=6, ax=None, slope=None, color="#264653"):
    """Draw the body at ``times`` [s] (default: ``n`` instants spread over the
    run, the moment of largest rotation among them) side by side on one
    axis, each over its own stretch of ground, with the time, rotation and
    slip written under it.

    Parameters
    ----------
    result : SimulationResult
    times : sequence of float, optional
        Instants [s]; each snapshot shows the history row nearest to it.
    n : int
        Number of instants when ``times`` is not given.
    ax : matplotlib Axes, optional
    slope : float, optional
        Ground inclination [rad] to draw the strip tilted (default: the
        run's ``result.ground``, level if none).

    Returns
    -------
    matplotlib Axes
    """
    plt = get_pyplot()
    hist = result.history
    t = hist["t"].to_numpy()
    if times is None:
        k_max = int(np.argmax(np.abs(hist["theta"].to_numpy())))
        times = sorted(set(np.linspace(t[0], t[-1], max(n, 2))[:-1].tolist() + [t[k_max]]))[:max(n, 2)]
    times = np.atleast_1d(np.asarray(times, float))
    if slope is None:
        ground = getattr(result, "ground", None)
        slope = ground.slope if ground is not None else 0.0
    verts, _pivots = block_outline(result.body)
    width = float(np.ptp(verts[:, 0]))
    height = float(np.ptp(verts[:, 1]))
    spacing = 1.6 * max(width, 0.8 * height) + float(np.max(np.abs(hist.get("d", [0.0]))))
    if ax is None:
        _fig, ax = plt.subplots(figsize=(1.7 * len(times) + 1.0, 2.8), constrained_layout=True)
    tilt = slope           # turned like the body: the slope frame's x descends to the right
    for i, ti in enumerate(times):
        k = int(np.clip(np.searchsorted(t, ti), 0, len(t) - 1))
        if k > 0 and abs(t[k - 1] - ti) < abs(t[k] - ti):
            k -= 1
        row = hist.iloc[k].to_dict()
        world, cm = pose(result.body, row)
        shift = np.array([i * spacing, 0.0])
        ground = np.array([[-0.5 * spacing, 0.0], [0.5 * spacing, 0.0]])
        pts = [_rotate(tilt, p + shift) for p in (world, cm[None, :], ground)]
        poly, cmw, gl = pts
        ax.plot(gl[:, 0], gl[:, 1], color="0.35", lw=1.2)
        ax.fill(poly[:, 0], poly[:, 1], facecolor=color, alpha=0.25, edgecolor=color, lw=1.4)
        ax.plot(cmw[:, 0], cmw[:, 1], "o", color=color, ms=3)
        label = f"t = {t[k]:.2f} s\nθ = {math.degrees(row['theta']):.1f}°"
        if "d" in row:
            label += f"\nd = {row['d'] * 100:.1f} cm"
        ax.annotate(label, xy=(gl[:, 0].mean(), gl[:, 1].mean()), xytext=(0, -6), textcoords="offset points",
                    ha="center", va="top", fontsize=7)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title(f"{result.outcome}: the body at {len(times)} instants", fontsize=9)
    return ax
