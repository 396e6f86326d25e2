"""The two-spring model's rigid limit (k_v -> inf), shared by the foundation tests: the block turns
about a corner that slides horizontally because the point of the base below the centre of mass
is held (y_c = b sin q): J(q) q'' + J'(q) q'^2/2 = -V'(q) with q measured toward the pivot,
J = I_G + M (h^2 + b^2 cos^2 q - 2 b h sin q cos q), V = M g (b sin q + h cos q)."""
import math

from scipy.integrate import quad


def rigid_limit_inertia(q, blk):
    M, b, h = blk.M, blk.b, blk.h
    return blk.I_G + M * (h * h + (b * math.cos(q)) ** 2 - 2 * b * h * math.sin(q) * math.cos(q))


def rigid_limit_potential(q, blk):
    return blk.M * blk.g * (blk.b * math.sin(q) + blk.h * math.cos(q))


def rigid_limit_quarter_period(q0, blk):
    """Release-to-impact time of the two-spring model as k_v -> inf, from rest at q0."""
    M, b, h, g = blk.M, blk.b, blk.h, blk.g

    def J(q):
        return rigid_limit_inertia(q, blk)

    def V(q):
        return rigid_limit_potential(q, blk)

    def f(u):      # q = q0 - u^2 removes the endpoint singularity
        if u == 0.0:
            return 2.0 * math.sqrt(J(q0) / (2.0 * M * g * (b * math.cos(q0) - h * math.sin(q0))))
        q = q0 - u * u
        return 2.0 * u * math.sqrt(J(q) / (2.0 * (V(q0) - V(q))))

    return quad(f, 0.0, math.sqrt(q0), epsabs=1e-15, epsrel=1e-13)[0]
