#ifndef FSE_SIM_PHYSICS_CLOTH_CONTACT_SOLVER_H
#define FSE_SIM_PHYSICS_CLOTH_CONTACT_SOLVER_H

// The `collision` effect (and `friction`, which acts at its contacts): positional contacts as
// in Müller et al. 2020 ("Detailed rigid body simulation with extended position based
// dynamics"), for cloth vertices against fixed rigid superellipsoids.
//
// Once per step, collision detection gathers the candidates: the vertices whose signed
// distance is at most tolerance + the distance a vertex can travel in the step; each brings
// the supporting plane at its nearest surface point (point p, outward normal n). In every
// substep a candidate below its plane (C = n·(x − p) < 0) is moved onto it. The superellipsoid
// is convex, so the half-space above a supporting plane lies outside the shape: a vertex held
// on its plane (in fact a skin of 1e-7 × tolerance above it, so that a resting vertex is
// outside beyond rounding and its next query takes the solver's cheaper outside path) is
// never inside; what is left inside after a step is the contact model's own
// error (a plane from an inexact nearest point, or a facet). Friction acts on the vertices
// pushed in the substep: static as a positional correction (the slip is undone while it is
// below μs times the push), dynamic in the velocity pass (the tangential velocity loses up to
// μd · push / h).

#include <memory>
#include <vector>

#include "contact/cloth_contact.h"
#include "model/scene.h"

namespace fse_sim {

class Contacts {
 public:
  Contacts(const Scene& scene, const SimulationOptions& options);

  /// Collision detection for the step to come: candidates for vertices that may reach the
  /// surface, given the largest vertex speed and the step.
  void detect(const Eigen::Matrix3Xd& x, double max_speed, double max_acceleration, double step);

  /// One substep's projection onto the planes (and static friction against x_start, the
  /// positions at the start of the substep).
  void project(Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& x_start,
               const Eigen::VectorXd& inverse_mass);

  /// Dynamic friction on the vertices pushed in the last projection (no-op without friction).
  void applyFriction(Eigen::Matrix3Xd& v, double h) const;

  const std::vector<ContactCandidate>& candidates() const { return candidates_; }
  /// Vertices pushed in the last projection (indices into candidates()).
  const std::vector<int>& active() const { return active_; }

 private:
  std::vector<std::unique_ptr<ContactDetector>> detectors_;
  std::vector<ContactCandidate> candidates_;
  std::vector<int> active_;
  std::vector<double> push_;  ///< per active contact: how far it was pushed (m)
  /// How far above its plane a contact holds a vertex, per unit of tolerance.
  static constexpr double kSkinPerTolerance = 1e-7;
  double tolerance_;
  double skin_;
  bool friction_;
  double mu_static_ = 0, mu_dynamic_ = 0;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_CLOTH_CONTACT_SOLVER_H
