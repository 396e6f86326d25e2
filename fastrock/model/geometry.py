"""Plane sections of rigid bodies: polygon mass properties, the support in a
resting pose, and 3D meshes cut by the shaking plane.

Pure numpy (trimesh only to read a mesh); no kernels.  Coordinates are in
metres, x horizontal (positive to the right), y vertical (positive up), as in
the rest of fastrock.  Rotations follow the rocking angle's sense: positive
clockwise (the top moves toward +x).

The functions validate their inputs and raise ``ValueError`` naming the
field: ``vertices`` (fewer than three points, repeated points, zero area, a
polygon that crosses itself), ``pose`` (a body that cannot stand in that
pose), ``axis`` (not a unit vector), ``path`` (a mesh that is not closed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastrock import _validate as V


# ------------------------------------------------------------------ polygons
def as_polygon(vertices, name="vertices"):
    """The vertices as an (n, 2) float array of a simple polygon, checked:
    at least three finite points, no repeated consecutive point, non-zero
    area and no two edges crossing or touching (other than neighbours at
    their shared vertex).  A closing vertex equal to the first is dropped."""
    try:
        P = np.array(vertices, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a sequence of (x, y) points [m]") from None
    if P.ndim != 2 or P.shape[1] != 2:
        raise ValueError(f"{name} must be a sequence of (x, y) points [m], got shape {P.shape}")
    if not np.isfinite(P).all():
        raise ValueError(f"{name} holds a non-finite coordinate")
    if len(P) > 3 and np.array_equal(P[0], P[-1]):
        P = P[:-1]
    if len(P) < 3:
        raise ValueError(f"{name} needs at least three points, got {len(P)}")
    scale = float(np.abs(P - P.mean(axis=0)).max())
    if scale == 0.0:
        raise ValueError(f"{name}: all points coincide")
    d = np.roll(P, -1, axis=0) - P
    if (np.hypot(d[:, 0], d[:, 1]) <= 1e-12 * scale).any():
        raise ValueError(f"{name} repeats a point (an edge of zero length)")
    crossing = first_crossing(P)
    if crossing is not None:
        i, j = crossing
        raise ValueError(f"{name}: the polygon crosses itself (edge {i} -> {(i + 1) % len(P)} "
                         f"meets edge {j} -> {(j + 1) % len(P)}); give the outline in order, "
                         f"once around")
    if abs(signed_area(P)) <= 1e-12 * scale * scale:
        raise ValueError(f"{name} encloses no area")
    return P


def signed_area(P):
    """Shoelace area [m^2]: positive for a counter-clockwise polygon."""
    x, y = P[:, 0], P[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def orientation(P):
    """+1 for a counter-clockwise polygon, -1 for a clockwise one."""
    return 1 if signed_area(P) > 0.0 else -1


def _meets(a, b, C, D, tol):
    """Which of the closed segments C[k]D[k] share a point with ab (within
    tol, a length): a proper crossing, or an end point on the other segment."""
    def cross(o, p, q):
        return (p[..., 0] - o[..., 0]) * (q[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (q[..., 0] - o[..., 0])

    def on_segment(p, q, r):
        # r collinear with pq (within tol): inside the bounding box?
        return ((np.minimum(p[..., 0], q[..., 0]) - tol <= r[..., 0]) &
                (r[..., 0] <= np.maximum(p[..., 0], q[..., 0]) + tol) &
                (np.minimum(p[..., 1], q[..., 1]) - tol <= r[..., 1]) &
                (r[..., 1] <= np.maximum(p[..., 1], q[..., 1]) + tol))

    A = np.broadcast_to(a, C.shape)
    B = np.broadcast_to(b, C.shape)
    tp = tol * math.hypot(b[0] - a[0], b[1] - a[1])
    tq = tol * np.hypot(D[:, 0] - C[:, 0], D[:, 1] - C[:, 1])
    d1, d2 = cross(C, D, A), cross(C, D, B)
    d3, d4 = cross(A, B, C), cross(A, B, D)
    proper = ((((d1 > tq) & (d2 < -tq)) | ((d1 < -tq) & (d2 > tq))) &
              (((d3 > tp) & (d4 < -tp)) | ((d3 < -tp) & (d4 > tp))))
    touch = (((np.abs(d1) <= tq) & on_segment(C, D, A)) | ((np.abs(d2) <= tq) & on_segment(C, D, B)) |
             ((np.abs(d3) <= tp) & on_segment(A, B, C)) | ((np.abs(d4) <= tp) & on_segment(A, B, D)))
    return proper | touch


def first_crossing(P):
    """The first pair of edge indices (i, j), i < j, whose edges meet other
    than neighbours at their shared vertex; None for a simple polygon.
    O(n^2) work, vectorised over j."""
    n = len(P)
    tol = 1e-12 * float(np.abs(P - P.mean(axis=0)).max())
    Q = np.roll(P, -1, axis=0)             # edge k runs from P[k] to Q[k]
    for i in range(n):
        a, b = P[i], Q[i]
        # the next edge shares b; it meets edge i elsewhere only if it folds back along it
        c = Q[(i + 1) % n]
        u, w = a - b, c - b
        if abs(u[0] * w[1] - u[1] * w[0]) <= tol * math.hypot(*u) and np.dot(u, w) > 0:
            return (i, i + 1) if i + 1 < n else (0, n - 1)
        j = np.arange(i + 2, n - 1 if i == 0 else n)
        if j.size:
            hit = np.flatnonzero(_meets(a, b, P[j], Q[j], tol))
            if hit.size:
                return i, int(j[hit[0]])
    return None


@dataclass(frozen=True)
class SectionProperties:
    """Mass properties of a plane section per unit out-of-plane thickness.

    Attributes
    ----------
    area : float
        A [m^2] (positive).
    centroid : ndarray, shape (2,)
        Centre of area [m].
    polar_moment : float
        J = integral of |r - centroid|^2 dA [m^4], the polar second moment
        about the centroid (I_G = rho t J for a plate of density rho and
        thickness t, or I_G = M J / A for mass M).
    """

    area: float
    centroid: np.ndarray
    polar_moment: float


def polygon_properties(vertices):
    """Area, centroid and polar second moment about the centroid of a simple
    polygon (either orientation).

    The Green's-theorem sums over the edges, taken about the first vertex to
    keep the sums well conditioned far from the origin.

    Parameters
    ----------
    vertices : array_like, shape (n, 2)
        Outline [m], once around, in order.

    Returns
    -------
    SectionProperties

    Examples
    --------
    >>> s = polygon_properties([(0, 0), (2, 0), (2, 1), (0, 1)])
    >>> float(s.area), s.centroid.tolist(), round(float(s.polar_moment), 12)
    (2.0, [1.0, 0.5], 0.833333333333)
    """
    P = as_polygon(vertices)
    o = P[0]
    Q = P - o
    x0, y0 = Q[:, 0], Q[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    c = x0 * y1 - x1 * y0
    A = 0.5 * c.sum()
    cx = ((x0 + x1) * c).sum() / (6.0 * A)
    cy = ((y0 + y1) * c).sum() / (6.0 * A)
    Iyy = ((x0 * x0 + x0 * x1 + x1 * x1) * c).sum() / 12.0   # integral of x^2
    Ixx = ((y0 * y0 + y0 * y1 + y1 * y1) * c).sum() / 12.0   # integral of y^2
    if A < 0.0:
        A, Ixx, Iyy = -A, -Ixx, -Iyy
    J = Ixx + Iyy - A * (cx * cx + cy * cy)
    return SectionProperties(area=float(A), centroid=np.array([cx, cy]) + o, polar_moment=float(J))


def convex_hull(points):
    """Convex hull of 2D points, counter-clockwise, without collinear points
    (Andrew's monotone chain)."""
    P = np.unique(np.asarray(points, dtype=float), axis=0)   # sorted by x, then y
    if len(P) < 3:
        return P

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in P:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0.0:
            lower.pop()
        lower.append(p)
    for p in P[::-1]:
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0.0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def rotate(points, angle, about=(0.0, 0.0)):
    """Rotate points by ``angle`` [rad], clockwise positive (the sense of the
    rocking angle theta), about the point ``about``."""
    P = np.asarray(points, dtype=float) - np.asarray(about, dtype=float)
    c, s = math.cos(angle), math.sin(angle)
    # physics.md 0: body vector (a, c) -> (a cos + c sin, -a sin + c cos)
    return np.column_stack([c * P[:, 0] + s * P[:, 1], -s * P[:, 0] + c * P[:, 1]]) + np.asarray(about)


@dataclass(frozen=True)
class Support:
    """A body resting on a hull facet.

    Attributes
    ----------
    outline : ndarray, shape (n, 2)
        The outline in the resting pose, relative to the centre of mass [m].
    left, right : ndarray, shape (2,)
        The two pivots (the extreme points of the lowest hull facet), relative
        to the centre of mass: (-b1, -h1) and (b2, -h2) [m].
    pose : float
        The rotation applied to the given outline [rad], clockwise positive:
        the requested pose plus the settling onto the facet.
    """

    outline: np.ndarray
    left: np.ndarray
    right: np.ndarray
    pose: float


def resting_support(outline, centre, pose=0.0, name="vertices"):
    """The pivots of a body resting on the ground in a pose.

    The outline is rotated by ``pose`` about the centre of mass; the body then
    settles on the facet of its convex hull whose outward normal points most
    nearly straight down, and is turned by the small extra angle that lays that
    facet flat (reported in ``Support.pose``).  The pivots are the facet's two
    end points.  The centre of mass must project strictly between them, else
    the body cannot stand (a ValueError naming ``pose``).

    Parameters
    ----------
    outline : array_like, shape (n, 2)
        Points of the body's outline [m] (a polygon, or any points whose hull
        is the body's).
    centre : array_like, shape (2,)
        The centre of mass [m], in the outline's coordinates.
    pose : float
        Rotation of the outline [rad], clockwise positive.

    Returns
    -------
    Support
    """
    pose = V.finite("pose", pose)
    c = np.asarray(centre, dtype=float)
    P = rotate(np.asarray(outline, dtype=float) - c, pose)
    H = convex_hull(P)
    if len(H) < 3:
        raise ValueError(f"{name}: the outline's points are collinear; a body needs an area")
    E = np.roll(H, -1, axis=0) - H
    # counter-clockwise hull: the outward normal of edge (dx, dy) is (dy, -dx)
    L = np.hypot(E[:, 0], E[:, 1])
    down = E[:, 0] / L                  # normal . (0, -1)
    k = int(np.argmax(down))
    # lay facet k flat: turn by the angle of its direction from +x, clockwise positive
    tilt = math.atan2(E[k, 1], E[k, 0])
    P = rotate(P, tilt)
    H = rotate(H, tilt)
    a, b = H[k], H[(k + 1) % len(H)]
    y0 = 0.5 * (a[1] + b[1])
    left, right = (a, b) if a[0] < b[0] else (b, a)
    left = np.array([left[0], y0])
    right = np.array([right[0], y0])
    width = right[0] - left[0]
    if not (left[0] < 0.0 < right[0]) or min(-left[0], right[0]) <= 1e-12 * width:
        raise ValueError(f"pose: the body cannot stand in this pose (pose = {pose:g} rad): its centre of "
                         f"mass projects outside the support [{left[0]:.6g}, {right[0]:.6g}] m "
                         f"(relative to the centre of mass)")
    return Support(outline=P, left=left, right=right, pose=pose + tilt)


# --------------------------------------------------------------------- meshes
@dataclass(frozen=True)
class MeshSection:
    """A closed 3D mesh reduced to the shaking plane.

    Attributes
    ----------
    volume : float
        [m^3].
    centre_of_mass : ndarray, shape (3,)
        [m], in the mesh's coordinates (uniform density).
    inertia : float
        Second moment of volume about the axis through the centre of mass
        along ``axis``, integral of the squared distance dV [m^5] (times the
        density: I_G [kg m^2]).
    outline : ndarray, shape (n, 2)
        The section by the shaking plane through the centre of mass, in plane
        coordinates relative to the centre of mass: x along ``axis x up``,
        y along ``up`` [m]; one closed loop, in order (the largest loop if the
        plane cuts the body in several pieces).
    loops : list of ndarray
        Every loop of the section, as ``outline``.
    """

    volume: float
    centre_of_mass: np.ndarray
    inertia: float
    outline: np.ndarray
    loops: list


def unit_vector(name, v):
    """A 3-vector of length 1 (within 1e-9), checked."""
    try:
        a = np.array(v, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a unit 3-vector, got {v!r}") from None
    if a.shape != (3,) or not np.isfinite(a).all():
        raise ValueError(f"{name} must be a unit 3-vector (x, y, z), got {v!r}")
    n = float(np.linalg.norm(a))
    if abs(n - 1.0) > 1e-9:
        raise ValueError(f"{name} must be a unit vector, got length {n:.6g}; "
                         f"normalise it (e.g. {name}=(0, 1, 0))")
    return a


def read_mesh(path):
    """A triangulated surface from an OBJ or STL file (trimesh), checked to be
    closed (watertight) and consistently oriented outward."""
    import trimesh
    from pathlib import Path
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"path: no such file {str(p)!r}")
    try:
        mesh = trimesh.load(str(p), force="mesh")
    except Exception as exc:       # trimesh raises many kinds on a bad file
        raise ValueError(f"path: cannot read a mesh from {str(p)!r}: {exc}") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ValueError(f"path: {str(p)!r} holds no triangulated surface")
    if not mesh.is_watertight:
        raise ValueError(f"path: the mesh in {str(p)!r} is not closed (not watertight: some edges "
                         f"belong to one face only); a body needs a closed surface to have a volume")
    if not mesh.is_winding_consistent:
        raise ValueError(f"path: the faces of {str(p)!r} are not consistently oriented")
    if mesh.volume < 0.0:
        mesh.invert()
    return mesh


def section_loops(mesh, origin, normal, xdir, ydir):
    """The loops of the plane section of a closed mesh, in plane coordinates
    (x along ``xdir``, y along ``ydir``, relative to ``origin``).

    Each triangle that the plane crosses gives one segment; the segments are
    chained end to end (a closed surface gives closed loops)."""
    V_ = mesh.vertices - origin
    d = V_ @ normal
    scale = float(np.abs(V_).max())
    d[np.abs(d) <= 1e-12 * scale] = 0.0
    segs = []
    for f in mesh.faces:
        pts = []
        for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
            da, db = d[a], d[b]
            if da == 0.0:
                pts.append(V_[a])
            if (da < 0.0 < db) or (db < 0.0 < da):
                t = da / (da - db)
                pts.append(V_[a] + t * (V_[b] - V_[a]))
        if len(pts) == 2:
            segs.append(pts)
        # a face lying in the plane, or touching it at one vertex, adds no segment
    if not segs:
        raise ValueError("axis: the plane through the centre of mass normal to axis does not cut the mesh")
    S = np.array([[[p @ xdir, p @ ydir] for p in s] for s in segs])
    tol = 1e-9 * scale
    loops = []
    used = np.zeros(len(S), dtype=bool)
    for start in range(len(S)):
        if used[start]:
            continue
        used[start] = True
        loop = [S[start, 0], S[start, 1]]
        while True:
            end = loop[-1]
            da = np.hypot(*(S[:, 0] - end).T)
            db = np.hypot(*(S[:, 1] - end).T)
            da[used] = np.inf
            db[used] = np.inf
            i, j = int(np.argmin(da)), int(np.argmin(db))
            if min(da[i], db[j]) > tol:
                break
            if da[i] <= db[j]:
                used[i] = True
                loop.append(S[i, 1])
            else:
                used[j] = True
                loop.append(S[j, 0])
        L = np.array(loop)
        if np.hypot(*(L[0] - L[-1])) <= tol:
            L = L[:-1]
        # drop points repeated by segments through a vertex
        keep = np.ones(len(L), dtype=bool)
        keep[1:] = np.hypot(*(np.diff(L, axis=0)).T) > tol
        L = L[keep]
        if len(L) >= 3:
            loops.append(L)
    if not loops:
        raise ValueError("axis: the section through the centre of mass normal to axis is degenerate")
    return loops


def mesh_section(path, axis=(0.0, 1.0, 0.0), up=(0.0, 0.0, 1.0), density=1.0):
    """Read a closed mesh and reduce it to the shaking plane.

    Parameters
    ----------
    path : str or Path
        OBJ or STL file, a closed triangulated surface [m].
    axis : 3-vector
        Unit vector normal to the shaking plane (the axis of rocking).
    up : 3-vector
        Unit vertical of the mesh's coordinates, normal to ``axis``.  The
        plane's horizontal is ``axis x up`` (axis (0, 1, 0) and up
        (0, 0, 1): the mesh's +x).
    density : float
        Multiplies the inertia only (default 1: per unit density).

    Returns
    -------
    MeshSection
    """
    n = unit_vector("axis", axis)
    up = unit_vector("up", up)
    if abs(float(n @ up)) > 1e-9:
        raise ValueError(f"axis must be normal to up (the vertical {up.tolist()}); got axis . up = "
                         f"{float(n @ up):.3g}: the shaking plane is vertical")
    xdir = np.cross(n, up)
    mesh = read_mesh(path)
    vol = float(mesh.volume)
    cm = np.array(mesh.center_mass, dtype=float)
    # trimesh: the inertia tensor about the centre of mass, axis aligned, for density mesh.density
    I3 = np.array(mesh.moment_inertia, dtype=float) / float(mesh.density)
    inertia = float(n @ I3 @ n) * density
    loops = section_loops(mesh, cm, n, xdir, up)
    areas = [abs(signed_area(L)) for L in loops]
    outline = loops[int(np.argmax(areas))]
    return MeshSection(volume=vol, centre_of_mass=cm, inertia=inertia, outline=outline, loops=loops)
