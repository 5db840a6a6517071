#include "contact/rigid_mesh_contact.h"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_superellipsoid/tessellation.h>

#include <cmath>

namespace fse_sim {

namespace fse = fcl_superellipsoid;

namespace {

/// Each triangle's unit normal, turned away from `inside` (a point of the solid the mesh bounds:
/// a body's centre) when `inside` is given; otherwise as wound.
Eigen::Matrix3Xd faceNormals(const fse::TriangleMesh<double>& mesh, const Eigen::Vector3d* inside) {
  Eigen::Matrix3Xd normals(3, long(mesh.triangles.size()));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const fcl::Triangle& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.vertices[tri[0]];
    const Eigen::Vector3d& b = mesh.vertices[tri[1]];
    const Eigen::Vector3d& c = mesh.vertices[tri[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double length = n.norm();
    n = length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
    if (inside != nullptr && n.dot((a + b + c) / 3 - *inside) < 0) n = -n;
    normals.col(long(t)) = n;
  }
  return normals;
}

}  // namespace

RigidMeshContact::RigidMeshContact(const std::vector<RigidBody>& bodies, const StaticMesh* bowl,
                                   int mesh_vertices) {
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the body frame's origin
  for (const RigidBody& body : bodies) {
    const fse::TriangleMesh<double> mesh = fse::tessellate(*body.shape, mesh_vertices);
    bodies_.push_back({fse::makeBVHModel<fcl::OBBRSSd>(mesh), faceNormals(mesh, &centre)});
  }
  if (bowl != nullptr) {
    fse::TriangleMesh<double> mesh;
    for (Eigen::Index v = 0; v < bowl->vertices.cols(); ++v) {
      mesh.vertices.push_back(bowl->vertices.col(v));
    }
    for (const auto& t : bowl->triangles) mesh.triangles.emplace_back(t[0], t[1], t[2]);
    bowl_ = {fse::makeBVHModel<fcl::OBBRSSd>(mesh), bowl->normals};  // outward, as wound
  }
}

void RigidMeshContact::contacts(const std::vector<RigidBody>& bodies, int i, int j, double margin,
                                std::vector<RigidContact>& out) const {
  const RigidBody& a = bodies[std::size_t(i)];
  const RigidBody* b = j >= 0 ? &bodies[std::size_t(j)] : nullptr;
  const Mesh& mesh_a = bodies_[std::size_t(i)];
  const Mesh& mesh_b = b != nullptr ? bodies_[std::size_t(j)] : bowl_;
  const fcl::Transform3d X_a = a.transform();
  const fcl::Transform3d X_b = b != nullptr ? b->transform() : fcl::Transform3d::Identity();
  const Eigen::Matrix3d R_a = X_a.linear(), R_b = X_b.linear();
  fcl::CollisionRequestd request(kMaxContactsPerPair, true);
  fcl::CollisionResultd result;
  fcl::collide(mesh_a.bvh.get(), X_a, mesh_b.bvh.get(), X_b, request, result);
  if (result.numContacts() > 0) {
    for (std::size_t k = 0; k < result.numContacts(); ++k) {
      const fcl::Contactd& contact = result.getContact(k);
      // FCL's normal is one of the two triangles' (its sign is not a convention): a moves away
      // from its own face (−n_a) or along the other's outward normal (+n_b).
      const Eigen::Vector3d n_a = R_a * mesh_a.normals.col(contact.b1);
      const Eigen::Vector3d n_b = R_b * mesh_b.normals.col(contact.b2);
      const double along_a = std::abs(contact.normal.dot(n_a));
      const double along_b = std::abs(contact.normal.dot(n_b));
      const Eigen::Vector3d n = along_a > along_b ? Eigen::Vector3d(-n_a) : n_b;
      const double depth = contact.penetration_depth;
      out.push_back(contactAt(a, i, b, j, -depth, contact.pos - 0.5 * depth * n,
                              contact.pos + 0.5 * depth * n, n));
    }
    return;
  }
  fcl::DistanceRequestd distance_request(true);  // nearest points (world frame)
  fcl::DistanceResultd distance_result;
  const double d = fcl::distance(mesh_a.bvh.get(), X_a, mesh_b.bvh.get(), X_b, distance_request,
                                 distance_result);
  if (!(d <= margin)) return;
  const Eigen::Vector3d& w_a = distance_result.nearest_points[0];
  const Eigen::Vector3d& w_b = distance_result.nearest_points[1];
  const Eigen::Vector3d gap = w_a - w_b;
  const double length = gap.norm();
  // Touching (no gap to take a direction from): away from a's nearest triangle.
  const Eigen::Vector3d n = length > 1e-12
                                ? Eigen::Vector3d(gap / length)
                                : Eigen::Vector3d(-(R_a * mesh_a.normals.col(distance_result.b1)));
  out.push_back(contactAt(a, i, b, j, d, w_a, w_b, n));
}

}  // namespace fse_sim
