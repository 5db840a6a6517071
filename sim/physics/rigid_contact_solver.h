#ifndef FSE_SIM_PHYSICS_RIGID_CONTACT_SOLVER_H
#define FSE_SIM_PHYSICS_RIGID_CONTACT_SOLVER_H

// The `rigid_contact` effect (with `friction` and `restitution`, which act at its contacts):
// positional contacts between rigid bodies as in Müller et al. 2020 ("Detailed rigid body
// simulation with extended position based dynamics"), §3.5–3.6.
//
// The contacts of a step (contact/rigid_contact.h) keep their points in the bodies' frames, so
// in every substep their separation is evaluated at the bodies' current poses:
//   position pass  a contact whose points are closer than a skin (d = (p_b − p_a)·n + skin
//                  > 0) is resolved by a positional impulse Δλ·n, Δλ = d / (w_a + w_b) with the
//                  generalised inverse masses (α = 0: a hard contact); static friction undoes
//                  the tangential slip of the substep while it is below μs·λn. A contact
//                  pushes at most what its points closed in by during the substep plus
//                  kMaxDepenetrationSpeed·h: an overlap a fast impact left behind is undone
//                  over several substeps, not in one push that the velocity update would turn
//                  into an explosion (a body squeezed between two others would otherwise gain
//                  energy from every Gauss–Seidel sweep);
//   velocity pass  at the contacts resolved in the position pass: the normal velocity is set
//                  to −e times the one before the substep at the contact of each pair that
//                  closed in fastest, to 0 at the others (and everywhere below 2|g|h, so that
//                  resting bodies do not jitter), then dynamic friction applies a tangential
//                  impulse of at most μd·λn/h (the Coulomb bound: the normal force is λn/h²), or
//                  what stops the sliding at the contact.
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

  explicit RigidContactSolver(const Scene& scene);

  /// Starts a substep: the contacts' normal velocities before it (for restitution).
  void begin(const std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts);
  /// The position pass of one substep of length h (after begin()).
  void projectPositions(std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                        double h);
  /// The velocity pass (friction, restitution) of the contacts the position pass resolved.
  void solveVelocities(std::vector<RigidBody>& bodies, const std::vector<RigidContact>& contacts,
                       double h) const;
  /// One contact's velocity pass: normal velocity to max(bounce, 0), then dynamic friction.
  void solveContactVelocity(std::vector<RigidBody>& bodies, const RigidContact& c, double bounce,
                            double lambda_n, double h) const;
  /// Contacts resolved in the last position pass.
  int activeCount() const { return int(active_.size()); }

 private:
  double mu_static_ = 0, mu_dynamic_ = 0;
  bool friction_ = false;
  double restitution_ = 0;
  double gravity_ = 0;  ///< |g|
  static constexpr double kSkinPerTolerance = 0.01;
  double skin_ = 0;                ///< m
  std::vector<double> vn_before_;  ///< per contact
  std::vector<int> active_;        ///< contacts resolved in the position pass
  std::vector<double> lambda_n_;   ///< per contact: its normal impulse this substep (N·s²)
  static constexpr double kMaxDepenetrationSpeed = 1.0;  ///< m/s
  std::vector<double> budget_, pushed_;  ///< per contact: how far it may push, and has (m)
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_RIGID_CONTACT_SOLVER_H
