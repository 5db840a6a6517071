#ifndef FSE_SIM_CONTACT_RIGID_CONTACT_H
#define FSE_SIM_CONTACT_RIGID_CONTACT_H

// Collision detection of a rigid-body scene: the contacts between the bodies, and between each
// body and the fixed bowl, for one step (docs/scenes.md → "Contact models"). Body pairs whose
// bounding spheres and bounding boxes come within the margin go to the run's contact model:
//   exact     the library's superellipsoid–superellipsoid pair (its signed distance, along the
//             normal whose gap equals it) and its contact region (fse::contactManifold), whose
//             places the pair keeps from step to step (contact/persistent_places.h), and a
//             support contact along the normal for while a body turns fast (turning_only);
//   vertices  each body's tessellation vertices against the other's implicit surface, both
//             ways, through the library's batched queries with the Exact solver (the paper's
//             model: one contact per vertex within the margin);
//   paper     the same with the paper's method at its case-study settings;
//   mesh      every body its tessellation, through FCL's mesh–mesh collision and distance, the
//             bowl included (contact/rigid_mesh_contact.h): what an FCL user would do.
// Against the bowl the library's models do the same, so that a body can neither pass between
// bowl vertices nor through a triangle: per nearby face, the body's support point along the
// face's normal where its foot lies on the face (for the exact model, within the margin of it);
// at a convex (rim) triangle the library's
// superellipsoid–triangle pair; the rim's vertices against the body's implicit surface.
// Pairs are examined in parallel; the contacts come out in the same order for any thread count.

#include <fcl/geometry/shape/triangle_p.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "model/rigid_body.h"
#include "model/scene.h"
#include "model/static_mesh.h"

namespace fse_sim {

/// The skin: the solver holds resting contacts this share of the tolerance apart rather than
/// exactly touching (physics/rigid_contact_solver.h); the exact model's regions reach across it.
constexpr double kRigidSkinPerTolerance = 0.01;

/// A contact for one step: body a's point r_a (a's frame) and the point r_b on b (b's frame;
/// the world for the bowl); a separates from b by moving along +n. Their separation
/// (p_a − p_b)·n is the signed distance at detection and is kept ≥ 0 by the solver.
struct RigidContact {
  int a = 0;
  int b = -1;  ///< −1: the bowl
  Eigen::Vector3d r_a{0, 0, 0}, r_b{0, 0, 0};
  Eigen::Vector3d n{0, 0, 1};
  double distance = 0;  ///< signed, m, at detection
  /// A support contact: r_a is a's support point along −n and r_b b's along +n (moved by
  /// support_offset along n), or for the bowl the foot of r_a on the face's plane, taken again
  /// at the poses of every substep (followSupport) rather than kept from detection: a body that
  /// turns during the step brings another point lowest (a spinning, pointy body another tip),
  /// and the constraint must hold that one off. Along a fixed n, a's extent staying short of
  /// b's (or of the plane) is what keeps them apart.
  bool follows_support = false;
  double support_offset = 0;  ///< m
  /// A support contact that holds the pair only while one of its bodies turns fast enough to
  /// bring another point lowest within the step; otherwise the region's places (kept as
  /// material points) hold it, and the step drops this one.
  bool turning_only = false;
  /// m, ≥ 0: the solver holds the separation less this (a persistent place's offset: how far
  /// it stood beyond the pair's distance when it was born; contact/persistent_places.h).
  double offset = 0;
  /// A persistent place: its two points were over each other along n when it was born, and
  /// static friction holds them so (not only their slip within a substep).
  bool anchored = false;
};

/// The contact of body a (index ia) with body b (index ib; b null and ib = −1: the bowl) from
/// world points w_a on a and w_b on b at signed distance d, a separating along n.
RigidContact contactAt(const RigidBody& a, int ia, const RigidBody* b, int ib, double d,
                       const Eigen::Vector3d& w_a, const Eigen::Vector3d& w_b,
                       const Eigen::Vector3d& n);

/// A support contact's points at the bodies' current poses (RigidContact::follows_support).
void followSupport(const std::vector<RigidBody>& bodies, RigidContact& c);

class RigidContactFinder {
 public:
  /// `bodies` as built (their shapes and, for the vertex models, tessellations); `bowl` may be
  /// null. The model is one of exact, vertices, paper, mesh.
  RigidContactFinder(const std::vector<RigidBody>& bodies, const StaticMesh* bowl,
                     ContactModel model, int mesh_vertices, int threads);
  ~RigidContactFinder();

  /// Replaces `out` with every contact whose signed distance is ≤ tolerance + the travel of the
  /// bodies involved (travel[i]: how far a point of body i can move before the next detection).
  void find(const std::vector<RigidBody>& bodies, double tolerance,
            const std::vector<double>& travel, std::vector<RigidContact>& out);

  /// The least signed distance between any two bodies and between any body and the bowl,
  /// measured on the exact surfaces (pairs, and bowl vertices and triangles), whatever the
  /// model; +∞ when nothing is within `reach`.
  double leastDistance(const std::vector<RigidBody>& bodies, double reach);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_CONTACT_RIGID_CONTACT_H
