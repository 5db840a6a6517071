#ifndef FCL_SUPERELLIPSOID_SUPERELLIPSOID_H
#define FCL_SUPERELLIPSOID_SUPERELLIPSOID_H

/// @file
/// The superellipsoid as an FCL collision geometry.
///
/// Convention (the reference paper's Eq. 3 and 4; docs/math.md → "Convention"):
/// radii a1, a2, a3 > 0 along the shape frame's x, y, z axes; ε1 shapes the xy-plane,
/// ε2 the z direction. The implicit (inside–outside) function is
///
///   F(x) = ( |x/a1|^(2/ε1) + |y/a2|^(2/ε1) )^(ε1/ε2) + |z/a3|^(2/ε2),   surface: F = 1.
///
/// (The paper's Eq. 2 prints the outer exponent as ε1/2: a typo that contradicts its Eq. 3/4.)
/// F grows like t^(2/ε2) along a ray, which overflows for far points and small ε, so all
/// evaluations go through the gauge G = F^(ε2/2), a nested p-norm that is 1-homogeneous:
///
///   G(x) = ‖( ‖(x/a1, y/a2)‖_(2/ε1), z/a3 )‖_(2/ε2),   G(t·x) = t·G(x).
///
/// Every p-norm is evaluated after dividing by its largest argument, so each power is
/// taken of a number in [0, 1]: no overflow for ε → 0 or far points, and no loss of the
/// small terms that matter when one exponent is near 2 and the other near 0.

#include <fcl/geometry/shape/shape_base.h>

#include <iosfwd>
#include <limits>
#include <memory>
#include <vector>

#include "fcl_superellipsoid/distance_options.h"
#include "fcl_superellipsoid/export.h"

namespace fcl_superellipsoid {

template <typename S>
using Vector3 = fcl::Vector3<S>;

/// The numeric range of the shape (docs/hardening.md → "Numeric range"): every radius in
/// [kMinRadius, kMaxRadius], and the largest at most kMaxAspectRatio × the smallest. Inside it
/// the mass properties stay finite and non-zero, and every query on a finite point gives a
/// finite answer (points far beyond the shape included); the constructor refuses radii outside.
template <typename S>
struct NumericRange;
template <>
struct NumericRange<double> {
  static constexpr double kMinRadius = 1e-50;
  static constexpr double kMaxRadius = 1e50;
  static constexpr double kMaxAspectRatio = 1e8;
};
template <>
struct NumericRange<float> {
  static constexpr float kMinRadius = 1e-6f;
  static constexpr float kMaxRadius = 1e6f;
  static constexpr float kMaxAspectRatio = 1e6f;
};

namespace detail {
template <typename S>
class ShapeCaches;  // what the solvers keep per shape; opaque to users
}  // namespace detail

/// How FCL's collide meets a triangle mesh (an fcl::BVHModel with triangles) against a
/// superellipsoid (Superellipsoid::setMeshContacts; docs/usage.md → "Contact manifolds").
enum class MeshContacts {
  /// One contact per penetrating vertex, the deepest first (the reference paper's model, for
  /// cloth and point clouds); distance queries always take the vertices.
  kVertices,
  /// The mesh as a surface: the places of its contact regions (contactManifolds), at most four
  /// per region, deepest region first, each with its region's normal and its own depth.
  kRegions,
};

/// A superellipsoid centred at the origin of its frame, axis-aligned in that frame.
///
/// Exponents are accepted in the open interval (0, 2), where the shape is convex and
/// smooth. The range tested and supported with full accuracy is [0.02, 1.98]; inside it
/// every evaluation is finite for points from 1e-12 × size to 1e6 × size from the centre.
///
/// Constructing a Superellipsoid registers the library's entries in FCL's function tables
/// (fcl_integration.h: registerWithFcl(), once per process, thread-safe), so the first query
/// through fcl::distance / fcl::collide with a GJKSolver_libccd already finds them. This is the
/// shape's one call into the FCL layer; it costs nothing after the first construction.
template <typename S>
class FSE_EXPORT Superellipsoid : public fcl::ShapeBase<S> {
 public:
  /// @throws std::invalid_argument if a radius is not finite and in NumericRange<S>, the radii's
  ///         aspect ratio exceeds NumericRange<S>::kMaxAspectRatio, or an exponent is not finite
  ///         or not in (0, 2). The message names the parameter and its value.
  /// Registers with FCL's tables on first use (see the class comment).
  Superellipsoid(S a1, S a2, S a3, S eps1, S eps2);
  Superellipsoid(const Vector3<S>& radii, S eps1, S eps2);
  /// Copies share what the solvers computed for the shape (a moved-from shape stays usable: a
  /// move copies).
  Superellipsoid(const Superellipsoid&) = default;
  Superellipsoid& operator=(const Superellipsoid&) = default;

  const Vector3<S>& radii() const { return radii_; }
  S eps1() const { return eps1_; }
  S eps2() const { return eps2_; }
  /// The largest radius: the length scale used for size-relative tolerances.
  S size() const { return radii_.maxCoeff(); }

  /// The evaluations below take a point p_S in the shape's frame.
  /// @throws std::invalid_argument if p_S (or η, ω) is not finite, naming it.

