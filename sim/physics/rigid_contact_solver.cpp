#include "physics/rigid_contact_solver.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fse_sim {
namespace {

/// The other side of a contact: a body, or the fixed bowl (nullptr).
RigidBody* otherBody(std::vector<RigidBody>& bodies, const RigidContact& c) {
  return c.b >= 0 ? &bodies[std::size_t(c.b)] : nullptr;
}

Eigen::Vector3d pointOnB(const std::vector<RigidBody>& bodies, const RigidContact& c) {
  return c.b >= 0 ? bodies[std::size_t(c.b)].toWorld(c.r_b) : c.r_b;
}

Eigen::Vector3d relativeVelocity(const std::vector<RigidBody>& bodies, const RigidContact& c) {
  const RigidBody& a = bodies[std::size_t(c.a)];
  Eigen::Vector3d v = a.velocityAt(a.q * c.r_a);
  if (c.b >= 0) {
    const RigidBody& b = bodies[std::size_t(c.b)];
    v -= b.velocityAt(b.q * c.r_b);
  }
  return v;
}

/// Applies impulse p to a at world point p_a and −p to b (if a body) at p_b, as positional
/// (positions = true) or velocity impulses.
void applyPair(RigidBody& a, RigidBody* b, const Eigen::Vector3d& p, const Eigen::Vector3d& p_a,
               const Eigen::Vector3d& p_b, bool positions) {
  if (positions) {
    a.applyPositionImpulse(p, p_a - a.x);
    if (b != nullptr) b->applyPositionImpulse(-p, p_b - b->x);
  } else {
    a.applyVelocityImpulse(p, p_a - a.x);
    if (b != nullptr) b->applyVelocityImpulse(-p, p_b - b->x);
  }
}

/// The unordered pair of a contact's two sides (−1: the bowl).
long pairKey(const RigidContact& c) {
  const long lo = std::min(c.a, c.b), hi = std::max(c.a, c.b);
  return (lo + 1) * 1000003L + (hi + 1);
}

double pairInverseMass(const RigidBody& a, const RigidBody* b, const Eigen::Vector3d& p_a,
                       const Eigen::Vector3d& p_b, const Eigen::Vector3d& direction) {
  double w = a.inverseMassAt(p_a - a.x, direction);
  if (b != nullptr) w += b->inverseMassAt(p_b - b->x, direction);
  return w;
}

}  // namespace

RigidContactSolver::RigidContactSolver(const Scene& scene) {
  if (scene.friction) {
    friction_ = true;
    mu_static_ = scene.friction->static_;
    mu_dynamic_ = scene.friction->dynamic;
  }
  if (scene.restitution) restitution_ = scene.restitution->coefficient;
  if (scene.gravity) gravity_ = scene.gravity->acceleration.norm();
  skin_ = kSkinPerTolerance * scene.rigid_contact->tolerance;
}

void RigidContactSolver::begin(const std::vector<RigidBody>& bodies,
                               const std::vector<RigidContact>& contacts) {
  vn_before_.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    vn_before_[k] = contacts[k].n.dot(relativeVelocity(bodies, contacts[k]));
  }
}

