"""Plane sections and meshes of rigid bodies (fastrock geometry, issue #17 item 2).

Oracles: exact mass properties of a rectangle, a triangle (J = A (a^2 + b^2 + c^2) / 36) and an
L-shape (two rectangles and the parallel-axis theorem), a random star polygon triangulated here
independently; scipy's convex hull; a box and a tetrahedron written as OBJ/STL files, whose volume,
centre of mass and inertia follow from the simplex moment formula.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import ConvexHull

from fastrock.model import geometry as geo


def cross2(u, v):
    return u[0] * v[1] - u[1] * v[0]


def rectangle(x0, y0, w, h):
    return [(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)]


# ------------------------------------------------------------ polygon properties
@pytest.mark.parametrize("origin", [(0.0, 0.0), (1e3, -2e3)])
@pytest.mark.parametrize("reverse", [False, True])
def test_rectangle_properties_exact(origin, reverse):
    w, h = 0.8, 2.6
    P = rectangle(origin[0], origin[1], w, h)
    if reverse:
        P = P[::-1]
    s = geo.polygon_properties(P)
    assert s.area == pytest.approx(w * h, rel=1e-14)
    assert s.centroid == pytest.approx([origin[0] + w / 2, origin[1] + h / 2], rel=1e-14, abs=1e-14)
    assert s.polar_moment == pytest.approx(w * h * (w * w + h * h) / 12, rel=1e-12)


def test_triangle_properties_exact():
    V = np.array([(0.1, -0.3), (2.0, 0.4), (0.7, 1.9)])
    a, b, c = (np.linalg.norm(V[i] - V[(i + 1) % 3]) for i in range(3))
    A = 0.5 * abs(cross2(V[1] - V[0], V[2] - V[0]))
    s = geo.polygon_properties(V)
    assert s.area == pytest.approx(A, rel=1e-14)
    assert s.centroid == pytest.approx(V.mean(axis=0), rel=1e-14)
    assert s.polar_moment == pytest.approx(A * (a * a + b * b + c * c) / 36, rel=1e-13)


def test_l_shape_properties_exact():
    """An L of a 3 x 1 foot and a 1 x 1 upright: the union of two rectangles."""
    L = [(0, 0), (3, 0), (3, 1), (1, 1), (1, 2), (0, 2)]
    parts = [((1.5, 0.5), 3.0, 3.0, 1.0), ((0.5, 1.5), 1.0, 1.0, 1.0)]    # centroid, area, w, h
    A = sum(p[1] for p in parts)
    c = sum(np.array(p[0]) * p[1] for p in parts) / A
    J = sum(p[1] * (p[2] ** 2 + p[3] ** 2) / 12 + p[1] * np.sum((np.array(p[0]) - c) ** 2) for p in parts)
    s = geo.polygon_properties(L)
    assert (s.area, *s.centroid) == pytest.approx((4.0, 1.25, 0.75), rel=1e-14)
    assert s.centroid == pytest.approx(c, rel=1e-14)
    assert s.polar_moment == pytest.approx(J, rel=1e-13)


@pytest.mark.parametrize("seed", range(5))
def test_random_polygon_against_a_fan_triangulation(seed):
    """A random star-shaped polygon about a centre; its triangles from that centre, each with the
    triangle's own formulas and the parallel-axis theorem, sum to the polygon's properties."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 40))
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = rng.uniform(0.3, 2.0, n)
    centre = rng.uniform(-5, 5, 2)
    P = centre + np.column_stack([r * np.cos(ang), r * np.sin(ang)])
    A = 0.0
    M1 = np.zeros(2)
    parts = []
    for i in range(n):
        T = np.array([centre, P[i], P[(i + 1) % n]])
        At = 0.5 * cross2(T[1] - T[0], T[2] - T[0])        # signed: counter-clockwise positive
        ct = T.mean(axis=0)
        a, b, c = (np.linalg.norm(T[k] - T[(k + 1) % 3]) for k in range(3))
        parts.append((At, ct, At * (a * a + b * b + c * c) / 36))
        A += At
        M1 += At * ct
    c = M1 / A
    J = sum(Jt + At * np.sum((ct - c) ** 2) for At, ct, Jt in parts)
    s = geo.polygon_properties(P)
    assert s.area == pytest.approx(A, rel=1e-12)
    assert s.centroid == pytest.approx(c, rel=1e-12, abs=1e-12)
    assert s.polar_moment == pytest.approx(J, rel=1e-11)
    assert geo.orientation(P) == 1 and geo.orientation(P[::-1]) == -1