  /// F(p_S), the paper's inside–outside function (1 on the surface). Overflows to +inf for
  /// far points with small ε2; prefer gauge().
  S implicitFunction(const Vector3<S>& p_S) const;
  /// G(p_S) = F^(ε2/2): 1-homogeneous, < 1 inside, 1 on the surface, > 1 outside.
  S gauge(const Vector3<S>& p_S) const;
  /// ∇G at p_S. 0-homogeneous (same on every ray), bounded, zero only at the centre.
  Vector3<S> gaugeGradient(const Vector3<S>& p_S) const;
  /// ∇F = (2/ε2)·G^(2/ε2 − 1)·∇G (the paper's Eq. 2 normal, up to scale).
  Vector3<S> implicitGradient(const Vector3<S>& p_S) const;
  /// Unit outward normal of the level set of G through p_S. At the centre, where it is
  /// undefined, returns +z.
  Vector3<S> normal(const Vector3<S>& p_S) const;
  /// Radial distance (paper Eq. 3): ‖p‖·(1 − 1/G(p)), signed (negative inside). Measured
  /// along the ray from the centre, so only an approximation of the Euclidean distance.
  /// At the centre itself it returns −(smallest radius).
  S radialDistance(const Vector3<S>& p_S) const;
  /// The point of the surface on the ray from the centre through p_S (p_S ≠ 0).
  Vector3<S> radialProjection(const Vector3<S>& p_S) const;
  /// Parametric surface (paper Eq. 4): η ∈ [−π/2, π/2] latitude, ω ∈ [−π, π) longitude.
  Vector3<S> surfacePoint(S eta, S omega) const;
  /// True if p_S is inside or on the surface (G ≤ 1).
  bool contains(const Vector3<S>& p_S) const;
  /// The support point: the surface point that maximises direction·x, in closed form as the
  /// gradient of the support function h (docs/math.md). Unique for every non-zero direction
  /// (the shape is strictly convex for ε < 2); any length of direction. For the zero
  /// direction every surface point qualifies: returns (a1, 0, 0).
  /// @throws std::invalid_argument if a component of direction is NaN or infinite.
  Vector3<S> supportPoint(const Vector3<S>& direction) const;

  /// A lower bound on the smallest principal radius of curvature of the surface (within 10 % of
  /// it): every ball of this radius that touches the surface from inside lies inside the shape
  /// (it "rolls freely"; docs/math.md → "The rolling-ball certificate"). 0 where an exponent is
  /// > 1 (the surface then has creases of unbounded curvature) or the largest radius exceeds
  /// 1000 × the smallest (beyond what its search is validated for). Computed on the first call
  /// (the Exact solver calls it where its cheaper certificates do not settle an inside query),
  /// then kept; copies share it.
  S minRadiusOfCurvature() const;

  /// The options FCL queries against this shape use (fcl_integration.h: mesh vertices,
  /// spheres). Default: the Exact method with its default tolerance.
  const DistanceOptions<S>& queryOptions() const { return query_options_; }
  /// @throws std::invalid_argument naming the bad value (see validateOptions).
  void setQueryOptions(const DistanceOptions<S>& options);
  /// How FCL's collide meets a triangle mesh against this shape. Default: kVertices. Point
  /// clouds are always met by their vertices.
  MeshContacts meshContacts() const { return mesh_contacts_; }
  /// @throws std::invalid_argument for a value that is not one of MeshContacts'.
  void setMeshContacts(MeshContacts contacts);

  // --- fcl::CollisionGeometry interface -------------------------------------------------
  /// Tight box ±a_i; aabb_center = 0, aabb_radius = ‖a‖.
  void computeLocalAABB() override;
  /// fcl::BV_UNKNOWN: FCL's NODE_TYPE enum is closed; this is its free slot.
  fcl::NODE_TYPE getNodeType() const override { return fcl::BV_UNKNOWN; }
  /// Closed form, V = 2·a1·a2·a3·ε1·ε2·B(ε1/2, ε1/2)·B(ε2/2 + 1, ε2).
  S computeVolume() const override;
  Vector3<S> computeCOM() const override { return Vector3<S>::Zero(); }
  /// Inertia about the centre for unit density (FCL's convention), diagonal in the frame.
  fcl::Matrix3<S> computeMomentofInertia() const override;
  /// The 8 corners of the local box, posed by tf: a convex set that encloses the shape
  /// (used by FCL's generic computeBV for OBB, RSS, kIOS, OBBRSS and k-DOPs).
  std::vector<Vector3<S>> getBoundVertices(const fcl::Transform3<S>& tf) const;

 private:
  Vector3<S> radii_;
  S eps1_;
  S eps2_;
  DistanceOptions<S> query_options_;
  MeshContacts mesh_contacts_ = MeshContacts::kVertices;
  friend class detail::ShapeCaches<S>;
  std::shared_ptr<const detail::ShapeCaches<S>> caches_;  // never null
};

template <typename S>
FSE_EXPORT std::ostream& operator<<(std::ostream& out, const Superellipsoid<S>& shape);

using Superellipsoidf = Superellipsoid<float>;
using Superellipsoidd = Superellipsoid<double>;

extern template class Superellipsoid<float>;
extern template class Superellipsoid<double>;

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SUPERELLIPSOID_H
