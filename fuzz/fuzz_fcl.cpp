// Fuzz target 3: the FCL front end and FCL's table entries (GJKSolver_libccd) on random pairs
// and poses: a superellipsoid of the fixed family (shape_family.h) against every FCL shape,
// another of the family, a mesh or a point cloud in every BV type (mostly of a fixed family
// too, familyMesh below; collide meets a triangle mesh by its vertices or, in one input of two,
// as a surface: MeshContacts::kRegions), both argument orders, float and double. No crash,
// finite results, and distance and collide agree on the sign (where both take the vertices).
// docs/hardening.md → "Fuzzing".
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/tessellation.h"
#include "fuzz_input.h"
#include "shape_family.h"

namespace {

using fcl_superellipsoid::Superellipsoid;
using fcl_superellipsoid::TriangleMesh;
using fuzz::Vector3;

/// The mesh's vertices: a tessellated superellipsoid of 5–80 vertices or a point cloud of 1–80,
/// around `size`; empty if the superellipsoid was refused.
template <typename S>
TriangleMesh<S> meshFromBytes(FuzzedDataProvider& in, S size) {
  TriangleMesh<S> mesh;
  if (in.ConsumeBool()) {
    try {
      const Superellipsoid<S> other(
          size * fuzz::aroundOne<S>(in, 2), size * fuzz::aroundOne<S>(in, 2),
          size * fuzz::aroundOne<S>(in, 2), fuzz::anyExponent<S>(in), fuzz::anyExponent<S>(in));
      mesh = fcl_superellipsoid::tessellate(other, in.ConsumeIntegralInRange<int>(5, 80));
    } catch (const std::invalid_argument& e) {
      fuzz::requireNamedValue(e);
    }
  } else {  // a point cloud
    const int n = in.ConsumeIntegralInRange<int>(1, 80);
    for (int i = 0; i < n; ++i) {
      mesh.vertices.emplace_back(size * (S(2) - S(4) * in.ConsumeProbability<S>()),
                                 size * (S(2) - S(4) * in.ConsumeProbability<S>()),
                                 size * (S(2) - S(4) * in.ConsumeProbability<S>()));
    }
  }
  return mesh;
}

/// A BVH of the mesh in one of the 8 BV types.
template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> makeBVH(const TriangleMesh<S>& mesh, int bv) {
  using fcl_superellipsoid::makeBVHModel;
  switch (bv) {
    case 0:
      return makeBVHModel<fcl::AABB<S>>(mesh);
    case 1:
      return makeBVHModel<fcl::OBB<S>>(mesh);
    case 2:
      return makeBVHModel<fcl::RSS<S>>(mesh);
    case 3:
      return makeBVHModel<fcl::kIOS<S>>(mesh);
    case 4:
      return makeBVHModel<fcl::OBBRSS<S>>(mesh);
    case 5:
      return makeBVHModel<fcl::KDOP<S, 16>>(mesh);
    case 6:
      return makeBVHModel<fcl::KDOP<S, 18>>(mesh);
    default:
      return makeBVHModel<fcl::KDOP<S, 24>>(mesh);
  }
}

/// The meshes the query inputs draw from (as the shapes, shape_family.h): for each shape size,
/// 4 tessellated superellipsoids (5, 12, 40 and 80 vertices; box-like, round, sharp and a
/// needle) and 4 point clouds (1, 8, 30 and 80 points within ±2 sizes) in each of the 8 BV
/// types, built on first use and kept. A new mesh's BVH is built from the input's bytes in 1
/// input in 16.
constexpr int kFamilyMeshes = 8;
constexpr int kBVTypes = 8;

template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> familyMesh(S size, int variant, int bv) {
  static std::map<S,
                  std::array<std::shared_ptr<fcl::CollisionGeometry<S>>, kFamilyMeshes * kBVTypes>>
      family;
  std::shared_ptr<fcl::CollisionGeometry<S>>& model = family[size][variant * kBVTypes + bv];
  if (model) return model;
  TriangleMesh<S> mesh;
  if (variant < 4) {
    struct Tessellated {
      S a, b, c, e1, e2;
      int resolution;
    };
    const Tessellated t[] = {{S(1), S(0.7), S(0.4), S(0.3), S(1.7), 5},
                             {S(0.5), S(1), S(0.2), S(1), S(1), 12},
                             {S(1), S(1), S(1), S(0.1), S(0.1), 40},
                             {S(0.2), S(0.2), S(1), S(1.98), S(0.65), 80}};
    const Tessellated& v = t[variant];
    using Range = fcl_superellipsoid::NumericRange<S>;
    auto radius = [size](S r) {  // kept in the radius range at its ends
      return std::clamp(size * r, Range::kMinRadius * S(1.001), Range::kMaxRadius);
    };
    mesh = fcl_superellipsoid::tessellate(
        Superellipsoid<S>(radius(v.a), radius(v.b), radius(v.c), v.e1, v.e2), v.resolution);
  } else {
    const int counts[] = {1, 8, 30, 80};
    std::mt19937 rng{unsigned(variant)};
    std::uniform_real_distribution<double> u(-2, 2);
    for (int i = 0; i < counts[variant - 4]; ++i) {
      mesh.vertices.emplace_back(size * S(u(rng)), size * S(u(rng)), size * S(u(rng)));
    }
  }
  model = makeBVH(mesh, bv);
  return model;
}

template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> makeMesh(FuzzedDataProvider& in, S size) {
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {  // a new mesh
    const TriangleMesh<S> mesh = meshFromBytes(in, size);
    if (mesh.vertices.empty()) return nullptr;
    return makeBVH(mesh, in.ConsumeIntegralInRange<int>(0, kBVTypes - 1));
  }
  const int variant = in.ConsumeIntegralInRange<int>(0, kFamilyMeshes - 1);
  return familyMesh(size, variant, in.ConsumeIntegralInRange<int>(0, kBVTypes - 1));
}

/// A point within `reach` of the origin.
template <typename S>
Vector3<S> anyPoint(FuzzedDataProvider& in, S reach) {
  return reach * Vector3<S>(S(1) - S(2) * in.ConsumeProbability<S>(),
                            S(1) - S(2) * in.ConsumeProbability<S>(),
                            S(1) - S(2) * in.ConsumeProbability<S>());
}

/// One of FCL's shapes, sized around `size` (down to degenerate: FCL accepts zero lengths and
/// collinear triangles), or another superellipsoid of the family.
template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> makeShapePartner(FuzzedDataProvider& in, S size,
                                                            int kind) {
  auto length = [&] {
    return size * fuzz::aroundOne<S>(in, 4) * S(in.ConsumeIntegralInRange<int>(0, 3) > 0);
  };
  switch (kind) {
    case 0:
      return std::make_shared<fcl::Sphere<S>>(size * fuzz::aroundOne<S>(in, 4));
    case 1:  // another of the family (new shapes: fuzz_new_shape)
      return fuzz::familyShape<S>(in);
    case 2:
      return std::make_shared<fcl::Ellipsoid<S>>(size * fuzz::aroundOne<S>(in, 4),
                                                 size * fuzz::aroundOne<S>(in, 4),
                                                 size * fuzz::aroundOne<S>(in, 4));
    case 3:
    case 4: {
      Vector3<S> n = anyPoint<S>(in, S(1));
      if (!(n.norm() > S(1e-3))) n = Vector3<S>::UnitZ();
      const S d = size * (S(4) - S(8) * in.ConsumeProbability<S>());
      if (kind == 3) return std::make_shared<fcl::Halfspace<S>>(n, d);
      return std::make_shared<fcl::Plane<S>>(n, d);
    }
    case 5:
      return std::make_shared<fcl::Capsule<S>>(length(), length());
    case 6:
      return std::make_shared<fcl::Box<S>>(length(), length(), length());
    case 7:
      return std::make_shared<fcl::Cylinder<S>>(length(), length());
    case 8:
      return std::make_shared<fcl::Cone<S>>(length(), length());
    case 9: {  // a tetrahedron, faces oriented outward
      auto v = std::make_shared<std::vector<Vector3<S>>>();
      const S l = length();
      *v = {Vector3<S>(l, l, l), Vector3<S>(l, -l, -l), Vector3<S>(-l, l, -l),
            Vector3<S>(-l, -l, l)};
      for (auto& p : *v) p += anyPoint<S>(in, size / 4);
      auto faces = std::make_shared<std::vector<int>>(
          std::vector<int>{3, 0, 1, 2, 3, 0, 3, 1, 3, 0, 2, 3, 3, 1, 3, 2});
      return std::make_shared<fcl::Convex<S>>(v, 4, faces);
    }
    default: {  // sized like the others (down to degenerate, up to any scalar)
      const S reach = size * fuzz::aroundOne<S>(in, 4);
      return std::make_shared<fcl::TriangleP<S>>(anyPoint<S>(in, reach), anyPoint<S>(in, reach),
                                                 anyPoint<S>(in, reach));
    }
  }
}

template <typename S>
void run(FuzzedDataProvider& in) {
  std::shared_ptr<Superellipsoid<S>> shape = fuzz::familyShape<S>(in);
  const S size = shape->size();
  std::shared_ptr<fcl::CollisionGeometry<S>> partner;
  const int kind = in.ConsumeIntegralInRange<int>(0, 13);
  partner = kind <= 10 ? makeShapePartner<S>(in, size, kind) : makeMesh<S>(in, size);
  if (!partner) return;
  // A mesh met as a surface by collide (MeshContacts::kRegions) in one input of two: on a copy
  // of the family's shape, which the other inputs share.
  const bool regions = kind > 10 && in.ConsumeBool();
  if (regions) {
    shape = std::make_shared<Superellipsoid<S>>(*shape);
    shape->setMeshContacts(fcl_superellipsoid::MeshContacts::kRegions);
  }
  const fcl::CollisionObject<S> o_shape(shape, fuzz::makePose<S>(in, S(2) * size));
  const fcl::CollisionObject<S> o_partner(partner, fuzz::makePose<S>(in, S(3) * size));
  const bool shape_first = in.ConsumeBool();
  const auto* o1 = shape_first ? &o_shape : &o_partner;
  const auto* o2 = shape_first ? &o_partner : &o_shape;
  const bool through_fcl = in.ConsumeBool();  // FCL's call reads our table entries
  fcl::detail::GJKSolver_libccd<S> solver;

  fcl::DistanceRequest<S> request(in.ConsumeBool());
  request.enable_signed_distance = in.ConsumeBool();
  fcl::DistanceResult<S> distance;
  try {
    if (through_fcl) {
      fcl::distance(o1, o2, &solver, request, distance);
    } else {
      fcl_superellipsoid::distance(o1, o2, request, distance);
    }
  } catch (const std::invalid_argument& e) {
    // A partner shape with a parameter out of range (aroundOne sometimes draws any scalar):
    // refused, naming the value (docs/hardening.md → "Bad input").
    fuzz::requireNamedValue(e);
    return;
  }
  const S d = distance.min_distance;
  fuzz::require(std::isfinite(d), "distance not finite");
  if (request.enable_nearest_points) {
    fuzz::require(distance.nearest_points[0].allFinite() && distance.nearest_points[1].allFinite(),
                  "nearest points not finite");
  }

  fcl::CollisionRequest<S> crequest(std::size_t(in.ConsumeIntegralInRange<int>(1, 8)),
                                    in.ConsumeBool());
  fcl::CollisionResult<S> collision;
  if (through_fcl) {  // (the partner passed distance's check: collide may not throw)
    fcl::collide(o1, o2, &solver, crequest, collision);
  } else {
    fcl_superellipsoid::collide(o1, o2, crequest, collision);
  }
  for (std::size_t k = 0; k < collision.numContacts(); ++k) {
    const fcl::Contact<S>& c = collision.getContact(k);
    fuzz::require(c.pos.allFinite() && c.normal.allFinite() && std::isfinite(c.penetration_depth),
                  "contact not finite");
    if (crequest.enable_contact) {
      fuzz::require(c.penetration_depth >= S(0), "negative penetration depth");
      fuzz::require(std::abs(c.normal.norm() - S(1)) <= S(1e-3), "contact normal not unit");
    }
  }
  // The sign: unsigned distance is −1 on penetration (FCL's convention). A band of the solver's
  // tolerance around contact is left out, where both answers are right. A mesh met as a surface
  // by collide is met by its vertices by distance: no common sign.
  const S band = (sizeof(S) == 4 ? S(1e-4) : S(1e-9)) * size * S(16);
  const bool penetrating = request.enable_signed_distance ? d < S(0) : d == S(-1);
  if (!regions && std::abs(d) > band) {
    fuzz::require(penetrating == collision.isCollision(), [&] {
      return "distance " + std::to_string(double(d)) + " but collide says " +
             std::to_string(collision.isCollision());
    });
  }
}

}  // namespace

FSE_FUZZ_FLOAT_AND_DOUBLE(run)
