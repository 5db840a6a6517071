// The public contact manifolds (contact_manifold.h): the pair's row of pair_kinds.h answers the
// hit and gives the other geometry's region body; narrowphase/contact_region.h builds the
// region; a triangle mesh's regions come from mesh_manifold.h.

#include "fcl_glue/contact_manifold.h"

#include <cmath>
#include <string>

#include "common/coordinate_range.h"
#include "common/invalid_argument.h"
#include "fcl_glue/mesh_manifold.h"
#include "narrowphase/contact_region.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

template <typename S>
void checkOptions(const char* where, const ManifoldOptions<S>& options) {
  if (!(std::isfinite(options.patch_tolerance) && options.patch_tolerance != S(0))) {
    throwInvalidArgument(where, "options.patch_tolerance must be finite and > 0 (< 0: the default)",
                         options.patch_tolerance);
  }
  if (!(options.outline_samples >= 3 && options.outline_samples <= 4096)) {
    throwInvalidArgument(where, "options.outline_samples must be in [3, 4096]",
                         options.outline_samples);
  }
  if (!(options.outline_area_tolerance > S(0) && std::isfinite(options.outline_area_tolerance))) {
    throwInvalidArgument(where, "options.outline_area_tolerance must be finite and > 0",
                         options.outline_area_tolerance);
  }
  if (!(options.max_points >= 1)) {
    throwInvalidArgument(where, "options.max_points must be >= 1", options.max_points);
  }
  if (!(options.merge_angle >= S(0) && options.merge_angle <= S(M_PI / 2))) {
    throwInvalidArgument(where, "options.merge_angle must be in [0, pi/2]", options.merge_angle);
  }
}

template <typename S>
S patchTolerance(const ManifoldOptions<S>& options, const Superellipsoid<S>& shape) {
  return options.patch_tolerance > S(0) ? options.patch_tolerance : S(1e-3) * shape.size();
}

}  // namespace

template <typename S>
ContactManifold<S> pairManifold(const Pair<S>& pair, const PairKind<S>& kind, const PairHit<S>& hit,
                                const ManifoldOptions<S>& options, ManifoldWarmStart<S>* warm) {
  const S tolerance = patchTolerance(options, *pair.shape);
  const std::unique_ptr<RegionBody<S>> shape = regionBody(*pair.shape, *pair.X_WS);
  const std::unique_ptr<RegionBody<S>> other = kind.region(pair, hit);
  // A warm start's points go to the world and back, each in its geometry's frame; a set with a
  // point that is not finite starts nothing.
  const fcl::Transform3<S>& X_WS = *pair.X_WS;
  const fcl::Transform3<S>& X_WO = *pair.X_WO;
  RegionWarmStart<S> world;
  const auto toWorld = [](const std::vector<Vector3<S>>& local, const fcl::Transform3<S>& X,
                          std::vector<Vector3<S>>& out) {
    for (const Vector3<S>& p : local) {
      out.push_back(X * p);
      if (!out.back().allFinite()) {
        out.clear();
        return;
      }
    }
  };
  if (warm != nullptr) {
    toWorld(warm->shape_points, X_WS, world.a);
    toWorld(warm->other_points, X_WO, world.b);
  }
  ContactManifold<S> out =
      contactRegion(*shape, *other, hit, Matrix3<S>(X_WS.linear()), tolerance, pair.shape->size(),
                    options, warm != nullptr ? &world : nullptr);
  if (warm != nullptr) {
    const fcl::Transform3<S> X_SW = X_WS.inverse(), X_OW = X_WO.inverse();
    warm->shape_points.clear();
    warm->other_points.clear();
    for (const Vector3<S>& p : world.a) warm->shape_points.push_back(X_SW * p);
    for (const Vector3<S>& p : world.b) warm->other_points.push_back(X_OW * p);
  }
  return out;
}

}  // namespace detail