void RigidContactSolver::projectPositions(std::vector<RigidBody>& bodies,
                                          const std::vector<RigidContact>& contacts, double h) {
  lambda_n_.assign(contacts.size(), 0.0);
  // How far each contact may push in this substep: what its points closed in by (their normal
  // velocity before it), plus an overlap the substep started with at no more than
  // kMaxDepenetrationSpeed.
  pushed_.assign(contacts.size(), 0.0);
  budget_.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    budget_[k] = (std::max(0.0, -vn_before_[k]) + kMaxDepenetrationSpeed) * h;
  }
  for (int iteration = 0; iteration < kPositionIterations; ++iteration) {
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const RigidContact& c = contacts[k];
      RigidBody& a = bodies[std::size_t(c.a)];
      RigidBody* b = otherBody(bodies, c);
      Eigen::Vector3d p_a = a.toWorld(c.r_a), p_b = pointOnB(bodies, c);
      const double d = std::min((p_b - p_a).dot(c.n) + skin_, budget_[k] - pushed_[k]);
      if (d <= 0) continue;
      const double w = pairInverseMass(a, b, p_a, p_b, c.n);
      if (w <= 0) continue;
      applyPair(a, b, (d / w) * c.n, p_a, p_b, true);
      pushed_[k] += d;
      lambda_n_[k] += d / w;
      if (!friction_) continue;
      // Static friction: the tangential slip of the contact points over the substep.
      p_a = a.toWorld(c.r_a);
      p_b = pointOnB(bodies, c);
      const Eigen::Vector3d prev_b = b != nullptr ? b->toWorldPrevious(c.r_b) : c.r_b;
      Eigen::Vector3d slip = (p_a - a.toWorldPrevious(c.r_a)) - (p_b - prev_b);
      slip -= slip.dot(c.n) * c.n;
      const double length = slip.norm();
      if (length <= 0) continue;
      const Eigen::Vector3d t = slip / length;
      const double w_t = pairInverseMass(a, b, p_a, p_b, t);
      if (w_t <= 0) continue;
      const double lambda_t = length / w_t;
      if (lambda_t < mu_static_ * lambda_n_[k]) applyPair(a, b, -lambda_t * t, p_a, p_b, true);
    }
  }
  active_.clear();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (lambda_n_[k] > 0) active_.push_back(int(k));
  }
}

void RigidContactSolver::solveVelocities(std::vector<RigidBody>& bodies,
                                         const std::vector<RigidContact>& contacts,
                                         double h) const {
  // Restitution once per pair of bodies (or body and bowl): at its active contact that closed
  // in fastest, and after the pair's other contacts have had their normal velocity set to 0
  // (otherwise they would cancel the bounce). Each contact of a face setting its own bounce
  // would spin the bodies up, one lever arm after another, past the energy they met with.
  std::unordered_map<long, std::size_t> fastest;  // pair → its fastest-closing active contact
  for (std::size_t i = 0; i < active_.size(); ++i) {
    const auto k = std::size_t(active_[i]);
    const auto [it, added] = fastest.emplace(pairKey(contacts[k]), k);
    if (!added && vn_before_[k] < vn_before_[it->second]) it->second = k;
  }
  for (const bool bouncing : {false, true}) {
    for (const int index : active_) {
      const auto k = std::size_t(index);
      const bool primary = fastest.at(pairKey(contacts[k])) == k;
      if (primary != bouncing) continue;
      const double e = primary && std::abs(vn_before_[k]) > 2 * gravity_ * h ? restitution_ : 0.0;
      solveContactVelocity(bodies, contacts[k], -e * vn_before_[k], lambda_n_[k], h);
    }
  }
}

void RigidContactSolver::solveContactVelocity(std::vector<RigidBody>& bodies, const RigidContact& c,
                                              double bounce, double lambda_n, double h) const {
  RigidBody& a = bodies[std::size_t(c.a)];
  RigidBody* b = otherBody(bodies, c);
  const Eigen::Vector3d p_a = a.toWorld(c.r_a), p_b = pointOnB(bodies, c);
  // The normal velocity first, then friction on the tangential velocity that is left, each as
  // its own impulse (an impulse along a mix of the two would not change the relative velocity
  // along itself: the generalised inverse mass differs by direction).
  const double dvn = -c.n.dot(relativeVelocity(bodies, c)) + std::max(bounce, 0.0);
  const double w_n = pairInverseMass(a, b, p_a, p_b, c.n);
  if (dvn != 0 && w_n > 0) applyPair(a, b, (dvn / w_n) * c.n, p_a, p_b, false);
  if (!friction_) return;
  const Eigen::Vector3d v = relativeVelocity(bodies, c);
  const Eigen::Vector3d vt = v - c.n.dot(v) * c.n;
  const double speed_t = vt.norm();
  if (!(speed_t > 0)) return;
  // Dynamic friction: the normal force is λn/h², so the friction impulse is at most
  // μd·|fn|·h = μd·λn/h, or what stops the tangential motion at the contact.
  const Eigen::Vector3d t = vt / speed_t;
  const double w_t = pairInverseMass(a, b, p_a, p_b, t);
  if (!(w_t > 0)) return;
  applyPair(a, b, -std::min(mu_dynamic_ * lambda_n / h, speed_t / w_t) * t, p_a, p_b, false);
}

}  // namespace fse_sim
