// The FCL example of docs/usage.md: a superellipsoid, a cloth mesh and a point cloud in a
// broadphase manager; contacts and distance through the library's callbacks. Checks its own answers
// against brute force over the vertices and exits non-zero if they disagree.
#include <fcl/fcl.h>
#include <fcl_superellipsoid/fcl_integration.h>
#include <fcl_superellipsoid/point_distance.h>
#include <fcl_superellipsoid/tessellation.h>

#include <cstdio>

namespace fse = fcl_superellipsoid;

int main() {
  // A rounded box, a thin cloth-like sheet above it, and a cloud of 1,000 points below it.
  auto shape = std::make_shared<fse::Superellipsoidd>(1.0, 0.8, 0.6, 0.3, 0.3);
  const fse::TriangleMesh<double> cloth_mesh =
      fse::tessellate(fse::Superellipsoidd(2, 2, 0.02, 1, 0.1), 400);
  fse::TriangleMesh<double> cloud_mesh;
  for (int i = 0; i < 1000; ++i) {  // a 10 × 10 × 10 grid, spacing 0.1
    cloud_mesh.vertices.emplace_back(0.1 * (i % 10) - 0.45, 0.1 * (i / 10 % 10) - 0.45,
                                     0.1 * (i / 100));
  }
  auto cloth = fse::makeBVHModel<fcl::OBBRSSd>(cloth_mesh);
  auto cloud = fse::makeBVHModel<fcl::OBBRSSd>(cloud_mesh);

  fcl::CollisionObjectd o_shape(shape);
  fcl::CollisionObjectd o_cloth(cloth, fcl::Transform3d(fcl::Translation3d(0, 0, 0.58)));
  fcl::CollisionObjectd o_cloud(cloud, fcl::Transform3d(fcl::Translation3d(0, 0, -1.8)));
  fcl::DynamicAABBTreeCollisionManagerd manager;
  manager.registerObjects({&o_shape, &o_cloth, &o_cloud});
  manager.setup();

  // Contacts: one per penetrating vertex (the cloth sags into the shape's top face).
  fcl::DefaultCollisionData<double> contacts;
  contacts.request.num_max_contacts = 100000;
  contacts.request.enable_contact = true;
  manager.collide(&contacts, fse::defaultCollisionFunction<double>);
  double deepest = 0;
  for (std::size_t k = 0; k < contacts.result.numContacts(); ++k) {
    deepest = std::max(deepest, contacts.result.getContact(k).penetration_depth);
  }
  std::printf("contacts: %zu, deepest %.9f\n", contacts.result.numContacts(), deepest);

  // Distance from the shape to the point cloud below it (signed, nearest points in world).
  fcl::DistanceResultd result;
  fse::distance(&o_shape, &o_cloud, fcl::DistanceRequestd(true, true), result);
  std::printf("distance to the cloud: %.9f at vertex %d, (%.3f, %.3f, %.3f)\n", result.min_distance,
              result.b2, result.nearest_points[1].x(), result.nearest_points[1].y(),
              result.nearest_points[1].z());

  // The same through FCL's own call with its solver (FCL's order: the mesh comes first).
  fcl::detail::GJKSolver_libccd<double> solver;
  fcl::DistanceResultd fcl_result;
  fcl::distance(&o_shape, &o_cloud, &solver, fcl::DistanceRequestd(true, true), fcl_result);
  std::printf("through fcl::distance with the solver: %.9f\n", fcl_result.min_distance);

  // Brute force over the vertices, for the check.
  std::size_t inside = 0;
  double max_depth = 0, cloud_distance = 1e300;
  for (const auto& v : cloth_mesh.vertices) {
    const double d = fse::pointDistance(*shape, o_cloth.getTransform() * v).distance;
    if (d < 0) ++inside, max_depth = std::max(max_depth, -d);
  }
  for (const auto& v : cloud_mesh.vertices) {
    cloud_distance =
        std::min(cloud_distance, fse::pointDistance(*shape, o_cloud.getTransform() * v).distance);
  }
  const bool ok = inside > 0 && contacts.result.numContacts() == inside &&
                  std::abs(deepest - max_depth) < 1e-12 &&
                  std::abs(result.min_distance - cloud_distance) < 1e-12 &&
                  std::abs(fcl_result.min_distance - cloud_distance) < 1e-12;
  std::printf("brute force: %zu contacts, deepest %.9f, distance %.9f: %s\n", inside, max_depth,
              cloud_distance, ok ? "agree" : "DISAGREE");
  return ok ? 0 : 1;
}
