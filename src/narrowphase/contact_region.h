#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_CONTACT_REGION_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_CONTACT_REGION_H

// Internal: the contact region of a pair from its hit (docs/math.md → "Contact regions").
// Each geometry is seen through a RegionBody (region_bodies.h): its support point and its
// extent along a line. Given the pair's normal n and signed distance d, each body's cap, the
// part beyond the other's supporting plane less the patch tolerance (thickness tolerance − d),
// is outlined on the contact plane by its extreme points in `outline_samples` directions; the
// two outlines are intersected (both convex, counter-clockwise), the depth is measured at each
// vertex along n, and the places are reduced.

#include <memory>
#include <optional>
#include <vector>

#include "fcl_superellipsoid/contact_manifold.h"
#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
using Matrix3 = Eigen::Matrix<S, 3, 3>;

/// A posed convex geometry as the region sees it. World coordinates.
template <typename S>
class RegionBody {
 public:
  virtual ~RegionBody() = default;
  /// A point of the body farthest along v ≠ 0. Unbounded bodies are not asked.
  virtual Vector3<S> support(const Vector3<S>& v) const = 0;
  /// A smooth body's gauge at the world point x (1 on its surface, 1-homogeneous about its
  /// centre) with its gradient and Hessian; false for the others (the cap's outline is then
  /// found from support points alone).
  virtual bool gauge(const Vector3<S>& /*x*/, S& /*value*/, Vector3<S>& /*gradient*/,
                     Matrix3<S>& /*hessian*/) const {
    return false;
  }
  /// The scale of the body (its largest radius; for a polytope, its largest coordinate).
  virtual S size() const = 0;
  /// max{s : y + s·m in the body} for the unit m, or std::nullopt where the line misses it (or
  /// is not finite).
  virtual std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const = 0;
  /// A halfspace (a plane acts as the one the shape is pushed out of): its cap is the whole
  /// contact plane.
  virtual bool unbounded() const { return false; }
  /// A flat polygon's corners (a triangle's three) into `out`, or false for other bodies: where
  /// every corner is in a cap, the cap is the polygon itself (a mesh's facets are outlined so).
  virtual bool corners(std::vector<Vector3<S>>& /*out*/) const { return false; }
};

/// Each cap's first outline points (world), one per sample direction: read as the starts of
/// a warm-started region (where there are as many as directions), then overwritten with the
/// region's own.
template <typename S>
struct RegionWarmStart {
  std::vector<Vector3<S>> a, b;
};

/// The region of the pair whose hit is `hit`, A being the superellipsoid's body (R_WS its
/// orientation, which fixes where the outlines' samples start) and B the other's. `tolerance`
/// > 0, `size` the shape's, options checked; `warm` may be null.
template <typename S>
ContactManifold<S> contactRegion(const RegionBody<S>& a, const RegionBody<S>& b,
                                 const PairHit<S>& hit, const Matrix3<S>& R_WS, S tolerance, S size,
                                 const ManifoldOptions<S>& options,
                                 RegionWarmStart<S>* warm = nullptr);

/// The region of `a` against flat pieces of one surface (a mesh's facets that face the same way,
/// each a RegionBody, world coordinates) at the hit (its normal, and its point on the surface
/// fixing the contact plane and the cap's base): a's cap, outlined once, clipped by each facet,
/// each clipped vertex measured along n against its facet; the region is the convex hull of those
/// places. The hit's place is one of them where `hit_on_facets` (the shape's deepest point lies
/// over a facet); else the region's distance is its deepest vertex's.
template <typename S>
ContactManifold<S> facetsRegion(const RegionBody<S>& a,
                                const std::vector<const RegionBody<S>*>& facets,
                                const PairHit<S>& hit, bool hit_on_facets, const Matrix3<S>& R_WS,
                                S tolerance, S size, const ManifoldOptions<S>& options);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_CONTACT_REGION_H
