// What an FCL user would do: a tessellated mesh (FCL's BVH traversal, the paper's baseline),
// GJK against the tessellation's convex hull or FCL's own Ellipsoid, and our front end.
// Each is queried the fastest fair way: FCL's geometry + pose call against a zero-radius
// sphere at the point, nearest points requested (every method here returns one).

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/tessellation.h"
#include "methods.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

/// A query against a zero-radius sphere at x, through `distance_fn` (plain FCL or our front
/// end). The shape under test sits at the origin with the identity pose, so FCL's world
/// frame is the shape's frame and nearest_points[0] is directly comparable.
template <typename DistanceFn>
Answer querySphere(const fcl::CollisionGeometryd* geometry, const fcl::Sphered& point,
                   bool is_signed, const Vector3<double>& x, DistanceFn distance_fn) {
  fcl::DistanceRequestd request(true);  // nearest points
  request.enable_signed_distance = is_signed;
  fcl::DistanceResultd result;
  fcl::Transform3d at_x = fcl::Transform3d::Identity();
  at_x.translation() = x;
  distance_fn(geometry, fcl::Transform3d::Identity(), &point, at_x, request, result);
  return {result.min_distance, result.nearest_points[0], -1};
}

double plainFcl(const fcl::CollisionGeometryd* o1, const fcl::Transform3d& tf1,
                const fcl::CollisionGeometryd* o2, const fcl::Transform3d& tf2,
                const fcl::DistanceRequestd& request, fcl::DistanceResultd& result) {
  return fcl::distance(o1, tf1, o2, tf2, request, result);
}

double frontEnd(const fcl::CollisionGeometryd* o1, const fcl::Transform3d& tf1,
                const fcl::CollisionGeometryd* o2, const fcl::Transform3d& tf2,
                const fcl::DistanceRequestd& request, fcl::DistanceResultd& result) {
  return fcl_superellipsoid::distance(o1, tf1, o2, tf2, request, result);
}

std::string verticesText(int n) {
  return n >= 1000 && n % 1000 == 0 ? std::to_string(n / 1000) + "k v" : std::to_string(n) + " v";
}

/// FCL's BVH mesh against a point: unsigned (FCL signs only primitive shape pairs; a point
/// inside the mesh gets its distance to the nearest triangle).
class FclMeshMethod final : public Method {
 public:
  FclMeshMethod(int vertices, std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model)
      : Method(kFclMesh, verticesText(vertices), vertices, false, bytes(*model)),
        model_(std::move(model)),
        point_(0) {}

  Answer query(const Vector3<double>& x) const override {
    return querySphere(model_.get(), point_, false, x, plainFcl);
  }

 private:
  // BVHModel::memUsage() prints but returns BVH_OK, not the size; count it here.
  static std::size_t bytes(const fcl::BVHModel<fcl::OBBRSSd>& m) {
    return sizeof(m) + sizeof(fcl::BVNode<fcl::OBBRSSd>) * m.getNumBVs() +
           (sizeof(fcl::Triangle) + sizeof(unsigned int)) * m.num_tris +  // + primitive indices
           sizeof(fcl::Vector3d) * m.num_vertices;
  }
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model_;
  fcl::Sphered point_;
};

/// GJK (libccd, FCL's default solver and tolerance) against a convex polytope: signed.
class FclShapeMethod final : public Method {
 public:
  FclShapeMethod(const char* family, std::string setting, double setting_value,
                 std::shared_ptr<fcl::CollisionGeometryd> geometry, std::size_t memory)
      : Method(family, std::move(setting), setting_value, true, memory),
        geometry_(std::move(geometry)),
        point_(0) {}

  Answer query(const Vector3<double>& x) const override {
    return querySphere(geometry_.get(), point_, true, x, plainFcl);
  }

 private:
  std::shared_ptr<fcl::CollisionGeometryd> geometry_;
  fcl::Sphered point_;
};

/// Our front end: the superellipsoid–sphere pair, answered by the Exact solver.
class FrontEndMethod final : public Method {
 public:
  explicit FrontEndMethod(const BenchShape& shape)
      : Method(kFrontEnd, "sphere r=0", NAN, true, 5 * sizeof(double)),
        shape_(std::make_shared<Superellipsoidd>(shape.make())),
        point_(0) {}

  Answer query(const Vector3<double>& x) const override {
    return querySphere(shape_.get(), point_, true, x, frontEnd);
  }

 private:
  std::shared_ptr<Superellipsoidd> shape_;
  fcl::Sphered point_;
};

}  // namespace

std::unique_ptr<Method> makeFclMeshMethod(const BenchShape& shape, int vertices) {
  const TriangleMesh<double> mesh = tessellate(shape.make(), vertices);
  return std::make_unique<FclMeshMethod>(vertices, makeBVHModel<fcl::OBBRSSd>(mesh));
}

std::unique_ptr<Method> makeFclConvexMethod(const BenchShape& shape, int vertices) {
  const TriangleMesh<double> mesh = tessellate(shape.make(), vertices);
  auto points = std::make_shared<std::vector<fcl::Vector3d>>(mesh.vertices);
  auto faces = std::make_shared<std::vector<int>>();
  for (const fcl::Triangle& t : mesh.triangles) {
    faces->insert(faces->end(), {3, int(t[0]), int(t[1]), int(t[2])});
  }
  const std::size_t bytes =
      sizeof(fcl::Convexd) + sizeof(fcl::Vector3d) * points->size() + sizeof(int) * faces->size();
  auto convex =
      std::make_shared<fcl::Convexd>(points, static_cast<int>(mesh.triangles.size()), faces);
  return std::make_unique<FclShapeMethod>(kFclConvex, verticesText(vertices), vertices, convex,
                                          bytes);
}

std::unique_ptr<Method> makeFclEllipsoidMethod(const BenchShape& shape) {
  auto ellipsoid = std::make_shared<fcl::Ellipsoidd>(shape.radii);
  return std::make_unique<FclShapeMethod>(kFclEllipsoid, "", NAN, ellipsoid, 3 * sizeof(double));
}

std::unique_ptr<Method> makeFrontEndMethod(const BenchShape& shape) {
  return std::make_unique<FrontEndMethod>(shape);
}

}  // namespace bench
}  // namespace fcl_superellipsoid
