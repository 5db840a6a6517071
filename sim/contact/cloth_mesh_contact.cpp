// The `mesh` contact model: what an FCL user without this library would do. The
// superellipsoid is tessellated (702 vertices by default, the paper's display mesh) into an
// FCL BVH (OBBRSS); each cloth vertex near the mesh's bounding box asks FCL for its distance
// to the mesh (a zero-radius sphere against the BVH: nearest point and triangle). FCL's
// mesh distance is unsigned (a point inside gets its distance to the nearest triangle), so
// the sign comes from the angle-weighted pseudonormal at the nearest point (Bærentzen and
// Aanæs 2005): the normal of the face, of the edge (sum of its two faces' normals) or of the
// vertex (its faces' normals weighted by their angles there), whichever feature holds the
// nearest point. For a closed mesh, (x − p)·pseudonormal > 0 exactly when x is outside.

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_superellipsoid/tessellation.h>

#include <cmath>
#include <map>

#include "contact/cloth_contact.h"

namespace fse_sim {

namespace fse = fcl_superellipsoid;

namespace {

class MeshContact final : public ContactDetector {
 public:
  MeshContact(const ShapeSpec& spec, int index, const SimulationOptions& options)
      : index_(index), pose_(shapePose(spec)), point_(0) {
    mesh_ = fse::tessellate(makeShape(spec), options.mesh_vertices);
    model_ = fse::makeBVHModel<fcl::OBBRSSd>(mesh_);
    box_min_ = box_max_ = mesh_.vertices[0];
    for (const auto& v : mesh_.vertices) {
      box_min_ = box_min_.cwiseMin(v);
      box_max_ = box_max_.cwiseMax(v);
    }
    computePseudonormals();
  }

  void detect(const Eigen::Matrix3Xd& x, double margin,
              std::vector<ContactCandidate>& out) override {
    const Eigen::Matrix3d R = pose_.linear();
    const Eigen::Vector3d t = pose_.translation();
    const fcl::Transform3d identity = fcl::Transform3d::Identity();
    fcl::DistanceRequestd request(true);  // nearest points
    for (Eigen::Index v = 0; v < x.cols(); ++v) {
      const Eigen::Vector3d q = R.transpose() * (x.col(v) - t);  // shape frame
      const Eigen::Vector3d outside =
          (q - box_max_).cwiseMax(box_min_ - q).cwiseMax(Eigen::Vector3d::Zero());
      if (outside.squaredNorm() > margin * margin) continue;
      fcl::Transform3d at_q = identity;
      at_q.translation() = q;
      fcl::DistanceResultd result;
      fcl::distance(model_.get(), identity, &point_, at_q, request, result);
      const int triangle = result.b1;
      if (triangle < 0 || triangle >= int(mesh_.triangles.size())) continue;
      const Eigen::Vector3d p = result.min_distance > 0 ? result.nearest_points[0] : q;
      const Eigen::Vector3d pn = pseudonormal(triangle, p);
      const double unsigned_distance = std::max(0.0, result.min_distance);
      const double sign = (q - p).dot(pn) >= 0 ? 1.0 : -1.0;
      const double d = sign * unsigned_distance;
      if (d > margin) continue;
      Eigen::Vector3d n = unsigned_distance > 1e-12 * (box_max_ - box_min_).norm()
                              ? Eigen::Vector3d(sign * (q - p) / unsigned_distance)
                              : pn;
      out.push_back({int(v), index_, d, pose_ * p, R * n});
    }
  }

 private:
  // The face, edge or vertex pseudonormal at p, a point of triangle `t`.
  Eigen::Vector3d pseudonormal(int t, const Eigen::Vector3d& p) const {
    const fcl::Triangle& tri = mesh_.triangles[t];
    const Eigen::Vector3d a = mesh_.vertices[tri[0]], b = mesh_.vertices[tri[1]],
                          c = mesh_.vertices[tri[2]];
    // Barycentric coordinates of p.
    const Eigen::Vector3d v0 = b - a, v1 = c - a, v2 = p - a;
    const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0),
                 d21 = v2.dot(v1);
    const double denom = d00 * d11 - d01 * d01;
    const double beta = (d11 * d20 - d01 * d21) / denom, gamma = (d00 * d21 - d01 * d20) / denom;
    const double bary[3] = {1 - beta - gamma, beta, gamma};
    constexpr double kOn = 1e-9;  // a coordinate this small puts p on the opposite feature
    int zero = 0, nonzero[3], nonzero_count = 0;
    for (int k = 0; k < 3; ++k) {
      if (bary[k] <= kOn) {
        ++zero;
      } else {
        nonzero[nonzero_count++] = k;
      }
    }
    if (zero == 2) return vertex_normal_[tri[nonzero[0]]];
    if (zero == 1) {
      const int u = int(tri[nonzero[0]]), w = int(tri[nonzero[1]]);
      return edge_normal_.at({std::min(u, w), std::max(u, w)});
    }
    return face_normal_[t];
  }

  void computePseudonormals() {
    face_normal_.resize(mesh_.triangles.size());
    vertex_normal_.assign(mesh_.vertices.size(), Eigen::Vector3d::Zero());
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      const fcl::Triangle& tri = mesh_.triangles[t];
      const Eigen::Vector3d n = (mesh_.vertices[tri[1]] - mesh_.vertices[tri[0]])
                                    .cross(mesh_.vertices[tri[2]] - mesh_.vertices[tri[0]])
                                    .normalized();
      face_normal_[t] = n;
      for (int k = 0; k < 3; ++k) {
        const int u = int(tri[k]), v = int(tri[(k + 1) % 3]), w = int(tri[(k + 2) % 3]);
        const Eigen::Vector3d e1 = (mesh_.vertices[v] - mesh_.vertices[u]).normalized();
        const Eigen::Vector3d e2 = (mesh_.vertices[w] - mesh_.vertices[u]).normalized();
        vertex_normal_[u] += std::acos(std::clamp(e1.dot(e2), -1.0, 1.0)) * n;
        edge_normal_
            .try_emplace(std::make_pair(std::min(u, v), std::max(u, v)), Eigen::Vector3d::Zero())
            .first->second += n;
      }
    }
    for (auto& n : vertex_normal_) n.normalize();
    for (auto& [edge, n] : edge_normal_) n.normalize();
  }

  int index_;
  Eigen::Isometry3d pose_;
  fse::TriangleMesh<double> mesh_;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model_;
  fcl::Sphered point_;
  Eigen::Vector3d box_min_, box_max_;
  std::vector<Eigen::Vector3d> face_normal_, vertex_normal_;
  std::map<std::pair<int, int>, Eigen::Vector3d> edge_normal_;
};

}  // namespace

std::unique_ptr<ContactDetector> makeMeshContact(const ShapeSpec& spec, int index,
                                                 const SimulationOptions& options) {
  return std::make_unique<MeshContact>(spec, index, options);
}

}  // namespace fse_sim
