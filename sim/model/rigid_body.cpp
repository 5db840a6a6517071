#include "model/rigid_body.h"

#include <algorithm>

#include "model/shapes.h"

namespace fse_sim {

fcl::Transform3d RigidBody::transform() const {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = x;
  return X;
}

Eigen::Matrix3d RigidBody::worldInverseInertia() const {
  const Eigen::Matrix3d R = q.toRotationMatrix();
  return R * inverse_inertia.asDiagonal() * R.transpose();
}

double RigidBody::inverseMassAt(const Eigen::Vector3d& r, const Eigen::Vector3d& n) const {
  if (fixed()) return 0;
  const Eigen::Vector3d rn = q.inverse() * r.cross(n);  // body frame
  return inverse_mass + rn.dot(inverse_inertia.cwiseProduct(rn));
}

void RigidBody::applyPositionImpulse(const Eigen::Vector3d& p, const Eigen::Vector3d& r) {
  if (fixed()) return;
  x += inverse_mass * p;
  const Eigen::Vector3d turn = worldInverseInertia() * r.cross(p);
  const Eigen::Quaterniond dq(0, turn[0], turn[1], turn[2]);
  q.coeffs() += 0.5 * (dq * q).coeffs();
  q.normalize();
}

void RigidBody::applyVelocityImpulse(const Eigen::Vector3d& p, const Eigen::Vector3d& r) {
  if (fixed()) return;
  v += inverse_mass * p;
  omega += worldInverseInertia() * r.cross(p);
}

double RigidBody::kineticEnergy() const {
  if (fixed()) return 0;
  const Eigen::Vector3d w_body = q.inverse() * omega;
  return 0.5 * mass * v.squaredNorm() + 0.5 * w_body.dot(inertia.cwiseProduct(w_body));
}

Eigen::Vector3d RigidBody::angularMomentum() const {
  const Eigen::Vector3d w_body = q.inverse() * omega;
  return q * inertia.cwiseProduct(w_body).eval();
}

RigidBody makeBody(const BodySpec& spec, double density) {
  RigidBody body;
  body.shape = std::make_shared<fcl_superellipsoid::Superellipsoidd>(makeShape(spec.shape));
  // The corner of the bounding box: a box-like shape (small ε) reaches nearly that far.
  body.bounding_radius = body.shape->radii().norm();
  body.mass = density * body.shape->computeVolume();
  body.inertia = density * body.shape->computeMomentofInertia().diagonal();
  if (!spec.fixed) {
    body.inverse_mass = 1 / body.mass;
    body.inverse_inertia = body.inertia.cwiseInverse();
    body.v = spec.velocity;
    body.omega = spec.angular_velocity;
  }
  const Eigen::Isometry3d pose = shapePose(spec.shape);
  body.x = pose.translation();
  body.q = Eigen::Quaterniond(pose.linear());
  body.x_prev = body.x;
  body.q_prev = body.q;
  return body;
}

double movingEnergy(const std::vector<RigidBody>& bodies, const Eigen::Vector3d& g) {
  double e = 0;
  for (const RigidBody& b : bodies) {
    if (b.fixed()) continue;
    e += b.kineticEnergy() - b.mass * g.dot(b.x);
  }
  return e;
}

double maxPointSpeed(const std::vector<RigidBody>& bodies) {
  double speed = 0;
  for (const RigidBody& b : bodies) {
    if (!b.fixed()) speed = std::max(speed, b.pointSpeedBound());
  }
  return speed;
}

}  // namespace fse_sim