# ------------------------------------------------------------ bad polygons
@pytest.mark.parametrize("P,match", [
    ([(0, 0), (1, 1), (1, 0), (0, 1)], "crosses itself"),                    # bow tie
    ([(0, 0), (2, 0), (2, 2), (1, -1), (0, 2)], "crosses itself"),           # an edge through another
    ([(0, 0), (2, 0), (1, 0), (1, 1)], "crosses itself"),                    # folds back along an edge
    ([(0, 0), (1, 0), (1, 0), (0, 1)], "zero length"),
    ([(0, 0), (1, 0)], "at least three"),
    ([(0, 0), (1, 1), (2, 2)], "crosses itself|no area"),
    ([(0, 0), (1, np.nan), (0, 1)], "non-finite"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], "shape"),
])
def test_bad_polygon_named(P, match):
    with pytest.raises(ValueError, match=f"^vertices.*({match})"):
        geo.polygon_properties(P)


def test_closing_vertex_and_collinear_points_accepted():
    P = rectangle(0, 0, 2, 1)
    s = geo.polygon_properties(P + [P[0]])
    assert s.area == pytest.approx(2.0)
    s = geo.polygon_properties([(0, 0), (1, 0), (2, 0), (2, 1), (0, 1)])
    assert s.area == pytest.approx(2.0)


# ------------------------------------------------------------ hull and support
@pytest.mark.parametrize("seed", range(3))
def test_convex_hull_against_scipy(seed):
    pts = np.random.default_rng(seed).normal(size=(200, 2))
    H = geo.convex_hull(pts)
    ref = pts[ConvexHull(pts).vertices]
    assert {tuple(p) for p in H} == {tuple(p) for p in ref}
    assert geo.signed_area(H) > 0


def test_support_of_a_rectangle_in_its_poses():
    b, h = 0.4, 1.5
    P = rectangle(-b, -h, 2 * b, 2 * h)
    sup = geo.resting_support(P, (0, 0), 0.0)
    assert sup.left == pytest.approx([-b, -h]) and sup.right == pytest.approx([b, -h])
    # a quarter turn clockwise: it lies on its long side
    sup = geo.resting_support(P, (0, 0), math.pi / 2)
    assert sup.left == pytest.approx([-h, -b]) and sup.right == pytest.approx([h, -b])
    # a slightly tilted pose settles back on the same facet, exactly flat
    sup = geo.resting_support(P, (0, 0), 0.2)
    assert sup.left[1] == sup.right[1]
    assert sup.pose == pytest.approx(0.0, abs=1e-15)
    assert sup.left == pytest.approx([-b, -h]) and sup.right == pytest.approx([b, -h])


def test_support_rotation_sense_is_theta():
    """Clockwise positive: a point on +x goes below the centre (body (a, c) -> (a cos + c sin,
    -a sin + c cos), physics.md 0)."""
    assert geo.rotate([(1.0, 0.0)], math.pi / 2) == pytest.approx(np.array([[0.0, -1.0]]), abs=1e-15)


def test_a_body_that_cannot_stand_names_pose():
    # an overhang: most of the mass to the right of a narrow foot (a boot)
    P = [(0, 0), (0.2, 0), (0.2, 1.0), (3.0, 1.0), (3.0, 1.5), (0, 1.5)]
    c = geo.polygon_properties(P).centroid
    assert c[0] > 0.2 * 1.5        # the centre of mass lies right of the hull's lowest facet...
    with pytest.raises(ValueError, match="^pose: the body cannot stand"):
        geo.resting_support(P, c, 0.0)


# ------------------------------------------------------------ meshes
BOX = (2.0, 1.0, 3.0)          # extents along x, y, z
BOX_ORIGIN = np.array([0.5, -0.2, 0.0])
CUBE_FACES = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
              (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]      # vertex index 4 i + 2 j + k


def box_vertices():
    a, b, c = BOX
    return np.array([[x, y, z] for x in (0, a) for y in (0, b) for z in (0, c)]) + BOX_ORIGIN


def write_obj(path, V, F):
    with open(path, "w") as f:
        for v in V:
            f.write("v %.17g %.17g %.17g\n" % tuple(v))
        for t in F:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
    return path


def write_stl(path, V, F):
    with open(path, "w") as f:
        f.write("solid body\n")
        for t in F:
            n = np.cross(V[t[1]] - V[t[0]], V[t[2]] - V[t[0]])
            n = n / np.linalg.norm(n)
            f.write("facet normal %.17g %.17g %.17g\n outer loop\n" % tuple(n))
            for i in t:
                f.write("  vertex %.17g %.17g %.17g\n" % tuple(V[i]))
            f.write(" endloop\nendfacet\n")
        f.write("endsolid body\n")
    return path