namespace {

/// The pair of a public call, its poses and options checked (`where` names the call).
template <typename S>
detail::Pair<S> checkedPair(const char* where, const Superellipsoid<S>& shape,
                            const fcl::Transform3<S>& X_WS, const fcl::CollisionGeometry<S>& other,
                            const fcl::Transform3<S>& X_WO, const ManifoldOptions<S>& options) {
  detail::checkPose(where, "X_WS", X_WS);
  detail::checkPose(where, "X_WO", X_WO);
  detail::checkOptions(where, options);
  return detail::makePair<S>(&shape, X_WS, &other, X_WO);
}

/// The region of the shape and another shape (its row's hit and body); a geometry without a
/// region is refused, naming `where`.
template <typename S>
ContactManifold<S> shapeManifold(const char* where, const detail::Pair<S>& pair,
                                 const ManifoldOptions<S>& options, ManifoldWarmStart<S>* warm) {
  const detail::PairKind<S>* kind = detail::findPairKind<S>(pair.other_type);
  std::optional<detail::PairHit<S>> hit;
  if (kind != nullptr && kind->region != nullptr) hit = kind->answer(pair, where);
  if (!hit) {
    if (kind != nullptr && kind->form == detail::PairForm::kMesh) {
      detail::throwInvalidArgument(where,
                                   "a BVH model may touch the shape in several regions: ask "
                                   "contactManifolds for them (its node type)",
                                   detail::nodeTypeName(pair.other_type));
    }
    detail::throwUnsupportedPartner(where, *pair.other);
  }
  return detail::pairManifold(pair, *kind, *hit, options, warm);
}

}  // namespace

template <typename S>
ContactManifold<S> contactManifold(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                   const fcl::CollisionGeometry<S>& other,
                                   const fcl::Transform3<S>& X_WO,
                                   const ManifoldOptions<S>& options) {
  constexpr const char* kWhere = "contactManifold";
  return shapeManifold(kWhere, checkedPair(kWhere, shape, X_WS, other, X_WO, options), options,
                       static_cast<ManifoldWarmStart<S>*>(nullptr));
}

template <typename S>
ContactManifold<S> contactManifold(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                   const fcl::CollisionGeometry<S>& other,
                                   const fcl::Transform3<S>& X_WO,
                                   const ManifoldOptions<S>& options, ManifoldWarmStart<S>& warm) {
  constexpr const char* kWhere = "contactManifold";
  return shapeManifold(kWhere, checkedPair(kWhere, shape, X_WS, other, X_WO, options), options,
                       &warm);
}

template <typename S>
std::vector<ContactManifold<S>> contactManifolds(const Superellipsoid<S>& shape,
                                                 const fcl::Transform3<S>& X_WS,
                                                 const fcl::CollisionGeometry<S>& other,
                                                 const fcl::Transform3<S>& X_WO,
                                                 const ManifoldOptions<S>& options) {
  constexpr const char* kWhere = "contactManifolds";
  const detail::Pair<S> pair = checkedPair(kWhere, shape, X_WS, other, X_WO, options);
  if (std::optional<std::vector<ContactManifold<S>>> regions =
          detail::meshManifolds(pair, options, detail::patchTolerance(options, shape), kWhere)) {
    return std::move(*regions);
  }
  ContactManifold<S> region =
      shapeManifold(kWhere, pair, options, static_cast<ManifoldWarmStart<S>*>(nullptr));
  if (region.points.empty()) return {};
  return {std::move(region)};
}

#define FSE_INSTANTIATE_CONTACT_MANIFOLD(S)                                                  \
  template ContactManifold<S> contactManifold(                                               \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const fcl::CollisionGeometry<S>&, \
      const fcl::Transform3<S>&, const ManifoldOptions<S>&);                                 \
  template ContactManifold<S> contactManifold(                                               \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const fcl::CollisionGeometry<S>&, \
      const fcl::Transform3<S>&, const ManifoldOptions<S>&, ManifoldWarmStart<S>&);          \
  template ContactManifold<S> detail::pairManifold(                                          \
      const detail::Pair<S>&, const detail::PairKind<S>&, const detail::PairHit<S>&,         \
      const ManifoldOptions<S>&, ManifoldWarmStart<S>*);                                     \
  template std::vector<ContactManifold<S>> contactManifolds(                                 \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const fcl::CollisionGeometry<S>&, \
      const fcl::Transform3<S>&, const ManifoldOptions<S>&);
FSE_INSTANTIATE_CONTACT_MANIFOLD(float)
FSE_INSTANTIATE_CONTACT_MANIFOLD(double)

}  // namespace fcl_superellipsoid
