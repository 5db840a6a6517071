#ifndef FSE_SIM_CONTACT_RIGID_MESH_CONTACT_H
#define FSE_SIM_CONTACT_RIGID_MESH_CONTACT_H

// The rigid bodies' `mesh` contact model: what an FCL user without this library would do. Every
// body is its tessellation (the scene's mesh_vertices) as an FCL BVH (OBBRSS), the bowl its
// triangles as another, and each pair the broad phase passes goes to FCL's mesh–mesh queries
// (docs/scenes.md → "Contact models"):
//   overlapping  fcl::collide with contacts: a point, a normal and a depth per intersecting
//                triangle pair (FCL's triangle–triangle test; the normal is one of the two
//                triangles' and is turned to point the way body a separates);
//   apart        fcl::distance with nearest points: one contact at the nearest pair, when it is
//                within the margin (FCL's mesh collision has no margin, so bodies about to touch
//                are seen this way).

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <memory>
#include <vector>

#include "contact/rigid_contact.h"
#include "model/rigid_body.h"
#include "model/static_mesh.h"

namespace fse_sim {

class RigidMeshContact {
 public:
  /// Tessellates every body with `mesh_vertices` vertices; `bowl` may be null.
  RigidMeshContact(const std::vector<RigidBody>& bodies, const StaticMesh* bowl, int mesh_vertices);

  /// The contacts between bodies i and j (b = j), or between body i and the bowl (j = −1),
  /// within `margin`, appended to `out`. Safe to call from several threads at once.
  void contacts(const std::vector<RigidBody>& bodies, int i, int j, double margin,
                std::vector<RigidContact>& out) const;

  /// The most contacts FCL reports for one pair (it stops looking there).
  static constexpr int kMaxContactsPerPair = 256;

 private:
  struct Mesh {
    std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> bvh;
    Eigen::Matrix3Xd normals;  ///< per triangle, outward, the mesh's frame
  };
  std::vector<Mesh> bodies_;
  Mesh bowl_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_CONTACT_RIGID_MESH_CONTACT_H