def simplex_moments(V, F):
    """Volume, centre and second-moment matrix (integral of r r^T dV) of a closed, outward-oriented
    triangle mesh from the tetrahedra (origin, face): each has the exact moments
    V_t / 20 (sum_k v_k v_k^T + (sum_k v_k)(sum_k v_k)^T) with v_0 = 0."""
    vol, m1, m2 = 0.0, np.zeros(3), np.zeros((3, 3))
    for t in F:
        P = V[list(t)]
        Vt = np.linalg.det(P) / 6.0
        s = P.sum(axis=0)
        vol += Vt
        m1 += Vt * s / 4.0
        m2 += Vt / 20.0 * (P.T @ P + np.outer(s, s))
    return vol, m1 / vol, m2


def inertia_about_axis(V, F, axis):
    vol, c, m2 = simplex_moments(V, F)
    S = m2 - vol * np.outer(c, c)              # central second moments
    n = np.asarray(axis, float)
    return np.trace(S) - n @ S @ n             # integral of the squared distance to the axis


@pytest.mark.parametrize("writer", [write_obj, write_stl])
@pytest.mark.parametrize("axis", [(0, 1, 0), (1, 0, 0), (0.6, 0.8, 0.0)])
def test_box_mesh_properties_exact(tmp_path, writer, axis):
    a, b, c = BOX
    V = box_vertices()
    path = writer(tmp_path / ("box" + (".obj" if writer is write_obj else ".stl")), V, CUBE_FACES)
    sec = geo.mesh_section(path, axis=axis)
    assert sec.volume == pytest.approx(a * b * c, rel=1e-13)
    assert sec.centre_of_mass == pytest.approx(BOX_ORIGIN + np.array(BOX) / 2, rel=1e-13)
    n = np.array(axis, float)
    S = np.diag([a * a, b * b, c * c]) * a * b * c / 12      # central integral of x_i^2
    assert sec.inertia == pytest.approx(np.trace(S) - n @ S @ n, rel=1e-12)
    # the section through the centre is a rectangle of height c, centred
    ys = sec.outline[:, 1]
    assert (ys.min(), ys.max()) == pytest.approx((-c / 2, c / 2), abs=1e-12)
    width = {(0, 1, 0): a, (1, 0, 0): b}.get(tuple(axis), None)
    if width is not None:
        xs = sec.outline[:, 0]
        assert (xs.min(), xs.max()) == pytest.approx((-width / 2, width / 2), abs=1e-12)


def test_tetrahedron_mesh_properties_exact(tmp_path):
    V = np.array([[0.0, 0.0, 0.0], [1.2, 0.0, 0.0], [0.3, 0.9, 0.0], [0.4, 0.35, 1.5]])
    F = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]
    vol = abs(np.linalg.det(V[1:] - V[0])) / 6
    assert simplex_moments(V, F)[0] == pytest.approx(vol)      # outward faces
    path = write_obj(tmp_path / "tet.obj", V, F)
    sec = geo.mesh_section(path, axis=(0, 1, 0))
    assert sec.volume == pytest.approx(vol, rel=1e-13)
    assert sec.centre_of_mass == pytest.approx(V.mean(axis=0), rel=1e-13)
    # the central second moments of a tetrahedron: V/20 (sum d_k d_k^T) with d_k = v_k - centroid
    D = V - V.mean(axis=0)
    S = vol / 20.0 * (D.T @ D)
    assert sec.inertia == pytest.approx(np.trace(S) - S[1, 1], rel=1e-12)
    assert sec.inertia == pytest.approx(inertia_about_axis(V, F, (0, 1, 0)), rel=1e-12)


def test_mesh_errors_name_the_field(tmp_path):
    V = box_vertices()
    good = write_obj(tmp_path / "box.obj", V, CUBE_FACES)
    opened = write_obj(tmp_path / "open.obj", V, CUBE_FACES[:-1])
    with pytest.raises(ValueError, match="^path: .* not closed"):
        geo.mesh_section(opened)
    with pytest.raises(ValueError, match="^axis must be a unit vector"):
        geo.mesh_section(good, axis=(0, 2, 0))
    with pytest.raises(ValueError, match="^axis must be a unit 3-vector"):
        geo.mesh_section(good, axis=(0, 1))
    with pytest.raises(ValueError, match="^axis must be normal to up"):
        geo.mesh_section(good, axis=(0, 0, 1))
    with pytest.raises(ValueError, match="^path: no such file"):
        geo.mesh_section(tmp_path / "missing.obj")


def test_long_outline_checked():
    """A survey outline of 2000 points: simple as given, crossing once two points trade places."""
    rng = np.random.default_rng(3)
    ang = np.sort(rng.uniform(0, 2 * np.pi, 2000))
    r = rng.uniform(0.8, 1.0, 2000)
    P = np.column_stack([r * np.cos(ang), r * np.sin(ang)])
    assert geo.polygon_properties(P).area > 0
    P[[100, 1100]] = P[[1100, 100]]
    with pytest.raises(ValueError, match="^vertices: the polygon crosses itself"):
        geo.polygon_properties(P)
