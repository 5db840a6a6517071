"""The superellipsoid collision geometry for FCL, on numpy arrays.

    import numpy as np
    import fcl_superellipsoid as fse

    shape = fse.Superellipsoid(radii=(3.5, 3.0, 2.0), exponents=(0.4, 0.3))
    d = shape.signed_distance(np.random.rand(10000, 3) * 8 - 4)   # (N,), < 0 inside

The manual, with every call and its conventions: docs/python.md.
"""
from ._core import (
    Box,
    Capsule,
    Cone,
    Contact,
    ContactManifold,
    Convex,
    Cylinder,
    DistanceGradients,
    DistanceJacobians,
    Ellipsoid,
    Halfspace,
    ManifoldPlaces,
    MarginQuery,
    Mesh,
    PairDistance,
    PairDistanceGradients,
    PairDistanceJacobians,
    Plane,
    PointQuery,
    Shape,
    Sphere,
    Superellipsoid,
    Triangle,
    collide,
    contact_manifolds,
    distance,
    distance_gradients,
    distance_jacobians,
    simd_instruction_set,
)

__all__ = [
    "Box",
    "Capsule",
    "Cone",
    "Contact",
    "ContactManifold",
    "Convex",
    "Cylinder",
    "DistanceGradients",
    "DistanceJacobians",
    "Ellipsoid",
    "Halfspace",
    "ManifoldPlaces",
    "MarginQuery",
    "Mesh",
    "PairDistance",
    "PairDistanceGradients",
    "PairDistanceJacobians",
    "Plane",
    "PointQuery",
    "Shape",
    "Sphere",
    "Superellipsoid",
    "Triangle",
    "collide",
    "contact_manifolds",
    "distance",
    "distance_gradients",
    "distance_jacobians",
    "simd_instruction_set",
]
