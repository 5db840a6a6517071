#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_BV_TYPES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_BV_TYPES_H

// Internal: FCL's eight BV types as the mesh pairs see them: the fcl::BVHModel<BV> behind a
// geometry (visitBvh), and each BV as a box swept by a sphere (sweptBox), which is how the BVH
// traversals bound a node (vertex_traversal.h, mesh_manifold.h).

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include <type_traits>

namespace fcl_superellipsoid {
namespace detail {

/// Calls f(model) with the BVHModel<BV> behind g for FCL's eight BV types; false if g is
/// not one of them.
template <typename S, typename F>
bool visitBvh(const fcl::CollisionGeometry<S>* g, F&& f) {
  if (g->getObjectType() != fcl::OT_BVH) return false;
  auto as = [&](auto* tag) {
    using BV = std::remove_pointer_t<decltype(tag)>;
    const auto* model = dynamic_cast<const fcl::BVHModel<BV>*>(g);
    if (model == nullptr) return false;
    f(*model);
    return true;
  };
  switch (g->getNodeType()) {
    case fcl::BV_AABB:
      return as(static_cast<fcl::AABB<S>*>(nullptr));
    case fcl::BV_OBB:
      return as(static_cast<fcl::OBB<S>*>(nullptr));
    case fcl::BV_RSS:
      return as(static_cast<fcl::RSS<S>*>(nullptr));
    case fcl::BV_kIOS:
      return as(static_cast<fcl::kIOS<S>*>(nullptr));
    case fcl::BV_OBBRSS:
      return as(static_cast<fcl::OBBRSS<S>*>(nullptr));
    case fcl::BV_KDOP16:
      return as(static_cast<fcl::KDOP<S, 16>*>(nullptr));
    case fcl::BV_KDOP18:
      return as(static_cast<fcl::KDOP<S, 18>*>(nullptr));
    case fcl::BV_KDOP24:
      return as(static_cast<fcl::KDOP<S, 24>*>(nullptr));
    default:
      return false;
  }
}

/// A box swept by a sphere, in the model's frame M: what every BV type is bounded as.
template <typename S>
struct SweptBox {
  Vector3<S> centre;
  fcl::Matrix3<S> axes;  // columns
  Vector3<S> half_extents;
  S radius = 0;
};

template <typename S>
SweptBox<S> sweptBox(const fcl::AABB<S>& bv) {
  return {bv.center(), fcl::Matrix3<S>::Identity(), S(0.5) * (bv.max_ - bv.min_), S(0)};
}
template <typename S>
SweptBox<S> sweptBox(const fcl::OBB<S>& bv) {
  return {bv.To, bv.axis, bv.extent, S(0)};
}
template <typename S>
SweptBox<S> sweptBox(const fcl::RSS<S>& bv) {
  return {bv.center(), bv.axis, Vector3<S>(S(0.5) * bv.l[0], S(0.5) * bv.l[1], S(0)), bv.r};
}
template <typename S>
SweptBox<S> sweptBox(const fcl::kIOS<S>& bv) {
  return sweptBox(bv.obb);
}
template <typename S>
SweptBox<S> sweptBox(const fcl::OBBRSS<S>& bv) {
  return sweptBox(bv.obb);
}
/// A k-DOP's first three slab pairs are the x, y, z ones: its bounding box.
template <typename S, std::size_t N>
SweptBox<S> sweptBox(const fcl::KDOP<S, N>& bv) {
  const Vector3<S> lo(bv.dist(0), bv.dist(1), bv.dist(2));
  const Vector3<S> hi(bv.dist(N / 2), bv.dist(N / 2 + 1), bv.dist(N / 2 + 2));
  return {S(0.5) * (lo + hi), fcl::Matrix3<S>::Identity(), S(0.5) * (hi - lo), S(0)};
}

/// The half width of the swept box's box along the unit u (without its sphere).
template <typename S>
S boxHalfWidth(const SweptBox<S>& box, const Vector3<S>& u) {
  return (box.axes.transpose() * u).cwiseAbs().dot(box.half_extents);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_BV_TYPES_H
