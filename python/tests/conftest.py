"""Shared fixtures of the Python tests: shapes over the exponent range, points by construction."""
import numpy as np
import pytest

import fcl_superellipsoid as fse

# Exponents from near-box to near-octahedron, radii from round to 4:2:1.
SHAPE_PARAMETERS = [
    ((1.0, 1.0, 1.0), (1.0, 1.0)),
    ((3.5, 3.0, 2.0), (0.4, 0.3)),
    ((2.0, 1.0, 0.5), (1.7, 0.1)),
    ((1.0, 2.0, 4.0), (0.1, 1.9)),
    ((0.3, 0.2, 0.25), (0.02, 0.02)),
]


@pytest.fixture(params=SHAPE_PARAMETERS, ids=lambda p: f"r{p[0]}-e{p[1]}")
def shape(request):
    radii, exponents = request.param
    return fse.Superellipsoid(radii, exponents)


def unit_directions(n, seed):
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(n, 3))
    return u / np.linalg.norm(u, axis=1, keepdims=True)


def outside_points(shape, n, seed):
    """Points at known distances outside: a support point s(u) moved by d along u, whose
    nearest surface point is s(u) (the shape is convex and u its outward normal there)."""
    u = unit_directions(n, seed)
    d = np.random.default_rng(seed + 1).uniform(0.01, 2.0, size=n) * shape.size
    surface = shape.support(u)
    return surface + d[:, None] * u, d, surface, u


def random_rotation(seed):
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q = q @ np.diag(np.sign(np.diag(r)))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def skew(v):
    """The matrix [v]x of the cross product: skew(v) @ w = v x w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
