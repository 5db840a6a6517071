#ifndef FCL_SUPERELLIPSOID_CONTACT_MANIFOLD_H
#define FCL_SUPERELLIPSOID_CONTACT_MANIFOLD_H

/// @file
/// The contact region of a superellipsoid and another geometry: what a rigid-body simulator
/// needs to hold a body at rest on a face (docs/usage.md → "Contact manifolds"; the geometry:
/// docs/math.md → "Contact regions").
///
/// The pair's normal n is the one its distance query finds (from the superellipsoid towards the
/// other geometry). Of each geometry, the region takes the points that reach within the patch
/// tolerance of the other's supporting plane at n: for a pair that overlaps by δ, the cap of
/// thickness δ + tolerance of each. Both caps are projected on the contact plane (through the
/// middle of the pair's witness points, normal n) and intersected: the region, a convex polygon.
/// Its vertices carry the depth at that place, the overlap of the two geometries along n there
/// (negative where they are apart, by at most the tolerance). The reduced contact points keep
/// the deepest place and span the region's area.
///
/// Answered for the other geometry being a Superellipsoid, fcl::Sphere, Ellipsoid, Box, Convex,
/// TriangleP, Capsule, Cylinder, Cone, Halfspace and Plane (contactManifold), and a triangle mesh
/// (fcl::BVHModel of any BV type), which may touch the shape in several regions
/// (contactManifolds).

#include <fcl/geometry/collision_geometry.h>

#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {

template <typename S>
struct ManifoldOptions {
  /// How far beyond the other's supporting plane a point still belongs to the region, in the
  /// world's length unit; < 0: 1e-3 × the superellipsoid's size (its largest radius).
  S patch_tolerance = S(-1);
  /// Each cap's outline is the polygon through its extreme points in `outline_samples` evenly
  /// spread directions (≥ 3), refined where an edge misses the outline: at most about
  /// `outline_area_tolerance` (> 0) of the cap's area is left out; ≥ 1: not refined (the
  /// cheapest outline, for those who want the reduced points only). Exact where the outline
  /// is a polygon (a polytope's face).
  int outline_samples = 8;
  S outline_area_tolerance = S(0.005);
  /// The most reduced contact points (≥ 1), per region.
  int max_points = 4;
  /// A triangle mesh's regions (contactManifolds): a triangle's region joins a deeper one's
  /// where their normals are within this angle (radians, in [0, π/2]); 0 merges coplanar
  /// triangles only (to rounding: use a tiny angle).
  S merge_angle = S(0.05);
};

/// One place of the region: the points of the two surfaces there, the middle between them on
/// the contact plane, and the depth (overlap along the normal; < 0: apart by that much).
template <typename S>
struct ManifoldPoint {
  Vector3<S> position;  ///< on the contact plane, world
  Vector3<S> on_shape;  ///< the superellipsoid's surface above `position` along n
  Vector3<S> on_other;  ///< the other's surface below `position`
  S depth;
};

template <typename S>
struct ContactManifold {
  Vector3<S> normal;  ///< unit, world, from the superellipsoid towards the other geometry
  S distance;         ///< the pair's signed distance (< 0: overlapping by −distance)
  /// The pair's witness points (world), the superellipsoid's and the other geometry's: apart,
  /// the nearest points; overlapping, the deepest points along the normal. What `distance`
  /// (signed, with nearest points) reports for the pair, so a caller that takes a manifold
  /// needs no distance query beside it.
  Vector3<S> on_shape, on_other;
  S patch_tolerance;  ///< the tolerance used
  /// The region's outline, counter-clockwise about `normal`, on the contact plane. One point
  /// where the region is a point (the two caps meet in less than the tolerance).
  std::vector<ManifoldPoint<S>> polygon;
  /// At most max_points places: the deepest, then those that span the most area.
  std::vector<ManifoldPoint<S>> points;
};

/// What a manifold leaves for the next one of the same pair a step later: each cap's extreme
/// points in the outline's first `outline_samples` directions, in its own geometry's frame. A
/// warm-started call starts each direction's search there (after a small motion, a step or two
/// of Newton's method instead of a search from the deepest point) and leaves its own points.
/// Empty, or of another number of directions, it starts nothing; a point that is not the
/// extreme any more (a large motion, another pair) is solved again from the start, so the
/// answer is the fresh call's whatever the warm start holds.
template <typename S>
struct ManifoldWarmStart {
  std::vector<Vector3<S>> shape_points;  ///< the superellipsoid's, in its frame
  std::vector<Vector3<S>> other_points;  ///< the other geometry's, in its frame (none: flat)
};

/// The contact region of the superellipsoid `shape` at X_WS and `other` at X_WO. Refuses a
/// geometry it has no region for, a pose or option that is not valid, naming the value.
template <typename S>
ContactManifold<S> contactManifold(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                   const fcl::CollisionGeometry<S>& other,
                                   const fcl::Transform3<S>& X_WO,
                                   const ManifoldOptions<S>& options = {});
/// The same, warm-started from `warm` (see ManifoldWarmStart), which it then overwrites.
template <typename S>
ContactManifold<S> contactManifold(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                   const fcl::CollisionGeometry<S>& other,
                                   const fcl::Transform3<S>& X_WO,
                                   const ManifoldOptions<S>& options, ManifoldWarmStart<S>& warm);

/// Every contact region of the superellipsoid `shape` at X_WS and `other` at X_WO, deepest
/// first: none where they are apart by more than the patch tolerance.
/// - A triangle mesh (fcl::BVHModel of any BV type) is a surface: each triangle within the
///   patch tolerance meets the shape along its own face normal (on the shape's side), as the
///   halfspace bounded by its plane would, clipped to the triangle; a triangle the shape
///   overlaps only across a ridge (its deepest part over a neighbour whose normal would clear
///   it) is left out. A triangle joins the first deeper one whose normal is within
///   `options.merge_angle` of its own. A region keeps its deepest triangle's normal and
///   distance; its polygon is the convex hull of the shape's cap clipped by each of its
///   triangles, on that triangle's contact plane, and its points are reduced from it as one
///   region's are. A vertex or ridge edge of the mesh within the tolerance that no face's
///   region holds (at least as deep less the tolerance, and overlapping if it does) is a region
///   of its own along the shape's normal at its deepest point: a vertex one place, a ridge its
///   deepest place and the ends of its part within the tolerance (docs/math.md → "A mesh's
///   regions"). A point cloud is refused (it has no surface).
/// - Every other geometry contactManifold answers: its region, if any.
template <typename S>
std::vector<ContactManifold<S>> contactManifolds(const Superellipsoid<S>& shape,
                                                 const fcl::Transform3<S>& X_WS,
                                                 const fcl::CollisionGeometry<S>& other,
                                                 const fcl::Transform3<S>& X_WO,
                                                 const ManifoldOptions<S>& options = {});

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_CONTACT_MANIFOLD_H
