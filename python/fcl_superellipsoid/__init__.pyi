# Type stubs of fcl_superellipsoid (written by hand; test_stubs.py checks them against the module).
from typing import Literal, NamedTuple, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.floating]
Pose = Union[None, ArrayLike, Tuple[ArrayLike, ArrayLike]]
Method = Literal["exact", "paper", "radial"]

simd_instruction_set: str

class PointQuery(NamedTuple):
    distance: Union[float, FloatArray]
    nearest_point: FloatArray
    normal: FloatArray

class MarginQuery(NamedTuple):
    index: npt.NDArray[np.int64]
    distance: FloatArray
    nearest_point: FloatArray
    normal: FloatArray

class DistanceGradients(NamedTuple):
    distance: Union[float, FloatArray]
    nearest_point: FloatArray
    normal: FloatArray
    d_pose: FloatArray
    d_shape: FloatArray
    differentiable: Union[bool, npt.NDArray[np.bool_]]

class DistanceJacobians(NamedTuple):
    distance: Union[float, FloatArray]
    nearest_point: FloatArray
    normal: FloatArray
    d_pose: FloatArray
    d_shape: FloatArray
    differentiable: Union[bool, npt.NDArray[np.bool_]]
    nearest_point_d_point: FloatArray
    nearest_point_d_pose: FloatArray
    nearest_point_d_shape: FloatArray
    normal_d_point: FloatArray
    normal_d_pose: FloatArray
    normal_d_shape: FloatArray

class PairDistance(NamedTuple):
    distance: float
    point1: npt.NDArray[np.float64]
    point2: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]

class PairDistanceGradients(NamedTuple):
    distance: float
    point1: npt.NDArray[np.float64]
    point2: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    d_pose1: npt.NDArray[np.float64]
    d_pose2: npt.NDArray[np.float64]
    d_shape1: Optional[npt.NDArray[np.float64]]
    d_shape2: Optional[npt.NDArray[np.float64]]
    differentiable: bool

class PairDistanceJacobians(NamedTuple):
    distance: float
    point1: npt.NDArray[np.float64]
    point2: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    d_pose1: npt.NDArray[np.float64]
    d_pose2: npt.NDArray[np.float64]
    d_shape1: Optional[npt.NDArray[np.float64]]
    d_shape2: Optional[npt.NDArray[np.float64]]
    differentiable: bool
    point1_d_pose1: npt.NDArray[np.float64]
    point1_d_pose2: npt.NDArray[np.float64]
    point2_d_pose1: npt.NDArray[np.float64]
    point2_d_pose2: npt.NDArray[np.float64]
    normal_d_pose1: npt.NDArray[np.float64]
    normal_d_pose2: npt.NDArray[np.float64]

class Contact(NamedTuple):
    position: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    depth: float

class ManifoldPlaces(NamedTuple):
    position: npt.NDArray[np.float64]
    point1: npt.NDArray[np.float64]
    point2: npt.NDArray[np.float64]
    depth: npt.NDArray[np.float64]

class ContactManifold(NamedTuple):
    normal: npt.NDArray[np.float64]
    distance: float
    point1: npt.NDArray[np.float64]
    point2: npt.NDArray[np.float64]
    patch_tolerance: float
    polygon: ManifoldPlaces
    points: ManifoldPlaces

class Shape: ...

class Superellipsoid(Shape):
    def __init__(self, radii: ArrayLike, exponents: ArrayLike) -> None: ...
    @property
    def radii(self) -> npt.NDArray[np.float64]: ...
    @property
    def exponents(self) -> Tuple[float, float]: ...
    @property
    def size(self) -> float: ...
    @property
    def volume(self) -> float: ...
    @property
    def inertia(self) -> npt.NDArray[np.float64]: ...
    def support(self, directions: ArrayLike) -> npt.NDArray[np.float64]: ...
    @overload
    def contains(self, points: Sequence[float]) -> bool: ...
    @overload
    def contains(self, points: ArrayLike) -> Union[bool, npt.NDArray[np.bool_]]: ...
    def tessellate(
        self, num_vertices: int
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
    def signed_distance(
        self,
        points: ArrayLike,
        pose: Pose = None,
        *,
        method: Method = "exact",
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        threads: int = 0,
        vectorize: bool = True,
    ) -> Union[float, FloatArray]: ...
    def closest_points(
        self,
        points: ArrayLike,
        pose: Pose = None,
        *,
        method: Method = "exact",
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        threads: int = 0,
        vectorize: bool = True,
    ) -> PointQuery: ...
    def distance_gradients(
        self,
        points: ArrayLike,
        pose: Pose = None,
        *,
        method: Literal["exact"] = "exact",
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        threads: int = 0,
        vectorize: bool = True,
    ) -> DistanceGradients: ...
    def distance_jacobians(
        self,
        points: ArrayLike,
        pose: Pose = None,
        *,
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
    ) -> DistanceJacobians: ...
    def within_margin(
        self,
        points: ArrayLike,
        margin: float,
        pose: Pose = None,
        *,
        method: Method = "exact",
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        threads: int = 0,
        vectorize: bool = True,
    ) -> MarginQuery: ...

class Box(Shape):
    def __init__(self, x: float, y: float, z: float) -> None: ...
    @property
    def side(self) -> npt.NDArray[np.float64]: ...

class Sphere(Shape):
    def __init__(self, radius: float) -> None: ...
    @property
    def radius(self) -> float: ...

class Ellipsoid(Shape):
    def __init__(self, a: float, b: float, c: float) -> None: ...
    @property
    def radii(self) -> npt.NDArray[np.float64]: ...

class Capsule(Shape):
    def __init__(self, radius: float, length: float) -> None: ...
    @property
    def radius(self) -> float: ...
    @property
    def length(self) -> float: ...

class Cylinder(Shape):
    def __init__(self, radius: float, length: float) -> None: ...
    @property
    def radius(self) -> float: ...
    @property
    def length(self) -> float: ...

class Cone(Shape):
    def __init__(self, radius: float, length: float) -> None: ...
    @property
    def radius(self) -> float: ...
    @property
    def length(self) -> float: ...

class Convex(Shape):
    def __init__(self, vertices: ArrayLike, faces: ArrayLike) -> None: ...

class Triangle(Shape):
    def __init__(self, a: ArrayLike, b: ArrayLike, c: ArrayLike) -> None: ...

class Halfspace(Shape):
    def __init__(self, normal: ArrayLike, offset: float) -> None: ...

class Plane(Shape):
    def __init__(self, normal: ArrayLike, offset: float) -> None: ...

class Mesh(Shape):
    def __init__(self, vertices: ArrayLike, triangles: ArrayLike) -> None: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_triangles(self) -> int: ...

def distance(shape1: Shape, pose1: Pose, shape2: Shape, pose2: Pose) -> PairDistance: ...
def distance_gradients(
    shape1: Shape, pose1: Pose, shape2: Shape, pose2: Pose
) -> PairDistanceGradients: ...
def distance_jacobians(
    shape1: Shape, pose1: Pose, shape2: Shape, pose2: Pose
) -> PairDistanceJacobians: ...
def collide(
    shape1: Shape, pose1: Pose, shape2: Shape, pose2: Pose, max_contacts: int = 1
) -> list[Contact]: ...
def contact_manifolds(
    shape1: Shape,
    pose1: Pose,
    shape2: Shape,
    pose2: Pose,
    *,
    patch_tolerance: Optional[float] = None,
    max_points: int = 4,
    outline_samples: int = 8,
    outline_area_tolerance: float = 0.005,
    merge_angle: float = 0.05,
) -> list[ContactManifold]: ...
