#ifndef FSE_SIM_PHYSICS_RIGID_CONTACT_SOLVER_H
#define FSE_SIM_PHYSICS_RIGID_CONTACT_SOLVER_H

// The `rigid_contact` effect (with `friction` and `restitution`, which act at its contacts):
// positional contacts between rigid bodies as in Müller et al. 2020 ("Detailed rigid body
// simulation with extended position based dynamics"), §3.5–3.6.
//
// The contacts of a step (contact/rigid_contact.h) keep their points in the bodies' frames, so
// in every substep their separation is evaluated at the bodies' current poses. Friction acts
// per patch: a pair's contacts whose normals lie within kGroupAngle of each other (a face on a
// face, a body on one of the bowl's faces), at the patch's centre of pressure (the middle of
// its contacts weighted by their normal impulses) with the sum of their normal impulses.
//   position pass  a contact whose points are closer than a skin, less its offset (d =
//                  (p_b − p_a)·n + offset + skin > 0), is resolved by a positional impulse
//                  Δλ·n, Δλ = d / (w_a + w_b) with the generalised inverse masses (α = 0: a
//                  hard contact). A contact pushes at most what its points closed in by during
//                  the substep plus kMaxDepenetrationSpeed·h: an overlap a fast impact left
//                  behind is undone over several substeps, not in one push that the velocity
//                  update would turn into an explosion. After each patch's pushes, static
//                  friction: the slip of the substep at the patch's centre is undone while that
//                  takes less than μs times the patch's normal impulse, and then at each of its
//                  contacts against its own. An anchored contact, a persistent place, undoes how
//                  far its two points lie apart along the contact plane (so that a resting
//                  body's residue of one substep does not add up to a creep), against the
//                  patch's bound: Coulomb's law holds for the face as a whole, however the
//                  sweeps share its normal impulse among its places;
//   velocity pass  kVelocityIterations sweeps over the contacts resolved in the position pass:
//                  the normal velocity is set to −e times the one before the substep at the
//                  contact of each pair that closed in fastest, to 0 at the others before it
//                  (and everywhere below 2|g|h, so that resting bodies do not jitter; in a
//                  face's impact the later sweeps' resets take part of the bounce back); then
//                  at each patch's centre dynamic friction, the sweeps' impulses together at
//                  most μd·λn/h (the Coulomb bound: the normal force is λn/h²), or what stops
//                  the sliding there.
// The skin (1 % of the tolerance) holds resting bodies just apart rather than exactly touching:
// their next detection then finds them separated, where the library's pair is a single Newton
// run instead of the overlapping case's multi-start search, at a cost in accuracy far below
// the tolerance.

#include <vector>

#include "contact/rigid_contact.h"
#include "model/rigid_body.h"
#include "model/scene.h"

namespace fse_sim {

class RigidContactSolver {
 public:
  /// Gauss–Seidel sweeps of the position pass per substep: one sweep leaves the contacts of a
  /// body resting on a face fighting (a correction at one corner tips the body onto the
  /// opposite one), which rocks it and inflates the normal impulses friction is measured by.
  /// (Six or eight stilled the bowl's last jittering body, but not the small bowl's bodies of
  /// the tests: docs/scenes.md → "Limitations (rigid bodies)".)
  static constexpr int kPositionIterations = 4;
  /// Sweeps of the velocity pass: one leaves a stack's friction and normal velocities fighting
  /// (friction at a face's centre turns the body, which its other contacts' normal velocities
  /// would undo), and the residue walks the stack along (1.3 mm in 5 s for five bodies, against
  /// 8e-7 m with four sweeps).
  static constexpr int kVelocityIterations = 4;

  explicit RigidContactSolver(const Scene& scene);

  /// Starts a substep: the contacts' normal velocities before it (for restitution).
  void begin(const std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts);
  /// The position pass of one substep of length h (after begin()).
  void projectPositions(std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                        double h);
  /// The velocity pass (friction, restitution) of the contacts the position pass resolved.
  void solveVelocities(std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                       double h);
  /// Contacts resolved in the last position pass.
  int activeCount() const { return int(active_.size()); }

 private:
  double mu_static_ = 0, mu_dynamic_ = 0;
  bool friction_ = false;
  double restitution_ = 0;
  double gravity_ = 0;             ///< |g|
  double skin_ = 0;                ///< m
  std::vector<double> vn_before_;  ///< per contact
  std::vector<int> active_;        ///< contacts resolved in the position pass
  std::vector<double> lambda_n_;   ///< per contact: its normal impulse this substep (N·s²)
  static constexpr double kMaxDepenetrationSpeed = 1.0;  ///< m/s
  std::vector<double> budget_, pushed_;  ///< per contact: how far it may push, and has (m)

  static constexpr double kGroupAngle = 0.35;  ///< rad (the file's comment)
  struct Group {
    std::vector<int> members;  ///< contact indices, of one pair
  };
  /// A group's active contacts as one: the centre of pressure on each body (the λn-weighted
  /// middle of its contact points), the λn-weighted normal (a separates along it; a, b: the
  /// group's first contact's), and the sum of their normal impulses (0: none active).
  struct Patch {
    int a = 0, b = -1;
    Eigen::Vector3d on_a{0, 0, 0}, on_b{0, 0, 0}, n{0, 0, 1};
    double lambda = 0;
  };
  std::vector<Group> groups_;
  std::vector<Eigen::Vector3d> friction_impulse_;  ///< per group, this velocity pass

  void groupContacts(const std::vector<RigidContact>& contacts);
  Patch patchOf(const std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                const Group& group) const;
  /// Returns the patch's normal impulse.
  double holdPatch(std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                   const Group& group) const;
  void holdPlace(std::vector<RigidBody>& bodies, const RigidContact& c, double lambda_n) const;
  void slidePatch(std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                  const Group& group, double h, Eigen::Vector3d& applied) const;
  /// One contact's normal velocity to max(bounce, 0).
  void solveNormalVelocity(std::vector<RigidBody>& bodies, const RigidContact& c,
                           double bounce) const;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_RIGID_CONTACT_SOLVER_H
