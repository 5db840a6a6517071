#ifndef FSE_SIM_MODEL_RIGID_BODY_H
#define FSE_SIM_MODEL_RIGID_BODY_H

// A rigid superellipsoid body of a `rigid_bodies` scene: its shape, mass properties and state,
// and the two ways XPBD changes it (Müller et al. 2020, "Detailed rigid body simulation with
// extended position based dynamics"): a positional impulse (moves and turns the body) and a
// velocity impulse. The body frame is the shape's frame: its principal axes are the shape's
// axes, so the inertia tensor is diagonal there.

#include <fcl_superellipsoid/fcl_integration.h>
#include <fcl_superellipsoid/superellipsoid.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "model/scene.h"
#include "model/scene_bodies.h"

namespace fse_sim {

struct RigidBody {
  std::shared_ptr<fcl_superellipsoid::Superellipsoidd> shape;
  double mass = 0;
  double inverse_mass = 0;                   ///< 0: fixed
  Eigen::Vector3d inertia{0, 0, 0};          ///< principal moments, body frame, kg·m²
  Eigen::Vector3d inverse_inertia{0, 0, 0};  ///< 0: fixed
  Eigen::Vector3d x{0, 0, 0}, v{0, 0, 0};    ///< centre and its velocity, world
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  ///< body → world
  Eigen::Vector3d omega{0, 0, 0};                         ///< angular velocity, world
  Eigen::Vector3d x_prev{0, 0, 0};                        ///< at the start of the substep
  Eigen::Quaterniond q_prev = Eigen::Quaterniond::Identity();

  double bounding_radius = 0;  ///< m: no point of the body is farther

  bool fixed() const { return inverse_mass == 0; }
  /// A point given in the body frame, in the world at the current pose.
  Eigen::Vector3d toWorld(const Eigen::Vector3d& r_body) const { return x + q * r_body; }
  /// The same at the pose of the substep's start.
  Eigen::Vector3d toWorldPrevious(const Eigen::Vector3d& r_body) const {
    return x_prev + q_prev * r_body;
  }
  fcl::Transform3d transform() const;
  /// I⁻¹ in the world frame.
  Eigen::Matrix3d worldInverseInertia() const;
  /// The generalised inverse mass w = 1/m + (r × n)ᵀ I⁻¹ (r × n) of a correction along unit n
  /// at world offset r from the centre (0 for a fixed body).
  double inverseMassAt(const Eigen::Vector3d& r, const Eigen::Vector3d& n) const;
  /// A positional impulse p at world offset r: x += p/m, q += ½·[I⁻¹(r × p), 0]·q.
  void applyPositionImpulse(const Eigen::Vector3d& p, const Eigen::Vector3d& r);
  /// A velocity impulse p at world offset r: v += p/m, ω += I⁻¹(r × p).
  void applyVelocityImpulse(const Eigen::Vector3d& p, const Eigen::Vector3d& r);
  /// A bound on the speed of any point of the body: |v| + |ω|·bounding_radius.
  double pointSpeedBound() const { return v.norm() + omega.norm() * bounding_radius; }
  /// The velocity of the material point at world offset r.
  Eigen::Vector3d velocityAt(const Eigen::Vector3d& r) const { return v + omega.cross(r); }
  /// ½mv² + ½ωᵀIω.
  double kineticEnergy() const;
  /// I·ω in the world frame.
  Eigen::Vector3d angularMomentum() const;
};

/// A body from its spec and the scene's density.
RigidBody makeBody(const BodySpec& spec, double density);

/// Kinetic + gravitational potential energy of the moving bodies under gravity g, J.
double movingEnergy(const std::vector<RigidBody>& bodies, const Eigen::Vector3d& g);
/// A bound on the speed of any point of a moving body (RigidBody::pointSpeedBound), m/s.
double maxPointSpeed(const std::vector<RigidBody>& bodies);

}  // namespace fse_sim

#endif  // FSE_SIM_MODEL_RIGID_BODY_H
