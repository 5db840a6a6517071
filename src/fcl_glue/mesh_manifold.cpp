#include "fcl_glue/mesh_manifold.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "fcl_glue/bv_types.h"
#include "fcl_glue/bvh_node.h"
#include "fcl_glue/pair_kinds.h"
#include "narrowphase/contact_region.h"
#include "narrowphase/mesh_facets.h"
#include "narrowphase/mesh_features.h"
#include "narrowphase/polytope_pair.h"
#include "narrowphase/region_bodies.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// The triangles whose BV the shape may come within `margin` of, in index order. A node is
/// skipped where a separating axis (the BV's box's three, the shape's three) keeps the shape's
/// bounding box, centre c and axes R in the model's frame, more than `margin` from the BV.
template <typename BV>
std::vector<int> trianglesNear(const fcl::BVHModel<BV>& model, const Vector3<typename BV::S>& c,
                               const fcl::Matrix3<typename BV::S>& R,
                               const Vector3<typename BV::S>& radii, typename BV::S margin) {
  using S = typename BV::S;
  std::vector<int> found;
  if (model.getNumBVs() <= 0) return found;
  const auto shapeHalfWidth = [&](const Vector3<S>& u) {
    return (R.transpose() * u).cwiseAbs().dot(radii);
  };
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const fcl::BVNode<BV>& node = model.getBV(stack.back());
    stack.pop_back();
    const SweptBox<S> box = sweptBox(node.bv);
    const Vector3<S> d = c - box.centre;
    S gap = -std::numeric_limits<S>::infinity();
    for (int k = 0; k < 3; ++k) {
      const Vector3<S> u = box.axes.col(k);
      gap = std::max(gap, std::abs(u.dot(d)) - shapeHalfWidth(u) - box.half_extents[k]);
      const Vector3<S> v = R.col(k);
      gap = std::max(gap, std::abs(v.dot(d)) - radii[k] - boxHalfWidth(box, v));
    }
    // A BV that is not finite (a vertex that is not) bounds nothing: its triangles are reached
    // and refused.
    const bool finite = box.centre.allFinite() && box.axes.allFinite() &&
                        box.half_extents.allFinite() && std::isfinite(box.radius);
    if (finite && gap - box.radius > margin) continue;
    if (isLeaf(node)) {
      found.push_back(primitiveId(node));
    } else {
      stack.push_back(rightChild(node));
      stack.push_back(leftChild(node));
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

/// Whether the facet's face holds the shape's contact at its normal, the shape overlapping its
/// plane by `overlap` with its deepest point there at barycentric coordinates `at` (`centre`:
/// the shape's, world). Over the facet it does. Beyond an edge, each neighbour across it (a
/// facet near the shape that shares the edge, found in `edges`) offers its own normal as a way out:
/// where moving the shape along it clears the facet by less than `overlap` less the tolerance, the
/// facet's normal overstates the contact (the shape rests across a ridge, on the neighbour's side,
/// and meets this facet only sideways), and it does not hold. A flat or concave continuation never
/// offers a shorter way out, nor does the mesh's boundary (no neighbour).
template <typename S>
bool faceHoldsContact(const std::vector<Facet<S>>& facets, const std::vector<EdgeOfFacet>& edges,
                      std::size_t i, const Vector3<S>& at, S overlap, const RegionBody<S>& shape,
                      const Vector3<S>& centre, S tolerance, S slack) {
  const Facet<S>& f = facets[i];
  S reach = shape.size();  // of the facet's corners and the shape, from the shape's centre
  for (const Vector3<S>& p : f.p) reach = std::max(reach, (p - centre).norm());
  for (int k = 0; k < 3; ++k) {
    if (at[k] >= -slack) continue;  // not beyond the edge opposite corner k
    const int a = f.corner[(k + 1) % 3], b = f.corner[(k + 2) % 3];
    const EdgeOfFacet first{std::min(a, b), std::max(a, b), -1};
    for (auto e = std::lower_bound(edges.begin(), edges.end(), first);
         e != edges.end() && (*e)[0] == first[0] && (*e)[1] == first[1]; ++e) {
      const std::size_t j = std::size_t((*e)[2]);
      if (j == i) continue;
      const Facet<S>& g = facets[j];
      // Measured from the shape's centre c, the clearance along u differs from `overlap` (the
      // clearance along f's normal) by at most |u − f.normal| × (the farthest corner's and the
      // shape's reach from c): a neighbour that faces the same way to within that cannot
      // refuse, and costs no support point.
      const Vector3<S>& u = g.normal;
      if ((u - f.normal).norm() * S(2) * reach < tolerance) continue;
      const S highest = std::max({f.p[0].dot(u), f.p[1].dot(u), f.p[2].dot(u)});
      const S clearance = highest - shape.support(Vector3<S>(-u)).dot(u);
      if (clearance < overlap - tolerance) return false;
    }
  }
  return true;
}

}  // namespace

template <typename S>
bool isTriangleMesh(const Pair<S>& pair) {
  bool triangles = false;
  visitBvh(pair.other, [&](const auto& model) {
    triangles = model.getModelType() == fcl::BVH_MODEL_TRIANGLES && model.num_tris > 0;
  });
  return triangles;
}

template <typename S>
std::optional<std::vector<ContactManifold<S>>> meshManifolds(const Pair<S>& pair,
                                                             const ManifoldOptions<S>& options,
                                                             S tolerance, const char* where,
                                                             std::vector<int>* first_facets) {
  const Superellipsoid<S>& shape = *pair.shape;
  const fcl::Transform3<S>& X_WS = *pair.X_WS;
  const fcl::Transform3<S>& X_WO = *pair.X_WO;
  const S size = shape.size();
  std::vector<std::pair<ContactManifold<S>, int>> regions;  // with the first facet's index
  const bool handled = visitBvh(pair.other, [&](const auto& model) {
    if (model.getModelType() == fcl::BVH_MODEL_POINTCLOUD) {
      throwInvalidArgument(where,
                           "the other geometry must be a triangle mesh: a point cloud has no "
                           "surface to make regions of (FCL's collide answers its vertices; its "
                           "model type)",
                           "BVH_MODEL_POINTCLOUD");
    }
    const fcl::Transform3<S> X_OS = X_WO.inverse(Eigen::Isometry) * X_WS;
    const Vector3<S> centre = X_WS.translation();
    std::vector<Facet<S>> facets;
    for (const int t : trianglesNear(model, Vector3<S>(X_OS.translation()),
                                     fcl::Matrix3<S>(X_OS.linear()), shape.radii(), tolerance)) {
      const fcl::Triangle& corners = model.tri_indices[t];
      Facet<S> f{t, {int(corners[0]), int(corners[1]), int(corners[2])}, {}, {}};
      checkTriangle(where, fcl::TriangleP<S>(model.vertices[corners[0]], model.vertices[corners[1]],
                                             model.vertices[corners[2]]));
      for (int k = 0; k < 3; ++k) f.p[k] = X_WO * model.vertices[corners[k]];
      const Vector3<S> area = (f.p[1] - f.p[0]).cross(f.p[2] - f.p[0]);
      const S twice = area.norm();
      // A triangle of no area has no face (its edges are its neighbours').
      if (!(twice > std::numeric_limits<S>::epsilon() * (f.p[1] - f.p[0]).squaredNorm() &&
            twice > S(0))) {
        continue;
      }
      f.normal = area / twice;
      if (f.normal.dot(centre - f.p[0]) < S(0)) f.normal = -f.normal;
      facets.push_back(f);
    }
    const std::unique_ptr<RegionBody<S>> shape_body = regionBody(shape, X_WS);
    const S slack = S(64) * std::numeric_limits<S>::epsilon();
    // Each facet's face as the other body: the shape pressed against its plane along its
    // normal, as against a halfspace; the facets the face holds the contact of, deepest first.
    std::vector<std::pair<S, std::size_t>> held;  // (the shape's overlap with the plane, facet)
    const std::vector<EdgeOfFacet> edges = edgesOf(facets);
    // Facets of one flat piece share their normal to the bit, and so their support point.
    Vector3<S> last_normal = Vector3<S>::Zero(), on_shape = Vector3<S>::Zero();
    for (std::size_t i = 0; i < facets.size(); ++i) {
      const Facet<S>& f = facets[i];
      if (f.normal != last_normal) on_shape = shape_body->support(Vector3<S>(-f.normal));
      last_normal = f.normal;
      const S overlap = (f.p[0] - on_shape).dot(f.normal);
      if (!(-overlap < tolerance)) continue;
      const Vector3<S> at = barycentric(f, Vector3<S>(on_shape + overlap * f.normal));
      if (faceHoldsContact(facets, edges, i, at, overlap, *shape_body, centre, tolerance, slack)) {
        held.emplace_back(-overlap, i);
      }
    }
    std::stable_sort(held.begin(), held.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    // A facet joins the first group whose first (deepest) facet's normal is within the merge
    // angle of its own; each group is one region, at its first facet's plane.
    const S min_cos = std::cos(options.merge_angle);
    std::vector<std::vector<std::size_t>> groups;
    for (const std::pair<S, std::size_t>& entry : held) {
      const std::size_t i = entry.second;
      auto joins = std::find_if(groups.begin(), groups.end(), [&](const auto& group) {
        return facets[group.front()].normal.dot(facets[i].normal) >= min_cos;
      });
      if (joins == groups.end()) {
        groups.push_back({i});
      } else {
        joins->push_back(i);
      }
    }
    const Matrix3<S> R_WS = X_WS.linear();
    std::vector<FaceCover<S>> cover(facets.size());
    for (const std::vector<std::size_t>& group : groups) {
      const Facet<S>& first = facets[group.front()];
      PairHit<S> hit;
      hit.normal = -first.normal;
      hit.on_shape = shape_body->support(hit.normal);
      const S overlap = (hit.on_shape - first.p[0]).dot(hit.normal);
      hit.distance = -overlap;
      hit.on_other = hit.on_shape - overlap * hit.normal;
      hit.other_primitive = first.index;
      std::vector<std::unique_ptr<RegionBody<S>>> bodies;
      std::vector<const RegionBody<S>*> pieces;
      bool hit_on_facets = false;
      for (const std::size_t i : group) {
        const Facet<S>& f = facets[i];
        bodies.push_back(
            regionBody(fcl::TriangleP<S>(f.p[0], f.p[1], f.p[2]), fcl::Transform3<S>::Identity()));
        pieces.push_back(bodies.back().get());
        const Vector3<S> below = hit.on_shape - (hit.on_shape - f.p[0]).dot(f.normal) * f.normal;
        hit_on_facets = hit_on_facets || barycentric(f, below).minCoeff() >= -slack;
      }
      ContactManifold<S> region =
          facetsRegion(*shape_body, pieces, hit, hit_on_facets, R_WS, tolerance, size, options);
      if (region.points.empty()) continue;
      for (const std::size_t i : group) cover[i] = {true, region.distance, region.normal};
      regions.emplace_back(std::move(region), first.index);
    }
    // The vertices and ridges poking into the shape where no face holds it.
    for (FeatureRegion<S>& f :
         featureRegions(shape, X_WS, *shape_body, facets, edges, cover, tolerance, options)) {
      regions.emplace_back(std::move(f.region), f.triangle);
    }
  });
  if (!handled) return std::nullopt;
  std::stable_sort(regions.begin(), regions.end(), [](const auto& x, const auto& y) {
    return x.first.distance < y.first.distance;
  });
  std::vector<ContactManifold<S>> out;
  for (auto& [region, facet] : regions) {
    out.push_back(std::move(region));
    if (first_facets != nullptr) first_facets->push_back(facet);
  }
  return out;
}

#define FSE_INSTANTIATE_MESH_MANIFOLD(S)                                             \
  template std::optional<std::vector<ContactManifold<S>>> meshManifolds(             \
      const Pair<S>&, const ManifoldOptions<S>&, S, const char*, std::vector<int>*); \
  template bool isTriangleMesh(const Pair<S>&);
FSE_INSTANTIATE_MESH_MANIFOLD(float)
FSE_INSTANTIATE_MESH_MANIFOLD(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
